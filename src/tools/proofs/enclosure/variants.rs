//! The variants the enclosure check traces, and what each must show.

use super::check::{Check, Failure, Outcome};
use super::trace::{Bn, Trace, N};
use crate::bounds::arith::{End, F32Arith};
use crate::bounds::proofs::BBOX_PAD;
// ---------------------------------------------------------------------------------
// The variants checked.

use crate::bounds::arith::TriOf;
use crate::bounds::round::{Outward, Round};

/// A triangle and a tile of fresh inputs.
fn inputs(t: &Trace) -> (TriOf<N>, [N; 4]) {
    let v = |p: &str, i: usize| ["x", "y", "z", "w"].map(|c| t.input(&format!("{p}{i}.{c}")));
    let tri = TriOf {
        q: [0, 1, 2].map(|i| v("q", i)),
        r: [0, 1, 2].map(|i| v("r", i)),
        c0: [0, 1, 2].map(|i| t.input(&format!("c0.{i}"))),
        c1: [0, 1, 2].map(|i| t.input(&format!("c1.{i}"))),
        k: t.input("k"),
    };
    let tile = ["x0", "y0", "x1", "y1"].map(|n| t.input(n));
    (tri, tile)
}

/// What a traced tile answer must show: its output ends (each of its side), and its
/// culls (each implying its exact counterpart).
type Demands = (Vec<(N, End, String)>, Vec<(Bn, String)>);

fn ends(name: &str, v: &[N; 2]) -> [(N, End, String); 2] {
    [(v[0], End::Lo, format!("{name} lower")), (v[1], End::Hi, format!("{name} upper"))]
}

/// The traced tile answer of `la2011` written with the arithmetic `R`: its outputs.
fn la2011<R: Round>(t: &Trace) -> Demands {
    use crate::bounds::la2011::{setup_of, tile_answer};
    let (tri, tile) = inputs(t);
    let s = setup_of::<R, Trace>(t, &tri);
    let (nonempty, tt, u, v) = tile_answer::<R, Trace>(t, &s, &tile);
    ([ends("t", &tt), ends("u", &u), ends("v", &v)].concat(), vec![(t.not(&nonempty), "tile reject".into())])
}

/// The traced tile answer of `nilsson2012-depth` written with the arithmetic `R`: the
/// depth range's ends.
fn nilsson<R: Round>(t: &Trace) -> Demands {
    use crate::bounds::nilsson2012_depth::{setup_of, tile_answer};
    let (tri, tile) = inputs(t);
    let s = setup_of::<R, Trace>(t, &tri);
    let (nonempty, z) = tile_answer::<R, Trace>(t, &s, &tile);
    (ends("z", &z).to_vec(), vec![(t.not(&nonempty), "tile reject".into())])
}

/// The traced tile answer of `mam2012-safe` written with the arithmetic `R`: the u and
/// v ranges' ends, the tile reject, and each per-sample line's cull at a sample
/// `(t, u, v)` of the shutter (each line's value below 0 must put the sample beyond the
/// line through its ends' exact values).
fn mam2012<R: Round>(t: &Trace) -> Demands {
    use crate::bounds::mam2012::{answer_of, line_eval, rejects_of, setup_safe_of};
    let (tri, tile) = inputs(t);
    let (why, axes) = setup_safe_of::<R, Trace>(t, &tri);
    let enabled = t.not(&t.any(&why));
    let [au, av] = [(0, 0, 2), (1, 1, 3)].map(|(a, lo, hi)| answer_of::<R, Trace>(t, &axes[a], &tile[lo], &tile[hi]));
    let reject = rejects_of(t, &why, &au, &av);
    let mut culls = vec![(reject, "tile reject".to_string())];
    let mut outs = vec![];
    let (st, zero, one) = (t.input("t"), t.lit(0.0), t.lit(1.0));
    for (name, a) in [("u", &au), ("v", &av)] {
        let w = t.input(name);
        // (An empty tile's range and lines are never read: demanded all the same.)
        let kept = t.and(&enabled, &t.not(&a.full));
        let r = [t.select(&kept, &a.range[0], &t.lit(-1.0)), t.select(&kept, &a.range[1], &one)];
        outs.extend(ends(name, &r));
        for (upper, (ok, la, lb)) in [false, true].into_iter().zip(&a.lines) {
            let g = line_eval::<R, Trace>(t, upper, la, lb, &st, &w);
            let shutter = t.and(&t.le(&zero, &st), &t.le(&st, &one));
            let cull = t.all(&[kept, *ok, shutter, t.lt(&g, &zero)]);
            culls.push((cull, format!("{name}t {} line", if upper { "upper" } else { "lower" })));
        }
    }
    (outs, culls)
}

/// The traced per-sample answer of `gdam2010-safe` written with the arithmetic `R`, at
/// a sample position `(X, Y)` and for a piece `[l, h]` of the shutter (any f32 values:
/// the cut points only decide where pieces end): the piece's cull, and the cull of the
/// whole shutter of a triangle whose vertices do not move. Each must imply its exact
/// counterpart: some edge's three exact Bernstein coefficients on the piece at or below
/// minus its pad and some edge's at or above its pad, with the pad `>= 0`.
fn gdam2010<R: Round>(t: &Trace) -> Demands {
    use crate::bounds::gdam2010::{end_of, piece_of, sample_of, still_of};
    let (tri, _) = inputs(t);
    let xyw = |p: &[N; 4]| [p[0], p[1], p[3]];
    let (q, r) = (tri.q.each_ref().map(xyw), tri.r.each_ref().map(xyw));
    let [x, y, l, h] = ["X", "Y", "l", "h"].map(|n| t.input(n));
    let s = sample_of::<R, Trace>(t, &q, &r, &x, &y, true);
    let (el, eh) = (end_of::<R, Trace>(t, &s, &l), end_of::<R, Trace>(t, &s, &h));
    let (piece, _) = piece_of::<R, Trace>(t, &s, &el, &eh);
    let e0 = end_of::<R, Trace>(t, &s, &t.lit(0.0));
    let (still, _) = still_of::<R, Trace>(t, &s, &e0);
    (vec![], vec![(piece, "piece cull".to_string()), (still, "still-triangle cull".to_string())])
}

/// The traced tile answer of `lb2011-safe` written with the arithmetic `R`: the t, u
/// and v ranges' ends, the tile reject, and each patch's cull at a sample `(l, t)` of
/// the lens and the shutter (a patch's value below 0 must put the sample where the
/// exact patch through its pinned corner values is below 0). Each patch's f32 value is
/// declared an upper end of that exact patch by [`EVAL_LEMMA`](crate::bounds::lb2011::EVAL_LEMMA)
/// on the formula of `lb2011_safe.g` built with the script's own constants
/// (`script_text`), where the code tests the script's limit on the corner values.
fn lb2011<R: Round>(t: &Trace, script_text: &str) -> Result<Demands, String> {
    let (tri, tile) = inputs(t);
    let ((reject, tt, u, v), culls) = lb2011_parts::<R>(t, script_text, &tri, &tile)?;
    let outs = kept_ends(t, &t.not(&reject), [("t", &tt), ("u", &u), ("v", &v)]);
    Ok((outs, [vec![(reject, "tile reject".to_string())], culls].concat()))
}

/// The ends of a kept tile's t, u and v ranges (the full domain where it is not kept: a
/// rejected tile's ranges are never read, and are demanded all the same where kept).
fn kept_ends(t: &Trace, kept: &Bn, ranges: [(&str, &[N; 2]); 3]) -> Vec<(N, End, String)> {
    let mut outs = vec![];
    for (name, r) in ranges {
        let full = if name == "t" { [0.0, 1.0] } else { [-1.0, 1.0] };
        let r = [t.select(kept, &r[0], &t.lit(full[0])), t.select(kept, &r[1], &t.lit(full[1]))];
        outs.extend(ends(name, &r));
    }
    outs
}

/// `lb2011-safe`'s traced tile answer `(reject, t, u, v)` for a triangle and a tile, and
/// its four patches' culls (see [`lb2011`]).
type LbParts = ((Bn, [N; 2], [N; 2], [N; 2]), Vec<(Bn, String)>);

fn lb2011_parts<R: Round>(t: &Trace, script_text: &str, tri: &TriOf<N>, tile: &[N; 4]) -> Result<LbParts, String> {
    use crate::bounds::lb2011::{axis_answer, axis_of, coefficients, eval_of, largest, tile_of, EVAL_LEMMA};
    use crate::tools::proofs::check::constant_in;
    let constant = |name| constant_in(crate::bounds::proofs::LB_PAD.file, script_text, name).map(|v| v as f32);
    let (pad, floor, limit) = (constant("PAD")?, constant("FLOOR")?, constant("LIMIT")?);
    let [ax, ay] = [0, 1].map(|a| axis_of::<R, Trace>(t, tri, a));
    let (xa, xp) = axis_answer::<R, Trace>(t, &ax, &tile[0], &tile[2]);
    let (ya, yp) = axis_answer::<R, Trace>(t, &ay, &tile[1], &tile[3]);
    let answer = tile_of(t, &xa, &ya);
    let mut culls = vec![];
    let (st, zero, one) = (t.input("t"), t.lit(0.0), t.lit(1.0));
    let shutter = [t.le(&zero, &st), t.le(&st, &one)];
    for (name, patches) in [("u", &xp), ("v", &yp)] {
        let l = t.input(name);
        let lens = [t.le(&t.lit(-1.0), &l), t.le(&l, &one)];
        for (p, which) in patches.iter().zip(["min", "max"]) {
            // The script's formula: the coefficients of the corner values, the constant
            // term padded by RN(RN(mg PAD) + FLOOR) and stepped up, then the evaluation.
            let [cp, cq, cr, cs] = coefficients(t, &p.g);
            let mg = largest(t, &p.g);
            let padded = t.next_up(&t.add(&cp, &t.add(&t.mul(&mg, &t.lit(pad)), &t.lit(floor))));
            let x = eval_of(t, &[padded, cq, cr, cs], &l, &st);
            let exact = eval_of(t, &[cp, cq, cr, cs], &l, &st);
            let conds = [t.lt(&mg, &t.lit(limit)), lens[0], lens[1], shutter[0], shutter[1]];
            t.known_end_if(x, End::Hi, exact, &conds, EVAL_LEMMA);
            let g = eval_of(t, &p.coef, &l, &st);
            let cull = t.all(&[p.emit, lens[0], lens[1], shutter[0], shutter[1], t.lt(&g, &zero)]);
            culls.push((cull, format!("{name}t {which} patch")));
        }
    }
    Ok((answer, culls))
}

/// The traced tile answer of `lc-safe` written with the arithmetic `R`: `la2011-safe`'s
/// and `lb2011-safe`'s answers for one triangle and tile, met as [`TileResult::and`]
/// meets them ([`crate::bounds::meet_of`], each interval; Empty when either part is or a
/// met interval is empty): the met t, u and v ranges' ends, the tile reject, and
/// `lb2011-safe`'s four patches' culls.
///
/// [`TileResult::and`]: crate::bounds::TileResult::and
fn lc<R: Round>(t: &Trace, script_text: &str) -> Result<Demands, String> {
    use crate::bounds::la2011::{setup_of, tile_answer};
    use crate::bounds::meet_of;
    let (tri, tile) = inputs(t);
    let s = setup_of::<R, Trace>(t, &tri);
    let (nonempty, ta, ua, va) = tile_answer::<R, Trace>(t, &s, &tile);
    let ((lb_reject, tb, ub, vb), culls) = lb2011_parts::<R>(t, script_text, &tri, &tile)?;
    let met = [(&ta, &tb), (&ua, &ub), (&va, &vb)].map(|(a, b)| meet_of(t, a, b));
    let empty: Vec<Bn> = met.iter().map(|r| t.gt(&r[0], &r[1])).collect();
    let reject = t.any(&[t.not(&nonempty), lb_reject, t.any(&empty)]);
    let outs = kept_ends(t, &t.not(&reject), [("t", &met[0]), ("u", &met[1]), ("v", &met[2])]);
    Ok((outs, [vec![(reject, "tile reject".to_string())], culls].concat()))
}

/// The lemma of `wu2013_safe.g`, as the check applies it.
pub const WU_LEMMA: &str = "wu2013_safe.g: for line endpoints |e_left|, |e_right| <= LIMIT and a lens value \
     |l| <= 1, the padded line's f32 value fl(fl(a l) + b') is finite and at or above a l + b (upper lines; lower \
     lines: at or below)";

/// The traced tile answer of `wu2013-safe` written with the arithmetic `R`: the u, v
/// and t ranges' ends, the tile reject, and each per-sample line's cull at a sample
/// `(l, t)` with `|l| <= 1` (a line's value below 0 must put the sample beyond the line
/// `a l + b` through its pinned intercept). Each line's f32 value
/// `fl(fl(a l) + b')` is declared an end of `a l + b` by [`WU_LEMMA`] on the formula of
/// `wu2013_safe.g` built with the script's own constants (`script_text`), where the
/// code tests the script's limit on the endpoints.
fn wu2013<R: Round>(t: &Trace, script_text: &str) -> Result<Demands, String> {
    use crate::bounds::wu2013::{line_gap, setup_of, tile_answer};
    use crate::tools::proofs::check::constant_in;
    let constant = |name| constant_in(crate::bounds::proofs::WU_PAD.file, script_text, name).map(|v| v as f32);
    let (pad, floor, limit) = (constant("PAD")?, constant("FLOOR")?, constant("LIMIT")?);
    let (tri, tile) = inputs(t);
    let (finite, axes) = setup_of::<R, Trace>(t, &tri);
    let a = tile_answer::<R, Trace>(t, &axes, &tile);
    let kept = t.and(&finite, &t.not(&a.reject));
    let outs = kept_ends(t, &kept, [("u", &a.u), ("v", &a.v), ("t", &a.t)]);
    let mut culls = vec![(t.and(&finite, &a.reject), "tile reject".to_string())];
    let st = t.input("t");
    for (name, cut) in [("u", &a.lines[0]), ("v", &a.lines[1])] {
        let l = t.input(name);
        let lens = [t.le(&t.lit(-1.0), &l), t.le(&l, &t.lit(1.0))];
        for (upper, side) in [true, false].into_iter().zip(cut) {
            let c = &side.line;
            // The script's formula: p = RN(RN(RN(RN(|a| + |a|) + |b|) + FLOOR) * PAD),
            // b' = the step outward of RN(b +- p), x = RN(RN(a l) + b').
            let sum = t.add(&t.add(&t.add(&t.abs(&c.a), &t.abs(&c.a)), &t.abs(&c.b)), &t.lit(floor));
            let p = t.mul(&sum, &t.lit(pad));
            let padded = if upper {
                t.moved_out(&t.next_up(&t.add(&c.b, &p)), &c.b, End::Hi)
            } else {
                t.moved_out(&t.next_down(&t.sub(&c.b, &p)), &c.b, End::Lo)
            };
            let x = t.add(&t.mul(&c.a, &l), &padded);
            let exact = t.add(&t.mul(&c.a, &l), &c.b);
            let within = c.ends.map(|e| t.le(&t.abs(&e), &t.lit(limit)));
            let conds = [within[0], within[1], lens[0], lens[1]];
            t.known_end_if(x, if upper { End::Hi } else { End::Lo }, exact, &conds, WU_LEMMA);
            let g = line_gap(t, upper, &c.a, &c.padded, &l, &st);
            let cull = t.all(&[finite, side.keep, lens[0], lens[1], t.lt(&g, &t.lit(0.0))]);
            culls.push((cull, format!("{name}t {} line", if upper { "upper" } else { "lower" })));
        }
    }
    Ok((outs, culls))
}

/// `bbox-safe`'s corner as `bbox_safe.g` states it, with the script's constants: for the
/// shear `s`, `n = a -+ s` and the depth `w`, `RN(n / w)` moved by the pad
/// `RN(RN(RN(RN(|s| + |n|) + FLOOR) / w) * PAD)`, then `STEPS` steps outward.
fn bbox_script_corner(t: &Trace, s: N, n: N, w: N, k: (f32, f32, usize)) -> [N; 2] {
    let (pad, floor, steps) = k;
    let q = t.div(&n, &w);
    let p = t.mul(&t.div(&t.add(&t.add(&t.abs(&s), &t.abs(&n)), &t.lit(floor)), &w), &t.lit(pad));
    let (mut lo, mut hi) = (t.sub(&q, &p), t.add(&q, &p));
    for _ in 0..steps {
        (lo, hi) = (t.next_down(&lo), t.next_up(&hi));
    }
    [lo, hi]
}

/// The lemma of `bbox_safe.g`, as the check applies it.
pub const BBOX_LEMMA: &str = "bbox_safe.g: the padded corner encloses (a -+ k c) / w for finite inputs, w > 0 \
     (a finite corner value has finite inputs: infinities and NaN propagate)";

/// The traced box of `bbox` with `corner`: the tile reject (which must imply that the
/// exact box misses the tile), with each corner of the script's formula declared an end
/// of its exact value by [`BBOX_LEMMA`].
fn bbox<C: crate::bounds::bbox::Corner>(t: &Trace, corner: &C, script_text: &str) -> Result<Vec<(Bn, String)>, String> {
    use crate::bounds::bbox::{aabb_of, rejects};
    use crate::tools::proofs::check::constant_in;
    let (tri, tile) = inputs(t);
    let (enabled, bx) = aabb_of(t, corner, &tri);
    let constant = |name| constant_in(BBOX_PAD.file, script_text, name).map(|v| v as f32);
    let k = (constant("PAD")?, constant("FLOOR")?, constant("STEPS")? as usize);
    for (p, c) in [(&tri.q, &tri.c0), (&tri.r, &tri.c1)] {
        for i in 0..3 {
            for axis in 0..2 {
                let (a, w) = (p[i][axis], p[i][3]);
                let s = if axis == 0 { c[i] } else { t.mul(&tri.k, &c[i]) };
                for n in [t.sub(&a, &s), t.add(&a, &s)] {
                    let [lo, hi] = bbox_script_corner(t, s, n, w, k);
                    let exact = t.div(&n, &w);
                    t.known_end(lo, End::Lo, exact, w, BBOX_LEMMA);
                    t.known_end(hi, End::Hi, exact, w, BBOX_LEMMA);
                }
            }
        }
    }
    Ok(vec![(rejects(t, &enabled, &bx, &tile), "tile reject".to_string())])
}

/// The variants whose composition the check covers.
pub const CHECKED: &[&str] = &[
    "bbox-safe",
    "la2011-safe",
    "mam2012-safe",
    "nilsson2012-depth-safe",
    "wu2013-safe",
    "gdam2010-safe",
    "lb2011-safe",
    "lc-safe",
];

/// Trace the tile answer of `id` (a variant of [`CHECKED`] or one of its planted slips
/// `broken/planted-no-up/ID`, `broken/planted-no-dn/ID`) and check it: its output ends
/// (la2011-safe: t, u, v; nilsson2012-depth-safe: z; mam2012-safe: u, v) and its culls
/// (the tile reject; mam2012-safe's per-sample lines; gdam2010-safe's pieces).
pub fn check(id: &str) -> Option<Outcome> {
    let base = id.rsplit('/').next()?;
    if !CHECKED.contains(&base) {
        return None;
    }
    check_traced(id)
}

fn finish(t: &Trace, culls: Result<Vec<(Bn, String)>, String>) -> Outcome {
    match culls {
        Ok(culls) => Check::new(t).run_with(&[], &culls),
        Err(e) => {
            Outcome { failures: vec![Failure { what: "the lemma's constants".into(), found: e }], ..Outcome::default() }
        }
    }
}

fn finish_demands(t: &Trace, demands: Result<Demands, String>) -> Outcome {
    match demands {
        Ok((outs, culls)) => Check::new(t).run_with(&outs, &culls),
        Err(e) => {
            Outcome { failures: vec![Failure { what: "the lemma's constants".into(), found: e }], ..Outcome::default() }
        }
    }
}

/// `wu2013-safe` checked against another text of its Gappa script (the lemma's formula
/// takes that text's constants): a control that a script other than the code's is
/// refused.
pub fn check_wu2013_with(script_text: &str) -> Outcome {
    let t = Trace::new();
    finish_demands(&t, wu2013::<Outward>(&t, script_text))
}

/// `lb2011-safe` checked against another text of its Gappa script (the lemma's formula
/// takes that text's constants): a control that a script other than the code's is
/// refused.
pub fn check_lb2011_with(script_text: &str) -> Outcome {
    let t = Trace::new();
    finish_demands(&t, lb2011::<Outward>(&t, script_text))
}

/// `bbox-safe` checked against another text of its Gappa script (the lemma's formula
/// takes that text's constants): a control that a script other than the code's is
/// refused.
pub fn check_bbox_with(script_text: &str) -> Option<Outcome> {
    use crate::bounds::bbox::SafeCorner;
    let t = Trace::new();
    Some(finish(&t, bbox(&t, &SafeCorner, script_text)))
}

/// [`check`] for every variant that can be traced, [`CHECKED`] or not.
pub fn check_traced(id: &str) -> Option<Outcome> {
    use crate::bounds::broken::planted::{NoDn, NoUp};
    let t = Trace::new();
    let base = id.rsplit('/').next()?;
    use crate::bounds::bbox::SafeCorner;
    use crate::bounds::broken::planted::{BandSlip, EqSlip};
    use crate::bounds::broken::planted::{NoDnCorner, NoUpCorner};
    let script = BBOX_PAD.text;
    let culls = match (id.strip_suffix(base)?, base) {
        ("", "bbox-safe") => Some(bbox(&t, &SafeCorner, script)),
        ("broken/planted-no-up/", "bbox-safe") => Some(bbox(&t, &NoUpCorner, script)),
        ("broken/planted-no-dn/", "bbox-safe") => Some(bbox(&t, &NoDnCorner, script)),
        ("broken/planted-eq/", "bbox-safe") => Some(bbox(&t, &EqSlip, script)),
        ("broken/planted-band/", "bbox-safe") => Some(bbox(&t, &BandSlip, script)),
        _ => None,
    };
    if let Some(culls) = culls {
        return Some(finish(&t, culls));
    }
    let (wu_text, lb_text) = (crate::bounds::proofs::WU_PAD.text, crate::bounds::proofs::LB_PAD.text);
    let wu = match (id.strip_suffix(base)?, base) {
        ("", "wu2013-safe") => Some(wu2013::<Outward>(&t, wu_text)),
        ("broken/planted-no-up/", "wu2013-safe") => Some(wu2013::<NoUp>(&t, wu_text)),
        ("broken/planted-no-dn/", "wu2013-safe") => Some(wu2013::<NoDn>(&t, wu_text)),
        ("", "lb2011-safe") => Some(lb2011::<Outward>(&t, lb_text)),
        ("broken/planted-no-up/", "lb2011-safe") => Some(lb2011::<NoUp>(&t, lb_text)),
        ("broken/planted-no-dn/", "lb2011-safe") => Some(lb2011::<NoDn>(&t, lb_text)),
        ("", "lc-safe") => Some(lc::<Outward>(&t, lb_text)),
        ("broken/planted-no-up/", "lc-safe") => Some(lc::<NoUp>(&t, lb_text)),
        ("broken/planted-no-dn/", "lc-safe") => Some(lc::<NoDn>(&t, lb_text)),
        _ => None,
    };
    if let Some(demands) = wu {
        return Some(finish_demands(&t, demands));
    }
    let outs = match (id.strip_suffix(base)?, base) {
        ("", "la2011-safe") => la2011::<Outward>(&t),
        ("broken/planted-no-up/", "la2011-safe") => la2011::<NoUp>(&t),
        ("broken/planted-no-dn/", "la2011-safe") => la2011::<NoDn>(&t),
        ("", "mam2012-safe") => mam2012::<Outward>(&t),
        ("broken/planted-no-up/", "mam2012-safe") => mam2012::<NoUp>(&t),
        ("broken/planted-no-dn/", "mam2012-safe") => mam2012::<NoDn>(&t),
        ("", "nilsson2012-depth-safe") => nilsson::<Outward>(&t),
        ("broken/planted-no-up/", "nilsson2012-depth-safe") => nilsson::<NoUp>(&t),
        ("broken/planted-no-dn/", "nilsson2012-depth-safe") => nilsson::<NoDn>(&t),
        ("", "gdam2010-safe") => gdam2010::<Outward>(&t),
        ("broken/planted-no-up/", "gdam2010-safe") => gdam2010::<NoUp>(&t),
        ("broken/planted-no-dn/", "gdam2010-safe") => gdam2010::<NoDn>(&t),
        _ => return None,
    };
    Some(Check::new(&t).run_with(&outs.0, &outs.1))
}
