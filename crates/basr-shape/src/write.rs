//! The decomposition as a font file: one glyph, on a grid 25 units tall (so
//! `--letter-height` sizes it) and as wide as the shape, every stroke with
//! explicit polyline edges a person can review and edit.

use std::fmt::Write as _;

use kurbo::Point;

use super::decompose::Decomposition;
use crate::font::GRID_HEIGHT;

/// The glyph an imported shape is stored under ("S" for shape).
pub const GLYPH: char = 'S';
/// Coordinates are written to this many decimals (units). assumed: a
/// millionth of a unit is under a micrometre at 10 m, far below the arm's
/// accuracy, and keeps the file readable.
const DECIMALS: i32 = 6;

fn round(v: f64) -> f64 {
    let f = 10f64.powi(DECIMALS);
    let r = (v * f).round() / f;
    if r == 0.0 {
        0.0 // no "-0"
    } else {
        r
    }
}

/// The corners of a polyline edge (what `decompose` builds).
fn vertices(e: &basr_geom::Edge) -> Vec<Point> {
    let mut v = vec![e.start()];
    for seg in e.segments() {
        match seg {
            basr_geom::Segment::Line(l) => v.push(l.p1),
            other => v.extend(
                basr_geom::Edge::new(vec![other.clone()])
                    .map(|e| e.sample(17))
                    .unwrap_or_default()
                    .into_iter()
                    .skip(1),
            ),
        }
    }
    v
}

/// Points of an edge in units, rounded, without repeats.
fn units(pts: &[Point], per_m: f64) -> Vec<[f64; 2]> {
    let mut v: Vec<[f64; 2]> = vec![];
    for p in pts {
        let q = [round(p.x * per_m), round(p.y * per_m)];
        // Points closer than the edge's join tolerance would make a
        // degenerate segment.
        if v.last()
            .is_none_or(|l| (l[0] - q[0]).hypot(l[1] - q[1]) > 2.0 * basr_geom::JOIN_TOLERANCE)
        {
            v.push(q);
        }
    }
    v
}

fn edge_toml(pts: &[[f64; 2]]) -> String {
    let mut s = String::from("[\n");
    for w in pts.windows(2) {
        let _ = writeln!(
            s,
            "  {{ line = [[{}, {}], [{}, {}]] }},",
            w[0][0], w[0][1], w[1][0], w[1][1]
        );
    }
    s.push(']');
    s
}

/// The font file text. `height_m` is the shape's height on the road (the
/// letter height to compile it with); `source` names the file it came from.
/// `notes` are further header lines (how the decomposition was picked).
pub fn font_toml(
    d: &Decomposition,
    width_m: f64,
    height_m: f64,
    source: &str,
    notes: &[String],
) -> String {
    let per_m = GRID_HEIGHT / height_m;
    let width = round(width_m * per_m);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# basr shape: {source}, decomposed into strokes by `basr import`."
    );
    let _ = writeln!(
        s,
        "# Compile it with:  basr compile {GLYPH} --font THIS_FILE --letter-height {}",
        basr_io::show_num(height_m)
    );
    let _ = writeln!(
        s,
        "# Units: 25 = the shape's height ({} m); the grid is the shape's width.",
        basr_io::show_num(height_m)
    );
    let _ = writeln!(
        s,
        "# Same format as fonts/basr.toml (see its header); each stroke's edges are\n\
         # polylines. Edit, then check with `basr check THIS_FILE`."
    );
    for (i, r) in d.regions.iter().enumerate() {
        let _ = writeln!(
            s,
            "# region {}: {:.3} m², {} ({} strokes, predicted {:.0} s, film error {:.1} %)",
            i + 1,
            r.area_m2,
            r.chosen.method,
            r.chosen.strokes,
            r.chosen.time_s,
            100.0 * r.chosen.film_error
        );
        for o in &r.others {
            let _ = writeln!(
                s,
                "#   not chosen: {} ({} strokes, {:.0} s, film error {:.1} %)",
                o.method,
                o.strokes,
                o.time_s,
                100.0 * o.film_error
            );
        }
    }
    for n in notes {
        let _ = writeln!(s, "# {n}");
    }
    let _ = writeln!(s);
    let name = std::path::Path::new(source)
        .file_stem()
        .and_then(|n| n.to_str())
        .unwrap_or("shape")
        .replace('"', "'");
    let _ = writeln!(s, "name = \"shape {name}\"");
    // min_rung: the decomposition already cut tips at half the fan's
    // narrowest band; below a tenth of a unit a rung is a mistake.
    let _ = writeln!(
        s,
        "grid = {{ width = {width}, height = {}, min_rung = 0.1 }}",
        GRID_HEIGHT
    );
    for st in &d.strokes {
        let l = units(&vertices(&st.left), per_m);
        let r = units(&vertices(&st.right), per_m);
        let _ = writeln!(s, "\n[[glyphs.{GLYPH}.strokes]]");
        let _ = writeln!(s, "left = {}", edge_toml(&l));
        let _ = writeln!(s, "right = {}", edge_toml(&r));
    }
    s
}
