//! # basr-geom
//!
//! Curves and edges of strokes, and lengths with units (`units`). Imports no other basr crate. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! Curves and edges: lines, cardinal splines, conic arcs; evaluation, arc length, subdivision.
//!
//! Every curve implements the narrow [`Curve`] trait (position, derivative, arc
//! length and its inverse, each to a requested accuracy), in the style of
//! kurbo's `ParamCurve*` traits. A [`Segment`] is one of the three curve kinds
//! of 001 §2.4; an [`Edge`] is a G0 chain of segments that can be split into
//! points of equal arc length (001 §2.4, fig. 2.7).

pub mod units;

mod cardinal;
mod conic;
mod edge;
mod quad;
mod segment;

pub use cardinal::Cardinal;
pub use conic::Conic;
pub use edge::Edge;
pub use kurbo::{Affine, Point, Vec2};
pub use quad::integrate;
pub use segment::Segment;

/// Default absolute accuracy for arc length work, in the curve's own units
/// (grid units for glyphs: 1e-9 of a unit is ~0.1 nm on an 8 ft letter).
pub const DEFAULT_ACCURACY: f64 = 1e-9;

/// How far apart (in the curve's units) two segment ends may be and still
/// count as joined (G0) in an edge. // assumed: well below any drawing
/// tolerance, well above the rounding of hand-typed decimals.
pub const JOIN_TOLERANCE: f64 = 1e-6;

/// A planar parametric curve on t ∈ [0, 1].
pub trait Curve {
    /// Position at parameter `t`.
    fn eval(&self, t: f64) -> Point;
    /// Derivative dP/dt at parameter `t`.
    fn deriv(&self, t: f64) -> Vec2;
    /// Arc length of the whole curve, within `accuracy` (absolute).
    fn arclen(&self, accuracy: f64) -> f64;
    /// The parameter t at which the arc length from the start equals `s`
    /// (clamped to [0, 1]); the length error is within `accuracy`.
    fn inv_arclen(&self, s: f64, accuracy: f64) -> f64;
    /// Start point.
    fn start(&self) -> Point {
        self.eval(0.0)
    }
    /// End point.
    fn end(&self) -> Point {
        self.eval(1.0)
    }
}

/// What can be wrong when building an edge. `index` counts segments from 0;
/// the messages count from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeomError {
    /// An edge needs at least one segment.
    #[error("an edge needs at least one segment")]
    Empty,
    /// A coordinate or parameter is NaN or infinite.
    #[error("segment {} has a non-finite coordinate or parameter", index + 1)]
    NotFinite { index: usize },
    /// A segment has (nearly) zero length.
    #[error("segment {} has zero length (its points coincide)", index + 1)]
    Degenerate { index: usize },
    /// A segment's length overflows (its points are finite but so far apart
    /// that the length is not a number).
    #[error("segment {} is too long to measure (its points are far apart, beyond 1e150)", index + 1)]
    TooLong { index: usize },
    /// Two consecutive segments do not meet.
    #[error(
        "segment {} starts at ({:.6}, {:.6}) but the previous one ends at ({:.6}, {:.6}) \
         ({gap:.3e} apart); an edge must be continuous",
        index + 1, start.x, start.y, prev_end.x, prev_end.y
    )]
    Gap {
        index: usize,
        prev_end: Point,
        start: Point,
        gap: f64,
    },
}

/// Inverse arc length on [0, 1] for any curve whose partial arc length can be
/// measured: `partial(t)` returns the length from 0 to t. Solved with kurbo's
/// ITP root finder, as kurbo's own `inv_arclen` does.
pub(crate) fn solve_inv_arclen(
    partial: impl Fn(f64) -> f64,
    total: f64,
    s: f64,
    accuracy: f64,
) -> f64 {
    if s <= 0.0 || total <= 0.0 {
        return 0.0;
    }
    if s >= total {
        return 1.0;
    }
    let epsilon = (accuracy / total).max(1e-15);
    kurbo::common::solve_itp(|t| partial(t) - s, 0.0, 1.0, epsilon, 1, 0.2, -s, total - s)
}
