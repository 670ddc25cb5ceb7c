//! The planner's tuning: every value the planner uses that is chosen rather
//! than derived from the arm's limits, the tip or the marking's geometry,
//! in one typed value, grouped by the stage that reads it. Each field
//! says its unit and why it has its value (`assumed:` where it was chosen
//! by measuring jobs, with what was measured).
//!
//! Compile plans with [`Tuning::DEFAULT`]; `CompileRequest::tuning` lets a
//! caller (the sensitivity test, an engineer exploring a value) plan with
//! another. The command line always plans with the default, so every job
//! `basr` writes is planned with these values and a job does not record
//! them.
//!
//! `tests/tuning_sensitivity.rs` moves each value by ±10 % (an integer by
//! ±1, its smallest step) and compiles a reduced sweep with it; what each
//! end does to the sweep is listed in docs/planner.md ("Tuning"), which
//! the test keeps in step with [`Tuning::knobs`] (only the two ends are
//! measured, not the range between or beyond).
//!
//! What is not here is either derived (the painting speed from the film
//! law, the fan's height from the rung's width, limits from the robot
//! description), a bound on work (most sweeps of a relaxation, most
//! points of a search: they end a loop, they do not shape the plan), a
//! step of a search that tries candidates in turn (`chain`'s tangent
//! scales 1, ½, ¼, 0; the time law's backward pass asking each step for
//! half the next point's speed where it can, `timing::path`), a
//! numerical tolerance, or a judge's threshold (the film's bounds, the
//! share of the tolerance the verified error may use: the acceptance
//! figures a plan is held to, not how it is made).

/// How a stroke's rungs are paired across its edges (`pairing`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pairing {
    /// Matched rungs are kept unless they ask the nozzle height or the
    /// tilt to change faster than this many times what its joint follows
    /// at film speed, and faster than equal arc-length rungs would (×).
    /// assumed, measured: the rate limits (`knots::knots_within`, `rate`)
    /// spread what a bowl's quarter asks (B, P, R, 3, D, 5 at 8 ft:
    /// 1.8–2.2 × the tilt's follow) with the film within 1.01×; the
    /// arrow's barb tips at 3 m asked 5.1× and slowed to 2.7–3.2× film
    /// (base rotation and tilt acceleration), the arrow's point 5.1 × the
    /// height's follow (equal arc-length: 3.8×).
    pub max_follow: f64,
    /// Fine edge steps per rung spacing (count, real). assumed: 8 lets a
    /// step's edges advance in ratios 1/3 … 3 and a rung average eight such
    /// steps (4 left the ratio steps visible as a zigzag in the rungs and
    /// the tilt: B's middle bar slowed to 1.49× film by the tilt's
    /// acceleration).
    pub fine_per_spacing: f64,
    /// Largest fine steps one step may take on either edge (count).
    /// assumed: 3, ratios from 1/3 to 3 between the edges' advance.
    pub max_step: usize,
    /// Edges whose lengths differ more than this ratio keep equal
    /// arc-length rungs (×): the search could not reach the far end within
    /// `max_step`. assumed (no measurement recorded): a little under
    /// `max_step`.
    pub max_length_ratio: f64,
    /// Share of the turn budget a step may turn at before it costs (1).
    /// assumed: leaves the turn limit (`turn`) a margin.
    pub turn_free: f64,
    /// Share of the sheet's depth (`basr_robot::paint_law::
    /// SHEET_DEPTH_SIGMA_M`) by which a job planned with its ends held in
    /// (`CompileRequest::hold_ends`, `rungs::held`) draws a rung's end in
    /// from an edge it meets at right angles to the edge's normal: the end
    /// moves by σ × this × |cos| of the angle between rung and edge (1).
    /// assumed, measured on C, G and J at 6 ft with the 509 tip alone
    /// (overspray 0.031–0.032, coverage 0.997): 0.15 and 0.25 paint all
    /// three (overspray 0.027–0.030, coverage 0.986–0.991), 0.5 trades too
    /// much coverage (0.976–0.980), 1.0 more (0.963–0.968).
    pub end_hold: f64,
    /// Weight of a turn over budget (per metre of travel). assumed,
    /// measured on B, P, R, 3 (docs/planner.md): a turn over budget
    /// outweighs everything.
    pub w_turn: f64,
    /// Weight of a rung's lean against the travel (sin², per metre).
    /// assumed: the least of the three.
    pub w_lean: f64,
    /// Weight of the distance from equal arc-length (× width², per metre).
    /// assumed, measured: 20 left P at cv 0.081, 100 at 0.042, 400 at
    /// 0.051. A cost on the ratio of the edges' advance instead left the
    /// wide end pivoting (P cv 0.060–0.072).
    pub w_diag: f64,
    /// Width (m) at which the distance from equal arc-length has weight
    /// `w_diag`. assumed (no measurement recorded): about a one-unit
    /// stroke at 8 ft (97 mm).
    pub ratio_width_m: f64,
}

/// How fast the fan, the tilt and the nozzle height may change while
/// painting (`turn`, `rate`, `knots`, `passes`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates {
    /// Share of the yaw joint's speed limit the fan's turn may take while
    /// painting (1). assumed: the base joint also turns the fan in the road
    /// frame (up to ≈ 0.05 rad/s at painting speed and 3 m reach) and the
    /// time law keeps its margin: 0.85 × 0.524 + 0.05 = 0.495 rad/s stays
    /// under 0.97 × 0.524 = 0.508 rad/s for BASR's 30°/s. (0.8 held the fan
    /// off the bowls' rungs longer: B, P, R, 3 cv 0.003–0.006 higher; 0.9
    /// passes the margin and STOP's bound ratio goes to 1.204.)
    pub turn_share: f64,
    /// Share of the tilt joint's speed limit at which the tilt's change
    /// between knots is spread when the knots are first placed
    /// (`knots::knots_within`, before `tilt_share`'s rate limit) (1).
    /// assumed: `turn_share`'s 0.85, which it shared until the tuning was
    /// collected; no measurement of its own.
    pub tilt_spread_share: f64,
    /// Share of the tilt joint's speed limit the tilt (and the nozzle
    /// height's joint) may take while painting (1). assumed: the time law
    /// keeps its margin and bounds the joint's rate by the steepest slope
    /// of its spline between knots, which exceeds the knot-to-knot slope
    /// by up to ≈ 15 % where the rate changes; 0.8 leaves that room.
    pub tilt_share: f64,
    /// Share of the tilt joint's acceleration limit the knot-to-knot tilt
    /// may take (1). assumed: the time law's shape-preserving spline is
    /// flat at a local extremum of the knots' values, which about doubles
    /// the curvature next to it, so under half,
    /// and the time law's step bounds are conservative on top: measured on
    /// 8's waist, 0.4 left the tilt's acceleration slowing it to 1.16× film
    /// there, 0.3 to 1.08×. The nozzle height's joint keeps its own
    /// share (`height_acc_share`); a job with problems is planned again
    /// with `gentle_tilt_acc_share`.
    pub tilt_acc_share: f64,
    /// Share of the vertical joint's acceleration limit the knot-to-knot
    /// nozzle height may take (1). assumed: the same spline as the tilt's
    /// (`tilt_acc_share`'s 0.3 of 8's waist); a gently planned job keeps it
    /// (the height's follow only ever raises a knot, a fan wider than its
    /// rung, and lowering it helped no glyph of the sweep that lowering
    /// the tilt's did).
    pub height_acc_share: f64,
    /// `tilt_acc_share` for a job planned gently (`CompileRequest::
    /// gentle_tilt`): compile plans a job again with it when its first plan
    /// has problems, and keeps the gentle job when that has none (1). The
    /// tilt's acceleration grows as the letter shrinks (a bowl's tilt turns
    /// over a shorter path at the same speed): 0.3 leaves 6 ft's D, P, R, 3
    /// and 5 NOT READY (B's bowls slowed to 1.41× film with the 509 tip),
    /// 7 ft's B and 3 and 9 ft's B and P. Measured over every glyph alone
    /// at 6, 7, 9 and 10 ft as the one share: 0.09, 0.10 and 0.11 paint the
    /// same glyphs (all but 6 ft's B, C, G, J, Q and S); 0.12 loses 9 ft's
    /// B, 0.132 7 ft's B and 9 ft's P, 0.15–0.2 6 ft's 3, 0.25 its P too;
    /// as compile's second plan, 0.09 and 0.11 paint the same glyphs at 6,
    /// 7 and 9 ft as 0.10. Not the default: at 8 ft it slows 6's and 9's
    /// tails to 1.27× film, which 0.3 paints within 1.15×.
    pub gentle_tilt_acc_share: f64,
    /// Rounds of smoothing of the tilt's spread change (count). assumed: 4
    /// round the corners over ≈ 3 knots either side.
    pub tilt_smoothing: usize,
    /// The tilt range the planner uses is the joint's less this (rad), so
    /// the time law's spline between knots (overshooting a knot held at a
    /// limit by a fraction of a milliradian) stays inside it. assumed:
    /// 0.25°, forty times the overshoot seen on STOP. (Narrow rungs hold
    /// the vertical joint at the bottom of its stroke, where a millimetre of
    /// inset would widen the fan past 3 %; there the setpoints are clamped
    /// instead, see `samples`.)
    pub tilt_inset_rad: f64,
}

/// The fan turned off a narrow stroke's rung (`narrow`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Narrow {
    /// The largest turn off the rung (rad). assumed: 60°, where the
    /// footprint covers half its length across; further turned it smears
    /// more along the stroke (`fan · sin φ`) than it narrows across, and a
    /// pointed end's zero-width rung would ask for 90°.
    pub max_turn_rad: f64,
    /// A knot leaned more than this (rad) keeps its fan on the rung: the
    /// turn would swing the lean off the rung and lose the balance the
    /// tilt was chosen for. assumed: 1°, far below the quadrilateral
    /// method's tilts on curves (5–15°); a narrow stroke's straight sides
    /// need no lean.
    pub leaned_rad: f64,
    /// Rounds of smoothing of the turn (count). assumed: 8 round a corner
    /// over ≈ 3 knots either side (30–60 mm at the rung spacing), the
    /// distance in which the fan joint reaches its turn rate at its
    /// acceleration limit at a narrow stroke's painting speed (0.44 rad/s
    /// at 5.2 rad/s² in 0.08 s, 15 mm at 0.16 m/s).
    pub smoothing: usize,
}

/// How strokes are entered, left and joined (`leads`, `joints`, `chain`,
/// `flight`, `trajectory`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joins {
    /// Lead-in and lead-out length (m): the nozzle reaches the painting
    /// speed before a stroke's first rung and keeps it past the last;
    /// half and none are tried where the arm cannot reach that far.
    /// assumed: 0.1 m. The reason recorded with it is for 0.05 m: that
    /// lets a path acceleration of 0.3 m/s² reach 0.17 m/s (v²/2a; a
    /// one-unit stroke at 8 ft), so 0.1 m leaves twice that room.
    pub lead_m: f64,
    /// Pseudo-knots per lead (count). assumed (no measurement recorded):
    /// 5, 20 mm apart at the default lead, the default rung spacing.
    pub lead_knots: usize,
    /// Path-parameter rate standing in for the joints' own motion in a
    /// blend (m of s per s of the slowest joint at its speed limit).
    /// assumed: about the painting speed (0.16 m/s), so blends and runs
    /// share a scale.
    pub blend_speed_mps: f64,
    /// Spacing of a blend's waypoints (m of s). assumed: the default rung
    /// spacing.
    pub blend_step_m: f64,
    /// Shortest blend (m of s): room to turn round where the next stroke
    /// starts where the last one ended and runs back. assumed: half the
    /// 0.1 m lead.
    pub blend_min_m: f64,
    /// Share of the time law's limits a flown join between two strokes is
    /// designed to (1). assumed: 0.9, chosen when the time law followed
    /// the designed join's waypoints. Since `flight` flies each join as a
    /// jerk-limited move of its own (`timing::join_move`), the designed
    /// join decides whether a join is flown at all (its synchronised move
    /// stays in the joints' ranges), prices joins for the stroke order
    /// (`chain::join_time`), and is the path only where that move is not
    /// found.
    pub design_share: f64,
    /// Share of that the designed join's last phase (arriving at the next
    /// stroke) accelerates at (1); its roles as `design_share`'s. assumed:
    /// half, chosen on STOP's and SCHOOL's verified errors (the hydraulic
    /// arm lagged a hard stop-and-go into the first rungs).
    pub arrival_share: f64,
    /// Time between the designed join's waypoints (s), which matter only
    /// where `flight`'s own move is not found. assumed: a quarter of the
    /// yaw servo's 0.1 s to full speed (000 app. C §3.2.1), so the spline
    /// through them keeps the ramps.
    pub flown_step_s: f64,
    /// Largest gap (m) between one stroke's last rung and the next one's
    /// first for the next to carry on without leads. assumed: a quarter of
    /// the default rung spacing.
    pub continue_gap_m: f64,
    /// Largest turn of the travel direction (rad) there. assumed: 20°.
    pub continue_turn_rad: f64,
    /// Share of the limits a jerk-limited air move holds back (1). The move
    /// is exact in continuous time (no grid), and every finite difference
    /// of its samples is a mean of the continuous rates, so only rounding
    /// needs room. assumed: ½ %.
    pub join_margin: f64,
    /// Jerk limit of every joint, as a multiple of its acceleration limit
    /// (1/s). assumed: no source gives jerk limits; each joint reaches its
    /// acceleration limit in 0.1 s (as the yaw servo reaches 30°/s in
    /// 0.1 s).
    pub jerk_per_acc: f64,
    /// Share of every velocity and acceleration limit the time law holds
    /// back on the painting path (against its grid's discretisation) and
    /// on the rest-to-rest air moves out of and back to stow (1). assumed:
    /// 3 % (`timing::DEFAULT_MARGIN`), ample for the 20 mm rung spacing;
    /// the timing property tests check the sampled output.
    pub path_margin: f64,
}

/// How compile re-times a station its verification run fails
/// (`basr::pipeline::compile`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retime {
    /// An error this soon after a stroke starts painting is the join's
    /// into it (s). assumed: about the hydraulic arm's settling after a
    /// fast join (the verified errors sit within 0.1 s of the first rung).
    pub arrival_s: f64,
    /// Each re-timing uses this share of the last one's accelerations (1).
    /// assumed: a few steps reach `min_pace` while each still gains.
    pub pace_step: f64,
    /// Slowest re-timing tried before the job is refused (share of the
    /// limits). assumed: a tenth.
    pub min_pace: f64,
}

/// How the planner treats a road surface that is not the truck's plane
/// (`basr::pipeline::compile`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Excursion of the surface from the truck's plane (m) left to the
    /// joints' clamp at the ends of the vertical stroke rather than
    /// narrowing the painting heights for a whole stroke. source: the
    /// nozzle's height over the road is to stay within 3 mm of plan; the
    /// fan's edges then move by at most this × tan(fan/2), 1.9 mm at the
    /// seed's 63.5° tip (under a third of the agency's 1/4 in), and only
    /// where the surface is that far off.
    pub clamp_free_m: f64,
}

/// The planner's one tuning value: see the module docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tuning {
    pub pairing: Pairing,
    pub rates: Rates,
    pub narrow: Narrow,
    pub joins: Joins,
    pub retime: Retime,
    pub surface: Surface,
}

impl Tuning {
    /// The values every job is planned with.
    pub const DEFAULT: Tuning = Tuning {
        pairing: Pairing {
            max_follow: 3.0,
            fine_per_spacing: 8.0,
            max_step: 3,
            max_length_ratio: 2.5,
            turn_free: 0.8,
            end_hold: 0.25,
            w_turn: 50.0,
            w_lean: 1.0,
            w_diag: 100.0,
            ratio_width_m: 0.1,
        },
        rates: Rates {
            turn_share: 0.85,
            tilt_spread_share: 0.85,
            tilt_share: 0.8,
            tilt_acc_share: 0.3,
            height_acc_share: 0.3,
            gentle_tilt_acc_share: 0.1,
            tilt_smoothing: 4,
            tilt_inset_rad: 0.0044, // 0.25°
        },
        narrow: Narrow {
            max_turn_rad: std::f64::consts::FRAC_PI_3,
            leaned_rad: 0.017453292519943295, // 1°
            smoothing: 8,
        },
        joins: Joins {
            lead_m: 0.10,
            lead_knots: 5,
            blend_speed_mps: 0.2,
            blend_step_m: 0.02,
            blend_min_m: 0.05,
            design_share: 0.9,
            arrival_share: 0.5,
            flown_step_s: 0.025,
            continue_gap_m: 0.005,
            continue_turn_rad: 0.35,
            join_margin: 0.005,
            jerk_per_acc: 10.0,
            path_margin: crate::timing::DEFAULT_MARGIN,
        },
        retime: Retime {
            arrival_s: 1.0,
            pace_step: 0.6,
            min_pace: 0.1,
        },
        surface: Surface {
            clamp_free_m: 0.003,
        },
    };

    /// Every value by its name (`stage.field`), for the sensitivity test
    /// and the docs' table.
    pub fn knobs(&mut self) -> Vec<(&'static str, Knob<'_>)> {
        use Knob::{Count, Real};
        // every field named, so a field added is a compile error here
        let Tuning {
            pairing:
                Pairing {
                    max_follow,
                    fine_per_spacing,
                    max_step,
                    max_length_ratio,
                    turn_free,
                    end_hold,
                    w_turn,
                    w_lean,
                    w_diag,
                    ratio_width_m,
                },
            rates:
                Rates {
                    turn_share,
                    tilt_spread_share,
                    tilt_share,
                    tilt_acc_share,
                    height_acc_share,
                    gentle_tilt_acc_share,
                    tilt_smoothing,
                    tilt_inset_rad,
                },
            narrow:
                Narrow {
                    max_turn_rad,
                    leaned_rad,
                    smoothing,
                },
            joins:
                Joins {
                    lead_m,
                    lead_knots,
                    blend_speed_mps,
                    blend_step_m,
                    blend_min_m,
                    design_share,
                    arrival_share,
                    flown_step_s,
                    continue_gap_m,
                    continue_turn_rad,
                    join_margin,
                    jerk_per_acc,
                    path_margin,
                },
            retime:
                Retime {
                    arrival_s,
                    pace_step,
                    min_pace,
                },
            surface: Surface { clamp_free_m },
        } = self;
        vec![
            ("pairing.max_follow", Real(max_follow)),
            ("pairing.fine_per_spacing", Real(fine_per_spacing)),
            ("pairing.max_step", Count(max_step)),
            ("pairing.max_length_ratio", Real(max_length_ratio)),
            ("pairing.turn_free", Real(turn_free)),
            ("pairing.end_hold", Real(end_hold)),
            ("pairing.w_turn", Real(w_turn)),
            ("pairing.w_lean", Real(w_lean)),
            ("pairing.w_diag", Real(w_diag)),
            ("pairing.ratio_width_m", Real(ratio_width_m)),
            ("rates.turn_share", Real(turn_share)),
            ("rates.tilt_spread_share", Real(tilt_spread_share)),
            ("rates.tilt_share", Real(tilt_share)),
            ("rates.tilt_acc_share", Real(tilt_acc_share)),
            ("rates.height_acc_share", Real(height_acc_share)),
            ("rates.gentle_tilt_acc_share", Real(gentle_tilt_acc_share)),
            ("rates.tilt_smoothing", Count(tilt_smoothing)),
            ("rates.tilt_inset_rad", Real(tilt_inset_rad)),
            ("narrow.max_turn_rad", Real(max_turn_rad)),
            ("narrow.leaned_rad", Real(leaned_rad)),
            ("narrow.smoothing", Count(smoothing)),
            ("joins.lead_m", Real(lead_m)),
            ("joins.lead_knots", Count(lead_knots)),
            ("joins.blend_speed_mps", Real(blend_speed_mps)),
            ("joins.blend_step_m", Real(blend_step_m)),
            ("joins.blend_min_m", Real(blend_min_m)),
            ("joins.design_share", Real(design_share)),
            ("joins.arrival_share", Real(arrival_share)),
            ("joins.flown_step_s", Real(flown_step_s)),
            ("joins.continue_gap_m", Real(continue_gap_m)),
            ("joins.continue_turn_rad", Real(continue_turn_rad)),
            ("joins.join_margin", Real(join_margin)),
            ("joins.jerk_per_acc", Real(jerk_per_acc)),
            ("joins.path_margin", Real(path_margin)),
            ("retime.arrival_s", Real(arrival_s)),
            ("retime.pace_step", Real(pace_step)),
            ("retime.min_pace", Real(min_pace)),
            ("surface.clamp_free_m", Real(clamp_free_m)),
        ]
    }

    /// This tuning with knob `name` moved: a real value times `factor`, a
    /// count one step up for a factor over 1 and one down for a factor
    /// under 1 (never under 1), unchanged at 1. `None` for a name that is
    /// not a knob.
    pub fn moved(mut self, name: &str, factor: f64) -> Option<Tuning> {
        let mut found = false;
        for (n, knob) in self.knobs() {
            if n != name {
                continue;
            }
            found = true;
            match knob {
                Knob::Real(v) => *v *= factor,
                Knob::Count(c) => {
                    if factor > 1.0 {
                        *c += 1;
                    } else if factor < 1.0 {
                        *c = c.saturating_sub(1).max(1);
                    }
                }
            }
        }
        found.then_some(self)
    }
}

impl Default for Tuning {
    fn default() -> Tuning {
        Tuning::DEFAULT
    }
}

/// One value of the tuning, to be read or moved.
pub enum Knob<'a> {
    /// A real number in its field's unit.
    Real(&'a mut f64),
    /// A count (rounds, steps, knots).
    Count(&'a mut usize),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_knob_has_one_name_and_moves_only_itself() {
        let mut t = Tuning::DEFAULT;
        let names: Vec<&str> = t.knobs().into_iter().map(|(n, _)| n).collect();
        let mut unique = names.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "a name twice");
        for n in &names {
            let up = Tuning::DEFAULT.moved(n, 1.1).unwrap();
            assert_ne!(up, Tuning::DEFAULT, "{n} did not move");
            // every other knob as it was
            let (mut up2, mut default) = (up, Tuning::DEFAULT);
            let moved: Vec<&str> = up2
                .knobs()
                .into_iter()
                .zip(default.knobs())
                .filter(|((_, a), (_, b))| match (a, b) {
                    (Knob::Real(x), Knob::Real(y)) => **x != **y,
                    (Knob::Count(x), Knob::Count(y)) => **x != **y,
                    _ => true,
                })
                .map(|((n, _), _)| n)
                .collect();
            assert_eq!(moved, vec![*n]);
        }
        assert!(Tuning::DEFAULT.moved("no.such", 1.1).is_none());
    }

    #[test]
    fn a_count_moves_by_one_and_stays_at_least_one() {
        let up = Tuning::DEFAULT.moved("pairing.max_step", 1.1).unwrap();
        assert_eq!(up.pairing.max_step, 4);
        let down = Tuning::DEFAULT.moved("pairing.max_step", 0.9).unwrap();
        assert_eq!(down.pairing.max_step, 2);
        let mut t = Tuning::DEFAULT;
        t.rates.tilt_smoothing = 1;
        assert_eq!(
            t.moved("rates.tilt_smoothing", 0.9)
                .unwrap()
                .rates
                .tilt_smoothing,
            1
        );
    }
}
