//! The chart of one family (`<family>.svg`): three stacked panels sharing the x axis,
//! the swept parameter on a log axis (base 2 for `perspective`; symmetric-log for
//! `w-zero`, which passes through 0: x = sign(w) (log10|w| + 7), so 1e-6 -> 1, 0 -> 0,
//! -1 -> -7); top: violation rate, middle: NaN/inf rate, bottom: STE (%; steps where a
//! method let nothing through are left out of its line). One colour per method, one line per method and panel, a dot
//! per step; the legend is a column of its own at the right.
//!
//! Drawn with `plotters` and only its SVG backend, as `tightness/chart.rs` does: labels
//! become SVG `<text>` elements (the viewer picks the font), no system font is needed.

use super::FamilyReport;
use plotters::prelude::*;

pub use crate::tools::tightness::chart::colour;

/// How the swept parameter maps to the x axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Log10,
    /// For the power-of-two steps of `perspective`.
    Log2,
    /// For `w-zero`, which passes through 0: `sign(p) (log10|p| + 7)`.
    SymLog,
}

impl Axis {
    pub fn of(family: &str) -> Axis {
        match family {
            "w-zero" => Axis::SymLog,
            "perspective" => Axis::Log2,
            _ => Axis::Log10,
        }
    }
    /// The x coordinate of a parameter value.
    pub fn x(self, p: f64) -> f64 {
        match self {
            Axis::Log10 => p.log10(),
            Axis::Log2 => p.log2(),
            Axis::SymLog if p == 0.0 => 0.0,
            Axis::SymLog => p.signum() * (p.abs().log10() + 7.0).max(0.0),
        }
    }
    /// The parameter value at an x coordinate, as a short label.
    fn label(self, x: f64) -> String {
        let v = match self {
            Axis::Log10 => 10f64.powf(x),
            Axis::Log2 => 2f64.powf(x),
            Axis::SymLog if x == 0.0 => 0.0,
            Axis::SymLog => x.signum() * 10f64.powf(x.abs() - 7.0),
        };
        super::fmt_param(format!("{v:.3e}").parse::<f64>().unwrap_or(v))
    }
    fn describe(self) -> &'static str {
        match self {
            Axis::Log10 | Axis::Log2 => "log",
            Axis::SymLog => "symmetric log: sign(w) (log10|w| + 7)",
        }
    }
}

/// The SVG text of the family's chart; `methods` fixes the colour order.
pub fn svg(r: &FamilyReport, methods: &[String]) -> anyhow::Result<String> {
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("chart: {e}");
    let axis = Axis::of(&r.family);
    let xs: Vec<f64> = r.steps.iter().map(|s| axis.x(s.parameter)).filter(|x| x.is_finite()).collect();
    let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let (lo, hi) = if lo.is_finite() && hi > lo {
        (lo, hi)
    } else if lo.is_finite() {
        (lo - 1.0, lo + 1.0)
    } else {
        (0.0, 1.0)
    };
    let pad = 0.04 * (hi - lo);
    let (xmin, xmax) = (lo - pad, hi + pad);
    // As many labels as whole units in the range, so that plotters picks a step of one
    // unit (one decade, or one octave for base 2) rather than half units.
    let labels = ((xmax.ceil() - xmin.floor()) as usize + 1).clamp(2, 40);
    let legend_w = 230u32;
    let (w, h) = (820 + legend_w, 900u32);
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let title = format!("stability: {} ({} cases per step, seed {})", r.family, r.cases, r.seed);
        let root = root.titled(&title, ("sans-serif", 18)).map_err(|e| err(&e))?;
        let (body, legend) = root.split_horizontally(w - legend_w);
        let text = ("sans-serif", 12).into_font();
        let mut y = 40;
        for (i, m) in methods.iter().enumerate() {
            let c = colour(i);
            legend
                .draw(&PathElement::new(vec![(8, y), (28, y)], c.stroke_width(2)))
                .and_then(|_| legend.draw(&Circle::new((18, y), 3, c.filled())))
                .and_then(|_| legend.draw(&Text::new(m.clone(), (36, y - 7), text.clone())))
                .map_err(|e| err(&e))?;
            y += 20;
        }
        let xdesc = format!("{} ({})", r.parameter, axis.describe());
        let ste_max = r.rows.iter().filter_map(|x| x.ste).fold(0.0f64, f64::max) * 100.0;
        let ste_top = if ste_max > 0.0 { (ste_max * 1.1).min(105.0) } else { 1.0 };
        let panels: [(&str, f64); 3] = [("violation rate", 1.05), ("NaN/inf rate", 1.05), ("STE (%)", ste_top)];
        let areas = body.split_evenly((3, 1));
        for (pi, (area, (name, ytop))) in areas.iter().zip(panels).enumerate() {
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(if pi == 2 { 44 } else { 24 })
                .y_label_area_size(56)
                .build_cartesian_2d(xmin..xmax, 0.0..ytop)
                .map_err(|e| err(&e))?;
            let mut mesh = chart.configure_mesh();
            let fmt = |x: &f64| axis.label(*x);
            mesh.y_desc(name)
                .x_label_formatter(&fmt)
                .x_labels(labels)
                .y_labels(5)
                .light_line_style(RGBColor(242, 242, 242));
            if pi == 2 {
                mesh.x_desc(xdesc.as_str());
            }
            mesh.draw().map_err(|e| err(&e))?;
            for (mi, m) in methods.iter().enumerate() {
                let c = colour(mi);
                let pts: Vec<(f64, f64)> = r
                    .rows
                    .iter()
                    .filter(|x| &x.method == m)
                    .filter_map(|x| {
                        let v = match pi {
                            0 => Some(x.violation_rate()),
                            1 => Some(x.nonfinite_rate()),
                            _ => x.ste.map(|s| 100.0 * s),
                        }?;
                        let xx = axis.x(x.parameter);
                        xx.is_finite().then_some((xx, v))
                    })
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                chart.draw_series(LineSeries::new(pts.clone(), c.stroke_width(2))).map_err(|e| err(&e))?;
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled()))).map_err(|e| err(&e))?;
            }
        }
        root.present().map_err(|e| err(&e))?;
    }
    Ok(buf)
}
