//! The branch-and-bound search for one extent over a box of samples, on the engine of
//! [`super::bnb`].

use super::bnb::{self, Flow, Frontier, Open, Problem, Ties};
use super::elimination::{corner_points, depth_estimate};
use super::enclosure::{
    box_values_eliminating, box_values_for_depth, box_values_with, classify_values, Box5, BoxClass, BoxValues,
};
use super::objective::{candidate_points, key_of, push_towards_bound, value_at, Extent, Objective, Push};
use crate::coverage::{classify, Coverage};
use crate::interval::Interval;
use crate::tri::Tri;

/// Settings of the solver.
#[derive(Clone, Copy, Debug)]
pub struct ExtentsConfig {
    /// Stop when the enclosure of an extreme is this narrow (u, v, t and depth).
    pub resolution: f64,
    /// Boxes one objective may pop before it gives up (the rest are reported undecided).
    pub max_boxes: usize,
    /// A box narrower than this fraction of the initial box in every searched
    /// dimension is not split further.
    pub min_fraction: f64,
    /// When a side or occupancy search on the enclosures alone leaves a gap, search
    /// again with (x, y) eliminated per (u, v, t) box (the module `elimination`); both
    /// are certified, so the better stands. It decides more cases (behind the lens
    /// above all) at the price of more boxes. Objective searches always eliminate.
    pub second_chance: bool,
    /// The occupancy search ("is anything covered?") eliminates (x, y) from the start,
    /// as the objective searches do. Otherwise it runs on the enclosures alone and
    /// eliminates only as a second chance: where a vertex or an edge grazes the tile
    /// at the end of a lens or time range, the enclosures alone spend the whole budget
    /// without a witness. The gate keeps it off, so its rows stay comparable with the
    /// recorded ones.
    pub occupancy_eliminates: bool,
}

impl Default for ExtentsConfig {
    fn default() -> Self {
        ExtentsConfig {
            resolution: 1e-4,
            max_boxes: 20_000,
            min_fraction: 1e-7,
            second_chance: false,
            occupancy_eliminates: true,
        }
    }
}

/// A certified enclosure `[lo, hi]` of an infimum or supremum, with its witness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extreme {
    pub lo: f64,
    pub hi: f64,
    /// An interior sample (confirmed exactly) at the witnessed end of the enclosure.
    pub witness: [f64; 5],
}

/// The result of one objective.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectiveResult {
    /// None when no interior sample was found.
    pub extreme: Option<Extreme>,
    /// Boxes left undecided (at minimum size or over budget).
    pub undecided: u64,
    /// Boxes examined.
    pub boxes: u64,
    /// The most extreme value no box rules out (the lowest for a minimum, the highest
    /// for a maximum; +inf / -inf when every box was decided): no interior sample
    /// goes beyond it except the witness's side of the enclosure.
    pub open: f64,
}

impl ObjectiveResult {
    /// The answer for a certified empty set.
    pub fn nothing(max: bool) -> Self {
        ObjectiveResult {
            extreme: None,
            undecided: 0,
            boxes: 0,
            open: if max { f64::NEG_INFINITY } else { f64::INFINITY },
        }
    }
}

/// The dimensions that matter for this triangle.
pub(super) fn active_dims(tri: &Tri) -> [bool; 5] {
    let lens = !tri.is_pinhole();
    let time = !tri.is_static();
    [true, true, lens, lens, time]
}

/// Run one extent over the initial box.
pub fn solve_objective(tri: &Tri, init: Box5, ext: Extent, cfg: &ExtentsConfig) -> ObjectiveResult {
    search(tri, init, ext, cfg, Search { eliminate: true, ..Search::default() })
}

/// What a search may skip.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Search {
    /// Only values of the objective beyond this bound matter (below it for a minimum,
    /// above it for a maximum): a box whose objective enclosure lies on the bound's
    /// side, or within the resolution of it, is tried for witnesses and then dropped
    /// rather than refined. With a witness found, the result encloses the extreme;
    /// without one and nothing undecided, no interior sample lies beyond
    /// `bound -/+ resolution`. With a witness beyond the bound, the extreme is refined
    /// only until the margin (its distance from the bound) is known to 1 %.
    pub bound: Option<f64>,
    /// Stop at the first interior sample (for "is anything covered?").
    pub first_witness: bool,
    /// With a witness beyond `bound`, at most this many more boxes refine the margin
    /// (None: until it is known to 1 %). The result still encloses the extreme: its
    /// witness is the farthest found, its other end what the open boxes allow.
    pub refine_boxes: Option<usize>,
    /// With a bound and no witness beyond it yet, give up after this many boxes in a
    /// row that did not raise the certified lower bound (the smallest key still open),
    /// as if the budget had run out: the result is the enclosure reached so far. Next
    /// to a bound that is tight to a rounding, most of a budget goes to boxes that can
    /// neither be ruled out nor hold a witness; this spends it on more cases instead.
    pub stall: Option<usize>,
    /// Decide (x, y) by elimination ([`super::box_values_eliminating`]: the covered
    /// pixels at a fixed (u, v, t) are a convex polygon) and split only (u, v, t) for a
    /// coordinate extent; propose witnesses at the (u, v, t) corners of a box too. Otherwise the boxes are judged by the enclosures alone and (x, y)
    /// is split like the rest behind the lens.
    pub eliminate: bool,
}

/// The share of the largest smear the objective's own coordinate is given when splitting
/// with elimination (without it: one half).
const OBJ_SHARE: f64 = 0.02;

/// True while some active lens or time coordinate of the box can still be split.
fn uvt_open(b: &Box5, init: &Box5, min_w: &[f64; 5], active: &[bool; 5]) -> bool {
    (2..5).any(|i| active[i] && init[i].width() > 0.0 && b[i].width() > min_w[i])
}

/// A box of the search with its enclosures.
struct Cell {
    b: Box5,
    bv: BoxValues,
}

/// The state of one extent search (see the module documentation of [`super`]).
struct ExtentSearch<'a> {
    tri: &'a Tri,
    obj: Objective,
    cfg: &'a ExtentsConfig,
    opts: Search,
    init: Box5,
    active: [bool; 5],
    min_w: [f64; 5],
    with_depth: bool,
    /// +1 for a minimum, -1 for a maximum: keys are the objective in the minimised
    /// orientation.
    sg: f64,
    /// Boxes with keys at or above this are only tried for witnesses.
    drop_at: f64,
    /// Key of the best witness (minimised orientation) and the witness itself.
    best: Option<(f64, [f64; 5])>,
    boxes: u64,
    /// Smallest key among boxes left undecided.
    stuck_lo: f64,
    /// Keys of boxes left undecided (at minimum size or over budget).
    stuck: Vec<f64>,
    dropped_lo: f64,
    final_lo: f64,
    /// Boxes examined when a witness first lay beyond the bound.
    beyond_at: Option<u64>,
    last_lower: f64,
    moved_at: u64,
}

impl ExtentSearch<'_> {
    /// Could a witness in a box of this key still improve on the best by more than the
    /// resolution?
    fn wanted(&self, key: f64) -> bool {
        self.best.is_none_or(|(w, _)| w - key > self.cfg.resolution)
    }

    /// Judge the points exactly and keep the best interior one (pushed towards the
    /// box's bound), until one is within the resolution of the box's key; true when
    /// some point was interior.
    ///
    /// Only with elimination ([`Search::eliminate`]) does it skip points: those after a
    /// witness within the resolution, and depth proposals whose plain-f64 depth does not
    /// improve on the best; and only then is a witness pushed along the covered
    /// polygon, to a sixteenth of the resolution. Without it, it judges every point and
    /// pushes at a fixed (x, y) as far as f64 goes, as the side searches of the gate
    /// always have (their answers stay the same bits).
    fn try_witnesses(&mut self, pts: Vec<[f64; 5]>, b: &Box5, key: f64) -> bool {
        let (tri, obj, eliminate) = (self.tri, self.obj, self.opts.eliminate);
        let mut found = false;
        for p in pts {
            if eliminate && !self.wanted(key) {
                break;
            }
            if let (true, Objective::Depth { .. }, Some((w, _)), Some(z)) =
                (eliminate, obj, self.best, depth_estimate(tri, p))
            {
                // (plain f64: only to skip a point that would not improve the best)
                if self.sg * z >= w {
                    continue;
                }
            }
            if classify(tri, p) == Coverage::Interior {
                found = true;
                let push =
                    if eliminate { Push::AlongPolygon { tol: self.cfg.resolution / 16.0 } } else { Push::FixedXy };
                let p = push_towards_bound(tri, obj, p, b, push);
                let val = value_at(tri, obj, p);
                let k = if self.sg > 0.0 { val.hi } else { -val.lo };
                if self.best.is_none_or(|(w, _)| k < w) {
                    self.best = Some((k, p));
                }
            }
        }
        found
    }
}

impl Problem for ExtentSearch<'_> {
    type Node = Cell;

    fn visit(&mut self, open: Open<Cell>, frontier: &mut Frontier<Cell>) -> Flow {
        let Open { key, depth, node: Cell { b, bv } } = open;
        let (cfg, opts, obj, sg) = (self.cfg, self.opts, self.obj, self.sg);
        let lower = key.min(self.stuck_lo);
        if let Some((w, _)) = self.best {
            // Beyond a claimed bound, the margin (bound - extreme) is wanted to 1 %,
            // not to the band that finds it, and with at most `refine_boxes` more boxes.
            let enough = match opts.bound {
                Some(bd) => cfg.resolution.max(0.01 * (sg * bd - w)),
                None => cfg.resolution,
            };
            if let Some(bd) = opts.bound {
                if w < sg * bd && self.beyond_at.is_none() {
                    self.beyond_at = Some(self.boxes);
                }
            }
            let refined_enough =
                matches!((self.beyond_at, opts.refine_boxes), (Some(b0), Some(r)) if self.boxes - b0 >= r as u64);
            if w - lower <= enough || refined_enough {
                self.final_lo = lower;
                return Flow::Stop;
            }
        }
        self.boxes += 1;
        if lower > self.last_lower {
            self.last_lower = lower;
            self.moved_at = self.boxes;
        }
        // A search for a witness beyond a bound that has stopped raising its certified
        // lower bound gives up like one out of budget (see `Search::stall`).
        let stagnant = matches!((opts.bound, self.beyond_at, opts.stall), (Some(_), None, Some(k)) if self.boxes - self.moved_at > k as u64);
        if self.boxes as usize > cfg.max_boxes || stagnant {
            self.stuck.push(key);
            self.stuck.extend(frontier.drain_keys());
            self.final_lo = lower;
            return Flow::Stop;
        }
        let class = classify_values(&bv);
        if class == BoxClass::Empty {
            return Flow::Continue;
        }
        let tri = self.tri;
        if class == BoxClass::Full && matches!(obj, Objective::Depth { .. }) && self.wanted(key) {
            // Every sample of a full box is interior, and at a fixed time the depth is
            // monotone in each of x, y, u, v there (its numerator affine in each, D in
            // u and v, D of one sign): its least and greatest values over the box are at
            // the corners, at some time. The corners at the box's three times come
            // within the box's time variation of the key.
            self.try_witnesses(full_box_corners(&b), &b, key);
        }
        // Witnesses, while one could still improve on the best.
        if self.wanted(key) {
            let found = self.try_witnesses(candidate_points(tri, obj, &b, opts.eliminate), &b, key);
            if !found && opts.eliminate && self.wanted(key) {
                // Nothing interior at the box's middle (u, v, t): its corners, each at
                // its covered polygon (near an extreme the covered set is a thin wedge
                // whose apex the box's centre keeps missing, while a corner on its open
                // side lies in it).
                self.try_witnesses(corner_points(tri, &b), &b, key);
            }
        }
        if opts.first_witness && self.best.is_some() {
            self.final_lo = f64::NEG_INFINITY;
            return Flow::Stop;
        }
        if key >= self.drop_at {
            self.dropped_lo = self.dropped_lo.min(key);
            return Flow::Continue;
        }
        // Split where the values move most (the smear), among the dimensions still
        // wider than the minimum; the objective's own coordinate is split at least
        // every other time until it is finer than half the resolution, and after that
        // like any other coordinate (for deciding boxes, not for the bound).
        let (init, active, min_w) = (&self.init, &self.active, &self.min_w);
        let mut smear = bv.open_smear();
        if (matches!(obj, Objective::Coord { .. }) || opts.eliminate)
            && !bv.in_front
            && bv.elim_smear.iter().any(|&v| v > 0.0)
        {
            // While (x, y) is eliminated, (u, v, t) are split where the combination
            // that nearly certified the box moves most.
            smear[2..5].copy_from_slice(&bv.elim_smear);
            // (x, y) are not split meanwhile, and their smears are of the edge values,
            // not of the combination: they do not scale the others.
            smear[0] = 0.0;
            smear[1] = 0.0;
        }
        let max_smear = smear.iter().cloned().fold(0.0, f64::max);
        let mut dim = None;
        let mut best_score = 0.0; // a coordinate that moves no open value is never split
        for i in 0..5 {
            if !active[i] || b[i].width() <= min_w[i] || init[i].width() == 0.0 {
                continue;
            }
            let mut score = smear[i];
            if let Objective::Depth { .. } = obj {
                // Both what decides coverage and what moves the depth matter: each
                // smear relative to its largest coordinate; with neither known, the
                // widest side relative to the initial box.
                let mut dsm = bv.depth_smear;
                let end = if obj.is_max() { bv.covered_depth.hi } else { bv.covered_depth.lo };
                if opts.eliminate && end.is_finite() {
                    // The bounds over the covered polygon move with (u, v, t) only.
                    dsm = [0.0, 0.0, bv.covered_smear[0], bv.covered_smear[1], bv.covered_smear[2]];
                }
                let (ds, dmax) = (dsm[i], dsm.iter().cloned().fold(0.0, f64::max));
                score = if dmax > 0.0 { ds / dmax } else { 0.0 };
                if max_smear > 0.0 {
                    score = score.max(smear[i] / max_smear);
                }
                if dmax == 0.0 && max_smear == 0.0 {
                    score = b[i].width() / init[i].width();
                }
            }
            if i < 2
                && (bv.in_front || opts.eliminate)
                && (matches!(obj, Objective::Coord { .. }) || opts.eliminate)
                && uvt_open(&b, init, min_w, active)
            {
                // The elimination (and in front of the lens the side test) decides
                // (x, y) for a small enough box of (u, v, t): refine (u, v, t) first.
                continue;
            }
            if matches!(obj, Objective::Coord { index, .. } if i == index) && b[i].width() > cfg.resolution * 0.5 {
                // (with elimination, less often: a thin slab of the objective's
                // coordinate is no easier to rule out, and the band cut below settles
                // the part next to a witness)
                score = score.max(if opts.eliminate { OBJ_SHARE } else { 0.5 } * max_smear);
            }
            if !score.is_finite() {
                score = f64::MAX;
            }
            if score > best_score {
                best_score = score;
                dim = Some(i);
            }
        }
        if dim.is_none() {
            // No smear points anywhere (a full box has no open value): split the
            // widest side, relative to the initial box, that can still be split.
            dim = (0..5)
                .filter(|&i| active[i] && b[i].width() > min_w[i] && init[i].width() > 0.0)
                .max_by(|&i, &j| (b[i].width() / init[i].width()).total_cmp(&(b[j].width() / init[j].width())));
        }
        let Some(mut dim) = dim else {
            // Nothing left to split. A box whose key its best witness does not reach
            // stays open (its key bounds the result), full or not: a full box's
            // witness stands for it only when it reaches the key.
            if !(class == BoxClass::Full && self.best.is_some_and(|(w, _)| w <= key)) {
                self.stuck.push(key);
                self.stuck_lo = self.stuck_lo.min(key);
            }
            return Flow::Continue;
        };
        let mut m = b[dim].mid();
        if let (Objective::Coord { index, .. }, Some((w, _)), true) = (obj, self.best, opts.eliminate) {
            // A box across the resolution band below the best witness is cut at the
            // band's edge: the part within the band is then settled as it stands and
            // only the part beyond it needs to be ruled out.
            let cut = sg * (w - 0.875 * cfg.resolution);
            if b[index].lo < cut && cut < b[index].hi {
                (dim, m) = (index, cut);
            }
        }
        for half in [Interval::new(b[dim].lo, m), Interval::new(m, b[dim].hi)] {
            let mut c = b;
            c[dim] = half;
            let cv = values(tri, obj, &c, self.with_depth, opts.eliminate);
            if classify_values(&cv) == BoxClass::Empty {
                continue;
            }
            let k = key_of(obj, &c, &cv).max(key);
            frontier.push(k, depth + 1, Cell { b: c, bv: cv });
        }
        Flow::Continue
    }
}

/// The corners of a box in (x, y, u, v) at its first, middle and last time (a coordinate
/// that is a point once).
fn full_box_corners(b: &Box5) -> Vec<[f64; 5]> {
    let ends = |i: usize| if b[i].width() > 0.0 { vec![b[i].lo, b[i].hi] } else { vec![b[i].lo] };
    let ts = if b[4].width() > 0.0 { vec![b[4].lo, b[4].mid(), b[4].hi] } else { vec![b[4].lo] };
    let mut out = Vec::with_capacity(48);
    for &x in &ends(0) {
        for &y in &ends(1) {
            for &u in &ends(2) {
                for &v in &ends(3) {
                    for &t in &ts {
                        out.push([x, y, u, v, t]);
                    }
                }
            }
        }
    }
    out
}

/// The box values the search judges by (see [`Search::eliminate`]).
fn values(tri: &Tri, obj: Objective, b: &Box5, with_depth: bool, eliminate: bool) -> BoxValues {
    if let (Objective::Depth { max }, true, true) = (obj, with_depth, eliminate) {
        return box_values_for_depth(tri, b, max);
    }
    if eliminate {
        box_values_eliminating(tri, b, with_depth)
    } else {
        box_values_with(tri, b, with_depth)
    }
}

/// Run one extent with the shortcuts of `opts`.
pub fn search(tri: &Tri, init: Box5, ext: Extent, cfg: &ExtentsConfig, opts: Search) -> ObjectiveResult {
    // A box with a NaN or reversed side, or a triangle with a non-finite number, is
    // outside what the solver answers: one undecided box, never a certificate.
    if init.iter().any(|i| i.lo.is_nan() || i.hi.is_nan() || i.lo > i.hi) || tri.check_finite().is_err() {
        return ObjectiveResult { extreme: None, undecided: 1, boxes: 0, open: f64::NAN };
    }
    let obj = ext.objective();
    let sg = if obj.is_max() { -1.0 } else { 1.0 };
    let with_depth = matches!(obj, Objective::Depth { .. });
    let mut s = ExtentSearch {
        tri,
        obj,
        cfg,
        opts,
        init,
        active: active_dims(tri),
        min_w: std::array::from_fn(|i| init[i].width() * cfg.min_fraction),
        with_depth,
        sg,
        // The bound in the minimised orientation.
        drop_at: opts.bound.map_or(f64::INFINITY, |b| sg * b - cfg.resolution),
        best: None,
        boxes: 0,
        stuck_lo: f64::INFINITY,
        stuck: Vec::new(),
        dropped_lo: f64::INFINITY,
        final_lo: f64::INFINITY,
        beyond_at: None,
        last_lower: f64::NEG_INFINITY,
        moved_at: 0,
    };
    let mut frontier = Frontier::new(Ties::Deepest);
    let bv = values(tri, obj, &init, with_depth, opts.eliminate);
    frontier.push(key_of(obj, &init, &bv), 0, Cell { b: init, bv });
    bnb::run(&mut s, &mut frontier);
    let mut final_lo = s.final_lo;
    if final_lo == f64::INFINITY {
        final_lo = s.stuck_lo;
    }
    final_lo = final_lo.min(s.dropped_lo);
    // Undecided boxes are the ones that keep the enclosure wider than the resolution.
    let undecided = match s.best {
        Some((w, _)) => s.stuck.iter().filter(|&&k| w - k > cfg.resolution).count() as u64,
        None => s.stuck.len() as u64,
    };
    let extreme = s.best.map(|(w, p)| {
        let lo = final_lo.min(w);
        if sg > 0.0 {
            Extreme { lo, hi: w, witness: p }
        } else {
            Extreme { lo: -w, hi: -lo, witness: p }
        }
    });
    let open = sg * final_lo;
    ObjectiveResult { extreme, undecided, boxes: s.boxes, open }
}
