//! The configuration of a drilling-system run: JSON in (every field optional except
//! `sections` and each section's `length`, `outer_diameter`, `inner_diameter`), defaults from
//! the `Default` impls below (one place each), validation naming dotted fields
//! (`sections[1].outer_diameter`, `top_drive.controller.kp`), the limits of a run
//! ([`MAX_CELLS`], [`MAX_DURATION`], [`MAX_OUTPUT_BYTES`], [`MAX_SECTIONS`]).
//!
//! Units: SI, except angles in degrees (`inclination_deg`) and speeds in rpm (`rpm`, `steps`);
//! stick speeds are rad/s.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::error::{Error, Num, Result};
use crate::metrics::STICK_SPEED;
use crate::schema::{self, join, kind, shown};

use super::axial::bitrock::DetournayBit;
use super::axial::hoist::{Autodriller, HoistMode, HoistParams};
use super::engine::bit_law;
pub use super::engine::bit_law::weakening::Weakening;
use super::grid::Grid;
use crate::well::plan::SegmentSpec;

/// Largest number of cells a run may have (`numerics.max_cells` may lower it).
pub const MAX_CELLS: usize = 10_000_000;
/// Largest number of string sections.
pub const MAX_SECTIONS: usize = 1_000;
/// Longest simulated duration, s (one day).
pub const MAX_DURATION: f64 = 86_400.0;
/// Largest memory of a run's outputs (series and field snapshots), bytes (512 MiB).
pub const MAX_OUTPUT_BYTES: usize = 512 << 20;
/// The default motor torque limit, N m ([`TopDrive::torque_limit`]).
pub const DEFAULT_TORQUE_LIMIT: f64 = 60e3;
/// Largest number of cell updates (cells times time steps) of one run: about half an hour at
/// the 6e8 cell updates per second one core of a 2-core AMD EPYC reaches (Well B, 1000 cells,
/// 60 s in 0.11 s). A run asking more is refused before it starts, naming what makes it long.
pub const MAX_CELL_STEPS: f64 = 1e12;
/// Largest outer diameter of a section, m (a hard limit against unit mistakes and overflow;
/// drill strings are below 0.5 m).
pub const MAX_DIAMETER: f64 = 10.0;
/// Longest section, m.
pub const MAX_SECTION_LENGTH: f64 = 100_000.0;
/// Number of output series stored per sample (`t`, surface and bit speed, motor and bit torque).
pub(crate) const SERIES: usize = 5;

/// One section of the string, from the top.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Section {
    /// A label for tables and plots.
    #[schemars(extend("label" = "section name"))]
    pub name: String,
    /// Measured length of the section, > 0 and at most 100 km (required).
    #[schemars(extend("unit" = "m", "label" = "section length"))]
    pub length: f64,
    /// Outer diameter of the pipe body, > 0 and at most 10 m (required).
    #[schemars(extend("unit" = "m", "label" = "outer diameter"))]
    pub outer_diameter: f64,
    /// Inner diameter, from 0 to below the outer diameter (required).
    #[schemars(extend("unit" = "m", "label" = "inner diameter"))]
    pub inner_diameter: f64,
    /// Shear modulus `G` of the material, > 0.
    #[schemars(extend("unit" = "Pa", "label" = "shear modulus"))]
    pub shear_modulus: f64,
    /// Density of the material, > 0 (and above the mud density).
    #[schemars(extend("unit" = "kg/m^3", "label" = "density"))]
    pub density: f64,
    /// Diameter at which the wall's friction acts, > 0; the friction lever arm is half of it.
    /// Null: the outer diameter.
    #[schemars(extend("unit" = "m", "label" = "contact diameter"))]
    pub contact_diameter: Option<f64>,
    /// Polar moment of area `J`, > 0. Null: `pi/32 (OD^4 - ID^4)` of the diameters.
    #[schemars(extend("unit" = "m^4", "label" = "polar moment"))]
    pub polar_moment: Option<f64>,
    /// Cross-section area `A`, > 0. Null: `pi/4 (OD^2 - ID^2)` of the diameters.
    #[schemars(extend("unit" = "m^2", "label" = "cross-section area"))]
    pub area: Option<f64>,
    /// `J4 = int r^4 dA`, > 0, of the `consistent` nonlinearity's `k5 = M J4 / 2` (unused by
    /// `linear`). Null: `pi/192 (OD^6 - ID^6)`, the annulus of the diameters. A section whose
    /// `polar_moment` is overridden (an equivalent section) needs it too for the consistent law.
    #[schemars(extend("unit" = "m^6", "label" = "quartic moment"))]
    pub quartic_moment: Option<f64>,
    /// Poisson's ratio, `0 < nu < 0.5`: with `shear_modulus` it gives the P-wave modulus
    /// `M = 2 G (1 - nu) / (1 - 2 nu)` of the `consistent` nonlinearity (unused by `linear`).
    #[schemars(extend("unit" = "", "label" = "Poisson's ratio"))]
    pub poisson_ratio: f64,
}

impl Default for Section {
    /// A template (the Aarsnes-Shor Well B drill pipe, 5 1/2", steel); `length` and the
    /// diameters are required in a configuration.
    fn default() -> Self {
        Section {
            name: "drill pipe".into(),
            length: 2500.0,
            outer_diameter: 0.146529,
            inner_diameter: 0.123024,
            shear_modulus: 79.3e9,
            density: 7850.0,
            contact_diameter: None,
            polar_moment: None,
            area: None,
            quartic_moment: None,
            poisson_ratio: 0.3,
        }
    }
}

/// The torque-twist law of the string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Nonlinearity {
    /// `tau = G J eps` (`eps` the twist per length): the linear wave equation.
    Linear,
    /// The finite-strain law of [`crate::model::Model::Consistent`],
    /// `tau = k2 eps + k5 eps^3` with `k2 = G J`, `k5 = M J4 / 2` (hardening).
    Consistent,
}

impl Nonlinearity {
    pub const NAMES: [&'static str; 2] = ["linear", "consistent"];
}

/// The inclination: one constant angle, or a table at the measured depths `well.md`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Inclination {
    Constant(f64),
    Table(Vec<f64>),
}

/// The well: survey (linear interpolation in measured depth, constant beyond the ends), mud.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Well {
    /// Measured depths of the survey stations, strictly increasing. Null with a constant
    /// inclination (one number in `inclination_deg`).
    #[schemars(extend("unit" = "m", "label" = "measured depth"))]
    pub md: Option<Vec<f64>>,
    /// Inclination at each `md` station, from 0 to below 180 degrees (0: vertical); one number without `md` is
    /// a constant inclination.
    #[schemars(extend("unit" = "deg", "label" = "inclination"))]
    pub inclination_deg: Inclination,
    /// Density of the mud, for the buoyancy of the string (weight `(rho - mud_density) g A` per
    /// metre): from 0 (no buoyancy) to below every section's density.
    #[schemars(extend("unit" = "kg/m^3", "label" = "mud density"))]
    pub mud_density: f64,
    /// Acceleration of gravity, >= 0.
    #[schemars(extend("unit" = "m/s^2", "label" = "gravity"))]
    pub gravity: f64,
    /// Azimuth in degrees clockwise from north, 0 to 360: one constant angle, or one per `md`
    /// station (with a plan: the constant azimuth it starts from).
    #[schemars(extend("unit" = "deg", "label" = "azimuth"))]
    pub azimuth_deg: Inclination,
    /// A survey file (CSV: columns md, inc, azi; units in the header as `md_m` / `md_ft`,
    /// `inc_deg` / `inc_rad`, ...; default m and degrees), in place of `md`,
    /// `inclination_deg` and `azimuth_deg`. A relative path is relative to the working
    /// directory here; the TOML loader makes it relative to the configuration file.
    #[schemars(extend("label" = "survey file"))]
    pub survey: Option<String>,
    /// A plan in place of the stations: segments `{hold = m}`, `{build = deg/30 m,
    /// inclination = deg}`, `{drop = ..., inclination = ...}`, `{turn = deg/30 m, azimuth =
    /// deg}` from the surface, vertical at azimuth `azimuth_deg` (a constant).
    #[schemars(extend("label" = "well plan"))]
    pub plan: Option<Vec<SegmentSpec>>,
    /// A survey (stations, file or plan) shorter than the string is refused, unless `extend`
    /// is true: then the hole goes straight on in the last station's direction.
    #[schemars(extend("label" = "extend the survey"))]
    pub extend: bool,
    /// The stations read from `survey` when the configuration was parsed (md m, inclination
    /// and azimuth degrees).
    #[serde(skip)]
    pub survey_stations: Option<std::sync::Arc<[Vec<f64>; 3]>>,
}

impl Default for Well {
    /// The Aarsnes-Shor Well B survey: vertical to 500 m, build to 60 deg at 1600 m.
    fn default() -> Self {
        Well {
            md: Some(vec![0.0, 500.0, 1600.0, 4000.0]),
            inclination_deg: Inclination::Table(vec![0.0, 0.0, 60.0, 60.0]),
            mud_density: 0.0,
            gravity: 9.81,
            azimuth_deg: Inclination::Constant(0.0),
            survey: None,
            plan: None,
            extend: false,
            survey_stations: None,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionModel {
    /// Set-valued Coulomb friction with a true stick phase (Aarsnes & Shor).
    SetValued,
    /// `tanh(omega / regularisation_speed)` times the kinetic limit.
    Regularised,
}

/// Along-string Coulomb friction (soft-string contact).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Friction {
    /// Static friction factor between string and wall, >= 0 (where no interval applies).
    ///
    /// One friction vocabulary for both models: a contact that sticks holds up to `static`
    /// (the break-off torque, the stick phases of the dynamic model); a contact that slides
    /// carries the kinetic factor `static x kinetic_ratio`, in the dynamic model and in every
    /// load of `torque-drag` (pick-up, slack-off and rotating are steady slides). A
    /// torque-and-drag "friction factor" is the kinetic factor: with `kinetic_ratio = 1` (one
    /// factor) `static` is it.
    #[serde(rename = "static")]
    #[schemars(extend("unit" = "", "label" = "static friction factor"))]
    pub static_coefficient: f64,
    /// Kinetic over static friction factor, in [0, 1]: the sliding factor of the dynamic model
    /// and of `torque-drag` is `static x kinetic_ratio`.
    #[schemars(extend("unit" = "", "label" = "kinetic/static friction ratio"))]
    pub kinetic_ratio: f64,
    /// A cell slower than this sticks if the torque needed to stop it is within the static
    /// limit, >= 0 (Aarsnes-Shor `o_thres`): the torsional wall friction's rule. The coupled
    /// wall friction of a run with a hoist (`coupling = "axial_torsional"`) has no threshold: a
    /// contact sticks exactly when the force that stops it in a step is within the static
    /// limit, and slides on the kinetic factor otherwise.
    #[schemars(extend("unit" = "rad/s", "label" = "stick speed"))]
    pub stick_speed: f64,
    /// The wall friction law: `set_valued` (a true stick phase) or `regularised` (smooth).
    #[schemars(extend("label" = "friction model"))]
    pub model: FrictionModel,
    /// The speed scale of `regularised` friction, > 0.
    #[schemars(extend("unit" = "rad/s", "label" = "regularisation speed"))]
    pub regularisation_speed: f64,
    /// The normal force the wall's friction limit is made of: `soft_string` (default), the
    /// normal force of the static soft-string torque-and-drag solution (buoyed weight and
    /// tension times curvature, rotating off bottom, or on bottom with the bit's weight), or
    /// `weight`, the buoyed weight times the sine of the inclination alone (Aarsnes & Shor 2018,
    /// eq. 6, to reproduce their model).
    #[schemars(extend("label" = "contact force"))]
    pub contact: Contact,
    /// Static friction factors over depth intervals (cased and open hole differ); `static`
    /// applies where no interval does. The kinetic factor is `kinetic_ratio` times the static
    /// one everywhere.
    #[schemars(extend("label" = "friction intervals"))]
    pub intervals: Vec<FrictionInterval>,
    /// What the wall friction of a coupled run (`[hoist]`) acts on: `axial_torsional` (default),
    /// the Coulomb friction against the contact's sliding velocity (axial speed, contact radius
    /// times angular speed) on both fields with one stick phase, so that a rotating string
    /// slides axially with little drag; or `torsion_only`, the torsional field alone (the axial
    /// field without wall friction, the coupled runs before this key). No effect without a hoist.
    #[schemars(extend("label" = "wall friction coupling"))]
    pub coupling: FrictionCoupling,
}

/// What the wall friction of a coupled run acts on ([`Friction::coupling`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionCoupling {
    /// Against the sliding velocity `(v, r omega)` on both fields
    /// ([`super::engine::coupled_friction`]).
    #[default]
    AxialTorsional,
    /// On the torsional field alone.
    TorsionOnly,
}

impl FrictionCoupling {
    pub const NAMES: [&'static str; 2] = ["axial_torsional", "torsion_only"];
}

/// The normal force of the wall's friction limit ([`Friction::contact`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Contact {
    /// `g sin(inc) (rho - rho_mud) A` per metre (Aarsnes & Shor 2018).
    Weight,
    /// The soft-string normal force per metre of [`crate::well::torque_drag`].
    SoftString,
}

impl Contact {
    pub const NAMES: [&'static str; 2] = ["weight", "soft_string"];
}

/// A static friction factor over `[top_md, bottom_md)`, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionInterval {
    /// Measured depth of the interval's top, >= 0.
    #[schemars(extend("unit" = "m", "label" = "interval top"))]
    pub top_md: f64,
    /// Measured depth of the interval's bottom, below its top.
    #[schemars(extend("unit" = "m", "label" = "interval bottom"))]
    pub bottom_md: f64,
    /// Static friction factor in the interval, >= 0.
    #[serde(rename = "static")]
    #[schemars(extend("unit" = "", "label" = "static friction factor"))]
    pub static_coefficient: f64,
}

impl Default for Friction {
    /// Aarsnes & Shor (2018), MAIN.m: `mu = 0.3`, `fRat = 0.65`, `oThres = 1.5`.
    fn default() -> Self {
        Friction {
            static_coefficient: 0.3,
            kinetic_ratio: 0.65,
            stick_speed: 1.5,
            model: FrictionModel::SetValued,
            regularisation_speed: 0.1,
            contact: Contact::SoftString,
            intervals: Vec::new(),
            coupling: FrictionCoupling::AxialTorsional,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ControllerKind {
    /// Ideal speed control: the top speed is the setpoint (motor torque inferred).
    Speed,
    /// Motor torque `kp e + ki int e` in a zero-order hold.
    Pi,
    /// PI tuned from the string impedance and a tuning frequency (SoftTorque).
    SoftTorque,
    /// Impedance matching (ZTorque): the top drive acts as a damper `z_factor Z` to the string.
    ZTorque,
}

impl ControllerKind {
    pub const NAMES: [&'static str; 4] = ["speed", "pi", "soft_torque", "z_torque"];
}

/// A named controller tuning (`top_drive.controller.preset`): it fills in the controller's
/// `type` and gains from the string ([`super::tuning::preset_controller`]; the rules and their
/// sources are in [`super::tuning`]); keys given beside it keep their values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ControllerPreset {
    /// A high-gain speed PI (`type = "pi"`): `kp = 50 Z`, `ki = 5 1/s^2 I_TD`.
    Stiff,
    /// SoftTorque / SoftSpeed (`type = "soft_torque"`): `kp = 4 Z`, `ki = (2 pi f1)^2 I_TD`.
    SoftTorque,
    /// ZTorque impedance matching (`type = "z_torque"`): `z_factor = 4`, the torque high-pass
    /// an octave below the first mode, `torque_highpass_time = 1 / (pi f1)`.
    ZTorque,
}

impl ControllerPreset {
    pub const NAMES: [&'static str; 3] = ["stiff", "soft_torque", "z_torque"];
    pub const ALL: [ControllerPreset; 3] =
        [ControllerPreset::Stiff, ControllerPreset::SoftTorque, ControllerPreset::ZTorque];

    /// The preset's name in the configuration.
    pub fn name(self) -> &'static str {
        match self {
            ControllerPreset::Stiff => "stiff",
            ControllerPreset::SoftTorque => "soft_torque",
            ControllerPreset::ZTorque => "z_torque",
        }
    }
}

/// The top-drive controller. `Z = J sqrt(G rho)` below is the characteristic impedance of the
/// top section (N m s = N m per rad/s: the torque a wave of 1 rad/s carries), `f1` the string's
/// first natural frequency (top fixed, bit free or with the BHA inertia), `I_TD` the top-drive
/// inertia. `drillstring tune CONFIG.toml` prints the gains of each preset for a string.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Controller {
    /// `speed` (ideal speed source), `pi` (a speed PI; a stiff one reflects the torsional waves
    /// back down the string), `soft_torque` (a PI tuned to absorb them at `tuning_frequency`),
    /// `z_torque` (the top drive lowers its speed by the high-passed string torque over
    /// `z_factor Z`, a damper to the waves).
    #[serde(rename = "type")]
    #[schemars(extend("label" = "controller"))]
    pub kind: ControllerKind,
    /// A named tuning, `stiff`, `soft_torque` or `z_torque`, that fills in `type` and the gains
    /// from the string; keys given beside it keep their values. Null: the keys as given.
    ///
    /// The rules and their sources: [`ControllerPreset`], [`super::tuning`].
    #[schemars(extend("label" = "controller preset"))]
    pub preset: Option<ControllerPreset>,
    /// `pi`: the proportional gain, >= 0: the motor torque per rad/s of speed error, i.e. the
    /// damping the top drive presents to the string.
    ///
    /// Compare it with `Z` (`kp >> Z`: a stiff top that reflects torque waves, `kp = Z`: a
    /// matched top that absorbs them). The Aarsnes & Shor default 38e3 is about 130 `Z` of a
    /// 5-in pipe. `soft_torque` computes it: `z_factor Z`.
    #[schemars(extend("unit" = "N*m*s/rad", "label" = "proportional gain"))]
    pub kp: f64,
    /// `pi`: the integral gain, >= 0: the motor torque per radian of accumulated speed error (a
    /// torsional spring to the setpoint's angle).
    ///
    /// `ki / kp` (1/s) is the corner below which the loop removes a steady speed error.
    /// `soft_torque` computes it: `(2 pi f)^2 I_TD`, so that at `f` this spring cancels the top
    /// drive's inertia.
    #[schemars(extend("unit" = "N*m/rad", "label" = "integral gain"))]
    pub ki: f64,
    /// `soft_torque`: the frequency at which the top drive's inertia is cancelled and it presents
    /// the pure damping `kp` (the stick-slip frequency), > 0. Null: the string's first natural
    /// frequency (fixed top, bit free or with the BHA inertia).
    #[schemars(extend("unit" = "Hz", "label" = "tuning frequency"))]
    pub tuning_frequency: Option<f64>,
    /// `soft_torque`, `z_torque`: the damping the top drive presents, in units of the top
    /// section's impedance `Z = J sqrt(G rho)`, > 0.
    ///
    /// Default 4, the published defaults of Simulator4nDOF (NORCE): its SoftTorque proportional gain `4 Z` and its ZTorque factor
    /// `0.25 / Z` on the high-passed torque (`1 / (z_factor Z)` here). On
    /// `examples/on-bottom-3000m.toml` at 40 rpm (300 cells) both then remove the stick-slip the
    /// PI controller leaves (SSI 0.21 and 0.03 against 1.12); at 1 `soft_torque` made it worse
    /// (1.47). Dimensionless; 1 matches the pipe (a torque wave is absorbed completely), larger
    /// is stiffer.
    #[schemars(extend("unit" = "", "label" = "impedance factor"))]
    pub z_factor: f64,
    /// `z_torque`: time constant of the low-pass that takes the mean string torque out of the
    /// impedance feedback (so that only the torque waves reduce the speed), > 0.
    ///
    /// Default `20 / (2 pi)` s: the torque high-pass of the ZTorque controller of Simulator4nDOF.
    /// While the string winds up before break-off its torque rises at `k Omega` (`k` the
    /// string's torsional stiffness), which the high-pass passes as `T k Omega`: the top drive
    /// turns at about `setpoint / (1 + T k / (z_factor Z))` until the mean torque has caught up
    /// (33 of 60 rpm for 15 s on `examples/on-bottom-3000m.toml` with the default; 14 rpm for
    /// 25 s at `z_factor = 1`). The `z_torque` preset ties `T` to the string, `1 / (pi f1)`.
    #[schemars(extend("unit" = "s", "label" = "torque high-pass time"))]
    pub torque_highpass_time: f64,
}

impl Default for Controller {
    /// Aarsnes & Shor (2018), MAIN.m: PI with `kp = 38e3`, `ki = 100e3`.
    fn default() -> Self {
        Controller {
            kind: ControllerKind::Pi,
            preset: None,
            kp: 38e3,
            ki: 100e3,
            tuning_frequency: None,
            z_factor: 4.0,
            torque_highpass_time: 20.0 / (2.0 * std::f64::consts::PI),
        }
    }
}

/// The top drive: inertia, setpoint and controller.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct TopDrive {
    /// Rotor inertia of the top drive, > 0.
    #[schemars(extend("unit" = "kg*m^2", "label" = "top-drive inertia"))]
    pub inertia: f64,
    /// The motor torque is clipped to `[-limit, limit]` (anti-windup), for every controller; > 0,
    /// a very large value (1e12) for no limit.
    ///
    /// Default 60 kN m: the continuous rating of a large top drive, as Simulator4nDOF (NORCE) sets
    /// its maximum top-drive torque; a run whose static torque exceeds it is warned that the
    /// string may never break free.
    #[schemars(extend("unit" = "N*m", "label" = "motor torque limit"))]
    pub torque_limit: f64,
    /// The top drive's speed setpoint (finite; negative turns the other way).
    #[schemars(extend("unit" = "rpm", "label" = "top-drive speed setpoint"))]
    pub rpm: f64,
    /// Time constant of the first-order approach of the setpoint from 0, >= 0 (0: a step).
    #[schemars(extend("unit" = "s", "label" = "ramp time"))]
    pub ramp_time: f64,
    /// `[time, rpm]` changes of the setpoint target at increasing times (approached with
    /// `ramp_time` too).
    #[schemars(extend("label" = "setpoint steps", "item_units" = ["s", "rpm"], "item_labels" = ["step time", "top-drive speed setpoint"]))]
    pub steps: Vec<[f64; 2]>,
    /// The speed controller.
    #[schemars(extend("label" = "controller"))]
    pub controller: Controller,
    /// Period of the zero-order hold of `pi` and `soft_torque`, > 0.
    #[schemars(extend("unit" = "s", "label" = "control interval"))]
    pub control_interval: f64,
    /// `speed`, `z_torque`: the bandwidth of the motor's speed loop, > 0.
    ///
    /// The top speed follows
    /// the speed these controllers ask for as a first-order lag of time constant
    /// `1 / (2 pi motor_bandwidth)` (exact over each step), so that the motor torque is the
    /// torque of a real drive and converges as the grid is refined (an ideal speed source asks
    /// the top-drive inertia times the jump of the speed over one step, a torque that grows as
    /// `1 / dt`). Default 10 Hz, the order of a variable-frequency drive's speed loop, well above
    /// a string's torsional modes (0.1-2 Hz).
    #[schemars(extend("unit" = "Hz", "label" = "motor bandwidth"))]
    pub motor_bandwidth: f64,
    /// What drives the top: `controller` (default: the controller of `controller` follows the
    /// setpoint `rpm`, `ramp_time`, `steps`) or `measured_speed` (the top speed is the series
    /// `speed_series`, imposed exactly, and the motor torque is the torque that imposes it:
    /// [`crate::drilling::engine::boundary::imposing_torque`]; the controller, setpoint and
    /// torque limit are then not used).
    #[schemars(extend("label" = "top boundary"))]
    pub mode: TopMode,
    /// `measured_speed`: the top-drive speed as `[time, rpm]` pairs, linearly interpolated;
    /// times finite and strictly increasing, covering the run (the first at or before 0, the
    /// last at or after `numerics.duration`). Empty with `controller`.
    #[schemars(extend("label" = "measured surface speed", "item_units" = ["s", "rpm"], "item_labels" = ["time", "top-drive speed"]))]
    pub speed_series: Vec<[f64; 2]>,
}

/// What drives the top of the string (`top_drive.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TopMode {
    /// The top drive with its controller and setpoint.
    #[default]
    Controller,
    /// The top speed follows `top_drive.speed_series` (a measured surface speed).
    MeasuredSpeed,
}

impl TopMode {
    pub const NAMES: [&'static str; 2] = ["controller", "measured_speed"];
}

impl Default for TopDrive {
    /// Aarsnes & Shor (2018): `I_TD = 2900` kg m^2, 40 rpm reached with a 1 s time constant,
    /// controller period 0.01 s.
    fn default() -> Self {
        TopDrive {
            inertia: 2900.0,
            torque_limit: DEFAULT_TORQUE_LIMIT,
            rpm: 40.0,
            ramp_time: 1.0,
            steps: Vec::new(),
            controller: Controller::default(),
            control_interval: 0.01,
            motor_bandwidth: 10.0,
            mode: TopMode::Controller,
            speed_series: Vec::new(),
        }
    }
}

/// The bit: off bottom (free end or a lumped BHA inertia) or on bottom (Navarro-Lopez torque).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Bit {
    /// Whether the bit cuts (on bottom, the bit-rock torque) or hangs free.
    #[schemars(extend("label" = "bit on bottom"))]
    pub on_bottom: bool,
    /// Weight on bit `W`, >= 0.
    #[schemars(extend("unit" = "N", "label" = "weight on bit"))]
    pub weight_on_bit: f64,
    /// Bit radius `r`, > 0 (or give `diameter`, not both).
    #[schemars(extend("unit" = "m", "label" = "bit radius"))]
    pub radius: f64,
    /// Bit diameter, > 0, in place of `radius` (not both). Null: `radius` gives the bit.
    #[schemars(extend("unit" = "m", "label" = "bit diameter"))]
    pub diameter: Option<f64>,
    /// Static bit-rock friction coefficient `mu_s`, >= 0.
    #[schemars(extend("unit" = "", "label" = "static bit friction"))]
    pub mu_static: f64,
    /// Kinetic bit-rock friction coefficient `mu_k`, from 0 to `mu_static`.
    #[schemars(extend("unit" = "", "label" = "kinetic bit friction"))]
    pub mu_kinetic: f64,
    /// Velocity-weakening rate of `T = W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)`, >= 0.
    #[schemars(extend("unit" = "s/rad", "label" = "velocity-weakening rate"))]
    pub decay: f64,
    /// Below this speed the bit sticks while the holding torque is within `W r mu_s`; >= 0.
    #[schemars(extend("unit" = "rad/s", "label" = "bit stick speed"))]
    pub stick_speed: f64,
    /// Lumped inertia at the bit, >= 0 (0: none).
    #[schemars(extend("unit" = "kg*m^2", "label" = "BHA inertia"))]
    pub bha_inertia: f64,
    /// The bit-rock law: `velocity_weakening` (default: the torque `W r mu(|w|)` with the weight
    /// on bit `weight_on_bit`, torsion only), `detournay` (the Detournay cutting + contact law of
    /// `bit.detournay` with the depth of cut per revolution `2 pi v / omega` of the bit's speeds)
    /// or `rgd` (the same law with the regenerative depth of cut, the bit's position one blade
    /// pass back), or `detournay_weakening` (the `detournay` law with the wear flats' friction
    /// falling with the bit's speed, `bit.weakening`). The laws but `velocity_weakening` need a
    /// `[hoist]` table and the reverse.
    #[schemars(extend("label" = "bit-rock law"))]
    pub law: BitRockLaw,
    #[schemars(extend("label" = "Detournay bit law"))]
    pub detournay: Detournay,
    #[schemars(extend("label" = "wear-flat friction weakening"))]
    pub weakening: Weakening,
    /// Lumped mass at the bit on the axial field of a coupled run (`[hoist]`), >= 0 (0: none,
    /// the string's end alone): its inertia and its buoyed weight along the hole (the density of
    /// the last section), which the string carries in the initial static tension.
    #[schemars(extend("unit" = "kg", "label" = "BHA mass"))]
    pub bha_mass: f64,
}

/// The bit-rock law of the bit (`bit.law`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BitRockLaw {
    /// The Navarro-Lopez velocity-weakening torque at the weight on bit `bit.weight_on_bit`.
    VelocityWeakening,
    /// The Detournay law with the depth of cut from the bit's axial and angular speed.
    Detournay,
    /// The Detournay law with the regenerative depth of cut (Richard, Germay & Detournay 2007).
    Rgd,
    /// The Detournay law (rate form) with the wear flats' friction falling with the bit's speed.
    DetournayWeakening,
}

impl BitRockLaw {
    /// The law's name in the configuration (`bit.law`).
    pub fn name(self) -> String {
        serde_json::to_value(self).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default()
    }
}

/// The Detournay cutting + frictional-contact law (`bit.law` `detournay` or `rgd`; Richard,
/// Germay & Detournay 2007) with the bit radius `bit.radius`: cutting `W_c = a zeta eps d`,
/// `T_c = a^2 eps d / 2`, contact `W_f <= a l sigma`, `T_f = gamma mu a W_f / 2` (`d` the depth
/// of cut per revolution). Defaults: Aarsnes & van de Wouw (2019).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Detournay {
    /// Number of blades `n`, >= 1.
    #[schemars(extend("unit" = "", "label" = "blades"))]
    pub blades: u32,
    /// Intrinsic specific energy of the rock `eps`, > 0: the cutting energy per volume.
    #[schemars(extend("unit" = "Pa", "label" = "intrinsic specific energy"))]
    pub intrinsic_specific_energy: f64,
    /// Ratio `zeta` of the vertical to the horizontal cutting force, >= 0.
    #[schemars(extend("unit" = "", "label" = "cutting force ratio"))]
    pub cutting_ratio: f64,
    /// Contact strength `sigma` under the wear flats, >= 0.
    #[schemars(extend("unit" = "Pa", "label" = "contact strength"))]
    pub contact_strength: f64,
    /// Total wear-flat length `l` (sum over the blades), >= 0.
    #[schemars(extend("unit" = "m", "label" = "wear-flat length"))]
    pub wear_flat_length: f64,
    /// Friction coefficient `mu` at the wear-flat/rock contact, >= 0.
    #[schemars(extend("unit" = "", "label" = "wear-flat friction"))]
    pub friction: f64,
    /// Bit geometry factor `gamma` (1 for a flat bit profile), >= 0.
    #[schemars(extend("unit" = "", "label" = "bit geometry factor"))]
    pub geometry: f64,
    /// The regenerative depth of cut of `bit.law = "rgd"`: `exact_delay` (default: the bit's
    /// position one blade angle back, interpolated exactly) or `upwind` (Aarsnes & van de Wouw's
    /// cut surface, first-order upwind on `cut_surface_cells` cells; diffusive).
    ///
    /// The upwind surface converges to the exact delay at first order in the cells; on their 169
    /// cells at 30 rpm its diffusion damps the regenerative instability (see the drilling guide).
    #[schemars(extend("label" = "cut surface"))]
    pub cut_surface: CutSurfaceScheme,
    /// Cells of the `upwind` cut surface over one blade angle, 1 to 1000000 (their code: 169, 84,
    /// 42 at 30, 60, 120 rpm); unused with `exact_delay`.
    #[schemars(extend("unit" = "", "label" = "cut-surface cells"))]
    pub cut_surface_cells: u32,
}

/// The regenerative depth of cut's numerics (`bit.detournay.cut_surface`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CutSurfaceScheme {
    /// The exact delay: the recorded bit position one blade angle back, interpolated.
    ExactDelay,
    /// First-order upwind transport of the depth of cut on `cut_surface_cells` cells.
    Upwind,
}

/// The most cells of an upwind cut surface (`bit.detournay.cut_surface_cells`).
pub const MAX_CUT_SURFACE_CELLS: u32 = 1_000_000;

impl Default for Detournay {
    /// The published case, [`DetournayBit::PUBLISHED`].
    fn default() -> Self {
        let p = DetournayBit::PUBLISHED;
        Detournay {
            blades: p.blades,
            intrinsic_specific_energy: p.intrinsic_specific_energy,
            cutting_ratio: p.cutting_ratio,
            contact_strength: p.contact_strength,
            wear_flat_length: p.wear_flat_length,
            friction: p.friction,
            geometry: p.geometry,
            cut_surface: CutSurfaceScheme::ExactDelay,
            cut_surface_cells: 169,
        }
    }
}

impl Detournay {
    /// The law with the bit radius `radius`.
    pub fn law(&self, radius: f64) -> DetournayBit {
        DetournayBit {
            radius,
            blades: self.blades,
            intrinsic_specific_energy: self.intrinsic_specific_energy,
            cutting_ratio: self.cutting_ratio,
            contact_strength: self.contact_strength,
            wear_flat_length: self.wear_flat_length,
            friction: self.friction,
            geometry: self.geometry,
        }
    }
}

/// What the hoist imposes at the top of the axial field (`hoist.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HoistKind {
    /// The block velocity `hoist.speed`.
    Velocity,
    /// The hook load `hoist.hook_load`.
    HookLoad,
    /// The weight on bit `hoist.weight_on_bit`: the hook load held at the static hook load of
    /// the string hanging off bottom less this weight (what a rig's weight indicator shows).
    WeightOnBit,
    /// The block velocity of the autodriller `[hoist.autodriller]` (a PI on the weight on bit or
    /// the rate of penetration).
    Autodriller,
}

/// The hoist at the top of the string. With a `[hoist]` table the run is coupled axial-torsional
/// with the bit on bottom (`bit.law` `detournay` or `rgd`); without it, torsion only.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Hoist {
    /// What the hoist imposes: `velocity` (the block velocity `speed`, default), `hook_load`
    /// (the force `hook_load` holding the string up), `weight_on_bit` (the hook load held at the
    /// static hook load of the string hanging off bottom less `weight_on_bit`) or `autodriller`
    /// (the block velocity of the PI `[hoist.autodriller]`).
    #[schemars(extend("label" = "hoist mode"))]
    pub mode: HoistKind,
    /// Block velocity of `velocity` mode, down positive (default 30 m/h).
    #[schemars(extend("unit" = "m/s", "label" = "block velocity"))]
    pub speed: f64,
    /// Hook load of `hook_load` mode, >= 0.
    #[schemars(extend("unit" = "N", "label" = "hook load"))]
    pub hook_load: f64,
    /// Weight on bit of `weight_on_bit` mode, >= 0: the static hook load of the hanging string
    /// less the hook load held (ramped from 0 with `ramp_time`).
    #[schemars(extend("unit" = "N", "label" = "hoist weight on bit"))]
    pub weight_on_bit: f64,
    /// Time constant of the hoist setpoint's approach to its target, >= 0 (0: a step). The
    /// block velocity starts at 0, the hook load at the static hook load of the hanging string,
    /// the weight on bit at 0.
    #[schemars(extend("unit" = "s", "label" = "hoist ramp time"))]
    pub ramp_time: f64,
    /// `[time, value]` changes of the mode's target at increasing times, approached with
    /// `ramp_time` as the top drive's `steps`: the block velocity (m/s), the hook load (N) or the
    /// autodriller's setpoint (N or m/s). Plain numbers are SI in either unit system.
    #[schemars(extend("label" = "hoist steps", "item_units" = ["s", "m/s or N"], "item_labels" = ["step time", "hoist target"]))]
    pub steps: Vec<[f64; 2]>,
    /// The autodriller of `mode = "autodriller"`.
    #[schemars(extend("label" = "autodriller"))]
    pub autodriller: Autodriller,
}

impl Default for Hoist {
    fn default() -> Self {
        let p = HoistParams::default();
        Hoist {
            mode: HoistKind::Velocity,
            speed: p.speed,
            hook_load: p.hook_load,
            weight_on_bit: p.weight_on_bit,
            ramp_time: p.ramp_time,
            steps: p.steps,
            autodriller: p.autodriller,
        }
    }
}

impl Hoist {
    /// The hoist part's parameters.
    pub fn params(&self) -> HoistParams {
        HoistParams {
            mode: match self.mode {
                HoistKind::Velocity => HoistMode::Velocity,
                HoistKind::HookLoad => HoistMode::HookLoad,
                HoistKind::WeightOnBit => HoistMode::WeightOnBit,
                HoistKind::Autodriller => HoistMode::Autodriller,
            },
            speed: self.speed,
            hook_load: self.hook_load,
            weight_on_bit: self.weight_on_bit,
            ramp_time: self.ramp_time,
            steps: self.steps.clone(),
            autodriller: self.autodriller,
        }
    }
}

impl Default for Bit {
    fn default() -> Self {
        Bit {
            on_bottom: false,
            weight_on_bit: 0.0,
            radius: 0.1,
            diameter: None,
            mu_static: 0.8,
            mu_kinetic: 0.5,
            decay: 1.0,
            stick_speed: STICK_SPEED,
            bha_inertia: 0.0,
            law: BitRockLaw::VelocityWeakening,
            detournay: Detournay::default(),
            weakening: Weakening::default(),
            bha_mass: 0.0,
        }
    }
}

/// Discretisation and outputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Numerics {
    /// Target number of cells: `dt = min(sum(L_i / c_i) / cells, min_i L_i / c_i)`, section `i`
    /// gets `floor(L_i / (c_i dt)) >= 1` cells (Courant number `<= 1`, `= 1` when uniform); a
    /// section shorter than a cell of the others raises the count.
    #[schemars(extend("unit" = "", "label" = "cells"))]
    pub cells: usize,
    /// Simulated time, > 0 and at most one day.
    #[schemars(extend("unit" = "s", "label" = "duration"))]
    pub duration: f64,
    /// Sampling interval of the time series, > 0 and at most `duration`.
    #[schemars(extend("unit" = "s", "label" = "output interval"))]
    pub output_interval: f64,
    /// Sampling interval of the space-time snapshots, >= 0 (0: none).
    #[schemars(extend("unit" = "s", "label" = "snapshot interval"))]
    pub field_interval: f64,
    /// A ceiling on `cells`, from 1 to 10 million (a guard against typos).
    #[schemars(extend("unit" = "", "label" = "maximum cells"))]
    pub max_cells: usize,
    /// `consistent` only: the largest shear strain at the outer surface, `gamma = (OD / 2) eps`,
    /// the time step is made for, in (0, 1].
    ///
    /// The step respects the tangent wave speed
    /// `sqrt((k2 + 3 k5 eps^2) / (rho J))` at this strain in every section (Courant number
    /// `<= 1`; every section's speed is raised by the largest of these hardening factors); a run
    /// whose strains exceed it reports a tangent Courant number above 1
    /// (`DrillStats::courant_peak`) in its message. Default 0.005: below the shear yield strain
    /// of high-strength drill-pipe steel (S-135: `931 MPa / sqrt(3) / G ~ 0.0068`), where the
    /// elastic law ends. A larger bound lowers the Courant numbers of the small strains below 1,
    /// where the first-order transport dissipates.
    #[schemars(extend("unit" = "", "label" = "maximum shear strain"))]
    pub max_shear_strain: f64,
    /// The Courant number `c dt / h` the step is made for, in `(0, 1]`: the step is this
    /// fraction of the Courant-1 step of the grid (the cells unchanged).
    ///
    /// Default 1: the exact shift, no numerical diffusion; below 1 the first-order upwind
    /// transport diffuses (`upwind_loss`), as the scheme of Aarsnes & Shor's code does at its 0.929.
    #[schemars(extend("unit" = "", "label" = "Courant number"))]
    pub courant: f64,
    /// The speed of a cell its sources are evaluated at: `after_transport` (default; the
    /// material now in the cell) or `before_transport` (the speed at the step start, as
    /// torsionalWaveStep.m of Aarsnes & Shor).
    ///
    /// With `before_transport` the wall friction's stick threshold (`friction.stick_speed`), the
    /// kinetic friction's direction and the viscous damping take the speed before the transport;
    /// the torque that stops a slow cell stays the one at the transported speed, and the kinetic
    /// friction is not clipped (it may reverse a cell within a step, as in their code). It exists
    /// to reproduce their published scheme; both converge to the same solution as the grid is
    /// refined. Linear torque-twist law and set-valued friction only.
    #[schemars(extend("label" = "source speed"))]
    pub source_speed: SourceSpeed,
    /// Where a coupled run starts: `rest` (default; the string at rest under its static
    /// tension, the bit just touching the rock, the setpoints ramping up) or `steady` (the bit
    /// law's steady drilling at the setpoints of t = 0, where Aarsnes & van de Wouw's code starts:
    /// turning at the top-drive speed with the torque of steady rotation, moving down at the
    /// hoist's rate, compressed to the steady weight on bit less the wall's drag, the bit at its
    /// steady depth of cut; [`super::start`]). `steady` needs a `[hoist]` that drills at t = 0.
    #[schemars(extend("label" = "initial state"))]
    pub initial_state: super::start::InitialState,
}

/// The speed of a cell its sources are evaluated at ([`Numerics::source_speed`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SourceSpeed {
    /// The transported speed (the solver's scheme).
    #[default]
    AfterTransport,
    /// The speed before the transport (the scheme of torsionalWaveStep.m).
    BeforeTransport,
}

impl Default for Numerics {
    /// Aarsnes & Shor (2018), parameters_WellB.m and MAIN.m: 1000 cells, 60 s.
    fn default() -> Self {
        Numerics {
            cells: 1000,
            duration: 60.0,
            output_interval: 0.01,
            field_interval: 0.5,
            max_cells: 1_000_000,
            max_shear_strain: 0.005,
            courant: 1.0,
            source_speed: SourceSpeed::AfterTransport,
            initial_state: super::start::InitialState::Rest,
        }
    }
}

/// The metrics window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MetricsConfig {
    /// `[t_start, t_end]` of the metrics window, `t_start < t_end`, holding at least two samples.
    /// Null: the last half of the run.
    #[schemars(extend("unit" = "s", "label" = "metrics window"))]
    pub window: Option<[f64; 2]>,
    /// The bit counts as stuck at or below this speed, >= 0.
    #[schemars(extend("unit" = "rad/s", "label" = "stick speed"))]
    pub stick_speed: f64,
}

impl Default for MetricsConfig {
    fn default() -> Self {
        MetricsConfig { window: None, stick_speed: STICK_SPEED }
    }
}

/// The static torque-and-drag analysis (`drillstring torque-drag`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct TorqueDragConfig {
    /// The torque on bit when drilling (rotating on bottom), >= 0.
    #[schemars(extend("unit" = "N*m", "label" = "torque on bit"))]
    pub bit_torque: f64,
    /// The travelling block's weight (with hook and top drive), added to hook loads, >= 0.
    #[schemars(extend("unit" = "N", "label" = "block weight"))]
    pub block_weight: f64,
    /// The longest element of the stepped solution, > 0 and at least the string's length over
    /// a million (the elements' count is bounded).
    #[schemars(extend("unit" = "m", "label" = "element length"))]
    pub step: f64,
    /// The friction factors of the broomstick plot (uniform along the hole), 1 to 100, each in [0, 10].
    #[schemars(extend("unit" = "", "label" = "friction factor"))]
    pub friction_factors: Vec<f64>,
    /// Bit depths of the broomstick plot, evenly spaced to the string's length, 2 to 100000.
    #[schemars(extend("unit" = "", "label" = "broomstick points"))]
    pub broomstick_points: usize,
}

impl Default for TorqueDragConfig {
    fn default() -> Self {
        TorqueDragConfig {
            bit_torque: 0.0,
            block_weight: 0.0,
            step: crate::well::torque_drag::DEFAULT_STEP,
            friction_factors: vec![0.1, 0.2, 0.3, 0.4],
            broomstick_points: 100,
        }
    }
}

/// A drilling-system run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DrillConfig {
    /// The string's sections from the top, 1 to 1000 (required).
    #[schemars(extend("label" = "sections"))]
    pub sections: Vec<Section>,
    #[schemars(extend("label" = "well"))]
    pub well: Well,
    #[schemars(extend("label" = "wall friction"))]
    pub friction: Friction,
    /// Viscous damping rate `c`, >= 0: the force `-rho J c omega` per unit length.
    #[schemars(extend("unit" = "1/s", "label" = "damping rate"))]
    pub damping_rate: f64,
    /// The torque-twist law: `linear` (default) or `consistent` (finite strain).
    #[schemars(extend("label" = "torque-twist law"))]
    pub nonlinearity: Nonlinearity,
    #[schemars(extend("label" = "top drive"))]
    pub top_drive: TopDrive,
    #[schemars(extend("label" = "bit"))]
    pub bit: Bit,
    #[schemars(extend("label" = "numerics"))]
    pub numerics: Numerics,
    #[schemars(extend("label" = "metrics"))]
    pub metrics: MetricsConfig,
    #[schemars(extend("label" = "torque and drag"))]
    pub torque_drag: TorqueDragConfig,
    /// The hoist: null (default) for a torsion-only run.
    #[schemars(extend("label" = "hoist"))]
    pub hoist: Option<Hoist>,
}

impl Default for DrillConfig {
    /// One template section ([`Section::default`]); every other part its own default.
    fn default() -> Self {
        DrillConfig {
            sections: vec![Section::default()],
            well: Well::default(),
            friction: Friction::default(),
            damping_rate: 0.0,
            nonlinearity: Nonlinearity::Linear,
            top_drive: TopDrive::default(),
            bit: Bit::default(),
            numerics: Numerics::default(),
            metrics: MetricsConfig::default(),
            torque_drag: TorqueDragConfig::default(),
            hoist: None,
        }
    }
}

/// Keys that must be present in a configuration's JSON.
pub(crate) const REQUIRED_TOP: [&str; 1] = ["sections"];
pub(crate) const REQUIRED_SECTION: [&str; 3] = ["length", "outer_diameter", "inner_diameter"];

/// A drilling configuration's error of the schema parse, in its own words: a top-drive step
/// names the step (`top_drive.steps[1]`, `[time s, rpm]`), the inclination its two forms, a
/// non-finite number the field's range ([`finite_range`], when `probe`).
fn refine(user: &Value, error: Error, probe: bool) -> Error {
    let Error::InvalidInput { field, value, allowed } = error;
    for key in ["steps", "speed_series"] {
        if let Some(rest) = field.strip_prefix(&format!("top_drive.{key}[")) {
            let index = rest.split(']').next().unwrap_or("");
            let step = user.pointer(&format!("/top_drive/{key}/{index}")).map_or(value, shown);
            return Error::invalid(format!("top_drive.{key}[{index}]"), step, "[time s, rpm]");
        }
    }
    if allowed.contains("untagged enum Inclination") {
        return Error::invalid(field, value, "a number or an array of numbers (degrees)");
    }
    if allowed == "a finite number" && probe {
        if let Some(range) = finite_range(user, &field) {
            return Error::invalid(field, value, range);
        }
    }
    Error::InvalidInput { field, value, allowed }
}

/// The range a numeric field takes, in the words of its own check, for the message of a
/// non-finite value there (`nan`, `inf`, which the parser refuses before any range is checked):
/// the configuration is checked again with a finite value at `field` far out of every range,
/// `-1e308` and then `1e308`, and the first error that names `field` gives the range. None when
/// both pass, or another field fails first.
fn finite_range(user: &Value, field: &str) -> Option<String> {
    let pointer: String = field.replace('[', ".").replace(']', "").split('.').map(|k| format!("/{k}")).collect();
    for probe in [-1e308, 1e308] {
        let mut copy = user.clone();
        *copy.pointer_mut(&pointer)? = Value::from(probe);
        match DrillConfig::parse_value(copy, false).and_then(|c| c.validate()) {
            Err(Error::InvalidInput { field: f, allowed, .. }) if f == field => return Some(allowed),
            Err(_) => return None,
            Ok(()) => {}
        }
    }
    None
}

/// The constant-inclination rule, the one place it lives: one inclination number
/// (`well.inclination_deg = 20`) with no survey depths given means no survey (`well.md` null;
/// the default depths are the default table's).
fn constant_inclination(well: &mut Map<String, Value>, md_given: bool) {
    if !md_given && well.get("inclination_deg").is_some_and(Value::is_number) {
        well.insert("md".into(), Value::Null);
    }
}

/// The error of a bit given by both its radius and its diameter.
fn bit_size_conflict() -> Error {
    Error::invalid(
        "bit.diameter",
        "both bit.radius and bit.diameter",
        "one of bit.radius or bit.diameter (the diameter is twice the radius)",
    )
}

/// After overrides: a bit radius set by an override replaces the configuration's diameter and a
/// diameter its radius (a table `bit` counts by its keys); both set is refused by the parse.
fn bit_size_override(config: &mut Value, overrides: &[Override]) {
    let sets = |key: &str| {
        overrides.iter().any(|(p, v): &Override| {
            (p == "bit" && v.get(key).is_some_and(|x| !x.is_null()))
                || (p.strip_prefix("bit.") == Some(key) && !v.is_null())
        })
    };
    let (radius, diameter) = (sets("radius"), sets("diameter"));
    if let Some(Value::Object(bit)) = config.get_mut("bit") {
        if diameter && !radius {
            bit.remove("radius");
        } else if radius && !diameter {
            bit.remove("diameter");
        }
    }
}

fn require(path: &str, map: &Map<String, Value>, keys: &[&str]) -> Result<()> {
    for k in keys {
        if !map.contains_key(*k) {
            return Err(Error::invalid(join(path, k), "missing", "a value (required)"));
        }
    }
    Ok(())
}

impl DrillConfig {
    /// Parses a configuration (JSON object), filling defaults; an error names the dotted field
    /// of an unknown key, a wrong type or a missing required value. Does not validate ranges
    /// ([`DrillConfig::validate`]).
    pub fn from_json(json: &str) -> Result<DrillConfig> {
        let user: Value = serde_json::from_str(json)
            .map_err(|e| Error::invalid("config", format!("text that is not JSON ({e})"), "a JSON object"))?;
        DrillConfig::from_value(user)
    }

    /// [`DrillConfig::from_json`] of a parsed JSON value.
    pub fn from_value(user: Value) -> Result<DrillConfig> {
        DrillConfig::parse_value(user, true)
    }

    /// [`DrillConfig::from_value`]; `probe`: a non-finite number's error names the field's
    /// range ([`finite_range`], which parses without probing).
    fn parse_value(mut user: Value, probe: bool) -> Result<DrillConfig> {
        let Value::Object(map) = &mut user else {
            return Err(Error::invalid("config", kind(&user), "a JSON object"));
        };
        require("", map, &REQUIRED_TOP)?;
        if let Some(Value::Array(sections)) = map.get("sections") {
            for (i, s) in sections.iter().enumerate() {
                if let Value::Object(s) = s {
                    require(&format!("sections[{i}]"), s, &REQUIRED_SECTION)?;
                }
            }
        }
        // a survey file or a plan replaces the stations: refuse both, and an inclination beside them
        let well_value = |key: &str| map.get("well").and_then(|w| w.get(key)).is_some_and(|v| !v.is_null());
        let sources: Vec<&str> = ["survey", "plan", "md"].into_iter().filter(|k| well_value(k)).collect();
        if sources.len() > 1 {
            return Err(Error::invalid(
                format!("well.{}", sources[1]),
                format!("both well.{} and well.{}", sources[0], sources[1]),
                "one of well.survey (a file), well.plan (segments), well.md with well.inclination_deg",
            ));
        }
        let stations_replaced = well_value("survey") || well_value("plan");
        let placeholder = map.get("well").and_then(|w| w.get("inclination_deg")).and_then(Value::as_f64) == Some(0.0);
        if stations_replaced && well_value("inclination_deg") && !placeholder {
            return Err(Error::invalid(
                "well.inclination_deg",
                "a value with a survey file or plan",
                "no value, or 0 (the survey file or plan gives the inclinations)",
            ));
        }
        if let Some(Value::Object(well)) = map.get_mut("well") {
            let md_given = well.contains_key("md");
            constant_inclination(well, md_given);
            if stations_replaced {
                well.insert("md".into(), Value::Null);
                well.insert("inclination_deg".into(), Value::from(0.0));
            }
        }
        if let Some(Value::Object(bit)) = map.get("bit") {
            let given = |key: &str| bit.get(key).is_some_and(|v| !v.is_null());
            if given("radius") && given("diameter") {
                return Err(bit_size_conflict());
            }
        }
        let mut cfg: DrillConfig = schema::parse(&user).map_err(|e| refine(&user, e, probe))?;
        if let Some(d) = cfg.bit.diameter.take() {
            // the normalised configuration gives the bit by its radius
            pos("bit.diameter", d, "m, or null to give bit.radius")?;
            cfg.bit.radius = d / 2.0;
        }
        super::well::load_survey(&mut cfg)?;
        let given: Vec<String> = user
            .pointer("/top_drive/controller")
            .and_then(Value::as_object)
            .map_or_else(Vec::new, |c| c.keys().cloned().collect());
        super::tuning::apply_preset(&mut cfg, &given)?;
        Ok(cfg)
    }

    /// The configuration as JSON, every default filled in.
    pub fn to_json(&self) -> String {
        // with a survey file or a plan, `well.md` is null and `well.inclination_deg` the
        // placeholder 0, which parse back to the same configuration
        serde_json::to_string(self).unwrap_or_else(|_| "{}".into())
    }

    /// Checks every value's range, naming the dotted field; also the discretisation (cell
    /// count, time step) and the output size against [`MAX_OUTPUT_BYTES`].
    pub fn validate(&self) -> Result<()> {
        self.validate_values()?;
        let grid = Grid::new(self)?;
        self.check_outputs(&grid)?;
        super::limits::check_cut_surface_work(self, &grid)
    }

    /// The coupled run's keys: `bit.law` `detournay` or `rgd` with a `[hoist]` table and the
    /// reverse, the Detournay law's and the hoist's ranges.
    fn validate_coupled(&self) -> Result<()> {
        // (whether the law needs the axial field, as the law declares it)
        let coupled = bit_law::axial_need(self.bit.law) == bit_law::AxialNeed::DepthOfCut;
        match (&self.hoist, coupled) {
            (None, true) => {
                return Err(Error::invalid(
                    "bit.law",
                    self.bit.law.name(),
                    "velocity_weakening without a [hoist] table (detournay and rgd need the hoist's axial field)",
                ))
            }
            (Some(_), false) => {
                return Err(Error::invalid(
                    "hoist",
                    "a [hoist] table with bit.law = velocity_weakening",
                    "bit.law = detournay or rgd with a [hoist] table (the coupled run), or no [hoist] table",
                ))
            }
            _ => {}
        }
        if coupled && self.bit.on_bottom {
            // the velocity-weakening law's keys: a coupled bit meets the rock through the hoist
            return Err(Error::invalid(
                "bit.on_bottom",
                format!("true with bit.law = {}", self.bit.law.name()),
                "false (a coupled run's bit reaches the rock through the [hoist] table: hoist.weight_on_bit, \
                 hoist.speed or hoist.hook_load; bit.on_bottom and bit.weight_on_bit belong to the velocity-weakening law)",
            ));
        }
        if let Some(h) = &self.hoist {
            finite("hoist.speed", h.speed, "m/s")?;
            nonneg("hoist.hook_load", h.hook_load, "N")?;
            nonneg("hoist.weight_on_bit", h.weight_on_bit, "N")?;
            nonneg("hoist.ramp_time", h.ramp_time, "s")?;
            h.params().validate("hoist")?;
            bit_law::validate(self)?;
            let cells = self.bit.detournay.cut_surface_cells;
            if !(1..=MAX_CUT_SURFACE_CELLS).contains(&cells) {
                return Err(Error::invalid(
                    "bit.detournay.cut_surface_cells",
                    cells,
                    format!("an integer in 1..={MAX_CUT_SURFACE_CELLS}"),
                ));
            }
        }
        Ok(())
    }

    /// `top_drive.speed_series`: with `mode = "measured_speed"` at least two `[time s, rpm]`
    /// pairs, finite, times strictly increasing and covering `[0, numerics.duration]`; with
    /// `controller` empty (a series that would be ignored is refused).
    fn validate_speed_series(&self) -> Result<()> {
        let td = &self.top_drive;
        let v = &td.speed_series;
        if td.mode == TopMode::Controller {
            if !v.is_empty() {
                return Err(Error::invalid(
                    "top_drive.speed_series",
                    format!("{} pairs", v.len()),
                    "empty with top_drive.mode = \"controller\" (set top_drive.mode = \"measured_speed\" to impose it)",
                ));
            }
            return Ok(());
        }
        if v.len() < 2 {
            return Err(Error::invalid(
                "top_drive.speed_series",
                format!("{} pairs", v.len()),
                "at least 2 [time s, rpm] pairs with top_drive.mode = \"measured_speed\"",
            ));
        }
        for (i, [t, rpm]) in v.iter().enumerate() {
            finite(format!("top_drive.speed_series[{i}][0]"), *t, "s")?;
            finite(format!("top_drive.speed_series[{i}][1]"), *rpm, "rpm")?;
            if i > 0 && *t <= v[i - 1][0] {
                return Err(Error::invalid(
                    format!("top_drive.speed_series[{i}][0]"),
                    Num(*t),
                    format!("times strictly increasing (after {} s)", Num(v[i - 1][0])),
                ));
            }
        }
        let (first, last, end) = (v[0][0], v[v.len() - 1][0], self.numerics.duration);
        if first > 0.0 {
            return Err(Error::invalid("top_drive.speed_series[0][0]", Num(first), "a time <= 0 s (covering the run)"));
        }
        if last < end {
            return Err(Error::invalid(
                format!("top_drive.speed_series[{}][0]", v.len() - 1),
                Num(last),
                format!("a time >= numerics.duration = {} s (covering the run)", Num(end)),
            ));
        }
        Ok(())
    }

    fn validate_values(&self) -> Result<()> {
        let n = self.sections.len();
        if !(1..=MAX_SECTIONS).contains(&n) {
            return Err(Error::invalid("sections", format!("{n} sections"), format!("1..={MAX_SECTIONS} sections")));
        }
        let mut min_density = f64::INFINITY;
        for (i, s) in self.sections.iter().enumerate() {
            let f = |k: &str| format!("sections[{i}].{k}");
            if !(s.length.is_finite() && s.length > 0.0 && s.length <= MAX_SECTION_LENGTH) {
                return Err(Error::invalid(
                    f("length"),
                    Num(s.length),
                    format!("a finite number > 0 m, at most {MAX_SECTION_LENGTH} m"),
                ));
            }
            if !(s.outer_diameter.is_finite() && s.outer_diameter > 0.0 && s.outer_diameter <= MAX_DIAMETER) {
                return Err(Error::invalid(
                    f("outer_diameter"),
                    Num(s.outer_diameter),
                    format!("a finite number > 0 m, at most {MAX_DIAMETER} m (in metres: 5 in = 0.127 m)"),
                ));
            }
            if let Some(d) = s.contact_diameter {
                if !(d.is_finite() && d > 0.0 && d <= MAX_DIAMETER) {
                    return Err(Error::invalid(
                        f("contact_diameter"),
                        Num(d),
                        format!("a finite number > 0 m, at most {MAX_DIAMETER} m, or null for the outer diameter"),
                    ));
                }
            }
            if !(s.inner_diameter.is_finite() && s.inner_diameter >= 0.0 && s.inner_diameter < s.outer_diameter) {
                return Err(Error::invalid(
                    f("inner_diameter"),
                    Num(s.inner_diameter),
                    format!("a finite number in [0, outer_diameter = {}) (m)", Num(s.outer_diameter)),
                ));
            }
            pos(f("shear_modulus"), s.shear_modulus, "Pa")?;
            pos(f("density"), s.density, "kg/m^3")?;
            crate::model::check_poisson_ratio(f("poisson_ratio"), s.poisson_ratio)?;
            for (k, v, unit) in [
                ("contact_diameter", s.contact_diameter, "m"),
                ("polar_moment", s.polar_moment, "m^4"),
                ("area", s.area, "m^2"),
                ("quartic_moment", s.quartic_moment, "m^6"),
            ] {
                if let Some(v) = v {
                    pos(f(k), v, &format!("{unit}, or null for the default"))?;
                }
            }
            min_density = min_density.min(s.density);
        }
        let w = &self.well;
        let replaced = w.survey.is_some() || w.plan.is_some();
        match (&w.md, &w.inclination_deg) {
            _ if replaced => {}
            (None, Inclination::Constant(x)) => super::limits::check_inclination("well.inclination_deg", *x)?,
            (Some(_), Inclination::Constant(_)) => {
                return Err(Error::invalid(
                    "well.inclination_deg",
                    "a single number with well.md given",
                    "a list of one inclination per well.md station (or null well.md)",
                ))
            }
            (None, Inclination::Table(_)) => {
                return Err(Error::invalid("well.md", "null", "the measured depths of the inclination table"))
            }
            (Some(md), Inclination::Table(inc)) => {
                if md.is_empty() {
                    return Err(Error::invalid("well.md", "an empty list", "at least one station"));
                }
                for (j, d) in md.iter().enumerate() {
                    finite(format!("well.md[{j}]"), *d, "m")?;
                    if j > 0 && *d <= md[j - 1] {
                        return Err(Error::invalid(
                            format!("well.md[{j}]"),
                            Num(*d),
                            format!("strictly increasing depths (> well.md[{}] = {})", j - 1, Num(md[j - 1])),
                        ));
                    }
                }
                if inc.len() != md.len() {
                    return Err(Error::invalid(
                        "well.inclination_deg",
                        format!("{} values", inc.len()),
                        format!("{} values (one per well.md station)", md.len()),
                    ));
                }
                for (j, x) in inc.iter().enumerate() {
                    super::limits::check_inclination(format!("well.inclination_deg[{j}]"), *x)?;
                }
            }
        }
        if !(w.mud_density.is_finite() && w.mud_density >= 0.0 && w.mud_density < min_density) {
            return Err(Error::invalid(
                "well.mud_density",
                Num(w.mud_density),
                format!("a finite number in [0, {}) kg/m^3 (below every section's density)", Num(min_density)),
            ));
        }
        nonneg("well.gravity", w.gravity, "m/s^2")?;
        match &w.azimuth_deg {
            Inclination::Constant(a) => within("well.azimuth_deg", *a, 0.0, 360.0, "degrees")?,
            Inclination::Table(v) => {
                for (j, a) in v.iter().enumerate() {
                    within(format!("well.azimuth_deg[{j}]"), *a, 0.0, 360.0, "degrees")?;
                }
            }
        }
        super::well::trajectory(self)?;
        for (j, iv) in self.friction.intervals.iter().enumerate() {
            let f = |k: &str| format!("friction.intervals[{j}].{k}");
            nonneg(f("top_md"), iv.top_md, "m")?;
            if !(iv.bottom_md.is_finite() && iv.bottom_md > iv.top_md) {
                return Err(Error::invalid(
                    f("bottom_md"),
                    Num(iv.bottom_md),
                    format!("a finite depth > top_md = {} m", Num(iv.top_md)),
                ));
            }
            nonneg(f("static"), iv.static_coefficient, "-")?;
        }
        super::limits::validate_torque_drag(self)?;
        let fr = &self.friction;
        nonneg("friction.static", fr.static_coefficient, "-")?;
        within("friction.kinetic_ratio", fr.kinetic_ratio, 0.0, 1.0, "-")?;
        nonneg("friction.stick_speed", fr.stick_speed, "rad/s")?;
        pos("friction.regularisation_speed", fr.regularisation_speed, "rad/s")?;
        nonneg("damping_rate", self.damping_rate, "1/s")?;
        self.validate_coupled()?;
        let td = &self.top_drive;
        pos("top_drive.inertia", td.inertia, "kg m^2")?;
        pos("top_drive.motor_bandwidth", td.motor_bandwidth, "Hz")?;
        if td.torque_limit.is_nan() || td.torque_limit <= 0.0 {
            return Err(Error::invalid(
                "top_drive.torque_limit",
                Num(td.torque_limit),
                "a number > 0 N m (a very large value, 1e12, for no limit)",
            ));
        }
        finite("top_drive.rpm", td.rpm, "rpm")?;
        nonneg("top_drive.ramp_time", td.ramp_time, "s")?;
        for (i, [t, rpm]) in td.steps.iter().enumerate() {
            nonneg(format!("top_drive.steps[{i}][0]"), *t, "s")?;
            if i > 0 && *t < td.steps[i - 1][0] {
                return Err(Error::invalid(format!("top_drive.steps[{i}][0]"), Num(*t), "times in increasing order"));
            }
            finite(format!("top_drive.steps[{i}][1]"), *rpm, "rpm")?;
        }
        let c = &td.controller;
        nonneg("top_drive.controller.kp", c.kp, "N m s/rad")?;
        nonneg("top_drive.controller.ki", c.ki, "N m/rad")?;
        if let Some(f) = c.tuning_frequency {
            pos("top_drive.controller.tuning_frequency", f, "Hz, or null for the string's first mode")?;
        }
        pos("top_drive.controller.z_factor", c.z_factor, "-")?;
        pos("top_drive.controller.torque_highpass_time", c.torque_highpass_time, "s")?;
        pos("top_drive.control_interval", td.control_interval, "s")?;
        self.validate_speed_series()?;
        let b = &self.bit;
        nonneg("bit.weight_on_bit", b.weight_on_bit, "N")?;
        pos("bit.radius", b.radius, "m")?;
        if let Some(d) = b.diameter {
            pos("bit.diameter", d, "m, or null to give bit.radius")?;
            if b.radius != d / 2.0 {
                return Err(bit_size_conflict());
            }
        }
        nonneg("bit.mu_static", b.mu_static, "-")?;
        within("bit.mu_kinetic", b.mu_kinetic, 0.0, b.mu_static, "-, at most bit.mu_static")?;
        nonneg("bit.decay", b.decay, "s/rad")?;
        nonneg("bit.stick_speed", b.stick_speed, "rad/s")?;
        nonneg("bit.bha_inertia", b.bha_inertia, "kg m^2")?;
        nonneg("bit.bha_mass", b.bha_mass, "kg")?;
        let nu = &self.numerics;
        if !(1..=MAX_CELLS).contains(&nu.max_cells) {
            return Err(Error::invalid("numerics.max_cells", nu.max_cells, format!("an integer in 1..={MAX_CELLS}")));
        }
        if !(1..=nu.max_cells).contains(&nu.cells) {
            return Err(Error::invalid(
                "numerics.cells",
                nu.cells,
                format!("an integer in 1..={} (numerics.max_cells)", nu.max_cells),
            ));
        }
        if !(nu.duration.is_finite() && nu.duration > 0.0 && nu.duration <= MAX_DURATION) {
            return Err(Error::invalid(
                "numerics.duration",
                Num(nu.duration),
                format!("a number in (0, {MAX_DURATION}] s"),
            ));
        }
        if !(nu.output_interval.is_finite() && nu.output_interval > 0.0 && nu.output_interval <= nu.duration) {
            return Err(Error::invalid(
                "numerics.output_interval",
                Num(nu.output_interval),
                format!("a number in (0, numerics.duration = {}] s", Num(nu.duration)),
            ));
        }
        nonneg("numerics.field_interval", nu.field_interval, "s, 0 for no snapshots")?;
        if !(nu.max_shear_strain.is_finite() && nu.max_shear_strain > 0.0 && nu.max_shear_strain <= 1.0) {
            return Err(Error::invalid(
                "numerics.max_shear_strain",
                Num(nu.max_shear_strain),
                "a number in (0, 1] (-)",
            ));
        }
        if !(nu.courant.is_finite() && nu.courant > 0.0 && nu.courant <= 1.0) {
            return Err(Error::invalid("numerics.courant", Num(nu.courant), "a number in (0, 1] (-)"));
        }
        if nu.source_speed == SourceSpeed::BeforeTransport
            && (self.nonlinearity != Nonlinearity::Linear || self.friction.model != FrictionModel::SetValued)
        {
            return Err(Error::invalid(
                "numerics.source_speed",
                "before_transport",
                "after_transport, or before_transport with nonlinearity = linear and friction.model = set_valued",
            ));
        }
        let m = &self.metrics;
        if let Some([a, b]) = m.window {
            if !(a.is_finite() && b.is_finite() && a < b) {
                return Err(Error::invalid(
                    "metrics.window",
                    format!("[{}, {}]", Num(a), Num(b)),
                    "[t_start, t_end] with t_start < t_end (s), or null for the last half of the run",
                ));
            }
            // at least two series samples t = k output_interval inside the window (the samples
            // the metrics are computed from, as `metrics::stick_slip` selects them)
            let dt = self.numerics.output_interval;
            let last = self.series_samples().saturating_sub(1) as f64;
            let mut lo = (a.max(0.0) / dt).floor();
            while lo * dt < a {
                lo += 1.0;
            }
            let mut hi = (b / dt).floor().min(last);
            while hi >= 0.0 && hi * dt > b {
                hi -= 1.0;
            }
            if hi - lo < 1.0 {
                return Err(Error::invalid(
                    "metrics.window",
                    format!("[{}, {}]", Num(a), Num(b)),
                    format!(
                        "a window holding at least 2 samples of the run's series (0 to numerics.duration = {} s \
                         every {} s)",
                        Num(self.numerics.duration),
                        Num(dt)
                    ),
                ));
            }
        }
        nonneg("metrics.stick_speed", m.stick_speed, "rad/s")?;
        super::limits::validate_loads(self)
    }

    /// Number of series samples (`t = k output_interval <= duration`).
    pub(crate) fn series_samples(&self) -> usize {
        samples(self.numerics.duration, self.numerics.output_interval)
    }

    /// Number of field snapshots (0 without).
    pub(crate) fn field_samples(&self) -> usize {
        if self.numerics.field_interval > 0.0 {
            samples(self.numerics.duration, self.numerics.field_interval)
        } else {
            0
        }
    }

    fn check_outputs(&self, grid: &Grid) -> Result<()> {
        let series = self.series_samples().saturating_mul(SERIES).saturating_mul(8);
        if series > MAX_OUTPUT_BYTES {
            return Err(Error::invalid(
                "numerics.output_interval",
                Num(self.numerics.output_interval),
                format!(
                    "an interval giving at most {} MiB of series ({} samples need {} MiB)",
                    MAX_OUTPUT_BYTES >> 20,
                    self.series_samples(),
                    series >> 20
                ),
            ));
        }
        let fields = self.field_samples().saturating_mul(2 * grid.cells() + 1).saturating_mul(8);
        if series.saturating_add(fields) > MAX_OUTPUT_BYTES {
            return Err(Error::invalid(
                "numerics.field_interval",
                Num(self.numerics.field_interval),
                format!(
                    "an interval giving at most {} MiB of outputs ({} snapshots of {} cells need {} MiB)",
                    MAX_OUTPUT_BYTES >> 20,
                    self.field_samples(),
                    grid.cells(),
                    fields >> 20
                ),
            ));
        }
        let steps = (self.numerics.duration / grid.dt).ceil();
        let work = steps * grid.cells() as f64;
        if work > MAX_CELL_STEPS {
            // a section shorter than a cell of the others sets the step
            let travel: f64 = grid.props.iter().zip(&grid.speed).map(|(p, c)| p.length / c).sum();
            let short = (0..grid.props.len()).find(|&i| {
                grid.counts[i] == 1 && grid.props[i].length / grid.speed[i] < travel / self.numerics.cells as f64
            });
            let what = format!(
                "a run of at most {} cell updates (cells x time steps; this one needs {}: {} cells x {} steps of {} s, \
                 about {} h)",
                Num(MAX_CELL_STEPS),
                Num(work),
                grid.cells(),
                Num(steps),
                Num(grid.dt),
                Num((work / 6e8 / 3600.0 * 10.0).round() / 10.0)
            );
            return Err(match short {
                Some(i) => Error::invalid(
                    format!("sections[{i}].length"),
                    Num(self.sections[i].length),
                    format!("a section long enough for a reasonable time step (its travel time sets the step): {what}"),
                ),
                None => Error::invalid(
                    "numerics.cells",
                    self.numerics.cells,
                    format!("fewer cells or a shorter numerics.duration: {what}"),
                ),
            });
        }
        Ok(())
    }
}

/// One field override: a dotted path with indices (`top_drive.rpm`, `sections[1].length`) and
/// its JSON value.
pub type Override = (String, Value);

/// The tokens of a dotted path with indices: `sections[1].length` -> `sections`, `1`, `length`.
enum Token<'a> {
    Key(&'a str),
    Index(usize),
}

fn tokens(path: &str) -> Option<Vec<Token<'_>>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (name, mut rest) = part.split_once('[').map_or((part, ""), |(n, r)| (n, r));
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return None;
        }
        out.push(Token::Key(name));
        while !rest.is_empty() {
            let (index, after) = rest.split_once(']')?;
            out.push(Token::Index(index.parse().ok()?));
            rest = match after.strip_prefix('[') {
                Some(r) => r,
                None if after.is_empty() => "",
                None => return None,
            };
        }
    }
    Some(out)
}

/// The form of an override's path, as errors state it.
pub const PATH_FORM: &str = "a dotted key with indices of the configuration (top_drive.rpm, sections[0].length)";

/// Sets `path` to `value` in the JSON configuration `config`: a table given for a table is
/// merged into it (its other keys kept), `null` sets null (an optional field's None; a
/// required number refuses it when parsed). The path goes through the tables and lists of
/// `config`; a key missing from a table is added (the parse names an unknown one and lists the
/// allowed keys). `field` names a malformed path in the error (`--set`, `axis`).
pub fn set_path(config: &mut Value, path: &str, value: &Value, field: &str) -> Result<()> {
    let toks = tokens(path).ok_or_else(|| Error::invalid(field, path, PATH_FORM))?;
    let mut node = config;
    let mut at = String::new();
    for (i, tok) in toks.iter().enumerate() {
        let last = i + 1 == toks.len();
        match tok {
            Token::Key(name) => {
                let here = join(&at, name);
                let map = match node {
                    Value::Object(map) => map,
                    Value::Array(items) => {
                        let allowed = format!("an index first: {at} is a list of {} ({at}[0].{name})", items.len());
                        return Err(Error::invalid(here, shown(value), allowed));
                    }
                    other => {
                        let allowed = format!("a key of a table: {at} is {}, not a table", shown(other));
                        return Err(Error::invalid(here, shown(value), allowed));
                    }
                };
                at = here;
                if last {
                    match (map.get_mut(*name), value) {
                        (Some(Value::Object(old)), Value::Object(new)) => {
                            old.extend(new.iter().map(|(k, v)| (k.clone(), v.clone())))
                        }
                        _ => {
                            map.insert((*name).to_string(), value.clone());
                        }
                    }
                    if path == "top_drive.controller.preset" && !value.is_null() {
                        // a preset set now replaces the controller's keys (set again after it to override)
                        for k in super::tuning::PRESET_KEYS {
                            map.remove(k);
                        }
                    }
                    return Ok(());
                }
                node = map.entry((*name).to_string()).or_insert_with(|| Value::Object(Default::default()));
            }
            Token::Index(k) => {
                let here = format!("{at}[{k}]");
                let Value::Array(items) = node else {
                    let allowed = format!("a key without an index: {at} is not a list");
                    return Err(Error::invalid(here, shown(value), allowed));
                };
                let len = items.len();
                let Some(item) = items.get_mut(*k) else {
                    let allowed = match len {
                        0 => format!("no index: {at} is empty"),
                        n => format!("an index 0..{} of {at}", n - 1),
                    };
                    return Err(Error::invalid(here, shown(value), allowed));
                };
                at = here;
                if last {
                    *item = value.clone();
                    return Ok(());
                }
                node = item;
            }
        }
    }
    Ok(())
}

/// Sets `overrides` in order in the JSON configuration `config` ([`set_path`]); one number for
/// `well.inclination_deg` without a `well.md` override drops the survey depths (the
/// constant-inclination rule of [`DrillConfig::from_json`]); a `bit.radius` override replaces a
/// `bit.diameter` and the reverse. `field` names a malformed path.
pub fn apply_overrides(config: &mut Value, overrides: &[Override], field: &str) -> Result<()> {
    for (path, v) in overrides {
        set_path(config, path, v, field)?;
    }
    bit_size_override(config, overrides);
    if overrides.iter().any(|(p, _)| p == "well.inclination_deg") {
        let md_given = overrides.iter().any(|(p, _)| p == "well.md");
        if let Some(Value::Object(well)) = config.get_mut("well") {
            constant_inclination(well, md_given);
        }
    }
    Ok(())
}

/// Overrides from JSON `[[path, value], ...]` (`items`, the parsed list); errors name `field`.
pub(crate) fn override_pairs(items: Vec<Value>, field: &str, form: &str) -> Result<Vec<Override>> {
    items
        .into_iter()
        .map(|pair| match pair {
            Value::Array(mut kv) if kv.len() == 2 && kv[0].is_string() => {
                let v = kv.pop().unwrap_or(Value::Null);
                let k = kv.pop().and_then(|k| k.as_str().map(str::to_string)).unwrap_or_default();
                Ok((k, v))
            }
            other => Err(Error::invalid(field, shown(&other), form)),
        })
        .collect()
}

/// The JSON configuration `config_json` with `overrides_json` (a JSON list of
/// `[dotted path, value]` pairs) set ([`apply_overrides`]), not parsed: errors name a path that
/// does not go through the configuration's tables and lists; `field` names a malformed path or
/// list.
pub fn override_value(config_json: &str, overrides_json: &str, field: &str) -> Result<Value> {
    let mut config: Value = serde_json::from_str(config_json)
        .map_err(|e| Error::invalid("config", format!("text that is not JSON ({e})"), "a JSON object"))?;
    let form = "a list of [dotted path, value] pairs";
    let items: Value = serde_json::from_str(overrides_json)
        .map_err(|e| Error::invalid(field, format!("text that is not JSON ({e})"), form))?;
    let Value::Array(items) = items else { return Err(Error::invalid(field, shown(&items), form)) };
    apply_overrides(&mut config, &override_pairs(items, field, form)?, field)?;
    Ok(config)
}

/// [`override_value`] parsed and, when `validate`, validated: the configuration (every default
/// filled in). Errors name the dotted field.
pub fn override_json(config_json: &str, overrides_json: &str, field: &str, validate: bool) -> Result<DrillConfig> {
    let cfg = DrillConfig::from_value(override_value(config_json, overrides_json, field)?)?;
    if validate {
        cfg.validate()?;
    }
    Ok(cfg)
}

/// Samples `k interval` for `k = 0, 1, ...` up to `duration` (with a relative tolerance).
fn samples(duration: f64, interval: f64) -> usize {
    let n = (duration / interval * (1.0 + 1e-12)).floor();
    if n.is_finite() && n < usize::MAX as f64 / 2.0 {
        n as usize + 1
    } else {
        usize::MAX
    }
}

/// Validation helpers: an error naming `field` unless `x` is in range.
pub(super) fn pos(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number > 0 ({unit})")))
    }
}
pub(super) fn nonneg(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number >= 0 ({unit})")))
    }
}
pub(super) fn within(field: impl Into<String>, x: f64, lo: f64, hi: f64, unit: &str) -> Result<()> {
    if x.is_finite() && (lo..=hi).contains(&x) {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a number in [{}, {}] ({unit})", Num(lo), Num(hi))))
    }
}
pub(super) fn finite(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number ({unit})")))
    }
}
