//! The per-sample time set `gdam2010-safe` computed before it was written over
//! `F32Arith` (f32 intervals as a type with early returns), verbatim but for the
//! constraint's glue: the reference `tests/encoded.rs` compares the method's per-sample
//! values with, sample for sample.

/// A closed f32 interval `[lo, hi]` that encloses one exact real: outward-rounded f32
/// arithmetic for `gdam2010-safe` (each rounded result stepped to the next f32 outward;
/// see the module doc). NaN ends make every sign test below false.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Iv {
    lo: f32,
    hi: f32,
}

impl Iv {
    const ZERO: Iv = Iv { lo: 0.0, hi: 0.0 };
    const NAN: Iv = Iv { lo: f32::NAN, hi: f32::NAN };
    /// The exact value lies within one f32 step of `r`, a result rounded to nearest.
    fn near(r: f32) -> Iv {
        Iv { lo: r.next_down(), hi: r.next_up() }
    }
    fn is_zero(self) -> bool {
        self.lo == 0.0 && self.hi == 0.0
    }
    fn add(self, o: Iv) -> Iv {
        if self.is_zero() {
            return o;
        }
        if o.is_zero() {
            return self;
        }
        Iv { lo: (self.lo + o.lo).next_down(), hi: (self.hi + o.hi).next_up() }
    }
    fn neg(self) -> Iv {
        Iv { lo: -self.hi, hi: -self.lo }
    }
    fn sub(self, o: Iv) -> Iv {
        self.add(o.neg())
    }
    fn mul(self, o: Iv) -> Iv {
        if self.is_zero() || o.is_zero() {
            return Iv::ZERO;
        }
        let p = [self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi];
        if p.iter().any(|v| v.is_nan()) {
            return Iv::NAN;
        }
        let lo = p.iter().fold(f32::INFINITY, |a, &b| a.min(b));
        let hi = p.iter().fold(f32::NEG_INFINITY, |a, &b| a.max(b));
        Iv { lo: lo.next_down(), hi: hi.next_up() }
    }
}

/// A point relative to the sample's pixel, `(x - X w, y - Y w)`, enclosed.
type Rel = [Iv; 2];

/// `p.x q.y - p.y q.x`, enclosed.
fn cross_iv(p: Rel, q: Rel) -> Iv {
    p[0].mul(q[1]).sub(p[1].mul(q[0]))
}

/// `p.x q.y - p.y q.x` in f32 (round to nearest: a guess for the cut points only).
fn cross2(p: [f32; 2], q: [f32; 2]) -> f32 {
    p[0] * q[1] - p[1] * q[0]
}

/// The pad of a culling test: this share of the square of the edge's size relative to
/// the pixel (module doc, "The pad").
const PAD_REL: f32 = 1.0 / 67_108_864.0; // 2^-26
/// ... plus this share of the square of the size of its terms in screen coordinates.
const PAD_ABS: f32 = 1.0 / 4_503_599_627_370_496.0; // 2^-52

/// Each edge's pad at pixel `(x, y)`, in f32: `PAD_REL (m_i + m_j)^2 +
/// PAD_ABS (n_i + n_j)^2 + 2^-126` with `m_i = |a_i.x| + |a_i.y| + |b_i.x - a_i.x| +
/// |b_i.y - a_i.y|` from the vertices relative to the pixel at both shutter ends (`a`
/// at t = 0, `b` at t = 1) and `n_i = |x_i| + |y_i|` at both ends `+ (|w_i| at both
/// ends) (|x| + |y|)`. A piece is culled for an edge only when its enclosures clear
/// the pad (module doc). NaN (from overflow) culls nothing.
fn edge_pads(q: &[[f32; 3]; 3], r: &[[f32; 3]; 3], x: f32, y: f32, a: [[f32; 2]; 3], b: [[f32; 2]; 3]) -> [f32; 3] {
    let m: [f32; 3] =
        std::array::from_fn(|i| a[i][0].abs() + a[i][1].abs() + (b[i][0] - a[i][0]).abs() + (b[i][1] - a[i][1]).abs());
    let xy = x.abs() + y.abs();
    let n: [f32; 3] = std::array::from_fn(|i| {
        q[i][0].abs() + q[i][1].abs() + r[i][0].abs() + r[i][1].abs() + (q[i][2].abs() + r[i][2].abs()) * xy
    });
    EDGES.map(|(i, j)| {
        let (s, u) = (m[i] + m[j], n[i] + n[j]);
        PAD_REL * s * s + PAD_ABS * u * u + f32::MIN_POSITIVE
    })
}

/// What the enclosures say about a closed piece `[l, h]` of the shutter.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Piece {
    /// Certified: no t in it is covered (some edge <= 0 and some edge >= 0 throughout).
    Culled,
    /// Certified: every t in it has all three edges of one strict sign.
    Covered,
    /// Neither.
    Open,
}

/// The time set of one pixel position (as the method's `Spans`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spans {
    pub n: usize,
    pub s: [[f32; 2]; 8],
}

impl Spans {
    pub fn as_slice(&self) -> &[[f32; 2]] {
        &self.s[..self.n]
    }
}

/// The old per-sample constraint: the vertices at both shutter ends.
pub struct SafeTimeSpans {
    q: [[f32; 3]; 3],
    r: [[f32; 3]; 3],
}

/// Edges as vertex pairs (k, (i, j)), as in the method's `TimeSpans`.
const EDGES: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
/// Pieces narrower than this are kept when open rather than split (t units).
const MIN_SPLIT: f32 = 1.0 / 4096.0;
/// Splits of open pieces per sample.
const SPLITS: usize = 12;

impl SafeTimeSpans {
    pub fn new(tri: &cullproof::Triangle) -> Self {
        let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
        SafeTimeSpans { q: tri.q.map(xyw), r: tri.r.map(xyw) }
    }

    /// A superset of the covered time set at pixel position (x, y), in f32: closed
    /// intervals whose complement in [0, 1] is certified uncovered.
    pub fn spans_at(&self, x: f32, y: f32) -> Spans {
        self.spans_with(x, y, true)
    }

    /// [`spans_at`](Self::spans_at), and without the pad (`padded` false) the time set
    /// of the code before the pad, which the tests compare with its old text.
    pub fn spans_with(&self, x: f32, y: f32, padded: bool) -> Spans {
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
        let pad = if padded { edge_pads(&self.q, &self.r, x, y, a, b) } else { [0.0; 3] };
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
        // The vertices and each edge's value at the end of a piece.
        let end = |t: f32| -> PieceEnd {
            let p = [at(0, t), at(1, t), at(2, t)];
            PieceEnd { t, p, e: EDGES.map(|(i, j)| cross_iv(p[i], p[j])), pad }
        };
        if self.fixed() {
            // No vertex moves: every vertex is `ai` at every t (`bi` is the same bits and
            // the motion is exactly 0), so there is one cut piece, [0, 1], whose two ends
            // are the same and whose middle coefficients are each edge's value doubled.
            // Culled, nothing is kept; covered, or open and split into pieces that are
            // all open, [0, 1] is kept.
            let e = end(0.0);
            if classify_fixed(&e) != Piece::Culled {
                out.n = 1;
                out.s[0] = [0.0, 1.0];
            }
            return out;
        }
        let mut buf = [0.0f32; MAX_CUTS];
        let n = self.cuts(a, b, pad, &mut buf);
        let cuts = &buf[..n];
        // Classify each piece between consecutive cuts (splitting open ones while the
        // budget lasts), left to right; keep all but the certified-uncovered pieces. The
        // next piece starts where the last one started (after a split) or ended: both
        // ends of the last piece are kept, so each end is evaluated once.
        let mut stack = [(0.0f32, 0.0f32); MAX_CUTS + SPLITS];
        let mut top = 0;
        for w in cuts.windows(2).rev() {
            stack[top] = (w[0], w[1]);
            top += 1;
        }
        let mut splits = SPLITS;
        let mut last: Option<(PieceEnd, PieceEnd)> = None;
        while top > 0 {
            top -= 1;
            let (l, h) = stack[top];
            let same = |e: &PieceEnd, t: f32| e.t.to_bits() == t.to_bits();
            let el = match &last {
                Some((p, _)) if same(p, l) => *p,
                Some((_, q)) if same(q, l) => *q,
                _ => end(l),
            };
            let eh = end(h);
            last = Some((el, eh));
            let kind = classify_piece(&el, &eh);
            if kind == Piece::Open && splits > 0 && h - l > MIN_SPLIT {
                let m = l + 0.5 * (h - l);
                if m > l && m < h {
                    splits -= 1;
                    stack[top] = (m, h);
                    stack[top + 1] = (l, m);
                    top += 2;
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

    /// The cut points, sorted, from 0 to 1, written to the front of `out` (their number
    /// returned): around each edge's roots and the vertex of its parabola, computed in
    /// f32 from the rounded relative vertices (`a` at t = 0, `b` at t = 1). They only
    /// decide where pieces end: any cut points give a superset.
    fn cuts(&self, a: [[f32; 2]; 3], b: [[f32; 2]; 3], pad: [f32; 3], out: &mut [f32; MAX_CUTS]) -> usize {
        out[0] = 0.0;
        out[1] = 1.0;
        let mut n = 2;
        let mut put = |c: f32| {
            // Only the cuts within [0, 1] are kept (NaN is not).
            if (0.0..=1.0).contains(&c) {
                out[n] = c;
                n += 1;
            }
        };
        let d: [[f32; 2]; 3] = std::array::from_fn(|i| [b[i][0] - a[i][0], b[i][1] - a[i][1]]);
        for (k, (i, j)) in EDGES.into_iter().enumerate() {
            let alpha = cross2(d[i], d[j]);
            let beta = cross2(a[i], d[j]) + cross2(d[i], a[j]);
            let gamma = cross2(a[i], a[j]);
            // Error scale of the edge's values: a few ulps of its terms.
            let mag = |p: [f32; 2], q: [f32; 2]| p[0].abs() + p[1].abs() + q[0].abs() + q[1].abs();
            // (and twice the pad: a piece is culled for the edge only beyond it)
            let err = 2f32.powi(-21) * mag(a[i], d[i]) * mag(a[j], d[j]) + f32::MIN_POSITIVE + 2.0 * pad[k];
            let mut roots = [0.0f32; 8];
            let mut nr = 0;
            roots_in_unit(alpha, beta, gamma, &mut roots, &mut nr);
            for &r in &roots[..nr] {
                let slope = (2.0 * alpha * r + beta).abs();
                let delta = (err / slope).min(0.5) + 2f32.powi(-21);
                for c in [r - delta, r - delta / 16.0, r + delta / 16.0, r + delta] {
                    put(c);
                }
            }
            if alpha != 0.0 {
                let tv = -beta / (2.0 * alpha);
                if tv > 0.0 && tv < 1.0 {
                    let delta = (err / alpha.abs()).sqrt().min(0.5) + 2f32.powi(-21);
                    for c in [tv - delta, tv - delta / 16.0, tv, tv + delta / 16.0, tv + delta] {
                        put(c);
                    }
                }
            }
        }
        // A stable sort, then the first of each run of equal values kept (as
        // `Vec::dedup`: -0 and 0 are equal, the first one stays).
        let cuts = &mut out[..n];
        cuts.sort_by(|p, q| p.partial_cmp(q).unwrap());
        let mut k = 1;
        for i in 1..n {
            if cuts[i] != cuts[k - 1] {
                cuts[k] = cuts[i];
                k += 1;
            }
        }
        k
    }
}

impl SafeTimeSpans {
    /// True when no vertex moves (each the same f32 bits at both shutter ends) and every
    /// input is finite.
    fn fixed(&self) -> bool {
        let bits = |p: &[f32; 3]| p.map(f32::to_bits);
        (0..3).all(|i| bits(&self.q[i]) == bits(&self.r[i]) && self.q[i].iter().all(|v| v.is_finite()))
    }
}

/// [`classify_piece`] for a piece whose two ends are both `e` (the same vertices): its
/// middle coefficient `P_i x P_j + P_i x P_j` is each edge's value added to itself.
fn classify_fixed(e: &PieceEnd) -> Piece {
    let (mut some_le, mut some_ge, mut all_gt, mut all_lt) = (false, false, true, true);
    for (v, pad) in e.e.into_iter().zip(e.pad) {
        let b = [v, v.add(v), v];
        some_le |= b.iter().all(|v| v.hi <= -pad);
        some_ge |= b.iter().all(|v| v.lo >= pad);
        all_gt &= b.iter().all(|v| v.lo > 0.0);
        all_lt &= b.iter().all(|v| v.hi < 0.0);
    }
    verdict(some_le, some_ge, all_gt, all_lt)
}

/// A piece's verdict from its edges' tests: culled when some edge is `<= 0` and some
/// edge `>= 0` throughout; covered when every edge is `> 0`, or every edge `< 0`,
/// throughout; open otherwise.
fn verdict(some_le: bool, some_ge: bool, all_gt: bool, all_lt: bool) -> Piece {
    if some_le && some_ge {
        Piece::Culled
    } else if all_gt || all_lt {
        Piece::Covered
    } else {
        Piece::Open
    }
}

/// At most this many cut points: 0, 1, and per edge 4 around each of 2 roots and 5
/// around its parabola's vertex.
const MAX_CUTS: usize = 2 + 3 * (2 * 4 + 5);

/// One end `t` of a piece of the shutter: the vertices relative to the pixel there
/// (enclosed) and each edge's value, `P_i(t) x P_j(t)`.
#[derive(Clone, Copy)]
struct PieceEnd {
    t: f32,
    p: [Rel; 3],
    e: [Iv; 3],
    /// Each edge's pad at the sample's pixel ([`edge_pads`]; the same at every t).
    pad: [f32; 3],
}

/// The piece between `l` and `h` (the values at its two ends): each edge is the cross
/// product of two vertices linear in t, so on the piece it is a quadratic with Bernstein
/// coefficients `P_i(l) x P_j(l)`, `(P_i(l) x P_j(h) + P_i(h) x P_j(l)) / 2`,
/// `P_i(h) x P_j(h)`, and its values lie between the least and the greatest of them.
///
/// The middle coefficient is computed only when it can matter: an edge whose end values
/// already have some `hi > 0` and some `lo < 0` (or a NaN) is `<= 0` throughout, `>= 0`
/// throughout, `> 0` and `< 0` by none of the four tests below, whatever the middle one
/// is. And once some edge is `<= 0` and some edge `>= 0`, the piece is culled whatever
/// the remaining edges are.
fn classify_piece(l: &PieceEnd, h: &PieceEnd) -> Piece {
    let (pl, ph) = (l.p, h.p);
    let (mut some_le, mut some_ge, mut all_gt, mut all_lt) = (false, false, true, true);
    for (k, (i, j)) in EDGES.into_iter().enumerate() {
        let ends = [l.e[k], h.e[k]];
        if !(ends.iter().all(|v| v.hi <= 0.0) || ends.iter().all(|v| v.lo >= 0.0)) {
            (all_gt, all_lt) = (false, false);
            continue;
        }
        let b = [l.e[k], cross_iv(pl[i], ph[j]).add(cross_iv(ph[i], pl[j])), h.e[k]];
        // (the middle one doubled: its sign, and half the pad, is what matters)
        let pad = l.pad[k];
        some_le |= b.iter().all(|v| v.hi <= -pad);
        some_ge |= b.iter().all(|v| v.lo >= pad);
        all_gt &= b.iter().all(|v| v.lo > 0.0);
        all_lt &= b.iter().all(|v| v.hi < 0.0);
        if some_le && some_ge {
            return Piece::Culled;
        }
    }
    verdict(some_le, some_ge, all_gt, all_lt)
}

/// Real roots of `a t^2 + b t + c` strictly inside (0, 1), appended to `out`.
fn roots_in_unit(a: f32, b: f32, c: f32, out: &mut [f32; 8], n: &mut usize) {
    let mut push = |r: f32| {
        if r > 0.0 && r < 1.0 {
            out[*n] = r;
            *n += 1;
        }
    };
    if a == 0.0 {
        if b != 0.0 {
            push(-c / b);
        }
        return;
    }
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc < 0.0 {
        return; // negative, or NaN from overflow
    }
    if disc == 0.0 {
        push(-b / (2.0 * a));
        return;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    push(q / a);
    if q != 0.0 {
        push(c / q);
    }
}
