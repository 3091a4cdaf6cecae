//! Exact coverage: the one place the measurement asks the exact oracle
//! ([`exact_coverage`]), through the batched oracle.

use crate::model::Sample;
use oracles::batch::Batch;
use oracles::Coverage;

/// Buffers of [`exact_coverage`], reused from call to call.
#[derive(Default)]
pub struct CoverageScratch {
    points: Vec<[f64; 5]>,
    classes: Vec<Coverage>,
}

/// The exact coverage of `samples` by the triangle of `batch`, one entry per sample
/// (interior only: boundary samples are not covered), written to `out`; returns
/// (covered, boundary, exact). The one place the measurement asks the exact oracle: the
/// batched oracle (`oracles::batch`), which classifies the samples side by side in lanes
/// and sends every sample whose signs it cannot certify to the scalar oracle, so every
/// class is the scalar oracle's (`oracles::coverage::classify`). `exact` counts the
/// samples decided by exact dyadic arithmetic: those neither the lanes nor the scalar
/// oracle's floating-point filter could settle.
pub fn exact_coverage(
    batch: &Batch,
    samples: &[Sample],
    scratch: &mut CoverageScratch,
    out: &mut [bool],
) -> (u64, u64, u64) {
    scratch.points.clear();
    scratch.points.extend(samples.iter().map(Sample::to_oracle));
    let st = batch.classify(&scratch.points, &mut scratch.classes);
    let (mut covered, mut boundary) = (0u64, 0u64);
    for (c, o) in scratch.classes.iter().zip(out.iter_mut()) {
        *o = *c == Coverage::Interior;
        covered += *o as u64;
        boundary += (*c == Coverage::Boundary) as u64;
    }
    (covered, boundary, st.exact_fallbacks)
}

/// [`exact_coverage`] sample by sample with the scalar oracle (the reference the
/// batched path is tested against).
#[cfg(test)]
pub(crate) fn exact_coverage_scalar(tri: &oracles::Tri, samples: &[Sample], out: &mut [bool]) -> (u64, u64, u64) {
    let (mut covered, mut boundary, mut exact) = (0u64, 0u64, 0u64);
    for (s, o) in samples.iter().zip(out.iter_mut()) {
        let (c, ex) = oracles::coverage::classify_traced(tri, s.to_oracle());
        exact += ex as u64;
        *o = c == Coverage::Interior;
        covered += *o as u64;
        boundary += (c == Coverage::Boundary) as u64;
    }
    (covered, boundary, exact)
}
