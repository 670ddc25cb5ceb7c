//! DXF HATCH boundaries, read from the file's group codes: the `dxf` crate
//! (0.6) skips HATCH entities, and no maintained crate reads them, so this
//! reads only what a filled hatch needs: its boundary paths, polyline
//! (with bulges) or edge loops of lines, circular arcs, elliptic arcs and
//! splines. Group codes as in the DXF reference's HATCH section
//! (AutoCAD 2012 DXF Reference, "HATCH", "Boundary Path Data").

use kurbo::{Arc, BezPath, Point, Vec2};

use super::dxf::{bulge_path, sample_spline, ARC_TOLERANCE};
use super::{Element, FillRule, ShapeError};

/// Boundary path type flag (group 92) bit: the path is a polyline.
const PATH_IS_POLYLINE: i64 = 2;
/// Edges of a loop whose ends are this far apart (relative to the loop's
/// size) are joined. assumed: 1e-6, far below a drawing's precision yet
/// above the round-off of angles written with 6 to 15 digits.
const JOIN_RELATIVE: f64 = 1e-6;

/// One group code and its value, with the line the code is on (1-based).
#[derive(Clone, Copy, Debug)]
struct Pair<'a> {
    code: i64,
    value: &'a str,
    line: usize,
}

/// The file as group code / value pairs (ASCII DXF: a code line, a value line).
fn pairs(text: &str) -> Vec<Pair<'_>> {
    let lines: Vec<&str> = text.lines().collect();
    lines
        .chunks(2)
        .enumerate()
        .filter_map(|(i, c)| {
            let code = c.first()?.trim().parse().ok()?;
            Some(Pair {
                code,
                value: c.get(1).map_or("", |v| v.trim()),
                line: 2 * i + 1,
            })
        })
        .collect()
}

/// Every HATCH of the ENTITIES section as one even-odd element whose
/// subpaths are its boundary loops.
pub fn read_hatches(text: &str, origin: &str) -> Result<Vec<Element>, ShapeError> {
    let p = pairs(text);
    let mut out = vec![];
    let mut in_entities = false;
    let mut i = 0;
    while i < p.len() {
        let (c, v) = (p[i].code, p[i].value);
        if c == 0 && v == "SECTION" {
            in_entities = p
                .get(i + 1)
                .is_some_and(|n| n.code == 2 && n.value == "ENTITIES");
        } else if c == 0 && v == "ENDSEC" {
            in_entities = false;
        } else if c == 0 && v == "HATCH" && in_entities {
            let end = (i + 1..p.len())
                .find(|&j| p[j].code == 0)
                .unwrap_or(p.len());
            out.push(hatch(&p[i..end], origin)?);
            i = end;
            continue;
        }
        i += 1;
    }
    Ok(out)
}

/// A cursor over one entity's pairs.
struct Cursor<'a, 'b> {
    p: &'b [Pair<'a>],
    i: usize,
    name: String,
    origin: &'b str,
}

impl<'a, 'b> Cursor<'a, 'b> {
    fn peek(&self) -> Option<i64> {
        self.p.get(self.i).map(|q| q.code)
    }

    fn bad(&self, what: String) -> ShapeError {
        let line = self.p.get(self.i).or(self.p.last()).map_or(0, |q| q.line);
        ShapeError::invalid(
            self.origin,
            format!(
                "{} (line {line}): {what}; save the drawing again as ASCII DXF, or draw the \
                 hatch's boundary as a closed polyline",
                self.name
            ),
        )
    }

    /// The next pair, which must have `code`.
    fn take(&mut self, code: i64) -> Result<&'a str, ShapeError> {
        match self.p.get(self.i) {
            Some(q) if q.code == code => {
                self.i += 1;
                Ok(q.value)
            }
            Some(q) => Err(self.bad(format!(
                "expected group code {code} of its boundary data, found {}",
                q.code
            ))),
            None => Err(self.bad(format!("its boundary data ends before group code {code}"))),
        }
    }

    fn num(&mut self, code: i64) -> Result<f64, ShapeError> {
        let v = self.take(code)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                self.i -= 1;
                self.bad(format!("group code {code} holds {v:?}, not a number"))
            })
    }

    fn int(&mut self, code: i64) -> Result<i64, ShapeError> {
        let v = self.take(code)?;
        v.parse::<i64>().map_err(|_| {
            self.i -= 1;
            self.bad(format!("group code {code} holds {v:?}, not an integer"))
        })
    }

    /// A count (at most the pairs left, so a corrupt count cannot allocate).
    fn count(&mut self, code: i64) -> Result<usize, ShapeError> {
        let n = self.int(code)?;
        let left = self.p.len() - self.i;
        usize::try_from(n)
            .ok()
            .filter(|&n| n <= left)
            .ok_or_else(|| {
                self.i -= 1;
                self.bad(format!("group code {code} gives a count of {n}"))
            })
    }

    fn point(&mut self, x: i64) -> Result<Point, ShapeError> {
        Ok(Point::new(self.num(x)?, self.num(x + 10)?))
    }

    /// Skip to the next pair with `code` (fields this reader does not need).
    fn seek(&mut self, code: i64) -> Result<(), ShapeError> {
        match self.p[self.i..].iter().position(|q| q.code == code) {
            Some(k) => {
                self.i += k;
                Ok(())
            }
            None => Err(self.bad(format!("no group code {code} (number of boundary paths)"))),
        }
    }
}

fn hatch(p: &[Pair<'_>], origin: &str) -> Result<Element, ShapeError> {
    let handle = p.iter().find(|q| q.code == 5).map(|q| q.value);
    let name = match handle {
        Some(h) => format!("HATCH (handle {h})"),
        None => format!("HATCH at line {}", p[0].line),
    };
    let mut c = Cursor {
        p,
        i: 1,
        name: name.clone(),
        origin,
    };
    c.seek(91)?;
    let paths = c.count(91)?;
    let mut path = BezPath::new();
    for _ in 0..paths {
        let flag = c.int(92)?;
        let lp = if flag & PATH_IS_POLYLINE != 0 {
            polyline_loop(&mut c)?
        } else {
            edge_loop(&mut c)?
        };
        path.extend(lp);
        let sources = c.count(97)?;
        for _ in 0..sources {
            c.take(330)?;
        }
    }
    if path.elements().is_empty() {
        return Err(ShapeError::invalid(
            origin,
            format!("{name} has no boundary path: nothing to fill; hatch a closed outline"),
        ));
    }
    Ok(Element {
        name,
        rule: FillRule::EvenOdd,
        path,
    })
}

/// A polyline boundary: 72 has-bulge, 73 closed, 93 vertices, 10/20 [42] each.
fn polyline_loop(c: &mut Cursor) -> Result<BezPath, ShapeError> {
    let has_bulge = c.int(72)? != 0;
    let _closed = c.int(73)?; // a hatch boundary is closed whatever the flag
    let n = c.count(93)?;
    let mut pts = Vec::with_capacity(n);
    for _ in 0..n {
        let q = c.point(10)?;
        let b = if has_bulge && c.peek() == Some(42) {
            c.num(42)?
        } else {
            0.0
        };
        pts.push((q, b));
    }
    if pts.len() > 1 && (pts[0].0 - pts[pts.len() - 1].0).hypot() < 1e-12 {
        pts.pop(); // the first vertex repeated at the end
    }
    if pts.len() < 3 && !pts.iter().any(|p| p.1 != 0.0) {
        return Err(c.bad(format!(
            "a polyline boundary of {} vertices encloses nothing",
            pts.len()
        )));
    }
    Ok(bulge_path(&pts))
}

/// One edge of an edge loop, as points or cubic pieces from its start to its end.
enum Piece {
    Line(Point, Point),
    Curve(BezPath),
}

impl Piece {
    fn ends(&self) -> (Point, Point) {
        match self {
            Piece::Line(a, b) => (*a, *b),
            Piece::Curve(p) => {
                let els = p.elements();
                let first = match els.first() {
                    Some(kurbo::PathEl::MoveTo(q)) => *q,
                    _ => Point::ORIGIN,
                };
                let last = els
                    .iter()
                    .rev()
                    .find_map(|e| e.end_point())
                    .unwrap_or(first);
                (first, last)
            }
        }
    }

    fn reversed(self) -> Piece {
        match self {
            Piece::Line(a, b) => Piece::Line(b, a),
            Piece::Curve(p) => Piece::Curve(p.reverse_subpaths()),
        }
    }
}

/// An edge boundary: 93 edges, each 72 type then its data.
fn edge_loop(c: &mut Cursor) -> Result<BezPath, ShapeError> {
    let n = c.count(93)?;
    let mut pieces: Vec<Piece> = Vec::with_capacity(n);
    for k in 0..n {
        let kind = c.int(72)?;
        let last = k + 1 == n;
        let piece = match kind {
            1 => Piece::Line(c.point(10)?, c.point(11)?),
            2 => {
                let centre = c.point(10)?;
                let r = c.num(40)?;
                let (a0, a1) = (c.num(50)?, c.num(51)?);
                let ccw = c.int(73)? != 0;
                Piece::Curve(elliptic(centre, Vec2::new(r, 0.0), 1.0, a0, a1, ccw))
            }
            3 => {
                let centre = c.point(10)?;
                let major = c.point(11)?.to_vec2();
                let ratio = c.num(40)?;
                let (a0, a1) = (c.num(50)?, c.num(51)?);
                let ccw = c.int(73)? != 0;
                Piece::Curve(elliptic(centre, major, ratio, a0, a1, ccw))
            }
            4 => spline_edge(c, last)?,
            other => {
                c.i -= 1;
                return Err(c.bad(format!(
                    "edge type {other} (group 72) is none of 1 line, 2 arc, 3 ellipse, 4 spline"
                )));
            }
        };
        pieces.push(piece);
    }
    chain(pieces).ok_or_else(|| c.bad("its boundary edges do not join into a closed loop".into()))
}

/// A circular or elliptic arc edge: centre, major axis (its end point from
/// the centre), minor/major ratio, start and end angles in degrees. A
/// clockwise edge (73 = 0) keeps its angles measured clockwise, as the DXF
/// reference's edge data and AutoCAD write them.
fn elliptic(centre: Point, major: Vec2, ratio: f64, a0: f64, a1: f64, ccw: bool) -> BezPath {
    let (s, e) = if ccw { (a0, a1) } else { (-a0, -a1) };
    let mut sweep = (e - s).to_radians();
    if ccw {
        sweep = sweep.rem_euclid(std::f64::consts::TAU);
    } else {
        sweep = -(-sweep).rem_euclid(std::f64::consts::TAU);
    }
    if sweep.abs() < 1e-12 {
        sweep = if ccw { 1.0 } else { -1.0 } * std::f64::consts::TAU;
    }
    let rx = major.hypot();
    let arc = Arc::new(
        centre,
        (rx, rx * ratio),
        s.to_radians(),
        sweep,
        major.atan2(),
    );
    let mut path = BezPath::new();
    path.move_to(arc.center + point_on(&arc, arc.start_angle));
    arc.to_cubic_beziers(ARC_TOLERANCE, |p1, p2, p| path.curve_to(p1, p2, p));
    path
}

fn point_on(arc: &Arc, t: f64) -> Vec2 {
    let (s, c) = arc.x_rotation.sin_cos();
    let (x, y) = (arc.radii.x * t.cos(), arc.radii.y * t.sin());
    Vec2::new(x * c - y * s, x * s + y * c)
}

/// A spline edge: 94 degree, 73 rational, 74 periodic, 95 knots, 96
/// control points, the knots (40), the control points (10/20, 42 weight
/// when rational), then fit data (97 count, 11/21 points, 12/22 and 13/23
/// tangents) that newer files write and this reader skips.
fn spline_edge(c: &mut Cursor, last: bool) -> Result<Piece, ShapeError> {
    let degree = c.int(94)?;
    let rational = c.int(73)? != 0;
    let _periodic = c.int(74)?;
    let nk = c.count(95)?;
    let nc = c.count(96)?;
    let knots = (0..nk).map(|_| c.num(40)).collect::<Result<Vec<_>, _>>()?;
    let mut cps = Vec::with_capacity(nc);
    let mut w = Vec::with_capacity(nc);
    for _ in 0..nc {
        cps.push(c.point(10)?);
        w.push(if rational && c.peek() == Some(42) {
            c.num(42)?
        } else {
            1.0
        });
    }
    // Fit data: "97 n" then points and tangents. A last edge's "97 0" may
    // instead be the path's source-object count; two 97s in a row settle it.
    let fit_follows = |c: &Cursor| {
        c.peek() == Some(97)
            && (!last || matches!(c.p.get(c.i + 1).map(|q| q.code), Some(11 | 12 | 97)))
    };
    if fit_follows(c) {
        let nf = c.count(97)?;
        for _ in 0..nf {
            c.point(11)?;
        }
        if c.peek() == Some(12) {
            c.point(12)?;
        }
        if c.peek() == Some(13) {
            c.point(13)?;
        }
    }
    let degree = usize::try_from(degree).unwrap_or(0);
    let pts = sample_spline(degree, &knots, &cps, &w).ok_or_else(|| {
        c.bad("a spline edge has a bad knot vector or too few control points".into())
    })?;
    let mut path = BezPath::new();
    path.move_to(pts[0]);
    for q in &pts[1..] {
        path.line_to(*q);
    }
    Ok(Piece::Curve(path))
}

/// The edges joined end to start into one closed subpath (an edge that
/// runs the other way is turned round), or `None` when they do not meet.
fn chain(pieces: Vec<Piece>) -> Option<BezPath> {
    let size = pieces
        .iter()
        .flat_map(|p| {
            let (a, b) = p.ends();
            [a, b]
        })
        .fold(0.0f64, |m, q| m.max(q.x.abs()).max(q.y.abs()))
        .max(1.0);
    let tol = JOIN_RELATIVE * size;
    let mut path = BezPath::new();
    let mut start = None;
    let mut at = Point::ORIGIN;
    for (k, piece) in pieces.into_iter().enumerate() {
        let (a, b) = piece.ends();
        let piece = if k == 0 || (a - at).hypot() <= tol {
            piece
        } else if (b - at).hypot() <= tol {
            piece.reversed()
        } else {
            return None;
        };
        let (a, b) = piece.ends();
        if k == 0 {
            path.move_to(a);
            start = Some(a);
        }
        match piece {
            Piece::Line(_, b) => path.line_to(b),
            Piece::Curve(p) => {
                for el in p.elements().iter().skip(1) {
                    path.push(*el);
                }
            }
        }
        at = b;
    }
    let start = start?;
    if (at - start).hypot() > tol {
        return None;
    }
    path.close_path();
    Some(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Shape;

    /// A DXF of one HATCH entity whose boundary data is `body`.
    fn dxf(body: &str) -> String {
        format!(
            "0\nSECTION\n2\nENTITIES\n0\nHATCH\n5\n3F\n100\nAcDbEntity\n8\n0\n100\nAcDbHatch\n\
             10\n0\n20\n0\n30\n0\n210\n0\n220\n0\n230\n1\n2\nSOLID\n70\n1\n71\n0\n{body}\
             75\n0\n76\n1\n98\n0\n0\nENDSEC\n0\nEOF\n"
        )
    }

    fn area(e: &Element) -> f64 {
        e.path.area().abs()
    }

    #[test]
    fn a_polyline_boundary_with_a_bulge_is_a_square_and_a_half_disc() {
        // 2 × 2 square whose top edge bulges out into a half circle of radius 1.
        let t = dxf(
            "91\n1\n92\n7\n72\n1\n73\n1\n93\n4\n10\n0\n20\n0\n10\n2\n20\n0\n\
                     10\n2\n20\n2\n42\n1\n10\n0\n20\n2\n97\n0\n",
        );
        let h = read_hatches(&t, "t.dxf").expect("reads");
        assert_eq!(h.len(), 1);
        assert_eq!(h[0].name, "HATCH (handle 3F)");
        let want = 4.0 + 0.5 * std::f64::consts::PI;
        assert!((area(&h[0]) - want).abs() < 1e-3, "{}", area(&h[0]));
    }

    #[test]
    fn edge_boundaries_of_lines_arcs_ellipses_and_splines_join() {
        // Lines along the bottom, a clockwise-stored arc edge is not used;
        // loop: (0,0)→(4,0) line, arc centre (4,1) r 1 from -90° to 90°
        // (ccw), line (4,2)→(0,2), half ellipse centre (0,1), major (0,1),
        // ratio 0.5 from 0° to 180° ccw: (0,2) → (0,0) bulging to x = -0.5.
        let t = dxf("91\n2\n92\n1\n93\n4\n\
                     72\n1\n10\n0\n20\n0\n11\n4\n21\n0\n\
                     72\n2\n10\n4\n20\n1\n40\n1\n50\n-90\n51\n90\n73\n1\n\
                     72\n1\n10\n4\n20\n2\n11\n0\n21\n2\n\
                     72\n3\n10\n0\n20\n1\n11\n0\n21\n1\n40\n0.5\n50\n0\n51\n180\n73\n1\n\
                     97\n0\n\
                     92\n1\n93\n1\n\
                     72\n4\n94\n1\n73\n0\n74\n0\n95\n6\n96\n4\n\
                     40\n0\n40\n0\n40\n1\n40\n2\n40\n3\n40\n3\n\
                     10\n1\n20\n0.5\n10\n2\n20\n0.5\n10\n2\n20\n1.5\n10\n1\n20\n0.5\n\
                     97\n0\n97\n0\n");
        let h = read_hatches(&t, "t.dxf").expect("reads");
        let outer = 8.0 + 0.5 * std::f64::consts::PI + 0.5 * std::f64::consts::PI * 0.5;
        // The spline of degree 1 is the triangle (1,.5) (2,.5) (2,1.5): a hole of 0.5.
        let regions = crate::region::regions(
            &crate::Outline {
                origin: "t".into(),
                elements: h,
                metres_per_unit: Some(1.0),
            },
            1.0,
        )
        .expect("regions");
        assert_eq!(regions.len(), 1);
        assert_eq!(regions[0].holes.len(), 1);
        assert!(
            (regions[0].area() - (outer - 0.5)).abs() < 0.01,
            "{} vs {}",
            regions[0].area(),
            outer - 0.5
        );
    }

    #[test]
    fn a_clockwise_arc_edge_reads_its_angles_clockwise() {
        // Half disc: line (-1,0)→(1,0), then the arc back over the top,
        // stored clockwise from 0° to 180° (angles measured clockwise: the
        // arc through (0,-1)), so the region is the lower half disc.
        let t = dxf("91\n1\n92\n1\n93\n2\n\
                     72\n1\n10\n-1\n20\n0\n11\n1\n21\n0\n\
                     72\n2\n10\n0\n20\n0\n40\n1\n50\n0\n51\n180\n73\n0\n97\n0\n");
        let h = read_hatches(&t, "t.dxf").expect("reads");
        let bb = h[0].path.bounding_box();
        assert!(bb.y0 < -0.99 && bb.y1 < 1e-9, "{bb:?}");
        assert!((area(&h[0]) - 0.5 * std::f64::consts::PI).abs() < 1e-3);
    }

    #[test]
    fn broken_hatches_are_refused_with_their_handle_and_line() {
        let e = read_hatches(
            &dxf("91\n1\n92\n1\n93\n2\n72\n1\n10\n0\n20\n0\n11\n1\n21\n0\n\
                                   72\n1\n10\n5\n20\n5\n11\n6\n21\n6\n97\n0\n"),
            "t.dxf",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("HATCH (handle 3F)") && e.contains("closed loop"),
            "{e}"
        );
        let e = read_hatches(&dxf("91\n1\n92\n1\n93\n1\n72\n9\n"), "t.dxf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("edge type 9") && e.contains("line "), "{e}");
        let e = read_hatches(&dxf("91\n1\n92\n2\n72\n0\n73\n1\n93\n99999\n"), "t.dxf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("count of 99999"), "{e}");
        let e = read_hatches(&dxf("91\n1\n92\n2\n72\n0\n73\n1\n93\n3\n10\nx\n"), "t.dxf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a number"), "{e}");
    }
}
