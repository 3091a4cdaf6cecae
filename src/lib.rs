//! cullproof: proves or breaks the conservativeness of culling bounds for stochastic
//! rasterization (simultaneous motion blur and depth of field).
//!
//! - [`model`]: the one model of `docs/model.md` (triangle, camera, tile, sample).
//! - [`bounds`]: the culling tests under test, one file per published method.
//! - [`agree`]: the agreement run of the exact oracle against Embree.
//! - [`tightness`]: sample test efficiency (STE) per method, tile size and scene.
//! - [`stability`]: one parameter swept towards a method's singularity (violations, NaN/inf, STE).
//!
//! The ground truth lives in the separate `oracles` crate, which never imports this one.

pub mod agree;
pub mod args;
pub mod bounds;
pub mod check;
pub mod corpus;
pub mod csearch;
pub mod exec;
pub mod explain;
pub mod gen;
pub mod model;
pub mod plugin;
pub mod stability;
pub mod tightness;

/// Outward-rounded interval arithmetic (the same small type the oracles use: it is
/// plain arithmetic, not a coverage decision, so sharing it puts no verdict on both
/// sides). Per-sample constraints of the bounds use it for their box evaluation.
pub use oracles::interval::Interval;
