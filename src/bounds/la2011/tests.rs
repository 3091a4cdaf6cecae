//! The unit tests of `la2011` (a file of their own to keep the method's file to its method).

use super::super::testkit::{
    assert_degenerate_input_is_answered, assert_keeps_covered, assert_spot, bounds_of, random_dual_case,
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
    let b = bounds(&tri, &Tile::square(10.0, 10.0, 4.0)).expect("inside tile culled");
    assert_eq!(b.t, [0.0, 1.0]);
    assert_eq!(b.u, [-1.0, 1.0]);
    assert_eq!(b.v, [-1.0, 1.0]);
}

#[test]
fn far_tiles_are_culled() {
    let tri = figure1::triangle();
    for tile in figure1::far_tiles() {
        assert!(bounds(&tri, &tile).is_none(), "{tile:?}");
    }
    // In-focus static triangle, tile beside it.
    let st = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 0.5, 1.0], [0.0, 10.0, 0.5, 1.0]]);
    assert!(bounds(&st, &Tile::square(11.0, 0.0, 1.0)).is_none());
    assert!(bounds(&st, &Tile::square(9.0, 0.0, 1.0)).is_some());
}

#[test]
fn figure1_la_box_is_coarse() {
    let tri = figure1::triangle();
    let tile = figure1::tile();
    let b = bounds(&tri, &tile).unwrap();
    let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
    assert!(close(b.u, figure1::LA_U), "u {:?}", b.u);
    assert!(close(b.t, figure1::LA_T), "t {:?}", b.t);
    assert!(close(b.v, figure1::LA_V), "v {:?}", b.v);
    // Only a diagonal strip of the (u, t) box is covered: samples with v = 0 and the
    // tile centre hit the triangle iff |-20 + 40 t + 8 u| < ~1, a strip of width
    // ~2/40 in t, while the box is 0.475 wide.
    let o = tri.to_oracle();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut inbox, mut hit) = (0, 0);
    for _ in 0..20000 {
        let s = Sample::new(0.0, 0.0, rng.gen_range(-1.0..=1.0), 0.0, rng.gen_range(0.0..=1.0));
        if b.admits(&s) {
            inbox += 1;
            hit += (oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior) as usize;
        }
    }
    let frac = hit as f64 / inbox as f64;
    assert!(frac > 0.05 && frac < 0.2, "covered fraction of the LA box {frac}");
    let (covered, _) = spot_check(&tri, &tile, 20000, 8);
    assert!(covered > 20);
}

#[test]
fn perspective_motion_time_bound_is_conservative_and_cuts() {
    // Approaching the camera (w 10 -> 1): screen motion accelerates; linear in clip
    // space. Tile near the end position.
    let tri = Triangle {
        q: [[0.0, 0.0, 0.5, 10.0], [20.0, 0.0, 0.5, 10.0], [0.0, 20.0, 0.5, 10.0]],
        r: [[30.0, 0.0, 0.5, 1.0], [32.0, 0.0, 0.5, 1.0], [30.0, 2.0, 0.5, 1.0]],
        c0: [0.5; 3],
        c1: [-0.5; 3],
        k: 1.0,
    };
    // Screen x of vertex 0 is 30 t / (10 - 9 t): it reaches the tile at t ~ 0.8.
    let tile = Tile::square(9.0, 0.0, 2.0);
    let b = bounds(&tri, &tile).unwrap();
    eprintln!("perspective: {b:?}");
    assert!(b.t[0] > 0.5 && b.t[1] < 1.0, "t {:?}", b.t);
    let (covered, _) = spot_check(&tri, &tile, 20000, 3);
    assert!(covered > 50);
}

#[test]
fn no_covered_sample_is_culled() {
    let mut seed = 100;
    let mut total = 0;
    let mut tris = cases::hard_triangles();
    tris.push(figure1::triangle());
    for tri in &tris {
        for tx in -6..6 {
            for ty in -6..6 {
                let tile = Tile::square(tx as f32 * 5.0, ty as f32 * 5.0, 5.0);
                total += spot_check(tri, &tile, 300, seed).0;
                seed += 1;
            }
        }
    }
    assert!(total > 2000, "too few covered samples: {total}");
}

#[test]
fn random_triangles_are_never_culled_where_covered() {
    // Random moving, defocused triangles (some with w <= 0, some with per-vertex
    // CoC); tiles centred on a projected vertex so that coverage happens.
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let (mut total, mut admitted) = (0, 0);
    for n in 0..300 {
        let (tri, tile) = random_dual_case(&mut rng, n);
        let (c, a) = spot_check(&tri, &tile, 2000, 1000 + n as u64);
        total += c;
        admitted += a;
    }
    eprintln!("random: covered {total}, admitted {admitted} of {}", 300 * 2000);
    assert!(total > 10000, "too few covered samples: {total}");
    assert!(admitted < 300 * 2000 * 9 / 10, "the bounds hardly cut: {admitted}");
}

#[test]
fn degenerate_input_does_not_panic() {
    assert_degenerate_input_is_answered(METHOD, &figure1::triangle());
}

// --- la2011-safe ---

fn safe(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    bounds_of(METHOD_SAFE, tri, tile)
}

/// `inner` lies in `outer`.
fn within(inner: [f32; 2], outer: [f32; 2]) -> bool {
    outer[0] <= inner[0] && inner[1] <= outer[1]
}

/// Every stored case where la2011 culls a covered sample (f32 interval ends, far from
/// the origin at ~1e6 px where it culls a covered tile outright, the tile reject at
/// its limit): the witness still holds against la2011, and la2011-safe admits it and
/// keeps every covered sample of the tile.
#[test]
fn safe_admits_every_corpus_witness_of_la2011() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/la2011");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let cf = crate::search::CaseFile::load(&path).unwrap();
        let Some(w) = &cf.witness else { continue };
        let holds = crate::search::witness_holds(METHOD, &cf.case, &cf.tile, w.sample);
        assert!(holds.is_ok(), "{}: la2011 no longer violates: {holds:?}", path.display());
        let safe_holds = crate::search::witness_holds(METHOD_SAFE, &cf.case, &cf.tile, w.sample);
        assert_eq!(safe_holds, Err("the method admits the witness".into()), "{}", path.display());
        let p = METHOD_SAFE.setup(&cf.case.triangle);
        assert_keeps_covered(p.as_ref(), &cf.case.triangle, &cf.tile, (2000, 300), 500 + n, "la2011-safe");
        n += 1;
    }
    assert!(n >= 8, "only {n} witnesses");
    // The far-from-origin case (static, in focus, ~1e6 px): la2011 culls the tile.
    let far = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/la2011/a07b6967125ee645.json");
    let cf = crate::search::CaseFile::load(&far).unwrap();
    assert!(bounds(&cf.case.triangle, &cf.tile).is_none());
    assert!(safe(&cf.case.triangle, &cf.tile).is_some());
}

/// The real-arithmetic algorithm of this file evaluated in f64, on the exact shears
/// `s[e][i]` (a product of two f32 values is exact in f64; every other f64 operation
/// is correctly rounded, 2^-29 of an f32 step, so the reference sits far inside the
/// one-step margins of la2011-safe unless it is exact).
fn reference(ax: &Axis<f32, bool>, s: [[f64; 3]; 2], lo: f32, hi: f32) -> Option<([f64; 2], [f64; 2])> {
    let d = |e: usize, i: usize, x: f32| ax.p[e][i] as f64 - x as f64 * ax.w[e][i] as f64;
    let (mut f, mut g) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (e, se) in s.iter().enumerate() {
        for (i, si) in se.iter().enumerate() {
            for x in [lo, hi] {
                f[e] = f[e].min(d(e, i, x) - si.abs());
                g[e] = g[e].max(d(e, i, x) + si.abs());
            }
        }
    }
    let chord = |l0: f64, l1: f64| -> Option<[f64; 2]> {
        let t = || (l0 / (l0 - l1)).clamp(0.0, 1.0);
        if l0 > 0.0 && l1 > 0.0 {
            None
        } else if l0 > 0.0 {
            Some([t(), 1.0])
        } else if l1 > 0.0 {
            Some([0.0, t()])
        } else {
            Some([0.0, 1.0])
        }
    };
    let (tf, tg) = (chord(f[0], f[1])?, chord(-g[0], -g[1])?);
    let t = [tf[0].max(tg[0]), tf[1].min(tg[1])];
    if t[0] > t[1] {
        return None;
    }
    // {u : d + u s < 0} over the shutter, per (i, X), for d, s at both ends.
    let hull = |d: [f64; 2], s: [f64; 2]| -> Option<[f64; 2]> {
        let th = |e: usize| -d[e] / s[e];
        if s[0] > 0.0 && s[1] > 0.0 {
            Some([f64::NEG_INFINITY, th(0).max(th(1))])
        } else if s[0] < 0.0 && s[1] < 0.0 {
            Some([th(0).min(th(1)), f64::INFINITY])
        } else if s[0] == 0.0 && s[1] == 0.0 {
            (d[0] < 0.0 || d[1] < 0.0).then_some([f64::NEG_INFINITY, f64::INFINITY])
        } else {
            Some([f64::NEG_INFINITY, f64::INFINITY])
        }
    };
    let (mut ha, mut hb) = (None::<[f64; 2]>, None::<[f64; 2]>);
    let join = |h: &mut Option<[f64; 2]>, r: Option<[f64; 2]>| {
        if let Some(r) = r {
            *h = Some(h.map_or(r, |h| [h[0].min(r[0]), h[1].max(r[1])]));
        }
    };
    for (i, ss) in (0..3).map(|i| (i, [s[0][i], s[1][i]])) {
        for x in [lo, hi] {
            let dd = [d(0, i, x), d(1, i, x)];
            join(&mut ha, hull(dd, ss));
            join(&mut hb, hull([-dd[0], -dd[1]], [-ss[0], -ss[1]]));
        }
    }
    let (ha, hb) = (ha?, hb?);
    let lens = [ha[0].max(hb[0]).max(-1.0), ha[1].min(hb[1]).min(1.0)];
    (lens[0] <= lens[1]).then_some((t, lens))
}

/// The f32 interval evaluation encloses the real-arithmetic answer for random axes of
/// every scale (subnormal to 1e30 coordinates and shears, w of either sign, exactly
/// 0, tiny or huge, shears crossing or touching 0, tile columns up to 1e6 px): it
/// culls only when the reference does, and its t and lens ranges hold the
/// reference's.
#[test]
fn safe_encloses_the_real_arithmetic_answer() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x1a2011);
    let mut both_cut = 0;
    for n in 0..60_000 {
        let scale = [1e-40f32, 1e-20, 1e-3, 1.0, 30.0, 1e3, 1e6, 1e15, 1e30][n % 9];
        let val = |rng: &mut ChaCha8Rng| -> f32 {
            match rng.gen_range(0..10) {
                0 => 0.0,
                1 => scale * rng.gen_range(-1..=1) as f32,
                _ => rng.gen_range(-1.0f32..1.0) * scale,
            }
        };
        let mut tri = figure1::triangle();
        for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
            p[0] = val(&mut rng);
            p[1] = val(&mut rng);
            p[3] = match rng.gen_range(0..6) {
                0 => 0.0,
                1 => rng.gen_range(-1e-6f32..1e-6),
                2 => rng.gen_range(-3.0f32..3.0),
                _ => rng.gen_range(0.01f32..4.0) * 10f32.powi(rng.gen_range(-3..4)),
            };
        }
        for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
            *c = val(&mut rng);
        }
        tri.k = [1.0f32, 0.7, 1.3, 1e-3][n % 4];
        let at = rng.gen_range(-1.0f32..1.0) * [0.0f32, 1.0, 1e2, 1e4, 1e6][n % 5];
        let size = [1e-3f32, 1.0, 4.0, 16.0][n % 4];
        let (lo, hi) = (at, at + size);
        for (axis, k) in [(0usize, 1.0f32), (1, tri.k)] {
            let ax = axis_of::<Outward, Plain>(&Plain, &TriOf::of(&tri), axis);
            let s = [tri.c0.map(|c| k as f64 * c as f64), tri.c1.map(|c| k as f64 * c as f64)];
            let got = bounds_f32::<Outward>(&ax, &[lo, hi]);
            let want = reference(&ax, s, lo, hi);
            match (got, want) {
                (None, Some(w)) => panic!("axis {axis} [{lo}, {hi}] culled, exact {w:?}: {tri:?}"),
                (Some((t, u)), Some((wt, wu))) => {
                    let (t, u) = (t.map(|x| x as f64), u.map(|x| x as f64));
                    assert!(t[0] <= wt[0] && wt[1] <= t[1], "axis {axis} t {t:?} exact {wt:?}: {tri:?} [{lo}, {hi}]");
                    assert!(
                        u[0] <= wu[0] && wu[1] <= u[1],
                        "axis {axis} lens {u:?} exact {wu:?}: {tri:?} [{lo}, {hi}]"
                    );
                    both_cut += (t != [0.0, 1.0] || u != [-1.0, 1.0]) as usize;
                }
                (None, None) => both_cut += 1,
                (Some(_), None) => {}
            }
        }
    }
    assert!(both_cut > 20_000, "the safe bounds hardly cut: {both_cut}");
}

/// la2011-safe's answer holds la2011's (each of its values encloses the one rounded
/// to nearest), so it culls a tile only where la2011 does; and it stays close:
/// nearly every tile la2011 culls is culled, and its intervals are barely wider.
#[test]
fn safe_contains_la2011_and_stays_close() {
    let mut rng = ChaCha8Rng::seed_from_u64(4242);
    let (mut culls, mut safe_culls, mut extra) = (0, 0, 0.0f64);
    let mut tris: Vec<(Triangle, Tile)> = (0..3000).map(|n| random_dual_case(&mut rng, n)).collect();
    for tri in cases::hard_triangles() {
        for tx in -6..6 {
            for ty in -6..6 {
                tris.push((tri, Tile::square(tx as f32 * 5.0, ty as f32 * 5.0, 5.0)));
            }
        }
    }
    for (tri, tile) in &tris {
        match (bounds(tri, tile), safe(tri, tile)) {
            (Some(o), Some(s)) => {
                assert!(within(o.u, s.u) && within(o.v, s.v) && within(o.t, s.t), "{o:?} not in {s:?}");
                extra += [(o.u, s.u), (o.v, s.v), (o.t, s.t)]
                    .iter()
                    .map(|(a, b)| ((b[1] - b[0]) - (a[1] - a[0])) as f64)
                    .sum::<f64>();
            }
            (Some(o), None) => panic!("la2011-safe culls where la2011 keeps {o:?}: {tri:?} {tile:?}"),
            (None, s) => {
                culls += 1;
                safe_culls += s.is_none() as usize;
            }
        }
    }
    eprintln!("la2011 culls {culls}, la2011-safe {safe_culls}; mean extra width {}", extra / tris.len() as f64);
    assert!(culls > 200 && safe_culls * 100 >= culls * 99, "culls {culls} vs safe {safe_culls}");
    assert!(extra / (tris.len() as f64) < 1e-4, "mean extra width {}", extra / tris.len() as f64);
}

/// Moves a triangle on screen by `(dx, dy)` px (in clip space: `x += dx w`) and
/// scales its screen size and CoC by `f`.
fn moved(tri: &Triangle, dx: f32, dy: f32, f: f32) -> Triangle {
    let mut t = *tri;
    for p in t.q.iter_mut().chain(t.r.iter_mut()) {
        p[0] = p[0] * f + dx * p[3];
        p[1] = p[1] * f + dy * p[3];
    }
    t.c0 = t.c0.map(|c| c * f);
    t.c1 = t.c1.map(|c| c * f);
    t
}

/// Uniform and near-miss samples (every covered one must be kept) on the hard
/// triangles moved far from the origin (1e4 .. 1e6 px), shrunk to 1e-3 (tiny),
/// grown 1e4-fold (huge), with a vertex at w ~ 0 or crossing it, and with CoCs
/// crossing and touching 0 (the focal plane), on a grid of tiles around each
/// projected vertex.
#[test]
fn safe_keeps_covered_samples_at_every_scale() {
    let mut family: Vec<(&str, Triangle, f32)> = Vec::new();
    let mut hard = cases::hard_triangles();
    hard.push(figure1::triangle());
    for (n, tri) in hard.iter().enumerate() {
        family.push(("plain", *tri, 1.0));
        for (dx, dy) in [(1.0e4f32, -3.0e4f32), (2.5e5, 1.0e5), (-1.0e6, 7.0e5)] {
            family.push(("far from origin", moved(tri, dx, dy, 1.0), 1.0));
        }
        family.push(("tiny", moved(tri, 0.0, 0.0, 1e-3), 1e-3));
        family.push(("huge", moved(tri, 0.0, 0.0, 1e4), 1e4));
        let mut w0 = *tri;
        w0.q[n % 3][3] = 1e-7;
        w0.r[n % 3][3] = -1e-7;
        family.push(("w crossing 0", w0, 1.0));
        let mut w1 = *tri;
        w1.r[(n + 1) % 3][3] = 1e-30;
        family.push(("w near 0", w1, 1.0));
        let mut focal = *tri;
        focal.c0 = [2.0, -1.5, 0.0];
        focal.c1 = [-1.0, 1e-30, 0.0];
        family.push(("focal plane", focal, 1.0));
    }
    let (mut covered, mut seed) = (0, 7000);
    for (what, tri, f) in &family {
        let p = METHOD_SAFE.setup(tri);
        for e in 0..2 {
            for i in 0..3 {
                let v = if e == 0 { tri.q[i] } else { tri.r[i] };
                if v[3] <= 0.05 {
                    continue;
                }
                let (cx, cy) = (v[0] / v[3], v[1] / v[3]);
                let size = 4.0 * f;
                for gx in -1..=1 {
                    for gy in -1..=1 {
                        let tile = Tile::square(cx + gx as f32 * size, cy + gy as f32 * size, size);
                        covered += assert_keeps_covered(p.as_ref(), tri, &tile, (150, 20), seed, what).0;
                        seed += 2;
                    }
                }
            }
        }
    }
    assert!(covered > 5000, "too few covered samples: {covered}");
}

/// Not vacuous: far tiles are culled, figure 1's bounds are LA's within a few ulps,
/// a static triangle keeps the whole time range inside, perspective motion still
/// cuts time, a moderately far (1e5 px) triangle still gets lens bounds.
#[test]
fn safe_is_not_vacuous() {
    let tri = figure1::triangle();
    for tile in figure1::far_tiles() {
        assert!(safe(&tri, &tile).is_none(), "{tile:?}");
    }
    let b = safe(&tri, &figure1::tile()).unwrap();
    let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
    assert!(close(b.u, figure1::LA_U) && close(b.t, figure1::LA_T) && close(b.v, figure1::LA_V), "{b:?}");
    let st = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 0.5, 1.0], [0.0, 10.0, 0.5, 1.0]]);
    assert!(safe(&st, &Tile::square(11.0, 0.0, 1.0)).is_none());
    let b = safe(&st, &Tile::square(2.0, 2.0, 1.0)).unwrap();
    assert_eq!((b.t, b.u, b.v), ([0.0, 1.0], [-1.0, 1.0], [-1.0, 1.0]));
    // Perspective approach (as in perspective_motion_time_bound_is_conservative_and_cuts).
    let persp = Triangle {
        q: [[0.0, 0.0, 0.5, 10.0], [20.0, 0.0, 0.5, 10.0], [0.0, 20.0, 0.5, 10.0]],
        r: [[30.0, 0.0, 0.5, 1.0], [32.0, 0.0, 0.5, 1.0], [30.0, 2.0, 0.5, 1.0]],
        c0: [0.5; 3],
        c1: [-0.5; 3],
        k: 1.0,
    };
    let b = safe(&persp, &Tile::square(9.0, 0.0, 2.0)).unwrap();
    assert!(b.t[0] > 0.5 && b.t[1] < 1.0, "t {:?}", b.t);
    // Figure 1 moved 1e5 px away: the enclosures are ~1/64 px wide, the lens and
    // time bounds move by ~1e-3.
    let far = moved(&tri, 1.0e5, -1.0e5, 1.0);
    let tile = Tile { x0: 1.0e5 - 0.5, y0: -1.0e5 - 0.5, x1: 1.0e5 + 0.5, y1: -1.0e5 + 0.5 };
    let b = safe(&far, &tile).unwrap();
    assert!(b.v[1] - b.v[0] < 0.4 && b.t[1] - b.t[0] < 0.5, "{b:?}");
    assert!(safe(&far, &Tile { x0: 1.0e5 + 30.0, x1: 1.0e5 + 31.0, ..tile }).is_none());
}

/// NaN or an infinity in any input gives the full domain for every tile (never a
/// cull), and degenerate or huge input is answered inside the domain.
#[test]
fn safe_non_finite_input_gives_full_bounds() {
    let full = |b: Option<TileBounds>| {
        let b = b.expect("culled");
        (b.u, b.v, b.t) == ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0])
    };
    let base = figure1::triangle();
    let far = Tile::square(1000.0, 1000.0, 1.0);
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for field in 0..9 {
            let mut t = base;
            match field {
                0 => t.q[1][0] = bad,
                1 => t.q[2][1] = bad,
                2 => t.r[0][3] = bad,
                3 => t.q[0][2] = bad,
                4 => t.c0[1] = bad,
                5 => t.c1[2] = bad,
                6 => t.k = bad,
                7 => t.r[2][0] = bad,
                _ => t.q[1][3] = bad,
            }
            assert!(full(safe(&t, &far)), "field {field} = {bad}");
            assert!(full(safe(&t, &figure1::tile())), "field {field} = {bad}");
        }
        let tile = Tile { x1: bad, ..far };
        assert!(full(safe(&base, &tile)), "tile x1 = {bad}");
    }
    assert_degenerate_input_is_answered(METHOD_SAFE, &base);
    let random = |n| random_dual_case(&mut ChaCha8Rng::seed_from_u64(n), n as usize);
    for n in 0..50 {
        let (tri, _) = random(n);
        assert_degenerate_input_is_answered(METHOD_SAFE, &tri);
    }
}

/// The random stress set of `random_triangles_are_never_culled_where_covered`, for
/// la2011-safe, with near-miss samples just beyond each bound.
#[test]
fn safe_random_triangles_are_never_culled_where_covered() {
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let mut total = 0;
    for n in 0..300 {
        let (tri, tile) = random_dual_case(&mut rng, n);
        let p = METHOD_SAFE.setup(&tri);
        total += assert_keeps_covered(p.as_ref(), &tri, &tile, (1000, 200), 3000 + 2 * n as u64, "random").0;
    }
    assert!(total > 5000, "too few covered samples: {total}");
}
