//! The gate's power: every method with every planted slip of
//! [`crate::bounds::broken`], each run through the gate with the real expectations and
//! the stored baseline (a slip in method M is held to M's expectations and M's
//! baseline rows). A slip is **killed** when the gate fails on it. A slip whose answers
//! are identical to the method's on every case of the run has **no effect** there
//! (equivalent on these cases: e.g. a looser interval for a method that narrows none)
//! and is left out of the score.

use super::baseline::BaselineFile;
use super::{run_with_baseline, CheckConfig, Expectations};
use crate::bounds::{broken, Method, TileResult};
use crate::cases::make_case;
use serde::Serialize;

/// One method x slip.
#[derive(Clone, Debug, Serialize)]
pub struct PowerRow {
    pub method: String,
    pub slip: String,
    /// Cases whose boundary-tile answer differs from the method's.
    pub changed: u64,
    pub killed: bool,
    /// How the gate failed: "status: method / regime: problem" for each failing row.
    pub by: Vec<String>,
}

/// The whole run.
#[derive(Clone, Debug, Serialize)]
pub struct PowerReport {
    pub cases: u64,
    pub seed: u64,
    pub rows: Vec<PowerRow>,
}

impl PowerReport {
    /// (killed, slips with an effect).
    pub fn score(&self) -> (usize, usize) {
        let live: Vec<&PowerRow> = self.rows.iter().filter(|r| r.changed > 0).collect();
        (live.iter().filter(|r| r.killed).count(), live.len())
    }
}

fn same(a: &TileResult, b: &TileResult, probes: &[crate::model::Sample]) -> bool {
    match (a, b) {
        (TileResult::Empty, TileResult::Empty) => true,
        (TileResult::Bounds(x), TileResult::Bounds(y)) => {
            let eq = |p: [f32; 2], q: [f32; 2]| p[0].to_bits() == q[0].to_bits() && p[1].to_bits() == q[1].to_bits();
            eq(x.u, y.u)
                && eq(x.v, y.v)
                && eq(x.t, y.t)
                && match (x.z, y.z) {
                    (Some(p), Some(q)) => eq(p, q),
                    (None, None) => true,
                    _ => false,
                }
                && x.constraints.len() == y.constraints.len()
                && x.constraints.iter().zip(&y.constraints).all(|(c, d)| {
                    c.name() == d.name() && probes.iter().all(|s| c.eval(s).to_bits() == d.eval(s).to_bits())
                })
        }
        _ => false,
    }
}

/// Samples at which two answers' constraints are compared: a fixed lattice over the
/// tile and the lens/shutter domain.
fn probes(tile: &crate::model::Tile) -> Vec<crate::model::Sample> {
    let mut out = Vec::new();
    let f = |k: usize, n: usize| (k as f32 + 0.5) / n as f32;
    for i in 0..4 {
        for j in 0..4 {
            for a in 0..3 {
                for b in 0..3 {
                    for c in 0..3 {
                        out.push(crate::model::Sample::new(
                            tile.x0 + f(i, 4) * (tile.x1 - tile.x0),
                            tile.y0 + f(j, 4) * (tile.y1 - tile.y0),
                            2.0 * f(a, 3) - 1.0,
                            2.0 * f(b, 3) - 1.0,
                            f(c, 3),
                        ));
                    }
                }
            }
        }
    }
    out
}

/// Cases (of the run's settings) on which the slip answers differently from the method
/// (intervals, or a constraint's value at one of the [`probes`]).
fn changed(cfg: &CheckConfig, m: &dyn Method, slip: &dyn Method) -> u64 {
    (0..cfg.cases)
        .filter(|&i| {
            let (_, case, tile) = make_case(&cfg.draw(), i);
            !same(&m.setup(&case.triangle).tile(&tile), &slip.setup(&case.triangle).tile(&tile), &probes(&tile))
        })
        .count() as u64
}

/// Run every method of `cfg.methods` with every slip in `slips`.
pub fn run(
    cfg: &CheckConfig,
    ex: &Expectations,
    base: Option<&BaselineFile>,
    slips: &[&str],
    progress: bool,
) -> PowerReport {
    let pb = if progress {
        indicatif::ProgressBar::new((cfg.methods.len() * slips.len()) as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    let mut rows = Vec::new();
    for m in &cfg.methods {
        for kind in slips {
            let id = format!("broken/{kind}/{}", m.info().id);
            pb.set_message(id.clone());
            let Some(slip) = broken::parse(&id) else { continue };
            let n = changed(cfg, m.as_ref(), slip);
            let (killed, by) = if n == 0 {
                (false, Vec::new())
            } else {
                let c = CheckConfig { methods: vec![crate::bounds::shared(slip)], ..cfg.clone() };
                let r = run_with_baseline(&c, ex, base, false);
                let by: Vec<String> = r
                    .rows
                    .iter()
                    .filter(|x| x.status.fails())
                    .map(|x| format!("{}: {}: {}", x.status.text(), x.regime, x.problems.join("; ")))
                    .collect();
                (r.failed(), by)
            };
            rows.push(PowerRow { method: m.info().id.into(), slip: kind.to_string(), changed: n, killed, by });
            pb.inc(1);
        }
    }
    pb.finish_and_clear();
    PowerReport { cases: cfg.cases, seed: cfg.seed, rows }
}

/// The table: a row per method, a column per slip (killed / survived / no effect),
/// and the score.
pub fn render(r: &PowerReport, slips: &[&str]) -> String {
    let mut s = format!("cullproof power, seed {}, {} cases per run\n\n{:<26}", r.seed, r.cases, "method");
    for k in slips {
        s += &format!(" {k:>11}");
    }
    s += "   killed\n";
    let mut methods: Vec<&str> = Vec::new();
    for row in &r.rows {
        if !methods.contains(&row.method.as_str()) {
            methods.push(&row.method);
        }
    }
    for m in methods {
        s += &format!("{m:<26}");
        let (mut k, mut live) = (0, 0);
        for kind in slips {
            let cell = match r.rows.iter().find(|x| x.method == m && x.slip == *kind) {
                Some(x) if x.changed == 0 => "no effect",
                Some(x) if x.killed => {
                    k += 1;
                    live += 1;
                    "killed"
                }
                Some(_) => {
                    live += 1;
                    "SURVIVED"
                }
                None => "-",
            };
            s += &format!(" {cell:>11}");
        }
        s += &format!("   {k}/{live}\n");
    }
    let (k, n) = r.score();
    s += &format!(
        "\nscore: {k} of {n} slips with an effect killed ({:.0} %); \"no effect\": the slip's answers equal the \
         method's on every case of the run.\n",
        if n > 0 { 100.0 * k as f64 / n as f64 } else { 100.0 }
    );
    for row in r.rows.iter().filter(|x| x.changed > 0 && !x.killed) {
        s += &format!("survived: broken/{}/{} ({} cases answered differently)\n", row.slip, row.method, row.changed);
    }
    s
}
