//! The cubic test's analysis against its documented meaning: the piece's limits at and just past
//! their bounds, the zone planes' arithmetic, the three references, the first order's slopes, and
//! what the test says it can and cannot see ([`Visibility`]), each against a sensitivity table of
//! central differences of the exact heights computed here (each error alone, ±h), not the engine's
//! own table; the height map's trapezoid averages and levelling.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, machine_preset};
use fiveaxis::cubic::identify::{identify_zones, parse_measurements, CubicIdentifyInput};
use fiveaxis::cubic::{
    analyze, height_map, Analysis, CubicGrid, CubicInput, CubicReference, Options, ZonePlane,
    MAX_GRID_POINTS,
};
use fiveaxis::cubic::{CubicPiece, MAX_PASSES_PER_ZONE};
use fiveaxis::machine::Machine;
use fiveaxis::schema::{read_split, Inputs, Quantity};
use nalgebra::DMatrix;
use serde_json::json;

fn piece(zone: f64, radius: f64, pick: f64) -> CubicPiece {
    CubicPiece::from_value(
        &json!({ "zoneSize": zone, "toolRadius": radius, "pick": pick }),
        "",
    )
    .unwrap()
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
/// The pick feed must be less than the ball's diameter 2r: with r = 3 mm, 5.9 mm is accepted
/// and 6 mm refused.
#[test]
fn the_pick_must_be_less_than_the_ball_diameter() {
    assert!(piece(16.0, 3.0, 5.9).validate().is_ok());
    let e = piece(16.0, 3.0, 6.0).validate().unwrap_err();
    assert_eq!(e.field, "setup.pick");
    assert!(e.message.contains("diameter 6 mm"), "{}", e.message);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
/// The pick feed may equal the zone size (one pass at each edge: 2 passes) but not exceed it.
#[test]
fn the_pick_may_equal_the_zone_but_not_exceed_it() {
    let at = piece(16.0, 10.0, 16.0);
    assert!(at.validate().is_ok());
    assert_eq!(at.passes_per_zone(), 2);
    let e = piece(16.0, 10.0, 17.0).validate().unwrap_err();
    assert!(e.message.contains("zone size 16 mm"), "{}", e.message);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
/// `n = ⌈zone/pick⌉` intervals make n + 1 passes: exactly MAX_PASSES_PER_ZONE is accepted
/// (zone 20 mm, pick 20/19999 mm), one more (pick 0.001 mm: 20001 passes) refused.
#[test]
fn exactly_the_largest_number_of_passes_is_accepted() {
    let n = (MAX_PASSES_PER_ZONE - 1) as f64;
    let at = piece(20.0, 3.0, 20.0 / n);
    assert_eq!(at.passes_per_zone(), MAX_PASSES_PER_ZONE);
    assert!(at.validate().is_ok());
    let past = piece(20.0, 3.0, 0.001);
    assert_eq!(past.passes_per_zone(), 20_001);
    assert!(past
        .validate()
        .unwrap_err()
        .message
        .contains("passes per zone"));
}

fn machine(prefix: &str) -> Machine {
    Machine::from_value(&machine_preset(prefix), "machine").unwrap()
}

fn default_piece() -> fiveaxis::cubic::CubicPiece {
    CubicInput::read(&json!({})).unwrap().setup
}

/// The six machine presets the page offers (their names' beginnings).
const PRESETS: [&str; 6] = [
    "B/C tilting table",
    "B swivel head, C rotary table",
    "C/A double turntable",
    "A/C trunnion table",
    "A/C fork head",
    "B swivel head with C table",
];

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_zone_plane_is_its_height_plus_its_slopes_times_the_offset_from_its_centre() {
    // h = 1 mm, ∂h/∂x = 0.5, ∂h/∂y = −0.25 about the centre (10, 20): at (14, 16) the plane is
    // 1 + 0.5·4 + (−0.25)·(−4) = 4 mm; at the centre itself 1 mm.
    let p = ZonePlane {
        height: 1.0,
        slope_x: 0.5,
        slope_y: -0.25,
    };
    assert_eq!(p.at((10.0, 20.0), 14.0, 16.0), 4.0);
    assert_eq!(p.at((10.0, 20.0), 10.0, 20.0), 1.0);
    assert_eq!(p.at((10.0, 20.0), 10.0, 24.0), 0.0);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn the_options_are_the_inputs_transform_and_reference() {
    for (transform, key, reference) in [
        (false, "zone1-plane", CubicReference::ZoneIPlane),
        (true, "zone1-height", CubicReference::ZoneIHeight),
        (false, "workpiece", CubicReference::Workpiece),
    ] {
        let input = CubicInput::read(&json!({ "transform": transform, "reference": key })).unwrap();
        assert_eq!(
            input.options(),
            Options {
                transform,
                reference
            },
            "{key}"
        );
    }
}

/// A trunnion with errors of both axes (angles up to `3e-4·scale` rad, offsets up to
/// `0.02·scale` mm) that move and tilt ZONE I without the workpiece set at zero.
fn erroneous_trunnion(scale: f64) -> Machine {
    let mut m = machine("A/C trunnion table");
    for (name, v) in [
        ("E_Y0A", 0.02),
        ("E_Z0A", -0.015),
        ("E_B0A", 3e-4),
        ("E_A0C", -2e-4),
        ("E_B0C", 1.5e-4),
        ("E_A0A", 1e-4),
    ] {
        m.errors.set(name, v * scale).unwrap();
    }
    m
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn heights_from_zone_i_are_the_workpiece_heights_less_zone_is_height_or_plane() {
    // Module docs: "zone1-height" subtracts ZONE I's height from every zone and keeps the
    // slopes; "zone1-plane" subtracts ZONE I's plane, extended to each zone's centre, and its
    // slopes. Checked on the exact planes and on every error's sensitivity.
    let m = erroneous_trunnion(1.0);
    let piece = default_piece();
    let run = |reference| {
        analyze(
            &m,
            &piece,
            &Options {
                transform: false,
                reference,
            },
        )
        .unwrap()
    };
    let w = run(CubicReference::Workpiece);
    let zh = run(CubicReference::ZoneIHeight);
    let zp = run(CubicReference::ZoneIPlane);
    let z1 = w.zones[0].exact;
    let c1 = (w.zones[0].centre[0], w.zones[0].centre[1]);
    // ZONE I must be off its nominal height and tilted both ways, or the checks below see
    // nothing.
    assert!(z1.height.abs() > 1e-3, "{z1:?}");
    assert!(z1.slope_x.abs() > 1e-5 && z1.slope_y.abs() > 1e-5, "{z1:?}");
    for (z, zone) in w.zones.iter().enumerate() {
        let (x, y) = (zone.centre[0], zone.centre[1]);
        let what = zone.zone.name;
        let p = zone.exact;
        let under = z1.height + z1.slope_x * (x - c1.0) + z1.slope_y * (y - c1.1);
        close(zh.zones[z].exact.height, p.height - z1.height, 1e-12, what);
        close(zh.zones[z].exact.slope_x, p.slope_x, 1e-15, what);
        close(zh.zones[z].exact.slope_y, p.slope_y, 1e-15, what);
        close(zp.zones[z].exact.height, p.height - under, 1e-12, what);
        close(
            zp.zones[z].exact.slope_x,
            p.slope_x - z1.slope_x,
            1e-15,
            what,
        );
        close(
            zp.zones[z].exact.slope_y,
            p.slope_y - z1.slope_y,
            1e-15,
            what,
        );
        for e in 0..w.errors.len() {
            let (k, k1) = (w.sensitivity[z][e], w.sensitivity[0][e]);
            let what = format!("{what} {}", w.errors[e].name);
            let under = k1.height + k1.slope_x * (x - c1.0) + k1.slope_y * (y - c1.1);
            close(
                zh.sensitivity[z][e].height,
                k.height - k1.height,
                1e-9,
                &what,
            );
            close(zp.sensitivity[z][e].height, k.height - under, 1e-9, &what);
            close(
                zp.sensitivity[z][e].slope_x,
                k.slope_x - k1.slope_x,
                1e-12,
                &what,
            );
            close(
                zp.sensitivity[z][e].slope_y,
                k.slope_y - k1.slope_y,
                1e-12,
                &what,
            );
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn the_first_order_slopes_follow_the_exact_slopes_of_several_errors_together() {
    // `linear` is Σ k·ε over the errors (height and both slopes); with angles up to 3·10⁻⁵ rad
    // the exact planes differ from it by second-order terms: below 10⁻⁸ in a slope (ε² ≈ 10⁻⁹
    // per pair of errors) and L·ε² ≈ 200 mm · 10⁻⁹ per pair in a height, while the slopes
    // themselves are of order ε.
    let m = erroneous_trunnion(0.1);
    let a = analyze(&m, &default_piece(), &Options::default()).unwrap();
    let mut tilted = (0.0f64, 0.0f64);
    for z in &a.zones {
        let what = z.zone.name;
        close(z.linear.slope_x, z.exact.slope_x, 1e-8, what);
        close(z.linear.slope_y, z.exact.slope_y, 1e-8, what);
        close(z.linear.height, z.exact.height, 5e-6, what);
        tilted.0 = tilted.0.max(z.exact.slope_x.abs());
        tilted.1 = tilted.1.max(z.exact.slope_y.abs());
    }
    assert!(tilted.0 > 1e-6 && tilted.1 > 1e-6, "{tilted:?}");
}

/// Central differences of the exact zone planes, each error alone at ±h (10⁻⁶ rad or
/// 10⁻⁴ mm), per mm or per rad: `[zone][error]`.
fn sensitivity_by_differences(m: &Machine, errors: &[&str]) -> Vec<Vec<ZonePlane>> {
    let piece = default_piece();
    let at = |name: &str, v: f64| -> Analysis {
        let mut m = m.clone();
        m.errors.set(name, v).unwrap();
        analyze(&m, &piece, &Options::default()).unwrap()
    };
    let mut k = vec![vec![ZonePlane::default(); errors.len()]; 9];
    for (e, name) in errors.iter().enumerate() {
        let angle = m
            .error_defs()
            .iter()
            .any(|d| d.name == *name && d.quantity == Quantity::SmallAngle);
        let h = if angle { 1e-6 } else { 1e-4 };
        let (p, q) = (at(name, h), at(name, -h));
        for (z, row) in k.iter_mut().enumerate() {
            let d = |f: fn(&ZonePlane) -> f64| {
                (f(&p.zones[z].exact) - f(&q.zones[z].exact)) / (2.0 * h)
            };
            row[e] = ZonePlane {
                height: d(|p| p.height),
                slope_x: d(|p| p.slope_x),
                slope_y: d(|p| p.slope_y),
            };
        }
    }
    k
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn the_test_reports_what_it_cannot_see_and_what_it_cannot_tell_apart_on_every_preset() {
    // Against central differences of the exact heights (each error alone), in the errors' own
    // units; an angle's column is compared per zone size (a height change over the zone), as
    // the module docs say, so that both kinds are dimensionless.
    let mut seen_tilt_only = 0;
    let mut seen_groups = 0;
    for preset in PRESETS {
        let m = machine(preset);
        let zone = default_piece().zone_size;
        let a = analyze(&m, &default_piece(), &Options::default()).unwrap();
        let names: Vec<&str> = a.errors.iter().map(|d| d.name).collect();
        let k = sensitivity_by_differences(&m, &names);
        let n = names.len();
        let per = |e: usize| {
            if a.errors[e].quantity == Quantity::SmallAngle {
                zone
            } else {
                1.0
            }
        };
        let col = |e: usize| -> Vec<f64> { (0..9).map(|z| k[z][e].height / per(e)).collect() };
        let norm = |c: &[f64]| c.iter().map(|x| x * x).sum::<f64>().sqrt();
        // Differences carry ~1e-9 of rounding: a column is zero below 1e-7, non-zero above
        // 1e-3 (every preset's columns are one or the other).
        let zero: Vec<bool> = (0..n)
            .map(|e| {
                let s = norm(&col(e));
                assert!(!(1e-7..1e-3).contains(&s), "{preset} {}: {s}", names[e]);
                s < 1e-7
            })
            .collect();
        let invisible: Vec<&str> = (0..n).filter(|&e| zero[e]).map(|e| names[e]).collect();
        assert_eq!(a.visibility.invisible, invisible, "{preset}");
        // Tilt-only: invisible, yet some zone's slope moves (per rad, of order 1).
        let tilts = |e: usize| (0..9).any(|z| k[z][e].slope_x.abs() + k[z][e].slope_y.abs() > 1e-4);
        let tilt_only: Vec<&str> = (0..n)
            .filter(|&e| zero[e] && tilts(e))
            .map(|e| names[e])
            .collect();
        assert_eq!(a.visibility.tilt_only, tilt_only, "{preset}");
        seen_tilt_only += tilt_only.len();

        // Alike: visible errors whose height columns are parallel, each group listed once with
        // at least two members, the first one's factor 1 and every member k = factor · k_first.
        let parallel = |a: usize, b: usize| {
            let (ca, cb) = (col(a), col(b));
            let dot: f64 = ca.iter().zip(&cb).map(|(x, y)| x * y).sum();
            let cos = dot.abs() / (norm(&ca) * norm(&cb));
            // Parallel to rounding (1 − cos below 10⁻⁸) or clearly not (above 10⁻⁶).
            assert!(
                !(1e-8..1e-6).contains(&(1.0 - cos)),
                "{preset} {} {}: cos {cos}",
                names[a],
                names[b]
            );
            1.0 - cos < 1e-8
        };
        let mut listed = vec![0; n];
        for group in &a.visibility.alike {
            assert!(group.len() >= 2, "{preset}: {group:?}");
            assert_eq!(group[0].1, 1.0, "{preset}: {group:?}");
            let first = names.iter().position(|d| *d == group[0].0).unwrap();
            for &(member, factor) in group {
                let e = names.iter().position(|d| *d == member).unwrap();
                listed[e] += 1;
                assert!(!zero[e], "{preset}: {member} is invisible yet in {group:?}");
                let scale = norm(&col(first)) * per(first);
                for (z, row) in k.iter().enumerate() {
                    let what = format!("{preset} {member} zone {z}");
                    close(
                        row[e].height,
                        factor * row[first].height,
                        1e-6 * scale,
                        &what,
                    );
                }
            }
            seen_groups += 1;
        }
        for a_ in 0..n {
            assert!(listed[a_] <= 1, "{preset}: {} in two groups", names[a_]);
            for b in a_ + 1..n {
                if !zero[a_] && !zero[b] && parallel(a_, b) {
                    let together = a.visibility.alike.iter().any(|g| {
                        g.iter().any(|m| m.0 == names[a_]) && g.iter().any(|m| m.0 == names[b])
                    });
                    assert!(
                        together,
                        "{preset}: {} and {} act alike",
                        names[a_], names[b]
                    );
                }
            }
        }
        // Rank of the 9 × n height table (singular values above 10⁻⁶ of the largest).
        let table = DMatrix::from_fn(9, n, |z, e| col(e)[z]);
        let sv = table.svd(false, false).singular_values;
        let top = sv.max();
        let rank = sv.iter().filter(|s| **s > 1e-6 * top).count();
        assert!(
            sv.iter().all(|s| *s > 1e-4 * top || *s < 1e-8 * top),
            "{preset}: {sv}"
        );
        assert_eq!(a.visibility.rank, rank, "{preset}");
        assert!(rank > 0);
    }
    // The presets between them have tilt-only errors and groups, or the checks above saw none.
    assert!(seen_tilt_only >= 2 && seen_groups >= 6);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_table_axis_offset_across_it_and_along_the_spindle_act_alike_by_tan_15_degrees() {
    // Li et al.'s B/C table, axes intersecting: an offset t of B moves a workpiece point by
    // t − Qᵀt with Qᵀ = R_Z(c)·R_Y(b) (module docs of cubic::any_machine), so a zone cut at B = b
    // rises by −(R_Y(b)e_x)_z = sin b per mm along X and 1 − cos b per mm along Z. Every outer
    // zone is cut at |b| = 30° (ZONE I at 0: both zero), so E_Z0B = tan 15° · E_X0B in every zone,
    // the sign that of b: the pair is one group of factor ± (1 − cos 30°)/sin 30°.
    let m = machine("B/C tilting table");
    let a = analyze(&m, &default_piece(), &Options::default()).unwrap();
    let group = a
        .visibility
        .alike
        .iter()
        .find(|g| g[0].0 == "E_X0B")
        .unwrap();
    assert_eq!(group.len(), 2, "{group:?}");
    assert_eq!(group[1].0, "E_Z0B");
    let t15 = (1.0 - 30f64.to_radians().cos()) / 30f64.to_radians().sin();
    close(group[1].1.abs(), t15, 1e-12, "|factor|");
    close(t15, 15f64.to_radians().tan(), 1e-15, "tan 15°");
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_measured_zone_without_piece_x_is_on_the_pieces_own_place_and_slopes_in_um_per_mm_are_thousandths(
) {
    // Module docs of `cubic::identify`: `piece_x_mm` is the set-up of a zone (the piece moved
    // along the face's first axis); left empty, the zone is on the piece's `workpieceX`.
    // `slope_x_um_per_mm` is in µm per mm: 5 µm/mm is 0.005 mm/mm.
    let piece = CubicInput::read(&json!({ "setup": { "workpieceX": 12.5 } }))
        .unwrap()
        .setup;
    let csv = "zone,piece_x_mm,height_um,slope_x_um_per_mm,slope_y\n\
               I,,1.5,5,0.002\n\
               II-1,-40,-2,-7.5,\n";
    let zones = parse_measurements(csv, &piece).unwrap();
    assert_eq!(zones.len(), 2);
    assert_eq!(zones[0].zone.1, 12.5);
    assert_eq!(zones[1].zone.1, -40.0);
    close(zones[0].height, 0.0015, 1e-15, "1.5 µm");
    close(zones[0].slope_x.unwrap(), 0.005, 1e-15, "5 µm/mm");
    close(zones[1].slope_x.unwrap(), -0.0075, 1e-15, "−7.5 µm/mm");
    assert_eq!(zones[0].slope_y, Some(0.002));
    assert_eq!(zones[1].slope_y, None);
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_file_too_short_to_fit_is_the_files_fault() {
    // One zone's height cannot be fitted (the fit needs two measurements at least): the error
    // points at the file the user gave (`csv`), not at the engine's internal fit.
    let m = machine_preset("B/C tilting table");
    let v = json!({ "machine": m, "csv": "zone,height_um\nII-1,3\n" });
    let (input, own): (CubicInput, CubicIdentifyInput) = read_split(&v, "").unwrap();
    let e = identify_zones(&input, &own).unwrap_err();
    assert_eq!(e.field, "csv", "{e}");
    assert!(e.message.contains("nothing to fit"), "{e}");
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_height_map_of_more_than_four_million_points_is_refused_before_anything_is_cut() {
    // A trunnion whose A stops at 20° cannot cut ZONE II-1 (A = 30°): a grid within the limit
    // gets as far as the machine and fails there; one point past it fails on the grid first.
    let mut v = machine_preset("A/C trunnion table");
    v["rotary"]["mFrom"] = json!(0);
    v["rotary"]["mTo"] = json!(20);
    let m = Machine::from_value(&v, "machine").unwrap();
    let run = |nx: usize, ny: usize| {
        let grid = CubicGrid::from_value(&json!({ "nx": nx, "ny": ny }), "").unwrap();
        height_map(&m, &default_piece(), &Options::default(), &grid).unwrap_err()
    };
    assert_eq!(MAX_GRID_POINTS, 4_000_000);
    for (nx, ny) in [(2000, 2000), (1000, 4000), (4000, 1000)] {
        let e = run(nx, ny);
        assert_eq!(e.field, "machine", "{nx} × {ny}: {e}");
    }
    for (nx, ny) in [(2000, 2001), (2001, 2000), (4001, 4001)] {
        let e = run(nx, ny);
        assert_eq!(e.field, "nx", "{nx} × {ny}: {e}");
        assert!(e.message.contains("at most 4000000"), "{e}");
    }
}

/// Trapezoidal weights of the grid coordinates `v` over `[c − half, c + half]`: 1 inside, ½ on
/// the ends (a grid point on a zone border counts half for each zone).
fn trapezoid(v: &[f64], c: f64, half: f64) -> Vec<(usize, f64)> {
    v.iter()
        .enumerate()
        .filter_map(|(i, &t)| {
            let d = (t - c).abs();
            if (d - half).abs() < 1e-9 {
                Some((i, 0.5))
            } else if d < half {
                Some((i, 1.0))
            } else {
                None
            }
        })
        .collect()
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn the_height_map_averages_each_zone_by_the_trapezoid_rule_and_levels_on_zone_is_centre() {
    // Module docs of `height_map`: zone averages by the trapezoidal rule (borders count half);
    // "zone1-height" subtracts the average, "zone1-plane" the least-squares plane, of ZONE I's
    // central square, inset from its borders by r, at most a quarter of the zone side. A 5 mm
    // ball on 16 mm zones: the inset is 4 mm (a quarter), so the square is |x|, |y| ≤ 4 mm.
    // Checked against the workpiece-frame map of the same cut, with a plane fitted here by
    // the normal equations of all three unknowns at once.
    let m = erroneous_trunnion(1.0);
    let input = CubicInput::read(&json!({
        "setup": { "zoneSize": 16, "toolRadius": 5, "pick": 2 }
    }))
    .unwrap();
    let grid = CubicGrid::from_value(&json!({ "nx": 49, "ny": 97 }), "").unwrap();
    let map = |reference| {
        let options = Options {
            transform: false,
            reference,
        };
        height_map(&m, &input.setup, &options, &grid).unwrap()
    };
    let w = map(CubicReference::Workpiece);
    let (nx, z) = (w.nx, 16.0);
    let square = |xc: f64, yc: f64, half: f64| -> Vec<(usize, f64)> {
        let wx = trapezoid(&w.x, xc, half);
        trapezoid(&w.y, yc, half)
            .into_iter()
            .flat_map(|(iy, wy)| wx.iter().map(move |&(ix, wx)| (iy * nx + ix, wx * wy)))
            .collect()
    };
    let mean = |h: &[f64], idx: &[(usize, f64)]| {
        idx.iter().map(|&(i, wi)| wi * h[i]).sum::<f64>() / idx.iter().map(|p| p.1).sum::<f64>()
    };
    // Grid steps 1 mm along X and 0.5 mm along Y: zone borders (±8 mm, ±24 mm) and the
    // square's (±4 mm) fall on grid points in both directions.
    for (k, zone) in fiveaxis::cubic::ZONES.iter().enumerate() {
        let idx = square(zone.col as f64 * z, zone.row as f64 * z, z / 2.0);
        assert_eq!(
            idx.iter().filter(|p| p.1 == 0.25).count(),
            4,
            "{}",
            zone.name
        );
        close(w.zone_average[k], mean(&w.height, &idx), 1e-12, zone.name);
    }
    let centre = square(0.0, 0.0, 4.0);
    let level = mean(&w.height, &centre);
    let h = map(CubicReference::ZoneIHeight);
    for (a, b) in h.height.iter().zip(&w.height) {
        close(*a, b - level, 1e-12, "zone1-height");
    }
    // Weighted least squares h ≈ a + b·x + c·y over the square.
    let (mut n, mut rhs) = (nalgebra::Matrix3::zeros(), nalgebra::Vector3::zeros());
    for &(i, wi) in &centre {
        let v = nalgebra::Vector3::new(1.0, w.x[i % nx], w.y[i / nx]);
        n += wi * v * v.transpose();
        rhs += wi * w.height[i] * v;
    }
    let plane = n.lu().solve(&rhs).unwrap();
    assert!(plane[1].abs() > 1e-5 && plane[2].abs() > 1e-5, "{plane}");
    let p = map(CubicReference::ZoneIPlane);
    for iy in 0..p.ny {
        for ix in 0..nx {
            let under = plane[0] + plane[1] * w.x[ix] + plane[2] * w.y[iy];
            let k = iy * nx + ix;
            close(p.height[k], w.height[k] - under, 1e-12, "zone1-plane");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_coarse_map_levelled_on_one_column_of_zone_i_stays_finite() {
    // 5 × 5 points over three 16 mm zones (12 mm apart): ZONE I's central square (inset by the
    // 3 mm ball: |x|, |y| ≤ 5 mm) holds the centre alone, so no slope can be fitted there; levelling on ZONE I's plane
    // is then levelling on its height, never a 0/0.
    let m = erroneous_trunnion(1.0);
    let grid = CubicGrid::from_value(&json!({ "nx": 5, "ny": 5 }), "").unwrap();
    let run = |reference| {
        let options = Options {
            transform: false,
            reference,
        };
        height_map(&m, &default_piece(), &options, &grid).unwrap()
    };
    let plane = run(CubicReference::ZoneIPlane);
    let height = run(CubicReference::ZoneIHeight);
    for (a, b) in plane.height.iter().zip(&height.height) {
        assert!(a.is_finite(), "{a}");
        close(*a, *b, 1e-12, "one point: plane = height");
    }
}

/// Li et al.'s B/C table with one error motion of the spindle's X slide (tool side), `E_ZX`.
fn li_with_e_zx(e_zx: serde_json::Value) -> Machine {
    let mut v = machine_preset("B/C tilting table");
    v["motions"] = json!({ "E_ZX": e_zx });
    Machine::from_value(&v, "machine").unwrap()
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn a_curved_straightness_gives_the_slope_of_the_secant_over_half_a_zone() {
    // Module docs: the tilt comes from three actual centres, the zone centre and zoneSize/2
    // along u and v. With X's straightness E_ZX = c·X² (the tool c·X² higher along Z at X) the
    // surface is curved; ZONE I (B = C = 0, X = x on the face) gets the secant's slope
    // c·((z/2)² − 0)/(z/2) = c·z/2 along x and none along y. Its centre is cut at the nominal
    // height (c·0² = 0), but the ball (r = 3 mm) touches a plane of slope s a little lower,
    // by r·(√(1 + s²) − 1). c = 10⁻⁵ /mm, z = 16 mm: s = 8·10⁻⁵.
    let c = 1e-5;
    let m = li_with_e_zx(json!({ "poly": [0, 0, c] }));
    let a = analyze(&m, &default_piece(), &Options::default()).unwrap();
    let z1 = a.zones[0].exact;
    let s = c * 16.0 / 2.0;
    close(z1.slope_x, s, 1e-12, "slope along x");
    close(z1.slope_y, 0.0, 1e-12, "slope along y");
    close(
        z1.height,
        -3.0 * ((1.0 + s * s).sqrt() - 1.0),
        1e-14,
        "height",
    );
}

// Found by cargo-mutants: a mutant in `crate/src/cubic/mod.rs` survived every other test.
#[test]
fn errors_that_tilt_a_zone_by_more_than_60_degrees_are_refused() {
    // E_ZX rising 4 mm over X from 0 to 1 mm: on 2 mm zones ZONE I's secant over 1 mm rises
    // 4 mm, a tilt of atan 4 = 76° (> 60°); 1.5 mm (56°) is accepted.
    let piece = CubicInput::read(&json!({ "setup": { "zoneSize": 2, "pick": 1 } }))
        .unwrap()
        .setup;
    let table = |rise: f64| {
        li_with_e_zx(json!({ "position": [-100, 0, 1, 100], "value": [0, 0, rise, rise] }))
    };
    let e = analyze(&table(4.0), &piece, &Options::default()).unwrap_err();
    assert_eq!(e.field, "machine.errors");
    assert!(e.message.contains("more than 60°"), "{e}");
    let a = analyze(&table(1.5), &piece, &Options::default()).unwrap();
    close(a.zones[0].exact.slope_x, 1.5, 1e-9, "56°");
}
