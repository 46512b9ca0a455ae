//! Every CSV reader of the engine shares one tokenizer (`fiveaxis::csv`): with `;` or a tab as
//! the separator a `,` inside a number is a decimal comma (European CMM exports); with `,` as the
//! separator it only separates. Per reader: the same data written both ways reads the same, and
//! a value written with a decimal comma is the number it stands for. Messages quote at most 40
//! characters of what the user gave.

use fiveaxis::cubic::identify::parse_measurements as cubic_measurements;
use fiveaxis::cubic::CubicPiece;
use fiveaxis::machine::motions::read_table_csv;
use fiveaxis::reversal::fit::parse_trace;
use fiveaxis::schema::Inputs;
use fiveaxis::sshape::identify::parse_measurements as sshape_measurements;
use serde_json::json;

/// A text of 10,000 characters with no separator and no number in it.
fn paste() -> String {
    "x".repeat(10_000)
}

/// The quoted part of a message is at most 40 characters of the user's text and an ellipsis.
fn assert_short(message: &str) {
    assert!(
        message.chars().count() < 300,
        "{} characters: {message:.300}",
        message.chars().count()
    );
    assert!(message.contains('…'), "{message}");
    assert!(!message.contains(&"x".repeat(41)), "{message}");
}

#[test]
fn sshape_measurements_accept_a_decimal_comma_with_semicolons_or_tabs() {
    // 100 points, TOP 1..50 then BOTTOM 1..50, deviation k·0.0001 mm written "0,0001"-style.
    let mut comma = String::from("curve,point,deviation_mm\n");
    let mut semicolon = String::from("curve;point;deviation_mm\n");
    let mut tab = String::from("curve\tpoint\tdeviation_um\n");
    for k in 0..100 {
        let (curve, point) = if k < 50 {
            ("top", k + 1)
        } else {
            ("bottom", k - 49)
        };
        comma.push_str(&format!("{curve},{point},0.{k:04}\n"));
        semicolon.push_str(&format!("{curve};{point};0,{k:04}\n"));
        // In µm: k·0.1 µm, "2,5"-style.
        tab.push_str(&format!("{curve}\t{point}\t{},{}\n", k / 10, k % 10));
    }
    let a = sshape_measurements(&comma).unwrap();
    let b = sshape_measurements(&semicolon).unwrap();
    let c = sshape_measurements(&tab).unwrap();
    for k in 0..100 {
        let want = k as f64 * 1e-4;
        assert!((a[k] - want).abs() < 1e-15, "{k}: {}", a[k]);
        assert_eq!(a[k], b[k], "{k}");
        assert!((c[k] - want).abs() < 1e-15, "{k}: {}", c[k]);
    }
    // With commas as separators a decimal comma is a fourth column, refused by its count.
    let e = sshape_measurements("curve,point,deviation_mm\ntop,1,0,0208\n").unwrap_err();
    assert!(
        e.message
            .contains("line 2: expected 3 columns like the header, got 4"),
        "{e}"
    );
    // A pasted text is quoted by its start only.
    let e =
        sshape_measurements(&format!("curve;point;deviation_mm\ntop;1;{}\n", paste())).unwrap_err();
    assert!(e.message.starts_with("line 2: deviation \"xxx"), "{e}");
    assert_short(&e.to_string());
    let e = sshape_measurements(&paste()).unwrap_err();
    assert_short(&e.to_string());
}

#[test]
fn cubic_zone_table_accepts_a_decimal_comma() {
    let piece = CubicPiece::from_value(&json!({}), "setup").unwrap();
    let a =
        cubic_measurements("zone;height_um;slope_x\nII-1;-5,5;0,001\nI;2,25;\n", &piece).unwrap();
    assert_eq!(a.len(), 2);
    assert!((a[0].height - -0.0055).abs() < 1e-15, "{}", a[0].height);
    assert_eq!(a[0].slope_x, Some(0.001));
    assert!((a[1].height - 0.00225).abs() < 1e-15, "{}", a[1].height);
    let b = cubic_measurements("zone\theight_mm\nII-1\t-0,0055\n", &piece).unwrap();
    assert_eq!(b[0].height, a[0].height);
    let c = cubic_measurements("zone,height_mm\nII-1,-0.0055\n", &piece).unwrap();
    assert_eq!(c[0].height, a[0].height);
    // Commas as separators: "1,5" is two cells.
    let e = cubic_measurements("zone,height_um\nII-1,-5,5\n", &piece).unwrap_err();
    assert!(
        e.message
            .contains("expected 2 columns like the header, got 3"),
        "{e}"
    );
    // A pasted zone name or header is quoted by its start only.
    let e = cubic_measurements(&format!("zone;height_um\n{};1\n", paste()), &piece).unwrap_err();
    assert_short(&e.to_string());
    let e =
        cubic_measurements(&format!("zone;height_um;{}\nI;1;2\n", paste()), &piece).unwrap_err();
    assert_short(&e.to_string());
}

#[test]
fn reversal_trace_accepts_a_decimal_comma() {
    // 360 points, 0.5° apart from 0.5°, deviation 2.5 µm written "0,0025" mm or "2,5" µm.
    let mut semicolon = String::from("angle_deg;deviation_mm\n");
    let mut tab = String::from("angle_deg\tdeviation_um\n");
    let mut comma = String::from("angle_deg,deviation_mm\n");
    for i in 0..360 {
        semicolon.push_str(&format!("{},5;0,0025\n", i));
        tab.push_str(&format!("{},5\t2,5\n", i));
        comma.push_str(&format!("{}.5,0.0025\n", i));
    }
    let a = parse_trace(&semicolon).unwrap();
    let b = parse_trace(&tab).unwrap();
    let c = parse_trace(&comma).unwrap();
    assert_eq!(a.angle.len(), 360);
    for i in 0..360 {
        let want = (i as f64 + 0.5).to_radians();
        assert!((a.angle[i] - want).abs() < 1e-15, "{i}");
        assert!((a.deviation[i] - 0.0025).abs() < 1e-15, "{i}");
        assert_eq!(
            (a.angle[i], a.deviation[i]),
            (b.angle[i], b.deviation[i]),
            "{i}"
        );
        assert_eq!(
            (a.angle[i], a.deviation[i]),
            (c.angle[i], c.deviation[i]),
            "{i}"
        );
    }
    let e = parse_trace("angle_deg,deviation_mm\n1,5,0,0025\n").unwrap_err();
    assert!(
        e.message
            .contains("expected 2 columns like the header, got 4"),
        "{e}"
    );
    let e = parse_trace(&paste()).unwrap_err();
    assert_short(&e.to_string());
    let e = parse_trace(&format!("angle_deg;deviation_mm\n1;{}\n", paste())).unwrap_err();
    assert_short(&e.to_string());
}

#[test]
fn error_motion_tables_accept_a_decimal_comma() {
    // Positioning of X in µm: 2.5 µm at 100 mm, 4.25 µm at 200 mm.
    let a = read_table_csv("X (mm); E_XX (µm)\n0;0\n100;2,5\n200,5;4,25\n", "E_XX").unwrap();
    assert_eq!(a.position, vec![0.0, 100.0, 200.5]);
    assert!(
        (a.value[1] - 0.0025).abs() < 1e-15 && (a.value[2] - 0.00425).abs() < 1e-15,
        "{:?}",
        a.value
    );
    let b = read_table_csv("X (mm)\tE_XX (µm)\n0\t0\n100\t2,5\n200,5\t4,25\n", "E_XX").unwrap();
    assert_eq!(a, b);
    let c = read_table_csv("X (mm), E_XX (µm)\n0, 0\n100, 2.5\n200.5, 4.25\n", "E_XX").unwrap();
    assert_eq!(a, c);
    let e = read_table_csv("X (mm), E_XX (µm)\n0, 0\n100, 2,5\n", "E_XX").unwrap_err();
    assert!(e.message.contains("line 3: expected two columns"), "{e}");
    let e = read_table_csv(
        &format!("X (mm); E_XX (µm)\n0;0\n100;{}\n", paste()),
        "E_XX",
    )
    .unwrap_err();
    assert!(e.message.starts_with("line 3: the value \"xxx"), "{e}");
    assert_short(&e.to_string());
    let e = read_table_csv(&format!("X ({}); E_XX (µm)\n0;0\n", paste()), "E_XX").unwrap_err();
    assert_short(&e.to_string());
}
