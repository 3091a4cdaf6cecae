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

pub mod chart;
mod cli;
pub mod cost;
mod count;
pub mod mesh;
pub mod obj;
pub mod pattern;
pub mod raster;
pub mod scene;

pub use cli::{run_cli, TightnessArgs};

use crate::bounds::{Conjunction, Grid, Method, Prepared, SampleCols, SampleConstraint, TileGrid, TileResult};
use crate::model::{Dims, Sample, Tile, Triangle};
use count::{count_admitted, count_passing, region_pass, AdmitScratch, Here};
use indicatif::ProgressBar;
use oracles::batch::Batch;
use oracles::extents::{Extent, ExtentsConfig, Occupancy, TileSolver};
use oracles::Coverage;
use pattern::Pattern;
use rand::SeedableRng;
use rayon::prelude::*;
use scene::{Scene, Setting};
use serde::Serialize;

/// An inclusive rectangle of pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelRect {
    pub fn pixels(&self) -> u64 {
        (self.x1 - self.x0 + 1) as u64 * (self.y1 - self.y0 + 1) as u64
    }
}

/// Where a triangle's samples can be covered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Footprint {
    /// Every covered sample lies in these pixels.
    Region(PixelRect),
    /// A vertex at w <= 0 (or a non-finite projection): the whole screen is traversed.
    WholeScreen,
    /// The footprint misses the screen: nothing to do.
    OffScreen,
}

/// The pixels holding every interior-covered sample of the triangle: its screen AABB
/// over the lens corners (u, v = ±1) and shutter ends (t = 0, 1), in f64 with a margin
/// of 1e-9 relative, clipped to the `width x height` screen (pixel p holds x in [p, p+1)).
pub fn footprint(tri: &Triangle, width: u32, height: u32) -> Footprint {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (p, c) in [(&tri.q, &tri.c0), (&tri.r, &tri.c1)] {
        for i in 0..3 {
            let w = p[i][3] as f64;
            if w.is_nan() || w <= 0.0 {
                return Footprint::WholeScreen;
            }
            for s in [-1.0, 1.0] {
                let cx = s * c[i] as f64;
                let cy = s * tri.k as f64 * c[i] as f64;
                let (x, y) = ((p[i][0] as f64 + cx) / w, (p[i][1] as f64 + cy) / w);
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if ![x0, x1, y0, y1].iter().all(|v| v.is_finite()) {
        return Footprint::WholeScreen;
    }
    let m = |v: f64| 1e-9 * (v.abs() + 1.0);
    let (x0, x1, y0, y1) = (x0 - m(x0), x1 + m(x1), y0 - m(y0), y1 + m(y1));
    let (w, h) = (width as f64, height as f64);
    if x1 < 0.0 || y1 < 0.0 || x0 >= w || y0 >= h {
        return Footprint::OffScreen;
    }
    let clamp = |v: f64, n: f64| v.floor().clamp(0.0, n - 1.0) as u32;
    Footprint::Region(PixelRect { x0: clamp(x0, w), y0: clamp(y0, h), x1: clamp(x1, w), y1: clamp(y1, h) })
}

/// The tiles of size `s` overlapping `r`: inclusive tile index ranges (tx0, ty0, tx1, ty1).
pub fn tile_range(r: &PixelRect, s: u32) -> (u32, u32, u32, u32) {
    (r.x0 / s, r.y0 / s, r.x1 / s, r.y1 / s)
}

/// The pixels of tile (tx, ty) of size s, clipped to the screen (inclusive).
pub fn tile_pixels(tx: u32, ty: u32, s: u32, width: u32, height: u32) -> PixelRect {
    PixelRect { x0: tx * s, y0: ty * s, x1: ((tx + 1) * s).min(width) - 1, y1: ((ty + 1) * s).min(height) - 1 }
}

/// The tile rectangle a method is asked about (continuous pixel coordinates).
pub fn tile_of(p: &PixelRect) -> Tile {
    Tile { x0: p.x0 as f32, y0: p.y0 as f32, x1: (p.x1 + 1) as f32, y1: (p.y1 + 1) as f32 }
}

/// Settings of a measurement.
#[derive(Clone, Debug)]
pub struct Config {
    /// Tile sizes in pixels.
    pub tiles: Vec<u32>,
    pub pattern: Pattern,
    /// Tiles per (setting, tile size) given a certified ceiling (0: none; at least the
    /// number traversed, e.g. `usize::MAX`: every one).
    pub certified_tiles: usize,
    /// Solver settings of the certified ceiling.
    pub certified: ExtentsConfig,
    /// Seed of the certified subset.
    pub seed: u64,
}

impl Config {
    pub fn new(tiles: Vec<u32>, pattern: Pattern) -> Self {
        Config {
            tiles,
            pattern,
            certified_tiles: 0,
            certified: ExtentsConfig { resolution: 1e-2, max_boxes: 2000, ..ExtentsConfig::default() },
            seed: pattern.seed,
        }
    }
}

/// Samples let through and covered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Samples the method lets through (tile not culled, every per-sample test passed).
    pub tested: u64,
    /// Tested samples that are interior-covered.
    pub hits: u64,
    /// Interior-covered samples the method culls (0 for a conservative method).
    pub missed: u64,
}

impl Counts {
    fn add(&mut self, o: &Counts) {
        self.tested += o.tested;
        self.hits += o.hits;
        self.missed += o.missed;
    }
}

/// The operations a method performed (the work the cost model charges, see [`cost`]):
/// on the triangles where it was enabled, and on those where it disabled itself (its
/// answer then is the whole domain: bbox's work, and charged as bbox's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Work {
    /// Triangles set up.
    pub setups: u64,
    /// Tile tests.
    pub tile_tests: u64,
    /// Samples given the per-sample test (every sample of a tile not culled).
    pub sample_tests: u64,
    pub disabled_setups: u64,
    pub disabled_tile_tests: u64,
    pub disabled_sample_tests: u64,
}

impl Work {
    fn add_setup(&mut self, disabled: bool) {
        *if disabled { &mut self.disabled_setups } else { &mut self.setups } += 1;
    }
    fn add_tile(&mut self, disabled: bool, samples: u64) {
        if disabled {
            self.disabled_tile_tests += 1;
            self.disabled_sample_tests += samples;
        } else {
            self.tile_tests += 1;
            self.sample_tests += samples;
        }
    }
    fn add(&mut self, o: &Work) {
        self.setups += o.setups;
        self.tile_tests += o.tile_tests;
        self.sample_tests += o.sample_tests;
        self.disabled_setups += o.disabled_setups;
        self.disabled_tile_tests += o.disabled_tile_tests;
        self.disabled_sample_tests += o.disabled_sample_tests;
    }
}

/// The whole screen's sample pattern, pixel-major: the `spp` samples of pixel (px, py)
/// start at `(py * width + px) * spp`. Built once per run (every pixel's samples depend
/// only on the pattern, see [`pattern`]) and shared by every triangle, setting and method.
pub struct SampleTable {
    pub width: u32,
    pub height: u32,
    pub spp: usize,
    pub samples: Vec<Sample>,
    /// The samples' x, y, u, v and t side by side (the interval tests and the
    /// per-sample constraints run over these, see [`SampleTable::cols`]).
    pub cols: [Vec<f32>; 5],
}

impl SampleTable {
    /// The pattern over a `width x height` screen (rows built in parallel; the table
    /// does not depend on the thread count).
    pub fn new(pattern: &Pattern, width: u32, height: u32) -> Self {
        let rows: Vec<Vec<Sample>> = (0..height)
            .into_par_iter()
            .map(|py| {
                let mut v = Vec::with_capacity(width as usize * pattern.spp as usize);
                pattern.region(0, py, width - 1, py, &mut v);
                v
            })
            .collect();
        let samples = rows.concat();
        let cols = [
            samples.iter().map(|s| s.x).collect(),
            samples.iter().map(|s| s.y).collect(),
            samples.iter().map(|s| s.u).collect(),
            samples.iter().map(|s| s.v).collect(),
            samples.iter().map(|s| s.t).collect(),
        ];
        SampleTable { width, height, spp: pattern.spp as usize, samples, cols }
    }
    /// The `n` samples from `start` on, side by side.
    pub fn cols(&self, start: usize, n: usize) -> SampleCols<'_> {
        let c = |k: usize| &self.cols[k][start..start + n];
        SampleCols { x: c(0), y: c(1), u: c(2), v: c(3), t: c(4) }
    }
    /// Where pixel (px, py)'s samples start.
    pub fn start(&self, px: u32, py: u32) -> usize {
        (py as usize * self.width as usize + px as usize) * self.spp
    }
}

/// `a / b`, None when b = 0.
fn ratio(a: u64, b: u64) -> Option<f64> {
    (b > 0).then(|| a as f64 / b as f64)
}

/// One method at one tile size and setting.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodRow {
    pub method: String,
    /// Built from a reconstruction (`docs/reconstructions.md`), not from the paper itself.
    pub reconstruction: bool,
    /// The method has per-sample constraints (it is not an interval-only test).
    pub per_sample: bool,
    pub setting: Setting,
    pub tile: u32,
    #[serde(flatten)]
    pub counts: Counts,
    /// hits / tested (None when nothing was tested).
    pub ste: Option<f64>,
    /// Triangles for which the method reported itself disabled (full bounds).
    pub disabled_triangles: u64,
    /// The operations performed.
    pub work: Work,
}

/// The sample ceiling at one tile size and setting (an upper bound on the STE of the
/// tightest interval-only test).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CeilingRow {
    pub setting: Setting,
    pub tile: u32,
    /// Pattern samples inside each tile's box of covered-sample (u, v, t) extents.
    pub tested: u64,
    /// Interior-covered samples (all lie in those boxes).
    pub covered: u64,
    pub ste: Option<f64>,
}

/// The certified ceiling on a random subset of tiles.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CertifiedRow {
    pub setting: Setting,
    pub tile: u32,
    /// (triangle, tile) pairs solved.
    pub tiles: u64,
    /// Of those, tiles where the solver left boxes open (enclosures wider than the
    /// resolution, or occupancy unknown).
    pub undecided_tiles: u64,
    /// Interior-covered pattern samples in those tiles.
    pub covered: u64,
    /// Pattern samples inside the outer certified extents box (contains the exact box).
    pub tested_certified: u64,
    /// Pattern samples inside the covered-sample box (inside the exact box).
    pub tested_sample_box: u64,
    /// covered / tested_certified: a lower bound on the true ceiling over these tiles.
    pub ste_lower: Option<f64>,
    /// covered / tested_sample_box: an upper bound on it.
    pub ste_upper: Option<f64>,
    /// Boxes the solver examined.
    pub boxes: u64,
}

/// What happened to the triangles of one setting.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SettingSummary {
    pub setting: Setting,
    pub triangles: u64,
    /// Triangles with a vertex at w <= 0: traversed over the whole screen.
    pub whole_screen: u64,
    /// Triangles whose footprint misses the screen: skipped.
    pub off_screen: u64,
    /// Samples classified by the exact oracle.
    pub samples_classified: u64,
    /// Interior-covered samples (the numerator of every method's STE when it misses none).
    pub covered: u64,
    /// Samples on an edge (not covered by the interior rule).
    pub boundary: u64,
    /// Samples decided by exact dyadic arithmetic: those whose signs neither the batched
    /// oracle's lanes nor the scalar oracle's floating-point filter could certify.
    pub exact_fallbacks: u64,
}

/// The result of [`measure`].
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Measurement {
    pub settings: Vec<SettingSummary>,
    pub rows: Vec<MethodRow>,
    pub ceiling: Vec<CeilingRow>,
    pub certified: Vec<CertifiedRow>,
}

/// One triangle's contribution.
#[derive(Default)]
struct TriCounts {
    whole_screen: bool,
    off_screen: bool,
    classified: u64,
    covered: u64,
    boundary: u64,
    exact: u64,
    /// [tile index][method index]
    counts: Vec<Vec<Counts>>,
    /// [tile index][method index]
    work: Vec<Vec<Work>>,
    /// [tile index]: (tested, covered)
    ceiling: Vec<(u64, u64)>,
    certified: Vec<CertifiedRow>,
    disabled: Vec<bool>,
}

impl TriCounts {
    /// Zero, for `nt` tile sizes and `nm` methods (the buffers kept from triangle to
    /// triangle).
    fn reset(&mut self, nt: usize, nm: usize) {
        self.whole_screen = false;
        self.off_screen = false;
        (self.classified, self.covered, self.boundary, self.exact) = (0, 0, 0, 0);
        self.counts.resize_with(nt, Vec::new);
        self.counts.iter_mut().for_each(|c| {
            c.clear();
            c.resize(nm, Counts::default());
        });
        self.work.resize_with(nt, Vec::new);
        self.work.iter_mut().for_each(|w| {
            w.clear();
            w.resize(nm, Work::default());
        });
        self.ceiling.clear();
        self.ceiling.resize(nt, (0, 0));
        self.certified.clear();
        self.disabled.clear();
        self.disabled.resize(nm, false);
    }
}

/// The sums over a setting's triangles (integers: the same in any order, so at any
/// thread count).
struct Sums {
    summary: SettingSummary,
    /// [tile index][method index]
    counts: Vec<Vec<Counts>>,
    work: Vec<Vec<Work>>,
    ceiling: Vec<(u64, u64)>,
    disabled: Vec<u64>,
    /// [tile index]
    certified: Vec<CertifiedRow>,
}

impl Sums {
    fn new(setting: Setting, tiles: &[u32], nm: usize) -> Self {
        let nt = tiles.len();
        Sums {
            summary: SettingSummary { setting, ..Default::default() },
            counts: vec![vec![Counts::default(); nm]; nt],
            work: vec![vec![Work::default(); nm]; nt],
            ceiling: vec![(0, 0); nt],
            disabled: vec![0; nm],
            certified: tiles.iter().map(|&s| CertifiedRow { setting, tile: s, ..Default::default() }).collect(),
        }
    }
    /// One triangle's contribution added.
    fn add(&mut self, r: &TriCounts, tiles: &[u32]) {
        let sum = &mut self.summary;
        sum.triangles += 1;
        sum.whole_screen += r.whole_screen as u64;
        sum.off_screen += r.off_screen as u64;
        sum.samples_classified += r.classified;
        sum.covered += r.covered;
        sum.boundary += r.boundary;
        sum.exact_fallbacks += r.exact;
        if r.off_screen {
            return;
        }
        self.add_tables(&r.counts, &r.work, &r.ceiling);
        for (d, &x) in self.disabled.iter_mut().zip(&r.disabled) {
            *d += x as u64;
        }
        for c in &r.certified {
            let ti = tiles.iter().position(|&s| s == c.tile).unwrap();
            self.certified[ti].add(c);
        }
    }
    /// Per tile size and method: counts and work added; per tile size: the ceiling's.
    fn add_tables(&mut self, counts: &[Vec<Counts>], work: &[Vec<Work>], ceiling: &[(u64, u64)]) {
        for ti in 0..self.counts.len() {
            for (acc, x) in self.counts[ti].iter_mut().zip(&counts[ti]) {
                acc.add(x);
            }
            for (acc, x) in self.work[ti].iter_mut().zip(&work[ti]) {
                acc.add(x);
            }
            self.ceiling[ti].0 += ceiling[ti].0;
            self.ceiling[ti].1 += ceiling[ti].1;
        }
    }
    /// Two partial sums added.
    fn merge(mut self, o: Sums) -> Sums {
        let (a, b) = (&mut self.summary, &o.summary);
        a.triangles += b.triangles;
        a.whole_screen += b.whole_screen;
        a.off_screen += b.off_screen;
        a.samples_classified += b.samples_classified;
        a.covered += b.covered;
        a.boundary += b.boundary;
        a.exact_fallbacks += b.exact_fallbacks;
        self.add_tables(&o.counts, &o.work, &o.ceiling);
        for (acc, c) in self.certified.iter_mut().zip(&o.certified) {
            acc.add(c);
        }
        for (d, &x) in self.disabled.iter_mut().zip(&o.disabled) {
            *d += x;
        }
        self
    }
}

impl CertifiedRow {
    /// The counts of `c` added (the STE bounds are computed from the sums at the end).
    fn add(&mut self, c: &CertifiedRow) {
        self.tiles += c.tiles;
        self.undecided_tiles += c.undecided_tiles;
        self.covered += c.covered;
        self.tested_certified += c.tested_certified;
        self.tested_sample_box += c.tested_sample_box;
        self.boxes += c.boxes;
    }
}

/// The coverage of the samples of a region (the union of a triangle's tiles of every
/// size), pixel-major like the [`SampleTable`]; the pixels outside the footprint are
/// not covered.
struct Local {
    rect: PixelRect,
    spp: usize,
    covered: Vec<bool>,
}

impl Local {
    fn start(&self, px: u32, py: u32) -> usize {
        let w = (self.rect.x1 - self.rect.x0 + 1) as usize;
        ((py - self.rect.y0) as usize * w + (px - self.rect.x0) as usize) * self.spp
    }
}

/// The rows of a tile: per pixel row, the start of its samples in the table and in the
/// [`Local`] coverage, and the row's sample count.
fn tile_rows(table: &SampleTable, local: &Local, p: &PixelRect, rows: &mut Vec<(usize, usize, usize)>) {
    rows.clear();
    let n = (p.x1 - p.x0 + 1) as usize * table.spp;
    for py in p.y0..=p.y1 {
        rows.push((table.start(p.x0, py), local.start(p.x0, py), n));
    }
}

fn uvt(s: &Sample) -> [f32; 3] {
    [s.u, s.v, s.t]
}

/// The box of the covered samples' (u, v, t) over the rows of a tile, widened to the
/// whole range in each of u, v (lens) and t (time) that the triangle's coverage does
/// not depend on (there the exact extents are the whole range as soon as one sample is
/// covered); None if no sample is covered.
fn covered_box(
    table: &SampleTable,
    local: &Local,
    rows: &[(usize, usize, usize)],
    dims: Dims,
) -> Option<[[f32; 2]; 3]> {
    let mut b: Option<[[f32; 2]; 3]> = None;
    for &(ts, ls, n) in rows {
        for (s, &cov) in table.samples[ts..ts + n].iter().zip(&local.covered[ls..ls + n]) {
            if cov {
                let c = uvt(s);
                let bb = b.get_or_insert([[c[0], c[0]], [c[1], c[1]], [c[2], c[2]]]);
                for k in 0..3 {
                    bb[k][0] = bb[k][0].min(c[k]);
                    bb[k][1] = bb[k][1].max(c[k]);
                }
            }
        }
    }
    if let Some(bb) = &mut b {
        if !dims.has_lens() {
            bb[0] = [-1.0, 1.0];
            bb[1] = [-1.0, 1.0];
        }
        if !dims.has_time() {
            bb[2] = [0.0, 1.0];
        }
    }
    b
}

/// The samples `start..start + n` of the table inside the (u, v, t) box `b` (the test
/// of [`in_box`], side by side).
fn count_in_box(table: &SampleTable, start: usize, n: usize, b: &[[f32; 2]; 3]) -> u64 {
    let (us, vs, ts) =
        (&table.cols[2][start..start + n], &table.cols[3][start..start + n], &table.cols[4][start..start + n]);
    let mut k = 0u32;
    for i in 0..n {
        k += ((b[0][0] <= us[i])
            & (us[i] <= b[0][1])
            & (b[1][0] <= vs[i])
            & (vs[i] <= b[1][1])
            & (b[2][0] <= ts[i])
            & (ts[i] <= b[2][1])) as u32;
    }
    k as u64
}

fn in_box(b: &[[f32; 2]; 3], s: &Sample) -> bool {
    let c = uvt(s);
    (0..3).all(|k| b[k][0] <= c[k] && c[k] <= b[k][1])
}

/// The certified ceiling of one tile.
#[allow(clippy::too_many_arguments)]
fn certify(
    tri: &oracles::Tri,
    dims: Dims,
    table: &SampleTable,
    local: &Local,
    p: &PixelRect,
    cfg: &ExtentsConfig,
    setting: Setting,
    s: u32,
) -> CertifiedRow {
    let t = tile_of(p);
    let mut rows = Vec::new();
    tile_rows(table, local, p, &mut rows);
    let mut solver = TileSolver::new(
        tri,
        [t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64],
        [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]],
        cfg,
    );
    let covered = rows.iter().map(|&(_, ls, n)| local.covered[ls..ls + n].iter().filter(|&&c| c).count() as u64).sum();
    let mut row = CertifiedRow { setting, tile: s, tiles: 1, covered, ..Default::default() };
    let outer: Option<[[f64; 2]; 3]> = match solver.occupancy() {
        Occupancy::Empty => None,
        occ => {
            let mut undecided = occ == Occupancy::Unknown;
            let full = [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]];
            let mut b = full;
            for ext in &Extent::ALL[..6] {
                let r = solver.objective(*ext);
                undecided |= r.undecided > 0;
                let (k, max) = (ext.sample_coord().expect("u, v or t") - 2, ext.is_max());
                if let Some(e) = r.extreme {
                    b[k][max as usize] = if max { e.hi } else { e.lo };
                }
            }
            row.undecided_tiles = undecided as u64;
            Some(b)
        }
    };
    if outer.is_none() && covered > 0 {
        // Cannot happen (the occupancy search is certified); counted as undecided.
        row.undecided_tiles = 1;
    }
    row.boxes = solver.boxes;
    let sample_box = covered_box(table, local, &rows, dims);
    for &(ts, ls, n) in &rows {
        for (smp, &cov) in table.samples[ts..ts + n].iter().zip(&local.covered[ls..ls + n]) {
            let c = uvt(smp);
            if let Some(b) = &outer {
                row.tested_certified += (0..3).all(|k| b[k][0] <= c[k] as f64 && c[k] as f64 <= b[k][1]) as u64;
            } else if cov {
                row.tested_certified += 1;
            }
            if let Some(b) = &sample_box {
                row.tested_sample_box += in_box(b, smp) as u64;
            }
        }
    }
    row
}

/// Buffers of [`exact_coverage`], reused from call to call.
#[derive(Default)]
pub struct CoverageScratch {
    points: Vec<[f64; 5]>,
    classes: Vec<Coverage>,
}

/// The exact coverage of `samples` by the triangle of `batch`, one entry per sample
/// (interior only: boundary samples are not covered), written to `out`; returns
/// (covered, boundary, exact). The one place the measurement asks the exact oracle: the
/// batched oracle (`oracles::batch`), which classifies the samples side by side in lanes
/// and sends every sample whose signs it cannot certify to the scalar oracle, so every
/// class is the scalar oracle's (`oracles::coverage::classify`). `exact` counts the
/// samples decided by exact dyadic arithmetic: those neither the lanes nor the scalar
/// oracle's floating-point filter could settle.
pub fn exact_coverage(
    batch: &Batch,
    samples: &[Sample],
    scratch: &mut CoverageScratch,
    out: &mut [bool],
) -> (u64, u64, u64) {
    scratch.points.clear();
    scratch.points.extend(samples.iter().map(Sample::to_oracle));
    let st = batch.classify(&scratch.points, &mut scratch.classes);
    let (mut covered, mut boundary) = (0u64, 0u64);
    for (c, o) in scratch.classes.iter().zip(out.iter_mut()) {
        *o = *c == Coverage::Interior;
        covered += *o as u64;
        boundary += (*c == Coverage::Boundary) as u64;
    }
    (covered, boundary, st.exact_fallbacks)
}

/// [`exact_coverage`] sample by sample with the scalar oracle (the reference the
/// batched path is tested against).
#[cfg(test)]
pub(crate) fn exact_coverage_scalar(tri: &oracles::Tri, samples: &[Sample], out: &mut [bool]) -> (u64, u64, u64) {
    let (mut covered, mut boundary, mut exact) = (0u64, 0u64, 0u64);
    for (s, o) in samples.iter().zip(out.iter_mut()) {
        let (c, ex) = oracles::coverage::classify_traced(tri, s.to_oracle());
        exact += ex as u64;
        *o = c == Coverage::Interior;
        covered += *o as u64;
        boundary += (c == Coverage::Boundary) as u64;
    }
    (covered, boundary, exact)
}

/// What every triangle of one setting shares.
struct Ctx<'a> {
    methods: &'a [&'static dyn Method],
    plan: &'a Plan,
    cfg: &'a Config,
    table: &'a SampleTable,
    setting: Setting,
}

/// The most parts of a conjunction met from its parts' answers (one with more is asked
/// itself).
const MAX_PARTS: usize = 4;

/// A placeholder answer.
static EMPTY: TileResult = TileResult::Empty;

/// Where a method's tile answer comes from.
enum Source {
    /// Its own setup (slot index).
    Own(usize),
    /// A conjunction of other methods' answers ([`Method::conjunction`]), their slots in
    /// order: derived from the answers the slots give anyway.
    Conj(Conjunction, Vec<usize>),
}

/// The methods the measurement sets up and asks per tile (**slots**: each distinct
/// method once), and per method of the run where its answer comes from. A method that
/// is by definition a conjunction of other registered methods (lc, mam2012-new and
/// their -safe variants) is not asked itself: its parts are (once, when they are also
/// in the run) and its answer is met from theirs ([`Conjunction::meet`], bit for bit
/// its own answer), so no tile test is repeated for the same tile.
struct Plan {
    slots: Vec<&'static dyn Method>,
    of: Vec<Source>,
}

impl Plan {
    fn new(methods: &[&'static dyn Method]) -> Plan {
        let mut slots: Vec<&'static dyn Method> = Vec::new();
        let mut slot = |m: &'static dyn Method| -> usize {
            let id = m.info().id;
            slots.iter().position(|x| x.info().id == id).unwrap_or_else(|| {
                slots.push(m);
                slots.len() - 1
            })
        };
        let mut of = Vec::with_capacity(methods.len());
        for &m in methods {
            of.push(match m.conjunction() {
                Some(c)
                    if (1..=MAX_PARTS).contains(&c.parts.len())
                        && c.parts.iter().all(|p| p.conjunction().is_none()) =>
                {
                    Source::Conj(c, c.parts.iter().map(|p| slot(**p)).collect())
                }
                _ => Source::Own(slot(m)),
            });
        }
        Plan { slots, of }
    }
}

/// Buffers reused from triangle to triangle (one per worker).
#[derive(Default)]
struct Scratch {
    covered: Vec<bool>,
    rows: Vec<(usize, usize, usize)>,
    coverage: CoverageScratch,
    admit: AdmitScratch,
    /// Buffers of [`region_pass`], kept from triangle to triangle.
    passes: Vec<Vec<bool>>,
}

fn measure_triangle(
    ctx: &Ctx,
    scratch: &mut Scratch,
    tri: &Triangle,
    fp: Footprint,
    chosen: &[(usize, u64)],
    out: &mut TriCounts,
) {
    let Ctx { methods, plan, cfg, table, setting } = *ctx;
    let (width, height) = (table.width, table.height);
    let nt = cfg.tiles.len();
    out.reset(nt, methods.len());
    let r = match fp {
        Footprint::OffScreen => {
            out.off_screen = true;
            return;
        }
        Footprint::WholeScreen => {
            out.whole_screen = true;
            PixelRect { x0: 0, y0: 0, x1: width - 1, y1: height - 1 }
        }
        Footprint::Region(r) => r,
    };
    // The union of the tiles of every size over r (tiles clipped to the screen).
    let mut u = r;
    for &s in &cfg.tiles {
        let (tx0, ty0, tx1, ty1) = tile_range(&r, s);
        u.x0 = u.x0.min(tx0 * s);
        u.y0 = u.y0.min(ty0 * s);
        u.x1 = u.x1.max(((tx1 + 1) * s).min(width) - 1);
        u.y1 = u.y1.max(((ty1 + 1) * s).min(height) - 1);
    }
    let spp = table.spp;
    let mut covered = std::mem::take(&mut scratch.covered);
    covered.clear();
    covered.resize(u.pixels() as usize * spp, false);
    let mut local = Local { rect: u, spp, covered };
    let otri = tri.to_oracle();
    let batch = Batch::new(&otri);
    let n_row = (r.x1 - r.x0 + 1) as usize * spp;
    for py in r.y0..=r.y1 {
        let (ts, ls) = (table.start(r.x0, py), local.start(r.x0, py));
        let (c, b, e) = exact_coverage(
            &batch,
            &table.samples[ts..ts + n_row],
            &mut scratch.coverage,
            &mut local.covered[ls..ls + n_row],
        );
        out.classified += n_row as u64;
        out.covered += c;
        out.boundary += b;
        out.exact += e;
    }
    let dims = tri.dims();
    let preps: Vec<Box<dyn Prepared>> = plan.slots.iter().map(|m| m.setup(tri)).collect();
    let slot_disabled: Vec<bool> = preps.iter().map(|p| p.disabled().is_some()).collect();
    for (d, src) in out.disabled.iter_mut().zip(&plan.of) {
        *d = match src {
            Source::Own(k) => slot_disabled[*k],
            Source::Conj(_, parts) => parts.iter().all(|&k| slot_disabled[k]),
        };
    }
    // The slots whose answer does not read the tile: asked once, and the values of their
    // per-sample constraints taken once per sample of the region (`pass`).
    let mut fixed: Vec<Option<TileResult>> = Vec::with_capacity(preps.len());
    let mut pass: Vec<Option<Vec<bool>>> = Vec::with_capacity(preps.len());
    let mut pool = std::mem::take(&mut scratch.passes);
    let any_tile = tile_of(&tile_pixels(r.x0 / cfg.tiles[0], r.y0 / cfg.tiles[0], cfg.tiles[0], width, height));
    for p in &preps {
        if p.tile_independent() {
            let a = p.tile(&any_tile);
            pass.push(match &a {
                TileResult::Bounds(b) if !b.constraints.is_empty() => {
                    let mut ps = pool.pop().unwrap_or_default();
                    region_pass(&mut scratch.admit, &[&b.constraints], table, &local, &mut ps);
                    Some(ps)
                }
                _ => None,
            });
            fixed.push(Some(a));
        } else {
            fixed.push(None);
            pass.push(None);
        }
    }
    let mut rows = std::mem::take(&mut scratch.rows);
    let mut admit = std::mem::take(&mut scratch.admit);
    let mut asked: Vec<Option<TileResult>> = Vec::with_capacity(preps.len());
    for (ti, &s) in cfg.tiles.iter().enumerate() {
        for (mi, w) in out.work[ti].iter_mut().enumerate() {
            w.add_setup(out.disabled[mi]);
        }
        let (tx0, ty0, tx1, ty1) = tile_range(&r, s);
        let ntx = (tx1 - tx0 + 1) as u64;
        // The tiles' boundaries (`tile_of(tile_pixels(..))`: the last one clipped to the
        // screen), and each asked method's answers over that grid.
        let xs: Vec<f32> = (tx0..=tx1).map(|t| (t * s) as f32).chain([((tx1 + 1) * s).min(width) as f32]).collect();
        let ys: Vec<f32> = (ty0..=ty1).map(|t| (t * s) as f32).chain([((ty1 + 1) * s).min(height) as f32]).collect();
        let grid = Grid::new(&xs, &ys);
        let grids: Vec<Option<Box<dyn TileGrid>>> =
            preps.iter().zip(&fixed).map(|(p, f)| f.is_none().then(|| p.grid(grid))).collect();
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                let p = tile_pixels(tx, ty, s, width, height);
                let tile = tile_of(&p);
                tile_rows(table, &local, &p, &mut rows);
                let n_here = rows.iter().map(|r| r.2 as u64).sum::<u64>();
                let cov_here = rows
                    .iter()
                    .map(|&(_, ls, n)| local.covered[ls..ls + n].iter().map(|&c| c as u32).sum::<u32>() as u64)
                    .sum::<u64>();
                if cov_here > 0 {
                    if let Some(b) = covered_box(table, &local, &rows, dims) {
                        let tested = rows.iter().map(|&(ts, _, n)| count_in_box(table, ts, n, &b)).sum::<u64>();
                        out.ceiling[ti].0 += tested;
                        out.ceiling[ti].1 += cov_here;
                    }
                }
                let (i, j) = ((tx - tx0) as usize, (ty - ty0) as usize);
                debug_assert_eq!(format!("{:?}", grid.tile(i, j)), format!("{tile:?}"));
                // Each slot's previous answer is dropped just before its new one is made,
                // so the allocator hands the freed constraint boxes straight back.
                asked.resize_with(grids.len(), || None);
                for (a, g) in asked.iter_mut().zip(&grids) {
                    *a = None;
                    *a = g.as_ref().map(|g| g.tile(i, j));
                }
                let answer = |k: usize| -> &TileResult { fixed[k].as_ref().or(asked[k].as_ref()).expect("asked") };
                for (mi, src) in plan.of.iter().enumerate() {
                    let c = &mut out.counts[ti][mi];
                    let w = &mut out.work[ti][mi];
                    let here = Here { table, local: &local, rows: &rows, n: n_here, cov: cov_here };
                    let kept = match src {
                        Source::Own(k) => match answer(*k) {
                            TileResult::Empty => false,
                            TileResult::Bounds(b) => {
                                let iv = (b.u, b.v, b.t);
                                match &pass[*k] {
                                    Some(ps) => count_passing(iv, ps, &here, c),
                                    None => count_admitted(&mut admit, iv, &[&b.constraints], &here, c),
                                }
                                true
                            }
                        },
                        Source::Conj(conj, parts) => {
                            let mut ans: [&TileResult; MAX_PARTS] = [&EMPTY; MAX_PARTS];
                            for (a, &k) in ans.iter_mut().zip(parts) {
                                *a = answer(k);
                            }
                            let ans = &ans[..parts.len()];
                            match conj.meet(ans) {
                                None => false,
                                Some(mt) => {
                                    let mut cons: [&[Box<dyn SampleConstraint>]; MAX_PARTS] = [&[]; MAX_PARTS];
                                    for (c, a) in cons.iter_mut().zip(ans) {
                                        if let TileResult::Bounds(b) = a {
                                            *c = &b.constraints;
                                        }
                                    }
                                    count_admitted(&mut admit, (mt.u, mt.v, mt.t), &cons[..ans.len()], &here, c);
                                    true
                                }
                            }
                        }
                    };
                    if kept {
                        w.add_tile(out.disabled[mi], n_here);
                    } else {
                        w.add_tile(out.disabled[mi], 0);
                        c.missed += cov_here;
                    }
                }
                let l = (ty - ty0) as u64 * ntx + (tx - tx0) as u64;
                // `chosen` is sorted: tile sizes in order, each one's tiles in order.
                if chosen.binary_search(&(ti, l)).is_ok() {
                    out.certified.push(certify(&otri, dims, table, &local, &p, &cfg.certified, setting, s));
                }
            }
        }
    }
    scratch.rows = rows;
    scratch.admit = admit;
    scratch.covered = local.covered;
    pool.extend(pass.into_iter().flatten());
    scratch.passes = pool;
}

/// The number of tiles of each size traversed for a footprint.
fn tiles_traversed(fp: Footprint, tiles: &[u32], width: u32, height: u32) -> Vec<u64> {
    let r = match fp {
        Footprint::OffScreen => return vec![0; tiles.len()],
        Footprint::WholeScreen => PixelRect { x0: 0, y0: 0, x1: width - 1, y1: height - 1 },
        Footprint::Region(r) => r,
    };
    tiles
        .iter()
        .map(|&s| {
            let (a, b, c, d) = tile_range(&r, s);
            (c - a + 1) as u64 * (d - b + 1) as u64
        })
        .collect()
}

/// The certified subset: per triangle, (tile index, local tile number) pairs, sorted;
/// for each tile size `n` pairs drawn uniformly without replacement from all traversed
/// ones (every one when `n` is at least their number).
fn choose_certified(
    fps: &[Footprint],
    cfg: &Config,
    setting: Setting,
    width: u32,
    height: u32,
) -> Vec<Vec<(usize, u64)>> {
    let mut chosen = vec![Vec::new(); fps.len()];
    if cfg.certified_tiles == 0 {
        return chosen;
    }
    let counts: Vec<Vec<u64>> = fps.iter().map(|&f| tiles_traversed(f, &cfg.tiles, width, height)).collect();
    for (ti, &s) in cfg.tiles.iter().enumerate() {
        let mut prefix = Vec::with_capacity(fps.len() + 1);
        prefix.push(0u64);
        for c in &counts {
            prefix.push(prefix.last().unwrap() + c[ti]);
        }
        let total = *prefix.last().unwrap();
        if total == 0 {
            continue;
        }
        let mut rng =
            rand_chacha::ChaCha8Rng::seed_from_u64(pattern::hash(&[cfg.seed, 0xce47, setting as u64, s as u64]));
        let n = cfg.certified_tiles.min(total as usize);
        let picks: Vec<u64> = if n == total as usize {
            (0..total).collect()
        } else {
            let mut p: Vec<u64> =
                rand::seq::index::sample(&mut rng, total as usize, n).into_iter().map(|x| x as u64).collect();
            p.sort_unstable();
            p
        };
        for g in picks {
            let tri = prefix.partition_point(|&p| p <= g) - 1;
            chosen[tri].push((ti, g - prefix[tri]));
        }
    }
    chosen
}

/// Measure the STE of `methods` on `scene` for each setting (see the module
/// documentation). `pb` advances by one per triangle and setting.
pub fn measure(
    scene: &Scene,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    cfg: &Config,
    pb: &ProgressBar,
) -> Measurement {
    let table = SampleTable::new(&cfg.pattern, scene.width, scene.height);
    measure_with(scene, &table, methods, settings, cfg, pb)
}

/// [`measure`] on a sample table built beforehand (`table` must be the pattern of
/// `cfg` over the scene's screen).
pub fn measure_with(
    scene: &Scene,
    table: &SampleTable,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    cfg: &Config,
    pb: &ProgressBar,
) -> Measurement {
    let (w, h) = (scene.width, scene.height);
    assert_eq!((table.width, table.height, table.spp), (w, h, cfg.pattern.spp as usize), "sample table mismatch");
    let mut m = Measurement::default();
    let plan = Plan::new(methods);
    for &setting in settings {
        let tris = scene.triangles(setting);
        let fps: Vec<Footprint> = tris.iter().map(|t| footprint(t, w, h)).collect();
        let chosen = choose_certified(&fps, cfg, setting, w, h);
        let ctx = Ctx { methods, plan: &plan, cfg, table, setting };
        let nm = methods.len();
        // Each worker keeps its buffers and its partial sums from triangle to triangle.
        let sums = tris
            .par_iter()
            .zip(fps.par_iter())
            .zip(chosen.par_iter())
            .fold(
                || (Scratch::default(), TriCounts::default(), Sums::new(setting, &cfg.tiles, nm)),
                |(mut scratch, mut tc, mut acc), ((t, &fp), ch)| {
                    measure_triangle(&ctx, &mut scratch, t, fp, ch, &mut tc);
                    acc.add(&tc, &cfg.tiles);
                    pb.inc(1);
                    (scratch, tc, acc)
                },
            )
            .map(|(_, _, acc)| acc)
            .reduce(|| Sums::new(setting, &cfg.tiles, nm), Sums::merge);
        let Sums { summary: sum, counts, work, ceiling, disabled, certified } = sums;
        for (ti, &s) in cfg.tiles.iter().enumerate() {
            for (mi, meth) in methods.iter().enumerate() {
                let info = meth.info();
                let c = counts[ti][mi];
                m.rows.push(MethodRow {
                    method: info.id.to_string(),
                    reconstruction: info.reconstruction,
                    per_sample: info.outputs.per_sample,
                    setting,
                    tile: s,
                    counts: c,
                    ste: ratio(c.hits, c.tested),
                    disabled_triangles: disabled[mi],
                    work: work[ti][mi],
                });
            }
            let (tested, covered) = ceiling[ti];
            m.ceiling.push(CeilingRow { setting, tile: s, tested, covered, ste: ratio(covered, tested) });
            if cfg.certified_tiles > 0 {
                let mut c = certified[ti].clone();
                c.ste_lower = ratio(c.covered, c.tested_certified);
                c.ste_upper = ratio(c.covered, c.tested_sample_box);
                m.certified.push(c);
            }
        }
        m.settings.push(sum);
    }
    m
}

#[cfg(test)]
mod tests;
