//! The inputs the encoded methods are compared on: physical cases of every regime with
//! tiles at their footprint's boundary and beside it, wild random triangles (coordinates
//! from subnormal to 1e30, w of either sign, exactly 0 or tiny, shears crossing or
//! touching 0) and the same with a NaN, an infinity or a signed zero planted in one
//! number of the triangle or the tile.

use cullproof::gen::{boundary_tile, physical_case, rng_for, tile_size, wild_triangle, Regime};
use cullproof::{Tile, Triangle};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The special values planted into inputs.
const SPECIAL: [f32; 8] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0, f32::MAX, 1e-45, -1.0];

fn near(rng: &mut ChaCha8Rng, n: usize) -> Tile {
    let far = [0.0f32, 1.0, 1e2, 1e4, 1e6];
    let x = rng.gen_range(-1.0f32..1.0) * far[n % 5];
    let y = rng.gen_range(-1.0f32..1.0) * far[(n / 5) % 5];
    Tile::square(x, y, [1e-3f32, 1.0, 4.0, 16.0][n % 4])
}

/// Plant a special value into one number of the triangle or the tile.
fn plant(rng: &mut ChaCha8Rng, tri: &mut Triangle, tile: &mut Tile) {
    let v = SPECIAL[rng.gen_range(0..SPECIAL.len())];
    match rng.gen_range(0..8) {
        0 => tri.q[rng.gen_range(0..3)][rng.gen_range(0..4)] = v,
        1 => tri.r[rng.gen_range(0..3)][rng.gen_range(0..4)] = v,
        2 => tri.c0[rng.gen_range(0..3)] = v,
        3 => tri.c1[rng.gen_range(0..3)] = v,
        4 => tri.k = v,
        5 => tile.x0 = v,
        6 => tile.y1 = v,
        _ => tri.q[rng.gen_range(0..3)][3] = if rng.gen_bool(0.5) { 0.0 } else { -0.0 },
    }
}

/// Case `n` of a seed: a triangle and tiles for it. A third are physical cases (regime
/// `n % 16`) with a boundary tile and a tile beside it, a third wild triangles with two
/// tiles near the origin or far from it, a third the same with a special value planted.
pub fn case(seed: u64, n: usize) -> (Triangle, Vec<Tile>) {
    let mut rng = rng_for(seed, n as u64);
    match n % 3 {
        0 => {
            let regime = Regime::ALL[(n / 3) % Regime::ALL.len()];
            let case = physical_case(&mut rng, regime);
            let size = tile_size(None, &mut rng);
            let t = boundary_tile(&case, &mut rng, size);
            let beside = Tile::square(t.x0 + size * rng.gen_range(-3..=3) as f32, t.y0 + size, size);
            (case.triangle, vec![t, beside])
        }
        1 => {
            let tri = wild_triangle(&mut rng, n / 3);
            (tri, vec![near(&mut rng, n / 3), near(&mut rng, n / 3 + 7)])
        }
        _ => {
            let mut tri = wild_triangle(&mut rng, n / 3);
            let mut tile = near(&mut rng, n / 3);
            plant(&mut rng, &mut tri, &mut tile);
            let other = near(&mut rng, n / 3 + 3);
            (tri, vec![tile, other])
        }
    }
}

/// The answer of a tile test bit for bit: every interval end's bits and every
/// constraint's debug form (which prints each f32 so that it reads back to the same
/// bits), or None for Empty.
pub fn bits(r: &cullproof::bounds::TileResult) -> Option<(Vec<u32>, String)> {
    match r {
        cullproof::bounds::TileResult::Empty => None,
        cullproof::bounds::TileResult::Bounds(b) => {
            let mut v: Vec<u32> = b.u.iter().chain(&b.v).chain(&b.t).map(|x| x.to_bits()).collect();
            v.extend(b.z.iter().flatten().map(|x| x.to_bits()));
            Some((v, format!("{:?}", b.constraints)))
        }
    }
}
