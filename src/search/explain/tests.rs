//! The unit tests of `explain` (a file of their own to keep the method's file to its method).

use super::*;
use crate::bounds::{by_id, MethodInfo, Outputs, Prepared, SampleBox, SampleConstraint};
use crate::model::{ThinLens, Triangle};
use crate::Interval;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn static_case() -> Case {
    let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [16.0, 0.0, 0.5, 1.0], [0.0, 16.0, 0.5, 1.0]]);
    Case { triangle: tri, lens: None }
}

/// A thin-lens triangle: defocus only (static), or defocus and motion.
fn lens_case(moving: bool) -> Case {
    let cam = ThinLens { fx: 50.0, fy: 60.0, cx: 0.0, cy: 0.0, radius: 0.3, focus: 4.0, near: 0.1, far: 100.0 };
    let q = [[-1.0, -1.0, 2.0], [1.0, -0.5, 6.0], [0.0, 1.0, 3.0]];
    let r = if moving { [[-0.5, -1.0, 3.0], [1.5, 0.0, 5.0], [0.5, 1.5, 2.5]] } else { q };
    Case { triangle: cam.triangle(q, r), lens: Some(cam) }
}

/// A thin-lens triangle whose hypotenuse sweeps 40 px across the tile at (-4, -4)
/// with a blur of about 8 px (moving), or stands still with the same blur where the
/// sweep is half way.
fn sweep_case(moving: bool) -> Case {
    let cam = ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 3.0, near: 0.1, far: 100.0 };
    let at = |p: [f32; 3], dx: f32| [p[0] + dx, p[1], p[2]];
    let q = [[-0.5, -0.5, 2.0], [0.1, -0.5, 2.0], [-0.5, 0.1, 2.0]];
    let (q, r) = if moving { (q, q.map(|p| at(p, 0.8))) } else { (q.map(|p| at(p, 0.4)), q.map(|p| at(p, 0.4))) };
    Case { triangle: cam.triangle(q, r), lens: Some(cam) }
}

fn motion_case() -> Case {
    let mut tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [10.0, 0.0, 0.5, 1.0], [0.0, 10.0, 0.5, 1.0]]);
    for i in 0..3 {
        tri.r[i][0] += 8.0;
    }
    Case { triangle: tri, lens: None }
}

/// An f32 sample in the tile that the case covers (interior), drawn at random.
fn interior_in(case: &Case, tile: &Tile, seed: u64) -> [f64; 5] {
    let tri = case.triangle.to_oracle();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..10_000)
        .map(|_| crate::bounds::testkit::random_sample(&mut rng, tile).to_oracle())
        .find(|&s| oracles::classify(&tri, s) == Coverage::Interior)
        .expect("an interior sample in the tile")
}

fn is_interior(case: &Case, w: [f64; 5]) -> bool {
    oracles::classify(&case.triangle.to_oracle(), w) == Coverage::Interior
}

/// The interior fraction of the grid against uniform random samples of the slice,
/// each classified directly.
fn check_fraction(case: &Case, slice: &Slice, seed: u64) -> f64 {
    let tri = case.triangle.to_oracle();
    let g = grid(&tri, None, slice, GRID);
    let frac = g.count(Coverage::Interior) as f64 / (GRID * GRID) as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = 4000;
    let mut hits = 0;
    for _ in 0..n {
        let mut s = slice.at.map(|c| c as f64);
        for k in 0..2 {
            let [a, b] = slice.ranges[k];
            s[slice.axes[k] as usize] = rng.gen_range(a..b) as f32 as f64;
        }
        hits += (oracles::classify(&tri, s) == Coverage::Interior) as usize;
    }
    let direct = hits as f64 / n as f64;
    assert!(frac > 0.0, "no covered cell in {slice:?}");
    assert!((frac - direct).abs() < 0.04, "grid {frac} vs random {direct} in {slice:?}");
    frac
}

fn assert_svg(s: &str) {
    assert!(s.starts_with("<svg"), "{}", &s[..s.len().min(200)]);
    assert!(s.trim_end().ends_with("</svg>"));
    assert_eq!(s.matches("<svg").count(), 1);
}

#[test]
fn static_case_draws_one_xy_panel_with_covered_cells() {
    let case = static_case();
    let tile = Tile::square(2.0, 2.0, 8.0);
    let w = [4.0, 5.0, 0.0, 0.0, 0.5];
    assert!(is_interior(&case, w));
    let s = svg(&case, &tile, by_id("bbox").unwrap(), w, "a static <check> & caption").unwrap();
    assert_svg(&s);
    assert!(s.contains("bbox"));
    assert!(s.contains("a static &lt;check&gt; &amp; caption"), "caption escaped and present");
    assert!(s.contains("(x, y) at u = 0, v = 0, t = 0.5"));
    assert!(!s.contains("tile culled"));
    assert!(s.contains("exactly interior; kept by the method"));
    let sl = slices(case.triangle.dims(), &tile, w);
    assert_eq!(sl.len(), 1);
    let f = check_fraction(&case, &sl[0], 1);
    assert!((f - 0.875).abs() < 0.02, "x + y < 16 over [2, 10]^2 is 7/8 of the tile: {f}");
    // The tile's upper right corner is outside the hypotenuse x + y = 16.
    let g = grid(&case.triangle.to_oracle(), None, &sl[0], GRID);
    assert_eq!(g.cover[GRID * GRID - 1], Coverage::Outside);
    assert_eq!(g.cover[0], Coverage::Interior);
}

#[test]
fn both_draws_two_panels_and_defocus_one() {
    let case = sweep_case(true);
    assert_eq!(case.triangle.dims(), Dims::Both);
    let tile = Tile::square(-4.0, -4.0, 4.0);
    let w = interior_in(&case, &tile, 7);
    let t0 = std::time::Instant::now();
    let s = svg(&case, &tile, by_id("lb2011").unwrap(), w, "both").unwrap();
    let took = t0.elapsed();
    eprintln!("a two-panel picture took {took:?}");
    assert!(took.as_secs_f64() < 5.0, "{took:?}");
    assert_svg(&s);
    assert!(s.contains("lb2011") && s.contains("(u, t) at") && s.contains("(v, t) at"));
    for sl in slices(Dims::Both, &tile, w) {
        let f = check_fraction(&case, &sl, 2);
        assert!(f > 0.05 && f < 0.95, "the sweep covers part of each slice: {f}");
    }

    let case = sweep_case(false);
    assert_eq!(case.triangle.dims(), Dims::Defocus);
    let w = interior_in(&case, &tile, 8);
    let s = svg(&case, &tile, by_id("wu2013").unwrap(), w, "defocus").unwrap();
    assert_svg(&s);
    assert!(s.contains("(u, v) at x = ") && !s.contains("(u, t) at"));
    let f = check_fraction(&case, &slices(Dims::Defocus, &tile, w)[0], 4);
    assert!(f > 0.05 && f < 0.95, "the blur covers part of the lens: {f}");
}

#[test]
fn motion_draws_an_xt_panel() {
    let case = motion_case();
    let tile = Tile::square(8.0, 1.0, 4.0);
    let w = [9.0, 2.0, 0.0, 0.0, 0.6];
    assert!(is_interior(&case, w));
    let s = svg(&case, &tile, by_id("la2011").unwrap(), w, "motion").unwrap();
    assert_svg(&s);
    assert!(s.contains("(x, t) at y = 2, u = 0, v = 0"));
    let sl = slices(Dims::Motion, &tile, w);
    assert_eq!(sl[0].ranges, [[8.0, 12.0], [0.0, 1.0]]);
    let f = check_fraction(&case, &sl[0], 3);
    assert!(f > 0.05 && f < 0.95, "the motion covers part of the (x, t) slice: {f}");
}

#[test]
fn culled_tile_is_marked() {
    let case = static_case();
    let tile = Tile::square(100.0, 100.0, 4.0);
    let s = svg(&case, &tile, by_id("bbox").unwrap(), [101.0, 101.0, 0.0, 0.0, 0.0], "far").unwrap();
    assert_svg(&s);
    assert!(s.contains("tile culled"));
    assert!(s.contains("answer: tile culled (empty)"));
    assert!(s.contains("exactly outside; culled by: tile culled"));
}

/// A test-only method: no tile cull, t^ = [0, 0.5], and two constraints: `u - 0.25`
/// (culls u < 0.25) and one that is NaN for t > 0.5 and 1 elsewhere.
struct Fake;
#[derive(Debug)]
struct ULine;
#[derive(Debug)]
struct NanLate;
impl SampleConstraint for ULine {
    fn name(&self) -> String {
        "u line".into()
    }
    fn eval(&self, s: &Sample) -> f32 {
        s.u - 0.25
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        b.u - Interval::point(0.25)
    }
}
impl SampleConstraint for NanLate {
    fn name(&self) -> String {
        "nan late".into()
    }
    fn eval(&self, s: &Sample) -> f32 {
        if s.t > 0.5 {
            f32::NAN
        } else {
            1.0
        }
    }
    fn eval_box(&self, _: &SampleBox) -> Interval {
        Interval::point(1.0)
    }
}
struct FakePrep;
impl Prepared for FakePrep {
    fn tile(&self, _: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        b.t = [0.0, 0.5];
        b.z = Some([0.0, 0.0]);
        b.constraints = vec![Box::new(ULine), Box::new(NanLate)];
        TileResult::Bounds(b)
    }
}
static FAKE_INFO: MethodInfo = MethodInfo {
    id: "fake-test-method",
    source: "explain tests",
    reconstruction: false,
    dims: &[Dims::Both],
    outputs: Outputs { tile_reject: false, lens: false, time: true, depth: true, per_sample: true },
};
impl Method for Fake {
    fn info(&self) -> &'static MethodInfo {
        &FAKE_INFO
    }
    fn setup(&self, _: &Triangle) -> Box<dyn Prepared> {
        Box::new(FakePrep)
    }
}
static FAKE: &dyn Method = &Fake;

/// A test-only method whose setup panics.
struct Panicky;
impl Method for Panicky {
    fn info(&self) -> &'static MethodInfo {
        &FAKE_INFO
    }
    fn setup(&self, _: &Triangle) -> Box<dyn Prepared> {
        panic!("setup of a broken method")
    }
}

#[test]
fn constraint_overlay_follows_eval_and_ignores_nan() {
    let case = lens_case(true);
    let tile = Tile::square(-4.0, -4.0, 4.0);
    let w = [-2.0, -2.0, 0.0, 0.1, 0.7];
    let sl = slices(Dims::Both, &tile, w);
    let b = match FakePrep.tile(&tile) {
        TileResult::Bounds(b) => b,
        TileResult::Empty => unreachable!(),
    };
    let tri = case.triangle.to_oracle();
    // (u, t) panel: culled exactly where u < 0.25 (NaN for t > 0.5 culls nothing).
    let g = grid(&tri, Some(&b), &sl[0], GRID);
    for j in 0..GRID {
        for i in 0..GRID {
            let s = sl[0].cell_centre(GRID, i, j);
            assert_eq!(g.culled[j * GRID + i], s.u < 0.25, "cell {i} {j} {s:?}");
        }
    }
    // 0.25 sits on the edge between cells 74 and 75 of [-1, 1] / 120.
    assert_eq!(g.culled_count(), 75 * GRID);
    // z^ = [0, 0] holds no hit depth: every interior cell is marked.
    let interior = g.count(Coverage::Interior);
    assert!(interior > 0);
    assert_eq!(g.depth_out.iter().filter(|&&d| d).count(), interior);

    let s = svg(&case, &tile, FAKE, w, "fake").unwrap();
    assert_svg(&s);
    // The witness has u = 0 < 0.25 and t = 0.7 outside t^; the NaN constraint is silent.
    assert!(s.contains("t^ [0, 0.5]; "), "{s}");
    assert!(s.contains("u line = -2.5e-1"));
    assert!(!s.contains("nan late ="));
}

#[test]
fn bad_input_is_an_error_and_odd_geometry_draws() {
    let case = static_case();
    let tile = Tile::square(0.0, 0.0, 4.0);
    let m = by_id("bbox").unwrap();
    assert!(svg(&case, &tile, m, [f64::NAN, 0.0, 0.0, 0.0, 0.0], "").is_err());
    assert!(svg(&case, &tile, m, [1.0e300, 0.0, 0.0, 0.0, 0.0], "").is_err());
    let e = svg(&case, &tile, &Panicky, [1.0, 1.0, 0.0, 0.0, 0.0], "").unwrap_err().to_string();
    assert!(e.contains("panic") && e.contains("setup of a broken method"), "{e}");
    assert!(svg(&case, &Tile { x0: 1.0, y0: 0.0, x1: 1.0, y1: 1.0 }, m, [0.0; 5], "").is_err());
    let mut bad = case;
    bad.triangle.q[0][0] = f32::INFINITY;
    assert!(svg(&bad, &tile, m, [0.0; 5], "").is_err());

    // Degenerate, behind the lens, far from the origin, witness outside the panel:
    // pictures all the same, for every method.
    let flat = Case { triangle: Triangle::fixed([[0.0, 0.0, 0.0, 0.0]; 3]), lens: None };
    let mut behind = lens_case(true);
    behind.triangle.r[2][3] = -1.0;
    behind.triangle.q[1][3] = 0.0;
    behind.lens = None; // the CoC no longer follows the lens: the per-vertex variant
    let far = Triangle::fixed([[1.0e7, 0.0, 0.5, 1.0], [1.0e7 + 16.0, 0.0, 0.5, 1.0], [1.0e7, 16.0, 0.5, 1.0]]);
    let far = Case { triangle: far, lens: None };
    let far_tile = Tile::square(1.0e7, 0.0, 2.0);
    let cases = [
        (flat, tile, [1.0, 1.0, 0.0, 0.0, 0.0]),
        (behind, Tile::square(-4.0, -4.0, 4.0), [-2.0, -2.0, 0.3, -0.2, 0.4]),
        (far, far_tile, [1.0e7 + 1.0, 1.0, 0.0, 0.0, 0.0]),
        (static_case(), tile, [50.0, 1.0, 0.0, 0.0, 0.0]),
    ];
    for (c, t, w) in cases {
        for m in crate::bounds::registry() {
            let s = svg(&c, &t, m, w, "odd").unwrap();
            assert_svg(&s);
        }
    }
    let g = grid(&far.triangle.to_oracle(), None, &slices(Dims::Static, &far_tile, cases[2].2)[0], GRID);
    assert!(g.count(Coverage::Interior) > GRID * GRID / 2, "the far tile lies inside the far triangle");
    let s = svg(&static_case(), &tile, m, [50.0, 1.0, 0.0, 0.0, 0.0], "odd").unwrap();
    assert!(s.contains("witness outside this panel"));
}

/// Writes pictures to explain_demo*.svg in the system's temporary directory for a
/// look by eye (lb2011 on the sweeping triangle, the test method's overlays, and a
/// culled tile); each must be a whole SVG document.
#[test]
fn demo_picture() {
    let out = |name: &str, s: &str| {
        assert!(s.starts_with("<svg") || s.contains("<svg"), "{name}: not an SVG document");
        assert!(s.trim_end().ends_with("</svg>"), "{name}: the document is cut short");
        std::fs::write(std::env::temp_dir().join(name), s).unwrap();
    };
    let demo = sweep_case(true);
    let tile = Tile::square(-4.0, -4.0, 4.0);
    let w = interior_in(&demo, &tile, 5);
    let s = svg(&demo, &tile, by_id("lb2011").unwrap(), w, "demo: an interior sample").unwrap();
    out("explain_demo.svg", &s);
    let case = lens_case(true);
    let s = svg(&case, &tile, FAKE, [-2.0, -2.0, 0.0, 0.1, 0.7], "demo: test constraints").unwrap();
    out("explain_demo_fake.svg", &s);
    let far = Tile::square(100.0, 100.0, 4.0);
    let s = svg(&static_case(), &far, by_id("bbox").unwrap(), [101.0, 101.0, 0.0, 0.0, 0.0], "demo: culled").unwrap();
    out("explain_demo_culled.svg", &s);
}
