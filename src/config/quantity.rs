//! Values with units: a config value written as a string with its unit
//! (`"70km/h"`, `"20MN/m"`, `"2.5mm"`, `"200MPa"`), in the file or after
//! `--set`, converted to the key's SI unit ([`super::units::key_units`]).
//!
//! The arithmetic and the unit database are those of `rink-core` (the
//! library behind the `rink` units calculator: exact rational arithmetic,
//! GNU-units-style definitions, dimension checking): the value is divided by
//! the key's SI unit and must come out dimensionless, so a unit of the wrong
//! kind is refused. ASCII powers (`m2`, `N m2`) are read as `m^2`. The
//! database is loaded once per thread, and only when a value carries a unit
//! (about 0.1 s), so configs of plain numbers pay nothing.
//!
//! Also here: each key's engineering display (`check` prints 27.78 m/s as
//! 100 km/h) and the plausibility ranges behind the notes on likely unit
//! mistakes (`rolling.speed = 70` meant as km/h).

use std::cell::RefCell;

thread_local! {
    static CONTEXT: RefCell<Option<rink_core::Context>> = const { RefCell::new(None) };
}

/// Keys whose unit is not a physical unit: a value with a unit is refused.
fn is_plain(si_unit: &str) -> bool {
    si_unit == "1" || si_unit.starts_with("dB")
}

/// A config value as a number in `si_unit`: a TOML number, or a string
/// with its unit ([`parse_quantity`]); None for anything else.
pub fn number(value: &toml::Value, si_unit: &str) -> Option<f64> {
    match value {
        toml::Value::String(t) => parse_quantity(t, si_unit).ok(),
        v => v.as_float().or(v.as_integer().map(|i| i as f64)),
    }
}

/// `text` (a number followed by a unit, e.g. `70km/h`) in `si_unit`, the
/// key's SI unit. The error says what was wrong (the unit unknown, or of
/// another kind than `si_unit`) and gives an example of the right kind.
pub fn parse_quantity(text: &str, si_unit: &str) -> Result<f64, String> {
    let text = text.trim();
    let (number, unit) = split_number(text);
    if number.is_empty() {
        return Err(format!("`{text}` is not a number with a unit (such as {})", example(si_unit)));
    }
    if unit.is_empty() {
        return number.parse::<f64>().map_err(|_| format!("`{text}` is not a number"));
    }
    if is_plain(si_unit) {
        return Err(format!(
            "`{text}` carries a unit, but the key is a plain number ({}); write the number alone",
            if si_unit == "1" { "dimensionless".to_string() } else { format!("in {si_unit}") }
        ));
    }
    // What a unit is written with; rink's lexer is not asked about anything
    // else (a backslash escape made it panic).
    if let Some(c) =
        unit.chars().find(|c| !(c.is_alphanumeric() || " ./*^()-+_%'\"".contains(*c) || "²³µ°·".contains(*c)))
    {
        return Err(format!("`{text}`: `{c}` is not part of a unit (such as {})", example(si_unit)));
    }
    let value_expr = format!("{number} {}", ascii_powers(unit));
    let ratio = eval(&format!("({value_expr}) / ({})", ascii_powers(si_unit)))?;
    match ratio {
        (v, true) if v.is_finite() => Ok(v),
        (_, true) => Err(format!("`{text}` is not a finite number")),
        (_, false) => {
            let kind = eval_quantity(&value_expr).unwrap_or_else(|| "another kind of quantity".into());
            let want = eval_quantity(&format!("1 {}", ascii_powers(si_unit))).unwrap_or_else(|| si_unit.to_string());
            Err(format!(
                "`{text}` is {} {kind}, but the key is {} {want} in {si_unit} (e.g. {})",
                article(&kind),
                article(&want),
                example(si_unit)
            ))
        }
    }
}

fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" }
}

/// An example of a value with a unit of the kind of `si_unit`.
pub fn example(si_unit: &str) -> String {
    let e = match si_unit {
        "m/s" => "\"70km/h\" or \"19.4m/s\"",
        "N" => "\"70kN\"",
        "Pa" => "\"210GPa\"",
        "N/m" => "\"20MN/m\"",
        "m" => "\"2.5mm\"",
        "kg" => "\"600kg\" or \"1.2t\"",
        "kg/m" => "\"60kg/m\"",
        "N m2" => "\"6.4MN m2\"",
        "N s/m" => "\"50kN s/m\"",
        "rad" => "\"30deg\"",
        _ => return format!("a number in {si_unit}"),
    };
    e.to_string()
}

/// Splits `70km/h` into (`70`, `km/h`): the longest leading number (sign,
/// digits, decimal point, exponent), then the rest, trimmed.
fn split_number(text: &str) -> (&str, &str) {
    let b = text.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let digits = |i: &mut usize| {
        let s = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        *i > s
    };
    let mut any = digits(&mut i);
    if i < b.len() && b[i] == b'.' {
        i += 1;
        any |= digits(&mut i);
    }
    if !any {
        return ("", text);
    }
    // An exponent only where digits follow (`2e3`, not `2 eV`).
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        if j < b.len() && b[j].is_ascii_digit() {
            i = j;
            digits(&mut i);
        }
    }
    (&text[..i], text[i..].trim())
}

/// `m2` -> `m^2`, `N m2` -> `N m^2`: a digit 2 or 3 right after a letter
/// is a power (no unit name ends in a digit).
fn ascii_powers(unit: &str) -> String {
    let mut out = String::with_capacity(unit.len() + 4);
    let mut prev_letter = false;
    for c in unit.chars() {
        if prev_letter && (c == '2' || c == '3') {
            out.push('^');
        }
        prev_letter = c.is_alphabetic();
        out.push(c);
    }
    out
}

/// Evaluates `expr`: (value, dimensionless).
fn eval(expr: &str) -> Result<(f64, bool), String> {
    with_context(|ctx| match rink_core::eval(ctx, expr) {
        Ok(rink_core::output::QueryReply::Number(n)) => match n.raw_value {
            Some(v) => Ok((v.value.to_f64(), v.unit.is_dimensionless())),
            None => Err(format!("cannot read `{expr}` as a number with a unit")),
        },
        Ok(_) => Err(format!("cannot read `{expr}` as a number with a unit")),
        Err(e) => Err(format!("cannot read the unit: {e}")),
    })
}

/// The name of the kind of quantity `expr` is (velocity, force, ...).
fn eval_quantity(expr: &str) -> Option<String> {
    with_context(|ctx| match rink_core::eval(ctx, expr) {
        Ok(rink_core::output::QueryReply::Number(n)) => n.quantity.map(|q| q.replace('_', " ")),
        _ => None,
    })
}

fn with_context<T>(f: impl FnOnce(&mut rink_core::Context) -> T) -> T {
    CONTEXT.with(|c| {
        let mut c = c.borrow_mut();
        let ctx =
            c.get_or_insert_with(|| rink_core::simple_context().expect("rink-core's bundled unit database loads"));
        f(ctx)
    })
}

/// `value` (in `si_unit`) in the unit an engineer would write it in, where
/// that differs from SI: `27.78 m/s` -> `100 km/h`, `2.1e11 Pa` -> `210 GPa`.
pub fn engineering(value: f64, si_unit: &str) -> Option<String> {
    if !value.is_finite() {
        return None;
    }
    let a = value.abs();
    let scaled = |f: f64, u: &str| Some(format!("{} {u}", sig(value / f)));
    match si_unit {
        "m/s" if a >= 1.0 => scaled(1.0 / 3.6, "km/h"),
        "rad" => scaled(std::f64::consts::PI / 180.0, "deg"),
        "m" if a == 0.0 => None,
        "m" if a < 1e-4 => scaled(1e-6, "um"),
        "m" if a < 1.0 => scaled(1e-3, "mm"),
        "kg" if a >= 1e3 => scaled(1e3, "t"),
        "Pa" | "N" | "N/m" | "N s/m" | "N m2" => {
            let (f, p) = if a >= 1e9 {
                (1e9, "G")
            } else if a >= 1e6 {
                (1e6, "M")
            } else if a >= 1e3 {
                (1e3, "k")
            } else {
                return None;
            };
            scaled(f, &format!("{p}{si_unit}"))
        }
        _ => None,
    }
}

/// Four significant digits, trailing zeros dropped.
fn sig(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

/// Where a number written without its unit is likely meant in another unit:
/// (key without indices, plausible range in SI, the units it may have been
/// meant in with their factor to SI).
type Plausible = (&'static str, f64, f64, &'static [(&'static str, f64)]);
const PLAUSIBLE: &[Plausible] = &[
    ("rolling.speed", 1.0, 50.0, &[("km/h", 1.0 / 3.6)]),
    ("traffic.mix.speed", 1.0, 50.0, &[("km/h", 1.0 / 3.6)]),
    ("load.normal_force", 5e3, 5e5, &[("kN", 1e3)]),
    ("traffic.mix.normal_force", 5e3, 5e5, &[("kN", 1e3)]),
    ("material.young_modulus", 1e10, 1e12, &[("GPa", 1e9), ("MPa", 1e6)]),
    ("geometry.wheel_radius", 0.1, 1.0, &[("mm", 1e-3)]),
    ("geometry.rail_head_radius", 0.05, 2.0, &[("mm", 1e-3)]),
    ("geometry.wheel_profile_radius", 0.05, 100.0, &[("mm", 1e-3)]),
    ("track.pad_stiffness", 1e7, 1e10, &[("MN/m", 1e6), ("kN/m", 1e3)]),
    ("track.ballast_stiffness", 1e6, 1e10, &[("MN/m", 1e6), ("kN/m", 1e3)]),
    ("track.rail_bending_stiffness", 1e6, 2e7, &[("MN m2", 1e6), ("kN m2", 1e3)]),
    ("track.rail_mass", 20.0, 100.0, &[]),
    ("track.sleeper_mass", 20.0, 600.0, &[]),
    ("dynamics.unsprung_mass", 50.0, 5000.0, &[("t", 1e3)]),
    ("traffic.axle_load", 5e3, 4e4, &[("t", 1e3)]),
    ("traffic.mix.axle_load", 5e3, 4e4, &[("t", 1e3)]),
    ("traffic.mix.unsprung_mass", 50.0, 5000.0, &[("t", 1e3)]),
    ("roughness.rms", 1e-9, 1e-3, &[("um", 1e-6), ("mm", 1e-3)]),
    ("roughness.harmonics.amplitude", 1e-9, 1e-3, &[("um", 1e-6), ("mm", 1e-3)]),
    ("roughness.wavelength_min", 1e-3, 10.0, &[("mm", 1e-3)]),
    ("roughness.wavelength_max", 1e-3, 10.0, &[("mm", 1e-3)]),
    ("load.harmonics.wavelength", 1e-3, 10.0, &[("mm", 1e-3)]),
];

/// A note when `value` of `key` (in SI, written without a unit) lies
/// outside the key's plausible range, naming the unit it was likely meant
/// in. Zero and infinite values (flat profiles, no stiffness) pass.
pub fn plausibility(key: &str, value: f64) -> Option<String> {
    let plain = super::units::strip_indices(key);
    let (_, lo, hi, units) = PLAUSIBLE.iter().find(|(k, ..)| *k == plain)?;
    let a = value.abs();
    if a == 0.0 || !a.is_finite() || (*lo..=*hi).contains(&a) {
        return None;
    }
    let si = super::units::key_units(key).unwrap_or("");
    let here = engineering(value, si).map(|e| format!(" ({e})")).unwrap_or_default();
    let side = if a < *lo { "below" } else { "above" };
    let meant = units.iter().find(|(_, f)| (*lo..=*hi).contains(&(a * f)));
    let hint = match meant {
        Some((u, _)) => format!("; if it is in {u}, write it with its unit: \"{}{u}\"", sig(value)),
        None => String::new(),
    };
    Some(format!(
        "{key} = {} {si}{here} is {side} the usual {} .. {} {si}{hint} (a value written with its unit is taken as meant)",
        sig(value),
        sig(*lo),
        sig(*hi)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn characters_no_unit_has_are_refused_before_rink_reads_them() {
        let e = parse_quantity("0\\u", "m/s").unwrap_err();
        assert!(e.contains("is not part of a unit"), "{e}");
        assert!(parse_quantity("1.5 m/s²", "m/s2").is_ok());
    }

    #[test]
    fn values_with_units_convert_to_si() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(parse_quantity("70km/h", "m/s").unwrap(), 70.0 / 3.6));
        assert!(close(parse_quantity("20MN/m", "N/m").unwrap(), 20e6));
        assert_eq!(parse_quantity("70kN", "N").unwrap(), 70e3);
        assert!(close(parse_quantity("22.5t", "kg").unwrap(), 22.5e3));
        assert!(close(parse_quantity("2000/d", "1/d").unwrap(), 2000.0));
        assert_eq!(parse_quantity("2.5mm", "m").unwrap(), 2.5e-3);
        assert_eq!(parse_quantity("200 MPa", "Pa").unwrap(), 200e6);
        assert_eq!(parse_quantity("6.4MN m2", "N m2").unwrap(), 6.4e6);
        assert_eq!(parse_quantity("3.4e-14 m2/N", "m2/N").unwrap(), 3.4e-14);
        assert_eq!(parse_quantity("10um", "m").unwrap(), 1e-5);
        assert_eq!(parse_quantity("1.2t", "kg").unwrap(), 1200.0);
        assert_eq!(parse_quantity("0.5", "m").unwrap(), 0.5);
    }

    #[test]
    fn a_unit_of_the_wrong_kind_is_refused() {
        let e = parse_quantity("70kN", "m/s").unwrap_err();
        assert!(e.contains("force") && e.contains("velocity") && e.contains("m/s"), "{e}");
        let e = parse_quantity("20MN/m", "N").unwrap_err();
        assert!(e.contains("N") && e.contains("70kN"), "{e}");
        assert!(parse_quantity("3 mm", "1").unwrap_err().contains("plain number"));
        assert!(parse_quantity("70 blorps", "m/s").unwrap_err().contains("unit"));
        assert!(parse_quantity("fast", "m/s").unwrap_err().contains("number"));
    }

    #[test]
    fn engineering_units() {
        assert_eq!(engineering(27.78, "m/s").unwrap(), "100 km/h");
        assert_eq!(engineering(2.1e11, "Pa").unwrap(), "210 GPa");
        assert_eq!(engineering(100e3, "N").unwrap(), "100 kN");
        assert_eq!(engineering(2e-4, "m").unwrap(), "0.2 mm");
        assert_eq!(engineering(1.5e-6, "m").unwrap(), "1.5 um");
        assert_eq!(engineering(1e-5, "m/s"), None);
        assert_eq!(engineering(0.5, "m").unwrap(), "500 mm");
        assert_eq!(engineering(0.3, "1"), None);
    }

    #[test]
    fn notes_name_the_likely_unit() {
        let n = plausibility("rolling.speed", 70.0).unwrap();
        assert!(n.contains("\"70km/h\""), "{n}");
        let n = plausibility("track.pad_stiffness", 20.0).unwrap();
        assert!(n.contains("\"20MN/m\""), "{n}");
        assert!(plausibility("rolling.speed", 27.78).is_none());
        assert!(plausibility("track.pad_stiffness", 1.2e8).is_none());
        assert!(plausibility("traffic.mix[1].speed", 30.0).is_none());
        let n = plausibility("traffic.axle_load", 22.5).unwrap();
        assert!(n.contains("\"22.5t\""), "{n}");
        assert!(plausibility("traffic.axle_load", 22.5e3).is_none());
        assert!(plausibility("geometry.wheel_profile_radius", f64::INFINITY).is_none());
    }
}
