//! Controller tuning from the string: the rules of the controller presets
//! (`top_drive.controller.preset`) and the recommendation `drillstring tune` prints.
//!
//! The numbers a rule takes ([`StringNumbers`]): the characteristic impedance of the top
//! section `Z = J sqrt(G rho)` (N m s), the string's first natural frequency `f1` (top fixed, bit
//! free or with the BHA inertia; [`first_natural_frequency`]), the top-drive inertia `I_TD`
//! (kg m^2) and the string's static torsional stiffness `k = 1 / sum L / (G J)` (N m/rad).
//!
//! The rules (each one function below):
//!
//! * `stiff` ([`stiff_gains`]): a high-gain speed PI, `kp = 50 Z`, `ki = 5 1/s^2 I_TD`: the
//!   "stiff PI" factors of Simulator4nDOF (NORCE, Open-Source-Drilling-Community/Simulator4nDOF,
//!   `Simulator/TopdriveController.cs`, `KpStiffAndZTorque = 50`, `KiStiffAndZTorque = 5`,
//!   `kp = KpFactor Z`, `ki = KiFactor I_TD`). Its speed loop on the top-drive inertia has the
//!   bandwidth `kp / (2 pi I_TD)` ([`speed_loop_bandwidth_hz`]), several times `f1`, and the top
//!   reflects a torque wave with the coefficient `(kp - Z) / (kp + Z) = 49 / 51`
//!   ([`reflection`]): it holds the speed and sends the waves back down, which is what lets
//!   stick-slip grow (Kyllingstad & Halsey, SPE Drilling Engineering 3(4), 1988).
//! * `soft_torque` ([`soft_torque_gains`]): SoftTorque / SoftSpeed, Kyllingstad & Halsey 1988 and
//!   Kyllingstad & Nessjøen, SPE/IADC 119660, 2009: the PI's integral spring cancels the
//!   top-drive inertia at the stick-slip frequency, `ki = (2 pi f)^2 I_TD` with `f = f1`, so that
//!   there the top drive is the pure damper `kp`; `kp = z_factor Z` with `z_factor = 4`, the
//!   published default of Simulator4nDOF (`KpSoftTorqueSpeed = 4`), which keeps the speed
//!   tracking while absorbing `1 - 3/5` of each wave's amplitude (`z_factor = 1` absorbs it all
//!   but lets the speed wander: on `examples/on-bottom-3000m.toml` it made stick-slip worse).
//! * `z_torque` ([`z_torque_highpass_time`]): ZTorque impedance matching (Dwars, SPE/IADC 173037,
//!   2015): the top speed is lowered by the high-passed string torque over `z_factor Z`,
//!   `z_factor = 4` (Simulator4nDOF's `AdditionalTuningFactorZTorque = 0.25` on `1 / Z`), and the
//!   high-pass corner an octave below the first mode, `T = 2 / (2 pi f1) = 1 / (pi f1)`: the
//!   first mode passes with 89 % of its amplitude and a phase lead of 27 degrees, while the
//!   string's wind-up before break-off (a torque ramp `k Omega`) lowers the top speed only to
//!   `setpoint / (1 + T k / (z_factor Z))` ([`windup_speed_ratio`]) instead of the fixed
//!   `20 / (2 pi)` s time constant's.

use std::f64::consts::PI;

use serde::Serialize;

use super::config::{Controller, ControllerKind, ControllerPreset, DrillConfig};
use super::grid::{first_natural_frequency, SectionProps};

/// `stiff`: `kp = STIFF_KP_PER_IMPEDANCE Z` (Simulator4nDOF's `KpStiffAndZTorque`).
pub const STIFF_KP_PER_IMPEDANCE: f64 = 50.0;
/// `stiff`: `ki = STIFF_KI_PER_INERTIA I_TD`, 1/s^2 (Simulator4nDOF's `KiStiffAndZTorque`).
pub const STIFF_KI_PER_INERTIA: f64 = 5.0;
/// `z_torque`: the high-pass corner is the first mode's frequency over this factor (an octave).
pub const Z_TORQUE_CORNER_RATIO: f64 = 2.0;

/// What the tuning rules take from a configuration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StringNumbers {
    /// Characteristic impedance of the top section `J sqrt(G rho)`, N m s.
    pub impedance: f64,
    /// First natural frequency of the string (top fixed, bit free or with the BHA inertia), Hz.
    pub first_mode_hz: f64,
    /// Top-drive inertia, kg m^2.
    pub top_drive_inertia: f64,
    /// Static torsional stiffness of the whole string `1 / sum L / (G J)`, N m/rad.
    pub stiffness: f64,
}

/// The numbers of `cfg`'s string and top drive (sections as given; not validated).
pub fn string_numbers(cfg: &DrillConfig) -> StringNumbers {
    let props: Vec<SectionProps> = cfg.sections.iter().map(|s| SectionProps::new(s, cfg.well.mud_density)).collect();
    let compliance: f64 = props.iter().map(|p| p.length / p.stiffness).sum();
    StringNumbers {
        impedance: props.first().map_or(f64::NAN, |p| p.impedance),
        first_mode_hz: first_natural_frequency(&props, cfg.bit.bha_inertia) / (2.0 * PI),
        top_drive_inertia: cfg.top_drive.inertia,
        stiffness: 1.0 / compliance,
    }
}

/// `stiff`: `(kp, ki) = (50 Z, 5 I_TD)`, N m s/rad and N m/rad.
pub fn stiff_gains(impedance: f64, inertia: f64) -> (f64, f64) {
    (STIFF_KP_PER_IMPEDANCE * impedance, STIFF_KI_PER_INERTIA * inertia)
}

/// `soft_torque`: `(kp, ki) = (z_factor Z, w^2 I_TD)`, N m s/rad and N m/rad, for the tuning
/// angular frequency `w = 2 pi f` (rad/s).
pub fn soft_torque_gains(z_factor: f64, impedance: f64, w: f64, inertia: f64) -> (f64, f64) {
    (z_factor * impedance, w * w * inertia)
}

/// `z_torque`: the torque high-pass time constant `1 / (2 pi f1 / 2) = 1 / (pi f1)`, s.
pub fn z_torque_highpass_time(first_mode_hz: f64) -> f64 {
    Z_TORQUE_CORNER_RATIO / (2.0 * PI * first_mode_hz)
}

/// The bandwidth of a proportional speed loop on the top-drive inertia, `kp / (2 pi I_TD)`, Hz.
pub fn speed_loop_bandwidth_hz(kp: f64, inertia: f64) -> f64 {
    kp / (2.0 * PI * inertia)
}

/// The reflection coefficient of a torque wave at a top that acts as the damper `damping`
/// (N m s) on a pipe of impedance `impedance`: `(c - Z) / (c + Z)` (1: a fixed top, 0: matched).
pub fn reflection(damping: f64, impedance: f64) -> f64 {
    (damping - impedance) / (damping + impedance)
}

/// `z_torque`: the fraction of the setpoint the top drive turns at while the string winds up
/// before break-off, `1 / (1 + T k / (z_factor Z))` (the high-pass passes the torque ramp
/// `k Omega` as `T k Omega`).
pub fn windup_speed_ratio(highpass_time: f64, stiffness: f64, z_factor: f64, impedance: f64) -> f64 {
    1.0 / (1.0 + highpass_time * stiffness / (z_factor * impedance))
}

/// The controller of `preset` for a string of `numbers`: `base` with the type and the keys the
/// preset sets (`stiff`: `kp`, `ki`; `soft_torque`: `kp`, `ki` from `base`'s `z_factor` (the
/// default 4 is the rule's) and `tuning_frequency` (None: `f1`); `z_torque`:
/// `torque_highpass_time`, with `base`'s `z_factor`).
pub fn preset_controller(preset: ControllerPreset, numbers: &StringNumbers, base: &Controller) -> Controller {
    let z = numbers.impedance;
    let inertia = numbers.top_drive_inertia;
    let mut c = base.clone();
    c.preset = Some(preset);
    match preset {
        ControllerPreset::Stiff => {
            c.kind = ControllerKind::Pi;
            (c.kp, c.ki) = stiff_gains(z, inertia);
        }
        ControllerPreset::SoftTorque => {
            c.kind = ControllerKind::SoftTorque;
            let f = c.tuning_frequency.unwrap_or(numbers.first_mode_hz);
            (c.kp, c.ki) = soft_torque_gains(c.z_factor, z, 2.0 * PI * f, inertia);
        }
        ControllerPreset::ZTorque => {
            c.kind = ControllerKind::ZTorque;
            c.torque_highpass_time = z_torque_highpass_time(numbers.first_mode_hz);
        }
    }
    c
}

/// The configuration keys of `top_drive.controller` a preset sets (the others keep their value).
pub const PRESET_KEYS: [&str; 6] = ["type", "kp", "ki", "tuning_frequency", "z_factor", "torque_highpass_time"];

/// Whether `preset`'s rule needs the BHA's inertia: `soft_torque` and `z_torque` tune to the
/// string's first mode `f1`, the stick-slip mode of the BHA swinging on the string's
/// compliance. Without a BHA inertia (`bit.bha_inertia = 0`) there is no such mass at the bit:
/// `f1` is the bare pipe's quarter-wave mode, which is not the stick-slip cycle, and the tuned
/// controller need not damp anything (measured: `z_torque` on `examples/s-well-3d.toml` at 40 rpm
/// without its BHA inertia chattered with a 0.18 s period between the +-60 kN m torque limits,
/// at the limit 12 % of the window, `tests/test_verdicts.py`). `stiff` takes no frequency
/// (`kp = 50 Z`, `ki = 5 I_TD`) and suits any string.
pub fn needs_bha_inertia(preset: ControllerPreset) -> bool {
    matches!(preset, ControllerPreset::SoftTorque | ControllerPreset::ZTorque)
}

/// Refuses a preset that [`needs_bha_inertia`] on a string without one (`bit.bha_inertia = 0`),
/// naming both keys and what to do instead.
pub fn check_preset(cfg: &DrillConfig) -> crate::error::Result<()> {
    match cfg.top_drive.controller.preset {
        Some(p) if needs_bha_inertia(p) && cfg.bit.bha_inertia <= 0.0 => Err(crate::error::Error::invalid(
            "top_drive.controller.preset",
            format!("{:?} with bit.bha_inertia = 0", p.name()),
            format!(
                "bit.bha_inertia > 0 kg m^2 for the preset {:?}: it tunes to the first mode of the BHA on the \
                 string, and this string has no BHA inertia; give the BHA's inertia, or the preset \"stiff\", or \
                 top_drive.controller.type = {:?} with its gains and no preset",
                p.name(),
                p.name()
            ),
        )),
        _ => Ok(()),
    }
}

/// Sets in `cfg`'s controller the values of its preset (if any) for the keys not in `given`
/// (the keys the configuration gave beside the preset), computed from `cfg`'s string when the
/// configuration is read; refused ([`check_preset`]) for a preset the string cannot be tuned by.
pub fn apply_preset(cfg: &mut DrillConfig, given: &[String]) -> crate::error::Result<()> {
    let Some(preset) = cfg.top_drive.controller.preset else {
        return Ok(());
    };
    check_preset(cfg)?;
    let given_values = cfg.top_drive.controller.clone();
    let mut c = preset_controller(preset, &string_numbers(cfg), &given_values);
    for key in given {
        match key.as_str() {
            "type" => c.kind = given_values.kind,
            "kp" => c.kp = given_values.kp,
            "ki" => c.ki = given_values.ki,
            "tuning_frequency" => c.tuning_frequency = given_values.tuning_frequency,
            "z_factor" => c.z_factor = given_values.z_factor,
            "torque_highpass_time" => c.torque_highpass_time = given_values.torque_highpass_time,
            _ => {}
        }
    }
    cfg.top_drive.controller = c;
    Ok(())
}

/// One preset's recommended settings and what they give.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PresetRecommendation {
    pub preset: &'static str,
    /// The controller the preset sets (type and gains).
    pub controller: Controller,
    /// The damping the top drive presents to torque waves, N m s (`kp`, or `z_factor Z`; for
    /// `stiff` the PI's `kp`).
    pub damping: f64,
    /// [`reflection`] of a torque wave at the top at that damping.
    pub reflection: f64,
    /// `stiff`, `soft_torque`: [`speed_loop_bandwidth_hz`] of `kp`, Hz; NaN for `z_torque`.
    pub speed_bandwidth_hz: f64,
    /// `z_torque`: [`windup_speed_ratio`]; NaN otherwise.
    pub windup_speed_ratio: f64,
    /// The rule with its numbers, one line.
    pub rule: String,
}

/// The recommended settings of every preset for `cfg`'s string.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recommendations {
    pub string: StringNumbers,
    #[serde(serialize_with = "crate::solution::serialize_list")]
    pub presets: Vec<PresetRecommendation>,
}

/// `x` with four significant digits (no exponent), as the rules are printed.
fn sig4(x: f64) -> String {
    let decimals = if x == 0.0 || !x.is_finite() { 0 } else { (3 - x.abs().log10().floor() as i32).max(0) as usize };
    format!("{x:.decimals$}")
}

/// [`Recommendations`] of a configuration (validated first).
pub fn recommend(cfg: &DrillConfig) -> crate::error::Result<Recommendations> {
    cfg.validate()?;
    let n = string_numbers(cfg);
    let (z, i, f1) = (n.impedance, n.top_drive_inertia, n.first_mode_hz);
    let presets = ControllerPreset::ALL
        .iter()
        .map(|&p| {
            let c = preset_controller(p, &n, &Controller::default());
            let nan = f64::NAN;
            let (damping, bandwidth, windup, rule) = match p {
                ControllerPreset::Stiff => (
                    c.kp,
                    speed_loop_bandwidth_hz(c.kp, i),
                    nan,
                    format!(
                        "kp = {STIFF_KP_PER_IMPEDANCE} Z = {} N m s/rad, ki = {STIFF_KI_PER_INERTIA} 1/s^2 x I_TD = {} \
                         N m/rad (Simulator4nDOF stiff PI)",
                        sig4(c.kp),
                        sig4(c.ki)
                    ),
                ),
                ControllerPreset::SoftTorque => (
                    c.kp,
                    speed_loop_bandwidth_hz(c.kp, i),
                    nan,
                    format!(
                        "kp = z_factor Z = {} Z = {} N m s/rad, ki = (2 pi f1)^2 I_TD = {} N m/rad at f1 = {} Hz \
                         (Kyllingstad & Nessjoen 2009)",
                        c.z_factor,
                        sig4(c.kp),
                        sig4(c.ki),
                        sig4(f1)
                    ),
                ),
                ControllerPreset::ZTorque => (
                    c.z_factor * z,
                    nan,
                    windup_speed_ratio(c.torque_highpass_time, n.stiffness, c.z_factor, z),
                    format!(
                        "z_factor = {} (damping {} N m s), torque_highpass_time = 1 / (pi f1) = {} s at f1 = {} Hz \
                         (Dwars 2015)",
                        c.z_factor,
                        sig4(c.z_factor * z),
                        sig4(c.torque_highpass_time),
                        sig4(f1)
                    ),
                ),
            };
            PresetRecommendation {
                preset: p.name(),
                reflection: reflection(damping, z),
                controller: c,
                damping,
                speed_bandwidth_hz: bandwidth,
                windup_speed_ratio: windup,
                rule,
            }
        })
        .collect();
    Ok(Recommendations { string: n, presets })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_bottom() -> DrillConfig {
        DrillConfig::from_json(
            r#"{"sections": [
                {"length": 3000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086,
                 "shear_modulus": 79.3e9, "density": 7850.0},
                {"length": 200.0, "outer_diameter": 0.1651, "inner_diameter": 0.0714,
                 "shear_modulus": 79.3e9, "density": 7850.0}],
                "top_drive": {"inertia": 2900.0}}"#,
        )
        .unwrap()
    }

    /// The rules against the closed forms, computed here from the pipe's dimensions.
    #[test]
    fn rules_match_hand_computed_closed_forms() {
        let cfg = on_bottom();
        let n = string_numbers(&cfg);
        // Z = pi/32 (OD^4 - ID^4) sqrt(G rho) of the 5-in pipe
        let j = PI / 32.0 * (0.127f64.powi(4) - 0.1086f64.powi(4));
        let z = j * (79.3e9f64 * 7850.0).sqrt();
        assert!((n.impedance / z - 1.0).abs() < 1e-14, "{} {z}", n.impedance);
        assert!((z - 296.5).abs() < 0.1, "{z}");
        // k = 1 / (L1 / (G J1) + L2 / (G J2))
        let j2 = PI / 32.0 * (0.1651f64.powi(4) - 0.0714f64.powi(4));
        let k = 1.0 / (3000.0 / (79.3e9 * j) + 200.0 / (79.3e9 * j2));
        assert!((n.stiffness / k - 1.0).abs() < 1e-14);
        let (kp, ki) = stiff_gains(z, 2900.0);
        assert_eq!((kp, ki), (50.0 * z, 14_500.0));
        let (kp, ki) = soft_torque_gains(4.0, z, 2.0 * PI * 0.2, 2900.0);
        assert!((kp - 4.0 * z).abs() < 1e-12 && (ki - 0.4 * 0.4 * PI * PI * 2900.0).abs() < 1e-9);
        // 1 / (pi f1): 0.2 Hz -> 1.5915494309189535 s
        assert!((z_torque_highpass_time(0.2) - 1.5915494309189535).abs() < 1e-15);
        assert!((speed_loop_bandwidth_hz(2.0 * PI * 2900.0, 2900.0) - 1.0).abs() < 1e-15);
        assert_eq!(reflection(3.0, 1.0), 0.5);
        assert_eq!(reflection(1.0, 1.0), 0.0);
        // T k / (z Z) = 2 * 300 / (4 * 300) = 0.5 -> 2/3
        assert!((windup_speed_ratio(2.0, 300.0, 4.0, 300.0) - 2.0 / 3.0).abs() < 1e-15);
    }

    /// A uniform free-ended string: f1 = c / (4 L), so the z_torque time constant is
    /// `4 L / (pi c)` and its wind-up ratio `1 / (1 + 4 / (pi z_factor))` whatever the pipe.
    #[test]
    fn a_uniform_string_gets_the_quarter_wave_numbers() {
        let cfg = DrillConfig::from_json(
            r#"{"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086,
                 "shear_modulus": 80e9, "density": 8000.0}],
                "top_drive": {}}"#,
        )
        .unwrap();
        let c = (80e9f64 / 8000.0).sqrt();
        let n = string_numbers(&cfg);
        assert!((n.first_mode_hz - c / 8000.0).abs() < 1e-9 * n.first_mode_hz, "{n:?}");
        // the rule's numbers (the preset itself is refused on a string without BHA inertia)
        let z = preset_controller(ControllerPreset::ZTorque, &n, &Controller::default());
        let t = z.torque_highpass_time;
        assert!((t - 8000.0 / (PI * c)).abs() < 1e-8 * t, "{t}");
        assert_eq!(z.kind, ControllerKind::ZTorque);
        let r = windup_speed_ratio(t, n.stiffness, 4.0, n.impedance);
        assert!((r - 1.0 / (1.0 + 4.0 / (PI * 4.0))).abs() < 1e-8, "{r}");
    }

    #[test]
    fn rules_print_four_significant_digits() {
        assert_eq!(sig4(14825.04), "14825");
        assert_eq!(sig4(296.5008), "296.5");
        assert_eq!(sig4(1.98932), "1.989");
        assert_eq!(sig4(0.16), "0.1600");
    }

    #[test]
    fn a_preset_fills_in_what_is_not_given() {
        let cfg = DrillConfig::from_json(
            r#"{"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                "top_drive": {"inertia": 1000.0, "controller": {"preset": "stiff", "ki": 7.0}}}"#,
        )
        .unwrap();
        let c = &cfg.top_drive.controller;
        let z = string_numbers(&cfg).impedance;
        assert_eq!((c.kind, c.kp, c.ki, c.preset), (ControllerKind::Pi, 50.0 * z, 7.0, Some(ControllerPreset::Stiff)));
        // the normalised configuration parses to the same (every key now given)
        let again = DrillConfig::from_json(&cfg.to_json()).unwrap();
        assert_eq!(&again, &cfg);
        let soft = DrillConfig::from_json(
            r#"{"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                "bit": {"bha_inertia": 100.0},
                "top_drive": {"controller": {"preset": "soft_torque", "z_factor": 2.0}}}"#,
        )
        .unwrap();
        assert_eq!(soft.top_drive.controller.kind, ControllerKind::SoftTorque);
        assert_eq!(soft.top_drive.controller.z_factor, 2.0);
    }

    /// `soft_torque` and `z_torque` tune to the BHA's mode: refused without a BHA inertia (with
    /// both keys named), `stiff` accepted; a type without a preset is the user's choice.
    #[test]
    fn presets_that_tune_to_the_bha_mode_are_refused_without_bha_inertia() {
        let string = r#""sections": [{"length": 3000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}]"#;
        for preset in ["soft_torque", "z_torque"] {
            let json = format!(r#"{{{string}, "top_drive": {{"controller": {{"preset": "{preset}"}}}}}}"#);
            let err = DrillConfig::from_json(&json).unwrap_err().to_string();
            assert!(err.contains("top_drive.controller.preset") && err.contains("bit.bha_inertia"), "{err}");
            let with_bha = format!(
                r#"{{{string}, "bit": {{"bha_inertia": 50.0}}, "top_drive": {{"controller": {{"preset": "{preset}"}}}}}}"#
            );
            assert!(DrillConfig::from_json(&with_bha).is_ok(), "{preset}");
        }
        let stiff = format!(r#"{{{string}, "top_drive": {{"controller": {{"preset": "stiff"}}}}}}"#);
        assert!(DrillConfig::from_json(&stiff).is_ok());
        let typed = format!(r#"{{{string}, "top_drive": {{"controller": {{"type": "z_torque"}}}}}}"#);
        assert!(DrillConfig::from_json(&typed).is_ok());
        assert!(!needs_bha_inertia(ControllerPreset::Stiff));
    }
}
