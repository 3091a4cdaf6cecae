//! Contract-breach accounting: the kinds of breach, each plugin's counters, and the
//! counts per plugin ([`breaches`], [`breaches_since`]).

use super::method::PluginMethod;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::Mutex;

/// Kinds of contract breach, counted per plugin (the names are the keys of
/// [`ContractBreaches::kinds`]).
#[derive(Clone, Copy)]
pub(super) enum Breach {
    TileCode,
    TileNan,
    TileInfinite,
    TileInverted,
    TileNoEval,
    EvalBoxNan,
    EvalBoxInverted,
    FpEnv,
}

const BREACHES: usize = 8;

impl Breach {
    pub(super) const ALL: [Breach; BREACHES] = [
        Breach::TileCode,
        Breach::TileNan,
        Breach::TileInfinite,
        Breach::TileInverted,
        Breach::TileNoEval,
        Breach::EvalBoxNan,
        Breach::EvalBoxInverted,
        Breach::FpEnv,
    ];
    fn key(self) -> &'static str {
        match self {
            Breach::TileCode => "tile-answer-code",
            Breach::TileNan => "tile-nan-end",
            Breach::TileInfinite => "tile-infinite-end",
            Breach::TileInverted => "tile-lo-above-hi",
            Breach::TileNoEval => "tile-constraints-without-eval",
            Breach::EvalBoxNan => "eval-box-nan-end",
            Breach::EvalBoxInverted => "eval-box-lo-above-hi",
            Breach::FpEnv => "fp-environment",
        }
    }
    fn words(self) -> &'static str {
        match self {
            Breach::TileCode => "tile() answers neither CP_EMPTY nor CP_BOUNDS (taken as CP_EMPTY)",
            Breach::TileNan => "tile() answers with a NaN interval end (culls every sample)",
            Breach::TileInfinite => "tile() answers with an infinite end of u, v or t (taken as given)",
            Breach::TileInverted => "tile() answers with lo > hi (culls every sample)",
            Breach::TileNoEval => "tile() answers with constraints but `eval` is NULL (ignored)",
            Breach::EvalBoxNan => "eval_box() enclosures with a NaN end (taken as the whole line)",
            Breach::EvalBoxInverted => "eval_box() enclosures with lo > hi (taken as the whole line)",
            Breach::FpEnv => {
                "the floating-point environment was left with flush-to-zero, denormals-are-zero or a rounding \
                 mode other than to nearest (by loading the library or by a call; reset to the standard one)"
            }
        }
    }
}

/// A plugin's contract breaches: answers that break include/cullproof.h, each judged
/// as the module doc says (the verdicts are those of the answer as given).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContractBreaches {
    /// The method id.
    pub method: String,
    /// The library, as given to `--plugin`.
    pub plugin: String,
    /// Answers that broke the contract.
    pub answers: u64,
    /// Of those, per kind of breach (an answer may show several).
    pub kinds: BTreeMap<String, u64>,
}

impl ContractBreaches {
    /// The line the command line prints at the end of a run.
    pub fn line(&self) -> String {
        let kinds: Vec<String> =
            Breach::ALL.iter().filter_map(|b| self.kinds.get(b.key()).map(|n| format!("{n} {}", b.words()))).collect();
        format!(
            "plugin {} (`{}`): {} answers broke the contract of include/cullproof.h: {}; each was judged by \
             that reading, as the header says",
            self.plugin,
            self.method,
            self.answers,
            kinds.join(", ")
        )
    }
}

/// Breach counters of one plugin.
#[derive(Default)]
pub(super) struct Counters {
    pub(super) answers: AtomicU64,
    pub(super) kinds: [AtomicU64; BREACHES],
}

/// Every plugin loaded so far, in load order.
pub(super) static LOADED: Mutex<Vec<&'static PluginMethod>> = Mutex::new(Vec::new());

/// The contract breaches of every plugin loaded in this process so far (zero counts
/// included), in load order.
pub fn breaches() -> Vec<ContractBreaches> {
    let loaded = LOADED.lock().unwrap_or_else(|e| e.into_inner()).clone();
    loaded
        .iter()
        .map(|m| ContractBreaches {
            method: m.info.id.to_string(),
            plugin: m.path.clone(),
            answers: m.breaches.answers.load(Relaxed),
            kinds: Breach::ALL
                .iter()
                .map(|b| (b.key().to_string(), m.breaches.kinds[*b as usize].load(Relaxed)))
                .filter(|(_, n)| *n > 0)
                .collect(),
        })
        .collect()
}

/// The breaches since `before` (an earlier [`breaches`]), plugins with none left out:
/// what one run added.
pub fn breaches_since(before: &[ContractBreaches]) -> Vec<ContractBreaches> {
    breaches()
        .into_iter()
        .filter_map(|mut now| {
            if let Some(b) = before.iter().find(|b| b.method == now.method) {
                now.answers -= b.answers;
                for (k, n) in now.kinds.iter_mut() {
                    *n -= b.kinds.get(k).copied().unwrap_or(0);
                }
                now.kinds.retain(|_, n| *n > 0);
            }
            (now.answers > 0).then_some(now)
        })
        .collect()
}
