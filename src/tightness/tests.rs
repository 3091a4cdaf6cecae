//! Tests of the measurement on tiny scenes (each a fraction of a second in release).

use super::pattern::{Pattern, PatternKind};
use super::scene::{self, Scene, Setting};
use super::*;
use crate::bounds::registry;

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
