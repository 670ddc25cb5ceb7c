//! What a compile is asked to do: the message or marking, the font, the
//! robot and the planning options, with their documented ranges.

use std::path::PathBuf;

use crate::knots::TiltMethod;
use crate::stations;
use basr_robot::AnyRobot;
use basr_shape::layout::Overrides;

use super::error::CompileError;

/// Default largest distance between rungs at the letter's scale (issue 4).
pub const DEFAULT_RUNG_SPACING_M: f64 = 0.020;
/// Default setpoint period (001 §4.2: "typically at 32 msec").
pub const DEFAULT_PERIOD_S: f64 = 0.032;

/// Where the message comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Words typed on the command line; each word one line.
    Message(String),
    /// A marking file's text (`lines`, or a scene of `[[item]]`s); `origin`
    /// names it in messages.
    Marking { text: String, origin: String },
    /// One library symbol alone, centred in the lane at the anchor.
    Symbol(String),
}

/// Tilt method (001 §2.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Tilt {
    None,
    Trapezoid,
    #[default]
    Quadrilateral,
}

impl Tilt {
    /// The tilt stage's method.
    pub fn method(self) -> TiltMethod {
        match self {
            Tilt::None => TiltMethod::None,
            Tilt::Trapezoid => TiltMethod::Trapezoid,
            Tilt::Quadrilateral => TiltMethod::Quadrilateral,
        }
    }

    /// The method a job was planned with, from its `layout.tilt_method`
    /// (the default where the name is none of them).
    pub fn of_job(name: &str) -> Tilt {
        match name {
            "none" => Tilt::None,
            "trapezoid" => Tilt::Trapezoid,
            _ => Tilt::Quadrilateral,
        }
    }

    /// The name written in the job (`layout.tilt_method`).
    pub fn name(self) -> &'static str {
        match self {
            Tilt::None => "none",
            Tilt::Trapezoid => "trapezoid",
            Tilt::Quadrilateral => "quadrilateral",
        }
    }
}

/// The tilt method a robot paints `asked` with, and the note when it
/// differs: the articulated arm leans its gun only in the arm's plane
/// (seed 003's pitch), so a fan painting across a stroke, which is across
/// the arm in all but a few rungs, cannot lean along itself; rather than
/// tilt a few rungs and not their neighbours, it paints every rung
/// untilted (`none`, the closest reachable tilt for a fan across the arm)
/// and says so. docs/robot-kinds.md.
pub fn tilt_for(asked: Tilt, robot: &AnyRobot) -> (Tilt, Option<super::warnings::Note>) {
    if robot.tilt_limit().is_some() || asked == Tilt::None {
        return (asked, None);
    }
    let text = format!(
        "the {} arm leans its gun only along the arm (seed 003's pitch), not along the fan: \
         --tilt {} is painted as --tilt none",
        robot.kind().name(),
        asked.name()
    );
    (Tilt::None, Some(super::warnings::Note::Layout { text }))
}

/// Everything `compile_job` needs. `CompileRequest::message("STOP")` gives
/// the defaults of `basr compile STOP`.
#[derive(Clone, Debug, PartialEq)]
pub struct CompileRequest {
    pub source: Source,
    /// Letter height, lane width and line gap given on the command line.
    pub overrides: Overrides,
    /// Font name or file; `None` = the embedded font.
    pub font: Option<String>,
    /// Robot description file; `None` = the embedded BASR.
    pub robot: Option<PathBuf>,
    /// A robot description already in hand (a job's own, when preview
    /// re-plans it); used instead of `robot` when set.
    pub robot_description: Option<AnyRobot>,
    pub tilt: Tilt,
    /// Largest distance between consecutive rungs (m).
    pub rung_spacing_m: f64,
    /// Setpoint period (s).
    pub period_s: f64,
    /// The gun is switched on this long before the nozzle reaches a
    /// stroke's first rung (valve opening delay; assumed 0 s: no source).
    pub gun_lead_s: f64,
    /// The gun is switched off this long before the nozzle reaches a
    /// stroke's last rung (valve closing delay; assumed 0 s: no source).
    pub gun_lag_s: f64,
    /// Margin kept from the edge of the arm's reach (m).
    pub reach_margin_m: f64,
    /// Run the closed-loop simulator on the job and re-time it until the arm
    /// follows it (`plan::verify`); off only where a job is re-planned for
    /// comparison and never written.
    pub verify: bool,
    /// Re-time where a plant of the spread set (drawn around the robot
    /// description) strays, as where the description does; off, the set's
    /// figures are only recorded (`summary.verified`). Off for imported
    /// shapes: their decomposition is chosen by measuring candidates, and
    /// re-timed joins slowed the arrow at 3 m into a NOT READY job.
    pub retime_on_spread: bool,
    /// Measure the written job's film as `basr preview` does and grade a
    /// failed bound (`plan::film`); off where a job is only compiled to be
    /// measured by its caller (shape candidates, re-planned comparisons).
    pub film: bool,
    /// Where the truck really stopped and the road under it (`basr fit`):
    /// compile keeps these stops instead of planning its own.
    pub site: Option<crate::site::Site>,
    /// The planner's tuning (`tuning::Tuning`): its default for every job
    /// the command line writes; another only where a caller explores one
    /// (the sensitivity test). A job does not record it.
    pub tuning: crate::tuning::Tuning,
    /// Plan the tilt gently (`tuning::Rates::gentle_tilt_acc_share` for
    /// `tilt_acc_share`): compile sets it when the first plan of a job has
    /// problems and keeps the gentle job when that has none; the job
    /// records it (`options.gentle_tilt`), so that `basr fit` and
    /// `preview --compare` plan again as compile did.
    pub gentle_tilt: bool,
    /// Hold the rungs' ends in from edges they meet obliquely (`rungs::
    /// held`, by `tuning::Pairing::end_hold` of the sheet's depth): compile
    /// sets it when a job's plans have problems otherwise and keeps that
    /// job when it has none; the job records it (`options.hold_ends`).
    pub hold_ends: bool,
    /// The tilt method was named (`--tilt`, or a job planned again with
    /// its own): compile keeps it. Otherwise compile may paint with the
    /// trapezoid method where the default quadrilateral one leaves
    /// problems and it has none (`compile::compile_strokes`); the job
    /// records the method it painted with (`layout.tilt_method`).
    pub tilt_named: bool,
}

impl CompileRequest {
    /// Defaults for a message typed on the command line.
    pub fn message(text: &str) -> CompileRequest {
        CompileRequest {
            source: Source::Message(text.to_string()),
            overrides: Overrides::default(),
            font: None,
            robot: None,
            robot_description: None,
            tilt: Tilt::default(),
            rung_spacing_m: DEFAULT_RUNG_SPACING_M,
            period_s: DEFAULT_PERIOD_S,
            gun_lead_s: 0.0,
            gun_lag_s: 0.0,
            reach_margin_m: stations::DEFAULT_MARGIN_M,
            verify: true,
            retime_on_spread: true,
            film: true,
            site: None,
            tuning: crate::tuning::Tuning::DEFAULT,
            gentle_tilt: false,
            hold_ends: false,
            tilt_named: false,
        }
    }
}

impl CompileRequest {
    /// The planning options the job records: `None` when every one is
    /// compile's default (the job then keeps the bytes it always had).
    pub fn recorded_options(&self) -> Option<basr_job::PlanOptions> {
        let d = CompileRequest::message("");
        let o = basr_job::PlanOptions {
            rung_spacing_m: self.rung_spacing_m,
            gun_lead_s: self.gun_lead_s,
            gun_lag_s: self.gun_lag_s,
            reach_margin_m: self.reach_margin_m,
            gentle_tilt: self.gentle_tilt,
            hold_ends: self.hold_ends,
        };
        let same = o.rung_spacing_m == d.rung_spacing_m
            && o.gun_lead_s == d.gun_lead_s
            && o.gun_lag_s == d.gun_lag_s
            && o.reach_margin_m == d.reach_margin_m
            && o.gentle_tilt == d.gentle_tilt
            && o.hold_ends == d.hold_ends;
        (!same).then_some(o)
    }

    /// This request with the options a job recorded (compile's defaults
    /// where it recorded none).
    pub fn with_options(mut self, o: Option<&basr_job::PlanOptions>) -> CompileRequest {
        let d = CompileRequest::message("");
        self.rung_spacing_m = o.map_or(d.rung_spacing_m, |o| o.rung_spacing_m);
        self.gun_lead_s = o.map_or(d.gun_lead_s, |o| o.gun_lead_s);
        self.gun_lag_s = o.map_or(d.gun_lag_s, |o| o.gun_lag_s);
        self.reach_margin_m = o.map_or(d.reach_margin_m, |o| o.reach_margin_m);
        self.gentle_tilt = o.is_some_and(|o| o.gentle_tilt);
        self.hold_ends = o.is_some_and(|o| o.hold_ends);
        self
    }

    /// The tuning this request plans with: `tuning`, its tilt's
    /// acceleration share the gentle one where `gentle_tilt`.
    pub fn planning_tuning(&self) -> crate::tuning::Tuning {
        let mut t = self.tuning;
        if self.gentle_tilt {
            t.rates.tilt_acc_share = t.rates.gentle_tilt_acc_share;
        }
        t
    }
}

/// Every option within its documented range (exit 2 with the range otherwise).
pub fn check_settings(req: &CompileRequest) -> Result<(), CompileError> {
    let positive = |field: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(CompileError::Setting {
                field,
                what: "a finite number above zero",
                value,
            })
        }
    };
    let non_negative = |field: &'static str, value: f64| {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(CompileError::Setting {
                field,
                what: "a finite number, zero or more",
                value,
            })
        }
    };
    positive("--rung-spacing-mm", req.rung_spacing_m * 1e3)?;
    positive("--period-s", req.period_s)?;
    non_negative("--gun-lead-s", req.gun_lead_s)?;
    non_negative("--gun-lag-s", req.gun_lag_s)?;
    non_negative("reach margin", req.reach_margin_m)?;
    let at_most = |field: &'static str, value: f64, max: f64, what: &'static str| {
        if value <= max {
            Ok(())
        } else {
            Err(CompileError::Setting { field, what, value })
        }
    };
    at_most(
        "--rung-spacing-mm",
        req.rung_spacing_m * 1e3,
        MAX_RUNG_SPACING_M * 1e3,
        "at most 100 mm: farther apart, rungs cut the corners of a letter's curves (default 20)",
    )?;
    at_most(
        "--period-s",
        req.period_s,
        MAX_PERIOD_S,
        "at most 0.1 s: a longer period would skip rungs at the painting speed (default 0.032)",
    )?;
    for (field, v) in [
        ("--gun-lead-s", req.gun_lead_s),
        ("--gun-lag-s", req.gun_lag_s),
    ] {
        at_most(
            field,
            v,
            MAX_GUN_SHIFT_S,
            "at most 1 s: the gun valve opens in tens of milliseconds, and a second is a \
             sixth of a metre of stroke at the painting speed (default 0)",
        )?;
    }
    Ok(())
}

/// Widest rung spacing, m. Assumed: the tightest curves of the road letters
/// (the S spine, the bowls) have radii of 0.1–0.2 m at 8 ft; rungs 0.1 m
/// apart already cut their chords by millimetres.
const MAX_RUNG_SPACING_M: f64 = 0.1;
/// Longest setpoint period, s: at the painting speed (≈ 0.16 m/s, SPEC §4) a
/// period past 0.125 s passes more than one default 20 mm rung between
/// setpoints; 0.1 s keeps every rung's change of speed and yaw in the job.
const MAX_PERIOD_S: f64 = 0.1;
/// Largest gun lead or lag, s. Assumed: an airless gun valve switches in tens
/// of milliseconds; a shift of a second moves the line's end by 0.16 m.
const MAX_GUN_SHIFT_S: f64 = 1.0;
