//! The least squares with rank detection (module docs of [`super`]), moved here from the
//! S-shape study so that every test piece uses it.

use crate::error::{check_range, Error, Result};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Default relative singular-value threshold of the rank decision.
pub const DEFAULT_RTOL: f64 = 1e-2;
/// A parameter is not identifiable when its squared length in the weak directions (the diagonal
/// of their projector) exceeds this, i.e. a component above 0.1; two such parameters are in one
/// group when the projector couples them by more than this.
const GROUP_WEIGHT: f64 = 1e-2;
/// A column at or below this fraction of the largest column's norm counts as zero.
pub const ZERO_COLUMN: f64 = 1e-12;

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
    /// Degrees of freedom of the residual, `m − rank` (≥ 1).
    pub dof: usize,
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
    if m < 2 || p == 0 {
        return Err(Error::field(
            "fit",
            format!("{m} measurements and {p} parameters: nothing to fit"),
        ));
    }
    if a.iter().chain(d.iter()).any(|v| !v.is_finite()) {
        return Err(Error::field("fit", "the data must be finite"));
    }
    // A column whose norm is rounding noise (at most 1e-12 of the largest, e.g. an offset along a
    // rotary axis's own line) is no effect at all: scaled to unit norm it would be a random
    // direction and a false rank.
    let norms: Vec<f64> = (0..p).map(|j| a.column(j).norm()).collect();
    let largest = norms.iter().fold(0.0f64, |x, y| x.max(*y));
    let scale: Vec<f64> = norms
        .iter()
        .map(|&s| if s > ZERO_COLUMN * largest { s } else { 0.0 })
        .collect();
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
    let rank = strong.len();
    if m <= rank {
        return Err(Error::field(
            "fit",
            format!(
                "{m} measurements determine {rank} independent combinations of the errors exactly: \
                 no measurement is left to judge them (fit fewer errors or measure more)"
            ),
        ));
    }
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
    // P0 = I − V_r·V_rᵀ also holds the directions a short matrix (m < p) has no singular
    // vector for.
    let mut p0 = DMatrix::<f64>::identity(p, p);
    for &i in &strong {
        let v = v_t.row(i).transpose();
        p0 -= &v * v.transpose();
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
        singular_values: (0..p)
            .map(|k| order.get(k).map_or(0.0, |&i| sv[i] / smax))
            .collect(),
        rtol,
        fitted: fitted_v.iter().copied().collect(),
        residuals,
        rms,
        max_abs,
        sigma,
        dof: m - rank,
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
