//! Eq 14 (Chanal et al. 2022) checked point by point against a second method: the exact
//! kinematic chain (`fiveaxis::chain`) with the machine's errors set by name through
//! `Machine::build`, at each measurement point's pose.
//!
//! Nothing here reuses what eq 14 computes: the contact height is recomputed from the nominal
//! chain's tool at the pose (`(P − tip)·axis`), the reference pose is checked to put the nominal
//! tool tip at the workpiece origin, the normal is the measurement point's own, and the errors
//! reach the chain through `Machine::build` (not through the eq 14 columns or
//! `Design::contributions`). A swapped error name, a flipped normal or a flipped contact-height
//! term fails here by far more than the second-order remainder allowed for.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::chanal::{self, PAPER_L0};
use fiveaxis::chain::Setup;
use fiveaxis::machine::Machine;
use fiveaxis::schema::{Inputs, Quantity};
use fiveaxis::sshape::machine::{DefectPoint, DefectReference, PathBranch};
use fiveaxis::sshape::study::{Design, SShapeModel, SShapeTool};
use nalgebra::{Matrix3, Vector3};
use serde_json::json;

/// Chanal et al.'s machine (the page's preset) and two other kinds.
fn machines() -> Vec<(&'static str, Machine)> {
    vec![
        ("Chanal et al.", chanal::machine(PAPER_L0)),
        (
            "A/C trunnion",
            Machine::from_value(
                &common::machine_preset("A/C trunnion table, vertical spindle"),
                "machine",
            )
            .unwrap(),
        ),
        (
            "A/C fork head",
            Machine::from_value(
                &json!({ "kind": "head-head", "type": "CAZ",
                         "geometry": { "pivotLength": 220, "toolLength": 90 } }),
                "machine",
            )
            .unwrap(),
        ),
    ]
}

fn tool() -> SShapeTool {
    SShapeTool {
        r_tool: 10.0,
        l_tool: 35.0,
    }
}

/// Every model option.
fn models() -> Vec<SShapeModel> {
    let mut out = Vec::new();
    for reference in [DefectReference::WorkOrigin, DefectReference::AxesZero] {
        for point in [DefectPoint::Tip, DefectPoint::Contact] {
            out.push(SShapeModel {
                branch: PathBranch::Paper,
                reference,
                point,
            });
        }
    }
    out
}

/// The exact deviation along the outward normal at every point of `d` when the machine `m`
/// has the errors `m.errors`: the tool point (tip, or the tool-axis point at the measured
/// point's height) of the erroneous chain minus that of the nominal chain at the point's pose,
/// minus the tip's shift at the reference pose (where the work offset was set with the tip),
/// in the part's frame, dotted with the point's normal.
fn exact_defects(m: &Machine, d: &Design, model: &SShapeModel) -> Vec<f64> {
    let built = m.build().unwrap();
    let nominal = built.nominal();
    let chain = &built.chain;
    let [u, v, n] = m.face_frame();
    let frame = Matrix3::from_columns(&[u, v, n]);
    let back = frame.transpose();
    // The reference pose, found here: rotary axes at zero; for the work origin the linear axes
    // that put the nominal tip at the origin (checked).
    let zero = vec![0.0; chain.len()];
    let q_ref = match model.reference {
        DefectReference::AxesZero => zero,
        DefectReference::WorkOrigin => {
            let q = nominal.solve_linear(&Vector3::zeros(), &zero).unwrap();
            let t = nominal.tool_pose(&q, false, &Setup::None).unwrap();
            assert!(t.tip.norm() < 1e-9, "the reference pose puts the tip at 0");
            q
        }
    };
    let shift = |q: &[f64], h: f64| -> Vector3<f64> {
        let a = chain.tool_pose(q, true, &Setup::None).unwrap();
        let b = nominal.tool_pose(q, false, &Setup::None).unwrap();
        back * ((a.tip + a.axis * h) - (b.tip + b.axis * h))
    };
    let reference = shift(&q_ref, 0.0);
    d.poses
        .iter()
        .map(|pp| {
            let q = &pp.pose.q;
            let h = match model.point {
                DefectPoint::Tip => 0.0,
                DefectPoint::Contact => {
                    // The point's height along the nominal tool, from the nominal chain.
                    let t = nominal.tool_pose(q, false, &Setup::None).unwrap();
                    let (tip, axis) = (back * t.tip, back * t.axis);
                    let h = (Vector3::from(pp.point.point) - tip).dot(&axis);
                    // On the flank between the tip and the section at lTool (eq 2).
                    assert!(h > 0.0 && h <= 35.0 + 1e-9, "height {h}");
                    h
                }
            };
            (shift(q, h) - reference).dot(&Vector3::from(pp.point.normal))
        })
        .collect()
}

/// A value of `scale` in the error's engine unit: 1 µm, or 5 µrad (about 1″).
fn small(q: Quantity) -> f64 {
    if q == Quantity::SmallAngle {
        5e-6
    } else {
        1e-3
    }
}

#[test]
fn each_error_alone_eq_14_is_the_exact_chain_at_every_point() {
    for (name, m) in machines() {
        for model in models() {
            let d = Design::new(&m, &tool(), &model).unwrap();
            for (j, def) in d.errors().iter().enumerate() {
                let eps = small(def.quantity);
                let mut with = m.clone();
                with.errors.set(def.name, eps).unwrap();
                let exact = exact_defects(&with, &d, &model);
                let simulated = d.simulate(&with.errors, 0.0);
                // Second-order remainder: a rotation ε moves a point at distance r by
                // r·ε²/2 off its first-order path, r < 1 m on these machines and the part:
                // 1000 mm · (5e-6)² / 2 = 1.25e-8 mm. A translation is exactly linear. The
                // tolerance, 1e-7 mm, is far below the smallest effect a wrong sign, name or
                // unit would make (h·ε ≥ 5 mm · 5e-6 = 2.5e-5 mm for the contact term).
                for (k, pp) in d.poses.iter().enumerate() {
                    let column = d.rows[k][j] * eps;
                    let label = format!("{name} {model:?} {} at {}", def.name, pp.point.label());
                    common::close(column, exact[k], 1e-7, &format!("{label}: column"));
                    common::close(simulated[k], exact[k], 1e-7, &format!("{label}: simulate"));
                }
            }
        }
    }
}

#[test]
fn all_errors_together_eq_14_is_the_exact_chain_at_every_point() {
    let mut rng = common::Rng::new(1415);
    for (name, m) in machines() {
        for model in models() {
            let d = Design::new(&m, &tool(), &model).unwrap();
            let mut with = m.clone();
            let mut sum_angles = 0.0;
            for def in d.errors() {
                let v = small(def.quantity) * rng.range(-1.0, 1.0);
                if def.quantity == Quantity::SmallAngle {
                    sum_angles += v.abs();
                }
                with.errors.set(def.name, v).unwrap();
            }
            let exact = exact_defects(&with, &d, &model);
            let simulated = d.simulate(&with.errors, 0.0);
            // Cross terms: every lever arm below 1 m, rotations adding to at most Σ|ε|:
            // 1000 mm · (Σ|ε|)², plus the translations turned by the rotations
            // (Σ|δ| ≤ 15 µm times Σ|ε|).
            let tol = 1000.0 * sum_angles * sum_angles + 0.015 * sum_angles + 1e-9;
            for (k, pp) in d.poses.iter().enumerate() {
                common::close(
                    simulated[k],
                    exact[k],
                    tol,
                    &format!("{name} {model:?} at {}", pp.point.label()),
                );
            }
        }
    }
}

#[test]
fn the_poses_are_the_inverse_kinematics_of_eq_2s_tool() {
    // The poses the comparison above uses: the nominal chain at each pose holds eq 2's tool
    // (tip and axis, in the part frame laid on the table) at the point's u, with B ≥ 0 on
    // Chanal et al.'s machine (their tan B ≥ 0, the "paper" branch).
    for (name, m) in machines() {
        let model = &models()[0];
        let d = Design::new(&m, &tool(), model).unwrap();
        let nominal = d.on.model.nominal();
        let [u, v, n] = m.face_frame();
        let frame = Matrix3::from_columns(&[u, v, n]);
        for pp in &d.poses {
            let t = d.path.at(d.part.surface(pp.point.surface), pp.point.u);
            let pose = nominal.tool_pose(&pp.pose.q, false, &Setup::None).unwrap();
            assert!((pose.tip - frame * t.tip).norm() < 1e-9, "{name}");
            assert!((pose.axis - frame * t.axis).norm() < 1e-12, "{name}");
            if name == "Chanal et al." {
                let b = pp.pose.q[nominal.index_of("B").unwrap()];
                assert!(b >= -1e-12, "B = {b}");
            }
        }
    }
}
