//! The recording instance of [`F32Arith`]: the code's data flow as one graph.

use crate::bounds::arith::{End, F32Arith};
use std::cell::RefCell;
use std::collections::HashMap;

/// A value of the trace (an index into its operations).
pub type N = u32;
/// A truth value of the trace.
pub type Bn = u32;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Op {
    Input(u32),
    Lit(u32),
    Add(N, N),
    Sub(N, N),
    Mul(N, N),
    Div(N, N),
    Fma(N, N, N),
    Neg(N),
    Abs(N),
    Min(N, N),
    Max(N, N),
    /// `min` and `max` that give NaN when either operand is NaN.
    MinN(N, N),
    MaxN(N, N),
    Up(N),
    Dn(N),
    Sel(Bn, N, N),
    Pin(N, End, u32),
    /// A value the code may choose freely.
    Free(N, u32),
    /// One end of a pinned range `[lo, hi]`: which, whether its quantity is > 0, lemma.
    Range(N, N, End, bool, u32),
    /// An end (`x`, which) of an interval whose exact value equals, by the lemma, the
    /// exact value of the second node.
    Same(N, N, End, u32),
    /// A value moved outward from an end (the second node), which side.
    Out(N, N, End),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum BOp {
    Const(bool),
    Lt(N, N),
    Le(N, N),
    Eq(N, N),
    IsNan(N),
    IsFinite(N),
    And(Bn, Bn),
    Or(Bn, Bn),
    Not(Bn),
    /// A condition the code may choose freely (it only turns culls off).
    Free(Bn, u32),
}

/// A value a lemma proves an end of an exact value ([`Trace::known_end`],
/// [`Trace::known_end_if`]).
#[derive(Clone, Debug)]
pub(super) struct Known {
    /// Its side.
    pub(super) end: End,
    /// The exact value's node.
    pub(super) exact: N,
    /// Where the lemma holds: the value finite and `positive` > 0 (`Some`), or every
    /// condition of `conds` true on the branch (`None`: the lemma proves finiteness too).
    pub(super) positive: Option<N>,
    pub(super) conds: Vec<Bn>,
}

/// Interned nodes.
pub(super) struct Pool<T> {
    pub(super) nodes: Vec<T>,
    index: HashMap<T, u32>,
}

impl<T> Default for Pool<T> {
    fn default() -> Self {
        Pool { nodes: vec![], index: HashMap::new() }
    }
}

impl<T: Copy + Eq + std::hash::Hash> Pool<T> {
    pub(super) fn add(&mut self, t: T) -> u32 {
        if let Some(&i) = self.index.get(&t) {
            return i;
        }
        let i = self.nodes.len() as u32;
        self.nodes.push(t);
        self.index.insert(t, i);
        i
    }
}

/// The recording instance of [`F32Arith`]: every operation becomes a node of one graph
/// (equal operations on equal operands are one node). Truth values with a constant
/// operand are folded, so that code paths the arithmetic rules out at compile time (a
/// factor 1 of the x axis) leave no branch behind.
#[derive(Default)]
pub struct Trace {
    f: RefCell<Pool<Op>>,
    b: RefCell<Pool<BOp>>,
    pub(super) inputs: RefCell<Vec<String>>,
    pub(super) lemmas: RefCell<Vec<&'static str>>,
    pub(super) choices: RefCell<Vec<&'static str>>,
    /// Values a lemma proves ends of an exact value.
    pub(super) known: RefCell<HashMap<N, Known>>,
    /// Selects whose branches the code declares of one exact value under their
    /// condition ([`F32Arith::select_same`]), and why.
    pub(super) same: RefCell<HashMap<N, &'static str>>,
}

impl Trace {
    pub fn new() -> Self {
        Self::default()
    }
    /// A fresh input named `name` (any f32 value).
    pub fn input(&self, name: &str) -> N {
        let mut ins = self.inputs.borrow_mut();
        ins.push(name.to_string());
        let i = ins.len() as u32 - 1;
        self.f.borrow_mut().add(Op::Input(i))
    }
    /// Declare, by the lemma named `lemma`, `node` an end (`end`) of the exact value of
    /// `exact`, wherever `node` is finite and `positive` is > 0. The lemma's proof must
    /// be about exactly the operations that compute `node` (the caller builds them from
    /// the lemma's own formula: equal operations are one node, so a code that computes
    /// anything else never meets the declared node).
    pub fn known_end(&self, node: N, end: End, exact: N, positive: N, lemma: &'static str) {
        self.note(&self.lemmas, lemma);
        self.known.borrow_mut().insert(node, Known { end, exact, positive: Some(positive), conds: vec![] });
    }

    /// Declare, by the lemma named `lemma`, `node` finite and an end (`end`) of the exact
    /// value of `exact` on every branch where each of `conds` holds (each a condition
    /// the code tests, or the sample's domain: the lemma's hypotheses). The lemma's
    /// proof must be about exactly the operations that compute `node`, as for
    /// [`known_end`](Self::known_end).
    pub fn known_end_if(&self, node: N, end: End, exact: N, conds: &[Bn], lemma: &'static str) {
        self.note(&self.lemmas, lemma);
        self.known.borrow_mut().insert(node, Known { end, exact, positive: None, conds: conds.to_vec() });
    }

    /// How many operations the trace holds.
    pub fn len(&self) -> usize {
        self.f.borrow().nodes.len()
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    pub(super) fn op(&self, n: N) -> Op {
        self.f.borrow().nodes[n as usize]
    }
    pub(super) fn bop(&self, b: Bn) -> BOp {
        self.b.borrow().nodes[b as usize]
    }
    fn node(&self, o: Op) -> N {
        self.f.borrow_mut().add(o)
    }
    fn bnode(&self, o: BOp) -> Bn {
        self.b.borrow_mut().add(o)
    }
    fn note(&self, list: &RefCell<Vec<&'static str>>, text: &'static str) -> u32 {
        let mut ls = list.borrow_mut();
        match ls.iter().position(|l| *l == text) {
            Some(i) => i as u32,
            None => {
                ls.push(text);
                ls.len() as u32 - 1
            }
        }
    }
    pub(super) fn lit_of(&self, n: N) -> Option<f32> {
        match self.op(n) {
            Op::Lit(b) => Some(f32::from_bits(b)),
            _ => None,
        }
    }
    pub(super) fn const_of(&self, b: Bn) -> Option<bool> {
        match self.bop(b) {
            BOp::Const(v) => Some(v),
            _ => None,
        }
    }
}

impl F32Arith for Trace {
    type F = N;
    type B = Bn;

    fn lit(&self, v: f32) -> N {
        // One NaN: every NaN literal means "no value".
        let v = if v.is_nan() { f32::NAN } else { v };
        self.node(Op::Lit(v.to_bits()))
    }
    fn add(&self, a: &N, b: &N) -> N {
        self.node(Op::Add(*a, *b))
    }
    fn sub(&self, a: &N, b: &N) -> N {
        self.node(Op::Sub(*a, *b))
    }
    fn mul(&self, a: &N, b: &N) -> N {
        self.node(Op::Mul(*a, *b))
    }
    fn div(&self, a: &N, b: &N) -> N {
        self.node(Op::Div(*a, *b))
    }
    fn fma(&self, a: &N, b: &N, c: &N) -> N {
        self.node(Op::Fma(*a, *b, *c))
    }
    fn neg(&self, a: &N) -> N {
        match self.lit_of(*a) {
            Some(v) => self.lit(-v),
            None => self.node(Op::Neg(*a)),
        }
    }
    fn abs(&self, a: &N) -> N {
        match self.lit_of(*a) {
            Some(v) => self.lit(v.abs()),
            None => self.node(Op::Abs(*a)),
        }
    }
    fn min(&self, a: &N, b: &N) -> N {
        self.node(Op::Min(*a, *b))
    }
    fn max(&self, a: &N, b: &N) -> N {
        self.node(Op::Max(*a, *b))
    }
    fn min_nan(&self, a: &N, b: &N) -> N {
        self.node(Op::MinN(*a, *b))
    }
    fn max_nan(&self, a: &N, b: &N) -> N {
        self.node(Op::MaxN(*a, *b))
    }
    fn next_up(&self, a: &N) -> N {
        self.node(Op::Up(*a))
    }
    fn next_down(&self, a: &N) -> N {
        self.node(Op::Dn(*a))
    }
    fn lt(&self, a: &N, b: &N) -> Bn {
        match (self.lit_of(*a), self.lit_of(*b)) {
            (Some(x), Some(y)) => self.truth(x < y),
            _ => self.bnode(BOp::Lt(*a, *b)),
        }
    }
    fn le(&self, a: &N, b: &N) -> Bn {
        match (self.lit_of(*a), self.lit_of(*b)) {
            (Some(x), Some(y)) => self.truth(x <= y),
            _ => self.bnode(BOp::Le(*a, *b)),
        }
    }
    fn eq(&self, a: &N, b: &N) -> Bn {
        match (self.lit_of(*a), self.lit_of(*b)) {
            (Some(x), Some(y)) => self.truth(x == y),
            _ => self.bnode(BOp::Eq(*a, *b)),
        }
    }
    fn is_nan(&self, a: &N) -> Bn {
        match self.lit_of(*a) {
            Some(x) => self.truth(x.is_nan()),
            None => self.bnode(BOp::IsNan(*a)),
        }
    }
    fn is_finite(&self, a: &N) -> Bn {
        match self.lit_of(*a) {
            Some(x) => self.truth(x.is_finite()),
            None => self.bnode(BOp::IsFinite(*a)),
        }
    }
    fn truth(&self, b: bool) -> Bn {
        self.bnode(BOp::Const(b))
    }
    fn and(&self, a: &Bn, b: &Bn) -> Bn {
        match (self.const_of(*a), self.const_of(*b)) {
            (Some(false), _) | (_, Some(false)) => self.truth(false),
            (Some(true), _) => *b,
            (_, Some(true)) => *a,
            _ if a == b => *a,
            _ => self.bnode(BOp::And(*a, *b)),
        }
    }
    fn or(&self, a: &Bn, b: &Bn) -> Bn {
        match (self.const_of(*a), self.const_of(*b)) {
            (Some(true), _) | (_, Some(true)) => self.truth(true),
            (Some(false), _) => *b,
            (_, Some(false)) => *a,
            _ if a == b => *a,
            _ => self.bnode(BOp::Or(*a, *b)),
        }
    }
    fn not(&self, a: &Bn) -> Bn {
        match self.bop(*a) {
            BOp::Const(v) => self.truth(!v),
            BOp::Not(x) => x,
            _ => self.bnode(BOp::Not(*a)),
        }
    }
    fn select(&self, c: &Bn, a: &N, b: &N) -> N {
        match self.const_of(*c) {
            Some(true) => *a,
            Some(false) => *b,
            None if a == b => *a,
            None => self.node(Op::Sel(*c, *a, *b)),
        }
    }
    fn pin(&self, a: &N, end: End, lemma: &'static str) -> N {
        let i = self.note(&self.lemmas, lemma);
        self.node(Op::Pin(*a, end, i))
    }
    fn pin_range(&self, v: &[N; 2], positive: bool, lemma: &'static str) -> [N; 2] {
        let i = self.note(&self.lemmas, lemma);
        [End::Lo, End::Hi].map(|e| self.node(Op::Range(v[0], v[1], e, positive, i)))
    }
    fn pin_same(&self, v: &[N; 2], like: &N, lemma: &'static str) -> [N; 2] {
        let i = self.note(&self.lemmas, lemma);
        [(v[0], End::Lo), (v[1], End::Hi)].map(|(x, e)| self.node(Op::Same(x, *like, e, i)))
    }
    fn moved_out(&self, moved: &N, from: &N, end: End) -> N {
        self.node(Op::Out(*moved, *from, end))
    }
    fn choose_truth(&self, b: &Bn, why: &'static str) -> Bn {
        if self.const_of(*b).is_some() {
            return *b;
        }
        let i = self.note(&self.choices, why);
        self.bnode(BOp::Free(*b, i))
    }
    fn choose(&self, a: &N, why: &'static str) -> N {
        let i = self.note(&self.choices, why);
        self.node(Op::Free(*a, i))
    }
    fn select_same(&self, c: &Bn, a: &N, b: &N, why: &'static str) -> N {
        let n = self.select(c, a, b);
        if matches!(self.op(n), Op::Sel(..)) {
            self.same.borrow_mut().insert(n, why);
        }
        n
    }
}
