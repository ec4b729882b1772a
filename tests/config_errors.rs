//! Bad input: a corpus of bad configs, each with the message it must
//! produce; all problems reported at once; property test of overrides.
use corrugation::config::load_str;
use proptest::prelude::*;

const BASE: &str = include_str!("../configs/paper_normal_30mm.toml");

fn errors(text: &str, set: &[&str]) -> Vec<String> {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    match load_str(text, "test.toml", &set) {
        Ok(_) => Vec::new(),
        Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn paper_configs_are_valid() {
    for (name, text) in [
        ("paper_steady", include_str!("../configs/paper_steady.toml")),
        ("paper_normal_30mm", BASE),
        ("paper_normal_15mm", include_str!("../configs/paper_normal_15mm.toml")),
        ("paper_longitudinal_30mm", include_str!("../configs/paper_longitudinal_30mm.toml")),
        ("paper_longitudinal_15mm", include_str!("../configs/paper_longitudinal_15mm.toml")),
        ("growth_saturation", include_str!("../configs/growth_saturation.toml")),
        ("growth_discrete", include_str!("../configs/growth_discrete.toml")),
    ] {
        assert_eq!(errors(text, &[]), Vec::<String>::new(), "{name}");
    }
}

#[test]
fn corpus_of_bad_values() {
    // (override, expected fragment of the single error message)
    let corpus: &[(&str, &str)] = &[
        (
            "material.friction_coefficient=0",
            "material.friction_coefficient: = 0 is out of range; expected a number in (0, 1]",
        ),
        (
            "material.friction_coefficient=1.5",
            "material.friction_coefficient: = 1.5 is out of range; expected a number in (0, 1]",
        ),
        ("material.poisson_ratio=0.5", "material.poisson_ratio: = 0.5 is out of range; expected a number in [0, 0.5)"),
        ("material.young_modulus=-1", "material.young_modulus: = -1 is out of range; expected a finite number > 0"),
        (
            "material.young_modulus=\"steel\"",
            "material.young_modulus: `steel` is not a number with a unit (such as \"210GPa\"); expected a finite number > 0 in Pa",
        ),
        ("load.normal_force=0", "load.normal_force: = 0 is out of range; expected a finite number > 0"),
        ("load.normal_force=nan", "load.normal_force: = NaN is out of range"),
        (
            "load.harmonics[0].amplitude=1e5",
            "load.harmonics: normal-force amplitudes sum to 1.000000e5 N >= load.normal_force = 1.000000e5 N: contact is lost where N <= 0, which is only allowed with no longitudinal force",
        ),
        (
            "load.longitudinal_force=30e3",
            "load.longitudinal_force: |F_x| reaches 3.000000e4 N, which must be < mu * min N = 2.200000e4 N",
        ),
        (
            "load.harmonics[0].wavelength=1.5e-4",
            "load.harmonics[0].wavelength: = 0.00015 m is shorter than two rail-grid cells (2 * rail.dx = 0.0002 m)",
        ),
        (
            "load.harmonics[0].quantity=lateral_force",
            "load.harmonics[0].quantity: = \"lateral_force\" is not allowed; expected one of \"normal_force\", \"longitudinal_force\"",
        ),
        (
            "contact.model=implicit",
            "contact.model: = \"implicit\" is not allowed; expected one of \"exact-transient\", \"simplified-transient\", \"fastsim\"",
        ),
        ("contact.elements_x=1", "contact.elements_x: = 1 is out of range; expected an integer in [2, 200]"),
        ("contact.elements_y=2.5", "contact.elements_y: expected an integer in [2, 200], found float"),
        ("contact.fastsim_bound=square", "contact.fastsim_bound: = \"square\" is not allowed"),
        (
            "geometry.wheel_profile_radius=-0.2",
            "geometry.wheel_profile_radius: = -0.2 m gives a lateral curvature sum B",
        ),
        (
            "geometry.wheel_profile_radius=0",
            "geometry.wheel_profile_radius: = 0 is out of range; expected a non-zero number or +-inf",
        ),
        ("geometry.wheel_radius=0.01", "outside Kalker's creep-coefficient table"),
        ("rolling.speed=0", "rolling.speed: = 0 is out of range; expected a number in (0, 200]"),
        ("passage.end=-0.05", "passage.end: = -0.05 must be > passage.start = -0.03"),
        ("passage.step_length=0", "passage.step_length: = 0 is out of range"),
        ("rail.x_max=-1", "rail.x_max: = -1 must be > rail.x_min = 0"),
        ("rail.dy=0.2", "rail.dy: = 0.2 is out of range; expected a number in (0, 0.01]"),
        ("wear.substeps=0", "wear.substeps: = 0 is out of range; expected an integer in [1, 64]"),
        ("wear.k_over_h=-1e-14", "wear.k_over_h: = -0.00000000000001 is out of range; expected a finite number >= 0"),
        ("output.store_fields=1", "output.store_fields: expected true or false, found integer"),
        ("material.colour=1", "material.colour: unknown key"),
        ("solver.tolerance=1", "solver: unknown section or key"),
    ];
    for (set, expected) in corpus {
        // Wide rail grid so the large-amplitude case reports only its own problem.
        let e = errors(BASE, &[set, "rail.half_width=0.05"]);
        assert_eq!(e.len(), 1, "--set {set}: expected one error, got {e:?}");
        assert!(e[0].contains(expected), "--set {set}:\n  got      {}\n  expected {expected}", e[0]);
    }
}

#[test]
fn fixed_grid_keys() {
    let exact = "contact.model=exact-transient";
    // The step follows the element (the config's step_length sets dx) ...
    let r = load_str(BASE, "base", &[exact.into(), "contact.grid=fixed".into()]).unwrap();
    let Some(f) = r.scene.contact.model.fixed_grid() else { panic!("fixed grid") };
    assert_eq!((f.dx, r.scene.step_length), (2e-4, 2e-4));
    assert!(r.toml.contains("dx = 0.0002") && r.toml.contains("friction_law = \"regularised\""), "{}", r.toml);
    let again = load_str(&r.toml, "resolved", &[]).unwrap();
    assert_eq!(again.scene, r.scene, "the resolved config reproduces the scene");
    // ... and the element the step without step_length.
    let no_step = BASE.replace("step_length = 2e-4              # m, V dt\n", "");
    let r =
        load_str(&no_step, "no step", &[exact.into(), "contact.grid=fixed".into(), "contact.dx=3e-4".into()]).unwrap();
    assert_eq!(r.scene.step_length, 3e-4);
    // The fixed grid's keys on the adapted mesh are checked and unused (a
    // fixed-grid config switches back with --set contact.grid=adapted).
    let r = load_str(BASE, "base", &[exact.into(), "contact.dx=4e-4".into()]).unwrap();
    assert_eq!((r.scene.contact.model.fixed_grid(), r.scene.step_length), (None, 2e-4));
    // (overrides, expected fragment of the single error)
    let corpus: &[(&[&str], &str)] = &[
        (
            &["contact.grid=fixed"],
            "contact.grid: = \"fixed\" is a discretisation of the exact-transient model, not of contact.model = \"fastsim\"",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.dx=4e-4", "passage.step_length=2e-4"],
            "passage.step_length: = 0.0002 m must equal contact.dx = 0.0004 m",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.solver=newton"],
            "contact.solver: = \"newton\" is the adapted mesh's reference solver",
        ),
        (&[exact, "contact.dx=0"], "contact.dx: = 0 is out of range; expected a number in (0, 0.01]"),
        (
            &[exact, "contact.grid=fixed", "contact.friction_law=sliding"],
            "contact.friction_law: = \"sliding\" is not allowed; expected one of \"regularised\", \"coulomb\"",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.scheme=fourth-order"],
            "contact.scheme: = \"fourth-order\" is not allowed",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.dy=0"],
            "contact.dy: = 0 is out of range; expected a number in (0, 0.01]",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.dy=1e-5"],
            "contact.dy: = 0.0002 m x 0.00001 m gives a potential-contact grid of",
        ),
        (
            &[exact, "contact.normal=profile"],
            "contact.normal: = \"profile\" solves the discrete (nonlinear) normal problem on the rail profile, which \
             needs contact.grid = \"fixed\"; allowed with contact.grid = \"adapted\": auto, linear, hertz",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.normal=elastic"],
            "contact.normal: = \"elastic\" is not allowed; expected one of \"auto\", \"linear\", \"profile\", \"hertz\"",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.normal=auto", "contact.profile_from=5e-6"],
            "contact.profile_from: unknown key",
        ),
        (
            &[exact, "contact.grid=fixed", "contact.normal=profile", "contact.profile_grid_scale=0.5"],
            "contact.profile_grid_scale: = 0.5 is out of range; expected a number in [1, 4]",
        ),
        (
            &[exact, "contact.grid=square"],
            "contact.grid: = \"square\" is not allowed; expected one of \"adapted\", \"fixed\"",
        ),
    ];
    for (set, expected) in corpus {
        let e = errors(BASE, set);
        assert_eq!(e.len(), 1, "--set {set:?}: expected one error, got {e:?}");
        assert!(e[0].contains(expected), "--set {set:?}:\n  got      {}\n  expected {expected}", e[0]);
    }
}

#[test]
fn fixed_grid_steps_divide_a_growth_stretch() {
    let growth = include_str!("../configs/growth_exact.toml");
    let set =
        |dx: &str| ["contact.grid=fixed".to_string(), format!("contact.dx={dx}"), format!("passage.step_length={dx}")];
    assert_eq!(errors(growth, &set("3e-4").each_ref().map(String::as_str)), Vec::<String>::new());
    let e = errors(growth, &set("2.8e-4").each_ref().map(String::as_str));
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].contains("contact.dx: = 0.00028 m must divide the periodic stretch rail.x_max - rail.x_min = 0.12 m"),
        "{e:?}"
    );
}

#[test]
fn a_string_key_takes_a_bare_word_in_every_config() {
    // 54E1 is also a TOML float (540.0): the key's default says it is text,
    // in a single-passage config without [track] as in a growth study.
    for base in [BASE, include_str!("../configs/growth_discrete.toml")] {
        let r = load_str(base, "base", &["track.rail=54E1".into()]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(r.scene.track.rail_name, "54E1");
    }
    let e = errors(BASE, &["track.rail=60E1"]);
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].starts_with("track.rail: = \"60E1\" is not allowed"), "{e:?}");
}

#[test]
fn either_step_key_set_alone_sets_both_on_the_fixed_grid() {
    // paper_normal_30mm gives passage.step_length, growth_exact contact.dx;
    // one override of the other key moves both (docs/src/reference/configuration.md); two
    // that differ are refused, and an invalid one leaves the file's key.
    let fixed = ["contact.model=exact-transient", "contact.grid=fixed"].map(String::from);
    let growth = include_str!("../configs/growth_exact.toml");
    for (config, key) in [(BASE, "contact.dx"), (growth, "passage.step_length")] {
        let mut set = fixed.to_vec();
        set.push(format!("{key}=2.5e-4"));
        let r = load_str(config, "base", &set).unwrap_or_else(|e| panic!("{key}: {e}"));
        assert_eq!(r.scene.step_length, 2.5e-4, "{key}");
        assert!(r.scene.contact.model.fixed_grid().is_some_and(|f| f.dx == 2.5e-4), "{key}");
    }
    let mut set = fixed.to_vec();
    set.push("contact.dx=0.5".into());
    let e = load_str(BASE, "base", &set).unwrap_err().to_string();
    assert!(e.contains("contact.dx: = 0.5 is out of range") && !e.contains("passage.step_length"), "{e}");
    let mut set = fixed.to_vec();
    set.extend(["contact.dx=2.5e-4".to_string(), "passage.step_length=3e-4".to_string()]);
    let e = load_str(BASE, "base", &set).unwrap_err().to_string();
    assert!(e.contains("passage.step_length: = 0.0003 m must equal contact.dx = 0.00025 m"), "{e}");
    // On the adapted mesh contact.dx is unused and the step stays the file's.
    let r = load_str(BASE, "base", &["contact.dx=2.5e-4".to_string()]).unwrap();
    assert_eq!(r.scene.step_length, 2e-4);
}

#[test]
fn each_choice_is_one_typed_value() {
    use corrugation::contact::PressureShape;
    use corrugation::contact::friction::FrictionLaw;
    use corrugation::contact::grid::{GridScheme, GridSolver};
    use corrugation::contact::transient::StepSolver;
    use corrugation::params::{ContactGrid, ContactModel, Mesh};
    let scene =
        |set: &[&str]| load_str(BASE, "base", &set.iter().map(|s| s.to_string()).collect::<Vec<_>>()).unwrap().scene;
    let mesh = Mesh { nx: 12, ny: 14 };
    let m = ["contact.elements_x=12", "contact.elements_y=14"];
    assert_eq!(
        scene(&[&m[..], &["contact.fastsim_bound=elliptic"]].concat()).contact.model,
        ContactModel::Fastsim { mesh, bound: PressureShape::Hertz }
    );
    assert_eq!(
        scene(&[&m[..], &["contact.model=simplified-transient"]].concat()).contact.model,
        ContactModel::SimplifiedTransient { mesh, bound: PressureShape::Parabolic }
    );
    assert_eq!(
        scene(&[&m[..], &["contact.model=exact-transient", "contact.solver=newton"]].concat()).contact.model,
        ContactModel::ExactTransient(ContactGrid::Adapted { mesh, solver: StepSolver::Newton })
    );
    // The adapted mesh takes Gauss-Seidel for the fixed grid's solver names.
    assert_eq!(
        scene(&[&m[..], &["contact.model=exact-transient", "contact.solver=cg"]].concat()).contact.model,
        ContactModel::ExactTransient(ContactGrid::Adapted { mesh, solver: StepSolver::GaussSeidel })
    );
    let fixed = scene(&[
        "contact.model=exact-transient",
        "contact.grid=fixed",
        "contact.friction_law=coulomb",
        "contact.scheme=third-order",
        "contact.solver=gauss-seidel",
    ]);
    let f = fixed.contact.model.fixed_grid().expect("a fixed grid");
    assert_eq!(
        (f.friction_law, f.scheme, f.solver),
        (FrictionLaw::Coulomb, GridScheme::ThirdOrder, GridSolver::GaussSeidel)
    );
    assert_eq!(fixed.contact.model.mesh(), None);
}

#[test]
fn whole_numbers_written_as_floats_are_integers() {
    let r = load_str(BASE, "base", &["contact.elements_x=1e1".into(), "wear.substeps=4.0".into()]).unwrap();
    assert_eq!(r.scene.contact.model.mesh().map(|m| m.nx), Some(10));
    assert_eq!(r.scene.wear_substeps, 4);
    assert!(r.toml.contains("elements_x = 10\n"), "{}", r.toml);
    let e = errors(BASE, &["contact.elements_x=1e3"]);
    assert_eq!(e, vec!["contact.elements_x: = 1000 is out of range; expected an integer in [2, 200]".to_string()]);
    let e = errors(BASE, &["contact.elements_x=1e30"]);
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].starts_with("contact.elements_x: expected an integer in [2, 200], found float"), "{e:?}");
}

#[test]
fn missing_keys_and_syntax() {
    let e = errors(&BASE.replace("young_modulus = 2.1e11          # Pa\n", ""), &[]);
    assert_eq!(
        e,
        vec![
            "material.young_modulus: missing; expected a finite number > 0 in Pa (or a string with its unit, e.g. \"210GPa\")"
                .to_string()
        ]
    );
    let e = errors("[material\nx = 1", &[]);
    assert!(e[0].starts_with("TOML syntax:"), "{e:?}");
    // The parser's picture of the line keeps its line breaks.
    let e = errors("a = [1,\nb = 2\n", &[]);
    assert!(e[0].contains("line 2, column 3\n") && e[0].contains("| b = 2\n"), "{e:?}");
    let e = errors(BASE, &["rail.half_width=0.005"]);
    assert_eq!(
        e,
        vec![
            "rail.half_width: = 0.005 m is narrower than the largest patch half-width b = 1.1563e-2 m (at N = 1.450000e5 N); it must be >= b"
                .to_string()
        ]
    );
    let e = errors(BASE, &["friction=0.3"]);
    assert!(e[0].contains("--set friction=0.3: the key must be a dotted path"), "{e:?}");
}

#[test]
fn all_problems_reported_at_once() {
    let e = errors(BASE, &["material.friction_coefficient=2", "contact.elements_x=0", "rail.dy=-1", "wear.colour=1"]);
    assert_eq!(e.len(), 4, "{e:?}");
    for key in ["material.friction_coefficient", "contact.elements_x", "rail.dy", "wear.colour"] {
        assert!(e.iter().any(|m| m.starts_with(key)), "{key} missing in {e:?}");
    }
}

#[test]
fn resolved_config_round_trips() {
    let r = load_str(BASE, "base", &["contact.elements_x=12".into()]).unwrap();
    let again = load_str(&r.toml, "resolved", &[]).unwrap();
    assert_eq!(again.scene, r.scene);
    assert_eq!(r.scene.contact.model.mesh().map(|m| m.nx), Some(12));
    assert!(r.toml.contains("substeps = 4"), "defaults are written out");
}

/// The value at dotted `key` (with `[0]` indices) of a TOML text.
fn value_at(toml_text: &str, key: &str) -> Option<f64> {
    let root: toml::Table = toml_text.parse().ok()?;
    let mut v = toml::Value::Table(root);
    for part in key.split('.') {
        v = match part.split_once('[') {
            Some((name, index)) => v.get(name)?.get(index.trim_end_matches(']').parse::<usize>().ok()?)?.clone(),
            None => v.get(part)?.clone(),
        };
    }
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// Any numeric override either validates, and the resolved config holds
    /// it, or is rejected with an error naming the overridden key's section
    /// (or one it constrains); never a panic. Values every key refuses (not
    /// finite, or <= 0 for a key that must be positive) are always rejected.
    #[test]
    fn numeric_overrides_are_applied_or_refused_by_name(key in prop::sample::select(vec![
        "material.young_modulus", "material.poisson_ratio", "material.friction_coefficient",
        "geometry.wheel_radius", "geometry.wheel_profile_radius", "geometry.rail_head_radius",
        "rolling.speed", "load.normal_force", "load.longitudinal_force", "load.harmonics[0].amplitude",
        "load.harmonics[0].wavelength", "passage.step_length", "rail.dx", "rail.half_width", "wear.k_over_h",
    ]), value in prop_oneof![any::<f64>(), -1e6..1e6f64, -1.0..1.0f64]) {
        let set = format!("{key}={value:e}").replace("NaN", "nan");
        let e = errors(BASE, &[&set]);
        let section = key.split('.').next().unwrap();
        for m in &e {
            prop_assert!(m.starts_with(section) || m.starts_with("load") || m.starts_with("geometry") || m.starts_with("rail"), "{set}: {m}");
        }
        // Signed keys: the longitudinal force (braking or traction), the
        // wheel profile radius (negative concave). Radii may be infinite
        // (flat), the rail head's only where the wheel's curvature leaves
        // B > 0 (not with this config's concave wheel).
        let signed = ["load.longitudinal_force", "geometry.wheel_profile_radius"];
        let refused_by_every_key = value.is_nan() || (value.is_infinite() && key != "geometry.wheel_profile_radius");
        // k/H = 0 is a run without wear; nu = 0 a valid material; a zero
        // harmonic amplitude no harmonic.
        let nonnegative = ["wear.k_over_h", "material.poisson_ratio", "load.harmonics[0].amplitude"];
        let positive = !signed.contains(&key) && !nonnegative.contains(&key);
        if refused_by_every_key || (positive && value <= 0.0) || (nonnegative.contains(&key) && value < 0.0) {
            prop_assert!(!e.is_empty(), "{set} was accepted");
        }
        if e.is_empty() {
            let r = load_str(BASE, "base", std::slice::from_ref(&set)).unwrap();
            prop_assert_eq!(value_at(&r.toml, key), Some(value), "{} not in the resolved config", set);
        }
    }
}

/// The friction characteristic's keys: defaults (Polach's dry rail), the
/// modifier's required keys, and the levels' order against the
/// coefficient at zero slip.
#[test]
fn friction_characteristic_keys() {
    use corrugation::contact::friction::Characteristic;
    let set = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let scene = load_str(BASE, "t", &set(&["material.friction_characteristic=exponential"])).unwrap().scene;
    let mu = scene.material.friction;
    assert_eq!(scene.material.characteristic, Characteristic::Exponential { ratio: 0.4 * mu / mu, speed: 1.0 / 0.6 });
    let e = errors(BASE, &["material.friction_characteristic=modifier"]);
    assert!(e.iter().any(|m| m.contains("material.kinetic_friction") && m.contains("missing")), "{e:?}");
    assert!(e.iter().any(|m| m.contains("material.friction_speed") && m.contains("missing")), "{e:?}");
    let e = errors(BASE, &["material.friction_characteristic=rational", "material.kinetic_friction=0.9"]);
    assert!(e.iter().any(|m| m.contains("material.kinetic_friction") && m.contains("must not exceed")), "{e:?}");
    let e = errors(
        BASE,
        &["material.friction_characteristic=modifier", "material.kinetic_friction=0.1", "material.friction_speed=0.5"],
    );
    assert!(e.iter().any(|m| m.contains("material.kinetic_friction") && m.contains("must exceed")), "{e:?}");
    let e = errors(BASE, &["material.friction_characteristic=exponential", "material.friction_speed=0"]);
    assert!(e.iter().any(|m| m.contains("material.friction_speed") && m.contains("(0, 100]")), "{e:?}");
    // Constant: the other keys checked, kept, unused.
    let scene = load_str(BASE, "t", &set(&["material.kinetic_friction=0.2"])).unwrap().scene;
    assert_eq!(scene.material.characteristic, Characteristic::Constant);
}

/// Friction memory: CONTACT's defaults where the coefficient varies, none
/// under the constant law (its keys checked and unused) or at distance 0;
/// the keys' ranges.
#[test]
fn friction_memory_keys() {
    use corrugation::contact::friction::FrictionMemory;
    let set = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let memory = |s: &[&str]| load_str(BASE, "t", &set(s)).unwrap().scene.material.memory;
    assert_eq!(memory(&["material.friction_characteristic=exponential"]), Some(FrictionMemory::CONTACT));
    assert_eq!(
        memory(&[
            "material.friction_characteristic=rational",
            "material.friction_memory=1e-4",
            "material.memory_speed=0.05"
        ]),
        Some(FrictionMemory { distance: 1e-4, floor: 0.05 })
    );
    assert_eq!(memory(&["material.friction_characteristic=exponential", "material.friction_memory=0"]), None);
    assert_eq!(memory(&["material.friction_memory=1e-4"]), None);
    let e = errors(BASE, &["material.friction_characteristic=exponential", "material.friction_memory=0.01"]);
    assert!(e.iter().any(|m| m.contains("material.friction_memory") && m.contains("[0, 0.001]")), "{e:?}");
    let e = errors(BASE, &["material.memory_speed=0"]);
    assert!(e.iter().any(|m| m.contains("material.memory_speed") && m.contains("(0, 10]")), "{e:?}");
}

#[test]
fn spectrum_keys_are_checked_and_need_a_growth_study() {
    const GROWTH: &str = include_str!("../configs/growth_exact.toml");
    let one = |set: &[&str]| {
        let e = errors(GROWTH, set);
        assert_eq!(e.len(), 1, "{set:?}: {e:?}");
        e[0].clone()
    };
    let e = one(&["spectrum.classes=0"]);
    assert!(e.starts_with("spectrum.classes: "), "{e}");
    let e = one(&["spectrum.classes=2", "spectrum.resolution=0.005"]);
    assert!(e.contains("spectrum.resolution: and spectrum.classes both set the Bloch classes"), "{e}");
    let e = one(&["spectrum.wavelength_min=0.05", "spectrum.wavelength_max=0.02"]);
    assert!(e.contains("spectrum.wavelength_max: = 0.02 m must be > spectrum.wavelength_min = 0.05 m"), "{e}");
    // 150 mm at 0.1 mm on the 120 mm stretch: 1875 classes.
    let e = one(&["spectrum.resolution=1e-4"]);
    assert!(e.contains("needs 1875 Bloch classes") && e.contains("at most 256"), "{e}");
    let e = one(&["spectrum.perturbation=1e-3"]);
    assert!(
        e.contains("spectrum.perturbation: = 0.001 is out of range; expected a number in [0.0000000001, 0.00001]"),
        "{e}"
    );
    let e = one(&["spectrum.difference=backward"]);
    assert!(e.contains("spectrum.difference: = \"backward\" is not allowed"), "{e}");
    let e = one(&["spectrum.bas=smooth"]);
    assert!(e.contains("spectrum.bas") && e.contains("base"), "{e}");
    // A resolution gives the classes: 150 mm at 5 mm on 120 mm is 37.5, 38.
    let r = load_str(GROWTH, "g", &["spectrum.resolution=0.005".to_string()]).unwrap();
    assert_eq!(r.scene.spectrum.unwrap().classes, 38);
    // Without a growth study the section is refused.
    let e = errors(BASE, &["spectrum.classes=2"]);
    assert!(e.iter().any(|m| m.contains("spectrum: is only allowed with a [growth] section")), "{e:?}");
}
