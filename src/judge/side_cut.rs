//! Deciding an interval side that lies within a rounding of the covered set's extent.
//!
//! A side claim "u <= U" (or u >= U, and the same for v and t) culls the samples beyond
//! `U`. A tight bound (a -safe variant rounds the exact extent outward to the next f32)
//! leaves a gap of an ulp or two between the extent and the claim: the extent search
//! that bounds the covered set box by box cannot close boxes that touch the covered set
//! at its extreme point, however small it makes them.
//!
//! The side is also a per-sample constraint whose value is exactly the linear function
//! `U - u` (a maximum) or `u - U` (a minimum): where it is `>= 0` the sample is kept.
//! Given as a [`Cut`] with no error, the constraint search ([`crate::judge::constraints`]) certifies
//! it with the multipliers of the (x, y) elimination: non-negative `lambda` with
//! `sum lambda_k sigma E_k + lambda_3 (u - U) <= 0` on a box (for a maximum) prove that
//! no interior sample of the box lies beyond the claim. Near the extreme point the
//! combination cancels the first-order part that the edge values and the claim share
//! (the KKT multipliers of the extreme), so the boxes it closes are about the square
//! root of the gap wide instead of the gap itself. Every box it cannot close is split
//! or left open; a witness is an f32 sample beyond the claim that the exact oracle
//! confirms interior.

use crate::bounds::{SampleBox, SampleConstraint, TileBounds};
use crate::judge::constraints::ConstraintVerdict;
use crate::model::{Sample, Tile};
use crate::Interval;
use oracles::extents::Cut;
use oracles::Tri;

/// One interval side as a constraint: coordinate `coord` (2 u, 3 v, 4 t) is kept when
/// `<= bound` (a maximum) or `>= bound` (a minimum).
#[derive(Clone, Copy, Debug)]
pub struct SideClaim {
    pub coord: usize,
    pub bound: f32,
    pub is_max: bool,
}

impl SideClaim {
    fn of(&self, s: &Sample) -> f32 {
        match self.coord {
            2 => s.u,
            3 => s.v,
            _ => s.t,
        }
    }
    fn range(&self, b: &SampleBox) -> Interval {
        match self.coord {
            2 => b.u,
            3 => b.v,
            _ => b.t,
        }
    }
}

impl SampleConstraint for SideClaim {
    fn name(&self) -> String {
        let c = ["u", "v", "t"][self.coord.clamp(2, 4) - 2];
        format!("{c} {}", if self.is_max { "max" } else { "min" })
    }
    /// 1 where the sample is kept, -1 beyond the claim (an exact comparison).
    fn eval(&self, s: &Sample) -> f32 {
        let c = self.of(s);
        let kept = if self.is_max { c <= self.bound } else { c >= self.bound };
        if kept {
            1.0
        } else {
            -1.0
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let r = self.range(b);
        let bound = self.bound as f64;
        let (all_kept, none_kept) =
            if self.is_max { (r.hi <= bound, r.lo > bound) } else { (r.lo >= bound, r.hi < bound) };
        if all_kept {
            Interval::point(1.0)
        } else if none_kept {
            Interval::point(-1.0)
        } else {
            Interval::new(-1.0, 1.0)
        }
    }
    /// `U - c` (a maximum) or `c - U` (a minimum), exact: where it is `>= 0` the sample
    /// is kept.
    fn lower_cut(&self, _b: &SampleBox) -> Option<Cut> {
        let mut cut = Cut::zero();
        let m = 1usize << self.coord;
        let sign = if self.is_max { -1.0 } else { 1.0 };
        cut.coef[m] = sign;
        cut.coef[0] = -sign * self.bound as f64;
        Some(cut)
    }
}

/// Search the tile and the whole lens/shutter domain for an interior sample beyond the
/// claim, certifying the boxes it closes with the claim's cut (pixels split too, see
/// [`crate::judge::constraints::search_with`]). `Proved` means no interior sample of the tile lies
/// beyond it; a `Violation` is an f32 sample beyond it that the exact oracle confirmed
/// interior.
pub fn decide(tri: &Tri, tile: &Tile, claim: SideClaim, budget: usize, min_width: f64) -> ConstraintVerdict {
    let mut b = TileBounds::full();
    b.constraints.push(Box::new(claim));
    crate::judge::constraints::search_with(tri, tile, &b, budget, min_width, true).verdict
}
