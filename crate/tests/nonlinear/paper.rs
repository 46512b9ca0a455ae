//! The nonlinear-error paper's stated facts (Geng, Wu & Qiu 2018), each checked against a value
//! derived independently of the engine's own search: closed forms, symmetry, dense sampling.

use crate::common;
use common::{close, deg, Rng};
use fiveaxis::nonlinear::*;
use fiveaxis::rotary::{Group, Pose, RotaryType};
use std::f64::consts::PI;

fn peak(t: RotaryType, k0: f64, m0: f64, dk: f64, dm: f64) -> Peak {
    Deviation::new(Move::new(t, Pose::new(k0, m0), Pose::new(k0 + dk, m0 + dm))).peak()
}

fn group(g: Group) -> impl Iterator<Item = RotaryType> {
    RotaryType::ALL.into_iter().filter(move |t| t.group() == g)
}

/// Maximum of f on [0, 1] by brute force: 100 001 samples. Used as the independent reference
/// for the engine's Newton refinement.
fn dense_max(f: impl Fn(f64) -> f64) -> (f64, f64) {
    common::sampled_max(100_000, f)
}

#[test]
fn the_u_half_approximations_eq25_eq30_are_the_error_at_u_half_for_all_twelve_types() {
    // eq 25 / eq 30 are the paper's own trigonometric expressions; δ(0.5) here comes from the
    // vectors P(0.5) and n. Their agreement checks our rotation and type conventions.
    let mut rng = Rng::new(25);
    for t in RotaryType::ALL {
        for _ in 0..200 {
            let (k0, m0) = (rng.range(-PI, PI), rng.range(-PI, PI));
            let (dk, dm) = (rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let mv = Move::new(t, Pose::new(k0, m0), Pose::new(k0 + dk, m0 + dm));
            let dev = Deviation::new(mv);
            if dev.plane_sine() < 1e-3 {
                continue;
            }
            let a = approx_half(t.group(), m0, dm, dk).expect("non-degenerate");
            close(a, dev.at(0.5), 1e-12, &format!("{t} approx vs δ(0.5)"));
        }
    }
}

#[test]
fn error_does_not_depend_on_the_start_angle_of_k_fig4() {
    // Fig 4: Δθk = 30°, Δθm = 15°, θm = 10°, θk from -180° to 180°: constant.
    for t in RotaryType::ALL {
        let reference = peak(t, 0.0, deg(10.0), deg(30.0), deg(15.0)).value;
        assert!(reference > 1e-3, "{t}: the Fig 4 move has a visible error");
        for i in 0..=72 {
            let k0 = deg(-180.0 + 5.0 * i as f64);
            let v = peak(t, k0, deg(10.0), deg(30.0), deg(15.0)).value;
            close(v, reference, 1e-12, &format!("{t} θk0 = {k0}"));
        }
    }
}

#[test]
fn at_the_pole_the_error_curve_is_sin_u_dm_times_sin_1_minus_u_dk_and_eq26_is_its_value_at_half() {
    // Group I starting at θm = 0 (Group II at θm = -90°): the tool starts on the K axis, the path
    // has polar angle u·Δθm and azimuth u·Δθk about K, so its distance from the meridian plane
    // of V1 is |sin(u Δθm) sin((1-u) Δθk)| exactly. Eq 26 is that curve at u = 0.5.
    let mut worst_shortfall: f64 = 0.0;
    for t in RotaryType::ALL {
        let m0 = if t.group() == Group::I {
            0.0
        } else {
            -PI / 2.0
        };
        for i in 1..=18 {
            for j in 1..=18 {
                let (dk, dm) = (deg(5.0 * i as f64), deg(5.0 * j as f64));
                let mv = Move::new(t, Pose::new(0.3, m0), Pose::new(0.3 + dk, m0 + dm));
                let dev = Deviation::new(mv);
                for s in 0..=20 {
                    let u = s as f64 / 20.0;
                    let closed = ((u * dm).sin() * ((1.0 - u) * dk).sin()).abs();
                    close(dev.at(u), closed, 1e-12, &format!("{t} curve at u={u}"));
                }
                let exact = dev.peak().value;
                let (_, reference) = dense_max(|u| ((u * dm).sin() * ((1.0 - u) * dk).sin()).abs());
                assert!(
                    exact >= reference - 1e-15 && exact - reference < 1e-9,
                    "{t}: {exact} vs {reference}"
                );
                let eq26 = closed_form_pole(dm, dk);
                assert!(eq26 <= exact + 1e-15);
                if i == j {
                    close(eq26, exact, 1e-13, "eq 26 is exact for |Δθk| = |Δθm|");
                }
                worst_shortfall = worst_shortfall.max((exact - eq26) / exact);
            }
        }
    }
    // Over (0, 90°]², eq 26 falls short of the exact maximum by at most about 1 %.
    assert!(
        worst_shortfall > 0.005 && worst_shortfall < 0.0103,
        "{worst_shortfall}"
    );
}

#[test]
fn group_two_is_group_one_with_theta_m_shifted_by_a_quarter_turn_eq31() {
    // Exact form under our conventions: V_II(θk, θm) = V_I(θk, θm + s·90°) with s = ±1 fixed per
    // rotary-axis feature, since e_J = R_M(s·90°) e_K. Because δ_I has period 180° in θm
    // (next test), δ_II(θm, Δθm, Δθk) = δ_I(θm + 90°, Δθm, Δθk) for either sign: eq 31.
    let mut rng = Rng::new(31);
    for t2 in group(Group::II) {
        let t1 = RotaryType::ALL
            .into_iter()
            .find(|t| t.k == t2.k && t.m == t2.m && t.group() == Group::I)
            .expect("partner");
        let pose = Pose::new(0.7, -0.4);
        let shifted = |s: f64| t1.tool_vector(Pose::new(pose.k, pose.m + s * PI / 2.0));
        let plus = (t2.tool_vector(pose) - shifted(1.0)).norm() < 1e-14;
        let minus = (t2.tool_vector(pose) - shifted(-1.0)).norm() < 1e-14;
        assert!(plus ^ minus, "{t2} is {t1} shifted by exactly one of ±90°");
        for _ in 0..100 {
            let (m0, dk, dm) = (
                rng.range(-PI, PI),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            );
            let a = peak(t2, 0.0, m0, dk, dm).value;
            let b = peak(t1, 0.0, m0 + PI / 2.0, dk, dm).value;
            close(a, b, 1e-11, &format!("eq 31 {t2}/{t1}"));
            if let (Some(x), Some(y)) = (
                approx_group2(m0, dm, dk),
                approx_group1(m0 + PI / 2.0, dm, dk),
            ) {
                close(x, y, 1e-11, "eq 31 on the approximations");
            }
        }
    }
}

#[test]
fn error_has_period_pi_in_theta_m_with_the_symmetric_lines_of_eq27() {
    let mut rng = Rng::new(27);
    for t in RotaryType::ALL {
        for _ in 0..40 {
            let (m0, dk, dm) = (
                rng.range(-PI, PI),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            );
            let v = peak(t, 0.0, m0, dk, dm).value;
            close(peak(t, 0.0, m0 + PI, dk, dm).value, v, 1e-11, "period π");
            // Eq 27: symmetric about θm = Nπ/2 - Δθm/2.
            let x = rng.range(0.0, PI);
            for n in -2..=2 {
                let line = n as f64 * PI / 2.0 - dm / 2.0;
                let a = peak(t, 0.0, line + x, dk, dm).value;
                let b = peak(t, 0.0, line - x, dk, dm).value;
                close(a, b, 1e-11, &format!("{t} symmetric about N = {n}"));
            }
        }
        // π is the smallest period: half of it does not repeat the values in general.
        let a = peak(t, 0.0, 0.3, 0.5, 0.2).value;
        let b = peak(t, 0.0, 0.3 + PI / 2.0, 0.5, 0.2).value;
        assert!((a - b).abs() > 1e-3, "{t}: π/2 is not a period");
    }
    // The paper's Fig 7 lines for Δθm = π/6: -7π/12, -π/12, 5π/12, 11π/12.
    let t = RotaryType::parse("CAZ").expect("type");
    for line in [
        -7.0 * PI / 12.0,
        -PI / 12.0,
        5.0 * PI / 12.0,
        11.0 * PI / 12.0,
    ] {
        for x in [0.1, 0.4, 0.9] {
            let a = peak(t, 0.0, line + x, 2.0 * PI / 6.0, PI / 6.0).value;
            let b = peak(t, 0.0, line - x, 2.0 * PI / 6.0, PI / 6.0).value;
            close(a, b, 1e-11, "Fig 7 symmetry line");
        }
    }
}

fn argmax_range(t: RotaryType, m0: f64, n: usize) -> (f64, f64) {
    let (mut lo, mut hi) = (1.0f64, 0.0f64);
    for i in 1..=n {
        for j in 1..=n {
            let (dk, dm) = (
                PI / 2.0 * i as f64 / n as f64,
                PI / 2.0 * j as f64 / n as f64,
            );
            let p = peak(t, 0.0, m0, dk, dm);
            if p.value > 1e-9 {
                lo = lo.min(p.u);
                hi = hi.max(p.u);
            }
        }
    }
    (lo, hi)
}

#[test]
fn argmax_u_ranges_of_figs_3_and_8_at_theta_m_zero() {
    // Paper: increments in (0, π/2], θm = 0. Group I: u in [0.4535, 0.5465]; Group II:
    // [0.5019, 0.5773]. The supremum/infimum are limits as one increment tends to 0, so a finer
    // grid reaches slightly further: Group I tends to the root of tan(uπ/2) = (π/2)(1-u),
    // u = 0.45227 (and 1 - that), Group II to 0.5 at the small end.
    let root = {
        // Bisection on tan(uπ/2) - (π/2)(1-u), independent of the engine.
        let (mut a, mut b) = (0.3, 0.6);
        for _ in 0..100 {
            let c = 0.5 * (a + b);
            if (c * PI / 2.0).tan() - PI / 2.0 * (1.0 - c) > 0.0 {
                b = c
            } else {
                a = c
            }
        }
        a
    };
    for t in group(Group::I) {
        let (lo, hi) = argmax_range(t, 0.0, 45);
        assert!(lo <= 0.4535 && lo >= root - 1e-6, "{t} lo {lo}");
        assert!(hi >= 0.5465 && hi <= 1.0 - root + 1e-6, "{t} hi {hi}");
    }
    for t in group(Group::II) {
        let (lo, hi) = argmax_range(t, 0.0, 45);
        assert!((0.5 - 1e-9..=0.5019).contains(&lo), "{t} lo {lo}");
        close(hi, 0.5773, 6e-5, "Group II upper end of Fig 8");
    }
}

#[test]
fn away_from_theta_m_zero_the_argmax_leaves_the_papers_ranges() {
    // What we find elsewhere: at θm = 45° (Group I) the maximum can sit anywhere from about
    // u = 0.21 to 0.79, and the u = 0.5 value can even be zero while the maximum is not.
    for t in group(Group::I) {
        let (lo, hi) = argmax_range(t, PI / 4.0, 30);
        assert!(lo < 0.25 && hi > 0.75, "{t}: {lo}..{hi}");
    }
    let t = RotaryType::parse("CAZ").expect("type");
    let a = analyze(
        Move::new(
            t,
            Pose::new(0.0, deg(45.0)),
            Pose::new(deg(5.0), deg(135.0)),
        ),
        1.0,
        3,
    )
    .expect("valid");
    assert!(a.max > 1e-3 && a.approx.expect("plane") < 1e-12, "{a:?}");
}

#[test]
fn a_move_of_m_alone_has_no_error_and_k_alone_only_at_multiples_of_90_degrees() {
    let mut rng = Rng::new(7);
    for t in RotaryType::ALL {
        for _ in 0..50 {
            // M alone: rotation about the fixed axis R_K e_M, perpendicular to the tool: a great circle.
            let (k0, m0, dm) = (rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-3.0, 3.0));
            assert!(peak(t, k0, m0, 0.0, dm).value < 1e-12, "{t} M alone");
        }
        // K alone sweeps a cone about K with half-angle given by θm: a great circle only when
        // the cone is flat or the tool lies on K. That is θm ∈ {0, ±90°, 180°} for both groups.
        for m_deg in [-180.0, -90.0, 0.0, 90.0, 180.0] {
            assert!(
                peak(t, 0.2, deg(m_deg), deg(40.0), 0.0).value < 1e-12,
                "{t} K alone at {m_deg}"
            );
        }
        for m_deg in [-135.0, -60.0, -10.0, 1.0, 30.0, 75.0, 120.0] {
            assert!(
                peak(t, 0.2, deg(m_deg), deg(40.0), 0.0).value > 1e-5,
                "{t} K alone at {m_deg}"
            );
        }
    }
}

#[test]
fn the_u_half_approximation_never_exceeds_the_exact_maximum() {
    let mut rng = Rng::new(12);
    for t in RotaryType::ALL {
        for _ in 0..500 {
            let (m0, dk, dm) = (rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI));
            let mv = Move::new(t, Pose::new(0.0, m0), Pose::new(dk, m0 + dm));
            let a = analyze(mv, 1.0, 2).expect("valid");
            if let Some(approx) = a.approx {
                assert!(approx <= a.max + 1e-15, "{t}: {approx} > {}", a.max);
            }
        }
    }
}

#[test]
fn exact_maximum_agrees_with_dense_sampling() {
    let mut rng = Rng::new(99);
    for t in RotaryType::ALL {
        for _ in 0..12 {
            let (m0, dk, dm) = (
                rng.range(-PI, PI),
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
            );
            let mv = Move::new(t, Pose::new(0.1, m0), Pose::new(0.1 + dk, m0 + dm));
            let dev = Deviation::new(mv);
            let p = dev.peak();
            let (u_ref, v_ref) = dense_max(|u| dev.at(u));
            // The refined maximum is never below the sampled one, and above it by no more than
            // the sampling error O(h²) with h = 1e-5.
            assert!(p.value >= v_ref - 1e-14, "{t}: {} < {v_ref}", p.value);
            assert!(p.value - v_ref < 1e-8, "{t}: {} vs {v_ref}", p.value);
            close(dev.at(p.u), p.value, 1e-15, "value at the reported u");
            if (p.value - v_ref) < 1e-12 && v_ref > 1e-6 {
                // Unique maximum: same place (or the symmetric one, same value).
                assert!((p.u - u_ref).abs() < 1e-3 || (dev.at(u_ref) - p.value).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn degenerate_moves_have_a_defined_finite_answer() {
    let t = RotaryType::parse("CAZ").expect("type");
    // A full turn of K at θm = 30°: start and end coincide; the chord form gives the cone's
    // diameter 2 sin 30° = 1 (times L) at u = 0.5.
    let a = analyze(
        Move::new(t, Pose::new(0.0, deg(30.0)), Pose::new(2.0 * PI, deg(30.0))),
        50.0,
        101,
    )
    .expect("valid");
    assert_eq!(a.reference, Reference::Coincident);
    close(a.max, 50.0, 1e-9, "full turn chord");
    close(a.u_at_max, 0.5, 1e-9, "full turn at u = 0.5");
    assert!(a.approx.is_none());
    // No move at all: zero.
    let z = analyze(
        Move::new(t, Pose::new(0.4, 0.2), Pose::new(0.4, 0.2)),
        50.0,
        5,
    )
    .expect("valid");
    assert_eq!(z.reference, Reference::Coincident);
    assert!(z.max == 0.0 && z.delta.iter().all(|d| *d == 0.0));
    // A half turn of M: opposite ends; the path is a great half circle, which the best-fit plane
    // through ±V0 contains: zero.
    let o = analyze(
        Move::new(t, Pose::new(0.4, deg(-90.0)), Pose::new(0.4, deg(90.0))),
        50.0,
        5,
    )
    .expect("valid");
    assert_eq!(o.reference, Reference::Opposite);
    assert!(o.max < 1e-10);
    // Opposite ends reached with both axes: finite, and no larger than the chord bound 2L.
    let b = analyze(
        Move::new(t, Pose::new(0.0, deg(60.0)), Pose::new(PI, deg(-60.0) + PI)),
        50.0,
        5,
    );
    let b = b.expect("valid");
    assert_eq!(b.reference, Reference::Opposite);
    // The value, by a second method. CAZ: V = R_Z(θk)·R_X(θm)·e_z, θk = π·u, θm = 60° + 60°·u:
    // V(u) = (sin πu·sin θm, −cos πu·sin θm, cos θm), V0 = (0, −sin 60°, cos 60°) = −V1. Under
    // u → 1 − u, V → (x, −y, −z): the path is symmetric about the plane through ±V0 and
    // V(0.5) = (1, 0, 0), whose normal is n = V0 × e_x / |…| = (0, cos 60°, sin 60°), and the
    // least-squares fit over symmetric samples has exactly that normal (the cross term with
    // the other candidate, e_x, is odd in u − 0.5 and sums to zero; along e_x the path is far
    // from the plane, 1 at u = 0.5). So δ(u) = L·|V(u)·n|, its maximum found by dense sampling
    // (error O(h²) with h = 1e-5).
    let (s60, c60) = (deg(60.0).sin(), deg(60.0).cos());
    let delta = |u: f64| {
        let (k, m) = (PI * u, deg(60.0 + 60.0 * u));
        50.0 * (-(k.cos()) * m.sin() * c60 + m.cos() * s60).abs()
    };
    let (_, want) = dense_max(delta);
    close(b.max, want, 1e-6, "opposite ends through both axes");
    // And within the bound every plane through the origin gives: δ ≤ L.
    assert!(b.max <= 50.0 + 1e-9);
    for r in [&a, &z, &o, &b] {
        assert!(r.delta.iter().all(|d| d.is_finite()));
    }
}

#[test]
fn error_scales_with_the_length() {
    let t = RotaryType::parse("ABZ").expect("type");
    let mv = Move::new(t, Pose::new(0.0, 0.2), Pose::new(0.5, 0.6));
    let a = analyze(mv, 10.0, 3).expect("valid");
    let b = analyze(mv, 250.0, 3).expect("valid");
    close(b.max, 25.0 * a.max, 1e-12, "linear in L");
}
