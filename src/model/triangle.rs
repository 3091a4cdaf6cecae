//! A moving, defocused triangle in homogeneous clip space.

use super::{finite, ModelError};
use serde::{Deserialize, Serialize};

/// Vertex i is `(x, y, z, w)` in clip space: `q[i]` at t = 0, `r[i]` at t = 1, moving
/// linearly `p_i(t) = (1-t) q_i + t r_i`. `c0[i]`, `c1[i]` are the signed circle of
/// confusion of vertex i at t = 0 and t = 1 (clip units, `c_i(t)` linear in t), and `k`
/// the aspect factor `fy/fx`. Seen from lens position (u, v), vertex i sits at
/// `p_i(t) + c_i(t) (u, k v, 0)`.
///
/// All values are `f32`, as a hardware unit would hold them. Degenerate geometry (zero
/// area, coincident vertices, w = 0, c = 0, vertices behind the lens) is valid input.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Triangle {
    pub q: [[f32; 4]; 3],
    pub r: [[f32; 4]; 3],
    pub c0: [f32; 3],
    pub c1: [f32; 3],
    pub k: f32,
}

/// Which of the sample dimensions a triangle really has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum Dims {
    /// Neither motion nor defocus: only (x, y) matter.
    Static,
    /// Coverage depends on t but not on (u, v).
    Motion,
    /// Coverage depends on (u, v) but not on t.
    Defocus,
    /// Both.
    Both,
}

impl Dims {
    pub fn has_time(self) -> bool {
        matches!(self, Dims::Motion | Dims::Both)
    }
    pub fn has_lens(self) -> bool {
        matches!(self, Dims::Defocus | Dims::Both)
    }
    pub fn name(self) -> &'static str {
        match self {
            Dims::Static => "static",
            Dims::Motion => "motion",
            Dims::Defocus => "defocus",
            Dims::Both => "both",
        }
    }
    pub const ALL: [Dims; 4] = [Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both];
}

const XYZW: [&str; 4] = ["x", "y", "z", "w"];

impl Triangle {
    /// A static, in-focus triangle from three clip-space vertices.
    pub fn fixed(v: [[f32; 4]; 3]) -> Self {
        Triangle { q: v, r: v, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 }
    }

    /// Checks every number; the error names the field and value.
    pub fn validate(&self) -> Result<(), ModelError> {
        for i in 0..3 {
            for (j, n) in XYZW.iter().enumerate() {
                finite(format!("q[{i}].{n}"), self.q[i][j])?;
                finite(format!("r[{i}].{n}"), self.r[i][j])?;
            }
            finite(format!("c0[{i}]"), self.c0[i])?;
            finite(format!("c1[{i}]"), self.c1[i])?;
        }
        finite("k", self.k)?;
        if self.k <= 0.0 {
            return Err(ModelError::OutOfRange {
                field: "k".into(),
                value: format!("{}", self.k),
                why: "the aspect factor fy/fx must be > 0",
            });
        }
        Ok(())
    }

    /// Which dimensions coverage depends on. A vertex whose position or CoC changes
    /// over the shutter makes time matter; any non-zero CoC makes the lens matter.
    pub fn dims(&self) -> Dims {
        let moving = self.q != self.r || self.c0 != self.c1;
        let defocus = self.c0.iter().chain(self.c1.iter()).any(|&c| c != 0.0);
        match (moving, defocus) {
            (false, false) => Dims::Static,
            (true, false) => Dims::Motion,
            (false, true) => Dims::Defocus,
            (true, true) => Dims::Both,
        }
    }

    /// Vertex i at time t, in f32 as hardware would compute it.
    pub fn at(&self, i: usize, t: f32) -> [f32; 4] {
        let (a, b) = (self.q[i], self.r[i]);
        [0, 1, 2, 3].map(|j| (1.0 - t) * a[j] + t * b[j])
    }

    /// CoC of vertex i at time t (f32).
    pub fn coc(&self, i: usize, t: f32) -> f32 {
        (1.0 - t) * self.c0[i] + t * self.c1[i]
    }

    /// The plain numbers the oracles take (f32 -> f64 is exact).
    pub fn to_oracle(&self) -> oracles::Tri {
        let f = |v: [f32; 4]| v.map(|x| x as f64);
        oracles::Tri {
            q: self.q.map(f),
            r: self.r.map(f),
            c0: self.c0.map(|x| x as f64),
            c1: self.c1.map(|x| x as f64),
            k: self.k as f64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_round_trip_is_bit_exact() {
        let mut t = Triangle::fixed([
            [0.1, -3.7e-12, 0.3, 1.0],
            [1e30, 2.0, 0.5, 7.0],
            [f32::MIN_POSITIVE / 8.0, 0.0, -0.0, 2.5],
        ]);
        t.r[1][0] = 0.33333334;
        t.c1 = [1e-40, -2.5, 123456.79];
        let s = serde_json::to_string(&t).unwrap();
        let back: Triangle = serde_json::from_str(&s).unwrap();
        for i in 0..3 {
            for j in 0..4 {
                assert_eq!(t.q[i][j].to_bits(), back.q[i][j].to_bits());
                assert_eq!(t.r[i][j].to_bits(), back.r[i][j].to_bits());
            }
            assert_eq!(t.c1[i].to_bits(), back.c1[i].to_bits());
        }
    }

    #[test]
    fn validation_names_field_and_value() {
        let mut t = Triangle::fixed([[0.0, 0.0, 0.0, 1.0]; 3]);
        assert!(t.validate().is_ok(), "degenerate geometry is valid input");
        t.r[2][3] = f32::NAN;
        let e = t.validate().unwrap_err().to_string();
        assert!(e.contains("r[2].w") && e.contains("NaN"), "{e}");
        t.r[2][3] = 1.0;
        t.k = -1.0;
        let e = t.validate().unwrap_err().to_string();
        assert!(e.contains("`k`") && e.contains("-1"), "{e}");
    }

    #[test]
    fn dims_follow_the_data() {
        let mut t = Triangle::fixed([[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]]);
        assert_eq!(t.dims(), Dims::Static);
        t.r[0][0] = 0.5;
        assert_eq!(t.dims(), Dims::Motion);
        t.r = t.q;
        t.c0 = [0.1; 3];
        t.c1 = [0.1; 3];
        assert_eq!(t.dims(), Dims::Defocus);
        t.c1[0] = 0.2;
        assert_eq!(t.dims(), Dims::Both);
    }
}
