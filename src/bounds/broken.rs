//! Deliberately broken bounds: the slips a hand-derived bound makes, used to show that
//! the gate and the search catch them (tests, and `cullproof search --method
//! broken/...` to measure the time to the first counterexample). Never in the registry.
//!
//! Each is a slip planted into any method at run time (no rebuild), so the gate's
//! power can be measured over every method x slip in one run (`cullproof power`):
//!
//! - `broken/shrink/<id>`: the method's u^, v^, t^ pulled in by 1e-3 at both ends.
//! - `broken/shrink-rel/<id>`: each narrowed end pulled in by 1e-5 of its interval's
//!   width (a slip as small as a rounding, far from the origin as near it).
//! - `broken/no-coc-pad/<id>`: the method run on the triangle with its circles of
//!   confusion dropped (the lens padding term forgotten), so defocus is ignored.
//! - `broken/t0-only/<id>`: the method run on the triangle frozen at its t = 0
//!   positions (the motion forgotten).
//! - `broken/swap-coc/<id>`: the CoCs at t = 0 and t = 1 swapped.
//! - `broken/half-tile/<id>`: the method asked about the tile shrunk by half its size
//!   around its centre (a dropped tile half-size).
//! - `broken/loose/<id>`: every narrowed end moved out by 1e-3 (not a violation: a
//!   loss of tightness, which the baseline comparison must see).
//! - `broken/loose-t-max/<id>`: only the upper end of t moved out by 1e-3 (one end:
//!   the tightness signature must see it at any seed and case count). Not in
//!   `cullproof power`'s list.
//!
//! Eighteen more, `broken/planted-eq/bbox-safe`, `broken/planted-band/bbox-safe`, and
//! `broken/planted-no-up/M-safe` and `broken/planted-no-dn/M-safe` for M = `bbox`,
//! `la2011`, `nilsson2012-depth`, `mam2012`, `wu2013`, `gdam2010`, `lb2011` and `lc`, are rare slips
//! planted in the `-safe` variants themselves ([`planted`]), not in `cullproof power`.

pub mod planted;

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

/// Moves each narrowed end of the answer: `f(lo, hi, domain_lo, domain_hi)` gives
/// the new ends.
struct Moved {
    inner: &'static dyn Method,
    info: &'static MethodInfo,
    f: fn([f32; 2], f32, f32) -> [f32; 2],
}
struct MovedP(Box<dyn Prepared>, fn([f32; 2], f32, f32) -> [f32; 2]);
impl Prepared for MovedP {
    fn tile(&self, t: &Tile) -> TileResult {
        match self.0.tile(t) {
            TileResult::Empty => TileResult::Empty,
            TileResult::Bounds(mut b) => {
                b.u = (self.1)(b.u, -1.0, 1.0);
                b.v = (self.1)(b.v, -1.0, 1.0);
                b.t = (self.1)(b.t, 0.0, 1.0);
                TileResult::Bounds(b)
            }
        }
    }
}
impl Method for Moved {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(MovedP(self.inner.setup(tri), self.f))
    }
}

fn shrink_rel(r: [f32; 2], lo: f32, hi: f32) -> [f32; 2] {
    let d = 1e-5 * (r[1] - r[0]).max(0.0);
    [if r[0] > lo { r[0] + d } else { r[0] }, if r[1] < hi { r[1] - d } else { r[1] }]
}

fn loosen(r: [f32; 2], lo: f32, hi: f32) -> [f32; 2] {
    [if r[0] > lo { (r[0] - 1e-3).max(lo) } else { r[0] }, if r[1] < hi { (r[1] + 1e-3).min(hi) } else { r[1] }]
}

fn loosen_t_max(r: [f32; 2], lo: f32, hi: f32) -> [f32; 2] {
    // (t is the only coordinate whose domain is [0, 1])
    if (lo, hi) == (0.0, 1.0) && r[1] < hi {
        [r[0], (r[1] + 1e-3).min(hi)]
    } else {
        r
    }
}

/// Runs the method on a changed triangle.
struct OnTriangle {
    inner: &'static dyn Method,
    info: &'static MethodInfo,
    f: fn(&Triangle) -> Triangle,
}
impl Method for OnTriangle {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        self.inner.setup(&(self.f)(tri))
    }
}

fn t0_only(t: &Triangle) -> Triangle {
    Triangle { r: t.q, c1: t.c0, ..*t }
}

fn swap_coc(t: &Triangle) -> Triangle {
    Triangle { c0: t.c1, c1: t.c0, ..*t }
}

/// Asks the method about the tile shrunk by half around its centre.
struct HalfTile {
    inner: &'static dyn Method,
    info: &'static MethodInfo,
}
struct HalfTileP(Box<dyn Prepared>);
impl Prepared for HalfTileP {
    fn tile(&self, t: &Tile) -> TileResult {
        let (qx, qy) = (0.25 * (t.x1 - t.x0), 0.25 * (t.y1 - t.y0));
        self.0.tile(&Tile { x0: t.x0 + qx, x1: t.x1 - qx, y0: t.y0 + qy, y1: t.y1 - qy })
    }
}
impl Method for HalfTile {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(HalfTileP(self.inner.setup(tri)))
    }
}

/// The slips `parse` knows, in the order `cullproof power` tries them.
pub const KINDS: [&str; 7] = ["shrink", "shrink-rel", "no-coc-pad", "t0-only", "swap-coc", "half-tile", "loose"];

/// The id of the method a broken variant breaks ("la2011" for "broken/shrink/la2011");
/// any other id is returned as it is.
pub fn inner_id(id: &str) -> &str {
    id.strip_prefix("broken/").and_then(|r| r.split_once('/')).map_or(id, |(_, inner)| inner)
}

/// The broken variant named `id` ("broken/shrink/la2011"), if it is one.
pub fn parse(id: &str) -> Option<&'static dyn Method> {
    // The rare slips planted for the symbolic search ([`planted`]).
    if let Some(m) = planted::parse(id) {
        return Some(m);
    }
    let rest = id.strip_prefix("broken/")?;
    let (kind, inner) = rest.split_once('/')?;
    let inner = by_id(inner)?;
    let name: &'static str = Box::leak(id.to_string().into_boxed_str());
    let info: &'static MethodInfo = Box::leak(Box::new(MethodInfo { id: name, ..*inner.info() }));
    let m: &'static dyn Method = match kind {
        "shrink" => Box::leak(Box::new(Shrunk { inner, info })),
        "no-coc-pad" => Box::leak(Box::new(NoCoc { inner, info })),
        "shrink-rel" => Box::leak(Box::new(Moved { inner, info, f: shrink_rel })),
        "loose" => Box::leak(Box::new(Moved { inner, info, f: loosen })),
        "loose-t-max" => Box::leak(Box::new(Moved { inner, info, f: loosen_t_max })),
        "t0-only" => Box::leak(Box::new(OnTriangle { inner, info, f: t0_only })),
        "swap-coc" => Box::leak(Box::new(OnTriangle { inner, info, f: swap_coc })),
        "half-tile" => Box::leak(Box::new(HalfTile { inner, info })),
        _ => return None,
    };
    Some(m)
}
