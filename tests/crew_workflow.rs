//! Issue 30, from the office to the truck: the documented workflows run in
//! one folder leave every input as it was and never put one command's
//! output over another's; hints suggest only what the user meant; NOT
//! READY is a negative verdict everywhere; marking files in feet.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{basr, stderr};

/// Run and require `code`, showing stderr when it differs.
fn expect(dir: &Path, args: &[&str], code: i32) -> Output {
    let out = basr(dir, args);
    assert_eq!(
        out.status.code(),
        Some(code),
        "basr {}: {}",
        args.join(" "),
        stderr(&out)
    );
    out
}

/// Every file under `dir` with its bytes.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                todo.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_path_buf();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// A filled rectangle, 1 × 2 units: a shape that decomposes at once.
const LOGO_SVG: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 20"><rect x="0" y="0" width="10" height="20" fill="black"/></svg>"#;

fn message_of(job: &Path) -> String {
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(job).unwrap()).unwrap();
    v["message"].as_str().unwrap().to_string()
}

/// README's session, its crew and signing steps, the symbols and scenes
/// and the custom shapes, in one folder: every input keeps its bytes, and
/// each command's default output carries the command's name.
#[test]
fn documented_workflows_keep_every_input_and_every_other_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::create_dir(d.join("markings")).unwrap();
    for m in ["rxr.toml", "stop_line.toml"] {
        std::fs::copy(repo.join("markings").join(m), d.join("markings").join(m)).unwrap();
    }
    std::fs::write(d.join("logo.svg"), LOGO_SVG).unwrap();
    // The user's own files, whatever basr's defaults are named.
    std::fs::write(d.join("STOP.svg"), "<svg>the user's drawing</svg>").unwrap();
    std::fs::write(d.join("STOP.html"), "<html>the user's page</html>").unwrap();
    let inputs = files(d);

    // README "A typical session" and "For crews".
    expect(d, &["compile", "STOP", "--csv", "STOP.csv", "-q"], 0);
    expect(d, &["preview", "STOP.job.json", "-q"], 0);
    assert!(d.join("STOP.preview.svg").exists());
    expect(d, &["check", "STOP.job.json"], 0);
    expect(d, &["report", "STOP.job.json", "--no-sim", "-q"], 0);
    assert!(d.join("STOP.sheet.html").exists());
    expect(d, &["keygen", "-o", "crew.key", "-q"], 0);
    let key = std::fs::read(d.join("crew.key.pub")).unwrap();
    expect(
        d,
        &[
            "compile", "STOP", "--sign", "crew.key", "--csv", "stop.csv", "-q",
        ],
        0,
    );
    expect(
        d,
        &[
            "check",
            "--trust",
            "crew.key.pub",
            "STOP.job.json",
            "stop.csv",
        ],
        0,
    );

    // Symbols and scenes: the symbol's job and the scene's share a
    // default name; the second compile stops before any work.
    expect(d, &["compile", "--symbol", "rxr", "-q"], 0);
    let rxr = std::fs::read(d.join("rxr.job.json")).unwrap();
    let out = expect(d, &["compile", "--marking", "markings/rxr.toml"], 2);
    let err = stderr(&out);
    assert!(
        err.contains("rxr.job.json holds the job of \"[rxr]\"")
            && err.contains("-o rxr-scene.job.json")
            && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(d.join("rxr.job.json")).unwrap(), rxr);
    // The same symbol again (any case) replaces its own job.
    expect(d, &["compile", "--symbol", "RXR", "-q"], 0);
    assert_eq!(message_of(&d.join("rxr.job.json")), "[rxr]");

    // Custom shapes: the preview of logo.job.json is not logo.svg.
    expect(
        d,
        &[
            "compile",
            "--shape",
            "logo.svg",
            "--shape-height-m",
            "2",
            "-q",
        ],
        0,
    );
    expect(d, &["preview", "logo.job.json", "-q"], 0);
    assert!(d.join("logo.preview.svg").exists());

    // Every input as it was; the key pair unchanged by the later runs.
    let after = files(d);
    for (path, bytes) in &inputs {
        assert_eq!(
            after.get(path),
            Some(bytes),
            "{} changed or vanished",
            path.display()
        );
    }
    assert_eq!(std::fs::read(d.join("crew.key.pub")).unwrap(), key);
}

#[test]
fn a_default_name_holding_something_else_is_refused_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("GO.job.json"), "my notes, not a job").unwrap();
    let out = expect(d, &["compile", "GO"], 2);
    let err = stderr(&out);
    assert!(
        err.contains("GO.job.json exists and is not a job basr wrote") && err.contains("--force"),
        "{err}"
    );
    // Refused before the work: nothing was planned or announced.
    assert!(!err.contains("stop 1"), "{err}");
    assert_eq!(
        std::fs::read_to_string(d.join("GO.job.json")).unwrap(),
        "my notes, not a job"
    );
    expect(d, &["compile", "GO", "--force", "-q"], 0);
    assert_eq!(message_of(&d.join("GO.job.json")), "GO");
}

#[test]
fn a_misspelt_option_is_never_turned_into_message_text() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = expect(d, &["compile", "STOP", "--lane-widht", "12ft"], 2);
    let err = stderr(&out);
    assert!(err.contains("--lane-width"), "{err}");
    assert!(
        !err.contains("12ft\"") && !err.contains("quote it"),
        "{err}"
    );
    let out = expect(d, &["compile", "STOP", "--letter-heigth", "2"], 2);
    let err = stderr(&out);
    assert!(err.contains("--letter-height"), "{err}");
    assert!(
        !err.contains("STOP 2") && !err.contains("quote it"),
        "{err}"
    );
    let out = expect(d, &["compile", "STOP", "--letter-height", "8", "ft"], 2);
    let err = stderr(&out);
    assert!(
        err.contains("hint: write the number and its unit as one: --letter-height 8ft"),
        "{err}"
    );
    assert!(
        !err.contains("STOP FT") && !err.contains("quote it"),
        "{err}"
    );
    // The usual slip still gets its hint.
    let out = expect(d, &["compile", "STOP", "AHEAD", "--csv", "sa.csv"], 2);
    assert!(
        stderr(&out).contains("quote it: basr compile \"STOP AHEAD\""),
        "{}",
        stderr(&out)
    );
    // Nothing was compiled by any of these.
    assert!(files(d).is_empty());
}

#[test]
fn symbol_names_are_found_whatever_their_case_and_a_message_that_names_one_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A misspelt name: the nearest by edit distance, not the first in order.
    let out = expect(d, &["compile", "--symbol", "RXX"], 2);
    let err = stderr(&out);
    assert!(err.contains("nearest: rxr"), "{err}");
    let out = expect(d, &["compile", "--symbol", "stopline"], 2);
    assert!(
        stderr(&out).contains("nearest: stop-line"),
        "{}",
        stderr(&out)
    );
    // A message that is the symbol's name is painted as asked, with a word
    // about the symbol; one the font cannot paint names it in its error.
    let out = expect(d, &["compile", "R-X-R"], 2);
    let err = stderr(&out);
    assert!(err.contains("basr compile --symbol rxr"), "{err}");
    let out = expect(d, &["compile", "RR X-ING"], 2);
    assert!(
        stderr(&out).contains("basr compile --symbol rxr"),
        "{}",
        stderr(&out)
    );
}

/// NOT READY is a negative verdict: compile writes the job and exits 1,
/// its JSON says the verdict, `check` refuses the job (exit 1, naming the
/// verdict) unless asked only to validate, `report` says it first.
#[test]
fn not_ready_exits_1_everywhere_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = expect(
        d,
        &[
            "compile",
            "BB",
            "--letter-height",
            "5ft",
            "--low-speed",
            "--json",
            "--no-size-search",
        ],
        1,
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict"], "not ready", "{v}");
    // --no-size-search: no sizes searched, and --json says so
    assert!(v["sizes"].is_null(), "{v}");
    assert!(
        stderr(&out).contains("verdict: NOT READY"),
        "{}",
        stderr(&out)
    );
    let job = d.join("BB.job.json");
    assert!(job.exists(), "a NOT READY job is written all the same");
    let out = expect(d, &["check", "BB.job.json"], 1);
    let err = stderr(&out);
    assert!(
        err.contains("BB.job.json: verdict NOT READY")
            && err.contains("do not load it on the truck"),
        "{err}"
    );
    let out = expect(d, &["check", "--validate-only", "BB.job.json"], 0);
    assert!(
        stderr(&out).contains("ok (verdict NOT READY)"),
        "{}",
        stderr(&out)
    );
    let out = expect(d, &["report", "BB.job.json", "--no-sim"], 1);
    let err = stderr(&out);
    assert!(err.starts_with("NOT READY: wrote BB.sheet.html"), "{err}");
}

/// A job compile planned with the gentle tilt says so in its summary (D
/// at 6 ft: its first plan had problems); one planned as usual does not.
#[test]
fn a_gently_planned_job_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = expect(d, &["compile", "D", "--letter-height", "6ft"], 0);
    assert!(
        stderr(&out).contains("\n  tilt: planned gently (its first plan had problems"),
        "{}",
        stderr(&out)
    );
    let out = expect(d, &["compile", "D"], 0);
    assert!(!stderr(&out).contains("planned gently"), "{}", stderr(&out));
}

/// Q at 6 ft (the tail's tight bowl): its first plan, the seed's tip, has
/// problems; compile writes the first later plan that paints, the 509 tip
/// with the default quadrilateral tilt, and says which tip to mount (the
/// trapezoid method comes later in the list, `choice::choices`, and is not
/// needed). A tilt named with --tilt is kept even where the default paints.
#[test]
fn compile_writes_the_first_plan_that_paints_and_keeps_a_named_tilt() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let tilt_of = |job: &str| {
        let v: serde_json::Value =
            serde_json::from_slice(&std::fs::read(d.join(job)).unwrap()).unwrap();
        v["layout"]["tilt_method"].as_str().unwrap().to_string()
    };
    let out = expect(
        d,
        &["compile", "Q", "--letter-height", "6ft", "-o", "q.job.json"],
        0,
    );
    let err = stderr(&out);
    assert!(err.contains("\n  spray tip: 509 "), "{err}");
    assert!(err.contains("verdict: READY"), "{err}");
    assert!(!err.contains("tilt: trapezoid"), "{err}");
    assert_eq!(tilt_of("q.job.json"), "quadrilateral");
    // --json says the same; the job is the one the summary described
    let out = expect(
        d,
        &[
            "compile",
            "Q",
            "--letter-height",
            "6ft",
            "-o",
            "q2.job.json",
            "--json",
        ],
        0,
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["tilt"]["method"], "quadrilateral", "{v}");
    assert_eq!(
        std::fs::read(d.join("q.job.json")).unwrap(),
        std::fs::read(d.join("q2.job.json")).unwrap(),
        "the same bytes"
    );
    let out = expect(
        d,
        &[
            "compile",
            "Q",
            "--letter-height",
            "6ft",
            "--tilt",
            "trapezoid",
            "--no-size-search",
            "-o",
            "named.job.json",
        ],
        0,
    );
    let err = stderr(&out);
    assert!(err.contains("verdict: READY"), "{err}");
    assert_eq!(tilt_of("named.job.json"), "trapezoid");
    // a job that paints with the default keeps it
    expect(d, &["compile", "Q", "-o", "q8.job.json"], 0);
    assert_eq!(tilt_of("q8.job.json"), "quadrilateral");
}

/// A scene measured with a tape in feet compiles to the job of its metric
/// twin, and the summary then speaks feet and inches.
#[test]
fn a_marking_in_feet_is_its_metric_twin() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ft = 0.3048;
    std::fs::write(
        d.join("feet.toml"),
        "[marking]\nlane_width_ft = 12\n\n[[item]]\nsymbol = \"stop-line\"\nat_ft = [0, 0]\n\n\
         [[item]]\nword = \"GO\"\nat_ft = [0, \"72in\"]\nletter_height_ft = 8\n",
    )
    .unwrap();
    std::fs::write(
        d.join("metres.toml"),
        format!(
            "[marking]\nlane_width_m = {}\n\n[[item]]\nsymbol = \"stop-line\"\nat_m = [0.0, 0.0]\n\n\
             [[item]]\nword = \"GO\"\nat_m = [0.0, {}]\nletter_height_m = {}\n",
            12.0 * ft,
            // "72in" as written: 72 × 0.0254 m (one ulp from 6 × 0.3048).
            72.0 * 0.0254,
            8.0 * ft
        ),
    )
    .unwrap();
    let out = expect(
        d,
        &["compile", "--marking", "feet.toml", "-o", "feet.job.json"],
        0,
    );
    let feet_text = stderr(&out);
    expect(
        d,
        &[
            "compile",
            "--marking",
            "metres.toml",
            "-o",
            "metres.job.json",
            "-q",
        ],
        0,
    );
    let feet = std::fs::read(d.join("feet.job.json")).unwrap();
    let metres = std::fs::read(d.join("metres.job.json")).unwrap();
    assert!(feet == metres, "the jobs differ");
    // The file was in feet: so is the summary; --units metric says metres.
    assert!(
        feet_text.contains("stop 1: arm axis ")
            && feet_text.contains(" ft")
            && !feet_text.contains(" m past"),
        "{feet_text}"
    );
    let out = expect(
        d,
        &[
            "compile",
            "--marking",
            "feet.toml",
            "-o",
            "feet.job.json",
            "--units",
            "metric",
        ],
        0,
    );
    assert!(stderr(&out).contains(" m past"), "{}", stderr(&out));
}
