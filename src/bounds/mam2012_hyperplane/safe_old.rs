//! `mam2012-hyperplane-safe`'s tile test as it was before its reject and bounds moved
//! into [`safe_cut`](super::safe_cut) (shared with the grid), kept verbatim: the
//! reference the current [`SafePrep::tile`](super::SafePrep) is compared with, bit for
//! bit (`safe_tile_is_its_old_code_bit_for_bit` in the parent's tests).

use super::*;

impl SafePrep {
    pub(super) fn tile_old(&self, tile: &Tile) -> TileResult {
        let Ok(edges) = &self.s else {
            return TileResult::Bounds(TileBounds::full());
        };
        let (x0, x1, y0, y1) = (tile.x0, tile.x1, tile.y0, tile.y1);
        if !([x0, x1, y0, y1].iter().all(|v| v.is_finite()) && x0 <= x1 && y0 <= y1) {
            return TileResult::Bounds(TileBounds::full());
        }
        let (dn, up) = (f32::next_down, f32::next_up);
        let (xs, ys) = (Iv::new(x0, x1), Iv::new(y0, y1));
        let mut out = TileBounds::full();
        for (ei, e) in edges.iter().enumerate() {
            let Some(a) = e.as_ref().and_then(|e| plane_safe(e, self.k, xs, ys)) else {
                continue;
            };
            // Lower bounds of the minimum over the hypercube: the xy part at the tile's
            // corner (each product and sum rounded down), then the u, v, t corner terms.
            let m_xy = dn(dn(a[0] + dn(a[1] * x0).min(dn(a[1] * x1))) + dn(a[2] * y0).min(dn(a[2] * y1)));
            let (mu, mv, mt) = (-a[3].abs(), -a[4].abs(), a[5].min(0.0));
            let m = dn(dn(dn(m_xy + mu) + mv) + mt);
            if m > 0.0 {
                return TileResult::Empty;
            }
            for (ak, rest, range) in [
                (a[3], dn(dn(m_xy + mv) + mt), &mut out.u),
                (a[4], dn(dn(m_xy + mu) + mt), &mut out.v),
                (a[5], dn(dn(m_xy + mu) + mv), &mut out.t),
            ] {
                let bound = -rest / ak;
                if !bound.is_finite() {
                    continue;
                }
                if ak > 0.0 {
                    range[1] = range[1].min(up(bound));
                } else if ak < 0.0 {
                    range[0] = range[0].max(dn(bound));
                }
            }
            if self.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a, safe: true }));
            }
        }
        finish(out)
    }
}
