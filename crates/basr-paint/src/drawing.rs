//! The preview's SVG page: one or more panels (a job, its film and its
//! figures) side by side on one colour scale — the header lines, the road
//! views with the film map, outlines, nozzle path and stops, the legend and
//! the per-letter table.

use svg::node::element::{Circle, Group, Path, Rectangle};
use svg::Document;

use super::captions::{glyph_ids, glyph_table, panel_lines, GLYPH_HEADER};
use super::preview::Preview;
use super::raster::Bounds;
use super::spray::Pose;
use super::verdict::Verdict;
use basr_job::Job;
use basr_plot::{self as plot, palette, Frame, HeatMap};

/// The colour scale tops out at this multiple of the target film.
// assumed: 1.5× shows both thin (< 50 %) and heavy (overlaps) film.
const SCALE_TOP: f64 = 1.5;
/// Colour steps of the film map, each 5 % of target from zero, so the
/// ±10 % band about the target is exactly four steps (plot::colour::film).
const LEVELS: usize = 30;
const SCALE_BOTTOM: f64 = 0.0;
/// Film below this share of target is drawn as bare road.
const HIDE_BELOW: f64 = 0.02;

/// One panel of the SVG: a job, its preview and a caption.
pub struct Panel<'a> {
    pub job: &'a Job,
    pub preview: &'a Preview,
    /// The film's verdict against the thresholds.
    pub verdict: &'a Verdict,
    /// The film is the simulated arm's (`--from-sim`), not the plan's.
    pub from_sim: bool,
    /// For a job re-planned from another (`--compare`): what it was
    /// re-planned from, as header lines (key, value).
    pub replanned: Option<&'a [(String, String)]>,
}

/// Road extent a panel shows: the film raster, the nozzle path and stations.
fn panel_bounds(p: &Panel) -> Bounds {
    let mut b = p.preview.film.grid.bounds();
    for pose in &p.preview.poses {
        if pose.x_m.is_finite() && pose.y_m.is_finite() {
            b.include([pose.x_m, pose.y_m]);
        }
    }
    for s in &p.job.stations {
        if s.x_m.is_finite() && s.y_m.is_finite() {
            b.include([s.x_m, s.y_m]);
        }
    }
    b.grow(0.1)
}

/// The road a single job's picture shows: one view per line of the
/// message (its letters and a truck stop within 3 m of them), so a two-line
/// job is not 17 m of road in one narrow panel; one view of everything for
/// a one-line job or a marking without lines.
fn line_views(p: &Panel) -> Vec<Bounds> {
    let mut lines: std::collections::BTreeMap<usize, Bounds> = Default::default();
    for g in &p.preview.outlines {
        let b = g.bounds();
        if !b.is_empty() {
            let e = lines.entry(g.line).or_insert(Bounds::EMPTY);
            *e = if e.is_empty() { b } else { e.union(b) };
        }
    }
    if lines.len() < 2 {
        return vec![panel_bounds(p)];
    }
    // assumed: 3 m reaches a stop planned for the line (STOP AHEAD's are
    // 2.2 m past each line's far edge).
    const STOP_REACH_M: f64 = 3.0;
    lines
        .into_values()
        .map(|mut b| {
            for s in &p.job.stations {
                let near = s.y_m >= b.min[1] - STOP_REACH_M && s.y_m <= b.max[1] + STOP_REACH_M;
                if near && s.x_m.is_finite() && s.y_m.is_finite() {
                    b.include([s.x_m, s.y_m]);
                }
            }
            b.grow(0.3)
        })
        .collect()
}

/// Views laid out at most this many to a row. // assumed: four 3.7 m lanes
/// side by side keep letters about 60 px tall on a 900 px page.
const VIEWS_PER_ROW: usize = 4;

/// Page geometry shared by the drawing and by tests that look at pixels.
struct Page {
    margin: f64,
    header: Vec<(String, String)>,
    head_h: f64,
    map_top: f64,
    frames: Vec<Frame>,
}

fn page(panels: &[Panel]) -> Page {
    let margin = 60.0;
    // Every panel at one scale, so letters compare at a glance.
    let extents: Vec<Bounds> = match panels {
        [one] => line_views(one),
        _ => panels.iter().map(panel_bounds).collect(),
    };
    let max_w = extents.iter().map(|b| b.width()).fold(0.0, f64::max);
    let max_h = extents.iter().map(|b| b.height()).fold(0.0, f64::max);
    let cols = extents.len().clamp(1, VIEWS_PER_ROW);
    let per_panel_px = if panels.len() > 1 {
        560.0
    } else {
        (900.0 - 40.0 * (cols - 1) as f64) / cols as f64
    };
    let px_per_m = (per_panel_px / max_w.max(1e-3)).min(760.0 / max_h.max(1e-3));
    let mut header: Vec<(String, String)> = Vec::new();
    if let Some(p) = panels.first() {
        header.push(("message".into(), p.job.message.replace('\n', " / ")));
        header.push((
            "robot".into(),
            format!(
                "{} ({} station{})",
                p.job.robot.name(),
                p.job.stations.len(),
                if p.job.stations.len() == 1 { "" } else { "s" }
            ),
        ));
        if panels.len() == 1 {
            header.push(("tilt method".into(), p.job.layout.tilt_method.clone()));
        }
        header.push((
            "spray".into(),
            format!(
                "fan {:.1}°, profile {}, {:.2} L/min × {:.2}, raster {} mm",
                p.job.paint.fan_angle_rad.to_degrees(),
                p.preview.profile,
                p.job.paint.flow_m3ps * 60e3,
                p.job.paint.transfer_efficiency,
                super::raster::mm_text(p.preview.metrics.resolution_m)
            ),
        ));
        if let Some(lines) = panels.iter().find_map(|p| p.replanned) {
            header.extend(lines.iter().cloned());
        }
        if panels.len() == 1 {
            header.extend(panel_lines(p));
        }
    }
    let head_h = plot::title_block_height(header.len()) + 20.0;
    let caption_h = match panels {
        [first, _, ..] => plot::title_block_height(panel_lines(first).len()) + 10.0,
        _ => 0.0,
    };
    let map_top = margin + head_h + caption_h;
    let mut frames = Vec::new();
    if panels.len() > 1 {
        let mut x = margin;
        for (ext, p) in extents.iter().zip(panels) {
            let frame = Frame::new(x, map_top, px_per_m, ext.min, ext.max);
            x += frame.width_px().max(glyph_table(p).1.iter().sum()) + 60.0;
            frames.push(frame);
        }
    } else {
        // Line views in rows, each row as tall as its tallest view, a
        // caption line above each.
        let caption = if extents.len() > 1 { 22.0 } else { 0.0 };
        let mut top = map_top + caption;
        for row in extents.chunks(VIEWS_PER_ROW) {
            let mut x = margin;
            let mut row_h: f64 = 0.0;
            for ext in row {
                let frame = Frame::new(x, top, px_per_m, ext.min, ext.max);
                x += frame.width_px() + 40.0;
                row_h = row_h.max(frame.height_px());
                frames.push(frame);
            }
            top += row_h + 40.0 + caption;
        }
    }
    Page {
        margin,
        header,
        head_h,
        map_top,
        frames,
    }
}

/// Where each panel's road frame lands on the page [`render_svg`] draws.
pub fn panel_frames(panels: &[Panel]) -> Vec<Frame> {
    page(panels).frames
}

/// Draw one or more previews side by side (one colour scale) as an SVG
/// document.
pub fn render_svg(panels: &[Panel], title: &str) -> String {
    let target = panels
        .first()
        .map_or(1.0, |p| p.preview.metrics.target_film_m);
    let pg = page(panels);
    let (margin, map_top) = (pg.margin, pg.map_top);
    let mut doc_g = Group::new().add(plot::title_block(margin, margin, title, &pg.header));
    let mut bottom: f64 = map_top;
    let mut right: f64 = margin;
    let vmax = (SCALE_BOTTOM + SCALE_TOP) * target;
    if let ([p], [_, _, ..]) = (panels, &pg.frames[..]) {
        // One job, a view per line.
        for (k, frame) in pg.frames.iter().enumerate() {
            let id = format!("line-view-{}", k + 1);
            let (x0, y0) = (frame.left_px, frame.top_px);
            doc_g = doc_g
                .add(
                    svg::node::element::ClipPath::new()
                        .set("id", id.clone())
                        .add(
                            // The road inside the frame only: another
                            // line's outlines stop at the view's edge.
                            Rectangle::new()
                                .set("x", plot::num(x0))
                                .set("y", plot::num(y0))
                                .set("width", plot::num(frame.width_px()))
                                .set("height", plot::num(frame.height_px())),
                        ),
                )
                .add(
                    plot::text(x0, y0 - 8.0, &format!("line {}", k + 1), 13.0, "start")
                        .set("font-weight", "bold"),
                )
                .add(road_layers(p, frame, vmax).set("clip-path", format!("url(#{id})")))
                .add(plot::axes(frame, tick_spacing(frame)));
            bottom = bottom.max(frame.top_px + frame.height_px());
            right = right.max(frame.left_px + frame.width_px() + 60.0);
        }
        let table_top = bottom + 50.0;
        let (rows, widths) = glyph_table(p);
        doc_g = doc_g.add(plot::table(
            margin,
            table_top,
            &widths,
            &GLYPH_HEADER,
            &rows,
        ));
        bottom = table_top + plot::table_height(rows.len());
        right = right.max(margin + widths.iter().sum::<f64>() + 60.0);
    }
    for (p, frame) in panels
        .iter()
        .zip(&pg.frames)
        .take(if pg.frames.len() > panels.len() {
            0
        } else {
            panels.len()
        })
    {
        if panels.len() > 1 {
            doc_g = doc_g.add(plot::title_block(
                frame.left_px,
                margin + pg.head_h,
                &format!(
                    "tilt: {}{}",
                    p.job.layout.tilt_method,
                    if p.replanned.is_some() {
                        " (re-planned)"
                    } else {
                        ""
                    }
                ),
                &panel_lines(p),
            ));
        }
        doc_g = doc_g.add(draw_panel(p, frame, vmax));
        let table_top = map_top + frame.height_px() + 50.0;
        let (rows, widths) = glyph_table(p);
        doc_g = doc_g.add(plot::table(
            frame.left_px,
            table_top,
            &widths,
            &GLYPH_HEADER,
            &rows,
        ));
        bottom = bottom.max(table_top + plot::table_height(rows.len()));
        right = frame.left_px + frame.width_px().max(widths.iter().sum()) + 60.0;
    }
    // The shared colour bar.
    let dummy = [0.0];
    let scale = HeatMap {
        values: &dummy,
        nx: 1,
        ny: 1,
        origin: [0.0, 0.0],
        cell_m: 1.0,
        vmin: SCALE_BOTTOM * target,
        vmax,
        levels: LEVELS,
        hide_below: HIDE_BELOW * target,
        target: Some(target),
    };
    let bar_h = 300.0_f64.min((bottom - map_top).max(100.0));
    doc_g = doc_g.add(plot::colour_bar(
        &scale,
        right,
        map_top + 20.0,
        18.0,
        bar_h,
        "film (µm)",
        1e6,
        6,
    ));
    let legend_top = map_top + bar_h + 60.0;
    doc_g = doc_g.add(legend(right, legend_top));
    let width = right + 160.0;
    let height = bottom.max(legend_top + 80.0) + margin;
    let doc = Document::new()
        .set("width", plot::num(width))
        .set("height", plot::num(height))
        .set(
            "viewBox",
            format!("0 0 {} {}", plot::num(width), plot::num(height)),
        )
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "#ffffff"),
        )
        .add(doc_g);
    let mut out = doc.to_string();
    out.push('\n');
    out
}

fn legend(x: f64, y: f64) -> Group {
    let item = |k: usize, colour: &str, dash: Option<&str>, label: &str| {
        let ty = y + 18.0 * k as f64;
        let mut l = plot::line(x, ty, x + 24.0, ty, colour, 2.0);
        if let Some(d) = dash {
            l = l.set("stroke-dasharray", d);
        }
        Group::new()
            .add(l)
            .add(plot::text(x + 30.0, ty + 4.0, label, 11.0, "start"))
    };
    Group::new()
        .add(
            Rectangle::new()
                .set("x", plot::num(x - 4.0))
                .set("y", plot::num(y - 10.0))
                .set("width", 34)
                .set("height", plot::num(18.0 * 3.0 + 4.0))
                .set("fill", "#9a9a9a"),
        )
        .add(item(0, palette::OUTLINE, None, "letter outline"))
        .add(item(1, palette::PATH_ON, None, "nozzle, gun on"))
        .add(item(2, palette::PATH_OFF, Some("4 3"), "nozzle, gun off"))
        .add(
            Circle::new()
                .set("cx", plot::num(x + 12.0))
                .set("cy", plot::num(y + 54.0))
                .set("r", 5)
                .set("fill", palette::STATION),
        )
        .add(plot::text(
            x + 30.0,
            y + 58.0,
            "truck stop (arm axis)",
            11.0,
            "start",
        ))
}

fn draw_panel(p: &Panel, frame: &Frame, vmax: f64) -> Group {
    road_layers(p, frame, vmax).add(plot::axes(frame, tick_spacing(frame)))
}

/// What [`draw_panel`] draws inside the frame: film, outlines, nozzle path,
/// stations and labels (everything but the axes).
fn road_layers(p: &Panel, frame: &Frame, vmax: f64) -> Group {
    let grid = &p.preview.film.grid;
    let target = p.preview.metrics.target_film_m;
    // Only the cells the frame shows (a line's view of a long job).
    let cell = grid.cell_m;
    let index = |v: f64, o: f64, n: usize| (((v - o) / cell).floor().max(0.0) as usize).min(n);
    let (i0, i1) = (
        index(frame.road_min[0], grid.x0, grid.nx),
        (index(frame.road_max[0], grid.x0, grid.nx) + 1).min(grid.nx),
    );
    let (j0, j1) = (
        index(frame.road_min[1], grid.y0, grid.ny),
        (index(frame.road_max[1], grid.y0, grid.ny) + 1).min(grid.ny),
    );
    let crop: Vec<f64> = (j0..j1)
        .flat_map(|j| {
            grid.data[j * grid.nx + i0..j * grid.nx + i1]
                .iter()
                .copied()
        })
        .collect();
    let map = HeatMap {
        values: &crop,
        nx: i1.saturating_sub(i0),
        ny: j1.saturating_sub(j0),
        origin: [grid.x0 + i0 as f64 * cell, grid.y0 + j0 as f64 * cell],
        cell_m: grid.cell_m,
        vmin: SCALE_BOTTOM * target,
        vmax,
        levels: LEVELS,
        hide_below: HIDE_BELOW * target,
        target: Some(target),
    };
    let (x0, y0) = frame.px([frame.road_min[0], frame.road_max[1]]);
    let mut g = Group::new()
        .add(
            Rectangle::new()
                .set("x", plot::num(x0))
                .set("y", plot::num(y0))
                .set("width", plot::num(frame.width_px()))
                .set("height", plot::num(frame.height_px()))
                .set("fill", palette::ROAD),
        )
        .add(map.draw(frame));
    // Letter outlines.
    let mut d = String::new();
    for gl in &p.preview.outlines {
        for poly in &gl.strokes {
            d.push_str(&frame.path_data(poly, true));
        }
    }
    g = g.add(
        Path::new()
            .set("d", d)
            .set("fill", "none")
            .set("stroke", palette::OUTLINE)
            .set("stroke-width", 0.8)
            .set("stroke-linejoin", "round"),
    );
    // Nozzle path, split into gun-on and gun-off runs.
    let (on, off) = path_runs(&p.preview.poses, frame);
    g = g
        .add(
            Path::new()
                .set("d", off)
                .set("fill", "none")
                .set("stroke", palette::PATH_OFF)
                .set("stroke-width", 0.8)
                .set("stroke-dasharray", "4 3"),
        )
        .add(
            Path::new()
                .set("d", on)
                .set("fill", "none")
                .set("stroke", palette::PATH_ON)
                .set("stroke-width", 0.8)
                .set("stroke-opacity", 0.8),
        );
    for (k, s) in p.job.stations.iter().enumerate() {
        let (sx, sy) = frame.px([s.x_m, s.y_m]);
        let (hx, hy) = frame.px([
            s.x_m + 0.4 * s.heading_rad.cos(),
            s.y_m + 0.4 * s.heading_rad.sin(),
        ]);
        g = g
            .add(plot::line(sx, sy, hx, hy, palette::STATION, 1.5))
            .add(
                Circle::new()
                    .set("cx", plot::num(sx))
                    .set("cy", plot::num(sy))
                    .set("r", 5)
                    .set("fill", palette::STATION),
            )
            .add(plot::text(
                sx + 8.0,
                sy - 6.0,
                &format!("stop {}", k + 1),
                11.0,
                "start",
            ));
    }
    g.add(labels(p, frame))
}

/// Letter labels (`1.3 O`) over each letter and stroke numbers (as the
/// warnings number them) at the middle of each stroke's painted run.
fn labels(p: &Panel, frame: &Frame) -> Group {
    let mut g = Group::new()
        .set("font-family", "DejaVu Sans, Arial, sans-serif")
        .set("paint-order", "stroke")
        .set("stroke", "#ffffff")
        .set("stroke-width", 2.5)
        .set("stroke-linejoin", "round");
    for (gl, id) in p
        .preview
        .outlines
        .iter()
        .zip(glyph_ids(&p.preview.outlines))
    {
        let b = gl.bounds();
        if b.is_empty() {
            continue;
        }
        let (x, y) = frame.px([(b.min[0] + b.max[0]) / 2.0, b.max[1]]);
        g = g.add(
            plot::text(x, y - 6.0, &format!("{id} {}", gl.label), 12.0, "middle")
                .set("font-weight", "bold"),
        );
    }
    // Each stroke's gun-on samples; the label sits at the middle one.
    let s = &p.job.samples;
    let mut runs: std::collections::BTreeMap<i64, Vec<usize>> = Default::default();
    for i in 0..s.len() {
        if s.paint[i] != 0 && s.stroke[i] >= 0 {
            runs.entry(s.stroke[i]).or_default().push(i);
        }
    }
    for (stroke, rows) in runs {
        let i = rows[rows.len() / 2];
        let (x, y) = frame.px([s.x_m[i], s.y_m[i]]);
        g = g
            .add(plot::text(x, y + 3.0, &stroke.to_string(), 9.0, "middle").set("fill", "#000000"));
    }
    g
}

/// Metre ticks about every 100 px, and at least four along the shorter
/// side (a narrow panel once had a single x tick).
fn tick_spacing(frame: &Frame) -> f64 {
    let short_m =
        (frame.road_max[0] - frame.road_min[0]).min(frame.road_max[1] - frame.road_min[1]);
    let raw = (100.0 / frame.px_per_m).min(short_m / 8.0);
    [0.05, 0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0]
        .into_iter()
        .find(|&t| t >= raw)
        .unwrap_or(50.0)
}

/// SVG path data of the nozzle's path (tip's foot) with the gun on and off;
/// points closer than half a pixel to the previous are dropped.
fn path_runs(poses: &[Pose], frame: &Frame) -> (String, String) {
    let (mut on, mut off) = (String::new(), String::new());
    // The run's gun state and the pen's last drawn point.
    let mut pen: Option<(bool, (f64, f64))> = None;
    for w in poses.windows(2) {
        let state = w[0].gun;
        let a = frame.px([w[0].x_m, w[0].y_m]);
        let b = frame.px([w[1].x_m, w[1].y_m]);
        if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
            pen = None;
            continue;
        }
        let d = if state { &mut on } else { &mut off };
        let from = match pen {
            Some((s, p)) if s == state => p,
            _ => {
                d.push_str(&format!("M{} {}", plot::num(a.0), plot::num(a.1)));
                a
            }
        };
        if (from.0 - b.0).hypot(from.1 - b.1) >= 0.5 {
            d.push_str(&format!("L{} {}", plot::num(b.0), plot::num(b.1)));
            pen = Some((state, b));
        } else {
            pen = Some((state, from));
        }
    }
    (on, off)
}
