//! The letters' outlines on the film raster: each glyph's stroke polygons
//! in the road frame, and which cells of a grid they cover — the fraction of
//! each cell inside (exact horizontal coverage on `SUB_ROWS` sub-rows per
//! cell row) and the lattice points inside, by which `metrics` judges the
//! cells the outline cuts (docs/preview.md, "Coverage at the outline").

use rayon::prelude::*;

use super::raster::{Bounds, Grid};

/// Sub-rows per cell row when rasterising outlines: the lattice of
/// `raster::Letters`, whose points are the sub-rows' centres.
pub(super) const SUB_ROWS: usize = super::raster::LATTICE;
/// A cell is "wholly inside" above this fraction.
pub(super) const INSIDE: f64 = 0.999;

/// One glyph's outlines in the road frame: each stroke's closed polygon.
#[derive(Clone, Debug)]
pub struct GlyphOutline {
    pub label: String,
    pub line: usize,
    pub strokes: Vec<Vec<[f64; 2]>>,
}

impl GlyphOutline {
    /// From the job's placed glyph: each stroke's outline is the left edge
    /// forward then the right edge reversed (src/job/mod.rs).
    pub fn from_placed(g: &basr_job::PlacedGlyph) -> GlyphOutline {
        GlyphOutline {
            label: g.char.clone(),
            line: g.line,
            strokes: g
                .strokes
                .iter()
                .map(|s| {
                    s.left
                        .iter()
                        .copied()
                        .chain(s.right.iter().rev().copied())
                        .collect()
                })
                .collect(),
        }
    }

    pub fn bounds(&self) -> Bounds {
        let mut b = Bounds::EMPTY;
        self.strokes.iter().flatten().for_each(|&p| b.include(p));
        b
    }

    /// Even-odd inside test against each stroke polygon.
    pub fn contains(&self, p: [f64; 2]) -> bool {
        self.strokes.iter().any(|poly| polygon_contains(poly, p))
    }
}

fn polygon_contains(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = poly.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

pub(super) fn signed_area(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// One grid cell a glyph's outlines reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaskCell {
    /// Cell index (`j * nx + i`).
    pub k: usize,
    /// Fraction of the cell inside the outlines.
    pub f: f64,
    /// Which points of the cell's `SUB_ROWS` × `SUB_ROWS` lattice lie
    /// inside (bit `row * SUB_ROWS + column`, row 0 at the cell's low y):
    /// the points at which [`edge_cell_share`] judges a cell the outline
    /// cuts.
    pub inside: u64,
}

/// Lattice points per cell side: one per sub-row, so the lattice's rows
/// are the sub-rows' centres and `inside` fits a `u64`.
const _: () = assert!(SUB_ROWS * SUB_ROWS <= 64);

/// The grid cells inside a glyph (sparse), with the fraction of each and
/// its inside lattice points.
pub fn coverage_mask(grid: &Grid, glyph: &GlyphOutline) -> Vec<MaskCell> {
    let h = grid.cell_m;
    let sh = h / SUB_ROWS as f64;
    let b = glyph.bounds();
    if b.is_empty() {
        return Vec::new();
    }
    let clamp_row = |v: f64| (v.max(0.0) as usize).min(grid.ny * SUB_ROWS);
    let s0 = clamp_row(((b.min[1] - grid.y0) / sh - 0.5).floor());
    let s1 = clamp_row(((b.max[1] - grid.y0) / sh + 0.5).ceil());
    if s1 <= s0 {
        return Vec::new();
    }
    let i0 = (((b.min[0] - grid.x0) / h).floor().max(0.0) as usize).min(grid.nx);
    let i1 = (((b.max[0] - grid.x0) / h).ceil().max(0.0) as usize).min(grid.nx);
    let (wx, rows) = (i1.saturating_sub(i0), s1 - s0);
    let mut local = vec![0.0f64; wx * rows.div_ceil(SUB_ROWS) + wx];
    let mut bits = vec![0u64; local.len()];
    let row_j0 = s0 / SUB_ROWS;
    // Per sub-row, per stroke: crossings.
    let mut crossings: Vec<Vec<f64>> = vec![Vec::new(); rows];
    let mut intervals: Vec<Vec<(f64, f64)>> = vec![Vec::new(); rows];
    for poly in &glyph.strokes {
        crossings.iter_mut().for_each(|c| c.clear());
        let n = poly.len();
        for k in 0..n {
            let (a, c) = (poly[k], poly[(k + 1) % n]);
            if a[1] == c[1] {
                continue;
            }
            let (lo, hi) = if a[1] < c[1] { (a, c) } else { (c, a) };
            // Sub-rows whose centre y lies in [lo.y, hi.y).
            let first = ((lo[1] - grid.y0) / sh - 0.5).ceil().max(s0 as f64) as usize;
            let last = ((hi[1] - grid.y0) / sh - 0.5).ceil().min(s1 as f64) as usize;
            for s in first..last {
                let y = grid.y0 + (s as f64 + 0.5) * sh;
                let x = lo[0] + (y - lo[1]) / (hi[1] - lo[1]) * (hi[0] - lo[0]);
                crossings[s - s0].push(x);
            }
        }
        for (r, c) in crossings.iter_mut().enumerate() {
            c.sort_by(f64::total_cmp);
            for pair in c.chunks_exact(2) {
                intervals[r].push((pair[0], pair[1]));
            }
        }
    }
    for (r, iv) in intervals.iter_mut().enumerate() {
        if iv.is_empty() {
            continue;
        }
        iv.sort_by(|a, b| a.0.total_cmp(&b.0));
        let jl = (s0 + r) / SUB_ROWS - row_j0;
        let row_bit = ((s0 + r) % SUB_ROWS) * SUB_ROWS;
        let mut merged: Vec<(f64, f64)> = Vec::new();
        for &(a, b) in iv.iter() {
            match merged.last_mut() {
                Some(m) if a <= m.1 => m.1 = m.1.max(b),
                _ => merged.push((a, b)),
            }
        }
        for (a, b) in merged {
            // Exact covered length in each cell of this sub-row.
            let fa = ((a - grid.x0) / h).max(i0 as f64).min(i1 as f64);
            let fb = ((b - grid.x0) / h).max(i0 as f64).min(i1 as f64);
            if fb <= fa {
                continue;
            }
            let (ca, cb) = (fa.floor() as usize, (fb.ceil() as usize).max(1) - 1);
            for i in ca..=cb.min(i1.saturating_sub(1)) {
                let lo = fa.max(i as f64);
                let hi = fb.min(i as f64 + 1.0);
                if hi > lo {
                    local[jl * wx + (i - i0)] += (hi - lo) / SUB_ROWS as f64;
                }
                // This sub-row's lattice points in [fa, fb): columns at
                // (a + ½) / SUB_ROWS of the cell.
                let per = SUB_ROWS as f64;
                let col = |u: f64| ((u - i as f64) * per - 0.5).ceil().clamp(0.0, per) as u32;
                let (a0, a1) = (col(fa), col(fb));
                if a1 > a0 {
                    let row = ((1u64 << a1) - 1) & !((1u64 << a0) - 1);
                    bits[jl * wx + (i - i0)] |= row << row_bit;
                }
            }
        }
    }
    let mut out = Vec::new();
    for (k, &f) in local.iter().enumerate() {
        if f > 0.0 {
            let (jl, il) = (k / wx, k % wx);
            let j = row_j0 + jl;
            if j < grid.ny {
                out.push(MaskCell {
                    k: j * grid.nx + i0 + il,
                    f: f.min(1.0),
                    inside: bits[k],
                });
            }
        }
    }
    out
}

/// The masks of the glyphs `ids` of `glyphs` on `grid`, in `ids`' order.
pub fn glyph_masks(grid: &Grid, glyphs: &[GlyphOutline], ids: &[usize]) -> Vec<Vec<MaskCell>> {
    ids.par_iter()
        .map(|&gi| coverage_mask(grid, &glyphs[gi]))
        .collect()
}

/// The lattice points of every cell of `grid` that lie inside the glyphs
/// whose `masks` these are (`raster::Letters`): the union of their masks'.
pub fn inside_lattice(grid: &Grid, masks: &[Vec<MaskCell>]) -> Vec<u64> {
    let mut bits = vec![0u64; grid.nx * grid.ny];
    for m in masks.iter().flatten() {
        bits[m.k] |= m.inside;
    }
    bits
}

/// The masks of some glyphs on the grid a film is laid on, made once for
/// both the deposit's judging where the paint lands (`lattice`, the
/// `raster::Letters` of the film) and the metrics (`take`).
pub struct Masks<'a> {
    glyphs: &'a [GlyphOutline],
    ids: &'a [usize],
    /// The masks made and the grid they were made on.
    made: std::sync::OnceLock<(GridKey, Vec<Vec<MaskCell>>)>,
}

/// What places a grid's cells: origin and cell size (bits), and extent.
type GridKey = ([u64; 3], [usize; 2]);

fn key_of(grid: &Grid) -> GridKey {
    (
        [grid.x0.to_bits(), grid.y0.to_bits(), grid.cell_m.to_bits()],
        [grid.nx, grid.ny],
    )
}

impl<'a> Masks<'a> {
    /// The glyphs `ids` of `glyphs`.
    pub fn of(glyphs: &'a [GlyphOutline], ids: &'a [usize]) -> Masks<'a> {
        Masks {
            glyphs,
            ids,
            made: std::sync::OnceLock::new(),
        }
    }

    /// Their lattice on `grid` (the film's), keeping the masks.
    pub fn lattice(&self, grid: &Grid) -> Vec<u64> {
        let masks = glyph_masks(grid, self.glyphs, self.ids);
        let bits = inside_lattice(grid, &masks);
        let _ = self.made.set((key_of(grid), masks));
        bits
    }

    /// The masks on `grid`, the film's: those made for its lattice, or
    /// made now (a film laid without them, or on another grid).
    pub fn take(self, grid: &Grid) -> Vec<Vec<MaskCell>> {
        let (glyphs, ids) = (self.glyphs, self.ids);
        match self.made.into_inner() {
            Some((key, masks)) if key == key_of(grid) => masks,
            _ => glyph_masks(grid, glyphs, ids),
        }
    }
}

/// Share of the area of `cells` whose film reaches `level`: a cell wholly
/// inside is judged by its own film, a cell the outline cuts by its inside
/// lattice points ([`edge_cell_share`]).
pub(super) fn coverage_share(
    grid: &Grid,
    cells: impl Iterator<Item = MaskCell>,
    level: f64,
) -> Option<f64> {
    let [a, c] = coverage_sums(grid, cells, level);
    (a > 0.0).then(|| c / a)
}

/// [`coverage_share`]'s two sums: the cells' letter area (in cells) and
/// its covered part.
pub(super) fn coverage_sums(
    grid: &Grid,
    cells: impl Iterator<Item = MaskCell>,
    level: f64,
) -> [f64; 2] {
    let (mut a, mut c) = (0.0, 0.0);
    for m in cells {
        a += m.f;
        let whole = || f64::from(u8::from(grid.data[m.k] >= level));
        let share = if m.f >= INSIDE {
            whole()
        } else {
            edge_cell_share(grid, m.k, m.inside, level).unwrap_or_else(whole)
        };
        c += m.f * share;
    }
    [a, c]
}

/// Covered share of a cell that an outline cuts: of the cell's lattice
/// points inside the outlines (`inside`, as in [`MaskCell`]), the share
/// whose film, interpolated bilinearly between cell centres, reaches
/// `level`. `None` when no lattice point lies inside (a sliver; the caller
/// judges the cell by its own film).
///
/// A cell's film is the average over the whole cell, road outside the
/// outline included, so a cell half inside an edge that the fan paints
/// exactly carries about half the film and the cell average alone would
/// call its inside part bare. Judging the inside points makes coverage
/// independent of where the outline falls within a cell (docs/preview.md,
/// "Coverage at the outline").
fn edge_cell_share(grid: &Grid, k: usize, inside: u64, level: f64) -> Option<f64> {
    if inside == 0 {
        return None;
    }
    let (i, j) = (k % grid.nx, k / grid.nx);
    let step = grid.cell_m / SUB_ROWS as f64;
    let (x0, y0) = (
        grid.x0 + i as f64 * grid.cell_m,
        grid.y0 + j as f64 * grid.cell_m,
    );
    let ok = (0..SUB_ROWS * SUB_ROWS)
        .filter(|&bit| inside >> bit & 1 == 1)
        .filter(|&bit| {
            let (row, col) = (bit / SUB_ROWS, bit % SUB_ROWS);
            let p = [
                x0 + (col as f64 + 0.5) * step,
                y0 + (row as f64 + 0.5) * step,
            ];
            grid.sample(p) >= level
        })
        .count();
    Some(ok as f64 / f64::from(inside.count_ones()))
}
