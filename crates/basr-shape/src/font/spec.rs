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
    /// 4 for letters; a shape imported by `basr import` is as wide as it is
    /// (in units of a 25th of its height).
    pub width: f64,
    pub height: f64,
    /// Shortest rung allowed (units); default 0.5, half a letter's stroke.
    /// A shape's decomposition trims its tips at the fan's physical limit
    /// itself and writes its own.
    #[serde(default)]
    pub min_rung: Option<f64>,
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

/// The same file read loosely, only to learn where each glyph's strokes,
/// edges and segments are: when the schema above refuses the file (an
/// unknown segment kind, a string for a number), this says which glyph and
/// stroke the offending span lies in. Unknown keys and leaf values are
/// ignored; a list that is not a list counts as empty.
#[derive(Debug, Default, Deserialize)]
pub struct Outline {
    #[serde(default)]
    primitives: BTreeMap<String, Spanned<OutlineStroke>>,
    #[serde(default)]
    glyphs: BTreeMap<String, OutlineGlyph>,
}

#[derive(Debug, Default, Deserialize)]
struct OutlineGlyph {
    #[serde(default)]
    strokes: Items<OutlineStroke>,
    #[serde(default)]
    copy: Option<Spanned<serde::de::IgnoredAny>>,
    #[serde(default)]
    transform: Items<serde::de::IgnoredAny>,
}

#[derive(Debug, Default, Deserialize)]
struct OutlineStroke {
    #[serde(default)]
    left: Items<OutlineSegment>,
    #[serde(default)]
    right: Items<OutlineSegment>,
    #[serde(default)]
    transform: Items<serde::de::IgnoredAny>,
}

#[derive(Debug, Default, Deserialize)]
struct OutlineSegment {
    #[serde(default)]
    transform: Items<serde::de::IgnoredAny>,
}

/// A list of spanned items, or (for any other value) no items.
#[derive(Debug)]
struct Items<T>(Vec<Spanned<T>>);

impl<T> Default for Items<T> {
    fn default() -> Self {
        Items(Vec::new())
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Items<T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T>(std::marker::PhantomData<T>);
        impl<'de, T: Deserialize<'de>> serde::de::Visitor<'de> for V<T> {
            type Value = Items<T>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("anything")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Items<T>, A::Error> {
                let mut out = Vec::new();
                while let Some(item) = seq.next_element()? {
                    out.push(item);
                }
                Ok(Items(out))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<Items<T>, A::Error> {
                while map
                    .next_entry::<serde::de::IgnoredAny, serde::de::IgnoredAny>()?
                    .is_some()
                {}
                Ok(Items::default())
            }
            fn visit_bool<E>(self, _: bool) -> Result<Items<T>, E> {
                Ok(Items::default())
            }
            fn visit_i64<E>(self, _: i64) -> Result<Items<T>, E> {
                Ok(Items::default())
            }
            fn visit_u64<E>(self, _: u64) -> Result<Items<T>, E> {
                Ok(Items::default())
            }
            fn visit_f64<E>(self, _: f64) -> Result<Items<T>, E> {
                Ok(Items::default())
            }
            fn visit_str<E>(self, _: &str) -> Result<Items<T>, E> {
                Ok(Items::default())
            }
        }
        d.deserialize_any(V(std::marker::PhantomData))
    }
}

fn contains<T>(s: &Spanned<T>, offset: usize) -> bool {
    s.span().contains(&offset)
}

impl OutlineStroke {
    /// Where in this stroke (or primitive) `offset` lies: "" or
    /// " left edge segment 2", " transform step 1", ...
    fn place(&self, offset: usize) -> String {
        for (side, segs) in [("left", &self.left), ("right", &self.right)] {
            for (i, seg) in segs.0.iter().enumerate() {
                if contains(seg, offset) {
                    let step = step_of(&seg.get_ref().transform, offset)
                        .map(|k| format!(" transform step {k}"))
                        .unwrap_or_default();
                    return format!(" {side} edge segment {}{step}", i + 1);
                }
            }
        }
        step_of(&self.transform, offset)
            .map(|k| format!(" transform step {k}"))
            .unwrap_or_default()
    }
}

fn step_of<T>(steps: &Items<T>, offset: usize) -> Option<usize> {
    steps
        .0
        .iter()
        .position(|s| contains(s, offset))
        .map(|i| i + 1)
}

impl Outline {
    /// Read `text` loosely; `None` if even that fails (a syntax error).
    pub fn read(text: &str) -> Option<Outline> {
        toml::from_str(text).ok()
    }

    /// The glyph, stroke, edge and segment whose source span holds byte
    /// `offset`, as "glyph 'I' stroke 1 left edge segment 2" (or
    /// "primitive `bowl` ..."), if any.
    pub fn place(&self, offset: usize) -> Option<String> {
        for (key, g) in &self.glyphs {
            for (i, s) in g.strokes.0.iter().enumerate() {
                if contains(s, offset) {
                    let at = s.get_ref().place(offset);
                    return Some(format!("glyph '{key}' stroke {}{at}", i + 1));
                }
            }
            if let Some(k) = step_of(&g.transform, offset) {
                return Some(format!("glyph '{key}' transform step {k}"));
            }
            if g.copy.as_ref().is_some_and(|c| contains(c, offset)) {
                return Some(format!("glyph '{key}'"));
            }
        }
        self.primitives.iter().find_map(|(name, p)| {
            contains(p, offset).then(|| format!("primitive `{name}`{}", p.get_ref().place(offset)))
        })
    }
}
