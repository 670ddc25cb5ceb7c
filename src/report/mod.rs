//! The job sheet (`basr report`): what a crew and a supervisor need on one
//! printed page. [`build`] turns a job, its film preview and verdict, the
//! simulator's verdict and the crew's tip tally into a [`Sheet`] of plain
//! words and figures; [`html::render`] lays the sheet out as one
//! self-contained HTML page (inline CSS and SVG, nothing fetched).

pub mod html;
pub mod tally;

use crate::job::{Job, Severity, Station};
use crate::paint::metrics::Metrics;
use crate::paint::verdict::Verdict;

/// Time a truck move between two stations takes: pull forward a few
/// metres, stop, let the arm settle. // assumed: 1 min; the job does not
/// time truck moves yet (issue 11 adds them to the plan).
pub const TRUCK_MOVE_S: f64 = 60.0;

/// The simulator's verdict as the sheet shows it (from a run, or read back
/// from `basr simulate --json`).
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
pub struct SimVerdict {
    pub controller: String,
    pub verdict: crate::sim::report::Verdict,
    #[serde(default)]
    pub reasons: Vec<String>,
    pub max_error_m: f64,
    pub rms_error_m: f64,
    pub tolerance_m: f64,
}

impl SimVerdict {
    pub fn from_report(r: &crate::sim::report::Report) -> SimVerdict {
        SimVerdict {
            controller: r.controller.clone(),
            verdict: r.verdict,
            reasons: r.reasons.clone(),
            max_error_m: r.max_error_m,
            rms_error_m: r.rms_error_m,
            tolerance_m: r.tolerance_m,
        }
    }

    /// An electric kind's servo simulation (`sim::servo_job`).
    pub fn from_servo(r: &crate::sim::servo_job::ServoJobReport) -> SimVerdict {
        SimVerdict {
            controller: r.controller.clone(),
            verdict: r.verdict,
            reasons: r.reasons.clone(),
            max_error_m: r.max_error_m,
            rms_error_m: r.rms_error_m,
            tolerance_m: r.tolerance_m,
        }
    }
}

/// What goes into a sheet.
pub struct Input<'a> {
    /// The job as the crew names it (its file name).
    pub job_name: &'a str,
    pub job: &'a Job,
    pub film: &'a Metrics,
    pub film_verdict: &'a Verdict,
    /// The film picture (an SVG document).
    pub film_svg: &'a str,
    pub sim: Option<&'a SimVerdict>,
    /// Paint through the current tip before this job, m³, when the crew
    /// keeps a tally.
    pub tip_used_before_m3: Option<f64>,
    /// Whether the job is signed, by which key and whether that was
    /// verified (`basr::job::trust::Seal::describe`).
    pub signature: &'a str,
}

/// One truck stop in words.
#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    /// 1-based, as the crew counts.
    pub number: usize,
    pub instruction: String,
    /// Time the arm works at this stop, s.
    pub work_s: f64,
}

/// One letter (or marking item) with its film figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Letter {
    /// 1-based line and place in the line, as the text numbers them.
    pub line: usize,
    pub place: usize,
    pub char: String,
    pub mean_film_m: Option<f64>,
    pub cv: Option<f64>,
    pub coverage: Option<f64>,
    pub overspray: Option<f64>,
    pub pass: bool,
}

/// A warning as the sheet lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct Note {
    /// A job written before severities existed has its notes as notices.
    pub severity: Severity,
    pub text: String,
}

/// Everything the page shows, in words and SI figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    pub title: String,
    /// (label, value) lines of the job's identity.
    pub facts: Vec<(String, String)>,
    /// The message's lines and items, 1-based.
    pub items: Vec<String>,
    pub stops: Vec<Stop>,
    pub time_on_site_s: f64,
    pub paint_m3: f64,
    /// The tip's life left after this job (min, max), m³, with a tally.
    pub tip_left_m3: Option<(f64, f64)>,
    pub tip_life_m3: (f64, f64),
    pub film_verdict: Verdict,
    pub film_lines: Vec<(String, String)>,
    pub film_svg: String,
    pub letters: Vec<Letter>,
    pub sim: Option<SimVerdict>,
    pub notes: Vec<Note>,
    /// `ready`, `ready with notes` or `not ready`.
    pub overall: &'static str,
}

/// Time on site: the job's arm time and a truck move between stops.
pub fn time_on_site_s(job: &Job) -> f64 {
    let moves = job.stations.len().saturating_sub(1) as f64;
    job.summary.duration_s + moves * TRUCK_MOVE_S
}

/// What the stations are measured from, in words.
pub fn anchor_words(job: &Job) -> String {
    let first_line = job.message.lines().next().unwrap_or("the marking");
    format!("the near edge of {first_line}")
}

/// `ready`, `ready with notes` or `not ready` from the warnings'
/// severities (and any other failed verdict).
pub fn overall(severities: &[Severity], failed: bool) -> &'static str {
    if failed || severities.contains(&Severity::Problem) {
        "not ready"
    } else if severities.contains(&Severity::Notice) {
        "ready with notes"
    } else {
        "ready"
    }
}

/// Where a station's arm axis is, said from the anchor: `4.60 m past the
/// near edge of STOP, on the lane centre`.
pub fn place_words(s: &Station, anchor: &str) -> String {
    let along = if s.y_m >= 0.0 {
        format!("{:.2} m past {anchor}", s.y_m)
    } else {
        format!("{:.2} m before {anchor}", -s.y_m)
    };
    // +x is the approaching driver's right (SPEC §2).
    let across = if s.x_m.abs() < 0.005 {
        "on the lane centre".to_string()
    } else if s.x_m > 0.0 {
        format!("{:.2} m right of the lane centre", s.x_m)
    } else {
        format!("{:.2} m left of the lane centre", -s.x_m)
    };
    // heading −π/2: the arm's axis points straight back against the traffic.
    let turn_deg = (s.heading_rad + std::f64::consts::FRAC_PI_2).to_degrees();
    let turn = if turn_deg.abs() < 0.5 {
        String::new()
    } else {
        format!(", the truck turned {turn_deg:+.1}° from the lane direction (counter-clockwise +)")
    };
    format!("{along}, {across}{turn}")
}

/// The stops in words: the first from the anchor, later ones as a drive
/// forward and the place reached.
pub fn stops(job: &Job) -> Vec<Stop> {
    let anchor = format!("{} (the marking's anchor)", anchor_words(job));
    let n = job.stations.len();
    let mut work = vec![0.0; n];
    let s = &job.samples;
    for i in 0..s.len().saturating_sub(1) {
        if let Some(w) = work.get_mut(s.station[i] as usize) {
            *w += s.t_s[i + 1] - s.t_s[i];
        }
    }
    job.stations
        .iter()
        .enumerate()
        .map(|(k, st)| {
            let instruction = if k == 0 {
                format!(
                    "Drive with the traffic and stop the truck with the arm's rotation axis {}.",
                    place_words(st, &anchor)
                )
            } else {
                let prev = &job.stations[k - 1];
                let d = (st.x_m - prev.x_m).hypot(st.y_m - prev.y_m);
                let dir = if st.y_m >= prev.y_m {
                    "forward"
                } else {
                    "back"
                };
                format!(
                    "When stop {k} is painted, drive {d:.2} m {dir} and stop with the axis {}.",
                    place_words(st, &anchor)
                )
            };
            Stop {
                number: k + 1,
                instruction,
                work_s: work[k],
            }
        })
        .collect()
}

/// The letters with their figures, numbered as the text numbers them.
fn letters(m: &Metrics, v: &Verdict) -> Vec<Letter> {
    let mut place_in_line = std::collections::BTreeMap::<usize, usize>::new();
    m.glyphs
        .iter()
        .map(|g| {
            let place = place_in_line.entry(g.line).or_insert(0);
            *place += 1;
            Letter {
                line: g.line + 1,
                place: *place,
                char: g.char.clone(),
                mean_film_m: g.mean_film_m,
                cv: g.cv,
                coverage: g.coverage,
                overspray: g.overspray,
                pass: crate::paint::verdict::glyph_passes(g, &v.thresholds),
            }
        })
        .collect()
}

/// The message's lines as items, with their letter counts and heights.
fn items(job: &Job) -> Vec<String> {
    let h = job.layout.letter_height_m;
    job.message
        .lines()
        .enumerate()
        .map(|(k, line)| {
            let n = line.chars().filter(|c| !c.is_whitespace()).count();
            format!(
                "line {}: {line} ({n} letter{}, {h:.2} m / {:.1} ft tall)",
                k + 1,
                if n == 1 { "" } else { "s" },
                h / crate::units::M_PER_FT
            )
        })
        .collect()
}

/// Build the sheet.
pub fn build(input: &Input) -> Sheet {
    let job = input.job;
    let stops = stops(job);
    let time_on_site_s = time_on_site_s(job);
    let paint_m3 = job.summary.paint_volume_m3;
    let life = (
        job.robot.paint().tip_life_min_m3,
        job.robot.paint().tip_life_max_m3,
    );
    let tip_left_m3 = input
        .tip_used_before_m3
        .map(|used| (life.0 - used - paint_m3, life.1 - used - paint_m3));
    let notes: Vec<Note> = job
        .summary
        .warnings
        .iter()
        .map(|w| Note {
            severity: w.graded(),
            text: w.message.clone(),
        })
        .collect();
    let sim_fails = input
        .sim
        .is_some_and(|s| s.verdict != crate::sim::report::Verdict::Pass);
    let severities: Vec<Severity> = notes.iter().map(|n| n.severity).collect();
    let overall = overall(&severities, sim_fails || !input.film_verdict.pass());
    let m = input.film;
    let pct = |v: Option<f64>| v.map_or("–".into(), |v| format!("{:.1} %", v * 100.0));
    let film_lines = vec![
        (
            "mean film".into(),
            m.mean_film_m.map_or("–".into(), |f| {
                format!("{:.0} µm (target {:.0} µm)", f * 1e6, m.target_film_m * 1e6)
            }),
        ),
        ("evenness (cv)".into(), pct(m.cv)),
        ("coverage".into(), pct(m.coverage)),
        ("overspray".into(), pct(m.overspray)),
    ];
    let facts = vec![
        ("job file".into(), input.job_name.to_string()),
        ("job sha256".into(), job.sha256.chars().take(16).collect()),
        ("signature".into(), input.signature.to_string()),
        ("robot".into(), job.robot.name().to_string()),
        (
            "lane".into(),
            format!(
                "{:.2} m wide; tilt method {}",
                job.layout.lane_width_m, job.layout.tilt_method
            ),
        ),
    ];
    Sheet {
        title: job.message.replace('\n', " / "),
        facts,
        items: items(job),
        stops,
        time_on_site_s,
        paint_m3,
        tip_left_m3,
        tip_life_m3: life,
        film_verdict: input.film_verdict.clone(),
        film_lines,
        film_svg: input.film_svg.to_string(),
        letters: letters(m, input.film_verdict),
        sim: input.sim.cloned(),
        notes,
        overall,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn place_words_say_along_across_and_turn() {
        let st = |x_m, y_m, heading_rad| Station {
            x_m,
            y_m,
            heading_rad,
        };
        let down = -std::f64::consts::FRAC_PI_2;
        assert_eq!(
            place_words(&st(0.0, 4.6, down), "the near edge of STOP"),
            "4.60 m past the near edge of STOP, on the lane centre"
        );
        assert_eq!(
            place_words(&st(0.3, -1.0, down), "A"),
            "1.00 m before A, 0.30 m right of the lane centre"
        );
        assert!(place_words(&st(-0.3, 1.0, 0.0), "A")
            .contains("left of the lane centre, the truck turned +90.0°"));
    }
}
