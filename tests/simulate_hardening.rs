//! Issue 12 hardening: robot numbers that would hang or overflow the
//! simulator are refused by `check` (exit 1), `compile` and `simulate`
//! (exit 2), each naming the field; a correctly sealed job whose content
//! `check` refuses is refused by `simulate` and `preview` before any work.

mod common;
use common::{basr, set_key, stderr};

/// The embedded description with `key = value` in place of its first `key =` line.
fn robot_with(key: &str, value: &str) -> String {
    set_key(basr::robot::BASR_TOML, key, value) + "\n"
}

#[test]
fn robot_numbers_that_would_hang_or_overflow_the_simulator_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    for (key, value, field) in [
        ("controller_sample_s", "1e-9", "control.controller_sample_s"),
        ("cylinder_stroke_m", "1e6", "arm.cylinder_stroke_m"),
        ("bulk_modulus_pa", "1e308", "hydraulics.bulk_modulus_pa"),
        ("delay_estimate_s", "1e6", "control.delay_estimate_s"),
        ("base_inertia_kgm2", "1e300", "dynamics.base_inertia_kgm2"),
        ("valve_flow_gain", "1e3", "hydraulics.valve_flow_gain"),
        ("supply_pa", "1e12", "hydraulics.supply_pa"),
        ("base_counts_per_rev", "1", "encoders.base_counts_per_rev"),
    ] {
        let p = dir.path().join("bad.toml");
        std::fs::write(&p, robot_with(key, value)).unwrap();
        let c = basr(dir.path(), &["check", "bad.toml"]);
        assert_eq!(
            c.status.code(),
            Some(1),
            "check {key}={value}: {}",
            stderr(&c)
        );
        assert!(
            stderr(&c).contains(field),
            "check names {field}: {}",
            stderr(&c)
        );
        let c = basr(
            dir.path(),
            &["compile", "I", "--robot", "bad.toml", "-o", "i.job.json"],
        );
        assert_eq!(
            c.status.code(),
            Some(2),
            "compile {key}={value}: {}",
            stderr(&c)
        );
        assert!(
            stderr(&c).contains(field),
            "compile names {field}: {}",
            stderr(&c)
        );
        assert!(!dir.path().join("i.job.json").exists());
    }
}

#[test]
fn simulate_bounds_its_substeps() {
    let dir = tempfile::tempdir().unwrap();
    let c = basr(dir.path(), &["compile", "I", "-o", "i.job.json"]);
    assert!(c.status.success(), "{}", stderr(&c));
    for bad in ["4294967295", "0", "101"] {
        let c = basr(dir.path(), &["simulate", "i.job.json", "--substeps", bad]);
        assert_eq!(c.status.code(), Some(2), "--substeps {bad}: {}", stderr(&c));
        assert!(stderr(&c).contains("substeps"), "{}", stderr(&c));
    }
}

#[test]
fn sealed_jobs_that_check_refuses_are_refused_before_simulation() {
    let dir = tempfile::tempdir().unwrap();
    let c = basr(dir.path(), &["compile", "I", "-o", "i.job.json"]);
    assert!(c.status.success(), "{}", stderr(&c));
    let good = basr::job::Job::read(&dir.path().join("i.job.json")).unwrap();
    let k = good.samples.len() / 2;
    type Edit = fn(&mut basr::job::Job, usize);
    let cases: [(&str, Edit); 3] = [
        ("tilt_rad", |j, k| {
            j.samples.tilt_rad[k] = std::f64::consts::FRAC_PI_2
        }),
        ("t_s", |j, k| j.samples.t_s[k] = 1e9),
        ("z_m", |j, k| j.samples.z_m[k] = 1e6),
    ];
    for (column, edit) in cases {
        let mut job = good.clone();
        edit(&mut job, k);
        job.seal();
        let p = dir.path().join("bad.job.json");
        job.write(&p).unwrap();
        let c = basr(dir.path(), &["check", "bad.job.json"]);
        assert_eq!(c.status.code(), Some(1), "check {column}: {}", stderr(&c));
        for cmd in ["simulate", "preview"] {
            let c = basr(dir.path(), &[cmd, "bad.job.json", "-q"]);
            assert_eq!(c.status.code(), Some(2), "{cmd} {column}: {}", stderr(&c));
            assert!(
                stderr(&c).contains(column),
                "{cmd} names {column}: {}",
                stderr(&c)
            );
        }
        // before any work: preview wrote no film picture
        assert!(!dir.path().join("bad.svg").exists(), "{column}");
    }
}
