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

use super::scene::V3;
use std::path::Path;

/// The largest vertex coordinate magnitude accepted: 10^15, far beyond any real mesh
/// and far enough below f32's 3.4e38 that the fitted scene's clip-space coordinates
/// (up to some 10^5 times the mesh size, with the camera's focal scale and screen
/// offset) stay finite. A larger coordinate is refused with its file, line and value.
pub const MAX_COORD: f32 = 1e15;

/// Why a vertex coordinate `w` (the word as written) is refused, if it is.
fn bad_coordinate(w: &str) -> Option<String> {
    match w.parse::<f32>() {
        Ok(x) if !x.is_finite() => Some(format!("`{w}` is not a finite number")),
        Ok(x) if x.abs() > MAX_COORD => Some(format!(
            "vertex coordinate `{w}` is too large: |x| must be at most {MAX_COORD:e} (the scene would overflow f32)"
        )),
        Ok(_) => None,
        Err(_) => Some(format!("`{w}` is not a number")),
    }
}

/// A problem found at one line of an OBJ file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    /// 1-based line number.
    pub line: usize,
    pub text: String,
    pub why: String,
}

/// The triangles of an OBJ file, in file order.
pub fn load(path: &Path) -> anyhow::Result<Vec<[V3; 3]>> {
    let file = path.display();
    if let Err(e) = std::fs::metadata(path) {
        anyhow::bail!("{file}: cannot open the OBJ file: {e}");
    }
    let opts = tobj::LoadOptions { triangulate: true, ignore_points: true, ignore_lines: true, ..Default::default() };
    let models = match tobj::load_obj(path, &opts) {
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
        let err = |why: String| Ok(Some(LineError { line: i + 1, text: line.trim().to_string(), why }));
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
                    Ok(_) => return Err(format!("`{w}` is not a finite number")),
                    Err(_) => return Err(format!("`{w}` is not a number")),
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
                        _ => return err(format!("the weight w = `{}` must be a non-zero number", rest[3])),
                    },
                    6 => {
                        if let Some(w) = rest[3..].iter().find(|w| w.parse::<f32>().is_err()) {
                            return err(format!("colour value `{w}` is not a number"));
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
                        return err(format!("face vertex `{w}` has more than 3 indices"));
                    }
                    let kinds = [("v", sv, nv), ("vt", svt, nvt), ("vn", svn, nvn)];
                    for (p, (what, so_far, total)) in parts.iter().zip(kinds) {
                        if p.is_empty() {
                            if what == "v" {
                                return err(format!("face vertex `{w}` has no position index"));
                            }
                            continue;
                        }
                        let Ok(x) = p.parse::<isize>() else {
                            return err(format!("face index `{p}` in `{w}` is not an integer"));
                        };
                        let resolved = if x < 0 { so_far as isize + x } else { x - 1 };
                        if x == 0 || resolved < 0 || resolved as usize >= total {
                            return err(format!(
                                "{what} index {x} in `{w}` is out of range (the file has {total} `{what}` lines{})",
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
    fn a_missing_file_and_an_empty_mesh_are_named() {
        let e = load(Path::new("/nonexistent/dir/none.obj")).unwrap_err().to_string();
        assert!(e.contains("none.obj") && e.contains("cannot open"), "{e}");
        let p = temp("empty.obj", "v 0 0 0\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("empty.obj") && e.contains("no triangles"), "{e}");
    }
}
