//! Real programs written outside this project (`crate/tests/data/toolpath/`, each with its
//! repository, path, commit and licence in the README there and beside its test below), read as
//! a machine would read them, with points checked at a few blocks by hand.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use common::toolpath::{caz, chords, close_vec, note, read_all, skipped};
use fiveaxis::machine::Machine;
use fiveaxis::rotary::RotaryType;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{read, Format, LengthUnit, Motion, NoteKind, Point, ReadOptions};
use fiveaxis::toolpath::{compare_path, Commands, Path};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI};

fn file(name: &str) -> String {
    let path = format!("{}/tests/data/toolpath/{name}", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).unwrap();
    String::from_utf8(bytes).unwrap()
}

/// An A/C trunnion (table-table CAZ): A from −120° to 30°, C turning without limit.
fn trunnion() -> Machine {
    Machine::from_value(
        &serde_json::json!({ "kind": "table-table", "type": "CAZ",
                             "rotary": { "mFrom": -120, "mTo": 30, "kContinuous": true } }),
        "machine",
    )
    .unwrap()
}

/// The points of file line `line`.
fn at_line(p: &[Point], line: u32) -> Vec<&Point> {
    p.iter().filter(|q| q.line == line).collect()
}

/// LinuxCNC/linuxcnc, `configs/sim/axis/vismach/5axis/table-rotary-tilting/demos/
/// boat-xyzac.ngc` (commit 55084aa), GPL-2.0: CAM output for an A/C trunnion ("FC HERMLE 5
/// AXIS MILLING"), tool-centre-point kinematics switched on by `M428`.
#[test]
fn a_five_axis_cam_program_for_an_a_c_trunnion() {
    let m = trunnion();
    let (p, r) = read_all(&file("linuxcnc_boat-xyzac.ngc"), Format::Nc, Some(&m));
    assert_eq!(
        r.tcp.as_deref(),
        Some("M428 (LinuxCNC tool-centre-point kinematics) on line 2")
    );
    assert!(r
        .unit_reason
        .starts_with("millimetres: the file states no unit"));
    // Line 51, G02 Y22.345 I4.051 J-2.931 from (−48.713, 20.275) (X of line 50, Y of
    // line 49): centre (−44.662, 17.344), 5.000136 from the start, 5.001 from the end.
    let arc = at_line(&p, 51);
    let c = Vector3::new(-44.662, 17.344, -6.625);
    for q in &arc {
        let d = (q.tip - c).norm();
        assert!(
            q.motion == Motion::Arc && (5.000136 - 1e-6..=5.001 + 1e-6).contains(&d),
            "{d}"
        );
    }
    close_vec(
        &arc[arc.len() - 1].tip,
        &Vector3::new(-44.662, 22.345, -6.625),
        1e-12,
        "arc end",
    );
    // Line 433, X-38.78 Y0.578 Z-1.054 C13.027: the tip as written, the commands, and
    // the tool axis R_Z(C)·R_X(A)·e_Z.
    let q = at_line(&p, 433)[0];
    assert_eq!(
        (q.tip, q.motion),
        (Vector3::new(-38.78, 0.578, -1.054), Motion::Feed)
    );
    assert_eq!(q.angles, Some([13.027, -10.74]));
    close_vec(&q.axis, &caz(13.027, -10.74), 1e-15, "axis");
    // Line 1860, A-75.0 C270.0 after the G0 of line 1859: a rapid swing.
    let swing = at_line(&p, 1860)[0];
    assert_eq!(
        (swing.motion, swing.angles),
        (Motion::Rapid, Some([270.0, -75.0]))
    );

    // The ranking on the machine it was written for: the headline is a cutting block's, the
    // C jump next to the pole of line 433 (C −25.599° → 13.027°, A −5.546° → −10.74°), not a
    // rapid's. δ here by sampling the interpolated tool axis against its great circle.
    let axes: Vec<_> = p.iter().map(|q| q.axis).collect();
    let motions: Vec<_> = p.iter().map(|q| q.motion).collect();
    let angles: Vec<_> = p.iter().map(|q| q.angles.unwrap()).collect();
    let path = Path {
        axes: &axes,
        motions: Some(&motions),
        commands: Some(Commands {
            angles: &angles,
            rtype: m.rotary_type,
        }),
    };
    let rows = compare_path(&m, &path, 100.0, 0.01, &[m.rotary_type]).unwrap();
    let own = &rows[0];
    assert!(own.commanded && own.unreachable.is_none());
    assert_eq!(p[own.max_segment + 1].line, 433);
    let i = own.max_segment;
    let (a0, a1) = (angles[i], angles[i + 1]);
    let n = caz(a0[0], a0[1]).cross(&caz(a1[0], a1[1])).normalize();
    let sampled = (0..=20_000)
        .map(|s| {
            let u = f64::from(s) / 20_000.0;
            (caz(a0[0] + u * (a1[0] - a0[0]), a0[1] + u * (a1[1] - a0[1])).dot(&n) * 100.0).abs()
        })
        .fold(0.0, f64::max);
    assert!(
        (own.max - sampled).abs() < 1e-6 * sampled,
        "{} vs {sampled}",
        own.max
    );
    assert!((1.0..2.0).contains(&own.max), "{}", own.max);
    // The rapids, apart: they swing far more and would have made the headline.
    assert_eq!(own.rapids.count, r.rapids);
    assert!(own.rapids.max > 10.0 * own.max, "{}", own.rapids.max);
    assert!(
        (own.rapids.m_swing.to_degrees() - 75.0).abs() < 1e-9,
        "{}",
        own.rapids.m_swing.to_degrees()
    );
}

/// FreeCAD/FreeCAD, `src/Mod/Path/PathTests/test_linuxcnc_metric_ref.ngc` (commit ee0ec2b),
/// LGPL-2.1: FreeCAD's LinuxCNC post output, a profile with G2 corners.
#[test]
fn a_freecad_profile_with_g2_corners() {
    let (p, r) = read_all(
        &file("freecad_linuxcnc_metric_ref.ngc"),
        Format::Nc,
        Some(&trunnion()),
    );
    assert_eq!(r.unit_reason, "millimetres: G21 on line 3");
    assert_eq!(at_line(&p, 25)[0].tip, Vector3::new(0.0, -2.5, -1.0));
    // Line 26, G2 Y0.000 I0.000 J2.500 from (0, −2.5): centre (0, 0), r = 2.5, a
    // quarter clockwise through the third quadrant; π/2 / (2·acos(1 − 0.001/2.5)) = 27.8 → 28.
    let arc = at_line(&p, 26);
    assert_eq!(arc.len(), chords(2.5, FRAC_PI_2, 0.001));
    assert_eq!(arc.len(), 28);
    for q in &arc {
        assert!((q.tip.xy().norm() - 2.5).abs() < 1e-9 && q.tip.x <= 1e-9 && q.tip.y <= 1e-9);
    }
}

/// LinuxCNC/linuxcnc, `tests/trajectory-planner/circular-arcs/nc_files/performance/
/// test_12mmflat.ngc` (commit 518bcde), GPL-2.0: CAM parallel finishing, G18 arcs by radius.
#[test]
fn g18_arcs_by_radius_from_a_cam_finishing_pass() {
    let (p, _) = read_all(
        &file("linuxcnc_tp_test_12mmflat.ngc"),
        Format::Nc,
        Some(&trunnion()),
    );
    // Line 11, G2 X104.66452 Z3.80337 R1598.76735 from (55.10202, 19.86847, 0.49686), in G18:
    // clockwise seen from +Y (Z to the right, X up), travelling up the view the centre lies to
    // the right, at +Z: c = m + h·(dz, 0, −dx)/|d| with h = √(R² − |d|²/4).
    let (s, e, r): (Vector3<f64>, Vector3<f64>, f64) = (
        Vector3::new(55.10202, 19.86847, 0.49686),
        Vector3::new(104.66452, 19.86847, 3.80337),
        1598.76735,
    );
    let d = e - s;
    let h = (r * r - d.norm_squared() / 4.0).sqrt();
    let side = Vector3::new(d.z, 0.0, -d.x) / d.norm();
    let (centre, other) = ((s + e) / 2.0 - side * h, (s + e) / 2.0 + side * h);
    assert!(centre.z > 1000.0);
    let arc = at_line(&p, 11);
    assert!(arc.len() > 10);
    for q in &arc {
        assert!(((q.tip - centre).norm() - r).abs() < 1e-6, "{:?}", q.tip);
        assert_eq!(q.tip.y, 19.86847);
    }
    // The other centre's arc bulges the other way by about 2·|d|²/(8R) = 0.39 mm.
    let mid = arc[arc.len() / 2].tip;
    assert!(((mid - other).norm() - r).abs() > 0.3);
}

/// aamorim1913/AptPostProcessor, `parts-2025/Telemecanique-Tilt-Support2.apt` (commit 909c1cb),
/// GPL-3.0: SolidWorks CAM APT with 6-number `CIRCLE/`s.
#[test]
fn solidworks_cam_apt_with_short_circles() {
    let (p, r) = read_all(&file("swcam_tilt_support2.apt"), Format::Apt, None);
    assert_eq!(r.unit_reason, "millimetres: UNIT/MM on line 2");
    // Line 15, RAPID/ then GOTO/-4.360504,-10.464015,25.
    assert_eq!(
        (at_line(&p, 15)[0].tip, at_line(&p, 15)[0].motion),
        (Vector3::new(-4.360504, -10.464015, 25.0), Motion::Rapid)
    );
    // Line 229 CIRCLE/17.4,-0.6,-3.,0,0,1. from (17.824264, −1.024264) to line 230's
    // (18, −0.6): 0.6 from the centre at both ends, 45° counter-clockwise about +Z; the step
    // 2·acos(1 − 0.001/0.6) = 0.1155 rad, π/4 / 0.1155 = 6.8 → 7 chords.
    let arc = at_line(&p, 230);
    assert_eq!(arc.len(), chords(0.6, PI / 4.0, 0.001));
    assert_eq!(arc.len(), 7);
    for q in &arc {
        let d = q.tip - Vector3::new(17.4, -0.6, -3.0);
        // (The file's 6 decimals put the start 0.5999995 from the centre.)
        assert!(
            (d.norm() - 0.6).abs() < 1e-6 && d.x > 0.0 && d.y <= 1e-9,
            "{d:?}"
        );
    }
    assert_eq!(note(&r, "CUTCOM/LEFT").line, 226);
}

/// aamorim1913/AptPostProcessor, `parts-2023/Teflon-gasket.apt` (commit 093eabd), GPL-3.0:
/// full circles written `CIRCLE/…,0,0,-1.` with the end at the start.
#[test]
fn solidworks_cam_full_circles_turn_clockwise_about_minus_z() {
    let (p, _) = read_all(&file("swcam_teflon_gasket.apt"), Format::Apt, None);
    // Lines 59–60: CIRCLE/15.,15.,-5.,0,0,-1. and GOTO/15.,-3.,-5. from (15, −3): a whole turn,
    // r = 18: 2π / (2·acos(1 − 0.001/18)) = 298.04 → 299 chords, counter-clockwise about −Z,
    // so from the bottom towards −X first.
    let arc = at_line(&p, 60);
    assert_eq!(arc.len(), chords(18.0, 2.0 * PI, 0.001));
    assert_eq!(arc.len(), 299);
    assert!(arc
        .iter()
        .all(|q| ((q.tip - Vector3::new(15.0, 15.0, -5.0)).norm() - 18.0).abs() < 1e-9));
    assert!(arc[0].tip.x < 15.0);
}

/// aamorim1913/AptPostProcessor, `parts-2025/Paralelipipedo-furos.apt` (commit 058b1ac),
/// GPL-3.0: SolidWorks CAM drilling cycles.
#[test]
fn solidworks_cam_drilling_cycles_are_rapid_positions() {
    let (p, r) = read_all(&file("swcam_paralelipipedo_furos.apt"), Format::Apt, None);
    assert!(p.iter().all(|q| q.motion == Motion::Rapid));
    assert_eq!(p[0].tip, Vector3::new(8.0, 15.0, 25.0));
    assert_eq!(at_line(&p, 24)[0].tip, Vector3::new(113.0, 15.0, 0.0));
    assert_eq!(note(&r, "CYCLE/").line, 16);
    // CSYS/1.,0,0,0,0,1.,0,0,0,0,1.,0 on line 13: the identity, said as such.
    assert_eq!(note(&r, "states the identity frame").line, 13);
    // Every statement is one the reader knows: 49 lines, 49 statements, the four
    // `CSI_SET_…` among SolidWorks' settings.
    // Found by cargo-mutants: the count of statements (`+=` as `-=`, `*=`) and the first word's
    // letters (`_` ending it) survived.
    assert_eq!(r.blocks, 49);
    assert_eq!(skipped(&r, "SolidWorks CAM settings (CSI_…)"), 4);
    assert_eq!(skipped(&r, "does not know"), 0);
    assert!(
        r.notes
            .iter()
            .all(|n| n.kind != NoteKind::Partial || n.text.contains("CYCLE/")),
        "{:?}",
        r.notes
    );
}

/// szborok/BRK_CNC_CORE, `test-data/…/DMU 85 monoblock MINUS/W5246NS01007B9.h` (commit
/// 1ca4c32), MIT (the repository's README): hyperMILL 2025 output for a DMU 85 monoBLOCK.
#[test]
fn a_hypermill_heidenhain_program_with_plane_spatial_and_labels_after_m30() {
    let (p, r) = read_all(
        &file("heid_hypermill_dmu85_B9.h"),
        Format::Heidenhain,
        Some(&trunnion()),
    );
    // Block 28 calls LBL 1, written after M30 (block 82): a datum shift of 0 and PLANE RESET.
    // Blocks 30–32 and 44–46 move in machine coordinates (M91): no point until X, Y and Z are
    // all given again, X and Y by block 57, Z by block 59 (Z50): file line 61, (165, −60, 50).
    assert_eq!(p[0].line, 61);
    assert_eq!(p[0].tip, Vector3::new(165.0, -60.0, 50.0));
    // Blocks 61–66 (lines 68–73): L … F MAX M99, the tapping cycle at six positions.
    let tips: Vec<_> = p[1..].iter().map(|q| (q.tip.x, q.tip.y)).collect();
    assert_eq!(
        tips,
        [
            (165.0, -60.0),
            (165.0, 60.0),
            (0.0, 40.0),
            (0.0, -40.0),
            (-165.0, -60.0),
            (-165.0, 60.0)
        ]
    );
    assert!(p
        .iter()
        .all(|q| q.motion == Motion::Rapid && q.tip.z == 50.0));
    // PLANE SPATIAL SPA0 SPB0 SPC0 … STAY: Q120 and Q122 are A = 0°, C = 0°.
    assert_eq!(p[0].angles, Some([0.0, 0.0]));
    assert_eq!(note(&r, "cycle 207 RIGID TAPPING NEW").count, 6);
    assert_eq!(note(&r, "M91/M92").line, 32);
    // Cycle parameters continue their CYCL DEF block with `~` after their comment (`Q240=0
    // ;TUNING MODE~`): only block 42, `FN 0:Q3=286`, is a Q assignment of its own before M30.
    assert_eq!(skipped(&r, "Q-parameter assignments"), 1);
}

/// 121philip/SINUMERIK-840D-sl-CAS-Package, `Approach A/CAM TEST.MPF` (commit 07c07dc, MIT):
/// an NX post's output for a Sinumerik 840D, 3-axis pocketing. Its first line defines five
/// variables without values (`DEF REAL _X_HOME, _Y_HOME, …`), which the reader once refused at
/// the first comma; its homes are moves in machine coordinates (`SUPA`), and its arcs are helical
/// ramps given by I and J.
#[test]
fn an_nx_sinumerik_program_with_def_variables_and_supa_homes() {
    let text = file("nx_sinumerik_840d_cam_test.mpf");
    assert_eq!(Format::detect(&text), Format::Siemens);
    let m = trunnion();
    let (p, r) = read_all(&text, Format::Siemens, Some(&m));
    assert_eq!(r.unit_reason, "millimetres: G710 on line 6");
    assert_eq!(r.dialect, "Siemens Sinumerik 840D");
    // The five SUPA blocks (lines 8, 9, 13, 14, 993) break the path and give no point.
    let supa = note(&r, "machine coordinates (SUPA");
    assert_eq!((supa.line, supa.count), (8, 5));
    assert!(p.iter().all(|q| q.line > 14 && q.line != 993));
    // The first point is line 18's rapid, the last line 990's (`N9900 G0 Z60.`).
    let first = &p[0];
    assert_eq!((first.line, first.motion), (18, Motion::Rapid));
    assert_eq!(first.tip, Vector3::new(165.356, 114.944, 60.0));
    let last = &p[p.len() - 1];
    assert_eq!((last.line, last.motion), (990, Motion::Rapid));
    assert_eq!(last.tip, Vector3::new(174.94, 98.786, 60.0));
    // Every point has the tool along +Z.
    assert!(p.iter().all(|q| q.axis == Vector3::z()));
    // Line 20, `G3 X165.434 Y122.046 Z49. I1.46 J3.535` from (165.356, 114.944, 53): a helix
    // counter-clockwise about (166.816, 118.479), radius 3.8246 at the start and 3.8254 at the
    // end (the post rounds to 3 decimals), from the start's angle atan2(−3.535, −1.46) to the
    // end's atan2(3.567, −1.382), 223.6° counter-clockwise, Z falling 4 mm in proportion.
    let c = Vector3::new(166.816, 118.479, 0.0);
    let angle = |q: &Vector3<f64>| (q.y - c.y).atan2(q.x - c.x);
    let (a0, a1) = ((-3.535f64).atan2(-1.46), 3.567f64.atan2(-1.382));
    let sweep = (a1 - a0).rem_euclid(2.0 * PI);
    assert!((sweep.to_degrees() - 223.6).abs() < 0.05);
    let arc = at_line(&p, 20);
    assert!(arc.len() > 10 && arc.iter().all(|q| q.motion == Motion::Arc));
    assert_eq!(arc[arc.len() - 1].tip, Vector3::new(165.434, 122.046, 49.0));
    for q in &arc {
        let turned = (angle(&q.tip) - a0).rem_euclid(2.0 * PI);
        assert!(
            turned > 0.0 && turned <= sweep + 1e-9,
            "line 20 at {:?}",
            q.tip
        );
        let radius = (q.tip - c).xy().norm();
        assert!((radius - 3.825).abs() < 1e-3, "radius {radius}");
        close(q.tip.z, 53.0 - 4.0 * turned / sweep, 1e-3, "z of the ramp");
    }
}

/// userFour/MECH491-postprocessor (commit 22c4fbb, CC0-1.0): one NX toolpath twice, as CL data
/// (`APT_Variable_Axis.txt`: `MSYS/3,3,0,…`, tool axes in the GOTOs, inches from `FEDRAT/IPM`)
/// and as NX's Haas UMC-750 post wrote it (`PostProcessed_Variable_Axis.txt`: `G20`, `G0
/// B-22.201 C1.05` before `G234` switches tool-centre-point control on, then X Y Z B C). The
/// UMC-750 is a B trunnion carrying a C table: table-table `CBZ`. The two readings agree point
/// by point: the NC tips are the CL tips in the MSYS frame, whose origin is 3 in = 76.2 mm along
/// X and Y, and the tool axes the machine gives from B and C (written to 0.001°) are NX's
/// (written to 10⁻⁷). The turn before `G234` reaches no point (X Y Z are not known after `G28`),
/// so no note says the path is the machine's.
#[test]
fn an_nx_clsf_and_its_haas_umc_750_program_give_the_same_path() {
    let umc = Machine::from_value(
        &serde_json::json!({ "kind": "table-table", "type": "CBZ" }),
        "machine",
    )
    .unwrap();
    let (cl, rc) = read_all(&file("nx_clsf_variable_axis.txt"), Format::Apt, None);
    let (nc, rn) = read_all(
        &file("haas_umc750_nx_variable_axis.nc"),
        Format::Nc,
        Some(&umc),
    );
    assert_eq!((rc.unit, rn.unit), (LengthUnit::Inch, LengthUnit::Inch));
    // The dialect as the page names it beside the file.
    assert_eq!(rc.dialect, "APT CL data");
    assert_eq!(rn.dialect, "ISO G-code (Fanuc, Haas)");
    assert!(rc
        .unit_reason
        .starts_with("inches: FEDRAT/IPM (a feed in inches) on line 15"));
    assert_eq!(rn.unit_reason, "inches: G20 on line 14");
    // MSYS/ comes before the feed that says inches: its origin is described in millimetres
    // once the unit is decided.
    assert!(note(&rc, "MSYS/")
        .text
        .contains("origin (76.2, 76.2, 0) mm"));
    assert_eq!(rc.frame_choice.unwrap().frame, "origin (76.2, 76.2, 0) mm");
    assert_eq!(rn.tcp.as_deref(), Some("G234 (Haas TCPC) on line 32"));
    assert!(
        rn.notes.iter().all(|n| n.kind != NoteKind::Tcp),
        "{:#?}",
        rn.notes
    );
    // The 348 GOTOs; the program's name `Omnf01_vx_0` (line 2) is not a word.
    assert_eq!(cl.len(), 348);
    assert_eq!(nc.len(), cl.len());
    let origin = Vector3::new(76.2, 76.2, 0.0);
    for (a, b) in cl.iter().zip(&nc) {
        assert_eq!(a.motion, b.motion, "CL line {}, NC line {}", a.line, b.line);
        // Both are written to 0.0001 in, rounded apart: they may differ by that.
        close_vec(&a.tip, &(b.tip + origin), 0.0001 * 25.4 + 1e-9, "tip");
        close_vec(&a.axis, &b.axis, 2e-5, "tool axis");
    }
}

/// ElMoe/Production-Data-Set-for-Five-Axis-CNC-Milling-with-Multiple-Changeovers,
/// `NC_code/Coordinate_system_representation_Achskreuz/…Achskreuz.mpf` (commit b800366, CC BY
/// 4.0): an NX post's program for the Sinumerik 840D sl of a Spinner U5-620, a B trunnion
/// carrying a C table (table-table `CBZ`), run on that machine for the data set. It machines
/// the faces of a cube 3+2: `G0 B90. C90.`, `TRAORI`, then `AROT` turns the frame so that its z
/// is the tool (`AROT X-90.`, `AROT Z90.`), and the face's moves are written in that frame.
///
/// The frame and the rotary axes are two statements of one tool direction, read by two
/// different parts of the reader (the frame's rotations, the machine's kinematics from B and C).
/// Each block that moves Z alone in its frame (`G1 Z-1.`, a plunge or a retract) moves the
/// tool tip along the tool axis, on every face.
#[test]
fn an_nx_sinumerik_program_for_a_b_c_table_machining_a_cube_3_plus_2() {
    let text = file("nx_sinumerik_spinner_u5_achskreuz.mpf");
    assert_eq!(Format::detect(&text), Format::Siemens);
    let spinner = Machine::from_value(
        &serde_json::json!({ "kind": "table-table", "type": "CBZ" }),
        "machine",
    )
    .unwrap();
    let (p, r) = read_all(&text, Format::Siemens, Some(&spinner));
    assert_eq!(r.unit_reason, "millimetres: G710 on line 7");
    assert_eq!(r.tcp.as_deref(), Some("TRAORI on line 1031"));
    // Line 1034, `G0 X31. Y-15.001 Z165.236` after `G0 B90. C0.0`, `TRAORI` and `AROT Y90.`:
    // AROT Y90 turns x onto −z and z onto x, so the tip is (165.236, −15.001, −31), and the
    // tool, tilted 90° by B, lies along +X.
    let q = at_line(&p, 1034)[0];
    close_vec(&q.tip, &Vector3::new(165.236, -15.001, -31.0), 1e-9, "tip");
    close_vec(&q.axis, &Vector3::x(), 1e-12, "axis");
    assert_eq!(q.angles, Some([0.0, 90.0]));
    // Every block of Z alone, on every face: the tip moves along the tool axis.
    let lines: Vec<&str> = text.lines().collect();
    let z_alone = |line: u32| {
        let words: Vec<&str> = lines[line as usize - 1]
            .split_whitespace()
            .skip(1)
            .collect();
        words.iter().any(|w| w.starts_with('Z'))
            && words
                .iter()
                .all(|w| w.starts_with(['Z', 'F']) || matches!(*w, "G0" | "G1"))
    };
    let mut axes: Vec<Vector3<f64>> = Vec::new();
    for w in p.windows(2) {
        if w[1].line != w[0].line && z_alone(w[1].line) {
            let d = w[1].tip - w[0].tip;
            assert!(
                d.norm() > 0.0 && d.cross(&w[1].axis).norm() < 1e-9 * d.norm().max(1.0),
                "line {}: the tip moves by {:?}, the tool axis is {:?}",
                w[1].line,
                d.as_slice(),
                w[1].axis.as_slice()
            );
            if axes.iter().all(|a| (a - w[1].axis).norm() > 1e-6) {
                axes.push(w[1].axis);
            }
        }
    }
    // The top, the four sides and a 45° face (`B90. C-135.`, `AROT X90. Y-45. Z-90.`): six tool
    // directions.
    assert!(axes.len() >= 6, "{axes:?}");
}

/// Programs the reader cannot read right are refused at their line, with the construct:
/// LinuxCNC/linuxcnc `configs/sim/axis/vismach/5axis/table-rotary-tilting/examples/
/// test-xyzac.ngc` (commit 1db7923, GPL-2.0), an o-word subroutine; aamorim1913/AptPostProcessor
/// `machine-code/CUT.h` (commit 1070a82, GPL-3.0), coordinates computed by FN functions; and that
/// repository's `tests/parts-2023/Teflon-gasket/11.h` (commit 4d71368, GPL-3.0), whose post
/// writes `CYCLE DEF` where a TNC reads `CYCL DEF`.
#[test]
fn programs_that_cannot_be_read_right_are_refused_at_their_line() {
    let m = trunnion();
    for (name, format, start, part) in [
        (
            "linuxcnc_test-xyzac.ngc",
            Format::Nc,
            "line 1, column 1: ",
            "o-words (LinuxCNC",
        ),
        (
            "heid_handwritten_cut.h",
            Format::Heidenhain,
            "line 35, column 1: ",
            "computed on line 31",
        ),
        (
            "swcam_heid_teflon_gasket_11.h",
            Format::Heidenhain,
            "line 17, column 4: ",
            "\"CYCLE\" is not a Heidenhain statement",
        ),
    ] {
        let e = read(&file(name), format, Some(&m), ReadOptions::default()).unwrap_err();
        assert!(
            e.message.starts_with(start) && e.message.contains(part),
            "{name}: {}",
            e.message
        );
    }
    // Each is recognised as its dialect from its first lines.
    assert_eq!(
        Format::detect(&file("heid_hypermill_dmu85_B9.h")),
        Format::Heidenhain
    );
    assert_eq!(Format::detect(&file("linuxcnc_boat-xyzac.ngc")), Format::Nc);
    assert_eq!(
        Format::detect(&file("swcam_tilt_support2.apt")),
        Format::Apt
    );
    let _ = RotaryType::ALL;
}
