//! The cubic-machining test (Li, Sato, Shirase & Sakamoto 2021) against references written
//! independently of the engine: the paper's Table 2 and stated facts (Sections 4.3 and 5.1),
//! first-order closed forms derived by hand from eqs 2 and 10 (below), the paper's matrices
//! (eqs 2–12) evaluated here with nalgebra, central finite differences, mirror symmetry, and the
//! closed-form scallop height of a ball-end mill.
//!
//! **The closed forms.** With `Q = R_Z(C)`, `P = R_Y(B)` (eq 3) and a small error written as
//! `p ↦ p + ω×p + t` (eqs 4–9 to first order), eq 10 moves a point `w` of the workpiece
//! (coordinates from the rotary centre, W = machine frame at B = C = 0) by
//! `Ω×w + T` with, for an error of the B–Y group, `Ω = QPω − ω`, `T = QPt − t`, and for the C–B
//! group `Ω = Qω − ω`, `T = Qt − t` (eq 2 alone, without M_WC: drop the `− ω`, `− t`). The
//! height of a flat face at `(x, y)` changes by `T_z + Ω_x·y − Ω_y·x`, its slopes by
//! `∂z/∂x = −Ω_y`, `∂z/∂y = Ω_x`.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::li::{height_map, machine, run, try_run, CubicSetup, GeometricErrors, ERRORS};
use common::{close, Rng};
use fiveaxis::cubic::{CubicReference, Options, ZONES};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

const ALL_REFERENCES: [CubicReference; 3] = [
    CubicReference::Workpiece,
    CubicReference::ZoneIHeight,
    CubicReference::ZoneIPlane,
];

fn opts(transform: bool, reference: CubicReference) -> Options {
    Options {
        transform,
        reference,
    }
}

/// A unit of error `k`: 1 mm or 1 rad.
fn is_angle(k: usize) -> bool {
    ERRORS[k].angular
}

/// Paper's Table 2, degrees: (B, C) per zone in Table 1's order.
const TABLE_2: [(f64, f64); 9] = [
    (0.0, 0.0),
    (30.0, 0.0),
    (30.0, 90.0),
    (30.0, 180.0),
    (30.0, 270.0),
    (30.0, 45.0),
    (30.0, 135.0),
    (30.0, 225.0),
    (30.0, 315.0),
];

#[test]
fn table_2_angles_come_out_of_the_inverse_kinematics() {
    let names = [
        "I", "II-1", "II-2", "II-3", "II-4", "III-1", "III-2", "III-3", "III-4",
    ];
    for setup in [
        CubicSetup::default(),
        CubicSetup {
            c_offset: 40.0,
            table_above_b: -70.0,
            workpiece_x: 12.0,
            ..Default::default()
        },
    ] {
        let a = run(&setup, &GeometricErrors::default(), &Options::default());
        for (z, ((b, c), name)) in a.zones.iter().zip(TABLE_2.iter().zip(names)) {
            assert_eq!(z.zone.name, name);
            close(z.b.to_degrees(), *b, 1e-9, &format!("B of {name}"));
            close(z.c.to_degrees(), *c, 1e-9, &format!("C of {name}"));
        }
    }
    // Fig 2's layout: the centres.
    let a = run(
        &CubicSetup::default(),
        &GeometricErrors::default(),
        &Options::default(),
    );
    let centres: Vec<[f64; 2]> = a.zones.iter().map(|z| z.centre).collect();
    assert_eq!(
        centres,
        vec![
            [0.0, 0.0],
            [-16.0, 0.0],
            [0.0, -16.0],
            [16.0, 0.0],
            [0.0, 16.0],
            [-16.0, -16.0],
            [16.0, -16.0],
            [16.0, 16.0],
            [-16.0, 16.0]
        ]
    );
}

#[test]
fn zero_errors_give_zero_deviation() {
    for transform in [false, true] {
        for reference in ALL_REFERENCES {
            let a = run(
                &CubicSetup {
                    c_offset: 25.0,
                    workpiece_y: -5.0,
                    ..Default::default()
                },
                &GeometricErrors::default(),
                &opts(transform, reference),
            );
            for z in &a.zones {
                for v in [
                    z.exact.height,
                    z.exact.slope_x,
                    z.exact.slope_y,
                    z.linear.height,
                ] {
                    assert!(v.abs() < 1e-12, "{} {v}", z.zone.name);
                }
            }
        }
    }
}

/// The Section 5.3 single-error cases and more: each error alone at 0.5 mm or 0.5°.
fn half_unit(k: usize) -> f64 {
    if is_angle(k) {
        0.5f64.to_radians()
    } else {
        0.5
    }
}

#[test]
fn with_the_workpiece_transform_zone_i_is_unaffected_by_every_error() {
    // Section 4.3 / Fig 12: no rotary axis moves in ZONE I, so with M_WC nothing changes there,
    // whatever the errors (exactly, not only to first order).
    let mut rng = Rng::new(1);
    let mut cases: Vec<GeometricErrors> = (0..8)
        .map(|k| GeometricErrors::single(k, half_unit(k)))
        .collect();
    cases.push(GeometricErrors::table5());
    for _ in 0..5 {
        cases.push(GeometricErrors(std::array::from_fn(|k| {
            rng.range(-1.0, 1.0) * half_unit(k)
        })));
    }
    for setup in [
        CubicSetup::default(),
        CubicSetup {
            c_offset: 30.0,
            table_above_b: 20.0,
            ..Default::default()
        },
    ] {
        for e in &cases {
            let a = run(&setup, e, &opts(true, CubicReference::Workpiece));
            let z1 = &a.zones[0];
            assert_eq!(z1.zone.name, "I");
            for v in [z1.exact.height, z1.exact.slope_x, z1.exact.slope_y] {
                assert!(v.abs() < 1e-12, "{e:?}: {v}");
            }
            for k in &a.sensitivity[0] {
                assert!(k.height.abs() < 1e-12 && k.slope_x.abs() < 1e-12);
            }
        }
    }
}

#[test]
fn without_the_transform_zone_i_is_affected_by_dz_by_only_section_4_3_names_dx_by_by_a_slip() {
    // Eq 2 at B = C = 0: P_T = E_CB·E_BY·P_M. The centre of ZONE I, (0, 0, h) from the rotary
    // centre, moves by ω×(0, 0, h) + t, whose z is t_z = δzBY: k = +1 for δzBY (a tool higher
    // in table coordinates leaves material: positive), 0 for every other error. Section 4.3
    // says "the Z-axis offset from the rotational center, δxBY": an X offset only moves the face
    // sideways.
    let a = run(
        &CubicSetup::default(),
        &GeometricErrors::default(),
        &opts(false, CubicReference::Workpiece),
    );
    for (k, def) in ERRORS.iter().enumerate() {
        let expected = if def.key == "dzBY" { 1.0 } else { 0.0 };
        close(a.sensitivity[0][k].height, expected, 1e-12, def.key);
    }
    // Exactly, with the 0.5 mm of Section 5.3: the face rises by 0.5 mm; δxBY moves nothing up.
    let dz = run(
        &CubicSetup::default(),
        &GeometricErrors::single(2, 0.5),
        &opts(false, CubicReference::Workpiece),
    );
    close(dz.zones[0].exact.height, 0.5, 1e-12, "δzBY = 0.5 mm");
    let dx = run(
        &CubicSetup::default(),
        &GeometricErrors::single(0, 0.5),
        &opts(false, CubicReference::Workpiece),
    );
    close(dx.zones[0].exact.height, 0.0, 1e-12, "δxBY = 0.5 mm");
}

#[test]
fn alpha_by_and_alpha_cb_act_alike_on_heights_and_dy_by_dx_cb_not_at_all() {
    // Section 4.3 / Fig 12, with the workpiece transform.
    let (ia, ic) = (3, 6);
    for setup in [
        CubicSetup::default(),
        CubicSetup {
            table_above_b: -60.0,
            workpiece_height: 120.0,
            ..Default::default()
        },
    ] {
        let a = run(
            &setup,
            &GeometricErrors::default(),
            &opts(true, CubicReference::Workpiece),
        );
        let mut tilts_differ = false;
        for (z, k) in a.zones.iter().zip(&a.sensitivity) {
            close(k[ia].height, k[ic].height, 1e-9, z.zone.name);
            tilts_differ |= (k[ia].slope_y - k[ic].slope_y).abs() > 0.1;
            for i in [1, 7] {
                assert!(
                    k[i].height.abs() < 1e-12,
                    "{} {}",
                    z.zone.name,
                    ERRORS[i].key
                );
            }
        }
        assert!(
            tilts_differ,
            "the tilts of αBY and αCB need not agree, and do not"
        );
    }
    // δyBY (along the B axis itself) and δxCB (C turning about a parallel line) do nothing to
    // heights or slopes, exactly, even at 0.5 mm.
    for i in [1, 7] {
        let a = run(
            &CubicSetup::default(),
            &GeometricErrors::single(i, 0.5),
            &opts(true, CubicReference::Workpiece),
        );
        for z in &a.zones {
            for v in [z.exact.height, z.exact.slope_x, z.exact.slope_y] {
                assert!(v.abs() < 1e-12, "{} {}: {v}", ERRORS[i].key, z.zone.name);
            }
        }
    }
}

/// The first-order closed forms of the module docs: (height, slope x, slope y) per unit error
/// `k` at the zone centre `(x, y)` (workpiece frame), for a workpiece centred at `(wx, wy)` from
/// the C axis and a C axis `d` from the B axis along X. Points are taken from the C-frame origin
/// (on C at the height of B): `w = (x + wx, y + wy, ·)`. An error of the B–Y group turns about the
/// bed origin, which is at `−Q·d·x̂` from there at pose (B, C) and at `−d·x̂` at B = C = 0.
#[allow(clippy::too_many_arguments)]
fn closed_form(
    k: usize,
    b: f64,
    c: f64,
    x: f64,
    y: f64,
    wx: f64,
    wy: f64,
    d: f64,
    transform: bool,
) -> [f64; 3] {
    let q = |v: Vector3<f64>| {
        Vector3::new(
            c.cos() * v.x - c.sin() * v.y,
            c.sin() * v.x + c.cos() * v.y,
            v.z,
        )
    };
    let p = |v: Vector3<f64>| {
        Vector3::new(
            b.cos() * v.x + b.sin() * v.z,
            v.y,
            -b.sin() * v.x + b.cos() * v.z,
        )
    };
    let unit = |i: usize| Vector3::ith(i, 1.0);
    // Error k: B–Y group or C–B group, rotation or translation, about/along which axis.
    let (b_group, angular, axis) = match k {
        0..=2 => (true, false, k),
        3..=5 => (true, true, k - 3),
        6 => (false, true, 0),
        _ => (false, false, 0),
    };
    let u = unit(axis);
    let w = Vector3::new(x + wx, y + wy, 0.0);
    let (moved, lever_q, lever_0) = if b_group {
        (q(p(u)), w + q(unit(0)) * d, w + unit(0) * d)
    } else {
        (q(u), w, w)
    };
    if !angular {
        let t = if transform { moved - u } else { moved };
        return [t.z, 0.0, 0.0];
    }
    let mut h = moved.cross(&lever_q).z;
    let mut omega = moved;
    if transform {
        h -= u.cross(&lever_0).z;
        omega -= u;
    }
    [h, -omega.y, omega.x]
}

#[test]
fn first_order_sensitivities_match_the_closed_forms_of_eqs_2_and_10() {
    for setup in [
        CubicSetup::default(),
        CubicSetup {
            c_offset: 50.0,
            workpiece_x: -6.0,
            workpiece_y: 10.0,
            table_above_b: 30.0,
            ..Default::default()
        },
    ] {
        for transform in [false, true] {
            let a = run(
                &setup,
                &GeometricErrors::default(),
                &opts(transform, CubicReference::Workpiece),
            );
            for (z, (k, (b, c))) in a.zones.iter().zip(a.sensitivity.iter().zip(TABLE_2)) {
                let [x, y] = z.centre;
                for e in 0..8 {
                    let [h, sx, sy] = closed_form(
                        e,
                        b.to_radians(),
                        c.to_radians(),
                        x,
                        y,
                        setup.workpiece_x,
                        setup.workpiece_y,
                        setup.c_offset,
                        transform,
                    );
                    let what = format!("{} {} transform={transform}", z.zone.name, ERRORS[e].key);
                    close(k[e].height, h, 1e-9, &what);
                    close(k[e].slope_x, sx, 1e-9, &what);
                    close(k[e].slope_y, sy, 1e-9, &what);
                }
            }
        }
    }
    // Some values in words, with M_WC: δxBY lowers every outer zone by sin 30° = 0.5 per mm,
    // δzBY by 1 − cos 30°; βBY (B's zero) tilts the workpiece on C: 0 at C = 0°, 2·16 mm/rad
    // at C = 180°.
    let a = run(
        &CubicSetup::default(),
        &GeometricErrors::default(),
        &Options::default(),
    );
    close(a.sensitivity[1][0].height, -0.5, 1e-12, "δxBY II-1");
    close(
        a.sensitivity[7][2].height,
        30f64.to_radians().cos() - 1.0,
        1e-12,
        "δzBY III-3",
    );
    close(a.sensitivity[1][4].height, 0.0, 1e-9, "βBY II-1");
    close(a.sensitivity[3][4].height, 32.0, 1e-9, "βBY II-3");
}

#[test]
fn exact_heights_match_the_papers_matrices() {
    // Eq 10 (eq 2 without M_WC) evaluated here with nalgebra: the tool centre of eq 14 carried
    // from machine into workpiece coordinates, three points per zone, the plane through them
    // moved down by r. The workpiece centre sits on the C axis at height H above the rotary
    // centre, so W = machine coordinates shifted by H at B = C = 0 (eq 11).
    let rot = |axis: nalgebra::Unit<Vector3<f64>>, a: f64| {
        Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&axis, a),
        )
    };
    let tr = |x: f64, y: f64, z: f64| {
        Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
    };
    let mut rng = Rng::new(8);
    let setup = CubicSetup {
        table_above_b: 15.0,
        workpiece_height: 40.0,
        ..Default::default()
    };
    let h = setup.table_above_b + setup.workpiece_height;
    let r = setup.tool_radius;
    for trial in 0..12 {
        let e: [f64; 8] = std::array::from_fn(|k| rng.range(-1.0, 1.0) * half_unit(k));
        let [dx, dy, dz, al, be, ga, acb, dxcb] = e;
        let e_by = rot(Vector3::z_axis(), ga)
            * rot(Vector3::y_axis(), be)
            * rot(Vector3::x_axis(), al)
            * tr(dx, dy, dz);
        let e_cb = rot(Vector3::x_axis(), acb) * tr(dxcb, 0.0, 0.0);
        let m_wc = (e_cb * e_by).inverse();
        let transform = trial % 2 == 0;
        let a = run(
            &setup,
            &GeometricErrors(e),
            &opts(transform, CubicReference::Workpiece),
        );
        for (z, (b, c)) in a.zones.iter().zip(TABLE_2) {
            let (mb, mc) = (
                rot(Vector3::y_axis(), b.to_radians()),
                rot(Vector3::z_axis(), c.to_radians()),
            );
            let centre = |x: f64, y: f64| {
                // Nominal centre in W (from the rotary centre), then machine coordinates.
                let w = Point3::new(x, y, h + r);
                let pm = (mc * mb).inverse() * w;
                let pw = if transform {
                    m_wc * mc * e_cb * mb * e_by * pm
                } else {
                    mc * e_cb * mb * e_by * pm
                };
                pw.coords - Vector3::new(0.0, 0.0, h)
            };
            let [x, y] = z.centre;
            let (c1, c2, c3) = (centre(x, y), centre(x + 8.0, y), centre(x, y + 8.0));
            let n = (c2 - c1).cross(&(c3 - c1)).normalize();
            let s = c1 - r * n;
            let height = s.z - (n.x * (x - s.x) + n.y * (y - s.y)) / n.z;
            close(z.exact.height, height, 1e-11, z.zone.name);
            close(z.exact.slope_x, -n.x / n.z, 1e-12, z.zone.name);
            close(z.exact.slope_y, -n.y / n.z, 1e-12, z.zone.name);
        }
    }
}

#[test]
fn small_errors_act_linearly_and_the_sensitivities_are_the_exact_ratio_e_over_epsilon() {
    // Eq 15: k = E/ε stays constant over a decade of ε and equals the analytic k.
    for transform in [false, true] {
        let o = opts(transform, CubicReference::Workpiece);
        let base = run(&CubicSetup::default(), &GeometricErrors::default(), &o);
        for k in 0..8 {
            let unit = if is_angle(k) { 1e-5 } else { 1e-3 }; // 0.57 mdeg, 1 µm
            let mut ratios = Vec::new();
            for scale in [1.0, 10.0] {
                let eps = unit * scale;
                let a = run(&CubicSetup::default(), &GeometricErrors::single(k, eps), &o);
                ratios.push(a.single.iter().map(|s| s[k] / eps).collect::<Vec<_>>());
            }
            for z in 0..9 {
                let kz = base.sensitivity[z][k].height;
                // Translations act exactly linearly; rotations to second order: |E/ε − k| ≲ ε·L
                // with L ≲ 2·(53 + 2·22.6) ≈ 200 mm (the ball centres are 53 mm above the
                // rotary centre and up to 22.6 mm off it).
                let tol = if is_angle(k) {
                    10.0 * unit * 200.0
                } else {
                    1e-9
                };
                for r in &ratios {
                    close(r[z], kz, tol, &format!("{} zone {z}", ERRORS[k].key));
                }
                close(ratios[0][z], ratios[1][z], tol, "constant over a decade");
            }
        }
    }
    // Together, Table 5's errors add up linearly: Σ k·ε within 0.01 µm of the exact height.
    for transform in [false, true] {
        let a = run(
            &CubicSetup::default(),
            &GeometricErrors::table5(),
            &opts(transform, CubicReference::Workpiece),
        );
        for z in &a.zones {
            close(z.exact.height, z.linear.height, 1e-5, z.zone.name);
        }
    }
}

#[test]
fn sensitivities_agree_with_finite_differences_of_the_exact_heights() {
    let setups = [
        CubicSetup::default(),
        CubicSetup {
            c_offset: 35.0,
            table_above_b: -40.0,
            workpiece_height: 70.0,
            workpiece_x: 9.0,
            workpiece_y: -14.0,
            ..Default::default()
        },
    ];
    for setup in &setups {
        for transform in [false, true] {
            for reference in ALL_REFERENCES {
                let o = opts(transform, reference);
                let base = run(setup, &GeometricErrors::default(), &o);
                for (k, def) in ERRORS.iter().enumerate() {
                    let h = if def.angular { 1e-6 } else { 1e-4 };
                    let p = run(setup, &GeometricErrors::single(k, h), &o);
                    let m = run(setup, &GeometricErrors::single(k, -h), &o);
                    for z in 0..9 {
                        let fd = |f: fn(&fiveaxis::cubic::ZonePlane) -> f64| {
                            (f(&p.zones[z].exact) - f(&m.zones[z].exact)) / (2.0 * h)
                        };
                        let s = &base.sensitivity[z][k];
                        let what = format!("{} zone {z} {o:?}", def.key);
                        close(s.height, fd(|q| q.height), 1e-6, &what);
                        close(s.slope_x, fd(|q| q.slope_x), 1e-7, &what);
                        close(s.slope_y, fd(|q| q.slope_y), 1e-7, &what);
                    }
                }
            }
        }
    }
}

#[test]
fn mirroring_the_machine_in_y_maps_opposite_zones_onto_each_other() {
    // The mirror y → −y maps the machine onto itself with C → −C: II-2 ↔ II-4, III-1 ↔ III-4,
    // III-2 ↔ III-3 (I, II-1, II-3 onto themselves). Rotations about X and Z and translations
    // along Y change sign (R_X(a) → R_X(−a), R_Z(c) → R_Z(−c)), about Y do not. So the exact
    // heights with the mirrored errors are those of the mirror zone, slope y changes sign.
    let partner = [0, 1, 4, 3, 2, 8, 7, 6, 5];
    let sigma = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, -1.0, 1.0];
    let mut rng = Rng::new(4);
    for trial in 0..8 {
        let setup = CubicSetup {
            c_offset: if trial % 2 == 0 { 0.0 } else { 22.0 },
            table_above_b: rng.range(-50.0, 50.0),
            workpiece_x: rng.range(-10.0, 10.0),
            ..Default::default()
        };
        let e: [f64; 8] = std::array::from_fn(|k| rng.range(-1.0, 1.0) * half_unit(k));
        let m: [f64; 8] = std::array::from_fn(|k| sigma[k] * e[k]);
        for transform in [false, true] {
            for reference in ALL_REFERENCES {
                let o = opts(transform, reference);
                let a = run(&setup, &GeometricErrors(e), &o);
                let b = run(&setup, &GeometricErrors(m), &o);
                for (z, &p) in partner.iter().enumerate() {
                    let (u, v) = (&a.zones[z].exact, &b.zones[p].exact);
                    close(u.height, v.height, 1e-11, ZONES[z].name);
                    close(u.slope_x, v.slope_x, 1e-12, ZONES[z].name);
                    close(u.slope_y, -v.slope_y, 1e-12, ZONES[z].name);
                }
            }
        }
    }
    // With M_WC, the position errors and βBY give equal heights in mirror zones, αBY and αCB
    // opposite ones (first order, default machine).
    let a = run(
        &CubicSetup::default(),
        &GeometricErrors::default(),
        &Options::default(),
    );
    for (z, &p) in partner.iter().enumerate() {
        for k in 0..8 {
            close(
                a.sensitivity[z][k].height,
                sigma[k] * a.sensitivity[p][k].height,
                1e-9,
                ERRORS[k].key,
            );
        }
    }
}

#[test]
fn first_order_heights_depend_on_the_horizontal_set_up_only() {
    // The issue: "when the B and C axes intersect, the first-order zone heights do not depend on
    // [the set-up]". True, and more: a small rotation about a line through `a` moves `w` by
    // ω×(w − a), whose z involves only horizontal distances, so the vertical set-up (table and
    // workpiece heights) never enters the first order, offset axes or not. The workpiece's place
    // on the table does; the B–C offset only without M_WC.
    let zero = GeometricErrors::default();
    let k_of = |s: CubicSetup, transform: bool| {
        run(&s, &zero, &opts(transform, CubicReference::Workpiece)).sensitivity
    };
    let max_diff = |a: &[[fiveaxis::cubic::ZonePlane; 8]],
                    b: &[[fiveaxis::cubic::ZonePlane; 8]]| {
        a.iter()
            .zip(b)
            .flat_map(|(u, v)| u.iter().zip(v).map(|(p, q)| (p.height - q.height).abs()))
            .fold(0.0, f64::max)
    };
    for transform in [false, true] {
        for (c_offset, wx) in [(0.0, 0.0), (50.0, 0.0), (-20.0, 7.0)] {
            let at = |table: f64, height: f64| {
                k_of(
                    CubicSetup {
                        table_above_b: table,
                        workpiece_height: height,
                        c_offset,
                        workpiece_x: wx,
                        ..Default::default()
                    },
                    transform,
                )
            };
            let base = at(0.0, 50.0);
            for (table, height) in [(-80.0, 30.0), (0.0, 200.0), (45.0, 5.0)] {
                let d = max_diff(&base, &at(table, height));
                assert!(d < 1e-9, "vertical set-up changes k by {d}");
            }
        }
        // Horizontal: the workpiece's place on C always matters; the offset of C from B only
        // shifts βBY by −cOffset everywhere (the pose-independent lever from the B axis to
        // the C axis, see the closed forms), which M_WC removes.
        let base = k_of(CubicSetup::default(), transform);
        let moved = k_of(
            CubicSetup {
                workpiece_y: 10.0,
                ..Default::default()
            },
            transform,
        );
        assert!(max_diff(&base, &moved) > 1.0);
        let offset = k_of(
            CubicSetup {
                c_offset: 50.0,
                ..Default::default()
            },
            transform,
        );
        for z in 0..9 {
            for k in 0..8 {
                let shift = if k == 4 && !transform { -50.0 } else { 0.0 };
                close(
                    offset[z][k].height - base[z][k].height,
                    shift,
                    1e-9,
                    "cOffset",
                );
            }
        }
    }
    // Second order: without M_WC, αBY tilts ZONE I's face (a plane at height H above the rotary
    // centre) about an X axis through that centre; at the same (x, y) the tilted plane lies at
    // H / cos α, so the exact height is H·(1/cos α − 1): it depends on the workpiece height.
    let a = 0.5f64.to_radians();
    for height in [50.0, 300.0] {
        let s = CubicSetup {
            workpiece_height: height,
            ..Default::default()
        };
        let r = run(
            &s,
            &GeometricErrors::single(3, a),
            &opts(false, CubicReference::Workpiece),
        );
        let h = s.table_above_b + height;
        close(
            r.zones[0].exact.height,
            h * (1.0 / a.cos() - 1.0),
            1e-12,
            "ZONE I",
        );
    }
}

#[test]
fn levelled_on_zone_i_the_heights_do_not_depend_on_the_workpiece_transform() {
    // Section 5.1 / Fig 15: a measurement frame parallel to ZONE I's surface gives the same
    // profile with or without M_WC (to first order; exactly for the sensitivities).
    let setup = CubicSetup::default();
    let zero = GeometricErrors::default();
    let without = run(&setup, &zero, &opts(false, CubicReference::ZoneIPlane));
    let with = run(&setup, &zero, &opts(true, CubicReference::ZoneIPlane));
    for z in 0..9 {
        for k in 0..8 {
            close(
                without.sensitivity[z][k].height,
                with.sensitivity[z][k].height,
                1e-9,
                "k",
            );
        }
    }
    // Exactly, the difference is of second order: a few nm for Table 5, 100 times less for a
    // tenth of Table 5.
    let difference = |f: f64| {
        let e = GeometricErrors(GeometricErrors::table5().0.map(|v| v * f));
        let a = run(&setup, &e, &opts(false, CubicReference::ZoneIPlane));
        let b = run(&setup, &e, &opts(true, CubicReference::ZoneIPlane));
        (0..9)
            .map(|z| (a.zones[z].exact.height - b.zones[z].exact.height).abs())
            .fold(0.0, f64::max)
    };
    let (full, tenth) = (difference(1.0), difference(0.1));
    assert!(full < 1e-5, "{full}");
    assert!(tenth < 0.011 * full, "{tenth} vs {full}");
    let e = GeometricErrors::table5();
    // Shifting only ZONE I's height does not remove the difference (its tilt stays).
    let a = run(&setup, &e, &opts(false, CubicReference::ZoneIHeight));
    let b = run(&setup, &e, &opts(true, CubicReference::ZoneIHeight));
    let most = (0..9)
        .map(|z| (a.zones[z].exact.height - b.zones[z].exact.height).abs())
        .fold(0.0, f64::max);
    assert!(most > 5e-4, "{most}");
}

// ---- the height map

/// Mean of the scallop profile r − √(r² − u²) over one step, u ∈ [−a, a], a = step/2.
fn mean_scallop(r: f64, step: f64) -> f64 {
    let a = step / 2.0;
    r - (a * (r * r - a * a).sqrt() + r * r * (a / r).asin()) / (2.0 * a)
}

#[test]
fn the_scallops_have_the_closed_form_height() {
    // h = r − √(r² − (p/2)²) = 0.4167 µm for p = 0.1 mm, r = 3 mm. CubicGrid points every 0.05 mm
    // in Y fall on the passes and half-way between them.
    let setup = CubicSetup::default();
    let m = height_map(
        &setup,
        &GeometricErrors::default(),
        &Options::default(),
        97,
        961,
    )
    .unwrap();
    let h = 3.0 - (9.0f64 - 0.05 * 0.05).sqrt();
    close(h * 1e3, 0.4167, 5e-5, "the brief's 0.4167 µm");
    close(m.scallop, h, 1e-15, "reported");
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for iy in 0..m.ny {
        for ix in 0..m.nx {
            // Away from the zone borders (where passes of two zones meet).
            let (x, y) = (m.x[ix], m.y[iy]);
            let inner = |t: f64| ((t + 24.0) % 16.0 - 8.0).abs() < 7.0;
            if inner(x) && inner(y) {
                let v = m.height[iy * m.nx + ix];
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    close(lo, 0.0, 1e-12, "on the passes");
    close(hi, h, 1e-12, "half-way between passes");
}

/// Weighted average of the map over the inner part of each zone (`margin` from its borders).
fn inner_averages(m: &fiveaxis::cubic::HeightMap, margin: f64) -> Vec<f64> {
    ZONES
        .iter()
        .map(|z| {
            let (xc, yc) = (16.0 * z.col as f64, 16.0 * z.row as f64);
            let (mut s, mut n) = (0.0, 0.0);
            for iy in 0..m.ny {
                for ix in 0..m.nx {
                    if (m.x[ix] - xc).abs() <= 8.0 - margin && (m.y[iy] - yc).abs() <= 8.0 - margin
                    {
                        s += m.height[iy * m.nx + ix];
                        n += 1.0;
                    }
                }
            }
            s / n
        })
        .collect()
}

#[test]
fn the_height_map_agrees_with_the_analytic_zone_heights() {
    // Inner parts of the zones (1.5 mm from their borders): the analytic plane plus, in the
    // workpiece frame, the mean scallop (closed form), to 0.01 µm; grid points every p/8 in Y
    // sample the scallops finely whatever the errors' sideways shift.
    // Whole zones (the map's own averages): the same within the band where a lower neighbour's
    // ball cuts across the border, a strip of width U = √(2rΔ) lowered by Δ − u²/2r on average
    // (2/3)·Δ over U, i.e. (2/3)·Δ·U/16 mm per lower neighbour (Δ the difference of the centre
    // heights), times 1.5 for the zones' tilts along the border, plus 0.01 µm.
    let setup = CubicSetup::default();
    let r = setup.tool_radius;
    let cases = [
        (
            GeometricErrors::table5(),
            opts(true, CubicReference::Workpiece),
        ),
        (
            GeometricErrors::table5(),
            opts(false, CubicReference::Workpiece),
        ),
        (
            GeometricErrors::table5(),
            opts(true, CubicReference::ZoneIHeight),
        ),
        (
            GeometricErrors::table5(),
            opts(false, CubicReference::ZoneIPlane),
        ),
        (
            GeometricErrors::single(4, 0.02f64.to_radians()),
            opts(true, CubicReference::Workpiece),
        ),
    ];
    let s_bar = mean_scallop(r, setup.step());
    for (e, o) in cases {
        let a = run(&setup, &e, &o);
        let m = height_map(&setup, &e, &o, 193, 3841).unwrap();
        let inner = inner_averages(&m, 1.5);
        let shift = if o.reference == CubicReference::Workpiece {
            s_bar
        } else {
            0.0
        };
        for (z, zone) in a.zones.iter().enumerate() {
            let what = format!("{} {o:?}", zone.zone.name);
            close(inner[z], zone.exact.height + shift, 1e-5, &what);
            let mut tol = 1e-5;
            for (other, nb) in a.zones.iter().zip(ZONES) {
                if (nb.col - zone.zone.col).abs() + (nb.row - zone.zone.row).abs() == 1 {
                    let d = zone.exact.height - other.exact.height;
                    if d > 0.0 {
                        tol += 1.5 * 2.0 / 3.0 * d * (2.0 * r * d).sqrt() / 16.0;
                    }
                }
            }
            let got = m.zone_average[z];
            assert!(
                (got - zone.exact.height - shift).abs() <= tol,
                "{what}: map {got} vs {} (tol {tol})",
                zone.exact.height + shift
            );
        }
    }
}

#[test]
fn only_nearby_passes_are_visited_and_the_result_is_that_of_all_passes() {
    // Brute force, independent of the engine's capsule formula: every ball position along every
    // pass of the chain (every 0.005 mm), for grid points around the corner where ZONE I, II-2,
    // II-3 and III-2 meet. Large errors: wide bands, and δxCB moves zones sideways.
    let setup = CubicSetup::default();
    let r = setup.tool_radius;
    for e in [
        GeometricErrors::single(4, 0.5f64.to_radians()),
        GeometricErrors::single(7, 0.5),
        GeometricErrors::table5(),
    ] {
        let o = Options::default();
        let m = height_map(&setup, &e, &o, 385, 385).unwrap();
        let mut model = machine(&setup, &e).build().unwrap();
        model.place_workpiece(&Vector3::new(0.0, 0.0, setup.workpiece_height));
        let chain = model.chain;
        let set = fiveaxis::chain::Setup::AtPose(vec![0.0; 5]);
        let a = run(&setup, &e, &o);
        let ix: Vec<usize> = (0..m.nx).filter(|&i| (m.x[i] - 8.0).abs() < 0.6).collect();
        let iy: Vec<usize> = (0..m.ny).filter(|&i| (m.y[i] + 8.0).abs() < 0.6).collect();
        let mut brute = vec![setup.stock; ix.len() * iy.len()];
        for (z, zone) in a.zones.iter().enumerate() {
            let [xc, yc] = zone.centre;
            if (xc - 8.0).abs() > 12.0 || (yc + 8.0).abs() > 12.0 {
                continue;
            }
            let dir = Vector3::from(ZONES[z].tool);
            let q0 = vec![zone.b, zone.c, 0.0, 0.0, 0.0];
            for k in 0..setup.passes_per_zone() {
                let y = yc - 8.0 + k as f64 * setup.step();
                if (y + 8.0).abs() > r + 1.0 {
                    continue;
                }
                for s in 0..=3200 {
                    let x = xc - 8.0 + 16.0 * s as f64 / 3200.0;
                    if (x - 8.0).abs() > r + 1.0 {
                        continue;
                    }
                    let tip = Vector3::new(x - r * dir.x, y - r * dir.y, r * (1.0 - dir.z));
                    let (q, _) = chain.inverse(&tip, &dir, Some(&q0)).unwrap();
                    let p = chain.tool_pose(&q, true, &set).unwrap();
                    let c = p.tip + r * p.axis;
                    for (j, &jy) in iy.iter().enumerate() {
                        for (i, &jx) in ix.iter().enumerate() {
                            let d2 = (m.x[jx] - c.x).powi(2) + (m.y[jy] - c.y).powi(2);
                            if d2 <= r * r {
                                let b = &mut brute[j * ix.len() + i];
                                *b = b.min(c.z - (r * r - d2).sqrt());
                            }
                        }
                    }
                }
            }
        }
        // Sampling the balls every 0.005 mm along the pass leaves at most (0.0025)²/2r above.
        for (j, &jy) in iy.iter().enumerate() {
            for (i, &jx) in ix.iter().enumerate() {
                let got = m.height[jy * m.nx + jx];
                let b = brute[j * ix.len() + i];
                assert!(
                    got <= b + 1e-12 && b - got <= 1.1e-6,
                    "({}, {}): {got} vs brute force {b}",
                    m.x[jx],
                    m.y[jy]
                );
            }
        }
        // The band search visits far fewer points than all passes × all grid points.
        assert!(m.evaluations < m.passes * m.nx * m.ny / 20);
    }
}

#[test]
fn the_levelled_height_map_is_zero_on_zone_is_central_square() {
    // Levelled on ZONE I (inset by r = 3 mm from its borders): what remains there is the
    // scallops' oscillation about their mean, and the least-squares plane has removed the mean.
    let setup = CubicSetup::default();
    for e in [
        GeometricErrors::table5(),
        GeometricErrors::single(4, 0.3f64.to_radians()),
    ] {
        let m = height_map(
            &setup,
            &e,
            &opts(false, CubicReference::ZoneIPlane),
            97,
            1921,
        )
        .unwrap();
        let central = inner_averages(&m, 3.0)[0];
        close(central, 0.0, 1e-5, "ZONE I's central square");
    }
}

#[test]
fn bad_setups_and_grids_are_reported() {
    let e = GeometricErrors::default();
    let o = Options::default();
    let msg = |s: CubicSetup| try_run(&s, &e, &o).err().unwrap().to_string();
    assert!(msg(CubicSetup {
        pick: 7.0,
        ..Default::default()
    })
    .starts_with("setup.pick:"));
    let read = |v: serde_json::Value| {
        fiveaxis::cubic::CubicInput::read(&v)
            .err()
            .unwrap()
            .to_string()
    };
    assert!(
        read(serde_json::json!({ "setup": { "workpieceHeight": -1 } }))
            .starts_with("setup.workpieceHeight:")
    );
    assert!(read(serde_json::json!({ "setup": { "toolRadius": "3" } }))
        .starts_with("setup.toolRadius:"));
    assert!(
        read(serde_json::json!({ "machine": { "errors": { "E_A0B": 6 } } }))
            .starts_with("machine.errors.E_A0B:")
    );
    assert!(
        read(serde_json::json!({ "machine": { "errors": { "alphaBY": 0.1 } } }))
            .starts_with("machine.errors.alphaBY: alphaBY is the symbol αBY")
    );
    assert!(height_map(&CubicSetup::default(), &e, &o, 3, 10)
        .unwrap_err()
        .to_string()
        .starts_with("ny:"));
}
