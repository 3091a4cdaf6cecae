//! The eight extents a search can be asked for, named, and what a search needs to know
//! about each: the key of a box, the value at a witness, and where to look for
//! witnesses.

use super::elimination::{clipped_point, depth_extreme_points, Polygon};
use super::enclosure::{Box5, BoxValues};
use crate::coverage::certainly_interior;
use crate::interval::Interval;
use crate::tri::Tri;

/// One end of one extent of the covered set over a tile: the infimum (`*Min`) or the
/// supremum (`*Max`) of the lens coordinates u and v, of the time t, or of the hit depth
/// z. The order of [`Extent::ALL`] is that of [`TileExtents::extremes`](super::TileExtents::extremes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Extent {
    UMin,
    UMax,
    VMin,
    VMax,
    TMin,
    TMax,
    ZMin,
    ZMax,
}

impl Extent {
    /// Every extent, in the order of [`TileExtents::extremes`](super::TileExtents::extremes).
    pub const ALL: [Extent; 8] = [
        Extent::UMin,
        Extent::UMax,
        Extent::VMin,
        Extent::VMax,
        Extent::TMin,
        Extent::TMax,
        Extent::ZMin,
        Extent::ZMax,
    ];

    /// The end of sample coordinate `index` (2: u, 3: v, 4: t); None for another index.
    pub fn coord(index: usize, max: bool) -> Option<Extent> {
        let n = match index {
            2 => 0,
            3 => 2,
            4 => 4,
            _ => return None,
        };
        Some(Extent::ALL[n + max as usize])
    }
    /// The end of the hit depth.
    pub fn depth(max: bool) -> Extent {
        if max {
            Extent::ZMax
        } else {
            Extent::ZMin
        }
    }
    /// Position in [`Extent::ALL`].
    pub fn position(self) -> usize {
        self as usize
    }
    /// A supremum (else an infimum).
    pub fn is_max(self) -> bool {
        self.position() % 2 == 1
    }
    /// The sample coordinate this extent is of (2: u, 3: v, 4: t; see
    /// [`Box5`]); None for the hit depth.
    pub fn sample_coord(self) -> Option<usize> {
        match self {
            Extent::UMin | Extent::UMax => Some(2),
            Extent::VMin | Extent::VMax => Some(3),
            Extent::TMin | Extent::TMax => Some(4),
            Extent::ZMin | Extent::ZMax => None,
        }
    }
    /// A short name: "u min", ..., "z max".
    pub fn name(self) -> &'static str {
        ["u min", "u max", "v min", "v max", "t min", "t max", "z min", "z max"][self.position()]
    }
    pub(super) fn objective(self) -> Objective {
        match self.sample_coord() {
            Some(index) => Objective::Coord { index, max: self.is_max() },
            None => Objective::Depth { max: self.is_max() },
        }
    }
}

/// What a search optimises, in the form its code matches on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Objective {
    /// Coordinate index 2 (u), 3 (v) or 4 (t); minimised or maximised.
    Coord { index: usize, max: bool },
    /// The hit depth (clip z / w of the hit).
    Depth { max: bool },
}

impl Objective {
    pub(super) fn is_max(self) -> bool {
        matches!(self, Objective::Coord { max: true, .. } | Objective::Depth { max: true })
    }
}

/// Lower bound (for a minimum) of the objective over a box, as a key to minimise.
pub(super) fn key_of(obj: Objective, b: &Box5, bv: &BoxValues) -> f64 {
    match obj {
        Objective::Coord { index, max: false } => b[index].lo,
        Objective::Coord { index, max: true } => -b[index].hi,
        Objective::Depth { max } => {
            // Both enclosures hold the depth of every covered sample of the box: the
            // tighter end of the two.
            let (lo, hi) = match (bv.depth, bv.vertex_depth) {
                (Some(a), Some(v)) => (a.lo.max(v.lo), a.hi.min(v.hi)),
                (Some(a), None) | (None, Some(a)) => (a.lo, a.hi),
                (None, None) => (f64::NEG_INFINITY, f64::INFINITY),
            };
            // (and the bounds the elimination certified)
            let (lo, hi) = (lo.max(bv.covered_depth.lo), hi.min(bv.covered_depth.hi));
            if max {
                -hi
            } else {
                lo
            }
        }
    }
}

/// An enclosure of the objective's value at a point (a coordinate exactly; the depth as
/// an outward-rounded quotient, whole line if D's enclosure holds 0).
pub(super) fn value_at(tri: &Tri, obj: Objective, s: [f64; 5]) -> Interval {
    match obj {
        Objective::Coord { index, .. } => Interval::point(s[index]),
        Objective::Depth { .. } => {
            crate::coverage::depth_enclosure(tri, s).unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY))
        }
    }
}

/// Witness candidates in a box: the point nearest the bound being sought (objective at
/// its end, the rest at the centre), the centre, the far end (each with (x, y) clipped
/// into the projected triangle where it meets the tile; the far end only with
/// elimination), then a few points drawn
/// from a generator seeded by the box itself (so runs are reproducible). Near an
/// extreme the covered set is often a thin wedge through a box corner that its centre
/// misses; scattered points find it.
pub(super) fn candidate_points(tri: &Tri, obj: Objective, b: &Box5, eliminate: bool) -> Vec<[f64; 5]> {
    // With elimination also the clipped point at a (u, v, t) for any signs of w (the
    // search tries the corners of the box's (u, v, t) when none of these is interior).
    let clip =
        |p: [f64; 5]| clipped_centroid(tri, p, b).or_else(|| if eliminate { clipped_point(tri, p, b) } else { None });
    let centre = b.map(|i| i.mid());
    let mut pts = Vec::with_capacity(9);
    if let (Objective::Depth { max }, true) = (obj, eliminate) {
        // The vertex of the covered polygon at the box's middle (u, v, t) where the
        // depth is extreme, nudged inside.
        pts.extend(depth_extreme_points(tri, centre, b, max));
    }
    // The centroid of the projected triangle (at the box's centre in u, v, t) clipped to
    // the box's (x, y) rectangle, when that is not empty: near an extreme the triangle
    // only grazes the tile and scattered points miss it.
    if let Some((cx, cy)) = clip(centre) {
        let mut p = centre;
        (p[0], p[1]) = (cx, cy);
        if let Objective::Coord { index, max } = obj {
            let mut near = p;
            near[index] = if max { b[index].hi } else { b[index].lo };
            if let Some((nx, ny)) = clip(near) {
                (near[0], near[1]) = (nx, ny);
                pts.push(near);
            }
        }
        pts.push(p);
    }
    if let Objective::Coord { index, max } = obj {
        let mut near = centre;
        near[index] = if max { b[index].hi } else { b[index].lo };
        pts.push(near);
        pts.push(centre);
        let mut far = centre;
        far[index] = if max { b[index].lo } else { b[index].hi };
        // The box's far end in the objective's coordinate, clipped: where the covered
        // set only begins inside the box (an edge or vertex grazing the tile), the near
        // end and the centre can both miss it.
        // (With elimination only: the gate's side searches keep their proposals.)
        if let Some((fx, fy)) = clip(far).filter(|_| eliminate) {
            let mut p = far;
            (p[0], p[1]) = (fx, fy);
            pts.push(p);
        }
        pts.push(far);
    } else {
        pts.push(centre);
    }
    if eliminate && !pts.is_empty() {
        return pts;
    }
    let mut seed = b
        .iter()
        .fold(0x9E37_79B9_7F4A_7C15u64, |h, i| (h ^ i.lo.to_bits()).wrapping_mul(0x100_0000_01B3) ^ i.hi.to_bits());
    for _ in 0..4 {
        let p = std::array::from_fn(|k| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let f = (seed >> 11) as f64 / (1u64 << 53) as f64;
            let v = b[k].lo + f * (b[k].hi - b[k].lo);
            v.clamp(b[k].lo, b[k].hi)
        });
        pts.push(p);
    }
    pts
}

/// The centroid of the triangle projected at (u, v, t) = `s[2..5]`, clipped to the
/// box's (x, y) rectangle (plain f64: it only proposes points, which are then judged
/// exactly). None when a vertex is not in front or the clipped polygon is empty.
pub(super) fn clipped_centroid(tri: &Tri, s: [f64; 5], b: &Box5) -> Option<(f64, f64)> {
    let (u, v, t) = (s[2], s[3], s[4]);
    let mut poly = Polygon::new();
    for i in 0..3 {
        let at = |j: usize| (1.0 - t) * tri.q[i][j] + t * tri.r[i][j];
        let c = (1.0 - t) * tri.c0[i] + t * tri.c1[i];
        let w = at(3);
        if w.is_nan() || w <= 0.0 {
            return None;
        }
        poly.push(((at(0) + u * c) / w, (at(1) + tri.k * v * c) / w));
    }
    // Sutherland-Hodgman against the four sides.
    let sides: [(usize, f64, bool); 4] =
        [(0, b[0].lo, true), (0, b[0].hi, false), (1, b[1].lo, true), (1, b[1].hi, false)];
    for (axis, lim, keep_above) in sides {
        let inside = |p: &(f64, f64)| {
            let c = if axis == 0 { p.0 } else { p.1 };
            if keep_above {
                c >= lim
            } else {
                c <= lim
            }
        };
        let mut out = Polygon::new();
        for k in 0..poly.len() {
            let (a, bb) = (poly.at(k), poly.at(k + 1));
            let (ia, ib) = (inside(&a), inside(&bb));
            if ia {
                out.push(a);
            }
            if ia != ib {
                let (ca, cb) = if axis == 0 { (a.0, bb.0) } else { (a.1, bb.1) };
                let f = (lim - ca) / (cb - ca);
                out.push((a.0 + f * (bb.0 - a.0), a.1 + f * (bb.1 - a.1)));
            }
        }
        poly = out;
        if poly.is_empty() {
            return None;
        }
    }
    let (cx, cy) = poly.centroid()?;
    Some((cx.clamp(b[0].lo, b[0].hi), cy.clamp(b[1].lo, b[1].hi)))
}

/// How [`push_towards_bound`] moves a witness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Push {
    /// At a fixed (x, y), bisecting as far as f64 goes.
    FixedXy,
    /// A step whose point is outside is tried again at the centroid of the covered
    /// polygon at its (u, v, t) (within the box's rectangle): the covered pixels move
    /// with the lens and the time, and near an extreme they shrink to a point that a
    /// fixed (x, y) leaves early. The bisection stops once its step is within `tol`.
    AlongPolygon { tol: f64 },
}

/// From an interior point, move the objective coordinate towards the box's bound by
/// bisection, every step certified interior by the fast path of the classifier (a point
/// it cannot certify counts as outside: the witness stays a hair short of the boundary
/// there, at no cost in exact arithmetic), so a witness hugs the boundary of the
/// covered set instead of sitting where it was drawn. See [`Push`] for the two ways.
pub(super) fn push_towards_bound(tri: &Tri, obj: Objective, p: [f64; 5], b: &Box5, push: Push) -> [f64; 5] {
    let Objective::Coord { index, max } = obj else { return p };
    let (tol, along) = match push {
        Push::FixedXy => (0.0, false),
        Push::AlongPolygon { tol } => (tol, true),
    };
    let mut inside = p;
    let mut out = p;
    out[index] = if max { b[index].hi } else { b[index].lo };
    if certainly_interior(tri, out) {
        return out;
    }
    for _ in 0..48 {
        let mut mid = inside;
        mid[index] = inside[index] + 0.5 * (out[index] - inside[index]);
        if mid[index] == inside[index] || mid[index] == out[index] || (out[index] - inside[index]).abs() <= tol {
            break;
        }
        if certainly_interior(tri, mid) {
            inside = mid;
            continue;
        }
        if let Some((x, y)) = clipped_point(tri, mid, b).filter(|_| along) {
            let mut moved = mid;
            (moved[0], moved[1]) = (x, y);
            if certainly_interior(tri, moved) {
                inside = moved;
                continue;
            }
        }
        out = mid;
    }
    inside
}
