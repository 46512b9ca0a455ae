//! Native tests of the binding's pure conversions (the rest of the binding needs WebAssembly and
//! is tested by `wasm/tests`, `tests/node` and `tests/e2e`). They let `npm run mutants -- binding`
//! test these functions natively; each checks a unit conversion worked out by hand, with π/180
//! written here, not taken from the engine.

use crate::{api_combination, error_quantity};
use fiveaxis::schema::Quantity;

const DEG: f64 = std::f64::consts::PI / 180.0;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

/// Angular location errors and error motions are small angles, linear ones small lengths, and a
/// name outside the table (the tool-radius error `dR`) is a small length (ISO 230-1: `E_A..`,
/// `E_B..`, `E_C..` are rotations, `E_X..`, `E_Y..`, `E_Z..` displacements).
#[test]
fn error_names_have_the_quantity_of_their_iso_letter() {
    assert_eq!(error_quantity("E_A0B"), Quantity::SmallAngle);
    assert_eq!(error_quantity("E_C0C"), Quantity::SmallAngle);
    assert_eq!(error_quantity("E_X0B"), Quantity::SmallLength);
    assert_eq!(error_quantity("E_Y0C"), Quantity::SmallLength);
    assert_eq!(error_quantity("dR"), Quantity::SmallLength);
}

/// by 180/π and the value is turned into degrees (× 180/π).
#[test]
fn api_combination_keeps_the_value_of_the_combination_in_api_units() {
    // Length first: x = (0.01 mm, 0.02° = 0.02·π/180 rad).
    let (c, f) = api_combination([("E_X0B", 1.0), ("E_A0B", 250.0)]);
    assert!(close(f, 1.0), "{f}");
    assert_eq!(c.len(), 2);
    assert!(close(c[0], 1.0) && close(c[1], 250.0 * DEG), "{c:?}");
    let (y, x) = ([0.01, 0.02], [0.01, 0.02 * DEG]);
    let engine = 1.0 * x[0] + 250.0 * x[1];
    assert!(close(c[0] * y[0] + c[1] * y[1], engine * f));

    // Angle first: the value comes out in degrees.
    let (c, f) = api_combination([("E_B0C", 2.0), ("E_Y0C", -0.5), ("E_C0B", 3.0)]);
    assert!(close(f, 1.0 / DEG), "{f}");
    assert!(
        close(c[0], 2.0) && close(c[1], -0.5 / DEG) && close(c[2], 3.0),
        "{c:?}"
    );
    let (y, x) = ([0.03, 0.2, -0.01], [0.03 * DEG, 0.2, -0.01 * DEG]);
    let engine = 2.0 * x[0] - 0.5 * x[1] + 3.0 * x[2];
    assert!(close(c[0] * y[0] + c[1] * y[1] + c[2] * y[2], engine * f));
}

/// No terms: no coefficients, and a factor of one (nothing to convert).
#[test]
fn api_combination_of_nothing_is_empty() {
    let (c, f) = api_combination(std::iter::empty::<(&str, f64)>());
    assert!(c.is_empty());
    assert_eq!(f, 1.0);
}
