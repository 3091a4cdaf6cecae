//! cullproof: proves or breaks the conservativeness of culling bounds for stochastic
//! rasterization (simultaneous motion blur and depth of field: every sample has five
//! coordinates x, y, u, v, t).
//!
//! # Gate your own bound
//! Implement [`Method`] (the per-triangle setup) and [`Prepared`] (the tile test: a
//! [`TileResult`] of intervals u^, v^, t^, an optional depth interval and optional
//! per-sample constraints), then run the [`Gate`] on it, for instance in your own
//! `cargo test`:
//!
//! ```
//! use cullproof::{Gate, MethodVerdict};
//! # let my_bound = cullproof::bounds::by_id("bbox-safe").unwrap();
//! let report = Gate::new().method(my_bound).cases(160).seed(1).run();
//! let mine = &report.methods[0];
//! assert_eq!(mine.verdict, MethodVerdict::Proven, "{}", report.render());
//! assert!(report.passed());
//! ```
//!
//! A violation comes back as a [`Counterexample`]: the case, the tile and a covered
//! sample confirmed in exact arithmetic, with the [`Bound`] it breaks. The example
//! `examples/own_bound.rs` is a whole bound gated end to end; `include/cullproof.h`
//! and `--plugin` take a bound written in C, `--exec` (docs/protocol.md) one in any
//! language.
//!
//! # The contract
//! A test may cull a sample only if the triangle cannot cover it; `docs/model.md` gives
//! the camera, the clip space, the coverage rule and the contract, and [`bounds`] its
//! Rust form. Bounds compute in f32 as hardware would; the judge is exact (outward
//! rounded intervals, then exact dyadic arithmetic) and lives in the separate `oracles`
//! crate, which never imports this one.
//!
//! # Modules
//! - [`bounds`]: the contract and the published methods (one file each), with their
//!   conservative `-safe` variants.
//! - [`model`]: triangle, camera, tile, sample, case.
//! - [`gate`]: the builder above and its typed report.
//! - [`counterexamples`]: find, shrink and write counterexamples of your bound
//!   ([`counterexamples::Search`]), re-judge a case file after a fix
//!   ([`counterexamples::replay`]) and explain one ([`counterexamples::explain`]).
//!
//! The other modules serve the `cullproof` command line (the gate's judge, search,
//! corpus, tightness, stability, plugins and the process protocol); they are public for
//! the command and the tests, and not part of the library's stable surface.

// The layers, each a folder, in the order data flows through them: a layer imports
// only the layers above it in this list (`tests/layers.rs` checks it).
pub mod bounds;
#[doc(hidden)]
pub mod cases;
#[doc(hidden)]
pub mod cli;
#[doc(hidden)]
pub mod external;
pub mod gate;
#[doc(hidden)]
pub mod io;
#[doc(hidden)]
pub mod judge;
pub mod model;
#[doc(hidden)]
pub mod search;
#[doc(hidden)]
pub mod tools;

pub use search::counterexamples;

pub use bounds::{
    Grid, Method, MethodInfo, MethodRef, Outputs, PerTile, Prepared, SampleBox, SampleConstraint, TileBounds, TileGrid,
    TileResult,
};
pub use cases::generate::Regime;
pub use gate::Expectations;
pub use gate::{Bound, Counterexample, Gate, GateReport, MethodReport, MethodVerdict, Unproven};
pub use model::{Case, Dims, Sample, SampleSet, Snap, Tile, Triangle, Viewport};

/// Outward-rounded interval arithmetic (the same small type the oracles use: it is
/// plain arithmetic, not a coverage decision, so sharing it puts no verdict on both
/// sides). Per-sample constraints of the bounds use it for their box evaluation.
pub use oracles::interval::Interval;
