//! The samples a bound promises to keep (`docs/model.md`, §7), through the public API:
//!
//! - a user's culler that is exact at the points of a sample set (it culls a tile when
//!   no point of the set in it is covered by the static triangle) is proven
//!   conservative under that set and violated under any position, with a witness off
//!   the set; the same for the 4x MSAA pattern, and a pixel-centre culler is violated
//!   under 4x MSAA;
//! - snapping: one case whose snapped triangle covers the pixel centre its unsnapped
//!   triangle misses; a culler that culls that tile is proven without snapping and
//!   violated with it (witness at the centre);
//! - viewport: every case placed lies in the guard band, its tile in the viewport;
//! - case files record the set, snap and viewport, old files read as the defaults, and
//!   a witness off the recorded set is refused by name.

use cullproof::bounds::{Method, MethodInfo, Outputs, Prepared, TileBounds, TileResult};
use cullproof::cases::try_make_case;
use cullproof::gate::{judge, CheckConfig};
use cullproof::model::samples::snap_coord;
use cullproof::search::{case_files, CaseFile};
use cullproof::{Bound, Case, Gate, MethodVerdict, Regime, SampleSet, Snap, Tile, Triangle, Viewport};
use std::path::PathBuf;
use std::sync::Arc;

/// Culls a tile when no point of `set` in it can be covered by the (static, pinhole)
/// triangle; any other triangle keeps the whole domain. "Can be covered" is decided in
/// f64 with a slack far above its rounding error, so the culler keeps every covered
/// point of the set (and a few uncovered ones next to an edge).
struct SetCuller {
    set: SampleSet,
    info: &'static MethodInfo,
}

static CENTRES_INFO: MethodInfo = MethodInfo {
    id: "centre-culler",
    source: "a test: exact at pixel centres",
    reconstruction: false,
    dims: &[],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: false, per_sample: false },
};
static MSAA4_INFO: MethodInfo = MethodInfo { id: "msaa4-culler", source: "a test: exact at 4x MSAA", ..CENTRES_INFO };

struct Prep {
    set: SampleSet,
    tri: Option<Triangle>,
}

/// Can the static pinhole triangle cover (x, y)? The homogeneous edge values and
/// determinant of `docs/model.md` §3.2 in f64, each with a slack of 1e-9 of its terms'
/// magnitude: "no" only when some value is certainly of the wrong sign for both
/// windings.
fn maybe_covered(t: &Triangle, x: f64, y: f64) -> bool {
    let p: Vec<[f64; 3]> =
        t.q.iter().map(|v| [v[0] as f64 - x * v[3] as f64, v[1] as f64 - y * v[3] as f64, v[3] as f64]).collect();
    let mut e = [(0.0, 0.0); 3];
    for (k, (i, j)) in [(1, 2), (2, 0), (0, 1)].into_iter().enumerate() {
        let (a, b) = (p[i][0] * p[j][1], p[i][1] * p[j][0]);
        e[k] = (a - b, 1e-9 * (a.abs() + b.abs()) + 1e-300);
    }
    let d = (0..3).map(|k| p[k][2] * e[k].0).sum::<f64>();
    let dm = (0..3).map(|k| (p[k][2] * e[k].0).abs() + p[k][2].abs() * e[k].1).sum::<f64>() * 1e-9 + 1e-300;
    [1.0, -1.0].iter().any(|s| e.iter().all(|&(v, err)| s * v > -err) && s * d > -dm)
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let Some(t) = &self.tri else { return TileResult::Bounds(TileBounds::full()) };
        let pts = self.set.points_in(tile.x0 as f64, tile.x1 as f64, tile.y0 as f64, tile.y1 as f64).unwrap();
        if pts.iter().any(|&(x, y)| maybe_covered(t, x, y)) {
            TileResult::Bounds(TileBounds::full())
        } else {
            TileResult::Empty
        }
    }
}

impl Method for SetCuller {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, t: &Triangle) -> Box<dyn Prepared> {
        let plain = t.q == t.r && t.c0 == t.c1 && t.c0.iter().all(|&c| c == 0.0) && t.q.iter().all(|v| v[3] > 0.0);
        Box::new(Prep { set: self.set, tri: plain.then_some(*t) })
    }
}

fn centre_culler() -> SetCuller {
    SetCuller { set: SampleSet::PixelCentres, info: &CENTRES_INFO }
}

fn gate(m: SetCuller, set: SampleSet) -> cullproof::GateReport {
    Gate::new().method(m).regimes(&[Regime::Static, Regime::Tiny]).cases(192).limit_every(0).samples(set).run()
}

#[test]
fn a_pixel_centre_culler_is_proven_under_centres_and_violated_under_any_position() {
    let r = gate(centre_culler(), SampleSet::PixelCentres);
    let m = r.method("centre-culler").unwrap();
    assert_eq!(m.verdict, MethodVerdict::Proven, "{}", r.render());
    assert!(r.passed() && r.render().contains("samples: centres"), "{}", r.render());

    let r = gate(centre_culler(), SampleSet::Any);
    let m = r.method("centre-culler").unwrap();
    assert_eq!(m.verdict, MethodVerdict::Violated, "{}", r.render());
    assert!(!r.passed());
    for cx in &m.counterexamples {
        assert_eq!(cx.bound, Bound::TileCulled);
        let (x, y) = (cx.sample[0], cx.sample[1]);
        assert!(!SampleSet::PixelCentres.contains(x, y), "the witness ({x}, {y}) is a pixel centre");
    }
}

#[test]
fn an_msaa4_culler_is_proven_under_msaa4_and_a_centre_culler_violated_under_it() {
    let msaa = SampleSet::Msaa(4);
    let r = gate(SetCuller { set: msaa, info: &MSAA4_INFO }, msaa);
    assert_eq!(r.method("msaa4-culler").unwrap().verdict, MethodVerdict::Proven, "{}", r.render());
    let r = gate(SetCuller { set: msaa, info: &MSAA4_INFO }, SampleSet::Any);
    assert_eq!(r.method("msaa4-culler").unwrap().verdict, MethodVerdict::Violated, "{}", r.render());
    // The centre culler drops tiles whose covered samples are MSAA positions only: the
    // witnesses are points of the pattern.
    let r = gate(centre_culler(), msaa);
    let m = r.method("centre-culler").unwrap();
    assert_eq!(m.verdict, MethodVerdict::Violated, "{}", r.render());
    assert!(m.counterexamples.iter().all(|c| msaa.contains(c.sample[0], c.sample[1])), "{:?}", m.counterexamples);
}

/// Culls the tile `[0, 1]^2` whatever the triangle: conservative for a triangle that
/// covers no sample of the set there.
struct CullUnitTile;
static UNIT_INFO: MethodInfo = MethodInfo { id: "cull-unit-tile", source: "a test", ..CENTRES_INFO };
struct Unit;
impl Prepared for Unit {
    fn tile(&self, t: &Tile) -> TileResult {
        if *t == Tile::square(0.0, 0.0, 1.0) {
            TileResult::Empty
        } else {
            TileResult::Bounds(TileBounds::full())
        }
    }
}
impl Method for CullUnitTile {
    fn info(&self) -> &'static MethodInfo {
        &UNIT_INFO
    }
    fn setup(&self, _: &Triangle) -> Box<dyn Prepared> {
        Box::new(Unit)
    }
}

#[test]
fn snapping_decides_coverage_of_the_snapped_triangle_exactly() {
    // Pixel positions (0.2, 0.2), (0.88, 0.2), (0.2, 0.7) at w = 3: the centre (0.5, 0.5)
    // lies outside (the long edge passes y = 0.479 at x = 0.5); snapped to quarter
    // pixels they are (0.25, 0.25), (1, 0.25), (0.25, 0.75), whose long edge passes
    // y = 0.583 there: the centre is covered.
    let w = 3.0f32;
    let v = |x: f32, y: f32| [x * w, y * w, 1.0, w];
    let case = Case { triangle: Triangle::fixed([v(0.2, 0.2), v(0.88, 0.2), v(0.2, 0.7)]), lens: None };
    let centre = [0.5, 0.5, 0.0, 0.0, 0.0];
    assert_eq!(oracles_class(&case, None, centre), "Outside");
    assert_eq!(oracles_class(&case, Some(Snap { bits: 2 }), centre), "Interior");
    assert_eq!(snap_coord(0.88 * w, w, 2), Some(3.0));

    let tile = Tile::square(0.0, 0.0, 1.0);
    let m: Vec<cullproof::MethodRef> = vec![Arc::new(CullUnitTile)];
    let mut cfg = CheckConfig::default_for(m.clone());
    cfg.sample_set = SampleSet::PixelCentres;
    let (js, _) = judge(&cfg, &m, &case, &tile, 0);
    assert_eq!(js[0].verdict(), cullproof::judge::Verdict::Proven);
    cfg.snap = Some(Snap { bits: 2 });
    let (js, _) = judge(&cfg, &m, &case, &tile, 0);
    let w = js[0].violation.as_ref().expect("the snapped triangle covers the centre");
    assert_eq!(&w.sample[..2], &[0.5, 0.5]);
    assert_eq!(w.tile, tile);
    // Without a sample set the unsnapped triangle is covered in the tile anyway.
    cfg.sample_set = SampleSet::Any;
    cfg.snap = None;
    assert_eq!(judge(&cfg, &m, &case, &tile, 0).0[0].verdict(), cullproof::judge::Verdict::Violated);
}

fn oracles_class(case: &Case, snap: Option<Snap>, p: [f64; 5]) -> String {
    let (_, tri) = cullproof::cases::place::judged_triangles(snap, case).unwrap();
    format!("{:?}", oracles::classify(&tri, p))
}

#[test]
fn every_case_placed_in_a_viewport_lies_in_its_guard_band() {
    let vp: Viewport = "1920x1080+64".parse().unwrap();
    let mut cfg = CheckConfig::default_for(Vec::new());
    cfg.viewport = Some(vp);
    let g = vp.guard_rect();
    let (mut placed, mut skipped) = (0, 0);
    for i in 0..320 {
        let Some((regime, case, tile)) = try_make_case(&cfg.draw(), i) else {
            skipped += 1;
            assert!(matches!(cfg.regimes[(i % 16) as usize], Regime::BehindLens | Regime::Huge | Regime::HugeCoc));
            continue;
        };
        placed += 1;
        let f = cullproof::cases::place::footprint(&case.triangle).expect("in front of the lens");
        assert!(f[0] >= g[0] && f[1] <= g[1] && f[2] >= g[2] && f[3] <= g[3], "{regime:?} {f:?}");
        assert!(vp.holds_tile(&tile), "{regime:?} {tile:?}");
        assert!(case.validate().is_ok());
    }
    assert!(placed >= 250 && skipped >= 20, "{placed} placed, {skipped} skipped");
    // The gate runs under it and says so; the cases it could not place are counted,
    // not judged, in their rows.
    let r = Gate::new().method(centre_culler()).cases(64).viewport(vp).samples(SampleSet::PixelCentres).run();
    let note = r.raw.samples.as_ref().unwrap();
    assert!(note.outside_viewport >= 4 && r.raw.cases == 64, "{note:?}");
    assert_eq!(r.method("centre-culler").unwrap().not_judged, note.outside_viewport, "{}", r.render());
    assert_eq!(r.raw.rows.iter().map(|x| x.not_judged).sum::<u64>(), note.outside_viewport);
    assert!(r.render().contains("viewport 1920x1080+64"));
    assert_eq!(r.method("centre-culler").unwrap().verdict, MethodVerdict::Proven, "{}", r.render());
}

#[test]
fn case_files_record_the_set_and_old_files_read_as_the_defaults() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/cases");
    let files = case_files(&[root]).unwrap();
    for f in &files {
        let cf = CaseFile::load(f).unwrap();
        assert_eq!((cf.samples, cf.snap, cf.viewport), (SampleSet::Any, None, None), "{}", f.display());
        // Written back, an old file has the same fields (none added for the defaults).
        let old: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(f).unwrap()).unwrap();
        let new = serde_json::to_value(&cf).unwrap();
        assert_eq!(
            old.as_object().unwrap().keys().collect::<Vec<_>>(),
            new.as_object().unwrap().keys().collect::<Vec<_>>()
        );
    }
    let mut cf = CaseFile::load(&files[0]).unwrap();
    cf.samples = SampleSet::Msaa(8);
    cf.snap = Some(Snap { bits: 8 });
    let dir = std::env::temp_dir().join(format!("cullproof-samples-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("recorded.json");
    let mut v = serde_json::to_value(&cf).unwrap();
    assert_eq!((v["samples"].as_str(), v["snap"].as_u64()), (Some("msaa8"), Some(8)));
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    if cf.witness.as_ref().is_some_and(|w| !SampleSet::Msaa(8).contains(w.sample[0], w.sample[1])) {
        let e = CaseFile::load(&p).unwrap_err().to_string();
        assert!(e.contains("recorded.json") && e.contains("witness.sample") && e.contains("msaa8"), "{e}");
    }
    v["witness"] = serde_json::Value::Null;
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let back = CaseFile::load(&p).unwrap();
    assert_eq!((back.samples, back.snap), (SampleSet::Msaa(8), Some(Snap { bits: 8 })));
    v["samples"] = "msaa3".into();
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let e = CaseFile::load(&p).unwrap_err().to_string();
    assert!(e.contains("`samples`") && e.contains("msaa3"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A pixel-centre filter with 1/256 px vertex snapping, gated in the viewport hardware
/// states: centred on the origin, +-2^15 px. Every case is proven or not judged (those
/// the viewport cannot hold or snapping cannot snap: behind the lens), none fails, and
/// the not-judged rows are skipped (not failed, not passed) in the JUnit file.
#[test]
fn a_pixel_centre_filter_with_snapping_in_a_centred_viewport_is_proven_or_not_judged() {
    let vp: Viewport = "centred:65536x65536".parse().unwrap();
    assert_eq!(vp.to_string(), "-32768,-32768,65536x65536");
    let r = Gate::new()
        .method(centre_culler())
        .cases(320)
        .limit_every(0)
        .viewport(vp)
        .samples(SampleSet::PixelCentres)
        .snap(8)
        .run();
    let m = r.method("centre-culler").unwrap();
    let text = r.render();
    assert!(r.passed(), "{text}");
    assert_eq!((m.violated, m.unproven), (0, 0), "{text}");
    assert!(m.proven > 200 && m.not_judged > 0 && m.proven + m.not_judged == 320, "{text}");
    assert_eq!(m.verdict, MethodVerdict::Proven, "{text}");
    assert!(text.contains("not judged"), "{text}");
    let behind = r.raw.rows.iter().find(|x| x.regime == "behind-lens").expect("its row is there");
    assert_eq!((behind.not_judged, behind.cases), (20, 20), "{text}");
    assert_eq!(behind.status, cullproof::gate::Status::NotJudged, "{text}");
    let xml = cullproof::gate::junit::render(&r.raw, &std::env::temp_dir(), "").unwrap();
    assert!(xml.contains("name=\"behind-lens\" time=\"0\"><skipped message=\"not judged"), "{xml}");
    assert!(!xml.contains("<failure"), "{xml}");
}
