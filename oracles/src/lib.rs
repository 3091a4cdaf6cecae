//! Ground-truth oracles for cullproof.
//!
//! This crate takes plain numbers (`f64`, which every `f32` converts to exactly) and
//! never imports the code under test, so one mistake cannot sit on both sides.
//! See the repository's `docs/model.md` for the model that every function here follows.

pub mod batch;
pub mod coverage;
pub mod dyadic;
pub mod embree;
pub mod extents;
pub mod filter;
pub mod interval;
pub mod poly;
pub mod ring;
pub mod timeline;
pub mod tri;

pub use coverage::{classify, classify_depth, Coverage, CoverageStats, DepthCheck};
pub use tri::Tri;
