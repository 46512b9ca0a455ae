//! Tan & Lim's RRTTT model (Section VI): the printed first-order ΔX, ΔY, ΔZ against the loop
//! they come from, and the machine's model against both.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use crate::common;

use common::Rng;
use fiveaxis::machine::errors::{self, ErrorDef};
use fiveaxis::machine::motions::{self, ErrorFunction, ErrorMotions};
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::volumetric::paper::{self, PaperErrors, SYMBOLS};
use fiveaxis::volumetric::{self, deviation_at};
use nalgebra::Vector3;
use serde_json::json;

fn unit(slot: usize, h: f64) -> PaperErrors {
    let mut v = [0.0; 33];
    v[slot] = h;
    PaperErrors::from_slots(&v)
}

fn random_pose(rng: &mut Rng) -> (Vector3<f64>, Vector3<f64>) {
    (
        Vector3::new(
            rng.range(-400.0, 400.0),
            rng.range(-300.0, 300.0),
            rng.range(-300.0, 300.0),
        ),
        Vector3::new(
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
            rng.range(-250.0, 0.0),
        ),
    )
}

#[test]
fn every_printed_coefficient_is_the_derivative_of_the_loop() {
    let mut rng = Rng::new(11);
    for _ in 0..5 {
        let (p, t) = random_pose(&mut rng);
        for (s, symbol) in SYMBOLS.iter().enumerate() {
            // Central difference of the exact loop; h small against 1 but the loop is nonlinear
            // only through products of errors, so the difference is exact to O(h²).
            let h = 1e-6;
            let plus = paper::loop_deviation(&unit(s, h), p, t).unwrap();
            let minus = paper::loop_deviation(&unit(s, -h), p, t).unwrap();
            let fd = (plus - minus) / (2.0 * h);
            // The printed form is linear in the errors: its coefficient is its value at 1.
            let printed = paper::printed(&unit(s, 1.0), p, t);
            let scale = 1.0 + p.norm() + t.norm();
            assert!(
                (fd - printed).norm() < 1e-6 * scale,
                "{symbol}: loop derivative {fd:?}, printed {printed:?}"
            );
        }
    }
}

#[test]
fn the_printed_form_misses_only_second_order_terms() {
    let mut rng = Rng::new(5);
    let (p, t) = random_pose(&mut rng);
    let mut base = [0.0; 33];
    for (s, v) in base.iter_mut().enumerate() {
        // Translations up to 10 µm, angles up to 50 µrad.
        let translation =
            matches!(s % 6, 0..=2) && s < 18 || (21..24).contains(&s) || (27..30).contains(&s);
        *v = if translation {
            rng.range(-0.01, 0.01)
        } else {
            rng.range(-5e-5, 5e-5)
        };
    }
    let remainder = |scale: f64| {
        let e = PaperErrors::from_slots(&base.map(|v| v * scale));
        (paper::loop_deviation(&e, p, t).unwrap() - paper::printed(&e, p, t)).norm()
    };
    let (r1, r2, r3) = (remainder(1.0), remainder(0.1), remainder(0.01));
    assert!(r1 > 1e-9, "the remainder should not vanish: {r1}");
    // Scaling the errors by 1/10 scales the remainder by 1/100.
    for (a, b) in [(r1, r2), (r2, r3)] {
        let ratio = a / b;
        assert!(
            (ratio - 100.0).abs() < 3.0,
            "remainder ratio {ratio} ({a} / {b})"
        );
    }
}

#[test]
fn zero_errors_give_zero_deviation() {
    let mut rng = Rng::new(3);
    let (p, t) = random_pose(&mut rng);
    let e = PaperErrors::default();
    assert_eq!(paper::loop_deviation(&e, p, t).unwrap(), Vector3::zeros());
    assert_eq!(paper::printed(&e, p, t), Vector3::zeros());
}

// ---- the machine's model on Tan & Lim's machine

fn tan_lim() -> Machine {
    Machine::from_value(
        &json!({
            "kind": "table-table", "type": "CAZ", "linear": "table-x",
            "geometry": { "rotaryOffset": 0, "tableHeight": 0, "toolLength": 100 },
            "rotary": { "kFrom": -360, "kTo": 360, "mFrom": -120, "mTo": 120 }
        }),
        "machine",
    )
    .unwrap()
}

/// The ISO error a paper symbol stands for, and `ISO = sign · symbol`.
fn iso_of(symbol: &str) -> (&'static ErrorDef, f64) {
    motions::MOTIONS
        .iter()
        .chain(errors::TABLE.iter())
        .find_map(|d| {
            d.aliases
                .iter()
                .find(|a| a.symbol == symbol)
                .map(|a| (d, a.sign))
        })
        .unwrap_or_else(|| panic!("no ISO error for {symbol}"))
}

/// The machine with only the error `def` at `value` (engine units).
fn with_error(def: &ErrorDef, value: f64) -> Machine {
    let mut m = tan_lim();
    match def.kind {
        errors::ErrorKind::Location => m.errors.set(def.name, value).unwrap(),
        errors::ErrorKind::Motion => {
            let mut mo = ErrorMotions::default();
            mo.set(def.name, ErrorFunction::Constant(value)).unwrap();
            m.motions = mo;
        }
    }
    m
}

/// The machine's deviation (workpiece and machine-axis directions) per unit of `def`, central
/// differences of the exact chain.
fn machine_rate(def: &ErrorDef, p: [f64; 3], k: f64, m: f64) -> (Vector3<f64>, Vector3<f64>) {
    let h = 1e-7;
    let at = |v: f64| {
        let c = volumetric::compare(&with_error(def, v), p, k, m).unwrap();
        (Vector3::from(c.machine), Vector3::from(c.machine_axes))
    };
    let ((w1, a1), (w0, a0)) = (at(h), at(-h));
    ((w1 - w0) / (2.0 * h), (a1 - a0) / (2.0 * h))
}

const SQUARENESS: [&str; 3] = ["α", "β1", "β2"];

#[test]
fn with_the_rotary_axes_at_zero_the_machine_is_the_paper_error_by_error() {
    let machine = tan_lim();
    let tool = machine.build().unwrap().chain.tool_tip;
    let mut rng = Rng::new(21);
    for _ in 0..3 {
        let p = [
            rng.range(-300.0, 300.0),
            rng.range(-200.0, 200.0),
            rng.range(-200.0, 200.0),
        ];
        for (s, symbol) in SYMBOLS.iter().enumerate() {
            if SQUARENESS.contains(symbol) {
                continue;
            }
            let (def, sign) = iso_of(symbol);
            let (work, _) = machine_rate(def, p, 0.0, 0.0);
            let paper = paper::printed(&unit(s, 1.0), Vector3::from(p), tool);
            // ISO = sign·symbol: per unit of the symbol the machine moves sign·(per unit ISO).
            assert!(
                (work * sign - paper).norm() < 1e-6 * (1.0 + paper.norm()),
                "{symbol} ({}): machine {:?}, paper {paper:?}",
                def.name,
                work * sign
            );
        }
    }
}

#[test]
fn squareness_differs_by_the_reference_axis_and_the_tilted_tool_only() {
    // Same angle between the axes; the machine's ISO orientations differ from the paper's
    // straightness-like squareness by (α) a rigid turn about Z of the nominal tip
    // (X+Xt, Y+Yt, Z+Zt), (β1, β2) the tilt of the tool offset (Xt, Yt, Zt) with Z.
    let machine = tan_lim();
    let tool = machine.build().unwrap().chain.tool_tip;
    let p = [120.0, -80.0, 60.0];
    let tip = Vector3::from(p) + tool;
    let expected = [
        // α = −E_C0Y: the Y frame turned by −α about Z moves the tip by −α·ẑ × (tip − 0),
        // with the tip in table coordinates; the paper has only +α·X in ΔY.
        -Vector3::z().cross(&tip),
        // β1 = −E_B0Z: −ŷ × tool.
        -Vector3::y().cross(&tool),
        // β2 = E_A0Z: x̂ × tool.
        Vector3::x().cross(&tool),
    ];
    for (symbol, diff) in SQUARENESS.iter().zip(expected) {
        let s = SYMBOLS.iter().position(|x| x == symbol).unwrap();
        let (def, sign) = iso_of(symbol);
        let (work, _) = machine_rate(def, p, 0.0, 0.0);
        let paper = paper::printed(&unit(s, 1.0), Vector3::from(p), tool);
        let got = work * sign - paper;
        assert!(
            (got - diff).norm() < 1e-6 * (1.0 + diff.norm()),
            "{symbol}: machine − paper {got:?}, expected {diff:?}"
        );
        assert!(diff.norm() > 1.0, "the difference is real for {symbol}");
    }
}

#[test]
fn with_c_turned_the_paper_is_the_deviation_along_the_machine_axes() {
    // The loop has no nominal rotation: its ΔX, ΔY, ΔZ are along the machine axes. On the
    // machine the table turns with C, so on the workpiece the same deviation is turned back.
    let machine = tan_lim();
    let tool = machine.build().unwrap().chain.tool_tip;
    let p = [150.0, 90.0, -40.0];
    let c = 70f64.to_radians();
    for (s, symbol) in SYMBOLS.iter().enumerate() {
        if SQUARENESS.contains(symbol) {
            continue;
        }
        let (def, sign) = iso_of(symbol);
        let (work, axes) = machine_rate(def, p, c, 0.0);
        let paper = paper::printed(&unit(s, 1.0), Vector3::from(p), tool);
        assert!(
            (axes * sign - paper).norm() < 1e-6 * (1.0 + paper.norm()),
            "{symbol}: along the axes {:?}, paper {paper:?}",
            axes * sign
        );
        // On the workpiece: under ISO 841 the table turns by −C, so a vector fixed along the
        // machine axes is seen on the workpiece turned by +C about Z: R_Z(C)·paper.
        let (sn, cs) = c.sin_cos();
        let turned = Vector3::new(
            cs * paper.x - sn * paper.y,
            sn * paper.x + cs * paper.y,
            paper.z,
        );
        let w = work * sign;
        assert!(
            (w - turned).norm() < 1e-6 * (1.0 + paper.norm()),
            "{symbol}: workpiece {w:?} is not the paper's turned by +C: {turned:?}"
        );
        if paper.x.hypot(paper.y) > 1e-3 {
            assert!(
                (w - axes * sign).norm() > 1e-4,
                "{symbol}: C turns the result"
            );
        }
    }
}

#[test]
fn with_a_turned_c_error_motions_follow_the_tilted_c_axis() {
    // The loop applies C's errors along the machine axes; on the machine C sits on A, so a
    // radial error motion of C is along C's own (tilted) frame: R_A·e.
    let machine = tan_lim();
    let model = machine.build().unwrap();
    let a = 35f64.to_radians();
    let p = [40.0, 60.0, 80.0];
    let q = model.positions(0.0, a);
    let (fw, _) = model.nominal().frames(&q, false).unwrap();
    for (name, e) in [
        ("E_XC", Vector3::x()),
        ("E_YC", Vector3::y()),
        ("E_ZC", Vector3::z()),
    ] {
        let def = motions::find(name).unwrap();
        let (_, axes) = machine_rate(def, p, 0.0, a);
        let expected = fw.rotation * e;
        assert!(
            (axes - expected).norm() < 1e-6,
            "{name}: {axes:?} vs R_A·e {expected:?}"
        );
    }
    // X's errors do not follow A: E_YX is along Y whatever A.
    let (_, axes) = machine_rate(motions::find("E_YX").unwrap(), p, 0.0, a);
    assert!((axes - Vector3::y()).norm() < 1e-6, "{axes:?}");
}

#[test]
fn error_motion_signs_are_of_the_tool_relative_to_the_workpiece() {
    // Independent of the paper: on a table X (Tan & Lim's), E_XX = +2 µm puts the tool 2 µm
    // further along +X on the workpiece; a spindle-side Y likewise; a pitch E_BX of the table
    // turns the tool about the X carriage's reference point by +E_BX (Y axis, right hand).
    let p = [100.0, 50.0, 20.0];
    let model = tan_lim().build().unwrap();
    let lin = ["X", "Y", "Z"].map(|a| model.chain.index_of(a).unwrap());
    let mut q = model.positions(0.0, 0.0);
    for (i, &l) in lin.iter().enumerate() {
        q[l] = p[i];
    }
    let one = |name: &str, v: f64| {
        let def = motions::find(name).unwrap();
        let m = with_error(def, v).build().unwrap();
        deviation_at(&m, &q).unwrap().0
    };
    assert!((one("E_XX", 0.002) - Vector3::new(0.002, 0.0, 0.0)).norm() < 1e-12);
    assert!((one("E_YY", 0.002) - Vector3::new(0.0, 0.002, 0.0)).norm() < 1e-12);
    // Pitch: the tip relative to the X carriage's origin is (X, Y, Z + Zt) in table coordinates.
    let b = 1e-5;
    let arm = Vector3::new(p[0], p[1], p[2]) + model.chain.tool_tip;
    let expected = Vector3::y().cross(&arm) * b;
    let got = one("E_BX", b);
    assert!(
        (got - expected).norm() < 1e-9 * arm.norm(),
        "{got:?} vs {expected:?}"
    );
}

#[test]
fn other_machines_are_refused_by_the_paper_model_with_the_preset_named() {
    let m = Machine::standard().unwrap();
    let e = volumetric::compare(&m, [0.0; 3], 0.0, 0.0).unwrap_err();
    assert!(e.message.contains("Tan & Lim"), "{e}");
}

/// `compare` reads the machine's ISO errors into the paper's symbols itself: with one small
/// error entered by its ISO name (1 µm or 1 µrad; squareness left out, see above), the paper's
/// printed first-order form at rotary axes zero is the machine's deviation along its axes (zero
/// for the yaw of Y, whose tool sits on Y's line), and
/// the symbols listed hold that one value (in the paper's sign) and zeros.
#[test]
fn an_iso_error_entered_reaches_the_paper_model_as_its_symbol() {
    let p = [120.0, -80.0, 60.0];
    for (s, symbol) in SYMBOLS.iter().enumerate() {
        if SQUARENESS.contains(symbol) {
            continue;
        }
        let (def, sign) = iso_of(symbol);
        let c = volumetric::compare(&with_error(def, 1e-6), p, 0.0, 0.0).unwrap();
        let (printed, machine) = (
            Vector3::from(c.paper_printed),
            Vector3::from(c.machine_axes),
        );
        assert!(
            (printed - machine).norm() < 1e-6 * machine.norm() + 1e-15,
            "{symbol} ({}): paper {printed:?}, machine {machine:?}",
            def.name
        );
        for (t, sym) in c.symbols.iter().enumerate() {
            let (name, v) = (&sym.symbol, sym.value);
            assert_eq!(name, SYMBOLS[t]);
            let want = if t == s { 1e-6 * sign } else { 0.0 };
            assert_eq!(v, want, "{symbol}: slot {name}");
        }
    }
}

/// Which errors the paper's loop leaves out: location errors of the rotary axes that are entered
/// (non-zero); a squareness error (the paper's α) and the errors left at zero are not listed.
#[test]
fn errors_the_paper_has_no_symbol_for_are_named() {
    let mut m = tan_lim();
    m.errors.set("E_Y0A", 0.01).unwrap();
    m.errors.set(iso_of("α").0.name, 1e-5).unwrap();
    let c = volumetric::compare(&m, [0.0; 3], 0.0, 0.0).unwrap();
    assert_eq!(c.not_in_paper, ["E_Y0A"]);
    let c = volumetric::compare(&tan_lim(), [0.0; 3], 0.0, 0.0).unwrap();
    assert!(c.not_in_paper.is_empty());
}

/// Each symbol's unit: the paper's δ (straightness, positioning) and ∂ (location) are lengths,
/// its E, α, β, φ, λ, γ angles.
#[test]
fn a_symbol_is_an_angle_unless_it_is_a_delta_or_a_partial() {
    for (s, symbol) in SYMBOLS.iter().enumerate() {
        let length = symbol.starts_with('δ') || symbol.starts_with('∂');
        assert_eq!(paper::is_angle(s), !length, "{symbol}");
    }
}
