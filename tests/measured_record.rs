//! `roughness.kind = "measured"`: a record file as the initial profile.
//! Bad records are refused naming the file and line (through the binary);
//! a record of known harmonics gives exactly those harmonics on the rail
//! grid; a resumed run rebuilds the profile from the run file's copy of the
//! record, bit for bit, without the record file.
use corrugation::config::{RecordSource, load_str_with};
use corrugation::growth::roughness::profile_line;
use corrugation::output::netcdf::{read_attr_str, read_f64};
use corrugation::params::Roughness;
use std::f64::consts::PI;
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_corrugation");

fn corrugation(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The paper's 15 mm scene (FASTSIM, 30 mm stretch, 0.1 mm rail grid) as a
/// growth study of `passes` passages from the record `record`.
fn config(record: &str, passes: usize, extra: &str) -> String {
    let base = include_str!("../configs/paper_normal_15mm.toml").replace("store_fields = true", "store_fields = false");
    format!(
        "{base}\n[growth]\npasses = {passes}\ncheckpoint_every = 1\ncontact_history = []\n\n\
         [roughness]\nkind = \"measured\"\nfile = \"{record}\"\n{extra}\n"
    )
}

/// 2 um at 15 mm (phase 0.5) and 1 um at 6 mm (phase -0.2), on 30 mm.
fn two_harmonics(x: f64) -> f64 {
    2e-6 * (2.0 * PI * x / 0.015 + 0.5).sin() + 1e-6 * (2.0 * PI * x / 0.006 - 0.2).sin()
}

/// A record of `n` samples `spacing` m apart (in m and um), after a header.
fn record_text(n: usize, spacing: f64, height: impl Fn(f64) -> f64) -> String {
    let mut s = String::from("# synthetic\nDistance (m)\tDisplacement (um)\n");
    for k in 0..n {
        let x = k as f64 * spacing;
        s.push_str(&format!("{x:.4}\t{:.6}\n", height(x) * 1e6));
    }
    s
}

#[test]
fn a_record_of_known_harmonics_gives_them_on_the_rail_grid() {
    let dir = tempfile::tempdir().unwrap();
    // Heights printed to 1e-6 um: the record holds the harmonics to 5e-13 m.
    std::fs::write(dir.path().join("rec.txt"), record_text(30, 1e-3, two_harmonics)).unwrap();
    let r = load_str_with(&config("rec.txt", 1, ""), "t", &[], &RecordSource::Dir(dir.path().into())).unwrap();
    let g = r.scene.growth.as_ref().unwrap();
    let Roughness::Measured(m) = &g.roughness else { panic!("measured") };
    let (x_min, dx) = (r.scene.rail.x_min, r.scene.rail.dx);
    let nx = ((r.scene.rail.x_max - x_min) / dx).round() as usize;
    assert_eq!(nx, 300);
    let xs: Vec<f64> = (0..nx).map(|i| x_min + i as f64 * dx).collect();
    let line = profile_line(&g.roughness, &xs, 0.03);
    let worst = xs.iter().zip(&line).map(|(x, h)| (h - two_harmonics(x - x_min)).abs()).fold(0.0, f64::max);
    assert!(worst < 2e-12, "largest departure {worst} m");
    // The two harmonics, exact; the others at the rounding of the file.
    let big: Vec<_> = m.harmonics.iter().filter(|h| h.amplitude > 1e-10).collect();
    assert_eq!(big.len(), 2, "{:?}", m.harmonics);
    assert!((big[0].wavelength - 0.015).abs() < 1e-15 && (big[0].amplitude - 2e-6).abs() < 1e-12);
    assert!((big[1].wavelength - 0.006).abs() < 1e-15 && (big[1].amplitude - 1e-6).abs() < 1e-12);
    // The resolved config names the record by its absolute path and its
    // samples' fingerprint.
    let t: toml::Table = r.toml.parse().unwrap();
    let file = t["roughness"]["file"].as_str().unwrap();
    assert!(Path::new(file).is_absolute() && file.ends_with("rec.txt"), "{file}");
    assert_eq!(t["roughness"]["sha256"].as_str().unwrap(), m.samples.sha256());
    assert_eq!(t["roughness"]["position_unit"].as_str(), Some("m"), "from the header");
}

#[test]
fn every_bad_record_is_refused_with_its_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let good: Vec<String> = (0..31).map(|k| format!("{:.4} {:.3}", k as f64 * 1e-3, (k % 7) as f64)).collect();
    let with = |edit: &dyn Fn(&mut Vec<String>)| {
        let mut lines = vec!["# header comment".to_string(), "pos h".to_string()];
        let mut data = good.clone();
        edit(&mut data);
        lines.extend(data);
        lines.join("\n") + "\n"
    };
    // (record text, config extra, the file:line the message must give, a word it must hold)
    let cases: Vec<(String, &str, &str, &str)> = vec![
        (with(&|d| d[4] = "0.004 1.2x".into()), "", "bad.txt:7", "expected numbers"),
        (with(&|d| d[6] = "0.004 1".into()), "", "bad.txt:9", "must increase"),
        (with(&|d| d[10] = "0.0104 1".into()), "", "bad.txt:13", "evenly sampled"),
        (with(&|d| drop(d.drain(12..15))), "", "bad.txt:15", "gap"),
        (with(&|d| d.truncate(20)), "", "bad.txt:22", "too short"),
        (with(&|_| {}), "wavelength_min = 0.0019", "bad.txt:4", "too coarse"),
        (with(&|d| d[3] = "0.003".into()), "", "bad.txt:6", "field"),
        // Positions in millimetres read as metres: the unit key named.
        (
            with(&|d| d.iter_mut().enumerate().for_each(|(k, l)| *l = format!("{k} {}", k % 7))),
            "",
            "bad.txt:4",
            "set roughness.position_unit = \"mm\"",
        ),
    ];
    for (i, (text, extra, at, word)) in cases.iter().enumerate() {
        std::fs::write(dir.path().join("bad.txt"), text).unwrap();
        let cfg = dir.path().join(format!("c{i}.toml"));
        std::fs::write(&cfg, config("bad.txt", 1, extra)).unwrap();
        let o = corrugation(&["check", cfg.to_str().unwrap()]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "case {i}: {e}");
        assert!(e.contains("roughness.file: "), "{e}");
        assert!(e.contains(at) && e.contains(word), "case {i}: expected {at} and `{word}` in:\n{e}");
    }
    // A stretch that is not a whole number of record samples, and a
    // window outside the record.
    std::fs::write(dir.path().join("bad.txt"), with(&|_| {})).unwrap();
    let cfg = dir.path().join("s.toml");
    std::fs::write(&cfg, config("bad.txt", 1, "")).unwrap();
    let o = corrugation(&["check", cfg.to_str().unwrap(), "--set", "rail.x_max=0.0305", "--set", "passage.end=0.04"]);
    assert!(stderr(&o).contains("whole number of them"), "{}", stderr(&o));
    let o = corrugation(&["check", cfg.to_str().unwrap(), "--set", "roughness.window_start=0.5"]);
    assert!(stderr(&o).contains("roughness.window_start: = 0.5 m lies outside the record"), "{}", stderr(&o));
    // A missing file.
    let o = corrugation(&["check", cfg.to_str().unwrap(), "--set", "roughness.file=none.txt"]);
    assert!(stderr(&o).contains("roughness.file: cannot read the record") && stderr(&o).contains("none.txt"));
}

#[test]
fn the_run_file_keeps_the_record_and_a_resume_needs_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("rec.txt");
    std::fs::write(&rec, record_text(31, 1e-3, two_harmonics)).unwrap();
    let cfg = dir.path().join("m.toml");
    std::fs::write(&cfg, config("rec.txt", 3, "remove_spikes = true\ndetrend = true")).unwrap();
    let whole = dir.path().join("whole.h5");
    let o = corrugation(&["run", cfg.to_str().unwrap(), "-o", whole.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("record: ") && stderr(&o).contains("periodic seam"), "{}", stderr(&o));
    let part = dir.path().join("part.h5");
    let o = corrugation(&["run", cfg.to_str().unwrap(), "-o", part.to_str().unwrap(), "--set", "growth.passes=2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The record as read is in the run file.
    let heights = read_f64(&part, "record", "height").unwrap();
    assert_eq!(heights.len(), 31);
    assert!((heights[3] - two_harmonics(0.003)).abs() < 1e-12);
    assert!(read_attr_str(&part, "record", "sha256").unwrap().len() == 64);
    // Without the record file, the resume rebuilds the same profile.
    std::fs::remove_file(&rec).unwrap();
    let o = corrugation(&["resume", part.to_str().unwrap(), "--passes", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (g, v) in [("rail", "profile"), ("rail", "state"), ("passes", "rms_corrugation")] {
        assert_eq!(read_f64(&part, g, v).unwrap(), read_f64(&whole, g, v).unwrap(), "{g}/{v}");
    }
    // The resolved config, run again: the record file must be the same.
    std::fs::write(&rec, record_text(31, 1e-3, |x| two_harmonics(x) * 1.01)).unwrap();
    let stored = dir.path().join("stored.toml");
    std::fs::write(&stored, read_attr_str(&whole, "", "config").unwrap()).unwrap();
    let o = corrugation(&["check", stored.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("roughness.sha256") && stderr(&o).contains("the record changed"), "{}", stderr(&o));
}

#[test]
fn the_shipped_example_finds_the_spikes_it_was_made_with() {
    // configs/records/synthetic_trolley.txt (scripts/make_measured_record.py)
    // holds +25 um at 0.212 m and -18 um at 0.433 m on 0.6 m at 1 mm.
    let cfg = format!("{}/configs/measured_rail.toml", env!("CARGO_MANIFEST_DIR"));
    let r = corrugation::config::load_file(Path::new(&cfg), &[]).unwrap();
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    let Some(Roughness::Measured(m)) = r.scene.growth.as_ref().map(|g| &g.roughness) else { panic!("measured") };
    assert_eq!(m.samples.positions.len(), 600);
    assert_eq!(m.report.windows, 5);
    let spikes: Vec<(f64, f64)> = m.report.spikes.iter().map(|(x, h, _)| (*x, *h)).collect();
    assert_eq!(spikes.len(), 2, "{spikes:?}");
    assert!((spikes[0].0 - 0.212).abs() < 1e-12 && (spikes[0].1 - 25e-6).abs() < 1.5e-6, "{spikes:?}");
    assert!((spikes[1].0 - 0.433).abs() < 1e-12 && (spikes[1].1 + 18e-6).abs() < 1.5e-6, "{spikes:?}");
    // Its three harmonics, periodic on the 120 mm stretch, come through
    // (the window's noise adds a few hundredths of a um).
    for (wavelength, amplitude) in [(0.040, 1.5e-6), (0.030, 1.0e-6), (0.015, 0.6e-6)] {
        let h = m.harmonics.iter().find(|h| (h.wavelength - wavelength).abs() < 1e-12).unwrap();
        assert!((h.amplitude - amplitude).abs() < 0.2 * amplitude, "{wavelength}: {}", h.amplitude);
    }
    // `check` reports the record and prints the inputs in engineering units.
    let o = corrugation(&["check", &cfg]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(text.contains("record             spikes removed: 2 beyond 5"), "{text}");
    assert!(text.contains("= 100 km/h") && text.contains("= 210 GPa"), "{text}");
}

#[test]
fn check_says_which_bands_of_the_record_the_stretch_misrepresents() {
    // A 2 um, 12 mm wave on 0.3 m at 0.5 mm: on the 30 mm stretch it is no
    // harmonic (30 / 12 = 2.5), its 12.5 mm band holds none of the
    // stretch's; a 15 mm wave is a harmonic and nothing is said.
    let dir = tempfile::tempdir().unwrap();
    for (wavelength, said) in [(0.012, true), (0.015, false)] {
        let record = dir.path().join("r.txt");
        std::fs::write(&record, record_text(600, 5e-4, |x| 2e-6 * (2.0 * PI * x / wavelength).sin())).unwrap();
        let cfg = dir.path().join("c.toml");
        std::fs::write(&cfg, config("r.txt", 1, "")).unwrap();
        let o = corrugation(&["check", cfg.to_str().unwrap()]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{}", stderr(&o));
        let line = text.lines().find(|l| l.contains("misrepresents"));
        assert_eq!(line.is_some(), said, "{wavelength}: {text}");
        if let Some(line) = line {
            // 2 um amplitude: 1.41 um rms, 3.0 dB re 1 um.
            assert!(line.contains("12.5 mm 3.0 dB in the record, no harmonic on the stretch"), "{line}");
        }
    }
}

#[test]
fn the_measured_rail_guide_reads_what_the_program_gives() {
    // docs/src/guide/measured-rail.md (scripts/measured_windows.sh): the
    // shipped example's rms from 1.277 um after the first passage to 1.052
    // um after 4.5e5 wheel passages, and its 40 mm harmonic's mean rate
    // -0.33 to -0.29 dB per 1e5 over the windows (window 0 inside).
    let cfg = format!("{}/configs/measured_rail.toml", env!("CARGO_MANIFEST_DIR"));
    let r = corrugation::config::load_file(Path::new(&cfg), &[]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.h5");
    corrugation::run::run_scene(&r, &out, &mut |_| {}).unwrap();
    let rms = read_f64(&out, "passes", "rms_corrugation").unwrap();
    let traffic = read_f64(&out, "passes", "traffic").unwrap();
    let (first, last) = (rms[0] * 1e6, rms[rms.len() - 1] * 1e6);
    assert!((first - 1.277).abs() < 6e-4 && (last - 1.052).abs() < 6e-4, "rms {first:.4} -> {last:.4} um");
    let n = traffic[traffic.len() - 1];
    assert!((n / 4.5e5 - 1.0).abs() < 0.02, "{n:e} wheel passages");
    let w = read_f64(&out, "passes", "wavelength").unwrap();
    let k = w.iter().position(|l| (l - 0.04).abs() < 1e-9).unwrap();
    let rate = read_f64(&out, "passes", "growth_rate").unwrap();
    let rate = rate.index_axis(ndarray::Axis(1), k).mean().unwrap();
    assert!((-0.335..=-0.285).contains(&rate), "40 mm {rate:.3} dB per 1e5");
}

#[test]
fn the_when_to_grind_guide_reads_what_the_spectrum_forecasts() {
    // docs/src/guide/when-to-grind.md, section 2: `corrugation spectrum
    // configs/measured_rail.toml`'s forecast, line by line where the guide
    // draws its conclusions from it.
    let cfg = format!("{}/configs/measured_rail.toml", env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.h5");
    let o = corrugation(&["spectrum", &cfg, "-o", out.to_str().unwrap()]);
    let text = stderr(&o);
    assert!(o.status.success(), "{text}");
    for line in [
        "  40 mm         0.6  -0.303    -3.2  now (+3.8 dB over it)",
        "  31.5 mm      -2.8  -0.560    -5.0  now (+2.2 dB over it)",
        "  linear horizon: 391 MGT, 4076 days (11 years) at 6000 axles per day (2.45e7 wheel passages)",
        "  54.8 mm       1.5  -0.344    16.9  after 408 MGT",
    ] {
        assert!(text.contains(line), "the guide's `{line}` is not in:\n{text}");
    }
}
