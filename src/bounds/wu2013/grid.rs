//! `wu2013` and `wu2013-safe` over a grid of tiles ([`Prepared::grid`]): both tests
//! split by axis. Stage 1's lens range on the x axis reads only the tile's columns
//! `[x0, x1]`, stage 2's crossings and lines on the x axis only those columns and that
//! lens range (the y axis likewise with the rows and v); what is left per tile is to meet
//! the two axes' time ranges in the order [`Prepared::tile`] does and to collect the
//! constraints. Every part is computed by the same functions as in `tile`, so each answer
//! is `tile`'s, bit for bit (`grid_tests.rs`).

use super::safe::{constraints_of, AxisCut, Columns, Iv, IvOps, LineEnds, SafeAxis, SafePrep};
use super::*;
use crate::bounds::arith::Plain;
use crate::bounds::round::Round;

/// The lens range of stage 1 on one axis as `tile` leaves it: `Some(range)` (the full
/// lens when stage 1 gives no bound), or `None` when stage 1 culls the tile.
type LensRange = Option<[f32; 2]>;

// ---------------------------------------------------------------------------------------
// wu2013-safe
// ---------------------------------------------------------------------------------------

/// What one column boundary (or row boundary) `s` gives every column next to it.
struct SafeBoundary {
    /// Per vertex, [`IvOps::at_column`] at `s`.
    at: [(Iv<f32>, Iv<f32>); 3],
    /// Per vertex, [`IvOps::lens_at`] at `s` (only where stage 1 can apply on the axis:
    /// every CoC of one strict sign over the shutter).
    lens: Option<[[Iv<f32>; 2]; 3]>,
    /// Per vertex, [`IvOps::line_ends`] at `s`.
    ends: [LineEnds<f32, bool>; 3],
}

impl SafeBoundary {
    fn new<R: Round>(axis: &SafeAxis<f32>, stage1: bool, s: f32) -> Self {
        let o = IvOps::<Plain, R>::new(&Plain);
        let at = axis.v.each_ref().map(|a| o.at_column(a, &s));
        let ends = std::array::from_fn(|k| o.line_ends(&axis.v[k], &at[k]));
        SafeBoundary { at, lens: stage1.then(|| o.lens_at(axis, &s)), ends }
    }
}

/// One column (x axis) or one row (y axis) of the grid: everything of `tile` that reads
/// that axis only.
struct SafeAxisPart {
    /// Stage 1's lens range (`None`: the tile is culled).
    lens: LensRange,
    /// Stage 2's crossing times as [`IvOps::sign_parts`] (`None`: no time bound from the
    /// axis).
    time: Option<[[f32; 2]; 4]>,
    /// The published lines over the lens range.
    cut: AxisCut<f32, bool>,
}

impl SafeAxisPart {
    /// The part between boundaries `b0` and `b1`, as [`tile_answer`](super::safe) computes it.
    fn new<R: Round>(axis: &SafeAxis<f32>, b0: &SafeBoundary, b1: &SafeBoundary) -> Option<Self> {
        let o = IvOps::<Plain, R>::new(&Plain);
        // Stage 1 where it can apply (else it is off: the full lens).
        let (on, some, r) = match (&b0.lens, &b1.lens) {
            (Some(l0), Some(l1)) => o.stage1(axis, [l0, l1]),
            _ => (false, true, [-1.0, 1.0]),
        };
        if on && !some {
            return None;
        }
        let l = if on { r } else { [-1.0, 1.0] };
        let cols: Columns<f32> = std::array::from_fn(|k| [b0.at[k], b1.at[k]]);
        let (timed, cr) = o.time_crossings(axis, &cols, &l);
        let time = timed.then(|| o.sign_parts(&cr));
        let ends = std::array::from_fn(|k| [b0.ends[k], b1.ends[k]]);
        let (there, e) = o.lines_from(&ends);
        Some(SafeAxisPart { lens: Some(l), time, cut: o.axis_cut(&there, &e, &l) })
    }

    /// Stage 2 of this axis on the time range `t` left by the axes before it: the
    /// sign-aware hull within `t`, then the lines (`None`: the tile is culled).
    fn time_from<R: Round>(&self, mut t: [f32; 2]) -> Option<[f32; 2]> {
        let o = IvOps::<Plain, R>::new(&Plain);
        if let Some(parts) = &self.time {
            let (some, r) = o.hull_within(parts, &t);
            if !some {
                return None;
            }
            t = r;
        }
        Some(o.bound(&self.cut, t))
    }
}

/// The parts of every column (or row) between consecutive `bounds`, each boundary's
/// values computed once (`None`: stage 1 culls that column).
fn safe_parts<R: Round>(axis: &SafeAxis<f32>, bounds: &[f32]) -> Vec<Option<SafeAxisPart>> {
    let stage1 = IvOps::<Plain, R>::new(&Plain).lens_directions(axis).0;
    let at: Vec<SafeBoundary> = bounds.iter().map(|&s| SafeBoundary::new::<R>(axis, stage1, s)).collect();
    at.windows(2).map(|w| SafeAxisPart::new::<R>(axis, &w[0], &w[1])).collect()
}

/// [`SafePrep::grid`]: per column boundary and per row boundary the vertices' column
/// parts, lens crossings and line ends; per column and per row stage 1's lens range,
/// stage 2's crossing hull parts and lines; per column also the time range the x axis
/// leaves (`tile` does the x axis first, from [0, 1]). Per tile: the row's hull within
/// that time range, the row's lines, and the constraints (x first, upper first).
pub(super) struct SafeGrid {
    /// Every input is finite (otherwise every tile gets the full domain, nothing is
    /// computed).
    finite: bool,
    /// Per column: its part and the time range after the x axis (`None`: culled).
    cols: Vec<(Option<SafeAxisPart>, Option<[f32; 2]>)>,
    rows: Vec<Option<SafeAxisPart>>,
    /// The axis's time hull and lines on the rows (with the rounding discipline).
    time_from: fn(&SafeAxisPart, [f32; 2]) -> Option<[f32; 2]>,
}

impl SafeGrid {
    pub(super) fn new<R: Round>(prep: &SafePrep<R>, grid: Grid) -> Self {
        let time_from = |p: &SafeAxisPart, t: [f32; 2]| p.time_from::<R>(t);
        if !prep.finite {
            return SafeGrid { finite: false, cols: Vec::new(), rows: Vec::new(), time_from };
        }
        let cols = safe_parts::<R>(&prep.x, grid.xs)
            .into_iter()
            .map(|p| {
                let t = p.as_ref().and_then(|p| p.time_from::<R>([0.0, 1.0]));
                (p, t)
            })
            .collect();
        let rows = safe_parts::<R>(&prep.y, grid.ys);
        SafeGrid { finite: true, cols, rows, time_from }
    }
}

impl TileGrid for SafeGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let mut b = TileBounds::full();
        if !self.finite {
            return TileResult::Bounds(b);
        }
        let ((c, tx), r) = (&self.cols[i], &self.rows[j]);
        let (Some(c), Some(r), Some(t)) = (c, r, *tx) else {
            return TileResult::Empty;
        };
        let (Some(u), Some(v)) = (c.lens, r.lens) else {
            return TileResult::Empty;
        };
        let Some(t) = (self.time_from)(r, t) else {
            return TileResult::Empty;
        };
        if t[0].is_nan() || t[1].is_nan() || t[0] > t[1] {
            return TileResult::Empty;
        }
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
        constraints_of(&c.cut, Lens::U, &mut cons);
        constraints_of(&r.cut, Lens::V, &mut cons);
        (b.u, b.v, b.t, b.constraints) = (u, v, t, cons);
        TileResult::Bounds(b)
    }
}

// ---------------------------------------------------------------------------------------
// wu2013 (published)
// ---------------------------------------------------------------------------------------

/// One column (x axis) or one row (y axis) of the grid for `wu2013`: stage 1's lens
/// range and stage 2's lines, as `tile` computes them from that axis alone.
struct AxisPart {
    lens: LensRange,
    lines: Option<Lines>,
}

impl AxisPart {
    fn new(prep: &Prep, axis: &Axis, full: [f32; 2], s0: f32, s1: f32) -> Self {
        let mut lens = Some(full);
        if prep.lens_ok {
            if let Some([lo, hi]) = axis.lens_range(s0, s1) {
                let out = [lo.max(-1.0), hi.min(1.0)];
                lens = (out[0] <= out[1]).then_some(out);
            }
        }
        let lines = lens.and_then(|_| axis.lines(s0, s1, prep.guarded));
        AxisPart { lens, lines }
    }
}

/// [`Prep::grid`]: per column and per row the lens range and the lines (each reads one
/// axis); per tile the lines' time ranges over the tile's lens ranges and the
/// constraints, in `tile`'s order (x first).
pub(super) struct PublishedGrid {
    cols: Vec<AxisPart>,
    rows: Vec<AxisPart>,
}

impl PublishedGrid {
    pub(super) fn new(prep: &Prep, grid: Grid) -> Self {
        let full = TileBounds::full();
        let cols = (0..grid.columns()).map(|i| grid.column(i)).map(|[a, b]| AxisPart::new(prep, &prep.x, full.u, a, b));
        let rows = (0..grid.rows()).map(|j| grid.row(j)).map(|[a, b]| AxisPart::new(prep, &prep.y, full.v, a, b));
        PublishedGrid { cols: cols.collect(), rows: rows.collect() }
    }
}

impl TileGrid for PublishedGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let (c, r) = (&self.cols[i], &self.rows[j]);
        let (Some(u), Some(v)) = (c.lens, r.lens) else {
            return TileResult::Empty;
        };
        let mut t = [0.0f32, 1.0];
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
        if let Some(ln) = c.lines {
            apply_lines(ln, Lens::U, u, &mut t, &mut cons);
        }
        if let Some(ln) = r.lines {
            apply_lines(ln, Lens::V, v, &mut t, &mut cons);
        }
        if t[0].is_nan() || t[1].is_nan() || t[0] > t[1] {
            return TileResult::Empty;
        }
        let mut b = TileBounds::full();
        (b.u, b.v, b.t, b.constraints) = (u, v, t, cons);
        TileResult::Bounds(b)
    }
}
