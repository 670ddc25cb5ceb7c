//! `basr simulate --fault KIND@T` (issue 12): a hardware fault injected at
//! time T of the job, for the simulated controller's safety monitor
//! (`safety.rs`) to catch. Each kind is one of the ways the arm of seed 000
//! can fail on the road; the flag may be given more than once (each fault
//! happens at its own time; the first the monitor catches stops the arm).
//!
//! - `supply-drop@T`: the supply hose bursts or the truck's pump stops and
//!   the supply pressure vents towards tank.
//! - `encoder-glitch@T`: the base-rotation encoder jumps by
//!   [`ENCODER_GLITCH_COUNTS`] and stays off by them (a slipped coupling or
//!   lost counts): the controller reads a wrong angle from then on.
//! - `valve-stuck@T`: the base motor's servovalve spool jams where it is
//!   (contamination, the common servovalve failure): commands no longer
//!   move it and the arm keeps swinging at the flow it lets through.

use serde::Serialize;

/// Offset of the glitching base encoder (counts). assumed: 1 000 counts,
/// 4.1° of 000 §III's 88 000 per turn, as a coupling that slips by a few
/// degrees; any jump beyond what the arm can turn in one 5 ms tick (a few
/// tens of counts) is caught the same way.
pub const ENCODER_GLITCH_COUNTS: f64 = 1000.0;

/// Time constant of the supply venting to tank after a supply drop (s).
/// assumed: 0.1 s, a burst 3/4 in supply hose emptying the accumulator's
/// few litres through a ruptured fitting.
pub const SUPPLY_VENT_TAU_S: f64 = 0.1;

/// At most this many `--fault` flags (a bound on the option).
pub const MAX_FAULTS: usize = 8;

/// What fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FaultKind {
    SupplyDrop,
    EncoderGlitch,
    ValveStuck,
}

impl FaultKind {
    pub const ALL: [FaultKind; 3] = [
        FaultKind::SupplyDrop,
        FaultKind::EncoderGlitch,
        FaultKind::ValveStuck,
    ];

    pub fn name(self) -> &'static str {
        match self {
            FaultKind::SupplyDrop => "supply-drop",
            FaultKind::EncoderGlitch => "encoder-glitch",
            FaultKind::ValveStuck => "valve-stuck",
        }
    }

    /// What happens to the arm, for the report.
    pub fn what(self) -> &'static str {
        match self {
            FaultKind::SupplyDrop => "the supply pressure vents towards tank",
            FaultKind::EncoderGlitch => {
                "the base encoder jumps by 1000 counts (4.1°) and stays off by them"
            }
            FaultKind::ValveStuck => "the base motor's servovalve spool jams where it is",
        }
    }
}

/// One injected fault.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fault {
    pub kind: FaultKind,
    /// When it happens, seconds from the job's start.
    pub at_s: f64,
}

/// The accepted forms, for every refusal.
pub const FORMS: &str = "KIND@SECONDS with KIND one of supply-drop, encoder-glitch, \
     valve-stuck and SECONDS the time from the job's start (e.g. --fault valve-stuck@12.5)";

/// A `--fault` that cannot be used: what was given and the forms accepted.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FaultError {
    #[error("{0:?} has no @: use {FORMS}")]
    NoAt(String),
    #[error("unknown fault {0:?}: use {FORMS}")]
    UnknownKind(String),
    #[error("{text:?} is not a number of seconds: use {FORMS}")]
    NotSeconds {
        text: String,
        #[source]
        source: std::num::ParseFloatError,
    },
    #[error("the time {0} must be a finite number of seconds from 0: use {FORMS}")]
    BadTime(f64),
    #[error("{0} --fault flags: at most {MAX_FAULTS}")]
    TooMany(usize),
    #[error("--fault {}@{}: the job ends at {duration_s:.3} s; give a time within it", .fault.kind.name(), .fault.at_s)]
    AfterEnd { fault: Fault, duration_s: f64 },
}

impl std::str::FromStr for Fault {
    type Err = FaultError;
    fn from_str(s: &str) -> Result<Fault, FaultError> {
        let Some((kind, at)) = s.split_once('@') else {
            return Err(FaultError::NoAt(s.to_string()));
        };
        let kind = FaultKind::ALL
            .into_iter()
            .find(|k| k.name() == kind.trim())
            .ok_or_else(|| FaultError::UnknownKind(kind.to_string()))?;
        let at_s: f64 = at.trim().parse().map_err(|source| FaultError::NotSeconds {
            text: at.to_string(),
            source,
        })?;
        if !(at_s.is_finite() && at_s >= 0.0) {
            return Err(FaultError::BadTime(at_s));
        }
        Ok(Fault { kind, at_s })
    }
}

/// What the active faults do to the plant and the sensors at one tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Active {
    /// The supply vents to tank and the pump delivers nothing.
    pub supply_lost: bool,
    /// Added to the base encoder's reading (rad).
    pub encoder_offset_rad: f64,
    /// The motor spool is jammed.
    pub motor_spool_stuck: bool,
}

impl Active {
    /// The faults of `faults` that have happened by `t`.
    pub fn at(faults: &[Fault], t: f64, counts_per_turn: f64) -> Active {
        let mut a = Active::default();
        for f in faults.iter().filter(|f| t >= f.at_s) {
            match f.kind {
                FaultKind::SupplyDrop => a.supply_lost = true,
                FaultKind::EncoderGlitch => {
                    a.encoder_offset_rad =
                        ENCODER_GLITCH_COUNTS * std::f64::consts::TAU / counts_per_turn
                }
                FaultKind::ValveStuck => a.motor_spool_stuck = true,
            }
        }
        a
    }
}

/// Check `faults` against a job of `duration_s` (bad input: the message).
pub fn check(faults: &[Fault], duration_s: f64) -> Result<(), FaultError> {
    if faults.len() > MAX_FAULTS {
        return Err(FaultError::TooMany(faults.len()));
    }
    if let Some(f) = faults.iter().find(|f| f.at_s > duration_s) {
        return Err(FaultError::AfterEnd {
            fault: *f,
            duration_s,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fault_specs_parse_and_bad_ones_name_the_forms() {
        let f: Fault = "valve-stuck@12.5".parse().unwrap();
        assert_eq!(f.kind, FaultKind::ValveStuck);
        assert_eq!(f.at_s, 12.5);
        for k in FaultKind::ALL {
            let f: Fault = format!("{}@0", k.name()).parse().unwrap();
            assert_eq!(f.kind, k);
        }
        for bad in [
            "valve-stuck",
            "valve@1",
            "supply-drop@",
            "supply-drop@-1",
            "supply-drop@nan",
            "supply-drop@inf",
            "@3",
        ] {
            let e = bad.parse::<Fault>().unwrap_err();
            assert!(
                e.to_string().contains("supply-drop, encoder-glitch"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn faults_act_from_their_time_on() {
        let f = [
            Fault {
                kind: FaultKind::EncoderGlitch,
                at_s: 2.0,
            },
            Fault {
                kind: FaultKind::SupplyDrop,
                at_s: 5.0,
            },
        ];
        assert_eq!(Active::at(&f, 1.9, 88000.0), Active::default());
        let a = Active::at(&f, 3.0, 88000.0);
        assert!(!a.supply_lost && (a.encoder_offset_rad - 0.0714).abs() < 1e-3);
        assert!(Active::at(&f, 5.0, 88000.0).supply_lost);
        assert_eq!(
            check(&f, 4.0).unwrap_err().to_string(),
            "--fault supply-drop@5: the job ends at 4.000 s; give a time within it"
        );
        assert!(check(&f, 6.0).is_ok());
    }
}
