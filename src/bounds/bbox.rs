//! `bbox`: the screen-space axis-aligned bounding box of the moving, defocused
//! triangle over the whole shutter and the whole lens (the BBOX rasterizer of
//! Munkberg & Akenine-Möller 2012, §3 and Tables 1-3: "a brute-force rasterizer
//! (BBOX), which tests all samples within the triangle's bounding box"; Wu 2013 §3.2
//! builds the same 2D box from the 6 vertex positions grown by the CoC; Nilsson et al.
//! 2012 App. A uses a moving bounding box \[MCH*11\] for depth). It gives no u, v, t
//! information: the tile is either Empty or gets the full domain.
//!
//! # The bound
//! Vertex i seen from lens position (u, v) at time t sits at
//! `x'_i = x_i(t) + u c_i(t)`, `y'_i = y_i(t) + k v c_i(t)`, `w_i(t)`, all linear in t
//! (`x_i(t) = (1-t) q_i.x + t r_i.x`, `c_i(t) = (1-t) c0_i + t c1_i`, ...).
//! When every `w_i(t) > 0` on the shutter, which for linear `w_i` is the same as
//! `q_i.w > 0` and `r_i.w > 0`, the AABB is
//!
//! ```text
//! X_min = min over i, e in {0,1}, s in {-1,+1} of (x_i^e + s c_i^e) / w_i^e
//! X_max = max over the same 12 values
//! Y_min, Y_max the same with (y_i^e + s k c_i^e) / w_i^e
//! ```
//! where `x_i^0 = q_i.x`, `x_i^1 = r_i.x`, `c_i^0 = c0_i`, `c_i^1 = c1_i` (and the same
//! for y, w). The tile `[x0,x1] x [y0,y1]` is Empty iff it is disjoint from
//! `[X_min, X_max] x [Y_min, Y_max]` (`x1 < X_min`, `x0 > X_max`, `y1 < Y_min` or
//! `y0 > Y_max`); a tile that only touches the box is kept.
//!
//! # Derivation (real arithmetic)
//! 1. *A covered pixel lies strictly inside the projected vertices.* Translate the
//!    sheared vertices to the sample's pixel: `P_k = (x'_k - x w_k, y'_k - y w_k, w_k)`.
//!    The edge values `E_k` are the w-components of `P_i x P_j`, and the adjugate
//!    identity `P_0 (P_1 x P_2)^T + P_1 (P_2 x P_0)^T + P_2 (P_0 x P_1)^T = D I`
//!    gives, on its w column, `sum_k E_k P_k = (0, 0, D)`. For an interior sample
//!    every `E_k` has the strict sign of `D != 0`, so `sum_k E_k (x'_k - x w_k) = 0`
//!    and `x = sum_k lambda_k (x'_k / w_k)` with `lambda_k = E_k w_k / sum_j E_j w_j`.
//!    With every `w_k > 0` the `lambda_k` are all > 0 and sum to 1: x is a strict
//!    convex combination of the projected sheared vertices, so
//!    `min_k x'_k/w_k < x < max_k x'_k/w_k` (and the same in y).
//! 2. *The extreme projections sit at the corners of the (u, t) square.* For fixed t,
//!    `x'_i / w_i = (x_i(t) + u c_i(t)) / w_i(t)` is affine in u (w does not depend on
//!    the lens), so over u in [-1, 1] its extremes are at u = ±1. For fixed u,
//!    `(x_i(t) + u c_i(t)) / w_i(t)` is a ratio of two affine functions of t with a
//!    denominator that does not vanish on [0, 1]; its derivative is
//!    `(n' w - n w') / w^2` with a constant numerator, so it is monotone and its
//!    extremes over [0, 1] are at t = 0 and t = 1. The minimum over the square
//!    `min_t min_u` is therefore the minimum over its 4 corners; x does not depend on
//!    v and y does not depend on u, so 3 vertices x 2 times x 2 lens signs per axis.
//!
//! # Vertices behind the lens
//! If some `w_i(t) <= 0` in the shutter the projection is unbounded (the vertex
//! projects to infinity as w crosses 0, or to the "wrong" side when w < 0, where
//! step 1 fails because some `lambda_k` change sign). What the papers do:
//! Wu 2013 §3.2 clips: "If the triangle passes the z = 0 plane, we find out the
//! intersection point at the near plane from the 6 triangle edges and 3 moving point
//! paths" (Figure 3.2), i.e. the box is built from near-plane intersections; Munkberg
//! 2012 §3 takes the AABB from Laine & Karras 2011 \[LK11\] (not available) and does not
//! discuss w <= 0; Nilsson 2012 does not discuss it for the box. There is no near
//! plane in our model (homogeneous rasterization covers points at any w > 0), so we
//! do not clip: **if any `q_i.w <= 0` or `r_i.w <= 0` the AABB is unbounded, the test
//! reports itself disabled and every tile gets the full bounds (never Empty).**
//! Non-finite box values (overflow of a projection, NaN from degenerate input) give
//! the same full answer for that axis.
//!
//! # f32
//! Each corner value is `fl(fl(x ± c) / w)` (for y, `fl(fl(y ± fl(k c)) / w)`): at
//! most 2 (y: 3) roundings, so a computed box side can sit a few ulps inside the
//! real one, and a tile whose side lies within those ulps of the box can be culled
//! while a covered sample exists in the sliver between. That is the only place
//! where f32 rounding can make the answer non-conservative; no epsilon is added.
//!
//! # Choices
//! - The papers leave open how touching is treated: we keep tiles that only touch the
//!   box (a covered sample is strictly inside, so culling them would also be
//!   conservative in real arithmetic).
//! - Wu 2013 §3.2 grows the box of the 6 projected vertices by the largest CoC over the
//!   vertices' depth range, a superset of the box here; we take the per-vertex sheared
//!   corners, which give the exact AABB of the union of the projected vertices over
//!   the lens square and the shutter (so this is the tightest BBOX).
//!
//! # `bbox-safe`: the same box, rounded outward
//! The f32 box above is the published one and stays as it is: the gate finds tiles it
//! culls although they hold covered samples (the tile's edge sits between the rounded
//! corner value and the exact one). `bbox-safe` computes the same corner values and
//! pads each outward by a bound on its rounding error, so the f32 box encloses the
//! real one and every tile it culls is empty (a proof, not a hope).
//!
//! *Error analysis* (u = 2^-24, the unit roundoff of f32 round-to-nearest; the inputs
//! `a` (x or y), `c`, `w > 0`, `k` are f32 values, exact). The corner value is
//! `q = fl(n / w)` with `n = fl(a ± s)`, `s = c` for x (exact) and `s = fl(k c)` for y.
//! A rounded result r of an exact z satisfies `|r - z| <= u |r|` while it is normal; a
//! product or quotient that underflows errs by at most 2^-150 instead, and a sum of two
//! floats that underflows is exact. With `X = (a ± k c) / w` the exact corner value
//! (k = 1 for x):
//!
//! ```text
//! |s - k c|       <= u |s| + 2^-150
//! |n - (a ± s)|   <= u |n|
//! |q - n / w|     <= u |q| + 2^-150,   so |q| <= (|n| / w + 2^-150) / (1 - u)
//! |q - X|         <= |q - n/w| + |n - (a ± s)| / w + |s - k c| / w
//!                 <= 2u (|n| + |s|) / w (1 + 2u) + 2^-149 + 2^-150 / w
//! ```
//!
//! The padding is computed in f32 as `p = fl(fl(fl(|s| + |n|) + 2^-120) / w) * 2^-21`.
//! Three roundings shrink it by at most a factor `(1 - u)^3`, the exact scaling by
//! 2^-21 = 8u can underflow by at most 2^-150, so
//! `p >= 8u (1 - u)^3 (|n| + |s| + 2^-120) / w - 2^-150`: four times the relative term
//! above, and `2^-141 (1 - u)^3 / w`, far above `2^-150 / w`. What is left,
//! `2^-149 + 2^-150` plus the rounding of `q ± p`, is covered by four steps to the next
//! f32 value: the first covers the rounding of the sum (a value rounded to nearest has
//! the exact one between it and its neighbour on that side), the other three move by at
//! least 3 x 2^-149. So the padded ends `next_down^4(fl(q - p))` and
//! `next_up^4(fl(q + p))` enclose X. A value that overflows (inf) or is NaN leaves that
//! axis unbounded, as in `bbox`.
//!
//! Together: the padded corner values enclose the exact ones, the exact box is the
//! min/max of those (derivation above, real arithmetic), and the f32 comparisons of
//! the tile's edges with the padded box are exact. So `bbox-safe` culls a tile only
//! when its distance from the real box exceeds zero: conservative for every finite
//! input with every w > 0, and disabled (full bounds) otherwise.
//!
//! Machine-checked: `src/bounds/proofs/bbox_safe.g` with z3's rounding lemmas (`docs/proofs.md`).
//!
//! *Cost*: per corner value two adds, a divide, a multiply and eight steps more than
//! `bbox`; the box grows by about 2^-21 (|s| + |n|) / w, a few f32 ulps of the
//! coordinates, which no sample test efficiency figure can see.

use super::*;
use crate::bounds::arith::{F32Arith, Plain, TriOf};

/// How one corner value is enclosed, written once over [`F32Arith`] (so the f32
/// method and its SMT-LIB2 encoding in `crate::tools::symbolic` are the same code): from the
/// vertex's coordinate `a` (x or y), its shear `s` (`c`, or `fl(k c)` for y), the
/// sheared value `n = fl(a ± s)` and the depth `w`, the enclosure `[lo, hi]` of the
/// corner value.
pub trait Corner: Send + Sync {
    fn corner<A: F32Arith>(&self, ar: &A, a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2];
}

/// `bbox`'s corner value: `fl(n / w)`.
#[derive(Clone, Copy, Debug)]
pub struct PlainCorner;

impl Corner for PlainCorner {
    fn corner<A: F32Arith>(&self, ar: &A, _a: &A::F, _s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        let q = ar.div(n, w);
        [q.clone(), q]
    }
}

/// `bbox-safe`'s corner value: `fl(n / w)` padded by `p` and four f32 steps (see the
/// module's error analysis).
#[derive(Clone, Copy, Debug)]
pub struct SafeCorner;

impl Corner for SafeCorner {
    fn corner<A: F32Arith>(&self, ar: &A, _a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        padded_corner(ar, s, n, w, [4, 4])
    }
}

/// The padded corner value with `steps[0]` steps down at the lower end and `steps[1]`
/// up at the upper one (bbox-safe: four each; a planted slip drops one side's).
pub(crate) fn padded_corner<A: F32Arith>(ar: &A, s: &A::F, n: &A::F, w: &A::F, steps: [usize; 2]) -> [A::F; 2] {
    // PAD = 2^-21 = 8u and FLOOR = 2^-120 (module constants, tied to the proof)
    let q = ar.div(n, w);
    let sum = ar.add(&ar.add(&ar.abs(s), &ar.abs(n)), &ar.lit(FLOOR));
    let pad = ar.mul(&ar.div(&sum, w), &ar.lit(PAD));
    let (mut lo, mut hi) = (ar.sub(&q, &pad), ar.add(&q, &pad));
    for _ in 0..steps[0] {
        lo = ar.next_down(&lo);
    }
    for _ in 0..steps[1] {
        hi = ar.next_up(&hi);
    }
    // w = +inf is outside the error analysis (finite inputs): n / w = 0 and a pad of
    // 0 would give a finite, culling box. NaN makes the axis never cull, as for
    // every other non-finite input.
    let nan = ar.lit(f32::NAN);
    let finite = ar.is_finite(w);
    [ar.select(&finite, &lo, &nan), ar.select(&finite, &hi, &nan)]
}

/// bbox, or bbox-safe (or a planted slip of [`super::broken::planted`]): the same box
/// with another corner value.
pub(crate) struct BBox<C: Corner> {
    pub(crate) info: &'static MethodInfo,
    pub(crate) corner: C,
}

/// The AABB of the triangle over lens and shutter, or `None` when it is unbounded.
#[derive(Clone, Copy, Debug)]
struct Prep {
    /// `[X_min, X_max, Y_min, Y_max]`, each possibly NaN/inf (then that axis never culls).
    bx: Option<[f32; 4]>,
}

/// The setup, over any [`F32Arith`]: whether the box is bounded (every vertex has
/// `w > 0` at both shutter ends; w is linear in t, and NaN counts as `w <= 0`) and the
/// box `[X_min, X_max, Y_min, Y_max]` over every corner value's enclosure; an axis
/// with a non-finite value is NaN (it never culls). The order of the operations is
/// the method's: per axis (x, then y), per shutter end, per vertex, `n = a - s` then
/// `a + s`, each corner; then the minimum and maximum in that order.
pub fn aabb_of<A: F32Arith, C: Corner>(ar: &A, corner: &C, tri: &TriOf<A::F>) -> (A::B, [A::F; 4]) {
    let ends = [(&tri.q, &tri.c0), (&tri.r, &tri.c1)];
    let zero = ar.lit(0.0);
    let positive: Vec<A::B> = ends.iter().flat_map(|(p, _)| p.iter().map(|v| ar.lt(&zero, &v[3]))).collect();
    let enabled = ar.all(&positive);
    let nan = ar.lit(f32::NAN);
    let mut bx = Vec::with_capacity(4);
    for axis in 0..2 {
        let mut vals = Vec::with_capacity(24);
        for (p, c) in ends {
            for i in 0..3 {
                let (a, w) = (&p[i][axis], &p[i][3]);
                // x: u = ±1 shears by ±c; y: v = ±1 shears by ±k c.
                let s = if axis == 0 { c[i].clone() } else { ar.mul(&tri.k, &c[i]) };
                for n in [ar.sub(a, &s), ar.add(a, &s)] {
                    vals.extend(corner.corner(ar, a, &s, &n, w));
                }
            }
        }
        let finite: Vec<A::B> = vals.iter().map(|v| ar.is_finite(v)).collect();
        let finite = ar.all(&finite);
        let lo = vals[1..].iter().fold(vals[0].clone(), |m, v| ar.min(&m, v));
        let hi = vals[1..].iter().fold(vals[0].clone(), |m, v| ar.max(&m, v));
        bx.push(ar.select(&finite, &lo, &nan));
        bx.push(ar.select(&finite, &hi, &nan));
    }
    let [x0, x1, y0, y1]: [A::F; 4] = bx.try_into().expect("two axes");
    (enabled, [x0, x1, y0, y1])
}

/// The tile reject, over any [`F32Arith`]: a bounded box disjoint from the tile
/// `[x0, y0, x1, y1]` (`x1 < X_min`, `x0 > X_max`, `y1 < Y_min` or `y0 > Y_max`;
/// comparisons with NaN are false, so an axis with a non-finite box never culls).
pub fn rejects<A: F32Arith>(ar: &A, enabled: &A::B, bx: &[A::F; 4], tile: &[A::F; 4]) -> A::B {
    let [tx0, ty0, tx1, ty1] = tile;
    let disjoint = ar.any(&[ar.lt(tx1, &bx[0]), ar.gt(tx0, &bx[1]), ar.lt(ty1, &bx[2]), ar.gt(ty0, &bx[3])]);
    ar.and(enabled, &disjoint)
}

/// The f32 setup of a corner rule: the box, or `None` when it is unbounded.
fn setup_f32<C: Corner>(corner: &C, tri: &Triangle) -> Option<[f32; 4]> {
    let (enabled, bx) = aabb_of(&Plain, corner, &TriOf::of(tri));
    enabled.then_some(bx)
}

/// Setup of the AABB (f32): each corner value `fl(n / w)`.
#[cfg(test)]
fn aabb(tri: &Triangle) -> Option<[f32; 4]> {
    setup_f32(&PlainCorner, tri)
}

/// `bbox-safe`'s relative pad, 2^-21 = 8u (proof: `src/bounds/proofs/bbox_safe.g`).
pub(crate) const PAD: f32 = 1.0 / (1u32 << 21) as f32;
/// `bbox-safe`'s floor, 2^-120: covers the underflow of k c and n / w.
pub(crate) const FLOOR: f32 = 1.0 / (1u128 << 120) as f32;

/// Setup of the outward-rounded AABB of `bbox-safe` (f32; see the module's error
/// analysis): each corner value padded by `p` and four f32 steps.
pub(crate) fn aabb_safe(tri: &Triangle) -> Option<[f32; 4]> {
    setup_f32(&SafeCorner, tri)
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let Some(bx) = self.bx else {
            return TileResult::Bounds(TileBounds::full());
        };
        if rejects(&Plain, &true, &bx, &crate::bounds::arith::tile_of(tile)) {
            TileResult::Empty
        } else {
            TileResult::Bounds(TileBounds::full())
        }
    }
    fn disabled(&self) -> Option<&'static str> {
        match self.bx {
            None => Some("some w_i(t) <= 0 in the shutter: the screen AABB is unbounded"),
            Some(_) => None,
        }
    }
}

static INFO: MethodInfo = MethodInfo {
    id: "bbox",
    source: "screen AABB of the moving, defocused triangle: BBOX of Munkberg & \
             Akenine-Möller 2012 §3, Tables 1-3; Wu 2013 §3.2; corners (x ± c)/w, \
             (y ± k c)/w at t = 0, 1 (derived in this file)",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: false, per_sample: false },
};

impl<C: Corner + 'static> Method for BBox<C> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep { bx: setup_f32(&self.corner, tri) })
    }
}

pub static METHOD: &dyn Method = &BBox { info: &INFO, corner: PlainCorner };

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "bbox-safe",
    source: "bbox with every corner value padded outward by a bound on its f32 rounding \
             error (error analysis in this file): conservative for every finite input",
    ..INFO
};

/// `bbox-safe`: the box rounded outward (see the module's error analysis).
pub static METHOD_SAFE: &dyn Method = &BBox { info: &INFO_SAFE, corner: SafeCorner };

#[cfg(test)]
mod tests {
    use super::super::testkit::assert_spot;
    use super::*;

    fn admits_any(r: &TileResult) -> bool {
        matches!(r, TileResult::Bounds(_))
    }

    /// Random samples in the tile: no interior-covered sample may be rejected.
    /// Returns the number of covered samples seen.
    fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> usize {
        assert_spot(METHOD, tri, tile, n, seed).0
    }

    fn moving() -> Triangle {
        // Moves right by 40 px, defocused with CoC 6 -> 2 (clip units, w = 2 -> 3).
        Triangle {
            q: [[0.0, 0.0, 0.5, 2.0], [20.0, 0.0, 0.5, 2.0], [0.0, 20.0, 0.5, 2.0]],
            r: [[120.0, 0.0, 0.5, 3.0], [150.0, 0.0, 0.5, 3.0], [120.0, 30.0, 0.5, 3.0]],
            c0: [6.0, 6.0, 6.0],
            c1: [2.0, 2.0, 2.0],
            k: 1.5,
        }
    }

    #[test]
    fn static_triangle_keeps_inside_tile() {
        let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0]]);
        let p = METHOD.setup(&tri);
        assert!(p.disabled().is_none());
        match p.tile(&Tile::square(10.0, 10.0, 4.0)) {
            TileResult::Bounds(b) => assert_eq!(b.t, [0.0, 1.0]),
            TileResult::Empty => panic!("inside tile culled"),
        }
    }

    #[test]
    fn far_tile_is_culled_and_box_is_tight() {
        let tri = moving();
        let p = METHOD.setup(&tri);
        // x range: t=0: (0-6)/2 = -3 .. (20+6)/2 = 13; t=1: (120-2)/3 = 39.33 .. 152/3 = 50.67.
        // y range: t=0: (0-9)/2 = -4.5 .. 29/2 = 14.5; t=1: -3/3 = -1 .. 33/3 = 11.
        assert!(matches!(p.tile(&Tile::square(200.0, 0.0, 4.0)), TileResult::Empty));
        assert!(matches!(p.tile(&Tile::square(0.0, -60.0, 4.0)), TileResult::Empty));
        assert!(matches!(p.tile(&Tile { x0: -10.0, y0: 0.0, x1: -3.01, y1: 1.0 }), TileResult::Empty));
        assert!(admits_any(&p.tile(&Tile { x0: -10.0, y0: 0.0, x1: -2.99, y1: 1.0 })));
        assert!(matches!(p.tile(&Tile { x0: 50.7, y0: 0.0, x1: 60.0, y1: 1.0 }), TileResult::Empty));
        assert!(admits_any(&p.tile(&Tile { x0: 50.6, y0: 0.0, x1: 60.0, y1: 1.0 })));
        assert!(matches!(p.tile(&Tile { x0: 0.0, y0: 14.6, x1: 1.0, y1: 20.0 }), TileResult::Empty));
        assert!(admits_any(&p.tile(&Tile { x0: 0.0, y0: 14.4, x1: 1.0, y1: 20.0 })));
        assert!(matches!(p.tile(&Tile { x0: 0.0, y0: -9.0, x1: 1.0, y1: -4.6 }), TileResult::Empty));
        assert!(admits_any(&p.tile(&Tile { x0: 0.0, y0: -9.0, x1: 1.0, y1: -4.4 })));
        // Touching counts as overlapping.
        assert!(admits_any(&p.tile(&Tile { x0: -10.0, y0: 0.0, x1: -3.0, y1: 1.0 })));
    }

    #[test]
    fn perspective_motion_extremes_are_at_the_ends() {
        // A vertex moving in depth: x/w along the path is monotone, so the box from the
        // ends is exact; checked against a dense scan of t.
        let tri = Triangle {
            q: [[-10.0, 0.0, 0.5, 1.0], [-8.0, 0.0, 0.5, 1.0], [-9.0, 1.0, 0.5, 1.0]],
            r: [[40.0, 0.0, 0.5, 10.0], [42.0, 0.0, 0.5, 10.0], [41.0, 1.0, 0.5, 10.0]],
            c0: [1.0, 1.0, 1.0],
            c1: [-3.0, -3.0, -3.0],
            k: 1.0,
        };
        let bx = aabb(&tri).unwrap();
        for n in 0..=1000 {
            let t = n as f32 / 1000.0;
            for i in 0..3 {
                let v = tri.at(i, t);
                let c = tri.coc(i, t);
                for s in [-1.0f32, 1.0] {
                    let x = (v[0] as f64 + s as f64 * c as f64) / v[3] as f64;
                    assert!(x >= bx[0] as f64 - 1e-4 && x <= bx[1] as f64 + 1e-4, "t {t} x {x} {bx:?}");
                }
            }
        }
    }

    #[test]
    fn vertex_behind_the_lens_gives_full_bounds() {
        let mut tri = moving();
        tri.r[2][3] = -1.0;
        let p = METHOD.setup(&tri);
        assert!(p.disabled().is_some());
        match p.tile(&Tile::square(1.0e6, 1.0e6, 2.0)) {
            TileResult::Bounds(b) => {
                assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
            }
            TileResult::Empty => panic!("w <= 0 must not cull"),
        }
        tri.r[2][3] = 0.0;
        assert!(METHOD.setup(&tri).disabled().is_some());
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        let tri = Triangle { q: [[0.0; 4]; 3], r: [[0.0; 4]; 3], c0: [0.0; 3], c1: [0.0; 3], k: 0.0 };
        let _ = METHOD.setup(&tri).tile(&Tile::square(0.0, 0.0, 1.0));
        let mut t2 = moving();
        t2.q[0][3] = 1.0e-45; // denormal w: projection overflows to inf, that axis never culls
        t2.q[0][0] = 1.0e30;
        let p = METHOD.setup(&t2);
        assert!(admits_any(&p.tile(&Tile::square(1.0e9, 0.0, 1.0))));
    }

    #[test]
    fn no_covered_sample_is_culled() {
        let tri = moving();
        // A thin-lens triangle crossing the focal plane (CoC changes sign) with
        // perspective motion: the first of the dual-space tests' hard triangles.
        let lens_tri = super::super::la2011::cases::hard_triangles()[0];
        let mut total = 0;
        let mut seed = 1;
        for (tri, tiles) in [
            (
                tri,
                vec![
                    Tile::square(-4.0, -5.0, 2.0),
                    Tile::square(12.0, 13.0, 2.0),
                    Tile::square(30.0, 4.0, 4.0),
                    Tile::square(48.0, 10.0, 3.0),
                ],
            ),
            (
                lens_tri,
                vec![Tile::square(-30.0, -30.0, 8.0), Tile::square(10.0, 5.0, 4.0), Tile::square(-5.0, 20.0, 4.0)],
            ),
        ] {
            for tile in tiles {
                total += spot_check(&tri, &tile, 4000, seed);
                seed += 1;
            }
        }
        assert!(total > 500, "too few covered samples to mean anything: {total}");
    }

    /// The padded box holds the exact corner values (computed in f64, exact for these
    /// sums and within 2^-53 for the quotient, far below an f32 ulp) of random
    /// triangles of every scale, including subnormal and huge coordinates, and holds
    /// the unpadded box.
    #[test]
    fn bbox_safe_never_culls_with_an_infinite_w() {
        // w = +inf at one vertex and shutter end: every corner value of the other
        // vertices is finite, yet the axis must not cull (non-finite input).
        let tri = Triangle::fixed([[10.0, 10.0, 0.5, f32::INFINITY], [20.0, 10.0, 0.5, 1.0], [10.0, 20.0, 0.5, 1.0]]);
        let bx = aabb_safe(&tri).expect("w > 0 everywhere: enabled");
        assert!(bx.iter().all(|v| v.is_nan()), "{bx:?}");
        let far = Tile::square(1000.0, 1000.0, 4.0);
        assert!(matches!(METHOD_SAFE.setup(&tri).tile(&far), TileResult::Bounds(_)));
        // The same triangle with a finite w culls that tile.
        let tri = Triangle::fixed([[10.0, 10.0, 0.5, 1.0], [20.0, 10.0, 0.5, 1.0], [10.0, 20.0, 0.5, 1.0]]);
        assert!(matches!(METHOD_SAFE.setup(&tri).tile(&far), TileResult::Empty));
    }

    #[test]
    fn the_safe_box_encloses_the_exact_corners() {
        let mut seed = 0x1234_5678_9abc_def1u64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in 0..20_000 {
            let scale = [1e-40f64, 1e-20, 1e-3, 1.0, 1e3, 1e6, 1e15, 1e30][n % 8];
            let mut tri = moving();
            for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
                p[0] = ((rnd() - 0.5) * 2.0 * scale) as f32;
                p[1] = ((rnd() - 0.5) * 2.0 * scale) as f32;
                p[3] = (rnd() * 4.0f64.powi((rnd() * 20.0) as i32 - 10)) as f32 + f32::MIN_POSITIVE;
            }
            for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
                *c = ((rnd() - 0.5) * 2.0 * scale) as f32;
            }
            tri.k = (0.25 + rnd() * 4.0) as f32;
            let (Some(safe), Some(plain)) = (aabb_safe(&tri), aabb(&tri)) else { continue };
            for (axis, ends) in [(0usize, [safe[0], safe[1]]), (1, [safe[2], safe[3]])] {
                if ends[0].is_nan() {
                    continue;
                }
                for (p, c) in [(&tri.q, &tri.c0), (&tri.r, &tri.c1)] {
                    for i in 0..3 {
                        let s = if axis == 0 { c[i] as f64 } else { tri.k as f64 * c[i] as f64 };
                        for sg in [-1.0, 1.0] {
                            let x = (p[i][axis] as f64 + sg * s) / p[i][3] as f64;
                            assert!(
                                ends[0] as f64 <= x && x <= ends[1] as f64,
                                "axis {axis} vertex {i}: exact {x:e} outside {ends:?} ({tri:?})"
                            );
                        }
                    }
                }
            }
            let pl = [plain[0], plain[1], plain[2], plain[3]];
            if !pl[0].is_nan() && !safe[0].is_nan() {
                assert!(safe[0] <= pl[0] && safe[1] >= pl[1]);
            }
        }
    }

    /// The code before it was written over [`F32Arith`], kept to show that the f32
    /// instance computes the same boxes and answers.
    mod before {
        use super::super::*;
        fn extent(vals: impl Iterator<Item = f32>) -> Option<[f32; 2]> {
            let mut lo = f32::INFINITY;
            let mut hi = f32::NEG_INFINITY;
            for v in vals {
                if !v.is_finite() {
                    return None;
                }
                lo = lo.min(v);
                hi = hi.max(v);
            }
            Some([lo, hi])
        }
        fn aabb_with(tri: &Triangle, corner: impl Fn(f32, f32, f32) -> [f32; 2] + Copy) -> Option<[f32; 4]> {
            let ends = [(&tri.q, &tri.c0), (&tri.r, &tri.c1)];
            if ends.iter().any(|(p, _)| p.iter().any(|v| v[3] <= 0.0 || v[3].is_nan())) {
                return None;
            }
            let corners = |axis: usize, scale: f32| {
                ends.iter().flat_map(move |(p, c)| {
                    (0..3).flat_map(move |i| {
                        let (a, w, s) = (p[i][axis], p[i][3], scale * c[i]);
                        [a - s, a + s].into_iter().flat_map(move |n| corner(n, s, w))
                    })
                })
            };
            let (kx, ky) = (1.0f32, tri.k);
            let nan = f32::NAN;
            let [x0, x1] = extent(corners(0, kx)).unwrap_or([nan, nan]);
            let [y0, y1] = extent(corners(1, ky)).unwrap_or([nan, nan]);
            Some([x0, x1, y0, y1])
        }
        pub fn aabb(tri: &Triangle) -> Option<[f32; 4]> {
            aabb_with(tri, |n, _, w| {
                let q = n / w;
                [q, q]
            })
        }
        pub fn aabb_safe(tri: &Triangle) -> Option<[f32; 4]> {
            const PAD: f32 = 1.0 / (1u32 << 21) as f32;
            const FLOOR: f32 = 1.0 / (1u128 << 120) as f32;
            aabb_with(tri, |n, s, w| {
                let q = n / w;
                let pad = ((s.abs() + n.abs() + FLOOR) / w) * PAD;
                let (lo, hi) = (q - pad, q + pad);
                [lo.next_down().next_down().next_down().next_down(), hi.next_up().next_up().next_up().next_up()]
            })
        }
        pub fn disjoint(bx: Option<[f32; 4]>, tile: &Tile) -> bool {
            bx.is_some_and(|[bx0, bx1, by0, by1]| tile.x1 < bx0 || tile.x0 > bx1 || tile.y1 < by0 || tile.y0 > by1)
        }
    }

    /// A random triangle of any scale (some with w <= 0, some overflowing) and a tile
    /// near its box.
    pub(crate) fn random_triangle(rnd: &mut impl FnMut() -> f64, n: usize) -> (Triangle, Tile) {
        let scale = [1e-40f64, 1e-20, 1e-3, 1.0, 1e3, 1e6, 1e15, 1e30][n % 8];
        let mut tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0]; 3]);
        for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
            p[0] = ((rnd() - 0.5) * 2.0 * scale) as f32;
            p[1] = ((rnd() - 0.5) * 2.0 * scale) as f32;
            p[3] = (rnd() * 4.0f64.powi((rnd() * 20.0) as i32 - 10)) as f32 + f32::MIN_POSITIVE;
            if rnd() < 0.02 {
                p[3] = -p[3];
            }
        }
        for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
            *c = ((rnd() - 0.5) * 2.0 * scale) as f32;
        }
        tri.k = (0.25 + rnd() * 4.0) as f32;
        let (x, y) = (((rnd() - 0.5) * 4.0 * scale) as f32, ((rnd() - 0.5) * 4.0 * scale) as f32);
        let size = (scale * rnd()) as f32;
        (tri, Tile { x0: x, y0: y, x1: x + size, y1: y + size })
    }

    #[test]
    fn the_generic_form_equals_the_old_code() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let same = |a: Option<[f32; 4]>, b: Option<[f32; 4]>| match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => a.iter().zip(&b).all(|(x, y)| x == y || (x.is_nan() && y.is_nan())),
            _ => false,
        };
        let mut culled = 0;
        for n in 0..50_000 {
            let (tri, tile) = random_triangle(&mut rnd, n);
            let (new, old) = (aabb(&tri), before::aabb(&tri));
            assert!(same(new, old), "{tri:?}: {new:?} vs {old:?}");
            let (new_s, old_s) = (aabb_safe(&tri), before::aabb_safe(&tri));
            assert!(same(new_s, old_s), "{tri:?}: {new_s:?} vs {old_s:?}");
            for (m, bx) in [(METHOD, old), (METHOD_SAFE, old_s)] {
                let empty = matches!(m.setup(&tri).tile(&tile), TileResult::Empty);
                assert_eq!(empty, before::disjoint(bx, &tile), "{tri:?} {tile:?}");
                culled += empty as usize;
            }
        }
        assert!(culled > 1000, "too few culled tiles to compare: {culled}");
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    }
}
