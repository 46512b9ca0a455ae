//! The friction fit (eq 2's f_c and a, C's position-loop gain) from a measured trace: the CSV
//! reader's line-numbered messages, recovery of the values a trace was simulated with, the
//! coverage of the 95 % intervals over many noise draws, traces the fit must refuse, and the
//! sample file of `public/samples/` (made by `write_the_sample_file`, checked reproducible).

#![allow(clippy::unwrap_used)]
use crate::common;

use common::Rng;
use fiveaxis::reversal::fit::{declared_machine, fit, parse_trace};
use fiveaxis::reversal::{simulate, ReversalCase};
use serde_json::{json, Value};

const SAMPLE_PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../public/samples/reversal-measured.csv"
);
const SAMPLE_SEED: u64 = 20170101;
const SAMPLE_NOISE: f64 = 0.0003;

fn gauss(rng: &mut Rng) -> f64 {
    let (u1, u2) = (rng.unit().max(1e-300), rng.unit());
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

fn case(v: Value) -> ReversalCase {
    ReversalCase::read(&v).unwrap()
}

/// The trace of `truth` at every `step_deg` of trace angle (finely simulated, interpolated),
/// with Gaussian noise of `noise` mm, as CSV text.
fn measured_csv(truth: &ReversalCase, step_deg: f64, noise: f64, seed: u64) -> String {
    let mut fine = truth.clone();
    fine.samples = 60_000;
    let (_, tr) = simulate(&fine).unwrap();
    let mut rng = Rng::new(seed);
    let mut s = String::from("angle_deg,deviation_mm\n");
    let mut a = step_deg;
    while a < 360.0 - step_deg / 2.0 {
        let x = a.to_radians();
        let i = tr.angle.partition_point(|v| *v < x).max(1);
        let (x0, x1) = (tr.angle[i - 1], tr.angle[i]);
        let d =
            tr.deviation[i - 1] + (tr.deviation[i] - tr.deviation[i - 1]) * (x - x0) / (x1 - x0);
        s.push_str(&format!("{a:.3},{:.7}\n", d + noise * gauss(&mut rng)));
        a += step_deg;
    }
    s
}

#[test]
fn the_reader_names_the_line() {
    let bad = [
        ("", "the file is empty"),
        (
            "angle_deg;dev\n1;2\n",
            "line 1: missing column 'deviation_mm'",
        ),
        (
            "angle_deg,deviation_mm\n0.5,0.001\n1.0,0.0x2\n",
            "line 3: deviation \"0.0x2\" is not a number",
        ),
        (
            "angle_deg,deviation_mm\n0.5,0.001\n0.4,0.002\n",
            "line 3: angle 0.4° does not increase (line 2 has 0.5000°)",
        ),
        (
            "# a comment\nangle_deg,deviation_um\n1,2,3\n",
            "line 3: expected 2 columns",
        ),
        (
            "angle_deg,deviation_mm\n500,0\n",
            "line 2: angle 500° is outside",
        ),
        (
            "angle_deg,deviation_mm\n1,0\n2,0\n",
            "csv: 2 points: the fit needs at least 50",
        ),
    ];
    for (text, want) in bad {
        let e = parse_trace(text).unwrap_err().to_string();
        assert!(e.contains(want), "{text:?}: {e}");
        assert!(e.starts_with("csv"), "{e}");
    }
    // No points near the reversal.
    let mut t = String::from("angle_deg,deviation_mm\n");
    for i in 0..100 {
        t.push_str(&format!("{},0\n", i as f64));
    }
    let e = parse_trace(&t).unwrap_err().to_string();
    assert!(e.contains("within ±10° of the reversal"), "{e}");
    // µm are read as µm.
    let mut t = String::from("angle_deg\tdeviation_um\n");
    for i in 0..360 {
        t.push_str(&format!("{}\t{}\n", i as f64 + 0.5, 2.0));
    }
    let m = parse_trace(&t).unwrap();
    assert!((m.deviation[0] - 0.002).abs() < 1e-15);
    assert_eq!(m.lines[0], 2);
}

#[test]
fn the_intervals_cover_the_truth_at_their_rate() {
    // f_c = 10 N·m, a = 500 1/rad, K_p = 30 1/s simulated at 1000 mm/min, 0.3 µm of noise at
    // every 0.05° (a ball bar samples far more densely); each fit starts from f_c = 6, a = 300,
    // K_p = 24. Over 40 draws the 95 % intervals of f_c
    // and a must hold the truth about 38 times: fewer than 34 would happen by chance with
    // probability below 0.5 %.
    let truth = case(json!({"step": 0.5}));
    let start =
        case(json!({"step": 0.5, "c": {"friction": 6, "frictionSlope": 300, "positionGain": 24}}));
    let draws = 40u64;
    let results: Vec<(bool, bool, bool)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..2u64)
            .map(|half| {
                let (truth, start) = (&truth, &start);
                s.spawn(move || {
                    (0..draws / 2)
                        .map(|i| {
                            let seed = 1000 + 2 * i + half;
                            let csv = measured_csv(truth, 0.05, 0.0003, seed);
                            let f = fit(start, &parse_trace(&csv).unwrap()).unwrap();
                            let inside = |e: fiveaxis::reversal::fit::FitEstimate, v: f64| {
                                e.low <= v && v <= e.high
                            };
                            assert!(
                                (f.sigma / 0.0003 - 1.0).abs() < 0.2,
                                "seed {seed}: sigma {}",
                                f.sigma
                            );
                            (
                                inside(f.fc, 10.0),
                                inside(f.slope, 500.0),
                                inside(f.kp, 30.0),
                            )
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    let count = |k: usize| results.iter().filter(|r| [r.0, r.1, r.2][k]).count();
    for (k, name) in ["f_c", "a", "K_p"].iter().enumerate() {
        let c = count(k);
        assert!(
            (34..=40).contains(&c),
            "{name}: {c} of {draws} intervals hold the truth"
        );
    }
}

#[test]
fn a_trace_without_a_dent_is_refused() {
    // No friction in the trace: f_c and a are not determined.
    let truth = case(json!({"test": {"feed": 3000}, "c": {"friction": 0}}));
    let csv = measured_csv(&truth, 0.5, 0.0003, 7);
    let start = case(json!({"test": {"feed": 3000}}));
    let e = fit(&start, &parse_trace(&csv).unwrap()).unwrap_err();
    assert_eq!(e.field, "csv");
    assert!(
        e.message.contains("friction dent") || e.message.contains("converge"),
        "{e}"
    );
    // Pure noise.
    let mut rng = Rng::new(3);
    let mut t = String::from("angle_deg,deviation_mm\n");
    for i in 1..720 {
        t.push_str(&format!("{},{}\n", i as f64 * 0.5, 0.001 * gauss(&mut rng)));
    }
    let e = fit(&start, &parse_trace(&t).unwrap()).unwrap_err();
    assert_eq!(e.field, "csv", "{e}");
}

/// The machine preset the sample file is made on (public/presets/machines.json), named in its
/// `# machine:` line.
const SAMPLE_MACHINE: &str = "B/C tilting table, vertical spindle (Li et al. 2021)";

fn preset_machine(name: &str) -> Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/presets/machines.json"
    ))
    .unwrap();
    let all: Value = serde_json::from_str(&text).unwrap();
    all["presets"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == name)
        .unwrap()["machine"]
        .clone()
}

fn sample_text() -> String {
    let truth = case(json!({
        "machine": preset_machine(SAMPLE_MACHINE),
        "c": {"friction": 12, "frictionSlope": 800, "positionGain": 28}
    }));
    let header = format!(
        "# Rotary-axis reversal test (Nishiguchi et al. 2017): a ball-bar trace, SIMULATED.\n\
         # machine: {SAMPLE_MACHINE}\n\
         # Made by crate/tests/reversal/fit.rs (write_the_sample_file) with the calculator's model:\n\
         # that machine preset, R = 50 mm, r = 25 mm, F = 1000 mm/min, C 0 -> 90 -> 0 deg,\n\
         # default drives without feed-forward, C friction f_c = 12 N.m, a = 800 1/rad, C position-loop\n\
         # gain 28 1/s; plus Gaussian noise of {} um (seed {SAMPLE_SEED}).\n\
         # angle_deg: trace angle (reversal of C at 180 deg); deviation_mm: radial, + outwards.\n",
        SAMPLE_NOISE * 1e3
    );
    header + &measured_csv(&truth, 0.1, SAMPLE_NOISE, SAMPLE_SEED)
}

#[test]
#[ignore = "writes public/samples/reversal-measured.csv; run with --ignored to regenerate"]
fn write_the_sample_file() {
    std::fs::create_dir_all(concat!(env!("CARGO_MANIFEST_DIR"), "/../public/samples")).unwrap();
    std::fs::write(SAMPLE_PATH, sample_text()).unwrap();
}

#[test]
fn the_sample_file_is_reproducible_and_fits() {
    let text = std::fs::read_to_string(SAMPLE_PATH).unwrap();
    assert_eq!(
        text,
        sample_text(),
        "run write_the_sample_file (--ignored) after a model change"
    );
    let f = fit(&case(json!({})), &parse_trace(&text).unwrap()).unwrap();
    for (e, v) in [(f.fc, 12.0), (f.slope, 800.0), (f.kp, 28.0)] {
        assert!(e.low <= v && v <= e.high, "{e:?} should hold {v}");
    }
    // It names its machine, a preset of the page.
    assert_eq!(declared_machine(&text), Some(SAMPLE_MACHINE));
}

#[test]
fn a_trace_names_its_machine_in_a_comment_line() {
    assert_eq!(declared_machine("angle_deg,deviation_mm\n1,0\n"), None);
    assert_eq!(
        declared_machine(
            "\u{feff}# a note: not it\n#  Machine :  A/C trunnion  \n# machine: later\n"
        ),
        Some("A/C trunnion")
    );
    assert_eq!(declared_machine("# machine:   \n"), None);
    // The reader skips the line.
    let t = "# machine: X\nangle_deg,deviation_mm\n".to_string()
        + &(1..60)
            .map(|i| format!("{},0\n", 170.0 + i as f64 * 0.3))
            .collect::<String>();
    assert_eq!(parse_trace(&t).unwrap().angle.len(), 59);
}
