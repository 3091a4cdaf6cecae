//! A query family: what the symbolic search needs to know about one encoded method.
//! A family names the f32 inputs of its template and its sides (which part of the
//! bound a query attacks), asserts over [`Smt`] that the method culls the template's
//! tile although the exact footprint reaches it, and turns a model's inputs back into
//! a case. The runner ([`super::prove`]) and the concolic planner
//! ([`super::concolic`]) work on any family; a newly encoded method plugs in with one
//! implementation and one arm in [`super::prove::family`].

use super::smt::Smt;
use crate::model::{Tile, Triangle};
use anyhow::{bail, Result};

/// The template of one encoded method.
pub trait Family: Sync {
    /// The free f32 inputs of the template, in order.
    fn inputs(&self) -> &'static [&'static str];
    /// The sides the queries attack, by name.
    fn sides(&self) -> &'static [&'static str];
    /// Inputs that only place the tile (no division or other costly step depends on
    /// them): the concolic search always leaves them free, so that the solver places
    /// the tile in the gap a fixed triangle leaves.
    fn tile_inputs(&self) -> &'static [usize];
    /// The default range sets of a side (one `[lo, hi)` per input each).
    fn default_ranges(&self, side: usize) -> Vec<Vec<[f32; 2]>>;
    /// Whether `[lo, hi)` is allowed for input `k` (an explanation when not).
    fn check_range(&self, k: usize, lo: f32, hi: f32) -> std::result::Result<(), String>;
    /// Assert over `smt` that, for the inputs `v` (free variables or literals), the
    /// exact footprint of the template's triangle reaches into its tile of side `side`
    /// (the hypotheses of a violation, without the method).
    fn assert_reached(&self, smt: &Smt, side: usize, v: &[String]);
    /// Assert over `smt` that, for the inputs `v`, the method culls the template's tile
    /// of side `side` while the exact footprint reaches into it.
    fn assert_violation(&self, smt: &Smt, side: usize, v: &[String]);
    /// The triangle and tile of concrete inputs, computed in f32 by the same template.
    fn instance(&self, side: usize, v: &[f32]) -> (Triangle, Tile);
    /// When only part of the method's cull is encoded: the parts left out (an `unsat`
    /// then proves nothing; a model is still judged against the whole method).
    fn partial(&self) -> Option<&'static str> {
        None
    }
    /// Whether a violation may also be a depth interval that excludes the covered
    /// samples' depth on a kept tile (not only a culled tile).
    fn depth(&self) -> bool {
        false
    }
}

/// One query: a side, a half-open range per input, and the inputs fixed to a value
/// (the others are free: the solver chooses them within their ranges).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Query {
    pub side: usize,
    pub ranges: Vec<[f32; 2]>,
    /// Per input: `Some(v)` fixes it to `v` (inside its range), `None` leaves it free.
    pub fixed: Vec<Option<f32>>,
}

impl Query {
    /// A query with every input free.
    pub fn free(side: usize, ranges: Vec<[f32; 2]>) -> Self {
        let n = ranges.len();
        Query { side, ranges, fixed: vec![None; n] }
    }

    /// The ranges of the free inputs and the values of the fixed ones, as
    /// `a=LO:HI,c=V,...` (the free ranges in the syntax of `--ranges`).
    pub fn text(&self, f: &dyn Family) -> String {
        f.inputs()
            .iter()
            .zip(self.ranges.iter().zip(&self.fixed))
            .map(|(n, (r, x))| match x {
                Some(v) => format!("{n}={v:e}"),
                None => format!("{n}={}:{}", r[0], r[1]),
            })
            .collect::<Vec<_>>()
            .join(",")
    }
}

/// A query's inputs over `smt`: a literal per fixed input, a variable confined to its
/// range per free one; and the names of the free ones, whose values a model shows.
fn inputs(smt: &Smt, f: &dyn Family, q: &Query) -> (Vec<String>, Vec<String>) {
    let (mut v, mut shown) = (Vec::new(), Vec::new());
    for (k, name) in f.inputs().iter().enumerate() {
        match q.fixed[k] {
            Some(x) => v.push(super::smt::lit(x)),
            None => {
                let n = smt.var(name);
                smt.range(&n, q.ranges[k][0], q.ranges[k][1]);
                shown.push(n.clone());
                v.push(n);
            }
        }
    }
    (v, shown)
}

/// The script of a query (folding the fixed inputs into the method's steps; see
/// [`Smt::folding`]) and the names of its free inputs, whose values the model shows.
pub fn script(f: &dyn Family, q: &Query) -> (String, Vec<String>) {
    let smt = Smt::folding();
    let (v, shown) = inputs(&smt, f, q);
    f.assert_violation(&smt, q.side, &v);
    (smt.script(&shown), shown)
}

/// The hypotheses of a query alone: its free inputs in their ranges (the fixed ones
/// are literals) and the exact footprint reaching the tile, without the claim that the
/// method culls it. An `unsat` of the query counts only when this script is `sat` with
/// the same solver: ranges that contradict each other, or that hold no reached tile at
/// all (the tile always beside the triangle), would make every claim `unsat`.
pub fn hypotheses_script(f: &dyn Family, q: &Query) -> String {
    let smt = Smt::folding();
    let (v, shown) = inputs(&smt, f, q);
    f.assert_reached(&smt, q.side, &v);
    smt.script(&shown)
}

/// Every literal constant the method's and the template's code use on a side (the
/// `lit()` calls of the encoding with every input free).
pub fn literals(f: &dyn Family, side: usize) -> Vec<f32> {
    let smt = Smt::folding();
    let v: Vec<String> = f.inputs().iter().map(|n| smt.var(n)).collect();
    f.assert_violation(&smt, side, &v);
    smt.literals()
}

/// Parse `--ranges NAME=LO:HI,...` (every input of the family named once, each range
/// non-empty and allowed by the family) into one range set.
pub fn parse_ranges(f: &dyn Family, flag: &str, s: &str) -> Result<Vec<[f32; 2]>> {
    let names = f.inputs().join(", ");
    let mut ranges: Vec<Option<[f32; 2]>> = vec![None; f.inputs().len()];
    for part in s.split(',') {
        let Some((name, r)) = part.trim().split_once('=') else {
            bail!("{flag} {s}: `{part}` is not NAME=LO:HI (names: {names})");
        };
        let Some(k) = f.inputs().iter().position(|n| *n == name.trim()) else {
            bail!("{flag} {s}: `{name}` is not an input (names: {names})");
        };
        let Some((lo, hi)) = r.split_once(':') else {
            bail!("{flag} {s}: `{r}` for `{name}` is not LO:HI");
        };
        let num = |v: &str| -> Result<f32> {
            match v.trim().parse::<f32>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => bail!("{flag} {s}: `{v}` for `{name}` is not a finite number"),
            }
        };
        let (lo, hi) = (num(lo)?, num(hi)?);
        if lo >= hi {
            bail!("{flag} {s}: the range {lo}:{hi} of `{name}` is empty (LO must be below HI)");
        }
        if let Err(e) = f.check_range(k, lo, hi) {
            bail!("{flag} {s}: {e}");
        }
        if ranges[k].replace([lo, hi]).is_some() {
            bail!("{flag} {s}: `{name}` is given twice");
        }
    }
    let mut out = Vec::new();
    for (k, r) in ranges.iter().enumerate() {
        match r {
            Some(r) => out.push(*r),
            None => bail!("{flag} {s}: no range for `{}` (give {names})", f.inputs()[k]),
        }
    }
    Ok(out)
}
