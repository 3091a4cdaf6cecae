//! Scenes for the tightness measurement: a thin-lens camera, a screen of `width x
//! height` pixels, and objects whose triangles are given in camera space (+z forward,
//! the lens at the origin, see `docs/model.md`) in a rest pose, each object with
//! a seeded rigid motion. The three settings of Munkberg & Akenine-Möller 2012 (Table 1)
//! are derived from one scene:
//!
//! - `static`: the rest pose, lens radius 0 (a pinhole, no motion);
//! - `blur`: the shutter runs over motion time `tau` in [-1/2, 1/2]: vertex positions at
//!   t = 0 and t = 1 are the rigid poses at tau = -1/2 and tau = +1/2 (vertices move
//!   linearly between them, as the model requires), and the lens has the scene's radius R;
//! - `blur2` ("blur x 2"): twice the shutter (tau in [-1, 1]) and lens radius 2R.
//!
//! Procedural scenes are shaped like the papers' test scenes (which are not available):
//! `hairball` (10,000 thin camera-facing hair ribbons around a ball: sub-pixel to a few
//! pixels, like Laine's Hairball), `interior` (a room of large wall, floor and ceiling
//! triangles at varied depth plus a crate and a ball: like Sponza, tens of large
//! triangles), `forest` (a ground, ten trees of small leaf triangles swaying in the
//! wind and a medium low-poly walking character near the focal plane: like Fairy
//! Forest). Every draw comes from a `ChaCha8Rng` stream of the seed. Pixel amounts in
//! the documentation (motion, CoC) are for a screen 240 pixels high and scale with the
//! screen height.

use crate::cases::generate::rng_for;
use crate::model::{ThinLens, Triangle};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::path::Path;

/// A camera-space point.
pub type V3 = [f32; 3];

/// The blur setting of a run (Munkberg 2012 Table 1: static, blur, blur x 2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Setting {
    /// No motion, pinhole camera.
    #[default]
    Static,
    /// The scene's motion over the shutter and its lens radius.
    Blur,
    /// Twice the shutter time and twice the lens radius.
    Blur2,
}

impl Setting {
    pub const ALL: [Setting; 3] = [Setting::Static, Setting::Blur, Setting::Blur2];
    pub fn name(self) -> &'static str {
        match self {
            Setting::Static => "static",
            Setting::Blur => "blur",
            Setting::Blur2 => "blur2",
        }
    }
    /// Multiplier of the shutter length and of the lens radius.
    pub fn scale(self) -> f32 {
        match self {
            Setting::Static => 0.0,
            Setting::Blur => 1.0,
            Setting::Blur2 => 2.0,
        }
    }
}

/// A rigid motion over motion time `tau`: rotation by `tau * angle` about the unit
/// `axis` through `pivot`, then translation by `tau * shift` (camera space).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RigidMotion {
    pub pivot: V3,
    pub axis: V3,
    pub angle: f32,
    pub shift: V3,
}

impl RigidMotion {
    pub fn none() -> Self {
        RigidMotion { pivot: [0.0; 3], axis: [0.0, 1.0, 0.0], angle: 0.0, shift: [0.0; 3] }
    }
    /// The pose of `p` at motion time `tau` (Rodrigues' rotation, in f64, rounded once).
    pub fn apply(&self, p: V3, tau: f32) -> V3 {
        if tau == 0.0 {
            return p;
        }
        let th = (tau * self.angle) as f64;
        let (s, c) = th.sin_cos();
        let k = self.axis.map(|x| x as f64);
        let v: [f64; 3] = std::array::from_fn(|i| p[i] as f64 - self.pivot[i] as f64);
        let kxv = [k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]];
        let kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
        std::array::from_fn(|i| {
            let rot = v[i] * c + kxv[i] * s + k[i] * kv * (1.0 - c);
            (self.pivot[i] as f64 + rot + tau as f64 * self.shift[i] as f64) as f32
        })
    }
}

/// An object: triangles in their rest pose, one rigid motion and an optional per-vertex
/// wobble (non-rigid).
#[derive(Clone, Debug)]
pub struct Object {
    pub name: String,
    pub tris: Vec<[V3; 3]>,
    pub motion: RigidMotion,
    /// Per-vertex wobble amplitude (camera-space units, 0 for none): at motion time tau
    /// a vertex moves by `tau * wobble` along a unit direction drawn from a hash of its
    /// rest position ([`wobble_dir`]), so vertices shared by triangles move together.
    pub wobble: f32,
}

/// The wobble direction of a rest-pose vertex: a unit vector from a hash of its
/// coordinates' bits.
pub fn wobble_dir(p: V3) -> V3 {
    let h = |k: u64| {
        let x = super::pattern::hash(&[k, p[0].to_bits() as u64, p[1].to_bits() as u64, p[2].to_bits() as u64]);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for k in 0..64u64 {
        let v = [h(3 * k), h(3 * k + 1), h(3 * k + 2)];
        let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if l2 > 1e-4 && l2 <= 1.0 {
            let l = l2.sqrt();
            return v.map(|x| (x / l) as f32);
        }
    }
    [0.0, 1.0, 0.0]
}

impl Object {
    /// The pose of rest vertex `p` at motion time `tau`.
    pub fn pose(&self, p: V3, tau: f32) -> V3 {
        let q = self.motion.apply(p, tau);
        if self.wobble == 0.0 || tau == 0.0 {
            return q;
        }
        let d = wobble_dir(p);
        std::array::from_fn(|i| q[i] + tau * self.wobble * d[i])
    }
}

/// A scene: camera (its `radius` is the lens radius of the `blur` setting), screen and
/// objects.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub camera: ThinLens,
    pub objects: Vec<Object>,
}

impl Scene {
    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.tris.len()).sum()
    }
    /// The lens of a setting: radius 0, R or 2R.
    pub fn lens(&self, s: Setting) -> ThinLens {
        ThinLens { radius: self.camera.radius * s.scale(), ..self.camera }
    }
    /// Camera-space vertices at t = 0 and t = 1 of every triangle, object by object.
    pub fn camera_space(&self, s: Setting) -> Vec<([V3; 3], [V3; 3])> {
        let half = 0.5 * s.scale();
        let mut out = Vec::with_capacity(self.triangle_count());
        for o in &self.objects {
            for t in &o.tris {
                out.push((t.map(|p| o.pose(p, -half)), t.map(|p| o.pose(p, half))));
            }
        }
        out
    }
    /// The clip-space triangles of a setting (thin-lens CoC per vertex).
    pub fn triangles(&self, s: Setting) -> Vec<Triangle> {
        let lens = self.lens(s);
        self.camera_space(s).into_iter().map(|(q, r)| lens.triangle(q, r)).collect()
    }
    /// Mean screen area (pixels) of the triangles in their rest pose that lie in front
    /// of the lens and overlap the screen (the papers quote this per scene).
    pub fn mean_area_px(&self) -> f64 {
        let cam = &self.camera;
        let (mut sum, mut n) = (0.0, 0usize);
        for o in &self.objects {
            for t in &o.tris {
                if t.iter().any(|p| p[2] <= 0.0) {
                    continue;
                }
                let pr = t.map(|p| {
                    let c = cam.clip(p);
                    [c[0] as f64 / c[3] as f64, c[1] as f64 / c[3] as f64]
                });
                let (xs, ys) = (pr.map(|p| p[0]), pr.map(|p| p[1]));
                let on = xs.iter().cloned().fold(f64::INFINITY, f64::min) < self.width as f64
                    && xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max) > 0.0
                    && ys.iter().cloned().fold(f64::INFINITY, f64::min) < self.height as f64
                    && ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max) > 0.0;
                if on {
                    let a = 0.5
                        * ((pr[1][0] - pr[0][0]) * (pr[2][1] - pr[0][1])
                            - (pr[2][0] - pr[0][0]) * (pr[1][1] - pr[0][1]))
                            .abs();
                    sum += a;
                    n += 1;
                }
            }
        }
        if n == 0 {
            0.0
        } else {
            sum / n as f64
        }
    }
}

/// The procedural scene names.
pub const NAMES: [&str; 3] = ["hairball", "interior", "forest"];

/// A procedural scene by name, or an OBJ mesh when `name` ends in `.obj`.
pub fn by_name(name: &str, seed: u64, width: u32, height: u32) -> anyhow::Result<Scene> {
    anyhow::ensure!(width >= 1 && height >= 1, "the screen must be at least 1x1 pixels (got {width}x{height})");
    match name {
        "hairball" => Ok(hairball(seed, width, height)),
        "interior" => Ok(interior(seed, width, height)),
        "forest" => Ok(forest(seed, width, height)),
        _ if name.to_ascii_lowercase().ends_with(".obj") => from_obj(Path::new(name), seed, width, height),
        _ => anyhow::bail!("--scene {name}: not a scene; use one of {} or a FILE.obj", NAMES.join(", ")),
    }
}

// ---------------------------------------------------------------------------
// Building blocks

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(s: f32, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn norm(a: V3) -> V3 {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if l > 0.0 {
        scale(1.0 / l, a)
    } else {
        [0.0, 1.0, 0.0]
    }
}
pub(super) fn unit_vector(rng: &mut ChaCha8Rng) -> V3 {
    loop {
        let v = [rng.gen_range(-1.0f32..1.0), rng.gen_range(-1.0f32..1.0), rng.gen_range(-1.0f32..1.0)];
        let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if l2 > 1e-4 && l2 <= 1.0 {
            return norm(v);
        }
    }
}

/// Pixel amounts below (motion, CoC) are given for a screen 240 pixels high and scale
/// with the screen height, so a scene looks the same at any resolution (rotations
/// scale by themselves: the focal length grows with the screen).
pub(super) fn px(height: u32) -> f32 {
    height as f32 / 240.0
}

/// A pinhole camera for the screen with vertical field of view `fov_y` (degrees),
/// square pixels (k = 1), the principal point at the screen centre.
pub(super) fn pinhole(width: u32, height: u32, fov_y: f64) -> ThinLens {
    let fy = (0.5 * height as f64 / (0.5 * fov_y.to_radians()).tan()) as f32;
    ThinLens {
        fx: fy,
        fy,
        cx: 0.5 * width as f32,
        cy: 0.5 * height as f32,
        radius: 0.0,
        focus: 1.0,
        near: 0.1,
        far: 1000.0,
    }
}

/// Focus at `focus` and the lens radius that gives a CoC radius of `coc_px` pixels at
/// depth `z_ref` (CoC in pixels = fx R |1/F - 1/z|).
pub(super) fn with_lens(cam: ThinLens, focus: f32, coc_px: f32, z_ref: f32) -> ThinLens {
    let d = (1.0 / focus - 1.0 / z_ref).abs().max(1e-6);
    ThinLens { focus, radius: coc_px / (cam.fx * d), ..cam }
}

/// A seeded motion around `pivot` at depth `depth`: a screen-plane shift of up to
/// `px` pixels (random direction, 50-100 %), a depth shift of up to `dz_frac` of the
/// depth, and a rotation of up to `max_angle` radians about a random axis.
pub(super) fn seeded_motion(
    rng: &mut ChaCha8Rng,
    cam: &ThinLens,
    pivot: V3,
    px: f32,
    dz_frac: f32,
    max_angle: f32,
) -> RigidMotion {
    let depth = pivot[2].max(0.1);
    let dir = rng.gen_range(0.0f32..std::f32::consts::TAU);
    let m = px * rng.gen_range(0.5f32..1.0) * depth / cam.fx;
    let shift = [m * dir.cos(), m * dir.sin(), dz_frac * depth * rng.gen_range(-1.0f32..1.0)];
    RigidMotion { pivot, axis: unit_vector(rng), angle: max_angle * rng.gen_range(-1.0f32..1.0), shift }
}

/// Two triangles of the quad a, b, c, d (in order around it).
fn quad(out: &mut Vec<[V3; 3]>, a: V3, b: V3, c: V3, d: V3) {
    out.push([a, b, c]);
    out.push([a, c, d]);
}

/// A quad subdivided into `nu x nv` quads: corner `o`, edges `eu`, `ev`.
fn grid(out: &mut Vec<[V3; 3]>, o: V3, eu: V3, ev: V3, nu: u32, nv: u32) {
    let at = |i: u32, j: u32| add(o, add(scale(i as f32 / nu as f32, eu), scale(j as f32 / nv as f32, ev)));
    for j in 0..nv {
        for i in 0..nu {
            quad(out, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
}

/// An axis-aligned box (12 triangles).
fn cuboid(out: &mut Vec<[V3; 3]>, lo: V3, hi: V3) {
    let p = |x: usize, y: usize, z: usize| [[lo[0], hi[0]][x], [lo[1], hi[1]][y], [lo[2], hi[2]][z]];
    quad(out, p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0));
    quad(out, p(0, 0, 1), p(0, 1, 1), p(1, 1, 1), p(1, 0, 1));
    quad(out, p(0, 0, 0), p(0, 1, 0), p(0, 1, 1), p(0, 0, 1));
    quad(out, p(1, 0, 0), p(1, 0, 1), p(1, 1, 1), p(1, 1, 0));
    quad(out, p(0, 0, 0), p(0, 0, 1), p(1, 0, 1), p(1, 0, 0));
    quad(out, p(0, 1, 0), p(1, 1, 0), p(1, 1, 1), p(0, 1, 1));
}

/// A UV sphere with `seg` segments around and `rings` rings.
fn sphere(out: &mut Vec<[V3; 3]>, c: V3, r: V3, seg: u32, rings: u32) {
    let at = |i: u32, j: u32| {
        let th = std::f32::consts::PI * j as f32 / rings as f32;
        let ph = std::f32::consts::TAU * i as f32 / seg as f32;
        [c[0] + r[0] * th.sin() * ph.cos(), c[1] - r[1] * th.cos(), c[2] + r[2] * th.sin() * ph.sin()]
    };
    for j in 0..rings {
        for i in 0..seg {
            let (a, b, cc, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if j == 0 {
                out.push([a, cc, d]);
            } else if j == rings - 1 {
                out.push([a, b, cc]);
            } else {
                quad(out, a, b, cc, d);
            }
        }
    }
}

/// A vertical prism with `n` sides between heights y0 and y1 (sides only).
fn prism(out: &mut Vec<[V3; 3]>, c: V3, radius: f32, y0: f32, y1: f32, n: u32) {
    let at = |i: u32, y: f32| {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        [c[0] + radius * a.cos(), y, c[2] + radius * a.sin()]
    };
    for i in 0..n {
        quad(out, at(i, y0), at(i + 1, y0), at(i + 1, y1), at(i, y1));
    }
}

// ---------------------------------------------------------------------------
// The procedural scenes

/// Hairball: 1,000 hair strands of 5 segments, each segment a thin ribbon facing the
/// camera (2 triangles): 10,000 triangles of 0.1-5 px^2, around a ball 6 units away.
/// One object; it spins and drifts. Focus on the front of the ball; R gives a CoC of
/// 3 px at its back.
pub fn hairball(seed: u64, width: u32, height: u32) -> Scene {
    let mut rng = rng_for(seed, 0x4a1b);
    let cam = pinhole(width, height, 40.0);
    let centre: V3 = [0.0, 0.0, 6.0];
    let mut tris = Vec::with_capacity(10_000);
    for _ in 0..1000 {
        let d = unit_vector(&mut rng);
        let mut p = add(centre, scale(0.5, d));
        let mut dir = norm(add(d, scale(0.4, unit_vector(&mut rng))));
        let seg_len = rng.gen_range(0.8f32..1.2) / 5.0;
        let w0 = rng.gen_range(0.008f32..0.016);
        for k in 0..5 {
            let next = add(p, scale(seg_len, dir));
            let side = norm(cross(dir, norm(p)));
            let (wa, wb) = (w0 * (1.0 - 0.15 * k as f32), w0 * (1.0 - 0.15 * (k + 1) as f32));
            quad(
                &mut tris,
                sub(p, scale(wa, side)),
                add(p, scale(wa, side)),
                add(next, scale(wb, side)),
                sub(next, scale(wb, side)),
            );
            p = next;
            dir = norm(add(dir, scale(0.35, unit_vector(&mut rng))));
        }
    }
    let motion = seeded_motion(&mut rng, &cam, centre, 6.0 * px(height), 0.02, 0.08);
    Scene {
        name: "hairball".into(),
        width,
        height,
        camera: with_lens(cam, 5.0, 3.0 * px(height), 7.6),
        objects: vec![Object { name: "hairball".into(), tris, motion, wobble: 0.0 }],
    }
}

/// Interior: a room (floor and ceiling 2x4 quads, side walls 4 quads each, back wall
/// 2x2, two pillars) 1.5 to 14 units deep, panning slowly (the camera's motion, as a
/// rigid motion of the room about the lens), a crate and a ball with motions of their
/// own: 156 triangles, most of them hundreds to thousands of pixels. Focus at depth 6;
/// R gives a CoC of 5 px at the back wall.
pub fn interior(seed: u64, width: u32, height: u32) -> Scene {
    let mut rng = rng_for(seed, 0x1e7e);
    let cam = pinhole(width, height, 60.0);
    let (x0, x1, y0, y1, z0, z1) = (-4.0f32, 4.0f32, -2.2f32, 2.2f32, 1.5f32, 14.0f32);
    let mut room = Vec::new();
    grid(&mut room, [x0, y1, z0], [x1 - x0, 0.0, 0.0], [0.0, 0.0, z1 - z0], 2, 4); // floor (+y is down on screen)
    grid(&mut room, [x0, y0, z0], [0.0, 0.0, z1 - z0], [x1 - x0, 0.0, 0.0], 4, 2); // ceiling
    grid(&mut room, [x0, y0, z0], [0.0, y1 - y0, 0.0], [0.0, 0.0, z1 - z0], 1, 4); // left wall
    grid(&mut room, [x1, y0, z0], [0.0, 0.0, z1 - z0], [0.0, y1 - y0, 0.0], 4, 1); // right wall
    grid(&mut room, [x0, y0, z1], [x1 - x0, 0.0, 0.0], [0.0, y1 - y0, 0.0], 2, 2); // back wall
    cuboid(&mut room, [-2.4, y0, 7.0], [-1.9, y1, 7.5]);
    cuboid(&mut room, [1.9, y0, 9.0], [2.4, y1, 9.5]);
    let pan = RigidMotion {
        pivot: [0.0, 0.0, 0.0],
        axis: norm([rng.gen_range(-0.2f32..0.2), 1.0, rng.gen_range(-0.2f32..0.2)]),
        angle: rng.gen_range(0.012f32..0.02) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 },
        shift: [0.0, 0.0, rng.gen_range(-0.15f32..0.15)],
    };
    let mut crate_ = Vec::new();
    cuboid(&mut crate_, [0.4, 1.0, 4.5], [1.6, y1, 5.7]);
    let mut ball = Vec::new();
    sphere(&mut ball, [-1.0, 1.5, 6.0], [0.7, 0.7, 0.7], 8, 5);
    let crate_motion = seeded_motion(&mut rng, &cam, [1.0, 1.6, 5.1], 8.0 * px(height), 0.03, 0.1);
    let ball_motion = seeded_motion(&mut rng, &cam, [-1.0, 1.5, 6.0], 12.0 * px(height), 0.05, 0.6);
    Scene {
        name: "interior".into(),
        width,
        height,
        camera: with_lens(cam, 6.0, 5.0 * px(height), z1),
        objects: vec![
            Object { name: "room".into(), tris: room, motion: pan, wobble: 0.0 },
            Object { name: "crate".into(), tris: crate_, motion: crate_motion, wobble: 0.0 },
            Object { name: "ball".into(), tris: ball, motion: ball_motion, wobble: 0.0 },
        ],
    }
}

/// Forest: a ground (4x6 quads, 2 to 40 units deep), ten trees (a 6-sided trunk and a
/// crown of 280 leaf triangles of 0.12-0.22 units, randomly oriented: 0.5-10 px each),
/// each swaying about its base, and a low-poly character (head, torso, arms, legs:
/// 212 triangles, 5.5 units away) walking across; the camera drifts (a shift shared by
/// every object). 3,180 triangles. Focus on the character; R gives a CoC of 4 px at
/// depth 30.
pub fn forest(seed: u64, width: u32, height: u32) -> Scene {
    let mut rng = rng_for(seed, 0xf0e5);
    let cam = pinhole(width, height, 50.0);
    let ground_y = 1.6f32;
    let drift_px = 4.0 * px(height);
    let dir = rng.gen_range(0.0f32..std::f32::consts::TAU);
    // A camera-space shift: its pixel motion is drift_px at depth 10 (parallax elsewhere).
    let drift = scale(drift_px * 10.0 / cam.fx, [dir.cos(), dir.sin(), 0.0]);
    let with_drift = |mut m: RigidMotion| {
        m.shift = add(m.shift, drift);
        m
    };
    let mut objects = Vec::new();
    let mut ground = Vec::new();
    grid(&mut ground, [-14.0, ground_y, 2.0], [28.0, 0.0, 0.0], [0.0, 0.0, 38.0], 4, 6);
    objects.push(Object { name: "ground".into(), tris: ground, motion: with_drift(RigidMotion::none()), wobble: 0.0 });
    for k in 0..10 {
        let base: V3 = [rng.gen_range(-7.0f32..7.0), ground_y, rng.gen_range(7.0f32..32.0)];
        let height_t = rng.gen_range(2.5f32..4.0);
        let mut tree = Vec::new();
        prism(&mut tree, base, 0.15, ground_y - height_t * 0.7, ground_y, 6);
        let crown: V3 = [base[0], ground_y - height_t, base[2]];
        for _ in 0..280 {
            let off = loop {
                let o = [rng.gen_range(-1.0f32..1.0), rng.gen_range(-1.0f32..1.0), rng.gen_range(-1.0f32..1.0)];
                if o[0] * o[0] + o[1] * o[1] + o[2] * o[2] <= 1.0 {
                    break o;
                }
            };
            let c = add(crown, [1.3 * off[0], 1.0 * off[1], 1.3 * off[2]]);
            let size = rng.gen_range(0.12f32..0.22);
            let (a, b) = (unit_vector(&mut rng), unit_vector(&mut rng));
            let n = norm(cross(a, b));
            let e1 = norm(a);
            let e2 = cross(n, e1);
            tree.push([
                add(c, scale(size, e1)),
                add(c, scale(size, add(scale(-0.5, e1), scale(0.6, e2)))),
                add(c, scale(size, add(scale(-0.4, e1), scale(-0.7, e2)))),
            ]);
        }
        let sway = RigidMotion {
            pivot: base,
            axis: norm([rng.gen_range(-1.0f32..1.0), 0.0, rng.gen_range(-1.0f32..1.0)]),
            angle: rng.gen_range(0.02f32..0.06),
            shift: [0.0; 3],
        };
        objects.push(Object { name: format!("tree-{k}"), tris: tree, motion: with_drift(sway), wobble: 0.0 });
    }
    // The character: feet on the ground at depth 5.5.
    let (cx, cz) = (0.6f32, 5.5f32);
    let mut body = Vec::new();
    sphere(&mut body, [cx, ground_y - 1.62, cz], [0.13, 0.15, 0.13], 10, 6); // head: 100
    prism(&mut body, [cx, 0.0, cz], 0.2, ground_y - 1.45, ground_y - 0.85, 8); // torso: 16
    sphere(&mut body, [cx, ground_y - 0.85, cz], [0.2, 0.08, 0.16], 8, 4); // hips: 32
    for (dx, y0, y1) in [(-0.28f32, 1.45f32, 0.95f32), (0.28, 1.45, 0.95), (-0.1, 0.85, 0.0), (0.1, 0.85, 0.0)] {
        cuboid(&mut body, [cx + dx - 0.05, ground_y - y0, cz - 0.05], [cx + dx + 0.05, ground_y - y1, cz + 0.05]);
    } // limbs: 48
    let walk = seeded_motion(&mut rng, &cam, [cx, ground_y - 0.9, cz], 14.0 * px(height), 0.03, 0.12);
    objects.push(Object { name: "character".into(), tris: body, motion: with_drift(walk), wobble: 0.0 });
    Scene { name: "forest".into(), width, height, camera: with_lens(cam, cz, 4.0 * px(height), 30.0), objects }
}

/// An OBJ mesh with the default controls (see [`super::mesh`]).
pub fn from_obj(path: &Path, seed: u64, width: u32, height: u32) -> anyhow::Result<Scene> {
    Ok(super::mesh::from_obj_with(path, seed, width, height, &super::mesh::MeshControls::default())?.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_are_seeded_and_in_front_of_the_lens() {
        for name in NAMES {
            let a = by_name(name, 3, 160, 120).unwrap();
            let b = by_name(name, 3, 160, 120).unwrap();
            let c = by_name(name, 4, 160, 120).unwrap();
            assert_eq!(a.camera_space(Setting::Blur2), b.camera_space(Setting::Blur2), "{name}");
            assert_ne!(a.camera_space(Setting::Blur2), c.camera_space(Setting::Blur2), "{name} ignores the seed");
            for s in Setting::ALL {
                for (q, r) in a.camera_space(s) {
                    assert!(q.iter().chain(r.iter()).all(|p| p[2] > 0.1), "{name} {s:?}: a vertex behind the lens");
                }
            }
            assert!(a.mean_area_px() > 0.0);
        }
        assert_eq!(hairball(1, 160, 120).triangle_count(), 10_000);
        assert_eq!(forest(1, 160, 120).triangle_count(), 3180);
        assert_eq!(interior(1, 160, 120).triangle_count(), 156);
    }

    #[test]
    fn settings_scale_shutter_and_lens() {
        let s = forest(1, 160, 120);
        assert_eq!(s.lens(Setting::Static).radius, 0.0);
        assert_eq!(s.lens(Setting::Blur2).radius, 2.0 * s.lens(Setting::Blur).radius);
        for (q, r) in s.camera_space(Setting::Static) {
            assert_eq!(q, r);
        }
        // The blur2 chord is twice the blur chord for a pure translation (the ground).
        let (b, b2) = (s.camera_space(Setting::Blur)[0], s.camera_space(Setting::Blur2)[0]);
        for i in 0..3 {
            for j in 0..3 {
                let (d1, d2) = (b.1[i][j] - b.0[i][j], b2.1[i][j] - b2.0[i][j]);
                assert!((d2 - 2.0 * d1).abs() <= 1e-5 * (1.0 + d1.abs()), "{d1} {d2}");
            }
        }
        for t in s.triangles(Setting::Blur) {
            let cam = s.lens(Setting::Blur);
            cam.check_matches(&t).unwrap();
        }
    }
}
