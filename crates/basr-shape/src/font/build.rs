//! From font source text to glyphs: parse, expand primitives, validate.

use std::collections::BTreeMap;

use kurbo::{Affine, Point, Vec2};
use toml::Spanned;

use super::spec::{FontSpec, Outline, PrimitiveSpec, SegmentSpec, TransformSpec};
use super::validate::{validate_glyph, DEFAULT_LIMITS};
use super::{Glyph, Stroke, GRID_HEIGHT, GRID_WIDTH};
use basr_geom::{Cardinal, Conic, Edge, GeomError, Segment};

/// What building found: the glyphs that built, and every problem.
pub struct Built {
    pub name: String,
    /// The grid's width (units): 4 for letters.
    pub grid_width: f64,
    pub glyphs: BTreeMap<char, Glyph>,
    pub problems: Vec<String>,
}

/// Turns byte offsets into `origin:line:col`.
pub struct Locator<'a> {
    pub(super) text: &'a str,
    pub(super) origin: &'a str,
    /// Byte offset of each line's start: every segment of a font names its
    /// place, and scanning the text from its start for each is quadratic
    /// (an imported shape has thousands of segments).
    line_starts: Vec<usize>,
}

impl<'a> Locator<'a> {
    pub fn new(text: &'a str, origin: &'a str) -> Locator<'a> {
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Locator {
            text,
            origin,
            line_starts,
        }
    }

    pub fn at(&self, offset: usize) -> String {
        // The line holding `offset`; `io::line_col` counts its column.
        let i = self.line_starts.partition_point(|&s| s <= offset).max(1) - 1;
        let start = self.line_starts[i];
        let (_, col) = basr_io::line_col(&self.text[start..], offset - start);
        format!("{}:{}:{col}", self.origin, i + 1)
    }

    /// A context string `origin:line:col: what` without its location, so a
    /// more precise location can be put in front.
    pub fn what<'c>(&self, ctx: &'c str) -> &'c str {
        let Some(rest) = ctx.strip_prefix(self.origin) else {
            return ctx;
        };
        let mut parts = rest.splitn(4, ':');
        match (parts.next(), parts.next(), parts.next(), parts.next()) {
            (Some(""), Some(l), Some(c), Some(tail))
                if l.chars().all(|d| d.is_ascii_digit())
                    && c.chars().all(|d| d.is_ascii_digit()) =>
            {
                tail.trim_start()
            }
            _ => ctx,
        }
    }
}

/// Coordinates beyond this (in the units a segment is written in) are a typo,
/// not a drawing: no font needs them, and near 1e154 lengths overflow.
const FAR_OFF: f64 = 1e6;
/// Widest grid a shape may have (units of a 25th of its height). assumed:
/// 40 heights, far wider than any lane holds at the smallest height.
const MAX_GRID_WIDTH: f64 = 1000.0;

pub fn build(text: &str, origin: &str) -> Built {
    build_checked(text, origin, true)
}

/// [`build`], with the glyphs' geometry checked (`validate_glyph`) only
/// when `geometry` is set: the embedded font, fixed at build time and
/// checked whole by a test, skips that (a tenth of a compile's time).
pub fn build_checked(text: &str, origin: &str, geometry: bool) -> Built {
    let loc = Locator::new(text, origin);
    let mut out = Built {
        name: String::new(),
        grid_width: GRID_WIDTH,
        glyphs: BTreeMap::new(),
        problems: vec![],
    };
    if text.trim().is_empty() {
        out.problems.push(format!(
            "{}: the font file is empty; a font needs `name`, `grid` and glyphs \
             (see the format notes at the top of fonts/basr.toml)",
            loc.at(0)
        ));
        return out;
    }
    let spec: FontSpec = match toml::from_str(text) {
        Ok(s) => s,
        Err(e) => {
            let offset = e.span().map(|s| s.start);
            let at = offset.map_or(origin.to_string(), |o| loc.at(o));
            // Which glyph and stroke the span is in: serde only knows the
            // field it was filling.
            let within = offset
                .and_then(|o| Outline::read(text)?.place(o))
                .map(|w| format!("{w}: "))
                .unwrap_or_default();
            out.problems.push(format!(
                "{at}: {within}{} (see the format notes at the top of fonts/basr.toml)",
                basr_io::one_line(e.message())
            ));
            return out;
        }
    };
    out.name = spec.name.get_ref().clone();
    if out.name.trim().is_empty() {
        out.problems.push(format!(
            "{}: the font needs a non-empty `name`",
            loc.at(spec.name.span().start)
        ));
    }
    let grid = spec.grid.get_ref();
    let mut limits = DEFAULT_LIMITS;
    // Letters use 4 × 25; an imported shape keeps the height of 25 (so the
    // letter height sizes it) and its own width.
    let width_ok = grid.width == GRID_WIDTH
        || (grid.width.is_finite() && grid.width > 0.0 && grid.width <= MAX_GRID_WIDTH);
    if !width_ok || grid.height != GRID_HEIGHT {
        out.problems.push(format!(
            "{}: grid is {} × {}; basr letters use the 4 × 25 grid of 001 §2.3 \
             (write `grid = {{ width = 4, height = 25 }}`; an imported shape keeps height 25 \
             and a width of at most {MAX_GRID_WIDTH})",
            loc.at(spec.grid.span().start),
            grid.width,
            grid.height
        ));
    } else {
        out.grid_width = grid.width;
        limits.frame = Some([grid.width, GRID_HEIGHT]);
    }
    match grid.min_rung {
        Some(r) if r.is_finite() && r > 0.0 => limits.min_rung = r,
        Some(r) => out.problems.push(format!(
            "{}: grid `min_rung = {r}` must be a positive number of units",
            loc.at(spec.grid.span().start)
        )),
        None => {}
    }

    let primitives = build_primitives(&spec.primitives, &loc, &mut out.problems);

    // Glyphs that copy another are built after the ones they copy.
    let mut order: Vec<(&Spanned<String>, &super::spec::GlyphSpec)> = spec.glyphs.iter().collect();
    order.sort_by_key(|(_, g)| g.copy.is_some());
    for (key, g) in order {
        let gat = loc.at(key.span().start);
        let key = key.get_ref();
        let mut chars = key.chars();
        let ch = match (chars.next(), chars.next()) {
            (Some(c), None) if c.is_ascii_uppercase() || c.is_ascii_digit() => c,
            _ => {
                out.problems.push(format!(
                    "{gat}: glyph `{key}`: a glyph key must be one capital letter or digit \
                     (lower case is drawn with the capitals; space is left to layout)"
                ));
                continue;
            }
        };
        let before = out.problems.len();
        let mut strokes: Vec<(String, Stroke)> = Vec::new();
        match (&g.copy, g.strokes.is_empty()) {
            (Some(src), true) => {
                let at = loc.at(src.span().start);
                let found = src
                    .get_ref()
                    .chars()
                    .next()
                    .filter(|_| src.get_ref().chars().count() == 1)
                    .and_then(|c| out.glyphs.get(&c));
                let Some(found) = found else {
                    out.problems.push(format!(
                        "{at}: glyph '{ch}': `copy = \"{}\"` names no valid glyph of this font \
                         (a copied glyph must itself have strokes)",
                        src.get_ref()
                    ));
                    continue;
                };
                let ctx = format!("{at}: glyph '{ch}'");
                let Some(m) = transform(&g.transform, &loc, &ctx, &mut out.problems) else {
                    continue;
                };
                for (i, s) in found.strokes.iter().enumerate() {
                    strokes.push((
                        format!("{ctx} stroke {} (copied)", i + 1),
                        s.transformed(&m),
                    ));
                }
            }
            (None, false) => {
                if !g.transform.is_empty() {
                    out.problems.push(format!(
                        "{gat}: glyph '{ch}': a glyph-level `transform` goes with `copy`; \
                         put it on each stroke instead"
                    ));
                    continue;
                }
                for (i, s) in g.strokes.iter().enumerate() {
                    let ctx = format!("{}: glyph '{ch}' stroke {}", loc.at(s.span().start), i + 1);
                    if let Some(st) = stroke(
                        s.get_ref(),
                        &primitives,
                        &spec.primitives,
                        &loc,
                        &ctx,
                        &mut out.problems,
                    ) {
                        strokes.push((ctx, st));
                    }
                }
            }
            _ => {
                out.problems.push(format!(
                    "{gat}: glyph '{ch}' needs either `strokes` or `copy = \"OTHER\"`, not both \
                     and not neither"
                ));
                continue;
            }
        }
        if geometry && out.problems.len() == before {
            out.problems.extend(validate_glyph(&strokes, &limits));
        }
        if out.problems.len() == before {
            let strokes = strokes.into_iter().map(|(_, s)| s).collect();
            out.glyphs.insert(ch, Glyph { ch, strokes });
        }
    }
    out
}

/// Primitives: stroke templates in their own coordinates, by name.
pub(super) fn build_primitives<'s>(
    specs: &'s BTreeMap<String, Spanned<PrimitiveSpec>>,
    loc: &Locator,
    problems: &mut Vec<String>,
) -> BTreeMap<&'s str, Stroke> {
    let mut primitives: BTreeMap<&str, Stroke> = BTreeMap::new();
    for (name, p) in specs {
        let ctx = format!("{}: primitive `{name}`", loc.at(p.span().start));
        let p = p.get_ref();
        let left = edge(&p.left, loc, &format!("{ctx} left edge"), problems);
        let right = edge(&p.right, loc, &format!("{ctx} right edge"), problems);
        if let (Some(left), Some(right)) = (left, right) {
            primitives.insert(name.as_str(), Stroke { left, right });
        }
    }
    primitives
}

/// One stroke of a glyph or symbol: a placed primitive or explicit edges,
/// with its transform and direction applied.
pub(super) fn stroke(
    s: &super::spec::StrokeSpec,
    primitives: &BTreeMap<&str, Stroke>,
    specs: &BTreeMap<String, Spanned<PrimitiveSpec>>,
    loc: &Locator,
    ctx: &str,
    problems: &mut Vec<String>,
) -> Option<Stroke> {
    let base = match (&s.primitive, &s.left, &s.right) {
        (Some(name), None, None) => match primitives.get(name.get_ref().as_str()) {
            Some(p) => p.clone(),
            None => {
                let known: Vec<&str> = specs.keys().map(|k| k.as_str()).collect();
                let why = if specs.contains_key(name.get_ref()) {
                    "is itself invalid (see its own error)".to_string()
                } else {
                    format!("is unknown; the font defines: {}", known.join(", "))
                };
                problems.push(format!(
                    "{}: {}: primitive `{}` {why}",
                    loc.at(name.span().start),
                    loc.what(ctx),
                    name.get_ref()
                ));
                return None;
            }
        },
        (None, Some(l), Some(r)) => {
            let left = edge(l, loc, &format!("{ctx} left edge"), problems);
            let right = edge(r, loc, &format!("{ctx} right edge"), problems);
            Stroke {
                left: left?,
                right: right?,
            }
        }
        _ => {
            problems.push(format!(
                "{ctx}: a stroke is either `primitive = \"NAME\"` (with an optional `transform`) \
                 or explicit `left` and `right` edges"
            ));
            return None;
        }
    };
    let m = transform(&s.transform, loc, ctx, problems)?;
    let placed = base.transformed(&m);
    Some(if s.reverse { placed.reversed() } else { placed })
}

fn edge(
    segs: &[Spanned<SegmentSpec>],
    loc: &Locator,
    ctx: &str,
    problems: &mut Vec<String>,
) -> Option<Edge> {
    let mut out: Vec<Segment> = Vec::new();
    let mut starts: Vec<usize> = Vec::new(); // source offset of each built segment
    let mut ok = true;
    for (i, s) in segs.iter().enumerate() {
        let sctx = format!(
            "{}: {} segment {}",
            loc.at(s.span().start),
            loc.what(ctx),
            i + 1
        );
        match segment(s.get_ref(), loc, &sctx, problems) {
            Some(v) => {
                if let Some(p) = v
                    .iter()
                    .flat_map(control_points)
                    .find(|p| p.is_finite() && (p.x.abs() > FAR_OFF || p.y.abs() > FAR_OFF))
                {
                    problems.push(format!(
                        "{sctx}: reaches ({}, {}), far off the 4 × 25 grid (x 0..4, y 0..25)",
                        short(p.x),
                        short(p.y)
                    ));
                    ok = false;
                    continue;
                }
                for seg in v {
                    out.push(seg);
                    starts.push(s.span().start);
                }
            }
            None => ok = false,
        }
    }
    if !ok {
        return None;
    }
    match Edge::new(out) {
        Ok(e) => Some(e),
        Err(e) => {
            let at = match &e {
                GeomError::Gap { index, .. }
                | GeomError::Degenerate { index }
                | GeomError::NotFinite { index }
                | GeomError::TooLong { index } => starts.get(*index).map(|&o| loc.at(o)),
                GeomError::Empty => None,
            };
            let fix = match &e {
                GeomError::Gap { .. } => " (make each segment start where the previous one ends)",
                GeomError::Degenerate { .. } => " (give the segment distinct ends)",
                _ => "",
            };
            match at {
                Some(at) => problems.push(format!("{at}: {}: {e}{fix}", loc.what(ctx))),
                None => problems.push(format!("{ctx}: {e}")),
            }
            None
        }
    }
}

/// A coordinate as written, in exponent form when huge (`{}` would print
/// all 300 digits of 1e300).
fn short(v: f64) -> String {
    if v.abs() < FAR_OFF {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The points that define a segment (every curve lies in their hull, up to
/// the cardinal's tangent points).
fn control_points(seg: &Segment) -> Vec<Point> {
    match seg {
        Segment::Line(l) => vec![l.p0, l.p1],
        Segment::Cardinal(c) => c.points().to_vec(),
        Segment::Conic(c) => vec![c.p0, c.p1, c.p2],
    }
}

fn pt(p: [f64; 2]) -> Point {
    Point::new(p[0], p[1])
}

fn segment(
    s: &SegmentSpec,
    loc: &Locator,
    ctx: &str,
    problems: &mut Vec<String>,
) -> Option<Vec<Segment>> {
    let kinds = [
        s.line.is_some(),
        s.cardinal.is_some(),
        s.arc.is_some(),
        s.conic.is_some(),
    ];
    if kinds.iter().filter(|&&k| k).count() != 1 {
        problems.push(format!(
            "{ctx}: a segment needs exactly one of `line`, `cardinal`, `arc`, `conic`"
        ));
        return None;
    }
    if (s.tension.is_some() || s.t.is_some()) && s.cardinal.is_none() {
        problems.push(format!(
            "{ctx}: `tension` and `t` belong to a `cardinal` segment"
        ));
        return None;
    }
    if s.weight.is_some() && s.conic.is_none() {
        problems.push(format!("{ctx}: `weight` belongs to a `conic` segment"));
        return None;
    }
    let mut v: Vec<Segment> = if let Some([a, b]) = s.line {
        vec![Segment::line(pt(a), pt(b))]
    } else if let Some(p) = s.cardinal {
        let tension = s.tension.unwrap_or(1.0); // 001 app. A uses a = 1 throughout
        let t = s.t.unwrap_or([0.0, 1.0]);
        if !(0.0..=1.0).contains(&t[0]) || !(0.0..=1.0).contains(&t[1]) || t[0] >= t[1] {
            problems.push(format!(
                "{ctx}: `t = [{}, {}]` must satisfy 0 ≤ t0 < t1 ≤ 1",
                t[0], t[1]
            ));
            return None;
        }
        if !(tension.is_finite() && tension > 0.0) {
            problems.push(format!("{ctx}: `tension` must be a positive number"));
            return None;
        }
        vec![Segment::Cardinal(Cardinal::with_range(
            p.map(pt),
            tension,
            (t[0], t[1]),
        ))]
    } else if let Some(a) = &s.arc {
        let sweep = (a.to_deg - a.from_deg).abs();
        if !(a.radii[0] > 0.0 && a.radii[1] > 0.0 && sweep > 0.0 && sweep <= 360.0) {
            problems.push(format!(
                "{ctx}: an arc needs positive radii and a sweep of 0–360° (from_deg ≠ to_deg)"
            ));
            return None;
        }
        Conic::elliptical_arc(
            pt(a.center),
            Vec2::new(a.radii[0], a.radii[1]),
            a.from_deg.to_radians(),
            a.to_deg.to_radians(),
        )
        .into_iter()
        .map(Segment::Conic)
        .collect()
    } else if let Some([p0, p1, p2]) = s.conic {
        let w = s.weight.unwrap_or(1.0);
        if !(w.is_finite() && w > 0.0) {
            problems.push(format!("{ctx}: a conic's `weight` must be positive"));
            return None;
        }
        vec![Segment::Conic(Conic::new(pt(p0), pt(p1), pt(p2), w))]
    } else {
        return None;
    };
    let m = transform(&s.transform, loc, ctx, problems)?;
    v = v.iter().map(|seg| seg.transformed(&m)).collect();
    if s.reverse {
        v = v.iter().rev().map(|seg| seg.reversed()).collect();
    }
    Some(v)
}

/// The composed placement (steps applied in the order written).
pub(super) fn transform(
    steps: &[Spanned<TransformSpec>],
    loc: &Locator,
    ctx: &str,
    problems: &mut Vec<String>,
) -> Option<Affine> {
    let mut m = Affine::IDENTITY;
    for (k, step) in steps.iter().enumerate() {
        let t = step.get_ref();
        let options = [
            t.translate.map(|[dx, dy]| Affine::translate((dx, dy))),
            t.scale.map(|[sx, sy]| Affine::scale_non_uniform(sx, sy)),
            t.rotate_deg.map(|d| Affine::rotate(d.to_radians())),
            t.mirror_x
                .map(|c| Affine::new([-1.0, 0.0, 0.0, 1.0, 2.0 * c, 0.0])),
            t.mirror_y
                .map(|c| Affine::new([1.0, 0.0, 0.0, -1.0, 0.0, 2.0 * c])),
            t.rotate180
                .map(|[cx, cy]| Affine::new([-1.0, 0.0, 0.0, -1.0, 2.0 * cx, 2.0 * cy])),
            t.shear_x.map(|k| Affine::new([1.0, 0.0, k, 1.0, 0.0, 0.0])),
        ];
        let given: Vec<Affine> = options.into_iter().flatten().collect();
        if given.len() != 1 {
            problems.push(format!(
                "{}: {}: each transform step needs exactly one of translate, scale, \
                 rotate_deg, mirror_x, mirror_y, rotate180, shear_x",
                loc.at(step.span().start),
                loc.what(ctx)
            ));
            return None;
        }
        let step_m = given[0];
        let why = if !step_m.is_finite() {
            Some("has a non-finite value (nan or inf); write a finite number")
        } else if step_m.determinant().abs() < 1e-12 {
            Some("collapses the plane (a zero scale?)")
        } else if !(step_m * m).is_finite() {
            Some("overflows: with the steps before it, the placement is not finite")
        } else {
            None
        };
        if let Some(why) = why {
            problems.push(format!(
                "{}: {}: transform step {} {why}",
                loc.at(step.span().start),
                loc.what(ctx),
                k + 1
            ));
            return None;
        }
        m = step_m * m;
    }
    Some(m)
}

#[cfg(test)]
mod tests {
    use super::Locator;

    #[test]
    fn locator_names_the_place_io_line_col_does() {
        let text = "a = 1\n\nb = \"é\"\nc = 2";
        let loc = Locator::new(text, "f.toml");
        for offset in 0..text.len() + 3 {
            let (line, col) = basr_io::line_col(text, offset);
            assert_eq!(
                loc.at(offset),
                format!("f.toml:{line}:{col}"),
                "offset {offset}"
            );
        }
    }
}
