//! `mam2012-hyperplane`'s tile path as it was before it was written over `F32Arith`
//! (kept verbatim: `plane`, the tile answer, `finish`): the reference the encoded code
//! is compared with, bit for bit. The setup (unchanged) comes from the crate.
#![allow(dead_code)]

use cullproof::bounds::mam2012_hyperplane::{edges_of, Edge};
use cullproof::bounds::TileBounds;
use cullproof::{Tile, Triangle};

type V3 = [f32; 3];

#[derive(Debug)]
struct Plane {
    edge: usize,
    a: [f32; 6],
    safe: bool,
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The hyperplane `a = (a_1, a_x, a_y, a_u, a_v, a_t)` of one edge for one tile.
fn plane(e: &Edge, k: f32, xc: f32, yc: f32, hx: f32, hy: f32) -> Option<[f32; 6]> {
    let xc3 = [xc, yc, 1.0];
    // Eq. 7.
    let z = e.n12[0].abs() * hx + e.n12[1].abs() * hy;
    let a_t = dot(e.n12, xc3) - z;
    let a2 = dot(e.n2, xc3) + (e.n2[0].abs() * hx + e.n2[1].abs() * hy);
    let p = 0.25 * a2.max(0.0);
    // Eq. 8.
    let pad_z = e.mc[2].abs() + e.mr[2];
    let avg_x = yc * e.mc[2] - e.mc[1];
    let rad_x = yc.abs() * e.mr[2] + hy * pad_z + e.mr[1];
    let avg_y = e.mc[0] - xc * e.mc[2];
    let rad_y = e.mr[0] + xc.abs() * e.mr[2] + hx * pad_z;
    let xi = -(rad_x + k * rad_y);
    let a = [e.n0[2] + xi - p, e.n0[0], e.n0[1], avg_x, k * avg_y, a_t];
    a.iter().all(|v| v.is_finite()).then_some(a)
}

/// Clamp the refined intervals to the domain; Empty when one is empty.
fn finish(mut out: TileBounds) -> Option<TileBounds> {
    let clamp = |r: [f32; 2], lo: f32, hi: f32| [r[0].max(lo), r[1].min(hi)];
    out.u = clamp(out.u, -1.0, 1.0);
    out.v = clamp(out.v, -1.0, 1.0);
    out.t = clamp(out.t, 0.0, 1.0);
    if !(out.u[0] <= out.u[1] && out.v[0] <= out.v[1] && out.t[0] <= out.t[1]) {
        return None;
    }
    Some(out)
}

/// The old answer bit for bit (as `cases::bits` reads a method's): None for Empty.
pub fn answer(per_sample: bool, tri: &Triangle, tile: &Tile) -> Option<(Vec<u32>, String)> {
    let Ok((edges, k)) = edges_of(tri) else {
        let b = TileBounds::full();
        return Some((b.u.iter().chain(&b.v).chain(&b.t).map(|x| x.to_bits()).collect(), "[]".into()));
    };
    let mut planes: Vec<Plane> = vec![];
    let (xc, yc) = tile.center();
    let (hx, hy) = (0.5 * (tile.x1 - tile.x0), 0.5 * (tile.y1 - tile.y0));
    let mut out = TileBounds::full();
    for (ei, e) in edges.iter().enumerate() {
        let Some(a) = plane(e, k, xc, yc, hx, hy) else {
            continue;
        };
        // The xy part once at the tile centre, padded by the half extents.
        let m_xy = a[0] + a[1] * xc + a[2] * yc - (a[1].abs() * hx + a[2].abs() * hy);
        let (mu, mv, mt) = (-a[3].abs(), -a[4].abs(), a[5].min(0.0));
        let m = m_xy + mu + mv + mt;
        if m > 0.0 {
            return None;
        }
        for (ak, rest, range) in
            [(a[3], m_xy + mv + mt, &mut out.u), (a[4], m_xy + mu + mt, &mut out.v), (a[5], m_xy + mu + mv, &mut out.t)]
        {
            let bound = -rest / ak;
            if !bound.is_finite() {
                continue;
            }
            if ak > 0.0 {
                range[1] = range[1].min(bound);
            } else if ak < 0.0 {
                range[0] = range[0].max(bound);
            }
        }
        if per_sample {
            planes.push(Plane { edge: ei, a, safe: false });
        }
    }
    let out = finish(out)?;
    let v = out.u.iter().chain(&out.v).chain(&out.t).map(|x| x.to_bits()).collect();
    Some((v, format!("{planes:?}")))
}
