//! The methods whose tile path is written over `F32Arith` (`cullproof::tools::symbolic`) answer
//! bit for bit as the code they replaced (kept in `tests/encoded/`), on physical cases
//! of every regime, wild random triangles and planted NaN, infinities, signed zeros and
//! w <= 0: the encoded code is the method, not a copy beside it.

#[path = "encoded/cases.rs"]
mod cases;
#[path = "encoded/gdam2010_safe_old.rs"]
mod gdam2010_safe_old;
#[path = "encoded/hyperplane_old.rs"]
mod hyperplane_old;
#[path = "encoded/la2011_old.rs"]
mod la2011_old;
#[path = "encoded/lb2011_safe_old.rs"]
mod lb2011_safe_old;
#[path = "encoded/mam2012_old.rs"]
mod mam2012_old;
#[path = "encoded/mam2012_safe_old.rs"]
mod mam2012_safe_old;
#[path = "encoded/nilsson2012_depth_old.rs"]
mod nilsson2012_depth_old;
#[path = "encoded/wu2013_safe_old.rs"]
mod wu2013_safe_old;

use cullproof::bounds::by_id;
use cullproof::{Tile, Triangle};

/// Compare a method with its old code on `n` cases; returns (tiles, culled).
fn compare(id: &str, n: usize, old: impl Fn(&Triangle, &Tile) -> cullproof::bounds::TileResult) -> (usize, usize) {
    compare_bits(id, n, |tri, tile| cases::bits(&old(tri, tile)))
}

/// [`compare`] with the old answer given as [`cases::bits`].
fn compare_bits(id: &str, n: usize, old: impl Fn(&Triangle, &Tile) -> Option<(Vec<u32>, String)>) -> (usize, usize) {
    let m = by_id(id).unwrap();
    let (mut tiles, mut culled) = (0, 0);
    for k in 0..n {
        let (tri, ts) = cases::case(0xe2c0de, k);
        let p = m.setup(&tri);
        for tile in &ts {
            let (new, old) = (cases::bits(&p.tile(tile)), old(&tri, tile));
            assert_eq!(new, old, "{id} case {k}: {tri:?} {tile:?}");
            tiles += 1;
            culled += new.is_none() as usize;
        }
    }
    (tiles, culled)
}

const N: usize = 60_000;

#[test]
fn la2011_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("la2011", N, |tri, tile| la2011_old::answer(false, tri, tile));
    assert_eq!(tiles, 2 * N);
    assert!(culled > N / 20, "only {culled} of {tiles} tiles culled: the reject went untested");
}

#[test]
fn la2011_safe_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("la2011-safe", N, |tri, tile| la2011_old::answer(true, tri, tile));
    assert_eq!(tiles, 2 * N);
    assert!(culled > N / 20, "only {culled} of {tiles} tiles culled: the reject went untested");
}

#[test]
fn lb2011_safe_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("lb2011-safe", N, lb2011_safe_old::answer);
    assert_eq!(tiles, 2 * N);
    assert!(culled > N / 20, "only {culled} of {tiles} tiles culled: the reject went untested");
}

#[test]
fn mam2012_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("mam2012", N, mam2012_old::answer);
    assert_eq!(tiles, 2 * N);
    assert!(culled > N / 20, "only {culled} of {tiles} tiles culled: the reject went untested");
}

#[test]
fn mam2012_safe_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("mam2012-safe", N, mam2012_safe_old::answer);
    assert_eq!(tiles, 2 * N);
    assert!(culled > N / 20, "only {culled} of {tiles} tiles culled: the reject went untested");
}

#[test]
fn wu2013_safe_is_its_old_code_bit_for_bit() {
    let (tiles, culled) = compare("wu2013-safe", N, wu2013_safe_old::answer);
    assert!(tiles > 100_000 && culled > 1_000, "{tiles} tiles, {culled} culled");
}

#[test]
fn mam2012_hyperplane_tile_path_is_its_old_code_bit_for_bit() {
    for (id, ps) in [("mam2012-hyperplane", false), ("mam2012-hyperplane-ps", true)] {
        let (tiles, culled) = compare_bits(id, N, |tri, tile| hyperplane_old::answer(ps, tri, tile));
        assert_eq!(tiles, 2 * N);
        assert!(culled > N / 20, "{id}: only {culled} of {tiles} tiles culled: the reject went untested");
    }
}

#[test]
fn nilsson2012_depth_is_its_old_code_bit_for_bit() {
    for (id, safe) in [("nilsson2012-depth", false), ("nilsson2012-depth-safe", true)] {
        let (tiles, culled) = compare(id, N, |tri, tile| nilsson2012_depth_old::answer(safe, tri, tile));
        assert_eq!(tiles, 2 * N);
        assert!(culled > N / 50, "{id}: only {culled} of {tiles} tiles culled: the reject went untested");
    }
}

/// `gdam2010-safe`'s time set against its old code (f32 intervals as a type with early
/// returns), span for span, at pixel positions in and around each case's tiles (every
/// case with its CoC zeroed: the method is motion-only).
#[test]
fn gdam2010_safe_is_its_old_code_bit_for_bit() {
    use cullproof::bounds::gdam2010::SafeTimeSpans;
    let (mut samples, mut culled, mut cut) = (0usize, 0usize, 0usize);
    for k in 0..20_000 {
        let (mut tri, ts) = cases::case(0x9da3, k);
        (tri.c0, tri.c1) = ([0.0; 3], [0.0; 3]);
        if !tri.q.iter().chain(tri.r.iter()).flatten().all(|v| v.is_finite()) {
            continue;
        }
        let (new, old) = (SafeTimeSpans::new(&tri), gdam2010_safe_old::SafeTimeSpans::new(&tri));
        for tile in &ts {
            let (x0, y0, x1, y1) = (tile.x0, tile.y0, tile.x1, tile.y1);
            for (fx, fy) in [(0.0, 0.0), (0.5, 0.5), (1.0, 0.25), (0.25, 1.0), (0.75, 0.0)] {
                let (x, y) = (x0 + fx * (x1 - x0), y0 + fy * (y1 - y0));
                let (a, b) = (new.spans_at(x, y), old.spans_at(x, y));
                let bits = |s: &[[f32; 2]]| s.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(a.as_slice()), bits(b.as_slice()), "case {k}: {tri:?} at ({x}, {y})");
                samples += 1;
                let kept: f32 = a.as_slice().iter().map(|s| s[1] - s[0]).sum();
                culled += (a.n == 0) as usize;
                cut += (a.n > 0 && kept < 1.0) as usize;
            }
        }
    }
    assert!(samples > 100_000 && culled > 1_000 && cut > 1_000, "{samples} positions, {culled} culled, {cut} cut");
}
