//! `mam2012-safe`'s tile answer as it was before its per-axis part became a function of
//! its own (for [`Prepared::grid`]), kept verbatim: the reference the current code is
//! compared with, bit for bit (`safe_tile_is_its_old_code_bit_for_bit` in the parent's
//! tests).

use super::*;

/// The old `PrepSafe::tile`, on the setup `setup_safe` returns.
pub(super) fn answer(setup: &Result<[SafeAxis; 2], &'static str>, tile: &Tile) -> TileResult {
    PrepSafeOld(setup).tile(tile)
}

struct PrepSafeOld<'a>(&'a Result<[SafeAxis; 2], &'static str>);

impl PrepSafeOld<'_> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let axes = match &self.0 {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        let mut out = TileBounds::full();
        for (is_v, ax, t0, t1) in [(false, &axes[0], tile.x0, tile.x1), (true, &axes[1], tile.y0, tile.y1)] {
            // A NaN or reversed tile: answer the whole domain.
            if t0.partial_cmp(&t1).is_none_or(|o| o == std::cmp::Ordering::Greater) {
                return TileResult::Bounds(TileBounds::full());
            }
            // Covered columns lie in the enclosed extent: clamp the tile to it; a tile
            // beside it holds no covered sample.
            let (x0, x1) = (t0.max(ax.dom[0]), t1.min(ax.dom[1]));
            if x0 > x1 {
                return TileResult::Empty;
            }
            let ends = |p: Option<SafePatch>, upper: bool| {
                let p = p?;
                let e = |k: usize| {
                    let r = p.range(x0, x1, k);
                    if upper {
                        r.hi
                    } else {
                        r.lo
                    }
                };
                let l = [e(0), e(1)];
                (l[0].is_finite() && l[1].is_finite()).then_some(l)
            };
            let (lo, hi) = (ends(ax.lo, false), ends(ax.hi, true));
            let r_lo = lo.map_or(-1.0, |l| l[0].min(l[1]).max(-1.0));
            let r_hi = hi.map_or(1.0, |l| l[0].max(l[1]).min(1.0));
            if r_lo > r_hi {
                return TileResult::Empty;
            }
            if is_v {
                out.v = [r_lo, r_hi];
            } else {
                out.u = [r_lo, r_hi];
            }
            for (upper, l) in [(false, lo), (true, hi)] {
                if let Some(l) = l {
                    // The slope rounded outward (the line then lies outside the exact one
                    // on t in [0, 1]) and the intercept moved out by LINE_PAD (a rounded
                    // difference with a representable l[0] never crosses l[0]).
                    let (a, b) = if upper {
                        ((l[1] - l[0]).next_up(), l[0] + LINE_PAD)
                    } else {
                        ((l[1] - l[0]).next_down(), l[0] - LINE_PAD)
                    };
                    if a.is_finite() && b.is_finite() {
                        out.constraints.push(Box::new(SafeLine(Line { is_v, upper, a, b })));
                    }
                }
            }
        }
        TileResult::Bounds(out)
    }
}
