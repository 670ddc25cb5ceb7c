//! `basr preview` of a scene painted from several stops: an overview of the
//! whole scene with every stop numbered, one view per stop (each stop
//! exactly once), and tick labels that never run into each other; a job
//! painted from one stop keeps its single view.

use std::path::{Path, PathBuf};

use assert_cmd::Command;

fn basr(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::cargo_bin("basr")
        .unwrap()
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

fn marking(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("markings")
        .join(name)
}

/// Compile `what` (compile's arguments) in `dir` and preview the job
/// `job`; the preview's SVG text and the job's number of stations.
fn preview(dir: &Path, what: &[&str], job: &str) -> (String, usize) {
    let mut args = vec!["compile"];
    args.extend_from_slice(what);
    args.push("--quiet");
    let out = basr(dir, &args);
    assert!(
        dir.join(job).exists(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = basr(dir, &["preview", job, "--quiet"]);
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg_name = job.replace(".job.json", ".preview.svg");
    let svg = std::fs::read_to_string(dir.join(svg_name)).unwrap();
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(job)).unwrap()).unwrap();
    let stations = doc["stations"].as_array().unwrap().len();
    (svg, stations)
}

/// Each `<text>` in `s`: its attribute `x`, `y` and its words.
fn texts(s: &str) -> Vec<(f64, f64, String)> {
    let attr = |tag: &str, name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let at = tag.find(&key).unwrap() + key.len();
        tag[at..tag[at..].find('"').unwrap() + at].parse().unwrap()
    };
    s.split("<text")
        .skip(1)
        .map(|t| {
            let close = t.find('>').unwrap();
            let tag = &t[..close];
            let body = &t[close + 1..t.find("</text>").unwrap()];
            (attr(tag, "x"), attr(tag, "y"), body.trim().to_string())
        })
        .collect()
}

/// The SVG from each view group's start (`class="view" id="…"`) to the
/// next one's, by id.
fn views(svg: &str) -> Vec<(String, &str)> {
    let starts: Vec<usize> = svg
        .match_indices("class=\"view\"")
        .map(|(i, _)| i)
        .collect();
    starts
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let end = starts.get(k + 1).copied().unwrap_or(svg.len());
            let part = &svg[i..end];
            let id = part.split("id=\"").nth(1).unwrap();
            (id[..id.find('"').unwrap()].to_string(), part)
        })
        .collect()
}

/// The tick labels of the first group of `class` in `view`.
fn ticks(view: &str, class: &str) -> Vec<(f64, f64, String)> {
    let key = format!("<g class=\"{class}\">");
    let Some(at) = view.find(&key) else {
        return Vec::new();
    };
    let body = &view[at..];
    texts(&body[..body.find("</g>").unwrap()])
}

/// Within every view: at least two x and two y tick labels, neighbouring x
/// labels apart by more than half of each one's width (10 px text, widths
/// as basr-plot estimates them), y labels farther apart than their height.
fn assert_ticks_clear(svg: &str) {
    let all = views(svg);
    assert!(!all.is_empty());
    for (id, view) in all {
        let mut xs = ticks(view, "ticks-x");
        let mut ys = ticks(view, "ticks-y");
        assert!(xs.len() >= 2 && ys.len() >= 2, "{id}: {xs:?} {ys:?}");
        xs.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in xs.windows(2) {
            let half = |t: &str| basr::plot::text_width_px(t, 10.0) / 2.0;
            let room = w[1].0 - w[0].0;
            assert!(
                room >= half(&w[0].2) + half(&w[1].2) + 2.0,
                "{id}: x labels {:?} and {:?} are {room} px apart",
                w[0].2,
                w[1].2
            );
        }
        ys.sort_by(|a, b| a.1.total_cmp(&b.1));
        for w in ys.windows(2) {
            let room = w[1].1 - w[0].1;
            assert!(
                room >= 12.0,
                "{id}: y labels {:?} and {:?} are {room} px apart",
                w[0].2,
                w[1].2
            );
        }
    }
}

#[test]
fn a_scene_of_four_stops_has_an_overview_and_each_stop_in_one_view() {
    let dir = tempfile::tempdir().unwrap();
    let m = marking("rxr.toml");
    let (svg, stations) = preview(
        dir.path(),
        &["--marking", m.to_str().unwrap()],
        "rxr.job.json",
    );
    // The RXR crossing is painted from four stops (two lines and the symbol
    // between them); one stop was once drawn twice and another nowhere.
    assert_eq!(stations, 4);
    let ids: Vec<String> = views(&svg).into_iter().map(|(id, _)| id).collect();
    let mut want = vec!["overview".to_string()];
    want.extend((1..=stations).map(|k| format!("stop-{k}")));
    assert_eq!(ids, want);
    for (id, view) in views(&svg) {
        let words: Vec<String> = texts(view).into_iter().map(|t| t.2).collect();
        let count = |w: &str| words.iter().filter(|t| *t == w).count();
        if id == "overview" {
            assert_eq!(count("Whole scene"), 1, "{words:?}");
            // Every stop numbered once, as the job sheet numbers them.
            for k in 1..=stations {
                assert_eq!(count(&format!("Stop {k}")), 1, "Stop {k}: {words:?}");
            }
            // Every item named: the two lines and the symbol.
            for item in ["1: [stop-line]", "2: [rxr]", "3: [stop-line]"] {
                assert_eq!(count(item), 1, "{item}: {words:?}");
            }
        } else {
            let k: usize = id["stop-".len()..].parse().unwrap();
            // The caption and the stop's own mark, no other stop's.
            assert_eq!(count(&format!("Stop {k}")), 2, "{id}: {words:?}");
            for other in (1..=stations).filter(|&o| o != k) {
                assert_eq!(count(&format!("Stop {other}")), 0, "{id}: {words:?}");
            }
            assert!(
                words.iter().any(|w| w.starts_with("paints ")),
                "{id}: {words:?}"
            );
            // What each stop paints: the first line whole, the symbol in
            // part from stops 2 and 3.
            let caption = words.join(" ");
            let says = match k {
                1 => "paints 1: [stop-line]",
                2 => "paints 2: [rxr] (part, with stop 3)",
                3 => "paints 2: [rxr] (part, with stop 2)",
                _ => "paints 3: [stop-line]",
            };
            assert!(caption.contains(says), "{id}: {caption}");
        }
    }
    assert_ticks_clear(&svg);
    // It still renders.
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    assert!(tree.size().width() > 900.0);
}

#[test]
fn a_job_from_one_stop_keeps_one_view_with_clear_ticks() {
    let dir = tempfile::tempdir().unwrap();
    let (svg, stations) = preview(dir.path(), &["STOP"], "STOP.job.json");
    assert_eq!(stations, 1);
    assert!(!svg.contains("id=\"overview\""));
    assert!(!svg.contains("id=\"stop-1\""));
    let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
    assert_eq!(words.iter().filter(|w| *w == "Stop 1").count(), 1);
    // The one panel's ticks (it is not a "view" group): 0.5 m apart.
    let xs = ticks(&svg, "ticks-x");
    let labels: Vec<&str> = xs.iter().map(|t| t.2.as_str()).collect();
    assert_eq!(labels, ["-1", "-0.5", "0", "0.5", "1"]);
    let ys = ticks(&svg, "ticks-y");
    assert!(ys.len() >= 8, "{ys:?}");
}

#[test]
fn a_two_line_job_from_one_stop_draws_the_stop_once() {
    // Letters 18 in tall, lines 1.83 m apart: both lines from one stop.
    let dir = tempfile::tempdir().unwrap();
    let (svg, stations) = preview(
        dir.path(),
        &[
            "GO NOW",
            "--letter-height",
            "18in",
            "--line-gap",
            "1.83",
            "-o",
            "GO_NOW.job.json",
            "--no-size-search",
        ],
        "GO_NOW.job.json",
    );
    assert_eq!(stations, 1);
    let ids: Vec<String> = views(&svg).into_iter().map(|(id, _)| id).collect();
    assert_eq!(ids, ["line-view-1", "line-view-2"]);
    let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
    assert_eq!(words.iter().filter(|w| *w == "Stop 1").count(), 1);
    assert_ticks_clear(&svg);
}
