//! The batch classification against the scalar oracle, sample by sample, on every
//! regime, on samples biased onto edges and vertices (down to exactly on them), at huge
//! and tiny scales, with w near 0 and with focal-plane crossings.

use super::*;
use crate::coverage::classify;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The regimes the generator draws from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    Static,
    Defocus,
    Motion,
    Both,
    FocalCrossing,
    WNearZero,
    BehindLens,
}

const SHAPES: [Shape; 7] = [
    Shape::Static,
    Shape::Defocus,
    Shape::Motion,
    Shape::Both,
    Shape::FocalCrossing,
    Shape::WNearZero,
    Shape::BehindLens,
];

/// A random triangle of a regime, all coordinates multiplied by `scale`.
fn tri_of(rng: &mut ChaCha8Rng, shape: Shape, scale: f64) -> Tri {
    let vert = |rng: &mut ChaCha8Rng| {
        let w = match shape {
            Shape::WNearZero => rng.gen_range(-1e-6..1e-6),
            Shape::BehindLens => rng.gen_range(-2.0..0.5),
            _ => rng.gen_range(0.2..2.0),
        };
        [rng.gen_range(-8.0..8.0) * w, rng.gen_range(-8.0..8.0) * w, rng.gen_range(-1.0..1.0), w]
    };
    let q = [vert(rng), vert(rng), vert(rng)];
    let moving = matches!(shape, Shape::Motion | Shape::Both | Shape::FocalCrossing | Shape::WNearZero);
    let r = if moving { q.map(|p| p.map(|c: f64| c + rng.gen_range(-0.5..0.5) * c.abs().max(0.1))) } else { q };
    let lens = matches!(shape, Shape::Defocus | Shape::Both | Shape::FocalCrossing | Shape::BehindLens);
    let c0: [f64; 3] = if lens { std::array::from_fn(|_| rng.gen_range(-1.0..1.0)) } else { [0.0; 3] };
    let c1 = match shape {
        Shape::FocalCrossing => c0.map(|c| -c * rng.gen_range(0.5..2.0)),
        Shape::Both => c0.map(|c| c + rng.gen_range(-0.3..0.3)),
        _ => c0,
    };
    let s = |p: [[f64; 4]; 3]| p.map(|v| v.map(|c| c * scale));
    Tri { q: s(q), r: s(r), c0: c0.map(|c| c * scale), c1: c1.map(|c| c * scale), k: rng.gen_range(0.5..2.0) }
}

/// The projected vertex i at (u, v, t), in f64 (only used to aim samples).
fn projected(tri: &Tri, i: usize, u: f64, v: f64, t: f64) -> (f64, f64) {
    let l = |j: usize| tri.q[i][j] + t * (tri.r[i][j] - tri.q[i][j]);
    let c = tri.c0[i] + t * (tri.c1[i] - tri.c0[i]);
    let w = l(3);
    ((l(0) + u * c) / w, (l(1) + tri.k * v * c) / w)
}

/// Samples: uniform over the projected region, and aimed at edges and vertices with
/// offsets from 1 down to 2^-60 of the edge length (and none at all).
fn samples_of(rng: &mut ChaCha8Rng, tri: &Tri, n: usize) -> Vec<[f64; 5]> {
    let lens = !tri.is_pinhole();
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let u = if lens { rng.gen_range(-1.0..=1.0) } else { 0.0 };
        let v = if lens { rng.gen_range(-1.0..=1.0) } else { 0.0 };
        let t = rng.gen_range(0.0..=1.0);
        let p = [0, 1, 2].map(|i| projected(tri, i, u, v, t));
        let (x, y) = match out.len() % 4 {
            0 => {
                let (mut x0, mut x1, mut y0, mut y1) = (p[0].0, p[0].0, p[0].1, p[0].1);
                for q in &p {
                    (x0, x1, y0, y1) = (x0.min(q.0), x1.max(q.0), y0.min(q.1), y1.max(q.1));
                }
                let (dx, dy) = (x1 - x0, y1 - y0);
                if !(dx.is_finite() && dy.is_finite()) || dx > 1e300 || dy > 1e300 {
                    continue;
                }
                (rng.gen_range(x0 - 0.1 * dx..=x1 + 0.1 * dx), rng.gen_range(y0 - 0.1 * dy..=y1 + 0.1 * dy))
            }
            1 => p[rng.gen_range(0..3)],
            _ => {
                let i = rng.gen_range(0..3);
                let (a, b) = (p[i], p[(i + 1) % 3]);
                let f: f64 = rng.gen_range(0.0..=1.0);
                let off = if rng.gen_bool(0.2) { 0.0 } else { 2f64.powf(-rng.gen_range(0.0..60.0)) };
                let off = if rng.gen_bool(0.5) { off } else { -off };
                let (dx, dy) = (b.1 - a.1, -(b.0 - a.0));
                (a.0 + f * (b.0 - a.0) + off * dx, a.1 + f * (b.1 - a.1) + off * dy)
            }
        };
        if x.is_finite() && y.is_finite() {
            let s = [x, y, u, v, t];
            // Every fourth biased sample rounded to f32, as the rasterizer's samples are.
            out.push(if rng.gen_bool(0.25) { s.map(|c| c as f32 as f64) } else { s });
        }
    }
    out
}

/// Batch against scalar, sample by sample; the stats of the batch.
fn assert_same(tri: &Tri, samples: &[[f64; 5]]) -> BatchStats {
    let mut out = Vec::new();
    let st = classify_batch(tri, samples, &mut out);
    assert_eq!(out.len(), samples.len());
    assert_eq!(st.samples, samples.len() as u64);
    for (s, c) in samples.iter().zip(&out) {
        assert_eq!(*c, classify(tri, *s), "tri {tri:?} sample {s:?}");
    }
    st
}

#[test]
fn every_regime_matches_the_scalar_oracle() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    for &shape in &SHAPES {
        let (mut all, mut uniform) = (BatchStats::default(), BatchStats::default());
        for scale in [1.0, 1e-30, 1e30, 1e-150, 1e150, 3e-300] {
            for _ in 0..6 {
                let tri = tri_of(&mut rng, shape, scale);
                let samples = samples_of(&mut rng, &tri, 700);
                all = all.merge(assert_same(&tri, &samples));
                let uni: Vec<_> = samples.iter().step_by(4).cloned().collect();
                uniform = uniform.merge(assert_same(&tri, &uni));
            }
        }
        eprintln!("{shape:?}: all {all:?}, uniform {uniform:?}");
        // The lanes decide almost every uniform sample that the scalar fast path decides
        // (the deferred samples that reached the exact path could not be decided in
        // floating point at all: values that underflow, or zero).
        let loose = uniform.deferred - uniform.exact_fallbacks;
        assert!(loose * 100 < uniform.samples, "{shape:?}: uniform {uniform:?}");
    }
}

#[test]
fn regimes_are_told_apart() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let name = |s| Batch::new(&tri_of(&mut rng.clone(), s, 1.0)).regime();
    assert_eq!(name(Shape::Static), "static");
    assert_eq!(name(Shape::Defocus), "defocus");
    assert_eq!(name(Shape::Motion), "motion");
    assert_eq!(name(Shape::Both), "both");
    rng = ChaCha8Rng::seed_from_u64(2);
    let mut t = tri_of(&mut rng, Shape::Static, 1.0);
    t.q[0][1] = f64::NAN;
    assert_eq!(Batch::new(&t).regime(), "not finite");
}

/// Triangles with small integer vertices (w = 1 at both shutter ends, dyadic circles of
/// confusion) and samples exactly on their edges and vertices at dyadic (u, v, t): the
/// values are exactly zero there, the filter must defer, and the exact path answers.
#[test]
fn exactly_on_edges_and_vertices_defers_to_the_exact_path() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut boundary = 0;
    for case in 0..64 {
        let int = |rng: &mut ChaCha8Rng| rng.gen_range(-16i32..16) as f64;
        let vert = |rng: &mut ChaCha8Rng| [int(rng), int(rng), 0.5, 1.0];
        let q = [vert(&mut rng), vert(&mut rng), vert(&mut rng)];
        let (moving, lens) = (case % 2 == 1, case % 4 >= 2);
        let r = if moving { [vert(&mut rng), vert(&mut rng), vert(&mut rng)] } else { q };
        let coc = |rng: &mut ChaCha8Rng| if lens { int(rng) / 4.0 } else { 0.0 };
        let c0 = [coc(&mut rng), coc(&mut rng), coc(&mut rng)];
        let c1 = if moving { [coc(&mut rng), coc(&mut rng), coc(&mut rng)] } else { c0 };
        let tri = Tri { q, r, c0, c1, k: 1.0 };
        let mut samples = Vec::new();
        for _ in 0..200 {
            let dy = |rng: &mut ChaCha8Rng, n: i32| rng.gen_range(-n..=n) as f64 / n as f64;
            let (u, v) = if lens { (dy(&mut rng, 4), dy(&mut rng, 4)) } else { (0.0, 0.0) };
            let t = if moving { rng.gen_range(0..=8) as f64 / 8.0 } else { 0.0 };
            // w = 1 everywhere: the projected vertices are exact dyadics.
            let p = [0, 1, 2].map(|i| projected(&tri, i, u, v, t));
            let i = rng.gen_range(0..3);
            let (a, b) = (p[i], p[(i + 1) % 3]);
            let f = rng.gen_range(0..=8) as f64 / 8.0;
            samples.push([a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1), u, v, t]);
        }
        let st = assert_same(&tri, &samples);
        let mut out = Vec::new();
        classify_batch(&tri, &samples, &mut out);
        let b = out.iter().filter(|c| **c == Coverage::Boundary).count() as u64;
        // Every boundary sample was deferred (the lanes never say boundary).
        assert!(st.deferred >= b, "case {case}: {st:?}, {b} boundary");
        boundary += b;
    }
    assert!(boundary > 1000, "{boundary} boundary samples");
}

#[test]
fn non_finite_samples_are_outside_and_their_block_still_exact() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for &shape in &SHAPES {
        let tri = tri_of(&mut rng, shape, 1.0);
        let mut samples = samples_of(&mut rng, &tri, 600);
        samples[5][0] = f64::NAN;
        samples[300][2] = f64::INFINITY;
        samples[301][4] = f64::NEG_INFINITY;
        assert_same(&tri, &samples);
        let mut out = Vec::new();
        classify_batch(&tri, &samples, &mut out);
        assert_eq!([out[5], out[300], out[301]], [Coverage::Outside; 3]);
    }
    // A triangle with a number that is not finite covers nothing.
    let mut tri = tri_of(&mut rng, Shape::Both, 1.0);
    tri.r[2][3] = f64::INFINITY;
    let other = tri_of(&mut rng, Shape::Both, 1.0);
    let samples = samples_of(&mut rng, &other, 50);
    let mut out = Vec::new();
    let st = classify_batch(&tri, &samples, &mut out);
    assert!(out.iter().all(|c| *c == Coverage::Outside));
    assert_eq!(st.deferred, 50);
}

#[test]
fn the_bound_rounds_up() {
    // up() never lands below the real result, even where the product underflows.
    for &(a, b) in &[(1e-200, 1e-200), (3.0, 1.0 / 3.0), (f64::MIN_POSITIVE, 0.5), (1e300, 1e300)] {
        let p = a * b;
        assert!(up(p) >= p && up(p) > 0.0);
    }
    // A product bound covers its own rounding and the subnormal range.
    let m = Mag { m: 1e-200, e: 0.0 }.mul(&Mag { m: 1e-200, e: 0.0 });
    assert!(m.m > 0.0 && m.e > 0.0);
    // Exact inputs whose product rounds: the error bound covers |a b - fl(a b)|.
    let a = Cst::c(0.1).mul(&Cst::c(3.0));
    let exact = Dyadic::from_f64(0.1) * Dyadic::from_f64(3.0) - Dyadic::from_f64(a.v);
    assert!(exact.to_f64().abs() <= a.e && a.e < 1e-15);
}
