//! Frames of the readers (`fiveaxis::toolpath::read::frame`): a frame given by its axes or by
//! a matrix read from a file is accepted within 1e-4 of orthonormal and made exactly so.

use fiveaxis::toolpath::read::frame::{arc, ArcError, Frame};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// `RᵀR − I`, largest entry.
fn off_orthonormal(r: &Matrix3<f64>) -> f64 {
    (r.transpose() * r - Matrix3::identity()).amax()
}

/// Axes each within 1e-4 of unit length and of perpendicular (rounded file values) make a
/// frame; 1.1e-4 off on any one of the three does not. The frame made keeps x and turns y to be
/// exactly perpendicular to it. (From the mutants of `from_axes`' checks and of its
/// Gram–Schmidt step.)
#[test]
fn axes_within_1e_4_of_orthonormal_make_an_exact_frame() {
    let o = Vector3::zeros();
    let (x, y) = (Vector3::x(), Vector3::y());
    for (within, beyond, what) in [
        (x * (1.0 + 0.9e-4), x * (1.0 + 1.1e-4), "x's length"),
        (x * (1.0 - 0.9e-4), x * (1.0 - 1.1e-4), "x's length, short"),
    ] {
        assert!(Frame::from_axes(o, within, y).is_some(), "{what}");
        assert!(Frame::from_axes(o, beyond, y).is_none(), "{what}");
    }
    assert!(Frame::from_axes(o, x, y * (1.0 + 0.9e-4)).is_some());
    assert!(Frame::from_axes(o, x, y * (1.0 + 1.1e-4)).is_none());
    // x · y of 0.9e-4 and 1.1e-4 (y's length off by 4e-9 only).
    let leaning = |d: f64| Vector3::new(d, 1.0, 0.0);
    assert!(Frame::from_axes(o, x, leaning(-1.1e-4)).is_none());
    let f = Frame::from_axes(o, x, leaning(0.9e-4)).unwrap_or_else(|| panic!("within 1e-4"));
    assert!(off_orthonormal(&f.rotation) < 1e-15);
    assert_eq!(f.rotation.column(0), x);
    assert!((f.rotation.column(1) - y).amax() < 1e-15);
    assert!((f.rotation.column(2) - Vector3::z()).amax() < 1e-15);
}

/// An arc needs a radius at both ends: a start or an end on the centre (within 1e-9 mm) is
/// `NoRadius`, whatever the other end's radius, not a difference of radii. (From the mutants of
/// that check.)
#[test]
fn an_arc_whose_start_or_end_is_on_the_centre_has_no_radius() {
    let (c, n) = (Vector3::zeros(), Vector3::z());
    let on = Vector3::new(1e-10, 0.0, 0.0);
    let off = Vector3::new(0.0, 5.0, 0.0);
    for (start, end) in [(on, off), (off, on), (on, on)] {
        assert_eq!(
            arc(&start, &end, &c, &n, true, 0, (0.001, 0.0)),
            Err(ArcError::NoRadius)
        );
    }
}

/// The two radii may differ by 10⁻⁴ of the radius (rounding of the written numbers) when the
/// reader allows no more: 10 and 10.0009 mm are one arc, 10 and 10.0011 mm are not. (From the
/// mutant dividing by the radius.)
#[test]
fn radii_may_differ_by_a_ten_thousandth_of_the_radius() {
    let (c, n) = (Vector3::zeros(), Vector3::z());
    let start = Vector3::new(10.0, 0.0, 0.0);
    assert!(arc(
        &start,
        &Vector3::new(0.0, 10.0009, 0.0),
        &c,
        &n,
        true,
        0,
        (0.001, 0.0)
    )
    .is_ok());
    assert_eq!(
        arc(
            &start,
            &Vector3::new(0.0, 10.0011, 0.0),
            &c,
            &n,
            true,
            0,
            (0.001, 0.0)
        )
        .map(|_| ()),
        Err(ArcError::Radii(10.0, 10.0011))
    );
}

/// An end that is the start but for rounding (10⁻¹² rad apart) closes a whole circle, as a full
/// circle is programmed: the tool goes round to the far side, x = −10. (From the mutant
/// that took such an end for a start 10⁻¹² rad away.)
#[test]
fn an_end_at_the_start_but_for_rounding_is_a_full_circle() {
    let (c, n) = (Vector3::zeros(), Vector3::z());
    let start = Vector3::new(10.0, 0.0, 0.0);
    let end = Vector3::new(10.0, 1e-11, 0.0);
    let p = arc(&start, &end, &c, &n, true, 0, (0.001, 0.0)).unwrap_or_else(|e| panic!("{e:?}"));
    let far = p.iter().map(|q| q.0.x).fold(f64::INFINITY, f64::min);
    assert!(far < -9.99, "{far}");
    // Clockwise about +Z, the same full circle starts towards −Y. (From the mutant that made
    // the clockwise whole turn negative.)
    let p = arc(&start, &start, &c, &n, false, 0, (0.001, 0.0)).unwrap_or_else(|e| panic!("{e:?}"));
    assert!(p.len() > 100 && p[0].0.y < 0.0, "{:?}", p.first());
    let far = p.iter().map(|q| q.0.x).fold(f64::INFINITY, f64::min);
    assert!(far < -9.99, "{far}");
}

/// Along the axis the tool moves in proportion to the angle, measured from wherever the centre
/// is on the axis: half a turn from (10, 0, 2) to (−10, 0, 4) about the Z axis through the
/// origin passes (0, 10, 3) halfway. (From the mutant that added the heights.)
#[test]
fn a_helix_rises_in_proportion_to_the_angle() {
    let p = arc(
        &Vector3::new(10.0, 0.0, 2.0),
        &Vector3::new(-10.0, 0.0, 4.0),
        &Vector3::zeros(),
        &Vector3::z(),
        true,
        0,
        (0.001, 0.0),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    for (q, u) in &p {
        let expected = Vector3::new(10.0 * (PI * u).cos(), 10.0 * (PI * u).sin(), 2.0 + 2.0 * u);
        assert!((q - expected).norm() < 1e-9, "at u = {u}: {q:?}");
    }
    assert!(p
        .iter()
        .any(|(q, _)| (q - Vector3::new(0.0, 10.0, 3.0)).norm() < 0.1));
}
