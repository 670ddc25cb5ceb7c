//! The site: where the truck really stopped and the road under it, as
//! `basr fit` measured them (docs/site.md). Compile keeps the job's stops
//! and puts the fitted one where it is, instead of planning stops; a stop
//! from which the arm cannot reach its marking is refused with the move
//! that brings it into reach.

use basr_job::{Road, Samples, Station};
use basr_robot::kinematics::wrap_pi;
use basr_robot::AnyRobot;

use super::error::StationError;
use super::passes::Passes;
use super::stations::{thin_tips, worst_point, StationPlan};

/// Where the truck stood for each stop and the road under them.
#[derive(Clone, Debug, PartialEq)]
pub struct Site {
    /// Every stop's pose, in the job's order (the fitted one among them).
    pub stations: Vec<Station>,
    /// The fitted stop (index from 0): the one whose reach is checked.
    pub fitted: usize,
    /// The road: the job's described surface and the plane fitted under
    /// the stop.
    pub road: Road,
    /// How the job being fitted timed and verified each stop
    /// (`summary.stops`, empty in jobs written before it): compile keeps
    /// every stop but the fitted one at its pace and with its figures
    /// instead of simulating it again (the caller then checks each kept
    /// stop moves as the job's did).
    pub kept: Vec<basr_job::StopTiming>,
    /// Each stop's passes as the job being fitted paints them, in its
    /// order (`painted_passes`; empty: ordered afresh): the fitted stop
    /// paints in the order the crew's job sheet gives, and the other
    /// stops move as the job's did, however each was ordered.
    pub painted: Vec<Vec<PaintedPass>>,
}

/// One pass as a job paints it: its stroke, the road points (m) where
/// its painting rows start and end, and where it is a quarter of its rows
/// in (which way round a closed pass, a wheel, is painted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaintedPass {
    pub stroke: usize,
    pub from_m: [f64; 2],
    pub to_m: [f64; 2],
    pub quarter_m: [f64; 2],
}

/// Each of `stops` stops' passes as `samples` paint them, in order: every
/// run of painting rows of one station and stroke (a run that changes
/// stroke without the gun closing is two).
pub fn painted_passes(samples: &Samples, stops: usize) -> Vec<Vec<PaintedPass>> {
    let mut out: Vec<Vec<PaintedPass>> = vec![Vec::new(); stops];
    let at = |i: usize| [samples.x_m[i], samples.y_m[i]];
    // the open run: its station, stroke and first and last rows
    let mut open: Option<(usize, usize, usize, usize)> = None;
    let mut close = |open: &mut Option<(usize, usize, usize, usize)>| {
        if let Some((si, stroke, first, last)) = open.take() {
            if let Some(stop) = out.get_mut(si) {
                stop.push(PaintedPass {
                    stroke,
                    from_m: at(first),
                    to_m: at(last),
                    quarter_m: at(first + (last - first) / 4),
                });
            }
        }
    };
    for i in 0..samples.len() {
        let here = (samples.paint[i] != 0 && samples.stroke[i] >= 0)
            .then(|| (samples.station[i] as usize, samples.stroke[i] as usize));
        match (&mut open, here) {
            (Some((si, k, _, last)), Some((s, stroke))) if *si == s && *k == stroke => *last = i,
            (_, here) => {
                close(&mut open);
                open = here.map(|(si, stroke)| (si, stroke, i, i));
            }
        }
    }
    close(&mut open);
    out
}

/// Rings of the search for a truck position that reaches (m): every
/// 50 mm out to 5 m. assumed: a crew repositions a truck to about a
/// hand's width, and 5 m is more than the arm's reach; beyond it the stop
/// is not the job's.
const RING_STEP_M: f64 = 0.05;
const RING_MAX_M: f64 = 5.0;
/// Directions tried on each ring (5° apart).
const RING_DIRECTIONS: usize = 72;

/// The site's stations for `passes`, each pass at the stop that painted
/// its stroke in the job being fitted (`Site::painted`), when that says
/// it for every pass (each stroke painted from one stop) and the fitted
/// stop reaches every point of its passes (as [`put_at_site`] asks): the
/// job's own grouping, without searching stations afresh only to replace
/// them (`stations::for_passes` then [`put_at_site`]; a third of
/// planning STOP's fitted stop). `None` otherwise (a job written before
/// `painted`, a stroke split between stops, a stop out of reach): the
/// caller plans the stations and [`put_at_site`] says what is wrong.
pub fn job_stations(passes: &Passes, site: &Site, robot: &AnyRobot) -> Option<StationPlan> {
    let mut stop_of = std::collections::BTreeMap::new();
    for (si, stop) in site.painted.iter().enumerate() {
        for p in stop {
            if *stop_of.entry(p.stroke).or_insert(si) != si {
                return None;
            }
        }
    }
    let station_of: Vec<usize> = passes
        .passes
        .iter()
        .map(|p| stop_of.get(&p.stroke).copied())
        .collect::<Option<_>>()?;
    let n = site.stations.len();
    if site.painted.len() != n || site.fitted >= n || station_of.iter().any(|&s| s >= n) {
        return None;
    }
    let region = robot.reach();
    let margin = |x: f64, y: f64| region.margin(x, y);
    // each stop's worst margin over its passes' points, as the planner's
    let mut points = vec![Vec::new(); n];
    for (p, &si) in passes.passes.iter().zip(&station_of) {
        points[si].extend(thin_tips(&p.knots));
    }
    let margins: Vec<f64> = points
        .iter()
        .zip(&site.stations)
        .map(|(pts, st)| worst_reach(pts, st, &margin))
        .collect();
    (margins[site.fitted] >= tilt_slack_m(robot)).then(|| StationPlan {
        stations: site.stations.clone(),
        station_of,
        margin_m: margins,
        road: site.road.clone(),
    })
}

/// How far (m) the nozzle's tip moves across the road as the tilt joint
/// leans it over its range, the other joints held (BASR's four-bar: 3.7 mm
/// at 15°). The reach region is the tip's at no tilt, so a fitted stop
/// must reach its points by this much more: a truck 0.68 m back from
/// STOP's stop reached the region by 8 mm and the leaned knots of its O
/// then asked the extension 1.5 mm below its range, an error that told
/// the crew to compile smaller letters instead of where to move (the
/// issue-29 audit).
fn tilt_slack_m(robot: &AnyRobot) -> f64 {
    let Some(tl) = robot.tilt_limit() else {
        return 0.0;
    };
    let mut q = super::stow::stow_joints(robot);
    let l = robot.limits();
    // mid-reach, the other joints at their stow
    q[1] = 0.5 * (l[1].min + l[1].max);
    q[4] = 0.0;
    let at = |tilt: f64| {
        let mut q = q;
        q[4] = tilt;
        let p = robot.fk(&q);
        [p.x_m, p.y_m]
    };
    let o = at(0.0);
    (0..=8)
        .map(|i| tl.min + (tl.max - tl.min) * i as f64 / 8.0)
        .map(|t| {
            let p = at(t);
            (p[0] - o[0]).hypot(p[1] - o[1])
        })
        .fold(0.0, f64::max)
}

/// `plan` with the site's stations and road: the stations compile planned
/// must be as many as the site's, and the fitted stop must reach every
/// point of its passes with `margin_m` to spare, or the move that does is
/// named.
pub fn put_at_site(
    plan: &mut StationPlan,
    passes: &Passes,
    site: &Site,
    robot: &AnyRobot,
    margin_m: f64,
) -> Result<(), StationError> {
    if site.stations.len() != plan.stations.len() {
        return Err(StationError::SiteStops {
            job: site.stations.len(),
            planned: plan.stations.len(),
        });
    }
    let si = site.fitted;
    let Some(planned) = plan.stations.get(si).cloned() else {
        return Ok(());
    };
    plan.stations = site.stations.clone();
    plan.road = site.road.clone();
    let Some(st) = plan.stations.get(si).cloned() else {
        return Ok(());
    };
    let region = robot.reach();
    let margin = |x: f64, y: f64| region.margin(x, y);
    let points: Vec<[f64; 2]> = passes
        .passes
        .iter()
        .zip(&plan.station_of)
        .filter(|(_, &s)| s == si)
        .flat_map(|(p, _)| thin_tips(&p.knots))
        .collect();
    let worst = |s: &Station| worst_reach(&points, s, &margin);
    let here = worst(&st);
    if let Some(m) = plan.margin_m.get_mut(si) {
        *m = here;
    }
    // The arm reaches every point (the planning margin is for the
    // controller's overshoot; simulation judges whether this stop keeps it),
    // the nozzle leaned as its knots ask.
    let slack = tilt_slack_m(robot);
    if here >= slack {
        return Ok(());
    }
    let (px, py) = worst_point(&points, &st, &margin);
    let advice = match nearest_reaching(&st, margin_m.max(slack), &worst) {
        Some(d) => move_words(&st, d),
        // Far off: back to where the job planned the stop, which reaches it.
        None => format!(
            "{} (to where the job planned the stop; nothing nearer reaches the whole stop: \
             check the points and the stop number too)",
            back_to(&st, &planned)
        ),
    };
    // each to the digits it is printed with, without a "-0.0"
    Err(StationError::SiteOutOfReach {
        stop: si + 1,
        x: basr_io::shown_as(st.x_m, 3),
        y: basr_io::shown_as(st.y_m, 3),
        turned_deg: basr_io::shown_as(turned_deg(st.heading_rad), 1),
        px: basr_io::shown_as(px, 3),
        py: basr_io::shown_as(py, 3),
        short_m: slack - here,
        advice,
    })
}

/// The worst reach margin (m) of road points `points` from a truck at
/// `st` (negative: one lies out of reach).
fn worst_reach(points: &[[f64; 2]], st: &Station, margin: &impl Fn(f64, f64) -> f64) -> f64 {
    points
        .iter()
        .map(|p| {
            let b = st.road_to_base(*p);
            margin(b[0], b[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// The smallest road-frame move of `st` (same heading) after which every
/// point keeps `margin_m`: the first ring with one, its best direction.
fn nearest_reaching(
    st: &Station,
    margin_m: f64,
    worst: &impl Fn(&Station) -> f64,
) -> Option<[f64; 2]> {
    let rings = (RING_MAX_M / RING_STEP_M).round() as usize;
    for k in 1..=rings {
        let r = k as f64 * RING_STEP_M;
        let mut best: Option<(f64, [f64; 2])> = None;
        for j in 0..RING_DIRECTIONS {
            let a = std::f64::consts::TAU * j as f64 / RING_DIRECTIONS as f64;
            let d = [r * a.cos(), r * a.sin()];
            let moved = Station {
                x_m: st.x_m + d[0],
                y_m: st.y_m + d[1],
                heading_rad: st.heading_rad,
            };
            let m = worst(&moved);
            if m >= margin_m && best.is_none_or(|(b, _)| m > b) {
                best = Some((m, d));
            }
        }
        if let Some((_, d)) = best {
            return Some(d);
        }
    }
    None
}

/// How far a truck at `heading_rad` is turned from the lane direction
/// (deg, counter-clockwise +, in (−180, 180]): the job sheet's and fit's
/// words for a stop (`report::place_words`), not the road frame's heading.
fn turned_deg(heading_rad: f64) -> f64 {
    wrap_pi(heading_rad + std::f64::consts::FRAC_PI_2).to_degrees()
}

/// The way from the truck at `st` back to the `planned` stop in the crew's
/// words: the move, and the turn where the headings differ (a truck
/// turned far round had only a move of 0.00 m to make).
fn back_to(st: &Station, planned: &Station) -> String {
    let d = [planned.x_m - st.x_m, planned.y_m - st.y_m];
    // counter-clockwise +
    let turn = wrap_pi(planned.heading_rad - st.heading_rad).to_degrees();
    // assumed: under half a degree is not a turn a driver can make.
    let turn = (turn.abs() >= 0.5).then(|| {
        format!(
            "{:.1}° {}",
            turn.abs(),
            if turn < 0.0 {
                "clockwise"
            } else {
                "counter-clockwise"
            }
        )
    });
    match (move_parts(st, d).is_empty(), turn) {
        (true, Some(t)) => format!("turn the truck {t}"),
        (false, Some(t)) => format!("{} and turn it {t}", move_words(st, d)),
        (_, None) => move_words(st, d),
    }
}

/// A road-frame move `d` of the truck at `st` in the crew's words: forward
/// or back along the truck, to its left or right.
fn move_words(st: &Station, d: [f64; 2]) -> String {
    format!(
        "move the truck {} (road frame: x {:+.2} m, y {:+.2} m)",
        move_parts(st, d).join(" and "),
        d[0],
        d[1]
    )
}

/// [`move_words`]'s parts: forward or back, left or right (none under a
/// centimetre).
fn move_parts(st: &Station, d: [f64; 2]) -> Vec<String> {
    // The truck faces away from the arm: +y of the base frame points back
    // along the arm's symmetry axis (heading_rad), so forward is its
    // opposite; the driver's right is forward turned a quarter clockwise.
    let fwd = [-st.heading_rad.cos(), -st.heading_rad.sin()];
    let right = [fwd[1], -fwd[0]];
    let along = d[0] * fwd[0] + d[1] * fwd[1];
    let across = d[0] * right[0] + d[1] * right[1];
    let mut parts = vec![];
    // assumed: under 1 cm is not a move a driver can make.
    if along.abs() >= 0.01 {
        let way = if along > 0.0 { "forward" } else { "back" };
        parts.push(format!("{:.2} m {way}", along.abs()));
    }
    if across.abs() >= 0.01 {
        let way = if across > 0.0 { "right" } else { "left" };
        parts.push(format!("{:.2} m to the {way}", across.abs()));
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The job's grouping: each pass (stroke 2's two among them) at the
    /// stop that painted its stroke in the job, at the site's poses; a
    /// stroke painted from two stops, one the job never painted, a job
    /// without painted passes, or a fitted stop out of reach: none, so
    /// the planner's search and `put_at_site`'s refusal speak.
    #[test]
    fn a_fitted_job_keeps_the_jobs_stops() {
        use crate::knots::Knot;
        use crate::passes::Pass;
        let robot = AnyRobot::Basr(basr_robot::Robot::basr());
        let down = -std::f64::consts::FRAC_PI_2;
        let stop = |y_m: f64| Station {
            x_m: 0.0,
            y_m,
            heading_rad: down,
        };
        // stop 0's axis 4 m up the lane, stop 1's 14 m: each paints 3 m
        // behind it
        let pass = |stroke: usize, y: f64| Pass {
            stroke,
            knots: vec![Knot::at(-0.2, y), Knot::at(0.2, y)],
        };
        let passes = Passes {
            passes: vec![pass(0, 1.0), pass(1, 11.0), pass(2, 11.2), pass(2, 11.4)],
            ..Passes::default()
        };
        let ran = |stroke: usize| PaintedPass {
            stroke,
            from_m: [0.0, 0.0],
            to_m: [0.0, 0.0],
            quarter_m: [0.0, 0.0],
        };
        let site = Site {
            stations: vec![stop(4.0), stop(14.0)],
            fitted: 1,
            road: Road::default(),
            kept: vec![],
            painted: vec![vec![ran(0)], vec![ran(1), ran(2)]],
        };
        let plan = job_stations(&passes, &site, &robot).expect("the job says every pass");
        assert_eq!(plan.station_of, vec![0, 1, 1, 1]);
        assert_eq!(plan.stations, site.stations);
        assert!(
            plan.margin_m.iter().all(|&m| m > 0.0),
            "{:?}",
            plan.margin_m
        );
        let mut far = site.clone();
        far.stations[1] = stop(24.0);
        assert!(job_stations(&passes, &far, &robot).is_none());
        let mut two = site.clone();
        two.painted[0].push(ran(1));
        assert!(job_stations(&passes, &two, &robot).is_none());
        let mut unpainted = site.clone();
        unpainted.painted[1].pop();
        assert!(job_stations(&passes, &unpainted, &robot).is_none());
        let mut old = site.clone();
        old.painted.clear();
        assert!(job_stations(&passes, &old, &robot).is_none());
    }

    /// Back to the planned stop: a truck turned far round is told to turn
    /// (it had a move of 0.00 m to make), in the sheet's convention
    /// (turned from the lane direction, counter-clockwise +); a truck off
    /// and turned gets both; one only off, the move alone.
    #[test]
    fn the_way_back_says_the_turn() {
        let down = -std::f64::consts::FRAC_PI_2;
        let planned = Station {
            x_m: 0.0,
            y_m: 4.57,
            heading_rad: down,
        };
        let at = |x_m: f64, y_m: f64, turned: f64| Station {
            x_m,
            y_m,
            heading_rad: down + turned.to_radians(),
        };
        assert_eq!(turned_deg(at(0.0, 0.0, 130.0).heading_rad), 130.0);
        assert!((turned_deg(at(0.0, 0.0, 200.0).heading_rad) + 160.0).abs() < 1e-9);
        assert_eq!(
            back_to(&at(0.0, 4.57, 130.0), &planned),
            "turn the truck 130.0° clockwise"
        );
        assert_eq!(
            back_to(&at(0.0, 4.57, -20.0), &planned),
            "turn the truck 20.0° counter-clockwise"
        );
        let both = back_to(&at(0.0, 2.57, 10.0), &planned);
        assert!(
            both.starts_with("move the truck ") && both.ends_with(" and turn it 10.0° clockwise"),
            "{both}"
        );
        let moved = back_to(&at(2.5, 4.57, 0.2), &planned);
        assert!(
            moved.starts_with("move the truck 2.50 m") && !moved.contains("turn"),
            "{moved}"
        );
    }

    /// A job's painting rows read back as runs: one per station and
    /// stroke the gun paints without closing, from its first row's place
    /// to its last's; air rows and rows of other strokes end a run.
    #[test]
    fn painted_passes_are_the_runs_of_painting_rows() {
        let mut s = Samples::default();
        // (station, stroke, paint, x)
        let rows: [(u32, i64, u8, f64); 12] = [
            (0, -1, 0, 0.0),
            (0, 3, 1, 0.1),
            (0, 3, 1, 0.2),
            (0, 3, 1, 0.3),
            (0, 3, 1, 0.4),
            (0, 3, 1, 0.5),
            (0, 1, 1, 0.6), // a join that runs on into another stroke
            (0, 1, 1, 0.7),
            (0, -1, 0, 0.8),
            (0, 3, 1, 0.9), // the same stroke again, after an air move
            (1, 3, 1, 1.0), // the next stop's rows
            (1, 3, 0, 1.1), // the gun closed on the stroke: not painting
        ];
        for (station, stroke, paint, x) in rows {
            s.push(&basr_job::SampleRow {
                station,
                stroke,
                paint,
                x_m: x,
                y_m: 1.0,
                ..Default::default()
            });
        }
        let p = |stroke, a: f64, q: f64, b: f64| PaintedPass {
            stroke,
            from_m: [a, 1.0],
            to_m: [b, 1.0],
            quarter_m: [q, 1.0],
        };
        assert_eq!(
            painted_passes(&s, 2),
            vec![
                vec![
                    p(3, 0.1, 0.2, 0.5),
                    p(1, 0.6, 0.6, 0.7),
                    p(3, 0.9, 0.9, 0.9)
                ],
                vec![p(3, 1.0, 1.0, 1.0)],
            ]
        );
        // a station the job does not have is left out
        assert_eq!(painted_passes(&s, 1).len(), 1);
    }

    #[test]
    fn moves_are_said_in_the_truck_frame() {
        let st = Station {
            x_m: 0.0,
            y_m: 4.0,
            heading_rad: -std::f64::consts::FRAC_PI_2,
        };
        // The truck drives with the traffic (+y): +y is forward, +x right.
        let w = move_words(&st, [0.2, -2.5]);
        assert!(
            w.contains("2.50 m back") && w.contains("0.20 m to the right"),
            "{w}"
        );
        let w = move_words(&st, [-0.3, 0.0]);
        assert!(
            w.contains("0.30 m to the left") && !w.contains("forward"),
            "{w}"
        );
    }

    #[test]
    fn the_nearest_reaching_move_is_found() {
        let st = Station {
            x_m: 0.0,
            y_m: 0.0,
            heading_rad: -std::f64::consts::FRAC_PI_2,
        };
        // Reaches where the truck is at y ≥ 1.2: the move is 1.2 m along +y.
        let worst = |s: &Station| s.y_m - 1.2;
        let d = nearest_reaching(&st, 0.0, &worst).unwrap();
        assert!((d[1] - 1.2).abs() < 1e-9 && d[0].abs() < 1e-9, "{d:?}");
        assert!(nearest_reaching(&st, 0.0, &|_: &Station| -1.0).is_none());
    }
}
