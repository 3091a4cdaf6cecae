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
}

/// A method that answers another's bounds, every interval pulled in by `eps` at both
/// ends (the kind of slip a hand-derived bound makes).
struct Shrunk {
    inner: &'static dyn Method,
    eps: f32,
    info: &'static MethodInfo,
}
struct ShrunkP(Box<dyn Prepared>, f32);
impl Prepared for ShrunkP {
    fn tile(&self, t: &Tile) -> TileResult {
        match self.0.tile(t) {
            TileResult::Empty => TileResult::Empty,
            TileResult::Bounds(mut b) => {
                let e = self.1;
                b.u = [b.u[0] + e, b.u[1] - e];
                b.v = [b.v[0] + e, b.v[1] - e];
                b.t = [b.t[0] + e, b.t[1] - e];
                TileResult::Bounds(b)
            }
        }
    }
}
impl Method for Shrunk {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(ShrunkP(self.inner.setup(tri), self.eps))
    }
}

fn leak(m: impl Method + 'static) -> &'static dyn Method {
    Box::leak(Box::new(m))
}

#[test]
fn a_bound_shrunk_by_1e_3_is_caught_within_a_few_cases() {
    for inner in ["bbox", "la2011", "mam2012"] {
        let inner = cullproof::bounds::by_id(inner).unwrap();
        let info: &'static MethodInfo = Box::leak(Box::new(MethodInfo { id: "shrunk", ..*inner.info() }));
        let m = leak(Shrunk { inner, eps: 1e-3, info });
        let mut cfg = CheckConfig::default_with(vec![m]);
        cfg.cases = 28;
        let r = run(&cfg, &Expectations::default(), false);
        let v: u64 = r.rows.iter().map(|x| x.violations).sum();
        assert!(v > 0, "{} shrunk by 1e-3 not caught in 28 cases", inner.info().id);
        assert!(r.failed());
        // The margin needed is what the slip took away, at most.
        for row in r.rows.iter().filter(|x| x.violations > 0) {
            let w = row.worst.as_ref().unwrap();
            assert!(w.margin > 0.0 && w.margin <= 1e-3 + 1e-6, "{} {}: margin {}", row.regime, w.bound, w.margin);
        }
    }
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
