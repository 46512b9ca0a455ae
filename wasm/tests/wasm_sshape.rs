//! The S-shape exports run as WebAssembly in headless Node (`wasm-pack test --node`): the part,
//! the overcut maps against the paper's maxima, the defects against Appendix A's closed form for
//! single errors, the identification of the sample file, and bad input (a malformed CSV names its
//! line).
#![cfg(target_arch = "wasm32")]

mod common;

use common::wasm::{error_message, js};
use fiveaxis::wasm;
use serde::Deserialize;
use wasm_bindgen::JsValue;
use wasm_bindgen_test::wasm_bindgen_test;

const SAMPLE: &str = include_str!("../../public/samples/sshape-measured.csv");
const MACHINE: &str = r#"{"l0":499.889,"rTool":10,"lTool":35}"#;

#[derive(Deserialize)]
struct Point {
    curve: String,
    number: usize,
    surface: String,
    u: f64,
    point: Vec<f64>,
    normal: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct PartOut {
    points: Vec<Point>,
    curve_lengths: Vec<f64>,
}

fn part_points() -> Vec<Point> {
    let out = wasm::sshape_part(JsValue::UNDEFINED).expect("default part");
    let p: PartOut = serde_wasm_bindgen::from_value(out).expect("shape");
    p.points
}

#[wasm_bindgen_test]
fn the_part_has_two_surfaces_and_100_numbered_points() {
    let out = wasm::sshape_part(js(r#"{"nu":27,"nv":4}"#)).expect("valid");
    let z: js_sys::Float64Array = {
        let s =
            js_sys::Array::from(&js_sys::Reflect::get(&out, &"surfaces".into()).expect("surfaces"));
        assert_eq!(s.length(), 2);
        js_sys::Reflect::get(&s.get(0), &"z".into())
            .expect("z")
            .into()
    };
    let z = z.to_vec();
    assert_eq!(z.len(), 27 * 4);
    assert!(
        z[..27].iter().all(|v| v.abs() < 1e-12) && z[81..].iter().all(|v| (v - 30.0).abs() < 1e-12)
    );
    let p: PartOut = serde_wasm_bindgen::from_value(out).expect("shape");
    assert_eq!(p.points.len(), 100);
    assert_eq!(
        (
            p.points[0].curve.as_str(),
            p.points[0].number,
            p.points[0].surface.as_str()
        ),
        ("top", 1, "A")
    );
    assert_eq!(
        (
            p.points[75].curve.as_str(),
            p.points[75].number,
            p.points[75].surface.as_str()
        ),
        ("bottom", 26, "B")
    );
    assert!(p
        .points
        .iter()
        .all(|q| (q.point[2] - if q.curve == "top" { 25.0 } else { 11.0 }).abs() < 1e-9));
    assert!(p.curve_lengths.iter().all(|l| *l > 400.0 && *l < 700.0));
    assert!(error_message(wasm::sshape_part(js(r#"{"nu":1}"#))).starts_with("nu:"));
}

#[wasm_bindgen_test]
fn overcut_maxima_match_the_papers_with_its_sign_of_n() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct S {
        id: String,
        max_eq6_paper: f64,
        max_gouge: f64,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        exact: js_sys::Float64Array,
    }
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        surfaces: Vec<S>,
        b_paper_side: Vec<f64>,
    }
    // 261 = 13·20 + 1 columns put every knot, where the maxima lie, on the grid.
    let out =
        wasm::sshape_overcut(js(r#"{"rTool":10,"lTool":35,"nu":261,"nv":4}"#)).expect("valid");
    let o: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    assert_eq!(o.surfaces[0].id, "A");
    assert!(
        (o.surfaces[0].max_eq6_paper / 0.0387 - 1.0).abs() < 0.08,
        "A eq 6 {}",
        o.surfaces[0].max_eq6_paper
    );
    assert!(
        (o.b_paper_side[0] / 0.0125 - 1.0).abs() < 0.05,
        "B eq 6, paper's side {}",
        o.b_paper_side[0]
    );
    for s in &o.surfaces {
        assert_eq!(s.exact.length(), 261 * 4);
        assert!(
            s.max_gouge > 0.015 && s.max_gouge < 0.03,
            "{} gouge {}",
            s.id,
            s.max_gouge
        );
    }
    assert!(error_message(wasm::sshape_overcut(js(
        r#"{"rTool":0,"lTool":35,"nu":10,"nv":3}"#
    )))
    .starts_with("rTool:"));
    assert!(error_message(wasm::sshape_overcut(js(
        r#"{"rTool":10,"lTool":20,"nu":10,"nv":3}"#
    )))
    .starts_with("lTool:"));
}

#[wasm_bindgen_test]
fn defects_of_single_errors_follow_appendix_a() {
    #[derive(Deserialize)]
    struct Pose {
        b: f64,
        c: f64,
        singular: bool,
    }
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        #[serde(with = "serde_wasm_bindgen::preserve")]
        total: js_sys::Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        contributions: js_sys::Float64Array,
        poses: Vec<Pose>,
        pair_cosines: Vec<f64>,
    }
    let a0b_deg = 3.2419e-4f64.to_degrees();
    let out = wasm::sshape_defects(js(&format!(
        r#"{{"machine":{MACHINE},"errors":{{"E_X0B":0.0294,"E_A0B":{a0b_deg}}},"dR":0}}"#
    )))
    .expect("valid");
    let o: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    let pts = part_points();
    let (total, contrib) = (o.total.to_vec(), o.contributions.to_vec());
    assert_eq!((total.len(), contrib.len(), o.poses.len()), (100, 800, 100));
    let l0 = 499.889;
    for k in 0..100 {
        let (b, c) = (o.poses[k].b.to_radians(), o.poses[k].c.to_radians());
        let n = &pts[k].normal;
        // Appendix A: E_X0B moves the tip by (cos C, −sin C, 0), E_A0B by L0·cos B·(sin C, cos C, 0);
        // the reference pose (B = C = 0) subtracts (1, 0, 0) and (0, L0, 0).
        let x0b = 0.0294 * ((c.cos() - 1.0) * n[0] - c.sin() * n[1]);
        let a0b = 3.2419e-4 * (l0 * b.cos() * (c.sin() * n[0] + c.cos() * n[1]) - l0 * n[1]);
        assert!((contrib[8 * k + 5] - x0b).abs() < 1e-9, "E_X0B at {k}");
        assert!((contrib[8 * k + 6] - a0b).abs() < 1e-9, "E_A0B at {k}");
        assert!((total[k] - x0b - a0b).abs() < 1e-9);
    }
    // The tool is vertical (C kept) exactly on the plane middle of the S, u ∈ [6/13, 8/13]: one
    // point of each of the four measurement curves lies there.
    for (k, p) in o.poses.iter().enumerate() {
        let inside = pts[k].u > 6.0 / 13.0 && pts[k].u < 8.0 / 13.0;
        assert_eq!(p.singular, inside, "point {k}");
    }
    assert_eq!(o.poses.iter().filter(|p| p.singular).count(), 4);
    assert!(o.pair_cosines[0] > -0.9, "work-origin reference: not alike");
    let out = wasm::sshape_defects(js(&format!(
        r#"{{"machine":{{"l0":499.889,"rTool":10,"lTool":35,"reference":"axesZero"}},"errors":{{}}}}"#
    )))
    .expect("valid");
    let o: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    assert!(
        o.pair_cosines[0] < -0.999 && o.pair_cosines[1] < -0.999,
        "eq 14 as printed: alike but for sign"
    );
}

#[wasm_bindgen_test]
fn identifying_the_sample_file_recovers_table_4() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Est {
        name: String,
        unit: String,
        value: Option<f64>,
        std_error: Option<f64>,
    }
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        estimates: Vec<Est>,
        rank: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        residuals: js_sys::Float64Array,
        rms: f64,
    }
    let input = js_sys::Object::new();
    js_sys::Reflect::set(&input, &"machine".into(), &js(MACHINE)).expect("set");
    js_sys::Reflect::set(&input, &"csv".into(), &SAMPLE.into()).expect("set");
    let out = wasm::sshape_identify(input.into()).expect("valid");
    let o: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    assert_eq!(o.rank, 9);
    assert_eq!(o.residuals.length(), 100);
    assert!(o.rms < 0.003);
    let get = |n: &str| o.estimates.iter().find(|e| e.name == n).expect("estimate");
    let x0b = get("E_X0B");
    assert_eq!(x0b.unit, "mm");
    assert!((x0b.value.expect("identifiable") - 0.0294).abs() < 4.0 * x0b.std_error.expect("se"));
    let a0b = get("E_A0B");
    assert_eq!(a0b.unit, "°");
    assert!(
        (a0b.value.expect("identifiable") - 3.2419e-4f64.to_degrees()).abs()
            < 4.0 * a0b.std_error.expect("se")
    );
    let dr = get("dR");
    assert!((dr.value.expect("identifiable") + 0.02).abs() < 4.0 * dr.std_error.expect("se"));
}

#[wasm_bindgen_test]
fn eq_14_as_printed_reports_the_pairs_as_groups() {
    #[derive(Deserialize)]
    struct Group {
        members: Vec<String>,
    }
    #[derive(Deserialize)]
    struct Out {
        groups: Vec<Group>,
        rank: usize,
    }
    let input = js_sys::Object::new();
    js_sys::Reflect::set(
        &input,
        &"machine".into(),
        &js(r#"{"l0":499.889,"rTool":10,"lTool":35,"reference":"axesZero"}"#),
    )
    .expect("set");
    js_sys::Reflect::set(&input, &"csv".into(), &SAMPLE.into()).expect("set");
    js_sys::Reflect::set(&input, &"radiusTerm".into(), &JsValue::FALSE).expect("set");
    let o: Out =
        serde_wasm_bindgen::from_value(wasm::sshape_identify(input.into()).expect("valid"))
            .expect("shape");
    assert_eq!(o.rank, 6);
    let members: Vec<Vec<String>> = o.groups.into_iter().map(|g| g.members).collect();
    assert_eq!(
        members,
        vec![
            vec!["E_A0Z".to_string(), "E_A0C".into()],
            vec!["E_B0Z".into(), "E_B0C".into()]
        ]
    );
}

#[wasm_bindgen_test]
fn bad_input_and_a_malformed_csv_come_back_as_errors_naming_the_place() {
    let with_csv = |csv: &str| {
        let input = js_sys::Object::new();
        js_sys::Reflect::set(&input, &"machine".into(), &js(MACHINE)).expect("set");
        js_sys::Reflect::set(&input, &"csv".into(), &csv.into()).expect("set");
        wasm::sshape_identify(input.into())
    };
    // Line 12 of the sample (the 3rd data row) damaged.
    let mut lines: Vec<String> = SAMPLE.lines().map(String::from).collect();
    assert!(lines[11].starts_with("top,3,"));
    lines[11] = "top,3,0.0x2".into();
    let msg = error_message(with_csv(&lines.join("\n")));
    assert!(
        msg.starts_with("csv: line 12: ") && msg.contains("\"0.0x2\" is not a number"),
        "{msg}"
    );
    lines[11] = "top,2,0.002".into();
    let msg = error_message(with_csv(&lines.join("\n")));
    assert!(
        msg.contains("line 12: point top 2 is given twice (first on line 11)"),
        "{msg}"
    );
    lines.remove(11);
    let msg = error_message(with_csv(&lines.join("\n")));
    assert!(
        msg.contains("1 of the 100 points are missing: top 3"),
        "{msg}"
    );
    let msg = error_message(with_csv("curve,point\ntop,1"));
    assert!(
        msg.starts_with("csv: line 1: missing column 'deviation_mm'"),
        "{msg}"
    );
    let cases = [
        (
            r#"{"machine":{"l0":-5,"rTool":10,"lTool":35},"errors":{}}"#,
            "machine.l0:",
        ),
        (
            r#"{"machine":{"l0":500,"rTool":10,"lTool":35,"branch":"other"},"errors":{}}"#,
            "machine.branch:",
        ),
        (
            r#"{"machine":{"l0":500,"rTool":10,"lTool":35},"errors":{"E_A0B":5}}"#,
            "errors.E_A0B:",
        ),
        (
            r#"{"machine":{"l0":500,"rTool":10,"lTool":35},"errors":{"E_X0B":"x"}}"#,
            "errors.E_X0B:",
        ),
        (
            r#"{"machine":{"l0":500,"rTool":-1,"lTool":35},"errors":{}}"#,
            "machine.rTool:",
        ),
        (
            r#"{"machine":{"l0":500,"rTool":10,"lTool":35},"dR":3}"#,
            "dR:",
        ),
        (r#"{"errors":{}}"#, "missing field `machine`"),
    ];
    for (input, want) in cases {
        let msg = error_message(wasm::sshape_defects(js(input)));
        assert!(msg.contains(want), "{input} -> {msg}");
    }
    assert!(error_message(wasm::sshape_defects(JsValue::UNDEFINED)).starts_with("input:"));
}
