//! `basr compile`: message or marking file → job file, and optionally the
//! setpoint CSV and the Adept V+ program.

use std::path::{Path, PathBuf};

use basr::layout::Overrides;
use basr::plan::compile::{compile_job, CompileRequest, Source, Tilt};

use super::{Global, Outcome};

/// Tilt method for the fan nozzle (001 §2.5).
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum TiltArg {
    /// Nozzle held upright.
    None,
    /// Trapezoid-bisector method (001 eq. 2.11–2.12).
    Trapezoid,
    /// Quadrilateral-bisector method (001 eq. 2.13–2.20).
    Quadrilateral,
}

/// Compile a roadway message into a job of timed actuator setpoints.
///
/// Words stack one per line, the first nearest the approaching driver; each
/// line is centred in the lane. The job (JSON) holds the robot description,
/// the stations where the truck stops, and one setpoint per control period
/// for every actuator. Without -o it is written as <MESSAGE>.job.json
/// (spaces → _) in the current folder. Same input, same bytes.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr compile STOP                               # writes STOP.job.json
  basr compile \"STOP AHEAD\" --csv sa.csv          # also the setpoint CSV
  basr compile --marking markings/school_xing.toml --adept school.v2
  basr compile BUS --letter-height 1.83 --tilt none --json
  basr compile STOP --sign crew.key --csv stop.csv # signed; stop.csv bound to it")]
pub struct Args {
    /// The message: letters A–Z (lower case is read as upper case), digits
    /// and spaces; each word is painted as one line.
    // Taken as raw bytes and checked in `run`, so a missing message or one
    // that is not UTF-8 gets our message naming --marking and the letters.
    #[arg(conflicts_with = "marking", value_parser = clap::value_parser!(std::ffi::OsString))]
    pub message: Option<std::ffi::OsString>,
    /// A marking file (TOML, see markings/) giving the lines and layout.
    #[arg(long, value_name = "FILE")]
    pub marking: Option<PathBuf>,
    /// Job file to write [default: <MESSAGE>.job.json].
    #[arg(short, long, value_name = "JOB")]
    pub output: Option<PathBuf>,
    /// Also write the setpoints as CSV (SPEC §3 columns).
    #[arg(long, value_name = "CSV")]
    pub csv: Option<PathBuf>,
    /// Also write an Adept V+ program (move trans / speed lines, mm and degrees).
    #[arg(long, value_name = "FILE")]
    pub adept: Option<PathBuf>,
    /// Font name or file [default: the embedded font].
    #[arg(long, value_name = "F")]
    pub font: Option<String>,
    /// Robot description file [default: the embedded BASR].
    #[arg(long, value_name = "F")]
    pub robot: Option<PathBuf>,
    /// Nozzle tilt method.
    #[arg(long, value_enum, default_value_t = TiltArg::Quadrilateral)]
    pub tilt: TiltArg,
    /// Letter height in metres, 0.3–10 [default: 2.44, or the marking file's].
    #[arg(allow_hyphen_values = true, long, value_name = "M")]
    pub letter_height: Option<f64>,
    /// Lane width in metres, at most 30 [default: 3.66, or the marking file's].
    #[arg(allow_hyphen_values = true, long, value_name = "M")]
    pub lane_width: Option<f64>,
    /// Clear space between lines in metres, at least 4× the letter height
    /// [default: 4× the letter height, or the marking file's].
    #[arg(allow_hyphen_values = true, long, value_name = "M")]
    pub line_gap: Option<f64>,
    /// Largest distance between rungs along a stroke, in millimetres (1–100).
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "MM",
        default_value_t = 20.0
    )]
    pub rung_spacing_mm: f64,
    /// Setpoint period in seconds, 0.005–0.1 (the controller samples at 0.005 s).
    #[arg(allow_hyphen_values = true, long, value_name = "S", default_value_t = basr::plan::compile::DEFAULT_PERIOD_S)]
    pub period_s: f64,
    /// Switch the gun on this many seconds before a stroke starts (0–1).
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "S",
        default_value_t = 0.0
    )]
    pub gun_lead_s: f64,
    /// Switch the gun off this many seconds before a stroke ends (0–1).
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "S",
        default_value_t = 0.0
    )]
    pub gun_lag_s: f64,
    /// Sign the job with this secret key (written by `basr keygen -o NAME`),
    /// so readers under `--trust NAME.pub` accept it.
    #[arg(long, value_name = "NAME")]
    pub sign: Option<PathBuf>,
    /// Print the summary as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

/// Finest rung spacing, mm. Assumed: 1/20 of the default and far below the
/// fan's footprint on the road (tens of mm); finer only multiplies the work
/// (1e-6 mm asked for a 39 GB allocation).
const MIN_RUNG_SPACING_MM: f64 = 1.0;
/// Finest setpoint period, s: the controller samples every 5 ms (000 §III),
/// so finer setpoints are never read and only multiply the job's size.
const MIN_PERIOD_S: f64 = 0.005;

/// File name stem for a message: spaces → `_`, and nothing that would leave
/// the current folder.
fn stem_of(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join("_")
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Refuse outputs that name one file twice, or an input: each would be
/// written over the other (the job over `--csv`, or over the marking file).
fn refuse_clashing_paths(args: &Args, out: &Path) -> anyhow::Result<()> {
    let mut outputs: Vec<(&str, &Path)> = vec![("the job (-o)", out)];
    if let Some(p) = &args.csv {
        outputs.push(("--csv", p));
    }
    if let Some(p) = &args.adept {
        outputs.push(("--adept", p));
    }
    let mut inputs: Vec<(&str, &Path)> = vec![];
    if let Some(p) = &args.marking {
        inputs.push(("the marking file (--marking)", p));
    }
    if let Some(p) = &args.robot {
        inputs.push(("the robot file (--robot)", p));
    }
    if let Some(f) = &args.font {
        inputs.push(("the font file (--font)", Path::new(f)));
    }
    super::refuse_clashes(&outputs, &inputs)
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    // Non-finite and non-positive values are reported by the planner.
    let too_fine = |v: f64, min: f64| v.is_finite() && v > 0.0 && v < min;
    anyhow::ensure!(
        !too_fine(args.rung_spacing_mm, MIN_RUNG_SPACING_MM),
        "--rung-spacing-mm {} is finer than the {MIN_RUNG_SPACING_MM} mm minimum: \
         finer rungs only multiply the work (default 20)",
        args.rung_spacing_mm
    );
    anyhow::ensure!(
        !too_fine(args.period_s, MIN_PERIOD_S),
        "--period-s {} is below the controller's {MIN_PERIOD_S} s sampling period, \
         which would never read the extra setpoints: give at least {MIN_PERIOD_S}",
        args.period_s
    );
    let source = match (&args.message, &args.marking) {
        (Some(m), None) => Source::Message(
            m.to_str()
                .ok_or_else(|| {
                    anyhow::anyhow!(
                        "the message {:?} is not UTF-8 text: messages take the letters A–Z, \
                         the digits 0–9 and spaces",
                        m.to_string_lossy()
                    )
                })?
                .to_string(),
        ),
        (None, Some(path)) => Source::Marking {
            text: basr::io::read_text(path)?,
            origin: path.display().to_string(),
        },
        _ => anyhow::bail!(
            "give the message to paint or a marking file: `basr compile STOP` or \
             `basr compile --marking markings/stop.toml`"
        ),
    };
    let req = CompileRequest {
        source,
        overrides: Overrides {
            letter_height_m: args.letter_height,
            lane_width_m: args.lane_width,
            line_gap_m: args.line_gap,
        },
        font: args.font.clone(),
        robot: args.robot.clone(),
        tilt: match args.tilt {
            TiltArg::None => Tilt::None,
            TiltArg::Trapezoid => Tilt::Trapezoid,
            TiltArg::Quadrilateral => Tilt::Quadrilateral,
        },
        rung_spacing_m: args.rung_spacing_mm * 1e-3,
        period_s: args.period_s,
        gun_lead_s: args.gun_lead_s,
        gun_lag_s: args.gun_lag_s,
        ..CompileRequest::message("")
    };
    // Every output path and the key are checked before the work, which
    // can take minutes.
    let key = args
        .sign
        .as_deref()
        .map(basr::job::trust::SecretKey::load)
        .transpose()?;
    for p in [&args.output, &args.csv, &args.adept].into_iter().flatten() {
        basr::io::check_writable(p)?;
    }
    let mut job = compile_job(&req)?;
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.job.json", stem_of(&job.message))));
    refuse_clashing_paths(&args, &out)?;
    basr::io::check_writable(&out)?;
    // main renames all three into place together when the run succeeds, and
    // drops them all when any fails or the run is interrupted; the job,
    // written last, is renamed last.
    if let Some(csv) = &args.csv {
        let sha256 = basr::job::csv::write(&job.samples, csv)?;
        job.bind_output("csv", csv, sha256);
    }
    if let Some(adept) = &args.adept {
        let sha256 = basr::job::adept::write(&job.message, &job.samples, &job.stations, adept)?;
        job.bind_output("adept", adept, sha256);
    }
    if !job.outputs.is_empty() {
        job.seal();
    }
    if let Some(key) = &key {
        job.sign(key);
    }
    // WriteError names the path and the OS reason.
    job.write(&out)?;
    let s = &job.summary;
    if args.json {
        let v = serde_json::json!({
            "job": out.display().to_string(),
            "csv": args.csv.as_ref().map(|p| p.display().to_string()),
            "adept": args.adept.as_ref().map(|p| p.display().to_string()),
            "message": job.message,
            "stations": job.stations,
            "samples": job.samples.len(),
            "control_period_s": job.control_period_s,
            "summary": s,
            "sha256": job.sha256,
            "signed_by": job.signature.as_ref().map(|s| s.key_id.clone()),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    }
    if !global.quiet {
        print_summary(&job, &out, &args);
    }
    Ok(Outcome::Success)
}

fn print_summary(job: &basr::job::Job, out: &Path, args: &Args) {
    let s = &job.summary;
    note!(
        "{}: {:?} in {} station(s), {} stroke(s), {} setpoints every {} s",
        out.display(),
        job.message.replace('\n', " / "),
        job.stations.len(),
        s.strokes,
        job.samples.len(),
        job.control_period_s
    );
    note!(
        "  duration {:.1} s: paint {:.1} s, air {:.1} s; paint sprayed {:.2} L",
        s.duration_s,
        s.paint_time_s,
        s.air_time_s,
        s.paint_volume_m3 * 1e3
    );
    if let Some((none, tilted)) = s.u_overall() {
        // The stroke whose tilted U strays furthest from even (0.5).
        let spread = |u: [f64; 2]| (0.5 - u[0]).max(u[1] - 0.5);
        let worst = s
            .balance
            .iter()
            .max_by(|a, b| spread(a.u_tilted).total_cmp(&spread(b.u_tilted)));
        note!(
            "  paint balance U (001 eq. 2.7, 0.5 is even): {:.3}–{:.3} untilted, \
             {:.3}–{:.3} with {} tilt{}",
            none[0],
            none[1],
            tilted[0],
            tilted[1],
            job.layout.tilt_method,
            worst
                .map(|w| format!(" (least even: stroke {}, letter {})", w.stroke, w.char))
                .unwrap_or_default()
        );
    }
    for (i, st) in job.stations.iter().enumerate() {
        note!(
            "  station {i}: arm axis at x {:+.3} m, y {:.3} m",
            st.x_m,
            st.y_m
        );
    }
    if let Some(c) = &args.csv {
        note!("  setpoints: {}", c.display());
    }
    if let Some(a) = &args.adept {
        note!("  Adept V+ program: {}", a.display());
    }
    if let Some(sig) = &job.signature {
        note!("  signed by key {}", sig.key_id);
    }
    if !s.warnings.is_empty() {
        note!("  {} warning(s):", s.warnings.len());
        for w in &s.warnings {
            note!("  warning: {}", w.message);
        }
    }
}
