//! Issue 30: exports an integrator loads, each read back by an independent
//! reader: the ROS 2 trajectory YAML (serde_norway), the MCAP trace (the
//! `mcap` crate) and the URScript program for the articulated kind.

use std::path::Path;
use std::process::Output;

mod common;
use common::basr;

fn ok(dir: &Path, args: &[&str]) -> Output {
    let out = basr(dir, args);
    assert!(
        out.status.success(),
        "basr {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn f(v: &serde_norway::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v:?}"))
}

/// The ROS 2 export of STOP: one JointTrajectory per stop with its fields,
/// times as {sec, nanosec}, velocities and accelerations that are the
/// positions' rates of change, and the gun's on/off times.
#[test]
fn ros2_export_reads_back_as_joint_trajectories() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["compile", "STOP", "-q"]);
    ok(
        d,
        &[
            "export",
            "STOP.job.json",
            "--format",
            "ros2",
            "-o",
            "stop.yaml",
        ],
    );
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("STOP.job.json")).unwrap()).unwrap();
    let text = std::fs::read_to_string(d.join("stop.yaml")).unwrap();
    let doc: serde_norway::Value = serde_norway::from_str(&text).unwrap();
    let stops = doc["stops"].as_sequence().unwrap();
    let stations = job["stations"].as_array().unwrap().len();
    assert_eq!(stops.len(), stations);
    let samples = &job["samples"];
    let rows = samples["t_s"].as_array().unwrap().len();
    let mut points_total = 0;
    let mut checked = 0;
    for (k, stop) in stops.iter().enumerate() {
        assert_eq!(
            stop["stop"].as_u64(),
            Some(k as u64 + 1),
            "stops count from 1"
        );
        let traj = &stop["trajectory"];
        let names: Vec<&str> = traj["joint_names"]
            .as_sequence()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert_eq!(
            names,
            [
                "base_rot_rad",
                "extension_m",
                "vertical_m",
                "ee_yaw_rad",
                "tilt_rad"
            ]
        );
        let points = traj["points"].as_sequence().unwrap();
        let first = points_total;
        points_total += points.len();
        let t: Vec<f64> = points
            .iter()
            .map(|p| {
                let ts = &p["time_from_start"];
                ts["sec"].as_u64().unwrap() as f64 + ts["nanosec"].as_u64().unwrap() as f64 * 1e-9
            })
            .collect();
        assert_eq!(t[0], 0.0);
        // Positions are the job's own setpoints.
        for (i, p) in points.iter().enumerate().step_by(97) {
            let pos = p["positions"].as_sequence().unwrap();
            for (j, name) in names.iter().enumerate() {
                let want = samples[*name][first + i].as_f64().unwrap();
                assert!(
                    (f(&pos[j]) - want).abs() < 1e-12,
                    "{name} row {}",
                    first + i
                );
            }
        }
        // Velocities: the positions' finite differences, within 1 % of the
        // largest speed of that joint (and accelerations those of the
        // velocities), wherever the arm moves.
        for j in 0..5 {
            let q: Vec<f64> = points.iter().map(|p| f(&p["positions"][j])).collect();
            let v: Vec<f64> = points.iter().map(|p| f(&p["velocities"][j])).collect();
            let a: Vec<f64> = points.iter().map(|p| f(&p["accelerations"][j])).collect();
            let vmax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let amax = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for i in 1..q.len() - 1 {
                let fd = (q[i + 1] - q[i - 1]) / (t[i + 1] - t[i - 1]);
                assert!(
                    (v[i] - fd).abs() <= 0.01 * vmax.max(1e-9),
                    "stop {} joint {j} point {i}: velocity {} vs finite difference {fd}",
                    k + 1,
                    v[i]
                );
                let fa = (v[i + 1] - v[i - 1]) / (t[i + 1] - t[i - 1]);
                assert!((a[i] - fa).abs() <= 0.01 * amax.max(1e-9));
                checked += 1;
            }
            assert!(vmax > 0.0, "joint {j} never moves at stop {}", k + 1);
        }
        // The gun: on/off pairs inside the stop's time, as the job's paint
        // column switches.
        let gun = stop["gun"].as_sequence().unwrap();
        assert!(!gun.is_empty());
        for g in gun {
            let (on, off) = (f(&g["on_s"]), f(&g["off_s"]));
            assert!(
                0.0 <= on && on < off && off <= *t.last().unwrap(),
                "{on} {off}"
            );
        }
    }
    assert_eq!(points_total, rows, "every setpoint is a point of one stop");
    assert!(checked > 1000);
    let switches_on = samples["paint"]
        .as_array()
        .unwrap()
        .windows(2)
        .filter(|w| w[0] == 0 && w[1] == 1)
        .count();
    let gun_total: usize = stops
        .iter()
        .map(|s| s["gun"].as_sequence().unwrap().len())
        .sum();
    assert_eq!(gun_total, switches_on);
}

#[test]
fn export_refuses_what_it_cannot_write() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["compile", "GO", "-q"]);
    let out = basr(d, &["export", "GO.job.json", "--format", "urscript"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("articulated") && err.contains("--format ros2"),
        "{err}"
    );
    assert!(!d.join("GO.urscript.script").exists());
    let out = basr(
        d,
        &["export", "GO.job.json", "--format", "ros2", "-o", "go.txt"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(!d.join("go.txt").exists());
    ok(d, &["export", "GO.job.json", "--format", "ros2", "-q"]);
    assert!(d.join("GO.ros2.yaml").exists());
}

/// The articulated kind's URScript: read back line by line, one `servoj`
/// per setpoint with the job's joints (UR wrist 2 at 0), the gun on
/// digital output 0 switched as the job's paint column, one program per
/// stop numbered from 1.
#[test]
fn urscript_reads_back_as_the_jobs_setpoints() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/articulated.toml");
    // The articulated arm's film may make GO NOT READY (exit 1): the job
    // is written all the same and its setpoints are what is posted.
    let out = basr(
        d,
        &[
            "compile",
            "GO",
            "--robot",
            robot.to_str().unwrap(),
            "-o",
            "arm.job.json",
            "-q",
            "--no-size-search",
        ],
    );
    let compiled = out.status.code();
    assert!(matches!(compiled, Some(0 | 1)) && d.join("arm.job.json").exists());
    // A NOT READY job is exported for inspection, said so on its first
    // line, and exits 1 as compile did.
    let out = basr(d, &["export", "arm.job.json", "--format", "urscript"]);
    assert_eq!(
        out.status.code(),
        compiled,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("arm.job.json")).unwrap()).unwrap();
    let first = std::fs::read_to_string(d.join("arm.urscript.script")).unwrap();
    assert_eq!(
        first.starts_with("# NOT READY:"),
        compiled == Some(1),
        "{}",
        first.lines().next().unwrap_or("")
    );
    let q = job["samples"]["kind_joints"].as_array().unwrap();
    let paint: Vec<u64> = job["samples"]["paint"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_u64().unwrap())
        .collect();
    let text = std::fs::read_to_string(d.join("arm.urscript.script")).unwrap();
    let mut servo = vec![];
    let mut gun_on = 0;
    let mut defs = vec![];
    for line in text.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("servoj([") {
            let list = rest.split(']').next().unwrap();
            let v: Vec<f64> = list.split(',').map(|x| x.trim().parse().unwrap()).collect();
            assert_eq!(v.len(), 6, "{line}");
            servo.push(v);
        } else if line == "set_standard_digital_out(0, True)" {
            gun_on += 1;
        } else if let Some(name) = line.strip_prefix("def ") {
            defs.push(name.to_string());
        }
    }
    assert_eq!(servo.len(), q.len());
    for (i, (got, want)) in servo.iter().zip(q).enumerate() {
        let want: Vec<f64> = want
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let ur = [want[0], want[1], want[2], want[3], 0.0, want[4]];
        for j in 0..6 {
            assert!(
                (got[j] - ur[j]).abs() <= 5e-7,
                "row {i} joint {j}: {} vs {}",
                got[j],
                ur[j]
            );
        }
    }
    let switches = paint.windows(2).filter(|w| w[0] == 0 && w[1] == 1).count()
        + usize::from(paint.first() == Some(&1));
    assert_eq!(gun_on, switches);
    let stations = job["stations"].as_array().unwrap().len();
    assert_eq!(defs.len(), stations + 1, "{defs:?}");
    assert_eq!(defs[0], "basr_stop_1():");
    assert_eq!(defs.last().unwrap(), "basr_job():");
}

/// `simulate --mcap`: the mcap crate reads the file back, with its three
/// JSON channels and their JSON schemas, one message per channel per
/// setpoint.
#[test]
fn simulate_writes_an_mcap_trace_the_mcap_crate_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["compile", "GO", "-q"]);
    ok(d, &["simulate", "GO.job.json", "--mcap", "go.mcap", "-q"]);
    let bytes = std::fs::read(d.join("go.mcap")).unwrap();
    let summary = mcap::Summary::read(&bytes)
        .unwrap()
        .expect("a summary section");
    let mut topics: Vec<(String, String, String)> = summary
        .channels
        .values()
        .map(|c| {
            let schema = c.schema.as_ref().expect("every channel has a schema");
            assert_eq!(schema.encoding, "jsonschema");
            let s: serde_json::Value = serde_json::from_slice(&schema.data).unwrap();
            assert_eq!(s["type"], "object", "{s}");
            (
                c.topic.clone(),
                c.message_encoding.clone(),
                schema.name.clone(),
            )
        })
        .collect();
    topics.sort();
    assert_eq!(
        topics,
        [
            ("/basr/error".into(), "json".into(), "basr.Error".into()),
            ("/basr/joints".into(), "json".into(), "basr.Joints".into()),
            (
                "/basr/nozzle".into(),
                "json".into(),
                "basr.NozzlePosition".into()
            ),
        ]
    );
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("GO.job.json")).unwrap()).unwrap();
    let rows = job["samples"]["t_s"].as_array().unwrap().len();
    let mut per_topic = std::collections::BTreeMap::<String, usize>::new();
    let mut last_error = 0.0;
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        *per_topic.entry(m.channel.topic.clone()).or_default() += 1;
        let v: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
        if m.channel.topic == "/basr/error" {
            last_error = v["error_m"].as_f64().unwrap();
        }
        if m.channel.topic == "/basr/nozzle" {
            assert!(v["desired"]["x"].is_number() && v["actual"]["y"].is_number());
        }
    }
    assert!(per_topic
        .values()
        .all(|&n| n > 0 && n == per_topic["/basr/error"]));
    assert!(
        per_topic["/basr/error"] + 2 >= rows,
        "{per_topic:?} for {rows} rows"
    );
    assert!(last_error.is_finite());
}
