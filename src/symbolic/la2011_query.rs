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

fn script_of<R: Round>(q: &Query) -> String {
    let smt = Smt::new();
    let v = INPUTS.map(|n| smt.var(n));
    for (name, r) in v.iter().zip(&q.ranges) {
        smt.range(name, r[0], r[1]);
    }
    let (tri, tile) = template(&smt, q.side, &v);
    let s = setup_of::<R, Smt>(&smt, &tri);
    let (nonempty, ..) = tile_answer::<R, Smt>(&smt, &s, &tile);
    smt.assert(&format!("(not {nonempty})"));
    let [a, c, w, t] = &v;
    let reach = match q.side {
        Side::XMin => {
            let lo = smt.fma_mode("RTN", t, w, c);
            let hi = smt.fma_mode("RTP", t, w, c);
            format!("(or (fp.lt {a} {lo}) (and (fp.eq {a} {lo}) (fp.lt {lo} {hi})))")
        }
        Side::XMax => {
            let mc = super::arith::F32Arith::neg(&smt, c);
            let lo = smt.fma_mode("RTN", t, w, &mc);
            let hi = smt.fma_mode("RTP", t, w, &mc);
            format!("(or (fp.gt {a} {hi}) (and (fp.eq {a} {hi}) (fp.lt {lo} {hi})))")
        }
    };
    smt.assert(&reach);
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
