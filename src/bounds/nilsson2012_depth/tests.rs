//! The unit tests of `nilsson2012_depth` (a file of their own to keep the method's file to its method).

use super::super::testkit::{bounds_of, random_lens, random_sample};
use super::*;
use crate::model::ThinLens;
use oracles::DepthCheck;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// [`w_from`] in f32: None when no hit is possible, else `(lo, hi)`.
fn wf<R: Round>(m_lo: f32, e_hi: f32) -> Option<(f32, f32)> {
    let b = w_from::<R, Plain>(&Plain, &m_lo, &e_hi);
    (!b.empty).then_some((b.lo, b.hi))
}

fn bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    bounds_of(METHOD, tri, tile)
}

fn cam() -> ThinLens {
    ThinLens { fx: 100.0, fy: 100.0, cx: 32.0, cy: 32.0, radius: 0.2, focus: 5.0, near: 0.5, far: 50.0 }
}

/// Random samples in the tile: every interior sample's exact depth lies in z^ and
/// no interior sample is culled. Returns the number of interior samples.
fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> usize {
    let res = bounds(tri, tile);
    let o = tri.to_oracle();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut covered = 0;
    for _ in 0..n {
        let s = random_sample(&mut rng, tile);
        let Some(b) = &res else {
            assert_ne!(
                oracles::classify(&o, s.to_oracle()),
                oracles::Coverage::Interior,
                "{tri:?} {tile:?}: {s:?} culled"
            );
            continue;
        };
        assert!(b.admits(&s));
        let z = b.z.unwrap_or([f32::NEG_INFINITY, f32::INFINITY]);
        match oracles::classify_depth(&o, s.to_oracle(), z[0] as f64, z[1] as f64) {
            DepthCheck::Inside => covered += 1,
            DepthCheck::NotInterior => {}
            d => panic!("{tri:?}\ntile {tile:?}: sample {s:?} depth {d:?} of z^ {z:?}"),
        }
    }
    covered
}

#[test]
fn static_flat_triangle_gets_its_depth() {
    // w = 2, z = 1 everywhere: z / w = 0.5 exactly.
    let tri = Triangle::fixed([[0.0, 0.0, 1.0, 2.0], [200.0, 0.0, 1.0, 2.0], [0.0, 200.0, 1.0, 2.0]]);
    let b = bounds(&tri, &Tile::square(10.0, 10.0, 4.0)).expect("inside tile culled");
    assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
    let z = b.z.expect("no depth");
    assert!(z[0] <= 0.5 && 0.5 <= z[1], "{z:?}");
    assert_eq!(z, [0.5, 0.5]);
    let s = Sample::new(12.0, 12.0, 0.0, 0.0, 0.5);
    assert_eq!(oracles::classify_depth(&tri.to_oracle(), s.to_oracle(), z[0] as f64, z[1] as f64), DepthCheck::Inside);
}

#[test]
fn static_tilted_triangle_from_a_camera() {
    let c = cam();
    let tri = c.triangle(
        [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
        [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
    );
    let tri = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tri };
    let mut n = 0;
    for (i, tile) in
        [Tile::square(5.0, 5.0, 4.0), Tile::square(20.0, 10.0, 8.0), Tile { x0: 0.3, y0: 1.7, x1: 1.9, y1: 2.2 }]
            .iter()
            .enumerate()
    {
        n += spot_check(&tri, tile, 3000, i as u64);
        let b = bounds(&tri, tile).unwrap();
        let z = b.z.unwrap();
        // The planes make it much tighter than the vertex box.
        let p = prepare(&tri);
        assert!(p.zeta_on);
        let zb = p.zeta_box;
        assert!(z[1] - z[0] < 0.5 * (zb[1] - zb[0]), "{z:?} vs box {zb:?}");
    }
    assert!(n > 1000, "{n}");
}

#[test]
fn far_tile_above_the_horizon_is_culled() {
    // A ground triangle y = -1 (camera space), from z = 2 to 40: its horizon is the
    // row y/w = cy = 32; tiles well above the horizon (larger y) cannot see it.
    let c = cam();
    let g = [[-5.0, -1.0, 2.0], [5.0, -1.0, 2.0], [0.0, -1.0, 40.0]];
    let tri = c.triangle(g, g);
    let tri = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tri };
    assert!(bounds(&tri, &Tile::square(28.0, 60.0, 8.0)).is_none());
    assert!(bounds(&tri, &Tile::square(28.0, 200.0, 8.0)).is_none());
    // Below the horizon it is kept and bounded.
    let b = bounds(&tri, &Tile::square(30.0, 10.0, 4.0)).expect("visible tile culled");
    assert!(b.z.is_some());
    spot_check(&tri, &Tile::square(30.0, 10.0, 4.0), 2000, 5);
}

#[test]
fn moving_triangle_depth_contains_random_samples() {
    let c = cam();
    let q = [[-1.0, -1.0, 3.0], [1.5, -1.0, 4.0], [-1.0, 1.5, 6.0]];
    let r = [[-0.5, -0.8, 4.0], [2.0, -0.6, 7.0], [-0.2, 1.2, 5.0]];
    let motion = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..c.triangle(q, r) };
    let both = c.triangle(q, r);
    // A triangle that flips facing during the shutter.
    let flip = Triangle {
        q: [[0.0, 0.0, 0.2, 1.0], [40.0, 0.0, 0.4, 1.5], [20.0, 30.0, 0.5, 2.0]],
        r: [[0.0, 10.0, 0.3, 1.2], [40.0, 10.0, 0.6, 2.0], [25.0, -20.0, 0.7, 2.5]],
        c0: [0.0; 3],
        c1: [0.0; 3],
        k: 1.0,
    };
    // Per-vertex CoC, vertex behind the lens at t = 1.
    let pv = Triangle {
        q: [[0.0, 0.0, 0.2, 1.0], [40.0, 0.0, 0.4, 1.5], [20.0, 30.0, 0.5, 2.0]],
        r: [[5.0, 5.0, -0.1, -0.5], [45.0, 8.0, 0.6, 2.0], [25.0, 35.0, 0.7, 2.5]],
        c0: [2.0, -1.0, 3.0],
        c1: [1.0, 0.5, -2.0],
        k: 1.2,
    };
    let mut total = 0;
    for (tri, tiles) in [
        (
            motion,
            vec![
                Tile::square(10.0, 10.0, 8.0),
                Tile::square(40.0, 30.0, 4.0),
                Tile { x0: 20.25, y0: 15.5, x1: 21.75, y1: 16.0 },
            ],
        ),
        (both, vec![Tile::square(10.0, 10.0, 8.0), Tile::square(40.0, 30.0, 4.0), Tile::square(0.0, 0.0, 1.0)]),
        (flip, vec![Tile::square(10.0, 0.0, 8.0), Tile::square(18.0, 12.0, 2.0)]),
        (pv, vec![Tile::square(10.0, 0.0, 8.0), Tile::square(18.0, 12.0, 4.0)]),
    ] {
        for (i, tile) in tiles.iter().enumerate() {
            total += spot_check(&tri, tile, 3000, 100 + i as u64);
        }
    }
    assert!(total > 3000, "{total}");
}

#[test]
fn plane_sweeping_the_lens_is_dropped() {
    // A triangle whose plane passes through the camera origin at t = 0 (seen edge
    // on): the offsets at t = 0 are 0, so both planes of base 0 are dropped.
    let tri = Triangle {
        q: [[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 1.0, 2.0], [0.0, 0.0, 1.5, 3.0]],
        r: [[0.0, 0.0, 0.5, 1.0], [10.0, 5.0, 1.0, 2.0], [0.0, 8.0, 1.5, 3.0]],
        c0: [0.0; 3],
        c1: [0.0; 3],
        k: 1.0,
    };
    let p = prepare(&tri);
    assert!(!p.planes[0].upper_on && !p.planes[0].lower_on);
    spot_check(&tri, &Tile::square(0.0, 0.0, 4.0), 3000, 9);
}

#[test]
fn degenerate_input_does_not_panic() {
    let z = Triangle::fixed([[0.0; 4]; 3]);
    let _ = METHOD.setup(&z).tile(&Tile::square(0.0, 0.0, 1.0));
    let mut nan = z;
    nan.q[0][0] = f32::NAN;
    let p = METHOD.setup(&nan);
    assert!(p.disabled().is_some());
    assert!(matches!(p.tile(&Tile::square(0.0, 0.0, 1.0)), TileResult::Bounds(_)));
}

#[test]
fn w_rule() {
    assert_eq!(wf::<Nearest>(2.0, 4.0), Some((0.0, 2.0)));
    assert_eq!(wf::<Nearest>(2.0, -4.0), None);
    assert_eq!(wf::<Nearest>(-2.0, -4.0), Some((2.0, f32::INFINITY)));
    assert_eq!(wf::<Nearest>(0.0, -4.0), None);
    assert_eq!(wf::<Nearest>(-1.0, 4.0), Some((0.0, f32::INFINITY)));
    assert_eq!(c_over_w::<Nearest, Plain>(&Plain, &[-2.0, -1.0], &[0.0, 4.0]), [f32::NEG_INFINITY, -0.25]);
    assert_eq!(c_over_w::<Nearest, Plain>(&Plain, &[1.0, 2.0], &[1.0, 4.0]), [0.25, 2.0]);
}

/// Random triangles of every kind (thin lens or per-vertex CoC, vertices behind the
/// lens, independent vertex motion in depth too), tiles on the moving triangle.
#[test]
fn random_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let (mut covered, mut bounded, mut tiles) = (0, 0, 0);
    for it in 0..200 {
        let c = random_lens(&mut rng);
        let zlo = if it % 4 == 0 { -1.0 } else { 0.6 };
        let q: [[f32; 3]; 3] = std::array::from_fn(|_| {
            let z = rng.gen_range(zlo..12.0f32);
            [rng.gen_range(-0.15f32..0.15) * z.abs(), rng.gen_range(-0.15f32..0.15) * z.abs(), z]
        });
        let r: [[f32; 3]; 3] = std::array::from_fn(|i| {
            [q[i][0] + rng.gen_range(-0.6..0.6), q[i][1] + rng.gen_range(-0.6..0.6), q[i][2] + rng.gen_range(-1.5..1.5)]
        });
        let mut tri = c.triangle(q, r);
        if it % 3 == 1 {
            tri.c0 = std::array::from_fn(|_| rng.gen_range(-20.0..20.0));
            tri.c1 = std::array::from_fn(|_| rng.gen_range(-20.0..20.0));
        }
        for _ in 0..4 {
            let t: f32 = rng.gen_range(0.0..1.0);
            let (b0, b1): (f32, f32) = (rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0));
            let (b0, b1) = if b0 + b1 > 1.0 { (1.0 - b0, 1.0 - b1) } else { (b0, b1) };
            let bb = [b0, b1, 1.0 - b0 - b1];
            let p: [f32; 4] = std::array::from_fn(|j| (0..3).map(|i| bb[i] * tri.at(i, t)[j]).sum());
            if p[3].is_nan() || p[3] <= 0.05 {
                continue;
            }
            let size = [1.0f32, 2.0, 4.0, 0.7][rng.gen_range(0..4)];
            let tile =
                Tile::square(p[0] / p[3] + rng.gen_range(-4.0..4.0), p[1] / p[3] + rng.gen_range(-4.0..4.0), size);
            tiles += 1;
            bounded +=
                bounds(&tri, &tile).is_some_and(|b| b.z.is_some_and(|z| z[0].is_finite() && z[1].is_finite())) as usize;
            covered += spot_check(&tri, &tile, 200, rng.gen());
        }
    }
    eprintln!("nilsson2012-depth random: {covered} interior samples, {bounded} of {tiles} tiles with a finite z^");
    assert!(covered > 10000 && bounded > tiles / 2, "{covered} {bounded} {tiles}");
}

#[test]
fn degenerate_and_huge_input_is_answered_in_the_domain() {
    super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    super::super::testkit::assert_degenerate_input_is_answered(METHOD_SAFE, &super::super::la2011::figure1::triangle());
}

/// The stored corpus cases of the original (far from the origin, screen-parallel,
/// static, motion, defocus, sliver): the original culls or misses its witness, the
/// safe variant keeps the tile and the witness's exact depth lies in its z^.
#[test]
fn safe_keeps_the_corpus_witnesses() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/nilsson2012-depth");
    let mut n = 0;
    for f in std::fs::read_dir(dir).unwrap() {
        let cf = crate::search::CaseFile::load(&f.unwrap().path()).unwrap();
        let (tri, tile) = (cf.case.triangle, cf.tile);
        let w = cf.witness.expect("a violation case has a witness").sample;
        let o = tri.to_oracle();
        let judge = |m: &dyn Method| match m.setup(&tri).tile(&tile) {
            TileResult::Empty => DepthCheck::Above,
            TileResult::Bounds(b) => {
                let z = b.z.unwrap_or([f32::NEG_INFINITY, f32::INFINITY]);
                oracles::classify_depth(&o, w, z[0] as f64, z[1] as f64)
            }
        };
        assert_ne!(judge(METHOD), DepthCheck::Inside, "{}: the original should miss its witness", cf.note);
        assert_eq!(judge(METHOD_SAFE), DepthCheck::Inside, "{tri:?} {tile:?} {w:?}");
        n += 1;
    }
    assert!(n >= 8, "{n}");
}

/// A screen-parallel triangle (every w equal): the original's plane bound rounds
/// one ulp below the vertex box and the interval is empty for some of these tiles;
/// the safe one always holds the depth, over many depths and screen offsets.
#[test]
fn safe_screen_parallel_is_never_empty() {
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let mut empties = 0;
    for _ in 0..2000 {
        let w: f32 = rng.gen_range(0.01f32..50.0);
        let z: f32 = rng.gen_range(-2.0f32..2.0) * w;
        let (ox, oy): (f32, f32) = (rng.gen_range(-2000.0..2000.0), rng.gen_range(-2000.0..2000.0));
        let v = |x: f32, y: f32| [(ox + x) * w, (oy + y) * w, z, w];
        let tri = Triangle::fixed([v(-30.0, -20.0), v(40.0, -25.0), v(5.0, 45.0)]);
        let tile = Tile::square(ox.floor(), oy.floor(), 1.0);
        empties += bounds(&tri, &tile).is_none() as usize;
        let b = bounds_of(METHOD_SAFE, &tri, &tile).expect("covered tile culled");
        let zz = b.z.expect("no depth");
        let s = Sample::new(tile.x0 + 0.5, tile.y0 + 0.5, 0.0, 0.0, 0.5);
        let d = oracles::classify_depth(&tri.to_oracle(), s.to_oracle(), zz[0] as f64, zz[1] as f64);
        assert_eq!(d, DepthCheck::Inside, "{tri:?} {tile:?} {zz:?}");
    }
    eprintln!("screen-parallel: the original culled {empties} of 2000 covered tiles");
}

/// Spot checks of the safe variant on the original's hard inputs: far from the
/// origin (1e4..1e6 px), huge and tiny scales, w near 0, vertices behind the lens,
/// the focal plane crossed (CoC through 0), slivers.
#[test]
fn safe_random_hard_inputs() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let (mut covered, mut tiles, mut finite) = (0, 0, 0);
    for it in 0..600 {
        let kind = it % 6;
        let scale: f32 = [1.0, 1e-3, 1e3, 1.0, 1.0, 1.0][kind];
        let off: f32 = if kind == 3 { 10f32.powi(rng.gen_range(4..=6)) } else { 0.0 };
        let vert = |rng: &mut ChaCha8Rng| {
            let w: f32 = match kind {
                4 => rng.gen_range(1e-4f32..0.05),
                5 => rng.gen_range(-0.5f32..3.0),
                _ => rng.gen_range(0.3f32..5.0),
            };
            let (x, y): (f32, f32) = (rng.gen_range(-20.0..20.0), rng.gen_range(-20.0..20.0));
            [(off + x) * scale * w, (off + y) * scale * w, rng.gen_range(-1.0f32..1.0) * w + 0.1, w]
        };
        let mut q = [vert(&mut rng), vert(&mut rng), vert(&mut rng)];
        let mut r = q;
        if it % 2 == 1 {
            r = [vert(&mut rng), vert(&mut rng), vert(&mut rng)];
        }
        if it % 12 == 7 {
            // A sliver: the third vertex close to the first edge.
            for p in [&mut q, &mut r] {
                p[2] = std::array::from_fn(|j| 0.5 * (p[0][j] + p[1][j]) + 1e-4 * p[2][j]);
            }
        }
        let mut tri = Triangle { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        if it % 3 == 0 {
            // Focal plane crossed: the CoC changes sign over the shutter.
            tri.c0 = std::array::from_fn(|_| rng.gen_range(-3.0..3.0) * scale);
            tri.c1 = tri.c0.map(|c| -c);
            tri.k = rng.gen_range(0.5..2.0);
        }
        for _ in 0..3 {
            let i = rng.gen_range(0..3);
            let p = tri.q[i];
            if p[3] <= 0.0 {
                continue;
            }
            let size = [1.0f32, 4.0, 16.0][rng.gen_range(0..3)] * scale.max(1.0);
            let tile = Tile::square(
                (p[0] / p[3] + rng.gen_range(-8.0..8.0) * scale).floor(),
                (p[1] / p[3] + rng.gen_range(-8.0..8.0) * scale).floor(),
                size,
            );
            tiles += 1;
            let b = bounds_of(METHOD_SAFE, &tri, &tile);
            finite += b.as_ref().is_some_and(|b| b.z.is_some_and(|z| z[0].is_finite() && z[1].is_finite())) as usize;
            let o = tri.to_oracle();
            let mut srng = ChaCha8Rng::seed_from_u64(it as u64);
            for _ in 0..300 {
                let s = random_sample(&mut srng, &tile);
                let z = match &b {
                    None => [f32::INFINITY, f32::NEG_INFINITY],
                    Some(b) => b.z.unwrap_or([f32::NEG_INFINITY, f32::INFINITY]),
                };
                match oracles::classify_depth(&o, s.to_oracle(), z[0] as f64, z[1] as f64) {
                    DepthCheck::Inside => covered += 1,
                    DepthCheck::NotInterior => {}
                    d => panic!("{tri:?}\ntile {tile:?}: sample {s:?} depth {d:?} of z^ {z:?} ({b:?})"),
                }
            }
        }
    }
    eprintln!("nilsson2012-depth-safe hard inputs: {covered} covered samples, {finite} of {tiles} tiles finite z^");
    assert!(covered > 5000 && finite > tiles / 3, "{covered} {finite} {tiles}");
}

/// Not vacuous: the safe variant still culls tiles above the horizon and gives a
/// depth interval far narrower than the vertex box, within a few ulps of the
/// original's.
#[test]
fn safe_is_not_vacuous() {
    let c = cam();
    let g = [[-5.0, -1.0, 2.0], [5.0, -1.0, 2.0], [0.0, -1.0, 40.0]];
    let ground = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..c.triangle(g, g) };
    assert!(bounds_of(METHOD_SAFE, &ground, &Tile::square(28.0, 60.0, 8.0)).is_none());
    assert!(bounds_of(METHOD_SAFE, &ground, &Tile::square(28.0, 200.0, 8.0)).is_none());
    let tilted = c.triangle(
        [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
        [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
    );
    let tilted = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tilted };
    let p = prepare(&tilted);
    assert!(p.zeta_on);
    let zb = p.zeta_box;
    for tile in [Tile::square(5.0, 5.0, 4.0), Tile::square(20.0, 10.0, 8.0)] {
        let z = bounds_of(METHOD_SAFE, &tilted, &tile).unwrap().z.unwrap();
        let z0 = bounds(&tilted, &tile).unwrap().z.unwrap();
        assert!(z[1] - z[0] < 0.5 * (zb[1] - zb[0]), "{z:?} vs box {zb:?}");
        assert!(z[0] <= z0[0] && z0[1] <= z[1], "{z:?} must hold {z0:?}");
        assert!((z[0] - z0[0]).abs() < 1e-5 && (z[1] - z0[1]).abs() < 1e-5, "{z:?} vs {z0:?}");
    }
    // Static flat triangle: a few ulps around its one depth.
    let flat = Triangle::fixed([[0.0, 0.0, 1.0, 2.0], [200.0, 0.0, 1.0, 2.0], [0.0, 200.0, 1.0, 2.0]]);
    let z = bounds_of(METHOD_SAFE, &flat, &Tile::square(10.0, 10.0, 4.0)).unwrap().z.unwrap();
    assert!(z[0] <= 0.5 && 0.5 <= z[1] && z[1] - z[0] < 1e-6, "{z:?}");
    assert!(bounds_of(METHOD_SAFE, &flat, &Tile::square(10.0, 10.0, 4.0)).is_some());
}

#[test]
fn safe_w_rule_rounds_outward() {
    // 1 / 3 is not an f32: the bounds step past it.
    let (_, hi) = wf::<Outward>(3.0, 1.0).unwrap();
    assert!(hi as f64 > 1.0 / 3.0);
    let (lo, _) = wf::<Outward>(-3.0, -1.0).unwrap();
    assert!((lo as f64) < 1.0 / 3.0);
    let q = c_over_w::<Outward, Plain>(&Plain, &[1.0, 2.0], &[3.0, 7.0]);
    assert!((q[0] as f64) < 1.0 / 7.0 && q[1] as f64 > 2.0 / 3.0);
    // NaN is not skipped by the safe min / max.
    assert!(min_g::<Outward, Plain>(&Plain, &1.0, &f32::NAN).is_nan());
    assert_eq!(min_g::<Nearest, Plain>(&Plain, &1.0, &f32::NAN), 1.0);
    assert_eq!(wf::<Outward>(f32::NEG_INFINITY, 1.0), Some((0.0, f32::INFINITY)));
}
