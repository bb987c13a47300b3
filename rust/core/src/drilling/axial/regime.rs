//! The regime of a coupled axial-torsional run over its metrics window: smooth drilling,
//! stick-slip, bit bounce, both, or off bottom ([`regime`], the one place of the criterion).

use serde::Serialize;

use crate::metrics::stickslip::Verdict;

/// The coupled regime of a window ([`regime`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Regime {
    /// The bit cuts throughout the window and never stops turning.
    #[serde(rename = "smooth drilling")]
    SmoothDrilling,
    /// The bit stops turning during part of the window, always in contact with the rock.
    #[serde(rename = "stick-slip")]
    StickSlip,
    /// The bit leaves the rock during part of the window and never stops turning.
    #[serde(rename = "bit bounce")]
    BitBounce,
    /// Both in one window.
    #[serde(rename = "stick-slip and bit bounce")]
    StickSlipAndBitBounce,
    /// The bit never touches the rock in the window.
    #[serde(rename = "off bottom")]
    OffBottom,
    /// No window, or a torsional verdict that is `undetermined` without bit bounce.
    #[serde(rename = "undetermined")]
    Undetermined,
}

impl Regime {
    /// The regime's name as metrics.json, a map's table and the report write it.
    pub fn name(self) -> &'static str {
        match self {
            Regime::SmoothDrilling => "smooth drilling",
            Regime::StickSlip => "stick-slip",
            Regime::BitBounce => "bit bounce",
            Regime::StickSlipAndBitBounce => "stick-slip and bit bounce",
            Regime::OffBottom => "off bottom",
            Regime::Undetermined => "undetermined",
        }
    }

    /// Every regime, in the order a map's legend lists them.
    pub const ALL: [Regime; 6] = [
        Regime::SmoothDrilling,
        Regime::StickSlip,
        Regime::BitBounce,
        Regime::StickSlipAndBitBounce,
        Regime::OffBottom,
        Regime::Undetermined,
    ];
}

/// The criterion of [`regime`], as a report states it.
pub const REGIME_CRITERION: &str = "off bottom: no weight on bit throughout the metrics window \
     (bounce_fraction = 1); bit bounce: no weight on bit during part of it (0 < bounce_fraction < 1); \
     stick-slip: the torsional verdict is yes (the bit stops turning during part of the window); both: \
     stick-slip and bit bounce; smooth drilling: the bit stays on the rock (bounce_fraction = 0) and the \
     torsional verdict is no and the window is past the axial transient; undetermined: no window, the torsional \
     verdict undetermined without bit bounce, or a window that would be smooth drilling but whose ROP or weight \
     on bit is still changing between its halves (the string still compressing: the transient criterion of the \
     motor torque, on the axial series)";

/// The regime of a coupled run's window from its torsional stick-slip verdict
/// (`metrics::stickslip::verdict`; `None` without metrics) and its bounce fraction (the share of
/// the window's samples with no weight on bit, NaN without samples), the criterion
/// [`REGIME_CRITERION`].
///
/// The thresholds are the exact zeros of the two fractions, the rule of the torsional verdict
/// (`0 < stuck_fraction < 1`), because both events are exact in the solution: the bit's
/// lift-off phase (bit bounce, the set-valued contact of `bit_boundary`) sets the weight on bit
/// to exactly 0 N, which no contact with the rock gives while the string pushes on it, and the
/// stick phase holds the bit speed below `metrics.stick_speed`; a threshold above 0 would hide
/// short events that are real in the model. A window with no weight on bit in every sample is
/// `off bottom` (the bit never reaches the rock: a
/// hoist speed too small or a string still hanging), whatever the rotation does; one sample
/// off the rock makes a bounce. The verdict `undetermined` (the bit stuck throughout, an
/// oscillation still growing, SSI >= 1 without a stop) does not make a smooth run: with bit
/// bounce the regime is `bit bounce`, else `undetermined`. The rule does not look at the rate
/// of penetration: a bit resting on the rock with a weight below its wear flats' contact force
/// `a l sigma` (it hardly cuts: `hoist.weight_on_bit = 0` drills at ~0.1 m/h) is `smooth
/// drilling` as long as it keeps contact and turns.
///
/// `axial_transient`: the window's ROP or weight on bit still changes between its halves
/// (`plausibility::axial_transient`, the criterion of the torsional transient warning): the
/// string is still compressing (the converged van de Wouw example at 120 rpm and 10 m/h drills
/// at 8.08 m/h over 180-240 s against the hoist's 10). Such a window is no steady regime, and
/// what would be `smooth drilling` is `undetermined`; a stop of the bit or a bounce in it is
/// real whatever follows, and keeps its name.
pub fn regime(verdict: Option<Verdict>, bounce_fraction: f64, axial_transient: bool) -> Regime {
    let Some(verdict) = verdict else { return Regime::Undetermined };
    if !bounce_fraction.is_finite() {
        return Regime::Undetermined;
    }
    let bounce = bounce_fraction > 0.0;
    if bounce_fraction >= 1.0 {
        Regime::OffBottom
    } else {
        match (verdict, bounce) {
            (Verdict::Yes, true) => Regime::StickSlipAndBitBounce,
            (Verdict::Yes, false) => Regime::StickSlip,
            (_, true) => Regime::BitBounce,
            (Verdict::No, false) if axial_transient => Regime::Undetermined,
            (Verdict::No, false) => Regime::SmoothDrilling,
            (Verdict::Undetermined, false) => Regime::Undetermined,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_regime_follows_its_criterion() {
        use Verdict::*;
        let cases = [
            (Some(No), 0.0, "smooth drilling"),
            (Some(Yes), 0.0, "stick-slip"),
            (Some(No), 0.2, "bit bounce"),
            (Some(Undetermined), 0.2, "bit bounce"),
            (Some(Yes), 1e-4, "stick-slip and bit bounce"),
            (Some(Yes), 1.0, "off bottom"),
            (Some(No), 1.0, "off bottom"),
            (Some(Undetermined), 0.0, "undetermined"),
            (None, 0.0, "undetermined"),
            (Some(No), f64::NAN, "undetermined"),
        ];
        for (verdict, bounce, name) in cases {
            let r = regime(verdict, bounce, false);
            assert_eq!(r.name(), name, "{verdict:?} {bounce}");
            assert_eq!(serde_json::to_value(r).unwrap(), name);
        }
        // a window still in the axial transient: smooth drilling is undetermined, the others stay
        assert_eq!(regime(Some(No), 0.0, true), Regime::Undetermined);
        assert_eq!(regime(Some(Yes), 0.0, true), Regime::StickSlip);
        assert_eq!(regime(Some(No), 0.2, true), Regime::BitBounce);
        assert_eq!(Regime::ALL.len(), 6);
    }
}
