//! The simulated controller's safety monitor (issue 12, faults): what the
//! real controller must do when the arm or its sensors fail, run every 5 ms
//! beside the control law.
//!
//! It stops the arm (the plant's `estop`: supply dumped to tank so the
//! counterbalance valves brake the motor, the extension's enable valve
//! closed, both valves centred) when
//! - an encoder moves further in one tick than its joint can (a glitch),
//! - the supply pressure falls below the low-pressure switch,
//! - the joints' following error puts the nozzle too far off its path,
//! - the base rotation leaves its safety window (000 §III's `q1_a` test);
//!
//! and it keeps the gun off while the encoders put the nozzle more than the
//! tolerance off the path, and for good once it has stopped the arm. The
//! gun's needle closes [`GUN_LATENCY_S`] after it is told to.

use serde::Serialize;

use super::control::Measurement;
use super::fault::Fault;
use super::model::SimModel;
use super::report::Place;

/// Following error (nozzle, from the encoders) that stops the arm (m).
/// assumed: 25 mm, four times the 1/4 in tolerance: past it the stroke is
/// lost anyway and the arm must not keep swinging; jobs within tolerance
/// stay well below it (the gun interlock acts at the tolerance itself).
pub const FOLLOW_LIMIT_M: f64 = 0.025;
/// Low supply pressure switch, as a fraction of the supply setting.
/// assumed: 60 %, below the ±10 % a healthy supply varies by and above
/// the accumulator's precharge (68 %) less its band, where the arm can no
/// longer be held.
pub const SUPPLY_SWITCH_FRACTION: f64 = 0.6;
/// An encoder step larger than this many times what its joint can move in
/// one tick at full valve opening is a glitch. assumed: 2 (the physical
/// bound already takes all of the supply across the valve).
pub const ENCODER_HEADROOM: f64 = 2.0;
/// Time from the gun told off to its needle closed (s). assumed: 20 ms, an
/// airless gun's solenoid-driven needle (10–30 ms).
pub const GUN_LATENCY_S: f64 = 0.02;
/// The arm is at rest when the nozzle moves slower than this (m/s).
/// assumed: 1 mm/s, below the encoders' resolution over one tick at reach.
pub const REST_SPEED_MPS: f64 = 1.0e-3;
/// How long the simulation goes on after a stop to see the arm come to rest (s).
pub const AFTER_STOP_S: f64 = 3.0;

/// One injected fault and where the nozzle was meant to be then.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaultEvent {
    pub kind: &'static str,
    pub at: Place,
    pub what: &'static str,
}

/// How the monitor stopped the arm.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stop {
    /// `encoder_jump`, `supply_low`, `following_error` or `safety_window`.
    pub kind: &'static str,
    pub cause: String,
    /// When and where the monitor stopped the arm (the desired nozzle point).
    pub at: Place,
    /// When the gun's needle had closed.
    pub gun_closed_s: f64,
    /// When the nozzle was at rest (None: still moving when the run ended).
    pub at_rest_s: Option<f64>,
    /// Farthest the nozzle went from where it was at the stop (m).
    pub stopping_distance_m: f64,
    /// Where the nozzle came to rest, road frame (m).
    pub rest_x_m: f64,
    pub rest_y_m: f64,
}

/// The `safety` object of a report (present when a fault was injected or
/// the monitor stopped the arm).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SafetyReport {
    pub faults: Vec<FaultEvent>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop: Option<Stop>,
    /// Nozzle travel with the gun open and the nozzle more than the
    /// tolerance off its path, from the first fault on (m): paint outside
    /// the letters.
    pub paint_off_path_m: f64,
    /// Largest nozzle error with the gun open after the first fault (m).
    pub max_error_gun_open_m: f64,
    pub gun_latency_s: f64,
}

impl SafetyReport {
    /// A few lines for a person.
    pub fn human(&self) -> String {
        let mut s = String::new();
        for f in &self.faults {
            s += &format!("  fault {} at {}: {}\n", f.kind, f.at.describe(), f.what);
        }
        match &self.stop {
            Some(st) => {
                s += &format!(
                    "  safety stop at {}: {}; gun closed at t = {:.3} s; ",
                    st.at.describe(),
                    st.cause,
                    st.gun_closed_s
                );
                s += &match st.at_rest_s {
                    Some(t) => format!(
                        "arm at rest at t = {t:.3} s, the nozzle at most {:.1} mm from where it was stopped, at rest at road ({:.3}, {:.3}) m\n",
                        st.stopping_distance_m * 1e3,
                        st.rest_x_m,
                        st.rest_y_m
                    ),
                    None => format!(
                        "arm still moving {AFTER_STOP_S:.0} s after the stop (held by trapped oil, swinging on it), the nozzle up to {:.1} mm from where it was stopped\n",
                        st.stopping_distance_m * 1e3
                    ),
                };
            }
            None if !self.faults.is_empty() => {
                s += "  the safety monitor did not stop the arm (the fault did not take it off its path)\n"
            }
            None => {}
        }
        if !self.faults.is_empty() {
            s += &format!(
                "  paint off the path after the fault: {:.1} mm of nozzle travel with the gun open (largest error with it open {:.2} mm)\n",
                self.paint_off_path_m * 1e3,
                self.max_error_gun_open_m * 1e3
            );
        }
        s
    }
}

/// The monitor's state over a run.
#[derive(Clone)]
pub struct Monitor {
    max_step_rot: f64,
    max_step_ext: f64,
    supply_switch_pa: f64,
    prev: Option<(f64, f64)>,
    /// Gun requests of the last ticks (the needle follows the oldest).
    gun: std::collections::VecDeque<bool>,
    faults: Vec<Fault>,
    events: Vec<FaultEvent>,
    stop: Option<Stop>,
    last_nozzle: Option<[f64; 2]>,
    /// The nozzle at the stop.
    stop_nozzle: Option<[f64; 2]>,
    paint_off_path_m: f64,
    max_error_gun_open_m: f64,
    period: f64,
}

impl Monitor {
    pub fn new(model: &SimModel, faults: &[Fault]) -> Monitor {
        let t = model.control.period_s;
        let h = &model.hydraulics;
        let dp = (h.supply_pa - h.tank_pa).sqrt();
        // fastest each joint can move: the spool at the controller's
        // command limit with all of the supply across one edge (000 eq.
        // 15–16), the smaller area filling
        let rot = model.motor.valve_gain * model.motor.command_limit * dp / model.motor.area;
        let cyl = &model.cylinder;
        let ext = model.arm.k * cyl.valve_gain * cyl.command_limit * dp / (cyl.alpha * cyl.area);
        let latency = (GUN_LATENCY_S / t).round().max(1.0) as usize;
        Monitor {
            max_step_rot: ENCODER_HEADROOM * rot * t,
            max_step_ext: ENCODER_HEADROOM * ext * t,
            supply_switch_pa: SUPPLY_SWITCH_FRACTION * h.supply_pa,
            prev: None,
            gun: std::iter::repeat_n(false, latency).collect(),
            faults: faults.to_vec(),
            events: vec![],
            stop: None,
            last_nozzle: None,
            stop_nozzle: None,
            paint_off_path_m: 0.0,
            max_error_gun_open_m: 0.0,
            period: t,
        }
    }

    /// Whether the arm is stopped.
    pub fn stopped(&self) -> bool {
        self.stop.is_some()
    }

    /// When the monitor stopped the arm.
    pub fn stopped_at(&self) -> Option<f64> {
        self.stop.as_ref().map(|s| s.at.t_s)
    }

    /// Note the faults that begin at this tick (`place`: the desired nozzle).
    pub fn note_faults(&mut self, t: f64, period: f64, place: &Place) {
        for f in &self.faults {
            if f.at_s <= t && f.at_s > t - period {
                self.events.push(FaultEvent {
                    kind: f.kind.name(),
                    at: place.clone(),
                    what: f.kind.what(),
                });
            }
        }
    }

    /// Judge this tick's readings; true while the arm must be stopped.
    /// `follow_m`: the nozzle's distance from its path by the encoders.
    pub fn check(
        &mut self,
        model: &SimModel,
        m: &Measurement,
        follow_m: f64,
        place: &Place,
    ) -> bool {
        if self.stop.is_some() {
            return true;
        }
        let (th, r) = (m.base_rot_rad, m.extension_m);
        let trip = if let Some((th0, r0)) = self.prev.filter(|&(th0, r0)| {
            (th - th0).abs() > self.max_step_rot || (r - r0).abs() > self.max_step_ext
        }) {
            let (joint, d, lim) = if (th - th0).abs() > self.max_step_rot {
                ("base rotation", (th - th0).abs(), self.max_step_rot)
            } else {
                ("extension", (r - r0).abs(), self.max_step_ext)
            };
            Some((
                "encoder_jump",
                format!(
                    "the {joint} encoder moved {d:.4} in one tick, more than the joint can ({lim:.4}): an encoder fault"
                ),
            ))
        } else if m.supply_pa < self.supply_switch_pa {
            Some((
                "supply_low",
                format!(
                    "supply pressure {:.2} MPa below the low-pressure switch ({:.2} MPa)",
                    m.supply_pa / 1e6,
                    self.supply_switch_pa / 1e6
                ),
            ))
        } else if th < model.arm.theta_min_rad || th > model.arm.theta_max_rad {
            Some((
                "safety_window",
                format!("base rotation {th:.4} rad left its safety window"),
            ))
        } else if follow_m > FOLLOW_LIMIT_M {
            Some((
                "following_error",
                format!(
                    "following error puts the nozzle {:.1} mm off its path (limit {:.0} mm)",
                    follow_m * 1e3,
                    FOLLOW_LIMIT_M * 1e3
                ),
            ))
        } else {
            None
        };
        self.prev = Some((th, r));
        if let Some((kind, cause)) = trip {
            self.stop = Some(Stop {
                kind,
                cause,
                at: place.clone(),
                gun_closed_s: place.t_s + GUN_LATENCY_S,
                at_rest_s: None,
                stopping_distance_m: 0.0,
                rest_x_m: place.x_m,
                rest_y_m: place.y_m,
            });
        }
        self.stop.is_some()
    }

    /// The gun this tick: the job's `paint` unless the encoders put the
    /// nozzle over `tolerance` off the path or the arm is stopped, `latency`
    /// ticks late.
    pub fn gun_open(&mut self, paint: bool, follow_m: f64, tolerance: f64) -> bool {
        let want = paint && !self.stopped() && follow_m <= tolerance;
        self.gun.push_back(want);
        self.gun.pop_front().unwrap_or(false)
    }

    /// Record where the nozzle actually is (`nozzle`, road frame) at `t`
    /// with `error` from its path and the gun `open`.
    pub fn nozzle(&mut self, t: f64, nozzle: [f64; 2], error: f64, open: bool, tolerance: f64) {
        let step = self
            .last_nozzle
            .map_or(0.0, |p| (nozzle[0] - p[0]).hypot(nozzle[1] - p[1]));
        self.last_nozzle = Some(nozzle);
        let faulted = self.faults.iter().any(|f| f.at_s <= t);
        if faulted && open {
            self.max_error_gun_open_m = self.max_error_gun_open_m.max(error);
            if error > tolerance {
                self.paint_off_path_m += step;
            }
        }
        // after the stop: travel until the nozzle moves slower than the
        // rest speed over a tick
        if let Some(st) = self.stop.as_mut().filter(|s| s.at_rest_s.is_none()) {
            let from = *self.stop_nozzle.get_or_insert(nozzle);
            if t > st.at.t_s {
                st.stopping_distance_m = st
                    .stopping_distance_m
                    .max((nozzle[0] - from[0]).hypot(nozzle[1] - from[1]));
                st.rest_x_m = nozzle[0];
                st.rest_y_m = nozzle[1];
                if step < REST_SPEED_MPS * self.period {
                    st.at_rest_s = Some(t);
                }
            }
        }
    }

    /// Whether the run may end: stopped and at rest, or long enough after.
    pub fn done(&self, t: f64) -> bool {
        self.stop.as_ref().is_some_and(|s| {
            s.at_rest_s.is_some_and(|r| t >= r + 0.5) || t >= s.at.t_s + AFTER_STOP_S
        })
    }

    /// The report's `safety` object (None when nothing was injected or stopped).
    pub fn finish(self) -> Option<SafetyReport> {
        if self.faults.is_empty() && self.stop.is_none() {
            return None;
        }
        Some(SafetyReport {
            faults: self.events,
            stop: self.stop,
            paint_off_path_m: self.paint_off_path_m,
            max_error_gun_open_m: self.max_error_gun_open_m,
            gun_latency_s: self.gun.len() as f64 * self.period,
        })
    }
}
