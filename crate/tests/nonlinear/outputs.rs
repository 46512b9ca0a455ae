//! The nonlinear move's derived outputs by their definitions, on random moves of all twelve
//! types: the sweep angle is the angle between the start and end tool vectors (each from the
//! type's forward kinematics), the plane sine `|V0 × V1|`, and the approximation's shortfall
//! `(max − approx)/max`, positive when eq 25/30 falls short of the exact maximum. The expected
//! values are computed here from the vectors and the other outputs, not copied.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, Rng};
use fiveaxis::nonlinear::{analyze, Move};
use fiveaxis::rotary::{Pose, RotaryType};
use nalgebra::Vector3;

#[test]
fn sweep_angle_plane_sine_and_shortfall_follow_their_definitions() {
    let mut rng = Rng::new(2018);
    let mut shortfalls = 0;
    for t in RotaryType::ALL {
        for _ in 0..20 {
            let start = Pose::new(rng.range(-3.0, 3.0), rng.range(-1.5, 1.5));
            let end = Pose::new(
                start.k + rng.range(-1.0, 1.0),
                start.m + rng.range(-1.0, 1.0),
            );
            let a = analyze(Move::new(t, start, end), 100.0, 3).unwrap();
            let v0 = t.tool_vector(start);
            let v1 = t.tool_vector(end);
            close(
                Vector3::from(a.start_vector).dot(&v0),
                1.0,
                1e-12,
                "V0 is the forward kinematics of the start",
            );
            close(Vector3::from(a.end_vector).dot(&v1), 1.0, 1e-12, "V1");
            let angle = v0.dot(&v1).clamp(-1.0, 1.0).acos();
            close(a.sweep_angle, angle, 1e-9, "sweep angle, rad");
            close(a.plane_sine, v0.cross(&v1).norm(), 1e-12, "plane sine");
            if let (Some(approx), Some(s)) = (a.approx, a.approx_shortfall) {
                close(s, (a.max - approx) / a.max, 1e-12, "shortfall");
                // The exact maximum is at least δ(0.5), which eq 25/30 approximates.
                assert!(a.max >= a.at_half - 1e-12);
                if s.abs() > 1e-9 {
                    shortfalls += 1;
                }
            }
        }
    }
    assert!(shortfalls > 50, "{shortfalls} moves with a shortfall");
}

/// A move's angles are refused beyond ±3600° (the documented `MAX_ANGLE_DEG`, ten turns) and when
/// not finite, each at its own field; 3600° itself is accepted (the bound is inclusive).
#[test]
fn a_move_beyond_ten_turns_or_not_finite_is_refused_at_its_field() {
    let t = RotaryType::ALL[0];
    let ok = Pose::new(0.0, 0.0);
    let turns = 3600f64.to_radians();
    assert!(analyze(Move::new(t, Pose::new(turns, 0.0), ok), 10.0, 8).is_ok());
    let cases = [
        ("start.k", Move::new(t, Pose::new(turns * 1.001, 0.0), ok)),
        ("start.m", Move::new(t, Pose::new(0.0, -turns * 1.001), ok)),
        ("end.k", Move::new(t, ok, Pose::new(f64::NAN, 0.0))),
        ("end.m", Move::new(t, ok, Pose::new(0.0, f64::INFINITY))),
    ];
    for (field, mv) in cases {
        let e = analyze(mv, 10.0, 8).expect_err(field);
        assert_eq!(e.field, field, "{}", e.message);
    }
}
