//! The setpoint CSV (SPEC §3): a header row of `COLUMNS`, one row per
//! control period.

use std::path::Path;

use super::{Samples, COLUMNS};

/// Write `samples` as CSV atomically to `path`; the SHA-256 of its bytes.
pub fn write(samples: &Samples, path: &Path) -> anyhow::Result<String> {
    Ok(basr_io::write_output(path, None, |w| {
        let mut out = ::csv::Writer::from_writer(w);
        out.write_record(samples.header())
            .map_err(std::io::Error::other)?;
        for i in 0..samples.len() {
            out.write_record(samples.csv_fields(i))
                .map_err(std::io::Error::other)?;
        }
        out.flush()
    })?)
}

/// Columns that hold integers (the rest are finite decimals).
const INTEGER_COLUMNS: &[&str] = &[
    "station",
    "stroke",
    "paint",
    "enc_base",
    "enc_extension",
    "enc_yaw",
    "enc_tilt",
    "enc_vertical",
];

/// Whether a text is a setpoint CSV (its header starts with SPEC §3's columns).
pub fn looks_like_csv(text: &str) -> bool {
    text.starts_with("t_s,station,stroke,paint,")
}

/// Every problem of a setpoint CSV's text (empty when sound), for `basr
/// check`: the SPEC §3 header, whole rows of numbers (integers where the
/// column counts), and `t_s` stepping by one period from 0. A CSV cut off
/// mid-row (a copy that did not finish) is reported at its last line. The
/// CSV carries no hash: to check its setpoints against the robot, check the
/// job it was written with.
pub fn check_source(text: &str, origin: &str) -> Vec<String> {
    const LIST: usize = 5;
    let mut out = vec![];
    let mut more = 0usize;
    let mut add = |out: &mut Vec<String>, m: String| {
        if out.len() < LIST {
            out.push(m);
        } else {
            more += 1;
        }
    };
    let mut lines = text.split_inclusive('\n').enumerate();
    let Some((_, header)) = lines.next() else {
        return vec![format!("{origin}: the file is empty")];
    };
    let names: Vec<&str> = header.trim_end().split(',').collect();
    if names.len() < COLUMNS.len() || names[..COLUMNS.len()] != *COLUMNS {
        return vec![format!(
            "{origin}:1: the header is not the setpoint columns of docs/csv.md ({}…): write it \
             again with `basr compile … --csv FILE`",
            COLUMNS[..4].join(",")
        )];
    }
    let t_col = 0;
    let mut times: Vec<f64> = vec![];
    for (i, line) in lines {
        let n = i + 1;
        if !line.ends_with('\n') {
            add(
                &mut out,
                format!(
                    "{origin}:{n}: the last row has no line end: the file is truncated; \
                     write it again with `basr compile … --csv FILE`"
                ),
            );
        }
        let fields: Vec<&str> = line.trim_end().split(',').collect();
        if fields.len() != names.len() {
            add(
                &mut out,
                format!(
                    "{origin}:{n}: {} fields but the header has {}: the row is cut short or \
                     was edited",
                    fields.len(),
                    names.len()
                ),
            );
            continue;
        }
        for (name, f) in names.iter().zip(&fields) {
            // The electric kinds' encoder columns are `enc_…` too.
            let ok = if INTEGER_COLUMNS.contains(name) || name.starts_with("enc_") {
                f.parse::<i64>().is_ok()
            } else {
                f.parse::<f64>().is_ok_and(f64::is_finite)
            };
            if !ok {
                add(
                    &mut out,
                    format!("{origin}:{n}: column {name} holds {f:?}, not a finite number"),
                );
            }
        }
        if let Ok(t) = fields[t_col].parse::<f64>() {
            times.push(t);
        }
    }
    if times.is_empty() && out.is_empty() {
        add(&mut out, format!("{origin}: the file has no setpoints"));
    }
    if let (Some(&t0), Some(&t1)) = (times.first(), times.get(1)) {
        let p = t1 - t0;
        if t0 != 0.0 || p.is_nan() || p <= 0.0 {
            add(
                &mut out,
                format!("{origin}:2: t_s starts at {t0}, then {t1}: it starts at 0 and grows"),
            );
        } else {
            for (k, &t) in times.iter().enumerate() {
                let want = super::tick_time(k, p);
                if (t - want).abs() > 1e-9 * want.max(1.0) {
                    add(
                        &mut out,
                        format!(
                            "{origin}:{}: t_s is {t} but a period of {p} s puts row {k} at {want}",
                            k + 2
                        ),
                    );
                }
            }
        }
    }
    if more > 0 {
        out.push(format!("{origin}: … and {more} more problem(s)"));
    }
    out
}

/// Problems of a setpoint CSV given beside its job (`basr check JOB CSV`,
/// SPEC §7): its bytes against the SHA-256 the job recorded for its CSV,
/// and when they differ, its rows against the job's samples, naming the
/// first row and column that differ. Empty when the CSV is the job's.
pub fn compare(job: &super::Job, text: &str, origin: &str, job_origin: &str) -> Vec<String> {
    let actual = basr_io::sha256_hex(text.as_bytes());
    let recorded = job.outputs.get("csv");
    if recorded.is_some_and(|b| b.sha256 == actual) {
        return vec![];
    }
    let mismatch = first_difference(job, text, origin, job_origin);
    let record = match recorded {
        Some(b) => format!(
            "{origin}: not the CSV written with {job_origin} (its SHA-256 is {actual}, the job \
             records {} for {})",
            b.sha256, b.file
        ),
        None => format!(
            "{origin}: {job_origin} records no CSV written with it (compile it again with \
             --csv to bind one)"
        ),
    };
    match (mismatch, recorded) {
        (Some(m), _) => vec![record, m],
        (None, Some(_)) => vec![record],
        (None, None) => vec![],
    }
}

/// The first line of `text` that differs from the CSV the job's samples
/// make, as `origin:line: row R, column C: …`.
fn first_difference(
    job: &super::Job,
    text: &str,
    origin: &str,
    job_origin: &str,
) -> Option<String> {
    let s = &job.samples;
    let mut lines = text.split('\n');
    let columns = s.header();
    let header = columns.join(",");
    if lines.next() != Some(header.as_str()) {
        return Some(format!("{origin}:1: the header is not the job's columns"));
    }
    for i in 0..s.len() {
        let line = i + 2;
        let want = s.csv_fields(i);
        let Some(got) = lines.next().filter(|l| !l.is_empty()) else {
            return Some(format!(
                "{origin}:{line}: the CSV ends after {i} rows but {job_origin} has {}",
                s.len()
            ));
        };
        let got: Vec<&str> = got.split(',').collect();
        for (c, name) in columns.iter().enumerate() {
            let g = got.get(c).copied().unwrap_or("(nothing)");
            if g != want[c] {
                return Some(format!(
                    "{origin}:{line}: row {i}, column {name}: the CSV has {g}, {job_origin} has {}",
                    want[c]
                ));
            }
        }
        if got.len() != columns.len() {
            return Some(format!(
                "{origin}:{line}: row {i} has {} fields, the job's rows {}",
                got.len(),
                columns.len()
            ));
        }
    }
    match lines.next() {
        Some("") | None if lines.next().is_none() => None,
        _ => Some(format!(
            "{origin}:{}: the CSV has more rows than the {} of {job_origin}",
            s.len() + 2,
            s.len()
        )),
    }
}
