//! A forecast's group in the spectrum file (book:
//! docs/src/reference/spectrum-file.md): per band its level now, rate,
//! limit and the traffic until it reaches it, and its level along a
//! traffic axis ([`crate::spectrum::outlook`]).

use super::netcdf::{NcError, NcGroup};
use crate::levels::forecast::Units;
use crate::spectrum::outlook::Outlook;
use ndarray::{Array1, Array2};

/// One forecast to write.
pub struct ForecastGroup<'a> {
    /// The group's name ("forecast", "forecast_grinding").
    pub name: &'a str,
    /// The forecast.
    pub outlook: &'a Outlook,
    /// The limit's name.
    pub limit_name: &'a str,
    /// The bands' set, in words.
    pub bands: &'a str,
    /// The operator's units.
    pub units: Units,
}

/// Writes `f` as a group of `root`.
pub fn write_forecast(root: &NcGroup, f: &ForecastGroup) -> Result<(), NcError> {
    let g = root.group(f.name)?;
    g.attr_str("limit_name", f.limit_name)?;
    g.attr_str("bands", f.bands)?;
    g.attr_str(
        "model",
        "linear growth spectrum: the roughness's band levels now, each band's growth by the spectrum's update \
         with the forced pattern (random phases)",
    )?;
    g.attr_f64("horizon", f.outlook.horizon)?;
    if let Some(t) = f.units.tonnes_per_passage {
        g.attr_f64("tonnes_per_passage", t)?;
    }
    if let Some(a) = f.units.axles_per_day {
        g.attr_f64("axles_per_day", a)?;
    }
    let rows = &f.outlook.rows;
    let col = |v: &dyn Fn(usize) -> f64| (0..rows.len()).map(v).collect::<Array1<f64>>();
    let centres: Vec<f64> = rows.iter().map(|r| r.band.wavelength).collect();
    g.coord_f64("band", &centres, "m", "nominal centre wavelength of the band", false)?;
    g.coord_f64("traffic", &f.outlook.traffic, "1", "wheel passages from now", false)?;
    let columns: [(&str, Array1<f64>, &str, &str); 7] = [
        ("band_lower", col(&|k| rows[k].band.lower), "m", "shortest wavelength of the band"),
        ("band_upper", col(&|k| rows[k].band.upper), "m", "longest wavelength of the band"),
        ("lines", col(&|k| rows[k].lines), "1", "harmonics of the supercell in the band (conjugate pairs once)"),
        ("level", col(&|k| rows[k].level), "dB re 1 um", "the band's roughness level now"),
        ("rate", col(&|k| rows[k].rate), "dB/1e5 passages", "the band's roughness growth rate now"),
        ("limit_level", col(&|k| rows[k].limit), "dB re 1 um", "the band's limit (inf: none)"),
        (
            "passages_to_limit",
            col(&|k| rows[k].passages),
            "1",
            "wheel passages until the band reaches its limit (0: now; inf: never within 1e15)",
        ),
    ];
    for (name, values, units, long) in columns {
        g.var_f64(name, &["band"], values.view().into_dyn(), units, long)?;
    }
    let n = f.outlook.traffic.len();
    let levels = Array2::from_shape_fn((rows.len(), n), |(b, t)| rows[b].levels[t]);
    g.var_f64("level_forecast", &["band", "traffic"], levels.view().into_dyn(), "dB re 1 um", "the band's level")?;
    Ok(())
}
