//! Tests written for mutants of `crate/src/sshape/` that a sampled mutation run let survive
//! (`npm run mutants -- sshape`): the smallest clamped uniform B-spline.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::sshape::bspline::BSpline;
use nalgebra::Vector3;

/// A clamped cubic needs p + 1 = 4 points. With exactly 4 it is the Bézier curve (knots
/// 0,0,0,0,1,1,1,1), whose midpoint is (P0 + 3·P1 + 3·P2 + P3)/8 (Bernstein weights at ½);
/// with 3 or 2 points it is refused.
#[test]
fn four_points_make_the_bezier_cubic_and_fewer_are_refused() {
    let p = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 2.0, 0.0),
        Vector3::new(3.0, 2.0, 1.0),
        Vector3::new(4.0, 0.0, 2.0),
    ];
    let c = BSpline::clamped_uniform(3, p.clone()).unwrap();
    assert_eq!(c.knots(), &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    let mid = (p[0] + 3.0 * p[1] + 3.0 * p[2] + p[3]) / 8.0;
    assert!((c.point(0.5) - mid).norm() < 1e-12);
    assert!(BSpline::clamped_uniform(3, p[..3].to_vec()).is_err());
    assert!(BSpline::clamped_uniform(3, p[..2].to_vec()).is_err());
}
