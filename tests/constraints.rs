//! Every per-sample constraint of every registered method: `eval_box` encloses `eval`,
//! and its cut never vouches for a sample `eval` culls.
//!
//! The contract of [`SampleConstraint::eval_box`] (`src/bounds/mod.rs`) is that it
//! encloses *every value `eval` can return* for a sample in the box, f32 rounding
//! included. The certified constraint search (`judge::constraints`) relies on it: a box whose
//! enclosure has `lo >= 0` is dropped as "culls nothing", so an enclosure that misses an
//! `eval` value can hide a violation from the gate.
//!
//! What is drawn: for 8 seeds x 16 regimes ([`Regime::ALL`]; case index = the regime's
//! position) a physical case ([`physical_case`] from [`rng_for`]`(seed, index)`), and on
//! it 3 boundary tiles ([`boundary_tile`], same rng) of each size 1, 4, 16 px. Every
//! registered method is set up on the case and asked for each tile; for every
//! constraint of a non-empty answer, 16 sample boxes are drawn inside
//! - the tile in x, y, and
//! - in u, v, t: the answer's intervals intersected with the domain `[-1, 1]^2 x [0, 1]`
//!   (or, for a quarter of the boxes, the whole domain: the contract holds for any box,
//!   and this puts boxes on the domain edges u = +-1, v = +-1, t = 0, 1 even when the
//!   answer's intervals stop short of them).
//!
//! Per coordinate, a box side is the whole range, a point (a random f32 or an end of the
//! range), a thin side (1..4 f32 ulps, or an f64 sliver that holds a single f32), a
//! random sub-range (f32 or plain f64 ends, as the constraint search's bisection makes), or a
//! sub-range touching the low or the high end of the range. Box 0 is the whole region,
//! box 1 a single point (which takes gdam2010's exact path), box 2 a point in (x, y) with
//! the whole region in (u, v, t). In each box, f32 samples (`Sample::new`) are taken at
//! the 32 corners (each end rounded inwards to the nearest f32 inside the box) and at
//! random interior points, and every coordinate of every sample is checked to lie in
//! the box as f64 before it is used.
//!
//! The assertion: `b.lo <= eval(s) as f64 <= b.hi` whenever `eval(s)` is finite.
//! Non-finite `eval` values are counted and reported (the contract cannot be stated for
//! them with a finite enclosure). A NaN enclosure is counted, and is a failure when the
//! sample's `eval` is finite: no constraint documents a NaN `eval_box` (see the comment
//! in [`check_constraint`]). The test also fails unless every method whose
//! [`MethodInfo`](cullproof::bounds::MethodInfo) says `per_sample` returned at least
//! [`MIN_CONSTRAINTS_PER_METHOD`] constraints and had at least
//! [`MIN_CHECKS_PER_METHOD`] samples checked (so it cannot silently test nothing), and it
//! prints the (method, constraint kind) pairs it exercised (kinds as
//! [`bound_kind`] names them). Every failure message gives the method, the
//! constraint's name and kind, the case (regime, seed, index), the tile, the box, the
//! sample, `eval` and the enclosure.
//!
//! The same boxes check the multilinear cuts ([`SampleConstraint::lower_cut`]) the judge
//! uses to decide boxes close to the covered set: wherever a cut vouches for a sample
//! (`P(s) >= err`, enclosed with outward rounding), `eval` must not cull it. Besides the
//! box's own samples, the f32 values on and around the cut's level set `P = err` along
//! each coordinate are tried, so the check reaches the rounding the cut's `err` allows
//! for ([`a_wrong_cut_is_caught`]: raised cuts and cuts without their error are caught).
//!
//! `CULLPROOF_CONSTRAINT_SEEDS=N` runs seeds 1..=N instead of the 8 fixed ones (a longer
//! search; about 35 s for N = 1000 in release). [`a_wrong_enclosure_is_caught`] checks
//! the harness: deliberately wrong enclosures must be caught.

use cullproof::bounds::{registry, Cut, SampleBox, SampleConstraint, TileResult};
use cullproof::cases::generate::{boundary_tile, physical_case, rng_for, Regime};
use cullproof::judge::bound_kind;
use cullproof::model::{Sample, Tile};
use cullproof::Interval;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::time::Instant;

const SEEDS: [u64; 8] = [1, 2, 3, 4, 5, 6, 7, 0x5eed_c0de];
const TILE_SIZES: [f32; 3] = [1.0, 4.0, 16.0];
const TILES_PER_SIZE: usize = 3;
/// Boxes drawn per constraint and tile.
const BOXES: usize = 16;
/// Random interior samples per box (on top of the 32 corners).
const INTERIOR: usize = 8;
/// Each per-sample method must have returned at least this many constraints ...
const MIN_CONSTRAINTS_PER_METHOD: u64 = 100;
/// ... and had at least this many samples checked against an enclosure.
const MIN_CHECKS_PER_METHOD: u64 = 10_000;
/// The stream the box and sample draws come from (separate from the case's own).
const BOX_STREAM: u64 = 0xb0c5_e1c0_5e5a;

/// Where a constraint came from, for the failure message.
struct Origin<'a> {
    method: &'a str,
    regime: Regime,
    seed: u64,
    index: u64,
    tile: &'a Tile,
}

/// What went wrong with one sample.
struct Failure {
    what: &'static str,
    text: String,
}

#[derive(Default)]
struct Tally {
    /// Constraints returned (one per constraint per tile answer).
    constraints: u64,
    /// Boxes evaluated.
    boxes: u64,
    /// Samples whose finite eval was checked against the enclosure.
    checks: u64,
    /// eval(s) was inf or NaN (not checkable against a finite enclosure).
    nonfinite_eval: u64,
    /// The enclosure had a NaN end.
    nan_enclosure: u64,
    /// The enclosure was not finite at an end (the whole line, e.g. lb2011's overflow guard).
    unbounded_enclosure: u64,
    /// Failures: a finite eval outside its enclosure, or with a NaN enclosure.
    outside: u64,
    nan_failures: u64,
    /// Boxes on which the constraint offered a [`Cut`].
    cuts: u64,
    /// Samples where a cut vouches (`P(s) >= err`, enclosed exactly) ...
    cut_checks: u64,
    /// ... of which within `2^-12` of the cut's magnitude of its zero set ...
    cut_near: u64,
    /// ... and those that `eval` culls all the same (failures).
    cut_failures: u64,
}

/// How many failures keep their full description.
const SHOWN: usize = 12;

/// The smallest f32 >= lo and the largest f32 <= hi, if the f64 range holds an f32.
fn f32_ends(iv: Interval) -> Option<(f32, f32)> {
    let up = |x: f64| {
        let r = x as f32;
        if (r as f64) < x {
            r.next_up()
        } else {
            r
        }
    };
    let down = |x: f64| {
        let r = x as f32;
        if (r as f64) > x {
            r.next_down()
        } else {
            r
        }
    };
    let (a, b) = (up(iv.lo), down(iv.hi));
    (a.is_finite() && b.is_finite() && a <= b && iv.contains(a as f64) && iv.contains(b as f64)).then_some((a, b))
}

/// A random f32 in the f64 range (which must hold one), rounded inwards.
fn f32_in(rng: &mut ChaCha8Rng, iv: Interval) -> Option<f32> {
    let (a, b) = f32_ends(iv)?;
    let x = if a == b { a } else { rng.gen_range(a..=b) };
    let x = x.clamp(a, b);
    iv.contains(x as f64).then_some(x)
}

/// One side of a sample box inside the range `r` (whose ends are f32 values).
fn side(rng: &mut ChaCha8Rng, r: Interval) -> Interval {
    let (lo, hi) = (r.lo, r.hi);
    let pick = |rng: &mut ChaCha8Rng| if hi > lo { rng.gen_range(lo..=hi) } else { lo };
    let f32_pick = |rng: &mut ChaCha8Rng| f32_in(rng, r).map(|x| x as f64).unwrap_or(lo);
    let ordered = |a: f64, b: f64| Interval::new(a.min(b), a.max(b));
    match rng.gen_range(0..9) {
        0 => r,
        1 => {
            // a point: an end or a random f32
            let p = match rng.gen_range(0..3) {
                0 => lo,
                1 => hi,
                _ => f32_pick(rng),
            };
            Interval::point(p)
        }
        2 => {
            // thin: 1..4 f32 ulps from an f32, clipped to the range
            let p = f32_pick(rng) as f32;
            let mut q = p;
            for _ in 0..rng.gen_range(1..=4) {
                q = q.next_up();
            }
            Interval::new(p as f64, (q as f64).min(hi))
        }
        3 => {
            // an f64 sliver after an f32: holds that f32 only
            let p = f32_pick(rng);
            let next = (p as f32).next_up() as f64;
            Interval::new(p, (p + 0.5 * (next - p)).min(hi))
        }
        4 => ordered(pick(rng), pick(rng)),
        5 => ordered(f32_pick(rng), f32_pick(rng)),
        6 => Interval::new(lo, pick(rng)),
        7 => Interval::new(pick(rng), hi),
        _ => {
            // touching an end, with an f32 far end
            if rng.gen_bool(0.5) {
                Interval::new(lo, f32_pick(rng))
            } else {
                Interval::new(f32_pick(rng), hi)
            }
        }
    }
}

/// The answer's interval intersected with the domain range; the domain range if that
/// is empty or NaN (then only the domain is meaningful).
fn region(ans: [f32; 2], dom: [f32; 2]) -> Interval {
    let (lo, hi) = (ans[0].max(dom[0]), ans[1].min(dom[1]));
    if lo.is_nan() || hi.is_nan() || lo > hi {
        Interval::new(dom[0] as f64, dom[1] as f64)
    } else {
        Interval::new(lo as f64, hi as f64)
    }
}

/// The f32 samples of a box: its 32 corners (ends rounded inwards) and `INTERIOR`
/// random points; every coordinate lies in the box as f64. Empty if a side holds no f32.
fn samples_in(rng: &mut ChaCha8Rng, b: &SampleBox) -> Vec<Sample> {
    let sides = [b.x, b.y, b.u, b.v, b.t];
    let Some(ends) = sides.iter().map(|&s| f32_ends(s)).collect::<Option<Vec<_>>>() else {
        return Vec::new();
    };
    let mut out = Vec::with_capacity(32 + INTERIOR);
    for corner in 0..32u32 {
        let c = |k: usize| if corner >> k & 1 == 0 { ends[k].0 } else { ends[k].1 };
        out.push(Sample::new(c(0), c(1), c(2), c(3), c(4)));
    }
    for _ in 0..INTERIOR {
        let c: Vec<f32> = sides.iter().map(|&s| f32_in(rng, s).unwrap()).collect();
        out.push(Sample::new(c[0], c[1], c[2], c[3], c[4]));
    }
    for s in &out {
        let p = s.to_oracle();
        for (k, side) in sides.iter().enumerate() {
            assert!(side.contains(p[k]), "test bug: sample {s:?} outside box {b:?} on axis {k}");
        }
    }
    out
}

/// `P(s)` of a cut at a sample, enclosed with outward rounding (exact coefficients and
/// f32 coordinates, so the enclosure is as tight as f64 allows).
fn cut_value(cut: &Cut, s: [f64; 5]) -> Interval {
    let mut sum = Interval::point(0.0);
    for (m, &c) in cut.coef.iter().enumerate() {
        if c == 0.0 {
            continue;
        }
        let term = (0..5).filter(|i| m >> i & 1 == 1).fold(Interval::point(c), |a, i| a * Interval::point(s[i]));
        sum = sum + term;
    }
    sum
}

/// The largest `|term|` sum of a cut over a box (the scale its zero set is judged at).
fn cut_magnitude(cut: &Cut, b: &SampleBox) -> f64 {
    let sides = [b.x, b.y, b.u, b.v, b.t];
    (0..32)
        .map(|m| {
            (0..5)
                .filter(|i| m >> i & 1 == 1)
                .fold(cut.coef[m].abs(), |a, i| a * sides[i].lo.abs().max(sides[i].hi.abs()))
        })
        .sum()
}

/// Samples of the box on and next to the cut's level set `P = err`: from each base
/// sample, along each coordinate `P` depends on (it is affine in each), the f32 values
/// around the solution, kept inside the box.
fn cut_level_samples(cut: &Cut, b: &SampleBox, base: &[Sample]) -> Vec<Sample> {
    let sides = [b.x, b.y, b.u, b.v, b.t];
    let mut out = Vec::new();
    for s in base {
        let p = s.to_oracle();
        for i in 0..5 {
            let at = |v: f64| {
                let mut q = p;
                q[i] = v;
                cut.estimate(q)
            };
            let (a0, slope) = (at(0.0), at(1.0) - at(0.0));
            if slope == 0.0 || !slope.is_finite() {
                continue;
            }
            let r = ((cut.err - a0) / slope) as f32;
            let mut cands = vec![r];
            let (mut up, mut dn) = (r, r);
            for _ in 0..3 {
                up = up.next_up();
                dn = dn.next_down();
                cands.push(up);
                cands.push(dn);
            }
            for v in cands {
                if v.is_finite() && sides[i].contains(v as f64) {
                    let mut c = [s.x, s.y, s.u, s.v, s.t];
                    c[i] = v;
                    out.push(Sample::new(c[0], c[1], c[2], c[3], c[4]));
                }
            }
        }
    }
    out
}

/// Check the cut a constraint offers on a box, if any: at every sample (the box's own
/// and those on the cut's level set) where it vouches, `eval` must not cull.
fn check_cut(
    c: &dyn SampleConstraint,
    bx: &SampleBox,
    samples: &[Sample],
    origin: &Origin,
    tally: &mut Tally,
    failures: &mut Vec<Failure>,
) {
    let Some(cut) = c.lower_cut(bx) else {
        return;
    };
    tally.cuts += 1;
    assert!(cut.err >= 0.0 && cut.err.is_finite(), "{}: cut with error {}", origin.method, cut.err);
    let scale = cut_magnitude(&cut, bx);
    let mut all = samples.to_vec();
    let bases: Vec<Sample> = samples.iter().step_by(4).copied().collect();
    all.extend(cut_level_samples(&cut, bx, &bases));
    for s in all {
        let pv = cut_value(&cut, s.to_oracle());
        // Vouched for only where the enclosure's low end is at least err (NaN: no).
        if pv.lo.partial_cmp(&cut.err).is_none_or(|o| o == std::cmp::Ordering::Less) {
            continue;
        }
        tally.cut_checks += 1;
        if pv.lo - cut.err <= scale * 2f64.powi(-12) {
            tally.cut_near += 1;
        }
        let g = c.eval(&s);
        if g < 0.0 {
            tally.cut_failures += 1;
            if failures.len() < SHOWN {
                failures.push(Failure {
                    what: "culled where its cut vouches",
                    text: format!(
                        "method {} constraint {:?}, case regime {} seed {:#x} index {}, tile {:?}\n  box {:?}\n  \
                         sample {:?}: eval {:e}, P in [{:e}, {:e}], err {:e}",
                        origin.method,
                        c.name(),
                        origin.regime.name(),
                        origin.seed,
                        origin.index,
                        origin.tile,
                        bx,
                        s,
                        g,
                        pv.lo,
                        pv.hi,
                        cut.err
                    ),
                });
            }
        }
    }
}

/// Check one constraint on `BOXES` boxes; failures are counted in the tally and the
/// first [`SHOWN`] described in `failures`.
fn check_constraint(
    c: &dyn SampleConstraint,
    tile: &Tile,
    ans: ([f32; 2], [f32; 2], [f32; 2]),
    origin: &Origin,
    rng: &mut ChaCha8Rng,
    tally: &mut Tally,
    failures: &mut Vec<Failure>,
) {
    let xr = Interval::new(tile.x0 as f64, tile.x1 as f64);
    let yr = Interval::new(tile.y0 as f64, tile.y1 as f64);
    for k in 0..BOXES {
        let whole_domain = rng.gen_bool(0.25);
        let (ur, vr, tr) = if whole_domain {
            (Interval::new(-1.0, 1.0), Interval::new(-1.0, 1.0), Interval::new(0.0, 1.0))
        } else {
            (region(ans.0, [-1.0, 1.0]), region(ans.1, [-1.0, 1.0]), region(ans.2, [0.0, 1.0]))
        };
        let regions = [xr, yr, ur, vr, tr];
        let sides: Vec<Interval> = match k {
            0 => regions.to_vec(),
            1 => regions.iter().map(|&r| Interval::point(f32_in(rng, r).unwrap() as f64)).collect(),
            2 => regions
                .iter()
                .enumerate()
                .map(|(i, &r)| if i < 2 { Interval::point(f32_in(rng, r).unwrap() as f64) } else { r })
                .collect(),
            _ => regions.iter().map(|&r| side(rng, r)).collect(),
        };
        let bx = SampleBox { x: sides[0], y: sides[1], u: sides[2], v: sides[3], t: sides[4] };
        let enc = c.eval_box(&bx);
        tally.boxes += 1;
        let nan = enc.lo.is_nan() || enc.hi.is_nan();
        if nan {
            tally.nan_enclosure += 1;
        } else if !enc.lo.is_finite() || !enc.hi.is_finite() {
            tally.unbounded_enclosure += 1;
        }
        let samples = samples_in(rng, &bx);
        if !samples.is_empty() {
            check_cut(c, &bx, &samples, origin, tally, failures);
        }
        for s in samples {
            let g = c.eval(&s);
            if !g.is_finite() {
                tally.nonfinite_eval += 1;
                continue;
            }
            let where_ = || {
                format!(
                    "method {} constraint {:?} (kind {:?})\n  case: regime {} seed {:#x} index {} \
                     (physical_case(&mut rng_for(seed, index), regime))\n  tile {:?}\n  box {:?}\n  \
                     sample {:?}\n  eval = {:e} ({:?}), eval_box = [{:e}, {:e}]",
                    origin.method,
                    c.name(),
                    bound_kind(&c.name()),
                    origin.regime.name(),
                    origin.seed,
                    origin.index,
                    origin.tile,
                    bx,
                    s,
                    g,
                    g,
                    enc.lo,
                    enc.hi
                )
            };
            if nan {
                // No constraint documents a NaN enclosure. lb2011's patches (also in
                // lc) and wu2013's lines return the whole real line `[-inf, inf]` instead
                // of a NaN or overflowing value (explicit checks in their `eval_box`);
                // mam2012's lines (also in mam2012-new) and mam2012-hyperplane's planes
                // are only emitted with finite f32 coefficients (`a.is_finite()`,
                // `line()` / `plane()` return None otherwise), and gdam2010's span ends
                // lie in [0, 1], so their outward-rounded f64 arithmetic over a finite
                // box cannot produce NaN either. The constraint search would read a NaN lower end as
                // "may cull" (its key becomes -inf), which is safe for the search, but the
                // trait promises an enclosure and NaN encloses nothing: a finite eval with
                // a NaN enclosure is a failure.
                tally.nan_failures += 1;
                if failures.len() < SHOWN {
                    failures.push(Failure { what: "NaN enclosure of a finite eval", text: where_() });
                }
                continue;
            }
            tally.checks += 1;
            let gv = g as f64;
            if !(enc.lo <= gv && gv <= enc.hi) {
                tally.outside += 1;
                if failures.len() < SHOWN {
                    failures.push(Failure { what: "eval outside eval_box", text: where_() });
                }
            }
        }
    }
}

/// What a run saw.
struct Run {
    per_method: BTreeMap<&'static str, Tally>,
    /// (method, constraint kind) -> (constraints, checks).
    per_kind: BTreeMap<(&'static str, String), (u64, u64)>,
    failures: Vec<Failure>,
    answers: u64,
}

/// A deliberately wrong enclosure or cut (the harness's own check: it must be caught).
#[derive(Clone, Copy, Debug)]
enum Mutation {
    /// Narrowed by this fraction of its width at each end.
    Narrow(f64),
    /// On a box that is a single point, the midpoint of the enclosure only: about the
    /// real value with the f32 rounding allowance dropped.
    PointMidpoint,
    /// Cuts raised by `2^-12` of their magnitude over the box (they vouch for samples
    /// just beyond their level set); enclosures untouched.
    CutRaise,
    /// Cuts with their error (the rounding allowance) dropped.
    CutNoErr,
}

#[derive(Debug)]
struct Mutated<'a> {
    inner: &'a dyn SampleConstraint,
    mutation: Mutation,
}

impl SampleConstraint for Mutated<'_> {
    fn name(&self) -> String {
        self.inner.name()
    }
    fn eval(&self, s: &Sample) -> f32 {
        self.inner.eval(s)
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let e = self.inner.eval_box(b);
        match self.mutation {
            Mutation::Narrow(frac) => {
                let d = frac * (e.hi - e.lo);
                Interval::new(e.lo + d, e.hi - d)
            }
            Mutation::CutRaise | Mutation::CutNoErr => e,
            Mutation::PointMidpoint => {
                let point = [b.x, b.y, b.u, b.v, b.t].iter().all(|i| i.lo == i.hi);
                if point {
                    Interval::point(e.mid())
                } else {
                    e
                }
            }
        }
    }
    fn lower_cut(&self, b: &SampleBox) -> Option<Cut> {
        let mut cut = self.inner.lower_cut(b)?;
        if let Mutation::CutRaise = self.mutation {
            cut.coef[0] += cut_magnitude(&cut, b) * 2f64.powi(-12);
        }
        if let Mutation::CutNoErr = self.mutation {
            cut.err = 0.0;
        }
        Some(cut)
    }
}

/// Check every constraint of every registered method on the cases of `seeds`; with
/// `mutation`, on [`Mutated`] enclosures instead.
fn run(seeds: &[u64], mutation: Option<Mutation>) -> Run {
    let methods = registry();
    let mut out = Run { per_method: BTreeMap::new(), per_kind: BTreeMap::new(), failures: Vec::new(), answers: 0 };
    for &seed in seeds {
        for (index, &regime) in Regime::ALL.iter().enumerate() {
            let index = index as u64;
            let mut rng = rng_for(seed, index);
            let case = physical_case(&mut rng, regime);
            let tiles: Vec<Tile> = TILE_SIZES
                .iter()
                .flat_map(|&size| (0..TILES_PER_SIZE).map(move |_| size))
                .map(|size| boundary_tile(&case, &mut rng, size))
                .collect();
            let mut brng = rng_for(seed ^ BOX_STREAM, index);
            for m in &methods {
                let id = m.info().id;
                let prep = m.setup(&case.triangle);
                for tile in &tiles {
                    out.answers += 1;
                    let TileResult::Bounds(b) = prep.tile(tile) else {
                        continue;
                    };
                    let origin = Origin { method: id, regime, seed, index, tile };
                    for c in &b.constraints {
                        let tally = out.per_method.entry(id).or_default();
                        tally.constraints += 1;
                        let before = tally.checks;
                        let ans = (b.u, b.v, b.t);
                        match mutation {
                            None => {
                                check_constraint(c.as_ref(), tile, ans, &origin, &mut brng, tally, &mut out.failures)
                            }
                            Some(mutation) => {
                                let s = Mutated { inner: c.as_ref(), mutation };
                                check_constraint(&s, tile, ans, &origin, &mut brng, tally, &mut out.failures)
                            }
                        }
                        let done = tally.checks - before;
                        let e = out.per_kind.entry((id, bound_kind(&c.name()))).or_default();
                        e.0 += 1;
                        e.1 += done;
                    }
                }
            }
        }
    }
    out
}

#[test]
fn eval_box_encloses_eval_for_every_method() {
    let start = Instant::now();
    let methods = registry();
    // `CULLPROOF_CONSTRAINT_SEEDS=N` runs seeds 1..=N instead (a longer search).
    let seeds: Vec<u64> = match std::env::var("CULLPROOF_CONSTRAINT_SEEDS") {
        Ok(n) => (1..=n.parse::<u64>().expect("CULLPROOF_CONSTRAINT_SEEDS: a number")).collect(),
        Err(_) => SEEDS.to_vec(),
    };
    let Run { per_method, per_kind, failures, answers } = run(&seeds, None);
    let secs = start.elapsed().as_secs_f64();

    eprintln!("eval_box vs eval: {} seeds, {answers} (method, tile) answers, {secs:.2} s", seeds.len());
    eprintln!(
        "{:<24} {:>11} {:>8} {:>10} {:>12} {:>9} {:>9} {:>8}",
        "method", "constraints", "boxes", "checks", "nonfinite-ev", "nan-encl", "unbounded", "FAILED"
    );
    for (id, t) in &per_method {
        eprintln!(
            "{:<24} {:>11} {:>8} {:>10} {:>12} {:>9} {:>9} {:>8}",
            id,
            t.constraints,
            t.boxes,
            t.checks,
            t.nonfinite_eval,
            t.nan_enclosure,
            t.unbounded_enclosure,
            t.outside + t.nan_failures
        );
    }
    eprintln!("cuts (lower_cut): method, boxes with a cut, samples vouched for, of them near the level set, culled");
    for (id, t) in per_method.iter().filter(|(_, t)| t.cuts > 0) {
        eprintln!("  {id:<26} {:>8} {:>10} {:>9} {:>6}", t.cuts, t.cut_checks, t.cut_near, t.cut_failures);
    }
    eprintln!("(method, constraint kind) pairs exercised: {}", per_kind.len());
    for ((id, kind), (n, checks)) in &per_kind {
        eprintln!("  {id:<24} {kind:<36} {n:>6} constraints {checks:>9} checks");
    }

    // Every method that says it gives per-sample constraints was really exercised (the
    // methods that say they do not are in the table above if they returned any, and
    // were checked all the same).
    let per_sample: Vec<&str> = methods.iter().filter(|m| m.info().outputs.per_sample).map(|m| m.info().id).collect();
    for id in ["lb2011", "lc", "mam2012", "mam2012-hyperplane-ps", "mam2012-new", "wu2013", "gdam2010"] {
        assert!(per_sample.contains(&id), "{id} no longer registered as a per-sample method: {per_sample:?}");
    }
    let mut thin = Vec::new();
    for id in &per_sample {
        let t = per_method.get(id);
        let (n, checks) = t.map_or((0, 0), |t| (t.constraints, t.checks));
        if n < MIN_CONSTRAINTS_PER_METHOD || checks < MIN_CHECKS_PER_METHOD {
            thin.push(format!("{id}: {n} constraints, {checks} checks"));
        }
    }

    // The cuts the judge relies on: offered where documented, reaching their level
    // set, and never vouching for a culled sample.
    for id in [
        "lb2011",
        "lb2011-safe",
        "mam2012-safe",
        "mam2012-hyperplane-ps",
        "mam2012-hyperplane-ps-safe",
        "wu2013",
        "wu2013-safe",
    ] {
        let t = per_method.get(id);
        let (cuts, near) = t.map_or((0, 0), |t| (t.cuts, t.cut_near));
        assert!(cuts >= 100 && near >= 100, "{id}: {cuts} boxes with a cut, {near} samples near a level set");
    }
    let cut_failures: u64 = per_method.values().map(|t| t.cut_failures).sum();
    if cut_failures > 0 {
        let shown: Vec<String> = failures.iter().map(|f| format!("{}:\n  {}", f.what, f.text)).collect();
        panic!("{cut_failures} samples culled where a cut vouches; the first {}:\n{}", shown.len(), shown.join("\n"));
    }

    let outside: u64 = per_method.values().map(|t| t.outside).sum();
    let nan: u64 = per_method.values().map(|t| t.nan_failures).sum();
    if outside + nan > 0 {
        let shown: Vec<String> = failures.iter().map(|f| format!("{}:\n  {}", f.what, f.text)).collect();
        panic!(
            "{outside} finite evals outside their eval_box, {nan} with a NaN eval_box; the first {}:\n{}",
            shown.len(),
            shown.join("\n")
        );
    }
    assert!(thin.is_empty(), "methods exercised too little: {thin:?}");
}

/// The harness itself, on 2 of the seeds: a wrong enclosure must be caught for every
/// per-sample method, so that the main test passing means something.
/// - Enclosures narrowed by 1% of their width at each end (the extremes of these
///   constraints over a box are reached at its corners, which are sampled).
/// - On point boxes, the enclosure's midpoint alone (the f32 rounding allowance
///   dropped): caught wherever the f32 evaluation rounds, which shows that the samples
///   reach the rounding the widening is there for. gdam2010 is exempt from this one: its
///   `t - a` is often exact in f32 (Sterbenz), so no rounding need show.
#[test]
fn a_wrong_enclosure_is_caught() {
    let methods = registry();
    for mutation in [Mutation::Narrow(0.01), Mutation::PointMidpoint] {
        let r = run(&SEEDS[..2], Some(mutation));
        for m in methods.iter().filter(|m| m.info().outputs.per_sample) {
            let id = m.info().id;
            let (caught, checks) = r.per_method.get(id).map_or((0, 0), |t| (t.outside, t.checks));
            eprintln!("{mutation:?}, {id}: {caught} of {checks} checks caught");
            if matches!(mutation, Mutation::PointMidpoint) && id == "gdam2010" {
                continue;
            }
            assert!(checks > 0 && caught > 0, "{id}: {mutation:?} went unnoticed ({checks} checks)");
        }
    }
}

/// The cut check itself, on 2 of the seeds:
/// - cuts raised by `2^-12` of their magnitude (vouching for samples just beyond their
///   level set, where the constraint culls) must be caught for every method that offers
///   cuts;
/// - cuts with their rounding allowance dropped must be caught for every method whose
///   cut needs one (its `eval` rounds to nearest): the level-set samples reach the
///   rounding. The directed-rounding cuts (`mam2012-safe`, `mam2012-new-safe`,
///   `mam2012-hyperplane-ps-safe`) have none to drop.
#[test]
fn a_wrong_cut_is_caught() {
    let r = run(&SEEDS[..2], Some(Mutation::CutRaise));
    let mut offered = 0;
    for (id, t) in r.per_method.iter().filter(|(_, t)| t.cuts > 0) {
        offered += 1;
        eprintln!("CutRaise, {id}: {} of {} vouched samples culled", t.cut_failures, t.cut_checks);
        assert!(t.cut_failures > 0, "{id}: a raised cut went unnoticed ({} checks)", t.cut_checks);
    }
    assert!(offered >= 7, "only {offered} methods offered cuts");
    let r = run(&SEEDS[..2], Some(Mutation::CutNoErr));
    for id in ["lb2011", "lb2011-safe", "lc", "lc-safe", "mam2012-hyperplane-ps", "wu2013", "wu2013-safe"] {
        let (caught, checks) = r.per_method.get(id).map_or((0, 0), |t| (t.cut_failures, t.cut_checks));
        eprintln!("CutNoErr, {id}: {caught} of {checks} vouched samples culled");
        assert!(caught > 0, "{id}: a cut without its rounding allowance went unnoticed ({checks} checks)");
    }
}
