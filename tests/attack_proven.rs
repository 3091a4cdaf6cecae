//! An independent attack on the gate's "proven" verdicts: for every method x tile pair
//! the default judge proves, sample exactly just beyond each claim of the answer (a
//! slab next to each narrowed interval end, at a few widths; the samples a per-sample
//! constraint rejects; the whole tile for a culled tile) and judge every sample with the
//! exact classifier. One interior sample the answer skips is a false "proven".
//!
//! The cases come from this file's own generator (screen positions up to a few
//! thousand pixels, moving and defocused, one vertex behind the lens in half of them;
//! tiles of 1 to 4 pixels on an edge), not from the gate's regimes.
//! `CULLPROOF_ATTACK_CASES=N` attacks N cases (default 120).

use cullproof::bounds::registry;
use cullproof::gate::{judge, CheckConfig};
use cullproof::judge::Verdict;
use cullproof::{Case, Sample, Tile, TileResult, Triangle};
use oracles::coverage::{classify, Coverage};
use oracles::{classify_depth, DepthCheck};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_case(rng: &mut ChaCha8Rng) -> (Triangle, Tile) {
    let centre = [rng.gen_range(-3000.0..3000.0f64), rng.gen_range(-3000.0..3000.0f64)];
    let spread = [4.0, 40.0, 400.0][rng.gen_range(0..3)];
    let behind = rng.gen_bool(0.5);
    let lens = rng.gen_bool(0.75);
    let motion = rng.gen_bool(0.75);
    let step = [0.5, 4.0, 40.0][rng.gen_range(0..3)];
    let mut q = [[0.0f32; 4]; 3];
    let mut r = [[0.0f32; 4]; 3];
    let (mut c0, mut c1) = ([0.0f32; 3], [0.0f32; 3]);
    for i in 0..3 {
        for moving in [false, true] {
            let (mut sx, mut sy) =
                (centre[0] + rng.gen_range(-spread..spread), centre[1] + rng.gen_range(-spread..spread));
            if moving {
                // The end position: a step of its own size from the start.
                let p = q[i];
                (sx, sy) = (
                    p[0] as f64 / p[3] as f64 + rng.gen_range(-step..step),
                    p[1] as f64 / p[3] as f64 + rng.gen_range(-step..step),
                );
            }
            let mut w: f64 = rng.gen_range(0.2..20.0);
            if behind && i == 0 {
                w = -rng.gen_range(0.05..10.0);
            }
            let z = w * rng.gen_range(-0.5..1.0) + rng.gen_range(-1.0..1.0);
            let v = [(sx * w) as f32, (sy * w) as f32, z as f32, w as f32];
            if !moving {
                q[i] = v;
            } else {
                r[i] = if motion { v } else { q[i] };
            }
        }
        if lens {
            c0[i] = rng.gen_range(-8.0..8.0);
            c1[i] = if motion { rng.gen_range(-8.0..8.0) } else { c0[i] };
        }
    }
    let tri = Triangle { q, r, c0, c1, k: if lens { rng.gen_range(0.5..2.0) } else { 1.0 } };
    let size = [1.0, 2.0, 4.0][rng.gen_range(0..3)];
    let t = rng.gen_range(0.0..1.0f32);
    let proj = |i: usize| {
        let p = tri.at(i, t);
        (p[0] as f64 / p[3] as f64, p[1] as f64 / p[3] as f64)
    };
    let (a, b) = (proj(1), proj(2));
    let f = rng.gen_range(0.0..1.0);
    let (px, py) = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
    let (px, py) = if px.is_finite() && py.is_finite() && px.abs() < 1e5 && py.abs() < 1e5 {
        (px, py)
    } else {
        (centre[0], centre[1])
    };
    // On the edge or up to a few tiles off it: tiles the triangle's motion and defocus
    // sweep only partly (where bounds narrow something) or not at all (where they cull).
    let off = [0.0, 2.0, 8.0][rng.gen_range(0..3)] * size;
    let (px, py) = (px + rng.gen_range(-off..=off), py + rng.gen_range(-off..=off));
    let x0 = (px - rng.gen_range(0.0..size)).floor() as f32;
    let y0 = (py - rng.gen_range(0.0..size)).floor() as f32;
    (tri, Tile::square(x0, y0, size as f32))
}

/// A sample of the tile and the domain, with `fix` coordinates set (index, value).
fn draw(rng: &mut ChaCha8Rng, tile: &Tile, fix: Option<(usize, f64)>) -> [f64; 5] {
    let mut s = [
        rng.gen_range(tile.x0 as f64..=tile.x1 as f64),
        rng.gen_range(tile.y0 as f64..=tile.y1 as f64),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(0.0..=1.0),
    ];
    if let Some((k, v)) = fix {
        s[k] = v;
    }
    s
}

/// Samples near a vertex that sits on one of the tile's columns or rows: the lens
/// position or time is solved so that vertex k's screen x (or y) is the column (row),
/// then nudged by up to 1e-3; the pixel is put a little inside the tile, next to the
/// vertex, at distances from 1e-7 to 1e-1 pixels.
fn vertex_tips(rng: &mut ChaCha8Rng, tri: &oracles::Tri, tile: &Tile, n: usize) -> Vec<[f64; 5]> {
    let mut out = Vec::new();
    for _ in 0..n {
        let k = rng.gen_range(0..3);
        let axis = rng.gen_range(0..2); // 0: x columns with u, 1: y rows with v
        let side = if rng.gen_bool(0.5) { [tile.x0, tile.y0][axis] } else { [tile.x1, tile.y1][axis] } as f64;
        let mut s = draw(rng, tile, None);
        let lens = 2 + axis;
        // P_k's coordinate on this axis minus side * w, as a + b l (l the lens
        // coordinate) at time t, and as c + d t at lens l.
        let kk = if axis == 0 { 1.0 } else { tri.k };
        let at = |l: f64, t: f64| {
            let p = (1.0 - t) * tri.q[k][axis] + t * tri.r[k][axis];
            let w = (1.0 - t) * tri.q[k][3] + t * tri.r[k][3];
            let c = (1.0 - t) * tri.c0[k] + t * tri.c1[k];
            (p + kk * l * c - side * w, kk * c, w)
        };
        if rng.gen_bool(0.5) {
            let (v0, slope, _) = at(0.0, s[4]);
            if slope != 0.0 {
                s[lens] = (-v0 / slope).clamp(-1.0, 1.0);
            }
        } else {
            let (a, _, _) = at(s[lens], 0.0);
            let (b, _, _) = at(s[lens], 1.0);
            if a != b {
                s[4] = (a / (a - b)).clamp(0.0, 1.0);
            }
        }
        let nudge = [0.0, 1e-7, 1e-5, 1e-3][rng.gen_range(0..4)];
        s[lens] = (s[lens] + rng.gen_range(-nudge..=nudge)).clamp(-1.0, 1.0);
        s[4] = (s[4] + rng.gen_range(-nudge..=nudge)).clamp(0.0, 1.0);
        // The vertex's screen position there, and the pixel next to it.
        let (u, v, t) = (s[2], s[3], s[4]);
        let scr = |j: usize| {
            let p = (1.0 - t) * tri.q[k][j] + t * tri.r[k][j];
            let c = (1.0 - t) * tri.c0[k] + t * tri.c1[k];
            let l = if j == 0 { u } else { tri.k * v };
            let w = (1.0 - t) * tri.q[k][3] + t * tri.r[k][3];
            (p + l * c) / w
        };
        let (vx, vy) = (scr(0), scr(1));
        if !(vx.is_finite() && vy.is_finite()) {
            continue;
        }
        let d = [1e-7, 1e-5, 1e-3, 1e-1][rng.gen_range(0..4)];
        let ang: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
        s[0] = (vx + d * ang.cos()).clamp(tile.x0 as f64, tile.x1 as f64);
        s[1] = (vy + d * ang.sin()).clamp(tile.y0 as f64, tile.y1 as f64);
        out.push(s);
    }
    out
}

/// Samples the answer skips, drawn next to each of its claims; the first interior one
/// (or one whose depth lies beyond the claimed depth range) is returned.
fn attack(rng: &mut ChaCha8Rng, tri: &oracles::Tri, tile: &Tile, answer: &TileResult, n: usize) -> Option<String> {
    let covered = |s: [f64; 5]| classify(tri, s) == Coverage::Interior;
    match answer {
        TileResult::Empty => {
            (0..8 * n).map(|_| draw(rng, tile, None)).find(|&s| covered(s)).map(|s| format!("culled tile covers {s:?}"))
        }
        TileResult::Bounds(b) => {
            let ends = [(2, b.u, -1.0, 1.0), (3, b.v, -1.0, 1.0), (4, b.t, 0.0, 1.0)];
            for (k, r, lo, hi) in ends {
                for (end, limit, below) in [(r[0] as f64, lo, true), (r[1] as f64, hi, false)] {
                    let narrowed = if below { end > limit } else { end < limit };
                    if !narrowed {
                        continue;
                    }
                    for width in [1e-7, 1e-5, 1e-3, 1e-1] {
                        for _ in 0..n {
                            let f: f64 = rng.gen_range(0.0..1.0);
                            let v = if below { end - f * width } else { end + f * width };
                            let v = v.clamp(lo, hi);
                            if (below && v >= end) || (!below && v <= end) {
                                continue;
                            }
                            let s = draw(rng, tile, Some((k, v)));
                            if covered(s) {
                                return Some(format!("coordinate {k} = {v} beyond the end {end}: {s:?} is covered"));
                            }
                        }
                    }
                }
            }
            if let Some(z) = b.z {
                for _ in 0..4 * n {
                    let s = draw(rng, tile, None);
                    if matches!(classify_depth(tri, s, z[0] as f64, z[1] as f64), DepthCheck::Below | DepthCheck::Above)
                    {
                        return Some(format!("depth of {s:?} outside [{}, {}]", z[0], z[1]));
                    }
                }
            }
            if !b.constraints.is_empty() {
                for _ in 0..8 * n {
                    let s = draw(rng, tile, None);
                    let f = Sample::new(s[0] as f32, s[1] as f32, s[2] as f32, s[3] as f32, s[4] as f32);
                    let fs = f.to_oracle();
                    if !b.admits(&f) && covered(fs) {
                        return Some(format!("a constraint culls the covered sample {fs:?}"));
                    }
                }
                // Where the covered set comes closest to what a separating bound culls:
                // a vertex on a tile column or row, samples just inside the triangle's
                // tip there.
                for s in vertex_tips(rng, tri, tile, 8 * n) {
                    let f = Sample::new(s[0] as f32, s[1] as f32, s[2] as f32, s[3] as f32, s[4] as f32);
                    let fs = f.to_oracle();
                    if tile.contains(f.x, f.y) && !b.admits(&f) && covered(fs) {
                        return Some(format!("a constraint culls the covered sample {fs:?} (vertex tip)"));
                    }
                }
            }
            None
        }
    }
}

#[test]
fn no_proven_pair_is_beaten_by_an_exact_attack() {
    let cases = std::env::var("CULLPROOF_ATTACK_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(120);
    let methods = registry();
    let cfg = CheckConfig::default_with(methods.clone());
    let mut rng = ChaCha8Rng::seed_from_u64(0xA77A_C4ED);
    let (mut proven, mut culled_or_narrowed) = (0usize, 0usize);
    let mut failures = Vec::new();
    for i in 0..cases as u64 {
        let (tri, tile) = random_case(&mut rng);
        let case = Case { triangle: tri, lens: None };
        if case.validate().is_err() {
            continue;
        }
        let (js, _) = judge(&cfg, &cfg.methods, &case, &tile, i);
        let otri = tri.to_oracle();
        for (m, j) in cfg.methods.iter().zip(&js) {
            if j.verdict() != Verdict::Proven {
                continue;
            }
            proven += 1;
            let answer = m.setup(&tri).tile(&tile);
            culled_or_narrowed += match &answer {
                TileResult::Empty => 1,
                TileResult::Bounds(b) => {
                    (b.u != [-1.0, 1.0] || b.v != [-1.0, 1.0] || b.t != [0.0, 1.0] || !b.constraints.is_empty())
                        as usize
                }
            };
            if let Some(why) = attack(&mut rng, &otri, &tile, &answer, 60) {
                failures.push(format!("{} case {i}: {why}; {tri:?} {tile:?}", m.info().id));
            }
        }
    }
    eprintln!("{proven} proven method x tile pairs attacked ({culled_or_narrowed} culling or narrowing something)");
    // (a pair whose answer is the whole domain skips nothing: there is nothing to attack)
    assert!(culled_or_narrowed > 2 * cases, "{proven} proven, {culled_or_narrowed} narrowing");
    assert!(failures.is_empty(), "{} false proven verdicts:\n{}", failures.len(), failures.join("\n"));
}
