//! `basr preview JOB`: simulate the paint film a job lays and draw it as an
//! SVG with its metrics (coverage, evenness, overspray, edges, U).

use std::path::{Path, PathBuf};

use anyhow::Context;
use basr::job::Job;
use basr::paint::film::{self, FilmOptions, JobFilm};
use basr::paint::preview::{self, JsonReport, Options, Panel, Preview};
use basr::paint::verdict::{self, Thresholds, Verdict};
use basr::paint::{Depth, Profile};
use basr::pipeline::compile::Tilt;

use super::replan::{self, REPLANNED_FROM};
use super::{Global, Outcome};

/// Simulate the paint film of a job and draw it.
///
/// The airless flat fan at every setpoint's tip pose (height, fan direction,
/// tilt) lays flow × transfer efficiency on a road-frame raster; the film is
/// measured against the letters' true outlines. Writes an SVG (film map in
/// µm with colour bar, outlines, nozzle path, stations, metrics, per-glyph
/// table); without -o it is the job's name with `.preview.svg`
/// (STOP.job.json → STOP.preview.svg) in the current folder, a name no
/// input of yours carries (`compile --shape logo.svg` then `preview
/// logo.job.json` keeps logo.svg).
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr preview STOP.job.json                   # writes STOP.preview.svg here
  basr preview STOP.job.json -o stop.svg --json
  basr preview STOP.job.json --resolution-mm 2 --profile beta:2,2
  basr preview STOP.job.json --compare none,trapezoid,quadrilateral
  basr preview rxr.job.json --compare none,quadrilateral       # a symbol alone
  basr preview stop_line.job.json --compare none,quadrilateral \
      --marking markings/stop_line.toml                        # a scene: its file

Metrics: coverage = share of letter area with >= 50 % of target film;
cv = std/mean of the film inside the letters (one cell in from the edge);
overspray = share of the paint on the road outside the letters; U = the
tile area ratio of 001 eq. 2.7 (50 % ideal).

Verdict: the film passes when cv <= 0.05, coverage >= 0.98 and overspray
<= 0.03 (change them with --max-cv, --min-coverage, --max-overspray;
docs/preview.md says why). Exit 0 pass, 1 fail, 2 bad input.")]
pub struct Args {
    /// The job file written by `basr compile`.
    pub job: PathBuf,

    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,

    /// SVG to write [default: the job's name with .preview.svg, in the current folder].
    #[arg(short, long, value_name = "SVG")]
    pub output: Option<PathBuf>,

    /// Print the metrics as JSON on stdout.
    #[arg(long)]
    pub json: bool,

    /// Raster cell size in millimetres [default: 5 (a long job's raster is
    /// held a band at a time; coarsened in 0.5 mm steps only if one band
    /// would not fit in memory); given, it is kept or the job refused].
    #[arg(allow_negative_numbers = true, long, value_name = "R")]
    pub resolution_mm: Option<f64>,

    /// Verdict: the largest coefficient of variation of the film inside
    /// the letters that passes.
    #[arg(long, value_name = "CV", default_value_t = verdict::CV_MAX)]
    pub max_cv: f64,

    /// Verdict: the smallest share of letter area with at least half the
    /// target film that passes.
    #[arg(long, value_name = "SHARE", default_value_t = verdict::COVERAGE_MIN)]
    pub min_coverage: f64,

    /// Verdict: the largest share of the paint outside the letters that
    /// passes.
    #[arg(long, value_name = "SHARE", default_value_t = verdict::OVERSPRAY_MAX)]
    pub max_overspray: f64,

    /// Flux across the fan: `uniform` (even on the road, the seed's
    /// assumption), `uniform-angle`, `gauss[:w,mean,sigma;…]` (lobes per unit
    /// angle, mean and sigma as fractions of the half fan angle) or
    /// `beta[:p,q]`. Default: the profile of the tip the job was planned
    /// for (the robot's `paint.profile`; `uniform` when it gives none), as
    /// compile measured it.
    #[arg(long, value_name = "PROFILE")]
    pub profile: Option<String>,

    /// Depth of the fan sheet on the road, square to the fan's line (along
    /// the travel where the fan stands square to it; across a skewed
    /// rung's edges where it does not): `gauss:MM` (standard deviation) or
    /// `tophat:MM` (full width).
    #[arg(long, value_name = "KIND:MM", default_value = "gauss:6")]
    pub fan_depth: String,

    /// Re-plan the job under each listed tilt method (none, trapezoid,
    /// quadrilateral) and draw them side by side. The re-planned jobs use
    /// the job's message or symbol (a scene: --marking), robot description,
    /// font, letter height, lane width and period; options the job does not
    /// record (rung spacing, gun lead/lag) take compile's defaults.
    #[arg(long, value_name = "METHODS", value_delimiter = ',')]
    pub compare: Vec<String>,

    /// With --compare: the marking file (a scene of items, or `lines`) the
    /// job was compiled from; it must lay out exactly as the job's items.
    #[arg(long, value_name = "FILE", requires = "compare")]
    pub marking: Option<PathBuf>,

    /// With --compare: the font file the job was compiled with, when it is
    /// not the embedded font (its sha256 must match the job's).
    #[arg(long, value_name = "F")]
    pub font: Option<String>,

    /// Preview the film the arm would actually lay: run the job through the
    /// closed-loop simulator (`basr simulate`, default sjct controller) and
    /// deposit from the simulated nozzle instead of the setpoints.
    #[arg(long, conflicts_with = "compare")]
    pub from_sim: bool,
}

/// Finest raster cell, mm. A sixth of the fan sheet's default σ = 6 mm and
/// a tenth of the 90→10 % edge widths measured (9–10 mm on STOP): finer
/// shows nothing new; STOP took 23 s at 1 mm and 3.5 min (560 MB) at 0.5 mm.
const MIN_RESOLUTION_MM: f64 = 1.0;
/// Coarsest raster cell, mm: a fifth of the narrowest stroke of an 8 ft
/// letter (one grid unit, 2.44 m / 25 = 97.6 mm; docs/marking.md). Coarser,
/// few cells lie inside a stroke with all their neighbours: STOP's cv 0.070
/// at 5 mm read 0.017 at 25 mm and overspray 0.026 → 0.077, and at 10⁹ mm
/// the metrics were empty.
const MAX_RESOLUTION_MM: f64 = 20.0;

/// `STOP.job.json` → `STOP.preview.svg` in the current folder: the
/// command in the name, so the default never lands on a user's own SVG
/// (a shape's job `logo.job.json` would otherwise write over `logo.svg`).
fn default_output(job: &Path) -> PathBuf {
    super::named_after_job(job, "preview.svg")
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let r = args
        .resolution_mm
        .unwrap_or(basr::paint::preview::DEFAULT_RESOLUTION_M * 1e3);
    let thresholds = Thresholds {
        cv_max: args.max_cv,
        coverage_min: args.min_coverage,
        overspray_max: args.max_overspray,
    };
    verdict::validate(&thresholds)?;
    if !(r.is_finite() && r > 0.0) {
        anyhow::bail!(
            "--resolution-mm {r}: give a cell size in millimetres above zero, \
             from {MIN_RESOLUTION_MM} to {MAX_RESOLUTION_MM} (default 5)"
        );
    }
    anyhow::ensure!(
        r >= MIN_RESOLUTION_MM,
        "--resolution-mm {r} is finer than the {MIN_RESOLUTION_MM} mm minimum: the film's \
         detail is the fan sheet's (σ 6 mm) and its edges' (≈ 10 mm), and finer cells only \
         cost time and memory (STOP at 0.5 mm: 3.5 min, 560 MB); give {MIN_RESOLUTION_MM} \
         to {MAX_RESOLUTION_MM}"
    );
    anyhow::ensure!(
        r <= MAX_RESOLUTION_MM,
        "--resolution-mm {r} is coarser than the {MAX_RESOLUTION_MM} mm maximum: cells wider \
         than a fifth of a one-unit stroke (98 mm at 8 ft) leave too few cells inside the \
         letters for coverage, cv and overspray to describe the film; give \
         {MIN_RESOLUTION_MM} to {MAX_RESOLUTION_MM}"
    );
    let mut opts = Options {
        resolution_m: r / 1000.0,
        profile: Profile::parse(args.profile.as_deref().unwrap_or("uniform"))?,
        depth: Depth::parse(&args.fan_depth)?,
        fit_cells: args
            .resolution_mm
            .is_none()
            .then_some(basr::paint::raster::FIT_CELLS),
        ..Options::default()
    };
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| default_output(&args.job));
    let mut inputs: Vec<(&str, &std::path::Path)> = vec![("the job", &args.job)];
    if let Some(f) = &args.font {
        inputs.push(("the font file (--font)", std::path::Path::new(f)));
    }
    if let Some(m) = &args.marking {
        inputs.push(("the marking file (--marking)", m));
    }
    super::refuse_clashes(&[("the SVG (-o)", &out)], &inputs)?;
    super::outputs::check("-o", &out, &["svg"])?;
    basr::io::check_writable(&out)?;
    let job = super::read_job(&args.job, &args.trust)?;
    // a correctly sealed job can still hold a tilt of 90° or a row at
    // t = 1e9 s: `basr check`'s content checks first (exit 2)
    super::simulate::content_checks(&job, &args.job)?;
    if args.profile.is_none() {
        opts.profile = basr::pipeline::film::job_profile(&job)?;
    }
    let origin = args.job.display().to_string();
    let not_carried = replan::not_recorded(&job);
    // (job, re-planned from the one given)
    let jobs: Vec<(Job, bool)> = if args.compare.is_empty() {
        vec![(job, false)]
    } else {
        let tilts: Vec<Tilt> = args
            .compare
            .iter()
            .map(|m| replan::parse_tilt(m))
            .collect::<anyhow::Result<_>>()?;
        // Re-planning is a compile (without its verifying simulation):
        // seconds for a scene.
        let spin = super::spinner(
            !global.quiet && !args.json,
            &format!("re-planning under {} tilt methods", tilts.len()),
        );
        let plan = if tilts.iter().any(|t| t.name() != job.layout.tilt_method) {
            let font = replan::replan_font(&job, &origin, args.font.as_deref(), "--compare")?;
            Some(replan::recover(
                &job,
                &origin,
                font,
                args.marking.as_deref(),
                "--compare",
            )?)
        } else {
            None
        };
        let mut v = Vec::new();
        for tilt in tilts {
            match &plan {
                Some(p) if job.layout.tilt_method != tilt.name() => {
                    v.push((replan::replan(&job, tilt, p)?, true))
                }
                _ => v.push((job.clone(), false)),
            }
        }
        spin.finish_and_clear();
        v
    };
    let replanned_lines = [
        ("re-planned from".to_string(), REPLANNED_FROM.to_string()),
        ("not carried".to_string(), not_carried.to_string()),
    ];
    let replanned_note = format!("re-planned from {REPLANNED_FROM}; not carried: {not_carried}");
    let bar = super::progress_bar(
        !global.quiet && !args.json,
        if args.from_sim {
            "simulating the arm, then painting"
        } else {
            "painting"
        },
    );
    // The film stage compile records in the job's summary (`paint::film`):
    // at the defaults both report the same figures.
    let how = FilmOptions {
        preview: opts.clone(),
        thresholds,
    };
    let films: Vec<JobFilm> = jobs
        .iter()
        .map(|(j, _)| {
            let progress = |done: usize, total: usize| {
                bar.set_length(total as u64);
                bar.set_position(done as u64);
            };
            if args.from_sim {
                preview_simulated(j, &opts, &progress).map(|p| film::judged(p, &thresholds))
            } else {
                film::film(j, &how, &progress).map_err(Into::into)
            }
            .with_context(|| format!("{origin}: preview"))
        })
        .collect::<anyhow::Result<_>>()?;
    bar.finish_and_clear();
    let (previews, verdicts): (Vec<Preview>, Vec<Verdict>) =
        films.into_iter().map(|f| (f.preview, f.verdict)).unzip();
    let panels: Vec<Panel> = jobs
        .iter()
        .zip(&previews)
        .zip(&verdicts)
        .map(|(((job, re), preview), verdict)| Panel {
            job,
            preview,
            verdict,
            from_sim: args.from_sim,
            replanned: re.then_some(&replanned_lines[..]),
        })
        .collect();
    let title = format!(
        "basr preview{}: {}",
        if args.from_sim {
            " of the SIMULATED arm"
        } else {
            ""
        },
        jobs[0].0.message.replace('\n', " / ")
    );
    let svg = preview::render_svg(&panels, &title);
    basr::io::write_atomic(&out, svg.as_bytes())?;

    if !global.quiet {
        for (((j, re), p), v) in jobs.iter().zip(&previews).zip(&verdicts) {
            let m = &p.metrics;
            let f = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{:.3}", v));
            note!(
                "{} [tilt {}{}]: coverage {}, cv {}, overspray {}, mean film {} µm (target {:.0}), U {}–{}",
                origin,
                j.layout.tilt_method,
                if *re { ", re-planned" } else { "" },
                f(m.coverage),
                f(m.cv),
                f(m.overspray),
                m.mean_film_m.map_or("–".into(), |v| format!("{:.0}", v * 1e6)),
                m.target_film_m * 1e6,
                f(m.u_min),
                f(m.u_max),
            );
            if args.resolution_mm.is_none() && (m.resolution_m - opts.resolution_m).abs() > 1e-12 {
                note!(
                    "  raster coarsened from {} mm to {} mm so this long job's film fits in \
                     memory (--resolution-mm chooses the cell and refuses what does not fit)",
                    basr::paint::raster::mm_text(opts.resolution_m),
                    basr::paint::raster::mm_text(m.resolution_m),
                );
            }
            note!("  {}", verdict_line(v));
        }
        if jobs.iter().any(|(_, re)| *re) {
            note!("note: {replanned_note}");
        }
        super::outputs::after_commit(format!("wrote {}", out.display()));
    }
    if args.json {
        let svg_name = out.display().to_string();
        let reports: Vec<JsonReport> = jobs
            .iter()
            .zip(&previews)
            .zip(&verdicts)
            .map(|(((j, re), p), v)| JsonReport {
                job: &origin,
                message: &j.message,
                tilt_method: &j.layout.tilt_method,
                profile: &p.profile,
                svg: Some(&svg_name),
                replanned: re.then_some(replanned_note.as_str()),
                from_sim: args.from_sim,
                verdict: v,
                metrics: &p.metrics,
            })
            .collect();
        let text = if reports.len() == 1 {
            serde_json::to_string_pretty(&reports[0])?
        } else {
            serde_json::to_string_pretty(&reports)?
        };
        basr::io::print_stdout(&(text + "\n"))?;
    }
    Ok(if verdicts.iter().all(Verdict::pass) {
        Outcome::Success
    } else {
        Outcome::Negative
    })
}

/// `verdict: PASS (cv 0.030 (≤ 0.050), …)` or `verdict: FAIL: cv …`.
pub fn verdict_line(v: &Verdict) -> String {
    if v.pass() {
        "film verdict: PASS (cv, coverage and overspray within the limits)".into()
    } else {
        format!("film verdict: FAIL: {}", v.reasons())
    }
}

/// One tick of the simulated arm: time, gun command, and the actual
/// nozzle point on the road with the deviations of height, fan direction
/// and tilt from the planned ([x, y, dz, dψ, dβ]).
struct SimTick {
    t_s: f64,
    paint: u8,
    actual: [f64; 5],
}

/// BASR's hydraulic simulation (SJCT), tick by tick.
fn hydraulic_track(
    job: &Job,
    robot: &basr::robot::Robot,
    progress: basr::paint::raster::Progress,
) -> anyhow::Result<Vec<SimTick>> {
    use basr::sim;
    let model = sim::SimModel::from_robot(robot)
        .map_err(|e| anyhow::anyhow!("the job's robot has no usable dynamics: {e}"))?;
    let sim_opts = sim::Options {
        controller: sim::ControllerKind::Sjct,
        tolerance_m: robot.control.accuracy_m,
        keep_trace: true,
        substeps: None,
        stop_over_m: None,
        waviness: true,
    };
    let outcome = sim::simulate(job, &model, &sim_opts, &mut |done, total| {
        // The simulation is the first half of the bar, the paint the second.
        progress(done as usize, 2 * total as usize)
    })?;
    // What the simulated joints add at a tick: the actual nozzle point, and
    // the deviations of height, fan direction and tilt from the planned.
    let tilt_of = |nut: f64| robot.tilt_from_nut(nut).ok();
    Ok(outcome
        .trace
        .iter()
        .map(|r| {
            let tilt_error = match (tilt_of(r.tilt_nut_m), tilt_of(r.tilt_nut_desired_m)) {
                (Some(a), Some(b)) => a - b,
                _ => 0.0,
            };
            SimTick {
                t_s: r.t_s,
                paint: r.paint,
                actual: [
                    r.x_m,
                    r.y_m,
                    // Vertical joint is positive down (docs/job.md).
                    -(r.vertical_m - r.vertical_desired_m),
                    (r.ee_yaw_rad - r.ee_yaw_desired_rad)
                        + (r.base_rot_rad - r.base_rot_desired_rad),
                    tilt_error,
                ],
            }
        })
        .collect())
}

/// An electric kind's servo simulation (`sim::servo_job::track`), tick by
/// tick: the followed joints' nozzle against the reference's.
fn servo_track(job: &Job) -> anyhow::Result<Vec<SimTick>> {
    let ticks = basr::sim::servo_job::track(job)?;
    let s = &job.samples;
    Ok(ticks
        .iter()
        .map(|t| {
            let st = &job.stations[s.station[t.index] as usize];
            let (a, w) = (&t.actual, &t.wanted);
            let road = st.base_to_road([a.x_m, a.y_m]);
            // The fan's deviation on its own branch (ψ with β, or ψ + π with −β).
            let d = basr::robot::kinematics::wrap_pi(a.yaw_rad - w.yaw_rad);
            let (dyaw, dtilt) = if d.abs() > std::f64::consts::FRAC_PI_2 {
                (
                    basr::robot::kinematics::wrap_pi(d + std::f64::consts::PI),
                    -a.tilt_rad - w.tilt_rad,
                )
            } else {
                (d, a.tilt_rad - w.tilt_rad)
            };
            SimTick {
                t_s: t.t_s,
                paint: s.paint[t.index],
                actual: [road[0], road[1], a.z_m - w.z_m, dyaw, dtilt],
            }
        })
        .collect())
}

/// The film from the simulated arm: each 5 ms trace tick gives the actual
/// nozzle position on the road; height, fan direction and tilt are the
/// planned ones (the job's rows, interpolated linearly as the preview of a
/// compiled job interpolates between them) corrected by the simulated
/// joints' deviations. U is measured on tiles at the job's own setpoint
/// times (the actual pose interpolated between ticks), so it compares with
/// the compiled job's U; tiles between 5 ms ticks, 0.8 mm apart, were
/// twisted end to end by servo jitter and spanned U 0.00–1.00 on STOP.
fn preview_simulated(
    job: &Job,
    opts: &Options,
    progress: basr::paint::raster::Progress,
) -> anyhow::Result<Preview> {
    use basr::paint::spray::{equivalent_fan, Pose};
    let track = match job.robot.basr() {
        Some(robot) => hydraulic_track(job, robot, progress)?,
        None => servo_track(job)?,
    };
    let s = &job.samples;
    let n = s.len();
    anyhow::ensure!(n > 0 && !track.is_empty(), "the job has no setpoints");
    let dt = job.control_period_s;
    let lerp = |a: f64, b: f64, f: f64| a + f * (b - a);
    // The planned (z, ψ, β) at time t, linear between rows.
    let planned = |t: f64| -> (f64, f64, f64) {
        let u = (t / dt).max(0.0);
        let i = (u.floor() as usize).min(n - 1);
        let j = (i + 1).min(n - 1);
        let f = (u - i as f64).clamp(0.0, 1.0);
        let (yaw_j, tilt_j) = equivalent_fan(s.yaw_rad[i], s.yaw_rad[j], s.tilt_rad[j]);
        (
            lerp(s.z_m[i], s.z_m[j], f),
            lerp(s.yaw_rad[i], yaw_j, f),
            lerp(s.tilt_rad[i], tilt_j, f),
        )
    };
    let trace = &track;
    let actual: Vec<[f64; 5]> = track.iter().map(|t| t.actual).collect();
    // On the job's road (docs/site.md): the station of the row at t.
    let station_at = |t: f64| s.station[((t / dt).max(0.0).floor() as usize).min(n - 1)];
    let pose = |t: f64, a: &[f64; 5], plan: (f64, f64, f64), gun: bool| {
        let p = Pose {
            t_s: t,
            x_m: a[0],
            y_m: a[1],
            z_m: plan.0 + a[2],
            yaw_rad: plan.1 + a[3],
            tilt_rad: plan.2 + a[4],
            gun,
        };
        basr::paint::preview::on_road(job, station_at(t) as usize, p)
    };
    let poses: Vec<Pose> = trace
        .iter()
        .zip(&actual)
        .map(|(r, a)| pose(r.t_s, a, planned(r.t_s), r.paint == 1))
        .collect();
    // Tiles: one pose per job row, the actual interpolated between ticks.
    let last = trace.len() - 1;
    let rows: Vec<Pose> = (0..n)
        .map(|i| {
            let t = s.t_s[i];
            let k = trace
                .partition_point(|r| r.t_s <= t)
                .saturating_sub(1)
                .min(last);
            let k1 = (k + 1).min(last);
            let span = trace[k1].t_s - trace[k].t_s;
            let f = if span > 0.0 {
                ((t - trace[k].t_s) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let a: [f64; 5] = std::array::from_fn(|c| lerp(actual[k][c], actual[k1][c], f));
            let plan = (s.z_m[i], s.yaw_rad[i], s.tilt_rad[i]);
            pose(t, &a, plan, s.paint[i] != 0)
        })
        .collect();
    // ...thinned to the sheet's depth of nozzle travel (36 mm at the default
    // σ = 6 mm), at least a raster cell. The film at a point is laid by
    // every pose whose sheet passes over it, so it cannot show what happens
    // within less travel than that; the arm's wobble does (its 9 Hz linkage
    // mode, 001 table 3.2, has an 18 mm wavelength at 0.16 m/s and turns the
    // nozzle's direction by ±20° within a 5 mm row), and tiles of one row
    // measured it: U 0.03–0.97 on STOP. For a constant curvature U does not
    // depend on a tile's length, so the longer tiles keep the compiled job's
    // U. A new stroke or gun state always starts a tile.
    let tile_travel_m = opts.resolution_m.max(2.0 * opts.depth.reach_m());
    let mut tiles: Vec<Pose> = Vec::with_capacity(n);
    let mut tile_strokes: Vec<i64> = Vec::with_capacity(n);
    for (i, p) in rows.iter().enumerate() {
        let keep = match (tiles.last(), tile_strokes.last()) {
            (Some(q), Some(&st)) => {
                st != s.stroke[i]
                    || q.gun != p.gun
                    || i + 1 == n
                    || (p.x_m - q.x_m).hypot(p.y_m - q.y_m) >= tile_travel_m
            }
            _ => true,
        };
        if keep {
            tiles.push(*p);
            tile_strokes.push(s.stroke[i]);
        }
    }
    let outlines: Vec<_> = job
        .layout
        .glyphs
        .iter()
        .map(basr::paint::metrics::GlyphOutline::from_placed)
        .collect();
    Ok(preview::preview_tiled(
        poses,
        Some(&tiles),
        &tile_strokes,
        &outlines,
        &job.paint,
        opts,
        &|done, total| progress(total + done, 2 * total),
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_output_drops_job_suffixes() {
        assert_eq!(
            default_output(Path::new("a/STOP.job.json")),
            PathBuf::from("STOP.preview.svg")
        );
        assert_eq!(
            default_output(Path::new("x.json")),
            PathBuf::from("x.preview.svg")
        );
        assert_eq!(
            default_output(Path::new("plain")),
            PathBuf::from("plain.preview.svg")
        );
    }
}
