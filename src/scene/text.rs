//! Byte-level text scanning shared by the text loaders (OBJ, MTL, ASCII STL, ASCII PLY): lines,
//! tokens and numbers, without allocating per line. Numbers parse exactly as Rust's `str::parse`.

use std::borrow::Cow;
use std::path::Path;

/// The physical line starting at `pos` (without its `\n` and a trailing `\r`) and the position
/// after it.
pub(crate) fn next_line(bytes: &[u8], pos: usize) -> (&[u8], usize) {
    let rest = bytes.get(pos..).unwrap_or(&[]);
    let (line, next) = match rest.iter().position(|&b| b == b'\n') {
        Some(i) => (&rest[..i], pos + i + 1),
        None => (rest, bytes.len()),
    };
    (line.strip_suffix(b"\r").unwrap_or(line), next)
}

/// The part of a line before a `#` comment, with trailing whitespace removed.
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    let line = match line.iter().position(|&b| b == b'#') {
        Some(i) => &line[..i],
        None => line,
    };
    trim(line)
}

pub(crate) fn trim(s: &[u8]) -> &[u8] {
    s.trim_ascii()
}

/// Whitespace-separated tokens of a line.
#[derive(Clone)]
pub(crate) struct Tokens<'a> {
    rest: &'a [u8],
}

impl<'a> Tokens<'a> {
    pub(crate) fn new(line: &'a [u8]) -> Self {
        Tokens { rest: line }
    }
    /// Everything after the tokens read so far, trimmed.
    pub(crate) fn rest(&self) -> &'a [u8] {
        trim(self.rest)
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a [u8];
    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        let start = self.rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let s = &self.rest[start..];
        let end = s
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(s.len());
        self.rest = &s[end..];
        Some(&s[..end])
    }
}

/// The first whitespace-separated token of `line` at or after `from`, as (start, end).
#[inline]
pub(crate) fn token_at(line: &[u8], from: usize) -> Option<(usize, usize)> {
    let rest = line.get(from..)?;
    let start = from + rest.iter().position(|b| !b.is_ascii_whitespace())?;
    let end = line[start..]
        .iter()
        .position(|b| b.is_ascii_whitespace())
        .map_or(line.len(), |n| start + n);
    Some((start, end))
}

/// A decimal float (anything `str::parse::<f64>` accepts, including `nan` and `inf`).
#[inline]
pub(crate) fn parse_f64(t: &[u8]) -> Option<f64> {
    std::str::from_utf8(t).ok()?.parse::<f64>().ok()
}

/// A finite coordinate, or the message saying what is wrong with it.
pub(crate) fn parse_coord(t: &[u8]) -> Result<f64, String> {
    match parse_f64(t) {
        None => Err(format!("bad number '{}'", show(t))),
        Some(x) if !x.is_finite() => Err(format!(
            "coordinate '{}' is not finite (NaN or infinity)",
            show(t)
        )),
        Some(x) => Ok(x),
    }
}

/// A decimal integer with an optional sign; `None` when malformed or beyond i64.
#[inline]
pub(crate) fn parse_int(t: &[u8]) -> Option<i64> {
    let (neg, digits) = match t.first()? {
        b'-' => (true, &t[1..]),
        b'+' => (false, &t[1..]),
        _ => (false, t),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_sub((d - b'0') as i64)?;
    }
    // Accumulated negatively so that i64::MIN parses.
    if neg { Some(v) } else { v.checked_neg() }
}

/// A token for a message: lossy UTF-8, shortened.
pub(crate) fn show(t: &[u8]) -> String {
    const MAX: usize = 40;
    let s = String::from_utf8_lossy(&t[..t.len().min(MAX)]);
    if t.len() > MAX {
        format!("{s}...")
    } else {
        s.into_owned()
    }
}

pub(crate) fn lossy(t: &[u8]) -> Cow<'_, str> {
    String::from_utf8_lossy(t)
}

/// The last component of a source name, used to name a mesh that the file does not name.
pub(crate) fn file_label(name: &str) -> String {
    Path::new(name)
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| name.to_string())
}
