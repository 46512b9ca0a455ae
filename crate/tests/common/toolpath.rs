//! Helpers of the toolpath tests: tool axes by tilt and azimuth, the machine NC blocks are read
//! for, and parser errors with their line and column.

use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{parse, Format};
use nalgebra::Vector3;

/// A C-A fork head (head-head CAZ), ISO 841 senses: NC letters C (K) and A (M).
#[allow(clippy::unwrap_used)]
pub fn caz_head() -> Machine {
    Machine::from_value(
        &serde_json::json!({ "kind": "head-head", "type": "CAZ" }),
        "machine",
    )
    .unwrap()
}

/// The message of the error parsing `text` gives (on the field `toolpath`).
#[track_caller]
pub fn error(text: &str, format: Format, machine: Option<&Machine>) -> String {
    match parse(text, format, machine) {
        Ok(p) => panic!("{text:?} parsed as {} points", p.len()),
        Err(e) => {
            assert_eq!(e.field, "toolpath", "{e}");
            e.message
        }
    }
}

/// Asserts the message starts with `line L, column C:` and contains `part`.
#[track_caller]
pub fn at(message: &str, line: u32, column: usize, part: &str) {
    let head = format!("line {line}, column {column}: ");
    assert!(
        message.starts_with(&head),
        "expected {head:?} at the start of {message:?}"
    );
    assert!(message.contains(part), "expected {part:?} in {message:?}");
}

/// Tool axis with tilt `t` from +Z and azimuth `c` (degrees).
pub fn tilted(t: f64, c: f64) -> Vector3<f64> {
    let (t, c) = (t.to_radians(), c.to_radians());
    Vector3::new(t.sin() * c.cos(), t.sin() * c.sin(), t.cos())
}
