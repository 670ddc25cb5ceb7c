//! `basr glyphs`: list a font's glyphs, export them as JSON, draw the alphabet sheet.

use std::path::PathBuf;

use anyhow::Context;
use basr::font::{Font, EMBEDDED_NAME};
use serde_json::json;

use super::{Global, Outcome};

/// Points per edge in `--json` (the issue asks for at least 50).
const JSON_POINTS: usize = 64;

/// List a font's glyphs; draw the alphabet sheet.
///
/// Lists each glyph with its stroke count and rung lengths; `--json`
/// prints every stroke's edges sampled at equal arc length (grid units:
/// x 0..4 right, y 0..25 up); `--svg` draws the alphabet sheet and says
/// only which file it wrote.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr glyphs\n  basr glyphs --svg alphabet.svg\n  \
                        basr glyphs --font my-font.toml --json > glyphs.json"
)]
pub struct Args {
    /// Font to use: the embedded font's name (`basr`) or a font file (TOML).
    #[arg(long, value_name = "NAME|FILE", default_value = EMBEDDED_NAME)]
    pub font: String,
    /// Print the glyphs as JSON on stdout: {"font", "glyphs": [{"char",
    /// "strokes": [{"left": [[x, y], ...], "right": [...]}]}]}, 64 points per edge.
    #[arg(long)]
    pub json: bool,
    /// Write the alphabet sheet (outlines, rungs, stroke order) to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

fn pts(v: Vec<kurbo::Point>) -> Vec<[f64; 2]> {
    v.into_iter().map(|p| [p.x, p.y]).collect()
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    if let Some(svg) = &args.svg {
        let font = std::path::Path::new(&args.font);
        super::refuse_clashes(&[("--svg", svg)], &[("the font file (--font)", font)])?;
        super::outputs::check("--svg", svg, &["svg"])?;
    }
    let font = Font::from_name_or_path(&args.font)?;
    if let Some(path) = &args.svg {
        let doc = basr::font::alphabet_sheet(&font);
        basr::io::write_atomic(path, doc.to_string().as_bytes())
            .with_context(|| format!("writing the alphabet sheet to {}", path.display()))?;
        if !global.quiet {
            let n = font.glyphs().count();
            let glyphs = if n == 1 { "glyph" } else { "glyphs" };
            super::outputs::after_commit(format!("wrote {} ({n} {glyphs})", path.display()));
        }
    }
    if args.json {
        let glyphs: Vec<_> = font
            .glyphs()
            .map(|g| {
                let strokes: Vec<_> = g
                    .strokes
                    .iter()
                    .map(|s| {
                        json!({
                            "left": pts(s.left.sample(JSON_POINTS)),
                            "right": pts(s.right.sample(JSON_POINTS)),
                        })
                    })
                    .collect();
                json!({ "char": g.ch.to_string(), "strokes": strokes })
            })
            .collect();
        let doc = json!({
            "font": { "name": font.name, "sha256": font.sha256 },
            "grid": { "width": basr::font::GRID_WIDTH, "height": basr::font::GRID_HEIGHT },
            "glyphs": glyphs,
        });
        basr::io::print_stdout(&(serde_json::to_string(&doc)? + "\n"))?;
    } else if args.svg.is_none() && !global.quiet {
        note!(
            "font {}, {}, sha256 {}",
            font.name,
            font.source_description(),
            font.sha256
        );
        for g in font.glyphs() {
            note!("{}", listing_line(g));
        }
    }
    Ok(Outcome::Success)
}

/// "B  6 strokes  rungs 1.00–4.00 units", "I  1 stroke  rungs 1.00 units".
fn listing_line(g: &basr::font::Glyph) -> String {
    let lengths: Vec<f64> = g
        .strokes
        .iter()
        .flat_map(|s| s.rungs(100))
        .map(|(a, b)| (b - a).hypot())
        .collect();
    let min = lengths.iter().copied().fold(f64::INFINITY, f64::min);
    let max = lengths.iter().copied().fold(0.0, f64::max);
    let (min, max) = (format!("{min:.2}"), format!("{max:.2}"));
    let rungs = if min == max {
        min
    } else {
        format!("{min}–{max}")
    };
    let n = g.strokes.len();
    let strokes = if n == 1 { "stroke" } else { "strokes" };
    format!("{}  {n} {strokes}  rungs {rungs} units", g.ch)
}
