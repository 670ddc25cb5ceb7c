//! Bounds on a shape file, checked before the work they bound: how deep
//! its SVG groups nest and how many elements it holds (counted before
//! usvg walks them), how many entities and vertices a DXF holds (counted on
//! its group codes before the dxf crate loads them), and, once read, every
//! coordinate finite, the vertices, the outline's total length and its
//! size on the road. An audit's hostile files (issue 31, R4 and R7) ran
//! for minutes, took gigabytes or overflowed the stack without them.

use kurbo::{PathEl, Point};

use super::{Outline, ShapeError};

mod svg;
pub use svg::check_svg_text;

/// Deepest nesting of SVG elements. assumed: drawing programs nest a few
/// groups (Inkscape layers, Illustrator clip groups: under 20); 20,000
/// nested `<g>` overflowed the stack in usvg's recursive walk, 100 does not.
pub const MAX_DEPTH: usize = 100;

/// Most SVG elements (with every `<use>` expanded) or DXF entities.
/// assumed: a road symbol is a few hundred elements; 10^6 DXF circles took
/// 51 s and 1.7 GB.
pub const MAX_ELEMENTS: u64 = 10_000;

/// Most vertices (path points, polyline vertices, spline control points)
/// of the whole outline. assumed: a detailed outline is a few thousand; the
/// decomposition sweeps every vertex pair, and a 100,000-vertex polygon ran
/// past a minute.
pub const MAX_VERTICES: usize = 20_000;

/// Longest total outline on the road (m), every contour summed. assumed:
/// the largest shape (10 m, [`super::MAX_SIZE_M`]) with a contour as
/// ragged as a detailed logo is a few hundred metres; past 2 km the
/// decomposition's bands hold more rungs than a job can paint.
pub const MAX_OUTLINE_M: f64 = 2000.0;

fn too_many(origin: &str, what: &str, found: u64, limit: u64, fix: &str) -> ShapeError {
    ShapeError::invalid(
        origin,
        format!("the file holds {found} {what}, more than the {limit} basr imports: {fix}"),
    )
}

/// A DXF's entities and vertices counted on its group codes (code 0 starts
/// an entity, codes 10 are points: vertices, centres, control points)
/// before the dxf crate loads them.
pub fn check_dxf_text(text: &str, origin: &str) -> Result<(), ShapeError> {
    let (mut entities, mut points) = (0u64, 0u64);
    let mut lines = text.lines();
    while let Some(code) = lines.next() {
        let value = lines.next().unwrap_or("");
        match code.trim() {
            "0" if !matches!(value.trim(), "SECTION" | "ENDSEC" | "EOF" | "SEQEND") => {
                entities += 1
            }
            "10" => points += 1,
            _ => {}
        }
    }
    if entities > MAX_ELEMENTS {
        return Err(too_many(
            origin,
            "entities",
            entities,
            MAX_ELEMENTS,
            "give only the outline to paint (delete the other entities or layers)",
        ));
    }
    if points > MAX_VERTICES as u64 {
        return Err(too_many(
            origin,
            "points",
            points,
            MAX_VERTICES as u64,
            "simplify the outline (AutoCAD: PEDIT ▸ Decurve, OVERKILL) or give fewer entities",
        ));
    }
    Ok(())
}

/// Every element's coordinates finite, and the whole outline's vertices
/// within [`MAX_VERTICES`].
pub fn check_outline(outline: &Outline) -> Result<(), ShapeError> {
    let origin = &outline.origin;
    let mut vertices = 0usize;
    for e in &outline.elements {
        for el in e.path.elements() {
            let (pts, n): ([Point; 3], usize) = match el {
                PathEl::MoveTo(p) | PathEl::LineTo(p) => ([*p; 3], 1),
                PathEl::QuadTo(a, b) => ([*a, *b, *b], 2),
                PathEl::CurveTo(a, b, c) => ([*a, *b, *c], 3),
                PathEl::ClosePath => ([Point::ORIGIN; 3], 0),
            };
            if let Some(p) = pts[..n]
                .iter()
                .find(|p| !(p.x.is_finite() && p.y.is_finite()))
            {
                return Err(ShapeError::invalid(
                    origin,
                    format!(
                        "{} has a point that is not a finite number ({}, {}): fix or delete \
                         that vertex",
                        e.name, p.x, p.y
                    ),
                ));
            }
            vertices += 1;
        }
    }
    if vertices > MAX_VERTICES {
        return Err(too_many(
            origin,
            "vertices",
            vertices as u64,
            MAX_VERTICES as u64,
            "simplify the outline (Inkscape: Path ▸ Simplify; AutoCAD: OVERKILL)",
        ));
    }
    Ok(())
}

/// The outline at `scale` (m per file unit): its width within the shape
/// sizes (`scale_for` bounds the height) and its total length within
/// [`MAX_OUTLINE_M`], before any region is built.
pub fn check_scaled(outline: &Outline, scale: f64, width_m: f64) -> Result<(), ShapeError> {
    use kurbo::ParamCurve;
    let origin = &outline.origin;
    if width_m.is_nan() || width_m > super::MAX_SIZE_M {
        return Err(ShapeError::invalid(
            origin,
            format!(
                "the shape would be {} m wide; shapes are at most {} m wide and tall: give a \
                 smaller --shape-height-m, or --shape-width-m W",
                basr_io::show_num(width_m),
                super::MAX_SIZE_M
            ),
        ));
    }
    let mut length = 0.0;
    for e in &outline.elements {
        for seg in e.path.segments() {
            // A segment's chord is no longer than its arc: a bound that never
            // refuses a drawing its real length would pass, with no
            // subdivision of huge curves to get it.
            length += (seg.end() - seg.start()).hypot() * scale;
        }
        if length > MAX_OUTLINE_M {
            return Err(ShapeError::invalid(
                origin,
                format!(
                    "the outline is more than {} m long at this size, the most basr imports: \
                     give a smaller --shape-height-m or a simpler drawing",
                    MAX_OUTLINE_M
                ),
            ));
        }
    }
    Ok(())
}
