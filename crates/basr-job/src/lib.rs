//! # basr-job
//!
//! The job document and everything about its bytes. Imports `basr-io` and `basr-robot`; never the planner, the previewer or the simulator. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! The job document (SPEC §3): what `compile` writes and `preview`,
//! `simulate` and `check` read. Reading verifies the format, the version,
//! the document hash and the robot hash before anything else trusts it.
//!
//! The file's bytes are its canonical form ([`canonical`],
//! docs/job-canonical-form.md): pretty JSON, keys in byte order, one line
//! end. `sha256` is the SHA-256 of those bytes without the `sha256` and
//! `signature` members; `signature` ([`trust`]) signs them without itself.
//! `robot_sha256` hashes the robot description's compact form
//! ([`canonical_json`]).

pub mod adept;
pub mod canonical;
pub mod csv;
mod read;
pub use read::signed_bytes;
pub mod reference;
pub mod road;
mod stream;
pub mod trust;
pub mod verify;
mod warning;

pub use road::{Road, StopPlane};
pub use warning::{Owner, OwnerKind, Severity, Warning, WarningKind};

use std::collections::BTreeMap;

use std::path::Path;

use serde::{Deserialize, Serialize};

use basr_robot::AnyRobot;

/// `format` value of every job document.
pub const FORMAT: &str = "basr-job";
/// The job format version this build writes and reads.
pub const VERSION: u32 = 1;

/// Errors from reading or verifying a job.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    // The parser's detail is in the message, not a `#[source]`: main prints
    // the source chain after the message, which repeated it.
    #[error("{path}: not valid JSON ({detail}); the file is truncated or was edited by hand: compile it again")]
    Syntax {
        path: String,
        detail: serde_json::Error,
    },
    #[error("{0}")]
    NotUtf8(String),
    #[error("{path} is empty: it holds no job; compile it again")]
    Empty { path: String },
    #[error("{path}: not a basr job (format is {found}, expected \"basr-job\"); give a job written by `basr compile`")]
    Format { path: String, found: String },
    #[error("{path}: job version {found} is not known to this basr (it reads version {VERSION}); use the basr that wrote it or compile it again")]
    Version { path: String, found: String },
    #[error("{path}: integrity check failed: the document hash is {actual} but the file says {stated}; the job was edited or damaged: compile it again")]
    Hash {
        path: String,
        stated: String,
        actual: String,
    },
    #[error("{path}: integrity check failed: the embedded robot description hashes to {actual} but robot_sha256 says {stated}; compile the job again")]
    RobotHash {
        path: String,
        stated: String,
        actual: String,
    },
    #[error("{path}: job structure invalid: {detail}")]
    Structure {
        path: String,
        detail: serde_json::Error,
    },
    #[error("{path}: job invalid: {what}")]
    Invalid { path: String, what: String },
    #[error("{path}:{line}:{col}: integrity check failed: the bytes are not the job's canonical form ({what}); the job was edited or saved again by another program: compile it again (docs/job-canonical-form.md)")]
    NotCanonical {
        path: String,
        line: usize,
        col: usize,
        what: String,
    },
    #[error("{path}: the job is not signed, and only jobs signed by the trusted key {trusted} are accepted (--trust or BASR_TRUST): compile it with `--sign` and that key's secret")]
    Unsigned { path: String, trusted: String },
    #[error("{path}: the job is signed by key {found}, not by the trusted key {trusted} (--trust or BASR_TRUST): compile it with `--sign` and the trusted key's secret, or trust key {found} if it is yours")]
    ForeignKey {
        path: String,
        found: String,
        trusted: String,
    },
    #[error("{path}: integrity check failed: the signature does not match the job for key {key_id}: the job was edited after it was signed: compile it again")]
    BadSignature { path: String, key_id: String },
}

/// Columns of a job's samples that are not one value per row.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SamplesError {
    #[error("samples column {column} has {len} values but t_s has {t_s}")]
    Column {
        column: &'static str,
        len: usize,
        t_s: usize,
    },
    #[error("samples kind_columns has {columns} names (10 expected), kind_joints {joints} rows and kind_encoders {encoders} rows, but t_s has {t_s}")]
    KindColumns {
        columns: usize,
        joints: usize,
        encoders: usize,
        t_s: usize,
    },
}

/// Paint settings the job was planned for (SPEC §3).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Paint {
    pub fan_angle_rad: f64,
    pub flow_m3ps: f64,
    pub transfer_efficiency: f64,
    pub film_m: f64,
    /// `flow × efficiency / film`: speed × stroke width (001 eq. 2.6).
    pub k_m2ps: f64,
    /// The spray tip to mount (`[[paint.tip]]` name), when the robot lists
    /// tips; absent for a robot with one tip, its `paint` table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tip: Option<String>,
}

/// One truck position: the arm's base frame in the road frame (SPEC §2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Station {
    pub x_m: f64,
    pub y_m: f64,
    pub heading_rad: f64,
}

impl Station {
    /// A road-frame point in this station's base frame: the road frame
    /// turned by `−(heading_rad − π/2)` about the arm's axis (frames in
    /// docs/job.md).
    pub fn road_to_base(&self, p: [f64; 2]) -> [f64; 2] {
        let a = -(self.heading_rad - std::f64::consts::FRAC_PI_2);
        let (dx, dy) = (p[0] - self.x_m, p[1] - self.y_m);
        [dx * a.cos() - dy * a.sin(), dx * a.sin() + dy * a.cos()]
    }

    /// A base-frame point of this station in the road frame (the inverse
    /// of [`Station::road_to_base`]).
    pub fn base_to_road(&self, p: [f64; 2]) -> [f64; 2] {
        let a = self.heading_rad - std::f64::consts::FRAC_PI_2;
        [
            self.x_m + p[0] * a.cos() - p[1] * a.sin(),
            self.y_m + p[0] * a.sin() + p[1] * a.cos(),
        ]
    }
}

/// The font a job was compiled with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FontRef {
    pub name: String,
    pub sha256: String,
}

/// Totals of a job (SPEC §3).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    pub duration_s: f64,
    pub paint_time_s: f64,
    pub air_time_s: f64,
    pub strokes: usize,
    pub paint_volume_m3: f64,
    pub warnings: Vec<Warning>,
    /// The paint balance of every stroke before and after tilt (issue 4:
    /// "report the U range per stroke before and after tilt"), in stroke order.
    #[serde(default)]
    pub balance: Vec<StrokeBalance>,
    /// Paint-time bound: the painted area over k (every stroke's area at
    /// speed × width = k, 001 eq. 2.6), s; 0 in jobs written before it.
    #[serde(default)]
    pub lower_bound_s: f64,
    /// `duration_s / lower_bound_s` (issue 11 aims at ≤ 1.20).
    #[serde(default)]
    pub bound_ratio: f64,
    /// Largest nozzle error while painting in the closed-loop simulation
    /// compile verified the job with (default controller), m; `None` when
    /// not verified.
    #[serde(default)]
    pub verified_max_error_m: Option<f64>,
    /// The plants drawn around the robot description compile then ran the
    /// job on (the arm as it may be): `None` when not verified, and for the
    /// electric kinds, whose servo plant has no drawn numbers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verified: Option<VerifiedOn>,
    /// How far the truck drives to each station from the previous one (the
    /// first from where the job starts), m.
    #[serde(default)]
    pub truck_moves_m: Vec<f64>,
    /// The film the job lays, measured by compile with the preview's model
    /// and bounds (`paint::film`, docs/preview.md); what `basr preview` of
    /// the job reports at its defaults. `None` in jobs written before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film: Option<FilmSummary>,
    /// Per station, how compile timed it and the errors it was verified
    /// with: `basr fit` re-plans one stop and keeps the others at these
    /// paces without simulating them again. Empty in jobs not verified and
    /// in jobs written before it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stops: Vec<StopTiming>,
}

/// How compile timed one station (the shares of the joints' limits its
/// moves were slowed to, 1 where not) and what verified it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopTiming {
    /// The moves out of and back to stow.
    pub air_pace: f64,
    /// The painting path.
    pub path_pace: f64,
    /// The joins slowed, each `[stroke, share]` (every join into the
    /// stroke at this stop) or `[stroke, share, pass]` (the join into its
    /// pass-th pass here, 0 the first painted).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub join_paces: Vec<JoinPace>,
    /// The move out of stow flies into the first stroke without resting.
    pub fly_in: bool,
    /// The largest painting error on the robot description, m.
    pub max_error_m: f64,
    /// Each plant of the verification set's largest (`verified`), m; empty
    /// for the electric kinds.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub plants_max_error_m: Vec<f64>,
    /// A plant's failure compile kept the station with, in words.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub over: Option<String>,
}

/// A join the verification slowed: the joins into `stroke` at a stop, or
/// only the one into its `pass`-th pass there (0 the first painted), flown
/// at `share` of the joints' accelerations. In a job, `[stroke, share]` or
/// `[stroke, share, pass]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "JoinPaceArray", into = "JoinPaceArray")]
pub struct JoinPace {
    pub stroke: usize,
    pub share: f64,
    pub pass: Option<usize>,
}

impl JoinPace {
    /// Whether it slows the join into pass `pass` (0 the first painted)
    /// of `stroke`.
    pub fn slows(&self, stroke: usize, pass: usize) -> bool {
        self.stroke == stroke && self.pass.is_none_or(|p| p == pass)
    }
}

/// [`JoinPace`] as a job writes it.
#[derive(Clone, Copy, Serialize, Deserialize)]
#[serde(untagged)]
enum JoinPaceArray {
    Pass(usize, f64, usize),
    Stroke(usize, f64),
}

impl From<JoinPaceArray> for JoinPace {
    fn from(a: JoinPaceArray) -> Self {
        match a {
            JoinPaceArray::Pass(stroke, share, pass) => JoinPace {
                stroke,
                share,
                pass: Some(pass),
            },
            JoinPaceArray::Stroke(stroke, share) => JoinPace {
                stroke,
                share,
                pass: None,
            },
        }
    }
}

impl From<JoinPace> for JoinPaceArray {
    fn from(j: JoinPace) -> Self {
        match j.pass {
            Some(pass) => JoinPaceArray::Pass(j.stroke, j.share, pass),
            None => JoinPaceArray::Stroke(j.stroke, j.share),
        }
    }
}

impl Summary {
    /// The totals of a job built by hand (tests, synthetic jobs): its
    /// duration, painting time, strokes and paint volume, the air time
    /// the rest, and nothing planned (no warnings, bound, film or verdict).
    pub fn timed(
        duration_s: f64,
        paint_time_s: f64,
        strokes: usize,
        paint_volume_m3: f64,
    ) -> Summary {
        Summary {
            duration_s,
            paint_time_s,
            air_time_s: duration_s - paint_time_s,
            strokes,
            paint_volume_m3,
            warnings: vec![],
            balance: vec![],
            lower_bound_s: 0.0,
            bound_ratio: 0.0,
            verified_max_error_m: None,
            verified: None,
            truck_moves_m: vec![],
            film: None,
            stops: vec![],
        }
    }
}

/// What compile verified a job on beyond the robot description: a fixed
/// set of plants drawn around it (Monte Carlo draws as `basr simulate
/// --plants N --spread S --seed K` makes them, and corners), each plant's
/// error its largest over the job's stations.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerifiedOn {
    /// Plants in the set (draws and corners).
    pub plants: u32,
    /// The draws' spread and seed.
    pub spread: f64,
    pub seed: u64,
    /// The set's 95th percentile (nearest rank) of the plants' largest
    /// nozzle error while painting, m.
    pub p95_max_error_m: f64,
    /// The worst plant's, m. With six plants the 95th percentile (nearest
    /// rank) is the worst; both are "at least" where `over` is set (a run
    /// ends at its first error over the bound).
    pub max_error_m: f64,
    /// Where a plant of the set strayed over compile's bound (or broke a
    /// limit) and compile kept the station as it was: what and where, in
    /// words. Absent when every plant stayed within.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub over: Option<String>,
}

/// Whether a job's film meets the preview's bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilmVerdict {
    Pass,
    Fail,
}

impl FilmVerdict {
    /// The file's word: `pass` or `fail`.
    pub fn name(self) -> &'static str {
        match self {
            FilmVerdict::Pass => "pass",
            FilmVerdict::Fail => "fail",
        }
    }
}

/// The film figures of a job as `basr preview JOB` gives them at its
/// defaults (docs/preview.md: metrics and verdict).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FilmSummary {
    /// Coefficient of variation of the film inside the letters.
    pub cv: Option<f64>,
    /// Share of letter area with at least half the target film.
    pub coverage: Option<f64>,
    /// Share of the paint on the road outside the letters.
    pub overspray: Option<f64>,
    /// Mean film inside the letters (m).
    pub mean_film_m: Option<f64>,
    /// The paint's target film (m).
    pub target_film_m: f64,
    /// Raster cell the film was measured on (m).
    pub resolution_m: f64,
    /// Against the preview's default bounds (`"pass"` or `"fail"` in the file).
    pub verdict: FilmVerdict,
    /// Each failed bound in words (`cv 0.051 over the 0.050 limit`); empty
    /// on a pass.
    pub failed: Vec<String>,
}

/// Range of the seed's tile area ratio U of one stroke (001 eq. 2.7–2.8:
/// the share of a tile's paint on its left half; 0.5 is even), over every
/// tile between consecutive rungs of every pass, as a fraction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StrokeBalance {
    pub stroke: usize,
    pub char: String,
    /// Message line (0 = nearest the approaching driver).
    pub line: usize,
    /// `[min, max]` with the fan untilted (`--tilt none`).
    pub u_untilted: [f64; 2],
    /// `[min, max]` with the tilts the job paints with (`layout.tilt_method`).
    pub u_tilted: [f64; 2],
}

impl Summary {
    /// `[min, max]` of U over every stroke, untilted and tilted; `None`
    /// for a job without strokes (or one written before `balance` existed).
    pub fn u_overall(&self) -> Option<([f64; 2], [f64; 2])> {
        let mut it = self.balance.iter();
        let first = it.next()?;
        Some(it.fold((first.u_untilted, first.u_tilted), |(a, b), s| {
            (
                [a[0].min(s.u_untilted[0]), a[1].max(s.u_untilted[1])],
                [b[0].min(s.u_tilted[0]), b[1].max(s.u_tilted[1])],
            )
        }))
    }
}

/// A glyph as placed on the road: its strokes' edges in the road frame (m).
/// Lets preview measure the film against the true outlines without the font.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlacedGlyph {
    pub char: String,
    /// Message line (0 = nearest the approaching driver).
    pub line: usize,
    pub strokes: Vec<PlacedStroke>,
}

/// One stroke's two edges, sampled densely, in the road frame (m).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlacedStroke {
    pub left: Vec<[f64; 2]>,
    pub right: Vec<[f64; 2]>,
}

/// Layout and planning settings the job was compiled with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Layout {
    pub letter_height_m: f64,
    pub lane_width_m: f64,
    /// `none`, `trapezoid` or `quadrilateral`.
    pub tilt_method: String,
    #[serde(serialize_with = "stream::glyphs_unless_elided")]
    pub glyphs: Vec<PlacedGlyph>,
    /// Planning options given to compile other than its defaults, so that
    /// `basr fit` and `preview --compare` plan again with them; absent
    /// when compile ran with its defaults (and in jobs written before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub options: Option<PlanOptions>,
    /// Laid out for a road below 25 mph (`--low-speed`: letters and
    /// symbols smaller without a notice), so that `basr fit` and `preview
    /// --compare` lay it out the same; absent when not. Here rather than
    /// in `options`, whose unknown fields an older basr refuses.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub low_speed: bool,
}

/// The planning options a job was compiled with (docs/job.md).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanOptions {
    /// Largest distance between rungs (m).
    pub rung_spacing_m: f64,
    /// The gun opens this long before the first rung (s).
    pub gun_lead_s: f64,
    /// The gun closes this long before the last rung (s).
    pub gun_lag_s: f64,
    /// Margin kept from the edge of the arm's reach (m).
    pub reach_margin_m: f64,
    /// The tilt was planned gently (a smaller share of its joint's
    /// acceleration): compile's second plan of a job whose first had
    /// problems. Absent when false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub gentle_tilt: bool,
    /// The rungs' ends were held in from edges they meet obliquely
    /// (compile's plan of a job whose plans had problems otherwise).
    /// Absent when false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub hold_ends: bool,
}

/// One control period's setpoint: a row of the CSV.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SampleRow {
    pub t_s: f64,
    pub station: u32,
    pub stroke: i64,
    pub paint: u8,
    pub x_m: f64,
    pub y_m: f64,
    pub z_m: f64,
    pub yaw_rad: f64,
    pub tilt_rad: f64,
    /// Nozzle speed over the road (m/s).
    pub speed_mps: f64,
    /// Stroke width being painted (m): stroke area swept per metre of nozzle
    /// travel, the rung length where rungs stand square to the path
    /// (`plan::knots::pace`); 0 when the gun is off.
    pub width_m: f64,
    pub base_rot_rad: f64,
    pub extension_m: f64,
    pub cylinder_m: f64,
    pub vertical_m: f64,
    pub ee_yaw_rad: f64,
    pub tilt_nut_m: f64,
    pub enc_base: i64,
    pub enc_extension: i64,
    pub enc_yaw: i64,
    pub enc_tilt: i64,
    pub enc_vertical: i64,
}

impl SampleRow {
    /// This row with BASR's joint, actuator and encoder columns written
    /// from `j` by `robot`'s kinematics; the nozzle columns stay as they are.
    pub fn with_basr_joints(self, robot: &basr_robot::Robot, j: &basr_robot::Joints) -> Self {
        self.with_spec_joints(j, &robot.actuators(j), &robot.encoders(j))
    }

    /// This row with the job's joint, actuator and encoder columns written
    /// from `j`, `act` and `enc`; the nozzle columns stay as they are.
    fn with_spec_joints(
        self,
        j: &basr_robot::Joints,
        act: &basr_robot::Actuators,
        enc: &basr_robot::Encoders,
    ) -> Self {
        SampleRow {
            tilt_rad: j.tilt_rad,
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
            ..self
        }
    }
}

/// Equality bit for bit (an f64 by its bits: −0.0 is not 0.0).
trait SameBits: Copy {
    fn same(self, other: Self) -> bool;
}

impl SameBits for f64 {
    fn same(self, other: f64) -> bool {
        self.to_bits() == other.to_bits()
    }
}

macro_rules! same_bits_by_eq {
    ($($t:ty),*) => {$(
        impl SameBits for $t {
            fn same(self, other: $t) -> bool {
                self == other
            }
        }
    )*};
}
same_bits_by_eq!(i64, u32, u8);

/// A column's value is a finite number (integers always are).
trait Finite: Copy {
    fn finite(self) -> bool;
}

impl Finite for f64 {
    fn finite(self) -> bool {
        self.is_finite()
    }
}

macro_rules! finite_by_type {
    ($($t:ty),*) => {$(
        impl Finite for $t {
            fn finite(self) -> bool {
                true
            }
        }
    )*};
}
finite_by_type!(i64, u32, u8);

macro_rules! samples_struct {
    ($($name:ident : $ty:ty),* $(,)?) => {
        /// The setpoints, column-wise (SPEC §3): equal-length arrays.
        #[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
        pub struct Samples {
            $(pub $name: Vec<$ty>,)*
            /// The electric kinds' own columns (docs/robot-kinds.md): the
            /// kind's five joint names, then their five encoder names;
            /// empty for BASR, whose joints are SPEC §3's columns.
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            pub kind_columns: Vec<String>,
            /// Per row, the kind's joints in `kind_columns` order (empty for BASR).
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            pub kind_joints: Vec<[f64; 5]>,
            /// Per row, the kind's encoder counts (empty for BASR).
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            pub kind_encoders: Vec<[i64; 5]>,
        }

        /// CSV column names, in SPEC order.
        pub const COLUMNS: &[&str] = &[$(stringify!($name)),*];

        impl Samples {
            /// Append one row.
            pub fn push(&mut self, r: &SampleRow) {
                $(self.$name.push(r.$name);)*
            }

            /// The first row at which `self` and `other` differ in any
            /// column but the clock `t_s`, bit for bit (the shorter's
            /// length when one is the start of the other): the rows a
            /// re-timed station shares with its last timing. The clock is
            /// left out because a run reads row i at i × the control
            /// period, never `t_s`, and a station's clock moves whenever a
            /// station before it is re-timed: compared, every later
            /// station's run started again from its first row.
            pub fn first_difference(&self, other: &Samples) -> usize {
                let n = self.len().min(other.len());
                (0..n)
                    .find(|&i| {
                        false $(|| (stringify!($name) != "t_s"
                            && !SameBits::same(self.$name[i], other.$name[i])))*
                            || self.kind_joints.get(i).map(|q| q.map(f64::to_bits))
                                != other.kind_joints.get(i).map(|q| q.map(f64::to_bits))
                            || self.kind_encoders.get(i) != other.kind_encoders.get(i)
                    })
                    .unwrap_or(n)
            }

            /// Room for `n` more rows in each of SPEC §3's columns (a long
            /// job's columns grown by doubling held up to twice their
            /// rows; the electric kinds' own columns grow as pushed).
            pub fn reserve_exact(&mut self, n: usize) {
                $(self.$name.reserve_exact(n);)*
            }

            /// Row `i` (SPEC §3's columns), or `None` past the end.
            pub fn row(&self, i: usize) -> Option<SampleRow> {
                if i >= self.len() {
                    return None;
                }
                Some(SampleRow { $($name: self.$name[i],)* })
            }

            /// Length of every column, or the first column whose length differs.
            pub fn check_lengths(&self) -> Result<usize, SamplesError> {
                let n = self.t_s.len();
                $(if self.$name.len() != n {
                    return Err(SamplesError::Column {
                        column: stringify!($name),
                        len: self.$name.len(),
                        t_s: n,
                    });
                })*
                self.check_kind_lengths(n)?;
                Ok(n)
            }

            /// Move `other`'s rows to the end of `self` (the kind's
            /// columns named as `self`'s), leaving `other` empty.
            pub fn append(&mut self, other: &mut Samples) {
                $(self.$name.append(&mut other.$name);)*
                self.kind_joints.append(&mut other.kind_joints);
                self.kind_encoders.append(&mut other.kind_encoders);
            }

            /// Rows `r` as samples of their own, the kind's columns too
            /// (a station's rows, simulated alone).
            pub fn rows(&self, r: std::ops::Range<usize>) -> Samples {
                Samples {
                    $($name: self.$name[r.clone()].to_vec(),)*
                    kind_columns: self.kind_columns.clone(),
                    kind_joints: self.kind_joints.get(r.clone()).map(<[_]>::to_vec).unwrap_or_default(),
                    kind_encoders: self.kind_encoders.get(r).map(<[_]>::to_vec).unwrap_or_default(),
                }
            }

            /// Each column's serialised name and value, in the order of
            /// their names (the canonical form's), the kind's columns only
            /// when present (as serialising skips them empty).
            pub(crate) fn columns_sorted(&self) -> Vec<(&'static str, &dyn stream::Column)> {
                let mut columns: Vec<(&'static str, &dyn stream::Column)> =
                    vec![$((stringify!($name), &self.$name)),*];
                if !self.kind_columns.is_empty() {
                    columns.push(("kind_columns", &self.kind_columns));
                }
                if !self.kind_joints.is_empty() {
                    columns.push(("kind_joints", &self.kind_joints));
                }
                if !self.kind_encoders.is_empty() {
                    columns.push(("kind_encoders", &self.kind_encoders));
                }
                columns.sort_unstable_by_key(|c| c.0);
                columns
            }

            /// Whether every value of row `i` is a finite number (its CSV
            /// fields hold no `NaN` or `inf`), without writing them.
            pub fn row_is_finite(&self, i: usize) -> bool {
                true $(&& Finite::finite(self.$name[i]))*
                    && self.kind_joints.get(i).is_none_or(|q| q.iter().all(|v| v.is_finite()))
            }

            /// Row `i` as CSV fields, in [`Samples::header`] order.
            pub fn csv_fields(&self, i: usize) -> Vec<String> {
                let mut out = vec![$(self.$name[i].to_string()),*];
                if let (Some(q), Some(e)) = (self.kind_joints.get(i), self.kind_encoders.get(i)) {
                    out.extend(q.iter().map(f64::to_string));
                    out.extend(e.iter().map(i64::to_string));
                }
                out
            }
        }
    };
}

samples_struct! {
    t_s: f64,
    station: u32,
    stroke: i64,
    paint: u8,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    yaw_rad: f64,
    tilt_rad: f64,
    speed_mps: f64,
    width_m: f64,
    base_rot_rad: f64,
    extension_m: f64,
    cylinder_m: f64,
    vertical_m: f64,
    ee_yaw_rad: f64,
    tilt_nut_m: f64,
    enc_base: i64,
    enc_extension: i64,
    enc_yaw: i64,
    enc_tilt: i64,
    enc_vertical: i64,
}

impl Samples {
    /// CSV column names: SPEC §3's, then the kind's own (none for BASR).
    pub fn header(&self) -> Vec<&str> {
        let mut h: Vec<&str> = COLUMNS.to_vec();
        h.extend(self.kind_columns.iter().map(String::as_str));
        h
    }

    /// Append a row: the nozzle columns of `nozzle` and the joints as the
    /// robot's kind writes them ([`basr_robot::ArmKind::row_joints`]):
    /// BASR's in the job's joint, actuator and encoder columns, another
    /// kind's in its own columns after them (the job's joint columns of
    /// `nozzle` are then written as they are, 0 when left at default).
    ///
    /// ```
    /// use basr_job::{SampleRow, Samples};
    /// use basr_robot::{AnyRobot, Robot};
    /// let robot = AnyRobot::Basr(Robot::basr());
    /// let q = robot.stow();
    /// let mut samples = Samples::default();
    /// samples.kind_columns = robot.own_sample_columns();
    /// samples.push_joints(&SampleRow::default(), &robot.row_joints(&q));
    /// let row = samples.row(0).unwrap();
    /// // BASR's joints are the job's own columns.
    /// assert_eq!(row.base_rot_rad, q[0]);
    /// assert!(samples.kind_joints.is_empty());
    /// assert_eq!(samples.check_lengths(), Ok(1));
    /// ```
    pub fn push_joints(&mut self, nozzle: &SampleRow, joints: &basr_robot::RowJoints) {
        match joints {
            basr_robot::RowJoints::Spec {
                joints,
                actuators,
                encoders,
            } => self.push(&nozzle.clone().with_spec_joints(joints, actuators, encoders)),
            basr_robot::RowJoints::Own { q, encoders } => {
                self.push(nozzle);
                self.push_kind(*q, *encoders);
            }
        }
    }

    /// Append the kind's joints and encoder counts of the last row pushed.
    pub fn push_kind(&mut self, q: [f64; 5], enc: [i64; 5]) {
        self.kind_joints.push(q);
        self.kind_encoders.push(enc);
    }

    /// The kind's columns are all there or all absent, one value per row.
    fn check_kind_lengths(&self, n: usize) -> Result<(), SamplesError> {
        let (c, q, e) = (
            self.kind_columns.len(),
            self.kind_joints.len(),
            self.kind_encoders.len(),
        );
        if c == 0 && q == 0 && e == 0 {
            return Ok(());
        }
        if c != 10 || q != n || e != n {
            return Err(SamplesError::KindColumns {
                columns: c,
                joints: q,
                encoders: e,
                t_s: n,
            });
        }
        Ok(())
    }

    /// Number of rows (length of `t_s`).
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    /// True when there are no rows.
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}

/// Time of setpoint `k` at `period_s`: k × period rounded to the nanosecond,
/// so `t_s` prints as the decimal a person reads (`0.288`, not the plain
/// product's `0.28800000000000003`). Any period the compiler accepts
/// (≥ 5 ms) is a whole number of nanoseconds to well under 1e-9 relative.
pub fn tick_time(k: usize, period_s: f64) -> f64 {
    round_ns(k as f64 * period_s)
}

/// `t` rounded to the nanosecond (the job's time resolution; see [`tick_time`]).
pub fn round_ns(t: f64) -> f64 {
    (t * 1e9).round() / 1e9
}

/// A file written with the job (SPEC §7): its name when written and the
/// SHA-256 of its bytes, so `basr check JOB FILE` can tell it is the pair.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BoundFile {
    /// File name as written (without its folder).
    pub file: String,
    pub sha256: String,
}

/// The whole job document.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub format: String,
    pub version: u32,
    pub message: String,
    pub font: FontRef,
    /// The description planned for, of any kind (SPEC §8).
    pub robot: AnyRobot,
    pub robot_sha256: String,
    pub paint: Paint,
    pub control_period_s: f64,
    pub layout: Layout,
    pub stations: Vec<Station>,
    /// The road surface under the marking (docs/site.md); absent on a
    /// flat road, so flat-road jobs keep their bytes.
    #[serde(default, skip_serializing_if = "Road::is_flat")]
    pub road: Road,
    #[serde(serialize_with = "stream::samples_unless_elided")]
    pub samples: Samples,
    pub summary: Summary,
    /// Files written with this job, by kind (`csv`, `adept`).
    #[serde(default)]
    pub outputs: BTreeMap<String, BoundFile>,
    pub sha256: String,
    /// Ed25519 signature over the canonical bytes without this member.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub signature: Option<trust::Signature>,
}

pub use basr_io::canon::canonical_json;

impl Paint {
    /// The job's `paint` object (SPEC §3) for a robot's nozzle and paint.
    pub fn of(p: &basr_robot::Paint) -> Paint {
        Paint {
            fan_angle_rad: p.fan_angle_rad,
            flow_m3ps: p.flow_m3ps,
            transfer_efficiency: p.transfer_efficiency,
            film_m: p.film_m,
            k_m2ps: p.k_m2ps(),
            tip: p.mounted.clone(),
        }
    }
}

/// The `sha256` of a job document given as a JSON value: the SHA-256 of its
/// canonical bytes without the `sha256` and `signature` members.
pub fn document_sha256(mut v: serde_json::Value) -> String {
    if let Some(obj) = v.as_object_mut() {
        obj.remove("sha256");
        obj.remove("signature");
    }
    basr_io::sha256_hex(&canonical::to_canonical(&v))
}

impl Job {
    /// Fill `robot_sha256` and `sha256` from the content, and drop any
    /// signature (it signed other content). Call last, after every other
    /// field is final; then [`Job::sign`] if the job is to be signed.
    pub fn seal(&mut self) {
        self.robot_sha256 = self.robot.sha256();
        self.signature = None;
        self.sha256.clear();
        // The canonical bytes without `sha256` and `signature`
        // ([`document_sha256`]), hashed as they are made.
        self.sha256 = stream::sha256_without(self, &["sha256", "signature"]);
    }

    /// Record a file written with the job (`kind`: `csv`, `adept`) and the
    /// SHA-256 of its bytes; [`Job::seal`] again afterwards.
    pub fn bind_output(&mut self, kind: &str, path: &Path, sha256: String) {
        let file = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        self.outputs
            .insert(kind.to_string(), BoundFile { file, sha256 });
    }

    /// Sign the sealed job with `key`: the signature covers the canonical
    /// bytes without the `signature` member.
    pub fn sign(&mut self, key: &trust::SecretKey) {
        self.signature = None;
        self.signature = Some(key.sign(&self.to_bytes()));
    }

    /// The document as written to disk: its canonical bytes (pretty JSON
    /// with sorted keys and a final line end). Deterministic for a given job.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        stream::write_canonical(self, &mut out, &[]).expect("a Vec takes every byte");
        out
    }

    /// Write atomically to `path`, the canonical bytes as they are made
    /// (`stream`: a long job's never held whole).
    pub fn write(&self, path: &Path) -> Result<(), basr_io::WriteError> {
        basr_io::write_atomic_with(path, |w| stream::write_canonical(self, w, &[]))
    }

    /// Parse and verify a job from text; `path` is used in messages only.
    pub fn from_str_verified(text: &str, path: &str) -> Result<Job, JobError> {
        Job::from_bytes(text.as_bytes().to_vec(), path, None)
    }

    /// Read and verify a job file (signed or not).
    pub fn read(path: &Path) -> anyhow::Result<Job> {
        Job::read_trusted(path, None)
    }

    /// Read and verify a job file; with `trusted`, only a job that key signed.
    pub fn read_trusted(path: &Path, trusted: Option<&trust::PublicKey>) -> anyhow::Result<Job> {
        let bytes = basr_io::read_bytes(path)?;
        Ok(Job::from_bytes(
            bytes,
            &path.display().to_string(),
            trusted,
        )?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slowed join reads and writes as `[stroke, share]` (every join into
    /// the stroke, as jobs wrote it before passes were named) or `[stroke,
    /// share, pass]`, and slows just the joins it names.
    #[test]
    fn a_join_pace_is_a_stroke_s_or_one_pass_s() {
        let all: JoinPace = serde_json::from_str("[9, 0.6]").unwrap();
        let one: JoinPace = serde_json::from_str("[9, 0.36, 2]").unwrap();
        assert_eq!((all.stroke, all.share, all.pass), (9, 0.6, None));
        assert_eq!((one.stroke, one.share, one.pass), (9, 0.36, Some(2)));
        assert_eq!(serde_json::to_string(&all).unwrap(), "[9,0.6]");
        assert_eq!(serde_json::to_string(&one).unwrap(), "[9,0.36,2]");
        assert!(all.slows(9, 0) && all.slows(9, 3) && !all.slows(8, 0));
        assert!(one.slows(9, 2) && !one.slows(9, 1) && !one.slows(2, 2));
        for bad in ["[9]", "[9, 0.5, 1, 2]", "[-1, 0.5]", "[9, 0.5, -1]", "{}"] {
            assert!(serde_json::from_str::<JoinPace>(bad).is_err(), "{bad}");
        }
    }

    /// A row is finite exactly when its CSV fields hold no `NaN` or `inf`
    /// (what `basr check` refused rows for before it read the numbers):
    /// each float column, and an electric kind's own joints.
    #[test]
    fn a_row_is_finite_when_its_fields_are() {
        let written = |s: &Samples, i: usize| {
            !s.csv_fields(i)
                .iter()
                .any(|f| f == "NaN" || f.contains("inf"))
        };
        let mut s = Samples::default();
        for v in [0.0, -1.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            s.push(&SampleRow {
                x_m: v,
                ..Default::default()
            });
            s.push(&SampleRow {
                speed_mps: v,
                enc_base: -7,
                ..Default::default()
            });
        }
        for i in 0..s.len() {
            assert_eq!(s.row_is_finite(i), written(&s, i), "row {i}");
        }
        assert_eq!(
            (0..s.len()).filter(|&i| !s.row_is_finite(i)).count(),
            6,
            "NaN, inf and −inf in either column"
        );
        // an electric kind's own joint
        s.kind_columns = vec!["q".into(); 10];
        s.kind_joints = vec![[0.0; 5]; s.len()];
        s.kind_encoders = vec![[0; 5]; s.len()];
        s.kind_joints[0][3] = f64::NAN;
        assert!(!s.row_is_finite(0) && !written(&s, 0));
    }

    pub(crate) fn tiny_job() -> Job {
        let mut samples = Samples::default();
        for i in 0..3 {
            samples.push(&SampleRow {
                t_s: i as f64 * 0.032,
                x_m: 0.1 * i as f64,
                ..Default::default()
            });
        }
        let mut job = Job {
            format: FORMAT.into(),
            version: VERSION,
            message: "I".into(),
            font: FontRef {
                name: "test".into(),
                sha256: String::new(),
            },
            robot: basr_robot::Robot::basr().into(),
            robot_sha256: String::new(),
            paint: Paint {
                fan_angle_rad: 1.108,
                flow_m3ps: 6.667e-6,
                transfer_efficiency: 0.9,
                film_m: 3.8e-4,
                k_m2ps: 0.0158,
                tip: None,
            },
            control_period_s: 0.032,
            layout: Layout {
                letter_height_m: 2.44,
                lane_width_m: 3.66,
                tilt_method: "quadrilateral".into(),
                glyphs: vec![],
                options: None,
                low_speed: false,
            },
            stations: vec![Station {
                x_m: 0.0,
                y_m: 4.0,
                heading_rad: -std::f64::consts::FRAC_PI_2,
            }],
            road: Road::default(),
            samples,
            summary: Summary::timed(0.064, 0.0, 0, 0.0),
            outputs: BTreeMap::new(),
            sha256: String::new(),
            signature: None,
        };
        job.seal();
        job
    }

    #[test]
    fn sealed_job_round_trips_and_verifies() {
        let job = tiny_job();
        let text = String::from_utf8(job.to_bytes()).unwrap();
        let back = Job::from_str_verified(&text, "t").unwrap();
        assert_eq!(back, job);
        assert_eq!(back.to_bytes(), job.to_bytes());
    }

    /// The bytes written a column at a time are the value's canonical
    /// bytes: a job with samples, one with the electric kinds' columns,
    /// one with none, one with non-finite numbers (printed `null`).
    #[test]
    fn streamed_bytes_are_the_canonical_bytes() {
        let job = tiny_job();
        stream::tests::same_as_the_value(&job);
        let mut kind = job.clone();
        let n = kind.samples.len();
        kind.samples.kind_columns = (0..10).map(|i| format!("c{i}")).collect();
        kind.samples.kind_joints = vec![[0.5, -1.0, 2.0, f64::NAN, 1e-300]; n];
        kind.samples.kind_encoders = vec![[1, -2, 3, 4, i64::MAX]; n];
        kind.signature = Some(trust::Signature {
            key_id: "k".into(),
            ed25519: "s".into(),
        });
        stream::tests::same_as_the_value(&kind);
        let mut empty = job;
        empty.samples = Samples::default();
        stream::tests::same_as_the_value(&empty);
    }

    #[test]
    fn edited_job_fails_hash() {
        let job = tiny_job();
        let text = String::from_utf8(job.to_bytes()).unwrap();
        let edited = text.replacen("\"message\": \"I\"", "\"message\": \"J\"", 1);
        assert_ne!(edited, text);
        let err = Job::from_str_verified(&edited, "t").unwrap_err();
        assert!(matches!(err, JobError::Hash { .. }), "{err}");
    }

    #[test]
    fn truncated_and_unknown_version_refused() {
        let job = tiny_job();
        let text = String::from_utf8(job.to_bytes()).unwrap();
        let err = Job::from_str_verified(&text[..text.len() / 2], "t").unwrap_err();
        assert!(matches!(err, JobError::Syntax { .. }));
        // Said once: the parser's detail is not also the error's source.
        let chain = format!("{:#}", anyhow::Error::from(err));
        assert_eq!(chain.matches("EOF while parsing").count(), 1, "{chain}");
        for empty in ["", " \n"] {
            let err = Job::from_str_verified(empty, "t").unwrap_err();
            assert!(err.to_string().contains("t is empty"), "{err}");
        }
        // A duplicate key said as one, wherever it stands (a duplicate
        // `format` also trips serde's own check of the head).
        for key in ["\"format\": \"basr-job\"", "\"message\": \"I\""] {
            let twice = text.replacen(key, &format!("{key},\n  {key}"), 1);
            let err = Job::from_str_verified(&twice, "t").unwrap_err().to_string();
            assert!(err.contains("appears twice"), "{err}");
        }
        let v2 = text.replacen("\"version\": 1", "\"version\": 2", 1);
        let err = Job::from_str_verified(&v2, "t").unwrap_err();
        assert!(matches!(err, JobError::Version { .. }), "{err}");
    }
}
