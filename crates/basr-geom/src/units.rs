//! Lengths as people type them: `2.44`, `2.44m`, `8ft`, `96in`, `2440mm`.
//! Every command-line option that takes a length reads it here and turns it
//! into the option's own unit (metres, or millimetres for `…-mm` options);
//! inside, everything is SI (SPEC §2). A bare number that reads better in
//! feet than in metres gets a hint (`--letter-height 8`: 8 ft = 2.44 m?).

/// Metres per foot and per inch (exact, by the 1959 international yard).
pub const M_PER_FT: f64 = 0.3048;
pub const M_PER_IN: f64 = 0.0254;

/// The units a person reads lengths in: the crew's tape.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum System {
    /// Metres, to the centimetre: `4.60 m`.
    #[default]
    Metric,
    /// Feet and inches, to the inch: `15 ft 1 in`.
    Us,
}

impl System {
    /// `m` (a length ≥ 0) as this system writes it for a crew.
    pub fn length(self, m: f64) -> String {
        match self {
            System::Metric => format!("{m:.2} m"),
            System::Us => {
                // To the inch: a truck is placed with a tape, not finer.
                let inches = (m / M_PER_IN).round() as i64;
                match (inches / 12, inches % 12) {
                    (0, i) => format!("{i} in"),
                    (ft, 0) => format!("{ft} ft"),
                    (ft, i) => format!("{ft} ft {i} in"),
                }
            }
        }
    }
}

/// A length as given: its value in metres and whether a unit was written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Length {
    pub m: f64,
    /// No unit was written: the number is in the option's own unit.
    pub bare: bool,
    /// Written in feet or inches (`8ft`, `96in`): the user reads US units.
    pub us: bool,
}

/// The unit suffixes accepted, with metres per unit.
const UNITS: [(&str, f64); 11] = [
    ("mm", 1e-3),
    ("cm", 1e-2),
    ("m", 1.0),
    ("ft", M_PER_FT),
    ("feet", M_PER_FT),
    ("foot", M_PER_FT),
    ("'", M_PER_FT),
    ("in", M_PER_IN),
    ("inch", M_PER_IN),
    ("inches", M_PER_IN),
    ("\"", M_PER_IN),
];

/// A length that cannot be read: what was typed and what to write.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LengthError {
    #[error("{text:?} is not a length: give a number with an optional unit, e.g. 2.44, 2.44m, 8ft, 96in or 2440mm")]
    NotANumber {
        text: String,
        #[source]
        source: std::num::ParseFloatError,
    },
    #[error("{text:?}: unknown unit {unit:?}; use m, mm, cm, ft or in (8ft, 96in, 2.44m)")]
    UnknownUnit { text: String, unit: String },
}

/// Read `text` as a length; a bare number is in units of `bare_m` metres
/// (1 for a metre option, 1e-3 for a millimetre one).
pub fn parse(text: &str, bare_m: f64) -> Result<Length, LengthError> {
    let t = text.trim();
    // A plain number (also `inf`, `NaN`: the option's own check refuses
    // those with its range).
    if let Ok(value) = t.parse::<f64>() {
        return Ok(Length {
            m: value * bare_m,
            bare: true,
            us: false,
        });
    }
    let split = t
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || c == '.'
                || (i == 0 && (c == '-' || c == '+'))
                || ((c == 'e' || c == 'E') && t[i + 1..].starts_with(|d: char| d.is_ascii_digit())))
        })
        .map_or(t.len(), |(i, _)| i);
    let (num, unit) = t.split_at(split);
    let unit = unit.trim();
    let value: f64 = num.parse().map_err(|source| LengthError::NotANumber {
        text: text.to_string(),
        source,
    })?;
    if unit.is_empty() {
        return Ok(Length {
            m: value * bare_m,
            bare: true,
            us: false,
        });
    }
    let per = UNITS
        .iter()
        .find(|(u, _)| u.eq_ignore_ascii_case(unit))
        .map(|&(_, f)| f)
        .ok_or_else(|| LengthError::UnknownUnit {
            text: text.to_string(),
            unit: unit.to_string(),
        })?;
    Ok(Length {
        m: value * per,
        bare: false,
        us: per == M_PER_FT || per == M_PER_IN,
    })
}

/// clap value parser for an option in metres.
pub fn metres(text: &str) -> Result<Length, LengthError> {
    parse(text, 1.0)
}

/// clap value parser for an option in millimetres: the value in mm.
pub fn millimetres(text: &str) -> Result<f64, LengthError> {
    parse(text, 1e-3).map(|l| l.m * 1e3)
}

/// clap value parser for a plain metre value (no hint wanted): metres.
pub fn metres_value(text: &str) -> Result<f64, LengthError> {
    parse(text, 1.0).map(|l| l.m)
}

/// A hint when a bare `length` lies outside `usual_m` as metres but inside
/// it read as feet (`--letter-height 8`): what the option got and what feet
/// would give.
pub fn feet_hint(option: &str, length: Length, usual_m: (f64, f64)) -> Option<String> {
    let inside = |v: f64| v >= usual_m.0 && v <= usual_m.1;
    if !length.bare || inside(length.m) || !inside(length.m * M_PER_FT) {
        return None;
    }
    let v = length.m;
    Some(format!(
        "{option} {v} is read as {v} m; if you meant feet, write {option} {v}ft ({:.4} m)",
        v * M_PER_FT
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffixes_convert_to_metres() {
        assert_eq!(metres("8ft").unwrap().m, 2.4384);
        assert!((metres("96in").unwrap().m - 2.4384).abs() < 1e-12);
        assert_eq!(metres("2440mm").unwrap().m, 2.44);
        assert_eq!(
            metres("2.44 m").unwrap(),
            Length {
                m: 2.44,
                bare: false,
                us: false
            }
        );
        assert_eq!(metres("8'").unwrap().m, 2.4384);
        assert!(metres("8ft").unwrap().us && metres("96in").unwrap().us);
        assert_eq!(
            metres("2.44").unwrap(),
            Length {
                m: 2.44,
                bare: true,
                us: false
            }
        );
        assert_eq!(metres("-1.5m").unwrap().m, -1.5);
        assert_eq!(metres("1e-3").unwrap().m, 1e-3);
        assert_eq!(millimetres("20").unwrap(), 20.0);
        assert!((millimetres("0.25in").unwrap() - 6.35).abs() < 1e-12);
    }

    #[test]
    fn bad_lengths_say_what_to_write() {
        assert_eq!(
            metres("8yd").unwrap_err().to_string(),
            "\"8yd\": unknown unit \"yd\"; use m, mm, cm, ft or in (8ft, 96in, 2.44m)"
        );
        let e = metres("ft").unwrap_err();
        assert!(
            e.to_string().starts_with("\"ft\" is not a length: give"),
            "{e}"
        );
        assert!(std::error::Error::source(&e).is_some());
        assert!(metres("").unwrap_err().to_string().contains("not a length"));
    }

    #[test]
    fn lengths_read_as_a_crew_reads_them() {
        assert_eq!(System::Metric.length(4.6), "4.60 m");
        assert_eq!(System::Us.length(4.6), "15 ft 1 in");
        assert_eq!(System::Us.length(12.0 * M_PER_FT), "12 ft");
        assert_eq!(System::Us.length(0.3), "1 ft");
        assert_eq!(System::Us.length(0.25), "10 in");
        assert_eq!(System::Us.length(0.2), "8 in");
    }

    #[test]
    fn a_bare_number_that_reads_as_feet_gets_a_hint() {
        let usual = (0.3, 3.7);
        let h = feet_hint("--letter-height", metres("8").unwrap(), usual).unwrap();
        assert!(h.contains("--letter-height 8ft (2.4384 m)"), "{h}");
        assert_eq!(
            feet_hint("--letter-height", metres("2.44").unwrap(), usual),
            None
        );
        assert_eq!(
            feet_hint("--letter-height", metres("8m").unwrap(), usual),
            None
        );
        // 50 ft is no letter height either: no guess.
        assert_eq!(
            feet_hint("--letter-height", metres("50").unwrap(), usual),
            None
        );
    }
}
