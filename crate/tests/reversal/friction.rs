//! Friction of C at the reversal (Nishiguchi et al. 2017, Section 5.2, Figs 12–14): the dent is
//! at the reversal only, proportional to r, absent without friction; its width against the feed;
//! halving the step changes the trace by less than 1 %; eq 2 itself.

#![allow(clippy::unwrap_used)]

use fiveaxis::reversal::{
    dent, simulate, simulate_with_step, step_check, table1_dents, ReversalCase,
};
use serde_json::{json, Value};

fn case(v: Value) -> ReversalCase {
    ReversalCase::read(&v).unwrap()
}

#[test]
fn eq2_is_a_spring_from_minus_to_plus_fc() {
    let c = case(json!({}));
    let (_, d) = c.drives();
    // Just after a reversal the friction still acts against the old direction…
    assert_eq!(d.friction(0.0, 1.0), -d.fc);
    // …it is zero where tanh(a·x′) = 1/2 …
    assert!(d.friction(0.5f64.atanh() / d.slope, 1.0).abs() < 1e-12);
    // …and Coulomb's f_c against the motion far from it.
    assert!((d.friction(10.0 / d.slope, -1.0) + d.fc).abs() < 1e-6 * d.fc);
}

#[test]
fn the_dent_is_at_the_reversal_only_and_proportional_to_r() {
    let mut depth = Vec::new();
    for r in [25.0, 50.0] {
        let c = case(json!({"test": {"offset": r}}));
        let (m, with) = simulate(&c).unwrap();
        let without = simulate_with_step(&c.with_c_friction(0.0), &m, c.step * 1e-3).unwrap();
        let d = dent(&with, &without);
        assert!(d.depth > 1e-3, "r = {r}: {d:?}");
        // Just after the reversal at 180° (C sticks while the friction turns over).
        let at = d.angle.to_degrees();
        assert!((180.0..185.0).contains(&at), "r = {r}: dent at {at}°");
        // Elsewhere the friction changes the trace by less than 2 % of the dent: away from the
        // reversal it is Coulomb friction, which the velocity loop's integral holds.
        for ((th, a), b) in with
            .theta
            .iter()
            .zip(&with.deviation)
            .zip(&without.deviation)
        {
            let deg = th.to_degrees();
            if (20.0..170.0).contains(&deg) || (200.0..340.0).contains(&deg) {
                assert!(
                    (a - b).abs() < 0.02 * d.depth,
                    "r = {r}: {deg}°: {a} vs {b}"
                );
            }
        }
        depth.push(d.depth);
    }
    let ratio = depth[1] / depth[0];
    assert!(
        (ratio - 2.0).abs() < 0.05 * 2.0,
        "depth(r = 50)/depth(r = 25) = {ratio}"
    );
}

#[test]
fn without_friction_there_is_no_dent() {
    // Fig 14(a): the position loop alone, no friction. Across the reversal the trace steps from
    // one level to the other (C's lag turns round, the linear axes' speed changes) but never
    // dips below the level it settles at; with friction it does, by the dent.
    let c = case(json!({"c": {"friction": 0}}));
    let (_, tr) = simulate(&c).unwrap();
    let level = |deg: f64| {
        let i = tr.theta.partition_point(|t| t.to_degrees() < deg);
        tr.deviation[i]
    };
    let (before, after) = (level(179.0), level(195.0));
    let step = (before - after).abs();
    let window: Vec<f64> = tr
        .theta
        .iter()
        .zip(&tr.deviation)
        .filter(|(t, _)| (179.0..195.0).contains(&t.to_degrees()))
        .map(|(_, d)| *d)
        .collect();
    let lowest = window.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        lowest >= before.min(after) - 0.02 * step,
        "{lowest} below {before}, {after}"
    );
    let with = case(json!({}));
    let (_, tr) = simulate(&with).unwrap();
    let lowest_with = tr
        .theta
        .iter()
        .zip(&tr.deviation)
        .filter(|(t, _)| (179.0..195.0).contains(&t.to_degrees()))
        .map(|(_, d)| *d)
        .fold(f64::INFINITY, f64::min);
    assert!(
        lowest_with < before.min(after) - 0.5 * step,
        "{lowest_with}"
    );
}

#[test]
fn the_dent_against_the_feed() {
    // Table 1's feeds and radii. The dent lasts as long as C's loop takes to absorb the
    // friction's turn, a time that does not depend on the feed, so its width in trace angle
    // grows in proportion to F; its depth, set by C's loop, hardly changes.
    let rows = table1_dents(&case(json!({}))).unwrap();
    assert_eq!(rows.len(), 6);
    for r in [25.0, 50.0] {
        let of = |f: f64| {
            rows.iter()
                .find(|x| x.feed == f && x.offset == r)
                .unwrap()
                .dent
        };
        let (d1, d3) = (of(1000.0), of(3000.0));
        let w = d3.width / d1.width;
        assert!((2.4..3.6).contains(&w), "r = {r}: width ratio {w}");
        assert!(
            (d3.depth / d1.depth - 1.0).abs() < 0.3,
            "r = {r}: {d1:?} {d3:?}"
        );
    }
}

#[test]
fn halving_the_step_changes_the_trace_by_less_than_one_percent() {
    for (f, r, ff) in [(1000.0, 25.0, "none"), (3000.0, 50.0, "velocity")] {
        let c = case(json!({"test": {"feed": f, "offset": r}, "feedForward": ff}));
        let (m, tr) = simulate(&c).unwrap();
        let s = step_check(&c, &m, &tr).unwrap();
        assert!(s.relative < 0.01, "F = {f}: {s:?}");
        assert!(s.difference > 0.0, "the two runs differ at all: {s:?}");
    }
}
