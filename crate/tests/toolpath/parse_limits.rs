//! The toolpath reader's documented rules at their edges: detection, lines of exactly `MAX_LINE`
//! bytes, error columns, NC words, limits, APT lines of 72 and 73 characters.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{at, caz_head, error, read_all};
use fiveaxis::machine::Machine;
use fiveaxis::toolpath::read::{
    parse, Format, Motion, Parser, Point, ReadOptions, DETECT_LINES, MAX_COORDINATE, MAX_LINE,
    MAX_POINTS,
};
use fiveaxis::toolpath::write::write;
use nalgebra::Vector3;

/// The tips of the points of `text`.
fn tips(text: &str, format: Format, machine: Option<&Machine>) -> Vec<Vector3<f64>> {
    parse(text, format, machine)
        .unwrap()
        .iter()
        .map(|p| p.tip)
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Format detection: the first telling line decides

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// `PARTNO` and `PPRINT` followed by text are APT; another APT word followed by text (not `/`)
/// decides nothing; a line of numbers decides CSV even when a later line looks like NC.
#[test]
fn the_first_telling_line_decides_the_format() {
    let cases = [
        ("PARTNO my part\n", Format::Apt),
        ("PPRINT made by hand\n", Format::Apt),
        // Creo's REMARK before numbers: the REMARK decides.
        ("REMARK x\n1,2,3\n", Format::Apt),
        ("pprint lower case\n", Format::Apt),
        ("FEDRAT 100\nN10 G1 X1\n", Format::Nc),
        ("GOTO next\nN10 G1 X1\n", Format::Nc),
        ("1,2,3,0,0,1\nN10 G1 X1\n", Format::Csv),
        ("-1 2 3 0 0 1\nGOTO/1,2,3\n", Format::Csv),
        (".5;1;2;0;0;1\nG1 X1\n", Format::Csv),
    ];
    for (text, format) in cases {
        assert_eq!(Format::detect(text), format, "{text:?}");
    }
}

// Found by cargo-mutants: `apt::is_statement`'s rule for a major word before `/` (each `&&`
// as `||`, each character class) survived.
/// An APT major word before `/` starts with a letter, has two or more letters and holds only
/// letters, digits, spaces, `-` and `_`: NX's `TOOL PATH/…` and `END-OF-PATH/` are APT; an ISO
/// comment or block with a `/` in its text (a date, a fixture's name) is not, nor a line of
/// numbers with a `/`.
#[test]
fn an_apt_major_word_is_letters_before_a_slash() {
    let cases = [
        (
            "TOOL PATH/VARIABLE_CONTOUR,TOOL,BPR-SNR-323S32\n",
            Format::Apt,
        ),
        ("END-OF-PATH/\n", Format::Apt),
        ("(DATE 12/01/2026)\nG0 X1 Y2 Z3\n", Format::Nc),
        ("N10 G0 X1 Y2 Z3 (FIXTURE A/B)\n", Format::Nc),
        ("12/3,4,5,0,0,1\n", Format::Csv),
    ];
    for (text, format) in cases {
        assert_eq!(Format::detect(text), format, "{text:?}");
    }
}

// Found by cargo-mutants: `Format::detect`'s line limit (`>` as `>=` and `==`) and its `#` rule
// (`||` as `&&`, `!nc` as `nc`) survived.
/// `#` comment lines decide nothing, whatever words they hold (`FMAX`, `TOOL CALL` and `GOTO/`
/// are Heidenhain's and APT's), and lines after the first [`DETECT_LINES`] are not read: a
/// telling line at line 2000 decides, one at line 2001 does not (the file is then CSV).
#[test]
fn comments_and_lines_after_the_first_detect_lines_decide_nothing() {
    for text in [
        "# exported from the L X+0 FMAX block\n1,2,3,0,0,1\n",
        "# TOOL CALL 5 Z S3000\n1 2 3 0 0 1\n",
        "# GOTO/1,2,3\n1;2;3;0;0;1\n",
    ] {
        assert_eq!(Format::detect(text), Format::Csv, "{text:?}");
    }
    let at_line = |n: usize| format!("{}G1 X1\n", "\n".repeat(n - 1));
    assert_eq!(Format::detect(&at_line(DETECT_LINES)), Format::Nc);
    assert_eq!(Format::detect(&at_line(DETECT_LINES + 1)), Format::Csv);
    let comments = |n: usize| format!("{}N10 G1 X1\n", "# x\n".repeat(n - 1));
    assert_eq!(Format::detect(&comments(DETECT_LINES)), Format::Nc);
    assert_eq!(Format::detect(&comments(DETECT_LINES + 1)), Format::Csv);
    // Lines are counted as the readers count them: `\r\n` (Windows), `\r` and `\n` each end
    // one line, so a Windows file's line 2000 still decides.
    for end in ["\r\n", "\r", "\n"] {
        let at = |n: usize| format!("{}G1 X1{end}", end.repeat(n - 1));
        assert_eq!(Format::detect(&at(DETECT_LINES)), Format::Nc, "{end:?}");
        assert_eq!(
            Format::detect(&at(DETECT_LINES + 1)),
            Format::Csv,
            "{end:?}"
        );
    }
    // `\r\r\n` is two line ends (a `\r`, then a `\r\n`).
    let mixed = format!("{}G1 X1\n", "\r\r\n".repeat(DETECT_LINES / 2));
    assert_eq!(Format::detect(&mixed), Format::Csv);
    let mixed = format!("{}G1 X1\n", "\r\r\n".repeat(DETECT_LINES / 2 - 1));
    assert_eq!(Format::detect(&mixed), Format::Nc);
}

// ---------------------------------------------------------------------------------------------
// Line lengths: at most MAX_LINE bytes, whole or carried over chunks

/// A `#` comment line of exactly `len` bytes.
fn comment(len: usize) -> String {
    format!("#{}", "x".repeat(len - 1))
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// A line of exactly [`MAX_LINE`] bytes is read, whether it comes whole or in pieces; one more
/// byte is the too-long error, in pieces as soon as the carried part passes the limit.
#[test]
fn a_line_of_exactly_max_line_bytes_is_read() {
    let whole = format!("{}\n1,2,3,0,0,1\n", comment(MAX_LINE));
    assert_eq!(tips(&whole, Format::Csv, None).len(), 1);

    // Carried: the whole long line without its end, then the end and a point.
    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    let mut out = Vec::new();
    p.feed(&comment(MAX_LINE), &mut out).unwrap();
    p.feed("\n1,2,3,0,0,1\n", &mut out).unwrap();
    p.finish(&mut out).unwrap();
    assert_eq!(out.len(), 1);
    assert_eq!(out[0].line, 2);

    let too_long = "line 1, column 1: expected a line of at most";
    let m = error(
        &format!("{}\n1,2,3,0,0,1\n", comment(MAX_LINE + 1)),
        Format::Csv,
        None,
    );
    assert!(m.starts_with(too_long), "{m}");
    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    p.feed(&comment(MAX_LINE), &mut out).unwrap();
    let e = p.feed("x", &mut out).unwrap_err();
    assert!(e.message.starts_with(too_long), "{}", e.message);
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// A continued APT statement of exactly [`MAX_LINE`] bytes before its last line is read; one
/// byte more is refused at the line that passes the limit.
#[test]
fn a_continued_apt_statement_of_exactly_max_line_bytes_is_read() {
    // Two pieces ending with `$` (the `$` is not part of the statement) of MAX_LINE/2 bytes.
    let half = MAX_LINE / 2;
    let first = |len: usize| format!("GOTO/1,{}$", " ".repeat(len - "GOTO/1,".len()));
    let second = |len: usize| format!("2,3,{}$", " ".repeat(len - "2,3,".len()));
    let text = format!("{}\n{}\n0,0,1\n", first(half), second(half));
    let p = parse(&text, Format::Apt, None).unwrap();
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
    assert_eq!(p[0].line, 1);
    let text = format!("{}\n{}\n0,0,1\n", first(half), second(half + 1));
    at(
        &error(&text, Format::Apt, None),
        2,
        1,
        "the continued statement is longer than",
    );
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// "A file without points is an error" counts the points of this file, not what the caller's
/// vector already holds, and a caller that drains the vector loses nothing.
#[test]
fn the_points_of_the_file_are_counted_not_the_callers_vector() {
    let earlier = Point {
        motion: Motion::Feed,
        tip: Vector3::zeros(),
        axis: Vector3::z(),
        line: 0,
        angles: None,
    };
    let mut out = vec![earlier; 3];
    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    p.feed("# nothing but a comment\n", &mut out).unwrap();
    let e = p.finish(&mut out).unwrap_err();
    assert!(
        e.message.contains("the file has no points"),
        "{}",
        e.message
    );

    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    p.feed("1,2,3,0,0,1\n", &mut out).unwrap();
    assert_eq!(out.len(), 4);
    out.clear();
    p.finish(&mut out).unwrap();
}

// Found by cargo-mutants: the range check of points scaled at the end (`>` as `>=` or `==`)
// and the index of the first point the caller still holds (`-` as `+`) survived: no test read
// a point before the hint that makes the file inches.
/// Points read before the hint that decides the unit (`FEDRAT/IPM`) are scaled at the end, and
/// checked against ±[`MAX_COORDINATE`] mm again: 3937.0078740157483 in is 100 000 mm to the
/// last bit, within; 5000 in is 127 000 mm, beyond, refused at its line.
#[test]
fn points_scaled_by_a_later_unit_hint_are_checked_against_the_range() {
    let (p, _) = read_all(
        "GOTO/3937.0078740157483,0,0\nFEDRAT/IPM,10\n",
        Format::Apt,
        None,
    );
    assert_eq!(p[0].tip.x, MAX_COORDINATE);
    let e = parse(
        "GOTO/1,0,0\nGOTO/5000,0,0\nFEDRAT/IPM,10\n",
        Format::Apt,
        None,
    )
    .unwrap_err();
    assert_eq!(
        e.message,
        "line 2: expected coordinates within ±100000 mm, got 127000 mm once read in inches"
    );
}

// Found by cargo-mutants: the index of a scaled point in the caller's vector (`i - first` as
// `i + first`) survived: every test held all the points, so that `first` was 0.
/// A caller that hands on the points of each chunk (the page's worker) and keeps only the
/// latest still gets those it holds scaled at the end: the points it holds are the file's last
/// ones, indexed from the first it still holds.
#[test]
fn points_still_held_are_scaled_when_the_caller_drained_the_earlier_ones() {
    let mut p = Parser::new(Format::Apt, None, ReadOptions::default()).unwrap();
    let mut out = Vec::new();
    p.feed("GOTO/1,0,0\nGOTO/2,0,0\n", &mut out).unwrap();
    assert_eq!(out.len(), 2);
    out.clear();
    p.feed("GOTO/3,0,0\nGOTO/4,0,0\nFEDRAT/IPM,10\n", &mut out)
        .unwrap();
    let r = p.finish(&mut out).unwrap();
    assert_eq!(r.unit, fiveaxis::toolpath::read::LengthUnit::Inch);
    let x: Vec<f64> = out.iter().map(|q| q.tip.x).collect();
    assert_eq!(x, [3.0 * 25.4, 4.0 * 25.4]);
}

// Found by cargo-mutants: `Parser::count`'s limit (`>` as `>=` or `==`) survived.
/// A file may give [`MAX_POINTS`] points, not one more: the count is of every point read, so a
/// caller that drains its vector between chunks (as the page's worker does) meets it too.
#[test]
fn a_file_may_give_max_points_points_and_not_one_more() {
    let per_chunk = 10_000;
    let chunk = "0,0,0,0,0,1\n".repeat(per_chunk);
    let mut out = Vec::with_capacity(per_chunk);
    let mut p = Parser::new(Format::Csv, None, ReadOptions::default()).unwrap();
    for _ in 0..MAX_POINTS / per_chunk as u64 {
        p.feed(&chunk, &mut out).unwrap();
        out.clear();
    }
    assert_eq!(p.lines() as u64, MAX_POINTS);
    let e = p.feed("0,0,0,0,0,1\n", &mut out).unwrap_err();
    assert_eq!(
        e.message,
        format!(
            "line {}: the file gives more than {MAX_POINTS} points (with its arcs and repeats); \
             read a part of the program at a time",
            MAX_POINTS + 1
        )
    );
}

// ---------------------------------------------------------------------------------------------
// CSV fields

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// Each non-finite tool-axis component is reported at its own column.
#[test]
fn a_non_finite_axis_component_is_reported_at_its_column() {
    // 1,2,3,  the fourth field starts at column 7, the fifth at 9, the sixth at 11.
    at(
        &error("1,2,3,1e999,0,1\n", Format::Csv, None),
        1,
        7,
        "expected a finite number for i",
    );
    at(
        &error("1,2,3,0,1e999,1\n", Format::Csv, None),
        1,
        9,
        "expected a finite number for j",
    );
    at(
        &error("1,2,3,0,0,-1e999\n", Format::Csv, None),
        1,
        11,
        "expected a finite number for k",
    );
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// With `;` or a tab as separator a comma is a decimal comma, and a decimal point still reads.
#[test]
fn a_decimal_point_reads_in_semicolon_and_tab_lines() {
    let t = tips(
        "1.5;2.25;3;0;0;1\n0.5\t-1.5\t2\t0\t0\t1\n",
        Format::Csv,
        None,
    );
    assert_eq!(
        t,
        [Vector3::new(1.5, 2.25, 3.0), Vector3::new(0.5, -1.5, 2.0)]
    );
}

// ---------------------------------------------------------------------------------------------
// APT: the count of numbers

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// The error points at the first number that does not fit: the 4th of a 4- or 5-number GOTO,
/// the 7th of a longer one (however many follow), one past the end when numbers are missing.
#[test]
fn a_wrong_count_of_apt_numbers_is_reported_where_it_goes_wrong() {
    let goto = "expected 3 numbers (x, y, z) or 6 (x, y, z, i, j, k) after GOTO/";
    at(&error("GOTO/1\n", Format::Apt, None), 1, 7, goto);
    at(
        &error("GOTO/1,2,3,0,1\n", Format::Apt, None),
        1,
        12,
        "got 5",
    );
    // GOTO/1,2,3,0,0,1,7,8: the 7th number starts at column 18.
    at(
        &error("GOTO/1,2,3,0,0,1,7,8\n", Format::Apt, None),
        1,
        18,
        "got 8",
    );
    at(
        &error("GOTO/1,2,3,0,0,1,7,8,9,10\n", Format::Apt, None),
        1,
        18,
        "got 10",
    );
    let tlaxis = "expected 3 numbers (i, j, k) after TLAXIS/";
    at(&error("TLAXIS/0,0,1,5\n", Format::Apt, None), 1, 14, tlaxis);
    at(
        &error("TLAXIS/0,0,1,5,6,7,8\n", Format::Apt, None),
        1,
        14,
        "got 7",
    );
}

// ---------------------------------------------------------------------------------------------
// NC words

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// The word rules of the ISO reader's docs: `X 12.5`, `X=12.5` and `X = 12.5` are one word; a
/// leading `/` is block delete, a `/` after a word is no word; a run of two letters is a keyword
/// of another dialect, refused with its column.
#[test]
fn nc_words_keywords_and_slashes() {
    let m = caz_head();
    let t = tips("X 1.5 Y= 2 Z = 3\n/N20 X4\n", Format::Nc, Some(&m));
    assert_eq!(
        t,
        [Vector3::new(1.5, 2.0, 3.0), Vector3::new(4.0, 2.0, 3.0)]
    );
    for (text, column) in [("X0 Y0 Z0\nDL1 X5\n", 1), ("X0 Y0 Z0\nG1 X8 TRAFOOF\n", 7)] {
        at(
            &error(text, Format::Nc, Some(&m)),
            2,
            column,
            "is not ISO G-code",
        );
    }
    at(
        &error("G1 X1 / Y2\n", Format::Nc, Some(&m)),
        1,
        7,
        "expected a word (a letter and a number, like X12.5), got \"/\"",
    );
    at(
        &error("G1 X=\n", Format::Nc, Some(&m)),
        1,
        4,
        "expected a number after X, got the end of the line",
    );
    at(
        &error("G1 X = \n", Format::Nc, Some(&m)),
        1,
        4,
        "expected a number after X, got the end of the line",
    );
}

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// ±100000 mm and ±360000° are accepted, in inch the position reached in mm counts:
/// 3937.0078 in = 99999.998 mm is in range, 3937.0079 in = 100000.0007 mm is not.
#[test]
fn nc_positions_at_their_limits() {
    let m = caz_head();
    let p = parse(
        "G1 X100000 Y-100000 Z0 C360000 A-360000\n",
        Format::Nc,
        Some(&m),
    )
    .unwrap();
    assert_eq!(p[0].tip, Vector3::new(1e5, -1e5, 0.0));
    assert_eq!(p[0].angles, Some([360000.0, -360000.0]));
    let p = parse("G20 X3937.0078 Y0 Z0\n", Format::Nc, Some(&m)).unwrap();
    assert!((p[0].tip.x - 3937.0078 * 25.4).abs() < 1e-9);
    at(
        &error("G20 X3937.0079\n", Format::Nc, Some(&m)),
        1,
        6,
        "expected X within ±100000 mm",
    );
    // Incremental: the position reached, exactly at the limit.
    let p = parse("X0 Y0 Z0\nG91 C300000\nC60000\n", Format::Nc, Some(&m)).unwrap();
    assert_eq!(p[1].angles, Some([300000.0, 0.0]));
    assert_eq!(p[2].angles, Some([360000.0, 0.0]));
}

// ---------------------------------------------------------------------------------------------
// The APT writer's line width

// Found by cargo-mutants: a mutant in `crate/src/toolpath/` survived every other test.
/// A GOTO is continued with `$` after z exactly when its one-line form would be longer than
/// 72 characters; no written line is longer.
#[test]
fn apt_lines_are_continued_only_past_72_characters() {
    let point = |axis: [f64; 3]| Point {
        motion: Motion::Feed,
        tip: Vector3::new(-99999.123456, -99999.123456, -99999.123456),
        axis: Vector3::from(axis),
        line: 0,
        angles: None,
    };
    // "GOTO/" 5 + three "-99999.123456" and two commas 41 + "," 1 = 47 characters before ijk.
    let xyz = "-99999.123456,-99999.123456,-99999.123456";
    // ijk "-0.123456789,0.12345678,1": 25 characters, 72 in all: one line.
    let text = write(Format::Apt, &[point([-0.123456789, 0.12345678, 1.0])], None).unwrap();
    let one = format!("GOTO/{xyz},-0.123456789,0.12345678,1");
    assert_eq!(one.len(), 72);
    assert!(text.lines().any(|l| l == one), "{text}");
    // One digit more: 73, continued after z.
    let text = write(
        Format::Apt,
        &[point([-0.123456789, 0.123456789, 1.0])],
        None,
    )
    .unwrap();
    let two = format!("GOTO/{xyz},$\n-0.123456789,0.123456789,1");
    assert!(text.contains(&two), "{text}");
    assert!(text.lines().all(|l| l.len() <= 72), "{text}");
}
