//! The shrinker: simpler cases and tiles that keep a violation.

use crate::bounds::MethodRef;
use crate::gate::{judge, CheckConfig};
use crate::judge::Judgement;
use crate::model::{Case, Tile};

/// One shrinking step: a simpler case and tile to try.
type Step = (&'static str, Case, Tile);

/// Drop the lens when an edit leaves the triangle no longer matching it (the case
/// becomes a per-vertex CoC case, judged by the exact oracle alone).
fn keep_lens_if_matching(mut c: Case) -> Case {
    if let Some(l) = &c.lens {
        if l.check_matches(&c.triangle).is_err() {
            c.lens = None;
        }
    }
    c
}

pub(super) fn round_bits(v: f32, bits: u32) -> f32 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let drop = 24 - bits;
    let b = v.to_bits();
    let half = 1u32 << (drop - 1);
    f32::from_bits(((b + half) >> drop) << drop)
}

/// Candidate simplifications, simplest first.
pub(super) fn steps(case: &Case, tile: &Tile, witness: [f64; 5]) -> Vec<Step> {
    let mut out: Vec<Step> = Vec::new();
    let t = case.triangle;
    if t.q != t.r || t.c0 != t.c1 {
        // Freeze the motion at the witness's time.
        let s = witness[4] as f32;
        let mut c = *case;
        for i in 0..3 {
            for j in 0..4 {
                let v = (1.0 - s) * t.q[i][j] + s * t.r[i][j];
                c.triangle.q[i][j] = v;
                c.triangle.r[i][j] = v;
            }
            let cc = (1.0 - s) * t.c0[i] + s * t.c1[i];
            c.triangle.c0[i] = cc;
            c.triangle.c1[i] = cc;
        }
        out.push(("freeze motion", keep_lens_if_matching(c), *tile));
    }
    if t.c0.iter().chain(&t.c1).any(|&c| c != 0.0) {
        let mut c = *case;
        c.triangle.c0 = [0.0; 3];
        c.triangle.c1 = [0.0; 3];
        out.push(("zero the CoC", keep_lens_if_matching(c), *tile));
    }
    for bits in [4u32, 8, 12, 16, 20] {
        let mut c = *case;
        let r = |v: &mut f32| *v = round_bits(*v, bits);
        c.triangle.q.iter_mut().flatten().for_each(r);
        c.triangle.r.iter_mut().flatten().for_each(r);
        c.triangle.c0.iter_mut().for_each(r);
        c.triangle.c1.iter_mut().for_each(r);
        if c != *case {
            out.push(("snap to fewer mantissa bits", keep_lens_if_matching(c), *tile));
        }
    }
    if t.k != 1.0 {
        let mut c = *case;
        c.triangle.k = 1.0;
        out.push(("aspect k = 1", keep_lens_if_matching(c), *tile));
    }
    // Move the depths to a corner of their range: every vertex to w = 1 at both shutter
    // ends (each divided by its w, CoC included, so its screen position and
    // screen-space CoC at t = 0 and t = 1 stay; only the perspective goes).
    let ws = t.q.iter().chain(&t.r).map(|p| p[3]);
    if ws.clone().all(|w| w > 0.0) && ws.clone().any(|w| w != 1.0) {
        let mut c = *case;
        let unit = |p: [f32; 4]| [p[0] / p[3], p[1] / p[3], p[2] / p[3], 1.0];
        c.triangle.q = t.q.map(unit);
        c.triangle.r = t.r.map(unit);
        c.triangle.c0 = std::array::from_fn(|i| t.c0[i] / t.q[i][3]);
        c.triangle.c1 = std::array::from_fn(|i| t.c1[i] / t.r[i][3]);
        out.push(("depths to w = 1", keep_lens_if_matching(c), *tile));
    }
    // Shrink the tile around the witness to the next smaller power-of-two tile.
    let size = (tile.x1 - tile.x0).min(tile.y1 - tile.y0);
    if size > 1.0 {
        let half = size / 2.0;
        let x0 = tile.x0 + if witness[0] as f32 >= tile.x0 + half { half } else { 0.0 };
        let y0 = tile.y0 + if witness[1] as f32 >= tile.y0 + half { half } else { 0.0 };
        out.push(("shrink the tile", *case, Tile::square(x0, y0, half)));
    }
    out
}

/// Shrink a violation: repeatedly take the first simplification under which the
/// method still shows a violation at least half as large (a culled covered tile, margin
/// inf, must stay one): a gross failure is never traded for a rounding one. Returns the
/// last case, tile and judgement, and the steps kept.
pub fn shrink(
    cfg: &CheckConfig,
    m: &MethodRef,
    case: Case,
    tile: Tile,
    first: Judgement,
    index: u64,
) -> (Case, Tile, Judgement, Vec<String>) {
    let floor = 0.5 * first.violation.as_ref().expect("a violation").margin;
    shrink_while(cfg, m, case, tile, first, index, &|j| j.violation.as_ref().is_some_and(|v| v.margin >= floor))
}

/// [`shrink`], keeping a step while `keep` holds of the method's judgement on it (the
/// witness of the last judgement is the one simplifications are centred on).
pub fn shrink_while(
    cfg: &CheckConfig,
    m: &MethodRef,
    case: Case,
    tile: Tile,
    first: Judgement,
    index: u64,
    keep: &dyn Fn(&Judgement) -> bool,
) -> (Case, Tile, Judgement, Vec<String>) {
    let (mut case, mut tile, mut j) = (case, tile, first);
    let mut kept = Vec::new();
    'outer: for _ in 0..64 {
        let w = j.violation.as_ref().expect("a violation").sample;
        for (name, c, t) in steps(&case, &tile, w) {
            if c.validate().is_err() || !crate::cases::place::placed_in(cfg.viewport, &c, &t) {
                continue;
            }
            let (js, _) = judge(cfg, std::slice::from_ref(m), &c, &t, index);
            if js[0].violation.is_some() && keep(&js[0]) {
                (case, tile, j) = (c, t, js[0].clone());
                kept.push(name.to_string());
                continue 'outer;
            }
        }
        break;
    }
    (case, tile, j, kept)
}
