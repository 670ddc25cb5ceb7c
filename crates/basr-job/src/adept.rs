//! The Adept V+ program form of a job (001 app. A): one `move trans(…)` and
//! one `speed` line per setpoint, millimetres and degrees.
//!
//! The seed's program wrote, per knot, `move trans(x,y,(z+offset),0,180,ψ)`
//! then `speed (v*scale), rotate MMPS`. Here every control period is one
//! such pair (the seed's §4.2 recommendation: points a control period
//! apart), positions in the station's base frame (the robot's own frame, as
//! the seed's coordinates were the Adept's), the gun on digital output 1
//! (`signal 1` / `signal -1`, 001 §2.7.1: "The paint gun is controlled
//! through the digital I/O") and the tilt as the eight-bit two's-complement
//! code of 0.2° steps on outputs 9–16 (001 table 2.2).

use std::fmt::Write as _;
use std::path::Path;

use super::{Road, Samples, Station};

/// Tilt resolution of the seed's Zworld interface (001 table 2.2: 0.2°/step).
const TILT_STEP_DEG: f64 = 0.2;
/// First digital output of the tilt code (assumed: the gun uses output 1).
const TILT_FIRST_SIGNAL: u32 = 9;

/// The V+ program text of `samples` planned over `stations`.
pub fn program(message: &str, samples: &Samples, stations: &[Station], road: &Road) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "; basr job {:?}: {} setpoints; mm and degrees; base frame of each station",
        message.replace('\n', " "),
        samples.len()
    );
    let _ = writeln!(
        out,
        "; output 1 drives the gun relay; outputs {}-{} carry the tilt code (0.2 deg/step)",
        TILT_FIRST_SIGNAL,
        TILT_FIRST_SIGNAL + 7
    );
    let mut station: Option<u32> = None;
    let mut gun = 0u8;
    let mut tilt_sent: Option<u8> = None;
    for i in 0..samples.len() {
        let st = samples.station[i];
        if station != Some(st) {
            if gun == 1 {
                let _ = writeln!(out, "signal -1");
                gun = 0;
            }
            if let Some(s) = stations.get(st as usize) {
                let _ = writeln!(
                    out,
                    // Stops count from 1 as the job sheet and compile say
                    // them; the job's `station` column is the 0-based index.
                    "; stop {}: move the truck so the arm axis is at x {:.3} m, y {:.3} m, heading {:.1} deg (job station {st})",
                    st + 1,
                    s.x_m,
                    s.y_m,
                    s.heading_rad.to_degrees()
                );
            }
            station = Some(st);
        }
        let Some(s) = stations.get(st as usize) else {
            continue;
        };
        let b = s.road_to_base([samples.x_m[i], samples.y_m[i]]);
        let yaw_b = samples.yaw_rad[i] - (s.heading_rad - std::f64::consts::FRAC_PI_2);
        let tilt_code =
            ((samples.tilt_rad[i].to_degrees() / TILT_STEP_DEG).round() as i64).clamp(-127, 127);
        let _ = writeln!(
            // 001 app. A prints every field with %5.1f.
            out,
            "move trans({:5.1},{:5.1},({:5.1}+offset),0,180,{:5.1})",
            b[0] * 1e3,
            b[1] * 1e3,
            // The base frame's height: the road frame's less the height
            // of the surface under the arm's axis.
            (samples.z_m[i] - road.origin_z(s)) * 1e3,
            wrap_deg(yaw_b.to_degrees())
        );
        let _ = writeln!(
            out,
            "speed ({:5.1}*scale), rotate MMPS",
            samples.speed_mps[i] * 1e3
        );
        // The tilt code only when it changes (the Zworld holds the last one).
        let code = (tilt_code as i8) as u8;
        if tilt_sent != Some(code) {
            let _ = writeln!(out, "bits {TILT_FIRST_SIGNAL},8 = {code}");
            tilt_sent = Some(code);
        }
        let p = samples.paint[i];
        if p != gun {
            let _ = writeln!(out, "signal {}", if p == 1 { "1" } else { "-1" });
            gun = p;
        }
    }
    if gun == 1 {
        let _ = writeln!(out, "signal -1");
    }
    out
}

/// Degrees into (−180, 180].
fn wrap_deg(d: f64) -> f64 {
    let mut w = d % 360.0;
    if w > 180.0 {
        w -= 360.0;
    } else if w <= -180.0 {
        w += 360.0;
    }
    // No "-0.0" in the program text.
    if w == 0.0 {
        0.0
    } else {
        w
    }
}

/// Whether a text is an Adept program `basr compile --adept` wrote.
pub fn looks_like_program(text: &str) -> bool {
    text.starts_with("; basr job ")
}

/// Problems of an Adept program given beside its job (`basr check JOB
/// PROGRAM`): its SHA-256 against the one the job recorded, and when they
/// differ, the first line that is not the job's program. Empty when it is.
pub fn compare(job: &super::Job, text: &str, origin: &str, job_origin: &str) -> Vec<String> {
    let actual = basr_io::sha256_hex(text.as_bytes());
    let Some(recorded) = job.outputs.get("adept") else {
        return vec![format!(
            "{origin}: {job_origin} records no Adept program written with it (compile it \
             again with --adept to bind one)"
        )];
    };
    if recorded.sha256 == actual {
        return vec![];
    }
    let want = program(&job.message, &job.samples, &job.stations, &job.road);
    let mut out = vec![format!(
        "{origin}: not the Adept program written with {job_origin} (its SHA-256 is {actual}, \
         the job records {} for {})",
        recorded.sha256, recorded.file
    )];
    let mut got = text.split('\n');
    for (n, w) in want.split('\n').enumerate() {
        let g = got.next();
        if g != Some(w) {
            out.push(format!(
                "{origin}:{}: the program has {:?}, {job_origin} gives {w:?}",
                n + 1,
                g.unwrap_or("(the end of the file)")
            ));
            break;
        }
    }
    out
}

/// Write the program atomically to `path`; the SHA-256 of its bytes.
pub fn write(
    message: &str,
    samples: &Samples,
    stations: &[Station],
    road: &Road,
    path: &Path,
) -> Result<String, basr_io::WriteError> {
    let text = program(message, samples, stations, road);
    basr_io::write_output(path, None, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SampleRow;

    #[test]
    fn base_frame_mm_and_degrees() {
        let stations = [Station {
            x_m: 0.0,
            y_m: 5.0,
            heading_rad: -std::f64::consts::FRAC_PI_2,
        }];
        let mut s = Samples::default();
        // 2 m behind the truck, fan across the lane (road yaw 0 → base 180°).
        s.push(&SampleRow {
            y_m: 3.0,
            z_m: 0.2,
            speed_mps: 0.16,
            tilt_rad: (-1.0f64).to_radians(),
            paint: 1,
            ..Default::default()
        });
        let p = program("STOP", &s, &stations, &Road::default());
        assert!(
            p.contains("move trans(  0.0,2000.0,(200.0+offset),0,180,180.0)"),
            "{p}"
        );
        assert!(p.contains("speed (160.0*scale), rotate MMPS"), "{p}");
        // Stops counted from 1, as the job sheet counts them.
        assert!(
            p.contains("; stop 1: move the truck") && p.contains("(job station 0)"),
            "{p}"
        );
        // −1° = −5 steps → two's complement 251 (001 table 2.2).
        assert!(p.contains("bits 9,8 = 251"), "{p}");
        assert!(
            p.contains("signal 1\n") && p.trim_end().ends_with("signal -1"),
            "{p}"
        );
    }
}
