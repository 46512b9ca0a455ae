//! The reading of error motions: CSV units and headers against the definitions of the units, the
//! value limits, constants and polynomials of one to eight coefficients, ISO names and the papers'
//! symbols refused with their ISO name and sign.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use fiveaxis::machine::motions::{self, read_table_csv};
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use serde_json::{json, Value};
use std::f64::consts::PI;

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// The units a CSV header may give (the doc of `read_table_csv`: lengths mm, µm, nm, m, in;
/// angles deg, rad, mrad, µrad, arcsec, µm/m, with the usual other spellings), each converted
/// to the API unit by its definition: 1 µm = 1e-3 mm, 1 nm = 1e-6 mm, 1 m = 1000 mm, 1 in =
/// 25.4 mm; 1 rad = 180/π °, 1 mrad = 0.18/π °, 1 µrad (and 1 µm/m, a slope) = 1.8e-4/π °,
/// 1″ = 1/3600 °.
#[test]
fn csv_headers_give_every_documented_unit_its_factor() {
    let lengths: [(&str, f64); 11] = [
        ("mm", 1.0),
        ("MM", 1.0),
        ("µm", 1e-3),
        ("\u{3bc}m", 1e-3),
        ("um", 1e-3),
        ("micron", 1e-3),
        ("microns", 1e-3),
        ("nm", 1e-6),
        ("m", 1e3),
        ("in", 25.4),
        ("inch", 25.4),
    ];
    for (unit, f) in lengths {
        // The value: 0.002 of the unit; the positions 0 and 2 of the unit.
        let t = read_table_csv(
            &format!("X ({unit}), E_XX ({unit})\n0, 0\n2, 0.002\n"),
            "E_XX",
        )
        .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(
            t.position[1],
            2.0 * f,
            1e-12 * f,
            &format!("position in {unit}"),
        );
        close(
            t.value[1],
            0.002 * f,
            1e-12 * f,
            &format!("value in {unit}"),
        );
        assert_eq!(t.units, [unit.to_string(), unit.to_string()]);
    }
    let angles: [(&str, f64); 15] = [
        ("deg", 1.0),
        ("°", 1.0),
        ("degree", 1.0),
        ("degrees", 1.0),
        ("rad", 180.0 / PI),
        ("mrad", 1e-3 * 180.0 / PI),
        ("µrad", 1e-6 * 180.0 / PI),
        ("urad", 1e-6 * 180.0 / PI),
        ("arcsec", 1.0 / 3600.0),
        ("″", 1.0 / 3600.0),
        ("\"", 1.0 / 3600.0),
        ("sec", 1.0 / 3600.0),
        ("as", 1.0 / 3600.0),
        ("µm/m", 1e-6 * 180.0 / PI),
        ("um/m", 1e-6 * 180.0 / PI),
    ];
    for (unit, f) in angles {
        // E_CC: positions of C (an angle) and values (an angle); E_BX: a length position.
        let t = read_table_csv(
            &format!("C [{unit}]; E_CC [{unit}]\n0; 0\n3; 0,03\n"),
            "E_CC",
        )
        .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(t.position[1], 3.0 * f, 1e-12 * f, &format!("C in {unit}"));
        close(t.value[1], 0.03 * f, 1e-12 * f, &format!("E_CC in {unit}"));
        let t = read_table_csv(&format!("X (mm), E_BX ({unit})\n0, 0\n1, 0.01\n"), "E_BX")
            .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(t.value[1], 0.01 * f, 1e-12 * f, &format!("E_BX in {unit}"));
        // An angle is not a length, nor the other way round.
        let e = read_table_csv(&format!("X (mm), E_XX ({unit})\n0, 0\n1, 1\n"), "E_XX");
        assert!(e.is_err(), "{unit} taken for a length");
    }
    for (unit, _) in lengths {
        let e = read_table_csv(&format!("X (mm), E_BX ({unit})\n0, 0\n1, 1\n"), "E_BX");
        assert!(e.is_err(), "{unit} taken for an angle");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// The header (doc of `read_table_csv` and `header_unit`): the unit is the text in `( )` or
/// `[ ]`; a `)` before the last `(` is no pair, so the `[ ]` count. A header word that is
/// neither another error motion's name (four letters such as `E_YX`) nor another axis letter is
/// the program's own and accepted, whatever its length.
#[test]
fn csv_headers_take_the_unit_from_a_pair_and_accept_their_own_words() {
    let t = read_table_csv("X [mm] )(, E_XX [µm]\n0, 0\n10, 4\n", "E_XX").unwrap();
    assert_eq!(t.units, ["mm".to_string(), "µm".to_string()]);
    close(t.value[1], 0.004, 1e-15, "4 µm");
    for header in ["dist (mm), devn (µm)", "p (mm), e (µm)", "mm, µm"] {
        let t = read_table_csv(&format!("{header}\n0, 0\n10, 4\n"), "E_XX")
            .unwrap_or_else(|e| panic!("{header}: {e}"));
        close(t.value[1], 0.004, 1e-15, header);
    }
}

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// A CSV value is accepted up to the error motion's limit (`ErrorDef::limit`, in the API unit)
/// inclusive and refused beyond it, with the line named.
#[test]
fn csv_values_are_accepted_up_to_the_limit_and_refused_beyond() {
    let limit = motions::find("E_XX").unwrap().limit;
    let at = format!("X (mm), E_XX (mm)\n0, {limit}\n1, -{limit}\n");
    let t = read_table_csv(&at, "E_XX").unwrap();
    assert_eq!(t.value, vec![limit, -limit]);
    let over = format!("X (mm), E_XX (mm)\n0, 0\n1, {}\n", limit * 1.001);
    let e = read_table_csv(&over, "E_XX").unwrap_err();
    assert!(e.message.starts_with("line 3"), "{e}");
}

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// Error motions as entered (module docs of `machine::motions`, "Values"): a constant of either
/// sign within the error's limit, a polynomial of one coefficient (a constant) up to eight
/// (degree 7, the most the reader takes), each kept in mm for a linear axis.
#[test]
fn error_motions_take_negative_constants_and_polynomials_of_one_to_eight_coefficients() {
    let read = |v: Value| Machine::from_value(&json!({ "motions": { "E_YX": v } }), "machine");
    let m = read(json!(-0.003)).unwrap();
    assert_eq!(
        m.motions.0["E_YX"].at(100.0, "E_YX", false).unwrap(),
        -0.003
    );
    let m = read(json!({ "poly": [-0.002] })).unwrap();
    assert_eq!(
        m.motions.0["E_YX"].at(250.0, "E_YX", false).unwrap(),
        -0.002
    );
    // 0.001·(1 + p + p² + … + p⁷) at p = 1 mm: 0.008 mm.
    let m = read(json!({ "poly": vec![0.001; 8] })).unwrap();
    close(
        m.motions.0["E_YX"].at(1.0, "E_YX", false).unwrap(),
        0.008,
        1e-15,
        "degree 7",
    );
    let e = read(json!({ "poly": vec![0.001; 9] })).unwrap_err();
    assert_eq!(e.field, "machine.motions.E_YX.poly", "{e}");
    let e = read(json!({ "poly": [] })).unwrap_err();
    assert_eq!(e.field, "machine.motions.E_YX.poly", "{e}");
}

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// A Tan & Lim symbol entered as an error motion is refused with the ISO name it stands for and
/// the sign (`ISO = sign · symbol`): their X moves the table, so X's straightness along Y and its
/// rotations change sign (δy(X) = −E_YX, Ez(X) = −E_CX), its positioning does not (δx(X) =
/// E_XX); their rotary-table rotations keep the sign convention of the loop, γ_C = −E_CC (the
/// doc of `motions::MOTIONS`). Either spelling, the symbol or its ASCII form, is recognised.
#[test]
fn a_papers_motion_symbol_is_refused_with_its_own_iso_name_and_sign() {
    for (entered, want) in [
        ("dy(X)", "E_YX = −δy(X)"),
        ("δy(X)", "E_YX = −δy(X)"),
        ("dx(X)", "E_XX = δx(X)"),
        ("Ez(X)", "E_CX = −Ez(X)"),
        ("gammaC", "E_CC = −γ_C"),
        ("γ_C", "E_CC = −γ_C"),
    ] {
        let e =
            Machine::from_value(&json!({ "motions": { entered: 0.001 } }), "machine").unwrap_err();
        assert!(e.message.contains(want), "{entered}: {e}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/machine/motions.rs` survived every other test.
/// Error motions set by ISO name are kept under that name (the X axis then lists its
/// positioning error E_XX with its value); an unknown name is refused and nothing is set.
#[test]
fn error_motions_are_set_by_iso_name_and_unknown_names_refused() {
    use fiveaxis::machine::motions::{ErrorFunction, ErrorMotions};
    let mut m = ErrorMotions::default();
    assert!(m.of_axis('X').is_none(), "nothing set yet");
    m.set("E_XX", ErrorFunction::Constant(0.002)).unwrap();
    let list = m.of_axis('X').unwrap();
    assert_eq!(list.len(), 1);
    assert_eq!(list[0].1, "E_XX");
    assert_eq!(list[0].2, ErrorFunction::Constant(0.002));
    assert!(m.set("E_QX", ErrorFunction::Constant(0.001)).is_err());
    assert!(m.of_axis('Y').is_none(), "the refused name set nothing");
}
