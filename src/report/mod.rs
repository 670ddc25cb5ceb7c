//! The job sheet (`basr report`): what a crew and a supervisor need on one
//! printed page. [`build`] turns a job, its film preview and verdict, the
//! simulator's verdict and the crew's tip tally into a [`Sheet`] of plain
//! words and figures; [`html::render`] lays the sheet out as one
//! self-contained HTML page (inline CSS and SVG, nothing fetched).

pub mod html;
pub mod site;
pub mod tally;

use crate::job::{Job, Severity, Station, WarningKind};
use crate::paint::metrics::Metrics;
use crate::paint::verdict::Verdict;
use crate::units::System;

/// Time a truck move between two stations takes: pull forward a few
/// metres, stop, let the arm settle. // assumed: 1 min; the job does not
/// time truck moves yet (issue 11 adds them to the plan).
pub const TRUCK_MOVE_S: f64 = 60.0;

/// The simulator's verdict as the sheet shows it (from a run, or read back
/// from `basr simulate --json`).
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
pub struct SimVerdict {
    /// The job simulated (`basr simulate --json` writes it first; absent
    /// in results written before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub job_sha256: Option<String>,
    pub controller: String,
    pub verdict: crate::sim::report::Verdict,
    #[serde(default)]
    pub reasons: Vec<String>,
    pub max_error_m: f64,
    pub rms_error_m: f64,
    pub tolerance_m: f64,
    /// What `verdict` judges: the robot description's own run, or the
    /// 95th percentile over plants (`simulate --plants N`); absent in
    /// results written before it (the description's run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verdict_on: Option<crate::sim::report::VerdictOn>,
}

impl SimVerdict {
    pub fn from_report(r: &crate::sim::report::Report) -> SimVerdict {
        SimVerdict {
            job_sha256: None,
            controller: r.controller.clone(),
            verdict: r.verdict,
            reasons: r.reasons.clone(),
            max_error_m: r.max_error_m,
            rms_error_m: r.rms_error_m,
            tolerance_m: r.tolerance_m,
            verdict_on: Some(r.verdict_on),
        }
    }

    /// An electric kind's servo simulation (`sim::servo_job`).
    pub fn from_servo(r: &crate::sim::servo_job::ServoJobReport) -> SimVerdict {
        SimVerdict {
            job_sha256: None,
            controller: r.controller.clone(),
            verdict: r.verdict,
            reasons: r.reasons.clone(),
            max_error_m: r.max_error_m,
            rms_error_m: r.rms_error_m,
            tolerance_m: r.tolerance_m,
            verdict_on: Some(crate::sim::report::VerdictOn::Nominal),
        }
    }
}

/// What goes into a sheet.
pub struct Input<'a> {
    /// The job as the crew names it (its file name).
    pub job_name: &'a str,
    pub job: &'a Job,
    pub film: &'a Metrics,
    pub film_verdict: &'a Verdict,
    /// The film picture (an SVG document).
    pub film_svg: &'a str,
    pub sim: Option<&'a SimVerdict>,
    /// Paint through the current tip before this job, m³, when the crew
    /// keeps a tally.
    pub tip_used_before_m3: Option<f64>,
    /// Whether the job is signed, by which key and whether that was
    /// verified (`basr::job::trust::Seal::describe`).
    pub signature: &'a str,
    /// The crew's units for truck positions and sizes.
    pub units: System,
}

/// One truck stop in words.
#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    /// 1-based, as the crew counts.
    pub number: usize,
    pub instruction: String,
    /// Time the arm works at this stop, s.
    pub work_s: f64,
}

/// One letter (or marking item) with its film figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Letter {
    /// 1-based line and place in the line, as the text numbers them.
    pub line: usize,
    pub place: usize,
    pub char: String,
    pub mean_film_m: Option<f64>,
    /// Its cv, coverage and overspray against the bounds the whole film is
    /// judged by, in that order (`paint::verdict::glyph_checks`).
    pub checks: Vec<crate::paint::verdict::Check>,
}

impl Letter {
    /// Every figure within the film's bounds.
    pub fn pass(&self) -> bool {
        self.checks.iter().all(|c| c.pass)
    }
}

/// A warning as the sheet lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct Note {
    /// A job written before severities existed has its notes as notices.
    pub severity: Severity,
    pub text: String,
}

/// Everything the page shows, in words and SI figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    pub title: String,
    /// (label, value) lines of the job's identity.
    pub facts: Vec<(String, String)>,
    /// The message's lines and items, 1-based.
    pub items: Vec<String>,
    pub stops: Vec<Stop>,
    pub time_on_site_s: f64,
    pub paint_m3: f64,
    /// The tip to mount, in the crew's words (`tip_words`), when the
    /// robot lists tips.
    pub tip: Option<String>,
    /// The tip's life left after this job (min, max), m³, with a tally.
    pub tip_left_m3: Option<(f64, f64)>,
    pub tip_life_m3: (f64, f64),
    pub film_verdict: Verdict,
    pub film_lines: Vec<(String, String)>,
    pub film_svg: String,
    pub letters: Vec<Letter>,
    pub sim: Option<SimVerdict>,
    pub notes: Vec<Note>,
    /// `ready`, `ready with notes` or `not ready`.
    pub overall: &'static str,
    /// "Load this on the truck": which file goes to the controller, how to
    /// check it there, how each stop starts (docs/truck.md).
    pub truck: Vec<String>,
    /// The one thing to do first, under the verdict.
    pub first: String,
    /// Problems and notices grouped by kind, most frequent first: (severity,
    /// how many, what, the first one's text).
    pub groups: Vec<Group>,
    /// Each stop's reference points to chalk for `basr fit`.
    pub chalk: Vec<site::Chalk>,
    /// The fit procedure in plain words.
    pub fit_steps: String,
}

/// Warnings of one kind and severity, as one line of the sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    pub severity: &'static str,
    pub count: usize,
    /// What they are, in a few words (`paint outside a letter`).
    pub what: String,
    /// The first (worst) one's full text.
    pub example: String,
}

/// A warning kind in a few words for the crew.
fn kind_words(kind: WarningKind) -> String {
    match kind {
        WarningKind::HeightClamped => {
            "paint outside a stroke (the stroke is narrower than the fan)".into()
        }
        WarningKind::Slowed => "a heavy line where the arm slows down".into(),
        WarningKind::Film => "the paint film misses its limits".into(),
        WarningKind::Layout => "a layout rule the marking bends".into(),
        WarningKind::Passes => "a stroke painted in side-by-side passes".into(),
        WarningKind::Shape => "how a shape is painted".into(),
        WarningKind::Stop => "the arm comes to rest".into(),
        WarningKind::Surface => "the road's surface under the marking".into(),
        WarningKind::Arm => "the arm as it may be strays over the bound".into(),
    }
}

/// Problems and notices grouped by kind: problems first, then the most
/// frequent first; the first of each group is its worst as compile orders
/// them.
pub fn groups(job: &Job) -> Vec<Group> {
    let mut out: Vec<(Group, WarningKind)> = vec![];
    for w in &job.summary.warnings {
        let severity = match w.severity {
            Some(sev @ (Severity::Problem | Severity::Notice)) => sev.name(),
            _ => continue,
        };
        match out
            .iter_mut()
            .find(|(g, k)| g.severity == severity && *k == w.kind)
        {
            Some((g, _)) => g.count += 1,
            None => out.push((
                Group {
                    severity,
                    count: 1,
                    what: kind_words(w.kind),
                    example: w.message.clone(),
                },
                w.kind,
            )),
        }
    }
    let mut out: Vec<Group> = out.into_iter().map(|(g, _)| g).collect();
    out.sort_by(|a, b| {
        (a.severity != "problem")
            .cmp(&(b.severity != "problem"))
            .then(b.count.cmp(&a.count))
    });
    out
}

/// The one thing to do first: for NOT READY the worst group's fix, else
/// the first stop.
fn first_thing(
    overall: &str,
    groups: &[Group],
    stops: &[Stop],
    film_fails: bool,
    tip_change: Option<String>,
) -> String {
    match overall {
        "not ready" => match groups.iter().find(|g| g.severity == "problem") {
            Some(g) => format!(
                "Do not paint this job. First fix: {} ({} place{}); the engineer who planned it \
                 compiles it again. {}",
                g.what,
                g.count,
                if g.count == 1 { "" } else { "s" },
                g.example
            ),
            None if film_fails => "Do not paint this job: the paint film fails its limits \
                                   (see The paint film); ask the engineer who planned it."
                .into(),
            None => "Do not paint this job: the simulated arm misses its accuracy; ask the \
                     engineer who planned it."
                .into(),
        },
        _ => {
            let drive = stops
                .first()
                .map_or("place the truck as below.".into(), |s| {
                    s.instruction.clone()
                });
            // A tip other than the one the crew mounts by default comes
            // before the drive: it is changed at the depot, not in the lane.
            match tip_change {
                Some(t) => {
                    let mut c = drive.chars();
                    let drive: String = c
                        .next()
                        .map(|f| f.to_lowercase().chain(c).collect())
                        .unwrap_or_default();
                    format!("Paint it. First: mount spray tip {t} on the gun; then {drive}")
                }
                None => format!("Paint it. First: {drive}"),
            }
        }
    }
}

/// Time on site: the job's arm time and a truck move between stops.
pub fn time_on_site_s(job: &Job) -> f64 {
    let moves = job.stations.len().saturating_sub(1) as f64;
    job.summary.duration_s + moves * TRUCK_MOVE_S
}

/// What the stations are measured from, in words.
pub fn anchor_words(job: &Job) -> String {
    anchor_words_in(job, System::Metric)
}

/// How near a line's or item's near edge must lie to the road's origin to
/// be named as the anchor (m). assumed: a letter's round parts dip 2 cm
/// below its grid (O of 8 ft letters: 0.0195 m), which a crew marks at
/// the grid's edge; 5 cm is under any item's clear space.
const AT_ANCHOR_M: f64 = 0.05;

/// [`anchor_words`] in the crew's units. The stops are placed from the
/// road's origin: a message's anchor is the near edge of its first line
/// (`the near edge of STOP`), but a scene places its items around the
/// origin (`at_m`) and a marking file may move it (`anchor_y_m`): the line
/// or item whose near edge lies at the origin is named (with its number
/// where two share a name: `item 2, [arrow-left]`), else the origin is
/// said from the nearest one (`the marking's anchor, 30.48 m past the near
/// edge of item 1, [arrow-left]`). A job without letters says its first
/// line.
pub fn anchor_words_in(job: &Job, units: System) -> String {
    anchor_in(job, units).0
}

/// [`anchor_words_in`], and whether the words name the anchor itself
/// (`the marking's anchor, …`) rather than the item at it.
fn anchor_in(job: &Job, units: System) -> (String, bool) {
    let names: Vec<&str> = job.message.lines().collect();
    // each line's (a scene's item's) near edge: the lowest point of its
    // outlines, along the road
    let mut near: std::collections::BTreeMap<usize, f64> = Default::default();
    for g in &job.layout.glyphs {
        let low = g
            .strokes
            .iter()
            .flat_map(|s| s.left.iter().chain(&s.right))
            .map(|p| p[1])
            .fold(f64::INFINITY, f64::min);
        if low.is_finite() {
            let e = near.entry(g.line).or_insert(f64::INFINITY);
            *e = e.min(low);
        }
    }
    let label = |k: usize| {
        let name = names.get(k).copied().unwrap_or("the marking");
        if names.iter().filter(|n| **n == name).count() > 1 {
            let what = if name.starts_with('[') {
                "item"
            } else {
                "line"
            };
            format!("{what} {}, {name}", k + 1)
        } else {
            name.to_string()
        }
    };
    let nearest = near
        .iter()
        .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()).then(a.0.cmp(b.0)));
    match nearest {
        None => (
            format!(
                "the near edge of {}",
                names.first().unwrap_or(&"the marking")
            ),
            false,
        ),
        Some((&k, &y)) if y.abs() <= AT_ANCHOR_M => {
            (format!("the near edge of {}", label(k)), false)
        }
        Some((&k, &y)) => (
            format!(
                "the marking's anchor, {} {} the near edge of {}",
                units.length(y.abs()),
                if y < 0.0 { "past" } else { "before" },
                label(k)
            ),
            true,
        ),
    }
}

/// `ready`, `ready with notes` or `not ready` from the warnings'
/// severities (and any other failed verdict).
pub fn overall(severities: &[Severity], failed: bool) -> &'static str {
    if failed || severities.contains(&Severity::Problem) {
        "not ready"
    } else if severities.contains(&Severity::Notice) {
        "ready with notes"
    } else {
        "ready"
    }
}

/// Where a station's arm axis is, said from the anchor: `4.60 m past the
/// near edge of STOP, on the lane centre`.
pub fn place_words(s: &Station, anchor: &str) -> String {
    place_words_in(s, anchor, System::Metric)
}

/// [`place_words`] in the crew's units (`15 ft 1 in past …`).
pub fn place_words_in(s: &Station, anchor: &str, units: System) -> String {
    let along = if s.y_m >= 0.0 {
        format!("{} past {anchor}", units.length(s.y_m))
    } else {
        format!("{} before {anchor}", units.length(-s.y_m))
    };
    // +x is the approaching driver's right (road frame).
    let across = if s.x_m.abs() < 0.005 {
        "on the lane centre".to_string()
    } else if s.x_m > 0.0 {
        format!("{} right of the lane centre", units.length(s.x_m))
    } else {
        format!("{} left of the lane centre", units.length(-s.x_m))
    };
    // heading −π/2: the arm's axis points straight back against the traffic.
    let turn_deg = (s.heading_rad + std::f64::consts::FRAC_PI_2).to_degrees();
    let turn = if turn_deg.abs() < 0.5 {
        String::new()
    } else {
        format!(", the truck turned {turn_deg:+.1}° from the lane direction (counter-clockwise +)")
    };
    format!("{along}, {across}{turn}")
}

/// The stops in words: the first from the anchor, later ones as a drive
/// forward and the place reached.
pub fn stops(job: &Job) -> Vec<Stop> {
    stops_in(job, System::Metric)
}

/// [`stops`] in the crew's units.
pub fn stops_in(job: &Job, units: System) -> Vec<Stop> {
    let anchor = match anchor_in(job, units) {
        (words, true) => words,
        (words, false) => format!("{words} (the marking's anchor)"),
    };
    let n = job.stations.len();
    let mut work = vec![0.0; n];
    let s = &job.samples;
    for i in 0..s.len().saturating_sub(1) {
        if let Some(w) = work.get_mut(s.station[i] as usize) {
            *w += s.t_s[i + 1] - s.t_s[i];
        }
    }
    job.stations
        .iter()
        .enumerate()
        .map(|(k, st)| {
            let instruction = if k == 0 {
                format!(
                    "Drive with the traffic and stop the truck with the arm's rotation axis {}.",
                    place_words_in(st, &anchor, units)
                )
            } else {
                let prev = &job.stations[k - 1];
                let d = (st.x_m - prev.x_m).hypot(st.y_m - prev.y_m);
                let dir = if st.y_m >= prev.y_m {
                    "forward"
                } else {
                    "back"
                };
                format!(
                    "When stop {k} is painted, drive {} {dir} and stop with the axis {}.",
                    units.length(d),
                    place_words_in(st, &anchor, units)
                )
            };
            Stop {
                number: k + 1,
                instruction,
                work_s: work[k],
            }
        })
        .collect()
}

/// The letters with their figures, numbered as the text numbers them.
fn letters(m: &Metrics, v: &Verdict) -> Vec<Letter> {
    let mut place_in_line = std::collections::BTreeMap::<usize, usize>::new();
    m.glyphs
        .iter()
        .map(|g| {
            let place = place_in_line.entry(g.line).or_insert(0);
            *place += 1;
            Letter {
                line: g.line + 1,
                place: *place,
                char: g.char.clone(),
                mean_film_m: g.mean_film_m,
                checks: crate::paint::verdict::glyph_checks(g, &v.thresholds),
            }
        })
        .collect()
}

/// What to paint, one entry per line or item, 1-based: a word as its
/// letters and height, a symbol as its name, description and size, a
/// shape as its outline's size (all from the job's own outlines).
fn items(job: &Job, units: System) -> Vec<String> {
    let h = job.layout.letter_height_m;
    let lib = crate::font::Library::embedded();
    let both = |m: f64| match units {
        System::Us => format!("{} ({m:.2} m)", units.length(m)),
        System::Metric => format!("{m:.2} m ({})", System::Us.length(m)),
    };
    job.message
        .lines()
        .enumerate()
        .map(|(k, line)| {
            // The item's outline: its extent across and along the lane.
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for g in job.layout.glyphs.iter().filter(|g| g.line == k) {
                for st in &g.strokes {
                    for p in st.left.iter().chain(&st.right) {
                        for a in 0..2 {
                            lo[a] = lo[a].min(p[a]);
                            hi[a] = hi[a].max(p[a]);
                        }
                    }
                }
            }
            let size = if lo[0].is_finite() {
                format!(
                    "{} across × {} along the lane",
                    both(hi[0] - lo[0]),
                    both(hi[1] - lo[1])
                )
            } else {
                String::new()
            };
            let name = line.strip_prefix('[').and_then(|l| l.strip_suffix(']'));
            match name {
                Some(n) => match lib.get(n) {
                    Some(sym) => format!("{}: the symbol {n} ({}), {size}", k + 1, sym.description),
                    None => format!("{}: the shape {n} (a filled outline), {size}", k + 1),
                },
                None => {
                    let n = line.chars().filter(|c| !c.is_whitespace()).count();
                    format!(
                        "{}: the word {line}, {n} letter{} {} tall",
                        k + 1,
                        if n == 1 { "" } else { "s" },
                        both(h)
                    )
                }
            }
        })
        .collect()
}

/// The tip the job is planned for, in the crew's words (`511 (45.2° fan,
/// 0.29 L/min, uniform flux)`), when the robot lists tips.
pub fn tip_words(job: &Job) -> Option<String> {
    let name = job.paint.tip.as_ref()?;
    let p = job.robot.paint();
    Some(format!(
        "{name} ({:.1}° fan, {:.2} L/min, {} flux)",
        p.fan_angle_rad.to_degrees(),
        p.flow_m3ps * 60_000.0, // m³/s → L/min
        p.profile_text()
    ))
}

/// "Load this on the truck", in steps: the files the controller takes
/// (those bound to the job), the check on the truck, how each stop starts.
pub fn truck_steps(job: &Job, job_name: &str) -> Vec<String> {
    let name = std::path::Path::new(job_name).file_name().map_or_else(
        || job_name.to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let bound: Vec<(&str, &str)> = [
        ("csv", "the setpoint CSV"),
        ("adept", "the Adept V+ program"),
    ]
    .into_iter()
    .filter_map(|(k, what)| job.outputs.get(k).map(|b| (what, b.file.as_str())))
    .collect();
    let mut steps = vec![];
    if let Some(tip) = tip_words(job) {
        steps.push(format!(
            "Mount spray tip {tip} on the gun before the first stop: the job is planned for it."
        ));
    }
    if bound.is_empty() {
        steps.push(format!(
            "No setpoint file is bound to this job: compile it again with --csv FILE (the truck's \
             control computer) or --adept FILE (an Adept controller), and copy that file with {name}."
        ));
    } else {
        let files: Vec<String> = bound.iter().map(|(w, f)| format!("{f} ({w})")).collect();
        steps.push(format!(
            "Copy {name} and {} to the truck; the controller runs {}.",
            files.join(" and "),
            bound
                .iter()
                .map(|(_, f)| *f)
                .collect::<Vec<_>>()
                .join(" or ")
        ));
    }
    let files: Vec<&str> = std::iter::once(name.as_str())
        .chain(bound.iter().map(|(_, f)| *f))
        .collect();
    steps.push(match &job.signature {
        Some(sig) => format!(
            "On the truck, before loading: basr check --trust crew.key.pub {} (the key {} signed \
             it); load only on exit 0 and \"ok (verdict READY…)\".",
            files.join(" "),
            sig.key_id
        ),
        None => format!(
            "On the truck, before loading: basr check {} (exit 0 to load). The job is not signed: \
             sign it (compile --sign crew.key) so the truck can check who planned it (--trust).",
            files.join(" ")
        ),
    });
    steps.push(format!(
        "Each stop (1 to {}): place the truck as \"Where the truck stops\" says, bring the arm to \
         rest (retracted, middle) and zero its encoders, then run that stop's setpoints (CSV rows \
         with station = stop − 1; the Adept program from \"; stop N:\"). The gun switches itself.",
        job.stations.len()
    ));
    steps
}

/// Build the sheet.
pub fn build(input: &Input) -> Sheet {
    let job = input.job;
    let stops = stops_in(job, input.units);
    let time_on_site_s = time_on_site_s(job);
    let paint_m3 = job.summary.paint_volume_m3;
    let life = (
        job.robot.paint().tip_life_min_m3,
        job.robot.paint().tip_life_max_m3,
    );
    let tip_left_m3 = input
        .tip_used_before_m3
        .map(|used| (life.0 - used - paint_m3, life.1 - used - paint_m3));
    let notes: Vec<Note> = job
        .summary
        .warnings
        .iter()
        .map(|w| Note {
            severity: w.graded(),
            text: w.message.clone(),
        })
        .collect();
    let sim_fails = input
        .sim
        .is_some_and(|s| s.verdict != crate::sim::report::Verdict::Pass);
    let severities: Vec<Severity> = notes.iter().map(|n| n.severity).collect();
    let overall = overall(&severities, sim_fails || !input.film_verdict.pass());
    let m = input.film;
    let pct = |v: Option<f64>| v.map_or("–".into(), |v| format!("{:.1} %", v * 100.0));
    let film_lines = vec![
        (
            "mean film".into(),
            m.mean_film_m.map_or("–".into(), |f| {
                format!("{:.0} µm (target {:.0} µm)", f * 1e6, m.target_film_m * 1e6)
            }),
        ),
        ("evenness (cv)".into(), pct(m.cv)),
        ("coverage".into(), pct(m.coverage)),
        ("overspray".into(), pct(m.overspray)),
    ];
    let mut facts = vec![
        ("job file".into(), input.job_name.to_string()),
        ("job sha256".into(), job.sha256.chars().take(16).collect()),
        ("signature".into(), input.signature.to_string()),
        ("robot".into(), job.robot.name().to_string()),
        (
            "lane".into(),
            format!(
                "{:.2} m wide; tilt method {}",
                job.layout.lane_width_m, job.layout.tilt_method
            ),
        ),
    ];
    // How compile planned a job whose first plan had problems (the
    // engineer's to know: `basr fit` plans it so again).
    let options = job.layout.options.as_ref();
    let planned: Vec<&str> = [
        (
            options.is_some_and(|o| o.gentle_tilt),
            "the tilt gently (a smaller share of its joint's acceleration)",
        ),
        (
            options.is_some_and(|o| o.hold_ends),
            "the rungs' ends held in from edges they meet obliquely",
        ),
    ]
    .into_iter()
    .filter_map(|(on, words)| on.then_some(words))
    .collect();
    if !planned.is_empty() {
        facts.push(("planned with".into(), planned.join("; ")));
    }
    let groups = groups(job);
    let tip = tip_words(job);
    // The job's tip when it is not the robot's first (the one compile
    // prefers, and the crew mounts by default).
    let first_tip = job.robot.paint().tips.first().map(|t| t.name.as_str());
    let tip_change = tip
        .clone()
        .filter(|_| first_tip.is_some_and(|f| job.paint.tip.as_deref() != Some(f)));
    let first = first_thing(
        overall,
        &groups,
        &stops,
        !input.film_verdict.pass(),
        tip_change,
    );
    Sheet {
        title: job.message.replace('\n', " / "),
        facts,
        items: items(job, input.units),
        stops,
        time_on_site_s,
        paint_m3,
        tip,
        tip_left_m3,
        tip_life_m3: life,
        film_verdict: input.film_verdict.clone(),
        film_lines,
        film_svg: input.film_svg.to_string(),
        letters: letters(m, input.film_verdict),
        sim: input.sim.cloned(),
        truck: truck_steps(job, input.job_name),
        first,
        groups,
        notes,
        overall,
        chalk: site::chalk(job, input.units),
        fit_steps: site::steps(input.job_name),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn place_words_say_along_across_and_turn() {
        let st = |x_m, y_m, heading_rad| Station {
            x_m,
            y_m,
            heading_rad,
        };
        let down = -std::f64::consts::FRAC_PI_2;
        assert_eq!(
            place_words(&st(0.0, 4.6, down), "the near edge of STOP"),
            "4.60 m past the near edge of STOP, on the lane centre"
        );
        assert_eq!(
            place_words(&st(0.3, -1.0, down), "A"),
            "1.00 m before A, 0.30 m right of the lane centre"
        );
        assert!(place_words(&st(-0.3, 1.0, 0.0), "A")
            .contains("left of the lane centre, the truck turned +90.0°"));
    }
}
