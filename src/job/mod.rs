//! The job document (SPEC §3): what `compile` writes and `preview`,
//! `simulate` and `check` read. Reading verifies the format, the version,
//! the document hash and the robot hash before anything else trusts it.
//!
//! Canonical form (used for `sha256` and `robot_sha256`): the value as
//! compact JSON (`serde_json::to_vec` of a `serde_json::Value`), object keys
//! in byte order (serde_json's default sorted map), numbers in serde_json's
//! shortest round-trip form; for the document hash the top-level `sha256`
//! key is removed first.

pub mod adept;
pub mod csv;
pub mod verify;

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::robot::Robot;

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
}

/// One truck position: the arm's base frame in the road frame (SPEC §2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Station {
    pub x_m: f64,
    pub y_m: f64,
    pub heading_rad: f64,
}

/// The font a job was compiled with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FontRef {
    pub name: String,
    pub sha256: String,
}

/// A note the planner wants a person to read (e.g. a slowed stroke).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// Short machine-readable kind, e.g. `"slowed"`, `"height_clamped"`.
    pub kind: String,
    /// How much it matters to the crew: `"info"` (nothing to do),
    /// `"notice"` (paints, slightly off somewhere), `"problem"` (visibly off
    /// target). Empty in jobs written before severities existed.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub severity: String,
    /// Stroke index, or -1 when not about one stroke.
    pub stroke: i64,
    /// Time in the job where it applies (s), when known.
    pub t_s: Option<f64>,
    /// Dimensionless factor (e.g. film excess = planned / actual speed).
    pub factor: Option<f64>,
    /// One sentence for a person.
    pub message: String,
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
    /// How far the truck drives to each station from the previous one (the
    /// first from where the job starts), m.
    #[serde(default)]
    pub truck_moves_m: Vec<f64>,
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
    pub glyphs: Vec<PlacedGlyph>,
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

macro_rules! samples_struct {
    ($($name:ident : $ty:ty),* $(,)?) => {
        /// The setpoints, column-wise (SPEC §3): equal-length arrays.
        #[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
        pub struct Samples {
            $(pub $name: Vec<$ty>,)*
        }

        /// CSV column names, in SPEC order.
        pub const COLUMNS: &[&str] = &[$(stringify!($name)),*];

        impl Samples {
            /// Append one row.
            pub fn push(&mut self, r: &SampleRow) {
                $(self.$name.push(r.$name);)*
            }

            /// Row `i`, or `None` past the end.
            pub fn row(&self, i: usize) -> Option<SampleRow> {
                if i >= self.len() {
                    return None;
                }
                Some(SampleRow { $($name: self.$name[i],)* })
            }

            /// Length of every column, or the first column whose length differs.
            pub fn check_lengths(&self) -> Result<usize, String> {
                let n = self.t_s.len();
                $(if self.$name.len() != n {
                    return Err(format!(
                        "samples column {} has {} values but t_s has {}",
                        stringify!($name), self.$name.len(), n
                    ));
                })*
                Ok(n)
            }

            /// Row `i` as CSV fields, in `COLUMNS` order.
            pub fn csv_fields(&self, i: usize) -> Vec<String> {
                vec![$(self.$name[i].to_string()),*]
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

/// The whole job document.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub format: String,
    pub version: u32,
    pub message: String,
    pub font: FontRef,
    pub robot: Robot,
    pub robot_sha256: String,
    pub paint: Paint,
    pub control_period_s: f64,
    pub layout: Layout,
    pub stations: Vec<Station>,
    pub samples: Samples,
    pub summary: Summary,
    pub sha256: String,
}

pub use crate::canon::canonical_json;

impl Paint {
    /// The job's `paint` object (SPEC §3) for a robot's nozzle and paint.
    pub fn of(p: &crate::robot::Paint) -> Paint {
        Paint {
            fan_angle_rad: p.fan_angle_rad,
            flow_m3ps: p.flow_m3ps,
            transfer_efficiency: p.transfer_efficiency,
            film_m: p.film_m,
            k_m2ps: p.k_m2ps(),
        }
    }
}

fn document_hash(mut v: serde_json::Value) -> String {
    if let Some(obj) = v.as_object_mut() {
        obj.remove("sha256");
    }
    crate::io::sha256_hex(&canonical_json(&v))
}

impl Job {
    /// Fill `robot_sha256` and `sha256` from the content. Call last, after
    /// every other field is final.
    pub fn seal(&mut self) {
        self.robot_sha256 = self.robot.sha256();
        self.sha256.clear();
        let v = serde_json::to_value(&*self).expect("job serialises");
        self.sha256 = document_hash(v);
    }

    /// The document as written to disk: pretty JSON with sorted keys and a
    /// final newline. Deterministic for a given job.
    pub fn to_bytes(&self) -> Vec<u8> {
        let v = serde_json::to_value(self).expect("job serialises");
        let mut out = serde_json::to_vec_pretty(&v).expect("value serialises");
        out.push(b'\n');
        out
    }

    /// Write atomically to `path`.
    pub fn write(&self, path: &Path) -> Result<(), crate::io::WriteError> {
        crate::io::write_atomic(path, &self.to_bytes())
    }

    /// Parse and verify a job from text; `path` is used in messages only.
    pub fn from_str_verified(text: &str, path: &str) -> Result<Job, JobError> {
        let p = || path.to_string();
        if text.trim().is_empty() {
            return Err(JobError::Empty { path: p() });
        }
        let v: serde_json::Value =
            serde_json::from_str(text).map_err(|detail| JobError::Syntax { path: p(), detail })?;
        let format = v.get("format").map(|f| f.to_string()).unwrap_or_default();
        if v.get("format").and_then(|f| f.as_str()) != Some(FORMAT) {
            return Err(JobError::Format {
                path: p(),
                found: if format.is_empty() {
                    "missing".into()
                } else {
                    format
                },
            });
        }
        match v.get("version").and_then(|x| x.as_u64()) {
            Some(n) if n == VERSION as u64 => {}
            _ => {
                return Err(JobError::Version {
                    path: p(),
                    found: v
                        .get("version")
                        .map(|x| x.to_string())
                        .unwrap_or_else(|| "missing".into()),
                })
            }
        }
        let stated = v
            .get("sha256")
            .and_then(|s| s.as_str())
            .unwrap_or("")
            .to_string();
        let actual = document_hash(v.clone());
        if stated != actual {
            return Err(JobError::Hash {
                path: p(),
                stated: if stated.is_empty() {
                    "nothing".into()
                } else {
                    stated
                },
                actual,
            });
        }
        let job: Job = serde_json::from_value(v)
            .map_err(|detail| JobError::Structure { path: p(), detail })?;
        let robot_actual = job.robot.sha256();
        if robot_actual != job.robot_sha256 {
            return Err(JobError::RobotHash {
                path: p(),
                stated: job.robot_sha256.clone(),
                actual: robot_actual,
            });
        }
        job.samples
            .check_lengths()
            .map_err(|what| JobError::Invalid { path: p(), what })?;
        Ok(job)
    }

    /// Read and verify a job file.
    pub fn read(path: &Path) -> anyhow::Result<Job> {
        let text = crate::io::read_text(path)?;
        Ok(Job::from_str_verified(&text, &path.display().to_string())?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            robot: Robot::basr(),
            robot_sha256: String::new(),
            paint: Paint {
                fan_angle_rad: 1.108,
                flow_m3ps: 6.667e-6,
                transfer_efficiency: 0.9,
                film_m: 3.8e-4,
                k_m2ps: 0.0158,
            },
            control_period_s: 0.032,
            layout: Layout {
                letter_height_m: 2.44,
                lane_width_m: 3.66,
                tilt_method: "quadrilateral".into(),
                glyphs: vec![],
            },
            stations: vec![Station {
                x_m: 0.0,
                y_m: 4.0,
                heading_rad: -std::f64::consts::FRAC_PI_2,
            }],
            samples,
            summary: Summary {
                duration_s: 0.064,
                paint_time_s: 0.0,
                air_time_s: 0.064,
                strokes: 0,
                paint_volume_m3: 0.0,
                warnings: vec![],
                balance: vec![],
                lower_bound_s: 0.0,
                bound_ratio: 0.0,
                verified_max_error_m: None,
                truck_moves_m: vec![],
            },
            sha256: String::new(),
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
        let v2 = text.replacen("\"version\": 1", "\"version\": 2", 1);
        let err = Job::from_str_verified(&v2, "t").unwrap_err();
        assert!(matches!(err, JobError::Version { .. }), "{err}");
    }
}
