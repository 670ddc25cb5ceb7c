//! SVG drawing shared by glyphs, preview, simulate and workspace.
