//! `mam2012-new`: the practical rasterizer of Munkberg and Akenine-Möller 2012 (NEW in
//! their Tables 1-3).
//!
//! Source: J. Munkberg and T. Akenine-Möller, "Hyperplane Culling for Stochastic
//! Rasterization", Eurographics 2012 short paper, §3: "we use three culling tests, namely
//! Laine et al.'s motion blur test in dual space \[LAKL11\], the bilinear test from Section
//! 2.1, and the hyperplane test (Section 2.2)". Text: Munkberg and Akenine-Möller 2012,
//! "Hyperplane Culling for Stochastic Rasterization", §3.
//!
//! # What it computes
//! The conjunction of three tests of the same triangle and tile, each set up on its own:
//! - `la2011` ([`super::la2011::METHOD`]): LA's per-tile time bounds (and its lens
//!   bounds, whatever that file implements; it is a reconstruction, see its own doc);
//! - `mam2012` ([`super::mam2012::METHOD`]): the ut / vt lines (per-tile u^, v^, reject,
//!   and four per-sample line constraints);
//! - `mam2012-hyperplane` ([`super::mam2012_hyperplane::METHOD`]): the per-tile
//!   hyperplane reject and refined u, v, t bounds, WITHOUT the per-sample hyperplane
//!   constraints (the paper: "We do not cull against the hyperplanes per sample"; its
//!   Table 1 gives those numbers only in parentheses).
//!
//! The tile result is `la.and(bilinear).and(hyperplane)` ([`TileResult::and`]): intervals
//! intersected, constraints kept, Empty if any test says Empty or an interval empties.
//! A conjunction of conservative tests is conservative; each component's assumptions
//! and f32 caveats are documented in its own file.
//!
//! # `mam2012-new-safe`
//! The same conjunction of `la2011-safe`, `mam2012-safe` and `mam2012-hyperplane-safe`,
//! each made conservative in f32 in its own file (f32 interval arithmetic with directed
//! steps; see their error analyses). A conjunction of conservative tests is
//! conservative, so nothing else needs an analysis; its price is the sum of the parts'.
//!
//! # Choices and deviations
//! - Composition through the registry statics only: this file does not depend on the
//!   internals of the other three files.
//! - Each test sees the full hypercube. In the paper's rasterizer the hyperplane test
//!   could start from the box already narrowed by the other tests (its refined bounds
//!   and trivial reject pick the hypercube corner); the conjunction here is the same or
//!   looser, never tighter, so conservativeness is unaffected.
//! - No selective enabling of the hyperplanes (the paper enables them per triangle by an
//!   AABB-area rule with no published threshold; see `mam2012_hyperplane`): the
//!   registered hyperplane method is always enabled. This changes cost, and STE only in
//!   the direction of culling more.
//! - The triangle's screen AABB that NEW traverses ("computed using a previous technique
//!   \[LK11\]") is not part of this test: the harness decides which tiles are asked.
//! - `disabled()` reports a reason only when all three components are disabled.

use super::*;

/// LA + bilinear + hyperplane (§3 of Munkberg & Akenine-Möller 2012), from three
/// registered methods (the published ones, or their -safe variants).
struct Mam2012New {
    info: &'static MethodInfo,
    parts: &'static [&'static &'static dyn Method; 3],
}

impl Mam2012New {
    /// The full domain, then each part in order ([`Conjunction::combine`]).
    fn conj(&self) -> Conjunction {
        Conjunction { parts: self.parts, from_full: true }
    }
}

static INFO: MethodInfo = MethodInfo {
    id: "mam2012-new",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §3 (NEW = LA motion test [LAKL11] + bilinear test §2.1 + hyperplane test §2.2)",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
};

pub static METHOD: &dyn Method = &Mam2012New {
    info: &INFO,
    parts: &[&super::la2011::METHOD, &super::mam2012::METHOD, &super::mam2012_hyperplane::METHOD],
};

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "mam2012-new-safe",
    source: "mam2012-new made conservative in f32: the conjunction of la2011-safe, mam2012-safe \
             and mam2012-hyperplane-safe",
    ..INFO
};

/// `mam2012-new-safe`: the same conjunction of the three -safe parts. A conjunction of
/// conservative tests is conservative, so nothing beyond the parts is needed.
pub static METHOD_SAFE: &dyn Method = &Mam2012New {
    info: &INFO_SAFE,
    parts: &[&super::la2011::METHOD_SAFE, &super::mam2012::METHOD_SAFE, &super::mam2012_hyperplane::METHOD_SAFE],
};

struct Prep {
    conj: Conjunction,
    parts: [Box<dyn Prepared>; 3],
}

impl Method for Mam2012New {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep { conj: self.conj(), parts: self.parts.map(|m| m.setup(tri)) })
    }
    fn conjunction(&self) -> Option<Conjunction> {
        Some(self.conj())
    }
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        self.conj.combine(|i| self.parts[i].tile(tile))
    }
    fn disabled(&self) -> Option<&'static str> {
        self.parts
            .iter()
            .all(|p| p.disabled().is_some())
            .then_some("all three component tests (la2011, mam2012, mam2012-hyperplane) are disabled")
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{covered, random_sample};
    use super::*;
    use crate::model::ThinLens;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn cam() -> ThinLens {
        ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 4.0, near: 0.1, far: 100.0 }
    }

    #[test]
    fn static_triangle_keeps_time_and_far_tile_is_culled() {
        let tri = Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0]]);
        let p = METHOD.setup(&tri);
        let TileResult::Bounds(b) = p.tile(&Tile::square(-1.0, -1.0, 2.0)) else { panic!("empty") };
        assert_eq!(b.t, [0.0, 1.0]);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..1000 {
            assert!(b.admits(&random_sample(&mut rng, &Tile::square(-1.0, -1.0, 2.0))));
        }
        assert!(matches!(p.tile(&Tile::square(100.0, 0.0, 2.0)), TileResult::Empty));
    }

    /// NEW admits no more than each of its two mam2012 parts.
    #[test]
    fn at_least_as_tight_as_its_parts() {
        let c = cam();
        let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
        let tri = c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]]));
        let tile = Tile::square(-0.5, -0.5, 1.0);
        let TileResult::Bounds(n) = METHOD.setup(&tri).tile(&tile) else { panic!("empty") };
        let parts = [super::super::mam2012::METHOD, super::super::mam2012_hyperplane::METHOD];
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        for _ in 0..20_000 {
            let s = random_sample(&mut rng, &tile);
            if n.admits(&s) {
                for m in parts {
                    let TileResult::Bounds(b) = m.setup(&tri).tile(&tile) else { panic!("part empty but NEW not") };
                    assert!(b.admits(&s), "{} culls {s:?} but NEW admits it", m.info().id);
                }
            }
        }
    }

    /// Random physical triangles (any depth, some crossing the focal plane or flipping
    /// facing, so that the parts are enabled in every combination) and tiles near them.
    #[test]
    fn conservative_on_random_triangles() {
        let mut rng = ChaCha8Rng::seed_from_u64(97);
        let c = cam();
        let (mut cov_total, mut culled) = (0, 0);
        for it in 0..200u64 {
            let z0: f32 = rng.gen_range(0.5..30.0);
            let z1: f32 = if it % 3 == 0 { z0 } else { rng.gen_range(0.5..30.0) };
            let mut v = || -> [f32; 3] {
                [rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.1..0.1f32)]
            };
            let (a, b, d) = (v(), v(), v());
            let mv = v();
            let q = [a, b, d].map(|p| [p[0] * z0, p[1] * z0, z0 * (1.0 + p[2])]);
            let r = [a, b, d].map(|p| [(p[0] + mv[0]) * z1, (p[1] + mv[1]) * z1, z1 * (1.0 + p[2])]);
            let tri = c.triangle(q, r);
            let p = METHOD.setup(&tri);
            for _ in 0..3 {
                let tile = Tile::square(rng.gen_range(-40.0..40.0), rng.gen_range(-40.0..40.0), 2.0);
                let res = p.tile(&tile);
                culled += matches!(res, TileResult::Empty) as usize;
                for _ in 0..2000 {
                    let s = random_sample(&mut rng, &tile);
                    if covered(&tri, &s) {
                        cov_total += 1;
                        let ok = match &res {
                            TileResult::Empty => false,
                            TileResult::Bounds(b) => b.admits(&s),
                        };
                        assert!(ok, "triangle {it} {tri:?} tile {tile:?}: covered {s:?} culled");
                    }
                }
            }
        }
        assert!(cov_total > 5000 && culled > 50, "{cov_total} {culled}");
    }

    #[test]
    fn conservative_on_random_samples() {
        let c = cam();
        let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
        let mut t = Triangle::fixed([[-10.0, -5.0, 0.0, 2.0], [12.0, -4.0, 0.0, 2.5], [0.0, 14.0, 0.0, 3.0]]);
        t.r = [[-4.0, -2.0, 0.0, 1.0], [14.0, 0.0, 0.0, 3.0], [6.0, 12.0, 0.0, 2.0]];
        t.c0 = [3.0, 1.0, 5.0];
        t.c1 = [0.5, 6.0, 2.0];
        t.k = 0.75;
        let cases = [
            (
                c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]])),
                vec![Tile::square(-0.5, -0.5, 1.0), Tile::square(-3.0, -2.0, 4.0)],
            ),
            (
                c.triangle(
                    [[-1.0, -1.0, 20.0], [2.0, -1.0, 20.0], [0.0, 2.0, 20.0]],
                    [[-1.0, -1.0, 4.5], [2.0, -1.0, 4.5], [0.0, 2.0, 4.5]],
                ),
                vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-24.0, -24.0, 4.0), Tile::square(40.0, -20.0, 4.0)],
            ),
            (
                c.triangle(
                    [[-1.0, -1.0, 3.0], [1.0, -0.8, 5.0], [0.0, 1.0, 3.2]],
                    [[-0.6, -0.7, 2.5], [0.9, -0.5, 6.0], [0.3, 0.8, 4.5]],
                ),
                vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-30.0, -30.0, 8.0), Tile::square(20.0, 10.0, 4.0)],
            ),
            (t, vec![Tile::square(0.0, 0.0, 1.0), Tile::square(-12.0, -6.0, 4.0), Tile::square(4.0, 6.0, 2.0)]),
        ];
        for (ci, (tri, tiles)) in cases.iter().enumerate() {
            let p = METHOD.setup(tri);
            let mut total = 0;
            for (ti, tile) in tiles.iter().enumerate() {
                let res = p.tile(tile);
                let mut rng = ChaCha8Rng::seed_from_u64(3000 + 10 * ci as u64 + ti as u64);
                for _ in 0..50_000 {
                    let s = random_sample(&mut rng, tile);
                    if covered(tri, &s) {
                        total += 1;
                        let ok = match &res {
                            TileResult::Empty => false,
                            TileResult::Bounds(b) => b.admits(&s),
                        };
                        assert!(ok, "case {ci} tile {ti}: covered {s:?} culled");
                    }
                }
            }
            assert!(total > 100, "case {ci}: only {total} covered samples");
        }
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    }
}
