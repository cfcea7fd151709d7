//! The crate's layers (docs/architecture.md), read from the imports of `src/`: every file
//! imports only from its own layer and the layers below, nothing goes through the crate
//! root's re-exports, and no files import each other in a loop.
//!
//! An import is any path into the crate in code (comments and strings do not count): a
//! `use` of `crate::`, `super::` or a child module, and a path such as
//! `crate::model::state::CmState` written inline. It names the file whose module is the
//! longest prefix of the path. The unit tests inside each file are held to the same rules.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The layers, lowest first, each with its top-level modules (folders of `src/`).
const LAYERS: [(&str, &[&str]); 8] = [
    ("base", &["base"]),
    ("model", &["profile", "model"]),
    (
        "kernels",
        &[
            "closed_form",
            "cluster",
            "cushion",
            "integrator",
            "table_phase",
            "tangential",
        ],
    ),
    ("solve", &["solve"]),
    ("scene", &["scene"]),
    ("outputs", &["outputs"]),
    ("apps", &["apps"]),
    ("front ends", &["cli"]),
];

/// A module path, `[]` for the crate root.
type Module = Vec<String>;

/// The source files of `src/` (but the binary's `main.rs`), by module path.
fn read_tree(src: &Path) -> BTreeMap<Module, String> {
    let mut files = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().and_then(|e| e.to_str()) != Some("rs") {
                continue;
            }
            let rel = path.strip_prefix(src).unwrap().with_extension("");
            let mut module: Module = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            match module.last().map(String::as_str) {
                Some("mod") | Some("lib") => {
                    module.pop();
                }
                Some("main") if module.len() == 1 => continue,
                _ => {}
            }
            files.insert(module, std::fs::read_to_string(&path).unwrap());
        }
    }
    files
}

/// The source with comments, string and character literals blanked (lifetimes kept).
fn code_only(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if (c == 'r' || c == 'b') && (i == 0 || !ident(b[i - 1])) && raw_start(&b, i) {
            // r"..", r#".."#, br"..": up to the quote followed by as many #.
            let mut j = i + 1 + usize::from(c == 'b');
            let mut hashes = 0;
            while b[j] == '#' {
                hashes += 1;
                j += 1;
            }
            j += 1;
            loop {
                if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                    i = j + 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                i += if b[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' && next == Some('\\') {
            i += 2;
            while i < b.len() && b[i] != '\'' {
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else if c == '\'' && b.get(i + 2) == Some(&'\'') {
            i += 3;
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Whether a raw string starts at `i` (`r"`, `r#`, `br"`, `br#`).
fn raw_start(b: &[char], i: usize) -> bool {
    let j = if b[i] == 'b' {
        if b.get(i + 1) != Some(&'r') {
            return false;
        }
        i + 2
    } else {
        i + 1
    };
    let mut k = j;
    while b.get(k) == Some(&'#') {
        k += 1;
    }
    b.get(k) == Some(&'"') && (k > j || b.get(j) == Some(&'"'))
}

/// Identifiers and the punctuation that paths and modules are made of.
fn tokens(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let chars: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(chars[start..i].iter().collect());
        } else if c == ':' && chars.get(i + 1) == Some(&':') {
            out.push("::".into());
            i += 2;
        } else {
            if "{};,*".contains(c) {
                out.push(c.to_string());
            } else if !c.is_whitespace() {
                out.push("#".into());
            }
            i += 1;
        }
    }
    out
}

/// The paths of a `use` tree starting at `t[*i]`, up to its end (`;`, or `,` / `}` of the
/// enclosing group).
fn use_tree(t: &[String], i: &mut usize, prefix: &[String], out: &mut Vec<Vec<String>>) {
    let mut path = prefix.to_vec();
    while *i < t.len() {
        match t[*i].as_str() {
            "::" => *i += 1,
            "{" => {
                *i += 1;
                while *i < t.len() && t[*i] != "}" {
                    use_tree(t, i, &path, out);
                    if *i < t.len() && t[*i] == "," {
                        *i += 1;
                    }
                }
                *i += 1;
                return;
            }
            ";" | "," | "}" => break,
            "as" => {
                out.push(path.clone());
                *i += 2;
                return;
            }
            "*" => *i += 1,
            seg => {
                if seg != "self" || path.is_empty() {
                    path.push(seg.to_string());
                }
                *i += 1;
            }
        }
    }
    out.push(path);
}

/// Every path into the crate that `code` (of the file of module `file`) writes, as the
/// module it starts from and its segments.
fn paths(file: &Module, code: &str) -> Vec<(Module, Vec<String>)> {
    let t = tokens(code);
    let mut out = Vec::new();
    // Inline modules (`mod tests { .. }`) by the brace depth they close at.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut children: BTreeSet<String> = BTreeSet::new();
    let mut depth = 0;
    let mut i = 0;
    let here = |inline: &[(String, usize)]| {
        let mut m = file.clone();
        m.extend(inline.iter().map(|(n, _)| n.clone()));
        m
    };
    while i < t.len() {
        match t[i].as_str() {
            "{" => depth += 1,
            "}" => {
                depth -= 1;
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
            }
            "mod" if i + 2 < t.len() => {
                if t[i + 2] == "{" {
                    inline.push((t[i + 1].clone(), depth));
                    depth += 1;
                    i += 3;
                    continue;
                }
                if inline.is_empty() {
                    children.insert(t[i + 1].clone());
                }
            }
            "use" => {
                i += 1;
                let mut trees = Vec::new();
                use_tree(&t, &mut i, &[], &mut trees);
                for p in trees {
                    out.push((here(&inline), p));
                }
                continue;
            }
            "crate" | "super" if t.get(i + 1).map(String::as_str) == Some("::") => {
                let mut p = vec![t[i].clone()];
                let mut j = i + 1;
                while t.get(j).map(String::as_str) == Some("::")
                    && t.get(j + 1)
                        .is_some_and(|s| s.chars().all(|c| c.is_alphanumeric() || c == '_'))
                {
                    p.push(t[j + 1].clone());
                    j += 2;
                }
                out.push((here(&inline), p));
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    // A `use` of a child module's name (`use rhs::State` in a mod.rs) means that child.
    out.into_iter()
        .filter_map(|(from, p)| {
            let first = p.first()?.as_str();
            match first {
                "crate" | "super" | "self" => Some((from, p)),
                _ if from == *file && children.contains(first) => {
                    let mut q = vec!["self".to_string()];
                    q.extend(p);
                    Some((from, q))
                }
                _ => None,
            }
        })
        .collect()
}

/// The module a path names, from the module `from` it is written in.
fn absolute(from: &Module, path: &[String]) -> Module {
    let mut m: Module = Vec::new();
    let mut rest = path;
    match path[0].as_str() {
        "crate" => rest = &path[1..],
        "self" => {
            m = from.clone();
            rest = &path[1..];
        }
        _ => {
            m = from.clone();
            while rest.first().map(String::as_str) == Some("super") {
                m.pop();
                rest = &rest[1..];
            }
        }
    }
    m.extend(rest.iter().cloned());
    m
}

/// The layer of a file's top-level module (`None` for the crate root and for a module the
/// table does not list).
fn layer(module: &Module) -> Option<usize> {
    let top = module.first()?;
    LAYERS
        .iter()
        .position(|(_, mods)| mods.contains(&top.as_str()))
}

fn name(m: &Module) -> String {
    if m.is_empty() {
        "the crate root (lib.rs)".into()
    } else {
        m.join("::")
    }
}

/// Every broken rule of the tree `files`, one line each.
fn violations(files: &BTreeMap<Module, String>) -> Vec<String> {
    let mut errors = Vec::new();
    let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (file, text) in files {
        if file.is_empty() {
            continue; // the crate root declares the layers and re-exports the public API
        }
        let Some(own) = layer(file) else {
            errors.push(format!(
                "src/{}: the top-level module `{}` is in no layer (tests/layering.rs, LAYERS)",
                file.join("/"),
                file[0]
            ));
            continue;
        };
        for (from, path) in paths(file, &code_only(text)) {
            let target = absolute(&from, &path);
            // The file whose module is the longest prefix of the path.
            let Some(k) = (0..=target.len())
                .rev()
                .find(|&k| files.contains_key(&target[..k]))
            else {
                continue;
            };
            let to = target[..k].to_vec();
            if &to == file {
                continue;
            }
            let shown = path.join("::");
            match layer(&to) {
                None => errors.push(format!(
                    "{}: `{shown}` imports through {}; name the module that defines it",
                    name(file),
                    name(&to)
                )),
                Some(l) if l > own => errors.push(format!(
                    "{}: `{shown}` imports {} of the layer {} from the layer {} below it",
                    name(file),
                    name(&to),
                    LAYERS[l].0,
                    LAYERS[own].0
                )),
                _ => {}
            }
            edges.entry(file.clone()).or_default().insert(to);
        }
    }
    for cycle in cycles(&edges) {
        let names: Vec<String> = cycle.iter().map(name).collect();
        errors.push(format!(
            "these files import each other in a loop: {}",
            names.join(", ")
        ));
    }
    errors
}

/// The strongly connected components of more than one file (Tarjan), each sorted.
fn cycles(edges: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
    struct Walk<'a> {
        edges: &'a BTreeMap<Module, BTreeSet<Module>>,
        index: BTreeMap<Module, usize>,
        low: BTreeMap<Module, usize>,
        stack: Vec<Module>,
        on: BTreeSet<Module>,
        out: Vec<Vec<Module>>,
    }
    fn visit(w: &mut Walk<'_>, v: &Module) {
        let n = w.index.len();
        w.index.insert(v.clone(), n);
        w.low.insert(v.clone(), n);
        w.stack.push(v.clone());
        w.on.insert(v.clone());
        for u in w.edges.get(v).into_iter().flatten() {
            if !w.index.contains_key(u) {
                visit(w, u);
                let l = w.low[u].min(w.low[v]);
                w.low.insert(v.clone(), l);
            } else if w.on.contains(u) {
                let l = w.index[u].min(w.low[v]);
                w.low.insert(v.clone(), l);
            }
        }
        if w.low[v] == w.index[v] {
            let mut comp = Vec::new();
            loop {
                let u = w.stack.pop().unwrap();
                w.on.remove(&u);
                let done = &u == v;
                comp.push(u);
                if done {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                w.out.push(comp);
            }
        }
    }
    let mut w = Walk {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !w.index.contains_key(v) {
            visit(&mut w, v);
        }
    }
    w.out
}

fn src_tree() -> BTreeMap<Module, String> {
    read_tree(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"))
}

#[test]
fn imports_run_only_downward_and_without_loops() {
    let errors = violations(&src_tree());
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// The check fails on the tree with one upward import added: the error type (base layer)
/// importing the scene layer.
#[test]
fn an_upward_import_fails_the_check() {
    let mut files = src_tree();
    let error = files
        .get_mut(&vec!["base".to_string(), "error".to_string()])
        .unwrap();
    error.push_str("\nuse crate::scene::Scene;\n");
    let errors = violations(&files);
    assert!(
        errors
            .iter()
            .any(|e| e.starts_with("base::error: `crate::scene::Scene` imports scene")),
        "{errors:?}"
    );
}

/// A loop between two files of one layer fails, and so does a path through the crate
/// root; comments and strings that spell a path do not count.
#[test]
fn loops_and_the_crate_root_fail_the_check() {
    let m = |p: &str| {
        p.split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect::<Module>()
    };
    let files: BTreeMap<Module, String> = [
        (m(""), "mod model;".to_string()),
        (m("model"), "pub(crate) mod a; pub(crate) mod b;".to_string()),
        (m("model::a"), "use super::b::X; // use crate::scene::Y;\n".to_string()),
        (
            m("model::b"),
            "use crate::model::a::{self as other, Z};\nlet s = \"crate::cli::x\";\nuse crate::Error;"
                .to_string(),
        ),
    ]
    .into_iter()
    .collect();
    let errors = violations(&files);
    assert_eq!(
        errors,
        [
            "model::b: `crate::Error` imports through the crate root (lib.rs); name the module \
             that defines it",
            "these files import each other in a loop: model::a, model::b",
        ],
        "{errors:?}"
    );
}
