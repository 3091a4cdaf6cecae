//! The documentation: README.md and the book in docs/.
//!
//! - Every relative link reaches a file of the repository, and a `#anchor` a heading of
//!   the file it names (GitHub's slug rule). Nothing points outside the repository: no
//!   http(s) link, no absolute path, no `..` above the root.
//! - Every documented command line (`cargo run --release -- COMMAND ...` or `cullproof
//!   COMMAND ...`, in a shell or YAML code block or in inline code) parses: the built binary
//!   is run with the same arguments and `--help` appended. clap reads the arguments in
//!   order and stops at `--help`, so an unknown flag or a malformed value before it fails
//!   (exit 2), while nothing is run. Placeholders (`ID`, `N`, `FILE.json`, ...) are replaced
//!   by a value of their kind, optional parts in `[...]` are kept, `a|b` takes the first
//!   alternative; a line with shell variables, `<...>` or an elision is skipped and listed.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Component, Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md, corpus/README.md and every Markdown file under docs/, sorted.
fn markdown_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "md") {
                out.push(p);
            }
        }
    }
    let root = root();
    let mut files = vec![root.join("README.md")];
    if root.join("corpus/README.md").exists() {
        files.push(root.join("corpus/README.md"));
    }
    walk(&root.join("docs"), &mut files);
    files
}

fn rel(path: &Path) -> String {
    path.strip_prefix(root()).unwrap_or(path).display().to_string()
}

/// One piece of a Markdown file: a fenced code block, or a run of text lines without a
/// blank line (a paragraph, a list, a table, a heading).
struct Block {
    fenced: bool,
    info: String,
    /// 1-based line of the first line of `text` in the file.
    line: usize,
    text: String,
}

fn blocks(source: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut para: Option<Block> = None;
    let mut fence: Option<(char, usize, usize, Block)> = None; // marker, length, indent, block
    for (i, line) in source.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        let marker = trimmed.chars().next().filter(|c| *c == '`' || *c == '~');
        let run = marker.map_or(0, |m| trimmed.chars().take_while(|c| *c == m).count());
        if let Some((m, len, ind, mut block)) = fence.take() {
            if marker == Some(m) && run >= len && trimmed[run..].trim().is_empty() {
                out.push(block);
            } else {
                let strip = line.len() - line.trim_start().len();
                block.text.push_str(&line[strip.min(ind)..]);
                block.text.push('\n');
                fence = Some((m, len, ind, block));
            }
            continue;
        }
        if run >= 3 {
            out.extend(para.take());
            let info = trimmed[run..].trim().to_string();
            fence =
                Some((marker.unwrap(), run, indent, Block { fenced: true, info, line: i + 2, text: String::new() }));
            continue;
        }
        if trimmed.is_empty() {
            out.extend(para.take());
            continue;
        }
        let p =
            para.get_or_insert_with(|| Block { fenced: false, info: String::new(), line: i + 1, text: String::new() });
        p.text.push_str(line);
        p.text.push('\n');
    }
    out.extend(para);
    if let Some((_, _, _, block)) = fence {
        panic!("a code block opened at line {} is never closed", block.line - 1);
    }
    out
}

/// The inline code spans of a text block: (byte range of the span with its backticks, its
/// content with line breaks read as spaces).
fn code_spans(text: &str) -> Vec<(std::ops::Range<usize>, String)> {
    let bytes = text.as_bytes();
    let run_at = |i: usize| bytes[i..].iter().take_while(|b| **b == b'`').count();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'`' {
            i += 1;
            continue;
        }
        let n = run_at(i);
        let start = i + n;
        let mut j = start;
        let mut close = None;
        while j < bytes.len() {
            if bytes[j] == b'`' {
                let m = run_at(j);
                if m == n {
                    close = Some(j);
                    break;
                }
                j += m;
            } else {
                j += 1;
            }
        }
        match close {
            Some(end) => {
                let content = text[start..end].replace('\n', " ");
                let strip = content.len() > 2 && content.starts_with(' ') && content.ends_with(' ');
                let content = if strip { content[1..content.len() - 1].to_string() } else { content };
                spans.push((i..end + n, content));
                i = end + n;
            }
            None => i = start,
        }
    }
    spans
}

/// The text with its inline code spans blanked (line breaks kept), for finding links.
fn without_code(text: &str) -> String {
    let mut out = text.as_bytes().to_vec();
    for (range, _) in code_spans(text) {
        for b in &mut out[range] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// GitHub's anchor for a heading: the rendered text, lower case, every character other
/// than a letter, a digit, a space, '-' or '_' dropped, spaces made '-'.
fn slug(heading: &str) -> String {
    // The rendered text: a link shows its text, code shows its content.
    let mut text = String::new();
    let mut rest = heading;
    while let Some(open) = rest.find('[') {
        let Some(mid) = rest[open..].find("](") else { break };
        let Some(close) = rest[open + mid..].find(')') else { break };
        text.push_str(&rest[..open]);
        text.push_str(&rest[open + 1..open + mid]);
        rest = &rest[open + mid + close + 1..];
    }
    text.push_str(rest);
    text.to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown file's headings (a repeated slug gets -1, -2, ... as on GitHub).
fn anchors(source: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for block in blocks(source).iter().filter(|b| !b.fenced) {
        for line in block.text.lines() {
            let hashes = line.chars().take_while(|c| *c == '#').count();
            if (1..=6).contains(&hashes) && line[hashes..].starts_with(' ') {
                let title = line[hashes..].trim().trim_end_matches('#').trim();
                let base = slug(title);
                let n = seen.entry(base.clone()).or_insert(0);
                out.insert(if *n == 0 { base.clone() } else { format!("{base}-{n}") });
                *n += 1;
            }
        }
    }
    out
}

/// The targets of the links and images of a text block, with their lines.
fn link_targets(block: &Block) -> Vec<(usize, String)> {
    let text = without_code(&block.text);
    let mut out = Vec::new();
    let line_of = |at: usize| block.line + text[..at].matches('\n').count();
    let mut from = 0;
    while let Some(k) = text[from..].find("](") {
        let start = from + k + 2;
        let Some(len) = text[start..].find(')') else { break };
        let target = text[start..start + len].trim();
        // A title after the address ("file.md "Title"") is not part of it.
        let target = target.split_whitespace().next().unwrap_or("").trim_matches(|c| c == '<' || c == '>');
        out.push((line_of(start), target.to_string()));
        from = start + len;
    }
    // Reference definitions: [label]: target
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with('[') {
            if let Some(k) = t.find("]:") {
                let target = t[k + 2..].split_whitespace().next().unwrap_or("");
                out.push((block.line + i, target.to_string()));
            }
        }
    }
    out
}

/// `base` joined with the relative `target`, read lexically; None when it leaves the root.
fn resolve(base_dir: &Path, target: &str) -> Option<PathBuf> {
    let root = root();
    let mut parts: Vec<String> =
        base_dir.strip_prefix(&root).ok()?.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    for c in Path::new(target).components() {
        match c {
            Component::Normal(s) => parts.push(s.to_string_lossy().into_owned()),
            Component::CurDir => {}
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(parts.iter().fold(root, |p, s| p.join(s)))
}

#[test]
fn links_resolve_inside_the_repository() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for file in markdown_files() {
        let source = std::fs::read_to_string(&file).unwrap();
        let name = rel(&file);
        // Nothing in the documentation may point outside the repository.
        for (i, line) in source.lines().enumerate() {
            if line.contains("http://") || line.contains("https://") {
                problems
                    .push(format!("{name}:{}: an http(s) address (nothing may point outside the repository)", i + 1));
            }
        }
        for block in blocks(&source).iter().filter(|b| !b.fenced) {
            for (line, target) in link_targets(block) {
                checked += 1;
                let at = format!("{name}:{line}: link `{target}`");
                if target.is_empty() {
                    problems.push(format!("{at}: empty"));
                    continue;
                }
                if target.contains("://") || target.starts_with("//") || target.starts_with("mailto:") {
                    problems.push(format!("{at}: points outside the repository"));
                    continue;
                }
                let (path, anchor) = match target.split_once('#') {
                    Some((p, a)) => (p, Some(a)),
                    None => (target.as_str(), None),
                };
                let dest = if path.is_empty() {
                    Some(file.clone())
                } else if path.starts_with('/') {
                    None
                } else {
                    resolve(file.parent().unwrap(), path)
                };
                let Some(dest) = dest else {
                    problems.push(format!("{at}: leaves the repository (use a path relative to the file)"));
                    continue;
                };
                if !dest.exists() {
                    problems.push(format!("{at}: no such file {}", rel(&dest)));
                    continue;
                }
                if let Some(anchor) = anchor {
                    if dest.extension().is_some_and(|e| e == "md") {
                        let known = anchors(&std::fs::read_to_string(&dest).unwrap());
                        if !known.contains(anchor) {
                            problems.push(format!("{at}: no heading with anchor #{anchor} in {}", rel(&dest)));
                        }
                    } else {
                        problems.push(format!("{at}: an anchor into a file that is not Markdown"));
                    }
                }
            }
        }
    }
    println!("docs: {checked} links checked");
    assert!(checked >= 50, "only {checked} links found: is the link scanner broken?");
    assert!(problems.is_empty(), "{} broken link(s):\n{}", problems.len(), problems.join("\n"));
}

#[test]
fn the_contents_link_every_chapter() {
    let contents = root().join("docs/README.md");
    let source = std::fs::read_to_string(&contents).expect("docs/README.md, the book's table of contents");
    let linked: BTreeSet<PathBuf> = blocks(&source)
        .iter()
        .filter(|b| !b.fenced)
        .flat_map(link_targets)
        .filter_map(|(_, t)| resolve(&root().join("docs"), t.split('#').next().unwrap()))
        .collect();
    let missing: Vec<String> = markdown_files()
        .into_iter()
        .filter(|f| f.starts_with(root().join("docs")) && *f != contents && !linked.contains(f))
        .map(|f| rel(&f))
        .collect();
    assert!(missing.is_empty(), "docs/README.md does not link: {}", missing.join(", "));
}

/// Where a documented command line came from.
#[derive(Clone, Debug)]
struct Found {
    at: String,
    text: String,
}

/// The subcommand and arguments of a documented command line, after the program name;
/// None when the text holds none. A command is `cargo run --release -- ...` anywhere in
/// the text, or `cullproof` and a lower-case word at its start.
fn command_of(text: &str) -> Option<String> {
    const CARGO: &str = "cargo run --release -- ";
    let t = text.trim_start().trim_start_matches("$ ");
    let rest = if let Some(k) = text.find(CARGO) {
        &text[k + CARGO.len()..]
    } else {
        t.strip_prefix("cullproof ").filter(|r| r.starts_with(|c: char| c.is_ascii_lowercase()))?
    };
    // The command ends at a shell comment, a pipe, a list operator or a redirection.
    let mut end = rest.len();
    for stop in [" #", " || ", " && ", " | ", "; ", " > ", " >> ", " 2>", " < "] {
        if let Some(k) = rest.find(stop) {
            end = end.min(k);
        }
    }
    let cmd = rest[..end].trim();
    (!cmd.is_empty()).then(|| cmd.to_string())
}

/// Every documented command line of the Markdown files.
fn documented_commands() -> Vec<Found> {
    let mut out = Vec::new();
    for file in markdown_files() {
        let source = std::fs::read_to_string(&file).unwrap();
        let name = rel(&file);
        for block in blocks(&source) {
            if block.fenced {
                let lang = block.info.split_whitespace().next().unwrap_or("");
                if !matches!(lang, "" | "sh" | "bash" | "shell" | "console" | "yaml" | "yml") {
                    continue;
                }
                // Lines continued with a backslash are one command.
                let mut logical = String::new();
                let mut first = 0;
                for (i, line) in block.text.lines().enumerate() {
                    if logical.is_empty() {
                        first = i;
                    }
                    if let Some(head) = line.strip_suffix('\\') {
                        logical.push_str(head);
                        logical.push(' ');
                        continue;
                    }
                    logical.push_str(line);
                    if let Some(text) = command_of(&logical) {
                        out.push(Found { at: format!("{name}:{}", block.line + first), text });
                    }
                    logical.clear();
                }
            } else {
                for (range, span) in code_spans(&block.text) {
                    if let Some(text) = command_of(&span) {
                        let line = block.line + block.text[..range.start].matches('\n').count();
                        out.push(Found { at: format!("{name}:{line}"), text });
                    }
                }
            }
        }
    }
    out
}

/// Shell words: spaces split, single and double quotes group.
fn shell_words(s: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut quote: Option<char> = None;
    for c in s.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => word.push(c),
            None if c == '\'' || c == '"' => {
                quote = Some(c);
                in_word = true;
            }
            None if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            None => {
                word.push(c);
                in_word = true;
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
}

/// A value for each placeholder the documentation uses.
fn placeholder(p: &str) -> Option<&'static str> {
    Some(match p {
        "ID" => "bbox-safe",
        "ID0" => "bbox",
        "IDS" => "bbox,bbox-safe",
        "KIND" => "shrink",
        "N" => "10",
        "S" => "1",
        "SECS" | "SECONDS" => "1",
        "R" => "static",
        "PX" => "4",
        "J" => "1",
        "B" => "100",
        "M" => "0.001",
        "K/N" => "0/2",
        "F" | "FILE.json" | "shard-K.json" => "report.json",
        "FILE" | "CASE.json" => "case.json",
        "FILE.obj" => "scene.obj",
        "PATH" => "corpus/cases",
        "OUT" | "DIR" => "out",
        "OUT.svg" => "out.svg",
        "BITS" => "8",
        "SET" => "centres",
        "gridN" => "grid8",
        "WxH+GUARD" | "WxH+G" => "1920x1080+64",
        "LIB.so" => "./lib.so",
        "COMMAND" => "true",
        _ => return None,
    })
}

/// Still a placeholder: a word in capitals (`X`, `TILE`), maybe with a file extension.
fn looks_like_placeholder(p: &str) -> bool {
    let stem = p.split('.').next().unwrap_or("");
    stem.chars().any(|c| c.is_ascii_uppercase())
        && stem.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

/// One word of a command with its placeholders replaced; Err(reason) to skip the line.
fn substitute(word: &str) -> Result<String, String> {
    if let Some(v) = placeholder(word) {
        return Ok(v.to_string());
    }
    if word.contains('|') && word.len() > 1 {
        // Alternatives: the first one that is no placeholder, else the first one filled in.
        let alts: Vec<&str> = word.split('|').filter(|a| !a.is_empty()).collect();
        let pick = alts.iter().find(|a| !looks_like_placeholder(a) && placeholder(a).is_none()).unwrap_or(&alts[0]);
        return substitute(pick);
    }
    if word.contains(',') {
        let parts: Result<Vec<String>, String> = word.split(',').filter(|p| !p.is_empty()).map(substitute).collect();
        return Ok(parts?.join(","));
    }
    if word.contains('/') && !word.starts_with('.') {
        let parts: Result<Vec<String>, String> =
            word.split('/').map(|p| if p.is_empty() { Ok(String::new()) } else { substitute(p) }).collect();
        return Ok(parts?.join("/"));
    }
    if looks_like_placeholder(word) {
        return Err(format!("placeholder `{word}`"));
    }
    Ok(word.to_string())
}

/// The arguments to run for a documented command; Err(reason) when it cannot be filled in.
fn arguments(cmd: &str) -> Result<Vec<String>, String> {
    if cmd.contains('$') {
        return Err("a shell variable".into());
    }
    if cmd.contains('<') || cmd.contains('>') {
        return Err("a `<...>` placeholder".into());
    }
    let mut args = Vec::new();
    for word in shell_words(cmd) {
        // Optional parts are kept: `[--time SECS]` -> `--time SECS`, `ID[,ID...]` -> `ID,ID`.
        let mut word = word.replace(['[', ']'], "");
        if word.is_empty() {
            continue;
        }
        if word.contains("...") {
            let head = word.trim_end_matches("...").trim_end_matches(',');
            let last = head.rsplit([',', '/']).next().unwrap_or("");
            if head.is_empty() || !looks_like_placeholder(last) {
                return Err(format!("an elision in `{word}`"));
            }
            word = head.to_string();
        }
        // `--flag=value`: fill in the value.
        if let Some((flag, value)) = word.split_once('=').filter(|(f, _)| f.starts_with("--")) {
            args.push(format!("{flag}={}", substitute(value)?));
            continue;
        }
        args.push(substitute(&word)?);
    }
    Ok(args)
}

#[test]
fn documented_command_lines_parse() {
    let bin = env!("CARGO_BIN_EXE_cullproof");
    let found = documented_commands();
    // Distinct argument lists, with where each was found.
    let mut runs: BTreeMap<Vec<String>, Vec<Found>> = BTreeMap::new();
    let mut skipped: Vec<(Found, String)> = Vec::new();
    for f in &found {
        match arguments(&f.text) {
            Ok(args) => runs.entry(args).or_default().push(f.clone()),
            Err(why) => skipped.push((f.clone(), why)),
        }
    }
    let mut failures = Vec::new();
    for (args, places) in &runs {
        let out = Command::new(bin).args(args).arg("--help").output().unwrap();
        if !out.status.success() {
            let err = String::from_utf8_lossy(&out.stderr);
            let first: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).take(3).collect();
            failures.push(format!(
                "{}: `{}`\n    ran: cullproof {} --help\n    {}",
                places.iter().map(|p| p.at.as_str()).collect::<Vec<_>>().join(", "),
                places[0].text,
                args.join(" "),
                first.join("\n    ")
            ));
        }
    }
    println!(
        "docs: {} documented command lines found, {} checked ({} distinct), {} skipped",
        found.len(),
        found.len() - skipped.len(),
        runs.len(),
        skipped.len()
    );
    for (args, places) in &runs {
        println!("  checked {}: cullproof {}", places[0].at, args.join(" "));
    }
    for (f, why) in &skipped {
        println!("  skipped {}: `{}` ({why})", f.at, f.text);
    }
    assert!(runs.len() >= 20, "only {} distinct command lines checked: is the extraction broken?", runs.len());
    assert!(
        skipped.len() * 4 <= found.len(),
        "{} of {} command lines skipped: fill in their placeholders",
        skipped.len(),
        found.len()
    );
    assert!(
        failures.is_empty(),
        "{} documented command line(s) do not parse:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_extraction_reads_what_the_documents_write() {
    // Placeholders, optional parts, alternatives and elisions.
    assert_eq!(
        arguments("search --method ID [--time SECS --seed S]").unwrap(),
        ["search", "--method", "bbox-safe", "--time", "1", "--seed", "1"]
    );
    assert_eq!(arguments("replay [PATH...]").unwrap(), ["replay", "corpus/cases"]);
    assert_eq!(arguments("stability --family F|all").unwrap(), ["stability", "--family", "all"]);
    assert_eq!(arguments("search --method broken/KIND/ID").unwrap(), ["search", "--method", "broken/shrink/bbox-safe"]);
    assert_eq!(
        arguments("check --exec \"python3 examples/python/bbox_exec.py\" --method py-bbox").unwrap(),
        ["check", "--exec", "python3 examples/python/bbox_exec.py", "--method", "py-bbox"]
    );
    assert!(arguments("check --shard ${{ matrix.shard }}/4").is_err());
    assert!(arguments("check --method la2011,... --json F").is_err());
    assert!(arguments("tightness --focus-at X").is_err());
    // Where commands are found, and where they end.
    assert_eq!(command_of("cargo run --release -- check   # the gate").as_deref(), Some("check"));
    assert_eq!(command_of("- run: cargo run --release -- merge a.json || true").as_deref(), Some("merge a.json"));
    assert_eq!(command_of("cullproof replay FILE").as_deref(), Some("replay FILE"));
    assert_eq!(command_of("cullproof::Gate::new()"), None);
    assert_eq!(command_of("cargo run --release --example own_bound"), None);
    // Slugs as GitHub makes them.
    assert_eq!(slug("2.1 The three verdicts"), "21-the-three-verdicts");
    assert_eq!(slug("5. The `--second-chance` search"), "5-the---second-chance-search");
    assert_eq!(slug("7. The gate's power: `power`"), "7-the-gates-power-power");
    assert_eq!(slug("A [link](x.md) in it"), "a-link-in-it");
    // A misspelt flag fails to parse.
    let bin = env!("CARGO_BIN_EXE_cullproof");
    let status = Command::new(bin).args(["check", "--casess", "10", "--help"]).output().unwrap().status;
    assert!(!status.success(), "clap accepted an unknown flag before --help");
}
