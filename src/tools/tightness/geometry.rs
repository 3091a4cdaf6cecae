//! Screen geometry: where a triangle's samples can be covered ([`footprint`]), the tiles
//! of a size over a pixel rectangle, and a tile's pixels and rectangle.

use crate::model::{Tile, Triangle};
use serde::Serialize;

/// An inclusive rectangle of pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelRect {
    pub fn pixels(&self) -> u64 {
        (self.x1 - self.x0 + 1) as u64 * (self.y1 - self.y0 + 1) as u64
    }
}

/// Where a triangle's samples can be covered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Footprint {
    /// Every covered sample lies in these pixels.
    Region(PixelRect),
    /// A vertex at w <= 0 (or a non-finite projection): the whole screen is traversed.
    WholeScreen,
    /// The footprint misses the screen: nothing to do.
    OffScreen,
}

/// The pixels holding every interior-covered sample of the triangle: its screen AABB
/// over the lens corners (u, v = ±1) and shutter ends (t = 0, 1), in f64 with a margin
/// of 1e-9 relative, clipped to the `width x height` screen (pixel p holds x in [p, p+1)).
pub fn footprint(tri: &Triangle, width: u32, height: u32) -> Footprint {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (p, c) in [(&tri.q, &tri.c0), (&tri.r, &tri.c1)] {
        for i in 0..3 {
            let w = p[i][3] as f64;
            if w.is_nan() || w <= 0.0 {
                return Footprint::WholeScreen;
            }
            for s in [-1.0, 1.0] {
                let cx = s * c[i] as f64;
                let cy = s * tri.k as f64 * c[i] as f64;
                let (x, y) = ((p[i][0] as f64 + cx) / w, (p[i][1] as f64 + cy) / w);
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if ![x0, x1, y0, y1].iter().all(|v| v.is_finite()) {
        return Footprint::WholeScreen;
    }
    let m = |v: f64| 1e-9 * (v.abs() + 1.0);
    let (x0, x1, y0, y1) = (x0 - m(x0), x1 + m(x1), y0 - m(y0), y1 + m(y1));
    let (w, h) = (width as f64, height as f64);
    if x1 < 0.0 || y1 < 0.0 || x0 >= w || y0 >= h {
        return Footprint::OffScreen;
    }
    let clamp = |v: f64, n: f64| v.floor().clamp(0.0, n - 1.0) as u32;
    Footprint::Region(PixelRect { x0: clamp(x0, w), y0: clamp(y0, h), x1: clamp(x1, w), y1: clamp(y1, h) })
}

/// The tiles of size `s` overlapping `r`: inclusive tile index ranges (tx0, ty0, tx1, ty1).
pub fn tile_range(r: &PixelRect, s: u32) -> (u32, u32, u32, u32) {
    (r.x0 / s, r.y0 / s, r.x1 / s, r.y1 / s)
}

/// The pixels of tile (tx, ty) of size s, clipped to the screen (inclusive).
pub fn tile_pixels(tx: u32, ty: u32, s: u32, width: u32, height: u32) -> PixelRect {
    PixelRect { x0: tx * s, y0: ty * s, x1: ((tx + 1) * s).min(width) - 1, y1: ((ty + 1) * s).min(height) - 1 }
}

/// The tile rectangle a method is asked about (continuous pixel coordinates).
pub fn tile_of(p: &PixelRect) -> Tile {
    Tile { x0: p.x0 as f32, y0: p.y0 as f32, x1: (p.x1 + 1) as f32, y1: (p.y1 + 1) as f32 }
}
