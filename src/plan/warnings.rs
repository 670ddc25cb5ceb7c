//! What the planner tells a person: one variant per kind of note, with its
//! data, a severity, and the one function that renders it to the job's text.
//!
//! Stages return `Note`s; only [`Note::render`] turns them into the job's
//! `summary.warnings` entries (kind, stroke, time, factor, sentence), so the
//! wording lives here and nowhere else.

use crate::job::{self, Warning};

/// How much a note matters to the crew (issue 15 sorts and colours by it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// For the record: the job paints as planned.
    Info,
    /// Worth a look before painting: the job paints, but not as asked.
    Notice,
    /// The paint will be off target somewhere.
    Problem,
}

impl Severity {
    pub fn name(self) -> &'static str {
        match self {
            Severity::Info => "info",
            Severity::Notice => "notice",
            Severity::Problem => "problem",
        }
    }
}

/// Which painted item a stroke belongs to, for messages: a letter's
/// character (or a symbol's name) and its line.
#[derive(Clone, Debug, PartialEq)]
pub struct Owner {
    /// What the item is, for a person: `"letter"`, `"symbol"`, `"shape"`.
    pub kind: &'static str,
    /// The character or name (`"S"`, `"arrow_left"`); `layout.glyphs[].char`.
    pub label: String,
    /// Line index (0 = nearest the approaching driver).
    pub line: usize,
}

impl std::fmt::Display for Owner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {} of line {}", self.kind, self.label, self.line + 1)
    }
}

/// Which limit slowed the nozzle below the painting speed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// A joint's speed limit (`Limits::NAMES` index).
    Speed { joint: usize },
    /// A joint's acceleration limit.
    Acceleration { joint: usize },
    /// The run-up from rest is too short to reach the speed.
    RunUp,
}

impl std::fmt::Display for Limit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = |j: usize| crate::robot::Limits::NAMES[j];
        match self {
            Limit::Speed { joint } => write!(f, "the {} speed limit", name(*joint)),
            Limit::Acceleration { joint } => write!(f, "the {} acceleration limit", name(*joint)),
            Limit::RunUp => write!(f, "the run-up from rest"),
        }
    }
}

/// One note of the planner.
#[derive(Clone, Debug, PartialEq)]
pub enum Note {
    /// A layout rule the marking bends (the layout's own sentence).
    Layout { text: String },
    /// A stroke wider than one pass paints, painted in parallel passes.
    Passes {
        stroke: usize,
        owner: Owner,
        passes: usize,
        max_width_m: f64,
    },
    /// Rungs narrower than the fan paints from the nozzle's lowest height.
    HeightClamped {
        stroke: usize,
        owner: Owner,
        clamped: usize,
        rungs: usize,
        min_height_m: f64,
        /// Largest fan width / rung width.
        worst_ratio: f64,
    },
    /// A limit holds the nozzle below the painting speed over paint.
    Slowed {
        stroke: usize,
        owner: Owner,
        limit: Limit,
        at_m: [f64; 2],
        t_s: f64,
        /// Film there / target film.
        film_ratio: f64,
    },
}

impl Note {
    pub fn severity(&self) -> Severity {
        match self {
            Note::Layout { .. } => Severity::Notice,
            Note::Passes { .. } | Note::HeightClamped { .. } => Severity::Info,
            Note::Slowed { .. } => Severity::Problem,
        }
    }

    /// The job's entry for this note: the one place a note becomes text.
    pub fn render(&self) -> Warning {
        match self {
            Note::Layout { text } => Warning {
                kind: "layout".into(),
                stroke: -1,
                t_s: None,
                factor: None,
                message: text.clone(),
            },
            Note::Passes {
                stroke,
                owner,
                passes,
                max_width_m,
            } => Warning {
                kind: "passes".into(),
                stroke: *stroke as i64,
                t_s: None,
                factor: Some(*passes as f64),
                message: format!(
                    "stroke {stroke} ({owner}) is wider than one pass can paint \
                     ({max_width_m:.3} m): painted in {passes} parallel passes"
                ),
            },
            Note::HeightClamped {
                stroke,
                owner,
                clamped,
                rungs,
                min_height_m,
                worst_ratio,
            } => Warning {
                kind: "height_clamped".into(),
                stroke: *stroke as i64,
                t_s: None,
                factor: Some(*worst_ratio),
                message: format!(
                    "stroke {stroke} ({owner}): {clamped} of {rungs} rungs are narrower than \
                     the fan paints from the nozzle's lowest height ({min_height_m:.3} m); the \
                     fan there paints up to {:.1} % wider than the stroke (the speed keeps the \
                     film)",
                    (worst_ratio - 1.0) * 100.0
                ),
            },
            Note::Slowed {
                stroke,
                owner,
                limit,
                at_m,
                t_s,
                film_ratio,
            } => Warning {
                kind: "slowed".into(),
                stroke: *stroke as i64,
                t_s: Some(job::round_ns(*t_s)),
                factor: Some(*film_ratio),
                message: format!(
                    "stroke {stroke} ({owner}): {limit} slows the nozzle below the painting \
                     speed near ({:.3}, {:.3}) m at t = {t_s:.2} s; the film there is up to \
                     {film_ratio:.2}× the target",
                    at_m[0], at_m[1]
                ),
            },
        }
    }
}

/// The job's `summary.warnings`, in the order the notes were made.
pub fn render_all(notes: &[Note]) -> Vec<Warning> {
    notes.iter().map(Note::render).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn owner() -> Owner {
        Owner {
            kind: "letter",
            label: "S".into(),
            line: 0,
        }
    }

    #[test]
    fn every_kind_renders_its_data_and_severity() {
        let slowed = Note::Slowed {
            stroke: 4,
            owner: owner(),
            limit: Limit::Acceleration { joint: 3 },
            at_m: [-1.0524, 0.6081],
            t_s: 19.3249999999,
            film_ratio: 1.05,
        };
        let w = slowed.render();
        assert_eq!(w.kind, "slowed");
        assert_eq!(w.stroke, 4);
        assert_eq!(w.factor, Some(1.05));
        assert!(
            w.message.starts_with(
                "stroke 4 (letter S of line 1): the ee_yaw_rad acceleration limit slows"
            ),
            "{}",
            w.message
        );
        assert!(w.message.contains("(-1.052, 0.608) m at t = 19.32 s"));
        assert_eq!(slowed.severity(), Severity::Problem);
        let layout = Note::Layout { text: "gap".into() };
        assert_eq!(layout.render().stroke, -1);
        assert_eq!(layout.severity(), Severity::Notice);
        let passes = Note::Passes {
            stroke: 2,
            owner: owner(),
            passes: 3,
            max_width_m: 0.2,
        };
        assert_eq!(passes.render().factor, Some(3.0));
        assert_eq!(passes.severity().name(), "info");
    }
}
