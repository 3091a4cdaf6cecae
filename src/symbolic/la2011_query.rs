//! The symbolic query for `la2011` (and `la2011-safe`): f32 inputs in stated ranges for
//! which the method rejects a tile that the exact footprint reaches.
//!
//! The template is `bbox`'s ([`super::bbox_query::template`]: a static triangle whose
//! left (right) edge is the vertical segment at `(a ∓ c) / w`, the tile
//! `[t - 1, t] x [8, 9]` or `[t, t + 1] x [8, 9]`), and so is the exact side (`a < t w + c`,
//! decided by two fused multiply-adds rounded down and up). The method's side is the whole
//! encoded setup and tile answer of `la2011` ([`crate::bounds::la2011::setup_of`],
//! [`crate::bounds::la2011::tile_answer`]: time chords, lens thresholds and the tile's
//! Empty), with the reject asserted. On this template la2011's time test culls the tile
//! when `fl(fl(a - fl(t w)) - c) > 0` for every vertex and column: the exact difference
//! is `a - t w - c`, so a tile whose column is within a rounding of the edge is the
//! target, as for `bbox`, without a division.

use super::arith::{F32Arith, TriOf};
use super::bbox_query::{template, Query, Side, INPUTS};
use super::smt::Smt;
use crate::bounds::la2011::{setup_of, tile_answer, Nearest, Outward, Round};

/// The SMT-LIB2 script of a query against `la2011` (`safe` false) or `la2011-safe`.
pub fn script(safe: bool, q: &Query) -> String {
    if safe {
        script_of::<Outward>(q)
    } else {
        script_of::<Nearest>(q)
    }
}

/// The query with the whole encoded answer's reject asserted (the lens thresholds and
/// both axes in the script): emitted for `--emit-smt`-style experiments; z3 4.8 did not
/// decide it within 900 s (README).
pub fn script_whole(safe: bool, q: &Query) -> String {
    fn of<R: Round>(q: &Query) -> String {
        let (smt, v, tri, tile) = inputs(q);
        let (nonempty, ..) = tile_answer::<R, Smt>(&smt, &setup_of::<R, Smt>(&smt, &tri), &tile);
        smt.assert(&format!("(not {nonempty})"));
        reach(&smt, q.side, &v);
        smt.script(&v)
    }
    if safe {
        of::<Outward>(q)
    } else {
        of::<Nearest>(q)
    }
}

/// The inputs in their ranges, and the template's triangle and tile.
fn inputs(q: &Query) -> (Smt, [String; 4], TriOf<String>, [String; 4]) {
    let smt = Smt::new();
    let v = INPUTS.map(|n| smt.var(n));
    for (name, r) in v.iter().zip(&q.ranges) {
        smt.range(name, r[0], r[1]);
    }
    let (tri, tile) = template(&smt, q.side, &v);
    (smt, v, tri, tile)
}

fn script_of<R: Round>(q: &Query) -> String {
    let (smt, v, tri, tile) = inputs(q);
    let s = setup_of::<R, Smt>(&smt, &tri);
    // The x axis's time part saying Empty makes the whole answer Empty
    // (`tile_answer`'s `nonempty` is a conjunction with it): the query asserts that part
    // only, so the lens thresholds' divisions and the y axis are not in the script (the
    // whole answer, [`script_whole`], was too hard for z3: see the README figures).
    let (time_ok, _) = s.x.time::<R, Smt>(&smt, &[tile[0].clone(), tile[2].clone()]);
    smt.assert(&format!("(not {time_ok})"));
    reach(&smt, q.side, &v);
    smt.script(&v)
}

/// Whether `id` is queried here: `Some(false)` for `la2011`, `Some(true)` for
/// `la2011-safe`, None otherwise.
pub fn safe_of(id: &str) -> Option<bool> {
    match id {
        "la2011" => Some(false),
        "la2011-safe" => Some(true),
        _ => None,
    }
}

/// Assert that the exact footprint reaches into the tile: `a < t w + c` (x-min) or
/// `a > t w - c` (x-max), decided by two fused multiply-adds rounded down and up.
fn reach(smt: &Smt, side: Side, v: &[String; 4]) {
    let [a, c, w, t] = v;
    let reach = match side {
        Side::XMin => {
            let lo = smt.fma_mode("RTN", t, w, c);
            let hi = smt.fma_mode("RTP", t, w, c);
            format!("(or (fp.lt {a} {lo}) (and (fp.eq {a} {lo}) (fp.lt {lo} {hi})))")
        }
        Side::XMax => {
            let mc = F32Arith::neg(smt, c);
            let lo = smt.fma_mode("RTN", t, w, &mc);
            let hi = smt.fma_mode("RTP", t, w, &mc);
            format!("(or (fp.gt {a} {hi}) (and (fp.eq {a} {hi}) (fp.lt {lo} {hi})))")
        }
    };
    smt.assert(&reach);
}
