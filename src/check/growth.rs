//! What `check` prints of a growth study: the spectrum's plan, the
//! directions and their cost, the wheelset's modes, the field units.

use super::*;

/// What `corrugation spectrum` would measure (a growth study's config; its
/// `[spectrum]` or the defaults) and its cost from the passage's estimate.
pub(super) fn print_spectrum(s: &corrugation::params::Scene, cost: &CostEstimate) {
    if s.growth.is_none() {
        return;
    }
    let params = s.spectrum.unwrap_or_default();
    let rails = 1 + usize::from(s.second_rail.is_some());
    let Some(p) = corrugation::spectrum::plan(s, &params, rails) else {
        println!(
            "spectrum           spectrum.wavelength_min to _max ({} to {} m) holds no harmonic of the stretch",
            params.wavelength_min, params.wavelength_max
        );
        return;
    };
    let harmonics: usize = p.classes.iter().map(|c| c.1).sum();
    let base = match params.base {
        corrugation::spectrum::Base::Smooth => "the smooth rail",
        corrugation::spectrum::Base::Roughness => "the initial roughness",
    };
    println!(
        "spectrum           `corrugation spectrum`{}: {} Bloch class(es) on a supercell of {:.4} m, {harmonics} harmonics \
         of {:.1} to {:.1} mm about {base}, {} difference(s) of {:.1e} m: {} rounds, {} passages ({} over one stretch), \
         about {:.0} s on 2 cores",
        if s.spectrum.is_some() { "" } else { " with the defaults" },
        p.classes.len(),
        p.supercell,
        params.wavelength_min * 1e3,
        params.wavelength_max * 1e3,
        <&str>::from(params.difference),
        params.perturbation,
        p.rounds,
        p.passages,
        p.passage_equivalents,
        p.passage_equivalents as f64 * cost.per_passage + cost.setup * params.classes as f64,
    );
}

/// What the normal contact of a growth study sees of the rail.
/// What the growth loop's dynamics closes, direction by direction, and what
/// the dynamics in every direction costs before the first passage.
pub(super) fn print_directions(
    s: &corrugation::params::Scene,
    g: &corrugation::params::GrowthParams,
    cost: &CostEstimate,
) {
    if let Some(choice) = &s.wheelset_choice {
        println!("wheelset choice    auto: {choice} (wheelset.model = \"rigid\", \"torsion\" or \"modal\" forces one)");
    }
    if g.dynamics == DynamicsKind::Imposed {
        return;
    }
    let Directions::All { contact_offset, creep_forces, spin } = g.directions else {
        println!(
            "directions         vertical: the normal force's dynamics{} (dynamics.directions = \"all\" adds the \
             longitudinal and lateral directions)",
            if s.wheelset.is_some() { ", and the torsional feedback on the creepage" } else { "" }
        );
        return;
    };
    let track = if matches!(g.dynamics, DynamicsKind::Discrete { .. }) {
        "discrete supports, 16 places of the bay"
    } else {
        "continuous supports"
    };
    let wheel = match &s.wheelset {
        Some(w) if w.modal.is_some() => "the modal wheelset's wheel 0",
        Some(_) => "rigid, its rotation through the wheelset's torsion",
        None => "rigid, free above the suspension, spinning",
    };
    let creep = match creep_forces {
        CreepForces::Transient => "their frequency response on the passage's own contact solver",
        CreepForces::Steady => "FASTSIM's steady slopes",
    };
    println!(
        "directions         every direction: the rail head along, across and vertically ({track}; the contact {:.1} mm \
         right of the centre line), the wheel {wheel}; creep forces from {creep}",
        contact_offset * 1e3
    );
    let mut left_out = Vec::new();
    if s.second_rail.is_none() {
        left_out.push(
            "the other rail's contact (the wheelset's other wheel runs free: its creep forces uncorrelated with this \
             rail's profile; [second_rail] couples both)",
        );
    }
    if s.wheelset.as_ref().is_none_or(|w| w.modal.is_none()) {
        left_out.push("the wheelset's flexible modes (wheelset.model = \"modal\")");
    }
    if !spin {
        left_out.push("the spin's variation");
    }
    left_out.push("the vehicle above the primary suspension (its modes are below the band)");
    println!("left out           {}", left_out.join("; "));
    if spin {
        let wheel_turns = if s.wheelset.as_ref().is_some_and(|w| w.modal.is_some()) {
            "the wheelset's yaw, the axle's horizontal bending and the wheels' axial modes"
        } else {
            "none: the rigid wheel does not turn about the vertical"
        };
        println!(
            "spin               in the loop: the rail head's rotation about the vertical and the wheel's ({wheel_turns}) \
             vary the spin creepage (dynamics.spin = false leaves it out)"
        );
    } else {
        println!("spin               left out of the loop (dynamics.spin = false): the spin stays at its mean");
    }
    if let Some(c) = cost.directions {
        println!(
            "directions cost    {:.1} s for the receptances in three directions, {:.1} s for the creep response, once \
             per traffic class before the first passage ({:.1} % of the study; vertical only: \
             dynamics.directions = \"vertical\"{})",
            c.tables,
            c.creep_response,
            100.0 * (c.tables + c.creep_response) / cost.total().max(1e-9),
            if creep_forces == CreepForces::Transient {
                ", steady creep slopes: dynamics.creep_forces = \"steady\""
            } else {
                ""
            }
        );
    }
}

/// The modal wheelset's modes (`[wheelset] model = "modal"`), at rest and
/// as the scene's spin `V / r` moves the coupled ones.
pub(super) fn print_wheelset_modes(s: &corrugation::params::Scene) {
    let Some(modal) = s.wheelset.as_ref().and_then(|w| w.modal.as_ref()) else {
        return;
    };
    let Some(model) = wheelset_model(s) else {
        return;
    };
    let source = match &modal.modes {
        corrugation::params::WheelsetModes::Default { .. } => "the default freight wheelset".to_string(),
        corrugation::params::WheelsetModes::Table { path, .. } => format!("the table {path}"),
    };
    println!(
        "wheelset           modal model: {} modes ({source}, on the primary suspension); the receptance at both \
         contacts in x, y, z and rotation",
        model.modes().len()
    );
    for (k, m) in model.modes().iter().enumerate() {
        println!("wheelset           mode {k}: {}", m.describe());
    }
    let spin = s.speed / s.geometry.wheel_radius;
    let moved: Vec<String> = model.frequencies(spin).iter().map(|f| format!("{f:.1}")).collect();
    println!(
        "wheelset           spinning at V / r = {spin:.1} rad/s the undamped modes are at {} Hz (the gyroscopic \
         coupling splits the bending pairs and the wheel's diametral pairs)",
        moved.join(", ")
    );
}

/// The roughness levels' bands and limit, and the traffic in the operator's
/// units (issue 35).
pub(super) fn print_field_units(s: &corrugation::params::Scene, g: &corrugation::params::GrowthParams) {
    use corrugation::levels::resolved_bands;
    let grid = corrugation::build::study_grid(s);
    let bands = resolved_bands(s.levels.bands, grid.nx, grid.dx);
    let limit = s.levels.limit.on(&bands);
    match (bands.first(), bands.last()) {
        (Some(long), Some(short)) => println!(
            "roughness levels   {} bands, {} to {} (a quarter of the stretch down to the grid), against the {} \
             ({} of them with a value)",
            bands.len(),
            long.label(),
            short.label(),
            corrugation::levels::limit::limit_words(&s.levels.limit.name),
            limit.iter().filter(|l| l.is_finite()).count()
        ),
        _ => println!("roughness levels   no band resolved (a band needs a quarter of the stretch)"),
    }
    let shares: Vec<f64> = g.classes.iter().map(|c| c.share).collect();
    let units = g.operation.units(&shares);
    let mut parts = Vec::new();
    if let Some(t) = units.tonnes_per_passage {
        parts.push(format!("{t:.2} t per wheel passage (MGT)"));
    }
    if let Some(a) = units.axles_per_day {
        parts.push(format!("{a} axles per day (days)"));
    }
    if !parts.is_empty() {
        println!("operator traffic   {}", parts.join(", "));
    }
}
