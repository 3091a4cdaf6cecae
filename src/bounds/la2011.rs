//! `la2011` (**reconstruction**): per-tile time bounds in dual space and per-tile lens
//! bounds, after Laine, Aila, Karras & Lehtinen 2011, "Clipless Dual-Space Bounds for
//! Faster Stochastic Rasterization" (LAKL11, ACM TOG 30(4) 106). That paper is not
//! available to this project; this file follows `docs/reconstructions.md` (§2 "The
//! dual-space quantity" with its clipless column test, §3 "la2011" with LA's time and
//! lens bounds), built on what the available papers say about LA: Munkberg &
//! Akenine-Möller 2012 §1 (LA culls "by clipping down the extents of u, v, and t
//! individually", Figure 1; cost in Table 3) and Wu 2013 ch. 2 (the motion part uses
//! `delta = x - w gamma`, linear in t, and bounds time "by linear interpolation"; the
//! defocus part bounds the lens from the triangle's extents at two lens positions).
//! Every formula below is derived again here; none is quoted from LAKL11.
//!
//! # The dual-space quantity
//! For a screen column X, vertex i, lens coordinate u and time t,
//! `delta_i(X, u, t) = x_i(t) + u c_i(t) - X w_i(t)`: the x of the sheared vertex
//! after translating column X to the origin (`P_i.x` of `docs/model.md`). It is affine in each
//! of X, u, t separately (the `u t` term comes from `c_i(t)`). In y:
//! `eps_i(Y, v, t) = y_i(t) + k v c_i(t) - Y w_i(t)`. Everything below is said for x;
//! y is the same with (Y, v, k c_i) in place of (X, u, c_i).
//!
//! # Lemma (why deltas bound coverage, for any sign of w)
//! For a sample (x, y, u, v, t) put `P_k = (delta_k(x, u, t), eps_k(y, v, t), w_k(t))`.
//! The edge values `E_k` are the w-components of `P_i x P_j`, and the adjugate
//! identity `sum_k P_k (P_i x P_j)^T = det(P) I` read on its w column gives
//! `sum_k E_k P_k = (0, 0, D)`. An interior sample has every `E_k` of the strict sign
//! of `D != 0`, so `sum_k E_k delta_k = 0` with positive (or all negative) weights:
//! the deltas cannot all be >= 0 (they would all be 0, the x column of P would vanish
//! and D = 0). Hence **interior => min_k delta_k(x,u,t) < 0 < max_k delta_k(x,u,t)**,
//! and the same for eps. No assumption on the sign of w is needed.
//!
//! # Clipless column test (from the tile's x to its two columns)
//! `delta_i(x)` is affine in x, so for x in [X0, X1]
//! `min(delta_i(X0), delta_i(X1)) <= delta_i(x) <= max(delta_i(X0), delta_i(X1))`.
//! Hence a covered sample in the tile at (u, t) has
//! `m(u,t) := min over i, X in {X0,X1} of delta_i(X,u,t) < 0` and
//! `M(u,t) := max over the same 6 values > 0`. If every `w_i > 0`, `delta_i` decreases
//! with X and `m = min_i delta_i(X1)`, `M = max_i delta_i(X0)`: the reconstruction's
//! formulas. Taking both columns for both sides is what keeps the test valid when a
//! vertex is behind the lens (w <= 0), without clipping ("clipless"). In f32 it gives
//! bit-identical values to the X1-only / X0-only form when every w > 0, because
//! `fl(X w)` and `fl(x - fl(X w))` are monotone in X.
//!
//! # LA time bounds
//! For a time t to hold a covered sample, `m(u, t) < 0` for some u in [-1, 1].
//! `delta_i` is affine in u, so `min_u delta_i(X,u,t) = delta_i(X,±1,t)`, i.e.
//! `x_i(t) - X w_i(t) - |c_i(t)|`; the lens is fixed at u = ±1 (both copies of each
//! vertex). So t can hold a covered sample only if
//! `F(t) := min over i, X, s = ±1 of delta_i(X, s, t) < 0`. Each of the 12 functions is
//! affine in t, so F is concave and lies above its chord:
//! `F(t) >= (1-t) L0 + t L1`, `L0 = F(0)`, `L1 = F(1)` (at t = 0, 1 the min over
//! s = ±1 is `d - |c|` with `c = c0_i` or `c1_i`). Cull the t where the chord is > 0:
//! - `L0 > 0` and `L1 > 0`: the chord is positive on [0, 1]: the tile is **Empty**
//!   (this is the clipless column test over the whole lens and shutter);
//! - `L0 > 0 >= L1`: keep `t >= t* = L0 / (L0 - L1)`;
//! - `L1 > 0 >= L0`: keep `t <= t*` (same formula);
//! - both <= 0: no cut.
//!
//! Symmetrically `G(t) := max ... delta_i(X, s, t) = max (x_i - X w_i + |c_i|)` is convex,
//! below its chord, and t needs `G(t) > 0`: cull where the chord `(1-t) H0 + t H1` is
//! < 0. The same is done in y with `|k c_i|`, and `t^` is the intersection of the four
//! ranges. Between the lens extremes nothing is lost: the bound holds for every u in
//! [-1, 1] because the minimum over u of an affine function is at u = ±1.
//!
//! # LA lens bounds
//! A covered sample at (u, t) needs `delta_i(X, u, t) < 0` for some (i, X) (condition
//! a) and `delta_j(X', u, t) > 0` for some (j, X') (condition b). For one (i, X), with
//! `d(t) = x_i(t) - X w_i(t)` and `c(t) = c_i(t)`, the set of u where
//! `d(t) + u c(t) < 0` is, per shutter time:
//! - `u < theta(t)` if `c(t) > 0`, `u > theta(t)` if `c(t) < 0`, with the per-vertex
//!   lens threshold `theta(t) = u_i(X, t) = (X w_i(t) - x_i(t)) / c_i(t)`;
//! - everything or nothing if `c(t) = 0`.
//!
//! If `c_i` has one strict sign at both shutter ends it has it on all of [0, 1], and
//! `theta` is a ratio of affine functions with a non-vanishing denominator, hence
//! monotone (its derivative has the constant numerator `d'c - d c'` over `c^2`): its
//! extremes over the shutter are at t = 0, 1. So the union over t is
//! `u < max(theta(0), theta(1))` (c > 0) or `u > min(theta(0), theta(1))` (c < 0). If
//! `c_i = 0` at both ends, the set is everything when `d(0) < 0` or `d(1) < 0` and
//! empty otherwise. If `c_i` changes sign or touches 0 at one end only, we take the
//! whole lens for that (i, X) (the reconstruction's "use the full lens"). The lens
//! range of condition (a) is the hull of the union over the 6 (i, X); (b) is the same
//! with the inequality reversed; `u^` is the intersection of both hulls with [-1, 1].
//! Empty when that intersection is empty (or when no (i, X) can satisfy a condition).
//!
//! # What we are unsure of in the reconstruction
//! - Whether LAKL11 evaluates its time bounds with the lens fixed at u = ±1 (as here)
//!   or inside the tile's already-clipped lens range, and whether it bounds time from
//!   the chord of the min over vertices (as here) or by per-vertex crossing times;
//!   the chord is the tightest bound that uses only the two shutter ends.
//! - Wu 2013 describes LA's lens part as interpolating the triangle's AABBs at two lens
//!   positions. For one time, with every w > 0, the per-vertex thresholds give exactly
//!   the lens range where the triangle's AABB at lens u meets the tile's columns (the
//!   AABB side `min_i (x_i + u c_i) / w_i` is a concave min of lines in u). Linear
//!   interpolation between AABBs at two lens positions replaces that min by its chord,
//!   which is below it: also conservative, never tighter. We implement the thresholds
//!   that `docs/reconstructions.md` specifies; LAKL11 may be looser here.
//! - The reconstruction asks for the full lens when some `w_i <= 0` in the shutter. The
//!   derivation above (both columns, the lemma) never uses the sign of w, so we keep
//!   the lens bounds then; with every w > 0 the thresholds at the other column are
//!   dominated and the result is identical (this is a deviation only for w <= 0).
//! - The "per tile" costs of munkberg2012 Table 3 (LA: 500 / 40 / -) suggest part of
//!   the work sits in the triangle setup; we recompute everything per tile.
//!
//! # f32
//! All values are computed in f32 without FMA: `d = fl(x - fl(X w))`, `fl(d ± |c|)`,
//! `t* = fl(L0 / fl(L0 - L1))`, `theta = fl(fl(fl(X w) - x) / c)`. A computed `L_k` can
//! differ from the real one by a few ulps of `|x| + |X w| + |c|`, and `t*` and `theta`
//! carry a few more ulps: a bound can cut a covered sample within those few ulps of
//! it, and a tile can be called Empty when the real `L0` or `L1` is within those ulps of
//! 0. No epsilon is added. Non-finite intermediate values (overflow, NaN from
//! degenerate input) make the affected quantity fall back to its full range.
//!
//! # Degenerate input
//! No division by a quantity that can be 0: `L0 - L1 > 0` where it is used, and `theta`
//! is only formed when `c` has a strict sign. Zero-area or coincident vertices need no
//! special case.

use super::*;

/// Sign class of a per-vertex lens shear over the shutter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    /// > 0 at both ends (so on all of [0, 1]).
    Pos,
    /// < 0 at both ends.
    Neg,
    /// Exactly 0 at both ends.
    Zero,
    /// Changes sign, touches 0 at one end, or is NaN.
    Cross,
}

impl Class {
    fn of(s0: f32, s1: f32) -> Class {
        if s0 > 0.0 && s1 > 0.0 {
            Class::Pos
        } else if s0 < 0.0 && s1 < 0.0 {
            Class::Neg
        } else if s0 == 0.0 && s1 == 0.0 {
            Class::Zero
        } else {
            Class::Cross
        }
    }
    fn flip(self) -> Class {
        match self {
            Class::Pos => Class::Neg,
            Class::Neg => Class::Pos,
            c => c,
        }
    }
}

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    /// w.
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y.
    s: [[f32; 3]; 2],
    class: [Class; 3],
}

impl Axis {
    fn new(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        let p = [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])];
        let w = [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])];
        let s = [tri.c0.map(|c| scale * c), tri.c1.map(|c| scale * c)];
        let class = [0, 1, 2].map(|i| Class::of(s[0][i], s[1][i]));
        Axis { p, w, s, class }
    }

    /// `d = p - X w` for end e, vertex i.
    fn d(&self, e: usize, i: usize, x: f32) -> f32 {
        self.p[e][i] - x * self.w[e][i]
    }

    /// Time range and lens range for the tile columns `[lo, hi]` of this axis, or
    /// None when the axis proves the tile empty.
    fn bounds(&self, lo: f32, hi: f32) -> Option<([f32; 2], [f32; 2])> {
        let cols = [lo, hi];
        // --- time: F(e) = min (d - |s|), G(e) = max (d + |s|) over i and both columns.
        let mut f = [f32::INFINITY; 2];
        let mut g = [f32::NEG_INFINITY; 2];
        let mut nan = false;
        for e in 0..2 {
            for i in 0..3 {
                let a = self.s[e][i].abs();
                for &x in &cols {
                    let d = self.d(e, i, x);
                    let (m, mm) = (d - a, d + a);
                    nan |= m.is_nan() || mm.is_nan();
                    f[e] = f[e].min(m);
                    g[e] = g[e].max(mm);
                }
            }
        }
        let t = if nan {
            [0.0, 1.0]
        } else {
            let tf = chord_nonpos(f[0], f[1])?;
            let tg = chord_nonpos(-g[0], -g[1])?;
            [tf[0].max(tg[0]), tf[1].min(tg[1])]
        };
        if t[0] > t[1] {
            return None;
        }
        // --- lens: hull of condition (a) "some d + u s < 0", and (b) "some d + u s > 0".
        let mut ha: Option<[f32; 2]> = None;
        let mut hb: Option<[f32; 2]> = None;
        let join = |h: &mut Option<[f32; 2]>, r: Option<[f32; 2]>| {
            if let Some(r) = r {
                *h = Some(match *h {
                    None => r,
                    Some(h) => [h[0].min(r[0]), h[1].max(r[1])],
                });
            }
        };
        for i in 0..3 {
            let s = [self.s[0][i], self.s[1][i]];
            for &x in &cols {
                let d = [self.d(0, i, x), self.d(1, i, x)];
                join(&mut ha, neg_hull(d, s, self.class[i]));
                join(&mut hb, neg_hull([-d[0], -d[1]], [-s[0], -s[1]], self.class[i].flip()));
            }
        }
        let (ha, hb) = (ha?, hb?);
        let lens = [ha[0].max(hb[0]).max(-1.0), ha[1].min(hb[1]).min(1.0)];
        if lens[0] > lens[1] {
            return None;
        }
        Some((t, lens))
    }
}

/// The t in [0, 1] where the chord `(1-t) l0 + t l1` is <= 0 (the rest is culled);
/// None when the chord is > 0 on all of [0, 1].
pub(crate) fn chord_nonpos(l0: f32, l1: f32) -> Option<[f32; 2]> {
    let cross = || {
        let t = l0 / (l0 - l1);
        if t.is_nan() {
            None
        } else {
            Some(t.clamp(0.0, 1.0))
        }
    };
    if l0 > 0.0 && l1 > 0.0 {
        None
    } else if l0 > 0.0 {
        Some([cross().unwrap_or(0.0), 1.0])
    } else if l1 > 0.0 {
        Some([0.0, cross().unwrap_or(1.0)])
    } else {
        Some([0.0, 1.0])
    }
}

/// Hull over t in [0, 1] of `{u real : d(t) + u s(t) < 0}`, for `d`, `s` affine in t
/// with end values `d[e]`, `s[e]` and sign class `class` of `s`; None when empty.
/// Bounds may be infinite.
fn neg_hull(d: [f32; 2], s: [f32; 2], class: Class) -> Option<[f32; 2]> {
    const FULL: [f32; 2] = [f32::NEG_INFINITY, f32::INFINITY];
    let theta = |e: usize| -d[e] / s[e];
    match class {
        Class::Pos => {
            let (a, b) = (theta(0), theta(1));
            if a.is_nan() || b.is_nan() {
                Some(FULL)
            } else {
                Some([f32::NEG_INFINITY, a.max(b)])
            }
        }
        Class::Neg => {
            let (a, b) = (theta(0), theta(1));
            if a.is_nan() || b.is_nan() {
                Some(FULL)
            } else {
                Some([a.min(b), f32::INFINITY])
            }
        }
        Class::Zero => {
            if d[0] < 0.0 || d[1] < 0.0 || d[0].is_nan() || d[1].is_nan() {
                Some(FULL)
            } else {
                None
            }
        }
        Class::Cross => Some(FULL),
    }
}

struct Prep {
    x: Axis,
    y: Axis,
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let Some((tx, u)) = self.x.bounds(tile.x0, tile.x1) else {
            return TileResult::Empty;
        };
        let Some((ty, v)) = self.y.bounds(tile.y0, tile.y1) else {
            return TileResult::Empty;
        };
        let t = [tx[0].max(ty[0]), tx[1].min(ty[1])];
        if t[0] > t[1] {
            return TileResult::Empty;
        }
        TileResult::Bounds(TileBounds { u, v, t, z: None, constraints: Vec::new() })
    }
}

struct La2011;

static INFO: MethodInfo = MethodInfo {
    id: "la2011",
    source: "reconstruction of Laine, Aila, Karras, Lehtinen 2011, Clipless Dual-Space \
             Bounds (LAKL11), as described in Munkberg & Akenine-Möller 2012 §1, Fig. 1, \
             Table 3 and Wu 2013 ch. 2; formulas per docs/reconstructions.md \
             (dual-space delta = x + u c - X w, chord time bounds, per-vertex lens thresholds)",
    reconstruction: true,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: false },
};

impl Method for La2011 {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k) })
    }
}

pub static METHOD: &dyn Method = &La2011;

/// The case of Munkberg & Akenine-Möller 2012, Figure 1: a small out-of-focus triangle
/// moving across the screen, and a tile around x = 0. Shared with the other methods'
/// tests so that their (u, t) regions can be compared with LA's box.
#[cfg(test)]
pub(crate) mod figure1 {
    use super::*;

    /// A 2 x 2 px triangle (w = 1, so clip units are pixels) moving from x = -20 to
    /// x = +20 over the shutter, with a constant CoC of 8 px (out of focus), k = 1.
    pub fn triangle() -> Triangle {
        Triangle {
            q: [[-21.0, -1.0, 0.5, 1.0], [-19.0, -1.0, 0.5, 1.0], [-20.0, 1.0, 0.5, 1.0]],
            r: [[19.0, -1.0, 0.5, 1.0], [21.0, -1.0, 0.5, 1.0], [20.0, 1.0, 0.5, 1.0]],
            c0: [8.0; 3],
            c1: [8.0; 3],
            k: 1.0,
        }
    }
    /// The 1 x 1 px tile around x = 0 (and y = 0).
    pub fn tile() -> Tile {
        Tile { x0: -0.5, y0: -0.5, x1: 0.5, y1: 0.5 }
    }
    /// LA's u^ for it: the whole lens (every vertex crosses the tile at some lens
    /// position over the shutter: thresholds (X - x_i)/8 run from -2.69 to 2.69).
    pub const LA_U: [f32; 2] = [-1.0, 1.0];
    /// LA's t^: the min of x_i - X1 - 8 is -29.5 at t = 0 and 10.5 at t = 1, so
    /// t <= 29.5 / 40; the max of x_i - X0 + 8 is -10.5 and 29.5, so t >= 10.5 / 40.
    pub const LA_T: [f32; 2] = [0.2625, 0.7375];
    /// LA's v^: the triangle spans y in [-1, 1] and is sheared by 8 v, so it meets the
    /// rows [-0.5, 0.5] only for |v| <= 1.5 / 8.
    pub const LA_V: [f32; 2] = [-0.1875, 0.1875];
}

/// Hand-made hard cases shared by the tests of la2011, lb2011 and lc.
#[cfg(test)]
pub(crate) mod cases {
    use super::*;

    /// Triangles of every kind in the model: thin lens crossing the focal plane,
    /// vertices behind the lens (w <= 0, clipless), per-vertex CoC with a zero and a
    /// sign change, perspective motion.
    pub fn hard_triangles() -> Vec<Triangle> {
        let cam = crate::model::ThinLens {
            fx: 50.0,
            fy: 60.0,
            cx: 0.0,
            cy: 0.0,
            radius: 0.3,
            focus: 4.0,
            near: 0.1,
            far: 100.0,
        };
        let a = cam.triangle(
            [[-1.0, -1.0, 2.0], [1.0, -0.5, 6.0], [0.0, 1.0, 3.0]],
            [[-0.5, -1.0, 3.0], [1.5, 0.0, 5.0], [0.5, 1.5, 2.5]],
        );
        // One vertex behind the lens at t = 1, one passing through w = 0.
        let b = cam.triangle(
            [[-1.0, -1.0, 2.0], [1.0, -0.5, 1.0], [0.0, 1.0, 3.0]],
            [[-0.5, -1.0, 3.0], [1.5, 0.0, -1.0], [0.5, 1.5, 2.5]],
        );
        let c = Triangle {
            q: [[-10.0, -5.0, 0.5, 1.0], [10.0, -4.0, 0.5, 1.5], [0.0, 12.0, 0.5, 2.0]],
            r: [[-4.0, -6.0, 0.5, 1.2], [16.0, -2.0, 0.5, 1.0], [4.0, 10.0, 0.5, 3.0]],
            c0: [3.0, 0.0, -2.0],
            c1: [-1.0, 0.0, -4.0],
            k: 0.7,
        };
        // Crossing behind the lens in clip units directly, large motion and blur.
        let d = Triangle {
            q: [[-3.0, 0.0, 0.5, 1.0], [3.0, 1.0, 0.5, 0.5], [0.0, 4.0, 0.5, -0.5]],
            r: [[5.0, 2.0, 0.5, 2.0], [9.0, -1.0, 0.5, -1.0], [2.0, 6.0, 0.5, 1.0]],
            c0: [2.0, 1.0, 1.5],
            c1: [0.5, 3.0, -1.0],
            k: 1.0,
        };
        vec![a, b, c, d]
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{assert_degenerate_input_is_answered, assert_spot, bounds_of, random_dual_case};
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
        bounds_of(METHOD, tri, tile)
    }

    /// Random samples in the tile: no interior-covered sample may be rejected.
    /// Returns (covered, admitted) sample counts.
    fn spot_check(tri: &Triangle, tile: &Tile, n: usize, seed: u64) -> (usize, usize) {
        assert_spot(METHOD, tri, tile, n, seed)
    }

    #[test]
    fn static_triangle_keeps_whole_time_range() {
        let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0]]);
        let b = bounds(&tri, &Tile::square(10.0, 10.0, 4.0)).expect("inside tile culled");
        assert_eq!(b.t, [0.0, 1.0]);
        assert_eq!(b.u, [-1.0, 1.0]);
        assert_eq!(b.v, [-1.0, 1.0]);
    }

    #[test]
    fn far_tiles_are_culled() {
        let tri = figure1::triangle();
        // Right of everything the triangle reaches (x <= 21 + 8), left, above, below.
        for tile in [
            Tile::square(30.0, -0.5, 1.0),
            Tile::square(-31.0, -0.5, 1.0),
            Tile::square(0.0, 10.0, 1.0),
            Tile::square(0.0, -11.0, 1.0),
        ] {
            assert!(bounds(&tri, &tile).is_none(), "{tile:?}");
        }
        // In-focus static triangle, tile beside it.
        let st = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 0.5, 1.0], [0.0, 10.0, 0.5, 1.0]]);
        assert!(bounds(&st, &Tile::square(11.0, 0.0, 1.0)).is_none());
        assert!(bounds(&st, &Tile::square(9.0, 0.0, 1.0)).is_some());
    }

    #[test]
    fn figure1_la_box_is_coarse() {
        let tri = figure1::triangle();
        let tile = figure1::tile();
        let b = bounds(&tri, &tile).unwrap();
        let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
        assert!(close(b.u, figure1::LA_U), "u {:?}", b.u);
        assert!(close(b.t, figure1::LA_T), "t {:?}", b.t);
        assert!(close(b.v, figure1::LA_V), "v {:?}", b.v);
        // Only a diagonal strip of the (u, t) box is covered: samples with v = 0 and the
        // tile centre hit the triangle iff |-20 + 40 t + 8 u| < ~1, a strip of width
        // ~2/40 in t, while the box is 0.475 wide.
        let o = tri.to_oracle();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let (mut inbox, mut hit) = (0, 0);
        for _ in 0..20000 {
            let s = Sample::new(0.0, 0.0, rng.gen_range(-1.0..=1.0), 0.0, rng.gen_range(0.0..=1.0));
            if b.admits(&s) {
                inbox += 1;
                hit += (oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior) as usize;
            }
        }
        let frac = hit as f64 / inbox as f64;
        assert!(frac > 0.05 && frac < 0.2, "covered fraction of the LA box {frac}");
        let (covered, _) = spot_check(&tri, &tile, 20000, 8);
        assert!(covered > 20);
    }

    #[test]
    fn perspective_motion_time_bound_is_conservative_and_cuts() {
        // Approaching the camera (w 10 -> 1): screen motion accelerates; linear in clip
        // space. Tile near the end position.
        let tri = Triangle {
            q: [[0.0, 0.0, 0.5, 10.0], [20.0, 0.0, 0.5, 10.0], [0.0, 20.0, 0.5, 10.0]],
            r: [[30.0, 0.0, 0.5, 1.0], [32.0, 0.0, 0.5, 1.0], [30.0, 2.0, 0.5, 1.0]],
            c0: [0.5; 3],
            c1: [-0.5; 3],
            k: 1.0,
        };
        // Screen x of vertex 0 is 30 t / (10 - 9 t): it reaches the tile at t ~ 0.8.
        let tile = Tile::square(9.0, 0.0, 2.0);
        let b = bounds(&tri, &tile).unwrap();
        eprintln!("perspective: {b:?}");
        assert!(b.t[0] > 0.5 && b.t[1] < 1.0, "t {:?}", b.t);
        let (covered, _) = spot_check(&tri, &tile, 20000, 3);
        assert!(covered > 50);
    }

    #[test]
    fn no_covered_sample_is_culled() {
        let mut seed = 100;
        let mut total = 0;
        let mut tris = cases::hard_triangles();
        tris.push(figure1::triangle());
        for tri in &tris {
            for tx in -6..6 {
                for ty in -6..6 {
                    let tile = Tile::square(tx as f32 * 5.0, ty as f32 * 5.0, 5.0);
                    total += spot_check(tri, &tile, 300, seed).0;
                    seed += 1;
                }
            }
        }
        assert!(total > 2000, "too few covered samples: {total}");
    }

    #[test]
    fn random_triangles_are_never_culled_where_covered() {
        // Random moving, defocused triangles (some with w <= 0, some with per-vertex
        // CoC); tiles centred on a projected vertex so that coverage happens.
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let (mut total, mut admitted) = (0, 0);
        for n in 0..300 {
            let (tri, tile) = random_dual_case(&mut rng, n);
            let (c, a) = spot_check(&tri, &tile, 2000, 1000 + n as u64);
            total += c;
            admitted += a;
        }
        eprintln!("random: covered {total}, admitted {admitted} of {}", 300 * 2000);
        assert!(total > 10000, "too few covered samples: {total}");
        assert!(admitted < 300 * 2000 * 9 / 10, "the bounds hardly cut: {admitted}");
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        assert_degenerate_input_is_answered(METHOD, &figure1::triangle());
    }
}
