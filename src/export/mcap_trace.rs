//! `basr simulate JOB --mcap FILE`: the simulation as an MCAP file that
//! Foxglove and Rerun open: JSON-encoded channels, each with a JSON schema —
//! `/basr/nozzle` (desired and actual nozzle position in the road frame,
//! the gun), `/basr/joints` (desired and actual joints and actuators) and
//! `/basr/error` (nozzle error and the linkage's deflection). Log times are
//! the job's times (ns from the job's start).

use std::collections::BTreeMap;

use ::mcap as mcap_crate;

use serde_json::json;

use crate::sim::report::TraceRow;

/// (topic, schema name, JSON schema of its messages).
pub fn channels() -> Vec<(&'static str, &'static str, serde_json::Value)> {
    let num = json!({"type": "number"});
    let xy = json!({"type": "object", "properties": {"x": num, "y": num, "z": num}});
    let joints = json!({
        "type": "object",
        "properties": {
            "base_rot_rad": num, "extension_m": num, "ee_yaw_rad": num,
            "tilt_nut_m": num, "vertical_m": num
        }
    });
    vec![
        (
            "/basr/nozzle",
            "basr.NozzlePosition",
            json!({
                "title": "basr.NozzlePosition",
                "description": "nozzle tip in the road frame (m): x across the lane, y along the traffic",
                "type": "object",
                "properties": {
                    "t_s": num, "station": {"type": "integer"}, "stroke": {"type": "integer"},
                    "paint": {"type": "boolean"}, "desired": xy, "actual": xy
                }
            }),
        ),
        (
            "/basr/joints",
            "basr.Joints",
            json!({
                "title": "basr.Joints",
                "description": "desired and simulated joints and actuators (rad, m)",
                "type": "object",
                "properties": {"t_s": num, "desired": joints, "actual": joints}
            }),
        ),
        (
            "/basr/error",
            "basr.Error",
            json!({
                "title": "basr.Error",
                "description": "nozzle error from the setpoint and the linkage deflection (m)",
                "type": "object",
                "properties": {"t_s": num, "error_m": num, "deflection_m": num}
            }),
        ),
    ]
}

/// The three messages of one trace row, in [`channels`] order.
fn messages(r: &TraceRow) -> [serde_json::Value; 3] {
    [
        json!({
            "t_s": r.t_s, "station": r.station, "stroke": r.stroke, "paint": r.paint != 0,
            "desired": {"x": r.x_desired_m, "y": r.y_desired_m, "z": 0.0},
            "actual": {"x": r.x_m, "y": r.y_m, "z": 0.0}
        }),
        json!({
            "t_s": r.t_s,
            "desired": {
                "base_rot_rad": r.base_rot_desired_rad, "extension_m": r.extension_desired_m,
                "ee_yaw_rad": r.ee_yaw_desired_rad, "tilt_nut_m": r.tilt_nut_desired_m,
                "vertical_m": r.vertical_desired_m
            },
            "actual": {
                "base_rot_rad": r.base_rot_rad, "extension_m": r.extension_m,
                "ee_yaw_rad": r.ee_yaw_rad, "tilt_nut_m": r.tilt_nut_m,
                "vertical_m": r.vertical_m
            }
        }),
        json!({"t_s": r.t_s, "error_m": r.error_m, "deflection_m": r.deflection_m}),
    ]
}

/// Why the trace could not be written as MCAP.
#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    #[error("writing the MCAP trace: {0}")]
    Mcap(mcap_crate::McapError),
    #[error("writing the MCAP trace: a message as JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// The MCAP file's bytes for a simulated trace.
pub fn trace(rows: &[TraceRow], job_message: &str) -> Result<Vec<u8>, TraceError> {
    let err = TraceError::Mcap;
    let mut buf = std::io::Cursor::new(Vec::new());
    {
        let mut w = mcap_crate::WriteOptions::new()
            .compression(None)
            .profile("")
            .create(&mut buf)
            .map_err(err)?;
        let mut ids = vec![];
        for (topic, name, schema) in channels() {
            let data = serde_json::to_vec(&schema)?;
            let schema_id = w.add_schema(name, "jsonschema", &data).map_err(err)?;
            let id = w
                .add_channel(schema_id, topic, "json", &BTreeMap::new())
                .map_err(err)?;
            ids.push(id);
        }
        let mut meta = BTreeMap::new();
        meta.insert("message".to_string(), job_message.to_string());
        w.write_metadata(&mcap_crate::records::Metadata {
            name: "basr job".into(),
            metadata: meta,
        })
        .map_err(err)?;
        for (seq, r) in rows.iter().enumerate() {
            let t_ns = (r.t_s.max(0.0) * 1e9).round() as u64;
            for (id, m) in ids.iter().zip(messages(r)) {
                let data = serde_json::to_vec(&m)?;
                w.write_to_known_channel(
                    &mcap_crate::records::MessageHeader {
                        channel_id: *id,
                        sequence: seq as u32,
                        log_time: t_ns,
                        publish_time: t_ns,
                    },
                    &data,
                )
                .map_err(err)?;
            }
        }
        w.finish().map_err(err)?;
    }
    Ok(buf.into_inner())
}
