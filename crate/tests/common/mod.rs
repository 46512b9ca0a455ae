//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod chanal;
pub mod li;
pub mod toolpath;

/// The B/C tilting-rotary table of the cubic-test paper (Li et al. 2021) as a bare chain: B about
/// Y on the bed, C about Z on B, both through the origin; X, Y, Z carry the tool. Chain order:
/// B, C, X, Y, Z.
pub fn bc_table() -> fiveaxis::chain::Chain {
    use fiveaxis::chain::{Chain, Link};
    use fiveaxis::geometry::Axis;
    Chain {
        work: vec![
            Link::rotary("B", Axis::Y).on_table(),
            Link::rotary("C", Axis::Z).on_table(),
        ],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Y", Axis::Y),
            Link::linear("Z", Axis::Z),
        ],
        work_origin: nalgebra::Vector3::zeros(),
        tool_tip: nalgebra::Vector3::zeros(),
        tool_axis: Axis::Z,
    }
}

/// A small deterministic generator (xorshift64*), so tests need no extra crate and never flake.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A standard normal deviate (Box–Muller).
    pub fn gauss(&mut self) -> f64 {
        let (u1, u2) = (self.unit().max(1e-300), self.unit());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    /// A direction uniform on the sphere (a point of the cube kept inside the unit ball, away
    /// from its centre, normalised).
    pub fn direction(&mut self) -> nalgebra::Vector3<f64> {
        loop {
            let v = nalgebra::Vector3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if v.norm() > 0.2 && v.norm() < 1.0 {
                return v / v.norm();
            }
        }
    }
}

pub fn deg(x: f64) -> f64 {
    x.to_radians()
}

/// The largest of `f` over `n + 1` equal steps of [0, 1] and where, `(u, value)` (the first
/// of equal values): a brute-force reference for the engine's maximisers.
pub fn sampled_max(n: usize, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let mut best = (0.0, f(0.0));
    for i in 1..=n {
        let u = i as f64 / n as f64;
        let v = f(u);
        if v > best.1 {
            best = (u, v);
        }
    }
    best
}

/// Asserts |a - b| <= tol, with a message.
#[track_caller]
pub fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: {a} vs {b} (diff {:e}, tol {tol:e})",
        (a - b).abs()
    );
}

/// The machine object of the preset in `public/presets/machines.json` whose name starts with
/// `prefix` (the presets the page offers).
#[allow(clippy::expect_used)]
pub fn machine_preset(prefix: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/presets/machines.json"
    ))
    .expect("public/presets/machines.json");
    let all: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    all["presets"]
        .as_array()
        .expect("a list of presets")
        .iter()
        .find(|p| p["name"].as_str().is_some_and(|n| n.starts_with(prefix)))
        .unwrap_or_else(|| panic!("no machine preset named {prefix}…"))["machine"]
        .clone()
}

/// A machine read from its JSON form, as the page sends it.
#[allow(clippy::unwrap_used)] // test helper: a failure should stop the test
pub fn machine(v: serde_json::Value) -> fiveaxis::machine::Machine {
    use fiveaxis::schema::Inputs;
    fiveaxis::machine::Machine::from_value(&v, "machine").unwrap()
}

/// `a − b` of two points given as arrays.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The length of a vector given as an array.
pub fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Each component of `got` within 1e-9 of `want`.
pub fn close3(got: [f64; 3], want: [f64; 3], what: &str) {
    for i in 0..3 {
        close(got[i], want[i], 1e-9, &format!("{what}[{i}]"));
    }
}

/// Every `.rs` file under `dir`, at any depth (the crate's own sources and tests: a failure to
/// read them stops the test).
#[allow(clippy::unwrap_used)]
pub fn rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}
