//! Reading a measured roughness record: a text file of position and height
//! along the rail, as roughness trolleys export them.
//!
//! What is read (docs: guide/measured-rail.md): one sample per line,
//! fields separated by tabs, semicolons, commas or blanks (with semicolons,
//! a decimal comma is read as a decimal point: `0,001;12,5`); the position
//! in column `position_column` and the height in `height_column` (1-based;
//! default 1 and 2; further columns are ignored); blank lines and comment
//! lines (starting with `#`, `%`, `//` or `!`) anywhere; any number of
//! header lines before the first sample. A unit in a header's column name,
//! in brackets or parentheses (`Distance (m)`, `Displacement [um]`), is
//! checked against the configured unit, or taken where the config gives
//! none. The positions must increase evenly: every step within 1 % of the
//! record's spacing (beyond the rounding of the printed positions), no
//! gaps.
//! Every refusal names the file and the line.

pub use crate::growth::record::RecordSamples;
use std::path::Path;

/// How to read a record.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadOptions {
    /// Position unit, "m" or "mm"; None: from the header, else "m".
    pub position_unit: Option<String>,
    /// Height unit, "um", "mm" or "m"; None: from the header, else "um".
    pub height_unit: Option<String>,
    /// 1-based column of the position.
    pub position_column: usize,
    /// 1-based column of the height.
    pub height_column: usize,
}

/// The allowed position units with their factor to m.
pub const POSITION_UNITS: [(&str, f64); 2] = [("m", 1.0), ("mm", 1e-3)];
/// The allowed height units with their factor to m.
pub const HEIGHT_UNITS: [(&str, f64); 3] = [("um", 1e-6), ("mm", 1e-3), ("m", 1.0)];

/// Relative tolerance of a step against the record's spacing.
pub const SPACING_TOLERANCE: f64 = 0.01;

fn factor(units: &[(&str, f64)], u: &str) -> f64 {
    units.iter().find(|(n, _)| *n == u).map(|(_, f)| *f).expect("a validated unit")
}

/// Reads the record in `file`.
pub fn read_record(file: &Path, options: &ReadOptions) -> Result<RecordSamples, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("cannot read the record {}: {e}", file.display()))?;
    parse_record(&bytes, file, options)
}

/// A line split into fields; `decimal_comma` where `,` is the decimal mark.
fn fields(line: &str) -> (Vec<String>, bool) {
    let clean = |f: &str| f.trim().trim_matches('"').trim().to_string();
    if line.contains(';') {
        (line.split(';').map(clean).collect(), true)
    } else if line.contains('\t') {
        (line.split('\t').map(clean).collect(), false)
    } else if line.contains(',') {
        (line.split(',').map(clean).collect(), false)
    } else {
        (line.split_whitespace().map(clean).collect(), false)
    }
}

/// A finite number, and the size of one unit of its last printed digit.
fn number(field: &str, decimal_comma: bool) -> Option<(f64, f64)> {
    let f = if decimal_comma { field.replace(',', ".") } else { field.to_string() };
    let lower = f.to_ascii_lowercase();
    if lower.contains("inf") || lower.contains("nan") {
        return None;
    }
    let v: f64 = f.parse().ok()?;
    let (mantissa, exp) = match lower.split_once('e') {
        Some((m, e)) => (m.to_string(), e.parse::<i32>().ok()?),
        None => (lower.clone(), 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    Some((v, 10f64.powi(exp - decimals)))
}

/// The unit named in a header field: `Distance (m)`, `height [µm]`.
fn header_unit(field: &str) -> Option<String> {
    let open = field.rfind(['(', '['])?;
    let close = field[open..].find([')', ']'])? + open;
    let u = field[open + 1..close].trim().to_lowercase();
    let u = u.replace(['µ', 'μ', '\u{fffd}'], "u");
    match u.as_str() {
        "m" => Some("m".into()),
        "mm" => Some("mm".into()),
        "um" | "micron" | "microns" | "micrometre" | "micrometer" => Some("um".into()),
        _ => None,
    }
}

fn is_comment(line: &str) -> bool {
    line.starts_with('#') || line.starts_with('%') || line.starts_with("//") || line.starts_with('!')
}

/// Reads a record from its bytes (`file` names it in messages).
pub fn parse_record(bytes: &[u8], file: &Path, options: &ReadOptions) -> Result<RecordSamples, String> {
    let at = |line: usize| format!("{}:{line}", file.display());
    let (pc, hc) = (options.position_column - 1, options.height_column - 1);
    let mut header: Vec<(usize, Vec<String>)> = Vec::new();
    let mut raw: Vec<(f64, f64, f64, usize)> = Vec::new();
    for (i, line) in bytes.split(|b| *b == b'\n').enumerate() {
        let n = i + 1;
        let text = String::from_utf8_lossy(line);
        let text = text.trim_start_matches('\u{feff}').trim();
        if text.is_empty() || is_comment(text) {
            continue;
        }
        let (f, comma) = fields(text);
        let p = f.get(pc).and_then(|x| number(x, comma));
        let h = f.get(hc).and_then(|x| number(x, comma));
        match (p, h) {
            (Some((p, dp)), Some((h, _))) => raw.push((p, h, dp, n)),
            _ if raw.is_empty() => header.push((n, f)),
            _ => {
                let what = if f.len() <= pc.max(hc) {
                    format!("has {} field(s)", f.len())
                } else {
                    format!("has `{}` and `{}`", f[pc], f[hc])
                };
                return Err(format!(
                    "{}: `{text}` {what}; expected numbers in column {} (position) and column {} (height), \
                     or a comment line starting with #",
                    at(n),
                    pc + 1,
                    hc + 1
                ));
            }
        }
    }
    // Units: the config's, checked against the header's; the header's where
    // the config gives none; else the defaults.
    let mut units = [options.position_unit.clone(), options.height_unit.clone()];
    let allowed: [&[(&str, f64)]; 2] = [&POSITION_UNITS, &HEIGHT_UNITS];
    let defaults = ["m", "um"];
    let names = ["roughness.position_unit", "roughness.height_unit"];
    for (line, f) in &header {
        for (k, col) in [pc, hc].into_iter().enumerate() {
            let Some(u) = f.get(col).and_then(|x| header_unit(x)) else { continue };
            match &units[k] {
                Some(given) if *given != u => {
                    return Err(format!(
                        "{}: the header gives column {} in {u}, but {} = \"{given}\"; correct the one that is wrong",
                        at(*line),
                        col + 1,
                        names[k]
                    ));
                }
                Some(_) => {}
                None if allowed[k].iter().any(|(n, _)| *n == u) => units[k] = Some(u),
                None => {
                    return Err(format!(
                        "{}: the header gives column {} in {u}, which {} does not allow (one of {})",
                        at(*line),
                        col + 1,
                        names[k],
                        allowed[k].iter().map(|(n, _)| format!("\"{n}\"")).collect::<Vec<_>>().join(", ")
                    ));
                }
            }
        }
    }
    let [pu, hu] = units;
    let pu = pu.unwrap_or(defaults[0].into());
    let hu = hu.unwrap_or(defaults[1].into());
    let (pf, hf) = (factor(&POSITION_UNITS, &pu), factor(&HEIGHT_UNITS, &hu));
    if raw.len() < 2 {
        return Err(format!(
            "{}: holds {} sample(s); a record needs at least two lines of position and height",
            file.display(),
            raw.len()
        ));
    }
    for w in raw.windows(2) {
        let ((p0, _, _, l0), (p1, _, _, l1)) = (w[0], w[1]);
        if p1 <= p0 {
            return Err(format!(
                "{}: position {p1} {pu} is not greater than the previous sample's {p0} {pu} (line {l0}); \
                 the positions must increase",
                at(l1)
            ));
        }
    }
    // The median step: a gap or a stray step does not bias it.
    let mut steps: Vec<f64> = raw.windows(2).map(|w| w[1].0 - w[0].0).collect();
    steps.sort_by(f64::total_cmp);
    let median = steps[steps.len() / 2];
    for w in raw.windows(2) {
        let ((p0, _, d0, l0), (p1, _, d1, l1)) = (w[0], w[1]);
        let step = p1 - p0;
        // Each printed position is within half a unit of its last digit.
        let tolerance = SPACING_TOLERANCE * median + 0.5 * (d0 + d1);
        if step > 1.5 * median {
            return Err(format!(
                "{}: a gap of {step:.6} {pu} after line {l0} (position {p0} {pu}), {:.0} missing sample(s) at the \
                 record's spacing {median} {pu}; a record must be evenly sampled without gaps (split it, or fill the gap)",
                at(l1),
                step / median - 1.0
            ));
        }
        if (step - median).abs() > tolerance {
            return Err(format!(
                "{}: the step {step:.6} {pu} from line {l0} differs from the record's spacing {median} {pu} by more than \
                 {:.0} %; a record must be evenly sampled",
                at(l1),
                100.0 * SPACING_TOLERANCE
            ));
        }
    }
    Ok(RecordSamples {
        file: file.to_path_buf(),
        positions: raw.iter().map(|r| r.0 * pf).collect(),
        heights: raw.iter().map(|r| r.1 * hf).collect(),
        lines: raw.iter().map(|r| r.3).collect(),
        position_unit: pu,
        height_unit: hu,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> ReadOptions {
        ReadOptions { position_unit: None, height_unit: None, position_column: 1, height_column: 2 }
    }

    fn parse(text: &str) -> Result<RecordSamples, String> {
        parse_record(text.as_bytes(), Path::new("r.txt"), &opts())
    }

    #[test]
    fn reads_the_common_layouts() {
        let csv = "Distance (m),Displacement (um)\n0.000,1.5\n0.001,-2.0\n0.002,0.25\n";
        let semicolon = "# exported\nDistance [mm];Height [um];Left\n0,0;1,5;9\n1,0;-2,0;9\n2,0;0,25;9\n";
        let blanks = "x y\n\n0 1.5\n0.001 -2\n0.002   0.25\n";
        for text in [csv, semicolon, blanks] {
            let r = parse(text).unwrap();
            assert_eq!(r.heights, vec![1.5e-6, -2e-6, 0.25e-6], "{text}");
            assert!((r.spacing() - 1e-3).abs() < 1e-15, "{text}");
        }
        assert_eq!(parse(semicolon).unwrap().position_unit, "mm");
        assert_eq!(parse(semicolon).unwrap().lines, vec![3, 4, 5]);
    }

    #[test]
    fn every_bad_record_is_refused_with_its_line() {
        let cases = [
            ("0 1\n0.001 2\n0.002 x\n", "r.txt:3"),
            ("0 1\n0.001 2\n0.001 3\n", "r.txt:3"),
            ("0 1\n0.002 2\n0.001 3\n", "r.txt:3"),
            ("0 1\n0.001 2\n0.002 3\n0.005 4\n0.006 5\n", "r.txt:4"),
            ("0.0000 1\n0.0010 2\n0.00215 3\n0.0030 4\n", "r.txt:3"),
            ("0 1\n0.001 2\n0.002\n", "r.txt:3"),
            ("0 1\n0.001 nan\n", "r.txt:2"),
            ("pos (mm) h\n0 1\n", "r.txt"),
        ];
        for (text, at) in cases {
            let e = parse(text).unwrap_err();
            assert!(e.starts_with(at), "{text:?}: {e}");
        }
        let e = parse_record(
            b"pos (mm),h\n0,1\n1,2\n",
            Path::new("r.txt"),
            &ReadOptions { position_unit: Some("m".into()), ..opts() },
        )
        .unwrap_err();
        assert!(e.starts_with("r.txt:1") && e.contains("roughness.position_unit"), "{e}");
    }

    #[test]
    fn rounded_positions_are_even() {
        // 0.5 mm steps printed to 0.001 m: 0, 0.001, 0.001, ... would not
        // increase; printed to 0.0001 m they are exact.
        let text: String = (0..20).map(|i| format!("{:.4} 0\n", i as f64 * 5e-4)).collect();
        assert!(parse(&text).is_ok());
        // 1/3 mm steps printed to 1 um.
        let text: String = (0..30).map(|i| format!("{:.6} 0\n", i as f64 / 3000.0)).collect();
        assert!(parse(&text).is_ok());
    }
}
