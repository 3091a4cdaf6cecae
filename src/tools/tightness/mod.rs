//! `tightness`: how many samples each culling method lets through, against how many the
//! triangle really covers — the **sample test efficiency** (STE, Fatahalian et al.
//! 2009; Munkberg & Akenine-Möller 2012 Table 1, Wu 2013 Table 4.1) per method, tile
//! size and blur setting of a scene.
//!
//! # The measurement ([`measure`])
//! For every triangle of a scene (see [`scene`]) and every method:
//! 1. **Setup** once per triangle ([`Method::setup`]).
//! 2. **Traversal**: the tiles of the tile grid (size S px, aligned to multiples of S)
//!    that overlap the triangle's screen footprint — the screen AABB of its vertices over
//!    the four lens corners and both shutter ends, computed in f64 from the f32 vertices
//!    with a relative margin of 1e-9, clipped to the screen ([`footprint`]). Every
//!    interior-covered sample lies strictly inside that box (a covered pixel is a strict
//!    convex combination of the projected sheared vertices when every w > 0; the box
//!    extremes sit at lens corners and shutter ends: `bounds/bbox.rs` derives both), so
//!    the traversal itself culls no covered sample. A triangle with a vertex at w <= 0 at
//!    either shutter end has an unbounded projection: **it falls back to the whole
//!    screen** (every tile is traversed and tested), and is counted (`whole_screen`). A
//!    footprint entirely off the screen is skipped and counted (`off_screen`).
//! 3. **Tile test** per tile, then for each sample of the pattern (see [`pattern`]) in
//!    the tile: *tested* if the tile was not culled and
//!    [`TileBounds::admits`](crate::bounds::TileBounds::admits) (intervals
//!    u^, v^, t^ and every per-sample constraint; a depth interval z^ is an occlusion
//!    test, not a coverage test, and is not applied).
//! 4. **Coverage** of each (triangle, sample) by the exact oracle
//!    (`oracles::classify == Interior`; boundary samples count as not covered), computed
//!    once and reused for every method and tile size (it does not depend on either). The
//!    samples go through the batched oracle (`oracles::batch`: lanes with certified
//!    signs, every uncertain sample sent to the scalar oracle), which gives every sample
//!    the scalar oracle's class.
//!
//! Per (method, tile size, setting): `tested` = samples let through, `hits` = tested and
//! covered, `missed` = covered but culled (by the tile test or a per-sample test; a
//! conservative method has 0; some published methods do not, and the count is always
//! shown), `STE = hits / tested`. `hits + missed` = the covered samples of the setting,
//! the same for every method and tile size.
//!
//! # The ceiling
//! The tightest interval-only tile test lets through, per tile, the samples inside the
//! box of the exact (u, v, t) extents of the covered set over the tile. Certified
//! extents of every tile take minutes on a real scene (`--certified all`), so by default
//! two figures are reported:
//! - the **sample ceiling**: per tile, the box of the (u, v, t) of the covered *pattern
//!   samples* themselves (the whole range in a coordinate the triangle's coverage does
//!   not depend on: u, v without defocus, t without motion), and the pattern samples
//!   inside it. That box lies inside the exact one, so it lets through no more samples:
//!   its STE is an **upper bound** on the true ceiling (for the same pattern). A method
//!   with per-sample constraints can beat it (those are not interval tests); an
//!   interval-only method that misses nothing cannot.
//! - optionally, a **certified ceiling** on a seeded random subset of the traversed
//!   tiles, or on every one of them (the exact ceiling of the scene): certified
//!   enclosures of the six extents (`oracles::extents::TileSolver`, resolution and box
//!   budget of [`Config::certified`]), each side taken at its outer
//!   end, so the box contains the exact one and its STE is a **lower bound** on the true
//!   ceiling over those tiles; the sample ceiling of the same tiles is shown beside it.
//!   A tile where the solver left boxes open (over budget) is counted `undecided`; its
//!   outer enclosure still holds (an unknown side is the whole range).
//!
//! # How it runs
//! The whole screen's sample pattern is built once ([`SampleTable`]) and shared by every
//! triangle, setting and method; each triangle is set up once per method and the setup
//! serves every tile size; the samples of a tile are counted row by row: the intervals
//! tested with u, v, t side by side, then each per-sample constraint evaluated once per
//! row on the samples inside them, in columns
//! ([`SampleConstraint::eval_row`](crate::bounds::SampleConstraint::eval_row): the
//! values of `eval`, bit for bit, computed side by side by the constraints the methods
//! use). Nothing per sample is stored but the triangle's coverage (and the verdicts of a
//! tile-independent answer's constraints, below), in buffers reused by each worker.
//!
//! No tile test is repeated and nothing that does not depend on the tile is recomputed
//! per tile (`Plan`): each distinct method is set up and asked once per tile (a
//! **slot**); a method that is by definition a conjunction of other registered methods
//! ([`Method::conjunction`]: lc, mam2012-new and their -safe variants) is met from its
//! parts' answers ([`Conjunction::meet`], the intervals of its own answer bit for bit,
//! its constraints those of the parts); an answer that does not read the tile
//! ([`Prepared::tile_independent`]: gdam2010 and gdam2010-safe) is asked once per
//! triangle, and its constraints are evaluated once per sample of the triangle's region
//! for every tile size (`region_pass`). Every other slot answers all the tiles of one
//! size over the triangle at once ([`Prepared::grid`]: the same answers as
//! [`Prepared::tile`], with each column's and each row's share computed once). The work
//! counted ([`Work`]) is still each method's own: a conjunction's tile test counts once
//! for it, whatever was shared. Exact coverage goes through one function
//! ([`exact_coverage`]). Each count also feeds the cost model ([`Work`],
//! [`cost`]).
//!
//! Results are integer counts, summed per worker and then across workers: the same in
//! any order, so identical at any thread count.
//!
//! [`Method::setup`]: crate::bounds::Method::setup
//! [`Method::conjunction`]: crate::bounds::Method::conjunction
//! [`Conjunction::meet`]: crate::bounds::Conjunction::meet
//! [`Prepared::tile_independent`]: crate::bounds::Prepared::tile_independent
//! [`Prepared::grid`]: crate::bounds::Prepared::grid
//! [`Prepared::tile`]: crate::bounds::Prepared::tile

mod ceiling;
pub mod chart;
pub mod cost;
mod count;
mod coverage;
mod geometry;
mod measurement;
pub mod mesh;
pub mod obj;
pub mod pattern;
pub mod raster;
pub mod scene;
mod sums;
mod table;
mod types;

pub use coverage::{exact_coverage, CoverageScratch};
pub use geometry::{footprint, tile_of, tile_pixels, tile_range, Footprint, PixelRect};
pub use measurement::{measure, measure_with};
pub use table::SampleTable;
pub use types::{CeilingRow, CertifiedRow, Config, Counts, Measurement, MethodRow, SettingSummary, Work};

#[cfg(test)]
mod tests;
