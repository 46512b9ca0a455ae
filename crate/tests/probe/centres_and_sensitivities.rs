//! The probing study's centres and their sensitivities (issue 31): the expected centre against
//! a closed form written out here, and every sensitivity of eq 2 against central finite
//! differences of the exact chain, on the three machines of the issue.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::probe::{Unknown, SPHERE_NAMES};
use nalgebra::Vector3;
use probe_common::{centre, machines, rot, study, with_errors};
use serde_json::json;

const SPHERE: [f64; 3] = [120.0, -40.0, 80.0];

#[test]
fn the_expected_centre_of_a_bc_table_is_the_sphere_turned_by_minus_c_then_minus_b() {
    // Table-table B/C, table surface at the B axis, tool tip at the spindle nose: the sphere at
    // s on the table is, in machine coordinates, at R_Y(−B)·R_Z(−C)·s (ISO 841: the table turns
    // against the command), and the linear axes are there.
    let s = study(json!({ "machine": probe_common::bc_table(),
        "sphere": { "x": SPHERE[0], "y": SPHERE[1], "height": SPHERE[2] } }));
    let sv = Vector3::from(SPHERE);
    for (c, b) in [(0.0, 0.0), (30.0, 0.0), (90.0, 45.0), (200.0, -60.0)] {
        let (c, b) = (f64::to_radians(c), f64::to_radians(b));
        let want = rot(1, -b) * rot(2, -c) * sv;
        let got = s.expected(c, b).unwrap();
        assert!((got - want).norm() < 1e-9, "C {c} B {b}: {got} vs {want}");
        // Without errors the probe measures what the control expects.
        assert!((s.measured(c, b).unwrap() - want).norm() < 1e-9);
    }
}

#[test]
fn the_expected_centre_of_an_ac_trunnion_includes_the_table_height_and_the_tool_length() {
    // A about X on the bed, C on it; table surface 100 mm above A, tool tip 100 mm below the
    // spindle nose: the sphere at (x, y, 100 + h) turned by R_X(−A)·R_Z(−C); Z reads 100 more.
    let s = study(json!({ "machine": probe_common::ac_trunnion(),
        "sphere": { "x": SPHERE[0], "y": SPHERE[1], "height": SPHERE[2] } }));
    for (c, a) in [(0.0, 0.0), (45.0, -30.0), (300.0, -90.0)] {
        let (c, a) = (f64::to_radians(c), f64::to_radians(a));
        let p = rot(0, -a) * rot(2, -c) * Vector3::new(SPHERE[0], SPHERE[1], 100.0 + SPHERE[2]);
        let want = p + Vector3::new(0.0, 0.0, 100.0);
        assert!((s.expected(c, a).unwrap() - want).norm() < 1e-9);
    }
}

#[test]
fn every_sensitivity_matches_central_differences_of_the_exact_chain() {
    let poses = [
        (0.0, 0.0),
        (30.0, 0.0),
        (135.0, -45.0),
        (250.0, 60.0),
        (10.0, -90.0),
    ];
    let mut checked = 0;
    for (name, machine) in machines() {
        let base = study(json!({ "machine": machine,
            "sphere": { "x": SPHERE[0], "y": SPHERE[1], "height": SPHERE[2] } }));
        for &(k, m) in &poses {
            let (k, m) = (f64::to_radians(k), f64::to_radians(m));
            if !base.reachable(k, m).unwrap() {
                continue;
            }
            let sens = base.sensitivities(k, m).unwrap();
            for (u, got) in base.unknowns.iter().zip(&sens) {
                let fd = match u {
                    Unknown::Error(d) => {
                        // Step: 1 µm or 1e-6 rad, in API units (mm, degrees).
                        let h_engine = if d.quantity.is_angle() { 1e-6 } else { 1e-3 };
                        let h_api = d.quantity.to_api(h_engine);
                        let plus = with_errors(&machine, json!({ d.name: h_api }));
                        let minus = with_errors(&machine, json!({ d.name: -h_api }));
                        (centre(&plus, SPHERE, k, m) - centre(&minus, SPHERE, k, m))
                            / (2.0 * h_engine)
                    }
                    Unknown::Sphere(i) => {
                        let h = 1e-3;
                        let mut sp = SPHERE;
                        let mut sm = SPHERE;
                        // The face frame of a vertical spindle is X, Y, Z.
                        sp[*i] += h;
                        sm[*i] -= h;
                        (centre(&machine, sp, k, m) - centre(&machine, sm, k, m)) / (2.0 * h)
                    }
                };
                // Per rad a lever of a few hundred mm: compare relative to the column's size.
                let tol = 1e-6 * (1.0 + fd.norm());
                checked += 1;
                assert!(
                    (got - fd).norm() < tol,
                    "{name}: {} at K {:.0}° M {:.0}°: {got} vs {fd}",
                    u.name(),
                    k.to_degrees(),
                    m.to_degrees()
                );
            }
        }
        assert!(SPHERE_NAMES
            .iter()
            .all(|n| base.names().iter().any(|m| m == n)));
    }
    // 3 machines × 12 errors + 3 sphere components at the reachable poses.
    assert!(checked >= 3 * 15 * 4, "{checked} columns checked");
}
