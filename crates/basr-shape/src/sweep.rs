//! Boustrophedon (trapezoidal) cells of a region along a sweep direction
//! (Choset's cellular decomposition): a line swept across the region meets
//! it in intervals; a cell is a run of intervals that continue unchanged,
//! and cells end only where the interval structure changes (a hole opens
//! or closes, a lobe begins or ends). Each cell becomes a band whose rungs
//! are the intervals, square to the sweep direction.

use kurbo::{Affine, Point};

use super::decompose::Band;
use super::region::Region;

/// Sweep positions closer than this (m) are one, and edges rising less are
/// level: the boolean step snaps vertices to a grid, so an edge that is
/// level in the drawing may rise by a float's width after the rotation.
/// assumed: a micrometre.
const EPS: f64 = 1e-6;

/// Long axis of the region: the direction (rad) of largest second moment.
pub fn principal_angle(r: &Region) -> f64 {
    // Area moments of a polygon by Green's theorem (holes are clockwise, so
    // they subtract).
    let (mut a, mut cx, mut cy, mut ixx, mut iyy, mut ixy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for c in r.contours() {
        let n = c.len();
        for i in 0..n {
            let (p, q) = (c[i], c[(i + 1) % n]);
            let w = p.x * q.y - q.x * p.y;
            a += w / 2.0;
            cx += (p.x + q.x) * w / 6.0;
            cy += (p.y + q.y) * w / 6.0;
            ixx += (p.y * p.y + p.y * q.y + q.y * q.y) * w / 12.0;
            iyy += (p.x * p.x + p.x * q.x + q.x * q.x) * w / 12.0;
            ixy += (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) * w / 24.0;
        }
    }
    if a.abs() < 1e-12 {
        return 0.0;
    }
    let (cx, cy) = (cx / a, cy / a);
    // Central moments: Σx² about the centroid (iyy holds ∫x²), Σy², Σxy.
    let sxx = iyy - a * cx * cx;
    let syy = ixx - a * cy * cy;
    let sxy = ixy - a * cx * cy;
    0.5 * (2.0 * sxy).atan2(sxx - syy)
}

/// The cells of `r` swept along direction `angle` (rad, road frame): each a
/// band travelling along `angle`, rungs square to it.
pub fn bands(r: &Region, angle: f64) -> Vec<Band> {
    // Rotate so the sweep runs along +y.
    let to = Affine::rotate(std::f64::consts::FRAC_PI_2 - angle);
    let back = to.inverse();
    let contours: Vec<Vec<Point>> = r
        .contours()
        .map(|c| c.iter().map(|p| to * *p).collect())
        .collect();
    cells(&contours)
        .into_iter()
        .map(|c| Band {
            rungs: (0..c.ys.len())
                .map(|i| {
                    (
                        back * Point::new(c.xl[i], c.ys[i]),
                        back * Point::new(c.xr[i], c.ys[i]),
                    )
                })
                .collect(),
        })
        .collect()
}

/// A y-monotone cell: its left and right boundary x at each y.
struct Cell {
    ys: Vec<f64>,
    xl: Vec<f64>,
    xr: Vec<f64>,
}

#[derive(Clone, Copy)]
struct Seg {
    lo: Point,
    hi: Point,
}

impl Seg {
    fn x_at(&self, y: f64) -> f64 {
        let t = (y - self.lo.y) / (self.hi.y - self.lo.y);
        self.lo.x + t.clamp(0.0, 1.0) * (self.hi.x - self.lo.x)
    }
}

fn cells(contours: &[Vec<Point>]) -> Vec<Cell> {
    let mut segs: Vec<Seg> = vec![];
    let mut ys: Vec<f64> = vec![];
    for c in contours {
        let n = c.len();
        for i in 0..n {
            let (p, q) = (c[i], c[(i + 1) % n]);
            ys.push(p.y);
            if (p.y - q.y).abs() > EPS {
                let (lo, hi) = if p.y < q.y { (p, q) } else { (q, p) };
                segs.push(Seg { lo, hi });
            }
        }
    }
    ys.sort_by(f64::total_cmp);
    ys.dedup_by(|a, b| (*a - *b).abs() <= EPS);
    segs.sort_by(|a, b| a.lo.y.total_cmp(&b.lo.y));
    let mut next = 0usize;
    let mut active: Vec<usize> = vec![];
    let mut out: Vec<Cell> = vec![];
    // Open cells: (cell index, its top left x, top right x) of the last sub-slab.
    let mut open: Vec<(usize, f64, f64)> = vec![];
    for k in 0..ys.len().saturating_sub(1) {
        let (y0, y1) = (ys[k], ys[k + 1]);
        let ym = 0.5 * (y0 + y1);
        while next < segs.len() && segs[next].lo.y <= y0 + EPS {
            active.push(next);
            next += 1;
        }
        active.retain(|&i| segs[i].hi.y > y0 + EPS);
        let mut span: Vec<usize> = active
            .iter()
            .copied()
            .filter(|&i| segs[i].hi.y >= y1 - EPS)
            .collect();
        span.sort_by(|&a, &b| segs[a].x_at(ym).total_cmp(&segs[b].x_at(ym)));
        let mut now: Vec<(usize, f64, f64)> = vec![];
        for pair in span.chunks_exact(2) {
            let (l, r) = (segs[pair[0]], segs[pair[1]]);
            let (bl, br) = (l.x_at(y0), r.x_at(y0));
            let (tl, tr) = (l.x_at(y1), r.x_at(y1));
            let cont = open
                .iter()
                .find(|(_, ol, or)| (ol - bl).abs() <= 1e-7 && (or - br).abs() <= 1e-7)
                .map(|o| o.0);
            let idx = match cont {
                Some(ci) => ci,
                None => {
                    out.push(Cell {
                        ys: vec![y0],
                        xl: vec![bl],
                        xr: vec![br],
                    });
                    out.len() - 1
                }
            };
            let c = &mut out[idx];
            c.ys.push(y1);
            c.xl.push(tl);
            c.xr.push(tr);
            now.push((idx, tl, tr));
        }
        open = now;
    }
    out
}
