//! The S-shape's functions against their definitions, each by a second route: the B-spline on
//! odd knot vectors against the Cox–de Boor sum and its derivatives, eq 6 from the surface's points,
//! `eq6_max` and the overcut map's grid point by point, the peaks of hand-written maps, the gouge
//! search kept in its window, the machine poses the same asked alone or among many, the arc-length
//! parameter against a polyline, the curve lengths, labels, the sensitivity columns' cosines, and
//! surface B with the paper's N giving its 0.0125 mm.

#![allow(clippy::unwrap_used)]
use crate::common;

use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::sshape::bspline::BSpline;
use fiveaxis::sshape::machine::{poses_along, PathBranch};
use fiveaxis::sshape::machine::{DefectPoint, DefectReference};
use fiveaxis::sshape::overcut::{eq6_max, overcut_map, Basis, OvercutMap, ToolPath};
use fiveaxis::sshape::part::{Part, Surface, SurfaceId};
use fiveaxis::sshape::study::{Design, SShapeModel, SShapeTool};
use nalgebra::Vector3;

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
/// A clamped cubic needs p + 1 = 4 points. With exactly 4 it is the Bézier curve (knots
/// 0,0,0,0,1,1,1,1), whose midpoint is (P0 + 3·P1 + 3·P2 + P3)/8 (Bernstein weights at ½);
/// with 3 or 2 points it is refused, as too few control points (not as a knot vector of the
/// wrong length, which the caller never gave).
// The refusal's reason is checked since a mutant of `clamped_uniform`'s guard survived; that
// mutant is equivalent (listed in mutants-equivalent.txt: `new` refuses with this message).
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
    for n in [3, 2] {
        let e = BSpline::clamped_uniform(3, p[..n].to_vec()).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("points: a curve of degree 3 needs at least 4 control points, got {n}")
        );
    }
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

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
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

/// Eq 6 from the module docs of `sshape::overcut`, by a second route: the tool tip of eq 2,
/// `E(u) = C1 + R_tool·N(u, 1) − L_tool·R(u)`, and the axis `R = (C1 − C0)/‖C1 − C0‖` from the
/// surface's points alone, their u-derivatives by central differences, `a = dE/du + h·dR/du`
/// with `h = L_tool − (1 − v)·‖C1 − C0‖`, `T = dC1/du` normalised (the paper's basis) or its
/// part perpendicular to `R` (the orthonormal one), `N ∥ S_u × S_v` at `v = 1`, and
/// `overcut = R_tool·(1 − |a·T|/√((a·T)² + (a·N)²))`. (N's sign does not matter there.)
fn eq6_by_hand(path: &ToolPath, s: &Surface, u: f64, v: f64, basis: Basis) -> f64 {
    let c1 = |u: f64| s.point(u, 1.0);
    let c0 = |u: f64| s.point(u, 0.0);
    let d = 1e-6;
    let du = |f: &dyn Fn(f64) -> Vector3<f64>| (f(u + d) - f(u - d)) / (2.0 * d);
    let ruling = |u: f64| (c1(u) - c0(u)).normalize();
    let normal = |u: f64| {
        let su = (c1(u + d) - c1(u - d)) / (2.0 * d);
        let n = su.cross(&(c1(u) - c0(u))).normalize();
        // outward as the surface's own normal says (the tip sits outside the part)
        if n.dot(&s.frame(u, 1.0).normal) < 0.0 {
            -n
        } else {
            n
        }
    };
    let tip = |u: f64| c1(u) + normal(u) * path.r_tool - ruling(u) * path.l_tool;
    let h = path.l_tool - (1.0 - v) * (c1(u) - c0(u)).norm();
    let a = du(&tip) + du(&ruling) * h;
    let t = du(&c1).normalize();
    let t = match basis {
        Basis::Paper => t,
        Basis::Orthonormal => (t - ruling(u) * t.dot(&ruling(u))).normalize(),
    };
    let (at, an) = (a.dot(&t), a.dot(&normal(u)));
    path.r_tool * (1.0 - at.abs() / at.hypot(an))
}

fn on_grid(i: usize, n: usize) -> f64 {
    i as f64 / (n - 1) as f64
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn eq6_is_the_tool_radius_times_one_less_sin_theta() {
    let part = Part::standard().unwrap();
    for path in [ToolPath::paper(), ToolPath::new(6.0, 50.0).unwrap()] {
        for id in SurfaceId::BOTH {
            let s = part.surface(id);
            let mut largest: f64 = 0.0;
            for iu in 1..40 {
                let u = iu as f64 / 40.0 + 0.003;
                for v in [0.0, 0.4, 1.0] {
                    for basis in [Basis::Paper, Basis::Orthonormal] {
                        let want = eq6_by_hand(&path, s, u, v, basis);
                        let got = path.overcut_eq6(s, u, v, basis);
                        assert!(
                            (got - want).abs() < 1e-6,
                            "{id:?} u {u} v {v} {basis:?}: {got} vs {want}"
                        );
                        largest = largest.max(want);
                    }
                }
            }
            assert!(largest > 0.01, "{id:?}: eq 6 reaches {largest} mm");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_largest_eq6_is_taken_over_the_whole_grid_corners_included() {
    // `eq6_max` over nu × nv points u = i/(nu − 1), v = j/(nv − 1): the largest of eq 6 there.
    let part = Part::standard().unwrap();
    let path = ToolPath::paper();
    for id in SurfaceId::BOTH {
        let s = part.surface(id);
        for (nu, nv) in [(2, 2), (3, 2), (5, 3), (9, 4)] {
            for basis in [Basis::Paper, Basis::Orthonormal] {
                let mut want = f64::NEG_INFINITY;
                for iu in 0..nu {
                    for iv in 0..nv {
                        let (u, v) = (on_grid(iu, nu), on_grid(iv, nv));
                        // at u = 0 and 1 the central difference would leave the domain: use
                        // the engine's eq 6, checked against the hand route inside
                        want = want.max(path.overcut_eq6(s, u, v, basis));
                    }
                }
                let got = eq6_max(&path, s, nu, nv, basis).unwrap();
                assert!(
                    (got - want).abs() < 1e-12,
                    "{id:?} {nu}×{nv} {basis:?}: {got} vs {want}"
                );
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_overcut_map_holds_eq6_and_the_gouge_at_each_grid_point_row_major() {
    let part = Part::standard().unwrap();
    let path = ToolPath::paper();
    let s = part.surface(SurfaceId::A);
    let (nu, nv) = (7, 3);
    let map = overcut_map(&path, s, nu, nv).unwrap();
    let u: Vec<f64> = (0..nu).map(|i| on_grid(i, nu)).collect();
    let v: Vec<f64> = (0..nv).map(|i| on_grid(i, nv)).collect();
    assert_eq!(map.u, u);
    assert_eq!(map.v, v);
    let z: Vec<f64> = v.iter().map(|v| 30.0 * v).collect();
    assert_eq!(map.z(), z);
    assert_eq!(map.eq6.len(), nu * nv);
    for (iv, &vv) in v.iter().enumerate() {
        for (iu, &uu) in u.iter().enumerate() {
            let k = iv * nu + iu;
            for (field, basis) in [
                (&map.eq6, Basis::Orthonormal),
                (&map.eq6_paper, Basis::Paper),
            ] {
                let want = path.overcut_eq6(s, uu, vv, basis);
                assert!((field[k] - want).abs() < 1e-12, "{basis:?} u {uu} v {vv}");
            }
            assert_eq!(map.exact[k], path.deviation(s, uu, vv), "u {uu} v {vv}");
        }
    }
    // the inner points against the hand route of eq 6
    for (iu, &uu) in u.iter().enumerate().take(nu - 1).skip(1) {
        let want = eq6_by_hand(&path, s, uu, 0.5, Basis::Orthonormal);
        assert!((map.eq6[nu + iu] - want).abs() < 1e-6);
    }
}

/// A map written by hand: u = 0, ½, 1 and v = 0, ½, 1 (z = 0, 15, 30 mm).
fn hand_map(eq6: Vec<f64>, exact: Vec<f64>) -> OvercutMap {
    OvercutMap {
        u: vec![0.0, 0.5, 1.0],
        v: vec![0.0, 0.5, 1.0],
        eq6_paper: eq6.iter().map(|x| 2.0 * x).collect(),
        eq6,
        exact,
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_peaks_are_the_largest_values_where_they_are_the_first_of_ties() {
    // `max_of`: the largest value of a row-major field [iv·nu + iu] and its (u[iu], v[iv]).
    let map = hand_map(vec![0.0; 9], vec![0.0; 9]);
    for k in 0..9 {
        let mut field = vec![0.25; 9];
        field[k] = 0.75;
        assert_eq!(
            map.max_of(&field),
            (0.75, map.u[k % 3], map.v[k / 3]),
            "k {k}"
        );
    }
    // ties: the first in row-major order
    assert_eq!(
        map.max_of(&[0.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 3.0, 3.0]),
        (3.0, 1.0, 0.5)
    );
    // peaks: eq 6 largest at (u ½, z 30), the gouge −δ largest at (u 1, z 15)
    let mut eq6 = vec![0.1; 9];
    eq6[7] = 0.4;
    let mut exact = vec![-0.001; 9];
    exact[5] = -0.02;
    let p = hand_map(eq6, exact).peaks();
    assert_eq!(p.eq6, 0.4);
    assert_eq!(p.eq6_paper, 0.8);
    assert_eq!(p.at_eq6, [0.5, 30.0]);
    assert_eq!(p.gouge, 0.02);
    assert_eq!(p.at_gouge, [1.0, 15.0]);
    // nowhere gouged: the gouge is 0, not the smallest undercut
    let p = hand_map(vec![0.1; 9], vec![0.003; 9]).peaks();
    assert_eq!(p.gouge, 0.0);
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_exact_deviation_is_searched_inside_its_window_only() {
    // `deviation_in(p, lo, hi)`: the smallest clearance of p from the tool at u' ∈ [lo, hi],
    // and that u'. A point cut at u ≈ 0.7, searched over [0.3, 0.5]: the answer lies in the
    // window, at the smallest of a dense scan of it.
    let part = Part::standard().unwrap();
    let path = ToolPath::paper();
    for id in SurfaceId::BOTH {
        let s = part.surface(id);
        for (u, lo, hi) in [(0.7, 0.3, 0.5), (0.2, 0.35, 0.6), (0.55, 0.5, 0.6)] {
            let p = s.point(u, 0.5);
            let (d, at) = path.deviation_in(s, &p, lo, hi, 40);
            assert!(at >= lo && at <= hi, "{id:?} [{lo}, {hi}]: u' = {at}");
            let scan = (0..=4000)
                .map(|i| {
                    let x = lo + (hi - lo) * i as f64 / 4000.0;
                    path.clearance(&path.at(s, x), &p)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(
                d <= scan + 1e-12 && d > scan - 1e-4,
                "{id:?}: {d} vs {scan}"
            );
            assert!((path.clearance(&path.at(s, at), &p) - d).abs() < 1e-12);
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_poses_do_not_depend_on_which_parameters_are_asked_for() {
    // `poses_along` follows the path from u = 0 in small steps whatever `us` holds, so the pose
    // at a parameter is the same asked alone or among 1301 others (C is carried through the
    // vertical middle of the S, where the tool axis alone does not fix it).
    let on = common::chanal::on(common::chanal::PAPER_L0);
    let part = Part::standard().unwrap();
    let path = ToolPath::paper();
    let dense: Vec<f64> = (0..=1300).map(|i| i as f64 / 1300.0).collect();
    for id in SurfaceId::BOTH {
        let s = part.surface(id);
        for branch in [PathBranch::Paper, PathBranch::Continuous] {
            let all = poses_along(&on, &path, s, &dense, branch).unwrap();
            let few = poses_along(&on, &path, s, &[1.0, 0.5, 0.25, 0.7], branch).unwrap();
            for (pose, i) in few.iter().zip([1300, 650, 325, 910]) {
                for (a, b) in pose.q.iter().zip(&all[i].q) {
                    assert!(
                        (a - b).abs() < 1e-6,
                        "{id:?} {branch:?} u {}: {a} vs {b}",
                        dense[i]
                    );
                }
                assert_eq!(pose.singular, all[i].singular);
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn eq6_is_largest_at_the_bottom_of_every_ruling() {
    // Eq 6 is zero at v = 1, where the tool's section at h = L_tool touches the top curve
    // (a·N = 0 there, sin θ = 1), and grows down the ruling: along every ruling of the
    // standard's surfaces it is largest at the bottom, v = 0. (This makes the mutants of
    // `eq6_max`'s v grid that keep v = 0 on it equivalent: see mutants-equivalent.txt.)
    let part = Part::standard().unwrap();
    for path in [ToolPath::paper(), ToolPath::new(6.0, 50.0).unwrap()] {
        for id in SurfaceId::BOTH {
            let s = part.surface(id);
            for iu in 0..=400 {
                let u = iu as f64 / 400.0;
                for basis in [Basis::Paper, Basis::Orthonormal] {
                    let top = path.overcut_eq6(s, u, 1.0, basis);
                    assert!(top.abs() < 1e-9, "{id:?} u {u} {basis:?}: {top} at the top");
                    let bottom = path.overcut_eq6(s, u, 0.0, basis);
                    for iv in 1..=60 {
                        let v = iv as f64 / 60.0;
                        let e = path.overcut_eq6(s, u, v, basis);
                        assert!(
                            e <= bottom + 1e-12,
                            "{id:?} u {u} v {v} {basis:?}: {e} > {bottom}"
                        );
                    }
                }
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_surfaces_are_named_a_and_b() {
    assert_eq!(SurfaceId::A.name(), "A");
    assert_eq!(SurfaceId::B.name(), "B");
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_mesh_is_the_surface_at_an_even_grid_row_major() {
    // `mesh(nu, nv)`: S(iu/(nu − 1), iv/(nv − 1)) at [iv·nu + iu], x, y and z apart.
    let part = Part::standard().unwrap();
    let s = part.surface(SurfaceId::B);
    for (nu, nv) in [(2, 2), (5, 3), (4, 7)] {
        let [x, y, z] = s.mesh(nu, nv);
        assert_eq!(x.len(), nu * nv);
        for iv in 0..nv {
            for iu in 0..nu {
                let p = s.point(on_grid(iu, nu), on_grid(iv, nv));
                let k = iv * nu + iu;
                assert_eq!(
                    [x[k], y[k], z[k]],
                    [p.x, p.y, p.z],
                    "{nu}×{nv} ({iu}, {iv})"
                );
            }
        }
    }
}

/// Arc length of the iso-curve `v` from u = 0 to `u`, as the length of a polyline of 4000
/// chords and 2000 chords combined by Richardson's rule (the chord's error is O(h²)).
fn polyline_length(s: &Surface, v: f64, u: f64) -> f64 {
    let chords = |n: usize| -> f64 {
        (0..n)
            .map(|i| {
                let a = u * i as f64 / n as f64;
                let b = u * (i + 1) as f64 / n as f64;
                (s.point(b, v) - s.point(a, v)).norm()
            })
            .sum()
    };
    let (coarse, fine) = (chords(2_000), chords(4_000));
    (4.0 * fine - coarse) / 3.0
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_parameter_at_an_arc_length_is_where_the_curve_is_that_long() {
    // `u_at_arc_length(v, s)`: the u at which the iso-curve v has length s from u = 0, s clamped
    // to [0, the curve's length]; `curve_length(v)` is the whole length.
    let part = Part::standard().unwrap();
    for id in SurfaceId::BOTH {
        let s = part.surface(id);
        for v in [0.0, 0.35, 1.0] {
            let total = polyline_length(s, v, 1.0);
            assert!((s.curve_length(v) - total).abs() < 1e-6, "{id:?} v {v}");
            for f in [0.013, 0.1, 0.25, 0.4, 0.5, 0.61, 0.77, 0.9, 0.999] {
                let want = f * total;
                let u = s.u_at_arc_length(v, want);
                let got = polyline_length(s, v, u);
                assert!(
                    (got - want).abs() < 1e-8,
                    "{id:?} v {v} s {want}: u {u} is {got} along"
                );
            }
            assert!(s.u_at_arc_length(v, -5.0).abs() < 1e-12);
            assert!((s.u_at_arc_length(v, total + 5.0) - 1.0).abs() < 1e-12);
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_four_curve_lengths_are_top_a_top_b_bottom_a_bottom_b() {
    // `curve_lengths`: the measurement curves at z = 25 mm (top) and 11 mm (bottom), v = z/30.
    let part = Part::standard().unwrap();
    let mut want = Vec::new();
    for z in [25.0, 11.0] {
        for id in SurfaceId::BOTH {
            want.push(polyline_length(part.surface(id), z / 30.0, 1.0));
        }
    }
    let got = part.curve_lengths();
    assert_eq!(got.len(), 4);
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-6, "{got:?} vs {want:?}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn a_point_is_labelled_by_its_curve_and_number() {
    let points = Part::standard_points().unwrap();
    assert_eq!(points[6].label(), "top 7");
    assert_eq!(points[50].label(), "bottom 1");
    assert_eq!(points[99].label(), "bottom 50");
}

/// The S-shape design on an A/C trunnion table (E_Z0C moves C along its own axis: no effect).
fn trunnion_design() -> Design {
    let m = Machine::from_value(
        &serde_json::json!({ "kind": "table-table", "type": "CAZ", "linear": "table-xy",
            "geometry": { "tableHeight": 80, "rotaryOffset": 15 } }),
        "machine",
    )
    .unwrap();
    let model = SShapeModel {
        branch: PathBranch::Paper,
        reference: DefectReference::WorkOrigin,
        point: DefectPoint::Tip,
    };
    Design::new(
        &m,
        &SShapeTool {
            r_tool: 10.0,
            l_tool: 35.0,
        },
        &model,
    )
    .unwrap()
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_column_cosine_and_the_alike_pairs_follow_the_sensitivity_columns() {
    // `column_cosine(a, b)`: a·b/(‖a‖·‖b‖) of the two errors' columns of `rows`, None for a name
    // the machine does not have or a column of zeros; `alike_pairs(min)`: every pair (in the
    // errors' order) with |cos| ≥ min, the largest |cos| first.
    let d = trunnion_design();
    let names: Vec<&str> = d.errors().iter().map(|e| e.name).collect();
    let col = |k: usize| -> Vec<f64> { d.rows.iter().map(|r| r[k]).collect() };
    let norm = |c: &[f64]| c.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut zero = 0;
    let mut want_pairs = Vec::new();
    for (i, a) in names.iter().enumerate() {
        for (j, b) in names.iter().enumerate() {
            let (ca, cb) = (col(i), col(j));
            let (na, nb) = (norm(&ca), norm(&cb));
            let got = d.column_cosine(a, b);
            if na == 0.0 || nb == 0.0 {
                assert_eq!(got, None, "{a} {b}");
                zero += usize::from(i == j);
                continue;
            }
            let want = ca.iter().zip(&cb).map(|(x, y)| x * y).sum::<f64>() / (na * nb);
            assert!(
                (got.unwrap() - want).abs() < 1e-12,
                "{a} {b}: {got:?} vs {want}"
            );
            if i == j {
                assert!((want - 1.0).abs() < 1e-12);
            }
            if i < j && want.abs() >= 0.99 {
                want_pairs.push((*a, *b, want));
            }
        }
    }
    assert_eq!(zero, 1, "E_Z0C alone has no effect");
    assert_eq!(d.column_cosine("E_Z0C", "E_X0C"), None);
    assert_eq!(d.column_cosine("E_X0Q", "E_X0C"), None);
    assert_eq!(d.column_cosine("E_X0C", "E_X0Q"), None);
    let pairs = d.alike_pairs(0.99);
    assert!(pairs.len() >= 3, "{pairs:?}");
    assert!(
        pairs.windows(2).all(|w| w[0].2.abs() >= w[1].2.abs()),
        "{pairs:?}"
    );
    let key = |p: &(&str, &str, f64)| (p.0.to_string(), p.1.to_string());
    let mut got: Vec<_> = pairs.iter().map(key).collect();
    let mut want: Vec<_> = want_pairs.iter().map(key).collect();
    got.sort();
    want.sort();
    assert_eq!(got, want);
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn the_design_points_are_the_standard_points_in_list_order() {
    let d = trunnion_design();
    let points = Part::standard_points().unwrap();
    let got = d.points();
    assert_eq!(got.len(), 100);
    for (g, p) in got.iter().zip(points) {
        assert_eq!(g.label(), p.label());
        assert_eq!((g.surface, g.u), (p.surface, p.u));
    }
}

// Found by cargo-mutants: a mutant in `crate/src/sshape/` survived every other test.
#[test]
fn surface_b_with_the_papers_sign_of_n_gives_the_papers_overcut() {
    // Chanal et al. print 0.0125 mm for surface B's eq 6 maximum, with N = R × T on both
    // surfaces, which puts the tool on B's inner side (facing A): `b_paper_side` is eq 6 over B
    // with its normal reversed, and the paper's number within 5 % (the grid's and the paper's
    // rounding); B's own (outward) side is another number.
    let path = ToolPath::paper();
    let o = fiveaxis::sshape::study::overcut(&path, 261, 4).unwrap();
    let (paper_t, perp_t) = o.b_paper_side;
    assert!((paper_t / 0.0125 - 1.0).abs() < 0.05, "{paper_t}");
    let part = Part::standard().unwrap();
    let mut inner = part.surface(SurfaceId::B).clone();
    inner.outward = -inner.outward;
    let want = eq6_max(&path, &inner, 261, 4, Basis::Orthonormal).unwrap();
    assert!((perp_t - want).abs() < 1e-15, "{perp_t} vs {want}");
    let outward =
        o.b.eq6_paper
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        (outward / 0.0125 - 1.0).abs() > 0.05,
        "B's outward side: {outward}"
    );
}
