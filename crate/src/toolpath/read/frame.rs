//! Frames and arcs, the geometry the readers apply: a rigid frame that takes a program's
//! coordinates to the workpiece frame ([`Frame`]), and an arc cut into chords within a tolerance
//! ([`arc`]).
//!
//! # Frames
//! A [`Frame`] is `p ↦ origin + R·p`: a point written in the frame (the program's coordinates
//! after a shift, a rotation or a tilted working plane) in the frame outside it (the workpiece
//! frame, in which the machine's kinematics give the tool axis). Directions turn by `R` only.
//! Every rotation is built from [`crate::geometry::rotation`] (right-hand rule, angles in
//! radians), so a frame is proper (`det R = 1`) by construction; a frame read as three axes from
//! a file is checked to be one ([`Frame::from_axes`]).

use crate::geometry::{angle_between, rotation, Axis};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::TAU;

/// Largest deviation from orthonormal accepted for axes read from a file (their numbers carry
/// 6 to 9 decimals).
const ORTHONORMAL_TOLERANCE: f64 = 1e-4;

/// A rigid frame: `p ↦ origin + R·p` (module docs). Lengths in mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// `R`: its columns are the frame's x, y and z axes in the outer frame.
    pub rotation: Matrix3<f64>,
    /// Where the frame's origin lies in the outer frame, mm.
    pub origin: Vector3<f64>,
}

impl Default for Frame {
    fn default() -> Self {
        Frame::IDENTITY
    }
}

impl Frame {
    /// The frame that changes nothing.
    pub const IDENTITY: Frame = Frame {
        rotation: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        origin: Vector3::new(0.0, 0.0, 0.0),
    };

    /// The same frame with lengths `k` times larger (its origin; a frame in another unit).
    pub fn scaled(&self, k: f64) -> Frame {
        Frame {
            rotation: self.rotation,
            origin: self.origin * k,
        }
    }

    /// A shift: `p ↦ p + by`.
    pub fn shift(by: Vector3<f64>) -> Frame {
        Frame {
            rotation: Matrix3::identity(),
            origin: by,
        }
    }

    /// A rotation by `angle` (rad, right-hand rule) about the line through `centre` along
    /// `axis`: `p ↦ centre + R·(p − centre)`.
    pub fn rotation_about(axis: Axis, angle: f64, centre: Vector3<f64>) -> Frame {
        let r = rotation(axis, angle);
        Frame {
            rotation: r,
            origin: centre - r * centre,
        }
    }

    /// The frame whose axes are `x` and `y` (and `z = x × y`) at `origin`, all in the outer
    /// frame; `None` unless `x` and `y` are unit and perpendicular within 1e-4 (then they are
    /// orthonormalised to rounding: `x` kept, `y` made perpendicular to it).
    pub fn from_axes(origin: Vector3<f64>, x: Vector3<f64>, y: Vector3<f64>) -> Option<Frame> {
        let tol = ORTHONORMAL_TOLERANCE;
        if (x.norm() - 1.0).abs() > tol || (y.norm() - 1.0).abs() > tol || x.dot(&y).abs() > tol {
            return None;
        }
        let x = x.normalize();
        let y = (y - x * x.dot(&y)).normalize();
        let z = x.cross(&y);
        Some(Frame {
            rotation: Matrix3::from_columns(&[x, y, z]),
            origin,
        })
    }

    /// The frame given by a rotation matrix read from a file (rows as written) and an origin;
    /// `None` unless the matrix is a proper rotation within 1e-4 (then its rows are
    /// orthonormalised to rounding).
    pub fn from_matrix(rows: [[f64; 3]; 3], origin: Vector3<f64>) -> Option<Frame> {
        let r = Matrix3::new(
            rows[0][0], rows[0][1], rows[0][2], rows[1][0], rows[1][1], rows[1][2], rows[2][0],
            rows[2][1], rows[2][2],
        );
        let f = Frame::from_axes(origin, r.column(0).into(), r.column(1).into())?;
        // The third column must be x × y (a proper rotation, not a mirror).
        let z: Vector3<f64> = r.column(2).into();
        ((z - f.rotation.column(2)).norm() <= ORTHONORMAL_TOLERANCE).then_some(f)
    }

    /// A point of this frame in the outer frame.
    pub fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.origin + self.rotation * p
    }

    /// A direction of this frame in the outer frame.
    pub fn direction(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * v
    }

    /// The frame `inner` written inside this one: `p ↦ self(inner(p))`.
    pub fn then(&self, inner: &Frame) -> Frame {
        Frame {
            rotation: self.rotation * inner.rotation,
            origin: self.apply(&inner.origin),
        }
    }

    /// The inverse: `q ↦ Rᵀ·(q − origin)`.
    pub fn inverse(&self) -> Frame {
        let rt = self.rotation.transpose();
        Frame {
            rotation: rt,
            origin: -(rt * self.origin),
        }
    }

    /// True when the frame moves no point by more than 1e-9 mm within 1 m of the origin.
    pub fn is_identity(&self) -> bool {
        self.origin.norm() < 1e-9 && (self.rotation - Matrix3::identity()).amax() < 1e-12
    }

    /// True when the frame only shifts.
    pub fn is_shift(&self) -> bool {
        (self.rotation - Matrix3::identity()).amax() < 1e-12
    }

    /// The frame in words: its origin, and its axes when it turns (`"origin (10, 0, 5) mm, x
    /// (1, 0, 0), y (0, −1, 0), z (0, 0, −1)"`), numbers to 6 significant decimals.
    pub fn describe(&self) -> String {
        let v = |v: Vector3<f64>| {
            let n = |x: f64| {
                let s = format!("{:.6}", x);
                let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
                if s == "-0" {
                    "0".to_string()
                } else {
                    s
                }
            };
            format!("({}, {}, {})", n(v.x), n(v.y), n(v.z))
        };
        let mut s = format!("origin {} mm", v(self.origin));
        if !self.is_shift() {
            let c = |i: usize| -> Vector3<f64> { self.rotation.column(i).into() };
            s.push_str(&format!(
                ", x axis {}, y axis {}, z axis {}",
                v(c(0)),
                v(c(1)),
                v(c(2))
            ));
        }
        s
    }
}

/// Largest number of chords one arc is cut into.
pub const MAX_ARC_CHORDS: usize = 100_000;

/// Why an arc cannot be cut into chords.
#[derive(Debug, Clone, PartialEq)]
pub enum ArcError {
    /// The end is not on the circle through the start: the two radii, mm.
    Radii(f64, f64),
    /// The start (or end) is on the centre: no circle.
    NoRadius,
}

/// An arc about `centre` (any point on its axis) with axis `normal` (unit), from `start` to
/// `end`, turning counter-clockwise about `normal` (right-hand rule) when `ccw`, else clockwise,
/// cut into the fewest equal chords whose sagitta stays within `chord_tolerance` (mm): the points
/// after `start` up to and including `end`, each with its fraction `u ∈ (0, 1]` of the arc.
///
/// * The swept angle is in `(0, 2π]` (a start equal to the end in the plane is a full circle);
///   `turns` more whole turns are added (a helix programmed with several turns).
/// * Along `normal` the point moves in proportion to the angle (a helix), and the radius changes
///   in proportion to it when the two radii differ by rounding (a spiral from `r₀` to `r₁`).
/// * A chord of an arc of radius `r` over the angle `φ` lies `r·(1 − cos(φ/2))` inside it, so
///   `φ = 2·acos(1 − tol/r)` is the largest step; `n = ⌈|θ|/φ⌉` chords (one when `r ≤ tol`), at
///   most [`MAX_ARC_CHORDS`].
/// * The radii at the start and the end may differ by `max(rounding, 10⁻⁴·r)` (what controls
///   accept as rounding of the written numbers; `rounding` in the same unit as the points);
///   more is [`ArcError::Radii`].
#[allow(clippy::too_many_arguments)]
pub fn arc(
    start: &Vector3<f64>,
    end: &Vector3<f64>,
    centre: &Vector3<f64>,
    normal: &Vector3<f64>,
    ccw: bool,
    turns: u32,
    (chord_tolerance, rounding): (f64, f64),
) -> Result<Vec<(Vector3<f64>, f64)>, ArcError> {
    let n = normal.normalize();
    let radial = |p: &Vector3<f64>| {
        let d = p - centre;
        d - n * n.dot(&d)
    };
    let (v0, v1) = (radial(start), radial(end));
    let (r0, r1) = (v0.norm(), v1.norm());
    if r0 < 1e-9 || r1 < 1e-9 {
        return Err(ArcError::NoRadius);
    }
    if (r0 - r1).abs() > (1e-4 * r0.max(r1)).max(rounding) {
        return Err(ArcError::Radii(r0, r1));
    }
    // Angle from v0 to v1 about n, counter-clockwise, in (0, 2π].
    let mut ccw_angle = n.dot(&v0.cross(&v1)).atan2(v0.dot(&v1));
    if ccw_angle <= 0.0 {
        ccw_angle += TAU;
    }
    // A start and end that coincide (to rounding) sweep a whole turn.
    if angle_between(&v0, &v1) < 1e-9 {
        ccw_angle = TAU;
    }
    let sweep = if ccw {
        ccw_angle
    } else {
        TAU - ccw_angle + if ccw_angle >= TAU { TAU } else { 0.0 }
    } + TAU * f64::from(turns);
    let r = r0.max(r1);
    let step = if r <= chord_tolerance {
        TAU
    } else {
        2.0 * (1.0 - chord_tolerance / r).acos()
    };
    let chords = ((sweep / step).ceil() as usize).clamp(1, MAX_ARC_CHORDS);
    let e0 = v0 / r0;
    let e1 = n.cross(&e0);
    let sign = if ccw { 1.0 } else { -1.0 };
    let (h0, h1) = (n.dot(&(start - centre)), n.dot(&(end - centre)));
    let mut out = Vec::with_capacity(chords);
    for i in 1..=chords {
        if i == chords {
            out.push((*end, 1.0));
            break;
        }
        let u = i as f64 / chords as f64;
        let (s, c) = (sign * sweep * u).sin_cos();
        let radius = r0 + (r1 - r0) * u;
        let p = centre + (e0 * c + e1 * s) * radius + n * (h0 + (h1 - h0) * u);
        out.push((p, u));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_and_its_inverse_compose_to_the_identity() {
        let f = Frame::rotation_about(Axis::Z, 0.7, Vector3::new(3.0, -2.0, 1.0))
            .then(&Frame::shift(Vector3::new(1.0, 2.0, 3.0)));
        let p = Vector3::new(-4.0, 5.5, 0.25);
        assert!((f.inverse().apply(&f.apply(&p)) - p).norm() < 1e-12);
        assert!(f.then(&f.inverse()).is_identity());
    }

    #[test]
    fn a_quarter_circle_keeps_every_chord_within_the_tolerance() {
        // Centre at the origin, r = 10, from (10, 0) to (0, 10) counter-clockwise about +z.
        let pts = arc(
            &Vector3::new(10.0, 0.0, 0.0),
            &Vector3::new(0.0, 10.0, 0.0),
            &Vector3::zeros(),
            &Vector3::z(),
            true,
            0,
            (0.001, 0.01),
        )
        .unwrap_or_default();
        // φ = 2·acos(1 − 1e-4) = 0.028285 rad; π/2 / φ = 55.53 → 56 chords.
        assert_eq!(pts.len(), 56);
        for (p, _) in &pts {
            assert!((p.norm() - 10.0).abs() < 1e-12 && p.x >= -1e-12 && p.y >= -1e-12);
        }
        // Clockwise the other way round: three quarters, 3 × 55.53 → 167 chords, through −y.
        let cw = arc(
            &Vector3::new(10.0, 0.0, 0.0),
            &Vector3::new(0.0, 10.0, 0.0),
            &Vector3::zeros(),
            &Vector3::z(),
            false,
            0,
            (0.001, 0.01),
        )
        .unwrap_or_default();
        assert_eq!(cw.len(), 167);
        assert!(cw
            .iter()
            .any(|(p, _)| (p - Vector3::new(0.0, -10.0, 0.0)).norm() < 0.2));
    }
}
