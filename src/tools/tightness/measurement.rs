//! The measurement itself: the plan of which methods are asked per tile, one triangle
//! measured at every tile size ([`measure_triangle`]), and [`measure`] over a scene.

use super::ceiling::{certify, choose_certified, count_in_box, covered_box};
use super::count::{count_admitted, count_passing, region_pass, AdmitScratch, Here};
use super::coverage::{exact_coverage, CoverageScratch};
use super::geometry::{footprint, tile_of, tile_pixels, tile_range, Footprint, PixelRect};
use super::scene::{Scene, Setting};
use super::sums::{Sums, TriCounts};
use super::table::{tile_rows, Local, SampleTable};
use super::types::{CeilingRow, Config, Measurement, MethodRow};
use crate::bounds::{Conjunction, Grid, Method, Prepared, SampleConstraint, TileGrid, TileResult};
use crate::model::Triangle;
use indicatif::ProgressBar;
use oracles::batch::Batch;
use rayon::prelude::*;

/// What every triangle of one setting shares.
struct Ctx<'a> {
    methods: &'a [&'static dyn Method],
    plan: &'a Plan,
    cfg: &'a Config,
    table: &'a SampleTable,
    setting: Setting,
}

/// The most parts of a conjunction met from its parts' answers (one with more is asked
/// itself).
const MAX_PARTS: usize = 4;

/// A placeholder answer.
static EMPTY: TileResult = TileResult::Empty;

/// Where a method's tile answer comes from.
enum Source {
    /// Its own setup (slot index).
    Own(usize),
    /// A conjunction of other methods' answers ([`Method::conjunction`]), their slots in
    /// order: derived from the answers the slots give anyway.
    Conj(Conjunction, Vec<usize>),
}

/// The methods the measurement sets up and asks per tile (**slots**: each distinct
/// method once), and per method of the run where its answer comes from. A method that
/// is by definition a conjunction of other registered methods (lc, mam2012-new and
/// their -safe variants) is not asked itself: its parts are (once, when they are also
/// in the run) and its answer is met from theirs ([`Conjunction::meet`], bit for bit
/// its own answer), so no tile test is repeated for the same tile.
struct Plan {
    slots: Vec<&'static dyn Method>,
    of: Vec<Source>,
}

impl Plan {
    fn new(methods: &[&'static dyn Method]) -> Plan {
        let mut slots: Vec<&'static dyn Method> = Vec::new();
        let mut slot = |m: &'static dyn Method| -> usize {
            let id = m.info().id;
            slots.iter().position(|x| x.info().id == id).unwrap_or_else(|| {
                slots.push(m);
                slots.len() - 1
            })
        };
        let mut of = Vec::with_capacity(methods.len());
        for &m in methods {
            of.push(match m.conjunction() {
                Some(c)
                    if (1..=MAX_PARTS).contains(&c.parts.len())
                        && c.parts.iter().all(|p| p.conjunction().is_none()) =>
                {
                    Source::Conj(c, c.parts.iter().map(|p| slot(**p)).collect())
                }
                _ => Source::Own(slot(m)),
            });
        }
        Plan { slots, of }
    }
}

/// Buffers reused from triangle to triangle (one per worker).
#[derive(Default)]
struct Scratch {
    covered: Vec<bool>,
    rows: Vec<(usize, usize, usize)>,
    coverage: CoverageScratch,
    admit: AdmitScratch,
    /// Buffers of [`region_pass`], kept from triangle to triangle.
    passes: Vec<Vec<bool>>,
}

fn measure_triangle(
    ctx: &Ctx,
    scratch: &mut Scratch,
    tri: &Triangle,
    fp: Footprint,
    chosen: &[(usize, u64)],
    out: &mut TriCounts,
) {
    let Ctx { methods, plan, cfg, table, setting } = *ctx;
    let (width, height) = (table.width, table.height);
    let nt = cfg.tiles.len();
    out.reset(nt, methods.len());
    let r = match fp {
        Footprint::OffScreen => {
            out.off_screen = true;
            return;
        }
        Footprint::WholeScreen => {
            out.whole_screen = true;
            PixelRect { x0: 0, y0: 0, x1: width - 1, y1: height - 1 }
        }
        Footprint::Region(r) => r,
    };
    // The union of the tiles of every size over r (tiles clipped to the screen).
    let mut u = r;
    for &s in &cfg.tiles {
        let (tx0, ty0, tx1, ty1) = tile_range(&r, s);
        u.x0 = u.x0.min(tx0 * s);
        u.y0 = u.y0.min(ty0 * s);
        u.x1 = u.x1.max(((tx1 + 1) * s).min(width) - 1);
        u.y1 = u.y1.max(((ty1 + 1) * s).min(height) - 1);
    }
    let spp = table.spp;
    let mut covered = std::mem::take(&mut scratch.covered);
    covered.clear();
    covered.resize(u.pixels() as usize * spp, false);
    let mut local = Local { rect: u, spp, covered };
    let otri = tri.to_oracle();
    let batch = Batch::new(&otri);
    let n_row = (r.x1 - r.x0 + 1) as usize * spp;
    for py in r.y0..=r.y1 {
        let (ts, ls) = (table.start(r.x0, py), local.start(r.x0, py));
        let (c, b, e) = exact_coverage(
            &batch,
            &table.samples[ts..ts + n_row],
            &mut scratch.coverage,
            &mut local.covered[ls..ls + n_row],
        );
        out.classified += n_row as u64;
        out.covered += c;
        out.boundary += b;
        out.exact += e;
    }
    let dims = tri.dims();
    let preps: Vec<Box<dyn Prepared>> = plan.slots.iter().map(|m| m.setup(tri)).collect();
    let slot_disabled: Vec<bool> = preps.iter().map(|p| p.disabled().is_some()).collect();
    for (d, src) in out.disabled.iter_mut().zip(&plan.of) {
        *d = match src {
            Source::Own(k) => slot_disabled[*k],
            Source::Conj(_, parts) => parts.iter().all(|&k| slot_disabled[k]),
        };
    }
    // The slots whose answer does not read the tile: asked once, and the values of their
    // per-sample constraints taken once per sample of the region (`pass`).
    let mut fixed: Vec<Option<TileResult>> = Vec::with_capacity(preps.len());
    let mut pass: Vec<Option<Vec<bool>>> = Vec::with_capacity(preps.len());
    let mut pool = std::mem::take(&mut scratch.passes);
    let any_tile = tile_of(&tile_pixels(r.x0 / cfg.tiles[0], r.y0 / cfg.tiles[0], cfg.tiles[0], width, height));
    for p in &preps {
        if p.tile_independent() {
            let a = p.tile(&any_tile);
            pass.push(match &a {
                TileResult::Bounds(b) if !b.constraints.is_empty() => {
                    let mut ps = pool.pop().unwrap_or_default();
                    region_pass(&mut scratch.admit, &[&b.constraints], table, &local, &mut ps);
                    Some(ps)
                }
                _ => None,
            });
            fixed.push(Some(a));
        } else {
            fixed.push(None);
            pass.push(None);
        }
    }
    let mut rows = std::mem::take(&mut scratch.rows);
    let mut admit = std::mem::take(&mut scratch.admit);
    let mut asked: Vec<Option<TileResult>> = Vec::with_capacity(preps.len());
    for (ti, &s) in cfg.tiles.iter().enumerate() {
        for (mi, w) in out.work[ti].iter_mut().enumerate() {
            w.add_setup(out.disabled[mi]);
        }
        let (tx0, ty0, tx1, ty1) = tile_range(&r, s);
        let ntx = (tx1 - tx0 + 1) as u64;
        // The tiles' boundaries (`tile_of(tile_pixels(..))`: the last one clipped to the
        // screen), and each asked method's answers over that grid.
        let xs: Vec<f32> = (tx0..=tx1).map(|t| (t * s) as f32).chain([((tx1 + 1) * s).min(width) as f32]).collect();
        let ys: Vec<f32> = (ty0..=ty1).map(|t| (t * s) as f32).chain([((ty1 + 1) * s).min(height) as f32]).collect();
        let grid = Grid::new(&xs, &ys);
        let grids: Vec<Option<Box<dyn TileGrid>>> =
            preps.iter().zip(&fixed).map(|(p, f)| f.is_none().then(|| p.grid(grid))).collect();
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                let p = tile_pixels(tx, ty, s, width, height);
                let tile = tile_of(&p);
                tile_rows(table, &local, &p, &mut rows);
                let n_here = rows.iter().map(|r| r.2 as u64).sum::<u64>();
                let cov_here = rows
                    .iter()
                    .map(|&(_, ls, n)| local.covered[ls..ls + n].iter().map(|&c| c as u32).sum::<u32>() as u64)
                    .sum::<u64>();
                if cov_here > 0 {
                    if let Some(b) = covered_box(table, &local, &rows, dims) {
                        let tested = rows.iter().map(|&(ts, _, n)| count_in_box(table, ts, n, &b)).sum::<u64>();
                        out.ceiling[ti].0 += tested;
                        out.ceiling[ti].1 += cov_here;
                    }
                }
                let (i, j) = ((tx - tx0) as usize, (ty - ty0) as usize);
                debug_assert_eq!(format!("{:?}", grid.tile(i, j)), format!("{tile:?}"));
                // Each slot's previous answer is dropped just before its new one is made,
                // so the allocator hands the freed constraint boxes straight back.
                asked.resize_with(grids.len(), || None);
                for (a, g) in asked.iter_mut().zip(&grids) {
                    *a = None;
                    *a = g.as_ref().map(|g| g.tile(i, j));
                }
                let answer = |k: usize| -> &TileResult { fixed[k].as_ref().or(asked[k].as_ref()).expect("asked") };
                for (mi, src) in plan.of.iter().enumerate() {
                    let c = &mut out.counts[ti][mi];
                    let w = &mut out.work[ti][mi];
                    let here = Here { table, local: &local, rows: &rows, n: n_here, cov: cov_here };
                    let kept = match src {
                        Source::Own(k) => match answer(*k) {
                            TileResult::Empty => false,
                            TileResult::Bounds(b) => {
                                let iv = (b.u, b.v, b.t);
                                match &pass[*k] {
                                    Some(ps) => count_passing(iv, ps, &here, c),
                                    None => count_admitted(&mut admit, iv, &[&b.constraints], &here, c),
                                }
                                true
                            }
                        },
                        Source::Conj(conj, parts) => {
                            let mut ans: [&TileResult; MAX_PARTS] = [&EMPTY; MAX_PARTS];
                            for (a, &k) in ans.iter_mut().zip(parts) {
                                *a = answer(k);
                            }
                            let ans = &ans[..parts.len()];
                            match conj.meet(ans) {
                                None => false,
                                Some(mt) => {
                                    let mut cons: [&[Box<dyn SampleConstraint>]; MAX_PARTS] = [&[]; MAX_PARTS];
                                    for (c, a) in cons.iter_mut().zip(ans) {
                                        if let TileResult::Bounds(b) = a {
                                            *c = &b.constraints;
                                        }
                                    }
                                    count_admitted(&mut admit, (mt.u, mt.v, mt.t), &cons[..ans.len()], &here, c);
                                    true
                                }
                            }
                        }
                    };
                    if kept {
                        w.add_tile(out.disabled[mi], n_here);
                    } else {
                        w.add_tile(out.disabled[mi], 0);
                        c.missed += cov_here;
                    }
                }
                let l = (ty - ty0) as u64 * ntx + (tx - tx0) as u64;
                // `chosen` is sorted: tile sizes in order, each one's tiles in order.
                if chosen.binary_search(&(ti, l)).is_ok() {
                    out.certified.push(certify(&otri, dims, table, &local, &p, &cfg.certified, setting, s));
                }
            }
        }
    }
    scratch.rows = rows;
    scratch.admit = admit;
    scratch.covered = local.covered;
    pool.extend(pass.into_iter().flatten());
    scratch.passes = pool;
}

/// `a / b`, None when b = 0.
fn ratio(a: u64, b: u64) -> Option<f64> {
    (b > 0).then(|| a as f64 / b as f64)
}

/// Measure the STE of `methods` on `scene` for each setting (see the module
/// documentation). `pb` advances by one per triangle and setting.
pub fn measure(
    scene: &Scene,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    cfg: &Config,
    pb: &ProgressBar,
) -> Measurement {
    let table = SampleTable::new(&cfg.pattern, scene.width, scene.height);
    measure_with(scene, &table, methods, settings, cfg, pb)
}

/// [`measure`] on a sample table built beforehand (`table` must be the pattern of
/// `cfg` over the scene's screen).
pub fn measure_with(
    scene: &Scene,
    table: &SampleTable,
    methods: &[&'static dyn Method],
    settings: &[Setting],
    cfg: &Config,
    pb: &ProgressBar,
) -> Measurement {
    let (w, h) = (scene.width, scene.height);
    assert_eq!((table.width, table.height, table.spp), (w, h, cfg.pattern.spp as usize), "sample table mismatch");
    let mut m = Measurement::default();
    let plan = Plan::new(methods);
    for &setting in settings {
        let tris = scene.triangles(setting);
        let fps: Vec<Footprint> = tris.iter().map(|t| footprint(t, w, h)).collect();
        let chosen = choose_certified(&fps, cfg, setting, w, h);
        let ctx = Ctx { methods, plan: &plan, cfg, table, setting };
        let nm = methods.len();
        // Each worker keeps its buffers and its partial sums from triangle to triangle.
        let sums = tris
            .par_iter()
            .zip(fps.par_iter())
            .zip(chosen.par_iter())
            .fold(
                || (Scratch::default(), TriCounts::default(), Sums::new(setting, &cfg.tiles, nm)),
                |(mut scratch, mut tc, mut acc), ((t, &fp), ch)| {
                    measure_triangle(&ctx, &mut scratch, t, fp, ch, &mut tc);
                    acc.add(&tc, &cfg.tiles);
                    pb.inc(1);
                    (scratch, tc, acc)
                },
            )
            .map(|(_, _, acc)| acc)
            .reduce(|| Sums::new(setting, &cfg.tiles, nm), Sums::merge);
        let Sums { summary: sum, counts, work, ceiling, disabled, certified } = sums;
        for (ti, &s) in cfg.tiles.iter().enumerate() {
            for (mi, meth) in methods.iter().enumerate() {
                let info = meth.info();
                let c = counts[ti][mi];
                m.rows.push(MethodRow {
                    method: info.id.to_string(),
                    reconstruction: info.reconstruction,
                    per_sample: info.outputs.per_sample,
                    setting,
                    tile: s,
                    counts: c,
                    ste: ratio(c.hits, c.tested),
                    disabled_triangles: disabled[mi],
                    work: work[ti][mi],
                });
            }
            let (tested, covered) = ceiling[ti];
            m.ceiling.push(CeilingRow { setting, tile: s, tested, covered, ste: ratio(covered, tested) });
            if cfg.certified_tiles > 0 {
                let mut c = certified[ti].clone();
                c.ste_lower = ratio(c.covered, c.tested_certified);
                c.ste_upper = ratio(c.covered, c.tested_sample_box);
                m.certified.push(c);
            }
        }
        m.settings.push(sum);
    }
    m
}
