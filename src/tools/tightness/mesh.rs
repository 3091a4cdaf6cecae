//! OBJ scenes and their controls: camera, lens and motion for a user's mesh, so the
//! settings that stress culling tests (perspective motion towards the camera, a focal
//! plane through the mesh, non-rigid motion) can be reproduced on any asset.
//!
//! The mesh (every object and group of the file, faces triangulated as fans, see
//! [`super::obj`]) is viewed from the front: turned 180 degrees about x (OBJ's +y up and
//! -z forward become the camera's -y up and +z forward), its bounding sphere (centre c,
//! radius r) centred at depth `D = distance * 1.15 r / sin(half the smaller field of
//! view)` (distance 1: the mesh fills the view). The lens focuses at `focus` (default:
//! the plane through the mesh's centre, depth D; `--focus-at X` puts it at D + X r, X in
//! [-1, 1] from the mesh's nearest to its farthest point); its radius is `--lens-radius`
//! or, by default, the radius giving a circle of confusion of 4 px (screen 240 px high)
//! at depth D + r (at D - r when the focus lies behind the centre). The blur setting's lens has that radius; blur2 twice it.
//!
//! Motion over the shutter (motion time tau in [-1/2, 1/2] for blur, [-1, 1] for blur2,
//! see [`super::scene`]), a comma-separated list of components (`--motion`):
//! - `rigid`: a seeded screen-plane shift of `--shift-px` px (50-100 %, random
//!   direction), a depth shift of up to 2 % of D and a rotation about a random axis
//!   moving the rim up to 8 px (the default motion);
//! - `dolly`: the mesh moves towards the camera by `--dolly` times D over tau in
//!   [-1/2, 1/2] (perspective motion: the screen footprint grows over the shutter);
//! - `rotate`: a rotation of `--rotate-deg` degrees about a seeded axis through the
//!   mesh's centre (replacing rigid's rotation);
//! - `wobble`: every vertex moves by up to `--wobble` times r along its own direction
//!   (non-rigid; shared vertices move together, see [`super::scene::wobble_dir`]);
//! - `none`: no motion (the blur settings then show defocus only).
//!
//! Every random draw comes from a `ChaCha8Rng` stream of the seed, in a fixed order, so
//! the same file, seed and controls give the same scene; the values used are recorded
//! in the report ([`MeshSettings`]).

use super::obj;
use super::scene::{pinhole, px, seeded_motion, unit_vector, with_lens, Object, RigidMotion, Scene, V3};
use crate::cases::generate::rng_for;
use anyhow::{bail, ensure, Result};
use rand::Rng;
use serde::Serialize;
use std::path::Path;

/// Camera, lens and motion flags of an OBJ scene (`cullproof tightness --scene FILE.obj`).
#[derive(clap::Args, Debug, Clone, Default, PartialEq)]
pub struct MeshControls {
    /// OBJ scenes: vertical field of view in degrees (1 to 170; default 45).
    #[arg(long)]
    pub fov: Option<f64>,
    /// OBJ scenes: camera distance as a multiple of the distance at which the mesh fills
    /// the view (0.05 to 100; default 1; below about 0.9 the camera is inside the
    /// mesh's bounding sphere and vertices may lie behind the lens).
    #[arg(long)]
    pub distance: Option<f64>,
    /// OBJ scenes: the blur setting's lens radius in camera-space units (>= 0; default:
    /// a circle of confusion of 4 px at the back of the mesh).
    #[arg(long)]
    pub lens_radius: Option<f64>,
    /// OBJ scenes: focal distance in camera-space units (> 0; default: the mesh's centre).
    #[arg(long, conflicts_with = "focus_at")]
    pub focus: Option<f64>,
    /// OBJ scenes: the focal plane through the mesh, -1 (its nearest point) to 1 (its
    /// farthest); 0 is its centre.
    #[arg(long)]
    pub focus_at: Option<f64>,
    /// OBJ scenes: motion components, comma-separated: rigid, dolly, rotate, wobble, or
    /// none (default: rigid).
    #[arg(long)]
    pub motion: Option<String>,
    /// OBJ scenes, `rigid`: screen-plane shift over the shutter in pixels (0 to 1000;
    /// default 10, for a screen 240 px high).
    #[arg(long)]
    pub shift_px: Option<f64>,
    /// OBJ scenes, `dolly`: distance travelled towards the camera over the shutter, as a
    /// fraction of the camera distance (0 to 1.5; default 0.3).
    #[arg(long)]
    pub dolly: Option<f64>,
    /// OBJ scenes, `rotate`: rotation over the shutter in degrees (-360 to 360; default 30).
    #[arg(long)]
    pub rotate_deg: Option<f64>,
    /// OBJ scenes, `wobble`: per-vertex displacement over the shutter as a fraction of
    /// the mesh's bounding radius (0 to 1; default 0.02).
    #[arg(long)]
    pub wobble: Option<f64>,
}

/// The camera, lens and motion an OBJ scene was built with (in the JSON report).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshSettings {
    /// The mesh file as given.
    pub path: String,
    pub fov_deg: f64,
    pub distance: f64,
    /// Depth of the mesh's centre (camera-space units).
    pub depth: f64,
    /// Radius of the mesh's bounding sphere.
    pub radius: f64,
    pub lens_radius: f64,
    pub focus: f64,
    pub motion: Vec<String>,
    pub shift_px: f64,
    pub dolly: f64,
    pub rotate_deg: Option<f64>,
    pub wobble: f64,
    /// The rigid motion drawn (pivot, axis, angle over the shutter, shift).
    pub rigid: RigidMotion,
}

impl MeshSettings {
    /// One line for the report's notes.
    pub fn describe(&self) -> String {
        format!(
            "fov {} deg, mesh centre at depth {:.4} (distance x{}), bounding radius {:.4}, lens radius {:.5}, focus \
             {:.4}, motion {} (shift {} px, dolly {}, rotate {}, wobble {})",
            self.fov_deg,
            self.depth,
            self.distance,
            self.radius,
            self.lens_radius,
            self.focus,
            self.motion.join("+"),
            self.shift_px,
            self.dolly,
            self.rotate_deg.map(|d| format!("{d} deg")).unwrap_or_else(|| "-".into()),
            self.wobble
        )
    }
}

const MOTIONS: [&str; 5] = ["rigid", "dolly", "rotate", "wobble", "none"];

impl MeshControls {
    /// The flags that were given, by name.
    fn given(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        let flags: [(&str, bool); 10] = [
            ("--fov", self.fov.is_some()),
            ("--distance", self.distance.is_some()),
            ("--lens-radius", self.lens_radius.is_some()),
            ("--focus", self.focus.is_some()),
            ("--focus-at", self.focus_at.is_some()),
            ("--motion", self.motion.is_some()),
            ("--shift-px", self.shift_px.is_some()),
            ("--dolly", self.dolly.is_some()),
            ("--rotate-deg", self.rotate_deg.is_some()),
            ("--wobble", self.wobble.is_some()),
        ];
        for (n, g) in flags {
            if g {
                v.push(n);
            }
        }
        v
    }

    /// A procedural scene has its own camera and motion: refuse the OBJ flags.
    pub fn refuse_for(&self, scene: &str) -> Result<()> {
        let g = self.given();
        ensure!(
            g.is_empty(),
            "{}: only for a FILE.obj scene (--scene {scene} has its own camera and motion)",
            g.join(", ")
        );
        Ok(())
    }

    /// The motion components, checked.
    fn motions(&self) -> Result<Vec<String>> {
        let s = self.motion.as_deref().unwrap_or("rigid");
        let mut out: Vec<String> = Vec::new();
        for part in s.split(',') {
            let p = part.trim();
            ensure!(
                MOTIONS.contains(&p),
                "--motion {s}: `{p}` is not a motion (use rigid, dolly, rotate, wobble, none, comma-separated)"
            );
            if !out.iter().any(|x| x == p) {
                out.push(p.to_string());
            }
        }
        ensure!(
            !(out.len() > 1 && out.iter().any(|x| x == "none")),
            "--motion {s}: `none` cannot be combined with other motions"
        );
        let uses = |flag: &str, m: &str, given: bool| -> Result<()> {
            ensure!(!given || out.iter().any(|x| x == m), "{flag}: only with --motion {m} (got --motion {s})");
            Ok(())
        };
        uses("--shift-px", "rigid", self.shift_px.is_some())?;
        uses("--dolly", "dolly", self.dolly.is_some())?;
        uses("--rotate-deg", "rotate", self.rotate_deg.is_some())?;
        uses("--wobble", "wobble", self.wobble.is_some())?;
        Ok(out)
    }
}

/// `flag`'s value, or `default`; refused (naming the flag and value) outside `lo..=hi`
/// or not finite.
fn value(flag: &str, v: Option<f64>, default: f64, lo: f64, hi: f64) -> Result<f64> {
    let x = v.unwrap_or(default);
    if !(x.is_finite() && lo <= x && x <= hi) {
        bail!("{flag} {x}: must be a number from {lo} to {hi}");
    }
    Ok(x)
}

/// The OBJ scene at `path` with the controls `c` (see the module documentation), and
/// the settings used.
pub fn from_obj_with(
    path: &Path,
    seed: u64,
    width: u32,
    height: u32,
    c: &MeshControls,
) -> Result<(Scene, MeshSettings)> {
    from_obj_with_progress(path, seed, width, height, c, &indicatif::ProgressBar::hidden())
}

/// [`from_obj_with`], advancing `pb` by the bytes of the file read
/// ([`obj::load_with_progress`]).
pub fn from_obj_with_progress(
    path: &Path,
    seed: u64,
    width: u32,
    height: u32,
    c: &MeshControls,
    pb: &indicatif::ProgressBar,
) -> Result<(Scene, MeshSettings)> {
    ensure!(width >= 1 && height >= 1, "the screen must be at least 1x1 pixels (got {width}x{height})");
    let fov = value("--fov", c.fov, 45.0, 1.0, 170.0)?;
    let distance = value("--distance", c.distance, 1.0, 0.05, 100.0)?;
    let motions = c.motions()?;
    let shift_px = value("--shift-px", c.shift_px, 10.0, 0.0, 1000.0)?;
    let dolly = value("--dolly", c.dolly, 0.3, 0.0, 1.5)?;
    let rotate_deg = value("--rotate-deg", c.rotate_deg, 30.0, -360.0, 360.0)?;
    let wobble = value("--wobble", c.wobble, 0.02, 0.0, 1.0)?;
    if let Some(r) = c.lens_radius {
        value("--lens-radius", Some(r), 0.0, 0.0, 1e9)?;
    }
    if let Some(f) = c.focus {
        ensure!(f.is_finite() && f > 0.0 && f <= 1e12, "--focus {f}: must be a positive distance (at most 1e12)");
    }
    let focus_at = value("--focus-at", c.focus_at, 0.0, -1.0, 1.0)?;

    let tris = obj::load_with_progress(path, pb)?;
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for t in &tris {
        for p in t {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i] as f64);
                hi[i] = hi[i].max(p[i] as f64);
            }
        }
    }
    let ctr: [f64; 3] = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
    let r = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt() * 0.5;
    let r = if r > 0.0 { r } else { 1.0 };
    let cam = pinhole(width, height, fov);
    let half_fov = (0.5 * width.min(height) as f64 / cam.fy as f64).atan();
    let depth = distance * 1.15 * r / half_fov.sin();
    let place = |p: [f32; 3]| -> V3 {
        [(p[0] as f64 - ctr[0]) as f32, (-(p[1] as f64 - ctr[1])) as f32, (depth - (p[2] as f64 - ctr[2])) as f32]
    };
    let placed: Vec<[V3; 3]> = tris.iter().map(|t| t.map(place)).collect();
    let mut rng = rng_for(seed, 0x0b1);
    let centre: V3 = [0.0, 0.0, depth as f32];
    let has = |m: &str| motions.iter().any(|x| x == m);
    // The draws happen in this order whatever the components, so adding one component
    // does not change the others' draws.
    let rim_px = 8.0 * px(height);
    let max_angle = rim_px * depth as f32 / (cam.fx * r as f32);
    let rigid = seeded_motion(&mut rng, &cam, centre, shift_px as f32 * px(height), 0.02, max_angle);
    let rot_axis = unit_vector(&mut rng);
    let _wobble_draw: u64 = rng.gen();
    let mut motion = if has("rigid") { rigid } else { RigidMotion { pivot: centre, ..RigidMotion::none() } };
    if has("rotate") {
        motion.axis = rot_axis;
        motion.angle = rotate_deg.to_radians() as f32;
    }
    if has("dolly") {
        motion.shift[2] -= (dolly * depth) as f32;
    }
    let wobble_amp = if has("wobble") { (wobble * r) as f32 } else { 0.0 };
    let focus = match c.focus {
        Some(f) => f,
        None => depth + focus_at * r,
    };
    let lens_radius = match c.lens_radius {
        Some(x) => x,
        None => {
            // 4 px of blur at the end of the mesh farther from the focal plane.
            let z_ref = if focus <= depth { depth + r } else { (depth - r).max(0.05 * depth) };
            with_lens(cam, focus as f32, 4.0 * px(height), z_ref as f32).radius as f64
        }
    };
    ensure!(
        (lens_radius as f32).is_finite(),
        "--lens-radius: the lens radius {lens_radius:e} does not fit f32; choose --lens-radius or --focus"
    );
    let camera = crate::model::ThinLens { focus: focus as f32, radius: lens_radius as f32, ..cam };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "mesh.obj".into());
    let settings = MeshSettings {
        path: path.display().to_string(),
        fov_deg: fov,
        distance,
        depth,
        radius: r,
        lens_radius,
        focus,
        motion: motions.clone(),
        shift_px: if has("rigid") { shift_px } else { 0.0 },
        dolly: if has("dolly") { dolly } else { 0.0 },
        rotate_deg: has("rotate").then_some(rotate_deg),
        wobble: if has("wobble") { wobble } else { 0.0 },
        rigid: motion,
    };
    let scene = Scene {
        name,
        width,
        height,
        camera,
        objects: vec![Object { name: path.display().to_string(), tris: placed, motion, wobble: wobble_amp }],
    };
    Ok((scene, settings))
}
