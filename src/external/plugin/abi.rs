//! The C ABI of `include/cullproof.h`: its version and caps, the `#[repr(C)]` types and
//! function pointers of a plugin's table, the calls into it, and reading its strings.

use std::ffi::{c_char, c_void};

/// The version of `include/cullproof.h` this build speaks.
pub const ABI_VERSION: u32 = 1;

/// The most per-sample constraints one tile answer may give (`CP_MAX_CONSTRAINTS`):
/// far more than any published bound uses (a handful), few enough that the adapter's
/// handles (32 bytes each) stay small. A larger `n_constraints` stops the run.
pub const MAX_CONSTRAINTS: u32 = 4096;

/// The longest string, in bytes before its NUL, a plugin may hand over (`CP_MAX_TEXT`):
/// `source`, a `disabled` reason, a constraint name. A string with no NUL within this
/// many bytes (plus one) is refused; cullproof never reads further.
pub const MAX_TEXT: usize = 1024;

/// The most distinct `disabled` strings (by address) one plugin may return
/// (`CP_MAX_REASONS`): they must be static, and each is copied once.
pub const MAX_REASONS: usize = 256;

pub(super) const CP_OUT_TILE_REJECT: u32 = 1;
pub(super) const CP_OUT_LENS: u32 = 2;
pub(super) const CP_OUT_TIME: u32 = 4;
pub(super) const CP_OUT_DEPTH: u32 = 8;
pub(super) const CP_OUT_PER_SAMPLE: u32 = 16;
pub(super) const CP_EMPTY: i32 = 0;
pub(super) const CP_BOUNDS: i32 = 1;

#[repr(C)]
pub(super) struct CpTriangle {
    pub(super) q: [[f32; 4]; 3],
    pub(super) r: [[f32; 4]; 3],
    pub(super) c0: [f32; 3],
    pub(super) c1: [f32; 3],
    pub(super) k: f32,
}

#[repr(C)]
pub(super) struct CpTile {
    pub(super) x0: f32,
    pub(super) y0: f32,
    pub(super) x1: f32,
    pub(super) y1: f32,
}

#[repr(C)]
pub(super) struct CpSample {
    pub(super) x: f32,
    pub(super) y: f32,
    pub(super) u: f32,
    pub(super) v: f32,
    pub(super) t: f32,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub(super) struct CpInterval {
    pub(super) lo: f64,
    pub(super) hi: f64,
}

#[repr(C)]
pub(super) struct CpSampleBox {
    pub(super) x: CpInterval,
    pub(super) y: CpInterval,
    pub(super) u: CpInterval,
    pub(super) v: CpInterval,
    pub(super) t: CpInterval,
}

#[repr(C)]
pub(super) struct CpBounds {
    pub(super) u: [f32; 2],
    pub(super) v: [f32; 2],
    pub(super) t: [f32; 2],
    pub(super) has_z: i32,
    pub(super) z: [f32; 2],
    pub(super) n_constraints: u32,
    pub(super) tile_state: *mut c_void,
}

pub(super) type SetupFn = unsafe extern "C" fn(*const CpTriangle, *mut *const c_char) -> *mut c_void;
pub(super) type TileFn = unsafe extern "C" fn(*const c_void, *const CpTile, *mut CpBounds) -> i32;
pub(super) type EvalFn = unsafe extern "C" fn(*const c_void, u32, *const CpSample) -> f32;
pub(super) type EvalBoxFn = unsafe extern "C" fn(*const c_void, u32, *const CpSampleBox, *mut CpInterval) -> i32;
pub(super) type NameFn = unsafe extern "C" fn(*const c_void, u32) -> *const c_char;
pub(super) type FreeFn = unsafe extern "C" fn(*mut c_void);

#[repr(C)]
pub(super) struct CpMethod {
    pub(super) abi_version: u32,
    pub(super) id: *const c_char,
    pub(super) source: *const c_char,
    pub(super) outputs: u32,
    pub(super) setup: Option<SetupFn>,
    pub(super) tile: Option<TileFn>,
    pub(super) eval: Option<EvalFn>,
    pub(super) eval_box: Option<EvalBoxFn>,
    pub(super) constraint_name: Option<NameFn>,
    pub(super) free_tile: Option<FreeFn>,
    pub(super) free_state: Option<FreeFn>,
}

/// The functions of a loaded plugin (checked at load).
pub(super) struct Table {
    pub(super) setup: SetupFn,
    pub(super) tile: TileFn,
    pub(super) eval: Option<EvalFn>,
    pub(super) eval_box: Option<EvalBoxFn>,
    pub(super) constraint_name: Option<NameFn>,
    pub(super) free_tile: Option<FreeFn>,
    pub(super) free_state: Option<FreeFn>,
}

/// A call into a plugin, as messages name it (the watchdog keeps it as a small number).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Call {
    Entry = 1,
    Setup,
    Tile,
    Eval,
    EvalBox,
    ConstraintName,
    FreeTile,
    FreeState,
}

impl Call {
    pub(super) const ALL: [Call; 8] = [
        Call::Entry,
        Call::Setup,
        Call::Tile,
        Call::Eval,
        Call::EvalBox,
        Call::ConstraintName,
        Call::FreeTile,
        Call::FreeState,
    ];
    pub(super) fn name(self) -> &'static str {
        match self {
            Call::Entry => "cullproof_method()",
            Call::Setup => "setup()",
            Call::Tile => "tile()",
            Call::Eval => "eval()",
            Call::EvalBox => "eval_box()",
            Call::ConstraintName => "constraint_name()",
            Call::FreeTile => "free_tile()",
            Call::FreeState => "free_state()",
        }
    }
}

/// The bytes of the string at `p` (not NULL) if its NUL lies within [`MAX_TEXT`]
/// bytes; bytes past the NUL or past the cap are never read.
///
/// # Safety
/// `p` points at readable bytes up to its NUL or the cap, whichever comes first.
pub(super) unsafe fn bounded_text(p: *const c_char) -> std::result::Result<Vec<u8>, ()> {
    let mut bytes = Vec::new();
    for i in 0..=MAX_TEXT {
        let b = *p.add(i) as u8;
        if b == 0 {
            return Ok(bytes);
        }
        bytes.push(b);
    }
    Err(())
}
