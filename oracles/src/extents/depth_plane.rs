//! Depth ends decided by a moving plane through the vertices, over the whole tile.
//!
//! Write the vertices at the sample's (u, v, t), translated so that its pixel is the
//! origin, as `(T_k, S_k, z_k, w_k)` with `T_k = x_k(t) + u c_k(t) - x w_k(t)` and `S_k =
//! y_k(t) + k v c_k(t) - y w_k(t)`. The hit depth minus a bound z is
//! `sum_k (E_k / D) (z_k - z w_k)` (the depth numerator is `sum_k E_k z_k` and, by the
//! adjugate identity, `D = sum_k E_k w_k`), and the same identity gives `sum_k E_k T_k =
//! 0` and `sum_k E_k S_k = 0`. So for any numbers `alpha`, `gamma` (they may even vary with
//! the sample)
//!
//! `depth - z = sum_k (E_k / D) F_k`,  `F_k = z_k - z w_k + alpha T_k + gamma S_k`,
//!
//! and at an interior sample every weight `E_k / D` is positive. If every `F_k >= 0`
//! there (`<= 0` for an upper end), the depth is `>= z` (`<= z`). With `alpha`, `gamma`
//! the negated x and y slopes of the plane through the three vertices
//! (`z_k = A x'_k + B y'_k + C w_k`), `F_k = w_k (A X + B Y + C - z)`: `w_k` times how far
//! the plane's depth at the pixel lies beyond z, which is what a tile-local depth bound
//! rests on.
//!
//! Over a box of (u, v, t) with the pixels of the whole tile, `alpha` and `gamma` are taken
//! affine in t (the planes at the box's two times, at its middle lens position); `F_k`
//! is then affine in each of x, y, u, v and of degree 2 in t, so its range over the box
//! is that of its 16 corner polynomials in t, bounded with rigorous rounding errors
//! ([`super::lanes::LPoly::range`]). Boxes that fail are split (lens and time, the
//! dimensions the triangle has) up to a budget. The plane is a heuristic: only the range
//! check certifies.

use super::lanes::{lconst, LPoly, Lanes};
use super::tpoly::TPoly;
use crate::interval::Interval;
use crate::ring::Ring;
use crate::tri::Tri;

/// The determinant of the columns `c` of a matrix of three rows (plain f64).
fn det3_cols(m: &[[f64; 4]; 3], [c0, c1, c2]: [usize; 3]) -> f64 {
    m[0][c0] * (m[1][c1] * m[2][c2] - m[1][c2] * m[2][c1]) - m[0][c1] * (m[1][c0] * m[2][c2] - m[1][c2] * m[2][c0])
        + m[0][c2] * (m[1][c0] * m[2][c1] - m[1][c1] * m[2][c0])
}

/// The plane's negated slopes `(-A, -B)` through the three vertices at (u, v, t) in the
/// sheared, homogeneous coordinates (plain f64; None when singular).
fn plane_slopes(tri: &Tri, u: f64, v: f64, t: f64) -> Option<(f64, f64)> {
    let l = |a: f64, b: f64| (1.0 - t) * a + t * b;
    let m: [[f64; 4]; 3] = std::array::from_fn(|k| {
        let c = l(tri.c0[k], tri.c1[k]);
        [
            l(tri.q[k][0], tri.r[k][0]) + u * c,
            l(tri.q[k][1], tri.r[k][1]) + tri.k * v * c,
            l(tri.q[k][3], tri.r[k][3]),
            l(tri.q[k][2], tri.r[k][2]),
        ]
    });
    let det3 = |c0: usize, c1: usize, c2: usize| det3_cols(&m, [c0, c1, c2]);
    let d = det3(0, 1, 2);
    let (a, b) = (det3(3, 1, 2) / d, det3(0, 3, 2) / d);
    (d != 0.0 && a.is_finite() && b.is_finite()).then_some((-a, -b))
}

/// True when every `F_k` keeps its sign over the box (x, y the tile's corners, `uvt` the
/// lens and time ranges) for `alpha = a[0] + a[1] s`, `gamma = g[0] + g[1] s`
/// (`s = t - t_mid`).
fn box_holds(tri: &Tri, tile: [f64; 4], uvt: [Interval; 3], z: f64, lower: bool, a: [f64; 2], g: [f64; 2]) -> bool {
    let tm = uvt[2].mid();
    let h = (uvt[2].hi - tm).max(tm - uvt[2].lo).max(0.0);
    let t = TPoly::t_at(tm);
    let one_minus_t = TPoly::c(1.0).sub(&t);
    let lerp2 = |p: f64, q: f64| one_minus_t.mul(&TPoly::c(p)).add(&t.mul(&TPoly::c(q)));
    // Corner n: lane n = 8 iu + 4 iv + 2 ix + iy.
    let e = |iv: Interval, n: usize| if n == 0 { iv.lo } else { iv.hi };
    let lane_u: [f64; 16] = std::array::from_fn(|n| e(uvt[0], n >> 3 & 1));
    let lane_v: [f64; 16] = std::array::from_fn(|n| e(uvt[1], n >> 2 & 1));
    let lane_x: [f64; 16] = std::array::from_fn(|n| [tile[0], tile[1]][n >> 1 & 1]);
    let lane_y: [f64; 16] = std::array::from_fn(|n| [tile[2], tile[3]][n & 1]);
    let kv: LPoly<1, 16> = LPoly::<1, 16>::splat(&TPoly::c(tri.k)).mul(&lconst(&lane_v));
    let affine =
        |c: [f64; 2]| LPoly::<2, 16>([Lanes { v: [c[0]; 16], e: [0.0; 16] }, Lanes { v: [c[1]; 16], e: [0.0; 16] }]);
    let (alpha, gamma) = (affine(a), affine(g));
    let zero = lconst(&[0.0; 16]).0[0];
    (0..3).all(|k| {
        let w = LPoly::<2, 16>::splat(&lerp2(tri.q[k][3], tri.r[k][3]));
        let c = LPoly::<2, 16>::splat(&lerp2(tri.c0[k], tri.c1[k]));
        let xk = LPoly::<2, 16>::splat(&lerp2(tri.q[k][0], tri.r[k][0]));
        let yk = LPoly::<2, 16>::splat(&lerp2(tri.q[k][1], tri.r[k][1]));
        let zk = LPoly::<2, 16>::splat(&lerp2(tri.q[k][2], tri.r[k][2]));
        // T_k and S_k in the lanes.
        let tk = xk.add(&lconst(&lane_u).mul(&c)).sub(&lconst(&lane_x).mul(&w));
        let sk = yk.add(&kv.mul(&c)).sub(&lconst(&lane_y).mul(&w));
        let base = zk.sub(&lconst(&[z; 16]).mul(&w));
        let f: LPoly<3, 16> =
            LPoly([base.0[0], base.0[1], zero]).add(&alpha.mul::<2, 3>(&tk)).add(&gamma.mul::<2, 3>(&sk));
        let (lo, hi) = f.range(h);
        if lower {
            lo.iter().all(|&x| x >= 0.0)
        } else {
            hi.iter().all(|&x| x <= 0.0)
        }
    })
}

/// True when no interior sample of the tile (`[x0, x1, y0, y1]`), at any lens position
/// and time of the domain, has a hit depth below `z` (`lower`) or above it, certified by
/// moving planes over at most `budget` boxes of (u, v, t) (see the module doc). False
/// when that is not shown (nothing is claimed then), and for a `z` or triangle that is
/// not finite.
pub fn depth_end_by_planes(tri: &Tri, tile: [f64; 4], z: f64, lower: bool, budget: usize) -> bool {
    if !z.is_finite() || tri.check_finite().is_err() || tile.iter().any(|v| !v.is_finite()) {
        return false;
    }
    let lens = !tri.is_pinhole();
    let time = !tri.is_static();
    let init = [
        if lens { Interval::new(-1.0, 1.0) } else { Interval::point(0.0) },
        if lens { Interval::new(-1.0, 1.0) } else { Interval::point(0.0) },
        if time { Interval::new(0.0, 1.0) } else { Interval::point(0.0) },
    ];
    let full = [2.0, 2.0, 1.0];
    let mut stack = vec![init];
    let mut boxes = 0usize;
    while let Some(b) = stack.pop() {
        boxes += 1;
        if boxes > budget {
            return false;
        }
        let (uc, vc) = (b[0].mid(), b[1].mid());
        let (t0, t1) = (b[2].lo, b[2].hi);
        let h = 0.5 * (t1 - t0);
        let mut tries: Vec<([f64; 2], [f64; 2])> = Vec::new();
        if let (Some(p0), Some(p1)) = (plane_slopes(tri, uc, vc, t0), plane_slopes(tri, uc, vc, t1)) {
            let slope = |x0: f64, x1: f64| if h > 0.0 { (x1 - x0) / (2.0 * h) } else { 0.0 };
            tries.push(([0.5 * (p0.0 + p1.0), slope(p0.0, p1.0)], [0.5 * (p0.1 + p1.1), slope(p0.1, p1.1)]));
        }
        if let Some(pm) = plane_slopes(tri, uc, vc, b[2].mid()) {
            tries.push(([pm.0, 0.0], [pm.1, 0.0]));
        }
        tries.push(([0.0; 2], [0.0; 2]));
        if tries.iter().any(|&(a, g)| box_holds(tri, tile, b, z, lower, a, g)) {
            continue;
        }
        // Split the widest dimension relative to the domain.
        let (dim, rel) =
            (0..3).map(|i| (i, b[i].width() / full[i])).fold((0, 0.0), |m, c| if c.1 > m.1 { c } else { m });
        if rel < 1e-9 {
            return false;
        }
        let m = b[dim].mid();
        for half in [Interval::new(b[dim].lo, m), Interval::new(m, b[dim].hi)] {
            let mut c = b;
            c[dim] = half;
            stack.push(c);
        }
    }
    true
}

/// The moving-plane certificate of a depth end as three [`super::Cut`]s over one box
/// of samples (`b`: x, y, u, v, t), for the constraint search's edge combinations: cut
/// k is `P_k = s F_k` (`s = 1` for a lower end `depth >= z`, `-1` for an upper end),
/// with `alpha`, `gamma` affine in t through the planes at the box's two times (at its
/// middle lens position). If `P_k >= 0` at an interior sample for every k, the depth
/// there is beyond no end: `depth - z = sum_k (E_k / D) F_k` with positive weights (the
/// module doc). Certifying each cut against the interior samples of the box (no
/// interior sample with `P_k < err`) therefore proves the end over the box, while the
/// edge values in the combination discount the pixels of the tile that the triangle
/// does not cover (which the whole-tile check of [`depth_end_by_planes`] must not
/// ignore).
///
/// `F_k` expands into monomials of x, y, u, v, t up to `t^2`. Each coefficient is
/// enclosed in outward-rounded interval arithmetic from the f64 inputs; the cut keeps
/// the midpoints, and `err` bounds what that leaves out over the box: the sum of each
/// coefficient interval's width times the largest magnitude of its monomial there. So
/// `P_k(s) >= err` implies `s F_k(s) >= 0`. None for a singular plane or values that
/// are not finite.
pub fn depth_plane_cuts(tri: &Tri, b: [Interval; 5], z: f64, lower: bool) -> Option<[super::Cut; 3]> {
    depth_cuts(tri, b, z, lower, Slopes::Plane)
}

/// How `alpha` and `gamma` of the depth certificate are chosen at a point (any choice
/// is sound: only the enclosure of the resulting `F_k` certifies).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slopes {
    /// The negated slopes of the plane through the three vertices: `F_k = w_k` times the
    /// plane's depth beyond z, independent of the pixel. With a vertex behind the lens
    /// (`w_k < 0`) that `F_k` has the wrong sign wherever the plane lies beyond z.
    Plane,
    /// The values that make the three `F_k` equal at the point (the box's middle pixel
    /// and lens position): `F_k = m` with `m = sum_k E_k (z_k - z w_k) / sum_k E_k`,
    /// positive at an interior point whose depth is beyond no end, whatever the signs
    /// of the vertices' w.
    Balanced,
    /// The values that keep the smallest `s F_k` (`s` = 1 for a lower end, -1 for an
    /// upper one) largest at the box's middle and at its four pixel corners (its middle
    /// lens position), with `|alpha|, |gamma|` at most 16 times the largest `|z_k - z
    /// w_k|` over the largest `|T_k|, |S_k|` there: a small linear program. Where the
    /// triangle turns edge-on (a facing flip) the plane's and the balanced slopes grow
    /// without bound, these stay finite.
    Widest,
}

/// The `(alpha, gamma)` of [`Slopes::Widest`] at the pixels `xy` and (u, v, t): the
/// linear program "maximise m with s (z_k - z w_k + alpha T_k + gamma S_k) >= m at
/// every pixel, k = 0, 1, 2, and the bounds on alpha, gamma" solved by trying every
/// vertex (three of its constraints taken as equalities; plain f64, None when no
/// vertex is feasible).
fn widest_slopes(tri: &Tri, xy: &[(f64, f64)], [u, v, t]: [f64; 3], z: f64, lower: bool) -> Option<(f64, f64)> {
    let s = if lower { 1.0 } else { -1.0 };
    let l = |a: f64, b: f64| (1.0 - t) * a + t * b;
    // Rows `a . (alpha, gamma, m) >= b`.
    let mut rows: Vec<([f64; 3], f64)> = Vec::with_capacity(3 * xy.len() + 5);
    let (mut base_max, mut ts_max) = (0.0f64, 0.0f64);
    for &(x, y) in xy {
        for k in 0..3 {
            let c = l(tri.c0[k], tri.c1[k]);
            let w = l(tri.q[k][3], tri.r[k][3]);
            let tk = l(tri.q[k][0], tri.r[k][0]) + u * c - x * w;
            let sk = l(tri.q[k][1], tri.r[k][1]) + tri.k * v * c - y * w;
            let base = s * (l(tri.q[k][2], tri.r[k][2]) - z * w);
            base_max = base_max.max(base.abs());
            ts_max = ts_max.max(tk.abs()).max(sk.abs());
            rows.push(([s * tk, s * sk, -1.0], -base));
        }
    }
    if !(base_max > 0.0 && ts_max > 0.0 && base_max.is_finite() && ts_max.is_finite()) {
        return None;
    }
    let r = 16.0 * base_max / ts_max;
    rows.push(([1.0, 0.0, 0.0], -r));
    rows.push(([-1.0, 0.0, 0.0], -r));
    rows.push(([0.0, 1.0, 0.0], -r));
    rows.push(([0.0, -1.0, 0.0], -r));
    rows.push(([0.0, 0.0, -1.0], -2.0 * base_max));
    let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        det3_cols(&[[a[0], a[1], a[2], 0.0], [b[0], b[1], b[2], 0.0], [c[0], c[1], c[2], 0.0]], [0, 1, 2])
    };
    let n = rows.len();
    let mut best: Option<(f64, f64, f64)> = None;
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (rows[i].0, rows[j].0, rows[k].0);
                let d = det(a, b, c);
                if d.abs() < 1e-300 || !d.is_finite() {
                    continue;
                }
                let col = |m: usize, r: [f64; 3], q: f64| {
                    let mut r = r;
                    r[m] = q;
                    r
                };
                let (bi, bj, bk) = (rows[i].1, rows[j].1, rows[k].1);
                // The objective first: a vertex no higher than the best so far cannot
                // replace it, so its feasibility need not be checked (the same vertex
                // wins as with every check made).
                let m = det(col(2, a, bi), col(2, b, bj), col(2, c, bk)) / d;
                if !m.is_finite() || best.is_some_and(|(_, _, bm)| m <= bm) {
                    continue;
                }
                let x: [f64; 3] = [
                    det(col(0, a, bi), col(0, b, bj), col(0, c, bk)) / d,
                    det(col(1, a, bi), col(1, b, bj), col(1, c, bk)) / d,
                    m,
                ];
                if !x.iter().all(|v| v.is_finite()) {
                    continue;
                }
                let feasible = rows.iter().all(|(a, b)| {
                    let lhs = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
                    lhs >= b - 1e-9 * (b.abs() + (a[0] * x[0]).abs() + (a[1] * x[1]).abs() + x[2].abs())
                });
                if feasible {
                    best = Some((x[0], x[1], x[2]));
                }
            }
        }
    }
    best.map(|(a, g, _)| (a, g))
}

/// The `(alpha, gamma)` that make `F_k` equal for the three vertices at the pixel
/// (x, y) and (u, v, t): the solution of `alpha T_k + gamma S_k - m = -(z_k - z w_k)`,
/// k = 0, 1, 2 (plain f64; None when singular).
fn balanced_slopes(tri: &Tri, p: [f64; 5], z: f64) -> Option<(f64, f64)> {
    let [x, y, u, v, t] = p;
    let l = |a: f64, b: f64| (1.0 - t) * a + t * b;
    let rows: [[f64; 4]; 3] = std::array::from_fn(|k| {
        let c = l(tri.c0[k], tri.c1[k]);
        let w = l(tri.q[k][3], tri.r[k][3]);
        let tk = l(tri.q[k][0], tri.r[k][0]) + u * c - x * w;
        let sk = l(tri.q[k][1], tri.r[k][1]) + tri.k * v * c - y * w;
        [tk, sk, -1.0, -(l(tri.q[k][2], tri.r[k][2]) - z * w)]
    });
    let det3 = |c0: usize, c1: usize, c2: usize| det3_cols(&rows, [c0, c1, c2]);
    let d = det3(0, 1, 2);
    let (a, g) = (det3(3, 1, 2) / d, det3(0, 3, 2) / d);
    (d != 0.0 && a.is_finite() && g.is_finite()).then_some((a, g))
}

/// [`depth_plane_cuts`] with `alpha`, `gamma` chosen by `slopes` at the box's two times
/// (its middle lens position and, for [`Slopes::Balanced`], its middle pixel), affine in
/// t between them.
pub fn depth_cuts(tri: &Tri, b: [Interval; 5], z: f64, lower: bool, slopes: Slopes) -> Option<[super::Cut; 3]> {
    use super::Cut;
    if !z.is_finite() || b.iter().any(|iv| !iv.lo.is_finite() || !iv.hi.is_finite()) {
        return None;
    }
    let (um, vm) = (b[2].mid(), b[3].mid());
    let (t0, t1) = (b[4].lo, b[4].hi);
    let at = |t: f64| match slopes {
        Slopes::Plane => plane_slopes(tri, um, vm, t),
        Slopes::Balanced => balanced_slopes(tri, [b[0].mid(), b[1].mid(), um, vm, t], z),
        Slopes::Widest => {
            let xy = [
                (b[0].mid(), b[1].mid()),
                (b[0].lo, b[1].lo),
                (b[0].lo, b[1].hi),
                (b[0].hi, b[1].lo),
                (b[0].hi, b[1].hi),
            ];
            widest_slopes(tri, &xy, [um, vm, t], z, lower)
        }
    };
    let (p0, p1) = (at(t0)?, at(t1)?);
    // alpha = a0 + a1 t, gamma = g0 + g1 t through the two planes (exact f64 values:
    // any numbers serve, only the enclosure of F_k's coefficients must be rigorous).
    let line = |x0: f64, x1: f64| {
        let s = if t1 > t0 { (x1 - x0) / (t1 - t0) } else { 0.0 };
        [x0 - s * t0, s]
    };
    let (a, g) = (line(p0.0, p1.0), line(p0.1, p1.1));
    if a.iter().chain(g.iter()).any(|v| !v.is_finite()) {
        return None;
    }
    let pt = Interval::point;
    let sign = if lower { 1.0 } else { -1.0 };
    let cut_k = |k: usize| -> Option<Cut> {
        let aff = |p: f64, q: f64| [pt(p), pt(q) - pt(p)];
        let (x, y) = (aff(tri.q[k][0], tri.r[k][0]), aff(tri.q[k][1], tri.r[k][1]));
        let (zz, w) = (aff(tri.q[k][2], tri.r[k][2]), aff(tri.q[k][3], tri.r[k][3]));
        let c = aff(tri.c0[k], tri.c1[k]);
        let kc = [pt(tri.k) * c[0], pt(tri.k) * c[1]];
        // Coefficients: lin[m] for the multilinear monomial m (bits x 1, y 2, u 4, v 8,
        // t 16), sq[m] for t^2 times the monomial m of x, y, u, v.
        let mut lin = [pt(0.0); 32];
        let mut sq = [pt(0.0); 16];
        // z_k - z w_k
        lin[0] = lin[0] + zz[0] - pt(z) * w[0];
        lin[Cut::T] = lin[Cut::T] + zz[1] - pt(z) * w[1];
        // (m0 + m1 t) (p0 + p1 t) q for a plane slope m and an affine term p of monomial q.
        let mut add = |m: [f64; 2], p: [Interval; 2], q: usize| {
            lin[q] = lin[q] + pt(m[0]) * p[0];
            lin[q | Cut::T] = lin[q | Cut::T] + pt(m[0]) * p[1] + pt(m[1]) * p[0];
            sq[q] = sq[q] + pt(m[1]) * p[1];
        };
        // T_k = x_k + u c_k - x w_k, S_k = y_k + k v c_k - y w_k.
        add(a, x, 0);
        add(a, c, Cut::U);
        add(a, [-w[0], -w[1]], Cut::X);
        add(g, y, 0);
        add(g, kc, Cut::V);
        add(g, [-w[0], -w[1]], Cut::Y);
        Cut::enclosing(&lin.map(|iv| pt(sign) * iv), &sq.map(|iv| pt(sign) * iv), &b, 0.0)
    };
    Some([cut_k(0)?, cut_k(1)?, cut_k(2)?])
}
