//! The cost axis: what a method's culling costs a software rasterizer, with its noise.
//!
//! Timing a whole render per method on a shared machine gives differences smaller than
//! the noise (two methods doing the same work plotted 20 % apart). Instead the cost is
//! **counts times per-operation costs**:
//!
//! - the counts come from the STE measurement ([`super::Work`], exact integers): per
//!   method, setting and tile size, the triangles set up, the tile tests, the samples
//!   given the per-sample test (every sample of a tile not culled) and the samples let
//!   through (`tested`, each then given the coverage test and shaded);
//! - the per-operation costs are timed ([`time_ops`]) on a fixed subset of the scene's
//!   triangles: the method's setup, its tile test over those triangles' tiles, its
//!   per-sample test ([`TileBounds::admits`]) over the samples of the tiles it keeps,
//!   and, once per setting for every method, the f32 coverage test and Gouraud shade of
//!   a sample ([`super::raster`]). The tile tests and sample tests timed are spread
//!   evenly over those of the subset and capped ([`MAX_TIMED_TILES`],
//!   [`MAX_TIMED_SAMPLES`]: a cost per operation needs no more). Each operation is timed
//!   over at least [`MIN_TIMED`] of calls, in `rounds` rounds run round robin over the methods (a slow
//!   spell of the machine hits them all); within a round the methods are timed side by
//!   side on the run's threads (`--jobs`), each operation on one thread, so every cost
//!   is a cost per thread with the other threads busy alike.
//!
//! Round r gives every method an estimated total `sum(count x cost_r)`; a method's cost
//! is the **median over the rounds, with the lowest and highest as its interval** (the
//! error bar of the chart). Where a method disabled itself on a triangle its answer is
//! the whole domain, bbox's work: those operations are charged at bbox's costs of the
//! same round, so a method disabled everywhere is never cheaper than bbox (its counts
//! are at least bbox's and its per-operation costs are bbox's). More generally, the
//! estimate grows with every count: a method that does more of every operation at the
//! same per-operation costs never plots cheaper.
//!
//! The costs of a method come from the triangles of the subset where it is enabled; a
//! method enabled on none of them is charged bbox's costs (it is then disabled on most
//! of the scene, and its counts say so).

use super::raster::Raster;
use super::scene::{Scene, Setting};
use super::{footprint, tile_of, tile_pixels, tile_range, Footprint, MethodRow, PixelRect, SampleTable};
use crate::bounds::{Method, Prepared, TileBounds, TileResult};
use crate::model::{Tile, Triangle};
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The least time over which each operation is timed per round (calls are repeated).
pub const MIN_TIMED: Duration = Duration::from_micros(600);

/// The most tile tests a method's tile cost is timed on per call (evenly spread over
/// its tiles of the subset): enough for [`MIN_TIMED`], no more.
pub const MAX_TIMED_TILES: usize = 1024;

/// The most samples a method's per-sample cost is timed on per call (the samples of
/// kept tiles evenly spread over those of the subset).
pub const MAX_TIMED_SAMPLES: usize = 16384;

/// Every `ceil(len / max)`-th item, from the first: at most `max` items spread evenly
/// over the list (all of them when there are no more than `max`).
fn spread<T>(v: Vec<T>, max: usize) -> Vec<T> {
    let k = v.len().div_ceil(max.max(1)).max(1);
    v.into_iter().step_by(k).collect()
}

/// A timed quantity: median over the rounds and the range of the rounds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    pub median: f64,
    pub lo: f64,
    pub hi: f64,
}

impl Estimate {
    /// Median, min and max of the values (NaN when empty).
    pub fn of(values: &[f64]) -> Self {
        if values.is_empty() {
            return Estimate { median: f64::NAN, lo: f64::NAN, hi: f64::NAN };
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) };
        Estimate { median, lo: v[0], hi: v[n - 1] }
    }
    /// Every value divided by `d`.
    pub fn over(&self, d: f64) -> Self {
        Estimate { median: self.median / d, lo: self.lo / d, hi: self.hi / d }
    }
}

/// One method's per-operation costs on one setting, nanoseconds per call, one value
/// per round (empty when the method was enabled on no triangle of the subset).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OpCosts {
    pub method: String,
    pub setting: Setting,
    /// Triangles of the subset the method was timed on (those where it is enabled).
    pub triangles: usize,
    pub setup_ns: Vec<f64>,
    pub tile_ns: Vec<f64>,
    pub sample_ns: Vec<f64>,
}

/// The per-operation costs of every method, and the shading cost per setting.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct OpTable {
    /// Tile size of the timed tile tests.
    pub tile: u32,
    pub rounds: u32,
    pub ops: Vec<OpCosts>,
    /// Per setting: ns per sample for the f32 coverage test and shade, per round.
    pub shade_ns: Vec<(Setting, Vec<f64>)>,
}

/// One method's estimated cost on one setting.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CostRow {
    pub method: String,
    pub setting: Setting,
    pub tile: u32,
    /// Estimated seconds of culling and shading for the whole scene.
    pub seconds: Estimate,
    /// `seconds` over bbox's median on the same setting.
    pub relative: Estimate,
    /// Median per-operation costs (ns): setup, tile test, sample test.
    pub setup_ns: f64,
    pub tile_ns: f64,
    pub sample_ns: f64,
}

/// Up to `n` triangle indices spread evenly over the on-screen triangles.
fn subset(fps: &[Footprint], n: usize) -> Vec<usize> {
    let on: Vec<usize> = (0..fps.len()).filter(|&i| fps[i] != Footprint::OffScreen).collect();
    if on.len() <= n {
        return on;
    }
    (0..n).map(|k| on[k * on.len() / n]).collect()
}

/// Call `f` repeatedly for at least [`MIN_TIMED`]; ns per operation (`ops` per call).
fn time_per_op(ops: usize, mut f: impl FnMut()) -> f64 {
    if ops == 0 {
        return f64::NAN;
    }
    let start = Instant::now();
    let mut calls = 0u64;
    loop {
        f();
        calls += 1;
        let e = start.elapsed();
        if e >= MIN_TIMED {
            return e.as_nanos() as f64 / (calls as f64 * ops as f64);
        }
    }
}

/// What one method is timed on: its enabled triangles of the subset, their tiles, and
/// the answers of the tiles it keeps with their samples.
struct Job<'a> {
    tris: Vec<&'a Triangle>,
    preps: Vec<Box<dyn Prepared>>,
    /// (index into `preps`, tile)
    tiles: Vec<(usize, Tile)>,
    kept: Vec<(TileBounds, PixelRect)>,
    samples: usize,
}

fn rect(fp: Footprint, w: u32, h: u32) -> Option<PixelRect> {
    match fp {
        Footprint::OffScreen => None,
        Footprint::WholeScreen => Some(PixelRect { x0: 0, y0: 0, x1: w - 1, y1: h - 1 }),
        Footprint::Region(r) => Some(r),
    }
}

fn job<'a>(m: &dyn Method, tris: &[&'a Triangle], fps: &[Footprint], table: &SampleTable, tile: u32) -> Job<'a> {
    let (w, h) = (table.width, table.height);
    let mut j = Job { tris: Vec::new(), preps: Vec::new(), tiles: Vec::new(), kept: Vec::new(), samples: 0 };
    let mut pixels = Vec::new();
    for (t, &fp) in tris.iter().zip(fps) {
        let Some(r) = rect(fp, w, h) else { continue };
        let prep = m.setup(t);
        if prep.disabled().is_some() {
            continue;
        }
        let (tx0, ty0, tx1, ty1) = tile_range(&r, tile);
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                let p = tile_pixels(tx, ty, tile, w, h);
                j.tiles.push((j.preps.len(), tile_of(&p)));
                pixels.push(p);
            }
        }
        j.tris.push(t);
        j.preps.push(prep);
    }
    // The timed tiles, evenly spread; the kept ones among them give the timed samples.
    let k = j.tiles.len().div_ceil(MAX_TIMED_TILES).max(1);
    j.tiles = spread(std::mem::take(&mut j.tiles), MAX_TIMED_TILES);
    let pixels: Vec<PixelRect> = pixels.into_iter().step_by(k).collect();
    for ((i, t), p) in j.tiles.iter().zip(pixels) {
        if let TileResult::Bounds(b) = j.preps[*i].tile(t) {
            j.samples += p.pixels() as usize * table.spp;
            j.kept.push((b, p));
        }
    }
    // Kept tiles evenly spread, as many as hold about MAX_TIMED_SAMPLES samples.
    if j.samples > MAX_TIMED_SAMPLES {
        let per = j.samples as f64 / j.kept.len() as f64;
        let n = ((MAX_TIMED_SAMPLES as f64 / per).ceil() as usize).max(1);
        j.kept = spread(std::mem::take(&mut j.kept), n);
        j.samples = j.kept.iter().map(|(_, p)| p.pixels() as usize * table.spp).sum();
    }
    j
}

fn for_samples(table: &SampleTable, p: &PixelRect, mut f: impl FnMut(&crate::model::Sample)) {
    let n = (p.x1 - p.x0 + 1) as usize * table.spp;
    for py in p.y0..=p.y1 {
        let s = table.start(p.x0, py);
        for x in &table.samples[s..s + n] {
            f(x);
        }
    }
}

/// One round of one method: ns per setup, tile test and sample test (each operation
/// timed on the calling thread).
fn time_method(m: &dyn Method, j: &Job, table: &SampleTable) -> [f64; 3] {
    let setup = time_per_op(j.tris.len(), || {
        for t in &j.tris {
            black_box(m.setup(black_box(t)));
        }
    });
    let tiles = time_per_op(j.tiles.len(), || {
        for (i, t) in &j.tiles {
            black_box(j.preps[*i].tile(black_box(t)));
        }
    });
    let samples = time_per_op(j.samples, || {
        for (b, p) in &j.kept {
            let mut n = 0u32;
            for_samples(table, p, |s| n += b.admits(black_box(s)) as u32);
            black_box(n);
        }
    });
    [setup, tiles, samples]
}

/// Time the operations of every method on every setting, `rounds` rounds round robin,
/// on up to `per_setting` triangles of each setting. The methods of a round are timed
/// side by side on the threads of the current rayon pool (each operation on one
/// thread, so a method's costs are per thread; with one thread, one after the other);
/// the shading cost once per round, alone. `pb` advances by one per method, setting
/// and round.
#[allow(clippy::too_many_arguments)]
pub fn time_ops(
    scene: &Scene,
    table: &SampleTable,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    tile: u32,
    rounds: u32,
    per_setting: usize,
    pb: &ProgressBar,
) -> OpTable {
    let (w, h) = (scene.width, scene.height);
    let mut out = OpTable { tile, rounds, ..Default::default() };
    for &setting in settings {
        let all = scene.triangles(setting);
        let fps_all: Vec<Footprint> = all.iter().map(|t| footprint(t, w, h)).collect();
        let idx = subset(&fps_all, per_setting);
        let tris: Vec<&Triangle> = idx.iter().map(|&i| &all[i]).collect();
        let fps: Vec<Footprint> = idx.iter().map(|&i| fps_all[i]).collect();
        let jobs: Vec<Job> = methods.par_iter().map(|m| job(*m, &tris, &fps, table, tile)).collect();
        // Shading: every sample of the tiles bbox keeps (or of every tile), triangle by triangle.
        let shade_jobs: Vec<(Raster, PixelRect)> = {
            let mut v = Vec::new();
            for (i, (t, &fp)) in tris.iter().zip(&fps).enumerate() {
                let Some(r) = rect(fp, w, h) else { continue };
                let (tx0, ty0, tx1, ty1) = tile_range(&r, tile);
                for ty in ty0..=ty1 {
                    for tx in tx0..=tx1 {
                        v.push((Raster::new(t, i as u64), tile_pixels(tx, ty, tile, w, h)));
                    }
                }
            }
            v
        };
        let shade_n: usize = shade_jobs.iter().map(|(_, p)| p.pixels() as usize * table.spp).sum();
        let shade_jobs = if shade_n > MAX_TIMED_SAMPLES {
            let n = ((MAX_TIMED_SAMPLES as f64 * shade_jobs.len() as f64 / shade_n as f64).ceil() as usize).max(1);
            spread(shade_jobs, n)
        } else {
            shade_jobs
        };
        let shade_n: usize = shade_jobs.iter().map(|(_, p)| p.pixels() as usize * table.spp).sum();
        let first = out.ops.len();
        for (m, j) in methods.iter().zip(&jobs) {
            out.ops.push(OpCosts {
                method: m.info().id.to_string(),
                setting,
                triangles: j.tris.len(),
                setup_ns: Vec::new(),
                tile_ns: Vec::new(),
                sample_ns: Vec::new(),
            });
        }
        let mut shade = Vec::new();
        for _ in 0..rounds.max(1) {
            // The methods of a round side by side on the pool's threads (each operation
            // timed on one thread); their costs kept in method order.
            let timed: Vec<[f64; 3]> = methods
                .par_iter()
                .zip(&jobs)
                .map(|(m, j)| {
                    let t = time_method(*m, j, table);
                    pb.inc(1);
                    t
                })
                .collect();
            for (k, (j, [setup, tiles, samples])) in jobs.iter().zip(timed).enumerate() {
                let row = &mut out.ops[first + k];
                if !j.tris.is_empty() {
                    row.setup_ns.push(setup);
                    row.tile_ns.push(if tiles.is_nan() { 0.0 } else { tiles });
                    row.sample_ns.push(if samples.is_nan() { 0.0 } else { samples });
                }
            }
            shade.push(time_per_op(shade_n, || {
                let mut acc = 0u32;
                for (ras, p) in &shade_jobs {
                    for_samples(table, p, |s| {
                        if let Some((z, c)) = ras.shade(black_box(s)) {
                            acc = acc.wrapping_add(c ^ z.to_bits());
                        }
                    });
                }
                black_box(acc);
            }));
        }
        out.shade_ns.push((setting, shade));
    }
    out
}

/// The costs of round `r` for `method` on `setting`: (setup, tile, sample) ns, or
/// None when it was not timed (no enabled triangle in the subset).
fn round_costs(ops: &OpTable, method: &str, setting: Setting, r: usize) -> Option<[f64; 3]> {
    let o = ops.ops.iter().find(|o| o.method == method && o.setting == setting)?;
    Some([*o.setup_ns.get(r)?, *o.tile_ns.get(r)?, *o.sample_ns.get(r)?])
}

/// The estimated cost of every method row at tile size `tile`: per round,
/// `sum(count x cost)` with disabled work at bbox's costs (see the module
/// documentation); median and range over the rounds. Needs bbox timed on each
/// setting (its costs price disabled work); rows without timing are left out.
pub fn costs(rows: &[MethodRow], ops: &OpTable, tile: u32) -> Vec<CostRow> {
    let mut out = Vec::new();
    for r in rows.iter().filter(|r| r.tile == tile) {
        let Some(totals) = totals(r, ops) else { continue };
        let bbox = rows.iter().find(|b| b.method == "bbox" && b.setting == r.setting && b.tile == tile);
        let reference = bbox.and_then(|b| totals_of(b, ops)).map(|t| Estimate::of(&t).median);
        let seconds = Estimate::of(&totals).over(1e9);
        let rel = reference.map(|x| Estimate::of(&totals).over(x)).unwrap_or(Estimate {
            median: f64::NAN,
            lo: f64::NAN,
            hi: f64::NAN,
        });
        let med = |v: &[f64]| Estimate::of(v).median;
        let o = ops.ops.iter().find(|o| o.method == r.method && o.setting == r.setting);
        out.push(CostRow {
            method: r.method.clone(),
            setting: r.setting,
            tile,
            seconds,
            relative: rel,
            setup_ns: o.map(|o| med(&o.setup_ns)).unwrap_or(f64::NAN),
            tile_ns: o.map(|o| med(&o.tile_ns)).unwrap_or(f64::NAN),
            sample_ns: o.map(|o| med(&o.sample_ns)).unwrap_or(f64::NAN),
        });
    }
    out
}

fn totals_of(r: &MethodRow, ops: &OpTable) -> Option<Vec<f64>> {
    totals(r, ops)
}

/// The estimated total (ns) of a row in each round.
fn totals(r: &MethodRow, ops: &OpTable) -> Option<Vec<f64>> {
    let shade = &ops.shade_ns.iter().find(|(s, _)| *s == r.setting)?.1;
    let mut out = Vec::new();
    for (k, &sh) in shade.iter().enumerate() {
        let bbox = round_costs(ops, "bbox", r.setting, k)?;
        let own = round_costs(ops, &r.method, r.setting, k).unwrap_or(bbox);
        out.push(total(r, own, bbox, sh));
    }
    Some(out)
}

/// `sum(count x cost)` for one round: the method's own costs on its enabled work,
/// bbox's on its disabled work, the shade on every sample let through.
pub fn total(r: &MethodRow, own: [f64; 3], bbox: [f64; 3], shade: f64) -> f64 {
    let w = &r.work;
    w.setups as f64 * own[0]
        + w.tile_tests as f64 * own[1]
        + w.sample_tests as f64 * own[2]
        + w.disabled_setups as f64 * bbox[0]
        + w.disabled_tile_tests as f64 * bbox[1]
        + w.disabled_sample_tests as f64 * bbox[2]
        + r.counts.tested as f64 * shade
}
