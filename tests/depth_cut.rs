//! An independent attack on `judge::depth_cut::decide`, the judge's decision of a depth
//! end by the moving-plane cuts certified with the edge values: for triangles and tiles
//! of this file's own generator (moving, defocused, facing flips, a vertex behind the
//! lens), depth ends at the least (greatest) depth the tile's samples show, a few ulps
//! either side of it and a little outside it. Every end it proves is attacked with the
//! samples that gave the estimate, a fresh dense set and samples pushed towards the
//! estimate's point: none may be interior with a hit depth beyond the end. An end one
//! f32 step inside a depth that an interior sample reaches must never be proved; where
//! the search reports a violation of it, the sample must be in the tile and the domain,
//! interior, with its hit depth beyond the end (decided here exactly).

use cullproof::judge::constraints::ConstraintVerdict;
use cullproof::judge::depth_cut::{decide, proves};
use cullproof::Tile;
use oracles::{classify_depth, DepthCheck, Tri};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const BUDGET: usize = 2000;

/// A triangle with f32 numbers: screen positions within a few hundred pixels, depths
/// in front of the far plane, motion in seven of ten, defocus in half, a vertex behind
/// the lens in one of eight, and in one of five a vertex that crosses the others
/// during the shutter (a facing flip).
fn triangle(g: &mut ChaCha8Rng) -> Tri {
    let behind = g.gen_bool(0.125);
    let moving = g.gen_bool(0.7);
    let defocus = g.gen_bool(0.5);
    let flip = moving && g.gen_bool(0.2);
    let key = |g: &mut ChaCha8Rng, k: usize| {
        let w: f64 = if behind && k == 0 { -g.gen_range(0.1..2.0) } else { g.gen_range(0.3..20.0) };
        let (x, y): (f64, f64) = (g.gen_range(-300.0..300.0), g.gen_range(-300.0..300.0));
        let z = w * g.gen_range(-0.3..0.99) + g.gen_range(-0.5..0.5);
        [x * w, y * w, z, w].map(|v| v as f32 as f64)
    };
    let q: [[f64; 4]; 3] = std::array::from_fn(|k| key(g, k));
    let mut r = q;
    if moving {
        for (k, v) in r.iter_mut().enumerate() {
            let d: f64 = if flip && k == 1 { 600.0 } else { 40.0 };
            v[0] = (v[0] + g.gen_range(-d..d) * v[3].abs()) as f32 as f64;
            v[1] = (v[1] + g.gen_range(-d..d) * v[3].abs()) as f32 as f64;
            v[2] = (v[2] + g.gen_range(-0.1..0.1) * v[3].abs()) as f32 as f64;
        }
    }
    let coc = |g: &mut ChaCha8Rng| if defocus { g.gen_range(-6.0f64..6.0) as f32 as f64 } else { 0.0 };
    let c0: [f64; 3] = std::array::from_fn(|_| coc(g));
    let c1: [f64; 3] = if moving { std::array::from_fn(|_| coc(g)) } else { c0 };
    Tri { q, r, c0, c1, k: g.gen_range(0.5f64..2.0) as f32 as f64 }
}

/// The hit depth of a sample in plain f64 when its three edge values and D agree in
/// sign (an estimate, for placing ends near the extreme only).
fn depth_estimate(tri: &Tri, [x, y, u, v, t]: [f64; 5]) -> Option<f64> {
    let l = |a: f64, b: f64| a + (b - a) * t;
    let p: [[f64; 4]; 3] = std::array::from_fn(|k| {
        let (c, w) = (l(tri.c0[k], tri.c1[k]), l(tri.q[k][3], tri.r[k][3]));
        [
            l(tri.q[k][0], tri.r[k][0]) + u * c - x * w,
            l(tri.q[k][1], tri.r[k][1]) + tri.k * v * c - y * w,
            l(tri.q[k][2], tri.r[k][2]),
            w,
        ]
    });
    let e: [f64; 3] = std::array::from_fn(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        p[i][0] * p[j][1] - p[i][1] * p[j][0]
    });
    let d: f64 = (0..3).map(|k| e[k] * p[k][3]).sum();
    let n: f64 = (0..3).map(|k| e[k] * p[k][2]).sum();
    (d != 0.0 && e.iter().all(|&ek| ek * d > 0.0)).then(|| n / d)
}

/// Samples of the tile and the domain: every corner at the lens corners and shutter
/// ends, then random points with each coordinate at an end of its range one time in
/// three.
fn dense(g: &mut ChaCha8Rng, tile: &Tile, n: usize) -> Vec<[f64; 5]> {
    let lo = [tile.x0 as f64, tile.y0 as f64, -1.0, -1.0, 0.0];
    let hi = [tile.x1 as f64, tile.y1 as f64, 1.0, 1.0, 1.0];
    let mut out: Vec<[f64; 5]> =
        (0..32usize).map(|c| std::array::from_fn(|i| if c >> i & 1 == 1 { hi[i] } else { lo[i] })).collect();
    for _ in 0..n {
        out.push(std::array::from_fn(|i| match g.gen_range(0..6) {
            0 => lo[i],
            1 => hi[i],
            _ => g.gen_range(lo[i]..=hi[i]),
        }));
    }
    out
}

/// Samples pushed from `s` towards random points of the box by 1e-9 to 1e-2 of the
/// box: where the extreme depth is reached, just beside the estimate.
fn around(g: &mut ChaCha8Rng, tile: &Tile, s: [f64; 5], n: usize) -> Vec<[f64; 5]> {
    let lo = [tile.x0 as f64, tile.y0 as f64, -1.0, -1.0, 0.0];
    let hi = [tile.x1 as f64, tile.y1 as f64, 1.0, 1.0, 1.0];
    (0..n)
        .map(|_| {
            let f = [1e-9, 1e-6, 1e-4, 1e-2][g.gen_range(0..4)];
            std::array::from_fn(|i| (s[i] + f * (g.gen_range(lo[i]..=hi[i]) - s[i])).clamp(lo[i], hi[i]))
        })
        .collect()
}

fn beyond(tri: &Tri, s: [f64; 5], z: f64, lower: bool) -> bool {
    let (z0, z1) = if lower { (z, f64::INFINITY) } else { (f64::NEG_INFINITY, z) };
    matches!(classify_depth(tri, s, z0, z1), DepthCheck::Below | DepthCheck::Above)
}

#[test]
fn no_depth_end_the_cuts_prove_is_beaten_by_an_exact_attack() {
    let mut g = ChaCha8Rng::seed_from_u64(0xde9_7c07);
    let (mut proved, mut near, mut refused_inside, mut tried, mut violations, mut real_points) =
        (0usize, 0usize, 0usize, 0usize, 0usize, 0usize);
    // Tiles tried (CULLPROOF_DEPTH_ATTACK=N for a longer attack).
    let tiles = std::env::var("CULLPROOF_DEPTH_ATTACK").ok().and_then(|v| v.parse().ok()).unwrap_or(160);
    while tried < tiles {
        let tri = triangle(&mut g);
        // A tile of 1, 4 or 16 px around an interior sample.
        let size = [1.0f32, 4.0, 16.0][g.gen_range(0..3)];
        let probe = Tile { x0: -400.0, x1: 400.0, y0: -400.0, y1: 400.0 };
        let Some(c) = dense(&mut g, &probe, 4000).into_iter().find(|&s| depth_estimate(&tri, s).is_some()) else {
            continue;
        };
        let (ax, ay) = (g.gen_range(0.0..size), g.gen_range(0.0..size));
        let (x0, y0) = ((c[0] as f32 - ax).floor(), (c[1] as f32 - ay).floor());
        let tile = Tile { x0, x1: x0 + size, y0, y1: y0 + size };
        let est = dense(&mut g, &tile, 3000);
        let seen: Vec<([f64; 5], f64)> = est.iter().filter_map(|&s| depth_estimate(&tri, s).map(|d| (s, d))).collect();
        if seen.is_empty() {
            continue;
        }
        tried += 1;
        for lower in [true, false] {
            let pick = |a: &&([f64; 5], f64), b: &&([f64; 5], f64)| a.1.total_cmp(&b.1);
            let &(at, ext) = if lower { seen.iter().min_by(pick) } else { seen.iter().max_by(pick) }.unwrap();
            let e32 = ext as f32;
            let (inward, outward) =
                if lower { (e32.next_up(), e32.next_down()) } else { (e32.next_down(), e32.next_up()) };
            let far = if lower { ext - 1e-3 * ext.abs() - 1e-4 } else { ext + 1e-3 * ext.abs() + 1e-4 };
            let mut attack = est.clone();
            attack.extend(around(&mut g, &tile, at, 400));
            // An end one step inside a depth some sample of the attack reaches.
            let reached = attack.iter().any(|&s| beyond(&tri, s, inward as f64, lower));
            if reached {
                match decide(&tri, &tile, inward as f64, lower, BUDGET, 1e-9) {
                    ConstraintVerdict::Proved => {
                        panic!("end {inward} (lower: {lower}) proved over {tile:?}, but a sample is beyond it\n{tri:?}")
                    }
                    // A violation the search reports must be one: an f32 sample of the
                    // tile and the domain, interior, with its hit depth beyond the end.
                    v @ (ConstraintVerdict::Violation(_) | ConstraintVerdict::ViolationAt(_)) => {
                        let p = match v {
                            ConstraintVerdict::Violation(s) => s.to_oracle(),
                            ConstraintVerdict::ViolationAt(p) => {
                                real_points += 1;
                                p
                            }
                            _ => unreachable!(),
                        };
                        let (lo, hi) = (
                            [tile.x0 as f64, tile.y0 as f64, -1.0, -1.0, 0.0],
                            [tile.x1 as f64, tile.y1 as f64, 1.0, 1.0, 1.0],
                        );
                        assert!(
                            (0..5).all(|i| lo[i] <= p[i] && p[i] <= hi[i]),
                            "violation {p:?} outside the tile {tile:?} or the domain"
                        );
                        assert!(
                            beyond(&tri, p, inward as f64, lower),
                            "violation {p:?} of end {inward} (lower: {lower}) is no violation\n{tri:?}"
                        );
                        violations += 1;
                    }
                    _ => {}
                }
                refused_inside += 1;
            }
            for (z, close) in [(e32 as f64, true), (outward as f64, true), (far, false)] {
                if !proves(&tri, &tile, z, lower, BUDGET, 1e-9) {
                    continue;
                }
                proved += 1;
                near += close as usize;
                attack.extend(dense(&mut g, &tile, 1000));
                for &s in &attack {
                    assert!(
                        !beyond(&tri, s, z, lower),
                        "end {z} (lower: {lower}) proved over {tile:?}, but {s:?} is interior beyond it\n{tri:?}"
                    );
                }
            }
        }
    }
    eprintln!("{proved} depth ends proved and attacked ({near} within an ulp of the estimate); {refused_inside} ends inside a reached depth refused, {violations} of them with a violation found and confirmed ({real_points} at a real point, not an f32 sample)");
    assert!(
        proved > 100 && near > 30 && refused_inside > 100 && violations > 20,
        "{proved} {near} {refused_inside} {violations}"
    );
}

/// The direct cuts of a depth end (`oracles::extents::DepthNumerator`: the depth's
/// numerator `N - z D`, one cut per side of D), certified box by box as the judge does
/// (`box_values_cutting`), attacked in every box they certify: boxes of all sizes
/// around the point of the tile where this file's estimate finds the extreme depth,
/// ends at the estimate, a few f32 steps either side and a little outside; dense exact
/// samples of the box and samples pushed towards the estimate's point. No sample may be
/// interior with a hit depth beyond a certified end; an end inside a depth an interior
/// sample of the box reaches must be refused, and many are.
#[test]
fn no_box_the_direct_depth_cuts_certify_holds_a_sample_beyond_the_end() {
    use oracles::extents::{box_values_cutting, DepthNumerator};
    use oracles::interval::Interval;
    let mut g = ChaCha8Rng::seed_from_u64(0xd1_4ec7);
    let (mut certified, mut refused_reached, mut flips, mut tried, mut samples) =
        (0usize, 0usize, 0usize, 0usize, 0usize);
    let boxes = std::env::var("CULLPROOF_DEPTH_ATTACK").ok().and_then(|v| v.parse().ok()).unwrap_or(1500usize);
    while tried < boxes {
        let tri = triangle(&mut g);
        let size = [1.0f32, 4.0, 16.0][g.gen_range(0..3)];
        let probe = Tile { x0: -400.0, x1: 400.0, y0: -400.0, y1: 400.0 };
        let Some(c) = dense(&mut g, &probe, 4000).into_iter().find(|&s| depth_estimate(&tri, s).is_some()) else {
            continue;
        };
        let (x0, y0) = ((c[0] as f32 - g.gen_range(0.0..size)).floor(), (c[1] as f32 - g.gen_range(0.0..size)).floor());
        let tile = Tile { x0, x1: x0 + size, y0, y1: y0 + size };
        let est = dense(&mut g, &tile, 2000);
        let seen: Vec<([f64; 5], f64)> = est.iter().filter_map(|&s| depth_estimate(&tri, s).map(|d| (s, d))).collect();
        if seen.is_empty() {
            continue;
        }
        let lower = g.gen_bool(0.5);
        let pick = |a: &&([f64; 5], f64), b: &&([f64; 5], f64)| a.1.total_cmp(&b.1);
        let &(at, ext) = if lower { seen.iter().min_by(pick) } else { seen.iter().max_by(pick) }.unwrap();
        // A box around the extreme's point: each side 2^-k of the tile or domain.
        let lo = [tile.x0 as f64, tile.y0 as f64, -1.0, -1.0, 0.0];
        let hi = [tile.x1 as f64, tile.y1 as f64, 1.0, 1.0, 1.0];
        let b: [Interval; 5] = std::array::from_fn(|i| {
            let w = (hi[i] - lo[i]) * 0.5f64.powi(g.gen_range(0..12));
            let a = (at[i] - w * g.gen_range(0.0..1.0)).clamp(lo[i], hi[i] - w);
            Interval::new(a, a + w)
        });
        let steps = g.gen_range(-3i32..=3);
        let mut z = ext as f32;
        for _ in 0..steps.abs() {
            z = if (steps > 0) == lower { z.next_down() } else { z.next_up() };
        }
        let z = if g.gen_bool(0.2) {
            if lower {
                ext - 1e-3 * ext.abs()
            } else {
                ext + 1e-3 * ext.abs()
            }
        } else {
            z as f64
        };
        let Some(num) = DepthNumerator::new(&tri, z) else { continue };
        let Some(cuts) = num.cuts(&b, lower) else { continue };
        tried += 1;
        let mut ok = [false; 2];
        box_values_cutting(&tri, &b, &cuts, &mut ok);
        // The attack: the box's corners, dense points, points towards the extreme.
        let mut attack: Vec<[f64; 5]> =
            (0..32usize).map(|c| std::array::from_fn(|i| if c >> i & 1 == 1 { b[i].hi } else { b[i].lo })).collect();
        for _ in 0..300 {
            attack.push(std::array::from_fn(|i| match g.gen_range(0..5) {
                0 => b[i].lo,
                1 => b[i].hi,
                _ => g.gen_range(b[i].lo..=b[i].hi),
            }));
        }
        let inside: [f64; 5] = std::array::from_fn(|i| at[i].clamp(b[i].lo, b[i].hi));
        for _ in 0..100 {
            let f = [1e-9, 1e-6, 1e-4, 1e-2][g.gen_range(0..4)];
            attack.push(std::array::from_fn(|i| {
                (inside[i] + f * (g.gen_range(b[i].lo..=b[i].hi) - inside[i])).clamp(b[i].lo, b[i].hi)
            }));
        }
        let reached = attack.iter().any(|&s| beyond(&tri, s, z, lower));
        if ok.iter().all(|&o| o) {
            certified += 1;
            // D at the lens centre (it does not depend on the pixel).
            let d0 = |t: f64| {
                let l = |a: f64, b: f64| a + (b - a) * t;
                let p: [[f64; 3]; 3] = std::array::from_fn(|k| {
                    [l(tri.q[k][0], tri.r[k][0]), l(tri.q[k][1], tri.r[k][1]), l(tri.q[k][3], tri.r[k][3])]
                });
                p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])
                    + p[1][2] * (p[2][0] * p[0][1] - p[2][1] * p[0][0])
                    + p[2][2] * (p[0][0] * p[1][1] - p[0][1] * p[1][0])
            };
            flips += (d0(0.0) * d0(1.0) < 0.0) as usize;
            samples += attack.len();
            assert!(
                !reached,
                "end {z} (lower: {lower}) certified over the box {b:?}, but a sample of it is interior beyond the end\n{tri:?}"
            );
        } else if reached {
            refused_reached += 1;
        }
    }
    eprintln!("{tried} boxes: {certified} certified and attacked with {samples} exact samples ({flips} of a triangle that flips during the shutter); {refused_reached} refused where a sample is beyond");
    assert!(certified > 300 && refused_reached > 50 && flips > 5, "{certified} {refused_reached} {flips}");
}
