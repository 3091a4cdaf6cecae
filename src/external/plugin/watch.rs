//! The per-call watchdog (see the module doc of [`super`]): how long a call into a plugin
//! may take ([`set_timeout`]), and the thread that ends the process when one takes longer.

use super::abi::Call;
use std::cell::{Cell, RefCell};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Arc, Mutex, Once};
use std::time::{Duration, Instant};

/// How long one call into a plugin may take by default (`--plugin-timeout`): the same
/// as `--exec-timeout`.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(30);

/// Set how long one call into a plugin may take before the watchdog ends the process
/// (`--plugin-timeout`; [`DEFAULT_TIMEOUT`] until set). Applies to every plugin, loaded
/// before or after.
pub fn set_timeout(d: Duration) {
    TIMEOUT_NS.store(d.as_nanos().clamp(1, u64::MAX as u128) as u64, Relaxed);
}

pub(super) static TIMEOUT_NS: AtomicU64 = AtomicU64::new(DEFAULT_TIMEOUT.as_nanos() as u64);

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
