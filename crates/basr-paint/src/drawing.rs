//! The preview's SVG page: one or more panels (a job, its film and its
//! figures) side by side on one colour scale — the header lines, the road
//! views with the film map, outlines, nozzle path and stops, the legend and
//! the per-letter table. A job painted from two or more stops gets an
//! overview of the whole scene and one view per stop (docs/preview.md).

use svg::node::element::{Circle, Group, Path, Rectangle};
use svg::Document;

use super::captions::{glyph_ids, glyph_table, panel_lines, GLYPH_HEADER};
use super::preview::Preview;
use super::raster::{Bounds, Grid};
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
    let mut b = p.preview.raster_bounds;
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
/// message (its letters, and each truck stop in the view of the line
/// nearest it), so a two-line job is not 17 m of road in one narrow panel;
/// one view of everything for a one-line job or a marking without lines.
fn line_views(p: &Panel) -> Vec<View> {
    let mut lines: std::collections::BTreeMap<usize, Bounds> = Default::default();
    for g in &p.preview.outlines {
        let b = g.bounds();
        if !b.is_empty() {
            let e = lines.entry(g.line).or_insert(Bounds::EMPTY);
            *e = if e.is_empty() { b } else { e.union(b) };
        }
    }
    let all: Vec<usize> = (0..p.job.stations.len()).collect();
    if lines.len() < 2 {
        return vec![View {
            id: "view".into(),
            title: String::new(),
            note: String::new(),
            bounds: panel_bounds(p),
            path_of: None,
            stops: all,
        }];
    }
    let letters: Vec<Bounds> = lines.into_values().collect();
    let mut views: Vec<View> = letters
        .iter()
        .enumerate()
        .map(|(k, b)| View {
            id: format!("line-view-{}", k + 1),
            title: format!("line {}", k + 1),
            note: String::new(),
            bounds: *b,
            path_of: None,
            stops: Vec::new(),
        })
        .collect();
    // Each stop in exactly one view: a stop between two lines was once drawn
    // in both, and one farther than 3 m from every line in none.
    for (k, s) in p.job.stations.iter().enumerate() {
        if !(s.x_m.is_finite() && s.y_m.is_finite()) {
            continue;
        }
        let v = nearest(&letters, [s.x_m, s.y_m]);
        views[v].stops.push(k);
        views[v].bounds.include([s.x_m, s.y_m]);
    }
    for v in &mut views {
        v.bounds = v.bounds.grow(0.3);
    }
    views
}

/// Index of the rectangle nearest `pt` (0 when `rects` is empty).
fn nearest(rects: &[Bounds], pt: [f64; 2]) -> usize {
    let gap = |b: &Bounds| {
        let dx = (b.min[0] - pt[0]).max(pt[0] - b.max[0]).max(0.0);
        let dy = (b.min[1] - pt[1]).max(pt[1] - b.max[1]).max(0.0);
        dx.hypot(dy)
    };
    (0..rects.len())
        .min_by(|&a, &b| gap(&rects[a]).total_cmp(&gap(&rects[b])))
        .unwrap_or(0)
}

/// One road view of a single job's page: what it shows and whose path.
#[derive(Clone, Debug)]
struct View {
    /// The SVG id of the view's group (`stop-2`, `line-view-1`).
    id: String,
    /// Its caption (`Stop 2`, `line 1`); empty: none.
    title: String,
    /// Words after the caption (what the stop paints).
    note: String,
    bounds: Bounds,
    /// Only this stop's nozzle path and stroke numbers; `None`: every stop's.
    path_of: Option<usize>,
    /// The stops marked in this view (indices into the job's stations).
    stops: Vec<usize>,
}

/// A job painted from two or more stops: one view per stop, of the road
/// that stop's gun paints and the stop itself; the view's caption says
/// which letters or items the stop paints. Stops are numbered from 1 as
/// the job sheet numbers them.
fn stop_views(p: &Panel) -> Vec<View> {
    let s = &p.job.samples;
    let n = p.job.stations.len();
    let (mut on, mut any) = (vec![Bounds::EMPTY; n], vec![Bounds::EMPTY; n]);
    let station = |i: usize| usize::try_from(s.station[i]).ok().filter(|&k| k < n);
    for i in 0..s.len() {
        let (Some(k), pt) = (station(i), [s.x_m[i], s.y_m[i]]) else {
            continue;
        };
        if pt[0].is_finite() && pt[1].is_finite() {
            any[k].include(pt);
            if s.paint[i] != 0 {
                on[k].include(pt);
            }
        }
    }
    let outlines: Vec<Bounds> = p.preview.outlines.iter().map(|g| g.bounds()).collect();
    let ids = glyph_ids(&p.preview.outlines);
    let names = items(p);
    // Each stop's gun-on points, gathered once: a long job has hundreds of
    // letters and stops and 10⁵ samples.
    let mut painted_at: Vec<Vec<[f64; 2]>> = vec![Vec::new(); n];
    for i in 0..s.len() {
        if let (Some(k), true) = (station(i), s.paint[i] != 0) {
            painted_at[k].push([s.x_m[i], s.y_m[i]]);
        }
    }
    // The letters each stop's gun paints in: any gun-on sample of the stop
    // inside a letter's box.
    let painted: Vec<Vec<usize>> = (0..n)
        .map(|k| {
            outlines
                .iter()
                .enumerate()
                .filter(|(_, gb)| {
                    // (a box above or below the stop's paint is skipped)
                    let apart = gb.min[1] > on[k].max[1] || gb.max[1] < on[k].min[1];
                    !(gb.is_empty() || apart)
                        && painted_at[k].iter().any(|q| {
                            q[0] >= gb.min[0]
                                && q[0] <= gb.max[0]
                                && q[1] >= gb.min[1]
                                && q[1] <= gb.max[1]
                        })
                })
                .map(|(i, _)| i)
                .collect()
        })
        .collect();
    (0..n)
        .map(|k| {
            let st = &p.job.stations[k];
            let mut b = if on[k].is_empty() { any[k] } else { on[k] };
            if st.x_m.is_finite() && st.y_m.is_finite() {
                b.include([st.x_m, st.y_m]);
            }
            if b.is_empty() {
                b = Bounds {
                    min: [-1.0, -1.0],
                    max: [1.0, 1.0],
                };
            }
            // A line painted whole from this stop by its name (`1: PED`),
            // else its letters painted here (`3.1 A, 3.2 H`); "part of" and
            // the other stops where one letter or item is shared (RXR's
            // symbol is painted from stops 2 and 3).
            let mut said: Vec<String> = Vec::new();
            for (line, text, _) in &names {
                let of_line: Vec<usize> = (0..outlines.len())
                    .filter(|&i| p.preview.outlines[i].line == *line)
                    .collect();
                let here: Vec<usize> = of_line
                    .iter()
                    .copied()
                    .filter(|i| painted[k].contains(i))
                    .collect();
                let shared: Vec<String> = (0..n)
                    .filter(|&o| o != k && here.iter().any(|i| painted[o].contains(i)))
                    .map(|o| (o + 1).to_string())
                    .collect();
                let part = match shared.as_slice() {
                    [] => String::new(),
                    [o] => format!(" (part, with stop {o})"),
                    more => format!(" (part, with stops {})", more.join(", ")),
                };
                match here.len() {
                    0 => {}
                    m if m == of_line.len() => said.push(format!("{text}{part}")),
                    _ => said.extend(
                        here.iter()
                            .map(|&i| format!("{} {}", ids[i], p.preview.outlines[i].label)),
                    ),
                }
            }
            View {
                id: format!("stop-{}", k + 1),
                title: format!("Stop {}", k + 1),
                note: if said.is_empty() {
                    String::new()
                } else {
                    format!("paints {}", said.join(", "))
                },
                bounds: b.grow(0.3),
                path_of: Some(k),
                stops: vec![k],
            }
        })
        .collect()
}

/// The whole scene the overview shows: every letter or item and every stop.
fn scene_bounds(p: &Panel) -> Bounds {
    let mut b = p
        .preview
        .outlines
        .iter()
        .fold(Bounds::EMPTY, |b, g| b.union(g.bounds()));
    for s in &p.job.stations {
        if s.x_m.is_finite() && s.y_m.is_finite() {
            b.include([s.x_m, s.y_m]);
        }
    }
    if b.is_empty() {
        b = panel_bounds(p);
    }
    // The lane across (the road frame's x = 0 is the lane's centre,
    // docs/job.md), so a narrow item is seen in its lane.
    let lane = p.job.layout.lane_width_m;
    if lane.is_finite() && lane > 0.0 && lane < 100.0 {
        b.include([-lane / 2.0, b.min[1]]);
        b.include([lane / 2.0, b.min[1]]);
    }
    b.grow(0.5)
}

/// The overview's largest size (px): as tall as the tallest road view, and
/// narrow, since a scene is one lane and long.
const OVERVIEW_H_PX: f64 = 760.0;
const OVERVIEW_W_PX: f64 = 240.0;

/// Each line or item of the job as the overview names it (`2: [rxr]`,
/// `1: SCHOOL`) with its line number (from 0) and its letters' box.
fn items(p: &Panel) -> Vec<(usize, String, Bounds)> {
    let mut by_line: std::collections::BTreeMap<usize, (Vec<&str>, Bounds)> = Default::default();
    for g in &p.preview.outlines {
        let e = by_line
            .entry(g.line)
            .or_insert_with(|| (Vec::new(), Bounds::EMPTY));
        e.0.push(&g.label);
        e.1 = e.1.union(g.bounds());
    }
    let message: Vec<&str> = p.job.message.split('\n').collect();
    by_line
        .into_iter()
        .filter(|(_, (_, b))| !b.is_empty())
        .map(|(line, (labels, b))| {
            let text = match message.get(line) {
                Some(t) if message.len() == by_line_len(p) => t.to_string(),
                _ if labels.iter().all(|l| l.chars().count() == 1) => labels.concat(),
                _ => labels.join(" "),
            };
            (line, plot::clip(&format!("{}: {text}", line + 1), 28), b)
        })
        .collect()
}

/// How many lines the job's letters fill (the highest line number + 1).
fn by_line_len(p: &Panel) -> usize {
    p.preview
        .outlines
        .iter()
        .map(|g| g.line + 1)
        .max()
        .unwrap_or(0)
}

/// Font size of the overview's item and stop labels (px).
const OVERVIEW_LABEL_PX: f64 = 11.0;

/// `ys` moved down as little as possible so consecutive ones (in page
/// order) are at least `gap` px apart; returned in the input's order.
fn spread(ys: &[f64], gap: f64) -> Vec<f64> {
    let mut order: Vec<usize> = (0..ys.len()).collect();
    order.sort_by(|&a, &b| ys[a].total_cmp(&ys[b]));
    let mut out = ys.to_vec();
    let mut last = f64::NEG_INFINITY;
    for k in order {
        out[k] = out[k].max(last + gap);
        last = out[k];
    }
    out
}

/// Views laid out at most this many to a row. // assumed: four 3.7 m lanes
/// side by side keep letters about 60 px tall on a 900 px page.
const VIEWS_PER_ROW: usize = 4;

/// Clear space between two views of a row beyond the room the right one's
/// y labels take (px).
const VIEW_GAP_PX: f64 = 24.0;

/// Page geometry shared by the drawing and by tests that look at pixels.
struct Page {
    margin: f64,
    header: Vec<(String, String)>,
    head_h: f64,
    map_top: f64,
    frames: Vec<Frame>,
    /// One job's views (its lines' or its stops'), one per frame; `None`
    /// for panels side by side (`--compare`) or a job in one view.
    views: Option<Vec<View>>,
    /// The whole scene of a job painted from two or more stops, and its
    /// item labels' right edge (px).
    overview: Option<(Frame, f64)>,
}

/// `views` at one scale in rows of [`VIEWS_PER_ROW`] from (`left`, `top`),
/// each with a caption line above; their frames and the bottom of the last
/// row. The first of a row has its frame at `left` (its y labels in the
/// margin) or, `room_first`, its y labels from `left`.
fn view_frames(views: &[View], left: f64, top: f64, room_first: bool) -> (Vec<Frame>, f64) {
    let max_w = views.iter().map(|v| v.bounds.width()).fold(0.0, f64::max);
    let max_h = views.iter().map(|v| v.bounds.height()).fold(0.0, f64::max);
    let cols = views.len().clamp(1, VIEWS_PER_ROW);
    let per_view_px = (900.0 - 40.0 * (cols - 1) as f64) / cols as f64;
    let px_per_m = (per_view_px / max_w.max(1e-3)).min(760.0 / max_h.max(1e-3));
    let caption = if views.iter().any(|v| !v.note.is_empty()) {
        CAPTION_PX
    } else if views.iter().any(|v| !v.title.is_empty()) {
        22.0
    } else {
        0.0
    };
    let mut frames = Vec::new();
    let mut top = top + caption;
    for row in views.chunks(VIEWS_PER_ROW) {
        let mut x = left;
        let mut row_h: f64 = 0.0;
        for (k, v) in row.iter().enumerate() {
            let at = |x| Frame::new(x, top, px_per_m, v.bounds.min, v.bounds.max);
            if k > 0 || room_first {
                let gap = if k > 0 { VIEW_GAP_PX } else { 0.0 };
                x += gap + plot::fit_axes(&at(x)).left_px;
            }
            let frame = at(x);
            x += frame.width_px();
            row_h = row_h.max(frame.height_px());
            frames.push(frame);
        }
        top += row_h + 40.0 + caption;
    }
    (frames, top - caption)
}

fn page(panels: &[Panel]) -> Page {
    let margin = 60.0;
    let mut header: Vec<(String, String)> = Vec::new();
    if let Some(p) = panels.first() {
        header.push(("message".into(), p.job.message.replace('\n', " / ")));
        header.push((
            "robot".into(),
            // "stops", as the panels, the job sheet and compile say.
            format!(
                "{} ({} stop{})",
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
                "{}fan {:.1}°, profile {}, {:.2} L/min × {:.2}, raster {} mm",
                // the tip the crew mounts, when the robot lists tips
                p.job
                    .paint
                    .tip
                    .as_ref()
                    .map(|t| format!("tip {t}: "))
                    .unwrap_or_default(),
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
    let mut pg = Page {
        margin,
        header,
        head_h,
        map_top,
        frames: Vec::new(),
        views: None,
        overview: None,
    };
    match panels {
        [p] if p.job.stations.len() > 1 => {
            // The whole scene on the left, each stop's view to its right.
            let b = scene_bounds(p);
            let ppm =
                (OVERVIEW_H_PX / b.height().max(1e-3)).min(OVERVIEW_W_PX / b.width().max(1e-3));
            let ov = Frame::new(margin, map_top + CAPTION_PX, ppm, b.min, b.max);
            let labels_w = items(p)
                .iter()
                .map(|(_, t, _)| plot::text_width_px(t, OVERVIEW_LABEL_PX))
                .fold(0.0, f64::max);
            let ov_right = ov.left_px + ov.width_px() + 8.0 + labels_w;
            let views = stop_views(p);
            let (frames, _) = view_frames(&views, ov_right + VIEW_GAP_PX, map_top, true);
            pg.frames = frames;
            pg.views = Some(views);
            pg.overview = Some((ov, ov_right));
        }
        [p] => {
            let views = line_views(p);
            let (frames, _) = view_frames(&views, margin, map_top, false);
            pg.frames = frames;
            // One view: drawn as a panel, as `--compare` draws each.
            pg.views = (views.len() > 1).then_some(views);
        }
        _ => {
            // Every panel at one scale, so letters compare at a glance.
            let extents: Vec<Bounds> = panels.iter().map(panel_bounds).collect();
            let max_w = extents.iter().map(|b| b.width()).fold(0.0, f64::max);
            let max_h = extents.iter().map(|b| b.height()).fold(0.0, f64::max);
            let px_per_m = (560.0 / max_w.max(1e-3)).min(760.0 / max_h.max(1e-3));
            let mut x = margin;
            for (ext, p) in extents.iter().zip(panels) {
                let frame = Frame::new(x, map_top, px_per_m, ext.min, ext.max);
                x += frame.width_px().max(glyph_table(p).1.iter().sum()) + 60.0;
                pg.frames.push(frame);
            }
        }
    }
    pg
}

/// Where each panel's road frame lands on the page [`render_svg`] draws
/// (for one job, its views' frames).
pub fn panel_frames(panels: &[Panel]) -> Vec<Frame> {
    page(panels).frames
}

/// Height of a view's caption (px): its title, and a note of up to two
/// lines under it.
const CAPTION_PX: f64 = 50.0;

/// `note` in lines of at most `chars` characters, broken at spaces: at most
/// two, the second cut with an ellipsis.
fn note_lines(note: &str, chars: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in note.split(' ') {
        let full = lines.len() == 2;
        match lines.last_mut() {
            // The second line takes the rest, to be cut below.
            Some(l) if full || l.chars().count() + 1 + word.chars().count() <= chars => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines.iter().map(|l| plot::clip(l, chars)).collect()
}

/// A caption over a view whose frame's top left is (`x`, `y`): its title
/// in bold and a note under it, in the view's width.
fn caption(x: f64, y: f64, title: &str, note: &str, width_px: f64) -> Group {
    // assumed: 11 px text averages under 6.5 px a character.
    let lines = if note.is_empty() {
        Vec::new()
    } else {
        note_lines(note, (width_px.max(120.0) / 6.5) as usize)
    };
    let n = lines.len() as f64;
    let mut g = Group::new().add(
        plot::text(x, y - 8.0 - 14.0 * n, title, 13.0, "start")
            .set("font-weight", "bold")
            .set("class", "caption"),
    );
    for (k, line) in lines.iter().enumerate() {
        let ly = y - 7.0 - 14.0 * (n - 1.0 - k as f64);
        g = g.add(plot::text(x, ly, line, 11.0, "start"));
    }
    g
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
    if let ([p], Some(views)) = (panels, &pg.views) {
        // One job, an overview and a view per stop, or a view per line.
        if let Some((ov, labels_right)) = &pg.overview {
            doc_g = doc_g.add(overview(p, ov));
            bottom = bottom.max(ov.top_px + ov.height_px());
            right = right.max(labels_right + 60.0);
        }
        let stations = if views.iter().any(|v| v.path_of.is_some()) {
            pose_stations(p)
        } else {
            Vec::new()
        };
        for (frame, view) in pg.frames.iter().zip(views) {
            let clip_id = format!("{}-clip", view.id);
            let (x0, y0) = (frame.left_px, frame.top_px);
            doc_g = doc_g.add(
                Group::new()
                    .set("id", view.id.clone())
                    .set("class", "view")
                    .add(
                        svg::node::element::ClipPath::new()
                            .set("id", clip_id.clone())
                            .add(
                                // The road inside the frame only: another
                                // view's outlines stop at the view's edge.
                                Rectangle::new()
                                    .set("x", plot::num(x0))
                                    .set("y", plot::num(y0))
                                    .set("width", plot::num(frame.width_px()))
                                    .set("height", plot::num(frame.height_px())),
                            ),
                    )
                    .add(caption(x0, y0, &view.title, &view.note, frame.width_px()))
                    .add(
                        road_layers(p, frame, vmax, view, &stations)
                            .set("clip-path", format!("url(#{clip_id})")),
                    )
                    .add(plot::axes_fitted(frame, "x (m)", "y (m)")),
            );
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
    } else {
        for (p, frame) in panels.iter().zip(&pg.frames) {
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
            let table_top = frame.top_px + frame.height_px() + 50.0;
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

/// The whole scene at a glance: the road, every letter or item outlined
/// and named at the right, every stop's arm axis marked and numbered.
fn overview(p: &Panel, frame: &Frame) -> Group {
    let (x0, y0) = (frame.left_px, frame.top_px);
    let (w, h) = (frame.width_px(), frame.height_px());
    let mut d = String::new();
    for gl in &p.preview.outlines {
        for poly in &gl.strokes {
            d.push_str(&frame.path_data(poly, true));
        }
    }
    let mut g = Group::new()
        .set("id", "overview")
        .set("class", "view")
        .add(caption(x0, y0, "Whole scene", "", w))
        .add(
            Rectangle::new()
                .set("x", plot::num(x0))
                .set("y", plot::num(y0))
                .set("width", plot::num(w))
                .set("height", plot::num(h))
                .set("fill", palette::ROAD),
        )
        .add(
            Path::new()
                .set("d", d)
                .set("fill", "#ffffff")
                .set("stroke", palette::OUTLINE)
                .set("stroke-width", 0.8)
                .set("stroke-linejoin", "round"),
        );
    let halo = || {
        Group::new()
            .set("paint-order", "stroke")
            .set("stroke", "#ffffff")
            .set("stroke-width", 2.5)
            .set("stroke-linejoin", "round")
    };
    // Items named beside the road, at their middles, never on each other.
    let items = items(p);
    let mids: Vec<f64> = items
        .iter()
        .map(|(_, _, b)| frame.px([0.0, (b.min[1] + b.max[1]) / 2.0]).1 + 4.0)
        .collect();
    let mut names = Group::new().set("class", "items");
    for ((_, text, b), y) in items.iter().zip(spread(&mids, OVERVIEW_LABEL_PX + 3.0)) {
        let (_, top) = frame.px([0.0, b.max[1]]);
        let (_, foot) = frame.px([0.0, b.min[1]]);
        let x = x0 + w;
        names = names
            // A bracket along the item's length at the road's edge.
            .add(plot::line(x + 3.0, top, x + 3.0, foot, palette::INK, 1.0))
            .add(plot::text(x + 8.0, y, text, OVERVIEW_LABEL_PX, "start"));
    }
    g = g.add(names);
    // Stops: the arm axis, its heading, "Stop k" beside it.
    let pts: Vec<(usize, (f64, f64))> = p
        .job
        .stations
        .iter()
        .enumerate()
        .filter(|(_, s)| s.x_m.is_finite() && s.y_m.is_finite())
        .map(|(k, s)| (k, frame.px([s.x_m, s.y_m])))
        .collect();
    let ys: Vec<f64> = pts.iter().map(|(_, (_, y))| y + 4.0).collect();
    let mut stops = halo().set("class", "stops");
    for ((k, (sx, sy)), ly) in pts.iter().zip(spread(&ys, OVERVIEW_LABEL_PX + 3.0)) {
        let s = &p.job.stations[*k];
        // The heading 14 px long at any scale.
        let (hx, hy) = (
            sx + 14.0 * s.heading_rad.cos(),
            sy - 14.0 * s.heading_rad.sin(),
        );
        stops = stops
            .add(plot::line(*sx, *sy, hx, hy, palette::STATION, 1.5))
            .add(
                Circle::new()
                    .set("cx", plot::num(*sx))
                    .set("cy", plot::num(*sy))
                    .set("r", 4)
                    .set("fill", palette::STATION),
            )
            .add(
                plot::text(
                    sx + 8.0,
                    ly,
                    &format!("Stop {}", k + 1),
                    OVERVIEW_LABEL_PX,
                    "start",
                )
                .set("font-weight", "bold"),
            );
    }
    g.add(stops).add(plot::axes_fitted(frame, "x (m)", "y (m)"))
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

/// A panel of a whole job: every stop's path and every stop.
fn draw_panel(p: &Panel, frame: &Frame, vmax: f64) -> Group {
    let all = View {
        id: String::new(),
        title: String::new(),
        note: String::new(),
        bounds: Bounds::EMPTY,
        path_of: None,
        stops: (0..p.job.stations.len()).collect(),
    };
    road_layers(p, frame, vmax, &all, &[]).add(plot::axes_fitted(frame, "x (m)", "y (m)"))
}

/// The stop (index into the job's stations) each pose was laid from: the
/// job's sample at or before the pose's time (the poses of a simulated arm
/// are 5 ms ticks, not the job's rows).
fn pose_stations(p: &Panel) -> Vec<Option<usize>> {
    let s = &p.job.samples;
    p.preview
        .poses
        .iter()
        .map(|pose| {
            let i = s.t_s.partition_point(|&t| t <= pose.t_s);
            s.station.get(i.saturating_sub(1)).map(|&k| k as usize)
        })
        .collect()
}

/// What [`draw_panel`] draws inside the frame: film, outlines, nozzle path,
/// stations and labels (everything but the axes); of the nozzle path,
/// stroke numbers and stops only what `view` shows.
/// `stations[i]`: the stop pose i was laid from ([`pose_stations`]), needed
/// only when the view shows one stop's path.
fn road_layers(
    p: &Panel,
    frame: &Frame,
    vmax: f64,
    view: &View,
    stations: &[Option<usize>],
) -> Group {
    let target = p.preview.metrics.target_film_m;
    // Only the cells the frame shows (a line's view of a long job; laid
    // again for that view when the job was measured band by band). Its
    // paint was laid once already, so laying it again fails only where that
    // did (`film_over`); then the view shows the road without film.
    let shown = Bounds {
        min: frame.road_min,
        max: frame.road_max,
    };
    let film = p.preview.film_over(shown);
    let bare;
    let grid: &Grid = match &film {
        Ok(g) => g,
        Err(_) => {
            bare = Grid {
                x0: frame.road_min[0],
                y0: frame.road_min[1],
                cell_m: p.preview.cell_m,
                nx: 0,
                ny: 0,
                data: Vec::new(),
            };
            &bare
        }
    };
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
    // Letter outlines: those the frame shows (a long job's view of one
    // line drew every line's outlines, clipped: 40 views of a 200-letter
    // job made a 137 MB picture).
    let mut d = String::new();
    for gl in p
        .preview
        .outlines
        .iter()
        .filter(|gl| gl.bounds().meets(&shown))
    {
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
    let keep = |i: usize| {
        view.path_of
            .is_none_or(|k| stations.get(i).copied().flatten() == Some(k))
    };
    let (on, off) = path_runs(&p.preview.poses, frame, &keep);
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
    for &k in &view.stops {
        let Some(s) = p.job.stations.get(k) else {
            continue;
        };
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
                &format!("Stop {}", k + 1),
                11.0,
                "start",
            ));
    }
    g.add(labels(p, frame, view.path_of))
}

/// Letter labels (`1.3 O`) over each letter and stroke numbers (as the
/// warnings number them) at the middle of each stroke's painted run.
fn labels(p: &Panel, frame: &Frame, stop: Option<usize>) -> Group {
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
        let here = stop.is_none_or(|k| s.station[i] as usize == k);
        if s.paint[i] != 0 && s.stroke[i] >= 0 && here {
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

/// SVG path data of the nozzle's path (tip's foot) with the gun on and off;
/// points closer than half a pixel to the previous are dropped.
/// Only the steps from a pose `keep` accepts are drawn.
fn path_runs(poses: &[Pose], frame: &Frame, keep: &dyn Fn(usize) -> bool) -> (String, String) {
    let (mut on, mut off) = (String::new(), String::new());
    // The run's gun state and the pen's last drawn point.
    let mut pen: Option<(bool, (f64, f64))> = None;
    for (i, w) in poses.windows(2).enumerate() {
        if !keep(i) {
            pen = None;
            continue;
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_too_close_are_moved_apart_in_page_order() {
        // Two stops 5 px apart on the page and one far off: the lower of
        // the two moves down to 14 px under the upper, the far one stays.
        let ys = [105.0, 100.0, 300.0];
        assert_eq!(spread(&ys, 14.0), vec![114.0, 100.0, 300.0]);
        // A run of three pushes each in turn.
        assert_eq!(spread(&[0.0, 1.0, 2.0], 10.0), vec![0.0, 10.0, 20.0]);
        assert!(spread(&[], 10.0).is_empty());
    }

    #[test]
    fn notes_break_at_spaces_into_two_lines_at_most() {
        assert_eq!(note_lines("paints 1: PED", 30), ["paints 1: PED"]);
        assert_eq!(
            note_lines("paints 2: [rxr] (part, with stop 3)", 23),
            ["paints 2: [rxr] (part,", "with stop 3)"]
        );
        let long = note_lines("paints 3.1 A, 3.2 H, 3.3 E, 3.4 A, 3.5 D, 4.1 S", 14);
        assert_eq!(long.len(), 2);
        assert!(long.iter().all(|l| l.chars().count() <= 14), "{long:?}");
        assert!(long[1].ends_with('…'), "{long:?}");
    }

    #[test]
    fn a_stop_belongs_to_the_nearest_line_only() {
        let line = |y0: f64, y1: f64| Bounds {
            min: [-1.0, y0],
            max: [1.0, y1],
        };
        // RXR's lines: 0–0.61, 5.18–10.06, 14.63–15.24 m.
        let lines = [line(0.0, 0.61), line(5.18, 10.06), line(14.63, 15.24)];
        // Stop 3 (12.55 m) was drawn with both lines within 3 m of it;
        // stop 4 (18.53 m), over 3 m past the last line, with none.
        assert_eq!(nearest(&lines, [0.0, 12.55]), 2);
        assert_eq!(nearest(&lines, [0.0, 18.53]), 2);
        assert_eq!(nearest(&lines, [0.0, 2.0]), 0);
        assert_eq!(nearest(&lines, [0.0, 7.0]), 1);
        assert_eq!(nearest(&[], [0.0, 7.0]), 0);
    }
}
