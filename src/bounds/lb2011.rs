//! `lb2011` (**reconstruction**): dual-space bounds with u-t and v-t correlation, as
//! four bilinear patches evaluated per sample, after Laine & Karras 2011, "Improved
//! Dual-Space Bounds for Simultaneous Motion and Defocus Blur", NVIDIA Technical
//! Report NVR-2011-004 (LK11). The report is not available to this project; this file
//! follows `docs/reconstructions.md` (§2 "The dual-space quantity", §4 "lb2011", LB's
//! per-sample patches), built on Munkberg & Akenine-Möller 2012: §1 (LK11 extends the
//! dual-space motion blur test "to a trilinear equation that takes correlations
//! between u&t and v&t into account", with "four bilinear patches ... evaluated for
//! each sample"), §2.1 under Eq. 1 (moving the denominator of `u_ij(t)` to the left
//! gives LK11's trilinear equation) and Table 3 (LB costs 400 per triangle, 16 per
//! tile, 12 per sample). Every formula below is derived again here.
//!
//! # The trilinear quantity
//! `delta_i(X, u, t) = x_i(t) + u c_i(t) - X w_i(t)` (`P_i.x` of `docs/model.md` for the
//! column X; affine in X, u, t separately) and in y `eps_i(Y, v, t) = y_i(t) + k v c_i(t) -
//! Y w_i(t)`. Munkberg's Eq. 1 threshold `u_ij(t) = n_i^x . p_j(t) / c_j(t)` is the root
//! in u of `delta_j(x_i, u, t) = 0` (their `n^x . p = x_i w - x = -delta` at u = 0).
//!
//! # Lemma (as in `la2011`; no assumption on the sign of w)
//! `sum_k E_k P_k = (0, 0, D)` (adjugate identity), so an interior-covered sample has
//! `min_k delta_k(x, u, t) < 0 < max_k delta_k(x, u, t)`; since `delta_k` is affine in
//! x, for x in the tile's [X0, X1]:
//! `m(u, t) := min over k, X in {X0, X1} of delta_k(X, u, t) < 0` and
//! `M(u, t) := max over the same 6 values > 0`. With every w > 0, `m = min_k
//! delta_k(X1, u, t)` and `M = max_k delta_k(X0, u, t)` (the reconstruction's tile sides;
//! bit-identical in f32 too, as `fl` is monotone); taking both columns keeps the test
//! valid for vertices behind the lens without clipping. Sign convention: the X1
//! patch culls where the min is > 0 (the triangle lies right of the tile); the X0
//! patch culls where the max is < 0 (left of it).
//!
//! # The patches
//! Per tile and axis, evaluate m at the four (u, t) corners u = ±1, t = 0, 1 (12
//! values each: 3 vertices x 2 columns) and let `B(u, t)` be their bilinear
//! interpolant. **Claim: B <= m on [-1, 1] x [0, 1].** Proof 1: each
//! `f_k = delta_k(X, ., .)` is bilinear in (u, t), so it equals its own bilinear
//! interpolant; bilinear interpolation is a positive linear operator (weights
//! `(1-a)(1-t), a(1-t), (1-a)t, a t >= 0`, `a = (u+1)/2`), so corners `m <= f_k` give
//! `B <= f_k` everywhere, for each k, hence `B <= min_k f_k = m`. Proof 2 (the
//! reconstruction's argument, which holds for *any* function concave along every
//! axis-parallel line, and m is one: along a line it is a min of affine functions):
//! on the edges t = 0 and t = 1, B is the chord of m in u, so `B(u, e) <= m(u, e)`;
//! for fixed u, B is the chord in t between `B(u, 0) <= m(u, 0)` and `B(u, 1) <=
//! m(u, 1)`, so `B(u, t) <= (1-t) m(u, 0) + t m(u, 1) <= m(u, t)` by concavity in t.
//! So the claim is true (no counterexample exists) and no deviation is needed.
//! A sample is culled when `B(u_s, t_s) > 0`; symmetrically the max patch `B'`
//! (interpolating M) is >= M and culls when `B'(u_s, t_s) < 0`. As `SampleConstraint`s
//! (culled when g < 0): `g = -B` (min patch) and `g = B'` (max patch), for x in u-t
//! and for y in v-t (with `k c`): four patches, as in munkberg2012.
//!
//! Each patch is stored as `g(l, t) = P + Q l + t (R + S l)` (l = u or v), with
//! `P = (g(-1,0) + g(1,0))/2`, `Q = (g(1,0) - g(-1,0))/2`, `R = (g(-1,1) + g(1,1))/2 - P`,
//! `S = (g(1,1) - g(-1,1))/2 - Q`, and evaluated per sample in f32 as
//! `fl(fl(P + fl(Q l)) + fl(t fl(R + fl(S l))))` (separate multiplies and adds, no
//! FMA): 3 multiply-adds per patch, 12 for the four, which matches the 12 per-sample
//! operations munkberg2012 Table 3 gives LB if a multiply-add counts as one.
//!
//! # Tile-level consequences (our addition: "what the patches imply")
//! A bilinear function on a box takes its extremes at the corners, and is affine along
//! each axis. So: the tile is **Empty** when a patch is < 0 (g) at all four corners
//! (then it culls the whole (l, t) square; for the min patches this is exactly LA's
//! clipless column test); `t^` keeps the t where `g(-1, t) >= 0` or `g(1, t) >= 0`
//! (hull of two chord ranges); `u^` (`v^`) keeps the l where `g(l, 0) >= 0` or
//! `g(l, 1) >= 0`. These cut nothing the patches would not cut, they only let the
//! tile pipeline skip samples early. A patch that is >= 0 at all four corners cannot
//! cull and is not emitted. The t range is at least as tight as LA's chord bound
//! (`min` of the two lines `g(±1, t)` is above the chord of the minima).
//!
//! # Choices the reconstruction leaves open
//! - Which samples' x is used: the patches are per tile (the sample's own x is not
//!   used; LK11's trilinear form could interpolate in x too).
//! - The tile ranges above and dropping patches that cannot cull.
//! - Both columns per patch (clipless; identical to the one-column form when w > 0).
//!
//! # f32 and the box enclosure
//! Corner values are `fl(fl(x - fl(X w)) ± s)` (`s = c` or `fl(k c)`): a few ulps of
//! `|x| + |X w| + |s|` off the real ones; the coefficients add one rounding each and
//! `eval` four more along its longest path. So B can exceed the real min by a few ulps
//! of the magnitudes involved, and a sample whose real `min_k delta_k` is within those
//! ulps of 0 can be culled: that is where f32 rounding can make the test
//! non-conservative; no epsilon is added. `eval_box` evaluates `P + Q l + t (R + S l)`
//! in outward-rounded f64 intervals over the box (P..S are the stored f32 values, exact
//! in f64) and widens by `2^-20 * (|P| + |Q| L + max(1, T) (|R| + |S| L)) + 2^-126 (1 +
//! L)(1 + T)` (L, T the largest |l|, |t| in the box): the f32 evaluation has at most 4
//! roundings on any path, relative error `<= 4 * 2^-24 < 2^-20` of that magnitude sum,
//! plus at most `2^-149` absolute per operation for subnormal results, scaled by at
//! most `(1 + L)(1 + T)`. When that magnitude reaches `2^126` an f32 intermediate may
//! overflow and the enclosure is the whole real line. A NaN corner value (degenerate
//! input) drops that axis's patches and ranges; a patch whose coefficients are not
//! finite or sum in magnitude to `2^125` or more is dropped (its f32 `eval` could
//! overflow to NaN, which would cull).

use super::la2011::chord_nonpos;
use super::*;

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y.
    s: [[f32; 3]; 2],
}

impl Axis {
    fn new(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        Axis {
            p: [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])],
            w: [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])],
            s: [tri.c0.map(|c| scale * c), tri.c1.map(|c| scale * c)],
        }
    }

    /// Corner values `[min, max]`, each indexed `[lens index (0: -1, 1: +1)][end]`, of
    /// `d + l s` over the 3 vertices and both columns; None if any is NaN.
    fn corners(&self, lo: f32, hi: f32) -> Option<[[[f32; 2]; 2]; 2]> {
        let mut mn = [[f32::INFINITY; 2]; 2];
        let mut mx = [[f32::NEG_INFINITY; 2]; 2];
        for e in 0..2 {
            for i in 0..3 {
                for x in [lo, hi] {
                    let d = self.p[e][i] - x * self.w[e][i];
                    for (li, val) in [(0, d - self.s[e][i]), (1, d + self.s[e][i])] {
                        if val.is_nan() {
                            return None;
                        }
                        mn[li][e] = mn[li][e].min(val);
                        mx[li][e] = mx[li][e].max(val);
                    }
                }
            }
        }
        Some([mn, mx])
    }
}

/// Which lens coordinate a patch reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Lens {
    U,
    V,
}

/// One bilinear patch as a per-sample constraint: `g(l, t) = P + Q l + t (R + S l)`,
/// the sample is culled when g < 0.
#[derive(Clone, Copy, Debug)]
pub struct Patch {
    name: &'static str,
    lens: Lens,
    p: f32,
    q: f32,
    r: f32,
    s: f32,
}

impl Patch {
    /// From the g values at (l, t) = (-1, 0), (1, 0), (-1, 1), (1, 1).
    fn from_corners(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Patch {
        let (g00, g10, g01, g11) = (g[0][0], g[1][0], g[0][1], g[1][1]);
        let p = (g00 + g10) * 0.5;
        let q = (g10 - g00) * 0.5;
        let r = (g01 + g11) * 0.5 - p;
        let s = (g11 - g01) * 0.5 - q;
        Patch { name, lens, p, q, r, s }
    }
    /// True when every coefficient is finite and `|P| + |Q| + |R| + |S| < 2^125`, so
    /// that no f32 intermediate of `eval` can overflow for |l| <= 1, 0 <= t <= 1.
    fn usable(&self) -> bool {
        let m = [self.p, self.q, self.r, self.s].iter().map(|c| c.abs() as f64).sum::<f64>();
        m < 2f64.powi(125)
    }
    fn lens_of(&self, smp: &Sample) -> f32 {
        match self.lens {
            Lens::U => smp.u,
            Lens::V => smp.v,
        }
    }
}

impl SampleConstraint for Patch {
    fn name(&self) -> String {
        self.name.to_string()
    }
    fn eval(&self, smp: &Sample) -> f32 {
        let l = self.lens_of(smp);
        let t = smp.t;
        (self.p + self.q * l) + t * (self.r + self.s * l)
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let l = match self.lens {
            Lens::U => b.u,
            Lens::V => b.v,
        };
        let t = b.t;
        let pt = |x: f32| Interval::point(x as f64);
        let val = (pt(self.p) + pt(self.q) * l) + t * (pt(self.r) + pt(self.s) * l);
        let lm = l.lo.abs().max(l.hi.abs());
        let tm = t.lo.abs().max(t.hi.abs());
        let a = |x: f32| (x as f64).abs();
        let mag = a(self.p) + a(self.q) * lm + tm.max(1.0) * (a(self.r) + a(self.s) * lm);
        let err = mag * 2f64.powi(-20) + 2f64.powi(-126) * (1.0 + lm) * (1.0 + tm);
        if mag.is_nan() || mag >= 2f64.powi(126) || val.lo.is_nan() || val.hi.is_nan() || !err.is_finite() {
            return Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        }
        val + Interval::new(-err, err)
    }
}

/// Ranges implied by one patch (g values at the corners, `g[l][e]`): the t where some
/// l has g >= 0 and the l where some t has g >= 0, or None if g < 0 on the whole square.
fn patch_ranges(g: [[f32; 2]; 2]) -> Option<([f32; 2], [f32; 2])> {
    let hull = |a: Option<[f32; 2]>, b: Option<[f32; 2]>| match (a, b) {
        (Some(a), Some(b)) => Some([a[0].min(b[0]), a[1].max(b[1])]),
        (a, b) => a.or(b),
    };
    // g >= 0  <=>  -g <= 0: chord_nonpos keeps where its argument line is <= 0.
    let t = hull(chord_nonpos(-g[0][0], -g[0][1]), chord_nonpos(-g[1][0], -g[1][1]))?;
    let sigma = hull(chord_nonpos(-g[0][0], -g[1][0]), chord_nonpos(-g[0][1], -g[1][1]))?;
    let l = [(2.0 * sigma[0] - 1.0).max(-1.0), (2.0 * sigma[1] - 1.0).min(1.0)];
    Some((t, l))
}

struct Prep {
    x: Axis,
    y: Axis,
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut out = TileBounds::full();
        let axes = [
            (&self.x, tile.x0, tile.x1, Lens::U, ["x1 patch (min delta, u-t)", "x0 patch (max delta, u-t)"]),
            (&self.y, tile.y0, tile.y1, Lens::V, ["y1 patch (min eps, v-t)", "y0 patch (max eps, v-t)"]),
        ];
        for (ax, lo, hi, lens, names) in axes {
            let Some([mn, mx]) = ax.corners(lo, hi) else {
                continue;
            };
            // g = -min (culls where the min patch is > 0), g = max (culls where < 0).
            let gs = [mn.map(|r| r.map(|v| -v)), mx];
            for (g, name) in gs.into_iter().zip(names) {
                let Some((t, l)) = patch_ranges(g) else {
                    return TileResult::Empty;
                };
                out.t = [out.t[0].max(t[0]), out.t[1].min(t[1])];
                let lr = if lens == Lens::U { &mut out.u } else { &mut out.v };
                *lr = [lr[0].max(l[0]), lr[1].min(l[1])];
                let can_cull = g.iter().flatten().any(|&v| v < 0.0);
                let patch = Patch::from_corners(name, lens, g);
                // A non-finite coefficient, or one so large that `eval` could overflow to
                // inf - inf = NaN (which culls), drops the patch.
                if can_cull && patch.usable() {
                    out.constraints.push(Box::new(patch));
                }
            }
        }
        if out.t[0] > out.t[1] || out.u[0] > out.u[1] || out.v[0] > out.v[1] {
            return TileResult::Empty;
        }
        TileResult::Bounds(out)
    }
}

struct Lb2011;

static INFO: MethodInfo = MethodInfo {
    id: "lb2011",
    source: "reconstruction of Laine & Karras 2011, NVR-2011-004 (LK11), as described in \
             Munkberg & Akenine-Möller 2012 §1, §2.1 (under Eq. 1) and Table 3; per \
             docs/reconstructions.md: four bilinear patches in u-t / v-t of the \
             min / max of delta = x + u c - X w over a tile's columns, evaluated per sample",
    reconstruction: true,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
};

impl Method for Lb2011 {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k) })
    }
}

pub static METHOD: &dyn Method = &Lb2011;

#[cfg(test)]
mod tests {
    use super::super::la2011::{cases, figure1};
    use super::super::testkit::{
        assert_degenerate_input_is_answered, assert_spot, bounds_of, random_dual_case, random_sample,
    };
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
        let tile = Tile::square(10.0, 10.0, 4.0);
        let b = bounds(&tri, &tile).expect("inside tile culled");
        assert_eq!(b.t, [0.0, 1.0]);
        // No patch can cull: the tile columns lie strictly between the vertices.
        assert!(b.constraints.is_empty(), "{:?}", b.constraints);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..1000 {
            assert!(b.admits(&random_sample(&mut rng, &tile)));
        }
    }

    #[test]
    fn far_tiles_are_culled() {
        let tri = figure1::triangle();
        for tile in [
            Tile::square(30.0, -0.5, 1.0),
            Tile::square(-31.0, -0.5, 1.0),
            Tile::square(0.0, 10.0, 1.0),
            Tile::square(0.0, -11.0, 1.0),
        ] {
            assert!(bounds(&tri, &tile).is_none(), "{tile:?}");
        }
    }

    #[test]
    fn figure1_patches_keep_only_the_strip() {
        let tri = figure1::triangle();
        let tile = figure1::tile();
        let b = bounds(&tri, &tile).unwrap();
        // With w = 1 and a constant CoC the min over vertices and columns is one plane:
        // vertex 0 at X1: B(u, t) = -21 + 40 t - 0.5 + 8 u exactly; the max is vertex 1
        // at X0: -19 + 40 t + 0.5 + 8 u. The kept (u, t) set is the diagonal strip
        // 18.5 <= 40 t + 8 u <= 21.5 (width 0.075 in t) inside LA's box.
        let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
        assert!(close(b.t, figure1::LA_T), "t {:?}", b.t);
        assert!(close(b.u, figure1::LA_U), "u {:?}", b.u);
        assert!(close(b.v, figure1::LA_V), "v {:?}", b.v);
        for (u, t, keep) in [
            (0.0f32, 0.5f32, true),
            (1.0, 0.3, true),
            (-1.0, 0.7, true),
            (0.0, 0.45, false),
            (0.0, 0.56, false),
            (1.0, 0.7, false),
            (-1.0, 0.3, false),
        ] {
            let s = Sample::new(0.0, 0.0, u, 0.0, t);
            assert_eq!(b.admits(&s), keep, "u {u} t {t}");
        }
        // Fraction of LA's box that LB keeps, and how much of it is covered.
        let o = tri.to_oracle();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let (mut in_la, mut in_lb, mut hit) = (0, 0, 0);
        for _ in 0..40000 {
            let s = Sample::new(0.0, 0.0, rng.gen_range(-1.0..=1.0), 0.0, rng.gen_range(0.0..=1.0));
            let la = figure1::LA_T[0] <= s.t && s.t <= figure1::LA_T[1];
            in_la += la as usize;
            if b.admits(&s) {
                assert!(la);
                in_lb += 1;
                hit += (oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior) as usize;
            }
        }
        let kept = in_lb as f64 / in_la as f64;
        assert!((kept - 0.075 / 0.475).abs() < 0.02, "LB keeps {kept} of LA's box");
        // At the pixel (0, 0) the triangle's row y = 0 spans [a - 0.5, a + 0.5] with
        // a = -20 + 40 t + 8 u: covered for 19.5 < 40 t + 8 u < 20.5, a third of the strip.
        let frac = hit as f64 / in_lb as f64;
        assert!((frac - 1.0 / 3.0).abs() < 0.03, "covered fraction of LB's strip {frac}");
        assert!(spot_check(&tri, &tile, 20000, 8).0 > 20);
    }

    #[test]
    fn patch_is_below_the_min_and_box_encloses_eval() {
        // The bilinear patch never exceeds the real min over vertices and columns (up to
        // f32 rounding), for every kind of triangle; eval lies in eval_box.
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut checked = 0;
        for tri in cases::hard_triangles() {
            for n in 0..150 {
                let tile = Tile::square(rng.gen_range(-15.0..15.0), rng.gen_range(-15.0..15.0), [1.0f32, 4.0][n % 2]);
                let Some(b) = bounds(&tri, &tile) else {
                    continue;
                };
                for c in &b.constraints {
                    checked += 1;
                    for _ in 0..200 {
                        let s = random_sample(&mut rng, &tile);
                        let (u, v, t) = (s.u as f64, s.v as f64, s.t as f64);
                        let o = tri.to_oracle();
                        let name = c.name();
                        let (axis, l, cols, scale) = if name.starts_with('x') {
                            (0, u, [tile.x0, tile.x1], 1.0)
                        } else {
                            (1, v, [tile.y0, tile.y1], o.k)
                        };
                        let mut mn = f64::INFINITY;
                        let mut mx = f64::NEG_INFINITY;
                        let mut mag = 0.0f64;
                        for i in 0..3 {
                            let lerp = |a: f64, b: f64| (1.0 - t) * a + t * b;
                            let p = lerp(o.q[i][axis], o.r[i][axis]);
                            let w = lerp(o.q[i][3], o.r[i][3]);
                            let cc = lerp(o.c0[i], o.c1[i]) * scale;
                            for x in cols {
                                let d = p + l * cc - x as f64 * w;
                                mn = mn.min(d);
                                mx = mx.max(d);
                                mag = mag.max(p.abs() + cc.abs() + (x as f64 * w).abs());
                            }
                        }
                        let g = c.eval(&s) as f64;
                        let tol = mag * 1e-5 + 1e-30;
                        if name.contains("min") {
                            assert!(-g <= mn + tol, "{name}: patch {} above min {mn}", -g);
                        } else {
                            assert!(g >= mx - tol, "{name}: patch {g} below max {mx}");
                        }
                        let pt = |x: f32| Interval::point(x as f64);
                        let bx = SampleBox { x: pt(s.x), y: pt(s.y), u: pt(s.u), v: pt(s.v), t: pt(s.t) };
                        assert!(c.eval_box(&bx).contains(g), "{name}: {g} not in {:?}", c.eval_box(&bx));
                        // A box around the sample.
                        let wide = |x: f32, lo: f64, hi: f64| {
                            Interval::new((x as f64 - 0.1).max(lo), (x as f64 + 0.1).min(hi))
                        };
                        let bx = SampleBox {
                            u: wide(s.u, -1.0, 1.0),
                            v: wide(s.v, -1.0, 1.0),
                            t: wide(s.t, 0.0, 1.0),
                            ..bx
                        };
                        let e = c.eval_box(&bx);
                        for _ in 0..5 {
                            let s2 = Sample::new(
                                s.x,
                                s.y,
                                rng.gen_range(bx.u.lo..=bx.u.hi) as f32,
                                rng.gen_range(bx.v.lo..=bx.v.hi) as f32,
                                rng.gen_range(bx.t.lo..=bx.t.hi) as f32,
                            );
                            let g2 = c.eval(&s2) as f64;
                            assert!(e.contains(g2), "{name}: {g2} not in {e:?}");
                        }
                    }
                }
            }
        }
        assert!(checked > 200, "only {checked} patches checked");
    }

    #[test]
    fn eval_box_covers_rounding_and_overflow() {
        let p = Patch { name: "t", lens: Lens::U, p: 1.0e30, q: -1.0e30, r: 3.0, s: 1.0e-30 };
        let b = SampleBox {
            x: Interval::point(0.0),
            y: Interval::point(0.0),
            u: Interval::point(1.0),
            v: Interval::point(0.0),
            t: Interval::point(0.5),
        };
        let e = p.eval_box(&b);
        assert!(e.contains(p.eval(&Sample::new(0.0, 0.0, 1.0, 0.0, 0.5)) as f64));
        let big = Patch { p: 3.0e38, q: 3.0e38, ..p };
        let e = big.eval_box(&b);
        assert!(e.lo == f64::NEG_INFINITY && e.hi == f64::INFINITY);
    }

    #[test]
    fn no_covered_sample_is_culled() {
        let mut seed = 100;
        let (mut total, mut admitted, mut n) = (0, 0, 0);
        let mut tris = cases::hard_triangles();
        tris.push(figure1::triangle());
        for tri in &tris {
            for tx in -6..6 {
                for ty in -6..6 {
                    let tile = Tile::square(tx as f32 * 5.0, ty as f32 * 5.0, 5.0);
                    let (c, a) = spot_check(tri, &tile, 300, seed);
                    total += c;
                    admitted += a;
                    n += 300;
                    seed += 1;
                }
            }
        }
        assert!(total > 2000, "too few covered samples: {total}");
        assert!(admitted < n / 2, "the test hardly culls: {admitted} of {n}");
    }

    #[test]
    fn random_triangles_are_never_culled_where_covered() {
        let mut rng = ChaCha8Rng::seed_from_u64(43);
        let mut total = 0;
        for n in 0..300 {
            let (tri, tile) = random_dual_case(&mut rng, n);
            total += spot_check(&tri, &tile, 2000, 2000 + n as u64).0;
        }
        assert!(total > 10000, "too few covered samples: {total}");
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        assert_degenerate_input_is_answered(METHOD, &figure1::triangle());
    }
}
