//! Issue 11's film acceptance, swept through the binary: every glyph A–Z,
//! 0–9 compiled alone at the default options, then `preview --json`: cv ≤
//! 0.05, coverage ≥ 0.98, overspray ≤ 0.03, and no painting sample at more
//! than 1.15 × the target film. The worst film is the larger of compile's
//! `slowed` notes (the time law's film ratio where a limit holds the nozzle
//! below the film law's speed) and a bound read from the job's own samples
//! (`sample_film_bound`), so a slow spot the notes missed still counts.
//!
//! Compile's own film check (`summary.film`, a `film` problem per failed
//! bound) must agree with the preview for every glyph.
//!
//! Glyphs that still miss a bound are listed in `MISSES` with the figures
//! measured when they were listed: they must not get worse (10 % slack on
//! the excess), and the test fails once one meets every bound, so the list
//! only shrinks.

use assert_cmd::Command;

const CV_MAX: f64 = 0.05;
const COVERAGE_MIN: f64 = 0.98;
const OVERSPRAY_MAX: f64 = 0.03;
const FILM_MAX: f64 = 1.15;

/// (glyph, cv, coverage, overspray, worst film ratio) of glyphs that still
/// miss a bound, as measured when listed. Empty since 2026-12-03, when the
/// last three left it: 8 (cv 0.072 → 0.025), 6 (0.051 → 0.039) and 9
/// (0.052 → 0.041), their loops cut by level lines through the counters
/// into bands painted upward (fonts/basr.toml; docs/font.md
/// "The loops of 6, 8 and 9"). B, P, R, 3 (matched rungs), H, N, U (the
/// preview's edge cells) and Q (its tail's cut) left it 2026-12-02.
const MISSES: &[(char, f64, f64, f64, f64)] = &[];

#[derive(Debug, Clone, Copy)]
struct Film {
    cv: f64,
    coverage: f64,
    overspray: f64,
    worst_film: f64,
    /// Compile grades a too-narrow stroke a problem (NOT READY).
    clamp_problem: bool,
    /// Compile's `summary.film` says what the preview says (figures and
    /// verdict), and it carries a `film` problem exactly when the preview
    /// fails the glyph (compile's check, docs/planner.md "Film").
    film_agrees: bool,
}

impl Film {
    fn meets_all(&self) -> bool {
        self.cv <= CV_MAX
            && self.coverage >= COVERAGE_MIN
            && self.overspray <= OVERSPRAY_MAX
            && self.worst_film <= FILM_MAX
    }

    /// No bound missed by more than 10 % beyond the recorded miss.
    fn no_worse_than(&self, m: &Film) -> bool {
        let over = |now: f64, then: f64, bound: f64| now <= bound.max(then) * 1.1;
        over(self.cv, m.cv, CV_MAX)
            && over(self.overspray, m.overspray, OVERSPRAY_MAX)
            && over(self.worst_film, m.worst_film, FILM_MAX)
            && 1.0 - self.coverage <= (1.0 - COVERAGE_MIN.min(m.coverage)) * 1.1
    }
}

fn film_of(glyph: char) -> Film {
    let dir = tempfile::tempdir().unwrap();
    let job = dir.path().join("g.json");
    let out = Command::cargo_bin("basr")
        .unwrap()
        .args(["compile", &glyph.to_string(), "--json", "-o"])
        .arg(&job)
        .output()
        .unwrap();
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // NOT READY (a problem among the warnings) exits 1 with the job written.
    let code = if summary["verdict"] == "not ready" {
        1
    } else {
        0
    };
    assert_eq!(out.status.code(), Some(code), "compile {glyph}");
    let clamp_problem = summary["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["kind"] == "height_clamped" && w["severity"] == "problem");
    let worst_film = summary["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|w| w["kind"] == "slowed")
        .filter_map(|w| w["factor"].as_f64())
        .fold(1.0, f64::max);
    let worst_film = worst_film.max(sample_film_bound(&job));
    let prev = Command::cargo_bin("basr")
        .unwrap()
        .arg("preview")
        .arg(&job)
        .args(["--json", "-o"])
        .arg(dir.path().join("g.svg"))
        .output()
        .unwrap();
    let p: serde_json::Value = serde_json::from_slice(&prev.stdout)
        .unwrap_or_else(|e| panic!("preview {glyph} --json: {e}"));
    let overspray = p["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["metric"] == "overspray")
        .and_then(|c| c["value"].as_f64())
        .expect("overspray");
    let film = &summary["summary"]["film"];
    let film_problem = summary["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["kind"] == "film" && w["severity"] == "problem");
    let film_agrees = ["cv", "coverage", "overspray", "mean_film_m", "verdict"]
        .iter()
        .all(|k| film[k] == p[k])
        && film_problem == (p["verdict"] == "fail");
    Film {
        cv: p["cv"].as_f64().unwrap(),
        coverage: p["coverage"].as_f64().unwrap(),
        overspray,
        worst_film,
        clamp_problem,
        film_agrees,
    }
}

/// A lower bound of the worst film over the job's painting samples, as a
/// share of the target: flow × efficiency / (speed × the fan's width on the
/// road at the sample's height and tilt). The fan sweeps at most its width
/// per metre, so the film is at least this. A run's first and last samples
/// are left out (their speed is a central difference across the gun's
/// switch, where the nozzle turns into the join).
fn sample_film_bound(job: &std::path::Path) -> f64 {
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(job).unwrap()).unwrap();
    let p = &v["robot"]["paint"];
    let f = |x: &serde_json::Value| x.as_f64().unwrap();
    let k = f(&p["flow_m3ps"]) * f(&p["transfer_efficiency"]) / f(&p["film_m"]);
    let half = 0.5 * f(&p["fan_angle_rad"]);
    let s = &v["samples"];
    let col = |name: &str| -> Vec<f64> { s[name].as_array().unwrap().iter().map(f).collect() };
    let (paint, stroke) = (col("paint"), col("stroke"));
    let (speed, z, tilt) = (col("speed_mps"), col("z_m"), col("tilt_rad"));
    let mut worst = 0.0f64;
    for i in 1..paint.len().saturating_sub(1) {
        let inside = (i - 1..=i + 1).all(|j| paint[j] == 1.0 && stroke[j] == stroke[i]);
        if !inside || speed[i] <= 0.0 {
            continue;
        }
        // 001 eq. 2.24: a tilted fan at height z paints as an untilted one
        // at z / factor.
        let b = tilt[i];
        let factor = (half + b).cos() * (half - b).cos() / (half.cos() * half.cos());
        let fan_w = 2.0 * z[i] / factor * half.tan();
        worst = worst.max(k / (speed[i] * fan_w));
    }
    worst
}

#[test]
fn every_glyph_alone_meets_the_film_bounds() {
    let glyphs: Vec<char> = ('A'..='Z').chain('0'..='9').collect();
    let mut failures = vec![];
    for g in glyphs {
        let f = film_of(g);
        // A stroke narrower than the fan makes the job NOT READY only where
        // the preview measures the glyph's overspray past its bound.
        if f.clamp_problem && f.overspray <= OVERSPRAY_MAX {
            failures.push(format!(
                "{g}: NOT READY for a narrow stroke, but the preview's overspray {} is within {OVERSPRAY_MAX}",
                f.overspray
            ));
        }
        if !f.film_agrees {
            failures.push(format!(
                "{g}: compile's summary.film or its film problem disagrees with preview: {f:?}"
            ));
        }
        match MISSES.iter().find(|m| m.0 == g) {
            None if !f.meets_all() => failures.push(format!("{g}: {f:?} misses a bound")),
            Some(&(_, cv, coverage, overspray, worst_film)) => {
                let then = Film {
                    cv,
                    coverage,
                    overspray,
                    worst_film,
                    clamp_problem: false,
                    film_agrees: true,
                };
                if f.meets_all() {
                    failures.push(format!("{g}: now meets every bound: drop it from MISSES"));
                } else if !f.no_worse_than(&then) {
                    failures.push(format!("{g}: {f:?} is worse than the recorded {then:?}"));
                }
            }
            None => {}
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
