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
//!
//! Only the x axis's time part of the reject is asserted: when it says Empty the whole
//! answer is Empty (`tile_answer`'s non-empty flag is a conjunction with it), and the
//! lens thresholds' divisions and the y axis stay out of the script. Asserting the
//! whole answer's reject instead made a query z3 4.8.12 did not decide within 900 s.

use super::arith::TriOf;
use super::bbox_query::{assert_reach, check_range, default_ranges, instance, template, Side, INPUTS};
use super::family::Family;
use super::smt::Smt;
use crate::bounds::la2011::{setup_of, Nearest, Outward, Round};
use crate::model::{Tile, Triangle};

/// The la2011 family: `safe` false for `la2011`, true for `la2011-safe`.
#[derive(Clone, Copy, Debug)]
pub struct La2011Family {
    pub safe: bool,
}

impl Family for La2011Family {
    fn inputs(&self) -> &'static [&'static str] {
        &INPUTS
    }
    fn sides(&self) -> &'static [&'static str] {
        &["x-min", "x-max"]
    }
    fn tile_inputs(&self) -> &'static [usize] {
        &[3]
    }
    fn default_ranges(&self, side: usize) -> Vec<Vec<[f32; 2]>> {
        default_ranges(side)
    }
    fn check_range(&self, k: usize, lo: f32, _hi: f32) -> Result<(), String> {
        check_range(k, lo)
    }
    fn assert_violation(&self, smt: &Smt, side: usize, v: &[String]) {
        let v = [v[0].clone(), v[1].clone(), v[2].clone(), v[3].clone()];
        if self.safe {
            assert_time_reject::<Outward>(smt, Side::of(side), &v)
        } else {
            assert_time_reject::<Nearest>(smt, Side::of(side), &v)
        }
    }
    fn instance(&self, side: usize, v: &[f32]) -> (Triangle, Tile) {
        instance(Side::of(side), [v[0], v[1], v[2], v[3]])
    }
}

/// The template's triangle and tile, la2011's setup, its x time part asserted to say
/// Empty, and the exact footprint asserted to reach into the tile.
fn assert_time_reject<R: Round>(smt: &Smt, side: Side, v: &[String; 4]) {
    let (tri, tile): (TriOf<String>, [String; 4]) = template(smt, side, v);
    let s = setup_of::<R, Smt>(smt, &tri);
    let (time_ok, _) = s.x.time::<R, Smt>(smt, &[tile[0].clone(), tile[2].clone()]);
    smt.assert(&format!("(not {time_ok})"));
    assert_reach(smt, side, v);
}

/// The family of `id`, if it is la2011 or la2011-safe.
pub fn family_of(id: &str) -> Option<La2011Family> {
    match id {
        "la2011" => Some(La2011Family { safe: false }),
        "la2011-safe" => Some(La2011Family { safe: true }),
        _ => None,
    }
}
