//! The units a measuring program writes in a CSV header (`fiveaxis::csv::unit_factor`), each to
//! the API unit of its kind (mm for a length, degrees for an angle), checked against the
//! definitions: 1 in = 25.4 mm exactly, 1 rad = 180/π°, 1″ = 1/3600°, a slope of 1 µm/m is
//! 10⁻⁶ rad. A unit of the other kind is `None` (a length is not an angle). The unit in a header
//! cell is the text in its last brackets (`header_unit`).
// Found by cargo-mutants: deleting any arm of `unit_factor` but mm and µm, or turning a `/` of
// the angle factors into `*` or `%`, changed no outcome of the tests before this file.

use fiveaxis::csv::{header_unit, unit_factor};
use std::f64::consts::PI;

fn close(a: Option<f64>, b: f64, what: &str) {
    let a = a.unwrap_or_else(|| panic!("{what}: not read"));
    assert!((a - b).abs() <= 1e-15 * b.abs(), "{what}: {a} vs {b}");
}

#[test]
fn every_length_unit_is_its_size_in_millimetres_and_no_angle() {
    for (unit, mm) in [
        ("mm", 1.0),
        ("µm", 1e-3),
        ("μm", 1e-3), // the Greek mu, as some programs write it
        ("um", 1e-3),
        ("micron", 1e-3),
        ("microns", 1e-3),
        ("nm", 1e-6),
        ("m", 1e3),
        ("in", 25.4),
        ("inch", 25.4),
        (" MM ", 1.0),
    ] {
        close(unit_factor(unit, false), mm, unit);
        assert_eq!(unit_factor(unit, true), None, "{unit} is not an angle");
    }
}

#[test]
fn every_angle_unit_is_its_size_in_degrees_and_no_length() {
    let rad = 180.0 / PI;
    for (unit, deg) in [
        ("deg", 1.0),
        ("°", 1.0),
        ("degree", 1.0),
        ("degrees", 1.0),
        ("rad", rad),
        ("mrad", 1e-3 * rad),
        ("µrad", 1e-6 * rad),
        ("urad", 1e-6 * rad),
        ("arcsec", 1.0 / 3600.0),
        ("″", 1.0 / 3600.0),
        ("\"", 1.0 / 3600.0),
        ("sec", 1.0 / 3600.0),
        ("as", 1.0 / 3600.0),
        ("µm/m", 1e-6 * rad),
        ("um/m", 1e-6 * rad),
    ] {
        close(unit_factor(unit, true), deg, unit);
        assert_eq!(unit_factor(unit, false), None, "{unit} is not a length");
    }
    assert_eq!(unit_factor("furlong", false), None);
    assert_eq!(unit_factor("furlong", true), None);
}

#[test]
fn the_unit_of_a_header_cell_is_in_its_brackets() {
    assert_eq!(header_unit("deviation (µm)"), "µm");
    assert_eq!(header_unit("X [mm]"), "mm");
    assert_eq!(header_unit("mm"), "mm");
    // A closing bracket before the opening one is no unit.
    assert_eq!(header_unit(")x("), ")x(");
}
