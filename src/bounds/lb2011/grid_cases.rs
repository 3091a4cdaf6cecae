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

fn compare<P: Parts>(prep: &Prep<P>, xs: &[f32], ys: &[f32], paths: &mut Paths, what: &str) {
    let grid = Grid::new(xs, ys);
    let answers = prep.grid(grid);
    for j in 0..grid.rows() {
        for i in 0..grid.columns() {
            let tile = grid.tile(i, j);
            let (want, got) = (format!("{:?}", prep.tile(&tile)), format!("{:?}", answers.tile(i, j)));
            assert_eq!(got, want, "{what}: tile ({i}, {j}) = {tile:?}");
            let (xp, yp) = (prep.parts.part(false, grid.column(i)), prep.parts.part(true, grid.row(j)));
            let x_without = !xp.ans.ok;
            paths[0] += (xp.ans.ok && xp.ans.none) as usize;
            paths[1] += (x_without && yp.ans.ok && yp.ans.none) as usize;
            paths[2] += (x_without && !yp.patches.is_empty()) as usize;
            paths[3] += (!want.starts_with("Empty") && want.contains("patch")) as usize;
        }
    }
}

/// Both variants' setups of a triangle, compared on `id`'s cases.
fn run<P: Parts>(id: &str, setup: impl Fn(&Triangle) -> Prep<P>) {
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
        let prep = setup(&tri);
        for t in &tiles {
            let xs = boundaries(&mut rng, t.x0, t.x1);
            let ys = boundaries(&mut rng, t.y0, t.y1);
            compare(&prep, &xs, &ys, &mut paths, &format!("{id}, case {c}, {tri:?}"));
        }
    }
    assert!(paths.iter().all(|&n| n > 20), "{id}: a path is hardly taken: {paths:?}");
}

#[test]
fn grid_answers_are_the_tile_answers_on_one_sided_and_odd_input() {
    run("lb2011", |tri| Prep { parts: PlainParts { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k) } });
    run("lb2011-safe", |tri| {
        let tri = TriOf::of(tri);
        let axis = |a| safe::axis_of::<Outward, Plain>(&Plain, &tri, a);
        Prep { parts: SafeParts::<Outward> { x: axis(0), y: axis(1), round: PhantomData } }
    });
}
