//! The judge: certified verdicts on one method's answer for one tile. Each claim is
//! proven (certified by the exact oracles, no gap left), violated (a covered interior
//! sample the answer culls, confirmed exactly) or left unproven with its reason.
//!
//! - [`tile`]: the verdict on a tile answer (its intervals, depth range and tile
//!   reject), side by side, and its witnesses;
//! - [`constraints`]: the certified search over the per-sample constraints, with the
//!   cuts of [`side_cut`] (an interval side left with a gap) and [`depth_cut`] (a depth
//!   end);
//! - [`agree`]: the second opinion (Embree, f32) and the oracles' agreement.

pub mod agree;
pub mod constraints;
pub mod depth_cut;
pub mod sample_set;
pub mod side_cut;
pub mod tile;

pub(crate) use tile::TileJudge;
pub use tile::{bound_kind, culled_by, in_domain, JudgeSettings, Judgement, Unproven, Verdict, Witness};
