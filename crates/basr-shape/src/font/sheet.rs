//! The alphabet sheet: every glyph drawn with its outline, rungs and stroke order.

use svg::node::element::{Group, Line, Path, Rectangle, Text};
use svg::Document;

use super::{Font, GRID_HEIGHT, GRID_WIDTH};

/// Rungs drawn per stroke on the sheet.
pub(super) const SHEET_RUNGS: usize = 24;
/// Pixels per grid unit.
const SCALE: f64 = 10.0;
/// Glyphs per row.
const PER_ROW: usize = 9;

/// Stroke-order labels: font size, and the box one digit takes (pixels).
const LABEL_SIZE: f64 = 8.0;
const LABEL_DIGIT_W: f64 = 4.6;
const LABEL_H: f64 = 9.0;

/// Stroke fill colours, cycled by stroke index so neighbours differ.
const COLOURS: [&str; 6] = [
    "#f2c14e", "#7fb3d5", "#a3d9a5", "#f5a3a3", "#c9a3e6", "#f7cf9e",
];

pub(super) fn fmt(v: f64) -> String {
    format!("{v:.3}")
}

/// The sheet as an SVG document: one cell per glyph, on the 4 × 25 grid,
/// strokes filled in alternating colours with their rungs and a number at
/// each stroke's start.
pub fn alphabet_sheet(font: &Font) -> Document {
    let cell_w = (GRID_WIDTH + 3.0) * SCALE;
    let cell_h = (GRID_HEIGHT + 5.0) * SCALE;
    let n = font.glyphs().count().max(1);
    let rows = n.div_ceil(PER_ROW);
    let width = cell_w * PER_ROW.min(n) as f64;
    let height = cell_h * rows as f64 + 30.0;
    let mut doc = Document::new()
        .set("viewBox", (0.0, 0.0, width, height))
        .set("width", width)
        .set("height", height)
        .set("font-family", "sans-serif")
        .add(
            Rectangle::new()
                .set("width", width)
                .set("height", height)
                .set("fill", "white"),
        )
        .add(
            Text::new(format!(
                "font {} ({} glyphs) — outline, {} rungs per stroke, numbers give stroke order",
                font.name, n, SHEET_RUNGS
            ))
            .set("x", 8)
            .set("y", 20)
            .set("font-size", 13),
        );
    for (i, glyph) in font.glyphs().enumerate() {
        let ox = (i % PER_ROW) as f64 * cell_w + 1.5 * SCALE;
        let oy = 30.0 + (i / PER_ROW) as f64 * cell_h + 1.5 * SCALE;
        // Grid units → pixels, y up.
        let map = |p: kurbo::Point| (ox + p.x * SCALE, oy + (GRID_HEIGHT - p.y) * SCALE);
        let mut g = Group::new();
        g = g.add(
            Rectangle::new()
                .set("x", fmt(ox))
                .set("y", fmt(oy))
                .set("width", fmt(GRID_WIDTH * SCALE))
                .set("height", fmt(GRID_HEIGHT * SCALE))
                .set("fill", "none")
                .set("stroke", "#cccccc")
                .set("stroke-width", 0.5),
        );
        g = draw_strokes(g, &glyph.strokes, &map);
        g = g.add(
            Text::new(glyph.ch.to_string())
                .set("x", fmt(ox + 0.5 * GRID_WIDTH * SCALE))
                .set("y", fmt(oy + GRID_HEIGHT * SCALE + 2.8 * SCALE))
                .set("font-size", 16)
                .set("text-anchor", "middle"),
        );
        doc = doc.add(g);
    }
    doc
}

/// Each stroke filled (colours cycled), its rungs, and its number at its
/// start (or as near it as keeps clear of the numbers before), mapped to
/// pixels by `map`.
pub(super) fn draw_strokes(
    mut g: Group,
    strokes: &[super::Stroke],
    map: &impl Fn(kurbo::Point) -> (f64, f64),
) -> Group {
    // Stroke-order labels already placed: centre and half width (px).
    let mut labels: Vec<(f64, f64, f64)> = Vec::new();
    for (k, s) in strokes.iter().enumerate() {
        let outline = s.outline(80);
        let mut d = String::new();
        for (j, p) in outline.iter().enumerate() {
            let (x, y) = map(*p);
            d.push_str(&format!(
                "{}{} {} ",
                if j == 0 { "M" } else { "L" },
                fmt(x),
                fmt(y)
            ));
        }
        d.push('Z');
        g = g.add(
            Path::new()
                .set("d", d)
                .set("fill", COLOURS[k % COLOURS.len()])
                .set("stroke", "black")
                .set("stroke-width", 0.8),
        );
        for (a, b) in s.rungs(SHEET_RUNGS) {
            let (x1, y1) = map(a);
            let (x2, y2) = map(b);
            g = g.add(
                Line::new()
                    .set("x1", fmt(x1))
                    .set("y1", fmt(y1))
                    .set("x2", fmt(x2))
                    .set("y2", fmt(y2))
                    .set("stroke", "#555555")
                    .set("stroke-width", 0.4),
            );
        }
        // At the stroke's start, or as near it along the stroke as
        // keeps clear of the labels before (strokes that start where
        // another starts, as X's centre and arm, would print "25").
        let text = format!("{}", k + 1);
        let half_w = 0.5 * LABEL_DIGIT_W * text.len() as f64 + 1.0;
        let clear = |&(x, y): &(f64, f64)| {
            labels
                .iter()
                .all(|&(lx, ly, lw)| (x - lx).abs() >= half_w + lw || (y - ly).abs() >= LABEL_H)
        };
        let along: Vec<(f64, f64)> = s
            .rungs(4 * SHEET_RUNGS)
            .into_iter()
            .map(|(a, b)| map(a.midpoint(b)))
            .collect();
        let (x, y) = along.iter().copied().find(clear).unwrap_or(along[0]);
        labels.push((x, y, half_w));
        g = g.add(
            Text::new(text)
                .set("x", fmt(x))
                .set("y", fmt(y + 3.0))
                .set("font-size", LABEL_SIZE)
                .set("text-anchor", "middle")
                .set("fill", "#b00000"),
        );
    }
    g
}
