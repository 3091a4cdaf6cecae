//! The thin-lens camera of the model.

use super::{finite, ModelError, Triangle};
use serde::{Deserialize, Serialize};

/// Camera space: +z forward, a thin lens of radius `radius` centred at the origin in
/// the plane z = 0, focal plane z = `focus`. Clip space: `x = fx X + cx Z`,
/// `y = fy Y + cy Z`, `w = Z`, and the depth row `z = (far Z - far near) / (far - near)`
/// (so z/w runs from 0 at `near` to 1 at `far`). Circle of confusion (signed, clip
/// units): `c(w) = a + b w` with `a = -fx R`, `b = fx R / F`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThinLens {
    pub fx: f32,
    pub fy: f32,
    pub cx: f32,
    pub cy: f32,
    pub radius: f32,
    pub focus: f32,
    pub near: f32,
    pub far: f32,
}

impl ThinLens {
    pub fn validate(&self) -> Result<(), ModelError> {
        for (n, v) in [
            ("fx", self.fx),
            ("fy", self.fy),
            ("cx", self.cx),
            ("cy", self.cy),
            ("radius", self.radius),
            ("focus", self.focus),
            ("near", self.near),
            ("far", self.far),
        ] {
            finite(format!("lens.{n}"), v)?;
        }
        let bad = |f: &str, v: f32, why| {
            Err(ModelError::OutOfRange { field: format!("lens.{f}"), value: format!("{v}"), why })
        };
        if self.radius < 0.0 {
            return bad("radius", self.radius, "a lens radius cannot be negative");
        }
        if self.focus <= 0.0 {
            return bad("focus", self.focus, "the focal plane must lie in front of the lens (focus > 0)");
        }
        if self.fx <= 0.0 {
            return bad("fx", self.fx, "the focal scale must be > 0");
        }
        if self.fy <= 0.0 {
            return bad("fy", self.fy, "the focal scale must be > 0");
        }
        if self.near >= self.far {
            return bad("far", self.far, "far must be greater than near");
        }
        Ok(())
    }
    /// `a = -fx R` (f32).
    pub fn a(&self) -> f32 {
        -self.fx * self.radius
    }
    /// `b = fx R / F` (f32).
    pub fn b(&self) -> f32 {
        self.fx * self.radius / self.focus
    }
    /// Aspect `k = fy / fx`.
    pub fn k(&self) -> f32 {
        self.fy / self.fx
    }
    /// CoC of a clip-space w, in f32.
    pub fn coc(&self, w: f32) -> f32 {
        self.a() + self.b() * w
    }
    /// Clip-space `(x, y, z, w)` of a camera-space point, in f32.
    pub fn clip(&self, p: [f32; 3]) -> [f32; 4] {
        let [x, y, z] = p;
        let depth = (self.far * z - self.far * self.near) / (self.far - self.near);
        [self.fx * x + self.cx * z, self.fy * y + self.cy * z, depth, z]
    }
    /// A triangle from camera-space vertices at t = 0 (`q`) and t = 1 (`r`), with the
    /// thin-lens CoC of each.
    pub fn triangle(&self, q: [[f32; 3]; 3], r: [[f32; 3]; 3]) -> Triangle {
        let q = q.map(|p| self.clip(p));
        let r = r.map(|p| self.clip(p));
        Triangle { q, r, c0: q.map(|p| self.coc(p[3])), c1: r.map(|p| self.coc(p[3])), k: self.k() }
    }
    /// Checks that a triangle's CoC and aspect are the ones this lens gives it (what
    /// makes a case physical, so that Embree can judge it too).
    pub fn check_matches(&self, t: &Triangle) -> Result<(), ModelError> {
        let mism = |field: String, have: f32, want: f32| ModelError::OutOfRange {
            field,
            value: format!("{have} (the lens gives {want})"),
            why: "a case with a lens must carry the thin-lens CoC c = a + b w of each vertex",
        };
        for i in 0..3 {
            if t.c0[i].to_bits() != self.coc(t.q[i][3]).to_bits() {
                return Err(mism(format!("c0[{i}]"), t.c0[i], self.coc(t.q[i][3])));
            }
            if t.c1[i].to_bits() != self.coc(t.r[i][3]).to_bits() {
                return Err(mism(format!("c1[{i}]"), t.c1[i], self.coc(t.r[i][3])));
            }
        }
        if t.k.to_bits() != self.k().to_bits() {
            return Err(mism("k".into(), t.k, self.k()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coc_is_zero_on_the_focal_plane() {
        let cam = ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 4.0, near: 0.1, far: 100.0 };
        assert_eq!(cam.coc(4.0), 0.0);
        assert!(cam.coc(8.0) > 0.0 && cam.coc(1.0) < 0.0);
    }

    #[test]
    fn negative_radius_is_refused_by_name() {
        let cam = ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: -0.5, focus: 4.0, near: 0.1, far: 100.0 };
        let e = cam.validate().unwrap_err().to_string();
        assert!(e.contains("lens.radius") && e.contains("-0.5"), "{e}");
    }
}
