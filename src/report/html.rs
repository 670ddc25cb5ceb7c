//! The sheet as one self-contained HTML page: inline CSS, the film picture
//! as inline SVG, no script, nothing fetched (a truck has no network). It
//! prints on A4 or Letter; sections do not break across pages.

use std::fmt::Write as _;

use super::{Sheet, SimVerdict};
use crate::job::Severity;

/// Text for HTML: `&`, `<`, `>`, `"` escaped.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

const STYLE: &str = "
body { font-family: 'DejaVu Sans', Arial, sans-serif; color: #1a1a1a; margin: 2em auto;
       max-width: 60em; padding: 0 1em; line-height: 1.35; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.15em; border-bottom: 2px solid #1a1a1a; padding-bottom: 0.1em; margin-top: 1.4em; }
table { border-collapse: collapse; margin: 0.4em 0; }
th, td { border: 1px solid #999; padding: 0.2em 0.6em; text-align: left; vertical-align: top; }
th { background: #eee; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.overall { font-size: 1.3em; font-weight: bold; padding: 0.4em 0.8em; display: inline-block;
           border: 3px solid; }
.ready { color: #1a7f37; } .ready-with-notes { color: #9a6700; } .not-ready { color: #cf222e; }
.pass { color: #1a7f37; font-weight: bold; } .fail { color: #cf222e; font-weight: bold; }
.problem { color: #cf222e; } .notice { color: #9a6700; } .info { color: #57606a; }
ol.stops li { margin-bottom: 0.5em; }
.chalk { display: flex; gap: 0.6em; align-items: flex-start; margin: 0.2em 0; }
.chalk svg { flex: none; border: 1px solid #ccc; width: 130px; height: 130px; }
.chalk p { margin: 0; font-size: 0.85em; }
p.fit { font-size: 0.85em; }
p.facts { font-size: 0.85em; margin: 0.8em 0 0.3em; }
figure { margin: 0.5em 0; }
figure svg { max-width: 100%; height: auto; border: 1px solid #ccc; }
section { break-inside: avoid; }
#first { font-weight: bold; margin: 0.4em 0; }
ol.groups li { margin-bottom: 0.4em; }
#appendix { font-size: 0.85em; }
#appendix section { break-inside: auto; }
h2.appendix { border-bottom: 3px double #1a1a1a; }

.sign td { height: 2.2em; min-width: 14em; }
@media print { body { margin: 0; max-width: none; font-size: 10pt; line-height: 1.25; }
                a { color: inherit; } h2 { margin-top: 0.6em; } .sign td { height: 1.7em; }
                table { margin: 0.2em 0; } ol.stops li { margin-bottom: 0.3em; }
                h1 { margin: 0 0 0.1em; } p.fit { margin: 0.2em 0; } .sign { break-inside: avoid; }
                .chalk svg { width: 64px; height: 64px; }
                #appendix { break-before: page; }
                #appendix figure svg { max-height: 9.5cm; width: auto; } }
";

fn minutes(s: f64) -> String {
    format!("{:.1} min", s / 60.0)
}

fn pass_fail(pass: bool) -> &'static str {
    if pass {
        "<span class=\"pass\">PASS</span>"
    } else {
        "<span class=\"fail\">FAIL</span>"
    }
}

fn row(out: &mut String, label: &str, value_html: &str) {
    let _ = writeln!(
        out,
        "<tr><th>{}</th><td>{value_html}</td></tr>",
        escape(label)
    );
}

fn summary(out: &mut String, s: &Sheet) {
    out.push_str("<section id=\"summary\"><h2>At a glance</h2><table>\n");
    row(out, "time on site", &minutes(s.time_on_site_s));
    row(
        out,
        "paint",
        &format!("{:.2} L (have at least this in the tank)", s.paint_m3 * 1e3),
    );
    let tip =
        match s.tip_left_m3 {
            Some((lo, hi)) if lo <= 0.0 => format!(
            "<span class=\"fail\">replace the tip{}</span>: after this job {:.1}–{:.1} L of its \
             {:.0}–{:.0} L life are left",
            if hi <= 0.0 { " before this job" } else { " soon" },
            lo.max(0.0) * 1e3,
            hi.max(0.0) * 1e3,
            s.tip_life_m3.0 * 1e3,
            s.tip_life_m3.1 * 1e3
        ),
            Some((lo, hi)) => format!(
                "{:.1}–{:.1} L of the tip's {:.0}–{:.0} L life left after this job",
                lo * 1e3,
                hi * 1e3,
                s.tip_life_m3.0 * 1e3,
                s.tip_life_m3.1 * 1e3
            ),
            None => format!(
            "a tip lasts {:.0}–{:.0} L; keep a tally (<code>--tip-tally FILE</code>) to see what \
             is left",
            s.tip_life_m3.0 * 1e3,
            s.tip_life_m3.1 * 1e3
        ),
        };
    // which tip, before how long it lasts: a job may call for another tip
    // than the one on the gun
    let tip = match &s.tip {
        Some(name) => format!("mount {}; {tip}", escape(name)),
        None => tip,
    };
    row(out, "spray tip", &tip);
    let film = if s.film_verdict.pass() {
        format!(
            "{} (evenness, coverage and overspray within the limits)",
            pass_fail(true)
        )
    } else {
        format!(
            "{}: {}",
            pass_fail(false),
            escape(&s.film_verdict.reasons())
        )
    };
    row(out, "paint film (preview)", &film);
    row(out, "arm accuracy (simulate)", &sim_text(s.sim.as_ref()));
    out.push_str("</table></section>\n");
}

fn sim_text(sim: Option<&SimVerdict>) -> String {
    match sim {
        None => "not simulated (run without <code>--no-sim</code>, or give \
                 <code>--sim FILE</code> from <code>basr simulate --json</code>)"
            .into(),
        Some(v) => {
            // What the verdict judged first: a run over plants fails on
            // their 95th percentile while the description's own run, the
            // figure that follows, may be well within the tolerance.
            let on = match v.verdict_on {
                Some(crate::sim::report::VerdictOn::PlantsP95) => {
                    " on the arm as it may be (the plants' 95th percentile)"
                }
                _ => "",
            };
            let mut t = format!(
                "{}{on}: nozzle within {:.2} mm of the plan (RMS {:.2} mm) against {:.2} mm \
                 on the robot as described, controller {}",
                pass_fail(v.verdict == crate::sim::report::Verdict::Pass),
                v.max_error_m * 1e3,
                v.rms_error_m * 1e3,
                v.tolerance_m * 1e3,
                escape(&v.controller)
            );
            for r in &v.reasons {
                let _ = write!(t, ";<br>{}", escape(r));
            }
            t
        }
    }
}

fn stops(out: &mut String, s: &Sheet) {
    out.push_str("<section id=\"stops\"><h2>Where the truck stops</h2><ol class=\"stops\">\n");
    for st in &s.stops {
        let _ = write!(
            out,
            "<li><strong>Stop {}.</strong> {} <em>The arm works here {}.</em>",
            st.number,
            escape(&st.instruction),
            minutes(st.work_s)
        );
        if let Some(c) = s.chalk.iter().find(|c| c.stop == st.number) {
            super::site::render(out, c);
        }
        out.push_str("</li>\n");
    }
    let _ = writeln!(
        out,
        "</ol><p class=\"fit\" id=\"fit\"><strong>If the truck stops off its place:</strong> {}</p></section>",
        escape(&s.fit_steps)
    );
}

fn film(out: &mut String, s: &Sheet) {
    out.push_str("<section id=\"film\"><h2>The paint film</h2><table>\n");
    for (k, v) in &s.film_lines {
        row(out, k, &escape(v));
    }
    out.push_str("</table>\n<figure>\n");
    out.push_str(&s.film_svg);
    out.push_str(
        "<figcaption>The film the plan lays (preview): colour by thickness against the \
         target, letter outlines in red, the nozzle's path.</figcaption></figure>\n",
    );
    out.push_str(&letters_table(&s.letters, &s.film_verdict));
    out.push_str("</section>\n");
}

fn warnings(out: &mut String, s: &Sheet) {
    out.push_str("<section id=\"warnings\"><h2>Warnings, every one</h2>\n");
    if s.notes.is_empty() {
        out.push_str("<p>None.</p>");
    }
    for (severity, heading) in [
        (Severity::Problem, "Problems: fix before painting"),
        (
            Severity::Notice,
            "Notices: the marking comes out, slightly off the target here",
        ),
        (Severity::Info, "For information"),
    ] {
        let sev = severity.name();
        let list: Vec<_> = s.notes.iter().filter(|n| n.severity == severity).collect();
        if list.is_empty() {
            continue;
        }
        let _ = writeln!(
            out,
            "<h3 class=\"{sev}\">{heading} ({})</h3><ul>",
            list.len()
        );
        for n in list {
            let _ = writeln!(out, "<li class=\"{sev}\">{}</li>", escape(&n.text));
        }
        out.push_str("</ul>\n");
    }
    out.push_str("</section>\n");
}

/// Problems and notices, one line per kind, problems first and the most
/// frequent first; every single warning is in the appendix.
fn grouped(out: &mut String, s: &Sheet) {
    out.push_str("<section id=\"groups\"><h2>Warnings: fix these first, expect these</h2>\n");
    if s.groups.is_empty() {
        out.push_str("<p>No problem and no notice.</p></section>\n");
        return;
    }
    out.push_str("<ol class=\"groups\">\n");
    for g in &s.groups {
        let word = if g.severity == "problem" {
            "Problem (fix before painting)"
        } else {
            "Notice (comes out slightly off)"
        };
        let _ = writeln!(
            out,
            "<li class=\"{}\"><strong>{word}: {} ×{}</strong>. {}</li>",
            g.severity,
            escape(&g.what),
            g.count,
            escape(&g.example)
        );
    }
    out.push_str("</ol></section>\n");
}

/// The page: what the crew reads in a minute first (the word and the one
/// thing to do, what to paint, where to stop, what to load, the warnings
/// grouped), then the engineer's appendix (film figures and picture, every
/// warning, the job's identity).
pub fn render(s: &Sheet) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>basr job sheet: {t}</title><style>{STYLE}</style></head><body>\n\
         <header><h1>Job sheet: {t}</h1>\n<p class=\"overall {cls}\" id=\"overall\">{word}</p>\n\
         <p id=\"first\" class=\"{cls}\">{first}</p>\n</header>\n",
        t = escape(&s.title),
        cls = s.overall.replace(' ', "-"),
        word = s.overall.to_uppercase(),
        first = escape(&s.first),
    );
    summary(&mut out, s);
    out.push_str("<section id=\"items\"><h2>What to paint</h2><ul>\n");
    for i in &s.items {
        let _ = writeln!(out, "<li>{}</li>", escape(i));
    }
    out.push_str("</ul></section>\n");
    stops(&mut out, s);
    out.push_str("<section id=\"truck\"><h2>Load this on the truck</h2><ol>\n");
    for t in &s.truck {
        let _ = writeln!(out, "<li>{}</li>", escape(t));
    }
    out.push_str("</ol></section>\n");
    grouped(&mut out, s);
    // One line: the crew checks the file name and the signature; the rest
    // identifies the job for the engineer.
    out.push_str("<section id=\"job\"><p class=\"facts\"><strong>The job:</strong> ");
    let facts: Vec<String> = s
        .facts
        .iter()
        .map(|(k, v)| format!("{}: <strong>{}</strong>", escape(k), escape(v)))
        .collect();
    out.push_str(&facts.join(" · "));
    out.push_str("</p>\n</section>\n");
    out.push_str(
        "<table class=\"sign\"><tr><th>checked by</th><td></td><th>date</th><td></td>\
         </tr><tr><th>painted by</th><td></td><th>date</th><td></td></tr></table>\n",
    );
    out.push_str("<div id=\"appendix\"><h2 class=\"appendix\">Appendix for the engineer</h2>\n");
    film(&mut out, s);
    warnings(&mut out, s);
    out.push_str("</div>\n</body></html>\n");
    out
}

/// The letters' table of the sheet, each letter's figures against the
/// bounds the whole film is judged by, and the line that explains OVER.
fn letters_table(
    letters: &[super::Letter],
    film_verdict: &crate::paint::verdict::Verdict,
) -> String {
    let mut out = String::new();
    out.push_str(
        "<table id=\"letters\"><tr><th>line</th><th>letter</th><th></th><th>mean film</th>\
         <th>evenness (cv)</th><th>coverage</th><th>overspray</th><th>verdict</th></tr>\n",
    );
    // A figure past its bound in bold. A letter past a bound where the
    // whole film is within them all is a notice, not a failure: the film's
    // verdict (and the job's) judges the whole marking, and one letter's
    // figures, over a few thousand cells, scatter more (SCHOOL at 6 ft:
    // S and C at 3.0 and 3.3 % overspray, the word at 2.2 %).
    let pct = |c: &crate::paint::verdict::Check| {
        // two decimals where one would read as the limit itself (3.0 %
        // over a 3 % limit, or 3.0 % within it)
        let t = c.value.map_or("–".into(), |v| {
            let short = format!("{:.1}", v * 100.0);
            if short == format!("{:.1}", c.limit * 100.0) && v != c.limit {
                format!("{:.2} %", v * 100.0)
            } else {
                format!("{short} %")
            }
        });
        if c.pass {
            format!("<td class=\"num\">{t}</td>")
        } else {
            format!("<td class=\"num\"><strong>{t}</strong></td>")
        }
    };
    let film_passes = film_verdict.pass();
    for l in letters {
        let _ = writeln!(
            out,
            "<tr><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td>\
             <td class=\"num\">{}</td>{}<td>{}</td></tr>",
            l.line,
            l.place,
            escape(&l.char),
            l.mean_film_m
                .map_or("–".into(), |f| format!("{:.0} µm", f * 1e6)),
            l.checks.iter().map(pct).collect::<String>(),
            if !l.pass() && film_passes {
                "<span class=\"notice\"><strong>OVER</strong></span>"
            } else {
                pass_fail(l.pass())
            }
        );
    }
    out.push_str("</table>\n");
    if film_passes && letters.iter().any(|l| !l.pass()) {
        let t = &film_verdict.thresholds;
        let _ = writeln!(
            out,
            "<p class=\"notice\"><strong>OVER</strong>: that letter's own figure in bold is \
             past the limit the whole film is judged by (cv ≤ {:.0} %, coverage ≥ {:.0} %, \
             overspray ≤ {:.0} %); the film as a whole is within every limit, which is \
             what the film's verdict judges. Expect that letter slightly off there.</p>",
            t.cv_max * 100.0,
            t.coverage_min * 100.0,
            t.overspray_max * 100.0
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run over plants that fails says so first: the description's
    /// figure that follows is within the tolerance (SCHOOL at 6 ft on 10
    /// plants at spread 0.4: 4.30 mm on the description, p95 13.8 mm).
    #[test]
    fn the_arm_row_says_what_its_verdict_judged() {
        let v = |on| SimVerdict {
            job_sha256: None,
            controller: "sjct".into(),
            verdict: crate::sim::report::Verdict::Fail,
            reasons: vec!["the 95th percentile … exceeds the tolerance".into()],
            max_error_m: 4.3e-3,
            rms_error_m: 0.5e-3,
            tolerance_m: 6.35e-3,
            verdict_on: on,
        };
        let plants = sim_text(Some(&v(Some(crate::sim::report::VerdictOn::PlantsP95))));
        assert!(
            plants.contains("FAIL</span> on the arm as it may be"),
            "{plants}"
        );
        assert!(
            plants.contains("6.35 mm on the robot as described"),
            "{plants}"
        );
        assert!(plants.contains(";<br>the 95th percentile"), "{plants}");
        for on in [Some(crate::sim::report::VerdictOn::Nominal), None] {
            let t = sim_text(Some(&v(on)));
            assert!(t.contains("FAIL</span>: nozzle within 4.30 mm"), "{t}");
        }
    }

    /// A letter whose own figure is past a bound while the whole film is
    /// within them all is marked OVER, its figure in bold, with the line
    /// saying what that means; on a film that fails it reads FAIL.
    #[test]
    fn a_letter_past_a_bound_of_a_passing_film_is_over_not_fail() {
        use crate::paint::metrics::GlyphMetrics;
        use crate::paint::verdict::{glyph_checks, Thresholds, Verdict};
        let t = Thresholds::default();
        let letter = |ch: &str, overspray: f64| {
            let g = GlyphMetrics {
                char: ch.into(),
                line: 0,
                area_m2: 0.3,
                mean_film_m: Some(380e-6),
                cv: Some(0.04),
                coverage: Some(0.99),
                overspray: Some(overspray),
                u_min: None,
                u_max: None,
            };
            super::super::Letter {
                line: 1,
                place: 1,
                char: ch.into(),
                mean_film_m: g.mean_film_m,
                checks: glyph_checks(&g, &t),
            }
        };
        let letters = [letter("S", 0.020), letter("C", 0.033)];
        let verdict = |v| Verdict {
            verdict: v,
            thresholds: t,
            checks: vec![],
        };
        let html = letters_table(&letters, &verdict("pass"));
        let rows: Vec<&str> = html.split("<tr>").skip(2).collect();
        assert!(
            !rows[0].contains("OVER") && rows[0].contains("PASS"),
            "{html}"
        );
        assert!(rows[1].contains("<strong>OVER</strong>"), "{html}");
        assert!(rows[1].contains("<strong>3.3 %</strong>"), "{html}");
        assert!(!html.contains("FAIL"), "{html}");
        assert!(
            html.contains("the film as a whole is within every limit"),
            "{html}"
        );
        let html = letters_table(&letters, &verdict("fail"));
        assert!(!html.contains("OVER"), "{html}");
        assert!(html.contains("FAIL"), "{html}");
    }

    #[test]
    fn escape_covers_markup() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
    }
}
