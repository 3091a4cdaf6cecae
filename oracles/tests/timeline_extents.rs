//! Per-ray exact time spans against per-sample exact coverage, and certified tile
//! extents against dense sampling.

use oracles::extents::{tile_extents, ExtentsConfig};
use oracles::timeline::covered_spans;
use oracles::{classify, Coverage, Tri};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_tri(rng: &mut ChaCha8Rng, lens: bool, motion: bool) -> Tri {
    let mut v = || {
        let w: f64 = rng.gen_range(0.5..4.0);
        [rng.gen_range(-6.0..6.0) * w, rng.gen_range(-6.0..6.0) * w, rng.gen_range(0.0..1.0) * w, w]
    };
    let q = [v(), v(), v()];
    let mut r = q;
    if motion {
        for p in r.iter_mut() {
            let w: f64 = rng.gen_range(0.5..4.0);
            *p = [p[0] + rng.gen_range(-8.0..8.0) * w, p[1] + rng.gen_range(-8.0..8.0) * w, p[2], w];
        }
    }
    let mut c = || if lens { rng.gen_range(-3.0..3.0) } else { 0.0 };
    let c0 = [c(), c(), c()];
    let c1 = if motion { [c(), c(), c()] } else { c0 };
    // quantise to f32 like the model does
    let f = |x: f64| x as f32 as f64;
    Tri { q: q.map(|p| p.map(f)), r: r.map(|p| p.map(f)), c0: c0.map(f), c1: c1.map(f), k: 0.75 }
}

#[test]
fn ray_spans_agree_with_per_sample_coverage() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut covered_checked = 0;
    for case in 0..60 {
        let tri = random_tri(&mut rng, case % 2 == 0, true);
        for _ in 0..10 {
            let (x, y) = (rng.gen_range(-8.0..8.0), rng.gen_range(-8.0..8.0));
            let (u, v) = (rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0));
            let spans = covered_spans(&tri, x, y, u, v, 1e-12);
            for k in 0..200 {
                let t = (k as f64 + 0.5) / 200.0;
                let c = classify(&tri, [x, y, u, v, t]);
                let in_span = spans.iter().any(|s| s.start.hi < t && t < s.end.lo);
                let near_end =
                    spans.iter().any(|s| (s.start.lo <= t && t <= s.start.hi) || (s.end.lo <= t && t <= s.end.hi));
                if near_end {
                    continue; // inside an endpoint enclosure: either answer is consistent
                }
                assert_eq!(c == Coverage::Interior, in_span, "tri {tri:?} ray {x} {y} {u} {v} t {t} spans {spans:?}");
                covered_checked += in_span as u32;
            }
        }
    }
    assert!(covered_checked > 1000, "too few covered samples to mean anything: {covered_checked}");
}

#[test]
fn tile_extents_enclose_every_sampled_covered_sample() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let cfg = ExtentsConfig::default();
    let mut nonempty = 0;
    let mut empty = 0;
    for case in 0..40 {
        let (lens, motion) = [(false, false), (false, true), (true, false), (true, true)][case % 4];
        let tri = random_tri(&mut rng, lens, motion);
        let size = [1.0, 2.0, 4.0][case % 3];
        let (x0, y0) = (rng.gen_range(-6.0..4.0f64).floor(), rng.gen_range(-6.0..4.0f64).floor());
        let tile = [x0, x0 + size, y0, y0 + size];
        let ex = tile_extents(&tri, tile, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg);
        // every witness is interior, exactly
        for e in ex.extremes.iter().flatten() {
            assert_eq!(classify(&tri, e.witness), Coverage::Interior);
            assert!(e.lo <= e.hi);
        }
        let mut any = false;
        for _ in 0..20_000 {
            let s = [
                rng.gen_range(tile[0]..tile[1]),
                rng.gen_range(tile[2]..tile[3]),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(0.0..1.0),
            ];
            if classify(&tri, s) != Coverage::Interior {
                continue;
            }
            any = true;
            assert!(!ex.empty, "certified empty but {s:?} is covered");
            for (d, (lo, hi)) in [(2, ex.u()), (3, ex.v()), (4, ex.t())] {
                if let (Some(lo), Some(hi)) = (lo, hi) {
                    assert!(s[d] >= lo.lo && s[d] <= hi.hi, "coordinate {d} of {s:?} outside [{}, {}]", lo.lo, hi.hi);
                }
            }
            if let (Some(lo), Some(hi)) = ex.z() {
                let dc = oracles::classify_depth(&tri, s, lo.lo, hi.hi);
                assert_eq!(dc, oracles::DepthCheck::Inside, "depth of {s:?} outside [{}, {}]", lo.lo, hi.hi);
            }
        }
        if any {
            nonempty += 1;
            // within resolution of the witnesses (unless undecided boxes widened them)
            if ex.undecided == 0 {
                for e in ex.extremes.iter().flatten() {
                    assert!(e.hi - e.lo <= cfg.resolution, "{e:?}");
                }
            }
        } else if ex.empty {
            empty += 1;
        }
    }
    assert!(nonempty >= 10 && empty >= 1, "nonempty {nonempty} empty {empty}");
}
