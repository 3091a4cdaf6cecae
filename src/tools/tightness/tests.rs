//! Tests of the measurement on tiny scenes (each a fraction of a second in release).

use super::coverage::exact_coverage_scalar;
use super::pattern::{Pattern, PatternKind};
use super::scene::{self, Scene, Setting};
use super::*;
use crate::bounds::{registry, TileResult};
use crate::cli::tightness::run_cli;
use crate::cli::tightness::TightnessArgs;
use crate::model::Sample;
use indicatif::ProgressBar;
use oracles::batch::Batch;
use oracles::Coverage;

fn tiny(name: &str, w: u32, h: u32) -> Scene {
    scene::by_name(name, 7, w, h).unwrap()
}

fn run(s: &Scene, spp: u32, kind: PatternKind, certified: usize) -> Measurement {
    let mut cfg = Config::new(vec![1, 2, 4, 8], Pattern::new(kind, spp, 3));
    cfg.certified_tiles = certified;
    cfg.certified.max_boxes = 300;
    measure(s, &registry(), &Setting::ALL, &cfg, &ProgressBar::hidden())
}

/// Every covered sample of every triangle, counted over the whole screen by brute force.
fn brute_covered(s: &Scene, setting: Setting, pattern: &Pattern) -> u64 {
    let mut samples = Vec::new();
    pattern.region(0, 0, s.width - 1, s.height - 1, &mut samples);
    s.triangles(setting)
        .iter()
        .map(|t| {
            let o = t.to_oracle();
            samples.iter().filter(|x| oracles::classify(&o, x.to_oracle()) == Coverage::Interior).count() as u64
        })
        .sum()
}

#[test]
fn the_traversal_loses_no_covered_sample() {
    let s = tiny("forest", 32, 24);
    let p = Pattern::new(PatternKind::Stratified, 2, 3);
    let m = measure(&s, &registry()[..1], &Setting::ALL, &Config::new(vec![1, 8], p), &ProgressBar::hidden());
    for sum in &m.settings {
        assert_eq!(sum.covered, brute_covered(&s, sum.setting, &p), "{:?}", sum.setting);
        assert!(sum.covered > 0);
    }
}

#[test]
fn counts_are_consistent_and_the_ceiling_bounds_interval_tests() {
    for (name, w, h) in [("forest", 64, 48), ("interior", 48, 36)] {
        let s = tiny(name, w, h);
        let m = run(&s, 2, PatternKind::Sobol, 0);
        for sum in &m.settings {
            assert_eq!(sum.whole_screen, 0, "{name}: the scenes keep every vertex in front of the lens");
            let rows: Vec<&MethodRow> = m.rows.iter().filter(|r| r.setting == sum.setting).collect();
            for r in &rows {
                // Every covered sample is either let through or missed, for every method and tile.
                assert_eq!(r.counts.hits + r.counts.missed, sum.covered, "{name} {r:?}");
                assert!(r.counts.tested >= r.counts.hits, "{name} {r:?}");
                if r.counts.missed == 0 {
                    assert!(r.counts.tested >= sum.covered, "{name} {r:?}");
                }
            }
            for c in m.ceiling.iter().filter(|c| c.setting == sum.setting) {
                assert_eq!(c.covered, sum.covered, "{name} {c:?}");
                for r in rows.iter().filter(|r| r.tile == c.tile) {
                    // The sample box of a tile lies inside any interval answer that keeps
                    // every covered sample of the tile.
                    if !r.per_sample && r.counts.missed == 0 {
                        assert!(c.tested <= r.counts.tested, "{name} ceiling {c:?} vs {r:?}");
                    }
                }
                // bbox admits every sample of the traversed tiles (but those its f32 box
                // rounds away): no conservative method tests more.
                let bbox = rows.iter().find(|r| r.method == "bbox" && r.tile == c.tile).unwrap();
                for r in rows.iter().filter(|r| r.tile == c.tile && r.counts.missed == 0) {
                    assert!(r.counts.tested <= bbox.counts.tested, "{name} {r:?} vs bbox {bbox:?}");
                }
            }
        }
        // Static: no motion, no lens; bbox lets through every sample of the tiles it keeps
        // and the ceiling is bbox restricted to tiles with a covered sample.
        let st = m.settings.iter().find(|x| x.setting == Setting::Static).unwrap();
        assert!(st.covered > 0);
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let s = tiny("forest", 64, 48);
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let a = one.install(|| run(&s, 2, PatternKind::Stratified, 2));
    let b = two.install(|| run(&s, 2, PatternKind::Stratified, 2));
    assert_eq!(a, b);
    assert!(a.certified.iter().any(|c| c.tiles > 0));
}

#[test]
fn the_certified_ceiling_brackets_with_the_sample_ceiling() {
    let s = tiny("interior", 32, 24);
    let m = run(&s, 4, PatternKind::Uniform, 6);
    for c in &m.certified {
        // The outer certified box contains the covered-sample box.
        assert!(c.tested_certified >= c.tested_sample_box, "{c:?}");
        assert!(c.tested_sample_box >= c.covered, "{c:?}");
        if let (Some(lo), Some(hi)) = (c.ste_lower, c.ste_upper) {
            assert!(lo <= hi, "{c:?}");
        }
    }
}

#[test]
fn the_certified_ceiling_of_every_tile() {
    // `--certified all`: every traversed tile is solved, so the certified rows count as
    // many tiles as bbox tests, their covered samples are every covered sample of the
    // setting, and the certified box lets through at least the sample ceiling.
    let s = tiny("interior", 16, 12);
    let mut cfg = Config::new(vec![1, 4], Pattern::new(PatternKind::Stratified, 2, 3));
    cfg.certified_tiles = usize::MAX;
    cfg.certified.max_boxes = 300;
    let m = measure(&s, &registry()[..1], &Setting::ALL, &cfg, &ProgressBar::hidden());
    assert_eq!(m.certified.len(), m.ceiling.len());
    for (c, ceil) in m.certified.iter().zip(&m.ceiling) {
        let bbox = m.rows.iter().find(|r| r.method == "bbox" && r.setting == c.setting && r.tile == c.tile).unwrap();
        assert_eq!(c.tiles, bbox.work.tile_tests, "{c:?}");
        assert!(c.tiles > 0);
        let sum = m.settings.iter().find(|x| x.setting == c.setting).unwrap();
        assert_eq!(c.covered, sum.covered, "{c:?}");
        assert!(c.tested_certified >= ceil.tested, "{c:?} {ceil:?}");
    }
}

#[test]
fn a_hand_made_static_triangle() {
    // One static, in-focus triangle on a 16x16 screen: with one sample per pixel at the
    // pixel's stratified position, bbox tests all samples of the tiles over its box.
    let cam = pinhole16();
    let obj = scene::Object {
        name: "t".into(),
        tris: vec![[[-0.5, -0.5, 2.0], [0.5, -0.5, 2.0], [-0.5, 0.5, 2.0]]],
        motion: scene::RigidMotion::none(),
        wobble: 0.0,
    };
    let s = Scene { name: "one".into(), width: 16, height: 16, camera: cam, objects: vec![obj] };
    let p = Pattern::new(PatternKind::Stratified, 1, 1);
    let m = measure(&s, &registry(), &[Setting::Static], &Config::new(vec![1, 4], p), &ProgressBar::hidden());
    let sum = &m.settings[0];
    // Half of the 8x8-pixel square [4, 12]^2 is covered: about 32 samples.
    assert!((24..=40).contains(&sum.covered), "{sum:?}");
    let bbox1 = m.rows.iter().find(|r| r.method == "bbox" && r.tile == 1).unwrap();
    assert_eq!(bbox1.counts.missed, 0);
    // The footprint (with its margin) spans pixels 3..=12; bbox keeps tiles touching its box.
    assert!(bbox1.counts.tested <= 100 && bbox1.counts.tested >= 64, "{bbox1:?}");
}

/// A pinhole 16 px wide (fx = 16, principal point at the centre).
fn pinhole16() -> crate::model::ThinLens {
    crate::model::ThinLens { fx: 16.0, fy: 16.0, cx: 8.0, cy: 8.0, radius: 0.0, focus: 2.0, near: 0.1, far: 100.0 }
}

#[test]
fn an_obj_scene_is_measured() {
    let dir = std::env::temp_dir().join(format!("cullproof-tight-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("cube.obj");
    let mut text = String::new();
    for v in 0..8 {
        text += &format!("v {} {} {}\n", v & 1, (v >> 1) & 1, (v >> 2) & 1);
    }
    text += "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    std::fs::write(&p, text).unwrap();
    let s = scene::by_name(p.to_str().unwrap(), 2, 32, 24).unwrap();
    assert_eq!(s.triangle_count(), 12);
    let m = run(&s, 1, PatternKind::Stratified, 0);
    assert!(m.settings.iter().all(|x| x.covered > 0 && x.whole_screen == 0));
}

#[test]
fn footprints_fall_back_or_skip() {
    let cam = pinhole16();
    let behind = cam.triangle([[0.0, 0.0, 2.0], [1.0, 0.0, -1.0], [0.0, 1.0, 2.0]], [[0.0, 0.0, 2.0]; 3]);
    assert_eq!(footprint(&behind, 16, 16), Footprint::WholeScreen);
    let off = cam.triangle([[10.0, 10.0, 2.0], [11.0, 10.0, 2.0], [10.0, 11.0, 2.0]], [[10.0, 10.0, 2.0]; 3]);
    assert_eq!(footprint(&off, 16, 16), Footprint::OffScreen);
    let on = cam.triangle(
        [[0.0, 0.0, 2.0], [0.25, 0.0, 2.0], [0.0, 0.25, 2.0]],
        [[0.0, 0.0, 2.0], [0.25, 0.0, 2.0], [0.0, 0.25, 2.0]],
    );
    assert_eq!(footprint(&on, 16, 16), Footprint::Region(PixelRect { x0: 7, y0: 7, x1: 10, y1: 10 }));
}

/// A bumpy UV sphere as OBJ text (`seg` around, `rings` rings: 2 seg (rings - 1) triangles).
fn bumpy_sphere(seg: usize, rings: usize) -> String {
    let r = |th: f64, ph: f64| 1.0 + 0.18 * (3.0 * th).sin() * (4.0 * ph).cos();
    let mut text = format!("v 0 {} 0\n", -r(0.0, 0.0));
    for j in 1..rings {
        let th = std::f64::consts::PI * j as f64 / rings as f64;
        for i in 0..seg {
            let ph = std::f64::consts::TAU * i as f64 / seg as f64;
            let rr = r(th, ph);
            text += &format!("v {} {} {}\n", rr * th.sin() * ph.cos(), -rr * th.cos(), rr * th.sin() * ph.sin());
        }
    }
    text += &format!("v 0 {} 0\n", r(std::f64::consts::PI, 0.0));
    let idx = |i: usize, j: usize| 2 + (j - 1) * seg + i % seg;
    for i in 0..seg {
        text += &format!("f 1 {} {}\n", idx(i + 1, 1), idx(i, 1));
    }
    for j in 1..rings - 1 {
        for i in 0..seg {
            text += &format!(
                "f {} {} {}\nf {} {} {}\n",
                idx(i, j),
                idx(i + 1, j),
                idx(i + 1, j + 1),
                idx(i, j),
                idx(i + 1, j + 1),
                idx(i, j + 1)
            );
        }
    }
    let top = 2 + (rings - 1) * seg;
    for i in 0..seg {
        text += &format!("f {} {} {top}\n", idx(i, rings - 1), idx(i + 1, rings - 1));
    }
    text
}

fn temp_obj(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("cullproof-tight-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn more_work_never_costs_less() {
    let s = tiny("forest", 48, 36);
    let cfg = Config::new(vec![2], Pattern::new(PatternKind::Stratified, 2, 3));
    let methods = registry();
    let table = SampleTable::new(&cfg.pattern, s.width, s.height);
    let m = measure_with(&s, &table, &methods, &Setting::ALL, &cfg, &ProgressBar::hidden());
    let ops = cost::time_ops(&s, &table, &methods, &Setting::ALL, 2, 3, 24, &ProgressBar::hidden());
    let costs = cost::costs(&m.rows, &ops, 2);
    assert_eq!(costs.len(), m.rows.len());
    let mut checked = 0;
    for c in &costs {
        let row = m.rows.iter().find(|r| r.method == c.method && r.setting == c.setting).unwrap();
        let bbox = costs.iter().find(|b| b.method == "bbox" && b.setting == c.setting).unwrap();
        // A method disabled on every triangle does bbox's work (or more): never cheaper.
        if row.work.setups == 0 && row.work.disabled_setups > 0 {
            let e = 1e-9 * bbox.seconds.hi;
            assert!(c.seconds.lo >= bbox.seconds.lo - e, "{c:?} vs {bbox:?}");
            assert!(c.seconds.median >= bbox.seconds.median - e, "{c:?} vs {bbox:?}");
            assert!(c.seconds.hi >= bbox.seconds.hi - e, "{c:?} vs {bbox:?}");
            checked += 1;
        }
        assert!(c.seconds.lo <= c.seconds.median && c.seconds.median <= c.seconds.hi, "{c:?}");
    }
    assert!(checked > 0, "the static setting disables the motion-only methods");
    // The estimate grows with every count at the same per-operation costs.
    let r = &m.rows[0];
    let base = cost::total(r, [10.0, 3.0, 1.0], [7.0, 2.0, 1.0], 5.0);
    for k in 0..7 {
        let mut more = r.clone();
        let w = &mut more.work;
        [
            &mut w.setups,
            &mut w.tile_tests,
            &mut w.sample_tests,
            &mut w.disabled_setups,
            &mut w.disabled_tile_tests,
            &mut w.disabled_sample_tests,
            &mut more.counts.tested,
        ][k]
            .clone_from(
                &(1 + [
                    r.work.setups,
                    r.work.tile_tests,
                    r.work.sample_tests,
                    r.work.disabled_setups,
                    r.work.disabled_tile_tests,
                    r.work.disabled_sample_tests,
                    r.counts.tested,
                ][k]),
            );
        assert!(cost::total(&more, [10.0, 3.0, 1.0], [7.0, 2.0, 1.0], 5.0) > base, "count {k}");
    }
}

#[test]
fn work_counts_match_the_traversal() {
    let s = tiny("interior", 32, 24);
    let m = run(&s, 2, PatternKind::Stratified, 0);
    for sum in &m.settings {
        let on = sum.triangles - sum.off_screen;
        for r in m.rows.iter().filter(|r| r.setting == sum.setting) {
            assert_eq!(r.work.setups + r.work.disabled_setups, on, "{r:?}");
            assert_eq!(r.work.disabled_setups, r.disabled_triangles, "{r:?}");
            // Every sample let through was given the sample test.
            assert!(r.work.sample_tests + r.work.disabled_sample_tests >= r.counts.tested, "{r:?}");
        }
    }
}

#[test]
fn mesh_controls_are_recorded_and_reproducible() {
    let p = temp_obj("bumpy.obj", &bumpy_sphere(12, 7));
    let c = mesh::MeshControls {
        motion: Some("rigid,dolly,rotate,wobble".into()),
        dolly: Some(0.4),
        rotate_deg: Some(20.0),
        wobble: Some(0.05),
        focus_at: Some(-0.5),
        fov: Some(50.0),
        ..Default::default()
    };
    let (a, sa) = mesh::from_obj_with(&p, 5, 40, 30, &c).unwrap();
    let (b, sb) = mesh::from_obj_with(&p, 5, 40, 30, &c).unwrap();
    let (d, _) = mesh::from_obj_with(&p, 6, 40, 30, &c).unwrap();
    assert_eq!(a.triangle_count(), 2 * 12 * 6);
    assert_eq!(a.camera_space(Setting::Blur2), b.camera_space(Setting::Blur2));
    assert_ne!(a.camera_space(Setting::Blur2), d.camera_space(Setting::Blur2), "the seed is ignored");
    assert_eq!(sa, sb);
    assert_eq!(sa.path, p.display().to_string());
    assert_eq!(sa.motion, ["rigid", "dolly", "rotate", "wobble"]);
    // The focal plane lies in the mesh, halfway between its front and its centre.
    assert!((sa.focus - (sa.depth - 0.5 * sa.radius)).abs() < 1e-9 * sa.depth, "{sa:?}");
    // Dolly: the mesh comes towards the camera over the shutter.
    let (q, r) = a.camera_space(Setting::Blur).into_iter().fold((0.0, 0.0), |(x, y), (q, r)| {
        (x + q.iter().map(|p| p[2] as f64).sum::<f64>(), y + r.iter().map(|p| p[2] as f64).sum::<f64>())
    });
    assert!(r < q, "{q} {r}");
    // Wobble is not rigid: a shared vertex moves the same in every triangle, but
    // differently from its neighbours beyond the rigid motion.
    let rigid_only = mesh::MeshControls { wobble: None, motion: Some("rigid,dolly,rotate".into()), ..c.clone() };
    let (e, _) = mesh::from_obj_with(&p, 5, 40, 30, &rigid_only).unwrap();
    assert_ne!(a.camera_space(Setting::Blur), e.camera_space(Setting::Blur));
    assert_eq!(a.camera_space(Setting::Static), e.camera_space(Setting::Static));
}

#[test]
fn mesh_controls_refuse_bad_values_by_name() {
    let p = temp_obj("ok.obj", &bumpy_sphere(6, 4));
    let bad = |c: mesh::MeshControls| mesh::from_obj_with(&p, 1, 16, 16, &c).unwrap_err().to_string();
    let e = bad(mesh::MeshControls { motion: Some("dolly".into()), dolly: Some(2.0), ..Default::default() });
    assert!(e.contains("--dolly") && e.contains('2'), "{e}");
    let e = bad(mesh::MeshControls { wobble: Some(0.1), ..Default::default() });
    assert!(e.contains("--wobble") && e.contains("--motion wobble"), "{e}");
    let e = bad(mesh::MeshControls { motion: Some("spin".into()), ..Default::default() });
    assert!(e.contains("spin"), "{e}");
    let e = bad(mesh::MeshControls { fov: Some(f64::NAN), ..Default::default() });
    assert!(e.contains("--fov"), "{e}");
    let e = bad(mesh::MeshControls { focus: Some(-1.0), ..Default::default() });
    assert!(e.contains("--focus"), "{e}");
    let e = mesh::MeshControls { fov: Some(30.0), ..Default::default() }.refuse_for("forest").unwrap_err().to_string();
    assert!(e.contains("--fov") && e.contains("FILE.obj"), "{e}");
    // A bad OBJ file names the file and the line.
    let q = temp_obj("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n");
    let e = mesh::from_obj_with(&q, 1, 16, 16, &Default::default()).unwrap_err().to_string();
    assert!(e.contains("broken.obj") && e.contains(":3:"), "{e}");
}

#[test]
fn the_same_seed_gives_the_same_report() {
    let p = temp_obj("rep.obj", &bumpy_sphere(8, 5));
    let dir = p.parent().unwrap().to_path_buf();
    let args = |json: &str| TightnessArgs {
        scene: p.display().to_string(),
        setting: "all".into(),
        spp: 2,
        tile: Some(4),
        pattern: PatternKind::Sobol,
        seed: 9,
        out: dir.join("out"),
        json: Some(dir.join(json)),
        jobs: Some(2),
        size: "24x16".into(),
        method: "bbox,lc".into(),
        certified: 2,
        no_timing: true,
        repeats: 1,
        cost_triangles: 8,
        mesh: mesh::MeshControls {
            motion: Some("dolly,wobble".into()),
            focus_at: Some(0.3),
            lens_radius: Some(0.05),
            ..Default::default()
        },
    };
    let read = |name: &str| {
        let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap();
        v.as_object_mut().unwrap().remove("seconds");
        v
    };
    run_cli(&args("a.json")).unwrap();
    run_cli(&args("b.json")).unwrap();
    let (a, b) = (read("a.json"), read("b.json"));
    assert_eq!(a, b);
    assert_eq!(a["mesh"]["path"], p.display().to_string());
    assert_eq!(a["mesh"]["motion"], serde_json::json!(["dolly", "wobble"]));
    assert_eq!(a["mesh"]["lens_radius"], 0.05);
}

#[test]
fn batched_exact_coverage_is_the_scalar_oracles() {
    use crate::cases::generate::{physical_case, rng_for, samples_for, Regime};
    let mut scratch = CoverageScratch::default();
    let mut regimes = 0;
    for (ri, regime) in Regime::ALL.into_iter().enumerate() {
        let mut classes = [0u64; 2];
        for k in 0..3u64 {
            let mut rng = rng_for(5, ri as u64 * 8 + k);
            let case = physical_case(&mut rng, regime);
            let otri = case.triangle.to_oracle();
            // Half uniform over the footprint, half next to an edge (where the lanes defer).
            let samples: Vec<Sample> = samples_for(&case, &mut rng, 700)
                .iter()
                .map(|p| Sample::new(p[0] as f32, p[1] as f32, p[2] as f32, p[3] as f32, p[4] as f32))
                .collect();
            let (mut a, mut b) = (vec![false; samples.len()], vec![false; samples.len()]);
            let batch = Batch::new(&otri);
            let (ca, ba, _) = exact_coverage(&batch, &samples, &mut scratch, &mut a);
            let (cb, bb, _) = exact_coverage_scalar(&otri, &samples, &mut b);
            assert_eq!(a, b, "{}: classes differ", regime.name());
            assert_eq!((ca, ba), (cb, bb), "{}", regime.name());
            classes[0] += ca;
            classes[1] += samples.len() as u64 - ca;
        }
        regimes += (classes[0] > 0 && classes[1] > 0) as usize;
    }
    assert!(regimes >= 8, "only {regimes} regimes had both covered and uncovered samples");
}

/// The counts of the measurement are those of [`TileBounds::admits`] sample by sample
/// over every traversed tile (the count in chunks of a row, with `eval_row`, on the
/// whole chunk or on the samples inside gathered, changes nothing): short rows (2
/// samples per pixel, 1 and 4 px tiles) and long ones (9 per pixel, 8 px tiles: rows of
/// 72 samples, a chunk of 64 and one of 8).
#[test]
fn counts_are_those_of_admits_sample_by_sample() {
    let gathered = counts_match_admits(2, vec![1, 4]) + counts_match_admits(9, vec![8]);
    assert!(gathered > 100, "only {gathered} long chunks with constraints and less than half inside");
}

/// [`counts_are_those_of_admits_sample_by_sample`] for one pattern density and tile
/// sizes; returns the number of (answer with constraints, chunk of more than 32
/// samples) pairs with less than half of the chunk inside the intervals.
fn counts_match_admits(spp: u32, tiles: Vec<u32>) -> u64 {
    let s = tiny("forest", 32, 24);
    let p = Pattern::new(PatternKind::Stratified, spp, 3);
    let cfg = Config::new(tiles, p);
    let methods = registry();
    let mut gathered = 0u64;
    let m = measure(&s, &methods, &Setting::ALL, &cfg, &ProgressBar::hidden());
    let table = SampleTable::new(&p, s.width, s.height);
    let mut per_sample_tiles = 0u64;
    for &setting in &Setting::ALL {
        for (ti, &size) in cfg.tiles.iter().enumerate() {
            let mut want = vec![Counts::default(); methods.len()];
            for tri in s.triangles(setting) {
                let r = match footprint(&tri, s.width, s.height) {
                    Footprint::OffScreen => continue,
                    Footprint::WholeScreen => PixelRect { x0: 0, y0: 0, x1: s.width - 1, y1: s.height - 1 },
                    Footprint::Region(r) => r,
                };
                let o = tri.to_oracle();
                let (tx0, ty0, tx1, ty1) = tile_range(&r, size);
                let preps: Vec<_> = methods.iter().map(|m| m.setup(&tri)).collect();
                for ty in ty0..=ty1 {
                    for tx in tx0..=tx1 {
                        let px = tile_pixels(tx, ty, size, s.width, s.height);
                        let mut smp = Vec::new();
                        for py in px.y0..=px.y1 {
                            let st = table.start(px.x0, py);
                            smp.extend_from_slice(&table.samples[st..st + (px.x1 - px.x0 + 1) as usize * table.spp]);
                        }
                        let cov: Vec<bool> =
                            smp.iter().map(|x| oracles::classify(&o, x.to_oracle()) == Coverage::Interior).collect();
                        for (mi, prep) in preps.iter().enumerate() {
                            let c = &mut want[mi];
                            match prep.tile(&tile_of(&px)) {
                                TileResult::Empty => c.missed += cov.iter().filter(|&&x| x).count() as u64,
                                TileResult::Bounds(b) => {
                                    per_sample_tiles += !b.constraints.is_empty() as u64;
                                    let row = (px.x1 - px.x0 + 1) as usize * table.spp;
                                    if !b.constraints.is_empty() && row > 32 {
                                        for r in smp.chunks(row) {
                                            for ch in r.chunks(64) {
                                                let inside = ch
                                                    .iter()
                                                    .filter(|x| {
                                                        let i = |r: [f32; 2], v: f32| r[0] <= v && v <= r[1];
                                                        i(b.u, x.u) && i(b.v, x.v) && i(b.t, x.t)
                                                    })
                                                    .count();
                                                gathered += (ch.len() > 32 && 2 * inside < ch.len()) as u64;
                                            }
                                        }
                                    }
                                    for (x, &cv) in smp.iter().zip(&cov) {
                                        let a = b.admits(x);
                                        c.tested += a as u64;
                                        c.hits += (a && cv) as u64;
                                        c.missed += (!a && cv) as u64;
                                    }
                                }
                            }
                        }
                    }
                }
            }
            for (mi, meth) in methods.iter().enumerate() {
                let id = meth.info().id;
                let row = m.rows.iter().find(|r| r.method == id && r.setting == setting && r.tile == size).unwrap();
                assert_eq!(row.counts, want[mi], "{id} {setting:?} tile {size} (index {ti})");
            }
        }
    }
    assert!(per_sample_tiles > 100, "only {per_sample_tiles} tiles with per-sample constraints");
    gathered
}
