//! Placed strokes: every band of paint of a marking in the road frame, with
//! the item (letter, symbol, shape) it belongs to.
//!
//! This is the seam between what is painted and how: a scene of words,
//! symbols or imported shapes only has to produce a [`PlacedStrokes`]; the
//! rest of the planner (rungs, knots, passes, stations, tours, time law)
//! reads nothing else about the marking. [`PlacedStrokes::from_letters`]
//! makes one from a laid-out message and its font.

use kurbo::Affine;

use basr_job::{PlacedGlyph, PlacedStroke as OutlineStroke};
use basr_shape::font::{Font, Stroke};
use basr_shape::layout::{Laid, Placed};

use super::warnings::{Note, Owner, OwnerKind};

/// Outline samples of `layout.glyphs` are at most this far apart (m).
const OUTLINE_STEP_M: f64 = 0.01;

/// One item of the marking: a letter, a symbol or a shape.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedItem {
    pub owner: Owner,
    /// A letter's height (m); `None` for a symbol or a shape.
    pub letter_height_m: Option<f64>,
}

/// One stroke in the road frame (left and right edges as the font or
/// shape gives them; see `font` for the convention).
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedStroke {
    pub stroke: Stroke,
    /// Index into [`PlacedStrokes::items`].
    pub item: usize,
}

/// Every stroke of a marking, in painting-plan order (the stroke index used
/// in messages and the job's `stroke` column is the index here).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PlacedStrokes {
    pub items: Vec<PlacedItem>,
    pub strokes: Vec<PlacedStroke>,
    /// Notes of the layout (MUTCD rules bent), carried into the job.
    pub notes: Vec<Note>,
}

impl PlacedStrokes {
    /// The strokes of a laid-out message or scene (letters and symbols
    /// already in the road frame), its warnings as layout notes.
    pub fn from_laid(laid: &Laid) -> PlacedStrokes {
        let mut out = PlacedStrokes {
            notes: laid
                .warnings
                .iter()
                .map(|w| Note::Layout { text: w.clone() })
                .collect(),
            ..PlacedStrokes::default()
        };
        for mark in &laid.marks {
            let item = out.items.len();
            out.items.push(PlacedItem {
                owner: Owner {
                    kind: mark.kind,
                    label: mark.label.clone(),
                    line: mark.line,
                },
                letter_height_m: mark.letter_height_m,
            });
            out.strokes
                .extend(mark.strokes.iter().map(|st| PlacedStroke {
                    stroke: st.clone(),
                    item,
                }));
        }
        out
    }

    /// The strokes of laid-out letters, each glyph mapped from its grid into
    /// the road frame. Letters without a glyph were refused by the layout.
    pub fn from_letters(placed: &Placed, font: &Font) -> PlacedStrokes {
        let mut out = PlacedStrokes {
            notes: placed
                .warnings
                .iter()
                .map(|w| Note::Layout { text: w.clone() })
                .collect(),
            ..PlacedStrokes::default()
        };
        for letter in &placed.letters {
            let Some(glyph) = font.glyph(letter.ch) else {
                continue;
            };
            let s = letter.scale_m;
            let to_road = Affine::new([s, 0.0, 0.0, s, letter.origin_m[0], letter.origin_m[1]]);
            let item = out.items.len();
            out.items.push(PlacedItem {
                owner: Owner {
                    kind: OwnerKind::Letter,
                    label: letter.ch.to_string(),
                    line: letter.line,
                },
                letter_height_m: Some(s * basr_shape::font::GRID_HEIGHT),
            });
            out.strokes
                .extend(glyph.strokes.iter().map(|st| PlacedStroke {
                    stroke: st.transformed(&to_road),
                    item,
                }));
        }
        out
    }

    /// Summed area of every stroke's outline (m²; overlaps count twice, as
    /// they are painted twice).
    pub fn painted_area_m2(&self) -> f64 {
        self.strokes
            .iter()
            .map(|ps| {
                let st = &ps.stroke;
                let len = st.left.length().max(st.right.length());
                let k = ((len / OUTLINE_STEP_M).ceil() as usize).max(1) + 1;
                let pts = st.outline(k);
                let n = pts.len();
                (0..n)
                    .map(|i| {
                        let (a, b) = (pts[i], pts[(i + 1) % n]);
                        a.x * b.y - b.x * a.y
                    })
                    .sum::<f64>()
                    .abs()
                    / 2.0
            })
            .sum()
    }

    /// Who stroke `i` belongs to.
    pub fn owner(&self, stroke: usize) -> &Owner {
        &self.items[self.strokes[stroke].item].owner
    }

    /// The height of the letter a stroke belongs to (m); `None` for a
    /// symbol's or a shape's.
    pub fn letter_height_m(&self, stroke: usize) -> Option<f64> {
        self.items[self.strokes[stroke].item].letter_height_m
    }

    /// The job's `layout.glyphs`: each item's stroke outlines (edges sampled
    /// at most `OUTLINE_STEP_M` apart), the items in order.
    pub fn outlines(&self) -> Vec<PlacedGlyph> {
        let mut glyphs: Vec<PlacedGlyph> = self
            .items
            .iter()
            .map(|it| PlacedGlyph {
                char: it.owner.label.clone(),
                line: it.owner.line,
                strokes: vec![],
            })
            .collect();
        for ps in &self.strokes {
            let st = &ps.stroke;
            let len = st.left.length().max(st.right.length());
            let k = ((len / OUTLINE_STEP_M).ceil() as usize).max(1) + 1;
            let pts = |e: &basr_geom::Edge| e.sample(k).iter().map(|p| [p.x, p.y]).collect();
            glyphs[ps.item].strokes.push(OutlineStroke {
                left: pts(&st.left),
                right: pts(&st.right),
            });
        }
        glyphs
    }
}

pub use basr_shape::layout::glyph_box;
