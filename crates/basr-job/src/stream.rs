//! A job's canonical bytes (`canonical`, docs/job-canonical-form.md)
//! written as they are made, never held whole.
//!
//! The canonical form is serde_json's pretty print of the job's JSON value
//! (object keys in byte order) and a line end. Built as a value first, a
//! long job's samples were most of compile's memory: the 200-letter job's
//! 134 MB file took a value tree several times that and the bytes on top.
//! Here the job is made a value without its samples (they serialise as
//! `{}` meanwhile), printed, and written around the samples' place; the
//! samples are printed column by column, in the order of their names, at
//! their depth: the same bytes, a column at a time.

use std::cell::Cell;
use std::io::{self, Write};

use serde::{Serialize, Serializer};

use crate::{Job, Samples};

thread_local! {
    /// While set, a job's samples serialise as `{}` ([`write_canonical`]
    /// prints them itself).
    static ELIDED: Cell<bool> = const { Cell::new(false) };
}

/// Sets [`ELIDED`] while alive, whatever ends its scope.
struct Elided;

impl Elided {
    fn on() -> Elided {
        ELIDED.with(|e| e.set(true));
        Elided
    }
}

impl Drop for Elided {
    fn drop(&mut self) {
        ELIDED.with(|e| e.set(false));
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

/// A column of the samples, printed as serde_json's pretty printer prints
/// it at depth 0.
pub(crate) trait Column {
    fn write_pretty(&self, w: &mut dyn Write) -> io::Result<()>;
}

impl<T: Serialize> Column for T {
    fn write_pretty(&self, w: &mut dyn Write) -> io::Result<()> {
        serde_json::to_writer_pretty(w, self).map_err(io::Error::other)
    }
}

/// A writer that indents every line after the first by `indent` more.
struct Indented<'a> {
    inner: &'a mut dyn Write,
    indent: &'static [u8],
}

impl Write for Indented<'_> {
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
const PLACE: &[u8] = b"\n  \"samples\": {}";

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
    let Some(at) = head.windows(PLACE.len()).position(|w| w == PLACE) else {
        // `samples` skipped: the job without it, as printed
        w.write_all(&head)?;
        return w.write_all(b"\n");
    };
    w.write_all(&head[..at + PLACE.len() - 2])?;
    write_samples(&job.samples, w)?;
    w.write_all(&head[at + PLACE.len()..])?;
    w.write_all(b"\n")
}

/// The samples object as the pretty printer prints it as a top-level
/// member's value: keys four spaces in, elements six.
fn write_samples(s: &Samples, w: &mut dyn Write) -> io::Result<()> {
    let mut first = true;
    w.write_all(b"{")?;
    s.each_column_sorted(&mut |name, column| {
        w.write_all(if first { b"\n    " } else { b",\n    " })?;
        first = false;
        serde_json::to_writer(&mut *w, name).map_err(io::Error::other)?;
        w.write_all(b": ")?;
        column.write_pretty(&mut Indented {
            inner: &mut *w,
            indent: b"    ",
        })
    })?;
    if first {
        w.write_all(b"}")
    } else {
        w.write_all(b"\n  }")
    }
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
        let mut out = Vec::new();
        write_canonical(job, &mut out, &["samples", "sha256"]).unwrap();
        let mut less = v;
        less.as_object_mut().unwrap().remove("samples");
        less.as_object_mut().unwrap().remove("sha256");
        assert_eq!(out, crate::canonical::to_canonical(&less));
    }
}
