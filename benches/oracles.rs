//! Speed of the ground truth: exact coverage (fast path + fallback rate), Embree rays
//! (single vs packets of 16) on the same samples, and certified tile extents.
//! `cargo bench --bench oracles`; criterion writes estimates.json under target/criterion.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use cullproof::cases::generate::{physical_case, rng_for, samples_for, Regime};
use cullproof::judge::agree::lens_tri;
use oracles::embree::EmbreeOracle;
use oracles::extents::{box_values_with, tile_extents, Box5, ExtentsConfig};
use oracles::interval::Interval;

fn cases() -> Vec<(cullproof::model::Case, Vec<[f64; 5]>)> {
    (0..14u64)
        .map(|i| {
            let mut rng = rng_for(99, i);
            let c = physical_case(&mut rng, Regime::ALL[(i % 7) as usize]);
            let s = samples_for(&c, &mut rng, 4096);
            (c, s)
        })
        .collect()
}

fn coverage(c: &mut Criterion) {
    let cs = cases();
    let n: u64 = cs.iter().map(|(_, s)| s.len() as u64).sum();
    let mut g = c.benchmark_group("coverage");
    g.throughput(Throughput::Elements(n));
    let tris: Vec<_> = cs.iter().map(|(c, _)| c.triangle.to_oracle()).collect();
    g.bench_function("exact", |b| {
        b.iter(|| {
            let mut k = 0u64;
            for (t, (_, s)) in tris.iter().zip(&cs) {
                for &x in s {
                    k += (oracles::classify(t, x) == oracles::Coverage::Interior) as u64;
                }
            }
            black_box(k)
        })
    });
    // The same samples in lanes; the per-triangle precomputation is timed too.
    g.bench_function("exact_batch", |b| {
        let mut out = Vec::new();
        b.iter(|| {
            let mut k = 0u64;
            for (t, (_, s)) in tris.iter().zip(&cs) {
                oracles::batch::Batch::new(t).classify(s, &mut out);
                k += out.iter().filter(|&&c| c == oracles::Coverage::Interior).count() as u64;
            }
            black_box(k)
        })
    });
    let ors: Vec<_> = cs.iter().map(|(c, _)| EmbreeOracle::new(&lens_tri(c).unwrap()).unwrap()).collect();
    g.bench_function("embree_single", |b| {
        b.iter(|| {
            let mut k = 0u64;
            for (o, (_, s)) in ors.iter().zip(&cs) {
                for &x in s {
                    k += o.hit(x) as u64;
                }
            }
            black_box(k)
        })
    });
    g.bench_function("embree_packet16", |b| {
        let mut out = Vec::new();
        b.iter(|| {
            let mut k = 0u64;
            for (o, (_, s)) in ors.iter().zip(&cs) {
                o.hits(s, &mut out);
                k += out.iter().filter(|&&h| h).count() as u64;
            }
            black_box(k)
        })
    });
    g.finish();
    // Fallback rate on uniform samples (printed once; not a timing).
    let mut st = oracles::CoverageStats::default();
    let mut out = Vec::new();
    for (t, (_, s)) in tris.iter().zip(&cs) {
        let uni: Vec<_> = s.iter().step_by(2).cloned().collect();
        st = st.merge(oracles::coverage::classify_all(t, &uni, &mut out));
    }
    eprintln!("exact fallbacks on uniform samples: {} of {}", st.exact_fallbacks, st.samples);
    let mut bs = oracles::batch::BatchStats::default();
    for (t, (_, s)) in tris.iter().zip(&cs) {
        bs = bs.merge(oracles::batch::classify_batch(t, s, &mut Vec::new()));
    }
    let regimes: Vec<_> = tris.iter().map(|t| oracles::batch::Batch::new(t).regime()).collect();
    eprintln!(
        "exact_batch on all samples: {} of {} deferred to the scalar oracle, {} of them exact; regimes {regimes:?}",
        bs.deferred, bs.samples, bs.exact_fallbacks
    );
}

fn extents(c: &mut Criterion) {
    // 2x2-pixel tiles on the footprint of each case at (u, v, t) = (0, 0, 0.5).
    let cs = cases();
    let mut jobs = Vec::new();
    for (case, s) in &cs {
        let t = case.triangle.to_oracle();
        if let Some(x) = s.iter().find(|x| oracles::classify(&t, **x) == oracles::Coverage::Interior) {
            let (x0, y0) = (x[0].floor(), x[1].floor());
            jobs.push((t, [x0, x0 + 2.0, y0, y0 + 2.0]));
        }
    }
    let cfg = ExtentsConfig::default();
    // Count-based cost (not noisy): boxes examined and boxes left undecided per tile.
    let (mut nodes, mut undecided) = (0u64, 0u64);
    for (t, tile) in &jobs {
        let ex = tile_extents(t, *tile, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg);
        (nodes, undecided) = (nodes + ex.boxes, undecided + ex.undecided);
    }
    eprintln!(
        "extents: {} tiles, {:.1} boxes per tile, {} undecided in all",
        jobs.len(),
        nodes as f64 / jobs.len().max(1) as f64,
        undecided
    );
    let mut g = c.benchmark_group("extents");
    g.sample_size(10);
    g.throughput(Throughput::Elements(jobs.len() as u64));
    g.bench_function("tile_2x2_res1e-4", |b| {
        b.iter(|| {
            for (t, tile) in &jobs {
                black_box(tile_extents(t, *tile, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg));
            }
        })
    });
    g.finish();
    // One box judgement (the unit of every certified search): boxes around covered
    // samples of each case, from the whole tile down to 2^-20 of it.
    let mut boxes: Vec<(oracles::Tri, Box5)> = Vec::new();
    for (case, s) in &cs {
        let t = case.triangle.to_oracle();
        for (k, x) in
            s.iter().filter(|x| oracles::classify(&t, **x) == oracles::Coverage::Interior).take(64).enumerate()
        {
            let f = 0.5f64.powi((k % 21) as i32);
            let half = [0.5 * f, 0.5 * f, f, f, 0.5 * f];
            boxes.push((t, std::array::from_fn(|i| Interval::new(x[i] - half[i], x[i] + half[i]))));
        }
    }
    let mut g = c.benchmark_group("box_values");
    g.throughput(Throughput::Elements(boxes.len() as u64));
    for depth in [false, true] {
        g.bench_function(if depth { "with_depth" } else { "coverage_only" }, |b| {
            b.iter(|| {
                for (t, bx) in &boxes {
                    black_box(box_values_with(t, bx, depth));
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, coverage, extents);
criterion_main!(benches);
