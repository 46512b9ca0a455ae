//! The study's inputs as the page and Node send them (commands in degrees, the machine's senses
//! of rotation, `L` given or the machine's), read natively, each export's numbers against the
//! same move built by hand in the study's angles (θ = −command on a reversed axis, module docs
//! of `fiveaxis::machine`). A reversed sense mirrors the path and leaves its errors as they are
//! (the last test), so the sweeps are checked on all four senses for their ranges and keys; the
//! senses themselves show in `angles` and `compare_types`. The maximum of one move
//! (`Deviation::peak`) is checked against brute force in `crate/tests/nonlinear/deviation.rs`; here it is the
//! reference for what the inputs feed it.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use fiveaxis::nonlinear::{
    linspace, Deviation, Move, NonlinearCase, NonlinearGridInput, SweepKInput, SweepMInput,
    TypeCompareInput,
};
use fiveaxis::rotary::{Pose, RotaryType};
use serde_json::{json, Value};

const L: f64 = 100.0;

/// A table-table machine of type `t` with the given senses, and `L` = 100 mm.
fn case_json(t: &str, k_reversed: bool, m_reversed: bool) -> Value {
    json!({
        "machine": {
            "kind": "table-table", "type": t,
            "rotary": { "kReversed": k_reversed, "mReversed": m_reversed },
        },
        "length": L,
    })
}

/// The case alone (with the inputs of an export that has defaults for all of them).
fn case_of(v: &Value) -> NonlinearCase {
    NonlinearCase::read_with::<TypeCompareInput>(v).unwrap().0
}

/// `case_json` with the export's own keys added.
fn with(mut case: Value, own: Value) -> Value {
    for (k, v) in own.as_object().unwrap() {
        case[k] = v.clone();
    }
    case
}

/// The sign a sense puts on a command: θ = s·command.
fn sense(reversed: bool) -> f64 {
    if reversed {
        -1.0
    } else {
        1.0
    }
}

const SENSES: [(bool, bool); 4] = [(false, false), (true, false), (false, true), (true, true)];

/// The maximum error (mm, at `L`) of the move between two commands (degrees) on type `t` with
/// the senses `(sk, sm)`, built by hand.
fn by_hand(t: RotaryType, (sk, sm): (f64, f64), start: (f64, f64), end: (f64, f64)) -> f64 {
    let pose = |(k, m): (f64, f64)| Pose::new(sk * k.to_radians(), sm * m.to_radians());
    Deviation::new(Move::new(t, pose(start), pose(end)))
        .peak()
        .value
        * L
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
#[test]
fn l_is_the_given_one_or_the_machines_swing() {
    let given = case_of(&json!({ "length": 80 }));
    assert_eq!(given.length().unwrap(), 80.0);
    // A head: pivot plus tool length; a table-table machine: the table surface's distance from
    // the centre of the rotary axes, √(height² + offset²).
    let head =
        json!({ "kind": "head-table", "geometry": { "pivotLength": 250, "toolLength": 120 } });
    let table =
        json!({ "kind": "table-table", "geometry": { "tableHeight": 30, "rotaryOffset": 40 } });
    for (machine, l) in [(head, 370.0), (table, 50.0)] {
        let case = case_of(&json!({ "machine": machine }));
        close(case.length().unwrap(), l, 1e-12, "L of the machine");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
#[test]
fn a_reversed_axis_flips_the_sign_of_its_command_only() {
    for (kr, mr) in SENSES {
        let case = case_of(&case_json("CBZ", kr, mr));
        let p = case.angles(0.3, -0.7);
        assert_eq!((p.k, p.m), (sense(kr) * 0.3, sense(mr) * -0.7), "{kr} {mr}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// Fig 4 on every sense: each start command of K (its `n` commands from `from` to `to`,
/// inclusive, equally spaced) against the move built by hand; the error does not depend on
/// where K starts (the whole move turns about K), which the flat curve shows.
#[test]
fn sweep_of_the_start_of_k_is_the_commanded_moves_errors() {
    let t = RotaryType::parse("CBZ").unwrap();
    for (kr, mr) in SENSES {
        let own = json!({ "thetaM": 20, "dK": 70, "dM": 35, "from": 0, "to": 90, "n": 4 });
        let (case, i): (_, SweepKInput) =
            NonlinearCase::read_with(&with(case_json("CBZ", kr, mr), own)).unwrap();
        let got = case.sweep_k(&i).unwrap();
        assert_eq!(got.len(), 4);
        for (j, &e) in got.iter().enumerate() {
            let k = 30.0 * j as f64;
            let want = by_hand(t, (sense(kr), sense(mr)), (k, 20.0), (k + 70.0, 55.0));
            close(e, want, 1e-9 * want, &format!("{kr} {mr} start K {k}°"));
            close(e, got[0], 1e-9 * want, "the same for every start of K");
        }
        assert!(
            got[0] > 0.5,
            "a move of 70° and 35° errs by millimetres: {}",
            got[0]
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// Fig 7 on every sense: one curve per ratio of the commands' increments ΔK/ΔM, labelled with
/// the ratio as given, each point the move from (0, M) to (ratio·ΔM, M + ΔM) in commands.
#[test]
fn sweep_of_the_start_of_m_is_the_commanded_moves_errors_per_ratio() {
    let t = RotaryType::parse("CAY").unwrap();
    for (kr, mr) in SENSES {
        let own = json!({ "dM": 30, "ratios": [0.5, -2, 3], "from": -40, "to": 50, "n": 4 });
        let (case, i): (_, SweepMInput) =
            NonlinearCase::read_with(&with(case_json("CAY", kr, mr), own)).unwrap();
        let curves = case.sweep_m(&i).unwrap();
        assert_eq!(curves.len(), 3);
        for (c, ratio) in curves.iter().zip([0.5, -2.0, 3.0]) {
            assert_eq!(c.ratio, ratio, "the ratio as given");
            assert_eq!(c.exact.len(), 4);
            for (j, &e) in c.exact.iter().enumerate() {
                let m = -40.0 + 30.0 * j as f64;
                let want = by_hand(
                    t,
                    (sense(kr), sense(mr)),
                    (0.0, m),
                    (ratio * 30.0, m + 30.0),
                );
                close(
                    e,
                    want,
                    1e-9 * want,
                    &format!("{kr} {mr} ratio {ratio} start M {m}°"),
                );
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// Figs 3, 5, 8 on every sense: the grid's increments are the commands as asked (degrees in,
/// radians out, columns K, rows M, ends included) and each cell the move from (0, M) by them.
#[test]
fn grid_of_increments_is_in_commands_and_each_cell_the_commanded_move() {
    let t = RotaryType::parse("BCX").unwrap();
    for (kr, mr) in SENSES {
        let own = json!({
            "thetaM": 25, "dK": { "from": -60, "to": 120 }, "dM": { "from": 10, "to": 70 },
            "nx": 4, "ny": 2,
        });
        let (case, i): (_, NonlinearGridInput) =
            NonlinearCase::read_with(&with(case_json("BCX", kr, mr), own)).unwrap();
        let g = case.grid(&i).unwrap();
        assert_eq!((g.nx, g.ny), (4, 2));
        let dk: [f64; 4] = [-60.0, 0.0, 60.0, 120.0];
        let dm: [f64; 2] = [10.0, 70.0];
        for (a, b) in g.d_k.iter().zip(dk) {
            close(*a, b.to_radians(), 1e-15, "ΔK of a column (rad)");
        }
        for (a, b) in g.d_m.iter().zip(dm) {
            close(*a, b.to_radians(), 1e-15, "ΔM of a row (rad)");
        }
        for (iy, &m) in dm.iter().enumerate() {
            for (ix, &k) in dk.iter().enumerate() {
                let want = by_hand(t, (sense(kr), sense(mr)), (0.0, 25.0), (k, 25.0 + m));
                let e = g.max[iy * dk.len() + ix];
                close(
                    e,
                    want,
                    1e-9 * want,
                    &format!("{kr} {mr} cell ΔK {k}° ΔM {m}°"),
                );
            }
        }
    }
    // An empty range is refused by its key.
    let own = json!({
        "thetaM": 25, "dK": { "from": 5, "to": 5 }, "dM": { "from": 10, "to": 70 }, "nx": 3, "ny": 3,
    });
    let (case, i): (_, NonlinearGridInput) =
        NonlinearCase::read_with(&with(case_json("BCX", false, false), own)).unwrap();
    let e = case.grid(&i).unwrap_err().to_string();
    assert!(e.contains("dK") && e.contains("empty"), "{e}");
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// The same move on the twelve types: every type reached makes the start and end tool vectors
/// of the machine's own move with its commands (in its senses), and errs as that move by hand;
/// the machine's own type keeps the commands as given (K = 200° is not folded to −160°).
#[test]
fn every_type_makes_the_same_tool_vectors_and_the_own_type_the_commands_given() {
    let own_type = RotaryType::parse("CBZ").unwrap();
    let (start, end) = ((200.0, 10.0), (230.0, 25.0));
    for (kr, mr) in SENSES {
        let (sk, sm) = (sense(kr), sense(mr));
        let own =
            json!({ "start": { "k": start.0, "m": start.1 }, "end": { "k": end.0, "m": end.1 } });
        let (case, i): (_, TypeCompareInput) =
            NonlinearCase::read_with(&with(case_json("CBZ", kr, mr), own)).unwrap();
        let rows = case.compare_types(&i.start, &i.end).unwrap();
        assert_eq!(rows.len(), 12);
        let pose = |(k, m): (f64, f64)| Pose::new(sk * k.to_radians(), sm * m.to_radians());
        let ends = [
            own_type.tool_vector(pose(start)),
            own_type.tool_vector(pose(end)),
        ];
        let mut reached = 0;
        for r in &rows {
            let (Some(c0), Some(c1)) = (r.start, r.end) else {
                assert!(r.max.is_none() && r.unreachable.is_some());
                continue;
            };
            let (c0, c1) = (Pose::new(c0[0], c0[1]), Pose::new(c1[0], c1[1]));
            reached += 1;
            let deg = |p: Pose| (p.k.to_degrees(), p.m.to_degrees());
            for (c, v) in [(c0, ends[0]), (c1, ends[1])] {
                let got = r.rtype.tool_vector(pose(deg(c)));
                assert!(
                    (got - v).norm() < 1e-9,
                    "{} {kr} {mr}: {got:?} vs {v:?}",
                    r.rtype.name()
                );
            }
            let want = by_hand(r.rtype, (sk, sm), deg(c0), deg(c1));
            close(r.max.unwrap(), want, 1e-9 * want.max(1e-9), &r.rtype.name());
            if r.rtype == own_type {
                close(
                    c0.k,
                    start.0.to_radians(),
                    1e-15,
                    "own type: K as commanded",
                );
                close(
                    c0.m,
                    start.1.to_radians(),
                    1e-15,
                    "own type: M as commanded",
                );
                close(
                    c1.k,
                    end.0.to_radians(),
                    1e-15,
                    "own type: end K as commanded",
                );
                close(
                    c1.m,
                    end.1.to_radians(),
                    1e-15,
                    "own type: end M as commanded",
                );
                assert!(want > 0.1, "the own move errs: {want}");
            }
        }
        assert!(reached >= 4, "{reached} types reach the move");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// `linspace`: `n` values from `a` to `b`, both included, equal steps; `[a]` when `n < 2`.
#[test]
fn linspace_is_equal_steps_with_both_ends() {
    let v = linspace(-3.0, 5.0, 5);
    assert_eq!(v, vec![-3.0, -1.0, 1.0, 3.0, 5.0]);
    assert_eq!(linspace(2.0, 7.0, 2), vec![2.0, 7.0]);
    assert_eq!(linspace(2.0, 7.0, 1), vec![2.0]);
    assert_eq!(linspace(2.0, 7.0, 0), vec![2.0]);
}

// Found by cargo-mutants: a mutant in `crate/src/nonlinear/inputs.rs` survived every other test.
/// A reversed axis mirrors the path: turning K, M or both the other way gives a path congruent
/// to the first (R_K(−θ) = S·R_K(θ)·S with S the reflection that fixes K's axis and e_H), so
/// every error and its u are the same on all four senses. The senses therefore show only in the
/// commands (`angles`, `compare_types`), never in the sweeps' numbers.
#[test]
fn a_reversed_sense_mirrors_the_path_and_leaves_every_error() {
    let mut rng = common::Rng::new(31);
    for t in RotaryType::ALL {
        for _ in 0..50 {
            let (k0, m0) = (rng.range(-3.0, 3.0), rng.range(-1.5, 1.5));
            let (k1, m1) = (k0 + rng.range(-2.0, 2.0), m0 + rng.range(-2.0, 2.0));
            let peak = |sk: f64, sm: f64| {
                let mv = Move::new(t, Pose::new(sk * k0, sm * m0), Pose::new(sk * k1, sm * m1));
                Deviation::new(mv).peak()
            };
            let p = peak(1.0, 1.0);
            for (sk, sm) in [(-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                let q = peak(sk, sm);
                close(q.value, p.value, 1e-12, &format!("{t:?} senses {sk} {sm}"));
                if p.value > 1e-6 {
                    close(q.u, p.u, 1e-6, "u of the maximum");
                }
            }
        }
    }
}
