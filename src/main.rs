//! The `cullproof` command line (thin: the commands live in the library's `cli` layer).

/// `corpus/expectations.json` and `corpus/baseline.json` as this binary was built with
/// them: what `check`, `merge`, `power` and `search` use outside the checkout (see
/// `cullproof::gate::locate`). Included here, in the binary, so that editing them
/// rebuilds only the command, not the library and every test.
const BUILT_IN: cullproof::gate::locate::BuiltIn = cullproof::gate::locate::BuiltIn {
    expectations: include_str!("../corpus/expectations.json"),
    baseline: include_str!("../corpus/baseline.json"),
};

fn main() {
    cullproof::cli::main(BUILT_IN)
}
