//! Where a case is made: a triangle drawn for a regime ([`generate`]), placed in a
//! viewport and snapped ([`place`]), and the tiles it is judged on: one on the
//! footprint's boundary ([`generate::boundary_tile`]) and the two at a method's own
//! tile-reject limit ([`limit_tiles`]).

pub mod generate;
pub mod limit_tiles;
pub mod place;

use crate::model::{Case, Tile, Viewport};
use generate::{boundary_tile, physical_case, rng_for, Regime};

/// How a run draws its cases: every case from its own stream of `seed`, the regimes in
/// turn, a tile of a fixed size (None: drawn from 1, 2, 4, 8, 16 px) and, under a
/// viewport, each case placed in it.
#[derive(Clone, Copy, Debug)]
pub struct Draw<'a> {
    pub seed: u64,
    pub regimes: &'a [Regime],
    pub tile: Option<f32>,
    pub viewport: Option<Viewport>,
}

/// The case with index `i`: its regime, the triangle and a tile on the footprint's
/// boundary (a tile containing a sample drawn near an edge).
///
/// Under a viewport the case is placed in it ([`place::place_case`]); a case that
/// cannot be placed is drawn as without one (use [`try_make_case`] to skip it).
pub fn make_case(d: &Draw, i: u64) -> (Regime, Case, Tile) {
    try_make_case(d, i).unwrap_or_else(|| make_case(&Draw { viewport: None, ..*d }, i))
}

/// [`make_case`], None when a viewport is set and no draw of the case's regime fits in
/// its guard band.
pub fn try_make_case(d: &Draw, i: u64) -> Option<(Regime, Case, Tile)> {
    let regime = d.regimes[(i % d.regimes.len() as u64) as usize];
    let (case, mut rng) = match d.viewport {
        None => {
            let mut rng = rng_for(d.seed, i);
            (physical_case(&mut rng, regime), rng)
        }
        Some(vp) => place::place_case(d.seed, i, regime, vp)?,
    };
    let size = generate::tile_size(d.tile, &mut rng);
    let mut tile = boundary_tile(&case, &mut rng, size);
    if let Some(vp) = d.viewport {
        tile = place::tile_in_viewport(tile, vp);
    }
    Some((regime, case, tile))
}
