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

/// Curves off the unit domain with repeated interior knots (degree, knots, points).
fn odd_curves() -> Vec<BSpline> {
    let pts = |n: usize| -> Vec<Vector3<f64>> {
        (0..n)
            .map(|i| {
                let t = i as f64;
                Vector3::new(t, (1.3 * t).sin() * 4.0, 0.2 * t * t - t)
            })
            .collect()
    };
    vec![
        // Cubic on [2, 5], a double knot at 3.5.
        BSpline::new(
            3,
            vec![2.0, 2.0, 2.0, 2.0, 2.5, 3.5, 3.5, 4.0, 5.0, 5.0, 5.0, 5.0],
            pts(8),
        )
        .unwrap(),
        // Quadratic on [−1, 3]: knots before the domain are not all equal.
        BSpline::new(
            2,
            vec![-3.0, -2.0, -1.0, 0.0, 0.0, 1.5, 3.0, 4.0, 6.0],
            pts(6),
        )
        .unwrap(),
        // Quadratic whose last interior knot reaches the domain's end (knots[n] = knots[n + 1]):
        // the last non-empty span is the one before.
        BSpline::new(2, vec![0.0, 0.0, 0.0, 1.0, 3.0, 3.0, 3.0, 3.0], pts(5)).unwrap(),
        // Quartic and quintic (the largest degree), clamped, uneven knots.
        BSpline::new(
            4,
            vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.4, 1.0, 1.0, 1.0, 1.0, 1.0],
            pts(7),
        )
        .unwrap(),
        BSpline::new(
            5,
            vec![
                1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 1.7, 2.6, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0,
            ],
            pts(9),
        )
        .unwrap(),
    ]
}

/// `N_(i,a)(u)` by the module docs' recursion on the domain's intervals `[u_i, u_(i+1))`,
/// `p ≤ i ≤ n` (`span` = `[p, n]`), the last non-empty one (`last`) closed at its right end.
fn cox_de_boor(t: &[f64], i: usize, a: usize, u: f64, span: (usize, usize), last: usize) -> f64 {
    if a == 0 {
        let inside = (span.0..=span.1).contains(&i);
        return f64::from(inside && t[i] <= u && (u < t[i + 1] || (i == last && u == t[i + 1])));
    }
    let f = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
    f(u - t[i], t[i + a] - t[i]) * cox_de_boor(t, i, a - 1, u, span, last)
        + f(t[i + a + 1] - u, t[i + a + 1] - t[i + 1]) * cox_de_boor(t, i + 1, a - 1, u, span, last)
}

#[test]
fn the_domain_the_span_and_the_point_follow_their_definitions_on_any_knot_vector() {
    for c in odd_curves() {
        let (p, t, n) = (c.degree(), c.knots(), c.points().len() - 1);
        // Domain [u_p, u_(n+1)].
        assert_eq!(c.domain(), (t[p], t[n + 1]));
        let (a, b) = (t[p], t[n + 1]);
        // The last non-empty span of the domain.
        let last = (p..=n).rev().find(|&s| t[s] < t[s + 1]).unwrap();
        for k in 0..=400 {
            let u = a - 0.5 + (b - a + 1.0) * k as f64 / 400.0;
            let uc = u.clamp(a, b);
            let s = c.span(u);
            assert!((p..=n).contains(&s), "{t:?} u {u}: span {s}");
            if uc < b {
                assert!(t[s] <= uc && uc < t[s + 1], "{t:?} u {u}: span {s}");
            } else {
                assert_eq!(s, last, "{t:?} at the end");
            }
            // Every knot itself, too (a knot starts its span).
            let want: Vector3<f64> = (0..=n)
                .map(|i| c.points()[i] * cox_de_boor(t, i, p, uc, (p, n), last))
                .sum();
            assert!(
                (c.point(u) - want).norm() < 1e-12,
                "{t:?} u {u}: {} vs {want}",
                c.point(u)
            );
        }
        for &k in t {
            if (a..b).contains(&k) {
                let s = c.span(k);
                assert!(t[s] <= k && k < t[s + 1], "{t:?} knot {k}: span {s}");
            }
        }
        assert_eq!(c.span(b), last);
        assert_eq!(c.span(b + 10.0), last);
        assert_eq!(c.span(a - 10.0), c.span(a));
    }
}

#[test]
fn the_derivatives_are_those_of_the_cox_de_boor_sum() {
    // Central differences of the module docs' sum, away from the knots (where a derivative may
    // jump): h = 1e-5 of the domain for C' (truncation ~h², ~1e-8 here), 1e-3 for C'' (~h² and
    // rounding 1e-16/h², below 1e-8), against values of order 10 to 10⁴.
    for c in odd_curves() {
        let (p, t, n) = (c.degree(), c.knots(), c.points().len() - 1);
        let (a, b) = c.domain();
        let last = (p..=n).rev().find(|&s| t[s] < t[s + 1]).unwrap();
        let sum = |u: f64| -> Vector3<f64> {
            (0..=n)
                .map(|i| c.points()[i] * cox_de_boor(t, i, p, u, (p, n), last))
                .sum()
        };
        let mut checked = 0;
        for k in 1..200 {
            let u = a + (b - a) * k as f64 / 200.0;
            if t.iter().any(|&knot| (u - knot).abs() < 0.01 * (b - a)) {
                continue;
            }
            let e = c.eval(u);
            let h1 = 1e-5 * (b - a);
            let d1 = (sum(u + h1) - sum(u - h1)) / (2.0 * h1);
            let h2 = 1e-3 * (b - a);
            let d2 = (sum(u + h2) - 2.0 * sum(u) + sum(u - h2)) / (h2 * h2);
            let (s1, s2) = (1.0 + d1.norm(), 1.0 + d2.norm());
            assert!(
                (e.d1 - d1).norm() < 1e-6 * s1,
                "{t:?} u {u}: C' {} vs {d1}",
                e.d1
            );
            assert!(
                (e.d2 - d2).norm() < 1e-4 * s2,
                "{t:?} u {u}: C'' {} vs {d2}",
                e.d2
            );
            checked += 1;
        }
        assert!(checked > 100, "{t:?}");
    }
}

#[test]
fn a_missing_point_is_named_on_its_own_curve() {
    // Module docs of `sshape::identify`: 50 points on each curve, a missing point is named.
    // Every point but top 30 (surface B of the top curve) and bottom 1.
    let mut text = String::from("curve,point,deviation_mm\n");
    for curve in ["top", "bottom"] {
        for point in 1..=50 {
            if (curve, point) != ("top", 30) && (curve, point) != ("bottom", 1) {
                text.push_str(&format!("{curve},{point},0.001\n"));
            }
        }
    }
    let e = fiveaxis::sshape::identify::parse_measurements(&text).unwrap_err();
    assert_eq!(e.field, "csv");
    assert!(
        e.message
            .ends_with("2 of the 100 points are missing: top 30, bottom 1"),
        "{e}"
    );
}
