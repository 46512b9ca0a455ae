//! Flank milling of the ruled surfaces with a cylindrical tool: the analytic tool path (eq 2),
//! the tool envelope (eqs 3–5), the overcut of eq 6, the exact gouge, and the defect of a
//! tool-radius error (Section 3.2), after Chanal, Duc & Chevalier (2022), Section 3.
//!
//! # Tool path (eq 2)
//! `T_tool(u) = C1(u) + R_tool·N(u, 1) − L_tool·R(u)`: the tool tip, with the tool axis `R(u)`
//! (tip → spindle); the tool's section at `h = L_tool` above the tip touches the top curve
//! `C1(u)` (paper: `R_tool = 10 mm`, `L_tool = 35 mm`). `N` is the unit outward normal, so the
//! tool lies outside the part.
//!
//! # Envelope and eq 6
//! A point `M = E + h·R + R_tool·n` of the tool (height `h` above the tip `E`, `n ⊥ R`) is on the
//! envelope when its velocity is tangent to the tool: `(dE/du + h·dR/du)·n = 0` (eqs 3–5).
//! Writing `n = cos θ·T + sin θ·N(u, 1)` gives `tan θ = −a·T/a·N` with `a = dE/du + h·dR/du`;
//! of the two solutions the one with `sin θ ≥ 0` is the contact on the part's side. Eq 6:
//! `overcut(u, h) = R_tool·(1 − sin θ)`, mapped over the surface with `h` the height of the
//! surface point `S(u, v)` on the tool: `h = L_tool − (1 − v)·‖C1 − C0‖`.
//! * [`Basis::Paper`]: `T = S_u/‖S_u‖` at `v = 1` as the paper defines it. It is not
//!   perpendicular to `R`, so `n` is then neither a unit vector nor perpendicular to the tool axis.
//! * [`Basis::Orthonormal`]: `T⊥` (the part of `T` perpendicular to `R`), which makes `n` a unit
//!   normal of the cylinder, as eqs 3–5 require.
//!
//! # Exact gouge
//! Independent of eqs 3–6: a surface point `P = S(u, v)` lies inside the tool at position `u'`
//! when its distance to the tool axis (the half-line from the tip `E(u')` along `R(u')`) is less
//! than `R_tool`. The signed deviation is `δ(u, v) = min over u' of (dist(P, axis(u')) − R_tool)`:
//! negative = the tool removes material beyond the nominal surface (overcut, gouge), positive =
//! material left (undercut), measured radially to the nearest tool position. The minimum is
//! searched over `u' ∈ [u − 0.02, u + 0.02]` (about ±12 mm of path; a coarse scan, then
//! golden-section refinement); the tests check it against a search over the whole path.
//! The tool at `u` contains the whole ruling `u` (its axis is parallel to `R(u)`, at distance
//! `R_tool` along `N(u, 1) ⊥ R(u)`), so `δ ≤ 0` everywhere: any gouge is made by neighbouring
//! tool positions, and this path leaves no undercut.
//!
//! # Tool-radius defect (Section 3.2)
//! A real radius `R' = R_tool + ΔR` cut along the same path moves the machined surface inwards
//! by `ΔR·sin θ`: deviation `−ΔR·sin θ(u, h)` (the paper writes `(R' − R)·sin θ` as a defect
//! magnitude).

use super::part::{Frame, Surface, HEIGHT};
use crate::error::{check_count, check_positive, Result};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// The paper's tool radius, mm.
pub const PAPER_R_TOOL: f64 = 10.0;
/// The paper's tool length (tip to the section touching the top curve), mm.
pub const PAPER_L_TOOL: f64 = 35.0;
/// Half-width of the window of tool positions searched for the exact gouge, in u.
pub const GOUGE_WINDOW: f64 = 0.02;

/// Which tangent the paper's `n = cos θ·T + sin θ·N` uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Basis {
    /// `T = S_u/‖S_u‖` (as defined in the paper).
    Paper,
    /// `T⊥ ⊥ R` (an orthonormal frame, as eqs 3–5 require).
    #[default]
    Orthonormal,
}

/// The tool of eq 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolPath {
    /// Tool radius, mm.
    pub r_tool: f64,
    /// Tool length: tip to the section that touches the top curve, mm.
    pub l_tool: f64,
}

/// Positions scanned by [`ToolPath::deviation`] in its window, before the golden section.
const DEVIATION_SCAN: usize = 40;

/// The tool at the scanned positions of a search window (see [`ToolPath::deviation_in`]).
struct Scan {
    lo: f64,
    hi: f64,
    step: f64,
    /// `(u', tool at u')` for `u' = lo + i·step`, `i = 0 … n`.
    at: Vec<(f64, ToolPoint)>,
}

/// One tool position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolPoint {
    /// Tool tip `E(u)`, mm.
    pub tip: Vector3<f64>,
    /// Unit tool axis `R(u)` (tip → spindle).
    pub axis: Vector3<f64>,
    /// `dE/du`, mm.
    pub tip_u: Vector3<f64>,
    /// `dR/du`.
    pub axis_u: Vector3<f64>,
    /// The surface frame at `(u, 1)`.
    pub top: Frame,
}

impl ToolPath {
    /// The paper's tool: `R_tool = 10 mm`, `L_tool = 35 mm`.
    pub fn paper() -> Self {
        Self {
            r_tool: PAPER_R_TOOL,
            l_tool: PAPER_L_TOOL,
        }
    }

    /// A tool with radius `r_tool` (0 < r ≤ 50 mm) and length `l_tool` (30 mm < l ≤ 500 mm:
    /// the tool must reach below the part's base).
    pub fn new(r_tool: f64, l_tool: f64) -> Result<Self> {
        check_positive("rTool", r_tool, 50.0, "mm")?;
        crate::error::check_range("lTool", l_tool, 30.0, 500.0, "mm")?;
        Ok(Self { r_tool, l_tool })
    }

    /// The tool position at `u` (eq 2) and its derivative.
    pub fn at(&self, surface: &Surface, u: f64) -> ToolPoint {
        let f = surface.frame(u, 1.0);
        let tip = f.point + f.normal * self.r_tool - f.ruling * self.l_tool;
        let tip_u = f.s_u + f.normal_u * self.r_tool - f.ruling_u * self.l_tool;
        ToolPoint {
            tip,
            axis: f.ruling,
            tip_u,
            axis_u: f.ruling_u,
            top: f,
        }
    }

    /// Height on the tool of the surface point `S(u, v)`: `L_tool − (1 − v)·‖C1 − C0‖`, mm.
    pub fn height(&self, t: &ToolPoint, v: f64) -> f64 {
        self.l_tool - (1.0 - v) * t.top.ruling_vector.norm()
    }

    /// `sin θ` of eq 5 at tool position `t` and height `h` (the root with `sin θ ≥ 0`).
    /// Degenerate case: a zero velocity `a` (never on the standard's surfaces) gives 1.
    pub fn sin_theta(&self, t: &ToolPoint, h: f64, basis: Basis) -> f64 {
        let a = t.tip_u + t.axis_u * h;
        let tangent = match basis {
            Basis::Paper => t.top.tangent,
            Basis::Orthonormal => t.top.tangent_perp,
        };
        let (at, an) = (a.dot(&tangent), a.dot(&t.top.normal));
        let r = at.hypot(an);
        if r == 0.0 {
            1.0
        } else {
            at.abs() / r
        }
    }

    /// Eq 6 at the surface point `(u, v)`, mm.
    pub fn overcut_eq6(&self, surface: &Surface, u: f64, v: f64, basis: Basis) -> f64 {
        let t = self.at(surface, u);
        self.r_tool * (1.0 - self.sin_theta(&t, self.height(&t, v), basis))
    }

    /// Signed distance (mm) of the point `p` from the tool at position `t`: distance to the
    /// axis half-line from the tip, minus the radius.
    pub fn clearance(&self, t: &ToolPoint, p: &Vector3<f64>) -> f64 {
        let d = p - t.tip;
        let along = d.dot(&t.axis).max(0.0);
        (d - t.axis * along).norm() - self.r_tool
    }

    /// The exact deviation `δ(u, v)` (mm; negative = gouge) and the tool position `u'` where
    /// the minimum is reached, searching `u' ∈ [lo, hi]` (a scan of `scan + 1` positions, then
    /// golden-section refinement to 1e-13 around the best one).
    pub fn deviation_in(
        &self,
        surface: &Surface,
        p: &Vector3<f64>,
        lo: f64,
        hi: f64,
        scan: usize,
    ) -> (f64, f64) {
        self.nearest(surface, p, &self.scan(surface, lo, hi, scan))
    }

    /// The tool at the `n + 1` equally spaced positions `lo + i·(hi − lo)/n` of a search
    /// window: computed once for every surface point whose window it is (the points of one `u`).
    fn scan(&self, surface: &Surface, lo: f64, hi: f64, n: usize) -> Scan {
        let step = (hi - lo) / n as f64;
        let at = (0..=n)
            .map(|i| {
                let x = lo + step * i as f64;
                (x, self.at(surface, x))
            })
            .collect();
        Scan { lo, hi, step, at }
    }

    /// [`Self::deviation_in`] over a scan already made: the smallest clearance of `p` at the
    /// scanned positions, refined by golden section within a step of the best one.
    fn nearest(&self, surface: &Surface, p: &Vector3<f64>, scan: &Scan) -> (f64, f64) {
        let mut best = (f64::INFINITY, scan.lo);
        for (x, t) in &scan.at {
            let y = self.clearance(t, p);
            if y < best.0 {
                best = (y, *x);
            }
        }
        let f = |x: f64| self.clearance(&self.at(surface, x), p);
        let a = (best.1 - scan.step).max(scan.lo);
        let b = (best.1 + scan.step).min(scan.hi);
        let x = crate::numeric::golden_max(|x| -f(x), a, b);
        let y = f(x);
        if y < best.0 {
            best = (y, x);
        }
        best
    }

    /// The search window of the surface points at `u`: `u ± GOUGE_WINDOW` within `[0, 1]`.
    fn window(u: f64) -> (f64, f64) {
        ((u - GOUGE_WINDOW).max(0.0), (u + GOUGE_WINDOW).min(1.0))
    }

    /// The exact deviation at the surface point `(u, v)` (window of [`GOUGE_WINDOW`]), mm.
    pub fn deviation(&self, surface: &Surface, u: f64, v: f64) -> f64 {
        let (lo, hi) = Self::window(u);
        self.deviation_in(surface, &surface.point(u, v), lo, hi, DEVIATION_SCAN)
            .0
    }

    /// Section 3.2: the deviation (mm, negative = inwards) at `(u, v)` caused by a real tool
    /// radius `R_tool + dr`: `−dr·sin θ(u, h)`.
    pub fn radius_defect(&self, surface: &Surface, u: f64, v: f64, dr: f64, basis: Basis) -> f64 {
        let t = self.at(surface, u);
        -dr * self.sin_theta(&t, self.height(&t, v), basis)
    }
}

/// Overcut maps of one surface on a `nu × nv` grid of `(u, v)` (row-major: `[iv·nu + iu]`).
#[derive(Debug, Clone, PartialEq)]
pub struct OvercutMap {
    /// Grid in u, `nu` values from 0 to 1.
    pub u: Vec<f64>,
    /// Grid in v, `nv` values from 0 to 1 (z = 30·v mm).
    pub v: Vec<f64>,
    /// Eq 6 with the paper's `T`, mm.
    pub eq6_paper: Vec<f64>,
    /// Eq 6 with `T⊥`, mm.
    pub eq6: Vec<f64>,
    /// Exact signed deviation `δ`, mm (negative = gouge).
    pub exact: Vec<f64>,
}

/// The peaks of one surface's [`OvercutMap`], with where they are: `[u, z mm]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OvercutPeaks {
    /// Largest eq 6 with the paper's `T`, mm.
    pub eq6_paper: f64,
    /// Largest eq 6 with `T⊥`, mm.
    pub eq6: f64,
    /// Largest gouge `−δ`, mm (0 where the surface is nowhere gouged).
    pub gouge: f64,
    /// Where the largest eq 6 (`T⊥`) is.
    pub at_eq6: [f64; 2],
    /// Where the largest gouge is.
    pub at_gouge: [f64; 2],
}

impl OvercutMap {
    /// The heights of the grid rows, `z = 30·v` mm.
    pub fn z(&self) -> Vec<f64> {
        self.v.iter().map(|v| v * HEIGHT).collect()
    }

    /// The largest overcuts and gouge of the map, and where they are.
    pub fn peaks(&self) -> OvercutPeaks {
        let (eq6_paper, _, _) = self.max_of(&self.eq6_paper);
        let (eq6, u6, v6) = self.max_of(&self.eq6);
        let gouge: Vec<f64> = self.exact.iter().map(|d| -d).collect();
        let (g, ug, vg) = self.max_of(&gouge);
        OvercutPeaks {
            eq6_paper,
            eq6,
            gouge: g.max(0.0),
            at_eq6: [u6, v6 * HEIGHT],
            at_gouge: [ug, vg * HEIGHT],
        }
    }

    /// Largest value of a row-major field and its `(u, v)`; of equal largest values, the first.
    pub fn max_of(&self, field: &[f64]) -> (f64, f64, f64) {
        let nu = self.u.len();
        let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
        for (k, &y) in field.iter().enumerate() {
            if y > best.0 {
                best = (y, self.u[k % nu], self.v[k / nu]);
            }
        }
        best
    }
}

/// The largest eq 6 overcut over an `nu × nv` grid of one surface (mm), with the given basis.
pub fn eq6_max(
    path: &ToolPath,
    surface: &Surface,
    nu: usize,
    nv: usize,
    basis: Basis,
) -> Result<f64> {
    check_count("nu", nu, 2, 20001)?;
    check_count("nv", nv, 2, 1001)?;
    let mut best = f64::NEG_INFINITY;
    for iu in 0..nu {
        let t = path.at(surface, iu as f64 / (nu - 1) as f64);
        for iv in 0..nv {
            let h = path.height(&t, iv as f64 / (nv - 1) as f64);
            best = best.max(path.r_tool * (1.0 - path.sin_theta(&t, h, basis)));
        }
    }
    Ok(best)
}

/// Computes the maps of one surface on a `nu × nv` grid (2..=2001 × 2..=101).
pub fn overcut_map(path: &ToolPath, surface: &Surface, nu: usize, nv: usize) -> Result<OvercutMap> {
    check_count("nu", nu, 2, 2001)?;
    check_count("nv", nv, 2, 101)?;
    let u: Vec<f64> = (0..nu).map(|i| i as f64 / (nu - 1) as f64).collect();
    let v: Vec<f64> = (0..nv).map(|i| i as f64 / (nv - 1) as f64).collect();
    let mut eq6_paper = vec![0.0; nu * nv];
    let mut eq6 = vec![0.0; nu * nv];
    let mut exact = vec![0.0; nu * nv];
    for (iu, &uu) in u.iter().enumerate() {
        let t = path.at(surface, uu);
        // Every point of this u searches the same window: the tool's positions scanned once.
        let (lo, hi) = ToolPath::window(uu);
        let scan = path.scan(surface, lo, hi, DEVIATION_SCAN);
        for (iv, &vv) in v.iter().enumerate() {
            let h = path.height(&t, vv);
            let k = iv * nu + iu;
            eq6_paper[k] = path.r_tool * (1.0 - path.sin_theta(&t, h, Basis::Paper));
            eq6[k] = path.r_tool * (1.0 - path.sin_theta(&t, h, Basis::Orthonormal));
            exact[k] = path.nearest(surface, &surface.point(uu, vv), &scan).0;
        }
    }
    Ok(OvercutMap {
        u,
        v,
        eq6_paper,
        eq6,
        exact,
    })
}
