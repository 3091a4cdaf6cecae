//! Every input in a claim's ranges can be judged: the -safe variants on cases scaled to
//! the ends of the f32 range. The first cases of the default gate, with the clip x, y and
//! the CoCs multiplied by `s` and z, w by `s_w` (the tile by `s / s_w`), keep their
//! geometry; only the magnitudes change. Every -safe variant must be proven on every
//! one whose scaled numbers stay finite: near 1e-36 with w near 1e-38 (where an
//! absolute rounding term too large once left lb2011-safe and lc-safe unproven on a
//! third of the cases), with w subnormal, and with coordinates near 1e37.

use cullproof::gate::engine::judge;
use cullproof::gate::CheckConfig;
use cullproof::judge::Verdict;
use cullproof::model::{Case, Tile};

const SAFE: [&str; 11] = [
    "bbox-safe",
    "la2011-safe",
    "lb2011-safe",
    "lc-safe",
    "mam2012-safe",
    "mam2012-hyperplane-safe",
    "mam2012-hyperplane-ps-safe",
    "mam2012-new-safe",
    "wu2013-safe",
    "nilsson2012-depth-safe",
    "gdam2010-safe",
];

/// Judges the first `n` cases scaled by `(s, s_w)`; returns the judgements made and the
/// cases whose scaled numbers were not all finite (not judged).
fn judge_scaled(n: u64, s: f32, sw: f32) -> (usize, usize) {
    let ms: Vec<_> = SAFE.iter().map(|id| cullproof::bounds::by_id(id).unwrap()).collect();
    let cfg = CheckConfig::default_with(ms);
    let (mut judged, mut skipped) = (0, 0);
    for i in 0..n {
        let (_, case, tile) = cullproof::cases::make_case(&cfg.draw(), i);
        let mut t = case.triangle;
        for v in t.q.iter_mut().chain(t.r.iter_mut()) {
            v[0] *= s;
            v[1] *= s;
            v[2] *= sw;
            v[3] *= sw;
        }
        for c in t.c0.iter_mut().chain(t.c1.iter_mut()) {
            *c *= s;
        }
        let f = s / sw;
        let tile = Tile { x0: tile.x0 * f, x1: tile.x1 * f, y0: tile.y0 * f, y1: tile.y1 * f };
        let finite =
            t.q.iter().chain(t.r.iter()).flatten().chain(t.c0.iter()).chain(t.c1.iter()).all(|x| x.is_finite())
                && [tile.x0, tile.x1, tile.y0, tile.y1].iter().all(|x| x.is_finite());
        if !finite {
            skipped += 1;
            continue;
        }
        let (js, _) = judge(&cfg, &cfg.methods, &Case { triangle: t, lens: None }, &tile, i);
        for (id, j) in SAFE.iter().zip(&js) {
            assert_eq!(
                j.verdict(),
                Verdict::Proven,
                "{id}, case {i} scaled by ({s:e}, {sw:e}): {:?} {:?}",
                j.unproven(),
                j.violation
            );
            judged += 1;
        }
    }
    (judged, skipped)
}

#[test]
fn the_safe_variants_are_proven_near_the_bottom_of_the_f32_range() {
    assert_eq!(judge_scaled(64, 1e-38, 1e-38), (64 * 11, 0));
    assert_eq!(judge_scaled(32, 1e-44, 1e-44), (32 * 11, 0));
}

#[test]
fn the_safe_variants_are_proven_near_the_top_of_the_f32_range() {
    let (judged, skipped) = judge_scaled(64, 1e33, 1.0);
    assert!(judged >= 50 * 11 && skipped > 0, "{judged} {skipped}");
}
