//! The symbol sheet: every library symbol drawn to one scale with its
//! strokes, rungs, stroke order and overall dimensions.

use svg::node::element::{Group, Line, Rectangle, Text};
use svg::Document;

use super::sheet::{draw_strokes, fmt, SHEET_RUNGS};
use super::{Library, Symbol};

/// Pixels per metre: the 16 ft RXR symbol is 300 px tall.
const PX_PER_M: f64 = 60.0;
/// Sheet width the cells wrap at (px).
const SHEET_W: f64 = 1500.0;
/// Room around a symbol in its cell: left, top (name), right (length), bottom (width), px.
const PAD: [f64; 4] = [20.0, 34.0, 86.0, 44.0];
const M_PER_FT: f64 = 0.3048;

/// "8 ft 0 in (2.44 m)", to the nearest inch.
pub fn feet_inches(m: f64) -> String {
    let inches = (m / M_PER_FT * 12.0).round() as i64;
    format!("{} ft {} in ({m:.2} m)", inches / 12, inches % 12)
}

fn dim_line(g: Group, a: (f64, f64), b: (f64, f64)) -> Group {
    let tick = |g: Group, p: (f64, f64), vertical: bool| {
        let (dx, dy) = if vertical { (4.0, 0.0) } else { (0.0, 4.0) };
        g.add(
            Line::new()
                .set("x1", fmt(p.0 - dx))
                .set("y1", fmt(p.1 - dy))
                .set("x2", fmt(p.0 + dx))
                .set("y2", fmt(p.1 + dy))
                .set("stroke", "#2060a0")
                .set("stroke-width", 1),
        )
    };
    let vertical = (a.0 - b.0).abs() < 1e-9;
    let g = g.add(
        Line::new()
            .set("x1", fmt(a.0))
            .set("y1", fmt(a.1))
            .set("x2", fmt(b.0))
            .set("y2", fmt(b.1))
            .set("stroke", "#2060a0")
            .set("stroke-width", 0.8),
    );
    tick(tick(g, a, vertical), b, vertical)
}

fn label(text: String, x: f64, y: f64, size: f64, anchor: &str, colour: &str) -> Text {
    Text::new(text)
        .set("x", fmt(x))
        .set("y", fmt(y))
        .set("font-size", size)
        .set("text-anchor", anchor.to_string())
        .set("fill", colour.to_string())
}

/// One symbol's cell at (ox, oy); returns the group.
fn cell(s: &Symbol, ox: f64, oy: f64) -> Group {
    let [w, l] = s.size_m;
    let x0 = ox + PAD[0];
    let y0 = oy + PAD[1];
    // Symbol frame (x across, centred; y along from 0) → pixels, y up.
    let map = |p: kurbo::Point| (x0 + (p.x + 0.5 * w) * PX_PER_M, y0 + (l - p.y) * PX_PER_M);
    let mut g = Group::new().add(
        Rectangle::new()
            .set("x", fmt(x0))
            .set("y", fmt(y0))
            .set("width", fmt(w * PX_PER_M))
            .set("height", fmt(l * PX_PER_M))
            .set("fill", "none")
            .set("stroke", "#cccccc")
            .set("stroke-width", 0.5),
    );
    g = draw_strokes(g, &s.strokes, &map);
    let assumed = if s.assumed.is_some() { " *" } else { "" };
    g = g.add(label(
        format!("{}{assumed}", s.name),
        x0,
        oy + 16.0,
        13.0,
        "start",
        "black",
    ));
    g = g.add(label(
        format!("{} strokes, {:.2} m²", s.strokes.len(), s.area_m2()),
        x0,
        oy + 28.0,
        9.0,
        "start",
        "#555555",
    ));
    // Width under the symbol, length to its right.
    let by = y0 + l * PX_PER_M + 12.0;
    g = dim_line(g, (x0, by), (x0 + w * PX_PER_M, by));
    g = g.add(label(
        feet_inches(w),
        x0 + 0.5 * w * PX_PER_M,
        by + 14.0,
        9.0,
        "middle",
        "#2060a0",
    ));
    let rx = x0 + w * PX_PER_M + 10.0;
    g = dim_line(g, (rx, y0), (rx, y0 + l * PX_PER_M));
    g.add(label(
        feet_inches(l),
        rx + 6.0,
        y0 + 0.5 * l * PX_PER_M,
        9.0,
        "start",
        "#2060a0",
    ))
}

/// The library sheet: one cell per symbol, in name order, wrapped into rows.
pub fn symbol_sheet(lib: &Library) -> Document {
    let mut cells = vec![];
    let (mut x, mut y, mut row_h) = (0.0_f64, 40.0_f64, 0.0_f64);
    for s in lib.symbols() {
        let cw = PAD[0] + s.size_m[0] * PX_PER_M + PAD[2];
        let ch = PAD[1] + s.size_m[1] * PX_PER_M + PAD[3];
        if x > 0.0 && x + cw > SHEET_W {
            x = 0.0;
            y += row_h;
            row_h = 0.0;
        }
        cells.push(cell(s, x, y));
        x += cw;
        row_h = row_h.max(ch);
    }
    let height = y + row_h + 10.0;
    let n = lib.symbols().count();
    let mut doc = Document::new()
        .set("viewBox", (0.0, 0.0, SHEET_W, height))
        .set("width", SHEET_W)
        .set("height", height)
        .set("font-family", "sans-serif")
        .add(
            Rectangle::new()
                .set("width", SHEET_W)
                .set("height", height)
                .set("fill", "white"),
        )
        .add(label(
            format!(
                "symbol library {} ({n} symbols), {PX_PER_M} px per metre: strokes filled, \
                 {SHEET_RUNGS} rungs per stroke, red numbers give painting order, blue lines \
                 the overall size; * = dimensions assumed (see `basr symbols`)",
                lib.name
            ),
            8.0,
            22.0,
            13.0,
            "start",
            "black",
        ));
    for c in cells {
        doc = doc.add(c);
    }
    doc
}
