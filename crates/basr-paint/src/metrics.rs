//! Judging a film raster against the letters' true outlines: mean film,
//! evenness, coverage, overspray, edge sharpness and the seed's tile area
//! ratio U (001 eq. 2.7–2.8), overall and per glyph.
//!
//! Definitions (all documented in README "Preview"):
//! - letter area: the union of the strokes' outline polygons, rasterised
//!   with exact horizontal coverage on `SUB_ROWS` sub-rows per cell row, so
//!   each cell carries the fraction of it inside a letter;
//! - interior: cells wholly inside whose 8 neighbours are wholly inside; the
//!   mean film and the coefficient of variation are taken there, so that the
//!   raster's one-cell blur at the outline does not count as unevenness;
//! - coverage: share of the letter area whose film is ≥ 50 % of target; a
//!   cell the outline cuts is judged by its lattice points inside the
//!   outline, at the film interpolated between cell centres;
//! - overspray: share of the volume on the road lying outside the outlines,
//!   each piece of the fan judged where it landed (`raster::Letters`), not
//!   by the cells its bilinear splat spread it over;
//! - edge width: along true letter edges (film-free road just outside), the
//!   distance over which the film falls from 90 % to 10 % of the film just
//!   inside; median and 90th percentile over points every cell along edges;
//! - U: for each pair of consecutive painted poses of a stroke, the fan
//!   lines as laid and the points where the nozzle axis meets the road split
//!   the swept quadrilateral into two tiles; U = A/(A_i + A_j) of each tile
//!   (0.5 ideal; above 0.5 the same paint covers more road, so a lighter film).

use rayon::prelude::*;
use serde::Serialize;

use super::boxes::BoxIndex;
pub use super::mask::{coverage_mask, GlyphOutline, MaskCell};
use super::mask::{coverage_share, coverage_sums, signed_area, INSIDE};
use super::raster::{Bounds, Film, Grid};
use super::spray::{equivalent_fan, Pose, SprayModel};
use super::PaintError;

/// Film threshold of coverage, as a share of target (issue 5).
pub const COVERAGE_SHARE: f64 = 0.5;

/// Min and max of U over a set of tiles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct URange {
    pub u_min: f64,
    pub u_max: f64,
    pub tiles: usize,
}

/// U over the tiles of one stroke (job stroke index).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrokeU {
    pub stroke: i64,
    /// Index into the glyph table, when the stroke lies on a glyph.
    pub glyph: Option<usize>,
    #[serde(flatten)]
    pub u: URange,
}

/// Metrics of one glyph.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GlyphMetrics {
    pub char: String,
    pub line: usize,
    pub area_m2: f64,
    pub mean_film_m: Option<f64>,
    pub cv: Option<f64>,
    pub coverage: Option<f64>,
    pub overspray: Option<f64>,
    pub u_min: Option<f64>,
    pub u_max: Option<f64>,
}

/// Everything the preview measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metrics {
    pub target_film_m: f64,
    /// Mean film over the letters' interior.
    pub mean_film_m: Option<f64>,
    /// Coefficient of variation of the film over the letters' interior.
    pub cv: Option<f64>,
    /// Share of letter area with film ≥ 50 % of target.
    pub coverage: Option<f64>,
    /// Share of the volume on the road outside the letters.
    pub overspray: Option<f64>,
    pub u_min: Option<f64>,
    pub u_max: Option<f64>,
    /// Median 90 %→10 % edge width over true letter edges (m).
    pub edge_width_m: Option<f64>,
    pub edge_width_p90_m: Option<f64>,
    /// Edge points measured / considered.
    pub edge_points: usize,
    pub letter_area_m2: f64,
    pub volume_on_road_m3: f64,
    /// Flow × efficiency × gun-on time (m³).
    pub volume_laid_m3: f64,
    pub gun_on_s: f64,
    pub resolution_m: f64,
    pub glyphs: Vec<GlyphMetrics>,
    pub strokes: Vec<StrokeU>,
    /// Each glyph's heaviest film: the fullest raster cell in its outline's
    /// box and that cell's centre (none for a box off the raster). Not
    /// printed: compile's film note names it (`pipeline::film`).
    #[serde(skip)]
    pub peaks: Vec<Option<Peak>>,
}

/// The fullest raster cell over a glyph's box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// Its film (m).
    pub film_m: f64,
    /// Its centre on the road (m).
    pub at_m: [f64; 2],
}

/// Mean and CV of `values` weighted by `weights`.
fn mean_cv(cells: impl Iterator<Item = (f64, f64)>) -> (Option<f64>, Option<f64>) {
    mean_cv_of(weighted_sums(cells))
}

/// Σw, Σw·v and Σw·v² of weighted `cells`.
fn weighted_sums(cells: impl Iterator<Item = (f64, f64)>) -> [f64; 3] {
    let (mut sw, mut s1, mut s2) = (0.0, 0.0, 0.0);
    for (v, w) in cells {
        sw += w;
        s1 += w * v;
        s2 += w * v * v;
    }
    [sw, s1, s2]
}

/// Mean and CV from [`weighted_sums`].
fn mean_cv_of([sw, s1, s2]: [f64; 3]) -> (Option<f64>, Option<f64>) {
    if sw <= 0.0 {
        return (None, None);
    }
    let mean = s1 / sw;
    let var = (s2 / sw - mean * mean).max(0.0);
    let cv = if mean > 0.0 {
        Some(var.sqrt() / mean)
    } else {
        None
    };
    (Some(mean), cv)
}

/// Measure `film` against `glyphs` (outlines, whose `masks` on the film's
/// grid these are: `mask::Masks`) for a `target_film_m`, with
/// `poses` (and their job stroke index, −1 when none) for U.
pub fn measure(
    film: &Film,
    masks: Vec<Vec<MaskCell>>,
    glyphs: &[GlyphOutline],
    target_film_m: f64,
    model: &SprayModel,
    poses: &[Pose],
    stroke_of: &[i64],
) -> Result<Metrics, PaintError> {
    // U per stroke, then the stroke's glyph by majority of its rung centres.
    let strokes = stroke_u(model, poses, stroke_of, glyphs)?;
    let all: Vec<usize> = (0..glyphs.len()).collect();
    let parts = measure_part(film, masks, glyphs, &all, target_film_m, &strokes);
    Ok(finish(
        vec![parts],
        Whole {
            target_film_m,
            resolution_m: film.grid.cell_m,
            volume_laid_m3: film.laid_m3,
            gun_on_s: film.gun_on_s,
            glyphs,
        },
        strokes,
    ))
}

/// What one raster (the whole job's, or one band's of a long job:
/// `bands`) adds to the job's metrics: sums that add up over rasters
/// that share no paint and no glyph, and the rows of the glyphs on it.
pub struct Part {
    /// Σ1, Σfilm, Σfilm² over the interior cells.
    interior: [f64; 3],
    /// Letter area and its covered share's sum, in cells (`coverage_sums`).
    covered: [f64; 2],
    /// Σ of the letters' cell fractions.
    letter_cells: f64,
    /// Σ film over every cell, and over what lies outside the letters
    /// (`None` for a film laid without them: no overspray).
    film_sum: f64,
    outside_sum: Option<f64>,
    /// Each glyph on it: its index in the job's glyphs, its row and peak.
    glyphs: Vec<(usize, GlyphMetrics, Option<Peak>)>,
    /// The edge widths measured and the true edge points considered.
    edge_widths: Vec<f64>,
    edge_considered: usize,
}

/// What [`finish`] takes of the whole job besides its parts.
pub struct Whole<'a> {
    pub target_film_m: f64,
    pub resolution_m: f64,
    pub volume_laid_m3: f64,
    pub gun_on_s: f64,
    /// The job's glyphs (each on one part).
    pub glyphs: &'a [GlyphOutline],
}

/// The part of the metrics `film` holds, for the glyphs `ids` of `glyphs`
/// (those wholly on it), whose `masks` on the film's grid these are (in
/// `ids`' order, `mask::Masks`); `strokes`, the job's U per stroke.
pub fn measure_part(
    film: &Film,
    masks: Vec<Vec<MaskCell>>,
    glyphs: &[GlyphOutline],
    ids: &[usize],
    target_film_m: f64,
    strokes: &[StrokeU],
) -> Part {
    let g = &film.grid;
    let n = g.nx * g.ny;
    let area = g.cell_m * g.cell_m;
    debug_assert_eq!(masks.len(), ids.len(), "a mask per glyph measured");
    let mut frac = vec![0.0f64; n];
    // Inside lattice points of the cells an outline cuts, over all glyphs.
    let mut edge_bits: std::collections::HashMap<usize, u64> = Default::default();
    for m in masks.iter().flatten() {
        frac[m.k] = (frac[m.k] + m.f).min(1.0);
        if m.f < INSIDE {
            *edge_bits.entry(m.k).or_default() |= m.inside;
        }
    }
    let interior = |k: usize| -> bool {
        let (i, j) = (k % g.nx, k / g.nx);
        if i == 0 || j == 0 || i + 1 >= g.nx || j + 1 >= g.ny {
            return false;
        }
        (j - 1..=j + 1).all(|jj| (i - 1..=i + 1).all(|ii| frac[jj * g.nx + ii] >= INSIDE))
    };
    let level = COVERAGE_SHARE * target_film_m;
    let interior_sums = weighted_sums(
        (0..n)
            .filter(|&k| frac[k] >= INSIDE && interior(k))
            .map(|k| (g.data[k], 1.0)),
    );
    let covered = coverage_sums(
        g,
        (0..n).filter(|&k| frac[k] > 0.0).map(|k| MaskCell {
            k,
            f: frac[k],
            inside: edge_bits.get(&k).copied().unwrap_or(u64::MAX),
        }),
        level,
    );
    // The paint that landed outside the letters, judged where it landed
    // (`raster::Letters`); a film laid without them has no overspray.
    let outside = |k: usize| film.outside.as_ref().map_or(0.0, |o| o[k]);
    let outside_sum: Option<f64> = film.outside.as_ref().map(|o| o.iter().sum::<f64>());

    // Per glyph: its cells' paint, and the paint outside the letters in
    // each cell, go to the glyph whose box is nearest the cell.
    let boxes: Vec<Bounds> = ids.iter().map(|&gi| glyphs[gi].bounds()).collect();
    let mut owner_vol = vec![(0.0f64, 0.0f64); ids.len()]; // (total, outside)
    if !ids.is_empty() {
        let index = BoxIndex::new(g, &boxes);
        for (k, &v) in g.data.iter().enumerate() {
            let o = outside(k);
            if v <= 0.0 && o <= 0.0 {
                continue;
            }
            let (i, j) = (k % g.nx, k / g.nx);
            let best = index.nearest(i, j, g.centre(i, j));
            owner_vol[best].0 += v * area;
            owner_vol[best].1 += o * area;
        }
    }
    let rows = ids
        .par_iter()
        .enumerate()
        .map(|(bi, &gi)| {
            let gl = &glyphs[gi];
            let m = &masks[bi];
            let (gm, gcv) = mean_cv(
                m.iter()
                    .filter(|c| c.f >= INSIDE && interior(c.k))
                    .map(|c| (g.data[c.k], 1.0)),
            );
            let u = merge_u(strokes.iter().filter(|s| s.glyph == Some(gi)).map(|s| s.u));
            let row = GlyphMetrics {
                char: gl.label.clone(),
                line: gl.line,
                area_m2: m.iter().map(|c| c.f).sum::<f64>() * area,
                mean_film_m: gm,
                cv: gcv,
                coverage: coverage_share(g, m.iter().copied(), level),
                overspray: (outside_sum.is_some() && owner_vol[bi].0 > 0.0)
                    .then(|| owner_vol[bi].1 / owner_vol[bi].0),
                u_min: u.map(|u| u.u_min),
                u_max: u.map(|u| u.u_max),
            };
            (gi, row, peak_over(g, boxes[bi]))
        })
        .collect();
    let outlines: Vec<&GlyphOutline> = ids.iter().map(|&gi| &glyphs[gi]).collect();
    let (edge_widths, edge_considered) = edge_samples(g, &outlines, &frac, target_film_m);
    Part {
        interior: interior_sums,
        covered,
        letter_cells: frac.iter().sum::<f64>(),
        film_sum: g.data.iter().sum::<f64>(),
        outside_sum,
        glyphs: rows,
        edge_widths,
        edge_considered,
    }
}

/// The fullest cell of `g` over box `b` (the cells whose index range the
/// box's corners give, clipped to the grid).
fn peak_over(g: &Grid, b: Bounds) -> Option<Peak> {
    let index = |v: f64, o: f64, n: usize| (((v - o) / g.cell_m).floor().max(0.0) as usize).min(n);
    let (i0, i1) = (index(b.min[0], g.x0, g.nx), index(b.max[0], g.x0, g.nx));
    let (j0, j1) = (index(b.min[1], g.y0, g.ny), index(b.max[1], g.y0, g.ny));
    let mut best: Option<Peak> = None;
    for j in j0..j1 {
        for i in i0..i1 {
            let v = g.data[j * g.nx + i];
            if best.is_none_or(|p| v > p.film_m) {
                best = Some(Peak {
                    film_m: v,
                    at_m: g.centre(i, j),
                });
            }
        }
    }
    best
}

/// The job's metrics from the parts of its rasters (one, or one per band
/// of a long job, in the order of the road) and `strokes`' U.
pub fn finish(parts: Vec<Part>, whole: Whole<'_>, strokes: Vec<StrokeU>) -> Metrics {
    let h = whole.resolution_m;
    let area = h * h;
    let add = |f: &dyn Fn(&Part) -> f64| parts.iter().fold(0.0, |s, p| s + f(p));
    let interior = [0, 1, 2].map(|i| add(&|p| p.interior[i]));
    let (mean, cv) = mean_cv_of(interior);
    let covered = [add(&|p| p.covered[0]), add(&|p| p.covered[1])];
    // (Σ·h)·h and Σ·(h·h), as `Grid::volume` and the single raster's
    // outside sum took them: one part gives its figures bit for bit.
    let volume = add(&|p| p.film_sum) * h * h;
    // No overspray unless every part judged where its paint landed.
    let outside = parts
        .iter()
        .try_fold(0.0, |s, p| p.outside_sum.map(|o| s + o))
        .map(|o| o * area);
    let overspray = outside.filter(|_| volume > 0.0).map(|o| o / volume);
    let all_u = merge_u(strokes.iter().map(|s| s.u));
    let mut widths: Vec<f64> = parts
        .iter()
        .flat_map(|p| p.edge_widths.iter().copied())
        .collect();
    let considered = parts.iter().map(|p| p.edge_considered).sum();
    let (edge_width, edge_p90, edge_points) = edge_figures(&mut widths, considered);
    let letter_area = add(&|p| p.letter_cells) * area;
    let mut rows: Vec<Option<(GlyphMetrics, Option<Peak>)>> = vec![None; whole.glyphs.len()];
    for p in parts {
        for (gi, row, peak) in p.glyphs {
            if let Some(slot) = rows.get_mut(gi) {
                *slot = Some((row, peak));
            }
        }
    }
    // Every glyph lies on one part (`bands`); one that did not would have
    // no figures rather than shift the rows after it.
    let (glyphs, peaks) = rows
        .into_iter()
        .zip(whole.glyphs)
        .map(|(row, gl)| {
            row.unwrap_or_else(|| {
                let none = GlyphMetrics {
                    char: gl.label.clone(),
                    line: gl.line,
                    area_m2: 0.0,
                    mean_film_m: None,
                    cv: None,
                    coverage: None,
                    overspray: None,
                    u_min: None,
                    u_max: None,
                };
                (none, None)
            })
        })
        .unzip();
    Metrics {
        target_film_m: whole.target_film_m,
        mean_film_m: mean,
        cv,
        coverage: (covered[0] > 0.0).then(|| covered[1] / covered[0]),
        overspray,
        u_min: all_u.map(|u| u.u_min),
        u_max: all_u.map(|u| u.u_max),
        edge_width_m: edge_width,
        edge_width_p90_m: edge_p90,
        edge_points,
        letter_area_m2: letter_area,
        volume_on_road_m3: volume,
        volume_laid_m3: whole.volume_laid_m3,
        gun_on_s: whole.gun_on_s,
        resolution_m: h,
        glyphs,
        strokes,
        peaks,
    }
}

fn merge_u(it: impl Iterator<Item = URange>) -> Option<URange> {
    it.fold(None, |acc: Option<URange>, u| {
        Some(match acc {
            None => u,
            Some(a) => URange {
                u_min: a.u_min.min(u.u_min),
                u_max: a.u_max.max(u.u_max),
                tiles: a.tiles + u.tiles,
            },
        })
    })
}

fn quad_area(p: [[f64; 2]; 4]) -> f64 {
    signed_area(&p).abs()
}

/// The seed's tile ratio U (001 eq. 2.7–2.8) over each stroke's tiles.
pub fn stroke_u(
    model: &SprayModel,
    poses: &[Pose],
    stroke_of: &[i64],
    glyphs: &[GlyphOutline],
) -> Result<Vec<StrokeU>, PaintError> {
    let mut out: Vec<StrokeU> = Vec::new();
    let mut votes: Vec<Vec<usize>> = Vec::new();
    // A point outside a glyph's box is outside its outline: the box is
    // tried first (the outline test over every glyph grew with the square
    // of a long job's letters, issue 28).
    let boxes: Vec<Bounds> = glyphs.iter().map(GlyphOutline::bounds).collect();
    let in_box = |b: &Bounds, p: [f64; 2]| {
        b.min[0] <= p[0] && p[0] <= b.max[0] && b.min[1] <= p[1] && p[1] <= b.max[1]
    };
    for k in 0..poses.len().saturating_sub(1) {
        let (a, b) = (&poses[k], &poses[k + 1]);
        let s = stroke_of.get(k).copied().unwrap_or(-1);
        if !a.gun || s < 0 || stroke_of.get(k + 1).copied() != Some(s) {
            continue;
        }
        let fa = model.footprint(a)?;
        let (yaw, tilt) = equivalent_fan(a.yaw_rad, b.yaw_rad, b.tilt_rad);
        let fb = model.footprint(&Pose {
            yaw_rad: yaw,
            tilt_rad: tilt,
            ..*b
        })?;
        let aj = quad_area([fa.minus(), fa.divider(), fb.divider(), fb.minus()]);
        let ai = quad_area([fa.divider(), fa.plus(), fb.plus(), fb.divider()]);
        let total = ai + aj; // 001 eq. 2.8
        if out.last().map(|o| o.stroke) != Some(s) {
            out.push(StrokeU {
                stroke: s,
                glyph: None,
                u: URange {
                    u_min: f64::INFINITY,
                    u_max: f64::NEG_INFINITY,
                    tiles: 0,
                },
            });
            votes.push(vec![0; glyphs.len()]);
        }
        let last = out.len() - 1;
        let centre = fa.at(0.5 * (fa.r_minus + fa.r_plus));
        if let Some(gi) = glyphs
            .iter()
            .zip(&boxes)
            .position(|(g, b)| in_box(b, centre) && g.contains(centre))
        {
            votes[last][gi] += 1;
        }
        // assumed: tiles under 1 mm² (the gun starting or stopping in place)
        // carry no information about the distribution.
        if total < 1e-6 {
            continue;
        }
        let ui = ai / total; // 001 eq. 2.7
        let u = &mut out[last].u;
        u.u_min = u.u_min.min(ui).min(1.0 - ui);
        u.u_max = u.u_max.max(ui).max(1.0 - ui);
        u.tiles += 1;
    }
    for (o, v) in out.iter_mut().zip(&votes) {
        let best = v
            .iter()
            .enumerate()
            .max_by_key(|(i, c)| (**c, usize::MAX - i));
        o.glyph = best.filter(|(_, c)| **c > 0).map(|(i, _)| i);
    }
    // A stroke can appear in several runs (e.g. split by a pause): merge.
    let mut merged: Vec<StrokeU> = Vec::new();
    for s in out.into_iter().filter(|s| s.u.tiles > 0) {
        match merged.iter_mut().find(|m| m.stroke == s.stroke) {
            Some(m) => {
                m.u = merge_u([m.u, s.u].into_iter()).unwrap_or(m.u);
                m.glyph = m.glyph.or(s.glyph);
            }
            None => merged.push(s),
        }
    }
    merged.sort_by_key(|s| s.stroke);
    Ok(merged)
}

/// The 90 %→10 % edge widths along the true edges of `glyphs` on `g`
/// (`frac`: each cell's share inside the letters), and how many true edge
/// points were considered.
fn edge_samples(
    g: &Grid,
    glyphs: &[&GlyphOutline],
    frac: &[f64],
    target: f64,
) -> (Vec<f64>, usize) {
    let h = g.cell_m;
    // Off the raster is road: it covers every letter (a band's, its
    // letters), so an edge facing the raster's border is judged as one
    // facing more road, whatever the raster's extent.
    let frac_at = |p: [f64; 2]| -> Option<f64> {
        let i = ((p[0] - g.x0) / h).floor();
        let j = ((p[1] - g.y0) / h).floor();
        if !(i.is_finite() && j.is_finite()) {
            return None;
        }
        if i < 0.0 || j < 0.0 || i >= g.nx as f64 || j >= g.ny as f64 {
            return Some(0.0);
        }
        Some(frac[j as usize * g.nx + i as usize])
    };
    // assumed: profiles reach 6 cells or 40 mm either side, whichever is
    // wider, enough for the fan's depth and the raster's blur.
    let reach = (6.0 * h).max(0.04);
    let step = h / 4.0;
    let steps = (2.0 * reach / step).round() as usize;
    // Each glyph's edges on their own (in parallel), in the glyphs' order.
    let per_glyph: Vec<(Vec<f64>, usize)> = glyphs
        .par_iter()
        .map(|gl| {
            let mut widths = Vec::new();
            let mut considered = 0usize;
            edges_of(gl, h, |p, out| {
                let at = |s: f64| [p[0] + s * out[0], p[1] + s * out[1]];
                // A true edge: road just outside, letter just inside.
                let (fo, fi) = (frac_at(at(3.0 * h)), frac_at(at(-3.0 * h)));
                if !(fo == Some(0.0) && fi.is_some_and(|f| f >= INSIDE)) {
                    return;
                }
                considered += 1;
                let profile: Vec<(f64, f64)> = (0..=steps)
                    .map(|s| {
                        let off = -reach + s as f64 * step;
                        (off, g.sample(at(off)))
                    })
                    .collect();
                if let Some(w) = fall_width(&profile, target) {
                    widths.push(w);
                }
            });
            (widths, considered)
        })
        .collect();
    let considered = per_glyph.iter().map(|p| p.1).sum();
    let widths = per_glyph.into_iter().flat_map(|p| p.0).collect();
    (widths, considered)
}

/// Calls `visit` at points every cell `h` along each edge of `gl`'s
/// outlines, with the edge's outward normal there.
fn edges_of(gl: &GlyphOutline, h: f64, mut visit: impl FnMut([f64; 2], [f64; 2])) {
    for poly in &gl.strokes {
        let ccw = signed_area(poly) > 0.0;
        let n = poly.len();
        for k in 0..n {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            if len <= 0.0 {
                continue;
            }
            let d = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
            let out = if ccw { [d[1], -d[0]] } else { [-d[1], d[0]] };
            let count = (len / h).floor() as usize;
            for m in 0..count {
                let t = (m as f64 + 0.5) * len / count as f64;
                let p = [a[0] + t * d[0], a[1] + t * d[1]];
                visit(p, out);
            }
        }
    }
}

/// Median and 90th percentile of edge `widths`, and how many there are
/// (the points considered when none was measured).
fn edge_figures(widths: &mut [f64], considered: usize) -> (Option<f64>, Option<f64>, usize) {
    if widths.is_empty() {
        return (None, None, considered);
    }
    widths.sort_by(f64::total_cmp);
    let pick = |q: f64| widths[((widths.len() - 1) as f64 * q).round() as usize];
    (Some(pick(0.5)), Some(pick(0.9)), widths.len())
}

/// Distance over which a profile (offset, film), inside to outside, falls
/// from 90 % to 10 % of its level inside the edge (the largest film in the
/// inner half). `None` when the inside is unpainted or the film never falls.
fn fall_width(profile: &[(f64, f64)], target: f64) -> Option<f64> {
    let half = profile.len() / 2;
    let level = profile[..half].iter().map(|p| p.1).fold(0.0, f64::max);
    if level < COVERAGE_SHARE * target {
        return None;
    }
    let peak = profile[..half].iter().position(|p| p.1 == level)?;
    let (hi, lo) = (0.9 * level, 0.1 * level);
    let i10 = (peak..profile.len()).find(|&i| profile[i].1 < lo)?;
    let i90 = (peak..i10).rev().find(|&i| profile[i].1 >= hi)?;
    let cross = |i: usize, v: f64| {
        let (a, b) = (profile[i], profile[i + 1]);
        if (b.1 - a.1).abs() < f64::MIN_POSITIVE {
            a.0
        } else {
            a.0 + (v - a.1) / (b.1 - a.1) * (b.0 - a.0)
        }
    };
    Some(cross(i10 - 1, lo) - cross(i90, hi))
}

#[cfg(test)]
mod tests {
    use super::super::mask::SUB_ROWS;
    use super::*;

    fn square(x0: f64, y0: f64, s: f64) -> GlyphOutline {
        GlyphOutline {
            label: "□".into(),
            line: 0,
            strokes: vec![vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]]],
        }
    }

    #[test]
    fn mask_area_is_exact_for_axis_aligned_and_close_for_slanted() {
        let grid = Grid::covering(
            Bounds {
                min: [-1.0, -1.0],
                max: [1.0, 1.0],
            },
            0.01,
        )
        .unwrap();
        let sq = square(-0.123, 0.0, 0.5);
        let a: f64 = coverage_mask(&grid, &sq).iter().map(|c| c.f).sum::<f64>() * 1e-4;
        assert!((a - 0.25).abs() < 0.25 * 2e-3, "{a}");
        let tri = GlyphOutline {
            label: "t".into(),
            line: 0,
            strokes: vec![vec![[0.0, 0.0], [0.7, 0.1], [0.2, 0.6]]],
        };
        let want = signed_area(&tri.strokes[0]).abs();
        let a: f64 = coverage_mask(&grid, &tri).iter().map(|c| c.f).sum::<f64>() * 1e-4;
        assert!((a / want - 1.0).abs() < 0.01, "{a} vs {want}");
        assert!(tri.contains([0.3, 0.2]) && !tri.contains([0.6, 0.5]));
        // The inside lattice points are the points the even-odd test puts
        // inside (vertices off the lattice, so no point lies on an edge).
        let odd = GlyphOutline {
            label: "t".into(),
            line: 0,
            strokes: vec![vec![[0.0013, 0.0007], [0.7031, 0.1017], [0.2027, 0.6011]]],
        };
        let step = grid.cell_m / SUB_ROWS as f64;
        for m in coverage_mask(&grid, &odd) {
            let (i, j) = (m.k % grid.nx, m.k / grid.nx);
            for bit in 0..SUB_ROWS * SUB_ROWS {
                let p = [
                    grid.x0 + i as f64 * grid.cell_m + (bit % SUB_ROWS) as f64 * step + step / 2.0,
                    grid.y0 + j as f64 * grid.cell_m + (bit / SUB_ROWS) as f64 * step + step / 2.0,
                ];
                assert_eq!(
                    m.inside >> bit & 1 == 1,
                    odd.contains(p),
                    "cell {i},{j} bit {bit}"
                );
            }
        }
    }

    #[test]
    fn overlapping_strokes_count_once() {
        let grid = Grid::covering(
            Bounds {
                min: [0.0, 0.0],
                max: [1.0, 1.0],
            },
            0.02,
        )
        .unwrap();
        let mut g = square(0.1, 0.1, 0.4);
        g.strokes.push(square(0.3, 0.1, 0.4).strokes.remove(0));
        let a: f64 = coverage_mask(&grid, &g).iter().map(|c| c.f).sum::<f64>() * 4e-4;
        assert!((a - 0.24).abs() < 1e-3, "{a}");
    }

    /// A stripe painted with soft edges (film falling linearly from target
    /// to bare over 7 mm, half of it outside: film is half the target on the
    /// outline, as the preview measures at letter edges): coverage must not
    /// depend on where the outline falls within a cell. Judged by the cell
    /// averages alone, the cells half inside each long edge fell under the
    /// 50 % threshold at some offsets and the stripe read ≈ 0.975.
    #[test]
    fn coverage_does_not_depend_on_where_the_outline_falls_in_a_cell() {
        let cell = 0.005;
        let ramp = |d: f64| (0.5 - d / 0.007).clamp(0.0, 1.0); // d: distance outside
        let mut seen = Vec::new();
        for o in 0..10 {
            let x0 = 0.1 + o as f64 * cell / 10.0;
            let stripe = GlyphOutline {
                label: "|".into(),
                line: 0,
                strokes: vec![vec![[x0, 0.1], [x0 + 0.2, 0.1], [x0 + 0.2, 0.9], [x0, 0.9]]],
            };
            let mut grid = Grid::covering(
                Bounds {
                    min: [0.0, 0.0],
                    max: [0.5, 1.0],
                },
                cell,
            )
            .unwrap();
            let film = |p: [f64; 2]| {
                let dx = (x0 - p[0]).max(p[0] - x0 - 0.2);
                let dy = (0.1 - p[1]).max(p[1] - 0.9);
                ramp(dx) * ramp(dy)
            };
            for j in 0..grid.ny {
                for i in 0..grid.nx {
                    let c = grid.centre(i, j);
                    let mut sum = 0.0;
                    for b in 0..16 {
                        for a in 0..16 {
                            let q = (a as f64 + 0.5) / 16.0 - 0.5;
                            let r = (b as f64 + 0.5) / 16.0 - 0.5;
                            sum += film([c[0] + q * cell, c[1] + r * cell]);
                        }
                    }
                    grid.data[j * grid.nx + i] = sum / 256.0;
                }
            }
            let mask = coverage_mask(&grid, &stripe);
            let cov = coverage_share(&grid, mask.into_iter(), 0.5).unwrap();
            seen.push(cov);
        }
        let (lo, hi) = seen
            .iter()
            .fold((1.0f64, 0.0f64), |(l, h), &c| (l.min(c), h.max(c)));
        assert!(lo >= 0.99, "coverage by offset {seen:?}");
        assert!(hi - lo <= 0.005, "coverage by offset {seen:?}");
    }

    /// A straight stroke painted by a fan of width `fan_m` along
    /// x = `off_m`, measured against a stripe `stripe_m` wide on the same
    /// line and longer than the paint (so its caps lie inside): the
    /// overspray.
    fn stripe_overspray(fan_m: f64, stripe_m: f64, off_m: f64, cell: f64) -> f64 {
        use super::super::raster::deposit_with_progress;
        let alpha = 63.5f64.to_radians();
        let z = fan_m / 2.0 / (alpha / 2.0).tan();
        let (dt, speed): (f64, f64) = (0.032, 0.3);
        let n = (0.8 / speed / dt).round() as usize;
        let poses: Vec<Pose> = (0..=n)
            .map(|k| Pose {
                t_s: k as f64 * dt,
                x_m: off_m,
                y_m: 0.1 + k as f64 * dt * speed,
                z_m: z,
                yaw_rad: 0.0,
                tilt_rad: 0.0,
                gun: k < n,
            })
            .collect();
        let (x0, x1) = (off_m - stripe_m / 2.0, off_m + stripe_m / 2.0);
        let stripe = GlyphOutline {
            label: "|".into(),
            line: 0,
            strokes: vec![vec![[x0, -0.2], [x1, -0.2], [x1, 1.2], [x0, 1.2]]],
        };
        let glyphs = [stripe];
        let model = SprayModel::seed(alpha).unwrap();
        let masks = super::super::mask::Masks::of(&glyphs, &[0]);
        let lattice = |g: &Grid| masks.lattice(g);
        let film = deposit_with_progress(
            &poses,
            &model,
            6e-6,
            cell,
            glyphs[0].bounds(),
            Some(&lattice),
            &|_, _| {},
        )
        .unwrap();
        let stroke_of = vec![0; poses.len()];
        let masks = masks.take(&film.grid);
        let m = measure(&film, masks, &glyphs, 3.8e-4, &model, &poses, &stroke_of).unwrap();
        m.overspray.unwrap()
    }

    /// Overspray is the paint that lands outside the outline, judged where
    /// it lands: a fan that paints a stripe exactly puts none outside,
    /// wherever the outline falls in a cell and whatever the cell (the
    /// cells' film alone, each cell's paint shared out by the part of the
    /// cell outside, read about 1/6 of a cell of the stripe's film outside
    /// each edge: 0.8 % on this 0.2 m stripe at 5 mm); a fan 10 % wider
    /// than the stripe puts 1/11 of its paint outside.
    #[test]
    fn overspray_is_the_paint_that_lands_outside_wherever_the_outline_falls() {
        for cell in [0.005, 0.002] {
            for o in 0..5 {
                let off = o as f64 * cell / 5.0;
                let exact = stripe_overspray(0.2, 0.2, off, cell);
                assert!(exact < 5e-4, "cell {cell} offset {off}: {exact}");
                let wide = stripe_overspray(0.22, 0.2, off, cell);
                assert!(
                    (wide - 1.0 / 11.0).abs() < 0.003,
                    "cell {cell} offset {off}: {wide}"
                );
            }
        }
    }

    /// A fan reaching past the outline by less than a piece of the fan
    /// (half a cell) still puts that paint outside: each piece is read
    /// along its length, an eighth of a cell apart. 1 mm past each side of
    /// a 0.2 m stripe is 0.002 / 0.202 of the paint; at 5 mm and at 10 mm
    /// cells, wherever the outline falls in a cell.
    #[test]
    fn a_fan_a_millimetre_past_the_outline_puts_that_millimetre_outside() {
        let want = 0.002 / 0.202;
        for cell in [0.005, 0.01] {
            // the reading's resolution: a lattice step on each side
            let tol = 2.0 * cell / 8.0 / 0.202;
            for o in 0..5 {
                let off = o as f64 * cell / 5.0;
                let got = stripe_overspray(0.202, 0.2, off, cell);
                assert!(
                    (got - want).abs() <= tol,
                    "cell {cell} offset {off}: {got} (want {want})"
                );
            }
        }
    }

    #[test]
    fn fall_width_of_a_linear_ramp() {
        // Level 1 until 0, linear to 0 at 0.1: 90 %→10 % over 0.08.
        let p: Vec<(f64, f64)> = (0..=400)
            .map(|k| {
                let x = -0.2 + k as f64 * 0.001;
                (x, (1.0 - x / 0.1).clamp(0.0, 1.0))
            })
            .collect();
        let w = fall_width(&p, 1.0).unwrap();
        assert!((w - 0.08).abs() < 1e-9, "{w}");
    }
}
