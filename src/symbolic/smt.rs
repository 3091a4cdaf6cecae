//! The SMT-LIB2 instance of [`F32Arith`]: every operation becomes one named constant
//! and its defining equation (`(declare-const tN ...)`, `(assert (= tN ...))`) in the
//! IEEE floating-point theory, binary32, round-to-nearest-even, in the order the code
//! performs it. Naming each step keeps the script as long as the computation (a term
//! shared by later steps is written once); z3 4.8 expands `define-fun` macros as
//! trees, which a running minimum (each step names the previous one twice) turns
//! exponential.

use super::arith::F32Arith;
use std::cell::RefCell;

/// The sort of an f32 value.
pub const F32: &str = "(_ FloatingPoint 8 24)";

/// The SMT-LIB2 literal of an f32 value, bit for bit (`(fp sign exponent significand)`;
/// every NaN is the one NaN of the theory).
pub fn lit(v: f32) -> String {
    if v.is_nan() {
        return "(_ NaN 8 24)".into();
    }
    let b = v.to_bits();
    format!("(fp #b{} #b{:08b} #b{:023b})", b >> 31, (b >> 23) & 0xff, b & 0x7f_ffff)
}

/// A script under construction: declarations, definitions and assertions, in order.
#[derive(Debug, Default)]
pub struct Smt {
    lines: RefCell<Vec<String>>,
    next: RefCell<usize>,
}

impl Smt {
    pub fn new() -> Self {
        Smt::default()
    }

    fn define(&self, sort: &str, body: String) -> String {
        let mut n = self.next.borrow_mut();
        let name = format!("t{}", *n);
        *n += 1;
        let mut l = self.lines.borrow_mut();
        l.push(format!("(declare-const {name} {sort})"));
        l.push(format!("(assert (= {name} {body}))"));
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

    /// The whole script: the definitions so far, then `check-sat` and the values of `show`.
    pub fn script(&self, show: &[String]) -> String {
        let mut s = String::from("(set-logic QF_FPBV)\n");
        for l in self.lines.borrow().iter() {
            s += l;
            s.push('\n');
        }
        s += "(check-sat)\n";
        if !show.is_empty() {
            s += &format!("(get-value ({}))\n", show.join(" "));
        }
        s
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
        lit(v)
    }
    fn add(&self, a: &String, b: &String) -> String {
        self.f(format!("(fp.add RNE {a} {b})"))
    }
    fn sub(&self, a: &String, b: &String) -> String {
        self.f(format!("(fp.sub RNE {a} {b})"))
    }
    fn mul(&self, a: &String, b: &String) -> String {
        self.f(format!("(fp.mul RNE {a} {b})"))
    }
    fn div(&self, a: &String, b: &String) -> String {
        self.f(format!("(fp.div RNE {a} {b})"))
    }
    fn fma(&self, a: &String, b: &String, c: &String) -> String {
        self.f(format!("(fp.fma RNE {a} {b} {c})"))
    }
    fn neg(&self, a: &String) -> String {
        self.f(format!("(fp.neg {a})"))
    }
    fn abs(&self, a: &String) -> String {
        self.f(format!("(fp.abs {a})"))
    }
    fn min(&self, a: &String, b: &String) -> String {
        self.f(format!("(ite (or (fp.isNaN {a}) (fp.lt {b} {a})) {b} {a})"))
    }
    fn max(&self, a: &String, b: &String) -> String {
        self.f(format!("(ite (or (fp.isNaN {a}) (fp.gt {b} {a})) {b} {a})"))
    }
    fn next_up(&self, a: &String) -> String {
        // On the bits: a zero goes to the smallest subnormal, a positive value one
        // step up, a negative one one step down (towards -0); NaN and +inf stay.
        self.f(format!(
            "(ite (or (fp.isNaN {a}) (and (fp.isInfinite {a}) (fp.isPositive {a}))) {a} \
             (ite (fp.isZero {a}) (fp #b0 #b00000000 #b00000000000000000000001) \
             ((_ to_fp 8 24) (ite (fp.isPositive {a}) (bvadd (fp.to_ieee_bv {a}) #x00000001) \
             (bvsub (fp.to_ieee_bv {a}) #x00000001)))))"
        ))
    }
    fn next_down(&self, a: &String) -> String {
        self.f(format!(
            "(ite (or (fp.isNaN {a}) (and (fp.isInfinite {a}) (fp.isNegative {a}))) {a} \
             (ite (fp.isZero {a}) (fp #b1 #b00000000 #b00000000000000000000001) \
             ((_ to_fp 8 24) (ite (fp.isNegative {a}) (bvadd (fp.to_ieee_bv {a}) #x00000001) \
             (bvsub (fp.to_ieee_bv {a}) #x00000001)))))"
        ))
    }
    fn lt(&self, a: &String, b: &String) -> String {
        self.b(format!("(fp.lt {a} {b})"))
    }
    fn le(&self, a: &String, b: &String) -> String {
        self.b(format!("(fp.leq {a} {b})"))
    }
    fn eq(&self, a: &String, b: &String) -> String {
        self.b(format!("(fp.eq {a} {b})"))
    }
    fn is_nan(&self, a: &String) -> String {
        self.b(format!("(fp.isNaN {a})"))
    }
    fn is_finite(&self, a: &String) -> String {
        self.b(format!("(not (or (fp.isNaN {a}) (fp.isInfinite {a})))"))
    }
    fn truth(&self, b: bool) -> String {
        b.to_string()
    }
    fn and(&self, a: &String, b: &String) -> String {
        self.b(format!("(and {a} {b})"))
    }
    fn or(&self, a: &String, b: &String) -> String {
        self.b(format!("(or {a} {b})"))
    }
    fn not(&self, a: &String) -> String {
        self.b(format!("(not {a})"))
    }
    fn select(&self, c: &String, a: &String, b: &String) -> String {
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
    }
}
