//! The creep response of a scene's contact: its solver (the model and grid
//! its passages use, given by the caller: the assembly's
//! `build_solver`), its mean state per wheel, and the
//! excitation whose accuracy and cost `docs/src/theory/creep-response.md`
//! measures.

use crate::contact::TangentialSolver;
use crate::dynamics::coupling::creep_response::{
    CreepResponse, CreepResponseError, Excitation, Longitudinal, MeanState, measure,
};
use crate::hertz::HertzShape;
use crate::params::Scene;

/// Length of the measured period in mean patch lengths `2 a0`: harmonics
/// every `pi / PERIOD_PATCHES` in reduced frequency `w a0 / V` (0.79 at
/// 4), where the interpolation of the table (through `1 / H`) is within
/// 1.3e-3 of |H(0)| of a table four times as dense for the creepages,
/// 6.4e-3 for the spin (the paper's scene; 6e-4 and 7e-4 at 8, for 30 %
/// more cost).
pub const PERIOD_PATCHES: f64 = 4.0;

/// Run-in at the mean state, in patch lengths `2 a0`, where the mean
/// longitudinal force is prescribed: the creepage it ends with is within
/// 2e-5 of that after 4 (1 % after 1), and the table within 2e-5 of
/// |H(0)|.
pub const RUN_IN_PATCHES: f64 = 2.0;

/// The run-in of a growth passage under creepage control, in patch lengths
/// `2 a` at the largest imposed load: from the Cattaneo start at a
/// prescribed creepage the exact theory's force approaches its steady
/// value exponentially over about 0.7 x 2a (tests/creepage_control.rs:
/// 1.5e-2 of mu N short after 2.5 x 2a, 4.5e-5 after 6.7 x 2a), where at a
/// prescribed force the creepage settles in about 2a; 7 x 2a leaves about
/// 3e-5 of mu N.
pub const CREEPAGE_RUN_IN: f64 = 7.0;

/// Excitation before the measured period, in patch lengths `2 a0`: the
/// response to the switched-on excitation decays by a factor of about 25
/// per two patch lengths on the paper's scene in partial slip (the table
/// moves by 1.8e-2 of |H(0)| from a lead of 2 to one of 8, by 7e-4 from 4,
/// 3e-5 from 6).
pub const LEAD_PATCHES: f64 = 4.0;

/// Root mean square of each input's multi-sine relative to the input's
/// scale ([`crate::dynamics::coupling::creep_response::input_scale`]), per [`crate::dynamics::coupling::creep_response::Input`]: 3e-3 for the
/// creepages and the spin (halving it moves the table by less than 7e-4
/// of |H(0)| on the paper's scene); 5 % of the mean normal force for the
/// normal force: on the fixed grid the steady force at a prescribed
/// creepage is piecewise linear in N, its slope wandering between 0.08 and
/// 0.25 over a few kN as the discrete contact area changes (0.148 on the
/// adapted mesh and over +-10 kN on the grid), and a multi-sine of 5 kN
/// rms averages it: its H(0) is within 0.5 % of the adapted mesh's and
/// halving or doubling it moves the table by 4-6 % of |H(0)|.
pub const LEVEL: [f64; 4] = [3e-3, 3e-3, 3e-3, 5e-2];

/// Largest reduced frequency of the table by default: with the default
/// period, eight harmonics, to about `2 pi` (wavelengths down to the
/// semi-axis `a0`, 6 mm on the paper's patch: below the shortest a growth
/// study's roughness holds, 10 mm, and at 15 steps per wavelength on the
/// shipped 0.4 mm grid).
pub const MAX_REDUCED: f64 = 6.5;

/// The mean state of a wheel of the scene with mean normal force `normal_force`
/// (N) and, unless the scene prescribes the creepage, mean longitudinal
/// force `longitudinal_force` (N).
pub fn mean_state(scene: &Scene, normal_force: f64, longitudinal_force: f64) -> MeanState {
    MeanState {
        normal_force,
        longitudinal: match scene.creepage_x {
            Some(xi) => Longitudinal::Creepage(xi),
            None => Longitudinal::Force(longitudinal_force),
        },
        creepage_y: scene.creepage_y,
        spin: scene.spin,
        speed: scene.speed,
        friction: scene.material.friction,
        characteristic: scene.material.characteristic,
        memory: scene.material.memory,
    }
}

/// The default excitation for `mean` on `scene` (all four inputs): the
/// constants above in patch lengths of the mean patch; a run-in of
/// [`CREEPAGE_RUN_IN`] patch lengths where the creepage is
/// prescribed (the exact theory's force settles slowly at a prescribed
/// creepage from the virgin start); the step of the scene's passage (the
/// fixed grid's element on the fixed grid); the largest reduced frequency
/// [`MAX_REDUCED`] or ten steps per wavelength, the smaller.
pub fn default_excitation(
    scene: &Scene,
    shape: &HertzShape,
    mean: &MeanState,
) -> Result<Excitation, CreepResponseError> {
    let a0 = shape.patch(mean.normal_force).map_err(|e| CreepResponseError::Input(e.to_string()))?.a;
    let step = scene.contact.model.fixed_grid().map_or(scene.step_length, |f| f.dx);
    let run_in = match mean.longitudinal {
        Longitudinal::Force(_) => RUN_IN_PATCHES,
        Longitudinal::Creepage(_) => CREEPAGE_RUN_IN,
    };
    Ok(Excitation {
        step,
        period: PERIOD_PATCHES * 2.0 * a0,
        max_reduced: MAX_REDUCED.min(2.0 * std::f64::consts::PI * a0 / (10.0 * step)),
        run_in: run_in * 2.0 * a0,
        lead: LEAD_PATCHES * 2.0 * a0,
        level: LEVEL,
        inputs: [true; 4],
    })
}

/// The scene's Hertz shape.
pub fn shape(scene: &Scene) -> HertzShape {
    HertzShape::new(scene.geometry.curvatures(), scene.material.elastic).expect("validated geometry")
}

/// The scene's tangential solver, built afresh per call (for the
/// measurement's runs).
pub type SolverOf<'a> = &'a (dyn Fn() -> Box<dyn TangentialSolver> + Sync);

/// The response of `scene`'s contact about `mean`, measured with the
/// scene's own solver (`make` builds one, the passages' model and grid) as
/// `excitation` says.
pub fn response(
    scene: &Scene,
    mean: &MeanState,
    excitation: &Excitation,
    make: SolverOf,
) -> Result<CreepResponse, CreepResponseError> {
    measure(make, &shape(scene), mean, excitation)
}

/// The response of `scene`'s contact for a wheel of mean normal force
/// `normal_force` and mean longitudinal force `longitudinal_force` (N;
/// unused where the scene prescribes the creepage), with the default
/// excitation, for the `inputs` asked (per [`crate::dynamics::coupling::creep_response::Input`]; the
/// torsional loop needs the longitudinal creepage and the normal force,
/// `[true, false, false, true]`, about a third of the cost of all four):
/// what replaces the steady slopes of
/// [`crate::dynamics::wheelset::torsion::TorsionFeedback`].
///
/// A response is measured once per process for the same contact, mean
/// state and excitation (the passage models a spectrum's threads build, a
/// test's studies of one scene): the measurement is deterministic, so the
/// table taken from [`MEASURED`] is the one measuring it again would give,
/// bit for bit.
pub fn default_response(
    scene: &Scene,
    normal_force: f64,
    longitudinal_force: f64,
    inputs: [bool; 4],
    make: SolverOf,
) -> Result<CreepResponse, CreepResponseError> {
    let mean = mean_state(scene, normal_force, longitudinal_force);
    let excitation = Excitation { inputs, ..default_excitation(scene, &shape(scene), &mean)? };
    let key = fingerprint(scene, &mean, &excitation);
    let found = MEASURED.lock().ok().and_then(|m| m.iter().find(|(k, _)| *k == key).map(|(_, r)| r.clone()));
    if let Some(r) = found {
        return Ok(r);
    }
    let r = response(scene, &mean, &excitation, make)?;
    if let Ok(mut m) = MEASURED.lock() {
        if m.len() == MEASURED_KEPT {
            m.remove(0);
        }
        m.push((key, r.clone()));
    }
    Ok(r)
}

/// How many measured responses [`MEASURED`] keeps (the latest).
const MEASURED_KEPT: usize = 8;

/// The responses measured in this process, each with its [`fingerprint`].
static MEASURED: std::sync::Mutex<Vec<(String, CreepResponse)>> = std::sync::Mutex::new(Vec::new());

/// Everything a response depends on, as text (`Debug` writes each `f64`
/// so that it reads back to the same bits): the mean state, the
/// excitation, and the parts of the scene the solver and its grid are
/// built from (the contact, the material, the geometry, the loads, the
/// rail's grid, the track and the vehicle). Left out, as they do not enter
/// the contact's solver: the roughness, the wear law, the traffic and
/// passage counts, the output.
fn fingerprint(scene: &Scene, mean: &MeanState, excitation: &Excitation) -> String {
    let growth = scene.growth.as_ref().map(|g| (g.dynamics, g.directions, &g.classes));
    format!(
        "{mean:?} {excitation:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {growth:?}",
        scene.contact,
        scene.material,
        scene.geometry,
        (scene.speed, scene.creepage_x, scene.creepage_y, scene.spin),
        scene.loads,
        (scene.start, scene.end, scene.step_length),
        scene.rail,
        scene.track,
        scene.vehicle,
        scene.wheelset,
        scene.second_rail,
        scene.growth.is_some(),
    )
}
