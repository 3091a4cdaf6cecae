//! The code `wu2013-safe` had before it was written over `F32Arith` (f32 intervals as a
//! type with early returns), verbatim but for its method glue, the grid path and the
//! constraint's type: the reference `tests/encoded.rs` compares it with, answer for
//! answer.

use cullproof::bounds::{SampleBox, SampleConstraint, TileBounds, TileResult};
use cullproof::{Interval, Sample, Tile, Triangle};

const LINE_LIMIT: f32 = 1.2676506e30; // 2^100

/// The four line endpoints of stage 2 on one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lines {
    ul: f32,
    ur: f32,
    ll: f32,
    lr: f32,
}

/// Printed as the method's own `Lens`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Lens {
    U,
    V,
}

/// The line as a constraint, printed as the method's `TimeLine`; only its Debug form is
/// compared.
#[derive(Clone, Copy, Debug)]
struct TimeLine {
    #[allow(dead_code)]
    lens: Lens,
    #[allow(dead_code)]
    upper: bool,
    a: f32,
    b: f32,
}

impl SampleConstraint for TimeLine {
    fn name(&self) -> String {
        String::new()
    }
    fn eval(&self, _: &Sample) -> f32 {
        f32::NAN
    }
    fn eval_box(&self, _: &SampleBox) -> Interval {
        Interval::new(f64::NEG_INFINITY, f64::INFINITY)
    }
}

/// An f32 interval enclosing an exact real value: every operation rounds to nearest and
/// then steps each end one f32 value outward (`next_down` / `next_up`), which encloses
/// the exact result of the operation on any reals in the operands (module doc). A
/// non-finite end (NaN, an overflow) makes the interval [`BAD`], whose tests are all
/// false, so that nothing is bounded from it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Iv {
    lo: f32,
    hi: f32,
}

/// The "no information" interval: NaN ends (every comparison with it is false).
const BAD: Iv = Iv { lo: f32::NAN, hi: f32::NAN };

impl Iv {
    /// An exact f32 input.
    fn pt(x: f32) -> Iv {
        if x.is_finite() {
            Iv { lo: x, hi: x }
        } else {
            BAD
        }
    }
    /// `[lo, hi]` are round-to-nearest values of the exact ends: one step outward.
    fn out(lo: f32, hi: f32) -> Iv {
        if lo.is_finite() && hi.is_finite() {
            Iv { lo: lo.next_down(), hi: hi.next_up() }
        } else {
            BAD
        }
    }
    fn ok(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
    /// Strictly positive / strictly negative (false for [`BAD`]).
    fn pos(self) -> bool {
        self.lo > 0.0
    }
    fn neg(self) -> bool {
        self.hi < 0.0
    }
    fn add(self, o: Iv) -> Iv {
        Iv::out(self.lo + o.lo, self.hi + o.hi)
    }
    fn sub(self, o: Iv) -> Iv {
        Iv::out(self.lo - o.hi, self.hi - o.lo)
    }
    /// The hull of the four end products (quotients), or [`BAD`] if one is not finite.
    fn hull4(p: [f32; 4]) -> Iv {
        if !p.iter().all(|x| x.is_finite()) {
            return BAD;
        }
        Iv::out(p[0].min(p[1]).min(p[2].min(p[3])), p[0].max(p[1]).max(p[2].max(p[3])))
    }
    fn mul(self, o: Iv) -> Iv {
        Iv::hull4([self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi])
    }
    /// `Iv::pt(a).mul(Iv::pt(b))`, the four equal products taken once: the product
    /// stepped outward, [`BAD`] unless it is finite (then so are `a` and `b`).
    fn pt_mul(a: f32, b: f32) -> Iv {
        let p = a * b;
        Iv::out(p, p)
    }
    /// `Iv::pt(a).mul(self)`, the two distinct products taken once: their hull stepped
    /// outward, [`BAD`] unless both are finite (a non-finite `a`, or `self` [`BAD`],
    /// gives a non-finite product). The order of two products equal in value but of
    /// opposite zero signs does not matter: both ends are stepped off zero.
    fn pt_scale(self, a: f32) -> Iv {
        let (p, q) = (a * self.lo, a * self.hi);
        if !(p.is_finite() && q.is_finite()) {
            return BAD;
        }
        Iv::out(p.min(q), p.max(q))
    }
    /// [`BAD`] unless the divisor has one strict sign.
    fn div(self, o: Iv) -> Iv {
        if !(o.pos() || o.neg()) {
            return BAD;
        }
        Iv::hull4([self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi])
    }
}

/// One vertex on one axis for `wu2013-safe`: position and w exact (f32 inputs), the CoC
/// (c, or k c on the y axis) as an enclosure.
#[derive(Clone, Copy, Debug)]
struct SafeVertex {
    p0: f32,
    w0: f32,
    c0: Iv,
    p1: f32,
    w1: f32,
    c1: Iv,
    /// The enclosures of `p0 - p1`, `w0 - w1` and `c0 - c1` (they do not depend on the
    /// tile: computed once, at setup).
    dp: Iv,
    dw: Iv,
    dc: Iv,
}

impl SafeVertex {
    fn new(p0: f32, w0: f32, c0: Iv, p1: f32, w1: f32, c1: Iv) -> Self {
        let dp = Iv::pt(p0).sub(Iv::pt(p1));
        let dw = Iv::pt(w0).sub(Iv::pt(w1));
        SafeVertex { p0, w0, c0, p1, w1, c1, dp, dw, dc: c0.sub(c1) }
    }
    /// The parts of `N` and `D` at column `X = s` that do not depend on `l`:
    /// `p0 - X w0` and `(p0 - p1) - X (w0 - w1)` (shared by the lens values of a column).
    fn at_column(&self, s: f32) -> (Iv, Iv) {
        (Iv::pt(self.p0).sub(Iv::pt_mul(s, self.w0)), self.dp.sub(self.dw.pt_scale(s)))
    }
    /// `N(X, l) = p0 - X w0 + l c0 = delta(t = 0)` and
    /// `D(X, l) = (p0 - p1) - X (w0 - w1) + l (c0 - c1) = delta(0) - delta(1)`, from the
    /// column's parts ([`at_column`](Self::at_column)).
    fn nd_from(&self, (ns, ds): (Iv, Iv), l: f32) -> (Iv, Iv) {
        (ns.add(self.c0.pt_scale(l)), ds.add(self.dc.pt_scale(l)))
    }
}

/// One crossing, for [`sign_hull`]: `delta_k` is affine in the variable z (u, or t),
/// increasing (`inc`) or decreasing, and vanishes at some `z_k` in `[m, hi]` for every
/// (column, other coordinate) of the tile.
type Crossing = (bool, f32, f32);

/// The hull, within `dom`, of the set of z at which not all `delta_k` have one strict
/// sign (the necessary condition for coverage, module doc): `None` if that set misses
/// `dom`. With I the increasing and J the decreasing deltas, some `delta_k <= 0` only for
/// z in `(-inf, max_I hi] u [min_J m, inf)` and some `delta_k >= 0` only for
/// z in `[min_I m, inf) u (-inf, max_J hi]`; the intersection is the union of the four
/// intervals below (exact comparisons, no rounding).
fn sign_hull(items: &[Crossing], dom: [f32; 2]) -> Option<[f32; 2]> {
    hull_within(&sign_parts(items), dom)
}

/// The four intervals of [`sign_hull`] before they meet the domain (they depend on the
/// crossings only: a grid computes them once per column or row).
fn sign_parts(items: &[Crossing]) -> [[f32; 2]; 4] {
    let inf = f32::INFINITY;
    let (mut mi, mut hi_i, mut mj, mut hi_j) = (inf, -inf, inf, -inf);
    for &(inc, m, h) in items {
        if inc {
            mi = mi.min(m);
            hi_i = hi_i.max(h);
        } else {
            mj = mj.min(m);
            hi_j = hi_j.max(h);
        }
    }
    [[mi, hi_i], [-inf, hi_i.min(hi_j)], [mj.max(mi), inf], [mj, hi_j]]
}

/// The hull of the parts of [`sign_parts`] within `dom`, or `None` if none meets it.
fn hull_within(parts: &[[f32; 2]; 4], dom: [f32; 2]) -> Option<[f32; 2]> {
    let mut out: Option<[f32; 2]> = None;
    for &[a, b] in parts {
        let (a, b) = (a.max(dom[0]), b.min(dom[1]));
        if a <= b {
            out = Some(out.map_or([a, b], |o| [o[0].min(a), o[1].max(b)]));
        }
    }
    out
}

/// One axis (x with u, or y with v) for `wu2013-safe`.
#[derive(Clone, Copy, Debug)]
struct SafeAxis {
    v: [SafeVertex; 3],
}

/// Per vertex, [`SafeVertex::at_column`] at the tile's two columns (shared by stage 2's
/// tile interval and its lines).
type Columns = [[(Iv, Iv); 2]; 3];

impl SafeAxis {
    /// The vertices' column parts at columns `s0`, `s1`.
    fn columns(&self, s0: f32, s1: f32) -> Columns {
        self.v.map(|a| [a.at_column(s0), a.at_column(s1)])
    }
    /// Stage 1, corrected: per vertex the enclosure of its lens crossings
    /// `u_k(X, t) = (X w_k(t) - p_k(t)) / c_k(t)` over the tile's columns and the shutter
    /// (the 4 corners X in {s0, s1}, t in {0, 1}), with the direction of `delta_k` in u
    /// (the sign of `c_k`). None (no lens bound) when a CoC is not of one strict sign
    /// over the shutter, or a value is not finite.
    fn lens_crossings(&self, s0: f32, s1: f32) -> Option<[Crossing; 3]> {
        let inc = self.lens_directions()?;
        let at = [s0, s1].map(|s| self.lens_at(s));
        Self::lens_crossings_from(inc, [&at[0], &at[1]])
    }

    /// Per vertex, the direction of `delta_k` in the lens coordinate (true: increasing,
    /// `c_k > 0`), or None when some CoC is not of one strict sign over the shutter
    /// (stage 1 then gives no lens bound on this axis, for every tile).
    fn lens_directions(&self) -> Option<[bool; 3]> {
        let mut out = [false; 3];
        for (a, o) in self.v.iter().zip(out.iter_mut()) {
            *o = if a.c0.pos() && a.c1.pos() {
                true
            } else if a.c0.neg() && a.c1.neg() {
                false
            } else {
                return None;
            };
        }
        Some(out)
    }

    /// Per vertex, the enclosures of its lens crossing `u_k(X, t)` at column `X = s`,
    /// at t = 0 and t = 1 (they read one column boundary only).
    fn lens_at(&self, s: f32) -> [[Iv; 2]; 3] {
        self.v.map(|a| [(a.p0, a.w0, a.c0), (a.p1, a.w1, a.c1)].map(|(p, w, c)| Iv::pt_mul(s, w).sub(Iv::pt(p)).div(c)))
    }

    /// [`lens_crossings`](Self::lens_crossings) from the directions and the values at
    /// the two boundaries `at` (left, right): per vertex the extremes over the shutter
    /// ends and the two columns, None if a value is not finite.
    fn lens_crossings_from(inc: [bool; 3], at: [&[[Iv; 2]; 3]; 2]) -> Option<[Crossing; 3]> {
        let mut out = [(false, 0.0, 0.0); 3];
        for (k, o) in out.iter_mut().enumerate() {
            let (mut m, mut h) = (f32::INFINITY, f32::NEG_INFINITY);
            for end in 0..2 {
                for side in at {
                    let l = side[k][end];
                    if !l.ok() {
                        return None;
                    }
                    m = m.min(l.lo);
                    h = h.max(l.hi);
                }
            }
            *o = (inc[k], m, h);
        }
        Some(out)
    }

    /// Stage 2, corrected (tile level): per vertex the enclosure of its crossing time
    /// `t_k = N / D` over the rectangle of columns [s0, s1] (`cols`) and lens `l` (a linear
    /// fraction of (X, l) jointly: its extremes are at the 4 corners when D keeps one
    /// strict sign there), with the direction of `delta_k(t) = N - t D` in t (increasing
    /// iff D < 0). Vertices may cross in opposite directions. None (no time bound from
    /// this axis) when some D is not of one strict sign on the rectangle.
    fn time_crossings(&self, cols: &Columns, l: [f32; 2]) -> Option<[Crossing; 3]> {
        let mut out = [(false, 0.0, 0.0); 3];
        for ((a, o), ac) in self.v.iter().zip(out.iter_mut()).zip(cols) {
            let (mut pos, mut neg) = (false, false);
            let (mut m, mut h) = (f32::INFINITY, f32::NEG_INFINITY);
            for &col in ac {
                for lv in l {
                    let (n, d) = a.nd_from(col, lv);
                    pos |= d.pos();
                    neg |= d.neg();
                    let t = n.div(d);
                    if !t.ok() {
                        return None;
                    }
                    m = m.min(t.lo);
                    h = h.max(t.hi);
                }
            }
            if pos == neg {
                return None;
            }
            *o = (neg, m, h);
        }
        Some(out)
    }

    /// Stage 2 as published (the green / red lines), enclosed: only when all three D
    /// share one strict sign on columns [s0, s1] (`cols`) x lens [-1, 1] (the guarded condition).
    /// Upper endpoints are upper ends of the enclosures, lower endpoints lower ends.
    fn lines(&self, cols: &Columns) -> Option<Lines> {
        let mut ends = [[None; 2]; 3];
        for ((a, ac), e) in self.v.iter().zip(cols).zip(ends.iter_mut()) {
            *e = ac.map(|col| a.line_ends(col));
        }
        Self::lines_from(&ends)
    }

    /// [`lines`](Self::lines) from each vertex's [`SafeVertex::line_ends`] at the two
    /// columns (`ends[vertex][side]`): None unless every one is there and all share
    /// one sign of D; the upper endpoints are their maxima, the lower ones their minima.
    fn lines_from(ends: &[[Option<LineEnds>; 2]; 3]) -> Option<Lines> {
        let mut out = Lines { ul: f32::NEG_INFINITY, ur: f32::NEG_INFINITY, ll: f32::INFINITY, lr: f32::INFINITY };
        let (mut pos, mut neg) = (false, false);
        for ve in ends {
            for e in ve {
                let (d_pos, [ul, ur, ll, lr]) = (*e)?;
                pos |= d_pos;
                neg |= !d_pos;
                if pos && neg {
                    return None;
                }
                out.ul = out.ul.max(ul);
                out.ur = out.ur.max(ur);
                out.ll = out.ll.min(ll);
                out.lr = out.lr.min(lr);
            }
        }
        Some(out)
    }
}

/// One vertex's part of the published lines at one column ([`SafeVertex::line_ends`]):
/// the sign of D there (true: D > 0) and the upper ends at l = -1, +1, then the lower
/// ends at l = -1, +1.
type LineEnds = (bool, [f32; 4]);

impl SafeVertex {
    /// The vertex's chord and tangent enclosures at column `col` (its
    /// [`at_column`](Self::at_column) parts) and l = -1, +1: the upper ends' maxima and
    /// the lower ends' minima, with the sign of D. None when D is not of one strict sign
    /// at l = -1 and +1, or a value is not finite. It reads one column boundary only.
    fn line_ends(&self, col: (Iv, Iv)) -> Option<LineEnds> {
        let (n0, d0) = self.nd_from(col, 0.0);
        let (nm, dm) = self.nd_from(col, -1.0);
        let (np, dp) = self.nd_from(col, 1.0);
        let d_pos = dm.pos() && dp.pos();
        if !(d_pos || (dm.neg() && dp.neg())) {
            return None;
        }
        let (n1, d1) = (self.c0, self.dc);
        let tm = nm.div(dm);
        let tp = np.div(dp);
        let tz = n0.div(d0);
        let slope = n1.sub(tz.mul(d1)).div(d0);
        let (gm, gp) = (tz.sub(slope), tz.add(slope));
        if !(tm.ok() && tp.ok() && gm.ok() && gp.ok()) {
            return None;
        }
        Some((d_pos, [tm.hi.max(gm.hi), tp.hi.max(gp.hi), tm.lo.min(gm.lo), tp.lo.min(gp.lo)]))
    }
}

/// `wu2013-safe`'s line pad, 2^-21 = 8u (proof: `src/bounds/proofs/wu2013_safe.g`).
const PAD: f32 = 1.0 / (1u32 << 21) as f32;
/// `wu2013-safe`'s line pad floor, 2^-100.
const FLOOR: f32 = 1.0 / (1u128 << 100) as f32;

/// A padded f32 line `t = a l + b'` through (or beyond) `(-1, e_left)`, `(1, e_right)`:
/// above both for an upper line, below both for a lower one, with `b'` moved outward by
/// the f32 error of [`TimeLine::eval`] (module doc). None beyond `LINE_LIMIT`.
fn safe_line(lens: Lens, upper: bool, e_left: f32, e_right: f32) -> Option<TimeLine> {
    if !(e_left.abs() <= LINE_LIMIT && e_right.abs() <= LINE_LIMIT) {
        return None;
    }
    // Any slope will do: the intercept is chosen to dominate both endpoints.
    let a = 0.5 * e_right - 0.5 * e_left;
    let b = if upper {
        (e_left + a).next_up().max((e_right - a).next_up())
    } else {
        (e_left + a).next_down().min((e_right - a).next_down())
    };
    let pad = (a.abs() + a.abs() + b.abs() + FLOOR) * PAD;
    let b = if upper { (b + pad).next_up() } else { (b - pad).next_down() };
    (a.is_finite() && b.is_finite()).then_some(TimeLine { lens, upper, a, b })
}

/// The safe lines' time range over lens range `l` and the constraints worth keeping
/// (the same choice as [`apply_lines`]).
fn apply_safe_lines(ln: Lines, lens: Lens, l: [f32; 2], t: &mut [f32; 2], cons: &mut Vec<Box<dyn SampleConstraint>>) {
    let cut = safe_line_cut(ln, lens, l);
    cut.bound(t);
    cut.push(cons);
}

/// What one axis's safe lines do to a tile over lens range `l` ([`apply_safe_lines`]):
/// the bound each puts on t and the constraint it keeps. It reads the axis only (the
/// lines, and the lens range of stage 1): a grid computes it once per column or row.
#[derive(Clone, Copy, Debug, Default)]
struct LineCut {
    /// The upper line's maximum over `l` (t is at most that), and its constraint.
    below: Option<f32>,
    upper: Option<TimeLine>,
    /// The lower line's minimum over `l` (t is at least that), and its constraint.
    above: Option<f32>,
    lower: Option<TimeLine>,
}

fn safe_line_cut(ln: Lines, lens: Lens, l: [f32; 2]) -> LineCut {
    let at = |c: &TimeLine, x: f32| Iv::pt_mul(c.a, x).add(Iv::pt(c.b));
    let mut cut = LineCut::default();
    if let Some(c) = safe_line(lens, true, ln.ul, ln.ur) {
        let (e0, e1) = (at(&c, l[0]), at(&c, l[1]));
        if e0.ok() && e1.ok() {
            cut.below = Some(e0.hi.max(e1.hi));
            if c.a != 0.0 && e0.lo.min(e1.lo) < 1.0 {
                cut.upper = Some(c);
            }
        }
    }
    if let Some(c) = safe_line(lens, false, ln.ll, ln.lr) {
        let (e0, e1) = (at(&c, l[0]), at(&c, l[1]));
        if e0.ok() && e1.ok() {
            cut.above = Some(e0.lo.min(e1.lo));
            if c.a != 0.0 && e0.hi.max(e1.hi) > 0.0 {
                cut.lower = Some(c);
            }
        }
    }
    cut
}

impl LineCut {
    /// Narrow the time range `t` by the lines.
    fn bound(&self, t: &mut [f32; 2]) {
        if let Some(h) = self.below {
            t[1] = t[1].min(h);
        }
        if let Some(l) = self.above {
            t[0] = t[0].max(l);
        }
    }
    /// Append the kept constraints (upper line first).
    fn push(&self, cons: &mut Vec<Box<dyn SampleConstraint>>) {
        for c in [self.upper, self.lower].into_iter().flatten() {
            cons.push(Box::new(c));
        }
    }
}

fn safe_axis(tri: &Triangle, j: usize, scale: f32) -> SafeAxis {
    let k = Iv::pt(scale);
    SafeAxis {
        v: std::array::from_fn(|i| {
            let (q, r) = (tri.q[i], tri.r[i]);
            let (c0, c1) = (k.mul(Iv::pt(tri.c0[i])), k.mul(Iv::pt(tri.c1[i])));
            SafeVertex::new(q[j], q[3], c0, r[j], r[3], c1)
        }),
    }
}

/// The old tile answer.
pub fn answer(tri: &Triangle, tile: &Tile) -> TileResult {
    let x = safe_axis(tri, 0, 1.0);
    let y = safe_axis(tri, 1, tri.k);
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite())
            && tri.k.is_finite();
    let mut b = TileBounds::full();
    if !finite {
        return TileResult::Bounds(b);
    }
    // Stage 1, sign-aware.
    for (axis, s0, s1, out) in [(&x, tile.x0, tile.x1, &mut b.u), (&y, tile.y0, tile.y1, &mut b.v)] {
        if let Some(cr) = axis.lens_crossings(s0, s1) {
            match sign_hull(&cr, [-1.0, 1.0]) {
                None => return TileResult::Empty,
                Some(r) => *out = r,
            }
        }
    }
    let mut t = [0.0f32, 1.0];
    let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
    for (axis, s0, s1, lens, l) in [(&x, tile.x0, tile.x1, Lens::U, b.u), (&y, tile.y0, tile.y1, Lens::V, b.v)] {
        let cols = axis.columns(s0, s1);
        if let Some(cr) = axis.time_crossings(&cols, l) {
            match sign_hull(&cr, t) {
                None => return TileResult::Empty,
                Some(r) => t = r,
            }
        }
        if let Some(ln) = axis.lines(&cols) {
            apply_safe_lines(ln, lens, l, &mut t, &mut cons);
        }
    }
    if t[0].is_nan() || t[1].is_nan() || t[0] > t[1] {
        return TileResult::Empty;
    }
    b.t = t;
    b.constraints = cons;
    TileResult::Bounds(b)
}
