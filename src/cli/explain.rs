//! `cullproof explain`: one case file explained (the method's answer, the exact extents over the tile,
//! the witness); with `--svg`, a picture of the sample space through the witness.

use anyhow::{Context, Result};
use std::path::PathBuf;

/// Arguments of `cullproof explain`.
#[derive(clap::Args)]
pub struct ExplainArgs {
    /// The case file, or a case id: HASH or METHOD/HASH (the name `search` gives the
    /// file), looked up under the corpus's cases/ (see --corpus).
    case: PathBuf,
    #[command(flatten)]
    corpus: crate::cli::args::CorpusFlag,
    /// Write the picture here (refuses to overwrite an existing file).
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Flags given here explain the case under another sample set, snap or viewport
    /// than the one the file records.
    #[command(flatten)]
    sample: crate::cli::args::SampleFlags,
}

/// Run `cullproof explain`.
pub fn run(args: ExplainArgs) -> Result<()> {
    let ExplainArgs { case, corpus, svg, sample } = args;
    if let Some(out) = &svg {
        anyhow::ensure!(
            std::fs::symlink_metadata(out).is_err(),
            "--svg {}: the file exists (an existing file is never overwritten)",
            out.display()
        );
        crate::io::output::file("--svg", out)?;
    }
    let case = crate::gate::locate::case_path(&case, &corpus.dir(crate::gate::locate::in_checkout())?)?;
    let mut cf = crate::search::CaseFile::load(&case)?;
    let over = sample.parse()?;
    cf.samples = over.samples.unwrap_or(cf.samples);
    cf.snap = over.snap.or(cf.snap);
    cf.viewport = over.viewport.or(cf.viewport);
    print!("{}", crate::search::describe(&cf));
    if let Some(out) = &svg {
        let m = crate::search::method_of(&cf.method).expect("checked at load");
        let w = cf.witness.as_ref().map(|w| w.sample).unwrap_or_else(|| {
            let (x, y) = cf.tile.center();
            [x as f64, y as f64, 0.0, 0.0, 0.5]
        });
        let caption = match &cf.witness {
            Some(w) => format!("{} culls the witness by {:.3e}", w.bound, w.margin),
            None => "no witness".into(),
        };
        // Under snapping the picture is of the snapped triangle the method saw.
        let (seen, _) = crate::cases::place::judged_triangles(cf.snap, &cf.case)
            .map_err(|e| anyhow::anyhow!("{}: {e}", case.display()))?;
        let shown = if cf.snap.is_some() { crate::Case { triangle: seen, lens: None } } else { cf.case };
        let text = crate::search::explain::svg(&shown, &cf.tile, m, w, &caption)?;
        let mut f = std::fs::OpenOptions::new().write(true).create_new(true).open(out).with_context(|| {
            format!("--svg {}: cannot create (an existing file is never overwritten)", out.display())
        })?;
        std::io::Write::write_all(&mut f, text.as_bytes()).with_context(|| format!("writing {}", out.display()))?;
        println!("wrote {}", out.display());
    }
    Ok(())
}
