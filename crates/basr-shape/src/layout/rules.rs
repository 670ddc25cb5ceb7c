//! MUTCD checks on a laid-out message or scene: each finding names its rule
//! and section (shared/MUTCD.md rows R3–R14) and is an error (the layout is
//! refused) or a warning (it goes into the job).
//!
//! Which are errors: what the MUTCD says `shall` (ONLY in a shared lane,
//! R11), what the project already refused (line gaps under 4×, R6), and
//! STOP painted past its stop line. The rest (`should`) are warnings.

use std::fmt;

use super::M_PER_FT;

/// Letters should be at least 6 ft (MUTCD 11th §3B.21 ¶01, R3).
pub const MIN_LETTER_HEIGHT_M: f64 = 6.0 * M_PER_FT;
/// Below 25 mph markings may be 25 % smaller (11th §3B.20 ¶11, R9).
pub const LOW_SPEED_FACTOR: f64 = 0.75;
/// At most three lines to a message (11th §3B.20 ¶06, R4).
pub const MAX_LINES: usize = 3;
/// Clear space between lines: 4× to 10× the letter height (11th §3B.20 ¶07, R6).
pub const LINE_GAP_HEIGHTS: (f64, f64) = (4.0, 10.0);
/// Lane-use arrows 100–300 ft apart (CA MUTCD §3B.23 ¶08, shared/MUTCD.md 2.3).
pub const ARROW_SPACING_M: (f64, f64) = (100.0 * M_PER_FT, 300.0 * M_PER_FT);
/// At least two arrows in a turn lane (11th §3B.23 ¶04, R13).
pub const MIN_TURN_ARROWS: usize = 2;

/// What the rules need of one item: what it is and where it lies along the lane.
#[derive(Clone, Debug, PartialEq)]
pub struct RuleItem {
    pub index: usize,
    /// "item 2 (word STOP)" or "line 1 (STOP)".
    pub label: String,
    pub word: Option<String>,
    pub symbol: Option<String>,
    /// Words only.
    pub letter_height_m: f64,
    /// Symbols only (1 = standard size).
    pub scale: f64,
    /// Lowest and highest road y the item's paint reaches.
    pub y: [f64; 2],
}

/// One rule's verdict on the layout.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    pub error: bool,
    /// "MUTCD 11th §3B.20 ¶06 (R4)".
    pub rule: &'static str,
    pub message: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{}: {}", self.rule, self.message)
    }
}

fn warn(rule: &'static str, message: String) -> Finding {
    Finding {
        error: false,
        rule,
        message,
    }
}

fn error(rule: &'static str, message: String) -> Finding {
    Finding {
        error: true,
        rule,
        message,
    }
}

fn ft(m: f64) -> f64 {
    m / M_PER_FT
}

/// Every finding on `items`. `scene`: the items are scene items (their order
/// in the file is the reading order and their gaps are measured here; a
/// message's own layout keeps both).
pub fn check(items: &[RuleItem], low_speed: bool, turn_lane: bool, scene: bool) -> Vec<Finding> {
    let mut out = vec![];
    let words: Vec<&RuleItem> = items.iter().filter(|i| i.word.is_some()).collect();
    let arrows: Vec<&RuleItem> = items.iter().filter(|i| is_arrow(i)).collect();
    if words.len() > MAX_LINES {
        out.push(warn(
            "MUTCD 11th §3B.20 ¶06 (R4)",
            format!(
                "the message has {} lines; an interrelated message should not exceed {MAX_LINES}",
                words.len()
            ),
        ));
    }
    letter_heights(&words, low_speed, &mut out);
    symbol_scales(items, low_speed, &mut out);
    if scene {
        reading_order(&words, &mut out);
        line_gaps(&words, &mut out);
    }
    let only = words.iter().find(|w| w.word.as_deref() == Some("ONLY"));
    if turn_lane || only.is_some() {
        turn_lane_rules(&arrows, only.copied(), &mut out);
    }
    stop_rules(items, &words, &mut out);
    out
}

fn is_arrow(i: &RuleItem) -> bool {
    i.symbol.as_deref().is_some_and(|s| {
        s.starts_with("arrow-") && s != "arrow-wrong-way" && s != "arrow-lane-reduction"
    })
}

fn letter_heights(words: &[&RuleItem], low_speed: bool, out: &mut Vec<Finding>) {
    let min = if low_speed {
        MIN_LETTER_HEIGHT_M * LOW_SPEED_FACTOR
    } else {
        MIN_LETTER_HEIGHT_M
    };
    for w in words {
        let h = w.letter_height_m;
        if h < min * (1.0 - 1e-9) {
            let why = if low_speed {
                "(6 ft less the 25 % allowed below 25 mph, §3B.20 ¶11)".to_string()
            } else {
                "(below 25 mph, --low-speed, 4.5 ft is allowed, §3B.20 ¶11)".to_string()
            };
            out.push(warn(
                "MUTCD 11th §3B.21 ¶01 (R3)",
                format!(
                    "{}: letters {:.2} m ({:.1} ft) tall are under {:.2} m ({:.1} ft) {why}",
                    w.label,
                    h,
                    ft(h),
                    min,
                    ft(min)
                ),
            ));
        }
    }
}

fn symbol_scales(items: &[RuleItem], low_speed: bool, out: &mut Vec<Finding>) {
    let min = if low_speed { LOW_SPEED_FACTOR } else { 1.0 };
    for i in items.iter().filter(|i| i.symbol.is_some()) {
        if i.scale < min * (1.0 - 1e-9) {
            out.push(warn(
                "MUTCD 11th §3B.20 ¶11 (R9)",
                format!(
                    "{}: scale {} is under {min}: symbols and arrows may be 25 % smaller only \
                     where the operating speed is below 25 mph{}",
                    i.label,
                    i.scale,
                    if low_speed { "" } else { " (--low-speed)" }
                ),
            ));
        }
    }
}

/// Words read in file order, the first nearest the road user (R5).
fn reading_order(words: &[&RuleItem], out: &mut Vec<Finding>) {
    for pair in words.windows(2) {
        if pair[1].y[0] < pair[0].y[0] {
            out.push(warn(
                "MUTCD 11th §3B.21 ¶02 (R5)",
                format!(
                    "{} is nearer the approaching driver than {} before it; a message reads \
                     in the direction of travel, so list its words nearest first",
                    pair[1].label, pair[0].label
                ),
            ));
        }
    }
}

/// Clear space between consecutive words along the lane (R6).
fn line_gaps(words: &[&RuleItem], out: &mut Vec<Finding>) {
    let mut by_y: Vec<&&RuleItem> = words.iter().collect();
    by_y.sort_by(|a, b| a.y[0].total_cmp(&b.y[0]));
    let (lo, hi) = LINE_GAP_HEIGHTS;
    for pair in by_y.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let gap = b.y[0] - a.y[1];
        let h = a.letter_height_m.max(b.letter_height_m);
        if gap < lo * h * (1.0 - 1e-9) {
            out.push(error(
                "MUTCD 11th §3B.20 ¶07 (R6)",
                format!(
                    "clear space between {} and {} is {gap:.2} m, under {lo}× the letter height \
                     ({:.2} m); move the farther word on",
                    a.label,
                    b.label,
                    lo * h
                ),
            ));
        } else if gap > hi * h {
            out.push(warn(
                "MUTCD 11th §3B.20 ¶07 (R6)",
                format!(
                    "clear space between {} and {} is {gap:.2} m, over {hi}× the letter height \
                     ({:.2} m): drivers read them as separate messages",
                    a.label,
                    b.label,
                    hi * h
                ),
            ));
        }
    }
}

fn turn_lane_rules(arrows: &[&RuleItem], only: Option<&RuleItem>, out: &mut Vec<Finding>) {
    if let Some(only) = only {
        for a in arrows {
            let name = a.symbol.as_deref().unwrap_or("");
            if matches!(
                name,
                "arrow-through-left" | "arrow-through-right" | "arrow-left-right" | "arrow-through"
            ) {
                out.push(error(
                    "MUTCD 11th §3B.21 ¶08 (R11)",
                    format!(
                        "{} marks a lane {} with {}; ONLY shall not be used in a lane shared by \
                         more than one movement",
                        only.label,
                        if name == "arrow-through" {
                            "for through traffic"
                        } else {
                            "shared by two movements"
                        },
                        a.label
                    ),
                ));
            }
        }
        // ONLY and the arrow it belongs to are one message: lines 4–10× apart.
        if let Some(gap) = arrows
            .iter()
            .map(|a| (a.y[0] - only.y[1]).max(only.y[0] - a.y[1]))
            .min_by(f64::total_cmp)
        {
            let h = only.letter_height_m;
            let (lo, hi) = LINE_GAP_HEIGHTS;
            if gap < lo * h * (1.0 - 1e-9) || gap > hi * h {
                out.push(warn(
                    "MUTCD 11th §3B.20 ¶07 (R6)",
                    format!(
                        "{} is {gap:.2} m clear of the nearest arrow; keep {lo}–{hi}× the letter \
                         height ({:.2}–{:.2} m)",
                        only.label,
                        lo * h,
                        hi * h
                    ),
                ));
            }
        }
    }
    if arrows.len() < MIN_TURN_ARROWS {
        out.push(warn(
            "MUTCD 11th §3B.23 ¶04 (R13)",
            format!(
                "a turn lane should have at least {MIN_TURN_ARROWS} arrows (one near the upstream \
                 end of the full-width lane, one upstream of the stop line); this one has {}",
                arrows.len()
            ),
        ));
    }
    let mut ys: Vec<[f64; 2]> = arrows.iter().map(|a| a.y).collect();
    ys.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let (lo, hi) = ARROW_SPACING_M;
    for p in ys.windows(2) {
        let d = p[1][0] - p[0][0];
        if d < lo * (1.0 - 1e-9) || d > hi * (1.0 + 1e-9) {
            out.push(warn(
                "CA MUTCD §3B.23 ¶08",
                format!(
                    "lane-use arrows {d:.1} m ({:.0} ft) apart; space them 100–300 ft \
                     ({lo:.1}–{hi:.1} m)",
                    ft(d)
                ),
            ));
        }
    }
}

/// STOP goes with a stop line and before it (11th §3B.21 ¶03, R10).
fn stop_rules(items: &[RuleItem], words: &[&RuleItem], out: &mut Vec<Finding>) {
    let line = items
        .iter()
        .find(|i| i.symbol.as_deref() == Some("stop-line"));
    for w in words.iter().filter(|w| w.word.as_deref() == Some("STOP")) {
        match line {
            Some(l) if w.y[0] > l.y[1] => out.push(error(
                "MUTCD 11th §3B.21 ¶03 (R10)",
                format!(
                    "{} lies past {}: the STOP legend is painted on the approach, before the \
                     stop line",
                    w.label, l.label
                ),
            )),
            Some(_) => {}
            None if items.len() > words.len() => out.push(warn(
                "MUTCD 11th §3B.21 ¶03 (R10)",
                format!("{} has no stop line in the scene", w.label),
            )),
            None => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(i: usize, w: &str, y0: f64, h: f64) -> RuleItem {
        RuleItem {
            index: i,
            label: format!("item {} (word {w})", i + 1),
            word: Some(w.into()),
            symbol: None,
            letter_height_m: h,
            scale: 1.0,
            y: [y0, y0 + h],
        }
    }

    fn symbol(i: usize, s: &str, y0: f64, len: f64) -> RuleItem {
        RuleItem {
            index: i,
            label: format!("item {} (symbol {s})", i + 1),
            word: None,
            symbol: Some(s.into()),
            letter_height_m: 0.0,
            scale: 1.0,
            y: [y0, y0 + len],
        }
    }

    fn rules(f: &[Finding]) -> Vec<&str> {
        f.iter().map(|f| f.rule).collect()
    }

    #[test]
    fn letter_height_with_and_without_low_speed() {
        let w = [word(0, "BUS", 0.0, 1.5)];
        let f = check(&w, false, false, true);
        assert_eq!(rules(&f), ["MUTCD 11th §3B.21 ¶01 (R3)"]);
        assert!(
            !f[0].error && f[0].message.contains("1.83 m (6.0 ft)"),
            "{}",
            f[0]
        );
        assert!(check(&w, true, false, true).is_empty(), "1.5 m ≥ 4.5 ft");
        let small = [word(0, "BUS", 0.0, 1.3)];
        assert_eq!(check(&small, true, false, true).len(), 1);
    }

    #[test]
    fn four_lines_and_gaps() {
        let h = 2.44;
        let ok: Vec<RuleItem> = (0..3)
            .map(|i| word(i, "A", i as f64 * 5.0 * h, h))
            .collect();
        assert!(check(&ok, false, false, true).is_empty());
        let mut four = ok.clone();
        four.push(word(3, "D", 15.0 * h, h));
        assert_eq!(
            rules(&check(&four, false, false, true)),
            ["MUTCD 11th §3B.20 ¶06 (R4)"]
        );
        let close = [word(0, "STOP", 0.0, h), word(1, "AHEAD", 2.0 * h, h)];
        let f = check(&close, false, false, true);
        assert!(f[0].error && f[0].rule.contains("R6"), "{f:?}");
        let far = [word(0, "STOP", 0.0, h), word(1, "AHEAD", 12.0 * h, h)];
        let f = check(&far, false, false, true);
        assert!(!f[0].error && f[0].message.contains("over 10×"), "{f:?}");
        let reversed = [word(0, "AHEAD", 5.0 * h, h), word(1, "STOP", 0.0, h)];
        assert!(
            rules(&check(&reversed, false, false, true)).contains(&"MUTCD 11th §3B.21 ¶02 (R5)")
        );
    }

    #[test]
    fn only_and_arrows() {
        let h = 2.44;
        let a = 2.44;
        let shared = [
            symbol(0, "arrow-through-left", 0.0, a),
            word(1, "ONLY", a + 5.0 * h, h),
        ];
        let f = check(&shared, false, false, true);
        assert!(f.iter().any(|f| f.error && f.rule.contains("R11")), "{f:?}");
        assert!(f.iter().any(|f| f.rule.contains("R13")), "one arrow: {f:?}");
        let good = [
            symbol(0, "arrow-left", 0.0, a),
            word(1, "ONLY", a + 5.0 * h, h),
            symbol(2, "arrow-left", 40.0, a),
        ];
        assert!(
            check(&good, false, false, true).is_empty(),
            "{:?}",
            check(&good, false, false, true)
        );
        let near = [
            symbol(0, "arrow-left", 0.0, a),
            word(1, "ONLY", a + 5.0 * h, h),
            symbol(2, "arrow-left", -20.0, a),
        ];
        assert_eq!(
            rules(&check(&near, false, false, true)),
            ["CA MUTCD §3B.23 ¶08"]
        );
    }

    #[test]
    fn stop_past_its_line_is_refused() {
        let h = 2.44;
        let ok = [symbol(0, "stop-line", 0.0, 0.61), word(1, "STOP", -5.0, h)];
        assert!(check(&ok, false, false, true).is_empty());
        let past = [symbol(0, "stop-line", 0.0, 0.61), word(1, "STOP", 2.0, h)];
        assert!(check(&past, false, false, true)[0].error);
        let alone = [symbol(0, "arrow-left", 0.0, 2.0), word(1, "STOP", 6.0, h)];
        assert!(rules(&check(&alone, false, false, true)).contains(&"MUTCD 11th §3B.21 ¶03 (R10)"));
    }
}
