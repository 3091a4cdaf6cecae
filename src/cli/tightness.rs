//! The `tightness` command: arguments, the run, the tables and the output files.

use crate::bounds::Method;
use crate::tools::tightness::cost::{self, CostRow, OpTable};
use crate::tools::tightness::mesh::{self, MeshControls};
use crate::tools::tightness::pattern::{Pattern, PatternKind};
use crate::tools::tightness::scene::{self, Scene, Setting};
use crate::tools::tightness::{
    chart, measure_with, CeilingRow, CertifiedRow, Config, MethodRow, SampleTable, SettingSummary,
};
use anyhow::{bail, ensure, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `cullproof tightness`.
#[derive(clap::Args, Debug, Clone)]
pub struct TightnessArgs {
    /// The scene: `hairball` (10,000 hair ribbons of 0.1-5 px^2), `interior` (a room of
    /// large triangles), `forest` (leaves, trees, a walking character) or a Wavefront
    /// FILE.obj (fitted into the view; camera, lens and motion set by the OBJ flags
    /// below, by default a seeded rigid motion).
    #[arg(long, default_value = "forest")]
    pub scene: String,
    /// The blur setting: `static` (no motion, pinhole), `blur` (the scene's motion and
    /// lens), `blur2` (twice the shutter time and lens radius) or `all`.
    #[arg(long, default_value = "all")]
    pub setting: String,
    /// Samples per pixel (16, as in Munkberg 2012 Table 2 and Wu 2013 Table 4.1).
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
    /// Tile size in pixels (default: each of 1, 2, 4 and 8).
    #[arg(long)]
    pub tile: Option<u32>,
    /// The sample pattern.
    #[arg(long, value_enum, default_value_t = PatternKind::Stratified)]
    pub pattern: PatternKind,
    /// Seed of the scene, the sample pattern and the certified subset.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output directory (created if missing): ste.md, ste.json, ste_vs_cost.svg.
    #[arg(long, default_value = "tightness-out")]
    pub out: PathBuf,
    /// Also write the JSON report to this file ("-": to standard output, and the table to
    /// standard error). An existing file is replaced only if it is an earlier tightness
    /// report.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Worker threads for the STE measurement (default: all cores; at most 4 per core).
    /// Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Screen size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "320x240")]
    pub size: String,
    /// Methods: `all` or comma-separated ids (see `cullproof methods`).
    #[arg(long, default_value = "all")]
    pub method: String,
    /// Tiles per setting and tile size whose ceiling is also certified (exact extents by
    /// the oracles' tile solver at resolution 1e-2, 2,000 boxes per extent), drawn at
    /// random from the traversed ones; `all` for every traversed tile (the exact
    /// ceiling of the whole scene: minutes, not seconds); 0 for none.
    #[arg(long, default_value = "16", value_parser = parse_certified)]
    pub certified: usize,
    /// Skip the cost timing (then there is no cost column and no chart).
    #[arg(long)]
    pub no_timing: bool,
    /// Timing rounds of the per-operation costs (run round robin over the methods; 1 to
    /// 1000): the cost is the median over the rounds, their range its error bar.
    #[arg(long, default_value_t = 5)]
    pub repeats: u32,
    /// Triangles per setting the per-operation costs are timed on (spread evenly over
    /// the scene; 1 to 100000).
    #[arg(long, default_value_t = 256)]
    pub cost_triangles: usize,
    #[command(flatten)]
    pub mesh: MeshControls,
}

/// The JSON report (`ste.json`).
#[derive(Clone, Debug, Serialize)]
pub struct TightnessReport {
    /// Always "cullproof-tightness" (lets a later run recognise its own file).
    pub kind: &'static str,
    pub scene: String,
    pub triangles: usize,
    pub width: u32,
    pub height: u32,
    /// Mean screen area of the rest-pose triangles on the screen (px^2).
    pub mean_area_px: f64,
    pub pattern: PatternKind,
    pub spp: u32,
    pub seed: u64,
    pub tiles: Vec<u32>,
    pub threads: usize,
    pub settings: Vec<SettingSummary>,
    /// STE per method, tile size and setting.
    pub rows: Vec<MethodRow>,
    /// The sample ceiling (an upper bound on the interval-only ceiling).
    pub ceiling: Vec<CeilingRow>,
    /// The certified ceiling on a random subset of tiles, or on every traversed tile
    /// (`certified_every_tile`): a lower bound on the ceiling there.
    pub certified: Vec<CertifiedRow>,
    /// The certified ceiling covers every traversed tile (`--certified all`).
    pub certified_every_tile: bool,
    /// The OBJ scene's camera, lens and motion (None for a procedural scene): with
    /// `scene_path` and `seed`, what reproduces the scene.
    pub mesh: Option<mesh::MeshSettings>,
    /// Tile size of the cost estimates.
    pub cost_tile: Option<u32>,
    /// The estimated cost per method and setting (relative to bbox on the same setting).
    pub cost: Vec<CostRow>,
    /// The timed per-operation costs behind `cost`.
    pub op_costs: Option<OpTable>,
    /// Wall time of the whole run (s).
    pub seconds: f64,
    pub notes: Vec<String>,
}

const KIND: &str = "cullproof-tightness";

/// `--certified`: a count of tiles, or `all` (every traversed tile, as `usize::MAX`).
fn parse_certified(s: &str) -> std::result::Result<usize, String> {
    match s.trim() {
        "all" => Ok(usize::MAX),
        t => t.parse::<usize>().map_err(|_| format!("`{s}`: expected a number of tiles or `all`")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .and_then(|(a, b)| Some((a.trim().parse::<u32>().ok()?, b.trim().parse::<u32>().ok()?)))
        .with_context(|| format!("--size {s}: expected WIDTHxHEIGHT in pixels, e.g. 320x240"))?;
    ensure!((1..=16384).contains(&w) && (1..=16384).contains(&h), "--size {s}: each side must be 1..16384 pixels");
    Ok((w, h))
}

fn parse_settings(s: &str) -> Result<Vec<Setting>> {
    if s == "all" {
        return Ok(Setting::ALL.to_vec());
    }
    let mut out = Vec::new();
    for part in s.split(',') {
        let x = Setting::ALL
            .into_iter()
            .find(|x| x.name() == part.trim())
            .with_context(|| format!("--setting {s}: `{part}` is not one of static, blur, blur2, all"))?;
        if !out.contains(&x) {
            out.push(x);
        }
    }
    Ok(out)
}

/// `--method`: the shared method-list parser ([`crate::cli::args::methods`]).
fn parse_methods(s: &str) -> Result<Vec<&'static dyn Method>> {
    crate::cli::args::methods("--method", s, false)
}

/// Refuse a scene whose clip-space triangles are not all finite in some setting (an
/// OBJ mesh too large for f32 once it is fitted into the view): the oracles judge only
/// finite numbers, and a method's answer for an infinite vertex means nothing.
fn check_scene_finite(scene: &Scene, settings: &[Setting], name: &str) -> Result<()> {
    for &s in settings {
        for (i, t) in scene.triangles(s).iter().enumerate() {
            if let Err(e) = t.validate() {
                bail!(
                    "--scene {name}: triangle {i} ({} setting) does not fit f32 clip space once the scene is \
                     placed in front of the camera: {e}; scale the mesh down",
                    s.name()
                );
            }
        }
    }
    Ok(())
}

/// The files written into `--out`.
const OUT_FILES: [&str; 3] = ["ste.md", "ste.json", "ste_vs_cost.svg"];

/// Refuse to replace a file that is not an earlier report of this command.
fn check_replaceable(p: &Path) -> Result<()> {
    if p.is_dir() {
        bail!("--json {}: is a directory", p.display());
    }
    if p.exists() {
        let text = std::fs::read_to_string(p).unwrap_or_default();
        let ours = serde_json::from_str::<serde_json::Value>(&text).ok().is_some_and(|v| v["kind"] == KIND);
        ensure!(
            ours,
            "--json {}: the file exists and is not an earlier tightness report; refusing to overwrite it",
            p.display()
        );
    }
    Ok(())
}

fn pct(x: Option<f64>) -> String {
    match x {
        None => "-".into(),
        Some(v) => {
            let p = 100.0 * v;
            if p >= 10.0 {
                format!("{p:.1}")
            } else {
                format!("{p:.2}")
            }
        }
    }
}

/// The tables (plain text, or Markdown when `md`).
pub fn render(r: &TightnessReport, md: bool) -> String {
    let settings: Vec<Setting> = r.settings.iter().map(|s| s.setting).collect();
    let cols: Vec<(Setting, u32)> = settings.iter().flat_map(|&s| r.tiles.iter().map(move |&t| (s, t))).collect();
    let methods: Vec<&MethodRow> = {
        let mut seen = Vec::<&MethodRow>::new();
        for row in &r.rows {
            if !seen.iter().any(|x| x.method == row.method) {
                seen.push(row);
            }
        }
        seen
    };
    let row_of = |m: &str, s: Setting, t: u32| r.rows.iter().find(|x| x.method == m && x.setting == s && x.tile == t);
    let head = |first: &str| -> String {
        if md {
            let mut h = format!("| {first} |");
            for (s, t) in &cols {
                h += &format!(" {} {t}x{t} |", s.name());
            }
            h += "\n|---|";
            h += &"---:|".repeat(cols.len());
            h + "\n"
        } else {
            let mut h = format!("{first:<26}");
            for (s, t) in &cols {
                h += &format!(" {:>10}", format!("{}:{t}", s.name()));
            }
            h + "\n"
        }
    };
    let line = |name: &str, cells: Vec<String>| -> String {
        if md {
            format!("| {name} | {} |\n", cells.join(" | "))
        } else {
            let mut l = format!("{name:<26}");
            for c in cells {
                l += &format!(" {c:>10}");
            }
            l + "\n"
        }
    };
    let mut s = String::new();
    let h1 = if md { "# " } else { "" };
    let h2 = if md { "## " } else { "" };
    s += &format!(
        "{h1}cullproof tightness: scene {} ({} triangles, mean area {:.1} px^2), {}x{} px, {} pattern, {} spp, seed {}\n\n",
        r.scene, r.triangles, r.mean_area_px, r.width, r.height, r.pattern.name(), r.spp, r.seed
    );
    s += &format!("{h2}STE (%) = covered samples let through / samples let through, per setting:tile size (px)\n\n");
    s += &head("method");
    for m in &methods {
        let name = format!("{}{}", m.method, if m.reconstruction { " (recon)" } else { "" });
        let cells = cols.iter().map(|&(st, t)| pct(row_of(&m.method, st, t).and_then(|x| x.ste))).collect();
        s += &line(&name, cells);
    }
    let ceil: Vec<String> = cols
        .iter()
        .map(|&(st, t)| pct(r.ceiling.iter().find(|c| c.setting == st && c.tile == t).and_then(|c| c.ste)))
        .collect();
    s += &line("sample ceiling*", ceil);
    s += "\n* sample ceiling: per tile, the samples inside the (u, v, t) box of the covered pattern samples (the \
          whole range in u, v or t where the triangle has no defocus or motion). An UPPER bound on the STE of the tightest interval-only tile test (the exact extents box contains it); \
          methods with per-sample tests can exceed it.\n";
    if md {
        // The counts behind the ratios (the terminal keeps to the ratios).
        s += &format!("\n{h2}Samples let through (tested; hits = tested and covered)\n\n");
        s += &head("method");
        for m in &methods {
            let cells = cols
                .iter()
                .map(|&(st, t)| {
                    row_of(&m.method, st, t)
                        .map(|x| format!("{} ({})", x.counts.tested, x.counts.hits))
                        .unwrap_or_default()
                })
                .collect();
            s += &line(&m.method, cells);
        }
        let ceil: Vec<String> = cols
            .iter()
            .map(|&(st, t)| {
                r.ceiling
                    .iter()
                    .find(|c| c.setting == st && c.tile == t)
                    .map(|c| format!("{} ({})", c.tested, c.covered))
                    .unwrap_or_default()
            })
            .collect();
        s += &line("sample ceiling", ceil);
    }
    // Missed samples.
    let any_missed = r.rows.iter().any(|x| x.counts.missed > 0);
    s += &format!("\n{h2}Covered samples culled (MISSED; 0 for a conservative method)\n\n");
    if any_missed {
        s += &head("method");
        for m in &methods {
            if r.rows.iter().any(|x| x.method == m.method && x.counts.missed > 0) {
                let cells = cols
                    .iter()
                    .map(|&(st, t)| row_of(&m.method, st, t).map(|x| x.counts.missed.to_string()).unwrap_or_default())
                    .collect();
                s += &line(&m.method, cells);
            }
        }
        let others: Vec<&str> = methods
            .iter()
            .filter(|m| !r.rows.iter().any(|x| x.method == m.method && x.counts.missed > 0))
            .map(|m| m.method.as_str())
            .collect();
        s += &format!("\nno covered sample missed by: {}\n", others.join(", "));
    } else {
        s += "none: every method let every covered sample through\n";
    }
    // Setting summaries.
    s += &format!("\n{h2}Samples per setting\n\n");
    let hdr = ["setting", "triangles", "whole-screen", "off-screen", "classified", "covered", "boundary", "exact"];
    if md {
        s += &format!("| {} |\n|---|{}\n", hdr.join(" | "), "---:|".repeat(hdr.len() - 1));
    } else {
        s += &format!(
            "{:<8} {:>9} {:>12} {:>10} {:>12} {:>10} {:>9} {:>6}\n",
            hdr[0], hdr[1], hdr[2], hdr[3], hdr[4], hdr[5], hdr[6], hdr[7]
        );
    }
    for x in &r.settings {
        let v = [
            x.setting.name().to_string(),
            x.triangles.to_string(),
            x.whole_screen.to_string(),
            x.off_screen.to_string(),
            x.samples_classified.to_string(),
            x.covered.to_string(),
            x.boundary.to_string(),
            x.exact_fallbacks.to_string(),
        ];
        if md {
            s += &format!("| {} |\n", v.join(" | "));
        } else {
            s += &format!(
                "{:<8} {:>9} {:>12} {:>10} {:>12} {:>10} {:>9} {:>6}\n",
                v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]
            );
        }
    }
    s += "whole-screen: triangles with a vertex at w <= 0, traversed over the whole screen; off-screen: skipped; \
          classified: samples judged by the exact oracle (boundary samples count as not covered; exact: decided \
          by exact dyadic arithmetic, where no floating-point filter could certify the signs).\n";
    // Disabled.
    let dis: Vec<String> = methods
        .iter()
        .filter_map(|m| {
            let per: Vec<String> = settings
                .iter()
                .filter_map(|&st| {
                    let x = r.rows.iter().find(|x| x.method == m.method && x.setting == st)?;
                    (x.disabled_triangles > 0).then(|| format!("{} {}", st.name(), x.disabled_triangles))
                })
                .collect();
            (!per.is_empty()).then(|| format!("{} ({})", m.method, per.join(", ")))
        })
        .collect();
    if !dis.is_empty() {
        s += &format!("\ntriangles where a method disabled itself (full bounds): {}\n", dis.join("; "));
    }
    // Certified.
    if !r.certified.is_empty() {
        let which = if r.certified_every_tile { "every traversed tile" } else { "a random subset of tiles" };
        s += &format!("\n{h2}Certified ceiling on {which} (TileSolver, resolution 1e-2)\n\n");
        let hdr = ["setting:tile", "tiles", "undecided", "covered", "STE lower (certified)", "STE upper (samples)"];
        if md {
            s += &format!("| {} |\n|---|{}\n", hdr.join(" | "), "---:|".repeat(hdr.len() - 1));
        } else {
            s += &format!("{:<12} {:>6} {:>9} {:>8} {:>22} {:>20}\n", hdr[0], hdr[1], hdr[2], hdr[3], hdr[4], hdr[5]);
        }
        for c in &r.certified {
            let v = [
                format!("{}:{}", c.setting.name(), c.tile),
                c.tiles.to_string(),
                c.undecided_tiles.to_string(),
                c.covered.to_string(),
                pct(c.ste_lower),
                pct(c.ste_upper),
            ];
            if md {
                s += &format!("| {} |\n", v.join(" | "));
            } else {
                s += &format!("{:<12} {:>6} {:>9} {:>8} {:>22} {:>20}\n", v[0], v[1], v[2], v[3], v[4], v[5]);
            }
        }
        s += "lower: samples inside the certified outer box of the exact (u, v, t) extents (contains the exact box); \
              upper: the sample ceiling of the same tiles. The true interval-only ceiling on these tiles lies between.\n";
    }
    // Cost.
    if !r.cost.is_empty() {
        let t = r.cost_tile.unwrap_or(0);
        s += &format!(
            "\n{h2}Estimated cost relative to bbox on the same setting ({t}x{t} tiles): median over {} timing \
             rounds [lowest, highest]; per-operation ns (setup / tile test / sample test)\n\n",
            r.op_costs.as_ref().map(|o| o.rounds).unwrap_or(0)
        );
        if md {
            s += "| method |";
            for st in &settings {
                s += &format!(" {} | {} ns |", st.name(), st.name());
            }
            s += &format!("\n|---|{}\n", "---:|".repeat(2 * settings.len()));
        } else {
            s += &format!("{:<26}", "method");
            for st in &settings {
                s += &format!(" {:>20} {:>18}", st.name(), "ns");
            }
            s += "\n";
        }
        for m in &methods {
            let mut cells: Vec<String> = Vec::new();
            for &st in &settings {
                match r.cost.iter().find(|x| x.method == m.method && x.setting == st) {
                    Some(x) => {
                        let e = x.relative;
                        cells.push(format!("{:.2} [{:.2}, {:.2}]", e.median, e.lo, e.hi));
                        cells.push(format!("{:.0}/{:.0}/{:.1}", x.setup_ns, x.tile_ns, x.sample_ns));
                    }
                    None => cells.extend(["-".to_string(), "-".to_string()]),
                }
            }
            if md {
                s += &format!("| {} | {} |\n", m.method, cells.join(" | "));
            } else {
                s += &format!("{:<26}", m.method);
                for pair in cells.chunks(2) {
                    s += &format!(" {:>20} {:>18}", pair[0], pair[1]);
                }
                s += "\n";
            }
        }
        s += "cost: counts of setups, tile tests, sample tests and samples let through (exact, from the STE \
              measurement) times per-operation costs timed on a subset of the triangles (work where a method \
              disabled itself is charged at bbox's costs); ns: the method's own median per-operation costs \
              (NaN: enabled on no timed triangle).\n";
    }
    s += &price_of_safety(r, &cols, md);
    for n in &r.notes {
        s += &format!("\nnote: {n}");
    }
    s += &format!("\n\nwall time {:.1} s on {} thread(s)\n", r.seconds, r.threads);
    s
}

/// The price of safety: for every method run with its `-safe` variant, the STE the
/// variant loses (points and share of the original's STE) per setting and tile size,
/// and the time it adds where both were timed. Empty when no pair was run.
fn price_of_safety(r: &TightnessReport, cols: &[(Setting, u32)], md: bool) -> String {
    let mut pairs: Vec<(&str, &str)> = Vec::new();
    for row in &r.rows {
        if let Some(base) = row.method.strip_suffix("-safe") {
            if r.rows.iter().any(|x| x.method == base) && !pairs.iter().any(|p| p.1 == row.method) {
                pairs.push((base, row.method.as_str()));
            }
        }
    }
    if pairs.is_empty() {
        return String::new();
    }
    let ste = |m: &str, st: Setting, t: u32| {
        r.rows.iter().find(|x| x.method == m && x.setting == st && x.tile == t).and_then(|x| x.ste)
    };
    let time =
        |m: &str, st: Setting| r.cost.iter().find(|x| x.method == m && x.setting == st).map(|x| x.seconds.median);
    let settings: Vec<Setting> = r.settings.iter().map(|x| x.setting).collect();
    let mut s = format!(
        "\n{}The price of safety: STE lost by each -safe variant, points (share of the original's STE), per \
         setting:tile size; time added where timed\n\n",
        if md { "## " } else { "" }
    );
    let mut hdr: Vec<String> = vec!["method".into()];
    hdr.extend(cols.iter().map(|(st, t)| format!("{}:{t}", st.name())));
    hdr.extend(
        settings
            .iter()
            .filter(|&&st| pairs.iter().any(|p| time(p.0, st).is_some()))
            .map(|st| format!("time {}", st.name())),
    );
    let fmt_row = |cells: &[String]| -> String {
        if md {
            format!("| {} |\n", cells.join(" | "))
        } else {
            let mut l = format!("{:<26}", cells[0]);
            for c in &cells[1..] {
                l += &format!(" {c:>16}");
            }
            l + "\n"
        }
    };
    s += &fmt_row(&hdr);
    if md {
        s += &format!("|---|{}\n", "---:|".repeat(hdr.len() - 1));
    }
    for (base, safe) in pairs {
        let mut cells = vec![safe.to_string()];
        for &(st, t) in cols {
            cells.push(match (ste(base, st, t), ste(safe, st, t)) {
                (Some(a), Some(b)) if a > 0.0 => {
                    format!("{:.3} ({:.1}%)", 100.0 * (a - b), 100.0 * (a - b) / a)
                }
                _ => "-".into(),
            });
        }
        for &st in &settings {
            if let (Some(a), Some(b)) = (time(base, st), time(safe, st)) {
                cells.push(format!("{:+.1}%", 100.0 * (b - a) / a));
            } else if hdr.iter().any(|h| *h == format!("time {}", st.name())) {
                cells.push("-".into());
            }
        }
        s += &fmt_row(&cells);
    }
    s += "A negative loss means the variant's STE is higher: the original culls covered samples there (see \
          MISSED), which costs it hits, or the variant's correction lets fewer samples through. Time: the \
          estimated cost's median (see the cost table for its range).\n";
    s
}

/// Run `cullproof tightness`.
pub fn run_cli(args: &TightnessArgs) -> Result<()> {
    let start = Instant::now();
    ensure!((1..=1024).contains(&args.spp), "--spp {}: must be 1..1024", args.spp);
    let tiles = match args.tile {
        Some(t) => {
            ensure!((1..=256).contains(&t), "--tile {t}: the tile size must be 1..256 pixels");
            vec![t]
        }
        None => vec![1, 2, 4, 8],
    };
    let settings = parse_settings(&args.setting)?;
    let methods = parse_methods(&args.method)?;
    let (w, h) = parse_size(&args.size)?;
    let jobs = crate::cli::args::jobs(args.jobs)?;
    ensure!((1..=1000).contains(&args.repeats), "--repeats {}: must be 1..1000", args.repeats);
    ensure!(
        (1..=100_000).contains(&args.cost_triangles),
        "--cost-triangles {}: must be 1..100000",
        args.cost_triangles
    );
    // The whole screen's pattern is held once (20 bytes a sample).
    let table_len = w as u64 * h as u64 * args.spp as u64;
    ensure!(
        table_len <= 64 << 20,
        "--size {} with --spp {}: the sample table would hold {table_len} samples (over 64 Mi); use a smaller \
         screen or spp",
        args.size,
        args.spp
    );
    if args.out.exists() && !args.out.is_dir() {
        bail!("--out {}: exists and is not a directory; refusing to write into it", args.out.display());
    }
    // Every output is checked before the run (see crate::io::output), so none fails after it.
    crate::io::output::dir("--out", &args.out)?;
    for name in OUT_FILES {
        let p = args.out.join(name);
        if p.exists() {
            crate::io::output::file("--out", &p)?;
        }
    }
    if let Some(j) = &args.json {
        if j.as_os_str() != "-" {
            check_replaceable(j)?;
            crate::io::output::file("--json", j)?;
        }
    }
    // The bar runs from the start: reading a large OBJ file takes time too (counted in
    // bytes of the file while it is read).
    let pb = ProgressBar::new(0);
    pb.set_style(
        ProgressStyle::with_template("{bar:40} {bytes}/{total_bytes} {msg} {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb.set_message(format!("reading the scene {}", args.scene));
    pb.enable_steady_tick(std::time::Duration::from_millis(200));
    let is_obj = args.scene.to_ascii_lowercase().ends_with(".obj");
    let loaded = (|| -> Result<_> {
        let (scene, mesh) = if is_obj {
            let (s, m) = mesh::from_obj_with_progress(Path::new(&args.scene), args.seed, w, h, &args.mesh, &pb)?;
            (s, Some(m))
        } else {
            args.mesh.refuse_for(&args.scene)?;
            (scene::by_name(&args.scene, args.seed, w, h)?, None)
        };
        check_scene_finite(&scene, &settings, &args.scene)?;
        Ok((scene, mesh))
    })();
    let (scene, mesh) = match loaded {
        Ok(x) => x,
        Err(e) => {
            pb.finish_and_clear();
            return Err(e);
        }
    };
    pb.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb.set_position(0);
    let pattern = Pattern::new(args.pattern, args.spp, args.seed);
    let mut cfg = Config::new(tiles.clone(), pattern);
    cfg.certified_tiles = args.certified;
    cfg.seed = args.seed;
    let threads = jobs.unwrap_or_else(rayon::current_num_threads).max(1);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().context("building the thread pool")?;
    let cost_tile = if tiles.contains(&2) { 2 } else { tiles[0] };
    let repeats = args.repeats;
    let total = (scene.triangle_count() * settings.len()) as u64
        + if args.no_timing { 0 } else { (methods.len() * settings.len()) as u64 * repeats as u64 };
    pb.set_length(total);
    pb.set_message("sample pattern");
    let table = pool.install(|| SampleTable::new(&pattern, w, h));
    pb.set_message("triangles (STE)");
    let m = pool.install(|| measure_with(&scene, &table, &methods, &settings, &cfg, &pb));
    let ops = (!args.no_timing).then(|| {
        pb.set_message("per-operation costs");
        pool.install(|| {
            cost::time_ops(&scene, &table, &methods, &settings, cost_tile, repeats, args.cost_triangles, &pb)
        })
    });
    pb.finish_and_clear();
    let costs = ops.as_ref().map(|o| cost::costs(&m.rows, o, cost_tile)).unwrap_or_default();
    let mut notes = vec![
        "a method's STE counts only covered samples it let through (hits / tested); MISSED counts covered samples \
         it culled"
            .to_string(),
        "depth intervals (z^) are not applied: they cull against a depth buffer, not coverage".to_string(),
    ];
    if let Some(ms) = &mesh {
        notes.push(format!("{}: {}", args.scene, ms.describe()));
    }
    let report = TightnessReport {
        kind: KIND,
        scene: scene.name.clone(),
        triangles: scene.triangle_count(),
        width: w,
        height: h,
        mean_area_px: scene.mean_area_px(),
        pattern: args.pattern,
        spp: pattern.spp,
        seed: args.seed,
        tiles,
        threads,
        settings: m.settings,
        rows: m.rows,
        ceiling: m.ceiling,
        certified: m.certified,
        certified_every_tile: args.certified == usize::MAX,
        mesh,
        cost_tile: (!costs.is_empty()).then_some(cost_tile),
        cost: costs,
        op_costs: ops,
        seconds: start.elapsed().as_secs_f64(),
        notes,
    };
    let text = render(&report, false);
    // With `--json -` standard output carries the JSON alone; the table goes to stderr.
    if args.json.as_ref().is_some_and(|j| j.as_os_str() == "-") {
        eprint!("{text}");
    } else {
        print!("{text}");
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let json = serde_json::to_string_pretty(&report)?;
    let write = |name: &str, body: &str| -> Result<PathBuf> {
        let p = args.out.join(name);
        crate::io::output::write(&p, body)?;
        Ok(p)
    };
    let mut written = vec![write("ste.md", &render(&report, true))?, write("ste.json", &json)?];
    if !report.cost.is_empty() {
        let panels = chart::points(&report.rows, &report.cost, cost_tile);
        let ids: Vec<String> = methods.iter().map(|m| m.info().id.to_string()).collect();
        let title = format!(
            "STE vs cost, {} ({}x{}, {} spp, {}x{} tiles)",
            report.scene, w, h, report.spp, cost_tile, cost_tile
        );
        written.push(write("ste_vs_cost.svg", &chart::svg(&panels, &ids, &title)?)?);
    } else if args.out.join("ste_vs_cost.svg").exists() {
        eprintln!("note: --no-timing: {} is from an earlier run", args.out.join("ste_vs_cost.svg").display());
    }
    if let Some(j) = &args.json {
        if j.as_os_str() == "-" {
            println!("{json}");
        } else {
            crate::io::output::write(j, &json)?;
            written.push(j.clone());
        }
    }
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    eprintln!("wrote {}", names.join(", "));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tools::tightness::mesh::MeshControls;
    use crate::tools::tightness::pattern::PatternKind;

    #[test]
    fn arguments_are_checked_by_name() {
        assert_eq!(parse_size("64x48").unwrap(), (64, 48));
        assert!(parse_size("64").unwrap_err().to_string().contains("--size"));
        assert_eq!(parse_settings("all").unwrap().len(), 3);
        assert!(parse_settings("blurry").unwrap_err().to_string().contains("blurry"));
        assert!(parse_methods("bbox,nope").err().unwrap().to_string().contains("nope"));
    }

    #[test]
    fn an_existing_file_is_never_replaced_silently() {
        let dir = std::env::temp_dir().join(format!("cullproof-tight-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let user = dir.join("notes.json");
        std::fs::write(&user, "{\"mine\": 1}").unwrap();
        assert!(check_replaceable(&user).unwrap_err().to_string().contains("refusing"));
        let ours = dir.join("old.json");
        std::fs::write(&ours, format!("{{\"kind\": \"{KIND}\"}}")).unwrap();
        assert!(check_replaceable(&ours).is_ok());
        // --out pointing at a file is refused before any work.
        let args = TightnessArgs {
            scene: "forest".into(),
            setting: "static".into(),
            spp: 1,
            tile: Some(8),
            pattern: PatternKind::Stratified,
            seed: 1,
            out: user.clone(),
            json: None,
            jobs: Some(1),
            size: "16x16".into(),
            method: "bbox".into(),
            certified: 0,
            no_timing: true,
            repeats: 1,
            cost_triangles: 16,
            mesh: MeshControls::default(),
        };
        let e = run_cli(&args).unwrap_err().to_string();
        assert!(e.contains("not a directory"), "{e}");
        assert_eq!(std::fs::read_to_string(&user).unwrap(), "{\"mine\": 1}");
    }
}
