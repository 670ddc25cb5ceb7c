//! # basr-shape
//!
//! What is painted: fonts (`font`), the symbol library, outline import and decomposition (this module), the layout in the lane (`layout`). Imports `basr-io`, `basr-geom`, `basr-robot` and `basr-job`; never the planner, the previewer or the simulator. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! ```
//! use basr_shape::font::Font;
//! use basr_shape::layout::{lay_marking, Marking, Overrides};
//!
//! // STOP at the default 8 ft letters in the default lane.
//! let marking = Marking::from_message("STOP", &Overrides::default()).unwrap();
//! let laid = lay_marking(&marking, Font::embedded(), false).unwrap();
//! assert_eq!(laid.marks.len(), 4);
//! assert!((laid.letter_height_m - 2.44).abs() < 1e-9);
//! ```
//!
//! Custom shapes: a filled outline from an SVG or DXF file, resolved into
//! regions with holes and decomposed into strokes (bands between two edges)
//! that the rest of the pipeline paints like a letter's.
//!
//! Stages, each one function: [`read`] (file → [`Outline`]: closed Bézier
//! contours in the file's units, y up, with their fill rule) → [`regions`]
//! (outline scaled to metres → non-overlapping [`Region`]s with holes, via
//! i_overlay) → [`decompose`] (regions → strokes in metres plus a report of
//! narrow places and of the method chosen per region) → [`font_toml`] (the
//! strokes as a one-glyph font file, editable, that `--font` reads back).
//!
//! The robot enters only as the fan's [`Bands`] (`plan::shapes::bands`);
//! compiling a shape, alone or as a scene's item, is `plan::shapes`.

pub mod chars;
pub mod font;
pub mod layout;

mod convex;
mod decompose;
mod dxf;
mod hatch;
pub mod limits;
mod lobes;
mod passes;
mod region;
mod ring;
mod svg;
mod sweep;
mod write;

use std::path::Path;

use kurbo::BezPath;

pub use decompose::{
    candidates, decompose, Bands, Candidate, Decomposition, Method, Narrow, Prediction,
    RegionReport, Steep, MAX_CANDIDATES,
};
pub use region::{regions, Region};
pub use write::{font_toml, GLYPH};

/// Shapes are sized like letters (SPEC §1 `--letter-height`): the bounds of
/// `check_settings` in `plan::compile` (0.3–10 m).
pub const MIN_SIZE_M: f64 = 0.3;
/// See [`MIN_SIZE_M`].
pub const MAX_SIZE_M: f64 = 10.0;

/// How contours overlapping themselves or each other are filled (SVG
/// `fill-rule`; DXF hatches and closed entities are even-odd).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillRule {
    NonZero,
    EvenOdd,
}

/// One filled element of the file: its closed contours and fill rule.
#[derive(Clone, Debug)]
pub struct Element {
    /// Who it is in the file, for messages: `path id="star"`, `LWPOLYLINE at line 120`.
    pub name: String,
    pub rule: FillRule,
    /// Closed contours, file units, y up.
    pub path: BezPath,
}

/// A whole file's filled elements.
#[derive(Clone, Debug)]
pub struct Outline {
    pub origin: String,
    pub elements: Vec<Element>,
    /// Metres per file unit when the file says (DXF `$INSUNITS`); `None` for SVG.
    pub metres_per_unit: Option<f64>,
}

/// Bad shape input; the message names the element (id or line) and the fix.
#[derive(Debug, thiserror::Error)]
pub enum ShapeError {
    #[error("{0:#}")]
    Read(anyhow::Error),
    #[error("{origin}: {what}")]
    Invalid { origin: String, what: String },
}

impl ShapeError {
    pub(crate) fn invalid(origin: &str, what: impl Into<String>) -> ShapeError {
        ShapeError::Invalid {
            origin: origin.to_string(),
            what: what.into(),
        }
    }
}

/// The size asked for: the shape's height or width on the road (m), or the
/// file's own units (DXF only).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Size {
    HeightM(f64),
    WidthM(f64),
    FileUnits,
}

/// Read an SVG (`.svg`) or DXF (`.dxf`) file into its filled contours,
/// within [`limits`].
pub fn read(path: &Path) -> Result<Outline, ShapeError> {
    let origin = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some(ext @ ("svg" | "dxf")) => {
            let text = basr_io::read_text(path).map_err(ShapeError::Read)?;
            read_str(&text, ext, &origin)
        }
        _ => Err(ShapeError::invalid(
            &origin,
            "a shape file must be an SVG (.svg) or a DXF (.dxf) drawing",
        )),
    }
}

/// [`read`] of a file's text; `ext` is `svg` or `dxf` (anything else reads
/// as DXF). For the fuzz targets and tests, which hold no file.
pub fn read_str(text: &str, ext: &str, origin: &str) -> Result<Outline, ShapeError> {
    let outline = if ext == "svg" {
        svg::read_svg(text, origin)?
    } else {
        dxf::read_dxf(text, origin)?
    };
    limits::check_outline(&outline)?;
    Ok(outline)
}

/// The scale (m per file unit) that gives the outline the asked size.
pub fn scale_for(outline: &Outline, size: Size) -> Result<f64, ShapeError> {
    let bb = bounds(outline);
    let (w, h) = (bb.width(), bb.height());
    let origin = &outline.origin;
    let scale = match size {
        Size::HeightM(m) => m / h,
        Size::WidthM(m) => m / w,
        Size::FileUnits => match outline.metres_per_unit {
            Some(s) => s,
            None => {
                return Err(ShapeError::invalid(
                    origin,
                    "an SVG has no physical size: give --shape-height-m H or --shape-width-m W",
                ))
            }
        },
    };
    let height = h * scale;
    if !(scale.is_finite() && scale > 0.0 && (MIN_SIZE_M..=MAX_SIZE_M).contains(&height)) {
        return Err(ShapeError::invalid(
            origin,
            format!(
                "the shape would be {} m tall and {} m wide; shapes are sized like letters, \
                 {MIN_SIZE_M}–{MAX_SIZE_M} m tall: give --shape-height-m H within those bounds",
                metres(height),
                metres(w * scale)
            ),
        ));
    }
    Ok(scale)
}

/// A size for a message: to the millimetre, without trailing zeros (one of
/// height and width is computed from the other, so it is no number the
/// user typed).
fn metres(v: f64) -> String {
    if v.is_finite() {
        basr_io::fixed(v, 3)
    } else {
        basr_io::show_num(v)
    }
}

/// The shape's name in jobs and messages (`[star]`): its file's stem.
pub fn label_of(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "shape".into(), |s| s.to_string_lossy().to_string())
}

/// Bounding box of every element.
pub fn bounds(outline: &Outline) -> kurbo::Rect {
    use kurbo::Shape;
    outline
        .elements
        .iter()
        .map(|e| e.path.bounding_box())
        .reduce(|a, b| a.union(b))
        .unwrap_or(kurbo::Rect::ZERO)
}

/// A shape file read, sized, resolved and decomposed.
#[derive(Clone, Debug)]
pub struct Imported {
    pub decomposition: Decomposition,
    /// Size on the road (m).
    pub width_m: f64,
    pub height_m: f64,
    /// Where the file came from (the font file's header names it).
    pub source: String,
    /// Lines for a person besides [`report_lines`] (how the decomposition
    /// was picked: `plan::shapes` measures the candidates' film).
    pub notes: Vec<String>,
    /// The decomposition as a one-glyph font file ([`font_toml`]).
    pub toml: String,
}

impl Imported {
    /// The font `toml` describes, as `--font` would load it.
    pub fn font(&self, origin: &str) -> Result<crate::font::Font, ShapeError> {
        crate::font::Font::from_toml_str(&self.toml, origin).map_err(|e| {
            ShapeError::invalid(
                origin,
                format!("the decomposition is not a valid font: {e}"),
            )
        })
    }

    /// `self` with `notes`, its font file's header saying them too.
    pub fn with_notes(mut self, notes: Vec<String>) -> Imported {
        self.notes = notes;
        self.toml = font_toml(
            &self.decomposition,
            self.width_m,
            self.height_m,
            &self.source,
            &self.notes,
        );
        self
    }
}

/// Every stage from the file to the font text, the decomposition with the
/// best predicted film.
pub fn import(path: &Path, size: Size, bands: &Bands) -> Result<Imported, ShapeError> {
    let mut all = import_candidates(path, size, bands)?;
    Ok(all.swap_remove(0))
}

/// Every stage from the file to the font text, for each candidate
/// decomposition ([`candidates`], best predicted first; never empty).
pub fn import_candidates(
    path: &Path,
    size: Size,
    bands: &Bands,
) -> Result<Vec<Imported>, ShapeError> {
    let outline = read(path)?;
    import_outline(&outline, size, bands)
}

/// [`import_candidates`] of an outline already read.
pub fn import_outline(
    outline: &Outline,
    size: Size,
    bands: &Bands,
) -> Result<Vec<Imported>, ShapeError> {
    limits::check_outline(outline)?;
    let scale = scale_for(outline, size)?;
    let bb = bounds(outline);
    let (width_m, height_m) = (bb.width() * scale, bb.height() * scale);
    limits::check_scaled(outline, scale, width_m)?;
    let regions = regions(outline, scale)?;
    let all = candidates(&regions, bands, &outline.origin)?;
    if all.iter().all(|d| d.strokes.is_empty()) {
        return Err(ShapeError::invalid(
            &outline.origin,
            format!(
                "the shape is everywhere narrower than the fan paints ({:.3} m): \
                 give a larger --shape-height-m",
                bands.min_width_m
            ),
        ));
    }
    Ok(all
        .into_iter()
        .filter(|d| !d.strokes.is_empty())
        .map(|decomposition| {
            let toml = font_toml(&decomposition, width_m, height_m, &outline.origin, &[]);
            Imported {
                decomposition,
                width_m,
                height_m,
                source: outline.origin.clone(),
                notes: vec![],
                toml,
            }
        })
        .collect())
}

/// Methods a region's report line names besides the one kept (the font
/// file's header lists them all). assumed: three fit a terminal line or two.
const REPORT_OTHERS: usize = 3;

/// Lines for a person: the method per region and the narrow places.
pub fn report_lines(d: &Decomposition, bands: &Bands) -> Vec<String> {
    let mut out = vec![];
    for (i, r) in d.regions.iter().enumerate() {
        out.push(format!(
            "region {}: {:.3} m², {}: {} strokes, predicted {:.0} s, film error {:.1} %{}",
            i + 1,
            r.area_m2,
            r.chosen.method,
            r.chosen.strokes,
            r.chosen.time_s,
            100.0 * r.chosen.film_error,
            r.others
                .iter()
                .take(REPORT_OTHERS)
                .map(|o| format!(
                    "; not {} ({} strokes, {:.0} s, {:.1} %)",
                    o.method,
                    o.strokes,
                    o.time_s,
                    100.0 * o.film_error
                ))
                .chain((r.others.len() > REPORT_OTHERS).then(|| format!(
                    "; {} more in the font file's header",
                    r.others.len() - REPORT_OTHERS
                )))
                .collect::<String>()
        ));
    }
    for n in &d.narrow {
        out.push(format!(
            "narrow: near ({:.3}, {:.3}) m from the shape's lower-left corner the shape is {:.3} m \
             wide over {:.3} m, {:.3} m narrower than the fan's narrowest band ({:.3} m): \
             {:.4} m² left bare, {:.4} m² sprayed outside",
            n.at.x,
            n.at.y,
            n.width_m,
            n.length_m,
            n.shortfall_m,
            bands.min_width_m,
            n.unpainted_m2,
            n.overspray_m2
        ));
    }
    for s in &d.steep {
        out.push(format!(
            "steep end: near ({:.3}, {:.3}) m from the shape's lower-left corner a band's width \
             changes faster than the nozzle height follows; its last {:.3} m past a {:.3} m rung \
             are left bare: {:.4} m²",
            s.at.x, s.at.y, s.length_m, s.width_m, s.unpainted_m2
        ));
    }
    out
}
