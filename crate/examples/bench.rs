//! Native timings of the engine's heavy kernels, for `npm run bench` (scripts/bench.mjs times the
//! same kernels as WebAssembly in Node on the same inputs and prints the ratio).
//! Prints one JSON object per line: `{"name": ..., "ms": ..., "check": ...}`, for the nonlinear
//! maxima also `"evaluations"`: orientation evaluations per move (native only, from
//! `Deviation::peak_counted`). With `BENCH_STEP` set, waits for a line on stdin before each
//! kernel (`step`): scripts/bench.mjs alternates the native and wasm timings kernel by kernel.

use fiveaxis::cubic::{self, CubicGrid, CubicInput};
use fiveaxis::nonlinear::{self, Deviation, Move};
use fiveaxis::rotary::{Pose, RotaryType};
use fiveaxis::sshape::study::{self, SShapeCase, SShapeDefectsInput};
use fiveaxis::toolpath::export::{ParsedToolpath, Reading};
use fiveaxis::toolpath::ToolpathReadInput;
use fiveaxis::volumetric;
use serde_json::{json, Value};
use std::time::Instant;

/// The machine object of a preset of `public/presets/machines.json` (the same file
/// scripts/bench.mjs reads).
fn preset(prefix: &str) -> Result<Value, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/presets/machines.json"
    ))?;
    let all: Value = serde_json::from_str(&text)?;
    all["presets"]
        .as_array()
        .and_then(|l| {
            l.iter()
                .find(|p| p["name"].as_str().is_some_and(|n| n.starts_with(prefix)))
        })
        .map(|p| p["machine"].clone())
        .ok_or_else(|| format!("no machine preset {prefix}").into())
}

/// Location errors of the volumetric benchmark (same as scripts/bench.mjs).
fn volumetric_errors() -> Value {
    json!({ "E_C0Y": 0.001, "E_B0Z": -0.0008, "E_Y0A": 0.005 })
}

/// Error motions of the volumetric benchmark: polynomials, a measured table, constants, on
/// every axis (same as scripts/bench.mjs).
fn volumetric_motions() -> Value {
    json!({
        "E_XX": { "poly": [0, 1e-5, 2e-9] },
        "E_BX": { "position": [-400, -200, 0, 200, 400], "value": [-0.0003, 0.0001, 0, 0.0002, -0.0001] },
        "E_YY": { "poly": [0.001, -8e-6] },
        "E_AY": 0.0002,
        "E_ZZ": { "poly": [0, 5e-6] },
        "E_XZ": { "position": [-300, 0, 300], "value": [0.002, 0, 0.003] },
        "E_XC": { "position": [0, 90, 180, 270, 360], "value": [0, 0.002, 0, -0.002, 0] },
        "E_CC": 0.001,
        "E_ZA": 0.003,
    })
}

/// The moves of the benchmark, degrees `[θk0, θm0, θk1, θm1]`, from the same formula as
/// scripts/bench.mjs.
fn moves(n: usize) -> Vec<[f64; 4]> {
    (0..n)
        .map(|i| {
            let x = i as f64 * 0.001;
            let k0 = 180.0 * (7.3 * x).sin();
            let m0 = 90.0 * (3.1 * x + 1.0).sin();
            let dk = 60.0 * (1.7 * x + 2.0).sin();
            let dm = 60.0 * (2.9 * x + 3.0).sin();
            [k0, m0, k0 + dk, m0 + dm]
        })
        .collect()
}

/// Short moves (real toolpath segments): the start angles of [`moves`], increments under 2.5°
/// per axis, so `|Δθk| + |Δθm| < 5°`. Degrees, from the same formula as scripts/bench.mjs.
fn short_moves(n: usize) -> Vec<[f64; 4]> {
    (0..n)
        .map(|i| {
            let x = i as f64 * 0.001;
            let k0 = 180.0 * (7.3 * x).sin();
            let m0 = 90.0 * (3.1 * x + 1.0).sin();
            let dk = 2.5 * (1.3 * x + 0.5).sin();
            let dm = 2.5 * (2.3 * x + 1.5).sin();
            [k0, m0, k0 + dk, m0 + dm]
        })
        .collect()
}

/// The benchmark toolpath: `n` points `[x, y, z, i, j, k]` (mm, unit axis), from the same formula
/// as scripts/bench.mjs: the tool tilted 10° to 60° from Z, its azimuth swinging ±170°, at most
/// about 0.5° of rotary motion a segment (a finishing path).
pub fn bench_path(n: usize) -> Vec<[f64; 6]> {
    (0..n)
        .map(|i| {
            let s = i as f64;
            let tilt = (35.0 + 25.0 * (0.0071 * s).sin()).to_radians();
            let az = (170.0 * (0.003 * s).sin()).to_radians();
            [
                100.0 * (0.001 * s).sin(),
                100.0 * (0.0013 * s).cos(),
                1e-5 * s,
                tilt.sin() * az.cos(),
                tilt.sin() * az.sin(),
                tilt.cos(),
            ]
        })
        .collect()
}

/// A CLSF of `n` statements as NX writes it (MSYS/, RAPID, FEDRAT/, six-number GOTOs), same
/// formula as scripts/bench.mjs.
pub fn clsf(n: usize) -> String {
    let mut s = String::from(
        "TOOL PATH/BENCH,TOOL,T1\nMSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n",
    );
    for i in 0..n.saturating_sub(2) {
        let x = i as f64;
        if i % 200 == 0 {
            s.push_str("RAPID\n");
        } else if i % 200 == 2 {
            s.push_str("FEDRAT/MMPM,1500.0000\n");
        } else {
            let (t, a) = (
                (30.0 + 20.0 * (0.003 * x).sin()).to_radians(),
                (0.002 * x).to_radians() * 57.0,
            );
            s.push_str(&format!(
                "GOTO/{:.4},{:.4},{:.4},{:.7},{:.7},{:.7}\n",
                100.0 * (0.001 * x).sin(),
                100.0 * (0.0013 * x).cos(),
                1e-3 * x,
                t.sin() * a.cos(),
                t.sin() * a.sin(),
                t.cos()
            ));
        }
    }
    s
}

/// An ISO program of `n` blocks for an A/C machine (G43.4, G1 X Y Z A C, an arc every 100
/// blocks), same formula as scripts/bench.mjs.
pub fn iso(n: usize) -> String {
    let mut s = String::from("%\nO1000\nG90 G21 G17\nG43.4 H1\nG0 X0 Y0 Z50 A0 C0\n");
    for i in 0..n.saturating_sub(6) {
        let x = i as f64;
        if i % 100 == 50 {
            s.push_str(&format!(
                "N{i} G2 X{:.4} Y{:.4} R50.\n",
                100.0 * (0.001 * x).sin() + 1.0,
                100.0 * (0.0013 * x).cos()
            ));
        } else {
            s.push_str(&format!(
                "N{i} G1 X{:.4} Y{:.4} Z{:.4} A{:.4} C{:.4}\n",
                100.0 * (0.001 * x).sin(),
                100.0 * (0.0013 * x).cos(),
                1e-3 * x,
                -30.0 - 20.0 * (0.003 * x).sin(),
                0.11 * x
            ));
        }
    }
    s.push_str("M30\n%\n");
    s
}

/// In a round driven by scripts/bench.mjs (`BENCH_STEP` set), says `ready` and waits for a line
/// on stdin before each kernel: the driver times each kernel natively, then as WebAssembly,
/// while the other side waits.
fn step() {
    if std::env::var_os("BENCH_STEP").is_some() {
        println!("ready");
        let mut line = String::new();
        // The end of the driver's input (or an unreadable one): the driver has gone, stop.
        if !matches!(std::io::stdin().read_line(&mut line), Ok(n) if n > 0) {
            std::process::exit(1);
        }
    }
}

/// Best of at least `repeat` timed runs and at least a second of them, milliseconds, and the last
/// result's checksum, after untimed runs for a second (at least one): as scripts/bench.mjs times
/// the WebAssembly side (there, hot code is optimised while it runs, and the machine's slow
/// spells last up to seconds).
fn time<T>(repeat: usize, f: impl FnMut() -> T, check: impl Fn(&T) -> f64) -> (f64, f64) {
    time_for(1.0, 1, repeat, f, check)
}

/// [`time`] with at least `secs` and at least `warm_runs` untimed runs, then at least `secs` and
/// at least `repeat` timed (`secs` 0: exactly `warm_runs`, then exactly `repeat`).
fn time_for<T>(
    secs: f64,
    warm_runs: usize,
    repeat: usize,
    mut f: impl FnMut() -> T,
    check: impl Fn(&T) -> f64,
) -> (f64, f64) {
    step();
    let warm = Instant::now();
    let mut i = 0;
    while i < warm_runs || warm.elapsed().as_secs_f64() < secs {
        f();
        i += 1;
    }
    let mut best = f64::INFINITY;
    let mut sum = 0.0;
    let timed = Instant::now();
    let mut i = 0;
    while i < repeat || timed.elapsed().as_secs_f64() < secs {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
        sum = check(&r);
        i += 1;
    }
    (best, sum)
}

/// The number at `pointer` of an export's result (NaN when the export failed or has none).
fn number(r: &fiveaxis::Result<Value>, pointer: &str) -> f64 {
    r.as_ref()
        .ok()
        .and_then(|v| v.pointer(pointer))
        .and_then(Value::as_f64)
        .unwrap_or(f64::NAN)
}

fn report(name: &str, (ms, check): (f64, f64)) {
    println!("{{\"name\":\"{name}\",\"ms\":{ms:.3},\"check\":{check:.12e}}}");
}

/// [`report`] with the average number of orientation evaluations per move of `moves` (degrees).
fn report_counted(name: &str, timed: (f64, f64), t: RotaryType, moves: &[[f64; 4]]) {
    let total: usize = moves
        .iter()
        .map(|m| {
            let [k0, m0, k1, m1] = m.map(f64::to_radians);
            let mv = Move::new(t, Pose::new(k0, m0), Pose::new(k1, m1));
            Deviation::new(mv).peak_counted().1
        })
        .sum();
    let (ms, check) = timed;
    let evaluations = total as f64 / moves.len() as f64;
    println!(
        "{{\"name\":\"{name}\",\"ms\":{ms:.3},\"check\":{check:.12e},\"evaluations\":{evaluations:.3}}}"
    );
}

/// The sphere test's benchmark input (same as scripts/bench.mjs): the B/C tilting table preset,
/// the sphere 150 mm off C's axis and 50 mm high, and 200 probed poses (C and B on integer
/// formulas, B within ±90°) whose centres `probeSimulate` gives on the machine with the sample's
/// errors, plus ±1 µm of integer-formula noise, written to 6 decimals. The JSON `probeIdentify`
/// takes, the same on both sides.
fn probe_input() -> Result<Value, Box<dyn std::error::Error>> {
    let machine = preset("B/C tilting table")?;
    let sphere = json!({ "x": 150, "y": 0, "height": 50 });
    let poses: Vec<(i64, i64)> = (0..200i64)
        .map(|i| ((i * 37) % 360 - 180, (i * 53) % 181 - 90))
        .collect();
    let mut measured = machine.clone();
    measured["errors"] =
        json!({ "E_X0B": 0.012, "E_Z0B": -0.008, "E_A0B": 0.005, "E_C0B": -0.003 });
    let sim = fiveaxis::api::call(
        "probeSimulate",
        &json!({ "machine": measured, "sphere": sphere,
            "k": poses.iter().map(|p| p.0).collect::<Vec<_>>(),
            "m": poses.iter().map(|p| p.1).collect::<Vec<_>>() }),
    )?;
    let mut csv = String::from("pose;C_deg;B_deg;X_mm;Y_mm;Z_mm\n");
    for (i, (p, s)) in poses
        .iter()
        .zip(sim["poses"].as_array().ok_or("probeSimulate: no poses")?)
        .enumerate()
    {
        let c: Vec<f64> = (0..3)
            .map(|a| {
                let noise = (((3 * i as i64 + a as i64) * 7919) % 2001 - 1000) as f64 * 1e-6;
                s["measured"][a].as_f64().unwrap_or(f64::NAN) + noise
            })
            .collect();
        csv.push_str(&format!(
            "{};{};{};{:.6};{:.6};{:.6}\n",
            i + 1,
            p.0,
            p.1,
            c[0],
            c[1],
            c[2]
        ));
    }
    Ok(json!({ "machine": machine, "sphere": sphere, "csv": csv }))
}

/// The checksum of an identification (same as scripts/bench.mjs): its values and the spread
/// after correction.
fn probe_check(r: &Value) -> f64 {
    let values: f64 = r["estimates"].as_array().map_or(f64::NAN, |l| {
        l.iter().filter_map(|e| e["value"].as_f64()).sum()
    });
    values + r["after"]["sigma"].as_f64().unwrap_or(f64::NAN)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = bench_path(1_000_000);
    let axes: Vec<nalgebra::Vector3<f64>> = path
        .iter()
        .map(|p| nalgebra::Vector3::new(p[3], p[4], p[5]))
        .collect();
    let machine = fiveaxis::machine::Machine::standard()?;
    let (ms, check) = time(
        1,
        || fiveaxis::toolpath::compare(&machine, &axes, 100.0, 0.01),
        |r| {
            r.as_ref()
                .map_or(f64::NAN, |rows| rows.iter().map(|r| r.max + r.mean).sum())
        },
    );
    // Orientation evaluations per segment of the exact maximum, over the 12 types.
    let (mut evaluations, mut segments) = (0usize, 0usize);
    for t in RotaryType::ALL {
        let model = fiveaxis::toolpath::machine_of_type(&machine, t).build()?;
        let f = fiveaxis::toolpath::follow(&model, &axes)?;
        let lay = model.layout;
        let pose = |i: usize| Pose::new(lay.k_factor * f.k[i], lay.m_factor * f.m[i]);
        for i in 1..f.k.len() {
            evaluations += Deviation::new(Move::new(t, pose(i - 1), pose(i)))
                .peak_counted()
                .1;
            segments += 1;
        }
    }
    let per = evaluations as f64 / segments.max(1) as f64;
    println!(
        "{{\"name\":\"toolpath: 10^6 points on the 12 types\",\"ms\":{ms:.3},\"check\":{check:.12e},\"evaluations\":{per:.3}}}"
    );
    // Reading: a 22,000-statement CLSF and a 16,000-block ISO program (target: under 0.5 s as
    // wasm), checksums the count and the sum of the tips. What `toolpathParse` does, natively:
    // the options read from JSON (the machine built) on each call, the bytes fed to a
    // `Reading`, `finish` (the points flattened, each point's line, angles and commands, the
    // report), and the result written out as every declared export's is (`api::call`: JSON;
    // the wasm side writes it into JavaScript objects and typed arrays).
    let read = |bytes: &[u8], options: &Value| -> fiveaxis::Result<Value> {
        let mut r = Reading::new(ToolpathReadInput::read(options)?);
        r.feed_bytes(bytes)?;
        let parsed: ParsedToolpath = r.finish()?;
        serde_json::to_value(&parsed)
            .map_err(|e| fiveaxis::Error::field("toolpathParse", e.to_string()))
    };
    let sum = |r: &fiveaxis::Result<Value>| {
        let count = number(r, "/count");
        let pts = r
            .as_ref()
            .ok()
            .and_then(|v| v.pointer("/path/points"))
            .and_then(Value::as_array);
        pts.map_or(f64::NAN, |p| {
            let v: Vec<f64> = p.iter().filter_map(Value::as_f64).collect();
            count + v.chunks(6).map(|q| q[0] + q[1] + q[2]).sum::<f64>()
        })
    };
    let cl = clsf(22_000);
    let apt = json!({ "format": "apt" });
    report(
        "toolpath read: CLSF, 22000 statements",
        time(10, || read(cl.as_bytes(), &apt), sum),
    );
    let nc = iso(16_000);
    let trunnion = json!({ "format": "nc", "machine": preset("A/C trunnion table")? });
    report(
        "toolpath read: ISO program, 16000 blocks",
        time(10, || read(nc.as_bytes(), &trunnion), sum),
    );
    // Volumetric: 10^6 exact poses on Tan & Lim's machine with error motions of every kind
    // (the same input as scripts/bench.mjs).
    let mut tan_lim = preset("C/A double turntable on an X table (Tan & Lim)")?;
    tan_lim["errors"] = volumetric_errors();
    tan_lim["motions"] = volumetric_motions();
    let input = volumetric::VolumetricInput::read(&json!({
        "machine": tan_lim,
        "region": { "plane": "XY", "uFrom": -300, "uTo": 300, "vFrom": -200, "vTo": 200, "at": 50, "k": 30, "m": -20, "steps": 1001 },
    }))?;
    report(
        "volumetric: 10^6 poses exact (1001 x 1001 plane) + budget",
        time(
            3,
            || volumetric::map(&input),
            |m| m.as_ref().map_or(f64::NAN, |m| m.norm.iter().sum()),
        ),
    );
    let t = RotaryType::parse("CAZ")?;
    let deg = moves(1_000_000);
    // The kernel takes radians; converting is part of what the wasm call does too.
    report_counted(
        "nonlinear: exact max of 10^6 moves",
        time(
            3,
            || {
                let rad: Vec<[f64; 4]> = deg.iter().map(|m| m.map(f64::to_radians)).collect();
                nonlinear::max_errors(t, &rad)
            },
            |r| r.iter().sum(),
        ),
        t,
        &deg,
    );
    let short = short_moves(1_000_000);
    report_counted(
        "nonlinear: exact max of 10^6 short moves (< 5°)",
        time(
            3,
            || {
                let rad: Vec<[f64; 4]> = short.iter().map(|m| m.map(f64::to_radians)).collect();
                nonlinear::max_errors(t, &rad)
            },
            |r| r.iter().sum(),
        ),
        t,
        &short,
    );
    let r90 = 90f64.to_radians();
    report(
        "nonlinear: 361x361 increment grid",
        time(
            3,
            || {
                nonlinear::sweep_increments(
                    t,
                    1.0,
                    10f64.to_radians(),
                    (-r90, r90),
                    (-r90, r90),
                    361,
                    361,
                )
            },
            |g| g.as_ref().map_or(f64::NAN, |g| g.max.iter().sum()),
        ),
    );
    // The cubic test's height map of the Table 5 machine at 0.05 mm (the page's default is
    // 193 points along X); the same JSON input as scripts/bench.mjs, read the same way.
    let mut li = preset("B/C tilting table, vertical spindle (Li et al. 2021)")?;
    li["errors"] = json!({
        "E_X0B": -0.0146, "E_Y0B": 0.0089, "E_Z0B": 0.0142, "E_A0B": 0.0023,
        "E_B0B": -0.0029, "E_C0B": 0.00002, "E_A0C": 0.00017, "E_X0C": -0.0094,
    });
    let case = CubicInput::read(&json!({ "machine": li }))?;
    report(
        "cubic: height map 961x961 (Table 5)",
        time(
            3,
            || {
                cubic::height_map(
                    &case.machine,
                    &case.setup,
                    &case.options(),
                    &CubicGrid {
                        nx: 961,
                        ny: Some(961),
                    },
                )
            },
            |m| m.as_ref().map_or(f64::NAN, |m| m.height.iter().sum()),
        ),
    );
    // S-shape: the inputs of scripts/bench.mjs.
    // The declared export on the same JSON as scripts/bench.mjs, result written out.
    let overcut = json!({ "tool": { "rTool": 10, "lTool": 35 }, "nu": 261, "nv": 16 });
    let exact_sum = |r: &fiveaxis::Result<Value>, i: usize| {
        r.as_ref()
            .ok()
            .and_then(|v| v.pointer(&format!("/surfaces/{i}/exact")))
            .and_then(Value::as_array)
            .map_or(f64::NAN, |a| a.iter().filter_map(Value::as_f64).sum())
    };
    report(
        "sshape: overcut maps of A and B (eq 6 + exact), 261 x 16",
        time(
            3,
            || fiveaxis::api::call("sshapeOvercut", &overcut),
            |r| exact_sum(r, 0) + exact_sum(r, 1),
        ),
    );
    // A new design per run (the engine keeps designs in a cache, so each run uses another
    // pivot), read from the same JSON and computed as `sshapeDefects` does.
    let chanal = preset("B swivel head, C rotary table, Y under the table")?;
    let machine_at = |run: usize| -> Value {
        let mut m = chanal.clone();
        m["geometry"]["pivotLength"] = json!(399.889 + 0.001 * run as f64);
        m["errors"] = json!({ "E_X0B": 0.0294, "E_A0B": 3.2419e-4f64.to_degrees() });
        m
    };
    // A count of runs, not a time, as scripts/bench.mjs: the last run's pivot, and so its
    // result, is the same on both sides.
    let mut run = 0;
    report(
        "sshape: eq 14 model (IK along both paths) + defects",
        time_for(
            0.0,
            30,
            10,
            || {
                run += 1;
                let (c, own) = SShapeCase::read_with::<SShapeDefectsInput>(
                    &json!({ "machine": machine_at(run) }),
                )?;
                let d = study::Design::cached(&c)?;
                let total = d.simulate(&c.machine.errors, own.d_r);
                std::hint::black_box((
                    d.contributions(&c.machine.errors).concat(),
                    d.radius_deviation(own.d_r),
                    d.alike_pairs(0.95),
                ));
                Ok::<_, fiveaxis::Error>(total)
            },
            |r| r.as_ref().map_or(f64::NAN, |v| v.iter().sum()),
        ),
    );
    let csv = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/samples/sshape-measured.csv"
    ))?;
    let paper = [
        "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
    ];
    // As the page does: the defects first (the design built and cached), then each
    // identification is the declared export `sshapeIdentify` on the same JSON as
    // scripts/bench.mjs, result written out (`api::call`: what the wasm export does, natively).
    SShapeCase::read_with::<SShapeDefectsInput>(&json!({ "machine": machine_at(0) }))
        .and_then(|(c, _)| study::Design::cached(&c))?;
    let ident = json!({ "machine": machine_at(0), "csv": csv, "parameters": paper });
    report(
        "sshape: identification of the 100-point sample (parse + SVD fit), 100 times",
        time(
            3,
            || {
                let mut r = Value::Null;
                for _ in 0..100 {
                    r = fiveaxis::api::call("sshapeIdentify", &ident)?;
                }
                Ok::<_, fiveaxis::Error>(r)
            },
            |r| number(r, "/rms"),
        ),
    );
    // The reversal test (Nishiguchi et al.): the default case, F = 1000 mm/min (19 s of motion,
    // 0.2 ms steps), simulated with C's friction and again without it, as reversalSimulate does;
    // one simulation is half of it.
    let rev = fiveaxis::reversal::ReversalCase::read(&json!({}))?;
    report(
        "reversal: default test with and without friction (2 simulations)",
        time(
            3,
            || -> Result<f64, fiveaxis::Error> {
                let (m, with) = fiveaxis::reversal::simulate(&rev)?;
                let without = fiveaxis::reversal::simulate_with_step(
                    &rev.with_c_friction(0.0),
                    &m,
                    with.step,
                )?;
                std::hint::black_box(fiveaxis::reversal::dent(&with, &without));
                Ok(with.deviation.iter().sum::<f64>())
            },
            |r| r.as_ref().map_or(f64::NAN, |v| *v),
        ),
    );
    // The cubic test designer on Li et al.'s B/C table with a second set-up 100 mm off the
    // axis (18 zones among 1098 candidates), and 100 identifications of its export filled in.
    let li = serde_json::from_str::<serde_json::Value>(&std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/presets/machines.json"
    ))?)?["presets"][0]["machine"]
        .clone();
    let design_input = serde_json::json!({ "machine": li, "secondSetup": 100 });
    // The declared exports `cubicDesign` and `cubicIdentify`, as the wasm side calls them.
    report(
        "cubic: test designer, B/C table, 2 set-ups (1098 candidate zones)",
        time(
            3,
            || fiveaxis::api::call("cubicDesign", &design_input),
            |d| number(d, "/designed/smallest"),
        ),
    );
    let designed = fiveaxis::api::call("cubicDesign", &design_input)?;
    let filled = designed
        .pointer("/designed/csv")
        .and_then(Value::as_str)
        .ok_or("cubicDesign: no designed.csv")?
        .replace(",,,\n", ",1,0.00001,-0.00001\n");
    let ident_input =
        serde_json::json!({ "machine": li, "csv": filled, "decision": { "noise": 0.001 } });
    report(
        "cubic: identification of 18 measured zones, 100 times",
        time(
            3,
            || {
                let mut r = Value::Null;
                for _ in 0..100 {
                    r = fiveaxis::api::call("cubicIdentify", &ident_input)?;
                }
                Ok::<_, fiveaxis::Error>(r)
            },
            |r| number(r, "/rms"),
        ),
    );
    // The sphere test: the identification of 200 probed poses, through the declared export on
    // the same JSON as the wasm side (`api::call`: read, identify, written as JSON).
    let probe = probe_input()?;
    report(
        "probe: identification of 200 probed poses (probeIdentify)",
        time(
            5,
            || fiveaxis::api::call("probeIdentify", &probe),
            |r| r.as_ref().map_or(f64::NAN, probe_check),
        ),
    );
    Ok(())
}
