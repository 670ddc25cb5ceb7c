//! Message or marking file → glyphs placed in the road frame (SPEC §2).
//!
//! Rules (sources in the comments beside each constant):
//! - letters sit on the seed's 4 × 25 grid, scaled by `height / 25` in both
//!   axes (square units, as 001 app. A scales x and y by `letterlength/25`);
//! - a letter's "up" is +y, the direction of traffic; one word per line, the
//!   first word nearest the approaching driver (smallest y);
//! - each line is centred on the lane (x = 0 at the anchor);
//! - clear space between lines at least 4× and at most 10× the letter height
//!   (MUTCD §3B.20: "at least four times the height of the characters …
//!   not more than ten times"); below 4× is an error, above 10× a warning;
//! - letters are upper case; lower case is accepted and read as upper case
//!   (the standard pavement alphabet has capitals only, and a crew typing
//!   `stop` means STOP).

use serde::{Deserialize, Serialize};

pub mod lengths;
pub mod place;
pub mod rules;
pub mod scene;

pub use place::{
    glyph_box, lay_marking, lay_scene, lay_scene_with, Laid, PlacedMark, ShapeImport,
    ShapeItemError, ShapeStrokes,
};
pub use scene::{is_scene, Item, ItemKind, Scene, ShapeSize};

/// Letter height when none is given (SPEC §4: 8 ft).
pub const DEFAULT_LETTER_HEIGHT_M: f64 = 2.44;
/// Lane width when none is given (SPEC §4: 12 ft).
pub const DEFAULT_LANE_WIDTH_M: f64 = 3.66;
/// Height of the letter grid in grid units (001 §2.1: 25 units tall).
pub const GRID_HEIGHT_UNITS: f64 = 25.0;
/// Width of one letter's grid in grid units (001 §2.1: 4 units wide).
pub const GRID_WIDTH_UNITS: f64 = 4.0;
/// Clear space between adjacent letters' grids, in grid units. The FHWA
/// Standard Alphabets (1977, pavement markings section; SHS 2004 ch. 6)
/// give letter-to-letter distances in spacing charts that are not in our
/// sources; assumed: half a letter grid (2 units, 0.195 m at 8 ft), which
/// keeps the longest shipped word (SCHOOL, 34 units = 3.32 m) inside a
/// 3.66 m lane, as the elongated pavement letters are meant to.
pub const DEFAULT_LETTER_SPACING_UNITS: f64 = 2.0;
/// Minimum clear space between lines, in letter heights (MUTCD §3B.20).
pub const MIN_LINE_GAP_HEIGHTS: f64 = 4.0;
/// Above this clear space between lines, in letter heights, warn (MUTCD §3B.20).
pub const MAX_LINE_GAP_HEIGHTS: f64 = 10.0;

/// Most letters one job takes. MUTCD §3B.20 advises word messages of at most
/// three lines; assumed: 200 letters (twice the largest benchmark, 100) keeps
/// a job's planning to minutes and its file to about 200 MB (some 1 700
/// setpoints of 475 bytes per letter), so a pasted paragraph is refused at
/// once instead of exhausting memory.
pub const MAX_LETTERS: usize = 200;

/// Largest line gap or anchor offset, m. Assumed: one marking is laid at one
/// site, within a kilometre; far beyond that the letters' curves lose their
/// millimetres to round-off (a line gap of 10³⁰⁰ m overflowed the planner).
pub const MAX_OFFSET_M: f64 = 1000.0;

/// Range of letter heights, m. Assumed bounds for sanity, not style: MUTCD
/// pavement words are 6–8 ft (1.8–2.4 m) and elongated symbols up to about
/// 24 ft; below 0.3 m a one-unit stroke (12 mm) is a fraction of the fan's
/// narrowest line, and above 10 m a letter outgrows any arm (BASR reaches
/// 5.36 m). Outside, a number is a typo (`--letter-height 244` for cm).
pub const LETTER_HEIGHT_RANGE_M: (f64, f64) = (0.3, 10.0);

/// Widest lane, m. Assumed: a marking is laid in one lane (3.66 m default,
/// 12 ft; MUTCD lanes are 2.7–4.6 m); 30 m spans a whole multi-lane approach.
/// Beyond it a number is a typo; unbounded (1e9 m) the station search grew to
/// 14 GB.
pub const MAX_LANE_WIDTH_M: f64 = 30.0;

/// [`LayoutError::TooWide`]'s message: the word's own width, and where
/// it is anchored off the centre, what that anchor leaves of the lane (a
/// 2.147 m word anchored 1 m off centre was once called 4.147 m wide); the
/// lane it needs and the letter height at which it fits this one, so the
/// crew chooses with figures (smaller letters can paint less evenly: the
/// job's verdict then says so).
fn too_wide(word: &str, width_m: f64, anchor_x_m: f64, lane_m: f64, fits: Option<f64>) -> String {
    use basr_io::show_num;
    let need = width_m + 2.0 * anchor_x_m.abs();
    let smaller = fits.map_or(String::new(), |h| {
        // Letters that small are not MUTCD word letters: say so rather
        // than suggest them as if they were a fix.
        let low = rules::MIN_LETTER_HEIGHT_M * rules::LOW_SPEED_FACTOR;
        let below = if h < low * (1.0 - 1e-9) {
            "; smaller than MUTCD allows for word letters: 6 ft, 4.5 ft under 25 mph"
        } else if h < rules::MIN_LETTER_HEIGHT_M * (1.0 - 1e-9) {
            "; under MUTCD's 6 ft, allowed only under 25 mph with --low-speed"
        } else {
            ""
        };
        format!(
            ", letters at most {} m ({:.1} ft) tall (--letter-height{below})",
            show_num((h * 1000.0).floor() / 1000.0),
            (h / 0.3048 * 10.0).floor() / 10.0
        )
    });
    let fix = format!(
        "use a lane at least {} m wide (--lane-width; a two-lane word spans both lanes){smaller}, \
         or a shorter word",
        show_num((need * 1000.0).ceil() / 1000.0)
    );
    if anchor_x_m == 0.0 {
        let (w, l) = basr_io::show_apart(width_m, lane_m);
        format!("{word:?} is {w} m wide but the lane is {l} m: {fix}")
    } else {
        let room = (lane_m - 2.0 * anchor_x_m.abs()).max(0.0);
        let (w, r) = basr_io::show_apart(width_m, room);
        format!(
            "{word:?} is {w} m wide but anchored {} m off the centre of the {} m lane \
             (anchor_x_m) it has {r} m: move the anchor towards the centre, or {fix}",
            show_num(anchor_x_m),
            show_num(lane_m)
        )
    }
}

/// Errors of layout and of marking files.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum LayoutError {
    #[error("the message is empty: give at least one letter, e.g. `basr compile STOP`")]
    Empty,
    #[error(
        "the message has {letters} letters; one job takes at most {MAX_LETTERS} \
         (MUTCD §3B.20 advises at most three lines): split it into several jobs"
    )]
    TooLong { letters: usize },
    #[error(
        "{field} {} m is more than {MAX_OFFSET_M} m from the origin: a marking is laid at one site; \
         split it into several jobs", basr_io::show_num(*value)
    )]
    TooFar { field: String, value: f64 },
    #[error(
        "unsupported character {} at position {position} of {message:?}: messages take \
         the letters A–Z (lower case is read as upper case), the digits 0–9 and spaces",
        crate::chars::describe(*ch)
    )]
    Unsupported {
        ch: char,
        position: usize,
        message: String,
    },
    #[error(
        "the font has no glyph for {ch:?} (position {position} of {message:?}); \
         `basr glyphs` lists what it has"
    )]
    NoGlyph {
        ch: char,
        position: usize,
        message: String,
    },
    #[error("{}", too_wide(word, *width_m, *anchor_x_m, *lane_m, *fits_at_height_m))]
    TooWide {
        word: String,
        /// The word's own width (m).
        width_m: f64,
        /// How far off the lane's centre it is anchored (m).
        anchor_x_m: f64,
        lane_m: f64,
        /// The largest letter height at which the word fits where it is
        /// anchored (m); `None` where the letter spacing alone overfills it.
        fits_at_height_m: Option<f64>,
    },
    #[error(
        "clear space between lines is {} m but must be at least {} m \
         ({MIN_LINE_GAP_HEIGHTS}× the letter height, MUTCD §3B.20): raise --line-gap",
        basr_io::show_apart(*gap_m, *min_m).0,
        basr_io::show_apart(*gap_m, *min_m).1
    )]
    GapTooSmall { gap_m: f64, min_m: f64 },
    #[error("{field} {} m is outside {min}..{max} m: {why}", basr_io::show_num(*value))]
    OutOfRange {
        field: String,
        value: f64,
        min: f64,
        max: f64,
        why: &'static str,
    },
    #[error("{field} must be {need}, got {} m", basr_io::show_num(*value))]
    BadNumber {
        field: String,
        need: &'static str,
        value: f64,
    },
    #[error("{origin}: {message}")]
    Marking { origin: String, message: String },
    #[error(
        "item {item}: no symbol {name:?} in the library; nearest: {nearest} \
         (`basr symbols` lists them all)"
    )]
    UnknownSymbol {
        item: usize,
        name: String,
        nearest: String,
    },
    #[error(
        "item {item} ({label}) reaches x = {x_m:+.3} m, {by_m:.3} m outside the {lane_m:.3} m \
         lane{}: move it (at_m), turn it, or widen the lane (lane_width_m); MUTCD 11th §3B.20 \
         ¶08 (R7): a marking is at most one lane wide, except SCHOOL",
        if *school { " and the half lane SCHOOL may take on either side" } else { "" }
    )]
    OutsideLane {
        item: usize,
        label: String,
        x_m: f64,
        by_m: f64,
        lane_m: f64,
        school: bool,
    },
    #[error(
        "{a} and {b} overlap by about {:.0} cm²: items may abut but must not paint the same \
         area twice; move one of them (at_m)", area_m2 * 1e4
    )]
    Overlap { a: String, b: String, area_m2: f64 },
    #[error("{message}{}", if *more > 0 { format!(" (and {more} more)") } else { String::new() })]
    Rule { message: String, more: usize },
    #[error("item {item}: shape {path:?}: {message}")]
    Shape {
        item: usize,
        path: String,
        message: String,
    },
}

/// The settings of one marking: its lines and how to lay them out.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Marking {
    /// Lines, first nearest the approaching driver; each one word.
    pub lines: Vec<String>,
    pub letter_height_m: f64,
    /// Clear space between adjacent letters of a word.
    pub letter_spacing_m: f64,
    pub lane_width_m: f64,
    /// Clear space between consecutive lines.
    pub line_gap_m: f64,
    /// Road-frame position of the anchor relative to the lane centre at the
    /// near edge of the first line (SPEC §2); (0, 0) unless a file moves it.
    pub anchor_x_m: f64,
    pub anchor_y_m: f64,
    /// The road surface the file describes (`[road]`); flat by default.
    #[serde(default)]
    pub road: basr_job::Road,
}

/// A marking file's `[road]` table (docs/site.md): the surface's cross
/// slope in percent, falling to the driver's right, and an optional crown
/// line where it changes sign. Unknown keys are errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RoadToml {
    cross_slope_pct: Option<f64>,
    crown_x_m: Option<f64>,
}

impl RoadToml {
    /// The surface described, or what is wrong with the table.
    pub(crate) fn road(table: Option<RoadToml>) -> Result<basr_job::Road, String> {
        let Some(t) = table else {
            return Ok(basr_job::Road::default());
        };
        let Some(pct) = t.cross_slope_pct else {
            return Err(
                "[road] needs cross_slope_pct (the surface's fall to the driver's \
                        right, in percent: cross_slope_pct = 2.0)"
                    .into(),
            );
        };
        let road = basr_job::Road {
            cross_slope: pct / 100.0,
            crown_x_m: t.crown_x_m,
            planes: vec![],
        };
        match road.problem(0) {
            Some(p) => Err(format!("[road]: {p}")),
            None => Ok(road),
        }
    }
}

/// Optional overrides of a marking's settings (the compile command line).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    pub letter_height_m: Option<f64>,
    pub lane_width_m: Option<f64>,
    pub line_gap_m: Option<f64>,
    /// `--low-speed`: operating speed below 25 mph (MUTCD 11th §3B.20 ¶11).
    pub low_speed: bool,
}

/// The `[marking]` table of a marking file. Unknown keys are errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MarkingToml {
    /// A name for people, e.g. "STOP AHEAD".
    #[allow(dead_code)] // documentation in the file; the lines are what is painted
    name: Option<String>,
    lines: Vec<String>,
    letter_height_m: Option<f64>,
    letter_height_ft: Option<f64>,
    letter_spacing_m: Option<f64>,
    lane_width_m: Option<f64>,
    line_gap_m: Option<f64>,
    anchor_x_m: Option<f64>,
    anchor_y_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MarkingFileToml {
    marking: MarkingToml,
    road: Option<RoadToml>,
}

/// Metres per foot (exact by definition).
const M_PER_FT: f64 = 0.3048;

impl Marking {
    /// Default settings for a message typed on the command line: words
    /// (separated by spaces or newlines) become lines.
    pub fn from_message(message: &str, o: &Overrides) -> Result<Marking, LayoutError> {
        let lines: Vec<String> = message
            .split([' ', '\n'])
            .filter(|w| !w.is_empty())
            // Lower case is painted as upper case, so the job says what is
            // painted: `compile stop` and `compile STOP` give one job.
            .map(|w| w.to_ascii_uppercase())
            .collect();
        let h = o.letter_height_m.unwrap_or(DEFAULT_LETTER_HEIGHT_M);
        let m = Marking {
            lines,
            letter_height_m: h,
            letter_spacing_m: DEFAULT_LETTER_SPACING_UNITS * h / GRID_HEIGHT_UNITS,
            lane_width_m: o.lane_width_m.unwrap_or(DEFAULT_LANE_WIDTH_M),
            line_gap_m: o.line_gap_m.unwrap_or(MIN_LINE_GAP_HEIGHTS * h),
            anchor_x_m: 0.0,
            anchor_y_m: 0.0,
            road: basr_job::Road::default(),
        };
        m.validate_message(message)?;
        Ok(m)
    }

    /// Parse a marking file (TOML with one `[marking]` table); `origin`
    /// names it in messages. Command-line overrides win over the file.
    pub fn from_toml(text: &str, origin: &str, o: &Overrides) -> Result<Marking, LayoutError> {
        let err = |message: String| LayoutError::Marking {
            origin: origin.to_string(),
            message,
        };
        const SHAPE: &str = "a marking file is a [marking] table with at least \
                             lines = [\"STOP\"]; see markings/stop.toml";
        if text.trim().is_empty() {
            return Err(err(format!("the file is empty: {SHAPE}")));
        }
        let file: MarkingFileToml = parse_marking(text).map_err(|m| {
            err(if m.is_missing_field() {
                format!("{m}: {SHAPE}")
            } else {
                m.to_string()
            })
        })?;
        let road = RoadToml::road(file.road).map_err(err)?;
        let t = file.marking;
        let h_file = match (t.letter_height_m, t.letter_height_ft) {
            (Some(_), Some(_)) => {
                return Err(err(
                    "give letter_height_m or letter_height_ft, not both".into()
                ))
            }
            (Some(m), None) => Some(m),
            (None, Some(ft)) => Some(ft * M_PER_FT),
            (None, None) => None,
        };
        let h = o
            .letter_height_m
            .or(h_file)
            .unwrap_or(DEFAULT_LETTER_HEIGHT_M);
        let lines: Vec<String> = t
            .lines
            .iter()
            .map(|l| l.trim().to_ascii_uppercase())
            .collect();
        for (i, l) in lines.iter().enumerate() {
            // A line break inside one line: `check` passed it and `compile`
            // refused it (issue 31, D12); both read the file here.
            if l.contains(|c: char| c.is_whitespace() && c != ' ') {
                return Err(err(format!(
                    "lines[{i}] = {l:?} holds a line break or tab; give each line its own \
                     string (lines = [\"ST\", \"OP\"] for two lines)"
                )));
            }
            if l.contains(' ') {
                return Err(err(format!(
                    "lines[{i}] = {l:?} holds several words; put one word per line \
                     (multi-word messages stack one word per line)"
                )));
            }
        }
        let m = Marking {
            lines,
            letter_height_m: h,
            letter_spacing_m: t
                .letter_spacing_m
                .unwrap_or(DEFAULT_LETTER_SPACING_UNITS * h / GRID_HEIGHT_UNITS),
            lane_width_m: o
                .lane_width_m
                .or(t.lane_width_m)
                .unwrap_or(DEFAULT_LANE_WIDTH_M),
            line_gap_m: o
                .line_gap_m
                .or(t.line_gap_m)
                .unwrap_or(MIN_LINE_GAP_HEIGHTS * h),
            anchor_x_m: t.anchor_x_m.unwrap_or(0.0),
            anchor_y_m: t.anchor_y_m.unwrap_or(0.0),
            road,
        };
        let joined = m.message();
        m.validate_message(&joined)
            .map_err(|e| err(e.to_string()))?;
        Ok(m)
    }

    /// The message as one string, lines joined with `\n` (SPEC §3 `message`).
    pub fn message(&self) -> String {
        self.lines.join("\n")
    }

    /// A file name stem for the job: lines joined with `_`.
    pub fn file_stem(&self) -> String {
        self.lines.join("_")
    }

    fn validate_message(&self, message: &str) -> Result<(), LayoutError> {
        for (i, ch) in message.chars().enumerate() {
            if !(ch.is_ascii_alphanumeric() || ch == ' ' || ch == '\n') {
                return Err(LayoutError::Unsupported {
                    ch,
                    position: i + 1,
                    message: message.to_string(),
                });
            }
        }
        let letters = self
            .lines
            .iter()
            .map(|l| l.chars().filter(|c| !c.is_whitespace()).count())
            .sum::<usize>();
        if letters > MAX_LETTERS {
            return Err(LayoutError::TooLong { letters });
        }
        if self.lines.iter().all(|l| l.is_empty()) {
            return Err(LayoutError::Empty);
        }
        // The letter height and lane width first: the line gap is derived
        // from the letter height when not given (1e308 letters once read
        // "line gap must be a finite number").
        for (field, v) in [
            ("letter height", self.letter_height_m),
            ("lane width", self.lane_width_m),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(LayoutError::BadNumber {
                    field: field.into(),
                    need: "a finite number of metres above zero",
                    value: v,
                });
            }
        }
        let (h_min, h_max) = LETTER_HEIGHT_RANGE_M;
        for (field, v, min, max, why) in [
            (
                "letter height",
                self.letter_height_m,
                h_min,
                h_max,
                "road letters are 1.8–2.4 m (6–8 ft); give metres (--letter-height 2.44)",
            ),
            (
                "lane width",
                self.lane_width_m,
                0.0,
                MAX_LANE_WIDTH_M,
                "a marking is laid in one lane (3.66 m, 12 ft, by default); give metres",
            ),
        ] {
            if v < min || v > max {
                return Err(LayoutError::OutOfRange {
                    field: field.into(),
                    value: v,
                    min,
                    max,
                    why,
                });
            }
        }
        if !(self.line_gap_m.is_finite() && self.line_gap_m > 0.0) {
            return Err(LayoutError::BadNumber {
                field: "line gap".into(),
                need: "a finite number of metres above zero",
                value: self.line_gap_m,
            });
        }
        for (field, v) in [
            ("letter spacing", self.letter_spacing_m),
            ("anchor x", self.anchor_x_m),
            ("anchor y", self.anchor_y_m),
        ] {
            if !v.is_finite() || (field == "letter spacing" && v < 0.0) {
                return Err(LayoutError::BadNumber {
                    field: field.into(),
                    need: if field == "letter spacing" {
                        "a finite number of metres, zero or more"
                    } else {
                        "a finite number of metres"
                    },
                    value: v,
                });
            }
        }
        for (field, v) in [
            ("line gap", self.line_gap_m),
            ("anchor x", self.anchor_x_m),
            ("anchor y", self.anchor_y_m),
        ] {
            if v.abs() > MAX_OFFSET_M {
                return Err(LayoutError::TooFar {
                    field: field.into(),
                    value: v,
                });
            }
        }
        Ok(())
    }
}

/// Why a marking file's text does not read as one.
#[derive(Debug, thiserror::Error)]
pub enum MarkingTextError {
    /// A length in feet or with its unit that cannot be read.
    #[error(transparent)]
    Lengths(#[from] lengths::LengthsError),
    /// The TOML does not read as the file's tables: toml's words on one
    /// line, after `line L, column C: ` where toml knows the place.
    #[error("{}{what}", .at.map_or(String::new(), |(l, c)| format!("line {l}, column {c}: ")))]
    Toml {
        at: Option<(usize, usize)>,
        what: String,
    },
}

impl MarkingTextError {
    /// A toml error of `text`, at its line and column when toml gives a span.
    fn toml(text: Option<&str>, e: &toml::de::Error) -> MarkingTextError {
        MarkingTextError::Toml {
            at: text
                .zip(e.span())
                .map(|(text, span)| basr_io::line_col(text, span.start)),
            what: basr_io::one_line(e.message()),
        }
    }

    /// A field the file must have is missing.
    fn is_missing_field(&self) -> bool {
        matches!(self, MarkingTextError::Toml { what, .. } if what.contains("missing field"))
    }
}

/// Read a marking file's TOML as `T`, its lengths in feet and inches or
/// written with their unit (`lane_width_ft = 12`, `at_m = ["0ft", "16ft"]`)
/// first turned into metres ([`lengths::marking_lengths_in_metres`]).
/// A metric file is read from its text, so its errors keep their line.
pub(crate) fn parse_marking<T: serde::de::DeserializeOwned>(
    text: &str,
) -> Result<T, MarkingTextError> {
    match lengths::marking_lengths_in_metres(text)? {
        Some(t) => toml::Value::Table(t)
            .try_into()
            .map_err(|e: toml::de::Error| MarkingTextError::toml(None, &e)),
        None => toml::from_str(text).map_err(|e| MarkingTextError::toml(Some(text), &e)),
    }
}

/// Whether a text that does not parse as TOML was meant as a marking file
/// (it has a `[marking]` table header), so `basr check` reports its syntax
/// error with the line instead of "not a basr file".
pub fn looks_like_marking(text: &str) -> bool {
    text.lines()
        .any(|l| l.trim() == "[marking]" || l.trim() == "[[item]]")
}

/// Every problem of a marking file's text (empty when valid); for `basr
/// check` (a scene's shape items are refused: see [`check_marking_source_with`]).
pub fn check_marking_source(text: &str, origin: &str) -> Vec<String> {
    check_marking_source_with(text, origin, &place::no_shapes)
}

/// [`check_marking_source`] with the importer a scene's shape items need.
pub fn check_marking_source_with(text: &str, origin: &str, shapes: ShapeImport) -> Vec<String> {
    if is_scene(text) {
        let font = crate::font::Font::embedded();
        let lib = crate::font::Library::embedded();
        return match Scene::from_toml(text, origin, &Overrides::default()) {
            Err(e) => vec![e.to_string()],
            Ok(s) => match lay_scene_with(&s, font, lib, shapes) {
                Ok(_) => vec![],
                Err(e) => vec![format!("{origin}: {e}")],
            },
        };
    }
    let m = match Marking::from_toml(text, origin, &Overrides::default()) {
        Ok(m) => m,
        Err(e) => return vec![e.to_string()],
    };
    // Width needs a font; the grid width is the same for every glyph.
    match place(&m, |_| Some(GlyphBox::GRID)) {
        Ok(_) => vec![],
        Err(e) => vec![format!("{origin}: {e}")],
    }
}

/// One letter placed on the road.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLetter {
    pub ch: char,
    /// Line index (0 = nearest the approaching driver).
    pub line: usize,
    /// Road-frame position of the glyph grid's origin (its lower-left corner).
    pub origin_m: [f64; 2],
    /// Metres per grid unit (both axes).
    pub scale_m: f64,
}

impl PlacedLetter {
    /// Glyph-grid point (units) → road frame (m). Letter up is +y (SPEC §2).
    pub fn to_road(&self, u: f64, v: f64) -> [f64; 2] {
        [
            self.origin_m[0] + self.scale_m * u,
            self.origin_m[1] + self.scale_m * v,
        ]
    }
}

/// A laid-out marking: letters in the road frame, and notes for a person.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    pub letters: Vec<PlacedLetter>,
    /// Width of each line (m), for the summary.
    pub line_widths_m: Vec<f64>,
    /// Road-frame y of each line's near edge.
    pub line_y_m: Vec<f64>,
    pub warnings: Vec<String>,
}

/// A glyph's extent in grid units: its advance width and the lowest and
/// highest y its paint reaches (round letters may overshoot 0..25).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlyphBox {
    pub width: f64,
    pub y_min: f64,
    pub y_max: f64,
}

impl GlyphBox {
    /// The full grid cell: 4 wide, 0..25 tall.
    pub const GRID: GlyphBox = GlyphBox {
        width: GRID_WIDTH_UNITS,
        y_min: 0.0,
        y_max: GRID_HEIGHT_UNITS,
    };
}

/// Place the marking's letters. `glyph_box(ch)` gives a glyph's extent
/// (grid units) or `None` when the font has no glyph for `ch`. Lines are
/// spaced so the clear space between the paint of consecutive lines is the
/// line gap; the first line's grid sits on the anchor.
pub fn place(
    m: &Marking,
    glyph_box: impl Fn(char) -> Option<GlyphBox>,
) -> Result<Placed, LayoutError> {
    let scale = m.letter_height_m / GRID_HEIGHT_UNITS; // 001 app. A: scalesize = letterlength/25
    let min_gap = MIN_LINE_GAP_HEIGHTS * m.letter_height_m;
    let mut warnings = vec![];
    if m.lines.len() > 1 {
        // Compare with a small tolerance so a gap given as exactly 4 h passes.
        if m.line_gap_m < min_gap * (1.0 - 1e-9) {
            return Err(LayoutError::GapTooSmall {
                gap_m: m.line_gap_m,
                min_m: min_gap,
            });
        }
        if m.line_gap_m > MAX_LINE_GAP_HEIGHTS * m.letter_height_m {
            warnings.push(format!(
                "clear space between lines {:.2} m is more than {MAX_LINE_GAP_HEIGHTS}× the \
                 letter height ({:.2} m); MUTCD §3B.20 advises against it: drivers read the \
                 lines as separate messages",
                m.line_gap_m,
                MAX_LINE_GAP_HEIGHTS * m.letter_height_m
            ));
        }
    }
    let message = m.message();
    let mut letters = vec![];
    let mut line_widths_m = vec![];
    let mut line_y_m = vec![];
    let mut position = 0usize;
    let mut prev_top: Option<f64> = None;
    for (li, word) in m.lines.iter().enumerate() {
        let mut widths = vec![];
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for ch in word.chars() {
            position += 1;
            let up = ch.to_ascii_uppercase();
            let b = glyph_box(up).ok_or(LayoutError::NoGlyph {
                ch,
                position,
                message: message.clone(),
            })?;
            lo = lo.min(b.y_min);
            hi = hi.max(b.y_max);
            widths.push((up, b.width * scale));
        }
        position += 1; // the separator
        let n = widths.len();
        let width: f64 = widths.iter().map(|(_, w)| w).sum::<f64>()
            + m.letter_spacing_m * n.saturating_sub(1) as f64;
        // The word must fit the lane where it is anchored.
        let reach = width / 2.0 + m.anchor_x_m.abs();
        if reach > m.lane_width_m / 2.0 + 1e-12 {
            // The glyphs scale with the letter height; so does the spacing
            // unless the marking file set it in metres.
            let h = m.letter_height_m;
            let default_spacing = DEFAULT_LETTER_SPACING_UNITS * h / GRID_HEIGHT_UNITS;
            let fixed = if (m.letter_spacing_m - default_spacing).abs() <= 1e-9 * h {
                0.0
            } else {
                m.letter_spacing_m * n.saturating_sub(1) as f64
            };
            let room = m.lane_width_m - 2.0 * m.anchor_x_m.abs() - fixed;
            let glyphs = width - fixed;
            let fits = (room > 0.0 && glyphs > 0.0)
                .then(|| m.letter_height_m * room / glyphs)
                .filter(|h| *h >= LETTER_HEIGHT_RANGE_M.0);
            return Err(LayoutError::TooWide {
                word: word.to_uppercase(),
                width_m: width,
                anchor_x_m: m.anchor_x_m,
                lane_m: m.lane_width_m,
                fits_at_height_m: fits,
            });
        }
        // Grid origin of this line: the first on the anchor, the next ones
        // a clear line gap above the previous line's paint.
        let y = match prev_top {
            None => m.anchor_y_m,
            Some(top) => top + m.line_gap_m - lo * scale,
        };
        prev_top = Some(y + hi * scale);
        let mut x = m.anchor_x_m - width / 2.0;
        for (ch, w) in widths {
            letters.push(PlacedLetter {
                ch,
                line: li,
                origin_m: [x, y],
                scale_m: scale,
            });
            x += w + m.letter_spacing_m;
        }
        line_widths_m.push(width);
        line_y_m.push(y);
    }
    Ok(Placed {
        letters,
        line_widths_m,
        line_y_m,
        warnings,
    })
}

/// The marking files shipped with basr (markings/*.toml), by file stem.
pub const SHIPPED_MARKINGS: &[(&str, &str)] = &[
    ("stop", include_str!("../../../../markings/stop.toml")),
    (
        "stop_ahead",
        include_str!("../../../../markings/stop_ahead.toml"),
    ),
    (
        "school_xing",
        include_str!("../../../../markings/school_xing.toml"),
    ),
    (
        "bus_only",
        include_str!("../../../../markings/bus_only.toml"),
    ),
    (
        "ped_xing",
        include_str!("../../../../markings/ped_xing.toml"),
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(_: char) -> Option<GlyphBox> {
        Some(GlyphBox::GRID)
    }

    #[test]
    fn line_gap_and_anchors_stay_within_a_site() {
        let far = |o: Overrides| Marking::from_message("A B", &o).unwrap_err();
        let e = far(Overrides {
            line_gap_m: Some(1e300),
            ..Overrides::default()
        });
        assert!(matches!(e, LayoutError::TooFar { .. }), "{e}");
        assert!(Marking::from_message(
            "A B",
            &Overrides {
                line_gap_m: Some(MAX_OFFSET_M),
                ..Overrides::default()
            }
        )
        .is_ok());
        let text = "[marking]\nlines = [\"A\"]\nanchor_y_m = -2000.0\n";
        let e = Marking::from_toml(text, "m.toml", &Overrides::default()).unwrap_err();
        assert!(e.to_string().contains("anchor y -2000 m"), "{e}");
    }

    #[test]
    fn letter_count_is_capped_spaces_not_counted() {
        let at_cap = vec!["ABCDE"; MAX_LETTERS / 5].join(" ");
        assert!(Marking::from_message(&at_cap, &Overrides::default()).is_ok());
        let over = format!("{at_cap} A");
        assert_eq!(
            Marking::from_message(&over, &Overrides::default()).unwrap_err(),
            LayoutError::TooLong {
                letters: MAX_LETTERS + 1
            }
        );
        let text = format!("[marking]\nlines = [{}]\n", vec!["\"STOP\""; 51].join(", "));
        let e = Marking::from_toml(&text, "m.toml", &Overrides::default()).unwrap_err();
        assert!(e.to_string().contains("204 letters"), "{e}");
    }

    #[test]
    fn stop_is_centred_and_upright() {
        let m = Marking::from_message("STOP", &Overrides::default()).unwrap();
        let p = place(&m, grid).unwrap();
        assert_eq!(p.letters.len(), 4);
        let s = 2.44 / 25.0;
        // 4 letters of 4 units and 3 gaps of 2 units = 22 units.
        assert!((p.line_widths_m[0] - 22.0 * s).abs() < 1e-12);
        let left = p.letters[0].to_road(0.0, 0.0);
        let right = p.letters[3].to_road(4.0, 25.0);
        assert!((left[0] + right[0]).abs() < 1e-12, "centred on x = 0");
        assert!((left[1]).abs() < 1e-12 && (right[1] - 2.44).abs() < 1e-12);
        assert_eq!(p.letters.iter().map(|l| l.ch).collect::<String>(), "STOP");
    }

    #[test]
    fn first_word_nearest_driver_with_gap() {
        let m = Marking::from_message("stop ahead", &Overrides::default()).unwrap();
        let p = place(&m, grid).unwrap();
        assert_eq!(p.line_y_m.len(), 2);
        assert_eq!(p.letters[0].ch, 'S');
        assert_eq!(p.letters[0].line, 0);
        let clear = p.line_y_m[1] - (p.line_y_m[0] + 2.44);
        assert!(clear >= 4.0 * 2.44 - 1e-9, "gap {clear}");
        assert!(p
            .letters
            .iter()
            .filter(|l| l.line == 1)
            .all(|l| l.origin_m[1] > 2.44));
    }

    #[test]
    fn bad_messages_are_named() {
        let o = Overrides::default();
        assert_eq!(
            Marking::from_message("   ", &o).unwrap_err(),
            LayoutError::Empty
        );
        match Marking::from_message("STO!P", &o).unwrap_err() {
            LayoutError::Unsupported { ch, position, .. } => {
                assert_eq!((ch, position), ('!', 4))
            }
            e => panic!("{e}"),
        }
        let m = Marking::from_message("ABCDEFGHIJKLMNOPQRSTUVWXYZ", &o).unwrap();
        let e = place(&m, grid).unwrap_err();
        assert!(e.to_string().contains("lane is 3.66 m"), "{e}");
        let gap = Overrides {
            line_gap_m: Some(3.0),
            ..o.clone()
        };
        let m = Marking::from_message("STOP AHEAD", &gap).unwrap();
        assert!(matches!(
            place(&m, grid),
            Err(LayoutError::GapTooSmall { .. })
        ));
        let wide = Overrides {
            line_gap_m: Some(30.0),
            ..o
        };
        let m = Marking::from_message("STOP AHEAD", &wide).unwrap();
        assert_eq!(place(&m, grid).unwrap().warnings.len(), 1);
    }

    /// A word too wide is told the height at which it fits: that height
    /// places, a hair more does not; and the lane it would need.
    #[test]
    fn too_wide_names_the_height_that_fits() {
        let at = |h: f64| {
            let o = Overrides {
                letter_height_m: Some(h),
                ..Overrides::default()
            };
            place(&Marking::from_message("SCHOOL", &o).unwrap(), grid)
        };
        let e = at(3.048).unwrap_err();
        let LayoutError::TooWide {
            fits_at_height_m: Some(h),
            width_m,
            ..
        } = e
        else {
            panic!("{e}")
        };
        assert!(h < 3.048 && at(h).is_ok(), "{h}");
        assert!(at(h * 1.001).is_err(), "{h}");
        let text = at(3.048).unwrap_err().to_string();
        assert!(text.contains("letters at most"), "{text}");
        assert!(!text.contains("MUTCD"), "8.9 ft is a MUTCD size: {text}");
        // A lane that fits the word only in letters MUTCD does not allow
        // says so.
        let narrow = |lane: f64| {
            let o = Overrides {
                lane_width_m: Some(lane),
                ..Overrides::default()
            };
            place(&Marking::from_message("SCHOOL", &o).unwrap(), grid)
                .unwrap_err()
                .to_string()
        };
        assert!(
            narrow(1.0).contains("smaller than MUTCD allows"),
            "{}",
            narrow(1.0)
        );
        assert!(
            narrow(2.2).contains("allowed only under 25 mph"),
            "{}",
            narrow(2.2)
        );
        let need = basr_io::show_num((width_m * 1000.0).ceil() / 1000.0);
        assert!(
            text.contains(&format!("a lane at least {need} m wide")),
            "{text}"
        );
    }

    #[test]
    fn missing_glyph_named() {
        let m = Marking::from_message("A7", &Overrides::default()).unwrap();
        let e = place(&m, |c| c.is_ascii_alphabetic().then_some(GlyphBox::GRID)).unwrap_err();
        assert!(
            matches!(
                e,
                LayoutError::NoGlyph {
                    ch: '7',
                    position: 2,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn shipped_markings_are_valid() {
        for (name, text) in SHIPPED_MARKINGS {
            let p = check_marking_source(text, name);
            assert!(p.is_empty(), "{name}: {p:?}");
        }
    }

    #[test]
    fn unknown_key_names_line_and_column() {
        let text = "[marking]\nlines = [\"STOP\"]\nletter_hieght_m = 2.0\n";
        let p = check_marking_source(text, "x.toml");
        assert_eq!(p.len(), 1);
        assert!(p[0].starts_with("x.toml: line 3, column 1"), "{}", p[0]);
        assert!(p[0].contains("letter_hieght_m"), "{}", p[0]);
    }

    #[test]
    fn file_settings_and_overrides() {
        let text =
            "[marking]\nlines = [\"BUS\", \"ONLY\"]\nletter_height_ft = 6.0\nline_gap_m = 10.0\n";
        let m = Marking::from_toml(text, "f", &Overrides::default()).unwrap();
        assert!((m.letter_height_m - 1.8288).abs() < 1e-12);
        assert_eq!(m.line_gap_m, 10.0);
        let o = Overrides {
            letter_height_m: Some(2.0),
            ..Default::default()
        };
        let m = Marking::from_toml(text, "f", &o).unwrap();
        assert_eq!(m.letter_height_m, 2.0);
        assert_eq!(m.message(), "BUS\nONLY");
    }
}
