//! Counting the samples of a tile that an answer admits (see the module documentation
//! of [`super`], "How it runs"): the intervals side by side, then each per-sample
//! constraint once per row ([`SampleConstraint::eval_row`]), or the verdicts of a
//! tile-independent answer's constraints looked up ([`region_pass`]).

use super::table::Local;
use super::{Counts, SampleTable};
use crate::bounds::{SampleCols, SampleConstraint};

/// The samples of one tile being counted: the rows (`tile_rows`) over the table and
/// the triangle's coverage, `n` samples of which `cov` are covered.
pub(super) struct Here<'a> {
    pub(super) table: &'a SampleTable,
    pub(super) local: &'a Local,
    pub(super) rows: &'a [(usize, usize, usize)],
    pub(super) n: u64,
    pub(super) cov: u64,
}

/// Into `pass`, per sample of the [`Local`] region: no constraint of `cons` culls it
/// (`g < 0` for none; a NaN value culls nothing), the values computed row by row
/// ([`SampleConstraint::eval_row`]).
pub(super) fn region_pass(
    sc: &mut AdmitScratch,
    cons: &[&[Box<dyn SampleConstraint>]],
    table: &SampleTable,
    local: &Local,
    pass: &mut Vec<bool>,
) {
    let rect = local.rect;
    let n = (rect.x1 - rect.x0 + 1) as usize * table.spp;
    pass.clear();
    pass.resize(local.covered.len(), true);
    sc.reserve(n);
    for py in rect.y0..=rect.y1 {
        let (ts, ls) = (table.start(rect.x0, py), local.start(rect.x0, py));
        let cols = table.cols(ts, n);
        let values = &mut sc.values[..n];
        for k in cons.iter().flat_map(|c| c.iter()) {
            k.eval_row(&cols, values);
            for (a, &g) in pass[ls..ls + n].iter_mut().zip(values.iter()) {
                // Culled when negative (a NaN value culls nothing, as in `admits`).
                let culled = g < 0.0;
                *a &= !culled;
            }
        }
    }
}

/// [`count_admitted`] for an answer whose constraints' verdicts per sample are `pass`
/// (of [`region_pass`]): the intervals side by side, and the verdicts looked up.
pub(super) fn count_passing(iv: ([f32; 2], [f32; 2], [f32; 2]), pass: &[bool], h: &Here, c: &mut Counts) {
    let ([u0, u1], [v0, v1], [t0, t1]) = iv;
    let (mut tested, mut hits) = (0u64, 0u64);
    for &(ts, ls, n) in h.rows {
        let t = &h.table.cols;
        let (us, vs, tv) = (&t[2][ts..ts + n], &t[3][ts..ts + n], &t[4][ts..ts + n]);
        let (cv, ps) = (&h.local.covered[ls..ls + n], &pass[ls..ls + n]);
        let (mut t_row, mut h_row) = (0u32, 0u32);
        for i in 0..n {
            let a =
                (u0 <= us[i]) & (us[i] <= u1) & (v0 <= vs[i]) & (vs[i] <= v1) & (t0 <= tv[i]) & (tv[i] <= t1) & ps[i];
            t_row += a as u32;
            h_row += (a & cv[i]) as u32;
        }
        tested += t_row as u64;
        hits += h_row as u64;
    }
    c.tested += tested;
    c.hits += hits;
    c.missed += h.cov - hits;
}

/// Rows of at most this many samples are evaluated whole: gathering a few samples of a
/// short row costs more than evaluating the constraints on all of it.
const WHOLE_ROW_BELOW: usize = 32;

/// Buffers of [`count_admitted`], reused from tile to tile.
#[derive(Default)]
pub(super) struct AdmitScratch {
    /// Per sample of a row: inside the intervals.
    mask: Vec<bool>,
    /// The row's samples inside the intervals, side by side (x, y, u, v, t), and
    /// their index in the row.
    inside: [Vec<f32>; 5],
    index: Vec<u32>,
    /// Per inside sample: no constraint culled it so far.
    alive: Vec<bool>,
    /// One constraint's values on the inside samples.
    values: Vec<f32>,
}

impl AdmitScratch {
    /// Room for a row of `n` samples in every buffer.
    fn reserve(&mut self, n: usize) {
        if self.mask.len() < n {
            self.mask.resize(n, false);
            self.index.resize(n, 0);
            for c in &mut self.inside {
                c.resize(n, 0.0);
            }
            self.alive.resize(n, false);
            self.values.resize(n, 0.0);
        }
    }
}

/// Count the samples of a tile that an answer admits: intervals `iv` (u, v, t) and the
/// per-sample constraints of every slice of `cons` (one answer's, or the parts' of a
/// conjunction). An answer with the whole (u, v, t) domain and no per-sample constraint
/// admits every sample ([`TileBounds::admits`] would say so sample by sample).
/// Otherwise, row by row, the samples inside the intervals are found side by side, and
/// each per-sample constraint is evaluated once on each of them
/// ([`SampleConstraint::eval_row`], the same values as `eval`): a sample passes when no
/// value is negative, as in `admits`.
///
/// [`TileBounds::admits`]: crate::bounds::TileBounds::admits
pub(super) fn count_admitted(
    sc: &mut AdmitScratch,
    iv: ([f32; 2], [f32; 2], [f32; 2]),
    cons: &[&[Box<dyn SampleConstraint>]],
    h: &Here,
    c: &mut Counts,
) {
    let (b_u, b_v, b_t) = iv;
    let (table, local, rows, n, cov) = (h.table, h.local, h.rows, h.n, h.cov);
    let no_constraints = cons.iter().all(|c| c.is_empty());
    let whole = b_u[0] <= -1.0 && b_u[1] >= 1.0 && b_v[0] <= -1.0 && b_v[1] >= 1.0 && b_t[0] <= 0.0 && b_t[1] >= 1.0;
    if whole && no_constraints {
        c.tested += n;
        c.hits += cov;
        return;
    }
    let (mut tested, mut hits) = (0u64, 0u64);
    let ([u0, u1], [v0, v1], [t0, t1]) = (b_u, b_v, b_t);
    for &(ts, ls, n) in rows {
        let (us, vs, tv) = (&table.cols[2][ts..ts + n], &table.cols[3][ts..ts + n], &table.cols[4][ts..ts + n]);
        let cv = &local.covered[ls..ls + n];
        if no_constraints {
            // The interval test of `TileBounds::admits`, side by side (vectorised).
            let (mut t_row, mut h_row) = (0u32, 0u32);
            for i in 0..n {
                let a = (u0 <= us[i]) & (us[i] <= u1) & (v0 <= vs[i]) & (vs[i] <= v1) & (t0 <= tv[i]) & (tv[i] <= t1);
                t_row += a as u32;
                h_row += (a & cv[i]) as u32;
            }
            tested += t_row as u64;
            hits += h_row as u64;
            continue;
        }
        // The intervals first (side by side), then the constraints: on the whole row's
        // columns when the row is short or at least half of its samples are inside (the
        // values of the others are not used), otherwise on the samples inside, gathered.
        sc.reserve(n);
        let mask = &mut sc.mask[..n];
        let mut m = 0usize;
        for i in 0..n {
            let a = (u0 <= us[i]) & (us[i] <= u1) & (v0 <= vs[i]) & (vs[i] <= v1) & (t0 <= tv[i]) & (tv[i] <= t1);
            mask[i] = a;
            m += a as usize;
        }
        if m == 0 {
            continue;
        }
        let whole_row = 2 * m >= n || n <= WHOLE_ROW_BELOW;
        if !whole_row {
            // The indices of the inside samples (written branch-free), then their columns.
            let index = &mut sc.index[..n];
            let mut k = 0usize;
            for (i, &a) in mask.iter().enumerate() {
                index[k] = i as u32;
                k += a as usize;
            }
            for (col, src) in sc.inside.iter_mut().zip(&table.cols) {
                let src = &src[ts..ts + n];
                for (d, &i) in col[..m].iter_mut().zip(&index[..m]) {
                    *d = src[i as usize];
                }
            }
        }
        let (cols, len) = if whole_row {
            (table.cols(ts, n), n)
        } else {
            let [x, y, u, v, t] = &sc.inside;
            (SampleCols::new(x, y, u, v, t, m), m)
        };
        let (alive, values) = (&mut sc.alive[..len], &mut sc.values[..len]);
        if whole_row {
            alive.copy_from_slice(mask);
        } else {
            alive.fill(true);
        }
        for k in cons.iter().flat_map(|c| c.iter()) {
            k.eval_row(&cols, values);
            for (a, &g) in alive.iter_mut().zip(values.iter()) {
                // Culled when negative (a NaN value culls nothing, as in `admits`).
                let culled = g < 0.0;
                *a &= !culled;
            }
        }
        let (mut t_row, mut h_row) = (0u32, 0u32);
        if whole_row {
            for (&a, &cv) in alive.iter().zip(cv) {
                t_row += a as u32;
                h_row += (a & cv) as u32;
            }
        } else {
            for (&a, &i) in alive.iter().zip(&sc.index[..m]) {
                t_row += a as u32;
                h_row += (a & cv[i as usize]) as u32;
            }
        }
        tested += t_row as u64;
        hits += h_row as u64;
    }
    c.tested += tested;
    c.hits += hits;
    c.missed += cov - hits;
}
