//! STL loader (binary and ASCII), with its own parser so that errors name the byte or line.
//!
//! Guarantees of a scene returned from here: every coordinate is finite, every corner index is in
//! range, triangles keep the file's winding (the stored normals are ignored), and vertices with
//! bitwise-identical coordinates (after mapping -0.0 to 0.0) are one vertex, so that closedness
//! can be analysed on what is otherwise a triangle soup.
//!
//! Detection: a file whose size is exactly 84 + 50 x (the count at byte 80) is binary, even if it
//! starts with `solid` (many binary exporters write that into the header). Otherwise a file that
//! starts with `solid` (after an optional UTF-8 byte-order mark and whitespace) and has no NUL
//! byte in its first KiB is ASCII; anything else is binary. The data is streamed, so for a
//! gzipped file, whose decompressed size is not known before reading it, the first rule cannot
//! apply: there a `solid` start without a NUL byte in the first KiB means ASCII. The two rules
//! differ only for a binary file with a `solid` header and no NUL byte in its first KiB, which
//! needs more than 2^24 triangles (the count's high byte is not 0) and nearly a KiB of triangle
//! data without a zero byte; truncation of a gzipped binary STL is reported where the data ends.
//!
//! Lines may end in `\r\n`.
//!
//! Binary: one mesh named after the file. ASCII: each `solid` begins a mesh named after it;
//! keywords are case-insensitive and tokens may be split across lines in any way; a missing final
//! `endsolid` is a warning.

use super::input::{BOM, Input};
use super::text::{file_label, lossy, parse_f64, show};
use super::{Scene, SceneBuilder};
use crate::error::LoadError;
use glam::DVec3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};
use std::io::Read;
use std::ops::Range;

pub(super) fn load<R: Read>(mut input: Input<R>, name: &str) -> Result<Scene, LoadError> {
    let len = input.len();
    let result = if is_binary(input.peek(DETECT), len) {
        binary(&mut input, name)
    } else {
        ascii(&mut input, name)
    };
    input.finish(result, name)
}

/// How much of the start of the file the detection looks at for NUL bytes.
const DETECT: usize = 1024;

fn binary_count(bytes: &[u8]) -> Option<u32> {
    let c = bytes.get(80..84)?;
    Some(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

/// The detection rule (module docs), from the first [`DETECT`] bytes and the length of the data
/// when it is known.
fn is_binary(head: &[u8], len: Option<u64>) -> bool {
    if let (Some(count), Some(len)) = (binary_count(head), len)
        && 84 + 50 * count as u64 == len
    {
        return true;
    }
    let text = head.strip_prefix(BOM).unwrap_or(head);
    let text = text.trim_ascii_start();
    let solid = text
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case(b"solid"));
    // An ASCII STL never holds a NUL; a binary one nearly always does in its count field.
    !solid || head.contains(&0)
}

fn binary<R: Read>(input: &mut Input<R>, name: &str) -> Result<Scene, LoadError> {
    let Some(header) = input.take::<84>() else {
        let len = input.pos();
        return Err(LoadError::byte(
            name,
            0,
            format!(
                "truncated binary STL: the header and triangle count need 84 bytes, file has {len} bytes"
            ),
        ));
    };
    let count = binary_count(&header).unwrap_or(0);
    let needed = 84 + 50 * count as u64;
    let truncated = |len: u64| {
        let complete = (len - 84) / 50;
        LoadError::byte(
            name,
            84 + 50 * complete,
            format!(
                "truncated binary STL: expected {count} triangles ({needed} bytes), file has {len} bytes"
            ),
        )
    };
    // With the length known, truncation is reported before reading; otherwise where data ends.
    if let Some(len) = input.len()
        && len < needed
    {
        return Err(truncated(len));
    }
    if 3 * count as u64 > u32::MAX as u64 {
        // Corner indices in a scene are u32.
        return Err(LoadError::byte(
            name,
            80,
            format!("{count} triangles are more than a scene can hold"),
        ));
    }
    let mut b = SceneBuilder::new(name);
    if let Some(len) = input.len()
        && len > needed
    {
        b.warn(format!(
            "{name}: {} bytes after the last of {count} triangles ignored",
            len - needed
        ));
    }
    let material = b.default_material();
    b.begin_mesh(file_label(name));
    // The count is only trusted as far as the data it claims is known to exist.
    let trusted = if input.len().is_some() {
        count as usize
    } else {
        (count as usize).min(1 << 20)
    };
    let mut weld = Welder::with_capacity(trusted.saturating_mul(3) / 6);
    for t in 0..count as u64 {
        let offset = 84 + 50 * t;
        let Some(rec) = input.take::<50>() else {
            return Err(truncated(input.pos()));
        };
        let mut idx = [0u32; 3];
        for (k, i) in idx.iter_mut().enumerate() {
            let mut p = [0.0f64; 3];
            for (a, c) in p.iter_mut().enumerate() {
                let at = 12 + 12 * k + 4 * a;
                let v = f32::from_le_bytes([rec[at], rec[at + 1], rec[at + 2], rec[at + 3]]);
                if !v.is_finite() {
                    return Err(LoadError::byte(
                        name,
                        offset,
                        format!(
                            "triangle {} of {count}: vertex {} has a coordinate that is not finite ({v})",
                            t + 1,
                            k + 1
                        ),
                    ));
                }
                *c = v as f64;
            }
            *i = weld
                .vertex(&mut b, DVec3::from_array(p))
                .ok_or_else(|| LoadError::byte(name, offset, "too many vertices"))?;
        }
        b.add_face(&idx, material);
    }
    if input.len().is_none() {
        let extra = input.skip_rest();
        if extra > 0 {
            b.warn(format!(
                "{name}: {extra} bytes after the last of {count} triangles ignored"
            ));
        }
    }
    finish(b, name)
}

fn finish(b: SceneBuilder, name: &str) -> Result<Scene, LoadError> {
    let faces = b.next_face_id();
    b.finish().ok_or_else(|| {
        if faces == 0 {
            LoadError::file(name, "empty scene: no triangles")
        } else {
            LoadError::file(
                name,
                format!("empty scene: all {faces} triangles are degenerate"),
            )
        }
    })
}

// ---- ASCII ----

/// Whitespace-separated tokens of the whole file, read line by line, with the line each is on.
/// A token is a range of `buf`, the current line.
struct Lexer<'i, R> {
    input: &'i mut Input<R>,
    buf: Vec<u8>,
    pos: usize,
    /// Line number of `buf`.
    line: usize,
    /// Line of the last token returned (where end-of-file errors are reported).
    last_line: usize,
}

impl<R: Read> Lexer<'_, R> {
    fn next(&mut self) -> Option<Range<usize>> {
        loop {
            while self
                .buf
                .get(self.pos)
                .is_some_and(|c| c.is_ascii_whitespace())
            {
                self.pos += 1;
            }
            if self.pos < self.buf.len() {
                break;
            }
            if !self.input.line(&mut self.buf) {
                return None;
            }
            self.line += 1;
            self.pos = 0;
        }
        let start = self.pos;
        while self
            .buf
            .get(self.pos)
            .is_some_and(|c| !c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        self.last_line = self.line;
        Some(start..self.pos)
    }

    fn text(&self, r: &Range<usize>) -> &[u8] {
        &self.buf[r.clone()]
    }

    /// The rest of the current line (a solid's name), trimmed.
    fn rest_of_line(&mut self) -> &[u8] {
        let start = self.pos.min(self.buf.len());
        self.pos = self.buf.len();
        self.buf[start..].trim_ascii()
    }
}

struct Ascii<'a, 'i, R> {
    name: &'a str,
    lex: Lexer<'i, R>,
    b: SceneBuilder,
    weld: Welder,
    material: u32,
}

fn ascii<R: Read>(input: &mut Input<R>, name: &str) -> Result<Scene, LoadError> {
    let mut b = SceneBuilder::new(name);
    let material = b.default_material();
    let capacity = input.len().map_or(0, |l| l as usize / 200);
    let mut p = Ascii {
        name,
        lex: Lexer {
            input,
            buf: Vec::new(),
            pos: 0,
            line: 0,
            last_line: 1,
        },
        b,
        weld: Welder::with_capacity(capacity),
        material,
    };
    p.solids()?;
    finish(p.b, name)
}

impl<R: Read> Ascii<'_, '_, R> {
    fn err(&self, line: usize, msg: impl Into<String>) -> LoadError {
        LoadError::line(self.name, line, msg)
    }

    /// The next token (a range of the lexer's line), or an error naming what was expected.
    fn expect_token(&mut self, what: &str) -> Result<Range<usize>, LoadError> {
        match self.lex.next() {
            Some(t) => Ok(t),
            None => Err(self.err(
                self.lex.last_line,
                format!("unexpected end of file: expected {what}"),
            )),
        }
    }

    fn expect_keyword(&mut self, kw: &str) -> Result<(), LoadError> {
        let r = self.expect_token(&format!("'{kw}'"))?;
        let t = self.lex.text(&r);
        if t.eq_ignore_ascii_case(kw.as_bytes()) {
            Ok(())
        } else {
            Err(self.err(
                self.lex.last_line,
                format!("expected '{kw}', found '{}'", show(t)),
            ))
        }
    }

    fn solids(&mut self) -> Result<(), LoadError> {
        while let Some(r) = self.lex.next() {
            let t = self.lex.text(&r);
            if !t.eq_ignore_ascii_case(b"solid") {
                return Err(self.err(
                    self.lex.last_line,
                    format!("expected 'solid', found '{}'", show(t)),
                ));
            }
            let solid_line = self.lex.last_line;
            let label = lossy(self.lex.rest_of_line()).into_owned();
            self.b.begin_mesh(if label.is_empty() {
                file_label(self.name)
            } else {
                label
            });
            loop {
                let Some(r) = self.lex.next() else {
                    self.b.warn(format!(
                        "{}:{solid_line}: solid has no 'endsolid'",
                        self.name
                    ));
                    return Ok(());
                };
                let t = self.lex.text(&r);
                if t.eq_ignore_ascii_case(b"endsolid") {
                    self.lex.rest_of_line();
                    break;
                } else if t.eq_ignore_ascii_case(b"facet") {
                    self.facet()?;
                } else {
                    return Err(self.err(
                        self.lex.last_line,
                        format!("expected 'facet' or 'endsolid', found '{}'", show(t)),
                    ));
                }
            }
        }
        Ok(())
    }

    fn facet(&mut self) -> Result<(), LoadError> {
        let facet_line = self.lex.last_line;
        self.expect_keyword("normal")?;
        for _ in 0..3 {
            // The stored normal is not used, but must be a number (NaN allowed: some exporters
            // write it for degenerate triangles).
            let r = self.expect_token("a normal component")?;
            let t = self.lex.text(&r);
            if parse_f64(t).is_none() {
                return Err(self.err(
                    self.lex.last_line,
                    format!("bad number '{}' in facet normal", show(t)),
                ));
            }
        }
        self.expect_keyword("outer")?;
        self.expect_keyword("loop")?;
        let mut idx = [0u32; 3];
        let mut n = 0;
        loop {
            let r = self.expect_token("'vertex' or 'endloop'")?;
            let t = self.lex.text(&r);
            if t.eq_ignore_ascii_case(b"endloop") {
                break;
            }
            if !t.eq_ignore_ascii_case(b"vertex") {
                return Err(self.err(
                    self.lex.last_line,
                    format!("expected 'vertex' or 'endloop', found '{}'", show(t)),
                ));
            }
            if n == 3 {
                return Err(self.err(
                    self.lex.last_line,
                    "facet has more than 3 vertices (STL facets are triangles)",
                ));
            }
            let mut p = [0.0f64; 3];
            for c in &mut p {
                let r = self.expect_token("a vertex coordinate")?;
                *c = super::text::parse_coord(self.lex.text(&r))
                    .map_err(|m| self.err(self.lex.last_line, m))?;
            }
            idx[n] = self
                .weld
                .vertex(&mut self.b, DVec3::from_array(p))
                .ok_or_else(|| self.err(self.lex.last_line, "too many vertices"))?;
            n += 1;
        }
        if n != 3 {
            return Err(self.err(
                self.lex.last_line,
                format!("facet has {n} vertices, expected 3"),
            ));
        }
        self.expect_keyword("endfacet")?;
        if self.b.next_face_id() >= u32::MAX / 3 {
            return Err(self.err(facet_line, "too many facets"));
        }
        self.b.add_face(&idx, self.material);
        Ok(())
    }
}

// ---- Welding ----

/// Bit patterns of a point's coordinates, -0.0 mapped to 0.0.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Key([u64; 3]);

impl Hash for Key {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u64(self.0[0]);
        h.write_u64(self.0[1]);
        h.write_u64(self.0[2]);
    }
}

/// A small fast hasher for the weld map (SipHash would dominate binary STL loading). Not
/// collision-resistant against crafted input, which only costs time.
#[derive(Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(23) ^ x).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
    fn finish(&self) -> u64 {
        // murmur3's finaliser: spreads the high bits that the multiplications filled into the low
        // bits the table indexes by (round coordinates have all-zero low mantissa bits).
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }
}

struct Welder {
    map: HashMap<Key, u32, BuildHasherDefault<KeyHasher>>,
}

impl Welder {
    fn with_capacity(n: usize) -> Self {
        Welder {
            map: HashMap::with_capacity_and_hasher(n, Default::default()),
        }
    }

    /// The index of the vertex at `p` (finite), added if new; `None` past u32 indices.
    fn vertex(&mut self, b: &mut SceneBuilder, p: DVec3) -> Option<u32> {
        let bits = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
        let key = Key([bits(p.x), bits(p.y), bits(p.z)]);
        if let Some(&i) = self.map.get(&key) {
            return Some(i);
        }
        if b.vertex_count() >= u32::MAX as usize {
            return None;
        }
        let p = DVec3::new(p.x + 0.0, p.y + 0.0, p.z + 0.0); // -0.0 + 0.0 == +0.0
        let i = b.add_vertex(p);
        self.map.insert(key, i);
        Some(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(bytes: &[u8], name: &str) -> Result<Scene, LoadError> {
        super::load(Input::new(bytes, Some(bytes.len() as u64)), name)
    }
    use crate::error::Location;

    fn tri_bytes(tris: &[[[f32; 3]; 3]], header: &[u8]) -> Vec<u8> {
        let mut out = vec![0u8; 80];
        out[..header.len()].copy_from_slice(header);
        out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
        for t in tris {
            out.extend_from_slice(&[0u8; 12]);
            for v in t {
                for c in v {
                    out.extend_from_slice(&c.to_le_bytes());
                }
            }
            out.extend_from_slice(&[0u8; 2]);
        }
        out
    }

    const T1: [[f32; 3]; 3] = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]];
    const T2: [[f32; 3]; 3] = [[1., 0., 0.], [1., 1., 0.], [0., 1., -0.]];

    #[test]
    fn binary_with_solid_header_welds_and_keeps_winding() {
        let bytes = tri_bytes(&[T1, T2], b"solid but binary");
        let s = load(&bytes, "t.stl").unwrap();
        assert_eq!(s.positions.len(), 4, "shared corners (and -0.0) welded");
        assert_eq!(s.faces.len(), 2);
        assert_eq!(s.face_corners(&s.faces[1]), &[1, 3, 2]);
        assert!(s.face_normal(&s.faces[0]).z > 0.0);
        assert!(s.positions.iter().all(|p| p.z.to_bits() == 0));
    }

    #[test]
    fn binary_truncated_and_nan() {
        let mut bytes = tri_bytes(&[T1, T2], b"");
        bytes.truncate(84 + 50 + 20);
        let e = load(&bytes, "t.stl").unwrap_err();
        assert_eq!(e.location, Location::Byte(134));
        assert!(
            e.message
                .contains("expected 2 triangles (184 bytes), file has 154 bytes")
        );

        let mut t = T2;
        t[2][1] = f32::NAN;
        let e = load(&tri_bytes(&[T1, t], b""), "t.stl").unwrap_err();
        assert_eq!(e.location, Location::Byte(134));
        assert!(e.message.contains("not finite"), "{e}");

        let e = load(b"\x01\x02", "t.stl").unwrap_err();
        assert_eq!(e.location, Location::Byte(0));
    }

    #[test]
    fn ascii_multiple_solids_case_insensitive() {
        let src = "solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid a\n\
                   SOLID\nFACET NORMAL 0 0 1 OUTER LOOP VERTEX 1 0 0 VERTEX 1 1 0\nVERTEX 0 1 0 ENDLOOP ENDFACET\n";
        let s = load(src.as_bytes(), "dir/t.stl").unwrap();
        assert_eq!(s.meshes.len(), 2);
        assert_eq!(s.meshes[0].name, "a");
        assert_eq!(s.meshes[1].name, "t.stl");
        assert_eq!(s.positions.len(), 4);
        assert!(s.stats.warnings.iter().any(|w| w.contains("endsolid")));
    }

    #[test]
    fn ascii_errors() {
        let head = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
        for (tail, line, needle) in [
            ("vertex 0 1 0\nvertex 1 1 0\n", 7, "more than 3"),
            ("endloop\nendfacet\n", 6, "2 vertices"),
            ("vertex 0 1 nan\n", 6, "not finite"),
            ("vertex 0 1 q\n", 6, "bad number"),
            (
                "vertex 0 1 0\nendloop\nendfacet\nfoo\n",
                9,
                "expected 'facet' or 'endsolid'",
            ),
            ("vertex 0 1 0\nendloop\n", 7, "unexpected end of file"),
        ] {
            let src = format!("{head}{tail}");
            let e = load(src.as_bytes(), "t.stl").unwrap_err();
            assert_eq!(e.location, Location::Line(line), "{tail:?}: {e}");
            assert!(e.message.contains(needle), "{tail:?}: {e}");
        }
    }

    #[test]
    fn empty_solid_is_an_empty_scene() {
        let e = load(b"solid x\nendsolid x\n", "t.stl").unwrap_err();
        assert_eq!(e.location, Location::File);
    }
}
