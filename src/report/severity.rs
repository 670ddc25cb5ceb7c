//! How much a planner warning matters to the crew: `info` (nothing to do),
//! `notice` (the marking comes out, a little off the target somewhere) or
//! `problem` (the result will be visibly wrong: fix before painting).
//! Judged on the warning's kind and factor against the film band the
//! preview draws (±10 % of the target film).

use crate::job::Warning;

/// Film excess (planned / actual speed) within the band the preview calls
/// on target. // assumed: ±10 %, the band of the film colour scale.
pub const FILM_BAND: f64 = 1.10;
/// Film excess from which a slowed place shows as a heavy line.
/// // assumed: 1.5×, the top of the preview's colour scale.
pub const FILM_HEAVY: f64 = 1.5;
/// Fan wider than the stroke by at most this share is not worth saying.
/// // assumed: 5 %, about one 5 mm raster cell either side of a 0.1 m stroke.
pub const WIDER_SMALL: f64 = 1.05;
/// Fan wider than the stroke by more than this share paints visibly
/// outside the letter. // assumed: 25 %, ≈ 12 mm either side of a 0.1 m stroke.
pub const WIDER_LARGE: f64 = 1.25;

/// `info`, `notice` or `problem`.
pub fn of(w: &Warning) -> &'static str {
    let f = w.factor.unwrap_or(1.0);
    match w.kind.as_str() {
        "slowed" if f > FILM_HEAVY => "problem",
        "slowed" if f > FILM_BAND => "notice",
        "slowed" => "info",
        "height_clamped" if f > WIDER_LARGE => "problem",
        "height_clamped" if f > WIDER_SMALL => "notice",
        "height_clamped" => "info",
        "passes" => "info",
        _ => "notice",
    }
}

/// Rank for sorting: problems first.
pub fn rank(severity: &str) -> u8 {
    match severity {
        "problem" => 0,
        "notice" => 1,
        _ => 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(kind: &str, factor: f64) -> Warning {
        Warning {
            kind: kind.into(),
            stroke: 1,
            t_s: None,
            factor: Some(factor),
            message: String::new(),
        }
    }

    #[test]
    fn small_excesses_are_info_large_ones_problems() {
        assert_eq!(of(&w("slowed", 1.03)), "info");
        assert_eq!(of(&w("slowed", 1.10)), "info");
        assert_eq!(of(&w("slowed", 1.2)), "notice");
        assert_eq!(of(&w("slowed", 1.71)), "problem");
        assert_eq!(of(&w("height_clamped", 1.009)), "info");
        assert_eq!(of(&w("height_clamped", 1.297)), "problem");
        assert_eq!(of(&w("passes", 3.0)), "info");
        assert_eq!(of(&w("layout", 1.0)), "notice");
        assert!(rank("problem") < rank("notice") && rank("notice") < rank("info"));
    }
}
