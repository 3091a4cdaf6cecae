//! The symbolic search (needs the `z3` binary; `.ci/run` installs it): the SMT-LIB2
//! meaning of the code evaluates to the same bits as the f32 meaning, and a z3 model of
//! bbox's f32 tile cull is confirmed as a violation by the exact judge.

#[allow(dead_code)]
mod common;

use common::Cli;
use cullproof::bounds::arith::{F32Arith, Plain, TriOf};
use cullproof::bounds::bbox::{aabb_of, rejects};
use cullproof::bounds::broken::planted::{BAND_HI, BAND_LO};
use cullproof::bounds::{by_id, TileResult};
use cullproof::tools::symbolic::prove::{
    family, prove, queries, range_sets, Limits, ProveReport, QueryReport, Rule, Strategy, Template, DEFAULT_FREE_SHARE,
    DEFAULT_RLIMIT,
};
use cullproof::tools::symbolic::smt::Smt;
use cullproof::tools::symbolic::solver::{self, Solvers};
use cullproof::tools::symbolic::z3::{self, Answer};
use cullproof::{Tile, Triangle};

/// xorshift in [0, 1).
fn rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn same_bits(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Evaluate terms of a finished script with z3 and read them back.
fn eval(smt: &Smt, floats: &[String], bools: &[String]) -> (Vec<f32>, Vec<bool>) {
    let mut show = floats.to_vec();
    show.extend(bools.iter().cloned());
    let script = smt.script(&show);
    if let Ok(p) = std::env::var("SYMB_DUMP") {
        std::fs::write(p, &script).unwrap();
    }
    let run = z3::run(&script, 240.0).expect("z3 runs (install z3)");
    assert_eq!(run.answer, Answer::Sat, "{}", run.output);
    let f = floats.iter().map(|n| z3::value(&run.output, n).unwrap()).collect();
    let b = bools.iter().map(|n| z3::truth(&run.output, n).unwrap()).collect();
    (f, b)
}

/// Evaluate the terms with z3 and require the f32 values bit for bit (any NaN for a
/// NaN) and the truth values.
fn assert_evaluates_to(smt: &Smt, floats: &[String], bools: &[String], want_f: &[f32], want_b: &[bool]) {
    let (f, b) = eval(smt, floats, bools);
    for (k, (w, g)) in want_f.iter().zip(&f).enumerate() {
        assert!(same_bits(*w, *g), "value {k} ({}): f32 {w:e}, z3 {g:e}", floats[k]);
    }
    assert_eq!(want_b, b);
}

#[test]
fn every_operation_means_the_same_bits_in_both_instances() {
    let specials =
        [0.0f32, -0.0, 1.0, -1.5, 1e-45, -1e-45, f32::MIN_POSITIVE, f32::MAX, f32::INFINITY, f32::NEG_INFINITY];
    let mut r = rng(7);
    let mut vals: Vec<f32> = specials.to_vec();
    vals.push(f32::NAN);
    for _ in 0..6 {
        vals.push(((r() - 0.5) * 2.0f64.powi((r() * 60.0) as i32 - 30)) as f32);
    }
    let smt = Smt::new();
    let p = Plain;
    let (mut want_f, mut got_f, mut want_b, mut got_b) = (vec![], vec![], vec![], vec![]);
    for (i, a) in vals.iter().enumerate() {
        let b = vals[(i * 7 + 3) % vals.len()];
        let c = vals[(i * 5 + 1) % vals.len()];
        let (sa, sb, sc) = (smt.lit(*a), smt.lit(b), smt.lit(c));
        for (w, g) in [
            (p.add(a, &b), smt.add(&sa, &sb)),
            (p.sub(a, &b), smt.sub(&sa, &sb)),
            (p.mul(a, &b), smt.mul(&sa, &sb)),
            (p.div(a, &b), smt.div(&sa, &sb)),
            (p.fma(a, &b, &c), smt.fma(&sa, &sb, &sc)),
            (p.neg(a), smt.neg(&sa)),
            (p.abs(a), smt.abs(&sa)),
            (p.min(a, &b), smt.min(&sa, &sb)),
            (p.max(a, &b), smt.max(&sa, &sb)),
            (p.next_up(a), smt.next_up(&sa)),
            (p.next_down(a), smt.next_down(&sa)),
            (p.select(&p.lt(a, &b), a, &c), smt.select(&smt.lt(&sa, &sb), &sa, &sc)),
        ] {
            want_f.push(w);
            got_f.push(g);
        }
        for (w, g) in [
            (p.lt(a, &b), smt.lt(&sa, &sb)),
            (p.le(a, &b), smt.le(&sa, &sb)),
            (p.eq(a, &b), smt.eq(&sa, &sb)),
            (p.is_nan(a), smt.is_nan(&sa)),
            (p.is_finite(a), smt.is_finite(&sa)),
        ] {
            want_b.push(w);
            got_b.push(g);
        }
    }
    let (f, b) = eval(&smt, &got_f, &got_b);
    for (k, (w, g)) in want_f.iter().zip(&f).enumerate() {
        assert!(
            same_bits(*w, *g),
            "operation {} of input {}: f32 {w:e} ({:#x}), z3 {g:e} ({:#x})",
            k % 12,
            k / 12,
            w.to_bits(),
            g.to_bits()
        );
    }
    assert_eq!(want_b, b);
}

/// A random triangle (some with a vertex whose x equals its CoC, some with a depth in
/// the planted band, some with w <= 0) and a tile near its box.
fn random_case(r: &mut impl FnMut() -> f64, n: usize) -> (Triangle, Tile) {
    let scale = [1e-3f64, 1.0, 1e3, 1e6][n % 4];
    let mut tri = Triangle::fixed([[0.0, 0.0, 0.5, 1.0]; 3]);
    for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
        p[0] = ((r() - 0.5) * 2.0 * scale) as f32;
        p[1] = ((r() - 0.5) * 2.0 * scale) as f32;
        p[3] = (0.1 + r() * 8.0) as f32;
    }
    for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
        *c = ((r() - 0.5) * 0.2 * scale) as f32;
    }
    tri.k = (0.5 + r()) as f32;
    match n % 5 {
        0 => tri.q[0][0] = tri.c0[0],
        1 => tri.r[1][3] = 2.00003,
        2 => tri.q[2][3] = -1.0,
        _ => {}
    }
    let (x, y) = (((r() - 0.5) * 4.0 * scale) as f32, ((r() - 0.5) * 4.0 * scale) as f32);
    let size = (scale * r()) as f32 + 1.0;
    (tri, Tile { x0: x, y0: y, x1: x + size, y1: y + size })
}

/// The anti-drift test: bbox's setup and tile reject, under every encoded corner rule,
/// evaluated by z3 from the SMT-LIB2 emission, give the f32 method's bits.
#[test]
fn the_emitted_method_evaluates_to_the_f32_bits() {
    let mut r = rng(0x5eed);
    let rules = [
        (Rule::Plain, "bbox"),
        (Rule::Safe, "bbox-safe"),
        (Rule::Eq, "broken/planted-eq/bbox-safe"),
        (Rule::Band, "broken/planted-band/bbox-safe"),
    ];
    let smt = Smt::new();
    let (mut floats, mut bools, mut want_f, mut want_b) = (vec![], vec![], vec![], vec![]);
    let mut culled = 0;
    for n in 0..10 {
        let (tri, tile) = random_case(&mut r, n);
        for (rule, id) in rules {
            let (en, bx) = aabb_of(&Plain, &rule, &TriOf::of(&tri));
            let rej = rejects(&Plain, &en, &bx, &[tile.x0, tile.y0, tile.x1, tile.y1]);
            // The f32 instance is the method the gate runs.
            let m = cullproof::cli::args::method("--method", id, true).unwrap();
            assert_eq!(rej, matches!(m.setup(&tri).tile(&tile), TileResult::Empty), "{id} {tri:?} {tile:?}");
            culled += rej as usize;
            let st = TriOf::of(&tri).map(|v| smt.lit(*v));
            let (sen, sbx) = aabb_of(&smt, &rule, &st);
            let stile = [tile.x0, tile.y0, tile.x1, tile.y1].map(|v| smt.lit(v));
            let srej = rejects(&smt, &sen, &sbx, &stile);
            floats.extend(sbx);
            want_f.extend(bx);
            bools.extend([sen, srej]);
            want_b.extend([en, rej]);
        }
    }
    assert_evaluates_to(&smt, &floats, &bools, &want_f, &want_b);
    assert!(culled > 0, "no culled tile among the inputs: the reject went untested");
    assert!(by_id("bbox").is_some());
}

/// The default concolic search of a method for a seed, with a generous plan (it stops
/// at the first confirmed violation).
fn search(id: &str, seed: u64, jobs: usize) -> ProveReport {
    let m = cullproof::cli::args::method("--method", id, true).unwrap();
    let f = family(id, Template::Static).unwrap();
    let sets = range_sets(f.as_ref(), None);
    let plan = queries(f.as_ref(), Strategy::Concolic, &sets, seed, 4000, DEFAULT_FREE_SHARE);
    let limits = Limits { timeout: 60.0, rlimit: Some(DEFAULT_RLIMIT), jobs, solvers: Solvers::Z3 };
    prove(m, Template::Static, Strategy::Concolic, seed, &plan, limits, None, None, false).unwrap()
}

/// The confirmed query of a report, and its case rebuilt from the model's inputs.
fn confirmed(r: &ProveReport, id: &str) -> (QueryReport, Triangle, Tile) {
    let q =
        r.queries.iter().find(|q| q.confirmed).unwrap_or_else(|| panic!("no confirmed case: {}", r.render())).clone();
    assert_eq!(q.answer, Answer::Sat);
    assert_eq!(Some(q.index), r.first_confirmed);
    assert_eq!(q.index + 1, r.queries.len(), "the run stops at the first confirmed query");
    let f = family(id, Template::Static).unwrap();
    let side = f.sides().iter().position(|s| *s == q.side).unwrap();
    let (tri, tile) = f.instance(side, q.inputs.as_ref().unwrap());
    (q, tri, tile)
}

/// The exact edge of the template (x-min: `(a - c) / w`, x-max: `(a + c) / w`) lies
/// strictly inside the tile's x range, decided in exact rationals.
fn edge_inside(side: &str, v: &[f32], tile: &Tile) -> bool {
    use num_rational::BigRational;
    let q = |x: f32| BigRational::from_float(x as f64).unwrap();
    let (a, c, w) = (q(v[0]), q(v[1]), q(v[2]));
    let x = if side == "x-min" { (a - c) / w } else { (a + c) / w };
    q(tile.x0) < x && x < q(tile.x1)
}

/// z3 places a tile that bbox's f32 box culls although the exact footprint reaches it,
/// and the exact judge confirms the case as a violation.
#[test]
fn the_symbolic_search_finds_bbox_f32_tile_cull() {
    let r = search("bbox", 1, 2);
    let (q, tri, tile) = confirmed(&r, "bbox");
    assert!(matches!(by_id("bbox").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
    assert!(edge_inside(q.side, q.inputs.as_ref().unwrap(), &tile), "{}", r.render());
    // bbox-safe does not cull it.
    assert!(!matches!(by_id("bbox-safe").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
    // Under the concolic plan an `unsat` is "none with these fixed values", never a
    // statement about the ranges.
    let text = r.render();
    if r.queries.iter().any(|q| q.answer == Answer::Unsat) {
        assert!(text.contains("none with these fixed values"), "{text}");
    }
    assert!(!text.contains("no input of this template and ranges"), "{text}");
}

/// The whole query of the narrow ranges (every input free): z3 finds bbox's cull there
/// too, in minutes (`cargo test --release --test symbolic -- --ignored`).
#[test]
#[ignore]
fn a_whole_query_finds_bbox_f32_tile_cull_in_narrow_ranges() {
    let m = by_id("bbox").unwrap();
    let f = family("bbox", Template::Static).unwrap();
    let r =
        cullproof::tools::symbolic::family::parse_ranges(f.as_ref(), "--ranges", "a=128:256,c=1:2,w=1.875:2,t=96:128")
            .unwrap();
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, r)];
    let limits = Limits { timeout: 900.0, rlimit: None, jobs: 1, solvers: Solvers::Z3 };
    let r = prove(m, Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false).unwrap();
    let (q, _, tile) = confirmed(&r, "bbox");
    assert!(edge_inside(q.side, q.inputs.as_ref().unwrap(), &tile));
}

/// The two planted slips are found and confirmed: the equality one with a vertex's x
/// equal to its CoC, the band one with a depth in the band. bbox-safe itself does not
/// cull the case (the slip is the only way to fail).
#[test]
fn the_symbolic_search_finds_the_planted_slips() {
    let safe = by_id("bbox-safe").unwrap();
    for id in ["broken/planted-eq/bbox-safe", "broken/planted-band/bbox-safe"] {
        let r = search(id, 1, 2);
        let (q, tri, tile) = confirmed(&r, id);
        let v = q.inputs.clone().unwrap();
        if id.contains("-eq/") {
            assert_eq!(v[0].to_bits(), v[1].to_bits(), "the equality slip fired without a == c: {v:?}");
        } else {
            assert!((BAND_LO..BAND_HI).contains(&v[2]), "the band slip fired outside the band: {v:?}");
        }
        let m = cullproof::cli::args::method("--method", id, true).unwrap();
        assert!(matches!(m.setup(&tri).tile(&tile), TileResult::Empty));
        assert!(!matches!(safe.setup(&tri).tile(&tile), TileResult::Empty), "{id}: bbox-safe culls it too");
        assert!(r.render().contains("first confirmed violation"));
    }
}

/// The report for a seed is the same at any number of jobs (the resource limit makes
/// each answer deterministic; the run stops at the same query).
#[test]
fn the_concolic_search_does_not_depend_on_jobs() {
    let id = "broken/planted-eq/bbox-safe";
    let (a, b) = (search(id, 3, 1), search(id, 3, 2));
    let key = |r: &ProveReport| -> Vec<(usize, String, String, Option<Vec<u32>>)> {
        r.queries
            .iter()
            .map(|q| {
                (
                    q.index,
                    q.query.clone(),
                    q.answer.name().to_string(),
                    q.inputs.as_ref().map(|v| v.iter().map(|x| x.to_bits()).collect()),
                )
            })
            .collect()
    };
    assert_eq!(key(&a), key(&b));
    assert!(a.first_confirmed.is_some(), "{}", a.render());
}

/// The f32 answer bits of a method's tile test: None for Empty, else t, u, v.
fn answer_bits(r: &TileResult) -> Option<[f32; 6]> {
    match r {
        TileResult::Empty => None,
        TileResult::Bounds(b) => Some([b.t[0], b.t[1], b.u[0], b.u[1], b.v[0], b.v[1]]),
    }
}

/// Cases for an encoded tile test: from [`random_case`], until `each` culled and `each`
/// kept tiles are found for every method id (with a few tiles moved onto the box).
fn culled_and_kept(ids: &[&str], each: usize, seed: u64) -> Vec<(Triangle, Tile)> {
    let mut r = rng(seed);
    let mut out = vec![];
    let mut count = vec![[0usize; 2]; ids.len()];
    for n in 0..20_000 {
        let (tri, mut tile) = random_case(&mut r, n);
        if n % 3 == 0 {
            // a tile just beside vertex 0's projection: the reject's limit
            let (x, y) = (tri.q[0][0] / tri.q[0][3], tri.q[0][1] / tri.q[0][3]);
            let s = tile.x1 - tile.x0;
            tile = Tile { x0: x + s * 0.01, y0: y, x1: x + s, y1: y + s };
        }
        let mut useful = false;
        for (k, id) in ids.iter().enumerate() {
            let culled = matches!(by_id(id).unwrap().setup(&tri).tile(&tile), TileResult::Empty) as usize;
            if count[k][culled] < each {
                count[k][culled] += 1;
                useful = true;
            }
        }
        if useful {
            out.push((tri, tile));
        }
        if count.iter().all(|c| c[0] >= each && c[1] >= each) {
            return out;
        }
    }
    panic!("not enough culled and kept tiles among the inputs: {count:?}");
}

/// The anti-drift test for la2011 and la2011-safe: their setup and tile answer (the
/// reject and the t, u, v ranges), emitted as SMT-LIB2 and evaluated by z3, give the
/// bits of the methods the gate runs.
#[test]
fn the_emitted_la2011_evaluates_to_the_f32_bits() {
    use cullproof::bounds::la2011::{setup_of, tile_answer};
    use cullproof::bounds::round::{Nearest, Outward, Round};
    fn both<R: Round>(smt: &Smt, tri: &Triangle, tile: &Tile) -> ((bool, [f32; 6]), (String, Vec<String>)) {
        let tv = [tile.x0, tile.y0, tile.x1, tile.y1];
        let (ok, t, u, v) = tile_answer::<R, Plain>(&Plain, &setup_of::<R, Plain>(&Plain, &TriOf::of(tri)), &tv);
        let st = TriOf::of(tri).map(|x| smt.lit(*x));
        let (sok, st_, su, sv) = tile_answer::<R, Smt>(smt, &setup_of::<R, Smt>(smt, &st), &tv.map(|x| smt.lit(x)));
        let terms = [st_, su, sv].concat();
        ((ok, [t[0], t[1], u[0], u[1], v[0], v[1]]), (sok, terms))
    }
    let ids = ["la2011", "la2011-safe"];
    let cases = culled_and_kept(&ids, 2, 0x1a2011);
    let smt = Smt::new();
    let (mut floats, mut bools, mut want_f, mut want_b) = (vec![], vec![], vec![], vec![]);
    for (tri, tile) in &cases {
        for id in ids {
            let gate = answer_bits(&by_id(id).unwrap().setup(tri).tile(tile));
            let ((ok, vals), (sok, terms)) =
                if id == "la2011" { both::<Nearest>(&smt, tri, tile) } else { both::<Outward>(&smt, tri, tile) };
            // The f32 instance is the method the gate runs.
            assert_eq!(ok, gate.is_some(), "{id} {tri:?} {tile:?}");
            if let Some(g) = gate {
                assert!(g.iter().zip(&vals).all(|(a, b)| same_bits(*a, *b)), "{id}: {g:?} {vals:?}");
                floats.extend(terms);
                want_f.extend(vals);
            }
            bools.push(sok);
            want_b.push(ok);
        }
    }
    assert_evaluates_to(&smt, &floats, &bools, &want_f, &want_b);
}

/// The anti-drift test for mam2012: its setup (the enabling conditions, the screen
/// extent, the patches) and tile answer (the reject, u^, v^ and the four lines),
/// emitted as SMT-LIB2 and evaluated by z3, give the bits of the method the gate runs.
#[test]
fn the_emitted_mam2012_evaluates_to_the_f32_bits() {
    use cullproof::bounds::mam2012::{setup_of, tile_answer};
    // mam2012 needs one CoC sign and every w > 0: make most random cases so.
    let cases: Vec<(Triangle, Tile)> = culled_and_kept(&["mam2012"], 3, 0x3a32012)
        .into_iter()
        .chain((0..40).map(|n| {
            let mut r = rng(n + 99);
            let (mut tri, tile) = random_case(&mut r, n as usize);
            for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
                *c = c.abs() + 0.01;
            }
            (tri, tile)
        }))
        .collect();
    let m = by_id("mam2012").unwrap();
    let smt = Smt::new();
    let (mut floats, mut bools, mut want_f, mut want_b) = (vec![], vec![], vec![], vec![]);
    let (mut culled, mut enabled) = (0, 0);
    for (tri, tile) in cases.iter().take(12) {
        let tv = [tile.x0, tile.y0, tile.x1, tile.y1];
        let (why, s) = setup_of(&Plain, &TriOf::of(tri), false);
        let on = !why.iter().any(|&w| w);
        let (sw, ss) = setup_of(&smt, &TriOf::of(tri).map(|x| smt.lit(*x)), false);
        bools.extend(sw);
        want_b.extend(why);
        let gate = m.setup(tri).tile(tile);
        if !on {
            assert!(matches!(gate, TileResult::Bounds(_)), "a disabled mam2012 culled");
            continue;
        }
        enabled += 1;
        let (ok, u, v, lines) = tile_answer(&Plain, &s, &tv);
        // The f32 instance is the method the gate runs.
        assert_eq!(ok, answer_bits(&gate).is_some(), "{tri:?} {tile:?}");
        culled += !ok as usize;
        let (sok, su, sv, slines) = tile_answer(&smt, &ss, &tv.map(|x| smt.lit(x)));
        bools.push(sok);
        want_b.push(ok);
        if let TileResult::Bounds(b) = &gate {
            assert!(same_bits(b.u[0], u[0]) && same_bits(b.u[1], u[1]) && same_bits(b.v[0], v[0]));
            let shown: Vec<String> =
                lines.iter().filter(|l| l.0).map(|l| format!("a: {:?}, b: {:?}", l.1, l.2)).collect();
            assert_eq!(shown.len(), b.constraints.len());
            for (s, c) in shown.iter().zip(&b.constraints) {
                assert!(format!("{c:?}").contains(s.as_str()), "{c:?} vs {s}");
            }
            floats.extend([su, sv].concat());
            want_f.extend([u, v].concat());
            for ((on, a, b), (son, sa, sb)) in lines.iter().zip(slines) {
                bools.push(son);
                want_b.push(*on);
                if *on {
                    floats.extend([sa, sb]);
                    want_f.extend([*a, *b]);
                }
            }
        }
    }
    assert!(culled >= 2 && enabled >= culled + 2, "culled {culled}, enabled {enabled}");
    assert_evaluates_to(&smt, &floats, &bools, &want_f, &want_b);
}

/// The anti-drift test for mam2012-hyperplane's tile path: from the f32 setup's edges,
/// the planes, the reject and the refined u^, v^, t^, emitted as SMT-LIB2 and evaluated
/// by z3, give the bits of the method the gate runs.
#[test]
fn the_emitted_mam2012_hyperplane_tile_path_evaluates_to_the_f32_bits() {
    use cullproof::bounds::mam2012_hyperplane::{edges_of, tile_answer};
    let m = by_id("mam2012-hyperplane-ps").unwrap();
    let smt = Smt::new();
    let (mut floats, mut bools, mut want_f, mut want_b) = (vec![], vec![], vec![], vec![]);
    let mut culled = 0;
    let cases = culled_and_kept(&["mam2012-hyperplane-ps"], 4, 0x4e9);
    for (tri, tile) in &cases {
        let Ok((edges, k)) = edges_of(tri) else { continue };
        let tv = [tile.x0, tile.y0, tile.x1, tile.y1];
        let (ok, ranges, planes) = tile_answer(&Plain, &edges, &k, &tv);
        let gate = m.setup(tri).tile(tile);
        // The f32 instance is the method the gate runs.
        assert_eq!(ok, answer_bits(&gate).is_some(), "{tri:?} {tile:?}");
        culled += !ok as usize;
        let sedges = edges.each_ref().map(|e| e.map(|x| smt.lit(x)));
        let (sok, sranges, splanes) = tile_answer(&smt, &sedges, &smt.lit(k), &tv.map(|x| smt.lit(x)));
        bools.push(sok);
        want_b.push(ok);
        if let TileResult::Bounds(b) = &gate {
            let flat: Vec<f32> = ranges.iter().flatten().copied().collect();
            let g = [b.u, b.v, b.t].concat();
            assert!(flat.iter().zip(&g).all(|(a, b)| same_bits(*a, *b)), "{flat:?} {g:?}");
            floats.extend(sranges.into_iter().flatten());
            want_f.extend(flat);
            for ((on, a), (son, sa)) in planes.iter().zip(splanes) {
                bools.push(son);
                want_b.push(*on);
                if *on {
                    floats.extend(sa);
                    want_f.extend(a);
                }
            }
        }
    }
    assert!(culled >= 2, "culled {culled}");
    assert_evaluates_to(&smt, &floats, &bools, &want_f, &want_b);
}

/// The la2011 query pinned to a model z3 found (x-min, `prove --method la2011 --symbolic
/// --strategy whole --ranges a=128:256,c=1:2,w=1.875:2,t=96:128`): z3 answers sat at
/// once, the f32 method culls the model's tile and the exact judge confirms the
/// violation; the same pinned query against la2011-safe is unsat.
#[test]
fn the_la2011_query_holds_a_known_violation() {
    let v = [236.125f32, 1.8749528, 1.9463676, 120.35242];
    let pin: Vec<[f32; 2]> = v.iter().map(|&x| [x, x.next_up()]).collect();
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, pin)];
    let limits = Limits { timeout: 300.0, rlimit: None, jobs: 1, solvers: Solvers::Z3 };
    let r = prove(by_id("la2011").unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false)
        .unwrap();
    let (q, tri, tile) = confirmed(&r, "la2011");
    assert_eq!(q.inputs.as_deref(), Some(&v[..]), "{}", r.render());
    assert!(edge_inside(q.side, q.inputs.as_ref().unwrap(), &tile), "{}", r.render());
    assert!(!matches!(by_id("la2011-safe").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
    let safe =
        prove(by_id("la2011-safe").unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false)
            .unwrap();
    assert_eq!(safe.queries[0].answer, Answer::Unsat, "{}", safe.render());
}

/// The concolic search finds la2011's f32 tile cull (x time part of the reject) and the
/// judge confirms it (`cargo test --release --test symbolic -- --ignored`).
#[test]
#[ignore]
fn the_symbolic_search_finds_la2011_f32_tile_cull() {
    let r = search("la2011", 1, 2);
    let (q, tri, tile) = confirmed(&r, "la2011");
    assert!(edge_inside(q.side, q.inputs.as_ref().unwrap(), &tile), "{}", r.render());
    assert!(!matches!(by_id("la2011-safe").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
}

/// Every emitted script is standard SMT-LIB 2 that both solvers read: logic `QF_BVFP`
/// and no z3-only function (`fp.to_ieee_bv`); Bitwuzla answers the pinned la2011 query
/// as z3 does (sat against la2011, confirmed by the judge; unsat against la2011-safe,
/// with its ranges alone shown satisfiable).
#[test]
fn the_scripts_are_standard_and_bitwuzla_agrees_with_z3() {
    for id in ["bbox", "bbox-safe", "la2011", "la2011-safe"] {
        let f = family(id, Template::Static).unwrap();
        for side in 0..f.sides().len() {
            for r in f.default_ranges(side) {
                let (s, _) = cullproof::tools::symbolic::family::script(
                    f.as_ref(),
                    &cullproof::tools::symbolic::family::Query::free(side, r),
                );
                assert!(s.starts_with("(set-logic QF_BVFP)"), "{id}: {}", &s[..60]);
                assert!(!s.contains("to_ieee_bv"), "{id}: a z3-only function in the script");
            }
        }
    }
    let v = [236.125f32, 1.8749528, 1.9463676, 120.35242];
    let pin: Vec<[f32; 2]> = v.iter().map(|&x| [x, x.next_up()]).collect();
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, pin)];
    let limits = Limits { timeout: 300.0, rlimit: None, jobs: 1, solvers: Solvers::BITWUZLA };
    let r = prove(by_id("la2011").unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false)
        .unwrap();
    let (q, _, _) = confirmed(&r, "la2011");
    assert_eq!(q.solver, solver::Solver::Bitwuzla);
    assert_eq!(q.inputs.as_deref(), Some(&v[..]), "{}", r.render());
    let safe =
        prove(by_id("la2011-safe").unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false)
            .unwrap();
    assert_eq!(safe.queries[0].answer, Answer::Unsat, "{}", safe.render());
    assert_eq!(safe.queries[0].hypotheses_sat, Some(true), "{}", safe.render());
}

/// An `unsat` whose hypotheses are themselves unsatisfiable (here an empty range,
/// which `--ranges` refuses but a query built by hand can hold) is not counted: the
/// answer is `unknown`, with the reason in the table.
#[test]
fn an_unsat_with_contradictory_hypotheses_is_not_counted() {
    let v = [236.125f32, 1.8749528, 1.9463676, 120.35242];
    let empty: Vec<[f32; 2]> = v.iter().map(|&x| [x, x]).collect();
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, empty)];
    for solvers in [Solvers::Z3, Solvers::BITWUZLA] {
        let limits = Limits { timeout: 60.0, rlimit: None, jobs: 1, solvers };
        let r = prove(
            by_id("la2011-safe").unwrap(),
            Template::Static,
            Strategy::Whole,
            0,
            &plan,
            limits,
            None,
            None,
            false,
        )
        .unwrap();
        assert_eq!(r.queries[0].answer, Answer::Unknown, "{}", r.render());
        assert_eq!(r.queries[0].hypotheses_sat, Some(false), "{}", r.render());
        assert!(r.render().contains("unsat not counted"), "{}", r.render());
    }
}

/// The narrow-range bbox cull that z3 needs minutes for (the ignored test above),
/// found by the portfolio: Bitwuzla answers first, the judge confirms it.
#[test]
fn the_portfolio_finds_bbox_f32_tile_cull_in_narrow_ranges() {
    let m = by_id("bbox").unwrap();
    let f = family("bbox", Template::Static).unwrap();
    let r =
        cullproof::tools::symbolic::family::parse_ranges(f.as_ref(), "--ranges", "a=128:256,c=1:2,w=1.875:2,t=96:128")
            .unwrap();
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, r)];
    let limits = Limits { timeout: 600.0, rlimit: None, jobs: 1, solvers: Solvers::BOTH };
    let r = prove(m, Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false).unwrap();
    let (q, _, tile) = confirmed(&r, "bbox");
    assert!(edge_inside(q.side, q.inputs.as_ref().unwrap(), &tile), "{}", r.render());
    eprintln!("{}", r.render());
}

/// `prove` searches symbolically without being told (`--symbolic` is the only mode and
/// optional): a short concolic run answers, with its report.
#[test]
fn prove_runs_without_the_symbolic_flag() {
    let json = std::env::temp_dir().join(format!("cullproof-prove-noflag-{}.json", std::process::id()));
    let out =
        Cli::new(&["prove", "--method", "bbox", "--queries", "3", "--dry-run", "--json", json.to_str().unwrap()]).run();
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    std::fs::remove_file(&json).ok();
    assert_eq!(j["method"], "bbox");
    assert!(j["queries"].as_array().is_some_and(|q| !q.is_empty()), "{j}");
}

/// A bound that culls every tile: the judge's verdict on it says whether the tile holds
/// a covered sample (violated: one confirmed exactly; proven: certified empty).
struct CullAll;
struct CullAllP;
impl cullproof::bounds::Prepared for CullAllP {
    fn tile(&self, _t: &Tile) -> TileResult {
        TileResult::Empty
    }
}
static CULL_ALL: cullproof::bounds::MethodInfo = cullproof::bounds::MethodInfo {
    id: "cull-all",
    source: "test: culls every tile",
    reconstruction: false,
    dims: &[],
    outputs: cullproof::bounds::Outputs {
        tile_reject: true,
        lens: false,
        time: false,
        depth: false,
        per_sample: false,
    },
};
impl cullproof::bounds::Method for CullAll {
    fn info(&self) -> &'static cullproof::bounds::MethodInfo {
        &CULL_ALL
    }
    fn setup(&self, _t: &Triangle) -> Box<dyn cullproof::bounds::Prepared> {
        Box::new(CullAllP)
    }
}

/// The moving template's exact side, attacked with the exact judge: on random moving,
/// defocused instances whose tile edge lies a little inside or outside the least (x-min;
/// greatest, x-max) edge position over the shutter, the SMT assertion "the footprint
/// reaches the tile" (all inputs pinned, z3) holds exactly when the judge finds a covered
/// sample in the tile, and fails exactly when the judge certifies the tile empty.
#[test]
fn the_moving_templates_exact_side_agrees_with_the_judge() {
    use cullproof::tools::symbolic::bbox_query::Side;
    use cullproof::tools::symbolic::moving_query::{assert_reach, template};
    let mut r = rng(11);
    let (mut reached, mut empty) = (0, 0);
    for i in 0..24 {
        let side = if i % 2 == 0 { Side::XMin } else { Side::XMax };
        let sgn = if side == Side::XMin { 1.0 } else { -1.0 };
        let u = |r: &mut dyn FnMut() -> f64, lo: f64, hi: f64| (lo + (hi - lo) * r()) as f32;
        let (a0, a1) = (u(&mut r, -60.0, 60.0), u(&mut r, -60.0, 60.0));
        let (c0, c1) = (u(&mut r, 0.5, 8.0), u(&mut r, 0.5, 8.0));
        let (w0, w1) = (u(&mut r, 0.5, 4.0), u(&mut r, 0.5, 4.0));
        // the least (x-min) edge position over the shutter, from the ends
        let x = |a: f32, c: f32, w: f32| (a as f64 - sgn * c as f64) / w as f64;
        let edge = if side == Side::XMin { x(a0, c0, w0).min(x(a1, c1, w1)) } else { x(a0, c0, w0).max(x(a1, c1, w1)) };
        // the tile's near edge 0.3 px inside (reached) or 0.3 px outside (not)
        let inside = i % 4 < 2;
        let d = if inside { 0.3 } else { -0.3 };
        // x-min: tile [t - 1, t] reaches when edge < t; x-max: tile [t, t + 1] when edge > t
        let t = (edge + sgn * d) as f32;
        let v = [a0, a1, c0, c1, w0, w1, t];
        let (tri, tile) = template(&Plain, side, &v);
        let pinned = (tri.triangle(), Tile { x0: tile[0], y0: tile[1], x1: tile[2], y1: tile[3] });
        let got = reach_agrees_with_judge(i, &v, pinned, |smt, lits| {
            assert_reach(smt, side, &std::array::from_fn(|k| lits[k].clone()))
        });
        reached += (got == Some(true)) as usize;
        empty += (got == Some(false)) as usize;
        assert_eq!(got, Some(inside), "instance {i} {v:?}: the edge is 0.3 px from the tile");
    }
    assert!(reached >= 10 && empty >= 10, "{reached} reached, {empty} empty");
}

/// z3 places a tile that bbox's f32 box culls on the moving template, and the judge
/// confirms it: the exact least edge position over the shutter lies in the tile.
#[test]
fn the_moving_template_finds_bbox_f32_tile_cull() {
    let m = by_id("bbox").unwrap();
    let f = family("bbox", Template::Moving).unwrap();
    let sets = range_sets(f.as_ref(), None);
    let plan = queries(f.as_ref(), Strategy::Concolic, &sets, 1, 4000, DEFAULT_FREE_SHARE);
    let limits = Limits { timeout: 60.0, rlimit: Some(DEFAULT_RLIMIT), jobs: 2, solvers: Solvers::Z3 };
    let r = prove(m, Template::Moving, Strategy::Concolic, 1, &plan, limits, None, None, false).unwrap();
    let q = r.queries.iter().find(|q| q.confirmed).unwrap_or_else(|| panic!("no confirmed case: {}", r.render()));
    let v = q.inputs.clone().unwrap();
    let side = f.sides().iter().position(|s| *s == q.side).unwrap();
    let (tri, tile) = f.instance(side, &v);
    assert!(matches!(m.setup(&tri).tile(&tile), TileResult::Empty));
    assert!(!matches!(by_id("bbox-safe").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
    // the template moves: the two shutter ends differ
    assert!(v[0] != v[1] || v[2] != v[3] || v[4] != v[5], "{v:?}");
    use num_rational::BigRational;
    let qv = |x: f32| BigRational::from_float(x as f64).unwrap();
    // the least (x-min) or greatest (x-max) exact edge position over the shutter
    let edge = if side == 0 {
        std::cmp::min((qv(v[0]) - qv(v[2])) / qv(v[4]), (qv(v[1]) - qv(v[3])) / qv(v[5]))
    } else {
        std::cmp::max((qv(v[0]) + qv(v[2])) / qv(v[4]), (qv(v[1]) + qv(v[3])) / qv(v[5]))
    };
    assert!(qv(tile.x0) < edge && edge < qv(tile.x1), "{}", r.render());
    assert!(r.render().contains("template moving"), "{}", r.render());
}

/// mam2012's (and mam2012-safe's) cull as a query family asserts exactly what the f32 method does: on
/// moving template instances (all inputs pinned), the assertion "mam2012 culls the
/// tile" is satisfiable exactly where the registered method answers Empty.
#[test]
fn the_mam2012_cull_asserts_what_the_method_culls() {
    for id in ["mam2012", "mam2012-safe"] {
        cull_asserts_what_the_method_culls(id);
    }
}

/// wu2013-safe's encoded tile answer (stage 1 and 2 with their lines, intervals
/// included) asserts a cull exactly where the f32 method culls, on pinned instances of
/// the moving template.
#[test]
fn the_wu2013_safe_cull_asserts_what_the_method_culls() {
    cull_asserts_what_the_method_culls("wu2013-safe");
}

fn cull_asserts_what_the_method_culls(id: &str) {
    use cullproof::tools::symbolic::bbox_query::{Side, TemplateCull};
    use cullproof::tools::symbolic::moving_query::template;
    use cullproof::tools::symbolic::prove::cull;
    let m = by_id(id).unwrap();
    let cull = cull(id).unwrap();
    let mut r = rng(5);
    let (mut culled, mut kept) = (0, 0);
    for i in 0..16 {
        let side = if i % 2 == 0 { Side::XMin } else { Side::XMax };
        let u = |r: &mut dyn FnMut() -> f64, lo: f64, hi: f64| (lo + (hi - lo) * r()) as f32;
        let mut v = [0f32; 7];
        for (k, (lo, hi)) in
            [(-60.0, 60.0), (-60.0, 60.0), (0.5, 8.0), (0.5, 8.0), (0.5, 4.0), (0.5, 4.0)].into_iter().enumerate()
        {
            v[k] = u(&mut r, lo, hi);
        }
        // the tile's edge from 40 px outside the triangle's near edge to 40 px inside
        let sgn = if side == Side::XMin { 1.0 } else { -1.0 };
        let near = (v[0] as f64 - sgn * v[2] as f64) / v[4] as f64;
        v[6] = (near + sgn * u(&mut r, -40.0, 40.0) as f64) as f32;
        let (tri, tile) = template(&Plain, side, &v);
        let (tri, tile) = (tri.triangle(), Tile { x0: tile[0], y0: tile[1], x1: tile[2], y1: tile[3] });
        let f32_culls = matches!(m.setup(&tri).tile(&tile), TileResult::Empty);
        let smt = Smt::folding();
        let lits: Vec<String> = v.iter().map(|&x| cullproof::tools::symbolic::smt::lit(x)).collect();
        let (t, tl) = template(&smt, side, &std::array::from_fn(|k| lits[k].clone()));
        smt.assert(&cull.cull(&smt, side, &t, &tl));
        let run = z3::run(&smt.script(&[]), 120.0).expect("z3 runs");
        let want = if f32_culls { Answer::Sat } else { Answer::Unsat };
        assert_eq!(run.answer, want, "{id} instance {i} {v:?}");
        if f32_culls {
            culled += 1
        } else {
            kept += 1
        }
    }
    assert!(culled >= 3 && kept >= 3, "{id}: {culled} culled, {kept} kept");
}

/// On the moving template (narrow ranges, every input free), Bitwuzla finds la2011's
/// f32 tile cull of a moving, defocused triangle (confirmed by the judge, the two shutter
/// ends differing) and shows la2011-safe culls no reached tile there: both sides `unsat`,
/// each with its ranges alone shown satisfiable.
#[test]
fn the_moving_template_separates_la2011_from_la2011_safe() {
    let ranges = "a0=128:256,a1=128:256,c0=1:2,c1=1:2,w0=1.875:2,w1=1.875:2,t=96:128";
    let f = family("la2011", Template::Moving).unwrap();
    let r = cullproof::tools::symbolic::family::parse_ranges(f.as_ref(), "--ranges", ranges).unwrap();
    let limits = Limits { timeout: 600.0, rlimit: None, jobs: 2, solvers: Solvers::BITWUZLA };
    let plan = vec![cullproof::tools::symbolic::family::Query::free(0, r.clone())];
    let found = prove(by_id("la2011").unwrap(), Template::Moving, Strategy::Whole, 0, &plan, limits, None, None, false)
        .unwrap();
    let q = found.queries.iter().find(|q| q.confirmed).unwrap_or_else(|| panic!("{}", found.render()));
    let v = q.inputs.clone().unwrap();
    assert!(v[0] != v[1] || v[2] != v[3] || v[4] != v[5], "{v:?}");
    let (tri, tile) = f.instance(0, &v);
    assert!(!matches!(by_id("la2011-safe").unwrap().setup(&tri).tile(&tile), TileResult::Empty));
    let both = vec![
        cullproof::tools::symbolic::family::Query::free(0, r.clone()),
        cullproof::tools::symbolic::family::Query::free(1, r),
    ];
    let safe =
        prove(by_id("la2011-safe").unwrap(), Template::Moving, Strategy::Whole, 0, &both, limits, None, None, false)
            .unwrap();
    for q in &safe.queries {
        assert_eq!((q.answer, q.hypotheses_sat), (Answer::Unsat, Some(true)), "{}", safe.render());
    }
    assert!(safe.render().contains("every query unsat with satisfiable ranges"), "{}", safe.render());
}

/// The hypotheses an `unsat` needs include a reached tile: with ranges that put every
/// `x-max` tile beside the triangle (`a` in [128, 136), `t` in [96, 128): the right edge
/// `(a + c) / w` stays below 74), bbox-safe's `x-max` query is `unsat` for want of any
/// reached tile and is reported unknown; its `x-min` query, where every tile of the
/// ranges is reached, counts.
#[test]
fn an_unsat_without_any_reached_tile_is_not_counted() {
    let f = family("bbox-safe", Template::Static).unwrap();
    let r = cullproof::tools::symbolic::family::parse_ranges(
        f.as_ref(),
        "--ranges",
        "a=128:136,c=1:1.125,w=1.875:2,t=96:128",
    )
    .unwrap();
    let plan = vec![
        cullproof::tools::symbolic::family::Query::free(0, r.clone()),
        cullproof::tools::symbolic::family::Query::free(1, r),
    ];
    let limits = Limits { timeout: 300.0, rlimit: None, jobs: 2, solvers: Solvers::BITWUZLA };
    let rep =
        prove(by_id("bbox-safe").unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false)
            .unwrap();
    let (min, max) = (&rep.queries[0], &rep.queries[1]);
    assert_eq!((min.answer, min.hypotheses_sat), (Answer::Unsat, Some(true)), "{}", rep.render());
    assert_eq!((max.answer, max.hypotheses_sat), (Answer::Unknown, Some(false)), "{}", rep.render());
    assert!(rep.render().contains("the ranges with a reached tile were not shown satisfiable"), "{}", rep.render());
}

/// nilsson2012-depth's encoded failure (its whole setup and tile answer, over
/// `F32Arith`) asserts exactly what the f32 method does wrong or culls: on pinned
/// instances of both templates (every vertex at one depth per shutter end, the
/// screen-parallel triangles where the published plane bound can round below the vertex
/// depth), the assertion is sat exactly where the method answers Empty or, for a flat
/// triangle (one z and one w for all six vertices), answers a depth interval that
/// excludes `z / w` (decided here in exact f64 products), for the published method and
/// for its -safe variant and planted slips.
#[test]
fn the_nilsson2012_cull_asserts_what_the_method_culls() {
    use cullproof::tools::symbolic::bbox_query::{self, Side, TemplateCull};
    use cullproof::tools::symbolic::moving_query;
    use cullproof::tools::symbolic::nilsson2012_query::cull_of;
    let mut r = rng(11);
    let (mut culled, mut kept, mut depth_wrong) = (0, 0, 0);
    for i in 0..24 {
        let side = if i % 2 == 0 { Side::XMin } else { Side::XMax };
        let moving = i % 3 == 0;
        let u = |r: &mut dyn FnMut() -> f64, lo: f64, hi: f64| (lo + (hi - lo) * r()) as f32;
        let draw = |r: &mut dyn FnMut() -> f64| -> Vec<f32> {
            if moving {
                let mut v: Vec<f32> = [(-60.0, 60.0), (-60.0, 60.0), (0.5, 8.0), (0.5, 8.0), (0.5, 4.0), (0.5, 4.0)]
                    .into_iter()
                    .map(|(lo, hi)| u(r, lo, hi))
                    .collect();
                v.push(u(r, -60.0, 60.0));
                v
            } else {
                [(-60.0, 60.0), (0.5, 8.0), (0.5, 4.0), (-60.0, 60.0)]
                    .into_iter()
                    .map(|(lo, hi)| u(r, lo, hi))
                    .collect()
            }
        };
        let build = |v: &[f32]| {
            let (tri, tile) = if moving {
                let (t, tl) = moving_query::template(&Plain, side, &std::array::from_fn(|k| v[k]));
                (t.triangle(), tl)
            } else {
                let (t, tl) = bbox_query::template(&Plain, side, &std::array::from_fn(|k| v[k]));
                (t.triangle(), tl)
            };
            (tri, Tile { x0: tile[0], y0: tile[1], x1: tile[2], y1: tile[3] })
        };
        // Every other static instance is drawn until the published method culls it (its
        // plane bound rounds below the one depth for about one depth in twenty).
        let mut v = draw(&mut r);
        let published = by_id("nilsson2012-depth").unwrap();
        for _ in 0..400 {
            let (tri, tile) = build(&v);
            if moving || i % 4 != 1 || matches!(published.setup(&tri).tile(&tile), TileResult::Empty) {
                break;
            }
            v = draw(&mut r);
        }
        let (tri, tile) = build(&v);
        for id in [
            "nilsson2012-depth",
            "nilsson2012-depth-safe",
            "broken/planted-no-up/nilsson2012-depth-safe",
            "broken/planted-no-dn/nilsson2012-depth-safe",
        ] {
            let m = by_id(id).or_else(|| cullproof::bounds::broken::parse(id)).unwrap();
            let flat = tri.q.iter().chain(&tri.r).all(|p| p[2] == tri.q[0][2] && p[3] == tri.q[0][3]);
            let (zv, wv) = (tri.q[0][2] as f64, tri.q[0][3] as f64);
            let f32_culls = match m.setup(&tri).tile(&tile) {
                TileResult::Empty => true,
                TileResult::Bounds(b) => {
                    let z = b.z.unwrap_or([f32::NEG_INFINITY, f32::INFINITY]);
                    let wrong = flat && wv > 0.0 && ((z[1] as f64) * wv < zv || (z[0] as f64) * wv > zv);
                    depth_wrong += wrong as usize;
                    wrong
                }
            };
            let smt = Smt::folding();
            let lits: Vec<String> = v.iter().map(|&x| cullproof::tools::symbolic::smt::lit(x)).collect();
            let (t, tl) = if moving {
                moving_query::template(&smt, side, &std::array::from_fn(|k| lits[k].clone()))
            } else {
                bbox_query::template(&smt, side, &std::array::from_fn(|k| lits[k].clone()))
            };
            smt.assert(&cull_of(id).unwrap().cull(&smt, side, &t, &tl));
            let run = z3::run(&smt.script(&[]), 120.0).expect("z3 runs");
            let want = if f32_culls { Answer::Sat } else { Answer::Unsat };
            assert_eq!(run.answer, want, "{id}, instance {i} {v:?}");
            if f32_culls {
                culled += 1
            } else {
                kept += 1
            }
        }
    }
    assert!(culled >= 3 && kept >= 3 && depth_wrong >= 3, "{culled} culled, {kept} kept, {depth_wrong} depth");
}

/// The conjunctions encoded in part (`lc` and `mam2012-new`: their la2011 part): a model is judged against the whole method and confirmed (Bitwuzla,
/// narrow static ranges), while an `unsat` is never counted: on a pinned instance whose
/// tile the triangle covers deep inside, `la2011` (encoded whole) gets `unsat` and `lc`
/// the same answer reported as unknown, naming the part left out.
#[test]
fn a_method_encoded_in_part_finds_counterexamples_but_proves_nothing() {
    use cullproof::tools::symbolic::family::Query;
    let ranges = "a=128:256,c=1:2,w=1.875:2,t=96:128";
    for id in ["lc", "mam2012-new"] {
        let f = family(id, Template::Static).unwrap();
        assert!(f.partial().is_some(), "{id}");
        let r = cullproof::tools::symbolic::family::parse_ranges(f.as_ref(), "--ranges", ranges).unwrap();
        let limits = Limits { timeout: 300.0, rlimit: None, jobs: 2, solvers: Solvers::BITWUZLA };
        let plan = vec![Query::free(0, r)];
        let found =
            prove(by_id(id).unwrap(), Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false).unwrap();
        let q = found.queries.iter().find(|q| q.confirmed).unwrap_or_else(|| panic!("{id}: {}", found.render()));
        let (tri, tile) = f.instance(0, q.inputs.as_ref().unwrap());
        assert!(matches!(by_id(id).unwrap().setup(&tri).tile(&tile), TileResult::Empty), "{id}");
    }
    // Pinned: a = 200, c = 1.5, w = 1.875, the tile 10 px inside the left edge.
    let v = [200.0f32, 1.5, 1.875, (200.0 - 1.5) / 1.875 + 10.0];
    let pinned = Query { side: 0, ranges: v.iter().map(|&x| [x, x.next_up()]).collect(), fixed: v.map(Some).to_vec() };
    let limits = Limits { timeout: 120.0, rlimit: None, jobs: 1, solvers: Solvers::Z3 };
    for (id, want) in [("la2011", Answer::Unsat), ("lc", Answer::Unknown), ("mam2012-new", Answer::Unknown)] {
        let r = prove(
            by_id(id).unwrap(),
            Template::Static,
            Strategy::Whole,
            0,
            std::slice::from_ref(&pinned),
            limits,
            None,
            None,
            false,
        )
        .unwrap();
        assert_eq!(r.queries[0].answer, want, "{id}: {}", r.render());
        assert_eq!(r.queries[0].partial_unsat.is_some(), want == Answer::Unknown, "{id}: {}", r.render());
        assert_eq!(r.render().contains("every query unsat"), want == Answer::Unsat, "{id}: {}", r.render());
        if want == Answer::Unknown {
            assert!(r.render().contains("only part of the method is encoded"), "{id}: {}", r.render());
        }
    }
}

/// On the static template (narrow ranges, every input free, Bitwuzla), the search finds
/// an f32 failure of nilsson2012-depth on a screen-parallel triangle (a culled tile or a
/// depth interval below the one depth), and each planted slip
/// of nilsson2012-depth-safe (one side's outward steps dropped) as a depth interval that
/// misses the covered samples' depth: `z max` for the dropped upward steps, `z min` for
/// the dropped downward ones, each confirmed by the exact judge.
#[test]
fn the_static_template_finds_nilsson2012_depth_and_its_planted_slips() {
    let ranges = "a=128:256,c=1:2,w=1.875:2,t=96:128";
    let limits = Limits { timeout: 600.0, rlimit: None, jobs: 1, solvers: Solvers::BITWUZLA };
    for (id, kinds) in [
        ("nilsson2012-depth", &["tile culled", "z max", "z min"][..]),
        ("broken/planted-no-up/nilsson2012-depth-safe", &["z max"]),
        ("broken/planted-no-dn/nilsson2012-depth-safe", &["z min"]),
    ] {
        let m = by_id(id).or_else(|| cullproof::bounds::broken::parse(id)).unwrap();
        let f = family(id, Template::Static).unwrap();
        let r = cullproof::tools::symbolic::family::parse_ranges(f.as_ref(), "--ranges", ranges).unwrap();
        let plan = vec![cullproof::tools::symbolic::family::Query::free(0, r)];
        let found = prove(m, Template::Static, Strategy::Whole, 0, &plan, limits, None, None, false).unwrap();
        let q = found.queries.iter().find(|q| q.confirmed).unwrap_or_else(|| panic!("{id}: {}", found.render()));
        let judged = q.judged.clone().unwrap_or_default();
        assert!(kinds.iter().any(|k| judged == format!("violation ({k})")), "{id}: {}", found.render());
    }
}

/// The static template's exact side (the footprint reaches the tile: the near edge
/// before the tile, the far edge at the tile's nearest row after it), attacked with the
/// tile 0.3 px inside or outside each edge: the SMT assertion is sat exactly where the
/// exact judge finds a covered sample and unsat exactly where it certifies the tile empty.
/// The far edge is the hypotenuse at row 8 moved by the lens in x and y, not the far
/// vertex, which let a solver place the tile 8 px beyond the triangle (a model the judge
/// found empty).
#[test]
fn the_static_templates_exact_side_agrees_with_the_judge_at_both_edges() {
    use cullproof::tools::symbolic::bbox_query::{template, Side};
    let f = family("bbox", Template::Static).unwrap();
    let mut r = rng(23);
    let (mut reached, mut empty) = (0, 0);
    for i in 0..32 {
        let side = if i % 2 == 0 { Side::XMin } else { Side::XMax };
        let sgn = if side == Side::XMin { 1.0 } else { -1.0 };
        let u = |r: &mut dyn FnMut() -> f64, lo: f64, hi: f64| (lo + (hi - lo) * r()) as f32;
        // c / w <= 4: the lens's vertical shift keeps row 8 inside the triangle, where the
        // far bound is exact
        let (a, c, w) = (u(&mut r, -60.0, 60.0), u(&mut r, 0.5, 2.0), u(&mut r, 0.5, 4.0));
        let inside = i % 4 < 2;
        let d = if inside { 0.3 } else { -0.3 };
        let t = if i % 8 < 4 {
            // the near edge: x-min reaches when (a - c) / w < t, x-max when (a + c) / w > t
            ((a as f64 - sgn * c as f64) / w as f64 + sgn * d) as f32
        } else {
            // the far edge at row 8, the lens moving it by (1 + s) c / w towards the tile
            let far = if side == Side::XMin { a + 64.0 * w } else { a - 64.0 * w };
            let (far, a64, c64, w64) = (far as f64, a as f64, c as f64, w as f64);
            let tilt = c64 * (far - a64).abs() / (8.0 * w64);
            let e = (7.0 * far + a64 + sgn * (8.0 * c64 + tilt)) / (8.0 * w64);
            // x-min: x0 = t - 1 reaches when x0 < e; x-max: x1 = t + 1 when x1 > e
            (e - sgn * d + sgn) as f32
        };
        let v = [a, c, w, t];
        let (tri, tile) = template(&Plain, side, &v);
        let pinned = (tri.triangle(), Tile { x0: tile[0], y0: tile[1], x1: tile[2], y1: tile[3] });
        let got = reach_agrees_with_judge(i, &v, pinned, |smt, lits| f.assert_reached(smt, i % 2, lits));
        reached += (got == Some(true)) as usize;
        empty += (got == Some(false)) as usize;
        assert_eq!(got, Some(inside), "instance {i} {v:?}: the tile is 0.3 px from an edge");
    }
    assert!(reached >= 12 && empty >= 12, "{reached} reached, {empty} empty");
}

/// Judge the template tile of pinned inputs `v` exactly (with a method that culls
/// everything, so a violation is a covered sample) and have z3 decide the template's
/// reach assertion (`assert_reach`) on the same inputs: sat where the judge finds a
/// covered sample, unsat where it certifies the tile empty. Returns whether the tile is
/// reached (`None` when the judge left it undecided).
fn reach_agrees_with_judge(
    i: usize,
    v: &[f32],
    (tri, tile): (Triangle, Tile),
    assert_reach: impl Fn(&Smt, &[String]),
) -> Option<bool> {
    let cfg = cullproof::gate::CheckConfig::default_with(vec![&CullAll]);
    let m = cullproof::bounds::shared(&CullAll);
    let case = cullproof::model::Case { triangle: tri, lens: None };
    let (js, _) = cullproof::gate::judge(&cfg, std::slice::from_ref(&m), &case, &tile, i as u64);
    let j = &js[0];
    let smt = Smt::folding();
    let lits: Vec<String> = v.iter().map(|&x| cullproof::tools::symbolic::smt::lit(x)).collect();
    assert_reach(&smt, &lits);
    let run = z3::run(&smt.script(&[]), 60.0).expect("z3 runs");
    match (j.violation.is_some(), j.verdict() == cullproof::judge::Verdict::Proven) {
        (true, _) => {
            assert_eq!(run.answer, Answer::Sat, "instance {i} {v:?}: the judge finds a covered sample");
            Some(true)
        }
        (false, true) => {
            assert_eq!(run.answer, Answer::Unsat, "instance {i} {v:?}: the judge certifies the tile empty");
            Some(false)
        }
        _ => None,
    }
}
