//! The corpus: case files anyone can replay, the randomized counterexample search and
//! its shrinker.
//!
//! A case file (`corpus/cases/<method>/<short-hash>.json`) holds one method, one
//! triangle (with its thin lens when it has one) and one tile as plain numbers, the
//! witness sample with the bound that culls it and the margin needed, the expected
//! verdict and where it came from. [`replay`] re-judges it: the stored witness is
//! re-decided exactly (it must still be interior and still culled), and the method is
//! judged afresh on the case.
//!
//! A case file found under a declared sample set, vertex snapping or viewport
//! (`docs/model.md`, §7) records them (`samples`, `snap`, `viewport`); a file without
//! those fields was found under the defaults (any position, no snap, no viewport).
//! Replay and explain judge a file under what it records.

use crate::bounds::{by_id, Method, MethodRef, TileResult};
use crate::check::expect::{pooled_looser, Entry};
use crate::check::{culled_by, judge, try_make_case, Cap, CheckConfig, Declared, Expectations, Judgement};
use crate::gen::Regime;
use crate::model::{Case, SampleSet, Snap, Tile, Viewport};
use crate::num_or_inf;
use crate::quote::{clip, quote};
use anyhow::{anyhow, bail, Context, Result};
use oracles::{classify, Coverage};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The format tag of a case file.
pub const FORMAT: &str = "cullproof-case/1";

/// The expected verdict of a case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Violation,
    Conservative,
}

/// The sample a method culls although it is covered.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WitnessRecord {
    /// (x, y, u, v, t).
    pub sample: [f64; 5],
    /// The bound that culls it ("tile culled", "u min", a constraint's name).
    pub bound: String,
    /// The padding of that bound that would admit it ("inf" when the tile was culled).
    #[serde(with = "num_or_inf")]
    pub margin: f64,
    /// Embree's verdict on the witness ray when the case is physical.
    #[serde(default)]
    pub embree_hit: Option<bool>,
}

/// Where a case came from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// "check", "search" or "hand".
    pub found_by: String,
    pub seed: u64,
    pub case_index: u64,
    pub regime: String,
    pub tool_version: String,
    /// Shrinking steps that were kept.
    #[serde(default)]
    pub shrink_steps: Vec<String>,
}

/// One case file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub format: String,
    pub method: String,
    pub case: Case,
    pub tile: Tile,
    pub expected: Verdict,
    #[serde(default)]
    pub witness: Option<WitnessRecord>,
    pub provenance: Provenance,
    /// Free text: what the case shows.
    #[serde(default)]
    pub note: String,
    /// The sample set the method promises to keep (absent: any position).
    #[serde(default, skip_serializing_if = "crate::model::samples::is_any")]
    pub samples: SampleSet,
    /// Vertex snapping the case was judged under (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snap: Option<Snap>,
    /// The viewport the case was placed in (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viewport: Option<Viewport>,
}

/// The method a case file names: a registered or plugged id, or a deliberately broken
/// variant of one (`broken/<slip>/<id>`, as `search` and the gate's JUnit witnesses
/// write them).
pub fn method_of(id: &str) -> Option<&'static dyn Method> {
    by_id(id).or_else(|| crate::bounds::broken::parse(id))
}

impl CaseFile {
    /// The case file of a violation found by `found_by` (a command: "check", "search",
    /// "symbolic"): the method's case and tile, the witness, where it came from; the
    /// sample set, snap and viewport of `cfg`. `note` says what the case shows.
    pub fn violation(
        method: &str,
        (case, tile): (Case, Tile),
        w: &crate::check::Witness,
        cfg: &CheckConfig,
        (found_by, case_index, regime): (&str, u64, String),
        shrink_steps: Vec<String>,
        note: String,
    ) -> CaseFile {
        CaseFile {
            format: FORMAT.into(),
            method: method.into(),
            case,
            tile,
            expected: Verdict::Violation,
            witness: Some(WitnessRecord {
                sample: w.sample,
                bound: w.bound.clone(),
                margin: w.margin,
                embree_hit: w.embree_hit,
            }),
            provenance: Provenance {
                found_by: found_by.into(),
                seed: cfg.seed,
                case_index,
                regime,
                tool_version: env!("CARGO_PKG_VERSION").into(),
                shrink_steps,
            },
            note,
            samples: cfg.sample_set,
            snap: cfg.snap,
            viewport: cfg.viewport,
        }
    }

    /// Read and check a case file; errors name the file and the field.
    pub fn load(path: &Path) -> Result<CaseFile> {
        Self::load_for(path, None)
    }

    /// [`CaseFile::load`]; with `method` given the file's own method id need not be a
    /// known one (the case is judged against `method`, a bound of the caller's own).
    pub fn load_for(path: &Path, method: Option<&MethodRef>) -> Result<CaseFile> {
        let text = std::fs::read_to_string(path).map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))?;
        let de = &mut serde_json::Deserializer::from_str(&text);
        let cf: CaseFile = serde_path_to_error::deserialize(de).map_err(|e| {
            let field = e.path().to_string();
            anyhow!(
                "{}: field `{}`: {}",
                path.display(),
                if field == "." { "(top level)".into() } else { clip(&field) },
                clip(&e.inner().to_string())
            )
        })?;
        if cf.format != FORMAT {
            bail!("{}: field `format` = {}: expected {FORMAT:?}", path.display(), quote(&cf.format));
        }
        if method.is_none() && method_of(&cf.method).is_none() {
            bail!(
                "{}: field `method` = {} is not a known method id (see `cullproof methods`; a plugin's id needs `--plugin LIB.so`)",
                path.display(),
                quote(&cf.method)
            );
        }
        cf.case.validate().map_err(|e| anyhow!("{}: in `case`: {e}", path.display()))?;
        cf.tile.validate().map_err(|e| anyhow!("{}: {e}", path.display()))?;
        if let Some(w) = &cf.witness {
            if let Some(k) = w.sample.iter().position(|v| !v.is_finite()) {
                bail!("{}: field `witness.sample[{k}]` = {} is not finite", path.display(), w.sample[k]);
            }
            if !cf.samples.contains(w.sample[0], w.sample[1]) {
                bail!(
                    "{}: field `witness.sample` = ({}, {}, ...): (x, y) is not a point of the sample set `{}`",
                    path.display(),
                    w.sample[0],
                    w.sample[1],
                    cf.samples
                );
            }
        }
        if let Some(v) = cf.viewport {
            if !v.holds_tile(&cf.tile) {
                bail!("{}: field `tile` = {:?} does not lie in the viewport {v}", path.display(), cf.tile);
            }
        }
        Ok(cf)
    }

    /// The run settings `cfg` with this file's sample set, snap and viewport.
    pub fn settings(&self, cfg: &CheckConfig) -> CheckConfig {
        CheckConfig { sample_set: self.samples, snap: self.snap, viewport: self.viewport, ..cfg.clone() }
    }

    /// A short content hash (16 hex digits, FNV-1a over the method, case and tile).
    /// Under a sample set, snap or viewport they are hashed too (a file of the defaults
    /// keeps the hash it always had).
    pub fn short_hash(&self) -> String {
        let mut key = serde_json::to_string(&(&self.method, &self.case, &self.tile)).unwrap_or_default();
        if !self.samples.is_any() || self.snap.is_some() || self.viewport.is_some() {
            key += &serde_json::to_string(&(&self.samples, &self.snap, &self.viewport)).unwrap_or_default();
        }
        let h = key.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ b as u64).wrapping_mul(0x100_0000_01b3));
        format!("{h:016x}")
    }

    /// Write under `dir/<method>/<hash>.json`. Never overwrites: an existing file is
    /// left as it is and reported as `Ok(None)`.
    pub fn write_new(&self, dir: &Path) -> Result<Option<PathBuf>> {
        let d = dir.join(&self.method);
        std::fs::create_dir_all(&d).with_context(|| format!("creating {}", d.display()))?;
        let path = d.join(format!("{}.json", self.short_hash()));
        let text = serde_json::to_string_pretty(self)? + "\n";
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(mut f) => {
                use std::io::Write;
                f.write_all(text.as_bytes()).with_context(|| format!("writing {}", path.display()))?;
                Ok(Some(path))
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(None),
            Err(e) => Err(anyhow!("{}: cannot create: {e}", path.display())),
        }
    }
}

/// Is this sample (rounded or not) interior and culled by the method on this tile?
/// Returns the bound that culls it and by how much, or why not.
pub fn witness_holds(
    m: &dyn Method,
    case: &Case,
    tile: &Tile,
    s: [f64; 5],
) -> std::result::Result<(String, f64), String> {
    witness_holds_in(m, case, tile, s, SampleSet::Any, None)
}

/// [`witness_holds`] under a sample set (the witness's (x, y) must be a point of it) and
/// vertex snapping (the method sees the snapped triangle, the oracle judges it exactly).
pub fn witness_holds_in(
    m: &dyn Method,
    case: &Case,
    tile: &Tile,
    s: [f64; 5],
    set: SampleSet,
    snap: Option<Snap>,
) -> std::result::Result<(String, f64), String> {
    let (seen, tri) = crate::check::samples::judged_triangles(snap, case)?;
    if !set.contains(s[0], s[1]) {
        return Err(format!("the witness's (x, y) = ({}, {}) is not a point of the sample set `{set}`", s[0], s[1]));
    }
    let inside = |v: f64, lo: f32, hi: f32| lo as f64 <= v && v <= hi as f64;
    if !(inside(s[0], tile.x0, tile.x1) && inside(s[1], tile.y0, tile.y1)) {
        return Err("the witness is not in the tile".into());
    }
    if !crate::check::in_domain(tile, s) {
        return Err(format!(
            "the witness (u, v, t) = ({}, {}, {}) is outside the lens/shutter domain [-1, 1]^2 x [0, 1]",
            s[2], s[3], s[4]
        ));
    }
    match classify(&tri, s) {
        Coverage::Interior => {}
        c => return Err(format!("the witness is not interior ({c:?})")),
    }
    match m.setup(&seen).tile(tile) {
        TileResult::Empty => Ok(("tile culled".into(), f64::INFINITY)),
        TileResult::Bounds(b) => {
            let mut worst = culled_by(&b, s);
            if let Some(z) = b.z {
                use oracles::DepthCheck;
                let depth = oracles::coverage::depth_enclosure(&tri, s);
                let beyond = match oracles::classify_depth(&tri, s, z[0] as f64, z[1] as f64) {
                    DepthCheck::Below => Some(("z min", depth.map_or(f64::INFINITY, |e| z[0] as f64 - e.hi))),
                    DepthCheck::Above => Some(("z max", depth.map_or(f64::INFINITY, |e| e.lo - z[1] as f64))),
                    _ => None,
                };
                if let Some((name, d)) = beyond {
                    // Decided exactly; the enclosure only sizes it.
                    let d = d.max(f64::MIN_POSITIVE);
                    if worst.as_ref().is_none_or(|w| d > w.1) {
                        worst = Some((name.into(), d));
                    }
                }
            }
            worst.ok_or_else(|| "the method admits the witness".into())
        }
    }
}

/// The outcome of replaying one file.
#[derive(Clone, Debug, Serialize)]
pub struct Replay {
    pub path: String,
    pub method: String,
    pub expected: Verdict,
    /// The stored witness, re-decided: Ok((bound, margin)) or why it no longer holds.
    pub witness: Option<std::result::Result<(String, f64), String>>,
    /// A fresh judgement: "violation", "proven", "unproven (reasons)".
    pub judged: String,
    pub margin: Option<f64>,
    pub ok: bool,
    /// The sample set, snap and viewport judged under, when not the defaults.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<String>,
}

fn judged_word(j: &Judgement) -> String {
    match j.verdict() {
        crate::check::Verdict::Violated => "violation".into(),
        crate::check::Verdict::Proven => "proven".into(),
        crate::check::Verdict::NotJudged => "not judged (the case cannot be snapped)".into(),
        crate::check::Verdict::Unproven => {
            let r: Vec<&str> = j.unproven().iter().map(|r| r.name()).collect();
            format!("unproven ({})", r.join(", "))
        }
    }
}

/// A stored witness re-decided: Ok((bound, margin)) when the method still culls it, or
/// why not; None when the file holds no witness.
pub type WitnessCheck = Option<std::result::Result<(String, f64), String>>;

/// The stored witness re-decided under `m` and a fresh judgement of `m` on the file's
/// case, under the file's settings (or those in `over`) with the whole side budget;
/// with the settings used.
fn judge_file(
    cf: &CaseFile,
    m: &MethodRef,
    cfg: &CheckConfig,
    over: &Declared,
) -> (WitnessCheck, Judgement, CheckConfig) {
    let mut cfg = CheckConfig { side_stall: 0, ..cf.settings(cfg) };
    over.apply(&mut cfg);
    let witness = cf
        .witness
        .as_ref()
        .map(|w| witness_holds_in(m.as_ref(), &cf.case, &cf.tile, w.sample, cfg.sample_set, cfg.snap));
    let (mut js, _) = judge(&cfg, std::slice::from_ref(m), &cf.case, &cf.tile, cf.provenance.case_index);
    (witness, js.swap_remove(0), cfg)
}

/// Re-judge one case file, with the whole side budget (one case: no stall cut-off).
/// The file's sample set, snap and viewport are used.
pub fn replay(path: &Path, cfg: &CheckConfig) -> Result<Replay> {
    replay_with(path, cfg, &Declared::default())
}

/// [`replay`], with the sample set, snap or viewport given in `over` in place of the
/// file's (to ask whether a case found under one set holds under another).
pub fn replay_with(path: &Path, cfg: &CheckConfig, over: &Declared) -> Result<Replay> {
    let cf = CaseFile::load(path)?;
    let m = crate::bounds::shared(method_of(&cf.method).expect("checked at load"));
    let (witness, j, cfg) = judge_file(&cf, &m, cfg, over);
    let j = &j;
    let judged = judged_word(j);
    let ok = match cf.expected {
        // The stored witness must still hold, and the fresh judgement must not
        // contradict it: a proof of conservativeness next to a witness that holds
        // would mean the judge is wrong. (Unproven is no contradiction: the fresh
        // search may run out of budget before it finds the stored sample again.)
        Verdict::Violation => matches!(witness, Some(Ok(_))) && j.verdict() != crate::check::Verdict::Proven,
        // A conservative case must be proven afresh, and its stored witness (if any)
        // must not hold.
        Verdict::Conservative => j.verdict() == crate::check::Verdict::Proven && !matches!(witness, Some(Ok(_))),
    };
    Ok(Replay {
        path: path.display().to_string(),
        method: cf.method,
        expected: cf.expected,
        witness,
        judged,
        margin: j.violation.as_ref().map(|w| w.margin),
        ok,
        samples: crate::check::samples::SetNote::of(&cfg, 0).map(|n| n.key()),
    })
}

/// The outcome of re-judging one file's case against another method
/// (`replay --method ID`).
#[derive(Clone, Debug, Serialize)]
pub struct Rejudge {
    pub path: String,
    /// The method the file was written for.
    pub found_for: String,
    /// The method judged now.
    pub method: String,
    /// The stored witness (if any) under the new method: Ok((bound, margin)) when it
    /// still culls it, or why not.
    pub witness: Option<std::result::Result<(String, f64), String>>,
    /// The fresh judgement: "violation", "proven", "unproven (reasons)".
    pub judged: String,
    /// "fixed" (proven afresh, the stored witness no longer culled), "still violated"
    /// (a violation found afresh, or the stored witness still culled), "unproven" or
    /// "not judged" (the case cannot be snapped under the file's settings).
    pub outcome: &'static str,
}

/// Re-judge the case of one file against `method` in place of the file's own (under
/// the file's sample set, snap and viewport, or those in `over`), with the whole side
/// budget: does a fixed bound still cull the stored witness, and is it proven on the
/// case?
pub fn rejudge(path: &Path, cfg: &CheckConfig, over: &Declared, method: &str) -> Result<Rejudge> {
    let m = method_of(method)
        .ok_or_else(|| anyhow::anyhow!("--method {method}: no such method (see `cullproof methods`)"))?;
    rejudge_with(path, cfg, over, &crate::bounds::shared(m))
}

/// [`rejudge`] against a method held by its handle (a bound of the caller's own, not
/// in the registry).
pub fn rejudge_with(path: &Path, cfg: &CheckConfig, over: &Declared, m: &MethodRef) -> Result<Rejudge> {
    let cf = CaseFile::load_for(path, Some(m))?;
    let method = m.info().id;
    let (witness, j, _) = judge_file(&cf, m, cfg, over);
    let j = &j;
    let outcome = match (j.verdict(), &witness) {
        (crate::check::Verdict::Violated, _) | (_, Some(Ok(_))) => "still violated",
        (crate::check::Verdict::Proven, _) => "fixed",
        (crate::check::Verdict::Unproven, _) => "unproven",
        (crate::check::Verdict::NotJudged, _) => "not judged",
    };
    Ok(Rejudge {
        path: path.display().to_string(),
        found_for: cf.method,
        method: method.to_string(),
        witness,
        judged: judged_word(j),
        outcome,
    })
}

/// Every `*.json` file under the paths (files are taken as given, directories walked).
pub fn case_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    fn walk(p: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
        let mut entries: Vec<_> = std::fs::read_dir(p)
            .with_context(|| format!("{}: cannot list", p.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        entries.sort();
        for e in entries {
            if e.is_dir() {
                walk(&e, out)?;
            } else if e.extension().is_some_and(|x| x == "json") {
                out.push(e);
            }
        }
        Ok(())
    }
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out)?;
        } else if p.exists() {
            out.push(p.clone());
        } else {
            bail!("{}: no such file or directory", p.display());
        }
    }
    Ok(out)
}

/// One shrinking step: a simpler case and tile to try.
type Step = (&'static str, Case, Tile);

/// Drop the lens when an edit leaves the triangle no longer matching it (the case
/// becomes a per-vertex CoC case, judged by the exact oracle alone).
fn keep_lens_if_matching(mut c: Case) -> Case {
    if let Some(l) = &c.lens {
        if l.check_matches(&c.triangle).is_err() {
            c.lens = None;
        }
    }
    c
}

fn round_bits(v: f32, bits: u32) -> f32 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let drop = 24 - bits;
    let b = v.to_bits();
    let half = 1u32 << (drop - 1);
    f32::from_bits(((b + half) >> drop) << drop)
}

/// Candidate simplifications, simplest first.
fn steps(case: &Case, tile: &Tile, witness: [f64; 5]) -> Vec<Step> {
    let mut out: Vec<Step> = Vec::new();
    let t = case.triangle;
    if t.q != t.r || t.c0 != t.c1 {
        // Freeze the motion at the witness's time.
        let s = witness[4] as f32;
        let mut c = *case;
        for i in 0..3 {
            for j in 0..4 {
                let v = (1.0 - s) * t.q[i][j] + s * t.r[i][j];
                c.triangle.q[i][j] = v;
                c.triangle.r[i][j] = v;
            }
            let cc = (1.0 - s) * t.c0[i] + s * t.c1[i];
            c.triangle.c0[i] = cc;
            c.triangle.c1[i] = cc;
        }
        out.push(("freeze motion", keep_lens_if_matching(c), *tile));
    }
    if t.c0.iter().chain(&t.c1).any(|&c| c != 0.0) {
        let mut c = *case;
        c.triangle.c0 = [0.0; 3];
        c.triangle.c1 = [0.0; 3];
        out.push(("zero the CoC", keep_lens_if_matching(c), *tile));
    }
    for bits in [4u32, 8, 12, 16, 20] {
        let mut c = *case;
        let r = |v: &mut f32| *v = round_bits(*v, bits);
        c.triangle.q.iter_mut().flatten().for_each(r);
        c.triangle.r.iter_mut().flatten().for_each(r);
        c.triangle.c0.iter_mut().for_each(r);
        c.triangle.c1.iter_mut().for_each(r);
        if c != *case {
            out.push(("snap to fewer mantissa bits", keep_lens_if_matching(c), *tile));
        }
    }
    if t.k != 1.0 {
        let mut c = *case;
        c.triangle.k = 1.0;
        out.push(("aspect k = 1", keep_lens_if_matching(c), *tile));
    }
    // Move the depths to a corner of their range: every vertex to w = 1 at both shutter
    // ends (each divided by its w, CoC included, so its screen position and
    // screen-space CoC at t = 0 and t = 1 stay; only the perspective goes).
    let ws = t.q.iter().chain(&t.r).map(|p| p[3]);
    if ws.clone().all(|w| w > 0.0) && ws.clone().any(|w| w != 1.0) {
        let mut c = *case;
        let unit = |p: [f32; 4]| [p[0] / p[3], p[1] / p[3], p[2] / p[3], 1.0];
        c.triangle.q = t.q.map(unit);
        c.triangle.r = t.r.map(unit);
        c.triangle.c0 = std::array::from_fn(|i| t.c0[i] / t.q[i][3]);
        c.triangle.c1 = std::array::from_fn(|i| t.c1[i] / t.r[i][3]);
        out.push(("depths to w = 1", keep_lens_if_matching(c), *tile));
    }
    // Shrink the tile around the witness to the next smaller power-of-two tile.
    let size = (tile.x1 - tile.x0).min(tile.y1 - tile.y0);
    if size > 1.0 {
        let half = size / 2.0;
        let x0 = tile.x0 + if witness[0] as f32 >= tile.x0 + half { half } else { 0.0 };
        let y0 = tile.y0 + if witness[1] as f32 >= tile.y0 + half { half } else { 0.0 };
        out.push(("shrink the tile", *case, Tile::square(x0, y0, half)));
    }
    out
}

/// Shrink a violation: repeatedly take the first simplification under which the
/// method still shows a violation at least half as large (a culled covered tile, margin
/// inf, must stay one): a gross failure is never traded for a rounding one. Returns the
/// last case, tile and judgement, and the steps kept.
pub fn shrink(
    cfg: &CheckConfig,
    m: &MethodRef,
    case: Case,
    tile: Tile,
    first: Judgement,
    index: u64,
) -> (Case, Tile, Judgement, Vec<String>) {
    let floor = 0.5 * first.violation.as_ref().expect("a violation").margin;
    shrink_while(cfg, m, case, tile, first, index, &|j| j.violation.as_ref().is_some_and(|v| v.margin >= floor))
}

/// [`shrink`], keeping a step while `keep` holds of the method's judgement on it (the
/// witness of the last judgement is the one simplifications are centred on).
pub fn shrink_while(
    cfg: &CheckConfig,
    m: &MethodRef,
    case: Case,
    tile: Tile,
    first: Judgement,
    index: u64,
    keep: &dyn Fn(&Judgement) -> bool,
) -> (Case, Tile, Judgement, Vec<String>) {
    let (mut case, mut tile, mut j) = (case, tile, first);
    let mut kept = Vec::new();
    'outer: for _ in 0..64 {
        let w = j.violation.as_ref().expect("a violation").sample;
        for (name, c, t) in steps(&case, &tile, w) {
            if c.validate().is_err() || !crate::check::samples::placed_in(cfg, &c, &t) {
                continue;
            }
            let (js, _) = judge(cfg, std::slice::from_ref(m), &c, &t, index);
            if js[0].violation.is_some() && keep(&js[0]) {
                (case, tile, j) = (c, t, js[0].clone());
                kept.push(name.to_string());
                continue 'outer;
            }
        }
        break;
    }
    (case, tile, j, kept)
}

/// What a search found.
#[derive(Clone, Debug, Serialize)]
pub struct Found {
    pub method: String,
    pub regime: String,
    pub case_index: u64,
    pub seconds_to_first: f64,
    pub margin: f64,
    pub bound: String,
    /// The kind of bound (as `corpus/expectations.json` names it, see
    /// [`crate::check::bound_kind`]) the finding is about.
    pub kind: String,
    pub shrink_steps: Vec<String>,
    /// Where it was written (None: the same case was already in the corpus).
    pub file: Option<String>,
    /// Beyond the method's expected signature for the regime: a kind of bound the
    /// signature does not list, a margin above its cap, or any violation where the
    /// regime is expected conservative (false when no expectations were given).
    pub beyond_signature: bool,
    /// The signature's cap on this kind's margin (null: the kind is not listed, the
    /// regime is not an expected violation, or no expectations were given).
    pub cap: Option<Cap>,
    /// Why it is beyond ("not in the signature", "above the cap 5e-5", "the regime is
    /// expected conservative"); empty inside the signature.
    pub signature: String,
}

/// One kind of bound violated in one regime during a search, over every case (before
/// any dedupe or shrinking), held against the signature.
#[derive(Clone, Debug, Serialize)]
pub struct KindSeen {
    pub regime: String,
    pub kind: String,
    /// Cases that violate it (by at least the search's minimum margin).
    pub cases: u64,
    /// The largest margin seen ("inf": a covered tile culled).
    #[serde(with = "num_or_inf")]
    pub max_margin: f64,
    /// The signature's cap (null: not listed, or not an expected violation).
    pub cap: Option<Cap>,
    /// The largest margin lies beyond the signature.
    pub beyond_signature: bool,
}

/// One regime of a search: its cases, and on their boundary tiles (as the gate judges
/// them) the cases with a violation and the proven interval ends probed for tightness.
/// Under `--gate` these are held against the signature's rate cap and tightness.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RegimeSeen {
    pub regime: String,
    pub cases: u64,
    /// Cases whose boundary tile shows a violation (by at least the minimum margin).
    pub violated: u64,
    /// The signature's rate cap (null: none).
    pub max_rate: Option<f64>,
    /// The signature's cap on the search's boundary-tile rate (null: none, or not at
    /// these settings); the table shows it in place of `max_rate` where there is one.
    pub max_boundary_rate: Option<f64>,
    pub tight: BTreeMap<String, crate::check::expect::TightStat>,
    /// Tiles judged at the method's own tile-reject limit, and those with a violation.
    pub limit_tiles: u64,
    pub limit_violations: u64,
    /// The signature's cap on the limit tiles' violation rate (null: none, or not at
    /// these settings).
    pub max_limit_rate: Option<f64>,
    /// Mean share of the boundary tile's uniform samples the answers admit.
    pub admit_fraction: f64,
    /// The signature's cap on that share (null: none, or not at these settings).
    pub max_admit: Option<f64>,
}

/// The result of a search.
#[derive(Clone, Debug, Serialize)]
pub struct SearchReport {
    pub method: String,
    pub seed: u64,
    pub cases: u64,
    pub seconds: f64,
    pub found: Vec<Found>,
    /// Under `--gate`: only violations beyond the signature are findings (shrunk,
    /// written, counted against `--max`); the others are only counted.
    pub gate: bool,
    /// The expectations file the violations were held against (None: none).
    pub expectations: Option<String>,
    /// Cases with a violation (at least the minimum margin), and of those the ones
    /// with some kind of bound beyond the signature.
    pub violated_cases: u64,
    pub beyond_cases: u64,
    /// Per regime and kind of bound violated (when expectations were given).
    pub kinds: Vec<KindSeen>,
    /// Per regime: cases, violated boundary tiles and tightness.
    pub regimes: Vec<RegimeSeen>,
    /// Under `--gate`: where the search's cases as a whole leave the signature (a
    /// violation rate above the cap, beyond counting noise; fewer tight ends than the
    /// tightness signature allows, per regime and pooled over the regimes), one line
    /// each. No single case witnesses these, so no case file is written for them.
    pub breaches: Vec<String>,
}

/// How a search runs (see [`search_with`]).
pub struct SearchOptions<'a> {
    /// Search for about this many seconds.
    pub seconds: f64,
    /// Stop after this many findings.
    pub max_found: usize,
    /// Ignore violations that need less margin.
    pub min_margin: f64,
    /// Where to write the shrunk cases (None: report only).
    pub out: Option<&'a Path>,
    pub progress: bool,
    /// The expectations each violation is held against, and the file's name (None:
    /// not judged).
    pub expectations: Option<(&'a Expectations, &'a str)>,
    /// Only violations beyond the signature are findings (needs `expectations`).
    pub gate: bool,
}

/// Randomized search for violations of one method: cases of the regimes in turn, in
/// parallel batches (the order of cases, hence the result, does not depend on the
/// thread count), for `seconds` or until `max_found` violations; each violation is
/// shrunk and written to `out` (never overwriting).
pub fn search(
    cfg: &CheckConfig,
    m: MethodRef,
    seconds: f64,
    max_found: usize,
    min_margin: f64,
    out: Option<&Path>,
    progress: bool,
) -> Result<SearchReport> {
    let o = SearchOptions { seconds, max_found, min_margin, out, progress, expectations: None, gate: false };
    search_with(cfg, m, &o)
}

/// [`search`], each violation held against the method's expected signature for its
/// regime (`corpus/expectations.json`, see [`crate::check::expect`]): every kind of
/// bound it violates, with its margin. Without the gate, one finding per regime and
/// bound (one per regime, bound and side of the signature when expectations are
/// given: a violation beyond the signature is never hidden behind one inside it),
/// each annotated. With `gate`, violations inside the signature are only counted
/// (they neither stop the search nor count against `max_found`), and each kind of
/// bound beyond the signature makes a finding (one per regime and kind), shrunk while
/// it stays beyond the signature at least half as large, and written with that
/// kind's own witness.
pub fn search_with(cfg: &CheckConfig, m: MethodRef, o: &SearchOptions) -> Result<SearchReport> {
    use rayon::prelude::*;
    anyhow::ensure!(!o.gate || o.expectations.is_some(), "a gated search needs the expectations");
    let cfg = &CheckConfig { witnesses_per_kind: true, ..cfg.clone() };
    let id = m.info().id;
    let measured = crate::check::settings::Settings::whole(cfg).measured();
    let entry = |r: Regime| o.expectations.map(|(ex, _)| ex.entry(id, r.name()).scoped(measured));
    // The kinds of bound a judgement violates beyond the signature, largest margin first.
    let beyond_kinds = |r: Regime, j: &Judgement| -> Vec<(String, f64, String)> {
        let Some(e) = entry(r) else { return Vec::new() };
        let mut v: Vec<_> = j
            .violated
            .iter()
            .filter(|(_, &mm)| mm >= o.min_margin)
            .filter_map(|(k, &mm)| e.beyond(k, mm).map(|why| (k.clone(), mm, why)))
            .collect();
        v.sort_by(|a, b| b.1.total_cmp(&a.1));
        v
    };
    let interesting = |r: Regime, j: &Judgement| {
        if o.gate {
            !beyond_kinds(r, j).is_empty()
        } else {
            j.violation.as_ref().is_some_and(|v| v.margin >= o.min_margin)
        }
    };
    let start = std::time::Instant::now();
    let pb = if o.progress { indicatif::ProgressBar::new_spinner() } else { indicatif::ProgressBar::hidden() };
    let mut found = Vec::new();
    let mut next = 0u64;
    let batch = 8 * rayon::current_num_threads() as u64;
    let mut seen = std::collections::BTreeSet::new();
    let (mut violated_cases, mut beyond_cases) = (0u64, 0u64);
    let mut kinds: std::collections::BTreeMap<(Regime, String), (u64, f64)> = Default::default();
    let mut per_regime: BTreeMap<Regime, RegimeSeen> = BTreeMap::new();
    while start.elapsed().as_secs_f64() < o.seconds && found.len() < o.max_found {
        let ids: Vec<u64> = (next..next + batch).collect();
        next += batch;
        // Per case: the boundary tile's judgement, and the limit tiles' when the
        // boundary tile shows nothing of interest.
        let results: Vec<(u64, Regime, Judgement, Option<Judgement>, (u32, u32), f64)> = ids
            .par_iter()
            .filter_map(|&i| {
                let (regime, case, tile) = try_make_case(cfg, i)?;
                let (js, _) = judge(cfg, std::slice::from_ref(&m), &case, &tile, i);
                let j = js.into_iter().next().unwrap();
                let admit = crate::check::admitted_share(cfg, m.as_ref(), &case, &tile, i);
                // Also the tiles at the method's own tile-reject limit (the witness
                // then carries the case, moved on screen, and the tile), counted for
                // the limit-tile rate.
                let (mut limit, mut counts) = (None, (0, 0));
                if !interesting(regime, &j) {
                    if let (Some(l), _) = crate::check::judge_limit_tiles(cfg, m.as_ref(), &case, i, 0) {
                        counts = (l.limit_tiles, l.limit_violations);
                        let w = l.violation.as_ref();
                        if w.is_some_and(|w| crate::check::samples::placed_in(cfg, &w.case, &w.tile)) {
                            limit = Some(l);
                        }
                    }
                }
                Some((i, regime, j, limit, counts, admit))
            })
            .collect();
        for (i, regime, j, limit, counts, admit) in results {
            // The boundary tile, as the gate judges it: rate, tightness and admitted
            // share; the limit tiles' rate.
            let rs = per_regime.entry(regime).or_default();
            rs.cases += 1;
            rs.admit_fraction += admit;
            rs.limit_tiles += counts.0 as u64;
            rs.limit_violations += counts.1 as u64;
            rs.violated += j.violated.values().any(|&mm| mm >= o.min_margin) as u64;
            for (k, &(n, t)) in &j.tight {
                let e = rs.tight.entry(k.clone()).or_default();
                (e.probed, e.tight) = (e.probed + n as u64, e.tight + t as u64);
            }
            // Count every kind violated in this case, over all its tiles.
            let mut all = j.clone();
            if let Some(l) = &limit {
                all.merge(l.clone());
            }
            if all.violated.values().any(|&mm| mm >= o.min_margin) {
                violated_cases += 1;
                beyond_cases += !beyond_kinds(regime, &all).is_empty() as u64;
                if o.expectations.is_some() {
                    for (k, &mm) in all.violated.iter().filter(|(_, &mm)| mm >= o.min_margin) {
                        let e = kinds.entry((regime, k.clone())).or_insert((0, 0.0));
                        *e = (e.0 + 1, e.1.max(mm));
                    }
                }
            }
            let f = match limit {
                Some(l) if !interesting(regime, &j) && interesting(regime, &l) => l,
                _ => j,
            };
            if !interesting(regime, &f) {
                continue;
            }
            let t_first = start.elapsed().as_secs_f64();
            let mut picks: Vec<(String, Option<(f64, String)>)> = Vec::new();
            if o.gate {
                picks.extend(beyond_kinds(regime, &f).into_iter().map(|(k, mm, why)| (k, Some((mm, why)))));
            } else {
                picks.push((crate::check::bound_kind(&f.violation.as_ref().unwrap().bound), None));
            }
            for (kind, beyond) in picks {
                if found.len() >= o.max_found {
                    break;
                }
                let Some(w) = f.witness_of(&kind).cloned() else { continue };
                if !crate::check::samples::placed_in(cfg, &w.case, &w.tile) {
                    continue;
                }
                // One file per (regime, bound) is enough for a run; with the gate, one
                // per (regime, kind) beyond the signature; without it, a violation
                // beyond the signature is not hidden behind one inside it.
                let key = match &beyond {
                    Some(_) => (regime, kind.clone(), true),
                    None => {
                        let out = entry(regime).and_then(|e| e.beyond(&kind, w.margin)).is_some();
                        (regime, w.bound.clone(), out)
                    }
                };
                if !seen.insert(key) {
                    continue;
                }
                let (c, t, jj, steps) = match &beyond {
                    Some((mm, _)) => {
                        let (floor, e) = (0.5 * mm, entry(regime).expect("the gate has expectations"));
                        let keep = |j: &Judgement| {
                            j.violated.get(&kind).is_some_and(|&x| x >= floor && e.beyond(&kind, x).is_some())
                        };
                        shrink_while(cfg, &m, w.case, w.tile, f.clone(), i, &keep)
                    }
                    None => shrink(cfg, &m, w.case, w.tile, f.clone(), i),
                };
                let w = match &beyond {
                    Some(_) => jj.witness_of(&kind),
                    None => jj.violation.as_ref(),
                }
                .expect("a violation")
                .clone();
                let kind = if beyond.is_some() { kind } else { crate::check::bound_kind(&w.bound) };
                let margin = jj.violated.get(&kind).copied().unwrap_or(w.margin);
                let e = entry(regime);
                let why = e.as_ref().and_then(|e| e.beyond(&kind, margin)).unwrap_or_default();
                let cap = e.as_ref().and_then(|e| e.cap(&kind)).map(Cap);
                let note = if why.is_empty() {
                    String::new()
                } else {
                    let other = if crate::check::bound_kind(&w.bound) != kind {
                        format!("; the stored witness is the case's worst ({})", w.bound)
                    } else {
                        String::new()
                    };
                    format!(
                        "search: `{kind}` margin {margin:.3e} beyond {id}'s signature in regime {} ({why}){other}",
                        regime.name()
                    )
                };
                let cf =
                    CaseFile::violation(id, (c, t), &w, cfg, ("search", i, regime.name().into()), steps.clone(), note);
                let file = match o.out {
                    Some(dir) => cf.write_new(dir)?.map(|p| p.display().to_string()),
                    None => None,
                };
                found.push(Found {
                    method: id.into(),
                    regime: regime.name().into(),
                    case_index: i,
                    seconds_to_first: t_first,
                    margin: w.margin,
                    bound: w.bound,
                    kind,
                    shrink_steps: steps,
                    file,
                    beyond_signature: !why.is_empty(),
                    cap,
                    signature: why,
                });
            }
        }
        pb.set_message(format!("{} cases, {} found", next, found.len()));
    }
    pb.finish_and_clear();
    let kinds = kinds
        .into_iter()
        .map(|((regime, kind), (cases, max_margin))| {
            let e = entry(regime).expect("counted only with expectations");
            KindSeen {
                regime: regime.name().into(),
                cap: e.cap(&kind).map(Cap),
                beyond_signature: e.beyond(&kind, max_margin).is_some(),
                kind,
                cases,
                max_margin,
            }
        })
        .collect();
    let mut breaches = Vec::new();
    let regimes: Vec<RegimeSeen> = per_regime
        .into_iter()
        .map(|(regime, mut seen)| {
            seen.regime = regime.name().into();
            if seen.cases > 0 {
                seen.admit_fraction /= seen.cases as f64;
            }
            if let Some(e) = entry(regime) {
                seen.max_rate = e.max_rate;
                seen.max_boundary_rate = e.max_boundary_rate;
                seen.max_limit_rate = e.max_limit_rate;
                seen.max_admit = e.max_admit;
                if o.gate {
                    let lines = e
                        .rate_breach(seen.violated, seen.cases)
                        .into_iter()
                        .chain(e.boundary_rate_breach(seen.violated, seen.cases))
                        .chain(e.limit_rate_breach(seen.limit_violations, seen.limit_tiles))
                        .chain(e.looser(&seen.tight))
                        .chain(e.admit_breach(seen.admit_fraction, seen.cases));
                    breaches.extend(lines.map(|l| format!("regime {}: {l}", regime.name())));
                }
            }
            seen
        })
        .collect();
    if o.gate {
        let rows: Vec<(Entry, &RegimeSeen)> = regimes
            .iter()
            .filter_map(|seen| {
                let r = Regime::ALL.into_iter().find(|r| r.name() == seen.regime)?;
                Some((entry(r)?, seen))
            })
            .collect();
        breaches.extend(pooled_looser(rows.iter().map(|(e, seen)| (e, &seen.tight))).into_iter().map(|(_, l)| l));
        breaches.extend(crate::check::expect::pooled_boundary_breach(
            rows.iter().map(|(e, seen)| (e, seen.violated, seen.cases)),
        ));
    }
    Ok(SearchReport {
        method: id.into(),
        seed: cfg.seed,
        cases: next,
        seconds: start.elapsed().as_secs_f64(),
        found,
        gate: o.gate,
        expectations: o.expectations.map(|(_, name)| name.to_string()),
        violated_cases,
        beyond_cases,
        kinds,
        regimes,
        breaches,
    })
}

fn fmt_cap(c: Option<Cap>) -> String {
    match c {
        None => "-".into(),
        Some(Cap(c)) if c.is_infinite() => "inf".into(),
        Some(Cap(c)) => format!("{c:e}"),
    }
}

/// The line that names one finding beyond the signature.
pub fn beyond_line(f: &Found) -> String {
    format!(
        "beyond the signature: {}, regime {}: `{}` margin {:.3e} {}{}",
        f.method,
        f.regime,
        f.kind,
        f.margin,
        f.signature,
        f.file.as_deref().map_or(String::new(), |p| format!(" (case file {p})"))
    )
}

/// The search's report as text: a line per finding; with the gate, the kinds of bound
/// seen per regime against the signature and a line per finding beyond it.
pub fn render_search(r: &SearchReport) -> String {
    let mut s = if r.gate {
        format!(
            "search {} --gate ({}): seed {}, {} cases in {:.1} s; {} case(s) violated, {} within the signature, {} beyond it; {} finding(s) beyond the signature\n",
            r.method,
            r.expectations.as_deref().unwrap_or("-"),
            r.seed,
            r.cases,
            r.seconds,
            r.violated_cases,
            r.violated_cases - r.beyond_cases,
            r.beyond_cases,
            r.found.len()
        )
    } else {
        format!(
            "search {}: seed {}, {} cases in {:.1} s, {} violation(s)\n",
            r.method,
            r.seed,
            r.cases,
            r.seconds,
            r.found.len()
        )
    };
    for f in &r.found {
        s += &format!(
            "  {:<15} case {:>6} after {:>6.2} s: {} by {:.3e}; shrunk: {}; {}{}\n",
            f.regime,
            f.case_index,
            f.seconds_to_first,
            f.bound,
            f.margin,
            if f.shrink_steps.is_empty() { "-".to_string() } else { f.shrink_steps.join(", ") },
            f.file
                .as_deref()
                .map_or("not written (already in the corpus or --dry-run)".to_string(), |p| format!("wrote {p}")),
            if f.beyond_signature && !r.gate {
                format!(" [beyond the signature: {}]", f.signature)
            } else {
                String::new()
            }
        );
    }
    if r.gate {
        if !r.kinds.is_empty() {
            s += &format!(
                "\nkinds of bound violated (all cases, before shrinking):\n  {:<15} {:<48} {:>7} {:>11} {:>9}  status\n",
                "regime", "kind", "cases", "max margin", "cap"
            );
            for k in &r.kinds {
                s += &format!(
                    "  {:<15} {:<48} {:>7} {:>11} {:>9}  {}\n",
                    k.regime,
                    k.kind,
                    k.cases,
                    if k.max_margin.is_infinite() { "inf".to_string() } else { format!("{:.3e}", k.max_margin) },
                    fmt_cap(k.cap),
                    if k.beyond_signature { "BEYOND" } else { "within" }
                );
            }
        }
        if !r.regimes.is_empty() {
            s += &format!(
                "\nper regime, as the gate judges them (boundary tiles; limit tiles at the method's own reject limit):\n  \
                 {:<15} {:>8} {:>9} {:>9} {:>12} {:>9} {:>7} {:>9}  tight ends (share)\n",
                "regime", "cases", "violated", "rate cap", "limit", "cap", "admit", "cap"
            );
            let cap = |c: Option<f64>| c.map_or("-".to_string(), |r| r.to_string());
            for g in &r.regimes {
                let tight: Vec<String> = g
                    .tight
                    .iter()
                    .filter(|(_, t)| t.probed > 0)
                    .map(|(k, t)| format!("{k} {:.2}", t.tight as f64 / t.probed as f64))
                    .collect();
                s += &format!(
                    "  {:<15} {:>8} {:>9} {:>9} {:>12} {:>9} {:>7.3} {:>9}  {}\n",
                    g.regime,
                    g.cases,
                    g.violated,
                    cap(g.max_boundary_rate.or(g.max_rate)),
                    format!("{}/{}", g.limit_violations, g.limit_tiles),
                    cap(g.max_limit_rate),
                    g.admit_fraction,
                    cap(g.max_admit),
                    if tight.is_empty() { "-".to_string() } else { tight.join(", ") }
                );
            }
        }
        if !r.found.is_empty() || !r.breaches.is_empty() {
            s += "\n";
        }
        for f in &r.found {
            s += &beyond_line(f);
            s += "\n";
        }
        for b in &r.breaches {
            s += &format!("beyond the signature: {}, {b}\n", r.method);
        }
    }
    s
}

/// The case in words: the method's answer, the exact extents of the covered set over
/// the tile, and the witness decided exactly (and by Embree when physical).
pub fn describe(cf: &CaseFile) -> String {
    describe_with(cf, method_of(&cf.method).expect("checked at load"))
}

/// [`describe`], the method's answer given by `m` (a bound of the caller's own, or
/// another than the file names).
pub fn describe_with(cf: &CaseFile, m: &dyn Method) -> String {
    use oracles::extents::{Extent, ExtentsConfig, Occupancy, TileSolver};
    let info = m.info();
    let (seen, tri) = match crate::check::samples::judged_triangles(cf.snap, &cf.case) {
        Ok(x) => x,
        Err(e) => return format!("{}: the case cannot be snapped: {e}\n", info.id),
    };
    let mut s =
        format!("{} ({}{})\n", info.id, info.source, if info.reconstruction { "; a reconstruction" } else { "" });
    s += &format!(
        "case: {} triangle ({}), found by {} (seed {}, case {}, regime {}){}\n",
        cf.case.triangle.dims().name(),
        if cf.case.lens.is_some() { "thin lens" } else { "no physical lens: exact oracle only" },
        cf.provenance.found_by,
        cf.provenance.seed,
        cf.provenance.case_index,
        cf.provenance.regime,
        if cf.provenance.shrink_steps.is_empty() {
            String::new()
        } else {
            format!(", shrunk: {}", cf.provenance.shrink_steps.join(", "))
        }
    );
    if !cf.note.is_empty() {
        s += &format!("note: {}\n", cf.note);
    }
    let t = &cf.tile;
    s += &format!("tile: [{}, {}] x [{}, {}]\n", t.x0, t.x1, t.y0, t.y1);
    if !cf.samples.is_any() || cf.snap.is_some() || cf.viewport.is_some() {
        let cfg = cf.settings(&CheckConfig::default_for(Vec::new()));
        s += &format!("{}\n", crate::check::samples::SetNote::of(&cfg, 0).map(|n| n.line()).unwrap_or_default());
        if cf.snap.is_some() {
            s += "the method sees the snapped triangle (rounded to f32); the exact oracle judges it unrounded\n";
        }
    }
    let prep = m.setup(&seen);
    if let Some(why) = prep.disabled() {
        s += &format!("the method is disabled for this triangle: {why}\n");
    }
    match prep.tile(t) {
        TileResult::Empty => s += "the method says: tile empty (culled)\n",
        TileResult::Bounds(b) => {
            s += &format!(
                "the method says: u in [{}, {}], v in [{}, {}], t in [{}, {}]",
                b.u[0], b.u[1], b.v[0], b.v[1], b.t[0], b.t[1]
            );
            if let Some(z) = b.z {
                s += &format!(", depth in [{}, {}]", z[0], z[1]);
            }
            if !b.constraints.is_empty() {
                let names: Vec<_> = b.constraints.iter().map(|c| c.name()).collect();
                s += &format!(", and per sample: {}", names.join("; "));
            }
            s += "\n";
        }
    }
    let cfg = ExtentsConfig { occupancy_eliminates: false, ..ExtentsConfig::default() };
    let tb = [t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64];
    let mut solver = TileSolver::new(&tri, tb, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg);
    match solver.occupancy() {
        Occupancy::Empty => s += "exact: nothing in the tile is covered (certified)\n",
        Occupancy::Unknown => s += "exact: the solver could not decide whether anything in the tile is covered\n",
        Occupancy::Covered(_) => {
            s += "exact extents of the covered samples over the tile (certified enclosures of each extreme):\n";
            // Only the dimensions the triangle has: without defocus every lens position
            // covers the same samples, without motion every time does.
            let (lens, time) = (!tri.is_pinhole(), !tri.is_static());
            if !lens {
                s += "  u, v      any (no defocus: every lens position covers the same samples)\n";
            }
            if !time {
                s += "  t         any (no motion: every time covers the same samples)\n";
            }
            let has = |ext: Extent| match ext {
                Extent::UMin | Extent::UMax | Extent::VMin | Extent::VMax => lens,
                Extent::TMin | Extent::TMax => time,
                _ => true,
            };
            for (ext, name) in Extent::ALL.into_iter().zip([
                "u min",
                "u max",
                "v min",
                "v max",
                "t min",
                "t max",
                "depth min",
                "depth max",
            ]) {
                if !has(ext) {
                    continue;
                }
                let r = solver.objective(ext);
                match r.extreme {
                    Some(e) => {
                        s += &format!(
                            "  {name:<9} in [{:.9}, {:.9}]{}\n",
                            e.lo,
                            e.hi,
                            if r.undecided > 0 { format!(" ({} boxes undecided)", r.undecided) } else { String::new() }
                        )
                    }
                    None => s += &format!("  {name:<9} unknown ({} boxes undecided)\n", r.undecided),
                }
            }
        }
    }
    match &cf.witness {
        None => s += "no witness stored\n",
        Some(w) => {
            let p = w.sample;
            s += &format!("witness (x, y, u, v, t) = ({}, {}, {}, {}, {})\n", p[0], p[1], p[2], p[3], p[4]);
            s += &format!("  exact coverage: {:?}\n", classify(&tri, p));
            match witness_holds_in(m, &cf.case, &cf.tile, p, cf.samples, cf.snap) {
                Ok((b, d)) => s += &format!("  culled by {b}, {d:.6e} beyond it: a VIOLATION\n"),
                Err(e) => s += &format!("  not a violation: {e}\n"),
            }
            if let Some(l) = crate::agree::lens_tri(&cf.case).filter(|_| cf.snap.is_none()) {
                if let Ok(o) = oracles::embree::EmbreeOracle::new(&l) {
                    s += &format!("  Embree (f32, second opinion): {}\n", if o.hit(p) { "hit" } else { "miss" });
                }
            }
            s += &format!("  stored: culled by {}, margin needed {:.6e}\n", w.bound, w.margin);
        }
    }
    s
}

#[cfg(test)]
mod tests;
