//! The gate itself: it passes on its fixed budget against corpus/expectations.json,
//! catches deliberately broken bounds within a few cases, and finds nothing wrong with
//! a bound that culls nothing.

use cullproof::bounds::{Method, MethodInfo, Outputs, Prepared, TileBounds, TileResult};
use cullproof::check::{run, CheckConfig, Expectations};
use cullproof::model::{Tile, Triangle};
use std::path::Path;

fn expectations() -> Expectations {
    Expectations::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/expectations.json")).unwrap()
}

#[test]
fn gate_passes_on_a_fixed_budget() {
    let mut cfg = CheckConfig::default_with(cullproof::bounds::registry());
    cfg.cases = 140;
    let r = run(&cfg, &expectations(), false);
    let bad: Vec<_> = r.rows.iter().filter(|x| x.status == "UNEXPECTED VIOLATION").collect();
    assert!(bad.is_empty(), "{}", cullproof::check::render(&r));
    assert_eq!(r.rows.iter().map(|x| x.cases).sum::<u64>(), 140 * cfg.methods.len() as u64);
    // The sampled cross-check ran, and Embree's f32 differs from the exact oracle on
    // at most 1 in 1000 uniform samples, except far from the origin (where f32 keeps
    // 1/16 px).
    assert!(r.cross_check.iter().map(|c| c.samples).sum::<u64>() > 10_000);
    for c in r.cross_check.iter().filter(|c| c.regime != "far-from-origin") {
        assert!((c.embree_over + c.embree_under) * 1000 <= c.samples, "{c:?}");
    }
    // the summary names every method once, bbox without a violation
    let text = cullproof::check::render(&r);
    let summary = text.split("per method, all regimes:").nth(1).expect("a per-method summary");
    for m in &cfg.methods {
        assert!(summary.lines().any(|l| l.starts_with(&format!("{} ", m.info().id))), "{}", m.info().id);
    }
    assert!(summary.lines().any(|l| l.starts_with("bbox ") && l.ends_with("no violation")), "{summary}");
    // every method x every regime got cases
    for m in &cfg.methods {
        for g in cullproof::gen::Regime::ALL {
            let n: u64 =
                r.rows.iter().filter(|x| x.method == m.info().id && x.regime == g.name()).map(|x| x.cases).sum();
            assert!(n >= 8, "{} x {}: {n} cases", m.info().id, g.name());
        }
    }
}

#[test]
fn a_bound_shrunk_by_1e_3_is_caught_within_a_few_cases() {
    for inner in ["bbox", "la2011", "mam2012"] {
        let m = cullproof::bounds::broken::parse(&format!("broken/shrink/{inner}")).unwrap();
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 28;
        let r = run(&cfg, &Expectations::default(), false);
        let v: u64 = r.rows.iter().map(|x| x.violations).sum();
        assert!(v > 0, "{inner} shrunk by 1e-3 not caught in 28 cases");
        assert!(r.failed());
        // The margin needed is what the slip took away, plus at most the method's own
        // f32 rounding (below 1e-4, corpus/expectations.json).
        for row in r.rows.iter().filter(|x| x.violations > 0) {
            let w = row.worst.as_ref().unwrap();
            assert!(w.margin > 0.0 && w.margin <= 1e-3 + 1e-4, "{} {}: margin {}", row.regime, w.bound, w.margin);
        }
        // Every case of the slip that is caught is caught by at least the slip.
        assert!(r.rows.iter().any(|x| x.margin_needed >= 0.9e-3), "{inner}: no witness near the 1e-3 slip");
    }
}

#[test]
fn a_dropped_lens_padding_term_is_caught_within_a_few_cases() {
    let m = cullproof::bounds::broken::parse("broken/no-coc-pad/bbox").unwrap();
    let mut cfg = CheckConfig::default_with(vec![m]);
    cfg.regimes = vec![cullproof::gen::Regime::Defocus];
    cfg.cases = 8;
    let r = run(&cfg, &Expectations::default(), false);
    assert!(r.rows[0].violations > 0 && r.failed(), "{}", cullproof::check::render(&r));
    // And the correct bbox passes the same cases.
    let mut ok = cfg.clone();
    ok.methods = vec![cullproof::bounds::by_id("bbox").unwrap()];
    assert_eq!(run(&ok, &Expectations::default(), false).rows[0].violations, 0);
}

struct Everything;
struct EverythingP;
impl Prepared for EverythingP {
    fn tile(&self, _t: &Tile) -> TileResult {
        TileResult::Bounds(TileBounds::full())
    }
}
static EVERYTHING: MethodInfo = MethodInfo {
    id: "bbox",
    source: "test: the whole domain",
    reconstruction: false,
    dims: &[],
    outputs: Outputs { tile_reject: false, lens: false, time: false, depth: false, per_sample: false },
};
impl Method for Everything {
    fn info(&self) -> &'static MethodInfo {
        &EVERYTHING
    }
    fn setup(&self, _t: &Triangle) -> Box<dyn Prepared> {
        Box::new(EverythingP)
    }
}

#[test]
fn a_bound_that_culls_nothing_shows_no_violation_in_100k_cases() {
    let mut cfg = CheckConfig::default_with(vec![&Everything]);
    cfg.cases = 100_000;
    cfg.samples = 0;
    let r = run(&cfg, &Expectations::default(), false);
    assert_eq!(r.rows.iter().map(|x| x.cases).sum::<u64>(), 100_000);
    assert!(r.rows.iter().all(|x| x.violations == 0 && x.undecided == 0), "{}", cullproof::check::render(&r));
}

/// A side search that stops raising its certified bound gives up after `side_stall`
/// boxes: the same cases cost fewer boxes, and what it still finds is a certified
/// violation all the same (the verdicts only lose rounding-size witnesses).
#[test]
fn stalled_side_searches_give_up_early() {
    let m = cullproof::bounds::by_id("la2011").unwrap();
    let run_with = |stall: usize| {
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 96;
        cfg.side_stall = stall;
        run(&cfg, &expectations(), false)
    };
    let (full, stalled) = (run_with(0), run_with(50));
    assert!(stalled.solver_boxes * 2 < full.solver_boxes, "{} vs {} boxes", stalled.solver_boxes, full.solver_boxes);
    let v = |r: &cullproof::check::CheckReport| r.rows.iter().map(|x| x.violations).sum::<u64>();
    assert!(v(&full) > 0 && v(&stalled) > 0, "{} and {} violations", v(&full), v(&stalled));
    assert!(!stalled.failed());
}
