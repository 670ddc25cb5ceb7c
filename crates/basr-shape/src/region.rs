//! Outline → regions: flatten every element to polygons in metres, resolve
//! self-intersections and overlaps under each element's fill rule, and
//! union the elements (i_overlay). A region is one outer boundary with its
//! holes.

use i_overlay::core::fill_rule::FillRule as IFill;
use i_overlay::float::simplify::SimplifyShape;
use kurbo::{Affine, PathEl, Point};

use super::{FillRule, Outline, ShapeError};

/// Curves become chords no farther than this from the curve (m).
/// assumed: a sixth of the 6.35 mm accuracy Caltrans asks of the arm (SPEC §4).
pub const FLATTEN_TOLERANCE_M: f64 = 0.001;
/// Regions smaller than this (m²) are float dust of the boolean step.
/// assumed: a 1 cm square, far below anything a 0.1 m fan can paint.
const MIN_REGION_AREA_M2: f64 = 1e-4;

/// One connected filled area: outer boundary counter-clockwise, holes clockwise (m).
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub outer: Vec<Point>,
    pub holes: Vec<Vec<Point>>,
}

impl Region {
    /// Filled area (m²).
    pub fn area(&self) -> f64 {
        signed_area(&self.outer) + self.holes.iter().map(|h| signed_area(h)).sum::<f64>()
    }

    /// Every contour, outer first.
    pub fn contours(&self) -> impl Iterator<Item = &Vec<Point>> {
        std::iter::once(&self.outer).chain(self.holes.iter())
    }
}

/// A star-shaped polygon about the origin with one vertex per radius,
/// evenly spaced in angle from the +x axis (tests' random shapes).
#[cfg(test)]
pub fn from_radii(radii: &[f64], start_rad: f64) -> Region {
    let n = radii.len();
    let outer = radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = start_rad + std::f64::consts::TAU * i as f64 / n as f64;
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect();
    Region {
        outer,
        holes: vec![],
    }
}

/// Shoelace area, positive counter-clockwise.
pub fn signed_area(p: &[Point]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|i| p[i].to_vec2().cross(p[(i + 1) % n].to_vec2()))
        .sum::<f64>()
}

/// The outline at `scale` metres per file unit, its lower-left corner at
/// the origin, resolved into regions (largest first).
pub fn regions(outline: &Outline, scale: f64) -> Result<Vec<Region>, ShapeError> {
    let bb = super::bounds(outline);
    let m = Affine::scale(scale) * Affine::translate((-bb.x0, -bb.y0));
    let mut all: Vec<Vec<[f64; 2]>> = vec![];
    for e in &outline.elements {
        let contours = flatten(&(m * e.path.clone()));
        let rule = match e.rule {
            FillRule::NonZero => IFill::NonZero,
            FillRule::EvenOdd => IFill::EvenOdd,
        };
        let shapes = contours.simplify_shape(rule);
        let area: f64 = shapes
            .iter()
            .flatten()
            .map(|c| signed_area(&pts(c)))
            .sum::<f64>();
        if area.abs() < MIN_REGION_AREA_M2 {
            return Err(ShapeError::invalid(
                &outline.origin,
                format!(
                    "{}: its outline crosses itself so that nothing is left filled under its \
                     fill rule (or it is too small to paint); redraw it as a simple closed \
                     outline",
                    e.name
                ),
            ));
        }
        all.extend(shapes.into_iter().flatten());
    }
    // Each simplified shape has its outer boundary one way and its holes
    // the other, so a non-zero union keeps holes that no other element fills.
    let mut out: Vec<Region> = all
        .simplify_shape(IFill::NonZero)
        .into_iter()
        .filter_map(|shape| {
            let mut cs = shape.into_iter().map(|c| pts(&c));
            let mut outer = cs.next()?;
            if signed_area(&outer) < 0.0 {
                outer.reverse();
            }
            let holes = cs
                .map(|mut h| {
                    if signed_area(&h) > 0.0 {
                        h.reverse();
                    }
                    h
                })
                .collect();
            Some(Region { outer, holes })
        })
        .filter(|r| r.area() >= MIN_REGION_AREA_M2)
        .collect();
    out.sort_by(|a, b| b.area().total_cmp(&a.area()));
    if out.is_empty() {
        return Err(ShapeError::invalid(
            &outline.origin,
            "nothing is left filled once the outlines are resolved; check the fill rules",
        ));
    }
    Ok(out)
}

fn pts(c: &[[f64; 2]]) -> Vec<Point> {
    c.iter().map(|p| Point::new(p[0], p[1])).collect()
}

/// Closed polygons of a path (m), chords within [`FLATTEN_TOLERANCE_M`].
fn flatten(path: &kurbo::BezPath) -> Vec<Vec<[f64; 2]>> {
    let mut out: Vec<Vec<[f64; 2]>> = vec![];
    let mut cur: Vec<[f64; 2]> = vec![];
    kurbo::flatten(path, FLATTEN_TOLERANCE_M, |el| match el {
        PathEl::MoveTo(p) => {
            if cur.len() >= 3 {
                out.push(std::mem::take(&mut cur));
            }
            cur = vec![[p.x, p.y]];
        }
        PathEl::LineTo(p)
            if cur
                .last()
                .is_none_or(|q| (q[0] - p.x).hypot(q[1] - p.y) > 1e-9) =>
        {
            cur.push([p.x, p.y]);
        }
        PathEl::ClosePath => {
            if cur.len() >= 3 {
                out.push(std::mem::take(&mut cur));
            }
            cur.clear();
        }
        _ => {}
    });
    if cur.len() >= 3 {
        out.push(cur);
    }
    out
}
