//! Culling bounds written in C (or anything with a C ABI), loaded at run time.
//!
//! A plugin is a shared library exporting `cullproof_method`, which returns the
//! `cp_method` table of `include/cullproof.h` (version [`ABI_VERSION`]). [`load`] opens
//! the library, checks the table (version, id, the functions its outputs need) and
//! returns a [`Method`] that calls the C functions; [`crate::bounds::plug`] makes it
//! known to every command by its own id (`cullproof check --plugin lib.so --method
//! my-bound`).
//!
//! What the adapter does with the answers, so that a mistake in the plugin shows up in
//! the gate instead of hiding:
//! - a tile answer other than `CP_BOUNDS` counts as `CP_EMPTY` (the tile is culled);
//! - interval ends are taken as given (a NaN end culls everything, as for built-in
//!   methods);
//! - a constraint without `eval_box` is evaluated per sample but cannot be certified:
//!   its box enclosure is the whole real line, so a case whose tile has it is proven
//!   only if the coverage search rules the tile's samples out, and is otherwise
//!   unproven (`constraint-budget`), never passed.
//!
//! The library stays loaded for the life of the process (the method is `'static`).
//! A plugin runs in cullproof's process: a crash in it ends the run. For bounds that
//! may crash, or that are not in C, use the process protocol instead.

use crate::bounds::{Method, MethodInfo, Outputs, Prepared, SampleBox, SampleConstraint, TileBounds, TileResult};
use crate::model::{Dims, Sample, Tile, Triangle};
use crate::Interval;
use anyhow::{bail, Context, Result};
use std::collections::HashMap;
use std::ffi::{c_char, c_void, CStr};
use std::path::Path;
use std::sync::{Arc, Mutex};

/// The version of `include/cullproof.h` this build speaks.
pub const ABI_VERSION: u32 = 1;

const CP_OUT_TILE_REJECT: u32 = 1;
const CP_OUT_LENS: u32 = 2;
const CP_OUT_TIME: u32 = 4;
const CP_OUT_DEPTH: u32 = 8;
const CP_OUT_PER_SAMPLE: u32 = 16;
const CP_BOUNDS: i32 = 1;

#[repr(C)]
struct CpTriangle {
    q: [[f32; 4]; 3],
    r: [[f32; 4]; 3],
    c0: [f32; 3],
    c1: [f32; 3],
    k: f32,
}

#[repr(C)]
struct CpTile {
    x0: f32,
    y0: f32,
    x1: f32,
    y1: f32,
}

#[repr(C)]
struct CpSample {
    x: f32,
    y: f32,
    u: f32,
    v: f32,
    t: f32,
}

#[repr(C)]
#[derive(Clone, Copy)]
struct CpInterval {
    lo: f64,
    hi: f64,
}

#[repr(C)]
struct CpSampleBox {
    x: CpInterval,
    y: CpInterval,
    u: CpInterval,
    v: CpInterval,
    t: CpInterval,
}

#[repr(C)]
struct CpBounds {
    u: [f32; 2],
    v: [f32; 2],
    t: [f32; 2],
    has_z: i32,
    z: [f32; 2],
    n_constraints: u32,
    tile_state: *mut c_void,
}

type SetupFn = unsafe extern "C" fn(*const CpTriangle, *mut *const c_char) -> *mut c_void;
type TileFn = unsafe extern "C" fn(*const c_void, *const CpTile, *mut CpBounds) -> i32;
type EvalFn = unsafe extern "C" fn(*const c_void, u32, *const CpSample) -> f32;
type EvalBoxFn = unsafe extern "C" fn(*const c_void, u32, *const CpSampleBox, *mut CpInterval) -> i32;
type NameFn = unsafe extern "C" fn(*const c_void, u32) -> *const c_char;
type FreeFn = unsafe extern "C" fn(*mut c_void);

#[repr(C)]
struct CpMethod {
    abi_version: u32,
    id: *const c_char,
    source: *const c_char,
    outputs: u32,
    setup: Option<SetupFn>,
    tile: Option<TileFn>,
    eval: Option<EvalFn>,
    eval_box: Option<EvalBoxFn>,
    constraint_name: Option<NameFn>,
    free_tile: Option<FreeFn>,
    free_state: Option<FreeFn>,
}

/// The functions of a loaded plugin (checked at load).
struct Table {
    setup: SetupFn,
    tile: TileFn,
    eval: Option<EvalFn>,
    eval_box: Option<EvalBoxFn>,
    constraint_name: Option<NameFn>,
    free_tile: Option<FreeFn>,
    free_state: Option<FreeFn>,
}

/// A culling method loaded from a shared library.
pub struct PluginMethod {
    info: &'static MethodInfo,
    table: Table,
    /// The "disabled" reasons the plugin returned, copied once per distinct pointer.
    reasons: Mutex<HashMap<usize, &'static str>>,
    /// Keeps the library mapped while the method exists.
    _lib: libloading::Library,
}

// The plugin promises (header: "Threads") that setup and tile may run concurrently.
unsafe impl Send for PluginMethod {}
unsafe impl Sync for PluginMethod {}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

/// A method id a user can type and a file can hold: letters, digits, `-`, `_`, `.`.
pub fn valid_id(id: &str) -> bool {
    !id.is_empty() && id.len() <= 64 && id.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))
}

/// Load the plugin at `path` (an error names the file and what is wrong with it).
pub fn load(path: &Path) -> Result<&'static dyn Method> {
    let at = path.display();
    // SAFETY: loading a library runs its initialisers; the user asked for this file.
    let lib = unsafe { libloading::Library::new(path) }.with_context(|| format!("--plugin {at}: cannot load"))?;
    let table: *const CpMethod = unsafe {
        let f: libloading::Symbol<unsafe extern "C" fn() -> *const CpMethod> = lib
            .get(b"cullproof_method\0")
            .with_context(|| format!("--plugin {at}: no `cullproof_method` symbol (see include/cullproof.h)"))?;
        f()
    };
    if table.is_null() {
        bail!("--plugin {at}: `cullproof_method()` returned NULL");
    }
    // SAFETY: the header says the table lives as long as the library, which we keep.
    let t = unsafe { &*table };
    if t.abi_version != ABI_VERSION {
        bail!(
            "--plugin {at}: built for cullproof.h ABI version {}, this cullproof speaks version {ABI_VERSION}",
            t.abi_version
        );
    }
    let text = |p: *const c_char, field: &str| -> Result<String> {
        if p.is_null() {
            bail!("--plugin {at}: field `{field}` is NULL");
        }
        // SAFETY: a NUL-terminated string (header); checked for UTF-8 below.
        let s = unsafe { CStr::from_ptr(p) };
        Ok(s.to_str().with_context(|| format!("--plugin {at}: field `{field}` is not UTF-8"))?.to_string())
    };
    let id = text(t.id, "id")?;
    if !valid_id(&id) {
        bail!("--plugin {at}: field `id` = {id:?}: use 1 to 64 letters, digits, '-', '_' or '.'");
    }
    let source = text(t.source, "source")?;
    if t.outputs & !31 != 0 {
        bail!("--plugin {at}: field `outputs` = {:#x} has bits no CP_OUT_* flag defines", t.outputs);
    }
    let (Some(setup), Some(tile)) = (t.setup, t.tile) else {
        bail!("--plugin {at}: fields `setup` and `tile` are required");
    };
    if t.outputs & CP_OUT_PER_SAMPLE != 0 && t.eval.is_none() {
        bail!("--plugin {at}: `outputs` has CP_OUT_PER_SAMPLE but field `eval` is NULL");
    }
    let o = t.outputs;
    let info = Box::leak(Box::new(MethodInfo {
        id: leak(id),
        source: leak(format!("plugin {at}: {source}")),
        reconstruction: false,
        dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
        outputs: Outputs {
            tile_reject: o & CP_OUT_TILE_REJECT != 0,
            lens: o & CP_OUT_LENS != 0,
            time: o & CP_OUT_TIME != 0,
            depth: o & CP_OUT_DEPTH != 0,
            per_sample: o & CP_OUT_PER_SAMPLE != 0,
        },
    }));
    let m = PluginMethod {
        info,
        table: Table {
            setup,
            tile,
            eval: t.eval,
            eval_box: t.eval_box,
            constraint_name: t.constraint_name,
            free_tile: t.free_tile,
            free_state: t.free_state,
        },
        reasons: Mutex::new(HashMap::new()),
        _lib: lib,
    };
    Ok(Box::leak(Box::new(m)))
}

/// Load a plugin and make it known to every command by its id.
pub fn load_and_plug(path: &Path) -> Result<&'static dyn Method> {
    let m = load(path)?;
    crate::bounds::plug(m).map_err(|e| anyhow::anyhow!("--plugin {}: {e}", path.display()))?;
    Ok(m)
}

fn tri_c(t: &Triangle) -> CpTriangle {
    CpTriangle { q: t.q, r: t.r, c0: t.c0, c1: t.c1, k: t.k }
}

/// The per-triangle state of a plugin.
struct PluginPrep {
    m: &'static PluginMethod,
    state: *mut c_void,
    disabled: Option<&'static str>,
}

unsafe impl Send for PluginPrep {}
unsafe impl Sync for PluginPrep {}

impl Drop for PluginPrep {
    fn drop(&mut self) {
        if let Some(f) = self.m.table.free_state {
            // SAFETY: once per setup, as the header says.
            unsafe { f(self.state) }
        }
    }
}

/// A tile state shared by that tile's constraints, freed with the last of them.
struct TileState {
    m: &'static PluginMethod,
    ptr: *mut c_void,
}

unsafe impl Send for TileState {}
unsafe impl Sync for TileState {}

impl Drop for TileState {
    fn drop(&mut self) {
        if let (Some(f), false) = (self.m.table.free_tile, self.ptr.is_null()) {
            // SAFETY: once per non-NULL tile state.
            unsafe { f(self.ptr) }
        }
    }
}

/// Constraint `index` of a tile.
struct PluginConstraint {
    ts: Arc<TileState>,
    index: u32,
}

impl std::fmt::Debug for PluginConstraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} constraint {}", self.ts.m.info.id, self.index)
    }
}

fn iv(i: Interval) -> CpInterval {
    CpInterval { lo: i.lo, hi: i.hi }
}

impl SampleConstraint for PluginConstraint {
    fn name(&self) -> String {
        let t = &self.ts.m.table;
        if let Some(f) = t.constraint_name {
            // SAFETY: the string lives as long as the tile state (header).
            let p = unsafe { f(self.ts.ptr, self.index) };
            if !p.is_null() {
                return unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned();
            }
        }
        format!("constraint {}", self.index)
    }
    fn eval(&self, s: &Sample) -> f32 {
        let c = CpSample { x: s.x, y: s.y, u: s.u, v: s.v, t: s.t };
        match self.ts.m.table.eval {
            // SAFETY: the tile state is alive (we hold it) and read-only.
            Some(f) => unsafe { f(self.ts.ptr, self.index, &c) },
            None => f32::NAN,
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let whole = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        let Some(f) = self.ts.m.table.eval_box else { return whole };
        let c = CpSampleBox { x: iv(b.x), y: iv(b.y), u: iv(b.u), v: iv(b.v), t: iv(b.t) };
        let mut out = CpInterval { lo: f64::NEG_INFINITY, hi: f64::INFINITY };
        // SAFETY: as for eval.
        let ok = unsafe { f(self.ts.ptr, self.index, &c, &mut out) };
        // An answer that is not an interval encloses nothing we can trust.
        if ok == 0 || out.lo.is_nan() || out.hi.is_nan() || out.lo > out.hi {
            return whole;
        }
        Interval::new(out.lo, out.hi)
    }
}

impl Prepared for PluginPrep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let full = TileBounds::full();
        let mut out = CpBounds {
            u: full.u,
            v: full.v,
            t: full.t,
            has_z: 0,
            z: [f32::NEG_INFINITY, f32::INFINITY],
            n_constraints: 0,
            tile_state: std::ptr::null_mut(),
        };
        let c = CpTile { x0: tile.x0, y0: tile.y0, x1: tile.x1, y1: tile.y1 };
        // SAFETY: the state came from this method's setup and is read-only.
        let r = unsafe { (self.m.table.tile)(self.state, &c, &mut out) };
        let ts = Arc::new(TileState { m: self.m, ptr: out.tile_state });
        if r != CP_BOUNDS {
            return TileResult::Empty;
        }
        let n = if self.m.table.eval.is_some() { out.n_constraints } else { 0 };
        let constraints: Vec<Box<dyn SampleConstraint>> = (0..n)
            .map(|index| Box::new(PluginConstraint { ts: ts.clone(), index }) as Box<dyn SampleConstraint>)
            .collect();
        TileResult::Bounds(TileBounds {
            u: out.u,
            v: out.v,
            t: out.t,
            z: (out.has_z != 0).then_some(out.z),
            constraints,
        })
    }
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

impl Method for PluginMethod {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        // SAFETY: every method handed out by `load` is leaked, so `self` is 'static.
        let me: &'static PluginMethod = unsafe { &*(self as *const PluginMethod) };
        let t = tri_c(tri);
        let mut why: *const c_char = std::ptr::null();
        // SAFETY: a plain call into the plugin with valid pointers.
        let state = unsafe { (self.table.setup)(&t, &mut why) };
        let disabled = (!why.is_null()).then(|| {
            let mut map = self.reasons.lock().unwrap_or_else(|e| e.into_inner());
            *map.entry(why as usize).or_insert_with(|| {
                // SAFETY: a static NUL-terminated string (header).
                leak(unsafe { CStr::from_ptr(why) }.to_string_lossy().into_owned())
            })
        });
        Box::new(PluginPrep { m: me, state, disabled })
    }
}
