//! The ball-bar circular test (ISO 230-4): traces synthesised from each fault's exact geometry
//! (not from the fitted model's first-order terms), with noise, recovered by the fit; G and H on
//! a trace whose values are known by construction; the reader's faults.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::Rng;
use fiveaxis::api::ApiInput;
use fiveaxis::ballbar::{evaluate, Ballbar, BallbarInput};
use serde_json::json;
use std::f64::consts::PI;

const R: f64 = 100.0;
const FEED: f64 = 1000.0; // mm/min

fn gauss(rng: &mut Rng) -> f64 {
    let (u1, u2) = (rng.unit().max(1e-300), rng.unit());
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// The faults of the machine, exactly as they move the tool.
#[derive(Default, Clone, Copy)]
struct Faults {
    /// The centre of the circle the machine makes, from the ball-bar's pivot, mm.
    centre: [f64; 2],
    /// Scale errors of u and v.
    scale: [f64; 2],
    /// v leans towards +u by this angle, rad.
    squareness: f64,
    /// u lags v by this time, s.
    lag: f64,
    /// Lost motion of u and v, mm.
    backlash: [f64; 2],
}

/// The trace (every 1°, both ways) of a machine with `f`, noise σ mm, as CSV in µm.
fn trace(f: Faults, noise: f64, seed: u64) -> String {
    let mut rng = Rng::new(seed);
    let omega = FEED / 60.0 / R;
    let mut out = format!(
        "# radius: {R} mm\n# feed: {FEED} mm/min\nangle (deg); deviation (µm); direction\n"
    );
    for (d, name) in [(1.0, "ccw"), (-1.0, "cw")] {
        for k in 0..360 {
            let th = (k as f64 + 0.5) * PI / 180.0;
            // Commanded position, then each fault's exact effect.
            let (u, v) = (R * (th - d * omega * f.lag).cos(), R * th.sin());
            let (du, dv) = (-d * th.sin(), d * th.cos()); // direction of travel
            let u = u * (1.0 + f.scale[0]) + f.squareness * v - 0.5 * f.backlash[0] * du.signum();
            let v = v * (1.0 + f.scale[1]) - 0.5 * f.backlash[1] * dv.signum();
            let dr = (u + f.centre[0]).hypot(v + f.centre[1]) - R + noise * gauss(&mut rng);
            out.push_str(&format!("{}; {}; {name}\n", th.to_degrees(), dr * 1e3));
        }
    }
    out
}

fn run(csv: &str) -> Ballbar {
    evaluate_input(json!({ "csv": csv })).unwrap()
}

/// The export on a JSON input: read (and checked), then evaluated.
fn evaluate_input(input: serde_json::Value) -> Result<Ballbar, fiveaxis::Error> {
    BallbarInput::read(&input).and_then(|i| evaluate(&i))
}

fn value(f: &fiveaxis::ballbar::Fitted) -> f64 {
    f.value.unwrap()
}

/// Each fault alone, with 0.3 µm of noise: recovered to the stated tolerance, the other
/// diagnostics near zero. The tolerances are about 3 standard errors: a `sin 2θ` or `cos 2θ`
/// coefficient from 720 points has `se ≈ σ·√(2/720) = 16 nm`, 0.32 µm/m or ppm at R = 100 mm.
#[test]
fn each_fault_alone_is_recovered() {
    let noise = 0.0003;
    type Case = (&'static str, Faults, fn(&Ballbar) -> f64, f64, f64);
    let cases: [Case; 6] = [
        (
            "centre u",
            Faults {
                centre: [0.010, 0.0],
                ..Default::default()
            },
            |b| value(&b.diagnostics.centre_u),
            0.010,
            1e-4,
        ),
        (
            "centre v",
            Faults {
                centre: [0.0, -0.006],
                ..Default::default()
            },
            |b| value(&b.diagnostics.centre_v),
            -0.006,
            1e-4,
        ),
        // ε_u − ε_v = 20 ppm.
        (
            "scale mismatch",
            Faults {
                scale: [20e-6, 0.0],
                ..Default::default()
            },
            |b| value(&b.diagnostics.scale_mismatch),
            20.0,
            1.0,
        ),
        // 30 µm/m, the axes closer than 90°.
        (
            "squareness",
            Faults {
                squareness: 30e-6,
                ..Default::default()
            },
            |b| value(&b.diagnostics.squareness),
            30.0,
            1.0,
        ),
        // u lags by 2 ms.
        (
            "servo mismatch",
            Faults {
                lag: 0.002,
                ..Default::default()
            },
            |b| value(&b.diagnostics.servo_mismatch),
            2.0,
            0.05,
        ),
        (
            "backlash u",
            Faults {
                backlash: [0.008, 0.0],
                ..Default::default()
            },
            |b| value(&b.diagnostics.backlash_u),
            0.008,
            1e-4,
        ),
    ];
    for (name, f, got, want, tol) in cases {
        let b = run(&trace(f, noise, 7));
        let g = got(&b);
        assert!(
            (g - want).abs() <= tol,
            "{name}: got {g}, want {want} ± {tol}"
        );
        // The others stay near zero.
        let d = &b.diagnostics;
        if name != "squareness" {
            assert!(
                value(&d.squareness).abs() < 1.0,
                "{name}: squareness {}",
                value(&d.squareness)
            );
        }
        if name != "backlash u" {
            assert!(
                value(&d.backlash_u).abs() < 2e-4,
                "{name}: backlash u {}",
                value(&d.backlash_u)
            );
        }
        if name != "scale mismatch" {
            assert!(
                value(&d.scale_mismatch).abs() < 1.0,
                "{name}: scale {}",
                value(&d.scale_mismatch)
            );
        }
    }
    let b = run(&trace(
        Faults {
            backlash: [0.0, 0.005],
            ..Default::default()
        },
        noise,
        8,
    ));
    assert!(
        (value(&b.diagnostics.backlash_v) - 0.005).abs() < 1e-4,
        "backlash v {:?}",
        b.diagnostics.backlash_v
    );
}

/// Several faults together, over 100 noise draws: each 95 % interval covers its true value in
/// at least 88 % of the draws (binomial: below 88 % of 100 has probability < 1 % at 95 %).
#[test]
fn several_faults_together_within_their_intervals() {
    let f = Faults {
        centre: [0.004, -0.003],
        scale: [12e-6, -5e-6],
        squareness: -15e-6,
        lag: 0.001,
        backlash: [0.003, 0.002],
    };
    let truth = [0.004, -0.003, 17.0, -15.0, 1.0, 0.003, 0.002];
    let mut covered = [0usize; 7];
    let runs = 100;
    for seed in 0..runs {
        let d = run(&trace(f, 0.0005, 1000 + seed)).diagnostics;
        let fitted = [
            d.centre_u,
            d.centre_v,
            d.scale_mismatch,
            d.squareness,
            d.servo_mismatch,
            d.backlash_u,
            d.backlash_v,
        ];
        for (i, (x, t)) in fitted.iter().zip(truth).enumerate() {
            if (x.value.unwrap() - t).abs() <= x.half_width.unwrap() {
                covered[i] += 1;
            }
        }
    }
    for (i, c) in covered.iter().enumerate() {
        assert!(*c >= 88, "diagnostic {i}: covered {c} of {runs}");
    }
}

/// A trace with a deviation column per direction (CCW +1 µm, CW −1 µm, every degree).
fn two_columns() -> String {
    let mut csv = String::from("# radius: 100 mm\nangle (deg); ccw (mm); cw (mm)\n");
    for k in 0..360 {
        csv.push_str(&format!("{k}; 0.001; -0.001\n"));
    }
    csv
}

/// A deviation column per direction with a value that is not a number: the message names the
/// column's direction and the line.
// Found by cargo-mutants: the CCW/CW word of this message (the reader's match on the column's
// direction) was untested.
#[test]
fn a_bad_value_names_the_directions_column() {
    let csv = two_columns();
    for (from, to, word) in [
        (
            "\n5; 0.001; -0.001\n",
            "\n5; fast; -0.001\n",
            "CCW deviation",
        ),
        ("\n5; 0.001; -0.001\n", "\n5; 0.001; slow\n", "CW deviation"),
    ] {
        let bad = csv.replacen(from, to, 1);
        let e = evaluate_input(json!({ "csv": bad }))
            .unwrap_err()
            .to_string();
        // Line 1 is the header's radius, line 2 the column names, angle 0 on line 3.
        assert!(e.contains("line 8: "), "{to}: {e}");
        assert!(e.contains(&format!("{word} \"")), "{to}: {e}");
        assert!(!e.contains(&format!("C{word}")), "{to}: {e}");
    }
}

/// The limits of what a circular test reads: 20 points round the circle are enough and 19 are
/// refused, with the count; a file whose test column names one test is read as that test.
// Found by cargo-mutants: the boundaries of the point count and of the number of tests
// (`read_trace`) were untested.
#[test]
fn twenty_points_and_one_named_test_are_read() {
    let good = trace(Faults::default(), 0.0, 1);
    let (head, points): (Vec<&str>, Vec<&str>) = good
        .lines()
        .partition(|l| l.starts_with('#') || l.starts_with("angle"));
    // Every 18th point of the CCW run: 20 points, 18° apart, round the whole circle.
    let spread: Vec<&str> = points.iter().take(360).step_by(18).copied().collect();
    assert_eq!(spread.len(), 20);
    let file = |pts: &[&str]| format!("{}\n{}\n", head.join("\n"), pts.join("\n"));
    let b = run(&file(&spread));
    assert!(
        b.g_ccw.is_some() && b.g_cw.is_none(),
        "{:?} {:?}",
        b.g_ccw,
        b.g_cw
    );
    let e = evaluate_input(json!({ "csv": file(&spread[..19]) }))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("needs at least 20 points round the circle, got 19"),
        "{e}"
    );
    // The same trace with a test column naming one test: the same result.
    let named = good
        .replace("; direction\n", "; direction; test\n")
        .replace("; ccw\n", "; ccw; left\n")
        .replace("; cw\n", "; cw; left\n");
    let (plain, with_test) = (run(&good), run(&named));
    assert_eq!(plain.g_ccw, with_test.g_ccw);
    assert_eq!(plain.g_cw, with_test.g_cw);
}
/// Known by construction: CCW `a·cos 3θ + c/2`, CW `a·cos 3θ − c/2` (no noise). The
/// least-squares circle of both is the nominal one (mean 0, no first harmonic), so
/// G_ccw = G_cw = 2a, G = 2a + c, H = c; the third harmonic has amplitude a.
#[test]
fn g_and_h_known_by_construction() {
    let (a, c) = (0.004, 0.003);
    let mut csv = String::from("# radius: 150 mm\nangle (deg); ccw (mm); cw (mm)\n");
    for k in 0..720 {
        let th = k as f64 * 0.5;
        let w = a * (3.0 * th.to_radians()).cos();
        csv.push_str(&format!("{th}; {}; {}\n", w + c / 2.0, w - c / 2.0));
    }
    let b = run(&csv);
    assert!((b.g_ccw.unwrap() - 2.0 * a).abs() < 1e-9, "{:?}", b.g_ccw);
    assert!((b.g_cw.unwrap() - 2.0 * a).abs() < 1e-9, "{:?}", b.g_cw);
    assert!((b.g - (2.0 * a + c)).abs() < 1e-9, "{}", b.g);
    assert!((b.h.unwrap() - c).abs() < 1e-9, "{:?}", b.h);
    let h3 = &b.diagnostics.harmonics[0];
    assert_eq!(h3.order, 3);
    assert!((h3.amplitude - a).abs() < 1e-9, "{}", h3.amplitude);
    assert_eq!(b.radius, 150.0);
}

/// A tolerance of G: at G it passes, just under it fails.
#[test]
fn verdict_against_a_tolerance_of_g() {
    let csv = trace(
        Faults {
            squareness: 30e-6,
            ..Default::default()
        },
        0.0,
        1,
    );
    let g = run(&csv).g;
    let judge = |t: f64| {
        evaluate_input(json!({ "csv": csv, "tolerance": t }))
            .unwrap()
            .pass
    };
    assert_eq!(judge(g), Some(true));
    assert_eq!(judge(f64::from_bits(g.to_bits() - 1)), Some(false));
    assert_eq!(judge(0.0), None);
}

/// A reversal spike at u's reversal (0°, CCW), synthesised as `h·exp(−φ/w)`, is found with its
/// height and width.
#[test]
fn a_reversal_spike_is_measured() {
    let (h, w) = (0.006, 2.0f64.to_radians());
    let mut csv = String::from("# radius: 100 mm\nangle (deg); deviation (mm); direction\n");
    for (d, name) in [(1.0, "ccw"), (-1.0, "cw")] {
        for k in 0..720 {
            let th = (k as f64 * 0.5).to_radians();
            let phi = (d * th).rem_euclid(2.0 * PI);
            let spike = if d > 0.0 && phi < 0.5 {
                h * (-phi / w).exp()
            } else {
                0.0
            };
            csv.push_str(&format!("{}; {spike}; {name}\n", th.to_degrees()));
        }
    }
    let b = run(&csv);
    let s = b
        .diagnostics
        .spikes
        .iter()
        .find(|s| s.at == 0.0 && s.direction == "ccw")
        .unwrap();
    // The fault model's columns (harmonics, backlash) take a little of the spike before it is
    // fitted on what they leave: height within 15 %, width within 25 %.
    assert!((s.height - h).abs() < 0.15 * h, "height {}", s.height);
    assert!((s.width - 2.0).abs() < 0.5, "width {}", s.width);
    let other = b
        .diagnostics
        .spikes
        .iter()
        .find(|s| s.at == 90.0 && s.direction == "ccw")
        .unwrap();
    assert!(
        other.height.abs() < 0.15 * h,
        "no spike at 90°: {}",
        other.height
    );
}

/// Bad files name their line.
#[test]
fn bad_traces_name_their_line() {
    let good = trace(Faults::default(), 0.0, 1);
    let cases = [
        (
            good.replacen("; ccw\n", "; sideways\n", 1),
            "csv: line 4: the direction must be ccw or cw",
        ),
        (
            good.replace("deviation (µm)", "deviation"),
            "csv: line 3: give the unit of the deviation",
        ),
        (
            good.replace("angle (deg)", "angle (grad)"),
            "csv: line 3: the angle's unit must be deg or rad",
        ),
        (
            good.replace("# radius: 100 mm", "# radius: 100 furlongs"),
            "csv: line 1: unknown unit of the radius",
        ),
        (
            "angle (deg); deviation (µm)\n0; 1\n".to_string(),
            "csv: needs at least 20 points",
        ),
        (
            good.replacen("; ccw\n", "; x; ccw\n", 1)
                .replacen("0.5; ", "0.5; x", 1),
            "csv: line 4:",
        ),
    ];
    for (text, want) in cases {
        let e = evaluate_input(json!({ "csv": text }))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(want), "got: {e}\nwant: {want}");
    }
    let e = evaluate(
        &BallbarInput::read(&json!({ "csv": good.replace("# radius: 100 mm\n", "") })).unwrap(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("radius: give the ball-bar's length"), "{e}");
}

/// The radius and the feed are 0 (read from the file's header) or at least 1 mm and 1 mm/min:
/// a value between is refused with the field's name, 0 and 1 are accepted.
// Found by cargo-mutants: `BallbarInput::check`'s bounds (and the whole check) were untested
// natively (the page's field validation tests them through the schema's limits only).
#[test]
fn radius_and_feed_are_zero_or_at_least_one() {
    let csv = trace(Faults::default(), 0.0, 1);
    for field in ["radius", "feed"] {
        for (v, accepted) in [
            (0.0, true),
            (0.5, false),
            (0.999, false),
            (1.0, true),
            (50.0, true),
        ] {
            let got = BallbarInput::read(&json!({ "csv": csv, field: v }));
            match got {
                Ok(_) => assert!(accepted, "{field} = {v} accepted"),
                Err(e) => {
                    assert!(!accepted, "{field} = {v} refused: {e}");
                    assert!(e.to_string().starts_with(&format!("{field}: ")), "{e}");
                    assert!(e.to_string().contains("at least 1"), "{e}");
                }
            }
        }
    }
}

/// A trace sampled on the reversal points themselves (every whole degree: 0°, 90°, 180° and
/// 270° included). At a reversal the axis stands still between its two directions, so the
/// lost motion is split: no offset there (the model's `sgn` is 0 at the reversal). The
/// backlash is recovered as from a trace between the reversals, to second order in `b/R`.
// Found by cargo-mutants: the model's `sgn` tested against 0 at exactly the reversal (`==`
// instead of `<` 1e-12: sin 0 = 0 then counts as a direction, and sin 180° = 1.2e-16 too).
#[test]
fn backlash_sampled_on_the_reversals() {
    let (bu, bv) = (0.01, 0.006);
    let mut csv = format!("# radius: {R} mm\nangle (deg); deviation (mm); direction\n");
    for (d, name) in [(1.0, "ccw"), (-1.0, "cw")] {
        for k in 0..360 {
            let th = (k as f64).to_radians();
            // Direction of travel of u (−d·sin θ) and v (d·cos θ), 0 at their reversals by
            // construction (k = 0, 180 for u; 90, 270 for v), not by the rounding of sin, cos.
            let su = if k % 180 == 0 {
                0.0
            } else {
                -d * th.sin().signum()
            };
            let sv = if k % 180 == 90 {
                0.0
            } else {
                d * th.cos().signum()
            };
            let (u, v) = (R * th.cos() - 0.5 * bu * su, R * th.sin() - 0.5 * bv * sv);
            csv.push_str(&format!("{k}; {}; {name}\n", u.hypot(v) - R));
        }
    }
    let d = run(&csv).diagnostics;
    // Second-order terms: (b/2)²/R ≈ 2.5e-7 mm.
    assert!(
        (value(&d.backlash_u) - bu).abs() < 2e-6,
        "{:?}",
        d.backlash_u
    );
    assert!(
        (value(&d.backlash_v) - bv).abs() < 2e-6,
        "{:?}",
        d.backlash_v
    );
}

/// The radius and the feed given as inputs override the file's `# radius:` and `# feed:`
/// lines; the file's feed is checked only when it is the one used.
// Found by cargo-mutants: which of the two values wins was untested (`>` as `<`, `==` as `!=`).
#[test]
fn the_inputs_radius_and_feed_override_the_files() {
    let f = Faults {
        squareness: 50e-6,
        lag: 0.002,
        ..Default::default()
    };
    let csv = trace(f, 0.0, 3);
    let from_file = run(&csv);
    assert_eq!((from_file.radius, from_file.feed), (R, Some(FEED)));
    let b = evaluate_input(json!({ "csv": csv, "radius": 2.0 * R, "feed": 2.0 * FEED })).unwrap();
    assert_eq!((b.radius, b.feed), (2.0 * R, Some(2.0 * FEED)));
    // The same sin 2θ coefficient read on twice the radius: half the squareness (µm/m); the
    // servo mismatch τ = 2c/(R·ω) with ω = F/R: the feed doubled, half the lag.
    let sq = |b: &Ballbar| value(&b.diagnostics.squareness);
    let servo = |b: &Ballbar| value(&b.diagnostics.servo_mismatch);
    assert!(
        (sq(&b) - sq(&from_file) / 2.0).abs() < 1e-9,
        "{} {}",
        sq(&b),
        sq(&from_file)
    );
    assert!(
        (servo(&b) - servo(&from_file) / 2.0).abs() < 1e-9,
        "{} {}",
        servo(&b),
        servo(&from_file)
    );

    // A file whose feed is out of range: refused when it is used, ignored when the input gives
    // the feed.
    let slow = csv.replace("# feed: 1000 mm/min", "# feed: 0.5 mm/min");
    assert_ne!(slow, csv);
    let e = evaluate_input(json!({ "csv": slow })).unwrap_err();
    assert!(
        e.to_string().starts_with("csv: the file's feed must be"),
        "{e}"
    );
    let b = evaluate_input(json!({ "csv": slow, "feed": FEED })).unwrap();
    assert_eq!(b.feed, Some(FEED));
}

/// A trace run one way only (CCW or CW): its own G, no G of the other direction, and no
/// hysteresis (it needs both).
// Found by cargo-mutants: `both` directions tested as CW twice.
#[test]
fn one_direction_has_no_hysteresis() {
    let csv = trace(
        Faults {
            backlash: [0.004, 0.0],
            ..Default::default()
        },
        0.0,
        4,
    );
    for (keep, other) in [("ccw", "cw"), ("cw", "ccw")] {
        let one: String = csv
            .lines()
            .filter(|l| !l.ends_with(&format!("; {other}")))
            .map(|l| format!("{l}\n"))
            .collect();
        let b = run(&one);
        assert_eq!(b.h, None, "{keep} only");
        let (mine, theirs) = if keep == "ccw" {
            (b.g_ccw, b.g_cw)
        } else {
            (b.g_cw, b.g_ccw)
        };
        assert_eq!(theirs, None, "{keep} only");
        assert_eq!(mine, Some(b.g), "{keep} only: G is its own");
    }
}

/// The 95 % intervals have the width of the closed form: on a whole circle sampled evenly both
/// ways, the `cos θ` and `cos 2θ` columns are orthogonal to every other column of the model, so
/// each coefficient's standard error is `σ·√(2/720)`, and the half width `t₀.₉₇₅·se` (t ≈ 1.963
/// at 704 degrees of freedom), times the diagnostic's scale: 1 for the centre, `2/R·10⁶` for
/// the scale mismatch in ppm. Within 10 % (the residuals' σ estimated from 720 points).
// Found by cargo-mutants: `t·se·|scale|` with `+` or `/` in place of `*` gave intervals that
// still covered the truth (too wide), so the coverage test alone passed.
#[test]
fn interval_widths_follow_the_closed_form() {
    let sigma = 0.0005;
    let f = Faults {
        centre: [0.004, -0.003],
        scale: [12e-6, -5e-6],
        ..Default::default()
    };
    let d = run(&trace(f, sigma, 11)).diagnostics;
    let se = sigma * (2.0f64 / 720.0).sqrt();
    for (name, fitted, scale) in [
        ("centre u", &d.centre_u, 1.0),
        ("centre v", &d.centre_v, 1.0),
        ("scale mismatch", &d.scale_mismatch, 2.0 / R * 1e6),
    ] {
        let want = 1.963 * se * scale;
        let got = fitted.half_width.unwrap();
        assert!(
            (got / want - 1.0).abs() < 0.1,
            "{name}: half width {got}, closed form {want}"
        );
    }
}

/// G, G per direction and H do not depend on where the circle is or on its radius: the
/// least-squares circle is removed first. The trace of `g_and_h_known_by_construction` with a
/// radius offset and a centre offset added gives the same values.
// Found by cargo-mutants: the circle's removal with `+` in place of `−` went unseen on traces
// whose least-squares circle is the nominal one.
#[test]
fn g_and_h_do_not_depend_on_the_circles_place() {
    let (a, c) = (0.004, 0.003);
    let (r0, eu, ev) = (0.02, 0.011, -0.007);
    let csv = |c: f64| {
        let mut csv = String::from("# radius: 150 mm\nangle (deg); ccw (mm); cw (mm)\n");
        for k in 0..720 {
            let th = (k as f64 * 0.5).to_radians();
            let w = a * (3.0 * th).cos() + r0 + eu * th.cos() + ev * th.sin();
            let (ccw, cw) = (w + c / 2.0, w - c / 2.0);
            csv.push_str(&format!("{}; {ccw}; {cw}\n", k as f64 * 0.5));
        }
        csv
    };
    let b = run(&csv(c));
    assert!((b.g_ccw.unwrap() - 2.0 * a).abs() < 1e-9, "{:?}", b.g_ccw);
    assert!((b.g_cw.unwrap() - 2.0 * a).abs() < 1e-9, "{:?}", b.g_cw);
    assert!((b.g - (2.0 * a + c)).abs() < 1e-9, "{}", b.g);
    assert!((b.h.unwrap() - c).abs() < 1e-9, "{:?}", b.h);
    assert!((value(&b.diagnostics.centre_u) - eu).abs() < 1e-9);
    assert!((value(&b.diagnostics.centre_v) - ev).abs() < 1e-9);
    // The deviations shown are those about that circle: the offsets gone, point by point.
    for (i, (th, dev)) in b.angle.iter().zip(&b.deviation).enumerate() {
        let want = a * (3.0 * th.to_radians()).cos() + b.direction[i] * c / 2.0;
        assert!(
            (dev - want).abs() < 1e-9,
            "point {i} at {th}°: {dev}, want {want}"
        );
    }
    // Without the split between the directions the model holds the trace exactly: the fitted
    // curve shown is the cyclic error alone, about the same circle.
    let b = run(&csv(0.0));
    for (i, (th, fit)) in b.angle.iter().zip(&b.fitted).enumerate() {
        let want = a * (3.0 * th.to_radians()).cos();
        assert!(
            (fit - want).abs() < 1e-9,
            "point {i} at {th}°: fitted {fit}, want {want}"
        );
    }
}

/// The cyclic error's harmonics 3 to 6, each with its own amplitude and phase
/// (`A·cos(kθ − φ)`), on a trace with a centre offset, a radius offset and a scale mismatch:
/// each harmonic is recovered exactly (the model holds the trace), in order of amplitude.
// Found by cargo-mutants: only the third harmonic was tested, whose column index is the same
// with `+ 2·i` and `− 2·i`.
#[test]
fn each_harmonic_with_its_amplitude_and_phase() {
    let harmonics = [
        (3, 0.002, 30.0f64),
        (4, 0.0015, -100.0),
        (5, 0.001, 170.0),
        (6, 0.0005, 60.0),
    ];
    let mut csv = String::from("# radius: 100 mm\nangle (deg); deviation (mm); direction\n");
    for name in ["ccw", "cw"] {
        for k in 0..720 {
            let th = (k as f64 * 0.5).to_radians();
            let mut w = 0.01 + 0.004 * th.cos() - 0.002 * th.sin() + 0.003 * (2.0 * th).cos();
            for (order, a, phase) in harmonics {
                w += a * (order as f64 * th - phase.to_radians()).cos();
            }
            csv.push_str(&format!("{}; {w}; {name}\n", k as f64 * 0.5));
        }
    }
    let got = run(&csv).diagnostics.harmonics;
    assert_eq!(
        got.iter().map(|h| h.order).collect::<Vec<_>>(),
        [3, 4, 5, 6]
    );
    for (h, (order, a, phase)) in got.iter().zip(harmonics) {
        assert!(
            (h.amplitude - a).abs() < 1e-9,
            "order {order}: amplitude {}",
            h.amplitude
        );
        assert!(
            (h.phase - phase).abs() < 1e-6,
            "order {order}: phase {}",
            h.phase
        );
    }
}

/// A reversal spike at every reversal, each direction its own heights: each is found at its
/// reversal and in its direction (`h·exp(−φ/w)`, φ travelled since the reversal).
// Found by cargo-mutants: the spikes were tested at u's reversal at 0° only (where 0° − q and
// 0° + q agree, and so do the CW and CCW windows' angle for q = 0).
#[test]
fn a_spike_at_each_reversal_and_direction() {
    let w = 1.5f64.to_radians();
    let at = [0.0f64, 90.0, 180.0, 270.0];
    let heights = [
        (1.0, "ccw", [0.006, 0.004, 0.005, 0.003]),
        (-1.0, "cw", [0.002, 0.007, 0.0035, 0.0045]),
    ];
    let mut csv = String::from("# radius: 100 mm\nangle (deg); deviation (mm); direction\n");
    for (d, name, hs) in heights {
        for k in 0..720 {
            let th = (k as f64 * 0.5).to_radians();
            let mut r = 0.0;
            for (q, h) in at.iter().zip(hs) {
                let phi = (d * (th - q.to_radians())).rem_euclid(2.0 * PI);
                if phi < 0.5 {
                    r += h * (-phi / w).exp();
                }
            }
            csv.push_str(&format!("{}; {r}; {name}\n", k as f64 * 0.5));
        }
    }
    let spikes = run(&csv).diagnostics.spikes;
    for (_, name, hs) in heights {
        for (q, h) in at.iter().zip(hs) {
            let s = spikes
                .iter()
                .find(|s| s.at == *q && s.direction == name)
                .unwrap();
            // The model's columns (backlash steps, harmonics) take part of each spike's tail
            // before it is fitted on what they leave: heights within 15 %, widths shortened
            // (0.8°–1.2° measured for 1.5°).
            assert!(
                (s.height - h).abs() < 0.15 * h,
                "{name} at {q}°: height {}, want {h}",
                s.height
            );
            assert!(
                (0.6..=1.8).contains(&s.width),
                "{name} at {q}°: width {}",
                s.width
            );
        }
    }
}

/// H when the two directions are sampled at different angles: the CW trace is interpolated at
/// the CCW trace's angles, across 0° = 360° too. `f(θ) = a·cos 3θ + b·sin 2θ` (not even in θ, so
/// that the wrap's two sides differ); CCW `f + c/2` and CW `f − c/2` every half degree, one of
/// them a quarter degree later (the CCW trace then begins before the CW trace's first angle,
/// or ends after its last): H = c to within linear interpolation's error, `(Δθ)²/8·max|f''|`
/// ≈ 0.5 nm for a half-degree step.
// Found by cargo-mutants: the interpolation (and its wrap at 0°) was untested: the CW and CCW
// traces of the other tests share their angles.
#[test]
fn hysteresis_between_sampled_angles() {
    let (a, b, c) = (0.004, 0.003, 0.003);
    for (ccw_start, cw_start) in [(0.0, 0.25), (0.25, 0.0)] {
        let mut csv = String::from("# radius: 150 mm\nangle (deg); deviation (mm); direction\n");
        for (d, name, start) in [(1.0, "ccw", ccw_start), (-1.0, "cw", cw_start)] {
            for k in 0..720 {
                let deg = start + k as f64 * 0.5;
                let th = f64::to_radians(deg);
                let r = a * (3.0 * th).cos() + b * (2.0 * th).sin() + d * c / 2.0;
                csv.push_str(&format!("{deg}; {r}; {name}\n"));
            }
        }
        let h = run(&csv).h.unwrap();
        assert!(
            (h - c).abs() < 1e-6,
            "CCW from {ccw_start}°, CW from {cw_start}°: H {h}, want {c}"
        );
    }
}

/// The header's units of the radius and the feed (mm or inches; mm/min, m/min or mm/s), and
/// a value that is not a number named with its line.
// Found by cargo-mutants: only `mm` and `mm/min` were read in tests, and the line of a bad
// value was not checked.
#[test]
fn header_units_of_radius_and_feed() {
    let good = trace(Faults::default(), 0.0, 1);
    for (from, to, radius, feed) in [
        ("# radius: 100 mm", "# radius: 4 in", 101.6, FEED),
        ("# radius: 100 mm", "# radius: 4 inch", 101.6, FEED),
        ("# feed: 1000 mm/min", "# feed: 1.5 m/min", R, 1500.0),
        ("# feed: 1000 mm/min", "# feed: 20 mm/s", R, 1200.0),
    ] {
        let b = run(&good.replace(from, to));
        assert!(
            (b.radius - radius).abs() < 1e-12,
            "{to}: radius {}",
            b.radius
        );
        assert!(
            (b.feed.unwrap() - feed).abs() < 1e-9,
            "{to}: feed {:?}",
            b.feed
        );
    }
    let e = evaluate(
        &BallbarInput::read(&json!({ "csv": good.replace("# feed: 1000", "# feed: fast") }))
            .unwrap(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("csv: line 2: the feed is not a number"),
        "{e}"
    );
}

/// A deviation column per direction with a unit the reader does not know: the message names
/// the column's direction.
// Found by cargo-mutants: the CCW/CW word of the message was untested.
#[test]
fn an_unknown_unit_names_the_directions_column() {
    let csv = two_columns();
    for (from, to, word) in [
        ("ccw (mm)", "ccw (furlongs)", "CCW deviation"),
        ("; cw (mm)", "; cw (furlongs)", "CW deviation"),
    ] {
        let bad = csv.replacen(from, to, 1);
        let e = evaluate_input(json!({ "csv": bad }))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("give the unit of the {word} in the header")),
            "{to}: {e}"
        );
    }
}
