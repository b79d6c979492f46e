//! One block of an OBJ file's lines, parsed without the rest of the file: what can be read
//! from a line alone (coordinates, the syntax of face corners, plain positive indices made
//! 0-based), the rest kept as written. Invariant: replaying a block's statements in order
//! (`Parser::replay`) does exactly what handing its lines to the parser one by one would, so
//! blocks may be parsed on any thread.

use crate::scene::text::{Tokens, next_line, parse_coord, parse_int, show, strip_comment};
use glam::DVec3;

/// Whether a line continues on the next (a trailing backslash before any comment).
pub(super) fn continues(line: &[u8]) -> bool {
    strip_comment(line).last() == Some(&b'\\')
}

/// A face corner as written: its vertex, texture and normal indices, not yet resolved against
/// what is defined before its line (`None`: not given).
#[derive(Clone, Copy)]
pub(super) struct RawCorner {
    pub(super) v: i64,
    pub(super) tex: Option<i64>,
    pub(super) nor: Option<i64>,
}

/// A statement (or a run of them) of a block, parsed without the rest of the file. Lines count
/// from 1 at the block's first line.
pub(super) enum Statement {
    /// `count` vertices on consecutive lines from `line`: the block's next `count` vertices.
    Vertices { line: usize, count: usize },
    /// A face of three or more corners given by positive vertex indices alone, the common
    /// case: its corners are the block's next `len` `corners` (0-based); `max` is the largest
    /// (1-based) index.
    Face { line: usize, len: usize, max: u32 },
    /// Any other face: its corners are the block's next `len` `raw` corners; `bad`: the syntax
    /// error of the corner after them, which ends the face.
    RawFace {
        line: usize,
        len: usize,
        bad: Option<String>,
    },
    /// Any other statement: the block's `text[start..end]`.
    Other {
        line: usize,
        start: usize,
        end: usize,
    },
    /// A `v` line with a bad or missing coordinate.
    BadVertex { line: usize, message: String },
}

/// The statements of one block of whole lines.
#[derive(Default)]
pub(super) struct Block {
    pub(super) statements: Vec<Statement>,
    pub(super) vertices: Vec<DVec3>,
    pub(super) corners: Vec<u32>,
    pub(super) raw: Vec<RawCorner>,
    /// The text of the `Other` statements (continued lines joined).
    pub(super) text: Vec<u8>,
    /// Physical lines in the block.
    pub(super) lines: usize,
}

impl Block {
    /// Parses the lines of `text` (whole lines; none continues past the end) into `self`.
    pub(super) fn parse(&mut self, text: &[u8]) {
        self.statements.clear();
        self.vertices.clear();
        self.corners.clear();
        self.raw.clear();
        self.text.clear();
        let mut joined: Vec<u8> = Vec::new();
        let (mut pos, mut line) = (0, 0);
        while pos < text.len() {
            let (raw, next) = next_line(text, pos);
            pos = next;
            line += 1;
            let start_line = line;
            let mut stripped = strip_comment(raw);
            if let Some(head) = stripped.strip_suffix(b"\\") {
                // Continuation: rare, so only this path copies.
                joined.clear();
                joined.extend_from_slice(head);
                joined.push(b' ');
                while pos < text.len() {
                    let (raw, next) = next_line(text, pos);
                    pos = next;
                    line += 1;
                    let t = strip_comment(raw);
                    if let Some(head) = t.strip_suffix(b"\\") {
                        joined.extend_from_slice(head);
                        joined.push(b' ');
                    } else {
                        joined.extend_from_slice(t);
                        break;
                    }
                }
                stripped = &joined;
            }
            self.statement(stripped, start_line);
        }
        self.lines = line;
    }

    fn statement(&mut self, text: &[u8], line: usize) {
        let mut toks = Tokens::new(text);
        let statement = match toks.next() {
            None => return,
            Some(b"v") => match vertex_coordinates(toks) {
                Ok(at) => {
                    self.vertices.push(DVec3::from_array(at));
                    if let Some(Statement::Vertices { line: first, count }) =
                        self.statements.last_mut()
                        && *first + *count == line
                    {
                        *count += 1;
                        return;
                    }
                    Statement::Vertices { line, count: 1 }
                }
                Err(message) => Statement::BadVertex { line, message },
            },
            Some(b"f") => self.face(toks, line),
            Some(_) => {
                let start = self.text.len();
                self.text.extend_from_slice(text);
                let end = self.text.len();
                Statement::Other { line, start, end }
            }
        };
        self.statements.push(statement);
    }

    /// A face: plain positive indices straight to 0-based corners, anything else as written.
    fn face(&mut self, toks: Tokens, line: usize) -> Statement {
        let start = self.corners.len();
        let mut max = 0;
        for t in toks.clone() {
            match plain_index(t) {
                Some(i) => {
                    max = max.max(i);
                    self.corners.push(i - 1);
                }
                None => {
                    self.corners.truncate(start);
                    return self.raw_face(toks, line);
                }
            }
        }
        let len = self.corners.len() - start;
        if len < 3 {
            self.corners.truncate(start);
            return self.raw_face(toks, line);
        }
        Statement::Face { line, len, max }
    }

    fn raw_face(&mut self, toks: Tokens, line: usize) -> Statement {
        let start = self.raw.len();
        let mut bad = None;
        for t in toks {
            match raw_corner(t) {
                Ok(c) => self.raw.push(c),
                Err(message) => {
                    bad = Some(message);
                    break;
                }
            }
        }
        let len = self.raw.len() - start;
        Statement::RawFace { line, len, bad }
    }
}

/// A corner that is a vertex index alone, in 1..=u32::MAX, written in decimal digits.
#[inline]
fn plain_index(t: &[u8]) -> Option<u32> {
    if t.is_empty() || t.len() > 10 {
        return None;
    }
    let mut v: u64 = 0;
    for &d in t {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v * 10 + (d - b'0') as u64;
    }
    u32::try_from(v).ok().filter(|&v| v > 0)
}

/// The three coordinates of a `v` line (anything after z, w or r g b colours, is ignored).
fn vertex_coordinates(mut toks: Tokens) -> Result<[f64; 3], String> {
    let mut c = [0.0f64; 3];
    for (i, slot) in c.iter_mut().enumerate() {
        let Some(t) = toks.next() else {
            return Err(format!("vertex has {i} coordinates, needs 3"));
        };
        *slot = parse_coord(t)?;
    }
    Ok(c)
}

/// A face corner's indices, or the message saying why it is not one.
fn raw_corner(t: &[u8]) -> Result<RawCorner, String> {
    let mut parts = t.split(|&b| b == b'/');
    let v = parts.next().unwrap_or(&[]);
    let tex = parts.next();
    let nor = parts.next();
    if parts.next().is_some()
        || tex.is_some_and(|p| !p.is_empty() && parse_int(p).is_none())
        || nor.is_some_and(|p| !p.is_empty() && parse_int(p).is_none())
    {
        return Err(format!(
            "bad face corner '{}' (expected v, v/t, v//n or v/t/n)",
            show(t)
        ));
    }
    let Some(v) = parse_int(v) else {
        return Err(format!("bad vertex index '{}'", show(t)));
    };
    let index = |p: Option<&[u8]>| p.filter(|p| !p.is_empty()).and_then(parse_int);
    Ok(RawCorner {
        v,
        tex: index(tex),
        nor: index(nor),
    })
}
