//! The sweep spec (TOML): a base config, the sweep's directory, and axes of
//! `--set`-style overrides whose cartesian product (or zip) gives the
//! members.
//!
//! ```toml
//! base = "growth_fastsim.toml"       # the base config, relative to this file
//! output = "../out/sweep_speed_pad"  # the sweep's directory, relative to this file
//! set = ["growth.passes=60"]         # optional: overrides for every member
//!
//! [[axis]]
//! key = "rolling.speed"              # a config key, as --set takes it
//! values = [16.67, 22.22, 27.78]
//!
//! [[axis]]
//! key = "track.pad_stiffness"
//! values = [100e6, 200e6, 500e6]
//! zip = false                        # true on axes of equal length pairs them
//! ```
//!
//! Axes with `zip = true` form one dimension (the first of them names it,
//! at its place among the axes); the others each form their own. Members
//! are numbered row-major over the dimensions (the last varies fastest),
//! and member `i` writes `member_<i>.h5` in the output directory.

use crate::config::{ConfigErrors, RecordSource, Resolved, load_str_with};
use std::fmt;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// The most members a sweep may have.
pub const MAX_MEMBERS: usize = 100_000;

/// One problem with a sweep spec or one of its members.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecError {
    /// Where: a spec key (`axis[1].values`) or a member and its config key.
    pub key: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.key, self.message)
    }
}

/// All problems found in a sweep spec.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecErrors {
    /// The spec file.
    pub path: PathBuf,
    /// The problems.
    pub errors: Vec<SpecError>,
}

impl fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.errors.len();
        writeln!(f, "invalid sweep spec {} ({n} problem{}):", self.path.display(), if n == 1 { "" } else { "s" })?;
        for e in &self.errors {
            writeln!(f, "  - {e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecErrors {}

/// One dimension of the sweep: a single axis, or the zipped axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// The config keys that vary along it (one, or the zipped ones).
    pub keys: Vec<String>,
    /// `values[k][i]`: the value of key `k` at position `i`.
    pub values: Vec<Vec<Value>>,
}

impl Dimension {
    /// Number of positions.
    pub fn len(&self) -> usize {
        self.values[0].len()
    }

    /// Whether it has no positions (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The dimension's name in the collected dataset: its first key with
    /// `.` and `[`, `]` replaced by `_` (`rolling.speed` -> `rolling_speed`).
    pub fn name(&self) -> String {
        dimension_name(&self.keys[0])
    }
}

/// `rolling.speed` -> `rolling_speed`, `traffic.mix[1].share` ->
/// `traffic_mix_1_share`.
pub fn dimension_name(key: &str) -> String {
    key.replace(['.', '['], "_").replace(']', "")
}

/// A validated sweep spec.
#[derive(Debug, Clone)]
pub struct SweepSpec {
    /// The spec file.
    pub path: PathBuf,
    /// The base config (resolved against the spec's folder).
    pub base: PathBuf,
    /// The base config's text.
    pub base_text: String,
    /// The sweep's directory (resolved against the spec's folder).
    pub output: PathBuf,
    /// Overrides for every member.
    pub set: Vec<String>,
    /// The dimensions, in spec order.
    pub dims: Vec<Dimension>,
}

/// One member of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// Index (0-based, row-major over the dimensions).
    pub index: usize,
    /// Position along each dimension.
    pub position: Vec<usize>,
    /// The axes' overrides (`key=value`), by dimension (the zipped keys
    /// together, at the first one's place), each dimension's keys in spec
    /// order.
    pub overrides: Vec<String>,
}

/// A TOML value as `--set` takes it.
pub fn set_value(v: &Value) -> String {
    v.to_string()
}

impl SweepSpec {
    /// Reads and checks the spec's own keys (the members' configs are
    /// checked by [`SweepSpec::resolve_all`]).
    pub fn load(path: &Path) -> Result<SweepSpec, SpecErrors> {
        let fail = |errors: Vec<SpecError>| SpecErrors { path: path.to_owned(), errors };
        let err = |key: &str, message: String| SpecError { key: key.into(), message };
        if crate::config::is_hdf5(path) {
            return Err(fail(vec![err(
                "file",
                format!(
                    "is an HDF5 file (a run file or a collected sweep), not a sweep spec (TOML); \
                     `corrugation resume {}` continues a run file",
                    path.display()
                ),
            )]));
        }
        let text = std::fs::read_to_string(path).map_err(|e| fail(vec![err("file", format!("cannot read: {e}"))]))?;
        let mut root: Table = text.parse().map_err(|e: toml::de::Error| {
            fail(vec![err("TOML syntax", e.to_string().trim().replace('\n', "\n    "))])
        })?;
        // A scene config given where a sweep spec belongs: say so, not the
        // spec keys it lacks.
        if !root.contains_key("base") && !root.contains_key("axis") {
            let scene: Vec<&str> = crate::config::SECTIONS.iter().copied().filter(|k| root.contains_key(*k)).collect();
            if !scene.is_empty() {
                return Err(fail(vec![err(
                    "file",
                    format!(
                        "is a run config (it has [{}]), not a sweep spec: run it with `corrugation run {}`; a sweep \
                         spec names its base config (base = \"...\"), its output folder (output = \"...\") and its \
                         axes ([[axis]]), see the sweep guide",
                        scene.join("], ["),
                        path.display()
                    ),
                )]));
            }
        }
        let mut errors = Vec::new();
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let string = |root: &mut Table, key: &str, errors: &mut Vec<SpecError>| match root.remove(key) {
            Some(Value::String(s)) if !s.is_empty() => Some(s),
            Some(other) => {
                errors.push(err(key, format!("expected a non-empty string (a path), found `{other}`")));
                None
            }
            None => {
                errors.push(err(key, "missing; expected a path relative to the spec file".into()));
                None
            }
        };
        let base = string(&mut root, "base", &mut errors).map(|b| folder.join(b));
        let output = string(&mut root, "output", &mut errors).map(|o| folder.join(o));
        let base_text = base.as_ref().and_then(|b| match std::fs::read_to_string(b) {
            Ok(t) => Some(t),
            Err(e) => {
                errors.push(err("base", format!("cannot read the base config {}: {e}", b.display())));
                None
            }
        });
        let set = match root.remove("set") {
            None => Vec::new(),
            Some(Value::Array(a)) => a
                .into_iter()
                .enumerate()
                .filter_map(|(i, v)| match v {
                    Value::String(s) if s.contains('=') => Some(s),
                    other => {
                        errors.push(err(
                            &format!("set[{i}]"),
                            format!("expected \"section.key=value\", found `{other}`"),
                        ));
                        None
                    }
                })
                .collect(),
            Some(other) => {
                errors.push(err("set", format!("expected a list of \"section.key=value\" strings, found `{other}`")));
                Vec::new()
            }
        };
        let axes = read_axes(&mut root, &mut errors);
        for (k, _) in root {
            errors.push(err(&k, "unknown key; allowed: base, output, set, axis".into()));
        }
        let dims = dimensions(&axes, &mut errors);
        let members: usize = dims.iter().map(Dimension::len).product();
        if members > MAX_MEMBERS {
            errors.push(err("axis", format!("the axes give {members} members; at most {MAX_MEMBERS} allowed")));
        }
        match (base, base_text, output) {
            (Some(base), Some(base_text), Some(output)) if errors.is_empty() => {
                Ok(SweepSpec { path: path.to_owned(), base, base_text, output, set, dims })
            }
            _ => Err(fail(errors)),
        }
    }

    /// Number of members.
    pub fn len(&self) -> usize {
        self.dims.iter().map(Dimension::len).product()
    }

    /// Whether the sweep has no members (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The members, by index.
    pub fn members(&self) -> Vec<Member> {
        (0..self.len()).map(|i| self.member(i)).collect()
    }

    /// Member `index` (< [`SweepSpec::len`]).
    pub fn member(&self, index: usize) -> Member {
        let mut rest = index;
        let mut position = vec![0; self.dims.len()];
        for (d, dim) in self.dims.iter().enumerate().rev() {
            position[d] = rest % dim.len();
            rest /= dim.len();
        }
        let mut overrides = Vec::new();
        for (dim, &p) in self.dims.iter().zip(&position) {
            for (key, values) in dim.keys.iter().zip(&dim.values) {
                overrides.push(format!("{key}={}", set_value(&values[p])));
            }
        }
        Member { index, position, overrides }
    }

    /// All overrides of `member`: the spec's `set`, then its axes'.
    pub fn overrides(&self, member: &Member) -> Vec<String> {
        self.set.iter().chain(&member.overrides).cloned().collect()
    }

    /// Digits in member file names (at least 4).
    fn width(&self) -> usize {
        self.len().saturating_sub(1).to_string().len().max(4)
    }

    /// `member_0003`.
    pub fn member_name(&self, index: usize) -> String {
        format!("member_{index:0w$}", w = self.width())
    }

    /// The member's run file.
    pub fn member_file(&self, index: usize) -> PathBuf {
        self.output.join(format!("{}.h5", self.member_name(index)))
    }

    /// The file a failed member leaves its error in.
    pub fn error_file(&self, index: usize) -> PathBuf {
        self.output.join(format!("{}.error", self.member_name(index)))
    }

    /// The lock a member's process holds while it runs.
    pub fn lock_file(&self, index: usize) -> PathBuf {
        self.output.join(format!("{}.lock", self.member_name(index)))
    }

    /// The member's log (local runs and Slurm tasks).
    pub fn log_file(&self, index: usize) -> PathBuf {
        self.output.join("logs").join(format!("{}.log", self.member_name(index)))
    }

    /// Creates the sweep's directory and its `logs` folder and checks that
    /// files can be written there.
    pub fn prepare_output(&self) -> std::io::Result<()> {
        std::fs::create_dir_all(self.output.join("logs"))?;
        crate::output::check_writable(&self.output.join("sweep.probe"))
    }

    /// The validated config of member `index`.
    pub fn resolve(&self, index: usize) -> Result<Resolved, ConfigErrors> {
        let member = self.member(index);
        let source = format!("{} (member {index}: {})", self.base.display(), member.overrides.join(", "));
        let dir = self.base.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        load_str_with(&self.base_text, &source, &self.overrides(&member), &RecordSource::Dir(dir.to_path_buf()))
    }

    /// Every member's validated config, or every member's errors at once:
    /// an error common to all members is reported once, the others with the
    /// member and its overrides.
    pub fn resolve_all(&self) -> Result<Vec<Resolved>, SpecErrors> {
        let mut ok = Vec::with_capacity(self.len());
        // Error text -> members that have it, in first-seen order.
        let mut seen: Vec<(String, Vec<usize>)> = Vec::new();
        for i in 0..self.len() {
            match self.resolve(i) {
                Ok(r) => ok.push(r),
                Err(e) => {
                    for e in e.errors {
                        let text = e.to_string();
                        match seen.iter_mut().find(|(t, _)| *t == text) {
                            Some((_, members)) => members.push(i),
                            None => seen.push((text, vec![i])),
                        }
                    }
                }
            }
        }
        if seen.is_empty() {
            // The members' spectra share one wavelength dimension when
            // collected: the same periodic stretch and rail grid.
            let grids: Vec<(f64, usize, f64)> = ok
                .iter()
                .map(|r| {
                    let g = crate::build::study_grid(&r.scene);
                    (g.x_min, g.nx, g.dx)
                })
                .collect();
            let first = grids[0];
            let errors: Vec<SpecError> = grids
                .iter()
                .enumerate()
                .filter(|(_, g)| **g != first)
                .map(|(i, (x_min, nx, dx))| SpecError {
                    key: self.describe(i),
                    message: format!(
                        "rail grid of {nx} nodes every {dx} m from {x_min} m, not member 0's {} every {} m from {} m: \
                         a sweep's members must share the stretch and rail grid (rail.x_min, rail.x_max, rail.dx), \
                         or their spectra cannot be collected on one wavelength dimension",
                        first.1, first.2, first.0
                    ),
                })
                .collect();
            if errors.is_empty() {
                return Ok(ok);
            }
            return Err(SpecErrors { path: self.path.clone(), errors });
        }
        let errors = seen
            .into_iter()
            .map(|(message, members)| {
                let key = if members.len() == self.len() && self.len() > 1 {
                    format!("all {} members", self.len())
                } else if members.len() > 3 {
                    format!("{} and {} more members", self.describe(members[0]), members.len() - 1)
                } else {
                    members.iter().map(|m| self.describe(*m)).collect::<Vec<_>>().join("; ")
                };
                SpecError { key, message }
            })
            .collect();
        Err(SpecErrors { path: self.path.clone(), errors })
    }

    /// `member 3 (rolling.speed=27.78, track.pad_stiffness=2e8)`.
    pub fn describe(&self, index: usize) -> String {
        format!("member {index} ({})", self.member(index).overrides.join(", "))
    }
}

/// One `[[axis]]` as read.
struct Axis {
    key: String,
    values: Vec<Value>,
    zip: bool,
}

fn read_axes(root: &mut Table, errors: &mut Vec<SpecError>) -> Vec<Axis> {
    let err = |key: String, message: String| SpecError { key, message };
    let items = match root.remove("axis") {
        None => {
            errors.push(err("axis".into(), "missing; a sweep needs at least one [[axis]]".into()));
            return Vec::new();
        }
        Some(Value::Array(a)) if a.is_empty() => {
            errors.push(err("axis".into(), "a sweep needs at least one [[axis]]".into()));
            return Vec::new();
        }
        Some(Value::Array(a)) => a,
        Some(other) => {
            errors.push(err("axis".into(), format!("expected an array of tables ([[axis]]), found `{other}`")));
            return Vec::new();
        }
    };
    let mut axes: Vec<Axis> = Vec::new();
    for (i, item) in items.into_iter().enumerate() {
        let at = |k: &str| format!("axis[{i}].{k}");
        let Value::Table(mut t) = item else {
            errors.push(err(format!("axis[{i}]"), "expected a table".into()));
            continue;
        };
        let key = match t.remove("key") {
            Some(Value::String(k))
                if k.split('.').count() >= 2 && !k.contains('=') && k.split('.').all(|p| !p.is_empty()) =>
            {
                Some(k)
            }
            Some(other) => {
                errors.push(err(
                    at("key"),
                    format!("expected a dotted config key such as \"rolling.speed\", found `{other}`"),
                ));
                None
            }
            None => {
                errors.push(err(at("key"), "missing; expected a config key such as \"rolling.speed\"".into()));
                None
            }
        };
        let values = match t.remove("values") {
            Some(Value::Array(v)) if v.is_empty() => {
                errors.push(err(at("values"), "is empty; an axis needs at least one value".into()));
                None
            }
            Some(Value::Array(v)) => {
                let kind = |v: &Value| match v {
                    Value::Integer(_) | Value::Float(_) => Some("number"),
                    Value::String(_) => Some("string"),
                    Value::Boolean(_) => Some("boolean"),
                    _ => None,
                };
                if let Some((j, bad)) = v.iter().enumerate().find(|(_, x)| kind(x).is_none()) {
                    errors.push(err(at("values"), format!("value {j} `{bad}`: expected numbers, strings or booleans")));
                    None
                } else if v.iter().any(|x| kind(x) != kind(&v[0])) {
                    errors.push(err(
                        at("values"),
                        "mixes types; all values of an axis must be numbers, or all strings, or all booleans".into(),
                    ));
                    None
                } else if v.iter().any(|x| matches!(x, Value::Float(f) if !f.is_finite())) {
                    errors.push(err(at("values"), "holds a value that is not finite".into()));
                    None
                } else {
                    Some(v)
                }
            }
            Some(other) => {
                errors.push(err(at("values"), format!("expected a list of values, found `{other}`")));
                None
            }
            None => {
                errors.push(err(at("values"), "missing; expected a list of values".into()));
                None
            }
        };
        let zip = match t.remove("zip") {
            None => Some(false),
            Some(Value::Boolean(b)) => Some(b),
            Some(other) => {
                errors.push(err(at("zip"), format!("expected true or false, found `{other}`")));
                None
            }
        };
        for (k, _) in t {
            errors.push(err(at(&k), "unknown key; allowed: key, values, zip".into()));
        }
        if let (Some(key), Some(values), Some(zip)) = (key, values, zip) {
            if let Some(j) = axes.iter().position(|a| a.key == key) {
                errors.push(err(at("key"), format!("= \"{key}\" is already axis[{j}]'s key")));
            } else {
                axes.push(Axis { key, values, zip });
            }
        }
    }
    axes
}

/// The dimensions of the axes: each unzipped axis its own, the zipped ones
/// one (at the place of the first), their lengths checked.
fn dimensions(axes: &[Axis], errors: &mut Vec<SpecError>) -> Vec<Dimension> {
    let mut dims: Vec<Dimension> = Vec::new();
    let mut zipped: Option<usize> = None;
    for (i, a) in axes.iter().enumerate() {
        match (a.zip, zipped) {
            (true, Some(d)) => {
                let first = &dims[d];
                if a.values.len() != first.len() {
                    errors.push(SpecError {
                        key: format!("axis[{i}].values"),
                        message: format!(
                            "has {} values, but the zipped axis \"{}\" has {}; zipped axes must have equal lengths",
                            a.values.len(),
                            first.keys[0],
                            first.len()
                        ),
                    });
                    continue;
                }
                dims[d].keys.push(a.key.clone());
                dims[d].values.push(a.values.clone());
            }
            (true, None) => {
                zipped = Some(dims.len());
                dims.push(Dimension { keys: vec![a.key.clone()], values: vec![a.values.clone()] });
            }
            (false, _) => dims.push(Dimension { keys: vec![a.key.clone()], values: vec![a.values.clone()] }),
        }
    }
    dims
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(dims: Vec<Dimension>) -> SweepSpec {
        SweepSpec {
            path: "s.toml".into(),
            base: "b.toml".into(),
            base_text: String::new(),
            output: "out".into(),
            set: vec![],
            dims,
        }
    }

    fn dim(key: &str, n: i64) -> Dimension {
        Dimension { keys: vec![key.into()], values: vec![(0..n).map(Value::Integer).collect()] }
    }

    #[test]
    fn members_are_row_major_with_the_last_dimension_fastest() {
        let s = spec(vec![dim("a.x", 2), dim("b.y", 3)]);
        assert_eq!(s.len(), 6);
        let m = s.member(4);
        assert_eq!(m.position, vec![1, 1]);
        assert_eq!(m.overrides, vec!["a.x=1".to_string(), "b.y=1".to_string()]);
        assert_eq!(s.member_name(4), "member_0004");
        assert_eq!(dimension_name("traffic.mix[1].share"), "traffic_mix_1_share");
    }

    #[test]
    fn zipped_axes_make_one_dimension() {
        let axes = vec![
            Axis { key: "a.x".into(), values: vec![Value::Integer(1), Value::Integer(2)], zip: true },
            Axis { key: "c.z".into(), values: vec![Value::Float(0.5)], zip: false },
            Axis { key: "b.y".into(), values: vec![Value::String("p".into()), Value::String("q".into())], zip: true },
        ];
        let mut errors = Vec::new();
        let dims = dimensions(&axes, &mut errors);
        assert!(errors.is_empty());
        assert_eq!(dims.len(), 2);
        assert_eq!(dims[0].keys, vec!["a.x", "b.y"]);
        let s = spec(dims);
        assert_eq!(s.member(1).overrides, vec!["a.x=2", "b.y=\"q\"", "c.z=0.5"]);
        let short = vec![
            Axis { key: "a.x".into(), values: vec![Value::Integer(1), Value::Integer(2)], zip: true },
            Axis { key: "b.y".into(), values: vec![Value::Integer(1)], zip: true },
        ];
        dimensions(&short, &mut errors);
        assert_eq!(errors.len(), 1);
        assert!(errors[0].to_string().starts_with("axis[1].values: has 1 values, but the zipped axis \"a.x\" has 2"));
    }
}
