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
//! The other modules are the rest of the pipeline the `cullproof` command runs, one
//! folder per layer in the order data flows (`io`, `model`, `bounds`, `external`,
//! `cases`, `judge`, `gate`, `search`, `tools`, `cli`; `docs/layout.md`); they are public
//! for the command and the tests, and not part of the library's stable surface.

// The layers, each a folder, in the order data flows through them: a layer imports
// only the layers before it (`tests/layers.rs` checks it; `docs/layout.md` says what each
// holds).
// 0: reading and writing.
#[doc(hidden)]
pub mod io;
// 1: the model.
pub mod model;
// 2: the contract and the published methods.
pub mod bounds;
// 3: bounds from outside the crate (C plugins, other processes).
#[doc(hidden)]
pub mod external;
// 4: where a case is made.
#[doc(hidden)]
pub mod cases;
// 5: certified verdicts on one answer for one tile.
#[doc(hidden)]
pub mod judge;
// 6: cases x methods, expectations, baseline, reports.
pub mod gate;
// 7: search, shrink, replay, explain.
#[doc(hidden)]
pub mod search;
// 8: tightness, stability, symbolic search, proofs.
#[doc(hidden)]
pub mod tools;
// 9: the command line.
#[doc(hidden)]
pub mod cli;

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
