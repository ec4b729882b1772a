//! The typed, validated parameters of a scene: what the kernels receive.
//! Built from a config by [`crate::config`]; SI units throughout.

use crate::contact::PressureShape;
use crate::contact::friction::{Characteristic, FrictionLaw};
use crate::contact::grid::{GridScheme, GridSolver};
use crate::contact::transient::StepSolver;
use crate::hertz::{Curvatures, Elastic};
use crate::loads::ImposedLoads;

mod choice;
mod growth;
pub mod record;
pub mod spectrum;

pub use choice::{AutoChoice, Candidate};
pub use growth::{
    BASE_NAME, CreepForces, Directions, DynamicsKind, GrowthParams, LevelBand, Operation, ProfileHarmonic, Roughness,
    StopRule, TrafficClass, TrafficScaling, is_mix,
};

/// Tangential contact model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "kebab-case")]
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
        self.into()
    }

    /// All models, in the order of the config documentation.
    pub const ALL: [ContactModelKind; 3] =
        [ContactModelKind::ExactTransient, ContactModelKind::SimplifiedTransient, ContactModelKind::Fastsim];
}

/// Materials and friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Elastic constants of wheel and rail (identical).
    pub elastic: Elastic,
    /// Friction coefficient mu (1): at zero slip speed.
    pub friction: f64,
    /// How the friction coefficient varies with the slip speed
    /// (`material.friction_characteristic`).
    pub characteristic: Characteristic,
    /// Friction memory (`material.friction_memory`,
    /// `material.memory_speed`): None where the coefficient follows the
    /// slip speed at once.
    pub memory: Option<crate::contact::friction::FrictionMemory>,
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

/// The contact: the tangential model with its discretisation, and what
/// the normal problem sees of the rail.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactParams {
    /// The tangential model and its discretisation.
    pub model: ContactModel,
    /// Regularisation velocity eps of the Coulomb law (m/s), transient models.
    pub regularisation: f64,
    /// What `contact.model = "auto"` chose (None when the config names the
    /// model).
    pub auto: Option<AutoChoice>,
    /// What the normal problem sees of the rail.
    pub normal: NormalContact,
}

/// A patch-adapted mesh (`contact.elements_x` x `contact.elements_y`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mesh {
    /// Elements per strip along x.
    pub nx: usize,
    /// Strips along y.
    pub ny: usize,
}

impl Mesh {
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Whether the mesh has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The tangential contact model with its discretisation
/// (`contact.model`, `contact.grid` and their keys): one value per valid
/// combination, so that only the exact model can be on the fixed grid.
/// Its element count is [`ContactModel::elements`] (`crate::build`), its
/// cost `crate::cost`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// Kalker's FASTSIM on the adapted mesh, with its traction bound.
    Fastsim {
        /// The mesh.
        mesh: Mesh,
        /// Traction bound (`contact.fastsim_bound`).
        bound: PressureShape,
    },
    /// The paper's time stepping with the simplified (Winkler) elastic
    /// model on the adapted mesh, with FASTSIM's traction bound.
    SimplifiedTransient {
        /// The mesh.
        mesh: Mesh,
        /// Traction bound (`contact.fastsim_bound`).
        bound: PressureShape,
    },
    /// The paper's non-stationary model with Kalker's exact theory, on the
    /// adapted mesh or the fixed grid.
    ExactTransient(ContactGrid),
}

impl ContactModel {
    /// Which model.
    pub fn kind(&self) -> ContactModelKind {
        match self {
            ContactModel::Fastsim { .. } => ContactModelKind::Fastsim,
            ContactModel::SimplifiedTransient { .. } => ContactModelKind::SimplifiedTransient,
            ContactModel::ExactTransient(_) => ContactModelKind::ExactTransient,
        }
    }

    /// Config name of the model.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// The fixed grid, if the model is on one.
    pub fn fixed_grid(&self) -> Option<FixedGridParams> {
        match self {
            ContactModel::ExactTransient(ContactGrid::Fixed(f)) => Some(*f),
            _ => None,
        }
    }

    /// The adapted mesh, if the model is on one.
    pub fn mesh(&self) -> Option<Mesh> {
        match *self {
            ContactModel::Fastsim { mesh, .. }
            | ContactModel::SimplifiedTransient { mesh, .. }
            | ContactModel::ExactTransient(ContactGrid::Adapted { mesh, .. }) => Some(mesh),
            ContactModel::ExactTransient(ContactGrid::Fixed(_)) => None,
        }
    }
}

/// How the exact-transient model discretises the contact area; its names
/// (`contact.grid`) are those of [`GridKind`].
#[derive(Debug, Clone, Copy, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(GridKind),
    derive(strum::EnumString, strum::IntoStaticStr, strum::VariantNames),
    strum(serialize_all = "lowercase"),
    doc = "The kind of [`ContactGrid`], named as `contact.grid`."
)]
pub enum ContactGrid {
    /// The paper's Paul-Hashemi mesh adapted to the Hertz ellipse of every
    /// step, solved by `solver` (Gauss-Seidel, or the Newton-Raphson
    /// reference).
    Adapted {
        /// The mesh.
        mesh: Mesh,
        /// How each step is solved (`contact.solver`).
        solver: StepSolver,
    },
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
    /// Tangential solver (`contact.solver`; "auto" resolved by the cost
    /// model for the scene's normal contact).
    pub solver: GridSolver,
    /// Tangential solver of the passages `contact.normal = "auto"` runs in
    /// the linear contact, on its own smaller grid (the same as `solver`
    /// unless "auto" chose them: the cost model's choice for that grid).
    pub linear_solver: GridSolver,
}

/// What the normal contact sees of the rail (`contact.normal`); its
/// names are those of [`NormalKind`].
#[derive(Debug, Clone, Copy, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(NormalKind),
    derive(strum::EnumString, strum::IntoStaticStr, strum::VariantNames),
    strum(serialize_all = "lowercase"),
    doc = "The kind of [`NormalContact`], named as `contact.normal`."
)]
pub enum NormalContact {
    /// The consistent chain, the default: the linear contact; on the
    /// fixed grid the nonlinear profile contact for a passage whose
    /// corrugation is beyond the linear range (its curvature against the
    /// wheel's, [`crate::growth::LINEAR_CONTACT_CURVATURE`]).
    Auto {
        /// Size of the potential-contact grid (as for `Profile`; 1 on the
        /// adapted mesh) (1).
        grid_scale: f64,
    },
    /// The linearised profile contact ([`crate::contact::linear`]): the
    /// patch moved and stretched to first order with the corrugation under
    /// it, the rest of the normal problem's linear response on it (on the
    /// adapted mesh the mesh moves with it; on the fixed grid its pressure
    /// is averaged over the elements). The dynamics see its equivalent
    /// roughness, the flat-punch average of the profile.
    Linear {
        /// Size of the potential-contact grid (the fixed grid's; 1 on the
        /// adapted mesh) (1).
        grid_scale: f64,
    },
    /// The quadratic gap less the rail profile under the patch
    /// (non-Hertzian, nonlinear; the fixed grid only); the dynamics see the
    /// equivalent roughness.
    Profile {
        /// Size of the potential-contact grid along x and y relative to
        /// the largest Hertz patch (1).
        grid_scale: f64,
    },
    /// The quadratic gap of the curvatures: Hertz's contact (the paper's
    /// chain), the profile entering through the dynamic force only
    /// (weighted across the patch by the Hertz line load, unfiltered along
    /// it). Kept for comparison: it lacks the contact's own response to
    /// the corrugation.
    Hertz,
}

impl NormalContact {
    /// Config name (`contact.normal`).
    pub fn name(self) -> &'static str {
        NormalKind::from(self).into()
    }

    /// Size of the potential-contact grid relative to the largest Hertz
    /// patch (1).
    pub fn grid_scale(self) -> f64 {
        match self {
            NormalContact::Hertz => 1.0,
            NormalContact::Linear { grid_scale }
            | NormalContact::Profile { grid_scale }
            | NormalContact::Auto { grid_scale } => grid_scale,
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

/// The wheels of a vehicle on one rail (`[vehicle]`).
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleParams {
    /// Positions behind the leading wheel (m): 0 first, increasing.
    pub wheels: Vec<f64>,
    /// Unsprung mass per wheel (kg), where the wheels differ
    /// (`dynamics.unsprung_mass` otherwise).
    pub unsprung_mass: Option<Vec<f64>>,
    /// Mean normal force per wheel (N), where the wheels differ
    /// (`load.normal_force` otherwise).
    pub normal_force: Option<Vec<f64>>,
    /// Mean longitudinal force per wheel (N), where the wheels differ
    /// (`load.longitudinal_force` otherwise).
    pub longitudinal_force: Option<Vec<f64>>,
}

impl Default for VehicleParams {
    /// One wheel.
    fn default() -> Self {
        VehicleParams { wheels: vec![0.0], unsprung_mass: None, normal_force: None, longitudinal_force: None }
    }
}

impl VehicleParams {
    /// Wheel `i`'s imposed loads: `loads` (its harmonics kept) with the
    /// wheel's own mean normal and longitudinal force where given.
    pub fn wheel_loads(&self, i: usize, loads: &crate::loads::ImposedLoads) -> crate::loads::ImposedLoads {
        let mut l = loads.clone();
        if let Some(n) = &self.normal_force {
            l.normal_force = n[i];
        }
        if let Some(f) = &self.longitudinal_force {
            l.longitudinal_force = f[i];
        }
        l
    }

    /// The largest normal force of any wheel under `loads` (N), imposed
    /// harmonics included.
    pub fn max_normal_force(&self, loads: &crate::loads::ImposedLoads) -> f64 {
        (0..self.wheels.len()).map(|i| self.wheel_loads(i, loads).max_normal_force()).fold(0.0, f64::max)
    }

    /// Wheel `i`'s unsprung mass (kg): its own where given, else `default`.
    pub fn wheel_mass(&self, i: usize, default: f64) -> f64 {
        self.unsprung_mass.as_ref().map_or(default, |m| m[i])
    }

    /// The distinct distances between two wheels (m), increasing.
    pub fn distances(&self) -> Vec<f64> {
        let mut d: Vec<f64> =
            self.wheels.iter().enumerate().flat_map(|(i, a)| self.wheels[i + 1..].iter().map(move |b| b - a)).collect();
        d.sort_by(f64::total_cmp);
        d.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
        d
    }
}

/// The wheelset (`[wheelset]`): its torsion ([`crate::dynamics::wheelset::torsion`])
/// and, with `model = "modal"`, the flexible rotating wheelset
/// ([`crate::dynamics::wheelset`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WheelsetParams {
    /// Axle torsional stiffness between the wheels (N m/rad).
    pub stiffness: f64,
    /// Polar moment of inertia of each wheel with its half axle (kg m^2).
    pub inertia: f64,
    /// Loss factor of the axle's torsion (1).
    pub loss_factor: f64,
    /// The modal model (`model = "modal"`); None: the torsional mode alone
    /// (`model = "torsion"`, the default).
    pub modal: Option<ModalWheelsetParams>,
}

/// The modal wheelset's keys (`[wheelset] model = "modal"`).
#[derive(Debug, Clone, PartialEq)]
pub struct ModalWheelsetParams {
    /// Mass of the wheelset with its axle boxes (kg).
    pub mass: f64,
    /// Roll moment of inertia about the longitudinal axis (kg m^2).
    pub roll_inertia: f64,
    /// Yaw moment of inertia about the vertical axis (kg m^2).
    pub yaw_inertia: f64,
    /// Primary suspension stiffness per axle box, longitudinal, lateral,
    /// vertical (N/m).
    pub suspension_stiffness: [f64; 3],
    /// Loss factor of the primary suspension (1).
    pub suspension_loss_factor: f64,
    /// Distance between the axle boxes (m).
    pub axle_box_spacing: f64,
    /// Distance between the two wheels' contact points (m).
    pub contact_spacing: f64,
    /// The flexible modes.
    pub modes: WheelsetModes,
}

/// Where the modal wheelset's flexible modes come from.
#[derive(Debug, Clone, PartialEq)]
pub enum WheelsetModes {
    /// The documented default ([`crate::dynamics::wheelset::standard`]),
    /// with the damping ratios of its bending and its wheel modes (1).
    Default {
        /// Damping ratio of the bending modes (1).
        bending_damping: f64,
        /// Damping ratio of the wheel's modes (1).
        wheel_damping: f64,
    },
    /// A user's table ([`crate::dynamics::wheelset::table`]) read from `path`.
    Table {
        /// The file (absolute).
        path: String,
        /// Its modes.
        table: crate::dynamics::wheelset::table::ModalTable,
    },
}

/// Output options.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputParams {
    /// Store the contact fields on (step, element).
    pub store_fields: bool,
    /// Title written to the run file.
    pub title: String,
}

/// The roughness levels the run reports (`[levels]`): their bands and the
/// limit they are held against ([`crate::levels`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LevelParams {
    /// The bands.
    pub bands: crate::levels::BandSet,
    /// The limit curve.
    pub limit: crate::levels::limit::LimitCurve,
}

impl Default for LevelParams {
    fn default() -> Self {
        LevelParams { bands: crate::levels::BandSet::ThirdOctave, limit: crate::levels::limit::LimitCurve::iso3095() }
    }
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
    /// Prescribed longitudinal creepage (1) (`load.control = "creepage"`),
    /// or None: the longitudinal force of `loads` prescribed.
    pub creepage_x: Option<f64>,
    /// Prescribed lateral creepage (1).
    pub creepage_y: f64,
    /// Prescribed spin (1/m).
    pub spin: f64,
    /// Imposed loads.
    pub loads: ImposedLoads,
    /// Contact model.
    pub contact: ContactParams,
    /// The wear law (`wear.law` and its keys).
    pub wear: crate::wear::WearLaw,
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
    /// The roughness levels reported and their limit (`[levels]`).
    pub levels: LevelParams,
    /// Growth study (None: a single passage).
    pub growth: Option<GrowthParams>,
    /// The track under the wheel (`[track]`).
    pub track: crate::dynamics::track::TrackConfig,
    /// The discrete track's supports over one period (`[track]`'s layout
    /// keys; one bay of `track` by default), reduced to the shortest
    /// period that repeats.
    pub layout: crate::dynamics::track::layout::Layout,
    /// The vehicle's wheels on the rail (`[vehicle]`; one by default).
    pub vehicle: VehicleParams,
    /// The wheelset (`[wheelset]`), if modelled (None: the rigid wheel).
    pub wheelset: Option<WheelsetParams>,
    /// What `wheelset.model = "auto"` chose and why (None where the
    /// config names the model).
    pub wheelset_choice: Option<String>,
    /// The wheelset's second rail (`[second_rail]`), if modelled: the
    /// rail of the scene is then the first (the wheelset's wheel 0).
    pub second_rail: Option<SecondRail>,
    /// What `corrugation spectrum` measures (`[spectrum]`; None: absent,
    /// the command takes the defaults).
    pub spectrum: Option<spectrum::SpectrumParams>,
}

/// The second rail of a wheelset (`[second_rail]`): its contact's steady
/// state (e.g. from a curving calculation) and its initial roughness. The
/// scene's own keys describe the first rail. Lateral creepage and spin are
/// in the same axes on both rails (y to the right of the direction of
/// travel), so a mirror-symmetric wheelset on tangent track has equal
/// lateral creepages and opposite spins.
#[derive(Debug, Clone, PartialEq)]
pub struct SecondRail {
    /// The two rails' names, the first rail's first ("left rail", "right
    /// rail"; a curve's "low rail", "high rail").
    pub names: [String; 2],
    /// Mean normal force on the second rail (N).
    pub normal_force: f64,
    /// Mean longitudinal force on its wheel (N) (force control).
    pub longitudinal_force: f64,
    /// Its longitudinal creepage (1) (creepage control), or None.
    pub creepage_x: Option<f64>,
    /// Its lateral creepage (1).
    pub creepage_y: f64,
    /// Its spin (1/m).
    pub spin: f64,
    /// Seed of its random roughness (a random or level-spectrum roughness;
    /// the other kinds are the first rail's).
    pub roughness_seed: Option<u64>,
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
        if let Some(w) = &c.wheels {
            scene.vehicle = VehicleParams { wheels: w.clone(), ..VehicleParams::default() };
        }
        if let Some(g) = scene.growth.as_mut() {
            g.dynamics = g.dynamics.with_unsprung_mass(c.unsprung_mass);
        }
        scene
    }

    /// The largest normal force of any traffic class, imposed harmonics
    /// included (N).
    pub fn max_normal_force(&self) -> f64 {
        match &self.growth {
            Some(g) => {
                g.classes.iter().map(|c| self.vehicle.max_normal_force(&c.loads(&self.loads))).fold(0.0, f64::max)
            }
            None => self.vehicle.max_normal_force(&self.loads),
        }
        .max(self.second_rail_scene().map_or(0.0, |s| s.loads.max_normal_force()))
    }

    /// The scene as the second rail's contact sees it (its loads,
    /// creepages and spin, and its initial roughness), where the wheelset
    /// has a second rail; the wheelset, track and vehicle are the same.
    pub fn second_rail_scene(&self) -> Option<Scene> {
        let second = self.second_rail.as_ref()?;
        let mut scene = self.clone();
        scene.second_rail = None;
        scene.loads.normal_force = second.normal_force;
        scene.loads.longitudinal_force = second.longitudinal_force;
        scene.creepage_x = second.creepage_x;
        scene.creepage_y = second.creepage_y;
        scene.spin = second.spin;
        if let (Some(g), Some(seed)) = (scene.growth.as_mut(), second.roughness_seed) {
            g.roughness = g.roughness.with_seed(seed);
        }
        Some(scene)
    }
}
