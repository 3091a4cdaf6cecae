//! A bug in your own bound found, shrunk, written, explained and, after the fix,
//! replayed: through library calls only.
//!
//! ```sh
//! cargo run --release --example find_and_replay
//! ```
//!
//! The bound: the screen box of the moving triangle over the shutter ends, computed in
//! f64 from the f32 inputs and rounded outward to f32. Its first version forgets the
//! lens (the circle of confusion does not widen the box), so on defocused triangles it
//! culls tiles that out-of-focus samples cover. The search finds such a case, shrinks
//! it and writes it as a case file; `explain` puts it in words; the fixed version
//! (the box widened by each vertex's CoC) is then replayed on the file and comes out
//! fixed.

use cullproof::counterexamples::{explain, replay, Search};
use cullproof::{Dims, Method, MethodInfo, Outputs, Prepared, Regime, Tile, TileBounds, TileResult, Triangle};
use std::path::{Path, PathBuf};

/// The bound; `lens` false is the first version, which forgets the lens.
pub struct ScreenBox {
    pub lens: bool,
}

/// Its per-triangle state: `[x min, x max, y min, y max]`, or None (no bound).
struct Prep(Option<[f32; 4]>);

static INFO: MethodInfo = MethodInfo {
    id: "screen-box",
    source: "example: screen box over the shutter ends (and the lens, once fixed), f64 rounded outward to f32",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: false, per_sample: false },
};

impl Method for ScreenBox {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let ends = [(&tri.q, &tri.c0), (&tri.r, &tri.c1)];
        if ends.iter().any(|(p, _)| p.iter().any(|v| v[3] <= 0.0 || v[3].is_nan())) {
            return Box::new(Prep(None));
        }
        let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for (p, c) in ends {
            for i in 0..3 {
                let w = p[i][3] as f64;
                let coc = if self.lens { c[i] as f64 } else { 0.0 };
                for (axis, shear) in [(0, coc), (1, tri.k as f64 * coc)] {
                    for s in [-shear, shear] {
                        let q = (p[i][axis] as f64 + s) / w;
                        b[2 * axis] = b[2 * axis].min(q);
                        b[2 * axis + 1] = b[2 * axis + 1].max(q);
                    }
                }
            }
        }
        if b.iter().any(|x| !x.is_finite()) {
            return Box::new(Prep(None));
        }
        // Outward to f32: one f32 step beyond the f64 value on each side.
        let down = |x: f64| (x as f32).next_down();
        let up = |x: f64| (x as f32).next_up();
        Box::new(Prep(Some([down(b[0]), up(b[1]), down(b[2]), up(b[3])])))
    }
}

impl Prepared for Prep {
    fn tile(&self, t: &Tile) -> TileResult {
        match self.0 {
            Some([x0, x1, y0, y1]) if t.x1 < x0 || t.x0 > x1 || t.y1 < y0 || t.y0 > y1 => TileResult::Empty,
            _ => TileResult::Bounds(TileBounds::full()),
        }
    }
}

/// What the walk through gives.
pub struct Outcome {
    /// The case file written for the first finding.
    pub file: PathBuf,
    /// Shrinking steps kept for it.
    pub shrunk: Vec<String>,
    /// `explain` of the file, under the first version.
    pub explained: String,
    /// `replay` of the file under the first version, then under the fixed one.
    pub before: String,
    pub after: String,
}

/// Search the first version on defocused triangles for `seconds` (one finding is
/// enough), write it under `dir`, explain it, and replay it before and after the fix.
pub fn walk(dir: &Path, seconds: f64) -> anyhow::Result<Outcome> {
    let report = Search::new(ScreenBox { lens: false })
        .regimes(&[Regime::Defocus])
        .seconds(seconds)
        .max(1)
        .write_to(dir)
        .run()?;
    let first = report.found.first().ok_or_else(|| anyhow::anyhow!("no violation found in {seconds} s"))?;
    let file = PathBuf::from(first.file.as_deref().ok_or_else(|| anyhow::anyhow!("the finding was not written"))?);
    Ok(Outcome {
        explained: explain(&file, ScreenBox { lens: false })?,
        before: replay(&file, ScreenBox { lens: false })?.outcome.to_string(),
        after: replay(&file, ScreenBox { lens: true })?.outcome.to_string(),
        shrunk: first.shrink_steps.clone(),
        file,
    })
}

#[allow(dead_code)]
fn main() -> anyhow::Result<()> {
    let dir = std::env::temp_dir().join(format!("cullproof-example-{}", std::process::id()));
    let o = walk(&dir, 30.0)?;
    println!("found and written: {} (shrunk: {})", o.file.display(), o.shrunk.join(", "));
    print!("{}", o.explained);
    println!("replayed under the first version: {}", o.before);
    println!("replayed under the fixed version: {}", o.after);
    Ok(())
}
