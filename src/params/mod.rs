//! The typed, validated parameters of a scene: what the kernels receive.
//! Built from a config by [`crate::config`]; SI units throughout.

use crate::contact::PressureShape;
use crate::contact::friction::FrictionLaw;
use crate::contact::grid::{GridScheme, GridSolver};
use crate::contact::transient::StepSolver;
use crate::hertz::{Curvatures, Elastic};
use crate::loads::ImposedLoads;

mod choice;
mod growth;

pub use choice::{AutoChoice, Candidate};
pub use growth::{
    DynamicsKind, GrowthParams, LevelBand, ProfileHarmonic, Roughness, StopRule, TrafficClass, TrafficScaling,
};

/// Tangential contact model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactModelKind {
    /// Kalker's FASTSIM (steady, simplified theory).
    Fastsim,
    /// The paper's non-stationary model with Kalker's exact theory.
    ExactTransient,
    /// The same time stepping with the simplified (Winkler) elastic model.
    SimplifiedTransient,
}

impl ContactModelKind {
    /// Config name of the model.
    pub fn name(self) -> &'static str {
        match self {
            ContactModelKind::Fastsim => "fastsim",
            ContactModelKind::ExactTransient => "exact-transient",
            ContactModelKind::SimplifiedTransient => "simplified-transient",
        }
    }

    /// All models, in the order of the config documentation.
    pub const ALL: [ContactModelKind; 3] =
        [ContactModelKind::ExactTransient, ContactModelKind::SimplifiedTransient, ContactModelKind::Fastsim];

    /// Whether the model carries a contact history between steps.
    pub fn is_transient(self) -> bool {
        self != ContactModelKind::Fastsim
    }
}

/// Materials and friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Elastic constants of wheel and rail (identical).
    pub elastic: Elastic,
    /// Coulomb friction coefficient mu (1).
    pub friction: f64,
}

/// Wheel and rail geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Wheel rolling radius (m).
    pub wheel_radius: f64,
    /// Lateral wheel-profile radius (m; negative concave, inf flat).
    pub wheel_profile_radius: f64,
    /// Lateral rail-head radius (m).
    pub rail_head_radius: f64,
}

impl Geometry {
    /// Hertz curvature sums A, B (1/m).
    pub fn curvatures(&self) -> Curvatures {
        Curvatures::wheel_on_rail(self.wheel_radius, self.wheel_profile_radius, self.rail_head_radius)
    }
}

/// Contact model and its discretisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactParams {
    /// The tangential model.
    pub model: ContactModelKind,
    /// Elements per strip along x.
    pub elements_x: usize,
    /// Strips along y.
    pub elements_y: usize,
    /// Regularisation velocity eps of the Coulomb law (m/s), transient models.
    pub regularisation: f64,
    /// Traction bound of FASTSIM.
    pub fastsim_bound: PressureShape,
    /// How the exact-transient model solves each step (Gauss-Seidel, or the
    /// Newton-Raphson reference).
    pub solver: StepSolver,
    /// What `contact.model = "auto"` chose (None when the config names the
    /// model).
    pub auto: Option<AutoChoice>,
    /// The discretisation of the exact-transient model.
    pub grid: ContactGrid,
    /// What the normal problem sees of the rail.
    pub normal: NormalContact,
}

/// How the exact-transient model discretises the contact area.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ContactGrid {
    /// The paper's Paul-Hashemi mesh adapted to the Hertz ellipse of every
    /// step (`elements_x` x `elements_y`).
    #[default]
    Adapted,
    /// A fixed potential-contact grid of uniform elements (CONTACT's
    /// discretisation).
    Fixed(FixedGridParams),
}

/// The fixed grid's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedGridParams {
    /// Element length along x (m); also the rolled distance per step.
    pub dx: f64,
    /// Element width along y (m).
    pub dy: f64,
    /// Friction law.
    pub friction_law: FrictionLaw,
    /// Backward difference of the material derivative.
    pub scheme: GridScheme,
    /// Tangential solver (`contact.solver`).
    pub solver: GridSolver,
}

/// What the normal contact sees of the rail (`contact.normal`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalContact {
    /// The quadratic gap of the curvatures: Hertz's contact (the paper's
    /// chain), the profile entering through the dynamic force only
    /// (weighted across the patch by the Hertz line load, unfiltered along
    /// it). Kept for comparison: it lacks the contact's own response to
    /// the corrugation.
    Hertz,
    /// The linearised profile contact of the adapted mesh
    /// ([`crate::contact::linear`]): the patch moved and stretched to first
    /// order with the corrugation under it, the rest of the normal
    /// problem's linear response on it. The dynamics see its equivalent
    /// roughness, the flat-punch average of the profile.
    Linear,
    /// The quadratic gap less the rail profile under the patch
    /// (non-Hertzian, nonlinear; the fixed grid only); the dynamics see the
    /// equivalent roughness.
    Profile {
        /// Size of the potential-contact grid along x and y relative to
        /// the largest Hertz patch (1).
        grid_scale: f64,
    },
    /// The consistent chain, the default: on the adapted mesh the linear
    /// contact; on the fixed grid the nonlinear profile contact, whose
    /// dynamics see the linear contact's equivalent roughness (the
    /// flat-punch average, no normal solves) while the corrugation's
    /// curvature is small against the wheel's, the nonlinear equivalent
    /// roughness beyond.
    Auto {
        /// Size of the potential-contact grid (as for `Profile`; 1 on the
        /// adapted mesh) (1).
        grid_scale: f64,
    },
}

impl NormalContact {
    /// Config name (`contact.normal`).
    pub fn name(self) -> &'static str {
        match self {
            NormalContact::Hertz => "hertz",
            NormalContact::Linear => "linear",
            NormalContact::Profile { .. } => "profile",
            NormalContact::Auto { .. } => "auto",
        }
    }

    /// Size of the potential-contact grid relative to the largest Hertz
    /// patch (1).
    pub fn grid_scale(self) -> f64 {
        match self {
            NormalContact::Hertz | NormalContact::Linear => 1.0,
            NormalContact::Profile { grid_scale } | NormalContact::Auto { grid_scale } => grid_scale,
        }
    }
}

/// Rail-surface grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailParams {
    /// First grid node along the rail (m).
    pub x_min: f64,
    /// Last grid node along the rail (m).
    pub x_max: f64,
    /// Node spacing along the rail (m).
    pub dx: f64,
    /// Node spacing across the rail (m).
    pub dy: f64,
    /// Lateral half-width of the grid (m).
    pub half_width: f64,
}

/// Output options.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputParams {
    /// Store the contact fields on (step, element).
    pub store_fields: bool,
    /// Title written to the run file.
    pub title: String,
}

/// A whole validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Materials.
    pub material: Material,
    /// Geometry.
    pub geometry: Geometry,
    /// Rolling speed V (m/s).
    pub speed: f64,
    /// Prescribed lateral creepage (1).
    pub creepage_y: f64,
    /// Prescribed spin (1/m).
    pub spin: f64,
    /// Imposed loads.
    pub loads: ImposedLoads,
    /// Contact model.
    pub contact: ContactParams,
    /// Archard coefficient k/H (m^2/N).
    pub k_over_h: f64,
    /// Wear sub-steps per contact step.
    pub wear_substeps: usize,
    /// First patch-centre position (m).
    pub start: f64,
    /// Last patch-centre position (m).
    pub end: f64,
    /// Rolled distance per contact step (m).
    pub step_length: f64,
    /// Rail grid.
    pub rail: RailParams,
    /// Output.
    pub output: OutputParams,
    /// Growth study (None: a single passage).
    pub growth: Option<GrowthParams>,
    /// The track under the wheel (`[track]`).
    pub track: crate::dynamics::track::TrackConfig,
}

impl Scene {
    /// The scene as wheels of traffic class `c` see it: its speed, mean
    /// normal and longitudinal force (the imposed harmonics kept) and
    /// unsprung mass. A study without `[traffic]` has one class whose scene
    /// is the scene itself.
    pub fn for_class(&self, c: &TrafficClass) -> Scene {
        let mut scene = self.clone();
        scene.speed = c.speed;
        scene.loads = c.loads(&self.loads);
        if let Some(g) = scene.growth.as_mut() {
            g.dynamics = g.dynamics.with_unsprung_mass(c.unsprung_mass);
        }
        scene
    }

    /// The largest normal force of any traffic class, imposed harmonics
    /// included (N).
    pub fn max_normal_force(&self) -> f64 {
        match &self.growth {
            Some(g) => g.classes.iter().map(|c| c.loads(&self.loads).max_normal_force()).fold(0.0, f64::max),
            None => self.loads.max_normal_force(),
        }
    }
}
