//! The tile answer `lb2011-safe` computed before it was written over `F32Arith` (f32
//! code with early returns and a table of functions for its two arithmetics), verbatim
//! but for its method glue and the constraint's trait methods: the reference
//! `tests/encoded.rs` compares the method's answers with, tile for tile.

use cullproof::bounds::{SampleBox, SampleConstraint, TileBounds, TileResult};
use cullproof::{Interval, Sample, Tile, Triangle};

/// `[min, max]` corner values of one axis, each indexed `[lens index][shutter end]`.
type Corners = [[[f32; 2]; 2]; 2];

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y.
    s: [[f32; 3]; 2],
    /// True when `s` is exact (`1 c` for x); else `fl(k c)`, one rounding off `k c`.
    s_exact: bool,
}

impl Axis {
    fn new(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        Axis {
            p: [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])],
            w: [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])],
            s: [tri.c0.map(|c| scale * c), tri.c1.map(|c| scale * c)],
            s_exact: scale == 1.0,
        }
    }

    /// The corner values of `lb2011` rounded
    /// outward (f32 interval arithmetic, one `next_up` / `next_down` step after every
    /// rounded operation): `[lower bounds of the min, upper bounds of the max]` of the
    /// exact `p - X w + l k c`. None if any is NaN or infinite.
    fn corners_safe(&self, lo: f32, hi: f32) -> Option<Corners> {
        let mut mn = [[f32::INFINITY; 2]; 2];
        let mut mx = [[f32::NEG_INFINITY; 2]; 2];
        for e in 0..2 {
            for i in 0..3 {
                let s = self.s[e][i];
                let (s_lo, s_hi) = if self.s_exact { (s, s) } else { (s.next_down(), s.next_up()) };
                for x in [lo, hi] {
                    // p - X w with one rounding (fused multiply-add), enclosed by a step.
                    let a = (-x).mul_add(self.w[e][i], self.p[e][i]);
                    let (a_lo, a_hi) = (a.next_down(), a.next_up());
                    let lows = [(a_lo - s_hi).next_down(), (a_lo + s_lo).next_down()];
                    let highs = [(a_hi - s_lo).next_up(), (a_hi + s_hi).next_up()];
                    for li in 0..2 {
                        if !(lows[li].is_finite() && highs[li].is_finite()) {
                            return None;
                        }
                        mn[li][e] = mn[li][e].min(lows[li]);
                        mx[li][e] = mx[li][e].max(highs[li]);
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
    #[allow(dead_code)] // (compared through Debug)
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
}

impl SampleConstraint for Patch {
    fn name(&self) -> String {
        self.name.to_string()
    }
    fn eval(&self, _: &Sample) -> f32 {
        f32::NAN
    }
    fn eval_box(&self, _: &SampleBox) -> Interval {
        Interval::new(f64::NEG_INFINITY, f64::INFINITY)
    }
}

/// `lb2011-safe`: the part of [0, 1] where `(1-t) a + t b >= 0`, rounded outward (a, b
/// finite). The crossing `t* = a / (a - b)` is a quotient of two positive numbers when
/// the chord changes sign; its lower bound divides by an upper bound of the denominator
/// and steps down, its upper bound divides by a lower bound and steps up.
fn chord_nonneg_safe(a: f32, b: f32) -> Option<[f32; 2]> {
    if a < 0.0 && b < 0.0 {
        None
    } else if a < 0.0 {
        // Rising through 0: kept [t*, 1], t* = (-a) / ((-a) + b), -a > 0, b >= 0. The
        // denominator rounds to >= -a > 0; an overflow to inf gives 0 (still below t*).
        let t = (-a / (b - a).next_up()).next_down();
        Some([t.max(0.0), 1.0])
    } else if b < 0.0 {
        // Falling through 0: kept [0, t*], t* = a / (a + (-b)), a >= 0, -b > 0. The
        // lower bound of the denominator can be 0 (a = 0, b = -2^-149): the quotient is
        // then NaN or inf, and the range the whole [0, 1].
        let t = (a / (a - b).next_down()).next_up();
        Some([0.0, if (0.0..1.0).contains(&t) { t } else { 1.0 }])
    } else {
        Some([0.0, 1.0])
    }
}

/// `lb2011-safe`: `l = 2 sigma - 1` rounded outward (`2 sigma` is exact, the difference
/// is rounded once: one step encloses it).
fn lens_safe(sigma: [f32; 2]) -> [f32; 2] {
    [(2.0 * sigma[0] - 1.0).next_down().max(-1.0), (2.0 * sigma[1] - 1.0).next_up().min(1.0)]
}

/// `lb2011-safe`: the patch with its constant coefficient raised by
/// `pad = 2^-18 mg + 2^-140` (mg the largest |corner value|), so that its f32 `eval`
/// is >= the exact bilinear interpolant of the corner values for |l| <= 1, t in
/// [0, 1] (module doc, "Per-sample evaluation"). None when no corner is < 0 (it cannot
/// cull) or mg >= 2^120 (the analysis assumes no overflow; dropping a patch is always
/// conservative).
fn patch_safe(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Option<Patch> {
    const PAD: f32 = 1.0 / (1u32 << 18) as f32; // 2^-18 = 64 u
    const FLOOR: f32 = 1.0 / (1u128 << 120) as f32 / (1u32 << 20) as f32; // 2^-140
    const LIMIT: f32 = (1u128 << 120) as f32; // 2^120
    if !g.iter().flatten().any(|&v| v < 0.0) {
        return None;
    }
    let mg = g.iter().flatten().fold(0.0f32, |m, v| m.max(v.abs()));
    // (A NaN cannot reach here: corners are finite.)
    if mg >= LIMIT || mg.is_nan() {
        return None;
    }
    let mut patch = Patch::from_corners(name, lens, g);
    patch.p = (patch.p + (mg * PAD + FLOOR)).next_up();
    patch.usable().then_some(patch)
}

/// Ranges implied by one patch (g values at the corners, `g[l][e]`): the t where some
/// l has g >= 0 and the l where some t has g >= 0, or None if g < 0 on the whole square.
fn patch_ranges(g: [[f32; 2]; 2]) -> Option<([f32; 2], [f32; 2])> {
    let hull = |a: Option<[f32; 2]>, b: Option<[f32; 2]>| match (a, b) {
        (Some(a), Some(b)) => Some([a[0].min(b[0]), a[1].max(b[1])]),
        (a, b) => a.or(b),
    };
    let t = hull(chord_nonneg_safe(g[0][0], g[0][1]), chord_nonneg_safe(g[1][0], g[1][1]))?;
    let sigma = hull(chord_nonneg_safe(g[0][0], g[1][0]), chord_nonneg_safe(g[0][1], g[1][1]))?;
    Some((t, lens_safe(sigma)))
}

struct Prep {
    x: Axis,
    y: Axis,
}

/// The old answer of `lb2011-safe` for a tile.
pub fn answer(tri: &Triangle, tile: &Tile) -> TileResult {
    let p = Prep { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k) };
    p.tile(tile)
}

impl Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut out = TileBounds::full();
        let axes = [
            (&self.x, tile.x0, tile.x1, Lens::U, ["x1 patch (min delta, u-t)", "x0 patch (max delta, u-t)"]),
            (&self.y, tile.y0, tile.y1, Lens::V, ["y1 patch (min eps, v-t)", "y0 patch (max eps, v-t)"]),
        ];
        for (ax, lo, hi, lens, names) in axes {
            let Some([mn, mx]) = ax.corners_safe(lo, hi) else {
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
                if let Some(patch) = patch_safe(name, lens, g) {
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
