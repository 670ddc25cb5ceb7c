//! The preview's verdict: the film's metrics against documented thresholds
//! (docs/preview.md), so a crew reads "pass" or "fail" instead of three
//! numbers. `preview` exits 1 on a fail, as `simulate` does.

use serde::Serialize;

use super::metrics::{GlyphMetrics, Metrics};

/// Default largest coefficient of variation of the film inside the
/// letters. // assumed: issue 15's default; a 5 % spread is below what a
/// person sees on a road marking, STOP's P bowls (1.7× film lines) are not.
pub const CV_MAX: f64 = 0.05;
/// Default smallest share of letter area with at least half the target
/// film. // assumed: issue 15's default; 2 % of STOP is about one stroke
/// end left thin.
pub const COVERAGE_MIN: f64 = 0.98;
/// Default largest share of the paint that lands outside the letters.
/// // assumed: issue 15's default; the fan's soft edges alone give 2–2.5 %.
pub const OVERSPRAY_MAX: f64 = 0.03;

/// The limits a film is judged against.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Thresholds {
    pub cv_max: f64,
    pub coverage_min: f64,
    pub overspray_max: f64,
}

impl Default for Thresholds {
    fn default() -> Self {
        Thresholds {
            cv_max: CV_MAX,
            coverage_min: COVERAGE_MIN,
            overspray_max: OVERSPRAY_MAX,
        }
    }
}

/// One metric against its limit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    pub metric: &'static str,
    /// `None` when the film gave nothing to measure (counts as a fail).
    pub value: Option<f64>,
    pub limit: f64,
    /// `"max"`: the value must be at most the limit; `"min"`: at least.
    pub bound: &'static str,
    pub pass: bool,
}

impl Check {
    fn new(metric: &'static str, value: Option<f64>, limit: f64, bound: &'static str) -> Check {
        let pass = value.is_some_and(|v| match bound {
            "max" => v <= limit,
            _ => v >= limit,
        });
        Check {
            metric,
            value,
            limit,
            bound,
            pass,
        }
    }

    /// `cv 0.070 over the 0.050 limit`, `coverage 0.989 (≥ 0.980)`.
    pub fn text(&self) -> String {
        // Three decimals, or four where three would read as the limit
        // itself ("coverage 0.980 under the 0.980 minimum").
        let v = self.value.map_or("not measured".into(), |v| {
            let short = format!("{v:.3}");
            if short == format!("{:.3}", self.limit) && v != self.limit {
                format!("{v:.4}")
            } else {
                short
            }
        });
        match (self.pass, self.bound) {
            (true, "max") => format!("{} {v} (≤ {:.3})", self.metric, self.limit),
            (true, _) => format!("{} {v} (≥ {:.3})", self.metric, self.limit),
            (false, "max") => format!("{} {v} over the {:.3} limit", self.metric, self.limit),
            (false, _) => format!("{} {v} under the {:.3} minimum", self.metric, self.limit),
        }
    }
}

/// The film's verdict.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    /// `"pass"` or `"fail"`.
    pub verdict: &'static str,
    pub thresholds: Thresholds,
    pub checks: Vec<Check>,
}

impl Verdict {
    pub fn pass(&self) -> bool {
        self.verdict == "pass"
    }

    /// The failed checks in words, `; `-joined (empty on a pass).
    pub fn reasons(&self) -> String {
        let failed: Vec<String> = self
            .checks
            .iter()
            .filter(|c| !c.pass)
            .map(Check::text)
            .collect();
        failed.join("; ")
    }
}

fn checks(
    cv: Option<f64>,
    coverage: Option<f64>,
    overspray: Option<f64>,
    t: &Thresholds,
) -> Vec<Check> {
    vec![
        Check::new("cv", cv, t.cv_max, "max"),
        Check::new("coverage", coverage, t.coverage_min, "min"),
        Check::new("overspray", overspray, t.overspray_max, "max"),
    ]
}

/// Judge the whole film.
pub fn judge(m: &Metrics, t: &Thresholds) -> Verdict {
    let checks = checks(m.cv, m.coverage, m.overspray, t);
    let verdict = if checks.iter().all(|c| c.pass) {
        "pass"
    } else {
        "fail"
    };
    Verdict {
        verdict,
        thresholds: *t,
        checks,
    }
}

/// One letter's figures against the bounds the whole film is judged by
/// (the job sheet marks the letters past one).
pub fn glyph_checks(g: &GlyphMetrics, t: &Thresholds) -> Vec<Check> {
    checks(g.cv, g.coverage, g.overspray, t)
}

/// A user-given threshold that is not a share from 0 to 1.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{flag} {value}: give a share from 0 to 1 (0.05 is 5 %; defaults: --max-cv {CV_MAX}, --min-coverage {COVERAGE_MIN}, --max-overspray {OVERSPRAY_MAX})")]
pub struct ThresholdError {
    /// The option (`--max-cv`, `--min-coverage`, `--max-overspray`).
    pub flag: &'static str,
    pub value: f64,
}

/// Check that user-given thresholds make sense; the message names the flag.
pub fn validate(t: &Thresholds) -> Result<(), ThresholdError> {
    for (flag, v) in [
        ("--max-cv", t.cv_max),
        ("--min-coverage", t.coverage_min),
        ("--max-overspray", t.overspray_max),
    ] {
        if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
            return Err(ThresholdError { flag, value: v });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(cv: Option<f64>, coverage: Option<f64>, overspray: Option<f64>) -> Metrics {
        Metrics {
            target_film_m: 3.8e-4,
            mean_film_m: Some(3.8e-4),
            cv,
            coverage,
            overspray,
            u_min: None,
            u_max: None,
            edge_width_m: None,
            edge_width_p90_m: None,
            edge_points: 0,
            letter_area_m2: 1.0,
            volume_on_road_m3: 0.0,
            volume_laid_m3: 0.0,
            gun_on_s: 0.0,
            resolution_m: 0.005,
            glyphs: vec![],
            strokes: vec![],
            peaks: vec![],
        }
    }

    #[test]
    fn limits_are_inclusive_and_each_one_can_fail() {
        let t = Thresholds::default();
        assert!(judge(&metrics(Some(0.05), Some(0.98), Some(0.03)), &t).pass());
        let cv = judge(&metrics(Some(0.0501), Some(0.99), Some(0.01)), &t);
        assert!(!cv.pass());
        assert!(
            cv.reasons().starts_with("cv 0.0501 over the 0.050 limit"),
            "{}",
            cv.reasons()
        );
        assert!(!judge(&metrics(Some(0.01), Some(0.979), Some(0.01)), &t).pass());
        // A miss that rounds to the limit shows the digit that misses.
        let close = judge(&metrics(Some(0.01), Some(0.9797), Some(0.01)), &t);
        assert_eq!(close.reasons(), "coverage 0.9797 under the 0.980 minimum");
        assert!(!judge(&metrics(Some(0.01), Some(0.99), Some(0.031)), &t).pass());
    }

    #[test]
    fn nothing_measured_fails() {
        let v = judge(&metrics(None, Some(1.0), Some(0.0)), &Thresholds::default());
        assert!(!v.pass());
        assert!(v.reasons().contains("not measured"));
    }

    #[test]
    fn thresholds_outside_zero_to_one_are_refused() {
        let mut t = Thresholds::default();
        assert!(validate(&t).is_ok());
        t.cv_max = 5.0;
        assert!(validate(&t)
            .unwrap_err()
            .to_string()
            .starts_with("--max-cv 5"));
        t.cv_max = f64::NAN;
        assert!(validate(&t).is_err());
    }
}
