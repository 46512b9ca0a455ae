//! The poses to probe: the simple layout, the designed one, and what no layout of poses with
//! this sphere can see.
//!
//! # What is maximised (the scaling, as the cubic designer's [`crate::cubic::design`])
//! Each unknown is scaled by a typical size (10 µm for a position, 10⁻⁴ rad = 20.6″ for an
//! angle) and each measured centre coordinate by the probing noise `noise`. In this scaled matrix
//! `S` (3 rows per pose: X, Y, Z; eq 2 of [`super`]) the `r`-th singular value, `r` the rank all
//! the candidate poses together reach, is the root-sum-square effect, in noise standard
//! deviations, of the weakest combination of typical errors that the poses can see. The designer
//! maximises it; below about 3 the poses hardly see that combination.
//!
//! # The candidates
//! Every `(K, M)` on a grid of `step` (15° by default) within the travel and the tilt limit
//! ([`super::Study::reachable`]); K written in its travel by [`crate::machine::fit`]. The rank
//! of all of them stacked is the most any layout can reach; the errors outside it are reported
//! ([`Visibility`]).
//!
//! # The simple layout
//! K in 30° steps at M = 0, then M in 30° steps over its travel at K = 0 (the pose K = M = 0
//! once, first: the reference pose), each kept when reachable.
//!
//! # The search
//! On the layout's Gram matrix `SᵀS`: coordinate ascent from the simple layout (truncated, or
//! extended greedily, to `count` poses): for each pose in turn every candidate not yet in the
//! layout is tried in its place and the best kept, by (rank, then `σ_r`, or the sum of the
//! logarithms of the singular values while the rank is short), until a sweep improves nothing
//! (at most 8 sweeps). Deterministic. With `count` at least the simple layout's size the
//! designed `σ_r` is never below the simple layout's (the search only accepts improvements).

use super::{SpherePlace, Study, Unknown};
use crate::error::{Error, Result};
use crate::identify::{fit, Fit, DEFAULT_RTOL};
use crate::machine::fit as in_travel;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::{DMatrix, Vector3};
use serde::Serialize;
use std::f64::consts::TAU;

/// The scaling of the designer's matrix, in words.
pub const SCALING: &str = "Each error is scaled by a typical size (10 µm for a position, 10 µm over 100 mm = 20.6″ for an angle) and each measured centre coordinate by the probing noise. A singular value is then how many noise standard deviations the corresponding combination of typical errors moves the measured centres; below about 3 the poses hardly see it.";

/// Relative singular value below which a direction counts as unseen.
const RANK_TOL: f64 = 1e-6;
/// A column at or below this fraction of the largest (scaled) counts as no effect at all.
const ZERO_COLUMN: f64 = 1e-9;
/// Step of the simple layout, degrees.
pub const SIMPLE_STEP_DEG: f64 = 30.0;

crate::inputs! {
    /// The designer's own inputs (with a [`super::ProbeInput`]).
    pub struct ProbeDesignInput {
        /// Grid step of the candidate poses, degrees (radians in Rust).
        pub step: f64 = "step" optional {
            label: "Candidate poses every",
            help: "The designer chooses among the poses of the rotary axes on a grid of this step, within the travel.",
            kind: schema::number(Quantity::Angle, 5.0, 90.0),
            default: DefaultValue::Num(15.0),
            group: "Sphere test design",
        },
        /// Number of poses; the simple layout's when left out.
        pub count: Option<usize> = "count" optional {
            label: "Number of poses",
            help: "How many poses to probe; left empty: as many as the simple layout ({K} every 30° at {M} = 0, {M} every 30° at {K} = 0).",
            kind: Kind::Count { min: 4, max: 200 },
            group: "Sphere test design",
        },
        /// A second place of the sphere, to show what it would add.
        pub second: SecondPlace = "second" optional {
            label: "Second sphere position",
            help: "Where a second sphere (or the same one moved) would sit; each coordinate left out: the first sphere's, 100 mm further along the table's first axis and 100 mm higher.",
            kind: Kind::Object(SecondPlace::FIELDS),
            default: DefaultValue::Empty,
        },
    }
}

/// How far the default second sphere sits from the first: along the table's first axis and
/// up, mm.
pub const SECOND_SHIFT: f64 = 100.0;

crate::inputs! {
    /// Where a second sphere would sit (mm, the face frame of the table surface, as
    /// [`SpherePlace`]); a coordinate left out is the first sphere's, moved by [`SECOND_SHIFT`]
    /// along the first axis and up.
    pub struct SecondPlace {
        /// Along the face's first axis, mm; left out: the first sphere's + 100 mm.
        pub x: Option<f64> = "x" optional {
            label: "Second sphere along the table's first axis",
            help: "From the table centre, along X for a vertical spindle; left empty: 100 mm further than the first sphere.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            group: "Second sphere position",
        },
        /// Along the face's second axis, mm; left out: the first sphere's.
        pub y: Option<f64> = "y" optional {
            label: "Second sphere along the table's second axis",
            help: "From the table centre, along Y for a vertical spindle; left empty: the first sphere's.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            group: "Second sphere position",
        },
        /// Height of its centre above the table surface, mm; left out: the first's + 100 mm.
        pub height: Option<f64> = "height" optional {
            label: "Second sphere centre above the table",
            help: "Height of the second sphere's centre above the table surface; left empty: 100 mm higher than the first sphere.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            group: "Second sphere position",
        },
    }
}

impl SecondPlace {
    /// The place, each coordinate left out taken from `first` (face frame coordinates, mm) as
    /// the struct's docs say.
    pub fn resolve(&self, first: [f64; 3]) -> SpherePlace {
        SpherePlace {
            x: self.x.unwrap_or(first[0] + SECOND_SHIFT),
            y: self.y.unwrap_or(first[1]),
            height: self.height.unwrap_or(first[2] + SECOND_SHIFT),
        }
    }
}

impl crate::edge::Checked for ProbeDesignInput {}

/// A pose to probe.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Pose {
    /// K's command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M's command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
    /// The centre the control expects there: linear-axis positions X, Y, Z, mm (module docs of
    /// `probe`).
    pub expected: [f64; 3],
    /// The probe's tilt from the table's normal, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub tilt: f64,
}

/// A layout of poses and how well it sees the errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Layout {
    /// The poses, in the order to probe them.
    pub poses: Vec<Pose>,
    /// Rank of the scaled matrix (relative threshold 10⁻⁶).
    pub rank: usize,
    /// Singular values of the scaled matrix, descending (noise standard deviations per typical
    /// error).
    pub singular_values: Vec<f64>,
    /// The `r`-th singular value (`r` the rank all candidates reach): the design's objective.
    pub smallest: f64,
    /// `σ₁/σ_r`; null when the rank is short of `r`.
    pub condition: Option<f64>,
    /// The pose table as CSV, with empty columns X_mm, Y_mm, Z_mm to fill in with the measured
    /// centres (the reader, [`super::measure`], takes it back as it is).
    pub csv: String,
    /// NC blocks: one block per pose positioning the rotary axes, with a comment to run the
    /// control's sphere-probing cycle there.
    pub nc: String,
}

pub use crate::identify::correct::{Inseparable, Unseen};

/// What the poses of this sphere can see, over every candidate pose together.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Visibility {
    /// Rank of all candidates together: the most any layout reaches.
    pub reachable_rank: usize,
    /// The unknowns each identifiable on its own.
    pub identifiable: Vec<String>,
    /// Errors with no effect on any centre at any reachable pose.
    pub invisible: Vec<Unseen>,
    /// Groups only combinations of which are measured.
    pub inseparable: Vec<Inseparable>,
}

/// What a second sphere position would add.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SecondSphere {
    /// Its centre in the workpiece frame, mm.
    pub centre: [f64; 3],
    /// Rank of both spheres' candidates together (each sphere's position its own unknowns
    /// when fitted).
    pub reachable_rank: usize,
    /// The errors identifiable with both spheres.
    pub identifiable: Vec<String>,
    /// Those a single sphere cannot identify and two can.
    pub gained: Vec<String>,
    /// In words.
    pub words: String,
}

/// The designer's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct ProbeDesign {
    /// The unknowns (columns): errors, then the sphere's position when fitted.
    pub unknowns: Vec<String>,
    /// Letters of K and M.
    pub axes: [char; 2],
    /// Number of candidate poses within the travel and the tilt limit.
    pub candidates: usize,
    /// What any layout with this sphere can see.
    pub visibility: Visibility,
    /// The simple layout (module docs).
    pub simple: Layout,
    /// The designed layout.
    pub designed: Layout,
    /// What a second sphere position would add.
    pub second_sphere: SecondSphere,
    /// How the matrix is scaled, in words.
    pub scaling: String,
    /// The conclusions in words.
    pub summary: Vec<String>,
}

/// A candidate pose with its scaled rows.
#[derive(Debug, Clone)]
struct Candidate {
    k: f64,
    m: f64,
    rows: [Vec<f64>; 3],
    gram: DMatrix<f64>,
}

/// The scaled rows of the centre at `(k, m)` (module docs).
fn scaled_rows(study: &Study, k: f64, m: f64) -> Result<[Vec<f64>; 3]> {
    let s = study.sensitivities(k, m)?;
    let row = |axis: usize| -> Vec<f64> {
        study
            .unknowns
            .iter()
            .zip(&s)
            .map(|(u, v)| v[axis] * u.typical() / study.noise)
            .collect()
    };
    Ok([row(0), row(1), row(2)])
}

fn candidate(study: &Study, k: f64, m: f64) -> Result<Candidate> {
    let rows = scaled_rows(study, k, m)?;
    let p = study.unknowns.len();
    let gram = DMatrix::from_fn(p, p, |i, j| rows.iter().map(|r| r[i] * r[j]).sum());
    Ok(Candidate { k, m, rows, gram })
}

/// Whole multiples of `step` in `[lo, hi]` (a continuous axis: one turn from 0), each written
/// in the travel by [`crate::machine::fit`], without repeats modulo a turn.
fn angles(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let n = (TAU / step).round().max(1.0) as usize;
    let mut out: Vec<f64> = Vec::new();
    if lo.is_finite() && hi - lo < TAU - 1e-9 {
        let first = (lo / step - 1e-9).ceil() as i64;
        let last = (hi / step + 1e-9).floor() as i64;
        for j in first..=last {
            out.push(j as f64 * step);
        }
        return out;
    }
    for j in 0..n {
        if let Some(a) = in_travel(j as f64 * step, lo, hi, None) {
            let same = |b: &f64| {
                let d = (a - b).rem_euclid(TAU);
                d.min(TAU - d) < 1e-9
            };
            if !out.iter().any(same) {
                out.push(a);
            }
        }
    }
    out
}

/// Every candidate pose of the grid (module docs).
fn candidates(study: &Study, step: f64) -> Result<Vec<Candidate>> {
    let [(k_lo, k_hi), (m_lo, m_hi)] = study.model.travel();
    let mut out = Vec::new();
    for m in angles(m_lo, m_hi, step) {
        for k in angles(k_lo, k_hi, step) {
            if study.reachable(k, m)? {
                out.push(candidate(study, k, m)?);
            }
        }
    }
    Ok(out)
}

/// The simple layout's poses: K every 30° at M = 0, then M every 30° at K = 0 (module docs).
pub fn simple_poses(study: &Study) -> Result<Vec<(f64, f64)>> {
    let [(k_lo, k_hi), (m_lo, m_hi)] = study.model.travel();
    let step = SIMPLE_STEP_DEG.to_radians();
    let k0 = in_travel(0.0, k_lo, k_hi, None).unwrap_or(0.0);
    let mut out = vec![(k0, 0.0)];
    for k in angles(k_lo, k_hi, step) {
        out.push((k, 0.0));
    }
    for m in angles(m_lo, m_hi, step) {
        out.push((k0, m));
    }
    let mut kept: Vec<(f64, f64)> = Vec::new();
    for (k, m) in out {
        if !kept.contains(&(k, m)) && study.reachable(k, m)? {
            kept.push((k, m));
        }
    }
    Ok(kept)
}

fn singular_values(g: &DMatrix<f64>) -> Vec<f64> {
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

fn rank_of(sv: &[f64]) -> usize {
    let top = sv.first().copied().unwrap_or(0.0);
    sv.iter()
        .filter(|s| **s > RANK_TOL * top && **s > 0.0)
        .count()
}

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

fn gram_of(set: &[&Candidate], p: usize) -> DMatrix<f64> {
    let mut g = DMatrix::zeros(p, p);
    for c in set {
        g += &c.gram;
    }
    g
}

/// The fit's view of stacked scaled rows: identifiable unknowns and groups (no data).
fn view(rows: &[&Vec<f64>], names: &[String]) -> Result<Fit> {
    let p = names.len();
    let m = rows.len().max(p) + 1;
    let a = DMatrix::from_fn(m, p, |r, c| rows.get(r).map_or(0.0, |row| row[c]));
    fit(&a, names, &vec![0.0; m], DEFAULT_RTOL)
}

/// The scaled rows of two spheres stacked, each sphere's position its own three unknowns
/// when fitted: columns = the errors, sphere 1, sphere 2.
fn two_sphere_rows(one: &[Candidate], two: &[Candidate], study: &Study) -> Vec<Vec<f64>> {
    let ne = study
        .unknowns
        .iter()
        .filter(|u| matches!(u, Unknown::Error(_)))
        .count();
    let fitted = study.unknowns.len() > ne;
    let width = if fitted { ne + 6 } else { ne };
    let mut out = Vec::new();
    for (set, second) in [(one, false), (two, true)] {
        for c in set {
            for r in &c.rows {
                let mut row = vec![0.0; width];
                row[..ne].copy_from_slice(&r[..ne]);
                if fitted {
                    let at = if second { ne + 3 } else { ne };
                    row[at..at + 3].copy_from_slice(&r[ne..ne + 3]);
                }
                out.push(row);
            }
        }
    }
    out
}

/// Designs the poses (module docs).
pub fn design(study: &Study, own: &ProbeDesignInput) -> Result<ProbeDesign> {
    let names = study.names();
    let p = names.len();
    let mut cands = candidates(study, own.step)?;
    if cands.is_empty() {
        return Err(Error::field(
            "machine",
            "no pose of the rotary axes is within the travel and the tilt limit",
        ));
    }
    // The simple layout's poses are candidates even off the grid.
    let simple_list = simple_poses(study)?;
    let mut simple_idx = Vec::new();
    for &(k, m) in &simple_list {
        let found = cands
            .iter()
            .position(|c| (c.k - k).abs() < 1e-9 && (c.m - m).abs() < 1e-9);
        let i = match found {
            Some(i) => i,
            None => {
                cands.push(candidate(study, k, m)?);
                cands.len() - 1
            }
        };
        simple_idx.push(i);
    }
    let all_rows: Vec<&Vec<f64>> = cands.iter().flat_map(|c| c.rows.iter()).collect();
    let all_fit = view(seen(&all_rows, &names)?, &names)?;
    let all_gram = gram_of(&cands.iter().collect::<Vec<_>>(), p);
    let r = rank_of(&singular_values(&all_gram));
    let visibility = visibility(study, &cands, &all_fit, r)?;

    // Start: the simple layout, truncated or extended greedily to `count`.
    let count = own.count.unwrap_or(simple_idx.len()).min(cands.len());
    let mut chosen: Vec<usize> = simple_idx.iter().copied().take(count).collect();
    while chosen.len() < count {
        let g = gram_of(&chosen.iter().map(|&i| &cands[i]).collect::<Vec<_>>(), p);
        let mut best: Option<(usize, (usize, f64))> = None;
        for (i, c) in cands.iter().enumerate() {
            if chosen.contains(&i) {
                continue;
            }
            let s = score(&singular_values(&(&g + &c.gram)), r);
            if best.map_or(true, |(_, b)| better(s, b)) {
                best = Some((i, s));
            }
        }
        match best {
            Some((i, _)) => chosen.push(i),
            None => break,
        }
    }
    let mut gram = gram_of(&chosen.iter().map(|&i| &cands[i]).collect::<Vec<_>>(), p);
    let mut current = score(&singular_values(&gram), r);
    for _sweep in 0..8 {
        let mut improved = false;
        for slot in 0..chosen.len() {
            for i in 0..cands.len() {
                if chosen.contains(&i) {
                    continue;
                }
                let trial = &gram - &cands[chosen[slot]].gram + &cands[i].gram;
                let s = score(&singular_values(&trial), r);
                if better(s, current) {
                    current = s;
                    gram = trial;
                    chosen[slot] = i;
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
    // Probe in a sensible order: by M, then K.
    chosen.sort_by(|&a, &b| {
        let (ca, cb) = (&cands[a], &cands[b]);
        (ca.m.abs(), ca.m, ca.k)
            .partial_cmp(&(cb.m.abs(), cb.m, cb.k))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let simple = layout(study, &simple_idx, &cands, r)?;
    let designed = layout(study, &chosen, &cands, r)?;

    // A second sphere position.
    let place = {
        let [u, v, n] = study.model.machine.face_frame();
        let s = study.sphere;
        own.second.resolve([s.dot(&u), s.dot(&v), s.dot(&n)])
    };
    let study2 = study.with_sphere(&place);
    let cands2: Vec<Candidate> = cands
        .iter()
        .filter_map(|c| match study2.reachable(c.k, c.m) {
            Ok(true) => Some(candidate(&study2, c.k, c.m)),
            Ok(false) => None,
            Err(e) => Some(Err(e)),
        })
        .collect::<Result<_>>()?;
    let rows2 = two_sphere_rows(&cands, &cands2, study);
    let mut names2: Vec<String> = names
        .iter()
        .filter(|n| !n.starts_with("sphere_"))
        .cloned()
        .collect();
    let ne = names2.len();
    if p > ne {
        names2.extend(super::SPHERE_NAMES.iter().map(|n| format!("{n}1")));
        names2.extend(super::SPHERE_NAMES.iter().map(|n| format!("{n}2")));
    }
    let fit2 = view(&rows2.iter().collect::<Vec<_>>(), &names2)?;
    let g2 = DMatrix::from_fn(names2.len(), names2.len(), |i, j| {
        rows2.iter().map(|r| r[i] * r[j]).sum()
    });
    let identifiable2: Vec<String> = fit2
        .estimates
        .iter()
        .filter(|e| e.group.is_none() && !e.name.starts_with("sphere_"))
        .map(|e| e.name.clone())
        .collect();
    let gained: Vec<String> = identifiable2
        .iter()
        .filter(|n| !visibility.identifiable.contains(n))
        .cloned()
        .collect();
    let words = if gained.is_empty() {
        "A second sphere position here adds no error that one sphere cannot identify: what one sphere cannot see acts like a change of the sphere's own position (or of the probe), which each sphere's fitted position absorbs.".to_string()
    } else {
        format!(
            "A second sphere position (centre {:.0}, {:.0}, {:.0} mm) would also identify {}: their effects differ from sphere to sphere by the lever arm.",
            study2.sphere[0],
            study2.sphere[1],
            study2.sphere[2],
            gained.join(", ")
        )
    };
    let second_sphere = SecondSphere {
        centre: [study2.sphere[0], study2.sphere[1], study2.sphere[2]],
        reachable_rank: rank_of(&singular_values(&g2)),
        identifiable: identifiable2,
        gained,
        words,
    };
    let mut summary = vec![format!(
        "{} poses designed: the weakest combination of typical errors moves the centres by {:.1} noise standard deviations ({:.1} with the simple layout of {} poses).",
        designed.poses.len(),
        designed.smallest,
        simple.smallest,
        simple.poses.len()
    )];
    summary.extend(
        visibility
            .invisible
            .iter()
            .map(|u| format!("{}: {}", u.name, u.why)),
    );
    summary.extend(visibility.inseparable.iter().map(|g| g.why.clone()));
    summary.push(second_sphere.words.clone());
    Ok(ProbeDesign {
        unknowns: names,
        axes: study.model.letters(),
        candidates: cands.len(),
        visibility,
        simple,
        designed,
        second_sphere,
        scaling: SCALING.to_string(),
        summary,
    })
}

/// What all candidates together see (module docs of [`super`]).
fn visibility(study: &Study, cands: &[Candidate], all: &Fit, r: usize) -> Result<Visibility> {
    let p = study.unknowns.len();
    let norms: Vec<f64> = (0..p)
        .map(|j| {
            cands
                .iter()
                .flat_map(|c| c.rows.iter())
                .map(|row| row[j] * row[j])
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let largest = norms.iter().fold(0.0f64, |a, b| a.max(*b));
    let [kl, ml] = study.model.letters();
    let mut invisible = Vec::new();
    for (j, u) in study.unknowns.iter().enumerate() {
        let Unknown::Error(d) = u else { continue };
        if norms[j] > ZERO_COLUMN * largest {
            continue;
        }
        let own_turn =
            d.component >= 3 && matches!((d.axis, d.component), ('A', 3) | ('B', 4) | ('C', 5));
        let why = if own_turn && (d.axis == kl || d.axis == ml) {
            format!(
                "the sphere lies on the {} axis line at every pose: a turn about that line (its zero position) moves no point of it, so no centre changes.",
                d.axis
            )
        } else {
            "its effect on every measured centre is zero at every reachable pose (the chain's sensitivity vanishes there).".to_string()
        };
        invisible.push(Unseen {
            name: d.name.to_string(),
            why,
        });
    }
    let invisible_names: Vec<&str> = invisible.iter().map(|u| u.name.as_str()).collect();
    // The fit's combinations are of the scaled unknowns x/typical: per API unit (mm, degree)
    // a coefficient c becomes c/typical (× π/180 for an angle), the first one scaled to 1.
    let api_text = |c: &crate::identify::Combination| -> String {
        let per = |name: &str| -> f64 {
            study
                .unknowns
                .iter()
                .find(|u| u.name() == name)
                .map_or(1.0, |u| u.quantity().to_engine(1.0) / u.typical())
        };
        let terms: Vec<(String, f64)> = c
            .terms
            .iter()
            .map(|(n, k)| (n.clone(), k * per(n)))
            .collect();
        let lead = terms.first().map_or(1.0, |t| t.1);
        let terms: Vec<(String, f64)> = terms.into_iter().map(|(n, k)| (n, k / lead)).collect();
        crate::identify::combination_text(&terms)
    };
    let mut inseparable = Vec::new();
    for g in &all.groups {
        let members: Vec<String> = g
            .members
            .iter()
            .filter(|n| !invisible_names.contains(&n.as_str()))
            .cloned()
            .collect();
        if members.is_empty() {
            continue;
        }
        let errors: Vec<&String> = members
            .iter()
            .filter(|n| !n.starts_with("sphere_"))
            .collect();
        if errors.is_empty() {
            continue;
        }
        let with_sphere = members.iter().any(|n| n.starts_with("sphere_"));
        let list = errors
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        let why = if with_sphere {
            format!(
                "{list}: acts on the centres as a change of the sphere's own position would (the sphere's position is fitted): only {} measured.",
                if g.combinations.is_empty() {
                    "nothing of it is".to_string()
                } else {
                    format!(
                        "the combination{} {} {}",
                        if g.combinations.len() > 1 { "s" } else { "" },
                        g.combinations
                            .iter()
                            .map(&api_text)
                            .collect::<Vec<_>>()
                            .join("; "),
                        if g.combinations.len() > 1 { "are" } else { "is" }
                    )
                }
            )
        } else {
            format!(
                "{list} move the centres alike at every pose: only {} measured.",
                if g.combinations.is_empty() {
                    "nothing of them is".to_string()
                } else {
                    g.combinations
                        .iter()
                        .map(&api_text)
                        .collect::<Vec<_>>()
                        .join("; ")
                        + " is"
                }
            )
        };
        inseparable.push(Inseparable {
            members,
            combinations: g.combinations.iter().map(&api_text).collect(),
            why,
        });
    }
    Ok(Visibility {
        reachable_rank: r,
        identifiable: all
            .estimates
            .iter()
            .filter(|e| e.group.is_none() && !e.name.starts_with("sphere_"))
            .map(|e| e.name.clone())
            .collect(),
        invisible,
        inseparable,
    })
}

fn layout(study: &Study, idx: &[usize], cands: &[Candidate], r: usize) -> Result<Layout> {
    let p = study.unknowns.len();
    let set: Vec<&Candidate> = idx.iter().map(|&i| &cands[i]).collect();
    let sv = singular_values(&gram_of(&set, p));
    let rank = rank_of(&sv);
    let smallest = if r > 0 { sv[r - 1] } else { 0.0 };
    let condition = (rank >= r && smallest > 0.0).then(|| sv[0] / smallest);
    let poses: Vec<Pose> = set
        .iter()
        .map(|c| {
            let e = study.expected(c.k, c.m)?;
            Ok(Pose {
                k: c.k,
                m: c.m,
                expected: [e[0], e[1], e[2]],
                tilt: study.tilt(c.k, c.m)?,
            })
        })
        .collect::<Result<_>>()?;
    Ok(Layout {
        csv: export_csv(study, &poses),
        nc: export_nc(study, &poses),
        poses,
        rank,
        singular_values: sv,
        smallest,
        condition,
    })
}

fn num(v: f64, digits: usize) -> String {
    let t = format!("{v:.digits$}");
    let t = if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    };
    if t == "-0" {
        "0".to_string()
    } else {
        t
    }
}

/// The pose table (module docs of [`super::measure`]): `pose`, K and M in degrees, the
/// expected centre, and empty `X_mm`, `Y_mm`, `Z_mm` for the measured one.
pub fn export_csv(study: &Study, poses: &[Pose]) -> String {
    let [kl, ml] = study.model.letters();
    let mut s = format!(
        "# Sphere test of the rotary axes, by the five-axis accuracy calculator.\n\
         # At each pose run the control's sphere-probing cycle and fill in X_mm, Y_mm, Z_mm: the\n\
         # linear-axis positions of the sphere's centre (machine coordinates, TCPM off).\n\
         # The expected centre (nominal kinematics, sphere at {}, {}, {} mm) is for reference.\n\
         pose,{kl}_deg,{ml}_deg,expected_x_mm,expected_y_mm,expected_z_mm,X_mm,Y_mm,Z_mm\n",
        num(study.sphere[0], 4),
        num(study.sphere[1], 4),
        num(study.sphere[2], 4),
    );
    for (i, p) in poses.iter().enumerate() {
        s.push_str(&format!(
            "{},{},{},{},{},{},,,\n",
            i + 1,
            num(p.k.to_degrees(), 6),
            num(p.m.to_degrees(), 6),
            num(p.expected[0], 4),
            num(p.expected[1], 4),
            num(p.expected[2], 4),
        ));
    }
    s
}

/// `v` to three decimals, without the sign of a value that rounds to zero (`0.000`, never
/// `-0.000`: a control reads both alike, a person wonders).
fn fixed3(v: f64) -> String {
    let t = format!("{v:.3}");
    if t == "-0.000" {
        "0.000".to_string()
    } else {
        t
    }
}

/// NC blocks (ISO/Fanuc style, comments in parentheses): a header, then one block per pose
/// positioning the rotary axes (`G0 C… B…`) with a comment to run the control's
/// sphere-probing cycle there and the centre to expect.
pub fn export_nc(study: &Study, poses: &[Pose]) -> String {
    let [kl, ml] = study.model.letters();
    let mut s = format!(
        "(SPHERE TEST OF THE ROTARY AXES {kl} AND {ml}, {} POSES)\n\
         (PROBE CALIBRATED, TCPM OFF, RETRACT THE PROBE TO A SAFE POSITION BEFORE EACH BLOCK)\n",
        poses.len()
    );
    for (i, p) in poses.iter().enumerate() {
        s.push_str(&format!(
            "N{} G0 {kl}{} {ml}{} (POSE {} OF {}, RUN THE CONTROL'S SPHERE-PROBING CYCLE HERE, EXPECTED CENTRE X{} Y{} Z{})\n",
            10 * (i + 1),
            fixed3(p.k.to_degrees()),
            fixed3(p.m.to_degrees()),
            i + 1,
            poses.len(),
            fixed3(p.expected[0]),
            fixed3(p.expected[1]),
            fixed3(p.expected[2]),
        ));
    }
    s.push_str("M30\n");
    s
}

/// The candidate grid's poses, for tests: `(k, m)` rad, every pose within the travel and the
/// tilt limit on a grid of `step` (rad).
pub fn candidate_poses(study: &Study, step: f64) -> Result<Vec<(f64, f64)>> {
    Ok(candidates(study, step)?
        .into_iter()
        .map(|c| (c.k, c.m))
        .collect())
}

/// The sphere's centre as `[x, y, z]`, mm.
pub fn centre_of(v: &Vector3<f64>) -> [f64; 3] {
    [v[0], v[1], v[2]]
}

/// `rows` (every candidate's), or the refusal when they are all zero: no pose sees any of the
/// errors to identify (each is along or about an axis's own line through the sphere).
fn seen<'a>(rows: &'a [&'a Vec<f64>], names: &[String]) -> Result<&'a [&'a Vec<f64>]> {
    if rows.iter().any(|r| r.iter().any(|v| *v != 0.0)) {
        Ok(rows)
    } else {
        Err(Error::field(
            "parameters",
            format!(
                "no pose within the travel and the tilt limit sees {}: it moves the sphere's centre nowhere (an error along or about an axis's own line through the sphere); fit the sphere's position too, move the sphere off that line, or choose other errors",
                names.join(", ")
            ),
        ))
    }
}
