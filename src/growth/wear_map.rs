//! The wear of one passage as a function of the rails it runs on,
//! `r -> W(r)`: the growth loop's model chain (dynamics -> contact -> wear,
//! [`super::growth_passage_rails`]) with its kernels built once for a
//! scene, one traffic class at a time.
//!
//! The growth study ([`super::study`]) calls it once per simulated
//! passage; the linear growth spectrum ([`crate::spectrum`]) calls it about
//! a rail and its perturbations. Both see the same passage, so the
//! spectrum's linearisation is the study's own map.
//!
//! The wear of the smooth rail, `W_0 = W(0)`, is the forced part of every
//! passage's wear (`W(r) = W_0 + J r + ...`): on discrete supports the
//! sleeper passing, and any imposed load harmonic, wear a pattern into a
//! rail that has none. [`WearMap::forced`] computes it once per class.

use super::{GrowthPass, Rail, growth_passage_rails};
use crate::build::{Derived, DynamicsError, build_deposit, build_solver, derive, study_grid, track_dynamics};
use crate::contact::{Elements, TangentialSolver};
use crate::dynamics::TrackDynamics;
use crate::params::{NormalContact, Scene, TrafficClass};
use crate::passage::{PassageError, PassageResult, PassageSpec, run_passage};
use crate::rail_grid::RailGrid;
use crate::wear::WearKernel;
use ndarray::Array2;

/// One traffic class's passage (speed, mean loads) and track dynamics
/// (speed, contact spring at its load, unsprung mass).
struct ClassModel {
    passage: PassageSpec,
    /// The passage of the wheelset's second rail, where it has one.
    second_passage: Option<PassageSpec>,
    dynamics: Option<Box<dyn TrackDynamics>>,
    /// The wear one passage of the class leaves on the smooth rails (the
    /// first's, then the second's) (m), once computed.
    forced: Option<Vec<Array2<f64>>>,
}

/// The passage's wear as a function of the rails' profiles, for each
/// traffic class of a scene (a study without `[traffic]` has one).
pub struct WearMap {
    d: Derived,
    solver: Box<dyn TangentialSolver>,
    /// The second rail's solver (its wheel runs beside the first's).
    second_solver: Option<Box<dyn TangentialSolver>>,
    deposit: Box<dyn WearKernel>,
    grid: RailGrid,
    normal: NormalContact,
    /// The normal contact as built (`normal` until pinned).
    configured: NormalContact,
    models: Vec<ClassModel>,
    /// Whether the scene has a second rail.
    two_rails: bool,
}

impl WearMap {
    /// The map of `scene`'s passages, one per class of `classes` (empty:
    /// a single passage without a growth study). One solver serves every
    /// class: its grid is sized for the largest load of any class, and the
    /// speed and loads come with each step. Fails where the dynamics in
    /// every direction cannot be set up.
    pub fn new(scene: &Scene, classes: &[TrafficClass]) -> Result<Self, DynamicsError> {
        let d = derive(scene);
        let solver = build_solver(scene, &d.shape);
        let second_solver = scene.second_rail.as_ref().map(|_| build_solver(scene, &d.shape));
        let deposit = build_deposit(&solver.elements());
        let models = classes
            .iter()
            .map(|c| {
                let cs = scene.for_class(c);
                let cd = derive(&cs);
                let dynamics = track_dynamics(&cs, &cd)?;
                let second_passage = cs.second_rail_scene().map(|s| derive(&s).passage);
                Ok(ClassModel { passage: cd.passage, second_passage, dynamics, forced: None })
            })
            .collect::<Result<_, DynamicsError>>()?;
        // What the normal contact sees of the rail: the consistent chain's is
        // the linear contact on the adapted mesh and the nonlinear profile
        // contact on the fixed grid.
        let normal = match scene.contact.normal {
            NormalContact::Auto { .. } if scene.contact.model.fixed_grid().is_none() => {
                NormalContact::Linear { grid_scale: 1.0 }
            }
            normal => normal,
        };
        Ok(WearMap {
            grid: study_grid(scene),
            d,
            solver,
            second_solver,
            deposit,
            normal,
            configured: normal,
            models,
            two_rails: scene.second_rail.is_some(),
        })
    }

    /// The quantities derived from the scene.
    pub fn derived(&self) -> &Derived {
        &self.d
    }

    /// The rail grid the profiles and the wear are on (periodic in a
    /// growth study).
    pub fn grid(&self) -> &RailGrid {
        &self.grid
    }

    /// The contact elements the fields are stored on.
    pub fn elements(&self) -> Elements {
        self.solver.elements()
    }

    /// What the passages' normal contact sees of the rail (`Auto` on the
    /// adapted mesh resolved to the linear contact).
    pub fn normal(&self) -> NormalContact {
        self.normal
    }

    /// Holds the normal contact `contact.normal = "auto"` chooses per
    /// passage at the choice of one passage: the linear profile contact
    /// (`linear`) or the nonlinear one, on the same solver (a
    /// linearisation's perturbed passages take the base rail's contact).
    pub fn pin_normal(&mut self, linear: bool) {
        if let NormalContact::Auto { grid_scale } = self.configured {
            self.normal =
                if linear { NormalContact::Linear { grid_scale } } else { NormalContact::Profile { grid_scale } };
        }
    }

    /// Gives the passages the normal contact back as configured (`auto`
    /// chooses per passage again), after [`WearMap::pin_normal`].
    pub fn unpin_normal(&mut self) {
        self.normal = self.configured;
    }

    /// Class `class`'s track dynamics (None: imposed loads only).
    pub fn dynamics(&self, class: usize) -> Option<&dyn TrackDynamics> {
        self.models.get(class).and_then(|m| m.dynamics.as_deref())
    }

    /// Class `class`'s passage (of its first rail).
    pub fn passage_spec(&self, class: usize) -> &PassageSpec {
        &self.models[class].passage
    }

    /// Contact steps of the longest passage of any class (its run-in and
    /// all its wheels); a single passage's without classes.
    pub fn steps_per_passage(&self) -> usize {
        let of = |m: &ClassModel| m.passage.n_steps() * m.dynamics.as_deref().map_or(1, |d| d.wheels());
        self.models.iter().map(of).max().unwrap_or(0).max(self.d.passage.n_steps())
    }

    /// A single passage of the scene (no growth study): the imposed loads
    /// over its rail grid, no profile.
    pub fn single(
        &mut self,
        record_fields: bool,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<PassageResult, PassageError> {
        run_passage(
            &self.d.passage,
            &self.d.shape,
            self.solver.as_mut(),
            self.deposit.as_ref(),
            &self.grid,
            record_fields,
            progress,
        )
    }

    /// One passage of class `class` over the rails' `profiles` (the first
    /// rail's, then the second's where the scene has one; m, on
    /// [`Self::grid`]): each rail's wear, dynamic force, histories.
    pub fn passage(
        &mut self,
        class: usize,
        profiles: &[&Array2<f64>],
        record_fields: bool,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<GrowthPass, PassageError> {
        let model = &self.models[class];
        let specs = [Some(&model.passage), model.second_passage.as_ref()];
        let rails: Vec<Rail> = specs
            .into_iter()
            .zip(profiles.iter().copied().map(Some).chain(std::iter::repeat(None)))
            .filter_map(|(spec, profile)| Some(Rail { spec: spec?, profile: profile? }))
            .collect();
        growth_passage_rails(
            &rails,
            &self.d.shape,
            self.solver.as_mut(),
            self.second_solver.as_deref_mut(),
            self.deposit.as_ref(),
            &self.grid,
            self.normal,
            model.dynamics.as_deref(),
            record_fields,
            progress,
        )
    }

    /// Whether class `class`'s smooth rail wears a pattern: its track forces
    /// a dynamic force there (the discrete supports' parametric excitation)
    /// or its loads have imposed harmonics. Elsewhere the smooth rail's
    /// wear is uniform along the stretch, and its harmonics zero.
    pub fn forces_pattern(&self, class: usize) -> bool {
        let model = &self.models[class];
        let imposed =
            |s: &PassageSpec| !s.loads.harmonics.is_empty() || s.wheel_loads.iter().any(|l| !l.harmonics.is_empty());
        model.dynamics.as_deref().is_some_and(|d| d.forces_smooth_rail())
            || imposed(&model.passage)
            || model.second_passage.as_ref().is_some_and(imposed)
    }

    /// The wear one passage of class `class` leaves on the smooth rails
    /// (m; the first rail's, then the second's), where it wears a pattern
    /// ([`Self::forces_pattern`]; None elsewhere): computed at the first
    /// call, kept for the next.
    pub fn forced(&mut self, class: usize) -> Result<Option<&[Array2<f64>]>, PassageError> {
        if !self.forces_pattern(class) {
            return Ok(None);
        }
        if self.models[class].forced.is_none() {
            let smooth = Array2::zeros((self.grid.ny, self.grid.nx));
            let profiles: Vec<&Array2<f64>> = if self.two_rails { vec![&smooth, &smooth] } else { vec![&smooth] };
            let w0 = self.passage(class, &profiles, false, &mut |_, _| {})?;
            self.models[class].forced = Some(w0.rails.into_iter().map(|r| r.wear).collect());
        }
        Ok(self.models[class].forced.as_deref())
    }

    /// The forced wear of class `class` if it was computed ([`Self::forced`]).
    pub fn forced_if_known(&self, class: usize) -> Option<&[Array2<f64>]> {
        self.models.get(class).and_then(|m| m.forced.as_deref())
    }
}
