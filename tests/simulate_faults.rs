//! `basr simulate --fault KIND@T`: each fault on a letter job is caught by
//! the safety monitor, the gun closes before paint goes off the path beyond
//! what the gun's latency forces, and the report says what, when and where.

use assert_cmd::Command;
use basr::sim::{self, fault::Fault, report::Verdict, safety, synthetic, SimModel};

/// A time in the middle of the first painting stroke of `job`.
fn mid_stroke(job: &basr::job::Job) -> f64 {
    let s = &job.samples;
    let first = s.paint.iter().position(|&p| p == 1).unwrap();
    let len = s.paint[first..].iter().take_while(|&&p| p == 1).count();
    s.t_s[first + len / 2]
}

fn run(job: &basr::job::Job, spec: &str) -> sim::Report {
    let model = SimModel::from_robot(&job.robot).unwrap();
    let f: Fault = spec.parse().unwrap();
    sim::simulate_faulted(job, &model, &sim::Options::default(), &[f], &mut |_, _| {})
        .unwrap()
        .report
}

#[test]
fn every_fault_mid_stroke_stops_the_arm_and_keeps_paint_on_the_path() {
    let job = synthetic::letter_job();
    let t = mid_stroke(&job);
    let period = 0.005;
    // painting speed of the letter job (synthetic.rs) over the gun's latency
    // and one control tick of detection: what the gun cannot help painting
    let forced = 0.16 * (safety::GUN_LATENCY_S + 2.0 * period);
    for (kind, caught_by) in [
        ("supply-drop", "supply_low"),
        ("encoder-glitch", "encoder_jump"),
        ("valve-stuck", "following_error"),
    ] {
        let r = run(&job, &format!("{kind}@{t}"));
        assert_eq!(r.verdict, Verdict::Fail, "{kind}");
        let s = r.safety.as_ref().expect("a safety report");
        assert_eq!(s.faults.len(), 1);
        assert_eq!(s.faults[0].kind, kind);
        assert!((s.faults[0].at.t_s - t).abs() < period, "{kind}");
        assert!(s.faults[0].at.stroke >= 0, "{kind}: mid-stroke");
        let stop = s.stop.as_ref().unwrap_or_else(|| panic!("{kind}: no stop"));
        assert_eq!(stop.kind, caught_by, "{kind}: {}", stop.cause);
        // a jammed spool is caught once the path has moved on from it (the
        // slower the base turns there, the later)
        assert!(
            stop.at.t_s >= t && stop.at.t_s < t + 5.0,
            "{kind}: {}",
            stop.at.t_s
        );
        assert!((stop.gun_closed_s - stop.at.t_s - safety::GUN_LATENCY_S).abs() < 1e-9);
        assert!(
            s.paint_off_path_m <= forced,
            "{kind}: {} m of paint off the path, more than the {forced} m the latency forces",
            s.paint_off_path_m
        );
        assert!(r.reasons.iter().any(|m| m.contains("safety monitor")));
        let text = r.human();
        assert!(text.contains(&format!("fault {kind} at t = ")), "{text}");
        assert!(text.contains("safety stop at t = "), "{text}");
    }
}

#[test]
fn a_caught_encoder_or_supply_fault_brings_the_arm_to_rest_within_centimetres() {
    let job = synthetic::letter_job();
    let t = mid_stroke(&job);
    for kind in ["supply-drop", "encoder-glitch"] {
        let r = run(&job, &format!("{kind}@{t}"));
        let stop = r.safety.unwrap().stop.unwrap();
        assert!(stop.at_rest_s.is_some(), "{kind}: still moving");
        assert!(
            stop.stopping_distance_m < 0.05,
            "{kind}: {} m",
            stop.stopping_distance_m
        );
        // the encoder glitch is caught on the tick it happens
        if kind == "encoder-glitch" {
            assert!((stop.at.t_s - t).abs() < 0.006, "{}", stop.at.t_s);
        }
    }
}

#[test]
fn without_a_fault_the_monitor_stays_silent() {
    let job = synthetic::letter_job();
    let model = SimModel::from_robot(&job.robot).unwrap();
    let r = sim::simulate(&job, &model, &sim::Options::default(), &mut |_, _| {})
        .unwrap()
        .report;
    assert!(r.safety.is_none());
    assert_eq!(r.verdict, Verdict::Pass);
}

#[test]
fn fault_flags_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let job = synthetic::letter_job();
    let t = mid_stroke(&job);
    let p = dir.path().join("letter.job.json");
    job.write(&p).unwrap();
    let basr = || {
        let mut c = Command::cargo_bin("basr").unwrap();
        c.current_dir(dir.path());
        c
    };
    let out = basr()
        .args(["simulate", "letter.job.json", "--json", "--fault"])
        .arg(format!("encoder-glitch@{t}"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["safety"]["faults"][0]["kind"], "encoder-glitch");
    assert_eq!(v["safety"]["stop"]["kind"], "encoder_jump");
    assert!(v["safety"]["stop"]["at"]["x_m"].is_number());
    for bad in [
        "valve-stuck",
        "gremlin@3",
        "supply-drop@-1",
        "supply-drop@1e9",
    ] {
        let out = basr()
            .args(["simulate", "letter.job.json", "--fault", bad])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(
            err.contains("supply-drop, encoder-glitch") || err.contains("the job ends at"),
            "{bad}: {err}"
        );
    }
    let out = basr()
        .args(["simulate", "letter.job.json", "--plants", "4", "--fault"])
        .arg(format!("valve-stuck@{t}"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--fault and --plants"));
}
