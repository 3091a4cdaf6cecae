//! Culling bounds in another process (Python, a shader harness, a simulator), spoken to
//! over stdin / stdout in JSON lines: the process protocol of `docs/protocol.md`
//! (version [`PROTOCOL`]).
//!
//! `cullproof check --exec "python3 my_bound.py" --method my-bound` starts the command
//! (through `sh -c`), greets it, learns its id, and sends it one request per tile test;
//! the answer comes back on one line. Per-sample constraints cross the boundary as
//! declared forms (affine or bilinear in x, y, u, v, t with f32 coefficients and a fixed
//! f32 evaluation order, see [`Form`]) which cullproof evaluates itself, in f32 for a
//! sample and with a sound enclosure for a box, so the gate certifies them like built-in
//! ones; an `opaque` constraint is evaluated by the process one sample at a time and
//! can only be sampled, never certified (its name says so).
//!
//! Failures are never taken for an answer: an error line from the process, a line that
//! does not parse, a process that exits, or one silent for longer than the timeout
//! stops the run with a message naming the bound, the request and what went wrong.
//!
//! Several worker threads each get a process of their own (started on demand, kept in
//! a pool), so the bound must not depend on the order of requests.

use crate::bounds::{Method, MethodInfo, Outputs, Prepared, SampleBox, SampleConstraint, TileBounds, TileResult};
use crate::io::quote::{clip, quote};
use crate::model::{Dims, Sample, Tile, Triangle};
use crate::Interval;
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The protocol version this build speaks.
pub const PROTOCOL: u32 = 1;

/// How long a process may take for one answer (the greeting included).
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(30);

/// The longest answer line taken, in bytes (1 MiB; the newline not counted). A longer
/// line stops the run with an error as soon as the limit is passed, before more of it
/// is held in memory.
pub const MAX_LINE: usize = 1 << 20;

/// The triangle as it crosses the boundary: the model's f32 values written as f64, so
/// that the decimal text denotes exactly the f32 value (an f32 printed as f32 reads back
/// as a different f64 in most languages).
#[derive(Serialize)]
struct TriMsg {
    q: [[f64; 4]; 3],
    r: [[f64; 4]; 3],
    c0: [f64; 3],
    c1: [f64; 3],
    k: f64,
}

fn wide<const N: usize>(a: [f32; N]) -> [f64; N] {
    a.map(|x| x as f64)
}

/// Read f32 coefficients that must be f32 values exactly (the form is evaluated in
/// f32 with them; a rounded coefficient would be a different constraint).
fn exact_f32<'de, D: serde::Deserializer<'de>, const N: usize>(d: D) -> std::result::Result<[f32; N], D::Error> {
    let v: Vec<f64> = Vec::deserialize(d)?;
    if v.len() != N {
        return Err(serde::de::Error::custom(format!("{} coefficients, expected {N}", v.len())));
    }
    let mut out = [0f32; N];
    for (o, x) in out.iter_mut().zip(&v) {
        *o = *x as f32;
        if *o as f64 != *x {
            return Err(serde::de::Error::custom(format!("coefficient {x} is not an f32 value")));
        }
    }
    Ok(out)
}

/// An interval end read as f64, rounded outward to f32 (`lo` down, `hi` up).
fn outward(r: [f64; 2]) -> [f32; 2] {
    let (mut lo, mut hi) = (r[0] as f32, r[1] as f32);
    if lo as f64 > r[0] {
        lo = lo.next_down();
    }
    if (hi as f64) < r[1] {
        hi = hi.next_up();
    }
    [lo, hi]
}

#[derive(Serialize)]
#[serde(tag = "op", rename_all = "lowercase")]
enum Request<'a> {
    Hello { protocol: u32 },
    Tile { n: u64, tri: &'a TriMsg, tile: [f64; 4] },
    Eval { n: u64, tri: &'a TriMsg, tile: [f64; 4], m: usize, s: [f64; 5] },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Hello {
    protocol: u32,
    id: String,
    #[serde(default)]
    source: String,
    #[serde(default)]
    outputs: Vec<String>,
}

/// A per-sample constraint as declared by the process.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "form", rename_all = "lowercase", deny_unknown_fields)]
pub enum Form {
    /// `g = ((((c[0] + c[1] x) + c[2] y) + c[3] u) + c[4] v) + c[5] t`, every product
    /// and sum rounded to f32 in that order (no fused multiply-add).
    Affine {
        #[serde(default)]
        name: Option<String>,
        #[serde(deserialize_with = "exact_f32")]
        c: [f32; 6],
    },
    /// `g = ((c[0] + c[1] a) + c[2] b) + c[3] (a b)` with `a`, `b` two of x, y, u, v, t,
    /// every product and sum rounded to f32 in that order (`a b` first).
    Bilinear {
        #[serde(default)]
        name: Option<String>,
        a: Var,
        b: Var,
        #[serde(deserialize_with = "exact_f32")]
        c: [f32; 4],
    },
    /// Any other function: the process evaluates it per sample (`op: eval`); it can be
    /// sampled, never certified.
    Opaque {
        #[serde(default)]
        name: Option<String>,
    },
}

/// A sample coordinate named in a form.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Var {
    X,
    Y,
    U,
    V,
    T,
}

impl Var {
    fn of(self, s: &Sample) -> f32 {
        match self {
            Var::X => s.x,
            Var::Y => s.y,
            Var::U => s.u,
            Var::V => s.v,
            Var::T => s.t,
        }
    }
    fn of_box(self, b: &SampleBox) -> Interval {
        match self {
            Var::X => b.x,
            Var::Y => b.y,
            Var::U => b.u,
            Var::V => b.v,
            Var::T => b.t,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TileAnswer {
    n: u64,
    #[serde(default)]
    error: Option<String>,
    #[serde(default)]
    empty: bool,
    #[serde(default)]
    u: Option<[f64; 2]>,
    #[serde(default)]
    v: Option<[f64; 2]>,
    #[serde(default)]
    t: Option<[f64; 2]>,
    #[serde(default)]
    z: Option<[f64; 2]>,
    #[serde(default)]
    constraints: Vec<Form>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EvalAnswer {
    n: u64,
    #[serde(default)]
    error: Option<String>,
    #[serde(default)]
    g: Option<f32>,
}

/// One running process.
struct Proc {
    child: Child,
    stdin: ChildStdin,
    lines: Receiver<std::io::Result<String>>,
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A culling method answered by another process.
pub struct ExecMethod {
    info: &'static MethodInfo,
    command: String,
    timeout: Duration,
    pool: Mutex<Vec<Proc>>,
    next: std::sync::atomic::AtomicU64,
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

fn spawn(command: &str) -> Result<Proc> {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(command)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .with_context(|| format!("--exec {command:?}: cannot start"))?;
    let stdin = child.stdin.take().expect("piped");
    let stdout = child.stdout.take().expect("piped");
    // A few lines ahead at most: one answer is read per request, so the memory held is
    // bounded by MAX_LINE times the channel's room.
    let (tx, rx) = std::sync::mpsc::sync_channel(2);
    std::thread::spawn(move || {
        let mut r = BufReader::new(stdout);
        loop {
            let line = match read_line(&mut r, MAX_LINE) {
                Ok(Some(l)) => Ok(l),
                Ok(None) => break,
                Err(e) => Err(e),
            };
            let stop = line.is_err();
            if tx.send(line).is_err() || stop {
                break;
            }
        }
    });
    Ok(Proc { child, stdin, lines: rx })
}

/// One line of `r` without its `\n` (None at the end of the stream), of at most `max`
/// bytes: a longer line is an error as soon as `max` is passed (the rest is not read).
fn read_line(r: &mut impl BufRead, max: usize) -> std::io::Result<Option<String>> {
    let mut line = Vec::new();
    let mut any = false;
    loop {
        let buf = match r.fill_buf() {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if buf.is_empty() {
            if !any {
                return Ok(None);
            }
            break;
        }
        any = true;
        let (take, done) = match buf.iter().position(|&b| b == b'\n') {
            Some(i) => (i, true),
            None => (buf.len(), false),
        };
        if line.len() + take > max {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("an answer line is longer than {max} bytes, the most the protocol takes"),
            ));
        }
        line.extend_from_slice(&buf[..take]);
        r.consume(take + done as usize);
        if done {
            break;
        }
    }
    String::from_utf8(line).map(Some).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("an answer line of {} bytes is not UTF-8 text", e.as_bytes().len()),
        )
    })
}

impl Proc {
    /// Send one request line and wait for one answer line.
    fn ask(&mut self, req: &str, timeout: Duration) -> std::result::Result<String, String> {
        if let Err(e) = self.stdin.write_all(req.as_bytes()).and_then(|_| self.stdin.flush()) {
            return Err(format!("cannot write to the process ({e}){}", self.status()));
        }
        match self.lines.recv_timeout(timeout) {
            Ok(Ok(line)) => Ok(line),
            Ok(Err(e)) => Err(format!("cannot read its answer ({e})")),
            Err(RecvTimeoutError::Timeout) => Err(format!("no answer within {} s", timeout.as_secs_f64())),
            Err(RecvTimeoutError::Disconnected) => Err(format!("it closed its output{}", self.status())),
        }
    }
    fn status(&mut self) -> String {
        std::thread::sleep(Duration::from_millis(20));
        match self.child.try_wait() {
            Ok(Some(s)) => format!("; the process exited: {s}"),
            _ => String::new(),
        }
    }
}

/// Start the command, greet it, and build the method it answers for (an error names
/// the command and what went wrong).
pub fn start(command: &str, timeout: Duration) -> Result<&'static dyn Method> {
    let mut p = spawn(command)?;
    let hello = serde_json::to_string(&Request::Hello { protocol: PROTOCOL })? + "\n";
    let line = p.ask(&hello, timeout).map_err(|e| anyhow::anyhow!("--exec {command:?}: greeting: {e}"))?;
    let h: Hello = serde_json::from_str(&line).map_err(|e| {
        anyhow::anyhow!(
            "--exec {command:?}: greeting answer {}: {} (see docs/protocol.md)",
            quote(&line),
            clip(&e.to_string())
        )
    })?;
    if h.protocol != PROTOCOL {
        bail!("--exec {command:?}: speaks protocol version {}, this cullproof speaks {PROTOCOL}", h.protocol);
    }
    if !crate::external::plugin::valid_id(&h.id) {
        bail!("--exec {command:?}: id {}: use 1 to 64 letters, digits, '-', '_' or '.'", quote(&h.id));
    }
    let mut outputs = Outputs { tile_reject: false, lens: false, time: false, depth: false, per_sample: false };
    for o in &h.outputs {
        match o.as_str() {
            "tile-reject" => outputs.tile_reject = true,
            "lens" => outputs.lens = true,
            "time" => outputs.time = true,
            "depth" => outputs.depth = true,
            "per-sample" => outputs.per_sample = true,
            _ => bail!(
                "--exec {command:?}: output {} is not one of tile-reject, lens, time, depth, per-sample",
                quote(o)
            ),
        }
    }
    let info = Box::leak(Box::new(MethodInfo {
        id: leak(h.id),
        source: leak(format!("process `{command}`: {}", h.source)),
        reconstruction: false,
        dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
        outputs,
    }));
    let m = ExecMethod {
        info,
        command: command.to_string(),
        timeout,
        pool: Mutex::new(vec![p]),
        next: std::sync::atomic::AtomicU64::new(0),
    };
    Ok(Box::leak(Box::new(m)))
}

/// Start a process bound and make it known to every command by its id.
pub fn start_and_plug(command: &str, timeout: Duration) -> Result<&'static dyn Method> {
    let m = start(command, timeout)?;
    crate::bounds::plug(m).map_err(|e| anyhow::anyhow!("--exec {command:?}: {e}"))?;
    Ok(m)
}

impl ExecMethod {
    /// One round trip on a pooled process; a failure stops the run (see the module doc).
    fn round_trip(&self, req: &str) -> String {
        let taken = self.pool.lock().unwrap_or_else(|e| e.into_inner()).pop();
        let mut p = match taken {
            Some(p) => p,
            None => match spawn(&self.command) {
                Ok(mut p) => {
                    let hello = format!("{{\"op\":\"hello\",\"protocol\":{PROTOCOL}}}\n");
                    if let Err(e) = p.ask(&hello, self.timeout) {
                        self.fail(req, &format!("greeting a new process: {e}"));
                    }
                    p
                }
                Err(e) => self.fail(req, &format!("{e:#}")),
            },
        };
        match p.ask(req, self.timeout) {
            Ok(line) => {
                self.pool.lock().unwrap_or_else(|e| e.into_inner()).push(p);
                line
            }
            Err(e) => self.fail(req, &e),
        }
    }

    fn fail(&self, req: &str, what: &str) -> ! {
        std::panic::panic_any(ExecFailure(format!(
            "exec bound `{}` (`{}`) failed on request {}: {what}; no answer was taken",
            self.info.id,
            self.command,
            req.trim_end()
        )))
    }
}

/// Why a run stopped on a bound in another process (the payload of the panic that
/// stops it: the tile test has no error channel, and no answer may be made up). The
/// command line reports it as an error; a library caller can catch it with
/// `std::panic::catch_unwind` and downcast the payload to this type.
#[derive(Clone, Debug)]
pub struct ExecFailure(pub String);

impl std::fmt::Display for ExecFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

fn tri_msg(t: &Triangle) -> TriMsg {
    TriMsg { q: t.q.map(wide), r: t.r.map(wide), c0: wide(t.c0), c1: wide(t.c1), k: t.k as f64 }
}

struct ExecPrep {
    m: &'static ExecMethod,
    tri: Arc<TriMsg>,
}

impl Prepared for ExecPrep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let n = self.m.next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let tl = wide([tile.x0, tile.y0, tile.x1, tile.y1]);
        let req = serde_json::to_string(&Request::Tile { n, tri: &self.tri, tile: tl }).expect("serialisable") + "\n";
        let line = self.m.round_trip(&req);
        let a: TileAnswer = match serde_json::from_str(&line) {
            Ok(a) => a,
            Err(e) => self.m.fail(&req, &format!("answer {} does not parse: {}", quote(&line), clip(&e.to_string()))),
        };
        if a.n != n {
            self.m.fail(&req, &format!("answer {} is for request {} (expected {n})", quote(&line), a.n));
        }
        if let Some(e) = a.error {
            self.m.fail(&req, &format!("the process reported: {}", clip(&e)));
        }
        if a.empty {
            return TileResult::Empty;
        }
        // An interval is `[lo, hi]` with lo <= hi (a tile with nothing in it is
        // `"empty": true`): anything else breaks the protocol.
        for (name, r) in [("u", a.u), ("v", a.v), ("t", a.t), ("z", a.z)] {
            if let Some([lo, hi]) = r {
                if lo.partial_cmp(&hi).is_none_or(|o| o == std::cmp::Ordering::Greater) {
                    self.m.fail(
                        &req,
                        &format!("answer field `{name}` = [{lo}, {hi}]: an interval needs lo <= hi (a tile with nothing in it is \"empty\": true)"),
                    );
                }
            }
        }
        let full = TileBounds::full();
        let constraints = a
            .constraints
            .into_iter()
            .enumerate()
            .map(|(i, form)| {
                Box::new(ExecConstraint { m: self.m, tri: self.tri.clone(), tile: tl, index: i, form })
                    as Box<dyn SampleConstraint>
            })
            .collect();
        TileResult::Bounds(TileBounds {
            u: a.u.map_or(full.u, outward),
            v: a.v.map_or(full.v, outward),
            t: a.t.map_or(full.t, outward),
            z: a.z.map(outward),
            constraints,
        })
    }
}

impl Method for ExecMethod {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        // SAFETY: every ExecMethod is leaked by `start`, so `self` is 'static.
        let me: &'static ExecMethod = unsafe { &*(self as *const ExecMethod) };
        Box::new(ExecPrep { m: me, tri: Arc::new(tri_msg(tri)) })
    }
}

/// A constraint of a tile answer.
struct ExecConstraint {
    m: &'static ExecMethod,
    tri: Arc<TriMsg>,
    tile: [f64; 4],
    index: usize,
    form: Form,
}

impl std::fmt::Debug for ExecConstraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {:?}", self.m.info.id, self.form)
    }
}

/// The f32 values a sample coordinate in `[lo, hi]` can take: `[lo, hi]` rounded
/// outward to f32.
fn f32_range(i: Interval) -> [f32; 2] {
    let (mut lo, mut hi) = (i.lo as f32, i.hi as f32);
    if lo as f64 > i.lo {
        lo = lo.next_down();
    }
    if (hi as f64) < i.hi {
        hi = hi.next_up();
    }
    [lo, hi]
}

/// `[min, max]` of f32 products over the corners: rounding to nearest is monotone, so
/// the f32 product of any values in the ranges lies between the rounded extremes.
fn mul_range(a: [f32; 2], b: [f32; 2]) -> [f32; 2] {
    let p = [a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1]];
    if p.iter().any(|x| x.is_nan()) {
        return [f32::NEG_INFINITY, f32::INFINITY];
    }
    [p.iter().copied().fold(f32::INFINITY, f32::min), p.iter().copied().fold(f32::NEG_INFINITY, f32::max)]
}

fn add_range(a: [f32; 2], b: [f32; 2]) -> [f32; 2] {
    let (lo, hi) = (a[0] + b[0], a[1] + b[1]);
    if lo.is_nan() || hi.is_nan() {
        return [f32::NEG_INFINITY, f32::INFINITY];
    }
    [lo, hi]
}

impl Form {
    /// The f32 value, in the stated order.
    pub fn eval(&self, s: &Sample) -> Option<f32> {
        match self {
            Form::Affine { c, .. } => {
                Some(((((c[0] + c[1] * s.x) + c[2] * s.y) + c[3] * s.u) + c[4] * s.v) + c[5] * s.t)
            }
            Form::Bilinear { a, b, c, .. } => {
                let (a, b) = (a.of(s), b.of(s));
                let ab = a * b;
                Some(((c[0] + c[1] * a) + c[2] * b) + c[3] * ab)
            }
            Form::Opaque { .. } => None,
        }
    }
    /// An enclosure of every f32 value [`Form::eval`] gives for an f32 sample in the
    /// box: the same operations on f32 ranges. Each operation rounds to nearest, which
    /// is monotone, so applying it to the ends of the ranges (all four corners for a
    /// product) bounds its result for every point between; no widening is needed.
    pub fn eval_box(&self, b: &SampleBox) -> Option<Interval> {
        let k = |x: f32| [x, x];
        let r = match self {
            Form::Affine { c, .. } => {
                let mut g = k(c[0]);
                for (ci, v) in c[1..].iter().zip([b.x, b.y, b.u, b.v, b.t]) {
                    g = add_range(g, mul_range(k(*ci), f32_range(v)));
                }
                g
            }
            Form::Bilinear { a, b: bv, c, .. } => {
                let (ra, rb) = (f32_range(a.of_box(b)), f32_range(bv.of_box(b)));
                let ab = mul_range(ra, rb);
                add_range(
                    add_range(add_range(k(c[0]), mul_range(k(c[1]), ra)), mul_range(k(c[2]), rb)),
                    mul_range(k(c[3]), ab),
                )
            }
            Form::Opaque { .. } => return None,
        };
        Some(Interval::new(r[0] as f64, r[1] as f64))
    }
    fn label(&self) -> Option<&str> {
        match self {
            Form::Affine { name, .. } | Form::Bilinear { name, .. } | Form::Opaque { name } => name.as_deref(),
        }
    }
}

impl SampleConstraint for ExecConstraint {
    fn name(&self) -> String {
        let base = self.form.label().map_or_else(|| format!("constraint {}", self.index), str::to_string);
        match self.form {
            Form::Opaque { .. } => format!("{base} (sampled, not certified)"),
            _ => base,
        }
    }
    fn eval(&self, s: &Sample) -> f32 {
        if let Some(g) = self.form.eval(s) {
            return g;
        }
        let n = self.m.next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let req = serde_json::to_string(&Request::Eval {
            n,
            tri: &self.tri,
            tile: self.tile,
            m: self.index,
            s: wide([s.x, s.y, s.u, s.v, s.t]),
        })
        .expect("serialisable")
            + "\n";
        let line = self.m.round_trip(&req);
        match serde_json::from_str::<EvalAnswer>(&line) {
            Ok(EvalAnswer { n: got, error: None, g: Some(g) }) if got == n => g,
            Ok(EvalAnswer { error: Some(e), .. }) => self.m.fail(&req, &format!("the process reported: {}", clip(&e))),
            Ok(_) => self.m.fail(&req, &format!("answer {} is not {{\"n\": {n}, \"g\": value}}", quote(&line))),
            Err(e) => self.m.fail(&req, &format!("answer {} does not parse: {}", quote(&line), clip(&e.to_string()))),
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        // An opaque constraint cannot be enclosed: the whole line (never certified).
        self.form.eval_box(b).unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_box_evaluation_encloses_every_f32_value_of_a_form() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..2000 {
            let c6: [f32; 6] =
                std::array::from_fn(|_| rng.gen_range(-1e3f32..1e3) * rng.gen_range(0.0f32..1.0).powi(8));
            let forms = [
                Form::Affine { name: None, c: c6 },
                Form::Bilinear { name: None, a: Var::U, b: Var::T, c: [c6[0], c6[1], c6[2], c6[3]] },
                Form::Bilinear { name: None, a: Var::X, b: Var::V, c: [c6[2], c6[3], c6[4], c6[5]] },
            ];
            let lo: [f64; 5] =
                std::array::from_fn(|i| if i < 2 { rng.gen_range(-1e3..1e3) } else { rng.gen_range(-1.0..1.0) });
            let w: [f64; 5] = std::array::from_fn(|_| rng.gen_range(0.0..0.5f64).powi(3));
            let iv = |i: usize| Interval::new(lo[i], lo[i] + w[i]);
            let b = SampleBox { x: iv(0), y: iv(1), u: iv(2), v: iv(3), t: iv(4) };
            for f in &forms {
                let e = f.eval_box(&b).unwrap();
                for _ in 0..20 {
                    let mut p = |i: usize| (lo[i] + w[i] * rng.gen_range(0.0..=1.0)) as f32;
                    let s = Sample { x: p(0), y: p(1), u: p(2), v: p(3), t: p(4) };
                    let g = f.eval(&s).unwrap() as f64;
                    assert!(e.lo <= g && g <= e.hi, "{f:?} {s:?}: {g} outside {e:?}");
                }
            }
        }
    }

    #[test]
    fn answer_lines_are_read_up_to_the_limit() {
        let mut r = std::io::Cursor::new(b"one\ntwo\n\nlast".to_vec());
        let mut got = Vec::new();
        while let Some(l) = read_line(&mut r, 8).unwrap() {
            got.push(l);
        }
        assert_eq!(got, ["one", "two", "", "last"]);
        // Reading stops at the limit: the rest of a long line is never held.
        let long = [vec![b'x'; 5000], b"\nnext\n".to_vec()].concat();
        let mut r = std::io::BufReader::with_capacity(64, std::io::Cursor::new(long));
        let e = read_line(&mut r, 100).unwrap_err().to_string();
        assert!(e.contains("longer than 100 bytes"), "{e}");
        assert!(r.get_ref().position() < 300);
        let mut r = std::io::Cursor::new(vec![b'a', 0xff, b'\n']);
        assert!(read_line(&mut r, 8).unwrap_err().to_string().contains("not UTF-8"));
    }

    #[test]
    fn forms_parse_and_evaluate_in_the_stated_order() {
        let f: Form = serde_json::from_str(r#"{"form":"affine","c":[1,2,0,0,0,0.5]}"#).unwrap();
        let s = Sample { x: 3.0, y: 0.0, u: 0.0, v: 0.0, t: 2.0 };
        assert_eq!(f.eval(&s), Some(8.0));
        let f: Form = serde_json::from_str(r#"{"form":"bilinear","a":"u","b":"t","c":[1,0,0,2],"name":"ut"}"#).unwrap();
        assert_eq!(f.eval(&Sample { u: 0.5, t: 0.5, ..s }), Some(1.5));
        assert!(serde_json::from_str::<Form>(r#"{"form":"cubic","c":[1]}"#).is_err());
        assert!(serde_json::from_str::<Form>(r#"{"form":"bilinear","a":"w","b":"t","c":[1,0,0,2]}"#).is_err());
        // A coefficient must be an f32 value exactly; an interval end is rounded outward.
        let e = serde_json::from_str::<Form>(r#"{"form":"affine","c":[0.1,0,0,0,0,0]}"#).unwrap_err();
        assert!(e.to_string().contains("not an f32 value"), "{e}");
        let [lo, hi] = outward([0.1, 0.1]);
        assert!((lo as f64) < 0.1 && (hi as f64) > 0.1 && hi == lo.next_up());
        assert_eq!(outward([0.5, 0.75]), [0.5, 0.75]);
    }
}
