//! A 5D sample.

use serde::{Deserialize, Serialize};

/// `(x, y)` in pixels (continuous), `(u, v)` in [-1, 1] on the lens, `t` in [0, 1].
/// Stored in f32 as a sample pattern in hardware would be.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    pub x: f32,
    pub y: f32,
    pub u: f32,
    pub v: f32,
    pub t: f32,
}

impl Sample {
    pub fn new(x: f32, y: f32, u: f32, v: f32, t: f32) -> Self {
        Sample { x, y, u, v, t }
    }
    /// The plain numbers the oracles take (exact).
    pub fn to_oracle(&self) -> [f64; 5] {
        [self.x as f64, self.y as f64, self.u as f64, self.v as f64, self.t as f64]
    }
}
