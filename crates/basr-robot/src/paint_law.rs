//! The film law of the robot's spray: the fan's angle, its paint rate
//! (speed × width, 001 eq. 2.6), the nozzle height that spans a width
//! (001 eq. 2.5, or a bench calibration) and the tip heights the vertical
//! joint reaches. The planner and the outline decomposition both ask the
//! robot for it ([`paint_law`]).

use serde::{Deserialize, Serialize};

use crate::{AnyRobot, Robot};

/// Standard deviation of the fan sheet's depth where it meets the road
/// (m), square to the fan's line: the preview lays the film with it
/// (`basr preview --fan-depth`'s default) and the planner holds a fan's
/// ends in by a share of it where a rung meets an edge obliquely.
// assumed: flat-fan sheets are roughly 1–2 cm thick where they meet the road
// at 0.1–0.35 m stand-off; σ = 6 mm gives a 90 %→10 % cap edge of ≈ 15 mm.
pub const SHEET_DEPTH_SIGMA_M: f64 = 0.006;

/// A paint law field out of its range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("paint law: {field} = {value} is invalid: it {why}")]
pub struct BadLaw {
    pub field: &'static str,
    pub value: f64,
    pub why: &'static str,
}

/// Nozzle height above the road as a function of stroke width.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum HeightLaw {
    /// h = (w/2)/tan(α/2): the fan's edges meet the rung's ends (001 eq. 2.5).
    Geometric,
    /// h = c0 + c1·w (m, m/m): a bench calibration of a real nozzle (001 fig. 2.25).
    Linear { c0: f64, c1: f64 },
}

/// What the spray needs from the arm: fan geometry, paint rate, height law
/// and the vertical joint's reach.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PaintLaw {
    /// Full fan angle α (63.5° in 001 App. A).
    pub fan_angle_rad: f64,
    /// speed × width (m²/s) = flow × transfer efficiency / wet film (001 eq. 2.6, SPEC §3).
    pub k_m2ps: f64,
    pub height: HeightLaw,
    /// Lowest nozzle tip height the vertical joint reaches (m above the road).
    pub min_height_m: f64,
    /// Highest nozzle tip height the vertical joint reaches (m above the road).
    pub max_height_m: f64,
}

impl PaintLaw {
    /// Untilted nozzle height that makes the fan exactly span width `w`.
    pub fn height_for_width(&self, width_m: f64) -> f64 {
        match self.height {
            HeightLaw::Geometric => 0.5 * width_m / (0.5 * self.fan_angle_rad).tan(),
            HeightLaw::Linear { c0, c1 } => c0 + c1 * width_m,
        }
    }

    /// Width of the fan's footprint at untilted height `z` (inverse of `height_for_width`).
    pub fn width_at_height(&self, height_m: f64) -> f64 {
        match self.height {
            HeightLaw::Geometric => 2.0 * height_m * (0.5 * self.fan_angle_rad).tan(),
            HeightLaw::Linear { c0, c1 } => (height_m - c0) / c1,
        }
    }

    /// Widest rung one pass can paint: the footprint at the top of the vertical joint's reach.
    pub fn max_width_m(&self) -> f64 {
        self.width_at_height(self.max_height_m)
    }

    /// Checks every field, naming the bad one.
    pub fn validate(&self) -> Result<(), BadLaw> {
        let bad =
            |field: &'static str, value: f64, why: &'static str| Err(BadLaw { field, value, why });
        let a = self.fan_angle_rad;
        if !(a.is_finite() && a > 0.0 && a < std::f64::consts::PI) {
            return bad("fan_angle_rad", a, "must lie strictly between 0 and π");
        }
        if !(self.k_m2ps.is_finite() && self.k_m2ps > 0.0) {
            return bad(
                "k_m2ps",
                self.k_m2ps,
                "must be positive (flow × efficiency / film)",
            );
        }
        if let HeightLaw::Linear { c0, c1 } = self.height {
            if !c0.is_finite() {
                return bad("height.c0", c0, "must be finite");
            }
            if !(c1.is_finite() && c1 > 0.0) {
                return bad(
                    "height.c1",
                    c1,
                    "must be positive (wider strokes need a higher nozzle)",
                );
            }
        }
        if !(self.min_height_m.is_finite() && self.min_height_m >= 0.0) {
            return bad("min_height_m", self.min_height_m, "must be ≥ 0");
        }
        if !(self.max_height_m.is_finite() && self.max_height_m > self.min_height_m) {
            return bad(
                "max_height_m",
                self.max_height_m,
                "must exceed min_height_m",
            );
        }
        if self.max_width_m().is_nan() || self.max_width_m() <= 0.0 {
            return bad(
                "max_height_m",
                self.max_height_m,
                "the height law paints no width at this height",
            );
        }
        Ok(())
    }
}

/// The paint law of the robot's nozzle and its painting heights: BASR's
/// from its vertical joint (`basr_paint_law`), an electric kind's the tip
/// heights of its description (its IK places the tip itself, tilted or not).
pub fn paint_law(robot: &AnyRobot) -> PaintLaw {
    if let Some(b) = robot.basr() {
        return basr_paint_law(b);
    }
    let p = robot.paint();
    let [lo, hi] = robot.tip_heights_m();
    PaintLaw {
        fan_angle_rad: p.fan_angle_rad,
        k_m2ps: p.k_m2ps(),
        height: height_law(p),
        min_height_m: lo,
        max_height_m: hi,
    }
}

fn height_law(p: &crate::Paint) -> HeightLaw {
    match (p.height_law_c0_m, p.height_law_c1) {
        (Some(c0), Some(c1)) => HeightLaw::Linear { c0, c1 },
        _ => HeightLaw::Geometric,
    }
}

/// BASR's paint law from its nozzle and vertical joint. The reachable tip
/// heights leave room for the tilt's vertical tip offset at any tilt.
pub fn basr_paint_law(robot: &Robot) -> PaintLaw {
    let p = &robot.paint;
    let top = robot.end_effector.tip_height_top_m;
    let v = &robot.limits.vertical_m;
    let t = &robot.limits.tilt_rad;
    // IK: vertical = top + rise(β) − z. A tip that sinks when tilted needs
    // room at the top of the stroke for every tilt; one that rises is
    // handled per knot (`lift_for_tilt`).
    let mut sink: f64 = 0.0;
    for k in 0..=40 {
        let b = t.min + (t.max - t.min) * k as f64 / 40.0;
        let off = robot.tilt_tip_offset(b);
        if off[1].is_finite() {
            sink = sink.max(-off[1]);
        }
    }
    PaintLaw {
        fan_angle_rad: p.fan_angle_rad,
        k_m2ps: p.k_m2ps(),
        height: height_law(p),
        min_height_m: top - v.max,
        max_height_m: top - v.min - sink,
    }
}
