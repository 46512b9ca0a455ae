//! Every export refuses what it does not know, with a message that starts with the path of the
//! offending input: an unknown key at the top and inside the machine, a misspelt error name, a
//! `NaN`, a value of the wrong kind. One test per export, as WebAssembly in headless Node.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{error_message, js, jv, preset, SAMPLE, TRUNNION};
use fiveaxis_wasm as fa;
use serde_json::{json, Value};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::wasm_bindgen_test;

/// `base` with `key` set to `value` (a nested path "a.b" walks into objects).
fn with(base: &Value, path: &str, value: Value) -> JsValue {
    let mut v = base.clone();
    let mut at = &mut v;
    let parts: Vec<&str> = path.split('.').collect();
    for p in &parts[..parts.len() - 1] {
        at = at
            .as_object_mut()
            .expect("an object")
            .entry(p.to_string())
            .or_insert_with(|| json!({}));
    }
    at.as_object_mut()
        .expect("an object")
        .insert(parts[parts.len() - 1].to_string(), value);
    jv(&v)
}

/// The checks every export with a machine gets: an unknown key at the top, in the machine's
/// geometry, a misspelt error and an error of an axis the machine lacks.
fn refuses<F: Fn(JsValue) -> Result<JsValue, wasm_bindgen::JsError>>(f: F, base: Value) {
    f(jv(&base)).expect("the base input is valid");
    let m = error_message(f(with(&base, "colour", json!(1))));
    assert!(
        m.starts_with("colour: unknown input; expected one of"),
        "{m}"
    );
    if base.get("machine").is_some() {
        let m = error_message(f(with(&base, "machine.geometry.tableHeigth", json!(5))));
        assert!(
            m.starts_with("machine.geometry.tableHeigth: unknown input"),
            "{m}"
        );
        assert!(m.contains("Did you mean \"tableHeight\"?"), "{m}");
        let m = error_message(f(with(&base, "machine.errors", json!({ "E_A0b": 0.01 }))));
        assert!(
            m.starts_with("machine.errors.E_A0b: unknown error name"),
            "{m}"
        );
        assert!(m.contains("Did you mean E_A0B?"), "{m}");
        let m = error_message(f(with(&base, "machine.errors", json!({ "E_Y0B": 0.01 }))));
        assert!(
            m.starts_with("machine.errors.E_Y0B: this machine has no B axis"),
            "{m}"
        );
        let m = error_message(f(with(&base, "machine.refrence", json!("x"))));
        assert!(m.starts_with("machine.refrence: unknown input"), "{m}");
    }
}

fn trunnion() -> Value {
    preset(TRUNNION)
}

#[wasm_bindgen_test]
fn cubic_test_refuses_unknown_inputs() {
    refuses(fa::cubicTest, json!({ "machine": trunnion() }));
    let m = error_message(fa::cubicTest(with(&json!({}), "setup.zonesize", json!(16))));
    assert!(
        m.starts_with("setup.zonesize: unknown input") && m.contains("\"zoneSize\""),
        "{m}"
    );
    // A paper's symbol is refused with its ISO name and sign.
    let m = error_message(fa::cubicTest(js(r#"{"machine":{"errors":{"dxBY":0.01}}}"#)));
    assert!(
        m.starts_with("machine.errors.dxBY: dxBY is the symbol δxBY")
            && m.contains("E_X0B = −δxBY"),
        "{m}"
    );
    // NaN cannot be written in JSON: set it directly.
    let obj = js(r#"{"setup":{"pick":0.1}}"#);
    let setup = js_sys::Reflect::get(&obj, &"setup".into()).expect("setup");
    js_sys::Reflect::set(&setup, &"pick".into(), &JsValue::from_f64(f64::NAN)).expect("set");
    assert_eq!(
        error_message(fa::cubicTest(obj)),
        "setup.pick: must be a finite number, got NaN"
    );
    assert!(error_message(fa::cubicTest(js(r#"{"transform":"yes"}"#)))
        .starts_with("transform: expected true or false"));
}

#[wasm_bindgen_test]
fn cubic_height_map_refuses_unknown_inputs() {
    refuses(
        fa::cubicHeightMap,
        json!({ "machine": trunnion(), "nx": 8, "ny": 8 }),
    );
    let m = error_message(fa::cubicHeightMap(js(r#"{"nx":8,"nz":8}"#)));
    assert!(
        m.starts_with("nz: unknown input") && m.contains("\"ny\""),
        "{m}"
    );
    assert!(error_message(fa::cubicHeightMap(js(r#"{"ny":8}"#))).starts_with("nx: is required"));
}

#[wasm_bindgen_test]
fn nonlinear_move_refuses_unknown_inputs() {
    refuses(
        fa::nonlinearMove,
        json!({ "machine": trunnion(), "start": { "k": 0, "m": 10 } }),
    );
    let m = error_message(fa::nonlinearMove(js(r#"{"start":{"k":0,"n":1}}"#)));
    assert!(m.starts_with("start.n: unknown input"), "{m}");
    assert!(error_message(fa::nonlinearMove(js(r#"{"lenght":5}"#)))
        .contains("Did you mean \"length\"?"));
    assert!(error_message(fa::nonlinearMove(js(r#"{"length":-5}"#)))
        .starts_with("length: must be greater than 0 mm"));
    assert!(
        error_message(fa::nonlinearMove(js(r#"{"start":{"k":"ten"}}"#)))
            .starts_with("start.k: expected a number of degrees")
    );
    assert!(error_message(fa::nonlinearMove(JsValue::from_f64(3.0)))
        .starts_with("input: expected an object"));
}

#[wasm_bindgen_test]
fn nonlinear_sweep_k_refuses_unknown_inputs() {
    refuses(
        fa::nonlinearSweepK,
        json!({ "machine": trunnion(), "thetaM": 10, "dK": 30, "dM": 15, "from": -180, "to": 180, "n": 5 }),
    );
}

#[wasm_bindgen_test]
fn nonlinear_sweep_m_refuses_unknown_inputs() {
    let base = json!({ "machine": trunnion(), "dM": 30, "ratios": [0.5, 2], "from": -90, "to": 90, "n": 5 });
    refuses(fa::nonlinearSweepM, base.clone());
    let m = error_message(fa::nonlinearSweepM(with(&base, "ratios", json!([]))));
    assert!(m.starts_with("ratios: expected 1 to 8 values"), "{m}");
    let m = error_message(fa::nonlinearSweepM(with(&base, "ratios", json!([1, 0]))));
    assert!(m.starts_with("ratios[1]: must not be zero"), "{m}");
}

#[wasm_bindgen_test]
fn nonlinear_grid_refuses_unknown_inputs() {
    let base = json!({ "machine": trunnion(), "thetaM": 0, "dK": { "from": 0, "to": 90 }, "dM": { "from": 0, "to": 60 }, "nx": 4, "ny": 3 });
    refuses(fa::nonlinearGrid, base.clone());
    let m = error_message(fa::nonlinearGrid(with(&base, "dK.form", json!(0))));
    assert!(m.starts_with("dK.form: unknown input"), "{m}");
}

#[wasm_bindgen_test]
fn nonlinear_compare_types_refuses_unknown_inputs() {
    refuses(
        fa::nonlinearCompareTypes,
        json!({ "machine": trunnion(), "length": 1 }),
    );
}

/// A three-point path: `[x, y, z, i, j, k]` per point.
fn path() -> JsValue {
    JsValue::from(js_sys::Float64Array::from(
        &[
            0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 10.0, 0.0, 0.0, 0.1, 0.0, 1.0, 20.0, 0.0, 0.0, 0.2, 0.1,
            1.0,
        ][..],
    ))
}

#[wasm_bindgen_test]
fn toolpath_exports_refuse_unknown_inputs_and_bad_points() {
    type Export = fn(JsValue, JsValue) -> Result<JsValue, wasm_bindgen::JsError>;
    let exports: [Export; 3] = [
        fa::toolpath_analyse,
        |v, p| fa::toolpath_compare(v, p, JsValue::UNDEFINED),
        fa::toolpath_refine,
    ];
    for f in exports {
        refuses(
            |v| f(v, path()),
            json!({ "machine": trunnion(), "length": 100, "tolerance": 0.01 }),
        );
        let m = error_message(f(jv(&json!({ "tolerance": -1 })), path()));
        assert!(m.starts_with("tolerance: must be greater than 0"), "{m}");
        let five = JsValue::from(js_sys::Float64Array::from(&[0.0; 5][..]));
        let m = error_message(f(jv(&json!({})), five));
        assert!(
            m.starts_with("points: length must be a multiple of 6"),
            "{m}"
        );
        let zero = JsValue::from(js_sys::Float64Array::from(
            &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0][..],
        ));
        let m = error_message(f(jv(&json!({})), zero));
        assert!(m.starts_with("points[1]: the tool axis"), "{m}");
        let m = error_message(f(jv(&json!({})), jv(&json!([1, 2, 3]))));
        assert!(m.starts_with("points: expected a Float64Array"), "{m}");
    }
}

#[wasm_bindgen_test]
fn toolpath_compare_refuses_unknown_types() {
    let input = jv(&json!({}));
    let m = error_message(fa::toolpath_compare(
        input.clone(),
        path(),
        jv(&json!(["CAZ", "CAW"])),
    ));
    assert!(m.starts_with("types[1]: unknown rotary-axis type"), "{m}");
    let m = error_message(fa::toolpath_compare(
        input.clone(),
        path(),
        jv(&json!("CAZ")),
    ));
    assert!(m.starts_with("types: expected a list"), "{m}");
    let rows = fa::toolpath_compare(input, path(), jv(&json!(["ABZ", "CAZ"]))).unwrap();
    assert_eq!(js_sys::Array::from(&rows).length(), 2);
}

#[wasm_bindgen_test]
fn nonlinear_max_errors_refuses_wrong_arguments() {
    let moves = |v: &[f64]| JsValue::from(js_sys::Float64Array::from(v));
    let err = |r: Result<js_sys::Float64Array, wasm_bindgen::JsError>| {
        error_message(r.map(JsValue::from))
    };
    assert!(err(fa::nonlinear_max_errors(
        "CAZ".into(),
        2.0.into(),
        moves(&[0.0, 1.0, 2.0])
    ))
    .starts_with("moves: length must be a multiple of 4"));
    assert!(err(fa::nonlinear_max_errors(
        "CAX".into(),
        2.0.into(),
        moves(&[])
    ))
    .starts_with("type: unknown rotary-axis type"));
    assert!(err(fa::nonlinear_max_errors(
        JsValue::from_f64(1.0),
        2.0.into(),
        moves(&[])
    ))
    .starts_with("type:"));
    assert!(err(fa::nonlinear_max_errors(
        "CAZ".into(),
        "2".into(),
        moves(&[])
    ))
    .starts_with("length:"));
    assert!(err(fa::nonlinear_max_errors(
        "CAZ".into(),
        2.0.into(),
        js_sys::Array::new().into()
    ))
    .starts_with("moves:"));
    assert!(err(fa::nonlinear_max_errors(
        "CAZ".into(),
        2.0.into(),
        moves(&[0.0, 0.0, 1e9, 0.0])
    ))
    .starts_with("moves[2]:"));
}

#[wasm_bindgen_test]
fn sshape_part_refuses_unknown_inputs() {
    refuses(fa::sshapePart, json!({ "nu": 10 }));
    fa::sshapePart(JsValue::UNDEFINED).expect("no input: the defaults");
    assert!(error_message(fa::sshapePart(js(r#"{"nu":1}"#)))
        .starts_with("nu: must be a whole number between 2 and 2001"));
}

#[wasm_bindgen_test]
fn sshape_overcut_refuses_unknown_inputs() {
    refuses(
        fa::sshapeOvercut,
        json!({ "tool": { "rTool": 10 }, "nu": 14, "nv": 2 }),
    );
    let m = error_message(fa::sshapeOvercut(js(r#"{"tool":{"rtool":10}}"#)));
    assert!(
        m.starts_with("tool.rtool: unknown input") && m.contains("\"rTool\""),
        "{m}"
    );
    assert!(
        error_message(fa::sshapeOvercut(js(r#"{"tool":{"lTool":30}}"#)))
            .starts_with("tool.lTool: must be greater than 30 mm")
    );
}

#[wasm_bindgen_test]
fn sshape_defects_refuses_unknown_inputs() {
    refuses(
        fa::sshapeDefects,
        json!({ "machine": trunnion(), "dR": 0.001 }),
    );
    let m = error_message(fa::sshapeDefects(js(
        r#"{"model":{"refrence":"axesZero"}}"#,
    )));
    assert!(
        m.starts_with("model.refrence: unknown input") && m.contains("\"reference\""),
        "{m}"
    );
    assert!(error_message(fa::sshapeDefects(js(
        r#"{"model":{"reference":"axeszero"}}"#
    )))
    .contains("Did you mean \"axesZero\"?"));
    assert!(error_message(fa::sshapeDefects(js(r#"{"dR":2}"#)))
        .starts_with("dR: must be between -1 mm and 1 mm"));
}

#[wasm_bindgen_test]
fn sshape_identify_refuses_unknown_inputs() {
    let base = json!({ "machine": trunnion(), "csv": SAMPLE });
    refuses(fa::sshapeIdentify, base.clone());
    let m = error_message(fa::sshapeIdentify(with(
        &base,
        "parameters",
        json!(["E_X0A", "E_X0a"]),
    )));
    assert!(
        m.starts_with("parameters[1]: unknown error name") && m.contains("Did you mean E_X0A?"),
        "{m}"
    );
    let m = error_message(fa::sshapeIdentify(with(
        &base,
        "parameters",
        json!(["E_X0B"]),
    )));
    assert!(
        m.starts_with("parameters[0]: E_X0B is not an error of this machine"),
        "{m}"
    );
    assert!(error_message(fa::sshapeIdentify(js(r#"{}"#))).starts_with("csv: is required"));
}

#[wasm_bindgen_test]
fn machine_schematic_refuses_unknown_inputs() {
    refuses(
        fa::machineSchematic,
        json!({ "machine": trunnion(), "m": 30 }),
    );
}

#[wasm_bindgen_test]
fn machine_inverse_refuses_unknown_inputs() {
    refuses(
        fa::machineInverse,
        json!({ "machine": trunnion(), "vector": [0, 0.5, 0.8] }),
    );
    assert!(error_message(fa::machineInverse(js(r#"{"vector":[0,1]}"#)))
        .starts_with("vector: expected 3 values, got 2"));
    assert!(
        error_message(fa::machineInverse(js(r#"{"vector":[0,0,0]}"#)))
            .starts_with("vector: the tool vector must be finite and non-zero")
    );
}

#[wasm_bindgen_test]
fn tool_vector_refuses_unknown_inputs() {
    refuses(
        fa::toolVector,
        json!({ "machine": trunnion(), "k": 10, "m": 20 }),
    );
    assert!(error_message(fa::toolVector(js(r#"{"k":10}"#))).starts_with("m: is required"));
}

#[wasm_bindgen_test]
fn the_schema_lists_every_exports_inputs() {
    #[derive(serde::Deserialize)]
    struct Field {
        path: String,
        unit: String,
    }
    #[derive(serde::Deserialize)]
    struct Schema {
        machine: Vec<Field>,
        errors: Vec<serde_json::Value>,
        exports: std::collections::BTreeMap<String, Vec<Field>>,
    }
    let s: Schema = common::read(fa::schema());
    assert_eq!(s.errors.len(), 21);
    assert!(s
        .machine
        .iter()
        .any(|f| f.path == "machine.geometry.pivotLength" && f.unit == "mm"));
    assert!(s
        .machine
        .iter()
        .any(|f| f.path == "machine.rotary.kFrom" && f.unit == "deg"));
    let cubic = &s.exports["cubicTest"];
    assert!(cubic.iter().any(|f| f.path == "setup.zoneSize"));
    assert!(cubic.iter().any(|f| f.path == "machine.errors"));
    let toolpath = &s.exports["toolpathAnalyse"];
    assert!(toolpath
        .iter()
        .any(|f| f.path == "tolerance" && f.unit == "mm"));
    assert!(s.exports["toolpathParse"]
        .iter()
        .any(|f| f.path == "format"));
    assert!(s.exports["reversalFit"]
        .iter()
        .any(|f| f.path == "c.frictionSlope"));
    assert!(s.exports["volumetricMap"]
        .iter()
        .any(|f| f.path == "region.steps"));
    assert!(s.exports["cubicIdentify"]
        .iter()
        .any(|f| f.path == "decision.noise" && f.unit == "mm"));
    assert!(s.exports["cubicDesign"]
        .iter()
        .any(|f| f.path == "maxTilt" && f.unit == "deg"));
    assert!(s.exports["reversalTrace"].iter().any(|f| f.path == "csv"));
    assert!(s.exports["ballbarRotaryIdentify"]
        .iter()
        .any(|f| f.path == "tests"));
    assert_eq!(s.exports.len(), 38);
}

fn tan_lim() -> Value {
    preset("C/A double turntable on an X table (Tan & Lim)")
}

#[wasm_bindgen_test]
fn volumetric_exports_refuse_unknown_inputs_and_error_motions() {
    let base = json!({ "machine": tan_lim(), "region": { "steps": 3 } });
    refuses(fa::volumetricMap, base.clone());
    let m = error_message(fa::volumetricMap(with(&base, "region.plane", json!("XW"))));
    assert!(m.starts_with("region.plane:"), "{m}");
    let m = error_message(fa::volumetricMap(with(&base, "region.stepz", json!(3))));
    assert!(m.starts_with("region.stepz: unknown input"), "{m}");
    let m = error_message(fa::volumetricMap(with(
        &base,
        "machine.motions",
        json!({ "E_XXX": 0.001 }),
    )));
    assert!(
        m.starts_with("machine.motions.E_XXX: unknown error motion")
            && m.contains("Did you mean E_XX?"),
        "{m}"
    );
    let m = error_message(fa::volumetricMap(with(
        &base,
        "machine.motions",
        json!({ "E_XB": 0.001 }),
    )));
    assert!(
        m.starts_with("machine.motions.E_XB: this machine has no B axis"),
        "{m}"
    );
    let m = error_message(fa::volumetricMap(with(
        &base,
        "machine.motions",
        json!({ "E_XX": { "poly": [0, 1], "extra": 1 } }),
    )));
    assert!(m.starts_with("machine.motions.E_XX.extra:"), "{m}");
    refuses(
        fa::volumetricPaper,
        json!({ "machine": tan_lim(), "x": 10 }),
    );
    let m = error_message(fa::volumetricPaper(jv(&json!({ "machine": {}, "x": 10 }))));
    assert!(m.starts_with("machine: Tan & Lim's loop"), "{m}");
    let ok = json!({ "name": "E_XX", "text": "X (mm), E_XX (um)\n0, 0\n10, 1\n" });
    fa::volumetricReadTable(jv(&ok)).expect("valid");
    let m = error_message(fa::volumetricReadTable(with(&ok, "nmae", json!("E_XX"))));
    assert!(m.starts_with("nmae: unknown input"), "{m}");
    let m = error_message(fa::volumetricReadTable(with(&ok, "name", json!("E_X0B"))));
    assert!(m.starts_with("name: E_X0B is a location error"), "{m}");
    let m = error_message(fa::volumetricReadTable(with(
        &ok,
        "text",
        json!("X (mm), E_XX (um)\n0, 0\n1, x\n"),
    )));
    assert!(m.starts_with("csv: line 3:"), "{m}");
}

#[wasm_bindgen_test]
fn cubic_identify_and_design_refuse_unknown_inputs() {
    let csv = "zone,height_um\nI,0\nII-1,-5\nII-2,-1\nII-3,-3\nII-4,-2\nIII-1,-5\nIII-2,-1\nIII-3,-2\nIII-4,-1\n";
    let base =
        json!({ "machine": trunnion(), "csv": csv, "parameters": ["E_Y0A", "E_Z0A", "E_B0Z"] });
    refuses(fa::cubicIdentify, base.clone());
    let m = error_message(fa::cubicIdentify(with(
        &base,
        "decision.nois",
        json!(0.001),
    )));
    assert!(
        m.starts_with("decision.nois: unknown input") && m.contains("Did you mean \"noise\"?"),
        "{m}"
    );
    let m = error_message(fa::cubicIdentify(with(&base, "decision.alpha", json!(0.9))));
    assert!(m.starts_with("decision.alpha: must be between"), "{m}");
    let m = error_message(fa::cubicIdentify(with(
        &base,
        "csv",
        json!("zone,height_um\nII-9,1\n"),
    )));
    assert!(m.starts_with("csv: line 2: zone \"II-9\""), "{m}");
    let m = error_message(fa::cubicIdentify(with(
        &base,
        "parameters",
        json!(["E_X0B"]),
    )));
    assert!(m.starts_with("parameters[0]: "), "{m}");
    let design = json!({ "machine": trunnion(), "grid": 2, "maxTilt": 20 });
    refuses(fa::cubicDesign, design.clone());
    let m = error_message(fa::cubicDesign(with(&design, "grid", json!(9))));
    assert!(m.starts_with("grid: "), "{m}");
    let m = error_message(fa::cubicDesign(with(&design, "maxTilt", json!("x"))));
    assert!(m.starts_with("maxTilt: "), "{m}");
}

#[wasm_bindgen_test]
fn a_toolpath_path_object_is_checked_key_by_key() {
    let points = || {
        js_sys::Float64Array::from(
            &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 10.0, 0.0, 0.0, 0.0, 0.0, 1.0][..],
        )
    };
    let obj = |extra: &[(&str, JsValue)]| {
        let o = js_sys::Object::new();
        js_sys::Reflect::set(&o, &"points".into(), &points()).unwrap();
        for (k, v) in extra {
            js_sys::Reflect::set(&o, &(*k).into(), v).unwrap();
        }
        JsValue::from(o)
    };
    let input = || jv(&json!({ "machine": { "type": "CAZ" } }));
    let m = error_message(fa::toolpath_analyse(
        input(),
        obj(&[("motion", jv(&json!([0, 1])))]),
    ));
    assert!(m.starts_with("path.motion: unknown key"), "{m}");
    let m = error_message(fa::toolpath_analyse(
        input(),
        obj(&[("motions", jv(&json!([0, 7])))]),
    ));
    assert!(
        m.starts_with("motions[1]: expected 0 (rapid), 1 (feed) or 2 (arc), got 7"),
        "{m}"
    );
    let m = error_message(fa::toolpath_analyse(
        input(),
        obj(&[("motions", jv(&json!([0])))]),
    ));
    assert!(
        m.starts_with("motions: expected one motion per point (2), got 1"),
        "{m}"
    );
    let m = error_message(fa::toolpath_analyse(
        input(),
        obj(&[("angles", jv(&json!([0, 0, 0, 0])))]),
    ));
    assert!(m.starts_with("readFor: expected the type"), "{m}");
    let m = error_message(fa::toolpath_analyse(
        input(),
        obj(&[("angles", jv(&json!([0, 0, 0]))), ("readFor", "CAZ".into())]),
    ));
    assert!(
        m.starts_with("angles: expected [K, M] per point, got 3 numbers"),
        "{m}"
    );
    // A rapid first, then a feed, with the program's commands: the machine's row follows them.
    let ok = fa::toolpath_analyse(
        input(),
        obj(&[
            ("motions", jv(&json!([0, 0]))),
            ("angles", jv(&json!([0, 0, 0, 0]))),
            ("readFor", "CAZ".into()),
        ]),
    )
    .unwrap();
    let summary = js_sys::Reflect::get(&ok, &"summary".into()).unwrap();
    assert_eq!(
        js_sys::Reflect::get(&summary, &"commanded".into())
            .unwrap()
            .as_bool(),
        Some(true)
    );
    assert_eq!(
        js_sys::Reflect::get(&summary, &"segments".into())
            .unwrap()
            .as_f64(),
        Some(0.0)
    );
}
