//! Convex pieces of a region (i_triangle: Delaunay triangulation, triangles
//! grouped into convex polygons), each swept along its own directions
//! (`decompose::pieces_plan`). The grouping is greedy: a star's arms may
//! come out merged with parts of its centre (`lobes` cuts them off whole).

use i_triangle::float::triangulatable::Triangulatable;
use kurbo::Point;

use super::region::{signed_area, Region};

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
