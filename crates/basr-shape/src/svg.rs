//! SVG → filled contours: usvg parses and normalises the file (shapes to
//! paths, arcs to cubics, group transforms, styles); this walks its tree.

use kurbo::{Affine, BezPath, Point};

use super::{Element, FillRule, Outline, ShapeError};

/// Ends of a subpath closer than this (file units) count as closed.
/// assumed: far below any drawing's detail, above float noise of usvg's f32.
const CLOSE_EPS: f64 = 1e-3;

pub fn read_svg(text: &str, origin: &str) -> Result<Outline, ShapeError> {
    if text.trim().is_empty() {
        return Err(ShapeError::invalid(
            origin,
            "the file is empty: an SVG with filled paths is needed",
        ));
    }
    refuse_text(text, origin)?;
    let tree = usvg::Tree::from_str(text, &usvg::Options::default()).map_err(|e| {
        ShapeError::invalid(
            origin,
            format!("not a readable SVG ({e}); export it again as plain SVG"),
        )
    })?;
    let mut elements = vec![];
    let mut count = 0usize;
    walk(tree.root(), origin, &mut count, &mut elements)?;
    if elements.is_empty() {
        return Err(ShapeError::invalid(
            origin,
            "no filled shape in the file: basr paints filled paths, polygons, circles and \
             ellipses; give the outline a fill",
        ));
    }
    Ok(Outline {
        origin: origin.to_string(),
        elements,
        metres_per_unit: None,
    })
}

/// usvg (without its text feature) drops `<text>`; say so instead of
/// painting the rest of the file without it.
fn refuse_text(text: &str, origin: &str) -> Result<(), ShapeError> {
    let Ok(doc) = usvg::roxmltree::Document::parse(text) else {
        return Ok(()); // usvg reports the syntax error with its position
    };
    if let Some(n) = doc
        .descendants()
        .find(|n| n.is_element() && n.tag_name().name() == "text")
    {
        let pos = doc.text_pos_at(n.range().start);
        let id = n
            .attribute("id")
            .map(|i| format!(" id=\"{i}\""))
            .unwrap_or_default();
        return Err(ShapeError::invalid(
            origin,
            format!(
                "line {}: <text{id}> is text, not an outline: convert it to paths first \
                 (Inkscape: Path ▸ Object to Path; Illustrator: Type ▸ Create Outlines)",
                pos.row
            ),
        ));
    }
    Ok(())
}

fn walk(
    g: &usvg::Group,
    origin: &str,
    count: &mut usize,
    out: &mut Vec<Element>,
) -> Result<(), ShapeError> {
    for node in g.children() {
        match node {
            usvg::Node::Group(g) => walk(g, origin, count, out)?,
            usvg::Node::Path(p) => {
                *count += 1;
                if let Some(e) = element(p, origin, *count)? {
                    out.push(e);
                }
            }
            usvg::Node::Image(_) | usvg::Node::Text(_) => {}
        }
    }
    Ok(())
}

fn element(p: &usvg::Path, origin: &str, k: usize) -> Result<Option<Element>, ShapeError> {
    let name = if p.id().is_empty() {
        format!("path {k} (no id)")
    } else {
        format!("path id=\"{}\"", p.id())
    };
    let Some(fill) = p.fill() else {
        if p.stroke().is_some() {
            return Err(ShapeError::invalid(
                origin,
                format!(
                    "{name} is only stroked, not filled: there is nothing to fill; \
                     convert the stroke to a filled outline (Inkscape: Path ▸ Stroke to Path)"
                ),
            ));
        }
        return Ok(None); // invisible
    };
    let rule = match fill.rule() {
        usvg::FillRule::NonZero => FillRule::NonZero,
        usvg::FillRule::EvenOdd => FillRule::EvenOdd,
    };
    let t = p.abs_transform();
    // SVG's y runs down the page; the road's y runs up.
    let m = Affine::new([1.0, 0.0, 0.0, -1.0, 0.0, 0.0])
        * Affine::new([
            t.sx as f64,
            t.ky as f64,
            t.kx as f64,
            t.sy as f64,
            t.tx as f64,
            t.ty as f64,
        ]);
    let mut path = BezPath::new();
    let mut start = Point::ORIGIN;
    let mut last = Point::ORIGIN;
    let mut open = false;
    let pt = |q: usvg::tiny_skia_path::Point| m * Point::new(q.x as f64, q.y as f64);
    let refuse_open = |at: Point| {
        ShapeError::invalid(
            origin,
            format!(
                "{name} has an open subpath (from ({:.3}, {:.3}) in the file's units): an open \
                 path encloses nothing to fill; close it (end it with Z)",
                at.x, -at.y
            ),
        )
    };
    use usvg::tiny_skia_path::PathSegment as S;
    for seg in p.data().segments() {
        match seg {
            S::MoveTo(q) => {
                if open && (last - start).hypot() > CLOSE_EPS {
                    return Err(refuse_open(start));
                }
                start = pt(q);
                last = start;
                open = true;
                path.move_to(start);
            }
            S::LineTo(q) => {
                last = pt(q);
                path.line_to(last);
            }
            S::QuadTo(a, q) => {
                last = pt(q);
                path.quad_to(pt(a), last);
            }
            S::CubicTo(a, b, q) => {
                last = pt(q);
                path.curve_to(pt(a), pt(b), last);
            }
            S::Close => {
                path.close_path();
                last = start;
                open = false;
            }
        }
    }
    if open && (last - start).hypot() > CLOSE_EPS {
        return Err(refuse_open(start));
    }
    Ok(Some(Element { name, rule, path }))
}
