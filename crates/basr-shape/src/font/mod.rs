//! Font files, the five primitives of 001 fig. 2.4, glyphs and their validation.
//!
//! A font is a TOML file (see `fonts/basr.toml`, whose header documents the
//! format). Glyphs live on the letter grid of 001 §2.3: x from 0 to 4 to the
//! right, y from 0 to 25 up. Each glyph is a list of [`Stroke`]s, painted in
//! that order.
//!
//! **Stroke convention.** A stroke has two edges, `left` and `right`, that
//! both run from the stroke's start to its end; `left` lies on the left of
//! the direction of travel. Rung i joins `left.subdivide(n)[i]` and
//! `right.subdivide(n)[i]` (001 §2.4, fig. 2.7–2.8); the start and end caps
//! are the straight rungs i = 0 and i = n, which a flat fan paints square.
//! Strokes of one glyph never overlap (they may abut along a shared rung or
//! edge), so no area is painted twice.

mod build;
mod sheet;
mod spec;
mod symbol;
mod symbol_sheet;
mod validate;

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

use kurbo::{Affine, Point};

use basr_geom::Edge;

pub use sheet::alphabet_sheet;
pub use symbol::{
    check_library_source, extent, looks_like_library, stroke_area, Library, Symbol, SYMBOL_LIMITS,
};
pub use symbol_sheet::{feet_inches, symbol_sheet};
pub use validate::{overlap_area, validate_stroke, Limits, DEFAULT_LIMITS};

/// Width of the letter grid in font units (001 §2.3: 25 × 4 grid).
pub const GRID_WIDTH: f64 = 4.0;
/// Height of the letter grid in font units (001 §2.3).
pub const GRID_HEIGHT: f64 = 25.0;

/// Name of the font built into the binary.
pub const EMBEDDED_NAME: &str = "basr";
const EMBEDDED_SOURCE: &str = include_str!("../../../../fonts/basr.toml");
const EMBEDDED_ORIGIN: &str = "fonts/basr.toml";

/// One band of paint between two opposing edges (see the module docs for
/// the convention).
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    pub left: Edge,
    pub right: Edge,
}

impl Stroke {
    /// The n + 1 rungs (left point, right point) of an n-way subdivision.
    pub fn rungs(&self, n: usize) -> Vec<(Point, Point)> {
        self.left
            .subdivide(n)
            .into_iter()
            .zip(self.right.subdivide(n))
            .collect()
    }

    /// Closed outline, counter-clockwise: the right edge forward, then the
    /// left edge backward, each sampled at `k` equal-arc-length points.
    pub fn outline(&self, k: usize) -> Vec<Point> {
        let mut pts = self.right.sample(k);
        let mut left = self.left.sample(k);
        left.reverse();
        pts.extend(left);
        pts
    }

    /// The stroke mapped by an affine transform. A mirroring map (negative
    /// determinant) swaps which edge is on the left, so the edges swap too.
    pub fn transformed(&self, m: &Affine) -> Stroke {
        let left = self.left.transformed(m);
        let right = self.right.transformed(m);
        if m.determinant() < 0.0 {
            Stroke {
                left: right,
                right: left,
            }
        } else {
            Stroke { left, right }
        }
    }

    /// The same band painted in the opposite direction.
    pub fn reversed(&self) -> Stroke {
        Stroke {
            left: self.right.reversed(),
            right: self.left.reversed(),
        }
    }
}

/// One character's strokes, in painting order.
#[derive(Debug, Clone, PartialEq)]
pub struct Glyph {
    pub ch: char,
    pub strokes: Vec<Stroke>,
}

/// A validated font.
#[derive(Debug, Clone, PartialEq)]
pub struct Font {
    /// The font's `name`.
    pub name: String,
    /// SHA-256 (hex) of the font file's bytes.
    pub sha256: String,
    /// Where it came from: the path it was read from, or `fonts/basr.toml`
    /// for the embedded font (see [`Font::embedded`]).
    pub origin: String,
    /// Whether this is the font built into the binary.
    pub embedded: bool,
    /// The grid's width (units): [`GRID_WIDTH`] for letters, a shape's own.
    pub grid_width: f64,
    glyphs: BTreeMap<char, Glyph>,
}

/// Why a font could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum FontError {
    /// The file could not be read as text (missing, unreadable, not UTF-8),
    /// said by the shared reader [`basr_io::read_text`]: the file, the OS
    /// reason or the offset of the first bad byte, and what to do. The whole
    /// chain is the message and there is no separate source, so `{:#}` in
    /// the CLI prints the OS reason once.
    #[error("{0:#}")]
    Read(anyhow::Error),
    /// The file was read but is not a valid font; every problem is listed,
    /// each naming file:line:col, the glyph and stroke.
    #[error("invalid font {origin}:\n  {}", problems.join("\n  "))]
    Invalid {
        origin: String,
        problems: Vec<String>,
    },
}

impl Font {
    /// The default font built into the binary (`fonts/basr.toml`).
    pub fn embedded() -> &'static Font {
        static FONT: OnceLock<Font> = OnceLock::new();
        FONT.get_or_init(|| {
            // The embedded source is fixed at build time and a test checks it
            // validates, so a failure here is a build defect, not bad input.
            // The test checks its glyphs' geometry too; here it is only
            // parsed and built.
            let mut font = Font::from_built(
                build::build_checked(EMBEDDED_SOURCE, EMBEDDED_ORIGIN, false),
                EMBEDDED_SOURCE,
                EMBEDDED_ORIGIN,
            )
            .unwrap_or_else(|e| panic!("the embedded font is invalid: {e}"));
            font.embedded = true;
            font
        })
    }

    /// The embedded font's source text.
    pub fn embedded_source() -> &'static str {
        EMBEDDED_SOURCE
    }

    /// Read and validate a font file (`-` reads standard input).
    pub fn load(path: impl AsRef<Path>) -> Result<Font, FontError> {
        let path = path.as_ref();
        let text = basr_io::read_text(path).map_err(FontError::Read)?;
        Font::from_toml_str(&text, &path.display().to_string())
    }

    /// `--font NAME|FILE`: the embedded font by its name, otherwise a file.
    pub fn from_name_or_path(name_or_path: &str) -> Result<Font, FontError> {
        if name_or_path == EMBEDDED_NAME {
            Ok(Font::embedded().clone())
        } else {
            Font::load(name_or_path)
        }
    }

    /// Parse and validate font source text; `origin` names it in messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Font, FontError> {
        Font::from_built(build::build(text, origin), text, origin)
    }

    /// The font `built` from `text`, or its problems.
    fn from_built(built: build::Built, text: &str, origin: &str) -> Result<Font, FontError> {
        if !built.problems.is_empty() {
            return Err(FontError::Invalid {
                origin: origin.to_string(),
                problems: built.problems,
            });
        }
        Ok(Font {
            name: built.name,
            sha256: basr_io::sha256_hex(text.as_bytes()),
            origin: origin.to_string(),
            embedded: false,
            grid_width: built.grid_width,
            glyphs: built.glyphs,
        })
    }

    /// Where the font came from, for people: "embedded fonts/basr.toml" or
    /// "file my-font.toml".
    pub fn source_description(&self) -> String {
        if self.embedded {
            format!("embedded {}", self.origin)
        } else {
            format!("file {}", self.origin)
        }
    }

    /// The glyph for `ch` (exactly as given; the font holds capitals and digits).
    pub fn glyph(&self, ch: char) -> Option<&Glyph> {
        self.glyphs.get(&ch)
    }

    /// All glyphs in character order.
    pub fn glyphs(&self) -> impl Iterator<Item = &Glyph> {
        self.glyphs.values()
    }

    /// The characters the font has, in order.
    pub fn chars(&self) -> String {
        self.glyphs.keys().collect()
    }
}

/// Whether a text that does not parse as TOML was meant to be a font (so
/// `basr check` reports its syntax error rather than "unknown file").
pub fn looks_like_font(text: &str) -> bool {
    text.lines().any(|l| {
        let l = l.trim_start();
        l.starts_with("[[glyphs.") || l.starts_with("[glyphs.") || l.starts_with("[primitives.")
    })
}

/// Every problem in a font source (empty when valid), for `basr check`.
pub fn check_source(text: &str, origin: &str) -> Vec<String> {
    build::build(text, origin).problems
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_font_validates() {
        let problems = check_source(EMBEDDED_SOURCE, EMBEDDED_ORIGIN);
        assert!(problems.is_empty(), "{}", problems.join("\n"));
        let f = Font::embedded();
        assert_eq!(f.name, EMBEDDED_NAME);
        // The embedded font skips the geometry checks when it is built:
        // this is the font a whole check gives.
        let checked = Font::from_toml_str(EMBEDDED_SOURCE, EMBEDDED_ORIGIN).unwrap();
        assert_eq!(checked.glyphs, f.glyphs);
        assert_eq!(f.sha256.len(), 64);
    }

    /// A glyph's painted area (grid units²): its strokes never overlap, so it
    /// is the sum of their outlines' shoelace areas, `k` points per edge.
    fn glyph_area(f: &Font, ch: char, k: usize) -> f64 {
        let shoelace = |p: &[Point]| {
            let n = p.len();
            0.5 * (0..n)
                .map(|i| p[i].to_vec2().cross(p[(i + 1) % n].to_vec2()))
                .sum::<f64>()
        };
        f.glyph(ch)
            .unwrap()
            .strokes
            .iter()
            .map(|s| shoelace(&s.outline(k)).abs())
            .sum()
    }

    /// B's bars run through its stem (fonts/basr.toml, docs/font.md "B's
    /// bars through the stem"): only the seams moved, so its area is the
    /// seed's (main 88313f0, stem and bars meeting at x = 1: 69.74342454
    /// at 2000 points per edge, 69.74342990 at 8000, 69.74343017 at
    /// 32 000, extrapolated to the curve).
    #[test]
    fn b_through_its_stem_keeps_the_seed_outline() {
        let seed = 69.743_430_19;
        let now = glyph_area(Font::embedded(), 'B', 8000);
        assert!(
            ((now - seed) / seed).abs() < 1e-6,
            "B: area {now} differs from the seed's {seed}"
        );
    }

    /// 6, 8 and 9 cut their loops into level bands (fonts/basr.toml): the
    /// outline must stay the seed's but for the apexes their domes trim
    /// (4.5 mm at 8 ft, where a rung would be under the loader's 0.5
    /// units): two in the 8, one in the 6 and the 9. The
    /// seed's areas (main 15f6282, 32 000 points per edge, extrapolated to
    /// the curve) are the figures to keep; any moved edge changes them.
    #[test]
    fn repartitioned_glyphs_keep_the_seed_outline() {
        use kurbo::{BezPath, CubicBez, ParamCurve, Shape};
        // Primitive 2's outer spline, a = 1, as its cubic Bézier (001 eq.
        // 2.1–2.3): from the apex (2, -0.2) to (4, 6).
        let spline = CubicBez::new(
            (2.0, -0.2),
            (2.0 + 4.0 / 3.0, -0.2),
            (4.0, 6.0 - 8.2 / 3.0),
            (4.0, 6.0),
        );
        // The dome's trim: the font's t, where the half-width is 0.26.
        let t = 0.067_262_094_691_118_43;
        let cut = spline.eval(t);
        assert!((cut.x - 2.26).abs() < 1e-12, "{cut:?}");
        // Half the trimmed cap: apex, up the axis, the chord, back down.
        let mut half = BezPath::new();
        half.move_to((2.0, -0.2));
        half.line_to((2.0, cut.y));
        half.line_to(cut);
        let back = spline.subsegment(0.0..t);
        half.curve_to(back.p2, back.p1, back.p0);
        half.close_path();
        let apex = 2.0 * half.area().abs();
        assert!(apex > 0.01 && apex < 0.02, "trimmed apex {apex}");
        let f = Font::embedded();
        for (ch, seed, apexes) in [
            ('6', 61.712_685_03, 1.0),
            ('8', 64.925_870_93, 2.0),
            ('9', 61.712_685_03, 1.0),
        ] {
            let now = glyph_area(f, ch, 8000);
            let want = seed - apexes * apex;
            assert!(
                ((now - want) / want).abs() < 1e-6,
                "{ch}: area {now} differs from the seed's {seed} less {apexes} trimmed apex(es) of {apex}"
            );
        }
    }
}
