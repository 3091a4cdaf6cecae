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
use cullproof::bounds::round::{Nearest, Outward, Round};
use cullproof::cases::generate::{boundary_tile, physical_case, Regime};
use cullproof::tools::proofs::enclosure::check;
use num_bigint::BigInt;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::RefCell;
use std::cmp::Ordering;

#[test]
fn the_checked_variants_pass_over_their_code() {
    let o = check("la2011-safe").expect("la2011-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 7, "t, u, v: both ends each, and the tile reject");
    assert!(o.pins > 0 && o.lemmas.len() == 1, "the chord's pins: {} {:?}", o.pins, o.lemmas);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("STEP") > 0 && used("quotient of ends, divisor of one strict sign") > 0, "{:?}", o.rules);
    let o = check("nilsson2012-depth-safe").expect("nilsson2012-depth-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 3, "z: both ends, and the tile reject");
    assert_eq!(o.lemmas.len(), 3, "w from a plane, the w range, the residuals' range: {:?}", o.lemmas);
    assert_eq!(o.choices.len(), 3, "the normal, the depth line, using a plane: {:?}", o.choices);
    let o = check("mam2012-safe").expect("mam2012-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 9, "u, v: both ends each, the tile reject and the four lines' culls");
    assert_eq!(o.lemmas.len(), 5, "domain, corners, columns, either corner, lines: {:?}", o.lemmas);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    for r in [
        "min (max) of the four end products or quotients",
        "an end moved outward (MONO)",
        "a rounded end compared with 0 (MONO)",
        "a comparison of one exact value with itself",
    ] {
        assert!(used(r) > 0, "{r}: {:?}", o.rules);
    }
    let o = check("wu2013-safe").expect("wu2013-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 11, "u, v, t: both ends each, the tile reject and the four lines' culls");
    assert_eq!(o.lemmas.len(), 3, "the lens range, the lines, wu2013_safe.g: {:?}", o.lemmas);
    assert_eq!(o.choices.len(), 3, "the slope, the endpoints' limit, keeping a line: {:?}", o.choices);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("an end a lemma proves") >= 4, "every line's f32 value: {:?}", o.rules);
    assert!(used("an end moved outward (MONO)") >= 4, "every padded intercept: {:?}", o.rules);
    assert!(used("min (max) of the four end products or quotients") > 0, "{:?}", o.rules);
    let o = check("lc-safe").expect("lc-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 11, "t, u, v met: both ends each, the tile reject and lb2011-safe's four patches");
    assert_eq!(o.lemmas.len(), 3, "the chord (both parts), lb2011-safe's corners, lb2011_safe.g: {:?}", o.lemmas);
    let o = check("bbox-safe").expect("bbox-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 1, "the tile reject");
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("an end a lemma proves") >= 48, "every corner's two ends: {:?}", o.rules);
}

/// wu2013-safe's lines are `wu2013_safe.g`'s formula with the script's own constants: a
/// pad halved, another floor or another limit in the script (or, the same, in the code)
/// leaves the code's line values outside the lemma, and the lines' culls unproven.
#[test]
fn a_wu2013_line_other_than_the_scripts_is_refused() {
    use cullproof::bounds::proofs::WU_PAD;
    use cullproof::tools::proofs::check::with_constant;
    use cullproof::tools::proofs::enclosure::check_wu2013_with;
    assert!(check_wu2013_with(WU_PAD.text).failures.is_empty());
    for (name, value) in [("PAD", "1b-22"), ("FLOOR", "1b-99"), ("LIMIT", "1b101")] {
        let text = with_constant(&WU_PAD, name, value);
        assert_ne!(text, WU_PAD.text);
        let o = check_wu2013_with(&text);
        assert!(o.failures.iter().any(|f| f.what.contains("line")), "{name} = {value} passed: {:?}", o.failures);
        assert!(!o.failures.iter().any(|f| f.what.contains("tile reject")), "{name}: {:?}", o.failures);
    }
}

/// bbox-safe's corners are the Gappa script's formula with the script's own constants:
/// a pad halved or a step less in the script (or, the same, in the code) leaves the
/// code's corners outside the lemma, and the tile reject unproven.
#[test]
fn a_bbox_corner_other_than_the_scripts_is_refused() {
    use cullproof::bounds::proofs::BBOX_PAD;
    use cullproof::tools::proofs::check::with_constant;
    let o = check("bbox-safe").unwrap();
    assert!(o.failures.is_empty());
    for (name, value) in [("PAD", "1b-22"), ("STEPS", "3"), ("FLOOR", "1b-121")] {
        let text = with_constant(&BBOX_PAD, name, value);
        assert_ne!(text, BBOX_PAD.text);
        let o = cullproof::tools::proofs::enclosure::check_bbox_with(&text).unwrap();
        assert!(!o.failures.is_empty(), "{name} = {value} passed");
    }
    for id in ["broken/planted-no-up/bbox-safe", "broken/planted-no-dn/bbox-safe", "broken/planted-eq/bbox-safe"] {
        let o = cullproof::tools::proofs::enclosure::check_traced(id).unwrap();
        assert!(o.failures.iter().any(|f| f.what.contains("tile reject")), "{id}: {:?}", o.failures);
    }
}

#[test]
fn a_dropped_outward_step_fails_the_enclosure_check() {
    for (id, side) in [
        ("broken/planted-no-up/bbox-safe", "tile reject"),
        ("broken/planted-no-dn/bbox-safe", "tile reject"),
        ("broken/planted-no-up/la2011-safe", "upper"),
        ("broken/planted-no-dn/la2011-safe", "lower"),
        ("broken/planted-no-up/nilsson2012-depth-safe", "upper"),
        ("broken/planted-no-dn/nilsson2012-depth-safe", "lower"),
        ("broken/planted-no-up/mam2012-safe", "line"),
        ("broken/planted-no-dn/mam2012-safe", "line"),
        ("broken/planted-no-up/wu2013-safe", "upper"),
        ("broken/planted-no-dn/wu2013-safe", "lower"),
        ("broken/planted-no-up/gdam2010-safe", "piece cull"),
        ("broken/planted-no-dn/gdam2010-safe", "piece cull"),
        ("broken/planted-no-up/lb2011-safe", "patch"),
        ("broken/planted-no-dn/lb2011-safe", "patch"),
        ("broken/planted-no-up/lc-safe", "patch"),
        ("broken/planted-no-dn/lc-safe", "patch"),
    ] {
        let o = check(id).expect("a planted slip of a checked variant is checked");
        assert!(!o.failures.is_empty(), "{id} passed");
        assert!(
            o.failures
                .iter()
                .any(|f| f.what.contains(side) && (f.found.contains("no end") || f.found.contains("imply"))),
            "{id}: no {side} end found wanting: {:?}",
            o.failures
        );
    }
    assert!(check("la2011").is_none(), "the published method has no enclosure claim");
    assert!(check("nilsson2012-depth").is_none(), "the published method has no enclosure claim");
    assert!(check("mam2012").is_none(), "the published method has no enclosure claim");
    assert!(check("wu2013").is_none(), "the published method has no enclosure claim");
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

/// A truth value of the pair arithmetic.
type T = (bool, Option<bool>);

/// An f32 value and its exact value.
#[derive(Clone, Debug)]
struct V(f32, X);

/// The attacking arithmetic; `bad` collects every pin whose end is on the wrong side.
#[derive(Default)]
struct Pair {
    bad: RefCell<Vec<String>>,
    pins: RefCell<usize>,
    /// Per-sample culls made whose exact counterpart holds.
    sample_culls: RefCell<usize>,
    turn: RefCell<usize>,
    /// Shortcuts taken (their condition true), each checked in exact arithmetic.
    shortcuts: RefCell<usize>,
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
    /// A truth value: the f32 one, and its counterpart over the exact values (None where
    /// an exact value is undefined).
    type B = (bool, Option<bool>);
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
        V(-a.0, arith('-', &X::Num(0.into(), 1.into()), &a.1)).fix_inf(&a.1, true)
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
    fn lt(&self, a: &V, b: &V) -> T {
        (a.0 < b.0, cmp(&a.1, &b.1).map(|o| o == Ordering::Less))
    }
    fn le(&self, a: &V, b: &V) -> T {
        (a.0 <= b.0, cmp(&a.1, &b.1).map(|o| o != Ordering::Greater))
    }
    fn eq(&self, a: &V, b: &V) -> T {
        (a.0 == b.0, cmp(&a.1, &b.1).map(|o| o == Ordering::Equal))
    }
    // Exact values are never NaN and always finite.
    fn is_nan(&self, a: &V) -> T {
        (a.0.is_nan(), Some(false))
    }
    fn is_finite(&self, a: &V) -> T {
        (a.0.is_finite(), Some(true))
    }
    fn truth(&self, b: bool) -> T {
        (b, Some(b))
    }
    fn and(&self, a: &T, b: &T) -> T {
        let x = match (a.1, b.1) {
            (Some(false), _) | (_, Some(false)) => Some(false),
            (Some(true), Some(true)) => Some(true),
            _ => None,
        };
        (a.0 && b.0, x)
    }
    fn or(&self, a: &T, b: &T) -> T {
        let x = match (a.1, b.1) {
            (Some(true), _) | (_, Some(true)) => Some(true),
            (Some(false), Some(false)) => Some(false),
            _ => None,
        };
        (a.0 || b.0, x)
    }
    fn not(&self, a: &T) -> T {
        (!a.0, a.1.map(|x| !x))
    }
    // A free condition only restricts a cull: its counterpart is "true".
    fn choose_truth(&self, b: &T, _why: &'static str) -> T {
        (b.0, Some(true))
    }
    fn select(&self, c: &T, a: &V, b: &V) -> V {
        if c.0 {
            a.clone()
        } else {
            b.clone()
        }
    }
    fn pin_range(&self, v: &[V; 2], _positive: bool, lemma: &'static str) -> [V; 2] {
        *self.pins.borrow_mut() += 1;
        for (x, end) in [(&v[0], End::Lo), (&v[1], End::Hi)] {
            if !on_side(x, end) {
                self.bad.borrow_mut().push(format!("pinned range ({lemma}): {x:?} is not a {end:?} end"));
            }
        }
        // The quantity the range holds: any value in it (the claims after the pin are
        // for all of them); the attack takes its ends and its midpoint in turn.
        let mut k = self.turn.borrow_mut();
        *k += 1;
        let (lo, hi) = (rat(v[0].0), rat(v[1].0));
        let x = match *k % 3 {
            0 => lo,
            1 => hi,
            _ => match (&lo, &hi) {
                (X::Num(a, b), X::Num(c, d)) => X::Num(a * d + c * b, b * d * 2),
                _ => X::Undef,
            },
        };
        let x = if cmp(&rat(v[0].0), &rat(v[1].0)) == Some(Ordering::Greater) { X::Undef } else { x };
        [V(v[0].0, x.clone()), V(v[1].0, x)]
    }
    fn choose(&self, a: &V, _why: &'static str) -> V {
        V(a.0, rat(a.0))
    }
    /// A shortcut's claim in exact arithmetic: where its condition holds, both branches
    /// have one exact value (each branch's own, computed without the shortcut).
    fn select_same(&self, c: &T, a: &V, b: &V, why: &'static str) -> V {
        if c.0 {
            *self.shortcuts.borrow_mut() += 1;
            if cmp(&a.1, &b.1).is_some_and(|o| o != Ordering::Equal) {
                self.bad.borrow_mut().push(format!("shortcut ({why}): exact {:?} and {:?} differ", a.1, b.1));
            }
        }
        self.select(c, a, b)
    }
    /// The lemma's equation is checked too, in exact arithmetic: `v`'s exact value must
    /// be `like`'s (where both are defined).
    fn pin_same(&self, v: &[V; 2], like: &V, lemma: &'static str) -> [V; 2] {
        *self.pins.borrow_mut() += 1;
        for (x, end) in [(&v[0], End::Lo), (&v[1], End::Hi)] {
            if !on_side(x, end) {
                self.bad.borrow_mut().push(format!("pinned same value ({lemma}): {x:?} is not a {end:?} end"));
            }
        }
        if cmp(&v[0].1, &like.1).is_some_and(|o| o != Ordering::Equal) {
            self.bad.borrow_mut().push(format!("{lemma}: {:?} and {:?} differ", v[0].1, like.1));
        }
        [V(v[0].0, like.1.clone()), V(v[1].0, like.1.clone())]
    }
    fn moved_out(&self, moved: &V, from: &V, end: End) -> V {
        let m = V(moved.0, from.1.clone());
        if !on_side(&m, end) {
            self.bad.borrow_mut().push(format!("moved out: {m:?} is not a {end:?} end"));
        }
        m
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
        2 => {
            f32::from_bits(rng.gen::<u32>() & 0x7fff_ffff | if rng.gen() { 0x8000_0000 } else { 0 }).clamp(-1e30, 1e30)
        }
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

/// A method's tile answer over the pair arithmetic: its output ranges, by name, and its
/// culls (the tile reject first).
type Answer = fn(&Pair, &TriOf<V>, &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>);

fn la2011<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    let s = setup_of::<R, Pair>(ar, tri);
    let (nonempty, t, u, v) = tile_answer::<R, Pair>(ar, &s, tile);
    (vec![("t", t), ("u", u), ("v", v)], vec![ar.not(&nonempty)])
}

fn nilsson<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    use cullproof::bounds::nilsson2012_depth as m;
    let s = m::setup_of::<R, Pair>(ar, tri);
    let (nonempty, z) = m::tile_answer::<R, Pair>(ar, &s, tile);
    (vec![("z", z)], vec![ar.not(&nonempty)])
}

/// mam2012-safe: the u and v ranges, the tile reject, and each line's cull at samples
/// drawn next to the line (the lens coordinate one to three f32 steps either side of the
/// line's f32 value at t in {0, 1/4, 1/2, 1} and at the ends of the shutter).
fn mam2012<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    use cullproof::bounds::mam2012::{answer_of, line_eval, rejects_of, setup_safe_of};
    let (why, axes) = setup_safe_of::<R, Pair>(ar, tri);
    let enabled = ar.not(&ar.any(&why));
    let [au, av] = [(0, 0, 2), (1, 1, 3)].map(|(a, lo, hi)| answer_of::<R, Pair>(ar, &axes[a], &tile[lo], &tile[hi]));
    let reject = rejects_of(ar, &why, &au, &av);
    let mut culls = vec![reject];
    let mut ranges = vec![];
    for (name, a) in [("u", &au), ("v", &av)] {
        let kept = ar.and(&enabled, &ar.not(&a.full));
        ranges.push((name, [0, 1].map(|k| ar.select(&kept, &a.range[k], &ar.lit([-1.0, 1.0][k])))));
        for (upper, (ok, la, lb)) in [false, true].into_iter().zip(&a.lines) {
            if !(kept.0 && ok.0) {
                continue;
            }
            for tv in [0.0f32, 0.25, 0.5, 1.0] {
                let line = la.0 * tv + lb.0;
                let mut w = line;
                for step in 0..7 {
                    let t = ar.lit(tv);
                    let g = line_eval::<R, Pair>(ar, upper, la, lb, &t, &ar.lit(w));
                    culls.push(ar.all(&[kept, *ok, ar.lt(&g, &ar.lit(0.0))]));
                    // one to three steps below the line's value, then above it
                    w = if step < 3 {
                        w.next_down()
                    } else if step == 3 {
                        line.next_up()
                    } else {
                        w.next_up()
                    };
                }
            }
        }
    }
    (ranges, culls)
}

/// wu2013-safe: the u, v and t ranges (where every input is finite and the tile is
/// kept), the tile reject, and each kept line's cull at samples drawn next to the line
/// (t one to three f32 steps either side of the line's f32 value at l in
/// {-1, -1/2, 0, 1/2, 1}). A cull's exact counterpart puts the sample beyond the line
/// through the pinned intercept: it fails where the padded f32 line lies inside it.
fn wu2013<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    use cullproof::bounds::wu2013::{line_gap, setup_of, tile_answer};
    let (finite, axes) = setup_of::<R, Pair>(ar, tri);
    let a = tile_answer::<R, Pair>(ar, &axes, tile);
    let kept = ar.and(&finite, &ar.not(&a.reject));
    let mut ranges = vec![];
    for (name, r, full) in [("u", &a.u, [-1.0, 1.0]), ("v", &a.v, [-1.0, 1.0]), ("t", &a.t, [0.0, 1.0])] {
        ranges.push((name, [0, 1].map(|k| ar.select(&kept, &r[k], &ar.lit(full[k])))));
    }
    let mut culls = vec![ar.and(&finite, &a.reject)];
    for cut in &a.lines {
        for (upper, side) in [true, false].into_iter().zip(cut) {
            if !(finite.0 && side.keep.0) {
                continue;
            }
            let c = &side.line;
            for lv in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
                let x = c.a.0 * lv + c.padded.0;
                let mut t = x;
                for step in 0..7 {
                    let l = ar.lit(lv);
                    let g = line_gap(ar, upper, &c.a, &c.padded, &l, &ar.lit(t));
                    let lens = [ar.le(&ar.lit(-1.0), &l), ar.le(&l, &ar.lit(1.0))];
                    culls.push(ar.all(&[finite, side.keep, lens[0], lens[1], ar.lt(&g, &ar.lit(0.0))]));
                    t = if step < 3 {
                        t.next_down()
                    } else if step == 3 {
                        x.next_up()
                    } else {
                        t.next_up()
                    };
                }
            }
        }
    }
    (ranges, culls)
}

/// Run a method over the pair arithmetic on `n` drawn inputs; the ends found on the
/// wrong side of their exact values (and the culls whose exact counterpart is false),
/// the number of ends compared, how many of them cut (inside the domain: t in (0, 1),
/// u, v in (-1, 1), a finite z), and the number of tiles culled.
fn attack(answer: Answer, n: usize, seed: u64) -> (Vec<String>, usize, usize, usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let ar = Pair::default();
    let (mut compared, mut inside, mut culls) = (0, 0, 0);
    for i in 0..n {
        // Half the draws are the gate's cases with a tile on the footprint's boundary
        // (every regime), half are wild values that reach the special branches.
        let (tri, tile) = if i % 2 == 0 {
            let case = physical_case(&mut rng, Regime::ALL[(i / 2) % Regime::ALL.len()]);
            let size = [1.0, 4.0, 16.0, 64.0][rng.gen_range(0..4)];
            let tile = boundary_tile(&case, &mut rng, size);
            // the boundary tile, or one moved 1-4 tiles off it (where culls happen)
            let k = [0.0, 1.0, 2.0, 4.0][rng.gen_range(0..4)] * size * if rng.gen() { 1.0 } else { -1.0 };
            let (dx, dy) = if rng.gen() { (k, 0.0) } else { (0.0, k) };
            let tri = TriOf::of(&case.triangle).map(|x| ar.lit(*x));
            (tri, [tile.x0 + dx, tile.y0 + dy, tile.x1 + dx, tile.y1 + dy].map(|x| ar.lit(x)))
        } else {
            wild(&ar, &mut rng)
        };
        let (ranges, cull_list) = answer(&ar, &tri, &tile);
        for (k, cull) in cull_list.iter().enumerate() {
            let held = usize::from(cull.0 && cull.1 == Some(true));
            if k == 0 {
                culls += held;
            } else {
                *ar.sample_culls.borrow_mut() += held;
            }
            if cull.0 && cull.1 == Some(false) {
                let what = if k == 0 { "tile reject" } else { "per-sample cull" };
                ar.bad.borrow_mut().push(format!("{what}: culled, its exact counterpart false ({tri:?})"));
            }
        }
        for (name, r) in ranges {
            for (k, end) in [(0, End::Lo), (1, End::Hi)] {
                compared += 1;
                let lim = match name {
                    "t" => [0.0, 1.0],
                    "z" => [f32::NEG_INFINITY, f32::INFINITY],
                    _ => [-1.0, 1.0],
                };
                inside += usize::from(r[k].0 > lim[0] && r[k].0 < lim[1]);
                if !on_side(&r[k], end) {
                    ar.bad.borrow_mut().push(format!("{name} {end:?}: {:?}", r[k]));
                }
            }
        }
    }
    assert!(*ar.pins.borrow() > 0, "the pins were never reached");
    assert!(culls > 0, "no tile was culled with its exact counterpart decided");
    let bad = ar.bad.borrow().clone();
    let samples = *ar.sample_culls.borrow();
    if samples > 0 {
        eprintln!("per-sample culls made (exact counterpart true): {samples}");
    }
    (bad, compared, inside, culls)
}

/// The check's conclusion for each variant it covers, attacked in exact arithmetic: no
/// end on the wrong side, at the outputs or at the pins. The same attack on the planted
/// slips finds ends on the wrong side (so it can fail).
#[test]
fn the_checked_ends_enclose_their_exact_values_on_drawn_inputs() {
    let methods: [(&str, Answer, Answer, Answer); 5] = [
        ("la2011-safe", la2011::<Outward>, la2011::<NoUp>, la2011::<NoDn>),
        ("nilsson2012-depth-safe", nilsson::<Outward>, nilsson::<NoUp>, nilsson::<NoDn>),
        ("mam2012-safe", mam2012::<Outward>, mam2012::<NoUp>, mam2012::<NoDn>),
        ("wu2013-safe", wu2013::<Outward>, wu2013::<NoUp>, wu2013::<NoDn>),
        ("lc-safe", lc::<Outward>, lc::<NoUp>, lc::<NoDn>),
    ];
    for (id, safe, no_up, no_dn) in methods {
        let (bad, n, inside, culls) = attack(safe, 20_000, 1);
        assert!(bad.is_empty(), "{id}: {} of {n}: {:?}", bad.len(), &bad[..bad.len().min(5)]);
        // The draws reach the interesting ends: strictly inside the domain, cut.
        assert!(inside * 20 > n, "{id}: only {inside} of {n} ends inside the domain");
        assert!(culls >= 100, "{id}: only {culls} tiles culled");
        let (bad_up, _, _, _) = attack(no_up, 4000, 1);
        let (bad_dn, _, _, _) = attack(no_dn, 4000, 1);
        eprintln!(
            "{id}: ends compared {n}, inside the domain {inside}, tiles culled (exact counterpart true) {culls}; slips: {} and {} ends on the wrong side",
            bad_up.len(),
            bad_dn.len()
        );
        assert!(bad_up.iter().any(|b| b.contains("Hi")), "{id}: the no-up slip was not caught by the attack");
        assert!(bad_dn.iter().any(|b| b.contains("Lo")), "{id}: the no-dn slip was not caught by the attack");
    }
}

/// The rules the check applies, and the chord lemma, are proven by z3 in real
/// arithmetic; the same script with one rule turned the wrong way is refuted.
#[test]
fn the_rules_are_proven_and_a_wrong_rule_is_refuted() {
    use cullproof::bounds::proofs::{Tool, RULES};
    use cullproof::tools::proofs::run::{run, run_text, Verdict};
    use std::time::Duration;
    let limit = Duration::from_secs(120);
    let o = run(&RULES, limit);
    if let Verdict::Missing(m) = &o.verdict {
        panic!("{m}");
    }
    assert_eq!(o.verdict, Verdict::Proven, "{:?}", o.verdict);
    // the upper end of a quotient turned into a lower one
    let wrong = RULES.text.replace("(>= (/ a4 b4) (/ A4 B4))", "(<= (/ a4 b4) (/ A4 B4))");
    assert_ne!(wrong, RULES.text);
    assert!(matches!(run_text(Tool::Z3, &wrong, limit).verdict, Verdict::Refuted(_)));
    // the chord lemma for upper ends instead of lower ones
    let wrong = RULES.text.replace("(=> (and (<= l0 L0) (<= l1 L1)", "(=> (and (>= l0 L0) (>= l1 L1)");
    assert_ne!(wrong, RULES.text);
    assert!(matches!(run_text(Tool::Z3, &wrong, limit).verdict, Verdict::Refuted(_)));
}

/// Two inputs `x`, `c` of a fresh trace, and `[lo, hi]`, an enclosure of `x x` (rounded
/// to nearest, stepped out).
fn square_and_input(t: &cullproof::tools::proofs::enclosure::Trace) -> (u32, u32, u32, u32) {
    let (x, c) = (t.input("x"), t.input("c"));
    let r = t.mul(&x, &x);
    (x, c, t.next_down(&r), t.next_up(&r))
}

/// The check on small pieces of interval code: each slip the proofs must notice (a step
/// in the wrong direction, a min where a max belongs, a step dropped, a quotient whose
/// divisor sign the code never tested) leaves an end the check refuses.
#[test]
fn a_swapped_min_max_or_a_wrong_step_leaves_no_end() {
    use cullproof::tools::proofs::enclosure::{Check, Trace, N};
    type Piece = fn(&Trace, N, N, N) -> N;
    // an upper end of |x| * c + d, for x in [lo, hi]: max(|lo|, |hi|) * |c| + d, rounded up
    let good: Piece = |t, lo, hi, c| {
        let m = t.max(&t.abs(&lo), &t.abs(&hi));
        t.next_up(&t.add(&t.next_up(&t.mul(&m, &t.abs(&c))), &c))
    };
    let swapped: Piece = |t, lo, hi, c| {
        let m = t.min(&t.abs(&lo), &t.abs(&hi));
        t.next_up(&t.add(&t.next_up(&t.mul(&m, &t.abs(&c))), &c))
    };
    let wrong_step: Piece = |t, lo, hi, c| {
        let m = t.max(&t.abs(&lo), &t.abs(&hi));
        t.next_up(&t.add(&t.next_down(&t.mul(&m, &t.abs(&c))), &c))
    };
    let dropped: Piece = |t, lo, hi, c| {
        let m = t.max(&t.abs(&lo), &t.abs(&hi));
        t.next_up(&t.add(&t.mul(&m, &t.abs(&c)), &c))
    };
    // an upper end of c / x: the divisor's sign must be tested first
    let untested: Piece = |t, lo, _hi, c| t.next_up(&t.div(&c, &lo));
    let tested: Piece = |t, lo, hi, c| {
        let zero = t.lit(0.0);
        let pos = t.lt(&zero, &lo);
        let q = t.select(&t.le(&zero, &c), &t.div(&c, &lo), &t.div(&c, &hi));
        t.select(&pos, &t.next_up(&q), &t.lit(f32::INFINITY))
    };
    for (name, piece, ok) in [
        ("good", good, true),
        ("swapped", swapped, false),
        ("wrong step", wrong_step, false),
        ("dropped", dropped, false),
        ("untested divisor", untested, false),
        ("tested divisor", tested, true),
    ] {
        let t = Trace::new();
        let (x, c, lo, hi) = square_and_input(&t);
        // finite inputs (as the variants' guards establish), else no bound
        let fin = t.and(&t.is_finite(&x), &t.is_finite(&c));
        let out = t.select(&fin, &piece(&t, lo, hi, c), &t.lit(f32::INFINITY));
        let o = Check::new(&t).run(&[(out, End::Hi, "out".into())]);
        let out_ok = o.failures.iter().all(|f| f.found == "may be NaN");
        assert_eq!(out_ok, ok, "{name}: {:?}", o.failures);
    }
}

/// `cullproof proofs` on each checked variant passes, and fails on each planted slip that
/// drops one side's outward steps (for la2011-safe's slips, whose template queries take
/// minutes, the enclosure part of the command alone; tests/proofs.rs runs the rest; bbox-safe's
/// slips: `a_bbox_corner_other_than_the_scripts_is_refused`).
#[test]
fn proofs_fails_on_every_planted_dropped_step() {
    use cullproof::cli::proofs::{render, run, run_enclosure};
    use std::time::Duration;
    let limit = Duration::from_secs(120);
    for id in ["nilsson2012-depth-safe", "mam2012-safe", "wu2013-safe", "gdam2010-safe", "lb2011-safe", "lc-safe"] {
        let r = run(&[id], limit, 100, 2, false);
        assert!(r.ok(), "{}", render(&r));
        assert_eq!(r.enclosure.len(), 1);
    }
    for id in [
        "broken/planted-no-up/nilsson2012-depth-safe",
        "broken/planted-no-dn/nilsson2012-depth-safe",
        "broken/planted-no-up/mam2012-safe",
        "broken/planted-no-dn/mam2012-safe",
        "broken/planted-no-up/wu2013-safe",
        "broken/planted-no-dn/wu2013-safe",
        "broken/planted-no-up/gdam2010-safe",
        "broken/planted-no-dn/gdam2010-safe",
        "broken/planted-no-up/lb2011-safe",
        "broken/planted-no-dn/lb2011-safe",
        "broken/planted-no-up/lc-safe",
        "broken/planted-no-dn/lc-safe",
    ] {
        let r = run(&[id], limit, 100, 2, false);
        assert!(!r.ok(), "{id} passed");
        let text = render(&r);
        assert!(text.contains("FAILED") && text.contains("SOME PROOFS FAILED"), "{text}");
    }
    for id in ["la2011-safe", "broken/planted-no-up/la2011-safe", "broken/planted-no-dn/la2011-safe"] {
        let e = run_enclosure(id).expect("checked");
        assert_eq!(e.failures.is_empty(), !id.starts_with("broken/"), "{id}: {:?}", e.failures);
    }
}

/// bbox-safe's box against the exact box (the hull of the exact corner values
/// `(a -+ k c) / w`, k = 1 on the x axis), in rationals, on drawn triangles with every
/// w > 0: no finite end on the wrong side. bbox's own box (no pad, no steps) is found on
/// the wrong side, so the attack can fail.
#[test]
fn the_bbox_safe_box_holds_the_exact_box_on_drawn_inputs() {
    use cullproof::bounds::arith::Plain;
    use cullproof::bounds::bbox::{aabb_of, Corner, PlainCorner, SafeCorner};
    fn wrong<C: Corner>(corner: &C, n: usize) -> (usize, usize) {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let (mut bad, mut ends) = (0, 0);
        for i in 0..n {
            let tri = if i % 2 == 0 {
                TriOf::of(&physical_case(&mut rng, Regime::ALL[(i / 2) % Regime::ALL.len()]).triangle)
            } else {
                let base = draw(&mut rng, 1.0);
                let mut vert = || {
                    let mut v = [0; 4].map(|_| draw(&mut rng, base));
                    v[3] = v[3].abs().max(f32::from_bits(1));
                    v
                };
                let (q, r) = ([vert(), vert(), vert()], [vert(), vert(), vert()]);
                let c = |rng: &mut ChaCha8Rng| [0; 3].map(|_| draw(rng, base));
                TriOf { q, r, c0: c(&mut rng), c1: c(&mut rng), k: draw(&mut rng, 1.0) }
            };
            let (enabled, bx) = aabb_of(&Plain, corner, &tri);
            if !enabled {
                continue;
            }
            for axis in 0..2 {
                let mut exact: Vec<X> = vec![];
                for (p, c) in [(&tri.q, &tri.c0), (&tri.r, &tri.c1)] {
                    for i in 0..3 {
                        let s = if axis == 0 { rat(c[i]) } else { arith('*', &rat(tri.k), &rat(c[i])) };
                        for op in ['-', '+'] {
                            exact.push(arith('/', &arith(op, &rat(p[i][axis]), &s), &rat(p[i][3])));
                        }
                    }
                }
                let (lo, hi) = (bx[2 * axis], bx[2 * axis + 1]);
                for e in &exact {
                    for (v, end) in [(lo, End::Lo), (hi, End::Hi)] {
                        if v.is_finite() {
                            ends += 1;
                            if !on_side(&V(v, e.clone()), end) {
                                bad += 1;
                            }
                        }
                    }
                }
            }
        }
        (bad, ends)
    }
    let (bad, ends) = wrong(&SafeCorner, 20_000);
    assert!(ends > 100_000, "only {ends} ends compared");
    assert_eq!(bad, 0, "bbox-safe: {bad} of {ends} ends on the wrong side");
    let (bad, _) = wrong(&PlainCorner, 20_000);
    assert!(bad > 0, "bbox's unpadded box was never found on the wrong side");
}

/// A cull must imply its exact counterpart: a tile edge below a lower end culls, below
/// an upper end does not; a NaN test that can hold is no reason to cull; a condition the
/// code chooses freely may only restrict a cull.
#[test]
fn a_cull_on_the_wrong_end_is_refused() {
    use cullproof::tools::proofs::enclosure::{Bn, Check, Trace, N};
    type Cull = fn(&Trace, N, N, N) -> Bn;
    let below_lo: Cull = |t, lo, _, e| t.lt(&e, &lo);
    let below_hi: Cull = |t, _, hi, e| t.lt(&e, &hi);
    let nan_test: Cull = |t, lo, _, e| t.or(&t.is_nan(&e), &t.lt(&e, &lo));
    let free_and: Cull = |t, lo, hi, e| t.and(&t.choose_truth(&t.lt(&e, &hi), "test"), &t.lt(&e, &lo));
    let free_or: Cull = |t, lo, hi, e| t.or(&t.choose_truth(&t.lt(&e, &hi), "test"), &t.lt(&e, &lo));
    for (name, cull, ok) in [
        ("below a lower end", below_lo, true),
        ("below an upper end", below_hi, false),
        ("a NaN test", nan_test, false),
        ("a free condition restricting it", free_and, true),
        ("a free condition enabling it", free_or, false),
    ] {
        let t = Trace::new();
        let (_, e, lo, hi) = square_and_input(&t);
        let b = cull(&t, lo, hi, e);
        let o = Check::new(&t).run_with(&[], &[(b, "cull".into())]);
        assert_eq!(o.failures.is_empty(), ok, "{name}: {:?}", o.failures);
    }
}

/// The rules mam2012-safe's intervals need refuse what they must: a min over only three
/// of the four end products, a pair of ends of two different values, a quotient whose
/// divisor's sign is not tested, an end "moved out" the wrong way, a rounded end compared
/// `<= 0`, and an interval taken as the same value as another while one of its ends is
/// no end.
#[test]
fn the_interval_rules_refuse_what_they_must() {
    use cullproof::tools::proofs::enclosure::{Bn, Check, Trace, N};
    // Two intervals: [dn(x x), up(x x)] and [dn(c c), up(c c)].
    let setup = |t: &Trace| {
        let (x, c) = (t.input("x"), t.input("c"));
        let (xx, cc) = (t.mul(&x, &x), t.mul(&c, &c));
        let a = [t.next_down(&xx), t.next_up(&xx)];
        let b = [t.next_down(&cc), t.next_up(&cc)];
        let fin = t.and(&t.is_finite(&x), &t.is_finite(&c));
        (a, b, fin)
    };
    type Piece = fn(&Trace, [N; 2], [N; 2]) -> N;
    let four: Piece = |t, a, b| {
        let p = [t.mul(&a[0], &b[0]), t.mul(&a[0], &b[1]), t.mul(&a[1], &b[0]), t.mul(&a[1], &b[1])];
        t.next_down(&t.min_nan(&t.min_nan(&t.min_nan(&p[0], &p[1]), &p[2]), &p[3]))
    };
    let three: Piece = |t, a, b| {
        let p = [t.mul(&a[0], &b[0]), t.mul(&a[0], &b[1]), t.mul(&a[1], &b[0])];
        t.next_down(&t.min_nan(&t.min_nan(&p[0], &p[1]), &p[2]))
    };
    let mixed: Piece = |t, a, b| {
        // [a_lo, b_hi] is no interval of one value
        let p = [t.mul(&a[0], &b[0]), t.mul(&a[0], &b[1]), t.mul(&b[1], &b[0]), t.mul(&b[1], &b[1])];
        t.next_down(&t.min_nan(&t.min_nan(&t.min_nan(&p[0], &p[1]), &p[2]), &p[3]))
    };
    let quotient: Piece = |t, a, b| {
        let q = [t.div(&a[0], &b[0]), t.div(&a[0], &b[1]), t.div(&a[1], &b[0]), t.div(&a[1], &b[1])];
        let lo = t.next_down(&t.min_nan(&t.min_nan(&t.min_nan(&q[0], &q[1]), &q[2]), &q[3]));
        t.select(&t.lt(&t.lit(0.0), &b[0]), &lo, &t.lit(f32::NAN))
    };
    let untested: Piece = |t, a, b| {
        let q = [t.div(&a[0], &b[0]), t.div(&a[0], &b[1]), t.div(&a[1], &b[0]), t.div(&a[1], &b[1])];
        t.next_down(&t.min_nan(&t.min_nan(&t.min_nan(&q[0], &q[1]), &q[2]), &q[3]))
    };
    let moved: Piece = |t, a, _| t.moved_out(&t.sub(&a[0], &t.lit(1e-6)), &a[0], End::Lo);
    let moved_in: Piece = |t, a, _| t.moved_out(&t.add(&a[0], &t.lit(1e-6)), &a[0], End::Lo);
    let same: Piece = |t, a, b| {
        let other = [t.next_down(&t.add(&a[0], &b[0])), t.next_up(&t.add(&a[1], &b[1]))];
        let s = t.pin_same(&other, &a[0], "test: the same value");
        t.max_nan(&a[0], &s[0])
    };
    let same_rounded: Piece = |t, a, b| {
        let other = [t.add(&a[0], &b[0]), t.next_up(&t.add(&a[1], &b[1]))];
        let s = t.pin_same(&other, &a[0], "test: the same value");
        t.max_nan(&a[0], &s[0])
    };
    for (name, piece, ok) in [
        ("four products", four, true),
        ("three products", three, false),
        ("ends of two values", mixed, false),
        ("quotient, divisor tested", quotient, true),
        ("quotient, divisor untested", untested, false),
        ("moved out", moved, true),
        ("moved in", moved_in, false),
        ("same value", same, true),
        ("same value, an end rounded", same_rounded, false),
    ] {
        let t = Trace::new();
        let (a, b, fin) = setup(&t);
        let out = t.select(&fin, &piece(&t, a, b), &t.lit(f32::NEG_INFINITY));
        let o = Check::new(&t).run(&[(out, End::Lo, "out".into())]);
        let out_ok = o.failures.iter().all(|f| f.found == "may be NaN");
        assert_eq!(out_ok, ok, "{name}: {:?}", o.failures);
    }
    // A rounded upper end decides `< 0` (rounding keeps the sign), not `<= 0` (a
    // positive value can round to 0).
    type Cull = fn(&Trace, N, N) -> Bn;
    let lt: Cull = |t, g, zero| t.lt(&g, &zero);
    let le: Cull = |t, g, zero| t.le(&g, &zero);
    for (name, cull, ok) in [("g < 0", lt, true), ("g <= 0", le, false)] {
        let t = Trace::new();
        let (a, _, fin) = setup(&t);
        let w = t.input("w");
        let g = t.sub(&w, &a[0]);
        let b = t.and(&fin, &cull(&t, g, t.lit(0.0)));
        let o = Check::new(&t).run_with(&[], &[(b, "cull".into())]);
        assert_eq!(o.failures.is_empty(), ok, "{name}: {:?}", o.failures);
    }
}

/// The exact edge values `E_k = P_i x P_j` of `gdam2010-safe` at the sample position
/// `(x, y)` and time `t` (rationals from the f32 inputs, no rounding): whether all
/// three are > 0 or all < 0 (the covered times are among those).
fn gdam_covered(q: &[[f32; 3]; 3], r: &[[f32; 3]; 3], x: f32, y: f32, t: f32) -> bool {
    let num = |v: X| match v {
        X::Num(n, d) => (n, d),
        _ => unreachable!("finite inputs"),
    };
    let (xs, ys, ts) = (rat(x), rat(y), rat(t));
    let p: Vec<[X; 2]> = (0..3)
        .map(|i| {
            let at = |c: usize| arith('+', &rat(q[i][c]), &arith('*', &ts, &arith('-', &rat(r[i][c]), &rat(q[i][c]))));
            let w = at(2);
            [arith('-', &at(0), &arith('*', &xs, &w)), arith('-', &at(1), &arith('*', &ys, &w))]
        })
        .collect();
    let signs: Vec<Ordering> = [(1, 2), (2, 0), (0, 1)]
        .iter()
        .map(|&(i, j)| {
            let e = arith('-', &arith('*', &p[i][0], &p[j][1]), &arith('*', &p[i][1], &p[j][0]));
            let (n, d) = num(e);
            (n * d).cmp(&BigInt::from(0))
        })
        .collect();
    signs.iter().all(|&s| s == Ordering::Greater) || signs.iter().all(|&s| s == Ordering::Less)
}

/// f64 estimates of where the edges of `gdam2010-safe` change sign at `(x, y)`: the
/// roots in (0, 1) of each edge's quadratic in t, and its vertex (where pieces are cut).
fn gdam_turns(q: &[[f32; 3]; 3], r: &[[f32; 3]; 3], x: f32, y: f32) -> Vec<f64> {
    let rel = |p: [f32; 3]| [p[0] as f64 - x as f64 * p[2] as f64, p[1] as f64 - y as f64 * p[2] as f64];
    let mut out = vec![];
    for (i, j) in [(1, 2), (2, 0), (0, 1)] {
        let (a, b) = (rel(q[i]), rel(q[j]));
        let (da, db) = ([rel(r[i])[0] - a[0], rel(r[i])[1] - a[1]], [rel(r[j])[0] - b[0], rel(r[j])[1] - b[1]]);
        let cr = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
        let (qa, qb, qc) = (cr(da, db), cr(a, db) + cr(da, b), cr(a, b));
        if qa != 0.0 {
            out.push(-qb / (2.0 * qa));
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 {
                out.extend([(-qb - disc.sqrt()) / (2.0 * qa), (-qb + disc.sqrt()) / (2.0 * qa)]);
            }
        } else if qb != 0.0 {
            out.push(-qc / qb);
        }
    }
    out.retain(|t| *t > 0.0 && *t < 1.0);
    out
}

/// gdam2010-safe's culls attacked in exact arithmetic, at sample positions on and next
/// to the edges' lines (a point of an edge at t = 0 or t = 1, rounded to f32, and the
/// tile's corners) and on pieces of the shutter next to where the edges change sign
/// (2^-23 to 2^-6 from a root or a vertex, 2^-10 to 1 wide) or at the shutter's ends;
/// every other case with its winding turned. Every piece the code culls must have its
/// exact counterpart true (the check's claim), and no time of it, at its ends, one f32
/// step inside them and 7 points between, may
/// have all three exact edge values of one strict sign (the method's claim); every
/// shortcut taken (`select_same`) must keep its exact value. With
/// `padded` false the pads are 0: the culls come as close to the edges as the rounding
/// lets them. Returns the failures, the pieces tried, culled, and the times checked.
fn gdam_attack<R: Round>(n: usize, seed: u64, padded: bool) -> (Vec<String>, usize, usize, usize) {
    use cullproof::bounds::gdam2010::{end_of, piece_of, sample_of, still_of};
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let ar = Pair::default();
    let (mut bad, mut pieces, mut culled, mut times) = (vec![], 0, 0, 0);
    use Regime::*;
    let regimes = [Static, Motion, BehindLens, Sliver, Tiny, Huge, Perspective, FacingFlip, FarFromOrigin, Degenerate];
    for i in 0..n {
        let case = physical_case(&mut rng, regimes[i % regimes.len()]);
        let tri = &case.triangle;
        let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
        let (mut q, mut r) = (tri.q.map(xyw), tri.r.map(xyw));
        // Every other case with its winding turned (two vertices swapped): the edges'
        // signs inside are then the other way round.
        if i % 2 == 1 {
            q.swap(1, 2);
            r.swap(1, 2);
        }
        if !q.iter().chain(r.iter()).flatten().all(|v| v.is_finite()) {
            continue;
        }
        let size = [1.0, 4.0, 16.0][rng.gen_range(0..3)];
        let tile = boundary_tile(&case, &mut rng, size);
        // A point of edge (i, j) at one shutter end, in screen coordinates.
        let (a, s, end) = (rng.gen_range(0..3), rng.gen::<f64>(), rng.gen_range(0..2));
        let b = (a + rng.gen_range(1..3)) % 3;
        let v = if end == 0 { &q } else { &r };
        let scr = |p: [f32; 3], c: usize| p[c] as f64 / p[2] as f64;
        let on = [0, 1].map(|c| (scr(v[a], c) + s * (scr(v[b], c) - scr(v[a], c))) as f32);
        let positions = [on, [tile.x0, tile.y0], [tile.x1, tile.y1]];
        for [x, y] in positions {
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            let (qv, rv) = (q.map(|p| p.map(|c| ar.lit(c))), r.map(|p| p.map(|c| ar.lit(c))));
            let smp = sample_of::<R, Pair>(&ar, &qv, &rv, &ar.lit(x), &ar.lit(y), padded);
            let mut cands = vec![(0.0f32, 1.0f32)];
            for t in gdam_turns(&q, &r, x, y) {
                for d in [2f64.powi(-23), 2f64.powi(-18), 2f64.powi(-12), 2f64.powi(-6)] {
                    for w in [2f64.powi(-10), 0.125, 1.0] {
                        cands.push(((t + d) as f32, ((t + d + w).min(1.0)) as f32));
                        cands.push((((t - d - w).max(0.0)) as f32, (t - d) as f32));
                    }
                }
            }
            for w in [2f32.powi(-20), 2f32.powi(-8), 0.25] {
                cands.extend([(0.0, w), (1.0 - w, 1.0)]);
            }
            for (l, h) in cands {
                if !(0.0 <= l && l <= h && h <= 1.0) {
                    continue;
                }
                pieces += 1;
                let (el, eh) = (end_of::<R, Pair>(&ar, &smp, &ar.lit(l)), end_of::<R, Pair>(&ar, &smp, &ar.lit(h)));
                let (cull, _) = piece_of::<R, Pair>(&ar, &smp, &el, &eh);
                if !cull.0 {
                    continue;
                }
                culled += 1;
                if cull.1 != Some(true) {
                    bad.push(format!("piece [{l}, {h}] at ({x}, {y}): culled, its exact counterpart {:?}", cull.1));
                }
                let mut ts = vec![l, h, l.next_up().min(h), h.next_down().max(l)];
                ts.extend((1..8).map(|k| l + (h - l) * k as f32 / 8.0));
                for t in ts.into_iter().filter(|t| (l..=h).contains(t)) {
                    times += 1;
                    if gdam_covered(&q, &r, x, y, t) {
                        bad.push(format!("piece [{l}, {h}] at ({x}, {y}): culled, t = {t} covered ({tri:?})"));
                    }
                }
            }
            // The whole shutter of a triangle that does not move.
            let e0 = end_of::<R, Pair>(&ar, &smp, &ar.lit(0.0));
            let (cull, _) = still_of::<R, Pair>(&ar, &smp, &e0);
            if cull.0 {
                culled += 1;
                if cull.1 != Some(true) {
                    bad.push(format!("still triangle at ({x}, {y}): culled, its exact counterpart {:?}", cull.1));
                }
                times += 1;
                if gdam_covered(&q, &r, x, y, 0.0) {
                    bad.push(format!("still triangle at ({x}, {y}): culled, covered ({tri:?})"));
                }
            }
        }
    }
    // Every shortcut taken kept its exact value.
    bad.extend(ar.bad.borrow().iter().cloned());
    let taken = *ar.shortcuts.borrow();
    eprintln!("shortcuts taken (exact values compared): {taken}");
    assert!(taken > 10_000, "only {taken} shortcuts taken");
    (bad, pieces, culled, times)
}

/// gdam2010-safe passes the check; its slips fail it; and the culls the check vouches
/// for hold in exact arithmetic (with its pads and with every pad 0), where the same
/// pieces without outward steps and pads are caught.
#[test]
fn gdam2010_safe_pieces_are_checked_and_hold_in_exact_arithmetic() {
    let o = check("gdam2010-safe").expect("gdam2010-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 2, "a piece's cull and a still triangle's cull");
    assert_eq!(o.choices.len(), 1, "the pad: {:?}", o.choices);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("min (max) of the four end products or quotients") >= 24, "{:?}", o.rules);
    for id in ["broken/planted-no-up/gdam2010-safe", "broken/planted-no-dn/gdam2010-safe"] {
        let o = check(id).expect("a planted slip of a checked variant is checked");
        assert!(
            o.failures.iter().any(|f| f.what.contains("piece cull") && f.found.contains("imply")),
            "{id}: {:?}",
            o.failures
        );
    }
    for padded in [true, false] {
        let (bad, pieces, culled, times) = gdam_attack::<Outward>(700, 7, padded);
        eprintln!("gdam2010-safe (padded {padded}): {pieces} pieces, {culled} culled, {times} times checked exactly");
        assert!(bad.is_empty(), "{} failures: {:?}", bad.len(), &bad[..bad.len().min(5)]);
        assert!(culled > 10_000 && times > 200_000, "{pieces} pieces, {culled} culled, {times} times");
    }
    // The same pieces rounded to nearest without steps (as a published f32 method
    // would), unpadded: culled where they are not.
    // (The slips, one side's steps dropped, rarely cull a covered time: the check
    // refuses them above; the attack needs both sides gone.)
    let (nearest, _, _, _) = gdam_attack::<Nearest>(700, 7, false);
    let wrong_shortcuts = nearest.iter().filter(|b| b.starts_with("shortcut")).count();
    eprintln!("unpadded, no steps: {} failures, {wrong_shortcuts} of them shortcuts", nearest.len());
    // (Without steps an interval [r, r] with r = 0 is taken as 0 where its exact value
    // is not: the shortcut's check can fail too.)
    assert!(wrong_shortcuts > 0, "no wrong shortcut found without steps");
    assert!(nearest.len() >= 10, "the attack cannot fail: {}", nearest.len());
}

/// A shortcut of one exact value (`F32Arith::select_same`) is verified: an interval
/// `[0, 0]` stands for 0, equal inputs for one value, a time of 0 for 0; a shortcut
/// taken on one end only, on inputs compared in part, or with the wrong branch is
/// refused.
#[test]
fn a_shortcut_must_keep_its_exact_value() {
    use cullproof::tools::proofs::enclosure::{Check, Trace};
    type Piece = fn(&Trace) -> u32;
    // [lo, hi] encloses x y; b + [lo, hi] where the interval is [0, 0] is b.
    fn sum(t: &Trace, both: bool) -> u32 {
        let (x, y, b) = (t.input("x"), t.input("y"), t.input("b"));
        let p = t.mul(&x, &y);
        let (lo, hi) = (t.next_down(&p), t.next_up(&p));
        let zero = t.lit(0.0);
        let z = if both { t.and(&t.eq(&lo, &zero), &t.eq(&hi, &zero)) } else { t.eq(&hi, &zero) };
        t.select_same(&z, &b, &t.next_up(&t.add(&hi, &b)), "zero sum")
    }
    // x - X w at both ends: their difference is 0 where the inputs are equal.
    fn still(t: &Trace, all: bool, swap: bool) -> u32 {
        let nx = t.neg(&t.input("X"));
        let (q, r) = (["qx", "qw"].map(|n| t.input(n)), ["rx", "rw"].map(|n| t.input(n)));
        let (a, b) = (t.fma(&nx, &q[1], &q[0]), t.fma(&nx, &r[1], &r[0]));
        let d = t.next_up(&t.sub(&t.next_up(&b), &t.next_down(&a)));
        let eq = if all { t.and(&t.eq(&q[0], &r[0]), &t.eq(&q[1], &r[1])) } else { t.eq(&q[0], &r[0]) };
        let tt = t.input("t");
        let moved = t.select_same(&eq, &t.lit(0.0), &d, "still");
        // a + t d at t = 0 is a (swapped: b, wrong).
        let at = t.next_up(&t.add(&t.next_up(&a), &t.next_up(&t.mul(&tt, &moved))));
        let end = if swap { t.next_up(&b) } else { t.next_up(&a) };
        t.select_same(&t.eq(&tt, &t.lit(0.0)), &end, &at, "at zero")
    }
    let cases: [(&str, Piece, bool); 5] = [
        ("both ends 0", |t| sum(t, true), true),
        ("one end 0", |t| sum(t, false), false),
        ("all inputs equal", |t| still(t, true, false), true),
        ("some inputs equal", |t| still(t, false, false), false),
        ("the other end's value", |t| still(t, true, true), false),
    ];
    for (name, piece, ok) in cases {
        let t = Trace::new();
        let out = piece(&t);
        let o = Check::new(&t).run(&[(out, End::Hi, "out".into())]);
        let refused = o.failures.iter().any(|f| f.what.starts_with("shortcut"));
        assert_eq!(!refused, ok, "{name}: {:?}", o.failures);
        if ok {
            assert!(o.rules.iter().any(|(r, k)| r.contains("shortcut") && *k > 0), "{name}: {:?}", o.rules);
        }
    }
}

/// lb2011-safe over the pair arithmetic: the t, u and v ranges (where the tile is
/// kept), the tile reject, and each emitted patch's cull at samples next to its zero
/// (l one to three f32 steps either side of the f32 root in l at t in {0, 1/4, 1/2, 1},
/// and t likewise at l in {-1, -1/2, 0, 1/2, 1}). A cull's exact counterpart is the
/// exact patch through the pinned corner values below 0 (the pins themselves are
/// checked against the exact min and max by the pair arithmetic); with `padded` false
/// the cull reads the patch without its pad (`pad_off`) instead.
fn lb2011_with<R: Round>(
    ar: &Pair,
    tri: &TriOf<V>,
    tile: &[V; 4],
    padded: bool,
) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    use cullproof::bounds::lb2011::{axis_answer, axis_of, coefficients, eval_of, tile_of};
    let [ax, ay] = [0, 1].map(|a| axis_of::<R, Pair>(ar, tri, a));
    let (xa, xp) = axis_answer::<R, Pair>(ar, &ax, &tile[0], &tile[2]);
    let (ya, yp) = axis_answer::<R, Pair>(ar, &ay, &tile[1], &tile[3]);
    let (reject, t, u, v) = tile_of(ar, &xa, &ya);
    let kept = ar.not(&reject);
    let mut ranges = vec![];
    for (name, r, full) in [("t", &t, [0.0, 1.0]), ("u", &u, [-1.0, 1.0]), ("v", &v, [-1.0, 1.0])] {
        ranges.push((name, [0, 1].map(|k| ar.select(&kept, &r[k], &ar.lit(full[k])))));
    }
    let mut culls = vec![reject];
    for p in xp.iter().chain(&yp) {
        if !p.emit.0 {
            continue;
        }
        let plain = coefficients(ar, &p.g);
        let coef = if padded { p.coef.clone() } else { plain.clone() };
        let c: [f32; 4] = coef.each_ref().map(|x| x.0);
        let mut samples = vec![];
        for tv in [0.0f32, 0.25, 0.5, 1.0] {
            let root = -(c[0] + c[2] * tv) / (c[1] + c[3] * tv);
            samples.extend(around(root).map(|l| (l, tv)));
        }
        for lv in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            let root = -(c[0] + c[1] * lv) / (c[2] + c[3] * lv);
            samples.extend(around(root).map(|t| (lv, t)));
        }
        for (lv, tv) in samples {
            if !(lv.abs() <= 1.0 && (0.0..=1.0).contains(&tv)) {
                continue;
            }
            let (l, st) = (ar.lit(lv), ar.lit(tv));
            let g = eval_of(ar, &coef, &l, &st);
            let exact = eval_of(ar, &plain, &l, &st);
            let below = cmp(&exact.1, &X::Num(0.into(), 1.into())).map(|o| o == Ordering::Less);
            culls.push((g.0 < 0.0, below));
        }
    }
    (ranges, culls)
}

/// Seven f32 values around `x`: three steps down, `x`, three steps up.
fn around(x: f32) -> [f32; 7] {
    let mut v = [x; 7];
    for k in 1..4 {
        v[3 - k] = v[4 - k].next_down();
        v[3 + k] = v[2 + k].next_up();
    }
    v
}

/// lc-safe: la2011-safe's and lb2011-safe's answers met (`meet_of`, as the conjunction
/// meets them), the combined tile reject, and lb2011-safe's patch culls.
fn lc<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    use cullproof::bounds::meet_of;
    let (la, la_culls) = la2011::<R>(ar, tri, tile);
    let (lb, lb_culls) = lb2011_with::<R>(ar, tri, tile, true);
    // la2011's ranges (t, u, v) are its answer's; lb2011's are selected where kept,
    // which is what the conjunction reads (a rejected part makes the whole Empty).
    let met: Vec<[V; 2]> = la.iter().zip(&lb).map(|((_, a), (_, b))| meet_of(ar, a, b)).collect();
    let empty: Vec<T> = met.iter().map(|r| ar.lt(&r[1], &r[0])).collect();
    let reject = ar.any(&[la_culls[0], lb_culls[0], ar.any(&empty)]);
    let kept = ar.not(&reject);
    let mut ranges = vec![];
    for ((name, _), (r, full)) in la.iter().zip(met.iter().zip([[0.0, 1.0], [-1.0, 1.0], [-1.0, 1.0]])) {
        ranges.push((*name, [0, 1].map(|k| ar.select(&kept, &r[k], &ar.lit(full[k])))));
    }
    (ranges, [vec![reject], lb_culls[1..].to_vec()].concat())
}

fn lb2011<R: Round>(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    lb2011_with::<R>(ar, tri, tile, true)
}

fn lb2011_unpadded(ar: &Pair, tri: &TriOf<V>, tile: &[V; 4]) -> (Vec<(&'static str, [V; 2])>, Vec<T>) {
    lb2011_with::<Nearest>(ar, tri, tile, false)
}

/// lb2011-safe: the check passes over its code (the corners pinned, every patch's f32
/// value found to be `lb2011_safe.g`'s formula), a script with another pad, floor or
/// limit is refused, and in exact arithmetic on drawn inputs no end lies on the wrong
/// side, no pin either, and no patch culls a sample its exact patch keeps. Controls: the
/// slips leave ends on the wrong side, and the patches rounded to nearest without steps
/// or pad cull samples they must keep.
#[test]
fn lb2011_safe_is_checked_and_holds_in_exact_arithmetic() {
    use cullproof::bounds::proofs::LB_PAD;
    use cullproof::tools::proofs::check::with_constant;
    use cullproof::tools::proofs::enclosure::check_lb2011_with;
    let o = check("lb2011-safe").expect("lb2011-safe is checked");
    assert!(o.failures.is_empty(), "{:?}", o.failures);
    assert_eq!(o.outputs, 11, "t, u, v: both ends each, the tile reject and the four patches' culls");
    assert_eq!(o.lemmas.len(), 3, "the corners, the chord, lb2011_safe.g: {:?}", o.lemmas);
    let used = |r: &str| o.rules.iter().find(|(n, _)| *n == r).map_or(0, |x| x.1);
    assert!(used("an end a lemma proves") >= 4, "every patch's f32 value: {:?}", o.rules);
    assert!(used("fused multiply-add of an end by an exact factor of known sign") >= 2, "{:?}", o.rules);
    for (name, value) in [("PAD", "1b-19"), ("FLOOR", "1b-139"), ("LIMIT", "1b121")] {
        let text = with_constant(&LB_PAD, name, value);
        assert_ne!(text, LB_PAD.text);
        let o = check_lb2011_with(&text);
        assert!(o.failures.iter().any(|f| f.what.contains("patch")), "{name} = {value} passed: {:?}", o.failures);
        assert!(!o.failures.iter().any(|f| f.what.contains("tile reject")), "{name}: {:?}", o.failures);
    }
    let (bad, n, inside, culls) = attack(lb2011::<Outward>, 20_000, 3);
    assert!(bad.is_empty(), "{} of {n}: {:?}", bad.len(), &bad[..bad.len().min(5)]);
    assert!(inside * 20 > n, "only {inside} of {n} ends inside the domain");
    assert!(culls >= 100, "only {culls} tiles culled");
    let (bad_up, _, _, _) = attack(lb2011::<NoUp>, 4000, 3);
    let (bad_dn, _, _, _) = attack(lb2011::<NoDn>, 4000, 3);
    let (nearest, _, _, _) = attack(lb2011_unpadded, 4000, 3);
    let sample = nearest.iter().filter(|b| b.starts_with("per-sample")).count();
    eprintln!(
        "lb2011-safe: ends compared {n}, inside the domain {inside}, tiles culled {culls}; slips: {} and {} wrong; \
         no steps, no pad: {} wrong, {sample} of them per-sample culls",
        bad_up.len(),
        bad_dn.len(),
        nearest.len()
    );
    assert!(bad_up.iter().any(|b| b.contains("Hi")), "the no-up slip was not caught by the attack");
    assert!(bad_dn.iter().any(|b| b.contains("Lo")), "the no-dn slip was not caught by the attack");
    assert!(sample > 0, "the unpadded patches culled no sample wrongly: the attack cannot fail");
}
