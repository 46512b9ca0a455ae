//! Identification from a machined cubic test piece (`fiveaxis::cubic::identify`): measurements
//! simulated with the exact chain at each zone's pose (`exact_planes`, not the first-order
//! sensitivities the fit uses), the paper's stated facts about what its heights cannot see, an
//! independent rank count by finite differences of the exact heights, the designed test
//! recovering every error it can see, its false-call rate, and the file's messages.
#![allow(clippy::unwrap_used)]
use crate::common;

use common::li::{self, CubicSetup, GeometricErrors};
use common::{machine_preset, Rng};
use fiveaxis::cubic::design::{design, CubicDesignInput};
use fiveaxis::cubic::identify::{
    exact_planes, identify_zones, parse_measurements, system, CubicIdentifyInput,
};
use fiveaxis::cubic::{CubicInput, Options, ZonePlane, ZoneSpec, ZONES};
use fiveaxis::identify::{self, Param, Verdict};
use fiveaxis::machine::errors::ErrorValues;
use fiveaxis::schema::read_split;
use nalgebra::DMatrix;
use serde_json::{json, Value};

/// Li et al.'s eight errors, ISO names (E = −ε of the paper).
const PAPER8: [&str; 8] = [
    "E_X0B", "E_Y0B", "E_Z0B", "E_A0B", "E_B0B", "E_C0B", "E_A0C", "E_X0C",
];

fn li_input(extra: Value) -> (CubicInput, CubicIdentifyInput) {
    let mut m = machine_preset("B/C tilting table, vertical spindle (Li et al. 2021)");
    m["errors"] = json!({});
    let mut v = json!({ "machine": m, "csv": "" });
    for (k, x) in extra.as_object().unwrap() {
        v[k] = x.clone();
    }
    read_split(&v, "").unwrap()
}

fn paper_specs(input: &CubicInput) -> Vec<(ZoneSpec, f64)> {
    ZONES
        .iter()
        .map(|d| {
            (
                ZoneSpec::paper(d, input.setup.zone_size),
                input.setup.workpiece_x,
            )
        })
        .collect()
}

fn planes(input: &CubicInput, errors: ErrorValues, specs: &[(ZoneSpec, f64)]) -> Vec<ZonePlane> {
    let mut m = input.machine.clone();
    m.errors = errors;
    exact_planes(&m, &input.setup, &input.options(), specs).unwrap()
}

/// A measurement file of the paper's zones (heights in µm, slopes when `slopes`).
fn paper_csv(p: &[ZonePlane], slopes: bool) -> String {
    let mut s = String::from(if slopes {
        "zone,height_um,slope_x,slope_y\n"
    } else {
        "zone,height_um\n"
    });
    for (d, z) in ZONES.iter().zip(p) {
        if slopes {
            s.push_str(&format!(
                "{},{:.6},{:.9},{:.9}\n",
                d.name,
                z.height * 1e3,
                z.slope_x,
                z.slope_y
            ));
        } else {
            s.push_str(&format!("{},{:.6}\n", d.name, z.height * 1e3));
        }
    }
    s
}

/// Rank of the exact heights' (and slopes') finite differences: each error alone at a small
/// value, the exact planes minus the error-free ones, relative threshold 1e-6. Independent of
/// the chain's analytic derivatives and of the fit.
fn finite_difference_rank(input: &CubicInput, names: &[&str], slopes: bool) -> usize {
    let specs = paper_specs(input);
    let base = planes(input, ErrorValues::none(), &specs);
    let lever = input.setup.zone_size / 2.0;
    let cols: Vec<Vec<f64>> = names
        .iter()
        .map(|n| {
            let h = if fiveaxis::machine::errors::find(n).unwrap().component >= 3 {
                1e-7
            } else {
                1e-5
            };
            let p = planes(input, ErrorValues::single(n, h).unwrap(), &specs);
            p.iter()
                .zip(&base)
                .flat_map(|(a, b)| {
                    let mut v = vec![(a.height - b.height) / h];
                    if slopes {
                        v.push((a.slope_x - b.slope_x) * lever / h);
                        v.push((a.slope_y - b.slope_y) * lever / h);
                    }
                    v
                })
                .collect()
        })
        .collect();
    // A column below 1e-6 (mm per mm, mm per rad) is no effect: rounding of the exact planes.
    let norm = |c: &Vec<f64>| c.iter().map(|x| x * x).sum::<f64>().sqrt();
    let m = DMatrix::from_fn(cols[0].len(), cols.len(), |r, c| {
        let n = norm(&cols[c]);
        if n > 1e-6 {
            cols[c][r] / n
        } else {
            0.0
        }
    });
    let sv = m.svd(false, false).singular_values;
    let top = sv.max();
    sv.iter().filter(|s| **s > 1e-6 * top).count()
}

#[test]
fn from_heights_the_paper_test_finds_three_combinations_and_names_what_it_cannot_see() {
    let params: Vec<String> = PAPER8.iter().map(|s| s.to_string()).collect();
    let (input, mut own) = li_input(json!({ "parameters": params }));
    let truth = GeometricErrors::table5().iso();
    own.csv = paper_csv(&planes(&input, truth.clone(), &paper_specs(&input)), false);
    let r = identify_zones(&input, &own).unwrap();
    let f = &r.judgement.fit;
    // The paper: δyBY, γBY and δxCB have no effect on the heights, αBY and αCB change them
    // alike. Also δxBY and δzBY: both lower every outer zone uniformly (by sin 30° and
    // 1 − cos 30° per mm, Section 4.3), so only E_X0B + tan 15°·E_Z0B is seen:
    // 8 − 3 − 1 − 1 = 3 combinations. The independent count agrees.
    assert_eq!(f.rank, 3);
    assert_eq!(finite_difference_rank(&input, &PAPER8, false), 3);
    let unseen: Vec<&str> = f
        .groups
        .iter()
        .filter(|g| g.combinations.is_empty())
        .flat_map(|g| g.members.iter().map(String::as_str))
        .collect();
    assert_eq!(unseen, vec!["E_Y0B", "E_C0B", "E_X0C"]);
    let alike: Vec<&Vec<String>> = f
        .groups
        .iter()
        .filter(|g| !g.combinations.is_empty())
        .map(|g| &g.members)
        .collect();
    assert_eq!(
        alike,
        vec![
            &vec!["E_X0B".to_string(), "E_Z0B".to_string()],
            &vec!["E_A0B".to_string(), "E_A0C".to_string()]
        ]
    );
    let xz = &f.groups[0].combinations[0];
    assert!(
        (xz.terms[1].1 - (15f64).to_radians().tan()).abs() < 1e-6,
        "{}",
        xz.text
    );
    // The words say so.
    let text = r.judgement.summary.join("\n");
    assert!(text.contains("cannot see E_Y0B at all"), "{text}");
    assert!(
        text.contains("E_A0B and E_A0C cannot be told apart"),
        "{text}"
    );
    // What it can see comes back (exact heights, rounded to 1 pm: second order only).
    let e = f.estimates.iter().find(|e| e.name == "E_B0B").unwrap();
    let t = truth.get("E_B0B");
    assert!(
        (e.value.unwrap() - t).abs() < 2e-3 * t.abs(),
        "E_B0B: {:?} vs {t}",
        e.value
    );
    // And the combinations: their values are Σ c·truth.
    for g in f.groups.iter().filter(|g| !g.combinations.is_empty()) {
        let c = &g.combinations[0];
        let want: f64 = c.terms.iter().map(|(n, k)| k * truth.get(n)).sum();
        assert!(
            (c.value - want).abs() < 5e-3 * want.abs(),
            "{} = {} vs {want}",
            c.text,
            c.value
        );
    }
}

#[test]
fn with_slopes_the_paper_test_also_sees_the_tilts() {
    let params: Vec<String> = PAPER8.iter().map(|s| s.to_string()).collect();
    let (input, mut own) = li_input(json!({ "parameters": params }));
    let truth = GeometricErrors::table5().iso();
    own.csv = paper_csv(&planes(&input, truth.clone(), &paper_specs(&input)), true);
    let r = identify_zones(&input, &own).unwrap();
    let f = &r.judgement.fit;
    assert_eq!(f.rank, finite_difference_rank(&input, &PAPER8, true));
    // γBY tilts the outer zones: it comes out now; δyBY and δxCB still change nothing, and the
    // two pairs stay together (their tilts differ too little for a condition number of 100).
    assert_eq!(f.rank, 4);
    let unseen: Vec<&str> = f
        .groups
        .iter()
        .flat_map(|g| g.members.iter().map(String::as_str))
        .collect();
    assert_eq!(
        unseen,
        vec!["E_X0B", "E_Z0B", "E_Y0B", "E_A0B", "E_A0C", "E_X0C"]
    );
    let e = f.estimates.iter().find(|e| e.name == "E_B0B").unwrap();
    let t = truth.get("E_B0B");
    assert!(
        (e.value.unwrap() - t).abs() < 0.01 * t.abs(),
        "E_B0B: {:?} vs {t}",
        e.value
    );
    // Table 5's γBY (0.00002°) is below what the truncated pairs leak into it; alone at 4″ it
    // comes back.
    let gamma = 2e-5;
    let p = planes(
        &input,
        ErrorValues::single("E_C0B", gamma).unwrap(),
        &paper_specs(&input),
    );
    own.csv = paper_csv(&p, true);
    let r = identify_zones(&input, &own).unwrap();
    let e = r
        .judgement
        .fit
        .estimates
        .iter()
        .find(|e| e.name == "E_C0B")
        .unwrap();
    assert!(
        (e.value.unwrap() - gamma).abs() < 1e-2 * gamma,
        "E_C0B: {:?}",
        e.value
    );
}

fn designed(preset: &str) -> (CubicInput, String) {
    let mut v = json!({ "machine": machine_preset(preset) });
    v["secondSetup"] = json!(100.0);
    let (input, own): (CubicInput, CubicDesignInput) = read_split(&v, "").unwrap();
    let d = design(&input, &own).unwrap();
    (input, d.designed.csv)
}

/// The designed export filled in with exact planes (µm, mm/mm) plus noise.
fn filled(
    input: &CubicInput,
    csv: &str,
    errors: &ErrorValues,
    noise: f64,
    rng: &mut Rng,
) -> String {
    let blank = csv
        .lines()
        .map(|l| {
            if l.ends_with(",,,") {
                format!("{}0,0,0", &l[..l.len() - 2])
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let zones = parse_measurements(&blank, &input.setup).unwrap();
    let specs: Vec<_> = zones.iter().map(|z| z.zone.clone()).collect();
    let p = planes(input, errors.clone(), &specs);
    let lever = input.setup.zone_size / 2.0;
    let mut out = Vec::new();
    let mut k = 0;
    for l in csv.lines() {
        if l.ends_with(",,,") {
            let z = p[k];
            k += 1;
            out.push(format!(
                "{}{:.6},{:.9},{:.9}",
                &l[..l.len() - 2],
                (z.height + noise * rng.gauss()) * 1e3,
                z.slope_x + noise / lever * rng.gauss(),
                z.slope_y + noise / lever * rng.gauss()
            ));
        } else {
            out.push(l.to_string());
        }
    }
    out.join("\n")
}

#[test]
fn the_designed_test_recovers_every_error_it_can_see_from_its_own_export() {
    for preset in ["B/C tilting", "A/C trunnion"] {
        let (input, csv) = designed(preset);
        // Every identifiable error at a few µm / µrad, exact chain, 0.5 µm noise.
        let all = input.machine.error_defs();
        let mut truth = ErrorValues::none();
        let mut rng = Rng::new(17);
        let own: CubicIdentifyInput = read_split::<CubicInput, CubicIdentifyInput>(
            &json!({ "machine": machine_preset(preset), "csv": filled(&input, &csv, &ErrorValues::none(), 0.0, &mut rng) }),
            "",
        )
        .unwrap()
        .1;
        let probe = identify_zones(&input, &own).unwrap();
        let alone: Vec<String> = probe
            .judgement
            .fit
            .estimates
            .iter()
            .filter(|e| e.value.is_some())
            .map(|e| e.name.clone())
            .collect();
        for d in &all {
            if alone.contains(&d.name.to_string()) {
                let v = if d.component >= 3 { 1e-4 } else { 0.01 } * rng.range(-1.0, 1.0).signum();
                truth.set(d.name, v).unwrap();
            }
        }
        let mut own = own;
        own.csv = filled(&input, &csv, &truth, 0.0002, &mut rng);
        own.decision.noise = Some(0.0002);
        own.decision.tolerance = 0.0;
        let r = identify_zones(&input, &own).unwrap();
        for d in &r.judgement.decisions {
            if let (Some(v), Some([lo, hi])) = (d.value, d.interval) {
                let t = truth.get(&d.name);
                // 99.9 % interval width from the 95 % one: ×1.7.
                let half = 1.7 * (hi - lo) / 2.0;
                assert!(
                    (v - t).abs() <= half,
                    "{preset} {}: {v} vs {t} ± {half}",
                    d.name
                );
                // Found wherever the truth is well above its standard error.
                if (t / d.std_error.unwrap()).abs() > 6.0 {
                    assert_eq!(d.verdict, Verdict::Present, "{preset} {}", d.name);
                }
            }
        }
        assert_eq!(r.judgement.goodness.explains, Some(true), "{preset}");
    }
}

#[test]
fn the_designed_test_holds_its_false_call_rate() {
    // B/C designed test, every error it can see fitted, half of them zero; 1 µm noise; 1000
    // parts from the exact chain.
    let (input, csv) = designed("B/C tilting");
    let mut rng = Rng::new(4242);
    let zero_file = filled(&input, &csv, &ErrorValues::none(), 0.0, &mut rng);
    let zones = parse_measurements(&zero_file, &input.setup).unwrap();
    let all = input.machine.error_defs();
    let (a, _, _) = system(&input.machine, &input.setup, &input.options(), &zones, &all).unwrap();
    let params: Vec<Param> = all.iter().map(|d| Param::error(d.name).unwrap()).collect();
    let names: Vec<String> = all.iter().map(|d| d.name.to_string()).collect();
    let f0 = identify::fit(&a, &names, &vec![0.0; a.nrows()], 1e-2).unwrap();
    let alone: Vec<usize> = (0..all.len())
        .filter(|&j| f0.estimates[j].value.is_some())
        .collect();
    let mut truth = ErrorValues::none();
    for (k, &j) in alone.iter().enumerate() {
        if k % 2 == 0 {
            let v = if all[j].component >= 3 { 3e-5 } else { 0.004 };
            truth.set(all[j].name, v).unwrap();
        }
    }
    let specs: Vec<_> = zones.iter().map(|z| z.zone.clone()).collect();
    let p = planes(&input, truth.clone(), &specs);
    let lever = input.setup.zone_size / 2.0;
    let clean: Vec<f64> = p
        .iter()
        .flat_map(|z| [z.height, z.slope_x * lever, z.slope_y * lever])
        .collect();
    let noise = 0.001;
    let options = identify::Options {
        noise: Some(noise),
        ..identify::Options::default()
    };
    let n = 1000;
    let mut false_parts = 0;
    for _ in 0..n {
        let d: Vec<f64> = clean.iter().map(|v| v + noise * rng.gauss()).collect();
        let j = identify::identify(&a, &params, &d, 1e-2, &options).unwrap();
        let false_call = j
            .decisions
            .iter()
            .any(|d| d.verdict == Verdict::Present && truth.get(&d.name) == 0.0)
            || j.combinations.iter().any(|c| c.verdict == Verdict::Present);
        if false_call {
            false_parts += 1;
        }
    }
    let rate = false_parts as f64 / n as f64;
    println!("designed cubic test: false-call rate {rate}");
    assert!(
        rate <= 0.05 + 2.33 * (0.05f64 * 0.95 / n as f64).sqrt(),
        "{rate}"
    );
}

#[test]
fn the_file_names_its_line() {
    let (input, _) = li_input(json!({}));
    let piece = &input.setup;
    let cases = [
        (
            "zone,height_um\nI,0\nII-9,1\n",
            "line 3: zone \"II-9\" is not one of Table 1's",
        ),
        (
            "zone,height_um\nI,0\nI,1\n",
            "line 3: zone I is given twice (first on line 2)",
        ),
        (
            "# x\nzone,height_um\nI,0x\n",
            "line 3: height \"0x\" is not a number",
        ),
        ("zone,depth\nI,0\n", "line 1: unknown column \"depth\""),
        ("zone,slope_x\nI,0\n", "line 1: missing column 'height_mm'"),
        (
            "zone,height_mm\nI,0,1\n",
            "line 2: expected 2 columns like the header, got 3",
        ),
        (
            "zone,x_mm,y_mm,tilt_deg,azimuth_deg,height_um\nA1,0,0,30,0,\n",
            "line 2: zone A1: no height",
        ),
        ("zone,x_mm,height_um\nA1,0,1\n", "needs all four columns"),
        ("zone,height_um\n", "no zone"),
    ];
    for (text, want) in cases {
        let e = parse_measurements(text, piece).unwrap_err().to_string();
        assert!(
            e.starts_with("csv: ") && e.contains(want),
            "expected {want:?} in {e:?}"
        );
    }
    // µm and mm agree; ZONE prefix accepted.
    let a = parse_measurements("zone,height_um\nZONE II-1,-5\n", piece).unwrap();
    let b = parse_measurements("zone,height_mm\nII-1,-0.005\n", piece).unwrap();
    assert_eq!(a[0].height, b[0].height);
    assert_eq!(a[0].zone, b[0].zone);
    let _ = li::machine(&CubicSetup::default(), &GeometricErrors::table5());
    let _ = Options::default();
}
