//! The forecast `corrugation spectrum` prints and writes beside the
//! spectrum: when each band of the study's initial roughness reaches its
//! limit, from the linear growth spectrum
//! ([`corrugation::spectrum::outlook`]): against the config's
//! `[levels]` limit, and, where those are one-third octaves, in EN
//! 13231-3's bands against the grinding limit; each rail of the scene.

use corrugation::config::Resolved;
use corrugation::levels::forecast::Units;
use corrugation::levels::limit::{LimitCurve, limit_words, set_name};
use corrugation::levels::{BandSet, LEVEL_FLOOR, all_bands};
use corrugation::output::forecast_group::ForecastGroup;
use corrugation::params::Roughness;
use corrugation::spectrum::Spectrum;
use corrugation::spectrum::forecast::BandGrowth;
use corrugation::spectrum::outlook::{Inputs, Outlook, outlook};

/// A forecast against one limit.
pub struct Forecast {
    /// Its group in the spectrum file.
    group: String,
    /// The rail, as the terminal names it.
    rail: String,
    /// The limit.
    limit: LimitCurve,
    /// The bands' set.
    set: BandSet,
    /// The forecast.
    outlook: Outlook,
    /// The operator's units.
    units: Units,
}

impl Forecast {
    /// Whether no band was forecast.
    pub fn is_empty(&self) -> bool {
        self.outlook.rows.is_empty()
    }

    /// The forecast as the spectrum file's group.
    pub fn group(&self) -> ForecastGroup<'_> {
        ForecastGroup {
            name: &self.group,
            outlook: &self.outlook,
            limit_name: &self.limit.name,
            bands: set_name(self.set),
            units: self.units,
        }
    }
}

/// The traffic the levels are written at: 1e3 to 1e9 wheel passages, four
/// a decade.
fn traffic() -> Vec<f64> {
    (12..=36).map(|k| 10f64.powf(f64::from(k) / 4.0)).collect()
}

/// The forecasts of `resolved`'s initial roughness on `s` (see the module
/// doc); none for a smooth rail.
pub fn forecasts(resolved: &Resolved, s: &Spectrum) -> Result<Vec<Forecast>, String> {
    let scene = &resolved.scene;
    let Some(g) = &scene.growth else { return Ok(Vec::new()) };
    if matches!(g.roughness, Roughness::None) {
        return Ok(Vec::new());
    }
    let params = scene.spectrum.unwrap_or_default();
    let growth = BandGrowth::new(s).map_err(|e| format!("the forecast: {e}"))?;
    let (density, record_length) = corrugation::growth::roughness::density(&g.roughness);
    let shares: Vec<f64> = g.classes.iter().map(|c| c.share).collect();
    let units = g.operation.units(&shares);
    let traffic = traffic();
    let mut asked = vec![("forecast", scene.levels.bands, scene.levels.limit.clone())];
    if scene.levels.bands == BandSet::ThirdOctave {
        asked.push(("forecast_grinding", BandSet::En13231, LimitCurve::grinding()));
    }
    // Each rail (a second rail's roughness is the first's kind, drawn with
    // its own seed: the same density).
    let rails: Vec<(String, &str)> = match &scene.second_rail {
        Some(two) => {
            vec![(rail_words(&two.names[0]), ""), (rail_words(&two.names[1]), "second_rail_")]
        }
        None => vec![("the rail".into(), "")],
    };
    let mut out = Vec::new();
    for (rail, (name, prefix)) in rails.iter().enumerate() {
        for (group, set, limit) in &asked {
            let bands: Vec<_> = all_bands(*set).into_iter().collect();
            let limits = limit.on(&bands);
            let pairs: Vec<_> = bands.into_iter().zip(limits).collect();
            let outlook = outlook(&Inputs {
                growth: &growth,
                rail,
                density: &density,
                record_length,
                measured: (params.wavelength_min, params.wavelength_max),
                bands: &pairs,
                traffic: &traffic,
            });
            let (group, rail, limit, set) = (format!("{prefix}{group}"), name.clone(), limit.clone(), *set);
            out.push(Forecast { group, rail, limit, set, outlook, units });
        }
    }
    Ok(out)
}

/// A rail's name as words: "the left rail", and a name that already ends
/// in "rail" as it is ("the low rail", not "the low rail rail").
fn rail_words(name: &str) -> String {
    if name.trim_end().to_lowercase().ends_with("rail") {
        format!("the {}", name.trim_end())
    } else {
        format!("the {name} rail")
    }
}

/// Prints each forecast as a table.
pub fn print(forecasts: &[Forecast]) {
    for f in forecasts {
        let words = limit_words(&f.limit.name);
        let question = match (f.set, f.limit.name.as_str()) {
            (_, "ISO 3095") => "the acoustic question: far stricter than a grinding trigger",
            (BandSet::En13231, _) if f.limit == LimitCurve::grinding() => {
                "when to grind: the rms a fresh grind is accepted at, per band"
            }
            _ => "the config's [levels]",
        };
        say!("forecast against the {words} ({question}), {}, linear regime:", f.rail);
        let shown: Vec<_> = f.outlook.rows.iter().filter(|r| r.level > LEVEL_FLOOR).collect();
        if f.is_empty() {
            say!("  no band forecast:");
        } else if shown.is_empty() {
            say!("  no band forecast holds roughness");
        } else {
            say!("  band       level  rate     limit   reaches the limit");
            say!("             dB     dB/1e5   dB");
        }
        for r in shown {
            let when = if r.passages == 0.0 {
                format!("now ({:+.1} dB over it)", r.level - r.limit)
            } else if r.extrapolated(&f.outlook) {
                format!(
                    "after {}: {:.1} times the linear horizon, an extrapolation",
                    f.units.describe(r.passages),
                    r.passages / f.outlook.horizon
                )
            } else if r.passages.is_finite() {
                format!("after {} (+{:.1} dB from now)", f.units.describe(r.passages), r.limit - r.level)
            } else if r.limit.is_finite() {
                "never (the band decays or settles below it)".into()
            } else {
                "no limit in this band".into()
            };
            let rate = if r.rate.is_finite() { format!("{:+7.3}", r.rate) } else { "      -".into() };
            say!("  {:<10} {:6.1} {rate}  {:6.1}  {when}", r.band.label(), r.level, r.limit);
        }
        let horizon = f.outlook.horizon;
        if horizon.is_finite() && !f.is_empty() {
            say!(
                "  linear horizon: {} (the roughness grown tenfold in rms; beyond it the forecast extrapolates)",
                f.units.describe(horizon)
            );
        }
        for (why, runs) in left_out_runs(f) {
            let spans: Vec<String> = runs
                .iter()
                .map(|r| match r.as_slice() {
                    [one] => one.clone(),
                    [first, .., last] => format!("{first} to {last}"),
                    [] => String::new(),
                })
                .collect();
            let count: usize = runs.iter().map(Vec::len).sum();
            let bands = if count == 1 { "band" } else { "bands" };
            say!("  left out: {count} {bands} ({}): {why}", spans.join(", "));
        }
    }
}

/// The bands a forecast left out, by reason, as runs of neighbouring bands
/// (labels).
fn left_out_runs(f: &Forecast) -> Vec<(String, Vec<Vec<String>>)> {
    let order = all_bands(f.set);
    let index = |b: &corrugation::levels::Band| order.iter().position(|o| o == b).unwrap_or(usize::MAX);
    let mut out: Vec<(String, Vec<Vec<String>>, usize)> = Vec::new();
    for (band, why) in &f.outlook.left_out {
        let i = index(band);
        match out.iter_mut().find(|(w, _, _)| w == why) {
            Some((_, runs, last)) => {
                if i == *last + 1 {
                    runs.last_mut().expect("a run").push(band.label());
                } else {
                    runs.push(vec![band.label()]);
                }
                *last = i;
            }
            None => out.push((why.clone(), vec![vec![band.label()]], i)),
        }
    }
    out.into_iter().map(|(w, r, _)| (w, r)).collect()
}

#[cfg(test)]
mod tests {
    use super::rail_words;

    #[test]
    fn a_rail_is_named_once() {
        assert_eq!(rail_words("left"), "the left rail");
        assert_eq!(rail_words("low rail"), "the low rail");
        assert_eq!(rail_words("High Rail "), "the High Rail");
    }
}
