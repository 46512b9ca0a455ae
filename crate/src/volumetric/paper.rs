//! Tan & Lim's model of the RRTTT machine, exactly as printed (Section VI, "Error analysis of
//! RRTTT(3) model"): the loop, its symbols and signs, and its first-order ΔX, ΔY, ΔZ.
//!
//! # The loop
//! ```text
//! R_x·[R_A·[R_C·P_a + T_C] + T_A] + T_x = R_y·[R_z·P_t + T_z] + T_y,    ΔP = P_a − (P + P_t)
//! ```
//! `P = (X, Y, Z)` the axis positions, `P_t = (X_t, Y_t, Z_t)` the tool offset (the tip in the Z
//! carriage's frame), `P_a` the actual tip in table coordinates. X carries the table (A, then C
//! on A), Y and Z carry the tool. Every `R` is the printed small-angle matrix
//! `[[1, −ε_z, ε_y], [ε_z, 1, −ε_x], [−ε_y, ε_x, 1]]` of its three angles (`E_x(X), E_y(X),
//! E_z(X)` for X; `φ, λ, γ` for C and A), and
//! ```text
//! T_x = (−X − δx(X), δy(X) − α·X, δz(X)),   T_y = (δx(Y), Y + δy(Y), δz(Y)),
//! T_z = (δx(Z) − β1·Z, δy(Z) − β2·Z, Z + δz(Z)),   T_C = −(∂X_C, ∂Y_C, ∂Z_C),  T_A likewise.
//! ```
//! [`loop_deviation`] solves it for `P_a` with the printed matrices (inverted exactly; they are
//! not rotations beyond first order). [`printed`] is the paper's first-order ΔX, ΔY, ΔZ, term by
//! term. The tests show the printed coefficients are the loop's derivatives, error by error.
//!
//! # What the loop leaves out
//! `R_C` and `R_A` hold only the error rotations: the table does not turn. The loop is the
//! machine with A and C at zero and their error values taken at θ; the deviation is along the
//! machine axes. On the machine ([`super`]) the table turns: the deviation seen on the workpiece
//! is the machine-axes deviation turned back by the table's rotation, and C's error motions act
//! along C's own (tilted by A) axis frame. The squareness errors: the paper writes α on X
//! (`T_x`'s `−α·X`) and β1, β2 as straightness of Z growing with Z; ISO 230-1 with X as the
//! reference writes them as the orientations `E_C0Y`, `E_B0Z`, `E_A0Z` of Y and Z. For the same
//! angles between the axes (`E_C0Y = −α`, `E_B0Z = −β1`, `E_A0Z = β2`) the two differ by a rigid
//! turn of the whole workpiece about Z by α (a choice of reference axis, which setting the
//! workpiece up by its edge removes), and the machine's tilted Z also tilts the tool: a term
//! `β·Z_t` the paper does not have.

use crate::error::{Error, Result};
use nalgebra::{Matrix3, Vector3};

/// Tan & Lim's error values at one pose, engine units (mm, rad), in their symbols and signs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PaperErrors {
    /// Per linear axis X, Y, Z: `δx, δy, δz` (mm), `E_x, E_y, E_z` (rad) at its position.
    pub linear: [[f64; 6]; 3],
    /// `α, β1, β2` (rad).
    pub square: [f64; 3],
    /// Per rotary axis C, A: `∂X, ∂Y, ∂Z` (mm), `φ, λ, γ` (rad) at its angle.
    pub rotary: [[f64; 6]; 2],
}

/// The paper's symbols in the order of [`PaperErrors::slots`] (33 of them).
pub const SYMBOLS: [&str; 33] = [
    "δx(X)", "δy(X)", "δz(X)", "Ex(X)", "Ey(X)", "Ez(X)", //
    "δx(Y)", "δy(Y)", "δz(Y)", "Ex(Y)", "Ey(Y)", "Ez(Y)", //
    "δx(Z)", "δy(Z)", "δz(Z)", "Ex(Z)", "Ey(Z)", "Ez(Z)", //
    "α", "β1", "β2", //
    "∂X_C", "∂Y_C", "∂Z_C", "φ_C", "λ_C", "γ_C", //
    "∂X_A", "∂Y_A", "∂Z_A", "φ_A", "λ_A", "γ_A",
];

/// Whether the symbol in slot `s` of [`SYMBOLS`] is an angle (rad) rather than a length (mm).
pub fn is_angle(s: usize) -> bool {
    match s {
        0..=17 => s % 6 >= 3,
        18..=20 => true,
        _ => (s - 21) % 6 >= 3,
    }
}

impl PaperErrors {
    /// All 33 values in the order of [`SYMBOLS`].
    pub fn slots(&self) -> [f64; 33] {
        let mut out = [0.0; 33];
        for (a, row) in self.linear.iter().enumerate() {
            out[6 * a..6 * a + 6].copy_from_slice(row);
        }
        out[18..21].copy_from_slice(&self.square);
        out[21..27].copy_from_slice(&self.rotary[0]);
        out[27..33].copy_from_slice(&self.rotary[1]);
        out
    }

    /// From 33 values in the order of [`SYMBOLS`].
    pub fn from_slots(v: &[f64; 33]) -> Self {
        let mut e = Self::default();
        for a in 0..3 {
            e.linear[a].copy_from_slice(&v[6 * a..6 * a + 6]);
        }
        e.square.copy_from_slice(&v[18..21]);
        e.rotary[0].copy_from_slice(&v[21..27]);
        e.rotary[1].copy_from_slice(&v[27..33]);
        e
    }
}

/// The printed small-angle matrix of angles `(ε_x, ε_y, ε_z)`.
fn small(ex: f64, ey: f64, ez: f64) -> Matrix3<f64> {
    Matrix3::new(1.0, -ez, ey, ez, 1.0, -ex, -ey, ex, 1.0)
}

/// `M⁻¹·v`, or an error when the printed matrix is singular (angles of order one radian).
fn solve(m: &Matrix3<f64>, v: Vector3<f64>) -> Result<Vector3<f64>> {
    m.try_inverse().map(|inv| inv * v).ok_or_else(|| {
        Error::field(
            "errors",
            "the printed small-angle matrix is singular: the angles are far too large for the paper's model",
        )
    })
}

/// The deviation `ΔP = P_a − (P + P_t)` of the loop solved exactly with the printed matrices
/// (module docs). `p` the axis positions X, Y, Z and `tool` the offset `X_t, Y_t, Z_t`, mm.
pub fn loop_deviation(
    e: &PaperErrors,
    p: Vector3<f64>,
    tool: Vector3<f64>,
) -> Result<Vector3<f64>> {
    let [lx, ly, lz] = e.linear;
    let [alpha, beta1, beta2] = e.square;
    let [c, a] = e.rotary;
    let (x, y, z) = (p.x, p.y, p.z);
    let r_x = small(lx[3], lx[4], lx[5]);
    let r_y = small(ly[3], ly[4], ly[5]);
    let r_z = small(lz[3], lz[4], lz[5]);
    let r_c = small(c[3], c[4], c[5]);
    let r_a = small(a[3], a[4], a[5]);
    let t_x = Vector3::new(-x - lx[0], lx[1] - alpha * x, lx[2]);
    let t_y = Vector3::new(ly[0], y + ly[1], ly[2]);
    let t_z = Vector3::new(lz[0] - beta1 * z, lz[1] - beta2 * z, z + lz[2]);
    let t_c = -Vector3::new(c[0], c[1], c[2]);
    let t_a = -Vector3::new(a[0], a[1], a[2]);
    let right = r_y * (r_z * tool + t_z) + t_y;
    // R_x·w + T_x = right → w = R_x⁻¹(right − T_x); w = R_A·u + T_A; u = R_C·P_a + T_C.
    let w = solve(&r_x, right - t_x)?;
    let u = solve(&r_a, w - t_a)?;
    let pa = solve(&r_c, u - t_c)?;
    Ok(pa - (p + tool))
}

/// The paper's printed first-order ΔX, ΔY, ΔZ, term by term as printed.
pub fn printed(e: &PaperErrors, p: Vector3<f64>, tool: Vector3<f64>) -> Vector3<f64> {
    let [lx, ly, lz] = e.linear;
    let [alpha, beta1, beta2] = e.square;
    let [c, a] = e.rotary;
    let (x, y, z) = (p.x, p.y, p.z);
    let (xt, yt, zt) = (tool.x, tool.y, tool.z);
    // Names as printed: δ (mm), E (rad) of X, Y, Z; ∂, φ, λ, γ of C and A.
    let (dx_x, dy_x, dz_x, ex_x, ey_x, ez_x) = (lx[0], lx[1], lx[2], lx[3], lx[4], lx[5]);
    let (dx_y, dy_y, dz_y, ex_y, ey_y, ez_y) = (ly[0], ly[1], ly[2], ly[3], ly[4], ly[5]);
    let (dx_z, dy_z, dz_z, ex_z, ey_z, ez_z) = (lz[0], lz[1], lz[2], lz[3], lz[4], lz[5]);
    let (dxc, dyc, dzc, phic, lamc, gamc) = (c[0], c[1], c[2], c[3], c[4], c[5]);
    let (dxa, dya, dza, phia, lama, gama) = (a[0], a[1], a[2], a[3], a[4], a[5]);
    let dx = dx_x
        + dx_y
        + dx_z
        + dxc
        + dxa
        + y * (ez_x + gamc + gama)
        + z * (-beta1 - ey_x + ey_y - lama - lamc)
        + yt * (ez_x - ez_y - ez_z + gama + gamc)
        + zt * (-ey_x + ey_y + ey_z - lama - lamc);
    let dy = -dy_x
        + dy_y
        + dy_z
        + dyc
        + dya
        + x * (alpha - ez_x - gama - gamc)
        + z * (-beta2 + ex_x - ex_y + phia + phic)
        + xt * (-ez_x + ez_y + ez_z - gama - gamc)
        + zt * (ex_x - ex_y - ex_z + phia + phic);
    let dz = -dz_x
        + dz_y
        + dz_z
        + dzc
        + dza
        + x * (ey_x + lama + lamc)
        + y * (-ex_x - phia - phic)
        + xt * (ey_x - ey_y - ey_z + lama + lamc)
        + yt * (-ex_x + ex_y + ex_z - phia - phic);
    Vector3::new(dx, dy, dz)
}
