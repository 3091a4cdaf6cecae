//! Proofs for all inputs: which `-safe` variants are proven conservative for every f32
//! input in stated ranges, by which scripts, and what the scripts depend on in the code
//! (`docs/proofs.md` says what is proven mechanically and what by argument).
//!
//! The scripts sit beside this file and are compiled into the binary:
//! - `prelude.smt2`: the shared definitions of the z3 lemmas (IEEE binary32 `F`, the
//!   wider binary64 `W`, Rust's `next_down` / `next_up` on the bits of an f32);
//! - `step.smt2`, `monotone.smt2`, `gap.smt2`, `ulp.smt2`: the rounding lemmas STEP,
//!   MONO, GAP and ULP, for every value of `W` (pure floating-point and bit-vector
//!   theory; extended to every real by the argument of `docs/proofs.md`);
//! - `bbox_safe.g`: Gappa, `bbox-safe`'s pad against the error of its corner value;
//! - `wu2013_safe.g`: Gappa, `wu2013-safe`'s line pad against the error of the line's
//!   per-sample evaluation;
//! - `lb2011_safe.g`: Gappa, `lb2011-safe`'s patch pad against the error of the patch's
//!   coefficients and its per-sample evaluation;
//! - `enclosure_rules.smt2`: z3 in real arithmetic, the rules of the enclosure check and
//!   the lemmas the code pins.
//!
//! - [`crate::tools::proofs::enclosure`] (with the command): for every variant of
//!   [`crate::tools::proofs::enclosure::CHECKED`] (`bbox-safe`, `la2011-safe`,
//!   `mam2012-safe`, `nilsson2012-depth-safe`, `wu2013-safe`, `gdam2010-safe`,
//!   `lb2011-safe`, `lc-safe`), the composition over the method's own f32 code, for
//!   every input.
//! - [`crate::tools::proofs::composition`] (with the command, built on the symbolic search):
//!   for `la2011-safe`, the composition over the method's own f32 code, as SMT queries
//!   on a template's ranges.
//!
//! [`VARIANTS`] declares, per variant, the input ranges, the scripts, and the code
//! facts the scripts assume; [`crate::tools::proofs::check`] compares the scripts' constants and formulas with
//! the code, [`crate::tools::proofs::run`] runs a script with its tool. `cullproof proofs`
//! ([`crate::cli::proofs`]) and `tests/proofs.rs` run them all.

use serde::Serialize;

/// The tool a script is written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Tool {
    /// `z3` (SMT-LIB2, QF_BVFP): a lemma is proven when z3 answers `unsat`.
    Z3,
    /// `gappa`: a script is proven when gappa exits 0.
    Gappa,
}

impl Tool {
    /// The executable looked up on the PATH.
    pub fn binary(self) -> &'static str {
        match self {
            Tool::Z3 => "z3",
            Tool::Gappa => "gappa",
        }
    }
    /// How to get the tool (the message of a missing tool).
    pub fn install(self) -> &'static str {
        match self {
            Tool::Z3 => "install z3 (Debian/Ubuntu: `apt-get install z3`, 4.8.12 or later; `.ci/run` does)",
            Tool::Gappa => "install gappa (Debian/Ubuntu: `apt-get install gappa`, 1.4.1 or later; `.ci/run` does)",
        }
    }
}

/// One proof script.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Script {
    /// Short name (`STEP`, `bbox-safe pad`).
    pub name: &'static str,
    /// File name in `src/bounds/proofs/`.
    pub file: &'static str,
    pub tool: Tool,
    /// What it proves, in one sentence.
    pub claim: &'static str,
    /// z3 scripts: whether the prelude (floating-point definitions) comes first; the
    /// real-arithmetic rules of the enclosure check go without it.
    #[serde(skip)]
    pub prelude: bool,
    #[serde(skip)]
    pub text: &'static str,
}

impl Script {
    /// The input given to the tool: z3 scripts get the prelude first.
    pub fn input(&self) -> String {
        match self.tool {
            Tool::Z3 if self.prelude => format!("{PRELUDE}{}", self.text),
            Tool::Z3 => self.text.to_string(),
            Tool::Gappa => self.text.to_string(),
        }
    }
}

/// The shared definitions of the z3 lemmas.
pub const PRELUDE: &str = include_str!("prelude.smt2");

/// Lemma STEP (z3).
pub const STEP: Script = Script {
    name: "STEP",
    file: "step.smt2",
    tool: Tool::Z3,
    claim: "a value rounded to nearest (or any nearest f32, ties either way), stepped one f32 \
            outward, encloses what was rounded: next_down(r) <= z <= next_up(r), subnormals, \
            zeros and overflow included",
    prelude: true,
    text: include_str!("step.smt2"),
};

/// Lemma MONO (z3).
pub const MONO: Script = Script {
    name: "MONO",
    file: "monotone.smt2",
    tool: Tool::Z3,
    claim: "rounding to nearest is monotone (so the f32 difference of f32 values x >= y is >= 0)",
    prelude: true,
    text: include_str!("monotone.smt2"),
};

/// Lemma GAP (z3).
pub const GAP: Script = Script {
    name: "GAP",
    file: "gap.smt2",
    tool: Tool::Z3,
    claim: "a step moves a finite f32 by at least 2^-149",
    prelude: true,
    text: include_str!("gap.smt2"),
};

/// Lemma ULP (z3).
pub const ULP: Script = Script {
    name: "ULP",
    file: "ulp.smt2",
    tool: Tool::Z3,
    claim: "the neighbours of a finite f32 r are within 2^-23 |r| + 2^-149 of it (with STEP: \
            every finite rounding errs by at most that)",
    prelude: true,
    text: include_str!("ulp.smt2"),
};

/// bbox-safe's pad (Gappa).
pub const BBOX_PAD: Script = Script {
    name: "bbox-safe pad",
    file: "bbox_safe.g",
    tool: Tool::Gappa,
    claim: "the pad 2^-21 (|s| + |n| + 2^-120) / w and four steps exceed the error of the \
            corner value (a +- k c) / w computed in f32, for every finite input with w > 0",
    prelude: false,
    text: include_str!("bbox_safe.g"),
};

/// wu2013-safe's line pad (Gappa).
pub const WU_PAD: Script = Script {
    name: "wu2013-safe pad",
    file: "wu2013_safe.g",
    tool: Tool::Gappa,
    claim: "the line pad 2^-21 (2 |a| + |b| + 2^-100) and one step keep the f32 evaluation \
            RN(RN(a l) + b') at or above the exact line a l + b for every |l| <= 1, and finite for \
            endpoints within 2^100",
    prelude: false,
    text: include_str!("wu2013_safe.g"),
};

/// lb2011-safe's patch pad (Gappa).
pub const LB_PAD: Script = Script {
    name: "lb2011-safe pad",
    file: "lb2011_safe.g",
    tool: Tool::Gappa,
    claim: "the pad 2^-18 max |g| + 2^-140 on a patch's constant term and one step keep its f32 \
            evaluation at or above the exact patch through its corner values g for every |l| <= 1 and \
            t in [0, 1], and finite for max |g| < 2^120",
    prelude: false,
    text: include_str!("lb2011_safe.g"),
};

/// The rules of the enclosure check, and the lemmas of its pins (z3, real arithmetic).
pub const RULES: Script = Script {
    name: "enclosure rules",
    file: "enclosure_rules.smt2",
    tool: Tool::Z3,
    claim: "how ends of intervals combine (sums, products by a factor of known sign, products of \
            ends of one sign, quotients by a divisor of one strict sign, min/max, max(|lo|, |hi|), \
            signs of ends, comparisons of ends, a fused multiply-add of an end by an exact factor of known sign) and \
            the lemmas pinned in the code (la2011's chord through lower ends, nilsson2012-depth's w bound from a plane, \
            mam2012-safe's and wu2013-safe's lens ranges, patches and lines, lb2011-safe's patch through corner \
            values at or above the exact ones), in real arithmetic",
    prelude: false,
    text: include_str!("enclosure_rules.smt2"),
};

/// Every script, each run once.
pub const SCRIPTS: &[Script] = &[STEP, MONO, GAP, ULP, BBOX_PAD, WU_PAD, LB_PAD, RULES];

/// An input range of a claim.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Range {
    /// The inputs it is about.
    pub inputs: &'static str,
    /// The range.
    pub range: &'static str,
}

/// How much of a proof for all inputs a machine checks (see
/// [`crate::gate::strength`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Level {
    /// Every step, the composition over the method's code included.
    MachineChecked,
    /// The rounding lemmas; their composition over the code is an argument.
    LemmasChecked,
}

impl Level {
    /// The words used in tables, JSON and the README.
    pub fn name(self) -> &'static str {
        match self {
            Level::MachineChecked => "machine-checked for all inputs in ranges",
            Level::LemmasChecked => "rounding lemmas checked, composition argued",
        }
    }
}

/// A `-safe` variant proven for all inputs in its ranges.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Variant {
    /// The method id.
    pub id: &'static str,
    /// The claim's input ranges (outside them: what the method answers, by code inspection).
    pub ranges: &'static [Range],
    /// The scripts the proof uses (names in [`SCRIPTS`]).
    pub scripts: &'static [&'static str],
    /// What the scripts prove for this variant.
    pub mechanical: &'static str,
    /// What the proof takes from an argument (`docs/proofs.md` and the method's file).
    pub by_argument: &'static str,
    /// How much of it a machine checks.
    pub level: Level,
}

/// Every finite f32 input; non-finite input: the full domain.
const ALL_FINITE: &[Range] = &[
    Range {
        inputs: "vertex x, y, z, w at both shutter ends, CoC c0, c1, aspect k, tile edges",
        range: "every finite f32 value (subnormals, zeros of either sign, up to +-MAX)",
    },
    Range { inputs: "any non-finite input", range: "answered with the full domain (code inspection)" },
];

/// The variants with a proof, in the registry's order.
pub const VARIANTS: &[Variant] = &[
    Variant {
        id: "bbox-safe",
        ranges: &[
            Range {
                inputs: "vertex x, y at both shutter ends, CoC c0, c1, aspect k, tile edges",
                range: "every finite f32 value",
            },
            Range { inputs: "vertex w at both shutter ends", range: "every finite f32 value > 0 (w <= 0: disabled)" },
            Range { inputs: "any non-finite input or intermediate", range: "that axis never culls (code inspection)" },
        ],
        scripts: &["STEP", "GAP", "ULP", "MONO", "bbox-safe pad", "enclosure rules"],
        mechanical: "the error model |RN(z) - z| <= 2^-23 |RN(z)| + 2^-149 (STEP, ULP), the four steps \
                     (STEP, GAP), and the inequality that the pad and the steps cover the corner value's \
                     error for every B = (|s| + |n|) / w >= 0 and w > 0 (bbox_safe.g, with the code's PAD, \
                     FLOOR and step count); the composition over the method's own f32 code for every \
                     input: the enclosure check traces the box and the tile reject, finds every corner \
                     the code computes to be bbox_safe.g's formula with the script's constants (so the \
                     lemma applies), and the reject to imply that the exact box misses the tile (enclosure \
                     rules)",
        by_argument: "collecting the error terms into g1 B + g2 / w + g3 (docs/proofs.md); the exact box is \
                      the hull of the exact corner values (bbox.rs derivation)",
        level: Level::MachineChecked,
    },
    Variant {
        id: "la2011-safe",
        ranges: ALL_FINITE,
        scripts: &["STEP", "MONO", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP), rounding is \
                     monotone (MONO); the composition over the method's own f32 code for every input: the \
                     enclosure check traces the tile answer and finds every end of t, u and v an end of \
                     its side of its exact value, and NaN-free, by rules z3 proves in real arithmetic \
                     (enclosure rules, with the chord lemma its pins use); on the template ranges, also \
                     the SMT query per side (no input culls a tile the exact footprint reaches)",
        by_argument: "the real-arithmetic derivation in la2011.rs (the exact values of the ends bound the \
                      covered samples), and that each branch the f32 code takes on its ends is one the \
                      exact values allow (fallbacks give the full domain)",
        level: Level::MachineChecked,
    },
    Variant {
        id: "lb2011-safe",
        ranges: &[
            Range {
                inputs: "vertex x, y, w at both shutter ends, CoC c0, c1, aspect k, tile edges",
                range: "every finite f32 value (subnormals, zeros of either sign, up to +-MAX)",
            },
            Range {
                inputs: "sample lens coordinate u, v and time t (the patches' l, t)",
                range: "|l| <= 1, t in [0, 1] (the model's lens and shutter)",
            },
            Range {
                inputs: "any non-finite input or corner value",
                range: "that axis gives nothing: no range, no patch (code inspection)",
            },
        ],
        scripts: &["STEP", "ULP", "lb2011-safe pad", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP, for the fused \
                     multiply-adds, the corner sums, the chords' crossings and the lens ranges); the error \
                     model (STEP, ULP) and the inequality that a patch's pad covers the error of its \
                     coefficients and of its per-sample evaluation for |l| <= 1, t in [0, 1] with its \
                     corner values within the code's limit, which keeps the evaluation finite \
                     (lb2011_safe.g, with the code's PAD, FLOOR and LIMIT); the composition over the \
                     method's own f32 code for every input: the enclosure check traces the setup and the \
                     tile answer and finds every end of t, u and v an end of its side of its exact value, \
                     and NaN-free, the tile reject to imply its exact counterpart, and each patch's cull \
                     to put the sample where the exact patch through its pinned corner values is < 0, \
                     with each patch's f32 value found to be lb2011_safe.g's formula with the script's \
                     constants where the code tests the script's limit (so the lemma applies), by rules \
                     z3 proves in real arithmetic (enclosure rules, with the lemmas of the corners and \
                     the chord)",
        by_argument: "the real-arithmetic derivation in lb2011.rs (a bilinear patch through corner values at \
                      or above -min (max) of the clipless dual-space quantities over the tile's columns is \
                      at or above -min (max) on the whole lens-time square, so a sample it culls is not \
                      covered; the ranges keep every (l, t) where it is >= 0), and that each branch the \
                      f32 code takes on its ends is one the exact values allow (fallbacks give the full \
                      domain)",
        level: Level::MachineChecked,
    },
    Variant {
        id: "lc-safe",
        ranges: &[
            Range {
                inputs: "vertex x, y, z, w at both shutter ends, CoC c0, c1, aspect k, tile edges",
                range: "every finite f32 value (subnormals, zeros of either sign, up to +-MAX)",
            },
            Range {
                inputs: "sample lens coordinate u, v and time t (the patches' l, t)",
                range: "|l| <= 1, t in [0, 1] (the model's lens and shutter)",
            },
            Range {
                inputs: "any non-finite input",
                range: "la2011-safe's part gives the full domain, lb2011-safe's that axis nothing (code inspection)",
            },
        ],
        scripts: &["STEP", "MONO", "ULP", "lb2011-safe pad", "enclosure rules"],
        mechanical: "what la2011-safe's and lb2011-safe's proofs check (STEP, MONO, ULP, lb2011_safe.g); \
                     the composition over the method's own f32 code for every input: the enclosure check \
                     traces both parts' tile answers for one triangle and tile and their meet (the code's \
                     own `meet_of`, as `TileResult::and` meets them) and finds every end of the met t, u \
                     and v an end of its side of its exact value, and NaN-free, the tile reject (either \
                     part's, or an empty met range) to imply its exact counterpart, and each of \
                     lb2011-safe's patch culls to put the sample where the exact patch through its \
                     pinned corner values is < 0 (enclosure rules)",
        by_argument: "the derivations of la2011.rs and lb2011.rs; that `Conjunction::combine` is Empty when \
                      a part is Empty and otherwise meets the parts' intervals with `meet_of` and keeps \
                      both parts' constraints (code inspection); and that each branch the f32 code takes on \
                      its ends is one the exact values allow",
        level: Level::MachineChecked,
    },
    Variant {
        id: "mam2012-safe",
        ranges: ALL_FINITE,
        scripts: &["STEP", "MONO", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP), rounding is \
                     monotone (MONO: a line's intercept moved out by its pad, the sign of a line's last \
                     rounded difference); the composition over the method's own f32 code for every \
                     input: the enclosure check traces the setup and the tile answer and finds every end \
                     of u and v an end of its side of its exact value, and NaN-free, the tile reject to \
                     imply its exact counterpart, and each per-sample line's cull (for t in [0, 1]) to put \
                     the sample beyond the line through its ends' exact values, by rules z3 proves in real \
                     arithmetic (enclosure rules: the four end products or quotients, and the lemmas of the \
                     patch domain, its corners, the tile's columns, the patch read from either corner and \
                     the lines that its pins use)",
        by_argument: "the real-arithmetic derivation in mam2012.rs (Figure 5's lines bound each u_j, the \
                      bilinear patch through corner values below them bounds every covered u over the \
                      screen extent), and that each branch the f32 code takes on its ends is one the \
                      exact values allow (fallbacks give the full domain)",
        level: Level::MachineChecked,
    },
    Variant {
        id: "wu2013-safe",
        ranges: &[
            Range {
                inputs: "vertex x, y, z, w at both shutter ends, CoC c0, c1, aspect k, tile edges",
                range: "every finite f32 value",
            },
            Range { inputs: "sample lens coordinate u, v (the lines' l)", range: "[-1, 1] (the model's lens)" },
            Range { inputs: "any non-finite input", range: "answered with the full domain (code inspection)" },
        ],
        scripts: &["STEP", "MONO", "GAP", "ULP", "wu2013-safe pad", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP, GAP); the error \
                     model (STEP, ULP) and the inequality that the lines' pad covers their f32 evaluation \
                     for every |l| <= 1 with the endpoints within the code's limit, which keeps every \
                     value of the evaluation finite (wu2013_safe.g, with the code's PAD, FLOOR and \
                     LIMIT); the composition over the method's own f32 code for every input: the \
                     enclosure check traces the setup and the tile answer and finds every end of u, v \
                     and t an end of its side of its exact value, and NaN-free, the tile reject to imply \
                     its exact counterpart, and each per-sample line's cull (|l| <= 1) to put the sample \
                     beyond the line through its pinned intercept, with each line's f32 value found to be \
                     wu2013_safe.g's formula with the script's constants where the code tests the \
                     script's limit (so the lemma applies), by rules z3 proves in real arithmetic \
                     (enclosure rules, with the lemmas of the lens range and the lines)",
        by_argument: "the real-arithmetic derivation in wu2013.rs (the sign-aware hulls of the crossings \
                      bound the covered lens values and times; the chord and tangent bound each crossing \
                      time over the lens), and that each branch the f32 code takes on its ends is one \
                      the exact values allow (fallbacks give the full domain)",
        level: Level::MachineChecked,
    },
    Variant {
        id: "nilsson2012-depth-safe",
        ranges: ALL_FINITE,
        scripts: &["STEP", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP); the \
                     composition over the method's own f32 code for every input: the enclosure check \
                     traces the tile answer and finds both depth ends ends of their side of their exact \
                     values, and NaN-free, by rules z3 proves in real arithmetic (enclosure rules, with \
                     the lemma of the w bound from a plane)",
        by_argument: "the real-arithmetic derivation in nilsson2012_depth.rs, at the two pins that name it \
                      (a covered sample's w lies in the tile's w range; its depth is a + c / w for a c \
                      in the residuals' range), and that each branch the f32 code takes on its ends is \
                      one the exact values allow",
        level: Level::MachineChecked,
    },
    Variant {
        id: "gdam2010-safe",
        ranges: &[
            Range {
                inputs: "vertex x, y, w at both shutter ends, sample position x, y",
                range: "every finite f32 value (subnormals, zeros of either sign, up to +-MAX)",
            },
            Range {
                inputs: "a piece [l, h] of the shutter",
                range: "any f32 values 0 <= l <= h <= 1 (the cut points)",
            },
            Range {
                inputs: "any non-finite vertex input, a non-finite sample position or a CoC other than 0",
                range: "nothing culled (code inspection)",
            },
        ],
        scripts: &["STEP", "MONO", "enclosure rules"],
        mechanical: "every rounded result stepped outward encloses the exact result (STEP, for the fused \
                     multiply-adds and the interval sums and products); the composition over the method's \
                     own f32 code for every input: the enclosure check traces the per-sample setup and one \
                     piece's answer and finds the piece's cull and the cull of a still triangle's whole \
                     shutter to imply their exact counterparts (some edge's three exact Bernstein \
                     coefficients at or below minus its pad and some edge's at or above it, the pad >= 0), \
                     by rules z3 proves in real arithmetic (enclosure rules: the four end products, sums \
                     of same-sided ends), and each of its shortcuts to keep the exact value (both branches \
                     one polynomial under the condition's equalities); MONO for g(s) >= 0 (an f32 \
                     difference of ordered f32 values)",
        by_argument: "the real-arithmetic derivation in gdam2010.rs (a quadratic on a piece lies between its \
                      least and greatest Bernstein coefficient, so an edge <= 0 and an edge >= 0 throughout \
                      leave no covered time; a still triangle's edges are constant), and that the kept \
                      pieces, which share their ends, merge into spans holding every kept time (its \
                      shortcuts, an interval [0, 0] taken as 0, equal inputs at both shutter ends as no \
                      motion, the vertex at t = 0 and t = 1 as its end value, are checked: their branches \
                      are one exact value under their conditions)",
        level: Level::MachineChecked,
    },
];

/// The script named `name`.
pub fn script(name: &str) -> Option<&'static Script> {
    SCRIPTS.iter().find(|s| s.name == name)
}

/// The variant with this method id.
pub fn variant(id: &str) -> Option<&'static Variant> {
    VARIANTS.iter().find(|v| v.id == id)
}

/// The strongest verdict a method can reach: proven for all inputs in ranges (these
/// scripts), or only what the gate certifies on its cases.
pub fn strength(id: &str) -> &'static str {
    match variant(id).map(|v| v.level) {
        Some(Level::MachineChecked) => {
            "machine-checked for all inputs in ranges (the composition over the code checked for every input, its rules and lemmas by z3; the method's derivation argued)"
        }
        Some(Level::LemmasChecked) => {
            "rounding lemmas checked, composition argued (z3/gappa check the lemmas; docs/proofs.md argues their composition)"
        }
        None => "no proof for all inputs (its verdict is the gate's, on its cases: `cullproof check`)",
    }
}
