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
    if let Some(doc) = super::limits::check_svg_text(text, origin)? {
        refuse_text(&doc, origin)?;
    }
    // basr paints no images: usvg is not to read what an <image> names. Its
    // default reads any path on disk (an href of /dev/zero reads forever)
    // and parses an embedded SVG without the limits above.
    let options = usvg::Options {
        image_href_resolver: usvg::ImageHrefResolver {
            resolve_data: Box::new(|_, _, _| None),
            resolve_string: Box::new(|_, _| None),
        },
        ..usvg::Options::default()
    };
    let parse = |text: &str| -> Result<Vec<Element>, ShapeError> {
        let tree = usvg::Tree::from_str(text, &options).map_err(|e| {
            ShapeError::invalid(
                origin,
                format!("not a readable SVG ({e}); export it again as plain SVG"),
            )
        })?;
        let mut elements = vec![];
        let mut count = 0usize;
        walk(tree.root(), origin, &mut count, &mut elements)?;
        Ok(elements)
    };
    let mut elements = parse(text)?;
    if elements.is_empty() {
        // usvg draws nothing of an <svg> without the SVG namespace (a
        // hand-written file's usual omission): read it as one.
        if let Some(with_ns) = with_svg_namespace(text) {
            elements = parse(&with_ns)?;
        }
    }
    if elements.is_empty() {
        return Err(ShapeError::invalid(
            origin,
            format!(
                "no filled shape in the file: {}; basr paints filled paths, rects, polygons, \
                 circles and ellipses",
                why_nothing_filled(text)
            ),
        ));
    }
    Ok(Outline {
        origin: origin.to_string(),
        elements,
        metres_per_unit: None,
    })
}

/// The text with `xmlns="http://www.w3.org/2000/svg"` on its root `<svg>`
/// when that has no namespace; `None` when it has one or is no XML.
fn with_svg_namespace(text: &str) -> Option<String> {
    let doc = usvg::roxmltree::Document::parse(text).ok()?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" || root.tag_name().namespace().is_some() {
        return None;
    }
    let at = root.range().start + "<svg".len();
    let mut out = String::with_capacity(text.len() + 40);
    out.push_str(text.get(..at)?);
    out.push_str(" xmlns=\"http://www.w3.org/2000/svg\"");
    out.push_str(text.get(at..)?);
    Some(out)
}

/// Why usvg found nothing filled, from the XML: no shape element at all,
/// shapes only where nothing is drawn (`<defs>`, `<symbol>`, `<clipPath>`,
/// …, never placed with `<use>`), or shapes unfilled or hidden.
fn why_nothing_filled(text: &str) -> String {
    const SHAPES: [&str; 7] = [
        "path", "rect", "circle", "ellipse", "polygon", "polyline", "line",
    ];
    const UNDRAWN: [&str; 6] = ["defs", "symbol", "clipPath", "mask", "pattern", "marker"];
    let Ok(doc) = usvg::roxmltree::Document::parse(text) else {
        return "the file is not XML".into();
    };
    let shapes: Vec<_> = doc
        .descendants()
        .filter(|n| n.is_element() && SHAPES.contains(&n.tag_name().name()))
        .collect();
    if shapes.is_empty() {
        return "it holds no path, rect, circle, ellipse or polygon element".into();
    }
    let undrawn = |n: &usvg::roxmltree::Node| {
        n.ancestors()
            .any(|a| a.is_element() && UNDRAWN.contains(&a.tag_name().name()))
    };
    let uses = doc
        .descendants()
        .any(|n| n.is_element() && n.tag_name().name() == "use");
    if shapes.iter().all(undrawn) && !uses {
        return "its shapes are only inside <defs>, <symbol>, <clipPath> or the like, which \
                draw nothing by themselves: place them with <use href=\"#id\"/> or move them \
                out"
        .into();
    }
    "its shapes are unfilled (fill=\"none\"), hidden (display=\"none\", \
     visibility=\"hidden\", opacity 0) or of zero size: give the outline a fill"
        .into()
}

/// usvg (without its text feature) drops `<text>`; say so instead of
/// painting the rest of the file without it.
fn refuse_text(doc: &usvg::roxmltree::Document, origin: &str) -> Result<(), ShapeError> {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// An `<image>` is neither read from disk nor parsed: `/dev/zero` would
    /// read until memory ran out, and the embedded SVG (an arc of radius
    /// 3e38, percent-encoded) would run for minutes in usvg.
    #[test]
    fn images_are_not_loaded() {
        let bomb = "%3Csvg xmlns='http://www.w3.org/2000/svg'%3E%3Cpath \
                    d='M0 0 A3e38 3e38 0 1 1 1 0'/%3E%3C/svg%3E";
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">
               <image href="/dev/zero" width="5" height="5"/>
               <image xlink:href="data:image/svg+xml,{bomb}" width="5" height="5"/>
               <rect width="10" height="20"/></svg>"#
        );
        let outline = read_svg(&svg, "x.svg").unwrap();
        assert_eq!(outline.elements.len(), 1);
    }
}
