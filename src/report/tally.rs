//! The tip tally: a small TOML file the crew keeps with the paint that has
//! gone through the current spray tip, one entry per job, so the job sheet
//! can say how much of the tip's 113–190 L life (001 §2.4) is left. A job
//! is counted once however often its sheet is printed; a new tip starts a
//! new file (delete or rename the old one). The file names the tip it
//! counts (the jobs' `paint.tip`, when the robot lists tips), and a job
//! planned for another tip is not counted in it.
//!
//! ```toml
//! # basr tip tally: paint through the current tip
//! tip = "511"
//! [[job]]
//! sha256 = "3f1c…"
//! message = "STOP"
//! paint_l = 0.82
//! ```

use serde::{Deserialize, Serialize};

/// The file's contents.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tally {
    /// The tip whose paint this counts: the first job's tip, when its
    /// robot lists tips (absent in a tally started before tallies named
    /// their tip, which takes the next job's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tip: Option<String>,
    #[serde(default, rename = "job")]
    pub jobs: Vec<Entry>,
}

/// One job's paint through the tip.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    pub sha256: String,
    pub message: String,
    /// Litres: the unit on the paint can (the file is for people).
    pub paint_l: f64,
}

/// A tip tally that cannot be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TallyError {
    #[error(
        "{origin}: not a tip tally ({why}); it holds [[job]] tables with sha256, message and \
         paint_l (docs/report.md)"
    )]
    NotATally { origin: String, why: String },
    #[error(
        "{origin} counts the paint through tip {counts}, but this job is planned for tip \
         {job_tip}: mount tip {job_tip} for it and keep its own tally (--tip-tally \
         tip-{job_tip}.toml); one file per tip"
    )]
    OtherTip {
        origin: String,
        counts: String,
        job_tip: String,
    },
    #[error(
        "{origin} counts the paint through tip {counts}, but this job names no tip (its \
         robot description lists none): keep its own tally; one file per tip"
    )]
    NoTip { origin: String, counts: String },
    #[error(
        "{origin} holds {jobs} job(s) but names no tip (written before tallies named theirs): \
         add `tip = \"NAME\"` at its top for the tip it counts, or start a new file for \
         tip {job_tip}"
    )]
    Unnamed {
        origin: String,
        jobs: usize,
        job_tip: String,
    },
    #[error("{origin}: job {job} ({message:?}) has paint_l = {paint_l}: give the litres used, 0 or more")]
    PaintL {
        origin: String,
        job: usize,
        message: String,
        paint_l: f64,
    },
}

impl Tally {
    /// Read a tally; `origin` names it in messages.
    pub fn parse(text: &str, origin: &str) -> Result<Tally, TallyError> {
        let t: Tally = toml::from_str(text).map_err(|e| TallyError::NotATally {
            origin: origin.into(),
            why: crate::io::one_line(&e.to_string()),
        })?;
        for (k, e) in t.jobs.iter().enumerate() {
            if !(e.paint_l.is_finite() && e.paint_l >= 0.0) {
                return Err(TallyError::PaintL {
                    origin: origin.into(),
                    job: k + 1,
                    message: e.message.clone(),
                    paint_l: e.paint_l,
                });
            }
        }
        Ok(t)
    }

    /// This tally for a job planned for `tip` (`paint.tip`, `None` when
    /// its robot lists no tips): refused when it counts another tip, or
    /// names a tip and the job none. A tally without a tip takes the
    /// job's when it holds no job yet; one that holds jobs and names no
    /// tip (written before tallies named theirs) cannot be told to count
    /// the job's tip, and is refused saying how to name it.
    pub fn for_tip(mut self, tip: Option<&str>, origin: &str) -> Result<Tally, TallyError> {
        match (&self.tip, tip) {
            (Some(counts), Some(job_tip)) if counts != job_tip => Err(TallyError::OtherTip {
                origin: origin.into(),
                counts: counts.clone(),
                job_tip: job_tip.into(),
            }),
            (Some(counts), None) => Err(TallyError::NoTip {
                origin: origin.into(),
                counts: counts.clone(),
            }),
            (None, Some(job_tip)) if !self.jobs.is_empty() => Err(TallyError::Unnamed {
                origin: origin.into(),
                jobs: self.jobs.len(),
                job_tip: job_tip.into(),
            }),
            (None, Some(job_tip)) => {
                self.tip = Some(job_tip.into());
                Ok(self)
            }
            _ => Ok(self),
        }
    }

    /// Litres through the tip, the job `sha256` excluded.
    pub fn used_m3_without(&self, sha256: &str) -> f64 {
        self.jobs
            .iter()
            .filter(|e| e.sha256 != sha256)
            .map(|e| e.paint_l * 1e-3)
            .sum()
    }

    /// The tally with this job counted (once).
    pub fn with_job(mut self, sha256: &str, message: &str, paint_m3: f64) -> Tally {
        if !self.jobs.iter().any(|e| e.sha256 == sha256) {
            self.jobs.push(Entry {
                sha256: sha256.into(),
                message: message.replace('\n', " / "),
                paint_l: (paint_m3 * 1e6).round() / 1e3,
            });
        }
        self
    }

    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).unwrap_or_default();
        format!("# basr tip tally: paint through the current tip (docs/report.md)\n{body}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_is_counted_once_and_the_file_reads_back() {
        let t = Tally::default()
            .with_job("aa", "STOP", 0.82e-3)
            .with_job("aa", "STOP", 0.82e-3)
            .with_job("bb", "STOP\nAHEAD", 1.98e-3);
        assert_eq!(t.jobs.len(), 2);
        assert!((t.used_m3_without("cc") - 2.80e-3).abs() < 1e-12);
        assert!((t.used_m3_without("aa") - 1.98e-3).abs() < 1e-12);
        let back = Tally::parse(&t.to_toml(), "t.toml").unwrap();
        assert_eq!(back, t);
        assert!(Tally::parse("used = 3", "t.toml")
            .unwrap_err()
            .to_string()
            .contains("not a tip tally"));
        // a tally that holds jobs and names no tip is not given one
        let unnamed = t
            .clone()
            .for_tip(Some("511"), "t.toml")
            .unwrap_err()
            .to_string();
        assert!(unnamed.contains("names no tip") && unnamed.contains("tip = \"NAME\""));
        assert!(t.clone().for_tip(None, "t.toml").is_ok());
        // a new tally names its tip, takes a job of that tip and refuses
        // another's, and a job that names none
        let t = Tally::default().for_tip(Some("511"), "t.toml").unwrap();
        let t = t.with_job("aa", "STOP", 0.82e-3);
        assert!(t.to_toml().contains("tip = \"511\""));
        let back = Tally::parse(&t.to_toml(), "t.toml").unwrap();
        assert_eq!(back.tip.as_deref(), Some("511"));
        assert!(back.clone().for_tip(Some("511"), "t.toml").is_ok());
        assert!(back
            .clone()
            .for_tip(None, "t.toml")
            .unwrap_err()
            .to_string()
            .contains("this job names no tip"));
        let other = back.for_tip(Some("509"), "t.toml").unwrap_err().to_string();
        assert!(
            other.contains("counts the paint through tip 511")
                && other.contains("planned for tip 509"),
            "{other}"
        );
        let neg = "[[job]]\nsha256 = \"a\"\nmessage = \"X\"\npaint_l = -1\n";
        assert!(Tally::parse(neg, "t.toml")
            .unwrap_err()
            .to_string()
            .contains("paint_l = -1"));
    }
}
