//! `la2011` and `la2011-safe` as they were before their tile path was written over
//! `F32Arith` (kept verbatim, the method's metadata aside): the reference the encoded
//! code is compared with, bit for bit.
#![allow(dead_code)]

use cullproof::bounds::{Prepared, TileBounds, TileResult};
use cullproof::{Tile, Triangle};
use std::marker::PhantomData;

/// An f32 interval `[lo, hi]`; in `la2011` both ends are the one rounded value.
type Iv = [f32; 2];

/// How a value rounded to nearest becomes a bound: `la2011` keeps it as it is (the
/// published arithmetic), `la2011-safe` steps it one f32 value outward.
trait Round: 'static {
    /// A value `<=` the exact result that `x` is the rounding (to nearest) of.
    fn dn(x: f32) -> f32;
    /// A value `>=` it.
    fn up(x: f32) -> f32;
    /// A computed value that must not be used (the quantity falls back to its full range).
    fn bad(x: f32) -> bool;
    /// Non-finite input (triangle or tile) gives the full domain before any arithmetic.
    const GUARD: bool;
}

/// `la2011`: round to nearest, no steps; only NaN falls back.
struct Nearest;

impl Round for Nearest {
    fn dn(x: f32) -> f32 {
        x
    }
    fn up(x: f32) -> f32 {
        x
    }
    fn bad(x: f32) -> bool {
        x.is_nan()
    }
    const GUARD: bool = false;
}

/// `la2011-safe`: f32 interval arithmetic (one step outward after each rounded
/// operation); any non-finite value falls back.
struct Outward;

impl Round for Outward {
    fn dn(x: f32) -> f32 {
        x.next_down()
    }
    fn up(x: f32) -> f32 {
        x.next_up()
    }
    fn bad(x: f32) -> bool {
        !x.is_finite()
    }
    const GUARD: bool = true;
}

/// Encloses the exact product `a b` of two f32 values: `fl(a b)` stepped outward, or
/// `fl(a b)` itself when it is exact (a factor 0 or ±1).
fn mul<R: Round>(a: f32, b: f32) -> Iv {
    let p = a * b;
    if a == 0.0 || b == 0.0 || a.abs() == 1.0 || b.abs() == 1.0 {
        [p, p]
    } else {
        [R::dn(p), R::up(p)]
    }
}

/// `-[lo, hi] = [-hi, -lo]` (exact).
fn neg(a: Iv) -> Iv {
    [-a[1], -a[0]]
}

/// Sign class of a per-vertex lens shear over the shutter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    /// > 0 at both ends (so on all of [0, 1]).
    Pos,
    /// < 0 at both ends.
    Neg,
    /// Exactly 0 at both ends.
    Zero,
    /// Changes sign, touches 0 at one end, or is NaN.
    Cross,
}

impl Class {
    /// The class of a shear whose end values lie in `s0`, `s1`: a strict sign only
    /// when the whole enclosure has it, Zero only when it is exactly 0.
    fn of(s0: Iv, s1: Iv) -> Class {
        if s0[0] > 0.0 && s1[0] > 0.0 {
            Class::Pos
        } else if s0[1] < 0.0 && s1[1] < 0.0 {
            Class::Neg
        } else if s0[0] == 0.0 && s0[1] == 0.0 && s1[0] == 0.0 && s1[1] == 0.0 {
            Class::Zero
        } else {
            Class::Cross
        }
    }
    fn flip(self) -> Class {
        match self {
            Class::Pos => Class::Neg,
            Class::Neg => Class::Pos,
            c => c,
        }
    }
}

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    /// w.
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y (an enclosure).
    s: [[Iv; 3]; 2],
    class: [Class; 3],
}

impl Axis {
    fn new<R: Round>(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        let p = [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])];
        let w = [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])];
        let s = [tri.c0.map(|c| mul::<R>(scale, c)), tri.c1.map(|c| mul::<R>(scale, c))];
        let class = [0, 1, 2].map(|i| Class::of(s[0][i], s[1][i]));
        Axis { p, w, s, class }
    }

    /// Encloses `d = p - X w` for end e, vertex i.
    fn d<R: Round>(&self, e: usize, i: usize, x: f32) -> Iv {
        let p = self.p[e][i];
        let xw = mul::<R>(x, self.w[e][i]);
        [R::dn(p - xw[1]), R::up(p - xw[0])]
    }

    /// Time range and lens range for the tile columns `[lo, hi]` of this axis, or
    /// None when the axis proves the tile empty.
    fn bounds<R: Round>(&self, lo: f32, hi: f32) -> Option<(Iv, Iv)> {
        let cols = [lo, hi];
        // --- time: F(e) = min (d - |s|), G(e) = max (d + |s|) over i and both columns
        // (a lower bound of F, an upper bound of G).
        let mut f = [f32::INFINITY; 2];
        let mut g = [f32::NEG_INFINITY; 2];
        let mut nan = false;
        for e in 0..2 {
            for i in 0..3 {
                let s = self.s[e][i];
                let a = s[0].abs().max(s[1].abs());
                for &x in &cols {
                    let d = self.d::<R>(e, i, x);
                    let (m, mm) = (R::dn(d[0] - a), R::up(d[1] + a));
                    nan |= R::bad(m) || R::bad(mm);
                    f[e] = f[e].min(m);
                    g[e] = g[e].max(mm);
                }
            }
        }
        let t = if nan {
            [0.0, 1.0]
        } else {
            let tf = chord::<R>(f[0], f[1])?;
            let tg = chord::<R>(-g[0], -g[1])?;
            [tf[0].max(tg[0]), tf[1].min(tg[1])]
        };
        if t[0] > t[1] {
            return None;
        }
        // --- lens: hull of condition (a) "some d + u s < 0", and (b) "some d + u s > 0".
        let mut ha: Option<Iv> = None;
        let mut hb: Option<Iv> = None;
        let join = |h: &mut Option<Iv>, r: Option<Iv>| {
            if let Some(r) = r {
                *h = Some(match *h {
                    None => r,
                    Some(h) => [h[0].min(r[0]), h[1].max(r[1])],
                });
            }
        };
        for i in 0..3 {
            let s = [self.s[0][i], self.s[1][i]];
            for &x in &cols {
                let d = [self.d::<R>(0, i, x), self.d::<R>(1, i, x)];
                join(&mut ha, neg_hull::<R>(d, s, self.class[i]));
                join(&mut hb, neg_hull::<R>(d.map(neg), s.map(neg), self.class[i].flip()));
            }
        }
        let (ha, hb) = (ha?, hb?);
        let lens = [ha[0].max(hb[0]).max(-1.0), ha[1].min(hb[1]).min(1.0)];
        if lens[0] > lens[1] {
            return None;
        }
        Some((t, lens))
    }
}

/// The t in [0, 1] where the chord `(1-t) l0 + t l1` is <= 0 (the rest is culled);
/// None when the chord is > 0 on all of [0, 1].
pub fn chord_nonpos(l0: f32, l1: f32) -> Option<[f32; 2]> {
    chord::<Nearest>(l0, l1)
}

/// [`chord_nonpos`] with the crossing `t* = l0 / (l0 - l1)` rounded by `R` towards the
/// kept side: down where it is the lower end (`l0 > 0 >= l1`), up where it is the upper
/// end (`l0 <= 0 < l1`); the denominator is rounded up in both cases (see the module's
/// `la2011-safe` analysis).
fn chord<R: Round>(l0: f32, l1: f32) -> Option<[f32; 2]> {
    let cross = |step: fn(f32) -> f32| {
        let t = step(l0 / R::up(l0 - l1));
        if t.is_nan() {
            None
        } else {
            Some(t.clamp(0.0, 1.0))
        }
    };
    if l0 > 0.0 && l1 > 0.0 {
        None
    } else if l0 > 0.0 {
        Some([cross(R::dn).unwrap_or(0.0), 1.0])
    } else if l1 > 0.0 {
        Some([0.0, cross(R::up).unwrap_or(1.0)])
    } else {
        Some([0.0, 1.0])
    }
}

/// Hull over t in [0, 1] of `{u real : d(t) + u s(t) < 0}`, for `d`, `s` affine in t
/// with end values in `d[e]`, `s[e]` and sign class `class` of `s`; None when empty.
/// Bounds may be infinite.
fn neg_hull<R: Round>(d: [Iv; 2], s: [Iv; 2], class: Class) -> Option<Iv> {
    const FULL: Iv = [f32::NEG_INFINITY, f32::INFINITY];
    // The threshold `theta = -d / s` takes its largest value over the enclosures at the
    // largest numerator `n = -d_lo`, over the smallest |s| if n >= 0 (the largest if
    // n < 0) when s > 0; its smallest value at the same n, over the smallest |s| if
    // n >= 0 (the largest if n < 0) when s < 0.
    let top = |e: usize| {
        let n = -d[e][0];
        R::up(if n >= 0.0 { n / s[e][0] } else { n / s[e][1] })
    };
    let bottom = |e: usize| {
        let n = -d[e][0];
        R::dn(if n >= 0.0 { n / s[e][1] } else { n / s[e][0] })
    };
    match class {
        Class::Pos => {
            let (a, b) = (top(0), top(1));
            if R::bad(a) || R::bad(b) {
                Some(FULL)
            } else {
                Some([f32::NEG_INFINITY, a.max(b)])
            }
        }
        Class::Neg => {
            let (a, b) = (bottom(0), bottom(1));
            if R::bad(a) || R::bad(b) {
                Some(FULL)
            } else {
                Some([a.min(b), f32::INFINITY])
            }
        }
        Class::Zero => {
            if d[0][0] < 0.0 || d[1][0] < 0.0 || d.iter().flatten().any(|&x| R::bad(x)) {
                Some(FULL)
            } else {
                None
            }
        }
        Class::Cross => Some(FULL),
    }
}

struct Prep<R> {
    x: Axis,
    y: Axis,
    /// Some input is not finite (only `la2011-safe` looks): every tile gets the full domain.
    full: bool,
    round: PhantomData<fn() -> R>,
}

impl<R: Round> Prepared for Prep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        if R::GUARD && (self.full || ![tile.x0, tile.x1, tile.y0, tile.y1].iter().all(|v| v.is_finite())) {
            return TileResult::Bounds(TileBounds::full());
        }
        let Some((tx, u)) = self.x.bounds::<R>(tile.x0, tile.x1) else {
            return TileResult::Empty;
        };
        let Some((ty, v)) = self.y.bounds::<R>(tile.y0, tile.y1) else {
            return TileResult::Empty;
        };
        let t = [tx[0].max(ty[0]), tx[1].min(ty[1])];
        if t[0] > t[1] {
            return TileResult::Empty;
        }
        TileResult::Bounds(TileBounds { u, v, t, z: None, constraints: Vec::new() })
    }
}

/// The old answer of `la2011` (`safe` false) or `la2011-safe` for a triangle and a tile.
pub fn answer(safe: bool, tri: &Triangle, tile: &Tile) -> TileResult {
    fn run<R: Round>(tri: &Triangle, tile: &Tile) -> TileResult {
        let finite =
            tri.q.iter().chain(&tri.r).flatten().chain(&tri.c0).chain(&tri.c1).chain([&tri.k]).all(|v| v.is_finite());
        let p = Prep::<R> {
            x: Axis::new::<R>(tri, 0, 1.0),
            y: Axis::new::<R>(tri, 1, tri.k),
            full: R::GUARD && !finite,
            round: PhantomData,
        };
        p.tile(tile)
    }
    if safe {
        run::<Outward>(tri, tile)
    } else {
        run::<Nearest>(tri, tile)
    }
}
