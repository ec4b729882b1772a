//! Typed, range-checked reading of one TOML section, collecting every error
//! (unknown key, missing key, wrong type, out of range) instead of stopping at
//! the first, and recording the resolved value (defaults filled in). A
//! number may be written as a string with its unit (`"70km/h"`), converted
//! to the key's SI unit ([`super::quantity`]); an unknown key is answered
//! with the nearest known one.

use super::ConfigError;
use super::quantity::{example, parse_quantity};
use super::units::key_units;
use toml::{Table, Value};

/// Allowed range of a number, with its description for error messages.
#[derive(Debug, Clone, Copy)]
pub enum Range {
    /// Any finite value.
    Finite,
    /// > 0, finite.
    Positive,
    /// > 0, infinity allowed.
    PositiveOrInf,
    /// >= 0, finite.
    NonNegative,
    /// Non-zero, infinity allowed (signed radii).
    NonZeroOrInf,
    /// lo <= v <= hi.
    Closed(f64, f64),
    /// lo < v <= hi.
    OpenClosed(f64, f64),
    /// lo <= v < hi.
    ClosedOpen(f64, f64),
}

impl Range {
    fn contains(self, v: f64) -> bool {
        match self {
            Range::Finite => v.is_finite(),
            Range::Positive => v > 0.0 && v.is_finite(),
            Range::PositiveOrInf => v > 0.0,
            Range::NonNegative => v >= 0.0 && v.is_finite(),
            Range::NonZeroOrInf => v != 0.0 && !v.is_nan(),
            Range::Closed(lo, hi) => (lo..=hi).contains(&v),
            Range::OpenClosed(lo, hi) => v > lo && v <= hi,
            Range::ClosedOpen(lo, hi) => v >= lo && v < hi,
        }
    }

    fn describe(self) -> String {
        match self {
            Range::Finite => "a finite number".into(),
            Range::Positive => "a finite number > 0".into(),
            Range::PositiveOrInf => "a number > 0 or inf".into(),
            Range::NonNegative => "a finite number >= 0".into(),
            Range::NonZeroOrInf => "a non-zero number or +-inf".into(),
            Range::Closed(lo, hi) => format!("a number in [{lo}, {hi}]"),
            Range::OpenClosed(lo, hi) => format!("a number in ({lo}, {hi}]"),
            Range::ClosedOpen(lo, hi) => format!("a number in [{lo}, {hi})"),
        }
    }
}

/// Reader of one section (a TOML table) at dotted path `path`.
pub struct Section<'a> {
    path: String,
    table: Table,
    errors: &'a mut Vec<ConfigError>,
    /// The keys asked for (present or not): the known keys of the section,
    /// for "did you mean".
    asked: Vec<String>,
    /// The resolved section (defaults filled in).
    pub resolved: Table,
}

impl<'a> Section<'a> {
    /// Takes `name` out of `parent` (a missing section reads as empty).
    pub fn new(parent: &mut Table, prefix: &str, name: &str, errors: &'a mut Vec<ConfigError>) -> Self {
        let path = if prefix.is_empty() { name.to_string() } else { format!("{prefix}.{name}") };
        let table = match parent.remove(name) {
            None => Table::new(),
            Some(Value::Table(t)) => t,
            Some(other) => {
                errors.push(ConfigError::new(&path, format!("must be a table, found {}", other.type_str())));
                Table::new()
            }
        };
        Section { path, table, errors, asked: Vec::new(), resolved: Table::new() }
    }

    /// A section from an already extracted table (array elements).
    pub fn from_table(path: String, table: Table, errors: &'a mut Vec<ConfigError>) -> Self {
        Section { path, table, errors, asked: Vec::new(), resolved: Table::new() }
    }

    /// Dotted name of `key` in this section.
    pub fn key(&self, key: &str) -> String {
        format!("{}.{key}", self.path)
    }

    /// Whether `key` is (still) in the section.
    pub fn has(&self, key: &str) -> bool {
        super::schema::note(&self.key(key), None);
        self.table.contains_key(key)
    }

    /// Takes `key`'s raw value out of the section (None when absent),
    /// counting it as a known key.
    pub fn raw(&mut self, key: &str) -> Option<Value> {
        super::schema::note(&self.key(key), Some("a string"));
        self.ask(key);
        self.table.remove(key)
    }

    /// Takes `key` out of the section where it is given and records
    /// `message` as its error (a key that does not fit the other keys).
    pub fn reject(&mut self, key: &str, message: &str) {
        self.ask(key);
        if self.table.remove(key).is_some() {
            self.error(key, message.to_string());
        }
    }

    fn ask(&mut self, key: &str) {
        if !self.asked.iter().any(|k| k == key) {
            self.asked.push(key.to_string());
        }
    }

    /// Records an error on `key`.
    pub fn error(&mut self, key: &str, message: String) {
        let k = self.key(key);
        self.errors.push(ConfigError::new(&k, message));
    }

    /// Takes `key` out of the section: the value converted by `extract`,
    /// `default` when absent, None (with the error recorded) when missing
    /// without default or of the wrong type. `expect` describes the allowed
    /// values for the messages.
    fn take<T>(
        &mut self,
        key: &str,
        default: Option<T>,
        expect: &str,
        extract: impl Fn(Value) -> Result<T, Value>,
    ) -> Option<T> {
        self.ask(key);
        super::schema::note(&self.key(key), Some(expect));
        match self.table.remove(key) {
            None => {
                if default.is_none() {
                    self.error(key, format!("missing; expected {expect}"));
                }
                default
            }
            Some(v) => match extract(v) {
                Ok(t) => Some(t),
                Err(other) => {
                    self.error(key, format!("expected {expect}, found {} `{other}`", other.type_str()));
                    None
                }
            },
        }
    }

    /// A number in `range`; `default` when absent (None = required).
    /// Returns None when missing or invalid (the error is recorded).
    pub fn f64(&mut self, key: &str, default: Option<f64>, range: Range) -> Option<f64> {
        let unit = key_units(&self.key(key));
        if let (Some(Value::String(text)), Some(unit)) = (self.table.get(key), unit) {
            match parse_quantity(text, unit) {
                Ok(v) => {
                    self.table.insert(key.into(), Value::Float(v));
                }
                Err(e) => {
                    self.table.remove(key);
                    self.ask(key);
                    self.error(key, format!("{e}; expected {} in {unit}", range.describe()));
                    return None;
                }
            }
        }
        let expect = match unit {
            Some(u) if u != "1" => {
                format!("{} in {u} (or a string with its unit, e.g. {})", range.describe(), example(u))
            }
            _ => range.describe(),
        };
        let v = self.take(key, default, &expect, |v| match v {
            Value::Float(f) => Ok(f),
            Value::Integer(i) => Ok(i as f64),
            other => Err(other),
        })?;
        if !range.contains(v) {
            self.error(key, format!("= {v} is out of range; expected {}", range.describe()));
            return None;
        }
        self.resolved.insert(key.into(), Value::Float(v));
        Some(v)
    }

    /// An integer in `[lo, hi]`.
    pub fn usize(&mut self, key: &str, default: Option<usize>, lo: usize, hi: usize) -> Option<usize> {
        let expect = format!("an integer in [{lo}, {hi}]");
        let v = self.take(key, default.map(|d| d as i64), &expect, |v| match v {
            Value::Integer(i) => Ok(i),
            Value::Float(x) if whole(x) => Ok(x as i64),
            other => Err(other),
        })?;
        if v < lo as i64 || v > hi as i64 {
            self.error(key, format!("= {v} is out of range; expected {expect}"));
            return None;
        }
        self.resolved.insert(key.into(), Value::Integer(v));
        Some(v as usize)
    }

    /// One of the `allowed` strings.
    pub fn choice(&mut self, key: &str, default: Option<&str>, allowed: &[&str]) -> Option<String> {
        let expect = format!("one of {}", allowed.iter().map(|a| format!("\"{a}\"")).collect::<Vec<_>>().join(", "));
        let v = self.take(key, default.map(str::to_string), &expect, |v| match v {
            Value::String(s) => Ok(s),
            other => Err(other),
        })?;
        if !allowed.contains(&v.as_str()) {
            self.error(key, format!("= \"{v}\" is not allowed; expected {expect}"));
            return None;
        }
        self.resolved.insert(key.into(), Value::String(v.clone()));
        Some(v)
    }

    /// A boolean.
    pub fn bool(&mut self, key: &str, default: bool) -> Option<bool> {
        let v = self.take(key, Some(default), "true or false", |v| match v {
            Value::Boolean(b) => Ok(b),
            other => Err(other),
        })?;
        self.resolved.insert(key.into(), Value::Boolean(v));
        Some(v)
    }

    /// Free text.
    pub fn string(&mut self, key: &str, default: &str) -> Option<String> {
        let v = self.take(key, Some(default.to_string()), "a string", |v| match v {
            Value::String(s) => Ok(s),
            other => Err(other),
        })?;
        self.resolved.insert(key.into(), Value::String(v.clone()));
        Some(v)
    }

    /// A non-empty list of at most `max` numbers in `range`.
    pub fn f64_list(&mut self, key: &str, default: Vec<f64>, range: Range, max: usize) -> Option<Vec<f64>> {
        let expect = format!("a list of 1 to {max} numbers, each {}", range.describe());
        let unit = key_units(&self.key(key));
        self.ask(key);
        super::schema::note(&self.key(key), Some(&expect));
        let v = match self.table.remove(key) {
            None => default,
            Some(Value::Array(a)) if (1..=max).contains(&a.len()) => {
                let mut out = Vec::new();
                for item in a {
                    let with_unit = match (&item, unit) {
                        (Value::String(t), Some(u)) => match parse_quantity(t, u) {
                            Ok(v) => Some(v),
                            Err(e) => {
                                self.error(key, format!("{e}; expected {expect}"));
                                return None;
                            }
                        },
                        _ => None,
                    };
                    match with_unit.or(item.as_float()).or(item.as_integer().map(|i| i as f64)) {
                        Some(x) if range.contains(x) => out.push(x),
                        _ => {
                            self.error(key, format!("contains `{item}`; expected {expect}"));
                            return None;
                        }
                    }
                }
                out
            }
            Some(other) => {
                self.error(key, format!("expected {expect}, found `{other}`"));
                return None;
            }
        };
        self.resolved.insert(key.into(), Value::Array(v.iter().map(|x| Value::Float(*x)).collect()));
        Some(v)
    }

    /// A list of integers in `[0, hi]`.
    pub fn usize_list(&mut self, key: &str, default: Vec<usize>, hi: usize) -> Option<Vec<usize>> {
        let expect = format!("a list of integers in [0, {hi}]");
        self.ask(key);
        super::schema::note(&self.key(key), Some(&expect));
        let v = match self.table.remove(key) {
            None => default,
            Some(Value::Array(a)) => {
                let mut out = Vec::new();
                for item in a {
                    match item.as_integer().or(item.as_float().filter(|x| whole(*x)).map(|x| x as i64)) {
                        Some(i) if (0..=hi as i64).contains(&i) => out.push(i as usize),
                        _ => {
                            self.error(key, format!("contains `{item}`; expected {expect}"));
                            return None;
                        }
                    }
                }
                out
            }
            Some(other) => {
                self.error(key, format!("expected {expect}, found {}", other.type_str()));
                return None;
            }
        };
        self.resolved.insert(key.into(), Value::Array(v.iter().map(|i| Value::Integer(*i as i64)).collect()));
        Some(v)
    }

    /// An array of tables (e.g. `[[load.harmonics]]`); each element is read
    /// with `read` as section `key[i]`.
    pub fn array_of_tables<T>(&mut self, key: &str, mut read: impl FnMut(&mut Section) -> Option<T>) -> Option<Vec<T>> {
        self.ask(key);
        super::schema::note(&self.key(key), Some("an array of tables"));
        let items = match self.table.remove(key) {
            None => Vec::new(),
            Some(Value::Array(a)) => a,
            Some(other) => {
                self.error(key, format!("expected an array of tables, found {}", other.type_str()));
                return None;
            }
        };
        let mut out = Vec::new();
        let mut resolved = Vec::new();
        let mut ok = true;
        for (i, item) in items.into_iter().enumerate() {
            let path = format!("{}[{i}]", self.key(key));
            let Value::Table(t) = item else {
                self.errors.push(ConfigError::new(&path, "expected a table".into()));
                ok = false;
                continue;
            };
            let mut s = Section::from_table(path, t, self.errors);
            let v = read(&mut s);
            resolved.push(Value::Table(s.finish()));
            match v {
                Some(v) => out.push(v),
                None => ok = false,
            }
        }
        self.resolved.insert(key.into(), Value::Array(resolved));
        ok.then_some(out)
    }

    /// Reports the keys nobody asked for and returns the resolved section.
    pub fn finish(self) -> Table {
        // The known keys: those asked for, and the numeric keys of this
        // section in the unit table (read only for some choices).
        let plain = super::units::strip_indices(&self.path);
        let mut known: Vec<String> = self.asked.clone();
        for (k, _) in super::units::all_keys() {
            if let Some(rest) = k.strip_prefix(&plain).and_then(|r| r.strip_prefix('.'))
                && !rest.contains('.')
                && !known.iter().any(|x| x == rest)
            {
                known.push(rest.to_string());
            }
        }
        for (k, _) in self.table {
            let key = format!("{}.{k}", self.path);
            let message = match elsewhere(&plain, &k) {
                Some(full) if nearest(&k, known.iter().map(String::as_str)).is_none() => {
                    format!("unknown key here; did you mean `{full}` (in [{}])?", section_of(&full))
                }
                _ => unknown_key_message(&k, &known),
            };
            self.errors.push(ConfigError::new(&key, message));
        }
        self.resolved
    }
}

/// The full name of a key called `key` in another section than `section`
/// (a key of the unit table: every numeric key), for a key written in the
/// wrong section; the first in the table where several sections have it.
fn elsewhere(section: &str, key: &str) -> Option<String> {
    super::units::all_keys()
        .map(|(k, _)| k)
        .find(|k| k.rsplit_once('.').is_some_and(|(s, name)| name == key && s != section && !s.contains('.')))
        .map(str::to_string)
}

/// `rolling.speed` -> `rolling`.
fn section_of(key: &str) -> &str {
    key.rsplit_once('.').map_or(key, |(s, _)| s)
}

/// "unknown key" with the nearest of `known` where one is near (at most a
/// third of its letters changed), else the list of known keys.
pub fn unknown_key_message(key: &str, known: &[String]) -> String {
    match nearest(key, known.iter().map(String::as_str)) {
        Some(k) => format!("unknown key; did you mean `{k}`?"),
        None if known.is_empty() => "unknown key".into(),
        None => {
            let mut list: Vec<&str> = known.iter().map(String::as_str).collect();
            list.sort_unstable();
            format!("unknown key; known here: {}", list.join(", "))
        }
    }
}

/// The candidate nearest to `word` in (Damerau-Levenshtein) edit
/// distance, if within a third of the longer name (at least 2 edits), or
/// the candidate that starts with `word` or that `word` starts with.
pub fn nearest<'k>(word: &str, candidates: impl Iterator<Item = &'k str>) -> Option<&'k str> {
    let w = word.to_lowercase();
    candidates
        .map(|c| {
            let d = strsim::damerau_levenshtein(&w, &c.to_lowercase());
            let allowed = (w.chars().count().max(c.chars().count()) / 3).max(2);
            let prefix = c.len() >= 3 && w.len() >= 3 && (c.starts_with(&*w) || w.starts_with(c));
            (c, d, d <= allowed || prefix)
        })
        .filter(|(_, _, near)| *near)
        .min_by_key(|(_, d, _)| *d)
        .map(|(c, _, _)| c)
}

/// Whether a float is a whole number written as a float (`1e3`, `1000.0`),
/// taken as that integer: below 2^52, where the float still holds the
/// halves (beyond, TOML has already rounded what was written).
fn whole(x: f64) -> bool {
    x.fract() == 0.0 && x.abs() < 2f64.powi(52)
}
