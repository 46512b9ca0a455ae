//! What a measured trace shows by itself, without the model: the dent's depth and width read
//! off the trace, and the fitted friction in the terms a drive takes (a share of its rated
//! torque, the torque step of a compensator).
//!
//! # The dent of a measured trace ([`measure_dent`])
//! Trace angle `θ` in this study's convention (C reverses at `θ = 180°`), radial deviation
//! `d(θ)` in mm, + outwards:
//!
//! * **Baseline** `b`: the median of `d` over the points with `170° ≤ θ ≤ 179°`, the trace's
//!   level just *before* the reversal (nothing of the reversal has reached the circle there at
//!   the paper's feeds; the median ignores noise spikes).
//! * **Fall** `g(θ) = b − d(θ)`: how far the trace lies inside its level before the reversal
//!   (mm, positive inwards).
//! * **Depth** `D`: the largest fall over the points with `180° ≤ θ ≤ 190°`, and its angle `θ*`
//!   (the first point when several tie). The trace is not smoothed: measurement noise adds up to
//!   its own peak to `D`.
//! * **Width** `W`: the span of trace angle around `θ*` over which the fall is at least `D/2`:
//!   from `θ*` the run of consecutive points with `g ≥ D/2` (among those with
//!   `170° ≤ θ ≤ 190°`), each end placed where `g` crosses `D/2` by linear interpolation
//!   between the last point inside and the first point outside (an end that reaches the
//!   window's edge stays at its last point). In time, `W·R/F` (the tool
//!   runs round the circle of radius `R` at the feed `F`).
//! * **Level after** `b₂`: the median of `d` over `188° ≤ θ ≤ 190°`; the **step**
//!   `S = b − b₂` is how far the trace stays down after the reversal (without feed-forward C's
//!   following error changes side when C reverses, which moves the circle by a step; friction
//!   adds the dent).
//!
//! Degenerate cases: fewer than 3 points in `[170°, 179°]`, in `[180°, 190°]` or in
//! `[188°, 190°]` is an error (field `csv`). A trace that never falls below its baseline
//! (`D ≤ 0`) has no dent: depth 0, width 0. When the fall stays at `D/2` or more up to the last
//! point of the window (190°), the dent has not ended there (`open`): the trace went down by a
//! step rather than a dent, and `W` is the span up to that point, a lower bound.
//!
//! Depth and width are what the trace shows, servo lag and friction together: the simulation's
//! dent ([`super::dent`], the difference of runs with and without friction) separates them,
//! and agrees with this depth when the drives follow without lag (both feed-forwards).
//!
//! # The friction for a drive ([`compensation`])
//! Eq 2, `f = f_c·(2·tanh(a·|x′|) − 1)·sgn(dx′/dt)`, is Coulomb friction `f_c·sgn(ẋ)` far from a
//! reversal (`a·|x′| ≫ 1`). Just before a reversal the friction torque is `+f_c` against the
//! old direction; right after it eq 2 still gives `f_c·(0 − 1)·sgn(new) = +f_c·sgn(old)` (the
//! spring is loaded), and once the table has turned `a·|x′| ≫ 1` it is `f_c·sgn(new) =
//! −f_c·sgn(old)`. The torque the motor must add to cancel it therefore changes by
//! `Δτ = 2·f_c` at each reversal: the torque step a friction compensator injects when the
//! commanded velocity changes sign, built up over the travel in which eq 2's spring turns (half
//! way at `atanh(½)/a`). Both are also given as shares of the drive's rated (continuous)
//! torque `T_r`, the unit drives take a friction compensation in: `f_c/T_r` and `2·f_c/T_r`.

use crate::error::{Error, Result};

/// Trace angles of the windows (degrees): the baseline, the dent, the level after.
const BEFORE: (f64, f64) = (170.0, 179.0);
const AFTER: (f64, f64) = (180.0, 190.0);
const SETTLED: (f64, f64) = (188.0, 190.0);
/// Fewest points in each window.
const MIN_POINTS: usize = 3;

/// The dent of a measured trace (module docs). Lengths in mm, angles in degrees at the edge
/// (radians in Rust).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct MeasuredDent {
    /// Baseline `b`: median deviation over 170°–179°, mm.
    pub baseline: f64,
    /// Depth `D`: the largest fall below the baseline over 180°–190°, mm (0: no dent).
    pub depth: f64,
    /// Its trace angle `θ*`, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub angle: f64,
    /// Width at half depth `W`, degrees of trace angle (radians in Rust; 0 without a dent; a
    /// lower bound when `open`).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub width: f64,
    /// Where the fall crosses half depth before `θ*`, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub low: f64,
    /// And after it (the last point of the window when `open`), degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub high: f64,
    /// The fall is still at half depth or more at the window's end (190°): `width` is a lower
    /// bound and the trace went down by a step.
    pub open: bool,
    /// Level after `b₂`: median deviation over 188°–190°, mm.
    pub level_after: f64,
    /// Step `S = b − b₂`, mm (positive: the trace stays inside after the reversal).
    pub step: f64,
}

impl MeasuredDent {
    /// The width as a time, s: `W·R/F` with the circle's radius `radius` (mm) and the feed
    /// `feed` (mm/min).
    pub fn duration(&self, radius: f64, feed: f64) -> f64 {
        self.width * radius / (feed / 60.0)
    }
}

/// The median of `v` (not empty).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// Measures the dent of a trace: `angle` (rad, increasing) and `deviation` (mm), as
/// [`super::fit::parse_trace`] reads them (module docs).
pub fn measure_dent(angle: &[f64], deviation: &[f64]) -> Result<MeasuredDent> {
    let inside = |w: (f64, f64)| {
        let (lo, hi) = (w.0.to_radians(), w.1.to_radians());
        move |a: f64| a >= lo && a <= hi
    };
    let window = |w: (f64, f64), what: &str| -> Result<Vec<f64>> {
        let v: Vec<f64> = angle
            .iter()
            .zip(deviation)
            .filter(|(a, _)| inside(w)(**a))
            .map(|(_, d)| *d)
            .collect();
        if v.len() < MIN_POINTS {
            return Err(Error::field(
                "csv",
                format!(
                    "{} points from {}° to {}° of trace angle ({what}): the dent's measurement needs at least {MIN_POINTS}",
                    v.len(),
                    w.0,
                    w.1
                ),
            ));
        }
        Ok(v)
    };
    let baseline = median(window(BEFORE, "the level before the reversal")?);
    window(AFTER, "just after the reversal")?;
    let level_after = median(window(SETTLED, "the level after the reversal")?);
    // The points of 170°–190°, their fall below the baseline.
    let span = inside((BEFORE.0, AFTER.1));
    let idx: Vec<usize> = (0..angle.len()).filter(|&i| span(angle[i])).collect();
    let th: Vec<f64> = idx.iter().map(|&i| angle[i]).collect();
    let g: Vec<f64> = idx.iter().map(|&i| baseline - deviation[i]).collect();
    let after = inside(AFTER);
    let mut k = None;
    for (j, (t, v)) in th.iter().zip(&g).enumerate() {
        if after(*t) && k.map_or(true, |m: usize| *v > g[m]) {
            k = Some(j);
        }
    }
    // `window(AFTER, …)` found points there.
    let k = k.unwrap_or(0);
    let depth = g[k];
    let step = baseline - level_after;
    if depth <= 0.0 {
        return Ok(MeasuredDent {
            baseline,
            depth: 0.0,
            angle: th[k],
            width: 0.0,
            low: th[k],
            high: th[k],
            open: false,
            level_after,
            step,
        });
    }
    let half = depth / 2.0;
    let cross = |i: usize, o: usize| th[i] + (half - g[i]) / (g[o] - g[i]) * (th[o] - th[i]);
    let mut i = k;
    while i > 0 && g[i - 1] >= half {
        i -= 1;
    }
    let low = if i > 0 { cross(i, i - 1) } else { th[0] };
    let mut j = k;
    while j + 1 < g.len() && g[j + 1] >= half {
        j += 1;
    }
    let open = j + 1 == g.len();
    let high = if open { th[j] } else { cross(j, j + 1) };
    Ok(MeasuredDent {
        baseline,
        depth,
        angle: th[k],
        width: high - low,
        low,
        high,
        open,
        level_after,
        step,
    })
}

/// The fitted friction in a drive's terms (module docs), N·m and shares of the rated torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compensation {
    /// The drive's rated torque `T_r`, N·m.
    pub rated: f64,
    /// `f_c / T_r`.
    pub friction_share: f64,
    /// The compensator's torque step at each reversal, `2·f_c`, N·m.
    pub step: f64,
    /// `2·f_c / T_r`.
    pub step_share: f64,
}

/// The friction `fc` (N·m) for a drive of rated torque `rated` (N·m, > 0): its share of the
/// rated torque and the compensator's torque step `2·f_c` (module docs).
pub fn compensation(fc: f64, rated: f64) -> Compensation {
    Compensation {
        rated,
        friction_share: fc / rated,
        step: 2.0 * fc,
        step_share: 2.0 * fc / rated,
    }
}
