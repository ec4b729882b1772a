//! Mixed traffic (`[[traffic.mix]]`): the linear regime's share-weighted
//! growth, the interleaving by share, the traffic-scaling bound per class
//! on the discrete track, determinism and bit-for-bit resume, and the
//! config's errors.
use crate::common;
use corrugation::config::load_str;
use corrugation::output::netcdf::{read_f64, read_i64};
use corrugation::run::{resume, run_scene};
use ndarray::Ix2;
use std::path::Path;

const GROWTH: &str = include_str!("../configs/growth_fastsim.toml");

/// Two classes: the base config's 100 km/h wheel and a slower, lighter one.
const MIX: &str = r#"
[[traffic.mix]]
name = "fast"
share = 1.0

[[traffic.mix]]
name = "slow"
speed = 20.0
normal_force = 90e3
longitudinal_force = 15e3
unsprung_mass = 500.0
share = 1.0
"#;

/// The cheap growth study (coarse mesh and grid) with overrides.
fn coarse(extra: &[&str]) -> Vec<String> {
    // The Hertz chain: its wear follows the profile through the dynamic
    // force alone, the closest to linear in the profile, so that the
    // superposition test sees the traffic mixing and not the contact's own
    // second-order terms (the linear profile contact's moved patch at this
    // 6 x 6 mesh: the mix off the sum by 1.4 % at m = 2e3).
    ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4"]
        .iter()
        .chain(&["contact.normal=hertz"])
        .chain(&["growth.contact_history=[]"])
        .chain(extra)
        .map(|s| s.to_string())
        .collect()
}

fn run(text: &str, set: &[String], dir: &Path, name: &str) -> std::path::PathBuf {
    let r = load_str(text, name, set).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(format!("{name}.h5"));
    run_scene(&r, &out, &mut |_| {}).unwrap();
    out
}

/// The corrugation the study wore into the rail: the final profile less
/// the initial roughness `r0` (of the centre line, uniform across), each
/// row less its mean along the rail (the uniform wear).
fn worn_corrugation(path: &Path, r0: &[f64]) -> ndarray::Array2<f64> {
    let state = read_f64(path, "rail", "state").unwrap().into_dimensionality::<Ix2>().unwrap();
    let mut d = state.clone();
    for mut row in d.rows_mut() {
        row.iter_mut().zip(r0).for_each(|(v, r)| *v -= r);
        let mean = row.mean().unwrap();
        row.mapv_inplace(|v| v - mean);
    }
    d
}

fn rms(a: &ndarray::Array2<f64>) -> f64 {
    (a.iter().map(|v| v * v).sum::<f64>() / a.len() as f64).sqrt()
}

/// Runs each class alone for two passages and the mix for four (fixed
/// `m`); returns the worn corrugation's rms of the larger class, of the
/// classes' difference and of the mix less the classes' sum (m).
fn superposition(m: &str, dir: &Path) -> (f64, f64, f64) {
    let scale = format!("growth.traffic_scale={m}");
    let fixed = ["growth.adaptive=false", scale.as_str()];
    let fast = run(GROWTH, &coarse(&[&fixed[..], &["growth.passes=2"]].concat()), dir, &format!("fast_{m}"));
    let slow_set = [
        "rolling.speed=20.0",
        "load.normal_force=90e3",
        "load.longitudinal_force=15e3",
        "dynamics.unsprung_mass=500.0",
        "growth.passes=2",
    ];
    let slow = run(GROWTH, &coarse(&[&fixed[..], &slow_set[..]].concat()), dir, &format!("slow_{m}"));
    let mixed_text = format!("{GROWTH}\n{MIX}");
    let mix = run(&mixed_text, &coarse(&[&fixed[..], &["growth.passes=4"]].concat()), dir, &format!("mix_{m}"));
    let class = read_i64(&mix, "passes", "traffic_class").unwrap();
    assert_eq!(class.as_slice().unwrap(), &[0, 1, 0, 1], "equal shares alternate");
    // The classes are recorded with their parameters.
    let speed = read_f64(&mix, "traffic", "speed").unwrap();
    assert_eq!(speed.as_slice().unwrap(), &[27.78, 20.0]);
    let share = read_f64(&mix, "traffic", "share").unwrap();
    assert_eq!(share.as_slice().unwrap(), &[0.5, 0.5]);
    // The initial roughness, the same in all three runs (same seed).
    let scene = load_str(&mixed_text, "mix", &coarse(&fixed)).unwrap().scene;
    let grid = corrugation::build::periodic_grid(&scene);
    let roughness = &scene.growth.as_ref().unwrap().roughness;
    let r0 = corrugation::growth::roughness::profile_line(roughness, &grid.xs(), grid.nx as f64 * grid.dx);
    let (a, b, m) = (worn_corrugation(&fast, &r0), worn_corrugation(&slow, &r0), worn_corrugation(&mix, &r0));
    let (largest, apart, error) = (rms(&a).max(rms(&b)), rms(&(&a - &b)), rms(&(&(&a + &b) - &m)));
    eprintln!(
        "m = {m}: worn corrugation rms {largest:.4e} m, classes apart {apart:.4e} m, mix off the sum {error:.4e} m"
    );
    (largest, apart, error)
}

#[test]
fn mixed_traffic_wears_the_sum_of_its_classes() {
    // In the linear regime the profile evolves as dr/dn = -sum_c s_c W_c(r)
    // with each W_c linear in r: over a traffic that changes r little, the
    // mix wears the sum of what each class alone wears over its own share of
    // the traffic. Two passages of each class alone against four of the mix
    // (the classes alternate, 2 m each): the corrugation worn in (the final
    // profile less the initial roughness, less the uniform wear) is their
    // sum within 1 % at m = 2e3 (measured 0.42 %), while the classes alone
    // differ by 58 %. The remainder is the splitting's: each passage sees
    // the profile the others left, a change of relative size m |W| / |r|,
    // so it grows in proportion to m (4.1 % at m = 2e4).
    let dir = tempfile::tempdir().unwrap();
    let (largest, apart, error) = superposition("2e3", dir.path());
    assert!(largest > 1e-10, "the study must wear a corrugation: {largest}");
    assert!(apart > 0.3 * largest, "the classes must differ for the test to mean anything: {apart} vs {largest}");
    assert!(error < 0.01 * largest, "{error} vs {largest}");
    let (largest_10, _, error_10) = superposition("2e4", dir.path());
    let order = (error_10 / largest_10) / (error / largest);
    assert!((5.0..20.0).contains(&order), "the remainder must grow in proportion to m: x{order} for m x10");
}

/// The mix on one sleeper bay of the discrete track (coarse).
fn discrete_mix(extra: &[&str]) -> Vec<String> {
    common::DISCRETE_BAY
        .iter()
        .chain(&[
            "growth.adaptive=true",
            "growth.traffic_scale=2e3",
            "growth.contact_history=[]",
            "traffic.mix[1].share=2.0",
        ])
        .chain(extra)
        .map(|s| s.to_string())
        .collect()
}

#[test]
fn mixed_traffic_on_the_discrete_track_keeps_the_bound_and_resumes_bit_for_bit() {
    let text = format!("{GROWTH}\n{MIX}");
    let dir = tempfile::tempdir().unwrap();
    // (The resumed run repeats the first four passages: it is also the
    // check that the same config gives the same result.)
    let full = run(&text, &discrete_mix(&["growth.passes=7"]), dir.path(), "full");
    let part = run(&text, &discrete_mix(&["growth.passes=4"]), dir.path(), "part");
    resume(&part, Some(3), None, &mut |_| {}).unwrap();
    for other in [&part] {
        for (g, v) in [("rail", "state"), ("passes", "traffic"), ("passes", "traffic_scale"), ("passes", "spectrum")] {
            let (a, b) = (read_f64(&full, g, v).unwrap(), read_f64(other, g, v).unwrap());
            assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{}: {g}/{v}", other.display());
        }
        assert_eq!(
            read_i64(&full, "passes", "traffic_class").unwrap(),
            read_i64(other, "passes", "traffic_class").unwrap()
        );
    }
    // Every update within the bound, whichever class; each class's m is its
    // own (the slow class changes the profile at another rate).
    let q = read_f64(&full, "passes", "update_ratio").unwrap();
    let bound = corrugation::growth::traffic::DEFAULT_MAX_UPDATE_RATIO;
    assert!(q.iter().all(|q| *q <= bound * (1.0 + 1e-12)), "{q:?}");
    // The real traffic of each class within one update of its share (1/3,
    // 2/3 of the total), the class of every passage recorded.
    let class = read_i64(&full, "passes", "traffic_class").unwrap();
    let m = read_f64(&full, "passes", "traffic_scale").unwrap();
    let total: f64 = m.iter().sum();
    let m_max = m.iter().fold(0.0f64, |a, b| a.max(*b));
    for (c, share) in [(0, 1.0 / 3.0), (1, 2.0 / 3.0)] {
        let t: f64 = class.iter().zip(m.iter()).filter(|(k, _)| **k == c).map(|(_, m)| m).sum();
        assert!(t > 0.0 && (t - share * total).abs() <= m_max, "class {c}: {t} of {total}");
    }
}

#[test]
fn traffic_mix_config_errors() {
    let text = format!("{GROWTH}\n{MIX}");
    let errors =
        |text: &str, set: &[&str]| match load_str(text, "g", &set.iter().map(|s| s.to_string()).collect::<Vec<_>>()) {
            Ok(_) => Vec::new(),
            Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
        };
    assert!(errors(&text, &[]).is_empty());
    let e = errors(&text, &["traffic.mix[1].share=0"]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[1].share: = 0 is out of range")), "{e:?}");
    let e = errors(&text, &["traffic.mix[1].name=\"fast\""]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[1].name: = \"fast\" names an earlier class")), "{e:?}");
    let e = errors(&text, &["traffic.mix[0].name=\"a b\""]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[0].name: = \"a b\" must be")), "{e:?}");
    let e = errors(&text, &["traffic.mix[1].speed=300"]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[1].speed: = 300 is out of range")), "{e:?}");
    let e = errors(&text, &["traffic.mix[1].colour=1"]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[1].colour: unknown key")), "{e:?}");
    // A class beyond the friction limit names its own key.
    let e = errors(&text, &["traffic.mix[1].longitudinal_force=40e3"]);
    assert!(
        e.iter().any(|m| m.starts_with("traffic.mix[1].longitudinal_force: = 4.000000e4 N: |F_x| reaches")),
        "{e:?}"
    );
    // A heavier class widens the largest patch beyond the rail grid.
    let e = errors(&text, &["traffic.mix[1].normal_force=400e3"]);
    assert!(e.iter().any(|m| m.starts_with("rail.half_width: ")), "{e:?}");
    let e = errors(&text, &["traffic.mix[0].name=\"base\""]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix[0].name: = \"base\" is reserved")), "{e:?}");
    let e = errors(&format!("{GROWTH}\n[traffic]\nmix = []\n"), &[]);
    assert!(e.iter().any(|m| m.starts_with("traffic.mix: must list at least one class")), "{e:?}");
    let single = include_str!("../configs/paper_normal_30mm.toml").to_string() + MIX;
    let e = errors(&single, &[]);
    assert!(e.iter().any(|m| m.starts_with("traffic: is only allowed with a [growth] section")), "{e:?}");
}
