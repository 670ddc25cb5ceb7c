//! The compile pipeline: message or marking → layout → strokes → rungs →
//! knots with tilt → passes → stations → order → IK → time law → the job.

use std::path::PathBuf;

use crate::job::{self, Job, Warning};
use crate::layout::{self, LayoutError, Marking, Overrides};
use crate::plan::stations::{self, StationError};

/// Default largest distance between rungs at the letter's scale (issue 4).
pub const DEFAULT_RUNG_SPACING_M: f64 = 0.020;
/// Default setpoint period (001 §4.2: "typically at 32 msec").
pub const DEFAULT_PERIOD_S: f64 = 0.032;

/// Where the message comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Words typed on the command line; each word one line.
    Message(String),
    /// A marking file's text; `origin` names it in messages.
    Marking { text: String, origin: String },
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
    /// The name written in the job (`layout.tilt_method`).
    pub fn name(self) -> &'static str {
        match self {
            Tilt::None => "none",
            Tilt::Trapezoid => "trapezoid",
            Tilt::Quadrilateral => "quadrilateral",
        }
    }
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
}

impl CompileRequest {
    /// Defaults for a message typed on the command line.
    pub fn message(text: &str) -> CompileRequest {
        CompileRequest {
            source: Source::Message(text.to_string()),
            overrides: Overrides::default(),
            font: None,
            robot: None,
            tilt: Tilt::default(),
            rung_spacing_m: DEFAULT_RUNG_SPACING_M,
            period_s: DEFAULT_PERIOD_S,
            gun_lead_s: 0.0,
            gun_lag_s: 0.0,
            reach_margin_m: stations::DEFAULT_MARGIN_M,
        }
    }
}

/// Why a compile failed; every variant is bad input (exit 2).
#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    #[error(transparent)]
    Layout(#[from] LayoutError),
    #[error(transparent)]
    Stations(#[from] StationError),
    #[error("{field} must be {what}, got {value}")]
    Setting {
        field: &'static str,
        what: &'static str,
        value: f64,
    },
    #[error("font: {0}")]
    Font(String),
    #[error("robot: {0}")]
    Robot(String),
    #[error("{0}")]
    Unreachable(String),
    #[error("time law: {0}")]
    Timing(String),
}

/// Compile a message or marking into a sealed job.
pub fn compile_job(req: &CompileRequest) -> Result<Job, CompileError> {
    check_settings(req)?;
    let marking = match &req.source {
        Source::Message(m) => Marking::from_message(m, &req.overrides)?,
        Source::Marking { text, origin } => Marking::from_toml(text, origin, &req.overrides)?,
    };
    let placed = layout::place(&marking, |_| Some(layout::GRID_WIDTH_UNITS))?;
    let mut warnings: Vec<Warning> = placed
        .warnings
        .iter()
        .map(|w| Warning {
            kind: "layout".into(),
            stroke: -1,
            t_s: None,
            factor: None,
            message: w.clone(),
        })
        .collect();
    let _ = &mut warnings;
    let _ = job::FORMAT;
    Err(CompileError::Font(
        "the stroke font is not built into this basr yet (issue 2)".into(),
    ))
}

fn check_settings(req: &CompileRequest) -> Result<(), CompileError> {
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
    Ok(())
}
