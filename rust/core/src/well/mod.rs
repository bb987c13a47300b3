//! The well's geometry: a survey of stations (measured depth, inclination, azimuth), its
//! minimum-curvature trajectory (positions, dogleg, curvature, the direction at any depth), and
//! plans of the common shapes (vertical, build, hold, drop, turn) written as stations.
//!
//! Coordinates: north, east and true vertical depth (down), metres; angles in radians inside,
//! degrees at the edges (configuration, CSV, tables). Inclination is measured from the
//! vertical (0 straight down, 90 horizontal, up to below 180), azimuth clockwise from north in
//! `[0, 360)` degrees.
//!
//! Minimum curvature (the industry's standard, e.g. SPE-84246 / ISCWSA): between two stations
//! the path is the circular arc tangent to both directions, of dogleg `beta` (the angle between
//! the directions), so the displacement is `dmd / 2 (t1 + t2) RF` with the ratio factor
//! `RF = tan(beta / 2) / (beta / 2)` (1 for a straight interval). The direction along the arc
//! is the spherical interpolation of `t1` and `t2`; the curvature is `beta / dmd`.

pub mod buckling;
pub mod plan;
pub mod td_limits;
pub mod torque_drag;

use crate::error::{Error, Num, Result};

/// A unit vector along the well at inclination `inc` and azimuth `azi` (radians):
/// (north, east, down).
pub fn direction(inc: f64, azi: f64) -> [f64; 3] {
    let (si, ci) = inc.sin_cos();
    let (sa, ca) = azi.sin_cos();
    [si * ca, si * sa, ci]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The angle between two unit vectors, accurate for small and large angles
/// (`2 atan2(|a - b|, |a + b|)`).
pub fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    2.0 * norm(d).atan2(norm(s))
}

/// A survey: stations of measured depth (m, strictly increasing from 0), inclination and
/// azimuth (radians).
#[derive(Debug, Clone, PartialEq)]
pub struct Survey {
    pub md: Vec<f64>,
    pub inc: Vec<f64>,
    pub azi: Vec<f64>,
    /// The inclinations as given, degrees.
    pub inc_deg: Vec<f64>,
    /// The azimuths as given (360 as 0), degrees.
    pub azi_deg: Vec<f64>,
}

impl Survey {
    /// A survey from stations in degrees, validated: the same number of values in each column,
    /// at least one station, the first at measured depth 0 (the surface), depths finite and
    /// strictly increasing, inclinations in `[0, 180)` and azimuths in `[0, 360]` degrees
    /// (360 read as 0). `field` names the input in messages (`well`, or a file).
    pub fn from_degrees(field: &str, md: &[f64], inc_deg: &[f64], azi_deg: &[f64]) -> Result<Survey> {
        if md.is_empty() {
            return Err(Error::invalid(
                format!("{field}.md"),
                "no stations",
                "at least one station (md 0 at the surface)",
            ));
        }
        for (name, n) in [("inclination_deg", inc_deg.len()), ("azimuth_deg", azi_deg.len())] {
            if n != md.len() {
                return Err(Error::invalid(
                    format!("{field}.{name}"),
                    format!("{n} values"),
                    format!("{} values (one per {field}.md station)", md.len()),
                ));
            }
        }
        for (j, &d) in md.iter().enumerate() {
            if !d.is_finite() {
                return Err(Error::invalid(format!("{field}.md[{j}]"), Num(d), "a finite depth in m"));
            }
            if j == 0 && d != 0.0 {
                return Err(Error::invalid(
                    format!("{field}.md[0]"),
                    Num(d),
                    "0 (the first station is at the surface; add a station at md 0)",
                ));
            }
            if j > 0 && d <= md[j - 1] {
                return Err(Error::invalid(
                    format!("{field}.md[{j}]"),
                    Num(d),
                    format!("strictly increasing depths (> {field}.md[{}] = {})", j - 1, Num(md[j - 1])),
                ));
            }
        }
        for (j, &x) in inc_deg.iter().enumerate() {
            if !(0.0..180.0).contains(&x) {
                return Err(Error::invalid(
                    format!("{field}.inclination_deg[{j}]"),
                    Num(x),
                    "0 <= inclination < 180 degrees (180 points straight up)",
                ));
            }
        }
        for (j, &x) in azi_deg.iter().enumerate() {
            if !(0.0..=360.0).contains(&x) {
                return Err(Error::invalid(format!("{field}.azimuth_deg[{j}]"), Num(x), "0 <= azimuth <= 360 degrees"));
            }
        }
        let azi_deg: Vec<f64> = azi_deg.iter().map(|x| x % 360.0).collect();
        Ok(Survey {
            md: md.to_vec(),
            inc: inc_deg.iter().map(|x| x.to_radians()).collect(),
            azi: azi_deg.iter().map(|x| x.to_radians()).collect(),
            inc_deg: inc_deg.to_vec(),
            azi_deg,
        })
    }

    pub fn len(&self) -> usize {
        self.md.len()
    }

    pub fn is_empty(&self) -> bool {
        self.md.is_empty()
    }

    /// The deepest station, m.
    pub fn depth(&self) -> f64 {
        self.md.last().copied().unwrap_or(0.0)
    }
}

/// A point of the trajectory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    pub md: f64,
    /// rad
    pub inc: f64,
    /// rad, in `[0, 2 pi)`
    pub azi: f64,
    /// Unit direction (north, east, down).
    pub tangent: [f64; 3],
    /// (north, east, tvd), m.
    pub position: [f64; 3],
    /// Curvature of the arc the point lies on, 1/m (0 beyond the last station).
    pub curvature: f64,
}

/// The minimum-curvature trajectory of a survey.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    pub survey: Survey,
    /// Unit direction at each station.
    pub tangent: Vec<[f64; 3]>,
    /// (north, east, tvd) at each station, m.
    pub position: Vec<[f64; 3]>,
    /// Dogleg of the interval ending at each station, rad (0 at the first).
    pub dogleg: Vec<f64>,
}

/// The ratio factor `tan(beta / 2) / (beta / 2)` of minimum curvature (series below 1e-4).
fn ratio_factor(beta: f64) -> f64 {
    if beta < 1e-4 {
        1.0 + beta * beta / 12.0
    } else {
        (beta / 2.0).tan() / (beta / 2.0)
    }
}

/// `sin(f beta) / sin(beta)`, the weight of spherical interpolation (`f` for small `beta`).
fn slerp_weight(f: f64, beta: f64) -> f64 {
    if beta < 1e-6 {
        f * (1.0 + (1.0 - f * f) * beta * beta / 6.0)
    } else {
        (f * beta).sin() / beta.sin()
    }
}

impl Trajectory {
    /// Minimum curvature through the stations of `survey`.
    pub fn new(survey: Survey) -> Trajectory {
        let n = survey.len();
        let tangent: Vec<[f64; 3]> = (0..n).map(|j| direction(survey.inc[j], survey.azi[j])).collect();
        let mut position = vec![[0.0; 3]; n];
        let mut dogleg = vec![0.0; n];
        for j in 1..n {
            let beta = angle_between(tangent[j - 1], tangent[j]);
            let half = 0.5 * (survey.md[j] - survey.md[j - 1]) * ratio_factor(beta);
            dogleg[j] = beta;
            for k in 0..3 {
                position[j][k] = position[j - 1][k] + half * (tangent[j - 1][k] + tangent[j][k]);
            }
        }
        Trajectory { survey, tangent, position, dogleg }
    }

    /// Dogleg severity of the interval ending at each station, degrees per 30 m (0 at the first).
    pub fn dls_deg_per_30m(&self) -> Vec<f64> {
        let md = &self.survey.md;
        (0..md.len())
            .map(|j| if j == 0 { 0.0 } else { self.dogleg[j].to_degrees() * 30.0 / (md[j] - md[j - 1]) })
            .collect()
    }

    /// The point at measured depth `md` (`md >= 0`): on the arc between the stations around
    /// it; beyond the last station, straight on in its direction.
    ///
    /// In an interval whose two directions share an azimuth or one of them is vertical (a
    /// planar arc in a vertical plane) the inclination is interpolated linearly in measured
    /// depth (exact for such an arc, and bit-for-bit the rule of a 2-D table); the direction
    /// itself is always the spherical interpolation.
    pub fn at(&self, md: f64) -> PathPoint {
        self.at_on(md, self.interval(md))
    }

    /// The interval holding `md`: the index of the station ending it (`1..n`), or `n` beyond
    /// the last station (a station's depth belongs to the interval below it).
    pub fn interval(&self, md: f64) -> usize {
        self.survey.md.partition_point(|&x| x <= md).max(1)
    }

    /// [`Trajectory::at`] on the arc of interval `k` ([`Trajectory::interval`]), so that a
    /// station's depth can be taken on the arc above it as well as below.
    pub fn at_on(&self, md: f64, k: usize) -> PathPoint {
        let s = &self.survey;
        let n = s.len();
        if k >= n {
            let j = n - 1;
            let t = self.tangent[j];
            let ds = md - s.md[j];
            let p = self.position[j];
            return PathPoint {
                md,
                inc: s.inc[j],
                azi: s.azi[j],
                tangent: t,
                position: [p[0] + ds * t[0], p[1] + ds * t[1], p[2] + ds * t[2]],
                curvature: 0.0,
            };
        }
        let (a, b) = (k - 1, k);
        let length = s.md[b] - s.md[a];
        let f = ((md - s.md[a]) / length).clamp(0.0, 1.0);
        let beta = self.dogleg[b];
        let (wa, wb) = (slerp_weight(1.0 - f, beta), slerp_weight(f, beta));
        let (ta, tb) = (self.tangent[a], self.tangent[b]);
        let mut t = [wa * ta[0] + wb * tb[0], wa * ta[1] + wb * tb[1], wa * ta[2] + wb * tb[2]];
        let tn = norm(t);
        t.iter_mut().for_each(|x| *x /= tn);
        // the chord from station a to the point: the arc from ta to t, of angle f beta
        let sub = f * beta;
        let half = 0.5 * f * length * ratio_factor(sub);
        let pa = self.position[a];
        let position = [pa[0] + half * (ta[0] + t[0]), pa[1] + half * (ta[1] + t[1]), pa[2] + half * (ta[2] + t[2])];
        let planar = s.azi[a] == s.azi[b] || s.inc[a] == 0.0 || s.inc[b] == 0.0;
        let (inc, azi) = if planar {
            let (ia, ib) = (s.inc_deg[a], s.inc_deg[b]);
            let inc = (ia + f * (ib - ia)).to_radians();
            let azi = if s.inc[a] == 0.0 { s.azi[b] } else { s.azi[a] };
            (inc, azi)
        } else {
            let inc = t[2].clamp(-1.0, 1.0).acos();
            let azi = t[1].atan2(t[0]).rem_euclid(std::f64::consts::TAU);
            (inc, azi)
        };
        PathPoint { md, inc, azi, tangent: t, position, curvature: beta / length }
    }

    /// The derivative of the direction along the arc of interval `k`, `dt/ds` (its length is
    /// the curvature, 1/m; it points to the inside of the bend), at measured depth `md`.
    pub fn curvature_vector_on(&self, md: f64, k: usize) -> [f64; 3] {
        let s = &self.survey;
        if k >= s.len() {
            return [0.0; 3];
        }
        let (a, b) = (k - 1, k);
        let length = s.md[b] - s.md[a];
        let beta = self.dogleg[b];
        let (ta, tb) = (self.tangent[a], self.tangent[b]);
        if beta < 1e-9 {
            return [(tb[0] - ta[0]) / length, (tb[1] - ta[1]) / length, (tb[2] - ta[2]) / length];
        }
        let f = ((md - s.md[a]) / length).clamp(0.0, 1.0);
        let scale = beta / (length * beta.sin());
        let (ca, cb) = (-((1.0 - f) * beta).cos() * scale, (f * beta).cos() * scale);
        [ca * ta[0] + cb * tb[0], ca * ta[1] + cb * tb[1], ca * ta[2] + cb * tb[2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn survey(md: &[f64], inc: &[f64], azi: &[f64]) -> Survey {
        Survey::from_degrees("well", md, inc, azi).unwrap()
    }

    /// A build from vertical to `inc` over an arc of radius `r` in the north-down plane:
    /// north = r (1 - cos i), tvd = r sin i, md = r i.
    #[test]
    fn circular_arc_in_a_vertical_plane() {
        let r = 1000.0;
        let i_end: f64 = 60.0;
        let md_end = r * i_end.to_radians();
        let t = Trajectory::new(survey(&[0.0, md_end], &[0.0, i_end], &[0.0, 0.0]));
        let p = t.position[1];
        let i = i_end.to_radians();
        assert!((p[0] - r * (1.0 - i.cos())).abs() < 1e-9, "{p:?}");
        assert!(p[1].abs() < 1e-12);
        assert!((p[2] - r * i.sin()).abs() < 1e-9);
        // every point on the arc lies on the circle, at the angle md / r
        for f in [0.1, 0.37, 0.5, 0.9] {
            let q = t.at(f * md_end);
            let a = f * i;
            assert!((q.position[0] - r * (1.0 - a.cos())).abs() < 1e-9);
            assert!((q.position[2] - r * a.sin()).abs() < 1e-9);
            assert!((q.inc - a).abs() < 1e-12);
            assert!((q.curvature - 1.0 / r).abs() < 1e-15);
        }
        // dogleg severity: 60 deg over md_end, per 30 m
        let dls = t.dls_deg_per_30m()[1];
        assert!((dls - 60.0 * 30.0 / md_end).abs() < 1e-12);
    }

    /// A horizontal turn at constant radius: a quarter circle in the north-east plane.
    #[test]
    fn horizontal_turn() {
        let r = 500.0;
        let md_end = r * PI / 2.0;
        let t = Trajectory::new(survey(&[0.0, md_end], &[90.0, 90.0], &[0.0, 90.0]));
        let p = t.position[1];
        assert!((p[0] - r).abs() < 1e-9 && (p[1] - r).abs() < 1e-9 && p[2].abs() < 1e-9, "{p:?}");
        let q = t.at(md_end / 3.0);
        assert!((q.azi - PI / 6.0).abs() < 1e-12);
        assert!((q.inc - PI / 2.0).abs() < 1e-12);
        assert!((q.position[0] - r * (PI / 6.0).sin()).abs() < 1e-9);
        assert!((q.position[1] - r * (1.0 - (PI / 6.0).cos())).abs() < 1e-9);
    }

    /// A helix (constant inclination, azimuth turning at a constant rate): the minimum-curvature
    /// positions converge to the helix's closed form at second order as stations are refined.
    #[test]
    fn helix_converges_at_second_order() {
        let (inc, turn, length) = (45f64, 90f64, 1000.0);
        let exact = |md: f64| {
            let i = inc.to_radians();
            let rate = turn.to_radians() / length;
            let a = rate * md;
            [i.sin() * a.sin() / rate, i.sin() * (1.0 - a.cos()) / rate, i.cos() * md]
        };
        let error = |n: usize| {
            let md: Vec<f64> = (0..=n).map(|j| length * j as f64 / n as f64).collect();
            let incs = vec![inc; n + 1];
            let azi: Vec<f64> = (0..=n).map(|j| turn * j as f64 / n as f64).collect();
            let t = Trajectory::new(survey(&md, &incs, &azi));
            let p = t.position[n];
            let e = exact(length);
            ((p[0] - e[0]).powi(2) + (p[1] - e[1]).powi(2) + (p[2] - e[2]).powi(2)).sqrt()
        };
        let (e1, e2) = (error(10), error(20));
        let order = (e1 / e2).log2();
        assert!(e1 > 1e-3 && (order - 2.0).abs() < 0.1, "errors {e1} {e2} order {order}");
    }

    #[test]
    fn straight_and_beyond_the_end() {
        let t = Trajectory::new(survey(&[0.0, 1000.0], &[30.0, 30.0], &[45.0, 45.0]));
        let q = t.at(1500.0);
        let i = 30f64.to_radians();
        assert!((q.position[2] - 1500.0 * i.cos()).abs() < 1e-9);
        assert!((q.position[0] - 1500.0 * i.sin() * 45f64.to_radians().cos()).abs() < 1e-9);
        assert_eq!(q.curvature, 0.0);
        assert_eq!(t.dogleg[1], 0.0);
    }

    #[test]
    fn bad_surveys_are_refused_naming_the_station() {
        let e = Survey::from_degrees("well", &[0.0, 10.0, 10.0], &[0.0; 3], &[0.0; 3]).unwrap_err();
        assert_eq!(e.field(), "well.md[2]");
        let e = Survey::from_degrees("well", &[5.0, 10.0], &[0.0; 2], &[0.0; 2]).unwrap_err();
        assert_eq!(e.field(), "well.md[0]");
        let e = Survey::from_degrees("well", &[0.0, 10.0], &[0.0, 181.0], &[0.0; 2]).unwrap_err();
        assert_eq!(e.field(), "well.inclination_deg[1]");
        let e = Survey::from_degrees("well", &[0.0, 10.0], &[0.0, 1.0], &[0.0, -1.0]).unwrap_err();
        assert_eq!(e.field(), "well.azimuth_deg[1]");
        let e = Survey::from_degrees("well", &[0.0, 10.0], &[0.0], &[0.0, 0.0]).unwrap_err();
        assert_eq!(e.field(), "well.inclination_deg");
    }

    #[test]
    fn angle_between_is_accurate_at_small_angles() {
        let a = direction(0.3, 1.0);
        let b = direction(0.3 + 1e-9, 1.0);
        assert!((angle_between(a, b) - 1e-9).abs() < 1e-15, "{}", angle_between(a, b));
        assert!((angle_between(direction(0.0, 0.0), direction(PI, 0.0)) - PI).abs() < 1e-15);
    }
}
