//! The test designer: for a machine and the errors a user cares about, the cubic test (the tool
//! vector of each zone, the number of zones and optionally a second set-up with the piece moved
//! along the face's first axis, off the table's axis) that makes every error the kind of test
//! can reveal identifiable, as well as possible.
//!
//! # What is maximised (the scaling)
//! Each error is scaled by a typical size, 10 µm for a position and 10 µm over 100 mm
//! (10⁻⁴ rad, 20.6″) for an angle, and every measured value by its noise: a height by `noise`,
//! a slope by `noise` over half a zone (as in [`super::identify::system`]). In this scaled
//! matrix `S` the `r`-th singular value (`r` the rank any such test can reach, below) is the
//! root-sum-square effect, in noise standard deviations, of the weakest combination of errors
//! of typical size that the test can see. The designer maximises it; a value below about 3 says
//! the test hardly sees that combination above the noise.
//!
//! # What any such test can reveal
//! The candidates are every zone position of an `n × n` grid on the face, every tilt from 0 to
//! `maxTilt` in 10° steps (and `maxTilt`) and every azimuth in 30° steps, in each set-up, kept
//! when the machine reaches them within its travel. The rank `r` of all the candidates' rows
//! stacked together is the most any test of this kind can determine; the errors and
//! combinations outside it are reported (with the fit's groups, [`crate::identify::fit`]) as
//! what no such test can see: e.g. an offset along a rotary axis's own line (a rotation about
//! its line moves no point of the line), an error the workpiece set-up at zero absorbs (a
//! table axis's zero), or a table axis's offset across its line, which only moves the piece
//! within the face's plane.
//!
//! Heights are taken from the workpiece frame (`reference` `workpiece`), so that each zone's
//! rows are its own; `transform` (the workpiece set at zero) is the input's.
//!
//! # The search
//! On the layout's Gram matrix `SᵀS` (the sum of each zone's share), whose eigenvalues are the
//! squared singular values. Coordinate ascent from the paper's layout (the candidate nearest 30° towards the centre, or maxTilt when smaller): for each zone in turn
//! every candidate tool vector at its position is tried and the best kept, by (rank, then the
//! `r`-th singular value, or the sum of the logarithms of the singular values while the rank is
//! short), until a sweep improves nothing (at most 8 sweeps). Deterministic.

use super::identify::{layout, tool_of, LayoutZone};
use super::zones::{Test, ZoneSpec};
use super::{CubicInput, CubicPiece, Options, ZONES};
use crate::error::{check_range, Error, Result};
use crate::identify::{fit, Fit, DEFAULT_RTOL};
use crate::machine::errors::ErrorDef;
use crate::machine::Machine;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::DMatrix;

/// The scaling of the designer's matrix, in words (module docs).
pub const SCALING: &str = "Each error is scaled by a typical size (10 µm for a position, 10 µm over 100 mm = 20.6″ for an angle) and each measured value by its noise (a height by the height noise, a slope by that noise over half a zone). A singular value is then how many noise standard deviations the corresponding combination of typical errors moves the measurements; below about 3 the test hardly sees it.";

/// Typical size of a position error, mm.
pub const TYPICAL_POSITION: f64 = 0.01;
/// Typical size of an angular error, rad (10 µm over 100 mm).
pub const TYPICAL_ANGLE: f64 = 1e-4;
/// Tilt and azimuth steps of the candidates, degrees.
pub const TILT_STEP_DEG: f64 = 10.0;
/// Azimuth step, degrees.
pub const AZIMUTH_STEP_DEG: f64 = 30.0;
/// Relative singular value below which a direction counts as unseen by every candidate.
const RANK_TOL: f64 = 1e-6;

crate::inputs! {
    /// The designer's own inputs (with a [`CubicInput`]).
    pub struct CubicDesignInput {
        /// The errors to make identifiable; all the machine's when left out.
        pub parameters: Option<Vec<String>> = "parameters" optional {
            label: "Errors to identify",
            help: "The machine's errors the test should separate; left out: all of them.",
            kind: crate::machine::errors::NAMES,
            group: "Test design",
        },
        /// Zones per side of the face.
        pub grid: usize = "grid" optional {
            label: "Zones per side",
            help: "The face is n × n zones of the piece's zone size (the paper: 3 × 3).",
            kind: Kind::Count { min: 2, max: 5 },
            default: DefaultValue::Num(3.0),
            group: "Test design",
        },
        /// Largest tilt of the tool from the face's normal, degrees.
        pub max_tilt: f64 = "maxTilt" optional {
            label: "Largest tool tilt",
            help: "From the face's normal (the paper tilts 30°); a ball-end mill cuts well up to about 60°.",
            kind: schema::number(Quantity::Angle, 10.0, 75.0),
            default: DefaultValue::Num(45.0),
            group: "Test design",
        },
        /// Slopes measured too.
        pub slopes: bool = "slopes" optional {
            label: "Zone tilts measured too (profilometer)",
            help: "On: every zone gives its height and its two slopes; off: heights only.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(true),
            group: "Test design",
        },
        /// Second set-up: the piece moved along the face's first axis, mm.
        pub second_setup: f64 = "secondSetup" optional {
            label: "Second set-up: piece moved along {U} by",
            help: "The same zones cut again with the piece moved this far off its first place (off the table's axis); 0: one set-up.",
            kind: schema::number(Quantity::Length, -1000.0, 1000.0),
            default: DefaultValue::Num(0.0),
            group: "Test design",
        },
        /// Noise of a measured height, mm.
        pub noise: f64 = "noise" optional {
            label: "Height measurement noise",
            help: "One standard deviation; it scales the measured values (module docs: what is maximised).",
            kind: schema::positive(Quantity::SmallLength, 1.0),
            default: DefaultValue::Num(0.001),
            group: "Test design",
        },
    }
}

/// A zone of a designed (or the paper's) layout.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignedZone {
    /// The zone on the machine.
    pub zone: LayoutZone,
    /// Set-up 1 or 2.
    pub setup: usize,
    /// Tilt from the face normal, rad.
    pub tilt: f64,
    /// Azimuth in the face frame, rad.
    pub azimuth: f64,
}

/// A layout's quality.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutReport {
    /// Its zones.
    pub zones: Vec<DesignedZone>,
    /// Rank of its scaled matrix (relative threshold 10⁻⁶).
    pub rank: usize,
    /// Singular values of the scaled matrix, descending (noise standard deviations per
    /// typical error).
    pub singular_values: Vec<f64>,
    /// The `r`-th singular value (`r` the reachable rank): the design's objective.
    pub smallest: f64,
    /// `σ₁/σ_r`, infinite when the rank is short of `r`.
    pub condition: f64,
    /// The fit's view: which errors it identifies alone, groups, what it cannot see.
    pub fit: Fit,
    /// The export: the zone table as CSV (with empty measurement columns).
    pub csv: String,
}

/// The designer's result.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// The errors considered (columns).
    pub errors: Vec<&'static ErrorDef>,
    /// The rank every candidate together reaches.
    pub reachable_rank: usize,
    /// The fit's view of all candidates together: the groups are what no such test can see.
    pub all: Fit,
    /// Number of candidate zones the machine reaches.
    pub candidates: usize,
    /// The paper's layout (9 zones, one set-up), or why it cannot be cut.
    pub paper: std::result::Result<LayoutReport, String>,
    /// The designed layout.
    pub designed: LayoutReport,
}

fn typical(d: &ErrorDef) -> f64 {
    if d.quantity == Quantity::SmallAngle {
        TYPICAL_ANGLE
    } else {
        TYPICAL_POSITION
    }
}

/// The scaled rows of one zone (module docs).
fn zone_rows(
    z: &LayoutZone,
    errors: &[&'static ErrorDef],
    piece: &CubicPiece,
    slopes: bool,
    noise: f64,
) -> Vec<Vec<f64>> {
    let lever = piece.zone_size / 2.0;
    let row = |f: &dyn Fn(usize) -> f64, w: f64| -> Vec<f64> {
        (0..errors.len())
            .map(|e| f(e) * typical(errors[e]) * w / noise)
            .collect()
    };
    let mut out = vec![row(&|e| z.sensitivity[e].height, 1.0)];
    if slopes {
        out.push(row(&|e| z.sensitivity[e].slope_x, lever));
        out.push(row(&|e| z.sensitivity[e].slope_y, lever));
    }
    out
}

fn singular_values(rows: &[&Vec<Vec<f64>>], p: usize) -> Vec<f64> {
    let flat: Vec<&Vec<f64>> = rows.iter().flat_map(|r| r.iter()).collect();
    if flat.is_empty() || p == 0 {
        return vec![0.0; p];
    }
    let m = DMatrix::from_fn(flat.len(), p, |r, c| flat[r][c]);
    let mut sv: Vec<f64> = m
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    sv.resize(p, 0.0);
    sv
}

fn rank_of(sv: &[f64]) -> usize {
    let top = sv.first().copied().unwrap_or(0.0);
    sv.iter()
        .filter(|s| **s > RANK_TOL * top && **s > 0.0)
        .count()
}

/// (rank capped at `r`, then σ_r or the log-sum of the singular values): larger is better.
fn score(sv: &[f64], r: usize) -> (usize, f64) {
    let k = rank_of(sv).min(r);
    if k >= r && r > 0 {
        (r, sv[r - 1])
    } else {
        (k, sv[..k].iter().map(|s| s.ln()).sum())
    }
}

fn better(a: (usize, f64), b: (usize, f64)) -> bool {
    a.0 > b.0 || (a.0 == b.0 && a.1 > b.1 * (1.0 + 1e-9) + 1e-300)
}

/// One candidate zone.
#[derive(Clone)]
struct Candidate {
    slot: usize,
    zone: DesignedZone,
    rows: Vec<Vec<f64>>,
    /// `RᵀR` of its rows (p × p): a layout's Gram matrix is the sum over its zones.
    gram: DMatrix<f64>,
}

fn gram_of(rows: &[Vec<f64>], p: usize) -> DMatrix<f64> {
    DMatrix::from_fn(p, p, |i, j| rows.iter().map(|r| r[i] * r[j]).sum())
}

/// Singular values of a layout from its Gram matrix `G = SᵀS`: `√eig(G)`, descending.
fn singular_values_of_gram(g: &DMatrix<f64>) -> Vec<f64> {
    let mut sv: Vec<f64> = g
        .clone()
        .symmetric_eigen()
        .eigenvalues
        .iter()
        .map(|e| e.max(0.0).sqrt())
        .collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    sv
}

/// Designs the test (module docs).
pub fn design(input: &CubicInput, own: &CubicDesignInput) -> Result<Design> {
    let machine = &input.machine;
    let piece = &input.setup;
    // Heights from the workpiece frame: each zone's rows are its own (module docs).
    let options = Options {
        transform: input.transform,
        reference: super::CubicReference::Workpiece,
    };
    let all = machine.error_defs();
    let errors: Vec<&'static ErrorDef> = match &own.parameters {
        None => all,
        Some(names) => names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                all.iter().copied().find(|d| d.name == n).ok_or_else(|| {
                    Error::field(
                        format!("parameters[{i}]"),
                        format!("{n} is not an error of this machine"),
                    )
                })
            })
            .collect::<Result<_>>()?,
    };
    if errors.is_empty() {
        return Err(Error::field(
            "parameters",
            "choose at least one error to identify",
        ));
    }
    let p = errors.len();
    let n = own.grid;
    let half = (n as f64 - 1.0) / 2.0;
    let positions: Vec<(f64, f64)> = (0..n * n)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            (
                (i as f64 - half) * piece.zone_size,
                (j as f64 - half) * piece.zone_size,
            )
        })
        .collect();
    let mut setups = vec![piece.workpiece_x];
    if own.second_setup != 0.0 {
        setups.push(piece.workpiece_x + own.second_setup);
    }
    check_range("secondSetup", own.second_setup, -1000.0, 1000.0, "mm")?;
    // Candidate tool vectors.
    let mut tilts: Vec<f64> = Vec::new();
    let mut t = 0.0;
    while t < own.max_tilt.to_degrees() - 1e-9 {
        tilts.push(t);
        t += TILT_STEP_DEG;
    }
    tilts.push(own.max_tilt.to_degrees());
    let azimuths: Vec<f64> = (0..(360.0 / AZIMUTH_STEP_DEG) as usize)
        .map(|k| k as f64 * AZIMUTH_STEP_DEG)
        .collect();
    let mut candidates: Vec<Candidate> = Vec::new();
    let slots = positions.len() * setups.len();
    for (s, &px) in setups.iter().enumerate() {
        let placed = CubicPiece {
            workpiece_x: px,
            ..piece.clone()
        };
        let test = Test::with_zones(machine, &placed, &options, &[])?;
        for (pi, &c) in positions.iter().enumerate() {
            let slot = s * positions.len() + pi;
            for &tilt in &tilts {
                for &az in if tilt == 0.0 {
                    &azimuths[..1]
                } else {
                    &azimuths[..]
                } {
                    let (tr, ar) = (tilt.to_radians(), az.to_radians());
                    let spec = ZoneSpec {
                        name: zone_name(s, pi, n),
                        centre: c,
                        tool: tool_of(tr, ar),
                    };
                    // Unreachable within the travel: not a candidate.
                    let Ok(z) = test.place(&spec) else {
                        continue;
                    };
                    let zone = LayoutZone {
                        piece_x: px,
                        tool: z.dir.into(),
                        rotary: z.rotary,
                        singular: z.singular,
                        sensitivity: test.sensitivities(&z, &errors)?,
                        spec,
                    };
                    let rows = zone_rows(&zone, &errors, piece, own.slopes, own.noise);
                    candidates.push(Candidate {
                        gram: gram_of(&rows, p),
                        slot,
                        zone: DesignedZone {
                            zone,
                            setup: s + 1,
                            tilt: tr,
                            azimuth: ar,
                        },
                        rows,
                    });
                }
            }
        }
    }
    if candidates.is_empty() {
        return Err(Error::field(
            "machine",
            "the machine reaches no zone of the face within its travel",
        ));
    }
    let all_rows: Vec<&Vec<Vec<f64>>> = candidates.iter().map(|c| &c.rows).collect();
    let sv_all = singular_values(&all_rows, p);
    let reachable_rank = rank_of(&sv_all);
    let all_fit = view(&candidates.iter().collect::<Vec<_>>(), &errors)?;

    // Start: per slot the candidate nearest 30° towards the face centre (the paper's rule).
    let mut chosen: Vec<usize> = Vec::with_capacity(slots);
    for slot in 0..slots {
        let pi = slot % positions.len();
        let (x, y) = positions[pi];
        let want = if x == 0.0 && y == 0.0 {
            [0.0, 0.0, 1.0]
        } else {
            let a = (-y).atan2(-x);
            tool_of(own.max_tilt.min(30f64.to_radians()), a)
        };
        let best = candidates
            .iter()
            .enumerate()
            .filter(|(_, c)| c.slot == slot)
            .max_by(|(_, a), (_, b)| {
                let d = |c: &Candidate| {
                    let t = tool_of(c.zone.tilt, c.zone.azimuth);
                    t[0] * want[0] + t[1] * want[1] + t[2] * want[2]
                };
                d(a).total_cmp(&d(b))
            })
            .map(|(i, _)| i);
        if let Some(i) = best {
            chosen.push(i);
        }
    }
    // The search works on the layout's Gram matrix (p × p), swapping one zone's share.
    let mut gram = DMatrix::<f64>::zeros(p, p);
    for &i in &chosen {
        gram += &candidates[i].gram;
    }
    let mut current = score(&singular_values_of_gram(&gram), reachable_rank);
    for _sweep in 0..8 {
        let mut improved = false;
        for k in 0..chosen.len() {
            let slot = candidates[chosen[k]].slot;
            for (i, c) in candidates.iter().enumerate() {
                if c.slot != slot || i == chosen[k] {
                    continue;
                }
                let trial = &gram - &candidates[chosen[k]].gram + &c.gram;
                let s = score(&singular_values_of_gram(&trial), reachable_rank);
                if better(s, current) {
                    current = s;
                    improved = true;
                    chosen[k] = i;
                    gram = trial;
                }
            }
        }
        if !improved {
            break;
        }
    }
    let designed = report(
        &chosen.iter().map(|&i| &candidates[i]).collect::<Vec<_>>(),
        &errors,
        reachable_rank,
        p,
    )?;
    let paper = paper_layout(machine, piece, &options, &errors, own)
        .and_then(|c| report(&c.iter().collect::<Vec<_>>(), &errors, reachable_rank, p))
        .map_err(|e| e.message);
    Ok(Design {
        errors,
        reachable_rank,
        all: all_fit,
        candidates: candidates.len(),
        paper,
        designed,
    })
}

fn zone_name(setup: usize, position: usize, n: usize) -> String {
    let (i, j) = (position % n, position / n);
    let col = (b'A' + i as u8) as char;
    format!("{}{col}{}", if setup == 0 { "" } else { "S2-" }, j + 1)
}

/// The paper's nine zones as candidates of set-up 1.
fn paper_layout(
    machine: &Machine,
    piece: &CubicPiece,
    options: &Options,
    errors: &[&'static ErrorDef],
    own: &CubicDesignInput,
) -> Result<Vec<Candidate>> {
    let specs: Vec<(ZoneSpec, f64)> = ZONES
        .iter()
        .map(|d| (ZoneSpec::paper(d, piece.zone_size), piece.workpiece_x))
        .collect();
    let zones = layout(machine, piece, options, &specs, errors)?;
    Ok(zones
        .into_iter()
        .enumerate()
        .map(|(slot, zone)| {
            let t = zone.spec.tool;
            let tilt = t[2].clamp(-1.0, 1.0).acos();
            let azimuth = if tilt == 0.0 { 0.0 } else { t[1].atan2(t[0]) };
            let rows = zone_rows(&zone, errors, piece, own.slopes, own.noise);
            Candidate {
                gram: gram_of(&rows, errors.len()),
                slot,
                zone: DesignedZone {
                    zone,
                    setup: 1,
                    tilt,
                    azimuth,
                },
                rows,
            }
        })
        .collect())
}

/// The fit's view of a layout: identifiable errors and groups (no data: only the structure).
fn view(cands: &[&Candidate], errors: &[&'static ErrorDef]) -> Result<Fit> {
    let flat: Vec<&Vec<f64>> = cands.iter().flat_map(|c| c.rows.iter()).collect();
    let p = errors.len();
    // Padded with zero rows so that the fit has a residual degree of freedom to compute.
    let m = flat.len().max(p) + 1;
    let a = DMatrix::from_fn(m, p, |r, c| flat.get(r).map_or(0.0, |row| row[c]));
    let names: Vec<String> = errors.iter().map(|d| d.name.to_string()).collect();
    fit(&a, &names, &vec![0.0; m], DEFAULT_RTOL)
}

fn report(
    cands: &[&Candidate],
    errors: &[&'static ErrorDef],
    r: usize,
    p: usize,
) -> Result<LayoutReport> {
    let rows: Vec<&Vec<Vec<f64>>> = cands.iter().map(|c| &c.rows).collect();
    let sv = singular_values(&rows, p);
    let rank = rank_of(&sv);
    let smallest = if r > 0 { sv[r - 1] } else { 0.0 };
    let condition = if rank >= r && smallest > 0.0 {
        sv[0] / smallest
    } else {
        f64::INFINITY
    };
    let zones: Vec<DesignedZone> = cands.iter().map(|c| c.zone.clone()).collect();
    Ok(LayoutReport {
        csv: export(&zones),
        fit: view(cands, errors)?,
        zones,
        rank,
        singular_values: sv,
        smallest,
        condition,
    })
}

/// The zone table to machine and to fill in (the identification reads it back, module docs of
/// [`super::identify`]): one row per zone with its set-up, centre, tilt, azimuth, tool vector
/// and the K, M commands, and empty `height_um`, `slope_x`, `slope_y`.
pub fn export(zones: &[DesignedZone]) -> String {
    let mut s = String::from(
        "# Cubic-machining test designed by the five-axis accuracy calculator.\n\
         # Cut each zone with its tool vector (i, j, k: workpiece coordinates, tip to spindle),\n\
         # measure its height at the centre (and its slopes, mm/mm), fill in the last columns.\n\
         zone,setup,piece_x_mm,x_mm,y_mm,tilt_deg,azimuth_deg,i,j,k,k_deg,m_deg,height_um,slope_x,slope_y\n",
    );
    let f = |v: f64| {
        let t = format!("{v:.6}");
        let t = t.trim_end_matches('0').trim_end_matches('.').to_string();
        if t == "-0" {
            "0".to_string()
        } else {
            t
        }
    };
    for z in zones {
        let l = &z.zone;
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},,,\n",
            l.spec.name,
            z.setup,
            f(l.piece_x),
            f(l.spec.centre.0),
            f(l.spec.centre.1),
            f(z.tilt.to_degrees()),
            f(z.azimuth.to_degrees().rem_euclid(360.0)),
            f(l.tool[0]),
            f(l.tool[1]),
            f(l.tool[2]),
            f(l.rotary[0].to_degrees()),
            f(l.rotary[1].to_degrees()),
        ));
    }
    s
}
