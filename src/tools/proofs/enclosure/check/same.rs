//! Shortcuts of one exact value ([`crate::bounds::arith::F32Arith::select_same`]): a
//! select whose two branches the code declares equal in real arithmetic wherever its
//! condition holds. The check verifies it: the condition's equalities become a
//! substitution (an input equal to an input or a literal; an exact value both of whose
//! ends, a lower and an upper one, equal 0, or one exact end equal to 0, is 0), and the
//! two branches' exact values, expanded as polynomials with rational coefficients over
//! the inputs (every other operation an opaque atom), must be the same polynomial under
//! it, in every case the condition's disjunctions allow. A shortcut it cannot show is a
//! failure.

use super::{Check, Pre, Real, Ri, ROOT};
use crate::tools::proofs::enclosure::trace::{BOp, Bn};
use num_bigint::BigInt;
use num_rational::BigRational;
use std::collections::{BTreeMap, HashMap};

/// A monomial: atoms (exact values) with their exponents, sorted.
type Mono = Vec<(Ri, u32)>;

/// A polynomial with rational coefficients (no zero coefficient stored).
#[derive(Clone, Debug, PartialEq, Default)]
struct Poly(BTreeMap<Mono, BigRational>);

impl Poly {
    fn konst(q: BigRational) -> Poly {
        let mut m = BTreeMap::new();
        if q != BigRational::from_integer(BigInt::from(0)) {
            m.insert(vec![], q);
        }
        Poly(m)
    }
    fn atom(r: Ri) -> Poly {
        Poly(BTreeMap::from([(vec![(r, 1)], BigRational::from_integer(BigInt::from(1)))]))
    }
    fn put(m: &mut BTreeMap<Mono, BigRational>, k: Mono, q: BigRational) {
        let zero = BigRational::from_integer(BigInt::from(0));
        let v = m.remove(&k).unwrap_or_else(|| zero.clone()) + q;
        if v != zero {
            m.insert(k, v);
        }
    }
    fn add(&self, o: &Poly) -> Poly {
        let mut m = self.0.clone();
        for (k, q) in &o.0 {
            Poly::put(&mut m, k.clone(), q.clone());
        }
        Poly(m)
    }
    fn neg(&self) -> Poly {
        Poly(self.0.iter().map(|(k, q)| (k.clone(), -q.clone())).collect())
    }
    fn mul(&self, o: &Poly) -> Poly {
        let mut m = BTreeMap::new();
        for (ka, qa) in &self.0 {
            for (kb, qb) in &o.0 {
                let mut k: BTreeMap<Ri, u32> = ka.iter().copied().collect();
                for &(r, e) in kb {
                    *k.entry(r).or_insert(0) += e;
                }
                Poly::put(&mut m, k.into_iter().collect(), qa * qb);
            }
        }
        Poly(m)
    }
}

/// At most this many cases of a condition's disjunctions are tried (more: not shown).
const MAX_CASES: usize = 64;

impl Check<'_> {
    /// Whether the exact values `ra` and `rb` are one value wherever `c` holds, as far
    /// as its equalities show.
    pub(super) fn same_under(&self, c: Bn, ra: Ri, rb: Ri) -> bool {
        let Some(cases) = self.eq_cases(c) else {
            return false;
        };
        cases.iter().all(|terms| {
            let subst = self.subst_of(terms);
            let mut memo = HashMap::new();
            self.poly(ra, &subst, &mut memo) == self.poly(rb, &subst, &mut memo)
        })
    }

    /// The condition as a disjunction of conjunctions of its equalities (other terms
    /// dropped: a hypothesis less only makes the proof harder); None beyond
    /// [`MAX_CASES`].
    fn eq_cases(&self, c: Bn) -> Option<Vec<Vec<Bn>>> {
        Some(match self.t.bop(c) {
            BOp::And(x, y) => {
                let (a, b) = (self.eq_cases(x)?, self.eq_cases(y)?);
                if a.len() * b.len() > MAX_CASES {
                    return None;
                }
                a.iter().flat_map(|p| b.iter().map(move |q| [p.clone(), q.clone()].concat())).collect()
            }
            BOp::Or(x, y) => {
                let v = [self.eq_cases(x)?, self.eq_cases(y)?].concat();
                if v.len() > MAX_CASES {
                    return None;
                }
                v
            }
            BOp::Free(x, _) => self.eq_cases(x)?,
            BOp::Eq(..) => vec![vec![c]],
            _ => vec![vec![]],
        })
    }

    /// The substitution the equalities `terms` give (see the module doc).
    fn subst_of(&self, terms: &[Bn]) -> HashMap<Ri, Poly> {
        let t = self.t;
        let mut subst = HashMap::new();
        // Exact values with an end equal to 0: which sides.
        let mut zero_ends: HashMap<Ri, (bool, bool)> = HashMap::new();
        for &b in terms {
            let BOp::Eq(x, y) = t.bop(b) else { continue };
            let (dx, dy) = (self.dir(x, ROOT), self.dir(y, ROOT));
            let exact = |d: super::Dir| !d.rounded && d.pre == Pre::Exact;
            if exact(dx) && exact(dy) {
                let (rx, ry) = (self.real(x), self.real(y));
                let mut memo = HashMap::new();
                if matches!(self.rget(rx), Real::Var(_)) {
                    let p = self.poly(ry, &subst, &mut memo);
                    subst.insert(rx, p);
                } else if matches!(self.rget(ry), Real::Var(_)) {
                    let p = self.poly(rx, &subst, &mut memo);
                    subst.insert(ry, p);
                }
                continue;
            }
            for (v, k) in [(x, y), (y, x)] {
                if t.lit_of(k) != Some(0.0) {
                    continue;
                }
                let d = self.dir(v, ROOT);
                if d.rounded {
                    continue;
                }
                let e = zero_ends.entry(self.real(v)).or_insert((false, false));
                match d.pre {
                    Pre::Lo => e.0 = true,
                    Pre::Hi => e.1 = true,
                    Pre::Exact => *e = (true, true),
                    _ => {}
                }
            }
        }
        for (r, (lo, hi)) in zero_ends {
            if lo && hi {
                subst.insert(r, Poly::default());
            }
        }
        subst
    }

    /// The exact value `r` as a polynomial over its inputs (and opaque atoms), with
    /// `subst` applied.
    fn poly(&self, r: Ri, subst: &HashMap<Ri, Poly>, memo: &mut HashMap<Ri, Poly>) -> Poly {
        if let Some(p) = subst.get(&r).or_else(|| memo.get(&r)) {
            return p.clone();
        }
        let p = match self.rget(r) {
            Real::K(b) => match BigRational::from_float(f32::from_bits(b) as f64) {
                Some(q) => Poly::konst(q),
                None => Poly::atom(r),
            },
            Real::Add(a, b) => self.poly(a, subst, memo).add(&self.poly(b, subst, memo)),
            Real::Sub(a, b) => self.poly(a, subst, memo).add(&self.poly(b, subst, memo).neg()),
            Real::Mul(a, b) => self.poly(a, subst, memo).mul(&self.poly(b, subst, memo)),
            Real::Neg(a) => self.poly(a, subst, memo).neg(),
            _ => Poly::atom(r),
        };
        memo.insert(r, p.clone());
        p
    }
}
