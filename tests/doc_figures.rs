//! The README's figures that come from the binary (issue 28: docs that
//! cannot go stale): the controller table and the Monte Carlo example are
//! computed here as `basr compile MSG` and `basr simulate JOB --json`
//! compute them (the same library calls, at the commands' defaults) and
//! compared with the README's blocks between `<!-- doc-figures: NAME -->`
//! and `<!-- /doc-figures: NAME -->`. A difference fails with both texts;
//! `scripts/doc-figures.sh` writes the blocks anew
//! (`BASR_DOC_FIGURES=write` on this test).

use std::path::PathBuf;

use basr::job::Job;
use basr::layout::Overrides;
use basr::pipeline::compile::{compile_job, CompileRequest};
use basr::sim::{self, ControllerKind, Report, SimModel};

/// The jobs of the controller table: name, message, letter height.
const JOBS: [(&str, &str, Option<f64>); 3] = [
    ("STOP", "STOP", None),
    ("SCHOOL", "SCHOOL", None),
    ("STOP at full reach", "STOP", Some(3.6)),
];

/// The table's rows, the default first.
const ROWS: [ControllerKind; 4] = [
    ControllerKind::Sjct,
    ControllerKind::Dyninv,
    ControllerKind::Scct,
    ControllerKind::Pid,
];

/// What seed 000 says of each controller (the table's last column).
fn seed_says(k: ControllerKind) -> &'static str {
    match k.name() {
        "sjct" => "§III: \"the most stable and accurate\"; §I: letter S within 1/4 in",
        "dyninv" => "§III: \"very accurate but for large extensions not very stable\"",
        "scct" => {
            "§II: its Simulink model met 1/4 in; §III: \"very unstable … should not be used \
             without changes\""
        }
        _ => {
            "§III: \"stable behavior, but with lower accuracy\"; the older controller erred by \
             ~10 mm (000 app. A Figure 2.1)"
        }
    }
}

/// `basr compile` of one table job at the command's defaults (the film is
/// not measured: it does not change the setpoints).
fn compile(message: &str, letter_height_m: Option<f64>) -> Job {
    let mut req = CompileRequest::message(message);
    req.overrides = Overrides {
        letter_height_m,
        ..Overrides::default()
    };
    req.film = false;
    compile_job(&req).unwrap_or_else(|e| panic!("compile {message}: {e}"))
}

fn model(job: &Job) -> SimModel {
    SimModel::from_robot(job.robot.basr().expect("a BASR job")).expect("the robot simulates")
}

/// `basr simulate JOB --controller C --json` of `job`.
fn simulate(job: &Job, k: ControllerKind) -> Report {
    let opts = sim::Options {
        controller: k,
        ..Default::default()
    };
    sim::simulate(job, &model(job), &opts, &mut |_, _| {})
        .unwrap_or_else(|e| panic!("simulate with {}: {e}", k.name()))
        .report
}

/// The controller table and what it says of SCCT.
fn controllers() -> String {
    let jobs: Vec<Job> = JOBS.iter().map(|(_, m, h)| compile(m, *h)).collect();
    // The full-reach job's largest extension setpoint (m).
    let reach = jobs[2]
        .samples
        .extension_m
        .iter()
        .copied()
        .fold(0.0, f64::max);
    let mut s = format!(
        "Measured with `basr simulate JOB --controller C --json` on jobs compiled at\n\
         defaults (`basr compile STOP`, `basr compile SCHOOL`) and at full reach\n\
         (`basr compile STOP --letter-height 3.6`: R up to {reach:.2} m, its largest\n\
         extension setpoint), max / RMS nozzle\n\
         error while painting (`max_error_m`, `rms_error_m`; PID also the whole job's,\n\
         `max_error_all_m`), beside what seed 000 reports:\n\n\
         | controller | STOP | SCHOOL | STOP at {reach:.2} m reach | seed 000 |\n\
         | --- | --- | --- | --- | --- |\n"
    );
    let mut scct_fails = vec![];
    for k in ROWS {
        let name = if k == ControllerKind::Sjct {
            format!("{} (default)", k.name())
        } else {
            k.name().to_string()
        };
        s += &format!("| {name} |");
        for (job, (job_name, _, _)) in jobs.iter().zip(JOBS) {
            let r = simulate(job, k);
            s += &format!(
                " {:.2} / {:.2} mm, {}",
                r.max_error_m * 1e3,
                r.rms_error_m * 1e3,
                r.verdict
            );
            if k == ControllerKind::Pid {
                s += &format!(" (whole job {:.1})", r.max_error_all_m * 1e3);
            }
            s += " |";
            if k == ControllerKind::Scct && !r.passed() {
                scct_fails.push(format!("{job_name} ({:.2} mm)", r.max_error_m * 1e3));
            }
        }
        s += &format!(" {} |\n", seed_says(k));
    }
    if scct_fails.is_empty() {
        s += "\nSCCT meets the tolerance on all three jobs, as its Simulink model met it in seed 000 §II.\n";
    } else {
        s += &format!(
            "\n**Departure: SCCT does not meet the tolerance where seed 000 §II says its \
             Simulink model met 1/4 in (6.35 mm)**: it fails {} (max error while painting). \
             It is kept as a choice (`--controller scct`), not the default.\n",
            scct_fails.join(", ")
        );
    }
    s
}

/// The Monte Carlo example of the Uncertainty paragraph.
fn monte_carlo() -> String {
    let job = compile("STOP", None);
    let p = sim::plants::PlantsOptions {
        n: 40,
        spread: 0.1,
        seed: 7,
    };
    let summary = sim::plants::run(&job, &model(&job), &sim::Options::default(), &p)
        .unwrap_or_else(|e| panic!("40 plants of STOP: {e}"));
    let tolerance = sim::Options::default().tolerance_m;
    format!(
        "`basr simulate STOP.job.json --plants 40 --spread 0.1 --seed 7 --json` (STOP\n\
         compiled at defaults): p50 {:.2} mm, p95 {:.2} mm, worst {:.2} mm, {:.0} % of the\n\
         plants pass; the verdict, on p95 against {:.2} mm: {}{}.\n",
        summary.p50_max_error_m * 1e3,
        summary.p95_max_error_m * 1e3,
        summary.worst_max_error_m * 1e3,
        summary.pass_fraction * 100.0,
        tolerance * 1e3,
        if summary.p95_max_error_m <= tolerance {
            "pass"
        } else {
            "fail"
        },
        summary
            .deciding_parameter
            .map(|d| format!(" (most often deciding a failure: `{d}`)"))
            .unwrap_or_default()
    )
}

/// The text between `name`'s markers in `doc`, and where it lies.
fn block(doc: &str, name: &str) -> (std::ops::Range<usize>, String) {
    let begin = format!("<!-- doc-figures: {name} -->\n");
    let end = format!("<!-- /doc-figures: {name} -->");
    let b = doc
        .find(&begin)
        .unwrap_or_else(|| panic!("README.md has no line `{}`", begin.trim_end()))
        + begin.len();
    let e = doc[b..]
        .find(&end)
        .unwrap_or_else(|| panic!("README.md has no line `{end}` after its begin marker"))
        + b;
    (b..e, doc[b..e].to_string())
}

#[test]
fn readme_figures_are_what_the_binary_prints_now() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("README.md");
    let mut doc = std::fs::read_to_string(&path).expect("README.md reads");
    let write = std::env::var("BASR_DOC_FIGURES").as_deref() == Ok("write");
    let mut stale = vec![];
    for (name, now) in [
        ("controllers", controllers()),
        ("monte-carlo", monte_carlo()),
    ] {
        let (range, was) = block(&doc, name);
        if was != now {
            stale.push(format!(
                "README.md's `{name}` block:\n--- in the README\n{was}--- the binary now\n{now}"
            ));
            doc.replace_range(range, &now);
        }
    }
    if write {
        std::fs::write(&path, doc).expect("README.md writes");
        return;
    }
    assert!(
        stale.is_empty(),
        "{}\nrun scripts/doc-figures.sh to write them",
        stale.join("\n")
    );
}
