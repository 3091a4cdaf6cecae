//! How a value rounded to nearest becomes a bound, shared by the methods whose published
//! form and `-safe` variant are one algorithm in two arithmetics (`la2011`,
//! `nilsson2012-depth`): the published method keeps every rounded value as it is
//! ([`Nearest`]), the `-safe` variant steps each rounded end one f32 value outward
//! ([`Outward`]). Written over [`F32Arith`], so that the f32 method and its SMT-LIB 2
//! encoding are the same code, and so that one planted slip (an outward step dropped on
//! one side, `crate::bounds::broken::planted`) applies to every method written this way.

use crate::bounds::arith::F32Arith;

/// The rounding discipline of a method written over [`F32Arith`].
pub trait Round: 'static {
    /// A value `<=` the exact result that `x` is the rounding (to nearest) of.
    fn dn<A: F32Arith>(ar: &A, x: &A::F) -> A::F;
    /// A value `>=` it.
    fn up<A: F32Arith>(ar: &A, x: &A::F) -> A::F;
    /// A computed value that must not be used (the quantity falls back to its full range).
    fn bad<A: F32Arith>(ar: &A, x: &A::F) -> A::B;
    /// The `-safe` variant's guards are on: non-finite input gives the full domain before
    /// any arithmetic, and a NaN operand of a min or max makes the result NaN (unknown)
    /// instead of vanishing.
    const GUARD: bool;
}

/// The published arithmetic: round to nearest, no steps; only NaN falls back.
pub struct Nearest;

impl Round for Nearest {
    fn dn<A: F32Arith>(_: &A, x: &A::F) -> A::F {
        x.clone()
    }
    fn up<A: F32Arith>(_: &A, x: &A::F) -> A::F {
        x.clone()
    }
    fn bad<A: F32Arith>(ar: &A, x: &A::F) -> A::B {
        ar.is_nan(x)
    }
    const GUARD: bool = false;
}

/// The `-safe` arithmetic: f32 interval arithmetic (one step outward after each rounded
/// operation); any non-finite value falls back.
pub struct Outward;

impl Round for Outward {
    fn dn<A: F32Arith>(ar: &A, x: &A::F) -> A::F {
        ar.next_down(x)
    }
    fn up<A: F32Arith>(ar: &A, x: &A::F) -> A::F {
        ar.next_up(x)
    }
    fn bad<A: F32Arith>(ar: &A, x: &A::F) -> A::B {
        ar.not(&ar.is_finite(x))
    }
    const GUARD: bool = true;
}

/// `min(a, b)` ([`F32Arith::min`]); with the guards on, a NaN operand gives NaN.
#[inline(always)]
pub fn min_g<R: Round, A: F32Arith>(ar: &A, a: &A::F, b: &A::F) -> A::F {
    guarded::<R, A>(ar, a, b, ar.min(a, b))
}

/// `max(a, b)` ([`F32Arith::max`]); with the guards on, a NaN operand gives NaN.
#[inline(always)]
pub fn max_g<R: Round, A: F32Arith>(ar: &A, a: &A::F, b: &A::F) -> A::F {
    guarded::<R, A>(ar, a, b, ar.max(a, b))
}

#[inline(always)]
fn guarded<R: Round, A: F32Arith>(ar: &A, a: &A::F, b: &A::F, m: A::F) -> A::F {
    if R::GUARD {
        let nan = ar.or(&ar.is_nan(a), &ar.is_nan(b));
        ar.select(&nan, &ar.lit(f32::NAN), &m)
    } else {
        m
    }
}
