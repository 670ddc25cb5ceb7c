//! What a simulation run found: tracking error of the nozzle in the road plane
//! (overall, while painting, per stroke), waviness, saturation, peak
//! pressures, limits violated, and the verdict against the tolerance.

use serde::{Deserialize, Serialize};

/// Where something happened.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Place {
    pub t_s: f64,
    /// Stroke index (−1 in an air move).
    pub stroke: i64,
    pub station: u32,
    /// Desired nozzle point in the road frame.
    pub x_m: f64,
    pub y_m: f64,
}

impl Place {
    /// `t = 12.345 s, stroke 3, road (0.120, 1.832) m`, or `air move` for
    /// the stroke outside strokes.
    pub fn describe(&self) -> String {
        format!(
            "t = {:.3} s, {}, road ({:.3}, {:.3}) m",
            self.t_s,
            self.stroke_name(),
            self.x_m,
            self.y_m
        )
    }

    /// `stroke 3`, or `air move`.
    pub fn stroke_name(&self) -> String {
        if self.stroke < 0 {
            "air move".into()
        } else {
            format!("stroke {}", self.stroke)
        }
    }
}

/// The unit a limit's values are printed in (they are stored in SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unit {
    /// An angle: rad and degrees.
    Angle,
    /// A length: mm.
    Length,
    /// A pressure: MPa.
    Pressure,
}

impl Unit {
    /// `value` (SI) with its unit.
    pub fn show(self, value: f64) -> String {
        match self {
            Unit::Angle => format!("{value:.4} rad ({:.2}°)", value.to_degrees()),
            Unit::Length => format!("{:.2} mm", value * 1e3),
            Unit::Pressure => format!("{:.2} MPa", value / 1e6),
        }
    }
}

/// Error statistics of one stroke.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrokeError {
    pub stroke: i64,
    pub max_error_m: f64,
    pub rms_error_m: f64,
    pub worst: Place,
}

/// Error above the path's own frequency content.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Waviness {
    /// High-pass cut-off (Hz): 4× the 95th percentile of the path's turning
    /// rate, kept within 0.5–5 Hz.
    pub cutoff_hz: f64,
    pub max_m: f64,
    pub rms_m: f64,
}

/// Time (s) each actuator spent at a limit.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Saturation {
    pub motor_valve_s: f64,
    pub cylinder_valve_s: f64,
    pub yaw_s: f64,
    pub tilt_s: f64,
    pub vertical_s: f64,
}

/// Highest chamber pressures (Pa).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PeakPressures {
    pub motor_a_pa: f64,
    pub motor_b_pa: f64,
    pub cylinder_a_pa: f64,
    pub cylinder_b_pa: f64,
}

/// Worst tracking error of each end-effector axis.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct AxisErrors {
    pub yaw_rad: f64,
    pub tilt_nut_m: f64,
    pub vertical_m: f64,
}

/// One limit the run went past.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LimitViolation {
    /// Short machine name, e.g. `base_rot_window` (one of the simulator's
    /// fixed set of limits).
    pub kind: &'static str,
    /// Whether it fails the verdict (a relief valve opening is only noted).
    pub fails: bool,
    pub first: Place,
    pub duration_s: f64,
    /// Worst value reached and the limit it passed (SI units of the axis).
    pub worst_value: f64,
    pub limit: f64,
    pub message: String,
}

/// The simulator's verdict on a job: `"pass"` or `"fail"` in
/// `basr simulate --json`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Within the tolerance, no limit broken.
    Pass,
    /// Why is in the report's `reasons`.
    Fail,
}

impl Verdict {
    /// Pass when nothing failed: `reasons` lists why it fails.
    pub fn of(reasons: &[String]) -> Verdict {
        if reasons.is_empty() {
            Verdict::Pass
        } else {
            Verdict::Fail
        }
    }

    /// The word: `pass` or `fail`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Pass => "pass",
            Verdict::Fail => "fail",
        }
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The result of `basr simulate`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    pub controller: String,
    pub tolerance_m: f64,
    pub verdict: Verdict,
    /// What the verdict is judged on: [`VerdictOn::Nominal`] (this run, on
    /// the plant the robot description describes) or
    /// [`VerdictOn::PlantsP95`] (the 95th percentile of `plants`; every
    /// other figure here is still the nominal run's).
    pub verdict_on: VerdictOn,
    /// Why it failed (empty on pass).
    pub reasons: Vec<String>,
    /// Verdict error: while painting (or the whole job if it never paints).
    pub max_error_m: f64,
    pub rms_error_m: f64,
    pub worst: Place,
    /// Over the whole job including air moves.
    pub max_error_all_m: f64,
    pub rms_error_all_m: f64,
    pub strokes: Vec<StrokeError>,
    pub waviness: Waviness,
    pub saturation: Saturation,
    pub peak_pressures: PeakPressures,
    pub axis_errors: AxisErrors,
    pub limits: Vec<LimitViolation>,
    pub duration_s: f64,
    pub painting_s: f64,
    pub control_period_s: f64,
    pub integrator_step_s: f64,
    /// With `--plants N`: the spread of the verdict error over N plants
    /// drawn around the description (the verdict is then on its p95).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plants: Option<super::plants::PlantsSummary>,
    /// With `--fault`, or when the safety monitor stopped the arm: what
    /// happened, when and where, and how the arm came to rest.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub safety: Option<super::safety::SafetyReport>,
    /// With `Options::stop_over_m`: the time the run ended at, its error
    /// first over that bound while painting (its figures are the run's up
    /// to there; the error would have grown on).
    #[serde(skip)]
    pub cut_short_at_s: Option<f64>,
}

/// What a report's verdict is judged on: `"nominal"` or `"plants_p95"` in
/// `basr simulate --json`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VerdictOn {
    /// The run itself, on the plant the robot description describes.
    Nominal,
    /// `--plants N`: the 95th percentile of the plants' errors.
    PlantsP95,
}

impl Report {
    pub fn passed(&self) -> bool {
        self.verdict == Verdict::Pass
    }

    /// The verdict and what it is judged on, in words: `PASS on the
    /// nominal plant (the robot description)` or `FAIL on the 95th
    /// percentile of 40 plants drawn around the robot description at
    /// spread 0.1 (each uncertain number within ±1–20 %; seed 7)`.
    pub fn verdict_words(&self) -> String {
        let on = match &self.plants {
            Some(p) if self.verdict_on == VerdictOn::PlantsP95 => {
                let sh: Vec<f64> = crate::plants::shares(p.spread)
                    .iter()
                    .map(|s| s.1)
                    .collect();
                let lo = sh.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = sh.iter().copied().fold(0.0, f64::max);
                format!(
                    "the 95th percentile of {} plants drawn around the robot description at spread {} (each uncertain number within ±{}–{} %; seed {})",
                    p.n,
                    basr_io::show_num(p.spread),
                    basr_io::show_num(lo * 100.0),
                    basr_io::show_num(hi * 100.0),
                    p.seed
                )
            }
            _ => "the nominal plant (the robot description)".into(),
        };
        format!("{} on {on}", self.verdict.name().to_uppercase())
    }

    /// A few lines for a person.
    pub fn human(&self) -> String {
        let mm = |m: f64| m * 1000.0;
        let nominal = format!(
            "max error {:.3} mm, RMS {:.3} mm while painting",
            mm(self.max_error_m),
            mm(self.rms_error_m),
        );
        let mut s = match &self.plants {
            Some(p) if self.verdict_on == VerdictOn::PlantsP95 => {
                let mut s = format!(
                    "simulate ({}): {} — p95 max error {:.3} mm (tolerance {:.3} mm)\n",
                    self.controller,
                    self.verdict_words(),
                    mm(p.p95_max_error_m),
                    mm(self.tolerance_m)
                );
                s += &p.human(self.tolerance_m);
                s += &format!(
                    "  the nominal plant alone (the robot description, not the verdict): {nominal}, {}\n",
                    if self.max_error_m <= self.tolerance_m {
                        "within the tolerance"
                    } else {
                        "over the tolerance"
                    }
                );
                s
            }
            _ => format!(
                "simulate ({}): {} — {nominal} (tolerance {:.3} mm)\n",
                self.controller,
                self.verdict_words(),
                mm(self.tolerance_m)
            ),
        };
        s += &format!(
            "  worst on the nominal plant at {}\n",
            self.worst.describe()
        );
        s += &format!(
            "  whole job: max {:.3} mm, RMS {:.3} mm; waviness above {:.2} Hz: max {:.3} mm, RMS {:.3} mm\n",
            mm(self.max_error_all_m),
            mm(self.rms_error_all_m),
            self.waviness.cutoff_hz,
            mm(self.waviness.max_m),
            mm(self.waviness.rms_m)
        );
        s += &format!(
            "  valves saturated: motor {:.2} s, cylinder {:.2} s; peak pressures {:.1}/{:.1} MPa (motor), {:.1}/{:.1} MPa (cylinder)\n",
            self.saturation.motor_valve_s,
            self.saturation.cylinder_valve_s,
            self.peak_pressures.motor_a_pa / 1e6,
            self.peak_pressures.motor_b_pa / 1e6,
            self.peak_pressures.cylinder_a_pa / 1e6,
            self.peak_pressures.cylinder_b_pa / 1e6
        );
        let worst_strokes = {
            let mut v: Vec<&StrokeError> = self.strokes.iter().collect();
            v.sort_by(|a, b| b.max_error_m.total_cmp(&a.max_error_m));
            v.truncate(3);
            v
        };
        for st in worst_strokes {
            s += &format!(
                "  stroke {}: max {:.3} mm at t = {:.3} s, RMS {:.3} mm\n",
                st.stroke,
                mm(st.max_error_m),
                st.worst.t_s,
                mm(st.rms_error_m)
            );
        }
        if let Some(safety) = &self.safety {
            s += &safety.human();
        }
        for l in &self.limits {
            s += &format!("  limit: {}\n", l.message);
        }
        for r in &self.reasons {
            s += &format!("  FAIL: {r}\n");
        }
        s
    }
}

/// One row of `--trace`: desired and actual at one control tick.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TraceRow {
    pub t_s: f64,
    pub station: u32,
    pub stroke: i64,
    pub paint: u8,
    pub x_desired_m: f64,
    pub y_desired_m: f64,
    pub x_m: f64,
    pub y_m: f64,
    pub error_m: f64,
    /// Nozzle deflection from the end-effector linkage's compliance (m).
    pub deflection_m: f64,
    pub base_rot_desired_rad: f64,
    pub base_rot_rad: f64,
    pub extension_desired_m: f64,
    pub extension_m: f64,
    pub motor_a_pa: f64,
    pub motor_b_pa: f64,
    pub cylinder_a_pa: f64,
    pub cylinder_b_pa: f64,
    pub u_motor: f64,
    pub u_cylinder: f64,
    pub ee_yaw_desired_rad: f64,
    pub ee_yaw_rad: f64,
    pub tilt_nut_desired_m: f64,
    pub tilt_nut_m: f64,
    pub vertical_desired_m: f64,
    pub vertical_m: f64,
}

/// Second-order Butterworth high-pass run forwards then backwards (zero
/// phase), in place. Written by hand: a biquad is a few lines and no crate of
/// the project's set does filtering.
pub fn highpass_zero_phase(x: &mut [f64], cutoff_hz: f64, dt: f64) {
    if x.len() < 3 {
        x.iter_mut().for_each(|v| *v = 0.0);
        return;
    }
    // bilinear transform with pre-warping
    let k = (std::f64::consts::PI * cutoff_hz * dt).tan();
    let q = std::f64::consts::FRAC_1_SQRT_2;
    let norm = 1.0 / (1.0 + k / q + k * k);
    let b0 = norm;
    let b1 = -2.0 * norm;
    let b2 = norm;
    let a1 = 2.0 * (k * k - 1.0) * norm;
    let a2 = (1.0 - k / q + k * k) * norm;
    let run = |x: &mut dyn Iterator<Item = &mut f64>| {
        // start from the first value as a settled state (no step transient)
        let (mut x1, mut x2, mut y1, mut y2) = (f64::NAN, 0.0, 0.0, 0.0);
        for v in x {
            if x1.is_nan() {
                x1 = *v;
                x2 = *v;
            }
            let y = b0 * *v + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
            x2 = x1;
            x1 = *v;
            y2 = y1;
            y1 = y;
            *v = y;
        }
    };
    run(&mut x.iter_mut());
    run(&mut x.iter_mut().rev());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_and_limits_say_their_units_and_air_moves() {
        let p = Place {
            t_s: 1.5,
            stroke: -1,
            station: 0,
            x_m: 0.1,
            y_m: 2.0,
        };
        assert_eq!(p.describe(), "t = 1.500 s, air move, road (0.100, 2.000) m");
        assert_eq!(Unit::Pressure.show(23_741_043.383), "23.74 MPa");
        assert_eq!(Unit::Length.show(1.5487), "1548.70 mm");
        assert_eq!(
            Unit::Angle.show(std::f64::consts::FRAC_PI_4),
            "0.7854 rad (45.00°)"
        );
    }

    #[test]
    fn highpass_keeps_fast_ripple_and_removes_slow_drift() {
        let dt = 0.005;
        let n = 4000;
        let slow: Vec<f64> = (0..n)
            .map(|i| (i as f64 * dt * 0.1 * std::f64::consts::TAU).sin())
            .collect();
        let fast: Vec<f64> = (0..n)
            .map(|i| 0.01 * (i as f64 * dt * 10.0 * std::f64::consts::TAU).sin())
            .collect();
        let mut sum: Vec<f64> = slow.iter().zip(&fast).map(|(a, b)| a + b).collect();
        highpass_zero_phase(&mut sum, 1.0, dt);
        // away from the ends the output is the ripple
        let worst = (500..n - 500)
            .map(|i| (sum[i] - fast[i]).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-3, "{worst}");
    }

    #[test]
    fn the_verdict_is_pass_without_reasons_and_keeps_its_word() {
        assert_eq!(Verdict::of(&[]), Verdict::Pass);
        assert_eq!(Verdict::of(&["limit".to_string()]), Verdict::Fail);
        assert_eq!(serde_json::to_value(Verdict::Fail).unwrap(), "fail");
        let back: Verdict = serde_json::from_value(serde_json::json!("pass")).unwrap();
        assert_eq!(back, Verdict::Pass);
        assert!(serde_json::from_value::<Verdict>(serde_json::json!("PASS")).is_err());
    }
}
