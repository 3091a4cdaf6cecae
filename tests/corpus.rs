//! Corpus replay: every case file under corpus/cases parses, names a known method, and
//! still shows what it expects (a stored witness of a violation is re-decided exactly
//! and must still be interior and culled).

use cullproof::gate::CheckConfig;
use cullproof::search::{case_files, replay, CaseFile, Verdict};
use std::path::PathBuf;

#[test]
fn every_corpus_case_replays_as_expected() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/cases");
    let files = case_files(&[dir]).unwrap();
    assert!(!files.is_empty(), "the corpus holds no case files");
    let cfg = CheckConfig::default_with(cullproof::bounds::registry());
    let mut bad = Vec::new();
    for f in &files {
        let r = replay(f, &cfg).unwrap();
        if !r.ok {
            bad.push(format!("{}: expected {:?}, judged {}, witness {:?}", r.path, r.expected, r.judged, r.witness));
        }
        let cf = CaseFile::load(f).unwrap();
        if cf.expected == Verdict::Violation {
            assert!(cf.witness.is_some(), "{}: a violation case must carry its witness", f.display());
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn every_expected_violation_is_backed_by_a_case_file() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let ex = cullproof::gate::Expectations::load(&root.join("corpus/expectations.json")).unwrap();
    let files = case_files(&[root.join("corpus/cases")]).unwrap();
    let cases: Vec<CaseFile> = files.iter().map(|f| CaseFile::load(f).unwrap()).collect();
    for (method, regimes) in &ex.0 {
        if regimes.values().any(|e| e.expect == cullproof::gate::Expected::Violation) {
            assert!(
                cases.iter().any(|c| &c.method == method && c.expected == Verdict::Violation),
                "{method}: expected to violate, but no case file in corpus/cases/{method}"
            );
        }
    }
}

#[test]
fn explain_renders_every_corpus_case() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for f in case_files(&[root.join("corpus/cases")]).unwrap() {
        let cf = CaseFile::load(&f).unwrap();
        let text = cullproof::search::describe(&cf);
        assert!(text.contains(&cf.method), "{}: the description does not name the method", f.display());
        // Extents only in the dimensions the triangle has.
        let t = &cf.case.triangle;
        let (lens, time) = (t.c0.iter().chain(&t.c1).any(|&c| c != 0.0), t.q != t.r || t.c0 != t.c1);
        if let Some(at) = text.find("exact extents of the covered samples") {
            let section = text[at..].split("witness").next().unwrap_or_default();
            for (dim, has, name) in [("u min", lens, "lens"), ("t min", time, "time")] {
                assert_eq!(
                    section.contains(dim),
                    has,
                    "{}: the {name} extents are shown exactly when the triangle has that dimension\n{text}",
                    f.display()
                );
            }
        }
        let m = cullproof::bounds::by_id(&cf.method).unwrap();
        let w = cf.witness.as_ref().map(|w| w.sample).unwrap_or_else(|| {
            let (x, y) = cf.tile.center();
            [x as f64, y as f64, 0.0, 0.0, 0.5]
        });
        let svg = cullproof::search::explain::svg(&cf.case, &cf.tile, m, w, "corpus test")
            .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        assert!(svg.starts_with("<svg") && svg.contains("witness"), "{}: not a picture of the witness", f.display());
    }
}

/// A stored witness outside the lens/shutter domain never holds, and a violation file
/// whose fresh judgement disagrees does not replay as ok.
#[test]
fn a_witness_outside_the_domain_does_not_replay() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let files = case_files(&[root.join("corpus/cases")]).unwrap();
    let cfg = CheckConfig::default_with(cullproof::bounds::registry());
    let dir = std::env::temp_dir().join(format!("cullproof-domain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut tried = 0;
    for f in &files {
        let mut cf = CaseFile::load(f).unwrap();
        let Some(w) = cf.witness.as_mut() else { continue };
        if cf.expected != Verdict::Violation {
            continue;
        }
        // Step one coordinate of the lens or shutter just outside the domain.
        let k = 2 + tried % 3;
        w.sample[k] = if k == 4 { 1.0 + f32::EPSILON as f64 } else { -1.0 - f32::EPSILON as f64 };
        let p = dir.join(format!("{tried}.json"));
        std::fs::write(&p, serde_json::to_string(&cf).unwrap()).unwrap();
        let r = replay(&p, &cfg).unwrap();
        assert!(!r.ok, "{}: a witness outside the domain replayed as ok", f.display());
        match &r.witness {
            Some(Err(why)) => assert!(why.contains("domain"), "{why}"),
            other => panic!("{}: {other:?}", f.display()),
        }
        tried += 1;
        if tried == 6 {
            break;
        }
    }
    assert_eq!(tried, 6);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn replay_with_another_method_says_fixed_or_still_violated() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/la2011");
    let files = case_files(&[dir]).unwrap();
    assert!(!files.is_empty());
    let cfg = CheckConfig::default_with(cullproof::bounds::registry());
    let none = cullproof::gate::Declared::default();
    for f in &files {
        // The safe variant admits every stored witness and is proven on the case.
        let r = cullproof::search::rejudge(f, &cfg, &none, "la2011-safe").unwrap();
        assert_eq!((r.outcome, r.found_for.as_str()), ("fixed", "la2011"), "{}: {r:?}", f.display());
        assert!(matches!(r.witness, Some(Err(_))), "{r:?}");
        // The published method still culls its own witness.
        let r = cullproof::search::rejudge(f, &cfg, &none, "la2011").unwrap();
        assert_eq!(r.outcome, "still violated", "{}: {r:?}", f.display());
    }
    let e = cullproof::search::rejudge(&files[0], &cfg, &none, "no-such-bound").unwrap_err().to_string();
    assert!(e.contains("no-such-bound"), "{e}");
}
