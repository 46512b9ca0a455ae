//! The simulated machined face (like Fig 16(b)): ball-end zig-zag passes, scallops included,
//! on a grid over the face (module docs of [`super`]).

use super::zones::Test;
use super::{CubicGrid, CubicPiece, CubicReference, Options};
use crate::error::{Error, Result};
use crate::machine::Machine;
use nalgebra::Vector3;
use serde::Serialize;

/// The simulated machined face (like Fig 16(b)): a height field of the ball-end zig-zag
/// (`cubicHeightMap`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct HeightMap {
    /// Grid points along X (u, columns).
    pub nx: usize,
    /// Grid points along Y (v, rows).
    pub ny: usize,
    /// X of the grid columns, mm: `nx` equal steps from `−1.5·zoneSize` to `+1.5·zoneSize`.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub x: Vec<f64>,
    /// Y of the grid rows, mm, likewise.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub y: Vec<f64>,
    /// Heights, mm, row-major `ny × nx`: the point `(x[ix], y[iy])` is `[iy·nx + ix]`.
    /// Scallops included.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub height: Vec<f64>,
    /// Average height over each zone (Table 1 order, that of `cubicTest`'s zones), mm: the
    /// trapezoidal rule on the grid (a point on a zone border counts half for each zone).
    /// Includes the mean scallop height.
    pub zone_average: Vec<f64>,
    /// The zones in the same order, with their nominal centres on the face.
    pub zones: Vec<ZoneAt>,
    /// Smallest height, mm.
    pub min: f64,
    /// Largest height, mm.
    pub max: f64,
    /// The actual step between passes (≤ pick), mm (see [`CubicPiece::pick`]).
    pub step: f64,
    /// Closed-form scallop height for that step, `r − √(r² − (step/2)²)`, mm.
    pub scallop: f64,
    /// Passes simulated (all zones).
    pub passes: usize,
    /// Pass-point evaluations made (a measure of the work).
    pub evaluations: usize,
}

/// A zone's name and nominal centre on the face.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct ZoneAt {
    /// Its name.
    pub name: &'static str,
    /// Centre along u, mm.
    pub x: f64,
    /// Along v, mm.
    pub y: f64,
}

/// Most grid points of a height map.
pub const MAX_GRID_POINTS: usize = 4_000_000;
/// Most grid points along one side of a height map.
pub const MAX_GRID_SIDE: usize = 4001;

/// One pass: the segment of actual ball centres.
struct Pass {
    a: Vector3<f64>,
    /// Unit direction from `a` to the other end.
    e: Vector3<f64>,
    len: f64,
    zmin: f64,
}

impl Pass {
    fn new(a: Vector3<f64>, b: Vector3<f64>) -> Self {
        let d = b - a;
        let len = d.norm();
        Self {
            a,
            e: if len > 0.0 { d / len } else { Vector3::x() },
            len,
            zmin: a.z.min(b.z),
        }
    }

    /// Lowest point of the swept ball (a capsule of radius `r` around the segment) above
    /// `(x, y)`, or +∞ where it does not reach. The cylinder part: the lower root `t = z − a_z`
    /// of `|v|² − (v·e)² = r²`, `v = (x − a_x, y − a_y, t)`, valid where the foot `v·e` lies on
    /// the segment; the two end spheres otherwise.
    fn bottom(&self, x: f64, y: f64, r: f64) -> f64 {
        let (dx, dy) = (x - self.a.x, y - self.a.y);
        let r2 = r * r;
        let sphere = |cx: f64, cy: f64, cz: f64| {
            let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if d2 <= r2 {
                cz - (r2 - d2).sqrt()
            } else {
                f64::INFINITY
            }
        };
        let b = self.a + self.e * self.len;
        let mut best = sphere(self.a.x, self.a.y, self.a.z).min(sphere(b.x, b.y, b.z));
        let ve = dx * self.e.x + dy * self.e.y;
        let qa = 1.0 - self.e.z * self.e.z;
        if qa > 1e-12 {
            let qb = -self.e.z * ve;
            let qc = dx * dx + dy * dy - ve * ve - r2;
            let disc = qb * qb - qa * qc;
            if disc >= 0.0 {
                let t = (-qb - disc.sqrt()) / qa;
                let s = ve + t * self.e.z;
                if (0.0..=self.len).contains(&s) {
                    best = best.min(self.a.z + t);
                }
            }
        }
        best
    }
}

/// A regular grid of points over the face.
struct Face {
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
}

impl Face {
    /// Index range of the coordinates `v` within `[lo, hi]` (sorted, equally spaced).
    fn span(v: &[f64], lo: f64, hi: f64) -> std::ops::Range<usize> {
        let n = v.len();
        let (v0, dv) = (v[0], v[1] - v[0]);
        let i0 = ((lo - v0) / dv).ceil().max(0.0);
        let i1 = ((hi - v0) / dv).floor() + 1.0;
        let i0 = if i0.is_finite() { i0 as usize } else { n };
        let i1 = if i1.is_finite() && i1 > 0.0 {
            (i1 as usize).min(n)
        } else {
            0
        };
        i0.min(i1)..i1
    }

    /// Lowers the grid to the pass wherever it cuts deeper, within `w` of the pass (horizontally).
    fn cut(&mut self, p: &Pass, w: f64, r: f64) -> usize {
        let b = p.a + p.e * p.len;
        let xs = Self::span(&self.x, p.a.x.min(b.x) - w, p.a.x.max(b.x) + w);
        let ys = Self::span(&self.y, p.a.y.min(b.y) - w, p.a.y.max(b.y) + w);
        let nx = self.x.len();
        let mut n = 0;
        for iy in ys {
            let y = self.y[iy];
            for ix in xs.clone() {
                let z = p.bottom(self.x[ix], y, r);
                let h = &mut self.h[iy * nx + ix];
                if z < *h {
                    *h = z;
                }
                n += 1;
            }
        }
        n
    }
}

/// The rows of the automatic grid: four per pass step, aligned with the passes (the face starts
/// on a pass), so that whole scallop periods can be averaged without aliasing; at most
/// [`MAX_GRID_SIDE`] and `MAX_GRID_POINTS / nx`.
pub fn auto_rows(setup: &CubicPiece, nx: usize) -> usize {
    let rows = 12 * (setup.passes_per_zone() - 1) + 1;
    rows.min(MAX_GRID_SIDE)
        .min(MAX_GRID_POINTS / nx.max(1))
        .max(4)
}

/// Simulates the machined face on an `nx × ny` grid (module docs; like Fig 16(b)); `ny` left out
/// is `auto_rows` (four rows per pass step).
///
/// Every zone is cut by its zig-zag passes along the face's first axis ([`CubicPiece::pick`]); a pass is the
/// segment between the actual tool centres (from the chain, eqs 1 and 14) of its two end points,
/// and the ball swept along it removes everything above its lower surface. The face is the
/// lowest of all passes and the stock, whatever the order of cutting. Only passes near a grid
/// point can reach it: a first sweep within one pick of each pass gives an upper bound `M` of
/// the face; a pass whose centres are at least `zmin` high cannot cut below `M` farther than
/// `√(r² − (zmin − M)²)` from its line, so the second, exact sweep stops there.
///
/// Heights are in the frame and reference of `options`: [`CubicReference::ZoneIHeight`] subtracts
/// the average, [`CubicReference::ZoneIPlane`] the least-squares plane, of ZONE I's central square
/// (inset from its borders by `r`, at most a quarter of the zone side), which the balls of the
/// neighbouring zones do not reach (they would bias the reference by up to a few per cent of
/// the height differences).
pub fn height_map(
    machine: &Machine,
    setup: &CubicPiece,
    options: &Options,
    grid: &CubicGrid,
) -> Result<HeightMap> {
    setup.validate()?;
    let nx = grid.nx;
    let ny = grid.ny.unwrap_or_else(|| auto_rows(setup, nx));
    if !(4..=MAX_GRID_SIDE).contains(&nx) || !(4..=MAX_GRID_SIDE).contains(&ny) {
        return Err(Error::field(
            "ny",
            format!("nx and ny must be between 4 and {MAX_GRID_SIDE}, got {nx} and {ny}"),
        ));
    }
    if nx * ny > MAX_GRID_POINTS {
        return Err(Error::field(
            "nx",
            format!("nx·ny must be at most {MAX_GRID_POINTS}, got {}", nx * ny),
        ));
    }
    let test = Test::new(machine, setup, options)?;
    let z = setup.zone_size;
    let r = setup.tool_radius;
    let step = setup.step();
    let half = 0.5 * z;

    let mut passes = Vec::with_capacity(9 * setup.passes_per_zone());
    for zone in &test.zones {
        let (xc, yc) = zone.centre;
        // Each pass runs between the actual tool centres (from the chain) of its two ends.
        for k in 0..setup.passes_per_zone() {
            let y = yc - half + k as f64 * step;
            let a = test.centre(zone, xc - half, y)?;
            let b = test.centre(zone, xc + half, y)?;
            passes.push(Pass::new(a, b));
        }
    }

    let lin = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| -1.5 * z + 3.0 * z * i as f64 / (n - 1) as f64)
            .collect()
    };
    let mut grid = Face {
        x: lin(nx),
        y: lin(ny),
        h: vec![setup.stock; nx * ny],
    };
    let mut evaluations = 0;
    for p in &passes {
        evaluations += grid.cut(p, step, r);
    }
    let bound = grid.h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    for p in &passes {
        let gap = p.zmin - bound;
        if gap >= r {
            continue;
        }
        let w = if gap > 0.0 {
            (r * r - gap * gap).sqrt()
        } else {
            r
        };
        evaluations += grid.cut(p, w * (1.0 + 1e-12) + 1e-12, r);
    }

    // Zone averages (trapezoidal weights: a point on a zone border counts half), then the
    // reference, taken on ZONE I's central square (inset by r, at most a quarter of the zone
    // side) where no pass of another zone reaches unless the errors move zones sideways.
    let weights = |v: &[f64], c: f64, half: f64| -> Vec<(usize, f64)> {
        let tol = 1e-9 * z;
        v.iter()
            .enumerate()
            .filter_map(|(i, &t)| {
                let d = (t - c).abs();
                if d < half - tol {
                    Some((i, 1.0))
                } else if d <= half + tol {
                    Some((i, 0.5))
                } else {
                    None
                }
            })
            .collect()
    };
    let square = |(xc, yc): (f64, f64), half: f64| -> Vec<(usize, f64)> {
        let wx = weights(&grid.x, xc, half);
        weights(&grid.y, yc, half)
            .into_iter()
            .flat_map(|(iy, wy)| wx.iter().map(move |&(ix, w)| (iy * nx + ix, w * wy)))
            .collect()
    };
    let members: Vec<Vec<(usize, f64)>> = test
        .zones
        .iter()
        .map(|zone| square(zone.centre, half))
        .collect();
    let reference_area = {
        let inner = square(test.zones[0].centre, half - r.min(0.25 * z));
        if inner.is_empty() {
            members[0].clone()
        } else {
            inner
        }
    };
    let mean = |h: &[f64], idx: &[(usize, f64)]| -> f64 {
        let w: f64 = idx.iter().map(|p| p.1).sum();
        idx.iter().map(|&(i, wi)| wi * h[i]).sum::<f64>() / w
    };
    match options.reference {
        CubicReference::Workpiece => {}
        CubicReference::ZoneIHeight => {
            let m = mean(&grid.h, &reference_area);
            grid.h.iter_mut().for_each(|h| *h -= m);
        }
        CubicReference::ZoneIPlane => {
            // Weighted least squares over ZONE I's central points: on a rectangular grid the
            // centred x and y are orthogonal, so each slope is a one-dimensional regression.
            let idx = &reference_area;
            let w: f64 = idx.iter().map(|p| p.1).sum();
            let m = mean(&grid.h, idx);
            let xm = idx.iter().map(|&(i, wi)| wi * grid.x[i % nx]).sum::<f64>() / w;
            let ym = idx.iter().map(|&(i, wi)| wi * grid.y[i / nx]).sum::<f64>() / w;
            let (mut sxz, mut sxx, mut syz, mut syy) = (0.0, 0.0, 0.0, 0.0);
            for &(i, wi) in idx {
                let (dx, dy, dz) = (grid.x[i % nx] - xm, grid.y[i / nx] - ym, grid.h[i] - m);
                sxz += wi * dx * dz;
                sxx += wi * dx * dx;
                syz += wi * dy * dz;
                syy += wi * dy * dy;
            }
            let sx = if sxx > 0.0 { sxz / sxx } else { 0.0 };
            let sy = if syy > 0.0 { syz / syy } else { 0.0 };
            for iy in 0..ny {
                for ix in 0..nx {
                    grid.h[iy * nx + ix] -= m + sx * (grid.x[ix] - xm) + sy * (grid.y[iy] - ym);
                }
            }
        }
    }
    let zone_average = members.iter().map(|idx| mean(&grid.h, idx)).collect();
    let zones = super::ZONES
        .iter()
        .map(|zd| ZoneAt {
            name: zd.name,
            x: f64::from(zd.col) * z,
            y: f64::from(zd.row) * z,
        })
        .collect();
    let min = grid.h.iter().copied().fold(f64::INFINITY, f64::min);
    let max = grid.h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok(HeightMap {
        nx,
        ny,
        x: grid.x,
        y: grid.y,
        height: grid.h,
        zone_average,
        zones,
        min,
        max,
        step,
        scallop: r - (r * r - 0.25 * step * step).sqrt(),
        passes: passes.len(),
        evaluations,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    //! The private pieces of the simulation against their definitions: the swept ball's lower
    //! surface against the lowest of many balls along the segment, the index range against a
    //! scan of the coordinates, the cut against both.
    use super::*;

    /// The swept ball's lowest point above `(x, y)` by brute force: the lowest of the balls
    /// centred at `n + 1` equally spaced points of the segment (+∞ where none reaches).
    fn lowest_ball(a: Vector3<f64>, b: Vector3<f64>, x: f64, y: f64, r: f64, n: usize) -> f64 {
        let mut lowest = f64::INFINITY;
        for i in 0..=n {
            let s = i as f64 / n as f64;
            let (cx, cy, cz) = (
                a.x + (b.x - a.x) * s,
                a.y + (b.y - a.y) * s,
                a.z + (b.z - a.z) * s,
            );
            let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if d2 <= r * r {
                lowest = lowest.min(cz - (r * r - d2).sqrt());
            }
        }
        lowest
    }

    #[test]
    fn a_pass_cuts_as_deep_as_the_lowest_ball_along_it() {
        let r = 3.0;
        // Level, rising along X, diagonal and steep, nearly vertical, and a point.
        let segments = [
            (Vector3::new(-8.0, 0.5, 2.0), Vector3::new(8.0, 0.5, 2.0)),
            (Vector3::new(-8.0, 0.0, 1.0), Vector3::new(8.0, 0.0, 3.0)),
            (Vector3::new(-5.0, -4.0, 4.0), Vector3::new(6.0, 3.0, -2.0)),
            (Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.5, 0.2, 9.0)),
            (Vector3::new(1.0, 1.0, 1.0), Vector3::new(1.0, 1.0, 1.0)),
        ];
        for (a, b) in segments {
            let p = Pass::new(a, b);
            for i in 0..=12 {
                for j in 0..=8 {
                    let (x, y) = (-12.0 + 2.0 * i as f64, -8.0 + 2.0 * j as f64);
                    let want = lowest_ball(a, b, x, y, r, 20_000);
                    let got = p.bottom(x, y, r);
                    if want.is_infinite() {
                        assert!(got.is_infinite(), "{a} {b} ({x}, {y}): {got}");
                    } else {
                        // The sampled lowest is never below the true one, and above it by at
                        // most the height change over half a sample step (< 1 µm here).
                        assert!(
                            got <= want + 1e-12 && got >= want - 1e-3,
                            "{a} {b} ({x}, {y}): {got} vs {want}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_span_is_every_index_whose_coordinate_lies_in_the_closed_interval() {
        let v: Vec<f64> = (0..11).map(|i| -5.0 + i as f64).collect();
        let scan = |lo: f64, hi: f64| -> Vec<usize> {
            (0..v.len()).filter(|&i| lo <= v[i] && v[i] <= hi).collect()
        };
        for (lo, hi) in [
            (-2.5, 1.5),
            (-2.0, 1.0),
            (-9.0, -3.0),
            (3.0, 9.0),
            (-9.0, 9.0),
            (-9.0, -6.0),
            (6.0, 9.0),
            (-9.0, -5.0),
            (5.0, 9.0),
            (0.2, 0.8),
            (2.0, 2.0),
            (1.0, -1.0),
        ] {
            let got: Vec<usize> = Face::span(&v, lo, hi).collect();
            assert_eq!(got, scan(lo, hi), "[{lo}, {hi}]");
        }
    }

    #[test]
    fn a_cut_lowers_the_grid_near_the_pass_to_the_ball_and_counts_the_points_it_tried() {
        let (r, w) = (3.0, 1.5);
        let (a, b) = (Vector3::new(-4.0, 0.5, 0.5), Vector3::new(4.0, 1.0, 1.5));
        let p = Pass::new(a, b);
        let x: Vec<f64> = (0..41).map(|i| -10.0 + 0.5 * i as f64).collect();
        let y: Vec<f64> = (0..21).map(|i| -5.0 + 0.5 * i as f64).collect();
        let stock = 1.0;
        let mut face = Face {
            x: x.clone(),
            y: y.clone(),
            h: vec![stock; x.len() * y.len()],
        };
        let n = face.cut(&p, w, r);
        // Within w of the segment's extent along X and Y: x in [−5.5, 5.5] (23 points), y in
        // [−1, 2.5] (8 points).
        assert_eq!(n, 23 * 8);
        let mut lowered = 0;
        for (iy, &yy) in y.iter().enumerate() {
            for (ix, &xx) in x.iter().enumerate() {
                let h = face.h[iy * x.len() + ix];
                let near = (-5.5..=5.5).contains(&xx) && (-1.0..=2.5).contains(&yy);
                let want = if near {
                    stock.min(p.bottom(xx, yy, r))
                } else {
                    stock
                };
                assert_eq!(h, want, "({xx}, {yy})");
                lowered += usize::from(h < stock);
            }
        }
        assert!(lowered > 20, "{lowered}");
    }

    fn piece(zone: f64, pick: f64) -> CubicPiece {
        use crate::schema::Inputs;
        CubicPiece::from_value(&serde_json::json!({ "zoneSize": zone, "pick": pick }), "").unwrap()
    }

    #[test]
    fn the_automatic_grid_has_four_rows_per_pass_step_within_the_limits() {
        // Three zones of 16 mm with passes every 2 mm: 48 mm in steps of 0.5 mm, 97 rows.
        assert_eq!(auto_rows(&piece(16.0, 2.0), 193), 97);
        // A pick that does not divide the zone: ⌈20/3⌉ = 7 steps of 20/7 mm, 84 + 1 rows.
        assert_eq!(auto_rows(&piece(20.0, 3.0), 193), 85);
        // One step per zone (pick = zone): 12 + 1 rows.
        assert_eq!(auto_rows(&piece(16.0, 16.0), 4), 13);
        // 2000 steps per zone would need 24 001 rows: at most 4001 …
        assert_eq!(auto_rows(&piece(200.0, 0.1), 500), MAX_GRID_SIDE);
        // … and at most 4 000 000 points in all: 4000 rows of 1000, 2000 of 2000.
        assert_eq!(auto_rows(&piece(200.0, 0.1), 1000), 4000);
        assert_eq!(auto_rows(&piece(200.0, 0.1), 2000), 2000);
    }

    #[test]
    fn the_face_is_the_lowest_of_every_pass_and_the_stock() {
        // Module docs: the face is the lowest of all passes and the stock, whatever the order;
        // the two sweeps only skip passes that cannot reach. Here against every pass at every
        // grid point. A 10 mm ball with 1 mm steps and errors large enough (0.3 mm, 0.3°) that
        // neighbouring zones differ by more than 0.05 mm: then some points are cut lowest by a
        // pass of the lower zone more than a step away, which only the second sweep tries.
        use crate::machine::Machine;
        use crate::schema::Inputs;
        let m = Machine::from_value(
            &serde_json::json!({
                "kind": "table-table", "type": "CAZ", "linear": "table-xy",
                "geometry": { "tableHeight": 65, "toolLength": 120 },
                "rotary": { "mFrom": -120, "mTo": 30 },
                "errors": { "E_Y0A": 0.3, "E_B0A": 0.3, "E_A0C": -0.2, "E_Z0C": 0.04 }
            }),
            "machine",
        )
        .unwrap();
        let setup = CubicPiece::from_value(&serde_json::json!({ "pick": 1, "toolRadius": 10 }), "")
            .unwrap();
        let options = Options {
            transform: false,
            reference: CubicReference::Workpiece,
        };
        let grid = CubicGrid::from_value(&serde_json::json!({ "nx": 61, "ny": 49 }), "").unwrap();
        let map = height_map(&m, &setup, &options, &grid).unwrap();
        let test = Test::new(&m, &setup, &options).unwrap();
        let (half, step, r) = (0.5 * setup.zone_size, setup.step(), setup.tool_radius);
        let mut passes = Vec::new();
        for zone in &test.zones {
            let (xc, yc) = zone.centre;
            for k in 0..setup.passes_per_zone() {
                let y = yc - half + k as f64 * step;
                let a = test.centre(zone, xc - half, y).unwrap();
                let b = test.centre(zone, xc + half, y).unwrap();
                passes.push((a, b, Pass::new(a, b)));
            }
        }
        assert_eq!(map.passes, passes.len());
        let mut far = 0;
        for (iy, &y) in map.y.iter().enumerate() {
            for (ix, &x) in map.x.iter().enumerate() {
                let (mut lowest, mut by) = (setup.stock, None);
                for (a, b, p) in &passes {
                    let z = p.bottom(x, y, r);
                    if z < lowest {
                        (lowest, by) = (z, Some((a, b)));
                    }
                }
                assert_eq!(map.height[iy * map.nx + ix], lowest, "({x}, {y})");
                if let Some((a, b)) = by {
                    let dx = (a.x.min(b.x) - x).max(x - a.x.max(b.x)).max(0.0);
                    let dy = (a.y.min(b.y) - y).max(y - a.y.max(b.y)).max(0.0);
                    far += usize::from(dx > step || dy > step);
                }
            }
        }
        assert!(
            far > 0,
            "no point is cut lowest by a pass more than a step away"
        );
        // The work, as the docs describe the two sweeps: every pass tries the grid points within
        // one step of its extent; then, with M the highest point of the face after that first
        // sweep (an upper bound of the final face), a pass whose
        // centres are `gap = zmin − M` above it and gap < r tries those within its reach
        // √(r² − gap²) (r where gap ≤ 0), widened by a hair (10⁻¹² relative and absolute) for
        // rounding.
        let tried = |p: &Pass, w: f64| {
            let b = p.a + p.e * p.len;
            let xs = Face::span(&map.x, p.a.x.min(b.x) - w, p.a.x.max(b.x) + w);
            let ys = Face::span(&map.y, p.a.y.min(b.y) - w, p.a.y.max(b.y) + w);
            xs.len() * ys.len()
        };
        let mut first = Face {
            x: map.x.clone(),
            y: map.y.clone(),
            h: vec![setup.stock; map.nx * map.ny],
        };
        for (_, _, p) in &passes {
            first.cut(p, step, r);
        }
        let top = first.h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(top > map.height.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        let mut work = 0;
        for (_, _, p) in &passes {
            work += tried(p, step);
            let gap = p.zmin - top;
            if gap < r {
                let reach = (r * r - gap.max(0.0).powi(2)).sqrt();
                work += tried(p, reach * (1.0 + 1e-12) + 1e-12);
            }
        }
        assert_eq!(map.evaluations, work);
        assert!(work > map.nx * map.ny);
    }
}
