//! Units and names at the JavaScript edge: every error of the table entered alone, in mm or
//! degrees, has the effect the engine computes natively with the value converted here (mm stay,
//! degrees × π/180), and every angle and per-angle sensitivity that comes out is in degrees. A
//! swapped name or an inverted degree/radian conversion anywhere between the page and the chain
//! fails one of these.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{jv, preset, read, CHANAL, LI, TRUNNION};
use fiveaxis::cubic::{self, CubicInput};
use fiveaxis::machine::errors::TABLE;
use fiveaxis::machine::Machine;
use fiveaxis::schema::{Inputs, Quantity};
use fiveaxis::sshape::study::{Design, SShapeModel, SShapeTool};
use fiveaxis_wasm as fa;
use serde::Deserialize;
use serde_json::{json, Value};
use wasm_bindgen_test::wasm_bindgen_test;

const DEG: f64 = std::f64::consts::PI / 180.0;

/// A machine that has the error's axis: A on the trunnion, the others on Li et al.'s B/C table.
fn machine_for(axis: char) -> Value {
    if axis == 'A' {
        preset(TRUNNION)
    } else {
        preset(LI)
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Zone {
    k: f64,
    m: f64,
    height: f64,
    slope_x: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct CubicOut {
    zones: Vec<Zone>,
    error_names: Vec<String>,
    error_units: Vec<String>,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    k_height: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    single: js_sys::Float64Array,
}

#[wasm_bindgen_test]
fn every_error_alone_in_the_cubic_test_is_the_native_engine_with_degrees_converted_here() {
    for def in TABLE {
        let api = 0.01; // mm, or degrees
        let engine = if def.quantity == Quantity::SmallAngle {
            api * DEG
        } else {
            api
        };
        let mut m = machine_for(def.axis);
        m["errors"] = json!({ def.name: api });
        let out: CubicOut = read(fa::cubicTest(jv(
            &json!({ "machine": m, "transform": false }),
        )));
        // Native: the same machine, the value set in engine units by this test.
        let mut native = Machine::from_value(&machine_for(def.axis), "machine").unwrap();
        native.errors.set(def.name, engine).unwrap();
        let input = CubicInput::read(&json!({ "transform": false })).unwrap();
        let a = cubic::analyze(&native, &input.setup, &input.options()).unwrap();
        let e = out
            .error_names
            .iter()
            .position(|n| n == def.name)
            .expect("a column");
        assert_eq!(
            out.error_units[e],
            if def.quantity == Quantity::SmallAngle {
                "deg"
            } else {
                "mm"
            }
        );
        let n = out.error_names.len();
        let k = out.k_height.to_vec();
        let single = out.single.to_vec();
        for (z, (zone, nz)) in out.zones.iter().zip(&a.zones).enumerate() {
            assert!(
                (zone.height - nz.exact.height).abs() < 1e-12,
                "{} zone {z}",
                def.name
            );
            assert!(
                (zone.slope_x - nz.exact.slope_x).abs() < 1e-12,
                "{} zone {z}",
                def.name
            );
            assert!(
                (single[z * n + e] - nz.exact.height).abs() < 1e-12,
                "{} alone",
                def.name
            );
            // Sensitivity per mm or per degree: the engine's per rad × π/180.
            let per = if def.quantity == Quantity::SmallAngle {
                DEG
            } else {
                1.0
            };
            let native_k = a.sensitivity[z][e].height * per;
            assert!(
                (k[z * n + e] - native_k).abs() < 1e-12 * (1.0 + native_k.abs()),
                "{} k",
                def.name
            );
            // And k·ε in the units at the edge is the first-order height.
            assert!(
                (k[z * n + e] * api - nz.linear.height).abs() < 1e-12,
                "{} k·ε",
                def.name
            );
            // Zone angles in degrees.
            assert!(
                (zone.k - nz.rotary[0] / DEG).abs() < 1e-9
                    && (zone.m - nz.rotary[1] / DEG).abs() < 1e-9
            );
        }
    }
}

#[wasm_bindgen_test]
fn every_error_alone_in_the_s_shape_is_the_native_engine_with_degrees_converted_here() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        names: Vec<String>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        total: js_sys::Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        sensitivity: js_sys::Float64Array,
        axes: Vec<String>,
        poses: Vec<Pose>,
    }
    #[derive(Deserialize)]
    struct Pose {
        values: Vec<f64>,
    }
    let mut machines_seen = 0;
    for def in TABLE {
        let api = 0.01;
        let engine = if def.quantity == Quantity::SmallAngle {
            api * DEG
        } else {
            api
        };
        // The S-shape on Chanal et al.'s machine, A's errors on the trunnion.
        let base = if def.axis == 'A' {
            preset(TRUNNION)
        } else {
            preset(CHANAL)
        };
        let mut m = base.clone();
        m["errors"] = json!({ def.name: api });
        let out: Out = read(fa::sshapeDefects(jv(&json!({ "machine": m }))));
        let mut native = Machine::from_value(&base, "machine").unwrap();
        native.errors.set(def.name, engine).unwrap();
        let tool = SShapeTool::from_value(&Value::Null, "tool").unwrap();
        let model = SShapeModel::from_value(&Value::Null, "model").unwrap();
        let d = Design::new(&native, &tool, &model).unwrap();
        let want = d.simulate(&native.errors, 0.0);
        let got = out.total.to_vec();
        for (p, (g, w)) in got.iter().zip(&want).enumerate() {
            assert!((g - w).abs() < 1e-12, "{} point {p}: {g} vs {w}", def.name);
        }
        let e = out
            .names
            .iter()
            .position(|n| n == def.name)
            .expect("column");
        let per = if def.quantity == Quantity::SmallAngle {
            DEG
        } else {
            1.0
        };
        let n = out.names.len();
        let s = out.sensitivity.to_vec();
        for p in 0..100 {
            assert!(
                (s[p * n + e] - d.rows[p][e] * per).abs() < 1e-12,
                "{} sensitivity",
                def.name
            );
        }
        // Poses: linear axes in mm, rotary ones in degrees.
        if machines_seen < 2 && (def.axis == 'A' || def.axis == 'C') {
            machines_seen += 1;
            for (pose, native_pose) in out.poses.iter().zip(&d.poses) {
                for (i, (v, q)) in pose.values.iter().zip(&native_pose.pose.q).enumerate() {
                    let rotary = matches!(out.axes[i].as_str(), "A" | "B" | "C");
                    let want = if rotary { q / DEG } else { *q };
                    assert!((v - want).abs() < 1e-9, "{} {}", out.axes[i], def.name);
                }
            }
        }
    }
}

#[wasm_bindgen_test]
fn identified_angles_come_out_in_degrees() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Est {
        name: String,
        unit: String,
        value: Option<f64>,
        std_error: Option<f64>,
        interval: Option<[f64; 2]>,
    }
    #[derive(Deserialize)]
    struct Out {
        estimates: Vec<Est>,
    }
    let params = [
        "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
    ];
    let o: Out = read(fa::sshapeIdentify(jv(&json!({
        "machine": preset(CHANAL), "csv": common::SAMPLE, "parameters": params,
    }))));
    let native = Machine::from_value(&preset(CHANAL), "machine").unwrap();
    let d = Design::new(
        &native,
        &SShapeTool::from_value(&Value::Null, "").unwrap(),
        &SShapeModel::from_value(&Value::Null, "").unwrap(),
    )
    .unwrap();
    let measured = fiveaxis::sshape::identify::parse_measurements(common::SAMPLE).unwrap();
    let names: Vec<String> = params.iter().map(|s| s.to_string()).collect();
    let f = d.identify(&measured, Some(&names), true, 0.01).unwrap();
    for (e, n) in o.estimates.iter().zip(&f.estimates) {
        assert_eq!(e.name, n.name);
        let angle = e.name != "E_X0B" && e.name != "dR";
        assert_eq!(e.unit, if angle { "deg" } else { "mm" });
        let per = if angle { 1.0 / DEG } else { 1.0 };
        assert!((e.value.unwrap() - n.value.unwrap() * per).abs() < 1e-12 * per);
        assert!((e.std_error.unwrap() - n.std_error.unwrap() * per).abs() < 1e-12 * per);
        // The 95 % interval in the same unit: value ± t(91 dof)·se, t = 1.9864 from a table.
        let [lo, hi] = e.interval.unwrap();
        let half = (hi - lo) / 2.0;
        assert!(
            (half / e.std_error.unwrap() - 1.9864).abs() < 1e-3,
            "{}",
            e.name
        );
        assert!(((hi + lo) / 2.0 - e.value.unwrap()).abs() < 1e-12 * per);
    }
}

#[wasm_bindgen_test]
fn axis_angles_in_and_out_are_degrees() {
    // toolVector: C = 90°, A = 30° on the trunnion is R_Z(90°)·R_X(30°)·e_z = (sin 30°, 0, cos 30°).
    let v: Vec<f64> = read(fa::toolVector(jv(
        &json!({ "machine": preset(TRUNNION), "k": 90, "m": 30 }),
    )));
    let want = [0.5, 0.0, 3f64.sqrt() / 2.0];
    for (g, w) in v.iter().zip(want) {
        assert!((g - w).abs() < 1e-12, "{v:?}");
    }
    // machineInverse gives the commands back in degrees.
    #[derive(Deserialize)]
    struct Pair {
        k: f64,
        m: f64,
    }
    #[derive(Deserialize)]
    struct Inv {
        solutions: Vec<Pair>,
        chosen: Option<usize>,
    }
    let r: Inv = read(fa::machineInverse(jv(&json!({
        "machine": preset(TRUNNION), "vector": want, "rule": "smallest-tilt",
    }))));
    let c = &r.solutions[r.chosen.expect("within the travel")];
    // A travels −120°..30°: of (C 90°, A 30°) and (C 270°, A −30°), equal tilts, A ≥ 0 first.
    assert!(
        (c.k - 90.0).abs() < 1e-9 && (c.m - 30.0).abs() < 1e-9,
        "{} {}",
        c.k,
        c.m
    );
    // The nonlinear study: degrees in (the move), degrees out (the sweep angle between V0, V1).
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Move {
        sweep_angle: f64,
        length: f64,
    }
    let mv: Move = read(fa::nonlinearMove(jv(&json!({
        "machine": preset(TRUNNION), "start": { "k": 0, "m": 0 }, "end": { "k": 0, "m": 20 },
    }))));
    assert!((mv.sweep_angle - 20.0).abs() < 1e-9, "{}", mv.sweep_angle);
    // L from the machine: the trunnion's table is 100 mm above its rotary centre.
    assert!((mv.length - 100.0).abs() < 1e-12);
    // The grid's increments are the commands asked for, in degrees.
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Grid {
        #[serde(with = "serde_wasm_bindgen::preserve")]
        d_k: js_sys::Float64Array,
    }
    let g: Grid = read(fa::nonlinearGrid(jv(&json!({
        "machine": preset(CHANAL), "length": 1, "thetaM": 0,
        "dK": { "from": -30, "to": 60 }, "dM": { "from": 0, "to": 10 }, "nx": 4, "ny": 2,
    }))));
    for (got, want) in g.d_k.to_vec().iter().zip([-30.0, 0.0, 30.0, 60.0]) {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}

#[wasm_bindgen_test]
fn alike_factors_are_per_unit_at_the_edge() {
    // Li et al.'s B/C table: αBY and αCB change the heights alike (README). In engine units the
    // factor between E_A0B and E_A0C is the engine's; per degree the two convert alike, so the
    // factor stays; between an angle and a length it would scale by π/180.
    #[derive(Deserialize)]
    struct Member {
        name: String,
        factor: f64,
    }
    #[derive(Deserialize)]
    struct Vis {
        alike: Vec<Vec<Member>>,
    }
    #[derive(Deserialize)]
    struct Out {
        visibility: Vis,
    }
    let o: Out = read(fa::cubicTest(jv(&json!({ "machine": preset(LI) }))));
    let native = Machine::from_value(&preset(LI), "machine").unwrap();
    let input = CubicInput::read(&json!({})).unwrap();
    let a = cubic::analyze(&native, &input.setup, &input.options()).unwrap();
    assert_eq!(o.visibility.alike.len(), a.visibility.alike.len());
    for (g, ng) in o.visibility.alike.iter().zip(&a.visibility.alike) {
        let q = |n: &str| TABLE.iter().find(|d| d.name == n).unwrap().quantity;
        for (m, (nn, nf)) in g.iter().zip(ng) {
            assert_eq!(&m.name, nn);
            let c = |n: &str| {
                if q(n) == Quantity::SmallAngle {
                    DEG
                } else {
                    1.0
                }
            };
            let want = nf * c(nn) / c(ng[0].0);
            assert!((m.factor - want).abs() < 1e-9 * want.abs().max(1.0), "{nn}");
        }
    }
    let has = |a: &str, b: &str| {
        o.visibility
            .alike
            .iter()
            .any(|g| g.iter().any(|m| m.name == a) && g.iter().any(|m| m.name == b))
    };
    assert!(has("E_A0B", "E_A0C"), "αBY and αCB alike");
}

#[wasm_bindgen_test]
fn volumetric_outputs_are_mm_and_degrees_and_tables_are_read_in_api_units() {
    #[derive(serde::Deserialize)]
    struct Worst {
        norm: f64,
        tilt: f64,
    }
    #[derive(serde::Deserialize)]
    struct Map {
        worst: Worst,
    }
    let machine = |motions: serde_json::Value| {
        let mut m = common::preset("C/A double turntable on an X table (Tan & Lim)");
        m["motions"] = motions;
        json!({ "machine": m, "region": { "steps": 3 } })
    };
    // A pitch of the spindle-side Y of 0.01° turns the tool axis by 0.01°: out in degrees.
    let r: Map = common::read(fa::volumetricMap(common::jv(&machine(
        json!({ "E_AY": 0.01 }),
    ))));
    assert!((r.worst.tilt - 0.01).abs() < 1e-12, "{}", r.worst.tilt);
    // A positioning error of Y of 2 µm entered in mm moves the tip 0.002 mm.
    let r: Map = common::read(fa::volumetricMap(common::jv(&machine(
        json!({ "E_YY": 0.002 }),
    ))));
    assert!(
        (r.worst.norm - 0.002).abs() < 1e-12 && r.worst.tilt.abs() < 1e-12,
        "{} {}",
        r.worst.norm,
        r.worst.tilt
    );
    // A polynomial in degrees per degree: E_CC = 1e-4 °/° · C at C = 90° is 0.009°, so the
    // paper's γ_C (= −E_CC) is −0.009 (degrees at the edge).
    #[derive(serde::Deserialize)]
    struct Symbol {
        symbol: String,
        value: f64,
        unit: String,
    }
    #[derive(serde::Deserialize)]
    struct Paper {
        symbols: Vec<Symbol>,
    }
    let mut input = machine(json!({ "E_CC": { "poly": [0, 1e-4] } }));
    input["k"] = json!(90);
    input.as_object_mut().unwrap().remove("region");
    let p: Paper = common::read(fa::volumetricPaper(common::jv(&input)));
    let g = p.symbols.iter().find(|s| s.symbol == "γ_C").unwrap();
    assert!(
        (g.value + 0.009).abs() < 1e-15 && g.unit == "deg",
        "{}",
        g.value
    );
    // CSV values in arc seconds come out in degrees: 36″ = 0.01°.
    #[derive(serde::Deserialize)]
    struct Table {
        position: Vec<f64>,
        value: Vec<f64>,
    }
    let t: Table = common::read(fa::volumetricReadTable(common::jv(&json!({
        "name": "E_CC", "text": "C (deg), E_CC (arcsec)\n0, 0\n90, 36\n"
    }))));
    assert_eq!(t.position, vec![0.0, 90.0]);
    assert!((t.value[1] - 0.01).abs() < 1e-15);
}
