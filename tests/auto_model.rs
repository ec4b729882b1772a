//! contact.model = "auto" on the paper scenes: the choice is the cheapest
//! the map predicts within the tolerance, never slower than the exact model
//! at the mesh it would otherwise need, and the chosen model's wear meets the
//! tolerance against the converged exact reference (tests/data, Richardson
//! extrapolation of exact 14, 20 and 28 with the observed order).
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::model_choice::{AccuracyMap, SAFETY};
use corrugation::params::{ContactModelKind, Scene};
use corrugation::passage::run_passage;

const SCENES: [(&str, &str, &str); 2] = [
    (
        "paper_normal_15mm",
        include_str!("../configs/paper_normal_15mm.toml"),
        include_str!("data/paper_normal_15mm_reference_wear.csv"),
    ),
    (
        "paper_normal_30mm",
        include_str!("../configs/paper_normal_30mm.toml"),
        include_str!("data/paper_normal_30mm_reference_wear.csv"),
    ),
];

/// The scene with its mesh keys removed and `model = "auto"`.
fn auto_scene(config: &str, tolerance: f64) -> Result<Scene, String> {
    let text: String =
        config.lines().filter(|l| !l.trim_start().starts_with("elements_")).collect::<Vec<_>>().join("\n");
    let set = ["contact.model=auto".to_string(), format!("contact.tolerance={tolerance}")];
    load_str(&text, "auto", &set).map(|r| r.scene).map_err(|e| e.to_string())
}

fn reference(csv: &str) -> Vec<f64> {
    csv.lines().filter(|l| !l.starts_with('#')).skip(1).map(|l| l.split(',').nth(1).unwrap().parse().unwrap()).collect()
}

/// Relative L2 error of the centre-line wear of one passage of `scene`.
fn wear_error(scene: &Scene, reference: &[f64]) -> f64 {
    let d = derive(scene);
    let mut solver = build_solver(scene, &d.shape);
    let dep = build_deposit(&solver.elements());
    let res = run_passage(&d.passage, &d.shape, solver.as_mut(), dep.as_ref(), &d.grid, false, &mut |_, _| {}).unwrap();
    let centre = d.grid.ny / 2;
    assert!(d.grid.y(centre).abs() < 1e-12, "the grid has a centre line");
    let w = res.wear.row(centre);
    assert_eq!(w.len(), reference.len());
    let diff: f64 = w.iter().zip(reference).map(|(a, b)| (a - b).powi(2)).sum();
    (diff / reference.iter().map(|b| b * b).sum::<f64>()).sqrt()
}

#[test]
fn the_choice_is_the_cheapest_within_the_tolerance_and_never_slower_than_exact() {
    for (name, config, _) in SCENES {
        for tolerance in [0.17, 0.2, 0.25, 0.3, 0.4, 0.5, 0.8] {
            let scene = auto_scene(config, tolerance).unwrap_or_else(|e| panic!("{name} {tolerance}: {e}"));
            let a = scene.contact.auto.expect("auto");
            assert_eq!(scene.contact.model.kind(), a.chosen.model);
            match a.chosen.grid_dx() {
                Some(dx) => {
                    let Some(f) = scene.contact.model.fixed_grid() else { panic!("fixed grid") };
                    assert_eq!((f.dx, scene.step_length), (dx, dx));
                }
                None => {
                    assert_eq!(scene.contact.model.mesh().map(|m| (m.nx, m.ny)), Some((a.chosen.mesh, a.chosen.mesh)))
                }
            }
            assert!(a.chosen.wear_error <= SAFETY * tolerance, "{name} {tolerance}");
            let exact = a.exact.expect("exact-transient meets every tolerance the map allows here");
            assert!(a.chosen.cpu_per_step <= exact.cpu_per_step, "{name} {tolerance}: slower than exact");
            // Nothing cheaper in the map meets it.
            for c in AccuracyMap::builtin().candidates(a.lambda_over_2a) {
                if c.cpu_per_step < a.chosen.cpu_per_step {
                    assert!(c.wear_error > SAFETY * tolerance, "{name} {tolerance}: {c:?} is cheaper and meets it");
                }
            }
        }
    }
}

#[test]
fn the_chosen_model_meets_the_tolerance_against_the_reference() {
    // Whatever the map picks must meet the tolerance; across these cases it
    // picks both the exact model (the fixed grid at 0.4 mm: since its
    // symmetric products the cheapest model of all at 30-60 mm, and up to
    // tolerances of 0.59 at 15 mm) and the simplified model (15 mm at 0.62:
    // 10 x 10).
    let cases = [(0, 0.4), (0, 0.23), (0, 0.62), (1, 0.45), (1, 0.2)];
    let mut models = Vec::new();
    for (i, tolerance) in cases {
        let (name, config, csv) = SCENES[i];
        let scene = auto_scene(config, tolerance).unwrap();
        let a = scene.contact.auto.unwrap();
        let error = wear_error(&scene, &reference(csv));
        let model = scene.contact.model.kind();
        eprintln!("{name} tolerance {tolerance}: {}, wear error {error:.4}", a.chosen.label());
        assert!(error <= tolerance, "{name}: {error} > {tolerance}");
        // The prediction is the map's measurement of the same scene family.
        assert!((error - a.chosen.wear_error).abs() < 0.25 * a.chosen.wear_error, "{name}: {error} vs {a:?}");
        models.push(model);
    }
    assert!(models.contains(&ContactModelKind::ExactTransient), "{models:?}");
    assert!(models.contains(&ContactModelKind::SimplifiedTransient), "{models:?}");
}

#[test]
fn auto_refuses_what_it_cannot_promise() {
    let (_, config, _) = SCENES[0];
    // Below the most accurate entry (the fixed grid at 0.14 mm, 0.017 at 15 mm).
    let e = auto_scene(config, 0.01).unwrap_err();
    assert!(e.contains("contact.tolerance") && e.contains("allowed here"), "{e}");
    // A wavelength shorter than the map: 5 mm over 2a_max = 13.5 mm.
    let short = config.replace("wavelength = 0.015", "wavelength = 0.005");
    let e = auto_scene(&short, 0.3).unwrap_err();
    assert!(e.contains("contact.model") && e.contains("below the measured map"), "{e}");
    // Mesh keys and a tolerance without auto.
    let set = ["contact.model=auto".to_string()];
    let e = load_str(config, "x", &set).unwrap_err().to_string();
    assert!(e.contains("contact.elements_x: is chosen by contact.model = \"auto\""), "{e}");
    let e = load_str(config, "x", &["contact.tolerance=0.2".to_string()]).unwrap_err().to_string();
    assert!(e.contains("contact.tolerance: applies to contact.model = \"auto\" only"), "{e}");
}

#[test]
fn auto_in_a_growth_study_fits_the_stretch_and_takes_the_consistent_chain() {
    // growth_exact.toml's study (10-120 mm roughness on 120 mm, receptance
    // dynamics) with the model chosen: a fixed grid whose element divides
    // the stretch (the map's 0.28 mm is not a divisor of 120 mm), and the
    // consistent chain's normal contact.
    let set = ["contact.model=auto", "contact.tolerance=0.02", "contact.grid=adapted", "passage.step_length=2e-4"];
    let r = corrugation::config::load_str(
        include_str!("../configs/growth_exact.toml"),
        "growth_exact",
        &set.map(String::from),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let Some(f) = r.scene.contact.model.fixed_grid() else { panic!("a fixed grid") };
    let steps = 0.12 / f.dx;
    assert!((steps - steps.round()).abs() < 1e-6 && f.dx <= 2.8e-4, "element {}", f.dx);
    // The consistent chain: the nonlinear profile contact on a grid 1.5
    // times the largest Hertz patch.
    assert_eq!(r.scene.contact.normal, corrugation::params::NormalContact::Auto { grid_scale: 1.5 });
    assert!(r.scene.contact.auto.and_then(|a| a.hertz_difference).is_some_and(|d| d > 0.05));
}
