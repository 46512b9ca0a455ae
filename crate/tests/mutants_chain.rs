//! Tests written for mutants of `crate/src/chain.rs` that the other tests let survive
//! (`npm run mutants -- chain`). Each checks an independent fact: a hand-computed pose, a closed
//! form, a symmetry or a finite difference; none pastes the engine's own output.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test
mod common;

use common::bc_table;

use fiveaxis::chain::{Chain, Link, RigidError, Setup};
use fiveaxis::geometry::Axis;
use nalgebra::{Point3, Vector3};
use std::f64::consts::FRAC_PI_2;

fn near(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

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
