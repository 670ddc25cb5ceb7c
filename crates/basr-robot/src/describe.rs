//! Reading and validating robot descriptions: every problem at once, each
//! with file:line:col, the field's dotted name, what is wrong and the fix.

use super::{fourbar::Assembly, JointLimit, Kind, Robot};

/// Errors from reading a robot description.
#[derive(Debug, thiserror::Error)]
pub enum RobotError {
    #[error("{message}")]
    Read { origin: String, message: String },
    #[error("{origin}: invalid robot description:\n  {}", problems.join("\n  "))]
    Invalid {
        origin: String,
        problems: Vec<String>,
    },
    /// A valid description of a kind the command does not take yet.
    #[error(
        "{origin}: a robot of kind \"{kind}\", but this needs BASR's description; compile, \
         preview, check, simulate, robot, pose, workspace and design take every kind \
         (docs/robot-kinds.md)"
    )]
    Kind { origin: String, kind: &'static str },
}

/// `origin:line:col` of a parser's error span, and the dotted name of the
/// field on that line when there is one.
fn span_location(
    text: &str,
    origin: &str,
    span: Option<std::ops::Range<usize>>,
) -> (String, Option<String>) {
    match span {
        Some(s) => {
            let (l, c) = basr_io::line_col(text, s.start);
            (format!("{origin}:{l}:{c}"), field_at_line(text, l))
        }
        None => (origin.to_string(), None),
    }
}

/// Table name of a header line (`[a.b]` → `a.b`), if it is one.
fn header(line: &str) -> Option<String> {
    let t = line.trim();
    let inner = t.strip_prefix('[')?;
    let end = inner.find(']')?;
    Some(
        inner[..end]
            .split('.')
            .map(|p| p.trim().trim_matches('"'))
            .collect::<Vec<_>>()
            .join("."),
    )
}

/// Key of a `key = value` line.
fn key_of(line: &str) -> Option<&str> {
    let t = line.trim_start();
    if t.starts_with('#') || t.starts_with('[') {
        return None;
    }
    let eq = t.find('=')?;
    Some(t[..eq].trim().trim_matches('"'))
}

/// 1-based line of a dotted field in the text: its `key =` line in its table,
/// else its table's header; `None` when absent (e.g. a missing field). An
/// array element (`a.b[3]`) is found at its array's line.
fn locate(text: &str, path: &str) -> Option<usize> {
    let path = path.split_once('[').map_or(path, |(p, _)| p);
    let (table, key) = match path.rfind('.') {
        Some(i) => (&path[..i], &path[i + 1..]),
        None => ("", path),
    };
    let mut current = String::new();
    let mut header_line = None;
    for (i, line) in text.lines().enumerate() {
        if let Some(h) = header(line) {
            if h == path {
                header_line = Some(i + 1);
            }
            current = h;
            continue;
        }
        if current == table && key_of(line) == Some(key) {
            return Some(i + 1);
        }
    }
    header_line
}

/// Dotted name of the field on a given 1-based line (table + key).
fn field_at_line(text: &str, line_no: usize) -> Option<String> {
    let mut current = String::new();
    for (i, line) in text.lines().enumerate() {
        if let Some(h) = header(line) {
            current = h;
        }
        if i + 1 == line_no {
            let key = key_of(line)?;
            return Some(if current.is_empty() {
                key.to_string()
            } else {
                format!("{current}.{key}")
            });
        }
    }
    None
}

/// Name of the table a line belongs to (the last header at or above it;
/// "" for the root table).
fn table_at_line(text: &str, line_no: usize) -> String {
    let mut current = String::new();
    for line in text.lines().take(line_no) {
        if let Some(h) = header(line) {
            current = h;
        }
    }
    current
}

/// serde's "missing field `k`" names the key alone; give its dotted name
/// from the table the error points at, and what to do.
fn dotted_missing(
    message: &str,
    text: &str,
    span: Option<std::ops::Range<usize>>,
) -> Option<String> {
    let key = message.strip_prefix("missing field `")?.strip_suffix('`')?;
    let table = span
        .map(|s| table_at_line(text, basr_io::line_col(text, s.start).0))
        .unwrap_or_default();
    let dotted = if table.is_empty() {
        key.to_string()
    } else {
        format!("{table}.{key}")
    };
    Some(format!(
        "missing field `{dotted}`; add it (`basr robot --toml` shows every field with its source)"
    ))
}

fn at(origin: &str, text: &str, path: &str, what: &str) -> String {
    match locate(text, path) {
        Some(line) => format!("{origin}:{line}: field `{path}`: {what}"),
        None => format!("{origin}: field `{path}`: {what}"),
    }
}

/// Non-finite floats anywhere in the TOML tree (TOML allows `nan`, `inf`).
fn non_finite(value: &toml::Value, path: &str, out: &mut Vec<String>) {
    match value {
        toml::Value::Float(f) if !f.is_finite() => out.push(path.to_string()),
        toml::Value::Table(t) => {
            for (k, v) in t {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                non_finite(v, &p, out);
            }
        }
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                non_finite(v, &format!("{path}[{i}]"), out);
            }
        }
        _ => {}
    }
}

/// Every problem of a robot description's text (empty when valid).
pub fn check_source(text: &str, origin: &str) -> Vec<String> {
    match super::AnyRobot::from_toml_str(text, origin) {
        Ok(_) => vec![],
        Err(RobotError::Invalid { problems, .. }) => problems,
        Err(e) => vec![e.to_string()],
    }
}

pub(super) fn parse(text: &str, origin: &str) -> Result<Robot, RobotError> {
    parse_as(text, origin, validate)
}

/// The `kind` of a description's text (absent = BASR); a text that is not
/// TOML is left to [`parse`] to report, as BASR.
pub(super) fn kind_of(text: &str, origin: &str) -> Result<Kind, RobotError> {
    let Ok(tree) = toml::from_str::<toml::Table>(text) else {
        return Ok(Kind::Basr);
    };
    match tree.get("kind") {
        None => Ok(Kind::Basr),
        Some(toml::Value::String(s)) if Kind::parse(s).is_some() => {
            Ok(Kind::parse(s).unwrap_or_default())
        }
        Some(v) => Err(RobotError::Invalid {
            origin: origin.to_string(),
            problems: vec![at(
                origin,
                text,
                "kind",
                &format!(
                    "must be one of {} (got {v}); absent means \"basr\"",
                    Kind::NAMES.map(|n| format!("\"{n}\"")).join(", ")
                ),
            )],
        }),
    }
}

/// Parse a description of one kind: syntax, non-finite numbers, fields
/// (serde), then `validate`'s semantic checks, each with its line.
pub(super) fn parse_as<T: serde::de::DeserializeOwned>(
    text: &str,
    origin: &str,
    validate: impl Fn(&T) -> Vec<(String, String)>,
) -> Result<T, RobotError> {
    let invalid = |problems| RobotError::Invalid {
        origin: origin.to_string(),
        problems,
    };
    let tree: toml::Table = match toml::from_str(text) {
        Ok(t) => t,
        Err(e) => {
            let (loc, field) = span_location(text, origin, e.span());
            let field = field
                .map(|f| format!(" in field `{f}`"))
                .unwrap_or_default();
            return Err(invalid(vec![format!(
                "{loc}: TOML syntax error{field}: {}; fix the syntax (see https://toml.io)",
                basr_io::one_line(e.message())
            )]));
        }
    };
    let mut bad = Vec::new();
    non_finite(&toml::Value::Table(tree), "", &mut bad);
    if !bad.is_empty() {
        return Err(invalid(
            bad.iter()
                .map(|p| at(origin, text, p, "must be a finite number (nan/inf given)"))
                .collect(),
        ));
    }
    let robot: T = match toml::from_str(text) {
        Ok(r) => r,
        Err(e) => {
            let (loc, field) = span_location(text, origin, e.span());
            let message = basr_io::one_line(e.message());
            if let Some(missing) = dotted_missing(&message, text, e.span()) {
                return Err(invalid(vec![format!("{loc}: {missing}")]));
            }
            let field = field.map(|f| format!("field `{f}`: ")).unwrap_or_default();
            return Err(invalid(vec![format!(
                "{loc}: {field}{message}; compare with `basr robot --toml`"
            )]));
        }
    };
    let problems = validate(&robot);
    if problems.is_empty() {
        Ok(robot)
    } else {
        Err(invalid(
            problems
                .iter()
                .map(|(p, w)| at(origin, text, p, w))
                .collect(),
        ))
    }
}

/// Semantic checks: (dotted field, what is wrong and how to fix it).
pub(crate) fn validate(r: &Robot) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = r.dynamics.problems();
    out.extend(super::ranges::problems(r));
    let mut positive = |path: &str, v: f64| {
        // Values are finite here (checked before deserialising).
        if v <= 0.0 {
            out.push((
                path.into(),
                format!("must be positive (got {})", basr_io::show_num(v)),
            ));
        }
    };
    let a = &r.arm;
    positive("arm.pantograph_ratio", a.pantograph_ratio);
    positive("arm.retracted_extension_m", a.retracted_extension_m);
    positive("arm.cylinder_stroke_m", a.cylinder_stroke_m);
    positive("arm.base_motor_ratio", a.base_motor_ratio);
    let e = &r.end_effector;
    positive("end_effector.mass_kg", e.mass_kg);
    positive("end_effector.vertical_stroke_m", e.vertical_stroke_m);
    positive("end_effector.tip_height_top_m", e.tip_height_top_m);
    positive(
        "end_effector.vertical_disturbance_m",
        e.vertical_disturbance_m,
    );
    positive(
        "end_effector.vertical_disturbance_hz",
        e.vertical_disturbance_hz,
    );
    positive("end_effector.yaw_gear_ratio", e.yaw_gear_ratio);
    positive("end_effector.tilt_screw_pitch_m", e.tilt_screw_pitch_m);
    positive(
        "end_effector.tilt_motor_turns_per_screw_turn",
        e.tilt_motor_turns_per_screw_turn,
    );
    positive(
        "end_effector.tilt_nut_max_speed_mps",
        e.tilt_nut_max_speed_mps,
    );
    positive(
        "end_effector.nozzle_below_joint_f_m",
        e.nozzle_below_joint_f_m,
    );
    positive(
        "end_effector.joint_f_test_torque_nm",
        e.joint_f_test_torque_nm,
    );
    let f = &e.fourbar;
    positive("end_effector.fourbar.ground_m", f.ground_m);
    positive("end_effector.fourbar.coupler_m", f.coupler_m);
    positive("end_effector.fourbar.rocker_m", f.rocker_m);
    let p = &r.paint;
    positive("paint.flow_m3ps", p.flow_m3ps);
    positive("paint.transfer_efficiency", p.transfer_efficiency);
    positive("paint.film_m", p.film_m);
    positive("paint.tip_life_min_m3", p.tip_life_min_m3);
    positive("paint.tip_life_max_m3", p.tip_life_max_m3);
    let c = &r.control;
    positive("control.period_s", c.period_s);
    positive("control.controller_sample_s", c.controller_sample_s);
    positive("control.delay_estimate_s", c.delay_estimate_s);
    positive("control.accuracy_m", c.accuracy_m);
    let n = &r.encoders;
    positive("encoders.base_counts_per_rev", n.base_counts_per_rev.into());
    positive("encoders.extension_m_per_count", n.extension_m_per_count);
    positive(
        "encoders.yaw_counts_per_motor_rev",
        n.yaw_counts_per_motor_rev.into(),
    );
    positive(
        "encoders.tilt_counts_per_motor_rev",
        n.tilt_counts_per_motor_rev.into(),
    );
    positive("encoders.vertical_m_per_count", n.vertical_m_per_count);
    let h = &r.hydraulics;
    for (name, v) in [
        ("supply_pa", h.supply_pa),
        ("tank_pa", h.tank_pa),
        ("bulk_modulus_pa", h.bulk_modulus_pa),
        (
            "base_motor_displacement_m3prad",
            h.base_motor_displacement_m3prad,
        ),
        ("base_chamber_a_m3", h.base_chamber_a_m3),
        ("base_chamber_b_m3", h.base_chamber_b_m3),
        ("valve_flow_gain", h.valve_flow_gain),
        ("command_limit", h.command_limit),
        ("gravity_b_n", h.gravity_b_n),
        ("gravity_d_m", h.gravity_d_m),
        ("gravity_x_min_m", h.gravity_x_min_m),
        ("gravity_x_max_m", h.gravity_x_max_m),
    ] {
        positive(&format!("hydraulics.{name}"), v);
    }
    for (name, l) in r.limits.iter() {
        let base = format!("limits.{name}");
        positive(&format!("{base}.max_vel"), l.max_vel);
        positive(&format!("{base}.max_acc"), l.max_acc);
    }

    let mut push = |path: &str, what: String| out.push((path.into(), what));
    if e.yaw_backlash_rad < 0.0 {
        push(
            "end_effector.yaw_backlash_rad",
            "must not be negative".into(),
        );
    }
    let (xs, ys) = (&e.joint_f_deflection_extension_m, &e.joint_f_deflection_rad);
    if xs.len() != ys.len() || xs.is_empty() {
        push(
            "end_effector.joint_f_deflection_rad",
            format!(
                "needs one value per joint_f_deflection_extension_m entry ({} given for {})",
                ys.len(),
                xs.len()
            ),
        );
    }
    if xs.windows(2).any(|w| w[0] >= w[1]) {
        push(
            "end_effector.joint_f_deflection_extension_m",
            "extensions must increase".into(),
        );
    }
    if ys.iter().any(|&y| y < 0.0) {
        push(
            "end_effector.joint_f_deflection_rad",
            "deflections must not be negative".into(),
        );
    }
    if f.tip_below_coupler_m < 0.0 {
        push(
            "end_effector.fourbar.tip_below_coupler_m",
            "must not be negative (the nozzle hangs below the coupler)".into(),
        );
    }
    if !(p.fan_angle_rad > 0.0 && p.fan_angle_rad < std::f64::consts::PI) {
        push(
            "paint.fan_angle_rad",
            format!(
                "must be between 0 and π (got {}); give the fan angle in radians, e.g. 1.1083 for 63.5°",
                basr_io::show_num(p.fan_angle_rad)
            ),
        );
    }
    if p.transfer_efficiency > 1.0 {
        push(
            "paint.transfer_efficiency",
            format!(
                "must be at most 1 (got {})",
                basr_io::show_num(p.transfer_efficiency)
            ),
        );
    }
    if p.tip_life_min_m3 > p.tip_life_max_m3 {
        push(
            "paint.tip_life_min_m3",
            format!(
                "reversed range: tip_life_min_m3 {} > tip_life_max_m3 {}; swap them",
                p.tip_life_min_m3, p.tip_life_max_m3
            ),
        );
    }
    for (path, what) in p.tip_problems() {
        push(&path, what);
    }
    match (p.height_law_c0_m, p.height_law_c1) {
        (Some(_), None) => push(
            "paint.height_law_c0_m",
            "given without paint.height_law_c1: give both or neither".into(),
        ),
        (None, Some(_)) => push(
            "paint.height_law_c1",
            "given without paint.height_law_c0_m: give both or neither".into(),
        ),
        (Some(_), Some(c1)) if c1 <= 0.0 => push(
            "paint.height_law_c1",
            format!("must be positive (height grows with width; got {c1})"),
        ),
        _ => {}
    }
    if h.tank_pa >= h.supply_pa {
        push(
            "hydraulics.tank_pa",
            format!(
                "must be below hydraulics.supply_pa ({} ≥ {})",
                h.tank_pa, h.supply_pa
            ),
        );
    }
    if h.gravity_x_min_m >= h.gravity_x_max_m {
        push(
            "hydraulics.gravity_x_min_m",
            "reversed range: must be below gravity_x_max_m".into(),
        );
    }
    if h.gravity_x_max_m >= 2.0 * h.gravity_d_m {
        push(
            "hydraulics.gravity_x_max_m",
            "must be below 2·gravity_d_m (F(x) = B·x/√(4d² − x²))".into(),
        );
    }

    // Ranges.
    let order = |name: &str, l: &JointLimit, push: &mut dyn FnMut(&str, String)| {
        if l.min >= l.max {
            push(
                &format!("limits.{name}.min"),
                format!(
                    "reversed range: min {} is not below max {}; swap them",
                    l.min, l.max
                ),
            );
        }
    };
    for (name, l) in r.limits.iter() {
        order(name, l, &mut push);
    }
    let lim = &r.limits;
    if lim.ee_yaw_rad.max - lim.ee_yaw_rad.min < std::f64::consts::PI {
        push(
            "limits.ee_yaw_rad.max",
            "the yaw range must span at least π so the fan can face every direction".into(),
        );
    }
    if lim.base_rot_rad.max - lim.base_rot_rad.min > 2.0 * std::f64::consts::PI {
        push(
            "limits.base_rot_rad.max",
            "the base window must span less than one turn".into(),
        );
    }
    if lim.extension_m.min < a.retracted_extension_m - 1e-9 {
        push(
            "limits.extension_m.min",
            format!(
                "{} is below arm.retracted_extension_m {} (the cylinder cannot retract further)",
                lim.extension_m.min, a.retracted_extension_m
            ),
        );
    }
    let rmax = r.max_planned_extension_m();
    if lim.extension_m.max > rmax + 1e-9 {
        push(
            "limits.extension_m.max",
            format!(
                "{} is beyond what the cylinder gives short of its end stop: retracted_extension_m + \
                 pantograph_ratio·(cylinder_stroke_m − cylinder_stroke_margin_m) = {rmax}; lower it \
                 to that",
                lim.extension_m.max
            ),
        );
    }
    if lim.extension_m.min <= a.a2_m.abs() {
        push(
            "limits.extension_m.min",
            "must exceed |arm.a2_m| so the inverse kinematics are unique".into(),
        );
    }
    if lim.vertical_m.min < 0.0 || lim.vertical_m.max > e.vertical_stroke_m + 1e-12 {
        push(
            "limits.vertical_m.max",
            format!(
                "the vertical range must lie within 0..end_effector.vertical_stroke_m ({})",
                e.vertical_stroke_m
            ),
        );
    }
    // The tilt linkage must assemble and the nut map stay monotonic over the
    // tilt range, or tilt ↔ nut would not be a function.
    if f.rocker_m > 0.0
        && f.coupler_m > 0.0
        && f.ground_m > 0.0
        && lim.tilt_rad.min < lim.tilt_rad.max
    {
        if f.rocker_m <= 0.5 * f.coupler_m {
            push(
                "end_effector.fourbar.rocker_m",
                "must be longer than half the coupler (Roberts' coupler point)".into(),
            );
        } else {
            let steps = 64;
            let mut prev: Option<f64> = None;
            let mut sign = 0.0;
            for i in 0..=steps {
                let b = lim.tilt_rad.min
                    + (lim.tilt_rad.max - lim.tilt_rad.min) * i as f64 / steps as f64;
                match (f.solve(b, Assembly::Below), f.nut_m(b)) {
                    (Some(_), Some(n)) => {
                        if let Some(q) = prev {
                            let s = (n - q).signum();
                            if sign == 0.0 {
                                sign = s;
                            } else if s != sign {
                                push(
                                    "limits.tilt_rad.max",
                                    format!("the four-bar's nut motion reverses within the tilt range (at {:.1}°); narrow the range", b.to_degrees()),
                                );
                                break;
                            }
                        }
                        prev = Some(n);
                    }
                    _ => {
                        push(
                            "end_effector.fourbar",
                            format!(
                                "the linkage cannot be assembled at tilt {:.1}° within limits.tilt_rad; check the link lengths",
                                b.to_degrees()
                            ),
                        );
                        break;
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(find: &str, replace: &str) -> String {
        let t = super::super::BASR_TOML;
        assert!(t.contains(find), "{find}");
        t.replacen(find, replace, 1)
    }

    /// A plan into the cylinder's end stop is refused: the extension limit
    /// at the full stroke, or a margin no extension limit leaves room for,
    /// is named with the value to use.
    #[test]
    fn extension_into_the_stroke_margin_is_refused() {
        let text = with("max = 5.305416666666667", "max = 5.358333333333333");
        let p = check_source(&text, "bad.toml");
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(p[0].contains("limits.extension_m.max"), "{}", p[0]);
        assert!(
            p[0].contains("end stop") && p[0].contains("5.305416666666667"),
            "{}",
            p[0]
        );
        // Without the margin the full stroke is allowed again.
        let text = text.replacen(
            "cylinder_stroke_margin_m = 0.00635",
            "cylinder_stroke_margin_m = 0",
            1,
        );
        assert!(check_source(&text, "ok.toml").is_empty());
        let p = check_source(
            &with(
                "cylinder_stroke_margin_m = 0.00635",
                "cylinder_stroke_margin_m = 0.2",
            ),
            "bad.toml",
        );
        assert!(
            p.iter().any(|m| m.contains("arm.cylinder_stroke_margin_m")),
            "{p:?}"
        );
    }

    /// The shipped tips read back, the seed's first; a tip listed twice, a
    /// profile no preview takes and a fan angle in radians are each named.
    #[test]
    fn spray_tips_are_read_and_checked() {
        let r = parse(super::super::BASR_TOML, "basr.toml").unwrap();
        let names: Vec<&str> = r.paint.tips.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["seed-63.5", "511", "817", "509"]);
        assert_eq!(r.paint.tips[0].fan_angle_rad(), r.paint.fan_angle_rad);
        // mounting the tip [paint] already describes is consistent
        let seed = with(
            "profile = \"uniform\"\n",
            "profile = \"uniform\"\nmounted = \"seed-63.5\"\n",
        );
        assert!(check_source(&seed, "seed.toml").is_empty());
        for (find, replace, field) in [
            ("name = \"511\"", "name = \"817\"", "paint.tip[2].name"),
            (
                "profile = \"uniform\"\n\n# A wider",
                "profile = \"cone\"\n\n# A wider",
                "paint.tip[1].profile",
            ),
            (
                "fan_angle_deg = 63.5",
                "fan_angle_deg = 1.108",
                "paint.tip[0].fan_angle_deg",
            ),
            // [paint] is the seed's tip: mounting the 509 over it would
            // name one tip to the crew and plan with another's fan
            (
                "profile = \"uniform\"\n",
                "profile = \"uniform\"\nmounted = \"509\"\n",
                "paint.mounted",
            ),
        ] {
            let p = check_source(&with(find, replace), "bad.toml");
            assert!(p.iter().any(|m| m.contains(field)), "{field}: {p:?}");
        }
    }

    #[test]
    fn syntax_error_has_line_and_column() {
        let text = with("a2_m = 0.01", "a2_m = = 0.01");
        let p = check_source(&text, "bad.toml");
        assert_eq!(p.len(), 1);
        let line = text.lines().position(|l| l.contains("a2_m = =")).unwrap() + 1;
        assert!(p[0].starts_with(&format!("bad.toml:{line}:")), "{}", p[0]);
    }

    #[test]
    fn nan_names_field_and_line() {
        let text = with("mass_kg = 35.0", "mass_kg = nan");
        let p = check_source(&text, "bad.toml");
        let line = text
            .lines()
            .position(|l| l.contains("mass_kg = nan"))
            .unwrap()
            + 1;
        assert_eq!(p.len(), 1);
        assert!(p[0].starts_with(&format!("bad.toml:{line}: field `end_effector.mass_kg`")));
    }

    #[test]
    fn all_problems_reported_at_once() {
        let text = with("mass_kg = 35.0", "mass_kg = -35.0").replacen(
            "min = 1.55\nmax = 5.305416666666667",
            "min = 5.305416666666667\nmax = 1.55",
            1,
        );
        let p = check_source(&text, "bad.toml");
        assert!(p
            .iter()
            .any(|m| m.contains("`end_effector.mass_kg`") && m.contains("positive")));
        assert!(p
            .iter()
            .any(|m| m.contains("`limits.extension_m.min`") && m.contains("reversed")));
        let mass_line = text
            .lines()
            .position(|l| l.contains("mass_kg = -35"))
            .unwrap()
            + 1;
        assert!(p
            .iter()
            .any(|m| m.starts_with(&format!("bad.toml:{mass_line}:"))));
    }

    #[test]
    fn wrong_type_and_unknown_field_named() {
        let text = with("a2_m = 0.01", "a2_m = \"ten\"");
        let p = check_source(&text, "bad.toml");
        assert!(p[0].contains("`arm.a2_m`"), "{}", p[0]);
        let text = with("a2_m = 0.01", "a2_m = 0.01\na3_m = 1.0");
        let p = check_source(&text, "bad.toml");
        assert!(p[0].contains("a3_m"), "{}", p[0]);
    }

    #[test]
    fn missing_field_named() {
        let text = with("a2_m = 0.01\n", "");
        let p = check_source(&text, "bad.toml");
        assert!(p[0].contains("a2_m"), "{}", p[0]);
    }

    fn line_of(text: &str, needle: &str) -> usize {
        text.lines().position(|l| l.starts_with(needle)).unwrap() + 1
    }

    #[test]
    fn missing_field_has_its_dotted_name() {
        for (cut, dotted, table) in [
            ("mass_kg = 35.0\n", "end_effector.mass_kg", "[end_effector]"),
            (
                "rocker_m = 0.23\n",
                "end_effector.fourbar.rocker_m",
                "[end_effector.fourbar]",
            ),
            (
                "max_vel = 0.8\n",
                "limits.vertical_m.max_vel",
                "[limits.vertical_m]",
            ),
            ("name = \"BASR\"\n", "name", "#"),
        ] {
            let text = with(cut, "");
            let p = check_source(&text, "bad.toml");
            assert_eq!(p.len(), 1);
            let line = line_of(&text, table);
            assert!(
                p[0].starts_with(&format!("bad.toml:{line}:1: missing field `{dotted}`")),
                "{}",
                p[0]
            );
        }
    }

    #[test]
    fn nan_in_an_array_has_its_line() {
        let text = with(
            "joint_f_deflection_extension_m = [1.470",
            "joint_f_deflection_extension_m = [nan",
        );
        let p = check_source(&text, "bad.toml");
        let line = line_of(&text, "joint_f_deflection_extension_m");
        assert_eq!(
            p,
            [format!(
                "bad.toml:{line}: field `end_effector.joint_f_deflection_extension_m[0]`: \
                 must be a finite number (nan/inf given)"
            )]
        );
    }

    #[test]
    fn multi_line_syntax_message_is_one_line() {
        let text = with("a2_m = 0.01", "a2_m = [1,");
        let p = check_source(&text, "bad.toml");
        assert_eq!(p.len(), 1);
        assert!(!p[0].contains('\n'), "{}", p[0]);
        assert!(p[0].contains("invalid array; expected `]`"), "{}", p[0]);
    }
}
