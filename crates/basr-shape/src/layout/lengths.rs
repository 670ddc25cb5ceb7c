//! A marking file's lengths in feet and inches, or written with their unit,
//! turned into the metres its reader takes: a US crew measures with a tape
//! in feet (`lane_width_ft = 12`, `at_ft = [0, 16]`, `at_m = ["0ft", "16ft"]`).

use basr_geom::units::{parse, LengthError, M_PER_FT, M_PER_IN};

/// A length of a marking file that cannot be read, named by where it is.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LengthsError {
    /// The same length in metres and in another unit.
    #[error("{at}{key} and {at}{metric} are one length: give {metric} or {key}, not both")]
    Both {
        at: String,
        metric: String,
        key: String,
    },
    /// Text that is not a length (`"6yd"`).
    #[error("{what}: {source}")]
    Length { what: String, source: LengthError },
    /// A value that is neither a number nor text (a table, a date).
    #[error(
        "{what} = {value}: give a length, a number or text with its unit (12, \"12ft\", \"144in\")"
    )]
    NotALength { what: String, value: String },
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
pub fn marking_lengths_in_metres(text: &str) -> Result<Option<toml::Table>, LengthsError> {
    let Ok(mut table) = text.parse::<toml::Table>() else {
        return Ok(None);
    };
    let changed = lengths_in_table(&mut table, "")?;
    Ok(changed.then_some(table))
}

/// [`marking_lengths_in_metres`] on one table and the tables below it;
/// `at` names where it is (`item 2: `) in messages. Whether anything changed.
fn lengths_in_table(t: &mut toml::Table, at: &str) -> Result<bool, LengthsError> {
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
                    return Err(LengthsError::Both {
                        at: at.into(),
                        metric,
                        key,
                    });
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
fn length_value(v: &toml::Value, per: f64, what: &str) -> Result<toml::Value, LengthsError> {
    Ok(match v {
        toml::Value::Integer(i) => toml::Value::Float(*i as f64 * per),
        toml::Value::Float(f) => toml::Value::Float(f * per),
        toml::Value::String(s) => toml::Value::Float(
            parse(s, per)
                .map_err(|source| LengthsError::Length {
                    what: what.into(),
                    source,
                })?
                .m,
        ),
        toml::Value::Array(a) => toml::Value::Array(
            a.iter()
                .map(|x| length_value(x, per, what))
                .collect::<Result<_, _>>()?,
        ),
        other => {
            return Err(LengthsError::NotALength {
                what: what.into(),
                value: other.to_string(),
            })
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(
            e.to_string()
                .contains("lane_width_m or lane_width_ft, not both"),
            "{e}"
        );
        let e = marking_lengths_in_metres("[[item]]\nat_ft = [0, \"6yd\"]\n").unwrap_err();
        assert!(
            e.to_string().contains("item 1: at_ft") && e.to_string().contains("unknown unit"),
            "{e}"
        );
    }
}
