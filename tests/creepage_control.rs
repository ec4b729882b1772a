//! Creepage control (`load.control = "creepage"`, `rolling.creepage_x`):
//! for every tangential model, a constant prescribed creepage reproduces
//! the steady state that force control reaches at the resulting force;
//! and the keys' bad combinations are refused.
use corrugation::build::{build_deposit, build_solver, derive};
use corrugation::config::load_str;
use corrugation::passage::{PatchHistory, run_passage};

const STEADY: &str = include_str!("../configs/paper_steady.toml");

/// paper_steady.toml without its longitudinal force (for creepage control).
fn no_force() -> String {
    STEADY.lines().filter(|l| !l.starts_with("longitudinal_force")).collect::<Vec<_>>().join("\n")
}

/// The history of one passage of `text` (paper_steady.toml: constant N =
/// 100 kN; 80 mm rolled) with `set`.
fn passage(text: &str, set: &[String]) -> PatchHistory {
    let mut all = vec!["passage.end=0.08".to_string(), "rail.x_max=0.072".into(), "output.store_fields=false".into()];
    all.extend(set.iter().cloned());
    let scene = load_str(text, "steady", &all).unwrap_or_else(|e| panic!("{set:?}: {e}")).scene;
    let d = derive(&scene);
    let mut solver = build_solver(&scene, &d.shape);
    let deposit = build_deposit(&solver.elements());
    run_passage(&d.passage, &d.shape, solver.as_mut(), deposit.as_ref(), &d.grid, false, &mut |_, _| {})
        .unwrap()
        .history
}

#[test]
fn a_prescribed_creepage_reproduces_force_controls_steady_state() {
    // Force control with F_x = 20 kN finds the creepage xi*; creepage
    // control at xi* must transmit F_x at the end of the passage (80 mm
    // rolled, 6.7 patch lengths 2a), the same steady state reached from
    // the other side of the transient: the force within 1e-4 of mu N,
    // model by model. From rest at a prescribed creepage the simplified
    // theory's force settles after rolling 2a (within 2e-8 of mu N at 20
    // mm); the exact theory's approaches its steady value exponentially
    // over about 0.7 x 2a (8.6 mm on the adapted mesh, 7.8 mm on the fixed
    // grid: 1.5e-2 / 1.1e-2 of mu N short at 30 mm, 4.5e-5 / 1.8e-5 at 80
    // mm), the elastic memory of the surface outside the patch, which the
    // force-controlled creepage settles through in about 2a.
    let models: [(&str, &[&str]); 6] = [
        ("fastsim", &["contact.model=fastsim"]),
        ("simplified", &["contact.model=simplified-transient"]),
        ("exact newton", &["contact.model=exact-transient", "contact.elements_x=12", "contact.elements_y=12"]),
        (
            "exact gauss-seidel",
            &[
                "contact.model=exact-transient",
                "contact.elements_x=12",
                "contact.elements_y=12",
                "contact.solver=gauss-seidel",
            ],
        ),
        ("fixed cg", &["contact.model=exact-transient", "contact.grid=fixed", "contact.dx=4e-4", "contact.dy=1e-3"]),
        (
            "fixed gauss-seidel",
            &[
                "contact.model=exact-transient",
                "contact.grid=fixed",
                "contact.dx=4e-4",
                "contact.dy=1e-3",
                "contact.solver=gauss-seidel",
            ],
        ),
    ];
    let mu_n = 0.4 * 1e5;
    for (name, set) in models {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let force = passage(STEADY, &set);
        let xi = *force.creepage_x.last().unwrap();
        let mut by_creepage = set.clone();
        by_creepage.extend(["load.control=\"creepage\"".to_string(), format!("rolling.creepage_x={xi:e}")]);
        let creepage = passage(&no_force(), &by_creepage);
        // The creepage stays where it is put; the force is the result.
        assert!(creepage.creepage_x.iter().all(|c| *c == xi), "{name}: creepage moved");
        let f = *creepage.longitudinal_force.last().unwrap();
        let f_force = *force.longitudinal_force.last().unwrap();
        eprintln!(
            "{name}: xi* = {xi:.6e}; creepage control's last force {f:.6e} N, force control's {f_force:.6e} N \
             (diff {:.2e} of mu N); first step {:.4e} N",
            (f - 2e4).abs() / mu_n,
            creepage.longitudinal_force[0]
        );
        assert!((f - 2e4).abs() < 1e-4 * mu_n, "{name}: {f} N against 2e4 N");
    }
}

#[test]
fn creepage_and_force_keys_follow_the_control() {
    let free = no_force();
    let errors =
        |text: &str, set: &[&str]| match load_str(text, "t", &set.iter().map(|s| s.to_string()).collect::<Vec<_>>()) {
            Ok(_) => Vec::new(),
            Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
        };
    let creepage = "load.control=creepage";
    for (text, set, key, expected) in [
        (STEADY, vec!["rolling.creepage_x=1e-3"], "rolling.creepage_x", "load.control = \"force\""),
        (
            STEADY,
            vec![creepage, "rolling.creepage_x=1e-3"],
            "load.longitudinal_force",
            "but load.control = \"creepage\"",
        ),
        (free.as_str(), vec![creepage], "rolling.creepage_x", "is required with load.control = \"creepage\""),
        (free.as_str(), vec![creepage, "rolling.creepage_x=0.2"], "rolling.creepage_x", "[-0.1, 0.1]"),
        (STEADY, vec!["load.control=torque"], "load.control", "force"),
        (
            free.as_str(),
            vec![
                creepage,
                "rolling.creepage_x=1e-3",
                "load.harmonics=[{quantity = \"longitudinal_force\", amplitude = 1e3, wavelength = 0.01}]",
            ],
            "load.harmonics[0].quantity",
            "but load.control = \"creepage\"",
        ),
    ] {
        let e = errors(text, &set);
        assert_eq!(e.len(), 1, "{set:?}: {e:?}");
        assert!(e[0].starts_with(key) && e[0].contains(expected), "{set:?}: {}", e[0]);
    }
}

#[test]
fn a_growth_study_under_creepage_control_resumes_bit_for_bit() {
    // growth_fastsim.toml at the creepage its 20 kN needs, 3 passages in
    // one run and 2 + 1 resumed.
    use corrugation::output::netcdf::read_f64;
    use corrugation::run::{resume, run_scene};
    let text: String = include_str!("../configs/growth_fastsim.toml")
        .lines()
        .filter(|l| !l.starts_with("longitudinal_force"))
        .collect::<Vec<_>>()
        .join("\n");
    let set = |passes: usize| -> Vec<String> {
        ["load.control=creepage", "rolling.creepage_x=-1.3e-3", "growth.contact_history=[]"]
            .iter()
            .map(|s| s.to_string())
            .chain([format!("growth.passes={passes}")])
            .collect()
    };
    let dir = tempfile::tempdir().unwrap();
    let (full, part) = (dir.path().join("full.h5"), dir.path().join("part.h5"));
    run_scene(&load_str(&text, "g", &set(3)).unwrap(), &full, &mut |_| {}).unwrap();
    run_scene(&load_str(&text, "g", &set(2)).unwrap(), &part, &mut |_| {}).unwrap();
    resume(&part, Some(1), None, &mut |_| {}).unwrap();
    for (g, v) in [("rail", "state"), ("passes", "rms_corrugation"), ("passes", "spectrum")] {
        let (a, b) = (read_f64(&full, g, v).unwrap(), read_f64(&part, g, v).unwrap());
        assert!(a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}/{v}");
    }
}

#[test]
fn a_growth_passage_under_creepage_control_wears_a_smooth_rail_evenly() {
    // The run-in lets the exact theory's force settle before the stretch
    // (build::CREEPAGE_RUN_IN): on a smooth rail with constant loads every
    // node of the periodic stretch sees the same steady patch, so the
    // centre line's wear is uniform. (With force control's 10 mm run-in the
    // force would still be 15 % of mu N short entering the stretch.)
    use corrugation::build::{build_deposit, build_solver, derive, study_grid};
    use corrugation::growth::growth_passage;
    let text: String = include_str!("../configs/growth_exact.toml")
        .lines()
        .filter(|l| !l.starts_with("longitudinal_force"))
        .collect::<Vec<_>>()
        .join("\n");
    let set: Vec<String> =
        ["load.control=creepage", "rolling.creepage_x=-1.26e-3", "dynamics.model=imposed", "contact.normal=hertz"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    let scene = load_str(&text, "g", &set).unwrap().scene;
    let d = derive(&scene);
    assert!(d.passage.start < scene.rail.x_min - 6.9 * 2.0 * d.patch_max.a, "run-in from {}", d.passage.start);
    let mut solver = build_solver(&scene, &d.shape);
    let deposit = build_deposit(&solver.elements());
    let grid = study_grid(&scene);
    let flat = ndarray::Array2::zeros((grid.ny, grid.nx));
    let g = growth_passage(
        &d.passage,
        &d.shape,
        solver.as_mut(),
        deposit.as_ref(),
        &grid,
        &flat,
        scene.contact.normal,
        None,
        false,
        &mut |_, _| {},
    )
    .unwrap();
    let line = g.rails[0].wear.row(grid.ny / 2).to_vec();
    let (lo, hi) = line.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    let force = g.rails[0].leading.history.longitudinal_force.last().unwrap();
    eprintln!("centre-line wear {lo:.6e} .. {hi:.6e} m; force {force:.6e} N");
    assert!(hi - lo < 1e-3 * hi, "{lo} .. {hi}");
}
