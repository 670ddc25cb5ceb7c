//! An SVG's bounds read from its XML alone, before usvg: how deep its
//! elements nest, how many there are, and how many segments its shapes
//! become, each `<use>` expanded as often as it is used. usvg's walk
//! recurses per level, copies each use, and turns every arc into cubics at
//! a fixed tolerance, so an arc of radius 3e38 became millions of curves
//! (a fuzzer's find: one `<path>` ran for minutes).

use std::collections::HashMap;
use std::f64::consts::TAU;

use kurbo::{Point, Vec2};
use svgtypes::{LengthUnit, PathParser, PathSegment};
use usvg::roxmltree::{Document, Node, NodeId};

use super::{too_many, MAX_DEPTH, MAX_ELEMENTS, MAX_VERTICES};
use crate::ShapeError;

/// An SVG's nesting depth, element count and segment count, every
/// `<use>` expanded as often as it is used, and its circles' and
/// rectangles' radii in absolute units: from its XML alone, before usvg.
/// A file that is no XML is left for usvg to report with its position
/// (`None`); otherwise the parsed XML, for the reader's other checks.
pub fn check_svg_text<'t>(text: &'t str, origin: &str) -> Result<Option<Document<'t>>, ShapeError> {
    // Before any XML parser: roxmltree's tokenizer recurses per level too.
    if let Some((depth, at)) = too_deep(text) {
        let line = text[..at].matches('\n').count() + 1;
        return Err(ShapeError::invalid(
            origin,
            format!(
                "line {line}: an element nested {depth} deep, more than the {MAX_DEPTH} levels \
                 basr imports: ungroup the drawing (Inkscape: Edit ▸ Select All, Object ▸ \
                 Ungroup)"
            ),
        ));
    }
    let Ok(doc) = Document::parse(text) else {
        return Ok(None);
    };
    relative_radii(&doc, origin)?;
    let ids: HashMap<&str, Node> = doc
        .descendants()
        .filter_map(|n| n.attribute("id").map(|i| (i, n)))
        .collect();
    let mut memo = HashMap::new();
    let tally = expanded(doc.root_element(), &ids, &mut memo, 0);
    if tally.elements > MAX_ELEMENTS {
        return Err(too_many(
            origin,
            "elements (each <use> counted as what it copies)",
            tally.elements,
            MAX_ELEMENTS,
            "simplify the drawing, or split it into several shapes",
        ));
    }
    if tally.segments > MAX_VERTICES as u64 {
        return Err(too_many(
            origin,
            "vertices (each arc counted as the curves usvg makes of it, each <use> as what it \
             copies)",
            tally.segments,
            MAX_VERTICES as u64,
            "simplify the outline (Inkscape: Path ▸ Simplify), or scale a drawing drawn at a \
             vast size down before export",
        ));
    }
    Ok(Some(doc))
}

/// The first element nested deeper than [`MAX_DEPTH`] (its depth and byte
/// offset), by a scan of the tags alone: comments, CDATA, processing
/// instructions and declarations skipped, quoted attribute values honoured,
/// `<a/>` opening nothing. Exact for well-formed XML; for other text it
/// only decides whether the parser gets to say what is wrong.
fn too_deep(text: &str) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let skip_to = |from: usize, end: &str| {
        text[from..]
            .find(end)
            .map_or(b.len(), |k| from + k + end.len())
    };
    let (mut i, mut depth) = (0usize, 0usize);
    while i < b.len() {
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &text[i..];
        if rest.starts_with("<!--") {
            i = skip_to(i + 4, "-->");
        } else if rest.starts_with("<![CDATA[") {
            i = skip_to(i + 9, "]]>");
        } else if rest.starts_with("<?") {
            i = skip_to(i + 2, "?>");
        } else if rest.starts_with("<!") || rest.starts_with("</") {
            depth = depth.saturating_sub(usize::from(rest.starts_with("</")));
            i = skip_to(i + 2, ">");
        } else {
            let start = i;
            let mut quote: Option<u8> = None;
            i += 1;
            while i < b.len() {
                match (quote, b[i]) {
                    (Some(q), c) if c == q => quote = None,
                    (None, c @ (b'"' | b'\'')) => quote = Some(c),
                    (None, b'>') => break,
                    _ => {}
                }
                i += 1;
            }
            if b.get(i.wrapping_sub(1)) != Some(&b'/') {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Some((depth, start));
                }
            }
            i += 1;
        }
    }
    None
}

/// Elements and the segments their shapes become.
#[derive(Clone, Copy, Default)]
struct Tally {
    elements: u64,
    segments: u64,
}

impl Tally {
    const OVER: Tally = Tally {
        elements: u64::MAX,
        segments: u64::MAX,
    };

    fn add(&mut self, other: Tally) {
        self.elements = self.elements.saturating_add(other.elements);
        self.segments = self.segments.saturating_add(other.segments);
    }

    fn over(&self) -> bool {
        self.elements > MAX_ELEMENTS || self.segments > MAX_VERTICES as u64
    }
}

/// Elements under `n` (itself included) and their segments, with each
/// `<use>` counting what it refers to; saturating, and a use past the
/// depth bound (a chain or a cycle of uses) counts as over the limits.
fn expanded<'a>(
    n: Node<'a, 'a>,
    ids: &HashMap<&str, Node<'a, 'a>>,
    memo: &mut HashMap<NodeId, Tally>,
    uses: usize,
) -> Tally {
    if let Some(t) = memo.get(&n.id()) {
        return *t;
    }
    if uses > MAX_DEPTH {
        return Tally::OVER;
    }
    let mut tally = Tally {
        elements: 1,
        segments: segments(n),
    };
    if n.tag_name().name() == "use" {
        let href = n
            .attributes()
            .find(|a| a.name() == "href")
            .map(|a| a.value().trim_start_matches('#'));
        if let Some(target) = href.and_then(|h| ids.get(h)) {
            tally.add(expanded(*target, ids, memo, uses + 1));
        }
    }
    for c in n.children().filter(|c| c.is_element()) {
        tally.add(expanded(c, ids, memo, uses));
        if tally.over() {
            break;
        }
    }
    memo.insert(n.id(), tally);
    tally
}

/// The tolerance (user units) to which usvg 0.45 turns arcs into cubics:
/// `to_cubic_beziers(0.1, …)` in its path parser (svgtypes 0.15) and in its
/// circle, ellipse and rounded-rectangle conversion.
const USVG_ARC_TOLERANCE: f64 = 0.1;

/// Cubics kurbo 0.11's `Arc::append_iter` makes of an arc: per full turn
/// (1.1163 r / tolerance)^(1/6), at least 4, r the larger radius; the same
/// expression, so the count is usvg's own. Saturating: an infinite radius
/// counts as `u64::MAX`, a NaN one (which kurbo makes no curve of) as 0.
fn arc_curves(radius: f64, sweep: f64) -> u64 {
    let per_turn = (1.1163 * radius / USVG_ARC_TOLERANCE)
        .powf(1.0 / 6.0)
        .max(3.999_999);
    (per_turn * sweep.abs() / TAU).ceil() as u64
}

/// Segments one element's own geometry becomes in usvg: a path's
/// commands (an arc as its cubics, from its end points and radii as
/// kurbo corrects them), a polyline's points, a circle's or ellipse's four
/// quarter arcs, a rounded rectangle's four corners and sides.
fn segments(n: Node) -> u64 {
    let radius = |name: &str| n.attribute(name).and_then(user_length);
    match n.tag_name().name() {
        "path" => n.attribute("d").map_or(0, path_segments),
        "polyline" | "polygon" => n
            .attribute("points")
            .map_or(0, |p| svgtypes::PointsParser::from(p).count() as u64 + 1),
        "line" => 2,
        "circle" => radius("r").map_or(0, |r| 2 + 4 * arc_curves(r, TAU / 4.0)),
        "ellipse" | "rect" => {
            let (rx, ry) = match (radius("rx"), radius("ry")) {
                (Some(x), Some(y)) => (x, y),
                (Some(r), None) | (None, Some(r)) => (r, r),
                (None, None) => (0.0, 0.0),
            };
            // A rectangle's corners are clamped to half its sides: the
            // count never exceeds the unclamped one, so this bounds it.
            2 + 4 * arc_curves(rx.max(ry), TAU / 4.0) + 4
        }
        _ => 0,
    }
}

/// A length in user units (usvg's 96 per inch), or `None` where usvg
/// draws nothing (unparsable). em, ex and % are refused beforehand by
/// [`relative_radii`].
fn user_length(text: &str) -> Option<f64> {
    let length: svgtypes::Length = text.parse().ok()?;
    let per = match length.unit {
        LengthUnit::None | LengthUnit::Px => 1.0,
        LengthUnit::In => 96.0,
        LengthUnit::Cm => 96.0 / 2.54,
        LengthUnit::Mm => 96.0 / 25.4,
        LengthUnit::Pt => 96.0 / 72.0,
        LengthUnit::Pc => 96.0 / 6.0,
        LengthUnit::Em | LengthUnit::Ex | LengthUnit::Percent => return None,
    };
    Some(length.number.abs() * per)
}

/// A path's segments, counted as svgtypes' simplifying parser emits them
/// (each arc as its cubics), without making them: the parse stops at the
/// first error, as usvg's does.
fn path_segments(d: &str) -> u64 {
    let to = |from: Point, abs: bool, x: f64, y: f64| {
        if abs {
            Point::new(x, y)
        } else {
            from + Vec2::new(x, y)
        }
    };
    let (mut at, mut start) = (Point::ORIGIN, Point::ORIGIN);
    let mut count = 0u64;
    for segment in PathParser::from(d) {
        let Ok(segment) = segment else { break };
        let n = match segment {
            PathSegment::MoveTo { abs, x, y } => {
                at = to(at, abs, x, y);
                start = at;
                1
            }
            PathSegment::LineTo { abs, x, y }
            | PathSegment::CurveTo { abs, x, y, .. }
            | PathSegment::SmoothCurveTo { abs, x, y, .. }
            | PathSegment::Quadratic { abs, x, y, .. }
            | PathSegment::SmoothQuadratic { abs, x, y } => {
                at = to(at, abs, x, y);
                1
            }
            PathSegment::HorizontalLineTo { abs, x } => {
                at.x = if abs { x } else { at.x + x };
                1
            }
            PathSegment::VerticalLineTo { abs, y } => {
                at.y = if abs { y } else { at.y + y };
                1
            }
            PathSegment::EllipticalArc {
                abs,
                rx,
                ry,
                x_axis_rotation,
                large_arc,
                sweep,
                x,
                y,
            } => {
                let arc = kurbo::SvgArc {
                    from: at,
                    to: to(at, abs, x, y),
                    radii: Vec2::new(rx, ry),
                    x_rotation: x_axis_rotation.to_radians(),
                    large_arc,
                    sweep,
                };
                at = arc.to;
                kurbo::Arc::from_svg_arc(&arc)
                    .map_or(1, |a| arc_curves(a.radii.x.max(a.radii.y), a.sweep_angle))
            }
            PathSegment::ClosePath { .. } => {
                at = start;
                1
            }
        };
        count = count.saturating_add(n);
        if count > MAX_VERTICES as u64 {
            break;
        }
    }
    count
}

/// A circle's, ellipse's or rectangle's radius in em, ex or %: usvg sizes
/// those from font sizes (which multiply down nested groups) and the
/// viewport, so no bound on the numbers bounds the radius. Drawing
/// programs write radii in user units.
fn relative_radii(doc: &Document, origin: &str) -> Result<(), ShapeError> {
    for n in doc
        .descendants()
        .filter(|n| matches!(n.tag_name().name(), "circle" | "ellipse" | "rect"))
    {
        for name in ["r", "rx", "ry"] {
            let Some(value) = n.attribute(name) else {
                continue;
            };
            let Ok(length) = value.parse::<svgtypes::Length>() else {
                continue;
            };
            if matches!(
                length.unit,
                LengthUnit::Em | LengthUnit::Ex | LengthUnit::Percent
            ) {
                let line = doc.text_pos_at(n.range().start).row;
                return Err(ShapeError::invalid(
                    origin,
                    format!(
                        "line {line}: <{} {name}=\"{value}\">: basr reads a radius in user \
                         units, px, in, cm, mm, pt or pc, not em, ex or %: write it as a number \
                         of user units",
                        n.tag_name().name()
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_is_measured_on_the_tags() {
        let nest = |n: usize| format!("<svg>{}{}</svg>", "<g>".repeat(n), "</g>".repeat(n));
        assert_eq!(too_deep(&nest(MAX_DEPTH - 1)), None);
        assert_eq!(too_deep(&nest(MAX_DEPTH)).map(|d| d.0), Some(MAX_DEPTH + 1));
        // Self-closing tags, comments, CDATA and a quoted '>' open nothing.
        let flat = format!(
            "<?xml version=\"1.0\"?><!-- <g><g> --><svg>{}<![CDATA[<g><g>]]><g a=\"x>y\"/></svg>",
            "<rect/>".repeat(500)
        );
        assert_eq!(too_deep(&flat), None);
    }

    /// The count is svgtypes' own: the simplifying parser usvg uses makes
    /// exactly this many segments of arcs from tiny to large radii, with
    /// the radii kurbo enlarges to reach the end point.
    #[test]
    fn arcs_are_counted_as_the_curves_usvg_makes_of_them() {
        for d in [
            "M0 0 A5 5 0 0 1 10 0",
            "M0 0 A5 5 0 1 1 10 0 a 200 80 30 0 0 -50 30",
            "M10 20 A1e6 1e6 0 1 0 30 40 L 0 0 Z",
            "M0 0 A1e-3 2e-3 0 0 1 1000 0",
            "M0 0 A 40 1e-2 15 1 1 900 -400",
            "M-5 7 h 10 v 3 A 300 300 0 0 0 100 100 Z",
        ] {
            let simplified = svgtypes::SimplifyingPathParser::from(d)
                .filter_map(Result::ok)
                .count() as u64;
            assert_eq!(path_segments(d), simplified, "{d}");
        }
    }

    #[test]
    fn an_arc_of_vast_radius_is_refused_before_usvg() {
        for svg in [
            // 6e12 curves: usvg would never finish.
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 A1e75 1e75 0 1 1 1e75 0"/></svg>"#,
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 A3e38 3e38 0 0 1 3e38 3e38 Z"/></svg>"#,
            // Radii too small to reach the end point: kurbo scales both up
            // by the same factor, ry from 1 to ~1e34.
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 A1e-4 1 0 0 1 1e30 0"/></svg>"#,
            r#"<svg xmlns="http://www.w3.org/2000/svg"><circle r="3e38"/></svg>"#,
            r#"<svg xmlns="http://www.w3.org/2000/svg"><ellipse rx="1" ry="1e30in"/></svg>"#,
            r#"<svg xmlns="http://www.w3.org/2000/svg"><rect width="1e38" height="1e38" rx="1e37"/></svg>"#,
        ] {
            let e = check_svg_text(svg, "x.svg").expect_err(svg).to_string();
            assert!(e.contains("vertices"), "{svg}: {e}");
        }
    }

    #[test]
    fn a_drawing_at_usual_sizes_passes() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 3000 3000">
            <circle cx="1500" cy="1500" r="1400"/><ellipse rx="20mm" ry="3in"/>
            <rect width="100%" height="50" rx="10"/>
            <path d="M0 0 A 2000 2000 0 0 1 3000 3000 L 0 3000 Z"/></svg>"#;
        check_svg_text(svg, "x.svg").unwrap();
        let doc = Document::parse(svg).unwrap();
        let mut memo = HashMap::new();
        let t = expanded(doc.root_element(), &HashMap::new(), &mut memo, 0);
        assert_eq!(t.elements, 5);
        // r = 1400: (1.1163 · 14000)^(1/6) = 5.0 → 2 curves per quarter.
        assert_eq!(
            segments(
                doc.descendants()
                    .find(|n| n.has_tag_name("circle"))
                    .unwrap()
            ),
            10
        );
        assert!(t.segments < 100, "{}", t.segments);
    }

    #[test]
    fn uses_multiply_the_segments_they_copy() {
        let arc = "A 2000 2000 0 0 1 ".to_string();
        let d: String = (0..200).map(|i| format!("{arc}{} 0 ", i + 1)).collect();
        let uses: String = (0..99).map(|_| r##"<use href="#p"/>"##).collect();
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path id="p" d="M0 0 {d}"/>{uses}</svg>"#
        );
        let e = check_svg_text(&svg, "x.svg").unwrap_err().to_string();
        assert!(e.contains("vertices"), "{e}");
    }

    #[test]
    fn a_radius_in_font_or_viewport_units_is_refused_with_its_line() {
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<g font-size=\"1e30\">\n\
                   <circle r=\"1e6em\"/></g></svg>";
        let e = check_svg_text(svg, "x.svg").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("r=\"1e6em\""), "{e}");
        let pct = r#"<svg xmlns="http://www.w3.org/2000/svg"><rect width="9" height="9" ry="50%"/></svg>"#;
        assert!(check_svg_text(pct, "x.svg").is_err());
    }
}
