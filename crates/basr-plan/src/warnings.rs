//! What the planner tells a person: one variant per kind of note, with its
//! data, a severity, and the one function that renders it to the job's text.
//!
//! Stages return `Note`s; only [`Note::render`] turns them into the job's
//! `summary.warnings` entries (kind, stroke, time, factor, sentence), so the
//! wording lives here and nowhere else.

use basr_job::{self as job, Warning, WarningKind};
use std::borrow::Cow;

pub use basr_job::{Owner, OwnerKind, Severity};

/// Which limit slowed the nozzle below the painting speed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// A joint's speed limit (the joint's setpoint name, of the robot's kind).
    Speed { joint: &'static str },
    /// A joint's acceleration limit.
    Acceleration { joint: &'static str },
    /// The run-up from rest is too short to reach the speed.
    RunUp,
}

impl std::fmt::Display for Limit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Limit::Speed { joint } => write!(f, "the {joint} speed limit"),
            Limit::Acceleration { joint } => write!(f, "the {joint} acceleration limit"),
            Limit::RunUp => write!(f, "the run-up from rest"),
        }
    }
}

/// Why the arm comes to rest inside a station.
#[derive(Clone, Debug, PartialEq)]
pub enum StopWhy {
    /// The station starts at rest in the stow pose (the truck has stopped).
    LeaveStow,
    /// The station ends at rest in the stow pose (the truck may move).
    BackToStow,
    /// Flying into this stroke would carry every moving joint past its range.
    JointRange {
        stroke: usize,
        owner: Owner,
        joint: &'static str,
    },
}

/// The heaviest film on an item: where, how heavy, and the stroke painted
/// nearest it.
#[derive(Clone, Debug, PartialEq)]
pub struct HotSpot {
    pub at_m: [f64; 2],
    /// Film there / target film.
    pub film_ratio: f64,
    pub stroke: Option<usize>,
}

/// The items whose own film fails the cv bound where the fan is painted
/// untilted, and why it is: without the lean the quadrilateral tilt gives
/// a fan on a curve (001 §2.5), the inside of the curve gets more paint
/// than the outside (BASR with `--tilt none` paints O, B and S with the
/// cv the articulated arm does: 0.136, 0.130, 0.145).
#[derive(Clone, Debug, PartialEq)]
pub struct Untilted {
    /// Each item over the bound, with its own cv.
    pub items: Vec<(Owner, f64)>,
    /// The robot kind that has no tilt along its fan; `None` where the
    /// request asked for `--tilt none`.
    pub lacks: Option<&'static str>,
}

/// What a cv failure on an untilted fan says: which items, and the degree
/// of freedom that would even them.
fn untilted_words(u: &Untilted) -> String {
    let items: Vec<String> = u
        .items
        .iter()
        .map(|(o, cv)| format!("{o} (cv {cv:.3})"))
        .collect();
    let why = match u.lacks {
        Some(kind) => format!(
            "the {kind} arm has no tilt along its fan, the degree of freedom that leans the \
             fan on a curve (001 §2.5) and evens the film across it"
        ),
        None => "--tilt none was asked; the quadrilateral tilt leans the fan on a curve \
                 (001 §2.5) and evens the film across it"
            .to_string(),
    };
    format!(
        "; uneven across the curves of {}, painted with the fan untilted: {why}",
        items.join(", ")
    )
}

/// The size at which a stroke painted in side-by-side sweeps fits one
/// sweep of the fan ([`Note::HeightClamped`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OneSweep {
    /// Widest fan / widest rung: that size as a share of this one.
    pub scale: f64,
    /// The letter's height (m); `None` for a symbol or a shape.
    pub letter_height_m: Option<f64>,
}

impl OneSweep {
    /// What the crew can do: smaller letters, by how much, and never
    /// larger ones; a letter size under MUTCD's minimum for word letters
    /// is said to be so, as the layout says it (6 ft, 4.5 ft under 25 mph
    /// with `--low-speed`, `basr_shape::layout::rules`).
    pub fn advice(&self) -> String {
        use basr_shape::layout::rules::{LOW_SPEED_FACTOR, MIN_LETTER_HEIGHT_M};
        let pct = (self.scale * 100.0).floor();
        let at = self.letter_height_m.map(|h| h * pct / 100.0);
        let low = MIN_LETTER_HEIGHT_M * LOW_SPEED_FACTOR;
        let size = |why: &str| {
            at.map_or(String::new(), |m| {
                format!(" ({m:.2} m, {:.1} ft{why})", m / basr_geom::units::M_PER_FT)
            })
        };
        match at {
            Some(m) if m < low * (1.0 - 1e-9) => format!(
                "Only letters at most {pct:.0} % of this size{} paint this stroke in one \
                 sweep; at every size MUTCD allows the seams stay, and larger letters do not \
                 help.",
                size(": smaller than MUTCD allows for word letters, 6 ft, 4.5 ft under 25 mph")
            ),
            Some(m) if m < MIN_LETTER_HEIGHT_M * (1.0 - 1e-9) => format!(
                "Only letters at most {pct:.0} % of this size{} paint this stroke in one \
                 sweep, without the narrow seams; larger letters do not help.",
                size(": under MUTCD's 6 ft, allowed only under 25 mph with --low-speed")
            ),
            _ => format!(
                "Letters at most {pct:.0} % of this size{} paint this stroke in one sweep, \
                 without the narrow seams; larger letters do not help.",
                size("")
            ),
        }
    }
}

/// One note of the planner.
#[derive(Clone, Debug, PartialEq)]
pub enum Note {
    /// A layout rule the marking bends (the layout's own sentence).
    Layout { text: String },
    /// The road under the marking lies off the plane the truck stands on,
    /// and what that does to the painting heights (`pipeline::compile`).
    Surface { text: String },
    /// A plant of the verification set strays over the bound on a station
    /// compile kept as it was (only a slower path for the whole station
    /// would help): what, where and how far (`pipeline::compile`).
    Arm { text: String },
    /// How a scene's shape item was decomposed, and why (`plan::shapes`:
    /// the method kept per region, the candidates' measured film, the
    /// places narrower than the fan); `label` is the shape's file stem.
    Shape { label: String, text: String },
    /// A stroke wider than one pass paints, painted in parallel passes
    /// (`passes` side by side at most), cut across into `stretches` where
    /// its width changes (`passes::split_passes`).
    Passes {
        stroke: usize,
        owner: Owner,
        passes: usize,
        stretches: usize,
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
        /// Share of the job's paint this stroke's wider fan lays outside
        /// the stroke (`passes::outside_area`).
        outside_share: f64,
        /// The same summed over every stroke of the job.
        job_outside_share: f64,
        /// Where the stroke is wider than one sweep of the fan and painted
        /// in side-by-side sweeps (whose seams leave these narrow bands):
        /// the size at which the whole stroke fits one sweep. Larger
        /// letters only widen the bands' mismatch there, so the advice
        /// differs.
        one_sweep: Option<OneSweep>,
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

    /// The film the job lays misses one of the preview's bounds
    /// (`plan::film`, measured with `paint::film` at preview's defaults).
    Film {
        /// The bound as the preview words it (`cv 0.051 over the 0.050
        /// limit`, `paint::verdict::Check::text`).
        failed: String,
        /// The metric's name (`cv`, `coverage`, `overspray`).
        metric: &'static str,
        /// The job's figure over its limit (value / limit).
        factor: Option<f64>,
        /// The item the bound fails worst on, with its own figure.
        worst: Option<(Owner, f64)>,
        /// For cv: the heaviest film on that item.
        hot: Option<HotSpot>,
        /// The tip the film was planned and measured for (`511, uniform-angle
        /// flux`), when the robot names one or a profile other than uniform.
        tip: Option<String>,
        /// For cv on a fan painted untilted: the items it fails and why
        /// the fan is not leaned.
        untilted: Option<Untilted>,
    },

    /// The arm comes to rest.
    Stop {
        station: usize,
        t_s: f64,
        at_m: [f64; 2],
        why: StopWhy,
    },
}

/// How to make the item larger, by what it is: letters by their height, a
/// symbol by its item's scale, a shape by its size.
fn larger_avoids(owner: &Owner) -> &'static str {
    match owner.kind {
        OwnerKind::Letter => "Larger letters (--letter-height) avoid it.",
        OwnerKind::Symbol => "A larger symbol (its scale) avoids it.",
        OwnerKind::Shape => "A larger shape (its height or width) avoids it.",
    }
}

/// Film within this factor of the target is on target: the ±10 % band the
/// preview's colour scale draws. // assumed: a film 10 % heavy or light is
/// not visible on the road.
pub const FILM_BAND: f64 = 1.10;
/// Film from this factor of the target shows as a heavy line. // assumed:
/// 1.5×, the top of the preview's colour scale.
pub const FILM_HEAVY: f64 = 1.5;
/// A fan at most this much wider than the stroke is not worth saying.
/// // assumed: 5 %, about one 5 mm raster cell either side of a 0.1 m stroke.
pub const WIDER_SMALL: f64 = 1.05;
/// A fan more than this much wider than the stroke paints visibly outside
/// the letter. // assumed: 25 %, about 12 mm either side of a 0.1 m stroke.
pub const WIDER_LARGE: f64 = 1.25;

/// Most of the job's paint the wider fans may lay outside their strokes
/// before a clamp is a problem. assumed: the preview's overspray bound
/// (3 %) less the 1.9 % (median) the fan's soft edges lay outside every letter
/// (preview at defaults: I 2.1 %, T 1.9 %, L 1.8 %), so the job as a whole
/// still meets the bound; see docs/planner.md.
pub const OUTSIDE_BUDGET: f64 = 0.011;

/// The severity of a measured excess: on target, off, visibly off.
fn graded(ratio: f64, small: f64, large: f64) -> Severity {
    if ratio > large {
        Severity::Problem
    } else if ratio > small {
        Severity::Notice
    } else {
        Severity::Info
    }
}

impl Note {
    /// Graded by how far off the paint is, not by the kind alone: a film
    /// 1.03× the target is information, 1.7× a problem.
    pub fn severity(&self) -> Severity {
        match self {
            Note::Layout { .. } | Note::Arm { .. } => Severity::Notice,
            Note::Passes { .. } | Note::Stop { .. } | Note::Shape { .. } | Note::Surface { .. } => {
                Severity::Info
            }
            // A fan visibly wider than the stroke is a problem only if the
            // paint it lays outside, measured over the whole job, could
            // carry the job past the preview's overspray bound.
            Note::HeightClamped {
                worst_ratio,
                job_outside_share,
                ..
            } => match graded(*worst_ratio, WIDER_SMALL, WIDER_LARGE) {
                Severity::Problem if *job_outside_share <= OUTSIDE_BUDGET => Severity::Notice,
                s => s,
            },
            Note::Slowed { film_ratio, .. } => graded(*film_ratio, FILM_BAND, FILM_HEAVY),
            // The preview fails this job's film (exit 1): the crew's
            // verdict must not say READY (docs/planner.md "Film").
            Note::Film { .. } => Severity::Problem,
        }
    }

    /// What the crew should do about it, by severity.
    fn todo(&self) -> Cow<'static, str> {
        let fixed = match (self, self.severity()) {
            (_, Severity::Info) => "Nothing to do.",
            // Seams of side-by-side sweeps: smaller letters paint the
            // stroke in one sweep; larger ones would make it worse.
            (
                Note::HeightClamped {
                    one_sweep: Some(one),
                    ..
                },
                _,
            ) => return Cow::Owned(one.advice()),
            (Note::Layout { .. }, _) => "Check that this is what was asked for.",
            (Note::Arm { .. }, _) => {
                "The job passes on the robot as described; on an arm that differs from it \
                 the nozzle may stray there. Before painting, check it on the arm as it may \
                 be: `basr simulate JOB --plants 40` (docs/simulate.md)."
            }
            (Note::HeightClamped { worst_ratio, .. }, Severity::Notice)
                if *worst_ratio <= WIDER_LARGE =>
            {
                "The edge there is slightly soft; nothing to do unless the edges must be crisp."
            }
            (Note::HeightClamped { owner, .. }, Severity::Notice) => {
                return Cow::Owned(format!(
                    "Expect a soft, slightly wide edge there; the job as a whole stays within \
                     the preview's overspray bound. {}",
                    larger_avoids(owner)
                ))
            }
            (Note::HeightClamped { owner, .. }, _) => {
                return Cow::Owned(format!(
                    "Expect paint outside the {} there; {}",
                    owner.kind.name(),
                    larger_avoids(owner).to_lowercase()
                ))
            }
            (
                Note::Film {
                    untilted: Some(Untilted { lacks: Some(_), .. }),
                    ..
                },
                _,
            ) => {
                "Do not paint these letters with this robot: paint them with one that leans \
                 its fan (BASR or the telescopic arm), or leave them out of the job."
            }
            (
                Note::Film {
                    untilted: Some(Untilted { lacks: None, .. }),
                    ..
                },
                _,
            ) => "Compile it again with the default --tilt quadrilateral.",
            (Note::Film { .. }, _) => {
                "Do not paint it as it is: `basr preview` of the job shows where; tell the \
                 engineer who planned it (the job's other notes say which way a different \
                 size helps: strokes narrower than the fan want larger letters, strokes \
                 painted in side-by-side sweeps smaller ones)."
            }
            (Note::Slowed { .. }, Severity::Notice) => {
                "It dries a little slower there; check it before opening the lane."
            }
            _ => {
                "Expect a heavy, slow-drying line there: check it before opening the lane and \
                 tell the engineer who planned the job."
            }
        };
        Cow::Borrowed(fixed)
    }

    /// The job's entry for this note: the one place a note becomes text.
    pub fn render(&self) -> Warning {
        let severity = Some(self.severity());
        let todo = self.todo();
        // A note of the whole job: no item, stroke, time or factor.
        let whole = |kind, message| Warning {
            kind,
            owner: None,
            severity,
            stroke: None,
            t_s: None,
            factor: None,
            message,
        };
        match self {
            Note::Layout { text } => whole(WarningKind::Layout, format!("{text}. {todo}")),
            Note::Arm { text } => whole(WarningKind::Arm, format!("{text}. {todo}")),
            Note::Surface { text } => whole(WarningKind::Surface, format!("{text}.")),
            // As `plan::shapes::compile_shape` writes a `--shape` job's lines.
            Note::Shape { label, text } => {
                whole(WarningKind::Shape, format!("shape {label}: {text}"))
            }
            Note::Passes {
                stroke,
                owner,
                passes,
                stretches,
                max_width_m,
            } => Warning {
                kind: WarningKind::Passes,
                owner: Some(owner.clone()),
                severity,
                stroke: Some(*stroke),
                t_s: None,
                factor: Some(*passes as f64),
                message: if *stretches > 1 {
                    format!(
                        "{owner}, stroke {stroke}: wider than one sweep of the fan ({:.0} mm) \
                         where it is widest and under two of its narrowest where it narrows, so \
                         it is cut across into {stretches} stretches, painted in up to {passes} \
                         side-by-side sweeps; the stretches meet across the stroke in a thin \
                         seam. {todo}",
                        max_width_m * 1e3
                    )
                } else {
                    format!(
                        "{owner}, stroke {stroke}: wider than one sweep of the fan ({:.0} mm), so \
                         it is painted in {passes} side-by-side sweeps. {todo}",
                        max_width_m * 1e3
                    )
                },
            },
            Note::HeightClamped {
                stroke,
                owner,
                clamped,
                rungs,
                min_height_m,
                worst_ratio,
                outside_share,
                job_outside_share,
                ..
            } => Warning {
                kind: WarningKind::HeightClamped,
                owner: Some(owner.clone()),
                severity,
                stroke: Some(*stroke),
                t_s: None,
                factor: Some(*worst_ratio),
                message: format!(
                    "{owner}, stroke {stroke}: at {clamped} of {rungs} places the stroke is \
                     narrower than the fan paints even with the nozzle at its lowest \
                     ({:.0} mm over the road), so paint lands up to {:.1} % wider than the \
                     stroke there (the film stays on target): {:.2} % of the job's paint \
                     lands outside the stroke there, {:.2} % over the whole job (budget {:.1} %). \
                     {todo}",
                    min_height_m * 1e3,
                    (worst_ratio - 1.0) * 100.0,
                    outside_share * 100.0,
                    job_outside_share * 100.0,
                    OUTSIDE_BUDGET * 100.0
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
                kind: WarningKind::Slowed,
                owner: Some(owner.clone()),
                severity,
                stroke: Some(*stroke),
                t_s: Some(job::round_ns(*t_s)),
                factor: Some(*film_ratio),
                message: format!(
                    "{owner}, stroke {stroke}: near ({:.2}, {:.2}) m the arm cannot keep the \
                     painting speed ({limit} holds it back, {t_s:.1} s into the job), so the \
                     film there is up to {film_ratio:.2}× the target. {todo}",
                    at_m[0], at_m[1]
                ),
            },
            Note::Film {
                failed,
                metric,
                factor,
                worst,
                hot,
                tip,
                untilted,
            } => Warning {
                kind: WarningKind::Film,
                owner: None,
                severity,
                stroke: hot.as_ref().and_then(|h| h.stroke),
                t_s: None,
                factor: *factor,
                message: format!(
                    "the film fails the preview's check: {failed}{}{}{}{}. {todo}",
                    tip.as_ref()
                        .map_or(String::new(), |t| format!(" with tip {t}")),
                    worst.as_ref().map_or(String::new(), |(owner, v)| format!(
                        ", worst on {owner} ({metric} {v:.3})"
                    )),
                    hot.as_ref().map_or(String::new(), |h| format!(
                        "; its heaviest film is {:.2}× the target near ({:.2}, {:.2}) m{}",
                        h.film_ratio,
                        h.at_m[0],
                        h.at_m[1],
                        h.stroke.map_or(String::new(), |s| format!(", stroke {s}"))
                    )),
                    untilted.as_ref().map_or(String::new(), untilted_words)
                ),
            },
            Note::Stop {
                station,
                t_s,
                at_m,
                why,
            } => {
                let (stroke, reason) = match why {
                    StopWhy::LeaveStow => (None, "the station starts from the stow pose".to_string()),
                    StopWhy::BackToStow => (None, "the station ends in the stow pose".to_string()),
                    StopWhy::JointRange {
                        stroke,
                        owner,
                        joint,
                    } => (
                        Some(*stroke),
                        format!(
                            "flying into stroke {stroke} ({owner}) would carry {joint} past its range"
                        ),
                    ),
                };
                Warning {
                    kind: WarningKind::Stop,
                    owner: None,
                    severity,
                    stroke,
                    t_s: Some(job::round_ns(*t_s)),
                    factor: None,
                    message: format!(
                        "station {}: the arm stops at t = {t_s:.2} s near ({:.3}, {:.3}) m: \
                         {reason}. {todo}",
                        station + 1,
                        at_m[0],
                        at_m[1]
                    ),
                }
            }
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
            kind: OwnerKind::Letter,
            label: "S".into(),
            line: 0,
        }
    }

    #[test]
    fn every_kind_renders_its_data_and_severity() {
        let slowed = Note::Slowed {
            stroke: 4,
            owner: owner(),
            limit: Limit::Acceleration {
                joint: "ee_yaw_rad",
            },
            at_m: [-1.0524, 0.6081],
            t_s: 19.3249999999,
            film_ratio: 1.05,
        };
        let w = slowed.render();
        assert_eq!(w.kind, WarningKind::Slowed);
        assert_eq!(w.stroke, Some(4));
        assert_eq!(w.owner, Some(owner()));
        assert_eq!(w.factor, Some(1.05));
        assert!(
            w.message
                .starts_with("letter S of line 1, stroke 4: near (-1.05, 0.61) m"),
            "{}",
            w.message
        );
        assert!(w
            .message
            .contains("(the ee_yaw_rad acceleration limit holds it back, 19.3 s"));
        // 1.05× is inside the ±10 % band: information, nothing to do.
        assert_eq!(slowed.severity(), Severity::Info);
        assert_eq!(w.severity, Some(Severity::Info));
        assert!(w.message.ends_with("Nothing to do."), "{}", w.message);
        let layout = Note::Layout { text: "gap".into() };
        assert_eq!(layout.render().stroke, None);
        assert_eq!(layout.render().owner, None);
        assert_eq!(layout.severity(), Severity::Notice);
        let passes = Note::Passes {
            stroke: 2,
            owner: owner(),
            passes: 3,
            stretches: 1,
            max_width_m: 0.2,
        };
        assert_eq!(passes.render().factor, Some(3.0));
        assert_eq!(passes.severity().name(), "info");
        assert!(!passes.render().message.contains("stretches"));
        let cut = Note::Passes {
            stroke: 2,
            owner: owner(),
            passes: 3,
            stretches: 2,
            max_width_m: 0.2,
        };
        assert!(cut.render().message.contains("cut across into 2 stretches"));
        assert_eq!(cut.render().factor, Some(3.0));
    }

    #[test]
    fn a_failed_film_bound_is_a_problem_naming_bound_value_and_where() {
        let film = Note::Film {
            failed: "cv 0.051 over the 0.050 limit".into(),
            metric: "cv",
            factor: Some(1.02),
            worst: Some((owner(), 0.063)),
            hot: Some(HotSpot {
                at_m: [0.123, -1.5],
                film_ratio: 1.625,
                stroke: Some(7),
            }),
            tip: None,
            untilted: None,
        };
        assert_eq!(film.severity(), Severity::Problem);
        let w = film.render();
        assert_eq!(
            (w.kind, w.severity),
            (WarningKind::Film, Some(Severity::Problem))
        );
        assert_eq!(w.stroke, Some(7));
        assert!(
            w.message.starts_with(
                "the film fails the preview's check: cv 0.051 over the 0.050 limit, worst on \
                 letter S of line 1 (cv 0.063); its heaviest film is 1.62× the target near \
                 (0.12, -1.50) m, stroke 7. Do not paint it"
            ),
            "{}",
            w.message
        );
    }

    #[test]
    fn severity_grows_with_how_far_off_the_paint_is() {
        let slowed = |film_ratio| Note::Slowed {
            stroke: 1,
            owner: owner(),
            limit: Limit::RunUp,
            at_m: [0.0, 0.0],
            t_s: 1.0,
            film_ratio,
        };
        assert_eq!(slowed(1.03).severity(), Severity::Info);
        assert_eq!(slowed(1.10).severity(), Severity::Info);
        assert_eq!(slowed(1.2).severity(), Severity::Notice);
        assert_eq!(slowed(1.71).severity(), Severity::Problem);
        assert!(slowed(1.71)
            .render()
            .message
            .contains("heavy, slow-drying line"));
        let clamped = |worst_ratio, job_outside_share| Note::HeightClamped {
            stroke: 1,
            owner: owner(),
            clamped: 9,
            rungs: 65,
            min_height_m: 0.078,
            worst_ratio,
            outside_share: 0.004,
            job_outside_share,
            one_sweep: None,
        };
        assert_eq!(clamped(1.009, 0.02).severity(), Severity::Info);
        assert_eq!(clamped(1.1, 0.02).severity(), Severity::Notice);
        assert_eq!(clamped(1.297, 0.02).severity(), Severity::Problem);
        // Seams of side-by-side sweeps: the advice is smaller letters,
        // by how much, and never larger ones.
        let seams = |letter_height_m: Option<f64>| {
            let mut n = clamped(1.297, 0.02);
            if let Note::HeightClamped { one_sweep, .. } = &mut n {
                *one_sweep = Some(OneSweep {
                    scale: 0.893,
                    letter_height_m,
                });
            }
            n.render().message
        };
        // 89 % of 8 ft is 7.1 ft: a size MUTCD allows
        let m = seams(Some(8.0 * 0.3048));
        assert!(
            m.contains("Letters at most 89 % of this size (2.17 m, 7.1 ft) paint"),
            "{m}"
        );
        // 89 % of 6 ft is under MUTCD's 6 ft; of 5 ft under its 4.5 ft too
        let m = seams(Some(6.0 * 0.3048));
        assert!(
            m.contains(
                "Only letters at most 89 % of this size (1.63 m, 5.3 ft: under MUTCD's 6 ft"
            ),
            "{m}"
        );
        let m = seams(Some(5.0 * 0.3048));
        assert!(
            m.contains("smaller than MUTCD allows for word letters"),
            "{m}"
        );
        assert!(
            m.contains("at every size MUTCD allows the seams stay"),
            "{m}"
        );
        // a symbol's stroke has no letter size to name
        let m = seams(None);
        assert!(m.contains("Letters at most 89 % of this size paint"), "{m}");
        assert!(
            !m.to_lowercase()
                .contains("larger letters (--letter-height)"),
            "{m}"
        );
        let w = clamped(1.297, 0.02).render();
        assert!(!w.message.contains("rung"), "jargon: {}", w.message);
        assert_eq!(w.severity, Some(Severity::Problem));
        assert!(
            w.message.contains("0.40 % of the job's paint"),
            "{}",
            w.message
        );
        assert!(w
            .message
            .contains("2.00 % over the whole job (budget 1.1 %)"));
        // A symbol is made larger by its item's scale, not the letter height.
        let mut symbol = clamped(1.297, 0.02);
        if let Note::HeightClamped { owner, .. } = &mut symbol {
            owner.kind = OwnerKind::Symbol;
            owner.label = "arrow-left".into();
        }
        let m = symbol.render().message;
        assert!(m.contains("paint outside the symbol there"), "{m}");
        assert!(m.contains("a larger symbol (its scale)"), "{m}");
        assert!(!m.contains("--letter-height"), "{m}");
        // Within the budget over the whole job: a notice that says why.
        let w = clamped(1.297, 0.008).render();
        assert_eq!(w.severity, Some(Severity::Notice));
        assert!(
            w.message.contains("within the preview's overspray bound"),
            "{}",
            w.message
        );
        assert!(clamped(1.1, 0.008)
            .render()
            .message
            .contains("slightly soft"));
    }
}
