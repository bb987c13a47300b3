//! The well of a drilling configuration: its survey (stations in `well.md`,
//! `well.inclination_deg`, `well.azimuth_deg`; a survey file `well.survey`; or a plan
//! `well.plan`), the minimum-curvature trajectory of [`crate::well`], and the static torque and
//! drag of the configuration's string in it ([`crate::well::torque_drag`]), which also gives
//! the wall's soft-string normal force of the dynamic model (`friction.contact`).

use std::sync::Arc;

use serde::Serialize;

use crate::error::{Error, Num, Result};
use crate::well::plan;
use crate::well::torque_drag::{
    self, Operation, Piece, Profile, ProfileMethod, Setup, SlidingFriction, SlidingInterval, TorqueDrag,
};
use crate::well::{Survey, Trajectory};

use super::config::{DrillConfig, Inclination};
use super::grid::SectionProps;

/// Column names a survey file may use for each quantity (lower case, before a unit).
const MD_NAMES: [&str; 3] = ["md", "measured_depth", "depth"];
const INC_NAMES: [&str; 3] = ["inc", "inclination", "incl"];
const AZI_NAMES: [&str; 3] = ["azi", "azimuth", "az"];

/// A column's name and unit: `md_m`, `md [ft]`, `inc (deg)`, `AZI_RAD`, or a bare name.
fn column(header: &str) -> (String, String) {
    let h = header.trim().to_lowercase();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let (Some(a), Some(b)) = (h.find(open), h.rfind(close)) {
            if a < b {
                return (h[..a].trim().trim_end_matches('_').to_string(), h[a + 1..b].trim().to_string());
            }
        }
    }
    match h.rsplit_once('_') {
        Some((name, unit)) if ["m", "ft", "deg", "rad"].contains(&unit) => (name.to_string(), unit.to_string()),
        _ => (h, String::new()),
    }
}

/// Reads a survey file: a CSV with a header naming columns md, inc and azi (also
/// `measured_depth`, `inclination`, `azimuth`; other columns are ignored), each with an
/// optional unit (`md_ft`, `md [m]`, `inc_rad`, `azi (deg)`; default m and degrees). Returns
/// the stations in m and degrees; an error names the file, the row (1 = the header) and the
/// column.
pub fn read_survey_csv(path: &str) -> Result<[Vec<f64>; 3]> {
    let field = format!("well.survey ({path})");
    let text = std::fs::read(path)
        .map_err(|e| Error::invalid(&field, format!("a file that cannot be read ({e})"), "a readable CSV file"))?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(text.as_slice());
    let headers = reader
        .headers()
        .map_err(|e| Error::invalid(&field, format!("no CSV header ({e})"), "a header row naming md, inc and azi"))?
        .clone();
    let mut index = [usize::MAX; 3];
    let mut scale = [1.0; 3];
    let mut names = [String::new(), String::new(), String::new()];
    for (j, h) in headers.iter().enumerate() {
        let (name, unit) = column(h);
        for (k, list) in [&MD_NAMES[..], &INC_NAMES[..], &AZI_NAMES[..]].iter().enumerate() {
            if list.contains(&name.as_str()) && index[k] == usize::MAX {
                let factor = match (k, unit.as_str()) {
                    (0, "" | "m") => 1.0,
                    (0, "ft") => 0.3048,
                    (1 | 2, "" | "deg") => 1.0,
                    (1 | 2, "rad") => 180.0 / std::f64::consts::PI,
                    _ => {
                        return Err(Error::invalid(
                            format!("{field}, row 1, column {}", j + 1),
                            format!("the unit {unit:?} of {h:?}"),
                            if k == 0 { "m or ft" } else { "deg or rad" },
                        ))
                    }
                };
                (index[k], scale[k], names[k]) = (j, factor, h.to_string());
            }
        }
    }
    for (k, what) in ["md", "inc", "azi"].iter().enumerate() {
        if index[k] == usize::MAX {
            return Err(Error::invalid(
                format!("{field}, row 1"),
                format!("the columns {:?}", headers.iter().collect::<Vec<_>>()),
                format!("a column named {what} (with an optional unit: {what}_m, {what} [deg], ...)"),
            ));
        }
    }
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    for (r, record) in reader.records().enumerate() {
        let row = r + 2;
        let record = record.map_err(|e| Error::invalid(format!("{field}, row {row}"), e.to_string(), "a CSV row"))?;
        for k in 0..3 {
            let cell = record.get(index[k]).unwrap_or("");
            let value: f64 = cell.parse().map_err(|_| {
                Error::invalid(format!("{field}, row {row}, column {}", names[k]), format!("{cell:?}"), "a number")
            })?;
            if !value.is_finite() {
                return Err(Error::invalid(
                    format!("{field}, row {row}, column {}", names[k]),
                    Num(value),
                    "a finite number",
                ));
            }
            out[k].push(value * scale[k]);
        }
    }
    if out[0].is_empty() {
        return Err(Error::invalid(&field, "no stations", "at least one row of md, inc, azi"));
    }
    // a station's row in messages: validate with the file's row numbers
    let md = &out[0];
    for j in 0..md.len() {
        let row = j + 2;
        let bad = |col: &str, v: f64, allowed: &str| {
            Error::invalid(format!("{field}, row {row}, column {col}"), Num(v), allowed.to_string())
        };
        if j == 0 && md[0] != 0.0 {
            return Err(bad(&names[0], md[0], "0 (the first station is at the surface; add a row at md 0)"));
        }
        if j > 0 && md[j] <= md[j - 1] {
            return Err(bad(&names[0], md[j], &format!("a depth > the row above's {}", Num(md[j - 1]))));
        }
        if !(0.0..180.0).contains(&out[1][j]) {
            return Err(bad(&names[1], out[1][j], "0 <= inclination < 180 degrees"));
        }
        if !(0.0..=360.0).contains(&out[2][j]) {
            return Err(bad(&names[2], out[2][j], "0 <= azimuth <= 360 degrees"));
        }
    }
    Ok(out)
}

/// Reads `well.survey` into `well.survey_stations` (once, at parsing).
pub fn load_survey(cfg: &mut DrillConfig) -> Result<()> {
    if let Some(path) = &cfg.well.survey {
        cfg.well.survey_stations = Some(Arc::new(read_survey_csv(path)?));
    }
    Ok(())
}

fn table(field: &str, x: &Inclination, n: usize) -> Result<Vec<f64>> {
    match x {
        Inclination::Constant(v) => Ok(vec![*v; n]),
        Inclination::Table(v) if v.len() == n => Ok(v.clone()),
        Inclination::Table(v) => {
            Err(Error::invalid(field, format!("{} values", v.len()), format!("{n} values (one per well.md station)")))
        }
    }
}

/// The survey of a configuration: from `well.survey`'s stations, `well.plan`, or the stations
/// `well.md` (a table whose first station is below the surface is continued up to md 0 at its
/// first direction), or a straight hole at a constant inclination.
pub fn survey(cfg: &DrillConfig) -> Result<Survey> {
    let w = &cfg.well;
    let constant_azimuth = match w.azimuth_deg {
        Inclination::Constant(a) => Some(a),
        Inclination::Table(_) => None,
    };
    if let Some(stations) = &w.survey_stations {
        let [md, inc, azi] = stations.as_ref();
        return Survey::from_degrees("well.survey", md, inc, azi);
    }
    if let Some(path) = &w.survey {
        let [md, inc, azi] = read_survey_csv(path)?;
        return Survey::from_degrees("well.survey", &md, &inc, &azi);
    }
    if let Some(specs) = &w.plan {
        if specs.is_empty() {
            return Err(Error::invalid(
                "well.plan",
                "an empty plan",
                "at least one segment ({hold = m}, {build = deg/30 m, inclination = deg}, ...), or no well.plan",
            ));
        }
        let Some(azimuth) = constant_azimuth else {
            return Err(Error::invalid(
                "well.azimuth_deg",
                "a table",
                "one number (the plan's initial azimuth) with well.plan",
            ));
        };
        let segments =
            specs.iter().enumerate().map(|(j, s)| s.segment(&format!("well.plan[{j}]"))).collect::<Result<Vec<_>>>()?;
        let (md, inc, azi) = plan::stations(&segments, azimuth)?;
        return Survey::from_degrees("well.plan", &md, &inc, &azi);
    }
    match (&w.md, &w.inclination_deg) {
        (None, Inclination::Constant(i)) => {
            let a = constant_azimuth.unwrap_or(0.0);
            Survey::from_degrees("well", &[0.0], &[*i], &[a])
        }
        (Some(md), inc) => {
            let inc = table("well.inclination_deg", inc, md.len())?;
            let azi = table("well.azimuth_deg", &w.azimuth_deg, md.len())?;
            let (mut m, mut i, mut a) = (md.clone(), inc, azi);
            if m.first().is_some_and(|&d| d > 0.0) {
                m.insert(0, 0.0);
                i.insert(0, i[0]);
                a.insert(0, a[0]);
            }
            Survey::from_degrees("well", &m, &i, &a)
        }
        (None, Inclination::Table(_)) => {
            Err(Error::invalid("well.md", "null", "the measured depths of the inclination table"))
        }
    }
}

/// The minimum-curvature trajectory of a configuration's survey; refused when the survey ends
/// above the bit (the string's length) unless `well.extend` is true or the hole is a straight
/// one of constant inclination, or when the hole reverses within an interval or rises above
/// the rig floor ([`super::limits::check_hole`]).
pub fn trajectory(cfg: &DrillConfig) -> Result<Trajectory> {
    let s = survey(cfg)?;
    let length: f64 = cfg.sections.iter().map(|s| s.length).sum();
    let straight = s.len() == 1;
    if !straight && !cfg.well.extend && s.depth() < length * (1.0 - 1e-12) {
        let source = if cfg.well.survey.is_some() {
            "well.survey"
        } else if cfg.well.plan.is_some() {
            "well.plan"
        } else {
            "well.md"
        };
        return Err(Error::invalid(
            source,
            format!("a survey to {} m", Num(s.depth())),
            format!(
                "a survey reaching the bit at {} m (the sections' length), or well.extend = true to continue the last \
                 station straight on",
                Num(length)
            ),
        ));
    }
    let traj = Trajectory::new(s);
    super::limits::check_hole(cfg, &traj, length)?;
    Ok(traj)
}

/// The static friction factor at `md`: the first `friction.intervals` entry holding it, else
/// `friction.static`.
pub fn friction_factor(cfg: &DrillConfig, md: f64) -> f64 {
    friction(cfg, 1.0).at(md)
}

/// The friction factors of a configuration times `ratio` (1: the static ones;
/// `friction.kinetic_ratio`: the sliding ones).
/// `friction.intervals` come first, then the hole sections' factors.
fn friction(cfg: &DrillConfig, ratio: f64) -> SlidingFriction {
    let mut intervals: Vec<SlidingInterval> = cfg
        .friction
        .intervals
        .iter()
        .map(|iv| SlidingInterval { top_md: iv.top_md, bottom_md: iv.bottom_md, mu: ratio * iv.static_coefficient })
        .collect();
    intervals.extend(super::pipe::hole_friction(cfg, ratio));
    SlidingFriction { mu: ratio * cfg.friction.static_coefficient, intervals }
}

/// The torque-and-drag setup of a configuration: its sections (buoyed weight, contact radius),
/// friction factors, weight on bit, torque on bit, block weight and step.
///
/// The friction factors are the sliding ones, `friction.static` (or an interval's) times
/// `friction.kinetic_ratio`: every operation of torque and drag is a steady slide (pick-up,
/// slack-off, rotating), as the dynamic model's steady states are (its wall friction slides on
/// the kinetic factor; the static one holds only a contact that sticks). With the default ratio
/// 1 the two are one factor. The static factors give the break-off torque ([`contact_profile`]).
pub fn setup(cfg: &DrillConfig) -> Setup {
    setup_with(cfg, cfg.friction.kinetic_ratio)
}

fn setup_with(cfg: &DrillConfig, ratio: f64) -> Setup {
    let g = cfg.well.gravity;
    Setup {
        pieces: cfg
            .sections
            .iter()
            .map(|s| {
                let p = SectionProps::new(s, cfg.well.mud_density);
                Piece {
                    length: s.length,
                    weight: super::pipe::buoyed_weight(s, cfg.well.mud_density, g),
                    contact_radius: p.contact_radius,
                    body: super::pipe::body(s),
                }
            })
            .collect(),
        friction: friction(cfg, ratio),
        weight_on_bit: cfg.bit.weight_on_bit,
        bit_torque: cfg.torque_drag.bit_torque,
        block_weight: cfg.torque_drag.block_weight,
        step: cfg.torque_drag.step,
        hole: super::pipe::hole(cfg),
        pressure_gradient: cfg.well.mud_density * g,
    }
}

/// The five operations' torque and drag of a configuration (stepped, Johancsik).
pub fn torque_drag(cfg: &DrillConfig) -> Result<TorqueDrag> {
    let traj = trajectory(cfg)?;
    let s = setup(cfg);
    s.validate_string()?;
    Ok(torque_drag::analyse_unchecked(&traj, &s, ProfileMethod::Stepwise))
}

/// The hook loads of the broomstick plot: bit depths `depth_m`, and for each friction factor
/// of `torque_drag.friction_factors` a row of pick-up, slack-off and rotating hook loads over
/// the depths, N.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Broomstick {
    #[serde(rename = "depth_m")]
    pub depths: Vec<f64>,
    pub friction_factors: Vec<f64>,
    pub pickup: Vec<Vec<f64>>,
    pub slackoff: Vec<Vec<f64>>,
    pub rotating: Vec<Vec<f64>>,
    /// The rotating off-bottom surface torque, N m, like the hook loads.
    #[serde(rename = "torque_rotating")]
    pub torque: Vec<Vec<f64>>,
}

/// The torque and drag of a configuration with its broomstick (what `torque-drag` reports).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TorqueDragReport {
    #[serde(flatten)]
    pub summary: TorqueDrag,
    pub broomstick: Broomstick,
}

/// The survey stations and their minimum-curvature positions, as table columns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrajectoryTable {
    pub md: Vec<f64>,
    pub inc_deg: Vec<f64>,
    pub azi_deg: Vec<f64>,
    pub north: Vec<f64>,
    pub east: Vec<f64>,
    pub tvd: Vec<f64>,
    /// Of the interval ending at each station (0 at the first).
    pub dls_deg_per_30m: Vec<f64>,
}

impl TrajectoryTable {
    pub fn new(traj: &Trajectory) -> TrajectoryTable {
        let column = |k: usize| traj.position.iter().map(|p| p[k]).collect::<Vec<f64>>();
        TrajectoryTable {
            md: traj.survey.md.clone(),
            inc_deg: traj.survey.inc_deg.clone(),
            azi_deg: traj.survey.azi_deg.clone(),
            north: column(0),
            east: column(1),
            tvd: column(2),
            dls_deg_per_30m: traj.dls_deg_per_30m(),
        }
    }
}

/// [`torque_drag`] and [`broomstick`] of a configuration.
pub fn report(cfg: &DrillConfig) -> Result<TorqueDragReport> {
    Ok(TorqueDragReport { summary: torque_drag(cfg)?, broomstick: broomstick(cfg)? })
}

pub fn broomstick(cfg: &DrillConfig) -> Result<Broomstick> {
    let traj = trajectory(cfg)?;
    let s = setup(cfg);
    super::limits::validate_torque_drag(cfg)?;
    let n = cfg.torque_drag.broomstick_points;
    let length = s.depth();
    // (the last depth the string's length itself: `length * n / n` can round above it)
    let depths: Vec<f64> = (1..=n).map(|k| if k == n { length } else { length * k as f64 / n as f64 }).collect();
    let mus = cfg.torque_drag.friction_factors.clone();
    let rows = torque_drag::broomstick(&traj, &s, &depths, &mus)?;
    let column = |k: usize| rows.iter().map(|row| row.iter().map(|r| r[k]).collect()).collect();
    Ok(Broomstick {
        depths,
        friction_factors: mus,
        pickup: column(0),
        slackoff: column(1),
        rotating: column(2),
        torque: column(3),
    })
}

/// The friction factor in `[0, 1]`, uniform along the hole, that reproduces a measured load
/// with the bit at `depth` (m, within the string's length) in `op`: the hook load (N, with the
/// block weight) or, rotating, the surface torque (N m) when given. Err: why none does (the
/// load at 0 and at 1 on the same side of the measured one), with the model's two loads.
pub fn implied_friction(
    cfg: &DrillConfig,
    traj: &Trajectory,
    depth: f64,
    op: Operation,
    hook_load: Option<f64>,
    torque: Option<f64>,
) -> std::result::Result<f64, String> {
    let s = setup(cfg);
    if !(depth.is_finite() && depth > 0.0 && depth <= s.depth()) {
        return Err(format!("bit depth {} m outside (0, {}] m, the string's length", Num(depth), Num(s.depth())));
    }
    let rotating = matches!(op, Operation::RotatingOffBottom | Operation::RotatingOnBottom);
    let (measured, is_torque) = match (hook_load, torque) {
        (_, Some(m)) if rotating => (m, true),
        (Some(h), _) if !rotating => (h, false),
        _ => return Err(format!("no {} for {}", if rotating { "surface torque" } else { "hook load" }, op.name())),
    };
    // the elements at the depth, shared by every factor of the bisection
    let el = s.elements(traj, depth);
    let load = |mu: f64| {
        let p = s.profile_on(traj, &el, op, ProfileMethod::Stepwise, Some(mu), s.bit_load(op));
        if is_torque {
            p.surface_torque()
        } else {
            p.surface_tension() + s.block_weight
        }
    };
    let (lo, hi) = (load(0.0), load(1.0));
    let unit = if is_torque { "N m" } else { "N" };
    let product = (lo - measured) * (hi - measured);
    if product.is_nan() || product > 0.0 {
        return Err(format!(
            "no friction factor in [0, 1] reproduces {} {unit} (the model gives {} at 0 and {} at 1)",
            Num(measured),
            Num(lo),
            Num(hi)
        ));
    }
    let (mut a, mut b, rising) = (0.0, 1.0, hi > lo);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if (load(m) < measured) == rising {
            a = m;
        } else {
            b = m;
        }
    }
    Ok(0.5 * (a + b))
}

/// The soft-string profile the dynamic model takes its wall contact from: rotating on bottom
/// (with `bit.weight_on_bit` and no torque on bit, whose value does not change the normal
/// force) when the bit is on bottom, else rotating off bottom.
pub fn contact_profile(cfg: &DrillConfig, traj: &Trajectory) -> Result<Profile> {
    // the static factors: its torque is the break-off torque
    let mut s = setup_with(cfg, 1.0);
    s.bit_torque = 0.0;
    s.validate_string()?;
    let op = if cfg.bit.on_bottom { Operation::RotatingOnBottom } else { Operation::RotatingOffBottom };
    Ok(s.solve(traj, op, ProfileMethod::Stepwise))
}

/// The normal force per length (N/m) of `profile` at `md`: that of the element holding it.
pub fn normal_force_at(profile: &Profile, md: f64) -> f64 {
    let k = profile.md.partition_point(|&x| x <= md);
    profile.normal_force[k.saturating_sub(1).min(profile.normal_force.len() - 1)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(name: &str, text: &str) -> String {
        let dir = std::env::temp_dir().join(format!("drillstring-survey-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_string_lossy().into_owned()
    }

    #[test]
    fn survey_files_with_units_and_errors_naming_row_and_column() {
        let p = write("a.csv", "MD [ft],Inc_deg,azi (rad),tvd\n0,0,0,0\n1000,10,0.5,999\n");
        let [md, inc, azi] = read_survey_csv(&p).unwrap();
        assert_eq!(md, vec![0.0, 304.8]);
        assert_eq!(inc, vec![0.0, 10.0]);
        assert!((azi[1] - 0.5f64.to_degrees()).abs() < 1e-12);
        let p = write("b.csv", "md_m,inc_deg,azi_deg\n0,0,0\n30,x,0\n");
        let e = read_survey_csv(&p).unwrap_err();
        assert!(e.field().ends_with("row 3, column inc_deg"), "{e}");
        let p = write("c.csv", "md_m,inc_deg,azi_deg\n0,0,0\n30,1,0\n20,2,0\n");
        assert!(read_survey_csv(&p).unwrap_err().field().ends_with("row 4, column md_m"));
        let p = write("d.csv", "md_m,inc_deg\n0,0\n");
        assert!(read_survey_csv(&p).unwrap_err().to_string().contains("a column named azi"));
        let p = write("e.csv", "md_m,inc_deg,azi_deg\n0,0,0\n30,190,0\n");
        assert!(read_survey_csv(&p).unwrap_err().field().ends_with("row 3, column inc_deg"));
        assert!(read_survey_csv("/nonexistent/survey.csv").unwrap_err().to_string().contains("cannot be read"));
    }

    #[test]
    fn a_short_survey_is_refused_unless_extended() {
        let mut cfg = DrillConfig::default();
        cfg.well.md = Some(vec![0.0, 1000.0]);
        cfg.well.inclination_deg = Inclination::Table(vec![0.0, 30.0]);
        let e = trajectory(&cfg).unwrap_err();
        assert_eq!(e.field(), "well.md");
        cfg.well.extend = true;
        let t = trajectory(&cfg).unwrap();
        assert!((t.at(2000.0).inc - 30f64.to_radians()).abs() < 1e-15);
    }

    /// The 2-D table form keeps its linear inclination bit for bit (the trajectory of a survey in
    /// one vertical plane turns at a constant rate between stations).
    #[test]
    fn table_inclination_is_the_linear_rule() {
        let cfg = DrillConfig::default();
        let t = trajectory(&cfg).unwrap();
        let (Some(d), Inclination::Table(inc)) = (&cfg.well.md, &cfg.well.inclination_deg) else {
            panic!("the default well is a table")
        };
        let linear = |md: f64| {
            let k = d.partition_point(|&x| x <= md);
            let deg = if k == 0 {
                inc[0]
            } else if k == d.len() {
                inc[d.len() - 1]
            } else {
                inc[k - 1] + (md - d[k - 1]) / (d[k] - d[k - 1]) * (inc[k] - inc[k - 1])
            };
            deg.to_radians()
        };
        for md in [0.0, 250.0, 500.0, 777.7, 1600.0, 2400.0] {
            assert_eq!(t.at(md).inc, linear(md));
        }
    }

    /// With the soft-string contact the cells' friction limits are `mu r N` of the torque-and-drag
    /// elements, and the break-off torque is the rotating surface torque: the cells' sum
    /// converges to it.
    #[test]
    fn soft_string_limits_sum_to_the_rotating_surface_torque() {
        let mut cfg = DrillConfig::default();
        cfg.well.mud_density = 1200.0;
        cfg.friction.intervals.push(super::super::config::FrictionInterval {
            top_md: 0.0,
            bottom_md: 1000.0,
            static_coefficient: 0.2,
        });
        let breakoff = super::super::grid::breakoff_torque(&cfg).unwrap();
        let td = torque_drag(&cfg).unwrap();
        // break-off at the static factors, torque and drag at the sliding ones
        let sliding = cfg.friction.kinetic_ratio * breakoff;
        assert!((td.surface_torque_off_bottom_nm - sliding).abs() < 1e-9 * breakoff);
        let mut errors = Vec::new();
        for cells in [500, 2000] {
            cfg.numerics.cells = cells;
            let g = super::super::grid::Grid::new(&cfg).unwrap();
            let sum: f64 = g.limit.iter().zip(&g.section_of).map(|(l, &s)| l * g.spacing[s]).sum();
            errors.push((sum / breakoff - 1.0).abs());
        }
        assert!(errors[1] < errors[0] && errors[1] < 2e-3, "{errors:?}");
        // the weight-only contact is larger in the build, where tension lifts the string
        cfg.friction.contact = super::super::config::Contact::Weight;
        assert!(super::super::grid::breakoff_torque(&cfg).unwrap() > breakoff);
    }

    #[test]
    fn survey_and_plan_configurations_round_trip() {
        let p = write("rt.csv", "md_m,inc_deg,azi_deg\n0,0,0\n500,0,0\n1500,40,30\n3000,40,60\n");
        let json = format!(
            r#"{{"sections": [{{"length": 2500, "outer_diameter": 0.127, "inner_diameter": 0.1}}], "well": {{"survey": {p:?}}}}}"#
        );
        let cfg = DrillConfig::from_json(&json).unwrap();
        cfg.validate().unwrap();
        let back = DrillConfig::from_json(&cfg.to_json()).unwrap();
        assert_eq!(back, cfg);
        assert_eq!(survey(&cfg).unwrap().md, vec![0.0, 500.0, 1500.0, 3000.0]);
        let json = r#"{"sections": [{"length": 2500, "outer_diameter": 0.127, "inner_diameter": 0.1}],
            "well": {"plan": [{"hold": 500}, {"build": 3, "inclination": 60}, {"hold": 2000}], "azimuth_deg": 45}}"#;
        let cfg = DrillConfig::from_json(json).unwrap();
        cfg.validate().unwrap();
        assert_eq!(DrillConfig::from_json(&cfg.to_json()).unwrap(), cfg);
        assert_eq!(survey(&cfg).unwrap().md, vec![0.0, 500.0, 1100.0, 3100.0]);
        let both = r#"{"sections": [{"length": 100, "outer_diameter": 0.127, "inner_diameter": 0.1}],
            "well": {"plan": [{"hold": 500}], "md": [0, 100], "inclination_deg": [0, 0]}}"#;
        assert_eq!(DrillConfig::from_json(both).unwrap_err().field(), "well.md");
        let bad = r#"{"sections": [{"length": 100, "outer_diameter": 0.127, "inner_diameter": 0.1}],
            "well": {"plan": [{"hold": 500, "turn": 3}]}}"#;
        assert_eq!(DrillConfig::from_json(bad).unwrap().validate().unwrap_err().field(), "well.plan[0]");
    }
}
