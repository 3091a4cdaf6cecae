//! The corner-by-corner loop that [`box_values_with`](super::box_values_with)
//! vectorises, kept to check that the two agree bit for bit.

use super::enclosure::{ends, Box5, BoxValues};
use super::tpoly::TPoly;
use crate::coverage::interval_div;
use crate::interval::Interval;
use crate::ring::Ring;
use crate::tri::Tri;

pub(super) fn box_values_with(tri: &Tri, b: &Box5, with_depth: bool) -> BoxValues {
    let tm = b[4].mid();
    let h = (b[4].hi - tm).max(tm - b[4].lo).max(0.0);
    let t = TPoly::t_at(tm);
    let (xs, nx) = ends(b[0]);
    let (ys, ny) = ends(b[1]);
    let (us, nu) = ends(b[2]);
    let (vs, nv) = ends(b[3]);
    let mut e: [Option<Interval>; 3] = [None; 3];
    let mut d: Option<Interval> = None;
    let mut nz: Option<Interval> = None;
    let mut depth: Option<Interval> = None;
    let mut depth_ok = true;
    // mid-t values of E_0..E_2 at each corner [u][v][x][y], and of D at [u][v]
    let mut em = [[[[[0.0f64; 3]; 2]; 2]; 2]; 2];
    let mut dm = [[0.0f64; 2]; 2];
    let mut zm = [[[[0.0f64; 2]; 2]; 2]; 2];
    let mut depth_smear = [0.0f64; 5];
    let mut smear = [[0.0f64; 5]; 4];
    let hull = |acc: &mut Option<Interval>, v: Interval| {
        *acc = Some(match acc {
            Some(a) => {
                if v.lo.is_nan() || v.hi.is_nan() || a.lo.is_nan() {
                    Interval::new(f64::NAN, f64::NAN)
                } else {
                    a.hull(v)
                }
            }
            None => v,
        })
    };
    // Per vertex, as polynomials in s: position, depth row, w, CoC at time t.
    let lerp = |i: usize, j: usize| TPoly::lerp(&TPoly::c(tri.q[i][j]), &TPoly::c(tri.r[i][j]), &t);
    let xb = [0, 1, 2].map(|i| lerp(i, 0));
    let yb = [0, 1, 2].map(|i| lerp(i, 1));
    let zb = [0, 1, 2].map(|i| lerp(i, 2));
    let wb = [0, 1, 2].map(|i| lerp(i, 3));
    let cb = [0, 1, 2].map(|i| TPoly::lerp(&TPoly::c(tri.c0[i]), &TPoly::c(tri.c1[i]), &t));
    // Sheared coordinates at the lens corners: x' depends on u only, y' on v only.
    let xs_u: [[TPoly; 3]; 2] = std::array::from_fn(|iu| [0, 1, 2].map(|i| xb[i].add(&TPoly::c(us[iu]).mul(&cb[i]))));
    let kv: [TPoly; 2] = std::array::from_fn(|iv| TPoly::c(tri.k).mul(&TPoly::c(vs[iv])));
    let ys_v: [[TPoly; 3]; 2] = std::array::from_fn(|iv| [0, 1, 2].map(|i| yb[i].add(&kv[iv].mul(&cb[i]))));
    // Translated coordinates: P.x depends on (x, u), P.y on (y, v).
    let px: [[[TPoly; 3]; 2]; 2] = std::array::from_fn(|ix| {
        std::array::from_fn(|iu| [0, 1, 2].map(|i| xs_u[iu][i].sub(&TPoly::c(xs[ix]).mul(&wb[i]))))
    });
    let py: [[[TPoly; 3]; 2]; 2] = std::array::from_fn(|iy| {
        std::array::from_fn(|iv| [0, 1, 2].map(|i| ys_v[iv][i].sub(&TPoly::c(ys[iy]).mul(&wb[i]))))
    });
    const EDGES: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
    for iu in 0..nu {
        for iv in 0..nv {
            // D = sum_i w_i E_i at x = y = 0 (the determinant of the sheared vertices).
            let (xa, ya) = (&xs_u[iu], &ys_v[iv]);
            let mut dp = TPoly::c(0.0);
            for (k, &(i, j)) in EDGES.iter().enumerate() {
                dp = dp.add(&wb[k].mul(&xa[i].mul(&ya[j]).sub(&ya[i].mul(&xa[j]))));
            }
            let dc = dp.range(h);
            dm[iu][iv] = dp.mid();
            smear[3][4] = smear[3][4].max(dp.variation(h));
            hull(&mut d, dc);
            for ix in 0..nx {
                for iy in 0..ny {
                    let (pxc, pyc) = (&px[ix][iu], &py[iy][iv]);
                    let ev = EDGES.map(|(i, j)| pxc[i].mul(&pyc[j]).sub(&pyc[i].mul(&pxc[j])));
                    for k in 0..3 {
                        hull(&mut e[k], ev[k].range(h));
                        em[iu][iv][ix][iy][k] = ev[k].mid();
                        smear[k][4] = smear[k][4].max(ev[k].variation(h));
                    }
                    if !with_depth {
                        depth_ok = false;
                        continue;
                    }
                    let n = ev[0].mul(&zb[0]).add(&ev[1].mul(&zb[1])).add(&ev[2].mul(&zb[2]));
                    let nc = n.range(h);
                    hull(&mut nz, nc);
                    // The depth N / D around a centre value z_c: N / D = z_c + M / D with
                    // M = N - z_c D. M keeps the correlation of N and D in t, so the
                    // quotient of enclosures stays tight where N and D move together.
                    let dmid = dp.mid();
                    let zc = n.mid() / dmid;
                    zm[iu][iv][ix][iy] = zc;
                    let zq = if zc.is_finite() {
                        let m = n.sub(&TPoly::c(zc).mul(&dp));
                        depth_smear[4] = depth_smear[4].max(m.variation(h) / dmid.abs());
                        interval_div(m.range(h), dc).map(|q| Interval::point(zc) + q)
                    } else {
                        None
                    };
                    // N / D is linear-fractional in each of x, y, u, v separately, hence
                    // monotone in each while D keeps its sign: its extremes over the
                    // box are at the corners too.
                    match zq {
                        Some(z) if depth_ok => hull(&mut depth, z),
                        _ => depth_ok = false,
                    }
                }
            }
        }
    }
    for iu in 0..nu {
        for iv in 0..nv {
            if nu == 2 && iu == 0 {
                smear[3][2] = smear[3][2].max((dm[1][iv] - dm[0][iv]).abs());
            }
            if nv == 2 && iv == 0 {
                smear[3][3] = smear[3][3].max((dm[iu][1] - dm[iu][0]).abs());
            }
            for ix in 0..nx {
                for iy in 0..ny {
                    let z = zm[iu][iv][ix][iy];
                    if nx == 2 && ix == 0 {
                        depth_smear[0] = depth_smear[0].max((zm[iu][iv][1][iy] - z).abs());
                    }
                    if ny == 2 && iy == 0 {
                        depth_smear[1] = depth_smear[1].max((zm[iu][iv][ix][1] - z).abs());
                    }
                    if nu == 2 && iu == 0 {
                        depth_smear[2] = depth_smear[2].max((zm[1][iv][ix][iy] - z).abs());
                    }
                    if nv == 2 && iv == 0 {
                        depth_smear[3] = depth_smear[3].max((zm[iu][1][ix][iy] - z).abs());
                    }
                    for k in 0..3 {
                        let here = em[iu][iv][ix][iy][k];
                        if nx == 2 && ix == 0 {
                            smear[k][0] = smear[k][0].max((em[iu][iv][1][iy][k] - here).abs());
                        }
                        if ny == 2 && iy == 0 {
                            smear[k][1] = smear[k][1].max((em[iu][iv][ix][1][k] - here).abs());
                        }
                        if nu == 2 && iu == 0 {
                            smear[k][2] = smear[k][2].max((em[1][iv][ix][iy][k] - here).abs());
                        }
                        if nv == 2 && iv == 0 {
                            smear[k][3] = smear[k][3].max((em[iu][1][ix][iy][k] - here).abs());
                        }
                    }
                }
            }
        }
    }
    // Separation by a side of the (x, y) rectangle: P_i.x at x = x_lo is
    // x'_i - x_lo w_i, negative iff vertex i projects left of x_lo (w_i > 0).
    let in_front = wb.iter().all(|w| w.range(h).lo > 0.0);
    let separated = in_front && {
        let side = |p: &[[TPoly; 3]; 2], n: usize, beyond_hi: bool| {
            (0..3).all(|i| {
                (0..n).all(|k| {
                    let r = p[k][i].range(h);
                    if beyond_hi {
                        r.lo >= 0.0
                    } else {
                        r.hi <= 0.0
                    }
                })
            })
        };
        side(&px[0], nu, false) || side(&px[nx - 1], nu, true) || side(&py[0], nv, false) || side(&py[ny - 1], nv, true)
    };
    let d = d.unwrap();
    // The per-corner quotients bound the depth only if D has one sign over the box.
    let depth = if depth_ok && (d.lo > 0.0 || d.hi < 0.0) { depth } else { None };
    if depth.is_none() || depth_smear.iter().any(|v| !v.is_finite()) {
        depth_smear = [0.0; 5];
    }
    let nz = nz.unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY));
    BoxValues {
        e: e.map(|v| v.unwrap()),
        d,
        nz,
        depth,
        vertex_depth: None,
        smear,
        depth_smear,
        in_front,
        separated,
        eliminated: false,
        elim_smear: [0.0; 3],
        covered_depth: Interval::new(f64::NEG_INFINITY, f64::INFINITY),
        covered_smear: [0.0; 3],
    }
}

#[cfg(test)]
mod tests {
    use super::super::enclosure::box_values_with;
    use super::*;
    use crate::extents::testgen::unit_stream;

    /// The vectorised corner loop returns exactly (bit for bit) what the corner-by-corner
    /// loop returns, on triangles of every kind (static, moving, defocused, behind the
    /// lens, far from the origin, degenerate) and boxes with point and open dimensions.
    #[test]
    fn lanes_match_the_corner_loop_bit_for_bit() {
        let mut next = unit_stream(0x2545_F491_4F6C_DD1D);
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        let same_iv = |a: Interval, b: Interval| same(a.lo, b.lo) && same(a.hi, b.hi);
        for case in 0..4000 {
            let scale = [1.0, 1e3, 1e6, 1e-3][case % 4];
            let kind = case / 4 % 5;
            let mut v = |lo: f64, hi: f64| lo + (hi - lo) * next();
            let mut q = [[0.0; 4]; 3];
            let mut r = [[0.0; 4]; 3];
            let (mut c0, mut c1) = ([0.0; 3], [0.0; 3]);
            for i in 0..3 {
                let w0 = if kind == 3 { v(-1.0, 2.0) } else { v(0.2, 3.0) };
                q[i] = [v(-20.0, 20.0) * scale * w0, v(-20.0, 20.0) * scale * w0, v(-1.0, 1.0), w0];
                r[i] = if kind == 0 {
                    q[i]
                } else {
                    [q[i][0] + v(-9.0, 9.0) * scale, q[i][1] + v(-9.0, 9.0) * scale, q[i][2], q[i][3] + v(-0.5, 0.5)]
                };
                if kind >= 2 {
                    c0[i] = v(-5.0, 5.0);
                    c1[i] = c0[i] + v(-2.0, 2.0);
                }
            }
            if kind == 4 {
                q[2] = q[1];
                r[2] = r[1];
            }
            let tri = Tri { q, r, c0, c1, k: v(0.5, 2.0) };
            let mut iv = |lo: f64, hi: f64, point: bool| {
                let a = v(lo, hi);
                if point {
                    Interval::point(a)
                } else {
                    let w = (hi - lo) * 10f64.powf(-v(0.0, 9.0));
                    Interval::new(a, a + w)
                }
            };
            let pts = (case * 7) % 32;
            let b: Box5 = [
                iv(-20.0 * scale, 20.0 * scale, pts & 1 != 0),
                iv(-20.0 * scale, 20.0 * scale, pts & 2 != 0),
                iv(-1.0, 1.0, pts & 4 != 0),
                iv(-1.0, 1.0, pts & 8 != 0),
                iv(0.0, 1.0, pts & 16 != 0),
            ];
            for with_depth in [false, true] {
                let a = box_values_with(&tri, &b, with_depth);
                let o = super::box_values_with(&tri, &b, with_depth);
                let ok = (0..3).all(|k| same_iv(a.e[k], o.e[k]))
                    && same_iv(a.d, o.d)
                    && same_iv(a.nz, o.nz)
                    && match (a.depth, o.depth) {
                        (Some(x), Some(y)) => same_iv(x, y),
                        (None, None) => true,
                        _ => false,
                    }
                    && (0..4).all(|k| (0..5).all(|i| same(a.smear[k][i], o.smear[k][i])))
                    && (0..5).all(|i| same(a.depth_smear[i], o.depth_smear[i]))
                    && a.in_front == o.in_front
                    && a.separated == o.separated;
                assert!(ok, "case {case} depth {with_depth}:\n{a:?}\n{o:?}");
            }
        }
    }
}
