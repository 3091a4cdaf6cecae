//! The STE-against-cost chart (`ste_vs_cost.svg`): one panel per setting, each with its
//! own log x axis (so no panel's range squashes another's); x = estimated cost relative
//! to bbox on the same setting ([`super::cost`]), the median over the timing rounds with
//! the rounds' range as a horizontal error bar; y = STE (%) at the cost's tile size (exact
//! counts: no error bar); one colour per method; published methods as filled circles,
//! reconstructions (`MethodInfo::reconstruction`) as hollow triangles; a method that
//! culled covered samples gets a red cross over its marker and is left out of the Pareto
//! front; the front is joined by a black line and ringed. The front marks only
//! differences larger than the noise: a conservative point is off it when another is
//! tighter and not surely costlier (its interval starts at or below this one's end), or
//! as tight and surely cheaper (its interval ends below this one's start). A conservative variant `<id>-safe` takes the colour of its original,
//! is drawn as a hollow square, and is joined to the original by a thin line in that
//! colour: the segment is the price of safety (its length along x the time added, its
//! drop in y the STE lost). The legend is a column of its own at the right, drawn in pixel
//! coordinates (plotters' series legend would sit over the points).
//!
//! Drawn with `plotters` and only its SVG backend: without a font feature plotters
//! measures text with its built-in estimate and the SVG backend writes the labels as
//! SVG `<text>` elements (the viewer picks the font), so no system font is needed.

use super::cost::CostRow;
use super::scene::Setting;
use super::MethodRow;
use plotters::prelude::*;

/// One method on one panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub method: String,
    pub reconstruction: bool,
    /// Covered samples the method culled.
    pub missed: u64,
    /// Relative cost (x): median over the rounds, and the rounds' range.
    pub cost: f64,
    pub cost_lo: f64,
    pub cost_hi: f64,
    /// STE in percent (y).
    pub ste: f64,
}

/// The points of each setting: STE at `tile` and the relative cost.
pub fn points(rows: &[MethodRow], costs: &[CostRow], tile: u32) -> Vec<(Setting, Vec<Point>)> {
    let mut out: Vec<(Setting, Vec<Point>)> = Vec::new();
    for t in costs.iter().filter(|c| c.tile == tile) {
        let Some(r) = rows.iter().find(|r| r.method == t.method && r.setting == t.setting && r.tile == tile) else {
            continue;
        };
        let c = t.relative;
        let ok = |x: f64| x.is_finite() && x > 0.0;
        let (Some(ste), true) = (r.ste, ok(c.median) && ok(c.lo) && ok(c.hi)) else { continue };
        let p = Point {
            method: r.method.clone(),
            reconstruction: r.reconstruction,
            missed: r.counts.missed,
            cost: c.median,
            cost_lo: c.lo,
            cost_hi: c.hi,
            ste: 100.0 * ste,
        };
        match out.iter_mut().find(|(s, _)| *s == t.setting) {
            Some((_, v)) => v.push(p),
            None => out.push((t.setting, vec![p])),
        }
    }
    out
}

/// True when `a` dominates `b` beyond the noise: tighter and not surely costlier, or as
/// tight and surely cheaper.
pub fn dominates(a: &Point, b: &Point) -> bool {
    (a.ste > b.ste && a.cost_lo <= b.cost_hi) || (a.ste >= b.ste && a.cost_hi < b.cost_lo)
}

/// Indices of the Pareto front (lower cost, higher STE, differences beyond the noise,
/// see [`dominates`]) among the points that missed no covered sample, in order of cost.
pub fn pareto(pts: &[Point]) -> Vec<usize> {
    let ok: Vec<usize> = (0..pts.len()).filter(|&i| pts[i].missed == 0).collect();
    let mut front: Vec<usize> =
        ok.iter().copied().filter(|&b| !ok.iter().any(|&a| a != b && dominates(&pts[a], &pts[b]))).collect();
    front.sort_by(|&a, &b| pts[a].cost.total_cmp(&pts[b].cost).then(pts[b].ste.total_cmp(&pts[a].ste)));
    front
}

/// Tick values for a log axis over [lo, hi]: the densest of the 1-1.5-2-3-5-7, 1-2-5
/// and 1 sequences (times powers of ten) that gives at most 6 ticks.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return vec![];
    }
    let seqs: [&[f64]; 3] = [&[1.0, 1.5, 2.0, 3.0, 5.0, 7.0], &[1.0, 2.0, 5.0], &[1.0]];
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut best = Vec::new();
    for seq in seqs {
        let mut v = Vec::new();
        for e in e0..=e1 {
            for m in seq {
                // Round to a short decimal so the labels print cleanly.
                let x = format!("{:.6e}", m * 10f64.powi(e)).parse::<f64>().unwrap_or(0.0);
                if (lo..=hi).contains(&x) {
                    v.push(x);
                }
            }
        }
        best = v;
        if best.len() <= 6 {
            break;
        }
    }
    best
}

/// The published method a variant belongs to: `bbox-safe` -> `bbox`.
pub fn base(m: &str) -> &str {
    m.strip_suffix("-safe").unwrap_or(m)
}

/// The palette shared by the charts (method i gets colour i, cycling).
pub fn colour(i: usize) -> RGBColor {
    const C: [(u8, u8, u8); 12] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
        (0, 0, 128),
        (128, 128, 0),
    ];
    let (r, g, b) = C[i % C.len()];
    RGBColor(r, g, b)
}

/// The SVG text of the chart. `methods` fixes the colour order; `title` heads it.
pub fn svg(panels: &[(Setting, Vec<Point>)], methods: &[String], title: &str) -> anyhow::Result<String> {
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("chart: {e}");
    let n = panels.len().max(1);
    let legend_w = 240u32;
    let (w, h) = (420 * n as u32 + legend_w, 500u32);
    let tri = |r: i32| vec![(0, -r), (r, r * 3 / 4), (-r, r * 3 / 4), (0, -r)];
    let recon_of =
        |m: &str| panels.iter().flat_map(|(_, v)| v.iter()).find(|p| p.method == m).map(|p| p.reconstruction);
    // One colour per published method; its -safe variant shares it.
    let mut bases: Vec<&str> = Vec::new();
    for m in methods {
        if !bases.contains(&base(m)) {
            bases.push(base(m));
        }
    }
    let colour_of = |m: &str| colour(bases.iter().position(|b| *b == base(m)).unwrap_or(0));
    let square = |r: i32| vec![(-r, -r), (r, -r), (r, r), (-r, r), (-r, -r)];
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let root = root.titled(title, ("sans-serif", 18)).map_err(|e| err(&e))?;
        let (body, legend) = root.split_horizontally(w - legend_w);
        // The legend, drawn by hand in pixel coordinates.
        let text = ("sans-serif", 12).into_font();
        let mut y = 40;
        for m in &bases {
            let c = colour_of(m);
            if recon_of(m) == Some(true) {
                legend
                    .draw(&(EmptyElement::at((16, y)) + PathElement::new(tri(5), c.stroke_width(2))))
                    .map_err(|e| err(&e))?;
            } else {
                legend.draw(&(EmptyElement::at((16, y)) + Circle::new((0, 0), 4, c.filled()))).map_err(|e| err(&e))?;
            }
            legend.draw(&Text::new(m.to_string(), (30, y - 7), text.clone())).map_err(|e| err(&e))?;
            y += 20;
        }
        y += 10;
        let notes: [(&str, u8); 5] = [
            ("filled circle: published method", 0),
            ("hollow triangle: reconstruction", 1),
            ("hollow square: its -safe variant", 4),
            ("ring + black line: Pareto front", 2),
            ("red cross: culled covered samples", 3),
        ];
        for (t, kind) in notes {
            let at = EmptyElement::at((16, y));
            match kind {
                0 => legend.draw(&(at + Circle::new((0, 0), 4, BLACK.filled()))),
                1 => legend.draw(&(at + PathElement::new(tri(5), BLACK.stroke_width(2)))),
                2 => legend.draw(&(at + Circle::new((0, 0), 8, BLACK.stroke_width(1)))),
                4 => legend.draw(&(at + PathElement::new(square(4), BLACK.stroke_width(2)))),
                _ => legend.draw(&(at + Cross::new((0, 0), 5, RED.stroke_width(2)))),
            }
            .map_err(|e| err(&e))?;
            legend.draw(&Text::new(t, (30, y - 7), text.clone())).map_err(|e| err(&e))?;
            y += 20;
        }
        legend
            .draw(&Text::new("(a method with a cross is left", (30, y - 7), text.clone()))
            .and_then(|_| legend.draw(&Text::new(" out of the Pareto front)", (30, y + 9), text.clone())))
            .map_err(|e| err(&e))?;
        let areas = body.split_evenly((1, n));
        for (area, (setting, pts)) in areas.iter().zip(panels) {
            let xmin = pts.iter().map(|p| p.cost_lo).fold(f64::INFINITY, f64::min);
            let xmax = pts.iter().map(|p| p.cost_hi).fold(f64::NEG_INFINITY, f64::max);
            let (xmin, xmax) = if xmin.is_finite() { (xmin / 1.3, xmax * 1.3) } else { (0.1, 10.0) };
            let ymax = pts.iter().map(|p| p.ste).fold(1.0, f64::max) * 1.1;
            let mut chart = ChartBuilder::on(area)
                .caption(setting.name(), ("sans-serif", 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(50)
                .build_cartesian_2d((xmin..xmax).log_scale().with_key_points(log_ticks(xmin, xmax)), 0.0..ymax)
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_desc("cost relative to bbox (log; bars: range of the rounds)")
                .y_desc("STE (%)")
                .x_label_formatter(&|x| format!("{x}"))
                .y_label_formatter(&|y| format!("{y:.0}"))
                .draw()
                .map_err(|e| err(&e))?;
            let front = pareto(pts);
            chart
                .draw_series(LineSeries::new(front.iter().map(|&i| (pts[i].cost, pts[i].ste)), BLACK.stroke_width(1)))
                .map_err(|e| err(&e))?;
            for &i in &front {
                chart
                    .draw_series(std::iter::once(Circle::new((pts[i].cost, pts[i].ste), 9, BLACK.stroke_width(1))))
                    .map_err(|e| err(&e))?;
            }
            // Each -safe variant joined to its original.
            for p in pts.iter().filter(|p| base(&p.method) != p.method) {
                if let Some(q) = pts.iter().find(|q| q.method == base(&p.method)) {
                    let line = [(q.cost, q.ste), (p.cost, p.ste)];
                    chart
                        .draw_series(LineSeries::new(line, colour_of(&p.method).stroke_width(1)))
                        .map_err(|e| err(&e))?;
                }
            }
            for p in pts {
                let c = colour_of(&p.method);
                let xy = (p.cost, p.ste);
                // The error bar: the range of the rounds, with end caps.
                chart
                    .draw_series(LineSeries::new([(p.cost_lo, p.ste), (p.cost_hi, p.ste)], c.stroke_width(1)))
                    .map_err(|e| err(&e))?;
                for x in [p.cost_lo, p.cost_hi] {
                    chart
                        .draw_series(std::iter::once(
                            EmptyElement::at((x, p.ste)) + PathElement::new(vec![(0, -4), (0, 4)], c.stroke_width(1)),
                        ))
                        .map_err(|e| err(&e))?;
                }
                if base(&p.method) != p.method {
                    chart.draw_series(std::iter::once(
                        EmptyElement::at(xy) + PathElement::new(square(5), c.stroke_width(2)),
                    ))
                } else if p.reconstruction {
                    chart.draw_series(std::iter::once(
                        EmptyElement::at(xy) + PathElement::new(tri(6), c.stroke_width(2)),
                    ))
                } else {
                    chart.draw_series(std::iter::once(EmptyElement::at(xy) + Circle::new((0, 0), 5, c.filled())))
                }
                .map_err(|e| err(&e))?;
                if p.missed > 0 {
                    chart.draw_series(std::iter::once(Cross::new(xy, 6, RED.stroke_width(2)))).map_err(|e| err(&e))?;
                }
            }
        }
        root.present().map_err(|e| err(&e))?;
    }
    Ok(buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(m: &str, cost: f64, ste: f64, missed: u64) -> Point {
        Point { method: m.into(), reconstruction: m.starts_with('r'), missed, cost, cost_lo: cost, cost_hi: cost, ste }
    }

    #[test]
    fn the_front_ignores_differences_within_the_noise() {
        let mut a = p("a", 1.0, 5.0, 0);
        let mut b = p("b", 1.1, 5.0, 0);
        // Same STE, b surely costlier: b is off the front.
        assert_eq!(pareto(&[a.clone(), b.clone()]), vec![0]);
        // Their intervals overlap: neither is surely cheaper, both stay.
        (a.cost_lo, a.cost_hi, b.cost_lo, b.cost_hi) = (0.9, 1.15, 1.0, 1.2);
        assert_eq!(pareto(&[a.clone(), b.clone()]), vec![0, 1]);
        // b tighter and not surely costlier: a is dominated.
        b.ste = 6.0;
        assert_eq!(pareto(&[a, b]), vec![1]);
    }

    #[test]
    fn pareto_keeps_only_undominated_conservative_points() {
        let pts = vec![
            p("a", 1.0, 5.0, 0),
            p("b", 2.0, 4.0, 0),
            p("c", 3.0, 9.0, 0),
            p("d", 0.5, 50.0, 3),
            p("e", 1.0, 6.0, 0),
        ];
        assert_eq!(pareto(&pts), vec![4, 2]);
    }

    #[test]
    fn log_ticks_are_few_and_inside() {
        assert_eq!(log_ticks(0.7, 1.6), vec![0.7, 1.0, 1.5]);
        assert_eq!(log_ticks(0.6, 14.0), vec![1.0, 2.0, 5.0, 10.0]);
        let t = log_ticks(0.001, 1e6);
        assert!(t.len() <= 10 && t.iter().all(|&x| (0.001..=1e6).contains(&x)), "{t:?}");
    }

    #[test]
    fn svg_has_the_labels_as_text() {
        let pts = vec![p("bbox", 1.0, 5.0, 0), p("recon", 2.0, 9.0, 0), p("bad", 1.5, 20.0, 7)];
        let s = svg(&[(Setting::Blur, pts)], &["bbox".into(), "recon".into(), "bad".into()], "test chart").unwrap();
        assert!(s.starts_with("<svg") && s.contains("</svg>"));
        for t in ["test chart", "blur", "bbox", "recon", "STE (%)"] {
            assert!(s.contains(t), "missing {t}");
        }
    }

    #[test]
    fn a_safe_variant_shares_its_colour_and_is_joined_to_it() {
        assert_eq!(base("bbox-safe"), "bbox");
        assert_eq!(base("mam2012-hyperplane-ps"), "mam2012-hyperplane-ps");
        let pts = vec![p("bbox", 1.0, 5.0, 0), p("bbox-safe", 1.2, 4.9, 0), p("other", 2.0, 9.0, 0)];
        let names: Vec<String> = ["bbox", "bbox-safe", "other"].iter().map(|s| s.to_string()).collect();
        let joined = svg(&[(Setting::Blur, pts.clone())], &names, "t").unwrap();
        let alone = svg(&[(Setting::Blur, pts[..1].iter().chain(&pts[2..]).cloned().collect())], &names, "t").unwrap();
        // The pair adds one line and one square in bbox's colour; the legend names bbox once.
        let c = colour(0);
        let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        assert!(joined.matches(&stroke).count() >= alone.matches(&stroke).count() + 2, "{joined}");
        assert_eq!(joined.matches("\nbbox\n").count(), 1, "{joined}");
        assert_eq!(joined.matches("\nbbox-safe\n").count(), 0, "{joined}");
    }
}
