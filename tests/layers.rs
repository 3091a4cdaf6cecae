//! The library's layers keep data flowing one way. `src/` holds one folder per layer,
//! in this order (`LAYERS`):
//!
//! `io` -> `model` -> `bounds` -> `external` -> `cases` -> `judge` -> `gate` -> `search`
//! -> `tools` -> `cli`
//!
//! and a layer imports only the layers before it: no import from an earlier layer to a
//! later one, and so no import loop among the layers. Inside each layer the files (a
//! folder's `mod.rs`, which declares them, is no node; a file's submodules, like
//! `gate/merge/validate.rs`, count as that file) import one another without a loop.
//! Every top-level module of `src/` is one of the layers.
//!
//! How the graph is read, from the source text alone:
//! - The modules compiled into the library are found from `src/lib.rs` by following
//!   `mod NAME;` declarations, so a file declared only under `#[cfg(test)]` is left out.
//! - Comments and the contents of string and character literals are blanked; a string
//!   that is exactly a path from `crate::` or `super::` is kept (serde's
//!   `#[serde(with = "crate::io::num_or_inf")]` names a module that way).
//! - An item under `#[cfg(test)]` is blanked up to its end (a `;` or a closing brace at
//!   its own level): test code may reach anywhere.
//! - Every path from `crate::` or `super::` (use trees with their `{...}` groups
//!   included) is followed through modules and through the `use` and `pub use` items
//!   of the modules it passes (`crate::Gate` is `gate::Gate`; `super::Row` from a file
//!   of `check/` is `check::row::Row`), down to the module that defines the item. A name
//!   taken from another crate stops at the last module passed (`crate::Interval`, the
//!   `oracles` crate's, is no edge).
//!
//! A loop fails the test, naming each edge of it with the first file and line that
//! makes it. The unit checks below show that the finder reports a hand-made loop and
//! that the reader sees the real edges, so a pass is not a reader that sees nothing.
//!
//! The same reading keeps the test scaffolding of `src/` (the bounds' test kit, the old
//! code kept for the bit-identity tests, ...) out of the library: no such file is
//! reached from `src/lib.rs` outside `#[cfg(test)]`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Edges of a graph, each with where it comes from (the first `file:line` seen).
type Graph = BTreeMap<String, BTreeMap<String, String>>;

fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

// ---------------------------------------------------------------------------------
// Source text: comments, literals and test items blanked.

/// Is `s` exactly a path from `crate::` or `super::` (`crate::io::num_or_inf`)?
fn is_path_text(s: &str) -> bool {
    let mut parts = s.split("::");
    matches!(parts.next(), Some("crate" | "super"))
        && s.contains("::")
        && parts.all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
}

fn is_ident_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The source with every comment and the contents of every string and character
/// literal replaced by spaces (line breaks kept, so lines keep their numbers), except
/// string literals that are a path ([`is_path_text`]).
fn code_of(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let n = c.len();
    let mut out = String::with_capacity(src.len());
    let blank = |out: &mut String, s: &[char]| {
        for &ch in s {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    let mut i = 0;
    while i < n {
        let ch = c[i];
        let next = c.get(i + 1).copied();
        if ch == '/' && next == Some('/') {
            let end = (i..n).find(|&j| c[j] == '\n').unwrap_or(n);
            blank(&mut out, &c[i..end]);
            i = end;
        } else if ch == '/' && next == Some('*') {
            let (mut j, mut depth) = (i, 0usize);
            while j < n {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    j += 1;
                }
            }
            blank(&mut out, &c[i..j.min(n)]);
            i = j.min(n);
        } else if is_ident_char(ch) {
            // A word: an identifier, a number, or the prefix of a string literal.
            let start = i;
            while i < n && is_ident_char(c[i]) {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            out.push_str(&word);
            let raw = matches!(word.as_str(), "r" | "br" | "cr");
            if raw && i < n && (c[i] == '"' || c[i] == '#') {
                let hashes = (i..n).take_while(|&j| c[j] == '#').count();
                if c.get(i + hashes) == Some(&'"') {
                    // r#"..."#: ends at a quote followed by as many hashes.
                    let body = i + hashes + 1;
                    let mut j = body;
                    while j < n && !(c[j] == '"' && (1..=hashes).all(|k| c.get(j + k) == Some(&'#'))) {
                        j += 1;
                    }
                    let end = (j + 1 + hashes).min(n);
                    literal(&mut out, &c[i..end], &c[body..j.min(n)]);
                    i = end;
                }
            } else if matches!(word.as_str(), "b" | "c") && i < n && c[i] == '"' {
                let end = string_end(&c, i);
                literal(&mut out, &c[i..end], &c[i + 1..end.saturating_sub(1).max(i + 1)]);
                i = end;
            }
        } else if ch == '"' {
            let end = string_end(&c, i);
            literal(&mut out, &c[i..end], &c[i + 1..end.saturating_sub(1).max(i + 1)]);
            i = end;
        } else if ch == '\'' {
            // A character literal ('x', '\n', '\u{..}') or a lifetime ('a, 'static).
            let end = if next == Some('\\') {
                (i + 3..n).find(|&j| c[j] == '\'').map_or(n, |j| j + 1)
            } else if c.get(i + 2) == Some(&'\'') {
                i + 3
            } else {
                i + 1
            };
            if end == i + 1 {
                out.push('\'');
            } else {
                out.push('\'');
                blank(&mut out, &c[i + 1..end - 1]);
                out.push('\'');
            }
            i = end;
        } else {
            out.push(ch);
            i += 1;
        }
    }
    out
}

/// The index after the string literal whose opening quote is at `i`.
fn string_end(c: &[char], i: usize) -> usize {
    let mut j = i + 1;
    while j < c.len() {
        match c[j] {
            '\\' => j += 2,
            '"' => return j + 1,
            _ => j += 1,
        }
    }
    c.len()
}

/// Write a literal: kept whole when its body is a path, else blanked whole (so the only
/// quotes left in the code open a path).
fn literal(out: &mut String, whole: &[char], body: &[char]) {
    let text: String = body.iter().collect();
    if is_path_text(&text) {
        out.extend(whole);
    } else {
        out.extend(whole.iter().map(|&ch| if ch == '\n' { '\n' } else { ' ' }));
    }
}

/// `code` (from [`code_of`]) with every item under `#[cfg(test)]` blanked, from the
/// attribute to the item's end: the first `;` at its own level, or the brace that
/// closes its body (for `const`, `static`, `use`, `let` and `type`, only the `;`).
fn strip_test_items(code: &str) -> String {
    const ATTR: &str = "#[cfg(test)]";
    let c: Vec<char> = code.chars().collect();
    let mut out = c.clone();
    let attr: Vec<char> = ATTR.chars().collect();
    let mut i = 0;
    while i + attr.len() <= c.len() {
        if c[i..i + attr.len()] != attr[..] {
            i += 1;
            continue;
        }
        let end = item_end(&c, i + attr.len());
        for ch in &mut out[i..end] {
            if *ch != '\n' {
                *ch = ' ';
            }
        }
        i = end;
    }
    out.into_iter().collect()
}

/// Where the item that starts at or after `i` (after its attributes) ends.
fn item_end(c: &[char], mut i: usize) -> usize {
    let n = c.len();
    loop {
        while i < n && c[i].is_whitespace() {
            i += 1;
        }
        if i + 1 < n && c[i] == '#' && c[i + 1] == '[' {
            let mut depth = 0i32;
            while i < n {
                match c[i] {
                    '[' => depth += 1,
                    ']' => {
                        depth -= 1;
                        if depth == 0 {
                            i += 1;
                            break;
                        }
                    }
                    _ => {}
                }
                i += 1;
            }
        } else {
            break;
        }
    }
    // The item's keyword, after its visibility (`pub`, `pub(crate)`, ...).
    let head: String = c[i..(i + 120).min(n)].iter().collect();
    let mut head = head.as_str();
    if let Some(rest) = head.strip_prefix("pub") {
        head = rest.trim_start();
        if head.starts_with('(') {
            head = head.split_once(')').map_or("", |(_, r)| r);
        }
    }
    let mut words = head.split(|ch: char| !is_ident_char(ch)).filter(|w| !w.is_empty());
    let (first, second) = (words.next().unwrap_or(""), words.next().unwrap_or(""));
    let semicolon_only = matches!(first, "const" | "static" | "use" | "let" | "type") && second != "fn";
    let mut depth = 0i32;
    while i < n {
        match c[i] {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => {
                depth -= 1;
                if depth < 0 {
                    return i; // the end of the enclosing block: the item was the last in it
                }
                if depth == 0 && c[i] == '}' && !semicolon_only {
                    return i + 1;
                }
            }
            ';' if depth == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    n
}

// ---------------------------------------------------------------------------------
// Tokens, module tree, paths.

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Word(String),
    /// `::`
    Sep,
    Punct(char),
}

/// Tokens of blanked code, each with its line (from 1).
fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let c: Vec<char> = code.chars().collect();
    let (mut out, mut line, mut i) = (Vec::new(), 1, 0);
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if is_ident_char(ch) {
            let start = i;
            while i < c.len() && is_ident_char(c[i]) {
                i += 1;
            }
            out.push((Tok::Word(c[start..i].iter().collect()), line));
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push((Tok::Sep, line));
            i += 2;
        } else if ch == '"' {
            // A literal kept by `code_of`: a path, read as its words.
            let end = string_end(&c, i);
            let text: String = c[i + 1..end - 1].iter().collect();
            for (k, part) in text.split("::").enumerate() {
                if k > 0 {
                    out.push((Tok::Sep, line));
                }
                out.push((Tok::Word(part.to_string()), line));
            }
            out.push((Tok::Punct(';'), line));
            i = end;
        } else {
            out.push((Tok::Punct(ch), line));
            i += 1;
        }
    }
    out
}

fn word(t: Option<&(Tok, usize)>) -> Option<&str> {
    match t {
        Some((Tok::Word(w), _)) => Some(w),
        _ => None,
    }
}

/// A path with its alias (the name it binds in a `use`; None for a glob).
type UsePath = (Vec<String>, Option<String>);

/// Parse the path tree at `toks[i..]` (`a::b::{c, d::e as f, self}`, `a::*`): every
/// leaf path, and the index after the tree.
fn parse_tree(toks: &[(Tok, usize)], mut i: usize) -> (Vec<UsePath>, usize) {
    let mut prefix = Vec::new();
    loop {
        match toks.get(i).map(|t| &t.0) {
            Some(Tok::Word(w)) if w != "as" => {
                prefix.push(w.clone());
                i += 1;
                if toks.get(i).map(|t| &t.0) == Some(&Tok::Sep) {
                    i += 1;
                    continue;
                }
                let mut alias = prefix.last().cloned();
                if word(toks.get(i)) == Some("as") {
                    alias = word(toks.get(i + 1)).map(str::to_string);
                    i += 2;
                }
                if prefix.last().map(String::as_str) == Some("self") {
                    prefix.pop();
                    // `a::{self}` binds `a` (the group's caller knows it when `prefix` is empty)
                    if alias.as_deref() == Some("self") && !prefix.is_empty() {
                        alias = prefix.last().cloned();
                    }
                }
                return (vec![(prefix, alias)], i);
            }
            Some(Tok::Punct('*')) => return (vec![(prefix, None)], i + 1),
            Some(Tok::Punct('{')) => {
                i += 1;
                let mut all = Vec::new();
                loop {
                    match toks.get(i).map(|t| &t.0) {
                        Some(Tok::Punct('}')) => return (all, i + 1),
                        Some(Tok::Punct(',')) => i += 1,
                        None => return (all, i),
                        _ => {
                            let (sub, next) = parse_tree(toks, i);
                            for (p, a) in sub {
                                let a = if a.as_deref() == Some("self") && p.is_empty() {
                                    prefix.last().cloned()
                                } else {
                                    a
                                };
                                all.push(([prefix.clone(), p].concat(), a));
                            }
                            if next == i {
                                i += 1;
                            } else {
                                i = next;
                            }
                        }
                    }
                }
            }
            _ => return (vec![(prefix, None)], i),
        }
    }
}

/// One module of the library: where its children's files are, what it declares.
#[derive(Default, Debug)]
struct Module {
    children: BTreeSet<String>,
    /// Names bound by its `use` items: name -> the absolute path (None: outside the crate).
    uses: BTreeMap<String, Option<Vec<String>>>,
}

/// A path from `crate::` or `super::` found in a module: the module it is written in,
/// the path as written, and where.
struct Ref {
    from: Vec<String>,
    path: Vec<String>,
    at: String,
}

/// The library's modules (by path from the root), the paths they reference and the
/// files compiled into it.
#[derive(Default)]
struct Crate {
    modules: BTreeMap<Vec<String>, Module>,
    refs: Vec<Ref>,
    files: BTreeSet<PathBuf>,
}

/// The file of module `name` declared in a module whose children live in `dir`.
fn child_file(dir: &Path, name: &str) -> Option<PathBuf> {
    [dir.join(format!("{name}.rs")), dir.join(name).join("mod.rs")].into_iter().find(|p| p.is_file())
}

/// Make `path`, written in module `at`, absolute (None: it leaves the crate).
fn absolute(krate: &Crate, at: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut base: Vec<String> = at.to_vec();
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some("self") => rest = &rest[1..],
        Some("super") => {
            while rest.first().map(String::as_str) == Some("super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        Some(first) => {
            let m = krate.modules.get(at)?;
            if !m.children.contains(first) {
                return None; // another crate (std, serde, oracles, ...)
            }
        }
        None => {}
    }
    Some([base, rest.to_vec()].concat())
}

impl Crate {
    fn read() -> Crate {
        let mut krate = Crate::default();
        krate.read_file(&src().join("lib.rs"), Vec::new(), src());
        krate
    }

    fn read_file(&mut self, file: &Path, path: Vec<String>, dir: PathBuf) {
        let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        self.files.insert(file.to_path_buf());
        let code = strip_test_items(&code_of(&text));
        let toks = tokens(&code);
        let rel = file.strip_prefix(src().parent().unwrap()).unwrap_or(file).display().to_string();
        // The module stack: (path, its children's directory, the brace depth of its body).
        let mut stack: Vec<(Vec<String>, PathBuf, i32)> = vec![(path, dir, 0)];
        let mut depth = 0i32;
        let mut uses: Vec<(Vec<String>, Vec<UsePath>)> = Vec::new();
        let mut i = 0;
        while i < toks.len() {
            let (tok, line) = (&toks[i].0, toks[i].1);
            let here = stack.last().unwrap().clone();
            match tok {
                Tok::Punct('{') => depth += 1,
                Tok::Punct('}') => {
                    depth -= 1;
                    if stack.len() > 1 && depth < here.2 {
                        stack.pop();
                    }
                }
                Tok::Word(w) if w == "mod" => {
                    if let (Some(name), Some((next, _))) = (word(toks.get(i + 1)), toks.get(i + 2)) {
                        let child: Vec<String> = [here.0.clone(), vec![name.to_string()]].concat();
                        self.modules.entry(here.0.clone()).or_default().children.insert(name.to_string());
                        if *next == Tok::Punct(';') {
                            let f = child_file(&here.1, name)
                                .unwrap_or_else(|| panic!("{rel}:{line}: no file for `mod {name};`"));
                            let child_dir = if f.ends_with("mod.rs") {
                                f.parent().unwrap().to_path_buf()
                            } else {
                                here.1.join(name)
                            };
                            self.read_file(&f, child, child_dir);
                        } else if *next == Tok::Punct('{') {
                            depth += 1;
                            stack.push((child, here.1.join(name), depth));
                            i += 3;
                            continue;
                        }
                    }
                }
                Tok::Word(w) if w == "use" && depth == here.2 => {
                    // The names it binds; its paths from `crate::` or `super::` are
                    // references too, read below when the loop reaches them.
                    uses.push((here.0.clone(), parse_tree(&toks, i + 1).0));
                }
                Tok::Word(w) if (w == "crate" || w == "super") && toks.get(i + 1).map(|t| &t.0) == Some(&Tok::Sep) => {
                    let starts = i == 0 || toks[i - 1].0 != Tok::Sep;
                    if starts {
                        let (tree, next) = parse_tree(&toks, i);
                        for (p, _) in tree {
                            self.refs.push(Ref { from: here.0.clone(), path: p, at: format!("{rel}:{line}") });
                        }
                        i = next;
                        continue;
                    }
                }
                _ => {}
            }
            i += 1;
        }
        self.modules.entry(stack[0].0.clone()).or_default();
        for (at, tree) in uses {
            for (p, alias) in tree {
                let Some(name) = alias else { continue };
                let target = absolute(self, &at, &p);
                self.modules.entry(at.clone()).or_default().uses.insert(name, target);
            }
        }
    }

    /// The module that defines what the absolute `path` names: the deepest module of
    /// the crate the path reaches (the root, `[]`, for a name of `lib.rs`; the module
    /// it passes last for a name it takes from another crate, as `bounds` for
    /// `crate::bounds::Cut`, the `oracles` crate's).
    fn resolve(&self, path: &[String], hops: usize) -> Option<Vec<String>> {
        let mut m: Vec<String> = Vec::new();
        for (k, seg) in path.iter().enumerate() {
            let module = self.modules.get(&m)?;
            if module.children.contains(seg) {
                m.push(seg.clone());
            } else if let Some(target) = module.uses.get(seg) {
                let Some(target) = target else { return Some(m) };
                if hops > 16 || target.as_slice() == &path[..=k] {
                    return Some(m);
                }
                return self.resolve(&[target.clone(), path[k + 1..].to_vec()].concat(), hops + 1);
            } else {
                return Some(m);
            }
        }
        Some(m)
    }

    /// The graph among the top-level modules, and per top-level module the one among
    /// its files.
    fn graphs(&self) -> (Graph, BTreeMap<String, Graph>) {
        let (mut top, mut inner) = (Graph::new(), BTreeMap::<String, Graph>::new());
        for r in &self.refs {
            let Some(abs) = absolute(self, &r.from, &r.path) else { continue };
            let Some(to) = self.resolve(&abs, 0) else { continue };
            let (Some(a), Some(b)) = (r.from.first(), to.first()) else { continue };
            if a != b {
                top.entry(a.clone()).or_default().entry(b.clone()).or_insert_with(|| r.at.clone());
            }
            if let ([c1, x, ..], [c2, y, ..]) = (r.from.as_slice(), to.as_slice()) {
                if c1 == c2 && x != y {
                    let g = inner.entry(c1.clone()).or_default();
                    g.entry(x.clone()).or_default().entry(y.clone()).or_insert_with(|| r.at.clone());
                }
            }
        }
        (top, inner)
    }
}

// ---------------------------------------------------------------------------------
// Cycles.

/// A cycle of `g` if it has one, as its nodes with the first repeated at the end.
fn find_cycle(g: &Graph) -> Option<Vec<String>> {
    // 0: unseen, 1: on the current path, 2: done
    fn visit(g: &Graph, n: &str, state: &mut BTreeMap<String, u8>, path: &mut Vec<String>) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        path.push(n.to_string());
        for m in g.get(n).into_iter().flat_map(|e| e.keys()) {
            match state.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = path.iter().position(|x| x == m).unwrap();
                    let mut cycle = path[start..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(g, m, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in g.keys() {
        if state.get(n.as_str()).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(g, n, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

/// The cycle's edges, each with where it is made.
fn describe(g: &Graph, cycle: &[String]) -> String {
    cycle.windows(2).map(|w| format!("  {} -> {} ({})", w[0], w[1], g[&w[0]][&w[1]])).collect::<Vec<_>>().join("\n")
}

fn graph(edges: &[(&str, &str)]) -> Graph {
    let mut g = Graph::new();
    for (a, b) in edges {
        g.entry(a.to_string()).or_default().insert(b.to_string(), "made up".into());
    }
    g
}

fn show(g: &Graph) -> String {
    g.iter()
        .map(|(a, e)| format!("  {a} -> {}", e.keys().cloned().collect::<Vec<_>>().join(", ")))
        .collect::<Vec<_>>()
        .join("\n")
}

// ---------------------------------------------------------------------------------
// The tests.

/// The layers, in the order data flows through them.
const LAYERS: &[&str] = &["io", "model", "bounds", "external", "cases", "judge", "gate", "search", "tools", "cli"];

/// Every edge of `top` that runs from a layer to a later one (or names a module that is
/// no layer), with where it is made.
fn back_edges(top: &Graph) -> Vec<String> {
    let rank = |m: &str| LAYERS.iter().position(|l| *l == m);
    let mut out = Vec::new();
    for (a, edges) in top {
        for (b, at) in edges {
            match (rank(a), rank(b)) {
                (Some(i), Some(j)) if j < i => {}
                (Some(_), Some(_)) => out.push(format!("  {a} -> {b} ({at}): {b} comes after {a}")),
                _ => out.push(format!("  {a} -> {b} ({at}): not a layer of {LAYERS:?}")),
            }
        }
    }
    out
}

#[test]
fn every_import_runs_to_an_earlier_layer() {
    let krate = Crate::read();
    let (top, _) = krate.graphs();
    eprintln!("layers:\n{}", show(&top));
    let tops: BTreeSet<&str> = krate.modules.keys().filter_map(|m| m.first()).map(|m| m.as_str()).collect();
    let strays: Vec<&&str> = tops.iter().filter(|m| !LAYERS.contains(m)).collect();
    assert!(strays.is_empty(), "top-level modules that are no layer of {LAYERS:?}: {strays:?}");
    let back = back_edges(&top);
    assert!(back.is_empty(), "imports against the layer order:\n{}", back.join("\n"));
    if let Some(c) = find_cycle(&top) {
        panic!("an import loop among the layers:\n{}", describe(&top, &c));
    }
}

#[test]
fn no_import_loop_among_the_files_of_a_layer() {
    let (_, inner) = Crate::read().graphs();
    for (layer, g) in &inner {
        eprintln!("files of src/{layer}/:\n{}", show(g));
        if let Some(c) = find_cycle(g) {
            panic!("an import loop among the files of src/{layer}/:\n{}", describe(g, &c));
        }
    }
}

#[test]
fn the_order_check_reports_an_edge_against_the_order() {
    let g = graph(&[("judge", "model"), ("cases", "gate"), ("gate", "stray")]);
    let back = back_edges(&g);
    assert_eq!(back.len(), 2, "{back:?}");
    assert!(back[0].contains("cases -> gate") && back[1].contains("gate -> stray"), "{back:?}");
}

#[test]
fn the_finder_reports_a_made_up_loop() {
    let g = graph(&[("a", "b"), ("b", "c"), ("c", "a"), ("c", "d"), ("d", "e")]);
    let c = find_cycle(&g).expect("a -> b -> c -> a is a loop");
    assert_eq!(c.first(), c.last(), "{c:?}");
    assert_eq!(c.len(), 4, "{c:?}");
    for w in c.windows(2) {
        assert!(g[&w[0]].contains_key(&w[1]), "{c:?}: no edge {} -> {}", w[0], w[1]);
    }
    assert!(describe(&g, &c).contains("-> a (made up)"), "{}", describe(&g, &c));
    assert_eq!(find_cycle(&graph(&[("a", "a")])), Some(vec!["a".to_string(), "a".to_string()]));
    assert_eq!(find_cycle(&graph(&[("a", "b"), ("b", "c"), ("a", "c"), ("d", "a")])), None);
}

#[test]
fn the_reader_blanks_comments_literals_and_test_items() {
    let src = r##"// crate::a in a comment
/* crate::b /* nested */ crate::c */
use crate::d::{self, e::F as G, h::*};
const S: &str = "crate::i::j and more"; const T: &str = r#"crate::k, "quoted""#;
#[serde(with = "crate::with_helper")]
fn f<'a>(x: &'a str) -> char { let _ = crate::l::m(x); '{' }
#[cfg(test)]
static GUARD: Thing = Thing { on: true };
#[cfg(test)]
mod tests { use crate::n; fn g() { crate::o::p(); } }
fn after() { super::q::r(); }
"##;
    let code = strip_test_items(&code_of(src));
    assert_eq!(code.lines().count(), src.lines().count(), "lines are kept");
    for gone in ["crate::a", "crate::b", "crate::c", "crate::i", "crate::k", "crate::n", "crate::o", "GUARD"] {
        assert!(!code.contains(gone), "{gone} is still there:\n{code}");
    }
    for kept in ["crate::d", "\"crate::with_helper\"", "crate::l::m", "super::q::r", "fn after"] {
        assert!(code.contains(kept), "{kept} is gone:\n{code}");
    }
    let toks = tokens(&code);
    let at = toks.iter().position(|t| t.0 == Tok::Word("use".into())).unwrap();
    let (tree, _) = parse_tree(&toks, at + 1);
    let want: Vec<UsePath> = vec![
        (vec!["crate".into(), "d".into()], Some("d".into())),
        (vec!["crate".into(), "d".into(), "e".into(), "F".into()], Some("G".into())),
        (vec!["crate".into(), "d".into(), "h".into()], None),
    ];
    assert_eq!(tree, want);
}

#[test]
fn the_reader_sees_the_real_edges() {
    let krate = Crate::read();
    let (top, inner) = krate.graphs();
    let has = |g: &Graph, a: &str, b: &str| g.get(a).is_some_and(|e| e.contains_key(b));
    // a use, an inline path, a serde path in a string, a re-export of lib.rs
    for (a, b) in [("search", "gate"), ("gate", "bounds"), ("search", "io"), ("judge", "model"), ("cli", "tools")] {
        assert!(has(&top, a, b), "{a} -> {b} not seen:\n{}", show(&top));
    }
    // `super::` paths, and names re-exported by gate/mod.rs
    let gate = &inner["gate"];
    for (a, b) in [("report", "row"), ("merge", "report"), ("strength", "row"), ("baseline", "report")] {
        assert!(has(gate, a, b), "gate/{a} -> gate/{b} not seen:\n{}", show(gate));
    }
    // test code is left out: files declared under #[cfg(test)] are not read at all
    assert!(!krate.modules.contains_key(&vec!["bounds".to_string(), "testkit".to_string()]));
    // a name lib.rs takes from another crate lands in no module (`crate::Interval` is
    // oracles'); one it re-exports from a module, in that module
    assert_eq!(krate.resolve(&["Interval".to_string()], 0), Some(vec![]));
    assert_eq!(krate.resolve(&["Gate".to_string()], 0), Some(vec!["gate".to_string(), "builder".to_string()]));
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The test scaffolding kept in `src/` (the bounds' test kit and shared grid and row
/// tests, the old code kept verbatim for the bit-identity tests, the extra grid cases,
/// the tests kept in files of their own) is declared under `#[cfg(test)]`, so the
/// library never compiles it.
#[test]
fn test_scaffolding_is_not_compiled_into_the_library() {
    let krate = Crate::read();
    let mut all = Vec::new();
    rust_files(&src(), &mut all);
    let scaffolding: Vec<&PathBuf> = all
        .iter()
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            matches!(name.as_ref(), "testkit.rs" | "safe_old.rs" | "grid_cases.rs" | "tests.rs")
                || name.ends_with("_tests.rs")
        })
        .collect();
    let named = |p: &PathBuf| p.strip_prefix(src()).unwrap().display().to_string();
    let names: BTreeSet<String> = scaffolding.iter().map(|p| named(p)).collect();
    for want in ["bounds/testkit.rs", "bounds/grid_tests.rs", "bounds/row_tests.rs"] {
        assert!(names.contains(want), "{want} not found among {names:?}");
    }
    // No verbatim old code: the bit-identity tests compare fingerprints recorded from it.
    assert!(!names.iter().any(|n| n.ends_with("safe_old.rs")), "old code kept in src/: {names:?}");
    let compiled: Vec<String> = scaffolding.into_iter().filter(|p| krate.files.contains(*p)).map(named).collect();
    assert!(
        compiled.is_empty(),
        "test scaffolding compiled into the library (declare it under #[cfg(test)]): {compiled:?}"
    );
    // the reader does reach the library's files
    assert!(krate.files.contains(&src().join("bounds/wu2013.rs")) && krate.files.len() > 50, "{}", krate.files.len());
}
