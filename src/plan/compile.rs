//! The compile pipeline: message or marking → layout → strokes → rungs →
//! knots with tilt → passes → stations → order → IK → time law → the job.

use std::f64::consts::FRAC_PI_2;
use std::path::PathBuf;

use kurbo::Affine;

use crate::font::Font;
use crate::job::{
    self, FontRef, Job, Layout as JobLayout, PlacedGlyph, PlacedStroke, SampleRow, Samples,
    Station, StrokeBalance, Summary, Warning,
};
use crate::layout::{self, LayoutError, Marking, Overrides};
use crate::plan::knots::{self, HeightLaw, Knot, PaintLaw, Rung, TiltMethod};
use crate::plan::order::{self, Ends};
use crate::plan::stations::{self, StationError};
use crate::plan::timing;
use crate::robot::kinematics::wrap_pi;
use crate::robot::{Joints, NozzlePose, Robot};

/// Default largest distance between rungs at the letter's scale (issue 4).
pub const DEFAULT_RUNG_SPACING_M: f64 = 0.020;
/// Default setpoint period (001 §4.2: "typically at 32 msec").
pub const DEFAULT_PERIOD_S: f64 = 0.032;

/// Where the message comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Words typed on the command line; each word one line.
    Message(String),
    /// A marking file's text; `origin` names it in messages.
    Marking { text: String, origin: String },
}

/// Tilt method (001 §2.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Tilt {
    None,
    Trapezoid,
    #[default]
    Quadrilateral,
}

impl Tilt {
    /// The name written in the job (`layout.tilt_method`).
    pub fn name(self) -> &'static str {
        match self {
            Tilt::None => "none",
            Tilt::Trapezoid => "trapezoid",
            Tilt::Quadrilateral => "quadrilateral",
        }
    }
}

/// Everything `compile_job` needs. `CompileRequest::message("STOP")` gives
/// the defaults of `basr compile STOP`.
#[derive(Clone, Debug, PartialEq)]
pub struct CompileRequest {
    pub source: Source,
    /// Letter height, lane width and line gap given on the command line.
    pub overrides: Overrides,
    /// Font name or file; `None` = the embedded font.
    pub font: Option<String>,
    /// Robot description file; `None` = the embedded BASR.
    pub robot: Option<PathBuf>,
    /// A robot description already in hand (a job's own, when preview
    /// re-plans it); used instead of `robot` when set.
    pub robot_description: Option<Robot>,
    pub tilt: Tilt,
    /// Largest distance between consecutive rungs (m).
    pub rung_spacing_m: f64,
    /// Setpoint period (s).
    pub period_s: f64,
    /// The gun is switched on this long before the nozzle reaches a
    /// stroke's first rung (valve opening delay; assumed 0 s: no source).
    pub gun_lead_s: f64,
    /// The gun is switched off this long before the nozzle reaches a
    /// stroke's last rung (valve closing delay; assumed 0 s: no source).
    pub gun_lag_s: f64,
    /// Margin kept from the edge of the arm's reach (m).
    pub reach_margin_m: f64,
}

impl CompileRequest {
    /// Defaults for a message typed on the command line.
    pub fn message(text: &str) -> CompileRequest {
        CompileRequest {
            source: Source::Message(text.to_string()),
            overrides: Overrides::default(),
            font: None,
            robot: None,
            robot_description: None,
            tilt: Tilt::default(),
            rung_spacing_m: DEFAULT_RUNG_SPACING_M,
            period_s: DEFAULT_PERIOD_S,
            gun_lead_s: 0.0,
            gun_lag_s: 0.0,
            reach_margin_m: stations::DEFAULT_MARGIN_M,
        }
    }
}

/// Why a compile failed; every variant is bad input (exit 2).
#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    #[error(transparent)]
    Layout(#[from] LayoutError),
    #[error(transparent)]
    Stations(#[from] StationError),
    #[error("{field} must be {what}, got {}", crate::io::show_num(*value))]
    Setting {
        field: &'static str,
        what: &'static str,
        value: f64,
    },
    #[error("font: {0}")]
    Font(String),
    #[error("robot: {0}")]
    Robot(String),
    #[error("{0}")]
    Unreachable(String),
    #[error("{0}")]
    Knots(String),
    #[error("time law: {0}")]
    Timing(String),
}

/// Knots keep this far inside the tilt range, so the time law's smooth
/// joint curves between knots (which may overshoot a knot held at a limit
/// by a fraction of a milliradian) stay inside it. assumed: forty times the
/// overshoot seen on STOP. (Narrow rungs hold the vertical joint at the
/// bottom of its stroke, where a millimetre of inset would widen the fan
/// past 3 %; there the setpoints are clamped instead, see `clamp_to_range`.)
const TILT_INSET_RAD: f64 = 0.0044; // 0.25°
/// Largest joint overshoot `clamp_to_range` absorbs (m or rad); anything
/// larger is a planning error.
const CLAMP_MAX: f64 = 1e-3;

/// Outline samples of `layout.glyphs` are at most this far apart (m).
const OUTLINE_STEP_M: f64 = 0.01;
/// Points of one item offered to the station planner (its knots, thinned).
const STATION_POINTS_PER_ITEM: usize = 32;

/// One continuous gun-on path: a stroke, or one pass of a wide stroke.
struct Item {
    stroke: usize,
    knots: Vec<Knot>,
}

/// Which letter a stroke belongs to, for messages.
struct StrokeInfo {
    ch: char,
    line: usize,
}

/// An item as the arm runs it: joints at every knot, in painting order.
struct Run {
    stroke: usize,
    /// Knots including the lead-in and lead-out.
    knots: Vec<Knot>,
    joints: Vec<Joints>,
    /// Indices of the first and last painting knot in `knots`.
    paint_first: usize,
    paint_last: usize,
}

/// Compile a message or marking into a sealed job.
pub fn compile_job(req: &CompileRequest) -> Result<Job, CompileError> {
    check_settings(req)?;
    let marking = match &req.source {
        Source::Message(m) => Marking::from_message(m, &req.overrides)?,
        Source::Marking { text, origin } => Marking::from_toml(text, origin, &req.overrides)?,
    };
    let robot = match &req.robot_description {
        Some(r) => r.clone(),
        None => Robot::load_or_default(req.robot.as_deref())
            .map_err(|e| CompileError::Robot(e.to_string()))?,
    };
    let owned_font;
    let font: &Font = match &req.font {
        None => Font::embedded(),
        Some(name) => {
            owned_font =
                Font::from_name_or_path(name).map_err(|e| CompileError::Font(e.to_string()))?;
            &owned_font
        }
    };
    let placed = layout::place(&marking, |ch| font.glyph(ch).map(glyph_box))?;
    let mut warnings: Vec<Warning> = placed
        .warnings
        .iter()
        .map(|w| Warning {
            kind: "layout".into(),
            stroke: -1,
            t_s: None,
            factor: None,
            message: w.clone(),
        })
        .collect();

    // Strokes → rungs → passes → knots.
    let law = paint_law(&robot);
    let method = match req.tilt {
        Tilt::None => TiltMethod::None,
        Tilt::Trapezoid => TiltMethod::Trapezoid,
        Tilt::Quadrilateral => TiltMethod::Quadrilateral,
    };
    let tl = &robot.limits.tilt_rad;
    let max_tilt = (tl.max.min(-tl.min) - TILT_INSET_RAD).max(0.0);
    let mut glyphs = vec![];
    let mut items: Vec<Item> = vec![];
    let mut strokes: Vec<StrokeInfo> = vec![];
    let mut balance: Vec<StrokeBalance> = vec![];
    for letter in &placed.letters {
        let Some(glyph) = font.glyph(letter.ch) else {
            continue; // place() has already refused letters without a glyph
        };
        let s = letter.scale_m;
        let to_road = Affine::new([s, 0.0, 0.0, s, letter.origin_m[0], letter.origin_m[1]]);
        let mut outlines = vec![];
        for stroke in &glyph.strokes {
            let st = stroke.transformed(&to_road);
            let sid = strokes.len();
            strokes.push(StrokeInfo {
                ch: letter.ch,
                line: letter.line,
            });
            let len = st.left.length().max(st.right.length());
            let k = ((len / OUTLINE_STEP_M).ceil() as usize).max(1) + 1;
            let pts = |e: &crate::geom::Edge| e.sample(k).iter().map(|p| [p.x, p.y]).collect();
            outlines.push(PlacedStroke {
                left: pts(&st.left),
                right: pts(&st.right),
            });
            let n = ((len / req.rung_spacing_m).ceil() as usize).max(1);
            let rungs: Vec<Rung> = st
                .rungs(n)
                .into_iter()
                .map(|(left, right)| Rung { left, right })
                .collect();
            let what = |e: knots::PlanError| {
                CompileError::Knots(format!(
                    "stroke {sid} (letter {} of line {}): {e}",
                    letter.ch,
                    letter.line + 1
                ))
            };
            let passes = knots::split_passes(&rungs, law.max_width_m(), 0.0).map_err(what)?;
            let mut clamped = 0usize;
            let mut rung_count = 0usize;
            let mut worst = 1.0f64;
            // knots::KnotPlan keeps U in percent; the job keeps fractions.
            let mut u_untilted = [f64::INFINITY, f64::NEG_INFINITY];
            let mut u_tilted = u_untilted;
            for pass in &passes {
                let mut kp = knots::knots(pass, &law, method, max_tilt).map_err(what)?;
                u_untilted = [
                    u_untilted[0].min(kp.u_before.0 / 100.0),
                    u_untilted[1].max(kp.u_before.1 / 100.0),
                ];
                u_tilted = [
                    u_tilted[0].min(kp.u_after.0 / 100.0),
                    u_tilted[1].max(kp.u_after.1 / 100.0),
                ];
                let raised = lift_for_tilt(&robot, &law, &mut kp.knots);
                if !raised.is_empty() {
                    // Wider footprints sweep more road: re-pace the pass.
                    knots::pace(pass, &mut kp.knots, law.k_m2ps);
                }
                clamped += kp
                    .clamped
                    .iter()
                    .filter(|c| !raised.contains(&c.rung))
                    .count()
                    + raised.len();
                rung_count += kp.knots.len();
                for k in &kp.knots {
                    if k.width_m > 0.0 {
                        worst = worst.max(k.fan_width_m / k.width_m);
                    }
                }
                items.push(Item {
                    stroke: sid,
                    knots: kp.knots,
                });
            }
            if u_untilted[0].is_finite() && u_tilted[0].is_finite() {
                balance.push(StrokeBalance {
                    stroke: sid,
                    char: letter.ch.to_string(),
                    line: letter.line,
                    u_untilted,
                    u_tilted,
                });
            }
            if passes.len() > 1 {
                warnings.push(Warning {
                    kind: "passes".into(),
                    stroke: sid as i64,
                    t_s: None,
                    factor: Some(passes.len() as f64),
                    message: format!(
                        "stroke {sid} (letter {} of line {}) is wider than one pass can paint \
                         ({:.3} m): painted in {} parallel passes",
                        letter.ch,
                        letter.line + 1,
                        law.max_width_m(),
                        passes.len()
                    ),
                });
            }
            if clamped > 0 {
                warnings.push(Warning {
                    kind: "height_clamped".into(),
                    stroke: sid as i64,
                    t_s: None,
                    factor: Some(worst),
                    message: format!(
                        "stroke {sid} (letter {} of line {}): {clamped} of {rung_count} rungs are \
                         narrower than the fan paints from the nozzle's lowest height \
                         ({:.3} m); the fan there paints up to {:.1} % wider than the stroke \
                         (the speed keeps the film)",
                        letter.ch,
                        letter.line + 1,
                        law.min_height_m,
                        (worst - 1.0) * 100.0
                    ),
                });
            }
        }
        glyphs.push(PlacedGlyph {
            char: letter.ch.to_string(),
            line: letter.line,
            strokes: outlines,
        });
    }

    // Stations: every item reachable from one truck position.
    let region = robot.region();
    let reach_pts: Vec<Vec<[f64; 2]>> = items.iter().map(|it| thin_tips(&it.knots)).collect();
    let splan = stations::plan(
        &reach_pts,
        marking.lane_width_m / 2.0,
        req.reach_margin_m,
        |x, y| region.margin(x, y),
    )?;

    // Per station: order, inverse kinematics, time law, setpoints.
    let stow = stow_joints(&robot);
    let mut samples = Samples::default();
    for (si, station) in splan.stations.iter().enumerate() {
        let mine: Vec<usize> = (0..items.len())
            .filter(|&i| splan.station_of[i] == si)
            .collect();
        let ends: Vec<Ends> = mine
            .iter()
            .map(|&i| {
                let k = &items[i].knots;
                let first = k.first().map(|k| k.tip).unwrap_or_default();
                let last = k.last().map(|k| k.tip).unwrap_or_default();
                Ends {
                    start: [first.x, first.y],
                    end: [last.x, last.y],
                }
            })
            .collect();
        let stow_pose = robot.fk(&stow);
        let from = stations::base_to_road(station, [stow_pose.x_m, stow_pose.y_m]);
        let cost = |a: [f64; 2], b: [f64; 2]| air_time_estimate(&robot, station, a, b);
        let tour = order::order(&ends, from, cost);
        let mut prev = stow;
        let mut runs = vec![];
        for v in &tour {
            let item = mine[v.item];
            let mut ks = items[item].knots.clone();
            if v.reversed {
                ks.reverse();
            }
            let mut solved = None;
            let mut first_err = None;
            for lead in [LEAD_M, 0.5 * LEAD_M, 0.0] {
                let (all, a, b) = with_leads(&ks, lead);
                match solve_run(&robot, station, &all, &prev) {
                    Ok(j) => {
                        solved = Some((all, j, a, b));
                        break;
                    }
                    Err((k, e)) => {
                        // Report the painting knot, not a lead's.
                        let k = k.saturating_sub(a).min(ks.len() - 1);
                        first_err.get_or_insert((k, e));
                    }
                }
            }
            let Some((all, joints, a, b)) = solved else {
                let (k, e) = first_err.unwrap_or((0, unreachable_pose()));
                let info = &strokes[items[item].stroke];
                return Err(CompileError::Unreachable(format!(
                    "stroke {} (letter {} of line {}) cannot be painted from station {si} at \
                     ({:.3}, {:.3}) m: {e}; use a smaller --letter-height or check the robot \
                     description",
                    items[item].stroke,
                    info.ch,
                    info.line + 1,
                    ks[k].tip.x,
                    ks[k].tip.y
                )));
            };
            prev = *joints.last().unwrap_or(&prev);
            runs.push(Run {
                stroke: items[item].stroke,
                knots: all,
                joints,
                paint_first: a,
                paint_last: b,
            });
        }
        let t0 = samples.len() as f64 * req.period_s;
        let (mut timed, slows) = time_station(&robot, &stow, &runs, req)?;
        clamp_to_range(&robot, &mut timed)?;
        // The robot's own check of the sampled joints (speeds, accelerations,
        // ball-nut speed): no job that breaks a limit leaves the compiler.
        let js: Vec<Joints> = timed.iter().map(|p| joints_of(&p.q)).collect();
        robot
            .check_rates(&js, req.period_s)
            .map_err(|e| CompileError::Timing(format!("station {si}: {e}")))?;
        for (k, j) in js.iter().enumerate() {
            robot.check_joints(j).map_err(|e| {
                CompileError::Timing(format!(
                    "station {si}, setpoint {k}: the joint path between knots leaves a joint's \
                     range ({e})"
                ))
            })?;
        }
        for sl in slows {
            let run = &runs[sl.run];
            let k = &run.knots[sl.knot.min(run.knots.len() - 1)];
            let info = &strokes[run.stroke];
            warnings.push(Warning {
                kind: "slowed".into(),
                stroke: run.stroke as i64,
                t_s: Some(job::round_ns(t0 + sl.t_s)),
                factor: Some(sl.factor),
                message: format!(
                    "stroke {} (letter {} of line {}): {} slows the nozzle below the painting \
                     speed near ({:.3}, {:.3}) m at t = {:.2} s; the film there is up to {:.2}× \
                     the target",
                    run.stroke,
                    info.ch,
                    info.line + 1,
                    sl.binding,
                    k.tip.x,
                    k.tip.y,
                    t0 + sl.t_s,
                    sl.factor
                ),
            });
        }
        append_samples(
            &mut samples,
            &robot,
            station,
            si as u32,
            &runs,
            &timed,
            req.period_s,
        );
    }

    let n = samples.len();
    let paint_samples = samples.paint.iter().filter(|&&p| p == 1).count();
    let duration_s = job::tick_time(n.saturating_sub(1), req.period_s);
    let paint_time_s = job::tick_time(paint_samples, req.period_s);
    let summary = Summary {
        duration_s,
        paint_time_s,
        air_time_s: job::round_ns((duration_s - paint_time_s).max(0.0)),
        strokes: strokes.len(),
        // Paint sprayed = flow × gun-on time (what leaves the tip; the film
        // gets the transfer-efficiency share of it).
        paint_volume_m3: robot.paint.flow_m3ps * paint_time_s,
        warnings,
        balance,
    };
    let mut job = Job {
        format: job::FORMAT.into(),
        version: job::VERSION,
        message: marking.message(),
        font: FontRef {
            name: font.name.clone(),
            sha256: font.sha256.clone(),
        },
        paint: robot.paint.job_paint(),
        robot,
        robot_sha256: String::new(),
        control_period_s: req.period_s,
        layout: JobLayout {
            letter_height_m: marking.letter_height_m,
            lane_width_m: marking.lane_width_m,
            tilt_method: req.tilt.name().into(),
            glyphs,
        },
        stations: splan.stations,
        samples,
        summary,
        outputs: Default::default(),
        sha256: String::new(),
        signature: None,
    };
    job.seal();
    Ok(job)
}

/// A glyph's extent on the grid: the grid's width, and the lowest and
/// highest points of its strokes' edges.
fn glyph_box(g: &crate::font::Glyph) -> layout::GlyphBox {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in &g.strokes {
        for e in [&s.left, &s.right] {
            for p in e.sample(65) {
                lo = lo.min(p.y);
                hi = hi.max(p.y);
            }
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return layout::GlyphBox::GRID;
    }
    layout::GlyphBox {
        width: crate::font::GRID_WIDTH,
        y_min: lo,
        y_max: hi,
    }
}

/// The paint law of the robot's nozzle and vertical joint. The reachable tip
/// heights leave room for the tilt's vertical tip offset at any tilt.
fn paint_law(robot: &Robot) -> PaintLaw {
    let p = &robot.paint;
    let top = robot.end_effector.tip_height_top_m;
    let v = &robot.limits.vertical_m;
    let t = &robot.limits.tilt_rad;
    // IK: vertical = top + rise(β) − z. A tip that sinks when tilted needs
    // room at the top of the stroke for every tilt; one that rises is
    // handled per knot (`lift_for_tilt`).
    let mut sink: f64 = 0.0;
    for k in 0..=40 {
        let b = t.min + (t.max - t.min) * k as f64 / 40.0;
        let off = robot.tilt_tip_offset(b);
        if off[1].is_finite() {
            sink = sink.max(-off[1]);
        }
    }
    PaintLaw {
        fan_angle_rad: p.fan_angle_rad,
        k_m2ps: p.k_m2ps(),
        height: match (p.height_law_c0_m, p.height_law_c1) {
            (Some(c0), Some(c1)) => HeightLaw::Linear { c0, c1 },
            _ => HeightLaw::Geometric,
        },
        min_height_m: top - v.max,
        max_height_m: top - v.min - sink,
    }
}

/// Raise knots whose tilted tip would need the vertical joint below its
/// stroke: the tilt four-bar lifts the tip by rise(β), so the lowest tip
/// height at tilt β is `law.min_height_m + rise(β)`. The fan then covers
/// more than the rung, and the speed follows the covered width (as
/// `knots::knots` does for its own clamp). Returns how many were raised.
fn lift_for_tilt(robot: &Robot, law: &PaintLaw, ks: &mut [Knot]) -> Vec<usize> {
    let mut raised = vec![];
    for (i, k) in ks.iter_mut().enumerate() {
        let rise = robot.tilt_tip_offset(k.tilt_rad)[1];
        if !(rise.is_finite() && rise > 0.0) {
            continue;
        }
        let z_min = law.min_height_m + rise;
        if k.z_m < z_min {
            let factor = crate::plan::tilt::height_factor(k.tilt_rad, law.fan_angle_rad);
            k.z_m = z_min;
            k.fan_width_m = law.width_at_height(z_min / factor).max(k.width_m);
            raised.push(i);
        }
    }
    raised
}

/// Up to `STATION_POINTS_PER_ITEM` knot tips, both ends included.
fn thin_tips(knots: &[Knot]) -> Vec<[f64; 2]> {
    let n = knots.len();
    if n == 0 {
        return vec![];
    }
    let step = n.div_ceil(STATION_POINTS_PER_ITEM).max(1);
    let mut v: Vec<[f64; 2]> = knots
        .iter()
        .step_by(step)
        .map(|k| [k.tip.x, k.tip.y])
        .collect();
    let last = knots[n - 1].tip;
    if (n - 1) % step != 0 {
        v.push([last.x, last.y]);
    }
    v
}

/// Where the arm waits while the truck moves: straight back, retracted,
/// nozzle at the top of its stroke, yaw and tilt centred (within limits).
fn stow_joints(robot: &Robot) -> Joints {
    let l = &robot.limits;
    let mid = |a: f64, b: f64| 0.5 * (a + b);
    Joints {
        base_rot_rad: mid(l.base_rot_rad.min, l.base_rot_rad.max),
        extension_m: l.extension_m.min,
        vertical_m: l.vertical_m.min,
        ee_yaw_rad: 0.0_f64.clamp(l.ee_yaw_rad.min, l.ee_yaw_rad.max),
        tilt_rad: 0.0_f64.clamp(l.tilt_rad.min, l.tilt_rad.max),
    }
}

/// Base-frame polar coordinates (θ1, R) of a road point.
fn polar(station: &Station, p: [f64; 2]) -> (f64, f64) {
    let b = stations::road_to_base(station, p);
    (b[1].atan2(b[0]), b[0].hypot(b[1]))
}

/// Estimated time of an air move of the arm between two road points: the
/// slower of base rotation and extension, each accelerating and braking at
/// its limit (symmetric, as the ordering needs).
fn air_time_estimate(robot: &Robot, station: &Station, a: [f64; 2], b: [f64; 2]) -> f64 {
    let (ta, ra) = polar(station, a);
    let (tb, rb) = polar(station, b);
    let l = &robot.limits;
    let t = |d: f64, v: f64, acc: f64| {
        let d = d.abs();
        if d * acc <= v * v {
            2.0 * (d / acc).sqrt()
        } else {
            d / v + v / acc
        }
    };
    t(tb - ta, l.base_rot_rad.max_vel, l.base_rot_rad.max_acc).max(t(
        rb - ra,
        l.extension_m.max_vel,
        l.extension_m.max_acc,
    ))
}

/// Joint travel time between two joint sets at the joints' speed limits.
fn travel(robot: &Robot, a: &Joints, b: &Joints) -> f64 {
    robot
        .limits
        .iter()
        .zip(a.values().into_iter().zip(b.values()))
        .map(|((_, l), (x, y))| (x - y).abs() / l.max_vel)
        .fold(0.0, f64::max)
}

/// The nozzle pose of a knot in a station's base frame.
fn knot_pose(station: &Station, k: &Knot) -> NozzlePose {
    let b = stations::road_to_base(station, [k.tip.x, k.tip.y]);
    NozzlePose {
        x_m: b[0],
        y_m: b[1],
        z_m: k.z_m,
        yaw_rad: k.yaw_rad - (station.heading_rad - FRAC_PI_2),
        tilt_rad: k.tilt_rad,
    }
}

/// Largest yaw-joint change between two knots of a run (rad). Knots are a
/// rung spacing apart (20 mm); the tightest turn in the font, a bowl's rung
/// pivoting about its inner end, turns the fan by well under this. A larger
/// step is a jump to the other fan branch (π) or yaw turn (2π).
const MAX_KNOT_YAW_STEP_RAD: f64 = std::f64::consts::FRAC_PI_2;

/// Joints for every knot of a run. The fan's two branches (ψ with β, ψ+π
/// with −β) and every yaw turn are tried at the first knot; each is followed
/// along the run by the nearest solution, and the branch with the least
/// joint travel (entry included) wins. Err: the knot index and why.
fn solve_run(
    robot: &Robot,
    station: &Station,
    ks: &[Knot],
    prev: &Joints,
) -> Result<Vec<Joints>, (usize, crate::robot::Unreachable)> {
    let first = knot_pose(station, &ks[0]);
    let starts = robot.ik(&first).map_err(|e| (0, e))?;
    let mut best: Option<(f64, Vec<Joints>)> = None;
    let mut last_err = None;
    'branch: for start in starts {
        let mut cost = travel(robot, prev, &start);
        let mut out = Vec::with_capacity(ks.len());
        out.push(start);
        for (i, k) in ks.iter().enumerate().skip(1) {
            let p = *out.last().unwrap_or(&start);
            match robot.ik_nearest(&knot_pose(station, k), &p) {
                // The nearest solution is on another branch or yaw turn: the
                // one this branch follows has left the yaw joint's range.
                // Turning the fan half or whole way round between two knots
                // would spray a disc with the gun on, so the branch fails.
                Ok(j) if (j.ee_yaw_rad - p.ee_yaw_rad).abs() > MAX_KNOT_YAW_STEP_RAD => {
                    let lim = &robot.limits.ee_yaw_rad;
                    let step = j.ee_yaw_rad - p.ee_yaw_rad;
                    // What the branch would have needed: the step less the
                    // half turns the jump added.
                    let own = step - std::f64::consts::PI * (step / std::f64::consts::PI).round();
                    let value = p.ee_yaw_rad + own;
                    last_err = Some((
                        i,
                        crate::robot::Unreachable {
                            joint: "ee_yaw_rad".into(),
                            value,
                            min: lim.min,
                            max: lim.max,
                            excess: (lim.min - value).max(value - lim.max).max(0.0),
                            flipped: false,
                        },
                    ));
                    continue 'branch;
                }
                Ok(j) => {
                    cost += travel(robot, &p, &j);
                    out.push(j);
                }
                Err(e) => {
                    last_err = Some((i, e));
                    continue 'branch;
                }
            }
        }
        if best.as_ref().is_none_or(|(c, _)| cost < *c - 1e-12) {
            best = Some((cost, out));
        }
    }
    match best {
        Some((_, v)) => Ok(v),
        None => Err(last_err.unwrap_or_else(|| (0, unreachable_pose()))),
    }
}

/// Placeholder reason when no IK branch was even tried (never expected).
fn unreachable_pose() -> crate::robot::Unreachable {
    crate::robot::Unreachable {
        joint: "pose".into(),
        value: f64::NAN,
        min: f64::NAN,
        max: f64::NAN,
        excess: f64::NAN,
        flipped: false,
    }
}

fn check_settings(req: &CompileRequest) -> Result<(), CompileError> {
    let positive = |field: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(CompileError::Setting {
                field,
                what: "a finite number above zero",
                value,
            })
        }
    };
    let non_negative = |field: &'static str, value: f64| {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(CompileError::Setting {
                field,
                what: "a finite number, zero or more",
                value,
            })
        }
    };
    positive("--rung-spacing-mm", req.rung_spacing_m * 1e3)?;
    positive("--period-s", req.period_s)?;
    non_negative("--gun-lead-s", req.gun_lead_s)?;
    non_negative("--gun-lag-s", req.gun_lag_s)?;
    non_negative("reach margin", req.reach_margin_m)?;
    let at_most = |field: &'static str, value: f64, max: f64, what: &'static str| {
        if value <= max {
            Ok(())
        } else {
            Err(CompileError::Setting { field, what, value })
        }
    };
    at_most(
        "--rung-spacing-mm",
        req.rung_spacing_m * 1e3,
        MAX_RUNG_SPACING_M * 1e3,
        "at most 100 mm: farther apart, rungs cut the corners of a letter's curves (default 20)",
    )?;
    at_most(
        "--period-s",
        req.period_s,
        MAX_PERIOD_S,
        "at most 0.1 s: a longer period would skip rungs at the painting speed (default 0.032)",
    )?;
    for (field, v) in [
        ("--gun-lead-s", req.gun_lead_s),
        ("--gun-lag-s", req.gun_lag_s),
    ] {
        at_most(
            field,
            v,
            MAX_GUN_SHIFT_S,
            "at most 1 s: the gun valve opens in tens of milliseconds, and a second is a \
             sixth of a metre of stroke at the painting speed (default 0)",
        )?;
    }
    Ok(())
}

/// Widest rung spacing, m. Assumed: the tightest curves of the road letters
/// (the S spine, the bowls) have radii of 0.1–0.2 m at 8 ft; rungs 0.1 m
/// apart already cut their chords by millimetres.
const MAX_RUNG_SPACING_M: f64 = 0.1;
/// Longest setpoint period, s: at the painting speed (≈ 0.16 m/s, SPEC §4) a
/// period past 0.125 s passes more than one default 20 mm rung between
/// setpoints; 0.1 s keeps every rung's change of speed and yaw in the job.
const MAX_PERIOD_S: f64 = 0.1;
/// Largest gun lead or lag, s. Assumed: an airless gun valve switches in tens
/// of milliseconds; a shift of a second moves the line's end by 0.16 m.
const MAX_GUN_SHIFT_S: f64 = 1.0;

/// Lead-in and lead-out length (m): the nozzle reaches the painting speed
/// before a stroke's first rung and keeps it past the last. assumed: 0.05 m
/// lets a path acceleration of 0.3 m/s² reach 0.17 m/s (a one-unit stroke
/// at 8 ft); shorter leads are tried where the arm cannot reach that far.
const LEAD_M: f64 = 0.10;
/// Pseudo-knots per lead.
const LEAD_KNOTS: usize = 5;

/// A knot with the same spray moved `d` metres along `dir` (road frame),
/// its fan turned by `dyaw`.
fn shifted(k: &Knot, dir: kurbo::Vec2, d: f64, dyaw: f64) -> Knot {
    Knot {
        mid: k.mid + dir * d,
        tip: k.tip + dir * d,
        yaw_rad: k.yaw_rad + dyaw,
        ..*k
    }
}

/// Fan turn per metre of tip travel from knot `a` to knot `b` (rad/m).
fn yaw_per_m(a: &Knot, b: &Knot) -> f64 {
    let ds = (b.tip - a.tip).hypot();
    let dyaw = crate::robot::kinematics::wrap_pi(b.yaw_rad - a.yaw_rad);
    if ds > knots::MIN_TIP_STEP_M && dyaw.is_finite() {
        dyaw / ds
    } else {
        0.0
    }
}

/// The run's knots with a lead-in and lead-out of `lead` metres along the
/// stroke's end directions; returns (knots, index of the first and last
/// painting knot).
fn with_leads(ks: &[Knot], lead: f64) -> (Vec<Knot>, usize, usize) {
    let n = ks.len();
    if lead <= 0.0 || n < 2 {
        return (ks.to_vec(), 0, n.saturating_sub(1));
    }
    let dir_in = (ks[0].tip - ks[1].tip).normalize();
    let dir_out = (ks[n - 1].tip - ks[n - 2].tip).normalize();
    if !(dir_in.is_finite() && dir_out.is_finite()) {
        return (ks.to_vec(), 0, n - 1);
    }
    // The fan already turns at the stroke's own rate when the gun opens: the
    // lead winds the turn up from rest (dyaw/ds falls linearly from the
    // stroke's rate at its end to 0 at the lead's far end), so a curved
    // stroke does not start with a step in yaw rate that the servo's
    // acceleration limit would answer by slowing the nozzle over paint.
    let (turn_in, turn_out) = (yaw_per_m(&ks[1], &ks[0]), yaw_per_m(&ks[n - 2], &ks[n - 1]));
    let wound = |d: f64| d - d * d / (2.0 * lead);
    let mut out = Vec::with_capacity(n + 2 * LEAD_KNOTS);
    for i in (1..=LEAD_KNOTS).rev() {
        let d = lead * i as f64 / LEAD_KNOTS as f64;
        out.push(shifted(&ks[0], dir_in, d, turn_in * wound(d)));
    }
    out.extend_from_slice(ks);
    for i in 1..=LEAD_KNOTS {
        let d = lead * i as f64 / LEAD_KNOTS as f64;
        out.push(shifted(&ks[n - 1], dir_out, d, turn_out * wound(d)));
    }
    (out, LEAD_KNOTS, LEAD_KNOTS + n - 1)
}

/// One station's timed samples: joints, the painting run (if any) whose
/// motion the sample belongs to, its path parameter, and the run whose gun
/// is commanded on.
struct Timed {
    q: Q,
    run: Option<usize>,
    s: f64,
    gun: Option<usize>,
}

/// Joint vector in `Limits::NAMES` order.
type Q = [f64; 5];

/// Jerk limit of every joint, as a multiple of its acceleration limit.
/// assumed: no source gives jerk limits; each joint reaches its
/// acceleration limit in 0.1 s (as the yaw servo reaches 30°/s in 0.1 s,
/// SPEC §4).
const JERK_PER_ACC: f64 = 10.0;

/// The robot's joint limits for the time law. The tilt's ball nut has its
/// own speed limit (SPEC §4: 0.11 m/s), applied as a tilt-rate limit at the
/// steepest nut travel per radian of the tilt range.
fn timing_limits(robot: &Robot) -> timing::JointLimits<5> {
    let mut vel = [0.0; 5];
    let mut acc = [0.0; 5];
    for (j, (_, l)) in robot.limits.iter().enumerate() {
        vel[j] = l.max_vel;
        acc[j] = l.max_acc;
    }
    let t = &robot.limits.tilt_rad;
    let fb = &robot.end_effector.fourbar;
    let steepest = (0..=60)
        .filter_map(|k| fb.nut_rate_m_per_rad(t.min + (t.max - t.min) * k as f64 / 60.0))
        .map(f64::abs)
        .fold(0.0, f64::max);
    if steepest > 0.0 {
        // 1 % below, for the nut rate between the sampled tilts.
        vel[4] = vel[4].min(robot.end_effector.tilt_nut_max_speed_mps / (steepest * 1.01));
    }
    timing::JointLimits {
        vel,
        acc,
        jerk: std::array::from_fn(|j| acc[j] * JERK_PER_ACC),
    }
}

fn q_of(j: &Joints) -> Q {
    j.values()
}

fn joints_of(q: &Q) -> Joints {
    Joints {
        base_rot_rad: q[0],
        extension_m: q[1],
        vertical_m: q[2],
        ee_yaw_rad: q[3],
        tilt_rad: q[4],
    }
}

/// Nozzle arc length at each knot (road frame, m), strictly increasing:
/// knots closer than 0.1 mm are nudged apart so the path stays defined.
fn arc_lengths(ks: &[Knot]) -> Vec<f64> {
    let mut s = Vec::with_capacity(ks.len());
    let mut acc = 0.0;
    for (i, k) in ks.iter().enumerate() {
        if i > 0 {
            let d = (k.tip - ks[i - 1].tip).hypot();
            acc += d.max(knots::MIN_TIP_STEP_M);
        }
        s.push(acc);
    }
    s
}

/// A slowdown of one painting run, for the job's warnings.
struct Slow {
    run: usize,
    factor: f64,
    knot: usize,
    t_s: f64,
    binding: String,
}

/// Time a station: stow → (air → run)* → air → stow, sampled at `period`
/// from t = 0 (`plan::timing`). Gun windows from the runs' first and last
/// painting knots, shifted by the lead and lag.
fn time_station(
    robot: &Robot,
    stow: &Joints,
    runs: &[Run],
    req: &CompileRequest,
) -> Result<(Vec<Timed>, Vec<Slow>), CompileError> {
    let limits = timing_limits(robot);
    let options = timing::PathOptions::default();
    let err = |what: String| CompileError::Timing(what);
    let mut pieces = vec![];
    // Piece index of each run, and each run's arc lengths.
    let mut run_piece = vec![];
    let mut arcs = vec![];
    let mut at = q_of(stow);
    for run in runs {
        let s = arc_lengths(&run.knots);
        let points: Vec<timing::PathPoint<5>> = run
            .knots
            .iter()
            .zip(&run.joints)
            .enumerate()
            .map(|(i, (k, j))| timing::PathPoint {
                s_m: s[i],
                q: q_of(j),
                // Leads are gun-off run-ups: as fast as the joints allow.
                max_speed_mps: (run.paint_first..=run.paint_last)
                    .contains(&i)
                    .then_some(k.speed_mps),
            })
            .collect();
        let first = points[0].q;
        pieces.push(
            timing::air_move(at, first, &limits, options.margin)
                .map_err(|e| err(format!("air move to stroke {}: {e}", run.stroke)))?,
        );
        run_piece.push(pieces.len());
        pieces.push(
            timing::time_path(&points, &limits, &options)
                .map_err(|e| err(format!("stroke {}: {e}", run.stroke)))?,
        );
        at = points[points.len() - 1].q;
        arcs.push(s);
    }
    pieces.push(
        timing::air_move(at, q_of(stow), &limits, options.margin)
            .map_err(|e| err(format!("air move to the stow pose: {e}")))?,
    );
    let sampled = timing::resample(&pieces, req.period_s).map_err(|e| err(e.to_string()))?;
    let starts: Vec<f64> = pieces
        .iter()
        .scan(0.0, |acc, p| {
            let s0 = *acc;
            *acc += p.duration_s();
            Some(s0)
        })
        .collect();
    // Gun command windows (station time).
    let windows: Vec<(f64, f64)> = runs
        .iter()
        .enumerate()
        .map(|(ri, run)| {
            let p = &pieces[run_piece[ri]];
            let (on, off) = p.gun_times(
                arcs[ri][run.paint_first],
                arcs[ri][run.paint_last],
                req.gun_lead_s,
                req.gun_lag_s,
            );
            let t0 = starts[run_piece[ri]];
            (t0 + on, t0 + off)
        })
        .collect();
    let mut out = Vec::with_capacity(sampled.len());
    let mut w = 0usize;
    for k in 0..sampled.len() {
        let t = sampled.t_s[k];
        let piece = sampled.piece[k];
        let run = run_piece.iter().position(|&p| p == piece);
        while w + 1 < windows.len() && t >= windows[w].1 {
            w += 1;
        }
        let gun = windows
            .get(w)
            .filter(|(on, off)| t >= *on && t < *off)
            .map(|_| w);
        out.push(Timed {
            q: sampled.q[k],
            run,
            s: sampled.s[k],
            gun,
        });
    }
    let mut slows = vec![];
    for (ri, &pi) in run_piece.iter().enumerate() {
        for sd in &pieces[pi].slowdowns {
            let binding = match sd.binding {
                timing::Binding::Velocity { joint } => {
                    format!("the {} speed limit", crate::robot::Limits::NAMES[joint])
                }
                timing::Binding::Acceleration { joint } => {
                    format!(
                        "the {} acceleration limit",
                        crate::robot::Limits::NAMES[joint]
                    )
                }
                timing::Binding::Rest => "the run-up from rest".into(),
            };
            slows.push(Slow {
                run: ri,
                factor: 1.0 / sd.factor.max(1e-9),
                knot: sd.worst_waypoint,
                t_s: starts[pi] + pieces[pi].time_at(arcs[ri][sd.worst_waypoint]),
                binding,
            });
        }
    }
    Ok((out, slows))
}

/// Clamp setpoints that the smooth joint curves carry a hair past a joint's
/// range (a knot held at the bottom of the vertical stroke); the rate
/// checks that follow still see every clamped sample.
fn clamp_to_range(robot: &Robot, timed: &mut [Timed]) -> Result<(), CompileError> {
    for (k, p) in timed.iter_mut().enumerate() {
        for (j, (name, l)) in robot.limits.iter().enumerate() {
            let v = p.q[j];
            let c = v.clamp(l.min, l.max);
            if (c - v).abs() > CLAMP_MAX {
                return Err(CompileError::Timing(format!(
                    "setpoint {k}: {name} = {v} leaves its range [{}, {}] between knots",
                    l.min, l.max
                )));
            }
            p.q[j] = c;
        }
    }
    Ok(())
}

/// Append a station's samples to the job's columns.
fn append_samples(
    samples: &mut Samples,
    robot: &Robot,
    station: &Station,
    station_index: u32,
    runs: &[Run],
    timed: &[Timed],
    period: f64,
) {
    let t0 = samples.len();
    let arcs: Vec<Vec<f64>> = runs.iter().map(|r| arc_lengths(&r.knots)).collect();
    // Nozzle in the road frame at every sample.
    let poses: Vec<(NozzlePose, [f64; 2], f64)> = timed
        .iter()
        .map(|p| {
            let pose = robot.fk(&joints_of(&p.q));
            let r = stations::base_to_road(station, [pose.x_m, pose.y_m]);
            let yaw = wrap_pi(pose.yaw_rad + station.heading_rad - FRAC_PI_2);
            (pose, r, yaw)
        })
        .collect();
    for (i, p) in timed.iter().enumerate() {
        let (pose, r, yaw) = &poses[i];
        let j = joints_of(&p.q);
        // Central difference of the nozzle position (one-sided at the ends).
        let (a, b) = (i.saturating_sub(1), (i + 1).min(timed.len() - 1));
        let speed = if b > a {
            let (pa, pb) = (&poses[a], &poses[b]);
            (pb.1[0] - pa.1[0]).hypot(pb.1[1] - pa.1[1]) / ((b - a) as f64 * period)
        } else {
            0.0
        };
        let act = robot.actuators(&j);
        let enc = robot.encoders(&j);
        let (stroke, paint, width) = match p.gun {
            Some(ri) => {
                let run = &runs[ri];
                // Before the run's motion (a gun lead) the width is the first rung's.
                let s = if p.run == Some(ri) {
                    p.s
                } else {
                    arcs[ri][run.paint_first]
                };
                let (w, _) = interp_knot(&run.knots, &arcs[ri], s);
                (run.stroke as i64, 1u8, w)
            }
            None => (-1, 0u8, 0.0),
        };
        samples.push(&SampleRow {
            t_s: job::tick_time(t0 + i, period),
            station: station_index,
            stroke,
            paint,
            x_m: r[0],
            y_m: r[1],
            z_m: pose.z_m,
            yaw_rad: *yaw,
            tilt_rad: j.tilt_rad,
            speed_mps: speed,
            width_m: width,
            base_rot_rad: j.base_rot_rad,
            extension_m: j.extension_m,
            cylinder_m: act.cylinder_m,
            vertical_m: j.vertical_m,
            ee_yaw_rad: j.ee_yaw_rad,
            tilt_nut_m: act.tilt_nut_m,
            enc_base: enc.base,
            enc_extension: enc.extension,
            enc_yaw: enc.yaw,
            enc_tilt: enc.tilt,
            enc_vertical: enc.vertical,
        });
    }
}

/// Rung width and painting speed at arc length `s`, linear between knots.
fn interp_knot(ks: &[Knot], arcs: &[f64], s: f64) -> (f64, f64) {
    let n = ks.len();
    let i = arcs.partition_point(|&a| a < s).clamp(1, n - 1);
    let (s0, s1) = (arcs[i - 1], arcs[i]);
    let f = if s1 > s0 {
        ((s - s0) / (s1 - s0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let lerp = |a: f64, b: f64| a + f * (b - a);
    (
        lerp(ks[i - 1].swept_width_m, ks[i].swept_width_m),
        lerp(ks[i - 1].speed_mps, ks[i].speed_mps),
    )
}
