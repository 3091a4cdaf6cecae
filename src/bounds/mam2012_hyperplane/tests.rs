//! The unit tests of `mam2012_hyperplane` (a file of their own to keep the method's file to its method).

use super::super::testkit::{assert_keeps_covered, near_miss_check, random_sample, spot_check};
use super::safe::*;
use super::*;
use crate::model::ThinLens;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn cam() -> ThinLens {
    ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 4.0, near: 0.1, far: 100.0 }
}

fn cases() -> Vec<(Triangle, Vec<Tile>)> {
    let c = cam();
    let mut v = Vec::new();
    // Small defocused triangle moving across the screen (Figure 1).
    let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
    v.push((
        c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]])),
        vec![Tile::square(-0.5, -0.5, 1.0), Tile::square(-3.0, -2.0, 4.0)],
    ));
    // Large moving triangle across the focal plane (c changes sign: fine here).
    v.push((
        c.triangle(
            [[-1.0, -1.0, 3.0], [1.0, -0.8, 5.0], [0.0, 1.0, 3.2]],
            [[-0.6, -0.7, 2.5], [0.9, -0.5, 6.0], [0.3, 0.8, 4.5]],
        ),
        vec![
            Tile::square(0.0, 0.0, 2.0),
            Tile::square(-30.0, -30.0, 8.0),
            Tile::square(20.0, 10.0, 4.0),
            Tile::square(-4.0, 20.0, 4.0),
        ],
    ));
    // Large perspective motion behind the focal plane.
    v.push((
        c.triangle(
            [[-1.0, -1.0, 20.0], [2.0, -1.0, 20.0], [0.0, 2.0, 20.0]],
            [[-1.0, -1.0, 4.5], [2.0, -1.0, 4.5], [0.0, 2.0, 4.5]],
        ),
        vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-24.0, -24.0, 4.0), Tile::square(40.0, -20.0, 4.0)],
    ));
    // Per-vertex CoC, aspect 0.75, clockwise on screen.
    let mut t = Triangle::fixed([[-10.0, -5.0, 0.0, 2.0], [0.0, 14.0, 0.0, 3.0], [12.0, -4.0, 0.0, 2.5]]);
    t.r = [[-4.0, -2.0, 0.0, 1.0], [6.0, 12.0, 0.0, 2.0], [14.0, 0.0, 0.0, 3.0]];
    t.c0 = [3.0, 5.0, -1.0];
    t.c1 = [0.5, 2.0, 6.0];
    t.k = 0.75;
    v.push((
        t,
        vec![
            Tile::square(0.0, 0.0, 1.0),
            Tile::square(-12.0, -6.0, 4.0),
            Tile::square(4.0, 6.0, 2.0),
            Tile::square(1.0, -3.0, 1.0),
        ],
    ));
    v
}

#[test]
fn conservative_on_random_samples() {
    for m in [METHOD, METHOD_PS, METHOD_SAFE, METHOD_PS_SAFE] {
        for (ci, (tri, tiles)) in cases().into_iter().enumerate() {
            let p = m.setup(&tri);
            assert_eq!(p.disabled(), None, "case {ci}");
            let mut total = 0;
            for (ti, tile) in tiles.iter().enumerate() {
                let (cov, bad) = spot_check(p.as_ref(), &tri, tile, 60_000, 2000 + 10 * ci as u64 + ti as u64);
                assert!(
                    bad.is_empty(),
                    "{} case {ci} tile {ti}: {} covered samples culled, first {:?}",
                    m.info().id,
                    bad.len(),
                    bad[0]
                );
                total += cov;
                let (_, bad) = near_miss_check(p.as_ref(), &tri, tile, 3000, 5000 + ti as u64);
                assert!(bad.is_empty(), "case {ci} tile {ti}: covered sample culled near a bound {:?}", bad[0]);
            }
            assert!(total > 100, "case {ci}: only {total} covered samples");
            eprintln!("{} case {ci}: {total} covered", m.info().id);
        }
    }
}

/// Many random physical triangles (both facings, any depth, some behind the lens)
/// and tiles near them.
#[test]
fn conservative_on_random_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let c = cam();
    let (mut near_total, mut enabled, mut cov_total, mut culled_tiles, mut culled_safe) = (0, 0, 0, 0, 0);
    for it in 0..300 {
        let z0: f32 = rng.gen_range(0.5..30.0);
        let z1: f32 = if it % 3 == 0 { z0 } else { rng.gen_range(0.5..30.0) };
        let mut v =
            || -> [f32; 3] { [rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.2..0.2f32)] };
        let (a, b, d) = (v(), v(), v());
        let mv = [v(), v(), v()];
        let q = [a, b, d].map(|p| [p[0] * z0, p[1] * z0, z0 + p[2] * z0]);
        let r = [0, 1, 2].map(|i| {
            [(([a, b, d][i][0] + mv[i][0]) * z1), ([a, b, d][i][1] + mv[i][1]) * z1, z1 + [a, b, d][i][2] * z1]
        });
        let tri = c.triangle(q, r);
        let p = METHOD_PS.setup(&tri);
        let safe = METHOD_PS_SAFE.setup(&tri);
        if p.disabled().is_some() {
            continue;
        }
        enabled += 1;
        for _ in 0..3 {
            let size = [1.0f32, 2.0, 4.0][rng.gen_range(0..3)];
            let tile = Tile::square(rng.gen_range(-40.0..40.0), rng.gen_range(-40.0..40.0), size);
            if matches!(p.tile(&tile), TileResult::Empty) {
                culled_tiles += 1;
            }
            let (cov, tried) =
                assert_keeps_covered(p.as_ref(), &tri, &tile, (2000, 300), it * 7 + 1, &format!("triangle {it}"));
            cov_total += cov;
            near_total += tried;
            let what = format!("safe, triangle {it}");
            assert_keeps_covered(safe.as_ref(), &tri, &tile, (2000, 300), it * 7 + 1, &what);
            culled_safe += matches!(safe.tile(&tile), TileResult::Empty) as usize;
        }
    }
    eprintln!("near-miss probes {near_total}, enabled {enabled}, covered {cov_total}, culled tiles {culled_tiles}");
    eprintln!("safe: culled tiles {culled_safe}");
    assert!(enabled > 150 && cov_total > 5000 && culled_tiles > 50);
    assert!(culled_safe * 10 >= culled_tiles * 9, "{culled_safe} vs {culled_tiles}");
}

#[test]
fn static_triangle_keeps_time_and_far_tile_is_culled() {
    for m in [METHOD, METHOD_PS, METHOD_SAFE, METHOD_PS_SAFE] {
        for tri in [
            Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0]]),
            Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0]]),
        ] {
            let p = m.setup(&tri);
            assert_eq!(p.disabled(), None);
            let TileResult::Bounds(b) = p.tile(&Tile::square(-1.0, -1.0, 2.0)) else { panic!("empty") };
            assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
            let mut rng = ChaCha8Rng::seed_from_u64(5);
            for _ in 0..1000 {
                assert!(b.admits(&random_sample(&mut rng, &Tile::square(-1.0, -1.0, 2.0))));
            }
            assert!(matches!(p.tile(&Tile::square(100.0, 0.0, 2.0)), TileResult::Empty));
            assert!(matches!(p.tile(&Tile::square(0.0, 21.0, 1.0)), TileResult::Empty));
        }
    }
}

/// A triangle sliding right: a tile it enters late gets a refined t lower bound.
#[test]
fn refined_time_bounds() {
    let mut tri = Triangle::fixed([[-40.0, -10.0, 0.0, 1.0], [-20.0, -10.0, 0.0, 1.0], [-30.0, 10.0, 0.0, 1.0]]);
    tri.r = tri.q.map(|p| [p[0] + 60.0, p[1], p[2], p[3]]);
    let p = METHOD.setup(&tri);
    let TileResult::Bounds(b) = p.tile(&Tile::square(5.0, 0.0, 2.0)) else { panic!("empty") };
    // For y in [0, 2] the right edge is at x = -25 - y/2 + 60 t: it reaches x = 5 at
    // t = 0.5; the left edge (x = -35 + y/2 + 60 t) leaves x = 7 at t = 0.7. Pure
    // screen motion (w fixed) makes n2 = 0 and the hyperplane exact.
    assert!(b.t[0] > 0.49 && b.t[0] <= 0.5, "{:?}", b.t);
    assert!(b.t[1] >= 0.7 && b.t[1] < 0.71, "{:?}", b.t);
}

#[test]
fn facing_flip_is_disabled() {
    // Vertex 2 crosses the opposite edge during the shutter.
    let mut tri = Triangle::fixed([[-10.0, -10.0, 0.0, 1.0], [10.0, -10.0, 0.0, 1.0], [0.0, 10.0, 0.0, 1.0]]);
    tri.r[2] = [0.0, -30.0, 0.0, 1.0];
    let p = METHOD.setup(&tri);
    assert!(p.disabled().unwrap().contains("facing"));
    let TileResult::Bounds(b) = p.tile(&Tile::square(500.0, 0.0, 1.0)) else { panic!("empty") };
    assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
    // Degenerate (zero area): disabled, no panic.
    let tri = Triangle::fixed([[0.0, 0.0, 0.0, 1.0]; 3]);
    assert!(METHOD_PS.setup(&tri).disabled().is_some());
}

#[test]
fn selective_enabling() {
    let c = cam();
    // A 2-unit triangle at the focal plane neighbourhood: little blur, enabled.
    let big = [[-1.0, -1.0, 4.2], [1.0, -1.0, 4.2], [0.0, 1.0, 4.2]];
    let m = Mam2012Hyperplane::selective(false, SELECTIVE_ENABLE_RATIO);
    assert_eq!(m.setup(&c.triangle(big, big)).disabled(), None);
    // A small, very defocused triangle: disabled.
    let small = [[-0.05, -0.05, 20.0], [0.05, -0.05, 20.0], [0.0, 0.05, 20.0]];
    assert!(m.setup(&c.triangle(small, small)).disabled().unwrap().contains("selective"));
    // The registered method never uses it.
    assert_eq!(METHOD.setup(&c.triangle(small, small)).disabled(), None);
    assert_eq!(m.info().id, "mam2012-hyperplane");
}

#[test]
fn per_sample_planes_cull_more() {
    // Figure 1 triangle: the per-sample planes admit fewer samples than the tile test.
    let c = cam();
    let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
    let tri = c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]]));
    let tile = Tile::square(-0.5, -0.5, 1.0);
    let TileResult::Bounds(a) = METHOD.setup(&tri).tile(&tile) else { panic!("empty") };
    let TileResult::Bounds(b) = METHOD_PS.setup(&tri).tile(&tile) else { panic!("empty") };
    assert_eq!(b.constraints.len(), 3);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut na, mut nb) = (0, 0);
    for _ in 0..20_000 {
        let s = random_sample(&mut rng, &tile);
        na += a.admits(&s) as usize;
        nb += b.admits(&s) as usize;
    }
    assert!(nb < na, "{nb} vs {na}");
}

#[test]
fn eval_box_encloses_eval() {
    let tri = cases()[3].0;
    let tile = Tile::square(0.0, 0.0, 1.0);
    let TileResult::Bounds(b) = METHOD_PS.setup(&tri).tile(&tile) else { panic!("empty") };
    assert_eq!(b.constraints.len(), 3);
    super::super::testkit::assert_eval_box_encloses(&b, &tile, 3);
}

#[test]
fn degenerate_input_is_answered_in_the_domain() {
    let mut tri = Triangle::fixed([[3e38, -3e38, 0.0, 1e-30], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, -1.0]]);
    tri.c0 = [3e38, 0.0, -1e-45];
    let tiles = [Tile::square(-1e30, 0.0, 1e30), Tile::square(0.0, 0.0, 1.0)];
    for m in [METHOD, METHOD_PS, METHOD_SAFE, METHOD_PS_SAFE] {
        super::super::testkit::assert_answered_in_domain(m.setup(&tri).as_ref(), &tiles);
    }
    let selective = Mam2012Hyperplane::selective(true, 4.0).setup(&tri);
    super::super::testkit::assert_answered_in_domain(selective.as_ref(), &tiles);
}

#[test]
fn degenerate_and_huge_input_is_answered_in_the_domain() {
    for m in [METHOD, METHOD_PS, METHOD_SAFE, METHOD_PS_SAFE] {
        super::super::testkit::assert_degenerate_input_is_answered(m, &super::super::la2011::figure1::triangle());
    }
}

/// The witnesses stored against the published method: each is interior, culled by
/// the original and kept by `-safe` (the tile is not culled and every bound admits
/// it).
#[test]
fn safe_keeps_the_stored_witnesses() {
    use crate::search::{witness_holds, CaseFile};
    let mut n = 0;
    for (dir, orig, safe) in
        [("mam2012-hyperplane", METHOD, METHOD_SAFE), ("mam2012-hyperplane-ps", METHOD_PS, METHOD_PS_SAFE)]
    {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases").join(dir);
        for f in std::fs::read_dir(&path).unwrap() {
            let f = f.unwrap().path();
            let cf = CaseFile::load(&f).unwrap();
            let Some(w) = &cf.witness else { continue };
            let culled = witness_holds(orig, &cf.case, &cf.tile, w.sample);
            assert!(culled.is_ok(), "{}: the original no longer culls its witness: {culled:?}", f.display());
            let kept = witness_holds(safe, &cf.case, &cf.tile, w.sample);
            assert_eq!(kept, Err("the method admits the witness".into()), "{}", f.display());
            n += 1;
        }
    }
    assert!(n >= 10, "{n} witnesses");
}

/// Triangles that break the published planes: far from the origin, sub-pixel, huge,
/// a vertex at w near 0 (and one behind the lens), the focal plane crossing a moving
/// triangle (CoC through 0), a screen-parallel sliver. `-safe` keeps every covered
/// sample of random and near-miss probes on tiles around them.
#[test]
fn safe_keeps_covered_samples_on_hard_input() {
    let c = cam();
    let mut hard: Vec<(&str, Triangle, Vec<Tile>)> = Vec::new();
    // Far from the origin (1e5 and 1e6 px), static and moving.
    for off in [1.0e5f32, 1.0e6] {
        let w = 2.0;
        let v = |x: f32, y: f32| [(off + x) * w, (off * 0.5 + y) * w, 0.0, w];
        let mut t = Triangle::fixed([v(0.0, 0.0), v(7.3, 0.4), v(2.1, 5.9)]);
        let tiles = vec![
            Tile::square(off, off * 0.5, 1.0),
            Tile::square(off + 2.0, off * 0.5 + 1.0, 2.0),
            Tile::square(off + 6.0, off * 0.5, 1.0),
        ];
        hard.push(("far static", t, tiles.clone()));
        t.r = t.q.map(|p| [p[0] + 3.0 * w, p[1] - 1.0 * w, p[2], p[3]]);
        t.c0 = [0.5, -0.25, 1.0];
        t.c1 = [1.0, 0.25, -0.5];
        hard.push(("far moving", t, tiles));
    }
    // Sub-pixel, moving and defocused.
    let q = [[0.100, 0.100, 5.0], [0.1005, 0.1001, 5.0], [0.1002, 0.1006, 5.0]];
    hard.push((
        "tiny",
        c.triangle(q, q.map(|p| [p[0] + 0.001, p[1], p[2] * 1.01])),
        vec![Tile::square(9.0, 9.0, 4.0), Tile::square(10.0, 10.0, 1.0), Tile::square(9.5, 10.5, 0.5)],
    ));
    // Huge (beyond the screen) and a vertex close to w = 0.
    let mut t = Triangle::fixed([[-1e5, -1e5, 0.0, 1.0], [1e5, -2e4, 0.0, 2.0], [0.0, 1e5, 0.0, 1.5]]);
    t.r[0] = [-1e5, -1e5, 0.0, 1e-6];
    hard.push(("huge, w near 0", t, vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-300.0, 50.0, 8.0)]));
    t.r[0][3] = -0.5;
    hard.push(("behind the lens", t, vec![Tile::square(0.0, 0.0, 2.0), Tile::square(40.0, -10.0, 4.0)]));
    // Moving through the focal plane (depth 4): CoC crosses 0.
    let q = [[-0.3, -0.2, 3.0], [0.3, -0.25, 3.5], [0.0, 0.3, 3.2]];
    hard.push((
        "focal crossing",
        c.triangle(q, q.map(|p| [p[0] + 0.1, p[1], p[2] + 2.0])),
        vec![Tile::square(-2.0, -2.0, 4.0), Tile::square(6.0, -5.0, 2.0), Tile::square(-9.0, 4.0, 2.0)],
    ));
    // Screen-parallel sliver moving along its own length.
    let mut t = Triangle::fixed([[-20.0, 0.0, 0.0, 1.0], [20.0, 0.01, 0.0, 1.0], [0.0, 0.03, 0.0, 1.0]]);
    t.r = t.q.map(|p| [p[0] + 5.0, p[1], p[2], p[3]]);
    hard.push(("sliver", t, vec![Tile::square(0.0, 0.0, 1.0), Tile::square(-3.0, -1.0, 2.0)]));
    let mut covered_total = 0;
    for m in [METHOD_SAFE, METHOD_PS_SAFE] {
        for (what, tri, tiles) in &hard {
            let p = m.setup(tri);
            for (ti, tile) in tiles.iter().enumerate() {
                let what = format!("{} {what} tile {ti}", m.info().id);
                let (cov, _) = assert_keeps_covered(p.as_ref(), tri, tile, (20_000, 2000), 77 + ti as u64, &what);
                covered_total += cov;
            }
        }
    }
    assert!(covered_total > 10_000, "{covered_total}");
}

/// Not vacuous: on ordinary triangles `-safe` still culls far tiles and narrows the
/// intervals, close to the published answer.
#[test]
fn safe_is_close_to_the_original() {
    let (mut culled, mut culled_safe, mut len, mut len_safe) = (0, 0, 0.0f64, 0.0f64);
    for (tri, tiles) in cases() {
        let (p, ps) = (METHOD.setup(&tri), METHOD_SAFE.setup(&tri));
        let mut all = tiles.clone();
        all.extend((0..40).map(|i| Tile::square(-40.0 + 2.0 * i as f32, -10.0 + 0.5 * i as f32, 2.0)));
        for tile in &all {
            let width = |r: &TileResult| match r {
                TileResult::Empty => 0.0,
                TileResult::Bounds(b) => ((b.u[1] - b.u[0]) + (b.v[1] - b.v[0]) + 2.0 * (b.t[1] - b.t[0])) as f64,
            };
            let (a, b) = (p.tile(tile), ps.tile(tile));
            culled += matches!(a, TileResult::Empty) as usize;
            culled_safe += matches!(b, TileResult::Empty) as usize;
            if matches!(b, TileResult::Empty) {
                assert!(matches!(a, TileResult::Empty), "safe culls a tile the original keeps: {tile:?}");
            }
            len += width(&a);
            len_safe += width(&b);
        }
    }
    eprintln!("culled {culled} / safe {culled_safe}; interval length {len} / safe {len_safe}");
    assert!(culled_safe > 30 && culled_safe * 10 >= culled * 9, "{culled_safe} vs {culled}");
    assert!(len_safe <= len * 1.01 + 1e-3, "{len_safe} vs {len}");
    // The sliding triangle of `refined_time_bounds`: the same t interval up to
    // rounding.
    let mut tri = Triangle::fixed([[-40.0, -10.0, 0.0, 1.0], [-20.0, -10.0, 0.0, 1.0], [-30.0, 10.0, 0.0, 1.0]]);
    tri.r = tri.q.map(|p| [p[0] + 60.0, p[1], p[2], p[3]]);
    let TileResult::Bounds(b) = METHOD_SAFE.setup(&tri).tile(&Tile::square(5.0, 0.0, 2.0)) else { panic!("empty") };
    assert!(b.t[0] > 0.4999 && b.t[0] <= 0.5 && b.t[1] >= 0.7 && b.t[1] < 0.7001, "{:?}", b.t);
}

/// The interval arithmetic encloses: random f32 operands, exact results in f64.
#[test]
fn intervals_enclose_exact_results() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let draw = |rng: &mut ChaCha8Rng| -> f32 {
        let e = rng.gen_range(-140..120);
        let x = rng.gen_range(-1.0f32..1.0) * 2f32.powi(e);
        if rng.gen_bool(0.05) {
            0.0
        } else {
            x
        }
    };
    for _ in 0..200_000 {
        let (a, b) = (draw(&mut rng), draw(&mut rng));
        let (ia, ib) = (Iv::point(a), Iv::point(b));
        let inside = |i: Iv, x: f64| (i.lo as f64) <= x && x <= i.hi as f64;
        assert!(inside(ia + ib, a as f64 + b as f64), "{a} + {b}");
        assert!(inside(ia - ib, a as f64 - b as f64), "{a} - {b}");
        // f32 x f32 is exact in f64 (48 bits), subnormals included down to 2^-298.
        assert!(inside(ia * ib, a as f64 * b as f64), "{a} * {b}");
        let c = draw(&mut rng);
        assert!(Iv::new(a.min(b), a.max(b)).dev(c) as f64 >= ((a as f64 - c as f64).abs()), "dev");
    }
    let third = Iv::third();
    assert!(third.lo < 1.0 / 3.0 && (1.0 / 3.0) < third.hi as f64);
    assert_eq!(Iv::point(f32::MAX) + Iv::point(f32::MAX), Iv { lo: f32::MAX, hi: f32::INFINITY });
    let whole = Iv::point(0.0) * Iv::new(1.0, f32::INFINITY);
    assert_eq!(whole, Iv { lo: f32::NEG_INFINITY, hi: f32::INFINITY });
}

#[test]
fn safe_eval_box_encloses_eval() {
    for (tri, tiles) in cases() {
        let p = METHOD_PS_SAFE.setup(&tri);
        for (i, tile) in tiles.iter().enumerate() {
            if let TileResult::Bounds(b) = p.tile(tile) {
                super::super::testkit::assert_eval_box_encloses(&b, tile, i as u64);
            }
        }
    }
}

/// `-safe`'s tile test (both per-sample settings) is its code before it was
/// restructured, bit for bit (the fingerprint of every answer, recorded while the old
/// code still ran beside it), on the stress stream of the bit-identity tests.
#[test]
fn safe_tile_is_its_old_code_bit_for_bit() {
    let (mut n, mut kept, mut empty) = (0, 0, 0);
    let mut fp = super::super::testkit::Fingerprint::new();
    for c in 0..20_000 {
        let (tri, tiles) = crate::cases::generate::bit_compare_case(61, c);
        for per_sample in [false, true] {
            let Ok(s) = setup_safe(&tri) else { continue };
            let p = SafePrep { s: Ok(s), k: tri.k, per_sample };
            for tile in &tiles {
                let new = p.tile(tile);
                fp.add(&format!("{new:?}"));
                n += 1;
                kept += matches!(new, TileResult::Bounds(ref b) if b.u != [-1.0, 1.0] || b.t != [0.0, 1.0]) as usize;
                empty += matches!(new, TileResult::Empty) as usize;
            }
        }
    }
    assert_eq!(
        fp.value(),
        0xc91a_a8ef_c1d0_d8de,
        "the answers on the stress stream are no longer those of the code before it was restructured \
         (recorded 2026-12-06 while both ran side by side and agreed)"
    );
    assert!(n > 20_000 && kept > 1000 && empty > 1000, "{n} {kept} {empty}");
}
