//! `--set section.key=value` overrides applied to the parsed TOML table
//! before validation. The value is read as a TOML value (`3e4`, `true`,
//! `"fastsim"`); text that is not valid TOML is taken as a string, so
//! `--set contact.model=fastsim` works without quotes; where the key
//! holds a string (in the file, or by default), the text is taken as a
//! string whatever it reads as (`--set track.rail=54E1` is the rail 54E1,
//! not the number 540).
//! Array elements are addressed as `load.harmonics[0].amplitude`.

use super::ConfigError;
use toml::{Table, Value};

/// Applies one `path=value` override; `defaults` is the config with its
/// defaults filled in (the resolved table), which says which keys hold
/// strings.
pub fn apply(root: &mut Table, assignment: &str, defaults: &Table) -> Result<(), ConfigError> {
    let err = |msg: &str| ConfigError::new(&format!("--set {assignment}"), msg.to_string());
    let (path, raw) = assignment.split_once('=').ok_or_else(|| err("expected section.key=value"))?;
    let value = parse_value(raw.trim());
    let parts: Vec<&str> = path.trim().split('.').collect();
    if parts.len() < 2 || parts.iter().any(|p| p.is_empty()) {
        return Err(err("the key must be a dotted path such as material.friction_coefficient"));
    }
    let string_key = matches!(lookup(defaults, &parts), Some(Value::String(_)));
    let mut table = root;
    for (n, part) in parts.iter().enumerate() {
        let (name, index) = split_index(part).ok_or_else(|| err("malformed array index"))?;
        let last = n + 1 == parts.len();
        match (index, last) {
            (None, true) => {
                let string_key = string_key || matches!(table.get(name), Some(Value::String(_)));
                let value = if string_key && !value.is_str() { Value::String(raw.trim().to_string()) } else { value };
                table.insert(name.to_string(), value);
                return Ok(());
            }
            (None, false) => {
                let entry = table.entry(name.to_string()).or_insert_with(|| Value::Table(Table::new()));
                table = entry.as_table_mut().ok_or_else(|| err(&format!("`{name}` is not a table")))?;
            }
            (Some(i), false) => {
                let array = table
                    .get_mut(name)
                    .and_then(Value::as_array_mut)
                    .ok_or_else(|| err(&format!("`{name}` is not an array of tables")))?;
                let len = array.len();
                table = array
                    .get_mut(i)
                    .and_then(Value::as_table_mut)
                    .ok_or_else(|| err(&format!("index {i} out of range: `{name}` has {len} elements")))?;
            }
            (Some(_), true) => return Err(err("cannot replace a whole array element")),
        }
    }
    Ok(())
}

/// The value at the dotted `parts` (array elements as `name[i]`) of `table`.
fn lookup<'t>(table: &'t Table, parts: &[&str]) -> Option<&'t Value> {
    let (first, rest) = parts.split_first()?;
    let (name, index) = split_index(first)?;
    let mut value = table.get(name)?;
    if let Some(i) = index {
        value = value.as_array()?.get(i)?;
    }
    if rest.is_empty() { Some(value) } else { lookup(value.as_table()?, rest) }
}

fn parse_value(raw: &str) -> Value {
    match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => t.remove("v").unwrap_or(Value::String(raw.to_string())),
        Err(_) => Value::String(raw.to_string()),
    }
}

/// `name[3]` -> ("name", Some(3)); `name` -> ("name", None).
fn split_index(part: &str) -> Option<(&str, Option<usize>)> {
    match part.split_once('[') {
        None => Some((part, None)),
        Some((name, rest)) => rest.strip_suffix(']')?.parse().ok().map(|i| (name, Some(i))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_numbers_strings_and_array_elements() {
        let mut t: Table = "[load]\n[[load.harmonics]]\namplitude = 1.0\n".parse().unwrap();
        apply(&mut t, "material.friction_coefficient=0.3", &Table::new()).unwrap();
        apply(&mut t, "contact.model=fastsim", &Table::new()).unwrap();
        apply(&mut t, "load.harmonics[0].amplitude=3e4", &Table::new()).unwrap();
        assert_eq!(t["material"]["friction_coefficient"].as_float(), Some(0.3));
        assert_eq!(t["contact"]["model"].as_str(), Some("fastsim"));
        assert_eq!(t["load"]["harmonics"][0]["amplitude"].as_float(), Some(3e4));
        assert!(
            apply(&mut t, "load.harmonics[3].amplitude=1", &Table::new())
                .unwrap_err()
                .to_string()
                .contains("out of range")
        );
        assert!(apply(&mut t, "nokey", &Table::new()).is_err());
    }

    #[test]
    fn a_string_key_takes_the_text_as_a_string() {
        let mut t: Table = "[track]\nrail = \"UIC60\"\nsleeper_spacing = 0.6\n".parse().unwrap();
        apply(&mut t, "track.rail=54E1", &Table::new()).unwrap();
        assert_eq!(t["track"]["rail"].as_str(), Some("54E1"));
        // A number key still takes a number.
        apply(&mut t, "track.sleeper_spacing=65E-2", &Table::new()).unwrap();
        assert_eq!(t["track"]["sleeper_spacing"].as_float(), Some(0.65));
        // A key the file leaves to its default string.
        let defaults: Table = "[track]\nrail = \"UIC60\"\n".parse().unwrap();
        let mut t = Table::new();
        apply(&mut t, "track.rail=54E1", &defaults).unwrap();
        assert_eq!(t["track"]["rail"].as_str(), Some("54E1"));
    }
}
