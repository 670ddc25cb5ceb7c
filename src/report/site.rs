//! The job sheet's part for the site: per stop, the reference points to
//! chalk (from the marking's anchor, in the crew's units, and as the points
//! file wants them) and a picture of where they are on the stop's strokes;
//! and the fit procedure in plain words (docs/site.md).

use std::fmt::Write as _;

use crate::job::reference::{reference_points, stop_strokes, ReferencePoint};
use crate::job::Job;
use crate::units::System;

use super::html::escape;

/// One stop's reference points and picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Chalk {
    /// 1-based, as the crew counts.
    pub stop: usize,
    /// (name, where in words, road x and y in metres).
    pub points: Vec<(String, String, [f64; 2])>,
    /// An inline SVG of the stop's strokes with the points marked.
    pub svg: String,
}

/// Where a road point is, from the anchor, in the crew's units: across
/// then along (`0.78 m right, 2.40 m past`).
fn words(p: [f64; 2], units: System) -> String {
    let across = if p[0].abs() < 0.005 {
        "on the centre".to_string()
    } else if p[0] > 0.0 {
        format!("{} right", units.length(p[0]))
    } else {
        format!("{} left", units.length(-p[0]))
    };
    // under half a centimetre either way reads 0.00 m (or 0 in) past, not
    // "0.00 m before" of a point a hair behind
    let along = if p[1] >= -0.005 {
        format!("{} past", units.length(p[1].max(0.0)))
    } else {
        format!("{} before", units.length(-p[1]))
    };
    format!("{across}, {along}")
}

/// `v`, but 0 where it prints as zero at three decimals (a point a
/// hair behind the anchor printed `-0.000`).
fn unsigned_zero(v: f64) -> f64 {
    if v.abs() < 5e-4 {
        0.0
    } else {
        v
    }
}

/// The strokes painted from stop `index`, as closed outlines (road frame).
fn outlines(job: &Job, index: usize) -> Vec<Vec<[f64; 2]>> {
    stop_strokes(job, index)
        .into_iter()
        .map(|st| {
            st.left
                .iter()
                .chain(st.right.iter().rev())
                .copied()
                .collect()
        })
        .collect()
}

/// Picture side (px) and margin: small enough that a stop's picture sits
/// beside its table and the crew's part of the sheet stays on one page.
const SIDE_PX: f64 = 64.0;
const MARGIN_PX: f64 = 8.0;

/// The stop's strokes seen from above, traffic up the page, the points
/// as red dots with their names.
fn picture(shapes: &[Vec<[f64; 2]>], points: &[ReferencePoint]) -> String {
    let all = shapes
        .iter()
        .flatten()
        .chain(points.iter().map(|p| &p.road_m));
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in all {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if !(lo[0].is_finite() && hi[0] > lo[0] - 1.0) {
        return String::new();
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(0.1);
    let scale = (SIDE_PX - 2.0 * MARGIN_PX) / span;
    let at = |p: &[f64; 2]| {
        (
            MARGIN_PX + (p[0] - lo[0]) * scale,
            SIDE_PX - MARGIN_PX - (p[1] - lo[1]) * scale,
        )
    };
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{SIDE_PX}\" height=\"{SIDE_PX}\" \
         viewBox=\"0 0 {SIDE_PX} {SIDE_PX}\" role=\"img\" aria-label=\"reference points\">\
         <rect width=\"100%\" height=\"100%\" fill=\"#f4f4f4\"/>"
    );
    for sh in shapes {
        let d: Vec<String> = sh
            .iter()
            .map(|p| {
                let (x, y) = at(p);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = write!(
            svg,
            "<polygon points=\"{}\" fill=\"#ddd\" stroke=\"#888\" stroke-width=\"0.6\"/>",
            d.join(" ")
        );
    }
    for (k, p) in points.iter().enumerate() {
        let (x, y) = at(&p.road_m);
        // Numbered as the line beside the picture lists them: names would
        // overlap at this size.
        let (dx, anchor) = if x > SIDE_PX / 2.0 {
            (-5.0, "end")
        } else {
            (5.0, "start")
        };
        let _ = write!(
            svg,
            "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"#c00\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"9\" font-weight=\"bold\" \
             text-anchor=\"{anchor}\" font-family=\"sans-serif\" fill=\"#c00\">{}</text>",
            x + dx,
            y + 3.0,
            k + 1
        );
    }
    svg.push_str(
        "<text x=\"2\" y=\"8\" font-size=\"7\" font-family=\"sans-serif\" fill=\"#555\">\
         ↑</text></svg>",
    );
    svg
}

/// Every stop's reference points.
pub fn chalk(job: &Job, units: System) -> Vec<Chalk> {
    (0..job.stations.len())
        .map(|k| {
            let refs = reference_points(job, k);
            let svg = picture(&outlines(job, k), &refs);
            Chalk {
                stop: k + 1,
                points: refs
                    .iter()
                    .map(|r| (r.name.clone(), words(r.road_m, units), r.road_m))
                    .collect(),
                svg,
            }
        })
        .collect()
}

/// The fit procedure in plain words, for the job file `job_name`.
pub fn steps(job_name: &str) -> String {
    format!(
        "jog the nozzle over each chalked point, read x, y and the road's height from the \
         controller into a points file and run basr fit {job_name} --points FILE -o \
         fitted.job.json --csv fitted.csv; load fitted.csv instead (basr fit --help shows \
         the file)."
    )
}

/// One stop's reference points as the stop's line on the sheet shows them:
/// the picture and the points in a line.
pub fn render(out: &mut String, c: &Chalk) {
    let _ = write!(
        out,
        "<div class=\"chalk\">{}<p>Reference points for basr fit: ",
        c.svg
    );
    let items: Vec<String> = c
        .points
        .iter()
        .enumerate()
        .map(|(k, (name, w, p))| {
            format!(
                "{} <strong>{}</strong> {} <code>[{:.3}, {:.3}]</code>",
                k + 1,
                escape(name),
                escape(w),
                unsigned_zero(p[0]),
                unsigned_zero(p[1])
            )
        })
        .collect();
    out.push_str(&items.join("; "));
    out.push_str("</p></div>");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_say_along_and_across() {
        assert_eq!(
            words([-0.94, 0.01], System::Metric),
            "0.94 m left, 0.01 m past"
        );
        assert_eq!(
            words([0.0, -1.0], System::Metric),
            "on the centre, 1.00 m before"
        );
        // a point a hair behind the anchor is not "0.00 m before", nor
        // printed -0.000
        assert_eq!(
            words([-1.134, -0.0004], System::Metric),
            "1.13 m left, 0.00 m past"
        );
        assert_eq!(format!("{:.3}", unsigned_zero(-0.0004)), "0.000");
        assert_eq!(unsigned_zero(-0.0006), -0.0006);
    }

    #[test]
    fn the_picture_marks_every_point() {
        let shapes = vec![vec![[0.0, 0.0], [0.3, 0.0], [0.3, 2.0], [0.0, 2.0]]];
        let pts = vec![
            ReferencePoint {
                name: "A".into(),
                road_m: [0.0, 0.0],
            },
            ReferencePoint {
                name: "B".into(),
                road_m: [0.3, 2.0],
            },
        ];
        let svg = picture(&shapes, &pts);
        assert_eq!(svg.matches("<circle").count(), 2);
        assert!(svg.contains(">1<") && svg.contains(">2<"));
        assert!(svg.contains("<polygon"));
    }
}
