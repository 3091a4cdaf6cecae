//! Cost of every culling method, per element: the per-triangle setup, the tile test on
//! 1 and 4 px tiles, and the per-sample test (intervals, per-sample constraints, and the
//! depth interval z^ when the method gives one).
//!
//! Each method runs on the first 64 cases of the check's placement (`cases::make_case`, seed 7,
//! every regime in turn) whose triangle has dimensions the method is designed for
//! (`MethodInfo::dims`): a motion-only method is not timed on defocused triangles,
//! where it only answers "disabled". Setup and the tile test are timed with what they
//! allocate (the boxed `Prepared`, the answer's boxed constraints) and free.
//! `cargo bench --bench bounds`; criterion writes estimates.json under target/criterion
//! (`setup/<id>`, `tile/<id>/<px>`, `sample/<id>`), each with its elements per iteration
//! in benchmark.json.

use criterion::measurement::WallTime;
use criterion::{black_box, criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, Throughput};
use cullproof::bounds::{registry, Method, Prepared, TileBounds, TileResult};
use cullproof::cases::generate::{rng_for, tile_sample};
use cullproof::cases::make_case;
use cullproof::gate::CheckConfig;
use cullproof::model::{Sample, Tile, Triangle};
use std::time::Duration;

const SEED: u64 = 7;
/// Cases per method.
const CASES: usize = 64;
/// Tile sizes of the tile test (px): the sizes the project reports.
const TILES: [f32; 2] = [1.0, 4.0];
/// The tile of the per-sample test: `TILES[SAMPLE_TILE]` = 4 px, with 256 samples
/// (16 per pixel).
const SAMPLE_TILE: usize = 1;
const SAMPLES: usize = 256;
/// Case indices scanned at most to find `CASES` per method.
const SCAN: u64 = 20_000;

/// One case of the placement: the triangle and its tile at each size of `TILES`.
struct Case {
    index: u64,
    tri: Triangle,
    tiles: [Tile; 2],
}

/// Cases in index order until every method has `CASES` of its dimensions.
fn cases(methods: &[&'static dyn Method]) -> Vec<Case> {
    let cfgs = TILES.map(|size| {
        let mut c = CheckConfig::default_with(registry());
        c.seed = SEED;
        c.tile = Some(size);
        c
    });
    let mut out: Vec<Case> = Vec::new();
    for index in 0..SCAN {
        let enough = methods.iter().all(|m| designed(*m, &out).len() >= CASES);
        if enough {
            break;
        }
        let (_, c, t0) = make_case(&cfgs[0].draw(), index);
        let (_, c1, t1) = make_case(&cfgs[1].draw(), index);
        // The case is drawn before the tile: the same triangle at every size.
        assert_eq!(c.triangle, c1.triangle);
        out.push(Case { index, tri: c.triangle, tiles: [t0, t1] });
    }
    for m in methods {
        assert!(designed(*m, &out).len() >= CASES, "{}: fewer than {CASES} cases of its dims", m.info().id);
    }
    out
}

/// The first `CASES` cases whose triangle has dimensions the method is designed for.
fn designed<'a>(m: &dyn Method, cs: &'a [Case]) -> Vec<&'a Case> {
    cs.iter().filter(|c| m.info().dims.contains(&c.tri.dims())).take(CASES).collect()
}

/// The hit depth N / D of the triangle's plane at the sample, in f32 as a rasterizer
/// interpolates it (the vertices sheared to the sample's (u, v, t) and translated to its
/// (x, y); E_k the edge functions, D = sum w_k E_k, N = sum z_k E_k).
fn plane_depth(tri: &Triangle, s: &Sample) -> f32 {
    let p: [[f32; 4]; 3] = std::array::from_fn(|i| {
        let (v, c) = (tri.at(i, s.t), tri.coc(i, s.t));
        [v[0] + s.u * c - s.x * v[3], v[1] + tri.k * s.v * c - s.y * v[3], v[2], v[3]]
    });
    let e = [
        p[1][0] * p[2][1] - p[1][1] * p[2][0],
        p[2][0] * p[0][1] - p[2][1] * p[0][0],
        p[0][0] * p[1][1] - p[0][1] * p[1][0],
    ];
    let d = p[0][3] * e[0] + p[1][3] * e[1] + p[2][3] * e[2];
    let n = p[0][2] * e[0] + p[1][2] * e[1] + p[2][2] * e[2];
    n / d
}

/// The per-sample test: the intervals and constraints, then the depth interval.
#[inline]
fn passes(b: &TileBounds, s: &Sample, depth: f32) -> bool {
    b.admits(s) && b.z.is_none_or(|z| z[0] <= depth && depth <= z[1])
}

fn configure(g: &mut BenchmarkGroup<'_, WallTime>) {
    g.sample_size(20);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(1));
}

fn setup(c: &mut Criterion) {
    let methods = registry();
    let cs = cases(&methods);
    let mut g = c.benchmark_group("setup");
    configure(&mut g);
    for m in &methods {
        let tris: Vec<Triangle> = designed(*m, &cs).iter().map(|c| c.tri).collect();
        let disabled = tris.iter().filter(|t| m.setup(t).disabled().is_some()).count();
        eprintln!("{}: {} triangles of {:?}, disabled on {disabled}", m.info().id, tris.len(), m.info().dims);
        g.throughput(Throughput::Elements(tris.len() as u64));
        g.bench_function(m.info().id, |b| {
            b.iter(|| {
                for t in &tris {
                    black_box(m.setup(black_box(t)));
                }
            })
        });
    }
    g.finish();
}

fn tile(c: &mut Criterion) {
    let methods = registry();
    let cs = cases(&methods);
    let mut g = c.benchmark_group("tile");
    configure(&mut g);
    for m in &methods {
        let mine = designed(*m, &cs);
        let preps: Vec<Box<dyn Prepared>> = mine.iter().map(|c| m.setup(&c.tri)).collect();
        for (k, size) in TILES.iter().enumerate() {
            let tiles: Vec<Tile> = mine.iter().map(|c| c.tiles[k]).collect();
            let empty = preps.iter().zip(&tiles).filter(|(p, t)| matches!(p.tile(t), TileResult::Empty)).count();
            eprintln!("{} at {size} px: {empty} of {} tiles empty", m.info().id, tiles.len());
            g.throughput(Throughput::Elements(tiles.len() as u64));
            g.bench_with_input(BenchmarkId::new(m.info().id, *size as u32), &tiles, |b, tiles| {
                b.iter(|| {
                    for (p, t) in preps.iter().zip(tiles) {
                        black_box(p.tile(black_box(t)));
                    }
                })
            });
        }
    }
    g.finish();
}

fn sample(c: &mut Criterion) {
    let methods = registry();
    let cs = cases(&methods);
    let mut g = c.benchmark_group("sample");
    configure(&mut g);
    for m in &methods {
        // Per non-empty tile: its bounds and the samples with their plane depths.
        let mut work: Vec<(TileBounds, Vec<(Sample, f32)>)> = Vec::new();
        for c in designed(*m, &cs) {
            let tile = c.tiles[SAMPLE_TILE];
            let TileResult::Bounds(b) = m.setup(&c.tri).tile(&tile) else { continue };
            let mut rng = rng_for(SEED + 1, c.index);
            let ss = (0..SAMPLES)
                .map(|_| {
                    let s = tile_sample(&mut rng, &tile);
                    (s, plane_depth(&c.tri, &s))
                })
                .collect();
            work.push((b, ss));
        }
        let n: usize = work.iter().map(|(_, ss)| ss.len()).sum();
        let passed: usize = work.iter().map(|(b, ss)| ss.iter().filter(|(s, d)| passes(b, s, *d)).count()).sum();
        let with_constraints = work.iter().filter(|(b, _)| !b.constraints.is_empty()).count();
        let with_z = work.iter().filter(|(b, _)| b.z.is_some()).count();
        eprintln!(
            "{}: {} tiles ({with_constraints} with constraints, {with_z} with z^), {passed} of {n} samples pass",
            m.info().id,
            work.len()
        );
        if n == 0 {
            continue;
        }
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(m.info().id, |b| {
            b.iter(|| {
                let mut k = 0u64;
                for (tb, ss) in &work {
                    for (s, d) in ss {
                        k += passes(tb, s, *d) as u64;
                    }
                }
                black_box(k)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, setup, tile, sample);
criterion_main!(benches);
