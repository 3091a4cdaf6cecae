//! The swept families: how each builds a case (a thin-lens [`Case`] made with
//! [`ThinLens::triangle`]) and its tile for one value of the swept parameter, and how
//! the parameter is measured back from the f32 case data (the `achieved` value of the
//! reports, which the tests hold against the requested one).
//!
//! Everything not swept is drawn from the case's own seeded rng. Where a family needs
//! the parameter to survive the rounding of camera space to f32 clip space, the camera
//! or the geometry is chosen so that the rounding cannot move it (each family says how).
//! The case index `i` (0-based within a step) alternates the dimensions where a family
//! mixes them, so every step sees the same mix.

use crate::cases::generate::{camera, Source};
use crate::model::{Case, ThinLens, Tile};
use crate::Interval;
use anyhow::{bail, Result};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A swept family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    Focal,
    WZero,
    Perspective,
    Sliver,
    Far,
    DoubleRoot,
}

/// One built case: the case, its tile and the parameter measured from the f32 data.
#[derive(Clone, Copy, Debug)]
pub struct Built {
    pub case: Case,
    pub tile: Tile,
    /// The swept parameter as the f32 case really has it (see [`Family::parameter`]).
    pub achieved: f64,
}

/// The decimal `1e{e}` as the nearest f64 (prints back as "1e-6", unlike `10f64.powi(-6)`).
fn pow10(e: i32) -> f64 {
    format!("1e{e}").parse().expect("a decimal literal")
}

/// `n` values from `10^e0` to `10^e1`, evenly spaced in the exponent.
fn log_steps(e0: i32, e1: i32, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![pow10(e0)];
    }
    (0..n)
        .map(|i| {
            let e = e0 as f64 + (e1 - e0) as f64 * i as f64 / (n - 1) as f64;
            if (e - e.round()).abs() < 1e-12 {
                pow10(e.round() as i32)
            } else {
                10f64.powf(e)
            }
        })
        .collect()
}

use crate::cases::generate::boundary_tile;

impl Family {
    pub const ALL: [Family; 6] =
        [Family::Focal, Family::WZero, Family::Perspective, Family::Sliver, Family::Far, Family::DoubleRoot];

    pub fn name(self) -> &'static str {
        match self {
            Family::Focal => "focal",
            Family::WZero => "w-zero",
            Family::Perspective => "perspective",
            Family::Sliver => "sliver",
            Family::Far => "far",
            Family::DoubleRoot => "double-root",
        }
    }

    /// `all`, one name, or names separated by commas; an unknown one is an error that
    /// names the flag and the value.
    pub fn parse(s: &str) -> Result<Vec<Family>> {
        if s.trim() == "all" {
            return Ok(Family::ALL.to_vec());
        }
        let names: Vec<&str> = Family::ALL.iter().map(|f| f.name()).collect();
        let mut out = Vec::new();
        for part in s.split(',') {
            let Some(f) = Family::ALL.into_iter().find(|f| f.name() == part.trim()) else {
                bail!("--family {s}: `{}` is not a family (one of: {}, all)", part.trim(), names.join(", "));
            };
            if !out.contains(&f) {
                out.push(f);
            }
        }
        Ok(out)
    }

    /// What the swept parameter is.
    pub fn parameter(self) -> &'static str {
        match self {
            Family::Focal => "|z0/focus - 1| of vertex 0 (its distance to the focal plane, relative)",
            Family::WZero => "w of vertex 0 at one end of the shutter (camera depth units)",
            Family::Perspective => "w(t=1)/w(t=0) of every vertex",
            Family::Sliver => "height/base of the triangle in pixels",
            Family::Far => "distance of the triangle from the screen origin (pixels)",
            Family::DoubleRoot => "depth of the tile corner inside the grazing edge at tangency (pixels)",
        }
    }

    /// Mixed into the seed so that families never share a case stream.
    pub fn salt(self) -> u64 {
        match self {
            Family::Focal => 0x51ab_f0ca_1000_0001,
            Family::WZero => 0x51ab_f0ca_1000_0002,
            Family::Perspective => 0x51ab_f0ca_1000_0003,
            Family::Sliver => 0x51ab_f0ca_1000_0004,
            Family::Far => 0x51ab_f0ca_1000_0005,
            Family::DoubleRoot => 0x51ab_f0ca_1000_0006,
        }
    }

    /// True for the family whose axis is symmetric-log (it passes through 0).
    pub fn symlog(self) -> bool {
        self == Family::WZero
    }

    /// The steps, from the benign end to the singular one. `n`: how many (default: one
    /// per decade, or per octave for `perspective`). `w-zero` takes `max(1, n/2)`
    /// positive values, 0, and as many negative ones (so 2 floor(n/2) + 1 steps).
    pub fn steps(self, n: Option<usize>) -> Vec<f64> {
        match self {
            Family::Focal => log_steps(0, -7, n.unwrap_or(8)),
            Family::Sliver => log_steps(-1, -8, n.unwrap_or(8)),
            Family::DoubleRoot => log_steps(-1, -8, n.unwrap_or(8)),
            Family::Far => log_steps(1, 7, n.unwrap_or(7)),
            Family::Perspective => {
                let n = n.unwrap_or(11);
                if n <= 1 {
                    return vec![1.0];
                }
                (0..n)
                    .map(|i| {
                        let e = 10.0 * i as f64 / (n - 1) as f64;
                        if (e - e.round()).abs() < 1e-12 {
                            2f64.powi(e.round() as i32)
                        } else {
                            2f64.powf(e)
                        }
                    })
                    .collect()
            }
            Family::WZero => {
                let k = (n.unwrap_or(9) / 2).max(1);
                let pos = log_steps(0, -6, k);
                let mut v = pos.clone();
                v.push(0.0);
                v.extend(pos.iter().rev().map(|x| -x));
                v
            }
        }
    }

    /// How the family builds its cases (for the Markdown report).
    pub fn describe(self) -> &'static str {
        match self {
            Family::Focal => {
                "Thin lens on (radius, focus, fx from the random camera). Vertex 0 at depth z0 = F (1 + s d) for \
                 the step d, rounded to the nearest f32 other than F itself; s = +1 or -1 at random (+1 when \
                 d >= 0.5: in front it would reach the lens). Vertex 1 in front of the focal plane (0.5-0.9 F), \
                 vertex 2 behind it (1.1-2 F), so the CoC signs differ. Even cases are static, odd cases move \
                 laterally (x, y only: every depth, and so the CoC of vertex 0, stays put over the shutter). Tile \
                 on the footprint boundary as in `check`."
            }
            Family::WZero => {
                "Motion on. Centre depth 2-20, vertices spread around it; vertex 0's camera depth at one shutter \
                 end (t = 0 or 1 at random) is set to the step (exactly: clip w = camera z), so it approaches the \
                 lens plane, touches it (0) and passes behind it (negative). The other end and the other vertices \
                 stay at ordinary depths. Even cases are pinhole (motion only), odd cases have the thin lens. \
                 Tile on the footprint boundary as in `check`."
            }
            Family::Perspective => {
                "Every vertex moves in depth: r.z = q.z * ratio (exact for powers of two), from a start depth \
                 0.5-2, with lateral motion scaled along (screen motion moderate, its timing hyperbolic). Even \
                 cases are pinhole, odd cases have the thin lens. Tile on the footprint boundary as in `check`."
            }
            Family::Sliver => {
                "The base A-B lies on the camera's x axis (or y axis, at random) with the principal point's cy \
                 (or cx) set to 0, so the base sits exactly on pixel row (column) 0, and the apex's pixel height \
                 is one f32 product set from the rounded base length: the aspect (at t = 0, seen from the lens \
                 centre) survives rounding even at 1e-8. Apex at 20-80 % along the base; depths within +-5 % of \
                 each other (equal depths would trip nilsson2012-depth's known equal-depth rounding, a different \
                 matter). Half the cases move (along the base and in depth: the aspect changes by a few % at \
                 t = 1), odd cases have the thin lens. Tile on the footprint boundary as in `check`."
            }
            Family::Far => {
                "The principal point (cx, cy) is put at the step's distance from the screen origin in a random \
                 direction and the triangle (2-40 px, centroid at the principal point, depths within +-5 % of \
                 each other) around it, so every pixel coordinate, the tile's and the samples' included, is of \
                 that size in f32. Cases cycle through static, motion, defocus, both. Tile on the footprint \
                 boundary as in `check`."
            }
            Family::DoubleRoot => {
                "Motion only (pinhole), aimed at gdam2010's time quadratics. The configuration of the unit test \
                 `near_double_root_is_where_f32_is_fragile` (edge A-B with A(t) = (-10 + t, -19 + d), B(t) = (19, \
                 36 + 4t), C = (20, -20) about a point P; its edge quadratic at P is 4 (t - 1/2)^2 - 19 d), run \
                 later or earlier so that the tangency falls at a random tm in 0.35-0.65, stretched by 0.7-1.4 \
                 along a random axis, rotated so that the edge's uncovered side faces into the tile diagonally \
                 (+-20 deg) from P, a corner of a tile-grid-aligned tile, and scaled 0.5-2x (an affine map with \
                 positive determinant keeps every edge's sign everywhere). The moving edge line then sweeps up \
                 to P and turns back: the edge quadratic at P has a double root at tm when the step is 0; the \
                 tile's covered set is the tip within about the step of P (the rest of the tile is never \
                 covered), for a time span of about 4 sqrt(step / scale) each side of tm (at 1e-1 that is the \
                 whole shutter, the roots lie outside it; at 1e-2 they lie inside in most cases, from 1e-3 on in \
                 all). The focal scale and the depths (one per vertex) are powers of two and cx = cy = 0, so \
                 camera -> pixel is exact; the eight moving coordinates of A and B are then nudged ulp by ulp \
                 (meet in the middle over +-3 ulps each, re-measured exactly) until P's depth, computed from the \
                 f32 data with outward-rounded intervals, matches the step to 0.1 % even at 1e-8 (see the \
                 measured min/max). The tile is placed by this construction, not by `samples_for`."
            }
        }
    }

    /// Build case `i` of a step with parameter `param`.
    pub fn build(self, param: f64, rng: &mut ChaCha8Rng, i: u64, tile: f32) -> Built {
        match self {
            Family::Focal => focal(param, rng, i, tile),
            Family::WZero => w_zero(param, rng, i, tile),
            Family::Perspective => perspective(param, rng, i, tile),
            Family::Sliver => sliver(param, rng, i, tile),
            Family::Far => far(param, rng, i, tile),
            Family::DoubleRoot => double_root(param, rng, tile),
        }
    }
}

fn finish(cam: ThinLens, q: [[f32; 3]; 3], r: [[f32; 3]; 3], rng: &mut ChaCha8Rng, size: f32) -> (Case, Tile) {
    let case = Case { triangle: cam.triangle(q, r), lens: Some(cam) };
    let tile = boundary_tile(&case, rng, size);
    (case, tile)
}

/// The f32 depth at relative distance `d` from the focal plane `f` (in front when
/// `s < 0`), never `f` itself.
pub fn focal_depth(f: f32, s: f32, d: f64) -> f32 {
    let z = (f as f64 * (1.0 + s as f64 * d)) as f32;
    if z != f {
        z
    } else if s > 0.0 {
        f.next_up()
    } else {
        f.next_down()
    }
}

/// Three vertices scattered up to `spread` around `centre` in x and y, each with the
/// depth `depth(rng, k)` (drawn after its x and y).
fn scatter(
    rng: &mut ChaCha8Rng,
    centre: [f32; 2],
    spread: f32,
    mut depth: impl FnMut(&mut ChaCha8Rng, usize) -> f32,
) -> [[f32; 3]; 3] {
    std::array::from_fn(|k| {
        let x = centre[0] + rng.gen_range(-1.0..1.0) * spread;
        let y = centre[1] + rng.gen_range(-1.0..1.0) * spread;
        [x, y, depth(rng, k)]
    })
}

fn focal(d: f64, rng: &mut ChaCha8Rng, i: u64, size: f32) -> Built {
    let cam = camera(rng, true);
    let f = cam.focus;
    let s = if d >= 0.5 { 1.0 } else { rng.sign() };
    let z = [focal_depth(f, s, d), f * rng.gen_range(0.5..0.9), f * rng.gen_range(1.1..2.0)];
    let centre = [rng.gen_range(-0.2..0.2) * f, rng.gen_range(-0.2..0.2) * f];
    let spread = f * rng.log_uniform(0.02, 0.3);
    let q = scatter(rng, centre, spread, |_, k| z[k]);
    let mut r = q;
    if i % 2 == 1 {
        let m = spread * rng.log_uniform(0.1, 3.0);
        let dm = [rng.gen_range(-1.0..1.0) * m, rng.gen_range(-1.0..1.0) * m];
        for p in r.iter_mut() {
            for j in 0..2 {
                p[j] += dm[j] + rng.gen_range(-0.2..0.2) * m;
            }
        }
    }
    let (case, tile) = finish(cam, q, r, rng, size);
    let achieved = (case.triangle.q[0][3] as f64 / f as f64 - 1.0).abs();
    Built { case, tile, achieved }
}

fn w_zero(w: f64, rng: &mut ChaCha8Rng, i: u64, size: f32) -> Built {
    let cam = camera(rng, i % 2 == 1);
    let z = rng.log_uniform(2.0, 20.0);
    let spread = z * rng.log_uniform(0.02, 0.3);
    let centre = [rng.gen_range(-0.3..0.3) * z, rng.gen_range(-0.3..0.3) * z];
    let mut q = scatter(rng, centre, spread, |rng, _| z + rng.gen_range(-0.3..0.3) * spread);
    let m = spread * rng.log_uniform(0.2, 3.0);
    let d = [rng.gen_range(-1.0..1.0) * m, rng.gen_range(-1.0..1.0) * m, rng.gen_range(-0.5..0.5) * m];
    let mut r = q.map(|p| [p[0] + d[0], p[1] + d[1], p[2] + d[2]]);
    let at_end = rng.gen_bool(0.5);
    if at_end {
        r[0][2] = w as f32;
    } else {
        q[0][2] = w as f32;
    }
    let (case, tile) = finish(cam, q, r, rng, size);
    let t = &case.triangle;
    let achieved = if at_end { t.r[0][3] } else { t.q[0][3] } as f64;
    Built { case, tile, achieved }
}

fn perspective(ratio: f64, rng: &mut ChaCha8Rng, i: u64, size: f32) -> Built {
    let cam = camera(rng, i % 2 == 1);
    let z0 = rng.log_uniform(0.5, 2.0);
    let spread = z0 * rng.log_uniform(0.02, 0.3);
    let centre = [rng.gen_range(-0.3..0.3) * z0, rng.gen_range(-0.3..0.3) * z0];
    let q = scatter(rng, centre, spread, |rng, _| z0 * rng.gen_range(0.9..1.1));
    let m = spread * rng.log_uniform(0.1, 3.0);
    let d = [rng.gen_range(-1.0..1.0) * m, rng.gen_range(-1.0..1.0) * m];
    let k = ratio as f32;
    let r = q.map(|p| [(p[0] + d[0]) * k, (p[1] + d[1]) * k, p[2] * k]);
    let (case, tile) = finish(cam, q, r, rng, size);
    let t = &case.triangle;
    let achieved = t.r[0][3] as f64 / t.q[0][3] as f64;
    Built { case, tile, achieved }
}

/// Height over base of the t = 0 triangle seen from the lens centre, in pixels (f64
/// from the f32 clip data; vertices 0-1 are the base).
pub fn pixel_aspect(c: &Case) -> f64 {
    let t = &c.triangle;
    let px = |k: usize| [t.q[k][0] as f64 / t.q[k][3] as f64, t.q[k][1] as f64 / t.q[k][3] as f64];
    let (a, b, p) = (px(0), px(1), px(2));
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (p[0] - a[0], p[1] - a[1]);
    (bx * cy - by * cx).abs() / (bx * bx + by * by)
}

fn sliver(aspect: f64, rng: &mut ChaCha8Rng, i: u64, size: f32) -> Built {
    let mut cam = camera(rng, i % 2 == 1);
    let vertical = rng.gen_bool(0.5);
    // The base runs along camera x (y) at y = 0 (x = 0); with cy = 0 (cx = 0) its
    // pixel row (column) is exactly 0 whatever the depths.
    if vertical {
        cam.cx = 0.0;
    } else {
        cam.cy = 0.0;
    }
    let z = rng.log_uniform(0.5, 50.0);
    // Depths differ a little (three equal depths trip nilsson2012-depth's known
    // equal-depth rounding, which is not what this family is about).
    let zs: [f32; 3] = std::array::from_fn(|_| z * rng.gen_range(0.95..1.05));
    let len = z * rng.log_uniform(0.01, 0.3);
    let a0 = rng.gen_range(-0.3..0.3) * z - 0.5 * len;
    let f = rng.gen_range(0.2..0.8);
    // (along the base, across it, depth) -> camera space
    let place = |p: [f32; 3]| if vertical { [p[1], p[0], p[2]] } else { p };
    let along = |p: [f32; 3]| {
        let c = cam.clip(place(p));
        (if vertical { c[1] } else { c[0] }) as f64 / c[3] as f64
    };
    let (pa, pb) = ([a0, 0.0, zs[0]], [a0 + len, 0.0, zs[1]]);
    let base = (along(pb) - along(pa)).abs();
    // The apex's pixel height is f_across off / z_C: set it to aspect * base.
    let f_across = if vertical { cam.fx } else { cam.fy } as f64;
    let off = (rng.sign() as f64 * aspect * base * zs[2] as f64 / f_across) as f32;
    let local = [pa, pb, [a0 + f * len, off, zs[2]]];
    let q = local.map(place);
    let r = if rng.gen_bool(0.5) {
        let da = rng.gen_range(-1.0..1.0) * len * rng.log_uniform(0.1, 3.0);
        let dz = rng.gen_range(-0.3..0.3) * z;
        local.map(|p| place([p[0] + da, p[1], p[2] + dz]))
    } else {
        q
    };
    let (case, tile) = finish(cam, q, r, rng, size);
    let achieved = pixel_aspect(&case);
    Built { case, tile, achieved }
}

/// Distance of the t = 0 triangle's centroid (seen from the lens centre) from the
/// screen origin, in pixels.
pub fn centroid_distance(c: &Case) -> f64 {
    let t = &c.triangle;
    let (mut x, mut y) = (0.0, 0.0);
    for k in 0..3 {
        x += t.q[k][0] as f64 / t.q[k][3] as f64 / 3.0;
        y += t.q[k][1] as f64 / t.q[k][3] as f64 / 3.0;
    }
    x.hypot(y)
}

fn far(dist: f64, rng: &mut ChaCha8Rng, i: u64, size: f32) -> Built {
    let (lens, moving) = [(false, false), (false, true), (true, false), (true, true)][(i % 4) as usize];
    let mut cam = camera(rng, lens);
    let phi = rng.gen_range(0.0..std::f64::consts::TAU);
    cam.cx = (dist * phi.cos()) as f32;
    cam.cy = (dist * phi.sin()) as f32;
    let z = rng.log_uniform(1.0, 20.0);
    let s = rng.log_uniform(2.0, 40.0) as f64;
    let mut o: [[f64; 2]; 3] = std::array::from_fn(|_| [rng.gen_range(-1.0..1.0) * s, rng.gen_range(-1.0..1.0) * s]);
    let mean = [(o[0][0] + o[1][0] + o[2][0]) / 3.0, (o[0][1] + o[1][1] + o[2][1]) / 3.0];
    for p in o.iter_mut() {
        p[0] -= mean[0];
        p[1] -= mean[1];
    }
    let (fx, fy) = (cam.fx as f64, cam.fy as f64);
    // Depths differ a little (see `sliver`); X = o z / fx keeps the pixel offsets o.
    let zs: [f32; 3] = std::array::from_fn(|_| z * rng.gen_range(0.95..1.05));
    let q: [[f32; 3]; 3] = std::array::from_fn(|k| {
        let zf = zs[k] as f64;
        [(o[k][0] * zf / fx) as f32, (o[k][1] * zf / fy) as f32, zs[k]]
    });
    let zf = z as f64;
    let r = if moving {
        let m = s * rng.log_uniform(0.1, 3.0) as f64;
        let a = rng.gen_range(0.0..std::f64::consts::TAU);
        let dz = rng.gen_range(-0.1..0.1) * z;
        q.map(|p| [p[0] + (m * a.cos() * zf / fx) as f32, p[1] + (m * a.sin() * zf / fy) as f32, p[2] + dz])
    } else {
        q
    };
    let (case, tile) = finish(cam, q, r, rng, size);
    let achieved = centroid_distance(&case);
    Built { case, tile, achieved }
}

// ---------------------------------------------------------------------------------
// double-root

/// The tangency of the moving edge A-B at the point P, from f32 pixel coordinates
/// `v = [A0x, A0y, A1x, A1y, B0x, B0y, B1x, B1y]` (A0 = A at t = 0, A1 at t = 1).
/// The edge value at P, `e(t) = (A(t) - P) x (B(t) - P) = alpha t^2 + beta t + gamma`.
#[derive(Clone, Copy, Debug)]
pub struct Tangency {
    pub alpha: Interval,
    pub beta: Interval,
    pub gamma: Interval,
    /// `beta^2 - 4 alpha gamma`, enclosed (outward rounded from the exact f32 data).
    pub disc: Interval,
    /// Time of closest approach `-beta / (2 alpha)`.
    pub tm: f64,
    /// How far P lies on the edge's covered side at `tm` (pixels; negative: never
    /// reached): `disc / (4 alpha |B(tm) - A(tm)|)`, the minimum of `-e` over the
    /// shutter over the edge length.
    pub delta: f64,
}

/// See [`Tangency`].
pub fn tangency(v: &[f32; 8], p: [f32; 2]) -> Tangency {
    // f32 - f32 is exact in f64 for the magnitudes used here.
    let rel = |k: usize| [v[k] as f64 - p[0] as f64, v[k + 1] as f64 - p[1] as f64];
    tangency_rel([rel(0), rel(2), rel(4), rel(6)])
}

/// [`tangency`] of `A0, A1, B0, B1` given relative to P (exact when the inputs are).
fn tangency_rel([a0, a1, b0, b1]: [[f64; 2]; 4]) -> Tangency {
    let pt = Interval::point;
    let da = [pt(a1[0] - a0[0]), pt(a1[1] - a0[1])];
    let db = [pt(b1[0] - b0[0]), pt(b1[1] - b0[1])];
    let a = [pt(a0[0]), pt(a0[1])];
    let b = [pt(b0[0]), pt(b0[1])];
    let cross = |p: [Interval; 2], q: [Interval; 2]| p[0] * q[1] - p[1] * q[0];
    let alpha = cross(da, db);
    let beta = cross(a, db) + cross(da, b);
    let gamma = cross(a, b);
    let disc = beta * beta - pt(4.0) * alpha * gamma;
    let tm = -beta.mid() / (2.0 * alpha.mid());
    let len = {
        let ax = a0[0] + tm * (a1[0] - a0[0]);
        let ay = a0[1] + tm * (a1[1] - a0[1]);
        let bx = b0[0] + tm * (b1[0] - b0[0]);
        let by = b0[1] + tm * (b1[1] - b0[1]);
        (bx - ax).hypot(by - ay)
    };
    Tangency { alpha, beta, gamma, disc, tm, delta: disc.mid() / (4.0 * alpha.mid() * len) }
}

fn nudge(x: f32, n: i32) -> f32 {
    let mut y = x;
    for _ in 0..n.unsigned_abs() {
        y = if n > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

/// Nudge the eight coordinates by at most +-`K` ulps each so that the tangency depth
/// comes as close to `target` as the f32 grid allows: the per-ulp effect of each
/// coordinate is measured on the f32 data, the best combinations of a linear model are
/// found by meet in the middle (two halves of 7^4 sums), and the best few are
/// re-measured.
fn fit_delta(v: [f32; 8], p: [f32; 2], target: f64) -> [f32; 8] {
    const K: i32 = 3;
    let d0 = tangency(&v, p).delta;
    let c: [f64; 8] = std::array::from_fn(|k| {
        let (mut up, mut dn) = (v, v);
        up[k] = nudge(v[k], 1);
        dn[k] = nudge(v[k], -1);
        0.5 * (tangency(&up, p).delta - tangency(&dn, p).delta)
    });
    let want = target - d0;
    let half = |ks: [usize; 4]| -> Vec<(f64, [i32; 4])> {
        let mut out = Vec::with_capacity(2401);
        let r = -K..=K;
        for n0 in r.clone() {
            for n1 in r.clone() {
                for n2 in r.clone() {
                    for n3 in r.clone() {
                        let n = [n0, n1, n2, n3];
                        let s: f64 = (0..4).map(|j| c[ks[j]] * n[j] as f64).sum();
                        out.push((s, n));
                    }
                }
            }
        }
        out
    };
    let h1 = half([0, 1, 2, 3]);
    let mut h2 = half([4, 5, 6, 7]);
    h2.sort_by(|a, b| a.0.total_cmp(&b.0));
    // The best pairs of the linear model (many: the model is only linear to about
    // 1e-9 px over a few ulps of every coordinate, so the exact values scatter).
    const KEEP: usize = 4096;
    let mut best: Vec<(f64, [i32; 4], [i32; 4])> = Vec::new();
    let mut worst_kept = f64::INFINITY;
    for (s1, n1) in &h1 {
        let j = h2.partition_point(|x| x.0 < want - s1);
        for jj in [j.saturating_sub(1), j.min(h2.len() - 1)] {
            let err = (s1 + h2[jj].0 - want).abs();
            if best.len() < KEEP {
                best.push((err, *n1, h2[jj].1));
                if best.len() == KEEP {
                    worst_kept = best.iter().map(|b| b.0).fold(0.0, f64::max);
                }
            } else if err < worst_kept {
                let w = best.iter_mut().max_by(|a, b| a.0.total_cmp(&b.0)).unwrap();
                *w = (err, *n1, h2[jj].1);
                worst_kept = best.iter().map(|b| b.0).fold(0.0, f64::max);
            }
        }
    }
    let mut out = v;
    let mut out_err = (d0 - target).abs();
    for (_, n1, n2) in best {
        let mut w = v;
        for j in 0..4 {
            w[j] = nudge(v[j], n1[j]);
            w[j + 4] = nudge(v[j + 4], n2[j]);
        }
        let e = (tangency(&w, p).delta - target).abs();
        if e < out_err {
            (out, out_err) = (w, e);
        }
    }
    out
}

/// The canonical grazing configuration (points relative to P): A(t), B(t) at t = 0 and
/// 1, and C, with the tangency at time `tm` (the test's configuration, whose tangency is
/// at 1/2, run `tm - 1/2` later). `d` moves A across the edge: P's depth is `0.2981 d`.
fn canonical(d: f64, tm: f64) -> [[f64; 2]; 5] {
    let (s0, s1) = (0.5 - tm, 1.5 - tm);
    [[-10.0 + s0, -19.0 + d], [-10.0 + s1, -19.0 + d], [19.0, 36.0 + 4.0 * s0], [19.0, 36.0 + 4.0 * s1], [20.0, -20.0]]
}

fn double_root(target: f64, rng: &mut ChaCha8Rng, size: f32) -> Built {
    let mut cam = camera(rng, false);
    let fx = 2f32.powi(rng.gen_range(7..=10));
    (cam.fx, cam.fy, cam.cx, cam.cy) = (fx, fx, 0.0, 0.0);
    // A power-of-two depth per vertex (pixel = clip / w stays exact; the depths differ,
    // see `sliver`).
    let zs: [f32; 3] = std::array::from_fn(|_| 2f32.powi(rng.gen_range(-1..=4)));
    // The tile and its grazed corner P.
    let (gi, gj) = (rng.gen_range(-64i32..64), rng.gen_range(-64i32..64));
    let (x0, y0) = (gi as f32 * size, gj as f32 * size);
    let (ci, cj) = (rng.gen_range(0..2), rng.gen_range(0..2));
    let p = [x0 + ci as f32 * size, y0 + cj as f32 * size];
    // A random affine image of the canonical configuration (an affine map with positive
    // determinant keeps every edge's sign at every point, so the tangency and the
    // coverage around P): a stretch by 0.7-1.4 along a random axis and its normal (so
    // that no two coordinates act alike, which the fit below needs), a rotation that
    // turns the edge's uncovered normal onto the diagonal into the tile from P (give or
    // take 20 degrees), and a scale of 0.5-2.
    let tm = rng.gen_range(0.35..0.65);
    let (s1, s2) = (rng.log_uniform(0.7, 1.4) as f64, rng.log_uniform(0.7, 1.4) as f64);
    let (sp, cp) = rng.gen_range(0.0..std::f64::consts::PI).sin_cos();
    let stretch = |[x, y]: [f64; 2]| {
        let (u, w) = (cp * x + sp * y, -sp * x + cp * y);
        let (u, w) = (s1 * u, s2 * w);
        [cp * u - sp * w, sp * u + cp * w]
    };
    // The normal of the canonical edge's uncovered side is (-2, 1); a symmetric stretch
    // maps normals by its inverse.
    let n = {
        let (x, y) = (-2.0, 1.0);
        let (u, w) = (cp * x + sp * y, -sp * x + cp * y);
        let (u, w) = (u / s1, w / s2);
        [cp * u - sp * w, sp * u + cp * w]
    };
    let into = [(1 - 2 * ci) as f64, (1 - 2 * cj) as f64];
    let theta = into[1].atan2(into[0]) - n[1].atan2(n[0]) + rng.gen_range(-0.35..0.35);
    let s = rng.log_uniform(0.5, 2.0) as f64;
    let (sn, cs) = theta.sin_cos();
    let map = |pt: [f64; 2]| {
        let [x, y] = stretch(pt);
        [s * (cs * x - sn * y), s * (sn * x + cs * y)]
    };
    let design = |d: f64| canonical(d, tm).map(map);
    // The depth of P in the design (exact arithmetic aside) is the target.
    let mut d = target / (0.2981 * s);
    for _ in 0..8 {
        let g = design(d);
        d *= target / tangency_rel([g[0], g[1], g[2], g[3]]).delta;
    }
    let pts = design(d);
    let mut v: [f32; 8] = std::array::from_fn(|k| (p[k % 2] as f64 + pts[k / 2][k % 2]) as f32);
    for _ in 0..6 {
        if (tangency(&v, p).delta / target - 1.0).abs() < 1e-4 {
            break;
        }
        v = fit_delta(v, p, target);
    }
    let c = [(p[0] as f64 + pts[4][0]) as f32, (p[1] as f64 + pts[4][1]) as f32];
    // Camera space: X = x z / fx is exact (powers of two), and so is the clip x = fx X.
    let cam_pt = |x: f32, y: f32, z: f32| [x * (z / fx), y * (z / fx), z];
    let q = [cam_pt(v[0], v[1], zs[0]), cam_pt(v[4], v[5], zs[1]), cam_pt(c[0], c[1], zs[2])];
    let r = [cam_pt(v[2], v[3], zs[0]), cam_pt(v[6], v[7], zs[1]), cam_pt(c[0], c[1], zs[2])];
    let case = Case { triangle: cam.triangle(q, r), lens: Some(cam) };
    let tile = Tile::square(x0, y0, size);
    Built { case, tile, achieved: tangency(&v, p).delta }
}

/// The grazed corner P of a double-root case and the eight moving coordinates, read
/// back from the f32 clip data (pixel = clip / w).
pub fn double_root_parts(b: &Built) -> ([f32; 8], [f32; 2]) {
    let t = &b.case.triangle;
    let px = |p: [f32; 4]| [p[0] / p[3], p[1] / p[3]];
    let (a0, a1, b0, b1) = (px(t.q[0]), px(t.r[0]), px(t.q[1]), px(t.r[1]));
    let v = [a0[0], a0[1], a1[0], a1[1], b0[0], b0[1], b1[0], b1[1]];
    // P is the tile corner nearest to A-B's closest approach: the one with the largest depth.
    let tl = &b.tile;
    let corners = [[tl.x0, tl.y0], [tl.x1, tl.y0], [tl.x0, tl.y1], [tl.x1, tl.y1]];
    let p = corners.into_iter().max_by(|a, c| tangency(&v, *a).delta.total_cmp(&tangency(&v, *c).delta)).unwrap();
    (v, p)
}
