//! Seeded generators of cases (thin-lens, physical) across the regimes where culling
//! bounds are stressed. Every draw comes from a `ChaCha8Rng` seeded from (seed, index),
//! so a case is the same at any thread count.

use crate::model::{Case, ThinLens, Triangle};
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
