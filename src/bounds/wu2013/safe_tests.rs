//! The unit tests of `wu2013-safe` (`safe.rs`); the helpers shared with the published
//! method's tests (`tests.rs`) are taken from there.

use super::super::testkit::bounds_of;
use super::safe::*;
use super::tests::{
    bounds, cam, one_side_translated, opposite_motion, spot_check, spot_check_of, tile_on, translated, unconstrained,
};
use super::*;
use crate::bounds::arith::Plain;
use crate::bounds::round::Outward;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn safe_bounds(tri: &Triangle, tile: &Tile) -> Option<TileBounds> {
    bounds_of(METHOD_SAFE, tri, tile)
}

/// Every witness stored for `wu2013` (corpus/cases/wu2013) is admitted by the safe
/// variant: the original's violations are gone.
#[test]
fn safe_admits_the_corpus_witnesses() {
    use crate::search::{witness_holds, CaseFile};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/wu2013");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let path = e.unwrap().path();
        let cf = CaseFile::load(&path).unwrap();
        let Some(w) = &cf.witness else { continue };
        assert!(
            witness_holds(METHOD, &cf.case, &cf.tile, w.sample).is_ok(),
            "{}: not a wu2013 witness",
            path.display()
        );
        let r = witness_holds(METHOD_SAFE, &cf.case, &cf.tile, w.sample);
        assert!(r.is_err(), "{}: wu2013-safe culls the witness: {r:?}", path.display());
        n += 1;
    }
    assert!(n >= 10, "{n}");
}

/// The two findings of the published test, and the random triangles outside its
/// assumptions: the safe variant culls no covered sample there.
#[test]
fn safe_keeps_the_findings() {
    let tri = opposite_motion();
    let s = Sample::new(20.0, 20.0, 0.0, 0.0, 1.0);
    let tile = Tile::square(19.0, 19.0, 2.0);
    assert!(safe_bounds(&tri, &tile).is_some_and(|b| b.admits(&s)));
    spot_check_of(METHOD_SAFE, &tri, &tile, 4000, 22);
    let c = cam();
    let g = [[-1.0, -1.0, 2.5], [1.0, -1.0, 6.0], [0.0, 1.2, 6.0]];
    let tri = c.triangle(g, g);
    spot_check_of(METHOD_SAFE, &tri, &Tile::square(31.0, 31.0, 2.0), 4000, 21);
    let (culled, covered, tris) = unconstrained(METHOD_SAFE, 79);
    eprintln!("wu2013-safe, unconstrained: {culled} of {covered} covered samples culled ({tris} triangles)");
    assert_eq!(culled, 0);
}

/// The sign-aware hull of the crossings `cr` within `dom` (None: no part meets it).
fn sign_hull(cr: &[(bool, f32, f32); 3], dom: [f32; 2]) -> Option<[f32; 2]> {
    let o = IvOps::<Plain, Outward>::new(&Plain);
    let (some, r) = o.hull_within(&o.sign_parts(cr), &dom);
    some.then_some(r)
}

/// The sign-aware hull on the "no vertex crosses the row" example: two deltas stay
/// positive, one negative, all crossing times negative: the published [min, max] is
/// empty, the hull is the whole shutter.
#[test]
fn sign_hull_handles_both_directions() {
    // Decreasing deltas (D > 0) crossing at t in [-3, -2] and [-5, -4], an
    // increasing one at [-1, -0.5]: for t >= 0 the first two are < 0, the third > 0.
    let cr = [(false, -3.0, -2.0), (false, -5.0, -4.0), (true, -1.0, -0.5)];
    assert_eq!(sign_hull(&cr, [0.0, 1.0]), Some([0.0, 1.0]));
    // One direction: the published interval.
    let cr = [(false, 0.2, 0.3), (false, 0.5, 0.6), (false, 0.25, 0.4)];
    assert_eq!(sign_hull(&cr, [0.0, 1.0]), Some([0.2, 0.6]));
    assert_eq!(sign_hull(&cr, [0.7, 1.0]), None);
    // Mixed, but all crossings before the shutter with every delta of one sign after.
    let cr = [(false, -3.0, -2.0), (true, -5.0, -4.0), (true, -1.0, -0.5)];
    // For t > -0.5: decreasing delta < 0, increasing deltas > 0: both signs present.
    assert_eq!(sign_hull(&cr, [0.0, 1.0]), Some([0.0, 1.0]));
    let cr = [(true, -3.0, -2.0), (true, -5.0, -4.0), (false, 2.0, 3.0)];
    // For t in [0, 1]: increasing deltas > 0, the decreasing one > 0 (before its
    // crossing): all positive, no coverage.
    assert_eq!(sign_hull(&cr, [0.0, 1.0]), None);
}

/// The f32 interval operations enclose the exact results (checked in f64, exact for
/// sums, differences and products of these f32 values; quotients to 2^-53).
#[test]
fn intervals_enclose_exact_results() {
    let o = IvOps::<Plain, Outward>::new(&Plain);
    let mut rng = ChaCha8Rng::seed_from_u64(0x1f32);
    for n in 0..200_000 {
        let scale = [1e-30f32, 1e-6, 1.0, 1e6, 1e15][n % 5];
        let mut r = || {
            let lo = rng.gen_range(-1.0f32..1.0) * scale;
            let hi = lo + rng.gen_range(0.0f32..1.0) * scale * [0.0f32, 1e-7, 1.0][n % 3];
            [lo, hi]
        };
        let (a, b) = (r(), r());
        let pick = |i: Iv<f32>, f: f64| i[0] as f64 + f * (i[1] as f64 - i[0] as f64);
        let (fa, fb) = (rng.gen_range(0.0..=1.0), rng.gen_range(0.0..=1.0));
        let (x, y) = (pick(a, fa), pick(b, fb));
        let inside = |i: Iv<f32>, z: f64, what: &str| {
            assert!(!o.ok(&i) || (i[0] as f64 <= z && z <= i[1] as f64), "{what}: {z:e} not in {i:?} ({a:?}, {b:?})");
        };
        // x, y are not f32 values in general, but lie in the intervals: the
        // enclosure must hold for them too (f64 rounding far below the f32 steps).
        inside(o.add(&a, &b), x + y, "add");
        inside(o.sub(&a, &b), x - y, "sub");
        inside(o.mul(&a, &b), x * y, "mul");
        inside(o.div(&a, &b), x / y, "div");
    }
    // Underflow: a product that rounds to 0 is enclosed by the subnormal neighbours.
    let t = o.mul(&o.pt(&1e-30), &o.pt(&1e-30));
    assert!(t[0] < 0.0 && t[1] > 0.0);
    assert!(!o.ok(&o.add(&o.pt(&f32::MAX), &o.pt(&f32::MAX))));
    assert!(!o.ok(&o.div(&o.pt(&1.0), &[-1.0, 1.0])));
    let bad = [f32::NAN; 2];
    assert!(!o.ok(&bad) && !o.pos(&bad) && !o.neg(&bad));
}

/// The padded lines: for random endpoints and f32 samples at or above (below) the
/// exact line through them, `eval` is never negative.
#[test]
fn safe_lines_never_cut_below_the_exact_line() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x11e5);
    for n in 0..200_000 {
        let scale = [1e-30f32, 1e-3, 1.0, 30.0, 1e6][n % 5];
        let (el, er) = (rng.gen_range(-1.0f32..1.0) * scale, rng.gen_range(-1.0f32..1.0) * scale);
        let upper = n % 2 == 0;
        let c = safe_line(Lens::U, upper, el, er).unwrap();
        let l: f32 = if n % 7 == 0 { [-1.0, 1.0, 0.0][n % 3] } else { rng.gen_range(-1.0..=1.0) };
        let exact = 0.5 * (el as f64 + er as f64) + 0.5 * (er as f64 - el as f64) * l as f64;
        // The f32 time nearest the exact line on the kept side.
        let mut t = exact as f32;
        if upper && (t as f64) > exact {
            t = t.next_down();
        }
        if !upper && (t as f64) < exact {
            t = t.next_up();
        }
        let g = c.eval(&Sample::new(0.0, 0.0, l, 0.0, t));
        assert!(g >= 0.0, "{c:?} l {l} t {t} exact {exact}: g {g}");
    }
}

/// Huge, tiny, far-from-origin, w near 0 and focal-plane input: no covered sample
/// culled (uniform and near-miss samples), answers in the domain.
#[test]
fn safe_on_extreme_input() {
    use super::super::testkit::assert_keeps_covered;
    let c = cam();
    let mut n = 0;
    let base = translated(&c, [[-1.0, -1.0, 8.0], [1.0, -1.2, 9.0], [0.2, 1.0, 7.0]], [0.8, 0.3, 1.5]);
    // Far from the origin: every clip x, y shifted by 1e6 px times w.
    let mut far = base;
    for p in far.q.iter_mut().chain(far.r.iter_mut()) {
        p[0] += 1.0e6 * p[3];
        p[1] -= 1.0e6 * p[3];
    }
    // Tiny: everything scaled by 1e-30 (w too: same image, subnormal-adjacent sums).
    let mut tiny = base;
    for p in tiny.q.iter_mut().chain(tiny.r.iter_mut()) {
        p.iter_mut().for_each(|x| *x *= 1e-30);
    }
    tiny.c0.iter_mut().chain(tiny.c1.iter_mut()).for_each(|x| *x *= 1e-30);
    // Huge: the same scaled by 1e30.
    let mut huge = base;
    for p in huge.q.iter_mut().chain(huge.r.iter_mut()) {
        p.iter_mut().for_each(|x| *x *= 1e30);
    }
    huge.c0.iter_mut().chain(huge.c1.iter_mut()).for_each(|x| *x *= 1e30);
    // w near 0 and behind the lens: one vertex from w = 1e-6 to -0.5.
    let mut near0 = base;
    near0.q[0][3] = 1e-6;
    near0.r[0][3] = -0.5;
    // Straddling the focal plane (F = 4), moving through it.
    let straddle = translated(&c, [[-1.0, -1.0, 2.5], [1.0, -1.0, 6.0], [0.0, 1.2, 3.9]], [0.3, -0.2, 0.5]);
    let mut rng = ChaCha8Rng::seed_from_u64(0xe77);
    for (what, tri, centre) in [
        ("far", far, [1.0e6 + 40.0, -1.0e6 + 36.0]),
        ("tiny", tiny, [40.0, 36.0]),
        ("huge", huge, [40.0, 36.0]),
        ("w near 0", near0, [40.0, 36.0]),
        ("straddle", straddle, [32.0, 32.0]),
    ] {
        let p = METHOD_SAFE.setup(&tri);
        for _ in 0..12 {
            let size = [0.5f32, 1.0, 2.0, 4.0][rng.gen_range(0..4)];
            let tile =
                Tile::square(centre[0] + rng.gen_range(-20.0..20.0), centre[1] + rng.gen_range(-20.0..20.0), size);
            n += assert_keeps_covered(p.as_ref(), &tri, &tile, (400, 40), rng.gen(), what).0;
            super::super::testkit::assert_answered_in_domain(p.as_ref(), &[tile]);
        }
    }
    assert!(n > 2000, "{n}");
    // Non-finite input gives the full domain (never a cull).
    let mut bad = base;
    bad.q[1][0] = f32::NAN;
    let b = safe_bounds(&bad, &Tile::square(1e6, 1e6, 2.0)).expect("NaN input culled a tile");
    assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
    assert!(b.constraints.is_empty());
    let mut inf = base;
    inf.c1[2] = f32::INFINITY;
    inf.r[0][3] = f32::INFINITY;
    let b = safe_bounds(&inf, &Tile::square(1e6, 1e6, 2.0)).expect("inf input culled a tile");
    assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
    super::super::testkit::assert_degenerate_input_is_answered(METHOD_SAFE, &super::super::la2011::figure1::triangle());
}

/// Not vacuous: far tiles are still culled, and on ordinary cases the bounds are
/// narrower than the domain and the lines cull samples; on triangles meeting the
/// thesis's assumptions the safe variant admits about what the original admits.
#[test]
fn safe_is_not_vacuous() {
    let c = cam();
    let tri = translated(&c, [[-1.0, -1.0, 8.0], [1.0, -1.0, 8.0], [0.0, 1.0, 8.5]], [2.0, 0.0, 0.0]);
    let tri = Triangle { c0: [0.0; 3], c1: [0.0; 3], ..tri };
    assert!(safe_bounds(&tri, &Tile::square(200.0, 30.0, 8.0)).is_none());
    assert!(safe_bounds(&tri, &Tile::square(-100.0, 30.0, 8.0)).is_none());
    let g = [[-1.0, -1.0, 8.0], [1.0, -1.0, 8.0], [0.0, 1.0, 9.0]];
    let tri = c.triangle(g, g);
    assert!(safe_bounds(&tri, &Tile::square(200.0, 30.0, 8.0)).is_none());
    assert!(safe_bounds(&tri, &Tile::square(30.0, -200.0, 8.0)).is_none());
    let b = safe_bounds(&tri, &Tile::square(45.0, 16.0, 1.0)).expect("edge tile culled");
    assert!(b.u[0] > -1.0, "{b:?}");
    let tri = translated(&c, [[-1.0, -1.0, 8.0], [1.0, -1.2, 9.0], [0.2, 1.0, 7.0]], [0.8, 0.3, 1.5]);
    let tile = Tile::square(24.0, 24.0, 2.0);
    let (b, o) = (safe_bounds(&tri, &tile).unwrap(), bounds(&tri, &tile).unwrap());
    assert!(!b.constraints.is_empty() && b.t != [0.0, 1.0], "{b:?}");
    // Within a few ulps of the published answer here.
    for (s, p) in [(b.u, o.u), (b.v, o.v), (b.t, o.t)] {
        assert!(s[0] <= p[0] && s[1] >= p[1] && s[0] >= p[0] - 1e-4 && s[1] <= p[1] + 1e-4, "{b:?} vs {o:?}");
    }
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let (mut adm_safe, mut adm_orig, mut covered, mut total) = (0, 0, 0, 0);
    for _ in 0..150 {
        let tri = one_side_translated(&mut rng, 0.0);
        for _ in 0..4 {
            let size = [1.0f32, 2.0, 4.0, 0.7][rng.gen_range(0..4)];
            let tile = tile_on(&tri, &mut rng, size);
            let seed = rng.gen();
            let (cv, ad) = spot_check_of(METHOD_SAFE, &tri, &tile, 200, seed);
            let (_, ao) = spot_check(&tri, &tile, 200, seed);
            covered += cv;
            adm_safe += ad;
            adm_orig += ao;
            total += 200;
        }
    }
    eprintln!("wu2013-safe random: {covered} covered, admitted {adm_safe} (wu2013: {adm_orig}) of {total}");
    assert!(adm_safe < total && adm_safe as f64 <= 1.02 * adm_orig as f64, "{adm_safe} {adm_orig}");
}

/// The per-sample constraints' `eval_box` encloses `eval` on the safe variant's lines.
#[test]
fn safe_eval_box_encloses_eval() {
    let c = cam();
    let tri = translated(&c, [[-1.0, -1.0, 8.0], [1.0, -1.2, 9.0], [0.2, 1.0, 7.0]], [0.8, 0.3, 1.5]);
    let mut k = 0;
    for tile in [Tile::square(18.0, 18.0, 2.0), Tile::square(24.0, 12.0, 2.0), Tile::square(24.0, 24.0, 2.0)] {
        if let Some(b) = safe_bounds(&tri, &tile) {
            k += b.constraints.len();
            super::super::testkit::assert_eval_box_encloses(&b, &tile, 9);
        }
    }
    assert!(k > 0);
}

/// The answer bit for bit: interval ends' bits and the constraints' debug form
/// (each f32 printed so that it reads back to the same bits); None for Empty.
fn answer_bits(r: &TileResult) -> Option<(Vec<u32>, String)> {
    match r {
        TileResult::Empty => None,
        TileResult::Bounds(b) => {
            let mut v: Vec<u32> = b.u.iter().chain(&b.v).chain(&b.t).map(|x| x.to_bits()).collect();
            v.extend(b.z.iter().flatten().map(|x| x.to_bits()));
            Some((v, format!("{:?}", b.constraints)))
        }
    }
}

/// `wu2013-safe` answers bit for bit as its code did before it was restructured (the
/// fingerprint of every answer, recorded while the old code still ran beside it) on
/// physical cases of every regime (a tile on the footprint's boundary and one
/// beside it), wild triangles near and far from the origin, and the same with NaN,
/// an infinity, a signed zero, f32::MAX or a subnormal planted in the triangle or the
/// tile, or a w set to +-0.
#[test]
fn safe_is_its_old_code_bit_for_bit() {
    let (mut tiles, mut culled, mut lines, mut narrowed) = (0usize, 0usize, 0usize, 0usize);
    let mut fp = super::super::testkit::Fingerprint::new();
    for n in 0..30_000usize {
        let (tri, ts) = crate::cases::generate::bit_compare_case(0x05af_e01d, n);
        let p = METHOD_SAFE.setup(&tri);
        for tile in &ts {
            let new = answer_bits(&p.tile(tile));
            fp.add(&format!("{new:?}"));
            tiles += 1;
            match &new {
                None => culled += 1,
                Some((v, c)) => {
                    lines += (c != "[]") as usize;
                    narrowed += (v[..6] != [-1.0f32, 1.0, -1.0, 1.0, 0.0, 1.0].map(f32::to_bits)) as usize;
                }
            }
        }
    }
    assert_eq!(
        fp.value(),
        0xbd6e_7637_995e_3cab,
        "the answers on the stress stream are no longer those of the code before it was restructured \
         (recorded 2026-12-06 while both ran side by side and agreed)"
    );
    // Every kind of answer was compared: culled, narrowed, with lines.
    assert!(
        culled > 1000 && narrowed > 1000 && lines > 500,
        "{tiles} tiles: {culled} culled, {narrowed} narrowed, {lines} with lines"
    );
}
