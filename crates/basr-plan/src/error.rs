//! Why a compile failed: every variant is bad input (exit 2) and says what
//! and how to fix it.

use basr_shape::layout::LayoutError;

/// Why a compile failed; every variant is bad input (exit 2).
#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    #[error(transparent)]
    Layout(#[from] LayoutError),
    #[error(transparent)]
    Stations(#[from] StationError),
    #[error("{field} must be {what}, got {}", basr_io::show_num(*value))]
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
    #[error("{0}")]
    Knots(String),
    #[error("time law: {0}")]
    Timing(String),
    #[error("verification: {0}")]
    Verify(String),
    #[error("film check: {0}")]
    Film(String),
    #[error(
        "the arm cannot follow this job closely enough even at {pace:.0} % of its joint \
         limits: {why}; use a smaller --letter-height, a shorter --period-s or check the \
         robot description"
    )]
    NotFollowed { pace: f64, why: String },
}

/// Errors of station planning.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum StationError {
    #[error(
        "stroke {item} cannot be reached from any truck position in the lane: its point \
         ({x:.3}, {y:.3}) m stays {short_m:.3} m outside the arm's reach (margin {margin_m} m); \
         use a smaller --letter-height or a robot with more reach"
    )]
    Unreachable {
        item: usize,
        x: f64,
        y: f64,
        short_m: f64,
        margin_m: f64,
    },
    #[error(
        "the marking now needs {planned} stops, but the job being fitted has {job}; re-plan \
         it from the same marking and options it was compiled with"
    )]
    SiteStops { job: usize, planned: usize },
    #[error(
        "stop {stop}: the arm cannot reach the marking from where the truck stopped (axis at \
         x {x:.3} m, y {y:.3} m, heading {heading_deg:.1}°): the point ({px:.3}, {py:.3}) m is \
         {short_m:.3} m outside its reach; {advice}, then chalk and measure the points again"
    )]
    SiteOutOfReach {
        stop: usize,
        x: f64,
        y: f64,
        heading_deg: f64,
        px: f64,
        py: f64,
        short_m: f64,
        advice: String,
    },
}
