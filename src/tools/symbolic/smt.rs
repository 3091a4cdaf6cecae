//! The SMT-LIB2 instance of [`F32Arith`]: every operation becomes one named constant
//! and its defining equation (`(declare-const tN ...)`, `(assert (= tN ...))`) in the
//! IEEE floating-point theory, binary32, round-to-nearest-even, in the order the code
//! performs it. Naming each step keeps the script as long as the computation (a term
//! shared by later steps is written once); z3 4.8 expands `define-fun` macros as
//! trees, which a running minimum (each step names the previous one twice) turns
//! exponential.
//!
//! [`Smt::folding`] builds a script that folds what is already known: an operation whose
//! operands are all literals is computed by [`Plain`] (the f32 meaning, which the tests
//! check against z3's evaluation of the same terms bit for bit) and becomes a literal, and
//! a step whose text was already written is shared instead of written twice. The script
//! then holds only the steps that depend on a free input, in the code's order: a query
//! with some inputs fixed (the concolic search of [`super::concolic`]) is as small as its
//! free part.

use crate::bounds::arith::{F32Arith, Plain};
use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap};

/// The sort of an f32 value.
pub const F32: &str = "(_ FloatingPoint 8 24)";
/// 2^-149, the smallest positive f32, and its negation; f32::MAX and its negation.
const TINY: &str = "(fp #b0 #b00000000 #b00000000000000000000001)";
const NEG_TINY: &str = "(fp #b1 #b00000000 #b00000000000000000000001)";
const MAX: &str = "(fp #b0 #b11111110 #b11111111111111111111111)";
const NEG_MAX: &str = "(fp #b1 #b11111110 #b11111111111111111111111)";

/// The SMT-LIB2 literal of an f32 value, bit for bit (`(fp sign exponent significand)`;
/// every NaN is the one NaN of the theory).
pub fn lit(v: f32) -> String {
    if v.is_nan() {
        return "(_ NaN 8 24)".into();
    }
    let b = v.to_bits();
    format!("(fp #b{} #b{:08b} #b{:023b})", b >> 31, (b >> 23) & 0xff, b & 0x7f_ffff)
}

/// The f32 value of a literal written by [`lit`] (None for any other term).
pub fn parse_lit(s: &str) -> Option<f32> {
    if s == "(_ NaN 8 24)" {
        return Some(f32::NAN);
    }
    let r = s.strip_prefix("(fp #b")?.strip_suffix(')')?;
    let bits: String = r.split(" #b").collect();
    if bits.len() != 32 || !bits.bytes().all(|c| c == b'0' || c == b'1') {
        return None;
    }
    u32::from_str_radix(&bits, 2).ok().map(f32::from_bits)
}

/// The truth value of a literal `true` / `false`.
fn parse_truth(s: &str) -> Option<bool> {
    match s {
        "true" => Some(true),
        "false" => Some(false),
        _ => None,
    }
}

/// A script under construction: declarations, definitions and assertions, in order.
#[derive(Debug, Default)]
pub struct Smt {
    lines: RefCell<Vec<String>>,
    next: RefCell<usize>,
    /// Fold literal operands and share repeated steps (see the module doc).
    fold: bool,
    /// The step already named for a (sort, body), when folding.
    seen: RefCell<HashMap<(String, String), String>>,
    /// The bits of every literal the code asked for ([`F32Arith::lit`]).
    lits: RefCell<BTreeSet<u32>>,
    /// Each named step's line (its `declare-const`; its defining `assert` follows).
    defs: RefCell<HashMap<String, usize>>,
}

impl Smt {
    pub fn new() -> Self {
        Smt::default()
    }

    /// A builder that folds operations on literals (computed by [`Plain`]) and shares
    /// repeated steps.
    pub fn folding() -> Self {
        Smt { fold: true, ..Smt::default() }
    }

    /// Every literal value the code used so far, in the order of their bits (the
    /// method's and the template's constants: the concolic search draws fixed inputs
    /// from them).
    pub fn literals(&self) -> Vec<f32> {
        self.lits.borrow().iter().map(|b| f32::from_bits(*b)).collect()
    }

    /// With folding, the literal of `f` applied to the values of `args` when all of
    /// them are literals.
    fn fold_f(&self, args: &[&String], f: impl FnOnce(&[f32]) -> f32) -> Option<String> {
        if !self.fold {
            return None;
        }
        let v: Option<Vec<f32>> = args.iter().map(|a| parse_lit(a)).collect();
        v.map(|v| lit(f(&v)))
    }
    /// The same for a truth value.
    fn fold_b(&self, args: &[&String], f: impl FnOnce(&[f32]) -> bool) -> Option<String> {
        if !self.fold {
            return None;
        }
        let v: Option<Vec<f32>> = args.iter().map(|a| parse_lit(a)).collect();
        v.map(|v| f(&v).to_string())
    }

    fn define(&self, sort: &str, body: String) -> String {
        if self.fold {
            if let Some(name) = self.seen.borrow().get(&(sort.to_string(), body.clone())) {
                return name.clone();
            }
        }
        let key = self.fold.then(|| (sort.to_string(), body.clone()));
        let mut n = self.next.borrow_mut();
        let name = format!("t{}", *n);
        *n += 1;
        let mut l = self.lines.borrow_mut();
        self.defs.borrow_mut().insert(name.clone(), l.len());
        l.push(format!("(declare-const {name} {sort})"));
        l.push(format!("(assert (= {name} {body}))"));
        if let Some(k) = key {
            self.seen.borrow_mut().insert(k, name.clone());
        }
        name
    }
    fn f(&self, body: String) -> String {
        self.define(F32, body)
    }
    fn b(&self, body: String) -> String {
        self.define("Bool", body)
    }

    /// A free f32 variable (an input the solver chooses), excluding NaN and the infinities.
    pub fn var(&self, name: &str) -> String {
        let mut l = self.lines.borrow_mut();
        l.push(format!("(declare-const {name} {F32})"));
        l.push(format!("(assert (not (or (fp.isNaN {name}) (fp.isInfinite {name}))))"));
        name.to_string()
    }

    /// Add a raw line (an assertion, a definition in another sort).
    pub fn push(&self, line: String) {
        self.lines.borrow_mut().push(line);
    }

    /// Assert a truth value.
    pub fn assert(&self, b: &str) {
        self.push(format!("(assert {b})"));
    }

    /// Assert `lo <= v < hi` (the half-open range a query declares for an input).
    pub fn range(&self, v: &str, lo: f32, hi: f32) {
        self.push(format!("(assert (and (fp.leq {} {v}) (fp.lt {v} {})))", lit(lo), lit(hi)));
    }

    /// The lines to write: all of them; with folding, only the named steps that an
    /// assertion (or a shown value) depends on. A step nothing depends on is a fresh
    /// constant equal to a total function of others, which any model can satisfy, so
    /// dropping it changes no answer (the method's code computes it, the query does
    /// not ask about it: e.g. the y axis of a box when only its x side is attacked).
    fn live_lines(&self, show: &[String]) -> Vec<bool> {
        let lines = self.lines.borrow();
        let defs = self.defs.borrow();
        let n = lines.len();
        if !self.fold {
            return vec![true; n];
        }
        let mut keep = vec![true; n];
        for &i in defs.values() {
            keep[i] = false;
            keep[i + 1] = false;
        }
        let words = |l: &str| -> Vec<String> {
            l.split(|c: char| c.is_whitespace() || c == '(' || c == ')')
                .filter(|w| !w.is_empty())
                .map(String::from)
                .collect()
        };
        let mut stack: Vec<String> = show.to_vec();
        for (i, l) in lines.iter().enumerate() {
            if keep[i] {
                stack.extend(words(l));
            }
        }
        while let Some(w) = stack.pop() {
            if let Some(&i) = defs.get(&w) {
                if !keep[i] {
                    keep[i] = true;
                    keep[i + 1] = true;
                    stack.extend(words(&lines[i + 1]));
                }
            }
        }
        keep
    }

    /// The whole script: the definitions so far (with folding, those the assertions
    /// depend on), then `check-sat` and the values of `show`.
    pub fn script(&self, show: &[String]) -> String {
        let mut s = String::from("(set-logic QF_BVFP)\n");
        let keep = self.live_lines(show);
        for (l, k) in self.lines.borrow().iter().zip(keep) {
            if k {
                s += l;
                s.push('\n');
            }
        }
        s += "(check-sat)\n";
        if !show.is_empty() {
            s += &format!("(get-value ({}))\n", show.join(" "));
        }
        s
    }

    /// `(OP MODE a b)` with a directed rounding mode (the exact side of a query, not the
    /// method): `fp.add`, `fp.sub`, `fp.mul` or `fp.div`.
    pub fn op_mode(&self, op: &str, mode: &str, a: &str, b: &str) -> String {
        self.f(format!("({op} {mode} {a} {b})"))
    }

    /// A term with a directed rounding mode (the exact side of a query, not the method).
    pub fn fma_mode(&self, mode: &str, a: &str, b: &str, c: &str) -> String {
        self.f(format!("(fp.fma {mode} {a} {b} {c})"))
    }
}

impl F32Arith for Smt {
    type F = String;
    type B = String;

    fn lit(&self, v: f32) -> String {
        self.lits.borrow_mut().insert(v.to_bits());
        lit(v)
    }
    fn add(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.add(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(fp.add RNE {a} {b})"))
    }
    fn sub(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.sub(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(fp.sub RNE {a} {b})"))
    }
    fn mul(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.mul(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(fp.mul RNE {a} {b})"))
    }
    fn div(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.div(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(fp.div RNE {a} {b})"))
    }
    fn fma(&self, a: &String, b: &String, c: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b, c], |v| Plain.fma(&v[0], &v[1], &v[2])) {
            return l;
        }
        self.f(format!("(fp.fma RNE {a} {b} {c})"))
    }
    fn neg(&self, a: &String) -> String {
        if let Some(l) = self.fold_f(&[a], |v| Plain.neg(&v[0])) {
            return l;
        }
        self.f(format!("(fp.neg {a})"))
    }
    fn abs(&self, a: &String) -> String {
        if let Some(l) = self.fold_f(&[a], |v| Plain.abs(&v[0])) {
            return l;
        }
        self.f(format!("(fp.abs {a})"))
    }
    fn min(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.min(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(ite (or (fp.isNaN {a}) (fp.lt {b} {a})) {b} {a})"))
    }
    fn max(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_f(&[a, b], |v| Plain.max(&v[0], &v[1])) {
            return l;
        }
        self.f(format!("(ite (or (fp.isNaN {a}) (fp.gt {b} {a})) {b} {a})"))
    }
    fn next_up(&self, a: &String) -> String {
        if let Some(l) = self.fold_f(&[a], |v| Plain.next_up(&v[0])) {
            return l;
        }
        // In floating-point terms only (standard SMT-LIB has no float-to-bits
        // conversion): rounding a + 2^-149 upwards gives the next float above a, for
        // every a but two, which are spelt out: -inf goes to -MAX (the sum stays -inf)
        // and -2^-149 goes to -0 (the exact sum is +0).
        self.f(format!(
            "(ite (= {a} (_ -oo 8 24)) {NEG_MAX} (ite (= {a} {NEG_TINY}) (_ -zero 8 24) \
             (fp.add RTP {a} {TINY})))"
        ))
    }
    fn next_down(&self, a: &String) -> String {
        if let Some(l) = self.fold_f(&[a], |v| Plain.next_down(&v[0])) {
            return l;
        }
        // The mirror image: +inf goes to MAX and 2^-149 to +0.
        self.f(format!(
            "(ite (= {a} (_ +oo 8 24)) {MAX} (ite (= {a} {TINY}) (_ +zero 8 24) \
             (fp.sub RTN {a} {TINY})))"
        ))
    }
    fn lt(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_b(&[a, b], |v| Plain.lt(&v[0], &v[1])) {
            return l;
        }
        self.b(format!("(fp.lt {a} {b})"))
    }
    fn le(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_b(&[a, b], |v| Plain.le(&v[0], &v[1])) {
            return l;
        }
        self.b(format!("(fp.leq {a} {b})"))
    }
    fn eq(&self, a: &String, b: &String) -> String {
        if let Some(l) = self.fold_b(&[a, b], |v| Plain.eq(&v[0], &v[1])) {
            return l;
        }
        self.b(format!("(fp.eq {a} {b})"))
    }
    fn is_nan(&self, a: &String) -> String {
        if let Some(l) = self.fold_b(&[a], |v| Plain.is_nan(&v[0])) {
            return l;
        }
        self.b(format!("(fp.isNaN {a})"))
    }
    fn is_finite(&self, a: &String) -> String {
        if let Some(l) = self.fold_b(&[a], |v| Plain.is_finite(&v[0])) {
            return l;
        }
        self.b(format!("(not (or (fp.isNaN {a}) (fp.isInfinite {a})))"))
    }
    fn truth(&self, b: bool) -> String {
        b.to_string()
    }
    fn and(&self, a: &String, b: &String) -> String {
        if self.fold {
            match (parse_truth(a), parse_truth(b)) {
                (Some(false), _) | (_, Some(false)) => return "false".into(),
                (Some(true), _) => return b.clone(),
                (_, Some(true)) => return a.clone(),
                _ => {}
            }
        }
        self.b(format!("(and {a} {b})"))
    }
    fn or(&self, a: &String, b: &String) -> String {
        if self.fold {
            match (parse_truth(a), parse_truth(b)) {
                (Some(true), _) | (_, Some(true)) => return "true".into(),
                (Some(false), _) => return b.clone(),
                (_, Some(false)) => return a.clone(),
                _ => {}
            }
        }
        self.b(format!("(or {a} {b})"))
    }
    fn not(&self, a: &String) -> String {
        if let Some(v) = parse_truth(a).filter(|_| self.fold) {
            return (!v).to_string();
        }
        self.b(format!("(not {a})"))
    }
    fn select(&self, c: &String, a: &String, b: &String) -> String {
        if self.fold {
            match parse_truth(c) {
                Some(true) => return a.clone(),
                Some(false) => return b.clone(),
                None if a == b => return a.clone(),
                None => {}
            }
        }
        self.f(format!("(ite {c} {a} {b})"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_carry_the_bits() {
        assert_eq!(lit(1.0), "(fp #b0 #b01111111 #b00000000000000000000000)");
        assert_eq!(lit(-0.0), "(fp #b1 #b00000000 #b00000000000000000000000)");
        assert_eq!(lit(f32::NAN), "(_ NaN 8 24)");
        for v in [1.0f32, -0.0, 3.5e-42, f32::MAX, f32::NEG_INFINITY] {
            assert_eq!(parse_lit(&lit(v)).unwrap().to_bits(), v.to_bits());
        }
        assert!(parse_lit("t3").is_none());
    }

    #[test]
    fn folding_computes_literals_and_shares_steps() {
        let s = Smt::folding();
        let (a, b) = (s.lit(1.0), s.lit(3.0));
        assert_eq!(s.div(&a, &b), lit(1.0f32 / 3.0));
        assert_eq!(s.lt(&a, &b), "true");
        let x = s.var("x");
        let (p, q) = (s.add(&x, &a), s.add(&x, &a));
        assert_eq!(p, q);
        assert_eq!(s.and(&s.truth(true), &s.lt(&x, &a)), s.lt(&x, &a));
        assert_eq!(s.select(&s.truth(false), &a, &x), x);
        assert_eq!(s.literals(), vec![1.0, 3.0]);
        // a step no assertion depends on is left out of the script
        let dead = s.mul(&x, &x);
        s.assert(&s.lt(&p, &b));
        let script = s.script(&[]);
        assert!(script.contains(&format!("(declare-const {p} ")), "{script}");
        assert!(!script.contains(&format!("(declare-const {dead} ")), "{script}");
        // without folding every step is written
        let u = Smt::new();
        let y = u.var("y");
        assert_ne!(u.add(&y, &u.lit(1.0)), u.add(&y, &u.lit(1.0)));
    }
}
