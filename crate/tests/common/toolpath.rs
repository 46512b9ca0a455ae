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

/// Reads `text` with `options`: the points and the report (a failure stops the test).
#[track_caller]
#[allow(clippy::unwrap_used)]
pub fn read_with(
    text: &str,
    format: Format,
    machine: Option<&Machine>,
    options: fiveaxis::toolpath::read::ReadOptions,
) -> (
    Vec<fiveaxis::toolpath::read::Point>,
    fiveaxis::toolpath::read::Report,
) {
    match fiveaxis::toolpath::read::read(text, format, machine, options) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    }
}

/// [`read_with`] the default options.
#[track_caller]
pub fn read_all(
    text: &str,
    format: Format,
    machine: Option<&Machine>,
) -> (
    Vec<fiveaxis::toolpath::read::Point>,
    fiveaxis::toolpath::read::Report,
) {
    read_with(text, format, machine, Default::default())
}

/// Asserts `|a − b| ≤ tol`.
#[track_caller]
pub fn close_vec(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64, what: &str) {
    assert!(
        (a - b).norm() <= tol,
        "{what}: {a:?} vs {b:?} (diff {:e})",
        (a - b).norm()
    );
}

/// The tool axis of a C/A machine (K = C about Z, M = A about X, spindle along Z), ISO 841
/// senses: `V = R_Z(c)·R_X(a)·e_Z = (sin a sin c, −sin a cos c, cos a)`.
pub fn caz(c_deg: f64, a_deg: f64) -> Vector3<f64> {
    let (c, a) = (c_deg.to_radians(), a_deg.to_radians());
    Vector3::new(a.sin() * c.sin(), -a.sin() * c.cos(), a.cos())
}

/// The fewest chords of an arc of radius `r` over `sweep` radians within `tol`: the sagitta of a
/// chord over `φ` is `r·(1 − cos(φ/2))`, so `φ ≤ 2·acos(1 − tol/r)`.
pub fn chords(r: f64, sweep: f64, tol: f64) -> usize {
    (sweep / (2.0 * (1.0 - tol / r).acos())).ceil() as usize
}

/// The note of `report` whose text contains `part`, with its line (a failure when none).
#[track_caller]
pub fn note<'a>(
    report: &'a fiveaxis::toolpath::read::Report,
    part: &str,
) -> &'a fiveaxis::toolpath::read::Note {
    report
        .notes
        .iter()
        .find(|n| n.text.contains(part))
        .unwrap_or_else(|| panic!("no note with {part:?} in {:#?}", report.notes))
}

/// The count of the skipped kind whose name contains `part` (0 when none).
pub fn skipped(report: &fiveaxis::toolpath::read::Report, part: &str) -> u32 {
    report
        .skipped
        .iter()
        .filter(|s| s.what.contains(part))
        .map(|s| s.count)
        .sum()
}

/// A Heidenhain conversational program of `blocks` between `BEGIN PGM T MM` (block 0) and
/// `END PGM T MM`, numbered from 1: block `n` is the file's line `n + 1`.
pub fn heidenhain_program(blocks: &[&str]) -> String {
    let mut s = String::from("0 BEGIN PGM T MM\n");
    for (i, b) in blocks.iter().enumerate() {
        s.push_str(&format!("{} {b}\n", i + 1));
    }
    s.push_str(&format!("{} END PGM T MM\n", blocks.len() + 1));
    s
}
