//! Tests of the Embree ray oracle (`oracles::embree`): hand-computed cases for
//! the static, moving, defocused and behind-the-lens configurations, packet vs
//! single-ray agreement, and input validation.

use std::sync::Arc;

use oracles::embree::{EmbreeError, EmbreeOracle, LensTri};

/// A triangle that does not move.
fn fixed(p: [[f32; 3]; 3], a: f64, focus: f64, k: f64) -> LensTri {
    LensTri { q: p, r: p, a, focus, k }
}

fn oracle(tri: &LensTri) -> EmbreeOracle {
    EmbreeOracle::new(tri).expect("valid triangle must build")
}

/// Tiny deterministic xorshift64 generator (no dependency needed).
struct XorShift(u64);

impl XorShift {
    fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A sample with x, y in [lo, hi], u, v in [-1, 1], t in [0, 1].
    fn sample(&mut self, lo: f64, hi: f64) -> [f64; 5] {
        [self.range(lo, hi), self.range(lo, hi), self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.unit()]
    }
}

#[test]
fn ray_for_follows_the_formula() {
    // a = -0.5, F = 2, k = 1.5; sample (x, y, u, v) = (0.25, -1, 1, -0.5):
    // origin    = (-a u, -a k v, 0) = (0.5, -0.375, 0)
    // direction = (x F + a u, y F + a k v, F) = (0.5 - 0.5, -2 + 0.375, 2) = (0, -1.625, 2)
    let o = oracle(&fixed([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]], -0.5, 2.0, 1.5));
    let (org, dir) = o.ray_for([0.25, -1.0, 1.0, -0.5, 0.3]);
    assert_eq!(org, [0.5, -0.375, 0.0]);
    assert_eq!(dir, [0.0, -1.625, 2.0]);
    // Rounding happens once, from the f64 value: x F = 0.1 * 3 is not 0.3f32 * 3f32.
    let o = oracle(&fixed([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]], 0.0, 3.0, 1.0));
    let (org, dir) = o.ray_for([0.1, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(org[2], 0.0);
    assert_eq!(dir, [(0.1f64 * 3.0) as f32, 0.0, 3.0]);
}

#[test]
fn static_triangle_in_focus() {
    // a = 0 (pinhole): pixel = (X / W, Y / W). Triangle at w = 2 with clip
    // vertices (-10,-10), (10,-10), (0,10): in pixels (-5,-5), (5,-5), (0,5).
    let o = oracle(&fixed([[-10.0, -10.0, 2.0], [10.0, -10.0, 2.0], [0.0, 10.0, 2.0]], 0.0, 1.0, 1.0));
    // Centroid in pixels: (0, -5/3).
    assert!(o.hit([0.0, -5.0 / 3.0, 0.0, 0.0, 0.0]));
    assert!(o.hit([0.0, -5.0 / 3.0, 0.3, -0.7, 0.9]), "u, v, t irrelevant here");
    // Far outside.
    assert!(!o.hit([50.0, 50.0, 0.0, 0.0, 0.0]));
    assert!(!o.hit([0.0, -6.0, 0.0, 0.0, 0.5]), "below the bottom edge y = -5");
    // The division by w matters: at y = 0 the clip triangle spans X in [-5, 5],
    // i.e. pixels x in [-2.5, 2.5]. Pixel 2 is inside, pixel 4 is not (it
    // would be inside if w were ignored).
    assert!(o.hit([2.0, 0.0, 0.0, 0.0, 0.0]));
    assert!(!o.hit([4.0, 0.0, 0.0, 0.0, 0.0]));
    // Reversed winding: two-sided.
    let o2 = oracle(&fixed([[-10.0, -10.0, 2.0], [0.0, 10.0, 2.0], [10.0, -10.0, 2.0]], 0.0, 1.0, 1.0));
    assert!(o2.hit([0.0, -5.0 / 3.0, 0.0, 0.0, 0.0]));
    assert!(!o2.hit([4.0, 0.0, 0.0, 0.0, 0.0]));
}

#[test]
fn moving_triangle() {
    // w = 1 throughout, so pixel = clip (x, y). At t = 0 the triangle is
    // (-3,-1), (-1,-1), (-2,1) (around x = -2); at t = 1 it is shifted by +4
    // (around x = +2); at t = 1/2 it is around x = 0.
    let tri = LensTri {
        q: [[-3.0, -1.0, 1.0], [-1.0, -1.0, 1.0], [-2.0, 1.0, 1.0]],
        r: [[1.0, -1.0, 1.0], [3.0, -1.0, 1.0], [2.0, 1.0, 1.0]],
        a: 0.0,
        focus: 1.0,
        k: 1.0,
    };
    let o = oracle(&tri);
    let left = |t: f64| [-2.0, -0.5, 0.0, 0.0, t];
    let right = |t: f64| [2.0, -0.5, 0.0, 0.0, t];
    let middle = |t: f64| [0.0, -0.5, 0.0, 0.0, t];
    assert!(o.hit(left(0.0)));
    assert!(!o.hit(left(1.0)));
    assert!(!o.hit(right(0.0)));
    assert!(o.hit(right(1.0)));
    assert!(o.hit(middle(0.5)));
    assert!(!o.hit(left(0.5)));
    assert!(!o.hit(right(0.5)));
    // At y = -0.5 the triangle spans x in [-2.75, -1.25] + 4t; pixel -1 is
    // covered from t = 1/16 to t = 7/16.
    assert!(!o.hit([-1.0, -0.5, 0.0, 0.0, 0.03]));
    assert!(o.hit([-1.0, -0.5, 0.0, 0.0, 0.1]));
    assert!(o.hit([-1.0, -0.5, 0.0, 0.0, 0.4]));
    assert!(!o.hit([-1.0, -0.5, 0.0, 0.0, 0.47]));
}

#[test]
fn defocus_shifts_coverage_with_lens_position() {
    // Lens a = -0.5, focus F = 2, so b = -a/F = 0.25 and c(w) = -0.5 + 0.25 w.
    // Triangle in the plane w = 4 (behind the focal plane): c(4) = -0.5 + 1 = 0.5.
    // Vertices (0,-40,4), (0,40,4), (40,0,4): at Y = 0 it covers X in [0, 40]
    // (left edge X = 0).
    // Sample pixel (x, y) = (0.05, 0), v = 0. The model: x w = X + u c(w), so
    //   X = x w - u c(w) = 0.05 * 4 - u * 0.5 = 0.2 - 0.5 u,
    //   Y = y w - k v c(w) = 0.
    //   u = -1: X = 0.2 + 0.5 =  0.7  in [0, 40]  -> covered
    //   u = +1: X = 0.2 - 0.5 = -0.3  < 0         -> not covered
    // (Ray check: origin (-a u, 0, 0) = (0.5 u, 0, 0), direction
    // (x F + a u, 0, F) = (0.1 - 0.5 u, 0, 2); at w = 4 the parameter is 2 and
    // X = 0.5 u + 2 (0.1 - 0.5 u) = 0.2 - 0.5 u.)
    let p = [[0.0, -40.0, 4.0], [0.0, 40.0, 4.0], [40.0, 0.0, 4.0]];
    let o = oracle(&fixed(p, -0.5, 2.0, 1.0));
    assert!(o.hit([0.05, 0.0, -1.0, 0.0, 0.0]));
    assert!(!o.hit([0.05, 0.0, 1.0, 0.0, 0.0]));
    // u = 0 (lens centre): X = 0.2 -> covered.
    assert!(o.hit([0.05, 0.0, 0.0, 0.0, 0.0]));

    // The same with v and aspect k = 2: rotate the setup to the bottom edge.
    // Vertices (-40,0,4), (40,0,4), (0,40,4): at X = 0 it covers Y in [0, 40].
    // Pixel (0, 0.2), u = 0: Y = y w - k v c(w) = 0.8 - 2 * v * 0.5 = 0.8 - v.
    //   v = -1: Y =  1.8 -> covered;  v = +1: Y = -0.2 -> not covered
    //   (with k wrongly taken as 1, v = +1 would give Y = 0.3, covered).
    let p2 = [[-40.0, 0.0, 4.0], [40.0, 0.0, 4.0], [0.0, 40.0, 4.0]];
    let o2 = oracle(&fixed(p2, -0.5, 2.0, 2.0));
    assert!(o2.hit([0.0, 0.2, 0.0, -1.0, 0.0]));
    assert!(!o2.hit([0.0, 0.2, 0.0, 1.0, 0.0]));
    let o2k1 = oracle(&fixed(p2, -0.5, 2.0, 1.0));
    assert!(o2k1.hit([0.0, 0.2, 0.0, 1.0, 0.0]));

    // Pinhole (a = 0): no lens dependence, X = 0.2 for every u.
    let pin = oracle(&fixed(p, 0.0, 2.0, 1.0));
    assert!(pin.hit([0.05, 0.0, -1.0, 0.0, 0.0]));
    assert!(pin.hit([0.05, 0.0, 1.0, 0.0, 0.0]));

    // In the focal plane (w = F = 2) c(2) = 0: sharp, no lens dependence.
    // X = x w = 0.05 * 2 = 0.1 for every u.
    let pf = [[0.0, -40.0, 2.0], [0.0, 40.0, 2.0], [40.0, 0.0, 2.0]];
    let of = oracle(&fixed(pf, -0.5, 2.0, 1.0));
    assert!(of.hit([0.05, 0.0, -1.0, 0.0, 0.0]));
    assert!(of.hit([0.05, 0.0, 1.0, 0.0, 0.0]));

    // In front of the focal plane (w = 1): c(1) = -0.25, the shift reverses.
    // X = x w - u c(w) = 0.05 + 0.25 u: u = -1 -> -0.2 (not covered),
    // u = +1 -> 0.3 (covered).
    let pn = [[0.0, -40.0, 1.0], [0.0, 40.0, 1.0], [40.0, 0.0, 1.0]];
    let on = oracle(&fixed(pn, -0.5, 2.0, 1.0));
    assert!(!on.hit([0.05, 0.0, -1.0, 0.0, 0.0]));
    assert!(on.hit([0.05, 0.0, 1.0, 0.0, 0.0]));
}

#[test]
fn vertex_behind_the_lens() {
    // V0 = (-1,-1,1), V1 = (1,-1,1), V2 = (0,1,-0.5): V2 has w < 0.
    // Plane: normal (V1-V0) x (V2-V0) = (2,0,0) x (1,2,-1.5) = (0,3,4), so
    // 3Y + 4W = 1 (does not contain the eye).
    let p = [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, -0.5]];
    let o = oracle(&fixed(p, 0.0, 1.0, 1.0));
    // In front: 0.45 V0 + 0.45 V1 + 0.1 V2 = (0, -0.8, 0.85), pixel (0, -0.8/0.85).
    assert!(o.hit([0.0, -0.8 / 0.85, 0.0, 0.0, 0.0]));
    assert!(o.hit([0.0, -0.8 / 0.85, 0.0, 0.0, 1.0]));
    // Behind: 0.1 V0 + 0.1 V1 + 0.8 V2 = (0, 0.6, -0.2), "pixel" 0.6/-0.2 = -3.
    // The line through the eye with pixel (0, -3) is (0, -3s, s); 3Y + 4W = -5s
    // equals 1 only at s = -0.2 < 0, i.e. only behind the eye: not covered.
    assert!(!o.hit([0.0, -3.0, 0.0, 0.0, 0.0]));
    // With a lens and motion through w = 0: no panic, packets agree.
    let tri = LensTri { q: p, r: [[-1.0, -1.0, 1.5], [1.0, -1.0, -0.2], [0.0, 1.0, 2.0]], a: -0.3, focus: 1.5, k: 1.0 };
    let o = oracle(&tri);
    assert!(o.hit([0.0, -0.8 / 0.85, 0.0, 0.0, 0.0]));
    let mut rng = XorShift(0x0bad_cafe_1234_5678);
    let samples: Vec<[f64; 5]> = (0..2000).map(|_| rng.sample(-5.0, 5.0)).collect();
    let mut out = Vec::new();
    o.hits(&samples, &mut out);
    for (s, &h) in samples.iter().zip(&out) {
        assert_eq!(h, o.hit(*s), "sample {s:?}");
    }
}

#[test]
fn degenerate_triangles_do_not_panic() {
    let cases = [
        // Coincident vertices.
        [[1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]],
        // Collinear (zero area).
        [[0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [2.0, 2.0, 1.0]],
        // All at the origin.
        [[0.0; 3]; 3],
        // Plane through the eye (a = 0): zero-area image.
        [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, -1.0]],
    ];
    let mut rng = XorShift(7);
    let samples: Vec<[f64; 5]> = (0..100).map(|_| rng.sample(-3.0, 3.0)).collect();
    for p in cases {
        for a in [0.0, -0.2] {
            let o = oracle(&fixed(p, a, 1.0, 1.0));
            let mut out = Vec::new();
            o.hits(&samples, &mut out);
            assert_eq!(out.len(), samples.len());
            for (s, &h) in samples.iter().zip(&out) {
                assert_eq!(h, o.hit(*s));
            }
            let _ = o.hit([1.0, 1.0, 0.0, 0.0, 0.5]);
        }
    }
}

/// A few triangles of different kinds (static, moving, defocused, crossing
/// w = 0) for the packet/single comparison.
fn assorted() -> Vec<LensTri> {
    vec![
        fixed([[-2.0, -2.0, 1.0], [2.0, -1.0, 1.5], [0.0, 2.5, 1.2]], 0.0, 1.0, 1.0),
        LensTri {
            q: [[-3.0, -1.0, 1.0], [-1.0, -1.0, 1.0], [-2.0, 1.0, 1.0]],
            r: [[1.0, -1.0, 2.0], [3.0, -1.0, 1.0], [2.0, 1.5, 1.0]],
            a: -0.4,
            focus: 1.3,
            k: 1.25,
        },
        LensTri {
            q: [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, -0.5]],
            r: [[-0.5, -1.5, 0.5], [1.5, -1.0, 2.0], [0.0, 2.0, 0.5]],
            a: -0.7,
            focus: 0.8,
            k: 0.75,
        },
    ]
}

#[test]
fn packets_agree_with_single_rays() {
    let mut rng = XorShift(0x9e37_79b9_7f4a_7c15);
    for tri in assorted() {
        let o = oracle(&tri);
        let samples: Vec<[f64; 5]> = (0..10_000).map(|_| rng.sample(-3.0, 3.0)).collect();
        let mut out = vec![true; 3]; // stale contents must be cleared
        o.hits(&samples, &mut out);
        assert_eq!(out.len(), samples.len());
        let mut n_hit = 0;
        for (i, (s, &h)) in samples.iter().zip(&out).enumerate() {
            assert_eq!(h, o.hit(*s), "sample {i}: {s:?}, triangle {tri:?}");
            n_hit += h as usize;
        }
        // The comparison is not vacuous: both answers occur often.
        assert!(n_hit > 200 && n_hit < 9_800, "{n_hit} hits of 10000 for {tri:?}");
    }
}

#[test]
fn packets_with_ragged_tails_and_bad_samples() {
    let o = oracle(&assorted()[1]);
    let mut rng = XorShift(42);
    let all: Vec<[f64; 5]> = (0..100).map(|_| rng.sample(-3.0, 3.0)).collect();
    let mut out = Vec::new();
    for n in [0, 1, 7, 8, 9, 15, 16, 17, 31, 33, 100] {
        o.hits(&all[..n], &mut out);
        assert_eq!(out.len(), n);
        for (s, &h) in all[..n].iter().zip(&out) {
            assert_eq!(h, o.hit(*s));
        }
    }
    // Non-finite samples: not covered, by both entry points; neighbours unaffected.
    let good = [-2.0, -0.5, 0.0, 0.0, 0.0];
    assert!(o.hit(good));
    let bad = [
        [f64::NAN, -0.5, 0.0, 0.0, 0.0],
        [-2.0, f64::INFINITY, 0.0, 0.0, 0.0],
        [-2.0, -0.5, 0.0, f64::NEG_INFINITY, 0.0],
        [-2.0, -0.5, 0.0, 0.0, f64::NAN],
    ];
    let mut mixed = vec![good];
    for b in bad {
        assert!(!o.hit(b));
        mixed.push(b);
        mixed.push(good);
    }
    o.hits(&mixed, &mut out);
    let expect: Vec<bool> = mixed.iter().map(|s| s[0] == -2.0 && s[1] == -0.5 && s[3] == 0.0 && s[4] == 0.0).collect();
    assert_eq!(out, expect);
}

#[test]
fn untraceable_samples_are_misses_not_aborts() {
    // Embree (Debian build, assertions on) aborts the process on a ray with a
    // component beyond FLT_LARGE = 1.844e18, and on a motion-blur packet ray
    // with time outside [0, 1]; the oracle must report such samples as not
    // covered instead of tracing them.
    let tri = LensTri {
        q: [[-3.0, -1.0, 1.0], [-1.0, -1.0, 1.0], [-2.0, 1.0, 1.0]],
        r: [[1.0, -1.0, 1.0], [3.0, -1.0, 1.0], [2.0, 1.0, 1.0]],
        a: -0.1,
        focus: 1.0,
        k: 1.0,
    };
    let o = oracle(&tri);
    // Sanity: the sample is covered at t = 0 and (shifted) at t = 1.
    assert!(o.hit([-2.0, -0.5, 0.0, 0.0, 0.0]));
    assert!(o.hit([2.0, -0.5, 0.0, 0.0, 1.0]));
    let mut samples = Vec::new();
    for t in [-1e-3, 1.001, -1.0, 2.0, 1e30, -1e300] {
        // Where the triangle would be if the motion were extrapolated.
        samples.push([-2.0 + 4.0 * t, -0.5, 0.0, 0.0, t]);
        samples.push([-2.0, -0.5, 0.0, 0.0, t]);
    }
    for big in [1.9e18, 1e30, 1e300] {
        samples.push([big, 0.0, 0.0, 0.0, 0.5]);
        samples.push([0.0, -big, 0.0, 0.0, 0.5]);
        // Origin -a u = 0.1 big: still traced (and a miss) for 1.9e18, beyond
        // FLT_LARGE for the others.
        samples.push([-2.0, -0.5, big, 0.0, 0.0]);
    }
    for s in &samples {
        assert!(!o.hit(*s), "{s:?}");
    }
    // Interleave with covered samples so the packet path mixes both kinds.
    let good = [-2.0, -0.5, 0.0, 0.0, 0.0];
    let mixed: Vec<[f64; 5]> = samples.iter().flat_map(|&s| [s, good]).collect();
    let mut out = Vec::new();
    o.hits(&mixed, &mut out);
    let expect: Vec<bool> = (0..mixed.len()).map(|i| i % 2 == 1).collect();
    assert_eq!(out, expect);
    // Large but traceable values still go to Embree (and miss).
    assert!(!o.hit([1e17, 0.0, 0.0, 0.0, 0.5]));
}

#[test]
fn oracle_is_send_sync_and_shareable() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<EmbreeOracle>();
    let o = Arc::new(oracle(&assorted()[2]));
    let mut rng = XorShift(99);
    let samples: Arc<Vec<[f64; 5]>> = Arc::new((0..4000).map(|_| rng.sample(-3.0, 3.0)).collect());
    let mut expect = Vec::new();
    o.hits(&samples, &mut expect);
    std::thread::scope(|scope| {
        for _ in 0..2 {
            let (o, samples, expect) = (o.clone(), samples.clone(), &expect);
            scope.spawn(move || {
                let mut out = Vec::new();
                o.hits(&samples, &mut out);
                assert_eq!(&out, expect);
                for (s, &e) in samples.iter().zip(expect) {
                    assert_eq!(o.hit(*s), e);
                }
            });
        }
    });
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let good = fixed([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]], -0.1, 1.0, 1.0);
    assert!(EmbreeOracle::new(&good).is_ok());

    let mut t = good;
    t.focus = 0.0;
    let e = EmbreeOracle::new(&t).unwrap_err();
    assert!(matches!(e, EmbreeError::FocusNotPositive(_)), "{e:?}");
    assert!(!e.to_string().is_empty());

    let mut t = good;
    t.focus = -2.0;
    assert!(matches!(EmbreeOracle::new(&t), Err(EmbreeError::FocusNotPositive(_))));

    let mut t = good;
    t.q[1][2] = f32::NAN;
    let e = EmbreeOracle::new(&t).unwrap_err();
    assert!(matches!(e, EmbreeError::NonFiniteVertex { time: 0, vertex: 1, coord: 2, .. }), "{e:?}");
    // Usable as a boxed std error.
    let boxed: Box<dyn std::error::Error> = Box::new(e);
    assert!(boxed.to_string().contains("non-finite"));

    let mut t = good;
    t.r[2][0] = f32::INFINITY;
    assert!(matches!(EmbreeOracle::new(&t), Err(EmbreeError::NonFiniteVertex { time: 1, .. })));

    for (i, bad) in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY].into_iter().enumerate() {
        let mut t = good;
        match i {
            0 => t.a = bad,
            1 => t.focus = bad,
            _ => t.k = bad,
        }
        assert!(matches!(EmbreeOracle::new(&t), Err(EmbreeError::NonFiniteParameter { .. })), "case {i}");
    }

    // A focus that rounds to a subnormal (or zero) f32, or beyond FLT_LARGE.
    for f in [1e-40, 1e-50, 1e19, 1e300] {
        let mut t = good;
        t.focus = f;
        assert!(matches!(EmbreeOracle::new(&t), Err(EmbreeError::FocusOutOfRange(_))), "focus {f}");
    }
    for f in [1e-30, 1e18] {
        let mut t = good;
        t.focus = f;
        assert!(EmbreeOracle::new(&t).is_ok(), "focus {f}");
    }

    let mut t = good;
    t.a = 0.5;
    assert!(matches!(EmbreeOracle::new(&t), Err(EmbreeError::LensParameterPositive(_))));
}
