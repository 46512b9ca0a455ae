//! The reader of measured sphere centres (issue 31): decimal commas with `;`, tabs or spaces,
//! explicit `+` signs, CRLF, units in the header, the reference pose on the first line, the
//! designer's own table filled in; and each kind of bad line named with its line number.
#![allow(clippy::unwrap_used)]

use fiveaxis::probe::measure::read;

const LETTERS: Option<[char; 2]> = Some(['C', 'A']);

#[test]
fn a_semicolon_file_with_decimal_commas_plus_signs_and_crlf_is_read_in_mm_and_radians() {
    let text = "# sphere test\r\npose;C_deg;A_deg;X_mm;Y_mm;Z_mm\r\nref;0;0;+0,0012;-0,0008;+150,0003\r\n\r\n1;+30;-45,5;10,5;-2;149,25\r\n";
    let m = read(text, LETTERS).unwrap();
    assert_eq!(m.separator, ";");
    assert_eq!(m.reference, Some(0));
    assert_eq!(m.poses.len(), 2);
    assert_eq!(m.poses[0].centre, [0.0012, -0.0008, 150.0003]);
    assert_eq!(m.poses[1].line, 5);
    assert_eq!(m.poses[1].label, "1");
    assert!((m.poses[1].k - 30f64.to_radians()).abs() < 1e-15);
    assert!((m.poses[1].m + 45.5f64.to_radians()).abs() < 1e-15);
    assert_eq!(m.poses[1].centre, [10.5, -2.0, 149.25]);
}

#[test]
fn spaces_and_tabs_separate_and_units_convert_from_micrometres_and_radians() {
    let spaces = "k_rad   m_deg  x_um y_um z_mm\n0 0 1,5 -2 100\n2.5 +90 2.5 0 100,001\n";
    let m = read(spaces, None).unwrap();
    assert_eq!(m.separator, "spaces");
    assert!((m.poses[0].centre[0] - 0.0015).abs() < 1e-15);
    assert!((m.poses[1].k - 2.5).abs() < 1e-12);
    assert!((m.poses[1].centre[0] - 0.0025).abs() < 1e-15);
    let tabs = "C (deg)\tA [deg]\tX/mm\tY\tZ\n0\t0\t1\t2\t3\n90\t-30\t1,25\t2\t3\n";
    let m = read(tabs, LETTERS).unwrap();
    assert_eq!(m.separator, "tab");
    assert_eq!(m.poses[1].centre[0], 1.25);
    // Commas separate, so no decimal comma there; the first line is not the reference here.
    let commas = "k,m,x,y,z\n30,0,1.5,2,3\n60,0,1,2,3\n";
    let m = read(commas, None).unwrap();
    assert_eq!(m.reference, None);
    assert_eq!(m.poses[0].centre, [1.5, 2.0, 3.0]);
}

#[test]
fn the_designers_table_filled_in_is_read_back() {
    let text = "# comment\npose,C_deg,B_deg,expected_x_mm,expected_y_mm,expected_z_mm,X_mm,Y_mm,Z_mm\n1,0,0,150,0,100,150.001,0.002,99.999\n2,30,0,129.9,-75,100,129.91,-75,100\n";
    let m = read(text, Some(['C', 'B'])).unwrap();
    assert_eq!(m.poses.len(), 2);
    assert_eq!(m.poses[0].centre, [150.001, 0.002, 99.999]);
}

fn err(text: &str) -> String {
    read(text, LETTERS).unwrap_err().to_string()
}

#[test]
fn each_kind_of_bad_line_is_named() {
    let head = "C_deg;A_deg;X_mm;Y_mm;Z_mm\n0;0;1;2;3\n";
    // A cell that is not a number, on line 3.
    assert_eq!(
        err(&format!("{head}30;0;1,2,3;2;3\n")),
        "csv: line 3: X \"1,2,3\" is not a number"
    );
    // Too few or too many values.
    assert_eq!(
        err(&format!("{head}30;0;1;2\n")),
        "csv: line 3: expected 5 values like the header, got 4"
    );
    assert!(err(&format!("{head}30;0;1;2;3;4\n")).starts_with("csv: line 3: expected 5 values"));
    // An empty measured cell (the designer's table not filled in).
    assert_eq!(
        err(&format!("{head}30;0;;2;3\n")),
        "csv: line 3: X is empty: fill in the measured value"
    );
    // Not finite, out of range.
    assert!(
        err(&format!("{head}30;0;inf;2;3\n")).starts_with("csv: line 3: X \"inf\" is not a number")
    );
    assert!(err(&format!("{head}4000;0;1;2;3\n"))
        .starts_with("csv: line 3: K \"4000\" is out of range"));
    // Line numbers count comments and blank lines.
    assert!(err(&format!("# a\n\n{head}x;0;1;2;3\n")).starts_with("csv: line 5: K \"x\""));
}

#[test]
fn header_problems_are_named_on_the_header_line() {
    assert_eq!(
        err("# c\nC_deg;A_deg;X_mm;Y_mm\n0;0;1;2\n"),
        "csv: line 2: missing column Z in the header"
    );
    assert!(err("C_deg;A_deg;X_in;Y_mm;Z_mm\n").starts_with("csv: line 1: unknown column \"X_in\""));
    assert!(err("C_grad;A_deg;X_mm;Y_mm;Z_mm\n").starts_with("csv: line 1: unknown column"));
    assert!(err("C (grad);A_deg;X_mm;Y_mm;Z_mm\n").contains("unknown angle unit \"grad\""));
    assert!(err("C_deg;k;A_deg;X_mm;Y_mm;Z_mm\n").contains("two columns for K"));
    assert!(err("").starts_with("csv: the file is empty"));
    assert!(err("C_deg;A_deg;X_mm;Y_mm;Z_mm\n0;0;1;2;3\n").contains("1 pose measured"));
}

// Found by cargo-mutants: the reference pose found without its label (`||` as `&&`, `m == 0` as
// `!=`) and the labels of a file without a label column (`len() + 1` as `- 1` or `* 1`) changed
// no outcome of the tests before.
#[test]
fn a_first_pose_at_zero_is_the_reference_unlabelled_and_poses_are_numbered_from_one() {
    let at_zero = read("C;A;X;Y;Z\n0;0;1;2;3\n30;0;1;2;3\n60;-30;1;2;3\n", LETTERS).unwrap();
    assert_eq!(at_zero.reference, Some(0));
    let labels: Vec<&str> = at_zero.poses.iter().map(|p| p.label.as_str()).collect();
    assert_eq!(labels, ["1", "2", "3"]);
    // K at zero but not M, or M but not K: no reference.
    for text in [
        "C;A;X;Y;Z\n0;30;1;2;3\n30;0;1;2;3\n",
        "C;A;X;Y;Z\n30;0;1;2;3\n0;0;1;2;3\n",
    ] {
        assert_eq!(read(text, LETTERS).unwrap().reference, None, "{text}");
    }
    // Labelled REF anywhere on the first line's pose: the reference, whatever its angles.
    let labelled = read("pose;C;A;X;Y;Z\nREF;30;10;1;2;3\nP2;0;0;1;2;3\n", LETTERS).unwrap();
    assert_eq!(labelled.reference, Some(0));
    assert_eq!(labelled.poses[1].label, "P2");
}
