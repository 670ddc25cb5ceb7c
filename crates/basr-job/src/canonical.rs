//! The canonical form of a job's bytes (docs/job-canonical-form.md): the
//! JSON value as serde_json's pretty printer writes it with object keys in
//! byte order, then one line end. Every reader refuses a job whose bytes are
//! not exactly that form; the hash and the signature cover those bytes.
//!
//! [`check`] walks the bytes once, without building the value: it verifies
//! each token against the form the printer would give it (the layout, a
//! strictly increasing key order, which also catches a duplicate key, the
//! string escapes, the number spelling) and returns the spans of the
//! top-level members, from which the bytes of the document without some of
//! them are put together for hashing and signing ([`without`]). Nothing in
//! here knows a job's keys: a field another stage adds is covered as is.

use std::ops::Range;

/// Nesting deeper than this is refused (serde_json's own parser stops at
/// 128; a job nests 5 deep).
const MAX_DEPTH: usize = 128;

/// Where and why the bytes are not canonical.
#[derive(Debug, Clone, PartialEq)]
pub struct NotCanonical {
    /// Byte offset of the first byte that differs from the canonical form.
    pub offset: usize,
    pub what: String,
    /// The bytes end before the document does.
    pub truncated: bool,
}

impl NotCanonical {
    /// 1-based line and column (in bytes) of the offset in `bytes`.
    pub fn line_col(&self, bytes: &[u8]) -> (usize, usize) {
        let before = &bytes[..self.offset.min(bytes.len())];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let col = before.iter().rev().take_while(|&&b| b != b'\n').count() + 1;
        (line, col)
    }
}

/// One top-level member: its key and the span of `"key": value`.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    pub key: String,
    pub span: Range<usize>,
    /// The value alone.
    pub value: Range<usize>,
}

type Result<T> = std::result::Result<T, NotCanonical>;

struct Walker<'a> {
    b: &'a [u8],
    i: usize,
}

impl Walker<'_> {
    fn fail<T>(&self, what: impl Into<String>) -> Result<T> {
        Err(NotCanonical {
            offset: self.i,
            what: what.into(),
            truncated: self.i >= self.b.len(),
        })
    }

    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    fn expect(&mut self, lit: &[u8], what: &str) -> Result<()> {
        for &c in lit {
            if self.peek() != Some(c) {
                return self.fail(format!("expected {what}"));
            }
            self.i += 1;
        }
        Ok(())
    }

    /// A line end and `depth` levels of two-space indentation.
    fn newline(&mut self, depth: usize) -> Result<()> {
        self.expect(b"\n", "a line end")?;
        for _ in 0..depth {
            self.expect(b"  ", "two spaces of indentation per level")?;
        }
        Ok(())
    }

    fn value(&mut self, depth: usize) -> Result<()> {
        if depth > MAX_DEPTH {
            return self.fail(format!("nesting deeper than {MAX_DEPTH} levels"));
        }
        match self.peek() {
            Some(b'{') => self.object(depth, |_, _, _| {}),
            Some(b'[') => self.array(depth),
            Some(b'"') => self.string().map(|_| ()),
            Some(b't') => self.expect(b"true", "`true`"),
            Some(b'f') => self.expect(b"false", "`false`"),
            Some(b'n') => self.expect(b"null", "`null`"),
            Some(b'-' | b'0'..=b'9') => self.number(),
            None => self.fail("a value"),
            Some(_) => self.fail("a value (object, array, string, number, true, false or null)"),
        }
    }

    /// An object at `depth`; `member(key, span)` sees each member of it.
    fn object(
        &mut self,
        depth: usize,
        mut member: impl FnMut(String, Range<usize>, Range<usize>),
    ) -> Result<()> {
        self.expect(b"{", "`{`")?;
        if self.peek() == Some(b'}') {
            self.i += 1;
            return Ok(());
        }
        // serde_json would keep the last of two equal keys and another
        // reader the first: every key of the object is looked for.
        let mut seen: Vec<String> = Vec::new();
        loop {
            self.newline(depth + 1)?;
            let start = self.i;
            let key = self.string()?;
            if seen.contains(&key) {
                self.i = start;
                return self.fail(format!("key {key:?} appears twice in one object"));
            }
            if let Some(prev) = seen.last().filter(|p| key.as_bytes() < p.as_bytes()) {
                self.i = start;
                return self.fail(format!(
                    "key {key:?} comes after {prev:?}: keys are in byte order"
                ));
            }
            self.expect(b": ", "`: ` after the key")?;
            let vstart = self.i;
            self.value(depth + 1)?;
            member(key.clone(), start..self.i, vstart..self.i);
            seen.push(key);
            match self.peek() {
                Some(b',') => self.i += 1,
                _ => break,
            }
        }
        self.newline(depth)?;
        self.expect(b"}", "`,` or `}`")
    }

    fn array(&mut self, depth: usize) -> Result<()> {
        self.expect(b"[", "`[`")?;
        if self.peek() == Some(b']') {
            self.i += 1;
            return Ok(());
        }
        loop {
            self.newline(depth + 1)?;
            self.value(depth + 1)?;
            match self.peek() {
                Some(b',') => self.i += 1,
                _ => break,
            }
        }
        self.newline(depth)?;
        self.expect(b"]", "`,` or `]`")
    }

    /// A string token, spelled as serde_json writes it; its decoded text.
    fn string(&mut self) -> Result<String> {
        let start = self.i;
        self.expect(b"\"", "a string")?;
        loop {
            match self.peek() {
                None => return self.fail("the closing `\"` of a string"),
                Some(b'"') => {
                    self.i += 1;
                    break;
                }
                Some(b'\\') => self.i += 2,
                Some(_) => self.i += 1,
            }
        }
        let token = &self.b[start..self.i.min(self.b.len())];
        let Ok(text) = serde_json::from_slice::<String>(token) else {
            self.i = start;
            return self.fail("a valid JSON string (escapes and UTF-8)");
        };
        let again = serde_json::to_vec(&text).expect("a string serialises");
        if again != token {
            self.i = start;
            return self.fail(format!(
                "the string spelled {} (escapes as serde_json writes them)",
                String::from_utf8_lossy(&again)
            ));
        }
        Ok(text)
    }

    /// A number token, spelled as serde_json writes the number it reads as.
    fn number(&mut self) -> Result<()> {
        let start = self.i;
        while matches!(
            self.peek(),
            Some(b'-' | b'+' | b'.' | b'e' | b'E' | b'0'..=b'9')
        ) {
            self.i += 1;
        }
        let token = &self.b[start..self.i];
        let text = std::str::from_utf8(token).unwrap_or_default();
        let Ok(n) = text.parse::<serde_json::Number>() else {
            self.i = start;
            return self.fail("a number");
        };
        let again = n.to_string();
        if again.as_bytes() != token {
            self.i = start;
            return self.fail(format!("the number spelled {again}, not {text}"));
        }
        Ok(())
    }
}

/// Verify that `bytes` are exactly the canonical form of one JSON object
/// and return its top-level members, in order.
pub fn check(bytes: &[u8]) -> Result<Vec<Member>> {
    let mut w = Walker { b: bytes, i: 0 };
    let mut members = Vec::new();
    w.object(0, |key, span, value| {
        members.push(Member { key, span, value })
    })?;
    w.expect(b"\n", "one line end after the closing `}`")?;
    if w.i != bytes.len() {
        return w.fail("the end of the file after the document's line end");
    }
    Ok(members)
}

/// The canonical bytes of the document without the top-level members
/// `skip`, as the pieces to feed a hash in order (no copy of the document).
pub fn without<'a>(bytes: &'a [u8], members: &[Member], skip: &[&str]) -> Vec<&'a [u8]> {
    let kept: Vec<&Member> = members
        .iter()
        .filter(|m| !skip.contains(&m.key.as_str()))
        .collect();
    if kept.is_empty() {
        return vec![b"{}\n"];
    }
    let mut pieces: Vec<&[u8]> = vec![b"{\n  "];
    for (k, m) in kept.iter().enumerate() {
        if k > 0 {
            pieces.push(b",\n  ");
        }
        pieces.push(&bytes[m.span.clone()]);
    }
    pieces.push(b"\n}\n");
    pieces
}

/// Canonical bytes of a JSON value (the form [`check`] accepts).
pub fn to_canonical(v: &serde_json::Value) -> Vec<u8> {
    let mut out = serde_json::to_vec_pretty(v).expect("a serde_json::Value always serialises");
    out.push(b'\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn canon(text: &str) -> Vec<u8> {
        to_canonical(&serde_json::from_str(text).unwrap())
    }

    #[test]
    fn the_printer_output_is_canonical() {
        let b = canon(
            r#"{"b": [1, 2.5, -0.0, 1e-7, 1e300, "x\n\u0001é"], "a": {}, "c": [], "d": {"z": null, "y": true}}"#,
        );
        let m = check(&b).unwrap();
        let keys: Vec<_> = m.iter().map(|m| m.key.as_str()).collect();
        assert_eq!(keys, ["a", "b", "c", "d"]);
        assert_eq!(&b[m[0].span.clone()], b"\"a\": {}");
        assert_eq!(&b[m[2].value.clone()], b"[]");
    }

    #[test]
    fn without_equals_the_printed_smaller_value() {
        let b = canon(r#"{"a": 1, "sha256": "x", "signature": {"k": 1}, "z": [1]}"#);
        let m = check(&b).unwrap();
        for skip in [
            &["sha256"][..],
            &["sha256", "signature"],
            &["a"],
            &["z"],
            &["a", "sha256", "signature", "z"],
        ] {
            let mut v: serde_json::Value = serde_json::from_slice(&b).unwrap();
            for k in skip {
                v.as_object_mut().unwrap().remove(*k);
            }
            assert_eq!(without(&b, &m, skip).concat(), to_canonical(&v), "{skip:?}");
        }
    }

    #[test]
    fn every_other_spelling_is_refused() {
        let good = String::from_utf8(canon(r#"{"a": 1.5e-7, "b": "x", "c": [1, 2]}"#)).unwrap();
        assert!(check(good.as_bytes()).is_ok());
        let cases = [
            (
                good.replacen("\"a\"", "\"b\": \"y\",\n  \"a\"", 1),
                "byte order",
            ),
            (good.replacen("\"b\"", "\"b\": \"y\",\n  \"b\"", 1), "twice"),
            (good.replacen("\"c\"", "\"a\": 1,\n  \"c\"", 1), "twice"),
            (good.replacen("1.5e-7", "1.5E-7", 1), "number"),
            (good.replacen("1.5e-7", "0.00000015", 1), "number"),
            (good.replacen("1.5e-7", "1.50e-7", 1), "number"),
            (good.replacen("\"x\"", "\"\\u0078\"", 1), "string"),
            (good.replacen(": ", ":", 1), "`: `"),
            (good.replacen("  \"a\"", "    \"a\"", 1), "a string"),
            (good.replacen("\n  \"c\"", " \"c\"", 1), "line end"),
            (good.trim_end().to_string(), "line end"),
            (good.clone() + "\n", "end of the file"),
            (
                good.replacen(
                    "\"a\": 1.5e-7,\n  \"b\": \"x\"",
                    "\"b\": \"x\",\n  \"a\": 1.5e-7",
                    1,
                ),
                "byte order",
            ),
            (
                serde_json::to_string(&serde_json::from_str::<serde_json::Value>(&good).unwrap())
                    .unwrap()
                    + "\n",
                "line end",
            ),
        ];
        for (text, says) in cases {
            assert_ne!(text, good);
            let e = check(text.as_bytes()).unwrap_err();
            assert!(e.what.contains(says), "{text:?}: {e:?}");
        }
        let cut = &good.as_bytes()[..good.len() / 2];
        assert!(check(cut).unwrap_err().truncated);
        let deep = "[".repeat(1000);
        assert!(check(format!("{{\n  \"a\": {deep}").as_bytes()).is_err());
    }
}
