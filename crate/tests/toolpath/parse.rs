//! The toolpath parser and writers (`fiveaxis::toolpath::parse`): each format against values
//! written by hand, NC tool axes against closed forms of `V = R_K(θk)·R_M(θm)·e_H`, every kind
//! of bad line with its line and column, chunked and streamed feeding, write → parse round
//! trips and format detection.

#![allow(clippy::unwrap_used, clippy::expect_used)]
use crate::common;

use common::toolpath::{at, caz_head, error};
use common::{close, Rng};
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{parse, Format, Motion, Parser, Point, ReadOptions, MAX_LINE};
use fiveaxis::toolpath::write::write;
use nalgebra::Vector3;
use serde_json::json;

fn machine(v: serde_json::Value) -> Machine {
    Machine::from_value(&v, "machine").unwrap()
}

fn close_vec(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64, what: &str) {
    assert!(
        (a - b).norm() <= tol,
        "{what}: {a:?} vs {b:?} (diff {:e})",
        (a - b).norm()
    );
}

fn unit(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z).normalize()
}

// ---------------------------------------------------------------------------------------------
// Each format against hand-written values

#[test]
fn csv_reads_every_separator_number_form_comment_and_header() {
    let text = "\u{feff}# exported toolpath\r\n\
                \r\n\
                X, Y, Z, I, J, K\r\n\
                1,2,3,0,0,1\r\n\
                -1.5;.5;1e-3;0;0;2\n\
                +2\t0\t-0.25\t3\t0\t4\n\
                10 20   30 0 -1 0   \n\
                # a comment between points\n\
                \x20 1. , 2 ,3.0e+1, 1, 1, 0 ,\n\
                7,8,9,0,0,1";
    let p = parse(text, Format::Csv, None).unwrap();
    let expected = [
        (4, Vector3::new(1.0, 2.0, 3.0), unit(0.0, 0.0, 1.0)),
        (5, Vector3::new(-1.5, 0.5, 0.001), unit(0.0, 0.0, 1.0)),
        (
            6,
            Vector3::new(2.0, 0.0, -0.25),
            Vector3::new(0.6, 0.0, 0.8),
        ),
        (
            7,
            Vector3::new(10.0, 20.0, 30.0),
            Vector3::new(0.0, -1.0, 0.0),
        ),
        (9, Vector3::new(1.0, 2.0, 30.0), unit(1.0, 1.0, 0.0)),
        (10, Vector3::new(7.0, 8.0, 9.0), Vector3::new(0.0, 0.0, 1.0)),
    ];
    assert_eq!(p.len(), expected.len());
    for (q, (line, tip, axis)) in p.iter().zip(expected) {
        assert_eq!(q.line, line);
        assert_eq!(q.tip, tip, "line {line}");
        close_vec(&q.axis, &axis, 1e-15, "axis");
        close(q.axis.norm(), 1.0, 1e-15, "unit axis");
        assert_eq!(q.angles, None);
    }
}

/// A decimal comma, as European CAM and measuring software writes it: with `;` or tabs as the
/// separator a comma inside a number is its decimal point; with commas as separators a comma
/// only separates (the values are written by hand).
#[test]
fn csv_reads_a_decimal_comma_with_semicolons_or_tabs() {
    let text = "x;y;z;i;j;k\n\
                1,5;-2,25;0,125;0;0;1\n\
                1,5\t2\t3\t0\t0,6\t0,8\n\
                1,5,2,3,0,0,1";
    let p = parse(text, Format::Csv, None);
    // The comma line has seven fields: refused, naming the count.
    let e = p.unwrap_err();
    assert!(e.message.contains("got 7"), "{}", e.message);
    let p = parse(&text[..text.rfind('\n').unwrap()], Format::Csv, None).unwrap();
    assert_eq!(p.len(), 2);
    assert_eq!(p[0].tip, Vector3::new(1.5, -2.25, 0.125));
    assert_eq!(p[1].tip, Vector3::new(1.5, 2.0, 3.0));
    close_vec(&p[1].axis, &Vector3::new(0.0, 0.6, 0.8), 1e-15, "axis");
    // Two commas in one field are no number, nor is a thousands point with a decimal comma
    // (`1.000,5`, 1000.5 in German): refused rather than read as 1.0005 or 1.
    for field in ["1,5,0", "1.000,5"] {
        let e = parse(&format!("{field};2;3;0;0;1"), Format::Csv, None).unwrap_err();
        assert!(
            e.message.contains("expected a number for x"),
            "{}",
            e.message
        );
    }
}

#[test]
fn csv_header_only_on_the_first_line_and_numbers_without_header() {
    let p = parse("0 0 0 1 0 0\n", Format::Csv, None).unwrap();
    assert_eq!(p[0].axis, Vector3::x());
    // A later non-numeric line is an error, not a header.
    let m = error("1,2,3,0,0,1\nx,y,z,i,j,k\n", Format::Csv, None);
    at(&m, 2, 1, "expected a number for x, got \"x\"");
}

#[test]
fn apt_reads_goto_tlaxis_continuations_comments_and_stops_at_fini() {
    let text = "$$ CL data\n\
                PARTNO TEST PART\n\
                MACHIN/UNCX01,1\n\
                CUTTER/6.000000\n\
                LOADTL/1\n\
                SPINDL/5000,CLW\n\
                COOLNT/ON\n\
                RAPID\n\
                GOTO/1,2,3\n\
                MULTAX/ON\n\
                FEDRAT/1000.000000,MMPM\n\
                GOTO/10.5,-20,30.25,0.6,0,0.8\n\
                goto / 11 , -21 , 31 $$ three numbers: the last axis\n\
                TLAXIS/0,3,4\n\
                GOTO/12,-22,32\n\
                GOTO/1.0,2.0,3.0,$\n\
                \x20   0.0,-1.0,0.0 $$ continued\n\
                GOTO/$\n\
                4,$\n\
                5,6\n\
                MULTAX/OFF\n\
                FINI\n\
                this is not read: GOTO/1.2.3\n";
    let p = parse(text, Format::Apt, None).unwrap();
    let expected = [
        (9, Vector3::new(1.0, 2.0, 3.0), Vector3::new(0.0, 0.0, 1.0)),
        (
            12,
            Vector3::new(10.5, -20.0, 30.25),
            Vector3::new(0.6, 0.0, 0.8),
        ),
        (
            13,
            Vector3::new(11.0, -21.0, 31.0),
            Vector3::new(0.6, 0.0, 0.8),
        ),
        (
            15,
            Vector3::new(12.0, -22.0, 32.0),
            Vector3::new(0.0, 0.6, 0.8),
        ),
        (
            16,
            Vector3::new(1.0, 2.0, 3.0),
            Vector3::new(0.0, -1.0, 0.0),
        ),
        (
            18,
            Vector3::new(4.0, 5.0, 6.0),
            Vector3::new(0.0, -1.0, 0.0),
        ),
    ];
    assert_eq!(p.len(), expected.len());
    for (q, (line, tip, axis)) in p.iter().zip(expected) {
        assert_eq!(q.line, line);
        assert_eq!(q.tip, tip, "line {line}");
        close_vec(&q.axis, &axis, 1e-15, "axis");
        assert_eq!(q.angles, None);
    }
}

/// CAZ: `V = R_Z(c)·R_X(a)·e_Z`. `R_X(a)·e_Z = (0, −sin a, cos a)`, and `R_Z(c)` turns that
/// into `(sin a sin c, −sin a cos c, cos a)`.
fn caz(c_deg: f64, a_deg: f64) -> Vector3<f64> {
    let (c, a) = (c_deg.to_radians(), a_deg.to_radians());
    Vector3::new(a.sin() * c.sin(), -a.sin() * c.cos(), a.cos())
}

/// CBZ: `V = R_Z(c)·R_Y(b)·e_Z`. `R_Y(b)·e_Z = (sin b, 0, cos b)`, and `R_Z(c)` turns that into
/// `(sin b cos c, sin b sin c, cos b)`.
fn cbz(c_deg: f64, b_deg: f64) -> Vector3<f64> {
    let (c, b) = (c_deg.to_radians(), b_deg.to_radians());
    Vector3::new(b.sin() * c.cos(), b.sin() * c.sin(), b.cos())
}

#[test]
fn nc_blocks_on_a_caz_fork_head_give_the_closed_form_tool_axis() {
    let m = caz_head();
    let text = "%\n\
                O1000 (CAZ fork head, Fräser Ø6)\n\
                N10 G90 G21 G17\n\
                N20 T1 M6\n\
                N30 G43.4 H1 (tool-centre-point control on)\n\
                N40 G43.4 H1\n\
                N50 G0 X10 Y-20.5 Z30 C0 A0\n\
                N60 G1 A30 F1000\n\
                n70 c90\n\
                N80 X.5 Y+2 Z1. C-45 A-60.25\n\
                N90 G91 X1 C10\n\
                N100 G90\n\
                N110 G20 X1\n\
                N120 G21 G28 Z0\n\
                N130 Z5\n\
                /N140 X = 7 ; block delete, '=' and a space\n\
                N150G1X8Y9Z10C370A-1\n\
                N160 M30\n\
                %\n";
    let p = parse(text, Format::Nc, Some(&m)).unwrap();
    let expected = [
        (7, [10.0, -20.5, 30.0], [0.0, 0.0]),
        (8, [10.0, -20.5, 30.0], [0.0, 30.0]),
        (9, [10.0, -20.5, 30.0], [90.0, 30.0]),
        (10, [0.5, 2.0, 1.0], [-45.0, -60.25]),
        (11, [1.5, 2.0, 1.0], [-35.0, -60.25]),
        (13, [25.4, 2.0, 1.0], [-35.0, -60.25]),
        (15, [25.4, 2.0, 5.0], [-35.0, -60.25]),
        (16, [7.0, 2.0, 5.0], [-35.0, -60.25]),
        (17, [8.0, 9.0, 10.0], [370.0, -1.0]),
    ];
    assert_eq!(p.len(), expected.len(), "{p:?}");
    for (q, (line, tip, angles)) in p.iter().zip(expected) {
        assert_eq!(q.line, line);
        // After G20 the axes not in the block stay where they are: 2 mm is 2/25.4 in, read
        // back as 2 mm to rounding.
        close_vec(&q.tip, &Vector3::from(tip), 1e-12, "tip");
        assert_eq!(q.angles, Some(angles), "line {line}");
        close_vec(&q.axis, &caz(angles[0], angles[1]), 1e-15, "CAZ axis");
    }
    // Spot values: C90 A30 tilts the tool towards +X: (sin 30°, 0, cos 30°).
    close_vec(
        &p[2].axis,
        &Vector3::new(0.5, 0.0, 3f64.sqrt() / 2.0),
        1e-15,
        "C90 A30",
    );
}

#[test]
fn nc_reversed_axes_turn_the_study_angle_round() {
    // Table-table CAZ with A reversed: θa = −A.
    let m =
        machine(json!({ "kind": "table-table", "type": "CAZ", "rotary": { "mReversed": true } }));
    let p = parse("X1 Y2 Z3 C40 A25\n", Format::Nc, Some(&m)).unwrap();
    close_vec(&p[0].axis, &caz(40.0, -25.0), 1e-15, "A reversed");
    assert_eq!(p[0].angles, Some([40.0, 25.0]));
    // Head-table CBZ (C table, B head) with C reversed: θc = −C.
    let m =
        machine(json!({ "kind": "head-table", "type": "CBZ", "rotary": { "kReversed": true } }));
    let p = parse("G1 X0 Y0 Z0 B-35 C120\nB20\n", Format::Nc, Some(&m)).unwrap();
    close_vec(&p[0].axis, &cbz(-120.0, -35.0), 1e-15, "C reversed");
    close_vec(&p[1].axis, &cbz(-120.0, 20.0), 1e-15, "C reversed, modal");
    assert_eq!(p[1].angles, Some([120.0, 20.0]));
}

// ---------------------------------------------------------------------------------------------
// Bad lines: line and column of the offending token, what was expected

#[test]
fn a_token_that_is_not_a_number() {
    let m = caz_head();
    at(
        &error(
            "x,y,z,i,j,k\n1,2,3,0,0,1\n1, 1.2.3 ,3,0,0,1\n",
            Format::Csv,
            None,
        ),
        3,
        4,
        "expected a number for y, got \"1.2.3\"",
    );
    at(
        &error("1 2 nan 0 0 1\n", Format::Csv, None),
        1,
        5,
        "expected a number for z, got \"nan\"",
    );
    at(
        &error("0\t0\t0\t0\t0\t1\n5\tinf\t0\t0\t0\t1\n", Format::Csv, None),
        2,
        3,
        "got \"inf\"",
    );
    at(
        &error("1,,3,0,0,1\n", Format::Csv, None),
        1,
        3,
        "expected a number for y, got \"\"",
    );
    at(
        &error("GOTO/1.2.3,0,0\n", Format::Apt, None),
        1,
        6,
        "expected a number after GOTO/, got \"1.2.3\"",
    );
    at(
        &error("MULTAX\nGOTO/1,2,3,0,0,1x\n", Format::Apt, None),
        2,
        16,
        "expected a number after GOTO/, got \"1x\"",
    );
    at(
        &error("G1 X1,5 Y2\n", Format::Nc, Some(&m)),
        1,
        5,
        "expected a number after X, got \"1,5\"",
    );
    at(
        &error("G1 X0\nY1.2.3\n", Format::Nc, Some(&m)),
        2,
        2,
        "expected a number after Y, got \"1.2.3\"",
    );
    at(
        &error("G1 X1 # 5\n", Format::Nc, Some(&m)),
        1,
        7,
        "# marks a macro variable (#1, #<name>): the calculator reads plain numbers",
    );
    at(
        &error("1,2,3,0,0,1\n2,3,4,0,0,1\n", Format::Apt, None),
        1,
        1,
        "expected an APT statement such as GOTO/x,y,z,i,j,k, got \"1\"",
    );
    at(
        &error("GOTO 1,2,3\n", Format::Apt, None),
        1,
        6,
        "expected / after GOTO, got \"1,2,3\"",
    );
}

#[test]
fn the_wrong_count_of_numbers() {
    at(
        &error("1,2,3,4,5\n", Format::Csv, None),
        1,
        10,
        "expected 6 numbers x,y,z,i,j,k, got 5",
    );
    at(
        &error("1 2 3 0 0 1 7\n", Format::Csv, None),
        1,
        13,
        "expected 6 numbers x,y,z,i,j,k, got 7",
    );
    at(
        &error("GOTO/1,2\n", Format::Apt, None),
        1,
        9,
        "expected 3 numbers (x, y, z) or 6 (x, y, z, i, j, k) after GOTO/, got 2",
    );
    at(
        &error("GOTO/1,2,3,0\n", Format::Apt, None),
        1,
        12,
        "after GOTO/, got 4",
    );
    at(
        &error("GOTO/1,2,3,0,0,1,9\n", Format::Apt, None),
        1,
        18,
        "after GOTO/, got 7",
    );
    // Continued: the 4th number is on line 2, column 2.
    at(
        &error("GOTO/1,2,3,$\n 0,0\n", Format::Apt, None),
        2,
        2,
        "after GOTO/, got 5",
    );
    at(
        &error("TLAXIS/0,1\nGOTO/1,2,3\n", Format::Apt, None),
        1,
        11,
        "expected 3 numbers (i, j, k) after TLAXIS/, got 2",
    );
}

#[test]
fn a_zero_or_non_finite_tool_axis() {
    at(
        &error("1,2,3,0,0,0\n", Format::Csv, None),
        1,
        7,
        "expected a non-zero tool axis (i, j, k), got (0, 0, 0)",
    );
    at(
        &error("1,2,3,1e400,0,0\n", Format::Csv, None),
        1,
        7,
        "expected a finite number for i, got \"1e400\"",
    );
    at(
        &error("GOTO/1,2,3,0.0,0,-0\n", Format::Apt, None),
        1,
        12,
        "non-zero tool axis",
    );
    at(
        &error("GOTO/1,2,3\nTLAXIS/0,0,0\n", Format::Apt, None),
        2,
        8,
        "non-zero tool axis",
    );
    // Tiny and huge (finite) components are fine: only the direction counts.
    let p = parse(
        "0,0,0,1e-300,0,1e-300\n0,0,0,1e300,1e300,0\n",
        Format::Csv,
        None,
    )
    .unwrap();
    close_vec(&p[0].axis, &unit(1.0, 0.0, 1.0), 1e-15, "tiny");
    close_vec(&p[1].axis, &unit(1.0, 1.0, 0.0), 1e-15, "huge");
}

#[test]
fn a_number_out_of_range() {
    let m = caz_head();
    at(
        &error("100000.5,0,0,0,0,1\n", Format::Csv, None),
        1,
        1,
        "expected x within ±100000 mm, got \"100000.5\"",
    );
    at(
        &error("0,0,-1e6,0,0,1\n", Format::Csv, None),
        1,
        5,
        "expected z within ±100000 mm",
    );
    at(
        &error("GOTO/0,2e5,0\n", Format::Apt, None),
        1,
        8,
        "expected y within ±100000 mm",
    );
    // ±100000 mm itself is accepted.
    assert_eq!(
        parse("-100000,100000,0,0,0,1\n", Format::Csv, None).unwrap()[0].tip,
        Vector3::new(-1e5, 1e5, 0.0)
    );
    at(
        &error("X0 Y0 Z0 C400000 A0\n", Format::Nc, Some(&m)),
        1,
        11,
        "expected C within ±360000°, got \"400000\"",
    );
    at(
        &error("A-360000.1\n", Format::Nc, Some(&m)),
        1,
        2,
        "expected A within ±360000°",
    );
    at(
        &error("X1\nX100001\n", Format::Nc, Some(&m)),
        2,
        2,
        "expected X within ±100000 mm, got \"100001\"",
    );
    // Incremental and inch: the position reached counts, in mm.
    at(
        &error("G91 C300000\nC60100\n", Format::Nc, Some(&m)),
        2,
        2,
        "expected C within ±360000°, got 360100°",
    );
    at(
        &error("G20 X4000\n", Format::Nc, Some(&m)),
        1,
        6,
        "expected X within ±100000 mm, got 101600 mm",
    );
}

#[test]
fn an_nc_rotary_word_not_of_this_machine() {
    let m = caz_head();
    at(
        &error("G1 X1 B10\n", Format::Nc, Some(&m)),
        1,
        7,
        "expected a rotary axis of this machine (C or A), got B",
    );
    // Columns count characters, not bytes.
    at(
        &error("X0\n(Ø6) b10\n", Format::Nc, Some(&m)),
        2,
        6,
        "got B",
    );
}

#[test]
fn a_word_letter_with_no_number() {
    let m = caz_head();
    at(
        &error("G1 X Y10\n", Format::Nc, Some(&m)),
        1,
        4,
        "expected a number after X, got \"Y10\"",
    );
    at(
        &error("X1\nN10 z\n", Format::Nc, Some(&m)),
        2,
        5,
        "expected a number after Z, got the end of the line",
    );
    at(
        &error("X1 F\n", Format::Nc, Some(&m)),
        1,
        4,
        "expected a number after F",
    );
}

#[test]
fn an_apt_continuation_at_the_end_of_the_file() {
    at(
        &error("GOTO/1,2,3,$\n", Format::Apt, None),
        1,
        12,
        "the statement continues with $ but the file ends",
    );
    // After a comment, with spaces, and without a last line end.
    at(
        &error(
            "GOTO/1,2,3,0,0,1\nGOTO/4,5,$ $$ continued",
            Format::Apt,
            None,
        ),
        2,
        10,
        "continues with $",
    );
}

#[test]
fn an_empty_file_is_an_error() {
    let m = caz_head();
    for (text, format) in [
        ("", Format::Csv),
        ("\n\n", Format::Csv),
        ("# only a comment\nx,y,z,i,j,k\n", Format::Csv),
        ("", Format::Apt),
        ("PARTNO EMPTY\nMULTAX/ON\nFINI\nGOTO/1,2,3\n", Format::Apt),
        ("", Format::Nc),
        ("%\nO1 (nothing)\nG90 G21\nM30\n%\n", Format::Nc),
    ] {
        // Each format says what a point would have been.
        let expected = match format {
            Format::Csv => "lines x,y,z,i,j,k",
            Format::Apt => "GOTO/x,y,z or GOTO/x,y,z,i,j,k statements",
            _ => "blocks that move the tool to a known position",
        };
        assert_eq!(
            error(text, format, Some(&m)),
            format!("the file has no points; expected {expected}"),
            "{text:?}"
        );
    }
}

#[test]
fn nc_needs_a_machine_and_formats_have_names() {
    let e = Parser::new(Format::Nc, None, ReadOptions::default()).unwrap_err();
    assert_eq!(e.field, "machine");
    for f in Format::ALL {
        assert_eq!(f.name().parse::<Format>().unwrap(), f);
        assert_eq!(f.name().to_uppercase().parse::<Format>().unwrap(), f);
        assert_eq!(f.to_string(), f.name());
    }
    let e = "gcode".parse::<Format>().unwrap_err();
    assert_eq!(e.field, "format");
    assert!(e
        .message
        .contains("expected csv, apt, nc, siemens or heidenhain"));
}

#[test]
fn a_line_too_long_to_carry_is_an_error() {
    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    let mut out = Vec::new();
    p.feed("1,2,3,0,0,1\n", &mut out).unwrap();
    let chunk = " ".repeat(MAX_LINE / 4);
    let mut result = Ok(());
    for _ in 0..5 {
        result = p.feed(&chunk, &mut out);
        if result.is_err() {
            break;
        }
    }
    let e = result.unwrap_err();
    let expected =
        format!("line 2, column 1: expected a line of at most {MAX_LINE} bytes, got a longer one");
    assert_eq!(e.message, expected);
    // The same line given whole is the same error.
    let text = format!("1,2,3,0,0,1\n{}\n", " ".repeat(MAX_LINE + 1));
    assert_eq!(error(&text, Format::Csv, None), expected);
}

// ---------------------------------------------------------------------------------------------
// Streaming

/// Feeds `text` in chunks of the sizes `sizes` gives (rounded up to a character boundary).
fn feed_in_chunks(
    text: &str,
    format: Format,
    machine: Option<&Machine>,
    mut size: impl FnMut() -> usize,
) -> (Vec<Point>, u32) {
    let mut parser = Parser::new(format, machine, ReadOptions::default()).unwrap();
    let mut out = Vec::new();
    let mut at = 0;
    while at < text.len() {
        let mut end = (at + size().max(1)).min(text.len());
        while !text.is_char_boundary(end) {
            end += 1;
        }
        parser.feed(&text[at..end], &mut out).unwrap();
        at = end;
    }
    parser.finish(&mut out).unwrap();
    (out, parser.lines())
}

#[test]
fn chunks_split_anywhere_give_the_same_points() {
    let m = caz_head();
    let texts = [
        (
            Format::Csv,
            "\u{feff}x;y;z;i;j;k\r\n1.25;-2;3e1;0;0;1\r\n\r\n# c\r4 5 6 1 0 0\r7,8,9,0,1,1\n10,11,12,0,0,-1",
            7,
        ),
        (
            Format::Apt,
            "PARTNO P\r\nMULTAX\r\nGOTO/1.5,2,3,$\r\n0,0.6,0.8 $$ c\r\nGOTO/4,5,6\rTLAXIS/1,0,0\nGOTO/$\n7,$\n8,9\r\nFINI\r\n",
            10,
        ),
        (
            Format::Nc,
            "%\r\nO12 (Fräser)\r\nG90 G21\r\nN1 G1 X12.5 Y-3 Z4 C10 A20\r\nN2 A-15.125 ; Ø\rN3 G91 X1 C5\nN4 G90 X0Y0Z0C0A0\r\nM30\r\n%",
            9,
        ),
    ];
    let mut rng = Rng::new(11);
    for (format, text, lines) in texts {
        let reference = parse(text, format, Some(&m)).unwrap();
        assert!(reference.len() >= 3, "{format}: {reference:?}");
        let (whole, n) = feed_in_chunks(text, format, Some(&m), || usize::MAX / 2);
        assert_eq!(whole, reference);
        assert_eq!(n, lines, "{format}: lines");
        let (bytes, n) = feed_in_chunks(text, format, Some(&m), || 1);
        assert_eq!(bytes, reference, "{format}: 1-byte chunks");
        assert_eq!(n, lines, "{format}: lines in 1-byte chunks");
        for _ in 0..200 {
            let max = 1 + (rng.next_u64() % 24) as usize;
            let (random, n) = feed_in_chunks(text, format, Some(&m), || {
                1 + (rng.next_u64() % max as u64) as usize
            });
            assert_eq!(random, reference, "{format}: random chunks");
            assert_eq!(n, lines);
        }
        // Empty chunks change nothing, also right after a '\r'.
        let mut parser = Parser::new(format, Some(&m), ReadOptions::default()).unwrap();
        let mut out = Vec::new();
        for c in text.split_inclusive('\r') {
            parser.feed(c, &mut out).unwrap();
            parser.feed("", &mut out).unwrap();
        }
        parser.finish(&mut out).unwrap();
        assert_eq!(out, reference, "{format}: empty chunks");
    }
}

#[test]
fn a_million_csv_lines_stream_in_64_kb_chunks() {
    const N: usize = 1_000_000;
    const CHUNK: usize = 64 * 1024;
    let tip = |i: usize| {
        Vector3::new(
            i as f64 * 0.001 - 500.0,
            (i % 1000) as f64 * -0.25,
            3.5 + (i % 7) as f64,
        )
    };
    let angle = |i: usize| ((i % 360) as f64).to_radians();
    let mut parser = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    let mut out = Vec::new();
    let mut seen = 0usize;
    let mut checked = 0usize;
    let mut check = |out: &mut Vec<Point>, seen: &mut usize| {
        for p in out.iter() {
            let i = *seen;
            if i % 99_991 == 0 || i == N - 1 {
                assert_eq!(p.tip, tip(i), "point {i}");
                let t = angle(i);
                close_vec(&p.axis, &Vector3::new(t.sin(), 0.0, t.cos()), 1e-15, "axis");
                assert_eq!(p.line as usize, i + 2, "line of point {i}");
                checked += 1;
            }
            *seen += 1;
        }
        out.clear();
    };
    let mut buf = String::with_capacity(2 * CHUNK);
    buf.push_str("x,y,z,i,j,k\n");
    let mut fed = 0usize;
    for i in 0..N {
        let (p, t) = (tip(i), angle(i));
        use std::fmt::Write;
        writeln!(
            buf,
            "{},{},{},{},0,{}",
            p.x,
            p.y,
            p.z,
            2.0 * t.sin(),
            2.0 * t.cos()
        )
        .unwrap();
        if buf.len() >= CHUNK {
            parser.feed(&buf[..CHUNK], &mut out).unwrap();
            fed += CHUNK;
            buf.drain(..CHUNK);
            check(&mut out, &mut seen);
        }
    }
    parser.feed(&buf, &mut out).unwrap();
    fed += buf.len();
    parser.finish(&mut out).unwrap();
    check(&mut out, &mut seen);
    assert_eq!(seen, N);
    assert_eq!(checked, 12);
    assert_eq!(parser.lines() as usize, N + 1);
    assert!(fed > 30 * CHUNK, "{fed} bytes fed");
}

// ---------------------------------------------------------------------------------------------
// Round trips

fn random_points(rng: &mut Rng, n: usize) -> Vec<Point> {
    (0..n)
        .map(|_| {
            let mut axis = Vector3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            axis.normalize_mut();
            Point {
                motion: Motion::Feed,
                tip: Vector3::new(
                    rng.range(-999.0, 999.0),
                    rng.range(-999.0, 999.0),
                    rng.range(-999.0, 999.0),
                ),
                axis,
                line: 0,
                angles: None,
            }
        })
        .collect()
}

#[test]
fn csv_and_apt_round_trip_within_the_written_precision() {
    let mut rng = Rng::new(5);
    let mut points = random_points(&mut rng, 500);
    // Every seventh point reached at rapid (the first one among them).
    for p in points.iter_mut().step_by(7) {
        p.motion = Motion::Rapid;
    }
    // Exact values, a negative zero and tiny components.
    points.push(Point {
        motion: Motion::Feed,
        tip: Vector3::new(-0.0, 1e-9, 12.5),
        axis: Vector3::new(-1e-12, 0.0, 1.0),
        line: 0,
        angles: None,
    });
    for format in [Format::Csv, Format::Apt] {
        let text = write(format, &points, None).unwrap();
        assert_eq!(Format::detect(&text), format);
        assert!(!text.contains("-0,"), "{format}: no negative zero");
        if format == Format::Apt {
            assert!(text.contains(",$\n"), "long GOTOs are continued");
            assert!(text.lines().all(|l| l.len() <= 72 || l.starts_with("$$")));
        }
        let back = parse(&text, format, None).unwrap();
        assert_eq!(back.len(), points.len());
        for (a, b) in points.iter().zip(&back) {
            // APT keeps the rapids (`RAPID` before each), CSV has feeds only.
            let motion = match format {
                Format::Apt => a.motion,
                _ => Motion::Feed,
            };
            assert_eq!(b.motion, motion, "{format}");
            close_vec(&a.tip, &b.tip, 5.1e-7 * 3f64.sqrt(), "tip");
            close_vec(&a.axis, &b.axis, 2e-9, "axis");
            assert_eq!(b.angles, None);
        }
        let last = back.last().unwrap();
        assert_eq!(last.tip, Vector3::new(0.0, 0.0, 12.5));
        assert_eq!(last.axis, Vector3::z());
    }
}

#[test]
fn nc_round_trips_within_the_written_precision() {
    let mut rng = Rng::new(9);
    for m in [
        caz_head(),
        machine(json!({ "kind": "head-table", "type": "CBZ", "rotary": { "kReversed": true } })),
        machine(json!({ "kind": "table-table", "type": "BAY" })),
    ] {
        let model = m.build().unwrap();
        let (rtype, kf, mf) = (
            model.layout.rtype,
            model.layout.k_factor,
            model.layout.m_factor,
        );
        let points: Vec<Point> = random_points(&mut rng, 300)
            .into_iter()
            .map(|mut p| {
                let (k, mm) = (rng.range(-400.0, 400.0), rng.range(-120.0, 120.0));
                p.angles = Some([k, mm]);
                p.axis = rtype.tool_vector(fiveaxis::rotary::Pose::new(
                    kf * k.to_radians(),
                    mf * mm.to_radians(),
                ));
                p
            })
            .collect();
        let letters = model.letters();
        let text = write(Format::Nc, &points, Some(letters)).unwrap();
        assert_eq!(Format::detect(&text), Format::Nc);
        let back = parse(&text, Format::Nc, Some(&m)).unwrap();
        assert_eq!(back.len(), points.len());
        for (a, b) in points.iter().zip(&back) {
            close_vec(&a.tip, &b.tip, 5.1e-5 * 3f64.sqrt(), "tip");
            let (x, y) = (a.angles.unwrap(), b.angles.unwrap());
            close(x[0], y[0], 5.1e-5, "K");
            close(x[1], y[1], 5.1e-5, "M");
            close_vec(&a.axis, &b.axis, 2.0 * 5.1e-5f64.to_radians(), "axis");
        }
        // Every number has a decimal point.
        let block = text.lines().find(|l| l.starts_with('X')).unwrap();
        assert!(block.split(' ').all(|w| w.contains('.')), "{block}");
    }
    // NC needs the letters and every point's angles.
    let p = random_points(&mut rng, 2);
    assert!(write(Format::Nc, &p, None).is_err());
    let e = write(Format::Nc, &p, Some(['C', 'A'])).unwrap_err();
    assert!(e.message.contains("point 1"), "{e}");
    // Nothing that is not finite is written.
    let mut bad = p.clone();
    bad[1].axis.y = f64::NAN;
    for format in Format::ALL {
        let e = write(format, &bad, Some(['C', 'A'])).unwrap_err();
        assert!(
            e.message.starts_with("point 2 (line 0) is not finite"),
            "{e}"
        );
    }
}

#[test]
fn written_nc_reads_exactly_as_written() {
    let p = Point {
        motion: Motion::Feed,
        tip: Vector3::new(10.0, -0.00004, 2.5),
        axis: caz(90.0, 30.0),
        line: 0,
        angles: Some([90.0, 30.0]),
    };
    let text = write(Format::Nc, &[p], Some(['C', 'A'])).unwrap();
    assert!(
        text.contains("\nG1 X10.0 Y0.0 Z2.5 C90.0 A30.0\n"),
        "{text}"
    );
}

// ---------------------------------------------------------------------------------------------
// Format detection

#[test]
fn the_format_is_detected_from_the_first_lines() {
    let cases = [
        ("1,2,3,0,0,1\n", Format::Csv),
        ("x,y,z,i,j,k\n1,2,3,0,0,1\n", Format::Csv),
        ("X Y Z I J K\n-1 2 3 0 0 1\n", Format::Csv),
        ("\u{feff}# comment\n\n.5;1;2;0;0;1", Format::Csv),
        ("", Format::Csv),
        ("GOTO/1,2,3\n", Format::Apt),
        ("  goto / 1,2,3\n", Format::Apt),
        ("$$ comment\n", Format::Apt),
        ("PARTNO my part\nGOTO/1,2,3", Format::Apt),
        ("MULTAX/ON\n", Format::Apt),
        ("CUTTER/6\n", Format::Apt),
        ("%\nO1000\n", Format::Nc),
        ("(comment)\nG90\n", Format::Nc),
        ("; Siemens\nTRAORI\n", Format::Siemens),
        ("TRAORI\nG1 X1\n", Format::Siemens),
        ("N10 G0 X0\nN20 R1=5\n", Format::Siemens),
        ("%_N_PART_MPF\n", Format::Siemens),
        ("0 BEGIN PGM PART MM\n", Format::Heidenhain),
        ("1 L X+10 Y-5 FMAX\n", Format::Heidenhain),
        ("%\n(on exit X=2.4)\no100 sub\n", Format::Nc),
        ("N10 G90 G21\n", Format::Nc),
        ("x12.5 y3\n", Format::Nc),
        ("G1X10Y20\n", Format::Nc),
        ("X=10\n", Format::Siemens),
        ("O1000\n", Format::Nc),
        // A comment right after a block number, with `=` in it (the first lines of a 5-axis
        // simulator's sample, Planet-Source-Code/cuq-a-5-axis-milling-machine-simulator
        // `test.nc`): ISO, where it was taken for a Siemens call `N1(…)` with `Offset=`.
        (
            "N1(File   : test.nc)\nN3(Offset=0.00 LACE CENTER)\nN4T006M06F800S1800\n",
            Format::Nc,
        ),
    ];
    for (text, format) in cases {
        assert_eq!(Format::detect(text), format, "{text:?}");
    }
}

/// A CSV file states no unit: read with "inches where the file does not say", its numbers are
/// inches (× 25.4 mm), and the report counts one block a point line, the comment, the header and
/// the blank line apart. (From the mutants of the CSV reader's scale and block count.)
#[test]
fn csv_in_inches_where_the_file_does_not_say() {
    let options = ReadOptions {
        unit: fiveaxis::toolpath::read::UnitChoice::Inch,
        ..Default::default()
    };
    let (p, r) = common::toolpath::read_with(
        "# measured\nx,y,z,i,j,k\n1,2,3,0,0,1\n\n0.5,0,-1,0,0,1\n",
        Format::Csv,
        None,
        options,
    );
    close_vec(&p[0].tip, &Vector3::new(25.4, 50.8, 76.2), 1e-12, "tip");
    close_vec(&p[1].tip, &Vector3::new(12.7, 0.0, -25.4), 1e-12, "tip");
    assert_eq!(r.unit, fiveaxis::toolpath::read::LengthUnit::Inch);
    assert_eq!(r.blocks, 2);
}
