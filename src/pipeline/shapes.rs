//! Shapes in the pipeline: the fan's bands a decomposition plans for, a
//! `compile --shape` job through the placed-strokes seam, and the importer
//! a scene's `shape =` items are laid out with (SPEC §5).
//!
//! `compile --shape FILE`: the shape's font is laid out like a one-letter
//! message (centred in the lane, its near edge at the anchor) so that
//! `compile --shape FILE` and `compile S --font IMPORTED.toml
//! --letter-height H` place the same strokes; the strokes are then
//! labelled as the shape they are, and the job's message names the file.

use std::path::{Path, PathBuf};

use crate::job::{Job, OwnerKind, Severity, Warning, WarningKind};
use crate::layout::{ShapeItemError, ShapeSize, ShapeStrokes};
use crate::paint::preview::{preview_job, Options};
use crate::pipeline::compile::{compile_strokes, CompileError, CompileRequest, Source};
use crate::pipeline::placed::lay_out;
use crate::robot::{AnyRobot, RobotError};
pub use crate::shape::label_of;
use crate::shape::{self, report_lines, Bands, Imported, Method, Prediction, ShapeError, Size};
use basr_plan::warnings::{Note, Owner};
use basr_plan::{inputs, request};

/// Film targets a candidate decomposition must meet to be kept on its cv
/// alone: issue 14's acceptance (coverage ≥ 0.97, overspray ≤ 0.04).
const MIN_COVERAGE: f64 = 0.97;
/// See [`MIN_COVERAGE`].
const MAX_OVERSPRAY: f64 = 0.04;
/// Candidates whose cv differ by less than this are equally even; the
/// shorter paint time decides. assumed: half a percent of cv.
const CV_TIE: f64 = 0.005;
/// A measured cv this low (within the coverage and overspray bounds) ends
/// the search for a better candidate. assumed: two thirds of issue 14's
/// acceptance cv (0.06), so the kept film meets it with margin.
const GOOD_CV: f64 = 0.04;
/// A decomposition note that starts with this is a problem of the job
/// (`compile_shape`): no candidate paints the shape within its targets.
pub const UNEVEN: &str = "uneven: ";
/// Issue 14's acceptance cv: a kept film within it and without problems
/// (a READY job) beats a more even one with a problem. assumed: the issue's
/// figure.
const ACCEPT_CV: f64 = 0.06;
/// Largest raster the candidates' film is measured on (cells). assumed:
/// 2 M cells is a 5 mm raster over 7 × 7 m and takes a fraction of a second.
const MEASURE_CELLS: usize = 2_000_000;

/// The bands the robot's nozzle paints ([`Bands::of`]).
pub fn bands(robot: &AnyRobot) -> Bands {
    Bands::of(robot)
}

/// The job's message for a shape: its file's stem in brackets, as a
/// scene's shape items are written (`layout::Scene::message`).
pub fn message_of(label: &str) -> String {
    format!("[{label}]")
}

/// Compile `imported` (its height is the letter height) with the rest of
/// `req`; `label` names the shape in the job (`layout.glyphs[].char` and
/// the message).
pub fn compile_shape(
    req: &CompileRequest,
    imported: &Imported,
    bands: &Bands,
    label: &str,
) -> Result<Job, CompileError> {
    let mut req = req.clone();
    req.overrides.letter_height_m = Some(imported.height_m);
    req.font = None;
    // The candidates and the job kept are timed alike: verified on the
    // spread set, its figures recorded, not re-timed for it.
    req.retime_on_spread = false;
    request::check_settings(&req)?;
    let inputs = inputs::read(&req)?;
    let font = imported
        .font(label)
        .map_err(|e| CompileError::Font(e.to_string()))?;
    let (mut marking, mut strokes) = lay_out(&req, &font)?;
    marking.lines = vec![message_of(label)];
    for it in &mut strokes.items {
        it.owner = Owner {
            kind: OwnerKind::Shape,
            label: label.to_string(),
            line: 0,
        };
    }
    let mut job = compile_strokes(&req, &marking, &font, inputs.robot, &strokes)?;
    // The job says how the shape was decomposed: per region the method kept
    // and the ones it beat, and the places narrower than the fan paints.
    let lines = report_lines(&imported.decomposition, bands);
    for l in lines.iter().chain(&imported.notes) {
        let severity = if l.starts_with(UNEVEN) {
            Severity::Problem
        } else {
            Severity::Info
        };
        job.summary.warnings.push(Warning {
            kind: WarningKind::Shape,
            severity: Some(severity),
            stroke: None,
            owner: None,
            t_s: None,
            factor: None,
            message: format!("shape {l}"),
        });
    }
    job.seal();
    Ok(job)
}

/// A candidate's film, compiled with compile's defaults and previewed.
#[derive(Clone, Copy, Debug)]
struct Measured {
    cv: f64,
    coverage: f64,
    overspray: f64,
    paint_s: f64,
    /// The job's problems (film slowed where the verifying simulation found
    /// the arm behind, paint outside): a job with one is NOT READY.
    problems: usize,
}

impl Measured {
    fn meets_bounds(&self) -> bool {
        self.coverage >= MIN_COVERAGE && self.overspray <= MAX_OVERSPRAY
    }
    /// Meets issue 14's film targets and has no problem: a READY job.
    fn ready(&self) -> bool {
        self.meets_bounds() && self.cv <= ACCEPT_CV && self.problems == 0
    }
    /// How far the film misses its targets: the largest of cv, bare area
    /// and overspray over their bounds (1 = on a bound), plus a tenth per
    /// problem. assumed: the bounds weigh alike (a star 0.8 m tall: convex
    /// pieces at cv 0.047 with overspray 0.044 beat a sweep at cv 0.75).
    fn shortfall(&self) -> f64 {
        let over = (self.cv / ACCEPT_CV)
            .max((1.0 - self.coverage) / (1.0 - MIN_COVERAGE))
            .max(self.overspray / MAX_OVERSPRAY);
        over + 0.1 * self.problems as f64
    }
    /// Even enough that no further candidate needs measuring.
    fn good(&self) -> bool {
        self.meets_bounds() && self.cv <= GOOD_CV && self.problems == 0
    }
}

/// Compile a candidate with compile's defaults (with the verifying
/// simulation: it slows the time law where the arm falls behind, and those
/// slow spots are the job's problems), and preview it.
fn measure(imported: &Imported, robot: &AnyRobot, b: &Bands, label: &str) -> Option<Measured> {
    let mut req = CompileRequest::message(shape::GLYPH.encode_utf8(&mut [0; 4]));
    req.source = Source::Message(shape::GLYPH.to_string());
    // Candidates are compared with the robot's first tip alone: compile's
    // change of tip for a candidate with problems would compare one
    // decomposition's film under one tip with another's under another.
    let first = robot.paint().tips.first().map(|t| t.name.clone());
    let mut one_tip = robot.clone().with_mounted(first.as_deref());
    one_tip.paint_mut().tips.clear();
    one_tip.paint_mut().mounted = None;
    req.robot_description = Some(one_tip);
    // Measured below on a raster of its own; its film bounds are counted
    // by `shortfall`, not as problems.
    req.film = false;
    let job = compile_shape(&req, imported, b, label).ok()?;
    let opts = Options {
        fit_cells: Some(MEASURE_CELLS),
        ..Options::default()
    };
    let m = preview_job(&job, &opts).ok()?.metrics;
    Some(Measured {
        cv: m.cv?,
        coverage: m.coverage?,
        overspray: m.overspray?,
        paint_s: job.summary.paint_time_s,
        problems: job
            .summary
            .warnings
            .iter()
            .filter(|w| w.severity == Some(Severity::Problem))
            .count(),
    })
}

/// What became of one candidate decomposition.
#[derive(Clone, Copy, Debug)]
enum Outcome {
    /// Compiled and previewed (`None`: it does not compile for the robot).
    Measured(Option<Measured>),
    /// Predicted the same as candidate `.0`, measured in its stead.
    CopyOf(usize),
    /// Not measured: an earlier candidate was good and none tied with it.
    Skipped,
}

/// Measure candidates (ranked by the predictor, best first) until one is
/// [`Measured::good`]: each round takes the next candidate with every
/// later one the predictor ties with it (`Prediction::film_tied`) up to a
/// fallback (a ring in concentric passes),
/// measures them in parallel, and stands in for copies
/// (`Prediction::same`) by the first of them.
/// `progress(done, total)` hears of each candidate measured (`total` the
/// number of candidates: the search usually stops before the last).
fn measure_ranked(
    all: &[Imported],
    robot: &AnyRobot,
    b: &Bands,
    label: &str,
    progress: &Progress<'_>,
) -> Vec<Outcome> {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let done = AtomicUsize::new(0);
    let pred: Vec<Prediction> = all.iter().map(|c| c.decomposition.prediction()).collect();
    // A ring in concentric passes is the one-pass ring's fallback: it
    // starts a round of its own, so it is compiled only when nothing
    // before it paints well (the ring it refines usually ties with it).
    let fallback: Vec<bool> = all
        .iter()
        .map(|c| {
            c.decomposition
                .regions
                .iter()
                .any(|r| matches!(r.chosen.method, Method::Ring { concentric: true }))
        })
        .collect();
    let mut out = vec![Outcome::Skipped; all.len()];
    let mut i = 0;
    while i < all.len() {
        let end = (i..all.len())
            .take_while(|&j| j == i || (pred[j].film_tied(&pred[i]) && !fallback[j]))
            .last()
            .map_or(i + 1, |j| j + 1);
        let mut todo = vec![];
        for j in i..end {
            match (0..j).find(|&k| !matches!(out[k], Outcome::CopyOf(_)) && pred[k].same(&pred[j]))
            {
                Some(k) if k < i || todo.contains(&k) => out[j] = Outcome::CopyOf(k),
                _ => todo.push(j),
            }
        }
        let got: Vec<(usize, Option<Measured>)> = todo
            .par_iter()
            .map(|&j| {
                let m = measure(&all[j], robot, b, label);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, all.len());
                (j, m)
            })
            .collect();
        let good = got.iter().any(|(_, m)| m.is_some_and(|m| m.good()));
        for (j, m) in got {
            out[j] = Outcome::Measured(m);
        }
        i = end;
        if good {
            break;
        }
    }
    out
}

/// The kept candidate among the measured: of those [`Measured::ready`],
/// the most even film (within [`CV_TIE`]), then the shorter paint time;
/// when none is, the one nearest its targets ([`Measured::shortfall`]);
/// the first when none compiled.
fn pick(outcomes: &[Outcome]) -> usize {
    let key = |m: &Measured| {
        if m.ready() {
            (0, (m.cv / CV_TIE).floor() as i64)
        } else {
            (1, (m.shortfall() / CV_TIE).floor() as i64)
        }
    };
    outcomes
        .iter()
        .enumerate()
        .filter_map(|(i, o)| match o {
            Outcome::Measured(Some(m)) => Some((i, *m)),
            _ => None,
        })
        .min_by(|a, b| {
            key(&a.1)
                .cmp(&key(&b.1))
                .then(a.1.paint_s.total_cmp(&b.1.paint_s))
        })
        .map_or(0, |(i, _)| i)
}

/// Read, size and decompose a shape file for `robot`, keeping the
/// candidate decomposition ([`shape::candidates`]) whose film is the most
/// even when it is compiled (with compile's defaults) and previewed: the
/// film model itself decides. Candidates are measured in the predictor's
/// order until one is good and every tie of it is measured
/// ([`measure_ranked`]); the decomposition's notes list every candidate's
/// measured film or why it was not measured.
pub fn import_measured(path: &Path, size: Size, robot: &AnyRobot) -> Result<Imported, ShapeError> {
    import_measured_with_progress(path, size, robot, &|_, _| {})
}

/// How far a long search has got: `(done, total)`, from any thread.
pub type Progress<'a> = dyn Fn(usize, usize) + Sync + 'a;

/// [`import_measured`], telling `progress` of each candidate measured (a
/// shape's search compiles and previews several: 30–60 s).
pub fn import_measured_with_progress(
    path: &Path,
    size: Size,
    robot: &AnyRobot,
    progress: &Progress<'_>,
) -> Result<Imported, ShapeError> {
    let b = bands(robot);
    let mut all = shape::import_candidates(path, size, &b)?;
    let label = label_of(path);
    let outcomes = measure_ranked(&all, robot, &b, &label, progress);
    let pick = pick(&outcomes);
    let notes = measured_notes(&all, &outcomes, pick);
    let chosen = all.swap_remove(pick);
    Ok(chosen.with_notes(notes))
}

/// [`import_measured`], its font checked to load back as `--font` reads
/// it and written to `output` (atomically): what `basr import` does.
pub fn import_to_file(
    path: &Path,
    size: Size,
    robot: &AnyRobot,
    output: &Path,
) -> anyhow::Result<Imported> {
    import_to_file_with_progress(path, size, robot, output, &|_, _| {})
}

/// [`import_to_file`], telling `progress` of each candidate measured.
pub fn import_to_file_with_progress(
    path: &Path,
    size: Size,
    robot: &AnyRobot,
    output: &Path,
    progress: &Progress<'_>,
) -> anyhow::Result<Imported> {
    let imported = import_measured_with_progress(path, size, robot, progress)?;
    imported.font(&output.display().to_string())?;
    crate::io::write_atomic(output, imported.toml.as_bytes())?;
    Ok(imported)
}

/// The candidates' lines for a person: how each was measured and which
/// was kept.
fn measured_notes(all: &[Imported], outcomes: &[Outcome], pick: usize) -> Vec<String> {
    let name = |c: &Imported| {
        c.decomposition
            .regions
            .iter()
            .map(|r| r.chosen.method.to_string())
            .collect::<Vec<_>>()
            .join(" + ")
    };
    let mut notes = vec![format!(
        "film of the candidate decompositions, compiled with compile's defaults and previewed \
         in the predictor's order until one has cv ≤ {GOOD_CV} and no problem, and every \
         candidate predicted as good as it is measured (kept: of those with cv ≤ {ACCEPT_CV}, \
         coverage ≥ {MIN_COVERAGE}, overspray ≤ {MAX_OVERSPRAY} and no problem, the most even \
         film, then the shorter paint time; when none, the nearest those targets):"
    )];
    for (i, (c, o)) in all.iter().zip(outcomes).enumerate() {
        let kept = if i == pick { "kept" } else { "not kept" };
        let p = c.decomposition.prediction();
        notes.push(match o {
            Outcome::Measured(Some(m)) => format!(
                "  {kept}: {}: cv {:.3}, coverage {:.3}, overspray {:.3}, paint {:.0} s, {} problems",
                name(c),
                m.cv,
                m.coverage,
                m.overspray,
                m.paint_s,
                m.problems
            ),
            Outcome::Measured(None) => {
                format!("  {kept}: {}: does not compile for this robot", name(c))
            }
            Outcome::CopyOf(k) => format!(
                "  not measured: {}: predicted the same as {}, turned by the shape's symmetry",
                name(c),
                name(&all[*k])
            ),
            Outcome::Skipped => format!(
                "  not measured: {}: predicted film error {:.1} % ({:.0} s), worse than a candidate measured good",
                name(c),
                100.0 * p.film_error,
                p.time_s
            ),
        });
    }
    if let Some(Outcome::Measured(Some(m))) = outcomes.get(pick) {
        if !m.ready() {
            notes.push(uneven_note(m, &all[pick].decomposition));
        }
    }
    notes
}

/// The job's problem when no candidate is READY: which targets the kept
/// film misses, and where the shape is narrower than the fan paints (the
/// physical limit: a tip narrower than the fan's narrowest band is sprayed
/// wider than itself or left bare).
fn uneven_note(m: &Measured, d: &shape::Decomposition) -> String {
    let mut missed = vec![];
    if m.cv > ACCEPT_CV {
        missed.push(format!("cv {:.3} (target ≤ {ACCEPT_CV})", m.cv));
    }
    if m.coverage < MIN_COVERAGE {
        missed.push(format!("coverage {:.3} (≥ {MIN_COVERAGE})", m.coverage));
    }
    if m.overspray > MAX_OVERSPRAY {
        missed.push(format!("overspray {:.3} (≤ {MAX_OVERSPRAY})", m.overspray));
    }
    if m.problems > 0 {
        missed.push(format!(
            "{} places where the arm cannot keep the painting speed (listed in the job)",
            m.problems
        ));
    }
    let narrow = match d
        .narrow
        .iter()
        .max_by(|a, b| a.length_m.total_cmp(&b.length_m))
    {
        Some(w) => format!(
            "; {} places are narrower than the fan's narrowest band ({:.3} m), the longest \
             near ({:.3}, {:.3}) m from the shape's lower-left corner, {:.3} m narrower over \
             {:.3} m; in all they leave {:.4} m² bare and spray {:.4} m² outside",
            d.narrow.len(),
            w.width_m + w.shortfall_m,
            w.at.x,
            w.at.y,
            w.shortfall_m,
            w.length_m,
            d.narrow.iter().map(|n| n.unpainted_m2).sum::<f64>(),
            d.narrow.iter().map(|n| n.overspray_m2).sum::<f64>(),
        ),
        None => String::new(),
    };
    format!(
        "{UNEVEN}no decomposition of the shape paints it evenly at this size: the best measured \
         misses {} (cv {:.3}, coverage {:.3}, overspray {:.3}){narrow}; parts narrower than the \
         fan paints or too short for the run-up are the usual cause: give a larger \
         --shape-height-m",
        missed.join(", "),
        m.cv,
        m.coverage,
        m.overspray,
    )
}

/// The robot a request paints with (as `inputs::read` finds it).
fn robot_of(req: &CompileRequest) -> Result<AnyRobot, RobotError> {
    match &req.robot_description {
        Some(r) => Ok(r.clone()),
        None => AnyRobot::load_or_default(req.robot.as_deref()),
    }
}

/// A scene item's shape file: relative paths are relative to the marking
/// file's folder (SPEC §5).
pub fn resolve(path: &Path, marking_file: &str) -> PathBuf {
    if path.is_absolute() {
        return path.to_path_buf();
    }
    Path::new(marking_file)
        .parent()
        .unwrap_or(Path::new(""))
        .join(path)
}

/// Import one scene shape for the robot: its strokes in the shape's frame
/// (lower-left corner at the origin, metres) and its size, and what the
/// job says of its decomposition (as `compile --shape` does).
pub fn import_item(
    robot: &AnyRobot,
    marking_file: &str,
    path: &Path,
    size: ShapeSize,
) -> Result<(ShapeStrokes, Vec<Note>), ShapeItemError> {
    let file = resolve(path, marking_file);
    let size = match size {
        ShapeSize::HeightM(h) => Size::HeightM(h),
        ShapeSize::WidthM(w) => Size::WidthM(w),
    };
    let imported = import_measured(&file, size, robot)?;
    let label = label_of(path);
    let notes = report_lines(&imported.decomposition, &bands(robot))
        .into_iter()
        .chain(imported.notes.iter().cloned())
        .map(|text| Note::Shape {
            label: label.clone(),
            text,
        })
        .collect();
    Ok((
        ShapeStrokes {
            strokes: imported.decomposition.strokes,
            width_m: imported.width_m,
            height_m: imported.height_m,
        },
        notes,
    ))
}

/// The importer `layout::lay_scene_with` takes, for a scene read from
/// `marking_file` and compiled with `req`'s robot; each shape's notes are
/// added to `notes`.
pub fn importer<'a>(
    req: &'a CompileRequest,
    marking_file: &'a str,
    notes: &'a std::cell::RefCell<Vec<Note>>,
) -> impl Fn(&Path, ShapeSize) -> Result<ShapeStrokes, ShapeItemError> + 'a {
    move |path, size| {
        let (strokes, n) = import_item(&robot_of(req)?, marking_file, path, size)?;
        notes.borrow_mut().extend(n);
        Ok(strokes)
    }
}
