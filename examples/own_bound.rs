//! A culling bound of your own, gated end to end.
//!
//! ```sh
//! cargo run --release --example own_bound
//! ```
//!
//! The bound: the screen box of the moving, defocused triangle over the lens corners and
//! the shutter ends, computed in f64 from the f32 inputs and rounded outward to f32
//! (an f64 corner value errs by at most two f64 roundings, far below the f32 step taken
//! outward), disabled when a vertex has w <= 0 at a shutter end. The gate should prove it
//! conservative on every case.

use cullproof::{Gate, Method, MethodInfo, MethodVerdict, Outputs, Prepared, Tile, TileBounds, TileResult, Triangle};

/// The method: nothing to configure.
struct WideBox;

/// Its per-triangle state: `[x min, x max, y min, y max]`, or None (no bound).
struct Prep(Option<[f32; 4]>);

static INFO: MethodInfo = MethodInfo {
    id: "wide-box",
    source: "example: screen box over lens corners and shutter ends, f64 rounded outward to f32",
    reconstruction: false,
    dims: &[cullproof::Dims::Static, cullproof::Dims::Motion, cullproof::Dims::Defocus, cullproof::Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: false, per_sample: false },
};

impl Method for WideBox {
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
                for (axis, shear) in [(0, c[i] as f64), (1, tri.k as f64 * c[i] as f64)] {
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

fn main() {
    let report = Gate::new().method(WideBox).cases(1920).seed(1).run();
    print!("{}", report.render());
    let mine = report.method("wide-box").expect("it ran");
    println!(
        "\nwide-box: {} cases, {} proven, {} violated, {} unproven: {:?}",
        mine.cases, mine.proven, mine.violated, mine.unproven, mine.verdict
    );
    for c in &mine.counterexamples {
        println!("  {:?}: {:?} at {:?} in {:?}", c.regime, c.bound, c.sample, c.tile);
    }
    if mine.verdict != MethodVerdict::Proven {
        std::process::exit(1);
    }
}
