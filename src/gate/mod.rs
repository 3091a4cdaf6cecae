//! The gate: run cases x methods through the judge, hold each method x regime row
//! against its expectations and the stored baseline, and report (text, JSON, JUnit),
//! merge shards and measure the gate's power.
//!
//! - [`engine`]: the run's settings ([`CheckConfig`]) and the run itself;
//! - [`expect`], [`baseline`], [`row`], [`strength`]: what a row is held against, and
//!   each method's strongest verdict;
//! - [`report`], [`junit`], [`merge`], [`settings`], [`tool`]: the report, its JUnit
//!   form, shards merged into one, the settings a report records, the tool's identity;
//! - [`power`]: planted slips run through the gate;
//! - [`locate`]: where the expectations and the baseline are found;
//! - [`builder`]: the gate as a library ([`Gate`], [`GateReport`]).

pub mod baseline;
pub mod builder;
pub mod case_file;
pub mod engine;
pub mod expect;
pub mod junit;
pub mod locate;
pub mod merge;
pub mod power;
pub mod report;
pub mod row;
pub mod settings;
pub mod strength;
pub mod tool;

pub use builder::{Bound, Counterexample, Gate, GateReport, MethodReport, MethodVerdict, Unproven};
pub use engine::*;
pub use expect::{Allowance, Cap, Entry, Expectations, Expected};
pub use report::{render, CheckReport, CrossCheck};
pub use row::{Row, Status};
pub use strength::{MethodStrength, Strength};
