//! `basr calibrate --stripe FILE`: fit a spray tip's flow and flux profile
//! to a measured test stripe and write the robot description with them.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use super::{Global, Outcome};
use basr::paint::stripe::{self, Stripe};

/// Fit a spray tip's flow and profile to a measured test stripe.
///
/// Paint a straight stripe with the tip untilted, its fan square to the
/// travel, at a known nozzle height and speed; measure the wet film across
/// it; give the readings as a CSV (docs/calibrate.md). calibrate fits the
/// flow and the flux profile across the fan (uniform, uniform-angle, or a
/// one-lobe gauss) and writes the robot description with that tip's
/// `flow_m3ps` and `profile`, every other value as it was. A stripe no
/// profile fits within --max-residual is refused (exit 2), naming each
/// profile's residual.
#[derive(clap::Args)]
#[command(after_help = "Examples:
  basr calibrate --stripe tip511.csv -o basr-calibrated.toml
  basr calibrate --stripe tip511.csv --robot my.toml -o my.toml
  basr compile STOP --robot basr-calibrated.toml

The stripe file (SI units; '#' lines give how it was painted):
  # tip = 511
  # height_m = 0.20
  # speed_mps = 0.15
  offset_m,film_m
  -0.120,0.0
  -0.115,0.000021
  ...")]
pub struct Args {
    /// The measured stripe: CSV `offset_m,film_m` with `# tip = NAME`,
    /// `# height_m = H` and `# speed_mps = V` header lines.
    #[arg(long, value_name = "FILE")]
    pub stripe: PathBuf,
    /// Robot description to calibrate; default: the embedded BASR.
    #[arg(long, value_name = "FILE")]
    pub robot: Option<PathBuf>,
    /// Where to write the calibrated robot description (TOML).
    #[arg(short, long, value_name = "ROBOT.toml")]
    pub output: PathBuf,
    /// Largest residual accepted: RMS of measured − fitted film over the
    /// stripe's peak film.
    // assumed: 0.05, a few times a wet-film gauge's reading step (25 µm
    // notches on a 380 µm film are 0.066 of it, read to half a notch).
    #[arg(long, value_name = "FRACTION", default_value_t = 0.05)]
    pub max_residual: f64,
}

/// A stripe file read: the tip it names and the stripe.
struct StripeFile {
    tip: String,
    stripe: Stripe,
}

/// Read the stripe CSV by hand: its `#` header lines carry how the stripe
/// was painted, which a CSV reader would drop, and every error names its line.
fn read_stripe(path: &Path) -> anyhow::Result<StripeFile> {
    let text = basr::io::read_text(path)?;
    let shown = path.display();
    let (mut tip, mut height, mut speed) = (None, None, None);
    let mut header_seen = false;
    let (mut offsets_m, mut film_m) = (Vec::new(), Vec::new());
    for (i, line) in text.lines().enumerate() {
        let at = format!("{shown}:{}", i + 1);
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(c) = line.strip_prefix('#') {
            let Some((k, v)) = c.split_once('=') else {
                continue; // a remark
            };
            let (k, v) = (k.trim(), v.trim().trim_matches('"'));
            let number = || -> anyhow::Result<f64> {
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && *x > 0.0)
                    .with_context(|| format!("{at}: {k} = {v:?}: give a number above zero"))
            };
            match k {
                "tip" => tip = Some(v.to_string()),
                "height_m" => height = Some(number()?),
                "speed_mps" => speed = Some(number()?),
                _ => anyhow::bail!(
                    "{at}: unknown header {k:?}; the header lines are `# tip = NAME`, \
                     `# height_m = H` (nozzle over the road) and `# speed_mps = V`"
                ),
            }
            continue;
        }
        if !header_seen {
            let cols: Vec<&str> = line.split(',').map(str::trim).collect();
            anyhow::ensure!(
                cols == ["offset_m", "film_m"],
                "{at}: expected the column header `offset_m,film_m`, found {line:?}"
            );
            header_seen = true;
            continue;
        }
        let cols: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |s: &str, what: &str| -> anyhow::Result<f64> {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .with_context(|| format!("{at}: {what} {s:?} is not a number (metres)"))
        };
        anyhow::ensure!(
            cols.len() == 2,
            "{at}: {} columns; each row is offset_m,film_m",
            cols.len()
        );
        let (x, f) = (num(cols[0], "offset_m")?, num(cols[1], "film_m")?);
        anyhow::ensure!(
            f >= 0.0,
            "{at}: film_m {f} is negative; give the wet film in metres (380 µm = 0.00038)"
        );
        offsets_m.push(x);
        film_m.push(f);
    }
    let missing =
        |what: &str| format!("{shown}: no `# {what} = …` header line; see `basr calibrate --help`");
    Ok(StripeFile {
        tip: tip.with_context(|| missing("tip"))?,
        stripe: Stripe {
            offsets_m,
            film_m,
            height_m: height.with_context(|| missing("height_m"))?,
            speed_mps: speed.with_context(|| missing("speed_mps"))?,
        },
    })
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    anyhow::ensure!(
        args.max_residual.is_finite() && args.max_residual > 0.0 && args.max_residual < 1.0,
        "--max-residual {}: give a fraction of the peak film between 0 and 1 (default 0.05)",
        args.max_residual
    );
    super::outputs::check("-o", &args.output, &["toml"])?;
    basr::io::check_writable(&args.output)?;
    let read = read_stripe(&args.stripe)?;
    let (text, origin) = match &args.robot {
        Some(p) => (basr::io::read_text(p)?, p.display().to_string()),
        None => (
            basr::robot::BASR_TOML.to_string(),
            "the embedded BASR".to_string(),
        ),
    };
    let robot = basr::robot::AnyRobot::from_toml_str(&text, &origin)?;
    let paint = robot.paint();
    let tip = paint.tip(&read.tip);
    let fan_angle_rad = match (tip, paint.tips.is_empty()) {
        (Some(t), _) => t.fan_angle_rad(),
        (None, true) => paint.fan_angle_rad,
        (None, false) => anyhow::bail!(
            "{}: tip {:?} is not one {origin} lists ([[paint.tip]]: {}); name one of them \
             in `# tip = …`, or add it to the robot description with its fan angle",
            args.stripe.display(),
            read.tip,
            paint
                .tips
                .iter()
                .map(|t| t.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let fits = stripe::fit(&read.stripe, fan_angle_rad, paint.transfer_efficiency)
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.stripe.display()))?;
    let best = &fits[0];
    let residuals = fits
        .iter()
        .map(|f| format!("{} {:.4}", f.profile_text, f.residual))
        .collect::<Vec<_>>()
        .join(", ");
    anyhow::ensure!(
        best.residual <= args.max_residual,
        "{}: the stripe fits no profile within the residual {} (RMS of measured − fitted \
         film over the peak film): {residuals}. Check the header's height and speed, that \
         the stripe was painted untilted with the fan square to the travel, and the readings",
        args.stripe.display(),
        args.max_residual
    );
    let edited = with_tip_figures(&text, &read.tip, tip.is_some(), paint, best)?;
    // The written description must read back as a valid robot.
    basr::robot::AnyRobot::from_toml_str(&edited, &args.output.display().to_string())
        .context("the calibrated robot description does not validate")?;
    basr::io::write_atomic(&args.output, edited.as_bytes())?;
    if !global.quiet {
        super::outputs::after_commit(format!(
            "tip {}: {} flux, flow {:.4e} m³/s ({:.3} L/min), residual {:.4} (each profile: {residuals}); \
             wrote {}",
            read.tip,
            best.profile_text,
            best.flow_m3ps,
            best.flow_m3ps * 60_000.0, // m³/s → L/min
            best.residual,
            args.output.display()
        ));
    }
    Ok(Outcome::Success)
}

/// `text` with the tip's `flow_m3ps` and `profile` set to `fit`'s (its
/// `[[paint.tip]]` entry, and the `paint` table too when that describes
/// the same tip or the robot lists none), comments and order kept.
fn with_tip_figures(
    text: &str,
    name: &str,
    listed: bool,
    paint: &basr::robot::Paint,
    fit: &stripe::Fit,
) -> anyhow::Result<String> {
    let mut doc: toml_edit::DocumentMut = text.parse().context("the robot description")?;
    let table = doc
        .get_mut("paint")
        .and_then(|p| p.as_table_like_mut())
        .context("the robot description has no [paint] table")?;
    let same_as_table = match paint.tip(name) {
        Some(t) => {
            (t.fan_angle_rad() - paint.fan_angle_rad).abs() <= 1e-9
                && (t.flow_m3ps - paint.flow_m3ps).abs() <= 1e-12
        }
        None => true,
    };
    if same_as_table || !listed {
        table.insert("flow_m3ps", toml_edit::value(fit.flow_m3ps));
        table.insert("profile", toml_edit::value(fit.profile_text.clone()));
    }
    if listed {
        let tips = table
            .get_mut("tip")
            .and_then(|t| t.as_array_of_tables_mut())
            .context("[[paint.tip]] is not an array of tables")?;
        for t in tips.iter_mut() {
            if t.get("name").and_then(|n| n.as_str()) == Some(name) {
                t.insert("flow_m3ps", toml_edit::value(fit.flow_m3ps));
                t.insert("profile", toml_edit::value(fit.profile_text.clone()));
            }
        }
    }
    Ok(doc.to_string())
}
