//! Whether a configuration key changes a drilling run under the configuration's modes: the
//! rule a stick-slip map ([`super::map::check_axes`]) refuses an axis by, whose rows would all
//! be the same.
//!
//! A key has no effect when the part it belongs to is not used: the top drive's controller,
//! setpoint and torque limit under `top_drive.mode = "measured_speed"`; a controller's gain
//! under another controller type; the hoist's keys of another `hoist.mode` (or without a
//! `[hoist]` table); the velocity-weakening bit's keys in a coupled run (the hoist sets the
//! weight on bit and the Detournay law the torque) or with the bit off bottom; the Detournay
//! law's keys with the velocity-weakening law; the wear flats' weakening (`bit.weakening`) under
//! any law but `detournay_weakening`; the regularisation speed of set-valued
//! friction; the torque-and-drag analysis's keys (but the element length of the soft-string
//! contact).
//!
//! ```
//! use drillstring_core::drilling::{effect::no_effect, DrillConfig};
//! let mut cfg = DrillConfig::default();
//! assert_eq!(no_effect(&cfg, "top_drive.rpm"), None);
//! cfg.top_drive.mode = drillstring_core::drilling::config::TopMode::MeasuredSpeed;
//! assert!(no_effect(&cfg, "top_drive.rpm").unwrap().contains("measured_speed"));
//! ```

use super::config::AutodrillerTarget;
use super::config::{
    BitRockLaw, Contact, ControllerKind, CutSurfaceScheme, DrillConfig, FrictionModel, HoistMode, TopMode,
};

/// The key without its indices: `top_drive.steps[0][1]` -> `top_drive.steps`.
fn bare(key: &str) -> String {
    let mut out = String::with_capacity(key.len());
    let mut depth = 0usize;
    for c in key.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// Why the dotted key `key` (`top_drive.rpm`, `hoist.steps[0][1]`) changes nothing in a run of
/// `cfg`, or `None` when it may (every key not listed in the module's rules).
pub fn no_effect(cfg: &DrillConfig, key: &str) -> Option<String> {
    let key = bare(key.trim());
    let k = key.as_str();
    let under = |prefix: &str| k == prefix || k.starts_with(&format!("{prefix}."));
    let one_of = |keys: &[&str]| keys.contains(&k);
    let td = &cfg.top_drive;
    if td.mode == TopMode::MeasuredSpeed
        && (under("top_drive.controller")
            || one_of(&[
                "top_drive.rpm",
                "top_drive.ramp_time",
                "top_drive.steps",
                "top_drive.torque_limit",
                "top_drive.control_interval",
                "top_drive.motor_bandwidth",
            ]))
    {
        return Some(format!(
            "top_drive.mode = \"measured_speed\" imposes the top speed top_drive.speed_series: the controller, its \
             setpoint and the torque limit are not used, so {k} changes nothing"
        ));
    }
    if td.mode == TopMode::Controller {
        let kind = td.controller.kind;
        let name = ControllerKind::NAMES[kind as usize];
        let users: Option<&str> = match k {
            "top_drive.controller.kp" | "top_drive.controller.ki" if kind != ControllerKind::Pi => {
                Some("pi (soft_torque computes its gains from z_factor and tuning_frequency)")
            }
            "top_drive.controller.tuning_frequency" if kind != ControllerKind::SoftTorque => Some("soft_torque"),
            "top_drive.controller.z_factor"
                if !matches!(kind, ControllerKind::SoftTorque | ControllerKind::ZTorque) =>
            {
                Some("soft_torque and z_torque")
            }
            "top_drive.controller.torque_highpass_time" if kind != ControllerKind::ZTorque => Some("z_torque"),
            "top_drive.control_interval" if !matches!(kind, ControllerKind::Pi | ControllerKind::SoftTorque) => {
                Some("pi and soft_torque")
            }
            _ => None,
        };
        if let Some(users) = users {
            return Some(format!(
                "{k} is used by the controller type {users} only, and top_drive.controller.type = \"{name}\""
            ));
        }
    }
    match &cfg.hoist {
        None if under("hoist") => {
            return Some(format!("no [hoist] table: the run is torsion only, so {k} changes nothing"));
        }
        None => {}
        Some(h) => {
            let mode = match h.mode {
                HoistMode::Velocity => "velocity",
                HoistMode::HookLoad => "hook_load",
                HoistMode::WeightOnBit => "weight_on_bit",
                HoistMode::Autodriller => "autodriller",
            };
            let owner = match k {
                "hoist.speed" => Some(HoistMode::Velocity),
                "hoist.hook_load" => Some(HoistMode::HookLoad),
                "hoist.weight_on_bit" => Some(HoistMode::WeightOnBit),
                _ if under("hoist.autodriller") => Some(HoistMode::Autodriller),
                _ => None,
            };
            if owner.is_some_and(|o| o != h.mode) {
                return Some(format!("{k} is not used with hoist.mode = \"{mode}\""));
            }
            if one_of(&["bit.weight_on_bit", "bit.mu_static", "bit.mu_kinetic", "bit.decay"]) {
                let by = match h.mode {
                    HoistMode::Velocity => "the block velocity hoist.speed",
                    HoistMode::HookLoad => "the hook load hoist.hook_load",
                    HoistMode::WeightOnBit => "hoist.weight_on_bit",
                    HoistMode::Autodriller if h.autodriller.target == AutodrillerTarget::WeightOnBit => {
                        "the autodriller's setpoint"
                    }
                    HoistMode::Autodriller => "the autodriller",
                };
                return Some(format!(
                    "a coupled run (a [hoist] table, hoist.mode = \"{mode}\") sets the weight on bit by {by} and the \
                     bit's torque by the Detournay law (bit.detournay): {k} belongs to the velocity-weakening law \
                     and changes nothing"
                ));
            }
        }
    }
    let law = cfg.bit.law;
    if under("bit.weakening") && law != BitRockLaw::DetournayWeakening {
        return Some(format!(
            "{k} is used by bit.law = \"detournay_weakening\" only (bit.law = \"{}\" here), so it changes nothing",
            law.name()
        ));
    }
    if law == BitRockLaw::VelocityWeakening {
        if under("bit.detournay") || k == "bit.bha_mass" {
            return Some(format!(
                "bit.law = \"velocity_weakening\" (torsion only): {k} belongs to the coupled run's Detournay bit and \
                 axial field and changes nothing"
            ));
        }
        if !cfg.bit.on_bottom && one_of(&["bit.weight_on_bit", "bit.mu_static", "bit.mu_kinetic", "bit.decay"]) {
            return Some(format!(
                "bit.on_bottom = false: the bit hangs free and its torque law is not used, so {k} changes nothing"
            ));
        }
    } else {
        let upwind = law == BitRockLaw::Rgd && cfg.bit.detournay.cut_surface == CutSurfaceScheme::Upwind;
        if k == "bit.detournay.cut_surface_cells" && !upwind {
            return Some(
                "bit.detournay.cut_surface_cells is used by bit.law = \"rgd\" with bit.detournay.cut_surface = \
                 \"upwind\" only"
                    .into(),
            );
        }
        if k == "bit.detournay.cut_surface" && law != BitRockLaw::Rgd {
            return Some("bit.detournay.cut_surface is used by bit.law = \"rgd\" only".into());
        }
    }
    if k == "friction.regularisation_speed" && cfg.friction.model != FrictionModel::Regularised {
        return Some(
            "friction.regularisation_speed is used by friction.model = \"regularised\" only (set_valued here)".into(),
        );
    }
    if under("torque_drag") && !(k == "torque_drag.step" && cfg.friction.contact == Contact::SoftString) {
        return Some(format!(
            "{k} belongs to the torque-and-drag analysis (drillstring torque-drag), not to a run{}",
            if k == "torque_drag.step" { " with friction.contact = \"weight\"" } else { "" }
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::config::Hoist;

    #[test]
    fn keys_of_unused_parts_have_no_effect() {
        let mut cfg = DrillConfig::default();
        for k in ["top_drive.rpm", "top_drive.controller.kp", "sections[0].length", "friction.static"] {
            assert_eq!(no_effect(&cfg, k), None, "{k}");
        }
        assert!(no_effect(&cfg, "hoist.speed").unwrap().contains("torsion only"));
        assert!(no_effect(&cfg, "bit.weight_on_bit").unwrap().contains("bit.on_bottom = false"));
        assert!(no_effect(&cfg, "bit.detournay.blades").unwrap().contains("velocity_weakening"));
        assert!(no_effect(&cfg, "torque_drag.friction_factors[0]").is_some());
        assert!(no_effect(&cfg, "top_drive.controller.z_factor").unwrap().contains("\"pi\""));
        cfg.bit.on_bottom = true;
        assert_eq!(no_effect(&cfg, "bit.weight_on_bit"), None);
        cfg.top_drive.mode = TopMode::MeasuredSpeed;
        let why = no_effect(&cfg, "top_drive.rpm").unwrap();
        assert!(why.contains("measured_speed") && why.contains("top_drive.rpm"), "{why}");
        assert!(no_effect(&cfg, "top_drive.steps[1][1]").is_some());
        assert_eq!(no_effect(&cfg, "top_drive.inertia"), None);
        cfg.top_drive.mode = TopMode::Controller;
        cfg.bit.on_bottom = false;
        cfg.bit.law = BitRockLaw::Rgd;
        cfg.hoist = Some(Hoist { mode: HoistMode::WeightOnBit, ..Hoist::default() });
        assert!(no_effect(&cfg, "bit.weight_on_bit").unwrap().contains("hoist.weight_on_bit"));
        assert!(no_effect(&cfg, "hoist.speed").unwrap().contains("weight_on_bit"));
        assert_eq!(no_effect(&cfg, "hoist.weight_on_bit"), None);
        assert_eq!(no_effect(&cfg, "bit.detournay.blades"), None);
        assert!(no_effect(&cfg, "bit.detournay.cut_surface_cells").is_some());
    }

    #[test]
    fn the_wear_flat_weakening_acts_under_its_law_only() {
        let mut cfg = DrillConfig::default();
        for law in [BitRockLaw::VelocityWeakening, BitRockLaw::Detournay, BitRockLaw::Rgd] {
            cfg.bit.law = law;
            for k in ["bit.weakening", "bit.weakening.static_friction", "bit.weakening.decay"] {
                let why = no_effect(&cfg, k).unwrap_or_else(|| panic!("{k} under {}", law.name()));
                assert!(why.contains("detournay_weakening") && why.contains(&law.name()), "{why}");
            }
        }
        cfg.bit.law = BitRockLaw::DetournayWeakening;
        cfg.hoist = Some(Hoist::default());
        for k in ["bit.weakening.static_friction", "bit.weakening.decay", "bit.detournay.friction"] {
            assert_eq!(no_effect(&cfg, k), None, "{k}");
        }
        // (a key beside the table is not under it)
        assert!(no_effect(&cfg, "bit.weakeningx").is_none());
    }
}
