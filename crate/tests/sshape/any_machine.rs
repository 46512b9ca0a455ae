//! The S-shape part on machines other than Chanal et al.'s (an A/C trunnion table, an A/C fork
//! head, a B-head/C-table with a horizontal spindle): the tool path through each machine's inverse
//! kinematics reproduces eq 2's tool, and eq 14's first-order defects agree with the exact chain
//! (the tool pose with the errors at each measurement pose, minus the same at the reference
//! pose, along the normal).

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, Rng};
use fiveaxis::chain::Setup;
use fiveaxis::machine::Machine;
use fiveaxis::schema::{Inputs, Quantity};
use fiveaxis::sshape::machine::{DefectPoint, DefectReference, PathBranch};
use fiveaxis::sshape::part::Part;
use fiveaxis::sshape::study::{Design, SShapeModel, SShapeTool};
use nalgebra::Vector3;
use serde_json::json;

fn machines() -> Vec<Machine> {
    [
        json!({ "kind": "table-table", "type": "CAZ", "linear": "table-xy",
                "geometry": { "tableHeight": 80, "rotaryOffset": 15 } }),
        json!({ "kind": "head-head", "type": "CAZ",
                "geometry": { "pivotLength": 220, "toolLength": 90, "rotaryOffset": -10 } }),
        json!({ "kind": "head-table", "type": "BCX", "linear": "table-z",
                "geometry": { "tableHeight": 30, "pivotLength": 150 } }),
    ]
    .into_iter()
    .map(|v| Machine::from_value(&v, "machine").unwrap())
    .collect()
}

fn tool() -> SShapeTool {
    SShapeTool {
        r_tool: 10.0,
        l_tool: 35.0,
    }
}

#[test]
fn the_path_through_each_machines_inverse_kinematics_is_eq_2s_tool() {
    for m in machines() {
        for branch in [PathBranch::Paper, PathBranch::Continuous] {
            let model = SShapeModel {
                branch,
                reference: DefectReference::WorkOrigin,
                point: DefectPoint::Tip,
            };
            let d = Design::new(&m, &tool(), &model).unwrap();
            let part = Part::standard().unwrap();
            for pp in &d.poses {
                let t = d.path.at(part.surface(pp.point.surface), pp.point.u);
                let pose =
                    d.on.model
                        .nominal()
                        .tool_pose(&pp.pose.q, false, &Setup::None)
                        .unwrap();
                assert!(
                    (pose.tip - d.on.frame * t.tip).norm() < 1e-9,
                    "{}",
                    m.kind.value()
                );
                assert!((pose.axis - d.on.frame * t.axis).norm() < 1e-12);
            }
        }
    }
}

#[test]
fn eq_14_is_the_first_order_of_the_exact_chain_on_every_machine() {
    let mut rng = Rng::new(5);
    for m in machines() {
        for reference in [DefectReference::WorkOrigin, DefectReference::AxesZero] {
            let model = SShapeModel {
                branch: PathBranch::Paper,
                reference,
                point: DefectPoint::Contact,
            };
            let d = Design::new(&m, &tool(), &model).unwrap();
            // Small random values of every error of the machine: 2 µm, 2 µrad.
            let mut errors = m.errors.clone();
            for def in d.errors() {
                let scale = if def.quantity == Quantity::SmallAngle {
                    2e-6
                } else {
                    2e-3
                };
                errors.set(def.name, scale * rng.range(-1.0, 1.0)).unwrap();
            }
            let predicted = d.simulate(&errors, 0.0);
            let mut actual = m.clone();
            actual.errors = errors;
            let chain = actual.build().unwrap().chain;
            let nominal = d.on.model.nominal();
            let q_ref = d.on.reference_positions(reference).unwrap();
            let shift = |q: &[f64], h: f64| -> Vector3<f64> {
                let a = chain.tool_pose(q, true, &Setup::None).unwrap();
                let b = nominal.tool_pose(q, false, &Setup::None).unwrap();
                (a.tip + a.axis * h) - (b.tip + b.axis * h)
            };
            let back = d.on.frame.transpose();
            for (pp, p) in d.poses.iter().zip(&predicted) {
                // The point's height on the tool, from the nominal chain's tool at the pose (not
                // the design's own `height`, so that a wrong sign there shows).
                let t = nominal.tool_pose(&pp.pose.q, false, &Setup::None).unwrap();
                let h = (Vector3::from(pp.point.point) - back * t.tip).dot(&(back * t.axis));
                let moved = back * (shift(&pp.pose.q, h) - shift(&q_ref, 0.0));
                let exact = moved.dot(&Vector3::from(pp.point.normal));
                // Second order: L·ε² with L below 1 m and ε = 2e-6: 4 nm.
                close(
                    *p,
                    exact,
                    5e-6,
                    &format!("{} {:?}", m.kind.value(), pp.point.label()),
                );
            }
        }
    }
}

#[test]
fn identification_recovers_what_the_part_can_separate_on_a_trunnion() {
    // Simulated part on the trunnion, errors of A and C, 1 µm noise: every error the fit finds
    // identifiable on its own comes back within 4 standard errors, and the rest are grouped.
    let m = machines().remove(0);
    let d = Design::new(
        &m,
        &tool(),
        &SShapeModel {
            branch: PathBranch::Paper,
            reference: DefectReference::WorkOrigin,
            point: DefectPoint::Tip,
        },
    )
    .unwrap();
    let mut truth = m.errors.clone();
    for (name, v) in [
        ("E_Y0A", 0.02),
        ("E_Z0A", -0.015),
        ("E_X0C", 0.01),
        ("E_B0A", 2e-4),
        ("E_A0C", -1e-4),
    ] {
        truth.set(name, v).unwrap();
    }
    let clean = d.simulate(&truth, 0.0);
    let mut rng = Rng::new(12);
    let noisy: Vec<f64> = clean
        .iter()
        .map(|v| v + 0.001 * (rng.unit() - 0.5) * 12f64.sqrt())
        .collect();
    let f = d.identify(&noisy, None, false, 0.01).unwrap();
    assert_eq!(f.estimates.len(), d.errors().len());
    let mut separate = 0;
    for e in &f.estimates {
        match (e.value, e.std_error) {
            (Some(v), Some(se)) => {
                separate += 1;
                let t = truth.get(&e.name);
                assert!(
                    (v - t).abs() < 4.0 * se + 1e-12,
                    "{}: {v} ± {se} vs {t}",
                    e.name
                );
            }
            _ => assert!(
                e.group.is_some(),
                "{} neither identified nor grouped",
                e.name
            ),
        }
    }
    assert_eq!(
        separate + f.groups.iter().map(|g| g.members.len()).sum::<usize>(),
        f.estimates.len()
    );
    assert!(
        f.rank < f.estimates.len(),
        "15 errors cannot all be separated by one part"
    );
}
