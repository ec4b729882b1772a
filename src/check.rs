//! `corrugation check`: the derived quantities of a validated scene (Hertz
//! patches, mesh or grid, passage, rail grid, growth settings, resonances)
//! and a rough cost estimate.

use corrugation::config::Resolved;
use corrugation::contact::grid::GRID_MARGIN;
use corrugation::contact::grid::convolution::smooth_padding;
use corrugation::contact::transient::StepSolver;
use corrugation::growth::traffic::TrafficScaling;
use corrugation::loads::LoadQuantity;
use corrugation::model_choice::{AccuracyMap, AutoChoice, Candidate, SAFETY, departures};
use corrugation::params::{ContactGrid, ContactModelKind, DynamicsKind, NormalContact};
use corrugation::run::{derive, fixed_grid_load, fixed_grid_spec, periodic_grid, track_dynamics};

/// What contact.model = "auto" chose and why.
fn print_auto(a: &AutoChoice) {
    let ms = |c: &Candidate| c.cpu_per_step * 1e3;
    println!(
        "auto               tolerance {} (relative centre-line wear error); shortest wavelength {:.4} mm, \
         lambda / 2a_max = {:.3}",
        a.tolerance,
        a.wavelength * 1e3,
        a.lambda_over_2a
    );
    let c = &a.chosen;
    println!(
        "auto choice        {}: predicted error {:.4}, {:.3} ms CPU per 0.2 mm rolled (the cheapest within the tolerance)",
        c.label(),
        c.wear_error,
        ms(c)
    );
    if let Some(e) = &a.exact {
        println!(
            "auto exact         the exact model would need {}: predicted error {:.4}, {:.3} ms CPU per 0.2 mm",
            e.label(),
            e.wear_error,
            ms(e)
        );
    }
    let list: Vec<String> = AccuracyMap::builtin()
        .candidates(a.lambda_over_2a)
        .iter()
        .map(|c| {
            let mark = if c.wear_error <= SAFETY * a.tolerance { "ok" } else { "no" };
            format!("{}: {:.3} in {:.2} ms {mark}", c.label(), c.wear_error, ms(c))
        })
        .collect();
    println!("auto candidates    (cheapest first) {}", list.join("; "));
    if let Some(d) = a.hertz_difference {
        let limit = corrugation::model_choice::hertz_validity::HERTZ_LIMIT;
        let verdict = if d <= limit {
            "inside the Hertz region: the Hertz normal contact".to_string()
        } else if c.grid_dx().is_some() {
            "outside the Hertz region: the profile in the normal contact once the corrugation is above the profile \
             contact's floor (contact.normal = \"auto\")"
                .to_string()
        } else {
            "outside the Hertz region: the chosen model has no profile contact; the run warns".to_string()
        };
        let by = if d.is_finite() { format!("{:.1} %", 100.0 * d) } else { "beyond the map".into() };
        println!(
            "auto normal        the initial corrugation: Hertz and profile contact differ by {by} in the wear's first \
             harmonic (limit {:.0} %, scripts/validity_map.sh): {verdict}",
            100.0 * limit
        );
    }
}

/// Prints what `check` reports.
pub fn print_check(r: &Resolved) {
    let s = &r.scene;
    let d = derive(s);
    let mm = |v: f64| v * 1e3;
    println!("config OK");
    let by = if s.contact.auto.is_some() { " (chosen by contact.model = \"auto\")" } else { "" };
    println!("contact model      {}{by}", s.contact.model.name());
    if let Some(a) = &s.contact.auto {
        print_auto(a);
        for note in departures(s) {
            println!("note               outside the map's conditions: {note}");
        }
    }
    println!("Hertz a/b          {:.4}", d.shape.aspect());
    if d.patch_min.is_none() {
        println!(
            "contact loss       N <= 0 on part of the stretch (min N = {:.4e} N): no patch there",
            s.loads.min_normal_force()
        );
    }
    for (label, p) in [("mean", Some(d.patch_mean)), ("min", d.patch_min), ("max", Some(d.patch_max))] {
        let Some(p) = p else { continue };
        println!(
            "Hertz at {label:<4} N   N = {:.4e} N: a = {:.4} mm, b = {:.4} mm, p0 = {:.1} MPa, approach = {:.4} mm",
            p.normal_force,
            mm(p.a),
            mm(p.b),
            p.p0 / 1e6,
            mm(p.approach)
        );
    }
    let fixed = match s.contact.grid {
        ContactGrid::Fixed(f) => Some((f, fixed_grid_spec(s, &d.shape, f))),
        ContactGrid::Adapted => None,
    };
    if let Some((f, spec)) = &fixed {
        let g = spec.grid();
        let in_contact = |a: f64, b: f64| std::f64::consts::PI * a * b / (f.dx * f.dy);
        println!(
            "grid               fixed, {} x {} = {} elements of {:.4} x {:.4} mm over x in [{:.4}, {:.4}] mm, y in \
             [{:.4}, {:.4}] mm (the patch at {:.4e} N with {:.0} % margin and {} elements along x, one along y; FFT {} x {})",
            g.nx,
            g.ny,
            g.len(),
            mm(f.dx),
            mm(f.dy),
            mm(g.x_front - g.nx as f64 * g.dx),
            mm(g.x_front),
            mm(g.y_low),
            mm(g.y_low + g.ny as f64 * g.dy),
            fixed_grid_load(s),
            GRID_MARGIN * 100.0,
            spec.lead_columns(),
            smooth_padding(g.nx),
            smooth_padding(g.ny)
        );
        println!(
            "grid contact       about {:.0} elements in contact at mean N ({:.1} x {:.1} elements across the patch), \
             {:.0} at max N; friction law {}, {} difference",
            in_contact(d.patch_mean.a, d.patch_mean.b),
            2.0 * d.patch_mean.a / f.dx,
            2.0 * d.patch_mean.b / f.dy,
            in_contact(d.patch_max.a, d.patch_max.b),
            f.friction_law.name(),
            f.scheme.name()
        );
        if let NormalContact::Auto { amplitude, .. } = f.normal {
            println!(
                "normal contact     auto: the Hertz contact while the corrugation's dominant harmonic is below \
                 {:.2} um or inside the Hertz region, the profile from then on (on the profile's grid)",
                amplitude * 1e6
            );
        }
        if let NormalContact::Profile { grid_scale } | NormalContact::Auto { grid_scale, .. } = f.normal {
            println!(
                "normal contact     profile: the rail's corrugation in the gap of every step (the grid {grid_scale} times \
                 the largest Hertz patch both ways); the dynamics see the equivalent roughness (a normal solve per step \
                 at the mean load before every passage)"
            );
        }
    } else {
        let el = 2.0 * d.patch_mean.a / s.contact.elements_x as f64;
        println!(
            "mesh               {} x {} = {} elements; element length {:.4} mm at mean N",
            s.contact.elements_x,
            s.contact.elements_y,
            s.contact.elements_x * s.contact.elements_y,
            mm(el)
        );
    }
    let p = &d.passage;
    let wear = if fixed.is_some() {
        "wear on the rail cells under each element".to_string()
    } else {
        format!("{} wear sub-steps", p.substeps)
    };
    println!(
        "passage            X from {:.4} to {:.4} mm, {} steps of {:.4} mm (dt = {:.4e} s), {wear}",
        mm(p.start),
        mm(p.end),
        p.n_steps(),
        mm(p.dt() * p.speed),
        p.dt(),
    );
    let g = if s.growth.is_some() { periodic_grid(s) } else { d.grid.clone() };
    let periodic = if s.growth.is_some() { " (periodic)" } else { "" };
    println!(
        "rail grid          {} x {} nodes{periodic}, dx = {:.4} mm, dy = {:.4} mm",
        g.nx,
        g.ny,
        mm(g.dx),
        mm(g.dy)
    );
    // Cost model from measurements on 2 cores (README, Performance), per
    // step: wear ~ 20 ns per node visit; FASTSIM ~ 18 ns per element and
    // solve, 25 solves; simplified-transient ~ 3 us per element; the exact
    // model with constant N ~ 60 ms at 400 elements, growing as N^3 (dense
    // LU); with a varying N (harmonics or track dynamics) 2.5 ms at 100 and
    // 175 ms at 400 elements, both fitted by 2.7e-9 N^3 s. The Gauss-Seidel
    // solver (scripts/solver_scaling.sh, wall): 2.4 ms at 100 and 11.8 ms at
    // 400 elements (~N^1.15 while C fits in cache), ~N^2.2 beyond. Measured
    // on the old AMD development machine; the newer Intel one (README,
    // Performance) takes 0.45-0.6 of these times: an upper estimate.
    let n_el = (s.contact.elements_x * s.contact.elements_y) as f64;
    let nodes = std::f64::consts::PI * d.patch_max.a * d.patch_max.b / (g.dx * g.dy);
    // The fixed grid (scripts/solver_scaling.sh, paper_normal_30mm on the
    // new machine): 5.0 ms per step with 478 elements in contact at the mean
    // load, 35.9 ms with 1912, 106.5 ms with 3902, fitted by N^1.46; the
    // wear deposit is in it. A scene that is not symmetric about the centre
    // line (lateral creepage, spin) solves the whole grid: 2.7 times
    // (scripts/stability_map.sh).
    let fixed_step = fixed.as_ref().map(|(f, _)| {
        let n_c = std::f64::consts::PI * d.patch_mean.a * d.patch_mean.b / (f.dx * f.dy);
        let symmetric = s.creepage_y == 0.0 && s.spin == 0.0;
        // With the profile in the contact: a larger grid, the gap of every
        // step and the equivalent roughness's normal solves; 2.0 times on
        // growth_exact.toml (3 passages: 3.6 s with "hertz", 7.3 s).
        let profile = if matches!(f.normal, NormalContact::Hertz) { 1.0 } else { 2.0 };
        5.0e-3 * (n_c / 478.0).powf(1.46) * if symmetric { 1.0 } else { 2.7 } * profile
    });
    let contact = match s.contact.model {
        _ if fixed_step.is_some() => fixed_step.unwrap_or_default(),
        ContactModelKind::Fastsim => 25.0 * 18e-9 * n_el,
        ContactModelKind::SimplifiedTransient => 3e-6 * n_el,
        ContactModelKind::ExactTransient if s.contact.solver == StepSolver::GaussSeidel => {
            if n_el <= 400.0 {
                2.4e-3 * (n_el / 100.0).powf(1.15)
            } else {
                11.8e-3 * (n_el / 400.0).powf(2.2)
            }
        }
        ContactModelKind::ExactTransient => {
            let varying = s.loads.harmonics.iter().any(|h| h.quantity == LoadQuantity::NormalForce)
                || s.growth.as_ref().is_some_and(|g| g.dynamics != DynamicsKind::Imposed);
            if varying { 2.7e-9 * n_el.powi(3) } else { 0.06 * (n_el / 400.0).powi(3) }
        }
    };
    // With "auto", the map's own measurement of the chosen model.
    // (per 0.2 mm rolled: per step of the fixed grid in proportion to its element).
    let contact =
        s.contact.auto.map_or(contact, |a| a.chosen.cpu_per_step * a.chosen.grid_dx().map_or(1.0, |dx| dx / 2e-4));
    let deposit = if fixed_step.is_some() { 0.0 } else { p.substeps as f64 * nodes * 20e-9 };
    let secs = p.n_steps() as f64 * (contact + deposit);
    let passes = s.growth.as_ref().map_or(1, |g| g.passes);
    if let Some(g) = &s.growth {
        match g.traffic {
            TrafficScaling::Fixed { scale, .. } => println!(
                "growth             {} passages x traffic scale {scale} = {:.4e} real passages; dynamics {:?}",
                g.passes,
                g.passes as f64 * scale,
                g.dynamics
            ),
            TrafficScaling::Adaptive { initial, max, max_update_ratio } => println!(
                "growth             {} passages, adaptive traffic scale from {initial} up to {max} (update ratio <= \
                 {max_update_ratio}); dynamics {:?}",
                g.passes, g.dynamics
            ),
        }
        println!("checkpoints        every {} passages; rail stored every {}", g.checkpoint_every, g.store_every);
        if !(g.classes.len() == 1 && g.classes[0].name == corrugation::config::traffic::BASE_NAME) {
            for c in &g.classes {
                println!(
                    "traffic class      {}: {:.1} % of the passages at {:.2} m/s ({:.0} km/h), N = {:.4e} N, F_x = {:.4e} N, \
                     unsprung mass {} kg",
                    c.name,
                    100.0 * c.share,
                    c.speed,
                    c.speed * 3.6,
                    c.normal_force,
                    c.longitudinal_force,
                    c.unsprung_mass
                );
            }
        }
        if g.dynamics != DynamicsKind::Imposed {
            let t = &s.track;
            let damping = |d: corrugation::dynamics::track::Damping| match d {
                corrugation::dynamics::track::Damping::LossFactor(eta) => format!("loss factor {eta}"),
                corrugation::dynamics::track::Damping::Viscous(c) => format!("{c:.4e} N s/m"),
            };
            println!(
                "track              {} rail (EI {:.4e} N m^2, {} kg/m) on {:.1} MN/m pads ({}) at {} m, {} kg per half \
                 sleeper, {:.1} MN/m ballast ({}); smeared for the continuous model",
                t.rail_name,
                t.rail.bending_stiffness,
                t.rail.mass,
                t.pad_stiffness / 1e6,
                damping(t.pad_damping),
                t.sleeper_spacing,
                t.sleeper_mass,
                t.ballast_stiffness / 1e6,
                damping(t.ballast_damping)
            );
            let discrete = corrugation::dynamics::discrete::DiscreteTrack::new(t);
            let used = if matches!(g.dynamics, DynamicsKind::Discrete { .. }) {
                "in the growth loop's discrete model"
            } else {
                "not in the continuous model the growth loop uses"
            };
            println!(
                "resonance          {:8.1} Hz  pinned-pinned (discrete supports: the simply supported Timoshenko span; \
                 {used}; `corrugation track` gives the receptances)",
                discrete.pinned_pinned_frequency()
            );
        }
        // (The discrete model tabulates its receptances for seconds: its
        // pinned-pinned resonance is printed above.)
        if let Some(t) = track_dynamics(s, &d).filter(|_| matches!(g.dynamics, DynamicsKind::Receptance { .. })) {
            for (label, f) in t.describe_resonances() {
                println!("resonance          {f:8.1} Hz  {label}");
            }
        }
    }
    // The discrete model tabulates its receptances once per traffic class:
    // about 1 s per 100 harmonics up to its 5 kHz on 2 cores.
    let setup: f64 = match &s.growth {
        Some(g) if matches!(g.dynamics, DynamicsKind::Discrete { .. }) => g
            .classes
            .iter()
            .map(|c| {
                let n = (corrugation::dynamics::discrete_dynamics::F_MAX * stretch_length(s) / c.speed).floor();
                n.min((periodic_grid(s).nx / 2) as f64) * 0.01
            })
            .sum(),
        _ => 0.0,
    };
    let setup_text = if setup > 0.0 {
        format!(" plus {setup:.1} s to tabulate the discrete track's receptances")
    } else {
        String::new()
    };
    println!(
        "estimated cost     {:.2} s per passage, {:.1} s in all{setup_text} on 2 cores (rough, from the benchmarks)",
        secs,
        secs * passes as f64
    );
}

/// Length of the periodic stretch of a scene (m).
fn stretch_length(s: &corrugation::params::Scene) -> f64 {
    s.rail.x_max - s.rail.x_min
}
