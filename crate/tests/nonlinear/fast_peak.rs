//! The fast maximum of `Deviation::peak` (the closed form of a move of one axis; Newton on the
//! single extremum where `g''` provably keeps one sign) against the dense reference
//! `Deviation::peak_dense`, on a million random moves of all twelve types and on the edge cases;
//! the number of orientation evaluations it takes; and the derivative bound `|V^(n)| ≤ S^n` its
//! proof rests on.
//!
//! Agreement is to `1e-12·δ + FLOOR`: the two methods stop at points a rounding apart, and `g`
//! itself is only known to about an ulp of the angles (the pose is rounded off the line) plus the
//! rounding of a dot product, about 1e-15 for the angles used here. So `δ` agrees to 1e-12
//! relative where it is above ~4e-3, and to the rounding floor below.

use crate::common;
use common::{deg, Rng};
use fiveaxis::nonlinear::{Deviation, Move, Peak, Reference};
use fiveaxis::rotary::{Group, Pose, RotaryType};
use std::f64::consts::PI;

/// Relative agreement of δ.
const REL: f64 = 1e-12;
/// Absolute agreement of δ: the rounding floor of `g` (see the file's docs; observed ≤ 1.3e-15).
const FLOOR: f64 = 4e-15;
/// Agreement of `u` where the maximum is well defined (`δ > U_ABOVE`).
const U_TOL: f64 = 1e-9;
/// Above this δ the place of the maximum is compared. Below it (a deviation of a nanometre per
/// metre of tool) the rounding of `g'` moves the root by up to ~1e-9.
const U_ABOVE: f64 = 1e-9;
/// ... and where the normal is well conditioned. Below this `|V0 × V1|` the normal carries a
/// rounding of about `ε/|V0 × V1|`, and `g` is mostly `P(u)` against that rounding: large enough
/// to pass `U_ABOVE`, flat enough that its maximum moves with the last bits of `g'`.
const U_SINE: f64 = 1e-6;
/// Places further apart than this with equal deviations are a tie, not a disagreement.
const U_TIE: f64 = 1e-3;
/// The dense method's fewest evaluations (17 samples, plus the refinement); fewer means the fast
/// path answered.
const DENSE_MIN: usize = 17;

#[derive(Default)]
struct Stats {
    compared: usize,
    worst_abs: f64,
    /// Worst relative difference of δ where δ > 1e-3, and where δ > 1e-6.
    worst_rel_1e3: f64,
    worst_rel_1e6: f64,
    worst_u: f64,
    ties: usize,
    short: usize,
    short_evals: usize,
    short_fast: usize,
    fast: usize,
}

fn mv(t: RotaryType, k0: f64, m0: f64, dk: f64, dm: f64) -> Move {
    Move::new(t, Pose::new(k0, m0), Pose::new(k0 + dk, m0 + dm))
}

/// Compares the fast and dense maxima of one move; returns the fast path's peak and evaluations.
#[track_caller]
fn check(m: Move, stats: &mut Stats) -> (Peak, usize) {
    let dev = Deviation::new(m);
    let (p, n) = dev.peak_counted();
    let q = dev.peak_dense();
    assert_eq!(p, dev.peak(), "peak() is peak_counted()'s peak");
    let what = || format!("{m:?}: fast {p:?} ({n} evaluations), dense {q:?}");
    assert!(
        p.value.is_finite() && (0.0..=1.0).contains(&p.u),
        "{}",
        what()
    );
    let diff = (p.value - q.value).abs();
    assert!(
        diff <= REL * q.value + FLOOR,
        "δ differs by {diff:e}: {}",
        what()
    );
    // The value is the deviation at the reported place (the fast path may take g there from
    // its Taylor series).
    let at = dev.at(p.u);
    assert!(
        (at - p.value).abs() <= REL * p.value + FLOOR,
        "δ({}) = {at} ≠ {}: {}",
        p.u,
        p.value,
        what()
    );
    if q.value > U_ABOVE && dev.plane_sine() > U_SINE {
        let du = (p.u - q.u).abs();
        if du > U_TIE && (dev.at(q.u) - at).abs() <= REL * p.value + FLOOR {
            // Two separate places with the same deviation to rounding: a tie (a periodic path,
            // or g flat to rounding), and either is the maximum.
            stats.ties += 1;
        } else {
            assert!(du <= U_TOL, "u differs by {du:e}: {}", what());
            stats.worst_u = stats.worst_u.max(du);
        }
    }
    stats.compared += 1;
    stats.worst_abs = stats.worst_abs.max(diff);
    if q.value > 1e-3 {
        stats.worst_rel_1e3 = stats.worst_rel_1e3.max(diff / q.value);
    }
    if q.value > 1e-6 {
        stats.worst_rel_1e6 = stats.worst_rel_1e6.max(diff / q.value);
    }
    if n < DENSE_MIN {
        stats.fast += 1;
    }
    let (dk, dm) = (m.end.k - m.start.k, m.end.m - m.start.m);
    if dk.abs() + dm.abs() < deg(5.0) {
        stats.short += 1;
        stats.short_evals += n;
        if n < DENSE_MIN {
            stats.short_fast += 1;
        }
    }
    (p, n)
}

fn sign(rng: &mut Rng) -> f64 {
    if rng.unit() < 0.5 {
        -1.0
    } else {
        1.0
    }
}

/// Increments with `|dk| + |dm|` uniform in `[lo, hi)` (radians), split at random, random signs;
/// one time in eight a pure move of one axis.
fn split(rng: &mut Rng, lo: f64, hi: f64) -> (f64, f64) {
    let span = rng.range(lo, hi);
    let f = match rng.next_u64() % 16 {
        0 => 0.0,
        1 => 1.0,
        _ => rng.unit(),
    };
    (sign(rng) * f * span, sign(rng) * (1.0 - f) * span)
}

#[test]
fn a_million_random_moves_fast_equals_dense_and_short_ones_take_few_evaluations() {
    let mut rng = Rng::new(20_180_409);
    let mut stats = Stats::default();
    for i in 0..1_000_000 {
        let t = RotaryType::ALL[(rng.next_u64() % 12) as usize];
        let (k0, m0) = (deg(rng.range(-360.0, 360.0)), deg(rng.range(-360.0, 360.0)));
        let (dk, dm) = match i % 4 {
            // Half short (|Δθk| + |Δθm| < 5°), a quarter medium, a quarter long.
            0 | 2 => split(&mut rng, 0.0, deg(5.0)),
            1 => split(&mut rng, deg(5.0), deg(120.0)),
            _ => (deg(rng.range(-400.0, 400.0)), deg(rng.range(-400.0, 400.0))),
        };
        check(mv(t, k0, m0, dk, dm), &mut stats);
    }
    let avg = stats.short_evals as f64 / stats.short as f64;
    eprintln!(
        "{} moves: worst |Δδ| {:e}, worst relative Δδ {:e} (δ > 1e-3), {:e} (δ > 1e-6), worst \
         |Δu| {:e} (δ > {U_ABOVE:e}), {} ties; fast path {} of {}; short moves: {:.3} evaluations on \
         average, fast path {} of {}",
        stats.compared,
        stats.worst_abs,
        stats.worst_rel_1e3,
        stats.worst_rel_1e6,
        stats.worst_u,
        stats.ties,
        stats.fast,
        stats.compared,
        avg,
        stats.short_fast,
        stats.short,
    );
    assert!(stats.short > 400_000);
    assert!(avg <= 10.0, "{avg} evaluations per short move");
    // The comparison is not of the dense method with itself: the fast path answers nearly all
    // short moves and many medium ones.
    assert!(stats.short_fast as f64 > 0.95 * stats.short as f64);
    assert!(stats.fast > stats.short_fast + 50_000);
    assert!(stats.worst_rel_1e3 <= 2e-12);
    assert_eq!(stats.ties, 0);
}

#[test]
fn pure_moves_of_one_axis() {
    let mut stats = Stats::default();
    // Down to 1e-6° (where |V0 × V1| is near DEGENERATE_SINE and the rounding of the normal
    // gives g up to ~1e-9: "no error" is asserted from 0.1° up).
    let spans = [
        1e-6, 1e-3, 0.1, 1.0, 2.5, 4.9, 30.0, 90.0, 179.0, 180.0, 359.0, 360.0, 400.0, 720.0,
    ];
    for t in RotaryType::ALL {
        let pole = match t.group() {
            Group::I => 0.0,
            Group::II => -90.0,
        };
        for m_deg in [
            -180.0, -135.0, -90.0, -60.0, -10.0, 0.0, 1.0, 30.0, 45.0, 75.0, 90.0, 120.0, 180.0,
        ] {
            for span in spans {
                for s in [-1.0, 1.0] {
                    // K alone: a cone about K, a great circle only when flat (θm at the
                    // equator) and a point when the tool is on K (θm at the pole). M alone: a
                    // great circle. No error then, unless the ends coincide (a full turn: the
                    // chord form).
                    let k = mv(t, 0.3, deg(m_deg), deg(s * span), 0.0);
                    let (p, n) = check(k, &mut stats);
                    let off_pole = (m_deg - pole).rem_euclid(180.0);
                    let coincident = Deviation::new(k).reference() == Reference::Coincident;
                    if (off_pole == 0.0 || off_pole == 90.0) && !coincident && span >= 0.1 {
                        assert!(p.value < 1e-12, "{t} K alone at θm {m_deg}: {p:?}");
                    }
                    let plane = Deviation::new(k).reference() == Reference::Plane;
                    assert!(!plane || n == 1, "{t} K alone: {n} evaluations");
                    let m = mv(t, 0.3, deg(m_deg), 0.0, deg(s * span));
                    let (p, n) = check(m, &mut stats);
                    if Deviation::new(m).reference() != Reference::Coincident && span >= 0.1 {
                        assert!(p.value < 1e-12, "{t} M alone at θm {m_deg}: {p:?}");
                    }
                    let plane = Deviation::new(m).reference() == Reference::Plane;
                    assert!(!plane || n == 1, "{t} M alone: {n} evaluations");
                }
            }
        }
    }
    // A short move of K alone away from the equator and the pole is an arc of a small circle:
    // the fast path answers it, and the answer is the arc's midpoint (it is symmetric about the
    // plane bisecting its chord), at the distance computed here from the cone's own vectors.
    let t = RotaryType::parse("CAZ").expect("type");
    for m_deg in [10.0, 30.0, 60.0, 80.0] {
        let (a, dk) = (deg(m_deg), deg(4.0));
        let (p, n) = check(mv(t, 0.3, a, dk, 0.0), &mut stats);
        assert_eq!(n, 1, "K alone at {m_deg}: the closed form");
        // CAZ: the tool at polar angle a from Z (the K axis), turned about Z by θk.
        let v = |phi: f64| [a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos()];
        let (v0, v1, vh) = (v(0.0), v(dk), v(0.5 * dk));
        let n = [
            v0[1] * v1[2] - v0[2] * v1[1],
            v0[2] * v1[0] - v0[0] * v1[2],
            v0[0] * v1[1] - v0[1] * v1[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let closed = ((vh[0] * n[0] + vh[1] * n[1] + vh[2] * n[2]) / len).abs();
        assert!(
            (p.value - closed).abs() <= 1e-12 * closed + FLOOR,
            "{p:?} vs {closed}"
        );
        assert!((p.u - 0.5).abs() < 1e-9, "{p:?}");
    }
}

#[test]
fn zero_moves_and_ends_that_coincide_or_are_opposite() {
    let mut stats = Stats::default();
    for t in RotaryType::ALL {
        for (k0, m0) in [
            (0.0, 0.0),
            (0.4, 0.2),
            (-3.0, 1.5),
            (deg(720.0), deg(-90.0)),
        ] {
            // No move: the chord form, exactly zero but for the rounding of sqrt(2 + 2g) with
            // g = -V0·V0 = -1 to an ulp (sqrt(4.4e-16) = 2.1e-8).
            let (p, _) = check(mv(t, k0, m0, 0.0, 0.0), &mut stats);
            assert!(p.u == 0.0 && p.value < 3e-8, "{t} no move: {p:?}");
            // A full turn of K: coincident ends; of M by 180°: opposite ends.
            let full = Deviation::new(mv(t, k0, m0 + 0.5, 2.0 * PI, 0.0));
            assert_ne!(full.reference(), Reference::Plane);
            check(mv(t, k0, m0 + 0.5, 2.0 * PI, 0.0), &mut stats);
            let half = Deviation::new(mv(t, k0, m0, 0.0, PI));
            assert_eq!(half.reference(), Reference::Opposite);
            check(mv(t, k0, m0, 0.0, PI), &mut stats);
            // Ends a hair from coinciding: a plane with a tiny, ill-conditioned sine.
            for eps in [1e-9, 3e-9, 1e-8, 1e-6] {
                check(mv(t, k0, m0 + 0.5, 2.0 * PI + eps, 0.0), &mut stats);
                check(mv(t, k0, m0 + 0.5, 2.0 * PI, eps), &mut stats);
                check(mv(t, k0, m0, eps, PI), &mut stats);
            }
        }
    }
}

#[test]
fn tiny_moves_down_to_the_degenerate_sine() {
    // Spans from 0.1 rad down to a few 1e-9 rad, where |V0 × V1| approaches DEGENERATE_SINE and
    // the rounding of the normal dominates g (both methods see the same g).
    let mut rng = Rng::new(9);
    let mut stats = Stats::default();
    let mut planes = 0;
    for e in 0..80 {
        let exp = -1.0 - e as f64 / 10.0;
        for _ in 0..500 {
            let t = RotaryType::ALL[(rng.next_u64() % 12) as usize];
            let (k0, m0) = (rng.range(-7.0, 7.0), rng.range(-7.0, 7.0));
            let (dk, dm) = split(&mut rng, 10f64.powf(exp), 3.0 * 10f64.powf(exp));
            let m = mv(t, k0, m0, dk, dm);
            if Deviation::new(m).reference() == Reference::Plane {
                planes += 1;
            }
            check(m, &mut stats);
        }
    }
    assert!(planes > 35_000, "{planes}");
    assert!(stats.fast > 30_000, "{}", stats.fast);
}

#[test]
fn near_the_pole() {
    // Group I at θm = 0, Group II at θm = -90°: the tool starts on (or next to) the K axis.
    let mut rng = Rng::new(26);
    let mut stats = Stats::default();
    for t in RotaryType::ALL {
        let pole = match t.group() {
            Group::I => 0.0,
            Group::II => -PI / 2.0,
        };
        for off in [
            0.0,
            1e-12,
            -1e-12,
            1e-9,
            -1e-9,
            1e-6,
            -1e-6,
            1e-3,
            -1e-3,
            deg(1.0),
        ] {
            for _ in 0..200 {
                let (dk, dm) = split(&mut rng, 0.0, deg(5.0));
                check(mv(t, rng.range(-PI, PI), pole + off, dk, dm), &mut stats);
                // Also moves that pass through the pole.
                check(mv(t, 0.2, pole + off - 0.5 * dm, dk, dm), &mut stats);
            }
        }
    }
}

/// Maximum of a unimodal `f` on `[0, 1]` by golden-section search (independent of the engine).
fn golden(f: impl Fn(f64) -> f64) -> (f64, f64) {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (0.0, 1.0);
    while b - a > 1e-14 {
        let (c, d) = (b - r * (b - a), a + r * (b - a));
        if f(c) > f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let u = 0.5 * (a + b);
    (u, f(u))
}

#[test]
fn at_the_pole_the_fast_path_finds_the_closed_form_maximum() {
    // Starting at the pole the error curve is |sin(u·Δθm)·sin((1-u)·Δθk)| (crate/tests/nonlinear/paper.rs),
    // log-concave on [0, 1] for increments under 90°: an answer independent of both methods.
    let mut rng = Rng::new(31);
    let mut stats = Stats::default();
    let mut fast = 0;
    for t in RotaryType::ALL {
        let pole = match t.group() {
            Group::I => 0.0,
            Group::II => -PI / 2.0,
        };
        for _ in 0..300 {
            let (dk, dm) = (deg(rng.range(0.05, 5.0)), deg(rng.range(0.05, 5.0)));
            let (p, n) = check(mv(t, 0.3, pole, dk, dm), &mut stats);
            let (u, v) = golden(|u| ((u * dm).sin() * ((1.0 - u) * dk).sin()).abs());
            assert!(
                (p.value - v).abs() <= 1e-12 * v + FLOOR,
                "{t}: {p:?} vs {v}"
            );
            assert!((p.u - u).abs() < 1e-6, "{t}: {p:?} vs u {u}");
            fast += usize::from(n < DENSE_MIN);
        }
    }
    assert!(fast > 3000, "{fast}");
}

#[test]
fn derivatives_of_the_orientation_are_bounded_by_powers_of_the_span() {
    // The lemma of the fast path: |V^(n)| ≤ S^n, S = |Δθk| + |Δθm|; and V''' of tool_vector_jet
    // is the derivative of V'' (central differences), its first three entries those of
    // tool_vector_derivatives.
    let mut rng = Rng::new(4);
    let mut tightest: f64 = 0.0;
    for t in RotaryType::ALL {
        for _ in 0..2000 {
            let pose = Pose::new(rng.range(-7.0, 7.0), rng.range(-7.0, 7.0));
            let (dk, dm) = (rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let s = dk.abs() + dm.abs();
            let jet = t.tool_vector_jet(pose, dk, dm);
            let (v, d1, d2) = t.tool_vector_derivatives(pose, dk, dm);
            assert_eq!([jet[0], jet[1], jet[2]], [v, d1, d2]);
            for (n, d) in jet.iter().enumerate() {
                let bound = s.powi(n as i32) * (1.0 + 1e-14);
                assert!(d.norm() <= bound, "{t} |V^({n})| = {} > {bound}", d.norm());
                if n > 0 {
                    tightest = tightest.max(d.norm() / s.powi(n as i32));
                }
            }
            let h = 1e-5;
            let at = |u: f64| {
                let p = Pose::new(pose.k + u * dk, pose.m + u * dm);
                t.tool_vector_derivatives(p, dk, dm).2
            };
            let fd = (at(h) - at(-h)) / (2.0 * h);
            assert!(
                (fd - jet[3]).norm() <= 1e-8 * s.powi(3).max(1.0),
                "{t}: V''' {:?} vs {:?}",
                jet[3],
                fd
            );
            // The fourth derivative (the Taylor remainder of the fast path), by differences.
            let third = |u: f64| {
                let p = Pose::new(pose.k + u * dk, pose.m + u * dm);
                t.tool_vector_jet(p, dk, dm)[3]
            };
            let d4 = (third(h) - third(-h)) / (2.0 * h);
            assert!(
                d4.norm() <= s.powi(4) * (1.0 + 1e-6) + 1e-7,
                "{t}: |V''''| > S⁴"
            );
        }
    }
    // The bound is attained (e.g. a move of one axis with the tool perpendicular to it).
    assert!(tightest > 0.999, "{tightest}");
}
