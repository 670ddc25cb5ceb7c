//! Honest size advice for a NOT READY word marking, or one refused for its
//! size: compile searches the letter heights near the one asked for (or,
//! for a word too wide for the lane, the one it fits at) and names the
//! nearest each way that paints READY (or READY WITH NOTES), instead of
//! guessing which way a change helps (above 8 ft larger letters paint
//! worse, below it smaller ones do).

use basr::layout::{LayoutError, Marking};
use basr::pipeline::compile::{compile_job, CompileError, CompileRequest, Source};
use rayon::prelude::*;

/// Step between the heights tried (m): a quarter foot, the finest step a
/// stencil set or an agency's drawing gives letters in. source: MUTCD
/// word letters are specified in feet (§3B.20); 0.25 ft = 76.2 mm.
const STEP_M: f64 = 0.0762;

/// Heights tried each way: 8 steps, 2 ft, the span between MUTCD's
/// minimum (6 ft) and the seed's size (8 ft); upwards at least as far as
/// the default letter height (`DEFAULT_LETTER_HEIGHT_M`, 8 ft: the size
/// the arm's vertical stroke was chosen for), so that 4.5 ft letters
/// under 25 mph (`--low-speed`) are told of the nearest that paints.
const STEPS: usize = 8;

/// Steps to try upwards from grid position `at` (the asked height in
/// steps): [`STEPS`], or as many as reach the default letter height on the
/// grid (8 ft) from below it, the first at the step above `at`.
fn steps_up(at: f64) -> usize {
    let top = (basr::layout::DEFAULT_LETTER_HEIGHT_M / STEP_M).round();
    let to_default = top - (at + 1e-6).floor();
    if to_default.is_finite() && to_default > STEPS as f64 {
        // bounded: the range below it is at most 10 m / 76 mm
        (to_default as usize).min(200)
    } else {
        STEPS
    }
}

/// The nearest letter heights that paint READY, each way from the one
/// asked for, within what was searched.
#[derive(Clone, Debug, PartialEq)]
pub struct SizeAdvice {
    pub asked_m: f64,
    pub smaller_m: Option<f64>,
    pub larger_m: Option<f64>,
    /// The heights searched: from the smallest to the largest tried.
    pub searched_m: [f64; 2],
    /// Searched for a word compile refused (no notes to point to).
    pub refused: bool,
    /// Nothing was found, and the search ended where the arm could not
    /// follow the job at the nearest heights either (`NotFollowed`): not
    /// the size, the robot.
    pub unfollowed: bool,
}

impl SizeAdvice {
    /// One line for the compile summary; each height as `--letter-height`
    /// takes it (`7.5ft`) and in metres.
    pub fn line(&self) -> String {
        let h = |m: f64| {
            let ft = (m / 0.3048 * 100.0).round() / 100.0;
            format!("{ft}ft ({m:.2} m)")
        };
        let [lo, hi] = self.searched_m;
        let found: Vec<String> = [("smaller", self.smaller_m), ("larger", self.larger_m)]
            .iter()
            .filter_map(|(w, m)| m.map(|m| format!("{} {w}", h(m))))
            .collect();
        if found.is_empty() && self.unfollowed {
            format!(
                "  sizes: the arm cannot follow the job at {} to {}{} (too fast to follow at \
                 every height tried): not the letters' size but the robot description (its \
                 hydraulics, its control) is the likely cause",
                h(lo),
                h(hi),
                if self.refused { " either" } else { "" }
            )
        } else if found.is_empty() {
            format!(
                "  sizes: no letter height from {} to {} paints READY or READY WITH NOTES here \
                 (this robot, its spray tips and this road){}",
                h(lo),
                h(hi),
                if self.refused {
                    ""
                } else {
                    "; the notes above say what fails"
                }
            )
        } else {
            format!(
                "  sizes: the nearest letter heights that paint READY or READY WITH NOTES: {} \
                 (--letter-height; searched {} to {} in quarter feet)",
                found.join(", "),
                h(lo),
                h(hi)
            )
        }
    }
}

/// Whether size advice applies: a word marking (a message, or a marking
/// file of lines rather than a scene) at a letter height, planned with
/// compile's own settings ([`settings_changed`]).
pub fn applies(req: &CompileRequest) -> bool {
    is_word(req) && settings_changed(req).is_empty()
}

/// A word marking: a message, or a marking file of lines rather than a
/// scene.
fn is_word(req: &CompileRequest) -> bool {
    match &req.source {
        Source::Message(m) => !m.trim().is_empty(),
        Source::Marking { text, .. } => !basr::layout::is_scene(text),
        Source::Symbol(_) => false,
    }
}

/// The planning settings `req` changes from compile's defaults, as the
/// options that set them: a job planned so is not searched for sizes (the
/// sizes that paint are judged at the defaults, and a fine rung spacing
/// makes each height a compile of many seconds: `--rung-spacing-mm 1`
/// searched 5.5 minutes for a STOP the defaults paint).
pub fn settings_changed(req: &CompileRequest) -> Vec<&'static str> {
    let d = CompileRequest::message("");
    let mut out = vec![];
    if req.rung_spacing_m != d.rung_spacing_m {
        out.push("--rung-spacing-mm");
    }
    if req.period_s != d.period_s {
        out.push("--period-s");
    }
    if req.gun_lead_s != d.gun_lead_s || req.gun_lag_s != d.gun_lag_s {
        out.push("--gun-lead-s/--gun-lag-s");
    }
    if req.reach_margin_m != d.reach_margin_m {
        out.push("the reach margin");
    }
    if req.tilt != d.tilt {
        out.push("--tilt");
    }
    out
}

/// The line for a NOT READY word marking not searched for sizes because
/// its settings are not compile's ([`settings_changed`]).
pub fn not_searched_line(req: &CompileRequest) -> Option<String> {
    let changed = settings_changed(req);
    (is_word(req) && !changed.is_empty()).then(|| {
        format!(
            "  sizes: not searched: this job is planned with {} other than compile's default; \
             compile it at the default first (the sizes that paint are judged there)",
            changed.join(", ")
        )
    })
}

/// The letter height to search around for a word marking compile refused
/// for its size (`CompileError::about_size`), and whether larger heights
/// may paint: the height the word fits the lane at when it was too wide
/// (only smaller ones fit), else the one asked for; `None` for a refusal
/// no other size mends, a marking without letters, or a word that fits the
/// lane only below `floor_m` (MUTCD's smallest: its own message says how
/// small).
pub fn refused_at(req: &CompileRequest, e: &CompileError, floor_m: f64) -> Option<(f64, bool)> {
    if !applies(req) || !e.about_size() {
        return None;
    }
    if let CompileError::Layout(LayoutError::TooWide {
        fits_at_height_m, ..
    }) = e
    {
        return fits_at_height_m
            .filter(|&h| h >= floor_m * (1.0 - 1e-9))
            .map(|h| (h, false));
    }
    let o = &req.overrides;
    let marking = match &req.source {
        Source::Message(m) => Marking::from_message(m, o).ok()?,
        Source::Marking { text, origin } => Marking::from_toml(text, origin, o).ok()?,
        Source::Symbol(_) => return None,
    };
    Some((marking.letter_height_m, true))
}

/// [`nearest_ready`] behind a spinner on the terminal (when `show`) saying
/// why compile searches.
pub fn search(
    req: &CompileRequest,
    asked_m: f64,
    floor_m: f64,
    larger: bool,
    refused: bool,
    show: bool,
) -> SizeAdvice {
    let why = if refused { "refused" } else { "NOT READY" };
    let spin = super::spinner(
        show,
        &format!("{why}: searching the letter heights near it for ones that paint"),
    );
    let advice = nearest_ready(req, asked_m, floor_m, larger, refused);
    spin.finish_and_clear();
    advice
}

/// Search the heights around `asked_m` (not below `floor_m`, the smallest
/// the agency allows; above it only when `larger`) for the nearest each
/// way whose job is READY or READY WITH NOTES; the candidates are compiled
/// in parallel, nearest first, and the search each way stops at the first
/// that paints. `refused`: searched for a word compile refused.
fn nearest_ready(
    req: &CompileRequest,
    asked_m: f64,
    floor_m: f64,
    larger: bool,
    refused: bool,
) -> SizeAdvice {
    /// What a height did.
    #[derive(Clone, Copy, PartialEq)]
    enum Tried {
        Paints,
        Not,
        /// Refused: too fast to follow even at a tenth of its limits.
        Unfollowed,
    }
    let paints = |r: &CompileRequest| match compile_job(r) {
        Ok(job) if super::compile::verdict_of(&job) != "not ready" => Tried::Paints,
        Err(CompileError::NotFollowed { .. }) => Tried::Unfollowed,
        _ => Tried::Not,
    };
    // A height is first planned without the closed-loop verification: one
    // whose plan is already NOT READY (its film, its strokes against the
    // fan) is refused at a tenth of the cost, as every height is where the
    // road's surface or the tip decides (a crown through STOP: 53 s of
    // searching before, measured in release on 2 cores). Only a height that
    // plans evenly is verified, and it is advised only if it then holds
    // (verification is taken not to take a planned problem away: were it
    // ever to, a height would go unadvised, never one advised that fails).
    let ready = |h: f64| {
        let mut r = req.clone();
        r.overrides.letter_height_m = Some(h);
        let planned = CompileRequest {
            verify: false,
            ..r.clone()
        };
        match paints(&planned) {
            Tried::Paints if r.verify => paints(&r),
            t => t,
        }
    };
    // The quarter feet either side of the asked height (never the asked
    // one), nearest first: sizes a crew can type as they are printed.
    // The asked height on the grid when within a tenth of a step of it: the
    // default 2.44 m is 8 ft (2.4384 m) to 1.6 mm, and trying 8 ft beside it
    // spent a compile on the same letters and left 6 ft untried.
    let at = {
        let at = asked_m / STEP_M;
        if (at - at.round()).abs() < 0.1 {
            at.round()
        } else {
            at
        }
    };
    // (nearest that paints, the last height tried, whether the search
    // ended where the arm could not follow at any height of a pair: `None`
    // when no height was tried that way; the first height tried)
    let side = |sign: f64| -> (Option<f64>, f64, Option<bool>, Option<f64>) {
        let first = if sign > 0.0 {
            (at + 1e-6).floor() + 1.0
        } else {
            (at - 1e-6).ceil() - 1.0
        };
        let steps = if sign > 0.0 { steps_up(at) } else { STEPS };
        let heights: Vec<f64> = (0..steps)
            .map(|k| (first + sign * k as f64) * STEP_M)
            .filter(|&h| h >= floor_m * (1.0 - 1e-9))
            .collect();
        // Two at a time (the machine's cores), nearest first; the second
        // height tried (m) is where the search that way ended. A pair the
        // arm cannot follow at all ends it: each such height is a verified
        // compile slowed to a tenth of the limits (a robot file with a far
        // too low supply pressure searched 6.7 s for nothing), and the
        // sizes beyond do not mend the robot.
        // every height tried so far too fast to follow
        let mut unfollowed = true;
        for pair in heights.chunks(2) {
            let tried: Vec<Tried> = pair.par_iter().map(|&h| ready(h)).collect();
            let last = pair[pair.len() - 1];
            let first = heights.first().copied();
            if let Some(i) = tried.iter().position(|&t| t == Tried::Paints) {
                return (Some(pair[i]), last, Some(false), first);
            }
            let all = tried.iter().all(|&t| t == Tried::Unfollowed);
            if all {
                return (None, last, Some(unfollowed), first);
            }
            unfollowed = false;
        }
        match heights.last() {
            Some(&h) => (None, h, Some(false), heights.first().copied()),
            None => (None, asked_m, None, None),
        }
    };
    let (smaller_m, lo, below, _) = side(-1.0);
    let (larger_m, hi, above, first_up) = if larger {
        side(1.0)
    } else {
        (None, asked_m, None, None)
    };
    // An asked height under the floor was compiled, but the heights
    // between it and the floor were not: the search begins at the floor.
    let lo = match first_up {
        Some(up) if asked_m < floor_m * (1.0 - 1e-9) => up,
        _ => lo.min(asked_m),
    };
    SizeAdvice {
        asked_m,
        smaller_m,
        larger_m,
        searched_m: [lo, hi.max(asked_m)],
        refused,
        // every way searched ended at heights the arm could not follow
        unfollowed: (below.is_some() || above.is_some())
            && below.unwrap_or(true)
            && above.unwrap_or(true),
    }
}
