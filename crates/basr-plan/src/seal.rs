//! The sealed job: the samples with their totals, the layout, the stations,
//! the robot and font they were planned for, and the notes, hashed.

use basr_job::{self as job, FontRef, Job, Layout, Samples, StrokeBalance, Summary};
use basr_robot::AnyRobot;
use basr_shape::font::Font;
use basr_shape::layout::Marking;

use super::placed::PlacedStrokes;
use super::request::Tilt;
use super::stations::StationPlan;
use super::warnings::{self, Note};

/// Everything the job document holds, as the stages made it.
pub struct Planned<'a> {
    pub marking: &'a Marking,
    pub font: &'a Font,
    pub robot: AnyRobot,
    pub tilt: Tilt,
    pub period_s: f64,
    pub strokes: &'a PlacedStrokes,
    pub stations: StationPlan,
    pub samples: Samples,
    pub balance: Vec<StrokeBalance>,
    pub notes: Vec<Note>,
    /// Options other than compile's defaults (`layout.options`).
    pub options: Option<job::PlanOptions>,
    /// Laid out for a low-speed road (`layout.low_speed`).
    pub low_speed: bool,
}

/// The job document, its totals computed and its hashes filled.
pub fn seal(p: Planned<'_>) -> Job {
    let mut job = assemble(p);
    job.seal();
    job
}

/// The job document with its totals, not yet hashed (what the verifying
/// rounds simulate; [`seal`] hashes it).
pub fn assemble(p: Planned<'_>) -> Job {
    let n = p.samples.len();
    let paint_samples = p.samples.paint.iter().filter(|&&g| g == 1).count();
    let duration_s = job::tick_time(n.saturating_sub(1), p.period_s);
    let paint_time_s = job::tick_time(paint_samples, p.period_s);
    // Every stroke painted at speed × width = k takes its area / k.
    let lower_bound_s = p.strokes.painted_area_m2() / p.robot.paint().k_m2ps();
    let summary = Summary {
        duration_s,
        paint_time_s,
        air_time_s: job::round_ns((duration_s - paint_time_s).max(0.0)),
        strokes: p.strokes.strokes.len(),
        // Paint sprayed = flow × gun-on time (what leaves the tip; the film
        // gets the transfer-efficiency share of it).
        paint_volume_m3: p.robot.paint().flow_m3ps * paint_time_s,
        warnings: warnings::render_all(&p.notes),
        balance: p.balance,
        lower_bound_s,
        bound_ratio: if lower_bound_s > 0.0 {
            duration_s / lower_bound_s
        } else {
            0.0
        },
        verified_max_error_m: None,
        verified: None,
        truck_moves_m: p
            .stations
            .stations
            .iter()
            .scan(None::<[f64; 2]>, |prev, st| {
                let d = prev.map_or(0.0, |q| (st.x_m - q[0]).hypot(st.y_m - q[1]));
                *prev = Some([st.x_m, st.y_m]);
                Some(d)
            })
            .collect(),
        // Measured on the sealed job by `plan::film` (compile_strokes).
        film: None,
        // Set by compile once every station is verified.
        stops: vec![],
    };
    Job {
        format: job::FORMAT.into(),
        version: job::VERSION,
        message: p.marking.message(),
        font: FontRef {
            name: p.font.name.clone(),
            sha256: p.font.sha256.clone(),
        },
        paint: job::Paint::of(p.robot.paint()),
        robot: p.robot,
        robot_sha256: String::new(),
        control_period_s: p.period_s,
        layout: Layout {
            letter_height_m: p.marking.letter_height_m,
            lane_width_m: p.marking.lane_width_m,
            tilt_method: p.tilt.name().into(),
            glyphs: p.strokes.outlines(),
            options: p.options,
            low_speed: p.low_speed,
        },
        stations: p.stations.stations,
        road: p.stations.road,
        samples: p.samples,
        summary,
        outputs: Default::default(),
        sha256: String::new(),
        signature: None,
    }
}
