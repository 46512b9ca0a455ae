//! The test designer (`fiveaxis::cubic::design`) on Li et al.'s B/C table and an A/C trunnion:
//! the designed test reaches the rank of every candidate together (every error such a test can
//! reveal at all is identifiable), its zones are reachable within the travel, it beats the
//! paper's layout, and the errors no such test can see are the ones the geometry says, checked
//! with the exact chain (not the first-order model the designer uses).
#![allow(clippy::unwrap_used)]
use crate::common;

use common::machine_preset;
use fiveaxis::cubic::design::{design, CubicDesignInput, Design, TYPICAL_ANGLE, TYPICAL_POSITION};
use fiveaxis::cubic::identify::{exact_planes, parse_measurements};
use fiveaxis::cubic::{CubicInput, Options};
use fiveaxis::machine::errors::ErrorValues;
use fiveaxis::machine::BranchRule;
use fiveaxis::schema::read_split;
use nalgebra::Vector3;
use serde_json::{json, Value};

fn input(preset: &str, own: Value) -> (CubicInput, CubicDesignInput) {
    let mut v = json!({ "machine": machine_preset(preset) });
    for (k, x) in own.as_object().unwrap() {
        v[k] = x.clone();
    }
    read_split(&v, "").unwrap()
}

fn run(preset: &str, own: Value) -> (CubicInput, Design) {
    let (i, o) = input(preset, own);
    let d = design(&i, &o).unwrap();
    (i, d)
}

/// The errors and combinations the fit of all candidates cannot see: single names, and for a
/// group with one identifiable combination, the members.
fn unseen(d: &Design) -> Vec<Vec<String>> {
    d.all.groups.iter().map(|g| g.members.clone()).collect()
}

/// Largest exact change of a height or of a slope over half a zone (mm) that `errors` make on
/// the zones of the CSV layout, against the machine without errors.
fn exact_effect(i: &CubicInput, csv: &str, errors: ErrorValues) -> f64 {
    let zones = parse_measurements(&fill(csv), &i.setup).unwrap();
    let specs: Vec<_> = zones.iter().map(|z| z.zone.clone()).collect();
    let o = Options {
        transform: i.transform,
        reference: i.reference,
    };
    let mut m = i.machine.clone();
    m.errors = ErrorValues::none();
    let base = exact_planes(&m, &i.setup, &o, &specs).unwrap();
    m.errors = errors;
    let with = exact_planes(&m, &i.setup, &o, &specs).unwrap();
    let lever = i.setup.zone_size / 2.0;
    base.iter()
        .zip(&with)
        .map(|(a, b)| {
            (a.height - b.height)
                .abs()
                .max(((a.slope_x - b.slope_x) * lever).abs())
                .max(((a.slope_y - b.slope_y) * lever).abs())
        })
        .fold(0.0, f64::max)
}

/// The export with zero heights filled in, so that it reads as a measurement file.
fn fill(csv: &str) -> String {
    csv.lines()
        .map(|l| {
            if l.ends_with(",,,") {
                format!("{}0,,", &l[..l.len() - 2])
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn typical(name: &str) -> f64 {
    if fiveaxis::machine::errors::find(name).unwrap().component >= 3 {
        TYPICAL_ANGLE
    } else {
        TYPICAL_POSITION
    }
}

fn check_machine(preset: &str, expected_unseen: &[&[&str]]) {
    for second in [0.0, 100.0] {
        let (i, d) = run(preset, json!({ "secondSetup": second }));
        let n = d.errors.len();
        // What no such test can see: the geometry's list (module docs of the design).
        let mut got = unseen(&d);
        got.sort();
        let mut want: Vec<Vec<String>> = expected_unseen
            .iter()
            .map(|g| g.iter().map(|s| s.to_string()).collect())
            .collect();
        want.sort();
        assert_eq!(got, want, "{preset}: what no test can see");
        let deficiency: usize = d.all.groups.iter().map(|g| g.deficiency).sum();
        assert_eq!(d.reachable_rank, n - deficiency, "{preset}");
        // The design: full rank on what can be revealed, every error outside the groups alone.
        let r = &d.designed;
        assert_eq!(r.rank, d.reachable_rank, "{preset} {second}: designed rank");
        assert!(
            r.condition.is_finite() && r.smallest > 0.1,
            "{preset}: {}",
            r.smallest
        );
        let alone = r.fit.estimates.iter().filter(|e| e.value.is_some()).count();
        let alone_all = d.all.estimates.iter().filter(|e| e.value.is_some()).count();
        assert_eq!(
            alone, alone_all,
            "{preset}: every error such a test can reveal, alone"
        );
        // The paper's layout sees less.
        let paper = d.paper.as_ref().unwrap();
        assert!(paper.rank < r.rank, "{preset}: paper rank {}", paper.rank);
        // Every designed zone reachable: the machine's own inverse kinematics within its
        // travel gives its tool vector back.
        let model = i.machine.build().unwrap();
        let [(k0, k1), (m0, m1)] = model.travel();
        for z in &r.zones {
            let t = Vector3::from(z.zone.tool);
            let o = model
                .orientations(&t, BranchRule::SmallestTilt, None)
                .unwrap();
            let c = o.pick("zone").unwrap();
            assert!(
                c.k >= k0 - 1e-12 && c.k <= k1 + 1e-12 && c.m >= m0 - 1e-12 && c.m <= m1 + 1e-12
            );
            let [k, m] = z.zone.rotary;
            assert!(
                (c.k - k).abs() < 1e-9 && (c.m - m).abs() < 1e-9,
                "{}",
                z.zone.spec.name
            );
            assert!(
                z.zone.spec.tool[2] >= (45f64).to_radians().cos() - 1e-12,
                "within the tilt"
            );
        }
        assert_eq!(r.zones.len(), if second == 0.0 { 9 } else { 18 });
        // The exact chain agrees: each unseen error (a group's unseen direction) changes no
        // height or slope of the designed zones beyond second order, each seen one does.
        for g in &d.all.groups {
            let mut e = ErrorValues::none();
            if g.combinations.is_empty() {
                e.set(&g.members[0], typical(&g.members[0])).unwrap();
            } else {
                // The unseen direction is orthogonal to the measurable combination.
                let c = &g.combinations[0].terms;
                let (a, ca) = (&c[0].0, c[0].1);
                let (b, cb) = (&c[1].0, c[1].1);
                // Σ c·x = 0: x_a = c_b·s, x_b = −c_a·s.
                let s = typical(a);
                e.set(a, s * cb).unwrap();
                e.set(b, -s * ca).unwrap();
            }
            let eff = exact_effect(&i, &r.csv, e);
            assert!(
                eff < 2e-5,
                "{preset}: {:?} changes the zones by {eff} mm",
                g.members
            );
        }
        for est in r.fit.estimates.iter().filter(|e| e.value.is_some()) {
            let e = ErrorValues::single(&est.name, typical(&est.name)).unwrap();
            let eff = exact_effect(&i, &r.csv, e);
            assert!(
                eff > 1e-4,
                "{preset}: {} changes the zones by only {eff} mm",
                est.name
            );
        }
    }
}

#[test]
fn li_bc_table_designed_test_identifies_every_error_a_face_can_reveal() {
    // B/C table (B about Y on the bed, C on B; tool along Z): what no face square to the
    // spindle can see, whatever the tool vector:
    // - E_Y0B, E_Z0C: offsets along an axis's own line (a rotation moves no point of its line);
    // - E_C0C: C's zero; the set-up at zero absorbs it (a turn about the face's own normal);
    // - E_X0C, E_Y0C: C's line offset across it moves the piece within the face's plane;
    // - E_A0Z: Z out of square about X moves the tool along Y, B's direction, which stays in
    //   the face's plane at every B and C;
    // - B's zero and C's tilt about Y act alike (the set-up conjugates one into the other),
    //   and B's tilt about Z with Y's squareness: only their combination.
    check_machine(
        "B/C tilting",
        &[
            &["E_Y0B"],
            &["E_Z0C"],
            &["E_C0C"],
            &["E_X0C"],
            &["E_Y0C"],
            &["E_A0Z"],
            &["E_B0B", "E_B0C"],
            &["E_C0B", "E_C0Y"],
        ],
    );
}

#[test]
fn ac_trunnion_designed_test_identifies_every_error_a_face_can_reveal() {
    // A/C trunnion: the same reasons with A about X: E_X0A along A's line, E_Z0C along C's,
    // C's zero absorbed, C's offsets within the face, Y's and Z's squareness about Z and Y
    // (moving the tool along X, A's direction), and A's zero with C's tilt about X.
    check_machine(
        "A/C trunnion",
        &[
            &["E_X0A"],
            &["E_Z0C"],
            &["E_C0C"],
            &["E_X0C"],
            &["E_Y0C"],
            &["E_C0Y"],
            &["E_B0Z"],
            &["E_A0A", "E_A0C"],
        ],
    );
}
