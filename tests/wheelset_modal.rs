//! `[wheelset] model = "modal"`: the keys, their defaults and ranges, a
//! user's modal table beside the config, its errors with file and line, the
//! torsional model's resolved config unchanged, and `check` naming the
//! modes.
use corrugation::build::wheelset_model;
use corrugation::config::{load_file, load_str};
use corrugation::dynamics::wheelset::{Dir, dof};
use std::f64::consts::PI;

/// growth_fastsim.toml under creepage control with `[wheelset]` + `extra`.
fn config(extra: &str) -> String {
    let text: String = include_str!("../configs/growth_fastsim.toml")
        .lines()
        .filter(|l| !l.starts_with("longitudinal_force"))
        .map(|l| match l {
            l if l.starts_with("[load]") => "[load]\ncontrol = \"creepage\"".to_string(),
            l if l.starts_with("[rolling]") => "[rolling]\ncreepage_x = -1.3e-3".to_string(),
            l => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    format!("{text}\n[wheelset]\n{extra}\n")
}

fn errors(text: &str) -> Vec<String> {
    match load_str(text, "t", &[]) {
        Ok(_) => Vec::new(),
        Err(e) => e.errors.iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn a_bare_section_takes_the_automatic_wheelset_and_records_it() {
    // [wheelset] without `model`: `auto`, recorded in the resolved config
    // (a stored section without it was written before `auto`, when it
    // meant the torsional mode: tests/resume.rs), here the modal wheelset
    // of a track in every direction; `model = "torsion"` keeps the
    // torsion's three keys and its two modes.
    let r = load_str(&config(""), "t", &[]).unwrap();
    let section = r.toml.split("[wheelset]").nth(1).unwrap();
    assert!(section.contains("model = \"auto\""), "{section}");
    assert!(r.scene.wheelset.as_ref().unwrap().modal.is_some());
    assert!(r.scene.wheelset_choice.as_deref().is_some_and(|c| c.starts_with("modal")));
    let r = load_str(&config("model = \"torsion\""), "t", &[]).unwrap();
    let section = r.toml.split("[wheelset]").nth(1).unwrap();
    let keys: Vec<&str> = section.lines().filter_map(|l| l.split_once(" = ").map(|(k, _)| k)).collect();
    assert_eq!(keys, ["model", "polar_inertia", "torsional_loss_factor", "torsional_stiffness"], "{section}");
    let w = r.scene.wheelset.as_ref().unwrap();
    assert!(w.modal.is_none() && r.scene.wheelset_choice.is_none());
    let model = wheelset_model(&r.scene).unwrap();
    assert_eq!(model.modes().len(), 2);
    // The vertical dynamics under creepage control: auto takes the torsion;
    // under force control, or with imposed loads, the rigid wheel.
    let vertical = load_str(&config(""), "t", &["dynamics.directions=vertical".into()]).unwrap();
    assert!(vertical.scene.wheelset.as_ref().is_some_and(|w| w.modal.is_none()));
    let imposed = load_str(&config(""), "t", &["dynamics.model=imposed".into()]).unwrap();
    assert!(imposed.scene.wheelset.is_none());
    let rigid = load_str(&config("model = \"rigid\""), "t", &[]).unwrap();
    assert!(rigid.scene.wheelset.is_none());
    let e = errors(&config("model = \"rigid\"\ntorsional_stiffness = 1e6"));
    assert!(
        e.len() == 1 && e[0].starts_with("wheelset.torsional_stiffness: is a key of the wheelset's torsion"),
        "{e:?}"
    );
}

#[test]
fn the_modal_model_reads_its_keys_with_their_defaults() {
    let r = load_str(&config("model = \"modal\""), "t", &[]).unwrap();
    let m = r.scene.wheelset.as_ref().unwrap().modal.as_ref().unwrap();
    assert_eq!((m.mass, m.roll_inertia, m.yaw_inertia), (1200.0, 660.0, 660.0));
    assert_eq!(m.suspension_stiffness, [31.4e6, 3.88e6, 1.22e6]);
    assert!(r.toml.contains("model = \"modal\"") && r.toml.contains("modes = \"default\""));
    let model = wheelset_model(&r.scene).unwrap();
    // 6 rigid, torsion, 2 x 2 bending, 2 umbrella, 2 wheels x 4 pairs.
    assert_eq!(model.modes().len(), 29);
    // The rolling radius is the scene's: the spin's x participation is -r
    // times its rotation.
    let spin = model.modes().iter().find(|m| m.name.starts_with("rigid spin")).unwrap();
    let r0 = r.scene.geometry.wheel_radius;
    assert_eq!(spin.shape[dof(0, Dir::X)], -r0 * spin.shape[dof(0, Dir::Theta)]);
    // A key's value reaches its mode: k_z per box -> bounce sqrt(2 k_z / m).
    let r = load_str(&config("model = \"modal\"\nsuspension_stiffness_z = 2e6\nmass = 1500"), "t", &[]).unwrap();
    let model = wheelset_model(&r.scene).unwrap();
    let bounce = model.modes().iter().find(|m| m.name.starts_with("rigid bounce")).unwrap();
    assert!((bounce.frequency - (4e6f64 / 1500.0).sqrt() / (2.0 * PI)).abs() < 1e-12);
}

#[test]
fn modal_keys_are_checked_and_belong_to_the_modal_model() {
    let e = errors(&config("model = \"torsion\"\nmass = 1500"));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.mass: is a key of the modal model"), "{e:?}");
    let e = errors(&config("model = \"flexible\""));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.model") && e[0].contains("\"modal\""), "{e:?}");
    let e = errors(&config("model = \"modal\"\nsuspension_stiffness_y = 0"));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.suspension_stiffness_y") && e[0].contains("[10000"), "{e:?}");
    let e = errors(&config("model = \"modal\"\nwheel_damping = 0.7"));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.wheel_damping") && e[0].contains("(0, 0.5]"), "{e:?}");
    let e = errors(&config("model = \"modal\"\nspeed = 3"));
    assert!(e.len() == 1 && e[0].starts_with("wheelset.speed: unknown key"), "{e:?}");
}

const TABLE: &str = "# two modes of a wheelset's FE analysis\n\
    name,frequency,damping_ratio,x0,y0,z0,theta0,x1,y1,z1,theta1,partner,coefficient\n\
    bending v,80,0.01,0,0.07,-0.004,0,0,-0.07,-0.004,0,bending h,1.1\n\
    bending h,81,0.01,-0.004,0,0,0,-0.004,0,0,0,,\n";

#[test]
fn a_table_beside_the_config_gives_the_flexible_modes() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("modes.csv"), TABLE).unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, config("model = \"modal\"\nmodes = \"modes.csv\"")).unwrap();
    let r = load_file(&path, &[]).unwrap();
    let absolute = std::fs::canonicalize(dir.path().join("modes.csv")).unwrap();
    assert!(r.toml.contains(&format!("modes = \"{}\"", absolute.display())), "{}", r.toml);
    let model = wheelset_model(&r.scene).unwrap();
    assert_eq!(model.modes().len(), 8);
    assert_eq!(model.modes()[6].name, "bending v");
    // The resolved config reads again (resume) from anywhere.
    let again = load_str(&r.toml, "stored", &[]).unwrap();
    assert_eq!(again.scene.wheelset, r.scene.wheelset);
    // Spinning, the table's coupling splits its pair.
    let at_rest = model.frequencies(0.0);
    let spinning = model.frequencies(100.0);
    assert!(at_rest.iter().any(|f| (f - 80.0).abs() < 1e-6) && !spinning.iter().any(|f| (f - 80.0).abs() < 0.1));
}

#[test]
fn a_bad_table_is_an_error_naming_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad = TABLE.replace("bending h,81", "bending h,-81");
    std::fs::write(dir.path().join("modes.csv"), bad).unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, config("model = \"modal\"\nmodes = \"modes.csv\"\nwheel_damping = 0.01")).unwrap();
    let e = load_file(&path, &[]).unwrap_err().errors;
    let e: Vec<String> = e.iter().map(|e| e.to_string()).collect();
    let file = std::fs::canonicalize(dir.path().join("modes.csv")).unwrap();
    assert_eq!(e.len(), 2, "{e:?}");
    assert!(e[0].starts_with("wheelset.wheel_damping: sets the default modes' damping"), "{e:?}");
    assert!(e[1].starts_with(&format!("wheelset.modes: {}: line 4: frequency = -81 Hz", file.display())), "{e:?}");
    std::fs::write(&path, config("model = \"modal\"\nmodes = \"missing.csv\"")).unwrap();
    let e = load_file(&path, &[]).unwrap_err().errors;
    assert!(e.len() == 1 && e[0].to_string().starts_with("wheelset.modes: cannot read the modal table"), "{e:?}");
    assert!(e[0].to_string().contains("missing.csv"), "{e:?}");
}

#[test]
fn check_names_the_modes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, config("model = \"modal\"")).unwrap();
    let bin = env!("CARGO_BIN_EXE_corrugation");
    let o = std::process::Command::new(bin).arg("check").arg(&path).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    eprintln!("{out}");
    assert!(out.contains("modal model: 29 modes (the default freight wheelset"), "{out}");
    assert!(out.contains("mode 7: first symmetric bending (vertical plane), 87.0 Hz, 1 % damping"), "{out}");
    assert!(out.contains("mode 6: torsion, 71.2 Hz, loss factor 0.02"), "{out}");
}
