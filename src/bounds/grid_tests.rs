//! [`Prepared::grid`] against [`Prepared::tile`]: for every registered method, every
//! tile of a grid gets the answer `tile` gives for it, bit for bit, constraints included,
//! on the stress stream of the bit-identity tests ([`bit_compare_case`]: physical cases
//! on boundary tiles, wild triangles, planted NaN, infinities, signed zeros, f32::MAX and
//! subnormals) and on the unit grids a rasterizer walks.

use super::*;
use crate::cases::generate::{bit_compare_case, boundary_tile, physical_case, rng_for, Regime};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A boundary value that breaks arithmetic.
fn odd(rng: &mut ChaCha8Rng) -> f32 {
    [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0, 0.0, f32::MAX, -f32::MAX, 1.0e-40][rng.gen_range(0..8)]
}

/// Grid boundaries around `[a, b]` (the steps of its width), one of them odd at times, in
/// reverse order at times.
pub(crate) fn boundaries(rng: &mut ChaCha8Rng, a: f32, b: f32) -> Vec<f32> {
    let w = b - a;
    let mut v = vec![a - w, a, b, b + w];
    if rng.gen_bool(0.3) {
        let k = rng.gen_range(0..v.len());
        v[k] = odd(rng);
    }
    if rng.gen_bool(0.1) {
        v.reverse();
    }
    v
}

/// The grids around a case's tiles: the first tile with neighbours on each side (its
/// width and height as the steps), the first tile's columns with the second tile's rows,
/// and a single tile.
fn grids_of(tiles: &[Tile]) -> Vec<(Vec<f32>, Vec<f32>)> {
    let (a, b) = (tiles[0], tiles[tiles.len() - 1]);
    let (w, h) = (a.x1 - a.x0, a.y1 - a.y0);
    vec![
        (vec![a.x0 - w, a.x0, a.x1, a.x1 + w, a.x1 + w + w], vec![a.y0 - h, a.y0, a.y1, a.y1 + h]),
        (vec![a.x0, a.x1, a.x1 + w], vec![b.y0, b.y1, b.y1 + (b.y1 - b.y0)]),
        (vec![b.x0, b.x1], vec![b.y0, b.y1]),
    ]
}

/// What must match: `Debug` prints every field, an f32 as the shortest decimal that reads
/// back to the same bits (the sign of zero included; any NaN prints as NaN).
fn answer(r: &TileResult) -> String {
    format!("{r:?}")
}

/// Compare every tile of the grid; returns (tiles compared, non-empty answers, answers
/// with constraints).
fn compare(m: &dyn Method, tri: &Triangle, xs: &[f32], ys: &[f32], what: &str) -> (usize, usize, usize) {
    let prep = m.setup(tri);
    let grid = Grid::new(xs, ys);
    let answers = prep.grid(grid);
    let (mut n, mut kept, mut cons) = (0, 0, 0);
    for j in 0..grid.rows() {
        for i in 0..grid.columns() {
            let want = prep.tile(&grid.tile(i, j));
            let got = answers.tile(i, j);
            assert_eq!(
                answer(&got),
                answer(&want),
                "{}: grid answer differs from the tile answer, {what}, tile ({i}, {j}) = {:?}, triangle {tri:?}",
                m.info().id,
                grid.tile(i, j)
            );
            n += 1;
            if let TileResult::Bounds(b) = &want {
                kept += 1;
                cons += !b.constraints.is_empty() as usize;
            }
        }
    }
    (n, kept, cons)
}

#[test]
fn grid_answers_are_the_tile_answers_bit_for_bit() {
    for m in registry() {
        let (mut n, mut kept, mut cons) = (0, 0, 0);
        for c in 0..1500 {
            let (tri, tiles) = bit_compare_case(73, c);
            for (xs, ys) in grids_of(&tiles) {
                let r = compare(m, &tri, &xs, &ys, &format!("stress case {c}"));
                n += r.0;
                kept += r.1;
                cons += r.2;
            }
        }
        // Grids of the harness's tile sizes around a boundary tile of a physical case.
        for c in 0..300u64 {
            let mut rng = rng_for(74, c);
            let case = physical_case(&mut rng, Regime::ALL[c as usize % Regime::ALL.len()]);
            let size = [1.0f32, 2.0, 4.0, 8.0][c as usize % 4];
            let t = boundary_tile(&case, &mut rng, size);
            let xs: Vec<f32> = (0..7).map(|k| t.x0 + size * (k - 3) as f32).collect();
            let ys: Vec<f32> = (0..5).map(|k| t.y0 + size * (k - 2) as f32).collect();
            let r = compare(m, &case.triangle, &xs, &ys, &format!("physical case {c}"));
            n += r.0;
            kept += r.1;
            cons += r.2;
        }
        let id = m.info().id;
        assert!(n > 30_000, "{id}: only {n} tiles compared");
        assert!(kept > 1000, "{id}: only {kept} non-empty answers compared");
        if m.info().outputs.per_sample && !id.starts_with("gdam2010") && id != "mam2012-safe" {
            assert!(cons > 100, "{id}: only {cons} answers with constraints compared");
        }
    }
}
