//! `corrugation check`: the derived quantities of a validated scene (Hertz
//! patches, mesh or grid, passage, rail grid, growth settings, resonances)
//! and a rough cost estimate.

use corrugation::build::{derive, fixed_grid_load, fixed_grid_spec, periodic_grid, track_dynamics, wheelset_model};
use corrugation::config::Resolved;
use corrugation::config::quantity::engineering;
use corrugation::config::units::key_units;
use corrugation::contact::grid::GRID_MARGIN;
use corrugation::contact::grid::convolution::smooth_padding;
use corrugation::cost::CostEstimate;
use corrugation::growth::record::MeasuredRoughness;
use corrugation::model_choice::{AccuracyMap, SAFETY, departures};
use corrugation::params::Roughness;
use corrugation::params::TrafficScaling;
use corrugation::params::{AutoChoice, Candidate};
use corrugation::params::{CreepForces, Directions, DynamicsKind, NormalContact};
use std::f64::consts::PI;

mod growth;
mod record;

use growth::{print_directions, print_field_units, print_spectrum, print_wheelset_modes};
use record::print_inputs;
pub use record::record_lines;

/// What contact.model = "auto" chose and why.
fn print_auto(a: &AutoChoice, normal: NormalContact) {
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
        let verdict = match normal {
            NormalContact::Hertz if d > limit => {
                "outside the Hertz region, and contact.normal = \"hertz\" leaves the corrugation out of the contact; \
                 the run warns"
            }
            NormalContact::Hertz => "inside the Hertz region",
            _ => "the corrugation is in the normal contact (see normal contact below)",
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
        print_auto(a, s.contact.normal);
        for note in departures(s) {
            println!("note               outside the map's conditions: {note}");
        }
    }
    println!("Hertz a/b          {:.4}", d.shape.aspect());
    println!("friction           {}", friction_line(s.material.friction, s.material.characteristic));
    if !s.material.characteristic.is_constant() {
        match s.material.memory {
            Some(m) => println!(
                "friction memory    relaxing over d_c = {:.3e} m of slip, at least at s_0 = {:.3e} m/s (CONTACT's); \
                 a step slides {:.3e} m at 1 m/s slip speed: the memory holds where a step slides less than d_c \
                 (the book: friction memory)",
                m.distance,
                m.floor,
                s.step_length / s.speed
            ),
            None => println!("friction memory    none: the coefficient follows the slip speed at once"),
        }
    }
    println!("wear law           {}", wear_line(&s.wear));
    if (s.creepage_y != 0.0 || s.spin != 0.0) && s.contact.model.fixed_grid().is_some() {
        println!(
            "curving            lateral creepage {:e}, spin {:e} 1/m: not symmetric about the centre line, the fixed \
             grid solves its whole grid (no folding: about 1.2 times the CG solver's cost per step, 2.7 times \
             Gauss-Seidel's; in the estimate below)",
            s.creepage_y, s.spin
        );
    }
    match s.creepage_x {
        Some(xi) => println!(
            "control            creepage: xi_x = {xi:e} prescribed, the longitudinal force its result (lateral \
             creepage {:e}, spin {:e} 1/m)",
            s.creepage_y, s.spin
        ),
        None => println!(
            "control            force: F_x = {:.4e} N prescribed, the creepage found (lateral creepage {:e}, spin {:e} 1/m)",
            s.loads.longitudinal_force, s.creepage_y, s.spin
        ),
    }
    if let (Some(second), Some(r)) = (s.second_rail_scene(), s.second_rail.as_ref()) {
        let [first_name, name] = &r.names;
        let steady = match second.creepage_x {
            Some(xi) => format!("xi_x = {xi:e}"),
            None => format!("F_x = {:.4e} N", second.loads.longitudinal_force),
        };
        let patch = d.shape.patch(second.loads.normal_force).ok();
        println!(
            "rails              two: the {first_name} (the keys and the lines above) and the {name}: N = {:.4e} N (a = {:.4} mm, \
             b = {:.4} mm), {steady}, lateral creepage {:e}, spin {:e} 1/m; the contacts coupled through the modal \
             wheelset's transfer receptances, the rails themselves not (their sleepers' rocking left out); each \
             rail its own roughness, wear and growth",
            second.loads.normal_force,
            patch.map_or(0.0, |p| p.a * 1e3),
            patch.map_or(0.0, |p| p.b * 1e3),
            second.creepage_y,
            second.spin
        );
    }
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
    let fixed = s.contact.model.fixed_grid().map(|f| (f, fixed_grid_spec(s, &d.shape, f)));
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
             {:.0} at max N; friction law {}, {} difference, tangential solver {}",
            in_contact(d.patch_mean.a, d.patch_mean.b),
            2.0 * d.patch_mean.a / f.dx,
            2.0 * d.patch_mean.b / f.dy,
            in_contact(d.patch_max.a, d.patch_max.b),
            f.friction_law.name(),
            f.scheme.name(),
            f.solver.resolve().name()
        );
    } else if let Some(mesh) = s.contact.model.mesh() {
        let el = 2.0 * d.patch_mean.a / mesh.nx as f64;
        println!(
            "mesh               {} x {} = {} elements; element length {:.4} mm at mean N",
            mesh.nx,
            mesh.ny,
            mesh.len(),
            mm(el)
        );
    }
    if s.growth.is_some() {
        print_normal_contact(s.contact.normal, fixed.is_some());
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
    if s.vehicle.wheels.len() > 1 {
        println!(
            "vehicle            {} wheels at {:?} m behind the leading one, coupled through the rail's transfer \
             receptances (distances {:?} m; `corrugation track` writes them); every wheel rolls over the stretch in \
             a passage, whose wear is theirs averaged: traffic counts wheel passages",
            s.vehicle.wheels.len(),
            s.vehicle.wheels,
            s.vehicle.distances()
        );
        let v = &s.vehicle;
        for (key, unit, values) in [
            ("unsprung mass", "kg", &v.unsprung_mass),
            ("normal force", "N", &v.normal_force),
            ("longitudinal force", "N", &v.longitudinal_force),
        ] {
            if let Some(values) = values {
                println!("vehicle            {key} per wheel {values:?} {unit}");
            }
        }
    }
    if let Some(t) = d.passage.torsion.first() {
        let w = &t.torsion;
        let corner = t.force_per_creepage.abs() * w.radius * w.radius / (w.inertia * s.speed) / (2.0 * PI);
        println!(
            "wheelset           torsional mode {:.1} Hz (k_t {:.3e} N m/rad, J {} kg m^2 per wheel), anti-resonance \
             {:.1} Hz; creep curve dF/dN = {:.4}, dF/dxi = {:.4e} N (FASTSIM, mean state); the creepage varies with \
             the dynamic normal force: the torque held below the resonance, the creepage above {:.0} Hz",
            w.resonance(),
            w.stiffness,
            w.inertia,
            (w.stiffness / w.inertia).sqrt() / (2.0 * PI),
            t.force_per_normal,
            t.force_per_creepage,
            corner
        );
    }
    print_wheelset_modes(s);
    let cost = corrugation::cost::estimate(s);
    if let Some(g) = &s.growth {
        match g.traffic {
            TrafficScaling::Fixed { scale, .. } => println!(
                "growth             {} passages x traffic scale {scale} = {:.4e} real passages; dynamics {}",
                g.passes,
                g.passes as f64 * scale,
                g.dynamics
            ),
            TrafficScaling::Adaptive { initial, max, max_update_ratio } => println!(
                "growth             {} passages, adaptive traffic scale from {initial} up to {max} (update ratio <= \
                 {max_update_ratio}); dynamics {}",
                g.passes, g.dynamics
            ),
        }
        println!("checkpoints        every {} passages; rail stored every {}", g.checkpoint_every, g.store_every);
        print_field_units(s, g);
        if corrugation::config::traffic::is_mix(&g.classes) {
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
            let discrete = corrugation::dynamics::track::discrete::DiscreteTrack::new(t);
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
        print_directions(s, g, &cost);
        // (The discrete model tabulates its receptances for seconds: its
        // pinned-pinned resonance is printed above; the dynamics in every
        // direction measures its creep response first.)
        if let Some(t) = track_dynamics(s, &d)
            .ok()
            .flatten()
            .filter(|_| matches!(g.dynamics, DynamicsKind::Receptance { .. }) && g.directions == Directions::Vertical)
        {
            for (label, f) in t.describe_resonances() {
                println!("resonance          {f:8.1} Hz  {label}");
            }
        }
    }
    let setup_text = if cost.setup > 0.0 {
        format!(
            " plus {:.1} s to set up the dynamics (the track's receptance tables, the creep response, and on the discrete \
             track a passage over the smooth rail per traffic class)",
            cost.setup
        )
    } else {
        String::new()
    };
    println!(
        "estimated cost     {:.2} s per passage, {:.1} s in all{setup_text} on 2 cores (rough, from the benchmarks); \
         memory about {:.0} MB",
        cost.per_passage,
        cost.per_passage * cost.passes as f64,
        cost.memory / 1e6
    );
    if let Some(Roughness::Measured(m)) = s.growth.as_ref().map(|g| &g.roughness) {
        for line in record_lines(m) {
            println!("record             {line}");
        }
    }
    print_spectrum(s, &cost);
    print_inputs(&r.toml);
}

fn print_normal_contact(normal: NormalContact, fixed: bool) {
    let linear = "the linear profile contact (the patch moved and stretched with the contact and the rest of the \
                  normal problem's linear response to the corrugation under it); the dynamics see its flat-punch \
                  average of the profile";
    let profile = |scale: f64| {
        format!(
            "the nonlinear profile contact (the rail's corrugation in the gap of every step, the grid {scale} times the \
             largest Hertz patch both ways); the dynamics see its equivalent roughness (a normal solve per step at the \
             mean load before every passage)"
        )
    };
    match normal {
        NormalContact::Hertz => println!(
            "normal contact     hertz: the paper's chain, no profile in the contact (the dynamics see the profile \
             weighted across the patch by the Hertz line load); for comparison only"
        ),
        NormalContact::Linear { grid_scale } if fixed => println!(
            "normal contact     linear: {linear}; its pressure averaged over the grid's elements, the grid \
             {grid_scale} times the largest Hertz patch both ways"
        ),
        NormalContact::Linear { .. } => println!("normal contact     linear: {linear}"),
        NormalContact::Profile { grid_scale } => println!("normal contact     profile: {}", profile(grid_scale)),
        NormalContact::Auto { grid_scale } if fixed => println!(
            "normal contact     auto: {linear} while the corrugation's curvature is below {:.0} % of the wheel's; \
             beyond, {}",
            100.0 * corrugation::growth::LINEAR_CONTACT_CURVATURE,
            profile(grid_scale),
        ),
        NormalContact::Auto { .. } => println!(
            "normal contact     auto: {linear}; a corrugation that opens the patch inside is reported (the \
             nonlinear profile contact needs contact.grid = \"fixed\")"
        ),
    }
}

/// `check`'s line on the friction law: the coefficient and how it varies
/// with the slip speed.
fn friction_line(mu: f64, ch: corrugation::contact::friction::Characteristic) -> String {
    use corrugation::contact::friction::Characteristic;
    match ch {
        Characteristic::Constant => format!("mu = {mu}, constant"),
        Characteristic::Exponential { ratio, speed } => {
            let kind = if ratio > 1.0 { "rising (a friction modifier's)" } else { "falling" };
            format!("mu = {mu} at zero slip, {kind} exponentially to {:.4} (v_c = {speed:.4} m/s)", mu * ratio)
        }
        Characteristic::Rational { ratio, speed } => {
            format!("mu = {mu} at zero slip, falling rationally to {:.4} (half way at {speed:.4} m/s)", mu * ratio)
        }
    }
}

/// `check`'s line on the wear law.
fn wear_line(law: &corrugation::wear::WearLaw) -> String {
    use corrugation::wear::WearLaw;
    match law {
        WearLaw::Archard { k_over_h } => format!("Archard, k/H = {k_over_h:e} m^2/N"),
        WearLaw::FrictionalWork(f) => format!(
            "frictional work (T-gamma/A): mild {} I below {} N/mm^2, severe {} to {} N/mm^2, catastrophic {} I - {} \
             ug/(m mm^2); rho = {} kg/m^3",
            f.mild_slope,
            f.mild_limit,
            f.severe_rate,
            f.severe_limit,
            f.catastrophic_slope,
            f.catastrophic_offset,
            f.density
        ),
        WearLaw::Map(m) => format!(
            "Archard with Jendel's map: k = {:e} in seizure (p3 > {} H), {:e} / {:e} / {:e} below {} / to {} / above \
             {} m/s; H = {:.4e} Pa",
            m.seizure, m.seizure_share, m.mild, m.severe, m.fast, m.slow_limit, m.fast_limit, m.fast_limit, m.hardness
        ),
    }
}
