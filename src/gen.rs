//! Seeded generators of cases (thin-lens, physical) across the regimes where culling
//! bounds are stressed. Every draw comes from a `ChaCha8Rng` seeded from (seed, index),
//! so a case is the same at any thread count.

use crate::model::{Case, Sample, ThinLens, Tile, Triangle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// The regimes of physical cases.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "kebab-case")]
pub enum Regime {
    Static,
    Motion,
    Defocus,
    Both,
    /// Vertices on both sides of the focal plane (their CoC changes sign).
    FocalCrossing,
    /// A vertex behind the lens (w < 0) at some time.
    BehindLens,
    /// A needle-thin triangle.
    Sliver,
}

impl Regime {
    pub const ALL: [Regime; 7] = [
        Regime::Static,
        Regime::Motion,
        Regime::Defocus,
        Regime::Both,
        Regime::FocalCrossing,
        Regime::BehindLens,
        Regime::Sliver,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Regime::Static => "static",
            Regime::Motion => "motion",
            Regime::Defocus => "defocus",
            Regime::Both => "both",
            Regime::FocalCrossing => "focal-crossing",
            Regime::BehindLens => "behind-lens",
            Regime::Sliver => "sliver",
        }
    }
}

/// The rng of case `index` of a run with `seed`.
pub fn rng_for(seed: u64, index: u64) -> ChaCha8Rng {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    r.set_stream(index);
    r
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    (rng.gen_range(lo.ln()..hi.ln())).exp()
}

/// A random thin-lens camera; `lens` false gives a pinhole (R = 0).
pub fn camera(rng: &mut ChaCha8Rng, lens: bool) -> ThinLens {
    let fx = log_uniform(rng, 100.0, 2000.0);
    let k = if rng.gen_bool(0.5) { 1.0 } else { 0.75 };
    ThinLens {
        fx,
        fy: fx * k,
        cx: rng.gen_range(-50.0..50.0),
        cy: rng.gen_range(-50.0..50.0),
        radius: if lens { log_uniform(rng, 0.005, 0.2) } else { 0.0 },
        focus: log_uniform(rng, 1.0, 20.0),
        near: 0.1,
        far: 1000.0,
    }
}

/// A physical case of the regime.
pub fn physical_case(rng: &mut ChaCha8Rng, regime: Regime) -> Case {
    use Regime::*;
    let lens = matches!(regime, Defocus | Both | FocalCrossing | BehindLens | Sliver)
        && !(regime == Sliver && rng.gen_bool(0.3));
    let cam = camera(rng, lens);
    let moving = matches!(regime, Motion | Both | BehindLens) || (regime == Sliver && rng.gen_bool(0.5));
    // Centre depth and size.
    let z = match regime {
        FocalCrossing => cam.focus * rng.gen_range(0.7..1.3),
        _ => log_uniform(rng, 0.5, 50.0),
    };
    let size = z * log_uniform(rng, 1e-3, 0.3);
    let centre = [rng.gen_range(-0.3..0.3) * z, rng.gen_range(-0.3..0.3) * z, z];
    let mut q = [[0.0f32; 3]; 3];
    for p in q.iter_mut() {
        for j in 0..3 {
            p[j] = centre[j] + rng.gen_range(-1.0..1.0) * size;
        }
    }
    match regime {
        FocalCrossing => {
            q[0][2] = cam.focus * rng.gen_range(0.5..0.95);
            q[1][2] = cam.focus * rng.gen_range(1.05..2.0);
        }
        BehindLens => {
            q[0][2] = -rng.gen_range(0.01..1.0) * z;
        }
        Sliver => {
            let f = log_uniform(rng, 1e-5, 1e-2);
            let (a, b) = (q[0], q[1]);
            for (j, c) in q[2].iter_mut().enumerate() {
                *c = a[j] + (b[j] - a[j]) * rng.gen_range(0.2..0.8) + f * size * rng.gen_range(-1.0..1.0);
            }
        }
        _ => {}
    }
    let mut r = q;
    if moving {
        let m = size * log_uniform(rng, 0.1, 10.0);
        let d = [rng.gen_range(-1.0..1.0) * m, rng.gen_range(-1.0..1.0) * m, rng.gen_range(-0.5..0.5) * m];
        for (i, p) in r.iter_mut().enumerate() {
            let wobble = if rng.gen_bool(0.3) { rng.gen_range(-0.3..0.3) * m } else { 0.0 };
            for j in 0..3 {
                p[j] += d[j] + if j == i { wobble } else { 0.0 };
            }
        }
    }
    let tri: Triangle = cam.triangle(q, r);
    Case { triangle: tri, lens: Some(cam) }
}

/// A uniform sample with (x, y) in the tile, over the whole lens and shutter.
pub fn tile_sample(rng: &mut ChaCha8Rng, tile: &Tile) -> Sample {
    Sample::new(
        rng.gen_range(tile.x0..=tile.x1),
        rng.gen_range(tile.y0..=tile.y1),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(0.0..=1.0),
    )
}

/// Samples for a case: half uniform over the triangle's screen region, half drawn near
/// its edges (a point on an edge of the sheared triangle at a random (u, v, t), pushed
/// off by 2^-e pixels, e uniform in [0, 40]). Rounded to f32 as hardware samples are.
pub fn samples_for(case: &Case, rng: &mut ChaCha8Rng, n: usize) -> Vec<[f64; 5]> {
    let tri = &case.triangle;
    let dims = tri.dims();
    let (lens, time) = (dims.has_lens(), dims.has_time());
    // Screen region: projected vertices over both shutter ends and lens corners.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for tt in [0.0f32, 1.0] {
        for (uu, vv) in [(-1.0f32, -1.0f32), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            for i in 0..3 {
                let p = tri.at(i, tt);
                let c = tri.coc(i, tt);
                if p[3] > 0.0 {
                    let px = ((p[0] + uu * c) / p[3]) as f64;
                    let py = ((p[1] + tri.k * vv * c) / p[3]) as f64;
                    x0 = x0.min(px);
                    x1 = x1.max(px);
                    y0 = y0.min(py);
                    y1 = y1.max(py);
                }
            }
        }
    }
    if !(x0.is_finite() && x1.is_finite() && y0.is_finite() && y1.is_finite()) || x1 - x0 > 1e5 || y1 - y0 > 1e5 {
        (x0, x1, y0, y1) = (-2000.0, 2000.0, -2000.0, 2000.0);
    }
    let pad = 0.1 * (x1 - x0).max(y1 - y0) + 1.0;
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let u = if lens { rng.gen_range(-1.0f32..=1.0) } else { 0.0 };
        let v = if lens { rng.gen_range(-1.0f32..=1.0) } else { 0.0 };
        let t = if time { rng.gen_range(0.0f32..=1.0) } else { 0.0 };
        let (x, y) = if out.len() % 2 == 0 {
            (rng.gen_range(x0 - pad..=x1 + pad), rng.gen_range(y0 - pad..=y1 + pad))
        } else {
            let i = rng.gen_range(0..3);
            let j = (i + 1) % 3;
            let proj = |k: usize| {
                let p = tri.at(k, t);
                let c = tri.coc(k, t);
                ((p[0] + u * c) as f64 / p[3] as f64, (p[1] + tri.k * v * c) as f64 / p[3] as f64, p[3])
            };
            let (ax, ay, aw) = proj(i);
            let (bx, by, bw) = proj(j);
            if !(aw > 0.0 && bw > 0.0) {
                continue;
            }
            let f: f64 = rng.gen_range(0.0..=1.0);
            let off = 2f64.powf(-rng.gen_range(0.0..40.0)) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            let (dx, dy) = (by - ay, -(bx - ax));
            let len = (dx * dx + dy * dy).sqrt().max(1e-300);
            (ax + f * (bx - ax) + off * dx / len, ay + f * (by - ay) + off * dy / len)
        };
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        out.push([x as f32 as f64, y as f32 as f64, u as f64, v as f64, t as f64]);
    }
    out
}
