//! A job's canonical bytes (`canonical`, docs/job-canonical-form.md)
//! written as they are made, never held whole.
//!
//! The canonical form is serde_json's pretty print of the job's JSON value
//! (object keys in byte order) and a line end. Built as a value first, a
//! long job's samples were most of compile's memory: the 200-letter job's
//! 134 MB file took a value tree several times that and the bytes on top
//! (its letters' outlines, `layout.glyphs`, another 17 MB of it). Here the
//! job is made a value without its samples and glyphs (they serialise as
//! `{}` and `[]` meanwhile), printed, and written around their places; the
//! samples are printed column by column, in the order of their names, and
//! the glyphs one by one, at their depth: the same bytes, a piece at a
//! time.

use std::cell::Cell;
use std::io::{self, Write};

use serde::{Serialize, Serializer};

use crate::{Job, PlacedGlyph, Samples};

thread_local! {
    /// While set, a job's samples serialise as `{}` and its layout's glyphs
    /// as `[]` ([`write_canonical`] prints them itself).
    static ELIDED: Cell<bool> = const { Cell::new(false) };
}

/// Sets [`ELIDED`] while alive and puts back what it was, whatever ends
/// its scope.
struct Elided(bool);

impl Elided {
    fn on() -> Elided {
        Elided(ELIDED.with(|e| e.replace(true)))
    }
}

impl Drop for Elided {
    fn drop(&mut self) {
        ELIDED.with(|e| e.set(self.0));
    }
}

/// `Job::samples`' serialiser: the samples, or `{}` while elided.
pub(crate) fn samples_unless_elided<S: Serializer>(s: &Samples, ser: S) -> Result<S::Ok, S::Error> {
    if ELIDED.with(Cell::get) {
        use serde::ser::SerializeMap;
        ser.serialize_map(Some(0))?.end()
    } else {
        s.serialize(ser)
    }
}

/// `Layout::glyphs`' serialiser: the glyphs, or `[]` while elided.
pub(crate) fn glyphs_unless_elided<S: Serializer>(
    g: &Vec<PlacedGlyph>,
    ser: S,
) -> Result<S::Ok, S::Error> {
    if ELIDED.with(Cell::get) {
        use serde::ser::SerializeSeq;
        ser.serialize_seq(Some(0))?.end()
    } else {
        g.serialize(ser)
    }
}

/// A column of the samples, printed as serde_json's pretty printer prints
/// it at depth 0, every line after the first `indent` further in.
pub(crate) trait Column {
    fn pretty(&self, indent: &[u8]) -> io::Result<Vec<u8>>;
}

impl<T: Serialize> Column for T {
    fn pretty(&self, indent: &[u8]) -> io::Result<Vec<u8>> {
        // Printed into memory, indented as it is printed (one buffer the
        // size of the column's text): printed into the output through a
        // `dyn Write`, each number and each line end was a write of its
        // own through two writers.
        let mut out = Vec::new();
        serde_json::to_writer_pretty(
            Indented {
                inner: &mut out,
                indent,
            },
            self,
        )
        .map_err(io::Error::other)?;
        Ok(out)
    }
}

/// A writer that indents every line after the first by `indent` more.
struct Indented<'a, W: Write + ?Sized> {
    inner: &'a mut W,
    indent: &'a [u8],
}

impl<W: Write + ?Sized> Write for Indented<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut rest = buf;
        while let Some(i) = rest.iter().position(|&b| b == b'\n') {
            self.inner.write_all(&rest[..=i])?;
            self.inner.write_all(self.indent)?;
            rest = &rest[i + 1..];
        }
        self.inner.write_all(rest)?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// Where the elided samples sit in the printed job: a top-level member
/// (two spaces in; a line end cannot occur inside a JSON string).
const SAMPLES: &[u8] = b"\n  \"samples\": {}";
/// The layout's place, and its glyphs' within it (the layout's first
/// member at four spaces in after it).
const LAYOUT: &[u8] = b"\n  \"layout\": {";
const GLYPHS: &[u8] = b"\n    \"glyphs\": []";

/// Where `pat` first occurs in `b` at or after `from`.
fn find(b: &[u8], pat: &[u8], from: usize) -> Option<usize> {
    b.get(from..)?
        .windows(pat.len())
        .position(|w| w == pat)
        .map(|i| i + from)
}

/// Writes `job`'s canonical bytes without its top-level members `skip`
/// (as `canonical::to_canonical` of its value with them removed).
pub(crate) fn write_canonical(job: &Job, w: &mut dyn Write, skip: &[&str]) -> io::Result<()> {
    let mut value = {
        let _elided = Elided::on();
        serde_json::to_value(job).map_err(io::Error::other)?
    };
    if let Some(members) = value.as_object_mut() {
        for key in skip {
            members.remove(*key);
        }
    }
    let head = serde_json::to_vec_pretty(&value).map_err(io::Error::other)?;
    drop(value);
    // The places, in the order of the bytes: (where the placeholder's
    // value starts, where it ends, what goes there).
    enum Piece {
        Samples,
        Glyphs,
    }
    let mut places: Vec<(usize, usize, Piece)> = Vec::new();
    if let Some(at) = find(&head, SAMPLES, 0) {
        places.push((at + SAMPLES.len() - 2, at + SAMPLES.len(), Piece::Samples));
    }
    if let Some(at) = find(&head, LAYOUT, 0).and_then(|l| find(&head, GLYPHS, l)) {
        places.push((at + GLYPHS.len() - 2, at + GLYPHS.len(), Piece::Glyphs));
    }
    places.sort_by_key(|p| p.0);
    let mut from = 0;
    for (start, end, piece) in places {
        w.write_all(&head[from..start])?;
        match piece {
            Piece::Samples => write_samples(&job.samples, w)?,
            Piece::Glyphs => write_glyphs(&job.layout.glyphs, w)?,
        }
        from = end;
    }
    w.write_all(&head[from..])?;
    w.write_all(b"\n")
}

/// The layout's glyphs as the pretty printer prints them as the value of
/// a member two deep: elements six spaces in, each its own value (keys in
/// order), printed one at a time.
fn write_glyphs(glyphs: &[PlacedGlyph], w: &mut dyn Write) -> io::Result<()> {
    if glyphs.is_empty() {
        return w.write_all(b"[]");
    }
    w.write_all(b"[")?;
    for (i, g) in glyphs.iter().enumerate() {
        w.write_all(if i == 0 { b"\n      " } else { b",\n      " })?;
        let value = serde_json::to_value(g).map_err(io::Error::other)?;
        serde_json::to_writer_pretty(
            &mut Indented {
                inner: &mut *w,
                indent: b"      ",
            },
            &value,
        )
        .map_err(io::Error::other)?;
    }
    w.write_all(b"\n    ]")
}

/// The samples object as the pretty printer prints it as a top-level
/// member's value: keys four spaces in, elements six. One column is held
/// printed at a time (about 7 MB on 200 letters): printing two at once on
/// two threads saved 45 ms of the seal's 375 and raised a 200-letter
/// compile's peak memory by 12 MB, to 1.48x its job file.
fn write_samples(s: &Samples, w: &mut dyn Write) -> io::Result<()> {
    let columns = s.columns_sorted();
    if columns.is_empty() {
        return w.write_all(b"{}");
    }
    w.write_all(b"{")?;
    for (k, (name, column)) in columns.iter().enumerate() {
        w.write_all(if k == 0 { b"\n    " } else { b",\n    " })?;
        serde_json::to_writer(&mut *w, name).map_err(io::Error::other)?;
        w.write_all(b": ")?;
        w.write_all(&column.pretty(b"    ")?)?;
    }
    w.write_all(b"\n  }")
}

/// The SHA-256 (hex) of `job`'s canonical bytes without the members
/// `skip`, hashed as they are made.
pub(crate) fn sha256_without(job: &Job, skip: &[&str]) -> String {
    let mut h = basr_io::Sha256Writer::default();
    write_canonical(job, &mut h, skip).expect("hashing takes every byte");
    h.hex()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The streamed bytes are the value's canonical bytes, with and without
    /// members, and the seal's hash is `document_sha256`'s.
    pub(crate) fn same_as_the_value(job: &Job) {
        let v = serde_json::to_value(job).unwrap();
        let mut out = Vec::new();
        write_canonical(job, &mut out, &[]).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            String::from_utf8(crate::canonical::to_canonical(&v)).unwrap()
        );
        assert_eq!(
            sha256_without(job, &["sha256", "signature"]),
            crate::document_sha256(v.clone())
        );
        for skip in [&["samples", "sha256"][..], &["layout"][..]] {
            let mut out = Vec::new();
            write_canonical(job, &mut out, skip).unwrap();
            let mut less = v.clone();
            for key in skip {
                less.as_object_mut().unwrap().remove(*key);
            }
            assert_eq!(out, crate::canonical::to_canonical(&less), "{skip:?}");
        }
    }
}
