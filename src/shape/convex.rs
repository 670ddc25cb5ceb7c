//! Convex pieces of a region (i_triangle: Delaunay triangulation, triangles
//! grouped into convex polygons), each swept along its own long axis: a
//! star becomes its five arms and its centre, each painted along itself,
//! where one sweep for the whole region cuts the arms across.

use i_triangle::float::triangulatable::Triangulatable;
use kurbo::Point;

use super::decompose::Band;
use super::region::{signed_area, Region};
use super::sweep;

/// The convex pieces of `r` as regions without holes, counter-clockwise.
pub fn pieces(r: &Region) -> Vec<Region> {
    let shape: Vec<Vec<[f64; 2]>> = r
        .contours()
        .map(|c| c.iter().map(|p| [p.x, p.y]).collect())
        .collect();
    shape
        .triangulate()
        .into_delaunay()
        .to_convex_polygons()
        .into_iter()
        .map(|c| {
            let mut outer: Vec<Point> = c.iter().map(|p| Point::new(p[0], p[1])).collect();
            if signed_area(&outer) < 0.0 {
                outer.reverse();
            }
            Region {
                outer,
                holes: vec![],
            }
        })
        .collect()
}

/// One piece's bands swept along `angle`, or along its own long axis when
/// `angle` is `None` (a convex piece is one cell in any direction).
pub fn bands(piece: &Region, angle: Option<f64>) -> Vec<Band> {
    sweep::bands(
        piece,
        angle.unwrap_or_else(|| sweep::principal_angle(piece)),
    )
}
