//! The library's rooms and their imports (book:
//! docs/src/development/index.md#code-structure): each top-level module of
//! `src/` is a room; a room imports another where its code (not its doc
//! comments) names `crate::other` (or, from the room's top file,
//! `super::other`). The rooms' graph has no circle, and the kernels
//! (contact, wear, dynamics and the numerics below them, levels) import
//! nothing from the layers above them (the typed parameters, the config
//! reader, the assembly, the growth loop, the spectrum, the output, the
//! runs and sweeps): a kernel receives what it needs.
//! `cargo test --test integration imports::` prints the graph.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The binary's own modules (`src/main.rs`'s `mod`s), not rooms of the
/// library.
const BINARY: [&str; 7] = ["main", "check", "forecast_cli", "interrupt", "progress", "spectrum_cli", "sweep_cli"];

/// The kernels and what they must not import.
const KERNELS: [&str; 12] = [
    "contact",
    "wear",
    "dynamics",
    "levels",
    "hertz",
    "creep_coefficients",
    "quadrature",
    "numerics",
    "harmonics",
    "rail_grid",
    "loads",
    "metrics",
];
const LAYERS: [&str; 10] =
    ["params", "config", "build", "growth", "spectrum", "output", "run", "sweep", "model_choice", "cost"];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, out)
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p)
        }
    }
}

/// The identifiers that follow `prefix` in `code`.
fn after<'a>(code: &'a str, prefix: &str) -> Vec<&'a str> {
    code.match_indices(prefix)
        .filter(|(i, _)| !code[..*i].ends_with(|c: char| c.is_alphanumeric() || c == '_'))
        .map(|(i, _)| {
            let rest = &code[i + prefix.len()..];
            let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
            &rest[..end]
        })
        .filter(|s| !s.is_empty())
        .collect()
}

/// Each room's imports of the other rooms.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    let room_of = |p: &Path| {
        let rel = p.strip_prefix(&src).unwrap();
        let first = rel.components().next().unwrap().as_os_str().to_string_lossy().to_string();
        first.trim_end_matches(".rs").to_string()
    };
    let rooms: BTreeSet<String> =
        all.iter().map(|p| room_of(p)).filter(|r| !BINARY.contains(&r.as_str()) && r != "lib").collect();
    let mut g: BTreeMap<String, BTreeSet<String>> = rooms.iter().map(|r| (r.clone(), BTreeSet::new())).collect();
    for p in &all {
        let room = room_of(p);
        if !rooms.contains(&room) {
            continue;
        }
        let rel = p.strip_prefix(&src).unwrap();
        // `super::` names the crate root from a room's top file.
        let top = rel.components().count() == 1 || rel.ends_with("mod.rs") && rel.components().count() == 2;
        let text = std::fs::read_to_string(p).unwrap();
        let code: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .map(|l| l.split(" // ").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n");
        let mut named = after(&code, "crate::");
        if top {
            named.extend(after(&code, "super::"));
        }
        for other in named {
            if other != room && rooms.contains(other) {
                g.get_mut(&room).unwrap().insert(other.to_string());
            }
        }
    }
    g
}

/// The rooms on a circle: the strongly connected components of more than
/// one room (Tarjan).
fn circles(g: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        let i = t.index.len();
        t.index.insert(v, i);
        t.low.insert(v, i);
        t.stack.push(v);
        t.on.insert(v);
        for w in &t.g[v] {
            let w = w.as_str();
            if !t.index.contains_key(w) {
                visit(t, w);
                let l = t.low[w].min(t.low[v]);
                t.low.insert(v, l);
            } else if t.on.contains(w) {
                let l = t.index[w].min(t.low[v]);
                t.low.insert(v, l);
            }
        }
        if t.low[v] == t.index[v] {
            let mut c = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                c.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if c.len() > 1 {
                c.sort();
                t.out.push(c);
            }
        }
    }
    let mut t =
        T { g, index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), on: BTreeSet::new(), out: Vec::new() };
    for v in g.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    t.out
}

#[test]
fn the_rooms_import_without_circles_and_the_kernels_import_no_layer_above() {
    let g = graph();
    for (room, imports) in &g {
        println!("{room} -> {}", imports.iter().cloned().collect::<Vec<_>>().join(", "));
    }
    // The graph is read: the growth loop imports the contact and the wear.
    assert!(g["growth"].contains("contact") && g["growth"].contains("wear"), "{g:?}");
    assert!(g.len() >= 20, "{} rooms", g.len());
    let c = circles(&g);
    assert!(c.is_empty(), "rooms on a circle: {c:?}");
    let mut upward = Vec::new();
    for k in KERNELS {
        for l in LAYERS {
            if g[k].contains(l) {
                upward.push(format!("{k} -> {l}"));
            }
        }
    }
    assert!(upward.is_empty(), "kernels importing a layer above them: {upward:?}");
}

#[test]
fn a_circle_is_found() {
    // The detector itself: a -> b -> c -> a is one circle, d apart.
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, to) in [("a", "b"), ("b", "c"), ("c", "a"), ("d", "a")] {
        g.entry(from.into()).or_default().insert(to.into());
        g.entry(to.into()).or_default();
    }
    assert_eq!(circles(&g), vec![vec!["a".to_string(), "b".into(), "c".into()]]);
    g.get_mut("c").unwrap().clear();
    assert!(circles(&g).is_empty());
}
