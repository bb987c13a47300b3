//! What a solve returns: samples, a status and statistics.

use std::fmt;

use serde::{Serialize, Serializer};

/// The name of the newtype struct [`serialize_list`] wraps a sequence in: a serialiser that
/// makes numeric sequences arrays (the Python bindings) makes this one a list of values, even
/// when empty; serde_json and the like see through it.
pub const LIST: &str = "list";

/// Serialises `values` (a sequence or a fixed-size array) as a list of values, not as a numeric
/// array; for `#[serde(serialize_with = "...")]`.
pub fn serialize_list<S: Serializer, V: Serialize + ?Sized>(values: &V, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_newtype_struct(LIST, values)
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Reached `t_end`.
    Success,
    /// Stopped after `max_steps` steps before reaching `t_end`.
    MaxStepsReached,
    /// The adaptive step size fell below the floor `10 * eps * |t|` (stiffness or a blow-up).
    StepSizeUnderflow,
    /// The state became NaN or infinite (divergence).
    NonFinite,
    /// Stopped on request (an [`crate::interrupt::Interrupt`] hook: Ctrl-C, a cancelled sweep).
    Interrupted,
    /// The samples could not be stored: the system refused the memory (the samples recorded
    /// before are kept).
    OutOfMemory,
}

impl Status {
    /// A stable integer code (used across the Python boundary).
    pub fn code(self) -> i32 {
        match self {
            Status::Success => 0,
            Status::MaxStepsReached => 1,
            Status::StepSizeUnderflow => 2,
            Status::NonFinite => 3,
            Status::Interrupted => 4,
            Status::OutOfMemory => 5,
        }
    }

    /// A stable short name (`"success"`, `"max_steps"`, `"step_size_underflow"`, `"non_finite"`,
    /// `"interrupted"`, `"out_of_memory"`).
    pub fn name(self) -> &'static str {
        match self {
            Status::Success => "success",
            Status::MaxStepsReached => "max_steps",
            Status::StepSizeUnderflow => "step_size_underflow",
            Status::NonFinite => "non_finite",
            Status::Interrupted => "interrupted",
            Status::OutOfMemory => "out_of_memory",
        }
    }

    pub fn is_success(self) -> bool {
        self == Status::Success
    }
}

/// A status serialises as its [`Status::name`].
impl Serialize for Status {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Work counters of one solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Right-hand-side evaluations (for second-order fixed-step schemes: acceleration evaluations).
    pub nfev: u64,
    /// Accepted steps.
    pub naccept: u64,
    /// Rejected steps (always 0 for fixed-step methods).
    pub nreject: u64,
    /// Of `nfev`, the evaluations made only for the dense output (DOP853's extra stages for
    /// output times strictly inside a step; 0 for the other methods): `nfev - ndense` does not
    /// depend on the output times.
    pub ndense: u64,
}

/// A sample could not be stored: the system refused memory for `bytes` bytes of samples
/// (the vector's size after the sample; the request doubles it when it grows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutOfMemory {
    pub bytes: usize,
}

impl OutOfMemory {
    /// The message of a run whose outputs could not be allocated up front.
    pub fn outputs_message(self) -> String {
        format!("the outputs ({} MiB) could not be allocated", self.bytes >> 20)
    }
}

/// Reserves, exactly and without aborting, room for `len` more values in each output vector
/// `(vector, len)` (the sample storage of a run, sized up front). `Err` carries the bytes of
/// all of them; the vectors reserved before the refusal keep their room.
pub fn reserve_outputs(outputs: &mut [(&mut Vec<f64>, usize)]) -> std::result::Result<(), OutOfMemory> {
    if outputs.iter_mut().all(|(v, len)| v.try_reserve_exact(*len).is_ok()) {
        Ok(())
    } else {
        let values = outputs.iter().fold(0usize, |sum, (_, len)| sum.saturating_add(*len));
        Err(OutOfMemory { bytes: values.saturating_mul(8) })
    }
}

/// The samples of one solve: `t[k]` and the state `y[k * dim .. (k + 1) * dim]`.
///
/// When the solve stops early (any status other than [`Status::Success`]) the samples
/// hold only the output times reached before it stopped.
///
/// Serialised as `t`, `y` (flat), `status`, `message`, the [`Stats`] and `dissipated`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Solution {
    #[serde(skip)]
    pub dim: usize,
    pub t: Vec<f64>,
    /// Row-major, `t.len() * dim` values.
    pub y: Vec<f64>,
    pub status: Status,
    /// Human-readable explanation of the status (empty on success).
    pub message: String,
    #[serde(flatten)]
    pub stats: Stats,
    /// For a second-order system with velocity-dependent forces: the energy they dissipated
    /// from the start to each sample (one value per sample, integrated with the state, see
    /// [`crate::system::Dissipating`]). Empty for a conservative system.
    pub dissipated: Vec<f64>,
}

impl Solution {
    /// An empty solution for a state of length `dim`, with room for `capacity` samples
    /// (less, down to none, when the system refuses that memory: the vectors then grow by
    /// [`Solution::try_push`]).
    pub fn with_capacity(dim: usize, capacity: usize) -> Self {
        let mut sol = Solution {
            dim,
            t: Vec::new(),
            y: Vec::new(),
            status: Status::Success,
            message: String::new(),
            stats: Stats::default(),
            dissipated: Vec::new(),
        };
        let values = capacity.saturating_mul(dim);
        if reserve_outputs(&mut [(&mut sol.t, capacity), (&mut sol.y, values)]).is_err() {
            sol.t = Vec::new();
            sol.y = Vec::new();
        }
        sol
    }

    /// Appends one sample; `Err` (nothing appended) when the memory for it cannot be had.
    /// Growing never aborts the process: the allocation is fallible.
    pub fn try_push(&mut self, t: f64, y: &[f64]) -> std::result::Result<(), OutOfMemory> {
        debug_assert_eq!(y.len(), self.dim);
        self.t.try_reserve(1).map_err(|_| OutOfMemory { bytes: 8 * (self.t.len() + 1) })?;
        self.y.try_reserve(y.len()).map_err(|_| OutOfMemory { bytes: 8 * (self.y.len() + y.len()) })?;
        self.t.push(t);
        self.y.extend_from_slice(y);
        Ok(())
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The state at sample `k`.
    pub fn state(&self, k: usize) -> &[f64] {
        &self.y[k * self.dim..(k + 1) * self.dim]
    }

    /// Ends the solve with a failure status and message.
    pub fn fail(&mut self, status: Status, message: impl Into<String>) {
        self.status = status;
        self.message = message.into();
    }
}
