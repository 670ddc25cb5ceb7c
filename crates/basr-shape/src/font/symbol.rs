//! The symbol library: arrows, lines, crosswalks and other road symbols,
//! written in the font format's natural extension (see the header of
//! `symbols/basr.toml`) and built into strokes in metres.
//!
//! A symbol's frame is the road frame of SPEC §2 at the symbol's anchor:
//! x across the lane (+ to the approaching driver's right), y along the
//! traffic, origin at the centre of the symbol's near edge. Loading shifts
//! the drawn strokes there (centred across, nearest point at y = 0), so a
//! symbol may be drawn in any convenient coordinates; its declared `size`
//! must match what the strokes span.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use kurbo::{Affine, Point};
use serde::Deserialize;
use toml::Spanned;

use super::build::{build_primitives, stroke, transform, Locator};
use super::spec::{PrimitiveSpec, StrokeSpec, TransformSpec};
use super::validate::{validate_glyph, Limits};
use super::{Font, Stroke, GRID_HEIGHT};

const EMBEDDED_SOURCE: &str = include_str!("../../../../symbols/basr.toml");
const EMBEDDED_ORIGIN: &str = "symbols/basr.toml";

/// How far the strokes' extent may differ from the declared `size`, as a
/// share of the larger dimension. assumed: 1 %, a drafting slip well below
/// what a crew would notice (1 in on an 8 ft arrow).
const SIZE_TOLERANCE: f64 = 0.01;

/// Validation of symbols, in metres (the font's limits are grid units).
pub const SYMBOL_LIMITS: Limits = Limits {
    // assumed: a little under the narrowest band the default robot's fan
    // paints (0.097 m from the nozzle's lowest height, SPEC §4): narrower
    // rungs are oversprayed.
    min_rung: 0.09,
    grid_margin: 0.0,
    rung_check_n: 100,
    samples: 240,
    // assumed: 2 mm rows and 1 cm² of overlap, the font's tolerances
    // (0.02 units and 0.01 square units) at an 8 ft letter.
    scan_step: 0.002,
    overlap_area: 1e-4,
    frame: None,
    unit: "m",
};

/// A built symbol: strokes in metres in the symbol's frame, painting order.
#[derive(Debug, Clone, PartialEq)]
pub struct Symbol {
    /// Kebab-case name (`arrow-left`).
    pub name: String,
    pub description: String,
    /// Width across the lane and length along it (m).
    pub size_m: [f64; 2],
    /// Where its dimensions come from (MUTCD, FHWA SHSM, a state standard).
    pub source: String,
    /// What is assumed and why, when a source does not give it.
    pub assumed: Option<String>,
    pub strokes: Vec<Stroke>,
}

impl Symbol {
    /// Painted area (m²): the strokes' outlines.
    pub fn area_m2(&self) -> f64 {
        self.strokes.iter().map(stroke_area).sum()
    }
}

/// Area of a stroke's outline (shoelace over 200 points per edge), m².
pub fn stroke_area(s: &Stroke) -> f64 {
    let pts = s.outline(200);
    let n = pts.len();
    0.5 * (0..n)
        .map(|i| pts[i].to_vec2().cross(pts[(i + 1) % n].to_vec2()))
        .sum::<f64>()
        .abs()
}

/// A validated symbol library.
#[derive(Debug, Clone, PartialEq)]
pub struct Library {
    pub name: String,
    pub sha256: String,
    pub origin: String,
    symbols: BTreeMap<String, Symbol>,
}

impl Library {
    /// The library built into the binary (`symbols/basr.toml`).
    pub fn embedded() -> &'static Library {
        static LIB: OnceLock<Library> = OnceLock::new();
        LIB.get_or_init(|| {
            // Fixed at build time and checked whole by a test
            // (`embedded_library_validates`): a failure is a build defect,
            // not bad input. Here the symbols' geometry is not checked again.
            Library::from_built(
                build(EMBEDDED_SOURCE, EMBEDDED_ORIGIN, false),
                EMBEDDED_SOURCE,
                EMBEDDED_ORIGIN,
            )
            .unwrap_or_else(|p| panic!("the embedded symbol library is invalid:\n{}", p.join("\n")))
        })
    }

    /// Parse and validate library text; every problem, each with file:line:col.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Library, Vec<String>> {
        Library::from_built(build(text, origin, true), text, origin)
    }

    /// The library `built` from `text`, or its problems.
    fn from_built(
        (name, symbols, problems): (String, BTreeMap<String, Symbol>, Vec<String>),
        text: &str,
        origin: &str,
    ) -> Result<Library, Vec<String>> {
        if !problems.is_empty() {
            return Err(problems);
        }
        Ok(Library {
            name,
            sha256: basr_io::sha256_hex(text.as_bytes()),
            origin: origin.to_string(),
            symbols,
        })
    }

    /// The symbol of that name; names are kebab-case and matched without
    /// regard to case (`RXR`, as the marking reads, is `rxr`).
    pub fn get(&self, name: &str) -> Option<&Symbol> {
        self.symbols
            .get(name)
            .or_else(|| self.symbols.get(&name.to_ascii_lowercase()))
    }

    /// All symbols by name.
    pub fn symbols(&self) -> impl Iterator<Item = &Symbol> {
        self.symbols.values()
    }

    /// Up to three names nearest `name`, nearest first: by edit distance
    /// (Damerau–Levenshtein, case ignored) to the whole name or, one edit
    /// dearer, to its beginning, so a shortened name finds its family
    /// (`arow` → `arrow-…`) and a slip finds its name (`stopline` →
    /// `stop-line`); ties in name order.
    pub fn nearest(&self, name: &str) -> Vec<&str> {
        let q = name.to_ascii_lowercase();
        let mut v: Vec<(usize, &str)> = self
            .symbols
            .keys()
            .map(|k| (name_distance(&q, k), k.as_str()))
            .collect();
        v.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(b.1)));
        v.into_iter().take(3).map(|(_, k)| k).collect()
    }
}

/// Edit distance from a typed name `q` (lower case) to a library name: to
/// the whole name, or one more than to a beginning of it.
fn name_distance(q: &str, name: &str) -> usize {
    let whole = strsim::damerau_levenshtein(q, name);
    let prefix = name
        .char_indices()
        .map(|(i, _)| i)
        .chain([name.len()])
        .filter(|&i| i > 0)
        .map(|i| strsim::damerau_levenshtein(q, &name[..i]) + 1)
        .min()
        .unwrap_or(whole);
    whole.min(prefix)
}

/// Whether a text is a symbol library (for `basr check`).
pub fn looks_like_library(text: &str) -> bool {
    text.lines().any(|l| {
        let l = l.trim_start();
        l.starts_with("[symbols.") || l.starts_with("[[symbols.")
    })
}

/// Every problem of a library's text (empty when valid), for `basr check`.
pub fn check_library_source(text: &str, origin: &str) -> Vec<String> {
    build(text, origin, true).2
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LibrarySpec {
    name: String,
    #[serde(default)]
    #[allow(dead_code)]
    description: Option<String>,
    /// Metres per drawing unit (0.3048: the symbols are drawn in feet).
    unit_m: Spanned<f64>,
    #[serde(default)]
    primitives: BTreeMap<String, Spanned<PrimitiveSpec>>,
    symbols: BTreeMap<Spanned<String>, SymbolSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SymbolSpec {
    description: String,
    /// Width across the lane and length along it, in drawing units.
    size: Spanned<[f64; 2]>,
    source: String,
    #[serde(default)]
    assumed: Option<String>,
    #[serde(default)]
    strokes: Vec<Spanned<StrokeSpec>>,
    /// Other symbols of the library placed inside this one.
    #[serde(default)]
    parts: Vec<Spanned<PartSpec>>,
    /// Letters of the embedded font placed inside the symbol.
    #[serde(default)]
    letters: Vec<Spanned<LetterSpec>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PartSpec {
    symbol: String,
    #[serde(default)]
    transform: Vec<Spanned<TransformSpec>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LetterSpec {
    /// One capital letter or digit of the embedded font.
    char: char,
    /// Lower-left corner of the letter's 4 × 25 grid, drawing units.
    at: [f64; 2],
    /// Letter height, drawing units.
    height: f64,
}

/// The library's name, symbols and problems; the symbols' geometry is
/// checked (`validate_glyph`) only with `geometry`.
fn build(
    text: &str,
    origin: &str,
    geometry: bool,
) -> (String, BTreeMap<String, Symbol>, Vec<String>) {
    let loc = Locator::new(text, origin);
    let mut problems = vec![];
    let mut out = BTreeMap::new();
    if text.trim().is_empty() {
        problems.push(format!(
            "{}: the symbol library is empty; it needs `name`, `unit_m` and [symbols.NAME] \
             tables (see the format notes at the top of symbols/basr.toml)",
            loc.at(0)
        ));
        return (String::new(), out, problems);
    }
    let spec: LibrarySpec = match toml::from_str(text) {
        Ok(s) => s,
        Err(e) => {
            let at = e.span().map_or(origin.to_string(), |s| loc.at(s.start));
            problems.push(format!(
                "{at}: {} (see the format notes at the top of symbols/basr.toml)",
                basr_io::one_line(e.message())
            ));
            return (String::new(), out, problems);
        }
    };
    let unit = *spec.unit_m.get_ref();
    if !(unit.is_finite() && unit > 0.0 && unit <= 1.0) {
        problems.push(format!(
            "{}: unit_m = {unit} must be the metres in one drawing unit, above 0 and at most 1 \
             (0.3048 for feet, 0.0254 for inches)",
            loc.at(spec.unit_m.span().start)
        ));
        return (spec.name, out, problems);
    }
    let primitives = build_primitives(&spec.primitives, &loc, &mut problems);
    let to_m = Affine::scale(unit);
    // Symbols with parts are built after the symbols they use (one level).
    let mut order: Vec<(&Spanned<String>, &SymbolSpec)> = spec.symbols.iter().collect();
    order.sort_by_key(|(_, s)| !s.parts.is_empty());
    for (key, s) in order {
        let at = loc.at(key.span().start);
        let name = key.get_ref();
        if !is_kebab(name) {
            problems.push(format!(
                "{at}: symbol `{name}`: a symbol name is lower-case words joined by `-` \
                 (`arrow-left`)"
            ));
            continue;
        }
        let before = problems.len();
        let mut strokes: Vec<(String, Stroke)> = vec![];
        for (i, st) in s.strokes.iter().enumerate() {
            let ctx = format!(
                "{}: symbol `{name}` stroke {}",
                loc.at(st.span().start),
                i + 1
            );
            if let Some(built) = stroke(
                st.get_ref(),
                &primitives,
                &spec.primitives,
                &loc,
                &ctx,
                &mut problems,
            ) {
                strokes.push((ctx, built.transformed(&to_m)));
            }
        }
        for (i, part) in s.parts.iter().enumerate() {
            let ctx = format!(
                "{}: symbol `{name}` part {}",
                loc.at(part.span().start),
                i + 1
            );
            let p = part.get_ref();
            let Some(used) = out.get(&p.symbol) else {
                problems.push(format!(
                    "{ctx}: `symbol = \"{}\"` names no symbol of this library without parts of \
                     its own",
                    p.symbol
                ));
                continue;
            };
            let Some(m) = transform(&p.transform, &loc, &ctx, &mut problems) else {
                continue;
            };
            // The part's transform is in drawing units, its strokes in metres.
            let m = to_m * m * to_m.inverse();
            let used: &Symbol = used;
            for (k, st) in used.strokes.iter().enumerate() {
                strokes.push((
                    format!("{ctx} (`{}` stroke {})", p.symbol, k + 1),
                    st.transformed(&m),
                ));
            }
        }
        for (i, l) in s.letters.iter().enumerate() {
            let ctx = format!(
                "{}: symbol `{name}` letter {}",
                loc.at(l.span().start),
                i + 1
            );
            let l = l.get_ref();
            let glyph = Font::embedded().glyph(l.char);
            let ok_h = l.height.is_finite() && l.height > 0.0;
            let Some(glyph) = glyph.filter(|_| ok_h && l.at.iter().all(|v| v.is_finite())) else {
                problems.push(format!(
                    "{ctx}: a letter needs `char` from the embedded font (A–Z, 0–9), a finite \
                     `at` and a positive `height`"
                ));
                continue;
            };
            let k = l.height / GRID_HEIGHT;
            let m = to_m * Affine::new([k, 0.0, 0.0, k, l.at[0], l.at[1]]);
            for (k, st) in glyph.strokes.iter().enumerate() {
                strokes.push((
                    format!("{ctx} ('{}' stroke {})", l.char, k + 1),
                    st.transformed(&m),
                ));
            }
        }
        if problems.len() > before {
            continue;
        }
        if strokes.is_empty() {
            problems.push(format!(
                "{at}: symbol `{name}` has no strokes, parts or letters"
            ));
            continue;
        }
        // Into the symbol's frame: centred across, nearest point at y = 0.
        let (lo, hi) = extent(strokes.iter().map(|(_, s)| s));
        let shift = Affine::translate((-0.5 * (lo.x + hi.x), -lo.y));
        let strokes: Vec<(String, Stroke)> = strokes
            .into_iter()
            .map(|(c, s)| (c, s.transformed(&shift)))
            .collect();
        let size = *s.size.get_ref();
        let spans = [(hi.x - lo.x) / unit, (hi.y - lo.y) / unit];
        let tol = SIZE_TOLERANCE * spans[0].max(spans[1]);
        if (spans[0] - size[0]).abs() > tol || (spans[1] - size[1]).abs() > tol {
            problems.push(format!(
                "{}: symbol `{name}`: its strokes span {:.3} × {:.3} units but `size` says \
                 {} × {}; correct `size` or the strokes",
                loc.at(s.size.span().start),
                spans[0],
                spans[1],
                size[0],
                size[1]
            ));
            continue;
        }
        if geometry {
            problems.extend(validate_glyph(&strokes, &SYMBOL_LIMITS));
        }
        if problems.len() > before {
            continue;
        }
        out.insert(
            name.clone(),
            Symbol {
                name: name.clone(),
                description: s.description.clone(),
                size_m: [spans[0] * unit, spans[1] * unit],
                source: s.source.clone(),
                assumed: s.assumed.clone(),
                strokes: strokes.into_iter().map(|(_, s)| s).collect(),
            },
        );
    }
    (spec.name, out, problems)
}

fn is_kebab(s: &str) -> bool {
    !s.is_empty()
        && s.split('-').all(|w| {
            !w.is_empty()
                && w.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit())
        })
}

/// Lower-left and upper-right corners of strokes' edges (dense samples).
pub fn extent<'a>(strokes: impl Iterator<Item = &'a Stroke>) -> (Point, Point) {
    let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
    let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for s in strokes {
        for e in [&s.left, &s.right] {
            for p in e.sample(200) {
                lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
                hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
            }
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SPEC §5's names, all of which the embedded library must hold.
    const SPEC_NAMES: [&str; 18] = [
        "arrow-through",
        "arrow-left",
        "arrow-right",
        "arrow-through-left",
        "arrow-through-right",
        "arrow-left-right",
        "arrow-u-turn",
        "arrow-lane-reduction",
        "arrow-wrong-way",
        "yield-ahead",
        "yield-line",
        "stop-line",
        "crosswalk-transverse",
        "crosswalk-continental",
        "rxr",
        "bike",
        "sharrow",
        "hov-diamond",
    ];

    #[test]
    fn embedded_library_validates() {
        let lib = Library::from_toml_str(EMBEDDED_SOURCE, EMBEDDED_ORIGIN)
            .unwrap_or_else(|p| panic!("{}", p.join("\n")));
        assert_eq!(&lib, Library::embedded());
    }

    #[test]
    fn embedded_library_has_every_spec_symbol() {
        let lib = Library::embedded();
        for n in SPEC_NAMES {
            let s = lib.get(n).unwrap_or_else(|| panic!("{n} missing"));
            assert!(!s.source.is_empty(), "{n} names no source");
            let (lo, hi) = extent(s.strokes.iter());
            assert!(
                lo.y.abs() < 1e-9 && (lo.x + hi.x).abs() < 1e-9,
                "{n} not anchored"
            );
        }
    }

    #[test]
    fn nearest_names_first() {
        let lib = Library::embedded();
        assert_eq!(lib.nearest("arow-left")[0], "arrow-left");
        assert_eq!(lib.nearest("RXR")[0], "rxr");
        assert_eq!(lib.nearest("rxx")[0], "rxr");
        assert_eq!(lib.nearest("bke")[0], "bike");
        assert_eq!(lib.nearest("yeild-line")[0], "yield-line");
        assert!(lib.get("RXR").is_some() && lib.get("Stop-Line").is_some());
        assert_eq!(lib.nearest("stopline")[0], "stop-line");
        assert!(lib.nearest("arow").iter().all(|n| n.starts_with("arrow-")));
    }

    fn lib(body: &str) -> Result<Library, Vec<String>> {
        Library::from_toml_str(
            &format!("name = \"t\"\nunit_m = 1.0\n[primitives.bar]\nleft = [{{ line = [[0, 0], [0, 1]] }}]\nright = [{{ line = [[1, 0], [1, 1]] }}]\n{body}"),
            "t.toml",
        )
    }

    #[test]
    fn size_overlap_and_thin_rungs_are_refused() {
        let ok = "[symbols.box]\ndescription = \"d\"\nsource = \"s\"\nsize = [1, 1]\nstrokes = [{ primitive = \"bar\" }]\n";
        let l = lib(ok).unwrap();
        let b = l.get("box").unwrap();
        assert!((b.area_m2() - 1.0).abs() < 1e-6);
        assert!(b.strokes[0].left.sample(2)[0].x + 0.5 < 1e-12, "centred");
        let e = lib(&ok.replace("size = [1, 1]", "size = [2, 1]")).unwrap_err();
        assert!(e[0].contains("span 1.000 × 1.000"), "{e:?}");
        let twice = ok.replace(
            "strokes = [{ primitive = \"bar\" }]",
            "strokes = [{ primitive = \"bar\" }, { primitive = \"bar\", transform = [{ translate = [0, 0.5] }] }]",
        );
        let e = lib(&twice.replace("size = [1, 1]", "size = [1, 1.5]")).unwrap_err();
        assert!(e.iter().any(|m| m.contains("overlaps stroke 1")), "{e:?}");
        let thin = ok.replace(
            "primitive = \"bar\" }",
            "primitive = \"bar\", transform = [{ scale = [0.05, 1] }] }",
        );
        let e = lib(&thin.replace("size = [1, 1]", "size = [0.05, 1]")).unwrap_err();
        assert!(
            e.iter()
                .any(|m| m.contains("shorter than the minimum 0.09")),
            "{e:?}"
        );
        let e = lib(&ok.replace("[symbols.box]", "[symbols.Box]")).unwrap_err();
        assert!(e[0].contains("lower-case"), "{e:?}");
    }
}
