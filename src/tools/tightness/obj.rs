//! Loading triangle meshes from Wavefront OBJ files (with the `tobj` crate).
//!
//! Every object and group of the file is read, polygons are triangulated as fans
//! (tobj's `triangulate`), points and lines are ignored, materials are not needed (a
//! missing `.mtl` is not an error). An error always names the file; when the file is
//! malformed it also names the line: tobj's errors carry no line number, so the file
//! is then scanned with the same rules (a `v` needs 3 numbers, optionally a non-zero w
//! or 3 colour values; `vt` 2 numbers; `vn` 3; each `f` index a non-zero integer that,
//! after resolving negative (relative) indices, names an existing `v`, `vt` or `vn`) and
//! the first offending line is reported. Coordinates that are not finite (`nan`, `inf`,
//! which Rust's float parser accepts) are refused the same way, and so are vertex
//! positions beyond [`MAX_COORD`] in magnitude (finite in f32, but the scene built from
//! them would overflow f32 once fitted into the view).
//!
//! Two caps hold the size of what a file can ask for: at most [`MAX_FACE_VERTICES`]
//! vertex references per face and [`MAX_TRIANGLES`] triangles in all (after the fans).
//! They are checked on the bytes as tobj reads them, so a file that passes one stops at
//! the line that does, with an error naming the file, the line and the count, before
//! tobj builds anything from that line. Errors quote at most a bounded prefix of a line
//! or a word ([`crate::io::quote`]). A long load shows its progress in bytes
//! ([`load_with_progress`]; the bar is drawn only on a terminal).

use super::scene::V3;
use crate::io::quote::clip;
use indicatif::ProgressBar;
use std::io::Read;
use std::path::Path;

/// The largest vertex coordinate magnitude accepted: 10^15, far beyond any real mesh
/// and far enough below f32's 3.4e38 that the fitted scene's clip-space coordinates
/// (up to some 10^5 times the mesh size, with the camera's focal scale and screen
/// offset) stay finite. A larger coordinate is refused with its file, line and value.
pub const MAX_COORD: f32 = 1e15;

/// The most vertex references one face (`f` line) may have. A polygon of n vertices
/// becomes a fan of n - 2 triangles; real meshes have faces of 3 or 4, and a face of
/// millions would only cost time and memory. Split a larger polygon into several faces.
pub const MAX_FACE_VERTICES: usize = 1024;

/// The most triangles a mesh may have, counted after the fans: 4,000,000 (400 times the
/// largest built-in scene, the 10,000-triangle hairball). Every triangle is held per
/// blur setting and tested per tile size and method, so a larger mesh would take hours
/// and gigabytes; decimate it first.
pub const MAX_TRIANGLES: usize = 4_000_000;

/// The caps of one load (the constants above; smaller in tests).
#[derive(Clone, Copy, Debug)]
struct Caps {
    face: usize,
    triangles: usize,
}

const CAPS: Caps = Caps { face: MAX_FACE_VERTICES, triangles: MAX_TRIANGLES };

/// Why a vertex coordinate `w` (the word as written) is refused, if it is.
fn bad_coordinate(w: &str) -> Option<String> {
    match w.parse::<f32>() {
        Ok(x) if !x.is_finite() => Some(format!("`{}` is not a finite number", clip(w))),
        Ok(x) if x.abs() > MAX_COORD => Some(format!(
            "vertex coordinate `{}` is too large: |x| must be at most {MAX_COORD:e} (the scene would overflow f32)",
            clip(w)
        )),
        Ok(_) => None,
        Err(_) => Some(format!("`{}` is not a number", clip(w))),
    }
}

/// The reader tobj reads the file through: it counts the bytes for the progress bar and
/// checks the caps as the bytes pass (words per `f` line, the running triangle total).
/// When a cap is passed it stops the read with an error (tobj then fails with a read
/// error) and keeps the reason in `stop`; a face over the cap is read to its end first
/// (counting only, nothing held), so the error gives its whole count.
struct Watch<R> {
    inner: R,
    pb: ProgressBar,
    caps: Caps,
    /// 1-based number of the line being read.
    line: usize,
    /// The first word of the line so far (only whether it is exactly `f` matters).
    key: Vec<u8>,
    words: usize,
    in_word: bool,
    /// The current line is a face already over the cap.
    over: bool,
    triangles: usize,
    ended: bool,
    /// Why the load stopped: `(line, reason)`.
    stop: Option<(usize, String)>,
}

impl<R: Read> Watch<R> {
    fn new(inner: R, pb: ProgressBar, caps: Caps) -> Self {
        Watch {
            inner,
            pb,
            caps,
            line: 1,
            key: Vec::new(),
            words: 0,
            in_word: false,
            over: false,
            triangles: 0,
            ended: false,
            stop: None,
        }
    }

    fn is_face(&self) -> bool {
        self.key == b"f"
    }

    fn end_line(&mut self) {
        if self.is_face() && self.stop.is_none() {
            let refs = self.words - 1;
            if refs > self.caps.face {
                self.stop = Some((
                    self.line,
                    format!(
                        "a face with {refs} vertex references: at most {} per face (split the polygon into \
                         several faces)",
                        self.caps.face
                    ),
                ));
            } else {
                self.triangles += refs.saturating_sub(2);
                if self.triangles > self.caps.triangles {
                    self.stop = Some((
                        self.line,
                        format!(
                            "the mesh passes {} triangles at this line (faces are triangulated as fans, n - 2 \
                             triangles per face of n vertices): at most {} triangles are taken (decimate the mesh)",
                            self.caps.triangles, self.caps.triangles
                        ),
                    ));
                }
            }
        }
        self.line += 1;
        self.key.clear();
        self.words = 0;
        self.in_word = false;
        self.over = false;
    }

    fn scan(&mut self, bytes: &[u8]) {
        for &b in bytes {
            match b {
                b'\n' => {
                    self.end_line();
                    if self.stop.is_some() {
                        return;
                    }
                }
                b' ' | b'\t' | b'\r' | 0x0b | 0x0c => self.in_word = false,
                _ => {
                    if !self.in_word {
                        self.in_word = true;
                        self.words += 1;
                        if self.words > self.caps.face + 1 && self.is_face() {
                            self.over = true;
                        }
                    }
                    if self.words == 1 && self.key.len() < 2 {
                        self.key.push(b);
                    }
                }
            }
        }
    }

    fn stopped() -> std::io::Error {
        std::io::Error::other("a cap of the OBJ loader was passed")
    }
}

impl<R: Read> Read for Watch<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.stop.is_some() {
            return Err(Self::stopped());
        }
        let n = self.inner.read(buf)?;
        self.pb.inc(n as u64);
        if n == 0 {
            if !self.ended {
                self.ended = true;
                self.end_line();
            }
        } else {
            self.scan(&buf[..n]);
            // A face over the cap: count the rest of its references, holding nothing.
            let mut chunk = Vec::new();
            while self.over && self.stop.is_none() {
                chunk.resize(64 << 10, 0);
                let k = self.inner.read(&mut chunk)?;
                self.pb.inc(k as u64);
                if k == 0 {
                    self.ended = true;
                    self.end_line();
                } else {
                    self.scan(&chunk[..k]);
                }
            }
        }
        if self.stop.is_some() {
            return Err(Self::stopped());
        }
        Ok(n)
    }
}

/// A problem found at one line of an OBJ file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    /// 1-based line number.
    pub line: usize,
    /// The line, trimmed (at most [`crate::io::quote::QUOTE_CHARS`] characters of it).
    pub text: String,
    pub why: String,
}

/// The triangles of an OBJ file, in file order.
pub fn load(path: &Path) -> anyhow::Result<Vec<[V3; 3]>> {
    load_with_progress(path, &ProgressBar::hidden())
}

/// [`load`], advancing `pb` by the bytes read (its length is set to the file's size).
pub fn load_with_progress(path: &Path, pb: &ProgressBar) -> anyhow::Result<Vec<[V3; 3]>> {
    load_capped(path, pb, CAPS)
}

fn load_capped(path: &Path, pb: &ProgressBar, caps: Caps) -> anyhow::Result<Vec<[V3; 3]>> {
    let file = path.display();
    let f = std::fs::File::open(path).map_err(|e| anyhow::anyhow!("{file}: cannot open the OBJ file: {e}"))?;
    if let Ok(m) = f.metadata() {
        pb.set_length(m.len());
    }
    pb.set_position(0);
    let opts = tobj::LoadOptions { triangulate: true, ignore_points: true, ignore_lines: true, ..Default::default() };
    let mut reader = std::io::BufReader::new(Watch::new(f, pb.clone(), caps));
    // Materials are not needed: a `mtllib` is not even opened.
    let loaded = tobj::load_obj_buf(&mut reader, &opts, |_| Err(tobj::LoadError::OpenFileFailed));
    if let Some((line, why)) = reader.get_ref().stop.clone() {
        anyhow::bail!("{file}:{line}: {why}");
    }
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => {
            return Err(match scan(path) {
                Ok(Some(le)) => {
                    anyhow::anyhow!("{file}:{}: {} (tobj: {e}): `{}`", le.line, le.why, le.text)
                }
                Ok(None) => {
                    anyhow::anyhow!("{file}: malformed OBJ (tobj: {e}); the line-by-line scan found no bad line")
                }
                Err(io) => anyhow::anyhow!("{file}: malformed OBJ (tobj: {e}); cannot re-read it: {io}"),
            });
        }
    };
    let mut tris = Vec::new();
    for m in &models {
        let pos = &m.mesh.positions;
        for f in m.mesh.indices.chunks_exact(3) {
            let v = |i: u32| -> V3 {
                let k = 3 * i as usize;
                [pos[k], pos[k + 1], pos[k + 2]]
            };
            tris.push([v(f[0]), v(f[1]), v(f[2])]);
        }
    }
    if let Some(x) = tris.iter().flatten().flatten().find(|x| !x.is_finite() || x.abs() > MAX_COORD) {
        return Err(match scan(path) {
            Ok(Some(le)) => anyhow::anyhow!("{file}:{}: {}: `{}`", le.line, le.why, le.text),
            // Only a position divided by a tiny weight w gets here.
            _ => anyhow::anyhow!(
                "{file}: a vertex coordinate is {x:e} (after dividing by its weight w): |x| must be finite and at \
                 most {MAX_COORD:e}"
            ),
        });
    }
    anyhow::ensure!(!tris.is_empty(), "{file}: no triangles (no `f` line with 3 or more vertices)");
    Ok(tris)
}

/// The first malformed line of an OBJ file, if any (see the module documentation for
/// the rules).
pub fn scan(path: &Path) -> std::io::Result<Option<LineError>> {
    let text = std::fs::read(path)?;
    let text = String::from_utf8_lossy(&text);
    // Totals first: tobj resolves positive indices after the whole object is read.
    let (mut nv, mut nvt, mut nvn) = (0usize, 0usize, 0usize);
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => nv += 1,
            Some("vt") => nvt += 1,
            Some("vn") => nvn += 1,
            _ => {}
        }
    }
    let (mut sv, mut svt, mut svn) = (0usize, 0usize, 0usize);
    for (i, line) in text.lines().enumerate() {
        let err = |why: String| Ok(Some(LineError { line: i + 1, text: clip(line.trim()), why }));
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        let numbers = |n: usize, what: &str| -> Result<(), String> {
            if rest.len() < n {
                return Err(format!("`{key}` needs {n} numbers ({what}), found {}", rest.len()));
            }
            for w in &rest[..n] {
                match w.parse::<f32>() {
                    Ok(x) if x.is_finite() => {}
                    Ok(_) => return Err(format!("`{}` is not a finite number", clip(w))),
                    Err(_) => return Err(format!("`{}` is not a number", clip(w))),
                }
            }
            Ok(())
        };
        match key {
            "v" => {
                if let Err(why) = numbers(3, "x y z") {
                    return err(why);
                }
                if let Some(why) = rest[..3].iter().find_map(|w| bad_coordinate(w)) {
                    return err(why);
                }
                match rest.len() {
                    3 => {}
                    4 => match rest[3].parse::<f32>() {
                        Ok(w) if w != 0.0 && w.is_finite() => {}
                        _ => return err(format!("the weight w = `{}` must be a non-zero number", clip(rest[3]))),
                    },
                    6 => {
                        if let Some(w) = rest[3..].iter().find(|w| w.parse::<f32>().is_err()) {
                            return err(format!("colour value `{}` is not a number", clip(w)));
                        }
                    }
                    n => return err(format!("`v` takes 3, 4 (x y z w) or 6 (x y z r g b) numbers, found {n}")),
                }
                sv += 1;
            }
            "vt" => {
                if let Err(why) = numbers(2, "u v") {
                    return err(why);
                }
                svt += 1;
            }
            "vn" => {
                if let Err(why) = numbers(3, "x y z") {
                    return err(why);
                }
                svn += 1;
            }
            "f" | "l" => {
                for w in &rest {
                    let parts: Vec<&str> = w.split('/').collect();
                    if parts.len() > 3 {
                        return err(format!("face vertex `{}` has more than 3 indices", clip(w)));
                    }
                    let kinds = [("v", sv, nv), ("vt", svt, nvt), ("vn", svn, nvn)];
                    for (p, (what, so_far, total)) in parts.iter().zip(kinds) {
                        if p.is_empty() {
                            if what == "v" {
                                return err(format!("face vertex `{}` has no position index", clip(w)));
                            }
                            continue;
                        }
                        let Ok(x) = p.parse::<isize>() else {
                            return err(format!("face index `{}` in `{}` is not an integer", clip(p), clip(w)));
                        };
                        let resolved = if x < 0 { so_far as isize + x } else { x - 1 };
                        if x == 0 || resolved < 0 || resolved as usize >= total {
                            return err(format!(
                                "{what} index {x} in `{}` is out of range (the file has {total} `{what}` lines{})",
                                clip(w),
                                if x < 0 { format!(", {so_far} before this line") } else { String::new() }
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str, text: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("cullproof-obj-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn a_good_file_loads_with_quads_triangulated() {
        let p =
            temp("good.obj", "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -4 -3 -2\n");
        let t = load(&p).unwrap();
        assert_eq!(t.len(), 3);
        assert_eq!(t[0][1], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn a_bad_vertex_names_file_and_line() {
        let p = temp("badv.obj", "v 0 0 0\nv 1 0 0\n\nv 1 oops 0\nf 1 2 3\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("badv.obj") && e.contains(":4:") && e.contains("oops"), "{e}");
    }

    #[test]
    fn an_index_out_of_range_names_file_and_line() {
        let p = temp("badf.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n# next is wrong\nf 1 2 9\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("badf.obj") && e.contains(":6:") && e.contains("out of range"), "{e}");
    }

    #[test]
    fn a_nan_coordinate_is_refused_with_its_line() {
        let p = temp("nan.obj", "v 0 0 0\nv nan 0 0\nv 1 1 0\nf 1 2 3\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("nan.obj") && e.contains(":2:") && e.contains("finite"), "{e}");
    }

    #[test]
    fn a_huge_coordinate_is_refused_with_its_line_and_value() {
        let p = temp("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1e36 0\nf 1 2 3\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("huge.obj") && e.contains(":3:") && e.contains("1e36") && e.contains("too large"), "{e}");
        let p = temp("edge.obj", "v 0 0 0\nv -1e15 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(load(&p).unwrap()[0][1][0], -1e15);
    }

    #[test]
    fn a_face_over_the_cap_is_refused_with_its_line_and_count() {
        let refs = " 1 2 3".repeat(700); // 2100 references
        let p = temp("bigface.obj", &format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf{refs}\nf 1 2 3\n"));
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("bigface.obj:5:") && e.contains("2100 vertex references") && e.contains("1024"), "{e}");
        assert!(e.len() < 400, "{e}");
        // At the cap it loads (a fan of n - 2 triangles); without a final newline too.
        let at = " 1 2 3 4".repeat(256);
        let p = temp("atcap.obj", &format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf{at}"));
        assert_eq!(load(&p).unwrap().len(), 1022);
        // The last line is checked even without its newline.
        let p = temp("lastface.obj", &format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nf{refs}"));
        assert!(load(&p).unwrap_err().to_string().contains("lastface.obj:4: a face with 2100"));
    }

    #[test]
    fn a_mesh_over_the_triangle_cap_is_refused_at_the_line_that_passes_it() {
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n# faces\n");
        for _ in 0..6 {
            text += "f 1 2 3 4\n"; // two triangles each
        }
        let p = temp("many.obj", &text);
        let pb = ProgressBar::hidden();
        let caps = Caps { face: 8, triangles: 10 };
        let e = load_capped(&p, &pb, caps).unwrap_err().to_string();
        assert!(e.contains("many.obj:11:") && e.contains("at most 10 triangles"), "{e}");
        assert_eq!(load_capped(&p, &pb, Caps { face: 8, triangles: 12 }).unwrap().len(), 12);
        // The bar went through the whole file.
        assert_eq!(pb.position(), text.len() as u64);
        assert_eq!(pb.length(), Some(text.len() as u64));
        // `f` only as a whole first word: `fo` lines and comments are not faces.
        let p = temp(
            "notfaces.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\n# f 1 2 3 1 2 3 1 2 3\nfoo 1 2 3 4 5 6 7 8 9 10\nf 1 2 3\n",
        );
        assert_eq!(load_capped(&p, &pb, Caps { face: 3, triangles: 1 }).unwrap().len(), 1);
    }

    #[test]
    fn a_long_bad_line_is_quoted_in_part() {
        let p = temp("longbad.obj", &format!("v 0 0 0\nv 1 0 {}\nv 1 1 0\nf 1 2 3\n", "9".repeat(100_000)));
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("longbad.obj:2:") && e.contains("bytes") && e.len() < 1000, "{e}");
    }

    #[test]
    fn a_missing_file_and_an_empty_mesh_are_named() {
        let e = load(Path::new("/nonexistent/dir/none.obj")).unwrap_err().to_string();
        assert!(e.contains("none.obj") && e.contains("cannot open"), "{e}");
        let p = temp("empty.obj", "v 0 0 0\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("empty.obj") && e.contains("no triangles"), "{e}");
    }
}
