//! A long job's film, band by band along the road.
//!
//! A job's film is measured on one raster over everything it paints and
//! every letter. For a long job that raster is most of its memory: the
//! 200-letter message's was 306 MB of film and as much again of the
//! letters' cell fractions, five times its 128 MB job file. Its lines
//! stand metres apart along the road, and no paint of one line lands on
//! another, so a raster that holds at most [`BAND_CELLS`] is laid and
//! measured whole, and a larger one is cut across the road into bands:
//! each band holds the intervals whose paint lands in it and the letters
//! that lie in it, no interval's paint and no letter is in two bands, and
//! the bands are laid, measured (`metrics::measure_part`) and dropped one
//! after another; their sums make the job's metrics (`metrics::finish`).
//! Each band's raster sits on the whole raster's lattice, so its cells
//! are the whole raster's there (their sums taken in another order).

use super::mask::GlyphOutline;
use super::raster::{self, Bounds};
use super::spray::{Pose, SprayModel};
use super::PaintError;

/// Cells of the largest raster laid whole (8 MB of film). assumed: a
/// one-line word at 8 ft across a 12 ft lane is about 0.5 M cells at the
/// 5 mm default; four times that keeps every job of a line or two on one
/// raster as before, and a long job's band rasters to tens of MB.
pub const BAND_CELLS: usize = 2_000_000;

/// Road (m) between two bands at the least: closer, what lies on either
/// side joins one band. assumed: half a metre, more than a fan's footprint
/// and the edge profiles' reach (`metrics`), so a cell's paint outside
/// the letters is not nearer another band's letter than its own band's
/// unless the paint strays half a metre from every letter.
pub const BAND_GAP_M: f64 = 0.5;

/// One band: what is laid and measured together.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The painted intervals (i: pose i to pose i + 1) whose paint lands
    /// in it, in time order.
    pub intervals: Vec<usize>,
    /// The glyphs (indices into the outlines) that lie in it.
    pub glyphs: Vec<usize>,
    /// What its raster covers: the intervals' paint and the glyphs.
    pub extent: Bounds,
}

/// Whether the raster over `extent` at `cell_m` is laid whole: it holds
/// at most `most` cells (two cells of margin each side, as laid).
pub fn whole(extent: Bounds, cell_m: f64, most: usize) -> bool {
    let cells = (extent.width() / cell_m + 5.0) * (extent.height() / cell_m + 5.0);
    cells <= most as f64
}

/// The bands of `poses`' `painted` intervals and `outlines`, in the order
/// of the road (y). `reach`: how far beyond a footprint's bounds paint may
/// land (the sheet's depth); `cell_m`, the raster's cell.
pub fn bands(
    poses: &[Pose],
    painted: &[usize],
    model: &SprayModel,
    reach: f64,
    outlines: &[GlyphOutline],
    cell_m: f64,
) -> Result<Vec<Band>, PaintError> {
    // What each item covers: an interval its two footprints (and the
    // depth's reach), a glyph its box.
    enum Item {
        Interval(usize),
        Glyph(usize),
    }
    let mut items: Vec<(Bounds, Item)> = Vec::with_capacity(painted.len() + outlines.len());
    for &i in painted {
        let b = raster::interval_bounds(poses, i, model)?;
        items.push((b.grow(reach), Item::Interval(i)));
    }
    for (g, outline) in outlines.iter().enumerate() {
        let b = outline.bounds();
        if !b.is_empty() {
            items.push((b, Item::Glyph(g)));
        }
    }
    // Sorted by where they start along the road, then swept: an item that
    // starts within the gap of the band's end joins it.
    items.sort_by(|a, b| a.0.min[1].total_cmp(&b.0.min[1]));
    let gap = BAND_GAP_M.max(8.0 * cell_m);
    let mut out: Vec<Band> = Vec::new();
    for (b, item) in items {
        let join = out
            .last()
            .is_some_and(|band| b.min[1] <= band.extent.max[1] + gap);
        if !join {
            out.push(Band {
                intervals: Vec::new(),
                glyphs: Vec::new(),
                extent: b,
            });
        }
        let Some(band) = out.last_mut() else {
            continue;
        };
        band.extent = band.extent.union(b);
        match item {
            Item::Interval(i) => band.intervals.push(i),
            Item::Glyph(g) => band.glyphs.push(g),
        }
    }
    for band in &mut out {
        band.intervals.sort_unstable();
        band.glyphs.sort_unstable();
    }
    Ok(out)
}
