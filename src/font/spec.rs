//! The font file's TOML schema (what a human writes), with source spans.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

/// A whole font file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FontSpec {
    pub name: Spanned<String>,
    /// Free text for the reader of the file.
    #[serde(default)]
    #[allow(dead_code)]
    pub description: Option<String>,
    pub grid: Spanned<GridSpec>,
    #[serde(default)]
    pub primitives: BTreeMap<String, Spanned<PrimitiveSpec>>,
    pub glyphs: BTreeMap<Spanned<String>, GlyphSpec>,
}

/// The letter grid (001 §2.3: 4 units wide, 25 tall).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    pub width: f64,
    pub height: f64,
}

/// A reusable stroke template (one of the five primitives of 001 fig. 2.4).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrimitiveSpec {
    /// Its number in 001 fig. 2.4 / table 2.1 (documentation).
    #[serde(default)]
    #[allow(dead_code)]
    pub number: Option<u8>,
    #[serde(default)]
    #[allow(dead_code)]
    pub description: Option<String>,
    pub left: Vec<Spanned<SegmentSpec>>,
    pub right: Vec<Spanned<SegmentSpec>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlyphSpec {
    /// Free text for the reader of the file.
    #[serde(default)]
    #[allow(dead_code)]
    pub note: Option<String>,
    /// The strokes, in painting order (unless `copy` is given).
    #[serde(default)]
    pub strokes: Vec<Spanned<StrokeSpec>>,
    /// Reuse another glyph's strokes (e.g. `9` is `6` turned 180°)...
    #[serde(default)]
    pub copy: Option<Spanned<String>>,
    /// ...placed with this transform (applied to every copied stroke).
    #[serde(default)]
    pub transform: Vec<Spanned<TransformSpec>>,
}

/// A stroke: either a placed primitive or explicit left and right edges.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrokeSpec {
    #[serde(default)]
    pub primitive: Option<Spanned<String>>,
    #[serde(default)]
    pub left: Option<Vec<Spanned<SegmentSpec>>>,
    #[serde(default)]
    pub right: Option<Vec<Spanned<SegmentSpec>>>,
    #[serde(default)]
    pub transform: Vec<Spanned<TransformSpec>>,
    #[serde(default)]
    pub reverse: bool,
    /// Free text for the reader of the file.
    #[serde(default)]
    #[allow(dead_code)]
    pub note: Option<String>,
}

/// One segment of an edge: exactly one of `line`, `cardinal`, `arc`, `conic`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    #[serde(default)]
    pub line: Option<[[f64; 2]; 2]>,
    #[serde(default)]
    pub cardinal: Option<[[f64; 2]; 4]>,
    #[serde(default)]
    pub tension: Option<f64>,
    #[serde(default)]
    pub t: Option<[f64; 2]>,
    #[serde(default)]
    pub arc: Option<ArcSpec>,
    #[serde(default)]
    pub conic: Option<[[f64; 2]; 3]>,
    #[serde(default)]
    pub weight: Option<f64>,
    #[serde(default)]
    pub transform: Vec<Spanned<TransformSpec>>,
    #[serde(default)]
    pub reverse: bool,
}

/// An elliptical arc centre + (rx cos φ, ry sin φ), φ from `from_deg` to `to_deg`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArcSpec {
    pub center: [f64; 2],
    pub radii: [f64; 2],
    pub from_deg: f64,
    pub to_deg: f64,
}

/// One step of a placement: exactly one key.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformSpec {
    /// Move by (dx, dy).
    #[serde(default)]
    pub translate: Option<[f64; 2]>,
    /// Scale by (sx, sy) about the origin.
    #[serde(default)]
    pub scale: Option<[f64; 2]>,
    /// Rotate counter-clockwise by this many degrees about the origin.
    #[serde(default)]
    pub rotate_deg: Option<f64>,
    /// Mirror in the vertical line x = c (x → 2c − x).
    #[serde(default)]
    pub mirror_x: Option<f64>,
    /// Mirror in the horizontal line y = c (y → 2c − y).
    #[serde(default)]
    pub mirror_y: Option<f64>,
    /// Rotate 180° about the point (cx, cy).
    #[serde(default)]
    pub rotate180: Option<[f64; 2]>,
    /// Shear: x → x + k·y.
    #[serde(default)]
    pub shear_x: Option<f64>,
}
