//! Identification of the location errors from the 100 measured deviations (Chanal et al. 2022,
//! Section 6, Table 4): the CSV reader's messages, the rank detection on a matrix with a known
//! dependence, round trips with the Table 4 values plus seeded noise, and the sample file of
//! `public/samples/` (made by `write_the_sample_file`; checked here against what its header states
//! by the exact chain, not against a copy of the engine's output).

#![allow(clippy::unwrap_used)]
use crate::common;

use common::chanal::{self, design, identify8, PAPER_L0};
use common::{close, Rng};
use fiveaxis::sshape::identify::{fit, parse_measurements, DEFAULT_RTOL};
use fiveaxis::sshape::machine::{DefectPoint, DefectReference, PathBranch};
use fiveaxis::sshape::part::{Curve, Part};
use nalgebra::DMatrix;

/// Table 4, "values for simulation": E_X0B = 0.0294 mm, E_A0B = 3.2419e-4 rad, others 0.
const TABLE4: [f64; 8] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0294, 3.2419e-4, 0.0];
/// The sample's tool-radius error (mm) and noise (mm, one standard deviation).
const SAMPLE_DR: f64 = -0.02;
const SAMPLE_NOISE: f64 = 0.002;
const SAMPLE_SEED: u64 = 20220208;
const SAMPLE_PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../public/samples/sshape-measured.csv"
);

fn gauss(rng: &mut Rng) -> f64 {
    rng.gauss()
}

fn csv(values: &[f64]) -> String {
    let pts = Part::standard().unwrap().measurement_points();
    let mut s = String::from("curve,point,deviation_mm\n");
    for (p, v) in pts.iter().zip(values) {
        s.push_str(&format!("{},{},{:.4}\n", p.curve.name(), p.number, v));
    }
    s
}

fn sample_text() -> String {
    let design = design(PAPER_L0, chanal::default_model());
    let clean = design.simulate(&chanal::errors(&TABLE4), SAMPLE_DR);
    let mut rng = Rng::new(SAMPLE_SEED);
    let noisy: Vec<f64> = clean
        .iter()
        .map(|v| v + SAMPLE_NOISE * gauss(&mut rng))
        .collect();
    let header = format!(
        "# S-shape test piece (ISO 10791-7): deviations at the 100 measurement points, SIMULATED.\n\
         # Made by crate/tests/sshape/identify.rs (write_the_sample_file) with the calculator's\n\
         # eq 14 model: head-B/table-C machine, L0 = {PAPER_L0} mm, tool R = 10 mm, L = 35 mm,\n\
         # inverse kinematics B >= 0 (paper), reference at the workpiece origin, tool tip.\n\
         # Errors: Table 4's values for simulation, E_X0B = 0.0294 mm, E_A0B = 3.2419e-4 rad,\n\
         # the other six 0; tool radius {SAMPLE_DR} mm (real tool smaller than 10 mm);\n\
         # plus Gaussian noise of {} um standard deviation (seed {SAMPLE_SEED}), rounded to 0.1 um.\n\
         # Deviation: along the outward normal, positive = material left, mm.\n",
        SAMPLE_NOISE * 1000.0
    );
    header + &csv(&noisy)
}

#[test]
#[ignore = "writes public/samples/sshape-measured.csv; run with --ignored to regenerate"]
fn write_the_sample_file() {
    std::fs::create_dir_all(concat!(env!("CARGO_MANIFEST_DIR"), "/../public/samples")).unwrap();
    std::fs::write(SAMPLE_PATH, sample_text()).unwrap();
}

/// The number the sample's header states between `before` and `unit` (e.g. `"E_X0B = "`,
/// `" mm"`).
fn stated(header: &str, before: &str, unit: &str) -> f64 {
    let start = header
        .find(before)
        .unwrap_or_else(|| panic!("the header states {before:?}"))
        + before.len();
    let len = header[start..]
        .find(unit)
        .unwrap_or_else(|| panic!("{before:?} is followed by {unit:?}"));
    header[start..start + len]
        .trim()
        .parse()
        .unwrap_or_else(|_| panic!("{before:?}: a number"))
}

/// The sample file checked against what its header states, by a second method: the header
/// must state the simulation's inputs (Table 4's values for simulation and L0 from the paper,
/// the tool, the noise), and the file's 100 values must be reproduced from those inputs by the
/// exact kinematic chain (not by eq 14, which made the file): the errors set on the machine by
/// name, the tool tip's shift at each point's pose minus its shift at the work origin, along the
/// point's normal, plus the tool-radius term. What is left must look like the stated noise.
#[test]
fn the_sample_file_is_what_its_header_says() {
    use fiveaxis::chain::Setup;
    use nalgebra::Vector3;
    let text = std::fs::read_to_string(SAMPLE_PATH).unwrap();
    let header: String = text
        .lines()
        .filter(|l| l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n");
    // The inputs the header states, against the paper (Section 5.2, Table 4).
    let l0 = stated(&header, "L0 = ", " mm");
    let r_tool = stated(&header, "tool R = ", " mm");
    let l_tool = stated(&header, "L = ", " mm");
    let x0b = stated(&header, "E_X0B = ", " mm");
    let a0b = stated(&header, "E_A0B = ", " rad");
    let dr = stated(&header, "tool radius ", " mm");
    let sigma = stated(&header, "noise of ", " um") * 1e-3;
    let step = stated(&header, "rounded to ", " um") * 1e-3;
    assert_eq!(
        (l0, r_tool, l_tool),
        (499.889, 10.0, 35.0),
        "the paper's set-up"
    );
    assert_eq!(
        (x0b, a0b),
        (0.0294, 3.2419e-4),
        "Table 4's values for simulation"
    );
    assert!(header.contains("the other six 0"));
    assert!(header.contains("B >= 0") && header.contains("reference at the workpiece origin"));
    assert!(header.contains("SIMULATED"));
    let measured = parse_measurements(&text).unwrap();

    // The exact chain with the stated errors, at the poses of eq 2's tool with B >= 0.
    let mut machine = chanal::machine(l0);
    machine.errors.set("E_X0B", x0b).unwrap();
    machine.errors.set("E_A0B", a0b).unwrap();
    let built = machine.build().unwrap();
    let nominal = built.nominal();
    let d = design(l0, chanal::default_model());
    let zero = vec![0.0; nominal.len()];
    let q_ref = nominal.solve_linear(&Vector3::zeros(), &zero).unwrap();
    let shift = |q: &[f64]| {
        let a = built.chain.tool_pose(q, true, &Setup::None).unwrap();
        let b = nominal.tool_pose(q, false, &Setup::None).unwrap();
        (a.tip - b.tip, b.tip, b.axis)
    };
    let (at_ref, tip_ref, _) = shift(&q_ref);
    assert!(
        tip_ref.norm() < 1e-9,
        "the work origin is where the tip was set"
    );
    let mut residuals = Vec::new();
    for (pp, m) in d.poses.iter().zip(&measured) {
        let (s, tip, axis) = shift(&pp.pose.q);
        let t = d.path.at(d.part.surface(pp.point.surface), pp.point.u);
        assert!((tip - t.tip).norm() < 1e-9 && (axis - t.axis).norm() < 1e-12);
        assert!(
            pp.pose.q[nominal.index_of("B").unwrap()] >= -1e-12,
            "B >= 0"
        );
        let n = Vector3::from(pp.point.normal);
        // A tool larger by dR on the same path cuts exactly dR deeper from its axis (the
        // clearance is the distance to the axis minus the radius): along the normal
        // −dR·|n − (n·a)a| (= −dR here: the ruling, the tool axis, lies in the surface).
        let radial = (n - axis * n.dot(&axis)).norm();
        let exact = (s - at_ref).dot(&n) - dr * radial;
        residuals.push(m - exact);
    }
    // What is left is the stated noise, rounded. Other contributions, bounded: second order of
    // the chain, (E_A0B)²·1 m = 1.1e-4 mm at most; the file's radius term −dR·sin θ (Section
    // 3.2) against the exact −dR, sin θ within 0.4 % of 1 on these surfaces (checked in
    // crate/tests/sshape/overcut.rs against the exact shift): 0.004·|dR| = 8e-5 mm; the rounding, half a
    // step.
    let model = 1000.0 * a0b * a0b + 0.004 * dr.abs() + step / 2.0;
    let n = residuals.len() as f64;
    let mean = residuals.iter().sum::<f64>() / n;
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / n).sqrt();
    let max = residuals.iter().fold(0.0f64, |a, r| a.max(r.abs()));
    // 100 normal deviates: each within 5 σ (all 100 together with probability 1 − 6e-5), the
    // mean within 4 σ/√100, the RMS within 1 ± 4.2·0.071 σ (χ with 100 degrees of freedom).
    assert!(max < 5.0 * sigma + model, "largest residual {max}");
    assert!(mean.abs() < 0.4 * sigma + model, "mean residual {mean}");
    assert!(
        rms > 0.7 * sigma - model && rms < 1.3 * sigma + model,
        "rms {rms}"
    );
    // The values are written to the stated step.
    for m in &measured {
        assert!(
            (m / step - (m / step).round()).abs() < 1e-6,
            "{m} on a {step} mm step"
        );
    }
    println!("residuals: mean {mean:e}, rms {rms:e}, max {max:e}");
}

#[test]
fn identifying_the_sample_recovers_table_4_and_the_tool_radius() {
    let d = parse_measurements(&std::fs::read_to_string(SAMPLE_PATH).unwrap()).unwrap();
    let design = design(PAPER_L0, chanal::default_model());
    let f = identify8(&design, &d, true, DEFAULT_RTOL);
    assert_eq!(f.rank, 9);
    assert!(f.groups.is_empty());
    let truth = [TABLE4.to_vec(), vec![SAMPLE_DR]].concat();
    for (e, t) in f.estimates.iter().zip(&truth) {
        let (v, se) = (e.value.unwrap(), e.std_error.unwrap());
        assert!((v - t).abs() < 4.0 * se, "{}: {v} ± {se} vs {t}", e.name);
    }
    for e in &f.estimates {
        println!(
            "{}: {:.4e} ± {:.2e}",
            e.name,
            e.value.unwrap(),
            e.std_error.unwrap()
        );
    }
    // 2 µm of noise on 100 points pins E_X0B and the radius to about 1 µm, E_A0B to 2 %.
    assert!(f.estimates[5].std_error.unwrap() < 1.5e-3);
    assert!(f.estimates[6].std_error.unwrap() < 0.02 * 3.2419e-4);
    assert!(f.estimates[8].std_error.unwrap() < 1.5e-3);
    // The residuals are the noise: about 2 µm RMS.
    assert!(f.rms > 0.0014 && f.rms < 0.0026, "rms {}", f.rms);
    close(f.sigma, SAMPLE_NOISE, 0.0006, "σ");
}

#[test]
fn round_trip_with_eq_14_as_printed_reports_the_two_pairs_and_recovers_table_4() {
    // DefectReference at all axes zero (eq 14 as printed): E_A0Z/E_A0C and E_B0Z/E_B0C come out as
    // two inseparable pairs (found from the singular values, not named in the code), each with
    // one identifiable combination, their difference; E_X0B and E_A0B are recovered.
    for branch in [PathBranch::Paper, PathBranch::Continuous] {
        let model = chanal::model(branch, DefectReference::AxesZero, DefectPoint::Tip);
        let design = design(PAPER_L0, model);
        let clean = design.simulate(&chanal::errors(&TABLE4), 0.0);
        let mut rng = Rng::new(7);
        let d: Vec<f64> = clean.iter().map(|v| v + 0.001 * gauss(&mut rng)).collect();
        let f = identify8(&design, &d, false, DEFAULT_RTOL);
        assert_eq!(f.rank, 6, "{branch:?}: {:?}", f.singular_values);
        let mut members: Vec<Vec<String>> = f.groups.iter().map(|g| g.members.clone()).collect();
        members.sort();
        assert_eq!(
            members,
            vec![
                vec!["E_A0Z".to_string(), "E_A0C".into()],
                vec!["E_B0Z".into(), "E_B0C".into()]
            ]
        );
        for g in &f.groups {
            assert_eq!(g.deficiency, 1);
            assert_eq!(g.combinations.len(), 1);
            let c = &g.combinations[0];
            // About their difference (coefficient −1 within 5 %: the pairs are nearly, not
            // exactly, opposite); its true value is 0.
            close(c.terms[1].1, -1.0, 0.05, "opposite pair");
            assert!(
                c.value.abs() < 4.0 * c.std_error,
                "{}: {} ± {}",
                c.text,
                c.value,
                c.std_error
            );
            // Not silently split: no individual values for the members.
            for m in &g.members {
                let e = f.estimates.iter().find(|e| &e.name == m).unwrap();
                assert!(e.value.is_none() && e.std_error.is_none());
            }
        }
        for (k, t) in [(5, 0.0294), (6, 3.2419e-4)] {
            let e = &f.estimates[k];
            assert!(
                (e.value.unwrap() - t).abs() < 4.0 * e.std_error.unwrap(),
                "{}",
                e.name
            );
        }
        assert!(f.estimates[5].std_error.unwrap() < 1e-3);
        assert!(f.estimates[6].std_error.unwrap() < 0.02 * 3.2419e-4);
    }
}

#[test]
fn an_exact_dependence_is_found_and_reported_not_split() {
    // Five parameters over 40 points; column 3 = −2 × column 1 and column 4 = column 0 + column 2:
    // rank 3, one group {1, 3}, one group {0, 2, 4} with two identifiable combinations.
    let mut rng = Rng::new(8);
    let base = DMatrix::from_fn(40, 3, |_, _| rng.range(-1.0, 1.0));
    let a = DMatrix::from_fn(40, 5, |r, c| match c {
        0 => base[(r, 0)],
        1 => base[(r, 1)],
        2 => base[(r, 2)],
        3 => -2.0 * base[(r, 1)],
        _ => base[(r, 0)] + base[(r, 2)],
    });
    let x = [0.3, -0.2, 0.5, 0.1, 0.05];
    let d: Vec<f64> = (0..40)
        .map(|r| (0..5).map(|c| a[(r, c)] * x[c]).sum())
        .collect();
    let names: Vec<String> = ["a", "b", "c", "d", "e"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let f = fit(&a, &names, &d, 1e-9).unwrap();
    assert_eq!(f.rank, 3);
    assert!(f.estimates.iter().all(|e| e.value.is_none()));
    let mut groups: Vec<_> = f
        .groups
        .iter()
        .map(|g| (g.members.clone(), g.deficiency, g.combinations.len()))
        .collect();
    groups.sort();
    assert_eq!(
        groups,
        vec![
            (vec!["a".to_string(), "c".into(), "e".into()], 1, 2),
            (vec!["b".to_string(), "d".into()], 1, 1),
        ]
    );
    // The identifiable combination of b and d is b − 2·d (the column relation b_col = −d_col/2):
    // its value is the true −0.2 − 2·0.1 = −0.4, whatever the split.
    let g = f.groups.iter().find(|g| g.members[0] == "b").unwrap();
    let c = &g.combinations[0];
    close(c.terms[1].1, -2.0, 1e-9, "b − 2·d");
    close(c.value, -0.4, 1e-9, "value");
    // Every combination of {a, c, e} has the value the truth gives it.
    let g = f.groups.iter().find(|g| g.members[0] == "a").unwrap();
    for c in &g.combinations {
        let truth: f64 = c
            .terms
            .iter()
            .map(|(n, k)| k * x[names.iter().position(|m| m == n).unwrap()])
            .sum();
        close(c.value, truth, 1e-9, &c.text);
    }
    close(f.rms, 0.0, 1e-12, "exact data");
}

#[test]
fn csv_errors_name_the_line() {
    let pts = Part::standard().unwrap().measurement_points();
    let good = csv(&vec![0.001; 100]);
    assert_eq!(parse_measurements(&good).unwrap().len(), 100);
    let lines: Vec<&str> = good.lines().collect();
    let with = |k: usize, line: &str| {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l[k] = line.to_string();
        l.join("\n")
    };
    let cases: Vec<(String, &str)> = vec![
        (
            with(0, "curve,point"),
            "line 1: missing column 'deviation_mm'",
        ),
        (
            with(0, "point,deviation_mm"),
            "line 1: missing column 'curve'",
        ),
        (
            with(0, "curve;point;deviation_mm"),
            "line 2: expected 3 columns",
        ),
        (
            with(5, "top,5"),
            "line 6: expected 3 columns like the header, got 2",
        ),
        (
            with(5, "top,5,abc"),
            "line 6: deviation \"abc\" is not a number",
        ),
        (with(5, "top,5,0,01"), "line 6: expected 3 columns"),
        (
            with(7, "middle,7,0.001"),
            "line 8: unknown measurement curve \"middle\"",
        ),
        (with(7, "top,51,0.001"), "line 8: point 51 is outside 1..50"),
        (
            with(7, "top,x,0.001"),
            "line 8: point \"x\" is not a whole number",
        ),
        (
            with(9, "top,3,0.001"),
            "line 10: point top 3 is given twice (first on line 4)",
        ),
        (
            with(9, "top,9,1e400"),
            "line 10: deviation \"1e400\" is not a number",
        ),
        (with(9, "top,9,55"), "line 10: deviation must be between"),
        (String::from("# nothing\n\n"), "the file is empty"),
        (
            lines[..60].join("\n"),
            "41 of the 100 points are missing: bottom 10, bottom 11",
        ),
    ];
    for (text, want) in cases {
        let e = parse_measurements(&text).unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("csv: "), "{msg}");
        assert!(msg.contains(want), "expected {want:?} in {msg:?}");
    }
    // Accepted variants: µm column, semicolons, comments, any order, other curve names.
    let mut text = String::from("# my CMM\nCurve;Point;Deviation_um\n");
    for p in pts.iter().rev() {
        let name = if p.curve == Curve::Top { "Z25" } else { "b" };
        text.push_str(&format!("{name};{};{}\n", p.number, p.number as f64));
    }
    let d = parse_measurements(&text).unwrap();
    close(d[0], 0.001, 1e-15, "top 1 in µm");
    close(d[99], 0.050, 1e-15, "bottom 50");
}

#[test]
fn the_standard_errors_match_the_scatter_over_repeated_noise_draws() {
    // 300 noise draws of 2 µm on the Table 4 part: the empirical spread of each estimate around
    // its true value agrees with the reported standard error within 15 %, and the estimates are
    // unbiased (mean error below 3 standard errors of the mean).
    let design = design(PAPER_L0, chanal::default_model());
    let clean = design.simulate(&chanal::errors(&TABLE4), SAMPLE_DR);
    let truth = [TABLE4.to_vec(), vec![SAMPLE_DR]].concat();
    let mut rng = Rng::new(99);
    let n = 300;
    let (mut sum, mut sum2, mut se) = ([0.0; 9], [0.0; 9], [0.0; 9]);
    for _ in 0..n {
        let d: Vec<f64> = clean
            .iter()
            .map(|v| v + SAMPLE_NOISE * gauss(&mut rng))
            .collect();
        let f = identify8(&design, &d, true, DEFAULT_RTOL);
        for k in 0..9 {
            let e = f.estimates[k].value.unwrap() - truth[k];
            sum[k] += e;
            sum2[k] += e * e;
            se[k] += f.estimates[k].std_error.unwrap() / n as f64;
        }
    }
    for k in 0..9 {
        let sd = (sum2[k] / n as f64).sqrt();
        assert!(
            (sd / se[k] - 1.0).abs() < 0.15,
            "parameter {k}: spread {sd:e}, standard error {:e}",
            se[k]
        );
        assert!(
            (sum[k] / n as f64).abs() < 3.0 * se[k] / (n as f64).sqrt(),
            "parameter {k} biased"
        );
    }
}
