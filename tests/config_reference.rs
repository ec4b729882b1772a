//! The configuration reference of the book (`docs/src/reference/configuration.md`)
//! against the code, so that the page cannot drift from what the program reads:
//!
//! - its keys are exactly the keys the config reader reads or looks for
//!   (recorded by `config::schema` while the shipped configs, a few probes
//!   that switch on the optional sections, and every value of every choice
//!   key are read);
//! - each key's unit is the one `src/config/units.rs` gives (empty for keys
//!   without a number), and every numeric key has one there;
//! - each key's allowed range is the one the reader checks (the words of its
//!   error messages, in the page's short form);
//! - each key's default is what the resolved config (defaults filled in)
//!   holds where a valid config leaves the key out: a value written in the
//!   cell, or a key named there whose value it takes; and "required" where
//!   leaving the key out is an error.
//!
//! On failure the message lists every difference and, for a key the page
//! lacks, the row to paste (its meaning left to write).

use corrugation::config::schema::{self, KeyLog, generic_key};
use corrugation::config::{RecordSource, load_str_with, units::key_units};

/// Reads a probe as the program reads a file in `configs/` (a measured
/// record relative to that folder).
fn load_str(
    text: &str,
    source: &str,
    overrides: &[String],
) -> Result<corrugation::config::Resolved, corrugation::config::ConfigErrors> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs");
    load_str_with(text, source, overrides, &RecordSource::Dir(dir))
}
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use toml::{Table, Value};

const PAGE_PATH: &str = "docs/src/reference/configuration.md";
const PAGE: &str = include_str!("../docs/src/reference/configuration.md");

/// One row of the page's tables.
#[derive(Debug)]
struct Row {
    unit: String,
    default: String,
    allowed: String,
}

/// Cells of a Markdown table row (`\|` is a pipe inside a cell).
fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    let mut out = vec![String::new()];
    let mut chars = inner.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                out.last_mut().unwrap().push('|');
                chars.next();
            }
            '|' => out.push(String::new()),
            _ => out.last_mut().unwrap().push(c),
        }
    }
    out.into_iter().map(|c| c.trim().to_string()).collect()
}

/// The rows of the page's key tables (those whose header's first cell is
/// `key`): first cell a single backticked dotted key.
fn page_rows(problems: &mut Vec<String>) -> BTreeMap<String, Row> {
    let mut rows = BTreeMap::new();
    let mut in_key_table = false;
    for (n, line) in PAGE.lines().enumerate() {
        if !line.starts_with('|') {
            in_key_table = false;
            continue;
        }
        if line.starts_with("| key |") {
            in_key_table = true;
        }
        if !in_key_table || !line.starts_with("| `") {
            continue;
        }
        let c = cells(line);
        let key = c[0].trim_matches('`');
        if c[0].matches('`').count() != 2 || !key.contains('.') {
            continue;
        }
        if c.len() != 5 {
            problems.push(format!("{PAGE_PATH}:{}: row of `{key}` has {} cells, expected 5", n + 1, c.len()));
            continue;
        }
        let row = Row { unit: c[1].clone(), default: c[2].clone(), allowed: c[3].clone() };
        if rows.insert(key.to_string(), row).is_some() {
            problems.push(format!("{PAGE_PATH}:{}: `{key}` has a second row", n + 1));
        }
    }
    rows
}

/// A piece of a description: text (whitespace collapsed) or a number.
#[derive(Debug)]
enum Token {
    Text(String),
    Number(f64),
}

fn tokens(s: &str) -> Vec<Token> {
    let b: Vec<char> = s.chars().collect();
    let mut out = Vec::new();
    let mut text = String::new();
    let mut i = 0;
    while i < b.len() {
        let starts_number = b[i].is_ascii_digit()
            || (matches!(b[i], '-' | '+' | '.')
                && b.get(i + 1).is_some_and(|c| c.is_ascii_digit() || *c == '.')
                && (i == 0 || !b[i - 1].is_alphanumeric()));
        if starts_number {
            let mut j = i + 1;
            while j < b.len()
                && (b[j].is_ascii_digit()
                    || b[j] == '.'
                    || ((b[j] == 'e' || b[j] == 'E')
                        && b.get(j + 1).is_some_and(|c| c.is_ascii_digit() || *c == '-' || *c == '+'))
                    || ((b[j] == '-' || b[j] == '+') && matches!(b[j - 1], 'e' | 'E')))
            {
                j += 1;
            }
            let word: String = b[i..j].iter().collect();
            if let Ok(x) = word.parse::<f64>() {
                let t = text.split_whitespace().collect::<Vec<_>>().join(" ");
                if !t.is_empty() {
                    out.push(Token::Text(t));
                }
                text.clear();
                out.push(Token::Number(x));
                i = j;
                continue;
            }
        }
        text.push(b[i]);
        i += 1;
    }
    let t = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if !t.is_empty() {
        out.push(Token::Text(t));
    }
    out
}

fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}

fn same_tokens(a: &str, b: &str) -> bool {
    let (ta, tb) = (tokens(a), tokens(b));
    ta.len() == tb.len()
        && ta.iter().zip(&tb).all(|(x, y)| match (x, y) {
            (Token::Text(x), Token::Text(y)) => x == y,
            (Token::Number(x), Token::Number(y)) => close(*x, *y),
            _ => false,
        })
}

/// The values of a `one of "a", "b"` description.
fn quoted(s: &str) -> BTreeSet<String> {
    s.split('"').skip(1).step_by(2).map(str::to_string).collect()
}

/// The backticked words of a cell.
fn backticked(s: &str) -> Vec<String> {
    s.split('`').skip(1).step_by(2).map(str::to_string).collect()
}

/// The page's short form of a reader's description of what a key allows.
fn short_form(description: &str) -> String {
    // A number that may carry its unit is described with the unit and an
    // example ("a number in (0, 200] in m/s (or a string with its unit,
    // e.g. 70km/h)"): the range is what the page's cell gives, the unit is
    // in its own column.
    let d = match description.find(" (or a string with its unit") {
        Some(i) => description[..i].rsplit_once(" in ").map_or(&description[..i], |(head, _)| head),
        None => description,
    };
    let simple = [
        ("a finite number", "finite"),
        ("a finite number > 0", "> 0"),
        ("a number > 0 or inf", "> 0 or inf"),
        ("a finite number >= 0", ">= 0"),
        ("a non-zero number or +-inf", "!= 0 or +-inf"),
        ("true or false", "true or false"),
        ("a string", "text"),
        ("an array of tables", "array of tables"),
    ];
    if let Some((_, s)) = simple.iter().find(|(r, _)| *r == d) {
        return s.to_string();
    }
    if let Some(r) = d.strip_prefix("a number in ") {
        return r.to_string();
    }
    if let Some(r) = d.strip_prefix("an integer in ") {
        // An upper bound beyond what a float holds exactly reads as none.
        if let [Token::Text(_), Token::Number(lo), Token::Text(_), Token::Number(hi), ..] = tokens(r).as_slice()
            && *hi >= 2f64.powi(53)
        {
            return format!("integer >= {lo}");
        }
        return format!("integer in {r}");
    }
    if d.starts_with("one of ") {
        return quoted(d).iter().map(|v| format!("`{v}`")).collect::<Vec<_>>().join(", ");
    }
    if let Some(r) = d.strip_prefix("a list of 1 to ")
        && let Some((n, each)) = r.split_once(" numbers, each ")
    {
        return format!("list of 1 to {n} numbers, each {}", short_form(each));
    }
    if let Some(r) = d.strip_prefix("a list of integers in ") {
        return format!("list of integers in {r}");
    }
    d.to_string()
}

/// Whether the page's allowed cell (before its first "; ") says `description`.
fn allowed_matches(cell: &str, description: &str) -> bool {
    let head = cell.split("; ").next().unwrap_or("");
    if description.starts_with("one of ") {
        return backticked(head).into_iter().collect::<BTreeSet<_>>() == quoted(description);
    }
    same_tokens(head, &short_form(description))
}

/// Leaf values of a config table by dotted key (array elements of tables as
/// `key[i]`, arrays of values as one leaf).
fn leaves(t: &Table, prefix: &str, out: &mut BTreeMap<String, Value>) {
    for (k, v) in t {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            Value::Table(inner) => leaves(inner, &key, out),
            Value::Array(a) if !a.is_empty() && a.iter().all(Value::is_table) => {
                for (i, item) in a.iter().enumerate() {
                    leaves(item.as_table().unwrap(), &format!("{key}[{i}]"), out);
                }
            }
            _ => {
                out.insert(key, v.clone());
            }
        }
    }
}

/// Whether a resolved default `v` is what the default cell says: a value
/// written there (numbers, backticked words, `""`, `true`/`false`, `[...]`)
/// or a key named there whose resolved value it equals.
fn default_matches(v: &Value, cell: &str, resolved: &BTreeMap<String, Value>) -> bool {
    let equal = |a: &Value, b: &Value| match (a, b) {
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len()
                && x.iter().zip(y).all(|(p, q)| {
                    match (
                        p.as_float().or(p.as_integer().map(|i| i as f64)),
                        q.as_float().or(q.as_integer().map(|i| i as f64)),
                    ) {
                        (Some(p), Some(q)) => close(p, q),
                        _ => p == q,
                    }
                })
        }
        _ => {
            match (a.as_float().or(a.as_integer().map(|i| i as f64)), b.as_float().or(b.as_integer().map(|i| i as f64)))
            {
                (Some(p), Some(q)) => close(p, q),
                _ => a == b,
            }
        }
    };
    for word in backticked(cell) {
        if let Some(other) = resolved.get(&word)
            && equal(v, other)
        {
            return true;
        }
    }
    // A default the program computes (from a file, from other keys) is
    // described, not given.
    if cell.contains("computed") {
        return true;
    }
    match v {
        Value::String(s) if s.is_empty() => cell.contains("\"\""),
        Value::String(s) => backticked(cell).contains(s),
        Value::Boolean(b) => cell.split(|c: char| !c.is_alphanumeric()).any(|w| w == b.to_string()),
        Value::Float(_) | Value::Integer(_) => {
            tokens(cell).iter().any(|t| matches!(t, Token::Number(x) if equal(v, &Value::Float(*x))))
        }
        Value::Array(_) => cell.split('`').any(|w| {
            w.starts_with('[')
                && format!("v = {w}")
                    .parse::<Table>()
                    .ok()
                    .and_then(|t| t.get("v").cloned())
                    .is_some_and(|a| equal(v, &a))
        }),
        _ => false,
    }
}

/// The configs the page is checked on: every shipped run config and probes
/// that switch on what no shipped config uses.
fn probes() -> Vec<(String, Table)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs");
    let mut out = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    for f in files.iter().filter(|f| f.extension().is_some_and(|e| e == "toml")) {
        let t: Table = std::fs::read_to_string(f).unwrap().parse().unwrap();
        if t.contains_key("base") {
            continue; // a sweep spec
        }
        out.push((format!("configs/{}", f.file_name().unwrap().to_string_lossy()), t));
    }
    let growth: Table = out.iter().find(|(n, _)| n.ends_with("growth_exact.toml")).unwrap().1.clone();
    let with = |name: &str, extra: &str, remove: &[&str]| {
        let mut t = growth.clone();
        for key in remove {
            let (section, k) = key.split_once('.').unwrap();
            t.get_mut(section).and_then(Value::as_table_mut).unwrap().remove(k);
        }
        let extra: Table = extra.parse().unwrap();
        for (k, v) in extra {
            match (t.get_mut(&k), v) {
                (Some(Value::Table(old)), Value::Table(new)) => old.extend(new),
                (_, v) => {
                    t.insert(k, v);
                }
            }
        }
        (format!("growth_exact.toml with {name}"), t)
    };
    out.push(with(
        "roughness harmonics",
        "[roughness]\nkind = \"harmonics\"\nharmonics = [{ amplitude = 1e-6, wavelength = 0.03, phase = 0.5 }]",
        &["roughness.seed", "roughness.rms", "roughness.wavelength_min", "roughness.wavelength_max"],
    ));
    out.push(with(
        "roughness levels",
        "[roughness]\nkind = \"levels\"\nbands = [{ wavelength = 0.0315, level = 0.0 }, { wavelength = 0.063, level = 3.0 }]",
        &["roughness.rms", "roughness.wavelength_min", "roughness.wavelength_max"],
    ));
    out.push(with(
        "a bogie of unequal wheels",
        "[vehicle]\nwheels = [0.0, 2.5]\nunsprung_mass = [600.0, 550.0]\nnormal_force = [1e5, 9e4]\n\
         longitudinal_force = [2e4, 1.8e4]\n[dynamics]\ndirections = \"vertical\"",
        &[],
    ));
    out.push(with(
        "creepage control and the torsional mode",
        "[load]\ncontrol = \"creepage\"\n[rolling]\ncreepage_x = -1.26e-3\n\
         [wheelset]\ntorsional_stiffness = 3e6\npolar_inertia = 30.0\ntorsional_loss_factor = 0.02",
        &["load.longitudinal_force"],
    ));
    out.push(with(
        "a track of its own",
        "[track]\nrail = \"54E1\"\nrail_bending_stiffness = 4.9e6\nrail_mass = 54.8\nrail_shear_stiffness = 2.2e8\n\
         rail_rotary_inertia = 0.18\nsleeper_spacing = 0.65\npad_stiffness = 3e8\npad_damping = 3e4\n\
         sleeper_mass = 150.0\nballast_stiffness = 8e7\nballast_damping = 6e4",
        &[],
    ));
    out.push(with(
        "a traffic mix",
        "[[traffic.mix]]\nname = \"bogie\"\nspeed = 22.22\nnormal_force = 9e4\nlongitudinal_force = 1e4\n\
         unsprung_mass = 550.0\nshare = 2.0\nwheels = [0.0, 2.5]\n[[traffic.mix]]\nshare = 1.0\n\
         [dynamics]\ndirections = \"vertical\"",
        &[],
    ));
    out.push(with(
        "traffic in the operator's units",
        "[traffic]\naxle_load = 22500.0\naxles_per_day = 2000.0\n[[traffic.mix]]\nshare = 1.0\naxle_load = 20000.0",
        &[],
    ));
    out.push(with(
        "trains per day",
        "[traffic]\ntrains_per_day = 100.0\naxles_per_train = 20.0\n[[traffic.mix]]\nshare = 1.0",
        &[],
    ));
    out.push(with(
        "levels against a limit table",
        "[levels]\nbands = \"third-octave\"\nlimit = \"table\"\nlimit_name = \"mine\"\n\
         [[levels.limit_table]]\nwavelength = 0.0315\nlevel = 15.0",
        &[],
    ));
    out.push(with(
        "a limit curve from a file",
        "[levels]\nlimit = \"file\"\nlimit_file = \"records/own_limit.csv\"",
        &[],
    ));
    out.push(with(
        "a rail section of its own in every direction",
        "[track]\nrail_axial_stiffness = 1.6e9\nrail_lateral_bending_stiffness = 1.08e6\n\
         rail_lateral_shear_stiffness = 2.0e8\nrail_lateral_rotary_inertia = 0.04\nrail_torsional_stiffness = 1.7e5\n\
         rail_polar_inertia = 0.2\nrail_height = 0.172\nrail_neutral_axis_height = 0.081\n\
         rail_shear_centre_height = 0.041",
        &[],
    ));
    out.push(with("levels against ISO 3095", "[levels]\nlimit = \"iso3095\"", &[]));
    // Track layouts, on the discrete track.
    let discrete: Table = out.iter().find(|(n, _)| n.ends_with("growth_discrete.toml")).unwrap().1.clone();
    for (name, extra) in [
        (
            "a layout by positions and patterns",
            "[track]\nsleeper_positions = [0.0, 0.55]\npad_stiffness_pattern = [2e8, 3e8]\n\
             sleeper_mass_pattern = [140.0, 120.0]\npad_loss_factor_pattern = [0.25, 0.4]\n\
             ballast_stiffness_pattern = [1e8, 5e7]",
        ),
        (
            "a random layout",
            "[track]\nspacing_std = 0.02\nspacing_min = 0.5\nspacing_max = 0.7\npad_stiffness_std = 2e7\n\
             pad_stiffness_min = 1e8\npad_stiffness_max = 3e8\nsleeper_mass_std = 10.0\nsleeper_mass_min = 100.0\n\
             sleeper_mass_max = 180.0\npad_loss_factor_std = 0.05\npad_loss_factor_min = 0.1\n\
             pad_loss_factor_max = 0.4\nballast_stiffness_std = 2e7\nballast_stiffness_min = 5e7\n\
             ballast_stiffness_max = 1.5e8\nseed = 3",
        ),
    ] {
        let mut t = discrete.clone();
        let extra: Table = format!("[rail]\nx_max = 1.2\n[passage]\nend = 1.2\n{extra}").parse().unwrap();
        for (k, v) in extra {
            match (t.get_mut(&k), v) {
                (Some(Value::Table(old)), Value::Table(new)) => old.extend(new),
                (_, v) => {
                    t.insert(k, v);
                }
            }
        }
        out.push((format!("growth_discrete.toml with {name}"), t));
    }
    out.push(with(
        "a spectrum",
        "[spectrum]\nwavelength_min = 0.012\nwavelength_max = 0.12\nclasses = 2\nperturbation = 5e-8\n\
         difference = \"forward\"\nbase = \"roughness\"",
        &[],
    ));
    out.push(with("a spectrum at a resolution", "[spectrum]\nresolution = 0.005", &[]));
    out.push(with("the modal wheelset", "[wheelset]\nmodel = \"modal\"", &[]));
    out.push(with(
        "the second rail under force control",
        "[wheelset]\nmodel = \"modal\"\n[second_rail]\nnormal_force = 1.1e5\nlongitudinal_force = 1e4\n\
         roughness_seed = 7",
        &[],
    ));
    out.push(with(
        "the automatic model choice",
        "[contact]\nmodel = \"auto\"\ntolerance = 0.1\n[passage]\nstep_length = 2e-4\n[growth]\nstop = \"saturation\"",
        &["contact.grid", "contact.dx", "contact.dy"],
    ));
    out
}

fn text(t: &Table) -> String {
    toml::to_string(t).unwrap()
}

/// Sets dotted `key` (no array) in `t` to `v`.
fn set(t: &mut Table, key: &str, v: Value) {
    let (section, k) = key.rsplit_once('.').unwrap();
    let mut here = t;
    for part in section.split('.') {
        here = here.entry(part).or_insert_with(|| Value::Table(Table::new())).as_table_mut().unwrap();
    }
    here.insert(k.to_string(), v);
}

/// Reads every probe, and every probe with each value of each of its choice
/// keys: the keys read, and the valid configs with their resolved tables.
fn explore() -> (KeyLog, Vec<(String, Table, Table)>) {
    let mut log = KeyLog::new();
    let mut valid = Vec::new();
    let merge = |l: KeyLog, log: &mut KeyLog| {
        for (k, v) in l {
            log.entry(k).or_default().extend(v);
        }
    };
    for (name, table) in probes() {
        let (result, l) = schema::record(|| load_str(&text(&table), &name, &[]));
        let resolved = match result {
            Ok(r) => r.toml.parse::<Table>().unwrap(),
            Err(e) => panic!("probe {name} must be a valid config:\n{e}"),
        };
        let choices: Vec<(String, BTreeSet<String>)> = l
            .iter()
            .filter(|(k, _)| !k.contains('['))
            .flat_map(|(k, ds)| ds.iter().filter(|d| d.starts_with("one of ")).map(|d| (k.clone(), quoted(d))))
            .collect();
        merge(l, &mut log);
        valid.push((name.clone(), table.clone(), resolved));
        for (key, values) in choices {
            for value in values {
                let mut t = table.clone();
                set(&mut t, &key, Value::String(value.clone()));
                let label = format!("{name} with {key} = \"{value}\"");
                let (result, l) = schema::record(|| load_str(&text(&t), &label, &[]));
                merge(l, &mut log);
                if let Ok(r) = result {
                    valid.push((label, t, r.toml.parse().unwrap()));
                }
            }
        }
    }
    (log, valid)
}

#[test]
fn the_configuration_reference_is_the_code_s() {
    let mut problems = Vec::new();
    let rows = page_rows(&mut problems);
    assert!(rows.len() > 50, "{PAGE_PATH} lists {} keys; its tables were not read", rows.len());
    let (log, valid) = explore();

    // Defaults seen in valid configs that leave a key out, and whether
    // leaving a given key out is an error ("missing").
    let mut defaults: BTreeMap<String, Vec<(String, Value)>> = BTreeMap::new();
    let mut required: BTreeMap<String, Vec<(String, bool)>> = BTreeMap::new();
    for (name, input, resolved) in &valid {
        let (mut given, mut all) = (BTreeMap::new(), BTreeMap::new());
        leaves(input, "", &mut given);
        leaves(resolved, "", &mut all);
        for (k, v) in &all {
            if !given.contains_key(k) {
                let problem = if default_matches(
                    v,
                    &rows.get(&generic_key(k)).map_or(String::new(), |r| r.default.clone()),
                    &all,
                ) {
                    None
                } else {
                    Some(v.clone())
                };
                if let Some(v) = problem {
                    defaults.entry(generic_key(k)).or_default().push((name.clone(), v));
                }
            }
        }
        for k in given.keys() {
            let g = generic_key(k);
            if required.get(&g).is_some_and(|v| v.len() >= 3) {
                continue;
            }
            let mut t = input.clone();
            remove(&mut t, k);
            let missing = match load_str(&text(&t), name, &[]) {
                Ok(_) => false,
                Err(e) => e.errors.iter().any(|e| e.key == *k && e.message.starts_with("missing")),
            };
            required.entry(g).or_default().push((format!("{name} without {k}"), missing));
        }
    }

    for (key, descriptions) in &log {
        let unit = key_units(key);
        let numeric = descriptions.iter().any(|d| d.contains("number") || d.contains("integer"));
        if numeric && unit.is_none() {
            problems.push(format!("`{key}` holds a number but src/config/units.rs gives it no unit"));
        }
        let Some(row) = rows.get(key) else {
            let default = if required.get(key).is_some_and(|r| r.iter().any(|(_, m)| *m)) {
                "required".to_string()
            } else {
                valid
                    .iter()
                    .find_map(|(_, _, r)| {
                        let mut all = BTreeMap::new();
                        leaves(r, "", &mut all);
                        all.into_iter().find(|(k, _)| generic_key(k) == *key).map(|(_, v)| match v {
                            Value::String(s) if s.is_empty() => "`\"\"`".to_string(),
                            Value::String(s) => format!("`{s}`"),
                            Value::Array(_) => format!("`{v}`"),
                            v => v.to_string(),
                        })
                    })
                    .unwrap_or_default()
            };
            let allowed = descriptions.iter().next().map(|d| short_form(d)).unwrap_or_default();
            problems.push(format!(
                "`{key}` is read by the config reader but not in {PAGE_PATH}; add the row\n    | `{key}` | {} | {default} | {allowed} | (what it means) |",
                unit.unwrap_or("")
            ));
            continue;
        };
        if descriptions.is_empty() {
            problems.push(format!(
                "`{key}` is looked for but never read in this test's configs: add a probe (probes()) that sets it"
            ));
        } else if !descriptions.iter().any(|d| allowed_matches(&row.allowed, d)) {
            let forms: Vec<_> = descriptions.iter().map(|d| format!("\"{}\"", short_form(d))).collect();
            problems.push(format!(
                "`{key}`: allowed \"{}\" is not what the reader checks: {} (the text before the first \"; \")",
                row.allowed,
                forms.join(" or ")
            ));
        }
        if row.unit != unit.unwrap_or("") {
            problems.push(format!(
                "`{key}`: unit \"{}\" but src/config/units.rs says \"{}\"",
                row.unit,
                unit.unwrap_or("")
            ));
        }
        if let Some(seen) = defaults.get(key) {
            for (config, v) in seen.iter().take(2) {
                problems.push(format!("`{key}`: default \"{}\" but {config} resolves it to {v}", row.default));
            }
        }
        if let Some(tries) = required.get(key) {
            let says_required = row.default.contains("required");
            let only_required = row.default == "required";
            if let Some((t, _)) = tries.iter().find(|(_, m)| *m).filter(|_| !says_required) {
                problems.push(format!("`{key}` has default \"{}\" but is required: {t} is missing it", row.default));
            }
            if let Some((t, _)) = tries.iter().find(|(_, m)| !*m).filter(|_| only_required) {
                problems.push(format!("`{key}` is documented as required, but {t} is valid"));
            }
        }
    }
    for key in rows.keys() {
        if !log.contains_key(key) {
            problems.push(format!("{PAGE_PATH} documents `{key}`, which the config reader never reads"));
        }
    }
    assert!(problems.is_empty(), "{} problems:\n- {}", problems.len(), problems.join("\n- "));
}

/// Removes dotted `key` (with `[i]` array elements) from `t`.
fn remove(t: &mut Table, key: &str) {
    let parts: Vec<&str> = key.split('.').collect();
    let mut here = t;
    for part in &parts[..parts.len() - 1] {
        let (name, index) = match part.split_once('[') {
            Some((n, i)) => (n, Some(i.trim_end_matches(']').parse::<usize>().unwrap())),
            None => (*part, None),
        };
        let v = here.get_mut(name).unwrap();
        here = match index {
            Some(i) => v.as_array_mut().unwrap()[i].as_table_mut().unwrap(),
            None => v.as_table_mut().unwrap(),
        };
    }
    here.remove(parts[parts.len() - 1]);
}

#[test]
fn short_forms_read_as_the_page_writes_them() {
    assert_eq!(short_form("a number in [0, 0.5)"), "[0, 0.5)");
    assert_eq!(short_form("a number in (0, 200] in m/s (or a string with its unit, e.g. 70km/h)"), "(0, 200]");
    assert_eq!(short_form("an integer in [1, 1000000]"), "integer in [1, 1000000]");
    assert!(same_tokens("integer in [1, 1e6]", &short_form("an integer in [1, 1000000]")));
    assert_eq!(short_form("an integer in [0, 9223372036854775807]"), "integer >= 0");
    assert!(allowed_matches("`b`, `a`; more words", "one of \"a\", \"b\""));
    assert!(!allowed_matches("`a`", "one of \"a\", \"b\""));
    assert!(allowed_matches("[-0.1, 0.1]; only with creepage control", "a number in [-0.1, 0.1]"));
    assert!(!allowed_matches("[-0.1, 0.2]", "a number in [-0.1, 0.1]"));
    assert!(same_tokens(
        "list of 1 to 8 numbers, each [0, 50]",
        &short_form("a list of 1 to 8 numbers, each a number in [0, 50]")
    ));
    assert_eq!(cells("| `a.b` | m | 1 | \\|x\\| < 2 | y |"), vec!["`a.b`", "m", "1", "|x| < 2", "y"]);
    let none = BTreeMap::new();
    assert!(default_matches(&Value::Float(1e9), "1e9", &none));
    assert!(default_matches(&Value::String(String::new()), "`\"\"`", &none));
    assert!(default_matches(&Value::Array(vec![Value::Integer(0)]), "`[0]`", &none));
    assert!(!default_matches(&Value::Float(0.1), "required", &none));
}
