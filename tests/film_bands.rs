//! A long job's film is laid and measured band by band along the road
//! (`paint::bands`), at a band's memory: the figures must be the ones the
//! whole job's raster gives (to rounding: the same cells, summed in
//! another order), every glyph and painted interval must be in exactly
//! one band, and a picture's view laid again must show the whole raster's
//! cells.

use basr::paint::bands::bands;
use basr::paint::metrics::Metrics;
use basr::paint::preview::{self, Options, Preview};
use basr::paint::raster::{self, Bounds, FIT_CELLS};
use basr::pipeline::compile::{compile_job, CompileRequest};

/// A two-line job (its lines metres apart), planned without verification
/// or film check: the preview measures it here.
fn two_lines() -> basr::job::Job {
    let mut req = CompileRequest::message("STOP AHEAD");
    req.verify = false;
    req.film = false;
    compile_job(&req).expect("STOP AHEAD plans")
}

/// The preview with rasters up to `band_cells` laid whole.
fn measured(job: &basr::job::Job, band_cells: usize) -> Preview {
    let opts = Options {
        fit_cells: Some(FIT_CELLS),
        band_cells,
        ..Options::default()
    };
    preview::preview_job(job, &opts).expect("the preview measures it")
}

fn close(a: f64, b: f64, what: &str) {
    let scale = a.abs().max(b.abs()).max(1e-300);
    assert!((a - b).abs() <= 1e-9 * scale, "{what}: {a:e} vs {b:e}");
}

fn close_opt(a: Option<f64>, b: Option<f64>, what: &str) {
    match (a, b) {
        (Some(a), Some(b)) => close(a, b, what),
        (a, b) => assert_eq!(a, b, "{what}"),
    }
}

/// The whole job's figures (not its glyphs').
fn same_job_figures(a: &Metrics, b: &Metrics) {
    close_opt(a.cv, b.cv, "cv");
    close_opt(a.coverage, b.coverage, "coverage");
    close_opt(a.overspray, b.overspray, "overspray");
    close_opt(a.mean_film_m, b.mean_film_m, "mean film");
    close(a.letter_area_m2, b.letter_area_m2, "letter area");
    close(
        a.volume_on_road_m3,
        b.volume_on_road_m3,
        "volume on the road",
    );
    assert_eq!(a.edge_points, b.edge_points);
}

fn same_metrics(a: &Metrics, b: &Metrics) {
    same_job_figures(a, b);
    close(a.volume_laid_m3, b.volume_laid_m3, "volume laid");
    close(a.gun_on_s, b.gun_on_s, "gun-on time");
    close_opt(a.edge_width_m, b.edge_width_m, "edge width");
    close_opt(a.edge_width_p90_m, b.edge_width_p90_m, "edge width p90");
    assert_eq!((a.u_min, a.u_max), (b.u_min, b.u_max));
    assert_eq!(a.resolution_m, b.resolution_m);
    assert_eq!(a.strokes, b.strokes);
    assert_eq!(a.glyphs.len(), b.glyphs.len());
    for (ga, gb) in a.glyphs.iter().zip(&b.glyphs) {
        let what = format!("glyph {} of line {}", ga.char, ga.line);
        assert_eq!((&ga.char, ga.line), (&gb.char, gb.line));
        close(ga.area_m2, gb.area_m2, &what);
        close_opt(ga.cv, gb.cv, &what);
        close_opt(ga.coverage, gb.coverage, &what);
        close_opt(ga.overspray, gb.overspray, &what);
        close_opt(ga.mean_film_m, gb.mean_film_m, &what);
    }
    assert_eq!(a.peaks.len(), b.peaks.len());
    for (pa, pb) in a.peaks.iter().zip(&b.peaks) {
        let (pa, pb) = (pa.expect("a peak"), pb.expect("a peak"));
        close(pa.film_m, pb.film_m, "peak film");
        // the same cell: its centre to rounding (each raster's origin is
        // its own multiple of the cell)
        close(pa.at_m[0], pb.at_m[0], "the peak's cell");
        close(pa.at_m[1], pb.at_m[1], "the peak's cell");
    }
}

#[test]
fn a_job_measured_in_bands_has_the_whole_rasters_figures() {
    let job = two_lines();
    let whole = measured(&job, usize::MAX);
    let banded = measured(&job, 0);
    assert!(whole.film.is_some(), "laid whole");
    assert!(banded.film.is_none(), "laid band by band");
    same_metrics(&whole.metrics, &banded.metrics);
    // The default keeps a job of two lines on one raster.
    assert!(measured(&job, basr::paint::bands::BAND_CELLS)
        .film
        .is_some());
}

#[test]
fn every_glyph_and_painted_interval_is_in_one_band() {
    let job = two_lines();
    let p = measured(&job, usize::MAX);
    let painted = raster::painted_intervals(&p.poses);
    let reach = p.model.depth.reach_m();
    let b = bands(&p.poses, &painted, &p.model, reach, &p.outlines, p.cell_m).unwrap();
    // STOP and AHEAD stand metres apart: a band each.
    assert_eq!(
        b.len(),
        2,
        "{:?}",
        b.iter().map(|b| b.extent).collect::<Vec<_>>()
    );
    let mut intervals: Vec<usize> = b.iter().flat_map(|b| b.intervals.clone()).collect();
    intervals.sort_unstable();
    assert_eq!(intervals, painted);
    let mut glyphs: Vec<usize> = b.iter().flat_map(|b| b.glyphs.clone()).collect();
    glyphs.sort_unstable();
    assert_eq!(glyphs, (0..p.outlines.len()).collect::<Vec<_>>());
    // Each band's letters are one line's, and the bands do not overlap.
    for band in &b {
        let lines: Vec<usize> = band.glyphs.iter().map(|&g| p.outlines[g].line).collect();
        assert!(lines.windows(2).all(|w| w[0] == w[1]), "{lines:?}");
    }
    assert!(b[0].extent.max[1] < b[1].extent.min[1]);
}

#[test]
fn a_view_laid_again_shows_the_whole_rasters_cells() {
    let job = two_lines();
    let whole = measured(&job, usize::MAX);
    let banded = measured(&job, 0);
    let w = &whole.film.as_ref().unwrap().grid;
    // A view across the second line's letters.
    let line = |l: usize| {
        whole
            .outlines
            .iter()
            .filter(|o| o.line == l)
            .fold(Bounds::EMPTY, |b, o| b.union(o.bounds()))
    };
    let view = line(1).grow(0.05);
    let g = banded.film_over(view).unwrap();
    assert!((g.cell_m - w.cell_m).abs() < 1e-15);
    let (mut checked, mut painted) = (0, 0);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let c = g.centre(i, j);
            if !(view.min[0] < c[0]
                && c[0] < view.max[0]
                && view.min[1] < c[1]
                && c[1] < view.max[1])
            {
                continue;
            }
            let wi = ((c[0] - w.x0) / w.cell_m).floor();
            let wj = ((c[1] - w.y0) / w.cell_m).floor();
            if wi < 0.0 || wj < 0.0 || wi >= w.nx as f64 || wj >= w.ny as f64 {
                // beyond the whole raster: no paint there
                assert_eq!(g.at(i, j), 0.0);
                continue;
            }
            let (a, b) = (g.at(i, j), w.at(wi as usize, wj as usize));
            assert!(
                (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-12),
                "{a} vs {b}"
            );
            checked += 1;
            painted += usize::from(a > 0.0);
        }
    }
    assert!(
        checked > 1000 && painted > 100,
        "{checked} cells, {painted} painted"
    );
}

/// Paint far from every letter (a line whose letters the job does not
/// list: a band of paint alone) is measured as the whole raster measures
/// it: the same volume (no paint lost at a band's border), overspray,
/// coverage and cv; only a letter's own overspray no longer counts paint
/// in another band (docs/preview.md).
#[test]
fn a_band_of_paint_without_letters_keeps_the_jobs_figures() {
    let mut job = two_lines();
    job.layout.glyphs.retain(|g| g.line == 0);
    let whole = measured(&job, usize::MAX);
    let banded = measured(&job, 0);
    assert!(banded.film.is_none());
    let (a, b) = (&whole.metrics, &banded.metrics);
    same_job_figures(a, b);
    // half the paint is AHEAD's, outside every listed letter
    assert!(a.overspray.unwrap() > 0.4, "{:?}", a.overspray);
    assert_eq!(a.glyphs.len(), b.glyphs.len());
}

/// A view of the whole of a long job (a `--compare` panel) is laid again
/// at a cell that keeps it to a band's memory, and holds all the paint.
#[test]
fn a_whole_job_view_is_coarsened_to_a_bands_memory() {
    let job = two_lines();
    let banded = measured(&job, 0);
    let view = banded.film_over(banded.raster_bounds).unwrap();
    assert!(view.nx * view.ny <= basr::paint::bands::BAND_CELLS);
    let on_view = view.data.iter().sum::<f64>() * view.cell_m * view.cell_m;
    close_within(on_view, banded.metrics.volume_on_road_m3, 1e-9);
}

fn close_within(a: f64, b: f64, rel: f64) {
    assert!(
        (a - b).abs() <= rel * a.abs().max(b.abs()),
        "{a:e} vs {b:e}"
    );
}
