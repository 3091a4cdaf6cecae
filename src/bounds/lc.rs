//! `lc` (**reconstruction**): LA's per-tile intervals followed by LB's per-sample
//! patches, the "(unpublished) combination of the two" that Munkberg &
//! Akenine-Möller 2012 evaluate as LC (§3; Table 1 STE, Table 2 time, Table 3 cost:
//! 700 per triangle, 56 per tile = LA's 40 + LB's 16, 12 per sample = LB's).
//!
//! # What it computes
//! Both tests are set up for the triangle (`la2011` and `lb2011`, both reconstructions;
//! see their files for the formulas, derivations, f32 notes and choices), and per tile
//! both answers are combined with [`TileResult::and`]: Empty if either is Empty;
//! otherwise the intersection of their u^, v^, t^ (Empty if it is empty) with LB's four
//! bilinear patches as per-sample constraints. Both parts are conservative in real
//! arithmetic for every triangle of the model (including w <= 0: both use the
//! clipless two-column form), so their intersection is too; f32 rounding can cost what
//! either part's rounding costs, nothing more. Nothing is disabled: LA falls back to the
//! full lens for a vertex whose CoC changes sign, and LB needs no division.
//!
//! # `lc-safe`
//! The same conjunction of `la2011-safe` and `lb2011-safe` (each made conservative in
//! f32 in its own file: f32 interval arithmetic with directed steps, and for lb2011's
//! patches a padded constant term). Each part alone culls only samples no triangle
//! covers, so their conjunction does too; nothing else needs an analysis. Its price is
//! the sum of the two parts' prices.
//!
//! # Choices
//! munkberg2012 does not say how LC orders the two tests; as the constraints are
//! independent, the order has no effect on which samples pass.

use super::*;

/// Both parts' setups; the tile answer is [`Conjunction::combine`] over them (LA first:
/// Empty there is the answer; otherwise LA's answer [`TileResult::and`] LB's).
struct Prep {
    conj: Conjunction,
    parts: [Box<dyn Prepared>; 2],
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        self.conj.combine(|i| self.parts[i].tile(tile))
    }
    fn disabled(&self) -> Option<&'static str> {
        match (self.parts[0].disabled(), self.parts[1].disabled()) {
            (Some(a), Some(_)) => Some(a),
            _ => None,
        }
    }
}

/// lc, or lc-safe: the same conjunction of two other registered methods (LA, then LB).
pub(crate) struct Lc {
    pub(crate) info: &'static MethodInfo,
    pub(crate) parts: &'static [&'static &'static dyn Method; 2],
}

impl Lc {
    fn conj(&self) -> Conjunction {
        Conjunction { parts: self.parts, from_full: false }
    }
}

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "lc",
    source: "reconstruction of LC, the combination of LA (Laine et al. 2011) and LB (Laine & \
             Karras 2011, NVR-2011-004) evaluated in Munkberg & Akenine-Möller 2012 §3, \
             Tables 1-3: la2011 tile intervals intersected with lb2011's, plus lb2011's \
             four per-sample bilinear patches",
    reconstruction: true,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
};

impl Method for Lc {
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

pub static METHOD: &dyn Method = &Lc { info: &INFO, parts: &[&super::la2011::METHOD, &super::lb2011::METHOD] };

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "lc-safe",
    source: "lc made conservative in f32: the conjunction of la2011-safe and lb2011-safe",
    ..INFO
};

/// `lc-safe`: the conjunction of `la2011-safe` and `lb2011-safe`. A conjunction of
/// conservative tests is conservative, so nothing beyond the two parts is needed.
pub static METHOD_SAFE: &dyn Method =
    &Lc { info: &INFO_SAFE, parts: &[&super::la2011::METHOD_SAFE, &super::lb2011::METHOD_SAFE] };

#[cfg(test)]
mod tests {
    use super::super::la2011::{cases, figure1};
    use super::super::testkit::{bounds_of, random_sample};
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn static_triangle_keeps_whole_time_range() {
        let tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0], [100.0, 0.0, 0.5, 1.0], [0.0, 100.0, 0.5, 1.0]]);
        let b = bounds_of(METHOD, &tri, &Tile::square(10.0, 10.0, 4.0)).expect("inside tile culled");
        assert_eq!(b.t, [0.0, 1.0]);
        assert!(METHOD.setup(&tri).disabled().is_none());
    }

    #[test]
    fn far_tiles_are_culled() {
        let tri = figure1::triangle();
        for tile in figure1::far_tiles() {
            assert!(bounds_of(METHOD, &tri, &tile).is_none(), "{tile:?}");
            assert!(bounds_of(METHOD_SAFE, &tri, &tile).is_none(), "lc-safe: {tile:?}");
        }
    }

    /// LC admits a sample iff both LA and LB do, and never rejects a covered one.
    #[test]
    fn is_the_conjunction_and_conservative() {
        let mut tris = cases::hard_triangles();
        tris.push(figure1::triangle());
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (mut covered, mut cut_by_la_only, mut cut_by_lb_only) = (0, 0, 0);
        for tri in &tris {
            let o = tri.to_oracle();
            for tx in -5..5 {
                for ty in -5..5 {
                    let tile = Tile::square(tx as f32 * 4.0, ty as f32 * 4.0, 4.0);
                    let lc = bounds_of(METHOD, tri, &tile);
                    let la = bounds_of(super::super::la2011::METHOD, tri, &tile);
                    let lb = bounds_of(super::super::lb2011::METHOD, tri, &tile);
                    for _ in 0..300 {
                        let s = random_sample(&mut rng, &tile);
                        let a = la.as_ref().is_some_and(|b| b.admits(&s));
                        let b = lb.as_ref().is_some_and(|b| b.admits(&s));
                        let c = lc.as_ref().is_some_and(|b| b.admits(&s));
                        assert_eq!(c, a && b, "{tile:?} {s:?}");
                        cut_by_la_only += (b && !a) as usize;
                        cut_by_lb_only += (a && !b) as usize;
                        if oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior {
                            covered += 1;
                            assert!(c, "{tri:?}\n{tile:?}: covered {s:?} rejected by {lc:?}");
                        }
                    }
                }
            }
        }
        assert!(covered > 2000, "{covered}");
        // LB's patches cull samples LA keeps.
        assert!(cut_by_lb_only > 0, "{cut_by_lb_only}");
        let _ = cut_by_la_only;
    }

    /// LA's per-vertex lens thresholds beat LB's patch when the vertex that is leftmost
    /// changes across the lens (vertices with different CoC): LC keeps LA's cut.
    #[test]
    fn la_lens_threshold_cuts_what_the_patch_keeps() {
        // Static, w = 1, per-vertex CoC. At the column X1 = 1: vertex A has d = 1, c = 1,
        // B has d = 5, c = 10, C has d = 3, c = 1. The min patch interpolates
        // min(1+u, 5+10u, 3+u) between -5 (u = -1) and 2 (u = 1): it culls u > 3/7 only,
        // while no vertex reaches the tile for u > -0.5 (LA's threshold of B).
        let tri = Triangle {
            q: [[2.0, 0.0, 0.5, 1.0], [6.0, 5.0, 0.5, 1.0], [4.0, 10.0, 0.5, 1.0]],
            r: [[2.0, 0.0, 0.5, 1.0], [6.0, 5.0, 0.5, 1.0], [4.0, 10.0, 0.5, 1.0]],
            c0: [1.0, 10.0, 1.0],
            c1: [1.0, 10.0, 1.0],
            k: 1.0,
        };
        let tile = Tile { x0: 0.0, y0: 4.0, x1: 1.0, y1: 6.0 };
        let la = bounds_of(super::super::la2011::METHOD, &tri, &tile).unwrap();
        let lb = bounds_of(super::super::lb2011::METHOD, &tri, &tile).unwrap();
        let lc = bounds_of(METHOD, &tri, &tile).unwrap();
        assert_eq!(la.u[1], -0.5);
        assert!((lb.u[1] - 3.0 / 7.0).abs() < 1e-6, "{:?}", lb.u);
        assert_eq!(lc.u[1], -0.5);
        let s = Sample::new(0.5, 5.0, 0.0, 0.0, 0.5);
        assert!(lb.admits(&s) && !la.admits(&s) && !lc.admits(&s));
        let o = tri.to_oracle();
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let mut covered = 0;
        for _ in 0..20000 {
            let s = random_sample(&mut rng, &tile);
            if oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior {
                covered += 1;
                assert!(lc.admits(&s), "{s:?}");
            }
        }
        assert!(covered > 100, "{covered}");
    }

    #[test]
    fn figure1_keeps_the_strip_inside_las_box() {
        let tri = figure1::triangle();
        let b = bounds_of(METHOD, &tri, &figure1::tile()).unwrap();
        let close = |a: [f32; 2], e: [f32; 2]| (a[0] - e[0]).abs() < 1e-6 && (a[1] - e[1]).abs() < 1e-6;
        assert!(close(b.t, figure1::LA_T) && close(b.u, figure1::LA_U) && close(b.v, figure1::LA_V), "{b:?}");
        assert!(!b.constraints.is_empty());
        assert!(b.admits(&Sample::new(0.0, 0.0, 0.0, 0.0, 0.5)));
        assert!(!b.admits(&Sample::new(0.0, 0.0, 1.0, 0.0, 0.7)));
    }
    /// Random triangles of every kind (w <= 0, static, motion-only, per-vertex and
    /// thin-lens CoC), random tiles, samples pushed to just outside a bound of LA, LB
    /// or LC, or onto the zero set of one of LB's patches (at a tile side): no method
    /// may reject a covered one.
    #[test]
    fn random_samples_near_the_bounds_are_not_culled_when_covered() {
        let mut rng = ChaCha8Rng::seed_from_u64(999);
        let ms: [&dyn Method; 3] = [super::super::la2011::METHOD, super::super::lb2011::METHOD, METHOD];
        let mut covered = 0u64;
        let mut viol = [0u64; 3];
        let mut near = 0u64;
        for n in 0..1500 {
            let kind = n % 6;
            let v = |rng: &mut ChaCha8Rng| {
                let w: f32 = if kind == 0 { rng.gen_range(-1.0..3.0) } else { rng.gen_range(0.2..4.0) };
                [rng.gen_range(-6.0..6.0) * w.abs().max(0.2), rng.gen_range(-6.0..6.0) * w.abs().max(0.2), 0.5, w]
            };
            let q = [v(&mut rng), v(&mut rng), v(&mut rng)];
            let r = if kind == 3 { q } else { [v(&mut rng), v(&mut rng), v(&mut rng)] };
            let (c0, c1) = if kind == 4 {
                ([0.0; 3], [0.0; 3])
            } else if kind == 5 {
                // thin lens c = a + b w
                let (a, b) = (rng.gen_range(-3.0..0.0f32), rng.gen_range(0.0..2.0f32));
                (q.map(|p| a + b * p[3]), r.map(|p| a + b * p[3]))
            } else {
                let mut c = || rng.gen_range(-4.0..4.0f32);
                ([c(), c(), c()], [c(), c(), c()])
            };
            let tri = Triangle { q, r, c0, c1, k: rng.gen_range(0.5..2.0) };
            let o = tri.to_oracle();
            let preps: Vec<_> = ms.iter().map(|m| m.setup(&tri)).collect();
            for _ in 0..4 {
                let size = [0.25f32, 1.0, 3.0, 8.0][rng.gen_range(0..4)];
                let tile = Tile::square(rng.gen_range(-8.0..8.0), rng.gen_range(-8.0..8.0), size);
                let res: Vec<_> = preps.iter().map(|p| p.tile(&tile)).collect();
                for j in 0..400 {
                    let mut s = Sample::new(
                        rng.gen_range(tile.x0..=tile.x1),
                        rng.gen_range(tile.y0..=tile.y1),
                        rng.gen_range(-1.0..=1.0),
                        rng.gen_range(-1.0..=1.0),
                        rng.gen_range(0.0..=1.0),
                    );
                    // half of the samples just outside some method's t/u/v bound
                    if j % 2 == 0 {
                        if let TileResult::Bounds(b) = &res[(j / 2) % 3] {
                            let eps = 1e-3 * rng.gen_range(0.0..1.0f32);
                            match rng.gen_range(0..6) {
                                0 => s.t = (b.t[0] - eps).max(0.0),
                                1 => s.t = (b.t[1] + eps).min(1.0),
                                2 => s.u = (b.u[0] - eps).max(-1.0),
                                3 => s.u = (b.u[1] + eps).min(1.0),
                                4 => s.v = (b.v[0] - eps).max(-1.0),
                                _ => s.v = (b.v[1] + eps).min(1.0),
                            }
                            near += 1;
                        }
                    }
                    if j % 4 == 1 {
                        if rng.gen_bool(0.5) {
                            s.x = if rng.gen_bool(0.5) { tile.x0 } else { tile.x1 }
                        }
                        if rng.gen_bool(0.5) {
                            s.y = if rng.gen_bool(0.5) { tile.y0 } else { tile.y1 }
                        }
                        if let TileResult::Bounds(b) = &res[1] {
                            if !b.constraints.is_empty() {
                                let c = &b.constraints[rng.gen_range(0..b.constraints.len())];
                                // bisection on t for g = 0 at this (u, v)
                                let g = |t: f32| c.eval(&Sample { t, ..s });
                                let (mut lo, mut hi) = (0.0f32, 1.0f32);
                                if (g(lo) < 0.0) != (g(hi) < 0.0) {
                                    for _ in 0..40 {
                                        let m = 0.5 * (lo + hi);
                                        if (g(m) < 0.0) == (g(lo) < 0.0) {
                                            lo = m
                                        } else {
                                            hi = m
                                        }
                                    }
                                    s.t = if rng.gen_bool(0.5) { lo } else { hi };
                                    near += 1;
                                }
                            }
                        }
                    }
                    if oracles::classify(&o, s.to_oracle()) == oracles::Coverage::Interior {
                        covered += 1;
                        for (m, r) in res.iter().enumerate() {
                            let ok = match r {
                                TileResult::Empty => false,
                                TileResult::Bounds(b) => b.admits(&s),
                            };
                            if !ok {
                                viol[m] += 1;
                                if viol[m] < 4 {
                                    eprintln!("VIOLATION {}: {tri:?} {tile:?} {s:?} {r:?}", ms[m].info().id);
                                }
                            }
                        }
                    }
                }
            }
        }
        assert_eq!(viol, [0; 3], "covered {covered}, pushed {near}");
        assert!(covered > 50000 && near > 500000, "covered {covered}, pushed {near}");
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    }
}
