//! Sample patterns: `spp` samples per pixel, each `(x, y, u, v, t)` with x in
//! `[px, px + 1)`, y in `[py, py + 1)`, u and v in `[-1, 1)`, t in `[0, 1)`, stored in
//! f32 as a hardware sample pattern would be (a value that f32 rounding would push onto
//! the upper end of its cell is moved one ulp down, so every sample stays in its pixel
//! and stratum).
//!
//! Every pixel's samples depend only on (seed, pixel, kind, spp): the pattern is a
//! property of the framebuffer, the same for every triangle, method and thread count.
//!
//! - [`PatternKind::Uniform`]: every coordinate independent and uniform (a `ChaCha8Rng`
//!   per pixel).
//! - [`PatternKind::Stratified`]: (x, y) jittered on an `a x b` grid of the pixel with
//!   `a * b = spp` (as square as spp allows), (u, v) jittered on the same grid shape
//!   over the lens square, t jittered in `spp` equal strata; the three stratifications
//!   are paired by two random permutations (so every xy cell, every uv cell and every t
//!   stratum holds exactly one sample).
//! - [`PatternKind::Sobol`]: the first `spp` points of the 5D Sobol sequence (direction
//!   numbers of Joe & Kuo 2008 for dimensions 2 to 5), each coordinate Owen-scrambled
//!   (nested uniform scrambling: each bit flipped by a hash of the seed, the pixel, the
//!   dimension and all higher bits) with a per-pixel seed. For spp a power of two every
//!   coordinate holds one sample per 1/spp stratum, and (x, y) form a (0, m, 2)-net.

use crate::model::Sample;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Which pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum PatternKind {
    /// Independent uniform coordinates.
    Uniform,
    /// Jittered strata in (x, y), in (u, v) and in t, paired by random permutations.
    Stratified,
    /// Owen-scrambled 5D Sobol points, scrambled per pixel.
    Sobol,
}

impl PatternKind {
    pub fn name(self) -> &'static str {
        match self {
            PatternKind::Uniform => "uniform",
            PatternKind::Stratified => "stratified",
            PatternKind::Sobol => "sobol",
        }
    }
}

/// A seeded per-pixel sample pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Pattern {
    pub kind: PatternKind,
    pub spp: u32,
    pub seed: u64,
}

/// SplitMix64's finaliser: a bijective 64-bit mix.
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A hash of several words (order matters).
pub(crate) fn hash(words: &[u64]) -> u64 {
    words.iter().fold(0x243F_6A88_85A3_08D3u64, |h, &w| mix64(h ^ mix64(w.wrapping_add(0x9E37_79B9_7F4A_7C15))))
}

/// `lo + f * width` in f32, kept inside `[lo, lo + width)` (f in [0, 1)).
fn in_cell(lo: f64, width: f64, f: f64) -> f32 {
    let hi = lo + width;
    let mut x = (lo + f * width) as f32;
    while x as f64 >= hi {
        x = x.next_down();
    }
    while (x as f64) < lo {
        x = x.next_up();
    }
    x
}

/// The grid `a x b` (a <= b, a * b = n) closest to square.
pub fn grid_shape(n: u32) -> (u32, u32) {
    let n = n.max(1);
    let mut a = (n as f64).sqrt().floor() as u32;
    while a > 1 && !n.is_multiple_of(a) {
        a -= 1;
    }
    let a = a.max(1);
    (a, n / a)
}

/// Owen scrambling of a 32-bit fixed-point fraction: bit k (from the top) is flipped
/// by one bit of a hash of the seed, the level k and the bits above it; the lowest 8
/// bits (below f32 resolution) are replaced by hash bits.
fn owen(x: u32, seed: u64) -> u32 {
    let mut out = 0u32;
    for level in 0..24u32 {
        let bit = 31 - level;
        let prefix = if level == 0 { 0 } else { (x >> (bit + 1)) as u64 };
        let flip = (hash(&[seed, level as u64, prefix]) & 1) as u32;
        out |= (((x >> bit) & 1) ^ flip) << bit;
    }
    out | (hash(&[seed, 99, (x >> 8) as u64]) as u32 & 0xFF)
}

/// Direction numbers of the first five Sobol dimensions: `v[d][k]` for bit k (0 = the
/// most significant). Dimension 1 is van der Corput; dimensions 2-5 use
/// (s, a, m) = (1, 0, [1]), (2, 1, [1, 3]), (3, 1, [1, 3, 1]), (3, 2, [1, 1, 1]).
fn sobol_directions() -> [[u32; 32]; 5] {
    let params: [(usize, u32, &[u32]); 4] = [(1, 0, &[1]), (2, 1, &[1, 3]), (3, 1, &[1, 3, 1]), (3, 2, &[1, 1, 1])];
    let mut v = [[0u32; 32]; 5];
    for (k, x) in v[0].iter_mut().enumerate() {
        *x = 1u32 << (31 - k);
    }
    for (d, &(s, a, m0)) in params.iter().enumerate() {
        // m_k (1-based k), as u64 to keep the shifts simple.
        let mut m = vec![0u64; 33];
        for (i, &mi) in m0.iter().enumerate() {
            m[i + 1] = mi as u64;
        }
        for k in s + 1..=32 {
            let mut mk = m[k - s] ^ (m[k - s] << s);
            for j in 1..s {
                // a's bits, a_1 the most significant of its s - 1 bits.
                let aj = (a >> (s - 1 - j)) & 1;
                if aj == 1 {
                    mk ^= m[k - j] << j;
                }
            }
            m[k] = mk;
        }
        for k in 1..=32 {
            v[d + 1][k - 1] = (m[k] << (32 - k)) as u32;
        }
    }
    v
}

/// Point `i` of the (unscrambled) 5D Sobol sequence as 32-bit fractions.
fn sobol_point(dirs: &[[u32; 32]; 5], i: u32) -> [u32; 5] {
    let mut out = [0u32; 5];
    for (d, o) in out.iter_mut().enumerate() {
        let mut x = 0u32;
        let mut idx = i;
        let mut k = 0;
        while idx != 0 {
            if idx & 1 == 1 {
                x ^= dirs[d][k];
            }
            idx >>= 1;
            k += 1;
        }
        *o = x;
    }
    out
}

fn to_unit(x: u32) -> f64 {
    x as f64 / 4_294_967_296.0
}

impl Pattern {
    pub fn new(kind: PatternKind, spp: u32, seed: u64) -> Self {
        Pattern { kind, spp: spp.max(1), seed }
    }

    /// Appends the `spp` samples of pixel `(px, py)` to `out`.
    pub fn pixel(&self, px: u32, py: u32, out: &mut Vec<Sample>) {
        let key = hash(&[self.seed, self.kind as u64, self.spp as u64, px as u64, py as u64]);
        let (x0, y0) = (px as f64, py as f64);
        let n = self.spp;
        match self.kind {
            PatternKind::Uniform => {
                let mut rng = ChaCha8Rng::seed_from_u64(key);
                for _ in 0..n {
                    let mut f = || rng.gen::<f64>();
                    let (a, b, c, d, e) = (f(), f(), f(), f(), f());
                    out.push(Sample::new(
                        in_cell(x0, 1.0, a),
                        in_cell(y0, 1.0, b),
                        in_cell(-1.0, 2.0, c),
                        in_cell(-1.0, 2.0, d),
                        in_cell(0.0, 1.0, e),
                    ));
                }
            }
            PatternKind::Stratified => {
                let mut rng = ChaCha8Rng::seed_from_u64(key);
                let (a, b) = grid_shape(n);
                let mut uv: Vec<u32> = (0..n).collect();
                let mut ts: Vec<u32> = (0..n).collect();
                // Fisher-Yates, written out so the draw order is fixed here.
                for p in [&mut uv, &mut ts] {
                    for i in (1..p.len()).rev() {
                        let j = rng.gen_range(0..=i);
                        p.swap(i, j);
                    }
                }
                for i in 0..n {
                    let (cx, cy) = (i % a, i / a);
                    let (ux, uy) = (uv[i as usize] % a, uv[i as usize] / a);
                    let t = ts[i as usize];
                    let mut f = || rng.gen::<f64>();
                    let (j0, j1, j2, j3, j4) = (f(), f(), f(), f(), f());
                    out.push(Sample::new(
                        in_cell(x0 + cx as f64 / a as f64, 1.0 / a as f64, j0),
                        in_cell(y0 + cy as f64 / b as f64, 1.0 / b as f64, j1),
                        in_cell(-1.0 + 2.0 * ux as f64 / a as f64, 2.0 / a as f64, j2),
                        in_cell(-1.0 + 2.0 * uy as f64 / b as f64, 2.0 / b as f64, j3),
                        in_cell(t as f64 / n as f64, 1.0 / n as f64, j4),
                    ));
                }
            }
            PatternKind::Sobol => {
                let dirs = sobol_dirs();
                let seeds: [u64; 5] = std::array::from_fn(|d| hash(&[key, d as u64]));
                for i in 0..n {
                    let p = sobol_point(dirs, i);
                    let f: [f64; 5] = std::array::from_fn(|d| to_unit(owen(p[d], seeds[d])));
                    out.push(Sample::new(
                        in_cell(x0, 1.0, f[0]),
                        in_cell(y0, 1.0, f[1]),
                        in_cell(-1.0, 2.0, f[2]),
                        in_cell(-1.0, 2.0, f[3]),
                        in_cell(0.0, 1.0, f[4]),
                    ));
                }
            }
        }
    }

    /// The samples of every pixel of `[px0, px1] x [py0, py1]` (inclusive), row by row,
    /// `spp` per pixel.
    pub fn region(&self, px0: u32, py0: u32, px1: u32, py1: u32, out: &mut Vec<Sample>) {
        out.clear();
        if px1 < px0 || py1 < py0 {
            return;
        }
        out.reserve((px1 - px0 + 1) as usize * (py1 - py0 + 1) as usize * self.spp as usize);
        for py in py0..=py1 {
            for px in px0..=px1 {
                self.pixel(px, py, out);
            }
        }
    }
}

fn sobol_dirs() -> &'static [[u32; 32]; 5] {
    static DIRS: std::sync::OnceLock<[[u32; 32]; 5]> = std::sync::OnceLock::new();
    DIRS.get_or_init(sobol_directions)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples(kind: PatternKind, spp: u32, seed: u64, px: u32, py: u32) -> Vec<Sample> {
        let mut v = Vec::new();
        Pattern::new(kind, spp, seed).pixel(px, py, &mut v);
        v
    }

    const KINDS: [PatternKind; 3] = [PatternKind::Uniform, PatternKind::Stratified, PatternKind::Sobol];

    #[test]
    fn deterministic_per_seed_and_in_range() {
        for kind in KINDS {
            for spp in [1, 4, 7, 16] {
                let a = samples(kind, spp, 5, 17, 3);
                assert_eq!(a.len(), spp as usize);
                assert_eq!(a, samples(kind, spp, 5, 17, 3), "{kind:?} is not deterministic");
                assert_ne!(a, samples(kind, spp, 6, 17, 3), "{kind:?} ignores the seed");
                assert_ne!(a, samples(kind, spp, 5, 18, 3), "{kind:?} repeats across pixels");
                for s in &a {
                    assert!((17.0..18.0).contains(&s.x) && (3.0..4.0).contains(&s.y), "{kind:?} {s:?}");
                    assert!((-1.0..1.0).contains(&s.u) && (-1.0..1.0).contains(&s.v), "{kind:?} {s:?}");
                    assert!((0.0..1.0).contains(&s.t), "{kind:?} {s:?}");
                }
            }
        }
    }

    #[test]
    fn stratified_has_one_sample_per_stratum() {
        for spp in [1, 2, 4, 6, 8, 9, 16, 32] {
            let (a, b) = grid_shape(spp);
            assert_eq!(a * b, spp);
            for seed in 0..20 {
                let s = samples(PatternKind::Stratified, spp, seed, 40, 9);
                let mut xy = vec![0; spp as usize];
                let mut uv = vec![0; spp as usize];
                let mut t = vec![0; spp as usize];
                for p in &s {
                    let cx = ((p.x - 40.0) as f64 * a as f64).floor() as u32;
                    let cy = ((p.y - 9.0) as f64 * b as f64).floor() as u32;
                    xy[(cy * a + cx) as usize] += 1;
                    let ux = ((p.u as f64 + 1.0) * 0.5 * a as f64).floor() as u32;
                    let uy = ((p.v as f64 + 1.0) * 0.5 * b as f64).floor() as u32;
                    uv[(uy * a + ux) as usize] += 1;
                    t[(p.t as f64 * spp as f64).floor() as usize] += 1;
                }
                assert!(xy.iter().all(|&c| c == 1), "spp {spp} seed {seed}: xy cells {xy:?}");
                assert!(uv.iter().all(|&c| c == 1), "spp {spp} seed {seed}: uv cells {uv:?}");
                assert!(t.iter().all(|&c| c == 1), "spp {spp} seed {seed}: t strata {t:?}");
            }
        }
    }

    #[test]
    fn sobol_is_stratified_in_every_coordinate() {
        for spp in [2, 4, 8, 16, 64] {
            for seed in 0..10 {
                let s = samples(PatternKind::Sobol, spp, seed, 2, 2);
                let unit = |p: &Sample| {
                    [
                        (p.x - 2.0) as f64,
                        (p.y - 2.0) as f64,
                        (p.u as f64 + 1.0) / 2.0,
                        (p.v as f64 + 1.0) / 2.0,
                        p.t as f64,
                    ]
                };
                for d in 0..5 {
                    let mut cells = vec![0; spp as usize];
                    for p in &s {
                        cells[(unit(p)[d] * spp as f64).floor() as usize] += 1;
                    }
                    assert!(cells.iter().all(|&c| c == 1), "spp {spp} seed {seed} dim {d}: {cells:?}");
                }
                // (x, y): one point per 2x2 quadrant for spp = 4 (a (0, 2, 2)-net).
                if spp == 4 {
                    let mut q = [0; 4];
                    for p in &s {
                        let u = unit(p);
                        q[((u[0] * 2.0) as usize) + 2 * ((u[1] * 2.0) as usize)] += 1;
                    }
                    assert_eq!(q, [1; 4], "seed {seed}");
                }
            }
        }
    }

    #[test]
    fn sobol_directions_match_the_known_start() {
        // Dimension 2 (m = 1, 3, 5, ...): v = 1/2, 3/4, 5/8 -> 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
        let d = sobol_directions();
        let got: Vec<f64> = (0..8).map(|i| to_unit(sobol_point(&d, i)[1])).collect();
        assert_eq!(got, vec![0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875]);
        // Dimension 3 (s = 2, a = 1, m = 1, 3; m_3 = 2 m_2 ^ 4 m_1 ^ m_1 = 3): v = 1/2, 3/4,
        // 3/8 -> 0, 1/2, 3/4, 1/4, 3/8, 7/8, 5/8, 1/8.
        let got: Vec<f64> = (0..8).map(|i| to_unit(sobol_point(&d, i)[2])).collect();
        assert_eq!(got, vec![0.0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125]);
    }

    #[test]
    fn cells_never_round_onto_their_upper_end() {
        // 0.99999999 rounds to 1.0 in f32; the sample must stay below the pixel's end.
        let x = in_cell(1023.0, 1.0, 0.999_999_999);
        assert!((1023.0..1024.0).contains(&x));
        let u = in_cell(-1.0, 2.0, 0.999_999_999_9);
        assert!(u < 1.0);
    }
}
