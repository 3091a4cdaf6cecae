//! One description, two meanings: the f32 operations a bound is written in, as a trait
//! with two instances. [`Plain`] computes in f32 (what the gate runs); the SMT-LIB2
//! builder of the symbolic search ([`crate::tools::symbolic::smt::Smt`]) emits the same
//! operations, in the same order, as IEEE binary32 terms with round-to-nearest-even.
//! Code written once over [`F32Arith`] is the method and its encoding at the same time,
//! so the two cannot drift apart.
//!
//! Every operation is specified bit for bit, NaN and signed zeros included, so that
//! both instances agree on every input:
//! - `add`, `sub`, `mul`, `div`, `fma` round to nearest, ties to even (IEEE 754);
//! - `min(a, b)` is `b` when `a` is NaN or `b < a`, else `a`; `max(a, b)` is `b` when
//!   `a` is NaN or `b > a`, else `a` (no dependence on the sign of a zero result
//!   beyond this rule, unlike `f32::min`, whose choice between -0 and +0 is left open);
//! - `lt`, `le`, `eq` are IEEE comparisons (false when either side is NaN);
//! - `next_up` / `next_down` are `f32::next_up` / `f32::next_down`.

use crate::model::{Tile, Triangle};

/// Which end of an interval a value is: below (`Lo`) or above (`Hi`) the exact value it
/// encloses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum End {
    Lo,
    Hi,
}

/// The f32 operations a bound's setup and tile test are written in.
pub trait F32Arith {
    /// An f32 value (a number, or a term).
    type F: Clone + std::fmt::Debug;
    /// A truth value (a bool, or a term).
    type B: Clone + std::fmt::Debug;

    fn lit(&self, v: f32) -> Self::F;
    fn add(&self, a: &Self::F, b: &Self::F) -> Self::F;
    fn sub(&self, a: &Self::F, b: &Self::F) -> Self::F;
    fn mul(&self, a: &Self::F, b: &Self::F) -> Self::F;
    fn div(&self, a: &Self::F, b: &Self::F) -> Self::F;
    /// `a * b + c` with one rounding.
    fn fma(&self, a: &Self::F, b: &Self::F, c: &Self::F) -> Self::F;
    fn neg(&self, a: &Self::F) -> Self::F;
    fn abs(&self, a: &Self::F) -> Self::F;
    fn min(&self, a: &Self::F, b: &Self::F) -> Self::F;
    fn max(&self, a: &Self::F, b: &Self::F) -> Self::F;
    fn next_up(&self, a: &Self::F) -> Self::F;
    fn next_down(&self, a: &Self::F) -> Self::F;

    fn lt(&self, a: &Self::F, b: &Self::F) -> Self::B;
    fn le(&self, a: &Self::F, b: &Self::F) -> Self::B;
    fn eq(&self, a: &Self::F, b: &Self::F) -> Self::B;
    fn is_nan(&self, a: &Self::F) -> Self::B;
    fn is_finite(&self, a: &Self::F) -> Self::B;

    fn truth(&self, b: bool) -> Self::B;
    fn and(&self, a: &Self::B, b: &Self::B) -> Self::B;
    fn or(&self, a: &Self::B, b: &Self::B) -> Self::B;
    fn not(&self, a: &Self::B) -> Self::B;
    /// `if c { a } else { b }`.
    fn select(&self, c: &Self::B, a: &Self::F, b: &Self::F) -> Self::F;

    /// `a`, one end (`end`) of an interval enclosing some exact quantity, taken from
    /// here on as an exact value of its own: the code that follows is right for exact
    /// values, and the real-arithmetic lemma named `lemma` carries that to the quantity
    /// the end encloses (the lemmas are listed and checked by `cullproof proofs`). The
    /// enclosure check of the proofs verifies that `a` is such an end; every other
    /// instance returns `a` itself.
    fn pin(&self, a: &Self::F, _end: End, _lemma: &'static str) -> Self::F {
        a.clone()
    }

    /// `v`, the ends of an interval that (by the lemma named `lemma`) holds some exact
    /// quantity (`> 0` when `positive`), taken from here on as a lower and an upper end
    /// of that one quantity. The enclosure check verifies that `v[0]` is a lower end and
    /// `v[1]` an upper end (each of its own exact value); every other instance returns
    /// `v` itself.
    fn pin_range(&self, v: &[Self::F; 2], _positive: bool, _lemma: &'static str) -> [Self::F; 2] {
        v.clone()
    }

    /// `v`, an interval whose ends enclose their own exact value, which by the lemma
    /// named `lemma` equals the exact value of `like` (one quantity written two ways):
    /// from here on a lower and an upper end of `like`'s exact value. The enclosure check
    /// verifies that `v[0]` is a lower end and `v[1]` an upper end (of `v`'s own exact
    /// value); every other instance returns `v` itself.
    fn pin_same(&self, v: &[Self::F; 2], _like: &Self::F, _lemma: &'static str) -> [Self::F; 2] {
        v.clone()
    }

    /// `moved`, a value the code computed from the end `from` by moving it outward
    /// (below it when `end` is `Lo`): from here on an end of `from`'s exact value. The
    /// enclosure check verifies that `from` is such an end and that `moved` cannot cross
    /// it (`from` less a literal `>= 0` for a lower end, plus one for an upper end: the
    /// rounding of a real beyond an f32 value stays beyond it); every other instance
    /// returns `moved` itself.
    fn moved_out(&self, moved: &Self::F, _from: &Self::F, _end: End) -> Self::F {
        moved.clone()
    }

    /// `a`, a value the code is free to choose (any f32 value would keep the method
    /// right, `why` says why), taken from here on as an exact value of its own; the
    /// enclosure check demands nothing of it. Every instance but the check returns `a`.
    fn choose(&self, a: &Self::F, _why: &'static str) -> Self::F {
        a.clone()
    }

    /// `b`, a condition the code is free to choose (`why`): it only ever turns a cull
    /// off, so the method's derivation does not rest on it. The enclosure check demands
    /// nothing of its exact counterpart where it restricts a cull; inside, its f32 truth
    /// is a fact (a lemma about the code may take it as a hypothesis). Every instance
    /// but the check returns `b`.
    fn choose_truth(&self, b: &Self::B, _why: &'static str) -> Self::B {
        b.clone()
    }

    /// `if c { a } else { b }` where, by the code's own argument `why`, both branches
    /// have one exact value wherever `c` holds (a shortcut: an exact 0 operand, a time
    /// at a shutter end, a vertex whose inputs are equal at both ends). The enclosure
    /// check verifies that argument (the two exact values agree as polynomials under the
    /// equalities `c` states) and takes `b`'s exact value for the select's; every other
    /// instance selects.
    fn select_same(&self, c: &Self::B, a: &Self::F, b: &Self::F, _why: &'static str) -> Self::F {
        self.select(c, a, b)
    }

    /// `[a && f()[0], .., a && f()[K - 1]]` for a pure `f`: the f32 instance evaluates
    /// `f` only where `a` holds (a short-circuit conjunction, the same truth values);
    /// every other instance evaluates it always and records the conjunctions.
    fn and_each<const K: usize>(&self, a: &Self::B, f: impl FnOnce() -> [Self::B; K]) -> [Self::B; K] {
        f().map(|b| self.and(a, &b))
    }

    /// `min(a, b)`, NaN when either is NaN (where [`F32Arith::min`] drops a NaN first
    /// operand).
    fn min_nan(&self, a: &Self::F, b: &Self::F) -> Self::F {
        let nan = self.or(&self.is_nan(a), &self.is_nan(b));
        self.select(&nan, &self.lit(f32::NAN), &self.min(a, b))
    }
    /// `max(a, b)`, NaN when either is NaN.
    fn max_nan(&self, a: &Self::F, b: &Self::F) -> Self::F {
        let nan = self.or(&self.is_nan(a), &self.is_nan(b));
        self.select(&nan, &self.lit(f32::NAN), &self.max(a, b))
    }
    /// `a > b`.
    fn gt(&self, a: &Self::F, b: &Self::F) -> Self::B {
        self.lt(b, a)
    }
    /// The conjunction of many truth values (true when there are none).
    fn all(&self, bs: &[Self::B]) -> Self::B {
        bs.iter().fold(self.truth(true), |acc, b| self.and(&acc, b))
    }
    /// The disjunction of many truth values (false when there are none).
    fn any(&self, bs: &[Self::B]) -> Self::B {
        bs.iter().fold(self.truth(false), |acc, b| self.or(&acc, b))
    }
}

/// The f32 instance: the method as the gate runs it.
#[derive(Clone, Copy, Debug, Default)]
pub struct Plain;

impl F32Arith for Plain {
    type F = f32;
    type B = bool;

    #[inline]
    fn lit(&self, v: f32) -> f32 {
        v
    }
    #[inline]
    fn add(&self, a: &f32, b: &f32) -> f32 {
        a + b
    }
    #[inline]
    fn sub(&self, a: &f32, b: &f32) -> f32 {
        a - b
    }
    #[inline]
    fn mul(&self, a: &f32, b: &f32) -> f32 {
        a * b
    }
    #[inline]
    fn div(&self, a: &f32, b: &f32) -> f32 {
        a / b
    }
    #[inline]
    fn fma(&self, a: &f32, b: &f32, c: &f32) -> f32 {
        a.mul_add(*b, *c)
    }
    #[inline]
    fn neg(&self, a: &f32) -> f32 {
        -a
    }
    #[inline]
    fn abs(&self, a: &f32) -> f32 {
        a.abs()
    }
    #[inline]
    fn min(&self, a: &f32, b: &f32) -> f32 {
        if a.is_nan() || b < a {
            *b
        } else {
            *a
        }
    }
    #[inline]
    fn max(&self, a: &f32, b: &f32) -> f32 {
        if a.is_nan() || b > a {
            *b
        } else {
            *a
        }
    }
    #[inline(always)]
    fn and_each<const K: usize>(&self, a: &bool, f: impl FnOnce() -> [bool; K]) -> [bool; K] {
        if *a {
            f()
        } else {
            [false; K]
        }
    }
    #[inline(always)]
    fn min_nan(&self, a: &f32, b: &f32) -> f32 {
        if a.is_nan() || b.is_nan() {
            f32::NAN
        } else if *b < *a {
            *b
        } else {
            *a
        }
    }
    #[inline(always)]
    fn max_nan(&self, a: &f32, b: &f32) -> f32 {
        if a.is_nan() || b.is_nan() {
            f32::NAN
        } else if *b > *a {
            *b
        } else {
            *a
        }
    }
    #[inline]
    fn next_up(&self, a: &f32) -> f32 {
        a.next_up()
    }
    #[inline]
    fn next_down(&self, a: &f32) -> f32 {
        a.next_down()
    }
    #[inline]
    fn lt(&self, a: &f32, b: &f32) -> bool {
        a < b
    }
    #[inline]
    fn le(&self, a: &f32, b: &f32) -> bool {
        a <= b
    }
    #[inline]
    fn eq(&self, a: &f32, b: &f32) -> bool {
        a == b
    }
    #[inline]
    fn is_nan(&self, a: &f32) -> bool {
        a.is_nan()
    }
    #[inline]
    fn is_finite(&self, a: &f32) -> bool {
        a.is_finite()
    }
    #[inline]
    fn truth(&self, b: bool) -> bool {
        b
    }
    #[inline]
    fn and(&self, a: &bool, b: &bool) -> bool {
        *a && *b
    }
    #[inline]
    fn or(&self, a: &bool, b: &bool) -> bool {
        *a || *b
    }
    #[inline]
    fn not(&self, a: &bool) -> bool {
        !a
    }
    #[inline]
    fn select(&self, c: &bool, a: &f32, b: &f32) -> f32 {
        if *c {
            *a
        } else {
            *b
        }
    }
}

/// A triangle whose numbers are values of some [`F32Arith`] (f32 numbers or terms),
/// laid out as [`Triangle`].
#[derive(Clone, Debug)]
pub struct TriOf<T> {
    pub q: [[T; 4]; 3],
    pub r: [[T; 4]; 3],
    pub c0: [T; 3],
    pub c1: [T; 3],
    pub k: T,
}

impl TriOf<f32> {
    /// The plain triangle's numbers.
    pub fn of(t: &Triangle) -> Self {
        TriOf { q: t.q, r: t.r, c0: t.c0, c1: t.c1, k: t.k }
    }
    /// Back to a [`Triangle`].
    pub fn triangle(&self) -> Triangle {
        Triangle { q: self.q, r: self.r, c0: self.c0, c1: self.c1, k: self.k }
    }
}

impl<T: Clone> TriOf<T> {
    /// The same triangle with every number mapped.
    pub fn map<U>(&self, f: impl Fn(&T) -> U) -> TriOf<U> {
        TriOf {
            q: self.q.each_ref().map(|p| p.each_ref().map(&f)),
            r: self.r.each_ref().map(|p| p.each_ref().map(&f)),
            c0: self.c0.each_ref().map(&f),
            c1: self.c1.each_ref().map(&f),
            k: f(&self.k),
        }
    }
}

/// A tile's edges `[x0, y0, x1, y1]` as values of some [`F32Arith`].
pub fn tile_of(t: &Tile) -> [f32; 4] {
    [t.x0, t.y0, t.x1, t.y1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_min_max_follow_the_stated_rule() {
        let p = Plain;
        assert_eq!(p.min(&f32::NAN, &1.0), 1.0);
        assert!(p.min(&1.0, &f32::NAN) == 1.0);
        assert_eq!(p.max(&f32::NAN, &-1.0), -1.0);
        assert_eq!(p.min(&2.0, &-3.0), -3.0);
        assert_eq!(p.max(&2.0, &-3.0), 2.0);
        // equal values keep the first (the sign of a zero included)
        assert!(p.min(&-0.0, &0.0).is_sign_negative());
        assert!(p.max(&0.0, &-0.0).is_sign_positive());
    }
}
