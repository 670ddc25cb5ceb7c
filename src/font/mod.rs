//! Font files, the five primitives of 001 fig. 2.4, glyphs and their validation.
