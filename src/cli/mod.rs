//! The commands of the `cullproof` binary, one file each (the variants of `Cmd` in
//! `main.rs` wrap their arguments), and the helpers they share.

pub mod check;
pub mod common;
pub mod explain;
pub mod merge;
pub mod methods;
pub mod oracle_agree;
pub mod power;
pub mod prove;
pub mod replay;
pub mod search;
