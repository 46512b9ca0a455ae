//! Rotations about the machine's principal axes, the one place where the engine builds them.
//!
//! Frames are right-handed. A rotation by a positive angle about an axis turns counter-clockwise
//! when seen from the positive end of that axis (right-hand rule), exactly the matrices of
//! eqs (5)-(7) of Geng, Wu & Qiu (2018) and of eq (3) of Li et al. (2021).
//! Angles are in radians inside the engine.

use nalgebra::{Matrix3, Unit, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// A principal direction of the machine: X, Y or Z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Axis {
    /// The X direction, axis of the rotary axis A.
    X,
    /// The Y direction, axis of the rotary axis B.
    Y,
    /// The Z direction, axis of the rotary axis C.
    Z,
}

impl Axis {
    /// All three, in order X, Y, Z.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// Index 0, 1, 2 for X, Y, Z.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// The unit vector along this axis.
    pub fn unit(self) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        v[self.index()] = 1.0;
        v
    }

    /// The one axis that is neither `self` nor `other` (`self != other`).
    pub fn third(self, other: Axis) -> Axis {
        match 3 - self.index() - other.index() {
            0 => Axis::X,
            1 => Axis::Y,
            _ => Axis::Z,
        }
    }

    /// The letter "X", "Y" or "Z".
    pub fn letter(self) -> char {
        ['X', 'Y', 'Z'][self.index()]
    }
}

/// Rotation matrix by `angle` radians about `axis` (eqs (5)-(7) of the nonlinear-error paper).
pub fn rotation(axis: Axis, angle: f64) -> Matrix3<f64> {
    let (s, c) = angle.sin_cos();
    match axis {
        Axis::X => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        Axis::Y => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        Axis::Z => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// The same rotation as [`rotation`] as a unit quaternion (for rigid transforms,
/// `nalgebra::Isometry3`).
pub fn quaternion(axis: Axis, angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Unit::new_unchecked(axis.unit()), angle)
}

/// Rotates `v` by `angle` radians about `axis` without building a matrix:
/// `rotation(axis, angle) * v`.
pub fn rotate(axis: Axis, angle: f64, v: &Vector3<f64>) -> Vector3<f64> {
    let (s, c) = angle.sin_cos();
    rotate_sc(axis, s, c, v)
}

/// [`rotate`] by the angle whose sine and cosine are `s` and `c`.
pub fn rotate_sc(axis: Axis, s: f64, c: f64, v: &Vector3<f64>) -> Vector3<f64> {
    match axis {
        Axis::X => Vector3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z),
        Axis::Y => Vector3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z),
        Axis::Z => Vector3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z),
    }
}

/// `axis.unit() x v`: the derivative of `rotate(axis, t, v)` with respect to `t` at `t = 0`.
pub fn cross_axis(axis: Axis, v: &Vector3<f64>) -> Vector3<f64> {
    match axis {
        Axis::X => Vector3::new(0.0, -v.z, v.y),
        Axis::Y => Vector3::new(v.z, 0.0, -v.x),
        Axis::Z => Vector3::new(-v.y, v.x, 0.0),
    }
}

/// Wraps an angle in radians into `(-pi, pi]`.
pub fn wrap_pi(angle: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let mut a = angle % two_pi;
    if a <= -std::f64::consts::PI {
        a += two_pi;
    } else if a > std::f64::consts::PI {
        a -= two_pi;
    }
    a
}

/// The angle in `[0, pi]` between two non-zero vectors, accurate also for nearly parallel and
/// nearly opposite vectors (atan2 of the cross and dot products, not acos of the dot product).
pub fn angle_between(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotate_agrees_with_matrix_and_right_hand_rule() {
        let v = Vector3::new(0.3, -1.2, 0.7);
        for axis in Axis::ALL {
            for &a in &[0.0, 0.4, -2.0, 3.0] {
                let d = rotation(axis, a) * v - rotate(axis, a, &v);
                assert!(d.norm() < 1e-15);
            }
        }
        // Right-hand rule: +90 deg about Z takes X to Y, about X takes Y to Z, about Y takes Z to X.
        let q = std::f64::consts::FRAC_PI_2;
        assert!((rotate(Axis::Z, q, &Axis::X.unit()) - Axis::Y.unit()).norm() < 1e-15);
        assert!((rotate(Axis::X, q, &Axis::Y.unit()) - Axis::Z.unit()).norm() < 1e-15);
        assert!((rotate(Axis::Y, q, &Axis::Z.unit()) - Axis::X.unit()).norm() < 1e-15);
    }

    #[test]
    fn quaternion_is_the_same_rotation_as_the_matrix() {
        for axis in Axis::ALL {
            for &a in &[0.0, 0.4, -2.0, 3.0] {
                let d = quaternion(axis, a).to_rotation_matrix().into_inner() - rotation(axis, a);
                assert!(d.norm() < 1e-15);
            }
        }
    }

    #[test]
    fn cross_axis_is_the_derivative_of_rotate() {
        let v = Vector3::new(0.3, -1.2, 0.7);
        let h = 1e-6;
        for axis in Axis::ALL {
            let fd = (rotate(axis, h, &v) - rotate(axis, -h, &v)) / (2.0 * h);
            assert!((fd - cross_axis(axis, &v)).norm() < 1e-9);
            assert!((axis.unit().cross(&v) - cross_axis(axis, &v)).norm() < 1e-15);
        }
    }

    #[test]
    fn axes_have_their_index_letter_unit_and_third() {
        let names = [(Axis::X, 0, 'X'), (Axis::Y, 1, 'Y'), (Axis::Z, 2, 'Z')];
        for (axis, i, letter) in names {
            assert_eq!(axis.index(), i);
            assert_eq!(axis.letter(), letter);
            let mut unit = Vector3::zeros();
            unit[i] = 1.0;
            assert_eq!(axis.unit(), unit);
        }
        // The third axis completes the pair, in either order: its unit is ± their cross product.
        for a in Axis::ALL {
            for b in Axis::ALL.into_iter().filter(|b| *b != a) {
                let t = a.third(b);
                assert!(t != a && t != b, "{a:?} {b:?} → {t:?}");
                assert_eq!(a.unit().cross(&b.unit()).abs(), t.unit());
            }
        }
    }

    #[test]
    fn angle_between_is_accurate_near_parallel_and_opposite() {
        let x = Vector3::new(2.0, 0.0, 0.0);
        for t in [1e-9, 1e-4, 0.5, 1.0, 2.0, std::f64::consts::PI - 1e-9] {
            let v = Vector3::new(t.cos(), t.sin(), 0.0) * 3.0;
            let got = angle_between(&x, &v);
            assert!((got - t).abs() < 1e-15 * (1.0 + t) + 1e-24, "{t}: {got}");
        }
        assert_eq!(angle_between(&x, &(-x)), std::f64::consts::PI);
        assert_eq!(angle_between(&x, &x), 0.0);
    }

    #[test]
    fn wrap_pi_range() {
        use std::f64::consts::PI;
        assert!((wrap_pi(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_pi(-PI) - PI).abs() < 1e-12);
        assert!((wrap_pi(0.5 - 4.0 * PI) - 0.5).abs() < 1e-12);
        // (−π, π]: π stays, −π becomes π, angles just inside stay as they are.
        assert_eq!(wrap_pi(PI), PI);
        assert_eq!(wrap_pi(-PI), PI);
        for a in [PI - 1e-12, -PI + 1e-12, 0.0, 1.0, -1.0] {
            assert_eq!(wrap_pi(a), a);
        }
        assert!((wrap_pi(PI + 0.25) - (0.25 - PI)).abs() < 1e-15);
        assert!((wrap_pi(-PI - 0.25) - (PI - 0.25)).abs() < 1e-15);
    }
}
