//! The run file in the field's units (issue 35): band levels against the
//! ISO 3095 limit, traffic in MGT and days, when each band reaches the
//! limit, `growth.stop = "limit"`, and resume bit for bit with them; the
//! config keys of `[levels]` and `[traffic]` and their refusals.
use corrugation::config::{load_file, load_str};
use corrugation::levels::forecast::{driven, passages_to_limit};
use corrugation::levels::limit::ISO3095_LIMIT;
use corrugation::output::netcdf::{read_attr_str, read_f64};
use corrugation::run::{resume, run_scene};
use std::path::{Path, PathBuf};

const GROWTH: &str = include_str!("../configs/growth_fastsim.toml");

/// The coarse growth study of the tests (about 0.05 s per passage).
fn overrides(extra: &[&str]) -> Vec<String> {
    let coarse = [
        "contact.elements_x=6",
        "contact.elements_y=6",
        "rail.dx=5e-4",
        "rail.dy=1e-3",
        "passage.step_length=5e-4",
        "growth.contact_history=[]",
        "growth.adaptive=false",
        "growth.traffic_scale=2e4",
    ];
    coarse.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn run(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let r = load_str(GROWTH, "growth", &overrides(extra)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(name);
    run_scene(&r, &out, &mut |_| {}).unwrap();
    out
}

fn table(path: &Path, name: &str) -> ndarray::Array2<f64> {
    read_f64(path, "passes", name).unwrap().into_dimensionality().unwrap()
}

fn column(path: &Path, name: &str) -> Vec<f64> {
    read_f64(path, "passes", name).unwrap().into_raw_vec_and_offset().0
}

fn errors(text: &str, set: &[&str]) -> String {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    load_str(text, "t", &set).map(|_| ()).unwrap_err().to_string()
}

#[test]
fn levels_limit_and_traffic_in_operator_units() {
    let dir = tempfile::tempdir().unwrap();
    let traffic = ["traffic.axle_load=22.5e3", "traffic.trains_per_day=100", "traffic.axles_per_train=32"];
    let out = run(dir.path(), "units.h5", &[&traffic[..], &["growth.passes=3"]].concat());
    // The bands a 120 mm stretch on a 0.5 mm grid resolves: 25 mm (a
    // quarter of it) down to 1.25 mm (lower edge above 1 mm).
    let band = column(&out, "band");
    let nominal = [25.0, 20.0, 16.0, 12.5, 10.0, 8.0, 6.3, 5.0, 4.0, 3.15, 2.5, 2.0, 1.6, 1.25];
    assert_eq!(band.len(), nominal.len(), "{band:?}");
    assert!(band.iter().zip(nominal).all(|(b, n)| (b * 1e3 - n).abs() < 1e-9));
    // The ISO 3095 limit of those bands (3.15 mm the table's last; shorter:
    // none, inf).
    let limit = column(&out, "limit_level");
    for (k, n) in nominal.iter().enumerate() {
        let want = ISO3095_LIMIT.iter().find(|(cm, _)| (cm * 10.0 - n).abs() < 1e-9).map_or(f64::INFINITY, |p| p.1);
        assert_eq!(limit[k], want, "{n} mm");
    }
    // passages_to_limit is the level's distance to the limit at its rate
    // (a band below 1 nm at the start, which holds no roughness of its own, at the pace
    // of its driven change: levels::forecast::driven).
    let (level, rate, to_limit) =
        (table(&out, "roughness_level"), table(&out, "level_rate"), table(&out, "passages_to_limit"));
    assert_eq!(level.dim(), (3, nominal.len()));
    // (A continuous track wears no forced pattern: the forecast is the
    // exponential one.)
    let forced = table(&out, "forced_band_wear");
    assert!(forced.iter().all(|f| *f == 0.0), "{forced:?}");
    let (initial, scale) = (column(&out, "initial_level"), column(&out, "traffic_scale"));
    for ((p, k), n) in to_limit.indexed_iter() {
        let before = if p == 0 { initial[k] } else { level[[p - 1, k]] };
        let (r, f) = driven(initial[k], before, level[[p, k]], rate[[p, k]], scale[p], 0.0);
        assert_eq!(*n, passages_to_limit(level[[p, k]], r, f, limit[k]));
        if n.is_finite() && *n > 0.0 && f == 0.0 {
            assert!((level[[p, k]] + rate[[p, k]] * n / 1e5 - limit[k]).abs() < 1e-9);
        }
    }
    // The rates are the level changes over the passages' traffic.
    // (A band at the floor, -120 dB, has no rate: 0.)
    let floor = corrugation::levels::LEVEL_FLOOR;
    for k in 0..nominal.len() {
        for (p, before) in [(0, initial[k]), (2, level[[1, k]])] {
            let want =
                if before > floor && level[[p, k]] > floor { (level[[p, k]] - before) * 1e5 / scale[p] } else { 0.0 };
            assert!((rate[[p, k]] - want).abs() < 1e-9, "band {k}, passage {p}");
        }
    }
    // Uniform random roughness of 1 um rms from 10 to 120 mm: the 10-25 mm
    // bands hold it (about -6 dB each), the short ones hold wear only.
    assert!(initial[0] > -15.0 && initial[0] < 5.0, "{initial:?}");
    // Traffic: 22.5 t axles, 3200 axles a day.
    let passages = column(&out, "traffic");
    let (mgt, days) = (column(&out, "traffic_mgt"), column(&out, "traffic_days"));
    for p in 0..3 {
        assert!((mgt[p] - passages[p] * 22.5 / 1e6).abs() < 1e-12 * mgt[p]);
        assert!((days[p] - passages[p] / 3200.0).abs() < 1e-12 * days[p]);
    }
    let (to_mgt, to_days) = (table(&out, "mgt_to_limit"), table(&out, "days_to_limit"));
    for ((p, k), n) in to_limit.indexed_iter() {
        let close = |a: f64, b: f64| a == b || (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(to_mgt[[p, k]], n * 22.5e-6) && close(to_days[[p, k]], n / 3200.0), "{p} {k}");
    }
    let rail_mgt = read_f64(&out, "rail", "traffic_mgt").unwrap();
    assert_eq!(rail_mgt.len(), read_f64(&out, "rail", "traffic").unwrap().len());
    // Without the operator's keys: no tonnes, no days.
    let plain = run(dir.path(), "plain.h5", &["growth.passes=1"]);
    assert!(read_f64(&plain, "passes", "traffic_mgt").is_err() && read_f64(&plain, "passes", "days_to_limit").is_err());
    assert!(read_f64(&plain, "passes", "passages_to_limit").is_ok());
}

#[test]
fn resumed_levels_and_limit_stop_are_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    // A limit 0.05 dB above each band's initial level: the first band that
    // grows reaches it, and growth.stop = "limit" ends the study there.
    let probe = run(dir.path(), "probe.h5", &["growth.passes=1"]);
    let (band, initial) = (column(&probe, "band"), column(&probe, "initial_level"));
    let entries: Vec<String> = band
        .iter()
        .zip(&initial)
        .filter(|(_, l)| **l > -60.0)
        .map(|(b, l)| format!("{{wavelength = {b}, level = {:.3}}}", l + 0.05))
        .collect();
    let table = format!("levels.limit_table=[{}]", entries.join(", "));
    let set = [
        "levels.limit=table",
        "levels.limit_name=tight",
        table.as_str(),
        "growth.stop=limit",
        "traffic.axle_load=20e3",
        "traffic.axles_per_day=5000",
    ];
    let full = run(dir.path(), "full.h5", &[&set[..], &["growth.passes=30"]].concat());
    let done = column(&full, "traffic").len();
    assert!(done < 30, "the limit stopped the study: {done} passages");
    let reason = read_attr_str(&full, "", "stop_reason").unwrap();
    assert!(reason.starts_with("limit: the ") && reason.contains("band reached the tight limit"), "{reason}");
    assert!(reason.ends_with(&format!("in passage {done}")), "{reason}");
    // The crossing passage: a band below the limit before, at or above it after.
    let (level, limit) = (self::table(&full, "roughness_level"), column(&full, "limit_level"));
    let before = if done > 1 { level.row(done - 2).to_vec() } else { column(&full, "initial_level") };
    assert!((0..limit.len()).any(|k| before[k] < limit[k] && level[[done - 1, k]] >= limit[k]));
    // A run stopped before the crossing and resumed gets the same file.
    let part = run(dir.path(), "part.h5", &[&set[..], &["growth.passes=1"]].concat());
    let s = resume(&part, Some(29), None, &mut |_| {}).unwrap();
    assert_eq!(s.passes, done);
    assert!(s.outlook.iter().any(|l| l.contains("reached the tight limit")), "{:?}", s.outlook);
    same_bits(&full, &part);
}

/// Every dataset of two files equal bit for bit (`passes/cpu_seconds`, a
/// wall-clock measurement, left out), the field-unit ones among them.
fn same_bits(a: &Path, b: &Path) {
    let vars = [
        "roughness_level",
        "level_rate",
        "initial_level",
        "limit_level",
        "passages_to_limit",
        "traffic_mgt",
        "traffic_days",
        "mgt_to_limit",
        "days_to_limit",
        "band",
        "traffic",
        "rms_corrugation",
        "spectrum",
    ];
    for v in vars {
        let (x, y) = (read_f64(a, "passes", v).unwrap(), read_f64(b, "passes", v).unwrap());
        assert_eq!(x.shape(), y.shape(), "{v}");
        assert!(x.iter().zip(y.iter()).all(|(p, q)| p.to_bits() == q.to_bits()), "passes/{v} differs");
    }
    for v in ["profile", "traffic_mgt", "traffic_days"] {
        let (x, y) = (read_f64(a, "rail", v).unwrap(), read_f64(b, "rail", v).unwrap());
        assert!(x.iter().zip(y.iter()).all(|(p, q)| p.to_bits() == q.to_bits()), "rail/{v} differs");
    }
}

#[test]
fn the_config_keys_and_their_refusals() {
    // Configs without the new keys resolve without them (stored configs,
    // sweep members' identity: unchanged).
    let r = load_str(GROWTH, "g", &[]).unwrap();
    assert!(!r.toml.contains("[levels]") && !r.toml.contains("axle"), "{}", r.toml);
    assert!(r.scene.growth.as_ref().unwrap().operation.axle_loads.is_none());
    // [traffic] without a mix: the base class, with the operator's units.
    let ok = load_str(GROWTH, "g", &["traffic.axle_load=22.5e3".into(), "traffic.axles_per_day=4000".into()]).unwrap();
    let g = ok.scene.growth.unwrap();
    assert_eq!(
        (g.classes.len(), g.operation.axle_loads, g.operation.axles_per_day),
        (1, Some(vec![22.5e3]), Some(4000.0))
    );
    let e = errors(GROWTH, &["traffic.axles_per_day=4000", "traffic.trains_per_day=100", "traffic.axles_per_train=4"]);
    assert!(e.contains("traffic.axles_per_day: is given with traffic.trains_per_day"), "{e}");
    let e = errors(GROWTH, &["traffic.trains_per_day=100"]);
    assert!(e.contains("traffic.axles_per_train: missing"), "{e}");
    let e = errors(GROWTH, &["traffic.axle_load=-1"]);
    assert!(e.contains("traffic.axle_load") && e.contains("(0, 100000]"), "{e}");
    // A mix: every class needs an axle load once one has one.
    let mix = include_str!("../configs/growth_discrete_mix.toml");
    let r = load_str(mix, "m", &["traffic.axle_load=20e3".into()]).unwrap();
    assert_eq!(r.scene.growth.unwrap().operation.axle_loads, Some(vec![20e3; 3]));
    let one = mix.replacen("share = 1.0", "share = 1.0\naxle_load = 25e3", 1);
    let e = errors(&one, &[]);
    assert!(e.contains("traffic.mix[1].axle_load: missing"), "{e}");
    let r = load_str(&one, "m", &["traffic.axle_load=20e3".into()]).unwrap();
    assert_eq!(r.scene.growth.unwrap().operation.axle_loads, Some(vec![25e3, 20e3, 20e3]));
    // [levels]: EN 13231-3's bands need their own limit, the grinding
    // limit by default; the grinding limit needs those bands.
    let e = errors(GROWTH, &["levels.bands=en13231-3", "levels.limit=iso3095"]);
    assert!(e.contains("levels.limit: = \"iso3095\" is a one-third-octave curve"), "{e}");
    let r = load_str(GROWTH, "g", &["levels.bands=en13231-3".into()]).unwrap();
    assert_eq!(r.scene.levels.limit, corrugation::levels::limit::LimitCurve::grinding());
    let e = errors(GROWTH, &["levels.limit=grinding"]);
    assert!(e.contains("levels.limit: = \"grinding\" is a limit in EN 13231-3's bands"), "{e}");
    let e = errors(GROWTH, &["levels.limit=table"]);
    assert!(e.contains("levels.limit_table: missing"), "{e}");
    let twice = "levels.limit_table=[{wavelength = 0.025, level = 3}, {wavelength = 0.026, level = 4}]";
    let e = errors(GROWTH, &["levels.limit=table", twice]);
    assert!(e.contains("levels.limit_table[1].wavelength: = 0.026 m: the 25 mm band again (entry 0)"), "{e}");
    let outside = "levels.limit_table=[{wavelength = 2.0, level = 3}]";
    let e = errors(GROWTH, &["levels.bands=en13231-3", "levels.limit=table", outside]);
    assert!(e.contains("levels.limit_table[0].wavelength: = 2 m is in none of the bands"), "{e}");
    let e = errors(GROWTH, &["growth.stop=sometimes"]);
    assert!(e.contains("growth.stop") && e.contains("limit"), "{e}");
}

#[test]
fn a_limit_curve_file_is_read_relative_to_the_config_and_kept_in_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let config = GROWTH.to_string() + "\n[levels]\nlimit = \"file\"\nlimit_file = \"curves/limit.csv\"\n";
    std::fs::create_dir(dir.path().join("curves")).unwrap();
    std::fs::write(dir.path().join("g.toml"), &config).unwrap();
    std::fs::write(dir.path().join("curves/limit.csv"), "# band, level\nwavelength_mm,level_dB\n25,1.5\n10,-2\n")
        .unwrap();
    let r = load_file(&dir.path().join("g.toml"), &overrides(&["growth.passes=1"])).unwrap();
    assert_eq!(r.scene.levels.limit.name, "curves/limit.csv");
    assert_eq!(r.scene.levels.limit.points, vec![(0.025, 1.5), (0.01, -2.0)]);
    // The resolved config holds the values: it loads without the file.
    assert!(r.toml.contains("limit = \"table\""), "{}", r.toml);
    let again = load_str(&r.toml, "stored", &[]).unwrap();
    assert_eq!(again.scene.levels, r.scene.levels);
    let out = dir.path().join("run.h5");
    run_scene(&r, &out, &mut |_| {}).unwrap();
    let limit = column(&out, "limit_level");
    assert_eq!((limit[0], limit[4]), (1.5, -2.0));
    assert!(limit[1].is_infinite());
    // A bad line is named with the file and line.
    std::fs::write(dir.path().join("curves/limit.csv"), "wavelength_mm,level_dB\n25,1.5\n10;x\n").unwrap();
    let e = load_file(&dir.path().join("g.toml"), &[]).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("levels.limit_file") && e.contains("limit.csv, line 3"), "{e}");
}

#[test]
fn the_field_units_change_no_physics() {
    // The same study with and without the operator's traffic, another band
    // set and limit, and the limit stop (not reached): every variable the
    // plain run writes is the same, bit for bit (the CPU time aside).
    let dir = tempfile::tempdir().unwrap();
    let plain = run(dir.path(), "plain.h5", &["growth.passes=3", "growth.store_every=2"]);
    let keyed = run(
        dir.path(),
        "keyed.h5",
        &[
            "growth.passes=3",
            "growth.store_every=2",
            "traffic.axle_load=25e3",
            "traffic.trains_per_day=80",
            "traffic.axles_per_train=24",
            "levels.bands=en13231-3",
            "levels.limit=none",
            "growth.stop=limit",
        ],
    );
    let file = corrugation::output::netcdf::open_file(&plain).unwrap();
    for group in ["passes", "rail"] {
        for name in file.group(group).unwrap().member_names().unwrap() {
            if name == "cpu_seconds" || name.starts_with("band") || name.contains("level") || name.contains("limit") {
                continue;
            }
            let (a, b) = (read_f64(&plain, group, &name), read_f64(&keyed, group, &name));
            let (Ok(a), Ok(b)) = (a, b) else { continue };
            assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{group}/{name} differs");
        }
    }
    // EN 13231-3's bands on a 120 mm stretch: 10-30 mm only (17.3 mm, <= 30 mm).
    assert_eq!(column(&keyed, "band").len(), 1);
    assert!(column(&keyed, "limit_level")[0].is_infinite());
    assert!(column(&keyed, "traffic_days").iter().zip(column(&keyed, "traffic")).all(|(d, t)| *d == t / 1920.0));
}
