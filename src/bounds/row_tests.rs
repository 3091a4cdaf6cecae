//! [`SampleConstraint::eval_row`] against [`SampleConstraint::eval`]: every constraint a
//! built-in method answers, on random samples of its tile and on samples with
//! infinite, huge, subnormal and NaN coordinates, gives the same f32 values bit for bit
//! (a NaN matches a NaN: which NaN an operation returns is not part of f32 arithmetic).

use super::*;
use crate::cases::generate::{boundary_tile, physical_case, rng_for, tile_sample, Regime};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The constraint's type, from its debug form (`Line { .. }` -> "Line"), with
/// "safe" appended to a hyperplane evaluated with downward steps.
fn kind(c: &dyn SampleConstraint) -> String {
    let d = format!("{c:?}");
    let head: String = d.chars().take_while(|ch| ch.is_alphanumeric() || *ch == '_').collect();
    if head == "Plane" && d.contains("safe: true") {
        "Plane safe".into()
    } else {
        head
    }
}

/// A sample coordinate that breaks arithmetic: infinities, NaN, huge, subnormal, -0.
fn odd(rng: &mut ChaCha8Rng) -> f32 {
    [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 3.0e38, -3.0e38, 1.0e-40, -0.0, f32::MAX][rng.gen_range(0..8)]
}

fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Compare `eval_row` with `eval` on `n` samples of `tile` (a quarter with one or more
/// odd coordinates); returns the NaN values seen.
fn check(c: &dyn SampleConstraint, tile: &Tile, rng: &mut ChaCha8Rng, n: usize) -> usize {
    let mut cols: [Vec<f32>; 5] = Default::default();
    for _ in 0..n {
        let s = tile_sample(rng, tile);
        let mut v = [s.x, s.y, s.u, s.v, s.t];
        if rng.gen_bool(0.25) {
            for x in v.iter_mut() {
                if rng.gen_bool(0.4) {
                    *x = odd(rng);
                }
            }
        }
        for (col, x) in cols.iter_mut().zip(v) {
            col.push(x);
        }
    }
    // Odd lengths and offsets too: a row that does not fill the vector width.
    let cut = rng.gen_range(0..n / 2);
    let [x, y, u, v, t] = &cols;
    let sc = SampleCols::new(&x[cut..], &y[cut..], &u[cut..], &v[cut..], &t[cut..], n - cut);
    let mut out = vec![0.0f32; n - cut];
    c.eval_row(&sc, &mut out);
    let mut nans = 0;
    for (i, &g) in out.iter().enumerate() {
        let e = c.eval(&sc.sample(i));
        assert!(
            same(g, e),
            "{}: eval_row {g} ({:#x}) != eval {e} ({:#x}) at {:?}",
            c.name(),
            g.to_bits(),
            e.to_bits(),
            sc.sample(i)
        );
        nans += g.is_nan() as usize;
    }
    nans
}

#[test]
fn eval_row_is_eval_bit_for_bit_for_every_overridden_constraint() {
    let mut seen: std::collections::BTreeMap<String, usize> = Default::default();
    let mut nans = 0;
    for (mi, m) in registry().into_iter().enumerate() {
        for (ri, regime) in Regime::ALL.into_iter().enumerate() {
            for k in 0..3u64 {
                let mut rng = rng_for(41, ((mi * 16 + ri) as u64) * 8 + k);
                let case = physical_case(&mut rng, regime);
                let prep = m.setup(&case.triangle);
                for size in [1.0f32, 4.0] {
                    let tile = boundary_tile(&case, &mut rng, size);
                    if let TileResult::Bounds(b) = prep.tile(&tile) {
                        for c in &b.constraints {
                            nans += check(c.as_ref(), &tile, &mut rng, 67);
                            *seen.entry(kind(c.as_ref())).or_default() += 1;
                        }
                    }
                }
            }
        }
    }
    for k in ["Line", "SafeLine", "Plane", "Plane safe", "Patch", "TimeLine", "TimeSpans", "SafeTimeSpans"] {
        assert!(seen.get(k).copied().unwrap_or(0) >= 3, "too few {k} constraints compared: {seen:?}");
    }
    assert!(nans > 0, "no NaN value compared");
}
