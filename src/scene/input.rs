//! An input file as a stream: lines and fixed-size records read from a [`BufRead`] in order, with
//! the byte offset of what has been read, so that the loaders hold only the scene they build and
//! one line at a time, never the whole (decompressed) file.
//!
//! Invariants: `pos` is the number of bytes of the (decompressed) data consumed so far, so a byte
//! offset in an error is an offset into the data as if it had been read whole; a leading UTF-8
//! byte-order mark is skipped by [`Input::line`] and counted in `pos`; after an I/O error every read
//! reports the end of the data and [`Input::finish`] turns the loader's result into that error,
//! whatever the loader concluded from the early end.

use crate::error::LoadError;
use std::io::{self, BufRead, Read};

/// The UTF-8 encoding of U+FEFF, which some editors write at the start of a text file.
pub(crate) const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Size of the read buffer: large enough that reading costs little next to parsing.
const BUFFER: usize = 1 << 20;

/// The longest line a text format may have. No mesh line comes near it; a longer one (a file
/// that is not text, or a comment of gigabytes) is an error rather than a line held whole.
pub(crate) const MAX_LINE: usize = 16 << 20;

/// The data, read through a buffer of its own (so that reading a value or finding a line end is
/// an inlined slice operation, whatever the reader behind it).
pub(crate) struct Input<R> {
    r: R,
    buf: Vec<u8>,
    /// The unread data is `buf[start..end]`.
    start: usize,
    end: usize,
    /// Bytes of the data before `buf[0]`.
    base: u64,
    /// Length of the data when known before reading it (a plain file, bytes in memory); `None`
    /// for a decompressed stream.
    len: Option<u64>,
    error: Option<io::Error>,
    eof: bool,
    /// Lines returned by [`Input::line`] so far.
    lines: u64,
}

impl<R: Read> Input<R> {
    pub(crate) fn new(r: R, len: Option<u64>) -> Self {
        let size = len.map_or(BUFFER, |l| {
            (l as usize).saturating_add(1).clamp(4096, BUFFER)
        });
        Input {
            r,
            buf: vec![0; size],
            start: 0,
            end: 0,
            base: 0,
            len,
            error: None,
            eof: false,
            lines: 0,
        }
    }

    /// Bytes consumed so far.
    pub(crate) fn pos(&self) -> u64 {
        self.base + self.start as u64
    }

    /// The length of the data, when known before reading it.
    pub(crate) fn len(&self) -> Option<u64> {
        self.len
    }

    /// Bytes left, when the length is known.
    pub(crate) fn left(&self) -> Option<u64> {
        self.len.map(|l| l.saturating_sub(self.pos()))
    }

    fn fail(&mut self, e: io::Error) {
        if self.error.is_none() {
            self.error = Some(e);
        }
    }

    #[inline]
    fn consume(&mut self, n: usize) {
        self.start += n;
    }

    /// Reads more data after what is unread (moved to the front of the buffer first). False when
    /// no more came: the end of the data, or an error.
    fn refill(&mut self) -> bool {
        if self.eof || self.error.is_some() {
            return false;
        }
        self.buf.copy_within(self.start..self.end, 0);
        self.base += self.start as u64;
        self.end -= self.start;
        self.start = 0;
        loop {
            match self.r.read(&mut self.buf[self.end..]) {
                Ok(0) => {
                    self.eof = true;
                    return false;
                }
                Ok(n) => {
                    self.end += n;
                    return true;
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => {
                    self.fail(e);
                    return false;
                }
            }
        }
    }

    /// Makes at least `n` unread bytes (at most the buffer's size, 4 KiB or more) available;
    /// false when the data ends first.
    fn fill_to(&mut self, n: usize) -> bool {
        while self.end - self.start < n {
            if !self.refill() {
                return false;
            }
        }
        true
    }

    /// Reads the next physical line into `out` (cleared first), without its `\n` and a `\r`
    /// before it; the first line loses a leading BOM. False at the end of the data, and after a
    /// line longer than [`MAX_LINE`] (an error for [`Input::finish`]).
    pub(crate) fn line(&mut self, out: &mut Vec<u8>) -> bool {
        out.clear();
        self.lines += 1;
        let first = self.pos() == 0;
        let mut any = false;
        loop {
            if self.start == self.end && !self.refill() {
                if !any {
                    return false;
                }
                break;
            }
            any = true;
            let avail = &self.buf[self.start..self.end];
            if let Some(i) = avail.iter().position(|&b| b == b'\n') {
                out.extend_from_slice(&avail[..i]);
                self.consume(i + 1);
                if out.last() == Some(&b'\r') {
                    out.pop();
                }
                break;
            }
            let n = avail.len();
            out.extend_from_slice(avail);
            self.consume(n);
            if out.len() > MAX_LINE {
                let message = format!(
                    "line {} is longer than {} MiB: not a mesh text file",
                    self.lines,
                    MAX_LINE >> 20
                );
                self.fail(io::Error::new(io::ErrorKind::InvalidData, message));
                out.clear();
                return false;
            }
        }
        if first && out.starts_with(BOM) {
            out.drain(..BOM.len());
        }
        true
    }

    /// Reads whole lines into `out` (cleared first), with their line ends: what the buffer holds
    /// up to its last `\n` (about [`BUFFER`] bytes), at least one line, and more while the last
    /// line read continues (`continues(line)`, the line without its `\r\n`). The first block
    /// loses a leading BOM. False at the end of the data, and after a line longer than
    /// [`MAX_LINE`] (an error for [`Input::finish`]). The lines of a block are the lines
    /// [`Input::line`] would have returned one by one.
    pub(crate) fn lines_block(&mut self, out: &mut Vec<u8>, continues: fn(&[u8]) -> bool) -> bool {
        out.clear();
        let first = self.pos() == 0;
        loop {
            if self.start == self.end && !self.refill() {
                break;
            }
            let avail = &self.buf[self.start..self.end];
            let taken = match avail.iter().rposition(|&b| b == b'\n') {
                Some(i) => i + 1,
                None => avail.len(),
            };
            let line_start = out.len();
            out.extend_from_slice(&avail[..taken]);
            self.consume(taken);
            self.lines += out[line_start..].iter().filter(|&&b| b == b'\n').count() as u64;
            let Some(body) = out.strip_suffix(b"\n") else {
                // No line end yet: one long line, or the last line of the data.
                let last = out.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
                if out.len() - last > MAX_LINE {
                    let message = format!(
                        "line {} is longer than {} MiB: not a mesh text file",
                        self.lines + 1,
                        MAX_LINE >> 20
                    );
                    self.fail(io::Error::new(io::ErrorKind::InvalidData, message));
                    out.clear();
                    return false;
                }
                continue;
            };
            let last = body.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
            let line = &body[last..];
            if !continues(line.strip_suffix(b"\r").unwrap_or(line)) {
                break;
            }
        }
        if first && out.starts_with(BOM) {
            out.drain(..BOM.len());
        }
        !out.is_empty()
    }

    /// Whether reading has failed.
    pub(crate) fn failed(&self) -> bool {
        self.error.is_some()
    }

    /// Drops a read error met after the data a loader stopped in (it read ahead): reading line
    /// by line would never have reached it, so the loader's own error is the file's first.
    pub(crate) fn forget_error(&mut self) {
        self.error = None;
    }

    /// The next `N` bytes, or `None` when fewer are left (then all of them are consumed).
    #[inline]
    pub(crate) fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        if self.end - self.start < N && !self.fill_to(N) {
            self.consume(self.end - self.start);
            return None;
        }
        let mut a = [0u8; N];
        a.copy_from_slice(&self.buf[self.start..self.start + N]);
        self.consume(N);
        Some(a)
    }

    /// Up to the first `n` (at most 4096) bytes of what is unread, without consuming them (for
    /// format detection).
    pub(crate) fn peek(&mut self, n: usize) -> &[u8] {
        self.fill_to(n);
        let end = self.end.min(self.start + n);
        &self.buf[self.start..end]
    }

    /// Whether no data is left.
    pub(crate) fn at_end(&mut self) -> bool {
        self.start == self.end && !self.refill()
    }

    /// Reads and drops everything left; returns how many bytes that was.
    pub(crate) fn skip_rest(&mut self) -> u64 {
        let mut n = 0;
        while !self.at_end() {
            let k = self.end - self.start;
            self.consume(k);
            n += k as u64;
        }
        n
    }

    /// Appends everything left to `out`.
    pub(crate) fn read_rest(&mut self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.buf[self.start..self.end]);
        self.consume(self.end - self.start);
        if self.eof || self.error.is_some() {
            return;
        }
        // Read past the buffer: it counts as consumed.
        match self.r.read_to_end(out) {
            Ok(n) => self.base += n as u64,
            Err(e) => self.fail(e),
        }
    }

    /// The loader's result, unless reading failed: then the read error (which explains any early
    /// end the loader saw).
    pub(crate) fn finish<T>(
        self,
        result: Result<T, LoadError>,
        name: &str,
    ) -> Result<T, LoadError> {
        match self.error {
            Some(e) => Err(LoadError::file(name, e.to_string())),
            None => result,
        }
    }
}

/// A reader over the file on disk that counts the bytes read and reports them, with the file's
/// size, to a progress callback; its read errors say "cannot read".
pub(crate) struct Progress<'a, R> {
    pub(crate) inner: R,
    pub(crate) read: u64,
    pub(crate) total: u64,
    pub(crate) on_progress: &'a mut dyn FnMut(u64, u64),
}

/// A read error of the file itself (as opposed to bad data inside it).
#[derive(Debug)]
pub(crate) struct ReadFailed(pub(crate) io::Error);

impl std::fmt::Display for ReadFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot read: {}", self.0)
    }
}

impl std::error::Error for ReadFailed {}

impl<R: Read> Read for Progress<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf).map_err(|e| match e.kind() {
            io::ErrorKind::Interrupted => e,
            k => io::Error::new(k, ReadFailed(e)),
        })?;
        self.read += n as u64;
        (self.on_progress)(self.read, self.total);
        Ok(n)
    }
}

/// A gzip decoder whose data errors say "bad gzip data" (read errors of the file pass through).
pub(crate) struct Gunzip<R>(pub(crate) flate2::bufread::MultiGzDecoder<R>);

impl<R: BufRead> Read for Gunzip<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.0.read(buf).map_err(|e| {
            if e.get_ref().is_some_and(|inner| inner.is::<ReadFailed>()) {
                e
            } else {
                io::Error::new(e.kind(), format!("bad gzip data: {e}"))
            }
        })
    }
}
