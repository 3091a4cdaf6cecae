//! `lb2011` and `lb2011-safe` over a grid ([`Prepared::grid`], `PatchGrid`) against
//! [`Prepared::tile`], bit for bit, on the paths the shared stress stream of
//! `grid_tests.rs` reaches only now and then: one axis without corners (a NaN or an
//! infinity planted in that axis's inputs) while the other axis rejects the tile, and
//! grid boundaries that are NaN, infinite, huge, subnormal, signed zeros or out of order.

use super::*;
use crate::bounds::grid_tests::boundaries;
use crate::cases::generate::{bit_compare_case, rng_for};
use rand::Rng;

/// How often each path was taken: `[x axis Empty, x without corners and y Empty, x
/// without corners and y with patches, non-empty answers with patches]`.
type Paths = [usize; 4];

fn compare(prep: &Prep, xs: &[f32], ys: &[f32], paths: &mut Paths, what: &str) {
    let grid = Grid::new(xs, ys);
    let answers = prep.grid(grid);
    let x = ["x1", "x0"];
    let y = ["y1", "y0"];
    for j in 0..grid.rows() {
        for i in 0..grid.columns() {
            let tile = grid.tile(i, j);
            let (want, got) = (format!("{:?}", prep.tile(&tile)), format!("{:?}", answers.tile(i, j)));
            assert_eq!(got, want, "{what}: tile ({i}, {j}) = {tile:?}");
            let (xp, yp) =
                (prep.axis_part(&prep.x, grid.column(i), Lens::U, x), prep.axis_part(&prep.y, grid.row(j), Lens::V, y));
            let x_none = (prep.arith.corners)(&prep.x, tile.x0, tile.x1).is_none();
            paths[0] += xp.is_none() as usize;
            paths[1] += (x_none && yp.is_none()) as usize;
            paths[2] += (x_none && yp.as_ref().is_some_and(|p| !p.patches.is_empty())) as usize;
            paths[3] += (!want.starts_with("Empty") && want.contains("patch")) as usize;
        }
    }
}

#[test]
fn grid_answers_are_the_tile_answers_on_one_sided_and_odd_input() {
    for (id, arith) in [("lb2011", &PLAIN), ("lb2011-safe", &SAFE)] {
        let mut paths = [0; 4];
        for c in 0..600 {
            let (mut tri, tiles) = bit_compare_case(91, c);
            let mut rng = rng_for(92, c as u64);
            // Plant a NaN or an infinity in the x inputs (no x corners) in half the cases.
            if c % 2 == 0 {
                let bad = [f32::NAN, f32::INFINITY][rng.gen_range(0..2)];
                let v = rng.gen_range(0..3);
                if rng.gen_bool(0.5) {
                    tri.q[v][0] = bad;
                } else {
                    tri.r[v][0] = bad;
                }
            }
            let prep = Prep { x: Axis::new(&tri, 0, 1.0), y: Axis::new(&tri, 1, tri.k), arith };
            for t in &tiles {
                let xs = boundaries(&mut rng, t.x0, t.x1);
                let ys = boundaries(&mut rng, t.y0, t.y1);
                compare(&prep, &xs, &ys, &mut paths, &format!("{id}, case {c}, {tri:?}"));
            }
        }
        assert!(paths.iter().all(|&n| n > 20), "{id}: a path is hardly taken: {paths:?}");
    }
}
