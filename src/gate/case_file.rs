//! Case files anyone can replay: the gate writes its witnesses as case files (JUnit,
//! `GateReport::write_cases`), the search its findings, and replay reads them back.
//!
//! A case file (`corpus/cases/<method>/<short-hash>.json`) holds one method, one
//! triangle (with its thin lens when it has one) and one tile as plain numbers, the
//! witness sample with the bound that culls it and the margin needed, the expected
//! verdict and where it came from. [`crate::search::replay()`] re-judges it: the stored witness is
//! re-decided exactly (it must still be interior and still culled), and the method is
//! judged afresh on the case.
//!
//! A case file found under a declared sample set, vertex snapping or viewport
//! (`docs/model.md`, §7) records them (`samples`, `snap`, `viewport`); a file without
//! those fields was found under the defaults (any position, no snap, no viewport).
//! Replay and explain judge a file under what it records.

use crate::bounds::{by_id, Method, MethodRef, TileResult};
use crate::gate::CheckConfig;
use crate::io::num_or_inf;
use crate::io::quote::{clip, quote};
use crate::judge::culled_by;
use crate::model::{Case, SampleSet, Snap, Tile, Viewport};
use anyhow::{anyhow, bail, Context, Result};
use oracles::{classify, Coverage};
use serde::{Deserialize, Serialize};
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
        w: &crate::judge::Witness,
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
    let (seen, tri) = crate::cases::place::judged_triangles(snap, case)?;
    if !set.contains(s[0], s[1]) {
        return Err(format!("the witness's (x, y) = ({}, {}) is not a point of the sample set `{set}`", s[0], s[1]));
    }
    let inside = |v: f64, lo: f32, hi: f32| lo as f64 <= v && v <= hi as f64;
    if !(inside(s[0], tile.x0, tile.x1) && inside(s[1], tile.y0, tile.y1)) {
        return Err("the witness is not in the tile".into());
    }
    if !crate::judge::in_domain(tile, s) {
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
