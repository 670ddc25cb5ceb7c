//! Marking scenes (SPEC §5): a marking file with `[[item]]` entries, each a
//! word, a library symbol or an outline file placed and turned in the lane.
//!
//! This module only reads and checks the file; `layout::place` puts the
//! items' strokes on the road and `layout::rules` applies the MUTCD checks.

use std::path::PathBuf;

use serde::Deserialize;

use super::{
    LayoutError, Overrides, DEFAULT_LANE_WIDTH_M, DEFAULT_LETTER_HEIGHT_M, LETTER_HEIGHT_RANGE_M,
    MAX_LANE_WIDTH_M, MAX_OFFSET_M, M_PER_FT,
};

/// Largest item rotation magnitude, degrees: a full turn either way.
const MAX_ROTATE_DEG: f64 = 360.0;
/// Range of a symbol's `scale`. MUTCD 11th §3B.20 ¶09–11 (R8, R9): markings
/// scale to the facility and may be 25 % smaller below 25 mph; assumed: up to
/// twice the standard size (a 16 ft arrow) before it outgrows the arm.
pub const SYMBOL_SCALE_RANGE: (f64, f64) = (0.5, 2.0);
/// Range of a shape's `height_m` / `width_m`. assumed: as letters (0.3–10 m).
const SHAPE_SIZE_RANGE_M: (f64, f64) = LETTER_HEIGHT_RANGE_M;

/// What an item paints.
#[derive(Clone, Debug, PartialEq)]
pub enum ItemKind {
    /// One line of text (one word), letters of the font.
    Word { text: String, letter_height_m: f64 },
    /// A symbol of the library at `scale` × its standard size.
    Symbol { name: String, scale: f64 },
    /// A filled outline from an SVG or DXF file (the shapes issue; resolved
    /// against the marking file's folder), sized by height or width.
    Shape { path: PathBuf, size: ShapeSize },
}

/// How a shape is sized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeSize {
    HeightM(f64),
    WidthM(f64),
}

/// One placed item of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    pub kind: ItemKind,
    /// Road-frame point of the centre of the item's near edge (SPEC §5).
    pub at_m: [f64; 2],
    /// Counter-clockwise turn about `at_m`, radians.
    pub rotate_rad: f64,
}

impl Item {
    /// "symbol stop-line", "word STOP", "shape logo.svg".
    pub fn label(&self) -> String {
        match &self.kind {
            ItemKind::Word { text, .. } => format!("word {text}"),
            ItemKind::Symbol { name, .. } => format!("symbol {name}"),
            ItemKind::Shape { path, .. } => format!("shape {}", path.display()),
        }
    }
}

/// A scene: its items (file order), the lane and the site's speed.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub name: Option<String>,
    pub items: Vec<Item>,
    pub lane_width_m: f64,
    /// Letter height of word items that give none.
    pub letter_height_m: f64,
    /// Operating speed below 25 mph: MUTCD 11th §3B.20 ¶11 (R9) allows 25 %
    /// smaller words, symbols and arrows.
    pub low_speed: bool,
    /// The lane is a mandatory turn lane (R11, R13 checks).
    pub turn_lane: bool,
    /// The road surface the file describes (`[road]`); flat by default.
    pub road: basr_job::Road,
}

impl Scene {
    /// The job's `message`: items' words and symbol names in file order.
    pub fn message(&self) -> String {
        self.items
            .iter()
            .map(|i| match &i.kind {
                ItemKind::Word { text, .. } => text.clone(),
                ItemKind::Symbol { name, .. } => format!("[{name}]"),
                // As `compile --shape` names it: the file's stem.
                ItemKind::Shape { path, .. } => format!("[{}]", crate::label_of(path)),
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// A file name stem for the job.
    pub fn file_stem(&self) -> String {
        self.message()
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect::<String>()
            .split('_')
            .filter(|w| !w.is_empty())
            .collect::<Vec<_>>()
            .join("_")
    }

    /// One library symbol alone, centred in the lane at the anchor
    /// (`basr compile --symbol NAME`, SPEC §1).
    pub fn single_symbol(name: &str, o: &Overrides) -> Result<Scene, LayoutError> {
        let s = Scene {
            name: None,
            items: vec![Item {
                kind: ItemKind::Symbol {
                    name: name.to_string(),
                    scale: 1.0,
                },
                at_m: [0.0, 0.0],
                rotate_rad: 0.0,
            }],
            lane_width_m: o.lane_width_m.unwrap_or(DEFAULT_LANE_WIDTH_M),
            letter_height_m: o.letter_height_m.unwrap_or(DEFAULT_LETTER_HEIGHT_M),
            low_speed: o.low_speed,
            turn_lane: false,
            road: basr_job::Road::default(),
        };
        check_lane(s.lane_width_m).map_err(|e| LayoutError::Marking {
            origin: "--lane-width".into(),
            message: e.to_string(),
        })?;
        Ok(s)
    }

    /// Parse a scene file (one with `[[item]]` tables); `origin` names it.
    pub fn from_toml(text: &str, origin: &str, o: &Overrides) -> Result<Scene, LayoutError> {
        let err = |message: String| LayoutError::Marking {
            origin: origin.to_string(),
            message,
        };
        let file: SceneFileToml = super::parse_marking(text).map_err(|e| err(e.to_string()))?;
        let road = super::RoadToml::road(file.road).map_err(err)?;
        let m = file.marking.unwrap_or_default();
        if m.lines.is_some() {
            return Err(err(
                "a scene's words are `[[item]]` entries with `word = \"STOP\"`; move the \
                 `lines` into items (one word per item) or drop the [[item]] tables"
                    .into(),
            ));
        }
        let h_file =
            height(m.letter_height_m, m.letter_height_ft).map_err(|e| err(e.to_string()))?;
        let lane = o
            .lane_width_m
            .or(m.lane_width_m)
            .unwrap_or(DEFAULT_LANE_WIDTH_M);
        check_lane(lane).map_err(|e| err(e.to_string()))?;
        let default_h = o
            .letter_height_m
            .or(h_file)
            .unwrap_or(DEFAULT_LETTER_HEIGHT_M);
        if file.item.is_empty() {
            return Err(err("the scene has no [[item]]".into()));
        }
        let mut items = vec![];
        for (i, it) in file.item.iter().enumerate() {
            let item = item(it, default_h, o).map_err(|m| err(format!("item {}: {m}", i + 1)))?;
            items.push(item);
        }
        Ok(Scene {
            name: m.name,
            items,
            lane_width_m: lane,
            letter_height_m: default_h,
            low_speed: o.low_speed || m.low_speed.unwrap_or(false),
            turn_lane: m.turn_lane.unwrap_or(false),
            road,
        })
    }
}

/// Whether a marking file's text is a scene (has `[[item]]` tables).
pub fn is_scene(text: &str) -> bool {
    text.lines().any(|l| l.trim() == "[[item]]")
}

/// A scene's setting or item that cannot be laid out: what is wrong and
/// what to write (the file's origin and item number are added by
/// [`Scene::from_toml`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("lane width {} m must be above 0 and at most {MAX_LANE_WIDTH_M} m (a marking is laid in one lane, 3.66 m by default)", basr_io::show_num(*.0))]
    LaneWidth(f64),
    #[error("give letter_height_m or letter_height_ft, not both")]
    BothHeights,
    #[error("letter height {} m is outside {}..{} m: road letters are 1.8–2.4 m (6–8 ft); give metres in letter_height_m or feet in letter_height_ft", basr_io::show_num(*.0), LETTER_HEIGHT_RANGE_M.0, LETTER_HEIGHT_RANGE_M.1)]
    LetterHeight(f64),
    #[error("an item is exactly one of `word = \"STOP\"`, `symbol = \"arrow-left\"` or `shape = \"logo.svg\"`")]
    NotOneKind,
    #[error("needs `at_m = [x, y]`: the centre of its near edge in the lane")]
    NoAt,
    #[error("at_m holds {0} numbers; give two, `at_m = [x, y]` (m across and along the lane: items lie on the road)")]
    AtCount(usize),
    #[error("at_m = [{}, {}] must be finite and within {MAX_OFFSET_M} m of the anchor", basr_io::show_num(.0[0]), basr_io::show_num(.0[1]))]
    At([f64; 2]),
    #[error("rotate_deg = {} must be within ±{MAX_ROTATE_DEG}", basr_io::show_num(*.0))]
    Rotate(f64),
    #[error("{keys} belong to a {what} item")]
    Misplaced {
        keys: &'static str,
        what: &'static str,
    },
    #[error("word = {0:?}: one word of the letters A–Z and digits (one item per line)")]
    Word(String),
    #[error("scale = {} is outside {}..{} (1 is the library's standard size)", basr_io::show_num(*.0), SYMBOL_SCALE_RANGE.0, SYMBOL_SCALE_RANGE.1)]
    Scale(f64),
    #[error("a shape needs exactly one of `height_m` or `width_m`")]
    ShapeSize,
    #[error("a shape's size {} m is outside {}..{} m", basr_io::show_num(*.0), SHAPE_SIZE_RANGE_M.0, SHAPE_SIZE_RANGE_M.1)]
    ShapeSizeRange(f64),
}

fn check_lane(lane: f64) -> Result<(), SceneError> {
    if !(lane.is_finite() && lane > 0.0 && lane <= MAX_LANE_WIDTH_M) {
        return Err(SceneError::LaneWidth(lane));
    }
    Ok(())
}

fn height(m: Option<f64>, ft: Option<f64>) -> Result<Option<f64>, SceneError> {
    let h = match (m, ft) {
        (Some(_), Some(_)) => return Err(SceneError::BothHeights),
        (Some(m), None) => Some(m),
        (None, Some(ft)) => Some(ft * M_PER_FT),
        (None, None) => None,
    };
    if let Some(h) = h {
        let (lo, hi) = LETTER_HEIGHT_RANGE_M;
        if !(h.is_finite() && (lo..=hi).contains(&h)) {
            return Err(SceneError::LetterHeight(h));
        }
    }
    Ok(h)
}

fn item(t: &ItemToml, default_h: f64, o: &Overrides) -> Result<Item, SceneError> {
    let given = [t.word.is_some(), t.symbol.is_some(), t.shape.is_some()];
    if given.iter().filter(|&&g| g).count() != 1 {
        return Err(SceneError::NotOneKind);
    }
    let at = t.at_m.as_deref().ok_or(SceneError::NoAt)?;
    let at: [f64; 2] = at.try_into().map_err(|_| SceneError::AtCount(at.len()))?;
    if at.iter().any(|v| !v.is_finite() || v.abs() > MAX_OFFSET_M) {
        return Err(SceneError::At(at));
    }
    let rot = t.rotate_deg.unwrap_or(0.0);
    if !(rot.is_finite() && rot.abs() <= MAX_ROTATE_DEG) {
        return Err(SceneError::Rotate(rot));
    }
    let only = |what: &'static str, ok: bool, keys: &'static str| -> Result<(), SceneError> {
        if ok {
            Ok(())
        } else {
            Err(SceneError::Misplaced { keys, what })
        }
    };
    let has_h = t.letter_height_m.is_some() || t.letter_height_ft.is_some();
    let has_size = t.height_m.is_some() || t.width_m.is_some();
    let kind = if let Some(w) = &t.word {
        only("shape", !has_size, "`height_m` and `width_m`")?;
        only("symbol", t.scale.is_none(), "`scale`")?;
        let text = w.trim().to_ascii_uppercase();
        if text.is_empty() || !text.chars().all(|c| c.is_ascii_alphanumeric()) {
            return Err(SceneError::Word(w.clone()));
        }
        let h = o
            .letter_height_m
            .or(height(t.letter_height_m, t.letter_height_ft)?)
            .unwrap_or(default_h);
        ItemKind::Word {
            text,
            letter_height_m: h,
        }
    } else if let Some(name) = &t.symbol {
        only("word", !has_h, "`letter_height_m` and `letter_height_ft`")?;
        only("shape", !has_size, "`height_m` and `width_m`")?;
        let scale = t.scale.unwrap_or(1.0);
        let (lo, hi) = SYMBOL_SCALE_RANGE;
        if !(scale.is_finite() && (lo..=hi).contains(&scale)) {
            return Err(SceneError::Scale(scale));
        }
        ItemKind::Symbol {
            name: name.clone(),
            scale,
        }
    } else {
        only("word", !has_h, "`letter_height_m` and `letter_height_ft`")?;
        only("symbol", t.scale.is_none(), "`scale`")?;
        let size = match (t.height_m, t.width_m) {
            (Some(h), None) => ShapeSize::HeightM(h),
            (None, Some(w)) => ShapeSize::WidthM(w),
            _ => return Err(SceneError::ShapeSize),
        };
        let v = match size {
            ShapeSize::HeightM(v) | ShapeSize::WidthM(v) => v,
        };
        let (lo, hi) = SHAPE_SIZE_RANGE_M;
        if !(v.is_finite() && (lo..=hi).contains(&v)) {
            return Err(SceneError::ShapeSizeRange(v));
        }
        ItemKind::Shape {
            path: PathBuf::from(t.shape.clone().unwrap_or_default()),
            size,
        }
    };
    Ok(Item {
        kind,
        at_m: at,
        rotate_rad: rot.to_radians(),
    })
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFileToml {
    marking: Option<SceneMarkingToml>,
    road: Option<super::RoadToml>,
    #[serde(default)]
    item: Vec<ItemToml>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneMarkingToml {
    name: Option<String>,
    /// Refused with a message: a scene's words are items.
    lines: Option<toml::Value>,
    lane_width_m: Option<f64>,
    letter_height_m: Option<f64>,
    letter_height_ft: Option<f64>,
    low_speed: Option<bool>,
    turn_lane: Option<bool>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ItemToml {
    word: Option<String>,
    symbol: Option<String>,
    shape: Option<String>,
    /// Read as a list so a third number is refused, not dropped: the TOML
    /// reader filled `[f64; 2]` from `[0, 0, 5]` (issue 31, R13).
    at_m: Option<Vec<f64>>,
    rotate_deg: Option<f64>,
    letter_height_m: Option<f64>,
    letter_height_ft: Option<f64>,
    scale: Option<f64>,
    height_m: Option<f64>,
    width_m: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(t: &str) -> Result<Scene, LayoutError> {
        Scene::from_toml(t, "s.toml", &Overrides::default())
    }

    #[test]
    fn items_parse_with_units_and_defaults() {
        let s = parse(
            "[marking]\nlane_width_m = 3.6\n[[item]]\nsymbol = \"stop-line\"\nat_m = [0, 0]\n\
             [[item]]\nword = \"stop\"\nat_m = [0.0, 2.4]\nletter_height_ft = 8\nrotate_deg = 90\n\
             [[item]]\nshape = \"logo.svg\"\nat_m = [0, 12]\nheight_m = 2.0\n",
        )
        .unwrap();
        assert_eq!(s.lane_width_m, 3.6);
        assert_eq!(s.items.len(), 3);
        match &s.items[1].kind {
            ItemKind::Word {
                text,
                letter_height_m,
            } => {
                assert_eq!(text, "STOP");
                assert!((letter_height_m - 2.4384).abs() < 1e-12);
            }
            k => panic!("{k:?}"),
        }
        assert!((s.items[1].rotate_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(matches!(
            s.items[2].kind,
            ItemKind::Shape {
                size: ShapeSize::HeightM(_),
                ..
            }
        ));
        assert_eq!(s.message(), "[stop-line]\nSTOP\n[logo]");
    }

    #[test]
    fn bad_items_say_which_and_why() {
        let e = parse("[[item]]\nsymbol = \"x\"\nword = \"A\"\nat_m = [0, 0]\n").unwrap_err();
        assert!(
            e.to_string().contains("item 1: an item is exactly one of"),
            "{e}"
        );
        let e = parse("[[item]]\nsymbol = \"x\"\n").unwrap_err();
        assert!(e.to_string().contains("needs `at_m"), "{e}");
        let e = parse("[[item]]\nword = \"A\"\nat_m = [0, 0]\nscale = 2\n").unwrap_err();
        assert!(e.to_string().contains("`scale` belong to a symbol"), "{e}");
        let e = parse("[[item]]\nshape = \"a.svg\"\nat_m = [0, 0]\n").unwrap_err();
        assert!(e.to_string().contains("exactly one of `height_m`"), "{e}");
        let e = parse("[[item]]\nword = \"A\"\nat_m = [0, 0]\nfoo = 1\n").unwrap_err();
        assert!(e.to_string().contains("line 4, column 1"), "{e}");
        let e = parse("[marking]\nlines = [\"A\"]\n[[item]]\nword = \"A\"\nat_m = [0, 0]\n")
            .unwrap_err();
        assert!(e.to_string().contains("move the `lines` into items"), "{e}");
        let e = parse("[[item]]\nsymbol = \"x\"\nat_m = [0, 0]\nscale = 9\n").unwrap_err();
        assert!(e.to_string().contains("outside 0.5..2"), "{e}");
    }
}
