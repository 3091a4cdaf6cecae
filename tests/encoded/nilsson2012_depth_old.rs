//! `nilsson2012-depth` and `nilsson2012-depth-safe` as they were before they were
//! written over `F32Arith` (kept verbatim, the method's metadata aside): the reference
//! the encoded code is compared with, bit for bit.
#![allow(dead_code)]

use cullproof::bounds::{Prepared, TileBounds, TileResult};
use cullproof::{Tile, Triangle};
use std::marker::PhantomData;

/// How each rounded f32 result is taken: as it comes (`Near`, the published method) or
/// moved one f32 step outward (`Outward`, `nilsson2012-depth-safe`). Every bound below
/// is written once, with `R::up` around a result that must not fall below the exact
/// value and `R::dn` around one that must not exceed it; with `Near` both are the
/// identity and the code is the published f32 computation, operation for operation.
trait Round: Send + Sync + 'static {
    /// True for the outward variant: NaN also propagates through min / max.
    const SAFE: bool;
    fn up(x: f32) -> f32;
    fn dn(x: f32) -> f32;
}

/// Round to nearest, nothing more (`nilsson2012-depth`).
struct Near;

/// One step outward after each rounded operation (`nilsson2012-depth-safe`).
struct Outward;

impl Round for Near {
    const SAFE: bool = false;
    #[inline(always)]
    fn up(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn dn(x: f32) -> f32 {
        x
    }
}

impl Round for Outward {
    const SAFE: bool = true;
    #[inline(always)]
    fn up(x: f32) -> f32 {
        x.next_up()
    }
    #[inline(always)]
    fn dn(x: f32) -> f32 {
        x.next_down()
    }
}

/// `a.min(b)`; for the safe variant a NaN operand gives NaN (an unknown value must not
/// be skipped as `f32::min` does).
fn min_r<R: Round>(a: f32, b: f32) -> f32 {
    if R::SAFE && (a.is_nan() || b.is_nan()) {
        f32::NAN
    } else {
        a.min(b)
    }
}

/// `a.max(b)`, NaN-propagating for the safe variant (see [`min_r`]).
fn max_r<R: Round>(a: f32, b: f32) -> f32 {
    if R::SAFE && (a.is_nan() || b.is_nan()) {
        f32::NAN
    } else {
        a.max(b)
    }
}

/// One moving plane with fixed normal n in (x, y, w): for every vertex, lens position
/// and time, `n . p' <= max(e)` over the shutter (max plane) or `>= min(e)` (min plane).
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: [f32; 3],
    /// The max plane's offsets at the two shutter ends, if it is enabled.
    upper: Option<[f32; 2]>,
    /// The min plane's offsets at the two shutter ends, if it is enabled.
    lower: Option<[f32; 2]>,
}

/// What one plane says about w over a tile.
#[derive(Clone, Copy, Debug, PartialEq)]
enum WBound {
    /// No hit is possible.
    Empty,
    /// `lo <= w <= hi` (lo >= 0, hi may be +inf).
    Range(f32, f32),
}

/// `w m <= E` for some `m in [m_lo, m_hi]`, `E in [e_lo, e_hi]`, with `w > 0`.
fn w_from<R: Round>(m_lo: f32, e_hi: f32) -> WBound {
    if !(m_lo.is_finite() && e_hi.is_finite()) {
        return WBound::Range(0.0, f32::INFINITY);
    }
    if m_lo > 0.0 {
        if e_hi <= 0.0 {
            WBound::Empty
        } else {
            WBound::Range(0.0, R::up(e_hi / m_lo))
        }
    } else if e_hi < 0.0 {
        if m_lo == 0.0 {
            WBound::Empty
        } else {
            WBound::Range(R::dn(e_hi / m_lo), f32::INFINITY)
        }
    } else {
        WBound::Range(0.0, f32::INFINITY)
    }
}

fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(p: [f32; 3], q: [f32; 3]) -> [f32; 3] {
    [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
}

/// `a . b` rounded up (`R::up` after each operation): `>=` the exact dot product.
fn dot_up<R: Round>(a: [f32; 3], b: [f32; 3]) -> f32 {
    R::up(R::up(R::up(a[0] * b[0]) + R::up(a[1] * b[1])) + R::up(a[2] * b[2]))
}

/// `a . b` rounded down: `<=` the exact dot product.
fn dot_dn<R: Round>(a: [f32; 3], b: [f32; 3]) -> f32 {
    R::dn(R::dn(R::dn(a[0] * b[0]) + R::dn(a[1] * b[1])) + R::dn(a[2] * b[2]))
}

/// Same strict sign, both finite.
fn same_sign(a: f32, b: f32) -> bool {
    (a > 0.0 && b > 0.0 && b.is_finite() && a.is_finite()) || (a < 0.0 && b < 0.0 && a.is_finite() && b.is_finite())
}

impl Plane {
    /// The planes with the normal of the triangle `base` (a shutter end, with CoC `cb`),
    /// bounding the triangle at that end and at the other end `oth` (CoC `co`).
    fn new<R: Round>(base: [[f32; 3]; 3], cb: [f32; 3], oth: [[f32; 3]; 3], co: [f32; 3], k: f32) -> Plane {
        // Any f32 normal will do (the offsets below are taken for this very n), so
        // n needs no outward rounding.
        let mut n = cross(sub3(base[1], base[0]), sub3(base[2], base[0]));
        if n[2] < 0.0 {
            n = n.map(|x| -x);
        }
        let lens = R::up(n[0].abs() + R::up(k * n[1].abs()));
        let ext = |pts: [[f32; 3]; 3], c: [f32; 3]| -> (f32, f32) {
            let mut hi = f32::NEG_INFINITY;
            let mut lo = f32::INFINITY;
            for i in 0..3 {
                let s = R::up(c[i].abs() * lens);
                hi = max_r::<R>(hi, R::up(dot_up::<R>(n, pts[i]) + s));
                lo = min_r::<R>(lo, R::dn(dot_dn::<R>(n, pts[i]) - s));
            }
            (lo, hi)
        };
        let (lb, hb) = ext(base, cb);
        let (lo, ho) = ext(oth, co);
        let finite = n.iter().all(|x| x.is_finite());
        Plane {
            n,
            upper: (finite && same_sign(hb, ho)).then_some([hb, ho]),
            lower: (finite && same_sign(lb, lo)).then_some([lb, lo]),
        }
    }

    /// The range of `m = n_x x + n_y y + n_w` over the tile (its four corners): the
    /// least corner value rounded down, the greatest rounded up.
    fn m_range<R: Round>(&self, tile: &Tile) -> (f32, f32) {
        let n = self.n;
        let lo = |x: f32, y: f32| R::dn(R::dn(R::dn(n[0] * x) + R::dn(n[1] * y)) + n[2]);
        let hi = |x: f32, y: f32| R::up(R::up(R::up(n[0] * x) + R::up(n[1] * y)) + n[2]);
        let corners = [(tile.x0, tile.y0), (tile.x1, tile.y0), (tile.x0, tile.y1), (tile.x1, tile.y1)];
        (
            corners.iter().map(|&(x, y)| lo(x, y)).fold(f32::INFINITY, min_r::<R>),
            corners.iter().map(|&(x, y)| hi(x, y)).fold(f32::NEG_INFINITY, max_r::<R>),
        )
    }

    /// The bounds on w of the max and the min plane over the tile (t^ = [0, 1]).
    fn w_bounds<R: Round>(&self, tile: &Tile) -> [WBound; 2] {
        let none = WBound::Range(0.0, f32::INFINITY);
        let (m_lo, m_hi) = self.m_range::<R>(tile);
        if m_lo.is_nan() || m_hi.is_nan() {
            return [none, none];
        }
        // max plane: w m <= M(t), M in [min, max] of its ends.
        let up = self.upper.map_or(none, |e| w_from::<R>(m_lo, e[0].max(e[1])));
        // min plane: w m >= m(t)  <=>  w (-m) <= -m(t).
        let lo = self.lower.map_or(none, |e| w_from::<R>(-m_hi, -(e[0].min(e[1]))));
        [up, lo]
    }
}

#[derive(Debug)]
struct Prep<R> {
    planes: [Plane; 2],
    /// w range of the six vertices (test 1).
    w_box: [f32; 2],
    /// zeta range of the six vertices when all w > 0 (test 1 in zeta).
    zeta_box: Option<[f32; 2]>,
    /// Conversion: zeta = a + c / w with c in [c_lo, c_hi].
    a: f32,
    c: [f32; 2],
    disabled: Option<&'static str>,
    round: PhantomData<fn() -> R>,
}

/// `c / w` over `c in [c0, c1]`, `w in [w0, w1]`, `0 <= w0 <= w1 < inf`, `w > 0`.
fn c_over_w<R: Round>(c: [f32; 2], w: [f32; 2]) -> [f32; 2] {
    if w[0] > 0.0 {
        let q = [(c[0], w[0]), (c[0], w[1]), (c[1], w[0]), (c[1], w[1])];
        return [
            q.iter().map(|&(c, w)| R::dn(c / w)).fold(f32::INFINITY, min_r::<R>),
            q.iter().map(|&(c, w)| R::up(c / w)).fold(f32::NEG_INFINITY, max_r::<R>),
        ];
    }
    let lo = if c[0] >= 0.0 { R::dn(c[0] / w[1]) } else { f32::NEG_INFINITY };
    let hi = if c[1] <= 0.0 { R::up(c[1] / w[1]) } else { f32::INFINITY };
    [lo, hi]
}

impl<R: Round> Prepared for Prep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        if self.disabled.is_some() {
            return TileResult::Bounds(b);
        }
        // w: the box, w > 0, and the planes.
        let (mut lo, mut hi) = (self.w_box[0].max(0.0), self.w_box[1]);
        for p in &self.planes {
            for wb in p.w_bounds::<R>(tile) {
                match wb {
                    WBound::Empty => return TileResult::Empty,
                    WBound::Range(l, h) => {
                        if !l.is_nan() {
                            lo = lo.max(l);
                        }
                        if !h.is_nan() {
                            hi = hi.min(h);
                        }
                    }
                }
            }
        }
        if hi.is_nan() || hi <= 0.0 || lo > hi {
            return TileResult::Empty;
        }
        let q = c_over_w::<R>(self.c, [lo, hi]);
        let mut z = [R::dn(self.a + q[0]), R::up(self.a + q[1])];
        if z[0].is_nan() {
            z[0] = f32::NEG_INFINITY;
        }
        if z[1].is_nan() {
            z[1] = f32::INFINITY;
        }
        if let Some(zb) = self.zeta_box {
            z = [z[0].max(zb[0]), z[1].min(zb[1])];
        }
        if z[0] > z[1] {
            return TileResult::Empty;
        }
        if z[0] > f32::NEG_INFINITY || z[1] < f32::INFINITY {
            b.z = Some(z);
        }
        TileResult::Bounds(b)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

fn prepare_with<R: Round>(tri: &Triangle) -> Prep<R> {
    let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite())
            && tri.k.is_finite();
    let (q, r) = (tri.q.map(xyw), tri.r.map(xyw));
    let planes = [Plane::new::<R>(q, tri.c0, r, tri.c1, tri.k), Plane::new::<R>(r, tri.c1, q, tri.c0, tri.k)];
    let verts: Vec<[f32; 4]> = tri.q.iter().chain(tri.r.iter()).cloned().collect();
    let w_box = [
        verts.iter().map(|p| p[3]).fold(f32::INFINITY, f32::min),
        verts.iter().map(|p| p[3]).fold(f32::NEG_INFINITY, f32::max),
    ];
    let zeta_box = verts.iter().all(|p| p[3] > 0.0).then(|| {
        [
            verts.iter().map(|p| R::dn(p[2] / p[3])).fold(f32::INFINITY, min_r::<R>),
            verts.iter().map(|p| R::up(p[2] / p[3])).fold(f32::NEG_INFINITY, max_r::<R>),
        ]
    });
    // The (w, z) line through the vertices of least and greatest w.
    let lo_v = verts.iter().cloned().fold(verts[0], |a, p| if p[3] < a[3] { p } else { a });
    let hi_v = verts.iter().cloned().fold(verts[0], |a, p| if p[3] > a[3] { p } else { a });
    let (mut a, mut bb) = (0.0f32, 0.0f32);
    if hi_v[3] > lo_v[3] {
        a = (hi_v[2] - lo_v[2]) / (hi_v[3] - lo_v[3]);
        bb = lo_v[2] - a * lo_v[3];
        if !(a.is_finite() && bb.is_finite()) {
            a = 0.0;
            bb = 0.0;
        }
    }
    // Residuals z - a w - bb, rounded down for the least and up for the greatest (a
    // and bb are any f32 values: the conversion is exact for every A, B).
    let res_lo = verts.iter().map(|p| R::dn(R::dn(p[2] - R::up(a * p[3])) - bb)).fold(f32::INFINITY, min_r::<R>);
    let res_hi = verts.iter().map(|p| R::up(R::up(p[2] - R::dn(a * p[3])) - bb)).fold(f32::NEG_INFINITY, max_r::<R>);
    let mut c = [R::dn(bb + res_lo), R::up(bb + res_hi)];
    if R::SAFE && (c[0].is_nan() || c[1].is_nan()) {
        c = [f32::NEG_INFINITY, f32::INFINITY];
    }
    Prep {
        planes,
        w_box,
        zeta_box,
        a,
        c,
        disabled: (!finite).then_some("non-finite triangle data"),
        round: PhantomData,
    }
}

/// The old method's setup (`safe`: nilsson2012-depth-safe).
pub fn prepared(safe: bool, tri: &Triangle) -> Box<dyn Prepared> {
    if safe {
        Box::new(prepare_with::<Outward>(tri))
    } else {
        Box::new(prepare_with::<Near>(tri))
    }
}

/// The old method's answer.
pub fn answer(safe: bool, tri: &Triangle, tile: &Tile) -> TileResult {
    prepared(safe, tri).tile(tile)
}
