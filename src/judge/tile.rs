//! Judging one method's answer on one tile against the ground truth: three verdicts.
//!
//! - **Violated**: an interior sample (confirmed in exact arithmetic) inside the tile
//!   and the lens/shutter domain that the answer culls.
//! - **Proven**: every claim the answer makes was certified: each narrowed interval
//!   side by a search that ruled out every box beyond it (no gap left, not even one
//!   below the solver's resolution), a culled tile by a certificate that it holds no
//!   interior sample, and the per-sample constraints by a search that decided every box.
//! - **Unproven**: anything else, with the reasons ([`Unproven`]). A budget, a stall or
//!   the smallest box size never turns into a pass.

use super::side_cut;
use crate::bounds::{TileBounds, TileResult};
use crate::judge::constraints::ConstraintVerdict;
use crate::model::{Case, Sample, Tile};
use oracles::embree::EmbreeOracle;
use oracles::extents::ExtentsConfig;
use oracles::extents::{Extent, Occupancy, Side, TileSolver};
use oracles::{classify, Coverage, DepthCheck, Tri};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Why a claim was neither certified nor refuted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Unproven {
    /// A culled tile whose occupancy the solver could not settle within its budget.
    TileUnknown,
    /// An interval side whose search ended with boxes beyond the claim still open (its
    /// budget, its stall limit or the smallest box size), and (u, v, t) that its
    /// decision as a constraint with its exact cut ([`super::side_cut`]) left open too:
    /// a gap, however small.
    SideGap,
    /// A depth witness beyond the bound that the exact depth check did not confirm.
    DepthUnconfirmed,
    /// A per-sample constraint search that ran out of its budget.
    ConstraintBudget,
    /// A per-sample constraint search that left boxes at its smallest size.
    ConstraintResolution,
    /// Under a declared sample set: a violation whose witness is not a sample of the
    /// set, no sample of the set found near it, and too many set points in the tile to
    /// judge one by one ([`super::sample_set`]).
    OffSet,
}

impl Unproven {
    pub const ALL: [Unproven; 6] = [
        Unproven::TileUnknown,
        Unproven::SideGap,
        Unproven::DepthUnconfirmed,
        Unproven::ConstraintBudget,
        Unproven::ConstraintResolution,
        Unproven::OffSet,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Unproven::TileUnknown => "tile-unknown",
            Unproven::SideGap => "side-gap",
            Unproven::DepthUnconfirmed => "depth-unconfirmed",
            Unproven::ConstraintBudget => "constraint-budget",
            Unproven::ConstraintResolution => "constraint-resolution",
            Unproven::OffSet => "off-set",
        }
    }
    fn bit(self) -> u8 {
        1 << (self as u8)
    }
}

/// The verdict on one method and one case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Proven,
    Violated,
    Unproven,
    /// The case could not be judged under the declared samples: a vertex key that
    /// vertex snapping cannot snap exactly (behind the lens, or beyond the grid's
    /// exact range), or a case that cannot be placed in the viewport. Counted apart,
    /// never a failure and never a pass.
    NotJudged,
}

/// One method on one case (over every tile judged for it).
#[derive(Clone, Debug, Default)]
pub struct Judgement {
    /// The violation with the largest margin found.
    pub violation: Option<Witness>,
    /// Every kind of bound violated (see [`bound_kind`]) with its largest margin.
    pub violated: BTreeMap<String, f64>,
    /// Reasons some claim stayed unproven (a bit per [`Unproven`]).
    unproven: u8,
    /// Nothing was judged (see [`Verdict::NotJudged`]).
    pub not_judged: bool,
    /// Only boundary samples were culled (sampled; says nothing about the proof).
    pub boundary_only: bool,
    /// Some violation is witnessed by an f32 sample (one a hardware sample generator
    /// can produce), not only by points between f32 values.
    pub f32_witness: bool,
    /// Tiles placed at this method's own tile-reject limit that were judged, and how
    /// many of them showed a violation.
    pub limit_tiles: u32,
    pub limit_violations: u32,
    /// When the method's limit tiles were placed: how far its reject limit lies beyond
    /// the footprint's extreme, in tile sizes ([`crate::cases::limit_tiles::Limit::slack`]).
    pub limit_slack: Option<f64>,
    /// Per interval end kind ("u min", ..., "t max"), the ends of this case probed for
    /// tightness and those with a covered sample within [`TIGHT_DELTA`] inside them
    /// (or beyond: a violated end counts as tight). See `TileJudge::probe_tight`.
    pub tight: BTreeMap<String, (u32, u32)>,
    /// Per kind of bound violated, the witness with the largest margin of that kind;
    /// kept only under [`JudgeSettings::witnesses_per_kind`] (the search's signature
    /// gate, which writes a case file for a kind that is not the worst one).
    pub by_kind: BTreeMap<String, Witness>,
    keep_by_kind: bool,
}

/// An interval end counts as tight when a covered sample lies within this much of it on
/// the inside (lens coordinates span 2, the shutter 1): a quarter of the smallest
/// loosening the gate must notice at any settings (1e-3).
pub const TIGHT_DELTA: f64 = 2.5e-4;

/// Boxes the search for a covered sample next to an end may examine.
pub const TIGHT_BUDGET: usize = 200;

/// Boxes the decision of a side left with a gap may take ([`super::side_cut`]), per box
/// of `--side-budget`: it runs only where the extent search could not close the side.
pub const SIDE_CUT_BUDGET_FACTOR: usize = 1;

impl Judgement {
    /// The judgement of a case that could not be judged ([`Verdict::NotJudged`]).
    pub fn not_judged() -> Self {
        Judgement { not_judged: true, ..Judgement::default() }
    }
    pub fn verdict(&self) -> Verdict {
        if self.not_judged {
            Verdict::NotJudged
        } else if self.violation.is_some() {
            Verdict::Violated
        } else if self.unproven != 0 {
            Verdict::Unproven
        } else {
            Verdict::Proven
        }
    }
    /// The reasons some claim stayed unproven (possibly also when a violation was found).
    pub fn unproven(&self) -> Vec<Unproven> {
        Unproven::ALL.into_iter().filter(|r| self.unproven & r.bit() != 0).collect()
    }
    /// Count one probed interval end of kind `name`, tight or not ([`Judgement::tight`]).
    fn tally_end(&mut self, name: &str, tight: bool) {
        let e = self.tight.entry(name.to_string()).or_insert((0, 0));
        (e.0, e.1) = (e.0 + 1, e.1 + tight as u32);
    }
    pub fn add_unproven(&mut self, r: Unproven) {
        self.unproven |= r.bit();
    }
    /// The witness of one kind of bound: the kind's own (under
    /// [`JudgeSettings::witnesses_per_kind`]), else the worst one.
    pub fn witness_of(&self, kind: &str) -> Option<&Witness> {
        self.by_kind.get(kind).or(self.violation.as_ref())
    }
    fn consider(&mut self, w: Witness) {
        let kind = bound_kind(&w.bound);
        let m = self.violated.entry(kind.clone()).or_insert(0.0);
        *m = m.max(w.margin);
        if self.keep_by_kind && self.by_kind.get(&kind).is_none_or(|v| w.margin > v.margin) {
            self.by_kind.insert(kind, w.clone());
        }
        if self.violation.as_ref().is_none_or(|v| w.margin > v.margin) {
            self.violation = Some(w);
        }
    }
    /// Fold in the judgement of another tile of the same case.
    pub fn merge(&mut self, o: Judgement) {
        self.not_judged |= o.not_judged;
        for (k, m) in o.violated {
            let e = self.violated.entry(k).or_insert(0.0);
            *e = e.max(m);
        }
        for (k, w) in o.by_kind {
            if self.by_kind.get(&k).is_none_or(|v| w.margin > v.margin) {
                self.by_kind.insert(k, w);
            }
        }
        if let Some(w) = o.violation {
            if self.violation.as_ref().is_none_or(|v| w.margin > v.margin) {
                self.violation = Some(w);
            }
        }
        self.unproven |= o.unproven;
        self.boundary_only |= o.boundary_only;
        self.f32_witness |= o.f32_witness;
        self.limit_tiles += o.limit_tiles;
        self.limit_violations += o.limit_violations;
        self.limit_slack = self.limit_slack.or(o.limit_slack);
        for (k, (n, t)) in o.tight {
            let e = self.tight.entry(k).or_insert((0, 0));
            (e.0, e.1) = (e.0 + n, e.1 + t);
        }
        if self.violation.is_some() {
            self.boundary_only = false;
        }
    }
}

/// The kind of a violated bound, as expectations name it: the bound's label up to a
/// `:` (what follows is the instance, e.g. a line's coefficients), with every word that
/// is a number replaced by `#` ("edge 1 hyperplane" and "edge 2 hyperplane" are one
/// kind).
pub fn bound_kind(label: &str) -> String {
    let head = label.split(':').next().unwrap_or(label);
    head.split_whitespace().map(|w| if w.parse::<f64>().is_ok() { "#" } else { w }).collect::<Vec<_>>().join(" ")
}

/// True when the point lies in the tile and in the lens/shutter domain
/// `[-1, 1]^2 x [0, 1]`: the only places a witness may be.
pub fn in_domain(tile: &Tile, p: [f64; 5]) -> bool {
    (tile.x0 as f64) <= p[0]
        && p[0] <= tile.x1 as f64
        && (tile.y0 as f64) <= p[1]
        && p[1] <= tile.y1 as f64
        && (-1.0..=1.0).contains(&p[2])
        && (-1.0..=1.0).contains(&p[3])
        && (0.0..=1.0).contains(&p[4])
}

pub(crate) fn f32_sample(p: [f64; 5]) -> Sample {
    Sample::new(p[0] as f32, p[1] as f32, p[2] as f32, p[3] as f32, p[4] as f32)
}

/// f32 samples around a point found beyond a bound on coordinate `axis` (0..5; 5 for a
/// depth bound, which no coordinate carries): on that axis the f32 values just beyond
/// the bound up to the point's own rounding, on the others the nearest f32 and its two
/// neighbours; only those in the tile and the domain. The exact oracle then says
/// whether one of them is a hardware-reachable witness.
fn f32_candidates(p: [f64; 5], axis: usize, bound: f32, is_max: bool, tile: &Tile) -> Vec<Sample> {
    let near = |x: f64| {
        let r = x as f32;
        [r, r.next_down(), r.next_up()]
    };
    let mut choices: Vec<Vec<f32>> = p.iter().map(|&x| near(x).to_vec()).collect();
    if axis < 5 {
        let (a, b) = if is_max { (bound.next_up(), p[axis] as f32) } else { (p[axis] as f32, bound.next_down()) };
        let mut v: Vec<f32> = vec![a, b, p[axis] as f32];
        v.retain(|&x| if is_max { x > bound } else { x < bound });
        v.sort_by(f32::total_cmp);
        v.dedup();
        choices[axis] = v;
    } else {
        // depth: keep (u, v, t) at their nearest f32 values
        for c in choices.iter_mut().skip(2) {
            c.truncate(1);
        }
    }
    let mut out = Vec::new();
    for &x in &choices[0] {
        for &y in &choices[1] {
            for &u in &choices[2] {
                for &v in &choices[3] {
                    for &t in &choices[4] {
                        let s = Sample::new(x, y, u, v, t);
                        if in_domain(tile, s.to_oracle()) {
                            out.push(s);
                        }
                    }
                }
            }
        }
    }
    out
}

/// Which of the method's answers culls the point, and by how much: an interval it lies
/// outside (distance in f64; a NaN end culls everything, margin infinite) or the
/// constraint with the most negative value (evaluated only when the point is an f32
/// sample, as hardware would see it). None when the intervals and constraints admit it
/// (depth aside).
pub fn culled_by(b: &TileBounds, p: [f64; 5]) -> Option<(String, f64)> {
    let mut worst: Option<(String, f64)> = None;
    let mut note = |name: String, d: f64| {
        if d > 0.0 && worst.as_ref().is_none_or(|w| d > w.1) {
            worst = Some((name, d));
        }
    };
    for (name, r, k) in [("u", b.u, 2), ("v", b.v, 3), ("t", b.t, 4)] {
        let nan = |x: f32| if x.is_nan() { f64::INFINITY } else { 0.0 };
        note(format!("{name} min"), (r[0] as f64 - p[k]).max(nan(r[0])));
        note(format!("{name} max"), (p[k] - r[1] as f64).max(nan(r[1])));
    }
    let s = f32_sample(p);
    if s.to_oracle() == p {
        for c in &b.constraints {
            note(c.name(), -(c.eval(&s) as f64));
        }
    }
    worst
}

/// A violation, with what is needed to replay it.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Witness {
    pub case_index: u64,
    pub case: Case,
    pub tile: Tile,
    /// The interior sample the method culls (exactly confirmed; in the tile and the
    /// lens/shutter domain).
    pub sample: [f64; 5],
    /// Which bound culls it: "tile culled", "u min", "t max", "z min", or a constraint's name.
    pub bound: String,
    /// Padding of that bound that would admit the witness ("inf" in JSON when a
    /// covered tile was culled).
    #[serde(with = "crate::io::num_or_inf")]
    pub margin: f64,
    /// Embree's verdict on the witness ray (None: not a physical case).
    pub embree_hit: Option<bool>,
}

/// What the judge may spend on one tile, and what it keeps.
#[derive(Clone, Debug)]
pub struct JudgeSettings {
    /// The solver's settings for occupancy and whole extents.
    pub extents: ExtentsConfig,
    /// How close to a claimed bound a side search may stop refining. 0 (the default)
    /// refines until every box beyond the bound is decided, which a proof needs: a box
    /// dropped within the band would leave a gap.
    pub band: f64,
    /// Boxes per interval side.
    pub side_budget: usize,
    /// An interval side gives up after this many boxes in a row that did not raise its
    /// certified bound while no witness lies beyond the claim (0: only the budget
    /// stops it). Such a side is tight to a rounding; giving up leaves it unproven.
    pub side_stall: usize,
    /// Boxes per constraint search.
    pub constraint_budget: usize,
    /// Constraint-search boxes narrower than this in every coordinate are not split.
    pub constraint_min_width: f64,
    /// Keep, per kind of bound violated, that kind's own worst witness in each
    /// judgement ([`Judgement::by_kind`]; off for `check`, which holds every
    /// judgement until the report).
    pub witnesses_per_kind: bool,
}

/// What the judge needs of one case and tile: the triangle, the solver over the tile,
/// Embree (physical cases) and the uniform samples of the tile.
pub(crate) struct TileJudge<'a> {
    pub cfg: &'a JudgeSettings,
    pub case: Case,
    pub tile: Tile,
    pub index: u64,
    pub tri: &'a Tri,
    pub solver: TileSolver<'a>,
    pub embree: Option<&'a EmbreeOracle>,
    pub uniform: &'a [Sample],
}

impl<'a> TileJudge<'a> {
    pub fn new(
        cfg: &'a JudgeSettings,
        case: Case,
        tile: Tile,
        index: u64,
        tri: &'a Tri,
        embree: Option<&'a EmbreeOracle>,
        uniform: &'a [Sample],
    ) -> Self {
        let tb = [tile.x0 as f64, tile.x1 as f64, tile.y0 as f64, tile.y1 as f64];
        let solver = TileSolver::new(tri, tb, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg.extents);
        TileJudge { cfg, case, tile, index, tri, solver, embree, uniform }
    }

    fn witness(&self, sample: [f64; 5], bound: String, margin: f64) -> Witness {
        Witness {
            case_index: self.index,
            case: self.case,
            tile: self.tile,
            sample,
            bound,
            margin,
            embree_hit: self.embree.map(|o| o.hit(sample)),
        }
    }

    /// A claim that culls every sample of the tile (an empty tile answer, or a NaN
    /// interval end): violated when the tile holds an interior sample, proven when it
    /// is certified empty.
    fn culls_everything(&mut self, j: &mut Judgement, label: &str) {
        match self.solver.occupancy() {
            Occupancy::Covered(w) if !in_domain(&self.tile, w) => j.add_unproven(Unproven::TileUnknown),
            Occupancy::Covered(w) => {
                let s = f32_sample(w);
                j.f32_witness |=
                    in_domain(&self.tile, s.to_oracle()) && classify(self.tri, s.to_oracle()) == Coverage::Interior;
                j.consider(self.witness(w, label.into(), f64::INFINITY))
            }
            Occupancy::Unknown => j.add_unproven(Unproven::TileUnknown),
            Occupancy::Empty => {}
        }
    }

    /// How tight a proven end is: is a covered sample within [`TIGHT_DELTA`] of it, on
    /// its inside (in the tile and the domain)? Recorded per end kind in
    /// [`Judgement::tight`]; a loosened answer leaves no covered sample that close, so
    /// the share of tight ends drops at any seed and case count (the expectations
    /// hold the least share each method shows). Ends of coordinates the triangle does
    /// not have are not probed.
    fn probe_tight(&mut self, j: &mut Judgement, ext: Extent, bound: f64, name: &str) {
        let Some(index) = ext.sample_coord() else { return };
        if (index == 4 && self.tri.is_static()) || (index < 4 && self.tri.is_pinhole()) {
            return;
        }
        let w = self.solver.witness_near(ext, bound, TIGHT_DELTA, TIGHT_BUDGET);
        let tight = w.is_some_and(|w| in_domain(&self.tile, w));
        j.tally_end(name, tight);
    }

    /// A u, v or t side whose extent search left a gap, decided by the constraint
    /// search with the side's exact cut ([`super::side_cut`]).
    fn decide_side(&self, coord: usize, bound: f32, is_max: bool) -> ConstraintVerdict {
        let claim = side_cut::SideClaim { coord, bound, is_max };
        let budget = SIDE_CUT_BUDGET_FACTOR * self.cfg.side_budget;
        side_cut::decide(self.tri, &self.tile, claim, budget, self.cfg.constraint_min_width)
    }

    /// Judge one tile answer.
    pub fn judge(&mut self, answer: &TileResult) -> Judgement {
        let mut j = Judgement { keep_by_kind: self.cfg.witnesses_per_kind, ..Judgement::default() };
        match answer {
            TileResult::Empty => self.culls_everything(&mut j, "tile culled"),
            TileResult::Bounds(b) => self.judge_bounds(&mut j, b),
        }
        if j.violation.is_some() {
            j.boundary_only = false;
        }
        j
    }

    fn judge_bounds(&mut self, j: &mut Judgement, b: &TileBounds) {
        let cfg = self.cfg;
        let tile = self.tile;
        let nan_end = [b.u, b.v, b.t].iter().flatten().chain(b.z.iter().flatten()).any(|x| x.is_nan());
        if nan_end {
            // Hardware's `lo <= s && s <= hi` is false for a NaN end: nothing passes.
            self.culls_everything(j, "NaN interval end");
            return;
        }
        // Interval sides, certified.
        let sides = [
            (b.u, [Extent::UMin, Extent::UMax], -1.0f32, 1.0f32, "u"),
            (b.v, [Extent::VMin, Extent::VMax], -1.0, 1.0, "v"),
            (b.t, [Extent::TMin, Extent::TMax], 0.0, 1.0, "t"),
        ];
        let mut checks: Vec<(Extent, f64, bool, String)> = Vec::new();
        for (r, ext, lo, hi, name) in sides {
            if r[0] > lo {
                checks.push((ext[0], r[0] as f64, false, format!("{name} min")));
            }
            if r[1] < hi {
                checks.push((ext[1], r[1] as f64, true, format!("{name} max")));
            }
        }
        if let Some(z) = b.z {
            checks.push((Extent::ZMin, z[0] as f64, false, "z min".into()));
            checks.push((Extent::ZMax, z[1] as f64, true, "z max".into()));
        }
        let mut found: Vec<Sample> = Vec::new();
        let stall = (cfg.side_stall > 0).then_some(cfg.side_stall);
        for (ext, bound, is_max, name) in checks {
            let coord = ext.sample_coord();
            // A depth end that every vertex respects at both ends of the shutter holds
            // for every interior sample (the depth is a positive combination of the
            // vertices' terms): decided exactly without a search.
            if coord.is_none() && oracles::coverage::depth_bound_holds(self.tri, bound, !is_max) {
                continue;
            }
            match self.solver.side(ext, bound, cfg.band, cfg.side_budget, stall) {
                Side::Beyond { witness: w, value, .. } => {
                    // A depth witness is re-judged exactly against the bound.
                    let want = if is_max { DepthCheck::Above } else { DepthCheck::Below };
                    let (z0, z1) = b.z.map(|z| (z[0] as f64, z[1] as f64)).unwrap_or((f64::MIN, f64::MAX));
                    let confirmed = coord.is_some() || oracles::classify_depth(self.tri, w, z0, z1) == want;
                    // The solver searches only the tile and the domain; a witness
                    // elsewhere would prove nothing about this answer.
                    if !in_domain(&tile, w) {
                        j.add_unproven(Unproven::SideGap);
                        continue;
                    }
                    if !confirmed {
                        j.add_unproven(Unproven::DepthUnconfirmed);
                        continue;
                    }
                    if coord.is_some() {
                        j.tally_end(&name, true);
                    }
                    j.consider(self.witness(w, name, (value - bound).abs()));
                    let axis = coord.unwrap_or(5);
                    let cands = f32_candidates(w, axis, bound as f32, is_max, &tile);
                    if coord.is_some() {
                        found.extend(cands);
                    } else {
                        j.f32_witness |=
                            cands.iter().any(|s| oracles::classify_depth(self.tri, s.to_oracle(), z0, z1) == want);
                    }
                }
                // Proven only when nothing beyond the claim is left open.
                Side::Within { gap, .. } => {
                    if gap > 0.0 {
                        // A gap: a claim within a rounding of the extent. Decide it as a
                        // constraint with its exact linear cut (u, v and t sides).
                        // A depth end: moving planes through the vertices, over the tile.
                        // Then the same planes certified against the covered samples only,
                        // with the edge values' multipliers ([`super::depth_cut`]).
                        let t = [tile.x0 as f64, tile.x1 as f64, tile.y0 as f64, tile.y1 as f64];
                        let verdict = match coord {
                            Some(c) => self.decide_side(c, bound as f32, is_max),
                            None if oracles::extents::depth_end_by_planes(
                                self.tri,
                                t,
                                bound,
                                !is_max,
                                cfg.side_budget,
                            ) =>
                            {
                                continue
                            }
                            None => super::depth_cut::decide(
                                self.tri,
                                &tile,
                                bound,
                                !is_max,
                                SIDE_CUT_BUDGET_FACTOR * cfg.side_budget,
                                cfg.constraint_min_width,
                            ),
                        };
                        match (verdict, coord) {
                            (ConstraintVerdict::Proved, Some(_)) => self.probe_tight(j, ext, bound, &name),
                            (ConstraintVerdict::Proved, None) => {}
                            (ConstraintVerdict::Violation(_) | ConstraintVerdict::ViolationAt(_), _) => {
                                // An f32 sample, or (a depth end) a real point finer than
                                // the f32 samples around it; both confirmed exactly.
                                let (w, sample) = match verdict {
                                    ConstraintVerdict::Violation(s) => (s.to_oracle(), Some(s)),
                                    ConstraintVerdict::ViolationAt(p) => (p, None),
                                    _ => unreachable!(),
                                };
                                if !in_domain(&tile, w) {
                                    j.add_unproven(Unproven::SideGap);
                                    continue;
                                }
                                // The margin: how far the sample lies beyond the end (for
                                // a depth, from its exact hit depth).
                                let margin = match coord {
                                    Some(c) => (w[c] - bound).abs(),
                                    None => {
                                        oracles::coverage::depth_distance(self.tri, w, bound).unwrap_or(f64::INFINITY)
                                    }
                                };
                                if coord.is_some() {
                                    j.tally_end(&name, true);
                                }
                                j.consider(self.witness(w, name, margin));
                                match (coord, sample) {
                                    (Some(_), Some(s)) => found.push(s),
                                    (Some(_), None) => {}
                                    (None, Some(_)) => j.f32_witness = true,
                                    (None, None) => {
                                        let (z0, z1) =
                                            if is_max { (f64::NEG_INFINITY, bound) } else { (bound, f64::INFINITY) };
                                        let want = if is_max { DepthCheck::Above } else { DepthCheck::Below };
                                        j.f32_witness |= f32_candidates(w, 5, bound as f32, is_max, &tile)
                                            .iter()
                                            .any(|s| oracles::classify_depth(self.tri, s.to_oracle(), z0, z1) == want);
                                    }
                                }
                            }
                            _ => j.add_unproven(Unproven::SideGap),
                        }
                    } else if coord.is_some() {
                        self.probe_tight(j, ext, bound, &name);
                    }
                }
            }
        }
        // Per-sample constraints: the certified search, then the sampled cross-check
        // (uniform samples and the witnesses found).
        if !b.constraints.is_empty() {
            match crate::judge::constraints::search(self.tri, &tile, b, cfg.constraint_budget, cfg.constraint_min_width)
                .verdict
            {
                ConstraintVerdict::Violation(s) => found.push(s),
                // Not given by a per-sample search (no claim about real points).
                ConstraintVerdict::ViolationAt(_) => j.add_unproven(Unproven::ConstraintBudget),
                ConstraintVerdict::Undecided => j.add_unproven(Unproven::ConstraintBudget),
                ConstraintVerdict::WithinResolution => j.add_unproven(Unproven::ConstraintResolution),
                ConstraintVerdict::Proved => {}
            }
        }
        if !b.constraints.is_empty() || !found.is_empty() {
            for s in self.uniform.iter().chain(&found) {
                if b.admits(s) || !in_domain(&tile, s.to_oracle()) {
                    continue;
                }
                match classify(self.tri, s.to_oracle()) {
                    Coverage::Interior => {
                        j.f32_witness = true;
                        let (name, deficit) = culled_by(b, s.to_oracle()).expect("not admitted");
                        j.consider(self.witness(s.to_oracle(), name, deficit));
                    }
                    Coverage::Boundary => j.boundary_only = true,
                    Coverage::Outside => {}
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bound_kinds_drop_instances() {
        assert_eq!(bound_kind("edge 2 hyperplane"), "edge # hyperplane");
        assert_eq!(bound_kind("wu2013 x upper line: t <= -0.5 u + 0.25"), "wu2013 x upper line");
        assert_eq!(bound_kind("u min"), "u min");
    }

    #[test]
    fn the_domain_is_closed_and_bounded() {
        let t = Tile::square(2.0, 3.0, 1.0);
        assert!(in_domain(&t, [2.0, 4.0, -1.0, 1.0, 0.0]));
        assert!(in_domain(&t, [3.0, 3.0, 1.0, -1.0, 1.0]));
        for k in 2..5 {
            let mut p = [2.5, 3.5, 0.0, 0.0, 0.5];
            p[k] = 1.0 + f32::EPSILON as f64;
            assert!(!in_domain(&t, p), "{p:?}");
            p[k] = if k == 4 { -1e-30 } else { -1.0 - 1e-12 };
            assert!(!in_domain(&t, p), "{p:?}");
        }
        assert!(!in_domain(&t, [1.9999999, 3.5, 0.0, 0.0, 0.5]));
    }

    #[test]
    fn f32_candidates_stay_in_the_domain() {
        let t = Tile::square(0.0, 0.0, 1.0);
        // A point at the lens corner, beyond a u max of 0.5: neighbours past u = 1 or
        // v = -1 or t = 1 would be outside the domain.
        let c = f32_candidates([0.5, 0.5, 1.0, -1.0, 1.0], 2, 0.5, true, &t);
        assert!(!c.is_empty());
        assert!(c.iter().all(|s| in_domain(&t, s.to_oracle())), "{c:?}");
        assert!(c.iter().all(|s| s.u > 0.5));
    }

    #[test]
    fn verdicts_follow_violation_then_unproven() {
        let mut j = Judgement::default();
        assert_eq!(j.verdict(), Verdict::Proven);
        j.add_unproven(Unproven::SideGap);
        assert_eq!(j.verdict(), Verdict::Unproven);
        assert_eq!(j.unproven(), vec![Unproven::SideGap]);
        let mut k = Judgement::default();
        k.violated.insert("u min".into(), 1e-3);
        k.violation = Some(Witness {
            case_index: 0,
            case: crate::model::Case {
                triangle: crate::model::Triangle::fixed([
                    [0.0, 0.0, 0.5, 1.0],
                    [1.0, 0.0, 0.5, 1.0],
                    [0.0, 1.0, 0.5, 1.0],
                ]),
                lens: None,
            },
            tile: Tile::square(0.0, 0.0, 1.0),
            sample: [0.1, 0.1, 0.0, 0.0, 0.5],
            bound: "u min".into(),
            margin: 1e-3,
            embree_hit: None,
        });
        j.merge(k);
        assert_eq!(j.verdict(), Verdict::Violated);
        assert_eq!(j.violated["u min"], 1e-3);
    }
}
