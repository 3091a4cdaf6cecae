//! Where a case is placed: the triangles the methods see and the oracle judges under
//! vertex snapping ([`judged_triangles`]), a case drawn into a viewport's guard band
//! ([`place_case`]) and its tile moved inside the viewport ([`tile_in_viewport`]).

use crate::cases::generate::{physical_case, rng_for, Regime};
use crate::model::samples::{snap_coord, Snap, Viewport};
use crate::model::{Case, Tile, Triangle};
use oracles::Tri;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The triangle the methods see and the one the oracle judges: the case's own, or under
/// snapping the snapped triangle, exact for the oracle (f64) and rounded to the nearest
/// f32 for the methods. Err names the first vertex key that cannot be snapped exactly.
pub fn judged_triangles(snap: Option<Snap>, case: &Case) -> Result<(Triangle, Tri), String> {
    let Some(s) = snap else {
        return Ok((case.triangle, case.triangle.to_oracle()));
    };
    let t = &case.triangle;
    let mut exact = t.to_oracle();
    let mut seen = *t;
    for (key, src, dst, out) in [("q", &t.q, &mut exact.q, &mut seen.q), ("r", &t.r, &mut exact.r, &mut seen.r)] {
        for i in 0..3 {
            let w = src[i][3];
            for (j, name) in [(0, "x"), (1, "y")] {
                let v = snap_coord(src[i][j], w, s.bits).ok_or_else(|| {
                    format!(
                        "{key}[{i}].{name} = {} (w = {w}) cannot be snapped to 2^-{} px exactly: w <= 0 or the \
                         position lies beyond the grid's exact range",
                        src[i][j], s.bits
                    )
                })?;
                dst[i][j] = v;
                out[i][j] = v as f32;
            }
        }
    }
    Ok((seen, exact))
}

/// Attempts at drawing a case of the regime that fits the viewport's guard band.
pub const PLACE_ATTEMPTS: u64 = 64;

const PLACE_STREAM: u64 = 0x91ac_e0f5_c4ee_7a11;

/// The screen box `[x0, x1, y0, y1]` of every vertex at both motion keys and every lens
/// corner (exact quotients of the f32 values, rounded outward by one f64 step), or None
/// when some such vertex is not in front of the lens.
pub fn footprint(t: &Triangle) -> Option<[f64; 4]> {
    let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
    for (p, c) in t.q.iter().zip(t.c0).chain(t.r.iter().zip(t.c1)) {
        if p[3].is_nan() || p[3] <= 0.0 {
            return None;
        }
        for (su, sv) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            let w = p[3] as f64;
            let x = (p[0] as f64 + su * c as f64) / w;
            let y = (p[1] as f64 + sv * t.k as f64 * c as f64) / w;
            b[0] = b[0].min(x.next_down());
            b[1] = b[1].max(x.next_up());
            b[2] = b[2].min(y.next_down());
            b[3] = b[3].max(y.next_up());
        }
    }
    b.iter().all(|v| v.is_finite()).then_some(b)
}

/// The case moved on screen by whole pixels `(dx, dy)` (clip x += dx w, in f32), and
/// whether the move was exact (every sum exact, so the footprint moved by exactly that).
fn shifted(case: &Case, dx: f32, dy: f32) -> Case {
    let mut c = *case;
    for p in c.triangle.q.iter_mut().chain(c.triangle.r.iter_mut()) {
        p[0] += dx * p[3];
        p[1] += dy * p[3];
    }
    c
}

/// A case of `regime` placed in the viewport: drawn from the case's own stream as
/// without a viewport, then (if its footprint fits the guard band) moved by whole
/// pixels to a random place whose footprint lies in the guard band and meets the
/// viewport; if it does not fit, drawn again from further streams, up to
/// [`PLACE_ATTEMPTS`] times. None when no draw fits (a regime whose triangles are
/// larger than the guard band, or reach behind the lens).
pub fn place_case(seed: u64, i: u64, regime: Regime, vp: Viewport) -> Option<(Case, ChaCha8Rng)> {
    let g = vp.guard_rect();
    for a in 0..PLACE_ATTEMPTS {
        let mut rng = if a == 0 { rng_for(seed, i) } else { rng_for(seed ^ PLACE_STREAM.wrapping_mul(a), i) };
        let case = physical_case(&mut rng, regime);
        let Some(f) = footprint(&case.triangle) else { continue };
        let (w, h) = (f[1] - f[0], f[3] - f[2]);
        if w + 2.0 > g[1] - g[0] || h + 2.0 > g[3] - g[2] {
            continue;
        }
        // Whole-pixel moves that keep the footprint in the guard band (one pixel of
        // room for the f32 rounding of the move) and meeting the viewport.
        let r = vp.rect();
        let lo_x = (g[0] - f[0] + 1.0).max(r[0] - f[1]).ceil();
        let hi_x = (g[1] - f[1] - 1.0).min(r[1] - f[0]).floor();
        let lo_y = (g[2] - f[2] + 1.0).max(r[2] - f[3]).ceil();
        let hi_y = (g[3] - f[3] - 1.0).min(r[3] - f[2]).floor();
        if lo_x > hi_x || lo_y > hi_y {
            continue;
        }
        let mut prng = rng_for(seed ^ PLACE_STREAM, i.wrapping_mul(PLACE_ATTEMPTS).wrapping_add(a));
        let dx = prng.gen_range(lo_x..=hi_x) as f32;
        let dy = prng.gen_range(lo_y..=hi_y) as f32;
        let moved = shifted(&case, dx, dy);
        let inside =
            footprint(&moved.triangle).is_some_and(|m| m[0] >= g[0] && m[1] <= g[1] && m[2] >= g[2] && m[3] <= g[3]);
        if inside && moved.validate().is_ok() {
            return Some((moved, rng));
        }
    }
    None
}

/// True when the case and tile keep to the viewport (always without one): the
/// footprint inside the guard band, the tile inside the viewport. The shrinker and the
/// search keep only such cases.
pub fn placed_in(viewport: Option<Viewport>, case: &Case, tile: &Tile) -> bool {
    let Some(vp) = viewport else { return true };
    let g = vp.guard_rect();
    vp.holds_tile(tile)
        && footprint(&case.triangle).is_some_and(|f| f[0] >= g[0] && f[1] <= g[1] && f[2] >= g[2] && f[3] <= g[3])
}

/// The tile moved (by whole tiles) into the viewport: the nearest tile of the same grid
/// inside it (the viewport is at least one tile wide, else the tile is clamped to it).
pub fn tile_in_viewport(t: Tile, vp: Viewport) -> Tile {
    let size = t.x1 - t.x0;
    // Offsets from the viewport's corner, by whole tiles.
    let fit = |a: f32, o: i32, n: u32| {
        let max = ((n as f32 - size) / size).floor() * size;
        o as f32 + if max < 0.0 { 0.0 } else { (a - o as f32).clamp(0.0, max) }
    };
    let (x0, y0) = (fit(t.x0, vp.x0, vp.width), fit(t.y0, vp.y0, vp.height));
    let r = vp.rect();
    Tile { x0, y0, x1: (x0 + size).min(r[1] as f32), y1: (y0 + size).min(r[3] as f32) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(v: [[f32; 2]; 3], w: f32) -> Case {
        Case {
            triangle: Triangle::fixed([
                [v[0][0] * w, v[0][1] * w, 0.5, w],
                [v[1][0] * w, v[1][1] * w, 0.5, w],
                [v[2][0] * w, v[2][1] * w, 0.5, w],
            ]),
            lens: None,
        }
    }

    #[test]
    fn snapping_moves_each_pixel_position_onto_the_grid_and_keeps_w() {
        let c = tri([[0.3, 0.3], [5.1, 0.2], [0.4, 4.7]], 3.0);
        let (seen, exact) = judged_triangles(Some(Snap { bits: 0 }), &c).unwrap();
        for i in 0..3 {
            assert_eq!(exact.q[i][3], 3.0);
            let (x, y) = (exact.q[i][0] / 3.0, exact.q[i][1] / 3.0);
            assert_eq!((x, y), (x.round(), y.round()), "{x} {y}");
            assert_eq!(seen.q[i][0], exact.q[i][0] as f32);
        }
        assert_eq!((exact.q[1][0], exact.q[2][1]), (15.0, 15.0));
        let (s2, e2) = judged_triangles(None, &c).unwrap();
        assert_eq!((s2, e2), (c.triangle, c.triangle.to_oracle()));
        let mut bad = c;
        bad.triangle.r[1][3] = -1.0;
        assert!(judged_triangles(Some(Snap { bits: 8 }), &bad).unwrap_err().contains("r[1].x"));
    }

    #[test]
    fn placed_cases_lie_in_the_guard_band_and_tiles_in_the_viewport() {
        for vp in ["640x480+32", "-320,-240,640x480+32", "centred:65536x65536+64"] {
            placed_in_one(vp.parse().unwrap());
        }
        // A viewport away from the origin: the tile moves by whole tiles into it.
        let vp: Viewport = "-1000,-500,640x480".parse().unwrap();
        let t = tile_in_viewport(Tile::square(1e6, -40.0, 16.0), vp);
        assert!(vp.holds_tile(&t) && t.x1 - t.x0 == 16.0 && t.x0 == -376.0 && t.y0 == -40.0, "{t:?}");
        let t = tile_in_viewport(Tile::square(-5000.0, -5000.0, 16.0), vp);
        assert!(vp.holds_tile(&t) && t.x0 == -1000.0 && t.y0 == -500.0, "{t:?}");
    }

    fn placed_in_one(vp: Viewport) {
        let g = vp.guard_rect();
        let [x0, x1, _, _] = vp.rect();
        let mut placed = 0;
        for i in 0..64 {
            let regime = Regime::ALL[(i % 16) as usize];
            if let Some((c, _)) = place_case(5, i, regime, vp) {
                placed += 1;
                let f = footprint(&c.triangle).unwrap();
                assert!(f[0] >= g[0] && f[1] <= g[1] && f[2] >= g[2] && f[3] <= g[3], "{regime:?} {f:?}");
            } else {
                assert!(matches!(regime, Regime::BehindLens | Regime::Huge | Regime::HugeCoc), "{regime:?}");
            }
        }
        assert!(placed >= 40, "{vp}: {placed}");
        let t = tile_in_viewport(Tile::square(1e6, -40.0, 16.0), vp);
        assert!(vp.holds_tile(&t) && t.x1 - t.x0 == 16.0 && t.x1 as f64 <= x1 && t.x0 as f64 >= x0, "{vp}: {t:?}");
    }
}
