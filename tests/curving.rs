//! Curving: profiles, contact geometry, equivalent conicity and steady
//! curving against standards, benchmarks and closed forms.

use corrugation::curving::conicity::RadiusDifference;
use corrugation::curving::geometry::{Geometry, Side, TrackShape, WheelsetShape};
use corrugation::curving::profile::Profile;
use corrugation::curving::rigid::radius_difference;

/// S1002 on 60E1 at 1:`inclination`, gauge 1435 mm, flange backs 1360 mm,
/// wheels of 460 mm.
fn standard(inclination: f64) -> Geometry {
    let wheelset =
        WheelsetShape { wheels: [Profile::s1002(), Profile::s1002()], radius: [0.46; 2], flange_back: 1.360 };
    let rails = [Profile::rail_60e1(), Profile::rail_60e1()];
    let track = TrackShape { rails, gauge: 1.435, gauge_depth: 0.014, inclination: (1.0 / inclination).atan() };
    Geometry::new(wheelset, track).unwrap()
}

/// EN 15302's benchmark cases: (case, rolling-radius difference, rows of
/// amplitude, reference conicity, lower, upper).
type Case = (usize, RadiusDifference, Vec<[f64; 4]>);

fn en15302_cases() -> Vec<Case> {
    let text = include_str!("data/en15302_benchmark.txt");
    let mut cases: Vec<Case> = Vec::new();
    let mut grid = (0.0, 0.0);
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split_whitespace().collect();
        match f[0] {
            "case" => {
                grid = (f[2].parse().unwrap(), f[3].parse().unwrap());
                cases.push((f[1].parse().unwrap(), RadiusDifference { shift: vec![], difference: vec![] }, vec![]));
            }
            "dr" => {
                let d: Vec<f64> = f[1..].iter().map(|v| v.parse::<f64>().unwrap() * 1e-3).collect();
                let n = d.len();
                let shift = (0..n).map(|i| (grid.0 + (grid.1 - grid.0) * i as f64 / (n - 1) as f64) * 1e-3).collect();
                cases.last_mut().unwrap().1 = RadiusDifference { shift, difference: d };
            }
            _ => {
                let v: Vec<f64> = f.iter().map(|v| v.parse().unwrap()).collect();
                cases.last_mut().unwrap().2.push([v[0], v[1], v[2], v[3]]);
            }
        }
    }
    cases
}

/// EN 15302's benchmark: the equivalent conicity of its nine reference
/// rolling-radius differences within the standard's tolerance band
/// (+-min(0.05, 0.5 tan gamma_e)) at every tabulated amplitude, 1-7 mm.
#[test]
fn equivalent_conicity_meets_en15302_benchmark() {
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for (case, dr, rows) in en15302_cases() {
        for [amp, reference, lower, upper] in rows {
            let Some(g) = dr.equivalent_conicity(amp * 1e-3) else { continue };
            checked += 1;
            assert!(
                (lower - 1e-9..=upper + 1e-9).contains(&g),
                "E{case} at {amp} mm: {g:.4} outside [{lower}, {upper}] (reference {reference})"
            );
            worst = worst.max((g - reference).abs());
        }
    }
    assert!(checked > 9 * 50, "{checked} amplitudes checked");
    assert!(worst < 0.01, "largest deviation {worst}");
    eprintln!("EN 15302 benchmark: {checked} amplitudes, largest deviation from the reference {worst:.4}");
}

/// S1002 against the Manchester contact benchmark's profile points
/// (Shackleton and Iwnicki 2008; `MBench_S1002_v3.prw` of CONTACT's
/// examples, lateral mirrored, mm): every 25th point within 1e-5 mm.
#[test]
fn s1002_matches_the_benchmark_points() {
    let points = [
        (6.9612628E+01, 1.3485642E+01),
        (5.9928328E+01, 2.6941279E+01),
        (5.0244029E+01, 2.7017293E+01),
        (4.2039956E+01, 2.0110714E+01),
        (4.0747062E+01, 1.7932114E+01),
        (3.7814698E+01, 1.0585419E+01),
        (3.2254015E+01, 4.9261168E+00),
        (2.4940124E+01, 2.4962203E+00),
        (1.6226081E+01, 1.1019054E+00),
        (6.3226037E+00, 2.8229325E-01),
        (-4.4933683E+00, -1.2185443E-01),
        (-1.5540845E+01, -2.6044927E-01),
        (-2.5681054E+01, -4.4883835E-01),
        (-3.4549661E+01, -9.3898710E-01),
        (-4.3265530E+01, -1.5200451E+00),
        (-5.1981400E+01, -2.1011030E+00),
    ];
    let wheel = Profile::s1002();
    for (y, z) in points {
        let h = wheel.height(-y * 1e-3).unwrap() * 1e3;
        assert!((h - z).abs() < 1e-5, "at {y} mm: {h} against {z}");
    }
}

/// 60E1's head from its drawing: 72.000 mm wide where the R13 arc meets the
/// 1:20 flank, 14.30 mm below the crown; the crown at the axis.
#[test]
fn rail_60e1_has_its_drawing_dimensions() {
    let rail = Profile::rail_60e1();
    assert_eq!(rail.height(0.0), Some(0.0));
    let (u, z) = corrugation::curving::profile::rail60e1::flank_start();
    assert!((2.0 * u - 72.0).abs() < 1e-9);
    assert!((z + 14.30).abs() < 0.01, "flank starts {z} mm below the crown");
    // Symmetric head, falling away from the crown.
    for u in [5e-3, 15e-3, 30e-3] {
        assert_eq!(rail.height(u), rail.height(-u));
        assert!(rail.height(u).unwrap() < rail.height(u - 1e-3).unwrap());
    }
}

/// The contact points of the rigid search against a brute-force scan of the
/// gap every micrometre across each rail: no overlap anywhere, the minimum
/// where the search put it (within 5 um) and zero (within 1 nm), both
/// sides; at shifts on the tread, at the contact's jump and in flange contact.
#[test]
fn contact_points_are_the_brute_force_minimum() {
    let g = standard(40.0);
    for y in [0.0, 2e-3, 5e-3, 6.5e-3, 8e-3] {
        let c = g.rigid(y).unwrap();
        for side in Side::BOTH {
            let axis = g.rail_axis(side);
            let (mut best, mut at) = (f64::INFINITY, 0.0);
            for k in -40_000..=40_000 {
                let yy = axis + k as f64 * 1e-6;
                if let Some(gap) = g.gap(side, &c.pose, yy)
                    && gap < best
                {
                    (best, at) = (gap, yy);
                }
            }
            let found = c.contact[side as usize];
            assert!(best > -1e-9, "{} at {y}: overlap {best}", side.name());
            assert!(found.gap.abs() < 1e-9, "{} at {y}: gap {}", side.name(), found.gap);
            assert!((at - found.lateral).abs() < 5e-6, "{} at {y}: {at} against {}", side.name(), found.lateral);
        }
    }
}

/// The rigid contact geometry against CONTACT's solution of the Manchester
/// contact benchmark A-2.2 (S1002 on UIC60 1:40; elastic contact at 10 kN
/// and the wheelset yawed 2.4 mrad per mm, which the rigid, unyawed
/// geometry leaves out): the contact angle within 0.01 rad at 20 of the 21
/// shifts (0-10 mm), within 0.025 rad at the flange's first touch (6.5 mm);
/// the jump to the rail's gauge corner between 4.5 and 5 mm and flange
/// contact (angle > 1 rad) from 6.5 mm in both.
#[test]
fn rigid_geometry_meets_the_manchester_contact_benchmark() {
    let g = standard(40.0);
    let text = include_str!("data/manchester_contact_a22.txt");
    let mut worst: f64 = 0.0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = line.split_whitespace().map(|s| s.parse().unwrap()).collect();
        let (shift, reference) = (v[0], v[2]);
        let angle = g.rigid(shift * 1e-3).unwrap().contact_angles()[0];
        let bound = if shift == 6.5 { 0.025 } else { 0.01 };
        assert!((angle - reference).abs() < bound, "at {shift} mm: {angle:.4} against {reference}");
        assert_eq!(angle > 1.0, reference > 1.0, "flange contact at {shift} mm");
        assert_eq!(angle > 0.2, reference > 0.2, "gauge corner at {shift} mm");
        if shift != 6.5 {
            worst = worst.max((angle - reference).abs());
        }
    }
    eprintln!("Manchester A-2.2 contact angles: largest difference {worst:.4} rad off the flange's first touch");
}

/// S1002 on 60E1 1:40: the rolling-radius difference is odd in the shift (to 0.1
/// um), and its equivalent conicity at 3 mm (EN 15302's method) is
/// 0.177 (the value this geometry gives; see the book for the published
/// range).
#[test]
fn standard_pair_is_symmetric_with_its_conicity() {
    let g = standard(40.0);
    let shifts: Vec<f64> = (-100..=100).map(|i| i as f64 * 1e-4).collect();
    let table = g.rigid_table(&shifts).unwrap();
    for (i, c) in table.iter().enumerate() {
        let mirror = &table[table.len() - 1 - i];
        let odd = c.radius_difference() + mirror.radius_difference();
        assert!(odd.abs() < 1e-7, "at {}: {odd}", shifts[i]);
    }
    let conicity = radius_difference(&shifts, &table).equivalent_conicity(3e-3).unwrap();
    assert!((conicity - 0.177).abs() < 0.002, "{conicity}");
}

use corrugation::config::{load_file, load_str};
use corrugation::curving::vehicle::GRAVITY;
use corrugation::output::netcdf::{read_f64, read_i8};
use std::path::Path;

/// configs/curve_pure_rolling.toml: a free wheelset of 1:20 cones at R =
/// 3000 m and balanced cant runs in pure rolling: its lateral shift gives
/// the rolling-radius difference 2 b r0 / R within 1 % (b half the contact
/// points' spacing), the longitudinal creepages vanish (< 1e-6), and the
/// study's keys are the followed wheel's state bit for bit.
#[test]
fn pure_rolling_config_balances_the_curvature() {
    let r = load_file(Path::new("configs/curve_pure_rolling.toml"), &[]).unwrap();
    let setup = r.curve.as_ref().unwrap();
    let w = &setup.state.wheelsets[0];
    let (l, h) = (w.on(Side::Left), w.on(Side::Right));
    let dr = h.contact.rolling_radius - l.contact.rolling_radius;
    let b = 0.5 * (l.contact.lateral - h.contact.lateral);
    let expected = 2.0 * b * 0.46 / setup.curve.radius;
    assert!((dr / expected - 1.0).abs() < 0.01, "dr {dr:e} against 2 b r0 / R {expected:e}");
    for p in [l, h] {
        assert!(p.creepage.x.abs() < 1e-6, "creepage {:e}", p.creepage.x);
    }
    assert!(w.shift < 0.0, "the wheelset moves to the high rail: {}", w.shift);
    // The study runs on the low wheel's state (the study's axes: y to the right).
    assert_eq!(r.scene.loads.normal_force.to_bits(), l.normal_force.to_bits());
    assert_eq!(r.scene.creepage_y.to_bits(), (-l.creepage.y).to_bits());
    assert_eq!(r.scene.spin.to_bits(), (-l.creepage.spin).to_bits());
}

/// The metro bogie (configs/curve_metro.toml, R = 300 m): every wheelset's
/// forces balance (residual below 1e-4 of the axle load, the solver's
/// tolerance), the creep force within mu N on every wheel, and the whole
/// bogie carries the curve's lateral load: the sum of the contact forces'
/// lateral components equals the uncompensated centrifugal force of both
/// axle loads (3e-4 of the axle load: three equations' residuals). The leading wheelset runs under-radial against the high rail's
/// gauge corner (angle of attack > 0, contact angle > 0.3 rad); the
/// trailing one nearly radial, towards the low rail.
#[test]
fn metro_bogie_balances_its_forces() {
    let r = load_file(Path::new("configs/curve_metro.toml"), &[]).unwrap();
    let s = r.curve.as_ref().unwrap();
    assert!(s.state.residual < 1e-4, "{}", s.state.residual);
    let mut lateral = 0.0;
    for w in &s.state.wheelsets {
        for p in &w.patches {
            let creep = p.force_x.hypot(p.force_lateral);
            assert!(creep <= 0.4 * p.normal_force * (1.0 + 1e-9), "{creep} > mu N");
            lateral += p.force_yz().0;
        }
    }
    let load = 2.0 * s.loads.axle_load / GRAVITY * s.curve.lateral_acceleration();
    assert!((lateral - load).abs() < 3e-4 * s.loads.axle_load, "{lateral} against {load}");
    eprintln!("lateral: {lateral:.1} N against {load:.1} N; residual {:.1e}", s.state.residual);
    let (lead, trail) = (&s.state.wheelsets[0], &s.state.wheelsets[1]);
    assert!(lead.angle_of_attack() > 3e-3 && trail.angle_of_attack().abs() < 1e-3, "{lead:?}");
    assert!(lead.on(Side::Right).contact_angle() > 0.3);
    assert!(trail.shift > 0.0);
}

/// A growth study's state from `[curve]` equals the same study with the
/// state given by hand (the resolved config without `[curve]`): the same
/// scene, and its passage bit for bit.
#[test]
fn a_study_from_the_curve_equals_the_state_given_by_hand() {
    let from_curve = load_file(Path::new("configs/curve_pure_rolling.toml"), &[]).unwrap();
    let mut table: toml::Table = from_curve.toml.parse().unwrap();
    table.remove("curve");
    let by_hand = load_str(&toml::to_string(&table).unwrap(), "by hand", &[]).unwrap();
    assert!(by_hand.curve.is_none());
    assert_eq!(from_curve.scene, by_hand.scene);
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.h5"), dir.path().join("b.h5"));
    corrugation::run::run_scene(&from_curve, &a, &mut |_| {}).unwrap();
    corrugation::run::run_scene(&by_hand, &b, &mut |_| {}).unwrap();
    for (group, var) in [
        ("contact/pass_00000", "normal_force"),
        ("contact/pass_00000", "longitudinal_force"),
        ("contact/pass_00000", "spin"),
        ("rail", "wear"),
    ] {
        let (x, y) = (read_f64(&a, group, var).unwrap(), read_f64(&b, group, var).unwrap());
        assert!(!x.is_empty() && x.shape() == y.shape(), "{var}");
        assert!(x.iter().zip(y.iter()).all(|(p, q)| p.to_bits() == q.to_bits()), "{var}");
    }
}

/// A growth study with `[curve]` resumes bit for bit: its stored config
/// holds the keys the curve set, with the values the curve gives them.
#[test]
fn a_curve_study_resumes_bit_for_bit() {
    let growth = include_str!("../configs/growth_fastsim.toml");
    // The keys the curve sets are absent.
    let text: String = growth
        .lines()
        .filter(|l| {
            let k = l.split('=').next().unwrap_or("").trim();
            !["wheel_radius", "wheel_profile_radius", "rail_head_radius", "normal_force", "longitudinal_force"]
                .contains(&k)
        })
        .map(|l| format!("{l}\n"))
        .collect::<String>()
        + "\n[curve]\nradius = 1000.0\ncant = 0.05\nvehicle = \"wheelset\"\nwheel_profile = \"cone 1:20\"\naxle_load = 120e3\n";
    let set: Vec<String> = [
        "contact.elements_x=6",
        "contact.elements_y=6",
        "rail.dx=5e-4",
        "rail.dy=1e-3",
        "passage.step_length=5e-4",
        "growth.adaptive=false",
        "growth.contact_history=[]",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let with = |n: &str| [set.clone(), vec![format!("growth.passes={n}")]].concat();
    let dir = tempfile::tempdir().unwrap();
    let full = dir.path().join("full.h5");
    let part = dir.path().join("part.h5");
    corrugation::run::run_scene(&load_str(&text, "curve", &with("3")).unwrap(), &full, &mut |_| {}).unwrap();
    corrugation::run::run_scene(&load_str(&text, "curve", &with("2")).unwrap(), &part, &mut |_| {}).unwrap();
    corrugation::run::resume(&part, Some(1), None, &mut |_| {}).unwrap();
    let (x, y) = (read_f64(&full, "rail", "profile").unwrap(), read_f64(&part, "rail", "profile").unwrap());
    assert_eq!(x.shape(), y.shape());
    assert!(x.iter().zip(y.iter()).all(|(p, q)| p.to_bits() == q.to_bits()));
}

/// Bad curves are refused, each naming its key: a radius out of range, a
/// trailing wheelset of a single wheelset, a key the curve sets given
/// otherwise, a wheel profile file that is not a profile (its line), and a
/// gauge the wheels do not fit.
#[test]
fn bad_curves_name_their_key() {
    let base = std::fs::read_to_string("configs/curve_pure_rolling.toml").unwrap();
    let refuse = |text: &str, set: &[&str], key: &str, words: &str| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let e = load_str(text, "bad", &set).unwrap_err().to_string();
        assert!(e.contains(key) && e.contains(words), "{key}: {e}");
    };
    refuse(&base, &["curve.radius=5"], "curve.radius", "[20, 100000]");
    refuse(&base, &["curve.wheelset=\"trailing\""], "curve.wheelset", "bogie");
    refuse(&base, &["rolling.spin=0.5"], "rolling.spin", "set by [curve]");
    refuse(&base, &["curve.gauge=1.30"], "curve", "contact table fails");
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("wheel.csv");
    std::fs::write(&file, "0, 0\n1, 0\n1, 0.1\n2, 0\n3, 0\n").unwrap();
    let text = base.replace("\"cone 1:20\"", &format!("{:?}", file.display().to_string()));
    refuse(&text, &[], "curve.wheel_profile", "line 3");
}

/// `corrugation curve` writes the groups and variables its readers use, and
/// refuses a config without `[curve]` (exit 2, nothing written).
#[test]
fn the_curve_command_writes_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.h5");
    let bin = env!("CARGO_BIN_EXE_corrugation");
    let run = std::process::Command::new(bin)
        .args(["curve", "configs/curve_pure_rolling.toml", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let shift = read_f64(&out, "geometry", "lateral_shift").unwrap();
    let dr = read_f64(&out, "geometry", "rolling_radius_difference").unwrap();
    assert_eq!(shift.len(), dr.len());
    for v in ["contact_angle_left", "contact_angle_right"] {
        assert_eq!(read_f64(&out, "geometry", v).unwrap().len(), shift.len());
    }
    let conicity = read_f64(&out, "geometry", "equivalent_conicity").unwrap();
    assert!(conicity.iter().all(|c| *c > 0.0 && *c < 1.0));
    for v in ["normal_force", "creepage_x", "creepage_y", "spin", "lateral_shift", "angle_of_attack"] {
        assert_eq!(read_f64(&out, "curving", v).unwrap().len(), 2, "{v}");
    }
    assert_eq!(read_i8(&out, "curving", "flange_contact").unwrap().len(), 2);
    let none = std::process::Command::new(bin)
        .args(["curve", "configs/paper_steady.toml", "-o"])
        .arg(dir.path().join("none.h5"))
        .output()
        .unwrap();
    assert_eq!(none.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&none.stderr).contains("[curve]"));
    assert!(!dir.path().join("none.h5").exists());
}

/// Linear curving theory (Boocock, *Vehicle System Dynamics* 5 (1969)
/// 1-26): a bogie of 1:20 cones on a large curve (R = 5000 m, balanced
/// cant), where the creepages stay near 1e-4. The linearised equations,
/// with Kalker's linear creep coefficients (f11, f22, f23 at the Hertz
/// ellipse of half the axle load), the rolling-radius difference's slope
/// `2 lambda`, the contact angle's slope (the gravitational stiffness) and
/// the contact spacing `2 b` from the contact table, give each wheelset's
/// lateral shift and angle of attack from a 6 x 6 linear system:
///
/// ```text
/// wheelset: 2 f22 psi - f23 (2/R - 2 delta' y / r0) - Q delta' y - K_y dy = 0
///           -2 b f11 (b / R + lambda y / r0) - K_psi dpsi = 0
/// frame:    sum K_y dy = 0,  sum (K_y dy x + K_psi dpsi) = 0
/// ```
///
/// The solver with the same creep law (`CreepLaw::Linear`) on the full
/// contact table, its normal forces from the wheelsets' balance, agrees
/// within 3 % on both wheelsets' angle of attack and lateral shift, with a
/// finite yaw stiffness 2 k_x d^2 (k_x = 5 MN/m). (With FASTSIM they differ
/// by 7-20 %: at these creepages the spin, 0.1 1/m from the cone, weighs
/// FASTSIM's flexibility and couples the wheels' forces, which the linear
/// theory does not.)
#[test]
fn large_curve_bogie_meets_linear_curving_theory() {
    use corrugation::creep_coefficients::creep_coefficients;
    use corrugation::curving::steady::{ContactModel, CreepLaw, Problem, TABLE};
    use corrugation::curving::table::ContactTable;
    use corrugation::curving::vehicle::{Curve, Loads, Primary, Vehicle};
    use corrugation::hertz::{Curvatures, Elastic, HertzShape};
    use nalgebra::{Matrix6, Vector6};
    let wheelset =
        WheelsetShape { wheels: [Profile::cone(0.05), Profile::cone(0.05)], radius: [0.46; 2], flange_back: 1.36 };
    let rails = [Profile::rail_60e1(), Profile::rail_60e1()];
    let track = TrackShape { rails, gauge: 1.435, gauge_depth: 0.014, inclination: (1.0f64 / 40.0).atan() };
    let g = Geometry::new(wheelset, track).unwrap();
    let table = ContactTable::cached(&g, TABLE.0, TABLE.1).unwrap();
    let (radius, speed, q) = (10000.0, 20.0, 120e3);
    let cant = 1.5 * (speed * speed / (GRAVITY * radius)).atan().sin();
    let primary = Primary { longitudinal: 5e6, lateral: 4e6, half_spacing: 1.0 };
    let a = 1.25;
    let elastic = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
    let problem = Problem {
        geometry: &g,
        table: &table,
        curve: Curve { radius, cant, rail_spacing: 1.5, speed },
        vehicle: Vehicle::Bogie { half_wheelbase: a, primary },
        loads: Loads { axle_load: q, centre_height: 0.46, traction: 0.0 },
        contact: ContactModel { elastic, friction: 0.4, creep: CreepLaw::Linear },
    };
    let state = problem.solve().unwrap();
    // The linear theory's coefficients from the table at the centre.
    let h = 5e-4;
    let (r0m, r00, r0p) = (table.at(-h).unwrap(), table.at(0.0).unwrap(), table.at(h).unwrap());
    let lambda = ((r0p.wheel[0].rolling_radius - r0p.wheel[1].rolling_radius)
        - (r0m.wheel[0].rolling_radius - r0m.wheel[1].rolling_radius))
        / (4.0 * h);
    let angle = |r: &corrugation::curving::table::Row| r.wheel[0].contact_angle(Side::Left);
    let slope = (angle(&r0p) - angle(&r0m)) / (2.0 * h);
    let c = &r00.wheel[0];
    let b = c.lateral;
    let r0 = 0.46;
    let shape = HertzShape::new(Curvatures { a: c.curvatures.0, b: c.curvatures.1 }, elastic).unwrap();
    let patch = shape.patch(q / 2.0).unwrap();
    // Kalker's linear creep coefficients at half the axle load.
    let k = creep_coefficients(patch.aspect(), 0.3).unwrap();
    let gab = elastic.shear_modulus() * patch.a * patch.b;
    let (f11, f22, f23) = (gab * k.c11, gab * k.c22, gab * (patch.a * patch.b).sqrt() * k.c23);
    let (ky, kpsi) = (primary.lateral_stiffness(), primary.yaw_stiffness());
    // Unknowns: y1, psi1, y2, psi2, yb, psib (x1 = +a, x2 = -a).
    let mut m = Matrix6::zeros();
    let mut rhs = Vector6::zeros();
    for (i, x) in [(0usize, a), (1, -a)] {
        let (iy, ip) = (2 * i, 2 * i + 1);
        // dy = y + x^2/(2R) - yb - psib x; dpsi = psi + x/R - psib.
        m[(iy, iy)] = 2.0 * f23 * slope / r0 - q * slope - ky;
        m[(iy, ip)] = 2.0 * f22;
        m[(iy, 4)] = ky;
        m[(iy, 5)] = ky * x;
        rhs[iy] = 2.0 * f23 / radius + ky * x * x / (2.0 * radius);
        m[(ip, iy)] = -2.0 * b * f11 * lambda / r0;
        m[(ip, ip)] = -kpsi;
        m[(ip, 5)] = kpsi;
        rhs[ip] = 2.0 * b * b * f11 / radius + kpsi * x / radius;
        // Frame.
        m[(4, iy)] += ky;
        m[(4, 4)] -= ky;
        m[(4, 5)] -= ky * x;
        rhs[4] -= ky * x * x / (2.0 * radius);
        m[(5, iy)] += ky * x;
        m[(5, ip)] += kpsi;
        m[(5, 4)] -= ky * x;
        m[(5, 5)] -= ky * x * x + kpsi;
        rhs[5] -= ky * x * x * x / (2.0 * radius) + kpsi * x / radius;
    }
    let linear = m.lu().solve(&rhs).unwrap();
    for (i, w) in state.wheelsets.iter().enumerate() {
        let (y, psi) = (linear[2 * i], linear[2 * i + 1]);
        eprintln!("wheelset {i}: shift {:.4e} against {y:.4e} m, yaw {:.4e} against {psi:.4e} rad", w.shift, w.yaw);
        assert!((w.yaw / psi - 1.0).abs() < 0.03, "yaw {} against {psi}", w.yaw);
        assert!((w.shift / y - 1.0).abs() < 0.03, "shift {} against {y}", w.shift);
    }
}
