//! `basr fit`: fit one stop of a job to where the truck really stopped and
//! to the road under it, from reference points the crew measured with the
//! arm, and re-plan that stop (docs/site.md).

use std::path::{Path, PathBuf};

use basr::job::{Job, Road};
use basr::pipeline::compile::{compile_job, Tilt};
use basr::plan::fit::{self, Measured};
use basr::plan::site::Site;
use serde::Deserialize;
use serde_json::json;

use super::{replan, Global, Outcome};

/// Fit a job's stop to where the truck stopped, and re-plan it.
///
/// At the stop, the crew chalks the reference points the job sheet lists
/// for it, jogs the nozzle over each and reads the arm's base-frame
/// position and the road's height there. Two or more points fix where the
/// truck stands (its axis and heading, least squares); three or more not
/// on a line also measure the road's surface as a plane. fit re-plans that
/// stop for the fitted pose and surface (joints, timing, closed-loop
/// verification, film), keeps the other stops, and writes a sealed job.
///
/// A point further than --tolerance-mm from where the others put it is
/// refused by name; a stop from which the arm cannot reach its marking is
/// refused with the move that brings it into reach.
///
/// Exit 0: the fitted job is written and READY (or READY WITH NOTES); 1:
/// it is written but NOT READY (its film or its arm fails there: `basr
/// report` says why); 2: bad input, nothing written.
#[derive(clap::Args)]
#[command(after_help = "Examples:
  basr fit STOP.job.json --points stop1.toml -o STOP.fit.job.json
  basr fit SCHOOL_XING.job.json --points stop2.toml --json
  basr fit scene.job.json --marking scene.toml --points p.toml --sign crew.key

The points file (TOML; lengths in metres):
  stop = 1                       # the stop, counted from 1 as on the job sheet
  [[point]]
  name = \"A\"                     # the job sheet's name (optional)
  road_m = [-1.074, 0.0]         # where the point is on the marking (road frame)
  base_m = [2.51, 3.88, 0.012]   # where the arm measured it (base frame):
                                 # x, y, and the road's height z under the tip
  # or, instead of base_m, the arm's encoder counts (named as the CSV's
  # enc_ columns) and the tip's height over the road when read:
  # encoders = { enc_base = 21500, enc_extension = 1234, enc_vertical = 800,
  #              enc_yaw = 0, enc_tilt = 0 }
  # tip_gap_m = 0.10             # (required with encoders)

JSON (--json): {\"job\", \"stop\", \"station\", \"planned_station\", \"moved\",
\"plane\", \"points\": [{\"name\", \"xy_m\", \"z_m\"}], \"verdict\", \"summary\",
\"sha256\", \"signed_by\"}; z_m is null without a plane.")]
pub struct Args {
    /// The job to fit (as compile wrote it).
    pub job: PathBuf,
    /// The measured points (TOML: `stop` and `[[point]]` tables).
    #[arg(long, value_name = "FILE")]
    pub points: PathBuf,
    /// The stop the points were measured at, counted from 1, where the
    /// file gives no `stop` (both given must agree).
    #[arg(long, value_name = "N")]
    pub stop: Option<usize>,
    /// The fitted job (default: JOB with `.fit` before `.job.json`).
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Sign the fitted job with this secret key (`basr keygen`).
    #[arg(long, value_name = "KEY")]
    pub sign: Option<PathBuf>,
    /// Largest distance (mm) between a point and where the fit puts it.
    #[arg(long, value_name = "MM", default_value_t = 10.0)]
    pub tolerance_mm: f64,
    /// The marking file a scene job was compiled from (a message or a
    /// library symbol is re-laid from the job itself).
    #[arg(long, value_name = "FILE")]
    pub marking: Option<PathBuf>,
    /// The font file the job was compiled with, if not the embedded one.
    #[arg(long, value_name = "F")]
    pub font: Option<String>,
    /// Also write the fitted job's setpoints as CSV (what the truck's
    /// controller loads; bound into the job as compile binds its own).
    #[arg(long, value_name = "CSV")]
    pub csv: Option<PathBuf>,
    /// Also write the fitted job as an Adept V+ program (as compile's).
    #[arg(long, value_name = "FILE")]
    pub adept: Option<PathBuf>,
    /// Print the fit as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,
}

/// Most points a file may hold. assumed: a crew measures three to six; a
/// hundred bounds the work of the outlier search (cubic in the points).
const MAX_POINTS: usize = 100;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PointsFile {
    stop: Option<usize>,
    #[serde(default)]
    point: Vec<PointToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PointToml {
    name: Option<String>,
    road_m: Vec<f64>,
    /// The arm's own reading: x, y, road height (m).
    base_m: Option<Vec<f64>>,
    /// Or its encoder counts, keyed by the setpoint CSV's column names.
    encoders: Option<std::collections::BTreeMap<String, i64>>,
    /// With `encoders`: the tip's height over the road when they were read
    /// (m; a shim's thickness, 0 touching).
    tip_gap_m: Option<f64>,
}

/// Where a point was measured, base frame: given, or from encoder counts
/// through the job's robot (forward kinematics; the road lies `tip_gap_m`
/// under the tip).
fn base_of(
    p: &PointToml,
    name: &str,
    robot: &basr::robot::AnyRobot,
    origin: &str,
) -> anyhow::Result<[f64; 3]> {
    match (&p.base_m, &p.encoders) {
        (Some(b), None) => {
            anyhow::ensure!(
                p.tip_gap_m.is_none(),
                "{origin}: point {name:?}: tip_gap_m goes with encoders, not base_m (base_m's \
                 z is the road's height already)"
            );
            match b[..] {
                [x, y, z] => Ok([x, y, z]),
                _ => anyhow::bail!(
                    "{origin}: point {name:?}: base_m has {} values; give three: [x, y, z] \
                     (m, the road's height under the tip third)",
                    b.len()
                ),
            }
        }
        (None, Some(e)) => {
            // The names the setpoint CSV (and `basr pose --json`) gives them.
            let names = robot.count_columns();
            let mut counts = [0i64; 5];
            for (k, n) in names.iter().enumerate() {
                counts[k] = *e.get(n).ok_or_else(|| {
                    anyhow::anyhow!(
                        "{origin}: point {name:?}: encoders lacks {n}; give all five: {}",
                        names.join(", ")
                    )
                })?;
            }
            if let Some(extra) = e.keys().find(|k| !names.contains(k)) {
                anyhow::bail!(
                    "{origin}: point {name:?}: encoders has {extra:?}, not a column of this \
                     robot; its encoders are {}",
                    names.join(", ")
                );
            }
            // a default would put the road at the tip: a nozzle that cannot
            // come within 78 mm of the road (BASR) would read it that high
            let gap = p.tip_gap_m.ok_or_else(|| {
                anyhow::anyhow!(
                    "{origin}: point {name:?}: encoders need tip_gap_m, the tip's height over \
                     the road when the counts were read (m; measure it with a rule)"
                )
            })?;
            anyhow::ensure!(
                gap.is_finite() && (0.0..=0.5).contains(&gap),
                "{origin}: point {name:?}: tip_gap_m {gap} m must be between 0 (touching) and \
                 0.5 m"
            );
            let q = robot.joints_from_encoders(&counts).map_err(|e| {
                anyhow::anyhow!("{origin}: point {name:?}: these counts are no pose: {e}")
            })?;
            // a count the joint cannot reach is a misread or mistyped count
            let (limits, joints) = (robot.limits(), robot.joint_names());
            for k in 0..5 {
                let l = &limits[k];
                // a part in a million of the range: the count's own rounding
                if l.excess(q[k]) > 1e-6 * (l.max - l.min) {
                    let (at, lo, hi) = (
                        basr::io::show_num(q[k]),
                        basr::io::show_num(l.min),
                        basr::io::show_num(l.max),
                    );
                    anyhow::bail!(
                        "{origin}: point {name:?}: {} = {} puts {} at {at}, outside its range \
                         {lo} to {hi}: check the count (`basr pose --json` prints a pose's)",
                        names[k],
                        counts[k],
                        joints[k]
                    );
                }
            }
            let pose = robot.fk(&q);
            Ok([pose.x_m, pose.y_m, pose.z_m - gap])
        }
        (Some(_), Some(_)) => {
            anyhow::bail!("{origin}: point {name:?} gives both base_m and encoders; give one")
        }
        (None, None) => anyhow::bail!(
            "{origin}: point {name:?} gives neither base_m = [x, y, z] nor encoders = {{ ... }}: \
             say where the arm measured it"
        ),
    }
}

/// Longest point name read (characters). assumed: the job sheet names
/// points A to D; a crew's own names are words, not paragraphs.
const MAX_NAME_CHARS: usize = 40;

/// The points file read and checked: the stop (from 0) and its points.
fn read_points(
    path: &Path,
    stop_arg: Option<usize>,
    robot: &basr::robot::AnyRobot,
    stops: usize,
) -> anyhow::Result<(usize, Vec<Measured>)> {
    let origin = path.display().to_string();
    let text = basr::io::read_text(path)?;
    let file: PointsFile = toml::from_str(&text).map_err(|e| {
        // what the file is, where it is plainly not TOML: the parser's own
        // words would point at a character
        let first = text
            .lines()
            .map(str::trim)
            .find(|l| !l.is_empty() && !l.starts_with('#'))
            .unwrap_or("");
        let what = if first.starts_with('{') {
            "it reads as JSON (a job?), not a points file".to_string()
        } else if first.contains(',') && !first.contains('=') && !first.starts_with('[') {
            "it reads as CSV (the setpoint CSV?), not a points file".to_string()
        } else {
            let at = e.span().map(|s| basr::io::line_col(&text, s.start));
            let at = at.map_or(String::new(), |(l, c)| format!("line {l}, column {c}: "));
            format!("{at}{}", basr::io::one_line(e.message()))
        };
        anyhow::anyhow!(
            "{origin}: {what}; a points file is TOML: `stop = 1` and [[point]] tables with \
             road_m = [x, y] and base_m = [x, y, z] (see basr fit --help)"
        )
    })?;
    let stop = match (stop_arg, file.stop) {
        (Some(a), Some(f)) if a != f => anyhow::bail!(
            "{origin} says stop = {f} but --stop {a} was given; the points belong to one stop"
        ),
        (Some(s), _) | (None, Some(s)) => s,
        (None, None) => anyhow::bail!(
            "{origin}: which stop were the points measured at? write `stop = N` (counted from 1 \
             as on the job sheet) or pass --stop N"
        ),
    };
    anyhow::ensure!(
        (1..=stops).contains(&stop),
        "{origin}: stop {stop} is not one of the job's stops (1 to {stops})"
    );
    anyhow::ensure!(
        file.point.len() <= MAX_POINTS,
        "{origin}: {} points; at most {MAX_POINTS} are read (three to six is usual)",
        file.point.len()
    );
    let mut out = Vec::with_capacity(file.point.len());
    for (i, p) in file.point.iter().enumerate() {
        let name = p.name.clone().unwrap_or_else(|| format!("point {}", i + 1));
        anyhow::ensure!(
            !name.trim().is_empty(),
            "{origin}: point {} has an empty name; name it as the job sheet does, or leave \
             name out",
            i + 1
        );
        // A name goes into messages and the job's notes: printable, and
        // short enough to read (the sheet's are one letter).
        anyhow::ensure!(
            !name.chars().any(char::is_control) && name.chars().count() <= MAX_NAME_CHARS,
            "{origin}: point {}'s name {:?} has control characters or is over \
             {MAX_NAME_CHARS} characters; name it as the job sheet does (A, B, C, D)",
            i + 1,
            name.chars().take(MAX_NAME_CHARS).collect::<String>()
        );
        let road: [f64; 2] = match p.road_m[..] {
            [x, y] => [x, y],
            _ => anyhow::bail!(
                "{origin}: point {name:?}: road_m has {} values; give two: [x, y] (m, from \
                 the job sheet)",
                p.road_m.len()
            ),
        };
        let base = base_of(p, &name, robot, &origin)?;
        anyhow::ensure!(
            road.iter().chain(&base).all(|v| v.is_finite()),
            "{origin}: point {name:?} has a value that is not a number ({:?}, {:?}); give \
             metres",
            road,
            base
        );
        // assumed: no marking lies 1 km from its anchor, and no arm reaches
        // 20 m; larger values are a unit or a typing slip.
        anyhow::ensure!(
            road.iter().all(|v| v.abs() <= 1000.0) && base.iter().all(|v| v.abs() <= 20.0),
            "{origin}: point {name:?} at road {road:?}, base {base:?} is not where a marking \
             and an arm are: give metres (road_m within 1 km of the anchor, base_m within \
             20 m of the arm's axis)"
        );
        anyhow::ensure!(
            !out.iter().any(|m: &Measured| m.name == name),
            "{origin}: two points are named {name:?}; give each its own name"
        );
        out.push(Measured { name, road, base });
    }
    Ok((stop - 1, out))
}

/// How far (m) from the outline of a stop's strokes a measured point may
/// lie and still be one of that stop's. assumed: a crew chalks the job
/// sheet's corners or other corners of the same strokes (on the outline);
/// a quarter metre takes one chalked a little beside its corner. A point
/// that near two stops' strokes is taken as the stop's the file names.
const ON_MARKING_M: f64 = 0.25;

/// Refuse points that cannot belong to stop `si`: a point off the marking
/// the job's stop paints (saying which stop paints it), or a road height
/// that is no road under the arm. (A measurement outside the arm's reach
/// as planned is a truck that stopped off: the fit says where to move.)
/// Which stop's a point is comes from the marking, not from the reach of
/// the stop as the job places it: a stop fitted with a turn may no longer
/// reach, as placed, a corner the crew chalked for it, and fitting it
/// again refused that point (the issue-29 audit).
fn check_frames(job: &Job, si: usize, points: &[Measured], origin: &str) -> anyhow::Result<()> {
    let parts = basr::job::reference::strokes_by_stop(job);
    let on = |k: usize, p: [f64; 2]| {
        parts.get(k).is_some_and(|strokes| {
            basr::job::reference::distance_to_strokes(strokes, p).is_some_and(|d| d <= ON_MARKING_M)
        })
    };
    for p in points {
        if !on(si, p.road) {
            let other = (0..job.stations.len()).find(|&k| on(k, p.road));
            match other {
                Some(k) => anyhow::bail!(
                    "{origin}: point {:?} at road ({:.3}, {:.3}) m is on stop {}'s part of the \
                     marking, not stop {}'s; measure stop {}'s points (the job sheet lists \
                     them) or set stop = {}",
                    p.name,
                    p.road[0],
                    p.road[1],
                    k + 1,
                    si + 1,
                    si + 1,
                    k + 1
                ),
                None => anyhow::bail!(
                    "{origin}: point {:?} at road ({:.3}, {:.3}) m is not on the marking any \
                     stop of this job paints; check its road_m against the job sheet",
                    p.name,
                    p.road[0],
                    p.road[1]
                ),
            }
        }
        anyhow::ensure!(
            p.base[2].abs() <= basr::job::road::MAX_PLANE_OFFSET_M,
            "{origin}: point {:?}'s road height {} m is more than {} m from the arm's base \
             level: base_m's third value is the road surface's height under the tip (m)",
            p.name,
            p.base[2],
            basr::job::road::MAX_PLANE_OFFSET_M
        );
    }
    Ok(())
}

/// The files bound to the job at `path` about to be replaced (`outputs`:
/// kind and file name), none when there is no such job or it cannot be
/// read as one.
fn replaced_bound(path: &Path) -> Vec<(String, String)> {
    #[derive(serde::Deserialize)]
    struct Bound {
        #[serde(default)]
        outputs: std::collections::BTreeMap<String, basr::job::BoundFile>,
    }
    let Ok(file) = std::fs::File::open(path) else {
        return vec![];
    };
    serde_json::from_reader::<_, Bound>(std::io::BufReader::new(file))
        .map(|b| b.outputs.into_iter().map(|(k, f)| (k, f.file)).collect())
        .unwrap_or_default()
}

/// The fitted job's path: `X.job.json` → `X.fit.job.json`.
fn default_output(job: &Path) -> PathBuf {
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "job.json".into());
    let stem = name
        .strip_suffix(".job.json")
        .or_else(|| name.strip_suffix(".json"))
        .unwrap_or(&name);
    job.with_file_name(format!("{stem}.fit.job.json"))
}

/// The rows of each station after the truck's drive to it (the leading
/// rows holding the stow pose), without their times: what must be the
/// same in the fitted job for every stop not fitted.
fn station_motion(job: &Job, si: usize) -> Vec<Vec<String>> {
    let s = &job.samples;
    let rows: Vec<Vec<String>> = (0..s.len())
        .filter(|&i| s.station[i] as usize == si)
        .map(|i| s.csv_fields(i).into_iter().skip(1).collect())
        .collect();
    let first = rows.first().cloned();
    let lead = rows
        .iter()
        .take_while(|r| Some(*r) == first.as_ref())
        .count();
    rows.into_iter().skip(lead.saturating_sub(1)).collect()
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    anyhow::ensure!(
        args.tolerance_mm.is_finite() && args.tolerance_mm > 0.0 && args.tolerance_mm <= 1000.0,
        "--tolerance-mm {} must be above 0 and at most 1000 (10 mm by default)",
        args.tolerance_mm
    );
    let origin = args.job.display().to_string();
    let job = super::read_job(&args.job, &args.trust)?;
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| default_output(&args.job));
    super::outputs::check("the fitted job", &out, &["json"])?;
    let mut outputs: Vec<(&str, &Path)> = vec![("the fitted job", &out)];
    if let Some(csv) = &args.csv {
        super::outputs::check("the setpoint CSV", csv, &["csv"])?;
        outputs.push(("the setpoint CSV", csv));
    }
    if let Some(adept) = &args.adept {
        outputs.push(("the Adept program", adept));
    }
    super::refuse_clashes(
        &outputs,
        &[("the job", &args.job), ("the points", &args.points)],
    )?;
    let key = args
        .sign
        .as_deref()
        .map(basr::job::trust::SecretKey::load)
        .transpose()?;
    for (_, p) in &outputs {
        basr::io::check_writable(p)?;
    }
    let points_origin = args.points.display().to_string();
    let (si, points) = read_points(&args.points, args.stop, &job.robot, job.stations.len())?;
    check_frames(&job, si, &points, &points_origin)?;
    let fitted = fit::fit(si + 1, &points, args.tolerance_mm * 1e-3)
        .map_err(|e| anyhow::anyhow!("{points_origin}: stop {}: {e}", si + 1))?;

    // The job's marking laid out again, with the fitted stop and road.
    let font = replan::replan_font(&job, &origin, args.font.as_deref(), "fit")?;
    let plan = replan::recover(&job, &origin, font, args.marking.as_deref(), "fit")?;
    let mut req = plan.request().clone();
    req.tilt = Tilt::of_job(&job.layout.tilt_method);
    req.tilt_named = true;
    let mut stations = job.stations.clone();
    stations[si] = fitted.station.clone();
    let mut road: Road = job.road.clone();
    road.planes.retain(|p| p.stop != si + 1);
    road.planes.extend(fitted.plane.clone());
    road.planes.sort_by_key(|p| p.stop);
    req.site = Some(Site {
        stations,
        fitted: si,
        road,
        kept: job.summary.stops.clone(),
        painted: basr::plan::site::painted_passes(&job.samples, job.stations.len()),
    });
    let spin = super::spinner(
        !global.quiet && !args.json,
        &format!("re-planning stop {} of {}", si + 1, job.stations.len()),
    );
    let planned = compile_job(&req);
    spin.finish_and_clear();
    let mut new = planned.map_err(|e| {
        // an error of the fitted stop's reach names the stop itself
        let what = match e {
            basr::pipeline::compile::CompileError::Stations(
                basr::plan::error::StationError::SiteOutOfReach { .. },
            ) => {
                format!("{origin}: re-planning")
            }
            _ => format!("{origin}: re-planning stop {}", si + 1),
        };
        anyhow::Error::new(e).context(what)
    })?;
    for k in (0..job.stations.len()).filter(|&k| k != si) {
        anyhow::ensure!(
            station_motion(&new, k) == station_motion(&job, k),
            "{origin}: re-planned, stop {} is not the job's, so fit cannot keep it as it was \
             (the marking file given with --marking, the font or the robot is not the one \
             the job was compiled from, or the job was written by another basr); give the \
             job's own files, or compile the job again and fit that; if they are the job's \
             own, report it with the job: this basr cannot re-plan it",
            k + 1
        );
    }
    // A fitted job replaced (a crew fitting again, or a second fit
    // without -o): the files bound to it stay beside it, no longer the
    // job's. Said after writing, for the files not written again now.
    let left_bound: Vec<(String, String)> = replaced_bound(&out)
        .into_iter()
        .filter(|(kind, _)| match kind.as_str() {
            "csv" => args.csv.is_none(),
            "adept" => args.adept.is_none(),
            _ => true,
        })
        .collect();
    super::outputs::write_job(
        &mut new,
        &out,
        args.csv.as_deref(),
        args.adept.as_deref(),
        key.as_ref(),
    )?;
    for (kind, file) in &left_bound {
        note!(
            "note: {} replaced a job whose {kind} file {file} stays beside it: that file is \
             not this job's (`basr check` refuses the pair); write this job's with --{kind} \
             FILE, or delete it",
            out.display()
        );
    }

    let planned_st = &job.stations[si];
    let st = &new.stations[si];
    let verdict = super::compile::verdict_of(&new);
    if args.json {
        let v = json!({
            "job": out.display().to_string(),
            "stop": si + 1,
            "station": st,
            "planned_station": planned_st,
            "moved": {
                "x_m": st.x_m - planned_st.x_m,
                "y_m": st.y_m - planned_st.y_m,
                "heading_rad": basr::robot::kinematics::wrap_pi(st.heading_rad - planned_st.heading_rad),
            },
            "plane": fitted.plane,
            "points": fitted.residuals,
            "verdict": verdict,
            "summary": new.summary,
            "sha256": new.sha256,
            "signed_by": new.signature.as_ref().map(|s| s.key_id.clone()),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    }
    if !global.quiet {
        // As the job sheet says a stop: from the anchor, turned from the lane.
        // A value that rounds to zero at the printed places is printed as
        // 0, not -0.000.
        let at = |v: f64, places: i32| {
            if v.abs() < 0.5 * 10f64.powi(-places) {
                0.0
            } else {
                v
            }
        };
        let turned = |h: f64| at((h + std::f64::consts::FRAC_PI_2).to_degrees(), 2);
        note!(
            "stop {}: the truck's axis is at x {:.3} m, y {:.3} m, turned {:+.2}° from the lane \
             direction (planned x {:.3} m, y {:.3} m, turned {:+.2}°)",
            si + 1,
            at(st.x_m, 3),
            at(st.y_m, 3),
            turned(st.heading_rad),
            at(planned_st.x_m, 3),
            at(planned_st.y_m, 3),
            turned(planned_st.heading_rad)
        );
        match &fitted.plane {
            Some(p) => note!(
                "road under the stop: a plane sloped {:.2} % along the arm's x and {:.2} % along \
                 its y, {:+.1} mm at its axis",
                at(p.dz_dx * 100.0, 2),
                at(p.dz_dy * 100.0, 2),
                at(p.z_m * 1e3, 1)
            ),
            None => note!(
                "road under the stop: as the job describes it (the points span no plane: give \
                 three or more, not on a line, at least {} m apart across it)",
                basr::plan::fit::MIN_PLANE_WIDTH_M
            ),
        }
        for r in &fitted.residuals {
            match r.z_m {
                Some(z) => note!(
                    "  {:<12} off by {:.1} mm on the road, {:+.1} mm in height",
                    r.name,
                    r.xy_m * 1e3,
                    basr::io::shown_as(z * 1e3, 1)
                ),
                None => note!("  {:<12} off by {:.1} mm on the road", r.name, r.xy_m * 1e3),
            }
        }
        if let (Some(c), Some(_)) = (job.road.crown_x_m, &fitted.plane) {
            let s = &job.samples;
            let xs = (0..s.len())
                .filter(|&i| s.station[i] as usize == si && s.paint[i] == 1)
                .map(|i| s.x_m[i]);
            let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
            if lo < c && c < hi {
                note!(
                    "note: the job's road has a crown line at x = {c:.2} m through this stop's \
                     marking; the plane the points measure replaces it under this stop, and \
                     one plane cannot follow a crown: check the fitted job's preview, or fit \
                     from two points to keep the job's crown under this stop"
                );
            }
        }
        if fitted.residuals.len() == 2 {
            note!(
                "note: two points fix the stop but cannot check each other: a point misread \
                 across the line between them moves the fit and shows in neither residual; \
                 chalk and measure a third (the job sheet lists three or four)"
            );
        }
        if job.signature.is_some() && key.is_none() {
            note!(
                "note: {origin} was signed; the fitted job is not (a truck that trusts only \
                 signed jobs refuses it): fit again with --sign KEY"
            );
        }
        if args.csv.is_none() && job.outputs.contains_key("csv") {
            note!(
                "note: the job's CSV is for the planned stop, not this one: write the fitted \
                 job's with --csv FILE and load that"
            );
        }
        note!(
            "wrote {} ({}: {:.1} s, stop {} re-planned)",
            out.display(),
            verdict.to_uppercase(),
            new.summary.duration_s,
            si + 1
        );
        if verdict == "not ready" {
            // Why, as compile says it; the notes' remedies are the
            // planner's (letter sizes, tips), which the crew cannot change
            // at the site: what it can do comes after.
            for line in super::compile::problem_lines(&new.summary.warnings, 8) {
                note!("{line}");
            }
            note!(
                "at the site: do not paint this stop as fitted. Check the points (a height \
                 read wrong tilts the fitted road), stand the truck where the job sheet says \
                 and level with the road it paints, and fit again; or ask the engineer who \
                 planned the job (letter sizes and tips are the planner's remedies above)"
            );
        }
    }
    // NOT READY is a negative verdict, as compile's: the job is written for
    // `basr report` to say why, and the exit code says not to paint it.
    Ok(if verdict == "not ready" {
        Outcome::Negative
    } else {
        Outcome::Success
    })
}
