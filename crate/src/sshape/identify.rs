//! Identification of the machine's location errors from deviations measured at the 100 points
//! (Chanal et al. 2022, Section 6, Table 4, Fig 21): the measurement file, a linear least-squares
//! fit with general rank detection, and the residuals.
//!
//! # The measurement file (CSV)
//! One line per point, 100 lines, any order, with a header naming the columns:
//!
//! ```text
//! # comment lines start with '#'; blank lines are ignored
//! curve,point,deviation_mm
//! top,1,0.0123
//! bottom,50,-0.0310
//! ```
//!
//! * `curve`: `top` (z = 25 mm) or `bottom` (z = 11 mm) (also `T`/`B`, `Z25`/`Z11`, `25`/`11`);
//! * `point`: 1..50 (1..25 on surface A, 26..50 on surface B, see [`super::part`]);
//! * `deviation_mm` (or `deviation`, also mm) or `deviation_um` (µm): the measured deviation along
//!   the outward normal, positive where the surface lies outside its nominal position.
//!
//! Separators: comma, semicolon or tab. Every problem is reported with its line number
//! (`csv: line 7: "0,01x" is not a number`); a missing point is named.
//!
//! # The fit
//! The model is linear in the parameters: `d_k = Σ_j A_kj·x_j + r_k`, with `A` the eq 14
//! sensitivities (and, optionally, the tool-radius column `−sin θ_k`, Section 3.2). Columns are
//! scaled to unit norm (so mm and rad compare), then decomposed by SVD: `A_s = U·Σ·Vᵀ`. The
//! numerical rank `r` counts the singular values above `rtol·σ_max` (default `rtol = 10⁻²`,
//! i.e. a condition number of 100 for the column-equilibrated matrix, a common limit for
//! identifiability in machine and robot calibration). The directions of the other singular
//! vectors are **not identifiable**. With `P0` the projector onto those weak directions (unique,
//! unlike the singular vectors themselves), a parameter whose `P0` diagonal exceeds 0.01 (a
//! component above 0.1 in the weak directions) cannot be separated from the others; such
//! parameters are grouped by the couplings of `P0`, and for each group the eigenvectors of its
//! block of `P0` give the weak directions (eigenvalue near 1, their number is the group's
//! deficiency) and the **identifiable combinations** (eigenvalue near 0), reported in original
//! units with their values and standard errors. Nothing about the S-shape is built in: the
//! pairs E_A0Z/E_A0C and E_B0Z/E_B0C come out of the sensitivities when they are (nearly)
//! dependent.
//!
//! Values: the minimum-norm solution in the scaled parameters (the truncated-SVD solution),
//! which for two opposite columns of equal norm is the paper's `x1 = E_A0C = −E_A0Z`; it is given
//! for every parameter as `min_norm`, while `value` is `None` for a parameter that is not
//! identifiable on its own. Standard errors from the residuals: `σ² = ‖r‖²/(m − r)`.

use crate::error::{check_range, Error, Result};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::part::{index_of, parse_curve, Curve, N_POINTS, POINTS_PER_CURVE};

/// Default relative singular-value threshold of the rank decision.
pub const DEFAULT_RTOL: f64 = 1e-2;
/// A parameter is not identifiable when its squared length in the weak directions (the diagonal
/// of their projector) exceeds this, i.e. a component above 0.1; two such parameters are in one
/// group when the projector couples them by more than this.
const GROUP_WEIGHT: f64 = 1e-2;

/// Parses the measurement CSV into 100 deviations (mm) in list order (TOP 1..50, BOTTOM 1..50).
pub fn parse_measurements(text: &str) -> Result<Vec<f64>> {
    let err = |line: usize, msg: String| Error::field("csv", format!("line {line}: {msg}"));
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hline, header) = lines.next().ok_or_else(|| {
        Error::field(
            "csv",
            "the file is empty: expected a header line curve,point,deviation_mm and 100 rows",
        )
    })?;
    let sep = [',', ';', '\t']
        .into_iter()
        .find(|c| header.contains(*c))
        .ok_or_else(|| {
            err(
                hline,
                format!(
                    "the header {header:?} has no separator; expected curve,point,deviation_mm"
                ),
            )
        })?;
    let names: Vec<String> = header
        .split(sep)
        .map(|s| s.trim().trim_matches('"').to_ascii_lowercase())
        .collect();
    let find = |want: &[&str]| names.iter().position(|n| want.contains(&n.as_str()));
    let col_curve = find(&["curve"]).ok_or_else(|| {
        err(
            hline,
            "missing column 'curve' in the header (top or bottom)".into(),
        )
    })?;
    let col_point = find(&["point"])
        .ok_or_else(|| err(hline, "missing column 'point' in the header (1..50)".into()))?;
    let (col_dev, scale) = match (
        find(&["deviation_mm", "deviation"]),
        find(&["deviation_um", "deviation_µm"]),
    ) {
        (Some(c), None) => (c, 1.0),
        (None, Some(c)) => (c, 1e-3),
        (Some(_), Some(_)) => {
            return Err(err(
                hline,
                "two deviation columns (mm and µm); keep one".into(),
            ))
        }
        (None, None) => {
            return Err(err(
                hline,
                "missing column 'deviation_mm' (or 'deviation_um') in the header".into(),
            ))
        }
    };
    let ncols = names.len();
    let mut values: Vec<Option<(f64, usize)>> = vec![None; N_POINTS];
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(sep).map(|c| c.trim().trim_matches('"')).collect();
        if cells.len() != ncols {
            return Err(err(
                line,
                format!(
                    "expected {ncols} columns like the header, got {}",
                    cells.len()
                ),
            ));
        }
        let curve = parse_curve(cells[col_curve]).map_err(|e| err(line, e.message))?;
        let number: usize = cells[col_point].parse().map_err(|_| {
            err(
                line,
                format!("point {:?} is not a whole number 1..50", cells[col_point]),
            )
        })?;
        if !(1..=2 * POINTS_PER_CURVE).contains(&number) {
            return Err(err(line, format!("point {number} is outside 1..50")));
        }
        let text_value = cells[col_dev];
        let value: f64 = text_value
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| err(line, format!("deviation {text_value:?} is not a number")))?;
        let value = value * scale;
        check_range("deviation", value, -10.0, 10.0, "mm")
            .map_err(|e| err(line, format!("deviation {}", e.message)))?;
        let k = index_of(curve, number);
        if let Some((_, first)) = values[k] {
            return Err(err(
                line,
                format!(
                    "point {} {number} is given twice (first on line {first})",
                    curve.name()
                ),
            ));
        }
        values[k] = Some((value, line));
    }
    let missing: Vec<String> = values
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_none())
        .map(|(k, _)| {
            let curve = if k < 2 * POINTS_PER_CURVE {
                Curve::Top
            } else {
                Curve::Bottom
            };
            format!("{} {}", curve.name(), k % (2 * POINTS_PER_CURVE) + 1)
        })
        .collect();
    if !missing.is_empty() {
        let shown: Vec<&str> = missing.iter().take(8).map(String::as_str).collect();
        return Err(Error::field(
            "csv",
            format!(
                "{} of the 100 points are missing: {}{}",
                missing.len(),
                shown.join(", "),
                if missing.len() > 8 { ", …" } else { "" }
            ),
        ));
    }
    Ok(values.into_iter().map(|v| v.map_or(0.0, |x| x.0)).collect())
}

/// One parameter of the fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Estimate {
    /// Its name, e.g. `E_A0B`.
    pub name: String,
    /// The value when it is identifiable on its own, else `None`.
    pub value: Option<f64>,
    /// The minimum-norm value (a convention for the non-identifiable ones).
    pub min_norm: f64,
    /// Standard error (same unit), `None` when not identifiable.
    pub std_error: Option<f64>,
    /// Index into `groups` when it cannot be separated from others.
    pub group: Option<usize>,
}

/// An identifiable combination `Σ coefficient_j·x_j`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Combination {
    /// `(name, coefficient)`; the first coefficient is 1.
    pub terms: Vec<(String, f64)>,
    /// Its value.
    pub value: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Readable form, e.g. `E_A0Z − 1.0006·E_A0C`.
    pub text: String,
}

/// Parameters that cannot be separated from one another, and what can be identified of them.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Group {
    /// The parameters.
    pub members: Vec<String>,
    /// Number of weak directions among them.
    pub deficiency: usize,
    /// The identifiable combinations (`members − deficiency` of them).
    pub combinations: Vec<Combination>,
}

/// The result of a fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Fit {
    /// Per parameter.
    pub estimates: Vec<Estimate>,
    /// Inseparable groups.
    pub groups: Vec<Group>,
    /// Numerical rank.
    pub rank: usize,
    /// Singular values of the column-scaled matrix, relative to the largest, descending.
    pub singular_values: Vec<f64>,
    /// The threshold used.
    pub rtol: f64,
    /// `A·x`, the fitted deviation per point (mm).
    pub fitted: Vec<f64>,
    /// Measured minus fitted, per point (mm).
    pub residuals: Vec<f64>,
    /// RMS of the residuals, mm.
    pub rms: f64,
    /// Largest |residual|, mm.
    pub max_abs: f64,
    /// Residual standard deviation `‖r‖/√(m − rank)`, mm.
    pub sigma: f64,
}

/// Least squares `d ≈ A·x` for the named columns of `a` (rows: points), with rank detection
/// (see the module documentation). `rtol` in (0, 1).
pub fn fit(a: &DMatrix<f64>, names: &[String], d: &[f64], rtol: f64) -> Result<Fit> {
    let (m, p) = a.shape();
    if names.len() != p || d.len() != m {
        return Err(Error::field(
            "fit",
            format!(
                "{m}×{p} matrix with {} names and {} values",
                names.len(),
                d.len()
            ),
        ));
    }
    check_range("rtol", rtol, 1e-15, 0.5, "")?;
    if m <= p {
        return Err(Error::field(
            "fit",
            format!("{m} points are too few for {p} parameters"),
        ));
    }
    if a.iter().chain(d.iter()).any(|v| !v.is_finite()) {
        return Err(Error::field("fit", "the data must be finite"));
    }
    let scale: Vec<f64> = (0..p).map(|j| a.column(j).norm()).collect();
    let a_s = DMatrix::from_fn(m, p, |r, c| {
        if scale[c] > 0.0 {
            a[(r, c)] / scale[c]
        } else {
            0.0
        }
    });
    let svd = a_s.svd(true, true);
    let (u, v_t) = match (svd.u, svd.v_t) {
        (Some(u), Some(v_t)) => (u, v_t),
        _ => return Err(Error::field("fit", "the SVD did not converge")),
    };
    let sv = &svd.singular_values;
    // Indices of the singular values, descending.
    let mut order: Vec<usize> = (0..sv.len()).collect();
    order.sort_by(|&i, &j| sv[j].total_cmp(&sv[i]));
    let smax = sv[order[0]];
    if smax == 0.0 {
        return Err(Error::field(
            "fit",
            "no parameter has any effect on the points",
        ));
    }
    let strong: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&i| sv[i] > rtol * smax)
        .collect();
    let weak: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&i| sv[i] <= rtol * smax)
        .collect();
    let rank = strong.len();
    let dv = DVector::from_column_slice(d);
    // Truncated-SVD solution in scaled coordinates.
    let mut xs = DVector::zeros(p);
    for &i in &strong {
        let coef = u.column(i).dot(&dv) / sv[i];
        xs += v_t.row(i).transpose() * coef;
    }
    let x: Vec<f64> = (0..p)
        .map(|j| {
            if scale[j] > 0.0 {
                xs[j] / scale[j]
            } else {
                0.0
            }
        })
        .collect();
    let fitted_v = a * DVector::from_column_slice(&x);
    let residuals: Vec<f64> = (0..m).map(|k| d[k] - fitted_v[k]).collect();
    let rss: f64 = residuals.iter().map(|r| r * r).sum();
    let sigma = (rss / (m - rank) as f64).sqrt();
    // Covariance of the scaled solution: σ²·V_r Σ_r⁻² V_rᵀ.
    let cov = |w: &DVector<f64>| -> f64 {
        strong
            .iter()
            .map(|&i| (v_t.row(i).transpose().dot(w) / sv[i]).powi(2))
            .sum::<f64>()
            * sigma
            * sigma
    };
    // The projector onto the weak directions, P0 = V0·V0ᵀ: unlike the singular vectors
    // themselves (any rotation of them within a repeated or tiny singular value is as good), it
    // is unique, and block-diagonal when the weak directions split into separate groups.
    let mut p0 = DMatrix::<f64>::zeros(p, p);
    for &i in &weak {
        let v = v_t.row(i).transpose();
        p0 += &v * v.transpose();
    }
    let weak_param = |j: usize| p0[(j, j)] > GROUP_WEIGHT || scale[j] == 0.0;
    // Groups: connected components of the weak parameters linked by P0.
    let mut group_of: Vec<Option<usize>> = vec![None; p];
    let mut group_members: Vec<Vec<usize>> = Vec::new();
    for j0 in 0..p {
        if !weak_param(j0) || group_of[j0].is_some() {
            continue;
        }
        let g = group_members.len();
        let mut members = vec![j0];
        group_of[j0] = Some(g);
        let mut k = 0;
        while k < members.len() {
            let i = members[k];
            for j in 0..p {
                if group_of[j].is_none() && weak_param(j) && p0[(i, j)].abs() > GROUP_WEIGHT {
                    group_of[j] = Some(g);
                    members.push(j);
                }
            }
            k += 1;
        }
        members.sort_unstable();
        group_members.push(members);
    }
    let mut groups = Vec::with_capacity(group_members.len());
    for members in &group_members {
        // Within the group, P0's eigenvectors with eigenvalue near 1 are the weak directions,
        // those near 0 the identifiable combinations.
        let k = members.len();
        let block = DMatrix::from_fn(k, k, |a1, b1| p0[(members[a1], members[b1])]);
        let eig = block.symmetric_eigen();
        let deficiency = eig.eigenvalues.iter().filter(|e| **e > 0.5).count();
        let mut combinations = Vec::new();
        for c in 0..k {
            if eig.eigenvalues[c] > 0.5 {
                continue;
            }
            let w_local = eig.eigenvectors.column(c);
            let mut w = DVector::zeros(p);
            for (li, &j) in members.iter().enumerate() {
                w[j] = w_local[li];
            }
            // In original units: coefficient_j = w_j·scale_j; the first one normalised to 1.
            let big = members
                .iter()
                .map(|&j| (w[j] * scale[j]).abs())
                .fold(0.0, f64::max);
            let lead = members
                .iter()
                .map(|&j| w[j] * scale[j])
                .find(|c| c.abs() > 1e-6 * big)
                .unwrap_or(1.0);
            let terms: Vec<(String, f64)> = members
                .iter()
                .map(|&j| (names[j].clone(), w[j] * scale[j] / lead))
                .filter(|(_, c)| c.abs() > 1e-9)
                .collect();
            let value: f64 = members.iter().map(|&j| w[j] * scale[j] * x[j]).sum::<f64>() / lead;
            let std_error = cov(&w).sqrt() / lead.abs();
            combinations.push(Combination {
                text: combination_text(&terms),
                terms,
                value,
                std_error,
            });
        }
        groups.push(Group {
            members: members.iter().map(|&j| names[j].clone()).collect(),
            deficiency,
            combinations,
        });
    }
    let estimates = (0..p)
        .map(|j| {
            let mut e = DVector::zeros(p);
            e[j] = 1.0;
            let identifiable = group_of[j].is_none();
            Estimate {
                name: names[j].clone(),
                value: identifiable.then_some(x[j]),
                min_norm: x[j],
                std_error: identifiable.then(|| cov(&e).sqrt() / scale[j]),
                group: group_of[j],
            }
        })
        .collect();
    let rms = (rss / m as f64).sqrt();
    let max_abs = residuals.iter().fold(0.0f64, |a1, r| a1.max(r.abs()));
    Ok(Fit {
        estimates,
        groups,
        rank,
        singular_values: order.iter().map(|&i| sv[i] / smax).collect(),
        rtol,
        fitted: fitted_v.iter().copied().collect(),
        residuals,
        rms,
        max_abs,
        sigma,
    })
}

/// `E_A0Z − 1.0187·E_A0C`: a combination as text (the first coefficient is taken as 1).
pub fn combination_text(terms: &[(String, f64)]) -> String {
    let mut s = String::new();
    for (k, (name, c)) in terms.iter().enumerate() {
        if k == 0 {
            s.push_str(name);
            continue;
        }
        let sign = if *c < 0.0 { " − " } else { " + " };
        s.push_str(sign);
        let a = c.abs();
        if (a - 1.0).abs() > 5e-5 {
            s.push_str(&format!("{}·", trim(a)));
        }
        s.push_str(name);
    }
    s
}

fn trim(a: f64) -> String {
    let t = format!("{a:.4}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}
