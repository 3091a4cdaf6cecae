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
//!
//! [`Method`]: crate::bounds::Method

mod abi;
mod breach;
pub(crate) mod fpenv;
mod loader;
mod method;
mod watch;

pub use abi::{ABI_VERSION, MAX_CONSTRAINTS, MAX_REASONS, MAX_TEXT};
pub use breach::{breaches, breaches_since, ContractBreaches};
pub use loader::{load, load_and_plug, valid_id};
pub use method::{PluginFailure, PluginMethod};
pub use watch::{set_timeout, DEFAULT_TIMEOUT};
