//! An SVG picture of one method on one case: what the triangle really covers, what the
//! method keeps, and the witness sample that shows where the two disagree.
//!
//! A picture is one or two 2D slices of the sample space `(x, y, u, v, t)` through the
//! witness, chosen by the triangle's [`Dims`] so that it shows no more dimensions than
//! the case has:
//!
//! | dims | panels |
//! |---|---|
//! | both | (u, t) at the witness's (x, y, v); (v, t) at the witness's (x, y, u) |
//! | defocus | (u, v) at the witness's (x, y) |
//! | motion | (x, t) over the tile's x range at the witness's (y, u, v) |
//! | static | (x, y) over the tile at the witness's (u, v, t) |
//!
//! Each panel is a grid of [`GRID`] x [`GRID`] cells, each judged at its centre, a
//! sample in f32 as hardware would hold it (the fixed coordinates are the witness's,
//! rounded to f32; the witness marker sits at its exact position):
//! - the exact class of the cell centre by [`oracles::classify`]: interior cells light
//!   blue, boundary cells dark blue;
//! - cells some per-sample constraint culls (`g_m(s) < 0` in f32; a NaN value culls
//!   nothing, as in [`TileBounds::admits`]): a translucent red overlay;
//! - interior cells whose exact hit depth lies outside `z^`: a translucent orange overlay;
//! - the method's tile answer: the box of its intervals over the panel's two
//!   coordinates (green outline; the tile itself along x and y), or, when it culls the
//!   tile, the panel hatched and outlined in red with the label "tile culled";
//! - the witness: a black cross in a circle.
//!
//! The title names the method and the caption; two text lines give the tile, the
//! method's answer, the witness's exact class and every bound of the answer that culls it.
//!
//! Drawing uses the `plotters` SVG backend without any font feature: plotters then writes
//! each label as a plain SVG `<text>` element (family "sans-serif") and only estimates its
//! size for the layout, so no font is read and the viewer renders the text.

use crate::bounds::{Method, TileBounds, TileResult};
use crate::model::{Case, Dims, Sample, Tile};
use anyhow::{anyhow, bail, Context, Result};
use oracles::{Coverage, DepthCheck};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Cells along each side of a panel.
pub const GRID: usize = 120;

const INTERIOR: RGBColor = RGBColor(166, 206, 240);
const BOUNDARY: RGBColor = RGBColor(33, 84, 160);
const CULLED: RGBColor = RGBColor(220, 20, 20);
const DEPTH: RGBColor = RGBColor(245, 140, 0);
const BOX: RGBColor = RGBColor(0, 130, 40);
const GREY: RGBColor = RGBColor(90, 90, 90);
const CULLED_ALPHA: f64 = 0.35;
const DEPTH_ALPHA: f64 = 0.45;

const PANEL_W: u32 = 540;
const PANEL_H: u32 = 520;
const TITLE_H: u32 = 78;
const LEGEND_H: u32 = 58;
const MIN_W: u32 = 800;

/// One coordinate of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Axis {
    X = 0,
    Y = 1,
    U = 2,
    V = 3,
    T = 4,
}

impl Axis {
    fn name(self) -> &'static str {
        ["x", "y", "u", "v", "t"][self as usize]
    }
}

/// A 2D slice of the sample space: `axes[0]` (horizontal) and `axes[1]` (vertical) run
/// over `ranges`, the other three coordinates are fixed at `at`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slice {
    pub axes: [Axis; 2],
    pub ranges: [[f64; 2]; 2],
    pub at: [f32; 5],
}

impl Slice {
    /// The f32 sample at the centre of cell (i, j) of an `n` x `n` grid (i along the
    /// horizontal axis, j along the vertical one).
    pub fn cell_centre(&self, n: usize, i: usize, j: usize) -> Sample {
        let mut s = self.at;
        for (k, idx) in [(0, i), (1, j)] {
            s[self.axes[k] as usize] = self.edge(k, n, idx as f64 + 0.5) as f32;
        }
        Sample::new(s[0], s[1], s[2], s[3], s[4])
    }

    /// The coordinate along axis `k` at grid position `p` (cell edges at integers).
    fn edge(&self, k: usize, n: usize, p: f64) -> f64 {
        let [a, b] = self.ranges[k];
        a + (b - a) * p / n as f64
    }

    /// The fixed coordinates, as "x = 3.5, y = 2".
    fn fixed_text(&self) -> String {
        [Axis::X, Axis::Y, Axis::U, Axis::V, Axis::T]
            .into_iter()
            .filter(|a| !self.axes.contains(a))
            .map(|a| format!("{} = {}", a.name(), num(self.at[a as usize] as f64)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The panels for a triangle with these dims, through `witness`.
pub(crate) fn slices(dims: Dims, tile: &Tile, witness: [f64; 5]) -> Vec<Slice> {
    let at = witness.map(|c| c as f32);
    let lens = [-1.0, 1.0];
    let time = [0.0, 1.0];
    let tx = [tile.x0 as f64, tile.x1 as f64];
    let ty = [tile.y0 as f64, tile.y1 as f64];
    let s = |axes, ranges| Slice { axes, ranges, at };
    match dims {
        Dims::Both => vec![s([Axis::U, Axis::T], [lens, time]), s([Axis::V, Axis::T], [lens, time])],
        Dims::Defocus => vec![s([Axis::U, Axis::V], [lens, lens])],
        Dims::Motion => vec![s([Axis::X, Axis::T], [tx, time])],
        Dims::Static => vec![s([Axis::X, Axis::Y], [tx, ty])],
    }
}

/// The classified cells of one panel, row by row from the bottom (cell (i, j) at
/// index `j * n + i`).
#[derive(Clone, Debug)]
pub(crate) struct Grid {
    pub n: usize,
    /// The exact class of each cell centre.
    pub cover: Vec<Coverage>,
    /// Some per-sample constraint is < 0 at the cell centre.
    pub culled: Vec<bool>,
    /// The cell centre is interior and its exact hit depth lies outside `z^`.
    pub depth_out: Vec<bool>,
}

#[cfg(test)]
impl Grid {
    /// Cells of this class.
    pub fn count(&self, c: Coverage) -> usize {
        self.cover.iter().filter(|&&x| x == c).count()
    }
    /// Cells some constraint culls.
    pub fn culled_count(&self) -> usize {
        self.culled.iter().filter(|&&x| x).count()
    }
}

/// Classifies the `n` x `n` cells of a slice: exact coverage of each cell centre, and,
/// when the method answered with bounds, its per-sample constraints and depth interval
/// there.
pub(crate) fn grid(tri: &oracles::Tri, bounds: Option<&TileBounds>, slice: &Slice, n: usize) -> Grid {
    let mut g = Grid { n, cover: Vec::with_capacity(n * n), culled: Vec::with_capacity(n * n), depth_out: vec![] };
    let z = bounds.and_then(|b| b.z);
    for j in 0..n {
        for i in 0..n {
            let s = slice.cell_centre(n, i, j);
            let c = oracles::classify(tri, s.to_oracle());
            g.cover.push(c);
            g.culled.push(bounds.is_some_and(|b| b.constraints.iter().any(|m| m.eval(&s) < 0.0)));
            g.depth_out.push(match z {
                Some([z0, z1]) if c == Coverage::Interior => {
                    depth_check(tri, s.to_oracle(), [z0, z1]).is_some_and(|d| d != DepthCheck::Inside)
                }
                _ => false,
            });
        }
    }
    g
}

/// Where the exact hit depth of `s` lies against `z^` (None: `z^` has a NaN end, which
/// admits no depth at all, or `s` is not interior).
fn depth_check(tri: &oracles::Tri, s: [f64; 5], z: [f32; 2]) -> Option<DepthCheck> {
    if z.iter().any(|v| v.is_nan()) {
        return None;
    }
    match oracles::classify_depth(tri, s, z[0] as f64, z[1] as f64) {
        DepthCheck::NotInterior => None,
        d => Some(d),
    }
}

/// A number as short as it stays exact: an f64 that is an f32 prints as that f32.
fn num(v: f64) -> String {
    if (v as f32) as f64 == v || !v.is_finite() {
        format!("{}", v as f32)
    } else {
        format!("{v}")
    }
}

fn interval_text(r: [f32; 2]) -> String {
    format!("[{}, {}]", r[0], r[1])
}

/// The method's answer, in one line.
fn answer_text(res: &TileResult, disabled: Option<&str>) -> String {
    let mut s = match res {
        TileResult::Empty => "answer: tile culled (empty)".to_string(),
        TileResult::Bounds(b) => {
            let mut s =
                format!("answer: u^ {}, v^ {}, t^ {}", interval_text(b.u), interval_text(b.v), interval_text(b.t));
            if let Some(z) = b.z {
                s += &format!(", z^ {}", interval_text(z));
            }
            if !b.constraints.is_empty() {
                s += &format!(", {} per-sample constraint(s)", b.constraints.len());
            }
            s
        }
    };
    if let Some(d) = disabled {
        s += &format!(" (disabled: {d})");
    }
    s
}

/// The witness's exact class and every bound of the answer that culls it.
fn witness_text(tri: &oracles::Tri, res: &TileResult, witness: [f64; 5]) -> String {
    let class = match oracles::classify(tri, witness) {
        Coverage::Interior => "interior",
        Coverage::Boundary => "boundary",
        Coverage::Outside => "outside",
    };
    let coords: Vec<String> = witness.iter().map(|&c| num(c)).collect();
    let mut why = Vec::new();
    match res {
        TileResult::Empty => why.push("tile culled".to_string()),
        TileResult::Bounds(b) => {
            for (name, r, c) in [("u^", b.u, witness[2]), ("v^", b.v, witness[3]), ("t^", b.t, witness[4])] {
                if !(r[0] as f64 <= c && c <= r[1] as f64) {
                    why.push(format!("{name} {}", interval_text(r)));
                }
            }
            if let Some(z) = b.z {
                match depth_check(tri, witness, z) {
                    Some(DepthCheck::Below) => why.push("hit depth below z^".into()),
                    Some(DepthCheck::Above) => why.push("hit depth above z^".into()),
                    _ => {}
                }
            }
            let s = witness.map(|c| c as f32);
            let s = Sample::new(s[0], s[1], s[2], s[3], s[4]);
            for m in &b.constraints {
                let g = m.eval(&s);
                if g < 0.0 {
                    why.push(format!("{} = {g:e}", m.name()));
                }
            }
        }
    }
    let why = if why.is_empty() { "kept by the method".to_string() } else { format!("culled by: {}", why.join("; ")) };
    format!("witness (x, y, u, v, t) = ({}): exactly {class}; {why}", coords.join(", "))
}

/// Cuts a text line to about what fits in `width` pixels at `size` px.
fn fit(s: &str, width: u32, size: f64) -> String {
    let max = (width as f64 / (0.5 * size)).max(8.0) as usize;
    if s.chars().count() <= max {
        s.to_string()
    } else {
        s.chars().take(max - 1).chain(std::iter::once('…')).collect()
    }
}

/// An SVG picture of one method on one case: slices of the sample space through `witness`.
///
/// `witness` is a sample `(x, y, u, v, t)` (usually a violation the gate found; it need
/// not be one) and `caption` a line of text for the title. Errors on an invalid case,
/// tile or witness, and on a panic of the method, rather than panicking.
pub fn svg(case: &Case, tile: &Tile, method: &'static dyn Method, witness: [f64; 5], caption: &str) -> Result<String> {
    case.validate().context("explain: invalid case")?;
    tile.validate().context("explain: invalid tile")?;
    if let Some(c) = witness.iter().find(|&&c| !(c as f32).is_finite()) {
        bail!("explain: witness {witness:?} has a coordinate {c} that is not a finite f32");
    }
    let run = std::panic::AssertUnwindSafe(|| render(case, tile, method, witness, caption));
    std::panic::catch_unwind(run).unwrap_or_else(|p| {
        let msg = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        Err(anyhow!("explain: panic while drawing {} on this case: {msg}", method.info().id))
    })
}

fn render(case: &Case, tile: &Tile, method: &'static dyn Method, witness: [f64; 5], caption: &str) -> Result<String> {
    let info = method.info();
    let prepared = method.setup(&case.triangle);
    let res = prepared.tile(tile);
    let bounds = match &res {
        TileResult::Empty => None,
        TileResult::Bounds(b) => Some(b),
    };
    let tri = case.triangle.to_oracle();
    let dims = case.triangle.dims();
    let panels: Vec<(Slice, Grid)> = slices(dims, tile, witness)
        .into_iter()
        .map(|s| {
            let g = grid(&tri, bounds, &s, GRID);
            (s, g)
        })
        .collect();

    let width = (PANEL_W * panels.len() as u32).max(MIN_W);
    let height = TITLE_H + PANEL_H + LEGEND_H;
    let title = format!("{}{}: {}", info.id, if info.reconstruction { " (reconstruction)" } else { "" }, caption);
    let line2 = format!(
        "tile [{}, {}] x [{}, {}], {}; {}",
        tile.x0,
        tile.x1,
        tile.y0,
        tile.y1,
        dims.name(),
        answer_text(&res, prepared.disabled())
    );
    let line3 = witness_text(&tri, &res, witness);

    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (width, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, rest) = root.split_vertically(TITLE_H);
        let (middle, bottom) = rest.split_vertically(PANEL_H);
        let left = |size: f64| TextStyle::from(("sans-serif", size).into_font()).pos(Pos::new(HPos::Left, VPos::Top));
        top.draw(&Text::new(fit(&title, width - 20, 18.0), (10, 8), left(20.0).color(&BLACK)))?;
        top.draw(&Text::new(fit(&line2, width - 20, 13.0), (10, 36), left(14.0).color(&GREY)))?;
        top.draw(&Text::new(fit(&line3, width - 20, 13.0), (10, 56), left(14.0).color(&BLACK)))?;
        let areas = middle.split_evenly((1, panels.len()));
        for ((slice, g), area) in panels.iter().zip(&areas) {
            draw_panel(area, slice, g, &res, witness)?;
        }
        draw_legend(&bottom, matches!(res, TileResult::Empty))?;
        root.present()?;
    }
    Ok(out)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A rectangle's outline as a closed path (the SVG backend writes rectangles without
/// their stroke width; paths keep it).
fn outline<C: Copy>(r: [(C, C); 2], style: ShapeStyle) -> PathElement<(C, C)> {
    let [(x0, y0), (x1, y1)] = r;
    PathElement::new(vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)], style)
}

fn draw_panel(area: &Area, slice: &Slice, g: &Grid, res: &TileResult, witness: [f64; 5]) -> Result<()> {
    let [h, v] = slice.axes;
    let [hr, vr] = slice.ranges;
    let caption = format!("({}, {}) at {}", h.name(), v.name(), slice.fixed_text());
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(58)
        .build_cartesian_2d(hr[0]..hr[1], vr[0]..vr[1])?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(h.name())
        .y_desc(v.name())
        .axis_desc_style(("sans-serif", 16))
        .label_style(("sans-serif", 12))
        .draw()?;

    let n = g.n;
    let cell = |i0: usize, i1: usize, j: usize| {
        [
            (slice.edge(0, n, i0 as f64), slice.edge(1, n, j as f64)),
            (slice.edge(0, n, i1 as f64), slice.edge(1, n, j as f64 + 1.0)),
        ]
    };
    // Runs of equal cells along each row, one rectangle per run.
    let runs = |want: &dyn Fn(usize) -> bool| {
        let mut rects = Vec::new();
        for j in 0..n {
            let mut i = 0;
            while i < n {
                if want(j * n + i) {
                    let start = i;
                    while i < n && want(j * n + i) {
                        i += 1;
                    }
                    rects.push(cell(start, i, j));
                } else {
                    i += 1;
                }
            }
        }
        rects
    };
    let layers: [(&dyn Fn(usize) -> bool, ShapeStyle); 4] = [
        (&|k| g.cover[k] == Coverage::Interior, INTERIOR.filled()),
        (&|k| g.cover[k] == Coverage::Boundary, BOUNDARY.filled()),
        (&|k| g.culled[k], CULLED.mix(CULLED_ALPHA).filled()),
        (&|k| g.depth_out[k], DEPTH.mix(DEPTH_ALPHA).filled()),
    ];
    for (want, style) in layers {
        chart.draw_series(runs(want).into_iter().map(|r| Rectangle::new(r, style)))?;
    }

    match res {
        TileResult::Bounds(b) => {
            let side = |k: usize| -> Option<[f64; 2]> {
                let r = slice.ranges[k];
                let iv = match slice.axes[k] {
                    Axis::U => b.u,
                    Axis::V => b.v,
                    Axis::T => b.t,
                    Axis::X | Axis::Y => return Some(r),
                };
                // As in `admits`: a NaN end admits nothing.
                let (lo, hi) = (iv[0] as f64, iv[1] as f64);
                let (lo, hi) = (lo.max(r[0]), hi.min(r[1]));
                (lo <= hi).then_some([lo, hi])
            };
            if let (Some(a), Some(c)) = (side(0), side(1)) {
                chart.draw_series(std::iter::once(outline([(a[0], c[0]), (a[1], c[1])], BOX.stroke_width(2))))?;
            } else {
                let at = ((hr[0] + hr[1]) / 2.0, vr[1] - 0.06 * (vr[1] - vr[0]));
                let style = TextStyle::from(("sans-serif", 15).into_font())
                    .color(&BOX)
                    .pos(Pos::new(HPos::Center, VPos::Center));
                chart.draw_series(std::iter::once(Text::new("method box misses this slice", at, style)))?;
            }
        }
        TileResult::Empty => {
            // Hatch lines y = x - c in the unit square, mapped onto the panel.
            let map = |p: (f64, f64)| (hr[0] + p.0 * (hr[1] - hr[0]), vr[0] + p.1 * (vr[1] - vr[0]));
            let hatch = (-9..10).map(|k| {
                let c = k as f64 / 10.0;
                let (x0, x1) = (c.max(0.0), (1.0 + c).min(1.0));
                PathElement::new(vec![map((x0, x0 - c)), map((x1, x1 - c))], CULLED.mix(0.6).stroke_width(1))
            });
            chart.draw_series(hatch)?;
            chart.draw_series(std::iter::once(outline([map((0.0, 0.0)), map((1.0, 1.0))], CULLED.stroke_width(3))))?;
            let style = TextStyle::from(("sans-serif", 26).into_font().style(FontStyle::Bold))
                .color(&CULLED)
                .pos(Pos::new(HPos::Center, VPos::Center));
            let at = map((0.5, 0.5));
            chart.draw_series(std::iter::once(Rectangle::new(
                [map((0.27, 0.44)), map((0.73, 0.56))],
                WHITE.mix(0.85).filled(),
            )))?;
            chart.draw_series(std::iter::once(Text::new("tile culled", at, style)))?;
        }
    }

    let (wh, wv) = (witness[h as usize], witness[v as usize]);
    let inside = |x: f64, r: [f64; 2]| r[0] <= x && x <= r[1];
    if inside(wh, hr) && inside(wv, vr) {
        chart.draw_series([
            Cross::new((wh, wv), 6, BLACK.stroke_width(2)).into_dyn(),
            Circle::new((wh, wv), 10, BLACK.stroke_width(2)).into_dyn(),
        ])?;
    } else {
        let at = ((hr[0] + hr[1]) / 2.0, vr[0] + 0.05 * (vr[1] - vr[0]));
        let style =
            TextStyle::from(("sans-serif", 14).into_font()).color(&BLACK).pos(Pos::new(HPos::Center, VPos::Center));
        chart.draw_series(std::iter::once(Text::new("witness outside this panel", at, style)))?;
    }
    Ok(())
}

/// One entry of the legend.
#[derive(Clone, Copy)]
enum Key {
    Fill(&'static [(RGBColor, f64)]),
    Outline(RGBColor),
    Witness,
    TileCulled,
}

fn draw_legend(area: &Area, culled: bool) -> Result<()> {
    let text = TextStyle::from(("sans-serif", 14).into_font()).color(&BLACK).pos(Pos::new(HPos::Left, VPos::Center));
    let (w, _) = area.dim_in_pixel();
    let mut items = vec![
        ("covered (exact, interior)", Key::Fill(&[(INTERIOR, 1.0)])),
        ("boundary", Key::Fill(&[(BOUNDARY, 1.0)])),
        ("culled by a constraint g < 0", Key::Fill(&[(CULLED, CULLED_ALPHA)])),
        ("covered and culled", Key::Fill(&[(INTERIOR, 1.0), (CULLED, CULLED_ALPHA)])),
        ("hit depth outside z^", Key::Fill(&[(INTERIOR, 1.0), (DEPTH, DEPTH_ALPHA)])),
        ("method's interval box", Key::Outline(BOX)),
        ("witness", Key::Witness),
    ];
    if culled {
        items.push(("tile culled", Key::TileCulled));
    }
    let (mut x, mut y) = (14i32, 16i32);
    for (label, key) in items {
        let label_w = (label.chars().count() as f64 * 6.2) as i32;
        if x + 28 + label_w > w as i32 - 10 {
            x = 14;
            y += 24;
        }
        let (a, b) = ((x, y - 7), (x + 20, y + 7));
        match key {
            Key::Fill(layers) => {
                for &(c, alpha) in layers {
                    area.draw(&Rectangle::new([a, b], c.mix(alpha).filled()))?;
                }
            }
            Key::Outline(c) => area.draw(&outline([a, b], c.stroke_width(2)))?,
            Key::Witness => {
                area.draw(&Cross::new((x + 10, y), 5, BLACK.stroke_width(2)))?;
                area.draw(&Circle::new((x + 10, y), 8, BLACK.stroke_width(2)))?;
            }
            Key::TileCulled => {
                area.draw(&outline([a, b], CULLED.stroke_width(2)))?;
                area.draw(&PathElement::new(vec![(a.0, b.1), (b.0, a.1)], CULLED.stroke_width(1)))?;
            }
        }
        area.draw(&Text::new(label.to_string(), (x + 28, y), text.clone()))?;
        x += 28 + label_w + 22;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
