//! The unit tests of `gdam2010` (a file of their own to keep the method's file to its method).

use super::super::testkit::assert_spot;
use super::safe::*;
use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn bounds(tri: &Triangle, tile: &Tile) -> TileBounds {
    match METHOD.setup(tri).tile(tile) {
        TileResult::Empty => panic!("gdam2010 never answers empty"),
        TileResult::Bounds(b) => b,
    }
}

/// A triangle moving in x, y and depth (so the edge quadratics are really quadratic).
/// A triangle that changes facing during the shutter: vertex 2 crosses edge 01.
fn flip() -> Triangle {
    Triangle {
        q: [[0.0, 0.0, 0.0, 1.0], [40.0, 0.0, 0.0, 1.0], [20.0, 30.0, 0.0, 1.0]],
        r: [[0.0, 10.0, 0.0, 1.0], [40.0, 10.0, 0.0, 1.0], [25.0, -20.0, 0.0, 1.0]],
        c0: [0.0; 3],
        c1: [0.0; 3],
        k: 1.0,
    }
}

fn moving() -> Triangle {
    let q = [[10.0, 10.0, 0.5, 1.0], [50.0, 14.0, 0.5, 1.0], [18.0, 44.0, 0.6, 1.0]];
    let r = [[60.0, 30.0, 1.0, 2.0], [100.0, 70.0, 1.0, 2.5], [40.0, 90.0, 1.2, 1.6]];
    Triangle { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 }
}

fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> (usize, usize) {
    assert_spot(METHOD, tri, tile, n, seed)
}

#[test]
fn static_triangle_keeps_whole_time_range() {
    let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0]]);
    let p = METHOD.setup(&tri);
    assert_eq!(p.disabled(), None);
    let b = bounds(&tri, &Tile::square(10.0, 10.0, 4.0));
    assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
    for t in [0.0, 0.3, 1.0] {
        assert!(b.admits(&Sample::new(12.0, 12.0, 0.0, 0.0, t)));
    }
    let sp = TimeSpans::new(&tri).spans_at(12.0, 12.0);
    assert_eq!(sp.as_slice(), &[[0.0, 1.0]]);
    // Clockwise winding too.
    let cw = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0]]);
    assert_eq!(TimeSpans::new(&cw).spans_at(12.0, 12.0).as_slice(), &[[0.0, 1.0]]);
}

#[test]
fn far_sample_is_culled() {
    let tri = moving();
    let b = bounds(&tri, &Tile::square(500.0, 500.0, 8.0));
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..200 {
        let s =
            Sample::new(rng.gen_range(500.0..508.0), rng.gen_range(500.0..508.0), 0.0, 0.0, rng.gen_range(0.0..=1.0));
        assert!(!b.admits(&s));
    }
}

#[test]
fn defocus_is_disabled() {
    let mut tri = moving();
    tri.c1[2] = 0.5;
    let p = METHOD.setup(&tri);
    assert_eq!(p.disabled(), Some("defocus: gdam2010 is motion-only"));
    match p.tile(&Tile::square(0.0, 0.0, 4.0)) {
        TileResult::Bounds(b) => assert!(b.constraints.is_empty() && b.t == [0.0, 1.0]),
        TileResult::Empty => panic!(),
    }
}

#[test]
fn conservative_on_moving_triangles() {
    let tri = moving();
    let mut flipped = moving();
    flipped.q.swap(1, 2);
    flipped.r.swap(1, 2);
    let flip = flip();
    let mut total = 0;
    for (tri, tiles) in [
        (
            tri,
            vec![
                Tile::square(30.0, 30.0, 8.0),
                Tile::square(55.0, 40.0, 4.0),
                Tile { x0: 20.3, y0: 19.7, x1: 21.1, y1: 20.9 },
            ],
        ),
        (flipped, vec![Tile::square(30.0, 30.0, 8.0), Tile::square(60.0, 50.0, 2.0)]),
        (flip, vec![Tile::square(16.0, 0.0, 8.0), Tile::square(20.0, -8.0, 4.0)]),
    ] {
        for (i, tile) in tiles.iter().enumerate() {
            let (c, a) = spot_check(&tri, tile, 4000, i as u64 + 7);
            assert!(a >= c);
            total += c;
        }
    }
    assert!(total > 1000, "too few covered samples to mean anything: {total}");
}

/// The longest runs of t on which the f32 set and the exact set disagree:
/// (exact covered but f32 not: the non-conservative side, f32 only: the extra side).
fn longest_disagreement(ours: &[[f32; 2]], exact: &[[f64; 2]]) -> (f64, f64) {
    let mut pts: Vec<f64> = vec![0.0, 1.0];
    pts.extend(ours.iter().flat_map(|s| [s[0] as f64, s[1] as f64]));
    pts.extend(exact.iter().flat_map(|s| [s[0], s[1]]));
    pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let inside_o = |t: f64| ours.iter().any(|s| s[0] as f64 <= t && t <= s[1] as f64);
    let inside_e = |t: f64| exact.iter().any(|s| s[0] <= t && t <= s[1]);
    let (mut run, mut worst) = ([0.0f64; 2], [0.0f64; 2]);
    for w in pts.windows(2) {
        if w[1] <= w[0] {
            continue;
        }
        let mid = 0.5 * (w[0] + w[1]);
        let (o, e) = (inside_o(mid), inside_e(mid));
        for (k, differs) in [e && !o, o && !e].into_iter().enumerate() {
            if differs {
                run[k] += w[1] - w[0];
                worst[k] = worst[k].max(run[k]);
            } else {
                run[k] = 0.0;
            }
        }
    }
    (worst[0], worst[1])
}

/// Agreement over a grid of pixel centres (every `step` pixels).
#[derive(Debug, Default)]
struct Agreement {
    pixels: usize,
    covered_pixels: usize,
    count_differences: usize,
    /// Longest run of exact-covered times the f32 set misses, and where.
    lost: f64,
    lost_at: String,
    /// Longest run of f32-only times, and where.
    extra: f64,
    extra_at: String,
}

fn compare_with_oracle(tri: &Triangle, xs: std::ops::Range<i32>, ys: std::ops::Range<i32>, step: usize) -> Agreement {
    let ts = TimeSpans::new(tri);
    let o = tri.to_oracle();
    let mut a = Agreement::default();
    for py in ys.step_by(step) {
        for px in xs.clone().step_by(step) {
            let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
            let exact = oracles::timeline::covered_spans(&o, x as f64, y as f64, 0.0, 0.0, 1e-12);
            let ours = ts.spans_at(x, y);
            a.pixels += 1;
            a.covered_pixels += !exact.is_empty() as usize;
            let ex: Vec<[f64; 2]> = exact.iter().map(|s| [s.start.lo, s.end.hi]).collect();
            a.count_differences += (ours.n != ex.len()) as usize;
            let (lost, extra) = longest_disagreement(ours.as_slice(), &ex);
            let at = || format!("pixel ({x}, {y}): f32 {:?} exact {ex:?}", ours.as_slice());
            if lost > a.lost {
                a.lost = lost;
                a.lost_at = at();
            }
            if extra > a.extra {
                a.extra = extra;
                a.extra_at = at();
            }
        }
    }
    a
}

fn shifted(tri: &Triangle, o: f32) -> Triangle {
    let f = |p: [f32; 4]| [p[0] + o * p[3], p[1] + o * p[3], p[2], p[3]];
    Triangle { q: tri.q.map(f), r: tri.r.map(f), ..*tri }
}

#[test]
fn agrees_with_exact_time_spans() {
    let flip = flip();
    // (name, triangle, grid, step, largest allowed disagreement)
    let cases = [
        ("moving, near the origin", moving(), (0..110, 0..100), 1, 1e-4),
        ("facing flip", flip, (-5..45, -25..35), 1, 1e-4),
        ("moving, screen offset 1000", shifted(&moving(), 1000.0), (1000..1110, 1000..1100), 2, 1e-2),
    ];
    for (name, tri, (xs, ys), step, tol) in cases {
        let a = compare_with_oracle(&tri, xs, ys, step);
        eprintln!(
            "gdam2010 vs oracle, {name}: {} pixel centres, {} covered, {} span-count differences; \
             longest lost run {:e} at {}; longest extra run {:e} at {}",
            a.pixels, a.covered_pixels, a.count_differences, a.lost, a.lost_at, a.extra, a.extra_at
        );
        assert!(a.covered_pixels > 100);
        assert!(a.lost < tol && a.extra < tol, "{name}: {a:?}");
    }
}

/// `eval_box` of a point (x, y) with a range of t, and of a box 2 px wide in x,
/// encloses `eval` at 9 times of the range, at `n` random pixels.
fn assert_eval_box_encloses_eval(ts: &dyn SampleConstraint, seed: u64, n: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..n {
        let (x, y) = (rng.gen_range(0.0f32..110.0), rng.gen_range(0.0f32..100.0));
        let (t0, t1) = (rng.gen_range(0.0f32..1.0), rng.gen_range(0.0f32..1.0));
        let (t0, t1) = (t0.min(t1), t0.max(t1));
        let pt = |v: f32| Interval::point(v as f64);
        let bx = SampleBox { x: pt(x), y: pt(y), u: pt(0.0), v: pt(0.0), t: Interval::new(t0 as f64, t1 as f64) };
        let wide = SampleBox { x: Interval::new(x as f64 - 1.0, x as f64 + 1.0), ..bx };
        let (e, w) = (ts.eval_box(&bx), ts.eval_box(&wide));
        for k in 0..=8 {
            let t = (t0 + (t1 - t0) * k as f32 / 8.0).clamp(t0, t1);
            let g = ts.eval(&Sample::new(x, y, 0.0, 0.0, t)) as f64;
            assert!(e.contains(g) && w.contains(g), "{g} not in {e:?} / {w:?}");
        }
    }
}

#[test]
fn eval_box_encloses_eval() {
    assert_eval_box_encloses_eval(&TimeSpans::new(&moving()), 11, 2000);
}

/// The time sets of `gdam2010-safe` without its pad are those of its code before it was
/// restructured, bit for bit (the fingerprint of every answer, recorded while the old
/// code still ran beside it), on the stress stream of the bit-identity tests, at positions in the
/// case's tiles and at odd ones (infinities, NaN, huge, subnormal, -0).
#[test]
fn safe_spans_are_their_old_code_bit_for_bit() {
    let odd = [f32::NAN, f32::INFINITY, -f32::INFINITY, 3.0e38, -0.0, 1.0e-40, f32::MAX];
    let (mut n_all, mut partial, mut split, mut fixed) = (0, 0, 0, [0, 0]);
    let mut fp = super::super::testkit::Fingerprint::new();
    for n in 0..20_000 {
        let (mut tri, tiles) = crate::cases::generate::bit_compare_case(91, n);
        if n % 2 == 1 {
            // A triangle that does not move (the fast path of `spans_at`).
            (tri.r, tri.c1) = (tri.q, tri.c0);
        }
        let s = SafeTimeSpans::new(&tri);
        let mut rng = crate::cases::generate::rng_for(92, n as u64);
        for tile in &tiles {
            for k in 0..4 {
                let (fx, fy): (f32, f32) = (rng.gen(), rng.gen());
                let y = tile.y0 + fy * (tile.y1 - tile.y0);
                let x = match k {
                    3 => odd[rng.gen_range(0..odd.len())],
                    _ => tile.x0 + fx * (tile.x1 - tile.x0),
                };
                let new = s.spans_with(x, y, false);
                fp.add(&format!("{new:?}"));
                n_all += 1;
                if n % 2 == 1 && x.is_finite() {
                    fixed[(new.n > 0) as usize] += 1;
                }
                partial += (new.n > 0 && new.as_slice() != [[0.0, 1.0]]) as usize;
                split += (new.n > 1) as usize;
            }
        }
    }
    assert_eq!(
        fp.value(),
        0x5d8a_c939_fe1e_9537,
        "the answers on the stress stream are no longer those of the code before it was restructured \
         (recorded 2026-12-06 while both ran side by side and agreed)"
    );
    assert!(n_all >= 160_000 && partial > 5_000 && split > 100, "{n_all} {partial} {split}");
    assert!(fixed[0] > 1000 && fixed[1] > 1000, "still triangles: {fixed:?} (culled, kept)");
}

#[test]
fn signed_distance_definition() {
    let sp = Spans { n: 2, s: [[0.1, 0.3], [0.6, 1.0], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]] };
    assert_eq!(sp.signed_distance(0.2), 0.1f32.min(0.3 - 0.2));
    assert!(sp.signed_distance(0.45) < 0.0);
    assert_eq!(sp.signed_distance(0.6), 0.0);
    assert_eq!(sp.signed_distance(0.0), -0.1);
    let empty = Spans { n: 0, s: [[0.0; 2]; 8] };
    assert_eq!(empty.signed_distance(0.5), -1.0);
}

/// An edge that grazes the pixel (o, o): relative to the pixel,
/// `A(t) = (-10 + t, -19 + d)`, `B(t) = (19, 36 + 4t)`, C fixed at (20, -20), so
/// `E_AB = 4 (t - 1/2)^2 - 19 d` and the pixel is covered only for
/// `|t - 1/2| < sqrt(19 d / 4)` (the other two edges stay negative). `d` is a few
/// ulps of `o - 19`. Returns (d, exact spans, f32 spans) per d.
type Grazing = (f32, Vec<[f64; 2]>, Vec<[f32; 2]>);

fn grazing(o: f32, steps: &[i32]) -> Vec<Grazing> {
    let mut out = Vec::new();
    for &k in steps {
        let ay = {
            let mut v = o - 19.0f32;
            for _ in 0..k {
                v = v.next_up();
            }
            v
        };
        let d = ay - (o - 19.0);
        let tri = Triangle {
            q: [[o - 10.0, ay, 0.0, 1.0], [o + 19.0, o + 36.0, 0.0, 1.0], [o + 20.0, o - 20.0, 0.0, 1.0]],
            r: [[o - 9.0, ay, 0.0, 1.0], [o + 19.0, o + 40.0, 0.0, 1.0], [o + 20.0, o - 20.0, 0.0, 1.0]],
            c0: [0.0; 3],
            c1: [0.0; 3],
            k: 1.0,
        };
        let exact: Vec<[f64; 2]> =
            oracles::timeline::covered_spans(&tri.to_oracle(), o as f64, o as f64, 0.0, 0.0, 1e-12)
                .iter()
                .map(|s| [s.start.lo, s.end.hi])
                .collect();
        let ours = TimeSpans::new(&tri).spans_at(o, o).as_slice().to_vec();
        out.push((d, exact, ours));
    }
    out
}

#[test]
fn near_double_root_is_where_f32_is_fragile() {
    let (mut lost, mut spans, mut worst) = (0, 0, 0.0f64);
    for o in [10.5f32, 100.5, 1000.5] {
        for (d, exact, ours) in grazing(o, &[0, 1, 2, 4, 8, 16, 64, 256]) {
            eprintln!("grazing edge at pixel {o}, d = {d:e}: exact {exact:?}, f32 {ours:?}");
            if d > 0.0 {
                // The exact set is one span around 1/2 of half-width sqrt(19 d / 4).
                assert_eq!(exact.len(), 1);
                let hw = (19.0 * d as f64 / 4.0).sqrt();
                assert!((exact[0][0] - (0.5 - hw)).abs() < 1e-9 && (exact[0][1] - (0.5 + hw)).abs() < 1e-9);
                spans += 1;
                match ours.as_slice() {
                    [] => lost += 1,
                    [s] => worst = worst.max((s[0] as f64 - exact[0][0]).abs()).max((s[1] as f64 - exact[0][1]).abs()),
                    _ => panic!("split span {ours:?}"),
                }
            } else {
                assert!(exact.is_empty());
            }
        }
    }
    eprintln!("grazing edge: {lost} of {spans} covered spans lost in f32, largest end error of the others {worst:e}");
    // Generic pixels err by ~1e-7 (agrees_with_exact_time_spans); here far more.
    assert!(worst > 1e-5 || lost > 0);
}

#[test]
fn degenerate_and_huge_input_is_answered_in_the_domain() {
    super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    let mut tri = super::super::la2011::figure1::triangle();
    (tri.c0, tri.c1) = ([0.0; 3], [0.0; 3]);
    super::super::testkit::assert_degenerate_input_is_answered(METHOD_SAFE, &tri);
    // Overflowing products (coordinates near f32::MAX) and a NaN vertex: no panic,
    // nothing culled on NaN.
    let mut huge = moving();
    huge.q[0] = [3.0e38, -3.0e38, 0.5, 1.0e-30];
    let c = SafeTimeSpans::new(&huge);
    let _ = c.spans_at(1e30, -1e30);
    let _ = c.eval(&Sample::new(3.0e38, -3.0e38, 0.0, 0.0, 0.5));
    let mut nan = moving();
    nan.r[1][3] = f32::NAN;
    let p = METHOD_SAFE.setup(&nan);
    assert_eq!(p.disabled(), Some("non-finite triangle data"));
    assert!(SafeTimeSpans::new(&moving()).spans_at(f32::NAN, 1.0).as_slice() == [[0.0, 1.0]]);
}

/// The exact covered spans, shrunk to the inside of their certified end enclosures
/// (a subset of the exact set: what a superset must hold).
fn exact_inner(tri: &Triangle, x: f32, y: f32) -> Vec<[f64; 2]> {
    oracles::timeline::covered_spans(&tri.to_oracle(), x as f64, y as f64, 0.0, 0.0, 1e-12)
        .iter()
        .map(|s| [s.start.hi, s.end.lo])
        .filter(|s| s[0] < s[1])
        .collect()
}

/// Over a grid of pixel centres: the safe set holds the exact one (no lost time)
/// and the longest run of extra time.
fn safe_grid(
    tri: &Triangle,
    xs: std::ops::Range<i32>,
    ys: std::ops::Range<i32>,
    step: usize,
    off: f32,
) -> (f64, String) {
    let ts = SafeTimeSpans::new(tri);
    let (mut extra, mut covered, mut at) = (0.0f64, 0, String::new());
    for py in ys.step_by(step) {
        for px in xs.clone().step_by(step) {
            let (x, y) = (off + px as f32 + 0.5, off + py as f32 + 0.5);
            let exact = exact_inner(tri, x, y);
            covered += !exact.is_empty() as usize;
            let ours = ts.spans_at(x, y);
            let (lost, more) = longest_disagreement(ours.as_slice(), &exact);
            assert_eq!(lost, 0.0, "pixel ({x}, {y}): safe {:?} exact {exact:?}", ours.as_slice());
            if more > extra {
                extra = more;
                at = format!("pixel ({x}, {y}): safe {:?} exact {exact:?}", ours.as_slice());
            }
        }
    }
    assert!(covered > 20, "{covered}");
    (extra, at)
}

#[test]
fn safe_holds_the_exact_time_spans() {
    let cases = [
        ("moving, near the origin", moving(), (0..110, 0..100), 2, 0.0, 1e-3),
        ("facing flip", flip(), (-5..45, -25..35), 1, 0.0, 1e-3),
        ("moving, screen offset 1000", shifted(&moving(), 1000.0), (0..110, 0..100), 3, 1000.0, 1e-3),
        ("moving, screen offset 1e5", shifted(&moving(), 1.0e5), (0..110, 0..100), 5, 1.0e5, 2e-2),
    ];
    for (name, tri, (xs, ys), step, off, tol) in cases {
        let (extra, at) = safe_grid(&tri, xs, ys, step, off);
        eprintln!("gdam2010-safe, {name}: nothing lost, longest extra run {extra:e} at {at}");
        assert!(extra < tol, "{name}: {extra}");
    }
}

/// The grazing edge of `near_double_root_is_where_f32_is_fragile`: the original
/// loses or shortens these spans, the safe set holds every one, up to 1e5 px.
#[test]
fn safe_holds_near_double_roots() {
    let mut worst = 0.0f64;
    for o in [10.5f32, 100.5, 1000.5, 100000.5] {
        let tri_at = |k: i32| {
            let ay = (0..k).fold(o - 19.0f32, |v, _| v.next_up());
            Triangle {
                q: [[o - 10.0, ay, 0.0, 1.0], [o + 19.0, o + 36.0, 0.0, 1.0], [o + 20.0, o - 20.0, 0.0, 1.0]],
                r: [[o - 9.0, ay, 0.0, 1.0], [o + 19.0, o + 40.0, 0.0, 1.0], [o + 20.0, o - 20.0, 0.0, 1.0]],
                c0: [0.0; 3],
                c1: [0.0; 3],
                k: 1.0,
            }
        };
        for k in [0, 1, 2, 4, 8, 16, 64, 256, 4096] {
            let tri = tri_at(k);
            let exact = exact_inner(&tri, o, o);
            let ours = SafeTimeSpans::new(&tri).spans_at(o, o);
            let (lost, extra) = longest_disagreement(ours.as_slice(), &exact);
            assert_eq!(lost, 0.0, "o {o} k {k}: safe {:?} exact {exact:?}", ours.as_slice());
            if o < 1000.0 {
                worst = worst.max(extra);
            }
        }
    }
    eprintln!("gdam2010-safe grazing edge: nothing lost; longest extra run near the origin {worst:e}");
    assert!(worst < 0.05, "{worst}");
}

/// The stored corpus cases of the original: its witness is covered and culled by
/// gdam2010, kept by gdam2010-safe.
#[test]
fn safe_keeps_the_corpus_witnesses() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/gdam2010");
    let mut n = 0;
    for f in std::fs::read_dir(dir).unwrap() {
        let cf = crate::search::CaseFile::load(&f.unwrap().path()).unwrap();
        let tri = cf.case.triangle;
        let w = cf.witness.expect("a violation case has a witness").sample;
        let s = Sample::new(w[0] as f32, w[1] as f32, w[2] as f32, w[3] as f32, w[4] as f32);
        assert_eq!(oracles::classify(&tri.to_oracle(), s.to_oracle()), oracles::Coverage::Interior);
        assert!(TimeSpans::new(&tri).eval(&s) < 0.0, "the original should cull its witness");
        assert!(SafeTimeSpans::new(&tri).eval(&s) >= 0.0, "{tri:?} {s:?}");
        n += 1;
    }
    assert!(n >= 3, "{n}");
}

/// Static triangles: f32 samples a few ulps either side of an edge, near the origin
/// and up to 1e6 px from it. Every covered one is kept by the safe variant; the
/// original culls some.
#[test]
fn safe_static_samples_at_an_edge() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut covered, mut orig_culled) = (0, 0);
    for it in 0..300 {
        let off = [0.0f32, 1.0e3, 1.0e5, 1.0e6][it % 4];
        let w: f32 = rng.gen_range(0.2..4.0);
        let v = |x: f32, y: f32| [(off + x) * w, (off + y) * w, 0.5, w];
        let p0 = [rng.gen_range(-50.0..0.0), rng.gen_range(-50.0..0.0)];
        let p1 = [rng.gen_range(10.0..60.0), rng.gen_range(-20.0..20.0)];
        let p2 = [rng.gen_range(-20.0..20.0), rng.gen_range(10.0..60.0)];
        let tri = Triangle::fixed([v(p0[0], p0[1]), v(p1[0], p1[1]), v(p2[0], p2[1])]);
        let (safe, orig) = (SafeTimeSpans::new(&tri), TimeSpans::new(&tri));
        for _ in 0..20 {
            // A point on edge 01 (relative to off), then a few f32 steps across.
            let f: f32 = rng.gen_range(0.1..0.9);
            let (ex, ey) = (off + p0[0] + f * (p1[0] - p0[0]), off + p0[1] + f * (p1[1] - p0[1]));
            let mut y = ey;
            for _ in 0..rng.gen_range(0..6) {
                y = if rng.gen() { y.next_up() } else { y.next_down() };
            }
            let s = Sample::new(ex, y, 0.0, 0.0, rng.gen_range(0.0..=1.0));
            if oracles::classify(&tri.to_oracle(), s.to_oracle()) == oracles::Coverage::Interior {
                covered += 1;
                assert!(safe.eval(&s) >= 0.0, "{tri:?} {s:?}");
                orig_culled += (orig.eval(&s) < 0.0) as usize;
            }
        }
    }
    eprintln!("static samples at an edge: {covered} covered, the original culls {orig_culled}, the safe one none");
    assert!(covered > 500 && orig_culled > 0, "{covered} {orig_culled}");
}

/// Random moving triangles (perspective motion, vertices behind the lens, tiny and
/// huge scales, far from the origin): at random pixels the safe set holds the exact
/// one; and it is not vacuous (most pixels away from the triangle are culled over
/// the whole shutter).
#[test]
fn safe_random_moving_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let (mut pixels, mut covered, mut empty) = (0, 0, 0);
    for it in 0..200 {
        let scale: f32 = [1.0, 1e-3, 1e3, 1.0][it % 4];
        let off: f32 = if it % 4 == 3 { 10f32.powi(rng.gen_range(3..=6)) } else { 0.0 };
        let mut vert = || {
            let w: f32 = if it % 5 == 0 { rng.gen_range(-0.5..3.0) } else { rng.gen_range(0.3..3.0) };
            let (x, y): (f32, f32) = (rng.gen_range(-20.0..20.0), rng.gen_range(-20.0..20.0));
            [(off + x * scale) * w, (off + y * scale) * w, 0.5, w]
        };
        let q = [vert(), vert(), vert()];
        let r = [vert(), vert(), vert()];
        let tri = Triangle { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        let ts = SafeTimeSpans::new(&tri);
        for _ in 0..10 {
            let (x, y) = (off + rng.gen_range(-25.0..25.0) * scale, off + rng.gen_range(-25.0..25.0) * scale);
            let exact = exact_inner(&tri, x, y);
            let ours = ts.spans_at(x, y);
            let (lost, _) = longest_disagreement(ours.as_slice(), &exact);
            assert_eq!(lost, 0.0, "{tri:?} pixel ({x}, {y}): safe {:?} exact {exact:?}", ours.as_slice());
            pixels += 1;
            covered += !exact.is_empty() as usize;
            empty += (ours.n == 0) as usize;
        }
    }
    eprintln!("gdam2010-safe random: {pixels} pixels, {covered} covered, {empty} culled over the whole shutter");
    assert!(covered > 200 && empty > pixels / 2, "{pixels} {covered} {empty}");
    // A far sample is culled.
    let tri = moving();
    let b = match METHOD_SAFE.setup(&tri).tile(&Tile::square(500.0, 500.0, 8.0)) {
        TileResult::Bounds(b) => b,
        TileResult::Empty => unreachable!(),
    };
    assert!(!b.admits(&Sample::new(503.0, 504.0, 0.0, 0.0, 0.5)));
    assert_eq!(SafeTimeSpans::new(&tri).spans_at(503.0, 504.0).n, 0);
}

#[test]
fn safe_eval_box_encloses_eval_and_conservative_spots() {
    assert_eval_box_encloses_eval(&SafeTimeSpans::new(&moving()), 12, 1000);
    let mut flipped = moving();
    flipped.q.swap(1, 2);
    flipped.r.swap(1, 2);
    let mut spots = 0;
    for (tri, tile) in [
        (moving(), Tile::square(30.0, 30.0, 8.0)),
        (flipped, Tile::square(60.0, 50.0, 2.0)),
        (flip(), Tile::square(16.0, 0.0, 8.0)),
    ] {
        let (c, a) = assert_spot(METHOD_SAFE, &tri, &tile, 4000, 3);
        assert!(a >= c);
        spots += c;
    }
    assert!(spots > 1000, "{spots}");
}
