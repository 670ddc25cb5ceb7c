//! A job's preview: its samples as poses, the film they lay, the metrics
//! against the letters' outlines; `drawing` makes the SVG that shows it all.

use rayon::prelude::*;
use serde::Serialize;

use super::bands;
pub use super::drawing::{panel_frames, render_svg, Panel};
use super::mask;
use super::metrics::{self, GlyphOutline, Metrics};
use super::raster::{self, Bounds, Film, Grid, Progress};
use super::spray::{Depth, Pose, Profile, SprayModel};
use super::verdict::Verdict;
use super::PaintError;
use basr_job::{Job, Samples};

/// Default raster cell (issue 5: `--resolution-mm` default 5).
pub const DEFAULT_RESOLUTION_M: f64 = 0.005;

/// How to run the preview.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    pub resolution_m: f64,
    pub profile: Profile,
    pub depth: Depth,
    /// Coarsen the raster held at once (the whole raster, or a long job's
    /// largest band) until it holds at most this many cells (the
    /// command's default when no `--resolution-mm` is given); `None` keeps
    /// `resolution_m` and refuses such a raster over [`raster::MAX_CELLS`].
    /// A picture's view laid again is coarsened to its own budget
    /// ([`Preview::film_over`]).
    pub fit_cells: Option<usize>,
    /// The largest raster laid whole; a larger one is laid and measured
    /// band by band along the road (`bands`; the same figures to rounding,
    /// at a band's memory).
    pub band_cells: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            resolution_m: DEFAULT_RESOLUTION_M,
            profile: Profile::Uniform,
            depth: Depth::default(),
            fit_cells: None,
            band_cells: bands::BAND_CELLS,
        }
    }
}

/// A computed preview of one job.
#[derive(Clone, Debug)]
pub struct Preview {
    /// The film over everything the job paints and every letter; `None`
    /// for a long job, measured band by band (`bands`): [`Preview::film_over`]
    /// lays the part a picture shows.
    pub film: Option<Film>,
    /// Where the film was laid: the raster's extent (the bands' together).
    pub raster_bounds: Bounds,
    /// The raster's cell (m).
    pub cell_m: f64,
    /// The fan and the flow reaching the road (m³/s) it was laid with.
    pub model: SprayModel,
    pub flow_eff_m3ps: f64,
    /// A long job's bands (none when the film was laid whole), for
    /// [`Preview::film_over`] to lay again the ones a view meets.
    pub bands: Vec<bands::Band>,
    pub metrics: Metrics,
    pub outlines: Vec<GlyphOutline>,
    pub poses: Vec<Pose>,
    pub profile: String,
}

/// The job's setpoints as poses (SPEC §3 columns).
pub fn poses_from_samples(s: &Samples) -> Vec<Pose> {
    (0..s.len())
        .map(|i| Pose {
            t_s: s.t_s[i],
            x_m: s.x_m[i],
            y_m: s.y_m[i],
            z_m: s.z_m[i],
            yaw_rad: s.yaw_rad[i],
            tilt_rad: s.tilt_rad[i],
            gun: s.paint[i] != 0,
        })
        .collect()
}

/// `pose`, painted from the job's station `station` (its index), as the
/// flat-road pose that lays the same film on the job's road: the nozzle's
/// height over the surface, its lean against it and the foot of the
/// perpendicular (docs/site.md). The pose itself on a flat road.
pub fn on_road(job: &Job, station: usize, pose: Pose) -> Pose {
    let Some(st) = job.stations.get(station).filter(|_| !job.road.is_flat()) else {
        return pose;
    };
    let r = job.road.relative(
        station,
        st,
        [pose.x_m, pose.y_m],
        pose.z_m,
        pose.yaw_rad,
        pose.tilt_rad,
    );
    Pose {
        x_m: r.xy[0],
        y_m: r.xy[1],
        z_m: r.height_m,
        tilt_rad: r.tilt_rad,
        ..pose
    }
}

fn check_paint(job: &Job) -> Result<(), PaintError> {
    let p = &job.paint;
    for (name, v) in [
        ("paint.fan_angle_rad", p.fan_angle_rad),
        ("paint.flow_m3ps", p.flow_m3ps),
        ("paint.transfer_efficiency", p.transfer_efficiency),
        ("paint.film_m", p.film_m),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(PaintError::Job(format!(
                "{name} is {v}: it must be a number above zero"
            )));
        }
    }
    if p.transfer_efficiency > 1.0 {
        return Err(PaintError::Job(format!(
            "paint.transfer_efficiency is {}: it must be at most 1",
            p.transfer_efficiency
        )));
    }
    Ok(())
}

/// Simulate the film of `job` and measure it.
pub fn preview_job(job: &Job, opts: &Options) -> Result<Preview, PaintError> {
    preview_job_with_progress(job, opts, &|_, _| {})
}

/// [`preview_job`], telling `progress` how far the deposition has got.
pub fn preview_job_with_progress(
    job: &Job,
    opts: &Options,
    progress: Progress,
) -> Result<Preview, PaintError> {
    check_paint(job)?;
    let poses: Vec<Pose> = poses_from_samples(&job.samples)
        .into_iter()
        .zip(&job.samples.station)
        .map(|(p, &st)| on_road(job, st as usize, p))
        .collect();
    let outlines: Vec<GlyphOutline> = job
        .layout
        .glyphs
        .iter()
        .map(GlyphOutline::from_placed)
        .collect();
    preview_tiled(
        poses,
        None,
        &job.samples.stroke,
        &outlines,
        &job.paint,
        opts,
        progress,
    )
}

/// Simulate and measure the film of any pose sequence with `stroke_of[i]`
/// the stroke index of pose i (−1 none); the tiles of U are its consecutive
/// poses.
pub fn preview_poses(
    poses: &[Pose],
    stroke_of: &[i64],
    outlines: &[GlyphOutline],
    paint: &basr_job::Paint,
    opts: &Options,
) -> Result<Preview, PaintError> {
    preview_tiled(
        poses.to_vec(),
        None,
        stroke_of,
        outlines,
        paint,
        opts,
        &|_, _| {},
    )
}

/// The film of `poses` (kept in the preview, for its picture), with U
/// measured on the tiles between consecutive `tiles` (the poses when
/// `None`; `stroke_of[i]` the stroke of tile i). The simulator's trace
/// deposits from every 5 ms tick, but its tiles are taken at the job's own
/// setpoint times: a tile 0.8 mm long is twisted end to end by the servos'
/// jitter, and its U says nothing about the paint's distribution.
pub fn preview_tiled(
    poses: Vec<Pose>,
    tiles: Option<&[Pose]>,
    stroke_of: &[i64],
    outlines: &[GlyphOutline],
    paint: &basr_job::Paint,
    opts: &Options,
    progress: Progress,
) -> Result<Preview, PaintError> {
    let tiles = tiles.unwrap_or(&poses);
    let model = SprayModel::new(paint.fan_angle_rad, opts.profile.clone(), opts.depth)?;
    let letters = outlines
        .iter()
        .fold(Bounds::EMPTY, |b, g| b.union(g.bounds()));
    let painted = raster::painted_bounds(&poses, &model)?;
    let extent = match (painted.is_empty(), letters.is_empty()) {
        (true, _) => letters,
        (_, true) => painted,
        _ => painted.union(letters),
    };
    let flow_eff_m3ps = paint.flow_m3ps * paint.transfer_efficiency;
    // The cell: the one asked for, coarsened (`fit_cells`) only where the
    // raster held at once would pass the budget: the whole raster, or a
    // long job's largest band (its raster is held a band at a time).
    let wanted = opts.resolution_m;
    let fitted = |b: Bounds| match opts.fit_cells {
        Some(budget) => raster::fitted_cell(b, wanted, budget),
        None => wanted,
    };
    let (cell_m, banded) = if extent.is_empty() || bands::whole(extent, wanted, opts.band_cells) {
        (fitted(extent), None)
    } else {
        raster::check_poses(&poses, flow_eff_m3ps)?;
        let intervals = raster::painted_intervals(&poses);
        let reach = raster::depth_reach(&model);
        let found = bands::bands(&poses, &intervals, &model, reach, outlines, wanted)?;
        let area = |b: &Bounds| b.width() * b.height();
        let largest = found
            .iter()
            .map(|b| b.extent)
            .max_by(|a, b| area(a).total_cmp(&area(b)));
        let cell = fitted(largest.unwrap_or(extent));
        let found = if cell == wanted {
            found
        } else {
            bands::bands(&poses, &intervals, &model, reach, outlines, cell)?
        };
        (cell, Some((intervals, found)))
    };
    let preview = |film: Option<Film>, raster_bounds, metrics, poses, bands| Preview {
        film,
        raster_bounds,
        cell_m,
        model: model.clone(),
        flow_eff_m3ps,
        bands,
        metrics,
        outlines: outlines.to_vec(),
        poses,
        profile: opts.profile.name(),
    };
    let Some((intervals, bands)) = banded else {
        let all: Vec<usize> = (0..outlines.len()).collect();
        let masks = mask::Masks::of(outlines, &all);
        let lattice = |g: &Grid| masks.lattice(g);
        let film = raster::deposit_with_progress(
            &poses,
            &model,
            flow_eff_m3ps,
            cell_m,
            letters,
            Some(&lattice),
            progress,
        )?;
        let masks = masks.take(&film.grid);
        let metrics = metrics::measure(
            &film,
            masks,
            outlines,
            paint.film_m,
            &model,
            tiles,
            stroke_of,
        )?;
        let bounds = film.grid.bounds();
        return Ok(preview(Some(film), bounds, metrics, poses, Vec::new()));
    };
    // A long job: band by band, each band's raster dropped once measured.
    let strokes = metrics::stroke_u(&model, tiles, stroke_of, outlines)?;
    // The bands in parallel (a band's measuring is one thread's work, its
    // deposit every thread's): each band's figures are its own whatever
    // the order they are made in, and they are added in the road's order.
    let done = std::sync::atomic::AtomicUsize::new(0);
    let per_band: Vec<(metrics::Part, f64, Bounds)> = bands
        .par_iter()
        .map(|band| {
            let masks = mask::Masks::of(outlines, &band.glyphs);
            let lattice = |g: &Grid| masks.lattice(g);
            let film = raster::deposit_intervals(
                &poses,
                &band.intervals,
                &model,
                flow_eff_m3ps,
                raster::Sheet {
                    cell_m,
                    extent: band.extent,
                    letters: Some(&lattice),
                },
                &|_, _| {},
            )?;
            let masks = masks.take(&film.grid);
            let part =
                metrics::measure_part(&film, masks, outlines, &band.glyphs, paint.film_m, &strokes);
            let n = done.fetch_add(band.intervals.len(), std::sync::atomic::Ordering::Relaxed);
            progress(n + band.intervals.len(), intervals.len());
            Ok((part, film.gun_on_s, film.grid.bounds()))
        })
        .collect::<Result<_, PaintError>>()?;
    let (mut parts, mut gun_on_s, mut raster_bounds) =
        (Vec::with_capacity(bands.len()), 0.0, Bounds::EMPTY);
    for (part, gun_on, bounds) in per_band {
        parts.push(part);
        gun_on_s += gun_on;
        raster_bounds = raster_bounds.union(bounds);
    }
    let metrics = metrics::finish(
        parts,
        metrics::Whole {
            target_film_m: paint.film_m,
            resolution_m: cell_m,
            volume_laid_m3: flow_eff_m3ps * gun_on_s,
            gun_on_s,
            glyphs: outlines,
        },
        strokes,
    );
    Ok(preview(None, raster_bounds, metrics, poses, bands))
}

impl Preview {
    /// The film over `b` on the preview's raster lattice: the whole film's
    /// cells there, or, for a long job measured band by band, the paint of
    /// every interval that lands in `b` laid again (a picture's view).
    pub fn film_over(&self, b: Bounds) -> Result<std::borrow::Cow<'_, Grid>, PaintError> {
        if let Some(film) = &self.film {
            return Ok(std::borrow::Cow::Borrowed(&film.grid));
        }
        // A view of many bands (the whole scene of a long job, `--compare`'s
        // panels) is a picture, drawn far coarser than the raster's cell: it
        // is laid at a cell that keeps it to a band's memory.
        let cell_m = raster::fitted_cell(b, self.cell_m, bands::BAND_CELLS);
        // Every interval whose paint can land in `b` is in a band whose
        // extent meets it (a band's extent holds its paint).
        let hits: Vec<usize> = self
            .bands
            .iter()
            .filter(|band| band.extent.meets(&b))
            .flat_map(|band| band.intervals.iter().copied())
            .collect();
        let film = raster::deposit_intervals(
            &self.poses,
            &hits,
            &self.model,
            self.flow_eff_m3ps,
            raster::Sheet {
                cell_m,
                extent: b,
                letters: None,
            },
            &|_, _| {},
        )?;
        Ok(std::borrow::Cow::Owned(film.grid))
    }
}

/// What `--json` prints.
#[derive(Serialize)]
pub struct JsonReport<'a> {
    pub job: &'a str,
    pub message: &'a str,
    pub tilt_method: &'a str,
    pub profile: &'a str,
    pub svg: Option<&'a str>,
    /// For a job re-planned by `--compare`: from what, and what the job
    /// does not record (so compile's defaults were used).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replanned: Option<&'a str>,
    /// The film is the simulated arm's (`--from-sim`).
    pub from_sim: bool,
    /// `verdict` ("pass" / "fail"), `thresholds`, `checks`.
    #[serde(flatten)]
    pub verdict: &'a Verdict,
    #[serde(flatten)]
    pub metrics: &'a Metrics,
}
