//! The run file's variables in the field's units ([`crate::levels`]):
//! band levels against the limit, when each band reaches it, and the
//! traffic in million gross tonnes and days.
//!
//! Group `passes`: coordinate `band` (the band's nominal centre
//! wavelength, m) with `band_lower` and `band_upper` (its wavelength
//! edges); `initial_level(band)`, `roughness_level(pass, band)`,
//! `level_rate(pass, band)`, `limit_level(band)`,
//! `passages_to_limit(pass, band)`; where `[traffic]` gives axle loads,
//! `traffic_mgt(pass)` and `mgt_to_limit(pass, band)`; where it gives
//! axles per day, `traffic_days(pass)` and `days_to_limit(pass, band)`.
//! Group `rail`: `traffic_mgt(pass)`, `traffic_days(pass)` of the stored
//! passages. Everything here is computed from the rows and the config, so
//! a resumed run writes the same numbers.

use super::netcdf::{NcError, NcGroup};
use super::run_record::RunRecord;
use crate::growth::state::PassRow;
use crate::levels::forecast::{Units, cumulative_mgt, driven, passages_to_limit};
use ndarray::{Array1, Array2, ArrayView1};

/// The operator's traffic after each row: (MGT, days), where given.
fn traffic_in_units(r: &RunRecord) -> (Option<Vec<f64>>, Option<Vec<f64>>) {
    let rows = &r.state.rows;
    let Some(op) = r.operation else { return (None, None) };
    let mgt = op.axle_loads.as_ref().map(|loads| {
        let steps: Vec<(usize, f64)> = rows.iter().map(|row| (row.traffic_class, row.traffic_scale)).collect();
        cumulative_mgt(&steps, loads)
    });
    let days = op.axles_per_day.map(|a| rows.iter().map(|row| row.traffic / a).collect());
    (mgt, days)
}

/// The operator's units of the record's traffic.
pub fn units(r: &RunRecord) -> Units {
    let shares: Vec<f64> = r.classes.iter().map(|c| c.share).collect();
    r.operation.map_or_else(Units::default, |op| op.units(&shares))
}

/// Writes the field-unit variables of group `passes`.
pub fn write_passes(g: &NcGroup, r: &RunRecord) -> Result<(), NcError> {
    let rows = &r.state.rows;
    let (mgt, days) = traffic_in_units(r);
    let pass = ["pass"];
    if let Some(mgt) = &mgt {
        g.var_f64(
            "traffic_mgt",
            &pass,
            Array1::from(mgt.clone()).view().into_dyn(),
            "Mt",
            "million gross tonnes (MGT) represented: real wheel passages times their class's axle load",
        )?;
    }
    if let Some(days) = &days {
        g.var_f64(
            "traffic_days",
            &pass,
            Array1::from(days.clone()).view().into_dyn(),
            "d",
            "days of traffic represented: real wheel passages over traffic.axles_per_day",
        )?;
    }
    let bands = r.bands;
    let (wavelength, lower, upper): (Vec<f64>, Vec<f64>, Vec<f64>) = (
        bands.iter().map(|b| b.wavelength).collect(),
        bands.iter().map(|b| b.lower).collect(),
        bands.iter().map(|b| b.upper).collect(),
    );
    g.coord_f64(
        "band",
        &wavelength,
        "m",
        "nominal centre wavelength of the roughness band (EN 15610 one-third octave, or EN 13231-3)",
        false,
    )?;
    let band = ["band"];
    g.var_f64("band_lower", &band, Array1::from(lower).view().into_dyn(), "m", "shortest wavelength of the band")?;
    g.var_f64("band_upper", &band, Array1::from(upper).view().into_dyn(), "m", "longest wavelength of the band")?;
    g.var_f64(
        "limit_level",
        &band,
        ArrayView1::from(r.limit).into_dyn(),
        "dB",
        &format!("{} limit of the band's roughness level, dB re 1 um (inf: no limit for the band)", r.limit_name),
    )?;
    g.var_attr_str("limit_level", "limit_name", r.limit_name)?;
    g.var_f64(
        "initial_level",
        &band,
        ArrayView1::from(r.state.initial_level.as_slice()).into_dyn(),
        "dB",
        "rail roughness level of the band before the first passage, dB re 1 um",
    )?;
    let table = |f: &dyn Fn(usize, &PassRow, usize) -> f64| {
        Array2::from_shape_fn((rows.len(), bands.len()), |(p, k)| f(p, &rows[p], k))
    };
    let dims = ["pass", "band"];
    let level = table(&|_, row, k| row.roughness_level[k]);
    g.var_f64(
        "roughness_level",
        &dims,
        level.view().into_dyn(),
        "dB",
        "rail roughness level L = 10 lg(r_rms^2 / r0^2), r0 = 1 um, of the band after the passage (EN 15610): \
         the grid lines of the running band |y| <= b of the mean patch, mean-square averaged",
    )?;
    let rate = table(&|_, row, k| row.level_rate[k]);
    g.var_f64(
        "level_rate",
        &dims,
        rate.view().into_dyn(),
        "dB/1e5 passages",
        "roughness-driven growth rate of the band's roughness level over the passage (the change by the wear less \
         the smooth rail's, W - W0), dB per 1e5 real wheel passages",
    )?;
    let forced = table(&|_, row, k| row.forced_band_wear.get(k).copied().unwrap_or(0.0));
    g.var_f64(
        "forced_band_wear",
        &dims,
        forced.view().into_dyn(),
        "m",
        "rms in the band of the wear one wheel passage of the class leaves on the smooth rail (the forced pattern, \
         per wheel passage; the running band's lines as roughness_level)",
    )?;
    let to_limit = table(&|p, row, k| {
        let before = if p == 0 { r.state.initial_level[k] } else { rows[p - 1].roughness_level[k] };
        let (rate, f) = driven(
            r.state.initial_level[k],
            before,
            row.roughness_level[k],
            row.level_rate[k],
            row.traffic_scale,
            forced_of(row, k),
        );
        passages_to_limit(row.roughness_level[k], rate, f, r.limit[k])
    });
    g.var_f64(
        "passages_to_limit",
        &dims,
        to_limit.view().into_dyn(),
        "1",
        "real wheel passages from the passage until the band reaches its limit, growing at the passage's \
         roughness-driven rate and by the forced pattern (0: at or above it; inf: it never reaches it)",
    )?;
    let u = units(r);
    if mgt.is_some()
        && let Some(t) = u.tonnes_per_passage
    {
        let v = to_limit.mapv(|n| n * t * 1e-6);
        g.var_f64(
            "mgt_to_limit",
            &dims,
            v.view().into_dyn(),
            "Mt",
            "million gross tonnes from the passage until the band reaches its limit (mean axle load of the mix)",
        )?;
    }
    if let Some(a) = u.axles_per_day {
        let v = to_limit.mapv(|n| n / a);
        g.var_f64(
            "days_to_limit",
            &dims,
            v.view().into_dyn(),
            "d",
            "days from the passage until the band reaches its limit",
        )?;
    }
    Ok(())
}

/// Writes the field-unit traffic of the stored passages in group `rail`.
pub fn write_rail(g: &NcGroup, r: &RunRecord) -> Result<(), NcError> {
    let (mgt, days) = traffic_in_units(r);
    let at = |v: &Vec<f64>| -> Array1<f64> { r.state.rail.iter().map(|s| v[s.index as usize]).collect() };
    if let Some(mgt) = &mgt {
        g.var_f64("traffic_mgt", &["pass"], at(mgt).view().into_dyn(), "Mt", "million gross tonnes represented")?;
    }
    if let Some(days) = &days {
        g.var_f64("traffic_days", &["pass"], at(days).view().into_dyn(), "d", "days of traffic represented")?;
    }
    Ok(())
}

/// Row `row`'s forced pattern in band `k` (m rms per wheel passage; 0 where
/// none was recorded).
fn forced_of(row: &PassRow, k: usize) -> f64 {
    row.forced_band_wear.get(k).copied().unwrap_or(0.0)
}
