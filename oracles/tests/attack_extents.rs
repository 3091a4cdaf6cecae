//! An independent attack on the certified tile extents: for every extent the solver
//! certifies (with the (x, y) elimination on, as `explain`, the tightness ceiling and the
//! second chance use it, and off, as the gate's side searches use it), look for an
//! interior sample beyond the certified end, by dense exact sampling of the tile's box
//! and by a descent that walks interior samples towards the claimed end. Every sample
//! is judged by the exact classifier; the depth is compared with the claim exactly
//! ([`oracles::classify_depth`]). The generator is this file's own: screen-space
//! triangles at coordinates up to a few thousand pixels, moving and defocused, one
//! vertex behind the lens in half of them, on tiles of 1 to 4 pixels where the
//! triangle's edges pass.
//!
//! The default run attacks a few hundred tiles; `CULLPROOF_ATTACK_TILES=N` attacks N
//! (the README gives the count of the long run).

use oracles::coverage::{classify, depth_enclosure, Coverage};
use oracles::extents::{search, Box5, Extent, ExtentsConfig, ObjectiveResult, Search};
use oracles::interval::Interval;
use oracles::{classify_depth, DepthCheck, Tri};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A triangle given by screen positions (pixels), clip w per vertex (negative: behind
/// the lens), depth, motion and circles of confusion; one tile where it may cover.
fn random_case(rng: &mut ChaCha8Rng) -> (Tri, [f64; 4], [bool; 3]) {
    let centre = [rng.gen_range(-3000.0..3000.0f64), rng.gen_range(-3000.0..3000.0f64)];
    let spread = [4.0, 40.0, 400.0][rng.gen_range(0..3)];
    let behind = rng.gen_bool(0.5);
    let lens = rng.gen_bool(0.75);
    let motion = rng.gen_bool(0.75);
    let mut q = [[0.0; 4]; 3];
    let mut r = [[0.0; 4]; 3];
    let (mut c0, mut c1) = ([0.0; 3], [0.0; 3]);
    for i in 0..3 {
        for moving in [false, true] {
            let sx = centre[0] + rng.gen_range(-spread..spread);
            let sy = centre[1] + rng.gen_range(-spread..spread);
            let mut w: f64 = rng.gen_range(0.2..20.0);
            if behind && i == 0 {
                w = -rng.gen_range(0.05..10.0);
            }
            let z = w * rng.gen_range(-0.5..1.0) + rng.gen_range(-1.0..1.0);
            let v = [sx * w, sy * w, z, w];
            if !moving {
                q[i] = v;
            } else {
                r[i] = if motion { v } else { q[i] };
            }
        }
        if lens {
            c0[i] = rng.gen_range(-30.0..30.0);
            c1[i] = if motion { rng.gen_range(-30.0..30.0) } else { c0[i] };
        }
    }
    // f32 inputs, as the tool's cases are.
    let f = |v: f64| v as f32 as f64;
    let tri = Tri {
        q: q.map(|v| v.map(f)),
        r: r.map(|v| v.map(f)),
        c0: c0.map(f),
        c1: c1.map(f),
        k: f(rng.gen_range(0.5..2.0)),
    };
    // A tile on a point of an edge of the triangle at a random (u, v, t) (where w
    // stays in front), else near the centre.
    let size = [1.0, 2.0, 4.0][rng.gen_range(0..3)];
    let s = [0.0, 0.0, rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), rng.gen_range(0.0..1.0)];
    let proj = |i: usize| {
        let t = s[4];
        let at = |j: usize| (1.0 - t) * tri.q[i][j] + t * tri.r[i][j];
        let c = (1.0 - t) * tri.c0[i] + t * tri.c1[i];
        let w = at(3);
        ((at(0) + s[2] * c) / w, (at(1) + tri.k * s[3] * c) / w)
    };
    let (a, b) = (proj(1), proj(2));
    let f = rng.gen_range(0.0..1.0);
    let (px, py) = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
    let (px, py) = if px.is_finite() && py.is_finite() { (px, py) } else { (centre[0], centre[1]) };
    let x0 = (px - rng.gen_range(0.0..size)).floor();
    let y0 = (py - rng.gen_range(0.0..size)).floor();
    (tri, [x0, x0 + size, y0, y0 + size], [lens, lens, motion])
}

/// The value of an extent at an interior sample (the depth as the midpoint of its
/// enclosure: only to steer the descent; claims are checked exactly).
fn value(tri: &Tri, ext: Extent, s: [f64; 5]) -> Option<f64> {
    match ext.sample_coord() {
        Some(i) => Some(s[i]),
        None => depth_enclosure(tri, s).map(|z| 0.5 * (z.lo + z.hi)),
    }
}

/// Is the interior sample `s` beyond the certified end of `ext` (exact)?
fn beyond(tri: &Tri, ext: Extent, s: [f64; 5], end: f64) -> bool {
    match ext.sample_coord() {
        Some(i) => classify(tri, s) == Coverage::Interior && if ext.is_max() { s[i] > end } else { s[i] < end },
        None => {
            let (z0, z1) = if ext.is_max() { (f64::NEG_INFINITY, end) } else { (end, f64::INFINITY) };
            matches!(classify_depth(tri, s, z0, z1), DepthCheck::Below | DepthCheck::Above)
        }
    }
}

/// Attack one certified end: dense samples, then descents from the best of them and from
/// the witness. Returns a sample beyond the end, if found.
fn attack(tri: &Tri, b: &Box5, active: [bool; 5], ext: Extent, end: f64, witness: Option<[f64; 5]>, rng: &mut ChaCha8Rng, dense: usize) -> Option<[f64; 5]> {
    let sg = if ext.is_max() { -1.0 } else { 1.0 };
    let draw = |rng: &mut ChaCha8Rng| -> [f64; 5] {
        std::array::from_fn(|k| if b[k].width() > 0.0 { rng.gen_range(b[k].lo..=b[k].hi) } else { b[k].lo })
    };
    let mut best: Vec<(f64, [f64; 5])> = Vec::new();
    for _ in 0..dense {
        let s = draw(rng);
        if classify(tri, s) != Coverage::Interior {
            continue;
        }
        if beyond(tri, ext, s, end) {
            return Some(s);
        }
        if let Some(v) = value(tri, ext, s) {
            best.push((sg * v, s));
        }
    }
    best.sort_by(|a, c| a.0.total_cmp(&c.0));
    best.truncate(4);
    if let Some(w) = witness {
        if let Some(v) = value(tri, ext, w) {
            best.push((sg * v, w));
        }
    }
    for (mut v, mut s) in best {
        // Pattern search over the active coordinates, steps from the box's width down to
        // 2^-40 of it; a move is kept when it stays interior and improves.
        for k in 0..5 {
            if !active[k] || b[k].width() == 0.0 {
                continue;
            }
        }
        let mut scale = 0.25;
        while scale > 1e-13 {
            let mut moved = false;
            for _ in 0..24 {
                let mut p = s;
                for k in 0..5 {
                    if active[k] && b[k].width() > 0.0 && rng.gen_bool(0.6) {
                        p[k] = (p[k] + rng.gen_range(-1.0..1.0) * scale * b[k].width()).clamp(b[k].lo, b[k].hi);
                    }
                }
                if classify(tri, p) != Coverage::Interior {
                    continue;
                }
                if beyond(tri, ext, p, end) {
                    return Some(p);
                }
                if let Some(pv) = value(tri, ext, p) {
                    if sg * pv < v {
                        (v, s, moved) = (sg * pv, p, true);
                    }
                }
            }
            if !moved {
                scale *= 0.5;
            }
        }
    }
    None
}

fn run(tiles: usize, seed: u64, dense: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let cfg = ExtentsConfig::default();
    let (mut attacked, mut ends, mut behind_tiles) = (0usize, 0usize, 0usize);
    let mut failures = Vec::new();
    while attacked < tiles {
        let (tri, tile, dims) = random_case(&mut rng);
        let active = [true, true, dims[0], dims[1], dims[2]];
        let b: Box5 = [
            Interval::new(tile[0], tile[1]),
            Interval::new(tile[2], tile[3]),
            if dims[0] { Interval::new(-1.0, 1.0) } else { Interval::point(0.0) },
            if dims[1] { Interval::new(-1.0, 1.0) } else { Interval::point(0.0) },
            if dims[2] { Interval::new(0.0, 1.0) } else { Interval::point(0.0) },
        ];
        attacked += 1;
        behind_tiles += (tri.q[0][3] < 0.0) as usize;
        for ext in Extent::ALL {
            if ext.sample_coord().is_some_and(|i| !active[i]) {
                continue;
            }
            for eliminate in [true, false] {
                let r: ObjectiveResult = search(&tri, b, ext, &cfg, Search { eliminate, ..Search::default() });
                let (end, witness) = match r.extreme {
                    Some(e) => (if ext.is_max() { e.hi } else { e.lo }, Some(e.witness)),
                    None if r.undecided == 0 => (if ext.is_max() { f64::NEG_INFINITY } else { f64::INFINITY }, None),
                    None => continue,
                };
                if !end.is_finite() && witness.is_some() {
                    continue;
                }
                ends += 1;
                if let Some(s) = attack(&tri, &b, active, ext, end, witness, &mut rng, dense) {
                    failures.push(format!(
                        "{} (elimination {eliminate}): certified end {end:e}, interior sample {s:?} beyond it; tri {tri:?} tile {tile:?}",
                        ext.name()
                    ));
                }
            }
        }
    }
    eprintln!("attacked {attacked} tiles ({behind_tiles} with a vertex behind the lens), {ends} certified ends");
    assert!(failures.is_empty(), "{} false certified ends:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn no_certified_extent_is_beaten_by_an_exact_attack() {
    let tiles = std::env::var("CULLPROOF_ATTACK_TILES").ok().and_then(|v| v.parse().ok()).unwrap_or(150);
    run(tiles, 23, 1500);
}
