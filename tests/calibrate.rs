//! `basr calibrate --stripe`: stripes made from the spray model with a known
//! profile and flow (and a little noise from a fixed seed) are recovered
//! through the binary, the calibrated robot is what compile plans for, and
//! a stripe no profile fits is refused naming the residual.

mod common;

use std::path::Path;

use basr::paint::stripe::film_across;
use basr::paint::{Depth, Profile, SprayModel};
use common::{basr, stderr};

/// The seed tip of the default robot (robots/basr.toml).
const TIP: &str = "seed-63.5";
const FAN_DEG: f64 = 63.5;
/// A flow unlike the robot's 6.67e-6, so recovering it is no accident.
const FLOW: f64 = 5.5e-6;
const HEIGHT_M: f64 = 0.2;
const SPEED_MPS: f64 = 0.15;
/// The default robot's transfer efficiency.
const EFFICIENCY: f64 = 0.9;

/// splitmix64: a fixed-seed noise source, the same bytes on every machine.
struct Noise(u64);

impl Noise {
    /// Uniform in [−1, 1).
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// The stripe CSV `profile` lays, a reading every 4 mm, with noise up to
/// `noise` of the peak film, its line 7 mm off the gauge's zero.
fn stripe_csv(profile: &str, noise: f64, seed: u64) -> String {
    let model = SprayModel::new(
        FAN_DEG.to_radians(),
        Profile::parse(profile).unwrap(),
        Depth::default(),
    )
    .unwrap();
    let offsets: Vec<f64> = (-40..=40).map(|k| 0.004 * k as f64 + 0.007).collect();
    let film: Vec<f64> = offsets
        .iter()
        .map(|&x| film_across(&model, HEIGHT_M, SPEED_MPS, FLOW, EFFICIENCY, x - 0.007))
        .collect();
    let peak = film.iter().cloned().fold(0.0, f64::max);
    let mut rng = Noise(seed);
    let mut csv = format!(
        "# a test stripe made from the spray model ({profile})\n# tip = {TIP}\n\
         # height_m = {HEIGHT_M}\n# speed_mps = {SPEED_MPS}\noffset_m,film_m\n"
    );
    for (x, f) in offsets.iter().zip(&film) {
        let f = (f + noise * peak * rng.next()).max(0.0);
        csv += &format!("{x:.4},{f:.8}\n");
    }
    csv
}

/// The tip's `flow_m3ps` and `profile` in the robot description at `path`.
fn tip_in(path: &Path, name: &str) -> (f64, String) {
    let v: toml::Value = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let tip = v["paint"]["tip"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["name"].as_str() == Some(name))
        .unwrap()
        .clone();
    (
        tip["flow_m3ps"].as_float().unwrap(),
        tip["profile"].as_str().unwrap().to_string(),
    )
}

fn calibrate(dir: &Path, profile: &str, seed: u64) -> (std::process::Output, std::path::PathBuf) {
    std::fs::write(dir.join("stripe.csv"), stripe_csv(profile, 0.01, seed)).unwrap();
    let out = dir.join("calibrated.toml");
    let run = basr(
        dir,
        &[
            "calibrate",
            "--stripe",
            "stripe.csv",
            "-o",
            "calibrated.toml",
        ],
    );
    (run, out)
}

#[test]
fn each_profile_and_its_flow_is_recovered_within_two_percent() {
    let dir = tempfile::tempdir().unwrap();
    for (seed, profile) in [(1, "uniform"), (2, "uniform-angle"), (3, "gauss:1,0,0.45")] {
        let (run, out) = calibrate(dir.path(), profile, seed);
        assert!(run.status.success(), "{profile}: {}", stderr(&run));
        let (flow, fitted) = tip_in(&out, TIP);
        assert!(
            (flow / FLOW - 1.0).abs() <= 0.02,
            "{profile}: flow {flow} for {FLOW}"
        );
        match profile.strip_prefix("gauss:1,0,") {
            Some(sigma) => {
                let want: f64 = sigma.parse().unwrap();
                let got: f64 = fitted
                    .strip_prefix("gauss:1,0,")
                    .unwrap_or_else(|| panic!("{profile} fitted as {fitted}"))
                    .parse()
                    .unwrap();
                assert!((got / want - 1.0).abs() <= 0.02, "σ {got} for {want}");
            }
            None => assert_eq!(fitted, profile),
        }
        // Every other value as it was: the other tips and the arm.
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.contains("name = \"511\""), "{text}");
        assert!(text.contains("cylinder_stroke_m = 0.457"), "{text}");
    }
}

#[test]
fn compile_plans_for_the_calibrated_profile_and_names_the_tip_when_the_film_fails() {
    let dir = tempfile::tempdir().unwrap();
    let (run, _) = calibrate(dir.path(), "uniform-angle", 2);
    assert!(run.status.success(), "{}", stderr(&run));
    let c = basr(
        dir.path(),
        &[
            "compile",
            "STOP",
            "--letter-height",
            "8ft",
            "--no-size-search",
            "--robot",
            "calibrated.toml",
            "-o",
            "stop.job.json",
        ],
    );
    let said = stderr(&c);
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("stop.job.json")).unwrap()).unwrap();
    let film = &job["summary"]["film"];
    let profile = job["robot"]["paint"]["profile"].as_str().unwrap();
    let tip = job["paint"]["tip"].as_str().unwrap();
    if c.status.code() == Some(0) {
        assert_eq!(film["verdict"], "pass", "{said}");
    } else {
        // NOT READY: the film fails for the tip as calibrated, and says so.
        assert_eq!(c.status.code(), Some(1), "{said}");
        assert_eq!(tip, TIP, "{said}");
        assert_eq!(profile, "uniform-angle");
        assert!(
            said.contains(&format!("with tip {TIP} (uniform-angle flux)")),
            "{said}"
        );
    }
}

#[test]
fn a_stripe_no_profile_fits_is_refused_naming_the_residual() {
    let dir = tempfile::tempdir().unwrap();
    // Two stripes side by side: no single fan lays that.
    let mut csv = format!(
        "# tip = {TIP}\n# height_m = {HEIGHT_M}\n# speed_mps = {SPEED_MPS}\noffset_m,film_m\n"
    );
    for k in -40..=40 {
        let x = 0.004 * k as f64;
        let f = if (0.03..0.09).contains(&x.abs()) {
            4e-4
        } else {
            0.0
        };
        csv += &format!("{x:.4},{f}\n");
    }
    std::fs::write(dir.path().join("stripe.csv"), csv).unwrap();
    let run = basr(
        dir.path(),
        &["calibrate", "--stripe", "stripe.csv", "-o", "out.toml"],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    let said = stderr(&run);
    assert!(
        said.contains("fits no profile within the residual 0.05"),
        "{said}"
    );
    assert!(said.contains("uniform-angle 0."), "{said}");
    assert!(!dir.path().join("out.toml").exists());
}

#[test]
fn a_tip_the_robot_does_not_list_is_refused_naming_the_tips() {
    let dir = tempfile::tempdir().unwrap();
    let csv = stripe_csv("uniform", 0.0, 4).replace("# tip = seed-63.5", "# tip = 999");
    std::fs::write(dir.path().join("stripe.csv"), csv).unwrap();
    let run = basr(
        dir.path(),
        &["calibrate", "--stripe", "stripe.csv", "-o", "out.toml"],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("seed-63.5, 511, 817, 509"),
        "{}",
        stderr(&run)
    );
    assert!(!dir.path().join("out.toml").exists());
}
