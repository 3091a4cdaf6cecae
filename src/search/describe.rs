//! A case file in words (`cullproof explain`).

use super::*;
use crate::bounds::{Method, TileResult};
use crate::gate::CheckConfig;
use oracles::classify;

/// The case in words: the method's answer, the exact extents of the covered set over
/// the tile, and the witness decided exactly (and by Embree when physical).
pub fn describe(cf: &CaseFile) -> String {
    describe_with(cf, method_of(&cf.method).expect("checked at load"))
}

/// [`describe()`], the method's answer given by `m` (a bound of the caller's own, or
/// another than the file names).
pub fn describe_with(cf: &CaseFile, m: &dyn Method) -> String {
    use oracles::extents::{Extent, ExtentsConfig, Occupancy, TileSolver};
    let info = m.info();
    let (seen, tri) = match crate::cases::place::judged_triangles(cf.snap, &cf.case) {
        Ok(x) => x,
        Err(e) => return format!("{}: the case cannot be snapped: {e}\n", info.id),
    };
    let mut s =
        format!("{} ({}{})\n", info.id, info.source, if info.reconstruction { "; a reconstruction" } else { "" });
    s += &format!(
        "case: {} triangle ({}), found by {} (seed {}, case {}, regime {}){}\n",
        cf.case.triangle.dims().name(),
        if cf.case.lens.is_some() { "thin lens" } else { "no physical lens: exact oracle only" },
        cf.provenance.found_by,
        cf.provenance.seed,
        cf.provenance.case_index,
        cf.provenance.regime,
        if cf.provenance.shrink_steps.is_empty() {
            String::new()
        } else {
            format!(", shrunk: {}", cf.provenance.shrink_steps.join(", "))
        }
    );
    if !cf.note.is_empty() {
        s += &format!("note: {}\n", cf.note);
    }
    let t = &cf.tile;
    s += &format!("tile: [{}, {}] x [{}, {}]\n", t.x0, t.x1, t.y0, t.y1);
    if !cf.samples.is_any() || cf.snap.is_some() || cf.viewport.is_some() {
        let cfg = cf.settings(&CheckConfig::default_for(Vec::new()));
        s += &format!("{}\n", crate::gate::settings::SetNote::of(&cfg, 0).map(|n| n.line()).unwrap_or_default());
        if cf.snap.is_some() {
            s += "the method sees the snapped triangle (rounded to f32); the exact oracle judges it unrounded\n";
        }
    }
    let prep = m.setup(&seen);
    if let Some(why) = prep.disabled() {
        s += &format!("the method is disabled for this triangle: {why}\n");
    }
    match prep.tile(t) {
        TileResult::Empty => s += "the method says: tile empty (culled)\n",
        TileResult::Bounds(b) => {
            s += &format!(
                "the method says: u in [{}, {}], v in [{}, {}], t in [{}, {}]",
                b.u[0], b.u[1], b.v[0], b.v[1], b.t[0], b.t[1]
            );
            if let Some(z) = b.z {
                s += &format!(", depth in [{}, {}]", z[0], z[1]);
            }
            if !b.constraints.is_empty() {
                let names: Vec<_> = b.constraints.iter().map(|c| c.name()).collect();
                s += &format!(", and per sample: {}", names.join("; "));
            }
            s += "\n";
        }
    }
    let cfg = ExtentsConfig { occupancy_eliminates: false, ..ExtentsConfig::default() };
    let tb = [t.x0 as f64, t.x1 as f64, t.y0 as f64, t.y1 as f64];
    let mut solver = TileSolver::new(&tri, tb, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg);
    match solver.occupancy() {
        Occupancy::Empty => s += "exact: nothing in the tile is covered (certified)\n",
        Occupancy::Unknown => s += "exact: the solver could not decide whether anything in the tile is covered\n",
        Occupancy::Covered(_) => {
            s += "exact extents of the covered samples over the tile (certified enclosures of each extreme):\n";
            // Only the dimensions the triangle has: without defocus every lens position
            // covers the same samples, without motion every time does.
            let (lens, time) = (!tri.is_pinhole(), !tri.is_static());
            if !lens {
                s += "  u, v      any (no defocus: every lens position covers the same samples)\n";
            }
            if !time {
                s += "  t         any (no motion: every time covers the same samples)\n";
            }
            let has = |ext: Extent| match ext {
                Extent::UMin | Extent::UMax | Extent::VMin | Extent::VMax => lens,
                Extent::TMin | Extent::TMax => time,
                _ => true,
            };
            for (ext, name) in Extent::ALL.into_iter().zip([
                "u min",
                "u max",
                "v min",
                "v max",
                "t min",
                "t max",
                "depth min",
                "depth max",
            ]) {
                if !has(ext) {
                    continue;
                }
                let r = solver.objective(ext);
                match r.extreme {
                    Some(e) => {
                        s += &format!(
                            "  {name:<9} in [{:.9}, {:.9}]{}\n",
                            e.lo,
                            e.hi,
                            if r.undecided > 0 { format!(" ({} boxes undecided)", r.undecided) } else { String::new() }
                        )
                    }
                    None => s += &format!("  {name:<9} unknown ({} boxes undecided)\n", r.undecided),
                }
            }
        }
    }
    match &cf.witness {
        None => s += "no witness stored\n",
        Some(w) => {
            let p = w.sample;
            s += &format!("witness (x, y, u, v, t) = ({}, {}, {}, {}, {})\n", p[0], p[1], p[2], p[3], p[4]);
            s += &format!("  exact coverage: {:?}\n", classify(&tri, p));
            match witness_holds_in(m, &cf.case, &cf.tile, p, cf.samples, cf.snap) {
                Ok((b, d)) => s += &format!("  culled by {b}, {d:.6e} beyond it: a VIOLATION\n"),
                Err(e) => s += &format!("  not a violation: {e}\n"),
            }
            if let Some(l) = crate::judge::agree::lens_tri(&cf.case).filter(|_| cf.snap.is_none()) {
                if let Ok(o) = oracles::embree::EmbreeOracle::new(&l) {
                    s += &format!("  Embree (f32, second opinion): {}\n", if o.hit(p) { "hit" } else { "miss" });
                }
            }
            s += &format!("  stored: culled by {}, margin needed {:.6e}\n", w.bound, w.margin);
        }
    }
    s
}
