//! Errors of invalid input. Numerical failures are not errors: they end a solve
//! with a [`crate::Status`] and a message.

use std::fmt;

/// An input the core refuses, naming the field, the value and what is allowed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Error {
    InvalidInput { field: String, value: String, allowed: String },
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn invalid(field: impl Into<String>, value: impl fmt::Display, allowed: impl Into<String>) -> Self {
        Error::InvalidInput { field: field.into(), value: value.to_string(), allowed: allowed.into() }
    }

    /// The offending field's name.
    pub fn field(&self) -> &str {
        match self {
            Error::InvalidInput { field, .. } => field,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidInput { field, value, allowed } => {
                write!(f, "invalid {field}: got {value}, expected {allowed}")
            }
        }
    }
}

impl std::error::Error for Error {}

/// A number as messages show it: ten significant digits at most, trailing zeros dropped,
/// plain notation for `1e-4 <= |x| < 1e15` and exponent notation otherwise, with Python's
/// exponent style (`2.5e-05`, `0.1`, `1e+20`, `nan`, `inf`).
///
/// ```
/// use drillstring_core::Num;
/// assert_eq!(Num(2.5e-5).to_string(), "2.5e-05");
/// assert_eq!(Num(0.1 + 0.2).to_string(), "0.3");
/// assert_eq!(Num(1234.5).to_string(), "1234.5");
/// assert_eq!(Num(-1e300).to_string(), "-1e+300");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_significant(f, self.0, 10, false)
    }
}

/// A computed number in a message (a torque, an amplitude: not a value the user typed), to 4
/// significant digits in [`Num`]'s style.
///
/// ```
/// use drillstring_core::error::Short;
/// assert_eq!(Short(549361.0367).to_string(), "549400");
/// assert_eq!(Short(0.002234360128).to_string(), "0.002234");
/// assert_eq!(Short(2.29002411).to_string(), "2.29");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_significant(f, self.0, 4, true)
    }
}

/// `x` to `digits` (>= 1) significant digits, trailing zeros of the fraction dropped: plain notation
/// for `1e-4 <= |x| < 1e15` (a longer integer part kept whole unless `round_integers`), exponent
/// notation otherwise.
fn write_significant(f: &mut fmt::Formatter<'_>, x: f64, digits: usize, round_integers: bool) -> fmt::Result {
    if !x.is_finite() {
        return f.write_str(if x.is_nan() {
            "nan"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        });
    }
    if x == 0.0 {
        return f.write_str(if x.is_sign_negative() { "-0" } else { "0" });
    }
    let sci = format!("{:.*e}", digits - 1, x);
    let (mantissa, exponent) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if (-4..15).contains(&exponent) {
        // an integer part longer than `digits`: kept whole, or rounded to `digits` digits
        let rounded: f64 = if round_integers { sci.parse().unwrap_or(x) } else { x };
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        f.write_str(&trim(&format!("{rounded:.decimals$}")))
    } else {
        let sign = if exponent < 0 { '-' } else { '+' };
        write!(f, "{}e{sign}{:02}", trim(mantissa), exponent.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::Num;

    #[test]
    fn numbers_in_messages_are_short() {
        let cases = [
            (2.5e-5, "2.5e-05"),
            (2.5e-5 * (1.0 + f64::EPSILON), "2.5e-05"),
            (0.1 + 0.2, "0.3"),
            (1.0, "1"),
            (-3.0, "-3"),
            (100.0, "100"),
            (1e-5, "1e-05"),
            (1e-4, "0.0001"),
            (1.5e-6, "1.5e-06"),
            (123456789012345.0, "123456789012345"),
            (1e15, "1e+15"),
            (1e-300, "1e-300"),
            (f64::MAX, "1.797693135e+308"),
            (2.0 / 3.0, "0.6666666667"),
            (f64::NAN, "nan"),
            (f64::NEG_INFINITY, "-inf"),
        ];
        for (x, want) in cases {
            assert_eq!(Num(x).to_string(), want, "{x:e}");
        }
    }
}
