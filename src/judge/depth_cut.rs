//! Deciding a depth end that lies within a rounding of the covered set's depth extent.
//!
//! A depth claim "depth >= Z" (a lower end; "<= Z" an upper one) drops the interior
//! samples whose hit depth lies beyond it. A tight bound (a -safe variant rounds the
//! exact extent outward to the next f32) leaves a gap of an ulp or two that the extent
//! search cannot close, and the moving plane checked over the whole tile
//! ([`oracles::extents::depth_end_by_planes`]) fails wherever the triangle's plane
//! passes beyond Z over pixels the triangle does not cover.
//!
//! Here the claim is a per-sample constraint for the constraint search
//! ([`crate::judge::constraints`]): its exact value culls an interior sample beyond Z, and each
//! box offers the three cuts of the moving-plane certificate
//! ([`oracles::extents::depth_plane_cuts`]): `s F_k >= 0` for every vertex k implies the
//! claim at an interior sample. Each cut is certified with the edge values' multipliers
//! (no interior sample of the box with `s F_k < 0`), so the pixels the triangle does not
//! cover no longer count, and near the extreme the combination cancels the first-order
//! part the plane and the edges share. A box the search cannot close, or a sample where
//! some `s F_k < 0` (the plane heuristic failing, which is no violation), leaves the end
//! unproven. A sample the search finds interior and beyond
//! the end (both decided exactly) is a violation of the end.

use crate::bounds::{SampleBox, SampleConstraint, TileBounds};
use crate::judge::constraints::ConstraintVerdict;
use crate::model::{Sample, Tile};
use crate::Interval;
use oracles::extents::{Cut, DepthNumerator, Slopes};
use oracles::{DepthCheck, Tri};

/// A depth end as a constraint: interior samples with a hit depth below `z` (a lower
/// end) or above it are culled.
#[derive(Clone, Debug)]
struct DepthClaim {
    tri: Tri,
    z: f64,
    lower: bool,
    /// `N - z D` as a polynomial, for the direct cuts (None when it cannot be built).
    numerator: Option<DepthNumerator>,
}

impl DepthClaim {
    /// True at an interior point whose hit depth lies beyond the end (exact).
    fn beyond(&self, p: &[f64; 5]) -> bool {
        let (z0, z1) = if self.lower { (self.z, f64::INFINITY) } else { (f64::NEG_INFINITY, self.z) };
        let beyond = if self.lower { DepthCheck::Below } else { DepthCheck::Above };
        oracles::classify_depth(&self.tri, *p, z0, z1) == beyond
    }
}

impl SampleConstraint for DepthClaim {
    fn name(&self) -> String {
        (if self.lower { "z min" } else { "z max" }).into()
    }
    /// -1 at an interior sample beyond the end, 1 elsewhere (exact).
    fn eval(&self, s: &Sample) -> f32 {
        if self.beyond(&s.to_oracle()) {
            -1.0
        } else {
            1.0
        }
    }
    /// 1 over a box where every vertex keeps `s (z_k - z w_k) >= 0` at both ends of its
    /// time range (`s` = 1 for a lower end): those terms are affine in t, so they keep
    /// it over the range, and at an interior sample the depth beyond z is their
    /// combination with positive weights (`depth - z = sum_k (E_k / D) (z_k - z w_k)`,
    /// [`oracles::extents::depth_plane_cuts`]), so nothing there is culled. Unknown
    /// elsewhere: only the cuts (or an empty box) close it.
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let s = Interval::point(if self.lower { 1.0 } else { -1.0 });
        let lerp = |p: f64, q: f64, t: f64| {
            let t = Interval::point(t);
            (Interval::point(1.0) - t) * Interval::point(p) + t * Interval::point(q)
        };
        let holds = (0..3).all(|k| {
            [b.t.lo, b.t.hi].into_iter().all(|t| {
                let (z, w) = (lerp(self.tri.q[k][2], self.tri.r[k][2], t), lerp(self.tri.q[k][3], self.tri.r[k][3], t));
                (s * (z - Interval::point(self.z) * w)).lo >= 0.0
            })
        });
        if holds {
            Interval::point(1.0)
        } else {
            Interval::new(-1.0, 1.0)
        }
    }
    /// The three moving-plane cuts over the box: where all hold, an interior sample's
    /// depth is beyond no end, and elsewhere `eval` culls only interior samples beyond
    /// it, so at a sample where every cut holds `eval` is 1.
    fn lower_cuts(&self, b: &SampleBox, out: &mut Vec<Cut>) -> bool {
        self.lower_cuts_of(b, 0, out)
    }
    /// Family 0: the plane's slopes; family 1: the balanced slopes, which a vertex behind
    /// the lens does not defeat; family 2: the widest slopes, which stay finite where the
    /// triangle turns edge-on ([`Slopes`]). All certify the same way. Family 3: the
    /// depth's numerator itself, one cut per side of D ([`DepthNumerator`]), which no
    /// facing flip defeats.
    fn cut_families(&self) -> usize {
        4
    }
    fn lower_cuts_of(&self, b: &SampleBox, family: usize, out: &mut Vec<Cut>) -> bool {
        let slopes = match family {
            1 => Slopes::Plane,
            2 => Slopes::Balanced,
            3 => Slopes::Widest,
            0 => {
                let cuts = self.numerator.as_ref().and_then(|n| n.cuts(&[b.x, b.y, b.u, b.v, b.t], self.lower));
                return match cuts {
                    Some(cuts) => {
                        out.extend(cuts);
                        true
                    }
                    None => false,
                };
            }
            _ => return false,
        };
        match oracles::extents::depth_cuts(&self.tri, [b.x, b.y, b.u, b.v, b.t], self.z, self.lower, slopes) {
            Some(cuts) => {
                out.extend(cuts);
                true
            }
            None => false,
        }
    }
}

/// The verdict of the constraint search on a depth end: `Proved` when no interior sample
/// of the tile, at any lens position and time, has a hit depth beyond `z` (below it for
/// a `lower` end), certified with the vertex terms and the families of cuts within
/// `budget` boxes; `Violation(s)` with an f32 sample of the tile, or `ViolationAt(p)`
/// with a real point of it, that the search found interior and beyond the end (both
/// decided exactly, by [`oracles::classify_depth`] and [`oracles::classify`]); anything
/// else when neither is shown. A `z` that is not finite is `Undecided`.
pub fn decide(tri: &Tri, tile: &Tile, z: f64, lower: bool, budget: usize, min_width: f64) -> ConstraintVerdict {
    if !z.is_finite() {
        return ConstraintVerdict::Undecided;
    }
    let mut b = TileBounds::full();
    let numerator = DepthNumerator::new(tri, z);
    let claim = DepthClaim { tri: *tri, z, lower, numerator };
    let beyond = |p: &[f64; 5]| claim.beyond(p);
    b.constraints.push(Box::new(claim.clone()));
    crate::judge::constraints::search_claim(tri, tile, &b, budget, min_width, &beyond).verdict
}

/// True when [`decide`] proves the end.
pub fn proves(tri: &Tri, tile: &Tile, z: f64, lower: bool, budget: usize, min_width: f64) -> bool {
    decide(tri, tile, z, lower, budget, min_width) == ConstraintVerdict::Proved
}
