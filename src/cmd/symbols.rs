//! `basr symbols`: list the symbol library, export it as JSON, draw its sheet.

use std::path::PathBuf;

use anyhow::Context;
use basr::font::{feet_inches, symbol_sheet, Library, Symbol};
use serde_json::json;

use super::{Global, Outcome};

#[derive(clap::Args)]
#[command(after_help = "Examples:
  basr symbols
  basr symbols --svg symbols.svg
  basr symbols --json | jq '.symbols[] | {name, width_m, length_m}'
  basr compile --symbol arrow-left")]
pub struct Args {
    /// Print the library as JSON on stdout: {"library", "symbols": [{"name",
    /// "width_m", "length_m", "area_m2", "source", "assumed", "strokes":
    /// [{"left": [[x, y], ...], "right": [...]}]}]}, 64 points per edge.
    #[arg(long)]
    pub json: bool,
    /// Write the symbol sheet (outlines, rungs, stroke order, dimensions) to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

fn symbol_json(s: &Symbol) -> serde_json::Value {
    json!({
        "name": s.name,
        "description": s.description,
        "width_m": s.size_m[0],
        "length_m": s.size_m[1],
        "area_m2": s.area_m2(),
        "source": s.source,
        "assumed": s.assumed,
        "strokes": super::glyphs::strokes_json(&s.strokes),
    })
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let lib = Library::embedded();
    if let Some(path) = &args.svg {
        let doc = symbol_sheet(lib);
        basr::io::write_atomic(path, doc.to_string().as_bytes())
            .with_context(|| format!("writing the symbol sheet to {}", path.display()))?;
        if !global.quiet {
            note!(
                "wrote {} ({} symbols)",
                path.display(),
                lib.symbols().count()
            );
        }
    }
    if args.json {
        let doc = json!({
            "library": { "name": lib.name, "sha256": lib.sha256, "origin": lib.origin },
            "symbols": lib.symbols().map(symbol_json).collect::<Vec<_>>(),
        });
        basr::io::print_stdout(&(serde_json::to_string(&doc)? + "\n"))?;
    } else if args.svg.is_none() && !global.quiet {
        note!(
            "symbol library {}, embedded {}, sha256 {}",
            lib.name,
            lib.origin,
            lib.sha256
        );
        for s in lib.symbols() {
            note!(
                "{:22} {:>2} strokes  {} × {}  {:.2} m²{}",
                s.name,
                s.strokes.len(),
                feet_inches(s.size_m[0]),
                feet_inches(s.size_m[1]),
                s.area_m2(),
                if s.assumed.is_some() {
                    "  (assumed)"
                } else {
                    ""
                }
            );
            note!("    {}", s.source);
        }
    }
    Ok(Outcome::Success)
}
