//! The unit tests of `search` (case files, the search, the shrinker).

use super::shrink::{round_bits, steps};
use super::*;
use crate::gate::CheckConfig;
use crate::model::{Case, SampleSet, Tile};

#[test]
fn depths_to_unit_w_keep_the_screen_positions_and_cocs_at_both_ends() {
    let mut tri = crate::model::Triangle::fixed([[2.0, 4.0, 1.0, 2.0], [8.0, 4.0, 2.0, 4.0], [3.0, 9.0, 0.5, 1.0]]);
    tri.r[0] = [6.0, 3.0, 1.5, 3.0];
    tri.c0 = [1.0, -2.0, 0.5];
    tri.c1 = [3.0, -2.0, 0.5];
    let case = Case { triangle: tri, lens: None };
    let tile = Tile::square(0.0, 0.0, 4.0);
    let (_, c, _) = steps(&case, &tile, [1.0, 1.0, 0.0, 0.0, 0.5])
        .into_iter()
        .find(|s| s.0 == "depths to w = 1")
        .expect("a case with w != 1 offers the step");
    let t = c.triangle;
    for i in 0..3 {
        assert_eq!((t.q[i][3], t.r[i][3]), (1.0, 1.0));
        for (a, b, ca, cb) in [(tri.q[i], t.q[i], tri.c0[i], t.c0[i]), (tri.r[i], t.r[i], tri.c1[i], t.c1[i])] {
            assert_eq!((a[0] / a[3], a[1] / a[3], ca / a[3]), (b[0], b[1], cb));
        }
    }
    // nothing to do when every w is already 1, or a vertex is behind the lens
    let flat = Case { triangle: t, lens: None };
    assert!(steps(&flat, &tile, [1.0; 5]).iter().all(|s| s.0 != "depths to w = 1"));
    let mut behind = case;
    behind.triangle.q[1][3] = -1.0;
    assert!(steps(&behind, &tile, [1.0; 5]).iter().all(|s| s.0 != "depths to w = 1"));
}

/// A conservative bbox case file built from generated case `index`.
fn fixture(index: u64) -> CaseFile {
    let (regime, case, tile) =
        crate::cases::make_case(&CheckConfig::default_with(crate::bounds::registry()).draw(), index);
    CaseFile {
        format: FORMAT.into(),
        method: "bbox".into(),
        case,
        tile,
        expected: Verdict::Conservative,
        witness: None,
        provenance: Provenance {
            found_by: "hand".into(),
            seed: 1,
            case_index: index,
            regime: regime.name().into(),
            tool_version: "0".into(),
            shrink_steps: vec![],
        },
        note: String::new(),
        samples: SampleSet::Any,
        snap: None,
        viewport: None,
    }
}

#[test]
fn round_bits_keeps_the_leading_bits() {
    assert_eq!(round_bits(1.0, 4), 1.0);
    assert_eq!(round_bits(1.1, 4), 1.125);
    assert_eq!(round_bits(-3.3, 8), -3.296875);
}

#[test]
fn a_bad_field_is_named_with_the_file() {
    let dir = std::env::temp_dir().join(format!("cullproof-corpus-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.json");
    let mut v = serde_json::to_value(fixture(3)).unwrap();
    v["case"]["triangle"]["q"][1][2] = serde_json::json!("oops");
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let e = CaseFile::load(&p).unwrap_err().to_string();
    assert!(e.contains("bad.json") && e.contains("case.triangle.q[1][2]"), "{e}");
    v["case"]["triangle"]["q"][1][2] = serde_json::json!(1.0);
    v["tile"]["x1"] = v["tile"]["x0"].clone();
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let e = CaseFile::load(&p).unwrap_err().to_string();
    assert!(e.contains("bad.json") && e.contains("tile.x1"), "{e}");
    v["method"] = serde_json::json!("nope");
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let e = CaseFile::load(&p).unwrap_err().to_string();
    assert!(e.contains("method") && e.contains("nope"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn writing_never_overwrites() {
    let dir = std::env::temp_dir().join(format!("cullproof-corpus-write-{}", std::process::id()));
    let mut cf = fixture(5);
    cf.note = "first".into();
    let p = cf.write_new(&dir).unwrap().expect("written");
    cf.note = "second".into();
    assert_eq!(cf.write_new(&dir).unwrap(), None);
    assert!(std::fs::read_to_string(&p).unwrap().contains("first"));
    assert_eq!(CaseFile::load(&p).unwrap().note, "first");
    std::fs::remove_dir_all(&dir).unwrap();
}
