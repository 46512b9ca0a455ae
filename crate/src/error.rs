//! The engine's one error type: every invalid input becomes an [`Error`] that names the
//! offending field and says what was expected, so that the page can show it next to the field.

use std::fmt;

/// An input the engine cannot compute with.
///
/// `field` is a dotted path into the input (`"start.k"`, `"length"`, `"errors.alphaBY"`);
/// `message` says what was wrong in words a user understands. `Display` renders
/// `"field: message"`, which is also the text of the JavaScript `Error` the binding throws.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error {
    /// Dotted path of the offending input field (empty when the error is not about one field).
    pub field: String,
    /// What was wrong and what is expected.
    pub message: String,
}

impl Error {
    /// An error about the input field `field`.
    pub fn field(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.field, self.message)
        }
    }
}

impl std::error::Error for Error {}

/// A text the user gave, quoted for a message: at most 40 characters (a longer one is cut with
/// an ellipsis), so that a pasted file is not repeated whole in the message.
pub fn quote(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() > MAX {
        let head: String = text.chars().take(MAX - 1).collect();
        format!("{head:?}…")
    } else {
        format!("{text:?}")
    }
}

/// The engine's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is a finite number in `[min, max]`; `unit` is used in the message only.
pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
    if !value.is_finite() {
        return Err(Error::field(
            field,
            format!("must be a finite number of {unit}, got {value}"),
        ));
    }
    if value < min || value > max {
        return Err(Error::field(
            field,
            format!("must be between {min} and {max} {unit}, got {value}"),
        ));
    }
    Ok(value)
}

/// Checks that `value` is a finite number strictly greater than zero and at most `max`.
pub fn check_positive(field: &str, value: f64, max: f64, unit: &str) -> Result<f64> {
    if !value.is_finite() {
        return Err(Error::field(
            field,
            format!("must be a finite number of {unit}, got {value}"),
        ));
    }
    if value <= 0.0 || value > max {
        return Err(Error::field(
            field,
            format!("must be greater than 0 and at most {max} {unit}, got {value}"),
        ));
    }
    Ok(value)
}

/// Checks that a sample count lies in `[min, max]`.
pub fn check_count(field: &str, value: usize, min: usize, max: usize) -> Result<usize> {
    if value < min || value > max {
        return Err(Error::field(
            field,
            format!("must be a whole number between {min} and {max}, got {value}"),
        ));
    }
    Ok(value)
}
