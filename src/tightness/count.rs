//! Counting the samples of a tile that an answer admits (see the module documentation
//! of [`super`], "How it runs"): the intervals side by side, then each per-sample
//! constraint once per row ([`SampleConstraint::eval_row`]), or the verdicts of a
//! tile-independent answer's constraints looked up ([`region_pass`]).

use super::{Counts, Local, SampleTable};
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

/// Chunks of at most this many samples of a row are evaluated whole: gathering a few
/// samples of a short chunk costs more than evaluating the constraints on all of it.
const WHOLE_BELOW: usize = 32;

/// Samples are counted in chunks of a row of at most this many, one bit per sample.
const CHUNK: usize = 64;

/// Buffers of [`count_admitted`], reused from tile to tile.
#[derive(Default)]
pub(super) struct AdmitScratch {
    /// Per sample of a chunk (or of a row, for [`region_pass`]): a flag (inside the
    /// intervals, or culled by a constraint).
    mask: Vec<bool>,
    /// The chunk's samples inside the intervals, side by side (x, y, u, v, t).
    inside: [Vec<f32>; 5],
    /// One constraint's values.
    values: Vec<f32>,
}

impl AdmitScratch {
    /// Room for `n` samples in every buffer.
    fn reserve(&mut self, n: usize) {
        if self.mask.len() < n {
            self.mask.resize(n, false);
            for c in &mut self.inside {
                c.resize(n, 0.0);
            }
            self.values.resize(n, 0.0);
        }
    }
}

/// Up to 64 flags as bits (flag i is bit i): eight at a time, by one product that moves
/// each byte's 0 or 1 into its own bit of the top byte.
fn pack(flags: &[bool]) -> u64 {
    debug_assert!(flags.len() <= 64);
    let mut words = flags.chunks_exact(8);
    let mut bits = 0u64;
    for (w, ch) in (&mut words).enumerate() {
        let bytes: [bool; 8] = ch.try_into().expect("chunks of 8");
        let x = u64::from_le_bytes(bytes.map(|b| b as u8));
        bits |= (x.wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * w);
    }
    let rest = words.remainder();
    let base = flags.len() - rest.len();
    for (j, &f) in rest.iter().enumerate() {
        bits |= (f as u64) << (base + j);
    }
    bits
}

/// Count the samples of a tile that an answer admits: intervals `iv` (u, v, t) and the
/// per-sample constraints of every slice of `cons` (one answer's, or the parts' of a
/// conjunction). An answer with the whole (u, v, t) domain and no per-sample constraint
/// admits every sample ([`TileBounds::admits`] would say so sample by sample).
/// Otherwise, in chunks of at most 64 samples of a row, the samples inside the intervals
/// are found side by side (one bit each), and each per-sample constraint is evaluated
/// once on them ([`SampleConstraint::eval_row`], the same values as `eval`) until none
/// is left: a sample passes when no value is negative, as in `admits`.
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
    sc.reserve(CHUNK);
    let cons = || cons.iter().flat_map(|c| c.iter());
    for &(ts, ls, n) in rows {
        for c0 in (0..n).step_by(CHUNK) {
            let (s, k) = (ts + c0, (n - c0).min(CHUNK));
            let (us, vs, tv) = (&table.cols[2][s..s + k], &table.cols[3][s..s + k], &table.cols[4][s..s + k]);
            // The interval test of `TileBounds::admits`, side by side, as bits.
            let mask = &mut sc.mask[..k];
            for i in 0..k {
                mask[i] = (u0 <= us[i]) & (us[i] <= u1) & (v0 <= vs[i]) & (vs[i] <= v1) & (t0 <= tv[i]) & (tv[i] <= t1);
            }
            let inside = pack(mask);
            if inside == 0 {
                continue;
            }
            let covered = pack(&local.covered[ls + c0..ls + c0 + k]);
            // Then the constraints (a sample is culled by a negative value; a NaN value
            // culls nothing, as in `admits`), until none is left: on the whole chunk when
            // it is short or at least half of it is inside (the values of the others are
            // not used), otherwise on the samples inside, gathered.
            let m = inside.count_ones() as usize;
            let alive = if no_constraints {
                inside
            } else if 2 * m >= k || k <= WHOLE_BELOW {
                let cols = table.cols(s, k);
                let mut alive = inside;
                for con in cons() {
                    con.eval_row(&cols, &mut sc.values[..k]);
                    for (f, &g) in sc.mask[..k].iter_mut().zip(&sc.values[..k]) {
                        *f = g < 0.0;
                    }
                    alive &= !pack(&sc.mask[..k]);
                    if alive == 0 {
                        break;
                    }
                }
                alive
            } else {
                // The positions of the inside samples in the chunk, then their columns.
                let mut at = [0u8; CHUNK];
                let mut bits = inside;
                for a in at[..m].iter_mut() {
                    *a = bits.trailing_zeros() as u8;
                    bits &= bits - 1;
                }
                for (col, src) in sc.inside.iter_mut().zip(&table.cols) {
                    let src = &src[s..s + k];
                    for (d, &i) in col[..m].iter_mut().zip(&at[..m]) {
                        *d = src[i as usize];
                    }
                }
                let [x, y, u, v, t] = &sc.inside;
                let cols = SampleCols::new(x, y, u, v, t, m);
                // Bit j: gathered sample j (at `at[j]` in the chunk) is still alive.
                let mut alive_g = u64::MAX >> (CHUNK - m);
                for con in cons() {
                    con.eval_row(&cols, &mut sc.values[..m]);
                    for (f, &g) in sc.mask[..m].iter_mut().zip(&sc.values[..m]) {
                        *f = g < 0.0;
                    }
                    alive_g &= !pack(&sc.mask[..m]);
                    if alive_g == 0 {
                        break;
                    }
                }
                let mut alive = 0u64;
                while alive_g != 0 {
                    alive |= 1 << at[alive_g.trailing_zeros() as usize];
                    alive_g &= alive_g - 1;
                }
                alive
            };
            tested += alive.count_ones() as u64;
            hits += (alive & covered).count_ones() as u64;
        }
    }
    c.tested += tested;
    c.hits += hits;
    c.missed += cov - hits;
}
