//! Bounds that live outside this crate, behind the same contract as the built-in ones
//! ([`crate::bounds::Method`]): a C library loaded into the process ([`plugin`],
//! `include/cullproof.h`) and a program in another process that answers the JSON-lines
//! protocol ([`exec`], `docs/protocol.md`).

pub mod exec;
pub mod plugin;
