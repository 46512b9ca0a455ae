//! The toolpath analysis by its definitions: K's sense per segment against dense sampling, flips
//! and arcs over the pole, the arc distance's closed form, slerp, the first of equal maxima, the
//! ranking's rows, the swing length and the file formats' parsers.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::tilted;
use fiveaxis::machine::Machine;
use fiveaxis::rotary::{Pose, RotaryType};
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{AptFrameChoice, Format, Motion, ReadOptions, UnitChoice};
use fiveaxis::toolpath::{
    analyse, analyse_path, arc_distance, machine_of_type, refine, slerp, Commands, Path,
    ToolpathCase, ToolpathReadInput,
};
use nalgebra::Vector3;
use serde_json::json;

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// Each named format is the parser's format of that name; `auto` leaves it to detection.
#[test]
fn each_file_format_names_its_parser() {
    let format = |f: &str| {
        ToolpathReadInput::read(&json!({ "format": f }))
            .unwrap()
            .format
            .format()
    };
    assert_eq!(format("auto"), None);
    assert_eq!(format("csv"), Some(Format::Csv));
    assert_eq!(format("apt"), Some(Format::Apt));
    assert_eq!(format("nc"), Some(Format::Nc));
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// `L` as given; left out, a head's pivot length plus tool length (the README's definition:
/// 250 + 120 = 370 mm).
#[test]
fn the_swing_length_is_the_given_one_or_pivot_plus_tool() {
    let head =
        json!({ "kind": "head-table", "geometry": { "pivotLength": 250, "toolLength": 120 } });
    let given = ToolpathCase::read(&json!({ "machine": head, "length": 80 })).unwrap();
    assert_eq!(given.length().unwrap(), 80.0);
    let machine = ToolpathCase::read(&json!({ "machine": head })).unwrap();
    assert_eq!(machine.length().unwrap(), 370.0);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// A ranking has one row per type asked for, each of that type, each over every segment of the
/// path (n points: n − 1 segments).
#[test]
fn the_ranking_has_one_row_per_type_over_every_segment() {
    let case = ToolpathCase::read(&json!({ "length": 100 })).unwrap();
    let axes: Vec<Vector3<f64>> = (0..5)
        .map(|i| {
            let a = 0.2 * f64::from(i);
            Vector3::new(a.sin(), 0.3 * a.sin(), a.cos()).normalize()
        })
        .collect();
    let types = [RotaryType::ALL[0], RotaryType::ALL[5], RotaryType::ALL[11]];
    let rows = case
        .compare(&fiveaxis::toolpath::Path::axes(&axes), &types)
        .unwrap();
    assert_eq!(rows.len(), types.len());
    for r in &rows {
        assert!(types.contains(&r.rtype));
        assert_eq!(r.segments, axes.len() - 1);
    }
}

// ---- Mutants of `crate/src/toolpath/mod.rs` left by the full run (segment flags, the arc's
// distance from the pole, slerp, refinement), each checked against its documented meaning.

fn model(machine: serde_json::Value, name: &str) -> fiveaxis::machine::Model {
    let m = Machine::from_value(&machine, "machine").unwrap();
    machine_of_type(&m, RotaryType::parse(name).unwrap())
        .build()
        .unwrap()
}

/// Angle between unit vectors, accurate near 0 and π (atan2 of the cross and dot products).
fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// With K turning against ISO 841 (`kReversed`) and M not, each segment's δ is the largest
/// distance of `L·P(u)` from the plane of its ends, where `P(u)` is the tool axis of the
/// linearly interpolated commands with K's sense applied: sampled densely here (2001 points),
/// with the sense found as the one that reproduces the path's axes.
#[test]
fn a_reversed_k_axis_is_applied_to_the_commands_of_each_segment() {
    let t = RotaryType::parse("CAZ").unwrap();
    let m = model(json!({ "rotary": { "kReversed": true } }), "CAZ");
    let axes: Vec<Vector3<f64>> = (0..6)
        .map(|i| tilted(15.0 + 8.0 * f64::from(i), 17.0 * f64::from(i)))
        .collect();
    let a = analyse(&m, &axes, 100.0, 0.01).unwrap();
    let f = &a.following;
    let reproduces = |fk: f64, fm: f64| {
        (0..axes.len())
            .all(|i| (t.tool_vector(Pose::new(fk * f.k[i], fm * f.m[i])) - axes[i]).norm() < 1e-9)
    };
    let senses = [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)];
    let (fk, fm) = *senses.iter().find(|s| reproduces(s.0, s.1)).unwrap();
    assert_eq!(fk * fm, -1.0, "one axis reversed, the other not");
    for (i, s) in a.segments.iter().enumerate() {
        let p = |u: f64| {
            t.tool_vector(Pose::new(
                fk * (f.k[i] + u * (f.k[i + 1] - f.k[i])),
                fm * (f.m[i] + u * (f.m[i + 1] - f.m[i])),
            ))
        };
        let n = p(0.0).cross(&p(1.0)).normalize();
        let dense = (0..=2000)
            .map(|j| 100.0 * p(f64::from(j) / 2000.0).dot(&n).abs())
            .fold(0.0, f64::max);
        assert!(dense > 1e-3, "segment {i} has a nonlinear error to compare");
        assert!(
            (s.delta - dense).abs() < 1e-6 * dense + 1e-12,
            "segment {i}: {} vs {dense}",
            s.delta
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// A flip (module docs): the larger of |ΔK|, |ΔM| above 30° *and* |ΔK| + |ΔM| above 10 times
/// the angle the tool turns. A 40° turn of C at a tilt of 60° turns the tool by 34.4° (far more
/// than a tenth of 40°): no flip. Leaving the vertical (the pole of C) in a 3.1° tilt towards an
/// azimuth 31° from where C stands: |ΔK| = 31° > 30° and 31° + 3.1° > 10 · 3.1°, a flip (one
/// that only the sum reaches: 31° − 3.1° would not).
#[test]
fn a_flip_needs_a_large_command_and_far_more_command_than_tool_turn() {
    let m = model(json!({}), "CAZ");
    let wide = analyse(&m, &[tilted(60.0, 0.0), tilted(60.0, 40.0)], 100.0, 1.0).unwrap();
    let (dk, dm) = (
        (wide.following.k[1] - wide.following.k[0])
            .abs()
            .to_degrees(),
        (wide.following.m[1] - wide.following.m[0])
            .abs()
            .to_degrees(),
    );
    assert!((dk - 40.0).abs() < 1e-9 && dm < 1e-9, "{dk} {dm}");
    assert!(!wide.segments[0].flip);
    assert_eq!(wide.summary.flips, 0);

    let path = [tilted(3.1, 0.0), Vector3::z(), tilted(3.1, 31.0)];
    let a = analyse(&m, &path, 100.0, 1.0).unwrap();
    let f = &a.following;
    let (dk, dm) = (
        (f.k[2] - f.k[1]).abs().to_degrees(),
        (f.m[2] - f.m[1]).abs().to_degrees(),
    );
    assert!(
        (dk - 31.0).abs() < 1e-9 && (dm - 3.1).abs() < 1e-9,
        "{dk} {dm}"
    );
    assert!(a.segments[1].flip);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// The pole flag follows the whole arc, not its ends: at a tilt of 80° from the vertical, from
/// azimuth 0° to 180°, the tool passes right over the vertical (the pole of C on CAZ), 80° from
/// either end. The same on ABZ near −X (its K = A, the tool along −X at B = −90°): the arc from
/// tilt 88° to 92° at azimuth 180.5° passes 0.5° from −X.
#[test]
fn an_arc_over_the_pole_is_flagged_though_its_ends_are_far_from_it() {
    let caz = model(json!({}), "CAZ");
    let over = analyse(&caz, &[tilted(80.0, 0.0), tilted(80.0, 180.0)], 100.0, 1.0).unwrap();
    assert!(over.segments[0].pole);
    let abz = model(json!({}), "ABZ");
    let minus_x = [tilted(88.0, 180.5), tilted(92.0, 180.5)];
    assert!(angle(&minus_x[0], &-Vector3::x()) > 2.0_f64.to_radians());
    let a = analyse(&abz, &minus_x, 100.0, 1.0).unwrap();
    assert!(a.following.unreachable.is_none());
    assert!(a.segments[0].pole);
    // The same arc turned to +X: flagged as well; and one 3° away from ±X: not.
    let plus_x = [tilted(88.0, 0.5), tilted(92.0, 0.5)];
    assert!(analyse(&abz, &plus_x, 100.0, 1.0).unwrap().segments[0].pole);
    let aside = [tilted(88.0, 183.0), tilted(92.0, 183.0)];
    assert!(!analyse(&abz, &aside, 100.0, 1.0).unwrap().segments[0].pole);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// Tool axes of any length (module docs): a path given as vectors 1000 mm long is analysed as
/// the unit path, including the pole flag of a short segment that starts 0.6° from the pole.
#[test]
fn tool_axes_of_any_length_give_the_analysis_of_the_unit_axes() {
    let m = model(json!({}), "CAZ");
    let unit = [tilted(0.6, 0.0), tilted(0.7, 10.0), tilted(5.0, 40.0)];
    let long: Vec<Vector3<f64>> = unit.iter().map(|a| a * 1000.0).collect();
    let a = analyse(&m, &unit, 100.0, 0.01).unwrap();
    assert!(a.segments[0].pole);
    let b = analyse(&m, &long, 100.0, 0.01).unwrap();
    for (s, t) in a.segments.iter().zip(&b.segments) {
        assert_eq!((s.pole, s.flip), (t.pole, t.flip));
        assert!((s.delta - t.delta).abs() < 1e-12);
    }
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// The arc's angular distance from a point, against the closed form: the great circle through
/// `x` and `e = (0, sin d, cos d)` has normal `(0, −cos d, sin d)`, so +Z is `d` from it, its
/// foot `e` inside the arc from −80° to +80° about `e`. Off the arc's span, the nearer end
/// counts; a zero-length arc is its end; a point on the circle's axis is 90° from all of it.
#[test]
fn the_distance_from_an_arc_is_to_its_nearest_point() {
    for d_deg in [0.3, 1.0002, 1.5, 20.0] {
        let d = f64::to_radians(d_deg);
        let (x, e) = (Vector3::x(), Vector3::new(0.0, d.sin(), d.cos()));
        let on = |t: f64| e * t.to_radians().cos() + x * t.to_radians().sin();
        let got = arc_distance(&on(-80.0), &on(80.0), &Vector3::z());
        assert!((got - d).abs() < 1e-12, "{d_deg}°: {}", got.to_degrees());
        // The arc from 10° to 80° misses the foot: its nearest point is its end at 10°.
        let end = angle(&on(10.0), &Vector3::z());
        assert!((arc_distance(&on(10.0), &on(80.0), &Vector3::z()) - end).abs() < 1e-12);
    }
    let a = tilted(30.0, 20.0);
    let p = tilted(50.0, 70.0);
    assert!((arc_distance(&a, &a, &p) - angle(&a, &p)).abs() < 1e-12);
    let n = Vector3::x().cross(&Vector3::y());
    let q = arc_distance(&Vector3::x(), &Vector3::y(), &n);
    assert!((q - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// Slerp: a unit vector `u·θ` from `a` on the arc to `b`; of opposite vectors, the normalised
/// straight interpolation (module docs): `a` before the middle and at it, `b` after.
#[test]
fn slerp_is_uniform_on_the_arc_and_picks_an_end_of_opposite_vectors() {
    let (a, b) = (tilted(10.0, 0.0), tilted(70.0, 50.0));
    let theta = angle(&a, &b);
    for u in [0.0, 0.25, 0.5, 0.9, 1.0] {
        let v = slerp(&a, &b, u);
        assert!((v.norm() - 1.0).abs() < 1e-12);
        assert!((angle(&a, &v) - u * theta).abs() < 1e-9, "{u}");
        assert!((angle(&v, &b) - (1.0 - u) * theta).abs() < 1e-9, "{u}");
    }
    assert!((slerp(&a, &a, 0.3) - a).norm() < 1e-15);
    assert!((slerp(&a, &-a, 0.25) - a).norm() < 1e-15);
    assert!((slerp(&a, &-a, 0.5) - a).norm() < 1e-15);
    assert!((slerp(&a, &-a, 0.75) + a).norm() < 1e-15);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// The statistics at their edges: a segment whose δ equals the tolerance is not above it, one
/// a hair over is; of equal largest δ (points repeated: δ = 0) the first segment is named.
#[test]
fn a_delta_at_the_tolerance_is_within_it_and_the_first_of_equal_maxima_is_named() {
    let m = model(json!({}), "CAZ");
    let path = [tilted(20.0, 0.0), tilted(30.0, 35.0)];
    let d = analyse(&m, &path, 100.0, 1.0).unwrap().segments[0].delta;
    assert!(d > 1e-3);
    assert_eq!(analyse(&m, &path, 100.0, d).unwrap().summary.above, 0);
    assert_eq!(
        analyse(&m, &path, 100.0, d * (1.0 - 1e-9))
            .unwrap()
            .summary
            .above,
        1
    );
    let still = [tilted(20.0, 10.0); 4];
    let s = analyse(&m, &still, 100.0, 0.01).unwrap().summary;
    assert_eq!((s.max, s.max_segment), (0.0, 0));
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// Refinement keeps each original point's tip and puts the inserted ones at equal fractions of
/// the straight line between the segment's end tips (equal pieces, module docs). A path of two
/// points is enough; one point, or tips and axes of different counts, are refused.
#[test]
fn refined_tips_are_the_given_ones_and_equal_steps_between_them() {
    let m = model(json!({}), "CBZ");
    let axes = [tilted(20.0, 0.0), tilted(21.0, 3.0), tilted(45.0, 60.0)];
    let tips = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(10.0, 5.0, -2.0),
        Vector3::new(40.0, -25.0, 7.0),
    ];
    let r = refine(&m, &tips, &axes, 200.0, 0.01).unwrap();
    let at = |j: usize| r.source.iter().position(|s| *s == Some(j)).unwrap();
    for (j, tip) in tips.iter().enumerate() {
        assert_eq!(r.tips[at(j)], *tip, "point {j}");
    }
    let n = at(2) - at(1);
    assert!(n >= 2, "the long segment is cut ({n} pieces)");
    for p in 1..n {
        let want = tips[1] + (tips[2] - tips[1]) * (p as f64 / n as f64);
        assert!((r.tips[at(1) + p] - want).norm() < 1e-9, "piece {p}");
    }
    assert!(refine(&m, &tips[..2], &axes[..2], 200.0, 0.01).is_ok());
    let err = refine(&m, &tips[..1], &axes[..1], 200.0, 0.01).unwrap_err();
    assert_eq!(err.field, "points");
    let err = refine(&m, &tips, &axes[..2], 200.0, 0.01).unwrap_err();
    assert_eq!(err.field, "points");
}

/// A toolpath input checks its machine as it is read (a travel of A from 30° to −10° is
/// refused at `machine.rotary.mTo`), the reader's options are the ones given, and a path's
/// motions and commands must be one per point and finite, each refused with its field.
// Found by cargo-mutants: the inputs' checks (`check` as `Ok(())`), `options` (as the
// defaults) and `Path::check` survived: the binding's tests call them only under WebAssembly.
#[test]
fn toolpath_inputs_check_their_machine_options_and_path() {
    let bad = json!({ "rotary": { "mFrom": 30, "mTo": -10 } });
    let e = ToolpathReadInput::read(&json!({ "machine": bad })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
    let e = ToolpathCase::read(&json!({ "machine": bad })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
    let o = ToolpathReadInput::read(&json!({
        "unit": "inch", "chordTolerance": 0.005, "aptFrame": "ignore"
    }))
    .unwrap()
    .options();
    assert_eq!(
        o,
        ReadOptions {
            unit: UnitChoice::Inch,
            chord_tolerance: 0.005,
            apt_frame: AptFrameChoice::Ignore
        }
    );
    let m = Machine::standard().unwrap().build().unwrap();
    let axes = [Vector3::z(), Vector3::new(0.0, 0.1, 1.0).normalize()];
    let rtype = m.layout.rtype;
    let refused = |path: Path, field: &str| {
        let e = analyse_path(&m, &path, 100.0, 0.01).unwrap_err();
        assert_eq!(e.field, field, "{e}");
    };
    refused(
        Path {
            axes: &axes,
            motions: Some(&[Motion::Feed]),
            commands: None,
        },
        "motions",
    );
    refused(
        Path {
            axes: &axes,
            motions: None,
            commands: Some(Commands {
                angles: &[[0.0, 0.0]],
                rtype,
            }),
        },
        "angles",
    );
    refused(
        Path {
            axes: &axes,
            motions: None,
            commands: Some(Commands {
                angles: &[[0.0, 0.0], [f64::NAN, 0.0]],
                rtype,
            }),
        },
        "angles[1]",
    );
}
