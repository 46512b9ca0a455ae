//! The three studies through the JavaScript API as a script would call them, against the papers'
//! facts and closed forms written here (not the engine's output): Li et al.'s Table 2 and the
//! first-order heights of eq 10 at II-1, eq 26 of the nonlinear paper, Chanal et al.'s
//! Appendix A for single errors and the identification of the sample file.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{error_message, jv, preset, read, CHANAL, LI, SAMPLE};
use fiveaxis_wasm as fa;
use serde::Deserialize;
use serde_json::json;
use wasm_bindgen::JsValue;
use wasm_bindgen_test::wasm_bindgen_test;

/// Li et al.'s Table 5 in ISO names: E = −ε of the paper (δxBY = 14.6 µm → E_X0B = −0.0146 mm).
fn table5() -> serde_json::Value {
    json!({
        "E_X0B": -0.0146, "E_Y0B": 0.0089, "E_Z0B": 0.0142, "E_A0B": 0.0023,
        "E_B0B": -0.0029, "E_C0B": 0.00002, "E_A0C": 0.00017, "E_X0C": -0.0094,
    })
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Zone {
    name: String,
    k: f64,
    m: f64,
    height: f64,
    linear_height: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct CubicOut {
    zones: Vec<Zone>,
    error_names: Vec<String>,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    k_height: js_sys::Float64Array,
}

#[wasm_bindgen_test]
fn the_cubic_test_on_li_et_als_machine_gives_table_2_and_eq_10() {
    let mut m = preset(LI);
    m["errors"] = table5();
    let r: CubicOut = read(fa::cubicTest(jv(&json!({ "machine": m }))));
    let names: Vec<&str> = r.zones.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(
        names,
        ["I", "II-1", "II-2", "II-3", "II-4", "III-1", "III-2", "III-3", "III-4"]
    );
    // Table 2: C (K) and B (M).
    let c = [0.0, 0.0, 90.0, 180.0, 270.0, 45.0, 135.0, 225.0, 315.0];
    for (z, c) in r.zones.iter().zip(c) {
        assert!((z.k - c).abs() < 1e-9, "{}: C {}", z.name, z.k);
        let b = if z.name == "I" { 0.0 } else { 30.0 };
        assert!((z.m - b).abs() < 1e-9, "{}: B {}", z.name, z.m);
    }
    // With M_WC, ZONE I is exact; II-1 (C = 0°) feels only δxBY (−sin 30° per mm) and δzBY
    // (cos 30° − 1 per mm) to first order (closed forms of eq 10), in the paper's signs.
    assert!(r.zones[0].height.abs() < 1e-15);
    let ii1 = -0.5 * 0.0146 + (30f64.to_radians().cos() - 1.0) * -0.0142;
    assert!((r.zones[1].linear_height - ii1).abs() < 1e-12);
    assert!((r.zones[1].height - ii1).abs() < 1e-7);
    // Per ISO error and per degree: E_X0B = −δxBY at II-1: +0.5; E_A0B = −αBY at II-2
    // (C = 90°): −ρ·sin C = −16 mm/rad, here per degree.
    let n = r.error_names.len();
    let col = |name: &str| r.error_names.iter().position(|e| e == name).unwrap();
    let k = r.k_height.to_vec();
    assert!((k[n + col("E_X0B")] - 0.5).abs() < 1e-12);
    assert!((k[2 * n + col("E_A0B")] + 16f64.to_radians()).abs() < 1e-9);
}

#[wasm_bindgen_test]
fn the_cubic_height_map_has_the_documented_shape() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct MapOut {
        nx: usize,
        ny: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        x: js_sys::Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        height: js_sys::Float64Array,
        zone_average: Vec<f64>,
        min: f64,
        max: f64,
        scallop: f64,
    }
    let m: MapOut = read(fa::cubicHeightMap(jv(&json!({
        "setup": { "zoneSize": 4, "pick": 0.5 }, "nx": 13, "ny": 25,
    }))));
    assert_eq!(
        (m.nx, m.ny, m.height.length(), m.x.length()),
        (13, 25, 325, 13)
    );
    assert_eq!(m.zone_average.len(), 9);
    let x = m.x.to_vec();
    assert!((x[0] + 6.0).abs() < 1e-12 && (x[12] - 6.0).abs() < 1e-12);
    // No errors: the face lies between the passes' bottoms (0) and the scallop tops.
    let scallop = 3.0 - (9.0f64 - 0.25 * 0.25).sqrt();
    assert!((m.scallop - scallop).abs() < 1e-15);
    assert!(
        m.min >= -1e-12 && m.max <= scallop + 1e-12,
        "{} {}",
        m.min,
        m.max
    );
    // Left out, ny is four rows per pass step: 8 intervals per zone → 12·8 + 1 rows.
    let auto: MapOut = read(fa::cubicHeightMap(jv(&json!({
        "setup": { "zoneSize": 4, "pick": 0.5 }, "nx": 13,
    }))));
    assert_eq!(auto.ny, 97);
}

#[wasm_bindgen_test]
fn a_nonlinear_move_from_the_pole_is_eq_26() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct MoveOut {
        max: f64,
        u_at_max: f64,
        closed_form: Option<f64>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        delta: js_sys::Float64Array,
    }
    // Group I (Li's CBZ) from θm = 0 with Δθk = Δθm = 40°: the maximum is at u = 0.5 and equals
    // eq 26, L·sin²(20°).
    let r: MoveOut = read(fa::nonlinearMove(jv(&json!({
        "machine": preset(LI), "length": 200, "start": { "k": 10, "m": 0 },
        "end": { "k": 50, "m": 40 }, "samples": 5,
    }))));
    let expected = 200.0 * 20f64.to_radians().sin().powi(2);
    assert!((r.max - expected).abs() < 1e-9);
    assert!((r.u_at_max - 0.5).abs() < 1e-7);
    assert!((r.closed_form.unwrap() - expected).abs() < 1e-9);
    // δ(u) = L |sin(u Δm) sin((1-u) Δk)| at u = 0.25.
    let d = 40f64.to_radians();
    assert!(
        (r.delta.to_vec()[1] - 200.0 * ((0.25 * d).sin() * (0.75 * d).sin()).abs()).abs() < 1e-9
    );
    // A reversed K gives the same error (a mirror image of the motion).
    let mut rev = preset(LI);
    rev["rotary"]["kReversed"] = json!(true);
    let r2: MoveOut = read(fa::nonlinearMove(jv(&json!({
        "machine": rev, "length": 200, "start": { "k": 10, "m": 0 }, "end": { "k": 50, "m": 40 },
    }))));
    assert!((r2.max - expected).abs() < 1e-9);
    // Li's machine has its table at the rotary centre: no L of its own.
    let msg = error_message(fa::nonlinearMove(jv(&json!({ "machine": preset(LI) }))));
    assert!(
        msg.starts_with("length: this machine's table surface is at its rotary centre"),
        "{msg}"
    );
    // Fig 4: the maximum error does not depend on the start angle of K.
    let k = fa::nonlinearSweepK(jv(&json!({
        "machine": preset(LI), "length": 10, "thetaM": 10, "dK": 30, "dM": 15,
        "from": -180, "to": 180, "n": 7,
    })))
    .unwrap();
    let max: js_sys::Float64Array = js_sys::Reflect::get(&k, &"max".into()).unwrap().into();
    let v = max.to_vec();
    assert!(v.iter().all(|x| (x - v[0]).abs() < 1e-10));
}

#[derive(Deserialize)]
struct Point {
    u: f64,
    normal: Vec<f64>,
}

#[derive(Deserialize)]
struct PartOut {
    points: Vec<Point>,
}

#[wasm_bindgen_test]
fn s_shape_defects_of_single_errors_follow_appendix_a() {
    #[derive(Deserialize)]
    struct Pose {
        values: Vec<f64>,
        singular: bool,
    }
    #[derive(Deserialize)]
    struct Out {
        names: Vec<String>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        total: js_sys::Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        contributions: js_sys::Float64Array,
        axes: Vec<String>,
        poses: Vec<Pose>,
    }
    let pts: PartOut = read(fa::sshapePart(JsValue::UNDEFINED));
    let mut m = preset(CHANAL);
    m["errors"] = json!({ "E_X0B": 0.0294, "E_A0B": 3.2419e-4f64.to_degrees() });
    let o: Out = read(fa::sshapeDefects(jv(&json!({ "machine": m }))));
    assert_eq!(o.axes, ["Y", "C", "X", "Z", "B"]);
    let (total, contrib) = (o.total.to_vec(), o.contributions.to_vec());
    let n = o.names.len();
    let col = |name: &str| o.names.iter().position(|e| e == name).unwrap();
    let l0 = 499.889;
    for k in 0..100 {
        let (c, b) = (
            o.poses[k].values[1].to_radians(),
            o.poses[k].values[4].to_radians(),
        );
        let nn = &pts.points[k].normal;
        // Appendix A: E_X0B moves the tip by (cos C, −sin C, 0), E_A0B by L0·cos B·(sin C,
        // cos C, 0); the reference pose (B = C = 0) subtracts (1, 0, 0) and (0, L0, 0).
        let x0b = 0.0294 * ((c.cos() - 1.0) * nn[0] - c.sin() * nn[1]);
        let a0b = 3.2419e-4 * (l0 * b.cos() * (c.sin() * nn[0] + c.cos() * nn[1]) - l0 * nn[1]);
        assert!(
            (contrib[n * k + col("E_X0B")] - x0b).abs() < 1e-9,
            "E_X0B at {k}"
        );
        assert!(
            (contrib[n * k + col("E_A0B")] - a0b).abs() < 1e-9,
            "E_A0B at {k}"
        );
        assert!((total[k] - x0b - a0b).abs() < 1e-9);
    }
    // The tool is vertical (C kept) exactly on the plane middle of the S, u ∈ [6/13, 8/13].
    for (k, p) in o.poses.iter().enumerate() {
        let inside = pts.points[k].u > 6.0 / 13.0 && pts.points[k].u < 8.0 / 13.0;
        assert_eq!(p.singular, inside, "point {k}");
    }
}

#[wasm_bindgen_test]
fn identifying_the_sample_file_recovers_table_4() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Est {
        name: String,
        value: Option<f64>,
        std_error: Option<f64>,
    }
    #[derive(Deserialize)]
    struct Group {
        members: Vec<String>,
    }
    #[derive(Deserialize)]
    struct Out {
        estimates: Vec<Est>,
        groups: Vec<Group>,
        rank: usize,
    }
    let paper = [
        "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
    ];
    let o: Out = read(fa::sshapeIdentify(jv(&json!({
        "machine": preset(CHANAL), "csv": SAMPLE, "parameters": paper,
    }))));
    assert_eq!(o.rank, 9);
    let get = |n: &str| o.estimates.iter().find(|e| e.name == n).unwrap();
    let near = |n: &str, t: f64| {
        let e = get(n);
        assert!(
            (e.value.unwrap() - t).abs() < 4.0 * e.std_error.unwrap(),
            "{n}"
        );
    };
    near("E_X0B", 0.0294);
    near("E_A0B", 3.2419e-4f64.to_degrees());
    near("dR", -0.02);
    // Eq 14 as printed: the pairs E_A0Z/E_A0C and E_B0Z/E_B0C cannot be separated.
    let o: Out = read(fa::sshapeIdentify(jv(&json!({
        "machine": preset(CHANAL), "csv": SAMPLE, "parameters": paper,
        "model": { "reference": "axesZero" }, "radiusTerm": false,
    }))));
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
fn a_malformed_csv_names_its_line() {
    let with_csv =
        |csv: &str| fa::sshapeIdentify(jv(&json!({ "machine": preset(CHANAL), "csv": csv })));
    let mut lines: Vec<String> = SAMPLE.lines().map(String::from).collect();
    assert!(lines[11].starts_with("top,3,"));
    lines[11] = "top,3,0.0x2".into();
    let msg = error_message(with_csv(&lines.join("\n")));
    assert!(
        msg.starts_with("csv: line 12: ") && msg.contains("\"0.0x2\" is not a number"),
        "{msg}"
    );
    lines.remove(11);
    let msg = error_message(with_csv(&lines.join("\n")));
    assert!(
        msg.contains("1 of the 100 points are missing: top 3"),
        "{msg}"
    );
}

#[wasm_bindgen_test]
fn the_overcut_maxima_match_the_papers_with_its_sign_of_n() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct S {
        max_eq6_paper: f64,
        max_gouge: f64,
    }
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        surfaces: Vec<S>,
        b_paper_side: Vec<f64>,
    }
    let o: Out = read(fa::sshapeOvercut(jv(&json!({ "nu": 261, "nv": 4 }))));
    assert!((o.surfaces[0].max_eq6_paper / 0.0387 - 1.0).abs() < 0.08);
    assert!((o.b_paper_side[0] / 0.0125 - 1.0).abs() < 0.05);
    for s in &o.surfaces {
        assert!(s.max_gouge > 0.015 && s.max_gouge < 0.03);
    }
}
