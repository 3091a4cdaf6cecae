//! The work after culling: a hardware-like coverage test of a sample in **f32** and
//! its shade, the per-sample price of every sample a culling test lets through (the
//! cost model in [`super::cost`] times it once per setting). For a sample (x, y, u, v,
//! t): the sheared vertices at the sample's (u, v, t), the three edge functions E_k
//! translated to the sample's (x, y), D = sum w_k E_k, covered when every E_k has the
//! strict sign of D (the model's rule evaluated in f32, not the exact oracle); for a
//! covered sample the hit depth N / D (N = sum E_k z_k) and a Gouraud shade (per-vertex
//! colours blended by the barycentrics E_k / sum E), as a depth test and a colour write
//! would use them.

use super::pattern::hash;
use crate::model::{Sample, Triangle};

/// Per-triangle values of the f32 coverage test.
pub struct Raster {
    q: [[f32; 4]; 3],
    d: [[f32; 4]; 3],
    c0: [f32; 3],
    dc: [f32; 3],
    k: f32,
    rgb: [[f32; 3]; 3],
}

impl Raster {
    pub fn new(tri: &Triangle, id: u64) -> Self {
        let d = std::array::from_fn(|i| std::array::from_fn(|j| tri.r[i][j] - tri.q[i][j]));
        let dc = std::array::from_fn(|i| tri.c1[i] - tri.c0[i]);
        let rgb = std::array::from_fn(|i| {
            let h = hash(&[id, i as u64]);
            [(h & 0xff) as f32, ((h >> 8) & 0xff) as f32, ((h >> 16) & 0xff) as f32]
        });
        Raster { q: tri.q, d, c0: tri.c0, dc, k: tri.k, rgb }
    }

    /// Covered (f32 rule) and, if so, the hit depth and packed colour.
    #[inline]
    pub fn shade(&self, s: &Sample) -> Option<(f32, u32)> {
        let mut p = [[0.0f32; 4]; 3];
        for (i, pi) in p.iter_mut().enumerate() {
            let c = self.c0[i] + s.t * self.dc[i];
            let w = self.q[i][3] + s.t * self.d[i][3];
            *pi = [
                self.q[i][0] + s.t * self.d[i][0] + s.u * c - s.x * w,
                self.q[i][1] + s.t * self.d[i][1] + self.k * s.v * c - s.y * w,
                self.q[i][2] + s.t * self.d[i][2],
                w,
            ];
        }
        let e = [
            p[1][0] * p[2][1] - p[1][1] * p[2][0],
            p[2][0] * p[0][1] - p[2][1] * p[0][0],
            p[0][0] * p[1][1] - p[0][1] * p[1][0],
        ];
        let d = p[0][3] * e[0] + p[1][3] * e[1] + p[2][3] * e[2];
        let inside = if d > 0.0 {
            e.iter().all(|&x| x > 0.0)
        } else if d < 0.0 {
            e.iter().all(|&x| x < 0.0)
        } else {
            false
        };
        if !inside {
            return None;
        }
        let n = e[0] * p[0][2] + e[1] * p[1][2] + e[2] * p[2][2];
        let sum = e[0] + e[1] + e[2];
        let ch =
            |k: usize| ((e[0] * self.rgb[0][k] + e[1] * self.rgb[1][k] + e[2] * self.rgb[2][k]) / sum) as u32 & 0xff;
        Some((n / d, ch(0) | ch(1) << 8 | ch(2) << 16))
    }
}
