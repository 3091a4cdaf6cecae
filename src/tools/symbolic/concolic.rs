//! The concolic plan: many small queries instead of a few whole ones. In each query
//! some inputs are fixed to concrete values and the others are left to the solver; a
//! step whose operands are all fixed folds into a literal ([`super::smt::Smt::folding`]),
//! so a division by a fixed depth, or a whole axis of fixed values, disappears from the
//! query and the solver's problem shrinks to the part that depends on the free inputs.
//!
//! # How a query is drawn (deterministic for a seed)
//! - Side and range set in turn (query `i` takes set `i mod n`).
//! - The tile's inputs ([`Family::tile_inputs`]) are always free; of the other inputs,
//!   one, chosen at random, is free in a share `free_share` of the queries (`--free-share`,
//!   default none), none in the others. A free one keeps
//!   its whole range (30 %), or is confined to one *piece* of it (40 %), or to a
//!   *window* of 2^4 to 2^12 consecutive f32 values around a value drawn as for a fixed
//!   input (30 %: its high bits fixed, its low bits free).
//! - The pieces of an input's range are cut at its *boundary points*: the range's ends,
//!   the powers of two inside it (binade boundaries, at most 12 binades below its
//!   largest magnitude) and every literal constant the method's and the template's code
//!   use ([`super::family::literals`], with its negation), when inside the range.
//!   Harvesting is generic: every `lit()` the encoding of the side calls, nothing chosen
//!   by hand.
//! - A fixed input is, with probability 0.3, a boundary point or one of its two f32
//!   neighbours; with probability 0.3 the value (3 in 4) or the negation of an input
//!   fixed before it (coinciding inputs); otherwise uniform in a piece drawn uniformly.
//!   A draw outside the range falls back to the uniform one.
//!
//! Why mostly none: on the bbox template a query with every triangle input fixed takes
//! about 0.05 s (the box folds to constants; z3 places the tile in the gap between the
//! box and the exact edge, or shows there is none), while one with a triangle input
//! free, even confined to 16 consecutive values, takes about a second (it must invert
//! an f32 division bit by bit): enumerating is faster than solving there. The free
//! queries stay available (`--free-share`) for templates where solving pays.
//!
//! An `unsat` of such a query says nothing about other values of the fixed inputs: the
//! runner reports it as "none with these fixed values", never as a proof.

use super::family::{literals, Family, Query};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The boundary points of `[lo, hi)`: its ends, the powers of two inside it (and their
/// negations), zero, and the literals inside it (and their negations), sorted.
pub fn boundaries(lo: f32, hi: f32, lits: &[f32]) -> Vec<f32> {
    let mut p = vec![lo, hi];
    let top = lo.abs().max(hi.abs());
    let etop = if top > 0.0 { top.log2().ceil() as i32 } else { 0 };
    for e in (etop - 12).max(-126)..=etop.min(127) {
        let v = 2f32.powi(e);
        p.extend([v, -v]);
    }
    p.push(0.0);
    for &l in lits {
        if l.is_finite() {
            p.extend([l, -l]);
        }
    }
    let mut p: Vec<f32> = p.into_iter().filter(|v| *v >= lo && *v <= hi).map(|v| v + 0.0).collect();
    p.sort_by(|a, b| a.total_cmp(b));
    p.dedup();
    p
}

/// Uniform in `[lo, hi)` (as an f32 inside the range).
fn uniform(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    let x = (lo as f64 + rng.gen::<f64>() * (hi as f64 - lo as f64)) as f32;
    if x >= hi {
        hi.next_down()
    } else {
        x.max(lo)
    }
}

/// A piece `[p_i, p_{i+1})` of the range cut at its boundary points.
fn piece(rng: &mut ChaCha8Rng, pts: &[f32]) -> [f32; 2] {
    let i = rng.gen_range(0..pts.len() - 1);
    [pts[i], pts[i + 1]]
}

/// A value for an input in `[lo, hi)` with boundary points `pts`, given the values of
/// the inputs fixed before it (see the module doc).
fn draw(rng: &mut ChaCha8Rng, lo: f32, hi: f32, pts: &[f32], earlier: &[Option<f32>]) -> f32 {
    let earlier: Vec<f32> = earlier.iter().flatten().copied().collect();
    let r = rng.gen::<f64>();
    let v = if r < 0.3 {
        let p = pts[rng.gen_range(0..pts.len())];
        match rng.gen_range(0..3) {
            0 => p.next_down(),
            1 => p,
            _ => p.next_up(),
        }
    } else if r < 0.6 && !earlier.is_empty() {
        let x = earlier[rng.gen_range(0..earlier.len())];
        if rng.gen_bool(0.75) {
            x
        } else {
            -x
        }
    } else {
        f32::NAN
    };
    if v >= lo && v < hi {
        v
    } else {
        let [plo, phi] = piece(rng, pts);
        uniform(rng, plo, phi)
    }
}

/// The `2^bits` consecutive f32 values around `v` (a third below, two thirds above),
/// clipped to `[lo, hi)`: the free input's high bits fixed, its low bits free.
pub fn window(v: f32, bits: u32, lo: f32, hi: f32) -> [f32; 2] {
    let n = 1u32 << bits;
    let (mut a, mut b) = (v, v);
    for _ in 0..n / 3 {
        a = a.next_down();
    }
    for _ in 0..n - n / 3 {
        b = b.next_up();
    }
    [a.max(lo), b.min(hi)]
}

/// `n` queries over the range sets `sets` (a side and a range per input each), for a
/// seed, with a triangle input free in a share `free_share` of them.
pub fn plan(f: &dyn Family, sets: &[(usize, Vec<[f32; 2]>)], seed: u64, n: usize, free_share: f64) -> Vec<Query> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let lits: Vec<Vec<f32>> = (0..f.sides().len()).map(|s| literals(f, s)).collect();
    let tile = f.tile_inputs();
    let others: Vec<usize> = (0..f.inputs().len()).filter(|k| !tile.contains(k)).collect();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let (side, ranges) = &sets[i % sets.len()];
        let pts: Vec<Vec<f32>> = ranges.iter().map(|r| boundaries(r[0], r[1], &lits[*side])).collect();
        let nfree = usize::from(rng.gen::<f64>() < free_share).min(others.len());
        let mut pool = others.clone();
        let mut free: Vec<usize> = tile.to_vec();
        for _ in 0..nfree {
            free.push(pool.swap_remove(rng.gen_range(0..pool.len())));
        }
        let mut q = Query::free(*side, ranges.clone());
        for k in 0..ranges.len() {
            let [lo, hi] = ranges[k];
            let v = draw(&mut rng, lo, hi, &pts[k], &q.fixed[..k]);
            if !free.contains(&k) {
                q.fixed[k] = Some(v);
            } else if !tile.contains(&k) {
                let r = rng.gen::<f64>();
                if r < 0.4 {
                    q.ranges[k] = piece(&mut rng, &pts[k]);
                } else if r < 0.7 {
                    q.ranges[k] = window(v, rng.gen_range(4..=12), lo, hi);
                }
            }
        }
        out.push(q);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundaries_cut_at_binades_and_literals() {
        let b = boundaries(0.5, 4.0, &[2.0, 2.0001, 64.0, f32::NAN]);
        assert_eq!(b, vec![0.5, 1.0, 2.0, 2.0001, 4.0]);
        let b = boundaries(-3.0, 3.0, &[]);
        assert!(!b.contains(&2f32.powi(-11)) && b.contains(&2f32.powi(-10)), "{b:?}");
        assert!(b.contains(&0.0) && b.contains(&-2.0) && b.contains(&1.0) && b[0] == -3.0);
    }
}
