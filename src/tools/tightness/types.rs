//! The settings of a measurement ([`Config`]) and what it reports: the counts and the
//! work per method, tile size and setting, the ceilings, and the summary per setting.

use super::pattern::Pattern;
use super::scene::Setting;
use oracles::extents::ExtentsConfig;
use serde::Serialize;

/// Settings of a measurement.
#[derive(Clone, Debug)]
pub struct Config {
    /// Tile sizes in pixels.
    pub tiles: Vec<u32>,
    pub pattern: Pattern,
    /// Tiles per (setting, tile size) given a certified ceiling (0: none; at least the
    /// number traversed, e.g. `usize::MAX`: every one).
    pub certified_tiles: usize,
    /// Solver settings of the certified ceiling.
    pub certified: ExtentsConfig,
    /// Seed of the certified subset.
    pub seed: u64,
}

impl Config {
    pub fn new(tiles: Vec<u32>, pattern: Pattern) -> Self {
        Config {
            tiles,
            pattern,
            certified_tiles: 0,
            certified: ExtentsConfig { resolution: 1e-2, max_boxes: 2000, ..ExtentsConfig::default() },
            seed: pattern.seed,
        }
    }
}

/// Samples let through and covered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Samples the method lets through (tile not culled, every per-sample test passed).
    pub tested: u64,
    /// Tested samples that are interior-covered.
    pub hits: u64,
    /// Interior-covered samples the method culls (0 for a conservative method).
    pub missed: u64,
}

impl Counts {
    pub(super) fn add(&mut self, o: &Counts) {
        self.tested += o.tested;
        self.hits += o.hits;
        self.missed += o.missed;
    }
}

/// The operations a method performed (the work the cost model charges, see [`cost`]):
/// on the triangles where it was enabled, and on those where it disabled itself (its
/// answer then is the whole domain: bbox's work, and charged as bbox's).
///
/// [`cost`]: super::cost
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Work {
    /// Triangles set up.
    pub setups: u64,
    /// Tile tests.
    pub tile_tests: u64,
    /// Samples given the per-sample test (every sample of a tile not culled).
    pub sample_tests: u64,
    pub disabled_setups: u64,
    pub disabled_tile_tests: u64,
    pub disabled_sample_tests: u64,
}

impl Work {
    pub(super) fn add_setup(&mut self, disabled: bool) {
        *if disabled { &mut self.disabled_setups } else { &mut self.setups } += 1;
    }
    pub(super) fn add_tile(&mut self, disabled: bool, samples: u64) {
        if disabled {
            self.disabled_tile_tests += 1;
            self.disabled_sample_tests += samples;
        } else {
            self.tile_tests += 1;
            self.sample_tests += samples;
        }
    }
    pub(super) fn add(&mut self, o: &Work) {
        self.setups += o.setups;
        self.tile_tests += o.tile_tests;
        self.sample_tests += o.sample_tests;
        self.disabled_setups += o.disabled_setups;
        self.disabled_tile_tests += o.disabled_tile_tests;
        self.disabled_sample_tests += o.disabled_sample_tests;
    }
}

/// One method at one tile size and setting.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodRow {
    pub method: String,
    /// Built from a reconstruction (`docs/reconstructions.md`), not from the paper itself.
    pub reconstruction: bool,
    /// The method has per-sample constraints (it is not an interval-only test).
    pub per_sample: bool,
    pub setting: Setting,
    pub tile: u32,
    #[serde(flatten)]
    pub counts: Counts,
    /// hits / tested (None when nothing was tested).
    pub ste: Option<f64>,
    /// Triangles for which the method reported itself disabled (full bounds).
    pub disabled_triangles: u64,
    /// The operations performed.
    pub work: Work,
}

/// The sample ceiling at one tile size and setting (an upper bound on the STE of the
/// tightest interval-only test).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CeilingRow {
    pub setting: Setting,
    pub tile: u32,
    /// Pattern samples inside each tile's box of covered-sample (u, v, t) extents.
    pub tested: u64,
    /// Interior-covered samples (all lie in those boxes).
    pub covered: u64,
    pub ste: Option<f64>,
}

/// The certified ceiling on a random subset of tiles.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CertifiedRow {
    pub setting: Setting,
    pub tile: u32,
    /// (triangle, tile) pairs solved.
    pub tiles: u64,
    /// Of those, tiles where the solver left boxes open (enclosures wider than the
    /// resolution, or occupancy unknown).
    pub undecided_tiles: u64,
    /// Interior-covered pattern samples in those tiles.
    pub covered: u64,
    /// Pattern samples inside the outer certified extents box (contains the exact box).
    pub tested_certified: u64,
    /// Pattern samples inside the covered-sample box (inside the exact box).
    pub tested_sample_box: u64,
    /// covered / tested_certified: a lower bound on the true ceiling over these tiles.
    pub ste_lower: Option<f64>,
    /// covered / tested_sample_box: an upper bound on it.
    pub ste_upper: Option<f64>,
    /// Boxes the solver examined.
    pub boxes: u64,
}

/// What happened to the triangles of one setting.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SettingSummary {
    pub setting: Setting,
    pub triangles: u64,
    /// Triangles with a vertex at w <= 0: traversed over the whole screen.
    pub whole_screen: u64,
    /// Triangles whose footprint misses the screen: skipped.
    pub off_screen: u64,
    /// Samples classified by the exact oracle.
    pub samples_classified: u64,
    /// Interior-covered samples (the numerator of every method's STE when it misses none).
    pub covered: u64,
    /// Samples on an edge (not covered by the interior rule).
    pub boundary: u64,
    /// Samples decided by exact dyadic arithmetic: those whose signs neither the batched
    /// oracle's lanes nor the scalar oracle's floating-point filter could certify.
    pub exact_fallbacks: u64,
}

/// The result of [`measure`].
///
/// [`measure`]: super::measure
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Measurement {
    pub settings: Vec<SettingSummary>,
    pub rows: Vec<MethodRow>,
    pub ceiling: Vec<CeilingRow>,
    pub certified: Vec<CertifiedRow>,
}
