//! The oracle's view of a triangle: plain numbers, as in the repository's `docs/model.md`.

/// A moving, defocused triangle in homogeneous clip space.
///
/// Vertex i is `(x, y, z, w)`: `q[i]` at t = 0, `r[i]` at t = 1, moving linearly.
/// `c0[i]`, `c1[i]` are its signed circle of confusion at t = 0 and t = 1 (clip-space
/// units), `k` the aspect factor `fy/fx`. Values are `f64`; callers holding `f32`
/// convert exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tri {
    pub q: [[f64; 4]; 3],
    pub r: [[f64; 4]; 3],
    pub c0: [f64; 3],
    pub c1: [f64; 3],
    pub k: f64,
}

impl Tri {
    /// The first non-finite number, named, if any. The oracles answer only finite input.
    pub fn check_finite(&self) -> Result<(), String> {
        for i in 0..3 {
            for (j, name) in ["x", "y", "z", "w"].iter().enumerate() {
                if !self.q[i][j].is_finite() {
                    return Err(format!("q[{i}].{name} = {} is not finite", self.q[i][j]));
                }
                if !self.r[i][j].is_finite() {
                    return Err(format!("r[{i}].{name} = {} is not finite", self.r[i][j]));
                }
            }
            if !self.c0[i].is_finite() {
                return Err(format!("c0[{i}] = {} is not finite", self.c0[i]));
            }
            if !self.c1[i].is_finite() {
                return Err(format!("c1[{i}] = {} is not finite", self.c1[i]));
            }
        }
        if !self.k.is_finite() {
            return Err(format!("k = {} is not finite", self.k));
        }
        Ok(())
    }
    /// True if no vertex moves.
    pub fn is_static(&self) -> bool {
        self.q == self.r && self.c0 == self.c1
    }
    /// True if every circle of confusion is zero (no defocus at any time).
    pub fn is_pinhole(&self) -> bool {
        self.c0.iter().chain(self.c1.iter()).all(|&c| c == 0.0)
    }
}
