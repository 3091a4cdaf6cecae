//! `wu2013` and `wu2013-safe` over a grid of tiles ([`Prepared::grid`]): both tests
//! split by axis. Stage 1's lens range on the x axis reads only the tile's columns
//! `[x0, x1]`, stage 2's crossings and lines on the x axis only those columns and that
//! lens range (the y axis likewise with the rows and v); what is left per tile is to meet
//! the two axes' time ranges in the order [`Prepared::tile`] does and to collect the
//! constraints. Every part is computed by the same functions as in `tile`, so each answer
//! is `tile`'s, bit for bit (`grid_tests.rs`).

use super::safe::{
    hull_within, safe_line_cut, sign_hull, sign_parts, Columns, Iv, LineCut, LineEnds, SafeAxis, SafePrep,
};
use super::*;

/// The lens range of stage 1 on one axis as `tile` leaves it: `Some(range)` (the full
/// lens when stage 1 gives no bound), or `None` when stage 1 culls the tile.
type LensRange = Option<[f32; 2]>;

// ---------------------------------------------------------------------------------------
// wu2013-safe
// ---------------------------------------------------------------------------------------

/// What one column boundary (or row boundary) `s` gives every column next to it.
struct SafeBoundary {
    /// Per vertex, [`SafeVertex::at_column`](super::safe::SafeVertex::at_column) at `s`.
    at: [(Iv, Iv); 3],
    /// Per vertex, [`SafeAxis::lens_at`] at `s` (only when stage 1 applies on the axis).
    lens: Option<[[Iv; 2]; 3]>,
    /// Per vertex, [`SafeVertex::line_ends`](super::safe::SafeVertex::line_ends) at `s`.
    ends: [Option<LineEnds>; 3],
}

impl SafeBoundary {
    fn new(axis: &SafeAxis, stage1: bool, s: f32) -> Self {
        let at = axis.v.map(|a| a.at_column(s));
        let mut ends = [None; 3];
        for ((a, &col), e) in axis.v.iter().zip(&at).zip(ends.iter_mut()) {
            *e = a.line_ends(col);
        }
        SafeBoundary { at, lens: stage1.then(|| axis.lens_at(s)), ends }
    }
}

/// One column (x axis) or one row (y axis) of the grid: everything of `tile` that reads
/// that axis only.
struct SafeAxisPart {
    /// Stage 1's lens range (`None`: the tile is culled).
    lens: LensRange,
    /// Stage 2's crossing times as [`sign_parts`] (`None`: no time bound from the axis).
    time: Option<[[f32; 2]; 4]>,
    /// The published lines over the lens range (an empty cut when there are none).
    cut: LineCut,
}

impl SafeAxisPart {
    /// The part between boundaries `b0` and `b1`; `full` is the lens range when stage 1
    /// gives no bound.
    fn new(axis: &SafeAxis, lens: Lens, full: [f32; 2], b0: &SafeBoundary, b1: &SafeBoundary) -> Self {
        let culled = SafeAxisPart { lens: None, time: None, cut: LineCut::default() };
        let mut l = full;
        if let (Some(inc), Some(at0), Some(at1)) = (axis.lens_directions(), &b0.lens, &b1.lens) {
            if let Some(cr) = SafeAxis::lens_crossings_from(inc, [at0, at1]) {
                match sign_hull(&cr, [-1.0, 1.0]) {
                    None => return culled,
                    Some(r) => l = r,
                }
            }
        }
        let cols: Columns = std::array::from_fn(|k| [b0.at[k], b1.at[k]]);
        let time = axis.time_crossings(&cols, l).map(|cr| sign_parts(&cr));
        let ends = std::array::from_fn(|k| [b0.ends[k], b1.ends[k]]);
        let cut = SafeAxis::lines_from(&ends).map_or_else(LineCut::default, |ln| safe_line_cut(ln, lens, l));
        SafeAxisPart { lens: Some(l), time, cut }
    }

    /// Stage 2 of this axis on the time range `t` left by the axes before it: the
    /// sign-aware hull within `t`, then the lines (`None`: the tile is culled).
    fn time_from(&self, mut t: [f32; 2]) -> Option<[f32; 2]> {
        if let Some(parts) = &self.time {
            t = hull_within(parts, t)?;
        }
        self.cut.bound(&mut t);
        Some(t)
    }
}

/// The parts of every column (or row) between consecutive `bounds`, each boundary's
/// values computed once.
fn safe_parts(axis: &SafeAxis, lens: Lens, full: [f32; 2], bounds: &[f32]) -> Vec<SafeAxisPart> {
    let stage1 = axis.lens_directions().is_some();
    let at: Vec<SafeBoundary> = bounds.iter().map(|&s| SafeBoundary::new(axis, stage1, s)).collect();
    at.windows(2).map(|w| SafeAxisPart::new(axis, lens, full, &w[0], &w[1])).collect()
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
    cols: Vec<(SafeAxisPart, Option<[f32; 2]>)>,
    rows: Vec<SafeAxisPart>,
}

impl SafeGrid {
    pub(super) fn new(prep: &SafePrep, grid: Grid) -> Self {
        if !prep.finite {
            return SafeGrid { finite: false, cols: Vec::new(), rows: Vec::new() };
        }
        let full = TileBounds::full();
        let cols = safe_parts(&prep.x, Lens::U, full.u, grid.xs)
            .into_iter()
            .map(|p| {
                let t = p.lens.and_then(|_| p.time_from([0.0, 1.0]));
                (p, t)
            })
            .collect();
        let rows = safe_parts(&prep.y, Lens::V, full.v, grid.ys);
        SafeGrid { finite: true, cols, rows }
    }
}

impl TileGrid for SafeGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let mut b = TileBounds::full();
        if !self.finite {
            return TileResult::Bounds(b);
        }
        let ((c, tx), r) = (&self.cols[i], &self.rows[j]);
        let (Some(u), Some(v), Some(t)) = (c.lens, r.lens, *tx) else {
            return TileResult::Empty;
        };
        let Some(t) = r.time_from(t) else {
            return TileResult::Empty;
        };
        if t[0].is_nan() || t[1].is_nan() || t[0] > t[1] {
            return TileResult::Empty;
        }
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::with_capacity(c.cut.count() + r.cut.count());
        c.cut.push(&mut cons);
        r.cut.push(&mut cons);
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
