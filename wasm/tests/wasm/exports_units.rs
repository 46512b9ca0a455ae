//! Units at the JavaScript edge checked by a second method, not against the engine's own
//! output: the S-shape export's total, contributions and per-degree sensitivities of every
//! error of Chanal et al.'s machine entered alone (in mm or degrees) against the exact
//! kinematic chain at the export's own poses (degrees turned into radians here); the nonlinear
//! move's sweep angle and approximation shortfall by their definitions.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{jv, preset, read, CHANAL};
use fiveaxis::chain::Setup;
use fiveaxis::machine::Machine;
use fiveaxis::schema::{Inputs, Quantity};
use fiveaxis::sshape::part::Part;
use fiveaxis_wasm as fa;
use nalgebra::{Matrix3, Vector3};
use serde::Deserialize;
use serde_json::json;
use wasm_bindgen_test::wasm_bindgen_test;

const DEG: f64 = std::f64::consts::PI / 180.0;

#[derive(Deserialize)]
struct Pose {
    values: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Defects {
    names: Vec<String>,
    units: Vec<String>,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    total: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    contributions: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    sensitivity: js_sys::Float64Array,
    axes: Vec<String>,
    poses: Vec<Pose>,
}

#[wasm_bindgen_test]
fn every_error_alone_in_the_s_shape_export_is_the_exact_chain_in_api_units() {
    let base = preset(CHANAL);
    let points = Part::standard_points().unwrap();
    let machine = Machine::from_value(&base, "machine").unwrap();
    let mut seen = Vec::new();
    for def in machine.error_defs() {
        let angle = def.quantity == Quantity::SmallAngle;
        // 0.0002° (3.5 µrad) or 0.2 µm: the chain's second order, 1 m·(3.5e-6)² = 1.2e-8 mm,
        // stays below the tolerance.
        let api = 2e-4;
        let engine = if angle { api * DEG } else { api };
        let mut m = base.clone();
        m["errors"] = json!({ def.name: api });
        let out: Defects = read(fa::sshapeDefects(jv(&json!({ "machine": m }))));
        let j = out.names.iter().position(|n| n == def.name).unwrap();
        assert_eq!(out.units[j], if angle { "deg" } else { "mm" });
        // The exact chain with the value set here in engine units.
        let mut with = machine.clone();
        with.errors.set(def.name, engine).unwrap();
        let built = with.build().unwrap();
        let nominal = built.nominal();
        let [u, v, n] = with.face_frame();
        let back = Matrix3::from_columns(&[u, v, n]).transpose();
        let shift = |q: &[f64]| {
            let a = built.chain.tool_pose(q, true, &Setup::None).unwrap();
            let b = nominal.tool_pose(q, false, &Setup::None).unwrap();
            back * (a.tip - b.tip)
        };
        let zero = vec![0.0; nominal.len()];
        let q_ref = nominal.solve_linear(&Vector3::zeros(), &zero).unwrap();
        let reference = shift(&q_ref);
        let cols = out.names.len();
        let (total, contributions, sensitivity) = (
            out.total.to_vec(),
            out.contributions.to_vec(),
            out.sensitivity.to_vec(),
        );
        let mut largest: f64 = 0.0;
        for (k, (pose, p)) in out.poses.iter().zip(points).enumerate() {
            // The export's poses: rotary axes in degrees, linear ones in mm.
            let q: Vec<f64> = pose
                .values
                .iter()
                .zip(&out.axes)
                .map(|(x, a)| {
                    if matches!(a.as_str(), "A" | "B" | "C") {
                        x * DEG
                    } else {
                        *x
                    }
                })
                .collect();
            let exact = (shift(&q) - reference).dot(&Vector3::from(p.normal));
            largest = largest.max(exact.abs());
            let what = format!("{} at point {k}", def.name);
            assert!(
                (total[k] - exact).abs() < 1e-8,
                "{what}: {} vs {exact}",
                total[k]
            );
            assert!((contributions[k * cols + j] - exact).abs() < 1e-8, "{what}");
            // Per degree (per mm): the exact effect divided by the value entered.
            assert!(
                (sensitivity[k * cols + j] - exact / api).abs() < 1e-8 / api,
                "{what}: sensitivity {} vs {}",
                sensitivity[k * cols + j],
                exact / api
            );
        }
        if largest > 1e-6 {
            seen.push(def.name);
        }
    }
    // No vacuous check: the eight errors Chanal et al. identify move the part (others, such as
    // E_Z0B, shift every pose alike and vanish with the reference).
    for name in [
        "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
    ] {
        assert!(seen.contains(&name), "{name} has an effect: {seen:?}");
    }
}

#[wasm_bindgen_test]
fn the_nonlinear_move_gives_its_sweep_angle_in_degrees_and_the_shortfall_by_its_definition() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Move {
        sweep_angle: f64,
        max: f64,
        approx: Option<f64>,
        approx_shortfall: Option<f64>,
    }
    let mv: Move = read(fa::nonlinearMove(jv(&json!({
        "machine": { "type": "CAZ" }, "length": 100,
        "start": { "k": 10, "m": 20 }, "end": { "k": 50, "m": 60 },
    }))));
    // CAZ: V = R_Z(k)·R_X(m)·e_z = (sin m·sin k, −sin m·cos k, cos m).
    let v = |k: f64, m: f64| {
        let (k, m) = (k * DEG, m * DEG);
        Vector3::new(m.sin() * k.sin(), -m.sin() * k.cos(), m.cos())
    };
    let want = v(10.0, 20.0).dot(&v(50.0, 60.0)).acos() / DEG;
    assert!(
        (mv.sweep_angle - want).abs() < 1e-9,
        "{} vs {want}",
        mv.sweep_angle
    );
    let a = mv.approx.unwrap();
    let s = mv.approx_shortfall.unwrap();
    assert!(a <= mv.max && s > 0.0, "{a} {} {s}", mv.max);
    assert!((s - (mv.max - a) / mv.max).abs() < 1e-12, "{s}");
}
