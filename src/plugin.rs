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
//! A plugin is held to limits, so that a broken one stops the run with a message instead
//! of taking the process down or hanging it (each stop is a [`PluginFailure`], exit
//! code 2 on the command line, naming the plugin, the call and the value):
//! - caps, checked before anything is allocated: at most [`MAX_CONSTRAINTS`] constraints
//!   per tile answer (`CP_MAX_CONSTRAINTS`), strings (`source`, `disabled` reasons,
//!   constraint names) of at most [`MAX_TEXT`] bytes (`CP_MAX_TEXT`), at most
//!   [`MAX_REASONS`] distinct `disabled` strings (they must be static);
//! - a watchdog: a call that has not returned after the timeout ([`set_timeout`],
//!   `--plugin-timeout`, default [`DEFAULT_TIMEOUT`]) ends the process with exit code 2
//!   and a message naming the plugin and the call (a call into C cannot be interrupted).
//!   Each call costs two relaxed stores into a per-thread slot; a watchdog thread looks
//!   at the slots every tenth of the timeout (at most every 100 ms) and fires on a call
//!   it has seen running for the whole timeout, so it never changes an answer;
//! - contract breaches (an interval end that is NaN, an infinite end of u^, v^ or t^,
//!   lo > hi, a tile answer neither `CP_EMPTY` nor `CP_BOUNDS`, constraints without
//!   `eval`, an `eval_box` enclosure that is not an interval) are judged exactly as
//!   above and counted per plugin ([`breaches`]); the command line prints one line per
//!   plugin that broke the contract at the end of the run, and `check --json` lists them
//!   (`contract_breaches`).
//!
//! The library stays loaded for the life of the process (the method is `'static`).
//! A plugin runs in cullproof's process: a crash in it ends the run. For bounds that
//! may crash, or that are not in C, use the process protocol instead.

use crate::bounds::{Method, MethodInfo, Outputs, Prepared, SampleBox, SampleConstraint, TileBounds, TileResult};
use crate::model::{Dims, Sample, Tile, Triangle};
use crate::Interval;
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};
use std::ffi::{c_char, c_void};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Arc, Mutex};
use std::time::Duration;

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

/// How long one call into a plugin may take by default (`--plugin-timeout`): the same
/// as `--exec-timeout`.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(30);

const CP_OUT_TILE_REJECT: u32 = 1;
const CP_OUT_LENS: u32 = 2;
const CP_OUT_TIME: u32 = 4;
const CP_OUT_DEPTH: u32 = 8;
const CP_OUT_PER_SAMPLE: u32 = 16;
const CP_EMPTY: i32 = 0;
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

/// A call into a plugin, as messages name it (the watchdog keeps it as a small number).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
enum Call {
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
    const ALL: [Call; 8] = [
        Call::Entry,
        Call::Setup,
        Call::Tile,
        Call::Eval,
        Call::EvalBox,
        Call::ConstraintName,
        Call::FreeTile,
        Call::FreeState,
    ];
    fn name(self) -> &'static str {
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

/// Set how long one call into a plugin may take before the watchdog ends the process
/// (`--plugin-timeout`; [`DEFAULT_TIMEOUT`] until set). Applies to every plugin, loaded
/// before or after.
pub fn set_timeout(d: Duration) {
    watch::TIMEOUT_NS.store(d.as_nanos().clamp(1, u64::MAX as u128) as u64, Relaxed);
}

/// The per-call watchdog (see the module doc).
mod watch {
    use super::Call;
    use std::cell::{Cell, RefCell};
    use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
    use std::sync::{Arc, Mutex, Once};
    use std::time::{Duration, Instant};

    pub(super) static TIMEOUT_NS: AtomicU64 = AtomicU64::new(super::DEFAULT_TIMEOUT.as_nanos() as u64);

    /// The names messages give the plugins, by index ("plugin PATH (`id`)").
    pub(super) static NAMES: Mutex<Vec<String>> = Mutex::new(Vec::new());

    /// A thread's plugin call: `seq << 24 | plugin << 8 | call`, call 0 when idle; `seq`
    /// counts the thread's calls, so two calls in a row are never taken for one.
    struct Slot(AtomicU64);

    /// A slot as the watchdog last saw it, and since when.
    struct Seen {
        slot: Arc<Slot>,
        state: u64,
        since: Instant,
    }

    static SLOTS: Mutex<Vec<Seen>> = Mutex::new(Vec::new());
    static START: Once = Once::new();

    /// Holds a thread's slot while the thread lives; its drop (at thread exit) clears
    /// [`SLOT`] first, and the watchdog then forgets the slot.
    struct Owner(Option<Arc<Slot>>);

    impl Drop for Owner {
        fn drop(&mut self) {
            SLOT.with(|s| s.set(std::ptr::null()));
        }
    }

    thread_local! {
        /// The thread's slot, null before its first watched call (and after its
        /// [`OWNER`] is gone): a plain load on every call.
        static SLOT: Cell<*const Slot> = const { Cell::new(std::ptr::null()) };
        static OWNER: RefCell<Owner> = const { RefCell::new(Owner(None)) };
    }

    /// Give this thread a slot (null when the thread is being torn down: then its
    /// calls are not watched, e.g. a plugin state freed by a thread-local destructor).
    #[cold]
    fn register_thread() -> *const Slot {
        let slot = Arc::new(Slot(AtomicU64::new(0)));
        if OWNER.try_with(|o| o.borrow_mut().0 = Some(slot.clone())).is_err() {
            return std::ptr::null();
        }
        let p = Arc::as_ptr(&slot);
        SLOTS.lock().unwrap_or_else(|e| e.into_inner()).push(Seen { slot, state: 0, since: Instant::now() });
        SLOT.with(|s| s.set(p));
        p
    }

    /// A new plugin's index for [`run`] (starts the watchdog with the first).
    pub(super) fn register(name: String) -> Option<u16> {
        START.call_once(|| {
            std::thread::Builder::new()
                .name("cullproof-plugin-watchdog".into())
                .spawn(watchdog)
                .expect("starting the plugin watchdog thread");
        });
        let mut names = NAMES.lock().unwrap_or_else(|e| e.into_inner());
        let i = u16::try_from(names.len()).ok()?;
        names.push(name);
        Some(i)
    }

    /// Run `f`, a call into plugin `plugin`, under the watchdog's eye.
    #[inline]
    pub(super) fn run<R>(plugin: u16, call: Call, f: impl FnOnce() -> R) -> R {
        let mut p = SLOT.with(|s| s.get());
        if p.is_null() {
            p = register_thread();
            if p.is_null() {
                return f();
            }
        }
        // SAFETY: a non-null SLOT points into the Arc that OWNER holds until it clears
        // SLOT, at this thread's exit.
        let slot = unsafe { &*p };
        let seq = (slot.0.load(Relaxed) >> 24).wrapping_add(1) & ((1 << 40) - 1);
        slot.0.store(seq << 24 | (plugin as u64) << 8 | call as u64, Relaxed);
        let r = f();
        slot.0.store(seq << 24, Relaxed);
        r
    }

    fn watchdog() {
        loop {
            let timeout = Duration::from_nanos(TIMEOUT_NS.load(Relaxed));
            std::thread::sleep((timeout / 10).clamp(Duration::from_millis(1), Duration::from_millis(100)));
            let now = Instant::now();
            let mut slots = SLOTS.lock().unwrap_or_else(|e| e.into_inner());
            // A slot only the watchdog holds belongs to a thread that has ended.
            slots.retain(|s| Arc::strong_count(&s.slot) > 1);
            for s in slots.iter_mut() {
                let state = s.slot.0.load(Relaxed);
                if state != s.state {
                    s.state = state;
                    s.since = now;
                } else if state & 0xff != 0 && now.duration_since(s.since) >= timeout {
                    // The call began before `since`: it has run for the whole timeout.
                    fire(state, timeout);
                }
            }
        }
    }

    fn fire(state: u64, timeout: Duration) -> ! {
        let call = Call::ALL.into_iter().find(|c| *c as u64 == state & 0xff).map_or("a call", |c| c.name());
        let i = ((state >> 8) & 0xffff) as usize;
        let name = NAMES.lock().unwrap_or_else(|e| e.into_inner()).get(i).cloned().unwrap_or_default();
        eprintln!(
            "error: {name}: {call} did not return within {} s (--plugin-timeout); the run stops \
             (a call into a plugin cannot be interrupted)",
            timeout.as_secs_f64()
        );
        std::process::exit(2)
    }
}

/// The floating-point environment every claim of this crate assumes (IEEE 754 binary32
/// and binary64, round to nearest even, gradual underflow: no flush-to-zero, no
/// denormals-are-zero), checked around every call into a plugin. On x86-64 that is
/// the MXCSR register of the calling thread; elsewhere nothing is checked.
pub(crate) mod fpenv {
    /// MXCSR: flush-to-zero (bit 15), denormals-are-zero (bit 6), rounding control
    /// (bits 13-14, 0 = to nearest).
    #[cfg(target_arch = "x86_64")]
    const NONSTANDARD: u32 = 1 << 15 | 1 << 6 | 3 << 13;

    /// Reset this thread's environment to the standard one; true when it was not.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    pub fn reset() -> bool {
        #[allow(deprecated)]
        // SAFETY: SSE is part of x86-64; reading MXCSR and clearing these bits (which
        // only restores the default rounding and underflow) cannot fault.
        unsafe {
            let c = std::arch::x86_64::_mm_getcsr();
            if c & NONSTANDARD != 0 {
                std::arch::x86_64::_mm_setcsr(c & !NONSTANDARD);
                return true;
            }
        }
        false
    }

    #[cfg(not(target_arch = "x86_64"))]
    #[inline]
    pub fn reset() -> bool {
        false
    }
}

/// Kinds of contract breach, counted per plugin (the names are the keys of
/// [`ContractBreaches::kinds`]).
#[derive(Clone, Copy)]
enum Breach {
    TileCode,
    TileNan,
    TileInfinite,
    TileInverted,
    TileNoEval,
    EvalBoxNan,
    EvalBoxInverted,
    FpEnv,
}

const BREACHES: usize = 8;

impl Breach {
    const ALL: [Breach; BREACHES] = [
        Breach::TileCode,
        Breach::TileNan,
        Breach::TileInfinite,
        Breach::TileInverted,
        Breach::TileNoEval,
        Breach::EvalBoxNan,
        Breach::EvalBoxInverted,
        Breach::FpEnv,
    ];
    fn key(self) -> &'static str {
        match self {
            Breach::TileCode => "tile-answer-code",
            Breach::TileNan => "tile-nan-end",
            Breach::TileInfinite => "tile-infinite-end",
            Breach::TileInverted => "tile-lo-above-hi",
            Breach::TileNoEval => "tile-constraints-without-eval",
            Breach::EvalBoxNan => "eval-box-nan-end",
            Breach::EvalBoxInverted => "eval-box-lo-above-hi",
            Breach::FpEnv => "fp-environment",
        }
    }
    fn words(self) -> &'static str {
        match self {
            Breach::TileCode => "tile() answers neither CP_EMPTY nor CP_BOUNDS (taken as CP_EMPTY)",
            Breach::TileNan => "tile() answers with a NaN interval end (culls every sample)",
            Breach::TileInfinite => "tile() answers with an infinite end of u, v or t (taken as given)",
            Breach::TileInverted => "tile() answers with lo > hi (culls every sample)",
            Breach::TileNoEval => "tile() answers with constraints but `eval` is NULL (ignored)",
            Breach::EvalBoxNan => "eval_box() enclosures with a NaN end (taken as the whole line)",
            Breach::EvalBoxInverted => "eval_box() enclosures with lo > hi (taken as the whole line)",
            Breach::FpEnv => {
                "the floating-point environment was left with flush-to-zero, denormals-are-zero or a rounding \
                 mode other than to nearest (by loading the library or by a call; reset to the standard one)"
            }
        }
    }
}

/// A plugin's contract breaches: answers that break include/cullproof.h, each judged
/// as the module doc says (the verdicts are those of the answer as given).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContractBreaches {
    /// The method id.
    pub method: String,
    /// The library, as given to `--plugin`.
    pub plugin: String,
    /// Answers that broke the contract.
    pub answers: u64,
    /// Of those, per kind of breach (an answer may show several).
    pub kinds: BTreeMap<String, u64>,
}

impl ContractBreaches {
    /// The line the command line prints at the end of a run.
    pub fn line(&self) -> String {
        let kinds: Vec<String> =
            Breach::ALL.iter().filter_map(|b| self.kinds.get(b.key()).map(|n| format!("{n} {}", b.words()))).collect();
        format!(
            "plugin {} (`{}`): {} answers broke the contract of include/cullproof.h: {}; each was judged by \
             that reading, as the header says",
            self.plugin,
            self.method,
            self.answers,
            kinds.join(", ")
        )
    }
}

/// Breach counters of one plugin.
#[derive(Default)]
struct Counters {
    answers: AtomicU64,
    kinds: [AtomicU64; BREACHES],
}

/// Every plugin loaded so far, in load order.
static LOADED: Mutex<Vec<&'static PluginMethod>> = Mutex::new(Vec::new());

/// The contract breaches of every plugin loaded in this process so far (zero counts
/// included), in load order.
pub fn breaches() -> Vec<ContractBreaches> {
    let loaded = LOADED.lock().unwrap_or_else(|e| e.into_inner()).clone();
    loaded
        .iter()
        .map(|m| ContractBreaches {
            method: m.info.id.to_string(),
            plugin: m.path.clone(),
            answers: m.breaches.answers.load(Relaxed),
            kinds: Breach::ALL
                .iter()
                .map(|b| (b.key().to_string(), m.breaches.kinds[*b as usize].load(Relaxed)))
                .filter(|(_, n)| *n > 0)
                .collect(),
        })
        .collect()
}

/// The breaches since `before` (an earlier [`breaches`]), plugins with none left out:
/// what one run added.
pub fn breaches_since(before: &[ContractBreaches]) -> Vec<ContractBreaches> {
    breaches()
        .into_iter()
        .filter_map(|mut now| {
            if let Some(b) = before.iter().find(|b| b.method == now.method) {
                now.answers -= b.answers;
                for (k, n) in now.kinds.iter_mut() {
                    *n -= b.kinds.get(k).copied().unwrap_or(0);
                }
                now.kinds.retain(|_, n| *n > 0);
            }
            (now.answers > 0).then_some(now)
        })
        .collect()
}

/// A culling method loaded from a shared library.
pub struct PluginMethod {
    info: &'static MethodInfo,
    table: Table,
    /// The library as given, for messages.
    path: String,
    /// The plugin's index for the watchdog.
    index: u16,
    breaches: Counters,
    /// The "disabled" reasons the plugin returned, copied once per distinct pointer.
    reasons: Mutex<HashMap<usize, &'static str>>,
    /// Keeps the library mapped while the method exists.
    _lib: libloading::Library,
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
    fn breach(&self, mask: u32) {
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

/// The bytes of the string at `p` (not NULL) if its NUL lies within [`MAX_TEXT`]
/// bytes; bytes past the NUL or past the cap are never read.
///
/// # Safety
/// `p` points at readable bytes up to its NUL or the cap, whichever comes first.
unsafe fn bounded_text(p: *const c_char) -> std::result::Result<Vec<u8>, ()> {
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
    // A library built with fast-math options may set flush-to-zero at load: reset it
    // here, before any other thread inherits it (the exact oracles need gradual
    // underflow), and count it below.
    let env_at_load = fpenv::reset();
    let entry = unsafe {
        let f: libloading::Symbol<unsafe extern "C" fn() -> *const CpMethod> = lib
            .get(b"cullproof_method\0")
            .with_context(|| format!("--plugin {at}: no `cullproof_method` symbol (see include/cullproof.h)"))?;
        *f
    };
    let Some(index) = watch::register(format!("plugin {at}")) else {
        bail!("--plugin {at}: at most {} plugins in one process", u16::MAX);
    };
    // SAFETY: the entry point takes nothing and returns the table (header).
    let table: *const CpMethod = watch::run(index, Call::Entry, || unsafe { entry() });
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
        // SAFETY: a NUL-terminated string (header), read no further than the cap.
        let s = unsafe { bounded_text(p) }.map_err(|()| {
            anyhow::anyhow!("--plugin {at}: field `{field}` has no NUL within {MAX_TEXT} bytes, the cap")
        })?;
        String::from_utf8(s).with_context(|| format!("--plugin {at}: field `{field}` is not UTF-8"))
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
        id: leak(id.clone()),
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
    if let Some(n) = watch::NAMES.lock().unwrap_or_else(|e| e.into_inner()).get_mut(index as usize) {
        *n = format!("plugin {at} (`{id}`)");
    }
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
        path: at.to_string(),
        index,
        breaches: Counters::default(),
        reasons: Mutex::new(HashMap::new()),
        _lib: lib,
    };
    let env_at_load = env_at_load | fpenv::reset();
    let m: &'static PluginMethod = Box::leak(Box::new(m));
    if env_at_load {
        m.breach(1 << Breach::FpEnv as u32);
    }
    LOADED.lock().unwrap_or_else(|e| e.into_inner()).push(m);
    Ok(m)
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
