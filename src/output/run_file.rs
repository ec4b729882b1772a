//! The run-file layout (book: docs/src/reference/run-file.md), written atomically (temporary
//! file, fsync, rename) so that a reader never sees a half-written file.
//!
//! * root attributes: `title`, `version`, `contact_model`, `config` (the
//!   resolved TOML), `status` ("checkpoint" or "complete"), `passes_done`,
//!   `passes_planned`, `stop_reason` (why a study with `growth.stop`
//!   ended before its planned passages; empty otherwise);
//! * group `rail`: coordinates `x`, `y`, `pass`; `traffic(pass)`,
//!   `profile(pass, y, x)`, `wear(pass, y, x)`, and `state(y, x)`, the
//!   profile after the last passage done (what a resumed run starts from);
//! * group `passes`: one row per simulated passage, with the band levels
//!   in the field's units ([`super::field_units`]);
//! * group `contact/pass_NNNNN`: the patch history of a stored passage;
//! * group `record` (a measured initial roughness): coordinate `position`
//!   (m), `height(position)` (m), the record as read, before processing;
//!   attributes `file`, `sha256`, `position_unit`, `height_unit` (the
//!   file's). A resumed run rebuilds the initial profile from it.

use super::netcdf::{NcError, NcGroup, write_atomically};
pub use super::run_record::RunRecord;
use crate::contact::Elements;
use crate::growth::record::RecordSamples;
use crate::growth::state::{PassRow, RailSnapshot};
use crate::params::TrafficClass;
use crate::passage::{PatchFields, PatchHistory};
use ndarray::{Array1, Array2, Array3, ArrayView1};
use std::path::Path;

/// Writes `record` to `path` atomically.
pub fn write_run_file(path: &Path, record: &RunRecord) -> Result<(), NcError> {
    write_atomically(path, |root| {
        root.attr_str("title", record.title)?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("contact_model", record.contact_model)?;
        root.attr_str("config", record.config)?;
        let done = record.state.rows.len();
        let complete = done >= record.passes_planned || record.stop_reason.is_some();
        root.attr_str("status", if complete { "complete" } else { "checkpoint" })?;
        root.attr_str("stop_reason", record.stop_reason.unwrap_or(""))?;
        root.attr_i64("passes_done", done as i64)?;
        root.attr_i64("passes_planned", record.passes_planned as i64)?;
        write_rail_groups(root, record)?;
        if !record.classes.is_empty() {
            write_classes(&root.group("traffic")?, record.classes)?;
        }
        if let Some(r) = record.record {
            write_record(&root.group("record")?, r)?;
        }
        // The wheelset's second rail: the same groups in `second_rail`.
        if let (Some(second), Some(names)) = (record.state.second_rail.as_deref(), record.rail_names) {
            root.attr_str("rail_name", &names[0])?;
            let group = root.group("second_rail")?;
            group.attr_str("rail_name", &names[1])?;
            write_rail_groups(&group, &RunRecord { state: second, ..record.clone() })?;
        }
        Ok(())
    })
}

/// One rail's groups `rail`, `passes` and `contact` in `root`.
fn write_rail_groups(root: &NcGroup, record: &RunRecord) -> Result<(), NcError> {
    let rail = root.group("rail")?;
    write_rail(&rail, record)?;
    super::field_units::write_rail(&rail, record)?;
    let passes = root.group("passes")?;
    write_passes(&passes, &record.state.rows, record.wavelengths, record.classes)?;
    write_regime_shares(&passes, &record.state.rows, record.wear_regimes)?;
    super::field_units::write_passes(&passes, record)?;
    let contact = root.group("contact")?;
    for (index, history) in &record.state.histories {
        let group = contact.group(&format!("pass_{index:05}"))?;
        write_history(&group, history, record)?;
        // The other wheels' histories: subgroups wheel_2, wheel_3, ...
        let others = record.state.wheel_histories.iter().filter(|(i, _)| i == index).flat_map(|(_, h)| h);
        for (k, h) in others.enumerate() {
            write_history(&group.group(&format!("wheel_{}", k + 2))?, h, record)?;
        }
    }
    Ok(())
}

fn write_rail(g: &NcGroup, r: &RunRecord) -> Result<(), NcError> {
    let grid = r.grid;
    let rail = &r.state.rail;
    g.coord_f64("x", &grid.xs(), "m", "position along the rail", false)?;
    g.coord_f64("y", &grid.ys(), "m", "lateral position on the rail head", false)?;
    let idx: Vec<i64> = rail.iter().map(|s| s.index).collect();
    g.coord_i64("pass", &idx, "1", "simulated passage index", true)?;
    let traffic: Array1<f64> = rail.iter().map(|s| s.traffic).collect();
    g.var_f64("traffic", &["pass"], traffic.view().into_dyn(), "1", "real wheel passages represented")?;
    let stack = |f: &dyn Fn(&RailSnapshot) -> &Array2<f64>| {
        let mut a = Array3::zeros((rail.len(), grid.ny, grid.nx));
        for (k, s) in rail.iter().enumerate() {
            a.index_axis_mut(ndarray::Axis(0), k).assign(f(s));
        }
        a
    };
    let profile = stack(&|s| &s.profile);
    g.var_f64(
        "profile",
        &["pass", "y", "x"],
        profile.view().into_dyn(),
        "m",
        "rail surface height change after the passage (wear negative)",
    )?;
    let wear = stack(&|s| &s.wear);
    g.var_f64(
        "wear",
        &["pass", "y", "x"],
        wear.view().into_dyn(),
        "m",
        "wear depth of one simulated wheel passage, the mean of the vehicle's wheels (unscaled by traffic)",
    )?;
    g.var_f64(
        "state",
        &["y", "x"],
        r.state.profile.view().into_dyn(),
        "m",
        "rail surface height change after the last passage done (the state a resumed run starts from)",
    )?;
    Ok(())
}

/// Group `record`: the measured record as read.
fn write_record(g: &NcGroup, r: &RecordSamples) -> Result<(), NcError> {
    g.attr_str("file", &r.file.display().to_string())?;
    g.attr_str("sha256", &r.sha256())?;
    g.attr_str("position_unit", &r.position_unit)?;
    g.attr_str("height_unit", &r.height_unit)?;
    g.coord_f64("position", &r.positions, "m", "position along the measured record", false)?;
    g.var_f64(
        "height",
        &["position"],
        ArrayView1::from(&r.heights).into_dyn(),
        "m",
        "measured rail height, as read (before spike removal, curvature processing and detrending)",
    )
}

/// Reads group `record` of the run file at `path`, if it has one.
pub fn read_record(path: &Path) -> Result<Option<RecordSamples>, NcError> {
    use super::netcdf::Attrs;
    let Ok(attrs) = Attrs::open(path, "record") else { return Ok(None) };
    let positions = super::netcdf::read_f64(path, "record", "position")?.iter().copied().collect();
    let heights = super::netcdf::read_f64(path, "record", "height")?.iter().copied().collect();
    Ok(Some(RecordSamples {
        file: attrs.str("file")?.into(),
        positions,
        heights,
        lines: Vec::new(),
        position_unit: attrs.str("position_unit")?,
        height_unit: attrs.str("height_unit")?,
    }))
}

/// Group `traffic`: one row per class on dimension `class`; the names in
/// the attribute `class_names` (space-separated, in class order).
fn write_classes(g: &NcGroup, classes: &[TrafficClass]) -> Result<(), NcError> {
    let idx: Vec<i64> = (0..classes.len() as i64).collect();
    g.coord_i64("class", &idx, "1", "traffic class index", false)?;
    let col = |f: fn(&TrafficClass) -> f64| -> Array1<f64> { classes.iter().map(f).collect() };
    let vars: [(&str, Array1<f64>, &str, &str); 5] = [
        ("speed", col(|c| c.speed), "m/s", "rolling speed of the class"),
        ("normal_force", col(|c| c.normal_force), "N", "mean normal force of the class"),
        ("longitudinal_force", col(|c| c.longitudinal_force), "N", "mean longitudinal force on the wheel"),
        ("unsprung_mass", col(|c| c.unsprung_mass), "kg", "unsprung mass per wheel"),
        ("share", col(|c| c.share), "1", "share of the real wheel passages"),
    ];
    for (name, v, units, long_name) in vars {
        g.var_f64(name, &["class"], v.view().into_dyn(), units, long_name)?;
    }
    g.attr_str("class_names", &class_names(classes))
}

/// The classes' names, space-separated.
fn class_names(classes: &[TrafficClass]) -> String {
    classes.iter().map(|c| c.name.as_str()).collect::<Vec<_>>().join(" ")
}

/// The wear regimes' shares on (`pass`, `wear_regime`), where the rows
/// have them (NaN in a row written before the wear laws).
fn write_regime_shares(g: &NcGroup, rows: &[PassRow], regimes: &[&str]) -> Result<(), NcError> {
    if regimes.is_empty() || rows.iter().all(|r| r.wear_regime_share.is_empty()) {
        return Ok(());
    }
    let index: Vec<i64> = (1..=regimes.len() as i64).collect();
    g.coord_i64("wear_regime", &index, "1", "the wear law's regime (flag_meanings)", false)?;
    g.var_attr_str("wear_regime", "flag_values", &index.iter().map(i64::to_string).collect::<Vec<_>>().join(" "))?;
    g.var_attr_str("wear_regime", "flag_meanings", &regimes.join(" "))?;
    let mut a = ndarray::Array2::from_elem((rows.len(), regimes.len()), f64::NAN);
    for (k, r) in rows.iter().enumerate() {
        a.row_mut(k).iter_mut().zip(&r.wear_regime_share).for_each(|(d, v)| *d = *v);
    }
    g.var_f64(
        "wear_regime_share",
        &["pass", "wear_regime"],
        a.view().into_dyn(),
        "1",
        "share of the leading wheel's wear volume in each regime of the wear law",
    )
}

fn write_passes(g: &NcGroup, rows: &[PassRow], wavelengths: &[f64], classes: &[TrafficClass]) -> Result<(), NcError> {
    let idx: Vec<i64> = rows.iter().map(|r| r.index).collect();
    g.coord_i64("pass", &idx, "1", "simulated passage index", true)?;
    let col = |f: fn(&PassRow) -> f64| -> Array1<f64> { rows.iter().map(f).collect() };
    let vars: [(&str, Array1<f64>, &str, &str); 9] = [
        ("traffic", col(|r| r.traffic), "1", "real wheel passages represented"),
        ("traffic_scale", col(|r| r.traffic_scale), "1", "real passages per simulated passage"),
        ("rms_corrugation", col(|r| r.rms_corrugation), "m", "rms of the centre-line rail profile minus its mean"),
        (
            "removed_volume",
            col(|r| r.removed_volume),
            "m3",
            "volume removed from the rail grid by one simulated passage",
        ),
        ("cpu_seconds", col(|r| r.cpu_seconds), "s", "CPU time of the passage"),
        (
            "update_ratio",
            col(|r| r.update_ratio),
            "1",
            "relative profile change of the update, m max_k |W_k|/|R_k| over the corrugation harmonics",
        ),
        (
            "contact_loss_steps",
            col(|r| r.contact_loss_steps),
            "1",
            "steps of the stretch where the wheel left the rail (N <= 0; the linear track model is not valid there)",
        ),
        (
            "profile_contact",
            col(|r| r.profile_contact),
            "1",
            "normal contact of the passage: 0 Hertz, 1 the nonlinear profile contact, 2 the linear profile contact, \
             3 the nonlinear profile contact with the linear contact's equivalent roughness",
        ),
        (
            "clipped_steps",
            col(|r| r.clipped_steps),
            "1",
            "steps at which the linear profile contact's pressure vanished well inside the patch (beyond its range)",
        ),
    ];
    for (name, v, units, long_name) in vars {
        g.var_f64(name, &["pass"], v.view().into_dyn(), units, long_name)?;
    }
    if !classes.is_empty() {
        let class: Array1<i64> = rows.iter().map(|r| r.traffic_class as i64).collect();
        g.var_i64(
            "traffic_class",
            &["pass"],
            class.view().into_dyn(),
            "1",
            "traffic class of the passage (group traffic)",
        )?;
        let values: Vec<String> = (0..classes.len()).map(|c| c.to_string()).collect();
        g.var_attr_str("traffic_class", "flag_values", &values.join(" "))?;
        g.var_attr_str("traffic_class", "flag_meanings", &class_names(classes))?;
    }
    g.coord_f64("wavelength", wavelengths, "m", "wavelength of the profile harmonic (stretch length / n)", false)?;
    let table = |f: fn(&PassRow) -> &Vec<f64>| {
        let mut a = ndarray::Array2::zeros((rows.len(), wavelengths.len()));
        for (k, r) in rows.iter().enumerate() {
            a.row_mut(k).iter_mut().zip(f(r)).for_each(|(d, v)| *d = *v);
        }
        a
    };
    let dims = ["pass", "wavelength"];
    let spectrum = table(|r| &r.spectrum);
    g.var_f64("spectrum", &dims, spectrum.view().into_dyn(), "m", "corrugation amplitude spectrum (centre line)")?;
    let filtered = table(|r| &r.filtered_spectrum);
    g.var_f64(
        "filtered_spectrum",
        &dims,
        filtered.view().into_dyn(),
        "m",
        "amplitude spectrum of the contact-filtered profile (Hertz line-load weights across the mean patch width)",
    )?;
    let rate = table(|r| &r.growth_rate);
    g.var_f64(
        "growth_rate",
        &dims,
        rate.view().into_dyn(),
        "dB/1e5 passages",
        "roughness-driven growth rate of each harmonic of the contact-filtered profile over the passage (the \
         change by the wear less the smooth rail's, W - W0)",
    )?;
    // Rows read from files written before the forced wear was recorded
    // have none: zeros (the smooth rail's wear was not computed then).
    let forced = table(|r| &r.forced_wear);
    g.var_f64(
        "forced_wear",
        &dims,
        forced.view().into_dyn(),
        "m",
        "amplitude of the contact-filtered wear one wheel passage of the class leaves on the smooth rail (W0: the \
         forced pattern, deepening linearly with traffic; per wheel passage)",
    )?;
    Ok(())
}

/// Per-step variables of a patch history: (name, units, long_name), in the
/// order of [`step_columns`].
pub(super) const STEP_VARS: [(&str, &str, &str); 15] = [
    ("time", "s", "time since the start of the passage"),
    ("x_c", "m", "patch centre position along the rail"),
    ("normal_force", "N", "normal force"),
    ("longitudinal_force", "N", "longitudinal force on the wheel"),
    ("creepage_x", "1", "longitudinal creepage (negative for a positive force on the wheel)"),
    ("creepage_y", "1", "lateral creepage"),
    ("spin", "1/m", "spin creepage"),
    (
        "semi_axis_a",
        "m",
        "semi-axis along the rail of the Hertz patch (of the moved patch with the linear profile contact)",
    ),
    (
        "semi_axis_b",
        "m",
        "semi-axis across the rail of the Hertz patch (of the moved patch with the linear profile contact)",
    ),
    (
        "max_pressure",
        "Pa",
        "maximum pressure: Hertz p0 on the adapted mesh (the largest element pressure with the linear profile contact), \
         the largest element pressure on the fixed grid",
    ),
    ("contact_area", "m2", "area in contact: pi a b on the adapted mesh, the elements with pressure on the fixed grid"),
    ("stick_fraction", "1", "fraction of elements in stick"),
    ("wear_volume_rate", "m3/s", "patch integral of the Archard wear rate"),
    (
        "newton_iterations",
        "1",
        "iterations of the contact solve: Newton-Raphson iterations or Gauss-Seidel sweeps (exact-transient, adapted mesh), FFT products of the CG solver or Gauss-Seidel sweeps (fixed grid; both, summed, on a step CG handed to Gauss-Seidel); 0 for FASTSIM",
    ),
    ("in_contact", "1", "1 in contact, 0 contact lost (N <= 0: no patch, fields zero)"),
];

/// The columns of [`STEP_VARS`].
fn step_columns(h: &PatchHistory) -> [&Vec<f64>; 15] {
    [
        &h.time,
        &h.x_c,
        &h.normal_force,
        &h.longitudinal_force,
        &h.creepage_x,
        &h.creepage_y,
        &h.spin,
        &h.semi_axis_a,
        &h.semi_axis_b,
        &h.max_pressure,
        &h.contact_area,
        &h.stick_fraction,
        &h.wear_volume_rate,
        &h.newton_iterations,
        &h.in_contact,
    ]
}

/// The columns of [`STEP_VARS`], to fill in.
pub(super) fn step_columns_mut(h: &mut PatchHistory) -> [&mut Vec<f64>; 15] {
    [
        &mut h.time,
        &mut h.x_c,
        &mut h.normal_force,
        &mut h.longitudinal_force,
        &mut h.creepage_x,
        &mut h.creepage_y,
        &mut h.spin,
        &mut h.semi_axis_a,
        &mut h.semi_axis_b,
        &mut h.max_pressure,
        &mut h.contact_area,
        &mut h.stick_fraction,
        &mut h.wear_volume_rate,
        &mut h.newton_iterations,
        &mut h.in_contact,
    ]
}

/// Real-valued patch fields on (step, element): (name, units, long_name),
/// in the order of [`field_columns`]; the `stick` flag (i8) comes after.
pub(super) const FIELD_VARS: [(&str, &str, &str); 6] = [
    ("pressure", "Pa", "normal pressure"),
    ("traction_x", "Pa", "longitudinal traction on the wheel"),
    ("traction_y", "Pa", "lateral traction on the wheel"),
    ("slip_x", "m/s", "longitudinal slip velocity of the wheel relative to the rail"),
    ("slip_y", "m/s", "lateral slip velocity of the wheel relative to the rail"),
    ("wear_rate", "m/s", "wear rate (the depth rate of the wear law)"),
];

/// The columns of [`FIELD_VARS`].
fn field_columns(f: &PatchFields) -> [&Array2<f64>; 6] {
    [&f.pressure, &f.traction_x, &f.traction_y, &f.slip_x, &f.slip_y, &f.wear_rate]
}

/// The columns of [`FIELD_VARS`], to fill in.
pub(super) fn field_columns_mut(f: &mut PatchFields) -> [&mut Array2<f64>; 6] {
    [&mut f.pressure, &mut f.traction_x, &mut f.traction_y, &mut f.slip_x, &mut f.slip_y, &mut f.wear_rate]
}

fn write_history(g: &NcGroup, h: &PatchHistory, record: &RunRecord) -> Result<(), NcError> {
    let steps: Vec<i64> = (0..h.time.len() as i64).collect();
    g.coord_i64("step", &steps, "1", "contact time step", false)?;
    let n = record.elements.len();
    let elements: Vec<i64> = (0..n as i64).collect();
    let order = match record.elements {
        Elements::Adapted(_) => "patch element (strip by strip, leading edge first)",
        Elements::Grid(_) => "potential-contact grid element (row by row, leading edge first)",
    };
    g.coord_i64("element", &elements, "1", order, false)?;
    for ((name, units, long_name), v) in STEP_VARS.iter().zip(step_columns(h)) {
        g.var_f64(name, &["step"], ArrayView1::from(v.as_slice()).into_dyn(), units, long_name)?;
    }
    let element_var = |name: &str, v: &[f64], units: &str, long_name: &str| {
        g.var_f64(name, &["element"], ArrayView1::from(v).into_dyn(), units, long_name)
    };
    match record.elements {
        Elements::Adapted(mesh) => {
            let d_xi: Vec<f64> = (0..n).map(|k| mesh.d_xi[mesh.strip(k)]).collect();
            element_var("xi", &mesh.xi, "1", "element centre x / a")?;
            element_var("eta", &mesh.eta, "1", "element centre y / b")?;
            element_var("d_xi", &d_xi, "1", "element length along x / a")?;
            element_var("d_eta", &vec![mesh.d_eta; n], "1", "strip width / b")?;
        }
        Elements::Grid(grid) => {
            let (a, b) = record.mean_patch;
            let (xs, ys) = grid.centres();
            let xi: Vec<f64> = xs.iter().map(|x| x / a).collect();
            let eta: Vec<f64> = ys.iter().map(|y| y / b).collect();
            element_var("xi", &xi, "1", "element centre x / a at the mean normal force")?;
            element_var("eta", &eta, "1", "element centre y / b at the mean normal force")?;
            element_var("d_xi", &vec![grid.dx / a; n], "1", "element length along x / a at the mean normal force")?;
            element_var("d_eta", &vec![grid.dy / b; n], "1", "element width / b at the mean normal force")?;
            element_var("element_x", &xs, "m", "element centre x in the contact frame (rolling direction)")?;
            element_var("element_y", &ys, "m", "element centre y in the contact frame (lateral)")?;
            element_var("element_dx", &vec![grid.dx; n], "m", "element length along x")?;
            element_var("element_dy", &vec![grid.dy; n], "m", "element width along y")?;
        }
    }
    if let Some(f) = &h.fields {
        let dims = ["step", "element"];
        for ((name, units, long_name), v) in FIELD_VARS.iter().zip(field_columns(f)) {
            g.var_f64(name, &dims, v.view().into_dyn(), units, long_name)?;
        }
        g.var_i8("stick", &dims, f.stick.view().into_dyn(), "1", "adhesion flag")?;
        g.var_attr_str("stick", "flag_values", "0 1")?;
        g.var_attr_str("stick", "flag_meanings", "slip stick")?;
        g.var_i8("wear_regime", &dims, f.wear_regime.view().into_dyn(), "1", "the wear law's regime")?;
        let values: Vec<String> = (0..=record.wear_regimes.len()).map(|v| v.to_string()).collect();
        g.var_attr_str("wear_regime", "flag_values", &values.join(" "))?;
        let meanings = std::iter::once("none").chain(record.wear_regimes.iter().copied()).collect::<Vec<_>>();
        g.var_attr_str("wear_regime", "flag_meanings", &meanings.join(" "))?;
    }
    Ok(())
}
