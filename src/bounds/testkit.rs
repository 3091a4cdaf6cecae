//! Test support shared by the method files (test builds only): the exact oracle's
//! verdict on a sample, uniform samples in a tile, and the spot checks every method
//! runs against the exact oracle.

use super::{Method, Prepared, TileBounds, TileResult};
use crate::model::{Sample, Tile, Triangle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// True if the exact oracle says the sample is interior-covered.
pub(crate) fn covered(tri: &Triangle, s: &Sample) -> bool {
    oracles::classify(&tri.to_oracle(), s.to_oracle()) == oracles::Coverage::Interior
}

pub(crate) use crate::cases::generate::tile_sample as random_sample;

/// The method's answer for one tile; None when the tile is culled.
pub(crate) fn bounds_of(m: &dyn Method, tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    match m.setup(tri).tile(tile) {
        TileResult::Empty => None,
        TileResult::Bounds(b) => Some(b),
    }
}

/// What a spot check saw.
pub(crate) struct Spot {
    /// Interior-covered samples drawn.
    pub covered: usize,
    /// Samples the bounds let through.
    pub admitted: usize,
    /// Covered samples the bounds reject: each one is a violation.
    pub culled: Vec<Sample>,
}

/// `n` uniform samples in the tile (seeded), judged against the tile answer `res`
/// (None = tile culled) by the exact oracle. Depth bounds are not judged here.
pub(crate) fn spot(res: Option<&TileBounds>, tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> Spot {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Spot { covered: 0, admitted: 0, culled: Vec::new() };
    for _ in 0..n {
        let s = random_sample(&mut rng, tile);
        let ok = res.is_some_and(|b| b.admits(&s));
        out.admitted += ok as usize;
        if covered(tri, &s) {
            out.covered += 1;
            if !ok {
                out.culled.push(s);
            }
        }
    }
    out
}

/// [`spot`] for a method, failing the test on the first covered sample it culls.
/// Returns (covered, admitted).
pub(crate) fn assert_spot(m: &dyn Method, tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> (usize, usize) {
    let res = bounds_of(m, tri, tile);
    let r = spot(res.as_ref(), tri, tile, n, seed);
    assert!(r.culled.is_empty(), "{tri:?}\ntile {tile:?}: covered sample {:?} rejected by {res:?}", r.culled.first());
    (r.covered, r.admitted)
}

/// Samples just outside each per-tile interval edge and just on the culled side of
/// each constraint (moved along u or v onto its zero, then past it): none may be
/// interior-covered. Returns (samples tried, covered samples culled).
pub(crate) fn near_miss_check(
    p: &dyn Prepared,
    tri: &Triangle,
    tile: &Tile,
    n: usize,
    seed: u64,
) -> (usize, Vec<Sample>) {
    let TileResult::Bounds(b) = p.tile(tile) else {
        return (0, Vec::new());
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut tried, mut bad) = (0, Vec::new());
    let mut probe = |s: Sample, bad: &mut Vec<Sample>| {
        if (-1.0..=1.0).contains(&s.u) && (-1.0..=1.0).contains(&s.v) && (0.0..=1.0).contains(&s.t) && !b.admits(&s) {
            tried += 1;
            if covered(tri, &s) {
                bad.push(s);
            }
        }
    };
    for _ in 0..n {
        let s = random_sample(&mut rng, tile);
        let d: f32 = rng.gen_range(1e-6..0.02);
        for (lo, hi, set) in [
            (b.u[0], b.u[1], (|s: &mut Sample, x: f32| s.u = x) as fn(&mut Sample, f32)),
            (b.v[0], b.v[1], |s: &mut Sample, x: f32| s.v = x),
            (b.t[0], b.t[1], |s: &mut Sample, x: f32| s.t = x),
        ] {
            for x in [lo - d, hi + d] {
                let mut s2 = s;
                set(&mut s2, x);
                probe(s2, &mut bad);
            }
        }
        for c in &b.constraints {
            for along_v in [false, true] {
                let at = |x: f32| {
                    let mut s2 = s;
                    if along_v {
                        s2.v = x
                    } else {
                        s2.u = x
                    }
                    s2
                };
                let (g0, g1) = (c.eval(&at(0.0)), c.eval(&at(1.0)));
                let slope = g1 - g0;
                let usable = slope.abs() > 1e-3 * (g0.abs() + g1.abs());
                if !usable {
                    continue;
                }
                let root = -g0 / slope;
                probe(at(root - d * slope.signum()), &mut bad);
            }
        }
    }
    (tried, bad)
}

/// [`spot`] on a prepared test: (covered samples, covered samples it culls).
pub(crate) fn spot_check(p: &dyn Prepared, tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> (usize, Vec<Sample>) {
    let res = match p.tile(tile) {
        TileResult::Empty => None,
        TileResult::Bounds(b) => Some(b),
    };
    let r = spot(res.as_ref(), tri, tile, n, seed);
    (r.covered, r.culled)
}

/// Every value `eval` returns for f32 samples drawn in random sub-boxes of the tile
/// (over the whole lens and shutter) lies in the constraint's `eval_box` enclosure.
pub(crate) fn assert_eval_box_encloses(b: &TileBounds, tile: &Tile, seed: u64) {
    use crate::bounds::SampleBox;
    use crate::Interval;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..2000 {
        let mut iv = |lo: f32, hi: f32| {
            let (a, c) = (rng.gen_range(lo..=hi), rng.gen_range(lo..=hi));
            Interval::new(a.min(c) as f64, a.max(c) as f64)
        };
        let bx = SampleBox {
            x: iv(tile.x0, tile.x1),
            y: iv(tile.y0, tile.y1),
            u: iv(-1.0, 1.0),
            v: iv(-1.0, 1.0),
            t: iv(0.0, 1.0),
        };
        for c in &b.constraints {
            let e = c.eval_box(&bx);
            for _ in 0..10 {
                let mut pick = |i: Interval| rng.gen_range(i.lo as f32..=i.hi as f32);
                let s = Sample::new(pick(bx.x), pick(bx.y), pick(bx.u), pick(bx.v), pick(bx.t));
                let g = c.eval(&s) as f64;
                assert!(e.contains(g), "{} {g} not in {e:?}", c.name());
            }
        }
    }
}

/// Triangle `n` of the random stress set of the dual-space tests: moving, defocused,
/// every fifth with a vertex that may sit at w <= 0, every seventh with zero CoC, any
/// aspect k; and a tile of 0.5, 2 or 6 px near one projected vertex.
pub(crate) fn random_dual_case(rng: &mut ChaCha8Rng, n: usize) -> (Triangle, Tile) {
    let mut v = || {
        let w: f32 = if n.is_multiple_of(5) { rng.gen_range(-0.5..3.0) } else { rng.gen_range(0.5..3.0) };
        [rng.gen_range(-8.0..8.0) * w.abs().max(0.3), rng.gen_range(-8.0..8.0) * w.abs().max(0.3), 0.5, w]
    };
    let q = [v(), v(), v()];
    let r = [v(), v(), v()];
    let mut c = || {
        if n.is_multiple_of(7) {
            0.0
        } else {
            rng.gen_range(-4.0..4.0)
        }
    };
    let tri = Triangle { q, r, c0: [c(), c(), c()], c1: [c(), c(), c()], k: rng.gen_range(0.5..2.0) };
    let i = rng.gen_range(0..3);
    let (cx, cy) = if q[i][3] > 0.1 { (q[i][0] / q[i][3], q[i][1] / q[i][3]) } else { (0.0, 0.0) };
    let size = [0.5f32, 2.0, 6.0][n % 3];
    let tile = Tile::square(cx - size * 0.5 + rng.gen_range(-2.0..2.0), cy - size * 0.5, size);
    (tri, tile)
}

/// A method must answer degenerate and huge input without panicking, with ordered
/// intervals inside the domain and constraints that can be evaluated: a zero triangle,
/// and `tri` with one vertex at +-3e38 (w = 1e-30) and extreme CoCs, on an ordinary
/// and on a huge tile.
pub(crate) fn assert_degenerate_input_is_answered(m: &dyn Method, tri: &Triangle) {
    let z = Triangle { q: [[0.0; 4]; 3], r: [[0.0; 4]; 3], c0: [0.0; 3], c1: [0.0; 3], k: 0.0 };
    assert_answered_in_domain(m.setup(&z).as_ref(), &[Tile::square(0.0, 0.0, 1.0)]);
    let mut t = *tri;
    t.q[0] = [3.0e38, -3.0e38, 0.5, 1.0e-30];
    t.c0[1] = 3.0e38;
    t.c1[2] = -3.0e38;
    assert_answered_in_domain(m.setup(&t).as_ref(), &[Tile::square(0.0, 0.0, 1.0), Tile::square(-1e30, 1e30, 1e20)]);
}

/// Every tile gets an answer (no panic): empty, or ordered intervals inside
/// [-1, 1]^2 x [0, 1] whose per-sample test answers too.
pub(crate) fn assert_answered_in_domain(p: &dyn Prepared, tiles: &[Tile]) {
    for tile in tiles {
        if let TileResult::Bounds(b) = p.tile(tile) {
            assert!(b.u[0] <= b.u[1] && b.v[0] <= b.v[1] && b.t[0] <= b.t[1], "{tile:?}: {b:?}");
            assert!(b.u[0] >= -1.0 && b.u[1] <= 1.0 && b.v[0] >= -1.0 && b.v[1] <= 1.0, "{tile:?}: {b:?}");
            assert!(b.t[0] >= 0.0 && b.t[1] <= 1.0, "{tile:?}: {b:?}");
            let _ = b.admits(&Sample::new(0.0, 0.0, 0.0, 0.0, 0.5));
        }
    }
}

/// Both checks on one prepared triangle and tile, failing with `what` and the first
/// culled covered sample: `n` uniform samples ([`spot_check`], seed `seed`) and `near`
/// samples just beyond each bound ([`near_miss_check`], seed `seed + 1`). Returns
/// (covered samples seen, near-miss samples tried).
pub(crate) fn assert_keeps_covered(
    p: &dyn Prepared,
    tri: &Triangle,
    tile: &Tile,
    (n, near): (usize, usize),
    seed: u64,
    what: &str,
) -> (usize, usize) {
    let (cov, bad) = spot_check(p, tri, tile, n, seed);
    assert!(bad.is_empty(), "{what} {tri:?} tile {tile:?}: {} covered samples culled, first {:?}", bad.len(), bad[0]);
    let (tried, bad) = near_miss_check(p, tri, tile, near, seed + 1);
    assert!(bad.is_empty(), "{what} {tri:?} tile {tile:?}: covered sample culled near a bound {:?}", bad[0]);
    (cov, tried)
}

/// A thin lens of the random-triangle tests: 100 x 110 px focal scale, centre (32, 32),
/// focus depth in [2, 10), lens radius in [0, 0.3) (0: a pinhole).
pub(crate) fn random_lens(rng: &mut ChaCha8Rng) -> crate::model::ThinLens {
    let focus = rng.gen_range(2.0f32..10.0);
    crate::model::ThinLens {
        fx: 100.0,
        fy: 110.0,
        cx: 32.0,
        cy: 32.0,
        radius: rng.gen_range(0.0..0.3),
        focus,
        near: 0.5,
        far: 50.0,
    }
}

/// A fingerprint of a stream of answers: FNV-1a (64 bits) over each answer's text,
/// with a separator after each. The bit-identity tests compare the stream's
/// fingerprint with the one recorded when the code was restructured, so any changed
/// bit of any answer on the stream (a value, a sign of zero, a constraint) changes it.
pub struct Fingerprint(u64);

impl Fingerprint {
    pub fn new() -> Self {
        Fingerprint(0xcbf2_9ce4_8422_2325)
    }
    pub fn add(&mut self, answer: &str) {
        for b in answer.bytes().chain([0xff]) {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
    pub fn value(&self) -> u64 {
        self.0
    }
}
