//! The samples: the whole screen's pattern, built once ([`SampleTable`]), and the
//! coverage of one triangle's region ([`Local`]), with the rows of a tile in both.

use super::geometry::PixelRect;
use super::pattern::Pattern;
use crate::bounds::SampleCols;
use crate::model::Sample;
use rayon::prelude::*;

/// The whole screen's sample pattern, pixel-major: the `spp` samples of pixel (px, py)
/// start at `(py * width + px) * spp`. Built once per run (every pixel's samples depend
/// only on the pattern, see [`pattern`]) and shared by every triangle, setting and method.
///
/// [`pattern`]: super::pattern
pub struct SampleTable {
    pub width: u32,
    pub height: u32,
    pub spp: usize,
    pub samples: Vec<Sample>,
    /// The samples' x, y, u, v and t side by side (the interval tests and the
    /// per-sample constraints run over these, see [`SampleTable::cols`]).
    pub cols: [Vec<f32>; 5],
}

impl SampleTable {
    /// The pattern over a `width x height` screen (rows built in parallel; the table
    /// does not depend on the thread count).
    pub fn new(pattern: &Pattern, width: u32, height: u32) -> Self {
        let rows: Vec<Vec<Sample>> = (0..height)
            .into_par_iter()
            .map(|py| {
                let mut v = Vec::with_capacity(width as usize * pattern.spp as usize);
                pattern.region(0, py, width - 1, py, &mut v);
                v
            })
            .collect();
        let samples = rows.concat();
        let cols = [
            samples.iter().map(|s| s.x).collect(),
            samples.iter().map(|s| s.y).collect(),
            samples.iter().map(|s| s.u).collect(),
            samples.iter().map(|s| s.v).collect(),
            samples.iter().map(|s| s.t).collect(),
        ];
        SampleTable { width, height, spp: pattern.spp as usize, samples, cols }
    }
    /// The `n` samples from `start` on, side by side.
    pub fn cols(&self, start: usize, n: usize) -> SampleCols<'_> {
        let c = |k: usize| &self.cols[k][start..start + n];
        SampleCols { x: c(0), y: c(1), u: c(2), v: c(3), t: c(4) }
    }
    /// Where pixel (px, py)'s samples start.
    pub fn start(&self, px: u32, py: u32) -> usize {
        (py as usize * self.width as usize + px as usize) * self.spp
    }
}

/// The coverage of the samples of a region (the union of a triangle's tiles of every
/// size), pixel-major like the [`SampleTable`]; the pixels outside the footprint are
/// not covered.
pub(super) struct Local {
    pub(super) rect: PixelRect,
    pub(super) spp: usize,
    pub(super) covered: Vec<bool>,
}

impl Local {
    pub(super) fn start(&self, px: u32, py: u32) -> usize {
        let w = (self.rect.x1 - self.rect.x0 + 1) as usize;
        ((py - self.rect.y0) as usize * w + (px - self.rect.x0) as usize) * self.spp
    }
}

/// The rows of a tile: per pixel row, the start of its samples in the table and in the
/// [`Local`] coverage, and the row's sample count.
pub(super) fn tile_rows(table: &SampleTable, local: &Local, p: &PixelRect, rows: &mut Vec<(usize, usize, usize)>) {
    rows.clear();
    let n = (p.x1 - p.x0 + 1) as usize * table.spp;
    for py in p.y0..=p.y1 {
        rows.push((table.start(p.x0, py), local.start(p.x0, py), n));
    }
}
