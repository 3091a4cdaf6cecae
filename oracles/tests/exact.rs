//! The exact oracle against an independent, slow BigRational evaluation of the model,
//! written out again here from `docs/model.md` (translated vertices, 2x2 edge determinants,
//! a full 3x3 determinant by cofactors), on random inputs that include huge, tiny and
//! denormal values.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use oracles::{classify, Coverage, Tri};
use quickcheck::{Arbitrary, Gen, QuickCheck};

fn r(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// The reference: exact rationals, straight from the model's definitions.
fn reference(t: &Tri, s: [f64; 5]) -> Coverage {
    let [x, y, u, v, tt] = s.map(r);
    let one = BigRational::from_integer(BigInt::from(1));
    let mut p: Vec<[BigRational; 3]> = Vec::new();
    for i in 0..3 {
        let lerp = |a: f64, b: f64| (&one - &tt) * r(a) + &tt * r(b);
        let c = lerp(t.c0[i], t.c1[i]);
        let w = lerp(t.q[i][3], t.r[i][3]);
        let xs = lerp(t.q[i][0], t.r[i][0]) + &u * &c;
        let ys = lerp(t.q[i][1], t.r[i][1]) + r(t.k) * &v * &c;
        p.push([xs - &x * &w, ys - &y * &w, w]);
    }
    let e = |i: usize, j: usize| &p[i][0] * &p[j][1] - &p[i][1] * &p[j][0];
    let es = [e(1, 2), e(2, 0), e(0, 1)];
    // det by cofactors along the first row
    let m = &p;
    let d = &m[0][0] * (&m[1][1] * &m[2][2] - &m[1][2] * &m[2][1])
        - &m[0][1] * (&m[1][0] * &m[2][2] - &m[1][2] * &m[2][0])
        + &m[0][2] * (&m[1][0] * &m[2][1] - &m[1][1] * &m[2][0]);
    let sg = |v: &BigRational| {
        if v.is_zero() {
            0
        } else if v.is_positive() {
            1
        } else {
            -1
        }
    };
    let signs = [sg(&es[0]), sg(&es[1]), sg(&es[2]), sg(&d)];
    if signs[3] != 0 && signs.iter().all(|&z| z == signs[3]) {
        Coverage::Interior
    } else if signs.contains(&1) && signs.contains(&-1) {
        Coverage::Outside
    } else {
        Coverage::Boundary
    }
}

/// A number drawn to stress arithmetic: ordinary, huge, tiny, denormal, exact zero,
/// or a small integer (which makes exact boundaries likely).
#[derive(Clone, Copy, Debug)]
struct Num(f64);
impl Arbitrary for Num {
    fn arbitrary(g: &mut Gen) -> Self {
        let pick = u8::arbitrary(g) % 8;
        let f = (i32::arbitrary(g) % 1000) as f64 / 100.0;
        Num(match pick {
            0 => 0.0,
            1 => (i8::arbitrary(g) % 5) as f64,
            2 => f * 1e30,
            3 => f * 1e-30,
            4 => f * 1e-310, // denormal
            5 => (f as f32) as f64,
            _ => f,
        })
    }
}

#[derive(Clone, Debug)]
struct Input(Tri, [f64; 5]);
impl Arbitrary for Input {
    fn arbitrary(g: &mut Gen) -> Self {
        let v = |g: &mut Gen| [0; 4].map(|_| Num::arbitrary(g).0);
        let q = [v(g), v(g), v(g)];
        let static_case = bool::arbitrary(g);
        let r = if static_case { q } else { [v(g), v(g), v(g)] };
        let c0 = [0; 3].map(|_| Num::arbitrary(g).0);
        let c1 = [0; 3].map(|_| Num::arbitrary(g).0);
        let k = 0.75;
        let unit = |g: &mut Gen| (u16::arbitrary(g) as f64) / 65535.0;
        let s = [Num::arbitrary(g).0, Num::arbitrary(g).0, 2.0 * unit(g) - 1.0, 2.0 * unit(g) - 1.0, unit(g)];
        Input(Tri { q, r, c0, c1, k }, s)
    }
}

#[test]
fn exact_matches_bigrational_reference() {
    fn prop(i: Input) -> bool {
        classify(&i.0, i.1) == reference(&i.0, i.1)
    }
    QuickCheck::new().tests(20_000).quickcheck(prop as fn(Input) -> bool);
}

#[test]
fn exact_matches_reference_on_ordinary_triangles_with_samples_on_vertices() {
    // Samples placed exactly on projected vertices / edges of integer triangles are
    // boundary cases the fast path cannot settle.
    fn prop(a: (i8, i8, i8, i8, i8, i8), px: i8, py: i8) -> bool {
        let q = [
            [a.0 as f64, a.1 as f64, 0.0, 1.0],
            [a.2 as f64, a.3 as f64, 0.0, 1.0],
            [a.4 as f64, a.5 as f64, 0.0, 1.0],
        ];
        let t = Tri { q, r: q, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        let s = [px as f64 / 2.0, py as f64 / 2.0, 0.0, 0.0, 0.0];
        classify(&t, s) == reference(&t, s)
    }
    QuickCheck::new().tests(20_000).quickcheck(prop as fn((i8, i8, i8, i8, i8, i8), i8, i8) -> bool);
}

#[test]
fn degenerate_inputs_answer_without_panic() {
    let z = [0.0, 0.0, 0.0, 0.0];
    let p = [1.0, 1.0, 0.0, 1.0];
    for q in [[z, z, z], [p, p, p], [z, p, p], [[0.0, 0.0, 0.0, -1.0], p, [2.0, 0.0, 0.0, 0.0]]] {
        let t = Tri { q, r: q, c0: [0.0; 3], c1: [1e-40, 0.0, -3.0], k: 1.0 };
        for s in [[0.0; 5], [1.0, 1.0, 1.0, -1.0, 1.0], [1e300, -1e300, 0.5, 0.5, 0.5]] {
            let c = classify(&t, s);
            assert_eq!(c, reference(&t, s), "{q:?} {s:?}");
        }
    }
    // a zero-area triangle covers nothing
    let t = Tri { q: [p, p, p], r: [p, p, p], c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
    assert_ne!(classify(&t, [1.0, 1.0, 0.0, 0.0, 0.0]), Coverage::Interior);
}
