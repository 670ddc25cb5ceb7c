//! Which glyph box is nearest a raster cell, found among the few boxes
//! that can be nearest the cell's block rather than among every box: the
//! metrics give each painted cell to its nearest glyph, and a scan over
//! every glyph for every cell made a long job's film check grow with the
//! square of its letters (issue 28).

use super::raster::{Bounds, Grid};

/// Squared distance from `c` to box `b` (0 inside), as the metrics have
/// always measured it.
pub(super) fn box_distance(b: &Bounds, c: [f64; 2]) -> f64 {
    let dx = (b.min[0] - c[0]).max(c[0] - b.max[0]).max(0.0);
    let dy = (b.min[1] - c[1]).max(c[1] - b.max[1]).max(0.0);
    dx * dx + dy * dy
}

/// The boxes, and per block of cells the boxes that can be nearest a cell
/// centre in it, in index order.
pub(super) struct BoxIndex<'a> {
    boxes: &'a [Bounds],
    /// Cells per block side.
    side: usize,
    /// Blocks per row.
    bx: usize,
    candidates: Vec<Vec<usize>>,
}

/// Cells per block side: about half the median box's larger side, so a
/// block sees a handful of boxes. assumed: any size gives the same answer;
/// this one keeps both the blocks and their lists short.
fn block_side(grid: &Grid, boxes: &[Bounds]) -> usize {
    let mut sizes: Vec<f64> = boxes
        .iter()
        .filter(|b| !b.is_empty())
        .map(|b| (b.max[0] - b.min[0]).max(b.max[1] - b.min[1]))
        .collect();
    if sizes.is_empty() {
        return grid.nx.max(grid.ny).max(1);
    }
    sizes.sort_by(f64::total_cmp);
    let half = 0.5 * sizes[sizes.len() / 2] / grid.cell_m;
    if half.is_finite() {
        (half as usize).clamp(1, grid.nx.max(grid.ny).max(1))
    } else {
        1
    }
}

impl<'a> BoxIndex<'a> {
    pub(super) fn new(grid: &Grid, boxes: &'a [Bounds]) -> BoxIndex<'a> {
        let side = block_side(grid, boxes);
        let bx = grid.nx.div_ceil(side).max(1);
        let by = grid.ny.div_ceil(side).max(1);
        let mut candidates = Vec::with_capacity(bx * by);
        for bj in 0..by {
            for bi in 0..bx {
                // The block's cell centres span this rectangle.
                let (i0, j0) = (bi * side, bj * side);
                let i1 = (i0 + side).min(grid.nx).max(i0 + 1) - 1;
                let j1 = (j0 + side).min(grid.ny).max(j0 + 1) - 1;
                let lo = grid.centre(i0, j0);
                let hi = grid.centre(i1, j1);
                candidates.push(candidates_of(boxes, lo, hi));
            }
        }
        BoxIndex {
            boxes,
            side,
            bx,
            candidates,
        }
    }

    /// The nearest box to `c`, the centre of cell (`i`, `j`); of equally
    /// near boxes the first (as a scan over every box finds it).
    pub(super) fn nearest(&self, i: usize, j: usize, c: [f64; 2]) -> usize {
        let list = &self.candidates[(j / self.side) * self.bx + i / self.side];
        let mut best = list.first().copied().unwrap_or(0);
        for &k in list {
            if box_distance(&self.boxes[k], c) < box_distance(&self.boxes[best], c) {
                best = k;
            }
        }
        best
    }
}

/// The boxes that can be nearest some point of the rectangle `lo`–`hi`:
/// every box whose distance to the rectangle is within the least of the
/// boxes' farthest distances from it. A box's distance is largest at a
/// corner (it grows away from the box along each axis apart), and the
/// rounded distances keep both orders, so no box left out can be nearer
/// than one kept, nor tie with one.
fn candidates_of(boxes: &[Bounds], lo: [f64; 2], hi: [f64; 2]) -> Vec<usize> {
    let corners = [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi];
    let farthest = |b: &Bounds| {
        corners
            .iter()
            .map(|&c| box_distance(b, c))
            .fold(0.0, f64::max)
    };
    let bound = boxes.iter().map(farthest).fold(f64::INFINITY, f64::min);
    let to_rect = |b: &Bounds| {
        let dx = (b.min[0] - hi[0]).max(lo[0] - b.max[0]).max(0.0);
        let dy = (b.min[1] - hi[1]).max(lo[1] - b.max[1]).max(0.0);
        dx * dx + dy * dy
    };
    (0..boxes.len())
        .filter(|&k| to_rect(&boxes[k]) <= bound)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scan over every box, as the metrics did it before the index.
    fn scan(boxes: &[Bounds], c: [f64; 2]) -> usize {
        let mut best = 0;
        for (k, b) in boxes.iter().enumerate() {
            if box_distance(b, c) < box_distance(&boxes[best], c) {
                best = k;
            }
        }
        best
    }

    #[test]
    fn the_index_finds_the_box_the_scan_finds_at_every_cell() {
        // Letters' boxes of a few lines, some touching, one repeated
        // (ties go to the first), one empty (a glyph without strokes).
        let mut boxes = vec![];
        for line in 0..3 {
            for k in 0..4 {
                let x = 0.6 * k as f64;
                let y = 3.0 * line as f64;
                boxes.push(Bounds {
                    min: [x, y],
                    max: [x + 0.45 + 0.05 * k as f64, y + 2.4],
                });
            }
        }
        boxes.push(boxes[5]);
        boxes.push(Bounds::EMPTY);
        let grid = Grid::covering(
            Bounds {
                min: [-1.0, -1.0],
                max: [4.0, 10.0],
            },
            0.05,
        )
        .unwrap();
        let index = BoxIndex::new(&grid, &boxes);
        assert!(index.side > 1, "blocks of one cell would test nothing");
        let mut differ = 0;
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let c = grid.centre(i, j);
                if index.nearest(i, j, c) != scan(&boxes, c) {
                    differ += 1;
                }
            }
        }
        assert_eq!(differ, 0);
        // The repeated box never wins over its first.
        let inside = [boxes[5].min[0] + 0.1, boxes[5].min[1] + 0.1];
        assert_eq!(scan(&boxes, inside), 5);
    }
}
