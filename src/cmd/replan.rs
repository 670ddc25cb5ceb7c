//! What `basr preview --compare` re-plans: the job's marking recovered (its
//! message, its one library symbol, or the marking file given with
//! `--marking`), laid out again and checked against the job's own
//! `layout.glyphs`, then compiled under each other tilt method.
//!
//! The job does not record the marking file a scene came from, only where
//! every item's outline landed; so a scene is re-read from the file the
//! operator names, and refused unless it lays out exactly where the job's
//! items are (the same check guards a message compiled with options the job
//! does not record, such as `--line-gap`).

use std::path::Path;

use anyhow::Context;
use basr::job::{Job, PlacedGlyph};
use basr::layout::Overrides;
use basr::pipeline::compile::{compile_job, CompileRequest, Source, Tilt};

/// What `--compare` carries from the job into the re-planned ones.
pub const REPLANNED_FROM: &str = "the job's message or symbol (a scene: --marking), robot, \
     font, letter height, lane width, low speed (--low-speed), period, rung spacing, gun \
     lead/lag and reach margin";
/// What it cannot: jobs written before they recorded their planning options
/// (`layout.options`) are re-planned with compile's defaults for them.
pub const NOT_RECORDED: &str = "nothing (a job written before jobs recorded their rung \
     spacing, gun lead/lag, reach margin and --low-speed: compile's defaults for those)";

/// What `--compare` cannot carry from `job`: nothing for a job that
/// records how it was timed (`summary.stops`, written since jobs record
/// their planning options too); else [`NOT_RECORDED`]'s caveat.
pub fn not_recorded(job: &Job) -> &'static str {
    if job.summary.stops.is_empty() {
        NOT_RECORDED
    } else {
        "nothing"
    }
}

/// Largest difference (m) between a re-laid outline point and the job's
/// for the layout to count as the job's. assumed: the job stores outlines
/// to the last bit (serde_json's float round trip), so only a float
/// re-association could differ; 1 µm is far below any change of layout.
const SAME_LAYOUT_M: f64 = 1e-6;

pub fn parse_tilt(s: &str) -> anyhow::Result<Tilt> {
    match s.trim() {
        "none" => Ok(Tilt::None),
        "trapezoid" => Ok(Tilt::Trapezoid),
        "quadrilateral" => Ok(Tilt::Quadrilateral),
        other => anyhow::bail!(
            "--compare: unknown tilt method {other:?}; use none, trapezoid or quadrilateral"
        ),
    }
}

/// The job's marking as a compile request (without the tilt), found and
/// checked by [`recover`].
pub struct Replan {
    req: CompileRequest,
}

/// The font to re-plan `job` with: the embedded one if the job was compiled
/// with it, else `--font`, which must be the job's font.
/// `by` names the command re-planning in messages (`--compare`, `fit`).
pub fn replan_font(
    job: &Job,
    origin: &str,
    font: Option<&str>,
    by: &str,
) -> anyhow::Result<Option<String>> {
    use basr::font::Font;
    let want = &job.font;
    match font {
        None if want.sha256 == Font::embedded().sha256 => Ok(None),
        None => anyhow::bail!(
            "{origin}: {by} re-plans the job, which was compiled with the font {:?} \
             (sha256 {}), not the embedded font; pass that font file with --font FILE",
            want.name,
            want.sha256
        ),
        Some(f) => {
            let given = Font::from_name_or_path(f).map_err(|e| anyhow::anyhow!("--font: {e}"))?;
            anyhow::ensure!(
                given.sha256 == want.sha256,
                "{origin}: --font {f} (sha256 {}) is not the font the job was compiled with \
                 ({:?}, sha256 {}); pass that font file, or leave --font out for the embedded font",
                given.sha256,
                want.name,
                want.sha256
            );
            Ok(Some(f.to_string()))
        }
    }
}

/// The library symbol a `basr compile --symbol NAME` job painted: its
/// message is `[NAME]` and its one outline is named NAME.
fn lone_symbol(job: &Job) -> Option<String> {
    let name = job.message.strip_prefix('[')?.strip_suffix(']')?;
    let one = matches!(&job.layout.glyphs[..], [g] if g.char == name);
    (one && basr::font::Library::embedded().get(name).is_some()).then(|| name.to_string())
}

/// A slope (m/m) in percent as the file gives it, to a millionth (2.004,
/// not 2.00, where that is what differs).
fn percent(s: f64) -> f64 {
    (s * 100.0 * 1e6).round() / 1e6
}

/// A road's described surface in words, for messages.
fn road_words(r: &basr::job::Road) -> String {
    match (r.cross_slope, r.crown_x_m) {
        (0.0, None) => "flat".to_string(),
        (s, None) => format!("cross_slope_pct = {}", percent(s)),
        (s, Some(c)) => format!("cross_slope_pct = {}, crown_x_m = {c}", percent(s)),
    }
}

/// Find what `job` was compiled from and check that it lays out as the job
/// did. `marking` is the `--marking` file (a scene, or a `lines` file);
/// `by` names the command re-planning in messages (`--compare`, `fit`).
pub fn recover(
    job: &Job,
    origin: &str,
    font: Option<String>,
    marking: Option<&Path>,
    by: &str,
) -> anyhow::Result<Replan> {
    use basr::robot::AnyRobot;
    // The job's description passed its hash check; read it back through the
    // validator so a sealed job with a broken robot is refused, not planned.
    let robot = AnyRobot::from_toml_str(&job.robot.to_toml_text(), "the job's robot description")
        .map_err(|e| anyhow::anyhow!("{by}: {e}"))?;
    let lane = Overrides {
        lane_width_m: Some(job.layout.lane_width_m),
        ..Overrides::default()
    };
    let with_height = Overrides {
        letter_height_m: Some(job.layout.letter_height_m),
        ..lane.clone()
    };
    // Each source with the overrides it may have been compiled with, the
    // file's own settings first.
    let (source, tries) = if let Some(path) = marking {
        let text = basr::io::read_text(path)?;
        let source = Source::Marking {
            text,
            origin: path.display().to_string(),
        };
        (source, vec![lane, with_height])
    } else if let Some(name) = lone_symbol(job) {
        (Source::Symbol(name), vec![lane])
    } else if job.message.contains('[') {
        anyhow::bail!(
            "{origin}: the job was compiled from a scene (its items: {}); {by} re-plans \
             it from its marking file: pass that file with --marking FILE",
            job.message.replace('\n', ", ")
        );
    } else {
        (
            Source::Message(job.message.replace('\n', " ")),
            vec![with_height],
        )
    };
    let mut differs = String::new();
    for overrides in tries {
        let mut req = CompileRequest::message("");
        req.source = source.clone();
        req.overrides = overrides;
        req.overrides.low_speed = job.layout.low_speed;
        req.robot_description = Some(robot.clone());
        req.font = font.clone();
        req.period_s = job.control_period_s;
        let req = req.with_options(job.layout.options.as_ref());
        let inputs = basr::plan::inputs::read(&req).map_err(|e| anyhow::anyhow!("{e}"))?;
        let (laid, strokes) = basr::pipeline::placed::lay_out(&req, &inputs.font)
            .map_err(|e| anyhow::anyhow!("{by}: {e}"))?;
        match first_difference(&job.layout.glyphs, &strokes.outlines()) {
            None => {
                // The job plans on the road it was compiled on; a marking
                // file describing another is not the file it came from.
                // (Without --marking the job's own road is used.)
                let (file, planned) = (&laid.road, &job.road);
                let differs =
                    (file.cross_slope, file.crown_x_m) != (planned.cross_slope, planned.crown_x_m);
                if marking.is_some() && differs {
                    anyhow::bail!(
                        "{origin}: {by}: the marking file's [road] ({}) is not the road the job \
                         was compiled on ({}); pass the file the job was compiled from",
                        road_words(file),
                        road_words(planned)
                    );
                }
                return Ok(Replan { req });
            }
            Some(d) => differs = d,
        }
    }
    let lines: Vec<&str> = job.message.lines().collect();
    let what = match marking {
        Some(p) => format!("the marking file {}", p.display()),
        None => format!("the job's message \"{}\"", lines.join(" ")),
    };
    // A message of several lines compiled with --line-gap lays out again
    // from a marking file of its lines and that gap (a scene's lines are
    // its items, `[symbol]`, which such a file refuses: a scene has only
    // its own marking file).
    let scene = job.message.contains('[');
    let gap = if scene {
        format!(
            "; the job is a scene (its items: {}): only the marking file it was compiled \
             from lays it out again",
            lines.join(", ")
        )
    } else if lines.len() > 1 {
        format!(
            "; a message compiled with --line-gap: write its lines and the gap in a marking \
             file ([marking] lines = [{}], line_gap_m = the gap given) and pass that",
            lines
                .iter()
                .map(|l| format!("\"{l}\""))
                .collect::<Vec<_>>()
                .join(", ")
        )
    } else {
        String::new()
    };
    anyhow::bail!(
        "{origin}: {by} cannot re-plan this job: {what} lays out differently from the \
         job ({differs}); pass the marking file the job was compiled from with --marking \
         FILE{gap}{shape}",
        shape = if scene {
            ""
        } else {
            " (a --shape job cannot be re-planned: compile it again instead)"
        }
    )
}

/// Where the re-laid outlines first differ from the job's, if they do.
fn first_difference(job: &[PlacedGlyph], laid: &[PlacedGlyph]) -> Option<String> {
    if job.len() != laid.len() {
        return Some(format!(
            "{} items and letters, the job has {}",
            laid.len(),
            job.len()
        ));
    }
    for (i, (a, b)) in job.iter().zip(laid).enumerate() {
        let same_points = |p: &[[f64; 2]], q: &[[f64; 2]]| {
            p.len() == q.len()
                && p.iter().zip(q).all(|(u, v)| {
                    (u[0] - v[0]).abs() <= SAME_LAYOUT_M && (u[1] - v[1]).abs() <= SAME_LAYOUT_M
                })
        };
        let same = a.char == b.char
            && a.strokes.len() == b.strokes.len()
            && a.strokes
                .iter()
                .zip(&b.strokes)
                .all(|(s, t)| same_points(&s.left, &t.left) && same_points(&s.right, &t.right));
        if !same {
            return Some(format!(
                "glyph {} is {:?} at another place or shape than the job's {:?}",
                i + 1,
                b.char,
                a.char
            ));
        }
    }
    None
}

impl Replan {
    /// The compile request that lays the job's marking out again.
    pub fn request(&self) -> &CompileRequest {
        &self.req
    }
}

/// The job re-planned with another tilt method.
pub fn replan(job: &Job, tilt: Tilt, r: &Replan) -> anyhow::Result<Job> {
    let mut req = r.req.clone();
    req.tilt = tilt;
    req.tilt_named = true;
    // preview measures the re-planned job's film itself.
    req.film = false;
    compile_job(&req).with_context(|| {
        format!(
            "--compare: re-planning {:?} with tilt {}",
            job.message,
            tilt.name()
        )
    })
}
