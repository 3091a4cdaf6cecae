//! The judge under a declared sample set, vertex snapping and viewport
//! (`docs/model.md`, §7).
//!
//! `SetJudge` wraps the tile judge (`TileJudge`). Under [`SampleSet::Any`] it is the
//! tile judge itself, unchanged. Under a smaller set:
//! - a continuous proof stands (the set is a subset of the tile);
//! - a continuous violation stands when its witness moves to a nearby point of the set
//!   (the same lens position and time) and the exact oracle confirms that point interior
//!   and culled;
//! - otherwise, when the tile holds at most [`MAX_POINTS`] points of the set, every
//!   point is judged on its own: the certified machinery runs on the degenerate box
//!   `[x, x] x [y, y]` (the solver does not split a zero-width side; a static pinhole
//!   triangle's point is classified exactly, as nothing else varies), and the point
//!   judgements are merged;
//! - with more points (a fine grid on a large tile) the case is unproven with the
//!   reason `off-set`: the continuous witness was not a sample of the set, and no
//!   point-wise proof was tried. Never a pass.
//!
//! Snapping replaces the triangle the method sees and the one the oracle judges
//! ([`crate::cases::place::judged_triangles`]).

use super::tile::{culled_by, in_domain, Judgement, TileJudge, Unproven, Witness};
use crate::bounds::TileResult;
use crate::model::samples::SampleSet;
use crate::model::Tile;
use oracles::{classify, Coverage, Tri};
/// The most points of a finite set a tile is judged at one by one (a 16-pixel tile
/// under 16x MSAA); beyond, a witness off the set leaves the case unproven (`off-set`).
pub const MAX_POINTS: u128 = 4096;

/// The tile judge under the run's sample set.
pub(crate) struct SetJudge<'a> {
    pub tj: TileJudge<'a>,
    set: SampleSet,
    /// The point judges, built on first need and shared by the methods.
    points: Option<Vec<TileJudge<'a>>>,
    /// Boxes spent by point judges dropped so far (kept in [`Self::boxes`]).
    extra_boxes: u64,
}

impl<'a> SetJudge<'a> {
    pub fn new(tj: TileJudge<'a>, set: SampleSet) -> Self {
        SetJudge { tj, set, points: None, extra_boxes: 0 }
    }

    /// Boxes the solvers examined.
    pub fn boxes(&self) -> u64 {
        self.tj.solver.boxes + self.extra_boxes + self.points.iter().flatten().map(|p| p.solver.boxes).sum::<u64>()
    }

    /// Judge one tile answer on the set's samples.
    pub fn judge(&mut self, answer: &TileResult) -> Judgement {
        let j = self.tj.judge(answer);
        if self.set.is_any() || j.verdict() == super::Verdict::Proven {
            return j;
        }
        if let Some(w) = &j.violation {
            if let Some(m) = self.mapped(answer, w) {
                return m;
            }
        }
        let t = self.tj.tile;
        let count = self.set.count_in(t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64).unwrap_or(u128::MAX);
        if count <= MAX_POINTS {
            let tri: &Tri = self.tj.tri;
            if let Some(pj) = self.point_judges() {
                return judge_points(pj, tri, answer, t);
            }
        }
        // Too many points to judge one by one: the continuous verdict's reasons stand,
        // a continuous violation off the set proves nothing.
        let mut out = Judgement::default();
        for r in j.unproven() {
            out.add_unproven(r);
        }
        if j.violation.is_some() {
            out.add_unproven(Unproven::OffSet);
        }
        out
    }

    /// A violation on the set next to the continuous witness `w`: the nearest points of
    /// the set with `w`'s lens position and time (exact, then rounded to f32), confirmed
    /// interior and culled. None when no such point is found (or `w` is a depth
    /// witness, which the point-wise judgement handles).
    fn mapped(&self, answer: &TileResult, w: &Witness) -> Option<Judgement> {
        if w.bound.starts_with('z') {
            return None;
        }
        let tile = self.tj.tile;
        for (x, y) in self.set.near(w.sample[0], w.sample[1]).into_iter().take(9) {
            let exact = [x, y, w.sample[2], w.sample[3], w.sample[4]];
            let rounded = [x, y, w.sample[2] as f32 as f64, w.sample[3] as f32 as f64, w.sample[4] as f32 as f64];
            for p in [exact, rounded] {
                if !in_domain(&tile, p) || classify(self.tj.tri, p) != Coverage::Interior {
                    continue;
                }
                // The point is confirmed culled by the answer itself (a NaN interval
                // end culls it with an infinite margin, as `culled_by` says).
                let culled = match answer {
                    TileResult::Empty => Some(("tile culled".to_string(), f64::INFINITY)),
                    TileResult::Bounds(b) => culled_by(b, p),
                };
                if let Some((bound, margin)) = culled {
                    let mut j = Judgement::default();
                    j.f32_witness = p.iter().all(|&c| c as f32 as f64 == c);
                    j.violated.insert(super::bound_kind(&bound), margin);
                    j.violation = Some(Witness { sample: p, bound, margin, embree_hit: None, ..w.clone() });
                    return Some(j);
                }
            }
        }
        None
    }

    /// The point judges of the tile (None when a point is not an f32 value: the tile
    /// lies where f32 cannot hold the set's positions).
    fn point_judges(&mut self) -> Option<&mut Vec<TileJudge<'a>>> {
        if self.points.is_none() {
            let t = self.tj.tile;
            let pts = self.set.points_in(t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64)?;
            if pts.iter().any(|&(x, y)| x as f32 as f64 != x || y as f32 as f64 != y) {
                return None;
            }
            let tj = &self.tj;
            let judges = pts
                .into_iter()
                .map(|(x, y)| {
                    let pt = Tile { x0: x as f32, x1: x as f32, y0: y as f32, y1: y as f32 };
                    TileJudge::new(tj.cfg, tj.case, pt, tj.index, tj.tri, None, &[])
                })
                .collect();
            self.points = Some(judges);
        }
        self.points.as_mut()
    }
}

/// Merge the judgements of every point; witnesses name the whole tile.
fn judge_points(points: &mut [TileJudge<'_>], tri: &Tri, answer: &TileResult, tile: Tile) -> Judgement {
    let fixed = tri.is_static() && tri.is_pinhole();
    let mut out = Judgement::default();
    for pj in points.iter_mut() {
        if fixed {
            // Nothing but (x, y) moves coverage: the point's exact class decides.
            let p = [pj.tile.x0 as f64, pj.tile.y0 as f64, 0.0, 0.0, 0.0];
            match classify(tri, p) {
                Coverage::Interior => {}
                Coverage::Boundary => {
                    out.boundary_only |= matches!(answer, TileResult::Empty);
                    continue;
                }
                Coverage::Outside => continue,
            }
        }
        out.merge(pj.judge(answer));
    }
    if let Some(w) = out.violation.as_mut() {
        w.tile = tile;
    }
    out
}
