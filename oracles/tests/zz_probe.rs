use oracles::extents::*;
use oracles::interval::Interval;
use oracles::Tri;
#[test]
#[ignore]
fn probe_box_cost() {
    let mk = |x: f64, y: f64, w: f64| [x * w, y * w, 0.5 * w, w];
    let q = [mk(0.0, 0.0, 1.0), mk(4.0, 0.0, 1.5), mk(0.0, 4.0, 2.0)];
    let r = [mk(8.0, 0.0, 1.2), mk(12.0, 0.0, 1.0), mk(8.0, 4.0, 2.5)];
    let tri = Tri { q, r, c0: [1.0, -0.5, 2.0], c1: [1.5, -0.2, 2.5], k: 1.0 };
    let b = [Interval::new(5.0, 6.0), Interval::new(1.0, 2.0), Interval::new(-1.0, 1.0), Interval::new(-1.0, 1.0), Interval::new(0.0, 1.0)];
    let st = std::time::Instant::now();
    let mut acc = 0.0;
    for _ in 0..100_000 {
        let bv = box_values(&tri, &std::hint::black_box(b));
        acc += bv.d.lo;
    }
    eprintln!("box_values: {:?} per box ({acc})", st.elapsed() / 100_000);
    let st = std::time::Instant::now();
    let mut n = 0;
    for i in 0..1_000_000 {
        let s = [5.0 + (i % 1000) as f64 * 1e-3, 1.5, 0.1, 0.2, (i % 997) as f64 / 997.0];
        n += (oracles::classify(&tri, std::hint::black_box(s)) == oracles::Coverage::Interior) as u32;
    }
    eprintln!("classify: {:?} per sample ({n})", st.elapsed() / 1_000_000);
}
