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

/// The checks and quoted texts at their documented edges (found by cargo-mutants, scope
/// `error`: the bounds and the length were reached by no test at their edges).
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_holds_both_its_ends_and_refuses_past_them_by_name() {
        assert_eq!(check_range("a.b", -2.0, -2.0, 3.0, "mm"), Ok(-2.0));
        assert_eq!(check_range("a.b", 3.0, -2.0, 3.0, "mm"), Ok(3.0));
        assert_eq!(check_range("a.b", 0.5, -2.0, 3.0, "mm"), Ok(0.5));
        for bad in [-2.0 - 1e-12, 3.0 + 1e-12, -1e9, 1e9] {
            let e = check_range("a.b", bad, -2.0, 3.0, "mm").unwrap_err();
            assert_eq!(e.field, "a.b");
            assert!(e.message.contains("between -2 and 3 mm"), "{e}");
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = check_range("rtol", bad, 0.0, 1.0, "").unwrap_err();
            assert!(e.message.contains("finite"), "{e}");
        }
    }

    #[test]
    fn positive_means_above_zero_up_to_the_maximum() {
        assert_eq!(check_positive("length", 1e-300, 10.0, "mm"), Ok(1e-300));
        assert_eq!(check_positive("length", 10.0, 10.0, "mm"), Ok(10.0));
        assert_eq!(check_positive("length", 4.0, 10.0, "mm"), Ok(4.0));
        for bad in [0.0, -0.0, -1.0, 10.0 + 1e-9, 1e6] {
            let e = check_positive("length", bad, 10.0, "mm").unwrap_err();
            assert_eq!(
                e.to_string(),
                format!("length: must be greater than 0 and at most 10 mm, got {bad}")
            );
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = check_positive("length", bad, 10.0, "mm").unwrap_err();
            assert!(
                e.message.starts_with("must be a finite number of mm"),
                "{e}"
            );
        }
    }

    #[test]
    fn a_count_holds_both_its_ends_and_refuses_past_them() {
        assert_eq!(check_count("n", 2, 2, 7), Ok(2));
        assert_eq!(check_count("n", 7, 2, 7), Ok(7));
        assert_eq!(check_count("n", 5, 2, 7), Ok(5));
        for bad in [0, 1, 8, usize::MAX] {
            let e = check_count("n", bad, 2, 7).unwrap_err();
            assert_eq!(
                e.to_string(),
                format!("n: must be a whole number between 2 and 7, got {bad}")
            );
        }
    }

    #[test]
    fn a_quote_keeps_forty_characters_and_cuts_a_longer_text_to_thirty_nine_and_an_ellipsis() {
        let forty = "é".repeat(40);
        assert_eq!(quote(&forty), format!("\"{forty}\""));
        let long = "x".repeat(41);
        assert_eq!(quote(&long), format!("\"{}\"…", "x".repeat(39)));
        // Characters, not bytes: 30 two-byte characters are under the limit.
        let short = "ü".repeat(30);
        assert_eq!(quote(&short), format!("\"{short}\""));
        assert_eq!(quote(""), "\"\"");
    }
}
