//! The film check of a compiled job: the sealed job's film measured by the
//! preview's own stage (`paint::film`, at `basr preview`'s defaults) and
//! every bound it misses made a [`Note::Film`], so compile's verdict knows
//! what the preview will say (docs/planner.md "Film").

use crate::job::{FilmSummary, Job};
use crate::paint::film::{self, FilmOptions, JobFilm};
use crate::paint::metrics::GlyphMetrics;
use crate::paint::Profile;

use basr_plan::error::CompileError;
use basr_plan::warnings::{HotSpot, Note, Owner, Untilted};

/// What compile records of the film: the summary's figures and the notes
/// for the bounds it misses.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmCheck {
    pub summary: FilmSummary,
    pub notes: Vec<Note>,
    /// The items (letters, symbols, shapes) whose own film misses a bound
    /// of the preview's, by name (`layout.glyphs[].char`): each item's
    /// figures against the same bounds as the whole job's. compile takes
    /// a plan other than its first (another tip, the gentle tilt, the
    /// trapezoid method, ends held in) only where none is: a choice judged
    /// on the whole job's film alone let a message of letters that each
    /// fail alone paint (B C G J S at 6 ft, each over a bound alone, as a
    /// whole within them).
    pub items_over: Vec<String>,
}

/// The film stage of compile: `job`'s film as `basr preview JOB` measures
/// it; `owners[i]` names the job's `layout.glyphs[i]` in the notes.
pub fn check(job: &Job, owners: &[Owner]) -> Result<FilmCheck, CompileError> {
    let mut options = FilmOptions::preview_defaults();
    // The film of the tip the robot describes: `basr preview` takes the
    // job's profile too when no `--profile` is given.
    options.preview.profile = job_profile(job).map_err(|e| CompileError::Film(e.to_string()))?;
    let measured =
        film::film(job, &options, &|_, _| {}).map_err(|e| CompileError::Film(e.to_string()))?;
    let t = &options.thresholds;
    let items_over = measured
        .preview
        .metrics
        .glyphs
        .iter()
        .filter(|g| {
            !crate::paint::verdict::glyph_checks(g, t)
                .iter()
                .all(|c| c.pass)
        })
        .map(|g| g.char.clone())
        .collect();
    Ok(FilmCheck {
        summary: measured.summary(),
        notes: notes(&measured, job, owners),
        items_over,
    })
}

/// The flux profile of the tip the job's robot describes (`paint.profile`,
/// uniform when absent).
pub fn job_profile(job: &Job) -> Result<Profile, crate::paint::PaintError> {
    let text = job.robot.paint().profile_text();
    Profile::parse(text).map_err(|e| {
        crate::paint::PaintError::Job(format!("the robot's paint.profile {text:?}: {e}"))
    })
}

/// How the film notes name the tip: its name and profile when the robot
/// names a tip or a profile other than the seed's uniform one.
fn tip_words(job: &Job) -> Option<String> {
    let p = job.robot.paint();
    let profile = p.profile_text();
    match (&p.mounted, profile) {
        (Some(name), _) => Some(format!("{name} ({profile} flux)")),
        (None, "uniform") => None,
        (None, _) => Some(format!("of the paint table ({profile} flux)")),
    }
}

/// One [`Note::Film`] per failed bound, naming the item it fails worst on
/// (for cv also its heaviest film, where and on which stroke).
fn notes(measured: &JobFilm, job: &Job, owners: &[Owner]) -> Vec<Note> {
    let glyphs = &measured.preview.metrics.glyphs;
    measured
        .verdict
        .checks
        .iter()
        .filter(|c| !c.pass)
        .map(|c| {
            let max = c.bound == "max";
            // The item's own figure of this metric; the worst is the
            // highest for an upper bound, the lowest for a lower one.
            let worst = glyphs
                .iter()
                .zip(owners)
                .enumerate()
                .filter_map(|(i, (g, o))| figure(g, c.metric).map(|v| (i, o, v)))
                .max_by(|a, b| {
                    let ord = a.2.total_cmp(&b.2);
                    if max {
                        ord
                    } else {
                        ord.reverse()
                    }
                });
            let hot = match (c.metric, worst) {
                ("cv", Some((i, _, _))) => hot_spot(measured, job, i),
                _ => None,
            };
            // An uneven film where the fan is painted untilted: the items
            // over the bound, and why the fan is not leaned.
            let untilted =
                (c.metric == "cv" && job.layout.tilt_method == "none").then(|| Untilted {
                    items: glyphs
                        .iter()
                        .zip(owners)
                        .filter_map(|(g, o)| g.cv.filter(|&v| v > c.limit).map(|v| (o.clone(), v)))
                        .collect(),
                    lacks: job
                        .robot
                        .tilt_limit()
                        .is_none()
                        .then(|| job.robot.kind().name()),
                });
            Note::Film {
                failed: c.text(),
                metric: c.metric,
                factor: c.value.map(|v| v / c.limit),
                worst: worst.map(|(_, o, v)| (o.clone(), v)),
                hot,
                tip: tip_words(job),
                untilted: untilted.filter(|u| !u.items.is_empty()),
            }
        })
        .collect()
}

/// The heaviest film over item `item` (the fullest raster cell inside its
/// outline's box: the hot spots of joins and slowed places are what lift
/// a letter's cv) and the stroke whose painting setpoint lies nearest it.
fn hot_spot(measured: &JobFilm, job: &Job, item: usize) -> Option<HotSpot> {
    let peak = (*measured.preview.metrics.peaks.get(item)?)?;
    let (best, at_m) = (peak.film_m, peak.at_m);
    let s = &job.samples;
    let stroke = (0..s.len())
        .filter(|&k| s.paint[k] == 1 && s.stroke[k] >= 0)
        .min_by(|&a, &b| {
            let d = |k: usize| (s.x_m[k] - at_m[0]).hypot(s.y_m[k] - at_m[1]);
            d(a).total_cmp(&d(b))
        })
        .map(|k| s.stroke[k] as usize);
    Some(HotSpot {
        at_m,
        film_ratio: best / measured.preview.metrics.target_film_m,
        stroke,
    })
}

/// A letter's figure of `metric` (the preview's per-letter table).
fn figure(g: &GlyphMetrics, metric: &str) -> Option<f64> {
    match metric {
        "cv" => g.cv,
        "coverage" => g.coverage,
        "overspray" => g.overspray,
        _ => None,
    }
}
