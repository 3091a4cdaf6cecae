//! Deliberately broken bounds: the slips a hand-derived bound makes, used to show that
//! the gate and the search catch them (tests, and `cullproof search --method
//! broken/...` to measure the time to the first counterexample). Never in the registry.
//!
//! - `broken/shrink/<id>`: the method's u^, v^, t^ pulled in by 1e-3 at both ends.
//! - `broken/no-coc-pad/<id>`: the method run on the triangle with its circles of
//!   confusion dropped (the lens padding term forgotten), so defocus is ignored.

use super::{by_id, Method, MethodInfo, Prepared, TileResult};
use crate::model::{Tile, Triangle};

/// How much `broken/shrink` pulls each interval in.
pub const SHRINK: f32 = 1e-3;

struct Shrunk {
    inner: &'static dyn Method,
    info: &'static MethodInfo,
}
struct ShrunkP(Box<dyn Prepared>);
impl Prepared for ShrunkP {
    fn tile(&self, t: &Tile) -> TileResult {
        match self.0.tile(t) {
            TileResult::Empty => TileResult::Empty,
            TileResult::Bounds(mut b) => {
                b.u = [b.u[0] + SHRINK, b.u[1] - SHRINK];
                b.v = [b.v[0] + SHRINK, b.v[1] - SHRINK];
                b.t = [b.t[0] + SHRINK, b.t[1] - SHRINK];
                TileResult::Bounds(b)
            }
        }
    }
}
impl Method for Shrunk {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(ShrunkP(self.inner.setup(tri)))
    }
}

struct NoCoc {
    inner: &'static dyn Method,
    info: &'static MethodInfo,
}
impl Method for NoCoc {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let mut t = *tri;
        t.c0 = [0.0; 3];
        t.c1 = [0.0; 3];
        self.inner.setup(&t)
    }
}

/// The broken variant named `id` ("broken/shrink/la2011"), if it is one.
pub fn parse(id: &str) -> Option<&'static dyn Method> {
    let rest = id.strip_prefix("broken/")?;
    let (kind, inner) = rest.split_once('/')?;
    let inner = by_id(inner)?;
    let name: &'static str = Box::leak(id.to_string().into_boxed_str());
    let info: &'static MethodInfo = Box::leak(Box::new(MethodInfo { id: name, ..*inner.info() }));
    let m: &'static dyn Method = match kind {
        "shrink" => Box::leak(Box::new(Shrunk { inner, info })),
        "no-coc-pad" => Box::leak(Box::new(NoCoc { inner, info })),
        _ => return None,
    };
    Some(m)
}
