//! The [`Method`] adaptor: a loaded plugin as a culling method, its per-triangle state
//! and tile constraints calling the C functions, and the answers judged against the
//! contract (a stop on a cap is a [`PluginFailure`]).

use super::abi::{
    bounded_text, Call, CpBounds, CpInterval, CpSample, CpSampleBox, CpTile, CpTriangle, FreeFn, Table, CP_BOUNDS,
    CP_EMPTY, MAX_CONSTRAINTS, MAX_REASONS, MAX_TEXT,
};
use super::breach::{Breach, Counters};
use super::fpenv;
use super::loader::leak;
use super::watch;
use crate::bounds::{Method, MethodInfo, Prepared, SampleBox, SampleConstraint, TileBounds, TileResult};
use crate::model::{Sample, Tile, Triangle};
use crate::Interval;
use std::collections::HashMap;
use std::ffi::{c_char, c_void};
use std::sync::atomic::Ordering::Relaxed;
use std::sync::{Arc, Mutex};

/// Why a run stopped on a plugin (the payload of the panic that stops it: the tile
/// test has no error channel, and no answer may be made up): a value beyond a cap,
/// with the plugin, the call and the value named. The command line reports it as an
/// error (exit code 2); a library caller can catch it with `std::panic::catch_unwind`
/// and downcast the payload to this type. (A call that hangs cannot be unwound: the
/// watchdog ends the process instead.)
#[derive(Clone, Debug)]
pub struct PluginFailure(pub String);

impl std::fmt::Display for PluginFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// A culling method loaded from a shared library.
pub struct PluginMethod {
    pub(super) info: &'static MethodInfo,
    pub(super) table: Table,
    /// The library as given, for messages.
    pub(super) path: String,
    /// The plugin's index for the watchdog.
    pub(super) index: u16,
    pub(super) breaches: Counters,
    /// The "disabled" reasons the plugin returned, copied once per distinct pointer.
    pub(super) reasons: Mutex<HashMap<usize, &'static str>>,
    /// Keeps the library mapped while the method exists.
    pub(super) _lib: libloading::Library,
}

// The plugin promises (header: "Threads") that setup and tile may run concurrently.
unsafe impl Send for PluginMethod {}
unsafe impl Sync for PluginMethod {}

impl PluginMethod {
    /// Run a call into the plugin under the watchdog, in the standard floating-point
    /// environment ([`fpenv`]): one left otherwise (before the call, by the library's
    /// loading; after it, by the call) is reset and counted as a breach.
    #[inline]
    fn call<R>(&self, c: Call, f: impl FnOnce() -> R) -> R {
        let before = fpenv::reset();
        let r = watch::run(self.index, c, f);
        if before | fpenv::reset() {
            self.breach(1 << Breach::FpEnv as u32);
        }
        r
    }

    /// Stop the run: `call` answered `what` (see [`PluginFailure`]).
    fn fail(&self, call: Call, what: &str) -> ! {
        std::panic::panic_any(PluginFailure(format!(
            "plugin {} (`{}`): {} {what}; no answer was taken",
            self.path,
            self.info.id,
            call.name()
        )))
    }

    /// Count one answer showing the breaches in `mask` (bits by [`Breach`]).
    #[cold]
    pub(super) fn breach(&self, mask: u32) {
        self.breaches.answers.fetch_add(1, Relaxed);
        for b in Breach::ALL {
            if mask & (1 << b as u32) != 0 {
                self.breaches.kinds[b as usize].fetch_add(1, Relaxed);
            }
        }
    }

    /// A string the plugin returned from `call`, read up to the cap.
    fn text(&self, call: Call, p: *const c_char, what: &str) -> String {
        // SAFETY: a NUL-terminated string (header), read no further than the cap.
        match unsafe { bounded_text(p) } {
            Ok(s) => String::from_utf8_lossy(&s).into_owned(),
            Err(()) => self.fail(call, &format!("returned {what} with no NUL within {MAX_TEXT} bytes, the cap")),
        }
    }
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
            self.m.call(Call::FreeState, || unsafe { f(self.state) })
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
            self.free(f)
        }
    }
}

impl TileState {
    /// Out of line, so that dropping a tile with nothing to free stays a few instructions.
    #[inline(never)]
    fn free(&self, f: FreeFn) {
        // SAFETY: once per non-NULL tile state.
        self.m.call(Call::FreeTile, || unsafe { f(self.ptr) })
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
        let m = self.ts.m;
        if let Some(f) = m.table.constraint_name {
            // SAFETY: the string lives as long as the tile state (header).
            let p = m.call(Call::ConstraintName, || unsafe { f(self.ts.ptr, self.index) });
            if !p.is_null() {
                return m.text(Call::ConstraintName, p, "a name");
            }
        }
        format!("constraint {}", self.index)
    }
    fn eval(&self, s: &Sample) -> f32 {
        let c = CpSample { x: s.x, y: s.y, u: s.u, v: s.v, t: s.t };
        match self.ts.m.table.eval {
            // SAFETY: the tile state is alive (we hold it) and read-only.
            Some(f) => self.ts.m.call(Call::Eval, || unsafe { f(self.ts.ptr, self.index, &c) }),
            None => f32::NAN,
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let whole = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        let Some(f) = self.ts.m.table.eval_box else { return whole };
        let c = CpSampleBox { x: iv(b.x), y: iv(b.y), u: iv(b.u), v: iv(b.v), t: iv(b.t) };
        let mut out = CpInterval { lo: f64::NEG_INFINITY, hi: f64::INFINITY };
        // SAFETY: as for eval.
        let ok = self.ts.m.call(Call::EvalBox, || unsafe { f(self.ts.ptr, self.index, &c, &mut out) });
        if ok == 0 {
            return whole;
        }
        // An answer that is not an interval encloses nothing we can trust.
        if out.lo.is_nan() || out.hi.is_nan() {
            self.ts.m.breach(1 << Breach::EvalBoxNan as u32);
            return whole;
        }
        if out.lo > out.hi {
            self.ts.m.breach(1 << Breach::EvalBoxInverted as u32);
            return whole;
        }
        Interval::new(out.lo, out.hi)
    }
}

/// Whether a `CP_BOUNDS` answer keeps the contract: u^, v^, t^ finite intervals, z^
/// (when given) an interval, infinite ends allowed; constraints only with `eval` (the
/// fast test of every answer; [`bounds_breaches`] says what is wrong).
#[inline]
fn bounds_keep_contract(out: &CpBounds, has_eval: bool) -> bool {
    // lo <= hi is false with a NaN end; with -inf < lo and hi < inf both ends are finite.
    let finite = |i: [f32; 2]| i[0] <= i[1] && i[0] > f32::NEG_INFINITY && i[1] < f32::INFINITY;
    finite(out.u)
        && finite(out.v)
        && finite(out.t)
        && (out.has_z == 0 || out.z[0] <= out.z[1])
        && (out.n_constraints == 0 || has_eval)
}

/// The breaches of a `CP_BOUNDS` answer (bits by [`Breach`]; see
/// [`bounds_keep_contract`]).
#[cold]
fn bounds_breaches(out: &CpBounds, has_eval: bool) -> u32 {
    let mut mask = 0;
    let mut end = |lo: f32, hi: f32, finite: bool| {
        if lo.is_nan() || hi.is_nan() {
            mask |= 1 << Breach::TileNan as u32;
        } else if lo > hi {
            mask |= 1 << Breach::TileInverted as u32;
        }
        if finite && (lo.is_infinite() || hi.is_infinite()) {
            mask |= 1 << Breach::TileInfinite as u32;
        }
    };
    for i in [out.u, out.v, out.t] {
        end(i[0], i[1], true);
    }
    if out.has_z != 0 {
        end(out.z[0], out.z[1], false);
    }
    if out.n_constraints > 0 && !has_eval {
        mask |= 1 << Breach::TileNoEval as u32;
    }
    mask
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
        let r = self.m.call(Call::Tile, || unsafe { (self.m.table.tile)(self.state, &c, &mut out) });
        let ts = Arc::new(TileState { m: self.m, ptr: out.tile_state });
        if r != CP_BOUNDS {
            if r != CP_EMPTY {
                self.m.breach(1 << Breach::TileCode as u32);
            }
            return TileResult::Empty;
        }
        // Checked before a handle is made (`ts` is freed on the way out).
        if out.n_constraints > MAX_CONSTRAINTS {
            self.m.fail(
                Call::Tile,
                &format!(
                    "answered n_constraints = {}, more than the cap {MAX_CONSTRAINTS} (CP_MAX_CONSTRAINTS)",
                    out.n_constraints
                ),
            );
        }
        let has_eval = self.m.table.eval.is_some();
        if !bounds_keep_contract(&out, has_eval) {
            self.m.breach(bounds_breaches(&out, has_eval));
        }
        let n = if has_eval { out.n_constraints } else { 0 };
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
        let state = self.call(Call::Setup, || unsafe { (self.table.setup)(&t, &mut why) });
        // Held from here, so that a stop below still frees the state.
        let mut prep = PluginPrep { m: me, state, disabled: None };
        if !why.is_null() {
            let mut map = self.reasons.lock().unwrap_or_else(|e| e.into_inner());
            let known = map.get(&(why as usize)).copied();
            prep.disabled = Some(match known {
                Some(r) => r,
                None => {
                    if map.len() >= MAX_REASONS {
                        drop(map);
                        self.fail(
                            Call::Setup,
                            &format!(
                                "returned `disabled` strings at more than {MAX_REASONS} addresses, the cap \
                                 (CP_MAX_REASONS; they must be static)"
                            ),
                        );
                    }
                    let r = leak(self.text(Call::Setup, why, "a `disabled` string"));
                    map.insert(why as usize, r);
                    r
                }
            });
        }
        Box::new(prep)
    }
}
