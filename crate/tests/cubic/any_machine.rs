//! The cubic-machining test on machines other than Li et al.'s: an A/C trunnion table and an
//! A/C fork head, against first-order heights derived by hand (below), finite differences of
//! the exact chain, the zones' tool vectors, and the travel.
//!
//! **Table axes, with the workpiece set at zero** (rotary axes intersecting at the bed origin,
//! the table turning by `Q = R_X(−a)·R_Z(−c)` for the commands a, c, ISO 841). An error
//! `(ω, t)` of the bed axis A displaces the table by `δ(P) = ω×P + t` before A's motion, so a
//! workpiece point that sits at `P0` (bed, all axes zero) is at `Q·P0 + δ(Q·P0)`; the set-up at
//! zero removes `Q·δ(P0)`. The tool cuts the bed point `Q·P0`, i.e. the workpiece point moved by
//! `d = −Qᵀ(δ(Q·P0) − Q·δ(P0)) = (ω − Qᵀω)×P0 + (t − Qᵀt)`. An error of C (on A) is turned by
//! A first, `D' = Q_A·D_C·Q_Aᵀ`, which gives the same with `Q_C = R_Z(−c)` in place of `Q`.
//! The zone's height changes by `n·d` at the face point (the ball radius cancels).
//!
//! **Head axes** (a fork head, C on the ram, A in the fork, the tool tip `L` = pivot + tool from
//! the axes' common point, tool direction `V = R_Z(c)·R_X(a)·e_z`). An error of C moves the ball
//! centre `(r − L)·V` from the pivot by `ω×((r − L)V) + t`; an error of A acts after C's
//! motion: `(R_Z(c)ω)×((r − L)V) + R_Z(c)t`. The workpiece does not turn, so the height changes
//! by `n·` that.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use fiveaxis::chain::Setup;
use fiveaxis::cubic::{analyze, CubicInput, CubicReference, Options, ZONES};
use fiveaxis::geometry::{rotation, Axis};
use fiveaxis::machine::errors::ErrorDef;
use fiveaxis::machine::Machine;
use fiveaxis::schema::{Inputs, Quantity};
use nalgebra::{Matrix3, Vector3};
use serde_json::{json, Value};

fn input(v: Value) -> CubicInput {
    CubicInput::read(&v).unwrap()
}

/// `(ω, t)` of a unit error: 1 rad about, or 1 mm along, its component.
fn unit_error(def: &ErrorDef) -> (Vector3<f64>, Vector3<f64>) {
    let e = Vector3::ith(def.component % 3, 1.0);
    if def.component < 3 {
        (Vector3::zeros(), e)
    } else {
        (e, Vector3::zeros())
    }
}

const TRUNNION: &str = r#"{ "kind": "table-table", "type": "CAZ", "linear": "table-xy",
    "geometry": { "tableHeight": 65, "toolLength": 120 },
    "rotary": { "mFrom": -120, "mTo": 30 } }"#;
const FORK: &str = r#"{ "kind": "head-head", "type": "CAZ", "linear": "spindle-xyz",
    "geometry": { "pivotLength": 180, "toolLength": 95, "tableHeight": 20 },
    "rotary": { "kFrom": -200, "kTo": 200, "mFrom": -100, "mTo": 100 } }"#;

fn machine(text: &str) -> Machine {
    Machine::from_value(&serde_json::from_str(text).unwrap(), "machine").unwrap()
}

/// Hand-derived first-order height sensitivity (module docs), per mm or per rad.
#[allow(clippy::too_many_arguments)]
fn hand(m: &Machine, def: &ErrorDef, a: f64, c: f64, x: f64, y: f64, face: f64, r: f64) -> f64 {
    let n = Vector3::z();
    let (w, t) = unit_error(def);
    let table = |q: Matrix3<f64>| {
        let p0 = Vector3::new(x, y, face);
        ((w - q.transpose() * w).cross(&p0) + (t - q.transpose() * t)).z
    };
    match (m.kind.value(), def.axis) {
        ("table-table", 'A') => table(rotation(Axis::X, -a) * rotation(Axis::Z, -c)),
        ("table-table", 'C') => table(rotation(Axis::Z, -c)),
        ("head-head", axis) => {
            let qc = rotation(Axis::Z, c);
            let v = qc * rotation(Axis::X, a) * n;
            let l = m.geometry.pivot_length + m.geometry.tool_length;
            let lever = v * (r - l);
            let (w, t) = if axis == 'A' {
                (qc * w, qc * t)
            } else {
                (w, t)
            };
            n.dot(&(w.cross(&lever) + t))
        }
        _ => f64::NAN,
    }
}

#[test]
fn zones_are_cut_with_table_1s_tool_vectors_within_the_travel() {
    for text in [TRUNNION, FORK] {
        let m = machine(text);
        let a = analyze(&m, &input(json!({})).setup, &Options::default()).unwrap();
        let model = m.build().unwrap();
        for (z, def) in a.zones.iter().zip(ZONES) {
            // FK of the zone's rotary pose gives Table 1's vector (u, v, n = X, Y, Z here).
            let q = model.positions(z.rotary[0], z.rotary[1]);
            let axis = model
                .nominal()
                .tool_pose(&q, false, &Setup::None)
                .unwrap()
                .axis;
            assert!(
                (axis - Vector3::from(def.tool)).norm() < 1e-12,
                "{}",
                def.name
            );
            let [(k0, k1), (m0, m1)] = model.travel();
            assert!(z.rotary[0] >= k0 - 1e-9 && z.rotary[0] <= k1 + 1e-9);
            assert!(z.rotary[1] >= m0 - 1e-9 && z.rotary[1] <= m1 + 1e-9);
        }
        // On the trunnion (A up to +30° only) II-1 is cut with A = 30°, C = 90°:
        // R_Z(90°)·R_X(30°)·e_z = (sin 90° sin 30°, −cos 90° sin 30°, cos 30°).
        if m.kind.value() == "table-table" {
            close(a.zones[1].rotary[1].to_degrees(), 30.0, 1e-9, "A of II-1");
            close(a.zones[1].rotary[0].to_degrees(), 90.0, 1e-9, "C of II-1");
        }
    }
}

#[test]
fn first_order_heights_match_the_hand_derived_forms_on_a_trunnion_and_a_fork_head() {
    for text in [TRUNNION, FORK] {
        let m = machine(text);
        let piece = input(json!({ "setup": { "workpieceHeight": 40 } })).setup;
        let a = analyze(&m, &piece, &Options::default()).unwrap();
        let face = m.geometry.table_height + piece.workpiece_height;
        let mut checked = 0;
        for (z, row) in a.zones.iter().zip(&a.sensitivity) {
            let [c, am] = z.rotary;
            for (def, k) in a.errors.iter().zip(row) {
                if !matches!(def.axis, 'A' | 'C') {
                    continue;
                }
                let expect = hand(
                    &m,
                    def,
                    am,
                    c,
                    z.centre[0],
                    z.centre[1],
                    face,
                    piece.tool_radius,
                );
                close(
                    k.height,
                    expect,
                    1e-9,
                    &format!("{} {} {}", m.kind.value(), z.zone.name, def.name),
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 9 * 12);
    }
}

#[test]
fn sensitivities_are_finite_differences_of_the_exact_chain() {
    for text in [TRUNNION, FORK] {
        let base = machine(text);
        for transform in [true, false] {
            for reference in [CubicReference::Workpiece, CubicReference::ZoneIPlane] {
                let o = Options {
                    transform,
                    reference,
                };
                let piece = input(json!({})).setup;
                let a = analyze(&base, &piece, &o).unwrap();
                for (e, def) in a.errors.iter().enumerate() {
                    let h = if def.quantity == Quantity::SmallAngle {
                        1e-6
                    } else {
                        1e-4
                    };
                    let run = |v: f64| {
                        let mut m = base.clone();
                        m.errors.set(def.name, v).unwrap();
                        analyze(&m, &piece, &o).unwrap()
                    };
                    let (p, q) = (run(h), run(-h));
                    for z in 0..9 {
                        let fd = (p.zones[z].exact.height - q.zones[z].exact.height) / (2.0 * h);
                        let fs = (p.zones[z].exact.slope_x - q.zones[z].exact.slope_x) / (2.0 * h);
                        let what = format!("{text:.20} {} zone {z} {o:?}", def.name);
                        close(a.sensitivity[z][e].height, fd, 1e-6, &what);
                        close(a.sensitivity[z][e].slope_x, fs, 1e-7, &what);
                    }
                }
            }
        }
    }
}

#[test]
fn the_test_says_which_errors_it_cannot_see() {
    // Hand forms: on the trunnion with the workpiece set at zero, A's axial offset (E_X0A:
    // Qᵀe_x = R_Z(c)e_x has no z), every position error of C (Q_Cᵀt keeps t's z), C's zero
    // position (ω = e_z = Q_Cᵀω) and A's tilt about Z (the z of (ω − Qᵀω)×P0 is
    // −sin a·(x cos c + y sin c), zero where each zone leans towards the centre) leave every
    // height alone; every other error of A and C moves some zone.
    let m = machine(TRUNNION);
    let a = analyze(&m, &input(json!({})).setup, &Options::default()).unwrap();
    let invisible: Vec<&str> = a
        .errors
        .iter()
        .filter(|d| matches!(d.axis, 'A' | 'C'))
        .filter(|d| {
            a.zones.iter().all(|z| {
                hand(
                    &m,
                    d,
                    z.rotary[1],
                    z.rotary[0],
                    z.centre[0],
                    z.centre[1],
                    65.0 + 50.0,
                    3.0,
                )
                .abs()
                    < 1e-12
            })
        })
        .map(|d| d.name)
        .collect();
    assert_eq!(
        invisible,
        ["E_X0A", "E_C0A", "E_X0C", "E_Y0C", "E_Z0C", "E_C0C"]
    );
    for name in invisible {
        assert!(a.visibility.invisible.contains(&name), "{name}");
    }
    // The report agrees with the sensitivity table for every error, squareness errors included.
    for (e, d) in a.errors.iter().enumerate() {
        let seen = a.sensitivity.iter().any(|row| row[e].height.abs() > 1e-9);
        assert_eq!(
            !seen,
            a.visibility.invisible.contains(&d.name),
            "{}",
            d.name
        );
    }
    // The rank is at most the number of visible errors and at most 8 (9 zones, ZONE I's
    // height fixed at zero by the set-up on this Group I machine).
    assert!(a.visibility.rank <= 8);
}

#[test]
fn a_zone_beyond_the_travel_is_reported_not_computed() {
    let mut m = machine(TRUNNION);
    m.rotary.m_from = 0.0;
    m.rotary.m_to = 20f64.to_radians();
    let e = analyze(&m, &input(json!({})).setup, &Options::default()).unwrap_err();
    assert_eq!(e.field, "machine");
    assert!(
        e.message.starts_with("ZONE II-1: outside the travel"),
        "{e}"
    );
    assert!(
        e.message.contains("A = 30°") && e.message.contains("A from 0° to 20°"),
        "{e}"
    );
}

#[test]
fn every_error_of_a_head_head_machine_acts() {
    // Each error of the fork head alone at 0.01 mm / 0.01°: the exact heights follow Σ k·ε
    // within the second-order remainder L·ε² (L = 275 mm: 8 nm for 0.01°).
    let base = machine(FORK);
    let piece = input(json!({})).setup;
    for def in base.error_defs() {
        let mut m = base.clone();
        let v = if def.quantity == Quantity::SmallAngle {
            0.01f64.to_radians()
        } else {
            0.01
        };
        m.errors.set(def.name, v).unwrap();
        let a = analyze(&m, &piece, &Options::default()).unwrap();
        let l = m.geometry.pivot_length + m.geometry.tool_length + 100.0;
        let tol = if def.quantity == Quantity::SmallAngle {
            l * v * v
        } else {
            1e-9
        };
        let mut moved = false;
        for z in &a.zones {
            close(z.exact.height, z.linear.height, tol, def.name);
            moved |= z.exact.height.abs() > 10.0 * tol;
        }
        assert_eq!(
            moved,
            !a.visibility.invisible.contains(&def.name),
            "{}",
            def.name
        );
    }
}
