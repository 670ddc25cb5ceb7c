//! Placed items → placed strokes: every letter and symbol of a marking as
//! strokes in the road frame (SPEC §2), with a label for messages and the
//! job's `layout.glyphs`. This is the value the planner starts from.
//!
//! Takes a [`Marking`] (lines of words) or a [`Scene`] (items), the font and
//! the symbol library; refuses a scene whose items leave the lane or overlap,
//! or name a symbol the library lacks; applies the MUTCD rules
//! (`layout::rules`): errors refuse, warnings travel with the result.

use std::path::Path;

use basr_job::OwnerKind;
use kurbo::{Affine, Point};

use super::rules::{self, RuleItem};
use super::scene::{Item, ItemKind, Scene, ShapeSize};
use super::{
    place, GlyphBox, LayoutError, Marking, DEFAULT_LETTER_SPACING_UNITS, GRID_HEIGHT_UNITS,
    MIN_LINE_GAP_HEIGHTS,
};
use crate::font::{overlap_area, Font, Glyph, Library, Stroke, SYMBOL_LIMITS};

/// One letter or symbol on the road: its strokes in painting order.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedMark {
    /// The letter ("S") or symbol name ("stop-line"): `layout.glyphs[].char`.
    pub label: String,
    /// Message line (lines) or item index (scenes), 0 first.
    pub line: usize,
    /// A letter, a symbol or a shape, for messages.
    pub kind: OwnerKind,
    /// A letter's height (m); `None` for a symbol or a shape.
    pub letter_height_m: Option<f64>,
    /// Road frame, metres.
    pub strokes: Vec<Stroke>,
}

/// A laid-out marking: what the planner paints, and notes for a person.
#[derive(Clone, Debug, PartialEq)]
pub struct Laid {
    pub marks: Vec<PlacedMark>,
    pub warnings: Vec<String>,
    /// The job's `message` (lines, or a scene's items, joined with `\n`).
    pub message: String,
    pub letter_height_m: f64,
    pub lane_width_m: f64,
    /// The road surface the marking file describes.
    pub road: basr_job::Road,
}

/// Lay out a message or a `lines` marking file.
pub fn lay_marking(m: &Marking, font: &Font, low_speed: bool) -> Result<Laid, LayoutError> {
    let placed = place(m, |ch| {
        font.glyph(ch).map(|g| glyph_box(g, font.grid_width))
    })?;
    let mut marks = vec![];
    for l in &placed.letters {
        let Some(g) = font.glyph(l.ch) else {
            continue; // place() has already refused letters without a glyph
        };
        let s = l.scale_m;
        let to_road = Affine::new([s, 0.0, 0.0, s, l.origin_m[0], l.origin_m[1]]);
        marks.push(PlacedMark {
            label: l.ch.to_string(),
            line: l.line,
            kind: OwnerKind::Letter,
            letter_height_m: Some(m.letter_height_m),
            strokes: g
                .strokes
                .iter()
                .map(|st| st.transformed(&to_road))
                .collect(),
        });
    }
    let words: Vec<RuleItem> = m
        .lines
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let (lo, hi) = extent(marks.iter().filter(|k| k.line == i));
            RuleItem {
                index: i,
                label: format!("line {} ({w})", i + 1),
                word: Some(w.clone()),
                symbol: None,
                letter_height_m: m.letter_height_m,
                scale: 1.0,
                y: [lo.y, hi.y],
            }
        })
        .collect();
    let mut warnings = placed.warnings;
    // Line gaps of a message are checked by place() with the gap it was given.
    warnings.extend(apply(rules::check(&words, low_speed, false, false))?);
    Ok(Laid {
        marks,
        warnings,
        message: m.message(),
        letter_height_m: m.letter_height_m,
        lane_width_m: m.lane_width_m,
        road: m.road.clone(),
    })
}

/// A scene's shape item decomposed into strokes: the shape's frame (its
/// lower-left corner at the origin, metres, y up = along the traffic).
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeStrokes {
    pub strokes: Vec<Stroke>,
    pub width_m: f64,
    pub height_m: f64,
}

/// Imports a shape item's file at its size (`plan::shapes::importer`: the
/// decomposition needs the robot's fan, which the layout does not know);
/// the error says what is wrong with the file and how to fix it.
pub type ShapeImport<'a> = &'a dyn Fn(&Path, ShapeSize) -> Result<ShapeStrokes, ShapeItemError>;

/// Why a scene's shape item could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum ShapeItemError {
    /// The layout was asked without an importer (it has no robot).
    #[error(
        "shape items are imported by `basr compile` and `basr check`; this caller has no \
         shapes importer"
    )]
    NoImporter,
    /// The robot whose fan the shape is decomposed for cannot be read.
    #[error(transparent)]
    Robot(#[from] basr_robot::RobotError),
    /// The file is no shape basr can paint, or not at that size.
    #[error(transparent)]
    Import(#[from] crate::ShapeError),
}

/// The importer of a layout without a robot: refuses shape items.
pub(super) fn no_shapes(_: &Path, _: ShapeSize) -> Result<ShapeStrokes, ShapeItemError> {
    Err(ShapeItemError::NoImporter)
}

/// Lay out a scene without shape items (see [`lay_scene_with`]).
pub fn lay_scene(s: &Scene, font: &Font, lib: &Library) -> Result<Laid, LayoutError> {
    lay_scene_with(s, font, lib, &no_shapes)
}

/// Lay out a scene: each item placed and turned, then lane, overlap and
/// MUTCD checks over all of them. `shapes` imports shape items.
pub fn lay_scene_with(
    s: &Scene,
    font: &Font,
    lib: &Library,
    shapes: ShapeImport,
) -> Result<Laid, LayoutError> {
    let mut marks: Vec<PlacedMark> = vec![];
    let mut rule_items = vec![];
    for (i, item) in s.items.iter().enumerate() {
        let placed = item_marks(i, item, font, lib, shapes)?;
        let (lo, hi) = extent(placed.iter());
        check_lane(i, item, lo, hi, s.lane_width_m)?;
        let (word, symbol, h, scale) = match &item.kind {
            ItemKind::Word {
                text,
                letter_height_m,
            } => (Some(text.clone()), None, *letter_height_m, 1.0),
            ItemKind::Symbol { name, scale } => (None, Some(name.clone()), 0.0, *scale),
            ItemKind::Shape { .. } => (None, None, 0.0, 1.0),
        };
        rule_items.push(RuleItem {
            index: i,
            label: format!("item {} ({})", i + 1, item.label()),
            word,
            symbol,
            letter_height_m: h,
            scale,
            y: [lo.y, hi.y],
        });
        marks.extend(placed);
    }
    check_overlaps(&marks, s)?;
    let warnings = apply(rules::check(&rule_items, s.low_speed, s.turn_lane, true))?;
    let letter_height_m = s
        .items
        .iter()
        .find_map(|i| match &i.kind {
            ItemKind::Word {
                letter_height_m, ..
            } => Some(*letter_height_m),
            _ => None,
        })
        .unwrap_or(s.letter_height_m);
    Ok(Laid {
        marks,
        warnings,
        message: s.message(),
        letter_height_m,
        lane_width_m: s.lane_width_m,
        road: s.road.clone(),
    })
}

/// Errors refuse the layout (the first, with how many more); warnings pass.
fn apply(findings: Vec<rules::Finding>) -> Result<Vec<String>, LayoutError> {
    let (errors, warnings): (Vec<_>, Vec<_>) = findings.into_iter().partition(|f| f.error);
    if let Some(first) = errors.first() {
        return Err(LayoutError::Rule {
            message: first.to_string(),
            more: errors.len() - 1,
        });
    }
    Ok(warnings.iter().map(|w| w.to_string()).collect())
}

/// The item's marks in the road frame: its own frame turned about its
/// anchor by `rotate_rad`, then moved to `at_m`.
fn item_marks(
    i: usize,
    item: &Item,
    font: &Font,
    lib: &Library,
    shapes: ShapeImport,
) -> Result<Vec<PlacedMark>, LayoutError> {
    let to_road = Affine::translate((item.at_m[0], item.at_m[1])) * Affine::rotate(item.rotate_rad);
    match &item.kind {
        ItemKind::Word {
            text,
            letter_height_m,
        } => {
            let h = *letter_height_m;
            let m = Marking {
                lines: vec![text.clone()],
                letter_height_m: h,
                letter_spacing_m: DEFAULT_LETTER_SPACING_UNITS * h / GRID_HEIGHT_UNITS,
                // The lane is checked on the placed item, turned.
                lane_width_m: f64::INFINITY,
                line_gap_m: MIN_LINE_GAP_HEIGHTS * h,
                anchor_x_m: 0.0,
                anchor_y_m: 0.0,
                road: basr_job::Road::default(),
            };
            let laid = lay_marking(&m, font, true)?;
            Ok(laid
                .marks
                .into_iter()
                .map(|mk| PlacedMark {
                    kind: OwnerKind::Letter,
                    letter_height_m: Some(h),
                    line: i,
                    strokes: mk.strokes.iter().map(|s| s.transformed(&to_road)).collect(),
                    label: mk.label,
                })
                .collect())
        }
        ItemKind::Symbol { name, scale } => {
            let sym = lib.get(name).ok_or_else(|| LayoutError::UnknownSymbol {
                item: i + 1,
                name: name.clone(),
                nearest: lib.nearest(name).join(", "),
            })?;
            let m = to_road * Affine::scale(*scale);
            Ok(vec![PlacedMark {
                // The library's spelling (`--symbol RXR` paints `rxr`).
                label: sym.name.clone(),
                line: i,
                kind: OwnerKind::Symbol,
                letter_height_m: None,
                strokes: sym.strokes.iter().map(|s| s.transformed(&m)).collect(),
            }])
        }
        ItemKind::Shape { path, size } => {
            let s = shapes(path, *size).map_err(|e| LayoutError::Shape {
                item: i + 1,
                path: path.display().to_string(),
                message: e.to_string(),
            })?;
            // The shape's near edge centred on its anchor (SPEC §5).
            let m = to_road * Affine::translate((-0.5 * s.width_m, 0.0));
            let label = path.file_stem().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into(),
            );
            Ok(vec![PlacedMark {
                label,
                line: i,
                kind: OwnerKind::Shape,
                letter_height_m: None,
                strokes: s.strokes.iter().map(|st| st.transformed(&m)).collect(),
            }])
        }
    }
}

/// Every item within the lane (|x| ≤ half its width). MUTCD 11th §3B.20 ¶08
/// (R7): a marking is at most one lane wide, except SCHOOL, which may span
/// two approach lanes (§7C.02 ¶01, R14): it may reach half a lane past
/// either edge.
fn check_lane(i: usize, item: &Item, lo: Point, hi: Point, lane: f64) -> Result<(), LayoutError> {
    let school = matches!(&item.kind, ItemKind::Word { text, .. } if text == "SCHOOL");
    let half = if school { lane } else { 0.5 * lane };
    let reach = lo.x.abs().max(hi.x.abs());
    // 1 µm: round-off of a symbol exactly as wide as the lane.
    if reach > half + 1e-6 {
        let x = if hi.x.abs() >= lo.x.abs() { hi.x } else { lo.x };
        return Err(LayoutError::OutsideLane {
            item: i + 1,
            label: item.label(),
            x_m: x,
            by_m: reach - half,
            lane_m: lane,
            school,
        });
    }
    Ok(())
}

/// No two items paint the same area (SPEC §5): stroke pairs of different
/// items whose boxes meet are measured.
fn check_overlaps(marks: &[PlacedMark], s: &Scene) -> Result<(), LayoutError> {
    let boxes: Vec<Vec<(Point, Point)>> = marks
        .iter()
        .map(|m| m.strokes.iter().map(extent_of).collect())
        .collect();
    for a in 0..marks.len() {
        for b in a + 1..marks.len() {
            if marks[a].line == marks[b].line {
                continue; // one item: the library and the font keep it clean
            }
            for (sa, ba) in marks[a].strokes.iter().zip(&boxes[a]) {
                for (sb, bb) in marks[b].strokes.iter().zip(&boxes[b]) {
                    let meet =
                        ba.0.x < bb.1.x && bb.0.x < ba.1.x && ba.0.y < bb.1.y && bb.0.y < ba.1.y;
                    if !meet {
                        continue;
                    }
                    let area = overlap_area(sa, sb, &SYMBOL_LIMITS);
                    if area > SYMBOL_LIMITS.overlap_area {
                        let (ia, ib) = (marks[a].line, marks[b].line);
                        return Err(LayoutError::Overlap {
                            a: format!("item {} ({})", ia + 1, s.items[ia].label()),
                            b: format!("item {} ({})", ib + 1, s.items[ib].label()),
                            area_m2: area,
                        });
                    }
                }
            }
        }
    }
    Ok(())
}

fn extent_of(s: &Stroke) -> (Point, Point) {
    crate::font::extent(std::iter::once(s))
}

/// Corners of the marks' strokes (zero box when there are none).
fn extent<'a>(marks: impl Iterator<Item = &'a PlacedMark>) -> (Point, Point) {
    let (lo, hi) = crate::font::extent(marks.flat_map(|m| m.strokes.iter()));
    if lo.x.is_finite() {
        (lo, hi)
    } else {
        (Point::ORIGIN, Point::ORIGIN)
    }
}

/// A glyph's extent on the grid: the font's grid width (4 for letters, an
/// imported shape's own), and the lowest and highest points of its strokes' edges.
pub fn glyph_box(g: &Glyph, width: f64) -> GlyphBox {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in &g.strokes {
        for e in [&s.left, &s.right] {
            for p in e.sample(65) {
                lo = lo.min(p.y);
                hi = hi.max(p.y);
            }
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return GlyphBox::GRID;
    }
    GlyphBox {
        width,
        y_min: lo,
        y_max: hi,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::Overrides;
    use proptest::prelude::*;

    fn one(symbol: &str, at: [f64; 2], rot_deg: f64) -> Scene {
        let text = format!(
            "[[item]]\nsymbol = \"{symbol}\"\nat_m = [{}, {}]\nrotate_deg = {rot_deg}\n",
            at[0], at[1]
        );
        Scene::from_toml(&text, "p.toml", &Overrides::default()).unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// Placing keeps a symbol's painted area and never lets a placed
        /// item out of the lane: either every point is inside or the
        /// layout is refused, by the amount the farthest point is out.
        #[test]
        fn placed_items_stay_in_the_lane_or_are_refused(
            i in 0usize..18, x in -2.0f64..2.0, y in -5.0f64..5.0, rot in -180.0f64..180.0
        ) {
            let lib = Library::embedded();
            let sym = lib.symbols().nth(i).unwrap();
            let s = one(&sym.name, [x, y], rot);
            let half = 0.5 * s.lane_width_m;
            match lay_scene(&s, Font::embedded(), lib) {
                Ok(laid) => {
                    let (lo, hi) = extent(laid.marks.iter());
                    prop_assert!(lo.x >= -half - 1e-6 && hi.x <= half + 1e-6);
                    let area: f64 = laid.marks.iter().flat_map(|m| &m.strokes)
                        .map(crate::font::stroke_area).sum();
                    prop_assert!((area - sym.area_m2()).abs() < 1e-6 * sym.area_m2().max(1.0));
                }
                Err(LayoutError::OutsideLane { by_m, x_m, .. }) => {
                    prop_assert!(by_m > 0.0);
                    prop_assert!((x_m.abs() - half - by_m).abs() < 1e-9);
                }
                Err(e) => prop_assert!(false, "{e}"),
            }
        }
    }

    #[test]
    fn items_that_share_paint_are_refused_both_named() {
        let text = "[[item]]\nsymbol = \"stop-line\"\nat_m = [0, 0]\n\
                    [[item]]\nword = \"SLOW\"\nat_m = [0, 0.5]\n";
        let s = Scene::from_toml(text, "o.toml", &Overrides::default()).unwrap();
        let e = lay_scene(&s, Font::embedded(), Library::embedded()).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("item 1 (symbol stop-line) and item 2 (word SLOW) overlap"),
            "{e}"
        );
        // Clear of the line (S and O dip 0.02 m below their grids) is fine.
        let text = text.replace("[0, 0.5]", "[0, 0.65]");
        let s = Scene::from_toml(&text, "o.toml", &Overrides::default()).unwrap();
        let laid = lay_scene(&s, Font::embedded(), Library::embedded());
        assert!(laid.is_ok(), "{laid:?}");
    }
}
