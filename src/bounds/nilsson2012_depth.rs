//! nilsson2012-depth: a conservative depth interval `z^` over a tile, after Nilsson,
//! Clarberg, Johnsson, Munkberg, Hasselgren, Toth, Salvi, Akenine-Möller, "Design and
//! Novel Uses of Higher-Dimensional Rasterization", HPG 2012, Appendix A ("Conservative
//! Depth Computations", Eq. 1 and Figure 18), used for z-culling, 5D occlusion queries
//! and continuous collision detection (§3).
//!
//! # What "depth" the paper bounds, and what we output
//! Appendix A works with clip-space points `(x, y, w)`: the plane normal is negated
//! "if n_w < 0", a plane must not "sweep through the camera origin", and the depth is
//! evaluated by intersecting a tile corner's ray with the plane. Along the ray through
//! pixel (X, Y) a point is `w (X, Y, 1)`, so what the paper bounds is **w** (camera-space
//! depth, linear). The model's hit depth is `zeta = z_hit / w_hit`, the barycentric blend
//! of the vertices' clip z over `w_hit` (`docs/model.md` §3.4; the oracle's `N / D`).
//! We bound w as the paper does and convert at the end (see "Conversion" below).
//!
//! # The hit point
//! For an interior sample (x, y, u, v, t) the barycentrics `b_k = E_k / sum E` are all
//! positive and sum to 1, and the hit point is `H = sum b_k p'_k(t)` where
//! `p'_k = p_k(t) + c_k(t) (u, k v, 0)` are the sheared vertices, with
//! `H = w_hit (x, y, 1)` in (x', y', w) and `w_hit > 0` (`docs/model.md`). Its depth is
//! `zeta = (sum b_k z_k(t)) / (sum b_k w_k(t))`. The shear moves x', y' only, never z, w.
//!
//! # Test 1: the moving bounding box (only its depth faces are used)
//! `w_hit` is a convex combination of `w_k(t)`, each a lerp of its two ends, so
//! `w_hit in [min, max]` of the six vertex w values: the nearest / farthest rectangle of
//! the moving box, as the paper uses only the far face for z_max and the near one for
//! z_min. We use only the depth of those faces (not their x, y extent: a ray that misses
//! the far rectangle would need the side faces, which the paper does not use either).
//! When all six w are > 0 the same box also bounds zeta directly: `zeta` is then a
//! weighted mean of `z_k / w_k` with weights `b_k w_k > 0`, and each `z_k(t) / w_k(t)`
//! is a linear fraction of t with no pole in [0, 1], hence monotone; so
//! `zeta in [min, max]` of the six `z / w` values. Both are used.
//!
//! # Test 2: moving planes (Eq. 1)
//! For each end of the shutter (base `t = 0` with the triangle `q`, and `t = 1` with `r`)
//! the normal `n = (P1 - P0) x (P2 - P0)` of the base triangle in (x, y, w) is taken,
//! negated if `n_w < 0` (the paper's orientation rule). The paper's plane for maximum
//! depth is `Pi(t): n . p + d + v t = 0` with `d = -n . q_0` and
//! `v = -max_i (n . r_i + d)` (Eq. 1), i.e. every vertex satisfies
//! `n . p_i(t) <= M(t) = (1 - t) M_base + t M_other` with `M_base = n . q_0` and
//! `M_other = max_i n . r_i`: the function `n . p_i(t) - M(t)` is linear in t, `<= 0` at
//! both ends, hence `<= 0` in between, and so is any convex combination. The paper's
//! "similarly ... minimum depth" is the same construction with min:
//! `n . p_i(t) >= m(t) = lerp(m_base, m_other)`.
//!
//! Choices and deviations here:
//! - `M_base = max_i n . P_i` (and `m_base = min_i`) over the three base vertices
//!   instead of `n . q_0`: identical in exact arithmetic (the base vertices lie on the
//!   plane), and it also covers the f32 rounding of the normal.
//! - Defocus (the paper's extension is one sentence: "the depth estimations need to be
//!   done at the four corners of the two-dimensional bounding box of the lens shape ...
//!   the second test has to be disabled if the plane sweeps over any part of the lens").
//!   We make it rigorous in sheared coordinates, where each lens position (u, v) sees
//!   its own triangle `p'_k` and its own lens point at the origin: with one normal n for
//!   all lens positions, `n . p'_i = n . p_i + c_i (n_x u + n_y k v)`, which is affine in
//!   (u, v), so its maximum over the lens square is at a corner:
//!   `n . p_i + |c_i| (|n_x| + k |n_y|)`. The plane offsets `M_base`, `M_other` take
//!   that maximum (and m the minimum); the planes then hold for every lens position,
//!   and "the plane sweeps over the lens" becomes "the origin of the sheared space lies
//!   on the plane for some t": `M(t) = 0` for some t in [0, 1].
//! - The paper disables a plane that sweeps through the camera origin (lens); so do we,
//!   per plane: the max plane is used only if `M_base`, `M_other` have the same strict
//!   sign, the min plane only if `m_base`, `m_other` do.
//! - The paper evaluates the planes "at the appropriate tile corner using the time
//!   interval t^ from the tile test". This method has no time bound of its own and
//!   outputs the full t range, so t^ = [0, 1] (the range of M over the shutter is
//!   `[min, max]` of its two ends).
//!
//! **From a plane to a bound on w.** Along the ray of (x, y), `n . H = w_hit m(x, y)` with
//! `m(x, y) = n_x x + n_y y + n_w`, affine in (x, y): its range over the tile is spanned by
//! the four tile corners (`[m_lo, m_hi]`). The max plane gives `w m <= E` for some
//! `m in [m_lo, m_hi]`, `E in [E_lo, E_hi]` (E = M(t)), and `w > 0`:
//! - `m_lo > 0`: `w <= E_hi / m_lo` if `E_hi > 0`; if `E_hi <= 0` no hit is possible and
//!   the tile is empty.
//! - `m_lo <= 0` and `E_hi < 0`: only rays with `m < 0` can hit, at `w >= E_hi / m_lo`
//!   (empty if `m_lo = 0`).
//! - otherwise (`m_lo <= 0 <= E_hi`): nothing.
//!
//! The min plane gives `w m >= E'`, i.e. `w (-m) <= -E'`, the same rule. These cases
//! are the paper's "evaluate the plane equation at the appropriate tile corner" made
//! explicit, including the corners where the ray is parallel to the plane and the case
//! where the plane lies behind the lens point for the whole tile (the tile cannot see
//! the triangle, so the answer is Empty: this method can reject tiles).
//!
//! # Conversion from w to zeta
//! For any constants A, B write `z_k(t) = A w_k(t) + B + rho_k(t)`; `rho_k` is again
//! linear in t. Then `zeta = A + (B + rho_H) / w_hit` with `rho_H = sum b_k rho_k(t)` in
//! `[min, max]` of the six `rho` values at the shutter ends. So, with
//! `c in [B + rho_min, B + rho_max]` and `w_hit in [w_lo, w_hi]`, `zeta in A + c / w`,
//! whose extremes lie at the corners (or are infinite on a side when `w_lo = 0`). This is
//! exact for any A, B in real arithmetic; we take the line through the (w, z) of the
//! vertices with the smallest and the largest w (A = B = 0 if those w are equal). For a
//! perspective camera `z = A w + B` holds for every vertex up to the f32 rounding of
//! the clip transform, the residuals are tiny, and the conversion is the monotone map
//! `zeta = A + B / w` of the paper's w bounds. The result is intersected with the direct
//! zeta box of test 1 (when all w > 0). A side that stays unbounded is `-inf` / `+inf`;
//! `z = None` when both are.
//!
//! # Output, degenerate input
//! `TileBounds { u, v, t: full, z: Some([zeta_lo, zeta_hi]) }`, or Empty when the w or
//! zeta interval is empty. A plane whose normal or offsets are not finite, or whose
//! offsets vanish or change sign (sweeps the lens), is dropped; zero-area base
//! triangles give n = 0 and offsets 0, hence dropped. NaN anywhere in a bound drops that
//! bound. `disabled()` is `Some` only when the triangle holds non-finite numbers.
//!
//! # Where f32 can make it non-conservative
//! Every quantity (normal, dot products, corner evaluations of m, divisions, the A, B
//! fit and residuals) is rounded to f32 with no outward rounding, so each bound can be
//! off by a few ulps of the magnitudes involved: a depth exactly at a bound (e.g. a
//! static triangle at constant depth, where the interval is a single value) may fall
//! just outside it. The tile rejection `E_hi <= 0` / `m_lo = 0` near the horizon of the
//! plane (m close to 0) depends on the sign of rounded values. The cancellation in
//! `n = (P1 - P0) x (P2 - P0)` for slivers makes the normal inaccurate, but the offsets
//! are taken from the same rounded normal, so only their own rounding matters.

use super::*;

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
fn w_from(m_lo: f32, e_hi: f32) -> WBound {
    if !(m_lo.is_finite() && e_hi.is_finite()) {
        return WBound::Range(0.0, f32::INFINITY);
    }
    if m_lo > 0.0 {
        if e_hi <= 0.0 {
            WBound::Empty
        } else {
            WBound::Range(0.0, e_hi / m_lo)
        }
    } else if e_hi < 0.0 {
        if m_lo == 0.0 {
            WBound::Empty
        } else {
            WBound::Range(e_hi / m_lo, f32::INFINITY)
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

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Same strict sign, both finite.
fn same_sign(a: f32, b: f32) -> bool {
    (a > 0.0 && b > 0.0 && b.is_finite() && a.is_finite()) || (a < 0.0 && b < 0.0 && a.is_finite() && b.is_finite())
}

impl Plane {
    /// The planes with the normal of the triangle `base` (a shutter end, with CoC `cb`),
    /// bounding the triangle at that end and at the other end `oth` (CoC `co`).
    fn new(base: [[f32; 3]; 3], cb: [f32; 3], oth: [[f32; 3]; 3], co: [f32; 3], k: f32) -> Plane {
        let mut n = cross(sub3(base[1], base[0]), sub3(base[2], base[0]));
        if n[2] < 0.0 {
            n = n.map(|x| -x);
        }
        let lens = n[0].abs() + k * n[1].abs();
        let ext = |pts: [[f32; 3]; 3], c: [f32; 3]| -> (f32, f32) {
            let mut hi = f32::NEG_INFINITY;
            let mut lo = f32::INFINITY;
            for i in 0..3 {
                let d = dot(n, pts[i]);
                let s = c[i].abs() * lens;
                hi = hi.max(d + s);
                lo = lo.min(d - s);
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

    /// The range of `m = n_x x + n_y y + n_w` over the tile (its four corners).
    fn m_range(&self, tile: &Tile) -> (f32, f32) {
        let m = |x: f32, y: f32| self.n[0] * x + self.n[1] * y + self.n[2];
        let c = [m(tile.x0, tile.y0), m(tile.x1, tile.y0), m(tile.x0, tile.y1), m(tile.x1, tile.y1)];
        (c.iter().cloned().fold(f32::INFINITY, f32::min), c.iter().cloned().fold(f32::NEG_INFINITY, f32::max))
    }

    /// The bounds on w of the max and the min plane over the tile (t^ = [0, 1]).
    fn w_bounds(&self, tile: &Tile) -> [WBound; 2] {
        let none = WBound::Range(0.0, f32::INFINITY);
        let (m_lo, m_hi) = self.m_range(tile);
        if m_lo.is_nan() || m_hi.is_nan() {
            return [none, none];
        }
        // max plane: w m <= M(t), M in [min, max] of its ends.
        let up = self.upper.map_or(none, |e| w_from(m_lo, e[0].max(e[1])));
        // min plane: w m >= m(t)  <=>  w (-m) <= -m(t).
        let lo = self.lower.map_or(none, |e| w_from(-m_hi, -(e[0].min(e[1]))));
        [up, lo]
    }
}

#[derive(Debug)]
struct Prep {
    planes: [Plane; 2],
    /// w range of the six vertices (test 1).
    w_box: [f32; 2],
    /// zeta range of the six vertices when all w > 0 (test 1 in zeta).
    zeta_box: Option<[f32; 2]>,
    /// Conversion: zeta = a + c / w with c in [c_lo, c_hi].
    a: f32,
    c: [f32; 2],
    disabled: Option<&'static str>,
}

/// `c / w` over `c in [c0, c1]`, `w in [w0, w1]`, `0 <= w0 <= w1 < inf`, `w > 0`.
fn c_over_w(c: [f32; 2], w: [f32; 2]) -> [f32; 2] {
    if w[0] > 0.0 {
        let q = [c[0] / w[0], c[0] / w[1], c[1] / w[0], c[1] / w[1]];
        return [q.iter().cloned().fold(f32::INFINITY, f32::min), q.iter().cloned().fold(f32::NEG_INFINITY, f32::max)];
    }
    let lo = if c[0] >= 0.0 { c[0] / w[1] } else { f32::NEG_INFINITY };
    let hi = if c[1] <= 0.0 { c[1] / w[1] } else { f32::INFINITY };
    [lo, hi]
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        if self.disabled.is_some() {
            return TileResult::Bounds(b);
        }
        // w: the box, w > 0, and the planes.
        let (mut lo, mut hi) = (self.w_box[0].max(0.0), self.w_box[1]);
        for p in &self.planes {
            for wb in p.w_bounds(tile) {
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
        let q = c_over_w(self.c, [lo, hi]);
        let mut z = [self.a + q[0], self.a + q[1]];
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

struct Nilsson2012Depth;

static INFO: MethodInfo = MethodInfo {
    id: "nilsson2012-depth",
    source: "Nilsson et al. 2012, Design and Novel Uses of Higher-Dimensional Rasterization, HPG 2012, \
             Appendix A (moving bounding box; moving planes, Eq. 1, Figure 18)",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: true, per_sample: false },
};

fn prepare(tri: &Triangle) -> Prep {
    let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite())
            && tri.k.is_finite();
    let (q, r) = (tri.q.map(xyw), tri.r.map(xyw));
    let planes = [Plane::new(q, tri.c0, r, tri.c1, tri.k), Plane::new(r, tri.c1, q, tri.c0, tri.k)];
    let verts: Vec<[f32; 4]> = tri.q.iter().chain(tri.r.iter()).cloned().collect();
    let w_box = [
        verts.iter().map(|p| p[3]).fold(f32::INFINITY, f32::min),
        verts.iter().map(|p| p[3]).fold(f32::NEG_INFINITY, f32::max),
    ];
    let zeta_box = verts.iter().all(|p| p[3] > 0.0).then(|| {
        let zs: Vec<f32> = verts.iter().map(|p| p[2] / p[3]).collect();
        [zs.iter().cloned().fold(f32::INFINITY, f32::min), zs.iter().cloned().fold(f32::NEG_INFINITY, f32::max)]
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
    let res: Vec<f32> = verts.iter().map(|p| p[2] - a * p[3] - bb).collect();
    let c = [
        bb + res.iter().cloned().fold(f32::INFINITY, f32::min),
        bb + res.iter().cloned().fold(f32::NEG_INFINITY, f32::max),
    ];
    Prep { planes, w_box, zeta_box, a, c, disabled: (!finite).then_some("non-finite triangle data") }
}

impl Method for Nilsson2012Depth {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(prepare(tri))
    }
}

pub static METHOD: &dyn Method = &Nilsson2012Depth;

#[cfg(test)]
mod tests {
    use super::super::testkit::{bounds_of, random_lens, random_sample};
    use super::*;
    use crate::model::ThinLens;
    use oracles::DepthCheck;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
        bounds_of(METHOD, tri, tile)
    }

    fn cam() -> ThinLens {
        ThinLens { fx: 100.0, fy: 100.0, cx: 32.0, cy: 32.0, radius: 0.2, focus: 5.0, near: 0.5, far: 50.0 }
    }

    /// Random samples in the tile: every interior sample's exact depth lies in z^ and
    /// no interior sample is culled. Returns the number of interior samples.
    fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> usize {
        let res = bounds(tri, tile);
        let o = tri.to_oracle();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut covered = 0;
        for _ in 0..n {
            let s = random_sample(&mut rng, tile);
            let Some(b) = &res else {
                assert_ne!(
                    oracles::classify(&o, s.to_oracle()),
                    oracles::Coverage::Interior,
                    "{tri:?} {tile:?}: {s:?} culled"
                );
                continue;
            };
            assert!(b.admits(&s));
            let z = b.z.unwrap_or([f32::NEG_INFINITY, f32::INFINITY]);
            match oracles::classify_depth(&o, s.to_oracle(), z[0] as f64, z[1] as f64) {
                DepthCheck::Inside => covered += 1,
                DepthCheck::NotInterior => {}
                d => panic!("{tri:?}\ntile {tile:?}: sample {s:?} depth {d:?} of z^ {z:?}"),
            }
        }
        covered
    }

    #[test]
    fn static_flat_triangle_gets_its_depth() {
        // w = 2, z = 1 everywhere: z / w = 0.5 exactly.
        let tri = Triangle::fixed([[0.0, 0.0, 1.0, 2.0], [200.0, 0.0, 1.0, 2.0], [0.0, 200.0, 1.0, 2.0]]);
        let b = bounds(&tri, &Tile::square(10.0, 10.0, 4.0)).expect("inside tile culled");
        assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
        let z = b.z.expect("no depth");
        assert!(z[0] <= 0.5 && 0.5 <= z[1], "{z:?}");
        assert_eq!(z, [0.5, 0.5]);
        let s = Sample::new(12.0, 12.0, 0.0, 0.0, 0.5);
        assert_eq!(
            oracles::classify_depth(&tri.to_oracle(), s.to_oracle(), z[0] as f64, z[1] as f64),
            DepthCheck::Inside
        );
    }

    #[test]
    fn static_tilted_triangle_from_a_camera() {
        let c = cam();
        let tri = c.triangle(
            [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
            [[-1.0, -1.0, 3.0], [1.5, -1.0, 6.0], [-1.0, 1.5, 9.0]],
        );
        let tri = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tri };
        let mut n = 0;
        for (i, tile) in
            [Tile::square(5.0, 5.0, 4.0), Tile::square(20.0, 10.0, 8.0), Tile { x0: 0.3, y0: 1.7, x1: 1.9, y1: 2.2 }]
                .iter()
                .enumerate()
        {
            n += spot_check(&tri, tile, 3000, i as u64);
            let b = bounds(&tri, tile).unwrap();
            let z = b.z.unwrap();
            // The planes make it much tighter than the vertex box.
            let zb = prepare(&tri).zeta_box.unwrap();
            assert!(z[1] - z[0] < 0.5 * (zb[1] - zb[0]), "{z:?} vs box {zb:?}");
        }
        assert!(n > 1000, "{n}");
    }

    #[test]
    fn far_tile_above_the_horizon_is_culled() {
        // A ground triangle y = -1 (camera space), from z = 2 to 40: its horizon is the
        // row y/w = cy = 32; tiles well above the horizon (larger y) cannot see it.
        let c = cam();
        let g = [[-5.0, -1.0, 2.0], [5.0, -1.0, 2.0], [0.0, -1.0, 40.0]];
        let tri = c.triangle(g, g);
        let tri = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tri };
        assert!(bounds(&tri, &Tile::square(28.0, 60.0, 8.0)).is_none());
        assert!(bounds(&tri, &Tile::square(28.0, 200.0, 8.0)).is_none());
        // Below the horizon it is kept and bounded.
        let b = bounds(&tri, &Tile::square(30.0, 10.0, 4.0)).expect("visible tile culled");
        assert!(b.z.is_some());
        spot_check(&tri, &Tile::square(30.0, 10.0, 4.0), 2000, 5);
    }

    #[test]
    fn moving_triangle_depth_contains_random_samples() {
        let c = cam();
        let q = [[-1.0, -1.0, 3.0], [1.5, -1.0, 4.0], [-1.0, 1.5, 6.0]];
        let r = [[-0.5, -0.8, 4.0], [2.0, -0.6, 7.0], [-0.2, 1.2, 5.0]];
        let motion = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..c.triangle(q, r) };
        let both = c.triangle(q, r);
        // A triangle that flips facing during the shutter.
        let flip = Triangle {
            q: [[0.0, 0.0, 0.2, 1.0], [40.0, 0.0, 0.4, 1.5], [20.0, 30.0, 0.5, 2.0]],
            r: [[0.0, 10.0, 0.3, 1.2], [40.0, 10.0, 0.6, 2.0], [25.0, -20.0, 0.7, 2.5]],
            c0: [0.0; 3],
            c1: [0.0; 3],
            k: 1.0,
        };
        // Per-vertex CoC, vertex behind the lens at t = 1.
        let pv = Triangle {
            q: [[0.0, 0.0, 0.2, 1.0], [40.0, 0.0, 0.4, 1.5], [20.0, 30.0, 0.5, 2.0]],
            r: [[5.0, 5.0, -0.1, -0.5], [45.0, 8.0, 0.6, 2.0], [25.0, 35.0, 0.7, 2.5]],
            c0: [2.0, -1.0, 3.0],
            c1: [1.0, 0.5, -2.0],
            k: 1.2,
        };
        let mut total = 0;
        for (tri, tiles) in [
            (
                motion,
                vec![
                    Tile::square(10.0, 10.0, 8.0),
                    Tile::square(40.0, 30.0, 4.0),
                    Tile { x0: 20.25, y0: 15.5, x1: 21.75, y1: 16.0 },
                ],
            ),
            (both, vec![Tile::square(10.0, 10.0, 8.0), Tile::square(40.0, 30.0, 4.0), Tile::square(0.0, 0.0, 1.0)]),
            (flip, vec![Tile::square(10.0, 0.0, 8.0), Tile::square(18.0, 12.0, 2.0)]),
            (pv, vec![Tile::square(10.0, 0.0, 8.0), Tile::square(18.0, 12.0, 4.0)]),
        ] {
            for (i, tile) in tiles.iter().enumerate() {
                total += spot_check(&tri, tile, 3000, 100 + i as u64);
            }
        }
        assert!(total > 3000, "{total}");
    }

    #[test]
    fn plane_sweeping_the_lens_is_dropped() {
        // A triangle whose plane passes through the camera origin at t = 0 (seen edge
        // on): the offsets at t = 0 are 0, so both planes of base 0 are dropped.
        let tri = Triangle {
            q: [[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 1.0, 2.0], [0.0, 0.0, 1.5, 3.0]],
            r: [[0.0, 0.0, 0.5, 1.0], [10.0, 5.0, 1.0, 2.0], [0.0, 8.0, 1.5, 3.0]],
            c0: [0.0; 3],
            c1: [0.0; 3],
            k: 1.0,
        };
        let p = prepare(&tri);
        assert!(p.planes[0].upper.is_none() && p.planes[0].lower.is_none());
        spot_check(&tri, &Tile::square(0.0, 0.0, 4.0), 3000, 9);
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        let z = Triangle::fixed([[0.0; 4]; 3]);
        let _ = METHOD.setup(&z).tile(&Tile::square(0.0, 0.0, 1.0));
        let mut nan = z;
        nan.q[0][0] = f32::NAN;
        let p = METHOD.setup(&nan);
        assert!(p.disabled().is_some());
        assert!(matches!(p.tile(&Tile::square(0.0, 0.0, 1.0)), TileResult::Bounds(_)));
    }

    #[test]
    fn w_rule() {
        assert_eq!(w_from(2.0, 4.0), WBound::Range(0.0, 2.0));
        assert_eq!(w_from(2.0, -4.0), WBound::Empty);
        assert_eq!(w_from(-2.0, -4.0), WBound::Range(2.0, f32::INFINITY));
        assert_eq!(w_from(0.0, -4.0), WBound::Empty);
        assert_eq!(w_from(-1.0, 4.0), WBound::Range(0.0, f32::INFINITY));
        assert_eq!(c_over_w([-2.0, -1.0], [0.0, 4.0]), [f32::NEG_INFINITY, -0.25]);
        assert_eq!(c_over_w([1.0, 2.0], [1.0, 4.0]), [0.25, 2.0]);
    }

    /// Random triangles of every kind (thin lens or per-vertex CoC, vertices behind the
    /// lens, independent vertex motion in depth too), tiles on the moving triangle.
    #[test]
    fn random_triangles() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let (mut covered, mut bounded, mut tiles) = (0, 0, 0);
        for it in 0..200 {
            let c = random_lens(&mut rng);
            let zlo = if it % 4 == 0 { -1.0 } else { 0.6 };
            let q: [[f32; 3]; 3] = std::array::from_fn(|_| {
                let z = rng.gen_range(zlo..12.0f32);
                [rng.gen_range(-0.15f32..0.15) * z.abs(), rng.gen_range(-0.15f32..0.15) * z.abs(), z]
            });
            let r: [[f32; 3]; 3] = std::array::from_fn(|i| {
                [
                    q[i][0] + rng.gen_range(-0.6..0.6),
                    q[i][1] + rng.gen_range(-0.6..0.6),
                    q[i][2] + rng.gen_range(-1.5..1.5),
                ]
            });
            let mut tri = c.triangle(q, r);
            if it % 3 == 1 {
                tri.c0 = std::array::from_fn(|_| rng.gen_range(-20.0..20.0));
                tri.c1 = std::array::from_fn(|_| rng.gen_range(-20.0..20.0));
            }
            for _ in 0..4 {
                let t: f32 = rng.gen_range(0.0..1.0);
                let (b0, b1): (f32, f32) = (rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0));
                let (b0, b1) = if b0 + b1 > 1.0 { (1.0 - b0, 1.0 - b1) } else { (b0, b1) };
                let bb = [b0, b1, 1.0 - b0 - b1];
                let p: [f32; 4] = std::array::from_fn(|j| (0..3).map(|i| bb[i] * tri.at(i, t)[j]).sum());
                if p[3].is_nan() || p[3] <= 0.05 {
                    continue;
                }
                let size = [1.0f32, 2.0, 4.0, 0.7][rng.gen_range(0..4)];
                let tile =
                    Tile::square(p[0] / p[3] + rng.gen_range(-4.0..4.0), p[1] / p[3] + rng.gen_range(-4.0..4.0), size);
                tiles += 1;
                bounded += bounds(&tri, &tile)
                    .is_some_and(|b| b.z.is_some_and(|z| z[0].is_finite() && z[1].is_finite()))
                    as usize;
                covered += spot_check(&tri, &tile, 200, rng.gen());
            }
        }
        eprintln!("nilsson2012-depth random: {covered} interior samples, {bounded} of {tiles} tiles with a finite z^");
        assert!(covered > 10000 && bounded > tiles / 2, "{covered} {bounded} {tiles}");
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    }
}
