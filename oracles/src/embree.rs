//! Embree ray oracle: a second opinion on thin-lens, motion-blurred coverage.
//!
//! # What it is
//!
//! One triangle in homogeneous clip space, given as plain `f32` numbers
//! ([`LensTri`]), is handed to Intel Embree 3 (through the `embree3` crate,
//! system library `libembree3`) as a motion-blurred triangle mesh, and every
//! sample `s = (x, y, u, v, t)` is turned into one ray. The sample is reported
//! covered iff Embree says the ray is occluded by the triangle.
//!
//! Embree is an independent implementation of ray/triangle intersection, so it
//! is useful to cross-check the exact oracles of this crate and the code under
//! test on many random samples. It is **never the judge**: Embree computes in
//! `f32` (the vertices as stored, the ray after rounding to `f32`, and the
//! intersection test itself), so it may disagree with exact coverage for
//! samples within a few ulps of an edge, near the `W = 0` plane, for rays
//! almost parallel to the triangle's plane, and for degenerate (zero-area)
//! triangles. A disagreement far from every edge is a real finding; one near
//! an edge is expected noise.
//!
//! # The model
//!
//! A vertex `i` has clip coordinates `(x, y, w)`: `q[i]` at `t = 0`, `r[i]` at
//! `t = 1`, and moves linearly, `p_i(t) = (1 - t) q_i + t r_i`. The thin-lens
//! camera has lens parameter `a = -fx * R <= 0` (`0` is a pinhole), focal
//! distance `F = focus > 0` (in `w` units) and aspect `k = fy / fx`; write
//! `b = -a / F` and `c(W) = a + b W` (so `c(F) = 0`: the focal plane is
//! sharp). Sample `(x, y, u, v, t)` (pixel position, lens position in
//! `[-1, 1]^2`, time in `[0, 1]`) is covered iff some point `(X, Y, W)` of the
//! triangle at time `t` with `W > 0` satisfies
//!
//! ```text
//! x W = X + u c(W),    y W = Y + k v c(W).
//! ```
//!
//! # The ray
//!
//! Those two equations describe a line in `(X, Y, W)` space; Embree's 3D
//! coordinates are taken to be exactly `(X, Y, Z) = (x, y, w)` of the clip
//! vertices (no projection, no division by `w`), and the line is written as
//! the ray
//!
//! ```text
//! origin    O = (-a u,          -a k v,          0)
//! direction D = (x F + a u,     y F + a k v,     F)
//! ```
//!
//! Checking: at parameter `s`, `W = s F`, and
//! `X + u c(W) = -a u + s (x F + a u) + u (a - a s) = s x F = x W`, likewise
//! for `Y`. Since `F > 0`, `W > 0` is exactly `s > 0`, so the ray segment is
//! `(tnear, tfar) = (0, +inf)`; Embree's triangle tests accept a hit distance
//! `T` only if `tnear < T <= tfar`, so a hit exactly on `W = 0` does not count,
//! as in the model. The map from camera space to clip space is linear, so
//! straight lines, triangles and their intersections are preserved, and
//! Embree's linear interpolation of the vertex positions between the two time
//! steps is exactly the model's `p_i(t)`. The ray's `time` is `t`. All of it
//! is computed in `f64` and rounded to `f32` once per component; see
//! [`EmbreeOracle::ray_for`].
//!
//! Embree triangles are two-sided (the Debian build is compiled without
//! `EMBREE_BACKFACE_CULLING`; the tests check both windings), so either
//! winding hits. Vertices with
//! `w <= 0` are not special: the triangle is just a triangle in 3D and the ray
//! segment starts at `W = 0`, so only its in-front part can be hit.
//!
//! # Embree calls used
//!
//! * `rtcNewDevice` once per process (config `threads=1`, error reporter off),
//!   shared by all oracles through `rtcRetainDevice`; see below.
//! * `rtcNewScene` + `rtcSetSceneFlags(RTC_SCENE_FLAG_ROBUST)`, default build
//!   quality (`MEDIUM`; for one primitive the builder's choice is immaterial).
//! * `rtcNewGeometry(RTC_GEOMETRY_TYPE_TRIANGLE)`,
//!   `rtcSetGeometryTimeStepCount(2)` (always, even for a static triangle),
//!   `rtcSetNewGeometryBuffer(VERTEX, slot 0 = q / slot 1 = r, FLOAT3)`,
//!   `rtcSetNewGeometryBuffer(INDEX, UINT3)` with the single triangle
//!   `(0, 1, 2)`, `rtcCommitGeometry`, `rtcAttachGeometry`, `rtcCommitScene`,
//!   `rtcGetDeviceError` after each step.
//! * Queries: `rtcOccluded1` ([`EmbreeOracle::hit`]) and `rtcOccluded16`
//!   ([`EmbreeOracle::hits`]; packets of 16 with a valid mask for the ragged
//!   tail: measured fastest of 1/4/8/16/stream on the AVX-512 test machine).
//!
//! # Why the ROBUST scene flag
//!
//! With `RTC_SCENE_FLAG_ROBUST` Embree uses its watertight (Plücker) triangle
//! test and conservative BVH traversal and "avoids optimizations that reduce
//! arithmetic accuracy". Without it the default (Möller–Trumbore) test can
//! leave pinholes or double hits along edges. An oracle should be as accurate
//! as the tool allows, especially near edges, and the speed cost for a
//! one-triangle scene is small, so ROBUST is always on.
//!
//! # Device sharing and the floating-point environment
//!
//! Embree recommends one device per application (the first one costs about
//! a millisecond here: ISA detection, TBB start-up; a scene for one triangle
//! costs a few microseconds), so all oracles share one process-wide device
//! created on first use; each [`EmbreeOracle`] owns its own reference to it
//! (reference-counted, released on drop) and its own scene.
//! The `embree3` crate sets flush-to-zero/denormals-are-zero in the calling
//! thread's MXCSR when it creates a device; this module saves and restores
//! MXCSR around that call so that building an oracle never changes the
//! caller's floating-point environment.
//!
//! # Threads
//!
//! [`EmbreeOracle`] is `Send + Sync` (the `embree3` crate declares `Device`
//! and `Scene` `Send + Sync`, and Embree allows concurrent queries on a
//! committed scene); queries take `&self`.

use std::fmt;
use std::sync::OnceLock;

use embree3::{
    BufferUsage, Config, Device, Format, GeometryKind, IntersectContext, Ray, Ray16, Scene, SceneFlags, ValidMask,
    ValidMaskN,
};

/// A thin-lens case as plain numbers (`f32` vertex data exactly as stored by
/// the caller).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LensTri {
    /// `(x, y, w)` of each vertex at `t = 0`.
    pub q: [[f32; 3]; 3],
    /// `(x, y, w)` of each vertex at `t = 1`.
    pub r: [[f32; 3]; 3],
    /// Lens parameter `-fx * R` (`<= 0`); `0` means pinhole.
    pub a: f64,
    /// Focal distance `F > 0`, in `w` units.
    pub focus: f64,
    /// Aspect `fy / fx`.
    pub k: f64,
}

/// Why an [`EmbreeOracle`] could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum EmbreeError {
    /// A vertex coordinate is NaN or infinite. `time` is 0 for `q`, 1 for `r`.
    NonFiniteVertex { time: u8, vertex: usize, coord: usize, value: f32 },
    /// `a`, `focus` or `k` is NaN or infinite.
    NonFiniteParameter { name: &'static str, value: f64 },
    /// `focus <= 0`.
    FocusNotPositive(f64),
    /// `focus` rounds to an `f32` that is subnormal (below about `1.2e-38`)
    /// or larger than Embree's `FLT_LARGE` (`1.844e18`): the ray direction's
    /// `w` component would be (nearly) zero or no ray would be traceable.
    FocusOutOfRange(f64),
    /// `a > 0` (the model has `a = -fx * R <= 0`).
    LensParameterPositive(f64),
    /// Embree reported an error; `stage` says during which step.
    Embree { stage: &'static str, code: embree3::Error },
}

impl fmt::Display for EmbreeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EmbreeError::NonFiniteVertex { time, vertex, coord, value } => {
                write!(f, "vertex {vertex} at t = {time} has non-finite coordinate {coord}: {value}")
            }
            EmbreeError::NonFiniteParameter { name, value } => {
                write!(f, "lens parameter `{name}` is not finite: {value}")
            }
            EmbreeError::FocusNotPositive(v) => {
                write!(f, "focal distance must be > 0, got {v}")
            }
            EmbreeError::FocusOutOfRange(v) => {
                write!(f, "focal distance {v} is outside the usable f32 range [{:e}, {FLT_LARGE:e}]", f32::MIN_POSITIVE)
            }
            EmbreeError::LensParameterPositive(v) => {
                write!(f, "lens parameter a = -fx*R must be <= 0, got {v}")
            }
            EmbreeError::Embree { stage, code } => {
                write!(f, "Embree error {code:?} during {stage}")
            }
        }
    }
}

impl std::error::Error for EmbreeError {}

/// An Embree scene holding one motion-blurred triangle, queried with one ray
/// per sample. See the [module documentation](self) for the ray construction,
/// the flags, and why its answers are a second opinion only.
///
/// `Send + Sync`: it can be shared between threads (e.g. in an `Arc`) and
/// queried concurrently.
pub struct EmbreeOracle {
    // The scene owns a reference to the (shared) device, and the attached
    // geometry; dropping it releases all three.
    scene: Scene<'static>,
    tri: LensTri,
}

impl fmt::Debug for EmbreeOracle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EmbreeOracle").field("tri", &self.tri).finish_non_exhaustive()
    }
}

// Compile-time check of the promise in the docs.
const _: () = {
    const fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<EmbreeOracle>();
};

/// The packet width used by [`EmbreeOracle::hits`].
const PACKET: usize = 16;

/// Embree's `FLT_LARGE`: a ray whose origin or direction has a component of
/// larger magnitude (or NaN) fails Embree's `ray.valid()` assertion, which the
/// Debian build keeps enabled, so tracing it would abort the whole process.
const FLT_LARGE: f32 = 1.844e18;

/// A valid mask with the 64-byte alignment Embree's 16-wide kernels may
/// assume (the crate's `ValidMaskN` is only 16-byte aligned). `repr(C)` puts
/// the field at offset 0, so the inner mask has the outer alignment.
#[repr(C, align(64))]
struct AlignedMask(ValidMaskN<PACKET>);

/// Runs `f` and restores the caller's MXCSR afterwards (the `embree3` crate
/// turns on FTZ/DAZ in the creating thread).
fn preserving_fp_env<T>(f: impl FnOnce() -> T) -> T {
    #[cfg(target_arch = "x86_64")]
    {
        #[allow(deprecated)]
        // SAFETY: reading MXCSR has no preconditions on x86_64 (SSE is baseline).
        let saved = unsafe { std::arch::x86_64::_mm_getcsr() };
        let out = f();
        #[allow(deprecated)]
        // SAFETY: writing back the value read above restores a valid state.
        unsafe {
            std::arch::x86_64::_mm_setcsr(saved)
        };
        out
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        f()
    }
}

/// The process-wide device (see the module docs), or the error its creation
/// gave (then every [`EmbreeOracle::new`] returns that error).
fn shared_device() -> Result<Device, EmbreeError> {
    static DEVICE: OnceLock<Result<Device, embree3::Error>> = OnceLock::new();
    DEVICE
        .get_or_init(|| {
            preserving_fp_env(|| Device::with_config(Config { threads: 1, report_errors: false, ..Config::default() }))
        })
        .clone()
        .map_err(|code| EmbreeError::Embree { stage: "device creation", code })
}

fn check(device: &Device, stage: &'static str) -> Result<(), EmbreeError> {
    match device.get_error() {
        embree3::Error::NONE => Ok(()),
        code => Err(EmbreeError::Embree { stage, code }),
    }
}

fn validate(tri: &LensTri) -> Result<(), EmbreeError> {
    for (time, verts) in [(0u8, &tri.q), (1u8, &tri.r)] {
        for (vertex, p) in verts.iter().enumerate() {
            for (coord, &value) in p.iter().enumerate() {
                if !value.is_finite() {
                    return Err(EmbreeError::NonFiniteVertex { time, vertex, coord, value });
                }
            }
        }
    }
    for (name, value) in [("a", tri.a), ("focus", tri.focus), ("k", tri.k)] {
        if !value.is_finite() {
            return Err(EmbreeError::NonFiniteParameter { name, value });
        }
    }
    if tri.focus <= 0.0 {
        return Err(EmbreeError::FocusNotPositive(tri.focus));
    }
    let focus32 = tri.focus as f32;
    if !(f32::MIN_POSITIVE..=FLT_LARGE).contains(&focus32) {
        return Err(EmbreeError::FocusOutOfRange(tri.focus));
    }
    if tri.a > 0.0 {
        return Err(EmbreeError::LensParameterPositive(tri.a));
    }
    Ok(())
}

impl EmbreeOracle {
    /// Builds and commits the one-triangle scene.
    ///
    /// Rejects non-finite numbers, `focus <= 0`, a `focus` whose `f32` is
    /// subnormal or above `1.844e18` (see [`EmbreeError::FocusOutOfRange`]),
    /// and `a > 0`. Degenerate triangles (zero area, coincident vertices) are
    /// accepted; Embree then simply reports whatever it reports (normally: no
    /// hits). So are vertices with `w <= 0`. Embree silently drops a primitive with a coordinate
    /// beyond about `1.8e18` in magnitude, which then is never hit.
    pub fn new(tri: &LensTri) -> Result<Self, EmbreeError> {
        validate(tri)?;
        let device = shared_device()?;
        // Clear any stale per-thread error so that only this build's errors count.
        let _ = device.get_error();

        let embree_err = |stage| move |code| EmbreeError::Embree { stage, code };

        let mut geom = device.create_geometry(GeometryKind::TRIANGLE).map_err(embree_err("geometry creation"))?;
        geom.set_time_step_count(2);
        for (slot, verts) in [(0u32, &tri.q), (1u32, &tri.r)] {
            geom.set_new_buffer::<[f32; 3]>(BufferUsage::VERTEX, slot, Format::FLOAT3, 12, 3)
                .map_err(embree_err("vertex buffer"))?
                .copy_from_slice(verts);
        }
        geom.set_new_buffer::<[u32; 3]>(BufferUsage::INDEX, 0, Format::UINT3, 12, 1)
            .map_err(embree_err("index buffer"))?
            .copy_from_slice(&[[0, 1, 2]]);
        let geom = geom.commit();
        check(&device, "geometry commit")?;

        let mut scene: Scene<'static> = device.create_scene().map_err(embree_err("scene creation"))?;
        scene.set_flags(SceneFlags::ROBUST);
        scene.attach_geometry(&geom);
        scene.commit();
        check(&device, "scene commit")?;

        Ok(EmbreeOracle { scene, tri: *tri })
    }

    /// The triangle and lens this oracle was built from.
    pub fn lens_tri(&self) -> &LensTri {
        &self.tri
    }

    /// The `f32` ray `(origin, direction)` Embree is given for sample
    /// `s = [x, y, u, v, t]`:
    /// origin `(-a u, -a k v, 0)`, direction `(x F + a u, y F + a k v, F)`,
    /// each component computed in `f64` and rounded to nearest `f32` once.
    /// (`t` only sets the ray's time.)
    pub fn ray_for(&self, s: [f64; 5]) -> ([f32; 3], [f32; 3]) {
        let [x, y, u, v, _t] = s;
        let LensTri { a, focus, k, .. } = self.tri;
        let org = [(-a * u) as f32, (-a * k * v) as f32, 0.0];
        let dir = [(x * focus + a * u) as f32, (y * focus + a * k * v) as f32, focus as f32];
        (org, dir)
    }

    /// The ray and time Embree is given for `s`, or `None` if Embree must not
    /// be given this ray: a non-finite component of `s`, a ray component
    /// beyond Embree's `FLT_LARGE` (about `1.8e18`), or a time outside
    /// `[0, 1]`. Embree asserts against the last two (its kernels for
    /// motion blur check the time), and the Debian build keeps assertions on.
    fn traceable(&self, s: [f64; 5]) -> Option<([f32; 3], [f32; 3], f32)> {
        if !s.iter().all(|c| c.is_finite()) {
            return None;
        }
        let (org, dir) = self.ray_for(s);
        let time = s[4] as f32;
        // `<=` is false for NaN, and the `as f32` casts turned overflow into inf.
        let ok = org.iter().chain(&dir).all(|c| c.abs() <= FLT_LARGE) && (0.0..=1.0).contains(&time);
        ok.then_some((org, dir, time))
    }

    /// One ray, `rtcOccluded1` (any hit with ray parameter in `(0, inf)`).
    ///
    /// A sample that cannot be traced is reported not covered, and no ray is
    /// given to Embree: one with a non-finite component, with `t` (as `f32`)
    /// outside `[0, 1]`, or whose `f32` ray has a component of magnitude above
    /// Embree's `FLT_LARGE` = `1.844e18`. (The Debian build of Embree keeps
    /// its assertions, and it asserts against such rays: tracing one would
    /// abort the process.)
    pub fn hit(&self, s: [f64; 5]) -> bool {
        let Some((org, dir, time)) = self.traceable(s) else {
            return false;
        };
        let mut ray = Ray::new(org, dir, 0.0, f32::INFINITY, time, u32::MAX, 0);
        let mut ctx = IntersectContext::incoherent();
        self.scene.occluded(&mut ctx, &mut ray)
    }

    /// Many samples: `out` is cleared and then holds one answer per sample, in
    /// order, equal to what [`hit`](Self::hit) says for it.
    ///
    /// Uses `rtcOccluded16` on packets of 16 rays (SoA), with the valid mask
    /// switching off the lanes past the end of a ragged last packet and the
    /// lanes of samples that cannot be traced (reported `false`, as in
    /// [`hit`](Self::hit)).
    /// Packets of 16 measured fastest here (AVX-512 machine, Debian Embree
    /// 3.13.5; about 100 Mrays/s against 70 for packets of 8, 45 for 4, 30
    /// for the stream API and 24 for single rays). Without AVX-512, Embree
    /// serves 16-wide packets through its generic stream path: still correct,
    /// maybe slower.
    pub fn hits(&self, samples: &[[f64; 5]], out: &mut Vec<bool>) {
        out.clear();
        out.reserve(samples.len());
        let mut ctx = IntersectContext::incoherent();
        let mut mask = AlignedMask(ValidMaskN::new([ValidMask::Invalid; PACKET]));
        for chunk in samples.chunks(PACKET) {
            let mut rays = Ray16::empty();
            for (i, lane) in mask.0.lanes_mut().iter_mut().enumerate() {
                *lane = ValidMask::Invalid;
                let Some(&s) = chunk.get(i) else { continue };
                let Some((org, dir, time)) = self.traceable(s) else {
                    continue;
                };
                rays.org_x[i] = org[0];
                rays.org_y[i] = org[1];
                rays.org_z[i] = org[2];
                rays.dir_x[i] = dir[0];
                rays.dir_y[i] = dir[1];
                rays.dir_z[i] = dir[2];
                rays.tnear[i] = 0.0;
                rays.tfar[i] = f32::INFINITY;
                rays.time[i] = time;
                rays.mask[i] = u32::MAX;
                rays.id[i] = i as u32;
                *lane = ValidMask::Valid;
            }
            self.scene.occluded16(&mut ctx, &mut rays, &mask.0);
            // An occluded lane has its tfar set to -inf; switched-off lanes keep
            // their initial +inf.
            out.extend((0..chunk.len()).map(|i| rays.tfar[i] == f32::NEG_INFINITY));
        }
    }
}
