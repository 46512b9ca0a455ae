//! Native timings of the engine's heavy kernels, for `npm run bench` (scripts/bench.mjs times the
//! same kernels as WebAssembly in Node on the same inputs and prints the ratio).
//! Prints one JSON object per line: `{"name": ..., "ms": ..., "check": ...}`.

use fiveaxis::cubic::{self, CubicSetup, GeometricErrors, Options};
use fiveaxis::nonlinear;
use fiveaxis::rotary::RotaryType;
use fiveaxis::sshape::{identify, machine, overcut::ToolPath, study};
use std::time::Instant;

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

/// Best of `repeat` runs, milliseconds, and the last result's checksum.
fn time<T>(repeat: usize, mut f: impl FnMut() -> T, check: impl Fn(&T) -> f64) -> (f64, f64) {
    let mut best = f64::INFINITY;
    let mut sum = 0.0;
    for _ in 0..repeat {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
        sum = check(&r);
    }
    (best, sum)
}

fn report(name: &str, (ms, check): (f64, f64)) {
    println!("{{\"name\":\"{name}\",\"ms\":{ms:.3},\"check\":{check:.12e}}}");
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let t = RotaryType::parse("CAZ")?;
    let deg = moves(1_000_000);
    // The kernel takes radians; converting is part of what the wasm call does too.
    report(
        "nonlinear: exact max of 10^6 moves",
        time(
            3,
            || {
                let rad: Vec<[f64; 4]> = deg.iter().map(|m| m.map(f64::to_radians)).collect();
                nonlinear::max_errors(t, &rad)
            },
            |r| r.iter().sum(),
        ),
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
    // 385 × 385); the JavaScript side passes the same errors in µm → mm and degrees.
    report(
        "cubic: height map 961x961 (Table 5)",
        time(
            3,
            || {
                cubic::height_map(
                    &CubicSetup::default(),
                    &GeometricErrors::table5(),
                    &Options::default(),
                    961,
                    961,
                )
            },
            |m| m.as_ref().map_or(f64::NAN, |m| m.height.iter().sum()),
        ),
    );
    // S-shape: the inputs of scripts/bench.mjs.
    let tool = ToolPath::paper();
    report(
        "sshape: overcut maps of A and B (eq 6 + exact), 261 x 16",
        time(
            3,
            || study::overcut(&tool, 261, 16),
            |o| {
                o.as_ref().map_or(f64::NAN, |o| {
                    o.a.exact.iter().sum::<f64>() + o.b.exact.iter().sum::<f64>()
                })
            },
        ),
    );
    // A new design per run (the wasm side has a cache, so each run uses another L0).
    let mut run = 0;
    report(
        "sshape: eq 14 model (IK along both paths) + defects",
        time(
            3,
            || {
                run += 1;
                let d = study::Design::new(
                    499.889 + 0.001 * run as f64,
                    tool,
                    machine::DefectModel::default(),
                )?;
                d.simulate(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0294, 3.2419e-4, 0.0], 0.0)
            },
            |r| r.as_ref().map_or(f64::NAN, |v| v.iter().sum()),
        ),
    );
    let csv = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/samples/sshape-measured.csv"
    ))?;
    let design = study::Design::new(machine::PAPER_L0, tool, machine::DefectModel::default())?;
    report(
        "sshape: identification of the 100-point sample (parse + SVD fit), 100 times",
        time(
            3,
            || {
                let mut fit = None;
                for _ in 0..100 {
                    let d = identify::parse_measurements(&csv)?;
                    fit = Some(design.identify(&d, true, identify::DEFAULT_RTOL)?);
                }
                fit.ok_or_else(|| fiveaxis::Error::field("bench", "no run"))
            },
            |f| f.as_ref().map_or(f64::NAN, |f| f.rms),
        ),
    );
    Ok(())
}
