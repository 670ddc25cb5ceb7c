//! DXF → filled contours with the `dxf` crate: closed LWPOLYLINE / POLYLINE
//! (bulges become circular arcs), CIRCLE, full ELLIPSE and closed SPLINE.
//! The crate (0.6) reads no HATCH entity; `hatch` reads their boundaries
//! from the group codes.

use dxf::entities::EntityType;
use dxf::enums::Units;
use kurbo::{Affine, Arc, BezPath, Point, Shape, Vec2};

use super::{Element, FillRule, Outline, ShapeError};

/// Curve flattening of arcs into cubics (file units, relative to the size).
/// assumed: 1e-4 of a unit keeps arcs exact to well under a millimetre at any
/// plausible drawing unit.
pub(super) const ARC_TOLERANCE: f64 = 1e-4;
/// Points per knot span when a SPLINE is sampled. assumed: a span of a road
/// drawing is a gentle curve; 32 chords keep it within a millimetre.
const SPLINE_SAMPLES_PER_SPAN: usize = 32;

pub fn read_dxf(text: &str, origin: &str) -> Result<Outline, ShapeError> {
    if text.trim().is_empty() {
        return Err(ShapeError::invalid(
            origin,
            "the file is empty: a DXF with closed polylines, circles or splines is needed",
        ));
    }
    super::limits::check_dxf_text(text, origin)?;
    let drawing = dxf::Drawing::load(&mut text.as_bytes()).map_err(|e| {
        ShapeError::invalid(
            origin,
            format!("not a readable DXF ({e}); save it again as ASCII DXF"),
        )
    })?;
    let mut elements = vec![];
    for e in drawing.entities() {
        let handle = e.common.handle.as_string();
        let name = |kind: &str| format!("{kind} (handle {handle})");
        let path = match &e.specific {
            EntityType::LwPolyline(p) => {
                let pts: Vec<(Point, f64)> = p
                    .vertices
                    .iter()
                    .map(|v| (Point::new(v.x, v.y), v.bulge))
                    .collect();
                closed(&pts, p.is_closed(), &name("LWPOLYLINE"), origin)?
            }
            EntityType::Polyline(p) => {
                let pts: Vec<(Point, f64)> = p
                    .vertices()
                    .map(|v| (Point::new(v.location.x, v.location.y), v.bulge))
                    .collect();
                closed(&pts, p.is_closed(), &name("POLYLINE"), origin)?
            }
            EntityType::Circle(c) => {
                // kurbo draws a full circle for r = -1 (issue 31, R8).
                if !(c.radius.is_finite() && c.radius > 0.0) {
                    return Err(ShapeError::invalid(
                        origin,
                        format!(
                            "{} has radius {}: a circle's radius must be a positive number; \
                             fix or delete it",
                            name("CIRCLE"),
                            basr_io::show_num(c.radius)
                        ),
                    ));
                }
                kurbo::Circle::new((c.center.x, c.center.y), c.radius).to_path(ARC_TOLERANCE)
            }
            EntityType::Ellipse(el) => ellipse(el, &name("ELLIPSE"), origin)?,
            EntityType::Spline(s) => spline(s, &name("SPLINE"), origin)?,
            EntityType::Arc(_) | EntityType::Line(_) => {
                return Err(ShapeError::invalid(
                    origin,
                    format!(
                        "{} is an open curve: loose lines and arcs enclose nothing to fill; \
                         join the outline into one closed polyline (AutoCAD: PEDIT ▸ Join)",
                        name(if matches!(e.specific, EntityType::Arc(_)) {
                            "ARC"
                        } else {
                            "LINE"
                        })
                    ),
                ))
            }
            EntityType::Text(_) | EntityType::MText(_) => {
                return Err(ShapeError::invalid(
                    origin,
                    format!(
                        "{} is text, not an outline: explode it to polylines first \
                         (AutoCAD: TXTEXP)",
                        name("TEXT")
                    ),
                ))
            }
            _ => continue, // dimensions, points, blocks: not paint
        };
        elements.push(Element {
            name: format!("{} (handle {handle})", entity_kind(&e.specific)),
            rule: FillRule::EvenOdd,
            path,
        });
    }
    elements.extend(super::hatch::read_hatches(text, origin)?);
    if elements.is_empty() {
        return Err(ShapeError::invalid(
            origin,
            "no closed outline in the file: basr fills closed LWPOLYLINE / POLYLINE, CIRCLE, \
             ELLIPSE and SPLINE entities and HATCH boundaries",
        ));
    }
    Ok(Outline {
        origin: origin.to_string(),
        elements,
        metres_per_unit: metres_per_unit(drawing.header.default_drawing_units),
    })
}

fn entity_kind(e: &EntityType) -> &'static str {
    match e {
        EntityType::LwPolyline(_) => "LWPOLYLINE",
        EntityType::Polyline(_) => "POLYLINE",
        EntityType::Circle(_) => "CIRCLE",
        EntityType::Ellipse(_) => "ELLIPSE",
        EntityType::Spline(_) => "SPLINE",
        _ => "entity",
    }
}

/// `$INSUNITS` → metres per unit; unitless drawings have no size of their own.
fn metres_per_unit(u: Units) -> Option<f64> {
    Some(match u {
        Units::Inches => 0.0254,
        Units::Feet => 0.3048,
        Units::Yards => 0.9144,
        Units::Millimeters => 0.001,
        Units::Centimeters => 0.01,
        Units::Decimeters => 0.1,
        Units::Meters => 1.0,
        Units::USSurveyFeet => 1200.0 / 3937.0,
        Units::USSurveyInch => 100.0 / 3937.0,
        _ => return None,
    })
}

/// A closed polyline with bulges (bulge = tan(θ/4) of the arc to the next
/// vertex, positive counter-clockwise: the DXF reference's definition).
fn closed(
    pts: &[(Point, f64)],
    is_closed: bool,
    name: &str,
    origin: &str,
) -> Result<BezPath, ShapeError> {
    let n = pts.len();
    let first_last_meet = n > 1 && (pts[0].0 - pts[n - 1].0).hypot() < 1e-9;
    if !(is_closed || first_last_meet) || n < 3 {
        return Err(ShapeError::invalid(
            origin,
            format!(
                "{name} is open: an open polyline encloses nothing to fill; close it \
                 (AutoCAD: PEDIT ▸ Close, or set its closed flag, group code 70 = 1)"
            ),
        ));
    }
    let count = if first_last_meet { n - 1 } else { n };
    Ok(bulge_path(&pts[..count]))
}

/// The closed path through `pts`, each vertex's bulge (tan of a quarter of
/// the arc's angle to the next vertex, positive counter-clockwise: the DXF
/// reference's definition) making that side a circular arc.
pub(super) fn bulge_path(pts: &[(Point, f64)]) -> BezPath {
    let n = pts.len();
    let mut path = BezPath::new();
    let Some(first) = pts.first() else {
        return path;
    };
    path.move_to(first.0);
    for i in 0..n {
        let (a, bulge) = pts[i];
        let b = pts[(i + 1) % n].0;
        if bulge.abs() < 1e-12 {
            path.line_to(b);
            continue;
        }
        let sweep = 4.0 * bulge.atan();
        let chord = b - a;
        let d = chord.hypot();
        if d < 1e-12 {
            continue;
        }
        let r = d / (2.0 * (sweep / 2.0).sin()).abs();
        // Centre: from the chord's midpoint along its left normal by
        // (d/2)/tan(θ/2), which is negative (to the right) for clockwise
        // arcs and for counter-clockwise ones over half a turn.
        let normal = Vec2::new(-chord.y, chord.x) / d;
        let c = a.midpoint(b) + normal * (0.5 * d / (sweep / 2.0).tan());
        let start = (a - c).atan2();
        let arc = Arc::new(c, (r, r), start, sweep, 0.0);
        arc.to_cubic_beziers(ARC_TOLERANCE, |p1, p2, p| path.curve_to(p1, p2, p));
    }
    path.close_path();
    path
}

fn ellipse(el: &dxf::entities::Ellipse, name: &str, origin: &str) -> Result<BezPath, ShapeError> {
    let full = (el.end_parameter - el.start_parameter).abs() >= std::f64::consts::TAU - 1e-9
        || (el.end_parameter - el.start_parameter).abs() < 1e-12;
    if !full {
        return Err(ShapeError::invalid(
            origin,
            format!("{name} is a partial ellipse, an open curve: nothing to fill; draw it whole"),
        ));
    }
    let major = Vec2::new(el.major_axis.x, el.major_axis.y);
    let rx = major.hypot();
    let ratio = el.minor_axis_ratio;
    if !(rx.is_finite() && rx > 0.0 && ratio.is_finite() && ratio > 0.0 && ratio <= 1.0) {
        return Err(ShapeError::invalid(
            origin,
            format!(
                "{name} has a major axis {} long and a minor/major ratio of {}: an ellipse \
                 needs a positive axis and a ratio in (0, 1]; fix or delete it",
                basr_io::show_num(rx),
                basr_io::show_num(ratio)
            ),
        ));
    }
    let m = Affine::translate((el.center.x, el.center.y)) * Affine::rotate(major.atan2());
    Ok(
        m * kurbo::Ellipse::new((0.0, 0.0), (rx, rx * el.minor_axis_ratio), 0.0)
            .to_path(ARC_TOLERANCE),
    )
}

/// A closed B-spline (possibly rational) sampled by de Boor's algorithm.
fn spline(s: &dxf::entities::Spline, name: &str, origin: &str) -> Result<BezPath, ShapeError> {
    let p = s.degree_of_curve.max(1) as usize;
    let cps: Vec<Point> = s
        .control_points
        .iter()
        .map(|c| Point::new(c.x, c.y))
        .collect();
    let w: Vec<f64> = if s.weight_values.len() == cps.len() {
        s.weight_values.clone()
    } else {
        vec![1.0; cps.len()]
    };
    let pts: Vec<Point> = if let Some(pts) = sample_spline(p, &s.knot_values, &cps, &w) {
        pts
    } else if s.fit_points.len() >= 3 {
        s.fit_points.iter().map(|c| Point::new(c.x, c.y)).collect()
    } else {
        return Err(ShapeError::invalid(
            origin,
            format!("{name} has too few control points or a bad knot vector; redraw it"),
        ));
    };
    let closes = pts.len() >= 3 && (pts[0] - pts[pts.len() - 1]).hypot() < 1e-6;
    if !(s.is_closed() || s.is_periodic() || closes) {
        return Err(ShapeError::invalid(
            origin,
            format!("{name} is an open spline: nothing to fill; close it"),
        ));
    }
    let mut path = BezPath::new();
    path.move_to(pts[0]);
    for q in &pts[1..] {
        path.line_to(*q);
    }
    path.close_path();
    Ok(path)
}

/// Points along a (rational) B-spline of `degree` over its knot spans, or
/// `None` when the knot vector does not fit the control points.
pub(super) fn sample_spline(
    degree: usize,
    k: &[f64],
    cps: &[Point],
    w: &[f64],
) -> Option<Vec<Point>> {
    let p = degree.max(1);
    if !(cps.len() > p && k.len() == cps.len() + p + 1 && w.len() == cps.len()) {
        return None;
    }
    let mut out = vec![];
    for span in p..cps.len() {
        let (t0, t1) = (k[span], k[span + 1]);
        if t1 <= t0 {
            continue;
        }
        for j in 0..SPLINE_SAMPLES_PER_SPAN {
            let t = t0 + (t1 - t0) * j as f64 / SPLINE_SAMPLES_PER_SPAN as f64;
            out.push(de_boor(span, t, p, k, cps, w));
        }
    }
    out.push(de_boor(cps.len() - 1, k[cps.len()], p, k, cps, w));
    (out.len() >= 2).then_some(out)
}

/// De Boor's algorithm for the rational B-spline of degree p at t in span k.
fn de_boor(k: usize, t: f64, p: usize, knots: &[f64], c: &[Point], w: &[f64]) -> Point {
    let mut d: Vec<(f64, f64, f64)> = (0..=p)
        .map(|j| {
            let i = j + k - p;
            (c[i].x * w[i], c[i].y * w[i], w[i])
        })
        .collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = j + k - p;
            let den = knots[i + 1 + p - r] - knots[i];
            let a = if den.abs() < 1e-300 {
                0.0
            } else {
                (t - knots[i]) / den
            };
            d[j] = (
                (1.0 - a) * d[j - 1].0 + a * d[j].0,
                (1.0 - a) * d[j - 1].1 + a * d[j].1,
                (1.0 - a) * d[j - 1].2 + a * d[j].2,
            );
        }
    }
    let (x, y, ww) = d[p];
    Point::new(x / ww, y / ww)
}
