//! Two rare slips planted in `bbox-safe` to measure what the symbolic search buys over
//! the random one (tests and `cullproof search`/`prove`; never in the registry). They
//! sit in the conservative variant so that they are the only way to fail (`bbox`'s own
//! f32 culls would be found first). Both are written over [`F32Arith`] like the
//! method, so the symbolic search sees exactly the code the random search runs.
//!
//! - `broken/planted-eq/bbox-safe`: a "fast path" for a vertex whose coordinate equals its
//!   shear exactly (`a == s`, so `a - s` is 0) that takes `a + s` instead: the box loses
//!   that corner, and a tile beside the triangle is culled. It fires only on an exact
//!   equality of two f32 inputs.
//! - `broken/planted-band/bbox-safe`: the shear dropped for a vertex whose depth lies in the
//!   narrow band `2 <= w < 2 + 2^-14` (a term wrong in a band of relative width 2^-15).

use super::arith::F32Arith;
use crate::bounds::bbox::{BBox, Corner, SafeCorner};
use crate::bounds::{Method, MethodInfo, Outputs};
use crate::model::Dims;

/// The exact-equality slip.
#[derive(Clone, Copy, Debug)]
pub struct EqSlip;

impl Corner for EqSlip {
    fn corner<A: F32Arith>(&self, ar: &A, a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        let slip = ar.eq(a, s);
        let n = ar.select(&slip, &ar.add(a, s), n);
        SafeCorner.corner(ar, a, s, &n, w)
    }
}

/// The lower end of the band of [`BandSlip`].
pub const BAND_LO: f32 = 2.0;
/// The upper end (excluded): `2 + 2^-14`.
pub const BAND_HI: f32 = 2.0 + 1.0 / 16384.0;

/// The narrow-band slip.
#[derive(Clone, Copy, Debug)]
pub struct BandSlip;

impl Corner for BandSlip {
    fn corner<A: F32Arith>(&self, ar: &A, a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        let band = ar.and(&ar.le(&ar.lit(BAND_LO), w), &ar.lt(w, &ar.lit(BAND_HI)));
        let n = ar.select(&band, a, n);
        SafeCorner.corner(ar, a, s, &n, w)
    }
}

const OUTPUTS: Outputs = Outputs { tile_reject: true, lens: false, time: false, depth: false, per_sample: false };
const DIMS: &[Dims] = &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both];

static INFO_EQ: MethodInfo = MethodInfo {
    id: "broken/planted-eq/bbox-safe",
    source: "bbox-safe with a slip that fires only when a vertex's coordinate equals its shear exactly",
    reconstruction: false,
    dims: DIMS,
    outputs: OUTPUTS,
};
static INFO_BAND: MethodInfo = MethodInfo {
    id: "broken/planted-band/bbox-safe",
    source: "bbox-safe with the shear dropped for depths 2 <= w < 2 + 2^-14",
    reconstruction: false,
    dims: DIMS,
    outputs: OUTPUTS,
};

/// `broken/planted-eq/bbox-safe`.
pub static EQ: &dyn Method = &BBox { info: &INFO_EQ, corner: EqSlip };
/// `broken/planted-band/bbox-safe`.
pub static BAND: &dyn Method = &BBox { info: &INFO_BAND, corner: BandSlip };

/// The planted variant with this id, if it is one.
pub fn parse(id: &str) -> Option<&'static dyn Method> {
    [EQ, BAND].into_iter().find(|m| m.info().id == id)
}
