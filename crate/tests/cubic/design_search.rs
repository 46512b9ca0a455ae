//! The cubic test's designer against what its module docs define, rebuilt here independently:
//! - the scaled matrix `S` (10 µm / 10⁻⁴ rad typical sizes, heights over the noise, slopes over
//!   the noise per half zone), rebuilt from each zone's public sensitivities: its singular
//!   values, rank (relative threshold 10⁻⁶), `σ_r` and the condition `σ₁/σ_r`;
//! - that the noise only scales `S` (rank and reachable rank do not depend on it);
//! - the candidate grid (`n × n` positions at `(i − (n−1)/2)·zoneSize`, the names A1 … and S2-A1
//!   …, the second set-up at `workpieceX + secondSetup`, tilts 0, 10, …, maxTilt, azimuths every
//!   30°, a tilt of 0 once), rebuilt zone by zone with the public `layout`;
//! - the search's end: no single zone swapped for another candidate of its place raises `σ_r`;
//! - the start (30° towards the face centre), seen where the search cannot improve on it;
//! - the paper's layout (tilt and azimuth of its tool vectors, condition infinite when its rank
//!   is short) and the fit's view of a layout with as many values as errors.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::machine_preset;
use fiveaxis::cubic::design::{
    design, CubicDesignInput, Design, DesignedZone, TYPICAL_ANGLE, TYPICAL_POSITION,
};
use fiveaxis::cubic::identify::{layout, tool_of, LayoutZone};
use fiveaxis::cubic::{CubicInput, CubicReference, Options, ZoneSpec, ZONES};
use fiveaxis::machine::errors::ErrorDef;
use fiveaxis::schema::{read_split, Quantity};
use nalgebra::DMatrix;
use serde_json::{json, Value};

/// The design inputs of a machine preset with the designer's own fields `own` (and `setup`).
fn input(preset: &str, own: Value) -> (CubicInput, CubicDesignInput) {
    let mut v = json!({ "machine": machine_preset(preset) });
    for (k, x) in own.as_object().unwrap() {
        v[k] = x.clone();
    }
    read_split(&v, "").unwrap()
}

fn run(preset: &str, own: Value) -> (CubicInput, CubicDesignInput, Design) {
    let (i, o) = input(preset, own);
    let d = design(&i, &o).unwrap();
    (i, o, d)
}

/// Typical size of an error (module docs): 10⁻⁴ rad for an angle, 10 µm for a position.
fn typical(d: &ErrorDef) -> f64 {
    if d.quantity == Quantity::SmallAngle {
        TYPICAL_ANGLE
    } else {
        TYPICAL_POSITION
    }
}

/// The scaled rows of one zone, from the module docs: per error its height sensitivity times
/// the error's typical size over the noise; with slopes, each slope sensitivity times the
/// typical size times half a zone (the height a slope makes over half a zone) over the noise.
fn rows_of(
    z: &LayoutZone,
    errors: &[&ErrorDef],
    zone_size: f64,
    o: &CubicDesignInput,
) -> Vec<Vec<f64>> {
    let row = |f: &dyn Fn(usize) -> f64, lever: f64| -> Vec<f64> {
        (0..errors.len())
            .map(|e| f(e) * typical(errors[e]) * lever / o.noise)
            .collect()
    };
    let mut out = vec![row(&|e| z.sensitivity[e].height, 1.0)];
    if o.slopes {
        let half = zone_size / 2.0;
        out.push(row(&|e| z.sensitivity[e].slope_x, half));
        out.push(row(&|e| z.sensitivity[e].slope_y, half));
    }
    out
}

/// Singular values of the stacked rows, descending, padded with zeros to `p`.
fn singular_values(rows: &[Vec<f64>], p: usize) -> Vec<f64> {
    let m = DMatrix::from_fn(rows.len(), p, |r, c| rows[r][c]);
    let mut sv: Vec<f64> = m.singular_values().iter().copied().collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    sv.resize(p, 0.0);
    sv
}

/// Rank with the documented relative threshold: singular values above 10⁻⁶ of the largest.
fn rank(sv: &[f64]) -> usize {
    sv.iter().filter(|s| **s > 1e-6 * sv[0]).count()
}

/// The layout's scaled matrix `S`, rebuilt from its zones' public sensitivities.
fn layout_rows(
    zones: &[DesignedZone],
    d: &Design,
    i: &CubicInput,
    o: &CubicDesignInput,
) -> Vec<Vec<f64>> {
    zones
        .iter()
        .flat_map(|z| rows_of(&z.zone, &d.errors, i.setup.zone_size, o))
        .collect()
}

#[track_caller]
fn close_rel(a: f64, b: f64, rel: f64, what: &str) {
    assert!(
        a.is_finite() && b.is_finite() && (a - b).abs() <= rel * a.abs().max(b.abs()),
        "{what}: {a} vs {b}"
    );
}

/// The candidates of the documented grid at one place of the face, each built on its own with
/// the public `layout` (heights from the workpiece frame, the input's `transform`); those the
/// machine cannot reach within its travel are left out, as `layout` refuses them.
fn candidates_at(
    i: &CubicInput,
    o: &CubicDesignInput,
    errors: &[&'static ErrorDef],
    piece_x: f64,
    centre: (f64, f64),
) -> Vec<LayoutZone> {
    let options = Options {
        transform: i.transform,
        reference: CubicReference::Workpiece,
    };
    // Tilts 0, 10, 20, … below maxTilt, then maxTilt; azimuths 0, 30, …, 330; tilt 0 once.
    let max = o.max_tilt.to_degrees();
    let mut tilts: Vec<f64> = (0..)
        .map(|k| 10.0 * k as f64)
        .take_while(|t| *t < max - 1e-6)
        .collect();
    tilts.push(max);
    let mut out = Vec::new();
    for t in tilts {
        let azimuths: Vec<f64> = if t == 0.0 {
            vec![0.0]
        } else {
            (0..12).map(|k| 30.0 * k as f64).collect()
        };
        for a in azimuths {
            let spec = ZoneSpec {
                name: "candidate".into(),
                centre,
                tool: tool_of(t.to_radians(), a.to_radians()),
            };
            if let Ok(mut z) = layout(&i.machine, &i.setup, &options, &[(spec, piece_x)], errors) {
                out.push(z.remove(0));
            }
        }
    }
    out
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The scaled matrix's singular values, rank, `σ_r` and condition `σ₁/σ_r` of the designed and
/// of the paper's layout are those of `S` rebuilt here from the zones' sensitivities with the
/// documented scaling. A zone of 12 mm (half: 6 mm, so neither `zone/2 = zone % 2` nor
/// `zone·2`) with slopes measured checks the slope's lever.
#[test]
fn singular_values_rank_and_condition_are_those_of_the_documented_scaled_matrix() {
    let (i, o, d) = run(
        "B/C tilting",
        json!({ "grid": 2, "maxTilt": 20, "noise": 0.002, "setup": { "zoneSize": 12 } }),
    );
    assert!(o.slopes && i.setup.zone_size == 12.0);
    let p = d.errors.len();
    let r = d.reachable_rank;
    // Seven of the B/C table's fifteen errors are what any face test can see (README).
    assert_eq!(r, 7);

    let des = &d.designed;
    let sv = singular_values(&layout_rows(&des.zones, &d, &i, &o), p);
    assert_eq!(des.singular_values.len(), p);
    for (k, (a, b)) in des.singular_values.iter().zip(&sv).enumerate() {
        // Rounding-level values (the unseen directions) compare in absolute terms.
        assert!(
            (a - b).abs() <= 1e-9 * sv[0],
            "designed σ{}: {a} vs {b}",
            k + 1
        );
    }
    assert_eq!(des.rank, rank(&sv));
    assert_eq!(
        des.rank, r,
        "the designed layout reaches the reachable rank"
    );
    close_rel(des.smallest, sv[r - 1], 1e-9, "σ_r");
    close_rel(des.condition, sv[0] / sv[r - 1], 1e-9, "condition σ₁/σ_r");

    // The paper's nine zones: the same matrix, their tilt and azimuth those of their tool
    // vectors (Table 1: ZONE I square to the face, the others 30° towards the centre).
    let paper = d.paper.as_ref().unwrap();
    assert_eq!(paper.zones.len(), 9);
    for (z, def) in paper.zones.iter().zip(ZONES.iter()) {
        assert_eq!(z.setup, 1);
        let want_tilt = if def.name == "I" {
            0.0
        } else {
            30f64.to_radians()
        };
        assert!(
            (z.tilt - want_tilt).abs() < 1e-12,
            "{}: tilt {}",
            def.name,
            z.tilt
        );
        let t = tool_of(z.tilt, z.azimuth);
        for c in 0..3 {
            assert!(
                (t[c] - def.tool[c]).abs() < 1e-12,
                "{}: tool {t:?}",
                def.name
            );
        }
    }
    let psv = singular_values(&layout_rows(&paper.zones, &d, &i, &o), p);
    for (a, b) in paper.singular_values.iter().zip(&psv) {
        assert!((a - b).abs() <= 1e-9 * psv[0], "paper σ: {a} vs {b}");
    }
    assert_eq!(paper.rank, rank(&psv));
    // The paper's layout sees 5 of the 7 (README); its σ_r is then rounding noise, not zero,
    // and the condition is infinite, as documented for a rank short of r.
    assert_eq!(paper.rank, 5);
    assert!(paper.smallest > 0.0 && paper.smallest < 1e-9 * psv[0]);
    assert_eq!(paper.condition, f64::INFINITY);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The noise only divides `S` by a constant: the rank of every candidate together and of the
/// designed layout are the same at 1 mm, 1 µm and 1 nm, with σ₁ from about 10⁻² to 10⁴ (so a
/// rank threshold not relative to σ₁ would count rounding noise or drop the weak directions).
#[test]
fn the_noise_scales_the_matrix_and_changes_no_rank() {
    for noise in [1.0, 0.001, 1e-6] {
        let (i, o, d) = run(
            "B/C tilting",
            json!({ "grid": 2, "maxTilt": 20, "noise": noise }),
        );
        let p = d.errors.len();
        let sv = singular_values(&layout_rows(&d.designed.zones, &d, &i, &o), p);
        assert_eq!(d.reachable_rank, 7, "noise {noise}");
        assert_eq!(d.designed.rank, 7, "noise {noise}");
        assert_eq!(rank(&sv), 7, "noise {noise}");
        assert_eq!(d.paper.as_ref().unwrap().rank, 5, "noise {noise}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The chosen errors are the matrix's columns, in the order given.
#[test]
fn the_named_errors_are_the_columns_in_the_given_order() {
    let names = ["E_B0Z", "E_X0B", "E_C0Y"];
    let (_, _, d) = run(
        "B/C tilting",
        json!({ "parameters": names, "grid": 2, "maxTilt": 10 }),
    );
    let got: Vec<&str> = d.errors.iter().map(|e| e.name).collect();
    assert_eq!(got, names);
    let fit: Vec<&str> = d
        .designed
        .fit
        .estimates
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    assert_eq!(fit, names);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The zones of a 3 × 3 grid in two set-ups: names, centres, set-ups, the piece's place, and each
/// zone's sensitivities those of its tool vector at its place (rebuilt with `layout` in that
/// set-up). The piece stands 20 mm off the table's axis, the second set-up 150 mm further.
#[test]
fn zones_sit_on_the_documented_grid_in_both_set_ups() {
    let (i, o, d) = run(
        "B/C tilting",
        json!({ "grid": 3, "maxTilt": 10, "secondSetup": 150,
                "setup": { "zoneSize": 10, "workpieceX": 20 } }),
    );
    let (size, x1) = (10.0, 20.0);
    let x2 = x1 + 150.0;
    let z = &d.designed.zones;
    assert_eq!(z.len(), 18);
    let mut seen = Vec::new();
    for dz in z {
        let name = &dz.zone.spec.name;
        // Set-up 2's zones are named "S2-…" and cut with the piece at workpieceX + secondSetup.
        let (setup, piece_x, local) = match name.strip_prefix("S2-") {
            Some(rest) => (2, x2, rest),
            None => (1, x1, name.as_str()),
        };
        assert_eq!(dz.setup, setup, "{name}");
        assert_eq!(dz.zone.piece_x, piece_x, "{name}");
        // A column letter along u (A the smallest x) and a row number along v (1 the smallest
        // y); the centre is (i − (n−1)/2, j − (n−1)/2) zones from the face centre, n = 3.
        let b = local.as_bytes();
        assert_eq!(b.len(), 2, "{name}");
        let (ci, rj) = ((b[0] - b'A') as f64, (b[1] - b'1') as f64);
        assert!(ci < 3.0 && rj < 3.0, "{name}");
        assert_eq!(
            dz.zone.spec.centre,
            ((ci - 1.0) * size, (rj - 1.0) * size),
            "{name}"
        );
        seen.push((setup, name.clone()));
        // Its sensitivities: its tool vector at its centre, the piece at its set-up's place.
        let mine = candidates_at(&i, &o, &d.errors, piece_x, dz.zone.spec.centre);
        let same = mine
            .iter()
            .find(|c| (0..3).all(|k| (c.spec.tool[k] - dz.zone.spec.tool[k]).abs() < 1e-12));
        let same = same.unwrap_or_else(|| panic!("{name}: tool not among the candidates"));
        for (e, (a, b)) in dz
            .zone
            .sensitivity
            .iter()
            .zip(&same.sensitivity)
            .enumerate()
        {
            let scale = 1.0 + b.height.abs();
            assert!(
                (a.height - b.height).abs() < 1e-9 * scale
                    && (a.slope_x - b.slope_x).abs() < 1e-9 * scale
                    && (a.slope_y - b.slope_y).abs() < 1e-9 * scale,
                "{name} {}: {a:?} vs {b:?}",
                d.errors[e].name
            );
        }
    }
    // Every place once in each set-up.
    seen.sort();
    seen.dedup();
    assert_eq!(seen.len(), 18);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The search ends where no sweep improves (module docs): no single zone swapped for another
/// candidate of its place (rebuilt here with `layout` from the documented tilts and azimuths)
/// raises the rank or the r-th singular value. Two set-ups of a 2 × 2 grid, heights only: this
/// search needs more than one sweep. The number of candidates is the grid's: 2 set-ups × 4
/// places × (1 + 2 tilts × 12 azimuths), all reached by the B/C table's travel.
#[test]
fn no_single_zone_swap_improves_the_designed_layout() {
    let (i, o, d) = run(
        "B/C tilting",
        json!({ "grid": 2, "maxTilt": 20, "slopes": false, "secondSetup": 100 }),
    );
    let p = d.errors.len();
    let r = d.reachable_rank;
    let zones = &d.designed.zones;
    assert_eq!(zones.len(), 8);
    let rows: Vec<Vec<Vec<f64>>> = zones
        .iter()
        .map(|z| rows_of(&z.zone, &d.errors, i.setup.zone_size, &o))
        .collect();
    let sv = singular_values(&rows.concat(), p);
    assert_eq!(rank(&sv), r);
    let best = sv[r - 1];
    let mut count = 0;
    for (k, z) in zones.iter().enumerate() {
        let cands = candidates_at(&i, &o, &d.errors, z.zone.piece_x, z.zone.spec.centre);
        count += cands.len();
        for c in &cands {
            let mut trial = rows.clone();
            trial[k] = rows_of(c, &d.errors, i.setup.zone_size, &o);
            let s = singular_values(&trial.concat(), p);
            assert!(
                rank(&s) < r || s[r - 1] <= best * (1.0 + 1e-7),
                "{}: tool {:?} gives σ_r {} > {best}",
                z.zone.spec.name,
                c.spec.tool,
                s[r - 1]
            );
        }
    }
    assert_eq!(count, 2 * 4 * (1 + 2 * 12));
    assert_eq!(d.candidates, count);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The start: each zone's tool leans 30° towards the face centre (the paper's rule), or as near
/// to that as the candidates go: at min(maxTilt, 30°). It is what the design keeps where nothing
/// beats it: with E_Z0B alone (B's line moved along Z by δ) a zone's height moves by
/// δ·(1 − cos B), B the tool's tilt from the face normal, whatever its azimuth; when that tilt is
/// maxTilt (30°, or 21° below it) every candidate of a place at maxTilt does equally well, and a
/// tie is no improvement. So each edge zone of a 3 × 3 grid keeps its start, the azimuth towards
/// the centre (at 30°, the paper's Table 1 tool vector); at 30° a corner keeps its start too,
/// within 15° of the diagonal towards the centre (the azimuths are 30° apart). (At 21° a 20°
/// tool 15° off the diagonal is nearer the wanted vector than a 21° one, so a corner starts at
/// 20° and the search moves it.) The centre, started square to the face, moves to maxTilt.
#[test]
fn a_zone_nothing_improves_keeps_the_start_towards_the_centre() {
    for max_tilt in [30.0, 21.0] {
        let (_, _, d) = run(
            "B/C tilting",
            json!({ "parameters": ["E_Z0B"], "grid": 3, "maxTilt": max_tilt, "slopes": false,
                    "setup": { "zoneSize": 16 } }),
        );
        assert_eq!(d.reachable_rank, 1);
        let zones = &d.designed.zones;
        assert_eq!(zones.len(), 9);
        for z in zones {
            let (x, y) = z.zone.spec.centre;
            let name = &z.zone.spec.name;
            assert!(
                (z.tilt.to_degrees() - max_tilt).abs() < 1e-9,
                "maxTilt {max_tilt}, {name}: tilt {}",
                z.tilt.to_degrees()
            );
            if x == 0.0 && y == 0.0 {
                continue;
            }
            // Towards the centre: azimuth atan2(−y, −x).
            let want = (-y).atan2(-x);
            let off = (z.azimuth - want)
                .sin()
                .atan2((z.azimuth - want).cos())
                .abs();
            let what = format!(
                "maxTilt {max_tilt}, {name}: azimuth {}",
                z.azimuth.to_degrees()
            );
            if x == 0.0 || y == 0.0 {
                assert!(off < 1e-9, "{what}");
                if max_tilt == 30.0 {
                    // The paper's tool vector of the same place (Table 1).
                    let def = ZONES
                        .iter()
                        .find(|def| (def.col as f64 * 16.0, def.row as f64 * 16.0) == (x, y))
                        .unwrap();
                    for c in 0..3 {
                        assert!((z.zone.spec.tool[c] - def.tool[c]).abs() < 1e-12, "{name}");
                    }
                }
            } else if max_tilt == 30.0 {
                assert!((off - 15f64.to_radians()).abs() < 1e-9, "{what}");
            }
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// The fit's view of a layout needs a residual degree of freedom: four heights (a 2 × 2 grid,
/// no slopes) of four errors the design makes independent determine all four, each alone.
#[test]
fn four_heights_identify_four_independent_errors() {
    let names = ["E_X0B", "E_Z0B", "E_C0B", "E_B0Z"];
    let (_, _, d) = run(
        "B/C tilting",
        json!({ "parameters": names, "grid": 2, "maxTilt": 30, "slopes": false }),
    );
    assert_eq!(d.reachable_rank, 4);
    let r = &d.designed;
    assert_eq!(r.zones.len(), 4);
    assert_eq!(r.rank, 4);
    assert_eq!(r.fit.rank, 4);
    assert!(r.fit.groups.is_empty(), "{:?}", r.fit.groups);
    assert!(r.fit.estimates.iter().all(|e| e.value.is_some()));
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/design.rs` survived every other test.
/// While the rank is short of the reachable rank (a 2 × 2 grid of heights only: 4 values
/// against r ≥ 5), the search ranks layouts by their rank, then by the sum of the logarithms
/// of their singular values (module docs): no single zone swapped for another candidate of its
/// place raises the rank, or at the same rank that sum.
#[test]
fn short_of_the_reachable_rank_no_single_swap_raises_the_rank_or_the_log_sum() {
    let (i, o, d) = run(
        "B/C tilting",
        json!({ "grid": 2, "maxTilt": 40, "slopes": false }),
    );
    let p = d.errors.len();
    let zones = &d.designed.zones;
    assert_eq!(zones.len(), 4);
    let rows: Vec<Vec<Vec<f64>>> = zones
        .iter()
        .map(|z| rows_of(&z.zone, &d.errors, i.setup.zone_size, &o))
        .collect();
    let objective = |rows: &[Vec<f64>]| {
        let sv = singular_values(rows, p);
        let k = rank(&sv);
        (k, sv[..k].iter().map(|s| s.ln()).sum::<f64>())
    };
    let (k, best) = objective(&rows.concat());
    assert!(k < d.reachable_rank, "{k} of {}", d.reachable_rank);
    for (n, z) in zones.iter().enumerate() {
        let cands = candidates_at(&i, &o, &d.errors, z.zone.piece_x, z.zone.spec.centre);
        assert!(cands.len() > 1);
        for c in &cands {
            let mut trial = rows.clone();
            trial[n] = rows_of(c, &d.errors, i.setup.zone_size, &o);
            let (kt, s) = objective(&trial.concat());
            assert!(
                kt < k || (kt == k && s <= best + 1e-7 * best.abs()),
                "{}: tool {:?} gives rank {kt}, log-sum {s} against {k}, {best}",
                z.zone.spec.name,
                c.spec.tool
            );
        }
    }
}
