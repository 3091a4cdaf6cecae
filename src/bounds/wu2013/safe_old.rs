//! `wu2013-safe`'s tile path as it was before its interval arithmetic took the shortcuts
//! of the current file (per-vertex constants at setup, products with a point operand),
//! kept verbatim: the reference the current code is compared with, bit for bit
//! (`safe_is_its_old_code_bit_for_bit` in the parent's tests).
#![allow(dead_code)]

use super::*;

// ---------------------------------------------------------------------------------------
// wu2013-safe (module doc, "`wu2013-safe`"): the same two stages in f32 interval
// arithmetic, with the sign-aware hull for mixed crossing directions.
// ---------------------------------------------------------------------------------------

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
}

impl SafeVertex {
    /// `N(X, l) = p0 - X w0 + l c0 = delta(t = 0)` and
    /// `D(X, l) = (p0 - p1) - X (w0 - w1) + l (c0 - c1) = delta(0) - delta(1)`.
    fn nd(&self, s: f32, l: f32) -> (Iv, Iv) {
        let (s, l) = (Iv::pt(s), Iv::pt(l));
        let n = Iv::pt(self.p0).sub(s.mul(Iv::pt(self.w0))).add(l.mul(self.c0));
        let dp = Iv::pt(self.p0).sub(Iv::pt(self.p1));
        let dw = Iv::pt(self.w0).sub(Iv::pt(self.w1));
        let d = dp.sub(s.mul(dw)).add(l.mul(self.c0.sub(self.c1)));
        (n, d)
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
    let parts = [[mi, hi_i], [-inf, hi_i.min(hi_j)], [mj.max(mi), inf], [mj, hi_j]];
    let mut out: Option<[f32; 2]> = None;
    for [a, b] in parts {
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

impl SafeAxis {
    /// Stage 1, corrected: per vertex the enclosure of its lens crossings
    /// `u_k(X, t) = (X w_k(t) - p_k(t)) / c_k(t)` over the tile's columns and the shutter
    /// (the 4 corners X in {s0, s1}, t in {0, 1}), with the direction of `delta_k` in u
    /// (the sign of `c_k`). None (no lens bound) when a CoC is not of one strict sign
    /// over the shutter, or a value is not finite.
    fn lens_crossings(&self, s0: f32, s1: f32) -> Option<[Crossing; 3]> {
        let mut out = [(false, 0.0, 0.0); 3];
        for (a, o) in self.v.iter().zip(out.iter_mut()) {
            let inc = if a.c0.pos() && a.c1.pos() {
                true
            } else if a.c0.neg() && a.c1.neg() {
                false
            } else {
                return None;
            };
            let (mut m, mut h) = (f32::INFINITY, f32::NEG_INFINITY);
            for (p, w, c) in [(a.p0, a.w0, a.c0), (a.p1, a.w1, a.c1)] {
                for s in [s0, s1] {
                    let l = Iv::pt(s).mul(Iv::pt(w)).sub(Iv::pt(p)).div(c);
                    if !l.ok() {
                        return None;
                    }
                    m = m.min(l.lo);
                    h = h.max(l.hi);
                }
            }
            *o = (inc, m, h);
        }
        Some(out)
    }

    /// Stage 2, corrected (tile level): per vertex the enclosure of its crossing time
    /// `t_k = N / D` over the rectangle of columns [s0, s1] and lens `l` (a linear
    /// fraction of (X, l) jointly: its extremes are at the 4 corners when D keeps one
    /// strict sign there), with the direction of `delta_k(t) = N - t D` in t (increasing
    /// iff D < 0). Vertices may cross in opposite directions. None (no time bound from
    /// this axis) when some D is not of one strict sign on the rectangle.
    fn time_crossings(&self, s0: f32, s1: f32, l: [f32; 2]) -> Option<[Crossing; 3]> {
        let mut out = [(false, 0.0, 0.0); 3];
        for (a, o) in self.v.iter().zip(out.iter_mut()) {
            let (mut pos, mut neg) = (false, false);
            let (mut m, mut h) = (f32::INFINITY, f32::NEG_INFINITY);
            for s in [s0, s1] {
                for lv in l {
                    let (n, d) = a.nd(s, lv);
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
    /// share one strict sign on columns [s0, s1] x lens [-1, 1] (the guarded condition).
    /// Upper endpoints are upper ends of the enclosures, lower endpoints lower ends.
    fn lines(&self, s0: f32, s1: f32) -> Option<Lines> {
        let mut out = Lines { ul: f32::NEG_INFINITY, ur: f32::NEG_INFINITY, ll: f32::INFINITY, lr: f32::INFINITY };
        let (mut pos, mut neg) = (false, false);
        for a in &self.v {
            for s in [s0, s1] {
                let (n0, d0) = a.nd(s, 0.0);
                let (nm, dm) = a.nd(s, -1.0);
                let (np, dp) = a.nd(s, 1.0);
                for d in [dm, dp] {
                    pos |= d.pos();
                    neg |= d.neg();
                    if !(d.pos() || d.neg()) {
                        return None;
                    }
                }
                if pos && neg {
                    return None;
                }
                let (n1, d1) = (a.c0, a.c0.sub(a.c1));
                let tm = nm.div(dm);
                let tp = np.div(dp);
                let tz = n0.div(d0);
                let slope = n1.sub(tz.mul(d1)).div(d0);
                let (gm, gp) = (tz.sub(slope), tz.add(slope));
                if !(tm.ok() && tp.ok() && gm.ok() && gp.ok()) {
                    return None;
                }
                out.ul = out.ul.max(tm.hi.max(gm.hi));
                out.ur = out.ur.max(tp.hi.max(gp.hi));
                out.ll = out.ll.min(tm.lo.min(gm.lo));
                out.lr = out.lr.min(tp.lo.min(gp.lo));
            }
        }
        Some(out)
    }
}

/// `wu2013-safe`'s line pad, 2^-21 = 8u (proof: `src/bounds/proofs/wu2013_safe.g`).
pub(crate) const PAD: f32 = 1.0 / (1u32 << 21) as f32;
/// `wu2013-safe`'s line pad floor, 2^-100.
pub(crate) const FLOOR: f32 = 1.0 / (1u128 << 100) as f32;

/// A padded f32 line `t = a l + b'` through (or beyond) `(-1, e_left)`, `(1, e_right)`:
/// above both for an upper line, below both for a lower one, with `b'` moved outward by
/// the f32 error of [`TimeLine::eval`] (module doc). None beyond `LINE_LIMIT`.
pub(crate) fn safe_line(lens: Lens, upper: bool, e_left: f32, e_right: f32) -> Option<TimeLine> {
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
    let at = |c: &TimeLine, x: f32| Iv::pt(c.a).mul(Iv::pt(x)).add(Iv::pt(c.b));
    if let Some(c) = safe_line(lens, true, ln.ul, ln.ur) {
        let (e0, e1) = (at(&c, l[0]), at(&c, l[1]));
        if e0.ok() && e1.ok() {
            t[1] = t[1].min(e0.hi.max(e1.hi));
            if c.a != 0.0 && e0.lo.min(e1.lo) < 1.0 {
                cons.push(Box::new(c));
            }
        }
    }
    if let Some(c) = safe_line(lens, false, ln.ll, ln.lr) {
        let (e0, e1) = (at(&c, l[0]), at(&c, l[1]));
        if e0.ok() && e1.ok() {
            t[0] = t[0].max(e0.lo.min(e1.lo));
            if c.a != 0.0 && e0.hi.max(e1.hi) > 0.0 {
                cons.push(Box::new(c));
            }
        }
    }
}

struct SafePrep {
    /// Every input is finite (otherwise every tile gets the full domain).
    finite: bool,
    x: SafeAxis,
    y: SafeAxis,
    disabled: Option<&'static str>,
}

impl Prepared for SafePrep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        if !self.finite {
            return TileResult::Bounds(b);
        }
        // Stage 1, sign-aware.
        for (axis, s0, s1, out) in [(&self.x, tile.x0, tile.x1, &mut b.u), (&self.y, tile.y0, tile.y1, &mut b.v)] {
            if let Some(cr) = axis.lens_crossings(s0, s1) {
                match sign_hull(&cr, [-1.0, 1.0]) {
                    None => return TileResult::Empty,
                    Some(r) => *out = r,
                }
            }
        }
        // Stage 2: the sign-aware tile interval over the lens range of stage 1, and the
        // published lines where all vertices cross in one direction.
        let mut t = [0.0f32, 1.0];
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
        for (axis, s0, s1, lens, l) in
            [(&self.x, tile.x0, tile.x1, Lens::U, b.u), (&self.y, tile.y0, tile.y1, Lens::V, b.v)]
        {
            if let Some(cr) = axis.time_crossings(s0, s1, l) {
                match sign_hull(&cr, t) {
                    None => return TileResult::Empty,
                    Some(r) => t = r,
                }
            }
            if let Some(ln) = axis.lines(s0, s1) {
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
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

fn safe_axis(tri: &Triangle, j: usize, scale: f32) -> SafeAxis {
    let k = Iv::pt(scale);
    SafeAxis {
        v: std::array::from_fn(|i| {
            let (q, r) = (tri.q[i], tri.r[i]);
            let (c0, c1) = (k.mul(Iv::pt(tri.c0[i])), k.mul(Iv::pt(tri.c1[i])));
            SafeVertex { p0: q[j], w0: q[3], c0, p1: r[j], w1: r[3], c1 }
        }),
    }
}

fn prepare_safe(tri: &Triangle) -> SafePrep {
    let x = safe_axis(tri, 0, 1.0);
    let y = safe_axis(tri, 1, tri.k);
    let one_sign = |ax: &SafeAxis| ax.v.iter().all(|a| (a.c0.pos() && a.c1.pos()) || (a.c0.neg() && a.c1.neg()));
    // A vertex with D identically 0 on axis j: no motion relative to any pixel ray.
    let dead =
        |j: usize| (0..3).any(|i| tri.q[i][j] == tri.r[i][j] && tri.q[i][3] == tri.r[i][3] && tri.c0[i] == tri.c1[i]);
    let disabled = (!one_sign(&x) && !one_sign(&y) && dead(0) && dead(1)).then_some(
        "no stage applies: a CoC is 0 or changes sign in the shutter on both axes (stage 1 off) and on both axes a \
         vertex has no motion relative to the pixel rays (stage 2 denominators vanish)",
    );
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite())
            && tri.k.is_finite();
    let disabled = if finite { disabled } else { Some("a non-finite input: the full domain for every tile") };
    SafePrep { finite, x, y, disabled }
}

/// The old answer for a tile.
pub(super) fn answer(tri: &Triangle, tile: &Tile) -> TileResult {
    prepare_safe(tri).tile(tile)
}
