//! The output sampler of a run: the series at `k output_interval`, linear between the step
//! ends around each sample time, and the field snapshots at the step nearest to
//! `k field_interval`; storage reserved up front ([`crate::solution::reserve_outputs`]).

use super::axial_field::{self, Axial};
use super::controller::RPM_PER_RAD_S;
use super::field::StringField;
use super::run::DrillRun;
use super::torsion::Torsion;
use crate::drilling::config::DrillConfig;
use crate::solution::OutOfMemory;

/// A channel of the series: its column in a sample [`Point`], and whether it is a load over a
/// step (held: the point at `t = 0` takes the first step's value, the state at rest having none).
/// Each part declares its channels where it is (the torsional ones here, a coupled run's in
/// [`super::axial`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Channel {
    pub column: usize,
    pub held: bool,
}

/// Time, s.
pub const TIME: Channel = Channel { column: 0, held: false };
/// The top drive's speed, rad/s.
pub const TOP_SPEED: Channel = Channel { column: 1, held: false };
/// The bit's speed (as reported, [`super::run`]), rad/s.
pub const BIT_SPEED: Channel = Channel { column: 2, held: false };
/// The motor torque of the step, N m.
pub const MOTOR_TORQUE: Channel = Channel { column: 3, held: true };
/// The torque on bit of the step, N m.
pub const BIT_TORQUE: Channel = Channel { column: 4, held: true };
/// The torsional channels.
pub const TORSIONAL: [Channel; 5] = [TIME, TOP_SPEED, BIT_SPEED, MOTOR_TORQUE, BIT_TORQUE];

/// Columns of a sample point: the torsional channels and a coupled run's
/// ([`super::axial_field::CHANNELS`], 0 without a hoist).
pub const COLUMNS: usize = TORSIONAL.len() + super::axial_field::CHANNELS.len();

/// The series' values at a step end, by [`Channel`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point([f64; COLUMNS]);

impl Default for Point {
    fn default() -> Self {
        Point([0.0; COLUMNS])
    }
}

impl std::ops::Index<Channel> for Point {
    type Output = f64;
    #[inline]
    fn index(&self, c: Channel) -> &f64 {
        &self.0[c.column]
    }
}

impl std::ops::IndexMut<Channel> for Point {
    #[inline]
    fn index_mut(&mut self, c: Channel) -> &mut f64 {
        &mut self.0[c.column]
    }
}

/// Where the sampling stands.
#[derive(Clone)]
pub struct Sampler {
    n_series: usize,
    n_fields: usize,
    out_dt: f64,
    field_dt: f64,
    next_series: usize,
    next_field: usize,
    /// Whether the run is coupled (the axial series are recorded).
    coupled: bool,
    /// The previous step end.
    prev: Point,
}

impl Sampler {
    pub fn new(cfg: &DrillConfig) -> Self {
        Sampler {
            n_series: cfg.series_samples(),
            n_fields: cfg.field_samples(),
            out_dt: cfg.numerics.output_interval,
            field_dt: cfg.numerics.field_interval,
            next_series: 0,
            next_field: 1,
            coupled: cfg.hoist.is_some(),
            prev: Point::default(),
        }
    }

    /// A session's sampler ([`super::session::Session`]): the series and, with `keep_fields`,
    /// the snapshots without an end (their storage grown as the session is stepped,
    /// [`Sampler::grow`]).
    pub fn open(cfg: &DrillConfig, keep_fields: bool) -> Self {
        let keep = keep_fields && cfg.numerics.field_interval > 0.0;
        Sampler { n_series: usize::MAX, n_fields: if keep { usize::MAX } else { 0 }, ..Sampler::new(cfg) }
    }

    /// Makes room for `rows` more samples of the series and `snapshots` more field snapshots
    /// of `cells` cells (and `axial_cells` of a coupled run), at least doubling storage that
    /// must grow.
    pub fn grow(
        &self,
        run: &mut DrillRun,
        rows: usize,
        snapshots: usize,
        cells: usize,
        axial_cells: usize,
    ) -> Result<(), OutOfMemory> {
        let snapshots = if self.n_fields == 0 { 0 } else { snapshots };
        let mut outputs = self.outputs(run, rows, snapshots, cells, axial_cells);
        for (v, more) in &mut outputs {
            let spare = v.capacity() - v.len();
            *more = if spare >= *more { 0 } else { (*more).max(v.len()) };
        }
        crate::solution::reserve_outputs(&mut outputs)
    }

    /// Reserves the run's sample storage for `cells` cells (and `axial_cells` of a coupled run).
    pub fn reserve(&self, run: &mut DrillRun, cells: usize, axial_cells: usize) -> Result<(), OutOfMemory> {
        crate::solution::reserve_outputs(&mut self.outputs(run, self.n_series, self.n_fields, cells, axial_cells))
    }

    /// Every output vector of `run` with the length it takes for `rows` series samples and
    /// `snapshots` field snapshots of `cells` cells (`axial_cells` of a coupled run; the axial
    /// ones 0 without a hoist).
    fn outputs<'r>(
        &self,
        run: &'r mut DrillRun,
        rows: usize,
        snapshots: usize,
        cells: usize,
        axial_cells: usize,
    ) -> [(&'r mut Vec<f64>, usize); 17] {
        let n_axial = if self.coupled { rows } else { 0 };
        let axial_cells = if self.coupled { axial_cells } else { 0 };
        [
            (&mut run.bit_axial_speed, n_axial),
            (&mut run.rop, n_axial),
            (&mut run.weight_on_bit, n_axial),
            (&mut run.hook_load, n_axial),
            (&mut run.bit_depth, n_axial),
            (&mut run.depth_of_cut, n_axial),
            (&mut run.block_position, n_axial),
            (&mut run.t, rows),
            (&mut run.surface_rpm, rows),
            (&mut run.bit_rpm, rows),
            (&mut run.motor_torque, rows),
            (&mut run.bit_torque, rows),
            (&mut run.field_t, snapshots),
            (&mut run.omega_field, snapshots * cells),
            (&mut run.torque_field, snapshots * cells),
            (&mut run.axial_speed_field, snapshots * axial_cells),
            (&mut run.axial_force_field, snapshots * axial_cells),
        ]
    }

    /// The initial snapshot (if any are asked for) and state `point` at `t = 0` (its held
    /// channels are the first step's); `false` when not finite.
    pub fn start(&mut self, torsion: &Torsion, axial: Option<&Axial>, run: &mut DrillRun, point: Point) -> bool {
        self.prev = point;
        self.n_fields == 0 || snapshot(torsion, axial, run, 0.0)
    }

    /// Whether a sample of the series falls at or before the step end `t`.
    #[inline]
    fn series_due(&self, t: f64) -> bool {
        self.next_series < self.n_series && self.next_series as f64 * self.out_dt <= t * (1.0 + 1e-12)
    }

    /// Whether [`Sampler::record`] needs the point at the end `t` of step `n` (0-based; the
    /// next step ending at `t_next`): the first step's (its held channels), and a step end
    /// with a sample of the series in the step before it or after it (the two ends a sample
    /// is interpolated between). The points of the other steps are not made.
    #[inline]
    pub fn needs_point(&self, n: u64, t: f64, t_next: f64) -> bool {
        n == 0 || self.series_due(t) || self.series_due(t_next)
    }

    /// Samples after step `n` (0-based) ending at `t` with the point `cur` there (`None` where
    /// [`Sampler::needs_point`] says it is not needed): the series up to `t`, then a snapshot
    /// of `torsion` (and of a coupled run's `axial`) if one is due (`dt` the step). `false`
    /// (the sample not stored) when a value is not finite.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        n: u64,
        t: f64,
        cur: Option<Point>,
        torsion: &Torsion,
        axial: Option<&Axial>,
        run: &mut DrillRun,
        dt: f64,
    ) -> bool {
        let Some(cur) = cur else {
            debug_assert!(!self.series_due(t));
            return self.snapshot_due(t, torsion, axial, run, dt);
        };
        debug_assert_eq!(t.to_bits(), cur[TIME].to_bits());
        let prev = &mut self.prev;
        if n == 0 {
            for &c in Torsion::channels().iter().chain(Axial::channels()).filter(|c| c.held) {
                prev[c] = cur[c];
            }
        }
        while self.next_series < self.n_series {
            let ts = self.next_series as f64 * self.out_dt;
            if ts > t * (1.0 + 1e-12) {
                break;
            }
            let w = if cur[TIME] > prev[TIME] {
                ((ts - prev[TIME]) / (cur[TIME] - prev[TIME])).clamp(0.0, 1.0)
            } else {
                1.0
            };
            let at = |c: Channel| prev[c] + w * (cur[c] - prev[c]);
            let sample =
                [ts, at(TOP_SPEED) * RPM_PER_RAD_S, at(BIT_SPEED) * RPM_PER_RAD_S, at(MOTOR_TORQUE), at(BIT_TORQUE)];
            if sample.iter().any(|v| !v.is_finite()) || Axial::channels().iter().any(|&c| !at(c).is_finite()) {
                return false;
            }
            if self.coupled {
                run.bit_axial_speed.push(at(axial_field::BIT_AXIAL_SPEED));
                run.rop.push(at(axial_field::ROP));
                run.weight_on_bit.push(at(axial_field::WEIGHT_ON_BIT));
                run.hook_load.push(at(axial_field::HOOK_LOAD));
                run.bit_depth.push(at(axial_field::BIT_DEPTH));
                run.depth_of_cut.push(at(axial_field::DEPTH_OF_CUT));
                run.block_position.push(at(axial_field::BLOCK_POSITION));
            }
            run.t.push(sample[0]);
            run.surface_rpm.push(sample[1]);
            run.bit_rpm.push(sample[2]);
            run.motor_torque.push(sample[3]);
            run.bit_torque.push(sample[4]);
            self.next_series += 1;
        }
        self.prev = cur;
        self.snapshot_due(t, torsion, axial, run, dt)
    }

    /// The snapshot at the step end `t` if one is due; `false` when a value is not finite.
    #[inline]
    fn snapshot_due(&mut self, t: f64, torsion: &Torsion, axial: Option<&Axial>, run: &mut DrillRun, dt: f64) -> bool {
        if self.next_field < self.n_fields && t >= self.next_field as f64 * self.field_dt - 0.5 * dt {
            if !snapshot(torsion, axial, run, t) {
                return false;
            }
            self.next_field += 1;
        }
        true
    }
}

/// Appends the fields at `t` (a coupled run's axial speed and force too); `false` (nothing
/// appended) when a value is not finite.
fn snapshot(torsion: &Torsion, axial: Option<&Axial>, run: &mut DrillRun, t: f64) -> bool {
    let start = run.omega_field.len();
    let axial_start = run.axial_speed_field.len();
    torsion.each_cell(|w, tau| {
        run.omega_field.push(w * RPM_PER_RAD_S);
        run.torque_field.push(tau);
    });
    if let Some(axial) = axial {
        axial.each_cell(|v, f| {
            run.axial_speed_field.push(v);
            run.axial_force_field.push(f);
        });
    }
    let finite = (run.omega_field[start..].iter().chain(&run.torque_field[start..]))
        .chain(run.axial_speed_field[axial_start..].iter().chain(&run.axial_force_field[axial_start..]))
        .all(|v| v.is_finite());
    if finite {
        run.field_t.push(t);
    } else {
        run.omega_field.truncate(start);
        run.torque_field.truncate(start);
        run.axial_speed_field.truncate(axial_start);
        run.axial_force_field.truncate(axial_start);
    }
    finite
}
