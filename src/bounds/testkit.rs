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

pub(crate) use crate::gen::tile_sample as random_sample;

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
