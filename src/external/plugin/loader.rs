//! Loading a plugin: opening the library, checking its table, and making the method
//! known to every command ([`load_and_plug`]).

use super::abi::{
    bounded_text, Call, CpMethod, Table, ABI_VERSION, CP_OUT_DEPTH, CP_OUT_LENS, CP_OUT_PER_SAMPLE, CP_OUT_TILE_REJECT,
    CP_OUT_TIME, MAX_TEXT,
};
use super::breach::{Breach, Counters, LOADED};
use super::fpenv;
use super::method::PluginMethod;
use super::watch;
use crate::bounds::{Method, MethodInfo, Outputs};
use crate::model::Dims;
use anyhow::{bail, Context, Result};
use std::collections::HashMap;
use std::ffi::c_char;
use std::path::Path;
use std::sync::Mutex;

pub(super) fn leak(s: String) -> &'static str {
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
