//! The four hyperplane variants over a grid ([`Prepared::grid`]: `PlainGrid`,
//! `SafeGrid`) against [`Prepared::tile`], bit for bit, on the paths the shared stress
//! stream of `grid_tests.rs` reaches only now and then: grid boundaries that are NaN,
//! infinite, huge, subnormal, signed zeros or out of order (a `-safe` column or row that
//! is not a finite ordered range answers the full domain), and edges whose plane is not
//! finite on some tiles only.

use super::safe::*;
use super::*;
use crate::bounds::grid_tests::boundaries;
use crate::cases::generate::{bit_compare_case, rng_for};

/// How often each path was taken: `[an edge without a finite plane on this tile while
/// another edge has one, Empty, the full domain for a tile that is not a finite ordered
/// box, answers with planes]`.
type Paths = [usize; 4];

/// Whether edge `ei`'s plane is finite on `tile` (the test `tile` makes per edge).
fn plane_ok(tri: &Triangle, safe: bool, ei: usize, tile: &Tile) -> Option<bool> {
    if safe {
        let edges = setup_safe(tri).ok()?;
        let (xs, ys) = (Iv::new(tile.x0, tile.x1), Iv::new(tile.y0, tile.y1));
        Some(edges[ei].as_ref().and_then(|e| plane_safe(e, tri.k, xs, ys)).is_some())
    } else {
        let s = setup(tri).ok()?;
        let (c, h) = centre(&Plain, &tile_of(tile));
        Some(plane_of(&Plain, &s.edges[ei], &s.k, &c, &h).0)
    }
}

fn compare(m: &dyn Method, tri: &Triangle, xs: &[f32], ys: &[f32], paths: &mut Paths, what: &str) {
    let safe = m.info().id.ends_with("safe");
    let prep = m.setup(tri);
    let grid = Grid::new(xs, ys);
    let answers = prep.grid(grid);
    for j in 0..grid.rows() {
        for i in 0..grid.columns() {
            let tile = grid.tile(i, j);
            let want = prep.tile(&tile);
            let (w, g) = (format!("{want:?}"), format!("{:?}", answers.tile(i, j)));
            assert_eq!(g, w, "{what}: tile ({i}, {j}) = {tile:?}");
            let ok = [0, 1, 2].map(|ei| plane_ok(tri, safe, ei, &tile));
            paths[0] += (ok.contains(&Some(false)) && ok.contains(&Some(true))) as usize;
            let ordered = [tile.x0, tile.x1, tile.y0, tile.y1].iter().all(|v| v.is_finite())
                && tile.x0 <= tile.x1
                && tile.y0 <= tile.y1;
            match &want {
                TileResult::Empty => paths[1] += 1,
                TileResult::Bounds(b) => {
                    paths[2] += (!ordered
                        && prep.disabled().is_none()
                        && w == format!("{:?}", TileResult::Bounds(TileBounds::full())))
                        as usize;
                    paths[3] += !b.constraints.is_empty() as usize;
                }
            }
        }
    }
}

#[test]
fn grid_answers_are_the_tile_answers_on_odd_boundaries() {
    for m in [METHOD, METHOD_PS, METHOD_SAFE, METHOD_PS_SAFE] {
        let id = m.info().id;
        let mut paths = [0; 4];
        for c in 0..600 {
            let (tri, tiles) = bit_compare_case(93, c);
            let mut rng = rng_for(94, c as u64);
            for t in &tiles {
                let xs = boundaries(&mut rng, t.x0, t.x1);
                let ys = boundaries(&mut rng, t.y0, t.y1);
                compare(m, &tri, &xs, &ys, &mut paths, &format!("{id}, case {c}, {tri:?}"));
            }
        }
        eprintln!("{id}: {paths:?}");
        let per_sample = m.info().outputs.per_sample;
        let safe = id.ends_with("safe");
        assert!(paths[0] > 20 && paths[1] > 20, "{id}: a path is hardly taken: {paths:?}");
        assert!(!safe || paths[2] > 20, "{id}: hardly any odd tile answered: {paths:?}");
        assert!(!per_sample || paths[3] > 20, "{id}: hardly any planes: {paths:?}");
    }
}
