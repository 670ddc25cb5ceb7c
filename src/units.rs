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

/// Read `text` as a length; a bare number is in units of `bare_m` metres
/// (1 for a metre option, 1e-3 for a millimetre one).
pub fn parse(text: &str, bare_m: f64) -> Result<Length, String> {
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
    let value: f64 = num.parse().map_err(|_| {
        format!("{text:?} is not a length: give a number with an optional unit, e.g. 2.44, 2.44m, 8ft, 96in or 2440mm")
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
        .ok_or_else(|| {
            format!("{text:?}: unknown unit {unit:?}; use m, mm, cm, ft or in (8ft, 96in, 2.44m)")
        })?;
    Ok(Length {
        m: value * per,
        bare: false,
        us: per == M_PER_FT || per == M_PER_IN,
    })
}

/// clap value parser for an option in metres.
pub fn metres(text: &str) -> Result<Length, String> {
    parse(text, 1.0)
}

/// clap value parser for an option in millimetres: the value in mm.
pub fn millimetres(text: &str) -> Result<f64, String> {
    parse(text, 1e-3).map(|l| l.m * 1e3)
}

/// clap value parser for a plain metre value (no hint wanted): metres.
pub fn metres_value(text: &str) -> Result<f64, String> {
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

/// Length keys of a marking file in other units than metres, with metres
/// per unit: `lane_width_ft = 12`, `at_ft = [0, 16]`, `height_in = 24`.
const KEY_UNITS: [(&str, f64); 2] = [("_ft", M_PER_FT), ("_in", M_PER_IN)];

/// A marking file's lengths in metres, for a crew that measures in feet:
/// every `NAME_ft` / `NAME_in` key becomes `NAME_m` (numbers, or arrays of
/// them, times the unit), and a length given as text with its unit
/// (`lane_width_m = "12ft"`, `at_m = ["0ft", "16ft"]`, `at_ft = [0, "6in"]`)
/// is read as `--letter-height 8ft` is. `Ok(None)` when the file has none
/// of these (or is not TOML: its reader reports that with the line), so a
/// metric file is read exactly as before.
pub fn marking_lengths_in_metres(text: &str) -> Result<Option<toml::Table>, String> {
    let Ok(mut table) = text.parse::<toml::Table>() else {
        return Ok(None);
    };
    let changed = lengths_in_table(&mut table, "")?;
    Ok(changed.then_some(table))
}

/// [`marking_lengths_in_metres`] on one table and the tables below it;
/// `at` names where it is (`item 2: `) in messages. Whether anything changed.
fn lengths_in_table(t: &mut toml::Table, at: &str) -> Result<bool, String> {
    let mut changed = false;
    let keys: Vec<String> = t.keys().cloned().collect();
    for key in keys {
        let unit = KEY_UNITS
            .iter()
            .find(|(suffix, _)| key.ends_with(suffix) && key.len() > suffix.len());
        let Some(value) = t.get(&key).cloned() else {
            continue;
        };
        match (unit, value) {
            (Some(&(suffix, per)), v) => {
                let base = &key[..key.len() - suffix.len()];
                let metric = format!("{base}_m");
                if t.contains_key(&metric) {
                    return Err(format!("{at}give {metric} or {key}, not both"));
                }
                let m = length_value(&v, per, &format!("{at}{key}"))?;
                t.remove(&key);
                t.insert(metric, m);
                changed = true;
            }
            // Not a guard: a guard cannot borrow the table mutably.
            #[allow(clippy::collapsible_match)]
            (None, toml::Value::Table(mut sub)) => {
                if lengths_in_table(&mut sub, &format!("{at}{key}."))? {
                    t.insert(key, toml::Value::Table(sub));
                    changed = true;
                }
            }
            (None, toml::Value::Array(items))
                if items.iter().all(|v| matches!(v, toml::Value::Table(_)))
                    && !items.is_empty() =>
            {
                let mut out = Vec::with_capacity(items.len());
                let mut any = false;
                for (i, v) in items.into_iter().enumerate() {
                    let toml::Value::Table(mut sub) = v else {
                        continue;
                    };
                    any |= lengths_in_table(&mut sub, &format!("{at}{key} {}: ", i + 1))?;
                    out.push(toml::Value::Table(sub));
                }
                if any {
                    t.insert(key, toml::Value::Array(out));
                    changed = true;
                }
            }
            (None, v) if key.ends_with("_m") && has_text(&v) => {
                let m = length_value(&v, 1.0, &format!("{at}{key}"))?;
                t.insert(key, m);
                changed = true;
            }
            _ => {}
        }
    }
    Ok(changed)
}

fn has_text(v: &toml::Value) -> bool {
    match v {
        toml::Value::String(_) => true,
        toml::Value::Array(a) => a.iter().any(has_text),
        _ => false,
    }
}

/// A length value (number, text with a unit, or an array of them) in
/// metres; a bare number is in units of `per` metres.
fn length_value(v: &toml::Value, per: f64, what: &str) -> Result<toml::Value, String> {
    Ok(match v {
        toml::Value::Integer(i) => toml::Value::Float(*i as f64 * per),
        toml::Value::Float(f) => toml::Value::Float(f * per),
        toml::Value::String(s) => {
            toml::Value::Float(parse(s, per).map_err(|e| format!("{what}: {e}"))?.m)
        }
        toml::Value::Array(a) => toml::Value::Array(
            a.iter()
                .map(|x| length_value(x, per, what))
                .collect::<Result<_, _>>()?,
        ),
        other => {
            return Err(format!(
                "{what} = {other}: give a length, a number or text with its unit (12, \"12ft\", \"144in\")"
            ))
        }
    })
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
        assert!(metres("8yd").unwrap_err().contains("unknown unit \"yd\""));
        assert!(metres("ft").unwrap_err().contains("not a length"));
        assert!(metres("").unwrap_err().contains("not a length"));
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
    fn marking_lengths_in_feet_become_metres() {
        let t = marking_lengths_in_metres(
            "[marking]\nlane_width_ft = 12\nletter_height_ft = 8\n[[item]]\nword = \"STOP\"\n\
             at_ft = [0, \"6in\"]\n[[item]]\nsymbol = \"rxr\"\nat_m = [\"1ft\", 2.5]\n",
        )
        .unwrap()
        .unwrap();
        let m = t["marking"].as_table().unwrap();
        assert_eq!(m["lane_width_m"].as_float(), Some(12.0 * M_PER_FT));
        assert_eq!(m["letter_height_m"].as_float(), Some(8.0 * M_PER_FT));
        assert!(!m.contains_key("lane_width_ft"));
        let items = t["item"].as_array().unwrap();
        let at = |i: usize| items[i].as_table().unwrap()["at_m"].clone();
        assert_eq!(
            at(0),
            toml::Value::Array(vec![0.0.into(), (6.0 * M_PER_IN).into()])
        );
        assert_eq!(at(1), toml::Value::Array(vec![M_PER_FT.into(), 2.5.into()]));
        // A metric file is left to its reader, untouched.
        assert_eq!(
            marking_lengths_in_metres("[marking]\nlines = [\"STOP\"]\nlane_width_m = 3.66\n"),
            Ok(None)
        );
        let e = marking_lengths_in_metres("[marking]\nlane_width_m = 3\nlane_width_ft = 12\n")
            .unwrap_err();
        assert!(e.contains("lane_width_m or lane_width_ft, not both"), "{e}");
        let e = marking_lengths_in_metres("[[item]]\nat_ft = [0, \"6yd\"]\n").unwrap_err();
        assert!(
            e.contains("item 1: at_ft") && e.contains("unknown unit"),
            "{e}"
        );
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
