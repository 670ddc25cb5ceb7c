//! `basr report`: the job sheet rendered by a real browser (headless
//! Chromium): its DOM holds the sheet's parts and its screenshot is not
//! blank. Skips, saying so, when no Chromium can be found (`.ci/run`
//! installs Debian's `chromium`; `BASR_CHROMIUM` names another binary).

use std::path::Path;
use std::process::Command as Process;

use assert_cmd::Command;

mod common;
use common::browser;

fn chromium(bin: &Path, profile: &Path, args: &[&str], page: &Path) -> std::process::Output {
    Process::new(bin)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--no-first-run",
            "--disable-extensions",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap()
}

#[test]
fn the_job_sheet_renders_in_a_browser() {
    let dir = tempfile::tempdir().unwrap();
    let basr = |args: &[&str]| {
        Command::cargo_bin("basr")
            .unwrap()
            .current_dir(dir.path())
            .args(args)
            .output()
            .unwrap()
    };
    assert!(basr(&["compile", "STOP", "-q"]).status.success());
    let out = basr(&["report", "STOP.job.json", "-o", "STOP.html"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("READY: wrote STOP.html (the job sheet"),
        "{err}"
    );
    let page = dir.path().join("STOP.html");
    let html = std::fs::read_to_string(&page).unwrap();
    // Self-contained: nothing to fetch, nothing to run.
    for bad in [
        "src=\"http",
        "href=\"http",
        "url(",
        "@import",
        "<script",
        "<link",
    ] {
        assert!(!html.contains(bad), "the page holds {bad:?}");
    }

    let Some(bin) = browser() else {
        eprintln!(
            "skipping the browser half: no headless Chromium found \
             (apt-get install chromium, or set BASR_CHROMIUM)"
        );
        return;
    };
    let profile = dir.path().join("profile");
    let dom = chromium(&bin, &profile, &["--dump-dom"], &page);
    assert!(
        dom.status.success(),
        "{}",
        String::from_utf8_lossy(&dom.stderr)
    );
    let dom = String::from_utf8_lossy(&dom.stdout);
    for part in [
        "Job sheet: STOP",
        "id=\"overall\"",
        "time on site",
        "Stop 1.",
        "4.57 m past the near edge of STOP",
        "id=\"letters\"",
        "<svg",
        "arm accuracy (simulate)",
        "Warnings",
    ] {
        assert!(dom.contains(part), "the rendered page lacks {part:?}");
    }
    // One row per letter under the header.
    let letters = dom.split("id=\"letters\"").nth(1).unwrap();
    let table = letters.split("</table>").next().unwrap();
    assert_eq!(table.matches("<tr>").count(), 1 + 4, "{table}");

    let shot = dir.path().join("STOP.png");
    let out = chromium(
        &bin,
        &profile,
        &[
            // The film picture is in the appendix, below the crew's part.
            "--window-size=1200,4000",
            &format!("--screenshot={}", shot.display()),
        ],
        &page,
    );
    assert!(
        out.status.success() && shot.exists(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let decoder = png::Decoder::new(std::fs::File::open(&shot).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let px = info.line_size / info.width as usize;
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(px).collect();
    let inked = pixels
        .iter()
        .filter(|p| p[..3].iter().any(|&c| c < 200))
        .count();
    // The film's green (viridis near the target) and the verdict's red.
    let green = pixels
        .iter()
        .filter(|p| p[1] > 150 && p[0] < 120 && p[2] < 140)
        .count();
    let red = pixels
        .iter()
        .filter(|p| p[0] > 180 && p[1] < 80 && p[2] < 80)
        .count();
    let n = pixels.len();
    assert!(inked * 100 > n * 3, "only {inked} of {n} pixels inked");
    assert!(green > 1000, "{green} green pixels: no film picture");
    assert!(red > 50, "{red} red pixels: no verdict or outlines");
}
