//! The gate's judge under proptest: cases from `gen::strategy` (the seeded generator's
//! builder fed by a shrinkable tape), a tile on the footprint's boundary. bbox must stay
//! conservative in every regime; a deliberately broken bound must be caught, and the
//! case proptest shrinks it to must still be a certified violation. Failures of the
//! conservative property are kept in corpus/proptest-regressions/ (the regression inbox:
//! proptest replays them first on every run).

use cullproof::bounds::Method;
use cullproof::cases::generate::{boundary_tile, rng_for, strategy, Regime};
use cullproof::gate::{judge, CheckConfig};
use cullproof::model::{Case, Tile};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, RngAlgorithm, TestError, TestRng, TestRunner};

/// A case of the regime and a boundary tile of 1..16 px.
fn case_and_tile(regime: Regime) -> impl Strategy<Value = (Case, Tile)> {
    (strategy::case(regime), 0usize..5, any::<u64>()).prop_map(|(case, k, seed)| {
        let size = [1.0f32, 2.0, 4.0, 8.0, 16.0][k];
        let tile = boundary_tile(&case, &mut rng_for(seed, 0), size);
        (case, tile)
    })
}

fn violates(m: &'static dyn Method, case: &Case, tile: &Tile) -> bool {
    let cfg = CheckConfig::default_with(vec![m]);
    judge(&cfg, &cfg.methods, case, tile, 0).0[0].violation.is_some()
}

#[test]
fn bbox_is_conservative_in_every_regime() {
    let bbox = cullproof::bounds::by_id("bbox").unwrap();
    for regime in Regime::ALL {
        let cfg = Config {
            cases: 12,
            failure_persistence: Some(Box::new(FileFailurePersistence::Direct("corpus/proptest-regressions/bbox.txt"))),
            ..Config::default()
        };
        let r = TestRunner::new(cfg).run(&case_and_tile(regime), |(case, tile)| {
            prop_assert!(!violates(bbox, &case, &tile), "bbox culls a covered sample: {case:?} {tile:?}");
            Ok(())
        });
        if let Err(e) = r {
            panic!("{}: {e}", regime.name());
        }
    }
}

#[test]
fn a_shrunk_bound_is_caught_and_its_shrunk_case_still_violates() {
    let m = cullproof::bounds::broken::parse("broken/shrink/bbox").unwrap();
    let cfg = Config { cases: 256, failure_persistence: None, ..Config::default() };
    let rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
    let mut runner = TestRunner::new_with_rng(cfg, rng);
    let r = runner.run(&case_and_tile(Regime::Motion), |(case, tile)| {
        prop_assert!(!violates(m, &case, &tile));
        Ok(())
    });
    match r {
        Err(TestError::Fail(_, (case, tile))) => {
            case.validate().unwrap();
            assert!(violates(m, &case, &tile), "the shrunk case no longer violates");
            // and the correct bound is conservative on it
            assert!(!violates(cullproof::bounds::by_id("bbox").unwrap(), &case, &tile));
        }
        other => panic!("the shrunk bbox was not caught in 256 cases: {other:?}"),
    }
}
