//! The gate itself: three verdicts (a budget never passes), tiles at each method's own
//! tile-reject limit (bbox's f32 culls found, bbox-safe proven), expectation signatures
//! and the baseline catching slips in methods already known to be off, and nothing
//! wrong with a bound that culls nothing.

use cullproof::bounds::{Method, MethodInfo, Outputs, Prepared, TileBounds, TileResult};
use cullproof::gate::baseline::BaselineFile;
use cullproof::gate::{run, run_with_baseline, CheckConfig, CheckReport, Expectations, Status};
use cullproof::model::{Tile, Triangle};
use std::path::Path;

fn expectations() -> Expectations {
    Expectations::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/expectations.json")).unwrap()
}

fn render(r: &CheckReport) -> String {
    cullproof::gate::render(r)
}

fn sum(r: &CheckReport, f: fn(&cullproof::gate::Row) -> u64) -> u64 {
    r.rows.iter().map(f).sum()
}

#[test]
fn gate_passes_on_a_fixed_budget() {
    let mut cfg = CheckConfig::default_with(cullproof::bounds::registry());
    cfg.cases = 140;
    let r = run(&cfg, &expectations(), false);
    assert!(!r.failed(), "{}", render(&r));
    assert_eq!(sum(&r, |x| x.cases), 140 * cfg.methods.len() as u64);
    // Every case gets exactly one of the three verdicts.
    for x in &r.rows {
        assert_eq!(x.proven + x.violations + x.unproven, x.cases, "{x:?}");
    }
    // The sampled cross-check ran, and Embree's f32 differs from the exact oracle on
    // at most 1 in 1000 uniform samples, except far from the origin (where f32 keeps
    // 1/16 px).
    assert!(r.cross_check.iter().map(|c| c.samples).sum::<u64>() > 10_000);
    for c in r.cross_check.iter().filter(|c| c.regime != "far-from-origin") {
        assert!((c.embree_over + c.embree_under) * 1000 <= c.samples, "{c:?}");
    }
    // the summary names every method once with its strongest verdict: bbox-safe
    // has a proof for all inputs (machine-checked) and every case of the run proven
    let text = render(&r);
    let summary = text.split("per method, all regimes").nth(1).expect("a per-method summary");
    for m in &cfg.methods {
        assert!(summary.lines().any(|l| l.starts_with(&format!("{} ", m.info().id))), "{}", m.info().id);
    }
    assert!(
        summary.lines().any(|l| l.starts_with("bbox-safe ")
            && l.contains("machine-checked for all inputs in ranges")
            && l.contains("all 140 cases proven")),
        "{summary}"
    );
    // every method x every regime got cases
    for m in &cfg.methods {
        for g in cullproof::cases::generate::Regime::ALL {
            let n: u64 =
                r.rows.iter().filter(|x| x.method == m.info().id && x.regime == g.name()).map(|x| x.cases).sum();
            assert!(n >= 8, "{} x {}: {n} cases", m.info().id, g.name());
        }
    }
}

/// bbox compares f32 corner quotients with the tile's edges; the limit tiles put an
/// edge right at the rounded value, so the gate finds the covered tiles bbox culls, by
/// itself. bbox-safe, the same box rounded outward, is proven on the same cases.
#[test]
fn the_gate_finds_bbox_f32_tile_culls_and_proves_bbox_safe() {
    let ms = ["bbox", "bbox-safe"].map(|m| cullproof::bounds::by_id(m).unwrap()).to_vec();
    let mut cfg = CheckConfig::default_with(ms);
    cfg.cases = 1200;
    cfg.limit_every = 1;
    let r = run(&cfg, &Expectations::default(), false);
    let rows = |m: &'static str| r.rows.iter().filter(move |x| x.method == m);
    let bbox_v: u64 = rows("bbox").map(|x| x.violations).sum();
    assert!(bbox_v >= 3, "bbox: {bbox_v} violations in 1200 cases\n{}", render(&r));
    for x in rows("bbox").filter(|x| x.violations > 0) {
        assert!(x.bounds.keys().all(|k| k == "tile culled"), "{x:?}");
        assert!(x.limit_violations > 0, "{x:?}");
    }
    for x in rows("bbox-safe") {
        assert_eq!(x.violations, 0, "{}", render(&r));
        assert!(x.limit_tiles > 0 || x.regime == "behind-lens", "{x:?}");
    }
    let safe_unproven: u64 = rows("bbox-safe").map(|x| x.unproven).sum();
    assert!(safe_unproven <= 12, "bbox-safe: {safe_unproven} unproven\n{}", render(&r));
}

/// A budget, a stall or a resolution never turns into a pass: with one box per side
/// and per constraint search, claims that need more cannot be settled, and those
/// cases are unproven, not proven; more budget never proves less. (A -safe variant:
/// what more budget decides for it is proofs; for a published method the judge's side
/// cuts may decide every extra case as a violation.)
#[test]
fn budgets_that_run_out_leave_cases_unproven() {
    // Per-sample planes (constraint budget) and depth ends (side budget): with one box
    // each, some cases of both stay open.
    let ms = ["mam2012-hyperplane-ps-safe", "nilsson2012-depth-safe"].map(|id| cullproof::bounds::by_id(id).unwrap());
    let run_with = |budget: usize| {
        let mut cfg = CheckConfig::default_with(ms.to_vec());
        cfg.cases = 64;
        cfg.judge.side_budget = budget;
        cfg.judge.constraint_budget = budget;
        cfg.judge.side_stall = 0;
        cfg.limit_every = 0;
        run(&cfg, &Expectations::default(), false)
    };
    let (full, starved) = (run_with(2000), run_with(1));
    let (p_full, p_starved) = (sum(&full, |x| x.proven), sum(&starved, |x| x.proven));
    assert!(p_starved < p_full, "proven with 1 box: {p_starved}, with 2000: {p_full}");
    assert!(sum(&starved, |x| x.unproven) > sum(&full, |x| x.unproven));
    for reason in ["constraint-budget", "side-gap"] {
        assert!(starved.rows.iter().any(|x| x.unproven_by.contains_key(reason)), "{reason}: {}", render(&starved));
    }
    for (a, b) in full.rows.iter().zip(&starved.rows) {
        assert!(
            b.proven <= a.proven,
            "{} {}: {} proven with 1 box, {} with 2000",
            a.method,
            a.regime,
            b.proven,
            a.proven
        );
    }
}

#[test]
fn a_bound_shrunk_by_1e_3_is_caught_within_a_few_cases() {
    for inner in ["bbox", "la2011", "mam2012"] {
        let m = cullproof::bounds::broken::parse(&format!("broken/shrink/{inner}")).unwrap();
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 28;
        let r = run(&cfg, &Expectations::default(), false);
        assert!(sum(&r, |x| x.violations) > 0, "{inner} shrunk by 1e-3 not caught in 28 cases");
        assert!(r.failed());
        // Every case of the slip that is caught is caught by at least the slip.
        assert!(r.rows.iter().any(|x| x.margin_needed >= 0.9e-3), "{inner}: no witness near the 1e-3 slip");
    }
}

/// A slip in a method already known to violate is still caught: its expectations
/// state the kinds of bounds it violates, with caps, and a rate cap.
#[test]
fn slips_in_known_bad_methods_leave_their_signature() {
    let ex = expectations();
    for id in ["broken/shrink/la2011", "broken/no-coc-pad/la2011", "broken/swap-coc/wu2013"] {
        let m = cullproof::bounds::broken::parse(id).unwrap();
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 320;
        let r = run(&cfg, &ex, false);
        assert!(r.failed(), "{id} passed the gate\n{}", render(&r));
        assert!(r.rows.iter().any(|x| x.status == Status::BeyondSignature), "{id}\n{}", render(&r));
    }
}

/// The tail in `check`: a kind above its regime's cap but within another regime's is
/// counted per row and held to the method's tail rate over all its rows; without a
/// tail rate it is beyond the signature. `broken/shrink/la2011-safe` pulls every end in
/// by 1e-3, above `motion`'s caps (1e-9) and within `static`'s (10).
#[test]
fn a_kind_above_its_regime_cap_counts_against_the_tail_rate() {
    use cullproof::cases::generate::Regime;
    let kinds = ["u min", "u max", "v min", "v max", "t min", "t max"];
    let caps = |c: &str| kinds.iter().map(|k| format!(r#""{k}": {c}"#)).collect::<Vec<_>>().join(", ");
    let gate = |tail: Option<&str>| {
        let rate = tail.map_or(String::new(), |t| format!(r#", "max_tail_rate": {t}"#));
        let row = |c: &str| {
            format!(
                r#"{{"expect": "violation", "why": "tail", "bounds": {{{}, "tile culled": "inf"}}, "max_rate": 1{rate}}}"#,
                caps(c)
            )
        };
        let text = format!(r#"{{"la2011-safe": {{"motion": {}, "static": {}}}}}"#, row("1e-9"), row("10"));
        let ex = Expectations::parse_with(&text, "tail test", &|m| cullproof::bounds::by_id(m).is_some()).unwrap();
        let m = cullproof::bounds::broken::parse("broken/shrink/la2011-safe").unwrap();
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.regimes = vec![Regime::Motion, Regime::Static];
        cfg.cases = 64;
        run(&cfg, &ex, false)
    };
    let row = |r: &CheckReport, regime: &str| r.rows.iter().find(|x| x.regime == regime).unwrap().clone();
    // every case allowed in the tail: the rows pass, the tail is counted
    let r = gate(Some("1"));
    let motion = row(&r, "motion");
    assert!(!r.failed() && motion.tail > 0 && motion.tail <= motion.violations, "{}", render(&r));
    assert_eq!(row(&r, "static").tail, 0, "within its own caps");
    // a tail rate the slip passes: the rows with a tail case fail, naming the count
    let r = gate(Some("0.0001"));
    let motion = row(&r, "motion");
    assert!(r.failed() && motion.status == Status::BeyondSignature, "{}", render(&r));
    assert!(motion.problems.iter().any(|p| p.starts_with("tail: ")), "{:?}", motion.problems);
    assert_eq!(row(&r, "static").status, Status::KnownViolation);
    // no tail rate: beyond the signature, each kind named
    let r = gate(None);
    let motion = row(&r, "motion");
    assert!(r.failed() && motion.tail == 0 && motion.status == Status::BeyondSignature, "{}", render(&r));
    assert!(motion.problems.iter().any(|p| p.contains("above the cap")), "{:?}", motion.problems);
}

#[test]
fn a_dropped_lens_padding_term_is_caught_within_a_few_cases() {
    let m = cullproof::bounds::broken::parse("broken/no-coc-pad/bbox").unwrap();
    let mut cfg = CheckConfig::default_with(vec![m]);
    cfg.regimes = vec![cullproof::cases::generate::Regime::Defocus];
    cfg.cases = 8;
    let r = run(&cfg, &Expectations::default(), false);
    assert!(r.rows[0].violations > 0 && r.failed(), "{}", render(&r));
    // And bbox-safe passes the same cases, every one proven.
    let mut ok = cfg.clone();
    ok.methods = cullproof::bounds::shared_all([cullproof::bounds::by_id("bbox-safe").unwrap()]);
    let r = run(&ok, &Expectations::default(), false);
    assert_eq!((r.rows[0].violations, r.rows[0].proven), (0, 8), "{}", render(&r));
}

/// The baseline: a run of the same settings compares row by row; a looser answer or
/// more violations than stored is a regression, the stored run itself is not.
#[test]
fn the_baseline_catches_a_looser_and_a_worse_method() {
    let m = cullproof::bounds::by_id("la2011").unwrap();
    let mut cfg = CheckConfig::default_with(vec![m]);
    cfg.cases = 160;
    let ex = Expectations::default();
    let first = run(&cfg, &ex, false);
    let mut file = BaselineFile::default();
    file.record(&cfg, &first).unwrap();
    let again = run_with_baseline(&cfg, &ex, Some(&file), false);
    assert!(again.baseline.is_some());
    assert!(again.rows.iter().all(|x| x.status != Status::Regression), "{}", render(&again));
    for (slip, what) in [("loose", "looser"), ("shrink-rel", "")] {
        let b = cullproof::bounds::broken::parse(&format!("broken/{slip}/la2011")).unwrap();
        let c = CheckConfig { methods: cullproof::bounds::shared_all([b]), ..cfg.clone() };
        let r = run_with_baseline(&c, &ex, Some(&file), false);
        let reg: Vec<_> = r.rows.iter().filter(|x| x.status == Status::Regression || x.status.fails()).collect();
        assert!(!reg.is_empty(), "{slip}: not seen against the baseline\n{}", render(&r));
        assert!(reg.iter().any(|x| x.problems.iter().any(|p| p.contains(what))), "{slip}\n{}", render(&r));
    }
    // Other settings: no baseline applies.
    let other = CheckConfig { seed: 2, ..cfg.clone() };
    assert!(run_with_baseline(&other, &ex, Some(&file), false).baseline.is_none());
}

struct Everything;
struct EverythingP;
impl Prepared for EverythingP {
    fn tile(&self, _t: &Tile) -> TileResult {
        TileResult::Bounds(TileBounds::full())
    }
}
static EVERYTHING: MethodInfo = MethodInfo {
    id: "everything",
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
fn a_bound_that_culls_nothing_is_proven_in_100k_cases() {
    let mut cfg = CheckConfig::default_with(vec![&Everything]);
    cfg.cases = 100_000;
    cfg.samples = 0;
    let r = run(&cfg, &Expectations::default(), false);
    assert_eq!(sum(&r, |x| x.cases), 100_000);
    assert_eq!(sum(&r, |x| x.proven), 100_000, "{}", render(&r));
}

/// A side search that stops raising its certified bound gives up after `side_stall`
/// boxes: the same cases cost fewer boxes, what it still finds is a certified
/// violation all the same, and what it gives up on is unproven.
#[test]
fn stalled_side_searches_give_up_early() {
    let m = cullproof::bounds::by_id("la2011").unwrap();
    let run_with = |stall: usize| {
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 96;
        cfg.judge.side_stall = stall;
        run(&cfg, &expectations(), false)
    };
    let (full, stalled) = (run_with(0), run_with(50));
    assert!(stalled.solver_boxes * 2 < full.solver_boxes, "{} vs {} boxes", stalled.solver_boxes, full.solver_boxes);
    let v = |r: &CheckReport| sum(r, |x| x.violations);
    assert!(v(&full) > 0 && v(&stalled) > 0, "{} and {} violations", v(&full), v(&stalled));
    assert!(sum(&stalled, |x| x.proven) <= sum(&full, |x| x.proven));
    assert!(!stalled.failed(), "{}", render(&stalled));
}

/// The stored baseline covers the default gate and the 960-case run of `power`, and
/// the 960-case run of every method matches it: no row worse than stored, no row
/// failing its expectations.
#[test]
fn the_stored_baseline_holds_at_960_cases() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let file = BaselineFile::load(&root.join("corpus/baseline.json")).unwrap();
    let mut cfg = CheckConfig::default_with(cullproof::bounds::registry());
    let default = cullproof::gate::settings::Settings::of(&cfg).unwrap();
    assert!(file.find(&default).is_some(), "no baseline for the default gate");
    cfg.cases = 960;
    let r = run_with_baseline(&cfg, &expectations(), Some(&file), false);
    assert!(r.baseline.as_deref().is_some_and(|b| b.contains("0 worse")), "{:?}\n{}", r.baseline, render(&r));
    assert!(!r.failed(), "{}", render(&r));
}

/// The default gate (`cullproof check`: seed 1, 9,600 cases, every method) passes its
/// expectations and matches the stored baseline row by row: what CI runs on every
/// change.
#[test]
fn the_default_gate_passes_and_matches_its_baseline() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let file = BaselineFile::load(&root.join("corpus/baseline.json")).unwrap();
    let cfg = CheckConfig::default_with(cullproof::bounds::registry());
    let r = run_with_baseline(&cfg, &expectations(), Some(&file), false);
    assert!(r.baseline.as_deref().is_some_and(|b| b.contains("0 worse")), "{:?}\n{}", r.baseline, render(&r));
    assert!(!r.failed(), "{}", render(&r));
    let safe: Vec<_> = r.rows.iter().filter(|x| x.method == "bbox-safe").collect();
    assert!(safe.iter().all(|x| x.proven == x.cases), "bbox-safe not proven on every case\n{}", render(&r));
}

/// `Gate::jobs` sets the worker threads of a library run, and the report does not
/// depend on it.
#[test]
fn a_library_gate_reports_the_same_at_any_thread_count() {
    let run = |jobs: usize| {
        cullproof::Gate::new()
            .method(cullproof::bounds::by_id("la2011-safe").unwrap())
            .method(cullproof::bounds::by_id("wu2013").unwrap())
            .cases(320)
            .jobs(jobs)
            .run()
    };
    let (one, two) = (run(1), run(2));
    // Everything but the header line, which holds the run's wall time.
    let body = |r: &cullproof::GateReport| r.render().lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&one), body(&two));
    let wu = one.method("wu2013").expect("wu2013 is in the report");
    assert!(wu.violated > 0, "the published wu2013 shows violations on 320 cases: {}", one.render());
}
