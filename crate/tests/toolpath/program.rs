//! A program read and ranked as the machine runs it (`fiveaxis::toolpath`): the headline and
//! every statistic on the cutting segments, the rapids apart; the machine the program was
//! written for following its own commands (branch and turns), within its travel or turning
//! without limit.
//!
//! The closed form used: when only K (C about Z) turns, by `Δ`, at a constant tilt `a` of M
//! (A about X), the tool axis `V(θ) = (sin a sin θ, −sin a cos θ, cos a)` sweeps a cone while
//! the programmed motion is the great circle through its ends. Taking the ends at `θ = ±h`,
//! `h = Δ/2`, the great circle's normal is `n ∝ V(−h) × V(h) ∝ (0, cos a, sin a cos h)`, and
//! `V(θ)·n = sin a cos a (cos h − cos θ)/√(cos²a + sin²a cos²h)`, largest at `θ = 0`, the
//! middle. So `δ = L·sin a cos a (1 − cos h)/√(cos²a + sin²a cos²h)`.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::read_all;
use fiveaxis::machine::Machine;
use fiveaxis::rotary::RotaryType;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{Format, Motion, Point};
use fiveaxis::toolpath::{
    analyse_path, compare_path, machine_of_type, refine_path, Commands, Path,
};
use nalgebra::Vector3;
use serde_json::json;

/// δ of a turn of K by `delta` degrees at a tilt `a` degrees, at `L = l` (module docs).
fn cone(l: f64, a: f64, delta: f64) -> f64 {
    let (s, c) = a.to_radians().sin_cos();
    let h = (delta / 2.0).to_radians();
    l * s * c * (1.0 - h.cos()) / (c * c + s * s * h.cos() * h.cos()).sqrt()
}

/// An A/C trunnion (table-table CAZ), A from −120° to 30°, C turning without limit.
fn trunnion(continuous: bool) -> Machine {
    Machine::from_value(
        &json!({ "kind": "table-table", "type": "CAZ",
                 "rotary": { "mFrom": -120, "mTo": 30, "kContinuous": continuous } }),
        "machine",
    )
    .unwrap()
}

/// The parts of a path of points read from a file.
struct Parts {
    axes: Vec<Vector3<f64>>,
    tips: Vec<Vector3<f64>>,
    motions: Vec<Motion>,
    angles: Vec<[f64; 2]>,
}

impl Parts {
    fn of(points: &[Point]) -> Parts {
        Parts {
            axes: points.iter().map(|p| p.axis).collect(),
            tips: points.iter().map(|p| p.tip).collect(),
            motions: points.iter().map(|p| p.motion).collect(),
            angles: points.iter().map(|p| p.angles.unwrap()).collect(),
        }
    }

    fn path(&self, rtype: RotaryType) -> Path<'_> {
        Path {
            axes: &self.axes,
            motions: Some(&self.motions),
            commands: Some(Commands {
                angles: &self.angles,
                rtype,
            }),
        }
    }
}

const PROGRAM: &str = "%\n\
                       G90 G21 G43.4 H1\n\
                       G0 X0 Y0 Z50 C0 A0\n\
                       G0 A-75 C270 (a rapid swing: A by 75°, C by 270°)\n\
                       G1 X10 C300 F1000 (cutting: C by 30° at A −75°)\n\
                       G1 X20 C360 (cutting: C by 60° at A −75°)\n\
                       M30\n\
                       %\n";

#[test]
fn the_headline_is_the_worst_cutting_segment_and_the_rapid_swing_is_apart() {
    let m = trunnion(true);
    let (points, report) = read_all(PROGRAM, Format::Nc, Some(&m));
    assert_eq!(report.rapids, 1);
    let parts = Parts::of(&points);
    let path = parts.path(caz_type());
    let model = m.without_errors().build().unwrap();
    let a = analyse_path(&model, &path, 100.0, 0.01).unwrap();
    assert!(a.summary.commanded);
    // Segment 0 the rapid, 1 and 2 the cuts: δ1 = cone(100, 75, 30) = 0.880 mm, δ2 =
    // cone(100, 75, 60) = 3.825 mm.
    let (d1, d2) = (cone(100.0, 75.0, 30.0), cone(100.0, 75.0, 60.0));
    assert!(
        (d1 - 0.8798).abs() < 1e-4 && (d2 - 3.8251).abs() < 1e-4,
        "{d1} {d2}"
    );
    assert!(a.segments[0].rapid && !a.segments[1].rapid && !a.segments[2].rapid);
    assert!(
        (a.segments[1].delta - d1).abs() < 1e-9 * d1,
        "{}",
        a.segments[1].delta
    );
    assert!(
        (a.segments[2].delta - d2).abs() < 1e-9 * d2,
        "{}",
        a.segments[2].delta
    );
    let s = &a.summary;
    assert_eq!((s.segments, s.max_segment), (2, 2));
    assert!((s.max - d2).abs() < 1e-9 * d2);
    assert!((s.mean - (d1 + d2) / 2.0).abs() < 1e-9);
    assert_eq!(s.above, 2);
    // The rapid: one, swinging A by 75° and C by 270°, its excursion larger than any cut's.
    assert_eq!(
        (s.rapids.count, s.rapids.swings, s.rapids.max_segment),
        (1, 1, 0)
    );
    assert!((s.rapids.m_swing.to_degrees() - 75.0).abs() < 1e-9);
    assert!((s.rapids.k_swing.to_degrees() - 270.0).abs() < 1e-9);
    assert!(s.rapids.max > d2, "{}", s.rapids.max);
    // The ranking: every row's largest δ is that of a cutting segment of its own analysis.
    let rows = compare_path(&m, &path, 100.0, 0.01, &RotaryType::ALL).unwrap();
    for r in &rows {
        let own = analyse_path(
            &machine_of_type(&m, r.rtype).build().unwrap(),
            &path,
            100.0,
            0.01,
        )
        .unwrap();
        let cut = own
            .segments
            .iter()
            .filter(|g| !g.rapid)
            .map(|g| g.delta)
            .fold(0.0, f64::max);
        assert_eq!(r.max, cut, "{}", r.rtype.name());
        assert_eq!(r.commanded, r.rtype == caz_type());
    }
    let own = rows.iter().find(|r| r.rtype == caz_type()).unwrap();
    assert!((own.max - d2).abs() < 1e-9 * d2);
}

#[test]
fn the_machine_follows_the_program_s_own_turns_within_its_travel_or_without_limit() {
    // C winds past a turn, as an impeller program does: 0° → −200° → −399.8°, tilted at A −30°.
    let text = "G43.4 H1\nG0 X0 Y0 Z50 C0 A-30\nG1 C-200\nG1 C-399.8\n";
    let m = trunnion(true);
    let (points, _) = read_all(text, Format::Nc, Some(&m));
    let parts = Parts::of(&points);
    let model = m.without_errors().build().unwrap();
    let a = analyse_path(&model, &parts.path(caz_type()), 100.0, 0.01).unwrap();
    assert_eq!(a.summary.unreachable, None);
    let c: Vec<f64> = a.following.k.iter().map(|k| k.to_degrees()).collect();
    assert!((c[2] + 399.8).abs() < 1e-9, "{c:?}");
    assert!((a.summary.k_travel.to_degrees() - 399.8).abs() < 1e-9);
    // δ of each cut is the cone's: C by 200° and by 199.8° at A −30°.
    assert!((a.segments[0].delta - cone(100.0, -30.0, 200.0).abs()).abs() < 1e-9);
    assert!((a.segments[1].delta - cone(100.0, -30.0, 199.8).abs()).abs() < 1e-9);
    // Within ±360° the machine cannot: the first point outside is named with its command.
    let limited = trunnion(false);
    let model = limited.without_errors().build().unwrap();
    let a = analyse_path(&model, &parts.path(caz_type()), 100.0, 0.01).unwrap();
    let u = a.summary.unreachable.unwrap();
    assert_eq!(u.point, 2);
    assert!(
        u.message
            .starts_with("commanded C = -399.8°, outside the travel of C (-360° to 360°)"),
        "{}",
        u.message
    );
    assert!(
        u.message.contains("continuous box"),
        "C is the table: {}",
        u.message
    );
    // A (−120° to 30°) is the tilt: no continuous box is offered for it.
    let (points, _) = read_all(
        "G43.4 H1\nG0 X0 Y0 Z50 C0 A-30\nG1 A45\n",
        Format::Nc,
        Some(&m),
    );
    let parts = Parts::of(&points);
    let a = analyse_path(&model, &parts.path(caz_type()), 100.0, 0.01).unwrap();
    let u = a.summary.unreachable.unwrap();
    assert!(
        u.message
            .starts_with("commanded A = 45°, outside the travel of A (-120° to 30°)")
            && !u.message.contains("continuous"),
        "{}",
        u.message
    );
}

#[test]
fn refining_inserts_points_into_cuts_only() {
    let m = trunnion(true);
    let (points, _) = read_all(PROGRAM, Format::Nc, Some(&m));
    let parts = Parts::of(&points);
    let model = m.without_errors().build().unwrap();
    let r = refine_path(&model, &parts.tips, &parts.path(caz_type()), 100.0, 0.01).unwrap();
    // The rapid (points 0 → 1) gets none; each cut gets enough for 10 µm; every original point
    // keeps the program's commands.
    assert_eq!(r.source[0], Some(0));
    assert_eq!(r.source[1], Some(1));
    assert!(r.added > 0 && r.max <= 0.01);
    for (i, s) in r.source.iter().enumerate() {
        if let Some(j) = s {
            assert!((r.k[i].to_degrees() - parts.angles[*j][0]).abs() < 1e-9);
            assert!((r.m[i].to_degrees() - parts.angles[*j][1]).abs() < 1e-9);
        }
    }
    assert_eq!(r.motions[1], Motion::Rapid);
    assert!(r.motions[2..].iter().all(|m| *m == Motion::Feed));
}

/// The type CAZ.
fn caz_type() -> RotaryType {
    RotaryType::parse("CAZ").unwrap()
}

/// The travel of the rotary axes in the summary is along the cutting moves: a rapid that turns
/// C by 90° is not counted (0 → 90 at rapid, then 90 → −110 cutting: 200°).
#[test]
fn the_travel_counts_the_cutting_moves_only() {
    let m = trunnion(true);
    let (points, _) = read_all(
        "G43.4 H1\nG0 X0 Y0 Z50 C0 A-30\nG0 C90\nG1 C-110 F500\n",
        Format::Nc,
        Some(&m),
    );
    let parts = Parts::of(&points);
    let model = m.without_errors().build().unwrap();
    let a = analyse_path(&model, &parts.path(caz_type()), 100.0, 0.01).unwrap();
    assert!(
        (a.summary.k_travel.to_degrees() - 200.0).abs() < 1e-9,
        "{}",
        a.summary.k_travel.to_degrees()
    );
    assert_eq!(a.summary.m_travel, 0.0);
}
