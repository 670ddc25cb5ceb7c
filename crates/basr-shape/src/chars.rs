//! Characters named for people: a message with a letter that only looks
//! Latin (Cyrillic 'О', Greek 'Α', a full-width 'Ｏ') is refused naming its
//! code point and the Latin letter it imitates, since the two print alike.

/// Look-alikes of the Latin capitals and digits the font has: (character,
/// script, the Latin character it looks like).
const LOOK_ALIKES: &[(char, &str, char)] = &[
    ('А', "Cyrillic", 'A'),
    ('В', "Cyrillic", 'B'),
    ('Е', "Cyrillic", 'E'),
    ('К', "Cyrillic", 'K'),
    ('М', "Cyrillic", 'M'),
    ('Н', "Cyrillic", 'H'),
    ('О', "Cyrillic", 'O'),
    ('Р', "Cyrillic", 'P'),
    ('С', "Cyrillic", 'C'),
    ('Т', "Cyrillic", 'T'),
    ('У', "Cyrillic", 'Y'),
    ('Х', "Cyrillic", 'X'),
    ('Ѕ', "Cyrillic", 'S'),
    ('І', "Cyrillic", 'I'),
    ('Ј', "Cyrillic", 'J'),
    ('а', "Cyrillic", 'a'),
    ('е', "Cyrillic", 'e'),
    ('о', "Cyrillic", 'o'),
    ('р', "Cyrillic", 'p'),
    ('с', "Cyrillic", 'c'),
    ('у', "Cyrillic", 'y'),
    ('х', "Cyrillic", 'x'),
    ('Α', "Greek", 'A'),
    ('Β', "Greek", 'B'),
    ('Ε', "Greek", 'E'),
    ('Ζ', "Greek", 'Z'),
    ('Η', "Greek", 'H'),
    ('Ι', "Greek", 'I'),
    ('Κ', "Greek", 'K'),
    ('Μ', "Greek", 'M'),
    ('Ν', "Greek", 'N'),
    ('Ο', "Greek", 'O'),
    ('Ρ', "Greek", 'P'),
    ('Τ', "Greek", 'T'),
    ('Υ', "Greek", 'Y'),
    ('Χ', "Greek", 'X'),
    ('ο', "Greek", 'o'),
];

/// `'О' (U+041E, a Cyrillic letter that looks like the Latin O; type the
/// Latin one)`; other characters as `'é' (U+00E9)`.
pub fn describe(c: char) -> String {
    let code = format!("U+{:04X}", c as u32);
    if let Some(&(_, script, latin)) = LOOK_ALIKES.iter().find(|(k, _, _)| *k == c) {
        return format!(
            "{c:?} ({code}, a {script} letter that looks like the Latin {latin}; type the Latin one)"
        );
    }
    // Full-width forms (U+FF01–U+FF5E) mirror ASCII at an offset.
    if ('\u{FF01}'..='\u{FF5E}').contains(&c) {
        if let Some(ascii) = char::from_u32(c as u32 - 0xFEE0) {
            return format!(
                "{c:?} ({code}, the full-width form of {ascii:?}; type the ordinary {ascii:?})"
            );
        }
    }
    if c.is_control() || c.is_whitespace() {
        return format!("{c:?} ({code}, an invisible character)");
    }
    format!("{c:?} ({code})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_alikes_name_their_code_point_and_latin_twin() {
        let d = describe('\u{041E}');
        assert!(
            d.contains("U+041E") && d.contains("Cyrillic") && d.contains("Latin O"),
            "{d}"
        );
        assert!(describe('Ο').contains("U+039F, a Greek letter"));
        assert!(describe('Ｏ').contains("full-width form of 'O'"));
        assert_eq!(describe('é'), "'é' (U+00E9)");
        assert!(describe('\u{200B}').contains("U+200B"));
    }

    #[test]
    fn no_look_alike_is_latin() {
        for &(c, _, _) in LOOK_ALIKES {
            assert!(!c.is_ascii(), "{c}");
        }
    }
}
