//! The S-shape study as the page and scripts use it: its inputs (the machine, the tool, the
//! model options), and the computations built from [`super::part`], [`super::overcut`],
//! [`super::machine`] and [`super::identify`].

use super::machine::{
    defect_matrix, measurement_poses, DefectPoint, DefectReference, OnMachine, PathBranch,
    PointPose,
};
use super::overcut::{eq6_max, overcut_map, Basis, OvercutMap, ToolPath};
use super::part::{MeasurementPoint, Part, SurfaceId, N_POINTS};
use crate::cache::{self, Models};
use crate::error::{Error, Result};
use crate::identify::{self, Fit, DEFAULT_RTOL};
use crate::machine::errors::{ErrorDef, ErrorValues};
use crate::machine::Machine;
use crate::schema::{self, DefaultValue, Inputs, Kind, Quantity};
use nalgebra::DMatrix;
use serde_json::Value;
use std::cell::RefCell;
use std::rc::Rc;

/// Name of the tool-radius parameter in a fit: `ΔR = R' − R_tool`, mm.
pub const RADIUS_NAME: &str = "dR";

crate::inputs! {
    /// The end mill of eq 2.
    pub struct SShapeTool {
        /// SShapeTool radius, mm.
        pub r_tool: f64 = "rTool" optional {
            label: "Tool radius",
            help: "Radius of the flank end mill (the paper: 10 mm).",
            kind: schema::positive(Quantity::Length, 50.0),
            default: DefaultValue::Num(10.0),
            group: "Tool",
        },
        /// Tip to the tool section touching the top curve, mm.
        pub l_tool: f64 = "lTool" optional {
            label: "Tool length to the top curve",
            help: "From the tool tip to the section that touches the top curve (eq 2); more than the part's 30 mm height (the paper: 35 mm).",
            kind: schema::Kind::Number { quantity: Quantity::Length, min: 30.0, max: 500.0, exclusive_min: true },
            default: DefaultValue::Num(35.0),
            group: "Tool",
        },
    }
}

impl SShapeTool {
    /// The tool path of eq 2 for this tool.
    pub fn path(&self) -> ToolPath {
        ToolPath {
            r_tool: self.r_tool,
            l_tool: self.l_tool,
        }
    }
}

crate::inputs! {
    /// The model options of the machining defect.
    pub struct SShapeModel {
        /// Inverse-kinematics branch along the path.
        pub branch: PathBranch = "branch" optional {
            label: "Inverse kinematics along the path",
            help: "Which of the two solutions the machine uses; where the tool lies along the rotary table's axis (the middle of the S) that axis keeps its previous angle.",
            kind: Kind::Choice(PathBranch::CHOICES),
            default: DefaultValue::Str("paper"),
            group: "Model",
        },
        /// Reference pose of eq 14.
        pub reference: DefectReference = "reference" optional {
            label: "Defect subtracted",
            help: "The defect at this pose is subtracted: where the work offset was set (Chanal et al.'s eq 14).",
            kind: Kind::Choice(DefectReference::CHOICES),
            default: DefaultValue::Str("workOrigin"),
            group: "Model",
        },
        /// SShapeTool point eq 14 moves.
        pub point: DefectPoint = "point" optional {
            label: "Tool point moved",
            help: "Eq 14 moves the tool tip; the contact point adds the tool's tilt.",
            kind: Kind::Choice(DefectPoint::CHOICES),
            default: DefaultValue::Str("tip"),
            group: "Model",
        },
    }
}

crate::inputs! {
    /// What every S-shape computation on a machine needs.
    pub struct SShapeCase {
        /// The machine and its errors.
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// The tool.
        pub tool: SShapeTool = "tool" optional {
            label: "Tool", kind: Kind::Object(SShapeTool::FIELDS), default: DefaultValue::Empty,
        },
        /// The model options.
        pub model: SShapeModel = "model" optional {
            label: "Model", kind: Kind::Object(SShapeModel::FIELDS), default: DefaultValue::Empty,
        },
    }
}

crate::inputs! {
    /// The defects' own inputs (with a [`SShapeCase`]).
    pub struct SShapeDefectsInput {
        /// SShapeTool-radius error `R' − R`, mm.
        pub d_r: f64 = "dR" optional {
            label: "Tool radius error R′ − R",
            help: "Positive: the real tool is larger than programmed, so the surface moves in.",
            kind: schema::number(Quantity::SmallLength, -1.0, 1.0),
            default: DefaultValue::Num(0.0),
            group: "Errors",
        },
    }
}

crate::inputs! {
    /// The identification's own inputs (with a [`SShapeCase`]).
    pub struct SShapeIdentifyInput {
        /// The measurement file.
        pub csv: String = "csv" {
            label: "Measured deviations (CSV)",
            help: "Header curve,point,deviation_mm (or deviation_um); 100 rows: top/bottom, 1–50 (1–25 surface A, 26–50 B); positive = material left.",
            kind: Kind::Text { max_len: 1_000_000 },
            group: "Identification",
        },
        /// The errors to identify; all the machine's when left out.
        pub parameters: Option<Vec<String>> = "parameters" optional {
            label: "Errors to identify",
            help: "The machine's errors the fit may use; left out: all of them. Those the part cannot separate are reported as groups.",
            kind: crate::machine::errors::NAMES,
            group: "Identification",
        },
        /// Fit a tool-radius error too.
        pub radius_term: bool = "radiusTerm" optional {
            label: "Fit a tool-radius error too",
            help: "Adds R′ − R to the unknowns (it moves every point along its normal by −sin θ per mm).",
            kind: Kind::Flag,
            default: DefaultValue::Flag(true),
            group: "Identification",
        },
        /// Relative singular-value threshold of the rank decision.
        pub rtol: f64 = "rtol" optional {
            label: "Rank threshold (relative singular value)",
            help: "Directions below it count as not identifiable (0.01: condition number 100).",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 1e-12, max: 0.5, exclusive_min: false },
            default: DefaultValue::Num(DEFAULT_RTOL),
            group: "Identification",
        },
        /// How the values are judged.
        pub decision: identify::DecisionInput = "decision" optional {
            label: "Decision",
            kind: Kind::Object(identify::DecisionInput::FIELDS),
            default: DefaultValue::Empty,
        },
    }
}

crate::inputs! {
    /// The part's surfaces for a drawing.
    pub struct SShapePartInput {
        /// Points along u.
        pub nu: usize = "nu" optional {
            label: "Drawing points along the S", kind: Kind::Count { min: 2, max: 2001 },
            default: DefaultValue::Num(131.0), shown: false,
        },
        /// Points over the height.
        pub nv: usize = "nv" optional {
            label: "Drawing points over the height", kind: Kind::Count { min: 2, max: 101 },
            default: DefaultValue::Num(7.0), shown: false,
        },
    }
}

crate::inputs! {
    /// The overcut maps: the tool and the grid.
    pub struct SShapeOvercutInput {
        /// The tool.
        pub tool: SShapeTool = "tool" optional {
            label: "Tool", kind: Kind::Object(SShapeTool::FIELDS), default: DefaultValue::Empty,
        },
        /// Points along u.
        pub nu: usize = "nu" optional {
            label: "Overcut map: points along u",
            help: "261 puts every knot on the grid.",
            kind: Kind::Count { min: 14, max: 1001 },
            default: DefaultValue::Num(261.0),
            group: "Overcut map",
        },
        /// Points over the height.
        pub nv: usize = "nv" optional {
            label: "Points over the height",
            kind: Kind::Count { min: 2, max: 61 },
            default: DefaultValue::Num(11.0),
            group: "Overcut map",
        },
    }
}

impl SShapeCase {
    /// Reads a case and the export's own inputs from one object: the keys of `B` go to `B`,
    /// the rest to the case.
    pub fn read_with<B: Inputs>(value: &Value) -> Result<(SShapeCase, B)> {
        let (case, own): (SShapeCase, B) = schema::read_split(value, "")?;
        case.check_case()?;
        Ok((case, own))
    }

    /// Checks the case once read: the machine, and no error motions.
    pub fn check_case(&self) -> Result<()> {
        self.machine.validate("machine")?;
        // Eq 14 is a model of the location errors: error motions would be left out unseen.
        if let Some(name) = self.machine.motions.0.keys().next() {
            return Err(Error::field(
                format!("machine.motions.{name}"),
                "the S-shape model (Chanal et al., eq 14) takes the location errors only; error motions are not in it. Clear the error motions (Volumetric tab) to run this study.",
            ));
        }
        Ok(())
    }
}

/// The identification of a case from its measurement file (`sshapeIdentify`): the file read,
/// the cached design ([`Design::cached`]), the fit and its decisions. Returns the measured
/// deviations (list order, mm) and the judgement.
pub fn identify_case(
    case: &SShapeCase,
    input: &SShapeIdentifyInput,
) -> Result<(Vec<f64>, identify::Judgement)> {
    let measured = super::identify::parse_measurements(&input.csv)?;
    let judgement = Design::cached(case)?.judge(
        &measured,
        input.parameters.as_deref(),
        input.radius_term,
        input.rtol,
        &input.decision.options(),
    )?;
    Ok((measured, judgement))
}

/// Everything the eq 14 model needs, computed once for a machine, tool and model.
#[derive(Debug, Clone)]
pub struct Design {
    /// The part.
    pub part: Part,
    /// The tool path.
    pub path: ToolPath,
    /// The part on the machine.
    pub on: OnMachine,
    /// The model options.
    pub model: SShapeModel,
    /// The 100 points with their machine poses.
    pub poses: Vec<PointPose>,
    /// Eq 14 sensitivities: row per point, column per machine error (mm per mm or per rad).
    pub rows: Vec<Vec<f64>>,
    /// Deviation per mm of tool-radius error: `−sin θ` at each point.
    pub radius: Vec<f64>,
}

impl Design {
    /// Builds the model for a machine (its errors are not used here), a tool and the options.
    pub fn new(machine: &Machine, tool: &SShapeTool, model: &SShapeModel) -> Result<Self> {
        let part = Part::standard()?;
        let path = tool.path();
        let on = OnMachine::new(&machine.without_errors())?;
        let points = Part::standard_points()?;
        let poses = measurement_poses(&on, &path, &part, points, model.branch)?;
        let rows = defect_matrix(&on, &poses, model.reference, model.point)?;
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
            on,
            model: model.clone(),
            poses,
            rows,
            radius,
        })
    }

    /// The design of a case, built once per machine (without its errors), tool and model and
    /// kept in a small per-thread cache ([`crate::cache`]): what the exports use, as the page
    /// asks for the defects and identifications with the same machine.
    pub fn cached(case: &SShapeCase) -> Result<Rc<Self>> {
        /// What a design depends on: the machine without its errors, the tool, the model.
        type Key = (Machine, SShapeTool, SShapeModel);
        thread_local! {
            static DESIGNS: Models<Key, Design> = const { RefCell::new(Vec::new()) };
        }
        let key = (
            case.machine.without_errors(),
            case.tool.clone(),
            case.model.clone(),
        );
        cache::get_or_build(&DESIGNS, key, || {
            Self::new(&case.machine, &case.tool, &case.model)
        })
    }

    /// The machine's errors, the columns of [`Self::rows`].
    pub fn errors(&self) -> &[&'static ErrorDef] {
        &self.on.errors
    }

    /// The measurement points.
    pub fn points(&self) -> Vec<MeasurementPoint> {
        self.poses.iter().map(|p| p.point).collect()
    }

    /// The deviation at each point (mm) for the machine's errors and a tool-radius error `dr`
    /// (mm): eq 14 applied to every error, plus `−sin θ·dr`.
    pub fn simulate(&self, errors: &ErrorValues, dr: f64) -> Vec<f64> {
        self.contributions(errors)
            .iter()
            .zip(self.radius_deviation(dr))
            .map(|(row, r)| row.iter().sum::<f64>() + r)
            .collect()
    }

    /// The deviation at each point (mm) from each of the machine's errors alone (eq 14, one
    /// column per [`Design::errors`]): row per point.
    pub fn contributions(&self, errors: &ErrorValues) -> Vec<Vec<f64>> {
        let xi: Vec<f64> = self.errors().iter().map(|d| errors.get(d.name)).collect();
        self.rows
            .iter()
            .map(|row| row.iter().zip(&xi).map(|(a, x)| a * x).collect())
            .collect()
    }

    /// The deviation at each point (mm) from a tool-radius error `dr` (mm) alone: `−sin θ·dr`.
    pub fn radius_deviation(&self, dr: f64) -> Vec<f64> {
        self.radius.iter().map(|r| r * dr).collect()
    }

    /// Least-squares identification of the errors `parameters` (all the machine's when `None`)
    /// and `dR` when `radius_term`, from measured deviations (mm, list order).
    pub fn identify(
        &self,
        measured: &[f64],
        parameters: Option<&[String]>,
        radius_term: bool,
        rtol: f64,
    ) -> Result<Fit> {
        let (a, names) = self.system(measured, parameters, radius_term)?;
        identify::fit(&a, &names, measured, rtol)
    }

    /// [`Self::identify`] with the decisions of [`crate::identify::judge`]: family-wise tests,
    /// the tolerance, intervals and the goodness of fit against the stated noise.
    pub fn judge(
        &self,
        measured: &[f64],
        parameters: Option<&[String]>,
        radius_term: bool,
        rtol: f64,
        options: &crate::identify::Options,
    ) -> Result<crate::identify::Judgement> {
        let (a, names) = self.system(measured, parameters, radius_term)?;
        let params: Vec<crate::identify::Param> = names
            .iter()
            .map(|n| {
                if n == RADIUS_NAME {
                    Ok(crate::identify::Param {
                        name: n,
                        quantity: Quantity::SmallLength,
                        def: None,
                        label: "the tool's radius R′ − R is",
                    })
                } else {
                    crate::identify::Param::error(n)
                }
            })
            .collect::<Result<_>>()?;
        crate::identify::identify(&a, &params, measured, rtol, options)
    }

    /// The sensitivity matrix of the chosen parameters (rows: points) and their names.
    fn system(
        &self,
        measured: &[f64],
        parameters: Option<&[String]>,
        radius_term: bool,
    ) -> Result<(DMatrix<f64>, Vec<String>)> {
        if measured.len() != N_POINTS {
            return Err(Error::field(
                "deviations",
                format!("expected {N_POINTS} values, got {}", measured.len()),
            ));
        }
        let columns: Vec<usize> = match parameters {
            None => (0..self.errors().len()).collect(),
            Some(names) => names
                .iter()
                .enumerate()
                .map(|(i, n)| {
                    self.on.error_index(n).ok_or_else(|| {
                        Error::field(
                            format!("parameters[{i}]"),
                            format!("{n} is not an error of this machine"),
                        )
                    })
                })
                .collect::<Result<_>>()?,
        };
        let p = columns.len() + usize::from(radius_term);
        if p == 0 {
            return Err(Error::field(
                "parameters",
                "choose at least one error to identify",
            ));
        }
        let a = DMatrix::from_fn(N_POINTS, p, |r, c| {
            if c < columns.len() {
                self.rows[r][columns[c]]
            } else {
                self.radius[r]
            }
        });
        let mut names: Vec<String> = columns
            .iter()
            .map(|&c| self.errors()[c].name.to_string())
            .collect();
        if radius_term {
            names.push(RADIUS_NAME.to_string());
        }
        Ok((a, names))
    }

    /// The cosine between the sensitivity columns of two errors (−1: they act alike but for
    /// sign); `None` when either is not an error of the machine or has no effect.
    pub fn column_cosine(&self, a: &str, b: &str) -> Option<f64> {
        let (i, j) = (self.on.error_index(a)?, self.on.error_index(b)?);
        let col = |k: usize| self.rows.iter().map(move |r| r[k]);
        let dot: f64 = col(i).zip(col(j)).map(|(x, y)| x * y).sum();
        let na = col(i).map(|x| x * x).sum::<f64>().sqrt();
        let nb = col(j).map(|x| x * x).sum::<f64>().sqrt();
        (na > 0.0 && nb > 0.0).then(|| dot / (na * nb))
    }

    /// Pairs of errors whose columns are nearly parallel (|cos| ≥ `min`), most alike first.
    pub fn alike_pairs(&self, min: f64) -> Vec<(&'static str, &'static str, f64)> {
        let e = self.errors();
        let mut out = Vec::new();
        for i in 0..e.len() {
            for j in i + 1..e.len() {
                if let Some(c) = self.column_cosine(e[i].name, e[j].name) {
                    if c.abs() >= min {
                        out.push((e[i].name, e[j].name, c));
                    }
                }
            }
        }
        out.sort_by(|a, b| b.2.abs().total_cmp(&a.2.abs()));
        out
    }
}

/// The largest overcuts Chanal et al. print for surfaces A and B, mm (eq 6, their tool path).
pub const PAPER_OVERCUT: [f64; 2] = [0.0387, 0.0125];

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
