//! # basr-plot
//!
//! SVG drawing. Imports `basr-io` only. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! SVG drawing shared by glyphs, preview, simulate and workspace: a road →
//! page mapping, a heat map of run-length merged cells, a colour bar, metre
//! axes, a title block and tables. Everything returns `svg` crate nodes;
//! numbers are written with fixed decimals so output is deterministic.

pub mod colour;

use std::collections::HashMap;

use svg::node::element::{Group, Line, Path, Rectangle, Text};

pub use colour::{hex, palette, viridis};

/// Pixels are written with this many decimals.
const DECIMALS: usize = 2;

/// A number for an SVG attribute: fixed decimals, trailing zeros dropped.
pub fn num(v: f64) -> String {
    basr_io::fixed(v, DECIMALS)
}

/// Maps road-frame metres to page pixels: x to the right, road +y up the
/// page (SVG y grows downwards), uniform scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Page position of the road point `road_min.x, road_max.y` (top left).
    pub left_px: f64,
    pub top_px: f64,
    pub px_per_m: f64,
    pub road_min: [f64; 2],
    pub road_max: [f64; 2],
}

impl Frame {
    /// A frame showing `road_min..road_max` with its top-left corner at
    /// (`left_px`, `top_px`) and `px_per_m`.
    pub fn new(
        left_px: f64,
        top_px: f64,
        px_per_m: f64,
        road_min: [f64; 2],
        road_max: [f64; 2],
    ) -> Self {
        Frame {
            left_px,
            top_px,
            px_per_m,
            road_min,
            road_max,
        }
    }

    /// Page point of a road point.
    pub fn px(&self, p: [f64; 2]) -> (f64, f64) {
        (
            self.left_px + (p[0] - self.road_min[0]) * self.px_per_m,
            self.top_px + (self.road_max[1] - p[1]) * self.px_per_m,
        )
    }

    pub fn width_px(&self) -> f64 {
        (self.road_max[0] - self.road_min[0]) * self.px_per_m
    }

    pub fn height_px(&self) -> f64 {
        (self.road_max[1] - self.road_min[1]) * self.px_per_m
    }

    /// SVG path data of a road polyline (`closed` adds `Z`).
    pub fn path_data(&self, points: &[[f64; 2]], closed: bool) -> String {
        let mut d = String::new();
        for (k, p) in points.iter().enumerate() {
            let (x, y) = self.px(*p);
            d.push_str(if k == 0 { "M" } else { "L" });
            d.push_str(&num(x));
            d.push(' ');
            d.push_str(&num(y));
        }
        if closed && !points.is_empty() {
            d.push('Z');
        }
        d
    }
}

/// Scalar field on a regular grid to draw as coloured cells.
pub struct HeatMap<'a> {
    /// Row-major values, row 0 at the lowest road y.
    pub values: &'a [f64],
    pub nx: usize,
    pub ny: usize,
    /// Road position of the grid's lower-left corner and its cell size (m).
    pub origin: [f64; 2],
    pub cell_m: f64,
    /// Colour scale: `vmin` maps to the low end, `vmax` (and above) to the top.
    pub vmin: f64,
    pub vmax: f64,
    /// Number of colour steps.
    pub levels: usize,
    /// Values below this are not drawn (bare background).
    pub hide_below: f64,
    /// Colour by the film scale about this target ([`colour::film`]);
    /// `None`: viridis.
    pub target: Option<f64>,
}

impl HeatMap<'_> {
    /// The colour step of a value, `None` when hidden.
    pub fn level(&self, v: f64) -> Option<usize> {
        if v.is_nan() || v < self.hide_below || self.levels == 0 {
            return None;
        }
        let t = (v - self.vmin) / (self.vmax - self.vmin);
        let l = (t * self.levels as f64).floor();
        Some((l.max(0.0) as usize).min(self.levels - 1))
    }

    /// Colour of step `l`.
    pub fn colour(&self, l: usize) -> [u8; 3] {
        let t = (l as f64 + 0.5) / self.levels as f64;
        match self.target {
            Some(target) if target > 0.0 => {
                colour::film((self.vmin + t * (self.vmax - self.vmin)) / target)
            }
            _ => viridis(t),
        }
    }

    /// The cells as one path per colour step, runs of equal steps merged
    /// along rows and identical runs merged down columns, in cell units
    /// under one transform (compact, and crisp in browsers and resvg).
    pub fn draw(&self, frame: &Frame) -> Group {
        // Top-left of the grid on the page.
        let (gx, gy) = frame.px([
            self.origin[0],
            self.origin[1] + self.ny as f64 * self.cell_m,
        ]);
        let scale = self.cell_m * frame.px_per_m;
        // Rectangles (col0, row0, width, height) per level; rows counted
        // from the top of the page.
        let mut rects: Vec<Vec<[usize; 4]>> = vec![Vec::new(); self.levels];
        let mut open: HashMap<(usize, usize, usize), usize> = HashMap::new();
        for r in 0..self.ny {
            let j = self.ny - 1 - r;
            let row = &self.values[j * self.nx..(j + 1) * self.nx];
            let mut next_open = HashMap::new();
            let mut i = 0;
            while i < self.nx {
                let Some(l) = self.level(row[i]) else {
                    i += 1;
                    continue;
                };
                let start = i;
                while i < self.nx && self.level(row[i]) == Some(l) {
                    i += 1;
                }
                let key = (start, i, l);
                let idx = match open.get(&key) {
                    Some(&k) => {
                        rects[l][k][3] += 1;
                        k
                    }
                    None => {
                        rects[l].push([start, r, i - start, 1]);
                        rects[l].len() - 1
                    }
                };
                next_open.insert(key, idx);
            }
            open = next_open;
        }
        let mut g = Group::new()
            .set(
                "transform",
                format!("translate({} {}) scale({})", num(gx), num(gy), scale),
            )
            .set("shape-rendering", "crispEdges");
        for (l, list) in rects.iter().enumerate() {
            if list.is_empty() {
                continue;
            }
            let mut d = String::with_capacity(list.len() * 16);
            for [c, r, w, h] in list {
                d.push_str(&format!("M{c} {r}h{w}v{h}h-{w}z"));
            }
            g = g.add(Path::new().set("fill", hex(self.colour(l))).set("d", d));
        }
        g
    }
}

/// A vertical colour bar for a heat map at (`x`, `y`) of size `w`×`h` px,
/// with ticks at round numbers in display units (value × `unit_scale`),
/// about `ticks` of them.
#[allow(clippy::too_many_arguments)] // a drawing call: position, size, scale
pub fn colour_bar(
    map: &HeatMap,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
    label: &str,
    unit_scale: f64,
    ticks: usize,
) -> Group {
    let mut g = Group::new();
    let step = h / map.levels.max(1) as f64;
    for l in 0..map.levels {
        let top = y + h - (l + 1) as f64 * step;
        g = g.add(
            Rectangle::new()
                .set("x", num(x))
                .set("y", num(top))
                .set("width", num(w))
                .set("height", num(step + 0.5))
                .set("fill", hex(map.colour(l))),
        );
    }
    g = g.add(
        Rectangle::new()
            .set("x", num(x))
            .set("y", num(y))
            .set("width", num(w))
            .set("height", num(h))
            .set("fill", "none")
            .set("stroke", palette::INK)
            .set("stroke-width", 0.5),
    );
    let (lo, hi) = (map.vmin * unit_scale, map.vmax * unit_scale);
    let tick = nice_step((hi - lo) / ticks.max(1) as f64);
    if tick > 0.0 {
        let mut k = (lo / tick).ceil() as i64;
        while (k as f64) * tick <= hi {
            let v = k as f64 * tick;
            let ty = y + h - (v - lo) / (hi - lo) * h;
            g = g
                .add(line(x + w, ty, x + w + 4.0, ty, palette::INK, 0.8))
                .add(text(x + w + 6.0, ty + 4.0, &num(v), 11.0, "start"));
            k += 1;
        }
    }
    // On the film scale: the target marked and the ±10 % band bracketed.
    if let Some(target) = map.target.filter(|t| *t > 0.0) {
        let at = |v: f64| y + h - (v - map.vmin) / (map.vmax - map.vmin) * h;
        let (t, b0, b1) = (
            at(target),
            at(target * (1.0 + colour::FILM_BAND)),
            at(target * (1.0 - colour::FILM_BAND)),
        );
        g = g
            .add(line(x - 6.0, t, x + w, t, palette::INK, 1.5))
            .add(line(x - 8.0, b0, x - 8.0, b1, palette::INK, 1.0))
            .add(line(x - 8.0, b0, x - 4.0, b0, palette::INK, 1.0))
            .add(line(x - 8.0, b1, x - 4.0, b1, palette::INK, 1.0))
            .add(text(
                x + w + 40.0,
                t + 4.0,
                "◀ target, ±10 % band",
                10.0,
                "start",
            ));
    }
    g.add(text(x, y - 8.0, label, 12.0, "start"))
}

/// `text` cut to `max` characters with an ellipsis, for titles and header
/// values that would run off the page (a 200-letter message).
pub fn clip(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
    s.push('…');
    s
}

/// Longest title and header value drawn, in characters. // assumed: about
/// 900 px of 16 px bold text, the width of a single panel.
pub const TITLE_CHARS: usize = 90;

/// The smallest of 1, 2, 5 × 10ⁿ at least `raw` (0 for non-positive input).
pub fn nice_step(raw: f64) -> f64 {
    if !(raw > 0.0 && raw.is_finite()) {
        return 0.0;
    }
    let p = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * p)
}

/// Most ticks along one axis (assumed: beyond this the labels overlap anyway).
const MAX_TICKS: f64 = 100.0;

/// Axes around a frame: a box and metre ticks along the bottom and left.
pub fn axes(frame: &Frame, tick_m: f64) -> Group {
    axes_named(frame, tick_m, "x (m)", "y (m)")
}

/// [`axes`] with other names for the two axes (`r (m)`, `z (m)`).
pub fn axes_named(frame: &Frame, tick_m: f64, x_name: &str, y_name: &str) -> Group {
    let (x0, y0) = frame.px([frame.road_min[0], frame.road_max[1]]);
    let (x1, y1) = frame.px([frame.road_max[0], frame.road_min[1]]);
    let mut g = Group::new().add(
        Rectangle::new()
            .set("x", num(x0))
            .set("y", num(y0))
            .set("width", num(x1 - x0))
            .set("height", num(y1 - y0))
            .set("fill", "none")
            .set("stroke", palette::INK)
            .set("stroke-width", 0.8),
    );
    // A caller's tick on a vast frame (a preview at kilometre cells) would
    // mean millions of labels or, past i64, a loop without end: coarsen it.
    let span = (frame.road_max[0] - frame.road_min[0]).max(frame.road_max[1] - frame.road_min[1]);
    let tick_m = if span / tick_m > MAX_TICKS {
        nice_step(span / MAX_TICKS)
    } else {
        tick_m
    };
    if !(tick_m.is_finite() && tick_m > 0.0) {
        return g;
    }
    let first = |lo: f64| (lo / tick_m).ceil() as i64;
    for k in first(frame.road_min[0])..=(frame.road_max[0] / tick_m).floor() as i64 {
        let v = k as f64 * tick_m;
        let (px, _) = frame.px([v, 0.0]);
        g = g
            .add(line(px, y1, px, y1 + 4.0, palette::INK, 0.8))
            .add(text(px, y1 + 15.0, &num(v), 10.0, "middle"));
    }
    for k in first(frame.road_min[1])..=(frame.road_max[1] / tick_m).floor() as i64 {
        let v = k as f64 * tick_m;
        let (_, py) = frame.px([0.0, v]);
        g = g
            .add(line(x0 - 4.0, py, x0, py, palette::INK, 0.8))
            .add(text(x0 - 6.0, py + 3.5, &num(v), 10.0, "end"));
    }
    g.add(text((x0 + x1) / 2.0, y1 + 28.0, x_name, 10.0, "middle"))
        // Turned, so it clears tick labels as wide as "-1.5".
        .add(
            text(x0 - 34.0, (y0 + y1) / 2.0, y_name, 10.0, "middle").set(
                "transform",
                format!("rotate(-90 {} {})", num(x0 - 34.0), num((y0 + y1) / 2.0)),
            ),
        )
}

/// Size of axis tick labels (px).
pub const TICK_FONT_PX: f64 = 10.0;
/// Clear space between two neighbouring tick labels (px).
// assumed: a little under one digit's width keeps "0.5 1" from reading as one number.
const TICK_LABEL_GAP_PX: f64 = 8.0;
/// Ticks at least this far apart when the axis is long enough (px).
// assumed: 60–150 px between ticks (the steps are 1, 2, 2.5, 5 apart) reads
// as a ruler; a 4.8 m STOP panel at 158 px/m keeps its 0.5 m ticks.
const TICK_TARGET_PX: f64 = 60.0;
/// ...and at least this many intervals along an axis while the labels
/// fit: a narrow panel once had a single x tick.
const MIN_TICK_INTERVALS: f64 = 5.0;

/// Width in px of `s` drawn at `size` px, over-estimated: per character the
/// advance of DejaVu Sans (digits 0.636 em, `.` 0.32 em, `-` 0.361 em,
/// others at most 0.7 em), the widest of the fonts the house family falls
/// back to (Helvetica and Arial are narrower), so a label judged to fit
/// fits in every viewer.
pub fn text_width_px(s: &str, size: f64) -> f64 {
    s.chars()
        .map(|c| match c {
            '0'..='9' => 0.636,
            '.' | ',' | ' ' => 0.32,
            '-' => 0.361,
            _ => 0.7,
        })
        .sum::<f64>()
        * size
}

/// The tick values `k · step` within `lo..=hi`.
pub fn tick_values(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    if !(step > 0.0 && step.is_finite() && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let (k0, k1) = ((lo / step).ceil(), (hi / step).floor());
    if k1 < k0 || k1 - k0 > MAX_TICKS {
        return Vec::new();
    }
    (k0 as i64..=k1 as i64).map(|k| k as f64 * step).collect()
}

/// The tick step (m) for an axis showing `lo..hi` at `px_per_m`, whose
/// labels ([`num`] of each value) take `extent(label)` px along the axis:
/// the smallest of 1, 2, 2.5, 5 × 10ⁿ (written exactly with [`num`]'s two
/// decimals) that puts ticks [`TICK_TARGET_PX`] or more apart, or closer on a
/// short axis, and leaves every pair of neighbouring labels
/// [`TICK_LABEL_GAP_PX`] apart. 0 when no step fits a label (an axis
/// shorter than one label), so the caller draws no ticks.
pub fn tick_step(lo: f64, hi: f64, px_per_m: f64, extent: &dyn Fn(&str) -> f64) -> f64 {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite() && px_per_m > 0.0 && px_per_m.is_finite()) {
        return 0.0;
    }
    let want_px = (span * px_per_m / MIN_TICK_INTERVALS).min(TICK_TARGET_PX);
    let fits = |step: f64| {
        let ticks = tick_values(lo, hi, step);
        !ticks.is_empty()
            && ticks.windows(2).all(|w| {
                let room = (w[1] - w[0]) * px_per_m;
                room >= (extent(&num(w[0])) + extent(&num(w[1]))) / 2.0 + TICK_LABEL_GAP_PX
            })
    };
    // From the step that would give MAX_TICKS up to one past the span.
    let n0 = ((span / MAX_TICKS).log10().floor() as i32).max(-2);
    for n in n0..n0 + 16 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let step = m * 10f64.powi(n);
            // Only steps num() writes exactly (0.025 would print as 0.03).
            if ((step * 100.0).round() - step * 100.0).abs() > 1e-9 {
                continue;
            }
            if step * px_per_m >= want_px && fits(step) {
                return step;
            }
            if step > 2.0 * span {
                return 0.0;
            }
        }
    }
    0.0
}

/// The tick steps [`axes_fitted`] draws on a frame and the room its labels
/// and the y axis's name take to the left of the frame (px).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FittedAxes {
    pub x_step: f64,
    pub y_step: f64,
    /// Room left of the frame's edge the y labels and name take (px).
    pub left_px: f64,
    /// Where the turned y-axis name's baseline sits, left of the frame (px).
    y_name_px: f64,
}

/// Tick steps for `frame` chosen from its size in pixels and its labels'
/// widths (x) and height (y), so no two labels touch.
pub fn fit_axes(frame: &Frame) -> FittedAxes {
    let f = frame;
    let x_step = tick_step(f.road_min[0], f.road_max[0], f.px_per_m, &|s| {
        text_width_px(s, TICK_FONT_PX)
    });
    let y_step = tick_step(f.road_min[1], f.road_max[1], f.px_per_m, &|_| TICK_FONT_PX);
    let widest = tick_values(f.road_min[1], f.road_max[1], y_step)
        .iter()
        .map(|v| text_width_px(&num(*v), TICK_FONT_PX))
        .fold(0.0, f64::max);
    // Labels end 6 px left of the frame; the turned name's glyphs reach
    // about 0.75 em left of its baseline and 0.25 em right of it.
    let y_name_px = (6.0 + widest + 0.25 * TICK_FONT_PX + 4.0).max(34.0);
    FittedAxes {
        x_step,
        y_step,
        left_px: y_name_px + 0.75 * TICK_FONT_PX,
        y_name_px,
    }
}

/// Axes around a frame as [`axes_named`] draws them, with the tick steps of
/// [`fit_axes`]: the x labels in a group of class `ticks-x`, the y labels
/// in one of class `ticks-y`, and the y axis's name clear of the widest y
/// label.
pub fn axes_fitted(frame: &Frame, x_name: &str, y_name: &str) -> Group {
    let fit = fit_axes(frame);
    let (x0, y0) = frame.px([frame.road_min[0], frame.road_max[1]]);
    let (x1, y1) = frame.px([frame.road_max[0], frame.road_min[1]]);
    let mut xs = Group::new().set("class", "ticks-x");
    for v in tick_values(frame.road_min[0], frame.road_max[0], fit.x_step) {
        let (px, _) = frame.px([v, 0.0]);
        xs = xs
            .add(line(px, y1, px, y1 + 4.0, palette::INK, 0.8))
            .add(text(px, y1 + 15.0, &num(v), TICK_FONT_PX, "middle"));
    }
    let mut ys = Group::new().set("class", "ticks-y");
    for v in tick_values(frame.road_min[1], frame.road_max[1], fit.y_step) {
        let (_, py) = frame.px([0.0, v]);
        ys = ys
            .add(line(x0 - 4.0, py, x0, py, palette::INK, 0.8))
            .add(text(x0 - 6.0, py + 3.5, &num(v), TICK_FONT_PX, "end"));
    }
    let name_x = x0 - fit.y_name_px;
    Group::new()
        .add(
            Rectangle::new()
                .set("x", num(x0))
                .set("y", num(y0))
                .set("width", num(x1 - x0))
                .set("height", num(y1 - y0))
                .set("fill", "none")
                .set("stroke", palette::INK)
                .set("stroke-width", 0.8),
        )
        .add(xs)
        .add(ys)
        .add(text((x0 + x1) / 2.0, y1 + 28.0, x_name, 10.0, "middle"))
        .add(text(name_x, (y0 + y1) / 2.0, y_name, 10.0, "middle").set(
            "transform",
            format!("rotate(-90 {} {})", num(name_x), num((y0 + y1) / 2.0)),
        ))
}

/// A title line followed by `key: value` lines, from (`x`, `y`) down.
pub fn title_block(x: f64, y: f64, title: &str, lines: &[(String, String)]) -> Group {
    let mut g = Group::new()
        .add(text(x, y, &clip(title, TITLE_CHARS), 16.0, "start").set("font-weight", "bold"));
    for (k, (key, value)) in lines.iter().enumerate() {
        let ty = y + 20.0 + 15.0 * k as f64;
        g = g
            .add(text(x, ty, key, 12.0, "start").set("fill", "#555555"))
            .add(text(
                x + 150.0,
                ty,
                &clip(value, TITLE_CHARS + 20),
                12.0,
                "start",
            ));
    }
    g
}

/// Height in px that [`title_block`] takes for `n` lines.
pub fn title_block_height(n: usize) -> f64 {
    20.0 + 15.0 * n as f64
}

/// Average advance of one character of the 11 px table text (px).
/// assumed: Helvetica's mean glyph width is about 0.55 em, with room to spare.
const TABLE_CHAR_PX: f64 = 6.5;

/// `widths` widened where a column's longest cell (or its header) needs
/// more room, so a long symbol name does not run into the next column.
pub fn fit_widths(widths: &[f64], header: &[&str], rows: &[Vec<String>]) -> Vec<f64> {
    widths
        .iter()
        .enumerate()
        .map(|(c, &w)| {
            let longest = rows
                .iter()
                .filter_map(|r| r.get(c))
                .map(|s| s.chars().count())
                .chain(header.get(c).map(|h| h.chars().count()))
                .max()
                .unwrap_or(0);
            w.max(longest as f64 * TABLE_CHAR_PX + 10.0)
        })
        .collect()
}

/// A table with a header row; `widths` are the column widths in px.
pub fn table(x: f64, y: f64, widths: &[f64], header: &[&str], rows: &[Vec<String>]) -> Group {
    let row_h = 15.0;
    let mut g = Group::new();
    let mut cx = x;
    for (c, h) in header.iter().enumerate() {
        g = g.add(text(cx, y, h, 11.0, "start").set("font-weight", "bold"));
        cx += widths.get(c).copied().unwrap_or(60.0);
    }
    let total: f64 = widths.iter().sum();
    g = g.add(line(x, y + 4.0, x + total, y + 4.0, palette::INK, 0.6));
    for (r, row) in rows.iter().enumerate() {
        let ty = y + (r + 1) as f64 * row_h + 2.0;
        let mut cx = x;
        for (c, cell) in row.iter().enumerate() {
            g = g.add(text(cx, ty, cell, 11.0, "start"));
            cx += widths.get(c).copied().unwrap_or(60.0);
        }
    }
    g
}

/// Height in px that [`table`] takes for `rows` rows.
pub fn table_height(rows: usize) -> f64 {
    15.0 * (rows + 1) as f64 + 6.0
}

/// A text element in the house font.
pub fn text(x: f64, y: f64, s: &str, size: f64, anchor: &str) -> Text {
    Text::new(s)
        .set("x", num(x))
        .set("y", num(y))
        .set("font-family", "Helvetica, Arial, sans-serif")
        .set("font-size", num(size))
        .set("text-anchor", anchor)
        .set("fill", palette::INK)
}

/// A straight line.
pub fn line(x0: f64, y0: f64, x1: f64, y1: f64, colour: &str, width: f64) -> Line {
    Line::new()
        .set("x1", num(x0))
        .set("y1", num(y0))
        .set("x2", num(x1))
        .set("y2", num(y1))
        .set("stroke", colour)
        .set("stroke-width", num(width))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(0.126), "0.13");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(12.5), "12.5");
    }

    #[test]
    fn long_titles_are_clipped_with_an_ellipsis() {
        assert_eq!(clip("STOP", 10), "STOP");
        let long = "STOPS / ".repeat(40);
        let c = clip(&long, TITLE_CHARS);
        assert_eq!(c.chars().count(), TITLE_CHARS);
        assert!(c.ends_with('…'));
    }

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(83.0), 100.0);
        assert_eq!(nice_step(0.3), 0.5);
        assert_eq!(nice_step(2.0), 2.0);
        assert_eq!(nice_step(-1.0), 0.0);
    }

    #[test]
    fn axes_on_a_vast_frame_keep_a_bounded_number_of_ticks() {
        let labels = |f: &Frame, tick: f64| axes(f, tick).to_string().matches("<text").count();
        let small = Frame::new(0.0, 0.0, 100.0, [0.0, 0.0], [2.0, 1.0]);
        // 0..2 and 0..1 at 0.5 m: 5 + 3 ticks and two axis titles.
        assert_eq!(labels(&small, 0.5), 10);
        let vast = Frame::new(0.0, 0.0, 1e-6, [-1e9, -1e9], [1e9, 1e9]);
        let n = labels(&vast, 50.0);
        assert!(n > 2 && n <= 2 * 101 + 2, "{n} labels");
        let endless = Frame::new(0.0, 0.0, 1e-300, [-1e300, 0.0], [1e300, 1.0]);
        assert!(labels(&endless, 50.0) <= 2 * 101 + 2);
    }

    /// Every neighbouring pair of labels of `step` on `lo..hi` at `ppm`
    /// has `gap` px between them (x labels: their widths).
    fn x_labels_clear(lo: f64, hi: f64, ppm: f64, step: f64, gap: f64) -> bool {
        tick_values(lo, hi, step).windows(2).all(|w| {
            let a = text_width_px(&num(w[0]), TICK_FONT_PX);
            let b = text_width_px(&num(w[1]), TICK_FONT_PX);
            (w[1] - w[0]) * ppm >= (a + b) / 2.0 + gap
        })
    }

    fn x_step(lo: f64, hi: f64, ppm: f64) -> f64 {
        tick_step(lo, hi, ppm, &|s| text_width_px(s, TICK_FONT_PX))
    }

    #[test]
    fn tick_labels_of_a_wide_short_panel_do_not_run_together() {
        // The scene preview's stop-line view: 4.3 m across at 64 px/m once
        // took 0.1 m ticks for its 1 m height, 6 px apart under labels
        // like "-1.8" 20 px wide.
        let s = x_step(-2.15, 2.15, 64.0);
        assert!(s >= 0.5, "{s}");
        assert!(x_labels_clear(-2.15, 2.15, 64.0, s, TICK_LABEL_GAP_PX));
        // ...and still at least three labels.
        assert!(tick_values(-2.15, 2.15, s).len() >= 3, "{s}");
    }

    #[test]
    fn ticks_are_60_px_or_more_apart_on_a_long_axis() {
        // 20 m at 40 px/m: 1 m = 40 px < 60 ≤ 2 m.
        assert_eq!(x_step(0.0, 20.0, 40.0), 2.0);
        // STOP's panel: 4.8 m at 158 px/m → 0.5 m (79 px), not 0.25.
        assert_eq!(x_step(-0.3, 4.5, 158.0), 0.5);
        assert_eq!(tick_step(-0.3, 4.5, 158.0, &|_| TICK_FONT_PX), 0.5);
    }

    #[test]
    fn a_short_axis_keeps_five_intervals_while_the_labels_fit() {
        // 1 m at 200 px/m: 0.2 m = 40 px (five intervals), not 0.5.
        let s = x_step(0.0, 1.0, 200.0);
        assert_eq!(s, 0.2);
        // The y axis (labels 10 px tall) of the same.
        assert_eq!(tick_step(0.0, 1.0, 200.0, &|_| TICK_FONT_PX), 0.2);
    }

    #[test]
    fn wide_labels_push_the_step_up() {
        // Labels like "-26.25" (about 35 px) need more room than "-26".
        let s = x_step(-31.0, -25.0, 60.0);
        assert!(
            x_labels_clear(-31.0, -25.0, 60.0, s, TICK_LABEL_GAP_PX),
            "{s}"
        );
        for narrow in [0.25, 0.5] {
            assert!(s > narrow || x_labels_clear(-31.0, -25.0, 60.0, narrow, 8.0));
        }
    }

    #[test]
    fn steps_are_written_exactly_and_tiny_axes_get_no_ticks() {
        for (lo, hi, ppm) in [(0.0, 0.1, 3000.0), (-0.3, 0.2, 2000.0), (0.0, 1e4, 0.05)] {
            let s = x_step(lo, hi, ppm);
            assert!(s > 0.0, "{lo} {hi} {ppm}");
            assert!(((s * 100.0).round() - s * 100.0).abs() < 1e-9, "{s}");
        }
        // 0.5 m at 20 px/m is 10 px: room for one label, not two.
        let s = x_step(0.0, 0.5, 20.0);
        assert_eq!(tick_values(0.0, 0.5, s).len(), 1, "{s}");
        // 3 cm at 20 px/m: no label fits between 0.31 and 0.34.
        assert_eq!(x_step(0.31, 0.34, 20.0), 0.0);
        assert_eq!(x_step(0.0, 0.0, 20.0), 0.0);
        assert_eq!(x_step(0.0, f64::NAN, 20.0), 0.0);
    }

    #[test]
    fn fitted_axes_keep_the_y_name_clear_of_wide_labels() {
        let narrow = fit_axes(&Frame::new(60.0, 0.0, 100.0, [0.0, 0.0], [2.0, 3.0]));
        // y labels every 0.25 m: "-30.75" is about 32 px wide.
        let wide = fit_axes(&Frame::new(60.0, 0.0, 250.0, [0.0, -31.0], [1.0, -28.0]));
        assert_eq!(wide.y_step, 0.25);
        assert_eq!(narrow.y_name_px, 34.0);
        assert!(wide.y_name_px > 6.0 + text_width_px("-30.75", TICK_FONT_PX));
        assert!(wide.left_px > wide.y_name_px);
        let svg = axes_fitted(
            &Frame::new(60.0, 0.0, 100.0, [0.0, 0.0], [2.0, 3.0]),
            "x (m)",
            "y (m)",
        )
        .to_string();
        assert!(svg.contains("class=\"ticks-x\"") && svg.contains("class=\"ticks-y\""));
    }

    #[test]
    fn frame_flips_y() {
        let f = Frame::new(10.0, 20.0, 100.0, [0.0, 0.0], [2.0, 1.0]);
        assert_eq!(f.px([0.0, 1.0]), (10.0, 20.0));
        assert_eq!(f.px([2.0, 0.0]), (210.0, 120.0));
    }

    #[test]
    fn heat_map_merges_runs_and_columns() {
        // 3×2 grid, all one level except a hidden cell.
        let v = [1.0, 1.0, 0.0, 1.0, 1.0, 0.0];
        let m = HeatMap {
            values: &v,
            nx: 3,
            ny: 2,
            origin: [0.0, 0.0],
            cell_m: 1.0,
            vmin: 0.0,
            vmax: 2.0,
            levels: 4,
            hide_below: 0.5,
            target: None,
        };
        let s = m
            .draw(&Frame::new(0.0, 0.0, 1.0, [0.0, 0.0], [3.0, 2.0]))
            .to_string();
        assert!(s.contains("M0 0h2v2h-2z"), "{s}");
        assert_eq!(s.matches("<path").count(), 1);
    }
}
