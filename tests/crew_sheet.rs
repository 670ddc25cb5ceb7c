//! Issue 30: a job sheet a crew reads in a minute — the verdict and the
//! one thing to do first, what to paint said per item (a symbol by its
//! name and size, not its name's letters), where to stop, what to load on
//! the truck, warnings grouped; the engineer's detail in an appendix; a
//! READY STOP sheet prints on at most 2 pages (Chromium, when installed).

use std::process::Command as Process;

mod common;
use common::{basr, browser, succeeded};

/// Pages of a PDF, counted by its page objects (`/Type /Page`, not
/// `/Pages`): independent of any PDF tool.
fn pdf_pages(pdf: &[u8]) -> usize {
    let text = String::from_utf8_lossy(pdf);
    text.match_indices("/Type /Page")
        .chain(text.match_indices("/Type/Page"))
        .filter(|(i, m)| !text[i + m.len()..].starts_with('s'))
        .count()
}

#[test]
fn a_ready_sheet_reads_in_a_minute_and_prints_on_two_pages() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = basr(d, &["compile", "STOP", "--csv", "STOP.csv", "-q"]);
    assert!(out.status.success());
    let out = basr(d, &["report", "STOP.job.json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(d.join("STOP.sheet.html")).unwrap();
    let crew = html.split("id=\"appendix\"").next().unwrap();
    for part in [
        ">READY<",
        "Paint it. First: Drive with the traffic",
        "1: the word STOP, 4 letters 2.44 m (8 ft) tall",
        "Load this on the truck",
        "Mount spray tip seed-63.5 (63.5° fan, 0.40 L/min, uniform flux) on the gun",
        "Copy STOP.job.json and STOP.csv (the setpoint CSV) to the truck",
        "basr check STOP.job.json STOP.csv",
        "No problem and no notice.",
    ] {
        assert!(crew.contains(part), "the crew's part lacks {part:?}");
    }
    // The engineer's detail is in the appendix, after the crew's part.
    assert!(!crew.contains("id=\"letters\"") && html.contains("id=\"letters\""));

    let Some(bin) = browser() else {
        eprintln!("skipping the page count: no headless Chromium (apt-get install chromium)");
        return;
    };
    let pdf = d.join("STOP.pdf");
    let out = Process::new(bin)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--no-pdf-header-footer",
        ])
        .arg(format!("--user-data-dir={}", d.join("profile").display()))
        .arg(format!("--print-to-pdf={}", pdf.display()))
        .arg(format!("file://{}", d.join("STOP.sheet.html").display()))
        .output()
        .unwrap();
    assert!(pdf.exists(), "{}", String::from_utf8_lossy(&out.stderr));
    let pages = pdf_pages(&std::fs::read(&pdf).unwrap());
    assert!(
        (1..=2).contains(&pages),
        "the READY STOP sheet prints on {pages} pages"
    );
}

#[test]
fn a_symbol_is_named_and_sized_and_a_not_ready_sheet_says_what_first() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert!(basr(d, &["compile", "--symbol", "stop-line", "-q"])
        .status
        .success());
    let out = basr(
        d,
        &[
            "report",
            "stop-line.job.json",
            "--no-sim",
            "--units",
            "us",
            "-q",
        ],
    );
    assert!(out.status.success());
    let html = std::fs::read_to_string(d.join("stop-line.sheet.html")).unwrap();
    assert!(
        html.contains("1: the symbol stop-line (") && html.contains(" across × "),
        "{html}"
    );
    assert!(
        !html.contains("letters,") && !html.contains("(11 letters"),
        "{html}"
    );
    // --units us: the truck's place in feet and inches.
    let stops = html.split("id=\"stops\"").nth(1).unwrap();
    assert!(
        stops.contains(" ft ") && !stops.contains(" m past"),
        "{stops}"
    );

    let out = basr(
        d,
        &[
            "compile",
            "BB",
            "--letter-height",
            "5ft",
            "--low-speed",
            "-q",
            "--no-size-search",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let out = basr(d, &["report", "BB.job.json", "--no-sim", "-q"]);
    assert_eq!(out.status.code(), Some(1));
    let html = std::fs::read_to_string(d.join("BB.sheet.html")).unwrap();
    let crew = html.split("id=\"appendix\"").next().unwrap();
    assert!(
        crew.contains("Do not paint this job. First fix: "),
        "{crew}"
    );
    // Grouped: one line per kind, not one per warning.
    let groups = crew.split("id=\"groups\"").nth(1).unwrap();
    let lines = groups.matches("<li class=\"problem\">").count();
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("BB.job.json")).unwrap()).unwrap();
    let problems = job["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|w| w["severity"] == "problem")
        .count();
    assert!(
        lines >= 1 && lines < problems,
        "{lines} lines for {problems} problems"
    );
}

/// `report --sim` takes a saved `basr simulate --json` result only for the
/// job it simulated (its `job_sha256`): another job's, or one that does
/// not name its job, is refused (exit 2) and no sheet is written.
#[test]
fn a_saved_simulation_of_another_job_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (job, h) in [("a.job.json", "8ft"), ("b.job.json", "9ft")] {
        let out = basr(
            d,
            &["compile", "STOP", "--letter-height", h, "-q", "-o", job],
        );
        assert!(out.status.code().is_some_and(|c| c <= 1));
    }
    let out = basr(d, &["simulate", "a.job.json", "--json"]);
    assert!(out.status.success());
    std::fs::write(d.join("sim.json"), &out.stdout).unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["job_sha256"].is_string(), "simulate names its job");
    // its own job: the sheet is written
    let own = basr(
        d,
        &[
            "report",
            "a.job.json",
            "--sim",
            "sim.json",
            "-o",
            "a.html",
            "-q",
        ],
    );
    assert!(
        own.status.success(),
        "{}",
        String::from_utf8_lossy(&own.stderr)
    );
    // another job's: refused, nothing written
    let other = basr(
        d,
        &["report", "b.job.json", "--sim", "sim.json", "-o", "b.html"],
    );
    let err = String::from_utf8_lossy(&other.stderr);
    assert_eq!(other.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the simulate result is of another job"),
        "{err}"
    );
    assert!(!d.join("b.html").exists());
    // a result that does not name its job
    let mut old = v.clone();
    old.as_object_mut().unwrap().remove("job_sha256");
    std::fs::write(d.join("old.json"), old.to_string()).unwrap();
    let out = basr(
        d,
        &["report", "a.job.json", "--sim", "old.json", "-o", "c.html"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("does not name the job"), "{err}");
    assert!(!d.join("c.html").exists());
}

/// A job that calls for another tip than the robot's first says which,
/// everywhere a crew or an integrator reads it: compile's `--json`, the
/// preview's header and the sheet's "At a glance" (the bicycle at 0.75 of
/// its size, whose wheels only the low-flow 509 paints evenly).
#[test]
fn a_job_that_calls_for_another_tip_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("bike.toml"),
        "[[item]]\nsymbol = \"bike\"\nat_m = [0.0, 0.0]\nscale = 0.75\n",
    )
    .unwrap();
    let v = common::json_of(basr(
        d,
        &[
            "compile",
            "--marking",
            "bike.toml",
            "--low-speed",
            "-o",
            "b.job.json",
            "--json",
        ],
    ));
    assert_eq!(v["tip"], "509", "{v}");
    assert_eq!(v["verdict"], "ready", "{v}");
    let out = basr(d, &["preview", "b.job.json", "-o", "b.svg", "-q"]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let svg = std::fs::read_to_string(d.join("b.svg")).unwrap();
    assert!(
        svg.contains("tip 509: fan 45.2°"),
        "the preview's spray line"
    );
    let out = basr(d, &["report", "b.job.json", "-o", "b.html"]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let html = std::fs::read_to_string(d.join("b.html")).unwrap();
    assert!(
        html.contains("spray tip</th><td>mount 509 (45.2° fan"),
        "the sheet's At a glance"
    );
    assert!(
        html.contains("Paint it. First: mount spray tip 509 (45.2° fan")
            && html.contains("on the gun; then drive with the traffic"),
        "the sheet's first thing to do"
    );
    // A tip tally counts one tip: started by a job of the seed's tip, it
    // names that tip and refuses the 509's job, writing nothing.
    succeeded(basr(d, &["compile", "STOP", "-q"]));
    let out = basr(
        d,
        &[
            "report",
            "STOP.job.json",
            "--tip-tally",
            "t.toml",
            "--no-sim",
        ],
    );
    assert!(out.status.success(), "{}", common::stderr(&out));
    let tally = std::fs::read_to_string(d.join("t.toml")).unwrap();
    assert!(tally.contains("tip = \"seed-63.5\""), "{tally}");
    let out = basr(
        d,
        &[
            "report",
            "b.job.json",
            "--tip-tally",
            "t.toml",
            "--no-sim",
            "-o",
            "b2.html",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", common::stderr(&out));
    assert!(
        common::stderr(&out).contains(
            "counts the paint through tip seed-63.5, but this job is planned for tip 509"
        ),
        "{}",
        common::stderr(&out)
    );
    assert!(!d.join("b2.html").exists());
    assert_eq!(std::fs::read_to_string(d.join("t.toml")).unwrap(), tally);
}

/// SCHOOL at 6 ft paints with each of its letters within the film's
/// bounds on its own (compile takes a plan other than its first only so),
/// and the sheet marks none of them OVER or FAIL (the OVER line itself:
/// src/report/html.rs's `a_letter_past_a_bound_of_a_passing_film_is_over_not_fail`).
#[test]
fn every_letter_of_a_small_word_that_paints_is_within_the_bounds() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = basr(
        d,
        &[
            "compile",
            "SCHOOL",
            "--letter-height",
            "6ft",
            "-o",
            "s.job.json",
            "-q",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "SCHOOL at 6 ft paints");
    let out = basr(d, &["report", "s.job.json", "--no-sim", "-q"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(d.join("s.sheet.html")).unwrap();
    assert!(html.contains(">READY WITH NOTES<"), "the job paints");
    // SCHOOL at 6 ft paints with its rungs' ends held in, at the default
    // tilt share: the sheet says the one and not the other.
    assert!(
        html.contains(
            "planned with: <strong>the rungs' ends held in from edges they meet \
             obliquely</strong>"
        ),
        "the sheet says how the job was planned"
    );
    assert!(!html.contains("the tilt gently"));
    let letters = html
        .split("<table id=\"letters\">")
        .nth(1)
        .and_then(|t| t.split("</table>").next())
        .expect("the letters table");
    let rows: Vec<&str> = letters.split("<tr>").skip(2).collect();
    assert_eq!(rows.len(), 6, "one row per letter of SCHOOL");
    assert!(
        rows.iter().all(|r| r.contains("PASS")),
        "every letter within: {letters}"
    );
}

/// A scene's stops are said from the item at the road's origin, not its
/// first line: an arrow 12 m before ONLY (at the origin) puts stop 2 past
/// ONLY, and the sheet must not say past the arrow (a truck 12 m off).
/// Two items of one name are told apart by number; an origin no item's
/// near edge lies at is said from the nearest item.
#[test]
fn a_scenes_stops_are_said_from_the_item_at_the_anchor() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("scene.toml"),
        "[marking]\nname = \"t\"\n[[item]]\nsymbol = \"arrow-left\"\nat_m = [0.0, -12.0]\n\
         [[item]]\nword = \"ONLY\"\nat_m = [0.0, 0.0]\nletter_height_ft = 8\n",
    )
    .unwrap();
    let out = basr(
        d,
        &["compile", "--marking", "scene.toml", "-o", "s.job.json"],
    );
    assert!(out.status.code().is_some_and(|c| c <= 1));
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("before the near edge of ONLY")
            && text.contains("past the near edge of ONLY"),
        "{text}"
    );
    assert!(!text.contains("edge of [arrow-left]"), "{text}");
    let out = basr(d, &["report", "s.job.json", "--no-sim", "-q"]);
    assert!(out.status.success());
    let html = std::fs::read_to_string(d.join("s.sheet.html")).unwrap();
    assert!(
        html.contains("past the near edge of ONLY (the marking's anchor)"),
        "the sheet's stops"
    );

    // two arrows, the second at the origin: named by number
    let out = basr(
        d,
        &[
            "compile",
            "--marking",
            concat!(env!("CARGO_MANIFEST_DIR"), "/markings/turn_lane.toml"),
            "-o",
            "t.job.json",
        ],
    );
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("the near edge of item 2, [arrow-left]"),
        "{text}"
    );

    // a word moved 2 m past the origin: the origin said from it
    std::fs::write(
        d.join("moved.toml"),
        "[marking]\nlines = [\"STOP\"]\nanchor_y_m = 2.0\n",
    )
    .unwrap();
    let out = basr(
        d,
        &["compile", "--marking", "moved.toml", "-o", "m.job.json"],
    );
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("past the marking's anchor, 1.98 m before the near edge of STOP"),
        "{text}"
    );
}
