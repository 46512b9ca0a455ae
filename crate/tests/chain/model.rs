//! The shared kinematic chain, checked against references written independently of it: the
//! cubic-test paper's explicit 4×4 matrices (Li et al. 2021, eqs 2–12), central finite
//! differences of the exact chain, the nonlinear-error study's tool-vector formula, and round
//! trips of the inverse kinematics.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test
use crate::common;

use common::{bc_table, close, deg, Rng};
use fiveaxis::chain::{Chain, ErrorKind, Link, RigidError, Setup};
use fiveaxis::geometry::Axis;
use fiveaxis::rotary::{Pose, RotaryType};
use nalgebra::{Matrix4, Point3, Vector3, Vector4};
use std::f64::consts::FRAC_PI_2;

/// A head-B / table-C machine like the S-shape paper's (Y carries the table, X-Z-B the head),
/// with non-zero offsets so that no lever arm is accidentally zero. Chain order: Y, C, X, Z, B.
fn head_table() -> Chain {
    Chain {
        work: vec![
            Link::linear("Y", Axis::Y).on_table(),
            Link::rotary("C", Axis::Z)
                .on_table()
                .at(Vector3::new(3.0, -2.0, 40.0)),
        ],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Z", Axis::Z).at(Vector3::new(0.0, 5.0, 0.0)),
            Link::rotary("B", Axis::Y).at(Vector3::new(1.0, 0.0, 300.0)),
        ],
        work_origin: Vector3::new(10.0, 20.0, 30.0),
        tool_tip: Vector3::new(0.0, 0.0, -250.0),
        tool_axis: Axis::Z,
    }
}

/// A fork head: C on the ram, A on C, spindle along Z. Chain order: X, Y, Z, C, A.
fn head_head() -> Chain {
    Chain {
        work: vec![],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Y", Axis::Y),
            Link::linear("Z", Axis::Z),
            Link::rotary("C", Axis::Z).at(Vector3::new(0.0, 0.0, 500.0)),
            Link::rotary("A", Axis::X).at(Vector3::new(0.0, 0.0, -100.0)),
        ],
        work_origin: Vector3::zeros(),
        tool_tip: Vector3::new(0.0, 0.0, -150.0),
        tool_axis: Axis::Z,
    }
}

fn rx(a: f64) -> Matrix4<f64> {
    let (s, c) = a.sin_cos();
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn ry(a: f64) -> Matrix4<f64> {
    let (s, c) = a.sin_cos();
    Matrix4::new(
        c, 0.0, s, 0.0, 0.0, 1.0, 0.0, 0.0, -s, 0.0, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn rz(a: f64) -> Matrix4<f64> {
    let (s, c) = a.sin_cos();
    Matrix4::new(
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn tr(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    Matrix4::new(
        1.0, 0.0, 0.0, x, 0.0, 1.0, 0.0, y, 0.0, 0.0, 1.0, z, 0.0, 0.0, 0.0, 1.0,
    )
}

/// The paper's eight errors, with the chain's location errors they map onto:
/// `E_?0B = -(δ?BY, α/β/γBY)`, `E_X0C = -δxCB`, `E_A0C = -αCB` (see chain.rs / cubic docs).
struct PaperErrors {
    dx: f64,
    dy: f64,
    dz: f64,
    alpha: f64,
    beta: f64,
    gamma: f64,
    alpha_cb: f64,
    dx_cb: f64,
}

impl PaperErrors {
    fn apply(&self, chain: &mut Chain) {
        chain.work[0].location = RigidError {
            x: -self.dx,
            y: -self.dy,
            z: -self.dz,
            a: -self.alpha,
            b: -self.beta,
            c: -self.gamma,
        };
        chain.work[1].location = RigidError {
            x: -self.dx_cb,
            a: -self.alpha_cb,
            ..Default::default()
        };
    }
    /// Eq (2)'s error matrices: the B-Y group and the C-B group.
    fn e_by(&self) -> Matrix4<f64> {
        rz(self.gamma) * ry(self.beta) * rx(self.alpha) * tr(self.dx, self.dy, self.dz)
    }
    fn e_cb(&self) -> Matrix4<f64> {
        rx(self.alpha_cb) * tr(self.dx_cb, 0.0, 0.0)
    }
}

#[test]
fn the_chain_reproduces_eqs_2_and_10_to_12_of_the_cubic_paper_exactly() {
    let mut rng = Rng::new(11);
    for _ in 0..200 {
        let e = PaperErrors {
            dx: rng.range(-0.5, 0.5),
            dy: rng.range(-0.5, 0.5),
            dz: rng.range(-0.5, 0.5),
            alpha: rng.range(-0.01, 0.01),
            beta: rng.range(-0.01, 0.01),
            gamma: rng.range(-0.01, 0.01),
            alpha_cb: rng.range(-0.01, 0.01),
            dx_cb: rng.range(-0.5, 0.5),
        };
        let mut chain = bc_table();
        e.apply(&mut chain);
        let (b, c) = (rng.range(-2.0, 2.0), rng.range(-4.0, 4.0));
        let pm = Vector3::new(
            rng.range(-100.0, 100.0),
            rng.range(-100.0, 100.0),
            rng.range(-50.0, 150.0),
        );
        let q = [b, c, pm.x, pm.y, pm.z];
        let pm4 = Vector4::new(pm.x, pm.y, pm.z, 1.0);
        // Eq (2): P_T = M_C · M_αCB · M_δxCB · M_B · M_γBY · M_βBY · M_αBY · M_δBY · P_M.
        let pt = rz(c) * e.e_cb() * ry(b) * e.e_by() * pm4;
        let got = chain.tool_pose(&q, true, &Setup::None).unwrap().tip;
        for k in 0..3 {
            close(got[k], pt[k], 1e-10, "eq 2");
        }
        // Eqs (10)-(12): P_W = M_WC · (eq 2), M_WC = (M_αCB M_δxCB M_γBY M_βBY M_αBY M_δBY)⁻¹.
        let m_wc = (e.e_cb() * e.e_by()).try_inverse().unwrap();
        let pw = m_wc * pt;
        let got = chain
            .tool_pose(&q, true, &Setup::AtPose(vec![0.0; 5]))
            .unwrap()
            .tip;
        for k in 0..3 {
            close(got[k], pw[k], 1e-10, "eq 10");
        }
    }
}

#[test]
fn without_errors_the_chain_gives_the_nonlinear_studys_tool_vector_for_all_machine_types() {
    // Table-table B/C (type CBZ), head-table C/B (CBZ), head-head C/A (CAZ): V = R_K(θk) R_M(θm) e_H.
    let cases: [(Chain, &str, &str, &str); 3] = [
        (bc_table(), "CBZ", "C", "B"),
        (head_table(), "CBZ", "C", "B"),
        (head_head(), "CAZ", "C", "A"),
    ];
    let mut rng = Rng::new(5);
    for (chain, name, k, m) in cases {
        let t = RotaryType::parse(name).unwrap();
        let layout = chain.rotary_type().unwrap();
        assert_eq!(layout.rtype, t, "{name}");
        let (ik, im) = (chain.index_of(k).unwrap(), chain.index_of(m).unwrap());
        for _ in 0..50 {
            let q: Vec<f64> = (0..5).map(|_| rng.range(-3.0, 3.0) * 50.0).collect();
            let mut q = q;
            q[ik] = rng.range(-3.0, 3.0);
            q[im] = rng.range(-3.0, 3.0);
            let v = t.tool_vector(Pose::new(q[ik], q[im]));
            let got = chain.tool_pose(&q, false, &Setup::None).unwrap().axis;
            assert!((got - v).norm() < 1e-12, "{name}: {got:?} vs {v:?}");
        }
    }
}

#[test]
fn linear_axes_move_the_tool_positively_relative_to_the_workpiece_on_either_branch() {
    // ISO 841: +Y on the table (head_table) and +X on the head both move the tool by +1 mm.
    let chain = head_table();
    let q0 = [0.0; 5];
    let p0 = chain.tool_pose(&q0, false, &Setup::None).unwrap().tip;
    for (name, dir) in [
        ("Y", Vector3::y()),
        ("X", Vector3::x()),
        ("Z", Vector3::z()),
    ] {
        let mut q = q0;
        q[chain.index_of(name).unwrap()] = 1.0;
        let p = chain.tool_pose(&q, false, &Setup::None).unwrap().tip;
        assert!((p - p0 - dir).norm() < 1e-12, "{name}");
    }
}

/// Central difference of the exact chain with respect to one error component.
fn finite_difference(
    chain: &Chain,
    link: usize,
    kind: ErrorKind,
    k: usize,
    q: &[f64],
    setup: &Setup,
) -> (Vector3<f64>, Vector3<f64>) {
    let h = 1e-6;
    let eval = |v: f64| {
        let mut c = chain.clone();
        match kind {
            ErrorKind::Location => c.link_mut(link).location.set(k, v),
            ErrorKind::Motion => {
                // The error-motion value at the current position only (the set-up pose sees
                // the value at its own position, here zero).
                let mut e = RigidError::default();
                e.set(k, v);
                let here = q[link];
                c.link_mut(link).motion = Some(std::sync::Arc::new(move |p| {
                    Ok(if p == here { e } else { RigidError::default() })
                }));
            }
        }
        c.tool_pose(q, true, setup).unwrap()
    };
    let (p, m) = (eval(h), eval(-h));
    ((p.tip - m.tip) / (2.0 * h), (p.axis - m.axis) / (2.0 * h))
}

#[test]
fn the_analytic_jacobian_matches_finite_differences_of_the_exact_chain() {
    let mut rng = Rng::new(99);
    for chain in [bc_table(), head_table(), head_head()] {
        for trial in 0..6 {
            let q: Vec<f64> = chain
                .links()
                .map(|(_, l)| match l.joint {
                    fiveaxis::chain::Joint::Linear(_) => rng.range(-200.0, 200.0),
                    fiveaxis::chain::Joint::Rotary(_) => rng.range(-3.0, 3.0),
                })
                .collect();
            let setup = if trial % 2 == 0 {
                Setup::None
            } else {
                Setup::AtPose((0..chain.len()).map(|_| rng.range(-1.0, 1.0)).collect())
            };
            let jac = chain.jacobian(&q, &setup).unwrap();
            assert_eq!(jac.len(), 12 * chain.len());
            for s in &jac {
                let (ft, fa) = finite_difference(&chain, s.link, s.kind, s.component, &q, &setup);
                let scale = 1.0 + ft.norm();
                assert!(
                    (s.tip - ft).norm() < 1e-6 * scale,
                    "{} tip: {:?} vs {:?}",
                    s.name,
                    s.tip,
                    ft
                );
                assert!(
                    (s.axis - fa).norm() < 1e-7,
                    "{} axis: {:?} vs {:?}",
                    s.name,
                    s.axis,
                    fa
                );
            }
        }
    }
}

#[test]
fn with_the_workpiece_set_up_at_a_pose_every_workpiece_branch_error_vanishes_there() {
    let mut rng = Rng::new(3);
    let mut chain = head_table();
    for i in 0..2 {
        chain.link_mut(i).location =
            RigidError::from_array([0.0; 6].map(|_| rng.range(-0.1, 0.1) * 1e-1));
    }
    let q0: Vec<f64> = vec![12.0, deg(20.0), -30.0, 40.0, deg(-15.0)];
    let nominal = chain.tool_pose(&q0, false, &Setup::None).unwrap();
    let set = chain
        .tool_pose(&q0, true, &Setup::AtPose(q0.clone()))
        .unwrap();
    assert!((nominal.tip - set.tip).norm() < 1e-12 && (nominal.axis - set.axis).norm() < 1e-14);
    // Without the set-up the errors show at q0.
    let conventional = chain.tool_pose(&q0, true, &Setup::None).unwrap();
    assert!((nominal.tip - conventional.tip).norm() > 1e-4);
}

/// Random axis positions away from the singular orientations: linear ±150 mm, K ±3 rad,
/// M ±1.5 rad.
fn random_positions(chain: &Chain, rng: &mut Rng) -> Vec<f64> {
    let layout = chain.rotary_type().unwrap();
    let mut q: Vec<f64> = (0..chain.len()).map(|_| rng.range(-150.0, 150.0)).collect();
    q[layout.k] = rng.range(-3.0, 3.0);
    q[layout.m] = rng.range(-1.5, 1.5);
    q
}

#[test]
fn inverse_kinematics_round_trips_on_every_machine_type() {
    let mut rng = Rng::new(17);
    for chain in [bc_table(), head_table(), head_head()] {
        for _ in 0..200 {
            let q = random_positions(&chain, &mut rng);
            let pose = chain.tool_pose(&q, false, &Setup::None).unwrap();
            let (back, singular) = chain.inverse(&pose.tip, &pose.axis, Some(&q)).unwrap();
            assert!(!singular);
            for (a, b) in q.iter().zip(&back) {
                close(*a, *b, 1e-8, "round trip continuing from the same pose");
            }
            // Without a previous pose some solution is found that gives the same tool pose.
            let (other, _) = chain.inverse(&pose.tip, &pose.axis, None).unwrap();
            let again = chain.tool_pose(&other, false, &Setup::None).unwrap();
            assert!(
                (again.tip - pose.tip).norm() < 1e-8 && (again.axis - pose.axis).norm() < 1e-12
            );
        }
    }
}

#[test]
fn bad_positions_are_reported_not_panicked() {
    let chain = bc_table();
    assert!(chain
        .tool_pose(&[0.0; 4], false, &Setup::None)
        .unwrap_err()
        .message
        .contains("expected 5"));
    assert!(chain
        .tool_pose(&[0.0, f64::NAN, 0.0, 0.0, 0.0], false, &Setup::None)
        .is_err());
    assert!(chain
        .jacobian(&[0.0; 5], &Setup::AtPose(vec![0.0; 3]))
        .is_err());
}

#[test]
fn inverse_all_gives_every_branch_and_each_reproduces_the_tool_pose() {
    let mut rng = Rng::new(23);
    for chain in [bc_table(), head_table(), head_head()] {
        let layout = chain.rotary_type().unwrap();
        for _ in 0..100 {
            let q = random_positions(&chain, &mut rng);
            let pose = chain.tool_pose(&q, false, &Setup::None).unwrap();
            let (all, singular) = chain.inverse_all(&pose.tip, &pose.axis).unwrap();
            assert!(!singular);
            assert_eq!(all.len(), 2);
            for s in &all {
                let again = chain.tool_pose(s, false, &Setup::None).unwrap();
                assert!(
                    (again.tip - pose.tip).norm() < 1e-8 && (again.axis - pose.axis).norm() < 1e-12
                );
            }
            // The two branches differ (M of opposite sign for these tool-along-K types), and
            // one of them is the pose we started from, up to whole turns.
            let turns = |a: f64, b: f64| {
                let d = (a - b) / std::f64::consts::TAU;
                (d - d.round()).abs() < 1e-9
            };
            assert!(all
                .iter()
                .any(|s| turns(s[layout.k], q[layout.k]) && turns(s[layout.m], q[layout.m])));
        }
    }
    // B/C table, tool vector (-1/2, 0, √3/2): B = 30°, C = 180° or B = -30°, C = 0°.
    let chain = bc_table();
    let v = Vector3::new(-0.5, 0.0, 3f64.sqrt() / 2.0);
    let (all, _) = chain.inverse_all(&Vector3::zeros(), &v).unwrap();
    let mut got: Vec<(i64, i64)> = all
        .iter()
        .map(|s| {
            (
                s[0].to_degrees().round() as i64,
                s[1].to_degrees().round() as i64,
            )
        })
        .collect();
    got.sort();
    assert_eq!(got, vec![(-30, 0), (30, 180)]);
    // Along the C axis: singular, one solution.
    let (all, singular) = chain
        .inverse_all(&Vector3::new(1.0, 2.0, 3.0), &Vector3::z())
        .unwrap();
    assert!(singular && all.len() == 1 && all[0][0] == 0.0);
}

#[test]
fn solve_linear_puts_the_tip_where_asked_for_any_rotary_positions() {
    // Rotary angles chosen by the caller (not by the chain's own IK): the linear axes found
    // must put the tip at the target, and keep the rotary positions untouched.
    let mut rng = Rng::new(23);
    for chain in [bc_table(), head_table(), head_head()] {
        let layout = chain.rotary_type().unwrap();
        for _ in 0..100 {
            let mut q: Vec<f64> = (0..chain.len()).map(|_| rng.range(-150.0, 150.0)).collect();
            q[layout.k] = rng.range(-6.0, 6.0);
            q[layout.m] = rng.range(-3.0, 3.0);
            let target = Vector3::new(
                rng.range(-200.0, 200.0),
                rng.range(-200.0, 200.0),
                rng.range(-50.0, 300.0),
            );
            let got = chain.solve_linear(&target, &q).unwrap();
            assert_eq!(got[layout.k], q[layout.k]);
            assert_eq!(got[layout.m], q[layout.m]);
            let tip = chain.tool_pose(&got, false, &Setup::None).unwrap().tip;
            assert!((tip - target).norm() < 1e-9, "{tip:?} vs {target:?}");
        }
    }
    let chain = bc_table();
    assert!(chain
        .solve_linear(&Vector3::new(f64::NAN, 0.0, 0.0), &[0.0; 5])
        .is_err());
    assert!(chain.solve_linear(&Vector3::zeros(), &[0.0; 4]).is_err());
}

#[test]
fn the_pose_evaluator_gives_tool_pose_whatever_changes_between_calls() {
    // Random walks that change one, some or all axes between calls, with location errors and
    // error motions: the kept transforms must never serve a stale link.
    let mut rng = Rng::new(7);
    for mut chain in [bc_table(), head_table(), head_head()] {
        for i in 0..chain.len() {
            let link = chain.link_mut(i);
            link.location.set(i % 6, 1e-3 * (i as f64 + 1.0));
            let k = (i + 2) % 6;
            link.motion = Some(std::sync::Arc::new(move |p| {
                let mut e = RigidError::default();
                e.set(k, 1e-4 * p.sin());
                Ok(e)
            }));
        }
        for errors in [false, true] {
            let mut ev = chain.poses(errors);
            let mut q: Vec<f64> = (0..chain.len()).map(|_| rng.range(-1.0, 1.0)).collect();
            for _ in 0..200 {
                for qi in q.iter_mut() {
                    if rng.unit() < 0.3 {
                        *qi = rng.range(-2.0, 2.0);
                    }
                }
                let a = ev.tool_pose(&q).unwrap();
                let b = chain.tool_pose(&q, errors, &Setup::None).unwrap();
                assert!((a.tip - b.tip).norm() < 1e-12 && (a.axis - b.axis).norm() < 1e-15);
            }
        }
    }
}

fn near(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// `D = T·R_X(a)·R_Y(b)·R_Z(c)`: by hand, `R_Y(90°)` turns `e_x` into `−e_z` and `R_X(90°)` then
/// turns `−e_z` into `+e_y`; the other order would give `−e_z`. The translation is added last.
#[test]
fn a_rigid_error_rotates_about_x_then_y_then_z_and_then_translates() {
    let d = RigidError {
        x: 1.0,
        y: 2.0,
        z: 3.0,
        a: FRAC_PI_2,
        b: FRAC_PI_2,
        c: 0.0,
    }
    .transform();
    let p = d * Point3::new(1.0, 0.0, 0.0);
    assert!(near(&p.coords, &Vector3::new(1.0, 3.0, 3.0), 1e-12), "{p}");
    // A rotation about Z alone: e_x → e_y.
    let r = RigidError {
        c: FRAC_PI_2,
        ..Default::default()
    }
    .transform();
    assert!(near(&(r * Vector3::x()), &Vector3::y(), 1e-12));
    // Zero angles: a pure translation.
    let t = RigidError {
        x: 0.5,
        ..Default::default()
    }
    .transform();
    assert!(near(
        &(t * Point3::origin()).coords,
        &Vector3::new(0.5, 0.0, 0.0),
        0.0
    ));
    assert!(near(&(t * Vector3::z()), &Vector3::z(), 0.0));
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// The six components by index follow the letters X Y Z A B C (fields by name).
#[test]
fn rigid_error_components_by_index_are_the_named_fields() {
    let mut e = RigidError::default();
    for k in 0..6 {
        e.set(k, (k + 1) as f64);
    }
    assert_eq!(
        (e.x, e.y, e.z, e.a, e.b, e.c),
        (1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    );
    for k in 0..6 {
        assert_eq!(e.get(k), (k + 1) as f64);
    }
    assert_eq!(e.to_array(), [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(RigidError::from_array(e.to_array()), e);
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// A link's debug text names it and marks an error-motion function (which has no text) as `fn`.
#[test]
fn a_link_prints_its_name_and_whether_it_has_error_motions() {
    let mut l = Link::rotary("C", Axis::Z);
    let plain = format!("{l:?}");
    assert!(plain.contains("\"C\"") && plain.contains("None"), "{plain}");
    l.motion = Some(std::sync::Arc::new(|_| Ok(RigidError::default())));
    let with = format!("{l:?}");
    assert!(with.contains("Some(\"fn\")"), "{with}");
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// Chain order is the workpiece branch, then the tool branch: index 1 is C (work), 2 is X (tool).
#[test]
fn links_are_indexed_workpiece_branch_first() {
    let mut chain = bc_table();
    let names: Vec<String> = (0..5).map(|i| chain.link(i).name.clone()).collect();
    assert_eq!(names, ["B", "C", "X", "Y", "Z"]);
    chain.link_mut(1).name = "c".into();
    chain.link_mut(2).name = "x".into();
    chain.link_mut(4).name = "z".into();
    assert_eq!(chain.work[1].name, "c");
    assert_eq!(chain.tool[0].name, "x");
    assert_eq!(chain.tool[2].name, "z");
    assert_eq!(chain.len(), 5);
    assert!(!chain.is_empty());
    assert_eq!(chain.index_of("Y"), Some(3));
    // A chain without axes is empty.
    let none = Chain {
        work: vec![],
        tool: vec![],
        ..bc_table()
    };
    assert!(none.is_empty());
    assert_eq!(none.len(), 0);
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// Error messages name the input and the axis: a wrong count gives the expected count and the
/// axis names, a non-finite position names its axis.
#[test]
fn position_errors_name_the_positions_and_the_axis() {
    let chain = bc_table();
    let e = chain.tool_pose(&[0.0; 4], false, &Setup::None).unwrap_err();
    assert_eq!(e.field, "positions");
    assert!(
        e.message
            .contains("expected 5 axis positions (B, C, X, Y, Z), got 4"),
        "{}",
        e.message
    );
    for (i, name) in ["B", "C", "X", "Y", "Z"].iter().enumerate() {
        let mut q = [0.0; 5];
        q[i] = f64::INFINITY;
        let e = chain.tool_pose(&q, false, &Setup::None).unwrap_err();
        assert!(
            e.message
                .contains(&format!("the position of {name} is not a finite number")),
            "{}",
            e.message
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// The axis frames sit at `F_(i−1)·T(o_i)`: on a table whose C is 100 mm above B (B about Y),
/// turning B by 90° (table side, so the frame turns by −90°) carries C's frame to x = −100 mm;
/// the tool-side frames are unaffected and start again at the bed.
#[test]
fn axis_frames_follow_the_offsets_and_the_motions_before_each_axis() {
    let mut chain = bc_table();
    chain.work[1] = Link::rotary("C", Axis::Z)
        .on_table()
        .at(Vector3::new(0.0, 0.0, 100.0));
    chain.tool[1] = Link::linear("Y", Axis::Y).at(Vector3::new(5.0, 0.0, 0.0));
    let f = chain.axis_frames(&[FRAC_PI_2, 0.3, 7.0, 0.0, 0.0]).unwrap();
    assert_eq!(f.len(), 5);
    let origin = |i: usize| (f[i] * Point3::origin()).coords;
    assert!(near(&origin(0), &Vector3::zeros(), 1e-12));
    // R_Y(−90°)·(0, 0, 100) = (−100, 0, 0).
    assert!(
        near(&origin(1), &Vector3::new(-100.0, 0.0, 0.0), 1e-9),
        "{}",
        origin(1)
    );
    assert!(near(
        &(f[1] * Vector3::z()),
        &Vector3::new(-1.0, 0.0, 0.0),
        1e-12
    ));
    assert!(near(&origin(2), &Vector3::zeros(), 1e-12));
    // Y sits 5 mm along X from X's frame, which has moved by X = 7.
    assert!(
        near(&origin(3), &Vector3::new(12.0, 0.0, 0.0), 1e-12),
        "{}",
        origin(3)
    );
    assert!(near(&origin(4), &Vector3::new(12.0, 0.0, 0.0), 1e-12));
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// ISO 230-1 names: location error `E_<letter>0<axis>`, error motion `E_<letter><axis>`; the
/// Jacobian lists the 6 location components of each link in chain order, then the 6 error-motion
/// components of each link, so entry `6·link + k` is location component `k` of `link`.
#[test]
fn sensitivities_carry_the_iso_names_in_the_documented_order() {
    let chain = bc_table();
    assert_eq!(chain.link(0).location_name(3), "E_A0B");
    assert_eq!(chain.link(2).location_name(0), "E_X0X");
    assert_eq!(chain.link(1).motion_name(5), "E_CC");
    assert_eq!(chain.link(4).motion_name(1), "E_YZ");
    let j = chain
        .jacobian(&[0.1, 0.2, 1.0, 2.0, 3.0], &Setup::None)
        .unwrap();
    assert_eq!(j.len(), 60);
    let letters = ["X", "Y", "Z", "A", "B", "C"];
    let axes = ["B", "C", "X", "Y", "Z"];
    for (n, s) in j.iter().enumerate() {
        let (link, k) = ((n % 30) / 6, n % 6);
        let want = if n < 30 {
            format!("E_{}0{}", letters[k], axes[link])
        } else {
            format!("E_{}{}", letters[k], axes[link])
        };
        assert_eq!(s.name, want);
        assert_eq!((s.link, s.component), (link, k));
    }
    assert_eq!(Chain::location_index(1, 4), 10);
    assert_eq!(Chain::location_index(3, 0), 18);
    assert_eq!(j[Chain::location_index(2, 5)].name, "E_C0X");
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// Without errors neither the chain's errors nor the set-up matter, and the B/C table's nominal
/// pose has a closed form: with the table turning by −b about Y and −c about Z (ISO 841), the
/// tool seen from the workpiece is `R_Z(c)·R_Y(b)·(x, y, z)` with axis `R_Z(c)·R_Y(b)·e_z`.
#[test]
fn without_errors_the_pose_is_the_closed_form_whatever_the_set_up() {
    let mut chain = bc_table();
    chain.link_mut(0).location = RigidError {
        x: 0.02,
        a: 1e-3,
        ..Default::default()
    };
    chain.link_mut(1).location = RigidError {
        y: -0.03,
        c: 2e-3,
        ..Default::default()
    };
    let (b, c, x, y, z): (f64, f64, f64, f64, f64) = (0.4, -1.1, 10.0, -20.0, 30.0);
    // R_Y(b)·(x, y, z), then R_Z(c).
    let (x1, y1, z1) = (b.cos() * x + b.sin() * z, y, -b.sin() * x + b.cos() * z);
    let tip = Vector3::new(c.cos() * x1 - c.sin() * y1, c.sin() * x1 + c.cos() * y1, z1);
    let axis = Vector3::new(c.cos() * b.sin(), c.sin() * b.sin(), b.cos());
    let q = [b, c, x, y, z];
    for setup in [Setup::None, Setup::AtPose(vec![0.3, 0.5, 1.0, 2.0, 3.0])] {
        let p = chain.tool_pose(&q, false, &setup).unwrap();
        assert!(near(&p.tip, &tip, 1e-9), "{} vs {tip}", p.tip);
        assert!(near(&p.axis, &axis, 1e-12), "{} vs {axis}", p.axis);
    }
    // With errors the same set-up does change the pose.
    let p = chain
        .tool_pose(&q, true, &Setup::AtPose(vec![0.3, 0.5, 1.0, 2.0, 3.0]))
        .unwrap();
    assert!(!near(&p.tip, &tip, 1e-4));
    // A set-up pose of the wrong length is refused, with or without errors.
    for errors in [false, true] {
        assert!(chain
            .tool_pose(&q, errors, &Setup::AtPose(vec![0.0; 3]))
            .is_err());
    }
}

// Found by cargo-mutants: a mutant in `crate/src/chain.rs` survived every other test.
/// Continuing from a previous pose, inverse kinematics picks, of the two rotary solutions, the
/// one nearest the previous commands. For the B/C table the tool direction is
/// `(cos c·sin b, sin c·sin b, cos b)`, so `(c, b)` and `(c + π, −b)` give the same direction
/// (worked by hand); the previous pose decides between them.
#[test]
fn inverse_continues_from_the_previous_pose_on_the_nearer_solution() {
    use std::f64::consts::PI;
    let chain = bc_table();
    let (b, c) = (0.3_f64, 0.7_f64);
    let dir = Vector3::new(c.cos() * b.sin(), c.sin() * b.sin(), b.cos());
    let tip = Vector3::new(5.0, -3.0, 20.0);
    // Equally far in C (π/2 from each), nearer (c + π, −b) in B: −0.2 is 0.1 from −0.3.
    // Chain order B, C, X, Y, Z.
    let prev = [-0.2, c + PI / 2.0, 0.0, 0.0, 0.0];
    let (q, singular) = chain.inverse(&tip, &dir, Some(&prev)).unwrap();
    assert!(!singular);
    assert!(
        (q[0] + b).abs() < 1e-9 && (q[1] - (c + PI)).abs() < 1e-9,
        "{q:?}"
    );
    // Equally far in B (0.3 from ±0.3), nearer (c, b) in C.
    let prev = [0.0, c + PI / 2.0 - 0.3, 0.0, 0.0, 0.0];
    let (q, _) = chain.inverse(&tip, &dir, Some(&prev)).unwrap();
    assert!((q[0] - b).abs() < 1e-9 && (q[1] - c).abs() < 1e-9, "{q:?}");
    let p = chain.tool_pose(&q, false, &Setup::None).unwrap();
    assert!(near(&p.tip, &tip, 1e-9) && near(&p.axis, &dir, 1e-12));
}
