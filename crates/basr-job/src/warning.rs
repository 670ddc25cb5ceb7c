//! The job's warnings, typed: what kind of note, how much it matters, the
//! item and stroke it is about. The file keeps the format jobs have always
//! had: `kind` and `severity` as lower-case words, `stroke` −1 when the
//! note is not about one stroke, and no owner (the owner is known to the
//! process that compiled the job; a job read from a file has none).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// How much a note matters to the crew (issue 15 sorts and colours by it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// For the record: the job paints as planned.
    Info,
    /// Worth a look before painting: the job paints, but not as asked.
    Notice,
    /// The paint will be off target somewhere.
    Problem,
}

impl Severity {
    /// The word the job file and the crew's text use.
    pub fn name(self) -> &'static str {
        match self {
            Severity::Info => "info",
            Severity::Notice => "notice",
            Severity::Problem => "problem",
        }
    }
}

impl std::fmt::Display for Severity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What a warning is about; the job's `kind` word.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WarningKind {
    /// A layout rule the marking bends.
    Layout,
    /// How a shape was decomposed, and why.
    Shape,
    /// A stroke wider than one pass, painted in parallel passes.
    Passes,
    /// Places narrower than the fan paints from the nozzle's lowest height.
    HeightClamped,
    /// A limit holds the nozzle below the painting speed over paint.
    Slowed,
    /// The job's film misses one of the preview's bounds.
    Film,
    /// The arm comes to rest.
    Stop,
    /// The road's surface under the marking off the truck's plane.
    Surface,
    /// A plant of compile's verification set (the arm as it may be) strays
    /// over the bound where compile kept the job as it was.
    Arm,
}

impl WarningKind {
    /// The job's `kind` word.
    pub fn name(self) -> &'static str {
        match self {
            WarningKind::Layout => "layout",
            WarningKind::Shape => "shape",
            WarningKind::Passes => "passes",
            WarningKind::HeightClamped => "height_clamped",
            WarningKind::Slowed => "slowed",
            WarningKind::Film => "film",
            WarningKind::Stop => "stop",
            WarningKind::Surface => "surface",
            WarningKind::Arm => "arm",
        }
    }
}

impl std::fmt::Display for WarningKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What kind of painted item a stroke belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OwnerKind {
    Letter,
    Symbol,
    Shape,
}

impl OwnerKind {
    /// The word messages use: `letter`, `symbol`, `shape`.
    pub fn name(self) -> &'static str {
        match self {
            OwnerKind::Letter => "letter",
            OwnerKind::Symbol => "symbol",
            OwnerKind::Shape => "shape",
        }
    }
}

/// Which painted item a stroke belongs to, for messages: a letter's
/// character (or a symbol's name) and its line.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Owner {
    /// What the item is.
    pub kind: OwnerKind,
    /// The character or name (`"S"`, `"arrow_left"`); `layout.glyphs[].char`.
    pub label: String,
    /// Line index (0 = nearest the approaching driver).
    pub line: usize,
}

impl std::fmt::Display for Owner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {} of line {}",
            self.kind.name(),
            self.label,
            self.line + 1
        )
    }
}

/// A note the planner wants a person to read (e.g. a slowed stroke).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// What the note is about (`"slowed"`, `"height_clamped"` in the file).
    pub kind: WarningKind,
    /// How much it matters to the crew: `info` (nothing to do), `notice`
    /// (paints, slightly off somewhere), `problem` (visibly off target).
    /// `None` in jobs written before severities existed (absent in the
    /// file); [`Warning::graded`] counts those as notices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub severity: Option<Severity>,
    /// The stroke it is about; −1 in the file when none.
    #[serde(with = "stroke_or_minus_one")]
    pub stroke: Option<usize>,
    /// Time in the job where it applies (s), when known.
    pub t_s: Option<f64>,
    /// Dimensionless factor (e.g. film excess = planned / actual speed).
    pub factor: Option<f64>,
    /// One sentence for a person.
    pub message: String,
    /// The item the note is about, for notes about one stroke of an item
    /// (`passes`, `height_clamped`, `slowed`). Not in the file: `None` in a
    /// job read back.
    #[serde(skip)]
    pub owner: Option<Owner>,
}

impl Warning {
    /// The severity, a job written before severities existed counted as a
    /// notice (the job sheet's rule: worth a look, not a refusal).
    pub fn graded(&self) -> Severity {
        self.severity.unwrap_or(Severity::Notice)
    }
}

/// `stroke` as the file has it: the index, or −1 for none.
mod stroke_or_minus_one {
    use super::*;

    pub fn serialize<S: Serializer>(stroke: &Option<usize>, s: S) -> Result<S::Ok, S::Error> {
        match stroke {
            Some(i) => s.serialize_u64(*i as u64),
            None => s.serialize_i64(-1),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
        let v = i64::deserialize(d)?;
        match v {
            -1 => Ok(None),
            i if i >= 0 => usize::try_from(i)
                .map(Some)
                .map_err(serde::de::Error::custom),
            i => Err(serde::de::Error::custom(format!(
                "warning stroke {i}: a stroke index is 0 or more, or -1 for none"
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn warning(stroke: Option<usize>, severity: Option<Severity>) -> Warning {
        Warning {
            kind: WarningKind::HeightClamped,
            severity,
            stroke,
            t_s: None,
            factor: Some(1.5),
            message: "m".into(),
            owner: Some(Owner {
                kind: OwnerKind::Symbol,
                label: "arrow_left".into(),
                line: 1,
            }),
        }
    }

    #[test]
    fn the_file_keeps_words_and_minus_one_and_drops_the_owner() {
        let w = warning(None, Some(Severity::Problem));
        let v = serde_json::to_value(&w).unwrap();
        assert_eq!(
            v,
            serde_json::json!({"kind": "height_clamped", "severity": "problem", "stroke": -1,
                "t_s": null, "factor": 1.5, "message": "m"})
        );
        let back: Warning = serde_json::from_value(v).unwrap();
        assert_eq!(back.stroke, None);
        assert_eq!(back.owner, None);
        assert_eq!(back.kind, WarningKind::HeightClamped);
        let v = serde_json::to_value(warning(Some(7), None)).unwrap();
        assert_eq!(v["stroke"], 7);
        assert!(v.get("severity").is_none(), "{v}");
        let back: Warning = serde_json::from_value(v).unwrap();
        assert_eq!((back.stroke, back.severity), (Some(7), None));
        assert_eq!(back.graded(), Severity::Notice);
    }

    #[test]
    fn a_stroke_below_minus_one_or_an_unknown_word_is_refused() {
        let mut v = serde_json::to_value(warning(None, None)).unwrap();
        v["stroke"] = serde_json::json!(-2);
        let e = serde_json::from_value::<Warning>(v.clone()).unwrap_err();
        assert!(e.to_string().contains("warning stroke -2"), "{e}");
        v["stroke"] = serde_json::json!(0);
        v["kind"] = serde_json::json!("wobble");
        assert!(serde_json::from_value::<Warning>(v).is_err());
    }

    #[test]
    fn names_are_the_file_words() {
        for k in [
            WarningKind::Layout,
            WarningKind::Shape,
            WarningKind::Passes,
            WarningKind::HeightClamped,
            WarningKind::Slowed,
            WarningKind::Film,
            WarningKind::Stop,
            WarningKind::Surface,
        ] {
            assert_eq!(serde_json::to_value(k).unwrap(), k.name());
        }
        for s in [Severity::Info, Severity::Notice, Severity::Problem] {
            assert_eq!(serde_json::to_value(s).unwrap(), s.name());
        }
        assert_eq!(
            warning(None, None).owner.unwrap().to_string(),
            "symbol arrow_left of line 2"
        );
    }
}
