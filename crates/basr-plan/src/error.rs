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
    /// The road's surface leaves the vertical joint no painting height
    /// (a crown or a fitted plane too far off the truck's plane).
    #[error("{0}")]
    Road(String),
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
    #[error(
        "time law: setpoint {setpoint}: the smooth path between two planned points carries \
         {joint} to {value:.4}, {past:.4} past its range [{:.4}, {:.4}]: the marking reaches \
         the edge of what the arm reaches from its stop; use a smaller --letter-height (or a \
         robot with more reach)",
        min,
        max
    )]
    PastRange {
        setpoint: usize,
        joint: &'static str,
        value: f64,
        past: f64,
        min: f64,
        max: f64,
    },
}

impl CompileError {
    /// Whether the marking's size is what the arm cannot paint: out of its
    /// reach, carried past a joint's range, too fast to follow even at a
    /// tenth of its limits, or too wide for the lane. A smaller or larger
    /// letter height may paint; a bad setting or file will not.
    pub fn about_size(&self) -> bool {
        matches!(
            self,
            CompileError::Unreachable(_)
                | CompileError::Stations(StationError::Unreachable { .. })
                | CompileError::NotFollowed { .. }
                | CompileError::PastRange { .. }
                | CompileError::Layout(LayoutError::TooWide { .. })
        )
    }
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
         x {x:.3} m, y {y:.3} m, the truck turned {turned_deg:+.1}° from the lane direction, \
         counter-clockwise +): the point ({px:.3}, {py:.3}) m is {short_m:.3} m outside its \
         reach; {advice}, then chalk and measure the points again"
    )]
    SiteOutOfReach {
        stop: usize,
        x: f64,
        y: f64,
        /// From the lane direction (deg, counter-clockwise +), as the job
        /// sheet says a stop.
        turned_deg: f64,
        px: f64,
        py: f64,
        short_m: f64,
        advice: String,
    },
}
