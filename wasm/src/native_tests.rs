//! Native tests of the binding's pure conversions (the rest of the binding needs WebAssembly and
//! is tested by `wasm/tests`, `tests/node` and `tests/e2e`). They let `npm run mutants -- binding`
//! test these functions natively; each checks a unit conversion worked out by hand, with π/180
//! written here, not taken from the engine.

use crate::degrees_of;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

/// 180/π degrees is one radian, π/2 is 90°, and the order and length are kept.
#[test]
fn degrees_of_converts_every_value_in_order() {
    let out = degrees_of(&[0.0, 1.0, std::f64::consts::FRAC_PI_2, -std::f64::consts::PI]);
    let want = [0.0, 180.0 / std::f64::consts::PI, 90.0, -180.0];
    assert_eq!(out.len(), want.len());
    for (a, b) in out.iter().zip(want) {
        assert!(close(*a, b), "{a} vs {b}");
    }
}
