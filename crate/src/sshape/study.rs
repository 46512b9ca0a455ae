//! The S-shape study as the page and scripts use it: one set of inputs (machine, tool, model
//! options), and the computations built from [`super::part`], [`super::overcut`],
//! [`super::machine`] and [`super::identify`].

use super::identify::{self, Fit};
use super::machine::{
    defect_matrix, measurement_poses, DefectModel, Errors, Machine, PointPose, ERROR_NAMES,
};
use super::overcut::{eq6_max, overcut_map, Basis, OvercutMap, ToolPath};
use super::part::{MeasurementPoint, Part, SurfaceId, N_POINTS};
use crate::error::{check_range, Error, Result};
use nalgebra::DMatrix;

/// Name of the tool-radius parameter in a fit: `ΔR = R' − R_tool`, mm.
pub const RADIUS_NAME: &str = "dR";
/// Largest accepted error value: 1 mm for `E_X0B`, 0.01 rad for the angles.
pub const MAX_ERROR: [f64; 8] = [0.01, 0.01, 0.01, 0.01, 0.01, 1.0, 0.01, 0.01];

/// Everything the eq 14 model needs, computed once for a machine, tool and model.
#[derive(Debug, Clone)]
pub struct Design {
    /// The part.
    pub part: Part,
    /// The tool path.
    pub path: ToolPath,
    /// The machine.
    pub machine: Machine,
    /// The model options.
    pub model: DefectModel,
    /// The 100 points with their machine poses.
    pub poses: Vec<PointPose>,
    /// Eq 14 sensitivities: row per point, column per error (mm per mm or per rad).
    pub rows: Vec<[f64; 8]>,
    /// Deviation per mm of tool-radius error: `−sin θ` at each point.
    pub radius: Vec<f64>,
}

impl Design {
    /// Builds the model for pivot distance `l0` (mm), the tool, and the options.
    pub fn new(l0: f64, path: ToolPath, model: DefectModel) -> Result<Self> {
        let part = Part::standard()?;
        let machine = Machine::new(l0)?;
        let points = Part::standard_points()?;
        let poses = measurement_poses(&machine, &path, &part, points, model.branch)?;
        let rows = defect_matrix(&machine, &poses, &model)?;
        let radius = poses
            .iter()
            .map(|pp| {
                let s = part.surface(pp.point.surface);
                let t = path.at(s, pp.point.u);
                -path.sin_theta(&t, pp.height, Basis::Orthonormal)
            })
            .collect();
        Ok(Self {
            part,
            path,
            machine,
            model,
            poses,
            rows,
            radius,
        })
    }

    /// The measurement points.
    pub fn points(&self) -> Vec<MeasurementPoint> {
        self.poses.iter().map(|p| p.point).collect()
    }

    /// The deviation at each point (mm) for errors `xi` and a tool-radius error `dr` (mm).
    pub fn simulate(&self, xi: &Errors, dr: f64) -> Result<Vec<f64>> {
        check_errors(xi)?;
        check_range("dR", dr, -1.0, 1.0, "mm")?;
        Ok(self
            .rows
            .iter()
            .zip(&self.radius)
            .map(|(row, r)| row.iter().zip(xi).map(|(a, x)| a * x).sum::<f64>() + r * dr)
            .collect())
    }

    /// Least-squares identification of the 8 errors (and `dR` when `radius_term`) from
    /// measured deviations (mm, list order).
    pub fn identify(&self, measured: &[f64], radius_term: bool, rtol: f64) -> Result<Fit> {
        if measured.len() != N_POINTS {
            return Err(Error::field(
                "deviations",
                format!("expected {N_POINTS} values, got {}", measured.len()),
            ));
        }
        let p = if radius_term { 9 } else { 8 };
        let a = DMatrix::from_fn(N_POINTS, p, |r, c| {
            if c < 8 {
                self.rows[r][c]
            } else {
                self.radius[r]
            }
        });
        let mut names: Vec<String> = ERROR_NAMES.iter().map(|s| s.to_string()).collect();
        if radius_term {
            names.push(RADIUS_NAME.to_string());
        }
        identify::fit(&a, &names, measured, rtol)
    }
}

/// Checks the 8 error values (finite, within [`MAX_ERROR`]).
pub fn check_errors(xi: &Errors) -> Result<()> {
    for (k, v) in xi.iter().enumerate() {
        let unit = if k == 5 { "mm" } else { "rad" };
        check_range(
            &format!("errors.{}", ERROR_NAMES[k]),
            *v,
            -MAX_ERROR[k],
            MAX_ERROR[k],
            unit,
        )?;
    }
    Ok(())
}

/// The overcut maps of both surfaces, and the maxima of eq 6 with the paper's sign of `N`
/// (`N = R × T` on both surfaces, i.e. the tool on the side of B that faces A).
#[derive(Debug, Clone)]
pub struct Overcut {
    /// Surface A (outward side).
    pub a: OvercutMap,
    /// Surface B (outward side).
    pub b: OvercutMap,
    /// Eq 6 maxima (paper's `T`, then `T⊥`) of surface B with the paper's `N = R × T`, which
    /// puts the tool on B's inner side (facing A), mm.
    pub b_paper_side: (f64, f64),
}

/// Computes the overcut maps of both surfaces on `nu × nv` grids.
pub fn overcut(path: &ToolPath, nu: usize, nv: usize) -> Result<Overcut> {
    let part = Part::standard()?;
    let mut inner = part.surface(SurfaceId::B).clone();
    inner.outward = -inner.outward;
    Ok(Overcut {
        a: overcut_map(path, part.surface(SurfaceId::A), nu, nv)?,
        b: overcut_map(path, part.surface(SurfaceId::B), nu, nv)?,
        b_paper_side: (
            eq6_max(path, &inner, nu, nv, Basis::Paper)?,
            eq6_max(path, &inner, nu, nv, Basis::Orthonormal)?,
        ),
    })
}
