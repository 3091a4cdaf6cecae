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
//!
//! And two slips in the arithmetic of each variant written with the shared rounding
//! discipline ([`crate::bounds::round`]: `la2011-safe`, `nilsson2012-depth-safe`,
//! `mam2012-safe`, `wu2013-safe`, `gdam2010-safe`, `lb2011-safe`, and `lc-safe` through its
//! two parts), for
//! the proofs tied to the code ([`crate::bounds::proofs`]):
//! `broken/planted-no-up/M-safe` keeps every lower end's outward step but drops the
//! upper ends' (each upper end is the value rounded to nearest, as in the published
//! method), `broken/planted-no-dn/M-safe` the reverse. Each is one outward step dropped
//! from half of the operations: the kind of edit a proof of the variant must notice.
//! `bbox-safe` has the same two (`broken/planted-no-up/bbox-safe`,
//! `broken/planted-no-dn/bbox-safe`): its corner's four steps on one side dropped, the
//! pad kept.

use crate::bounds::arith::F32Arith;
use crate::bounds::bbox::{padded_corner, BBox, Corner, SafeCorner};
use crate::bounds::gdam2010::Gdam2010Safe;
use crate::bounds::la2011::La2011;
use crate::bounds::lb2011::Lb2011Safe;
use crate::bounds::lc::Lc;
use crate::bounds::mam2012::Mam2012Safe;
use crate::bounds::nilsson2012_depth::Nilsson2012Depth;
use crate::bounds::round::Round;
use crate::bounds::wu2013::Wu2013Safe;
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

/// `bbox-safe`'s corner with the outward steps of its upper end dropped (the pad kept).
#[derive(Clone, Copy, Debug)]
pub struct NoUpCorner;

impl Corner for NoUpCorner {
    fn corner<A: F32Arith>(&self, ar: &A, _a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        padded_corner(ar, s, n, w, [4, 0])
    }
}

/// `bbox-safe`'s corner with the outward steps of its lower end dropped.
#[derive(Clone, Copy, Debug)]
pub struct NoDnCorner;

impl Corner for NoDnCorner {
    fn corner<A: F32Arith>(&self, ar: &A, _a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        padded_corner(ar, s, n, w, [0, 4])
    }
}

/// A `-safe` arithmetic ([`Round`]) with the upper ends' steps dropped.
pub struct NoUp;

impl Round for NoUp {
    fn dn<A: F32Arith>(ar: &A, x: &A::F) -> A::F {
        ar.next_down(x)
    }
    fn up<A: F32Arith>(_: &A, x: &A::F) -> A::F {
        x.clone()
    }
    fn bad<A: F32Arith>(ar: &A, x: &A::F) -> A::B {
        ar.not(&ar.is_finite(x))
    }
    const GUARD: bool = true;
}

/// A `-safe` arithmetic with the lower ends' steps dropped.
pub struct NoDn;

impl Round for NoDn {
    fn dn<A: F32Arith>(_: &A, x: &A::F) -> A::F {
        x.clone()
    }
    fn up<A: F32Arith>(ar: &A, x: &A::F) -> A::F {
        ar.next_up(x)
    }
    fn bad<A: F32Arith>(ar: &A, x: &A::F) -> A::B {
        ar.not(&ar.is_finite(x))
    }
    const GUARD: bool = true;
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

/// A planted slip's description: the method's own, under the slip's id and source.
const fn slip(id: &'static str, source: &'static str, of: MethodInfo) -> MethodInfo {
    MethodInfo { id, source, ..of }
}

static INFO_NO_UP: MethodInfo = slip(
    "broken/planted-no-up/la2011-safe",
    "la2011-safe with the outward step of every upper end dropped",
    crate::bounds::la2011::INFO,
);
static INFO_NO_DN: MethodInfo = slip(
    "broken/planted-no-dn/la2011-safe",
    "la2011-safe with the outward step of every lower end dropped",
    crate::bounds::la2011::INFO,
);
static INFO_NO_UP_DEPTH: MethodInfo = slip(
    "broken/planted-no-up/nilsson2012-depth-safe",
    "nilsson2012-depth-safe with the outward step of every upper end dropped",
    crate::bounds::nilsson2012_depth::INFO,
);
static INFO_NO_DN_DEPTH: MethodInfo = slip(
    "broken/planted-no-dn/nilsson2012-depth-safe",
    "nilsson2012-depth-safe with the outward step of every lower end dropped",
    crate::bounds::nilsson2012_depth::INFO,
);

/// `broken/planted-no-up/la2011-safe`.
pub static NO_UP: &dyn Method = &La2011::<NoUp> { info: &INFO_NO_UP, round: std::marker::PhantomData };
/// `broken/planted-no-dn/la2011-safe`.
pub static NO_DN: &dyn Method = &La2011::<NoDn> { info: &INFO_NO_DN, round: std::marker::PhantomData };

/// `broken/planted-no-up/nilsson2012-depth-safe`.
pub static NO_UP_DEPTH: &dyn Method =
    &Nilsson2012Depth::<NoUp> { info: &INFO_NO_UP_DEPTH, round: std::marker::PhantomData };
/// `broken/planted-no-dn/nilsson2012-depth-safe`.
pub static NO_DN_DEPTH: &dyn Method =
    &Nilsson2012Depth::<NoDn> { info: &INFO_NO_DN_DEPTH, round: std::marker::PhantomData };

static INFO_NO_UP_MAM: MethodInfo = slip(
    "broken/planted-no-up/mam2012-safe",
    "mam2012-safe with the outward step of every upper end dropped",
    crate::bounds::mam2012::INFO,
);
static INFO_NO_DN_MAM: MethodInfo = slip(
    "broken/planted-no-dn/mam2012-safe",
    "mam2012-safe with the outward step of every lower end dropped",
    crate::bounds::mam2012::INFO,
);

/// `broken/planted-no-up/mam2012-safe`.
pub static NO_UP_MAM: &dyn Method = &Mam2012Safe::<NoUp> { info: &INFO_NO_UP_MAM, round: std::marker::PhantomData };
/// `broken/planted-no-dn/mam2012-safe`.
pub static NO_DN_MAM: &dyn Method = &Mam2012Safe::<NoDn> { info: &INFO_NO_DN_MAM, round: std::marker::PhantomData };

static INFO_NO_UP_WU: MethodInfo = slip(
    "broken/planted-no-up/wu2013-safe",
    "wu2013-safe with the outward step of every upper end dropped",
    crate::bounds::wu2013::INFO,
);
static INFO_NO_DN_WU: MethodInfo = slip(
    "broken/planted-no-dn/wu2013-safe",
    "wu2013-safe with the outward step of every lower end dropped",
    crate::bounds::wu2013::INFO,
);

/// `broken/planted-no-up/wu2013-safe`.
pub static NO_UP_WU: &dyn Method = &Wu2013Safe::<NoUp> { info: &INFO_NO_UP_WU, round: std::marker::PhantomData };
/// `broken/planted-no-dn/wu2013-safe`.
pub static NO_DN_WU: &dyn Method = &Wu2013Safe::<NoDn> { info: &INFO_NO_DN_WU, round: std::marker::PhantomData };

static INFO_NO_UP_GDAM: MethodInfo = slip(
    "broken/planted-no-up/gdam2010-safe",
    "gdam2010-safe with the outward step of every upper end dropped",
    crate::bounds::gdam2010::INFO,
);
static INFO_NO_DN_GDAM: MethodInfo = slip(
    "broken/planted-no-dn/gdam2010-safe",
    "gdam2010-safe with the outward step of every lower end dropped",
    crate::bounds::gdam2010::INFO,
);

/// `broken/planted-no-up/gdam2010-safe`.
pub static NO_UP_GDAM: &dyn Method = &Gdam2010Safe::<NoUp> { info: &INFO_NO_UP_GDAM, round: std::marker::PhantomData };
/// `broken/planted-no-dn/gdam2010-safe`.
pub static NO_DN_GDAM: &dyn Method = &Gdam2010Safe::<NoDn> { info: &INFO_NO_DN_GDAM, round: std::marker::PhantomData };

static INFO_NO_UP_LB: MethodInfo = slip(
    "broken/planted-no-up/lb2011-safe",
    "lb2011-safe with the outward step of every upper end dropped",
    crate::bounds::lb2011::INFO,
);
static INFO_NO_DN_LB: MethodInfo = slip(
    "broken/planted-no-dn/lb2011-safe",
    "lb2011-safe with the outward step of every lower end dropped",
    crate::bounds::lb2011::INFO,
);

/// `broken/planted-no-up/lb2011-safe`.
pub static NO_UP_LB: &dyn Method = &Lb2011Safe::<NoUp> { info: &INFO_NO_UP_LB, round: std::marker::PhantomData };
/// `broken/planted-no-dn/lb2011-safe`.
pub static NO_DN_LB: &dyn Method = &Lb2011Safe::<NoDn> { info: &INFO_NO_DN_LB, round: std::marker::PhantomData };

static INFO_NO_UP_LC: MethodInfo = slip(
    "broken/planted-no-up/lc-safe",
    "lc-safe with the outward step of every upper end dropped (in both parts)",
    crate::bounds::lc::INFO,
);
static INFO_NO_DN_LC: MethodInfo = slip(
    "broken/planted-no-dn/lc-safe",
    "lc-safe with the outward step of every lower end dropped (in both parts)",
    crate::bounds::lc::INFO,
);

/// `broken/planted-no-up/lc-safe`: the conjunction of the two parts' no-up slips.
pub static NO_UP_LC: &dyn Method = &Lc { info: &INFO_NO_UP_LC, parts: &[&NO_UP, &NO_UP_LB] };
/// `broken/planted-no-dn/lc-safe`: the conjunction of the two parts' no-dn slips.
pub static NO_DN_LC: &dyn Method = &Lc { info: &INFO_NO_DN_LC, parts: &[&NO_DN, &NO_DN_LB] };

static INFO_NO_UP_BOX: MethodInfo =
    slip("broken/planted-no-up/bbox-safe", "bbox-safe with the outward steps of every upper end dropped", INFO_EQ);
static INFO_NO_DN_BOX: MethodInfo =
    slip("broken/planted-no-dn/bbox-safe", "bbox-safe with the outward steps of every lower end dropped", INFO_EQ);

/// `broken/planted-no-up/bbox-safe`.
pub static NO_UP_BOX: &dyn Method = &BBox { info: &INFO_NO_UP_BOX, corner: NoUpCorner };
/// `broken/planted-no-dn/bbox-safe`.
pub static NO_DN_BOX: &dyn Method = &BBox { info: &INFO_NO_DN_BOX, corner: NoDnCorner };

/// `broken/planted-eq/bbox-safe`.
pub static EQ: &dyn Method = &BBox { info: &INFO_EQ, corner: EqSlip };
/// `broken/planted-band/bbox-safe`.
pub static BAND: &dyn Method = &BBox { info: &INFO_BAND, corner: BandSlip };

/// The planted variant with this id, if it is one.
pub fn parse(id: &str) -> Option<&'static dyn Method> {
    [
        EQ,
        BAND,
        NO_UP,
        NO_DN,
        NO_UP_DEPTH,
        NO_DN_DEPTH,
        NO_UP_MAM,
        NO_DN_MAM,
        NO_UP_WU,
        NO_DN_WU,
        NO_UP_GDAM,
        NO_DN_GDAM,
        NO_UP_LB,
        NO_DN_LB,
        NO_UP_LC,
        NO_DN_LC,
        NO_UP_BOX,
        NO_DN_BOX,
    ]
    .into_iter()
    .find(|m| m.info().id == id)
}
