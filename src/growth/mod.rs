//! Long-term corrugation growth on a periodic stretch of rail (book:
//! docs/src/theory/growth-loop.md): the outer loop over wheel passages
//!
//! ```text
//! r_n(X, Y) -> N_n(X) = imposed + dynamic(r_n) -> passage -> W_n(X, Y)
//!           -> r_{n+1} = r_n - m W_n
//! ```
//!
//! One simulated passage stands for `m` real ones (traffic scaling). The
//! stretch `[x_min, x_min + L)` is periodic: the patch starts a run-in before
//! it, in the contact state the previous lap would have left, and the wear of
//! the patch positions inside the stretch is folded onto the periodic grid,
//! so every node receives exactly one full passage of the patch.

mod hertz_check;
pub mod mix;
pub mod record;
pub mod roughness;
mod row;
pub mod state;
pub mod stop;
pub mod study;
pub mod traffic;
pub mod wear_map;

use crate::contact::grid::RailSurface;
use crate::contact::{RailContact, TangentialSolver};
use crate::dynamics::{ContactSignals, ContactVariations, TrackDynamics};
use crate::hertz::HertzShape;
use crate::loads::ImposedLoads;
use crate::metrics::centre_row;
use crate::params::NormalContact;
use crate::passage::{PassageError, PassageResult, PassageSpec, PatchHistory, PeriodicSignal, run_passage};
use crate::rail_grid::RailGrid;
use crate::wear::WearKernel;
use ndarray::Array2;
use std::sync::Arc;

/// Wear on an extended grid (same node lattice) folded onto the periodic
/// grid `grid` (node x_min + i dx, i = 0..nx, period nx dx).
pub fn fold_periodic(ext: &Array2<f64>, ext_grid: &RailGrid, grid: &RailGrid) -> Array2<f64> {
    let mut out = Array2::zeros((grid.ny, grid.nx));
    let n = grid.nx as i64;
    for i in 0..ext_grid.nx {
        let k = ((ext_grid.x(i) - grid.x_min) / grid.dx).round() as i64;
        let col = k.rem_euclid(n) as usize;
        for j in 0..grid.ny {
            out[[j, col]] += ext[[j, i]];
        }
    }
    out
}

/// The Hertz semi-axes (a, b) (m) of a study's mean patch, across which
/// its contact-filtered line is weighted: of the mean load, or under mixed
/// traffic the classes' patches weighted by their shares (one line for
/// every passage, so that growth rates compare across passages of
/// different classes).
pub fn mean_patch(scene: &crate::params::Scene, shape: &HertzShape) -> (f64, f64) {
    let patch = |n: f64| shape.patch(n).expect("validated loads keep N > 0");
    match scene.growth.as_ref().map(|g| g.classes.as_slice()) {
        Some(classes) if !classes.is_empty() => classes.iter().fold((0.0, 0.0), |(a, b), c| {
            let p = patch(c.normal_force);
            (a + c.share * p.a, b + c.share * p.b)
        }),
        _ => {
            let p = patch(scene.loads.normal_force);
            (p.a, p.b)
        }
    }
}

/// The centre-line profile seen by the wheel: the profile averaged across
/// the patch width with the Hertz line-load weight: the pressure integrated
/// along x, `int p dx = (pi/2) a p0 (1 - (y/b)^2)`, so the weight is
/// `1 - (y/b)^2` (the profile as the pressure-weighted patch sees it across
/// the rail).
pub fn contact_filtered_line(profile: &Array2<f64>, grid: &RailGrid, b: f64) -> Vec<f64> {
    let weights: Vec<(usize, f64)> =
        (0..grid.ny).map(|j| (j, (1.0 - (grid.y(j) / b).powi(2)).max(0.0))).filter(|(_, w)| *w > 0.0).collect();
    if weights.is_empty() {
        return profile.row(centre_row(grid)).to_vec();
    }
    let total: f64 = weights.iter().map(|(_, w)| w).sum();
    (0..grid.nx).map(|i| weights.iter().map(|(j, w)| w * profile[[*j, i]]).sum::<f64>() / total).collect()
}

/// The equivalent roughness of the profile under the surface set on
/// `solver`: the rigid approach that holds the mean load `force` (N) with
/// the patch centre at `x_min + j step`, `j < n`, negated and less its
/// mean, so that it is the height of a point rail that the wheel would
/// follow: the contact filter derived from the contact itself (Remington
/// and Thompson's idea, without their assumed weighting).
///
/// Its linear limit (small profile, fixed load N): the approach is
/// `dPi/dN` of the contact's complementary energy, and a gap change `-r`
/// changes that energy by `-int p r dA`, so the approach changes by
/// `-int (dp/dN) r dA`: the profile averaged with the weight `dp/dN`, the
/// pressure increment of a load increment. For a Hertz ellipse that is
/// the rigid flat punch's `1 / (2 pi a b sqrt(1 - x^2/a^2 - y^2/b^2))`,
/// whose line load along x is uniform: a profile uniform across the rail
/// is averaged over the patch length, `sin(k a) / (k a)` for a harmonic
/// (tests/profile_contact.rs: within 6e-4 at 16-100 mm). Beyond it the
/// filter is nonlinear: the patch splits and leaves the troughs.
pub fn equivalent_roughness(
    solver: &mut dyn TangentialSolver,
    x_min: f64,
    step: f64,
    n: usize,
    force: f64,
) -> Result<Vec<f64>, PassageError> {
    let positions: Vec<f64> = (0..n).map(|j| x_min + j as f64 * step).collect();
    let approach = solver.approaches(&positions, force).map_err(|(j, source)| PassageError::Approach {
        x: positions[j],
        normal_force: force,
        source,
    })?;
    let mean = approach.iter().sum::<f64>() / n.max(1) as f64;
    Ok(approach.iter().map(|d| mean - d).collect())
}

/// The equivalent roughness of the linear profile contact: the profile
/// averaged over the Hertz ellipse `a x b` (m) of the mean load with the
/// weight `dp/dN`, the rigid flat punch's pressure per unit load
/// `1 / (2 pi a b sqrt(1 - x^2/a^2 - y^2/b^2))`, less its mean
/// (the linear limit of [`equivalent_roughness`], derived there). Per
/// harmonic `R_k(y) exp(i k X)` of the rows the average along x over the
/// chord `2 a c`, `c = sqrt(1 - y^2/b^2)`, is `J0(k a c) / (2 b)` per unit
/// width, so
///
/// ```text
/// r_eq(X) = sum_k exp(i k X) int_{-b}^{b} J0(k a sqrt(1 - y^2/b^2)) R_k(y) dy / (2 b),
/// ```
///
/// which for a profile uniform across the rail is `sin(k a) / (k a)` per
/// harmonic (the identity `int_0^1 J0(z sqrt(1 - t^2)) dt = sin z / z`).
/// Rows enter with the part of their cell inside `|y| < b`.
pub fn linear_roughness(profile: &Array2<f64>, grid: &RailGrid, a: f64, b: f64) -> Vec<f64> {
    use num_complex::Complex64;
    use rustfft::FftPlanner;
    let n = grid.nx;
    let mut planner = FftPlanner::new();
    let (fwd, inv) = (planner.plan_fft_forward(n), planner.plan_fft_inverse(n));
    let mut total = vec![Complex64::default(); n];
    for j in 0..grid.ny {
        let y = grid.y(j);
        let width = ((y + 0.5 * grid.dy).min(b) - (y - 0.5 * grid.dy).max(-b)).max(0.0);
        if width == 0.0 {
            continue;
        }
        let c = (1.0 - (y / b).powi(2)).max(0.0).sqrt();
        let mut row: Vec<Complex64> = profile.row(j).iter().map(|v| Complex64::new(*v, 0.0)).collect();
        fwd.process(&mut row);
        for (k, v) in row.iter().enumerate().skip(1) {
            // Wavenumber of bin k (the upper half are the negative ones).
            let m = if k <= n / 2 { k as f64 } else { (n - k) as f64 };
            let wave = 2.0 * std::f64::consts::PI * m / (n as f64 * grid.dx);
            total[k] += v * (libm::j0(wave * a * c) * width / (2.0 * b));
        }
    }
    inv.process(&mut total);
    total.iter().map(|v| v.re / n as f64).collect()
}

/// What one growth passage produced.
#[derive(Debug, Clone)]
pub struct GrowthPass {
    /// What it left on each rail: the first rail's, then the wheelset's
    /// second rail's where it has one.
    pub rails: Vec<RailPass>,
    /// Steps at which the fixed grid's CG solver handed over to
    /// Gauss-Seidel, summed over every wheel of every rail.
    pub fallback_steps: usize,
    /// Whether the passage took the linear profile contact (its pressure
    /// and its equivalent roughness); otherwise the nonlinear one (or
    /// Hertz's).
    pub linear_contact: bool,
    /// Why `Auto`'s linear contact stopped, if it did and the passage was
    /// run again with the nonlinear contact.
    pub rerun: Option<String>,
}

/// What one growth passage left on one rail.
#[derive(Debug, Clone)]
pub struct RailPass {
    /// Its leading wheel's passage on the extended grid (history, unfolded
    /// wear; its own fallback steps).
    pub leading: PassageResult,
    /// Its other wheels' patch histories (a vehicle of several wheels),
    /// the second wheel first (empty for one wheel).
    pub wheel_histories: Vec<PatchHistory>,
    /// Wear of one simulated wheel passage on the periodic grid (m): with
    /// several wheels, the mean of theirs.
    pub wear: Array2<f64>,
    /// Its leading wheel's dynamic normal force on the periodic grid (N).
    pub dynamic_force: Vec<f64>,
    /// Steps inside the stretch where a wheel left the rail (N <= 0),
    /// summed over its wheels: the linear track model is not valid there.
    pub contact_loss_steps: usize,
    /// Steps at which the linear profile contact's pressure vanished well
    /// inside the patch, summed over its wheels: the linearisation beyond
    /// its range.
    pub clipped_steps: usize,
}

/// The largest curvature of the corrugation, relative to the wheel's
/// (`R max |r''|`), up to which `contact.normal = "auto"` on the fixed grid
/// takes the linear profile contact; beyond, the nonlinear profile contact.
/// On the validity map of the linear contact (`scripts/validity_map.sh`
/// with `CANDIDATE=linear`, growth_exact.toml's scene, 0.4 mm grid), where
/// the nonlinear contact is above its noise floor (5 um and more), the two
/// contacts' first harmonics of the wear differ by 4-11 % up to `R r'' =
/// 0.5` (20 mm at 10 um) and by up to 35 % beyond (20 mm at 20 um, `R r''
/// = 1`). 1 um rms of random roughness from 10 mm up has `R max |r''|` of
/// 0.3.
pub const LINEAR_CONTACT_CURVATURE: f64 = 0.5;

/// Runs one passage over the periodic stretch with the current `profile`:
/// the dynamic force of the profile as the contact sees it (if `dynamics`)
/// adds to the imposed loads; wear is deposited for patch positions inside
/// the stretch and folded onto `grid`.
///
/// What the contact sees (`normal`): with [`NormalContact::Hertz`] the
/// profile weighted across the mean patch width by the Hertz line load
/// ([`contact_filtered_line`]), the contact itself Hertzian; with
/// [`NormalContact::Linear`] the corrugation (less the harmonics the
/// contact does not resolve, [`RailSurface::corrugation_above`]) in the
/// linear profile contact of every step and the dynamics see its
/// [`linear_roughness`]; with [`NormalContact::Profile`] the corrugation is
/// in the nonlinear normal problem of every step and the dynamics see its
/// [`equivalent_roughness`] at the mean load; [`NormalContact::Auto`] (the
/// fixed grid's: the adapted mesh's is resolved to `Linear` by the
/// caller) is `Linear` while the corrugation's curvature is below
/// [`LINEAR_CONTACT_CURVATURE`] of the wheel's, `Profile` beyond.
///
/// With several wheels on the rail (`dynamics` coupling them,
/// [`crate::dynamics::model`]) every wheel runs over the whole stretch
/// with its own dynamic force, and the wear is their mean: one wheel
/// passage, whose traffic counts wheel passages; the history is the
/// leading wheel's. `progress` counts the steps of all the wheels.
///
/// A passage `Auto` gives the linear contact that stops at a step (a long
/// wave that moves the patch by half of it while its curvature is small,
/// which the linearisation refuses, [`crate::contact::ContactError::LinearRange`]; or a
/// patch beyond the block of the grid the linear contact runs on) is run
/// again with the nonlinear contact ([`GrowthPass::rerun`]).
#[allow(clippy::too_many_arguments)]
pub fn growth_passage(
    spec: &PassageSpec,
    shape: &HertzShape,
    solver: &mut dyn TangentialSolver,
    deposit: &dyn WearKernel,
    grid: &RailGrid,
    profile: &Array2<f64>,
    normal: NormalContact,
    dynamics: Option<&dyn TrackDynamics>,
    record_fields: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<GrowthPass, PassageError> {
    let rails = [Rail { spec, profile }];
    growth_passage_rails(&rails, shape, solver, None, deposit, grid, normal, dynamics, record_fields, progress)
}

/// One rail of a growth passage: its passage (loads, creepages, spin) and
/// its profile.
#[derive(Debug, Clone, Copy)]
pub struct Rail<'a> {
    /// The passage of its wheels.
    pub spec: &'a PassageSpec,
    /// Its profile (m).
    pub profile: &'a Array2<f64>,
}

/// [`growth_passage`] of a wheelset on `rails` (the first rail first; a
/// second where the dynamics couples the wheelset's two contacts,
/// [`crate::dynamics::model`]): each rail's wheel runs over its
/// own profile with its own steady state and its own dynamic variations,
/// and wears its own rail. `Auto` takes the linear contact where every
/// rail's corrugation allows it. With `second_solver` (a solver like
/// `solver`) the two rails' wheels run at once, one on each (the same
/// results: every passage starts from a reset solver).
#[allow(clippy::too_many_arguments)]
pub fn growth_passage_rails<'o>(
    rails: &[Rail],
    shape: &HertzShape,
    solver: &mut dyn TangentialSolver,
    mut second_solver: Option<&mut (dyn TangentialSolver + 'o)>,
    deposit: &dyn WearKernel,
    grid: &RailGrid,
    normal: NormalContact,
    dynamics: Option<&dyn TrackDynamics>,
    record_fields: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<GrowthPass, PassageError> {
    // Auto: the linear contact while the curvature of the corrugation it
    // sees is small against the wheel's (the raw profile's second
    // differences see the wear's rounding at the rail cells' scale too).
    let surfaces = |solver: &dyn TangentialSolver| -> Vec<RailSurface> {
        rails
            .iter()
            .map(|r| {
                let a = shape.patch(r.spec.loads.normal_force).map(|p| p.a).unwrap_or(0.0);
                linear_surface(r.profile, grid, solver, a)
            })
            .collect()
    };
    let linear = match normal {
        NormalContact::Linear { .. } => Some(surfaces(&*solver)),
        NormalContact::Auto { .. } => Some(surfaces(&*solver)).filter(|all| {
            all.iter().all(|s| {
                let (crest, trough) = s.curvature_range();
                trough.max(-crest) < LINEAR_CONTACT_CURVATURE * 2.0 * shape.curvatures().a
            })
        }),
        _ => None,
    }
    .map(|all| all.into_iter().map(Arc::new).collect::<Vec<_>>());
    let auto = matches!(normal, NormalContact::Auto { .. });
    let mut run = |linear| {
        let second = second_solver.as_deref_mut();
        passage_with(rails, shape, solver, second, deposit, grid, normal, linear, dynamics, record_fields, progress)
    };
    match run(linear.clone()) {
        Err(e @ PassageError::Tangential { .. }) if auto && linear.is_some() => {
            run(None).map(|g| GrowthPass { rerun: Some(e.to_string()), ..g })
        }
        result => result,
    }
}

/// The corrugation the linear contact sees: less the harmonics shorter than
/// it resolves on a patch of semi-axis `a` (m). Aliased on its normal mesh
/// they would drive wear at the mesh's scale (measured: a 1.5-1.8 mm
/// pattern growing out of rounding on growth_fastsim.toml's 40 x 40 mesh).
fn linear_surface(profile: &Array2<f64>, grid: &RailGrid, solver: &dyn TangentialSolver, a: f64) -> RailSurface {
    RailSurface::corrugation_above(profile, grid, solver.linear_resolution(a).unwrap_or(0.0))
}

/// [`growth_passage_rails`] in the linear contact over each rail's surface
/// `linear`, or without it in the one `normal` names.
#[allow(clippy::too_many_arguments)]
fn passage_with<'o>(
    rails: &[Rail],
    shape: &HertzShape,
    solver: &mut dyn TangentialSolver,
    mut second_solver: Option<&mut (dyn TangentialSolver + 'o)>,
    deposit: &dyn WearKernel,
    grid: &RailGrid,
    normal: NormalContact,
    linear: Option<Vec<Arc<RailSurface>>>,
    dynamics: Option<&dyn TrackDynamics>,
    record_fields: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<GrowthPass, PassageError> {
    let length = grid.nx as f64 * grid.dx;
    let linear_contact = linear.is_some();
    // Each rail's surface in the normal problem of every step.
    let seen_by = match (normal, &linear) {
        (NormalContact::Hertz, _) => Seen::HertzLine,
        (_, Some(_)) => Seen::Linear,
        _ => Seen::Profile,
    };
    let surfaces: Vec<Option<RailContact>> = rails
        .iter()
        .enumerate()
        .map(|(r, rail)| match (seen_by, &linear) {
            (Seen::HertzLine, _) => None,
            (_, Some(l)) => Some(RailContact::Linear(l[r].clone())),
            _ => Some(RailContact::Profile(Arc::new(RailSurface::corrugation(rail.profile, grid)))),
        })
        .collect();
    // The solver's surface is the rail's whose wheel it solves.
    let mut current: Option<usize> = None;
    let mut use_rail = |solver: &mut dyn TangentialSolver, r: usize| -> Result<(), PassageError> {
        if current != Some(r)
            && let Some(surface) = &surfaces[r]
        {
            solver.set_surface(Some(surface.clone())).map_err(PassageError::Surface)?;
        }
        current = Some(r);
        Ok(())
    };
    // Each wheel's rail and loads, and the profile it sees at its mean load
    // (the same for wheels of the same load on the same rail).
    let wheels = dynamics.map_or(1, |d| d.wheels());
    let rail_of: Vec<usize> = (0..wheels).map(|w| dynamics.map_or(0, |d| d.rail_of(w))).collect();
    let loads: Vec<ImposedLoads> = (0..wheels)
        .map(|w| {
            let spec = rails[rail_of[w]].spec;
            match spec.wheel_loads.get(w) {
                Some(l) if rail_of[w] == 0 => l.clone(),
                _ => spec.loads.clone(),
            }
        })
        .collect();
    // The two rails' wheels at once, each on its own solver (the second
    // rail's holds its surface throughout).
    let parallel = rails.len() == 2 && rail_of.contains(&1) && second_solver.is_some();
    if parallel && let (Some(other), Some(surface)) = (second_solver.as_deref_mut(), &surfaces[1]) {
        other.set_surface(Some(surface.clone())).map_err(PassageError::Surface)?;
    }
    let mut seen: Vec<Vec<f64>> = Vec::with_capacity(wheels);
    for (w, l) in loads.iter().enumerate() {
        let same = (0..w).find(|&o| rail_of[o] == rail_of[w] && loads[o].normal_force == l.normal_force);
        let line = match same {
            Some(o) => seen[o].clone(),
            None => {
                let rail = &rails[rail_of[w]];
                let on: &mut dyn TangentialSolver = match second_solver.as_deref_mut() {
                    Some(other) if parallel && rail_of[w] == 1 => other,
                    _ => {
                        use_rail(solver, rail_of[w])?;
                        &mut *solver
                    }
                };
                seen_profile(
                    seen_by,
                    on,
                    rail.profile,
                    grid,
                    shape,
                    l.normal_force,
                    rail.spec.step_length,
                    dynamics.is_some(),
                )?
            }
        };
        seen.push(line);
    }
    // Each wheel's force when it is at X (one wheel without dynamics), and
    // where the dynamics has every direction, its creep force's and
    // creepages' variations.
    let speed = rails[0].spec.speed;
    let variations = dynamics.map(|d| d.contact_variations(&seen, grid.dx, speed));
    let forces: Vec<Vec<f64>> = match &variations {
        Some(v) => v.iter().map(|c| c.normal().to_vec()).collect(),
        None => vec![vec![0.0; grid.nx]],
    };
    let signals: Option<Vec<&ContactSignals>> =
        variations.as_ref().and_then(|v| v.iter().map(ContactVariations::every).collect());
    // Extended grid on the same lattice, wide enough for the largest patch
    // of this passage (imposed plus dynamic normal force, of any wheel), so
    // no wear is clipped at its ends.
    let peak_force = forces
        .iter()
        .zip(&loads)
        .map(|(f, l)| l.max_normal_force() + f.iter().fold(0.0f64, |m, v| m.max(v.abs())))
        .fold(0.0f64, f64::max);
    let a_max = shape.patch(peak_force).map(|p| p.a).unwrap_or(0.0);
    let a_max = a_max * normal.grid_scale();
    let reach = (a_max / grid.dx).ceil() as usize + 2;
    let ext = RailGrid { x_min: grid.x_min - reach as f64 * grid.dx, nx: grid.nx + 2 * reach, ..grid.clone() };
    // Every wheel over the whole stretch with its own force; the wear of
    // one wheel passage is the mean of its rail's wheels (wheel passages
    // are the traffic).
    let window = grid.x_min..grid.x_min + length;
    let mut wear = vec![Array2::zeros((grid.ny, grid.nx)); rails.len()];
    let mut on_rail = vec![0usize; rails.len()];
    let (mut contact_loss_steps, mut clipped_steps) = (vec![0; rails.len()], vec![0; rails.len()]);
    let mut fallback_steps = 0;
    let mut leading: Vec<Option<PassageResult>> = vec![None; rails.len()];
    let mut wheel_histories = vec![Vec::new(); rails.len()];
    let wheel_spec = |w: usize, force: &Vec<f64>| -> PassageSpec {
        let r = rail_of[w];
        let mut spec = rails[r].spec.clone();
        spec.surface = surfaces[r].clone();
        spec.wear_window = (grid.x_min, grid.x_min + length);
        spec.loads = loads[w].clone();
        spec.dynamic_normal_force = Some(PeriodicSignal { x0: grid.x_min, dx: grid.dx, values: force.clone() });
        let signal = |values: &Vec<f64>| Some(PeriodicSignal { x0: grid.x_min, dx: grid.dx, values: values.clone() });
        if let Some(c) = signals.as_ref().map(|s| &s[w]) {
            // The dynamics in every direction: the creepage's variation
            // (creepage control), or the force's (force control: the
            // contact solver finds the creepage), the lateral creepage's
            // and the spin's.
            if spec.creepage_x.is_some() {
                spec.dynamic_creepage_x = signal(&c.creepage_x);
            } else {
                spec.dynamic_longitudinal_force = signal(&c.force_x);
            }
            spec.dynamic_creepage_y = signal(&c.creepage_y);
            // The spin's variation (zeros without the spin's channel: the
            // spin then stays the mean's, bit for bit).
            if c.spin.iter().any(|v| *v != 0.0) {
                spec.dynamic_spin = signal(&c.spin);
            }
        }
        // The wheelset's torsion: the creepage's answer to the normal
        // force's variation (the imposed harmonics' and the dynamic force).
        let torsion = spec.torsion.get(w).or(spec.torsion.first()).filter(|_| dynamics.is_some() && signals.is_none());
        spec.dynamic_creepage_x = spec.dynamic_creepage_x.take().or_else(|| {
            torsion.map(|t| {
                let variation: Vec<f64> = grid
                    .xs()
                    .iter()
                    .zip(force)
                    .map(|(x, f)| f + spec.loads.normal_force_at(*x) - spec.loads.normal_force)
                    .collect();
                PeriodicSignal { x0: grid.x_min, dx: grid.dx, values: t.creepage(&variation, grid.dx, spec.speed) }
            })
        });
        spec
    };
    let specs: Vec<PassageSpec> = forces.iter().enumerate().map(|(w, f)| wheel_spec(w, f)).collect();
    let passages: Vec<PassageResult> = match second_solver {
        Some(other) if parallel => {
            // Each rail's wheels one after the other, the rails side by
            // side; the progress is the first rail's.
            use_rail(solver, 0)?;
            let order = &rail_of;
            let on = move |r: usize| (0..wheels).filter(move |&w| order[w] == r);
            let first_wheels = on(0).count();
            let (first, second) = std::thread::scope(|scope| {
                let second = scope.spawn(|| {
                    on(1)
                        .map(|w| {
                            run_passage(&specs[w], shape, &mut *other, deposit, &ext, record_fields, &mut |_, _| {})
                        })
                        .collect::<Result<Vec<_>, _>>()
                });
                let first = on(0)
                    .enumerate()
                    .map(|(k, w)| {
                        let mut report = |done: usize, total: usize| progress(k * total + done, first_wheels * total);
                        run_passage(&specs[w], shape, &mut *solver, deposit, &ext, record_fields, &mut report)
                    })
                    .collect::<Result<Vec<_>, _>>();
                (first, second.join().expect("the second rail's passages do not panic"))
            });
            // Back in the wheels' order: the first rail's, then the second's.
            let (mut first, mut second) = (first?.into_iter(), second?.into_iter());
            rail_of
                .iter()
                .map(|&r| if r == 0 { first.next() } else { second.next() }.expect("a passage per wheel"))
                .collect()
        }
        _ => {
            let mut out = Vec::with_capacity(wheels);
            for (w, spec) in specs.iter().enumerate() {
                use_rail(solver, rail_of[w])?;
                let mut report = |done: usize, total: usize| progress(w * total + done, wheels * total);
                out.push(run_passage(spec, shape, solver, deposit, &ext, record_fields, &mut report)?);
            }
            out
        }
    };
    for (w, passage) in passages.into_iter().enumerate() {
        let r = rail_of[w];
        let mut folded = fold_periodic(&passage.wear, &ext, grid);
        if let Some(pitch) = deposit.pitch().filter(|p| *p > grid.dx * (1.0 + 1e-9)) {
            crate::wear::deposit::band_limit(&mut folded, grid.dx, pitch);
        }
        wear[r] += &folded;
        on_rail[r] += 1;
        let h = &passage.history;
        contact_loss_steps[r] +=
            h.x_c.iter().zip(&h.in_contact).filter(|(x, c)| window.contains(*x) && **c == 0.0).count();
        clipped_steps[r] += passage.clipped_steps;
        fallback_steps += passage.fallback_steps;
        match &leading[r] {
            None => leading[r] = Some(passage),
            Some(_) => wheel_histories[r].push(passage.history),
        }
    }
    for (wear, n) in wear.iter_mut().zip(&on_rail) {
        if *n > 1 {
            *wear /= *n as f64;
        }
    }
    // Each rail's leading wheel, its other wheels' histories, its wear and
    // its leading wheel's dynamic force.
    let rails = leading
        .into_iter()
        .zip(wheel_histories)
        .zip(wear)
        .enumerate()
        .map(|(r, ((lead, wheel_histories), wear))| {
            let w = rail_of.iter().position(|&q| q == r).expect("a wheel on every rail");
            RailPass {
                leading: lead.expect("a passage per rail"),
                wheel_histories,
                wear,
                dynamic_force: forces[w].clone(),
                contact_loss_steps: contact_loss_steps[r],
                clipped_steps: clipped_steps[r],
            }
        })
        .collect();
    Ok(GrowthPass { rails, fallback_steps, linear_contact, rerun: None })
}

/// How a passage's dynamics sees the profile (module docs of
/// [`growth_passage`]).
#[derive(Debug, Clone, Copy)]
enum Seen {
    /// The profile weighted across the patch by the Hertz line load.
    HertzLine,
    /// The linear profile contact's flat-punch average.
    Linear,
    /// The nonlinear profile contact's equivalent roughness.
    Profile,
}

/// The profile a wheel of mean load `force` (N) sees, as `seen` says, on
/// the rail grid's nodes; zero where there are no dynamics to see it.
#[allow(clippy::too_many_arguments)]
fn seen_profile(
    seen: Seen,
    solver: &mut dyn TangentialSolver,
    profile: &Array2<f64>,
    grid: &RailGrid,
    shape: &HertzShape,
    force: f64,
    step_length: f64,
    dynamics: bool,
) -> Result<Vec<f64>, PassageError> {
    let patch = shape.patch(force);
    Ok(match seen {
        Seen::HertzLine => contact_filtered_line(profile, grid, patch.map(|p| p.b).unwrap_or(grid.half_width)),
        _ if !dynamics => vec![0.0; grid.nx],
        Seen::Linear => match patch {
            Ok(p) => linear_roughness(profile, grid, p.a, p.b),
            Err(_) => vec![0.0; grid.nx],
        },
        Seen::Profile => {
            let length = grid.nx as f64 * grid.dx;
            let n = (length / step_length).round().max(1.0) as usize;
            let step = length / n as f64;
            let r = equivalent_roughness(solver, grid.x_min, step, n, force)?;
            let signal = PeriodicSignal { x0: grid.x_min, dx: step, values: r };
            grid.xs().iter().map(|x| signal.at(*x)).collect()
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_roughness_is_the_flat_punch_average_of_the_profile() {
        // Uniform across the rail: sin(k a) / (k a) per harmonic (closed
        // form). Varying across: against a direct quadrature of
        // int r dp/dN dA over the ellipse (rho = sin phi, midpoint rules).
        let (a, b) = (6e-3, 10e-3);
        let grid = RailGrid { x_min: 0.0, dx: 2e-4, nx: 600, half_width: 0.012, dy: 1e-4, ny: 241 };
        for wavelength in [0.015, 0.024, 0.06] {
            let k = 2.0 * std::f64::consts::PI / wavelength;
            let uniform = Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| (k * grid.x(i)).cos());
            let eq = linear_roughness(&uniform, &grid, a, b);
            let expected = (k * a).sin() / (k * a);
            // The rows' cells resolve the weight across to O(dy^1.5).
            assert!((eq[0] - expected).abs() < 2e-3, "{wavelength}: {} vs {expected}", eq[0]);
            let shaped = |x: f64, y: f64| (k * x).cos() * (1.0 + 3.0 * (y / b).powi(2));
            let varying = Array2::from_shape_fn((grid.ny, grid.nx), |(j, i)| shaped(grid.x(i), grid.y(j)));
            let eq = linear_roughness(&varying, &grid, a, b);
            let (nphi, ntheta) = (400, 400);
            let mut direct = 0.0;
            for p in 0..nphi {
                let phi = (p as f64 + 0.5) * 0.5 * std::f64::consts::PI / nphi as f64;
                for t in 0..ntheta {
                    let theta = (t as f64 + 0.5) * 2.0 * std::f64::consts::PI / ntheta as f64;
                    let (x, y) = (a * phi.sin() * theta.cos(), b * phi.sin() * theta.sin());
                    direct += phi.sin() * shaped(x, y);
                }
            }
            direct *= 0.5 * std::f64::consts::PI / nphi as f64 / ntheta as f64;
            // (The stretch holds whole wavelengths: the profile's mean is 0.)
            assert!((eq[0] - direct).abs() < 5e-3 * direct.abs(), "{} vs {direct}", eq[0]);
        }
    }

    #[test]
    fn filtered_line_is_the_line_load_weighted_mean_across_the_patch() {
        // Uniform across the head: the line itself. A profile (y/b)^2: the
        // mean of u^2 under the weight 1 - u^2 is (2/3 - 2/5) / (4/3) = 1/5.
        let grid = RailGrid { x_min: 0.0, dx: 1e-3, nx: 3, half_width: 0.012, dy: 1e-5, ny: 2401 };
        let b = 0.01;
        let flat = Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| i as f64);
        assert!(contact_filtered_line(&flat, &grid, b).iter().enumerate().all(|(i, v)| (v - i as f64).abs() < 1e-12));
        let bowl = Array2::from_shape_fn((grid.ny, grid.nx), |(j, _)| (grid.y(j) / b).powi(2));
        let line = contact_filtered_line(&bowl, &grid, b);
        assert!((line[0] - 0.2).abs() < 1e-6, "{}", line[0]);
    }
}
