//! The ceiling: the box of a tile's covered samples (the sample ceiling), the certified
//! ceiling of one tile, and the seeded choice of the tiles that get a certified one.

use super::geometry::{tile_of, tile_range, Footprint, PixelRect};
use super::pattern;
use super::scene::Setting;
use super::table::{tile_rows, Local, SampleTable};
use super::types::{CertifiedRow, Config};
use crate::model::{Dims, Sample};
use oracles::extents::{Extent, ExtentsConfig, Occupancy, TileSolver};
use rand::SeedableRng;

fn uvt(s: &Sample) -> [f32; 3] {
    [s.u, s.v, s.t]
}

/// The box of the covered samples' (u, v, t) over the rows of a tile, widened to the
/// whole range in each of u, v (lens) and t (time) that the triangle's coverage does
/// not depend on (there the exact extents are the whole range as soon as one sample is
/// covered); None if no sample is covered.
pub(super) fn covered_box(
    table: &SampleTable,
    local: &Local,
    rows: &[(usize, usize, usize)],
    dims: Dims,
) -> Option<[[f32; 2]; 3]> {
    let mut b: Option<[[f32; 2]; 3]> = None;
    for &(ts, ls, n) in rows {
        for (s, &cov) in table.samples[ts..ts + n].iter().zip(&local.covered[ls..ls + n]) {
            if cov {
                let c = uvt(s);
                let bb = b.get_or_insert([[c[0], c[0]], [c[1], c[1]], [c[2], c[2]]]);
                for k in 0..3 {
                    bb[k][0] = bb[k][0].min(c[k]);
                    bb[k][1] = bb[k][1].max(c[k]);
                }
            }
        }
    }
    if let Some(bb) = &mut b {
        if !dims.has_lens() {
            bb[0] = [-1.0, 1.0];
            bb[1] = [-1.0, 1.0];
        }
        if !dims.has_time() {
            bb[2] = [0.0, 1.0];
        }
    }
    b
}

/// The samples `start..start + n` of the table inside the (u, v, t) box `b` (the test
/// of [`in_box`], side by side).
pub(super) fn count_in_box(table: &SampleTable, start: usize, n: usize, b: &[[f32; 2]; 3]) -> u64 {
    let (us, vs, ts) =
        (&table.cols[2][start..start + n], &table.cols[3][start..start + n], &table.cols[4][start..start + n]);
    let mut k = 0u32;
    for i in 0..n {
        k += ((b[0][0] <= us[i])
            & (us[i] <= b[0][1])
            & (b[1][0] <= vs[i])
            & (vs[i] <= b[1][1])
            & (b[2][0] <= ts[i])
            & (ts[i] <= b[2][1])) as u32;
    }
    k as u64
}

fn in_box(b: &[[f32; 2]; 3], s: &Sample) -> bool {
    let c = uvt(s);
    (0..3).all(|k| b[k][0] <= c[k] && c[k] <= b[k][1])
}

/// The certified ceiling of one tile.
#[allow(clippy::too_many_arguments)]
pub(super) fn certify(
    tri: &oracles::Tri,
    dims: Dims,
    table: &SampleTable,
    local: &Local,
    p: &PixelRect,
    cfg: &ExtentsConfig,
    setting: Setting,
    s: u32,
) -> CertifiedRow {
    let t = tile_of(p);
    let mut rows = Vec::new();
    tile_rows(table, local, p, &mut rows);
    let mut solver = TileSolver::new(
        tri,
        [t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64],
        [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]],
        cfg,
    );
    let covered = rows.iter().map(|&(_, ls, n)| local.covered[ls..ls + n].iter().filter(|&&c| c).count() as u64).sum();
    let mut row = CertifiedRow { setting, tile: s, tiles: 1, covered, ..Default::default() };
    let outer: Option<[[f64; 2]; 3]> = match solver.occupancy() {
        Occupancy::Empty => None,
        occ => {
            let mut undecided = occ == Occupancy::Unknown;
            let full = [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]];
            let mut b = full;
            for ext in &Extent::ALL[..6] {
                let r = solver.objective(*ext);
                undecided |= r.undecided > 0;
                let (k, max) = (ext.sample_coord().expect("u, v or t") - 2, ext.is_max());
                if let Some(e) = r.extreme {
                    b[k][max as usize] = if max { e.hi } else { e.lo };
                }
            }
            row.undecided_tiles = undecided as u64;
            Some(b)
        }
    };
    if outer.is_none() && covered > 0 {
        // Cannot happen (the occupancy search is certified); counted as undecided.
        row.undecided_tiles = 1;
    }
    row.boxes = solver.boxes;
    let sample_box = covered_box(table, local, &rows, dims);
    for &(ts, ls, n) in &rows {
        for (smp, &cov) in table.samples[ts..ts + n].iter().zip(&local.covered[ls..ls + n]) {
            let c = uvt(smp);
            if let Some(b) = &outer {
                row.tested_certified += (0..3).all(|k| b[k][0] <= c[k] as f64 && c[k] as f64 <= b[k][1]) as u64;
            } else if cov {
                row.tested_certified += 1;
            }
            if let Some(b) = &sample_box {
                row.tested_sample_box += in_box(b, smp) as u64;
            }
        }
    }
    row
}

/// The number of tiles of each size traversed for a footprint.
fn tiles_traversed(fp: Footprint, tiles: &[u32], width: u32, height: u32) -> Vec<u64> {
    let r = match fp {
        Footprint::OffScreen => return vec![0; tiles.len()],
        Footprint::WholeScreen => PixelRect { x0: 0, y0: 0, x1: width - 1, y1: height - 1 },
        Footprint::Region(r) => r,
    };
    tiles
        .iter()
        .map(|&s| {
            let (a, b, c, d) = tile_range(&r, s);
            (c - a + 1) as u64 * (d - b + 1) as u64
        })
        .collect()
}

/// The certified subset: per triangle, (tile index, local tile number) pairs, sorted;
/// for each tile size `n` pairs drawn uniformly without replacement from all traversed
/// ones (every one when `n` is at least their number).
pub(super) fn choose_certified(
    fps: &[Footprint],
    cfg: &Config,
    setting: Setting,
    width: u32,
    height: u32,
) -> Vec<Vec<(usize, u64)>> {
    let mut chosen = vec![Vec::new(); fps.len()];
    if cfg.certified_tiles == 0 {
        return chosen;
    }
    let counts: Vec<Vec<u64>> = fps.iter().map(|&f| tiles_traversed(f, &cfg.tiles, width, height)).collect();
    for (ti, &s) in cfg.tiles.iter().enumerate() {
        let mut prefix = Vec::with_capacity(fps.len() + 1);
        prefix.push(0u64);
        for c in &counts {
            prefix.push(prefix.last().unwrap() + c[ti]);
        }
        let total = *prefix.last().unwrap();
        if total == 0 {
            continue;
        }
        let mut rng =
            rand_chacha::ChaCha8Rng::seed_from_u64(pattern::hash(&[cfg.seed, 0xce47, setting as u64, s as u64]));
        let n = cfg.certified_tiles.min(total as usize);
        let picks: Vec<u64> = if n == total as usize {
            (0..total).collect()
        } else {
            let mut p: Vec<u64> =
                rand::seq::index::sample(&mut rng, total as usize, n).into_iter().map(|x| x as u64).collect();
            p.sort_unstable();
            p
        };
        for g in picks {
            let tri = prefix.partition_point(|&p| p <= g) - 1;
            chosen[tri].push((ti, g - prefix[tri]));
        }
    }
    chosen
}
