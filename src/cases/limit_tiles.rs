//! Where the gate puts its tiles.
//!
//! - The **boundary tile** (every case, shared by every method): a tile on the grid of
//!   its size holding a sample drawn near an edge of the triangle.
//! - **Limit tiles** (per method): a method's tile reject is a comparison of values it
//!   computed, in f32, with the tile's edges. Its error hides where that comparison
//!   flips, and a tile placed at random almost never lands there. So the gate finds the
//!   flip itself: it slides a tile towards the footprint's extreme in one direction
//!   (right, left, up or down; at the extreme over lens corners and shutter ends, in
//!   the row or column of the grid cell holding it) and bisects over the f32 values of
//!   the tile's leading edge until the method keeps the tile at one f32 value and culls
//!   it at the next. Both tiles are judged: the culled one must hold no interior sample
//!   (its edge sits exactly on the method's limit, so a limit computed a rounding too
//!   far inside is caught), the kept one has the method's answer at its tightest.
//!
//! The bisection asks only the method's own tile test, so it works for any method,
//! built in or not.

use crate::bounds::{Prepared, TileResult};
use crate::model::{Case, Tile};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The direction a limit tile is slid in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    Right,
    Left,
    Up,
    Down,
}

impl Dir {
    pub const ALL: [Dir; 4] = [Dir::Right, Dir::Left, Dir::Up, Dir::Down];
}

/// The footprint's extreme in a direction, over the vertices, the four lens corners and
/// both shutter ends (the screen box of the moving, defocused triangle when every vertex
/// is in front of the lens), and the other coordinate there (at a lens position drawn
/// from `rng` on the other lens axis). None when some vertex has w <= 0 at a shutter end
/// (the footprint is unbounded) or the values are not finite.
pub fn footprint_extreme(case: &Case, dir: Dir, rng: &mut ChaCha8Rng) -> Option<(f64, f64)> {
    let tri = case.triangle.to_oracle();
    let other: f64 = rng.gen_range(-1.0..=1.0);
    let mut best: Option<(f64, f64)> = None;
    for e in 0..2 {
        for i in 0..3 {
            let p = if e == 0 { tri.q[i] } else { tri.r[i] };
            let c = if e == 0 { tri.c0[i] } else { tri.c1[i] };
            let w = p[3];
            if w.is_nan() || w <= 0.0 {
                return None;
            }
            for s in [-1.0f64, 1.0] {
                let (along, across) = match dir {
                    Dir::Right | Dir::Left => ((p[0] + s * c) / w, (p[1] + tri.k * other * c) / w),
                    Dir::Up | Dir::Down => ((p[1] + tri.k * s * c) / w, (p[0] + other * c) / w),
                };
                let key = if matches!(dir, Dir::Right | Dir::Up) { along } else { -along };
                if best.is_none_or(|b| key > b.0) {
                    best = Some((key, across));
                }
            }
        }
    }
    let (key, across) = best?;
    let along = if matches!(dir, Dir::Right | Dir::Up) { key } else { -key };
    (along.is_finite() && across.is_finite() && along.abs() < 1e30 && across.abs() < 1e30).then_some((along, across))
}

/// A total order on f32 values as integers (adjacent floats are adjacent integers).
fn ord(x: f32) -> i64 {
    let b = x.to_bits() as i32;
    (if b < 0 { i32::MIN - b } else { b }) as i64
}

fn unord(k: i64) -> f32 {
    let k = k as i32;
    f32::from_bits((if k < 0 { i32::MIN - k } else { k }) as u32)
}

/// The tile of `size` whose leading edge (in direction `dir`) is at `edge`, spanning
/// `[across0, across0 + size]` on the other axis.
fn tile_at(dir: Dir, edge: f32, across0: f32, size: f32) -> Option<Tile> {
    let t = match dir {
        Dir::Right => Tile { x0: edge, x1: edge + size, y0: across0, y1: across0 + size },
        Dir::Left => Tile { x0: edge - size, x1: edge, y0: across0, y1: across0 + size },
        Dir::Up => Tile { y0: edge, y1: edge + size, x0: across0, x1: across0 + size },
        Dir::Down => Tile { y0: edge - size, y1: edge, x0: across0, x1: across0 + size },
    };
    t.validate().is_ok().then_some(t)
}

/// The case moved on screen by `(dx, dy)` pixels: every clip-space x and y shifted by
/// that many times its w, in f32. Depths and CoCs stay, so a physical case keeps its
/// lens; the new roundings of the sums give the method new corner values.
fn shifted(case: &Case, dx: f32, dy: f32) -> Case {
    let mut c = *case;
    for p in c.triangle.q.iter_mut().chain(c.triangle.r.iter_mut()) {
        p[0] += dx * p[3];
        p[1] += dy * p[3];
    }
    c
}

/// Where the method's tile test flips along `dir` for tiles of `size` whose other axis
/// spans the grid cell holding `across`: the leading edges `(kept, culled)`, adjacent
/// f32 values. None when it does not flip between a tile over the extreme `along` and
/// one two tiles beyond it.
fn flip(p: &dyn Prepared, dir: Dir, along: f64, across0: f32, size: f32) -> Option<(f32, f32)> {
    let culled = |edge: f32| tile_at(dir, edge, across0, size).map(|t| matches!(p.tile(&t), TileResult::Empty));
    let fwd = matches!(dir, Dir::Right | Dir::Up);
    let s = size as f64;
    let (inside, outside) = if fwd { (along - 0.5 * s, along + 2.0 * s) } else { (along + 0.5 * s, along - 2.0 * s) };
    let (mut k_in, mut k_out) = (ord(inside as f32), ord(outside as f32));
    if culled(unord(k_in))? || !culled(unord(k_out))? {
        return None;
    }
    while (k_out - k_in).abs() > 1 {
        let mid = k_in + (k_out - k_in) / 2;
        match culled(unord(mid))? {
            true => k_out = mid,
            false => k_in = mid,
        }
    }
    Some((unord(k_in), unord(k_out)))
}

/// The tiles at a method's tile-reject limit.
pub struct Limit {
    /// The case, moved on screen by a fraction of a pixel.
    pub case: Case,
    /// The method's setup of that case.
    pub prepared: Box<dyn Prepared>,
    /// The last tile kept and the first culled: their leading edges are adjacent f32
    /// values.
    pub kept: Tile,
    pub culled: Tile,
    /// How far the culled tile's edge lies beyond the footprint's extreme (computed in
    /// f64), in tile sizes (negative: inside). A looser reject has a larger slack.
    pub slack: f64,
}

/// The tiles at a method's tile-reject limit for a case ([`Limit`]), whose
/// leading edges are adjacent f32 values. The case is moved on screen by a fraction
/// of a pixel, `shifts` times at random; for each shift and each direction the flip
/// is found, and the one that lies farthest inside the footprint's extreme (computed
/// in f64) is kept: there a culled tile is most likely to hold covered samples. None
/// when the method does not cull tiles near the footprint.
pub fn limit_tiles(
    setup: &dyn Fn(&Case) -> Box<dyn Prepared>,
    case: &Case,
    rng: &mut ChaCha8Rng,
    size: f32,
    shifts: usize,
) -> Option<Limit> {
    let mut best: Option<(f64, Case, Tile, Tile, f64)> = None;
    let mut best_p: Option<Box<dyn Prepared>> = None;
    for k in 0..shifts.max(1) {
        let c = if k == 0 { *case } else { shifted(case, rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5)) };
        if c.validate().is_err() {
            continue;
        }
        let p = setup(&c);
        let mut improved = false;
        for dir in Dir::ALL {
            let Some((along, across)) = footprint_extreme(&c, dir, rng) else { continue };
            let across0 = ((across / size as f64).floor() * size as f64) as f32;
            let Some((kept, culled)) = flip(p.as_ref(), dir, along, across0, size) else { continue };
            // How far the culled tile's edge lies inside the extreme, in units of the
            // edge's ulp (positive: inside).
            let ulp = (culled.abs().next_up() - culled.abs()).max(f32::MIN_POSITIVE) as f64;
            let inside =
                if matches!(dir, Dir::Right | Dir::Up) { along - culled as f64 } else { culled as f64 - along };
            let score = inside / ulp;
            if best.as_ref().is_none_or(|b| score > b.0) {
                if let (Some(kt), Some(ct)) = (tile_at(dir, kept, across0, size), tile_at(dir, culled, across0, size)) {
                    best = Some((score, c, kt, ct, -inside / size as f64));
                    improved = true;
                }
            }
        }
        if improved {
            best_p = Some(p);
        }
    }
    let (_, case, kept, culled, slack) = best?;
    Some(Limit { case, prepared: best_p?, kept, culled, slack })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_float_order_is_monotone_and_adjacent() {
        for x in [-3.5f32, -1e-30, -0.0, 0.0, 1e-40, 1.0, 7.25e6] {
            assert_eq!(unord(ord(x)).to_bits(), if x == 0.0 { 0.0f32.to_bits() } else { x.to_bits() });
            assert_eq!(unord(ord(x) + 1), if x == -0.0 || x == 0.0 { f32::from_bits(1) } else { x.next_up() });
        }
        assert!(ord(-1.0) < ord(-0.5) && ord(-0.5) < ord(0.0) && ord(0.0) < ord(2.0));
    }
}
