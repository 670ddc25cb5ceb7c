//! The words and numbers on a preview panel: the header's key–value lines
//! (the job, the film's figures and verdict) and the per-letter table.

use super::drawing::Panel;
use super::metrics::{GlyphOutline, Metrics};
use basr_plot as plot;

fn pct(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{:.1} %", v * 100.0))
}

fn um(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{:.0} µm", v * 1e6))
}

fn mm(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{:.1} mm", v * 1e3))
}

fn u_range(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) => format!("{:.1}–{:.1}", a * 100.0, b * 100.0),
        _ => "–".into(),
    }
}

/// The metric lines of the title block.
fn metric_lines(m: &Metrics) -> Vec<(String, String)> {
    vec![
        (
            "mean film".into(),
            format!(
                "{} (target {:.0} µm, {})",
                um(m.mean_film_m),
                m.target_film_m * 1e6,
                pct(m.mean_film_m.map(|f| f / m.target_film_m))
            ),
        ),
        ("CV inside letters".into(), pct(m.cv)),
        ("coverage (≥ 50 %)".into(), pct(m.coverage)),
        ("overspray".into(), pct(m.overspray)),
        ("U range (50 ideal)".into(), u_range(m.u_min, m.u_max)),
        (
            "edge 90→10 %".into(),
            format!(
                "{} median, {} p90",
                mm(m.edge_width_m),
                mm(m.edge_width_p90_m)
            ),
        ),
        (
            "paint".into(),
            format!(
                "{:.2} L on the road of {:.2} L laid, gun on {:.1} s",
                m.volume_on_road_m3 * 1e3,
                m.volume_laid_m3 * 1e3,
                m.gun_on_s
            ),
        ),
    ]
}

/// A panel's caption: its verdict, where its film comes from, its metrics.
pub(super) fn panel_lines(p: &Panel) -> Vec<(String, String)> {
    let v = p.verdict;
    let mut lines = vec![(
        "film verdict".to_string(),
        if v.pass() {
            "PASS (cv, coverage and overspray within the limits)".to_string()
        } else {
            format!("FAIL: {}", v.reasons())
        },
    )];
    if p.from_sim {
        lines.push((
            "film of".into(),
            "the SIMULATED arm (basr simulate, sjct controller), not the plan".into(),
        ));
    }
    lines.extend(metric_lines(&p.preview.metrics));
    lines
}

fn glyph_rows(m: &Metrics, outlines: &[GlyphOutline]) -> Vec<Vec<String>> {
    m.glyphs
        .iter()
        .zip(glyph_ids(outlines))
        .map(|(g, id)| {
            vec![
                format!("{id} {}", g.char),
                // People count lines from 1, as compile's warnings do.
                (g.line + 1).to_string(),
                format!("{:.3}", g.area_m2),
                um(g.mean_film_m),
                pct(g.cv),
                pct(g.coverage),
                pct(g.overspray),
                u_range(g.u_min, g.u_max),
            ]
        })
        .collect()
}

pub(super) const GLYPH_HEADER: [&str; 8] = [
    "letter",
    "line",
    "area m²",
    "mean",
    "CV",
    "coverage",
    "overspray",
    "U",
];
const GLYPH_WIDTHS: [f64; 8] = [60.0, 35.0, 60.0, 60.0, 55.0, 65.0, 65.0, 70.0];

/// A panel's per-glyph table: its rows and their column widths.
pub(super) fn glyph_table(p: &Panel) -> (Vec<Vec<String>>, Vec<f64>) {
    let rows = glyph_rows(&p.preview.metrics, &p.preview.outlines);
    let widths = plot::fit_widths(&GLYPH_WIDTHS, &GLYPH_HEADER, &rows);
    (rows, widths)
}

/// `line.place` of every glyph as the text numbers them (1-based), in the
/// glyph table's order: `1.3` is the third letter of the first line.
pub(super) fn glyph_ids(outlines: &[GlyphOutline]) -> Vec<String> {
    let mut seen = std::collections::BTreeMap::<usize, usize>::new();
    outlines
        .iter()
        .map(|g| {
            let place = seen.entry(g.line).or_insert(0);
            *place += 1;
            format!("{}.{}", g.line + 1, place)
        })
        .collect()
}
