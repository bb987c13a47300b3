//! Two runs of one configuration compared metric by metric, with the tolerances defined once
//! ([`tolerances`]): the grid check (`check_grid`, the run on twice the cells) and the start
//! check (`check_start`, the run from rest against the run from the steady state,
//! [`super::start::InitialState`]).
//!
//! A metric is a number or a text (a verdict, a regime); each run gives its metrics by name
//! (the names of `metrics.json`: the stick-slip metrics and, for a coupled run, its `coupled`
//! block), and only the names both runs give are compared.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// How a metric's change is judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// The relative change `b / a - 1` (none when `a = 0`: then only `b = 0` is within).
    Rel,
    /// The change `b - a` in the metric's unit.
    Abs,
    /// A verdict or regime that must not change (the change 0 or 1).
    Equal,
}

/// How far each metric may move between the two runs of a check before it warns: the name,
/// the kind, the tolerance and the floor, each metric's in the registry of outputs
/// ([`crate::outputs::Output::tolerance`]). The torsional ones: the stuck fraction and the lowest
/// bit speed as differences (a fraction, rpm), the others relative; the coupled ones: the means of
/// ROP, weight and torque on bit within 2 %, the hook load within 1 % (it is mostly the string's
/// weight), MSE within 3 % (a ratio of two means), the bounce fraction within 0.02, the regime
/// unchanged. The floor: a change at most this large (in the metric's unit) is within whatever
/// its relative size (the SSI of two runs that hardly oscillate, 3e-5 and 1e-7, agree: both below
/// 0.01).
pub fn tolerances() -> Vec<(&'static str, Kind, f64, f64)> {
    crate::outputs::tolerances()
}

/// A metric's value: a number (NaN: undefined; a verdict as 0 or 1) or a text.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Value {
    Number(f64),
    Text(String),
}

impl Value {
    fn defined(&self) -> bool {
        match self {
            Value::Number(x) => !x.is_nan(),
            Value::Text(_) => true,
        }
    }
}

/// One metric of a check: its value in each run, the change, the tolerance and whether the
/// change is within it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    pub metric: &'static str,
    /// None when undefined (NaN).
    pub value: Option<Value>,
    pub other: Option<Value>,
    /// `other - value` (`abs`), `other / value - 1` (`rel`; None when `value` is 0), 0 or 1 for
    /// a verdict that kept or changed; None when either is undefined.
    pub change: Option<f64>,
    pub kind: Kind,
    pub tolerance: f64,
    /// The change is within the tolerance (a metric undefined in one run only is not).
    pub within: bool,
}

/// The rows of [`tolerances`] whose metric both `a` and `b` give, in its order.
pub fn compare(a: &BTreeMap<String, Value>, b: &BTreeMap<String, Value>) -> Vec<Row> {
    tolerances()
        .into_iter()
        .filter_map(|(name, kind, tolerance, floor)| {
            let (x, y) = (a.get(name)?, b.get(name)?);
            let (change, within) = match (x.defined(), y.defined()) {
                (false, false) => (None, true),
                (true, true) => {
                    let (change, within) = judge(x, y, kind, tolerance);
                    let small = matches!((x, y), (Value::Number(p), Value::Number(q)) if (q - p).abs() <= floor);
                    (change, within || small)
                }
                _ => (None, false),
            };
            let shown = |v: &Value| v.defined().then(|| v.clone());
            Some(Row { metric: name, value: shown(x), other: shown(y), change, kind, tolerance, within })
        })
        .collect()
}

/// The change of two defined values and whether it is within `tolerance`.
fn judge(x: &Value, y: &Value, kind: Kind, tolerance: f64) -> (Option<f64>, bool) {
    match (x, y, kind) {
        (_, _, Kind::Equal) => {
            let same = x == y;
            (Some(if same { 0.0 } else { 1.0 }), same)
        }
        (Value::Number(a), Value::Number(b), Kind::Rel) => {
            if *a == 0.0 {
                (None, a == b)
            } else {
                let change = b / a - 1.0;
                (Some(change), change.abs() <= tolerance || a == b)
            }
        }
        (Value::Number(a), Value::Number(b), Kind::Abs) => {
            let change = b - a;
            (Some(change), change.abs() <= tolerance || a == b)
        }
        // a text judged as a number: only equal texts agree
        _ => (None, x == y),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(pairs: &[(&str, Value)]) -> BTreeMap<String, Value> {
        pairs.iter().map(|(k, v)| (k.to_string(), v.clone())).collect()
    }

    #[test]
    fn each_kind_is_judged_by_its_rule_and_only_common_metrics_are_compared() {
        use Value::{Number as N, Text as T};
        let a = metrics(&[
            ("ssi", N(1.0)),
            ("stuck_fraction", N(0.2)),
            ("period_s", N(f64::NAN)),
            ("bit_rpm_min", N(f64::NAN)),
            ("rop_mean_m_per_h", N(10.0)),
            ("regime", T("smooth drilling".into())),
            ("settled", N(1.0)),
        ]);
        let b = metrics(&[
            ("ssi", N(1.04)),
            ("stuck_fraction", N(0.25)),
            ("period_s", N(f64::NAN)),
            ("bit_rpm_min", N(3.0)),
            ("rop_mean_m_per_h", N(8.08)),
            ("regime", T("undetermined".into())),
            ("settled", N(1.0)),
            ("wob_mean_N", N(1.0)),
        ]);
        let rows = compare(&a, &b);
        let names: Vec<_> = rows.iter().map(|r| r.metric).collect();
        assert_eq!(
            names,
            ["ssi", "stuck_fraction", "period_s", "bit_rpm_min", "settled", "rop_mean_m_per_h", "regime"]
        );
        let row = |n: &str| rows.iter().find(|r| r.metric == n).unwrap().clone();
        assert!(row("ssi").within && (row("ssi").change.unwrap() - 0.04).abs() < 1e-12);
        // below the SSI's floor a relative change of -100 % is within
        let tiny = compare(&metrics(&[("ssi", N(3e-5))]), &metrics(&[("ssi", N(1e-7))]));
        assert!(tiny[0].within && tiny[0].change.unwrap() < -0.99, "{tiny:?}");
        assert!(!row("stuck_fraction").within);
        assert!(row("period_s").within && row("period_s").value.is_none());
        assert!(!row("bit_rpm_min").within && row("bit_rpm_min").change.is_none());
        assert!(row("settled").within);
        let rop = row("rop_mean_m_per_h");
        assert!(!rop.within && (rop.change.unwrap() + 0.192).abs() < 1e-12, "{rop:?}");
        assert_eq!((row("regime").within, row("regime").change), (false, Some(1.0)));
    }
}
