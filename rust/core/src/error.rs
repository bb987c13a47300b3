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
