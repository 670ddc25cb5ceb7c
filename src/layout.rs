//! Message or marking file → glyphs placed in the road frame.
