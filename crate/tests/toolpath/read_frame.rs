//! Frames of the readers (`fiveaxis::toolpath::read::frame`): a frame given by its axes or by
//! a matrix read from a file is accepted within 1e-4 of orthonormal and made exactly so.

use fiveaxis::toolpath::read::frame::Frame;
use nalgebra::{Matrix3, Vector3};

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
