//! `oracle-agree`: the exact oracle against Embree on random thin-lens cases.
//!
//! Every sample is judged twice: exactly ([`oracles::classify`]) and by Embree's f32
//! ray query. Boundary samples (an edge value or D exactly zero) may go either way in
//! Embree and are counted apart. Any other difference is a **disagreement**; the exact
//! verdict settles it. A disagreement is **unsettled** when the sample lies farther
//! from the nearest edge than the f32 band below, which an f32 ray test cannot explain:
//! that is a defect in one of the two oracles and fails the run.
//!
//! # The f32 band
//! Embree sees the vertices as stored (f32) but rounds the ray origin and direction to
//! f32 and intersects in f32 (watertight test, ROBUST scene). The direction
//! `(x F + a u, y F + a k v, F)` carries a relative error of 2^-24 per component, which
//! moves the ray's pixel position by about 2^-24 (|x| + |a u| / F) pixels; the
//! intersection adds a few ulps of the vertex coordinates, which is a pixel error
//! relative to the projected vertex magnitudes. The band allowed is
//! `BAND_REL * (1 + |x| + |y| + max_i |projected vertex i|)` pixels with
//! `BAND_REL = 2^-16`, a wide margin over those few-ulp effects. Far from the origin a
//! second-order term takes over: an edge test is a 2x2 determinant of coordinates of
//! size about M = |x| + |y| + max |projected vertex| (pixels, times w), so f32 leaves
//! it an absolute error of a few 2^-24 M^2, which is 2^-24 M^2 / L pixels across an edge
//! of L pixels; the band adds `2^-20 M^2 / L_min` (L_min the shortest projected edge,
//! when every w > 0). At 1e6 px from the origin that is tens of pixels for a small
//! triangle (the far-from-origin regime shows disagreements up to 53 px from an edge,
//! all settled by the exact oracle); 500 px from the origin it is 2.4e-2 px for a 10 px
//! edge.
//! Amplification by near-degenerate geometry (a ray grazing the triangle's plane) is
//! not modelled; the run reports `max_disagreement_distance` so the band can be judged
//! against data.

use crate::cases::generate::{physical_case, rng_for, samples_for, Regime};
use crate::model::Case;
use indicatif::{ProgressBar, ProgressStyle};
use oracles::embree::{EmbreeOracle, LensTri};
use oracles::{Coverage, Tri};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;

/// Relative size of the f32 band (see the module doc): 2^-16.
pub const BAND_REL: f64 = 1.0 / 65536.0;

/// Samples judged per case.
pub const SAMPLES_PER_CASE: usize = 2000;

/// Counts of one run (or one regime of it).
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct AgreeCounts {
    pub cases: u64,
    pub samples: u64,
    pub agree: u64,
    pub boundary: u64,
    pub disagree: u64,
    /// Disagreements where Embree said covered and the exact oracle did not.
    pub embree_over: u64,
    /// Disagreements where Embree said not covered and the exact oracle said interior.
    pub embree_under: u64,
    pub unsettled: u64,
    /// Largest distance (pixels) of a disagreeing sample to the nearest edge line.
    pub max_disagreement_distance: f64,
    /// Samples the exact oracle settled with big-integer arithmetic.
    pub exact_fallbacks: u64,
    /// Cases Embree refused (e.g. a coordinate out of its range); none expected.
    pub embree_refused: u64,
}

impl AgreeCounts {
    fn merge(mut self, o: &AgreeCounts) -> AgreeCounts {
        self.cases += o.cases;
        self.samples += o.samples;
        self.agree += o.agree;
        self.boundary += o.boundary;
        self.disagree += o.disagree;
        self.embree_over += o.embree_over;
        self.embree_under += o.embree_under;
        self.unsettled += o.unsettled;
        self.max_disagreement_distance = self.max_disagreement_distance.max(o.max_disagreement_distance);
        self.exact_fallbacks += o.exact_fallbacks;
        self.embree_refused += o.embree_refused;
        self
    }
}

/// A disagreement, kept for the report.
#[derive(Clone, Debug, Serialize)]
pub struct Disagreement {
    pub case_index: u64,
    pub regime: &'static str,
    pub sample: [f64; 5],
    pub exact: &'static str,
    pub embree: bool,
    pub distance_px: f64,
    pub band_px: f64,
}

/// The result of a run.
#[derive(Clone, Debug, Serialize)]
pub struct AgreeReport {
    pub seed: u64,
    #[serde(flatten)]
    pub total: AgreeCounts,
    pub by_regime: BTreeMap<&'static str, AgreeCounts>,
    /// The disagreements farthest from an edge (up to 20).
    pub worst: Vec<Disagreement>,
}

/// Distance (pixels) from the sample to the nearest edge line of the sheared triangle,
/// and the f32 band at the sample. f64 arithmetic: a report, not a verdict.
pub fn edge_distance_and_band(tri: &Tri, s: [f64; 5]) -> (f64, f64) {
    let [x, y, u, v, t] = s;
    let mut px = [0.0; 3];
    let mut py = [0.0; 3];
    let mut w = [0.0; 3];
    let mut mag: f64 = 0.0;
    let mut proj = [(0.0, 0.0); 3];
    for i in 0..3 {
        let l = |j: usize| (1.0 - t) * tri.q[i][j] + t * tri.r[i][j];
        let c = (1.0 - t) * tri.c0[i] + t * tri.c1[i];
        let xs = l(0) + u * c;
        let ys = l(1) + tri.k * v * c;
        w[i] = l(3);
        px[i] = xs - x * w[i];
        py[i] = ys - y * w[i];
        if w[i] != 0.0 {
            mag = mag.max((xs / w[i]).abs()).max((ys / w[i]).abs());
        }
        proj[i] = (xs / w[i], ys / w[i]);
    }
    let shortest = if w.iter().all(|&w| w > 0.0) {
        [(0, 1), (1, 2), (2, 0)]
            .iter()
            .map(|&(i, j): &(usize, usize)| (proj[i].0 - proj[j].0).hypot(proj[i].1 - proj[j].1))
            .fold(f64::INFINITY, f64::min)
    } else {
        f64::INFINITY
    };
    let mut dist = f64::INFINITY;
    for (i, j) in [(1, 2), (2, 0), (0, 1)] {
        let e = px[i] * py[j] - py[i] * px[j];
        let gx = -w[i] * py[j] + py[i] * w[j];
        let gy = -px[i] * w[j] + w[i] * px[j];
        let g = (gx * gx + gy * gy).sqrt();
        if g > 0.0 {
            dist = dist.min(e.abs() / g);
        }
    }
    let m = x.abs() + y.abs() + mag;
    let second = if shortest > 0.0 { 2f64.powi(-20) * m * m / shortest } else { 0.0 };
    let band = BAND_REL * (1.0 + m) + second;
    (dist, band)
}

/// The numbers the Embree oracle takes for a physical case (None without a lens).
pub fn lens_tri(case: &Case) -> Option<LensTri> {
    let l = case.lens?;
    let tri = &case.triangle;
    let f = |p: [f32; 4]| [p[0], p[1], p[3]];
    Some(LensTri { q: tri.q.map(f), r: tri.r.map(f), a: l.a() as f64, focus: l.focus as f64, k: tri.k as f64 })
}

fn run_case(seed: u64, index: u64, per_case: usize) -> (Regime, AgreeCounts, Vec<Disagreement>) {
    let regime = Regime::ALL[(index % Regime::ALL.len() as u64) as usize];
    let mut rng = rng_for(seed, index);
    let case = physical_case(&mut rng, regime);
    let mut c = AgreeCounts { cases: 1, ..Default::default() };
    let mut worst = Vec::new();
    let oracle = match EmbreeOracle::new(&lens_tri(&case).expect("physical case")) {
        Ok(o) => o,
        Err(_) => {
            c.embree_refused = 1;
            return (regime, c, worst);
        }
    };
    let tri = case.triangle.to_oracle();
    let samples = samples_for(&case, &mut rng, per_case);
    let mut hits = Vec::new();
    oracle.hits(&samples, &mut hits);
    let mut covs = Vec::new();
    c.exact_fallbacks += oracles::batch::classify_batch(&tri, &samples, &mut covs).exact_fallbacks;
    for ((s, &hit), &cov) in samples.iter().zip(&hits).zip(&covs) {
        c.samples += 1;
        match (cov, hit) {
            (Coverage::Boundary, _) => c.boundary += 1,
            (Coverage::Interior, true) | (Coverage::Outside, false) => c.agree += 1,
            (exact, embree) => {
                c.disagree += 1;
                if embree {
                    c.embree_over += 1
                } else {
                    c.embree_under += 1
                }
                let (d, band) = edge_distance_and_band(&tri, *s);
                c.max_disagreement_distance = c.max_disagreement_distance.max(d);
                if d > band {
                    c.unsettled += 1;
                }
                worst.push(Disagreement {
                    case_index: index,
                    regime: regime.name(),
                    sample: *s,
                    exact: if exact == Coverage::Interior { "interior" } else { "outside" },
                    embree,
                    distance_px: d,
                    band_px: band,
                });
            }
        }
    }
    (regime, c, worst)
}

/// Disagreements kept for the report.
const WORST_KEPT: usize = 20;

/// The running sums of a run: counts in all and per regime, and the disagreements
/// farthest from an edge. Cases are folded in as they are judged (nothing is held per
/// case, so a run of any length needs the same memory).
#[derive(Default)]
struct Acc {
    total: AgreeCounts,
    by_regime: BTreeMap<&'static str, AgreeCounts>,
    worst: Vec<Disagreement>,
}

impl Acc {
    /// Keep the `WORST_KEPT` farthest disagreements, ties by case index; the sort is
    /// stable, so equal ones keep the order of the cases (and of the samples in a case).
    fn keep_worst(&mut self) {
        self.worst.sort_by(|a, b| b.distance_px.total_cmp(&a.distance_px).then(a.case_index.cmp(&b.case_index)));
        self.worst.truncate(WORST_KEPT);
    }
    fn add(mut self, (regime, c, w): (Regime, AgreeCounts, Vec<Disagreement>)) -> Acc {
        self.total = std::mem::take(&mut self.total).merge(&c);
        let e = self.by_regime.entry(regime.name()).or_default();
        *e = std::mem::take(e).merge(&c);
        if !w.is_empty() {
            self.worst.extend(w);
            self.keep_worst();
        }
        self
    }
    /// `self` holds earlier cases than `o` (rayon's reduce keeps the order).
    fn merge(mut self, o: Acc) -> Acc {
        self.total = std::mem::take(&mut self.total).merge(&o.total);
        for (k, c) in o.by_regime {
            let e = self.by_regime.entry(k).or_default();
            *e = std::mem::take(e).merge(&c);
        }
        if !o.worst.is_empty() {
            self.worst.extend(o.worst);
            self.keep_worst();
        }
        self
    }
}

/// Judge `samples` samples (rounded up to whole cases) from `seed`. Identical results
/// at any thread count: each case draws from its own stream and the merge is in order.
/// The cases are folded into running sums as they are judged: memory does not grow
/// with `samples` (the command line bounds it, see `cullproof::cli::args::AGREE_MAX_SAMPLES`).
pub fn run(seed: u64, samples: u64, progress: bool) -> AgreeReport {
    let per = SAMPLES_PER_CASE as u64;
    let cases = samples.div_ceil(per).max(1);
    let pb = if progress { ProgressBar::new(cases) } else { ProgressBar::hidden() };
    pb.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} cases {elapsed_precise} eta {eta}").unwrap());
    let acc = (0..cases)
        .into_par_iter()
        .map(|i| {
            let r = run_case(seed, i, SAMPLES_PER_CASE);
            pb.inc(1);
            r
        })
        .fold(Acc::default, Acc::add)
        .reduce(Acc::default, Acc::merge);
    pb.finish_and_clear();
    let Acc { total, by_regime, mut worst } = acc;
    worst.truncate(WORST_KEPT);
    AgreeReport { seed, total, by_regime, worst }
}

/// The table a person reads.
pub fn render(r: &AgreeReport) -> String {
    let mut s = String::new();
    s += &format!("oracle-agree, seed {}: exact coverage vs Embree (f32), thin-lens cases\n\n", r.seed);
    s += &format!(
        "{:<15} {:>6} {:>10} {:>10} {:>9} {:>9} {:>8} {:>8} {:>10} {:>12}\n",
        "regime", "cases", "samples", "agree", "boundary", "disagree", "e>exact", "e<exact", "unsettled", "max dist px"
    );
    let row = |name: &str, c: &AgreeCounts| {
        format!(
            "{:<15} {:>6} {:>10} {:>10} {:>9} {:>9} {:>8} {:>8} {:>10} {:>12.3e}\n",
            name,
            c.cases,
            c.samples,
            c.agree,
            c.boundary,
            c.disagree,
            c.embree_over,
            c.embree_under,
            c.unsettled,
            c.max_disagreement_distance
        )
    };
    for (name, c) in &r.by_regime {
        s += &row(name, c);
    }
    s += &row("all", &r.total);
    s += &format!(
        "\nexact fallbacks: {} of {} samples ({:.2e}); Embree refused {} cases\n",
        r.total.exact_fallbacks,
        r.total.samples,
        r.total.exact_fallbacks as f64 / r.total.samples.max(1) as f64,
        r.total.embree_refused
    );
    s += if r.total.unsettled == 0 {
        "verdict: AGREE — every disagreement lies within the f32 band of an edge and the exact oracle settled it\n"
    } else {
        "verdict: UNSETTLED DISAGREEMENTS — a sample far from every edge was judged differently (see --json 'worst')\n"
    };
    s
}
