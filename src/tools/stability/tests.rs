//! Tests of the sweep: the families build valid cases that really carry the parameter,
//! the run is deterministic across thread counts, a broken bound shows up, the chart
//! and the files are written, bad input is refused by name.

use super::families::{centroid_distance, double_root_parts, pixel_aspect, tangency};
use super::*;
use crate::bounds;
use crate::cases::generate::rng_for;
use crate::cli::stability::{run_cli, StabilityArgs};
use oracles::{classify, Coverage};
use std::path::Path;

fn built(f: Family, step: usize, param: f64, c: u64) -> Built {
    let mut rng = rng_for(1 ^ f.salt(), step as u64 * 1_000_000 + c);
    f.build(param, &mut rng, c, 4.0)
}

#[test]
fn every_family_builds_valid_cases_that_carry_the_parameter() {
    for f in Family::ALL {
        let steps = f.steps(None);
        assert!(steps.len() >= 7, "{}: {steps:?}", f.name());
        for (s, &p) in steps.iter().enumerate() {
            for c in 0..6 {
                let b = built(f, s, p, c);
                let ctx = format!("{} step {s} ({p:e}) case {c}", f.name());
                b.case.validate().unwrap_or_else(|e| panic!("{ctx}: {e}"));
                b.tile.validate().unwrap_or_else(|e| panic!("{ctx}: {e}"));
                let t = &b.case.triangle;
                let cam = b.case.lens.unwrap();
                match f {
                    Family::Focal => {
                        let got = (t.q[0][3] as f64 / cam.focus as f64 - 1.0).abs();
                        assert!((got - p).abs() <= 2f64.powi(-22) * (1.0 + p), "{ctx}: {got:e}");
                        assert_eq!(got, b.achieved, "{ctx}");
                        assert!(t.q[1][3] < cam.focus && t.q[2][3] > cam.focus, "{ctx}: one in front, one behind");
                        assert!((0..3).all(|k| t.q[k][3] == t.r[k][3]), "{ctx}: depths stay over the shutter");
                        assert!(cam.radius > 0.0, "{ctx}: lens on");
                    }
                    Family::WZero => {
                        let w = p as f32;
                        assert!(t.q[0][3] == w || t.r[0][3] == w, "{ctx}: {:?} {:?}", t.q[0], t.r[0]);
                        assert_eq!(b.achieved, w as f64, "{ctx}");
                        assert!(t.q != t.r, "{ctx}: motion on");
                        for k in 1..3 {
                            assert!(t.q[k][3] > 0.5 && t.r[k][3] > 0.5, "{ctx}: vertex {k} at an ordinary depth");
                        }
                    }
                    Family::Perspective => {
                        for k in 0..3 {
                            let ratio = t.r[k][3] as f64 / t.q[k][3] as f64;
                            assert!((ratio / p - 1.0).abs() <= 2f64.powi(-23), "{ctx}: vertex {k} ratio {ratio}");
                        }
                    }
                    Family::Sliver => {
                        let a = pixel_aspect(&b.case);
                        assert!((a / p - 1.0).abs() < 1e-3, "{ctx}: aspect {a:e}");
                        let mut late = b.case;
                        late.triangle.q = late.triangle.r;
                        let a1 = pixel_aspect(&late);
                        assert!((a1 / p - 1.0).abs() < 0.25, "{ctx}: aspect at t = 1 {a1:e}");
                        let w = [t.q[0][3], t.q[1][3], t.q[2][3]];
                        assert!(w[0] != w[1] || w[1] != w[2], "{ctx}: depths differ");
                    }
                    Family::Far => {
                        let d = centroid_distance(&b.case);
                        assert!((d - p).abs() <= 1e-6 * p + 1e-3, "{ctx}: centroid at {d}");
                        let (x, y) = b.tile.center();
                        let tile_dist = (x as f64).hypot(y as f64);
                        assert!(tile_dist > 0.5 * p - 100.0, "{ctx}: tile at {tile_dist}");
                    }
                    Family::DoubleRoot => double_root_checks(&b, p, &ctx),
                }
            }
        }
    }
}

/// The double-root construction: the depth is the step (to 0.2 %), certified to be the
/// f32 data's, the grazed corner is covered near t = 1/2 and the rest of the tile never.
fn double_root_checks(b: &Built, p: f64, ctx: &str) {
    let (v, corner) = double_root_parts(b);
    let tg = tangency(&v, corner);
    assert!((tg.delta / p - 1.0).abs() < 2e-3, "{ctx}: depth {:e}", tg.delta);
    assert!(tg.disc.lo > 0.0 && tg.disc.width() < 1e-3 * tg.disc.lo, "{ctx}: disc {:?}", tg.disc);
    assert!(tg.alpha.lo > 0.0 && (0.3..0.7).contains(&tg.tm), "{ctx}: tm {}", tg.tm);
    assert_eq!(b.achieved, tg.delta);
    assert!(b.case.triangle.c0 == [0.0; 3] && b.case.triangle.dims() == crate::model::Dims::Motion, "{ctx}");
    let tri = b.case.triangle.to_oracle();
    let at = |x: f32, y: f32, t: f64| classify(&tri, [x as f64, y as f64, 0.0, 0.0, t]);
    assert_eq!(at(corner[0], corner[1], tg.tm as f32 as f64), Coverage::Interior, "{ctx}: the corner at tm");
    // The covered span at P is tm -+ sqrt(disc) / (2 alpha); where it lies inside the
    // shutter, the shutter's ends are not covered.
    let half = tg.disc.mid().sqrt() / (2.0 * tg.alpha.mid());
    if p <= 1e-3 {
        assert!(half < 0.3 && tg.tm - half > 0.0 && tg.tm + half < 1.0, "{ctx}: span {half}");
    }
    for (t, outside) in [(0.0, tg.tm - half > 1e-3), (1.0, tg.tm + half < 1.0 - 1e-3)] {
        if outside {
            assert_ne!(at(corner[0], corner[1], t), Coverage::Interior, "{ctx}: the corner at t = {t}");
        }
    }
    let tl = b.tile;
    for i in 0..=8 {
        for j in 0..=8 {
            let (x, y) = (tl.x0 + 0.5 * i as f32, tl.y0 + 0.5 * j as f32);
            if [x, y] == corner {
                continue;
            }
            for k in 0..=50 {
                let c = at(x, y, k as f64 / 50.0);
                assert_ne!(c, Coverage::Interior, "{ctx}: ({x}, {y}) at t = {} is covered", k as f64 / 50.0);
            }
        }
    }
}

#[test]
fn double_root_discriminant_goes_to_zero() {
    let f = Family::DoubleRoot;
    for c in 0..4 {
        let rel: Vec<f64> = f
            .steps(None)
            .iter()
            .enumerate()
            .map(|(s, &p)| {
                let (v, corner) = double_root_parts(&built(f, s, p, c));
                let tg = tangency(&v, corner);
                tg.disc.mid() / (tg.beta.mid() * tg.beta.mid() + tg.alpha.mid() * tg.alpha.mid())
            })
            .collect();
        assert!(rel.windows(2).all(|w| w[1] < w[0] * 0.5), "case {c}: {rel:?}");
        assert!(*rel.last().unwrap() < 1e-6, "{rel:?}");
    }
}

#[test]
fn steps_run_from_the_benign_end() {
    assert_eq!(Family::Focal.steps(None), vec![1.0, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7]);
    assert_eq!(Family::Perspective.steps(None)[10], 1024.0);
    assert_eq!(Family::WZero.steps(None), vec![1.0, 1e-2, 1e-4, 1e-6, 0.0, -1e-6, -1e-4, -1e-2, -1.0]);
    assert_eq!(Family::WZero.steps(Some(15)).len(), 15);
    assert_eq!(Family::Far.steps(Some(3)), vec![1e1, 1e4, 1e7]);
    assert_eq!(fmt_param(1e-6), "1e-6");
    assert_eq!(fmt_param(1024.0), "1024");
    assert_eq!(fmt_param(-1e-4), "-1e-4");
}

fn small(methods: &[&str], steps: usize, cases: u64) -> Config {
    let ms = methods.iter().map(|m| bounds::by_id(m).or_else(|| bounds::broken::parse(m)).unwrap()).collect();
    let mut c = Config::new(ms);
    c.steps = Some(steps);
    c.cases = cases;
    c.samples = 128;
    c
}

fn run_in(threads: usize, cfg: &Config, f: Family) -> FamilyReport {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let mut r = pool.install(|| run_family(cfg, f, false));
    r.seconds = None;
    r
}

#[test]
fn identical_at_any_thread_count() {
    let cfg = small(&["bbox", "mam2012-hyperplane", "gdam2010"], 2, 4);
    for f in [Family::Sliver, Family::DoubleRoot] {
        let (a, b) = (run_in(1, &cfg, f), run_in(2, &cfg, f));
        assert_eq!(a.rows.len(), 6);
        assert_eq!(a, b, "{}", f.name());
        assert!(a.rows.iter().any(|r| r.tested > 0), "{}: something is tested", f.name());
    }
}

#[test]
fn a_broken_bound_shows_and_bbox_does_not() {
    let cfg = small(&["bbox", "broken/shrink/bbox"], 2, 6);
    let r = run_in(2, &cfg, Family::Focal);
    let rate = |m: &str| {
        let rows: Vec<&Row> = r.rows.iter().filter(|x| x.method == m).collect();
        rows.iter().map(|x| x.violations).sum::<u64>() as f64 / rows.iter().map(|x| x.cases).sum::<u64>() as f64
    };
    assert_eq!(rate("bbox"), 0.0, "{:#?}", r.rows);
    assert!(rate("broken/shrink/bbox") > 0.0, "{:#?}", r.rows);
    let ff = |m: &str| r.first_fails.iter().find(|x| x.method == m).unwrap().clone();
    assert_eq!(ff("bbox").step, None);
    assert!(ff("broken/shrink/bbox").step.is_some());
    // Pulled in by 1e-3: beyond the f32 allowance.
    assert!(ff("broken/shrink/bbox").gross_step.is_some());
    // The stored witness is covered and culled by the method's answer on its case.
    for row in r.rows.iter().filter(|x| x.violations > 0) {
        let w = row.witness.as_ref().unwrap();
        assert_eq!(classify(&w.case.triangle.to_oracle(), w.sample), Coverage::Interior, "{row:?}");
        let m = bounds::broken::parse(&row.method).unwrap();
        match m.setup(&w.case.triangle).tile(&w.tile) {
            TileResult::Empty => {}
            TileResult::Bounds(b) => assert!(crate::judge::culled_by(&b, w.sample).is_some(), "{row:?}"),
        }
        assert!(w.case_index % 1_000_000 < 6, "{row:?}");
    }
    for row in &r.rows {
        assert!(row.hits <= row.tested, "{row:?}");
        assert_eq!(row.cases, 6);
    }
    // bbox lets every covered sample through, the shrunk one fewer of them.
    let hits = |m: &str| r.rows.iter().filter(|x| x.method == m).map(|x| x.hits).sum::<u64>();
    assert!(hits("broken/shrink/bbox") <= hits("bbox"));
    let text = render(&r, false);
    assert!(text.contains("first fails at") && text.contains("broken/shrink/bbox"), "{text}");
}

fn fake_report(family: &str, params: &[f64], methods: &[&str]) -> FamilyReport {
    let mut rows = Vec::new();
    for (s, &p) in params.iter().enumerate() {
        for (mi, m) in methods.iter().enumerate() {
            rows.push(Row {
                family: family.into(),
                step: s,
                parameter: p,
                method: m.to_string(),
                cases: 10,
                violations: (s * mi) as u64 % 4,
                undecided: 0,
                boundary_only: 0,
                nonfinite: (s == 1) as u64,
                disabled: 0,
                tested: 100,
                hits: 10 + 5 * mi as u64,
                ste: Some((10 + 5 * mi) as f64 / 100.0),
                margin: 0.0,
                worst_bound: None,
                witness: None,
            });
        }
    }
    FamilyReport {
        family: family.into(),
        parameter: "the parameter".into(),
        construction: String::new(),
        seed: 1,
        cases: 10,
        tile: 4.0,
        samples: 100,
        methods: methods.iter().map(|m| m.to_string()).collect(),
        steps: params
            .iter()
            .enumerate()
            .map(|(s, &p)| Step { step: s, parameter: p, achieved_min: p, achieved_max: p })
            .collect(),
        rows,
        first_fails: vec![],
        seconds: None,
    }
}

#[test]
fn the_chart_has_a_line_per_method_and_panel() {
    let methods = ["bbox", "la2011", "gdam2010"];
    for (family, params) in [("focal", vec![1.0, 1e-1, 1e-2, 1e-3]), ("w-zero", vec![1.0, 1e-6, 0.0, -1e-6, -1.0])] {
        let r = fake_report(family, &params, &methods);
        let names: Vec<String> = methods.iter().map(|m| m.to_string()).collect();
        let s = chart::svg(&r, &names).unwrap();
        assert!(s.starts_with("<svg") && s.trim_end().ends_with("</svg>"));
        for t in ["violation rate", "NaN/inf rate", "STE (%)", "bbox", "la2011", "gdam2010", "the parameter"] {
            assert!(s.contains(t), "{family}: missing {t}");
        }
        for (i, _) in methods.iter().enumerate() {
            let c = chart::colour(i);
            let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
            let lines = s.lines().filter(|l| l.contains("<polyline") && l.contains(&stroke)).count();
            assert_eq!(lines, 4, "{family}: method {i}: three panels and the legend ({stroke})");
        }
    }
    let a = chart::Axis::SymLog;
    assert_eq!((a.x(-1e-6), a.x(0.0), a.x(1.0)), (-1.0, 0.0, 7.0));
    assert_eq!(chart::Axis::of("perspective").x(1024.0), 10.0);
}

fn args(family: &str, method: &str, out: &Path) -> StabilityArgs {
    StabilityArgs {
        family: family.into(),
        method: method.into(),
        steps: Some(2),
        cases: 2,
        seed: 3,
        tile: 4.0,
        samples: 64,
        out: out.to_path_buf(),
        json: Some(out.join("rows.json")),
        jobs: Some(1),
    }
}

#[test]
fn the_command_writes_svg_markdown_and_json() {
    let dir = std::env::temp_dir().join(format!("cullproof-stability-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    run_cli(&args("sliver,far", "bbox,mam2012-hyperplane", &dir)).unwrap();
    for f in ["sliver", "far"] {
        let svg = std::fs::read_to_string(dir.join(format!("{f}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("</svg>"), "{f}");
        assert!(svg.matches("<polyline").count() >= 2 * 3, "{f}: a line per method and panel");
        let md = std::fs::read_to_string(dir.join(format!("{f}.md"))).unwrap();
        assert!(md.contains("First fails at") && md.contains("mam2012-hyperplane"), "{f}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("rows.json")).unwrap()).unwrap();
    assert_eq!(json["kind"], "cullproof-stability");
    let fams = json["families"].as_array().unwrap();
    assert_eq!(fams.len(), 2);
    let rows = fams[0]["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * 2);
    for k in ["family", "step", "parameter", "method", "cases", "violations", "undecided", "nonfinite", "ste"] {
        assert!(rows[0].get(k).is_some(), "row field {k}");
    }
    assert!(fams[0]["first_fails"][0].get("parameter").is_some());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_is_refused_by_name() {
    let e = Family::parse("focal,wzero").unwrap_err().to_string();
    assert!(e.contains("--family") && e.contains("`wzero`") && e.contains("w-zero"), "{e}");
    let dir = std::env::temp_dir().join("cullproof-stability-never-written");
    let e = run_cli(&args("nope", "bbox", &dir)).unwrap_err().to_string();
    assert!(e.contains("--family nope"), "{e}");
    let e = run_cli(&args("focal", "bbox,la2012", &dir)).unwrap_err().to_string();
    assert!(e.contains("--method") && e.contains("`la2012`"), "{e}");
    let mut a = args("focal", "bbox", &dir);
    a.tile = -1.0;
    assert!(run_cli(&a).unwrap_err().to_string().contains("--tile -1"));
    assert!(!dir.exists(), "nothing written on bad input");
}
