//! The limit the band levels are held against: ISO 3095's rail roughness
//! limit (the reference track of the TSI Noise: the acoustic question), a
//! grinding limit in EN 13231-3's corrugation bands (the grinding
//! question), or a user's curve (a CSV of band and level).
//!
//! The grinding limit: Grassie, Saxon and Smith, "Measurement of
//! longitudinal rail irregularities and criteria for acceptable grinding",
//! J. Sound Vib. 227(5) (1999) 949-964, proposed rms limits per wavelength
//! band for the acceptance of a ground rail: 3 um at 10-30 mm, 7 um at
//! 30-100 and 100-300 mm, 45 um at 300-1000 mm (100 um at 1-3 m, outside
//! EN 13231-3's bands), each not to be exceeded over more than 5 % of the
//! ground length. EN 13231-3 took over the bands and the 5 % rule; its own
//! table of limits (by class of work) could not be checked against a
//! public copy, so it is not shipped: a network gives its class's values
//! as a file or table. A rail past the acceptance limit of a fresh grind is
//! a rail a grind would bring back inside it: the limit answers "when is a
//! grind due", earlier than a network's intervention limit.
//!
//! ISO 3095's limit, dB re 1 um, by nominal one-third-octave band centre
//! wavelength: ISO 3095:2013, Figure 2, the value printed beside each point
//! of the limit spectrum, 40 cm down to 0.315 cm; the same numbers are
//! listed as the "TSI limit" in EN 15610:2009, Annex B.9.2, and are the
//! reference track's rail roughness limit of the TSI Noise (Commission
//! Regulation (EU) No 1304/2014, which refers to EN ISO 3095:2013). The
//! values were checked against a public transcription of both printings
//! (jmrplens/phonometry, its ISO 3095 test data: Figure 2 and the EN 15610
//! listing agree to the digit).

use super::{Band, BandSet};
use std::path::Path;

/// ISO 3095:2013 Figure 2: (nominal centre wavelength in cm, limit level in
/// dB re 1 um).
pub const ISO3095_LIMIT: [(f64, f64); 22] = [
    (40.0, 17.1),
    (31.5, 15.0),
    (25.0, 13.0),
    (20.0, 11.0),
    (16.0, 9.0),
    (12.5, 7.0),
    (10.0, 4.9),
    (8.0, 2.9),
    (6.3, 0.9),
    (5.0, -1.1),
    (4.0, -3.2),
    (3.15, -5.0),
    (2.5, -5.6),
    (2.0, -6.2),
    (1.6, -6.8),
    (1.25, -7.4),
    (1.0, -8.0),
    (0.8, -8.6),
    (0.63, -9.2),
    (0.5, -9.8),
    (0.4, -10.4),
    (0.315, -11.0),
];

/// Grassie, Saxon and Smith (1999): (a wavelength inside the EN 13231-3
/// band (m), rms limit (m)).
pub const GRINDING_LIMIT: [(f64, f64); 4] = [(0.02, 3e-6), (0.055, 7e-6), (0.17, 7e-6), (0.55, 45e-6)];

/// A limit curve: a level per band.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitCurve {
    /// What the terminal and the run file call it ("ISO 3095").
    pub name: String,
    /// (a wavelength inside the band (m), limit level (dB re 1 um)).
    pub points: Vec<(f64, f64)>,
}

impl LimitCurve {
    /// ISO 3095's rail roughness limit.
    pub fn iso3095() -> Self {
        LimitCurve { name: "ISO 3095".into(), points: ISO3095_LIMIT.iter().map(|(cm, l)| (cm * 1e-2, *l)).collect() }
    }

    /// The grinding limit in EN 13231-3's bands (see the module doc).
    pub fn grinding() -> Self {
        LimitCurve {
            name: "grinding acceptance (Grassie et al. 1999)".into(),
            points: GRINDING_LIMIT.iter().map(|(w, rms)| (*w, 20.0 * (rms / super::R0).log10())).collect(),
        }
    }

    /// No limit: every band's limit is infinite.
    pub fn none() -> Self {
        LimitCurve { name: "no".into(), points: Vec::new() }
    }

    /// The limit of each of `bands` (dB re 1 um): the level of the curve's
    /// point inside the band; +inf where the curve has none (no limit: the
    /// band never reaches it).
    pub fn on(&self, bands: &[Band]) -> Vec<f64> {
        bands
            .iter()
            .map(|b| self.points.iter().find(|(w, _)| b.contains(*w)).map_or(f64::INFINITY, |(_, l)| *l))
            .collect()
    }
}

/// The band of `set` holding the wavelength `lambda` (m), if any.
pub fn band_of(set: BandSet, lambda: f64) -> Option<Band> {
    match set {
        BandSet::ThirdOctave => {
            let k = (-10.0 * lambda.log10()).round();
            (k.abs() < 100.0).then(|| Band::third_octave(k as i32)).filter(|b| b.contains(lambda))
        }
        BandSet::En13231 => super::all_bands(set).into_iter().find(|b| b.contains(lambda)),
    }
}

/// Why a limit curve could not be read.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("{file}, line {line}: {message}")]
pub struct CurveError {
    /// The file.
    pub file: String,
    /// 1-based line (0: the file as a whole).
    pub line: u64,
    /// What is wrong and what is allowed.
    pub message: String,
}

/// Reads a limit curve from CSV `text` (from `file`, for messages) for the
/// bands of `set`: one band per record, `wavelength, level` (level in dB re
/// 1 um); the wavelength in m, or in mm or cm where the header's first
/// column says so (`wavelength_mm`, `wavelength (cm)`). Comma, semicolon or
/// tab separated; lines starting with `#` are comments; one header line
/// allowed. Each wavelength must fall in a band of `set` (for
/// one-third-octave bands the nominal centre, e.g. 0.0315), each band once.
pub fn read_curve(text: &str, file: &str, set: BandSet) -> Result<Vec<(f64, f64)>, CurveError> {
    let fail = |line: u64, message: String| CurveError { file: file.into(), line, message };
    let delimiter = [b',', b';', b'\t'].into_iter().find(|d| text.as_bytes().contains(d)).unwrap_or(b',');
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .delimiter(delimiter)
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut scale = 1.0;
    let mut points: Vec<(f64, f64, u64)> = Vec::new();
    let mut first = true;
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            fail(line, format!("not readable as CSV: {e}"))
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let numbers: Vec<Option<f64>> = record.iter().map(|f| f.parse::<f64>().ok()).collect();
        if first && numbers.first().is_some_and(Option::is_none) {
            // The header: the first column's unit.
            let name = record.get(0).unwrap_or("").to_ascii_lowercase();
            scale = if name.contains("mm") {
                1e-3
            } else if name.contains("cm") {
                1e-2
            } else {
                1.0
            };
            first = false;
            continue;
        }
        first = false;
        let (Some(Some(w)), Some(Some(level)), 2) = (numbers.first(), numbers.get(1), numbers.len()) else {
            return Err(fail(
                line,
                format!(
                    "expected two numbers, wavelength and level (dB re 1 um), found `{}`",
                    record.iter().collect::<Vec<_>>().join(", ")
                ),
            ));
        };
        let lambda = w * scale;
        if !(lambda > 0.0 && lambda.is_finite()) {
            return Err(fail(line, format!("wavelength {w} must be > 0")));
        }
        if !(level.is_finite() && (-100.0..=100.0).contains(level)) {
            return Err(fail(line, format!("level {level} dB must be in [-100, 100]")));
        }
        let Some(band) = band_of(set, lambda) else {
            return Err(fail(line, format!("wavelength {lambda} m is in none of the bands ({})", set_name(set))));
        };
        if let Some((_, _, earlier)) = points.iter().find(|(w, _, _)| band.contains(*w)) {
            return Err(fail(line, format!("names the {} band again (line {earlier})", band.label())));
        }
        points.push((lambda, *level, line));
    }
    if points.is_empty() {
        return Err(fail(0, "holds no band: expected lines `wavelength, level`".into()));
    }
    Ok(points.into_iter().map(|(w, l, _)| (w, l)).collect())
}

/// Reads the limit curve CSV at `path` (see [`read_curve`]).
pub fn read_curve_file(path: &Path, set: BandSet) -> Result<Vec<(f64, f64)>, CurveError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| CurveError {
        file: file.clone(),
        line: 0,
        message: format!("cannot read: {e}"),
    })?;
    read_curve(&text, &file, set)
}

/// The band set's name in the config's words.
pub fn set_name(set: BandSet) -> &'static str {
    match set {
        BandSet::ThirdOctave => "one-third octaves",
        BandSet::En13231 => "EN 13231-3's 10-30, 30-100, 100-300, 300-1000 mm",
    }
}

/// A limit curve's name as words: "ISO 3095 limit", and a name that
/// already ends in "limit" as it is ("network limit", not "network limit
/// limit").
pub fn limit_words(name: &str) -> String {
    if name.trim_end().to_lowercase().ends_with("limit") {
        name.trim_end().to_string()
    } else {
        format!("{name} limit")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grinding_limit_is_the_papers_rms_in_each_band() {
        let limit = LimitCurve::grinding().on(&crate::levels::all_bands(BandSet::En13231));
        // Bands longest first: 300-1000, 100-300, 30-100, 10-30 mm; 45, 7,
        // 7, 3 um rms.
        let want = [45.0f64, 7.0, 7.0, 3.0].map(|um| 20.0 * um.log10());
        for (l, w) in limit.iter().zip(want) {
            assert!((l - w).abs() < 1e-12, "{limit:?}");
        }
        assert!((want[3] - 9.542).abs() < 1e-3);
    }

    #[test]
    fn a_limit_name_is_said_once() {
        assert_eq!(limit_words("ISO 3095"), "ISO 3095 limit");
        assert_eq!(limit_words("network limit"), "network limit");
        assert_eq!(limit_words("Grinding Limit "), "Grinding Limit");
        assert_eq!(limit_words("limits.csv"), "limits.csv limit");
    }
    use crate::levels::resolved_bands;

    #[test]
    fn iso3095_limit_is_the_standards_table() {
        // ISO 3095:2013 Figure 2 / EN 15610:2009 Annex B.9.2, band by band.
        let curve = LimitCurve::iso3095();
        let bands: Vec<Band> = (4..=25).map(Band::third_octave).collect();
        let limit = curve.on(&bands);
        let table = [
            17.1, 15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2, -5.0, -5.6, -6.2, -6.8, -7.4, -8.0, -8.6,
            -9.2, -9.8, -10.4, -11.0,
        ];
        assert_eq!(limit, table);
        // 400 mm is band k = 4, 3.15 mm k = 25; beyond the table no limit.
        assert_eq!(curve.on(&[Band::third_octave(3), Band::third_octave(26)]), vec![f64::INFINITY; 2]);
        // On a 120 mm stretch the 25 mm (2.5 cm) band is the longest: -5.6 dB.
        assert_eq!(curve.on(&resolved_bands(BandSet::ThirdOctave, 600, 2e-4))[0], -5.6);
    }

    #[test]
    fn a_csv_curve_is_read_band_by_band() {
        let text = "# my limit\nwavelength_mm; level_dB\n31.5; 10\n25;8.5\n\n12.5 ; 2\n";
        let points = read_curve(text, "l.csv", BandSet::ThirdOctave).unwrap();
        assert_eq!(points.len(), 3);
        assert!((points[0].0 - 0.0315).abs() < 1e-15 && points[2] == (0.0125, 2.0));
        let curve = LimitCurve { name: "l.csv".into(), points };
        let bands = [Band::third_octave(15), Band::third_octave(17)];
        assert_eq!(curve.on(&bands), vec![10.0, f64::INFINITY]);
        // Without a header, metres.
        assert_eq!(read_curve("0.0315,10\n", "l.csv", BandSet::ThirdOctave).unwrap(), vec![(0.0315, 10.0)]);
        // EN 13231-3's bands: any wavelength inside the band.
        let en = read_curve("0.02,5\n0.05,8\n", "e.csv", BandSet::En13231).unwrap();
        assert_eq!(en, vec![(0.02, 5.0), (0.05, 8.0)]);
    }

    #[test]
    fn bad_csv_lines_are_named() {
        let err = |text: &str| read_curve(text, "l.csv", BandSet::ThirdOctave).unwrap_err();
        let e = err("wavelength,level\n0.0315,10\n0.025,abc\n");
        assert_eq!((e.line, e.file.as_str()), (3, "l.csv"));
        assert!(e.message.contains("two numbers"), "{}", e.message);
        assert_eq!(err("0.0315,10\n0.031,11\n").line, 2);
        assert!(err("0.0315,10\n0.031,11\n").message.contains("31.5 mm band again (line 1)"));
        assert!(err("-0.01,3\n").message.contains("> 0"));
        assert!(err("0.01,300\n").message.contains("[-100, 100]"));
        assert!(err("# nothing\n").message.contains("holds no band"));
        assert_eq!(err("0.01,1,2\n").line, 1);
        let e = read_curve("2.0,3\n", "e.csv", BandSet::En13231).unwrap_err();
        assert!(e.message.contains("none of the bands"), "{}", e.message);
    }
}
