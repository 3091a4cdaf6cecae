//! An independent attack on what `gdam2010-safe` vouches for over a box, the two
//! things the judge proves its tiles with: its box enclosure (`eval_box >= 0`: no
//! sample of the box culled) and its cuts (`lower_cuts`: no sample culled where every
//! cut holds, one family per side of a facing flip). Triangles come from this file's
//! own generator (static, moving, flipping facing, tiny, far from the origin); boxes
//! are placed at several scales on the triangle's edges and vertices; inside each,
//! f32 samples are drawn at random and pushed onto the band next to each edge where
//! the method's pad decides (edge values between minus the pad and 0), and every one
//! the claim covers is evaluated with the method's own f32 code: one culled sample is a
//! false claim. Then the gate's judge is run on boundary tiles and every tile it proves
//! is attacked with exact samples at the edges. A planted wrong cut (its constant
//! raised past the pad) shows the attack can fail.

use cullproof::bounds::{by_id, Cut, SampleBox, TileResult};
use cullproof::judge::constraints::{self, ConstraintVerdict};
use cullproof::{Interval, Sample, Tile, Triangle};
use oracles::coverage::{classify, Coverage};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A motion-only triangle: screen positions around `centre`, depth w in [0.2, 5],
/// static, moving, or flipping facing during the shutter.
fn triangle(rng: &mut ChaCha8Rng) -> Triangle {
    let centre = [0.0f64, 50.0, 3000.0, 1.0e5][rng.gen_range(0..4)];
    let size = [0.5f64, 8.0, 60.0][rng.gen_range(0..3)];
    let kind = rng.gen_range(0..3); // 0 static, 1 moving, 2 flipping
    let mut q = [[0.0f32; 4]; 3];
    let mut r = [[0.0f32; 4]; 3];
    for i in 0..3 {
        let (sx, sy) = (centre + rng.gen_range(-size..size), centre + rng.gen_range(-size..size));
        let w: f64 = rng.gen_range(0.2..5.0);
        q[i] = [(sx * w) as f32, (sy * w) as f32, 0.5, w as f32];
        r[i] = match kind {
            0 => q[i],
            1 => {
                let (ex, ey) = (sx + rng.gen_range(-size..size), sy + rng.gen_range(-size..size));
                let w1 = w * rng.gen_range(0.7..1.4);
                [(ex * w1) as f32, (ey * w1) as f32, 0.5, w1 as f32]
            }
            _ => q[i],
        };
    }
    if kind == 2 {
        // Vertex 0 crosses the opposite edge: the winding turns over.
        let (a, b) = (q[1], q[2]);
        let m = |c: usize| 0.5 * (a[c] / a[3] + b[c] / b[3]);
        let (px, py) = (q[0][0] / q[0][3], q[0][1] / q[0][3]);
        let (ex, ey) = (2.0 * m(0) - px, 2.0 * m(1) - py);
        r[0] = [ex * q[0][3], ey * q[0][3], 0.5, q[0][3]];
    }
    Triangle { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 }
}

/// Vertex i's position relative to pixel (x, y) at time t, in f64.
fn rel(tri: &Triangle, i: usize, x: f64, y: f64, t: f64) -> (f64, f64) {
    let l = |c: usize| tri.q[i][c] as f64 + t * (tri.r[i][c] as f64 - tri.q[i][c] as f64);
    (l(0) - x * l(3), l(1) - y * l(3))
}

/// Edge k's value at a sample, in f64 (edges (1, 2), (2, 0), (0, 1)).
fn edge(tri: &Triangle, k: usize, x: f64, y: f64, t: f64) -> f64 {
    let (i, j) = [(1, 2), (2, 0), (0, 1)][k];
    let (a, b) = (rel(tri, i, x, y, t), rel(tri, j, x, y, t));
    a.0 * b.1 - a.1 * b.0
}

/// The pad `gdam2010-safe` states for edge k at pixel (x, y), in f64: `2^-26 (m_i +
/// m_j)^2 + 2^-52 (n_i + n_j)^2` with `m` the sizes of the vertices relative to the
/// pixel and their motions, `n` their sizes on the screen (the method's module doc).
fn pad_at(tri: &Triangle, k: usize, x: f64, y: f64) -> f64 {
    let (i, j) = [(1, 2), (2, 0), (0, 1)][k];
    let m = |v: usize| {
        let (a, b) = (rel(tri, v, x, y, 0.0), rel(tri, v, x, y, 1.0));
        a.0.abs() + a.1.abs() + (b.0 - a.0).abs() + (b.1 - a.1).abs()
    };
    let n = |v: usize| {
        let (q, r) = (tri.q[v].map(|c| c as f64), tri.r[v].map(|c| c as f64));
        q[0].abs() + q[1].abs() + r[0].abs() + r[1].abs() + (q[3].abs() + r[3].abs()) * (x.abs() + y.abs())
    };
    2f64.powi(-26) * (m(i) + m(j)).powi(2) + 2f64.powi(-52) * (n(i) + n(j)).powi(2)
}

/// f32 samples of the box: random ones, and ones moved in x onto `E_k = target` for
/// targets across the band where the pad decides (0 to -2 pads; then a few f32 steps
/// either way), clamped into the box.
fn samples(tri: &Triangle, b: &SampleBox, rng: &mut ChaCha8Rng, n: usize) -> Vec<Sample> {
    // The f32 nearest v within the box's side (None when the side holds no f32).
    let f = |i: Interval, v: f64| -> Option<f32> {
        let mut s = v as f32;
        while (s as f64) < i.lo {
            s = s.next_up();
        }
        while (s as f64) > i.hi {
            s = s.next_down();
        }
        ((s as f64) >= i.lo).then_some(s)
    };
    let pick = |i: Interval, rng: &mut ChaCha8Rng| i.lo + rng.gen::<f64>() * (i.hi - i.lo);
    let mut out = Vec::new();
    for _ in 0..n {
        let (x, y, t) = (pick(b.x, rng), pick(b.y, rng), pick(b.t, rng));
        let (Some(fx), Some(fy), Some(ft)) = (f(b.x, x), f(b.y, y), f(b.t, t)) else { continue };
        out.push(Sample::new(fx, fy, 0.0, 0.0, ft));
        let k = rng.gen_range(0..3);
        // E_k is affine in x at fixed (y, t): solve for the target.
        let (e0, e1) = (edge(tri, k, x, y, t), edge(tri, k, x + 1.0, y, t));
        let slope = e1 - e0;
        if slope == 0.0 || !slope.is_finite() {
            continue;
        }
        let scale = pad_at(tri, k, x, y);
        let target = -scale * [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 2.0][rng.gen_range(0..7)];
        let xs = x + (target - e0) / slope;
        if !(b.x.lo..=b.x.hi).contains(&xs) {
            continue;
        }
        let Some(mut sx) = f(b.x, xs) else { continue };
        for _ in 0..rng.gen_range(0..4) {
            sx = if rng.gen() { sx.next_up() } else { sx.next_down() };
        }
        let Some(sx) = f(b.x, sx as f64) else { continue };
        out.push(Sample::new(sx, fy, 0.0, 0.0, ft));
    }
    out
}

/// Where the cuts vouch for a sample: every untagged cut holds and every cut of one
/// side's family holds (tested with a margin, so the f64 estimate decides).
fn vouched(cuts: &[Cut], s: &Sample) -> bool {
    let p = [s.x as f64, s.y as f64, 0.0, 0.0, s.t as f64];
    let holds = |c: &Cut| {
        let v = c.estimate(p);
        let scale = c.coef.iter().chain(c.t2.iter()).fold(0.0f64, |a, &x| a.max(x.abs())) * 1e-12;
        v >= c.err + scale
    };
    let all = |tag: i8| cuts.iter().filter(|c| c.d_sign == tag).all(holds);
    all(0) && ((!cuts.iter().any(|c| c.d_sign != 0)) || all(1) || all(-1))
}

/// A box of width `w` around a point on edge k (or at vertex k) at time t.
fn box_at(tri: &Triangle, rng: &mut ChaCha8Rng, w: f64) -> SampleBox {
    let t: f64 = if rng.gen() { rng.gen_range(0.0..1.0) } else { 0.0 };
    let k = rng.gen_range(0..3);
    let (i, j) = [(1, 2), (2, 0), (0, 1)][k];
    let at = |v: usize| {
        let l = |c: usize| tri.q[v][c] as f64 + t * (tri.r[v][c] as f64 - tri.q[v][c] as f64);
        (l(0) / l(3), l(1) / l(3))
    };
    let f = if rng.gen_bool(0.3) { 0.0 } else { rng.gen_range(0.0..1.0) };
    let (a, b) = (at(i), at(j));
    let (cx, cy) = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
    let (ox, oy) = (rng.gen_range(-0.5..0.5) * w, rng.gen_range(-0.5..0.5) * w);
    let iv = |c: f64| Interval::new(((c - 0.5 * w) as f32) as f64, ((c + 0.5 * w) as f32).next_up() as f64);
    let tw: f64 = [1.0, 0.1, 1e-3][rng.gen_range(0..3)];
    let t0 = (t - rng.gen::<f64>() * tw).max(0.0);
    let t1 = (t0 + tw).min(1.0);
    SampleBox {
        x: iv(cx + ox),
        y: iv(cy + oy),
        u: Interval::point(0.0),
        v: Interval::point(0.0),
        t: Interval::new((t0 as f32) as f64, (t1 as f32) as f64),
    }
}

struct Tally {
    boxes: usize,
    enclosed: usize,
    cut_boxes: usize,
    samples: usize,
    false_claims: Vec<String>,
}

fn attack(plant: Option<f64>, n_tri: usize, seed: u64) -> Tally {
    let m = by_id("gdam2010-safe").expect("registered");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally { boxes: 0, enclosed: 0, cut_boxes: 0, samples: 0, false_claims: Vec::new() };
    for _ in 0..n_tri {
        let tri = triangle(&mut rng);
        let prep = m.setup(&tri);
        let b = match prep.tile(&Tile::square(0.0, 0.0, 1.0)) {
            TileResult::Bounds(b) => b,
            TileResult::Empty => continue,
        };
        let Some(c) = b.constraints.first() else { continue };
        for _ in 0..12 {
            let w = [16.0, 1.0, 1e-3, 1e-6][rng.gen_range(0..4)];
            let bx = box_at(&tri, &mut rng, w);
            tally.boxes += 1;
            let enclosed = c.eval_box(&bx).lo >= 0.0;
            let mut cuts = Vec::new();
            let has_cuts = !enclosed && c.lower_cuts(&bx, &mut cuts);
            if let Some(raise) = plant {
                for cut in &mut cuts {
                    // A cut that claims more than the pad allows: raised by `raise` pads.
                    let pad = (0..3).map(|k| pad_at(&tri, k, bx.x.mid(), bx.y.mid())).fold(0.0, f64::max);
                    cut.coef[0] += raise * pad;
                }
            }
            if !enclosed && !has_cuts {
                continue;
            }
            tally.enclosed += enclosed as usize;
            tally.cut_boxes += has_cuts as usize;
            for s in samples(&tri, &bx, &mut rng, 60) {
                if !enclosed && !vouched(&cuts, &s) {
                    continue;
                }
                tally.samples += 1;
                let g = c.eval(&s);
                if g < 0.0 {
                    tally.false_claims.push(format!(
                        "{} culls {s:?} (eval {g}) in box {bx:?} of {tri:?}",
                        if enclosed { "eval_box >= 0" } else { "the cuts vouch, yet it" }
                    ));
                }
            }
        }
    }
    tally
}

#[test]
fn box_enclosures_and_cuts_hold_under_dense_samples() {
    let n = std::env::var("CULLPROOF_GDAM_ATTACK").ok().and_then(|v| v.parse().ok()).unwrap_or(400);
    let t = attack(None, n, 61);
    eprintln!(
        "gdam2010-safe box claims: {} boxes, {} enclosed >= 0, {} with cuts, {} samples they cover: {} false",
        t.boxes,
        t.enclosed,
        t.cut_boxes,
        t.samples,
        t.false_claims.len()
    );
    assert!(t.false_claims.is_empty(), "{}", t.false_claims[..t.false_claims.len().min(5)].join("\n"));
    assert!(t.enclosed > 50 && t.cut_boxes > 500 && t.samples > 50_000, "too little attacked");
}

#[test]
fn the_attack_finds_a_planted_wrong_cut() {
    // Cuts raised by one pad vouch for samples that the method culls (beyond its pad).
    let t = attack(Some(1.0), 150, 62);
    eprintln!("planted: {} false claims found in {} samples", t.false_claims.len(), t.samples);
    assert!(!t.false_claims.is_empty(), "the attack found nothing in {} samples", t.samples);
}

#[test]
fn every_tile_the_judge_proves_keeps_its_covered_edge_samples() {
    let m = by_id("gdam2010-safe").expect("registered");
    let mut rng = ChaCha8Rng::seed_from_u64(63);
    let (mut proved, mut tiles, mut interior, mut false_proofs) = (0, 0, 0, Vec::new());
    for _ in 0..150 {
        let tri = triangle(&mut rng);
        let o = tri.to_oracle();
        let prep = m.setup(&tri);
        for _ in 0..3 {
            let w = [1.0, 4.0, 16.0][rng.gen_range(0..3)];
            let bx = box_at(&tri, &mut rng, w);
            let (x0, y0) = (bx.x.lo.floor() as f32, bx.y.lo.floor() as f32);
            let tile = Tile::square(x0, y0, [1.0, 2.0, 4.0][rng.gen_range(0..3)]);
            let TileResult::Bounds(b) = prep.tile(&tile) else { continue };
            tiles += 1;
            if constraints::search(&o, &tile, &b, 2000, 1e-9).verdict != ConstraintVerdict::Proved {
                continue;
            }
            proved += 1;
            let whole = SampleBox {
                x: Interval::new(tile.x0 as f64, tile.x1 as f64),
                y: Interval::new(tile.y0 as f64, tile.y1 as f64),
                u: Interval::point(0.0),
                v: Interval::point(0.0),
                t: Interval::new(0.0, 1.0),
            };
            for s in samples(&tri, &whole, &mut rng, 400) {
                if classify(&o, s.to_oracle()) == Coverage::Interior {
                    interior += 1;
                    if !b.admits(&s) {
                        false_proofs.push(format!("{s:?} in {tile:?} of {tri:?}"));
                    }
                }
            }
        }
    }
    eprintln!(
        "gdam2010-safe judged tiles: {tiles}, proven {proved}, {interior} interior edge samples: {} culled",
        false_proofs.len()
    );
    assert!(false_proofs.is_empty(), "{}", false_proofs[..false_proofs.len().min(5)].join("\n"));
    assert!(proved > 200 && interior > 10_000, "{proved} {interior}");
}
