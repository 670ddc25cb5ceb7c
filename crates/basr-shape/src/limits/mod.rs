//! Bounds on a shape file, checked before the work they bound: how deep
//! its SVG groups nest and how many elements it holds (counted before
//! usvg walks them), how many entities and vertices a DXF holds (counted on
//! its group codes before the dxf crate loads them), and, once read, every
//! coordinate finite, the vertices, the outline's total length and its
//! size on the road. An audit's hostile files (issue 31, R4 and R7) ran
//! for minutes, took gigabytes or overflowed the stack without them.

use std::collections::HashMap;

use kurbo::{PathEl, Point};

use super::{Outline, ShapeError};

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

/// An SVG's nesting depth and element count, every `<use>` expanded as
/// often as it is used, from its XML alone: before usvg, whose walk
/// recurses per level and copies each use. A file that is no XML is left
/// for usvg to report with its position.
pub fn check_svg_text(text: &str, origin: &str) -> Result<(), ShapeError> {
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
    let Ok(doc) = usvg::roxmltree::Document::parse(text) else {
        return Ok(());
    };
    let ids: HashMap<&str, usvg::roxmltree::Node> = doc
        .descendants()
        .filter_map(|n| n.attribute("id").map(|i| (i, n)))
        .collect();
    let mut memo = HashMap::new();
    let count = expanded(doc.root_element(), &ids, &mut memo, 0);
    if count > MAX_ELEMENTS {
        return Err(too_many(
            origin,
            "elements (each <use> counted as what it copies)",
            count,
            MAX_ELEMENTS,
            "simplify the drawing, or split it into several shapes",
        ));
    }
    Ok(())
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

/// Elements under `n` (itself included) with each `<use>` counting what it
/// refers to; saturating, and a use past the depth bound (a chain or a
/// cycle of uses) counts as over the limit.
fn expanded<'a>(
    n: usvg::roxmltree::Node<'a, 'a>,
    ids: &HashMap<&str, usvg::roxmltree::Node<'a, 'a>>,
    memo: &mut HashMap<usvg::roxmltree::NodeId, u64>,
    uses: usize,
) -> u64 {
    if let Some(c) = memo.get(&n.id()) {
        return *c;
    }
    if uses > MAX_DEPTH {
        return MAX_ELEMENTS + 1;
    }
    let mut count: u64 = 1;
    if n.tag_name().name() == "use" {
        let href = n
            .attributes()
            .find(|a| a.name() == "href")
            .map(|a| a.value().trim_start_matches('#'));
        if let Some(target) = href.and_then(|h| ids.get(h)) {
            count = count.saturating_add(expanded(*target, ids, memo, uses + 1));
        }
    }
    for c in n.children().filter(|c| c.is_element()) {
        count = count.saturating_add(expanded(c, ids, memo, uses));
        if count > MAX_ELEMENTS {
            break;
        }
    }
    memo.insert(n.id(), count);
    count
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
}
