//! Checks that the scripts are about the code: a changed constant, a changed padding
//! formula or a changed step primitive without a changed proof is an error here.
//!
//! - [`constants`]: every constant a script declares that the code also has, parsed
//!   from the script and compared with the code's value.
//! - [`bbox_formula`]: `bbox-safe`'s setup recomputed from the script's constants
//!   (`PAD`, `FLOOR`, `STEPS`) with the script's formula, bit for bit against the code's
//!   `aabb_safe` on random triangles of every scale.
//! - [`wu_formula`]: `wu2013-safe`'s padded lines and their evaluation recomputed from
//!   the script's constants and formula, bit for bit against the code's.
//! - [`primitives_script`]: a ground z3 script asserting that the prelude's `nd`, `nu`
//!   and `rn` are Rust's `f32::next_down`, `f32::next_up` and rounding to nearest on
//!   values from every range (zeros, subnormals, MAX, infinities, ties); it is proven
//!   (unsat) exactly when every one agrees.

use crate::bounds::proofs::{Script, BBOX_PAD, LB_PAD, WU_PAD};
use crate::bounds::{bbox, lb2011, wu2013, SampleConstraint};
use crate::model::{Sample, Triangle};

/// A constant as a script declares it (`NAME = value;` at the start of a line), parsed
/// as a Gappa number (`4`, `1b-21` = 2^-21, `0.5`).
pub fn script_constant(script: &Script, name: &str) -> Result<f64, String> {
    constant_in(script.file, script.text, name)
}

/// [`script_constant`] in the text `text` of the script named `file`.
pub fn constant_in(file: &str, text: &str, name: &str) -> Result<f64, String> {
    let line = text
        .lines()
        .find(|l| l.split('=').next().is_some_and(|n| n.trim() == name) && !l.trim_start().starts_with('#'))
        .ok_or_else(|| format!("{file}: no line `{name} = ...;`"))?;
    let value = line.split_once('=').map(|(_, v)| v.trim().trim_end_matches(';').trim()).unwrap_or("");
    parse_gappa_number(value).ok_or_else(|| format!("{file}: `{name} = {value}`: not a number"))
}

/// `m`, `mbe` (m 2^e) or a decimal.
fn parse_gappa_number(s: &str) -> Option<f64> {
    match s.split_once('b') {
        Some((m, e)) => Some(m.parse::<f64>().ok()? * 2f64.powi(e.parse::<i32>().ok()?)),
        None => s.parse().ok(),
    }
}

/// The script with `NAME = value;` replaced (how the tests show that a changed constant
/// breaks a proof).
pub fn with_constant(script: &Script, name: &str, value: &str) -> String {
    script
        .text
        .lines()
        .map(|l| {
            if l.split('=').next().is_some_and(|n| n.trim() == name) && !l.trim_start().starts_with('#') {
                format!("{name} = {value};")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every constant shared by a script and the code: (script, name, script value, code value).
pub fn shared_constants() -> Vec<(&'static Script, &'static str, f64)> {
    vec![
        (&BBOX_PAD, "PAD", bbox::PAD as f64),
        (&BBOX_PAD, "FLOOR", bbox::FLOOR as f64),
        (&WU_PAD, "PAD", wu2013::PAD as f64),
        (&WU_PAD, "FLOOR", wu2013::FLOOR as f64),
        (&WU_PAD, "LIMIT", wu2013::LINE_LIMIT as f64),
        (&LB_PAD, "PAD", lb2011::PAD as f64),
        (&LB_PAD, "FLOOR", lb2011::FLOOR as f64),
        (&LB_PAD, "LIMIT", lb2011::LIMIT as f64),
    ]
}

/// The shared constants agree (the f32 facts the lemmas use as well).
pub fn constants() -> Result<(), String> {
    let mut errs = Vec::new();
    for (s, name, code) in shared_constants() {
        match script_constant(s, name) {
            Ok(v) if v == code => {}
            Ok(v) => errs.push(format!("{}: {name} = {v:e} but the code has {code:e}", s.file)),
            Err(e) => errs.push(e),
        }
    }
    for (name, v, fact) in
        [("U", 2f64.powi(-23), f32::EPSILON as f64), ("E", 2f64.powi(-149), f32::from_bits(1) as f64)]
    {
        match script_constant(&BBOX_PAD, name) {
            Ok(s) if s == v && v == fact => {}
            Ok(s) => errs.push(format!("{}: {name} = {s:e}, the f32 fact is {fact:e}", BBOX_PAD.file)),
            Err(e) => errs.push(e),
        }
    }
    if errs.is_empty() {
        Ok(())
    } else {
        Err(errs.join("; "))
    }
}

/// `bbox-safe`'s box as `bbox_safe.g` describes it, with the script's constants.
fn bbox_box(tri: &Triangle, pad: f32, floor: f32, steps: usize) -> Option<[f32; 4]> {
    let ends = [(&tri.q, &tri.c0), (&tri.r, &tri.c1)];
    if ends.iter().any(|(p, _)| p.iter().any(|v| v[3] <= 0.0 || v[3].is_nan())) {
        return None;
    }
    let mut bx = [f32::NAN; 4];
    for (axis, scale) in [(0usize, 1.0f32), (1, tri.k)] {
        let (mut lo, mut hi, mut finite) = (f32::INFINITY, f32::NEG_INFINITY, true);
        for (p, c) in ends {
            for i in 0..3 {
                let (a, w, s) = (p[i][axis], p[i][3], scale * c[i]);
                for n in [a - s, a + s] {
                    let q = n / w;
                    let pd = ((s.abs() + n.abs() + floor) / w) * pad;
                    let (mut l, mut h) = (q - pd, q + pd);
                    for _ in 0..steps {
                        (l, h) = (l.next_down(), h.next_up());
                    }
                    finite &= l.is_finite() && h.is_finite();
                    (lo, hi) = (lo.min(l), hi.max(h));
                }
            }
        }
        if finite {
            bx[2 * axis] = lo;
            bx[2 * axis + 1] = hi;
        }
    }
    Some(bx)
}

/// Random triangles of every scale (subnormal to 1e30 coordinates, w over twenty binades).
fn random_triangles(n: usize) -> impl Iterator<Item = Triangle> {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(move |i| {
        let scale = [1e-40f64, 1e-20, 1e-3, 1.0, 1e3, 1e6, 1e15, 1e30][i % 8];
        let mut v = || ((rnd() - 0.5) * 2.0 * scale) as f32;
        let mut tri = Triangle { q: [[0.0; 4]; 3], r: [[0.0; 4]; 3], c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
            (p[0], p[1], p[2]) = (v(), v(), 0.5);
        }
        for c in tri.c0.iter_mut().chain(tri.c1.iter_mut()) {
            *c = v();
        }
        for p in tri.q.iter_mut().chain(tri.r.iter_mut()) {
            p[3] = (rnd() * 4.0f64.powi((rnd() * 20.0) as i32 - 10)) as f32 + f32::MIN_POSITIVE;
        }
        tri.k = (0.25 + rnd() * 4.0) as f32;
        tri
    })
}

/// `bbox-safe`'s setup is the script's formula with the script's constants: bit for bit
/// on `n` random triangles.
pub fn bbox_formula(n: usize) -> Result<(), String> {
    let get = |name| script_constant(&BBOX_PAD, name);
    bbox_formula_with(get("PAD")?, get("FLOOR")?, get("STEPS")?, n)
}

/// [`bbox_formula`] with these constants in place of the script's.
pub fn bbox_formula_with(pad: f64, floor: f64, steps: f64, n: usize) -> Result<(), String> {
    let (pad, floor) = (pad as f32, floor as f32);
    if steps.fract() != 0.0 || !(1.0..=64.0).contains(&steps) {
        return Err(format!("{}: STEPS = {steps} is not a count", BBOX_PAD.file));
    }
    for tri in random_triangles(n) {
        let code = bbox::aabb_safe(&tri);
        let script = bbox_box(&tri, pad, floor, steps as usize);
        let same = match (code, script) {
            (None, None) => true,
            (Some(a), Some(b)) => {
                a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
            }
            _ => false,
        };
        if !same {
            return Err(format!(
                "bbox-safe's setup differs from {} (PAD {pad:e}, FLOOR {floor:e}, STEPS {steps}): code {code:?}, \
                 script {script:?} for {tri:?}",
                BBOX_PAD.file
            ));
        }
    }
    Ok(())
}

/// `wu2013-safe`'s padded line through `(-1, e_left)`, `(1, e_right)` as `wu2013_safe.g`
/// describes it: `(a, b')`.
fn wu_line(upper: bool, e_left: f32, e_right: f32, pad: f32, floor: f32) -> (f32, f32) {
    let a = 0.5 * e_right - 0.5 * e_left;
    let b = if upper {
        (e_left + a).next_up().max((e_right - a).next_up())
    } else {
        (e_left + a).next_down().min((e_right - a).next_down())
    };
    let p = (a.abs() + a.abs() + b.abs() + floor) * pad;
    (a, if upper { (b + p).next_up() } else { (b - p).next_down() })
}

/// `wu2013-safe`'s lines (`safe_line`) and their evaluation (`TimeLine::eval`) are the
/// script's formula with the script's constants: bit for bit on `n` random lines.
pub fn wu_formula(n: usize) -> Result<(), String> {
    let get = |name| script_constant(&WU_PAD, name);
    wu_formula_with(get("PAD")?, get("FLOOR")?, n)
}

/// [`wu_formula`] with these constants in place of the script's.
pub fn wu_formula_with(pad: f64, floor: f64, n: usize) -> Result<(), String> {
    let (pad, floor) = (pad as f32, floor as f32);
    let mut seed = 0x5851_f42d_4c95_7f2du64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..n {
        let scale = [1e-38f64, 1e-20, 1e-3, 1.0, 1e3, 1e15, 1e29][i % 7];
        let (el, er) = (((rnd() - 0.5) * scale) as f32, ((rnd() - 0.5) * scale) as f32);
        let (l, t) = ((rnd() * 2.0 - 1.0) as f32, rnd() as f32);
        for upper in [true, false] {
            let Some(line) = wu2013::safe_line(wu2013::Lens::U, upper, el, er) else {
                return Err(format!("wu2013-safe: no line through ({el:e}, {er:e})"));
            };
            let (a, b) = wu_line(upper, el, er, pad, floor);
            let s = Sample { x: 0.0, y: 0.0, u: l, v: 0.0, t };
            let want = if upper { (a * l + b) - t } else { t - (a * l + b) };
            let got = line.eval(&s);
            if (line.a, line.b) != (a, b) || got.to_bits() != want.to_bits() {
                return Err(format!(
                    "wu2013-safe's line differs from {} (PAD {pad:e}, FLOOR {floor:e}): code a {} b {} eval {got:e}, \
                     script a {a} b {b} eval {want:e} (e_left {el:e}, e_right {er:e}, upper {upper})",
                    WU_PAD.file, line.a, line.b
                ));
            }
        }
    }
    Ok(())
}

/// A ground z3 script (prelude included) whose answer is `unsat` iff the prelude's `nd`,
/// `nu` and `rn` agree with Rust's `next_down`, `next_up` and rounding of an f64 to
/// nearest on every listed value.
pub fn primitives_script() -> String {
    let mut bits: Vec<u32> = vec![
        0x0000_0000,
        0x8000_0000,
        0x0000_0001,
        0x8000_0001,
        0x007f_ffff,
        0x0080_0000,
        0x8080_0000,
        0x3f80_0000,
        0xbf80_0000,
        0x3f7f_ffff,
        0x7f7f_ffff,
        0xff7f_ffff,
        0x7f80_0000,
        0xff80_0000,
    ];
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    while bits.len() < 64 {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let b = (seed >> 32) as u32;
        if !f32::from_bits(b).is_nan() {
            bits.push(b);
        }
    }
    let max = f32::MAX as f64;
    let mut wides: Vec<f64> = vec![
        1.0 + 2f64.powi(-24),
        1.0 + 3.0 * 2f64.powi(-24),
        -(1.0 + 2f64.powi(-24)),
        2f64.powi(-150),
        3.0 * 2f64.powi(-150),
        -(2f64.powi(-151)),
        max + 2f64.powi(103),
        max + 2f64.powi(102),
        -(max + 2f64.powi(103)),
        1e-300,
        1e300,
    ];
    wides.extend(bits.iter().map(|&b| f32::from_bits(b) as f64 * (1.0 + 2f64.powi(-30))));
    let mut conj = Vec::new();
    for b in bits {
        let x = f32::from_bits(b);
        conj.push(format!("(= (nd #x{b:08x}) #x{:08x})", x.next_down().to_bits()));
        conj.push(format!("(= (nu #x{b:08x}) #x{:08x})", x.next_up().to_bits()));
    }
    for w in wides.into_iter().filter(|w| !w.is_nan()) {
        conj.push(format!("(= (rn ((_ to_fp 11 53) #x{:016x})) (f #x{:08x}))", w.to_bits(), (w as f32).to_bits()));
    }
    format!(
        "{}; The prelude's primitives against Rust's, on listed values (generated by \
         src/tools/proofs/check.rs).\n(assert (not (and\n  {}\n)))\n(check-sat)\n",
        crate::bounds::proofs::PRELUDE,
        conj.join("\n  ")
    )
}
