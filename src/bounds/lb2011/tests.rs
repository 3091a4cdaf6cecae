//! The unit tests of `lb2011` (a file of their own to keep the method's file to its method).

use super::super::la2011::{cases, figure1};
use super::super::testkit::{
    assert_degenerate_input_is_answered, assert_spot, bounds_of, random_dual_case, random_sample,
};
use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    bounds_of(METHOD, tri, tile)
}

/// Random samples in the tile: no interior-covered sample may be rejected.
/// Returns (covered, admitted) sample counts.
fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> (usize, usize) {
    assert_spot(METHOD, tri, tile, n, seed)
}

#[test]
fn static_triangle_keeps_whole_time_range() {
    let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0]]);
    let tile = Tile::square(10.0, 10.0, 4.0);
    let b = bounds(&tri, &tile).expect("inside tile culled");
    assert_eq!(b.t, [0.0, 1.0]);
    // No patch can cull: the tile columns lie strictly between the vertices.
    assert!(b.constraints.is_empty(), "{:?}", b.constraints);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..1000 {
        assert!(b.admits(&random_sample(&mut rng, &tile)));
    }
}

#[test]
fn far_tiles_are_culled() {
    let tri = figure1::triangle();
    for tile in figure1::far_tiles() {
        assert!(bounds(&tri, &tile).is_none(), "{tile:?}");
    }
}

#[test]
fn figure1_patches_keep_only_the_strip() {
    let tri = figure1::triangle();
    let tile = figure1::tile();
    let b = bounds(&tri, &tile).unwrap();
    // With w = 1 and a constant CoC the min over vertices and columns is one plane:
    // vertex 0 at X1: B(u, t) = -21 + 40 t - 0.5 + 8 u exactly; the max is vertex 1
    // at X0: -19 + 40 t + 0.5 + 8 u. The kept (u, t) set is the diagonal strip
    // 18.5 <= 40 t + 8 u <= 21.5 (width 0.075 in t) inside LA's box.
    let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
    assert!(close(b.t, figure1::LA_T), "t {:?}", b.t);
    assert!(close(b.u, figure1::LA_U), "u {:?}", b.u);
    assert!(close(b.v, figure1::LA_V), "v {:?}", b.v);
    for (u, t, keep) in [
        (0.0f32, 0.5f32, true),
        (1.0, 0.3, true),
        (-1.0, 0.7, true),
        (0.0, 0.45, false),
        (0.0, 0.56, false),
        (1.0, 0.7, false),
        (-1.0, 0.3, false),
    ] {
        let s = Sample::new(0.0, 0.0, u, 0.0, t);
        assert_eq!(b.admits(&s), keep, "u {u} t {t}");
    }
    // Fraction of LA's box that LB keeps, and how much of it is covered.
    let o = tri.to_oracle();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut in_la, mut in_lb, mut hit) = (0, 0, 0);
    for _ in 0..40000 {
        let s = Sample::new(0.0, 0.0, rng.gen_range(-1.0..=1.0), 0.0, rng.gen_range(0.0..=1.0));
        let la = figure1::LA_T[0] <= s.t && s.t <= figure1::LA_T[1];
        in_la += la as usize;
        if b.admits(&s) {
            assert!(la);
            in_lb += 1;
            hit += (oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior) as usize;
        }
    }
    let kept = in_lb as f64 / in_la as f64;
    assert!((kept - 0.075 / 0.475).abs() < 0.02, "LB keeps {kept} of LA's box");
    // At the pixel (0, 0) the triangle's row y = 0 spans [a - 0.5, a + 0.5] with
    // a = -20 + 40 t + 8 u: covered for 19.5 < 40 t + 8 u < 20.5, a third of the strip.
    let frac = hit as f64 / in_lb as f64;
    assert!((frac - 1.0 / 3.0).abs() < 0.03, "covered fraction of LB's strip {frac}");
    assert!(spot_check(&tri, &tile, 20000, 8).0 > 20);
}

#[test]
fn patch_is_below_the_min_and_box_encloses_eval() {
    // The bilinear patch never exceeds the real min over vertices and columns (up to
    // f32 rounding), for every kind of triangle; eval lies in eval_box.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut checked = 0;
    for tri in cases::hard_triangles() {
        for n in 0..150 {
            let tile = Tile::square(rng.gen_range(-15.0..15.0), rng.gen_range(-15.0..15.0), [1.0f32, 4.0][n % 2]);
            let Some(b) = bounds(&tri, &tile) else {
                continue;
            };
            for c in &b.constraints {
                checked += 1;
                for _ in 0..200 {
                    let s = random_sample(&mut rng, &tile);
                    let (u, v, t) = (s.u as f64, s.v as f64, s.t as f64);
                    let o = tri.to_oracle();
                    let name = c.name();
                    let (axis, l, cols, scale) = if name.starts_with('x') {
                        (0, u, [tile.x0, tile.x1], 1.0)
                    } else {
                        (1, v, [tile.y0, tile.y1], o.k)
                    };
                    let mut mn = f64::INFINITY;
                    let mut mx = f64::NEG_INFINITY;
                    let mut mag = 0.0f64;
                    for i in 0..3 {
                        let lerp = |a: f64, b: f64| (1.0 - t) * a + t * b;
                        let p = lerp(o.q[i][axis], o.r[i][axis]);
                        let w = lerp(o.q[i][3], o.r[i][3]);
                        let cc = lerp(o.c0[i], o.c1[i]) * scale;
                        for x in cols {
                            let d = p + l * cc - x as f64 * w;
                            mn = mn.min(d);
                            mx = mx.max(d);
                            mag = mag.max(p.abs() + cc.abs() + (x as f64 * w).abs());
                        }
                    }
                    let g = c.eval(&s) as f64;
                    let tol = mag * 1e-5 + 1e-30;
                    if name.contains("min") {
                        assert!(-g <= mn + tol, "{name}: patch {} above min {mn}", -g);
                    } else {
                        assert!(g >= mx - tol, "{name}: patch {g} below max {mx}");
                    }
                    let pt = |x: f32| Interval::point(x as f64);
                    let bx = SampleBox { x: pt(s.x), y: pt(s.y), u: pt(s.u), v: pt(s.v), t: pt(s.t) };
                    assert!(c.eval_box(&bx).contains(g), "{name}: {g} not in {:?}", c.eval_box(&bx));
                    // A box around the sample.
                    let wide =
                        |x: f32, lo: f64, hi: f64| Interval::new((x as f64 - 0.1).max(lo), (x as f64 + 0.1).min(hi));
                    let bx =
                        SampleBox { u: wide(s.u, -1.0, 1.0), v: wide(s.v, -1.0, 1.0), t: wide(s.t, 0.0, 1.0), ..bx };
                    let e = c.eval_box(&bx);
                    for _ in 0..5 {
                        let s2 = Sample::new(
                            s.x,
                            s.y,
                            rng.gen_range(bx.u.lo..=bx.u.hi) as f32,
                            rng.gen_range(bx.v.lo..=bx.v.hi) as f32,
                            rng.gen_range(bx.t.lo..=bx.t.hi) as f32,
                        );
                        let g2 = c.eval(&s2) as f64;
                        assert!(e.contains(g2), "{name}: {g2} not in {e:?}");
                    }
                }
            }
        }
    }
    assert!(checked > 200, "only {checked} patches checked");
}

#[test]
fn eval_box_covers_rounding_and_overflow() {
    let p = Patch { name: "t", lens: Lens::U, p: 1.0e30, q: -1.0e30, r: 3.0, s: 1.0e-30 };
    let b = SampleBox {
        x: Interval::point(0.0),
        y: Interval::point(0.0),
        u: Interval::point(1.0),
        v: Interval::point(0.0),
        t: Interval::point(0.5),
    };
    let e = p.eval_box(&b);
    assert!(e.contains(p.eval(&Sample::new(0.0, 0.0, 1.0, 0.0, 0.5)) as f64));
    let big = Patch { p: 3.0e38, q: 3.0e38, ..p };
    let e = big.eval_box(&b);
    assert!(e.lo == f64::NEG_INFINITY && e.hi == f64::INFINITY);
}

#[test]
fn no_covered_sample_is_culled() {
    let mut seed = 100;
    let (mut total, mut admitted, mut n) = (0, 0, 0);
    let mut tris = cases::hard_triangles();
    tris.push(figure1::triangle());
    for tri in &tris {
        for tx in -6..6 {
            for ty in -6..6 {
                let tile = Tile::square(tx as f32 * 5.0, ty as f32 * 5.0, 5.0);
                let (c, a) = spot_check(tri, &tile, 300, seed);
                total += c;
                admitted += a;
                n += 300;
                seed += 1;
            }
        }
    }
    assert!(total > 2000, "too few covered samples: {total}");
    assert!(admitted < n / 2, "the test hardly culls: {admitted} of {n}");
}

#[test]
fn random_triangles_are_never_culled_where_covered() {
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let mut total = 0;
    for n in 0..300 {
        let (tri, tile) = random_dual_case(&mut rng, n);
        total += spot_check(&tri, &tile, 2000, 2000 + n as u64).0;
    }
    assert!(total > 10000, "too few covered samples: {total}");
}

#[test]
fn degenerate_input_does_not_panic() {
    assert_degenerate_input_is_answered(METHOD, &figure1::triangle());
}

// ----- lb2011-safe -----

fn safe_bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    bounds_of(METHOD_SAFE, tri, tile)
}

/// Enclosures (outward-rounded f64) of `delta_k(X, l, t)` on one axis, for the 3
/// vertices and both columns (rows) of the tile.
fn deltas(tri: &Triangle, tile: &Tile, axis: usize, l: f32, t: f32) -> Vec<Interval> {
    let pt = |x: f32| Interval::point(x as f64);
    let (t, l) = (pt(t), pt(l));
    let lerp = |a: f32, b: f32| pt(a) + t * (pt(b) - pt(a));
    let cols = if axis == 0 { [tile.x0, tile.x1] } else { [tile.y0, tile.y1] };
    let scale = if axis == 0 { pt(1.0) } else { pt(tri.k) };
    let mut out = Vec::new();
    for i in 0..3 {
        let p = lerp(tri.q[i][axis], tri.r[i][axis]);
        let w = lerp(tri.q[i][3], tri.r[i][3]);
        let c = lerp(tri.c0[i], tri.c1[i]) * scale;
        for x in cols {
            out.push(p - pt(x) * w + l * c);
        }
    }
    out
}

/// True when the exact `min delta < 0 < max delta` holds for certain on both axes at
/// (u, v, t): the lemma's necessary condition for any covered sample in the tile.
fn surely_necessary(tri: &Triangle, tile: &Tile, u: f32, v: f32, t: f32) -> bool {
    [(0, u), (1, v)].into_iter().all(|(axis, l)| {
        let d = deltas(tri, tile, axis, l, t);
        d.iter().any(|e| e.hi < 0.0) && d.iter().any(|e| e.lo > 0.0)
    })
}

/// Lens and time values that sit on the zero set of some `delta_k`: the roots in l
/// at random t and the roots in t at l = -1, 0, 1, with their f32 neighbours, plus
/// the domain's corners and random values.
fn probes(tri: &Triangle, tile: &Tile, axis: usize, rng: &mut ChaCha8Rng) -> Vec<(f32, f32)> {
    let cols = if axis == 0 { [tile.x0, tile.x1] } else { [tile.y0, tile.y1] };
    let scale = if axis == 0 { 1.0 } else { tri.k as f64 };
    let d_at = |i: usize, x: f32, l: f64, t: f64| {
        let lerp = |a: f32, b: f32| a as f64 + t * (b as f64 - a as f64);
        lerp(tri.q[i][axis], tri.r[i][axis]) - x as f64 * lerp(tri.q[i][3], tri.r[i][3])
            + l * scale * lerp(tri.c0[i], tri.c1[i])
    };
    let near = |x: f32, lo: f32, hi: f32| {
        let mut v = vec![x];
        let (mut a, mut b) = (x, x);
        for _ in 0..3 {
            a = a.next_down();
            b = b.next_up();
            v.extend([a, b]);
        }
        v.into_iter().filter(move |y| (lo..=hi).contains(y))
    };
    let mut out = vec![(-1.0, 0.0), (1.0, 0.0), (-1.0, 1.0), (1.0, 1.0)];
    for _ in 0..6 {
        out.push((rng.gen_range(-1.0..=1.0), rng.gen_range(0.0..=1.0)));
    }
    for i in 0..3 {
        for x in cols {
            for _ in 0..3 {
                let t: f32 = rng.gen_range(0.0..=1.0);
                let (d0, d1) = (d_at(i, x, 0.0, t as f64), d_at(i, x, 1.0, t as f64));
                let l = (-d0 / (d1 - d0)) as f32;
                if l.is_finite() {
                    out.extend(near(l, -1.0, 1.0).map(|l| (l, t)));
                }
            }
            for l in [-1.0f32, 0.0, 1.0] {
                let (d0, d1) = (d_at(i, x, l as f64, 0.0), d_at(i, x, l as f64, 1.0));
                let t = (-d0 / (d1 - d0)) as f32;
                if t.is_finite() {
                    out.extend(near(t, 0.0, 1.0).map(|t| (l, t)));
                }
            }
        }
    }
    out
}

/// Every probe (u, v, t) that surely meets the necessary condition must be admitted
/// at the tile's corners and centre. Returns (necessary probes, admitted probes of
/// all, probes culled by the original that are surely necessary).
fn check_safe_on(tri: &Triangle, tile: &Tile, rng: &mut ChaCha8Rng) -> (usize, usize, usize) {
    let safe = safe_bounds(tri, tile);
    let plain = bounds(tri, tile);
    let pu = probes(tri, tile, 0, rng);
    let pv = probes(tri, tile, 1, rng);
    let (mut need, mut adm, mut plain_bad) = (0, 0, 0);
    for (n, &(u, tu)) in pu.iter().enumerate() {
        for k in 0..4 {
            let (v, tv) = pv[(n * 7 + k * 13) % pv.len()];
            for t in [tu, tv] {
                let nec = surely_necessary(tri, tile, u, v, t);
                let s = Sample::new(tile.x0, tile.y1, u, v, t);
                let ok = safe.as_ref().is_some_and(|b| b.admits(&s));
                assert!(ok || !nec, "lb2011-safe culls a necessary (u, v, t) {s:?}\n{tri:?}\n{tile:?}\n{safe:?}");
                need += nec as usize;
                adm += ok as usize;
                plain_bad += (nec && !plain.as_ref().is_some_and(|b| b.admits(&s))) as usize;
            }
        }
    }
    // The patches are upper bounds of the exact min / max at every probe.
    if let Some(b) = &safe {
        for c in &b.constraints {
            let name = c.name();
            let (axis, ps) = if name.starts_with('x') { (0, &pu) } else { (1, &pv) };
            for &(l, t) in ps.iter() {
                let s = if axis == 0 { Sample::new(0.0, 0.0, l, 0.0, t) } else { Sample::new(0.0, 0.0, 0.0, l, t) };
                let g = c.eval(&s) as f64;
                let d = deltas(tri, tile, axis, l, t);
                let need = if name.contains("min") {
                    d.iter().map(|e| -e.lo).fold(f64::NEG_INFINITY, f64::max)
                } else {
                    d.iter().map(|e| e.hi).fold(f64::NEG_INFINITY, f64::max)
                };
                assert!(g >= need, "{name} at l {l} t {t}: eval {g} below the exact bound {need}\n{tri:?}\n{tile:?}");
                let pt = |x: f32| Interval::point(x as f64);
                let bx = SampleBox { x: pt(s.x), y: pt(s.y), u: pt(s.u), v: pt(s.v), t: pt(s.t) };
                assert!(c.eval_box(&bx).contains(g), "{name}: {g} not in {:?}", c.eval_box(&bx));
            }
        }
        super::super::testkit::assert_eval_box_encloses(b, tile, rng.gen());
    }
    (need, adm, plain_bad)
}

/// A random triangle of one of the hard kinds, positioned in pixels around (ox, oy),
/// and a tile near one of its projected vertices.
fn hard_case(rng: &mut ChaCha8Rng, kind: usize) -> (Triangle, Tile) {
    let (ox, oy): (f32, f32) = match kind {
        3 => (rng.gen_range(-1.0e6..1.0e6), rng.gen_range(-1.0e6..1.0e6)),
        _ => (rng.gen_range(-100.0..100.0), rng.gen_range(-100.0..100.0)),
    };
    let size: f32 = match kind {
        1 => 1.0e4,
        2 => 1.0e-3,
        _ => 30.0,
    };
    let wgen = |rng: &mut ChaCha8Rng| -> f32 {
        match kind {
            4 => rng.gen_range(-1.0e-6..1.0e-6),
            5 => rng.gen_range(-0.5..2.0),
            6 => rng.gen_range(1.0e3..1.0e5),
            _ => rng.gen_range(0.5..20.0),
        }
    };
    let v = |rng: &mut ChaCha8Rng| {
        let w = wgen(rng);
        let (x, y) = (ox + rng.gen_range(-size..size), oy + rng.gen_range(-size..size));
        [x * w, y * w, 0.5, w]
    };
    let q = [v(rng), v(rng), v(rng)];
    let moving = rng.gen_bool(0.7);
    let r = if moving { [v(rng), v(rng), v(rng)] } else { q };
    // CoC: physical c = a + b w crossing the focal plane, or per vertex, huge or tiny.
    let cmag: f32 = match kind {
        1 | 7 => 3.0e3,
        2 => 1.0e-30,
        _ => 5.0,
    };
    let (c0, c1) = if kind == 0 || rng.gen_bool(0.5) {
        let focus = q[0][3] * rng.gen_range(0.5f32..1.5);
        let b = cmag / focus.abs().max(1e-30);
        (q.map(|p| b * (p[3] - focus)), r.map(|p| b * (p[3] - focus)))
    } else {
        let mut c = || rng.gen_range(-cmag..cmag);
        ([c(), c(), c()], [c(), c(), c()])
    };
    let tri = Triangle { q, r, c0, c1, k: rng.gen_range(0.5..2.0) };
    let i = rng.gen_range(0..3);
    let p = if rng.gen_bool(0.5) { q[i] } else { r[i] };
    let (cx, cy) = if p[3].abs() > 1e-30 { (p[0] / p[3], p[1] / p[3]) } else { (ox, oy) };
    let ts = [1.0f32, 2.0, 4.0, 16.0][rng.gen_range(0..4)];
    let jitter = if kind == 2 { size } else { (size * 0.1).max(ts) };
    let (x0, y0) = (cx + rng.gen_range(-jitter..jitter), cy + rng.gen_range(-jitter..jitter));
    // Pixel-aligned tiles, or for the tiny triangle tiles of its own size.
    let tile = if kind == 2 { Tile::square(x0, y0, ts * size / 8.0) } else { Tile::square(x0.floor(), y0.floor(), ts) };
    (tri, tile)
}

#[test]
fn safe_admits_every_necessary_lens_time_on_hard_input() {
    // Kinds: 0 ordinary thin lens through the focal plane, 1 huge (1e4 px, CoC 3e3),
    // 2 tiny (1e-3 px, CoC 1e-30), 3 far from the origin (1e6 px), 4 w near 0
    // (|w| < 1e-6), 5 vertices behind the lens, 6 huge w, 7 huge CoC.
    let mut rng = ChaCha8Rng::seed_from_u64(2011);
    let mut totals = [(0usize, 0usize, 0usize); 8];
    for n in 0..1600 {
        let kind = n % 8;
        let (tri, tile) = hard_case(&mut rng, kind);
        let (a, b, c) = check_safe_on(&tri, &tile, &mut rng);
        totals[kind].0 += a;
        totals[kind].1 += b;
        totals[kind].2 += c;
    }
    for (kind, &(need, adm, _)) in totals.iter().enumerate() {
        assert!(need > 100, "kind {kind}: only {need} necessary probes: {totals:?}");
        assert!(adm > need, "kind {kind}: nothing culled ({adm} admitted, {need} necessary): {totals:?}");
    }
    eprintln!("(necessary, admitted, culled by lb2011 though necessary) per kind: {totals:?}");
    // The probes sit on the rounding-sized boundary that the original misses.
    let plain_bad: usize = totals.iter().map(|t| t.2).sum();
    assert!(plain_bad > 0, "the probes never catch lb2011 itself: {totals:?}");
}

#[test]
fn safe_keeps_covered_samples_of_the_stored_lb2011_cases() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/lb2011");
    let mut n = 0;
    for f in std::fs::read_dir(&dir).unwrap() {
        let path = f.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let cf = crate::search::CaseFile::load(&path).unwrap();
        let w = cf.witness.as_ref().expect("a violation case has a witness");
        assert!(crate::search::witness_holds(METHOD, &cf.case, &cf.tile, w.sample).is_ok(), "{path:?}");
        let r = crate::search::witness_holds(METHOD_SAFE, &cf.case, &cf.tile, w.sample);
        assert!(r.is_err(), "{path:?}: lb2011-safe still culls the witness: {r:?}");
        let tri = &cf.case.triangle;
        assert_spot(METHOD_SAFE, tri, &cf.tile, 4000, 77);
        let mut rng = ChaCha8Rng::seed_from_u64(n);
        check_safe_on(tri, &cf.tile, &mut rng);
        n += 1;
    }
    assert!(n >= 2, "only {n} stored cases");
}

#[test]
fn safe_is_not_vacuous() {
    // Far tiles are still culled, the figure-1 strip keeps its size.
    let tri = figure1::triangle();
    for tile in [Tile::square(30.0, -0.5, 1.0), Tile::square(-31.0, -0.5, 1.0), Tile::square(0.0, 10.0, 1.0)] {
        assert!(safe_bounds(&tri, &tile).is_none(), "{tile:?}");
    }
    let tile = figure1::tile();
    let (a, b) = (bounds(&tri, &tile).unwrap(), safe_bounds(&tri, &tile).unwrap());
    for (x, y) in [(a.t, b.t), (a.u, b.u), (a.v, b.v)] {
        assert!(y[0] <= x[0] && x[1] <= y[1], "safe {y:?} inside plain {x:?}");
        assert!(x[0] - y[0] < 1e-5 && y[1] - x[1] < 1e-5, "safe {y:?} much wider than plain {x:?}");
    }
    assert_eq!(a.constraints.len(), b.constraints.len());
    for (u, t, keep) in [(0.0f32, 0.5f32, true), (0.0, 0.45, false), (0.0, 0.56, false), (1.0, 0.7, false)] {
        assert_eq!(b.admits(&Sample::new(0.0, 0.0, u, 0.0, t)), keep, "u {u} t {t}");
    }
    // On the random stress set, safe and plain admit nearly the same samples.
    let mut rng = ChaCha8Rng::seed_from_u64(44);
    let (mut pa, mut sa) = (0usize, 0usize);
    for n in 0..300 {
        let (tri, tile) = random_dual_case(&mut rng, n);
        let (p, s) = (bounds(&tri, &tile), safe_bounds(&tri, &tile));
        for _ in 0..200 {
            let smp = random_sample(&mut rng, &tile);
            pa += p.as_ref().is_some_and(|b| b.admits(&smp)) as usize;
            sa += s.as_ref().is_some_and(|b| b.admits(&smp)) as usize;
        }
        assert_spot(METHOD_SAFE, &tri, &tile, 500, 5000 + n as u64);
    }
    // (Safe may admit a few fewer: its FMA difference is more accurate than plain's.)
    let slack = pa / 1000 + 10;
    assert!(sa + slack >= pa && sa <= pa + slack, "plain admits {pa}, safe {sa}");
    assert!(sa < 300 * 200 * 3 / 4, "safe hardly culls: {sa}");
}

#[test]
fn safe_non_finite_input_never_culls_that_axis() {
    let base = figure1::triangle();
    let far = Tile::square(30.0, -0.5, 1.0); // culled by x only
    assert!(safe_bounds(&base, &far).is_none());
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 3.0e38] {
        let mut tri = base;
        tri.q[1][0] = bad;
        tri.q[1][3] = if bad == 3.0e38 { 1.0e-30 } else { 1.0 };
        let b = safe_bounds(&tri, &far).expect("a non-finite x must not cull");
        assert!(b.constraints.iter().all(|c| c.name().starts_with('y')), "{b:?}");
        assert_eq!(b.u, [-1.0, 1.0]);
        let mut tri = base;
        tri.c1[2] = bad;
        assert!(safe_bounds(&tri, &far).is_some(), "a non-finite CoC must not cull ({bad})");
    }
    let mut tri = base;
    tri.k = f32::NAN;
    assert!(safe_bounds(&tri, &Tile::square(0.0, 10.0, 1.0)).is_some(), "NaN k culls in y");
    assert_degenerate_input_is_answered(METHOD_SAFE, &base);
}

#[test]
fn safe_chord_and_patch_enclose() {
    // Chords: the kept range holds the exact crossing, for extreme magnitudes.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..100_000 {
        let e = |rng: &mut ChaCha8Rng| {
            let m: f32 = rng.gen_range(-1.0..1.0);
            m * 2f32.powi(rng.gen_range(-149..127))
        };
        let (a, b) = (e(&mut rng), e(&mut rng));
        let (some, r) = crate::bounds::la2011::chord::<Outward, Plain>(&Plain, &-a, &-b);
        let r = some.then_some(r);
        let (a64, b64) = (a as f64, b as f64);
        if a < 0.0 && b < 0.0 {
            assert!(r.is_none());
            continue;
        }
        let r = r.unwrap();
        assert!(0.0 <= r[0] && r[0] <= r[1] && r[1] <= 1.0);
        // Where the chord is >= 0 (checked at the crossing, in f64: exact enough here).
        if (a < 0.0) != (b < 0.0) {
            let ts = a64 / (a64 - b64);
            assert!(r[0] as f64 <= ts && ts <= r[1] as f64, "{a} {b}: {ts} not in {r:?}");
        } else {
            assert_eq!(r, [0.0, 1.0]);
        }
    }
    // Patches: eval >= the exact bilinear interpolant of the corners.
    for n in 0..20_000 {
        let scale = 2f32.powi(rng.gen_range(-140..118));
        let g = [[0; 2]; 2].map(|r: [i32; 2]| r.map(|_| rng.gen_range(-1.0f32..1.0) * scale));
        let sp = safe::patch_of::<Outward, Plain>(&Plain, &true, g);
        if !sp.emit {
            continue;
        }
        let [p, q, r, s] = sp.coef;
        let p = Patch { name: "t", lens: Lens::U, p, q, r, s };
        // Never dropped for a magnitude (the error analysis bounds |P'| + |Q| + |R| + |S|
        // by about 6 mg < 2^123).
        assert!(p.usable(), "{p:?}");
        for k in 0..20 {
            let (l, t): (f32, f32) = match (n + k) % 3 {
                0 => ([-1.0, 1.0][k % 2], [0.0, 1.0][(k / 2) % 2]),
                _ => (rng.gen_range(-1.0..=1.0), rng.gen_range(0.0..=1.0)),
            };
            let pt = |x: f32| Interval::point(x as f64);
            let (a, tt) = (pt(l), pt(t));
            let one = pt(1.0);
            let half = pt(0.5);
            let al = (a + one) * half;
            let exact = (one - al) * (one - tt) * pt(g[0][0])
                + al * (one - tt) * pt(g[1][0])
                + (one - al) * tt * pt(g[0][1])
                + al * tt * pt(g[1][1]);
            let v = p.eval(&Sample::new(0.0, 0.0, l, 0.0, t)) as f64;
            assert!(v >= exact.hi, "g {g:?} at ({l}, {t}): eval {v} below {exact:?}");
        }
    }
}

/// The patches' error bound (`error_over`) against the exact value of the patch, where
/// the f32 evaluation underflows: coefficients from 2^-149 to 2^-100 (and some normal
/// ones beside them), lens and time values of every size. Each rounding of the f32
/// evaluation errs by at most 2^-24 of its result or, for a result that underflows, by
/// 2^-150 absolute; the bound allows 4 * 2^-24 of the magnitudes plus 2^-146 (1 + L)(1 +
/// T). Every evaluation must be within it; and the absolute errors seen must exceed what
/// a bound of 2^-152 (1 + L)(1 + T) would allow, or this test could not catch one that
/// is too small.
#[test]
fn the_patch_error_bound_holds_where_the_evaluation_underflows() {
    use oracles::dyadic::Dyadic;
    let mut g = ChaCha8Rng::seed_from_u64(0x5b_7e1);
    let (mut beyond_small, mut n) = (0usize, 0usize);
    let coef = |g: &mut ChaCha8Rng| {
        let e = g.gen_range(-149..-100);
        let m: f32 =
            if g.gen_bool(0.1) { g.gen_range(-1e-3..1e-3) } else { g.gen_range(-2.0f32..2.0) * 2f32.powi(e.max(-126)) };
        let v = if e < -126 { m * 2f32.powi(e + 126) } else { m };
        if g.gen_bool(0.5) {
            v
        } else {
            // A subnormal of any size.
            f32::from_bits(g.gen_range(1u32..0x0080_0000)) * if g.gen_bool(0.5) { 1.0 } else { -1.0 }
        }
    };
    for _ in 0..20_000 {
        let patch =
            Patch { name: "attack", lens: Lens::U, p: coef(&mut g), q: coef(&mut g), r: coef(&mut g), s: coef(&mut g) };
        for _ in 0..10 {
            let l: f32 = if g.gen_bool(0.2) { [-1.0, 1.0, 0.0][g.gen_range(0..3)] } else { g.gen_range(-1.0f32..=1.0) };
            let t: f32 = if g.gen_bool(0.2) { [0.0, 1.0][g.gen_range(0..2)] } else { g.gen_range(0.0f32..=1.0) };
            let s = Sample::new(0.0, 0.0, l, 0.0, t);
            let got = patch.eval(&s);
            let d = |x: f32| Dyadic::from_f64(x as f64);
            let exact = &(&d(patch.p) + &(&d(patch.q) * &d(l))) + &(&d(t) * &(&d(patch.r) + &(&d(patch.s) * &d(l))));
            let diff = (&d(got) - &exact).to_f64().abs();
            let (_, err) = patch.error_over(Interval::point(l as f64), Interval::point(t as f64));
            assert!(
                diff <= err,
                "{patch:?} at l = {l:e}, t = {t:e}: f32 {got:e}, exact {:e}, error {diff:e} above the bound {err:e}",
                exact.to_f64()
            );
            let (mag, _) = patch.error_over(Interval::point(l as f64), Interval::point(t as f64));
            let small = mag * 2f64.powi(-20) + 2f64.powi(-152) * (1.0 + l.abs() as f64) * (1.0 + t as f64);
            beyond_small += (diff > small) as usize;
            n += 1;
        }
    }
    eprintln!("{n} evaluations within the bound; {beyond_small} beyond a bound of 2^-152 (1 + L)(1 + T)");
    assert!(beyond_small > 100, "{beyond_small}");
}
