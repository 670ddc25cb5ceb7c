//! The film check of a compiled job: the sealed job's film measured by the
//! preview's own stage (`paint::film`, at `basr preview`'s defaults) and
//! every bound it misses made a [`Note::Film`], so compile's verdict knows
//! what the preview will say (docs/planner.md "Film").

use crate::job::{FilmSummary, Job};
use crate::paint::film::{self, FilmOptions, JobFilm};
use crate::paint::metrics::GlyphMetrics;

use super::error::CompileError;
use super::warnings::{Note, Owner};

/// What compile records of the film: the summary's figures and the notes
/// for the bounds it misses.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmCheck {
    pub summary: FilmSummary,
    pub notes: Vec<Note>,
}

/// The film stage of compile: `job`'s film as `basr preview JOB` measures
/// it; `owners[i]` names the job's `layout.glyphs[i]` in the notes.
pub fn check(job: &Job, owners: &[Owner]) -> Result<FilmCheck, CompileError> {
    let measured = film::film(job, &FilmOptions::preview_defaults(), &|_, _| {})
        .map_err(|e| CompileError::Film(e.to_string()))?;
    Ok(FilmCheck {
        summary: measured.summary(),
        notes: notes(&measured, owners),
    })
}

/// One [`Note::Film`] per failed bound, naming the item it fails worst on.
fn notes(measured: &JobFilm, owners: &[Owner]) -> Vec<Note> {
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
                .filter_map(|(g, o)| figure(g, c.metric).map(|v| (o, v)))
                .max_by(|a, b| {
                    let ord = a.1.total_cmp(&b.1);
                    if max {
                        ord
                    } else {
                        ord.reverse()
                    }
                })
                .map(|(o, v)| (o.clone(), v));
            Note::Film {
                failed: c.text(),
                metric: c.metric,
                factor: c.value.map(|v| v / c.limit),
                worst,
            }
        })
        .collect()
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
