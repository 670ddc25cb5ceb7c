//! End-to-end: `basr import` and `basr compile --shape` on the test shapes
//! in tests/data/shapes, the round trip through the font file, and every
//! refused input (exit 2, the element named, nothing written).

use assert_cmd::Command;
use std::path::{Path, PathBuf};

fn basr() -> Command {
    Command::cargo_bin("basr").expect("binary built")
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/shapes")
        .join(name)
}

/// The setpoint arrays of a job (its `samples`), as JSON.
fn samples(job: &Path) -> serde_json::Value {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(job).expect("job")).expect("json");
    v["samples"].clone()
}

// Every test shape, each its own test so the harness runs them side by side.
#[test]
fn the_star_imports_checks_and_compiles() {
    imports_checks_and_compiles("star.svg", Some("2.4"));
}

#[test]
fn the_ring_imports_checks_and_compiles() {
    imports_checks_and_compiles("ring.svg", Some("2"));
}

#[test]
fn the_heart_imports_checks_and_compiles() {
    imports_checks_and_compiles("heart.svg", Some("2"));
}

#[test]
fn the_arch_imports_checks_and_compiles() {
    imports_checks_and_compiles("arch.svg", Some("2"));
}

#[test]
fn the_arrow_dxf_imports_checks_and_compiles() {
    imports_checks_and_compiles("arrow.dxf", None);
}

#[test]
fn the_shield_dxf_imports_checks_and_compiles() {
    imports_checks_and_compiles("shield.dxf", None);
}

fn imports_checks_and_compiles(name: &str, size: Option<&str>) {
    let dir = tempfile::tempdir().expect("tmp");
    let toml = dir.path().join(format!("{name}.toml"));
    let mut cmd = basr();
    cmd.arg("import").arg(data(name)).arg("-o").arg(&toml);
    if let Some(h) = size {
        cmd.args(["--shape-height-m", h]);
    }
    cmd.assert().success();
    basr().arg("check").arg(&toml).assert().success();
    let job = dir.path().join(format!("{name}.job.json"));
    let mut cmd = basr();
    cmd.args(["compile", "--shape"])
        .arg(data(name))
        .arg("-o")
        .arg(&job);
    if let Some(h) = size {
        cmd.args(["--shape-height-m", h]);
    }
    let out = cmd.output().expect("run");
    assert!(
        compiled(&out, &job),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&job).expect("job");
    assert!(
        text.contains("\"kind\": \"shape\""),
        "{name}: the job names the method"
    );
    // The job's message and layout name the shape by its file's stem.
    let v: serde_json::Value = serde_json::from_str(&text).expect("json");
    let stem = name.split('.').next().expect("stem");
    assert_eq!(v["message"], format!("[{stem}]"), "{name}");
    assert_eq!(v["layout"]["glyphs"][0]["char"], stem, "{name}");
}

#[test]
fn imported_ring_compiles_to_the_same_setpoints_as_shape() {
    let dir = tempfile::tempdir().expect("tmp");
    let toml = dir.path().join("ring.toml");
    basr()
        .arg("import")
        .arg(data("ring.svg"))
        .args(["--shape-height-m", "2", "-o"])
        .arg(&toml)
        .assert()
        .success();
    let a = dir.path().join("a.job.json");
    basr()
        .args(["compile", "--shape"])
        .arg(data("ring.svg"))
        .args(["--shape-height-m", "2", "-o"])
        .arg(&a)
        .assert()
        .success();
    let b = dir.path().join("b.job.json");
    basr()
        .args(["compile", "S", "--font"])
        .arg(&toml)
        .args(["--letter-height", "2", "-o"])
        .arg(&b)
        .assert()
        .success();
    let (sa, sb) = (samples(&a), samples(&b));
    assert!(sa["t_s"].as_array().is_some_and(|t| t.len() > 100));
    assert_eq!(sa, sb, "the font file holds the decomposition exactly");
}

#[test]
fn ring_is_painted_as_ring_following_bands() {
    let out = basr()
        .arg("import")
        .arg(data("ring.svg"))
        .args(["--shape-height-m", "2", "--json", "-o"])
        .arg(tempfile::tempdir().expect("tmp").path().join("r.toml"))
        .assert()
        .success()
        .get_output()
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(v["regions"][0]["method"], "ring-following bands");
    assert_eq!(v["strokes"], 4, "a quarter turn per band");
}

/// Import `body` as `name`: exit 2, stderr returned, no output left.
fn refused(name: &str, body: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("tmp");
    let input = dir.path().join(name);
    std::fs::write(&input, body).expect("write");
    let out_path = dir.path().join("out.toml");
    let out = basr()
        .arg("import")
        .arg(&input)
        .arg("-o")
        .arg(&out_path)
        .args(extra)
        .assert()
        .code(2)
        .get_output()
        .clone();
    assert!(!out_path.exists(), "{name}: nothing is written");
    let listing: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
    assert_eq!(listing.len(), 1, "{name}: no temporary file left");
    String::from_utf8_lossy(&out.stderr).to_string()
}

const H: [&str; 2] = ["--shape-height-m", "2"];

#[test]
fn bad_shapes_are_refused_with_the_element_and_the_fix() {
    let svg = |inner: &str| {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 100 100\">\n{inner}\n</svg>\n"
        )
    };
    let e = refused(
        "t.svg",
        &svg("<rect width=\"10\" height=\"10\"/>\n<text id=\"label\" x=\"5\" y=\"5\">HI</text>"),
        &H,
    );
    assert!(
        e.contains("line 3") && e.contains("label") && e.contains("Object to Path"),
        "{e}"
    );
    let e = refused(
        "s.svg",
        &svg("<path id=\"outline\" fill=\"none\" stroke=\"black\" d=\"M 0,0 L 50,50 L 0,50 Z\"/>"),
        &H,
    );
    assert!(
        e.contains("outline") && e.contains("only stroked") && e.contains("Stroke to Path"),
        "{e}"
    );
    let e = refused(
        "o.svg",
        &svg("<path id=\"hook\" d=\"M 0,0 L 50,50 L 0,50\"/>"),
        &H,
    );
    assert!(
        e.contains("hook") && e.contains("open subpath") && e.contains("Z"),
        "{e}"
    );
    let e = refused("e.svg", "", &H);
    assert!(e.contains("empty"), "{e}");
    let e = refused("n.svg", &svg(""), &H);
    assert!(e.contains("no filled shape"), "{e}");
    // The same square twice under even-odd: nothing is left filled.
    let e = refused(
        "x.svg",
        &svg("<path id=\"twice\" fill-rule=\"evenodd\" d=\"M 0,0 H 50 V 50 H 0 Z M 0,0 H 50 V 50 H 0 Z\"/>"),
        &H,
    );
    assert!(e.contains("twice") && e.contains("crosses itself"), "{e}");
    let e = refused(
        "b.svg",
        &svg("<rect width=\"10\" height=\"10\"/>"),
        &["--shape-height-m", "12"],
    );
    assert!(e.contains("0.3–10 m"), "{e}");
    let e = refused("u.svg", &svg("<rect width=\"10\" height=\"10\"/>"), &[]);
    assert!(e.contains("--shape-height-m"), "{e}");
    let e = refused("w.txt", "hello", &H);
    assert!(e.contains(".svg") && e.contains(".dxf"), "{e}");
}

#[test]
fn open_dxf_polyline_is_refused_by_handle() {
    let text = std::fs::read_to_string(data("arrow.dxf")).expect("arrow");
    // Clear the closed flag (group 70 = 1 → 0) of the one polyline.
    let open = text.replacen("\n70\n1\n", "\n70\n0\n", 1);
    assert_ne!(open, text);
    let e = refused("a.dxf", &open, &[]);
    assert!(
        e.contains("LWPOLYLINE (handle 2A)") && e.contains("PEDIT"),
        "{e}"
    );
}

#[test]
fn compile_refuses_a_size_without_a_shape() {
    basr()
        .args(["compile", "STOP", "--shape-height-m", "2"])
        .assert()
        .code(2);
}

#[test]
fn a_hatch_is_read_from_its_boundary_edges_with_its_hole() {
    // tests/data/shapes/shield.dxf: one HATCH, an edge loop of lines and an
    // arc (a 1.2 m square under a half disc) around a polyline hole of two
    // bulged sides (a disc of radius 0.25 m), metres.
    let out = basr()
        .arg("import")
        .arg(data("shield.dxf"))
        .args(["--json", "-o"])
        .arg(tempfile::tempdir().expect("tmp").path().join("s.toml"))
        .assert()
        .success()
        .get_output()
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let pi = std::f64::consts::PI;
    let want = 1.44 + 0.5 * pi * 0.36 - pi * 0.0625;
    let area = v["area_m2"].as_f64().expect("area");
    assert!((area - want).abs() < 0.002, "{area} vs {want}");
    assert!((v["height_m"].as_f64().expect("h") - 1.8).abs() < 1e-6);
    // The same hatch with a corrupt edge type is refused by handle and line.
    let text = std::fs::read_to_string(data("shield.dxf")).expect("shield");
    let bad = text.replacen("72\n2\n", "72\n7\n", 1);
    assert_ne!(bad, text);
    let e = refused("h.dxf", &bad, &[]);
    assert!(
        e.contains("HATCH (handle 4B)") && e.contains("edge type 7") && e.contains("line "),
        "{e}"
    );
}

/// A scene file in a temporary folder with ring.svg beside it.
fn scene_dir(items: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("tmp");
    std::fs::copy(data("ring.svg"), dir.path().join("ring.svg")).expect("copy");
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, items).expect("write");
    (dir, scene)
}

/// A compile that ran to its verdict and wrote `job`: exit 0, or exit 1
/// exactly when the job is NOT READY (a problem among its warnings).
fn compiled(out: &std::process::Output, job: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(job) else {
        return false;
    };
    let v: serde_json::Value = serde_json::from_str(&text).expect("json");
    let problem = v["summary"]["warnings"]
        .as_array()
        .expect("warnings")
        .iter()
        .any(|w| w["severity"] == "problem");
    out.status.code() == Some(if problem { 1 } else { 0 })
}

/// Compile a scene file to `job`; the job as JSON.
fn compile_scene(scene: &Path, job: &Path) -> serde_json::Value {
    let out = basr()
        .args(["compile", "--marking"])
        .arg(scene)
        .arg("-o")
        .arg(job)
        .output()
        .expect("run");
    assert!(
        compiled(&out, job),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(job).expect("job")).expect("json")
}

#[test]
fn a_scene_with_a_shape_item_compiles_previews_and_simulates() {
    let scene = data("scene.toml");
    basr().arg("check").arg(&scene).assert().success();
    let dir = tempfile::tempdir().expect("tmp");
    let job = dir.path().join("scene.job.json");
    let v = compile_scene(&scene, &job);
    assert_eq!(v["message"], "[ring]\n[arrow-through]");
    let chars: Vec<_> = v["layout"]["glyphs"]
        .as_array()
        .expect("glyphs")
        .iter()
        .map(|g| g["char"].as_str().unwrap_or("").to_string())
        .collect();
    assert_eq!(chars, ["ring", "arrow-through"]);
    // The job says how the ring was decomposed and why, as a `--shape`
    // job does: the method kept and the candidates' measured film.
    let shape: Vec<&str> = v["summary"]["warnings"]
        .as_array()
        .expect("warnings")
        .iter()
        .filter(|w| w["kind"] == "shape")
        .inspect(|w| assert_eq!(w["severity"], "info", "{w}"))
        .filter_map(|w| w["message"].as_str())
        .collect();
    assert!(
        shape
            .iter()
            .any(|m| m.starts_with("shape ring: region 1: ") && m.contains("ring-following bands")),
        "{shape:#?}"
    );
    assert!(
        shape
            .iter()
            .any(|m| m.starts_with("shape ring:   kept: ring-following bands: cv ")),
        "{shape:#?}"
    );
    basr()
        .arg("preview")
        .arg(&job)
        .arg("-o")
        .arg(dir.path().join("scene.svg"))
        .assert()
        .success();
    basr().arg("simulate").arg(&job).assert().success();
}

#[test]
fn a_shape_item_is_placed_turned_and_checked_like_any_item() {
    let item = |extra: &str| {
        format!("[[item]]\nshape = \"ring.svg\"\nat_m = [0.0, 1.0]\nheight_m = 1.2\n{extra}")
    };
    // Turned a quarter turn about its anchor (the centre of its near edge):
    // the ring's centre moves from (0, 1.6) to (-0.6, 1.0).
    let (dir, scene) = scene_dir(&item("rotate_deg = 90\n"));
    let v = compile_scene(&scene, &dir.path().join("j.json"));
    let pts: Vec<(f64, f64)> = v["layout"]["glyphs"][0]["strokes"]
        .as_array()
        .expect("strokes")
        .iter()
        .flat_map(|s| ["left", "right"].map(|e| s[e].as_array().cloned().unwrap_or_default()))
        .flatten()
        .map(|p| (p[0].as_f64().unwrap_or(0.0), p[1].as_f64().unwrap_or(0.0)))
        .collect();
    assert!(!pts.is_empty());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    for (got, want) in [(x0, -1.2), (x1, 0.0), (y0, 0.4), (y1, 1.6)] {
        assert!((got - want).abs() < 0.01, "extent {x0} {x1} {y0} {y1}");
    }
    // Wider than the lane, a missing file, and two items on the same paint.
    for (text, want) in [
        (
            "[[item]]\nshape = \"ring.svg\"\nat_m = [0.0, 0.0]\nwidth_m = 4.0\n".to_string(),
            "lane",
        ),
        (
            "[[item]]\nshape = \"nope.svg\"\nat_m = [0.0, 0.0]\nheight_m = 2.0\n".to_string(),
            "nope.svg",
        ),
        (
            format!("{}[[item]]\nword = \"BIKE\"\nat_m = [0.0, 1.5]\n", item("")),
            "overlap",
        ),
    ] {
        let (dir, scene) = scene_dir(&text);
        let job = dir.path().join("j.json");
        let out = basr()
            .args(["compile", "--marking"])
            .arg(&scene)
            .arg("-o")
            .arg(&job)
            .assert()
            .code(2)
            .get_output()
            .clone();
        let e = String::from_utf8_lossy(&out.stderr);
        assert!(e.contains("item 1") && e.contains(want), "{want}: {e}");
        assert!(!job.exists());
        basr().arg("check").arg(&scene).assert().failure();
    }
}
