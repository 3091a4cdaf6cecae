//! The directions of the traced values towards their exact values, the rules that give
//! them, the facts that hold inside a branch, and the demands on outputs and pins.

use super::trace::{BOp, Bn, Op, Pool, Trace, N};
use crate::bounds::arith::End;
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};

mod same;

// ---------------------------------------------------------------------------------
// Exact values.

type Ri = u32;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Real {
    /// An input, or a pinned end (its own exact value from there on).
    Var(N),
    K(u32),
    Add(Ri, Ri),
    Sub(Ri, Ri),
    Mul(Ri, Ri),
    Div(Ri, Ri),
    Neg(Ri),
    Abs(Ri),
    Min(Ri, Ri),
    Max(Ri, Ri),
    /// The exact value along the branch the f32 code takes.
    Ite(Bn, Ri, Ri),
    /// The quantity a pinned range holds (its ends, whether it is > 0).
    Quant(N, N, bool),
}

// ---------------------------------------------------------------------------------
// Directions.

/// What a value is to its exact value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pre {
    /// The value is NaN (a literal): it stands for "no value" and is allowed anywhere
    /// a NaN-tolerant claim is made; outputs must be NaN-free.
    Nan,
    Exact,
    Lo,
    Hi,
    Any,
}

/// A direction: `pre`, after a rounding to nearest when `rounded`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Dir {
    pre: Pre,
    rounded: bool,
}

const EXACT: Dir = Dir { pre: Pre::Exact, rounded: false };
const ANY: Dir = Dir { pre: Pre::Any, rounded: false };

fn unrounded(pre: Pre) -> Dir {
    Dir { pre, rounded: false }
}
fn rounded(pre: Pre) -> Dir {
    if pre == Pre::Any || pre == Pre::Nan {
        unrounded(pre)
    } else {
        Dir { pre, rounded: true }
    }
}

fn flip(p: Pre) -> Pre {
    match p {
        Pre::Lo => Pre::Hi,
        Pre::Hi => Pre::Lo,
        p => p,
    }
}

fn join_pre(a: Pre, b: Pre) -> Pre {
    use Pre::*;
    match (a, b) {
        (Nan, x) | (x, Nan) => x,
        (Any, _) | (_, Any) => Any,
        (Exact, x) | (x, Exact) => x,
        (Lo, Lo) => Lo,
        (Hi, Hi) => Hi,
        _ => Any,
    }
}

fn join(a: Dir, b: Dir) -> Dir {
    let pre = join_pre(a.pre, b.pre);
    if pre == Pre::Any {
        return ANY;
    }
    let r = (a.rounded && a.pre != Pre::Nan) || (b.rounded && b.pre != Pre::Nan);
    Dir { pre, rounded: r && pre != Pre::Nan }
}

/// `a + b` of two ends: same sides stay, exact is neutral.
fn add_pre(a: Pre, b: Pre) -> Pre {
    use Pre::*;
    match (a, b) {
        (Nan, _) | (_, Nan) => Nan,
        (Exact, x) | (x, Exact) => x,
        (Lo, Lo) => Lo,
        (Hi, Hi) => Hi,
        _ => Any,
    }
}

/// A sign.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sg {
    Pos,
    Neg,
    NonNeg,
    NonPos,
    Zero,
}

impl Sg {
    fn of(v: f32) -> Option<Sg> {
        if v > 0.0 {
            Some(Sg::Pos)
        } else if v < 0.0 {
            Some(Sg::Neg)
        } else if v == 0.0 {
            Some(Sg::Zero)
        } else {
            None
        }
    }
    fn ge0(self) -> bool {
        matches!(self, Sg::Pos | Sg::NonNeg | Sg::Zero)
    }
    fn le0(self) -> bool {
        matches!(self, Sg::Neg | Sg::NonPos | Sg::Zero)
    }
    fn strict(self) -> bool {
        matches!(self, Sg::Pos | Sg::Neg)
    }
    fn neg(self) -> Sg {
        match self {
            Sg::Pos => Sg::Neg,
            Sg::Neg => Sg::Pos,
            Sg::NonNeg => Sg::NonPos,
            Sg::NonPos => Sg::NonNeg,
            Sg::Zero => Sg::Zero,
        }
    }
    /// Whether two facts about one number contradict each other.
    fn clash(a: Sg, b: Sg) -> bool {
        (a == Sg::Pos && b.le0()) || (a == Sg::Neg && b.ge0()) || (b == Sg::Pos && a.le0()) || (b == Sg::Neg && a.ge0())
    }
    /// The stronger of two facts about one number.
    fn meet(a: Option<Sg>, b: Option<Sg>) -> Option<Sg> {
        match (a, b) {
            (None, x) | (x, None) => x,
            (Some(x), Some(y)) if x.strict() || x == Sg::Zero => Some(x).or(Some(y)),
            (Some(x), Some(y)) if y.strict() || y == Sg::Zero => Some(y).or(Some(x)),
            (Some(Sg::NonNeg), Some(Sg::NonPos)) | (Some(Sg::NonPos), Some(Sg::NonNeg)) => Some(Sg::Zero),
            (Some(x), Some(_)) => Some(x),
        }
    }
}

/// Facts that hold inside a branch.
#[derive(Clone, Default)]
struct Facts {
    /// f32 signs of values (each value NaN-free, or the sign only if it is not NaN:
    /// `sure` tells which).
    f_sign: HashMap<N, (Sg, bool)>,
    /// Signs of exact values.
    r_sign: HashMap<Ri, Sg>,
    finite: HashSet<N>,
    nan_free: HashSet<N>,
    /// Disjunctions known true (their disjuncts).
    ors: Vec<Vec<Bn>>,
    /// The branch cannot be taken (a constant false condition).
    dead: bool,
}

/// A failed demand of the check.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    /// The output or the lemma the demand was made for.
    pub what: String,
    /// What the value is instead.
    pub found: String,
}

/// What the check found for one traced tile answer.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    /// Operations of the traced code.
    pub ops: usize,
    /// Output ends checked.
    pub outputs: usize,
    /// Pinned values checked (each under every branch it is reached in).
    pub pins: usize,
    /// The lemmas the pins use, by name.
    pub lemmas: Vec<&'static str>,
    /// The values the code chooses freely, and why any value will do.
    pub choices: Vec<&'static str>,
    /// Demands not met (empty: the composition is checked).
    pub failures: Vec<Failure>,
    /// How often each rule was used.
    pub rules: Vec<(&'static str, usize)>,
}

/// The direction analysis over one [`Trace`].
pub struct Check<'t> {
    t: &'t Trace,
    reals: RefCell<Pool<Real>>,
    real_memo: RefCell<HashMap<N, Ri>>,
    ctxs: RefCell<Vec<Facts>>,
    ctx_index: RefCell<HashMap<(usize, Bn, bool, bool), usize>>,
    /// The conditions each context assumes (sorted), and the context of each such set:
    /// a branch reached along two paths is one context.
    assumed: RefCell<Vec<Vec<(Bn, bool)>>>,
    /// (Contexts made inside a probe at the root are their own: their facts were
    /// worked out with a probe's findings.)
    by_assumed: RefCell<HashMap<Assumed, usize>>,
    dir_memo: RefCell<HashMap<(N, usize), Dir>>,
    /// Keyed also by whether a probe at the root asked (its findings are its own).
    nan_memo: RefCell<HashMap<(N, usize, bool), bool>>,
    fin_memo: RefCell<HashMap<(N, usize, bool), bool>>,
    failures: RefCell<Vec<Failure>>,
    /// The pinned values met (each once, whatever branches it was checked under).
    pins: RefCell<HashSet<N>>,
    used: RefCell<HashMap<&'static str, usize>>,
    /// Inside a probe at the root (> 0): a pin that is no end there gives no end rather
    /// than a failure.
    probing: std::cell::Cell<u32>,
    probe_memo: RefCell<HashMap<(N, usize), Dir>>,
}

const ROOT: usize = 0;

/// The conditions a context assumes (sorted), and whether a probe at the root made it.
type Assumed = (Vec<(Bn, bool)>, bool);

impl<'t> Check<'t> {
    pub fn new(t: &'t Trace) -> Self {
        Check {
            t,
            reals: RefCell::new(Pool::default()),
            real_memo: RefCell::new(HashMap::new()),
            ctxs: RefCell::new(vec![Facts::default()]),
            ctx_index: RefCell::new(HashMap::new()),
            assumed: RefCell::new(vec![vec![]]),
            by_assumed: RefCell::new(HashMap::from([((vec![], false), ROOT), ((vec![], true), ROOT)])),
            dir_memo: RefCell::new(HashMap::new()),
            nan_memo: RefCell::new(HashMap::new()),
            fin_memo: RefCell::new(HashMap::new()),
            failures: RefCell::new(vec![]),
            pins: RefCell::new(HashSet::new()),
            used: RefCell::new(HashMap::new()),
            probing: std::cell::Cell::new(0),
            probe_memo: RefCell::new(HashMap::new()),
        }
    }

    fn rule(&self, name: &'static str) {
        *self.used.borrow_mut().entry(name).or_insert(0) += 1;
    }

    // --- exact values -------------------------------------------------------------

    fn rnode(&self, r: Real) -> Ri {
        self.reals.borrow_mut().add(r)
    }
    fn rget(&self, r: Ri) -> Real {
        self.reals.borrow().nodes[r as usize]
    }

    /// The exact value of `n`: its operations in real arithmetic, steps and roundings
    /// dropped, selects along the f32 branch.
    fn real(&self, n: N) -> Ri {
        if let Some(&r) = self.real_memo.borrow().get(&n) {
            return r;
        }
        let t = self.t;
        let known = t.known.borrow().get(&n).map(|k| k.exact);
        if let Some(exact) = known {
            let r = self.real(exact);
            self.real_memo.borrow_mut().insert(n, r);
            return r;
        }
        let r = match t.op(n) {
            Op::Input(_) | Op::Pin(..) | Op::Free(..) => self.rnode(Real::Var(n)),
            Op::Range(lo, hi, _, positive, _) => self.rnode(Real::Quant(lo, hi, positive)),
            Op::Same(_, like, ..) => self.real(like),
            Op::Out(_, from, _) => self.real(from),
            Op::Lit(b) => self.rnode(Real::K(b)),
            Op::Add(a, b) => self.rnode(Real::Add(self.real(a), self.real(b))),
            Op::Sub(a, b) => self.rnode(Real::Sub(self.real(a), self.real(b))),
            Op::Mul(a, b) => self.rnode(Real::Mul(self.real(a), self.real(b))),
            Op::Div(a, b) => self.rnode(Real::Div(self.real(a), self.real(b))),
            Op::Fma(a, b, c) => {
                let m = self.rnode(Real::Mul(self.real(a), self.real(b)));
                self.rnode(Real::Add(m, self.real(c)))
            }
            Op::Neg(a) => self.rnode(Real::Neg(self.real(a))),
            Op::Abs(a) => self.rnode(Real::Abs(self.real(a))),
            Op::Min(a, b) | Op::MinN(a, b) => self.minmax(true, self.real(a), self.real(b)),
            Op::Max(a, b) | Op::MaxN(a, b) => self.minmax(false, self.real(a), self.real(b)),
            Op::Up(a) | Op::Dn(a) => self.real(a),
            Op::Sel(c, a, b) => {
                let (ra, rb) = (self.real(a), self.real(b));
                let why = t.same.borrow().get(&n).copied();
                if ra == rb {
                    ra
                } else if let Some(why) = why {
                    // A shortcut: both branches one exact value where `c` holds.
                    if self.same_under(c, ra, rb) {
                        self.rule("a shortcut's branches of one exact value");
                        rb
                    } else {
                        self.record(Failure {
                            what: format!("shortcut ({why})"),
                            found: "its branches' exact values are not shown equal under its condition".into(),
                        });
                        self.rnode(Real::Ite(c, ra, rb))
                    }
                } else {
                    self.rnode(Real::Ite(c, ra, rb))
                }
            }
        };
        self.real_memo.borrow_mut().insert(n, r);
        r
    }

    /// min / max of exact values, in one canonical form: the set of its terms (nested
    /// mins flattened, each term once, sorted), without the neutral +inf (min) or -inf
    /// (max).
    fn minmax(&self, min: bool, a: Ri, b: Ri) -> Ri {
        let neutral = Real::K(if min { f32::INFINITY } else { f32::NEG_INFINITY }.to_bits());
        let mut set: Vec<Ri> = self.terms(min, a);
        set.extend(self.terms(min, b));
        set.retain(|&r| self.rget(r) != neutral);
        set.sort_unstable();
        set.dedup();
        match set.split_first() {
            None => self.rnode(neutral),
            Some((&first, rest)) => {
                rest.iter().fold(first, |acc, &r| self.rnode(if min { Real::Min(acc, r) } else { Real::Max(acc, r) }))
            }
        }
    }

    /// The terms of a min (`min`) or max of exact values (itself, when it is none).
    fn terms(&self, min: bool, r: Ri) -> Vec<Ri> {
        match (self.rget(r), min) {
            (Real::Min(a, b), true) | (Real::Max(a, b), false) => {
                let mut v = self.terms(min, a);
                v.extend(self.terms(min, b));
                v
            }
            _ => vec![r],
        }
    }

    // --- facts --------------------------------------------------------------------

    fn facts(&self, ctx: usize) -> std::cell::Ref<'_, Facts> {
        std::cell::Ref::map(self.ctxs.borrow(), |c| &c[ctx])
    }

    /// The branch of `ctx` where `c` is `v`.
    fn push(&self, ctx: usize, c: Bn, v: bool) -> usize {
        let probing = self.probing.get() > 0;
        if let Some(&i) = self.ctx_index.borrow().get(&(ctx, c, v, probing)) {
            return i;
        }
        let mut set = self.assumed.borrow()[ctx].clone();
        let i = match set.binary_search(&(c, v)) {
            Ok(_) => ctx,
            Err(at) => {
                set.insert(at, (c, v));
                let known = self.by_assumed.borrow().get(&(set.clone(), probing)).copied();
                match known {
                    Some(i) => i,
                    None => {
                        let mut f = self.facts(ctx).clone();
                        self.assume(ctx, &mut f, c, v);
                        let mut cs = self.ctxs.borrow_mut();
                        cs.push(f);
                        let i = cs.len() - 1;
                        drop(cs);
                        self.assumed.borrow_mut().push(set.clone());
                        self.by_assumed.borrow_mut().insert((set, probing), i);
                        i
                    }
                }
            }
        };
        self.ctx_index.borrow_mut().insert((ctx, c, v, probing), i);
        i
    }

    /// Add to `f` what `c == v` says (directions are read in `ctx`, the branch the
    /// condition is tested in).
    fn assume(&self, ctx: usize, f: &mut Facts, c: Bn, v: bool) {
        let t = self.t;
        match (t.bop(c), v) {
            (BOp::Const(k), v) => {
                if k != v {
                    f.dead = true
                }
            }
            (BOp::Not(x), v) => self.assume(ctx, f, x, !v),
            (BOp::Free(x, _), v) => self.assume(ctx, f, x, v),
            (BOp::And(x, y), true) | (BOp::Or(x, y), false) => {
                self.assume(ctx, f, x, v);
                self.assume(ctx, f, y, v);
            }
            (BOp::Or(..), true) => {
                let mut ds = vec![];
                self.terms_of(c, false, &mut ds);
                // Disjuncts this branch refutes drop out (a NaN test of a NaN-free value).
                let open: Vec<Bn> = ds
                    .into_iter()
                    .filter(|&d| !matches!(t.bop(d), BOp::IsNan(x) if f.nan_free.contains(&x) || self.nan_free(x, ctx)))
                    .collect();
                match open.len() {
                    0 => f.dead = true,
                    1 => self.assume(ctx, f, open[0], true),
                    _ => f.ors.push(open),
                }
            }
            (BOp::IsNan(a), true) => {
                if f.nan_free.contains(&a) || self.nan_free(a, ctx) {
                    f.dead = true;
                }
            }
            (BOp::And(..), false) => {}
            (BOp::IsNan(a), false) => {
                f.nan_free.insert(a);
            }
            (BOp::IsFinite(a), true) => {
                f.finite.insert(a);
                f.nan_free.insert(a);
                // A finite select of a value and a non-finite literal took the value.
                if let Op::Sel(c, x, y) = t.op(a) {
                    let bad = |v: N| t.lit_of(v).is_some_and(|l| !l.is_finite());
                    if bad(y) {
                        self.assume(ctx, f, c, true);
                        f.finite.insert(x);
                        f.nan_free.insert(x);
                    } else if bad(x) {
                        self.assume(ctx, f, c, false);
                        f.finite.insert(y);
                        f.nan_free.insert(y);
                    }
                }
            }
            (BOp::IsFinite(a), false) => {
                if f.finite.contains(&a) || self.finite(a, ctx) {
                    f.dead = true;
                }
            }
            (BOp::Eq(a, b), true) => {
                f.nan_free.insert(a);
                f.nan_free.insert(b);
                // A factor equal to 0 or ±1: one fact, kept as a disjunction of one term
                // (what `exact_product` reads).
                if [a, b].iter().any(|&x| t.lit_of(x).is_some_and(|v| v == 0.0 || v.abs() == 1.0)) {
                    f.ors.push(vec![c]);
                }
                if t.lit_of(b) == Some(0.0) {
                    self.sign_fact(ctx, f, a, Sg::Zero, true);
                }
                if t.lit_of(a) == Some(0.0) {
                    self.sign_fact(ctx, f, b, Sg::Zero, true);
                }
            }
            (BOp::Eq(..), false) => {}
            (BOp::Lt(a, b), true) | (BOp::Le(a, b), true) => {
                let strict = matches!(t.bop(c), BOp::Lt(..));
                f.nan_free.insert(a);
                f.nan_free.insert(b);
                if t.lit_of(b) == Some(0.0) {
                    self.sign_fact(ctx, f, a, if strict { Sg::Neg } else { Sg::NonPos }, true);
                }
                if t.lit_of(a) == Some(0.0) {
                    self.sign_fact(ctx, f, b, if strict { Sg::Pos } else { Sg::NonNeg }, true);
                }
            }
            (BOp::Lt(a, b), false) | (BOp::Le(a, b), false) => {
                // not (a < b): a >= b or a NaN operand.
                let strict = matches!(t.bop(c), BOp::Lt(..));
                if t.lit_of(b) == Some(0.0) {
                    self.sign_fact(ctx, f, a, if strict { Sg::NonNeg } else { Sg::Pos }, false);
                }
                if t.lit_of(a) == Some(0.0) {
                    self.sign_fact(ctx, f, b, if strict { Sg::NonPos } else { Sg::Neg }, false);
                }
            }
        }
    }

    /// The terms of a disjunction (`and`: of a conjunction).
    fn terms_of(&self, c: Bn, and: bool, out: &mut Vec<Bn>) {
        match (self.t.bop(c), and) {
            (BOp::Or(x, y), false) | (BOp::And(x, y), true) => {
                self.terms_of(x, and, out);
                self.terms_of(y, and, out);
            }
            _ => out.push(c),
        }
    }

    /// Record the sign `s` of the f32 value `a` (`sure`: `a` is not NaN), and what it
    /// says of the exact value of `a` when `a` is an end of the right side.
    fn sign_fact(&self, ctx: usize, f: &mut Facts, a: N, s: Sg, sure: bool) {
        let sure = sure || f.nan_free.contains(&a) || self.nan_free(a, ctx);
        let old = f.f_sign.get(&a).copied();
        if let Some((o, true)) = old {
            if sure && Sg::clash(o, s) {
                f.dead = true;
            }
        }
        let new = match old {
            Some((o, os)) if os == sure => (Sg::meet(Some(o), Some(s)).unwrap_or(s), sure),
            Some((o, true)) => (o, true),
            _ => (s, sure),
        };
        f.f_sign.insert(a, new);
        if !sure {
            return;
        }
        let d = self.dir(a, ctx);
        let r = self.real(a);
        let rs = match (d.pre, d.rounded) {
            (Pre::Exact, false) => Some(s),
            // a <= A: a > 0 gives A > 0, a >= 0 gives A >= 0.
            (Pre::Lo, false) => match s {
                Sg::Pos => Some(Sg::Pos),
                Sg::NonNeg | Sg::Zero => Some(Sg::NonNeg),
                _ => None,
            },
            (Pre::Hi, false) => match s {
                Sg::Neg => Some(Sg::Neg),
                Sg::NonPos | Sg::Zero => Some(Sg::NonPos),
                _ => None,
            },
            // a = RN(A) exact-valued: rounding is monotone, so a > 0 needs A > 0.
            (Pre::Exact, true) => match s {
                Sg::Pos | Sg::Neg => Some(s),
                _ => None,
            },
            _ => None,
        };
        if let Some(rs) = rs {
            if f.r_sign.get(&r).is_some_and(|&o| Sg::clash(o, rs)) {
                f.dead = true;
            }
            let m = Sg::meet(f.r_sign.get(&r).copied(), Some(rs)).unwrap_or(rs);
            f.r_sign.insert(r, m);
        }
    }

    /// The sign of the f32 value `n` in `ctx`, if known (NaN aside: a NaN `n` makes
    /// everything computed from it NaN).
    fn f_sign(&self, n: N, ctx: usize) -> Option<Sg> {
        if let Some(v) = self.t.lit_of(n) {
            return Sg::of(v);
        }
        // A fact that is not strict (x <= 0 from a failed test x > 0) may be sharpened by
        // what the value is (an upper end of a value < 0).
        let fact = self.facts(ctx).f_sign.get(&n).map(|&(s, _)| s);
        if fact.is_some_and(|s| s.strict() || s == Sg::Zero) {
            return fact;
        }
        Sg::meet(fact, self.f_sign_own(n, ctx))
    }

    /// [`Check::f_sign`] from what the value is, facts about it aside.
    fn f_sign_own(&self, n: N, ctx: usize) -> Option<Sg> {
        match self.t.op(n) {
            Op::Abs(_) => return Some(Sg::NonNeg),
            // The rounding of a sum of two values >= 0 is >= 0 (MONO), and of a product of
            // two values of known signs has the product's sign or is 0.
            Op::Add(a, b) => {
                if let (Some(sa), Some(sb)) = (self.f_sign(a, ctx), self.f_sign(b, ctx)) {
                    if sa.ge0() && sb.ge0() {
                        return Some(Sg::NonNeg);
                    }
                    if sa.le0() && sb.le0() {
                        return Some(Sg::NonPos);
                    }
                }
            }
            Op::Mul(a, b) => {
                if let (Some(sa), Some(sb)) = (self.f_sign(a, ctx), self.f_sign(b, ctx)) {
                    let same = (sa.ge0() && sb.ge0()) || (sa.le0() && sb.le0());
                    let opposite = (sa.ge0() && sb.le0()) || (sa.le0() && sb.ge0());
                    match (same, opposite) {
                        (true, false) => return Some(Sg::NonNeg),
                        (false, true) => return Some(Sg::NonPos),
                        _ => {}
                    }
                }
            }
            Op::Neg(a) => {
                if let Some(s) = self.f_sign(a, ctx) {
                    return Some(s.neg());
                }
            }
            _ => {}
        }
        // An end whose exact value has a strict sign on its far side: a >= A > 0.
        let d = self.dir(n, ctx);
        if d.rounded {
            return None;
        }
        let rs = self.r_sign(self.real(n), ctx)?;
        match d.pre {
            Pre::Exact => Some(rs),
            Pre::Hi if rs == Sg::Pos || rs == Sg::NonNeg => Some(rs),
            Pre::Lo if rs == Sg::Neg || rs == Sg::NonPos => Some(rs),
            _ => None,
        }
    }

    /// The sign of an exact value in `ctx`, if known.
    fn r_sign(&self, r: Ri, ctx: usize) -> Option<Sg> {
        let fact = self.facts(ctx).r_sign.get(&r).copied();
        let own = match self.rget(r) {
            Real::K(b) => Sg::of(f32::from_bits(b)),
            Real::Abs(_) => Some(Sg::NonNeg),
            Real::Quant(_, _, true) => Some(Sg::Pos),
            Real::Neg(a) => self.r_sign(a, ctx).map(Sg::neg),
            Real::Add(a, b) => add_sign(self.r_sign(a, ctx), self.r_sign(b, ctx)),
            Real::Sub(a, b) => add_sign(self.r_sign(a, ctx), self.r_sign(b, ctx).map(Sg::neg)),
            Real::Mul(a, b) => mul_sign(self.r_sign(a, ctx), self.r_sign(b, ctx)),
            _ => None,
        };
        Sg::meet(fact, own)
    }

    fn finite(&self, n: N, ctx: usize) -> bool {
        let key = (n, ctx, self.probing.get() > 0);
        if let Some(&v) = self.fin_memo.borrow().get(&key) {
            return v;
        }
        if ctx != ROOT && self.at_root(|| self.finite(n, ROOT)) {
            return true;
        }
        let t = self.t;
        let known = self.facts(ctx).finite.contains(&n);
        let by_lemma = || {
            let k = t.known.borrow().get(&n).cloned();
            k.is_some_and(|k| k.positive.is_none() && self.conds_hold(&k.conds, ctx))
        };
        let v = known
            || by_lemma()
            || match t.op(n) {
                Op::Lit(b) => f32::from_bits(b).is_finite(),
                Op::Neg(a) | Op::Abs(a) | Op::Pin(a, ..) | Op::Free(a, _) | Op::Same(a, ..) | Op::Out(a, ..) => {
                    self.finite(a, ctx)
                }
                Op::Range(lo, _, End::Lo, ..) | Op::Range(_, lo, End::Hi, ..) => self.finite(lo, ctx),
                Op::Min(a, b) | Op::Max(a, b) | Op::MinN(a, b) | Op::MaxN(a, b) => {
                    self.finite(a, ctx) && self.finite(b, ctx)
                }
                Op::Sel(c, a, b) => self.finite(a, self.push(ctx, c, true)) && self.finite(b, self.push(ctx, c, false)),
                _ => false,
            };
        self.fin_memo.borrow_mut().insert(key, v);
        v
    }

    /// Whether `n` cannot be NaN in `ctx`.
    fn nan_free(&self, n: N, ctx: usize) -> bool {
        if self.facts(ctx).dead {
            return true;
        }
        let key = (n, ctx, self.probing.get() > 0);
        if let Some(&v) = self.nan_memo.borrow().get(&key) {
            return v;
        }
        if ctx != ROOT && self.at_root(|| self.nan_free(n, ROOT)) {
            return true;
        }
        let t = self.t;
        let known = self.facts(ctx).nan_free.contains(&n);
        let v = known
            || self.finite(n, ctx)
            || match t.op(n) {
                Op::Lit(b) => !f32::from_bits(b).is_nan(),
                Op::Input(_) => false,
                // finite + finite is never NaN; finite + inf neither.
                Op::Add(a, b) | Op::Sub(a, b) => {
                    (self.finite(a, ctx) && self.nan_free(b, ctx)) || (self.nan_free(a, ctx) && self.finite(b, ctx))
                }
                Op::Mul(a, b) => self.finite(a, ctx) && self.finite(b, ctx),
                Op::Div(a, b) => {
                    self.finite(a, ctx) && self.nan_free(b, ctx) && self.f_sign(b, ctx).is_some_and(|s| s.strict())
                }
                // Finite factors give a finite product; a nonzero finite literal factor
                // a product that is not NaN: then a finite addend keeps it so.
                Op::Fma(a, b, c) => {
                    let nonzero = |x: N| t.lit_of(x).is_some_and(|v| v.is_finite() && v != 0.0);
                    (self.finite(a, ctx) && self.finite(b, ctx) && self.nan_free(c, ctx))
                        || (self.finite(c, ctx)
                            && ((nonzero(a) && self.nan_free(b, ctx)) || (nonzero(b) && self.nan_free(a, ctx))))
                }
                Op::Neg(a)
                | Op::Abs(a)
                | Op::Up(a)
                | Op::Dn(a)
                | Op::Pin(a, ..)
                | Op::Free(a, _)
                | Op::Same(a, ..)
                | Op::Out(a, ..) => self.nan_free(a, ctx),
                Op::Range(a, _, End::Lo, ..) | Op::Range(_, a, End::Hi, ..) => self.nan_free(a, ctx),
                Op::Min(a, b) | Op::Max(a, b) | Op::MinN(a, b) | Op::MaxN(a, b) => {
                    self.nan_free(a, ctx) && self.nan_free(b, ctx)
                }
                Op::Sel(c, a, b) => {
                    self.nan_free(a, self.push(ctx, c, true)) && self.nan_free(b, self.push(ctx, c, false))
                }
            };
        self.nan_memo.borrow_mut().insert(key, v);
        v
    }

    /// Whether every condition of `conds` holds in `ctx`: each is a term of a condition
    /// the branch assumes true (through conjunctions and conditions chosen freely).
    fn conds_hold(&self, conds: &[Bn], ctx: usize) -> bool {
        let assumed = self.assumed.borrow()[ctx].clone();
        let mut terms = vec![];
        for (b, v) in assumed {
            if v {
                self.true_terms(b, &mut terms);
            }
        }
        conds.iter().all(|c| terms.contains(c))
    }
    fn true_terms(&self, b: Bn, out: &mut Vec<Bn>) {
        match self.t.bop(b) {
            BOp::And(x, y) => {
                self.true_terms(x, out);
                self.true_terms(y, out);
            }
            BOp::Free(x, _) => self.true_terms(x, out),
            _ => out.push(b),
        }
    }

    /// Whether `a * b` is exact in `ctx`: a factor is the literal 0 or ±1, or the branch
    /// holds a disjunction each of whose terms says so of `a` or `b`.
    fn exact_product(&self, a: N, b: N, ctx: usize) -> bool {
        let t = self.t;
        let unit = |x: N| matches!(t.lit_of(x), Some(v) if v == 0.0 || v.abs() == 1.0);
        if unit(a) || unit(b) {
            return true;
        }
        let says = |d: Bn| match t.bop(d) {
            BOp::Eq(x, k) => {
                let kv = t.lit_of(k);
                let of_factor = x == a || x == b;
                let abs_of_factor = matches!(t.op(x), Op::Abs(y) if y == a || y == b);
                (of_factor && matches!(kv, Some(v) if v == 0.0 || v.abs() == 1.0))
                    || (abs_of_factor && matches!(kv, Some(v) if v == 0.0 || v == 1.0))
            }
            _ => false,
        };
        let f = self.facts(ctx);
        f.ors.iter().any(|ds| ds.iter().all(|&d| says(d)))
    }

    // --- directions -----------------------------------------------------------------

    fn dir(&self, n: N, ctx: usize) -> Dir {
        if self.facts(ctx).dead {
            return unrounded(Pre::Nan);
        }
        if let Some(&d) = self.dir_memo.borrow().get(&(n, ctx)) {
            return d;
        }
        // A probe's findings are its own (a pin that is no end gives no end there).
        let probing = self.probing.get() > 0;
        if probing {
            if let Some(&d) = self.probe_memo.borrow().get(&(n, ctx)) {
                return d;
            }
        }
        // What holds at the root holds in every branch: a value whose direction does not
        // need this branch's facts is not worked out again for it (nested selects on
        // unrelated conditions would otherwise multiply the contexts).
        // Once the check has failed, what the root gives is the answer: the verdict
        // stands, and a failing variant's branches are not searched one by one.
        if ctx != ROOT {
            let d0 = self.at_root(|| self.dir(n, ROOT));
            if (d0.pre != Pre::Any && !d0.rounded) || !self.failures.borrow().is_empty() {
                self.dir_memo.borrow_mut().insert((n, ctx), d0);
                return d0;
            }
        }
        let d = self.dir_of(n, ctx);
        if probing {
            self.probe_memo.borrow_mut().insert((n, ctx), d);
        } else {
            self.dir_memo.borrow_mut().insert((n, ctx), d);
        }
        d
    }

    /// `f` as a probe at the root: a pin that is no end there gives no end rather than a
    /// failure (the pin is demanded where the code reaches it).
    fn at_root<T>(&self, f: impl FnOnce() -> T) -> T {
        self.probing.set(self.probing.get() + 1);
        let r = f();
        self.probing.set(self.probing.get() - 1);
        r
    }

    /// Operands of an arithmetic operation: unrounded directions (a rounded value used
    /// without its step gives nothing).
    fn operand(&self, n: N, ctx: usize) -> Pre {
        let d = self.dir(n, ctx);
        if d.rounded {
            Pre::Any
        } else {
            d.pre
        }
    }

    fn dir_of(&self, n: N, ctx: usize) -> Dir {
        let t = self.t;
        let known = t.known.borrow().get(&n).cloned();
        if let Some(k) = known {
            let holds = match k.positive {
                Some(p) => self.finite(n, ctx) && self.f_sign(p, ctx) == Some(Sg::Pos),
                None => self.conds_hold(&k.conds, ctx),
            };
            if holds {
                self.rule("an end a lemma proves");
                return unrounded(if k.end == End::Lo { Pre::Lo } else { Pre::Hi });
            }
            return ANY;
        }
        match t.op(n) {
            Op::Input(_) | Op::Free(..) => EXACT,
            Op::Lit(b) => unrounded(if f32::from_bits(b).is_nan() { Pre::Nan } else { Pre::Exact }),
            Op::Add(a, b) => {
                self.rule("sum of same-sided ends");
                rounded(add_pre(self.operand(a, ctx), self.operand(b, ctx)))
            }
            Op::Sub(a, b) => {
                self.rule("sum of same-sided ends");
                rounded(add_pre(self.operand(a, ctx), flip(self.operand(b, ctx))))
            }
            Op::Mul(a, b) => self.product(a, b, ctx),
            Op::Div(a, b) => self.quotient(a, b, ctx),
            Op::Fma(a, b, c) => {
                let (da, db, dc) = (self.operand(a, ctx), self.operand(b, ctx), self.operand(c, ctx));
                if da == Pre::Exact && db == Pre::Exact && dc == Pre::Exact {
                    return rounded(Pre::Exact);
                }
                // An end times an exact factor of known sign (flipped when <= 0), plus an
                // end: the product is not rounded, so the real rules compose (scale, sum).
                for (dx, y, dy) in [(da, b, db), (db, a, da)] {
                    if dy != Pre::Exact {
                        continue;
                    }
                    let scaled = match self.f_sign(y, ctx) {
                        Some(s) if s.ge0() => dx,
                        Some(s) if s.le0() => flip(dx),
                        _ => continue,
                    };
                    self.rule("fused multiply-add of an end by an exact factor of known sign");
                    return rounded(add_pre(scaled, dc));
                }
                ANY
            }
            Op::Neg(a) => {
                let d = self.dir(a, ctx);
                Dir { pre: flip(d.pre), rounded: d.rounded }
            }
            Op::Abs(a) => {
                let d = self.dir(a, ctx);
                if d.pre == Pre::Exact || d.pre == Pre::Nan {
                    d
                } else {
                    ANY
                }
            }
            Op::Min(a, b) | Op::Max(a, b) | Op::MinN(a, b) | Op::MaxN(a, b) => {
                // A min that gives NaN on a NaN operand needs no NaN-free operands: its
                // value is NaN ("no value") or the min of them all.
                let propagate = matches!(t.op(n), Op::MinN(..) | Op::MaxN(..));
                if !(propagate || self.nan_free(a, ctx) && self.nan_free(b, ctx)) {
                    return ANY;
                }
                if let (Op::Max(..), Op::Abs(x), Op::Abs(y)) = (t.op(n), t.op(a), t.op(b)) {
                    if self.pair(x, y, ctx) {
                        self.rule("max(|lo|, |hi|) >= |x|");
                        return unrounded(Pre::Hi);
                    }
                }
                // The whole tree of nested mins (maxes) at once, its operands grouped by
                // exact value. A min is a lower end when each group has a lower end (or
                // exact) member, whatever the others are (a min over both ends of some
                // values); an upper end when every operand is one. A max the same way
                // round.
                let min = matches!(t.op(n), Op::Min(..) | Op::MinN(..));
                let own = if min { Pre::Lo } else { Pre::Hi };
                let mut leaves = vec![];
                self.leaves(n, min, &mut leaves);
                if !propagate && !leaves.iter().all(|&x| self.nan_free(x, ctx)) {
                    return ANY;
                }
                if let Some(d) = self.corners(min, propagate, &leaves, ctx) {
                    self.rule("min (max) of the four end products or quotients");
                    return d;
                }
                let dirs: Vec<(Ri, Pre)> = leaves.iter().map(|&x| (self.real(x), self.operand(x, ctx))).collect();
                let is = |d: Pre, side: Pre| d == side || d == Pre::Exact;
                self.rule("min/max of ends");
                if dirs.iter().all(|(_, d)| *d == Pre::Exact) {
                    EXACT
                } else if dirs.iter().all(|(r, _)| dirs.iter().any(|(r2, d)| r2 == r && is(*d, own))) {
                    unrounded(own)
                } else if dirs.iter().all(|(_, d)| is(*d, flip(own))) {
                    unrounded(flip(own))
                } else {
                    ANY
                }
            }
            Op::Up(a) | Op::Dn(a) => {
                let up = matches!(t.op(n), Op::Up(_));
                let d = self.dir(a, ctx);
                let want = if up { Pre::Hi } else { Pre::Lo };
                match d.pre {
                    Pre::Nan => d,
                    Pre::Exact => {
                        self.rule("STEP");
                        unrounded(want)
                    }
                    p if p == want => {
                        self.rule("STEP");
                        unrounded(want)
                    }
                    _ => ANY,
                }
            }
            Op::Sel(c, a, b) => {
                // (No end on one side is no end: the other side is not worked out.)
                let da = self.dir(a, self.push(ctx, c, true));
                if da.pre == Pre::Any {
                    return ANY;
                }
                join(da, self.dir(b, self.push(ctx, c, false)))
            }
            Op::Range(lo, hi, end, _, lemma) => {
                self.pins.borrow_mut().insert(n);
                let name = t.lemmas.borrow()[lemma as usize];
                for (x, e) in [(lo, End::Lo), (hi, End::Hi)] {
                    let d = self.dir(x, ctx);
                    let want = if e == End::Lo { Pre::Lo } else { Pre::Hi };
                    if d.rounded || !(d.pre == want || d.pre == Pre::Exact || d.pre == Pre::Nan) {
                        if self.probing.get() > 0 {
                            return ANY;
                        }
                        self.fail(format!("pinned range's {} end (lemma `{name}`)", end_name(e)), d);
                    }
                }
                unrounded(if end == End::Lo { Pre::Lo } else { Pre::Hi })
            }
            Op::Same(x, _, end, lemma) => {
                self.pins.borrow_mut().insert(n);
                let d = self.dir(x, ctx);
                let want = if end == End::Lo { Pre::Lo } else { Pre::Hi };
                if d.rounded || !(d.pre == want || d.pre == Pre::Exact || d.pre == Pre::Nan) {
                    let name = t.lemmas.borrow()[lemma as usize];
                    if self.probing.get() > 0 {
                        return ANY;
                    }
                    self.fail(format!("{} end of a value the lemma `{name}` equates", end_name(end)), d);
                }
                unrounded(want)
            }
            Op::Out(m, from, end) => {
                // `from - k` (k >= 0) rounds to a value <= from: from is an f32 value and
                // rounding is monotone (MONO); `from + k` mirrors for an upper end.
                // A step in the same direction after it keeps it beyond; the amount is a
                // literal or a value of known sign (NaN aside: a NaN amount gives NaN).
                let lo = end == End::Lo;
                let inner = match t.op(m) {
                    Op::Dn(x) if lo => x,
                    Op::Up(x) if !lo => x,
                    _ => m,
                };
                let signed = |k: N, nonneg: bool| match t.lit_of(k) {
                    Some(v) => (nonneg && v >= 0.0) || (!nonneg && v <= 0.0),
                    None => self.f_sign(k, ctx).is_some_and(|s| if nonneg { s.ge0() } else { s.le0() }),
                };
                let beyond = inner == from
                    || match t.op(inner) {
                        Op::Sub(f, k) => f == from && signed(k, lo),
                        Op::Add(f, k) => f == from && signed(k, !lo),
                        _ => false,
                    };
                let want = if lo { Pre::Lo } else { Pre::Hi };
                let d = self.dir(from, ctx);
                if beyond && !d.rounded && (d.pre == want || d.pre == Pre::Exact || d.pre == Pre::Nan) {
                    self.rule("an end moved outward (MONO)");
                    unrounded(want)
                } else {
                    ANY
                }
            }
            Op::Pin(a, end, lemma) => {
                self.pins.borrow_mut().insert(n);
                let d = self.dir(a, ctx);
                let want = if end == End::Lo { Pre::Lo } else { Pre::Hi };
                let ok = !d.rounded && (d.pre == want || d.pre == Pre::Exact);
                if !ok {
                    if self.probing.get() > 0 {
                        return ANY;
                    }
                    let name = t.lemmas.borrow()[lemma as usize];
                    self.fail(format!("pinned {} end (lemma `{name}`)", end_name(end)), d);
                }
                EXACT
            }
        }
    }

    /// The operands of the tree of nested mins (`min`) or maxes at `n` (of one kind:
    /// NaN-propagating or not).
    fn leaves(&self, n: N, min: bool, out: &mut Vec<N>) {
        let kind = |x: N| matches!(self.t.op(x), Op::MinN(..) | Op::MaxN(..));
        match (self.t.op(n), min) {
            (Op::Min(a, b), true) | (Op::Max(a, b), false) | (Op::MinN(a, b), true) | (Op::MaxN(a, b), false) => {
                let k = kind(n);
                for x in [a, b] {
                    if kind(x) == k {
                        self.leaves(x, min, out);
                    } else {
                        out.push(x);
                    }
                }
            }
            _ => out.push(n),
        }
    }
    /// The corner rule: `leaves` (of a min when `min`, else of a max) are the rounded
    /// products (or quotients) of the ends of two intervals, every combination of an end
    /// of the first with an end of the second present (an interval of one exact value
    /// counts as its one end), each NaN-free (or the min NaN-propagating: `propagate`),
    /// and for quotients every divisor end of one strict sign. The exact product (quotient) of the two exact values lies between
    /// the least and the greatest combination, so the min is the rounding of a real at or
    /// below it (a lower end before its step) and the max one at or above it.
    fn corners(&self, min: bool, propagate: bool, leaves: &[N], ctx: usize) -> Option<Dir> {
        let t = self.t;
        let mut combos = vec![];
        let mut quotient = None;
        for &l in leaves {
            let (x, y, q) = match t.op(l) {
                Op::Mul(x, y) => (x, y, false),
                Op::Div(x, y) => (x, y, true),
                _ => return None,
            };
            if quotient.is_some_and(|v| v != q) || !(propagate || self.nan_free(l, ctx)) {
                return None;
            }
            quotient = Some(q);
            combos.push((x, y));
        }
        let quotient = quotient?;
        let set = |f: fn(&(N, N)) -> N| {
            let mut v: Vec<N> = combos.iter().map(f).collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let (xs, ys) = (set(|c| c.0), set(|c| c.1));
        let one = |v: &[N]| match v {
            [x] => Some(self.operand(*x, ctx) == Pre::Exact),
            [x, y] => self.pair(*x, *y, ctx).then_some(false),
            _ => None,
        };
        let (ex, ey) = (one(&xs)?, one(&ys)?);
        if !xs.iter().all(|x| ys.iter().all(|y| combos.contains(&(*x, *y)))) {
            return None;
        }
        if quotient {
            let signs: Vec<Option<Sg>> = ys.iter().map(|&y| self.f_sign(y, ctx)).collect();
            let strict = |s: &Option<Sg>| s.is_some_and(Sg::strict);
            if !(signs.iter().all(strict) && signs.iter().all(|s| *s == signs[0])) {
                return None;
            }
        }
        Some(if ex && ey { rounded(Pre::Exact) } else { rounded(if min { Pre::Lo } else { Pre::Hi }) })
    }

    /// `x`, `y` are the two ends of one interval: one lower and one upper, the same
    /// exact value.
    fn pair(&self, x: N, y: N, ctx: usize) -> bool {
        let (dx, dy) = (self.operand(x, ctx), self.operand(y, ctx));
        let sides = matches!((dx, dy), (Pre::Lo, Pre::Hi) | (Pre::Hi, Pre::Lo) | (Pre::Exact, _) | (_, Pre::Exact));
        sides && dx != Pre::Any && dy != Pre::Any && self.real(x) == self.real(y)
    }

    fn product(&self, a: N, b: N, ctx: usize) -> Dir {
        let (da, db) = (self.operand(a, ctx), self.operand(b, ctx));
        if da == Pre::Nan || db == Pre::Nan {
            return unrounded(Pre::Nan);
        }
        if da == Pre::Exact && db == Pre::Exact {
            if self.exact_product(a, b, ctx) {
                self.rule("exact product (a factor 0 or ±1)");
                return EXACT;
            }
            return rounded(Pre::Exact);
        }
        // One exact factor of known sign scales the other end (flipping it when <= 0).
        for (x, dx, y, dy) in [(a, da, b, db), (b, db, a, da)] {
            if dy == Pre::Exact {
                if let Some(s) = self.f_sign(y, ctx) {
                    if s.ge0() {
                        self.rule("end times an exact factor >= 0");
                        return rounded(dx);
                    }
                    if s.le0() {
                        self.rule("end times an exact factor <= 0");
                        return rounded(flip(dx));
                    }
                }
            }
            let _ = x;
        }
        // Two lower ends >= 0: a b <= A b <= A B.
        let (sa, sb) = (self.f_sign(a, ctx), self.f_sign(b, ctx));
        if da == Pre::Lo && db == Pre::Lo && sa.is_some_and(Sg::ge0) && sb.is_some_and(Sg::ge0) {
            self.rule("product of lower ends >= 0");
            return rounded(Pre::Lo);
        }
        // Two upper ends of exact values >= 0: a b >= a B >= A B.
        let (ra, rb) = (self.r_sign(self.real(a), ctx), self.r_sign(self.real(b), ctx));
        if da == Pre::Hi && db == Pre::Hi && ra.is_some_and(Sg::ge0) && rb.is_some_and(Sg::ge0) {
            self.rule("product of upper ends of values >= 0");
            return rounded(Pre::Hi);
        }
        ANY
    }

    fn quotient(&self, a: N, b: N, ctx: usize) -> Dir {
        let (da, db) = (self.operand(a, ctx), self.operand(b, ctx));
        if da == Pre::Nan || db == Pre::Nan {
            return unrounded(Pre::Nan);
        }
        // The divisor's exact value and the divisor have one strict sign.
        let rb = self.r_sign(self.real(b), ctx);
        let fb = self.f_sign(b, ctx);
        let strict = match (rb, fb) {
            (Some(r), Some(f)) if r.strict() && f.strict() && (r == f) => Some(r),
            (_, Some(f)) if db == Pre::Exact && f.strict() => Some(f),
            _ => None,
        };
        let Some(sb) = strict else { return ANY };
        if da == Pre::Exact && db == Pre::Exact {
            return rounded(Pre::Exact);
        }
        let sa = self.f_sign(a, ctx);
        // Upper end of A / B: A / B <= a / B <= a / b.
        let num_hi = da == Pre::Exact || (da == Pre::Hi && sb == Sg::Pos) || (da == Pre::Lo && sb == Sg::Neg);
        let den_hi = db == Pre::Exact
            || (db == Pre::Lo && sa.is_some_and(Sg::ge0))
            || (db == Pre::Hi && sa.is_some_and(Sg::le0));
        let num_lo = da == Pre::Exact || (da == Pre::Lo && sb == Sg::Pos) || (da == Pre::Hi && sb == Sg::Neg);
        let den_lo = db == Pre::Exact
            || (db == Pre::Hi && sa.is_some_and(Sg::ge0))
            || (db == Pre::Lo && sa.is_some_and(Sg::le0));
        if num_hi && den_hi {
            self.rule("quotient of ends, divisor of one strict sign");
            return rounded(Pre::Hi);
        }
        if num_lo && den_lo {
            self.rule("quotient of ends, divisor of one strict sign");
            return rounded(Pre::Lo);
        }
        ANY
    }

    fn fail(&self, what: String, d: Dir) {
        self.record(Failure { what, found: describe(d) });
    }

    /// Record a failure (once).
    fn record(&self, f: Failure) {
        let mut fs = self.failures.borrow_mut();
        if !fs.contains(&f) {
            fs.push(f);
        }
    }

    /// Whether the f32 truth value `b` implies the same formula over the exact values
    /// (`under`), or is implied by it (`!under`), in `ctx`. A comparison `a < b` implies
    /// `A < B` when `a` is an upper end (or exact) and `b` a lower end; it is implied by it
    /// when the sides are the other way round and neither can be NaN.
    fn truth_holds(&self, b: Bn, under: bool, ctx: usize) -> bool {
        self.truth_in(b, under, false, ctx)
    }

    /// [`Check::truth_holds`]; `conj`: `b` is a term of a conjunction that must imply its
    /// counterpart (where a free condition may stand: it only restricts).
    fn truth_in(&self, b: Bn, under: bool, conj: bool, ctx: usize) -> bool {
        let t = self.t;
        if self.facts(ctx).dead {
            return true;
        }
        // (A NaN operand makes an f32 comparison false: nothing to imply.)
        let end = |x: N, want: Pre| {
            let d = self.dir(x, ctx);
            !d.rounded && (d.pre == want || d.pre == Pre::Exact || (under && d.pre == Pre::Nan))
        };
        match t.bop(b) {
            BOp::Const(_) => true,
            BOp::Not(x) => self.truth_in(x, !under, false, ctx),
            // A free condition only ever restricts a cull: allowed as a term of a
            // conjunction that implies its counterpart, nowhere else.
            BOp::Free(..) => under && conj,
            // Where the f32 conjunction holds, its first term does while the second is
            // checked; where the disjunction's second term decides, the first is false.
            // Where the f32 conjunction holds, all its terms do: each is checked with all
            // of them as facts (facts about f32 values that hold there).
            BOp::And(..) if under => {
                let mut terms = vec![];
                self.terms_of(b, true, &mut terms);
                let c = terms.iter().fold(ctx, |c, &o| self.push(c, o, true));
                terms.iter().all(|&x| self.truth_in(x, true, true, c))
            }
            BOp::Or(x, y) if under => {
                self.truth_in(x, true, false, ctx) && self.truth_in(y, true, false, self.push(ctx, x, false))
            }
            // Where the exact disjunction must bring the f32 one about, the f32 first term
            // is false while the second is checked.
            BOp::Or(x, y) => {
                self.truth_in(x, false, false, ctx) && self.truth_in(y, false, false, self.push(ctx, x, false))
            }
            BOp::And(x, y) => self.truth_in(x, false, false, ctx) && self.truth_in(y, false, false, ctx),
            // X <= X holds whatever the ends are.
            BOp::Le(x, y) if under && self.real(x) == self.real(y) => {
                self.rule("a comparison of one exact value with itself");
                true
            }
            BOp::Lt(x, y) | BOp::Le(x, y) if under => {
                end(x, Pre::Hi) && end(y, Pre::Lo) || (matches!(t.bop(b), BOp::Lt(..)) && self.rounded_sign(x, y, ctx))
            }
            // Implied by its counterpart: from ends the other way round, or because the
            // branch's facts make the exact comparison false (x < 0 with X known >= 0).
            BOp::Lt(x, y) | BOp::Le(x, y) => {
                let strict = matches!(t.bop(b), BOp::Lt(..));
                let never = |v: N, s: Option<Sg>, lower: bool| {
                    t.lit_of(v) == Some(0.0)
                        && s.is_some_and(|s| if lower == strict { s.le0() } else { matches!(s, Sg::Neg) })
                };
                let (rx, ry) = (self.r_sign(self.real(x), ctx), self.r_sign(self.real(y), ctx));
                // 0 < Y false when Y <= 0; 0 <= Y false when Y < 0; X < 0 false when
                // X >= 0; X <= 0 false when X > 0.
                let exact_false = never(x, ry, true)
                    || (t.lit_of(y) == Some(0.0) && rx.is_some_and(|s| if strict { s.ge0() } else { s == Sg::Pos }));
                exact_false || (end(x, Pre::Lo) && end(y, Pre::Hi) && self.nan_free(x, ctx) && self.nan_free(y, ctx))
            }
            // x == 0 for an end x: exact when x is exact, or when the facts put its exact
            // value on the end's own side of 0 too (a lower end 0 of a value <= 0).
            BOp::Eq(x, y) if under => {
                let zero_end = |v: N, k: N| {
                    if t.lit_of(k) != Some(0.0) {
                        return false;
                    }
                    let d = self.dir(v, ctx);
                    let rs = self.r_sign(self.real(v), ctx);
                    !d.rounded
                        && match d.pre {
                            Pre::Exact => true,
                            Pre::Lo => rs.is_some_and(Sg::le0),
                            Pre::Hi => rs.is_some_and(Sg::ge0),
                            _ => false,
                        }
                };
                (self.dir(x, ctx) == EXACT && self.dir(y, ctx) == EXACT) || zero_end(x, y) || zero_end(y, x)
            }
            BOp::Eq(x, y) => self.dir(x, ctx) == EXACT && self.dir(y, ctx) == EXACT,
            // Exact values are real numbers: never NaN, always finite. So a NaN test
            // implies its counterpart only where it cannot hold, and a finiteness test is
            // implied by its counterpart only where the value is finite.
            BOp::IsNan(x) => !under || self.nan_free(x, ctx),
            BOp::IsFinite(x) => under || self.finite(x, ctx),
        }
    }

    /// `x < y` with one side the literal 0 and the other a rounding to nearest of a real
    /// on the right side of its exact value (an upper end or exact on the left, a lower
    /// end or exact on the right): rounding is monotone and keeps 0 (MONO), so
    /// `RN(z) < 0` needs `z < 0`, and `0 < RN(z)` needs `0 < z`.
    fn rounded_sign(&self, x: N, y: N, ctx: usize) -> bool {
        let t = self.t;
        let side = |v: N, want: Pre| {
            let d = self.dir(v, ctx);
            d.rounded && (d.pre == want || d.pre == Pre::Exact)
        };
        let ok = (t.lit_of(y) == Some(0.0) && side(x, Pre::Hi)) || (t.lit_of(x) == Some(0.0) && side(y, Pre::Lo));
        if ok {
            self.rule("a rounded end compared with 0 (MONO)");
        }
        ok
    }

    /// [`Check::run`] with truth-valued outputs too: each must imply its formula over the
    /// exact values (a cull the f32 code decides, the exact values decide too).
    pub fn run_with(&self, outputs: &[(N, End, String)], culls: &[(Bn, String)]) -> Outcome {
        for (b, name) in culls {
            self.rule("comparisons of ends");
            if !self.truth_holds(*b, true, ROOT) {
                let at = self.culprit_truth(*b);
                self.failures.borrow_mut().push(Failure {
                    what: format!("output {name}"),
                    found: format!(
                        "does not imply its exact counterpart (a comparison of ends on the wrong sides): {at}"
                    ),
                });
            }
        }
        let mut o = self.run(outputs);
        o.outputs += culls.len();
        o
    }

    /// Demand that each output is an end of its side (or exact) and NaN-free, and
    /// collect the outcome (pins are demanded as they are met).
    pub fn run(&self, outputs: &[(N, End, String)]) -> Outcome {
        // Every shortcut is verified, whether a demand reads its exact value or not.
        let mut shortcuts: Vec<N> = self.t.same.borrow().keys().copied().collect();
        shortcuts.sort_unstable();
        for n in shortcuts {
            self.real(n);
        }
        for (n, end, name) in outputs {
            let d = self.dir(*n, ROOT);
            let want = if *end == End::Lo { Pre::Lo } else { Pre::Hi };
            if d.rounded || !(d.pre == want || d.pre == Pre::Exact) {
                let at = self.culprit(*n);
                self.failures.borrow_mut().push(Failure {
                    what: format!("output {name} ({} end)", end_name(*end)),
                    found: format!("{}; first operation without a rule: {at}", describe(d)),
                });
            }
            if !self.nan_free(*n, ROOT) {
                self.failures.borrow_mut().push(Failure { what: format!("output {name}"), found: "may be NaN".into() });
            }
        }
        let mut rules: Vec<(&'static str, usize)> = self.used.borrow().iter().map(|(k, v)| (*k, *v)).collect();
        rules.sort();
        Outcome {
            ops: self.t.len(),
            outputs: outputs.len(),
            pins: self.pins.borrow().len(),
            lemmas: self.t.lemmas.borrow().clone(),
            choices: self.t.choices.borrow().clone(),
            failures: self.failures.borrow().clone(),
            rules,
        }
    }
}

fn end_name(e: End) -> &'static str {
    match e {
        End::Lo => "lower",
        End::Hi => "upper",
    }
}

fn describe(d: Dir) -> String {
    let p = match d.pre {
        Pre::Nan => "NaN",
        Pre::Exact => "exact",
        Pre::Lo => "a lower end",
        Pre::Hi => "an upper end",
        Pre::Any => "no end (no rule applies: a step missing, in the wrong direction, or ends of both sides mixed)",
    };
    if d.rounded {
        format!("rounded to nearest from {p}, with no outward step")
    } else {
        p.to_string()
    }
}

fn add_sign(a: Option<Sg>, b: Option<Sg>) -> Option<Sg> {
    let (a, b) = (a?, b?);
    if a.ge0() && b.ge0() {
        Some(if a == Sg::Pos || b == Sg::Pos { Sg::Pos } else { Sg::NonNeg })
    } else if a.le0() && b.le0() {
        Some(if a == Sg::Neg || b == Sg::Neg { Sg::Neg } else { Sg::NonPos })
    } else {
        None
    }
}

fn mul_sign(a: Option<Sg>, b: Option<Sg>) -> Option<Sg> {
    let (a, b) = (a?, b?);
    if a == Sg::Zero || b == Sg::Zero {
        return Some(Sg::Zero);
    }
    let neg = a.le0() != b.le0();
    let strict = a.strict() && b.strict();
    Some(match (neg, strict) {
        (false, true) => Sg::Pos,
        (false, false) => Sg::NonNeg,
        (true, true) => Sg::Neg,
        (true, false) => Sg::NonPos,
    })
}

impl Check<'_> {
    /// Where a value's direction is lost: the deepest operation under `n` (at the root)
    /// whose operands have directions but which no rule covers, with its operands.
    fn culprit(&self, n: N) -> String {
        self.culprit_in(n, ROOT)
    }
    fn culprit_in(&self, n: N, ctx: usize) -> String {
        let d = self.dir(n, ctx);
        let op = self.t.op(n);
        let kids: Vec<(N, usize)> = match op {
            Op::Add(a, b)
            | Op::Sub(a, b)
            | Op::Mul(a, b)
            | Op::Div(a, b)
            | Op::Min(a, b)
            | Op::Max(a, b)
            | Op::MinN(a, b)
            | Op::MaxN(a, b) => vec![(a, ctx), (b, ctx)],
            Op::Neg(a) | Op::Abs(a) | Op::Up(a) | Op::Dn(a) | Op::Pin(a, ..) | Op::Same(a, ..) => vec![(a, ctx)],
            Op::Out(m, from, _) => vec![(m, ctx), (from, ctx)],
            Op::Sel(c, a, b) => vec![(a, self.push(ctx, c, true)), (b, self.push(ctx, c, false))],
            _ => vec![],
        };
        for &(k, kc) in &kids {
            let dk = self.dir(k, kc);
            if dk.pre == Pre::Any
                || (dk.rounded && !matches!(op, Op::Up(_) | Op::Dn(_) | Op::Sel(..) | Op::Neg(_) | Op::Abs(_)))
            {
                return self.culprit_in(k, kc);
            }
        }
        let of: Vec<String> = kids.iter().map(|&(k, kc)| self.show(k, kc)).collect();
        format!("{} is {} (of {})", self.name(n), describe(d), of.join("; "))
    }

    /// A value in words: its name, its direction, and its sign where known.
    fn show(&self, n: N, ctx: usize) -> String {
        let sign = match self.f_sign(n, ctx) {
            Some(Sg::Pos) => ", > 0",
            Some(Sg::Neg) => ", < 0",
            Some(Sg::NonNeg) => ", >= 0",
            Some(Sg::NonPos) => ", <= 0",
            Some(Sg::Zero) => ", = 0",
            None => "",
        };
        let nan = if self.nan_free(n, ctx) { "" } else { ", may be NaN" };
        format!("{}: {}{sign}{nan}", self.name(n), describe(self.dir(n, ctx)))
    }

    /// What a value is, in words (an input by its name).
    fn name(&self, n: N) -> String {
        match self.t.op(n) {
            Op::Input(i) => format!("input {}", self.t.inputs.borrow()[i as usize]),
            Op::Lit(b) => format!("{}", f32::from_bits(b)),
            Op::Add(..) => "a sum".into(),
            Op::Sub(..) => "a difference".into(),
            Op::Mul(..) => "a product".into(),
            Op::Div(..) => "a quotient".into(),
            Op::Fma(..) => "a fused multiply-add".into(),
            Op::Neg(..) => "a negation".into(),
            Op::Abs(..) => "an absolute value".into(),
            Op::Min(..) => "a min".into(),
            Op::Max(..) => "a max".into(),
            Op::MinN(..) => "a min (NaN on a NaN operand)".into(),
            Op::MaxN(..) => "a max (NaN on a NaN operand)".into(),
            Op::Up(..) => "a step up".into(),
            Op::Dn(..) => "a step down".into(),
            Op::Sel(..) => "a select".into(),
            Op::Pin(..) => "a pinned value".into(),
            Op::Free(..) => "a value chosen freely".into(),
            Op::Range(..) => "an end of a pinned range".into(),
            Op::Same(..) => "an end of a value a lemma equates with another".into(),
            Op::Out(..) => "an end moved outward".into(),
        }
    }

    /// Where a cull fails: the first comparison or test under `b` that does not imply its
    /// counterpart, with its operands.
    fn culprit_truth(&self, b: Bn) -> String {
        self.culprit_truth_in(b, true, ROOT)
    }
    fn culprit_truth_in(&self, b: Bn, under: bool, ctx: usize) -> String {
        let t = self.t;
        match t.bop(b) {
            BOp::Not(x) => self.culprit_truth_in(x, !under, ctx),
            BOp::And(..) if under => {
                let mut terms = vec![];
                self.terms_of(b, true, &mut terms);
                let c = terms.iter().fold(ctx, |c, &o| self.push(c, o, true));
                for &x in &terms {
                    if !self.truth_in(x, true, true, c) {
                        return self.culprit_truth_in(x, true, c);
                    }
                }
                "none".into()
            }
            BOp::And(x, y) | BOp::Or(x, y) => {
                if !self.truth_holds(x, under, ctx) {
                    return self.culprit_truth_in(x, under, ctx);
                }
                let c2 = match t.bop(b) {
                    BOp::And(..) if under => self.push(ctx, x, true),
                    BOp::Or(..) => self.push(ctx, x, false),
                    _ => ctx,
                };
                self.culprit_truth_in(y, under, c2)
            }
            BOp::Lt(x, y) | BOp::Le(x, y) | BOp::Eq(x, y) => {
                let sym = match t.bop(b) {
                    BOp::Lt(..) => "<",
                    BOp::Le(..) => "<=",
                    _ => "==",
                };
                let need = match (t.bop(b), under) {
                    (BOp::Eq(..), _) => "exact values, or an end 0 of a value the facts put at 0",
                    (_, true) => "an upper end on the left and a lower end on the right",
                    (_, false) => "a lower end on the left and an upper end on the right, NaN-free",
                };
                let lost = |v: N| {
                    let d = self.dir(v, ctx);
                    if d.pre == Pre::Any || d.rounded {
                        format!("; {}", self.culprit_in(v, ctx))
                    } else {
                        String::new()
                    }
                };
                format!(
                    "`{} {sym} {}` needs {need}: {} and {}{}{}",
                    self.name(x),
                    self.name(y),
                    self.show(x, ctx),
                    self.show(y, ctx),
                    lost(x),
                    lost(y)
                )
            }
            BOp::IsNan(x) => format!("a NaN test of {} that can hold", self.show(x, ctx)),
            BOp::IsFinite(x) => format!("a finiteness test of {} that can fail", self.show(x, ctx)),
            BOp::Free(..) => "a condition chosen freely, where it could enable a cull".into(),
            BOp::Const(_) => "a constant".into(),
        }
    }
}
