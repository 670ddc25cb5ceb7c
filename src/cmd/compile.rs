//! `basr compile`: message or marking file → job file, and optionally the
//! setpoint CSV and the Adept V+ program.

use std::path::{Path, PathBuf};

use basr::job::{Owner, Severity, Warning};
use basr::layout::Overrides;
use basr::pipeline::compile::{compile_job, CompileRequest, Source, Tilt};
use basr::units::Length;

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
///
/// Every job is verified in the closed-loop simulator and its film measured
/// as `basr preview` measures it (summary.film): a film that fails the
/// preview's bounds (cv <= 0.05, coverage >= 0.98, overspray <= 0.03) is a
/// problem and the verdict reads NOT READY. Before that, a job whose plan
/// has problems is planned again with each spray tip the robot lists and
/// with a gentler tilt (a smaller share of the tilt joint's acceleration:
/// small letters' bowls), and the first that paints is written; the
/// summary names the tip to mount and says "tilt: planned gently". Still
/// with problems, it is planned with the trapezoid tilt method (unless
/// --tilt names one): the summary then says "tilt: trapezoid"; then with
/// the fan's ends held in where a stroke's edge runs oblique to it (small
/// letters' curves lay paint across such edges): "ends: held in".
///
/// When a word marking (a message or a file of lines) is NOT READY, compile
/// then compiles the quarter-foot letter heights around it, up to 2 ft each
/// way (upwards at least to the default 8 ft) and not below MUTCD's 6 ft
/// (4.5 ft with --low-speed), and names the
/// nearest each way that paints READY or READY WITH NOTES ("sizes:", and
/// `sizes` in --json). A word refused for its size (out of the arm's reach,
/// carried past a joint's range, too fast to follow, or too wide for the
/// lane: then from the height it fits at, downwards) gets the same line
/// under the reason. That takes seconds more on the default robot (QP at
/// 6 ft: 3.3 s in all), up to a minute on the telescopic arm;
/// --no-size-search skips it.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr compile STOP                               # writes STOP.job.json
  basr compile \"STOP AHEAD\" --csv sa.csv          # also the setpoint CSV
  basr compile --marking markings/school_xing.toml --adept school.v2
  basr compile BUS --letter-height 1.83 --tilt none --json
  basr compile --symbol arrow-left                # writes arrow-left.job.json
  basr compile --marking markings/stop_line.toml  # a scene: stop line and STOP
  basr compile --shape logo.svg --shape-height-m 2 -o logo.job.json
  basr compile STOP --sign crew.key --csv stop.csv # signed; stop.csv bound to it

Exit codes: 0 the job is READY or READY WITH NOTES; 1 it is NOT READY (the
job is still written, so `basr report` can say why; do not paint it);
2 bad input or usage (nothing is written).")]
pub struct Args {
    /// The message: letters A–Z (lower case is read as upper case), digits
    /// and spaces; each word is painted as one line.
    // Taken as raw bytes and checked in `run`, so a missing message or one
    // that is not UTF-8 gets our message naming --marking and the letters.
    #[arg(conflicts_with_all = ["marking", "shape"], value_parser = clap::value_parser!(std::ffi::OsString))]
    pub message: Option<std::ffi::OsString>,
    /// A marking file (TOML, see markings/): `lines` of words, or a scene of
    /// `[[item]]`s (words and symbols placed in the lane).
    #[arg(long, value_name = "FILE", conflicts_with = "shape")]
    pub marking: Option<PathBuf>,
    /// One library symbol alone at its standard size, centred in the lane
    /// with its near end at the anchor (`basr symbols` lists the names).
    #[arg(long, value_name = "NAME", conflicts_with_all = ["message", "marking", "shape"])]
    pub symbol: Option<String>,
    /// The operating speed is below 25 mph: letters down to 4.5 ft and
    /// symbols down to 75 % pass the MUTCD checks (11th §3B.20 ¶11).
    #[arg(long)]
    pub low_speed: bool,
    /// Do not search the letter heights near a NOT READY word marking, or
    /// one refused for its size (out of reach, too fast to follow, too wide
    /// for the lane), for
    /// ones that paint (that search plans up to 16 other heights and
    /// verifies those that plan without problems: seconds, or most of a
    /// minute on a slow laptop). For scripts and comparisons
    /// that only want the job; the job and its verdict are the same.
    #[arg(long)]
    pub no_size_search: bool,
    /// A filled outline to paint (SVG or DXF), decomposed into strokes as
    /// `basr import` does; centred in the lane, its near edge at the anchor.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["font", "letter_height"])]
    pub shape: Option<PathBuf>,
    #[command(flatten)]
    pub shape_size: super::import::SizeArgs,
    /// Job file to write [default: <MESSAGE>.job.json].
    #[arg(short, long, value_name = "JOB")]
    pub output: Option<PathBuf>,
    /// Also write the setpoints as CSV (columns: docs/csv.md).
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
    /// Nozzle tilt method [default: quadrilateral; where its job has
    /// problems and the trapezoid method's has none, trapezoid]. Named,
    /// it is kept.
    #[arg(long, value_enum)]
    pub tilt: Option<TiltArg>,
    /// Letter height of the words, 0.3–10 m; metres unless a unit is
    /// written (8ft, 96in, 2440mm) [default: 2.44, or the marking file's].
    /// A symbol has no letters: with --symbol, or a scene without a word,
    /// it is refused (a scene item's `scale` sizes a symbol).
    #[arg(allow_hyphen_values = true, long, value_name = "LENGTH", value_parser = basr::units::metres)]
    pub letter_height: Option<Length>,
    /// Lane width, at most 30 m; metres unless a unit is written (12ft)
    /// [default: 3.66, or the marking file's].
    #[arg(allow_hyphen_values = true, long, value_name = "LENGTH", value_parser = basr::units::metres)]
    pub lane_width: Option<Length>,
    /// Clear space between lines, at least 4× the letter height; metres
    /// unless a unit is written [default: 4× the letter height, or the
    /// marking file's].
    #[arg(allow_hyphen_values = true, long, value_name = "LENGTH", value_parser = basr::units::metres)]
    pub line_gap: Option<Length>,
    /// Largest distance between rungs along a stroke, 1–100 mm;
    /// millimetres unless a unit is written (0.75in). Finer is not better:
    /// the tilt and the fan's turn then follow every small change between
    /// rungs and the arm slows to keep up (STOP's slowest place: 1.09× film
    /// at 15 mm, 1.3× at 10, 1.5× at 8, NOT READY at 1–5 mm with up to
    /// 4.5×; none at the default); the job's notes say where.
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "MM",
        default_value = "20",
        value_parser = basr::units::millimetres
    )]
    pub rung_spacing_mm: f64,
    /// Setpoint period in seconds, 0.005–0.1 (the controller samples at 0.005 s).
    #[arg(allow_hyphen_values = true, long, value_name = "S", default_value_t = basr::pipeline::compile::DEFAULT_PERIOD_S)]
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
    /// Replace the default job file (<MESSAGE>.job.json) even when it holds
    /// a job compiled from something else (`--symbol rxr`, then `--marking
    /// markings/rxr.toml`, both rxr.job.json); without it such a compile
    /// stops (exit 2) and names the file.
    #[arg(long)]
    pub force: bool,
    /// Sign the job with this secret key (written by `basr keygen -o NAME`),
    /// so readers under `--trust NAME.pub` accept it.
    #[arg(long, value_name = "NAME")]
    pub sign: Option<PathBuf>,
    /// Units for the truck's stops in the summary: metric (4.60 m) or us
    /// (feet and inches, 15 ft 1 in) [default: us when the marking file or
    /// --letter-height/--lane-width are in feet or inches, else metric].
    #[arg(long, value_enum, value_name = "UNITS")]
    pub units: Option<super::UnitsArg>,
    /// Print the summary as JSON on stdout (the verdict, the spray tip to
    /// mount, every warning with its severity).
    #[arg(long)]
    pub json: bool,
    /// List every warning (info and notices too), not only the problems.
    #[arg(long, short)]
    pub verbose: bool,
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
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The default job name's stem: a shape's job is named after its file, a
/// symbol's after the symbol, a scene's after its file, a message's after
/// the `message` it paints.
fn default_stem(args: &Args, scene_file: bool, message: &str) -> String {
    match (&args.shape, &args.symbol, &args.marking) {
        (Some(p), _, _) => p
            .file_stem()
            .map(|s| stem_of(&s.to_string_lossy()))
            .unwrap_or_else(|| "shape".into()),
        (None, Some(name), _) => stem_of(&library_name(Some(name))),
        (None, None, Some(path)) if scene_file => path
            .file_stem()
            .map_or_else(|| stem_of(message), |s| stem_of(&s.to_string_lossy())),
        _ => stem_of(message),
    }
}

/// The job's `message` as the compile will write it, worked out from the
/// arguments alone (cheap: no planning), so a default name that holds a
/// job of something else is refused before minutes of work. `None` when
/// the input is bad: the compile reports that.
fn predicted_message(args: &Args) -> Option<(String, bool)> {
    use basr::layout::{Marking, Scene};
    let o = Overrides::default();
    if let Some(name) = &args.symbol {
        return Some((
            basr::pipeline::shapes::message_of(&library_name(Some(name))),
            false,
        ));
    }
    if let Some(p) = &args.shape {
        let label = p.file_stem()?.to_string_lossy().to_string();
        return Some((basr::pipeline::shapes::message_of(&label), false));
    }
    if let Some(m) = &args.message {
        return Some((
            Marking::from_message(m.to_str()?, &o).ok()?.message(),
            false,
        ));
    }
    let path = args.marking.as_deref()?;
    let text = std::fs::read_to_string(path).ok()?;
    let origin = path.display().to_string();
    if basr::layout::is_scene(&text) {
        Some((Scene::from_toml(&text, &origin, &o).ok()?.message(), true))
    } else {
        Some((
            Marking::from_toml(&text, &origin, &o).ok()?.message(),
            false,
        ))
    }
}

/// A `--symbol` name as the library spells it (names are matched without
/// regard to case); an unknown name as given, for the layout's error that
/// lists the nearest.
fn library_name(name: Option<&str>) -> String {
    let name = name.unwrap_or_default();
    basr::font::Library::embedded()
        .get(name)
        .map_or_else(|| name.to_string(), |s| s.name.clone())
}

/// Messages that are a symbol's name or the words it stands for: painting
/// them as letters is seldom what is meant (`basr compile RXR` paints the
/// letters R, X, R; the crossing symbol is `--symbol rxr`).
const SYMBOL_WORDS: [(&str, &str); 5] = [
    ("RXR", "rxr"),
    ("RRXING", "rxr"),
    ("RXING", "rxr"),
    ("RAILROADXING", "rxr"),
    ("RAILROADCROSSING", "rxr"),
];

/// A hint when the message (spaces and hyphens aside, case ignored) is a
/// symbol's name or one of [`SYMBOL_WORDS`]: the symbol and how to paint it.
fn symbol_hint(message: &str) -> Option<String> {
    let key: String = message
        .chars()
        .filter(|c| !c.is_whitespace() && *c != '-' && *c != '_')
        .collect::<String>()
        .to_ascii_uppercase();
    let lib = basr::font::Library::embedded();
    let name = SYMBOL_WORDS
        .iter()
        .find(|(w, _)| *w == key)
        .map(|(_, n)| n.to_string())
        .or_else(|| {
            lib.symbols()
                .find(|s| s.name.replace('-', "").eq_ignore_ascii_case(&key))
                .map(|s| s.name.clone())
        })?;
    let sym = lib.get(&name)?;
    Some(format!(
        "{:?} names a symbol: `{}` ({}) is painted with `basr compile --symbol {}`; a \
         message is painted as letters",
        message.trim(),
        sym.name,
        sym.description,
        sym.name
    ))
}

/// A hint when the message is a file's name (`basr compile crown.toml`):
/// which option or command reads that file. Only for a name with a dot
/// or a slash, which no message holds.
fn file_hint(message: &str) -> Option<String> {
    let m = message.trim();
    if !m.contains(['.', '/', '\\']) {
        return None;
    }
    let ext = Path::new(m)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let exists = Path::new(m).is_file();
    let quoted = if m.contains(char::is_whitespace) {
        format!("{m:?}")
    } else {
        m.to_string()
    };
    Some(match ext.as_deref() {
        Some("toml") => format!(
            "{m:?} is a marking file's name, not a message: compile it with `basr compile \
             --marking {quoted}`"
        ),
        Some("svg" | "dxf") => format!(
            "{m:?} is a shape's file name, not a message: paint a filled outline with `basr \
             compile --shape {quoted}`"
        ),
        Some("json") => format!(
            "{m:?} is a job file's name: compile writes jobs; `basr preview {quoted}`, `basr \
             simulate {quoted}` and `basr check {quoted}` read them"
        ),
        _ if exists => format!(
            "{m:?} is a file, not a message: compile reads a marking file with --marking \
             (TOML) or a shape with --shape (SVG, DXF)"
        ),
        _ => return None,
    })
}

/// Refuse a default job name that holds a job of something else (another
/// message, symbol, scene or shape): compiling `--symbol rxr` and then
/// `--marking markings/rxr.toml` must not silently replace the first job.
/// The same message compiled again (other options) replaces its own job.
/// A file there that is not a basr job is refused too: it is the user's.
fn refuse_replacing_another(
    out: &Path,
    message: &str,
    stem: &str,
    args: &Args,
) -> anyhow::Result<()> {
    let Ok(bytes) = std::fs::read(out) else {
        return Ok(());
    };
    let kind = match (&args.marking, &args.symbol, &args.shape) {
        (Some(_), _, _) => "scene",
        (_, Some(_), _) => "symbol",
        (_, _, Some(_)) => "shape",
        _ => "text",
    };
    let fix = format!(
        "give -o {stem}-{kind}.job.json for this one, or --force to replace {}",
        out.display()
    );
    let held = serde_json::from_slice::<serde_json::Value>(&bytes)
        .ok()
        .and_then(|v| v.get("message")?.as_str().map(str::to_string));
    match held {
        Some(m) if m == message => Ok(()),
        Some(m) => anyhow::bail!(
            "{} holds the job of {:?}, compiled from something else; this compile is of \
             {:?} and would replace it: {fix}",
            out.display(),
            m.replace('\n', " / "),
            message.replace('\n', " / ")
        ),
        None => anyhow::bail!(
            "{} exists and is not a job basr wrote; this compile would replace it: {fix}",
            out.display()
        ),
    }
}

/// Usual ranges, m, for the feet hint: letters of 1–12 ft (MUTCD §3B.20
/// uses 6–8 ft) and lanes of 8–16 ft. // assumed: wide enough for
/// every marking in markings/, narrow enough that 8 (ft) falls outside.
const USUAL_LETTER_HEIGHT_M: (f64, f64) = (0.3, 3.7);
const USUAL_LANE_WIDTH_M: (f64, f64) = (2.4, 5.0);

/// Hints for bare numbers that look like feet (`--letter-height 8`).
fn feet_hints(args: &Args) -> Vec<String> {
    [
        ("--letter-height", args.letter_height, USUAL_LETTER_HEIGHT_M),
        ("--lane-width", args.lane_width, USUAL_LANE_WIDTH_M),
    ]
    .into_iter()
    .filter_map(|(flag, l, usual)| basr::units::feet_hint(flag, l?, usual))
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
    if let Some(p) = &args.shape {
        inputs.push(("the shape file (--shape)", p));
    }
    if let Some(p) = &args.robot {
        inputs.push(("the robot file (--robot)", p));
    }
    if let Some(f) = &args.font {
        inputs.push(("the font file (--font)", Path::new(f)));
    }
    super::refuse_clashes(&outputs, &inputs)
}

/// A path's last part, for a progress line (`markings/rxr.toml` → `rxr.toml`).
fn file_name(p: &Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// `--letter-height` sizes the letters of words: a symbol, or a scene of
/// symbols and shapes without a word, has none, and the option would do
/// nothing but switch the printout to feet. Refused, saying what sizes
/// those instead. (A scene that does not parse is left to compile, which
/// names its error.)
fn refuse_height_without_letters(args: &Args, req: &CompileRequest) -> anyhow::Result<()> {
    if args.letter_height.is_none() {
        return Ok(());
    }
    let what = match &req.source {
        Source::Symbol(name) => format!("the symbol {name}"),
        Source::Marking { text, origin } if basr::layout::is_scene(text) => {
            match basr::layout::Scene::from_toml(text, origin, &req.overrides) {
                Ok(scene)
                    if !scene
                        .items
                        .iter()
                        .any(|i| matches!(i.kind, basr::layout::ItemKind::Word { .. })) =>
                {
                    format!("{origin} (a scene of symbols and shapes, no word)")
                }
                _ => return Ok(()),
            }
        }
        _ => return Ok(()),
    };
    anyhow::bail!(
        "--letter-height sizes the letters of words, and {what} has none: a symbol \
         keeps its standard size (a scene's `scale = 1.5` in its [[item]] scales it, \
         `--low-speed` makes it 25 % smaller) and a shape takes `height_m` or `width_m` \
         in its [[item]]; leave --letter-height out"
    )
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    // Before any work: a folder or a wrong name fails now, not after planning.
    if let Some(p) = &args.output {
        // Two outputs on one file is the more useful complaint.
        refuse_clashing_paths(&args, p)?;
        super::outputs::check("-o", p, &["json"])?;
    }
    if let Some(p) = &args.csv {
        super::outputs::check("--csv", p, &["csv"])?;
    }
    if let Some(p) = &args.adept {
        super::outputs::check("--adept", p, &[])?;
    }
    if args.output.is_none() && !args.force {
        if let Some((message, scene_file)) = predicted_message(&args) {
            let stem = default_stem(&args, scene_file, &message);
            let out = PathBuf::from(format!("{stem}.job.json"));
            refuse_replacing_another(&out, &message, &stem, &args)?;
        }
    }
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
    let mut shape = None;
    let source = match (&args.message, &args.marking) {
        _ if args.symbol.is_some() => Source::Symbol(library_name(args.symbol.as_deref())),
        (None, None) if args.shape.is_some() => {
            let path = args.shape.as_deref().unwrap_or(Path::new(""));
            let robot = basr::robot::AnyRobot::load_or_default(args.robot.as_deref())?;
            let bands = basr::pipeline::shapes::bands(&robot);
            // The search compiles and previews candidate decompositions:
            // the long part of a shape's compile (30–60 s).
            let bar = super::progress_bar(
                !global.quiet && !args.json,
                &format!("{}: trying decompositions", file_name(path)),
            );
            let imported = basr::pipeline::shapes::import_measured_with_progress(
                path,
                args.shape_size.size(),
                &robot,
                &|done, total| {
                    bar.set_length(total as u64);
                    bar.set_position(done as u64);
                },
            );
            bar.finish_and_clear();
            shape = Some((imported?, bands));
            Source::Message(basr::shape::GLYPH.to_string())
        }
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
            "give the message to paint, a marking file or a symbol: `basr compile STOP`, \
             `basr compile --marking markings/stop.toml` or `basr compile --symbol stop-line`"
        ),
    };
    let req = CompileRequest {
        source,
        overrides: Overrides {
            letter_height_m: args.letter_height.map(|l| l.m),
            lane_width_m: args.lane_width.map(|l| l.m),
            line_gap_m: args.line_gap.map(|l| l.m),
            low_speed: args.low_speed,
        },
        font: args.font.clone(),
        robot: args.robot.clone(),
        tilt: match args.tilt {
            Some(TiltArg::None) => Tilt::None,
            Some(TiltArg::Trapezoid) => Tilt::Trapezoid,
            Some(TiltArg::Quadrilateral) | None => Tilt::Quadrilateral,
        },
        tilt_named: args.tilt.is_some(),
        rung_spacing_m: args.rung_spacing_mm * 1e-3,
        period_s: args.period_s,
        gun_lead_s: args.gun_lead_s,
        gun_lag_s: args.gun_lag_s,
        ..CompileRequest::message("")
    };
    refuse_height_without_letters(&args, &req)?;
    anyhow::ensure!(
        args.shape.is_some()
            || (args.shape_size.shape_height_m.is_none()
                && args.shape_size.shape_width_m.is_none()),
        "--shape-height-m and --shape-width-m size a --shape FILE; give the shape too"
    );
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
    let mut hints = feet_hints(&args);
    if let Source::Message(m) = &req.source {
        hints.extend(symbol_hint(m));
        hints.extend(file_hint(m));
    }
    let scene_file =
        matches!(&req.source, Source::Marking { text, .. } if basr::layout::is_scene(text));
    let spin = super::spinner(
        !global.quiet && !args.json,
        &format!(
            "compiling {}",
            match (&req.source, &args.shape) {
                (_, Some(p)) => file_name(p),
                (Source::Marking { origin, .. }, _) => file_name(Path::new(origin)),
                (Source::Symbol(s), _) => s.clone(),
                (Source::Message(m), _) => basr::plot::clip(&m.replace('\n', " / "), 40),
            }
        ),
    );
    let compiled = match (&shape, &args.shape) {
        (Some((imported, bands)), Some(path)) => {
            let label = path
                .file_stem()
                .map(|s| s.to_string_lossy().to_string())
                .unwrap_or_else(|| "shape".into());
            basr::pipeline::shapes::compile_shape(&req, imported, bands, &label)
        }
        _ => compile_job(&req),
    };
    spin.finish_and_clear();
    let floor = basr::layout::rules::MIN_LETTER_HEIGHT_M
        * if args.low_speed {
            basr::layout::rules::LOW_SPEED_FACTOR
        } else {
            1.0
        };
    let mut job = compiled.map_err(|e| {
        // A word refused for its size (out of reach, too wide for the
        // lane, too fast to follow): the nearest heights that paint.
        let sizes = (!args.no_size_search && shape.is_none())
            .then(|| super::sizes::refused_at(&req, &e, floor))
            .flatten()
            .map(|(asked, larger)| {
                let show = !global.quiet && !args.json;
                super::sizes::search(&req, asked, floor, larger, true, show).line()
            });
        let layout = matches!(e, basr::pipeline::compile::CompileError::Layout(_));
        let mut text = format!("{:#}", anyhow::Error::from(e));
        // A marking file's layout error names the file (a scene's item
        // errors said "item 1: …" alone).
        if let (true, Source::Marking { origin, .. }) = (layout, &req.source) {
            if !text.starts_with(origin.as_str()) {
                text = format!("{origin}: {text}");
            }
        }
        for h in &hints {
            text.push_str(&format!("\n  hint: {h}"));
        }
        if let Some(line) = sizes {
            text.push('\n');
            text.push_str(&line);
        }
        anyhow::anyhow!(text)
    })?;
    // A failed compile carries the hints in its error (above); say them
    // once either way.
    if !global.quiet {
        for h in &hints {
            note!("hint: {h}");
        }
    }
    let stem = default_stem(&args, scene_file, &job.message);
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{stem}.job.json")));
    super::outputs::check("the job", &out, &["json"])?;
    refuse_clashing_paths(&args, &out)?;
    if args.output.is_none() && !args.force {
        refuse_replacing_another(&out, &job.message, &stem, &args)?;
    }
    basr::io::check_writable(&out)?;
    // main renames all three into place together when the run succeeds, and
    // drops them all when any fails or the run is interrupted; the job,
    // written last, is renamed last.
    super::outputs::write_job(
        &mut job,
        &out,
        args.csv.as_deref(),
        args.adept.as_deref(),
        key.as_ref(),
    )?;
    let s = &job.summary;
    let verdict = verdict_of(&job);
    // A word marking that does not paint READY: the nearest sizes that do.
    let sizes = (verdict == "not ready"
        && !args.no_size_search
        && shape.is_none()
        && super::sizes::applies(&req))
    .then(|| {
        let show = !global.quiet && !args.json;
        super::sizes::search(&req, job.layout.letter_height_m, floor, true, false, show)
    });
    if args.json {
        let v = serde_json::json!({
            "job": out.display().to_string(),
            "csv": args.csv.as_ref().map(|p| p.display().to_string()),
            "adept": args.adept.as_ref().map(|p| p.display().to_string()),
            "message": job.message,
            "stations": job.stations,
            "samples": job.samples.len(),
            "control_period_s": job.control_period_s,
            "verdict": verdict,
            // the spray tip to mount (null for a robot that lists none)
            "tip": job.paint.tip,
            // the tilt method painted with, and whether gently
            "tilt": {
                "method": job.layout.tilt_method,
                "gentle": job.layout.options.as_ref().is_some_and(|o| o.gentle_tilt),
            },
            // the rungs' ends held in from oblique edges (options.hold_ends)
            "ends_held": job.layout.options.as_ref().is_some_and(|o| o.hold_ends),
            "summary": s,
            "sha256": job.sha256,
            "signed_by": job.signature.as_ref().map(|s| s.key_id.clone()),
            "sizes": sizes.as_ref().map(|a| {
                // To the micrometre: 6 ft is 1.8288 m, not 1.8288000000000002.
                let um = |m: f64| (m * 1e6).round() / 1e6;
                serde_json::json!({
                    "asked_m": um(a.asked_m),
                    "nearest_ready_smaller_m": a.smaller_m.map(um),
                    "nearest_ready_larger_m": a.larger_m.map(um),
                    "searched_m": a.searched_m.map(um),
                })
            }),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    }
    if !global.quiet {
        // Printed once every output is in place.
        let mut text = summary_text(&job, &out, &args);
        text.extend(sizes.as_ref().map(super::sizes::SizeAdvice::line));
        if verdict == "not ready" && !args.no_size_search && shape.is_none() && sizes.is_none() {
            text.extend(super::sizes::not_searched_line(&req));
        }
        super::outputs::after_commit(text.join("\n"));
    }
    // NOT READY is a negative verdict (exit 1): a script that compiles and
    // loads must not take it for a job to paint. The job is written all
    // the same, for `basr report` to say why.
    Ok(if verdict == "not ready" {
        Outcome::Negative
    } else {
        Outcome::Success
    })
}

/// The job's verdict as its sheet and `basr check` say it: `ready`,
/// `ready with notes` or `not ready`.
pub fn verdict_of(job: &basr::job::Job) -> &'static str {
    let severities: Vec<basr::job::Severity> =
        job.summary.warnings.iter().map(Warning::graded).collect();
    basr::report::overall(&severities, false)
}

/// Lines compile prints at most without --verbose (issue 15: a crew reads
/// a short block, not 300 warnings).
const MAX_LINES: usize = 12;
/// Stops listed one per line before they are summed up in one.
const MAX_STOP_LINES: usize = 3;

/// What a group of like problems adds to its first one's line: the other
/// strokes it names, each once and in order ("the same on strokes 5, 6,
/// 8"), and how many more places the first one's own stroke has.
fn same_on(g: &[&Warning]) -> String {
    let mut others: Vec<usize> = g[1..]
        .iter()
        .filter_map(|w| w.stroke)
        .filter(|&s| Some(s) != g[0].stroke)
        .collect();
    let again = g.len() - 1 - others.len();
    others.sort_unstable();
    others.dedup();
    let list: Vec<String> = others.iter().map(usize::to_string).collect();
    let places = |n: usize| format!("{n} more place{}", if n == 1 { "" } else { "s" });
    match (list.len(), again) {
        (0, 0) => String::new(),
        (0, n) => format!(" (and {} on this stroke)", places(n)),
        (k, n) => format!(
            " (the same on stroke{} {}{})",
            if k == 1 { "" } else { "s" },
            list.join(", "),
            if n > 0 {
                format!(", and {} on this one", places(n))
            } else {
                String::new()
            }
        ),
    }
}

/// The warnings of one kind and severity on one item, worst first: printed
/// as one line. A note about a stroke of an item (it has an owner) joins
/// the like notes on that item; any other stands alone, joined only by
/// the same sentence again.
fn grouped<'w>(warnings: &[&'w Warning]) -> Vec<Vec<&'w Warning>> {
    /// What a warning is on, for grouping.
    #[derive(PartialEq)]
    enum On<'a> {
        Item(&'a Owner),
        Alone(&'a str),
    }
    let on = |w: &'w Warning| match &w.owner {
        Some(o) => On::Item(o),
        None => On::Alone(&w.message),
    };
    let mut groups: Vec<Vec<&Warning>> = Vec::new();
    for &w in warnings {
        match groups
            .iter_mut()
            .find(|g| g[0].kind == w.kind && g[0].severity == w.severity && on(g[0]) == on(w))
        {
            Some(g) => g.push(w),
            None => groups.push(vec![w]),
        }
    }
    for g in &mut groups {
        g.sort_by(|a, b| b.factor.unwrap_or(0.0).total_cmp(&a.factor.unwrap_or(0.0)));
    }
    groups
}

/// The units the summary speaks: `--units`, else those the user wrote
/// lengths in (a marking file in feet or inches, `--lane-width 12ft`).
fn units_of(args: &Args) -> basr::units::System {
    use basr::units::System;
    if let Some(u) = args.units {
        return u.into();
    }
    let in_feet = |l: Option<Length>| l.is_some_and(|l| l.us);
    let marking_in_feet = args
        .marking
        .as_deref()
        .and_then(|p| std::fs::read_to_string(p).ok())
        .is_some_and(|t| t.lines().any(us_length_line));
    if marking_in_feet || in_feet(args.letter_height) || in_feet(args.lane_width) {
        System::Us
    } else {
        System::Metric
    }
}

/// Whether a marking file's line gives a position or width in feet or
/// inches (`lane_width_ft = 12`, `at_m = ["0ft", "16ft"]`); letter heights
/// in feet are how MUTCD states them, so `letter_height_ft` alone is not.
fn us_length_line(line: &str) -> bool {
    let Some((key, value)) = line.split_once('=') else {
        return false;
    };
    let key = key.trim();
    let us_key = (key.ends_with("_ft") || key.ends_with("_in")) && key != "letter_height_ft";
    let value = value.split('#').next().unwrap_or("");
    us_key
        || ["ft\"", "in\"", "feet\"", "inches\""]
            .iter()
            .any(|u| value.contains(u))
}

/// Compile's human text: what, where the truck stops, time on site, paint,
/// the verdict and the problems; `verbose` adds every warning.
fn summary_text(job: &basr::job::Job, out: &Path, args: &Args) -> Vec<String> {
    let s = &job.summary;
    let stops = job.stations.len();
    let mut lines = vec![format!(
        "{}: {:?}, {stops} stop{}, {:.1} min on site, {:.2} L of paint ({} strokes, {} setpoints)",
        out.display(),
        job.message.replace('\n', " / "),
        if stops == 1 { "" } else { "s" },
        basr::report::time_on_site_s(job) / 60.0,
        s.paint_volume_m3 * 1e3,
        s.strokes,
        job.samples.len()
    )];
    let units = units_of(args);
    let anchor = basr::report::anchor_words_in(job, units);
    if stops <= MAX_STOP_LINES {
        for (k, st) in job.stations.iter().enumerate() {
            lines.push(format!(
                "  stop {}: arm axis {}",
                k + 1,
                basr::report::place_words_in(st, &anchor, units)
            ));
        }
    } else {
        lines.push(format!(
            "  stops 1–{stops}: the first with the arm axis {}; `basr report` lists them all",
            basr::report::place_words_in(&job.stations[0], &anchor, units)
        ));
    }
    let written: Vec<String> = [("setpoints", &args.csv), ("Adept V+ program", &args.adept)]
        .iter()
        .filter_map(|(what, p)| p.as_ref().map(|p| format!("{what} {}", p.display())))
        .collect();
    if !written.is_empty() {
        lines.push(format!("  also wrote {}", written.join(", ")));
    }
    if let Some(sig) = &job.signature {
        lines.push(format!("  signed by key {}", sig.key_id));
    }
    if let Some(tip) = basr::report::tip_words(job) {
        lines.push(format!("  spray tip: {tip}"));
    }
    let gentle = job.layout.options.as_ref().is_some_and(|o| o.gentle_tilt);
    let chose = args.tilt.is_none() && job.layout.tilt_method == Tilt::Trapezoid.name();
    if gentle || chose {
        let how = match (chose, gentle) {
            (true, true) => "trapezoid, planned gently",
            (true, false) => "trapezoid",
            _ => "planned gently",
        };
        let why = match (chose, gentle) {
            (true, _) => {
                "the quadrilateral method's plan had problems; the trapezoid method's \
                 has none"
            }
            _ => {
                "its first plan had problems; a smaller share of the tilt joint's \
                 acceleration paints it"
            }
        };
        lines.push(format!("  tilt: {how} ({why})"));
    }
    if job.layout.options.as_ref().is_some_and(|o| o.hold_ends) {
        lines.push(
            "  ends: held in where a stroke's edge runs oblique to the fan (the plans without \
             had problems; the fan sheet's depth carried paint across those edges)"
                .to_string(),
        );
    }
    if let Some(f) = &s.film {
        lines.push(film_line(f));
    }
    if let Some(line) = followed_line(s) {
        lines.push(line);
    }
    let count = |sev| {
        s.warnings
            .iter()
            .filter(|w| w.severity == Some(sev))
            .count()
    };
    let (problems, notices, infos) = (
        count(Severity::Problem),
        count(Severity::Notice),
        count(Severity::Info),
    );
    let severities: Vec<Severity> = s.warnings.iter().map(Warning::graded).collect();
    let verdict = basr::report::overall(&severities, false).to_uppercase();
    let more = if args.verbose || s.warnings.is_empty() {
        String::new()
    } else {
        "; --verbose lists them".to_string()
    };
    lines.push(format!(
        "  verdict: {verdict} ({problems} problem{}, {notices} notice{}, {infos} for \
         information{more})",
        if problems == 1 { "" } else { "s" },
        if notices == 1 { "" } else { "s" },
    ));
    if args.verbose {
        for w in &s.warnings {
            let sev = w.severity.map_or("", Severity::name);
            lines.push(format!("  {sev}: {}", w.message));
        }
        return lines;
    }
    let room = MAX_LINES.saturating_sub(lines.len());
    lines.extend(problem_lines(&s.warnings, room));
    lines
}

/// How closely the simulated arm followed the job when compile verified
/// it, in one line: `arm (closed loop): nozzle within 3.90 mm of the path
/// on the robot description, 4.46 mm on 6 plants drawn around it (bound
/// 4.76 mm)`; `None` for a job not verified.
fn followed_line(s: &basr::job::Summary) -> Option<String> {
    let nominal = s.verified_max_error_m?;
    let bound = basr::pipeline::verify::spread::SHARE * basr::sim::Options::default().tolerance_m;
    let plants = s.verified.as_ref().map_or(String::new(), |v| {
        format!(
            ", {}{:.2} mm on {} plants drawn around it",
            if v.over.is_some() { "at least " } else { "" },
            v.max_error_m * 1e3,
            v.plants
        )
    });
    let over = s.verified.as_ref().is_some_and(|v| v.over.is_some());
    Some(format!(
        "  arm (closed loop): nozzle within {:.2} mm of the path on the robot description{plants} (bound {:.2} mm){}",
        nominal * 1e3,
        bound * 1e3,
        if over {
            "; over it on a plant, not re-timed for it (summary.verified.over, docs/simulate.md)"
        } else {
            ""
        }
    ))
}

/// The job's film as `basr preview` measures it, in one line:
/// `film: cv 0.027, coverage 0.997, overspray 0.024, mean 379 µm (target
/// 380 µm): pass`, or `…: FAIL (cv 0.051 over the 0.050 limit)`.
fn film_line(f: &basr::job::FilmSummary) -> String {
    let n = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{v:.3}"));
    let verdict = if f.failed.is_empty() {
        f.verdict.name().to_string()
    } else {
        format!(
            "{} ({})",
            f.verdict.name().to_uppercase(),
            f.failed.join("; ")
        )
    };
    format!(
        "  film (as `basr preview` measures it): cv {}, coverage {}, overspray {}, mean {} \
         (target {:.0} µm): {verdict}",
        n(f.cv),
        n(f.coverage),
        n(f.overspray),
        f.mean_film_m
            .map_or("–".to_string(), |m| format!("{:.0} µm", m * 1e6)),
        f.target_film_m * 1e6,
    )
}

/// The problems among `warnings`, one line a group of the same warning
/// (`  problem: …, the same on strokes …`), in at most `room` lines (the
/// last then says how many more there are and where).
pub(super) fn problem_lines(warnings: &[Warning], room: usize) -> Vec<String> {
    let problems: Vec<&Warning> = warnings
        .iter()
        .filter(|w| w.severity == Some(Severity::Problem))
        .collect();
    let groups = grouped(&problems)
        .into_iter()
        .map(|g| format!("  problem: {}{}", g[0].message, same_on(&g)))
        .collect::<Vec<_>>();
    if groups.len() <= room {
        return groups;
    }
    let keep = room.saturating_sub(1);
    let left = groups.len() - keep;
    let mut lines: Vec<String> = groups.into_iter().take(keep).collect();
    lines.push(format!(
        "  … {left} more problem lines: --verbose, or `basr report` for the job sheet"
    ));
    lines
}

#[cfg(test)]
mod tests {
    use super::{grouped, same_on};
    use basr::job::{Owner, OwnerKind, Severity, Warning, WarningKind};

    fn on(stroke: usize) -> Warning {
        Warning {
            kind: WarningKind::Slowed,
            severity: Some(Severity::Problem),
            stroke: Some(stroke),
            t_s: None,
            factor: None,
            message: String::new(),
            owner: None,
        }
    }

    #[test]
    fn a_group_names_each_other_stroke_once_in_order() {
        let g = [on(9), on(8), on(6), on(9), on(6), on(8), on(5)];
        let refs: Vec<&Warning> = g.iter().collect();
        assert_eq!(
            same_on(&refs),
            " (the same on strokes 5, 6, 8, and 1 more place on this one)"
        );
        let alone = [on(3), on(3), on(3)];
        let refs: Vec<&Warning> = alone.iter().collect();
        assert_eq!(same_on(&refs), " (and 2 more places on this stroke)");
        assert_eq!(same_on(&[&on(3)]), "");
        let two = [on(3), on(4)];
        let refs: Vec<&Warning> = two.iter().collect();
        assert_eq!(same_on(&refs), " (the same on stroke 4)");
    }

    #[test]
    fn notes_group_by_their_typed_owner_not_by_their_words() {
        let letter = |label: &str, stroke, factor, message: &str| Warning {
            owner: Some(Owner {
                kind: OwnerKind::Letter,
                label: label.into(),
                line: 0,
            }),
            factor: Some(factor),
            message: message.into(),
            ..on(stroke)
        };
        // The same words on two letters stay apart; different words on one
        // letter join, worst first; an owner-less note stands alone.
        let ws = [
            letter("S", 1, 1.2, "same words"),
            letter("T", 2, 1.9, "same words"),
            letter("S", 3, 1.7, "other words"),
            Warning {
                kind: WarningKind::Film,
                message: "same words".into(),
                ..on(4)
            },
        ];
        let refs: Vec<&Warning> = ws.iter().collect();
        let g = grouped(&refs);
        let strokes: Vec<Vec<Option<usize>>> = g
            .iter()
            .map(|g| g.iter().map(|w| w.stroke).collect())
            .collect();
        assert_eq!(
            strokes,
            vec![vec![Some(3), Some(1)], vec![Some(2)], vec![Some(4)]]
        );
    }
}
