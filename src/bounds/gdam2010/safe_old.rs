//! `gdam2010-safe`'s time set at a pixel position as it was before the current code
//! dropped its heap buffers and shared the values at each piece's ends, kept verbatim:
//! the reference the current [`SafeTimeSpans::spans_at`] is compared with, bit for bit
//! (`safe_spans_are_their_old_code_bit_for_bit` in the parent's tests).

use super::*;

impl SafeTimeSpans {
    /// A superset of the covered time set at pixel position (x, y), in f32: closed
    /// intervals whose complement in [0, 1] is certified uncovered.
    pub(super) fn spans_at_old(&self, x: f32, y: f32) -> Spans {
        let mut out = Spans { n: 0, s: [[0.0; 2]; 8] };
        if !(x.is_finite() && y.is_finite()) {
            out.n = 1;
            out.s[0] = [0.0, 1.0];
            return out;
        }
        // The vertices relative to the pixel at both shutter ends: one fused
        // multiply-add (one rounding) per coordinate, then one step outward.
        let rel = |p: [f32; 3]| [(-x).mul_add(p[2], p[0]), (-y).mul_add(p[2], p[1])];
        let (a, b) = (self.q.map(rel), self.r.map(rel));
        let ai = a.map(|p| p.map(Iv::near));
        let bi = b.map(|p| p.map(Iv::near));
        // The motion of each, exactly 0 for a vertex that does not move.
        let di: [Rel; 3] = std::array::from_fn(|i| {
            if self.q[i] == self.r[i] {
                [Iv::ZERO; 2]
            } else {
                [bi[i][0].sub(ai[i][0]), bi[i][1].sub(ai[i][1])]
            }
        });
        // Enclosure of vertex i at time t (an f32 in [0, 1]).
        let at = |i: usize, t: f32| -> Rel {
            if t == 0.0 {
                ai[i]
            } else if t == 1.0 {
                bi[i]
            } else {
                let tt = Iv { lo: t, hi: t };
                [ai[i][0].add(tt.mul(di[i][0])), ai[i][1].add(tt.mul(di[i][1]))]
            }
        };
        let cuts = self.cuts_old(a, b);
        // Classify each piece between consecutive cuts (splitting open ones while the
        // budget lasts), left to right; keep all but the certified-uncovered pieces.
        let mut stack: Vec<(f32, f32)> = cuts.windows(2).rev().map(|w| (w[0], w[1])).collect();
        let mut splits = SPLITS;
        while let Some((l, h)) = stack.pop() {
            let (pl, ph) = ([at(0, l), at(1, l), at(2, l)], [at(0, h), at(1, h), at(2, h)]);
            let kind = classify_piece_old(pl, ph);
            if kind == Piece::Open && splits > 0 && h - l > MIN_SPLIT {
                let m = l + 0.5 * (h - l);
                if m > l && m < h {
                    splits -= 1;
                    stack.push((m, h));
                    stack.push((l, m));
                    continue;
                }
            }
            if kind == Piece::Culled {
                continue;
            }
            if out.n > 0 && out.s[out.n - 1][1] >= l {
                out.s[out.n - 1][1] = h;
            } else if out.n == out.s.len() {
                out.s[out.n - 1][1] = h; // full: keep the gap too (conservative)
            } else {
                out.s[out.n] = [l, h];
                out.n += 1;
            }
        }
        out
    }

    /// The cut points, sorted, from 0 to 1: around each edge's roots and the vertex of
    /// its parabola, computed in f32 from the rounded relative vertices (`a` at t = 0,
    /// `b` at t = 1). They only decide where pieces end: any cut points give a superset.
    fn cuts_old(&self, a: [[f32; 2]; 3], b: [[f32; 2]; 3]) -> Vec<f32> {
        let mut cuts = vec![0.0f32, 1.0];
        let d: [[f32; 2]; 3] = std::array::from_fn(|i| [b[i][0] - a[i][0], b[i][1] - a[i][1]]);
        for (i, j) in EDGES {
            let alpha = cross2(d[i], d[j]);
            let beta = cross2(a[i], d[j]) + cross2(d[i], a[j]);
            let gamma = cross2(a[i], a[j]);
            // Error scale of the edge's values: a few ulps of its terms.
            let mag = |p: [f32; 2], q: [f32; 2]| p[0].abs() + p[1].abs() + q[0].abs() + q[1].abs();
            let err = 2f32.powi(-21) * mag(a[i], d[i]) * mag(a[j], d[j]) + f32::MIN_POSITIVE;
            let mut roots = [0.0f32; 8];
            let mut n = 0;
            roots_in_unit(alpha, beta, gamma, &mut roots, &mut n);
            for &r in &roots[..n] {
                let slope = (2.0 * alpha * r + beta).abs();
                let delta = (err / slope).min(0.5) + 2f32.powi(-21);
                cuts.extend([r - delta, r - delta / 16.0, r + delta / 16.0, r + delta]);
            }
            if alpha != 0.0 {
                let tv = -beta / (2.0 * alpha);
                if tv > 0.0 && tv < 1.0 {
                    let delta = (err / alpha.abs()).sqrt().min(0.5) + 2f32.powi(-21);
                    cuts.extend([tv - delta, tv - delta / 16.0, tv, tv + delta / 16.0, tv + delta]);
                }
            }
        }
        cuts.retain(|c| (0.0..=1.0).contains(c));
        cuts.sort_by(|p, q| p.partial_cmp(q).unwrap());
        cuts.dedup();
        cuts
    }
}

/// The piece between `pl` (the vertices at its start) and `ph` (at its end): each edge
/// is the cross product of two vertices linear in t, so on the piece it is a quadratic
/// with Bernstein coefficients `P_i(l) x P_j(l)`, `(P_i(l) x P_j(h) + P_i(h) x P_j(l)) / 2`,
/// `P_i(h) x P_j(h)`, and its values lie between the least and the greatest of them.
fn classify_piece_old(pl: [Rel; 3], ph: [Rel; 3]) -> Piece {
    let (mut some_le, mut some_ge, mut all_gt, mut all_lt) = (false, false, true, true);
    for (i, j) in EDGES {
        let b = [cross_iv(pl[i], pl[j]), cross_iv(pl[i], ph[j]).add(cross_iv(ph[i], pl[j])), cross_iv(ph[i], ph[j])];
        // (the middle one doubled: only its sign matters)
        some_le |= b.iter().all(|v| v.hi <= 0.0);
        some_ge |= b.iter().all(|v| v.lo >= 0.0);
        all_gt &= b.iter().all(|v| v.lo > 0.0);
        all_lt &= b.iter().all(|v| v.hi < 0.0);
    }
    if some_le && some_ge {
        Piece::Culled
    } else if all_gt || all_lt {
        Piece::Covered
    } else {
        Piece::Open
    }
}
