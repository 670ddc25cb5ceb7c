//! The film stage: a job's film laid on the raster, measured against the
//! letters' outlines and judged against the bounds. One function serves
//! `basr preview` (which draws it) and `basr compile` (which records it in
//! the job's summary and grades a failed bound), so the two cannot
//! disagree: same model, same raster, same thresholds.

use super::preview::{self, Options, Preview};
use super::raster::{Progress, FIT_CELLS};
use super::verdict::{self, Thresholds, Verdict};
use super::PaintError;
use basr_job::{FilmSummary, FilmVerdict, Job};

/// How to measure the film: the preview's options and the verdict's bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmOptions {
    pub preview: Options,
    pub thresholds: Thresholds,
}

impl FilmOptions {
    /// What `basr preview JOB` uses when given no option: the default
    /// 5 mm cell (coarsened only where the raster held at once would not
    /// fit, `raster::FIT_CELLS`),
    /// the uniform fan, the default sheet depth and the default bounds.
    /// Compile measures with these, so its figures are preview's.
    pub fn preview_defaults() -> FilmOptions {
        FilmOptions {
            preview: Options {
                fit_cells: Some(FIT_CELLS),
                ..Options::default()
            },
            thresholds: Thresholds::default(),
        }
    }
}

/// A job's film: the preview (raster and metrics) and its verdict.
#[derive(Clone, Debug)]
pub struct JobFilm {
    pub preview: Preview,
    pub verdict: Verdict,
}

impl JobFilm {
    /// The figures the job's `summary.film` records.
    pub fn summary(&self) -> FilmSummary {
        let m = &self.preview.metrics;
        FilmSummary {
            cv: m.cv,
            coverage: m.coverage,
            overspray: m.overspray,
            mean_film_m: m.mean_film_m,
            target_film_m: m.target_film_m,
            resolution_m: m.resolution_m,
            verdict: if self.verdict.pass() {
                FilmVerdict::Pass
            } else {
                FilmVerdict::Fail
            },
            failed: self
                .verdict
                .checks
                .iter()
                .filter(|c| !c.pass)
                .map(verdict::Check::text)
                .collect(),
        }
    }
}

/// The film stage: lay `job`'s film, measure it and judge it.
pub fn film(job: &Job, how: &FilmOptions, progress: Progress) -> Result<JobFilm, PaintError> {
    let preview = preview::preview_job_with_progress(job, &how.preview, progress)?;
    Ok(judged(preview, &how.thresholds))
}

/// A film already laid (the simulated arm's, `preview --from-sim`), judged.
pub fn judged(preview: Preview, thresholds: &Thresholds) -> JobFilm {
    let verdict = verdict::judge(&preview.metrics, thresholds);
    JobFilm { preview, verdict }
}
