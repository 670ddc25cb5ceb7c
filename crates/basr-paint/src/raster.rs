//! The deposition raster: film thickness on a road-frame grid, integrated
//! along a timed sequence of nozzle poses with the gun on.
//!
//! Time law: the gun state of pose i holds until pose i+1 (sample and
//! hold, as a controller applies setpoints), so interval [tᵢ, tᵢ₊₁] is
//! painted when pose i has the gun on; the pose is interpolated linearly
//! inside the interval. Each interval is cut into sub-steps short enough
//! that neither end of the fan moves more than half a cell; each sub-step
//! lays `flow × efficiency × dt` at its mid-time pose. The fan line is cut
//! into pieces of at most half a cell, each carrying the profile's share
//! of that line, and spread across the sheet by the depth nodes; every
//! piece is splatted bilinearly, so the raster holds exactly the volume
//! laid (up to rounding).
//!
//! Where the letters are given (a [`Letters`] lattice), each piece is also
//! judged where it lands, before the bilinear splat spreads it over four
//! cells: the piece's length along the fan is read at points an eighth of
//! a cell apart, each at the nearest of its cell's `LATTICE` × `LATTICE`
//! lattice points, and the share of them outside the letters adds that
//! share of the piece's volume to [`Film::outside`] in the cell the piece
//! lands in. Overspray is that volume: the splat's one-cell spread across
//! an outline the fan paints exactly is the raster's, not paint on the
//! road outside the letter, while a fan reaching past an outline by a
//! millimetre puts its millimetre outside.

use rayon::prelude::*;

pub use super::mm_text;
use super::spray::{Footprint, Pose, SprayModel};
use super::PaintError;

/// Painted intervals handled by one parallel work item. Fixed, so the sum
/// order (and so every output byte) does not depend on the thread count.
const INTERVALS_PER_CHUNK: usize = 48;

/// Largest raster the preview will allocate (cells); a guard against a
/// resolution far too fine for the job's extent.
// assumed: 60 M cells ≈ 480 MB of f64.
pub const MAX_CELLS: usize = 60_000_000;

/// Lattice points per cell side at which [`Letters`] tells inside from
/// outside (0.625 mm apart at the default 5 mm cell).
pub const LATTICE: usize = 8;
const _: () = assert!(LATTICE * LATTICE <= 64);

/// Which points of each cell of a grid lie inside the letters: one `u64`
/// per cell (`j * nx + i`), bit `row * LATTICE + col` set when the point
/// ((col + ½) / LATTICE, (row + ½) / LATTICE) of the cell is inside (all
/// set: wholly inside; none: outside every letter). Given the grid the
/// film is laid on (`mask::inside_lattice` builds it).
pub type Letters<'a> = Option<&'a (dyn Fn(&Grid) -> Vec<u64> + Sync)>;

/// An axis-aligned rectangle in the road frame (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: [f64; 2],
    pub max: [f64; 2],
}

impl Bounds {
    /// The empty rectangle (union identity).
    pub const EMPTY: Bounds = Bounds {
        min: [f64::INFINITY; 2],
        max: [f64::NEG_INFINITY; 2],
    };

    pub fn include(&mut self, p: [f64; 2]) {
        for (k, v) in p.into_iter().enumerate() {
            self.min[k] = self.min[k].min(v);
            self.max[k] = self.max[k].max(v);
        }
    }

    pub fn union(mut self, o: Bounds) -> Bounds {
        self.include(o.min);
        self.include(o.max);
        self
    }

    /// Whether the two rectangles share a point (edges included).
    pub fn meets(&self, o: &Bounds) -> bool {
        self.min[0] <= o.max[0]
            && o.min[0] <= self.max[0]
            && self.min[1] <= o.max[1]
            && o.min[1] <= self.max[1]
    }

    pub fn grow(self, by: f64) -> Bounds {
        Bounds {
            min: [self.min[0] - by, self.min[1] - by],
            max: [self.max[0] + by, self.max[1] + by],
        }
    }

    pub fn is_empty(&self) -> bool {
        !(self.min[0] <= self.max[0] && self.min[1] <= self.max[1])
    }

    pub fn width(&self) -> f64 {
        self.max[0] - self.min[0]
    }

    pub fn height(&self) -> f64 {
        self.max[1] - self.min[1]
    }
}

/// Film thickness (m) on a regular road-frame grid. Cell (i, j) covers
/// `[x0 + i·h, x0 + (i+1)·h) × [y0 + j·h, y0 + (j+1)·h)`; `data` is row-major
/// with j (y) the row, j = 0 at the lowest y.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    pub x0: f64,
    pub y0: f64,
    pub cell_m: f64,
    pub nx: usize,
    pub ny: usize,
    pub data: Vec<f64>,
}

impl Grid {
    /// An empty grid covering `b` with cells of `cell_m`, aligned to
    /// multiples of `cell_m` so that grids of one resolution line up.
    pub fn covering(b: Bounds, cell_m: f64) -> Result<Grid, PaintError> {
        if !(cell_m > 0.0 && cell_m.is_finite()) {
            return Err(PaintError::Model(format!(
                "raster resolution {cell_m} m must be a positive number"
            )));
        }
        if b.is_empty() || !b.min[0].is_finite() || !b.max[1].is_finite() {
            return Err(PaintError::Model("nothing to raster: empty extent".into()));
        }
        let i0 = (b.min[0] / cell_m).floor();
        let j0 = (b.min[1] / cell_m).floor();
        let nx = ((b.max[0] / cell_m).ceil() - i0).max(1.0);
        let ny = ((b.max[1] / cell_m).ceil() - j0).max(1.0);
        if nx * ny > MAX_CELLS as f64 {
            return Err(PaintError::Model(format!(
                "a {:.2} m × {:.2} m raster at {} mm needs {:.0} cells (limit {MAX_CELLS}); \
                 use a coarser --resolution-mm",
                b.width(),
                b.height(),
                mm_text(cell_m),
                nx * ny
            )));
        }
        let (nx, ny) = (nx as usize, ny as usize);
        Ok(Grid {
            x0: i0 * cell_m,
            y0: j0 * cell_m,
            cell_m,
            nx,
            ny,
            data: vec![0.0; nx * ny],
        })
    }

    /// Centre of cell (i, j).
    pub fn centre(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.x0 + (i as f64 + 0.5) * self.cell_m,
            self.y0 + (j as f64 + 0.5) * self.cell_m,
        ]
    }

    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.data[j * self.nx + i]
    }

    /// Film at a road point, interpolated bilinearly between cell centres
    /// (0 outside the grid).
    pub fn sample(&self, p: [f64; 2]) -> f64 {
        let fx = (p[0] - self.x0) / self.cell_m - 0.5;
        let fy = (p[1] - self.y0) / self.cell_m - 0.5;
        let (i0, j0) = (floor(fx), floor(fy));
        let (tx, ty) = (fx - i0, fy - j0);
        let get = |i: f64, j: f64| {
            if i < 0.0 || j < 0.0 || i >= self.nx as f64 || j >= self.ny as f64 {
                0.0
            } else {
                self.at(i as usize, j as usize)
            }
        };
        get(i0, j0) * (1.0 - tx) * (1.0 - ty)
            + get(i0 + 1.0, j0) * tx * (1.0 - ty)
            + get(i0, j0 + 1.0) * (1.0 - tx) * ty
            + get(i0 + 1.0, j0 + 1.0) * tx * ty
    }

    /// Volume on the grid (m³).
    pub fn volume(&self) -> f64 {
        self.data.iter().sum::<f64>() * self.cell_m * self.cell_m
    }

    /// Largest film value.
    pub fn max(&self) -> f64 {
        self.data.iter().fold(0.0, |m, &v| m.max(v))
    }

    /// Road-frame rectangle the grid covers.
    pub fn bounds(&self) -> Bounds {
        Bounds {
            min: [self.x0, self.y0],
            max: [
                self.x0 + self.nx as f64 * self.cell_m,
                self.y0 + self.ny as f64 * self.cell_m,
            ],
        }
    }
}

/// The result of depositing a pose sequence.
#[derive(Clone, Debug)]
pub struct Film {
    pub grid: Grid,
    /// Per cell of `grid`, the film (m: volume over the cell's area) of
    /// the paint that landed outside the letters in that cell; `None`
    /// when laid without [`Letters`] (nothing was judged).
    pub outside: Option<Vec<f64>>,
    /// Volume laid: flow × efficiency × gun-on time (m³).
    pub laid_m3: f64,
    /// Total gun-on time (s).
    pub gun_on_s: f64,
    /// Paint that fell outside the grid (m³); 0 unless a fan swings far
    /// beyond its end poses within one interval.
    pub lost_m3: f64,
}

/// Accumulates splats into a window of the global grid.
struct Canvas<'a> {
    i0: i64,
    j0: i64,
    nx: usize,
    ny: usize,
    /// Volume per cell (m³), not yet divided by the cell area.
    vol: Vec<f64>,
    /// The letters over the global grid (`Judge`), and the volume per
    /// window cell that landed outside them.
    letters: Option<&'a Judge>,
    out: Vec<f64>,
    x0: f64,
    y0: f64,
    /// 1 / the cell size (1/m).
    inv_h: f64,
    /// Splats that fell outside the window (rare: a fan turning or tilting
    /// past the bounds of its end poses).
    spill: Vec<([f64; 2], f64, f64)>,
}

impl Canvas<'_> {
    /// Add mass `m` at `p` to the four nearest cell centres, `outside` of
    /// it (judged by [`Judge::outside_share`]) to the outside film of the
    /// cell `p` lies in; when they are not all in the window, keep it in
    /// `spill` for the global grid.
    fn splat(&mut self, p: [f64; 2], m: f64, outside: f64) {
        let f = self.cells(p);
        self.splat_cells(f, m, outside, || p);
    }

    /// `p` in cells from the grid's first cell centre.
    #[inline]
    fn cells(&self, p: [f64; 2]) -> [f64; 2] {
        [
            (p[0] - self.x0) * self.inv_h - 0.5,
            (p[1] - self.y0) * self.inv_h - 0.5,
        ]
    }

    /// [`Canvas::splat`] of the point `[fx, fy]` cells from the grid's
    /// first cell centre; `p()` is that point on the road, for `spill`.
    #[inline]
    fn splat_cells(
        &mut self,
        [fx, fy]: [f64; 2],
        m: f64,
        outside: f64,
        p: impl FnOnce() -> [f64; 2],
    ) {
        // Left of or below the grid's first cell centre (or not a number):
        // off every window. From there on truncation is the floor.
        if !(fx >= 0.0 && fy >= 0.0) {
            self.spill.push((p(), m, outside));
            return;
        }
        let (fi, fj) = (fx as i64, fy as i64);
        let (tx, ty) = (fx - fi as f64, fy - fj as f64);
        let i = fi - self.i0;
        let j = fj - self.j0;
        if i < 0 || j < 0 || i + 1 >= self.nx as i64 || j + 1 >= self.ny as i64 {
            self.spill.push((p(), m, outside));
            return;
        }
        let (i, j) = (i as usize, j as usize);
        let k = j * self.nx + i;
        let (a, b) = (m * (1.0 - ty), m * ty);
        self.vol[k] += a * (1.0 - tx);
        self.vol[k + 1] += a * tx;
        self.vol[k + self.nx] += b * (1.0 - tx);
        self.vol[k + self.nx + 1] += b * tx;
        if outside > 0.0 && !self.out.is_empty() {
            // The cell the point lands in: of the splat's four (so in the
            // window), the one whose centre is nearest.
            let (di, dj) = (usize::from(tx >= 0.5), usize::from(ty >= 0.5));
            self.out[k + dj * self.nx + di] += outside;
        }
    }
}

/// The letters a film's paint is judged against, over the global grid:
/// each cell's lattice points inside (`Letters`) and, so that a piece
/// landing in a cell wholly inside or wholly outside is judged by one
/// byte, the cell's class.
struct Judge {
    nx: usize,
    ny: usize,
    bits: Vec<u64>,
    class: Vec<u8>,
    /// Per cell: every cell within `reach` cells of it wholly inside
    /// (`INSIDE`), wholly outside (`OUTSIDE`), or neither (`EDGE`): a
    /// piece landing there, with all its sheet's depth nodes, is judged
    /// by this one byte.
    deep: Vec<u8>,
}

impl Judge {
    const OUTSIDE: u8 = 0;
    const INSIDE: u8 = 1;
    const EDGE: u8 = 2;

    /// Points at which a piece (at most half a cell long) is read: an
    /// eighth of a cell apart, the lattice's spacing.
    const READS: usize = LATTICE / 2;

    /// The cell class of the point `f` (cells from the first cell centre)
    /// and, for a cell the outline cuts, whether the point is outside;
    /// off the grid is outside.
    #[inline]
    fn outside_at(&self, f: [f64; 2]) -> (u8, bool) {
        let Some((k, [u, v])) = self.cell_of(f) else {
            return (Judge::OUTSIDE, true);
        };
        match self.class[k] {
            Judge::INSIDE => (Judge::INSIDE, false),
            Judge::OUTSIDE => (Judge::OUTSIDE, true),
            c => {
                let per = LATTICE as f64;
                let col = ((u * per) as usize).min(LATTICE - 1);
                let row = ((v * per) as usize).min(LATTICE - 1);
                (c, self.bits[k] >> (row * LATTICE + col) & 1 == 0)
            }
        }
    }

    /// The cell the point `f` (cells from the first cell centre) lies in
    /// and the point's place in it (0 to 1 along x and y); `None` off the
    /// grid.
    #[inline]
    fn cell_of(&self, f: [f64; 2]) -> Option<(usize, [f64; 2])> {
        let (gx, gy) = (f[0] + 0.5, f[1] + 0.5);
        if !(gx >= 0.0 && gy >= 0.0) {
            return None;
        }
        let (ci, cj) = (gx as usize, gy as usize);
        (ci < self.nx && cj < self.ny)
            .then(|| (cj * self.nx + ci, [gx - ci as f64, gy - cj as f64]))
    }

    /// The share of a piece of the fan from `a` to `b` (cells from the
    /// first cell centre; at most half a cell apart) that lies outside the
    /// letters: none or all when both ends lie in cells wholly inside or
    /// wholly outside, else read at [`Judge::READS`] points along it.
    #[inline]
    fn outside_share(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        let (ca, oa) = self.outside_at(a);
        let (cb, _) = self.outside_at(b);
        if ca != Judge::EDGE && ca == cb {
            return if oa { 1.0 } else { 0.0 };
        }
        let n = Judge::READS;
        let out = (0..n)
            .filter(|&j| {
                let t = (j as f64 + 0.5) / n as f64;
                self.outside_at([a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t])
                    .1
            })
            .count();
        out as f64 / n as f64
    }

    /// The judge of `grid`'s lattice `bits`, for pieces whose points lie
    /// within `reach_m` of the point they are splatted about.
    fn of(grid: &Grid, bits: Vec<u64>, reach_m: f64) -> Judge {
        let class: Vec<u8> = bits
            .iter()
            .map(|&b| match b {
                0 => Judge::OUTSIDE,
                u64::MAX => Judge::INSIDE,
                _ => Judge::EDGE,
            })
            .collect();
        // A point within reach_m of a point in cell i lies within
        // ⌈reach / cell⌉ cells of i; one more for rounding.
        let r = ((reach_m / grid.cell_m).ceil().max(0.0) as usize).min(grid.nx.max(grid.ny)) + 1;
        let all = |c: u8| Judge::all_within(grid.nx, grid.ny, r, |k| class[k] == c);
        let (inside, outside) = (all(Judge::INSIDE), all(Judge::OUTSIDE));
        let deep = inside
            .iter()
            .zip(&outside)
            .map(|(&i, &o)| {
                if i {
                    Judge::INSIDE
                } else if o {
                    Judge::OUTSIDE
                } else {
                    Judge::EDGE
                }
            })
            .collect();
        Judge {
            nx: grid.nx,
            ny: grid.ny,
            bits,
            class,
            deep,
        }
    }

    /// Per cell: whether `is` holds for every cell within `r` cells
    /// (Chebyshev) of it, cells off the grid counting as not (a row pass
    /// then a column pass of running counts).
    fn all_within(nx: usize, ny: usize, r: usize, is: impl Fn(usize) -> bool) -> Vec<bool> {
        let window = 2 * r + 1;
        let run = |n: usize, at: &dyn Fn(usize) -> bool| -> Vec<bool> {
            // prefix counts over 0..n, then each window [i − r, i + r]
            let mut pre = vec![0usize; n + 1];
            for i in 0..n {
                pre[i + 1] = pre[i] + usize::from(at(i));
            }
            (0..n)
                .map(|i| i >= r && i + r < n && pre[i + r + 1] - pre[i - r] == window)
                .collect()
        };
        let mut rows = vec![false; nx * ny];
        for j in 0..ny {
            let ok = run(nx, &|i| is(j * nx + i));
            rows[j * nx..(j + 1) * nx].copy_from_slice(&ok);
        }
        let mut out = vec![false; nx * ny];
        for i in 0..nx {
            let ok = run(ny, &|j| rows[j * nx + i]);
            for (j, v) in ok.into_iter().enumerate() {
                out[j * nx + i] = v;
            }
        }
        out
    }

    /// The deep class of the cell the point `f` (cells from the first
    /// cell centre) lies in; `EDGE` off the grid.
    #[inline]
    fn deep_at(&self, f: [f64; 2]) -> u8 {
        self.cell_of(f).map_or(Judge::EDGE, |(k, _)| self.deep[k])
    }
}

/// `x.floor()`, bit for bit (signed zeros and infinities included; NaN
/// stays NaN), without the call into libm that `f64::floor` makes on
/// x86-64 without SSE4.1 (the default target): `Grid::sample` reads the
/// film at every edge point. (A splat needs no floor: it lands only at or
/// past the first cell centre, where truncation is the floor.)
#[inline]
fn floor(x: f64) -> f64 {
    // 2^52: from there on every f64 is an integer (NaN is returned too)
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x;
    }
    // truncation toward zero, exact in this range
    let t = x as i64 as f64;
    if t > x {
        t - 1.0
    } else {
        t.copysign(x)
    }
}

/// Every point the fan of `fp` can paint lies within this rectangle, plus
/// the depth's reach.
fn footprint_bounds(fp: &Footprint) -> Bounds {
    let mut b = Bounds::EMPTY;
    b.include(fp.minus());
    b.include(fp.plus());
    b
}

pub(crate) fn depth_reach(model: &SprayModel) -> f64 {
    model.depth.reach_m()
}

/// The road the fan sweeps between poses `i` and `i + 1` of `poses` (both
/// footprints' bounds; the depth's reach not added).
pub(crate) fn interval_bounds(
    poses: &[Pose],
    i: usize,
    model: &SprayModel,
) -> Result<Bounds, PaintError> {
    Ok(footprint_bounds(&model.footprint(&poses[i])?)
        .union(footprint_bounds(&model.footprint(&poses[i + 1])?)))
}

/// Road-frame extent of everything `poses` paint (empty when the gun is
/// never on).
pub fn painted_bounds(poses: &[Pose], model: &SprayModel) -> Result<Bounds, PaintError> {
    let mut b = Bounds::EMPTY;
    for w in poses.windows(2) {
        if w[0].gun {
            b = b
                .union(footprint_bounds(&model.footprint(&w[0])?))
                .union(footprint_bounds(&model.footprint(&w[1])?));
        }
    }
    if b.is_empty() {
        return Ok(b);
    }
    Ok(b.grow(depth_reach(model)))
}

/// Cells the raster held at once (a job's whole raster, or one band of a
/// long job's: `bands`) is coarsened to fit when the user did not ask for
/// a cell size. // assumed: 40 M cells (320 MB of f64 plus the metrics'
/// masks) on a small machine shared with other work; a band of letters is
/// about half a million at 5 mm, so only a marking painted without a break
/// over about 1000 m² meets it. MAX_CELLS stays the hard limit for an
/// explicit size.
pub const FIT_CELLS: usize = 40_000_000;

/// The finest cell, at least `wanted_m` and in steps of 0.5 mm, whose grid
/// over `b` holds at most `budget` cells.
pub fn fitted_cell(b: Bounds, wanted_m: f64, budget: usize) -> f64 {
    if b.is_empty() || wanted_m.is_nan() || wanted_m <= 0.0 {
        return wanted_m;
    }
    // Two cells of margin as deposit adds, plus one for the alignment.
    let cells = |c: f64| ((b.width() / c).ceil() + 5.0) * ((b.height() / c).ceil() + 5.0);
    let step = 0.0005; // assumed: half-millimetre steps read well in the title
    let mut c = wanted_m;
    while cells(c) > budget as f64 && c < 1.0 {
        c = ((c / step).floor() + 1.0) * step;
    }
    c
}

/// How far a long computation has got: `(done, total)`, called from worker
/// threads.
pub type Progress<'a> = &'a (dyn Fn(usize, usize) + Sync);

/// Deposit the paint of `poses` (time-ordered, gun state holding until the
/// next pose) with `flow_eff_m3ps` = flow × transfer efficiency reaching the
/// road, on a grid of `cell_m` covering the painted region and `extra`.
pub fn deposit(
    poses: &[Pose],
    model: &SprayModel,
    flow_eff_m3ps: f64,
    cell_m: f64,
    extra: Bounds,
) -> Result<Film, PaintError> {
    deposit_with_progress(poses, model, flow_eff_m3ps, cell_m, extra, None, &|_, _| {})
}

/// [`deposit`], judging where the paint lands against `letters`, and
/// telling `progress` how many painted intervals are done.
pub fn deposit_with_progress(
    poses: &[Pose],
    model: &SprayModel,
    flow_eff_m3ps: f64,
    cell_m: f64,
    extra: Bounds,
    letters: Letters<'_>,
    progress: Progress,
) -> Result<Film, PaintError> {
    check_poses(poses, flow_eff_m3ps)?;
    let painted = painted_intervals(poses);
    let mut extent = painted_bounds(poses, model)?;
    if !extra.is_empty() {
        extent = if extent.is_empty() {
            extra
        } else {
            extent.union(extra)
        };
    }
    deposit_intervals(
        poses,
        &painted,
        model,
        flow_eff_m3ps,
        Sheet {
            cell_m,
            extent,
            letters,
        },
        progress,
    )
}

/// What deposition asks of its input: a flow ≥ 0 and time that never goes
/// back.
pub fn check_poses(poses: &[Pose], flow_eff_m3ps: f64) -> Result<(), PaintError> {
    if !(flow_eff_m3ps >= 0.0 && flow_eff_m3ps.is_finite()) {
        return Err(PaintError::Model(format!(
            "flow × efficiency {flow_eff_m3ps} m³/s must be a number ≥ 0"
        )));
    }
    for (i, w) in poses.windows(2).enumerate() {
        if w[1].t_s.partial_cmp(&w[0].t_s).is_none_or(|o| o.is_lt()) {
            return Err(PaintError::Pose(format!(
                "time goes backwards (or is not a number) between samples {i} and {}",
                i + 1
            )));
        }
    }
    Ok(())
}

/// The intervals of `poses` the gun paints: i for poses i → i + 1, the gun
/// open at i and time moving on.
pub fn painted_intervals(poses: &[Pose]) -> Vec<usize> {
    (0..poses.len().saturating_sub(1))
        .filter(|&i| poses[i].gun && poses[i + 1].t_s > poses[i].t_s)
        .collect()
}

/// The road a film is laid on: a grid of `cell_m` covering `extent`, and
/// the letters its paint is judged against (none: no outside film).
#[derive(Clone, Copy)]
pub struct Sheet<'a> {
    pub cell_m: f64,
    pub extent: Bounds,
    pub letters: Letters<'a>,
}

/// The paint of the intervals `painted` of `poses` (checked as
/// [`deposit_with_progress`] checks them) on `sheet`'s grid, aligned to
/// the global lattice of its cell: a band of a long job (`bands`) gets
/// the values the whole job's grid has there. Paint landing off the grid
/// is `lost_m3`.
pub fn deposit_intervals(
    poses: &[Pose],
    painted: &[usize],
    model: &SprayModel,
    flow_eff_m3ps: f64,
    sheet: Sheet<'_>,
    progress: Progress,
) -> Result<Film, PaintError> {
    let Sheet {
        cell_m,
        extent,
        letters,
    } = sheet;
    // Two cells of margin keep every bilinear splat on the grid.
    let mut grid = Grid::covering(extent.grow(2.0 * cell_m), cell_m)?;
    let half = cell_m / 2.0;
    let depth = model.depth.nodes(half);
    // a piece's points: its depth nodes' reach, and half a piece (a
    // quarter of a cell) along the fan
    let reach = depth_reach(model) + 0.25 * cell_m;
    let judge = letters.map(|f| Judge::of(&grid, f(&grid), reach));
    let letters = judge.as_ref();

    let done = std::sync::atomic::AtomicUsize::new(0);
    let chunks: Vec<Canvas> = painted
        .par_chunks(INTERVALS_PER_CHUNK)
        .map(|chunk| {
            let c = deposit_chunk(poses, chunk, model, flow_eff_m3ps, &grid, &depth, letters);
            let n = done.fetch_add(chunk.len(), std::sync::atomic::Ordering::Relaxed);
            progress(n + chunk.len(), painted.len());
            c
        })
        .collect::<Result<_, _>>()?;
    let area = cell_m * cell_m;
    let mut whole = Canvas {
        i0: 0,
        j0: 0,
        nx: grid.nx,
        ny: grid.ny,
        vol: std::mem::take(&mut grid.data),
        x0: grid.x0,
        y0: grid.y0,
        inv_h: 1.0 / cell_m,
        spill: Vec::new(),
        letters,
        out: if letters.is_some() {
            vec![0.0; grid.nx * grid.ny]
        } else {
            Vec::new()
        },
    };
    let add_window = |dst: &mut [f64], src: &[f64], c: &Canvas| {
        for jj in 0..c.ny {
            let row = (c.j0 as usize + jj) * grid.nx + c.i0 as usize;
            let src = &src[jj * c.nx..(jj + 1) * c.nx];
            for (d, v) in dst[row..row + c.nx].iter_mut().zip(src) {
                *d += v;
            }
        }
    };
    for c in &chunks {
        add_window(&mut whole.vol, &c.vol, c);
        if !c.out.is_empty() {
            add_window(&mut whole.out, &c.out, c);
        }
        for &(p, m, o) in &c.spill {
            whole.splat(p, m, o);
        }
    }
    let lost_m3: f64 = whole.spill.iter().map(|s| s.1).sum();
    grid.data = whole.vol;
    grid.data.iter_mut().for_each(|v| *v /= area);
    let outside = letters.map(|_| {
        let mut o = whole.out;
        o.iter_mut().for_each(|v| *v /= area);
        o
    });
    let gun_on_s: f64 = painted
        .iter()
        .map(|&i| poses[i + 1].t_s - poses[i].t_s)
        .sum();
    Ok(Film {
        grid,
        outside,
        laid_m3: flow_eff_m3ps * gun_on_s,
        gun_on_s,
        lost_m3,
    })
}

/// Deposit a run of painted intervals into a canvas over their own extent.
fn deposit_chunk<'a>(
    poses: &[Pose],
    chunk: &[usize],
    model: &SprayModel,
    flow_eff_m3ps: f64,
    grid: &Grid,
    depth: &[(f64, f64)],
    letters: Option<&'a Judge>,
) -> Result<Canvas<'a>, PaintError> {
    let h = grid.cell_m;
    let half = h / 2.0;
    let reach = depth_reach(model);
    let mut b = Bounds::EMPTY;
    for &i in chunk {
        b = b.union(interval_bounds(poses, i, model)?);
    }
    let b = b.grow(reach + 2.0 * h);
    // Window in global cell indices, clipped to the grid.
    let gi0 = ((((b.min[0] - grid.x0) / h).floor() as i64).max(0)).min(grid.nx as i64 - 1);
    let gj0 = ((((b.min[1] - grid.y0) / h).floor() as i64).max(0)).min(grid.ny as i64 - 1);
    let gi1 = (((b.max[0] - grid.x0) / h).ceil() as i64).clamp(gi0 + 1, grid.nx as i64);
    let gj1 = (((b.max[1] - grid.y0) / h).ceil() as i64).clamp(gj0 + 1, grid.ny as i64);
    let mut canvas = Canvas {
        i0: gi0,
        j0: gj0,
        nx: (gi1 - gi0) as usize,
        ny: (gj1 - gj0) as usize,
        vol: vec![0.0; ((gi1 - gi0) * (gj1 - gj0)) as usize],
        x0: grid.x0,
        y0: grid.y0,
        inv_h: 1.0 / h,
        spill: Vec::new(),
        letters,
        out: if letters.is_some() {
            vec![0.0; ((gi1 - gi0) * (gj1 - gj0)) as usize]
        } else {
            Vec::new()
        },
    };
    for &i in chunk {
        let (a, bpose) = (&poses[i], &poses[i + 1]);
        let dt = bpose.t_s - a.t_s;
        let fa = model.footprint(a)?;
        let fb = model.footprint(&a.lerp(bpose, 1.0))?;
        let moved = dist(fa.minus(), fb.minus())
            .max(dist(fa.plus(), fb.plus()))
            .max(dist(fa.foot, fb.foot));
        let n = ((moved / half).ceil() as usize).max(1);
        let vol_step = flow_eff_m3ps * dt / n as f64;
        for k in 0..n {
            let pose = a.lerp(bpose, (k as f64 + 0.5) / n as f64);
            let fp = model.footprint(&pose)?;
            lay_line(&mut canvas, model, &fp, vol_step, half, depth);
        }
    }
    Ok(canvas)
}

/// Lay `vol` of paint along one footprint, in pieces of at most `piece_m`.
fn lay_line(
    canvas: &mut Canvas,
    model: &SprayModel,
    fp: &Footprint,
    vol: f64,
    piece_m: f64,
    depth: &[(f64, f64)],
) {
    let w = fp.width();
    let pieces = ((w / piece_m).ceil() as usize).max(1);
    let step = w / pieces as f64;
    let n = [-fp.u[1], fp.u[0]];
    // the sheet's normal in cells per metre: a depth node d off the line
    // lies d·nh cells from it
    let nh = [n[0] * canvas.inv_h, n[1] * canvas.inv_h];
    // half a piece along the fan, in cells
    let half = [
        0.5 * step * fp.u[0] * canvas.inv_h,
        0.5 * step * fp.u[1] * canvas.inv_h,
    ];
    let mut c_lo = model.cdf(fp.theta_at(fp.r_minus));
    for k in 0..pieces {
        let r_hi = fp.r_minus + (k + 1) as f64 * step;
        let c_hi = model.cdf(fp.theta_at(r_hi));
        let share = c_hi - c_lo;
        c_lo = c_hi;
        if share <= 0.0 {
            continue;
        }
        let p = fp.at(r_hi - 0.5 * step);
        let f = canvas.cells(p);
        // far from every outline, the whole piece and its sheet at once
        let deep = canvas
            .letters
            .map_or(Judge::INSIDE, |judge| judge.deep_at(f));
        for &(d, wd) in depth {
            let c = [f[0] + d * nh[0], f[1] + d * nh[1]];
            let m = vol * share * wd;
            // the piece from one end to the other, judged where it lands
            let outside = match (deep, canvas.letters) {
                (Judge::EDGE, Some(judge)) => {
                    m * judge.outside_share(
                        [c[0] - half[0], c[1] - half[1]],
                        [c[0] + half[0], c[1] + half[1]],
                    )
                }
                (Judge::OUTSIDE, _) => m,
                _ => 0.0,
            };
            canvas.splat_cells(c, m, outside, || [p[0] + d * n[0], p[1] + d * n[1]]);
        }
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cell is deep inside only when every cell within the radius is
    /// wholly inside (off the grid counts as not): a 3 × 3 block of
    /// inside cells in a 7 × 7 grid is deep inside at its centre alone at
    /// radius 1, nowhere at radius 2; deep outside needs the whole
    /// neighbourhood outside and on the grid.
    #[test]
    fn deep_cells_have_their_whole_neighbourhood_on_one_side() {
        let (nx, ny) = (7, 7);
        let class: Vec<u8> = (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                if (2..5).contains(&i) && (2..5).contains(&j) {
                    Judge::INSIDE
                } else {
                    Judge::OUTSIDE
                }
            })
            .collect();
        let inside = |r| Judge::all_within(nx, ny, r, |k| class[k] == Judge::INSIDE);
        let deep: Vec<usize> = (0..nx * ny).filter(|&k| inside(1)[k]).collect();
        assert_eq!(deep, vec![3 * nx + 3]);
        assert!(inside(2).iter().all(|&d| !d));
        let outside = Judge::all_within(nx, ny, 1, |k| class[k] == Judge::OUTSIDE);
        let deep_out: Vec<usize> = (0..nx * ny).filter(|&k| outside[k]).collect();
        // none: every on-grid cell with a full neighbourhood touches the block
        assert!(deep_out.is_empty(), "{deep_out:?}");
    }

    /// `floor` is `f64::floor` bit for bit: the edge cases, and any f64.
    #[test]
    fn floor_is_libm_floor_bit_for_bit() {
        let same = |x: f64| {
            assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "{x:e}");
        };
        for x in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.5,
            2.999_999_999_999_999_6,
            -2.999_999_999_999_999_6,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            1e300,
            -1e300,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            same(x);
        }
        assert!(floor(f64::NAN).is_nan());
        proptest::proptest!(|(bits: u64)| {
            let x = f64::from_bits(bits);
            if !x.is_nan() {
                same(x);
            }
        });
        proptest::proptest!(|(x in -1e6f64..1e6)| same(x));
    }

    /// A splat lays its mass on the four cell centres around its point,
    /// bilinearly (the reference with `f64::floor`), or keeps all of it in
    /// `spill` when they are not all in the window: left of, below, right
    /// of or above it, on a cell line, and anywhere.
    #[test]
    fn a_splat_lays_its_mass_bilinearly_or_spills_it_whole() {
        let window = || Canvas {
            i0: 3,
            j0: 2,
            nx: 6,
            ny: 5,
            vol: vec![0.0; 30],
            x0: -0.1,
            y0: 0.2,
            inv_h: 1.0 / 0.005,
            spill: Vec::new(),
            letters: None,
            out: Vec::new(),
        };
        let check = |p: [f64; 2]| {
            let mut c = window();
            c.splat(p, 2.0, 0.0);
            let fx = (p[0] - c.x0) * c.inv_h - 0.5;
            let fy = (p[1] - c.y0) * c.inv_h - 0.5;
            let (i, j) = (fx.floor() - c.i0 as f64, fy.floor() - c.j0 as f64);
            let inside = i >= 0.0 && j >= 0.0 && i + 1.0 < c.nx as f64 && j + 1.0 < c.ny as f64;
            let laid: f64 = c.vol.iter().sum();
            if !inside {
                assert_eq!(c.spill, vec![(p, 2.0, 0.0)], "{p:?}");
                assert_eq!(laid, 0.0);
                return;
            }
            assert!(c.spill.is_empty(), "{p:?}");
            assert!((laid - 2.0).abs() < 1e-12, "{p:?}: {laid}");
            let (tx, ty) = (fx - fx.floor(), fy - fy.floor());
            let k = j as usize * c.nx + i as usize;
            let want = [
                (k, 2.0 * (1.0 - ty) * (1.0 - tx)),
                (k + 1, 2.0 * (1.0 - ty) * tx),
                (k + c.nx, 2.0 * ty * (1.0 - tx)),
                (k + c.nx + 1, 2.0 * ty * tx),
            ];
            for (cell, v) in want {
                assert!((c.vol[cell] - v).abs() < 1e-12, "{p:?} cell {cell}");
            }
        };
        let h = 0.005;
        // the window's first cell centre, its cell lines, and just outside
        let (x, y) = (-0.1 + 3.5 * h, 0.2 + 2.5 * h);
        for p in [
            [x, y],
            [x - 1e-9, y],
            [x, y - 1e-9],
            [x + 4.0 * h, y + 3.0 * h],
            [x + 5.0 * h, y],
            [x, y + 4.0 * h],
            [x + 1.5 * h, y + 2.25 * h],
            [-0.1 - h, y],
            [f64::NAN, y],
        ] {
            if p[0].is_nan() {
                let mut c = window();
                c.splat(p, 2.0, 0.0);
                assert_eq!(c.spill.len(), 1);
                assert_eq!(c.vol.iter().sum::<f64>(), 0.0);
                continue;
            }
            check(p);
        }
        proptest::proptest!(|(dx in -0.02f64..0.06, dy in -0.02f64..0.05)| check([x + dx, y + dy]));
        // A window at the grid's first cell (as the whole grid's is): a
        // point less than a cell before its first centre spills whole
        // (truncation there is not the floor).
        let mut c = Canvas {
            i0: 0,
            j0: 0,
            ..window()
        };
        for p in [
            [-0.1 + 0.2 * h, 0.2 + 2.0 * h],
            [-0.1 + 2.0 * h, 0.2 + 0.3 * h],
        ] {
            c.splat(p, 2.0, 0.0);
        }
        assert_eq!(c.spill.len(), 2);
        assert_eq!(c.vol.iter().sum::<f64>(), 0.0);
    }

    #[test]
    fn fitted_cell_coarsens_only_what_does_not_fit() {
        let small = Bounds {
            min: [-2.0, 0.0],
            max: [2.0, 3.0],
        };
        assert_eq!(fitted_cell(small, 0.005, FIT_CELLS), 0.005);
        // A 200-letter job: 40 lines 12.2 m apart across a 3.66 m lane.
        let long = Bounds {
            min: [-1.83, 0.0],
            max: [1.83, 488.0],
        };
        let c = fitted_cell(long, 0.005, FIT_CELLS);
        let cells = |c: f64| (long.width() / c + 5.0) * (long.height() / c + 5.0);
        assert!(c > 0.005 && cells(c) <= FIT_CELLS as f64, "{c}");
        // The finest half-millimetre step that fits, not any coarser.
        assert!(cells(c - 0.0005) > FIT_CELLS as f64, "{c}");
        assert!(Grid::covering(long.grow(2.0 * c), c).is_ok());
    }

    #[test]
    fn millimetres_are_printed_with_their_digits() {
        assert_eq!(mm_text(0.005), "5");
        assert_eq!(mm_text(0.0025), "2.5");
        assert_eq!(mm_text(1e-5), "0.01");
        assert_eq!(mm_text(1.25e-5), "0.0125");
        assert_eq!(mm_text(1e3), "1000000");
    }
    use crate::spray::{Depth, Profile};

    const ALPHA: f64 = 63.5 * std::f64::consts::PI / 180.0; // SPEC §4

    /// A straight stroke along +y at constant speed, fan across it.
    fn straight(width: f64, speed: f64, length: f64, dt: f64) -> Vec<Pose> {
        let z = width / 2.0 / (ALPHA / 2.0).tan(); // 001 eq. 2.5
        let n = (length / speed / dt).round() as usize;
        (0..=n)
            .map(|k| Pose {
                t_s: k as f64 * dt,
                x_m: 0.0,
                y_m: k as f64 * dt * speed,
                z_m: z,
                yaw_rad: 0.0,
                tilt_rad: 0.0,
                gun: k < n,
            })
            .collect()
    }

    #[test]
    fn straight_stroke_at_k_over_w_lays_the_target_film() {
        let (flow, eff, film) = (6.667e-6, 0.9, 3.8e-4); // SPEC §4 example
        let k = flow * eff / film; // 001 eq. 2.6
        let w = 0.2;
        let poses = straight(w, k / w, 1.0, 0.032);
        let m = SprayModel::seed(ALPHA).unwrap();
        let f = deposit(&poses, &m, flow * eff, 0.005, Bounds::EMPTY).unwrap();
        // Middle of the stroke: away from the caps and the side edges.
        for x in [-0.06, 0.0, 0.05] {
            let v = f.grid.sample([x, 0.5]);
            assert!((v / film - 1.0).abs() < 0.02, "film {v} at x = {x}");
        }
        assert!(f.grid.sample([0.2, 0.5]) == 0.0);
    }

    #[test]
    fn deposited_volume_is_flow_times_gun_on_time() {
        let m = SprayModel::new(
            ALPHA,
            Profile::parse("beta:2,3").unwrap(),
            Depth::TopHat { width_m: 0.02 },
        )
        .unwrap();
        let mut poses = straight(0.3, 0.1, 0.4, 0.032);
        // A turning, tilting, rising stretch and a gun-off gap.
        for (k, p) in poses.iter_mut().enumerate() {
            p.yaw_rad = 0.02 * k as f64;
            p.tilt_rad = 0.1 * (k as f64 * 0.3).sin();
            p.z_m += 0.002 * k as f64;
            p.gun = p.gun && !(5..9).contains(&k);
        }
        let f = deposit(&poses, &m, 6e-6, 0.005, Bounds::EMPTY).unwrap();
        let expect = 6e-6 * f.gun_on_s;
        assert!((f.grid.volume() / expect - 1.0).abs() < 1e-9);
        assert!((f.laid_m3 - expect).abs() < 1e-15);
        let on_intervals = poses[..poses.len() - 1].iter().filter(|p| p.gun).count();
        assert!((f.gun_on_s - on_intervals as f64 * 0.032).abs() < 1e-9);
    }

    #[test]
    fn result_does_not_depend_on_chunking_threads() {
        let m = SprayModel::seed(ALPHA).unwrap();
        let poses = straight(0.15, 0.1, 0.8, 0.032);
        let a = deposit(&poses, &m, 6e-6, 0.005, Bounds::EMPTY).unwrap();
        let b = deposit(&poses, &m, 6e-6, 0.005, Bounds::EMPTY).unwrap();
        assert_eq!(a.grid, b.grid);
    }

    #[test]
    fn backwards_time_and_bad_height_are_errors() {
        let m = SprayModel::seed(ALPHA).unwrap();
        let mut poses = straight(0.15, 0.1, 0.1, 0.032);
        poses[1].t_s = -1.0;
        assert!(deposit(&poses, &m, 6e-6, 0.005, Bounds::EMPTY).is_err());
        let mut poses = straight(0.15, 0.1, 0.1, 0.032);
        poses[1].z_m = f64::NAN;
        assert!(deposit(&poses, &m, 6e-6, 0.005, Bounds::EMPTY).is_err());
    }
}
