//! The enclosure check of `cullproof proofs` (the composition of a `-safe` variant's
//! rounding argument, checked over the method's own code for every input), and an
//! independent attack on what it concludes.
//!
//! The attack runs the same code over [`Pair`], an arithmetic of its own: every value
//! is the f32 result (as the gate computes it) together with the exact rational value of
//! the same operations without rounding or steps, along the branches the f32 code takes,
//! pins taken as exact from there on. Where the check says "this output is a lower end",
//! the f32 value must be `<=` that exact value, on every input drawn.

use cullproof::bounds::arith::{End, F32Arith, TriOf};
use cullproof::bounds::broken::planted::{NoDn, NoUp};
use cullproof::bounds::la2011::{setup_of, tile_answer};
use cullproof::bounds::round::{Outward, Round};
use cullproof::cases::generate::{boundary_tile, physical_case, Regime};
use cullproof::tools::proofs::enclosure::check;
use num_bigint::BigInt;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::RefCell;
use std::cmp::Ordering;

#[test]
fn la2011_safe_is_checked_over_its_code_and_every_end_encloses() {
    let o = check("la2011-safe").expect("la2011-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 6, "t, u, v: both ends each");
    assert!(o.pins > 0 && o.lemmas.len() == 1, "the chord's pins: {} {:?}", o.pins, o.lemmas);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("STEP") > 0 && used("quotient of ends, divisor of one strict sign") > 0, "{:?}", o.rules);
}

#[test]
fn a_dropped_outward_step_fails_the_enclosure_check() {
    for (id, side) in [("broken/planted-no-up/la2011-safe", "upper"), ("broken/planted-no-dn/la2011-safe", "lower")] {
        let o = check(id).expect("a planted slip of a checked variant is checked");
        assert!(!o.failures.is_empty(), "{id} passed");
        assert!(
            o.failures.iter().any(|f| f.what.contains(side) && f.found.contains("no end")),
            "{id}: no {side} end found wanting: {:?}",
            o.failures
        );
    }
    assert!(check("la2011").is_none(), "the published method has no enclosure claim");
}

/// An extended exact value.
#[derive(Clone, Debug)]
enum X {
    Num(BigInt, BigInt),
    PosInf,
    NegInf,
    /// No value (NaN, 0 / 0, inf - inf): no claim is made on it.
    Undef,
}

fn rat(v: f32) -> X {
    if v.is_nan() {
        return X::Undef;
    }
    if v.is_infinite() {
        return if v > 0.0 { X::PosInf } else { X::NegInf };
    }
    let b = v.to_bits();
    let (sign, exp, frac) = (b >> 31, ((b >> 23) & 0xff) as i32, (b & 0x7f_ffff) as i64);
    let (m, e) = if exp == 0 { (frac, -149) } else { (frac | 0x80_0000, exp - 150) };
    let m = BigInt::from(if sign == 1 { -m } else { m });
    if e >= 0 {
        X::Num(m << e as usize, BigInt::from(1))
    } else {
        X::Num(m, BigInt::from(1) << (-e) as usize)
    }
}

fn cmp(a: &X, b: &X) -> Option<Ordering> {
    use X::*;
    Some(match (a, b) {
        (Undef, _) | (_, Undef) => return None,
        (NegInf, NegInf) | (PosInf, PosInf) => Ordering::Equal,
        (NegInf, _) | (_, PosInf) => Ordering::Less,
        (PosInf, _) | (_, NegInf) => Ordering::Greater,
        (Num(an, ad), Num(bn, bd)) => (an * bd).cmp(&(bn * ad)),
    })
}

fn arith(op: char, a: &X, b: &X) -> X {
    use X::*;
    match (a, b) {
        (Num(an, ad), Num(bn, bd)) => match op {
            '+' => Num(an * bd + bn * ad, ad * bd),
            '-' => Num(an * bd - bn * ad, ad * bd),
            '*' => Num(an * bn, ad * bd),
            _ if *bn == BigInt::from(0) => Undef,
            _ if *bn < BigInt::from(0) => Num(-(an * bd), -(ad * bn)),
            _ => Num(an * bd, ad * bn),
        },
        _ => Undef,
    }
}

/// An f32 value and its exact value.
#[derive(Clone, Debug)]
struct V(f32, X);

/// The attacking arithmetic; `bad` collects every pin whose end is on the wrong side.
#[derive(Default)]
struct Pair {
    bad: RefCell<Vec<String>>,
    pins: RefCell<usize>,
}

fn on_side(v: &V, end: End) -> bool {
    match (cmp(&rat(v.0), &v.1), end) {
        (None, _) => true,
        (Some(o), End::Lo) => o != Ordering::Greater,
        (Some(o), End::Hi) => o != Ordering::Less,
    }
}

impl F32Arith for Pair {
    type F = V;
    type B = bool;
    fn lit(&self, v: f32) -> V {
        V(v, rat(v))
    }
    fn add(&self, a: &V, b: &V) -> V {
        V(a.0 + b.0, arith('+', &a.1, &b.1))
    }
    fn sub(&self, a: &V, b: &V) -> V {
        V(a.0 - b.0, arith('-', &a.1, &b.1))
    }
    fn mul(&self, a: &V, b: &V) -> V {
        V(a.0 * b.0, arith('*', &a.1, &b.1))
    }
    fn div(&self, a: &V, b: &V) -> V {
        V(a.0 / b.0, arith('/', &a.1, &b.1))
    }
    fn fma(&self, a: &V, b: &V, c: &V) -> V {
        V(a.0.mul_add(b.0, c.0), arith('+', &arith('*', &a.1, &b.1), &c.1))
    }
    fn neg(&self, a: &V) -> V {
        V(-a.0, arith('-', &X::Num(0.into(), 1.into()), &a.1))
            .fix_inf(&a.1, true)
    }
    fn abs(&self, a: &V) -> V {
        let neg = matches!(cmp(&a.1, &X::Num(0.into(), 1.into())), Some(Ordering::Less));
        if neg {
            self.neg(a).with_f32(a.0.abs())
        } else {
            V(a.0.abs(), a.1.clone())
        }
    }
    fn min(&self, a: &V, b: &V) -> V {
        let f = if a.0.is_nan() || b.0 < a.0 { b.0 } else { a.0 };
        let x = match cmp(&a.1, &b.1) {
            Some(Ordering::Greater) => b.1.clone(),
            Some(_) => a.1.clone(),
            None => X::Undef,
        };
        V(f, x)
    }
    fn max(&self, a: &V, b: &V) -> V {
        let f = if a.0.is_nan() || b.0 > a.0 { b.0 } else { a.0 };
        let x = match cmp(&a.1, &b.1) {
            Some(Ordering::Less) => b.1.clone(),
            Some(_) => a.1.clone(),
            None => X::Undef,
        };
        V(f, x)
    }
    fn next_up(&self, a: &V) -> V {
        V(a.0.next_up(), a.1.clone())
    }
    fn next_down(&self, a: &V) -> V {
        V(a.0.next_down(), a.1.clone())
    }
    fn lt(&self, a: &V, b: &V) -> bool {
        a.0 < b.0
    }
    fn le(&self, a: &V, b: &V) -> bool {
        a.0 <= b.0
    }
    fn eq(&self, a: &V, b: &V) -> bool {
        a.0 == b.0
    }
    fn is_nan(&self, a: &V) -> bool {
        a.0.is_nan()
    }
    fn is_finite(&self, a: &V) -> bool {
        a.0.is_finite()
    }
    fn truth(&self, b: bool) -> bool {
        b
    }
    fn and(&self, a: &bool, b: &bool) -> bool {
        *a && *b
    }
    fn or(&self, a: &bool, b: &bool) -> bool {
        *a || *b
    }
    fn not(&self, a: &bool) -> bool {
        !a
    }
    fn select(&self, c: &bool, a: &V, b: &V) -> V {
        if *c {
            a.clone()
        } else {
            b.clone()
        }
    }
    fn pin(&self, a: &V, end: End, lemma: &'static str) -> V {
        *self.pins.borrow_mut() += 1;
        if !on_side(a, end) {
            self.bad.borrow_mut().push(format!("pin ({lemma}): {a:?} is not a {end:?} end"));
        }
        V(a.0, rat(a.0))
    }
}

impl V {
    fn with_f32(self, f: f32) -> V {
        V(f, self.1)
    }
    /// -(+inf) = -inf for the exact side too.
    fn fix_inf(self, x: &X, _neg: bool) -> V {
        match x {
            X::PosInf => V(self.0, X::NegInf),
            X::NegInf => V(self.0, X::PosInf),
            _ => self,
        }
    }
}

/// An f32 value drawn to exercise branches: small integers and halves (exact
/// products, ties), ±0, ±1, values of any exponent, near-equal pairs.
fn draw(rng: &mut ChaCha8Rng, near: f32) -> f32 {
    match rng.gen_range(0..10) {
        0 => rng.gen_range(-8..=8) as f32 * 0.5,
        1 => [0.0, -0.0, 1.0, -1.0][rng.gen_range(0..4)],
        2 => f32::from_bits(rng.gen::<u32>() & 0x7fff_ffff | if rng.gen() { 0x8000_0000 } else { 0 }).clamp(-1e30, 1e30),
        3 => near * (1.0 + rng.gen_range(-1e-6..1e-6)),
        4 => rng.gen_range(-1e6..1e6),
        _ => rng.gen_range(-4.0..4.0),
    }
}

/// A triangle and a tile of drawn values.
fn wild(ar: &Pair, rng: &mut ChaCha8Rng) -> (TriOf<V>, [V; 4]) {
    let base = draw(rng, 1.0);
    let mut vert = || {
        let mut v = [0; 4].map(|_| draw(rng, base));
        if v[3].is_nan() || v[3] == 0.0 {
            v[3] = 1.0;
        }
        v.map(|x| ar.lit(x))
    };
    let (q, r) = ([vert(), vert(), vert()], [vert(), vert(), vert()]);
    let tri = TriOf {
        q,
        r,
        c0: [0; 3].map(|_| ar.lit(draw(rng, base))),
        c1: [0; 3].map(|_| ar.lit(draw(rng, base))),
        k: ar.lit(draw(rng, 1.0)),
    };
    let [a, b, c, d] = [0; 4].map(|_| draw(rng, base));
    (tri, [a.min(b), c.min(d), a.max(b), c.max(d)].map(|x| ar.lit(x)))
}

/// Run `R`'s la2011 over the pair arithmetic on `n` drawn inputs; the ends found on the
/// wrong side of their exact values, and the number of ends compared.
fn attack<R: Round>(n: usize, seed: u64) -> (Vec<String>, usize, usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let ar = Pair::default();
    let (mut compared, mut inside) = (0, 0);
    for i in 0..n {
        // Half the draws are the gate's cases with a tile on the footprint's boundary
        // (every regime), half are wild values that reach the special branches.
        let (tri, tile) = if i % 2 == 0 {
            let case = physical_case(&mut rng, Regime::ALL[(i / 2) % Regime::ALL.len()]);
            let size = [1.0, 4.0, 16.0, 64.0][rng.gen_range(0..4)];
            let tile = boundary_tile(&case, &mut rng, size);
            let tri = TriOf::of(&case.triangle).map(|x| ar.lit(*x));
            (tri, [tile.x0, tile.y0, tile.x1, tile.y1].map(|x| ar.lit(x)))
        } else {
            wild(&ar, &mut rng)
        };
        let s = setup_of::<R, Pair>(&ar, &tri);
        let (_, t, u, v) = tile_answer::<R, Pair>(&ar, &s, &tile);
        for (name, r) in [("t", &t), ("u", &u), ("v", &v)] {
            for (k, end) in [(0, End::Lo), (1, End::Hi)] {
                compared += 1;
                let lim = if name == "t" { [0.0, 1.0] } else { [-1.0, 1.0] };
                inside += usize::from(r[k].0 > lim[0] && r[k].0 < lim[1]);
                if !on_side(&r[k], end) {
                    ar.bad.borrow_mut().push(format!("{name} {end:?}: {:?}", r[k]));
                }
            }
        }
    }
    assert!(*ar.pins.borrow() > 0, "the pins were never reached");
    let bad = ar.bad.borrow().clone();
    (bad, compared, inside)
}

/// The check's conclusion for la2011-safe, attacked in exact arithmetic: no end on the
/// wrong side, at the outputs or at the pins. The same attack on a planted slip finds
/// ends on the wrong side (so it can fail).
#[test]
fn the_checked_ends_enclose_their_exact_values_on_drawn_inputs() {
    let (bad, n, inside) = attack::<Outward>(4000, 1);
    assert!(bad.is_empty(), "{} of {n}: {:?}", bad.len(), &bad[..bad.len().min(5)]);
    // The draws reach the interesting ends: strictly inside the domain, cut by the method.
    assert!(inside * 20 > n, "only {inside} of {n} ends inside the domain");
    let (bad_up, _, _) = attack::<NoUp>(4000, 1);
    let (bad_dn, _, _) = attack::<NoDn>(4000, 1);
    eprintln!("ends compared {n}, inside the domain {inside}; slips: {} and {} ends on the wrong side", bad_up.len(), bad_dn.len());
    assert!(bad_up.iter().any(|b| b.contains("Hi")), "the no-up slip was not caught by the attack");
    assert!(bad_dn.iter().any(|b| b.contains("Lo")), "the no-dn slip was not caught by the attack");
}
