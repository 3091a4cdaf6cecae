//! Seeded generators of cases (thin-lens, physical) across the regimes where culling
//! bounds are stressed. Every draw comes from a [`Source`]: a `ChaCha8Rng` seeded from
//! (seed, index), so a case is the same at any thread count, or a [`Tape`] of numbers in
//! [0, 1) that proptest draws and shrinks (see [`strategy`]). One builder serves both, so
//! a proptest case is a case of the same regime the gate checks.

use crate::model::{Case, Sample, ThinLens, Tile, Triangle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// The regimes of physical cases.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "kebab-case")]
pub enum Regime {
    Static,
    Motion,
    Defocus,
    Both,
    /// Vertices on both sides of the focal plane (their CoC changes sign).
    FocalCrossing,
    /// A vertex behind the lens (w < 0) at some time.
    BehindLens,
    /// A needle-thin triangle.
    Sliver,
    /// Smaller than a pixel on screen (1e-3 .. 1 px).
    Tiny,
    /// Far larger than the screen (1e2 .. 1e5 px), every vertex in front of the lens.
    Huge,
    /// Large perspective motion: every vertex's depth changes 2- to 8-fold over the shutter.
    Perspective,
    /// The triangle turns over during the shutter (mirrored at t = 1, so its winding
    /// flips and it is degenerate in between).
    FacingFlip,
    /// Circles of confusion of 1e2 .. 3e3 pixels at the centre depth (far from focus,
    /// lens radius up to 50).
    HugeCoc,
    /// Circles of confusion of 1e-4 .. 0.3 pixels at the centre depth.
    TinyCoc,
    /// The triangle 1e4 .. 1e6 px from the screen origin, where f32 keeps few fraction bits.
    FarFromOrigin,
    /// Zero area: two vertices equal, or all three, or collinear, at one or both ends of
    /// the shutter.
    Degenerate,
    /// All three vertices at one depth (a wall facing the camera), moving, if at all, in
    /// x and y only.
    ScreenParallel,
}

impl Regime {
    pub const ALL: [Regime; 16] = [
        Regime::Static,
        Regime::Motion,
        Regime::Defocus,
        Regime::Both,
        Regime::FocalCrossing,
        Regime::BehindLens,
        Regime::Sliver,
        Regime::Tiny,
        Regime::Huge,
        Regime::Perspective,
        Regime::FacingFlip,
        Regime::HugeCoc,
        Regime::TinyCoc,
        Regime::FarFromOrigin,
        Regime::Degenerate,
        Regime::ScreenParallel,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Regime::Static => "static",
            Regime::Motion => "motion",
            Regime::Defocus => "defocus",
            Regime::Both => "both",
            Regime::FocalCrossing => "focal-crossing",
            Regime::BehindLens => "behind-lens",
            Regime::Sliver => "sliver",
            Regime::Tiny => "tiny",
            Regime::Huge => "huge",
            Regime::Perspective => "perspective",
            Regime::FacingFlip => "facing-flip",
            Regime::HugeCoc => "huge-coc",
            Regime::TinyCoc => "tiny-coc",
            Regime::FarFromOrigin => "far-from-origin",
            Regime::Degenerate => "degenerate",
            Regime::ScreenParallel => "screen-parallel",
        }
    }
}

/// The rng of case `index` of a run with `seed`.
pub fn rng_for(seed: u64, index: u64) -> ChaCha8Rng {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    r.set_stream(index);
    r
}

/// Where a generator's numbers come from.
pub trait Source {
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f32, hi: f32) -> f32;
    /// True with probability p.
    fn chance(&mut self, p: f64) -> bool;
    /// Log-uniform in [lo, hi).
    fn log_uniform(&mut self, lo: f32, hi: f32) -> f32 {
        self.range(lo.ln(), hi.ln()).exp()
    }
    /// Uniform in [lo, hi), but an end of the range with probability 1/4 (each end 1/8):
    /// the corners of a parameter's range are where bounds break.
    fn cornered(&mut self, lo: f32, hi: f32) -> f32 {
        let x = self.range(0.0, 1.0);
        if x < 0.125 {
            lo
        } else if x >= 0.875 {
            hi
        } else {
            lo + (hi - lo) * (x - 0.125) / 0.75
        }
    }
    /// Log-uniform with the ends of the range favoured as in [`cornered`](Self::cornered).
    fn log_cornered(&mut self, lo: f32, hi: f32) -> f32 {
        self.cornered(lo.ln(), hi.ln()).exp().clamp(lo, hi)
    }
    /// +1 or -1.
    fn sign(&mut self) -> f32 {
        if self.chance(0.5) {
            1.0
        } else {
            -1.0
        }
    }
}

impl Source for ChaCha8Rng {
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        self.gen_range(lo..hi)
    }
    fn chance(&mut self, p: f64) -> bool {
        self.gen_bool(p)
    }
}

/// A fixed list of numbers in [0, 1) read in turn (0.5 once it runs out). A number
/// shrunk towards 0 moves a range draw to its low end and makes a chance false, so
/// proptest's shrinking walks towards plainer cases.
#[derive(Clone, Debug)]
pub struct Tape {
    vals: Vec<f64>,
    pos: usize,
}

impl Tape {
    pub fn new(vals: Vec<f64>) -> Self {
        Tape { vals, pos: 0 }
    }
    fn next(&mut self) -> f64 {
        let x = self.vals.get(self.pos).copied().unwrap_or(0.5).clamp(0.0, 1.0);
        self.pos += 1;
        x
    }
}

impl Source for Tape {
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let x = lo + (hi - lo) * self.next() as f32;
        if x < hi {
            x.max(lo)
        } else {
            lo.max(hi - (hi - lo) * f32::EPSILON)
        }
    }
    fn chance(&mut self, p: f64) -> bool {
        self.next() >= 1.0 - p
    }
}

/// proptest strategies over the same builder as the seeded generator.
pub mod strategy {
    use super::{physical_case, Regime, Tape};
    use crate::model::Case;
    use proptest::prelude::*;

    /// Numbers a case of any regime needs, with room to spare.
    pub const TAPE_LEN: usize = 64;

    /// A case of the regime built from a tape of [0, 1) numbers (the tape shrinks).
    pub fn case(regime: Regime) -> impl Strategy<Value = Case> {
        proptest::collection::vec(0.0f64..1.0, TAPE_LEN).prop_map(move |v| physical_case(&mut Tape::new(v), regime))
    }

    /// A case of any regime.
    pub fn any_case() -> impl Strategy<Value = (Regime, Case)> {
        (0..Regime::ALL.len()).prop_flat_map(|k| {
            let r = Regime::ALL[k];
            case(r).prop_map(move |c| (r, c))
        })
    }
}

/// A random thin-lens camera; `lens` false gives a pinhole (R = 0).
pub fn camera(rng: &mut impl Source, lens: bool) -> ThinLens {
    let fx = rng.log_uniform(100.0, 2000.0);
    let k = if rng.chance(0.5) { 1.0 } else { 0.75 };
    ThinLens {
        fx,
        fy: fx * k,
        cx: rng.range(-50.0, 50.0),
        cy: rng.range(-50.0, 50.0),
        radius: if lens { rng.log_uniform(0.005, 0.2) } else { 0.0 },
        focus: rng.log_uniform(1.0, 20.0),
        near: 0.1,
        far: 1000.0,
    }
}

/// A physical case of the regime.
pub fn physical_case(rng: &mut impl Source, regime: Regime) -> Case {
    use Regime::*;
    if regime > Sliver {
        return stress_case(rng, regime);
    }
    let lens = matches!(regime, Defocus | Both | FocalCrossing | BehindLens | Sliver)
        && !(regime == Sliver && rng.chance(0.3));
    let cam = camera(rng, lens);
    let moving = matches!(regime, Motion | Both | BehindLens) || (regime == Sliver && rng.chance(0.5));
    // Centre depth and size.
    let z = match regime {
        FocalCrossing => cam.focus * rng.range(0.7, 1.3),
        _ => rng.log_uniform(0.5, 50.0),
    };
    let size = z * rng.log_uniform(1e-3, 0.3);
    let centre = [rng.range(-0.3, 0.3) * z, rng.range(-0.3, 0.3) * z, z];
    let mut q = [[0.0f32; 3]; 3];
    for p in q.iter_mut() {
        for j in 0..3 {
            p[j] = centre[j] + rng.range(-1.0, 1.0) * size;
        }
    }
    match regime {
        FocalCrossing => {
            q[0][2] = cam.focus * rng.range(0.5, 0.95);
            q[1][2] = cam.focus * rng.range(1.05, 2.0);
        }
        BehindLens => {
            q[0][2] = -rng.range(0.01, 1.0) * z;
        }
        Sliver => {
            let f = rng.log_uniform(1e-5, 1e-2);
            let (a, b) = (q[0], q[1]);
            for (j, c) in q[2].iter_mut().enumerate() {
                *c = a[j] + (b[j] - a[j]) * rng.range(0.2, 0.8) + f * size * rng.range(-1.0, 1.0);
            }
        }
        _ => {}
    }
    let mut r = q;
    if moving {
        let m = size * rng.log_uniform(0.1, 10.0);
        move_rigidly(rng, &mut r, m, f32::INFINITY);
    }
    let tri: Triangle = cam.triangle(q, r);
    Case { triangle: tri, lens: Some(cam) }
}

/// Translate by a random offset of size `m` (depth half as much, and at most
/// `depth_cap`), each vertex wobbling apart with probability 0.3.
fn move_rigidly(rng: &mut impl Source, r: &mut [[f32; 3]; 3], m: f32, depth_cap: f32) {
    let cap = |x: f32, j: usize| if j == 2 { x.clamp(-depth_cap, depth_cap) } else { x };
    let d = [rng.range(-1.0, 1.0) * m, rng.range(-1.0, 1.0) * m, cap(rng.range(-0.5, 0.5) * m, 2)];
    for (i, p) in r.iter_mut().enumerate() {
        let wobble = if rng.chance(0.3) { rng.range(-0.3, 0.3) * m } else { 0.0 };
        for j in 0..3 {
            p[j] += d[j] + if j == i { cap(wobble, j) } else { 0.0 };
        }
    }
}

/// The regimes after `Sliver`: each stresses one thing, with the lens and the motion on
/// or off at random (so static, motion-only and defocus-only cases occur) and sizes,
/// depths and ratios log-uniform with the ends of their ranges favoured.
fn stress_case(rng: &mut impl Source, regime: Regime) -> Case {
    use Regime::*;
    let lens = match regime {
        HugeCoc | TinyCoc => true,
        _ => rng.chance(0.6),
    };
    let mut moving = match regime {
        Perspective | FacingFlip => true,
        _ => rng.chance(0.6),
    };
    let mut cam = camera(rng, lens);
    if regime == FarFromOrigin {
        cam.cx = rng.sign() * rng.log_cornered(1e4, 1e6);
        cam.cy = rng.sign() * rng.log_cornered(1e4, 1e6);
    }
    let z = match regime {
        HugeCoc if rng.chance(0.5) => cam.focus * rng.log_cornered(0.05, 0.4),
        HugeCoc => (cam.focus * rng.log_cornered(3.0, 20.0)).min(500.0),
        _ => rng.log_cornered(0.5, 50.0),
    };
    // The CoC of depth z in pixels is fx R |1/F - 1/z|: choose it, then the radius.
    let coc_px = match regime {
        HugeCoc => Some((rng.log_cornered(1e2, 3e3), 50.0)),
        TinyCoc => Some((rng.log_cornered(1e-4, 0.3), 1.0)),
        _ => None,
    };
    if let Some((px, cap)) = coc_px {
        let per_radius = cam.fx * (1.0 / cam.focus - 1.0 / z).abs();
        cam.radius = (px / per_radius).min(cap);
    }
    // Size in camera units from a projected size in pixels.
    let px = match regime {
        Tiny => rng.log_cornered(1e-3, 1.0),
        Huge => rng.log_cornered(1e2, 1e5),
        _ => rng.log_cornered(1.0, 300.0),
    };
    let size = z * px / cam.fx;
    let centre = [rng.range(-0.3, 0.3) * z, rng.range(-0.3, 0.3) * z, z];
    let depth = size.min(0.4 * z);
    let mut q = [[0.0f32; 3]; 3];
    for p in q.iter_mut() {
        p[0] = centre[0] + rng.range(-1.0, 1.0) * size;
        p[1] = centre[1] + rng.range(-1.0, 1.0) * size;
        p[2] = centre[2] + rng.range(-1.0, 1.0) * depth;
    }
    if regime == ScreenParallel {
        for p in q.iter_mut() {
            p[2] = z;
        }
    }
    if regime == Degenerate && rng.chance(0.5) {
        degenerate(rng, &mut q);
        moving = moving && rng.chance(0.5);
    }
    let mut r = q;
    match regime {
        Perspective => {
            // every vertex's depth scaled 2..8-fold (towards or away), x and y moving too
            let ratio = rng.log_cornered(2.0, 8.0);
            let ratio = if rng.chance(0.5) { ratio } else { 1.0 / ratio };
            let m = size * rng.log_uniform(0.1, 10.0);
            let d = [rng.range(-1.0, 1.0) * m, rng.range(-1.0, 1.0) * m];
            for p in r.iter_mut() {
                p[0] = p[0] * ratio + d[0];
                p[1] = p[1] * ratio + d[1];
                p[2] *= ratio;
            }
        }
        FacingFlip => {
            // mirror the vertices' directions (x/z, y/z) about a line through their
            // centroid, each at its own depth: the image is mirrored, its winding flips
            let a = rng.range(0.0, std::f32::consts::PI);
            let (c, s) = (a.cos(), a.sin());
            let dir = q.map(|p| [p[0] / p[2], p[1] / p[2]]);
            let g = [(dir[0][0] + dir[1][0] + dir[2][0]) / 3.0, (dir[0][1] + dir[1][1] + dir[2][1]) / 3.0];
            for (p, d) in r.iter_mut().zip(dir) {
                let (dx, dy) = (d[0] - g[0], d[1] - g[1]);
                let along = dx * c + dy * s;
                p[0] = (g[0] + 2.0 * along * c - dx) * p[2];
                p[1] = (g[1] + 2.0 * along * s - dy) * p[2];
            }
            if rng.chance(0.5) {
                let m = size * rng.log_uniform(0.1, 3.0);
                move_rigidly(rng, &mut r, m, 0.25 * z);
            }
        }
        _ if moving => {
            let m = size * rng.log_cornered(0.1, 10.0);
            let depth_cap = if regime == ScreenParallel { 0.0 } else { 0.25 * z };
            move_rigidly(rng, &mut r, m, depth_cap);
        }
        _ => {}
    }
    if regime == Degenerate && moving && rng.chance(0.5) {
        // degenerate at the end of the shutter only
        degenerate(rng, &mut r);
    }
    Case { triangle: cam.triangle(q, r), lens: Some(cam) }
}

/// Make a triangle degenerate in place: two vertices equal, all three equal, or the
/// third on the segment between the first two (computed in f32, so it may sit an ulp
/// off the line: the exact oracle judges the case as it is).
fn degenerate(rng: &mut impl Source, q: &mut [[f32; 3]; 3]) {
    let kind = rng.range(0.0, 3.0);
    if kind < 1.0 {
        q[2] = q[0];
    } else if kind < 2.0 {
        q[1] = q[0];
        q[2] = q[0];
    } else {
        let f = rng.range(0.0, 1.0);
        let (a, b) = (q[0], q[1]);
        q[2] = std::array::from_fn(|j| a[j] + (b[j] - a[j]) * f);
    }
}

/// A wild triangle for robustness tests of the bounds (not a physical case): vertex
/// coordinates at one of nine scales from subnormal to 1e30 (`n % 9`), some exactly 0
/// or a whole multiple of the scale; `w` of either sign, exactly 0, tiny or spread over
/// seven decades; circles of confusion of one sign or mixed; the aspect factor from
/// `[1, 0.7, 1.3, 1e-3, 0, -1]` (`n % 6`), so zero and negative shears too.
pub fn wild_triangle(rng: &mut ChaCha8Rng, n: usize) -> Triangle {
    let scale = [1e-40f32, 1e-20, 1e-3, 1.0, 30.0, 1e3, 1e6, 1e15, 1e30][n % 9];
    let val = |rng: &mut ChaCha8Rng| -> f32 {
        match rng.gen_range(0..10) {
            0 => 0.0,
            1 => scale * rng.gen_range(-1..=1) as f32,
            _ => rng.gen_range(-1.0f32..1.0) * scale,
        }
    };
    let mut tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0]; 3]);
    for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
        p[0] = val(rng);
        p[1] = val(rng);
        p[3] = match rng.gen_range(0..6) {
            0 => 0.0,
            1 => rng.gen_range(-1e-6f32..1e-6),
            2 => rng.gen_range(-3.0f32..3.0),
            _ => rng.gen_range(0.01f32..4.0) * 10f32.powi(rng.gen_range(-3..4)),
        };
    }
    let one_sign = rng.gen_bool(0.5);
    for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
        *c = val(rng);
        if one_sign {
            *c = c.abs().max(1e-30);
        }
    }
    tri.k = [1.0f32, 0.7, 1.3, 1e-3, 0.0, -1.0][n % 6];
    tri
}

/// The special values [`bit_compare_case`] plants: NaN, both infinities, both zeros,
/// f32::MAX, the smallest subnormal and -1.
const SPECIAL: [f32; 8] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0, f32::MAX, 1e-45, -1.0];

/// A square tile near the origin or far from it (up to 1e6 px, by `n`), 1e-3 to 16 px.
fn stress_tile(rng: &mut ChaCha8Rng, n: usize) -> Tile {
    let far = [0.0f32, 1.0, 1e2, 1e4, 1e6];
    let x = rng.gen_range(-1.0f32..1.0) * far[n % 5];
    let y = rng.gen_range(-1.0f32..1.0) * far[(n / 5) % 5];
    Tile::square(x, y, [1e-3f32, 1.0, 4.0, 16.0][n % 4])
}

/// Plant a special value into one number of the triangle or the tile (or set a w to
/// a signed zero).
fn plant(rng: &mut ChaCha8Rng, tri: &mut Triangle, tile: &mut Tile) {
    let v = SPECIAL[rng.gen_range(0..SPECIAL.len())];
    match rng.gen_range(0..8) {
        0 => tri.q[rng.gen_range(0..3)][rng.gen_range(0..4)] = v,
        1 => tri.r[rng.gen_range(0..3)][rng.gen_range(0..4)] = v,
        2 => tri.c0[rng.gen_range(0..3)] = v,
        3 => tri.c1[rng.gen_range(0..3)] = v,
        4 => tri.k = v,
        5 => tile.x0 = v,
        6 => tile.y1 = v,
        _ => tri.q[rng.gen_range(0..3)][3] = if rng.gen_bool(0.5) { 0.0 } else { -0.0 },
    }
}

/// Case `n` of a stress stream for comparing two implementations of a bound bit for
/// bit: a triangle and two tiles. A third are physical cases (regime `n / 3` in turn)
/// with a tile on the footprint's boundary and one beside it, a third wild triangles
/// ([`wild_triangle`]) with two tiles near the origin or far from it, and a third the
/// same with a special value (NaN, an infinity, a signed zero, f32::MAX, a subnormal)
/// planted in one number of the triangle or the tile.
pub fn bit_compare_case(seed: u64, n: usize) -> (Triangle, Vec<Tile>) {
    let mut rng = rng_for(seed, n as u64);
    match n % 3 {
        0 => {
            let case = physical_case(&mut rng, Regime::ALL[(n / 3) % Regime::ALL.len()]);
            let size = tile_size(None, &mut rng);
            let t = boundary_tile(&case, &mut rng, size);
            let beside = Tile::square(t.x0 + size * rng.gen_range(-3..=3) as f32, t.y0 + size, size);
            (case.triangle, vec![t, beside])
        }
        1 => {
            let tri = wild_triangle(&mut rng, n / 3);
            (tri, vec![stress_tile(&mut rng, n / 3), stress_tile(&mut rng, n / 3 + 7)])
        }
        _ => {
            let mut tri = wild_triangle(&mut rng, n / 3);
            let mut tile = stress_tile(&mut rng, n / 3);
            plant(&mut rng, &mut tri, &mut tile);
            let other = stress_tile(&mut rng, n / 3 + 3);
            (tri, vec![tile, other])
        }
    }
}

/// A uniform sample with (x, y) in the tile, over the whole lens and shutter. Total on
/// every finite tile, even one wider than `f32::MAX` (see `coordinate`).
pub fn tile_sample(rng: &mut ChaCha8Rng, tile: &Tile) -> Sample {
    Sample::new(
        coordinate(rng, tile.x0, tile.x1),
        coordinate(rng, tile.y0, tile.y1),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(0.0..=1.0),
    )
}

/// Uniform in `[lo, hi]` (finite ends). `rand` panics on a range whose width, divided
/// by its largest unit draw `1 - f32::EPSILON`, overflows f32 (a tile from -f32::MAX to
/// f32::MAX, or from 0 to f32::MAX): such a range is drawn in f64, where the width of
/// any two f32 values is finite, as `lo (1 - u) + hi u`, rounded back into `[lo, hi]`.
/// Every other range takes the draw it always took (runs repeat bit for bit). Ends in
/// the wrong order are swapped; a non-finite end gives a non-finite coordinate (no
/// tile has one: tiles are validated).
fn coordinate(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    if ((hi - lo) / (1.0 - f32::EPSILON)).is_finite() {
        return rng.gen_range(lo..=hi);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return lo + hi;
    }
    let u: f64 = rng.gen_range(0.0..=1.0);
    let x = lo as f64 * (1.0 - u) + hi as f64 * u;
    (x as f32).clamp(lo, hi)
}

/// Samples for a case: half uniform over the triangle's screen region, half drawn near
/// its edges (a point on an edge of the sheared triangle at a random (u, v, t), pushed
/// off by 2^-e pixels, e uniform in [0, 40]). Rounded to f32 as hardware samples are.
/// A tile size in pixels: `fixed`, or drawn from 1, 2, 4, 8, 16.
pub fn tile_size(fixed: Option<f32>, rng: &mut ChaCha8Rng) -> f32 {
    use rand::seq::SliceRandom;
    fixed.unwrap_or_else(|| *[1.0f32, 2.0, 4.0, 8.0, 16.0].choose(rng).expect("five sizes"))
}

/// A tile of `size` pixels (on the grid of that size) holding a sample drawn near an
/// edge of the triangle ([`samples_for`]): where its footprint's boundary is. The
/// gate's cases ([`crate::cases::make_case`]) and the stability sweeps place tiles this way.
pub fn boundary_tile(case: &Case, rng: &mut ChaCha8Rng, size: f32) -> Tile {
    let pts = samples_for(case, rng, 16);
    // odd indices are the edge-biased samples
    let p = pts[1 + 2 * rng.gen_range(0..8)];
    let (x0, y0) = ((p[0] as f32 / size).floor() * size, (p[1] as f32 / size).floor() * size);
    Tile::square(x0, y0, size)
}

pub fn samples_for(case: &Case, rng: &mut ChaCha8Rng, n: usize) -> Vec<[f64; 5]> {
    let tri = &case.triangle;
    let dims = tri.dims();
    let (lens, time) = (dims.has_lens(), dims.has_time());
    // Screen region: projected vertices over both shutter ends and lens corners.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for tt in [0.0f32, 1.0] {
        for (uu, vv) in [(-1.0f32, -1.0f32), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            for i in 0..3 {
                let p = tri.at(i, tt);
                let c = tri.coc(i, tt);
                if p[3] > 0.0 {
                    let px = ((p[0] + uu * c) / p[3]) as f64;
                    let py = ((p[1] + tri.k * vv * c) / p[3]) as f64;
                    x0 = x0.min(px);
                    x1 = x1.max(px);
                    y0 = y0.min(py);
                    y1 = y1.max(py);
                }
            }
        }
    }
    if !(x0.is_finite() && x1.is_finite() && y0.is_finite() && y1.is_finite()) || x1 - x0 > 1e5 || y1 - y0 > 1e5 {
        (x0, x1, y0, y1) = (-2000.0, 2000.0, -2000.0, 2000.0);
    }
    let pad = 0.1 * (x1 - x0).max(y1 - y0) + 1.0;
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let u = if lens { rng.gen_range(-1.0f32..=1.0) } else { 0.0 };
        let v = if lens { rng.gen_range(-1.0f32..=1.0) } else { 0.0 };
        let t = if time { rng.gen_range(0.0f32..=1.0) } else { 0.0 };
        let (x, y) = if out.len() % 2 == 0 {
            (rng.gen_range(x0 - pad..=x1 + pad), rng.gen_range(y0 - pad..=y1 + pad))
        } else {
            let i = rng.gen_range(0..3);
            let j = (i + 1) % 3;
            let proj = |k: usize| {
                let p = tri.at(k, t);
                let c = tri.coc(k, t);
                ((p[0] + u * c) as f64 / p[3] as f64, (p[1] + tri.k * v * c) as f64 / p[3] as f64, p[3])
            };
            let (ax, ay, aw) = proj(i);
            let (bx, by, bw) = proj(j);
            if !(aw > 0.0 && bw > 0.0) {
                continue;
            }
            let f: f64 = rng.gen_range(0.0..=1.0);
            let off = 2f64.powf(-rng.gen_range(0.0..40.0)) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            let (dx, dy) = (by - ay, -(bx - ax));
            let len = (dx * dx + dy * dy).sqrt().max(1e-300);
            (ax + f * (bx - ax) + off * dx / len, ay + f * (by - ay) + off * dy / len)
        };
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        out.push([x as f32 as f64, y as f32 as f64, u as f64, v as f64, t as f64]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Dims;

    fn cases(regime: Regime, n: u64) -> Vec<Case> {
        (0..n).map(|i| physical_case(&mut rng_for(5, i), regime)).collect()
    }

    /// Pinhole screen position of vertex i at time t (None behind the lens).
    fn screen(c: &Case, i: usize, t: f32) -> Option<(f64, f64)> {
        let p = c.triangle.at(i, t);
        (p[3] > 0.0).then(|| (p[0] as f64 / p[3] as f64, p[1] as f64 / p[3] as f64))
    }

    fn extent(c: &Case, t: f32) -> Option<f64> {
        let ps: Option<Vec<_>> = (0..3).map(|i| screen(c, i, t)).collect();
        let ps = ps?;
        let span = |f: fn(&(f64, f64)) -> f64| {
            let v: Vec<f64> = ps.iter().map(f).collect();
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
        };
        Some(span(|p| p.0).max(span(|p| p.1)))
    }

    fn area(c: &Case, t: f32) -> Option<f64> {
        let (a, b, d) = (screen(c, 0, t)?, screen(c, 1, t)?, screen(c, 2, t)?);
        Some((b.0 - a.0) * (d.1 - a.1) - (b.1 - a.1) * (d.0 - a.0))
    }

    fn coc_px(c: &Case, i: usize) -> f64 {
        let t = &c.triangle;
        (t.c0[i] as f64 / t.q[i][3] as f64).abs()
    }

    fn median(mut v: Vec<f64>) -> f64 {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    }

    #[test]
    fn every_regime_gives_valid_cases_in_its_dimensions() {
        for r in Regime::ALL {
            let cs = cases(r, 200);
            for c in &cs {
                c.validate().unwrap_or_else(|e| panic!("{}: {e}", r.name()));
            }
            let dims: Vec<Dims> = cs.iter().map(|c| c.triangle.dims()).collect();
            let only = |d: Dims| dims.iter().all(|&x| x == d);
            match r {
                Regime::Static => assert!(only(Dims::Static)),
                Regime::Motion => assert!(only(Dims::Motion)),
                Regime::Defocus => assert!(only(Dims::Defocus)),
                Regime::Both => assert!(only(Dims::Both)),
                Regime::Perspective | Regime::FacingFlip => assert!(dims.iter().all(|d| d.has_time())),
                Regime::HugeCoc | Regime::TinyCoc => assert!(dims.iter().all(|d| d.has_lens())),
                // The stress regimes mix static, motion-only, defocus-only and both.
                Regime::Tiny | Regime::Huge | Regime::FarFromOrigin | Regime::Degenerate | Regime::ScreenParallel => {
                    for d in [Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both] {
                        assert!(dims.contains(&d), "{}: no {} case in 200", r.name(), d.name());
                    }
                }
                _ => {}
            }
        }
    }

    #[test]
    fn stress_regimes_have_their_property() {
        let e0 = |r| cases(r, 200).iter().filter_map(|c| extent(c, 0.0)).collect::<Vec<_>>();
        let tiny = e0(Regime::Tiny);
        assert!(tiny.iter().all(|&e| e < 3.0) && median(tiny) < 0.3);
        let huge = e0(Regime::Huge);
        let (lo, mid) = (huge.iter().cloned().fold(f64::MAX, f64::min), median(huge));
        assert!(lo > 10.0 && mid > 1e3, "huge: smallest extent {lo}, median {mid}");
        for c in cases(Regime::Huge, 200) {
            assert!((0..3).all(|i| c.triangle.q[i][3] > 0.0 && c.triangle.r[i][3] > 0.0));
        }
        for c in cases(Regime::Perspective, 200) {
            for i in 0..3 {
                let ratio = c.triangle.r[i][3] / c.triangle.q[i][3];
                let f = ratio.max(1.0 / ratio);
                assert!((1.999..=8.001).contains(&f), "depth ratio {ratio}");
            }
        }
        let flips = cases(Regime::FacingFlip, 200)
            .iter()
            .filter(|c| matches!((area(c, 0.0), area(c, 1.0)), (Some(a), Some(b)) if a * b < 0.0))
            .count();
        assert!(flips >= 190, "only {flips} of 200 facing-flip cases turn over");
        let huge_coc: Vec<f64> = cases(Regime::HugeCoc, 200).iter().map(|c| coc_px(c, 0).max(coc_px(c, 1))).collect();
        assert!(median(huge_coc) > 100.0);
        let tiny_coc: Vec<f64> = cases(Regime::TinyCoc, 200).iter().map(|c| coc_px(c, 0)).collect();
        assert!(median(tiny_coc.clone()) < 0.3 && tiny_coc.iter().all(|&x| x > 0.0));
        for c in cases(Regime::FarFromOrigin, 200) {
            let (x, y) = screen(&c, 0, 0.0).unwrap();
            assert!(x.abs() > 5e3 && y.abs() > 5e3, "({x}, {y}) is near the origin");
        }
        let flat = cases(Regime::Degenerate, 200)
            .iter()
            .filter(|c| {
                [0.0, 1.0].iter().any(|&t| match (area(c, t), extent(c, t)) {
                    (Some(a), Some(e)) => a.abs() <= 1e-4 * e * e,
                    _ => false,
                })
            })
            .count();
        assert!(
            flat >= 100,
            "only {flat} of 200 degenerate cases have an area below 1e-4 of their squared extent at a shutter end"
        );
        for c in cases(Regime::ScreenParallel, 200) {
            let t = &c.triangle;
            assert!((0..3).all(|i| t.q[i][3] == t.q[0][3] && t.r[i][3] == t.q[0][3] && t.q[i][2] == t.q[0][2]));
        }
    }

    #[test]
    fn a_tape_builds_the_same_case_twice_and_zeros_give_a_plain_one() {
        for r in Regime::ALL {
            let v: Vec<f64> = (0..strategy::TAPE_LEN).map(|i| (i as f64 * 0.618034).fract()).collect();
            let a = physical_case(&mut Tape::new(v.clone()), r);
            let b = physical_case(&mut Tape::new(v), r);
            assert_eq!(a, b);
            a.validate().unwrap();
            let z = physical_case(&mut Tape::new(vec![0.0; strategy::TAPE_LEN]), r);
            z.validate().unwrap_or_else(|e| panic!("{}: {e}", r.name()));
        }
    }

    #[test]
    fn tile_samples_are_drawn_on_every_finite_tile() {
        let mut rng = rng_for(3, 0);
        let m = f32::MAX;
        for (x0, x1) in [(-m, m), (0.0, m), (-m, 0.0), (m.next_down(), m), (-m, -m / 2.0), (-1e38, 3e38)] {
            let tile = Tile { x0, y0: -m, x1, y1: m };
            for _ in 0..200 {
                let s = tile_sample(&mut rng, &tile);
                assert!(s.x.is_finite() && x0 <= s.x && s.x <= x1, "{x0} {x1}: {}", s.x);
                assert!(s.y.is_finite(), "{}", s.y);
            }
        }
        // The two ends are reached in the wide form (not only one half of the range).
        let xs: Vec<f32> = (0..400).map(|_| coordinate(&mut rng, -m, m)).collect();
        assert!(xs.iter().any(|&x| x < -1e38) && xs.iter().any(|&x| x > 1e38));
        // An ordinary tile draws what it always drew.
        let tile = Tile::square(3.0, 5.0, 4.0);
        let (mut a, mut b) = (rng_for(9, 1), rng_for(9, 1));
        assert_eq!(tile_sample(&mut a, &tile).x, b.gen_range(3.0f32..=7.0));
    }
}
