//! The timing pass: an end-to-end software stochastic rasterizer per method, timed
//! with `std::time::Instant` on one thread and normalised to `bbox` on the `static`
//! setting (as Munkberg & Akenine-Möller 2012, Table 2: "execution times ... for a CPU
//! implementation running on one core ... including triangle setup, rasterization,
//! Gouraud shading, and framebuffer updates. All numbers are normalized against BBOX
//! on the static scene").
//!
//! Per triangle, inside the timed region: the method's setup; the traversal of the
//! tiles over the triangle's screen footprint ([`super::footprint`]; the whole screen
//! when a vertex has w <= 0); the tile test; for every pattern sample of a non-culled
//! tile the method's per-sample test ([`TileBounds::admits`]); for each sample let
//! through, a hardware-like coverage test in **f32** (the sheared vertices at the
//! sample's (u, v, t), the three edge functions E_k translated to the sample's (x, y),
//! D = sum w_k E_k, covered when every E_k has the strict sign of D — the model's rule
//! evaluated in f32, not the exact oracle); for a covered sample a depth test against
//! a per-sample depth buffer (hit depth N / D, N = sum E_k z_k) and a Gouraud shade
//! (per-vertex colours blended by the barycentrics E_k / sum E) written to a
//! per-sample colour buffer. Not timed: building the clip-space triangles, the sample
//! pattern (a fixed table, as in hardware) and clearing the buffers.
//!
//! Timings on a shared machine are noisy: every method's pass is run `repeats` times,
//! round robin over the methods (so a slow spell of the machine hits all of them), and
//! the fastest is kept, after one untimed warm-up pass per setting. The tile test allocates its answer (`TileBounds` holds boxed
//! per-sample constraints), as it does for every method: hardware would not.

use super::pattern::{hash, Pattern};
use super::scene::{Scene, Setting};
use super::{footprint, tile_of, tile_pixels, tile_range, Footprint, PixelRect};
use crate::bounds::{Method, TileBounds, TileResult};
use crate::model::{Sample, Triangle};
use indicatif::ProgressBar;
use serde::Serialize;
use std::time::Instant;

/// One method's time on one setting.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimingRow {
    pub method: String,
    pub setting: Setting,
    pub tile: u32,
    /// Wall time of the fastest pass (seconds, one thread).
    pub seconds: f64,
    /// `seconds` over the reference pass (bbox on static when both were timed).
    pub relative: f64,
    /// Samples let through by the method (tile and per-sample tests).
    pub tested: u64,
    /// Of those, covered by the f32 edge test.
    pub covered_f32: u64,
}

/// The framebuffer: per-sample depth and colour.
struct Framebuffer {
    depth: Vec<f32>,
    color: Vec<u32>,
}

/// Per-triangle values of the f32 coverage test.
struct Raster {
    q: [[f32; 4]; 3],
    d: [[f32; 4]; 3],
    c0: [f32; 3],
    dc: [f32; 3],
    k: f32,
    rgb: [[f32; 3]; 3],
}

impl Raster {
    fn new(tri: &Triangle, id: u64) -> Self {
        let d = std::array::from_fn(|i| std::array::from_fn(|j| tri.r[i][j] - tri.q[i][j]));
        let dc = std::array::from_fn(|i| tri.c1[i] - tri.c0[i]);
        let rgb = std::array::from_fn(|i| {
            let h = hash(&[id, i as u64]);
            [(h & 0xff) as f32, ((h >> 8) & 0xff) as f32, ((h >> 16) & 0xff) as f32]
        });
        Raster { q: tri.q, d, c0: tri.c0, dc, k: tri.k, rgb }
    }

    /// Covered (f32 rule) and, if so, the hit depth and packed colour.
    #[inline]
    fn shade(&self, s: &Sample) -> Option<(f32, u32)> {
        let mut p = [[0.0f32; 4]; 3];
        for (i, pi) in p.iter_mut().enumerate() {
            let c = self.c0[i] + s.t * self.dc[i];
            let w = self.q[i][3] + s.t * self.d[i][3];
            *pi = [
                self.q[i][0] + s.t * self.d[i][0] + s.u * c - s.x * w,
                self.q[i][1] + s.t * self.d[i][1] + self.k * s.v * c - s.y * w,
                self.q[i][2] + s.t * self.d[i][2],
                w,
            ];
        }
        let e = [
            p[1][0] * p[2][1] - p[1][1] * p[2][0],
            p[2][0] * p[0][1] - p[2][1] * p[0][0],
            p[0][0] * p[1][1] - p[0][1] * p[1][0],
        ];
        let d = p[0][3] * e[0] + p[1][3] * e[1] + p[2][3] * e[2];
        let inside = if d > 0.0 {
            e.iter().all(|&x| x > 0.0)
        } else if d < 0.0 {
            e.iter().all(|&x| x < 0.0)
        } else {
            false
        };
        if !inside {
            return None;
        }
        let n = e[0] * p[0][2] + e[1] * p[1][2] + e[2] * p[2][2];
        let sum = e[0] + e[1] + e[2];
        let ch =
            |k: usize| ((e[0] * self.rgb[0][k] + e[1] * self.rgb[1][k] + e[2] * self.rgb[2][k]) / sum) as u32 & 0xff;
        Some((n / d, ch(0) | ch(1) << 8 | ch(2) << 16))
    }
}

/// Render one triangle with one method; returns (tested, covered).
#[allow(clippy::too_many_arguments)]
fn render(
    tri: &Triangle,
    id: u64,
    method: &dyn Method,
    tile: u32,
    width: u32,
    height: u32,
    table: &[Sample],
    spp: usize,
    fb: &mut Framebuffer,
) -> (u64, u64) {
    let r = match footprint(tri, width, height) {
        Footprint::OffScreen => return (0, 0),
        Footprint::WholeScreen => PixelRect { x0: 0, y0: 0, x1: width - 1, y1: height - 1 },
        Footprint::Region(r) => r,
    };
    let prep = method.setup(tri);
    let ras = Raster::new(tri, id);
    let (mut tested, mut covered) = (0u64, 0u64);
    let (tx0, ty0, tx1, ty1) = tile_range(&r, tile);
    for ty in ty0..=ty1 {
        for tx in tx0..=tx1 {
            let p = tile_pixels(tx, ty, tile, width, height);
            let TileResult::Bounds(b) = prep.tile(&tile_of(&p)) else { continue };
            let (t, c) = samples_of_tile(&b, &ras, &p, width, table, spp, fb);
            tested += t;
            covered += c;
        }
    }
    (tested, covered)
}

#[inline]
fn samples_of_tile(
    b: &TileBounds,
    ras: &Raster,
    p: &PixelRect,
    width: u32,
    table: &[Sample],
    spp: usize,
    fb: &mut Framebuffer,
) -> (u64, u64) {
    let (mut tested, mut covered) = (0u64, 0u64);
    for py in p.y0..=p.y1 {
        for px in p.x0..=p.x1 {
            let base = (py as usize * width as usize + px as usize) * spp;
            for (k, s) in table[base..base + spp].iter().enumerate() {
                if !b.admits(s) {
                    continue;
                }
                tested += 1;
                if let Some((z, rgb)) = ras.shade(s) {
                    covered += 1;
                    let i = base + k;
                    if z < fb.depth[i] {
                        fb.depth[i] = z;
                        fb.color[i] = rgb;
                    }
                }
            }
        }
    }
    (tested, covered)
}

/// Time every method on every setting (one thread; the fastest of `repeats` passes, run
/// round robin).
/// `relative` is against bbox on static when both are timed, else against the first
/// pass timed. `pb` advances by one per pass.
pub fn time_methods(
    scene: &Scene,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    tile: u32,
    pattern: &Pattern,
    repeats: u32,
    pb: &ProgressBar,
) -> Vec<TimingRow> {
    let (w, h, spp) = (scene.width, scene.height, pattern.spp as usize);
    let mut table = Vec::new();
    pattern.region(0, 0, w - 1, h - 1, &mut table);
    let mut fb = Framebuffer { depth: vec![f32::INFINITY; table.len()], color: vec![0; table.len()] };
    let mut rows = Vec::new();
    for &setting in settings {
        let tris = scene.triangles(setting);
        let first = rows.len();
        for m in methods {
            rows.push(TimingRow {
                method: m.info().id.to_string(),
                setting,
                tile,
                seconds: f64::INFINITY,
                relative: f64::NAN,
                tested: 0,
                covered_f32: 0,
            });
        }
        // One untimed pass first (caches, branch predictors, clock ramp-up), then round
        // robin: a slow spell of the machine hits every method, not one method's passes.
        if let Some(m) = methods.first() {
            for (i, tri) in tris.iter().enumerate() {
                render(tri, i as u64, *m, tile, w, h, &table, spp, &mut fb);
            }
        }
        for _ in 0..repeats.max(1) {
            for (k, m) in methods.iter().enumerate() {
                fb.depth.fill(f32::INFINITY);
                fb.color.fill(0);
                let start = Instant::now();
                let (mut t, mut c) = (0u64, 0u64);
                for (i, tri) in tris.iter().enumerate() {
                    let (a, b) = render(tri, i as u64, *m, tile, w, h, &table, spp, &mut fb);
                    t += a;
                    c += b;
                }
                let secs = start.elapsed().as_secs_f64();
                std::hint::black_box(&fb.color);
                let row = &mut rows[first + k];
                row.seconds = row.seconds.min(secs);
                (row.tested, row.covered_f32) = (t, c);
                pb.inc(1);
            }
        }
    }
    let reference = rows
        .iter()
        .find(|r| r.method == "bbox" && r.setting == Setting::Static)
        .or(rows.first())
        .map(|r| r.seconds)
        .unwrap_or(1.0);
    for r in &mut rows {
        r.relative = r.seconds / reference;
    }
    rows
}

/// What the relative times are relative to.
pub fn reference_name(rows: &[TimingRow]) -> String {
    if rows.iter().any(|r| r.method == "bbox" && r.setting == Setting::Static) {
        "bbox on static".into()
    } else {
        rows.first().map(|r| format!("{} on {}", r.method, r.setting.name())).unwrap_or_default()
    }
}
