//! Well plans of the common shapes, written as survey stations: hold (straight on, vertical
//! from the surface), build or drop at a rate to a target inclination (an arc in the vertical
//! plane of the current azimuth: one minimum-curvature interval, exact), and turn at a rate to
//! a target azimuth at constant inclination (stations every [`TURN_STATION_INTERVAL`] m, as a
//! survey would sample it).
//!
//! ```
//! use drillstring_core::well::plan::{stations, Segment};
//! // a J well: vertical to 500 m, build at 3 deg/30 m to 60 deg, hold 2000 m
//! let (md, inc, _azi) = stations(&[
//!     Segment::Hold { length: 500.0 },
//!     Segment::Build { rate: 3.0, inclination: 60.0 },
//!     Segment::Hold { length: 2000.0 },
//! ], 0.0).unwrap();
//! assert_eq!(md, vec![0.0, 500.0, 1100.0, 3100.0]);
//! assert_eq!(inc, vec![0.0, 0.0, 60.0, 60.0]);
//! ```

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

/// The station spacing of planned turns, m (a survey's usual 30 m).
pub const TURN_STATION_INTERVAL: f64 = 30.0;

/// Rates are in degrees per 30 m (the field's unit of dogleg severity).
pub const RATE_LENGTH: f64 = 30.0;

/// The most stations of a plan (3000 km of turns sampled every 30 m): a turn at a rate so slow
/// that it would need more is refused before its stations are allocated.
pub const MAX_PLAN_STATIONS: usize = 100_000;

/// The largest inclination change of one planned station interval, degrees: a longer build or
/// drop is written as several stations on its arc (exact: the arc is planar), so that no
/// interval's dogleg comes near 180 degrees, where minimum curvature is undefined.
pub const MAX_BUILD_INTERVAL_DEG: f64 = 90.0;

/// One segment of a plan. In a configuration: a table with one of the keys `hold` (m),
/// `build` / `drop` (deg/30 m, with `inclination`: the target, deg) or `turn` (deg/30 m,
/// positive clockwise, with `azimuth`: the target, deg).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Segment {
    Hold { length: f64 },
    Build { rate: f64, inclination: f64 },
    Turn { rate: f64, azimuth: f64 },
}

/// A segment as written in a configuration (`{hold = 500}`, `{build = 3, inclination = 60}`,
/// `{drop = 2, inclination = 0}`, `{turn = -2, azimuth = 270}`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// A straight hold of this length, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "m", "label" = "hold length"))]
    pub hold: Option<f64>,
    /// Build at this rate, > 0, to the target `inclination`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "deg/(30 m)", "label" = "build rate"))]
    pub build: Option<f64>,
    /// Drop at this rate, > 0, to the target `inclination`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "deg/(30 m)", "label" = "drop rate"))]
    pub drop: Option<f64>,
    /// Turn at this rate, nonzero, positive clockwise, to the target `azimuth`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "deg/(30 m)", "label" = "turn rate"))]
    pub turn: Option<f64>,
    /// The target inclination of a build or drop, from 0 to below 180 degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "deg", "label" = "target inclination"))]
    pub inclination: Option<f64>,
    /// The target azimuth of a turn, 0 to 360 degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("unit" = "deg", "label" = "target azimuth"))]
    pub azimuth: Option<f64>,
}

impl SegmentSpec {
    /// The segment this table describes; `field` names it in messages (`well.plan[2]`).
    pub fn segment(&self, field: &str) -> Result<Segment> {
        let kinds = [self.hold, self.build, self.drop, self.turn].iter().filter(|x| x.is_some()).count();
        if kinds != 1 {
            return Err(Error::invalid(
                field,
                format!("{kinds} of hold, build, drop, turn"),
                "exactly one of hold (m), build or drop (deg/30 m, with inclination), turn (deg/30 m, with azimuth)",
            ));
        }
        let positive = |name: &str, x: f64, unit: &str| {
            if x.is_finite() && x > 0.0 {
                Ok(x)
            } else {
                Err(Error::invalid(format!("{field}.{name}"), Num(x), format!("a finite number > 0 {unit}")))
            }
        };
        let needs = |name: &str, x: Option<f64>, other: &str| {
            x.ok_or_else(|| {
                Error::invalid(format!("{field}.{name}"), "missing", format!("the target of the {other}, deg"))
            })
        };
        let refuse = |name: &str, x: Option<f64>| match x {
            Some(v) => Err(Error::invalid(
                format!("{field}.{name}"),
                Num(v),
                "no value here (only build and drop take inclination, turn takes azimuth)",
            )),
            None => Ok(()),
        };
        if let Some(length) = self.hold {
            refuse("inclination", self.inclination)?;
            refuse("azimuth", self.azimuth)?;
            return Ok(Segment::Hold { length: positive("hold", length, "m")? });
        }
        if let Some(rate) = self.turn {
            refuse("inclination", self.inclination)?;
            if !(rate.is_finite() && rate != 0.0) {
                return Err(Error::invalid(
                    format!("{field}.turn"),
                    Num(rate),
                    "a finite rate != 0 deg/30 m (positive clockwise)",
                ));
            }
            return Ok(Segment::Turn { rate, azimuth: needs("azimuth", self.azimuth, "turn")? });
        }
        refuse("azimuth", self.azimuth)?;
        let (name, rate) =
            if let Some(r) = self.build { ("build", r) } else { ("drop", self.drop.unwrap_or(f64::NAN)) };
        let rate = positive(name, rate, "deg/30 m")?;
        let inclination = needs("inclination", self.inclination, name)?;
        Ok(Segment::Build { rate: if name == "drop" { -rate } else { rate }, inclination })
    }
}

/// The stations (md m, inclination deg, azimuth deg) of a plan starting vertical at the surface
/// (with the azimuth `azimuth` deg for the first build). A build must raise the inclination and
/// a drop lower it; targets within `[0, 180)` and `[0, 360)` degrees; at most
/// [`MAX_PLAN_STATIONS`] stations.
pub fn stations(segments: &[Segment], azimuth: f64) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let (mut md, mut inc, mut azi) = (vec![0.0], vec![0.0], vec![azimuth]);
    for (j, seg) in segments.iter().enumerate() {
        let field = format!("well.plan[{j}]");
        let (d0, i0, a0) = (*md.last().unwrap(), *inc.last().unwrap(), *azi.last().unwrap());
        match *seg {
            Segment::Hold { length } => {
                md.push(d0 + length);
                inc.push(i0);
                azi.push(a0);
            }
            Segment::Build { rate, inclination } => {
                if !(0.0..180.0).contains(&inclination) {
                    return Err(Error::invalid(
                        format!("{field}.inclination"),
                        Num(inclination),
                        "0 <= inclination < 180 deg",
                    ));
                }
                let change = inclination - i0;
                if change == 0.0 || change.signum() != rate.signum() {
                    let (kind, want) = if rate > 0.0 { ("build", ">") } else { ("drop", "<") };
                    return Err(Error::invalid(
                        format!("{field}.inclination"),
                        Num(inclination),
                        format!("a target {want} the inclination reached, {} deg, for a {kind}", Num(i0)),
                    ));
                }
                let n = (change.abs() / MAX_BUILD_INTERVAL_DEG).ceil().max(1.0) as usize;
                for k in 1..=n {
                    let f = k as f64 / n as f64;
                    md.push(d0 + f * change / rate * RATE_LENGTH);
                    inc.push(if k == n { inclination } else { i0 + f * change });
                    azi.push(a0);
                }
            }
            Segment::Turn { rate, azimuth } => {
                if !(0.0..360.0).contains(&azimuth) {
                    return Err(Error::invalid(format!("{field}.azimuth"), Num(azimuth), "0 <= azimuth < 360 deg"));
                }
                if i0 == 0.0 {
                    return Err(Error::invalid(field, "a turn of a vertical well", "a build before the turn"));
                }
                // the way the rate's sign turns: clockwise (positive) or anticlockwise
                let change =
                    if rate > 0.0 { (azimuth - a0).rem_euclid(360.0) } else { -(a0 - azimuth).rem_euclid(360.0) };
                let length = change / rate * RATE_LENGTH;
                let n = (length / TURN_STATION_INTERVAL).ceil().max(1.0);
                let room = MAX_PLAN_STATIONS.saturating_sub(md.len());
                if n.is_nan() || n > room as f64 {
                    // the slowest rate whose stations fit
                    let slowest = change.abs() * RATE_LENGTH / (room.max(1) as f64 * TURN_STATION_INTERVAL);
                    return Err(Error::invalid(
                        format!("{field}.turn"),
                        Num(rate),
                        format!(
                            "a rate of at least {} deg/30 m in magnitude for this {} deg turn (a plan of at most \
                             {MAX_PLAN_STATIONS} stations, one every {TURN_STATION_INTERVAL} m of a turn)",
                            Num(slowest),
                            Num(change.abs())
                        ),
                    ));
                }
                let n = n as usize;
                for k in 1..=n {
                    let f = k as f64 / n as f64;
                    md.push(d0 + f * length);
                    inc.push(i0);
                    azi.push(if k == n { azimuth } else { (a0 + f * change).rem_euclid(360.0) });
                }
            }
        }
    }
    // a plan of zero-length pieces (a turn of 0 degrees) leaves repeated depths: drop them
    let mut keep = vec![true; md.len()];
    for j in 1..md.len() {
        keep[j] = md[j] > md[j - 1];
    }
    let pick = |v: Vec<f64>| v.into_iter().zip(&keep).filter(|(_, k)| **k).map(|(x, _)| x).collect::<Vec<_>>();
    Ok((pick(md), pick(inc), pick(azi)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::well::{Survey, Trajectory};

    #[test]
    fn an_s_well_in_four_segments() {
        let segs = [
            Segment::Hold { length: 500.0 },
            Segment::Build { rate: 2.0, inclination: 30.0 },
            Segment::Hold { length: 1000.0 },
            Segment::Build { rate: -1.5, inclination: 0.0 },
        ];
        let (md, inc, azi) = stations(&segs, 45.0).unwrap();
        assert_eq!(md, vec![0.0, 500.0, 950.0, 1950.0, 2550.0]);
        assert_eq!(inc, vec![0.0, 0.0, 30.0, 30.0, 0.0]);
        let t = Trajectory::new(Survey::from_degrees("well", &md, &inc, &azi).unwrap());
        let dls = t.dls_deg_per_30m();
        assert!((dls[2] - 2.0).abs() < 1e-12 && (dls[4] - 1.5).abs() < 1e-12, "{dls:?}");
        // back to vertical: north and east offsets equal (azimuth 45)
        let p = t.position[4];
        assert!((p[0] - p[1]).abs() < 1e-9 && p[0] > 100.0);
    }

    #[test]
    fn a_turn_is_sampled_and_ends_on_target() {
        let segs = [
            Segment::Hold { length: 100.0 },
            Segment::Build { rate: 3.0, inclination: 90.0 },
            Segment::Turn { rate: -3.0, azimuth: 270.0 },
        ];
        let (md, _inc, azi) = stations(&segs, 0.0).unwrap();
        assert_eq!(*azi.last().unwrap(), 270.0);
        // 90 degrees anticlockwise at 3 deg/30 m: 900 m, in 30 m stations
        assert!((md.last().unwrap() - (100.0 + 900.0 + 900.0)).abs() < 1e-9);
        assert_eq!(md.len(), 3 + 30);
    }

    #[test]
    fn specs_name_the_field() {
        let e = SegmentSpec { build: Some(3.0), ..Default::default() }.segment("well.plan[1]").unwrap_err();
        assert_eq!(e.field(), "well.plan[1].inclination");
        let e = SegmentSpec { hold: Some(3.0), build: Some(1.0), ..Default::default() }
            .segment("well.plan[0]")
            .unwrap_err();
        assert_eq!(e.field(), "well.plan[0]");
        let e = stations(&[Segment::Build { rate: 3.0, inclination: 0.0 }], 0.0).unwrap_err();
        assert_eq!(e.field(), "well.plan[0].inclination");
        let s = SegmentSpec { drop: Some(2.0), inclination: Some(10.0), ..Default::default() }.segment("p").unwrap();
        assert_eq!(s, Segment::Build { rate: -2.0, inclination: 10.0 });
    }
}
