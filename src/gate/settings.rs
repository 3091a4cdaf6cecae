//! What a run was: the settings a baseline entry belongs to ([`Settings`]) and the
//! run a report describes ([`RunInfo`]: its methods, settings and shard), which
//! `cullproof merge` holds equal across the shards of one run.

use super::CheckConfig;
use crate::model::{SampleSet, Snap, Viewport};
use serde::{Deserialize, Serialize};

/// The settings a baseline belongs to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    pub seed: u64,
    pub cases: u64,
    pub regimes: Vec<String>,
    pub tile: Option<f32>,
    pub samples: usize,
    pub side_budget: usize,
    pub side_stall: usize,
    pub constraint_budget: usize,
    pub limit_every: u64,
    pub limit_budget: usize,
    /// The sample set, snap and viewport (`centres`, `msaa4 snap 8 viewport
    /// 1920x1080+64`, ...); absent for the defaults, so older entries still match.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sample_set: Option<String>,
    /// The judge's second chance (`--second-chance`); absent when off.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub second_chance: bool,
}

impl Settings {
    /// The settings of a run (None for a timed or sharded run, which has no fixed
    /// case set to compare).
    pub fn of(cfg: &CheckConfig) -> Option<Settings> {
        (cfg.time.is_none() && cfg.shard == (0, 1)).then(|| Settings::whole(cfg))
    }

    /// Whether the measured parts of a signature (the limit-tile rate cap and the
    /// admitted share, see [`super::expect::Entry::max_admit`]) hold for a run with
    /// these settings: they were measured with tile sizes drawn per case, every pixel
    /// position, no snapping and no viewport, and a fixed tile size or a placement
    /// changes what a correct method admits and how often its limit tiles fail.
    pub fn measured(&self) -> bool {
        self.tile.is_none() && self.sample_set.is_none()
    }

    /// The settings of the whole run a (possibly sharded) run belongs to.
    pub fn whole(cfg: &CheckConfig) -> Settings {
        Settings {
            seed: cfg.seed,
            cases: cfg.cases,
            regimes: cfg.regimes.iter().map(|r| r.name().to_string()).collect(),
            tile: cfg.tile,
            samples: cfg.samples,
            side_budget: cfg.judge.side_budget,
            side_stall: cfg.judge.side_stall,
            constraint_budget: cfg.judge.constraint_budget,
            limit_every: cfg.limit_every,
            limit_budget: cfg.limit_budget,
            sample_set: SetNote::of(cfg, 0).map(|n| n.key()),
            second_chance: cfg.judge.extents.second_chance,
        }
    }
}

/// What a run was: its methods and settings, for checking that shards belong together.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunInfo {
    /// Method ids, in the run's order.
    pub methods: Vec<String>,
    /// The settings (seed, cases of the whole run, regimes, tile, budgets).
    pub settings: Settings,
    /// Shard `[k, n]` of the run.
    pub shard: [u64; 2],
    /// A run for a time (`--time`): its cases depend on the machine; not mergeable.
    pub timed: bool,
}

impl RunInfo {
    /// The run described by a configuration.
    pub fn of(cfg: &CheckConfig) -> RunInfo {
        RunInfo {
            methods: cfg.methods.iter().map(|m| m.info().id.to_string()).collect(),
            settings: Settings::whole(cfg),
            shard: [cfg.shard.0, cfg.shard.1],
            timed: cfg.time.is_some(),
        }
    }
}

/// The sample set, snapping and viewport of a run as the reports name them (absent
/// from a report of the defaults).
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct SetNote {
    /// `any`, `centres`, `msaa4`, `grid8`, ...
    pub set: SampleSet,
    /// Snap grid in bits below the pixel.
    pub snap: Option<Snap>,
    pub viewport: Option<Viewport>,
    /// Cases whose regime gave no draw that fits the viewport's guard band (not judged).
    pub outside_viewport: u64,
}

impl SetNote {
    /// None for the defaults (any position, no snap, no viewport).
    pub fn of(cfg: &CheckConfig, outside_viewport: u64) -> Option<SetNote> {
        let default = cfg.sample_set.is_any() && cfg.snap.is_none() && cfg.viewport.is_none();
        (!default).then_some(SetNote { set: cfg.sample_set, snap: cfg.snap, viewport: cfg.viewport, outside_viewport })
    }
    /// The short form the baseline's settings carry: `centres`, `msaa4 snap 8
    /// viewport 1920x1080+64`.
    pub fn key(&self) -> String {
        let mut s = self.set.to_string();
        if let Some(n) = self.snap {
            s += &format!(" snap {n}");
        }
        if let Some(v) = self.viewport {
            s += &format!(" viewport {v}");
        }
        s
    }
    /// One line for the table's header.
    pub fn line(&self) -> String {
        let mut s = format!("samples: {}", self.set);
        if let Some(n) = self.snap {
            s += &format!(", vertices snapped to 2^-{} px", n.bits);
        }
        if let Some(v) = self.viewport {
            s += &format!(", viewport {v}");
            if self.outside_viewport > 0 {
                s += &format!(" ({} cases could not be placed in it, not judged)", self.outside_viewport);
            }
        }
        s
    }
}
