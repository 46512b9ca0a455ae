//! The deviation function of a move against its definition in the module docs (eqs 9, 10, 19–21
//! and the coincident-ends chord), its maximum against a brute force, the documented evaluation
//! counts of the three ways to the maximum, eqs 25/26/30, `analyze`'s lengths, and the
//! opposite-ends plane as the least-squares eigenvector.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, Rng};
use fiveaxis::nonlinear::{
    analyze, approx_group1, approx_group2, approx_half, closed_form_pole, max_errors, split_within,
    starts_at_pole, sweep_increments, sweep_start_m, Deviation, Move, Reference,
};
use fiveaxis::rotary::{Group, Pose, RotaryType};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// `P(u)` by eq 10's linear interpolation of the angles and eq 9's orientation.
fn p_at(mv: &Move, u: f64) -> Vector3<f64> {
    let pose = Pose::new(
        mv.start.k + u * (mv.end.k - mv.start.k),
        mv.start.m + u * (mv.end.m - mv.start.m),
    );
    mv.rtype.tool_vector(pose)
}

fn random_move(rng: &mut Rng, t: RotaryType, span: f64) -> Move {
    let start = Pose::new(rng.range(-3.0, 3.0), rng.range(-1.4, 1.4));
    let end = Pose::new(
        start.k + rng.range(-span, span),
        start.m + rng.range(-span, span),
    );
    Move::new(t, start, end)
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_deviation_is_the_distance_from_the_plane_of_the_ends() {
    // δ(u)/L = |P(u)·n|, n = V0 × V1/|V0 × V1|; plane_sine = |V0 × V1|; the maximum is the
    // largest of δ(u) over [0, 1] (a brute force of 20 001 samples: within its step's O(h²)).
    let mut rng = Rng::new(915);
    let mut checked = 0;
    for t in RotaryType::ALL {
        for _ in 0..12 {
            let mv = random_move(&mut rng, t, 1.2);
            let (v0, v1) = (p_at(&mv, 0.0), p_at(&mv, 1.0));
            let cross = v0.cross(&v1);
            let d = Deviation::new(mv);
            close(d.plane_sine(), cross.norm(), 1e-12, "plane sine");
            if cross.norm() < 1e-3 {
                continue;
            }
            assert_eq!(d.reference(), Reference::Plane);
            let n = cross / cross.norm();
            for u in [0.0, 0.1, 0.37, 0.5, 0.9, 1.0] {
                close(d.at(u), p_at(&mv, u).dot(&n).abs(), 1e-12, "δ(u)/L");
            }
            let (_, max) = common::sampled_max(20_000, |u| p_at(&mv, u).dot(&n).abs());
            let peak = d.peak();
            assert!(
                peak.value >= max - 1e-12 && peak.value <= max + 1e-6,
                "{t:?} {mv:?}: {} vs {max}",
                peak.value
            );
            close(
                d.at(peak.u),
                peak.value,
                1e-12,
                "the peak's value is δ at its u",
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn coincident_ends_give_the_chord_from_the_start() {
    // A full turn of K (θm fixed off the pole) brings the tool back: V0 = V1, and δ(u)/L is the
    // chord |P(u) − V0|. The tool turns about K's axis, so the chord is 2·sin α·|sin(πu)| with
    // α the angle of V0 from that axis: largest, 2·sin α, at u = ½.
    for t in RotaryType::ALL {
        for (k0, m) in [(0.0, 0.4), (0.7, -1.1)] {
            let mv = Move::new(t, Pose::new(k0, m), Pose::new(k0 + 2.0 * PI, m));
            let d = Deviation::new(mv);
            assert_eq!(d.reference(), Reference::Coincident, "{t:?}");
            let v0 = p_at(&mv, 0.0);
            for u in [0.1, 0.25, 0.5, 0.8] {
                close(d.at(u), (p_at(&mv, u) - v0).norm(), 1e-12, "chord");
            }
            // sin α from the chord at u = ½ (P(½) is V0 turned by π: |P(½) − V0| = 2 sin α).
            let two_sin_alpha = (p_at(&mv, 0.5) - v0).norm();
            assert!(two_sin_alpha > 0.1);
            close(
                d.at(0.25),
                two_sin_alpha * (PI / 4.0).sin(),
                1e-12,
                "2 sin α sin(π/4)",
            );
            let peak = d.peak();
            close(peak.value, two_sin_alpha, 1e-12, "largest chord");
            close(peak.u, 0.5, 1e-6, "at u = ½");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_evaluations_counted_are_those_the_docs_state() {
    // Module docs, "Exact maximum": a move of one axis takes one evaluation; the dense method at
    // least 17 (16 + 4·(|Δθk| + |Δθm|) steps and the refinement); a short move of both axes
    // close to a great circle "a handful" (2 to 5 on average).
    let mut rng = Rng::new(77);
    for t in RotaryType::ALL {
        for _ in 0..3 {
            let start = Pose::new(rng.range(-3.0, 3.0), rng.range(0.3, 1.2));
            let k_only = Move::new(t, start, Pose::new(start.k + 0.5, start.m));
            let m_only = Move::new(t, start, Pose::new(start.k, start.m - 0.4));
            // Past two turns (the tool passes its extremes more than once; by symmetry u = ½ is
            // an extremum, here the one on the short arc between V0 and V1, and the largest |g|
            // is at u = ½ ± π/Δθ, on the long arc).
            let k_long = Move::new(t, start, Pose::new(start.k - 4.0 * PI - 1.0, start.m));
            let m_long = Move::new(t, start, Pose::new(start.k, start.m + 4.0 * PI + 0.7));
            let k_back = Move::new(t, start, Pose::new(start.k + 4.0 * PI + 1.0, start.m));
            for (mv, long) in [
                (k_only, false),
                (m_only, false),
                (k_long, true),
                (k_back, true),
                (m_long, true),
            ] {
                let d = Deviation::new(mv);
                if d.reference() == Reference::Plane {
                    let (peak, n) = d.peak_counted();
                    assert_eq!(n, 1, "{t:?} {mv:?}");
                    close(peak.value, d.peak_dense().value, 1e-12, "one-axis peak");
                    let (v0, v1) = (p_at(&mv, 0.0), p_at(&mv, 1.0));
                    let n = v0.cross(&v1).normalize();
                    let (_, max) = common::sampled_max(20_000, |u| p_at(&mv, u).dot(&n).abs());
                    assert!(
                        peak.value >= max - 1e-12 && peak.value <= max + 1e-6,
                        "{t:?}"
                    );
                    // The peak's u is where δ has that value; of the mirror pair u, 1 − u
                    // (equal by symmetry) the earlier, as `single_axis_extremum` documents.
                    close(d.at(peak.u), peak.value, 1e-12, "δ at the peak's u");
                    if long && peak.value > 1e-6 {
                        assert!(peak.u < 0.5, "{t:?} {mv:?}: u {}", peak.u);
                        close(d.at(1.0 - peak.u), peak.value, 1e-12, "its mirror");
                    }
                }
            }
        }
        // A full turn: coincident ends, the dense method.
        let full = Move::new(t, Pose::new(0.0, 0.5), Pose::new(2.0 * PI, 0.5));
        let (_, n) = Deviation::new(full).peak_counted();
        assert!((17 + 4 * 6..400).contains(&n), "{t:?}: {n}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_dense_method_finds_the_largest_deviation_of_any_move() {
    // `peak_dense`, the reference method for every move: its maximum is that of δ over [0, 1],
    // against 20 001 samples, whose own shortfall is at most max|g''|·h²/8 ≤ S²·h²/8 (module
    // docs: |g⁽ⁿ⁾| ≤ Sⁿ, S = |Δθk| + |Δθm|); its u is where δ has that value. Moves up to two
    // turns of both axes (several maxima), planes, coincident and opposite ends.
    let mut rng = Rng::new(4242);
    for t in RotaryType::ALL {
        let mut moves: Vec<Move> = (0..4).map(|_| random_move(&mut rng, t, 13.0)).collect();
        moves.push(random_move(&mut rng, t, 0.3));
        moves.push(Move::new(
            t,
            Pose::new(0.3, 0.6),
            Pose::new(0.3 + 6.0 * PI, 0.6),
        ));
        for mv in moves {
            let d = Deviation::new(mv);
            let peak = d.peak_dense();
            let (_, max) = common::sampled_max(20_000, |u| d.at(u));
            let s = (mv.end.k - mv.start.k).abs() + (mv.end.m - mv.start.m).abs();
            let slack = s * s * (1.0 / 20_000.0_f64).powi(2) / 8.0 + 1e-13;
            assert!(
                peak.value >= max - 1e-13 && peak.value <= max + slack,
                "{t:?} {mv:?}: {} vs {max}",
                peak.value
            );
            close(d.at(peak.u), peak.value, 1e-13, "δ at the dense peak's u");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_dense_method_samples_16_plus_4_s_steps() {
    // Module docs: g is sampled at 16 + 4·S steps (S in radians), then each local maximum is
    // refined. Three full turns of K bring the tool back (coincident ends: the dense method):
    // S = 6π, so at least 16 + ⌈24π⌉ + 1 = 93 evaluations.
    for t in RotaryType::ALL {
        let mv = Move::new(t, Pose::new(0.2, 0.5), Pose::new(0.2 + 6.0 * PI, 0.5));
        let d = Deviation::new(mv);
        assert_eq!(d.reference(), Reference::Coincident);
        let (peak, n) = d.peak_counted();
        assert!((93..93 + 3 * 70).contains(&n), "{t:?}: {n}");
        // the chord of a full turn, three times over: largest at u = 1/6, ½ or 5/6
        assert!(
            [1.0 / 6.0, 0.5, 5.0 / 6.0]
                .iter()
                .any(|u| (peak.u - u).abs() < 1e-6),
            "{t:?}: {peak:?}"
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn eqs_25_and_30_are_the_deviation_at_mid_move() {
    // Eq 25 (Group I) and eq 30 (Group II) give δ(½)/L in closed form from θm0, Δθm, Δθk: the
    // same number as |P(½)·n| from the vectors, for every type of the group; `None` where
    // |V0 × V1| vanishes (no move).
    let mut rng = Rng::new(2530);
    for t in RotaryType::ALL {
        let eq = |m: f64, dm: f64, dk: f64| match t.group() {
            Group::I => approx_group1(m, dm, dk),
            Group::II => approx_group2(m, dm, dk),
        };
        for _ in 0..20 {
            let mv = random_move(&mut rng, t, 1.5);
            let (dk, dm) = (mv.end.k - mv.start.k, mv.end.m - mv.start.m);
            let d = Deviation::new(mv);
            if d.plane_sine() < 1e-6 {
                continue;
            }
            close(eq(mv.start.m, dm, dk).unwrap(), d.at(0.5), 1e-12, "δ(½)/L");
        }
        assert_eq!(eq(0.4, 0.0, 0.0), None, "{t:?}: no move");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn opposite_ends_take_the_least_squares_plane_of_the_path() {
    // V1 = −V0 (module docs): the reference plane through ±V0 fitted to the path sampled at
    // 257 equal steps of u, i.e. the unit n ⊥ V0 that minimises Σ (P(u_i)·n)². A full turn of K
    // with a half turn of M (home ⊥ M's axis, so that M's half turn reverses the tool), and half
    // a turn of K with M from m0 to π − m0 (which reverses the tool on Group I), from general
    // starts and from the home pose (V0 along x, y or z).
    let mut seen = 0;
    for t in RotaryType::ALL {
        for (k0, m0) in [(0.3, 0.4), (-1.0, 1.1), (0.0, 0.0), (0.7, 0.3)] {
            let moves = [
                Move::new(t, Pose::new(k0, m0), Pose::new(k0 + 2.0 * PI, m0 + PI)),
                Move::new(t, Pose::new(k0, m0), Pose::new(k0 + PI, PI - m0)),
            ];
            for mv in moves {
                if Deviation::new(mv).reference() == Reference::Opposite {
                    seen += 1;
                    assert_least_squares_plane(&mv);
                }
            }
        }
    }
    assert!(seen >= 30, "{seen} moves with opposite ends");
}

/// The move's reference normal is the unit n ⊥ V0 that minimises Σ (P(u_i)·n)² over 257 equal
/// steps of u (the smaller eigenvalue of the sums' 2 × 2 matrix in a basis of the test's own), and
/// δ(u) is |P·n|.
fn assert_least_squares_plane(mv: &Move) {
    let d = Deviation::new(*mv);
    let v0 = p_at(mv, 0.0);
    let n = d.normal();
    close(n.norm(), 1.0, 1e-12, "unit normal");
    close(n.dot(&v0), 0.0, 1e-12, "n ⊥ V0");
    let samples: Vec<Vector3<f64>> = (0..257).map(|i| p_at(mv, i as f64 / 256.0)).collect();
    let sum = |n: &Vector3<f64>| samples.iter().map(|p| p.dot(n).powi(2)).sum::<f64>();
    // The least of Σ (P·n)² over unit n = e1·cos φ + e2·sin φ is the smaller eigenvalue of the
    // 2 × 2 matrix [a b; b c] of the sums in a basis of the test's own.
    let e1 = v0.cross(&Vector3::new(0.3, -0.5, 0.8)).normalize();
    let e2 = v0.cross(&e1);
    let (a, b, c) = (
        sum(&e1),
        0.5 * (sum(&(e1 + e2)) - sum(&e1) - sum(&e2)),
        sum(&e2),
    );
    let least = 0.5 * (a + c) - (0.25 * (a - c).powi(2) + b * b).sqrt();
    close(
        sum(&n),
        least,
        1e-12 * (1.0 + a + c),
        "the least sum of squares",
    );
    // Where the two eigenvalues stand apart, the normal is its eigenvector (up to sign).
    let gap = 2.0 * (0.25 * (a - c).powi(2) + b * b).sqrt();
    if gap > 1e-3 * (a + c) {
        let (x, y) = if (least - a).abs() > (least - c).abs() {
            (b, least - a)
        } else {
            (least - c, b)
        };
        let want = (e1 * x + e2 * y).normalize();
        let off = (n - want).norm().min((n + want).norm());
        assert!(
            off < 1e-9,
            "{mv:?}: the normal is {off:e} off the eigenvector"
        );
    }
    close(
        d.at(0.37),
        p_at(mv, 0.37).dot(&n).abs(),
        1e-12,
        "δ(u) from that plane",
    );
}

/// `g(u) = P(u)·n` of a plane move and its second and third derivatives at u = ½, by central
/// differences of eq 10's path (steps 1e-3 and 4e-3: errors about 1e-7·S⁴ and 1e-5·S⁵, far
/// inside the test's factor-of-two margins).
fn g_jet_by_differences(mv: &Move) -> (f64, f64) {
    let n = p_at(mv, 0.0).cross(&p_at(mv, 1.0)).normalize();
    let g = |u: f64| p_at(mv, u).dot(&n);
    let h = 1e-3;
    let g2 = (g(0.5 + h) - 2.0 * g(0.5) + g(0.5 - h)) / (h * h);
    let h = 4e-3;
    let g3 = (g(0.5 + 2.0 * h) - 2.0 * g(0.5 + h) + 2.0 * g(0.5 - h) - g(0.5 - 2.0 * h))
        / (2.0 * h * h * h);
    (g2, g3)
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_fast_path_answers_exactly_where_the_docs_prove_g_has_one_bend() {
    // Module docs, "Exact maximum": with S = |Δθk| + |Δθm|, g'' keeps its sign on [0, 1] (and the
    // fast path answers, with a handful of evaluations) when |g''(½)| exceeds
    // min(S³/2, |g'''(½)|/2 + S⁴/8); otherwise the dense method answers (at least 17). Checked
    // with g'' and g''' by differences, on moves clearly on either side (a factor of two).
    let mut rng = Rng::new(4242);
    let (mut fast, mut dense) = (0, 0);
    for t in RotaryType::ALL {
        for _ in 0..1000 {
            let span = [0.05, 0.3, 1.0, 2.5][rng.next_u64() as usize % 4];
            let mv = random_move(&mut rng, t, span);
            let (dk, dm) = (mv.end.k - mv.start.k, mv.end.m - mv.start.m);
            let d = Deviation::new(mv);
            if d.reference() != Reference::Plane || d.plane_sine() < 1e-3 {
                continue;
            }
            let s = dk.abs() + dm.abs();
            let (g2, g3) = g_jet_by_differences(&mv);
            let bound = (0.5 * s.powi(3)).min(0.5 * g3.abs() + 0.125 * s.powi(4));
            let (peak, evaluations) = d.peak_counted();
            if g2.abs() > 2.0 * bound {
                fast += 1;
                assert!(evaluations <= 8, "{t:?} {mv:?}: {evaluations} evaluations");
            } else if g2.abs() < 0.5 * bound {
                dense += 1;
                assert!(evaluations >= 17, "{t:?} {mv:?}: {evaluations} evaluations");
            }
            close(
                peak.value,
                d.peak_dense().value,
                1e-12,
                "either way the maximum",
            );
        }
    }
    assert!(fast > 1000 && dense > 1000, "fast {fast}, dense {dense}");
}

/// The pole of each group (eq 31): θm0 = 0 (mod π) for Group I, π/2 (mod π) for Group II.
fn pole(g: Group) -> f64 {
    match g {
        Group::I => 0.0,
        Group::II => PI / 2.0,
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn a_move_starts_at_the_pole_within_1e_12_of_its_group_s_angles() {
    for g in [Group::I, Group::II] {
        for turns in [-2.0, -1.0, 0.0, 1.0, 3.0] {
            let at = pole(g) + turns * PI;
            for off in [0.0, 5e-13, -5e-13] {
                assert!(starts_at_pole(g, at + off), "{g:?} {at} {off}");
            }
            for off in [3e-12, -3e-12, 0.2, PI / 2.0] {
                assert!(!starts_at_pole(g, at + off), "{g:?} {at} {off}");
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn at_the_pole_the_error_is_eq_26_at_half_and_its_product_form_along_the_move() {
    // Module docs of closed_form_pole: from the pole the tool's error is
    // |sin(u·Δθm)·sin((1 − u)·Δθk)|, |sin(Δθm/2)·sin(Δθk/2)| at u = ½ (eq 26); `analyze` reports
    // eq 26 (times L) there and nothing off the pole.
    let mut rng = Rng::new(26);
    let l = 250.0;
    for t in RotaryType::ALL {
        for _ in 0..6 {
            let (dk, dm) = (rng.range(-1.5, 1.5), rng.range(-1.5, 1.5));
            let k0 = rng.range(-3.0, 3.0);
            let m0 = pole(t.group()) + PI * (rng.next_u64() % 3) as f64 - PI;
            let mv = Move::new(t, Pose::new(k0, m0), Pose::new(k0 + dk, m0 + dm));
            let d = Deviation::new(mv);
            for u in [0.1, 0.3, 0.5, 0.8] {
                let want = ((u * dm).sin() * ((1.0 - u) * dk).sin()).abs();
                close(d.at(u), want, 1e-12, "the product form at the pole");
            }
            let eq26 = ((0.5 * dm).sin() * (0.5 * dk).sin()).abs();
            close(closed_form_pole(dm, dk), eq26, 1e-15, "eq 26");
            let a = analyze(mv, l, 3).unwrap();
            close(a.closed_form.unwrap(), eq26 * l, 1e-12, "eq 26 × L");
            let off = Move::new(
                t,
                Pose::new(k0, m0 + 0.3),
                Pose::new(k0 + dk, m0 + 0.3 + dm),
            );
            assert_eq!(analyze(off, l, 3).unwrap().closed_form, None);
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn analyze_gives_every_length_in_mm_and_the_curve_at_even_steps_of_u() {
    // Each length is the fraction of L from the deviation's definition times L (= 250 mm); the
    // curve's u are i/(n − 1); eq 25/30 (times L) equals δ(½); a move with no error (M alone on
    // a great circle) has no shortfall (0/0).
    let mut rng = Rng::new(661);
    let l = 250.0;
    for t in RotaryType::ALL {
        for _ in 0..8 {
            let mv = random_move(&mut rng, t, 1.0);
            let a = analyze(mv, l, 5).unwrap();
            let d = Deviation::new(mv);
            assert_eq!(a.u, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
            for (u, delta) in a.u.iter().zip(&a.delta) {
                close(*delta, d.at(*u) * l, 1e-12, "δ(u) in mm");
            }
            let peak = common::sampled_max(20_000, |u| d.at(u));
            assert!(
                a.max >= peak.1 * l - 1e-9 && a.max <= peak.1 * l + 1e-4,
                "max in mm"
            );
            close(
                d.at(a.u_at_max) * l,
                a.max,
                1e-9,
                "δ at u_at_max is the max",
            );
            close(a.at_half, d.at(0.5) * l, 1e-12, "δ(½) in mm");
            let (dk, dm) = (mv.end.k - mv.start.k, mv.end.m - mv.start.m);
            match d.reference() {
                Reference::Plane if d.plane_sine() > 1e-6 => {
                    let approx = a.approx.unwrap();
                    close(approx, d.at(0.5) * l, 1e-9, "eq 25/30 is δ(½)");
                    let eq = approx_half(t.group(), mv.start.m, dm, dk).unwrap();
                    close(approx, eq * l, 1e-12, "eq 25/30 × L");
                    close(
                        a.approx_shortfall.unwrap(),
                        (a.max - approx) / a.max,
                        1e-12,
                        "",
                    );
                }
                Reference::Plane => {}
                _ => assert_eq!(a.approx, None),
            }
        }
    }
    let t = RotaryType::parse("CBZ").unwrap();
    let m_alone = Move::new(t, Pose::new(0.4, 0.2), Pose::new(0.4, 0.9));
    let a = analyze(m_alone, l, 3).unwrap();
    assert!(a.max < 1e-12 && a.approx.is_some(), "{a:?}");
    assert_eq!(a.approx_shortfall, None);
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn bulk_maxima_and_the_fig_7_approximation_are_each_moves_own() {
    let mut rng = Rng::new(781);
    for t in RotaryType::ALL {
        let moves: Vec<[f64; 4]> = (0..5)
            .map(|_| {
                let mv = random_move(&mut rng, t, 1.0);
                [mv.start.k, mv.start.m, mv.end.k, mv.end.m]
            })
            .collect();
        let got = max_errors(t, &moves);
        assert_eq!(got.len(), 5);
        for (m, e) in moves.iter().zip(&got) {
            let mv = Move::new(t, Pose::new(m[0], m[1]), Pose::new(m[2], m[3]));
            let d = Deviation::new(mv);
            let (_, brute) = common::sampled_max(20_000, |u| d.at(u));
            assert!(
                *e >= brute - 1e-12 && *e <= brute + 1e-6,
                "{t:?} {e} vs {brute}"
            );
        }
        // Fig 7: the approximation of each point is δ(½) of its move (0, θm) → (ratio·ΔM, θm + ΔM),
        // times L; the exact one its maximum.
        let (l, dm) = (120.0, 0.4);
        let curves = sweep_start_m(t, l, dm, &[0.5, -3.0], (-0.6, 0.9), 4).unwrap();
        for c in &curves {
            for (j, (e, a)) in c.exact.iter().zip(&c.approx).enumerate() {
                let m = -0.6 + 0.5 * j as f64;
                let mv = Move::new(t, Pose::new(0.0, m), Pose::new(c.ratio * dm, m + dm));
                let d = Deviation::new(mv);
                close(*e, d.peak().value * l, 1e-12, "exact × L");
                if d.reference() == Reference::Plane && d.plane_sine() > 1e-6 {
                    close(a.unwrap(), d.at(0.5) * l, 1e-9, "approximation = δ(½) × L");
                }
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn a_split_move_of_both_axes_steps_each_axis_by_its_share() {
    // n equal steps of a move of both axes: each axis steps |Δθ|/n, and the n pieces' largest
    // δ (from their own planes) is what the split reports, within the tolerance.
    let t = RotaryType::parse("CBZ").unwrap();
    let mv = Move::new(t, Pose::new(0.2, 0.3), Pose::new(1.4, 0.9));
    let s = split_within(mv, 100.0, 0.01).unwrap();
    let n = s.steps.unwrap();
    assert!(n > 2, "{n}");
    close(s.step_k, 1.2 / n as f64, 1e-15, "step of K");
    close(s.step_m, 0.6 / n as f64, 1e-15, "step of M");
    let piece = |i: usize| {
        let at = |u: f64| Pose::new(0.2 + 1.2 * u, 0.3 + 0.6 * u);
        let p = Move::new(t, at(i as f64 / n as f64), at((i + 1) as f64 / n as f64));
        Deviation::new(p).peak().value * 100.0
    };
    let worst = (0..n).map(piece).fold(0.0, f64::max);
    close(s.max, worst, 1e-12, "the largest piece");
    assert!(s.max <= 0.01);
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/mod.rs` survived every other test.
#[test]
fn the_increment_grid_gives_u_of_the_maximum_where_there_is_an_error() {
    let t = RotaryType::parse("CBZ").unwrap();
    let g = sweep_increments(t, 100.0, 0.4, (-0.5, 0.5), (0.0, 0.6), 3, 3).unwrap();
    for iy in 0..3 {
        for ix in 0..3 {
            let (dk, dm) = (-0.5 + 0.5 * ix as f64, 0.3 * iy as f64);
            let mv = Move::new(t, Pose::new(0.0, 0.4), Pose::new(dk, 0.4 + dm));
            let peak = Deviation::new(mv).peak();
            let (e, u) = (g.max[iy * 3 + ix], g.u_at_max[iy * 3 + ix]);
            close(e, peak.value * 100.0, 1e-12, "cell");
            if dk == 0.0 {
                // No move, or M alone (on CBZ the tool then tilts along a great circle through
                // the spindle's home axis): no error, so no u. K alone at a tilt sweeps a cone.
                assert!(e < 1e-10 && u.is_none(), "{dk} {dm}: {e} {u:?}");
            } else {
                assert!(e > 1e-3, "{dk} {dm}: {e}");
                assert_eq!(u, Some(peak.u));
            }
        }
    }
}
