//! The toolpath study (`fiveaxis::toolpath`): following a path with continuity, flips and poles,
//! the ranking of the twelve types, and refinement to a tolerance, against values derived
//! independently (the issue's stated numbers, dense sampling of the tool axis, closed forms).

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use crate::common;

use common::toolpath::tilted;
use fiveaxis::machine::Machine;
use fiveaxis::rotary::{Pose, RotaryType};
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::Motion;
use fiveaxis::toolpath::{
    analyse, analyse_path, compare, follow, follow_commands, machine_of_type, refine, refine_path,
    slerp, Commands, Path,
};
use nalgebra::Vector3;
use serde_json::json;

fn machine(value: serde_json::Value) -> Machine {
    Machine::from_value(&value, "machine").unwrap()
}

fn rtype(name: &str) -> RotaryType {
    RotaryType::parse(name).unwrap()
}

/// The model of the machine `inputs` (JSON) with rotary-axis type `t`.
fn model(inputs: serde_json::Value, t: RotaryType) -> fiveaxis::machine::Model {
    machine_of_type(&machine(inputs), t).build().unwrap()
}

/// δ of the linear interpolation of the commands from `(k0, m0)` to `(k1, m1)` (rad) on `t`,
/// by dense sampling (2001 points) of the distance of `L·P(u)` from the plane of its ends:
/// independent of the engine's exact maximum.
fn dense_delta(t: RotaryType, f: (f64, f64), a: (f64, f64), b: (f64, f64), l: f64) -> f64 {
    let p = |u: f64| {
        t.tool_vector(Pose::new(
            f.0 * (a.0 + u * (b.0 - a.0)),
            f.1 * (a.1 + u * (b.1 - a.1)),
        ))
    };
    let n = p(0.0).cross(&p(1.0)).normalize();
    (0..=2000)
        .map(|i| l * p(i as f64 / 2000.0).dot(&n).abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_same_tool_path_on_other_types_gives_the_issues_numbers() {
    // Issue: the move CAZ (θk, θm) = (0°, 10°) → (30°, 25°) at L = 100 mm, applied as the same
    // joint move to ABZ and CAY, gives 1.391 mm on both; the same tool path (start and end tool
    // vectors) gives 0.129 mm on ABZ and 3.292 mm on CAY (and on CAZ itself, its own move).
    let caz = rtype("CAZ");
    let v0 = caz.tool_vector(Pose::new(0.0, 10f64.to_radians()));
    let v1 = caz.tool_vector(Pose::new(30f64.to_radians(), 25f64.to_radians()));
    let rows = compare(&machine(json!({})), &[v0, v1], 100.0, 0.01).unwrap();
    let max = |name: &str| rows.iter().find(|r| r.rtype.name() == name).unwrap().max;
    assert!((max("CAZ") - 3.292).abs() < 5e-4, "{}", max("CAZ"));
    assert!((max("ABZ") - 0.129).abs() < 5e-4, "{}", max("ABZ"));
    assert!((max("CAY") - 3.292).abs() < 5e-4, "{}", max("CAY"));
    // Ranked by the largest error.
    assert!(rows.windows(2).all(|w| w[0].max <= w[1].max));
    assert_eq!(rows.len(), 12);
}

/// Points every `step` degrees along the great circle through `tilted(t0, c)` … : a straight
/// tilt sweep in the vertical plane at azimuth `c`, offset sideways by `offset` degrees (so that
/// it passes the vertical at that angle), from tilt `from` to `to`.
fn sweep_past_vertical(c: f64, offset: f64, from: f64, to: f64, step: f64) -> Vec<Vector3<f64>> {
    let (c, o) = (c.to_radians(), offset.to_radians());
    // Plane through the origin with normal n = (−sin c, cos c, 0) rotated by `offset` about the
    // in-plane horizontal direction d = (cos c, sin c, 0).
    let d = Vector3::new(c.cos(), c.sin(), 0.0);
    let side = Vector3::new(-c.sin(), c.cos(), 0.0);
    let up = Vector3::z() * o.cos() + side * o.sin();
    let n = ((to - from) / step).round() as usize;
    (0..=n)
        .map(|i| {
            let t = (from + step * i as f64).to_radians();
            up * t.cos() + d * t.sin()
        })
        .collect()
}

#[test]
fn a_path_past_the_pole_flags_a_pole_and_a_flip_there_and_a_path_far_from_it_none() {
    // CAZ: K = C about Z, so the pole is the vertical tool. A tilt sweep from −20° to +20° that
    // passes 0.2° beside the vertical, in 1° steps: C must turn by far more than the tool does
    // next to the vertical.
    let m = model(json!({}), rtype("CAZ"));
    let near = sweep_past_vertical(30.0, 0.2, -20.0, 20.0, 1.0);
    let a = analyse(&m, &near, 100.0, 0.01).unwrap();
    let flagged: Vec<usize> = (0..a.segments.len())
        .filter(|&i| a.segments[i].flip)
        .collect();
    // The vertical is passed between points 20 (tilt 0° along the sweep) and its neighbours.
    assert!(!flagged.is_empty(), "no flip flagged");
    assert!(
        flagged.iter().all(|&i| (19..=20).contains(&i)),
        "{flagged:?}"
    );
    assert!(a.segments[19].pole || a.segments[20].pole);
    assert_eq!(a.summary.flips, flagged.len());
    // Away from the pole: the same sweep tilted between 20° and 60° (on one side): no flag.
    let far = sweep_past_vertical(30.0, 0.2, 20.0, 60.0, 1.0);
    let b = analyse(&m, &far, 100.0, 0.01).unwrap();
    assert_eq!((b.summary.flips, b.summary.poles), (0, 0));
    // The same near-pole sweep on a type whose pole is elsewhere (ABZ: K = A about X) flags nothing.
    let abz = model(json!({}), rtype("ABZ"));
    let c = analyse(&abz, &near, 100.0, 0.01).unwrap();
    assert_eq!((c.summary.flips, c.summary.poles), (0, 0));
}

#[test]
fn following_reproduces_every_tool_axis_and_moves_the_axes_continuously() {
    let endless = json!({"rotary": {"kFrom": -3600, "kTo": 3600}});
    let m = model(endless, rtype("CBZ"));
    // A cone around Z at 30°, two turns of the azimuth in 3° steps.
    let path: Vec<Vector3<f64>> = (0..=240).map(|i| tilted(30.0, 3.0 * i as f64)).collect();
    let f = follow(&m, &path).unwrap();
    assert!(f.unreachable.is_none());
    for (i, a) in path.iter().enumerate() {
        let v = rtype("CBZ").tool_vector(Pose::new(f.k[i], f.m[i]));
        assert!((v - a).norm() < 1e-12, "point {i}");
    }
    // Around a cone at tilt 30°, C turns with the azimuth (3° per point) and B stays put.
    for i in 1..path.len() {
        assert!(
            ((f.k[i] - f.k[i - 1]).to_degrees() - 3.0).abs() < 1e-9,
            "{i}"
        );
        assert!((f.m[i] - f.m[i - 1]).abs() < 1e-12);
    }
}

#[test]
fn the_end_of_the_travel_unwinds_the_rotary_table_and_is_flagged() {
    // C travels ±200° only. Round the cone, at C = 200° the nearest way on is the other branch
    // (C − 180°, B reversed): a flip at azimuth 201°, 381° and 561° in two turns.
    let m = model(json!({"rotary": {"kFrom": -200, "kTo": 200}}), rtype("CBZ"));
    let path: Vec<Vector3<f64>> = (0..=240).map(|i| tilted(30.0, 3.0 * i as f64)).collect();
    let a = analyse(&m, &path, 100.0, 0.01).unwrap();
    assert!(a.following.unreachable.is_none());
    let k: Vec<f64> = a.following.k.iter().map(|x| x.to_degrees()).collect();
    assert!(k
        .iter()
        .all(|&x| (-200.0 - 1e-6..=200.0 + 1e-6).contains(&x)));
    let unwinds: Vec<usize> = (1..k.len())
        .filter(|&i| (k[i] - k[i - 1]).abs() > 90.0)
        .collect();
    assert_eq!(unwinds, [67, 127, 187]);
    for &i in &unwinds {
        assert!(a.segments[i - 1].flip, "segment {}", i - 1);
    }
    assert_eq!(a.summary.flips, 3);
    assert_eq!(a.summary.poles, 0);
    // No number of points fixes a swing round at the end of the travel: refining leaves those
    // three segments as they are, says so, and keeps every other segment within the tolerance
    // (dense sampling of the commands it gives).
    let tips = vec![Vector3::zeros(); path.len()];
    let r = refine(&m, &tips, &path, 100.0, 0.01).unwrap();
    assert_eq!(r.unfixed, [66, 126, 186]);
    let t = rtype("CBZ");
    let mut over = 0;
    for i in 1..r.k.len() {
        if dense_delta(
            t,
            (1.0, 1.0),
            (r.k[i - 1], r.m[i - 1]),
            (r.k[i], r.m[i]),
            100.0,
        ) > 0.01 + 1e-12
        {
            over += 1;
        }
    }
    assert_eq!(over, 3);
}

#[test]
fn a_tilt_beyond_the_travel_stops_the_path_at_that_point() {
    // B tilts from −10° to 40°: a path tilting to 45° on the far side cannot be followed beyond
    // the first point tilting more than 40° (either solution needs |B| > 40° or B < −10°).
    let m = model(json!({"rotary": {"mFrom": -10, "mTo": 40}}), rtype("CBZ"));
    let path: Vec<Vector3<f64>> = (0..=9).map(|i| tilted(5.0 * i as f64, 0.0)).collect();
    let a = analyse(&m, &path, 100.0, 0.01).unwrap();
    let (at, why) = a.following.unreachable.clone().unwrap();
    assert_eq!(at, 9);
    assert!(why.contains("B = 45°"), "{why}");
    assert_eq!(a.segments.len(), 8);
    assert_eq!(a.summary.unreachable.as_ref().unwrap().point, 9);
    // In a ranking such a type comes after every type that follows the whole path.
    let rows = compare(
        &machine(json!({"rotary": {"mFrom": -10, "mTo": 40}})),
        &path,
        100.0,
        0.01,
    )
    .unwrap();
    let first_unreachable = rows.iter().position(|r| r.unreachable.is_some()).unwrap();
    assert!(rows[first_unreachable..]
        .iter()
        .all(|r| r.unreachable.is_some()));
    // Among those, the farther a type gets along the path, the better it ranks.
    let stops: Vec<usize> = rows[first_unreachable..]
        .iter()
        .map(|r| r.unreachable.as_ref().unwrap().point)
        .collect();
    assert!(stops.windows(2).all(|w| w[0] >= w[1]), "{stops:?}");
}

#[test]
fn the_statistics_are_those_of_the_segments() {
    let m = model(json!({}), rtype("CAY"));
    let path: Vec<Vector3<f64>> = (0..=60)
        .map(|i| tilted(10.0 + i as f64 * 0.7, 5.0 * i as f64))
        .collect();
    let a = analyse(&m, &path, 150.0, 0.005).unwrap();
    let mut d: Vec<f64> = a.segments.iter().map(|s| s.delta).collect();
    let n = d.len();
    let s = &a.summary;
    assert_eq!(s.segments, 60);
    assert!((s.mean - d.iter().sum::<f64>() / n as f64).abs() < 1e-15);
    assert_eq!(s.above, d.iter().filter(|&&x| x > 0.005).count());
    d.sort_by(f64::total_cmp);
    assert_eq!(s.max, d[n - 1]);
    // Nearest rank: 95 % of 60 is 57, the 57th smallest.
    assert_eq!(s.p95, d[56]);
    let k_travel: f64 = a.following.k.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    assert!((s.k_travel - k_travel).abs() < 1e-12);
    // Each δ is the dense-sampled error of the linear interpolation of the commands.
    for (i, seg) in a.segments.iter().enumerate() {
        let f = &a.following;
        let dense = dense_delta(
            rtype("CAY"),
            (1.0, 1.0),
            (f.k[i], f.m[i]),
            (f.k[i + 1], f.m[i + 1]),
            150.0,
        );
        assert!(
            seg.delta >= dense - 1e-12 && seg.delta - dense < 1e-6 * seg.delta.max(1e-9),
            "{i}"
        );
    }
}

#[test]
fn refining_keeps_every_piece_within_the_tolerance_with_the_fewest_points() {
    let t = rtype("CBZ");
    let m = model(json!({}), t);
    // Segments of different lengths: the tilt and azimuth grow in uneven steps.
    let steps = [0.5, 4.0, 1.0, 9.0, 0.2, 15.0, 2.0];
    let mut axes = vec![tilted(20.0, 0.0)];
    let (mut tilt, mut az) = (20.0, 0.0);
    for s in steps {
        tilt += s;
        az += 3.0 * s;
        axes.push(tilted(tilt, az));
    }
    let tips: Vec<Vector3<f64>> = (0..axes.len())
        .map(|i| Vector3::new(10.0 * i as f64, 0.0, 0.0))
        .collect();
    let (l, tol) = (200.0, 0.01);
    let before = analyse(&m, &axes, l, tol).unwrap();
    let r = refine(&m, &tips, &axes, l, tol).unwrap();
    // Every piece of the refined path, measured by dense sampling, is within the tolerance.
    for i in 1..r.k.len() {
        let d = dense_delta(t, (1.0, 1.0), (r.k[i - 1], r.m[i - 1]), (r.k[i], r.m[i]), l);
        assert!(d <= tol + 1e-12, "piece {i}: {d}");
    }
    assert!(r.max <= tol);
    // The original points are all there, in order; segments within the tolerance got none.
    let originals: Vec<usize> = r.source.iter().flatten().copied().collect();
    assert_eq!(originals, (0..axes.len()).collect::<Vec<_>>());
    for (i, seg) in before.segments.iter().enumerate() {
        let at = |j: usize| r.source.iter().position(|s| *s == Some(j)).unwrap();
        let inserted = at(i + 1) - at(i) - 1;
        if seg.delta <= tol {
            assert_eq!(inserted, 0, "segment {i} needed none");
            continue;
        }
        assert!(inserted > 0, "segment {i}");
        // One piece fewer would not do: cut into `inserted` equal pieces, some piece exceeds.
        let n = inserted;
        let mut worst: f64 = 0.0;
        let mut prev = (before.following.k[i], before.following.m[i]);
        for j in 1..=n {
            let v = slerp(&axes[i], &axes[i + 1], j as f64 / n as f64);
            let o = m
                .orientations(
                    &v,
                    fiveaxis::machine::BranchRule::Nearest,
                    Some([prev.0, prev.1]),
                )
                .unwrap();
            let c = o.solutions[o.chosen.unwrap()];
            worst = worst.max(dense_delta(t, (1.0, 1.0), prev, (c.k, c.m), l));
            prev = (c.k, c.m);
        }
        assert!(worst > tol, "segment {i}: {n} pieces would do ({worst})");
        // The inserted tips lie on the straight line between the segment's ends.
        for j in at(i) + 1..at(i + 1) {
            let d = (r.tips[j] - tips[i]).cross(&(tips[i + 1] - tips[i])).norm();
            assert!(d < 1e-9);
        }
    }
    assert_eq!(r.added, r.source.iter().filter(|s| s.is_none()).count());
    assert!(r.added > 0);
}

#[test]
fn inputs_that_cannot_be_analysed_are_refused_with_their_path() {
    let m = Machine::standard().unwrap().build().unwrap();
    let err = analyse(&m, &[Vector3::z()], 100.0, 0.01).unwrap_err();
    assert_eq!(err.field, "points");
    let err = analyse(&m, &[Vector3::z(), Vector3::zeros()], 100.0, 0.01).unwrap_err();
    assert_eq!(err.field, "points[1]");
    let err = analyse(&m, &[Vector3::z(), Vector3::x()], 0.0, 0.01).unwrap_err();
    assert_eq!(err.field, "length");
    let err = analyse(&m, &[Vector3::z(), Vector3::x()], 100.0, -1.0).unwrap_err();
    assert_eq!(err.field, "tolerance");
}

/// The tool axes of a sample file of `public/samples/` (written by `scripts/samples.mjs`).
fn sample(name: &str, format: fiveaxis::toolpath::read::Format) -> Vec<Vector3<f64>> {
    let text = std::fs::read_to_string(format!("../public/samples/{name}")).unwrap();
    fiveaxis::toolpath::read::parse(&text, format, None)
        .unwrap()
        .iter()
        .map(|p| p.axis)
        .collect()
}

#[test]
fn the_dome_sample_flips_exactly_the_types_whose_k_axis_is_vertical() {
    // The dome's meridian passes 0.3° beside the vertical, tilting ±40°, 1° a point. K about Z
    // (C: CAZ CBZ CAY CBX) must swing by about 2·atan(0.5/0.3) ≈ 118° next to the vertical:
    // a pole passage and a flip on either side of it. K about X or Y never comes near its pole
    // (the tool stays within 40° of Z). ABX and ACX (tool along X at zero) need M to tilt the
    // tool by at least 90° + 40° minus a hair from X, beyond the default ±120° of M: they
    // cannot start.
    let axes = sample(
        "dome-past-the-pole.csv",
        fiveaxis::toolpath::read::Format::Csv,
    );
    assert_eq!(axes.len(), 81);
    let rows = compare(&machine(json!({})), &axes, 150.0, 0.01).unwrap();
    for r in &rows {
        let name = r.rtype.name();
        match name.as_str() {
            "CAZ" | "CBZ" | "CAY" | "CBX" => {
                assert_eq!((r.flips, r.poles), (2, 2), "{name}");
                assert!(r.max > 0.1, "{name}: {}", r.max);
            }
            "ABX" | "ACX" => assert_eq!(r.unreachable.as_ref().map(|u| u.point), Some(0)),
            _ => {
                assert_eq!((r.flips, r.poles, r.above), (0, 0, 0), "{name}");
                assert!(r.unreachable.is_none());
            }
        }
    }
    // Ranked: the smooth types first, the flipping ones after, those that cannot start last.
    let order: Vec<String> = rows.iter().map(|r| r.rtype.name()).collect();
    let pos = |n: &str| order.iter().position(|x| x == n).unwrap();
    for smooth in ["BCY", "BAZ", "ABZ", "ACY"] {
        assert!(
            pos(smooth) < pos("CAZ") && pos("CAZ") < pos("ABX"),
            "{order:?}"
        );
    }
}

#[test]
fn the_impeller_sample_turns_c_round_and_tilts_a_and_b_less() {
    // The swarf path goes once round Z (six blades 60° apart), tilted 41° to 49° from Z. K
    // about Z follows the azimuth (at least 300° of C in all), while K about X or Y only rocks:
    // its total travel stays below C's. Every type that follows the whole path keeps its worst
    // segment within a few times the tolerance (0.5° of blade per point) unless it flips.
    let axes = sample("impeller-swarf.apt", fiveaxis::toolpath::read::Format::Apt);
    assert_eq!(axes.len(), 751);
    let rows = compare(&machine(json!({})), &axes, 150.0, 0.01).unwrap();
    let row = |n: &str| rows.iter().find(|r| r.rtype.name() == n).unwrap();
    assert!(row("CBZ").k_travel.to_degrees() > 300.0);
    assert!(row("BAZ").k_travel < row("CBZ").k_travel);
    for r in rows
        .iter()
        .filter(|r| r.unreachable.is_none() && r.flips == 0)
    {
        assert!(r.max < 0.05, "{}: {}", r.rtype, r.max);
    }
    assert!(rows
        .windows(2)
        .all(|w| w[0].unreachable.is_some() <= w[1].unreachable.is_some()));
}

#[test]
fn rows_computed_apart_and_sorted_by_their_rank_key_are_the_ranking_of_all_twelve() {
    // The page ranks the twelve types in several workers, each on a share, and merges the rows
    // by their `rank` key alone. On a path some types cannot follow (B from −10° to 40°), the
    // merge must give the ranking of all twelve at once, row for row.
    let m = machine(json!({"rotary": {"mFrom": -10, "mTo": 40}}));
    let path: Vec<Vector3<f64>> = (0..=9).map(|i| tilted(5.0 * i as f64, 20.0)).collect();
    let all = compare(&m, &path, 100.0, 0.01).unwrap();
    assert!(all.iter().any(|r| r.unreachable.is_some()));
    assert!(all.iter().any(|r| r.unreachable.is_none()));
    let mut merged = Vec::new();
    for share in 0..3 {
        let types: Vec<RotaryType> = RotaryType::ALL
            .iter()
            .enumerate()
            .filter(|(j, _)| j % 3 == share)
            .map(|(_, t)| *t)
            .collect();
        merged.extend(fiveaxis::toolpath::compare_types(&m, &path, 100.0, 0.01, &types).unwrap());
    }
    merged.sort_by(|a, b| {
        a.rank
            .iter()
            .zip(&b.rank)
            .map(|(x, y)| x.partial_cmp(y).unwrap())
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    assert_eq!(merged, all);
    // The rule the key stands for: the types that follow the whole path first, by largest δ
    // then mean δ; then the others, the farthest along first.
    for w in all.windows(2) {
        match (&w[0].unreachable, &w[1].unreachable) {
            (None, None) => assert!((w[0].max, w[0].mean) <= (w[1].max, w[1].mean)),
            (Some(_), None) => panic!(
                "{} cannot follow the path, ranked before {}",
                w[0].rtype.name(),
                w[1].rtype.name()
            ),
            (Some(a), Some(b)) => assert!(a.point >= b.point),
            (None, Some(_)) => {}
        }
    }
}

#[test]
fn a_path_from_javascript_is_checked_number_by_number() {
    use fiveaxis::toolpath::export::{Part, PathInput, PathValue, MAX_COORDINATE};
    let msg = |v: PathValue| PathInput::read(v).unwrap_err().to_string();
    let two = vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 10.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    assert!(msg(PathValue::Other).starts_with("points: expected a Float64Array"));
    assert!(
        msg(PathValue::Points(vec![0.0; 5])).starts_with("points: length must be a multiple of 6")
    );
    // A coordinate beyond ±MAX_COORDINATE either way, named with the range it must be in.
    for v in [1.5, -1.5] {
        let mut far = two.clone();
        far[7] = MAX_COORDINATE * v;
        let m = msg(PathValue::Points(far));
        assert!(
            m.starts_with(&format!(
                "points[1][1]: must be between {} and {MAX_COORDINATE} mm",
                -MAX_COORDINATE
            )),
            "{m}"
        );
    }
    let mut nan = two.clone();
    nan[2] = f64::NAN;
    assert!(msg(PathValue::Points(nan)).starts_with("points[0][2]: "));
    let mut zero = two.clone();
    zero[9..].fill(0.0);
    assert!(msg(PathValue::Points(zero)).starts_with("points[1]: the tool axis"));
    // An object: keys first, then each part.
    let obj = |parts: Vec<(&'static str, Part)>| {
        let keys = parts.iter().map(|(k, _)| k.to_string()).collect();
        let get = move |k: &str| {
            Ok(parts
                .iter()
                .find(|(key, _)| *key == k)
                .map_or(Part::Json(serde_json::Value::Null), |(_, p)| p.clone()))
        };
        PathInput::read(PathValue::Object { keys, get: &get })
    };
    let points = || ("points", Part::Float64(two.clone()));
    let e = obj(vec![points(), ("motion", Part::Json(json!([0, 1])))])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("path.motion: unknown key"), "{}", e);
    let e = obj(vec![("points", Part::Json(json!([0, 0, 0, 0, 0, 1])))])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("points: expected a Float64Array"), "{}", e);
    let e = obj(vec![points(), ("motions", Part::Uint8(vec![0, 7]))])
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("motions[1]: expected 0 (rapid), 1 (feed) or 2 (arc), got 7"),
        "{}",
        e
    );
    let e = obj(vec![points(), ("readFor", Part::Json(json!("CAZ")))])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("readFor: readFor names the machine"), "{}", e);
    let ok = obj(vec![
        points(),
        ("motions", Part::Json(json!([0, 1]))),
        ("angles", Part::Float64(vec![0.0, 0.0, 10.0, 5.0])),
        ("readFor", Part::Json(json!("CAZ"))),
    ])
    .unwrap();
    assert_eq!(ok.tips[1], Vector3::new(10.0, 0.0, 0.0));
    assert_eq!(ok.commands.as_ref().unwrap().0[1], [10.0, 5.0]);
    assert_eq!(ok.commands.unwrap().1, rtype("CAZ"));
}

/// A program's commands are followed to the ends of their travel, and within the travel's
/// tolerance (10⁻⁹ rad) beyond: A from −120° to 30°, commanded at 30°, −120° and 30° + 5·10⁻⁸°
/// (8.7·10⁻¹⁰ rad); 2·10⁻⁷° (3.5·10⁻⁹ rad) beyond either end is outside, and the message says
/// where.
// Found by cargo-mutants: the travel's tolerance (`lo − tol` as `lo + tol`, `hi + tol` as
// `hi − tol`, `hi · tol`) survived.
#[test]
fn commands_are_followed_to_the_ends_of_their_travel() {
    let m = model(json!({"rotary": {"mFrom": -120, "mTo": 30}}), rtype("CAZ"));
    let inside = [[0.0, 30.0], [10.0, -120.0], [0.0, 30.0 + 5e-8]];
    let f = follow_commands(&m, &inside);
    assert!(f.unreachable.is_none(), "{:?}", f.unreachable);
    let m_rad: Vec<f64> = inside.iter().map(|a| a[1].to_radians()).collect();
    assert_eq!(f.m, m_rad);
    for (a, end) in [(30.0 + 2e-7, "30"), (-120.0 - 2e-7, "-120")] {
        let f = follow_commands(&m, &[[0.0, 0.0], [0.0, a]]);
        let (at, why) = f.unreachable.unwrap();
        assert_eq!((at, f.m.len()), (1, 1), "{a}");
        assert!(
            why.starts_with(&format!(
                "commanded A = {end}°, outside the travel of A (-120° to 30°)"
            )),
            "{why}"
        );
    }
}

/// The rapids of a path on one machine, by their commands (C/A, L = 100 mm): K turning 20° at
/// A = 25° (a cone: δ > 0), A turning −15° alone (a great circle), a rapid that turns nothing,
/// and the first two rapids again. Four swing the rotary axes; the largest swing of K is 20°, of
/// M 15°; the largest δ is the first of the two equal ones; each rapid move lists its segment,
/// its signed turns and its δ, against dense sampling of the move.
// Found by cargo-mutants: the rapids' swings (`||` as `&&`, `>` as `==` or `<`), M's swing (`−`
// as `+`), the first of equal maxima (`>` as `>=`) and `rapid_moves` (its turns, or none)
// survived.
#[test]
fn the_rapids_are_counted_with_their_swings_and_listed() {
    let t = rtype("CAZ");
    let m = model(json!({}), t);
    let deg = [
        [0.0, 25.0],
        [20.0, 25.0],
        [20.0, 25.0],
        [20.0, 10.0],
        [20.0, 10.0],
        [0.0, 25.0],
        [20.0, 25.0],
        [20.0, 10.0],
    ];
    let motions = [
        Motion::Feed,
        Motion::Rapid,
        Motion::Feed,
        Motion::Rapid,
        Motion::Rapid,
        Motion::Feed,
        Motion::Rapid,
        Motion::Rapid,
    ];
    let axes: Vec<Vector3<f64>> = deg
        .iter()
        .map(|a| common::toolpath::caz(a[0], a[1]))
        .collect();
    let path = Path {
        axes: &axes,
        motions: Some(&motions),
        commands: Some(Commands {
            angles: &deg,
            rtype: t,
        }),
    };
    let a = analyse_path(&m, &path, 100.0, 0.01).unwrap();
    let r = &a.summary.rapids;
    assert_eq!((r.count, r.swings), (5, 4));
    assert!(
        (r.k_swing - 20f64.to_radians()).abs() < 1e-15,
        "{}",
        r.k_swing
    );
    assert!(
        (r.m_swing - 15f64.to_radians()).abs() < 1e-15,
        "{}",
        r.m_swing
    );
    let rad = |x: f64| x.to_radians();
    let cone = dense_delta(
        t,
        (1.0, 1.0),
        (0.0, rad(25.0)),
        (rad(20.0), rad(25.0)),
        100.0,
    );
    assert!(cone > 0.1, "{cone}");
    assert!(
        (r.max - cone).abs() < 1e-4 * cone,
        "{} against {cone}",
        r.max
    );
    assert_eq!(r.max_segment, 0);
    let moves: Vec<_> = a
        .rapid_moves()
        .iter()
        .map(|v| {
            (
                v.segment,
                v.k_turn.to_degrees().round(),
                v.m_turn.to_degrees().round(),
            )
        })
        .collect();
    assert_eq!(
        moves,
        [
            (0, 20.0, 0.0),
            (2, 0.0, -15.0),
            (3, 0.0, 0.0),
            (5, 20.0, 0.0),
            (6, 0.0, -15.0)
        ]
    );
    let ex: Vec<f64> = a.rapid_moves().iter().map(|v| v.excursion).collect();
    assert_eq!(ex[0], r.max);
    assert_eq!(ex[3], ex[0]);
    // The great circle's δ is 0 to rounding; the move that turns nothing measures the chord
    // |P − V₀| as √(2 − 2 P·V₀), which the rounding of |V₀|² (10⁻¹⁶) makes √(2·10⁻¹⁶)·L ≈ 1.4 nm.
    assert!(ex[1] < 1e-9 && ex[2] < 2e-6, "{ex:?}");
}

/// Refining a path the program commands keeps the program's commands: C commanded from 0° to
/// 350° at A = 30° in one cutting block swings C round though the tool turns 10° the other way;
/// pieces that follow the tool (C to −10°) would not be the program's, so the segment is left as
/// it is and listed. A tool axis of zero is refused with the point's path.
// Found by cargo-mutants: the check that the pieces end at the commanded angles (the guard as
// `true`, `&&` as `||`) and the point's index in an error (`i + 1` as `i · 1`) survived.
#[test]
fn refining_keeps_the_program_s_commands() {
    let t = rtype("CAZ");
    let m = model(json!({}), t);
    let deg = [[0.0, 30.0], [350.0, 30.0]];
    let axes: Vec<Vector3<f64>> = deg
        .iter()
        .map(|a| common::toolpath::caz(a[0], a[1]))
        .collect();
    let path = Path {
        axes: &axes,
        motions: None,
        commands: Some(Commands {
            angles: &deg,
            rtype: t,
        }),
    };
    let tips = [Vector3::zeros(), Vector3::x()];
    let r = refine_path(&m, &tips, &path, 100.0, 0.01).unwrap();
    assert_eq!((r.added, r.unfixed.clone()), (0, vec![0]));
    assert_eq!(r.k, [0.0, 350f64.to_radians()]);
    let tips = [Vector3::zeros(); 3];
    let e = refine(
        &m,
        &tips,
        &[Vector3::z(), Vector3::x(), Vector3::zeros()],
        100.0,
        0.01,
    )
    .unwrap_err();
    assert_eq!(e.field, "points[2]", "{e}");
}
