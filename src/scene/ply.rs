//! PLY loader (ASCII, binary little- and big-endian), with its own parser so that errors name the
//! header line, the body line (ASCII) or the byte offset (binary).
//!
//! Guarantees of a scene returned from here: every coordinate is finite, every corner index is in
//! range, faces keep the file's winding and order (ids in file order), and the whole file is one
//! mesh named after it.
//!
//! Read: the `vertex` element's `x`, `y`, `z` (any scalar type) and the `face` element's
//! `vertex_indices` (or `vertex_index`) list of any integer type; every other property and
//! element is skipped, lists included, in all three encodings. A file with vertices but no face is
//! an error (a point cloud is not a scene).
//!
//! Untrusted sizes: element counts and list lengths come from the file, so nothing is allocated
//! for more entries than the bytes left could hold, fixed-size binary elements are checked against
//! the bytes left before reading, and size arithmetic is checked. Elements without properties
//! occupy no bytes and are not iterated (their count may be anything).
//!
//! ASCII bodies are read one element entry per line (blank lines are skipped); an entry with too
//! few or too many values is an error at its line. Header and ASCII lines may end in `\r\n`; a
//! leading UTF-8 byte-order mark is skipped.
//!
//! The data is streamed. When its length is not known in advance (a gzipped file), the checks
//! against the bytes left are replaced by finding the end where it comes (a truncated element is
//! then reported at the entry that runs out), and memory is reserved for at most
//! `UNKNOWN_LEFT_RESERVE` entries ahead of reading them.

use super::input::Input;
use super::text::{Tokens, file_label, lossy, parse_f64, parse_int, show, token_at};
use super::{Scene, SceneBuilder};
use crate::error::{LoadError, Location};
use glam::DVec3;
use std::io::Read;

pub(super) fn load<R: Read>(mut input: Input<R>, name: &str) -> Result<Scene, LoadError> {
    let result = parse(&mut input, name);
    input.finish(result, name)
}

fn parse<R: Read>(input: &mut Input<R>, name: &str) -> Result<Scene, LoadError> {
    let h = header(input, name)?;
    let data = match h.encoding {
        Encoding::Ascii => read_body(
            &h,
            &mut AsciiBody {
                input,
                buf: Vec::new(),
                at: 0,
                line: h.end_line,
            },
            name,
        )?,
        Encoding::Binary { big_endian } => read_body(
            &h,
            &mut BinBody {
                record: input.pos(),
                input,
                big_endian,
            },
            name,
        )?,
    };

    let mut b = SceneBuilder::new(name);
    for w in data.warnings {
        b.warn(w);
    }
    let material = b.default_material();
    b.begin_mesh(file_label(name));
    for p in data.positions {
        b.add_vertex(p);
    }
    let mut start = 0usize;
    for len in &data.face_lens {
        let end = start + *len as usize;
        if let Some(c) = data.corners.get(start..end) {
            b.add_face(c, material);
        }
        start = end;
    }
    let faces = data.face_lens.len();
    b.finish().ok_or_else(|| {
        if faces == 0 {
            LoadError::file(name, "empty scene: no faces (a point cloud is not a scene)")
        } else {
            LoadError::file(
                name,
                format!("empty scene: all {faces} faces are degenerate"),
            )
        }
    })
}

// ---- Header ----

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn parse(t: &[u8]) -> Option<Ty> {
        Some(match t {
            b"char" | b"int8" => Ty::I8,
            b"uchar" | b"uint8" => Ty::U8,
            b"short" | b"int16" => Ty::I16,
            b"ushort" | b"uint16" => Ty::U16,
            b"int" | b"int32" => Ty::I32,
            b"uint" | b"uint32" => Ty::U32,
            b"float" | b"float32" => Ty::F32,
            b"double" | b"float64" => Ty::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
    fn is_int(self) -> bool {
        !matches!(self, Ty::F32 | Ty::F64)
    }
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Ty),
    List { count: Ty, item: Ty },
}

#[derive(Debug)]
struct Prop {
    name: Vec<u8>,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: Vec<u8>,
    count: u64,
    props: Vec<Prop>,
    line: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

#[derive(Debug)]
struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Line of `end_header`.
    end_line: usize,
    vertex: Option<VertexRole>,
    face: Option<FaceRole>,
}

#[derive(Clone, Copy, Debug)]
struct VertexRole {
    element: usize,
    xyz: [usize; 3],
}

#[derive(Clone, Copy, Debug)]
struct FaceRole {
    element: usize,
    list: usize,
}

fn header<R: Read>(input: &mut Input<R>, name: &str) -> Result<Header, LoadError> {
    let err = |line: usize, msg: String| LoadError::line(name, line, msg);
    let mut text = Vec::new();
    input.line(&mut text);
    if text.trim_ascii() != b"ply" {
        return Err(err(
            1,
            "not a PLY file: the first line must be 'ply'".to_string(),
        ));
    }
    let mut line = 1;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if !input.line(&mut text) {
            return Err(err(line, "the header has no 'end_header' line".to_string()));
        }
        line += 1;
        let mut toks = Tokens::new(&text);
        let Some(kw) = toks.next() else { continue };
        match kw {
            b"end_header" => break,
            b"comment" | b"obj_info" => continue,
            b"format" => {
                let fmt = toks.next().unwrap_or(b"");
                let enc = match fmt {
                    b"ascii" => Encoding::Ascii,
                    b"binary_little_endian" => Encoding::Binary { big_endian: false },
                    b"binary_big_endian" => Encoding::Binary { big_endian: true },
                    _ => {
                        return Err(err(
                            line,
                            format!(
                                "unsupported format '{}' (expected ascii, binary_little_endian or binary_big_endian)",
                                show(fmt)
                            ),
                        ));
                    }
                };
                match toks.next() {
                    Some(b"1.0") | Some(b"1") => {}
                    v => {
                        return Err(err(
                            line,
                            format!(
                                "unsupported PLY version '{}' (expected 1.0)",
                                show(v.unwrap_or(b""))
                            ),
                        ));
                    }
                }
                if encoding.is_some() {
                    return Err(err(line, "a second format line".to_string()));
                }
                encoding = Some(enc);
            }
            b"element" => {
                let (Some(ename), Some(count)) = (toks.next(), toks.next()) else {
                    return Err(err(
                        line,
                        "element line needs a name and a count".to_string(),
                    ));
                };
                // Plain decimal digits only (`str::parse` would also take a sign).
                let parsed = if count.iter().all(u8::is_ascii_digit) {
                    std::str::from_utf8(count)
                        .ok()
                        .and_then(|c| c.parse::<u64>().ok())
                } else {
                    None
                };
                let count = match parsed {
                    Some(c) => c,
                    None => {
                        return Err(err(line, format!("bad element count '{}'", show(count))));
                    }
                };
                elements.push(Element {
                    name: ename.to_vec(),
                    count,
                    props: Vec::new(),
                    line,
                });
            }
            b"property" => {
                let Some(el) = elements.last_mut() else {
                    return Err(err(line, "property before any element".to_string()));
                };
                let t = toks.next().unwrap_or(b"");
                let kind = if t == b"list" {
                    let (c, i) = (toks.next().unwrap_or(b""), toks.next().unwrap_or(b""));
                    let (Some(count), Some(item)) = (Ty::parse(c), Ty::parse(i)) else {
                        return Err(err(
                            line,
                            format!("bad list types '{}' '{}'", show(c), show(i)),
                        ));
                    };
                    if !count.is_int() {
                        return Err(err(
                            line,
                            format!("list count type must be an integer type, not '{}'", show(c)),
                        ));
                    }
                    Kind::List { count, item }
                } else {
                    match Ty::parse(t) {
                        Some(ty) => Kind::Scalar(ty),
                        None => {
                            return Err(err(line, format!("unknown property type '{}'", show(t))));
                        }
                    }
                };
                let Some(pname) = toks.next() else {
                    return Err(err(line, "property without a name".to_string()));
                };
                if toks.next().is_some() {
                    return Err(err(
                        line,
                        "unexpected text after the property name".to_string(),
                    ));
                }
                el.props.push(Prop {
                    name: pname.to_vec(),
                    kind,
                });
            }
            _ => {
                return Err(err(
                    line,
                    format!("unknown header line starting with '{}'", show(kw)),
                ));
            }
        }
    }
    let end_line = line;
    let Some(encoding) = encoding else {
        return Err(err(end_line, "the header has no format line".to_string()));
    };

    let mut vertex = None;
    let mut face = None;
    for (k, e) in elements.iter().enumerate() {
        let ename = lossy(&e.name);
        if e.name == b"vertex" {
            if vertex.is_some() {
                return Err(err(e.line, "a second 'vertex' element".to_string()));
            }
            if e.count > u32::MAX as u64 {
                return Err(err(e.line, format!("too many vertices ({})", e.count)));
            }
            let mut xyz = [0usize; 3];
            for (slot, axis) in xyz.iter_mut().zip([&b"x"[..], b"y", b"z"]) {
                let Some(i) = e.props.iter().position(|p| p.name == axis) else {
                    return Err(err(
                        e.line,
                        format!("the vertex element has no '{}' property", lossy(axis)),
                    ));
                };
                if matches!(e.props[i].kind, Kind::List { .. }) {
                    return Err(err(
                        e.line,
                        format!("vertex property '{}' is a list", lossy(axis)),
                    ));
                }
                *slot = i;
            }
            vertex = Some(VertexRole { element: k, xyz });
        } else if e.name == b"face" {
            if face.is_some() {
                return Err(err(e.line, "a second 'face' element".to_string()));
            }
            if e.count > u32::MAX as u64 {
                return Err(err(e.line, format!("too many faces ({})", e.count)));
            }
            let Some(i) = e
                .props
                .iter()
                .position(|p| p.name == b"vertex_indices" || p.name == b"vertex_index")
            else {
                return Err(err(
                    e.line,
                    "the face element has no 'vertex_indices' list property".to_string(),
                ));
            };
            match e.props[i].kind {
                Kind::List { item, .. } if item.is_int() => {}
                Kind::List { .. } => {
                    return Err(err(
                        e.line,
                        "face vertex indices must be of an integer type".to_string(),
                    ));
                }
                Kind::Scalar(_) => {
                    return Err(err(
                        e.line,
                        "face 'vertex_indices' must be a list property".to_string(),
                    ));
                }
            }
            face = Some(FaceRole {
                element: k,
                list: i,
            });
        } else if ename.is_empty() {
            return Err(err(e.line, "element without a name".to_string()));
        }
    }
    if vertex.is_none() {
        return Err(err(
            end_line,
            "the header declares no 'vertex' element".to_string(),
        ));
    }
    Ok(Header {
        encoding,
        elements,
        end_line,
        vertex,
        face,
    })
}

// ---- Body ----

#[derive(Clone, Copy)]
enum Num {
    I(i64),
    F(f64),
}

impl Num {
    fn f64(self) -> f64 {
        match self {
            Num::I(i) => i as f64,
            Num::F(x) => x,
        }
    }
}

enum ValueError {
    /// No more data in the entry (ASCII: on the line; binary: in the file).
    End,
    Bad(String),
}

/// One encoding's way of reading element entries.
trait Body {
    /// Starts the next entry; false when there is no data left at all.
    fn begin(&mut self) -> bool;
    fn value(&mut self, ty: Ty) -> Result<Num, ValueError>;
    /// Ends an entry; an error message when it has data left over.
    fn end(&mut self) -> Result<(), String>;
    /// Where the current entry starts.
    fn location(&self) -> Location;
    /// Where the data ran out.
    fn eof_location(&self) -> Location;
    /// Message for an entry that runs out of data in the middle.
    fn short_message(&self, element: &str, i: u64, count: u64) -> String;
    /// Checks that an element's entries can fit in what is left, before reading them.
    fn precheck(&self, e: &Element, name: &str) -> Result<(), LoadError>;
    /// How many entries of `e` the data left could hold at most (for reserving memory).
    fn max_entries(&self, e: &Element) -> u64;
    /// Whether a list of `n` items of `ty` could fit in what is left.
    fn list_fits(&self, n: u64, ty: Ty) -> bool;
    /// Whether anything but whitespace is left after the last element.
    fn has_trailing(&mut self) -> bool;
}

/// Only a bound on allocation where the data left is unknown (a decompressed stream): how many
/// entries memory is reserved for ahead of reading them.
const UNKNOWN_LEFT_RESERVE: u64 = 1 << 16;

struct BinBody<'i, R> {
    input: &'i mut Input<R>,
    record: u64,
    big_endian: bool,
}

impl<R: Read> BinBody<'_, R> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let mut a: [u8; N] = self.input.take()?;
        if self.big_endian {
            a.reverse();
        }
        Some(a)
    }
    /// The length of the data: known in advance, or found on reaching its end.
    fn total(&self) -> u64 {
        self.input.len().unwrap_or(self.input.pos())
    }
}

impl<R: Read> Body for BinBody<'_, R> {
    fn begin(&mut self) -> bool {
        self.record = self.input.pos();
        !self.input.at_end()
    }
    fn value(&mut self, ty: Ty) -> Result<Num, ValueError> {
        // Bytes are reversed to little-endian order by `take` for big-endian files.
        let v = match ty {
            Ty::I8 => self
                .take::<1>()
                .map(|a| Num::I(i8::from_le_bytes(a) as i64)),
            Ty::U8 => self.take::<1>().map(|a| Num::I(a[0] as i64)),
            Ty::I16 => self
                .take::<2>()
                .map(|a| Num::I(i16::from_le_bytes(a) as i64)),
            Ty::U16 => self
                .take::<2>()
                .map(|a| Num::I(u16::from_le_bytes(a) as i64)),
            Ty::I32 => self
                .take::<4>()
                .map(|a| Num::I(i32::from_le_bytes(a) as i64)),
            Ty::U32 => self
                .take::<4>()
                .map(|a| Num::I(u32::from_le_bytes(a) as i64)),
            Ty::F32 => self
                .take::<4>()
                .map(|a| Num::F(f32::from_le_bytes(a) as f64)),
            Ty::F64 => self.take::<8>().map(|a| Num::F(f64::from_le_bytes(a))),
        };
        v.ok_or(ValueError::End)
    }
    fn end(&mut self) -> Result<(), String> {
        Ok(())
    }
    fn location(&self) -> Location {
        Location::Byte(self.record)
    }
    fn eof_location(&self) -> Location {
        Location::Byte(self.total())
    }
    fn short_message(&self, element: &str, i: u64, count: u64) -> String {
        format!(
            "truncated: {element} {} of {count} (starting at this byte) runs past the end of the file ({} bytes)",
            i + 1,
            self.total()
        )
    }
    fn precheck(&self, e: &Element, name: &str) -> Result<(), LoadError> {
        let mut size = 0u64;
        for p in &e.props {
            match p.kind {
                Kind::Scalar(t) => size += t.size() as u64,
                Kind::List { .. } => return Ok(()),
            }
        }
        // Unknown length: truncation is found where the data ends.
        let Some(left) = self.input.left() else {
            return Ok(());
        };
        match e.count.checked_mul(size) {
            Some(need) if need <= left => Ok(()),
            need => {
                let complete = left / size.max(1);
                let need = need.map_or("more than 2^64".to_string(), |n| n.to_string());
                Err(LoadError::byte(
                    name,
                    self.input.pos() + complete * size,
                    format!(
                        "truncated: element '{}' declares {} entries of {size} bytes ({need} bytes) but only {left} bytes are left, enough for {complete}",
                        lossy(&e.name),
                        e.count
                    ),
                ))
            }
        }
    }
    fn max_entries(&self, e: &Element) -> u64 {
        let min: u64 = e
            .props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(t) => t.size() as u64,
                Kind::List { count, .. } => count.size() as u64,
            })
            .sum();
        self.input
            .left()
            .map_or(UNKNOWN_LEFT_RESERVE, |left| left / min.max(1))
    }
    fn list_fits(&self, n: u64, ty: Ty) -> bool {
        let Some(left) = self.input.left() else {
            return true; // reading item by item finds the end
        };
        n.checked_mul(ty.size() as u64)
            .is_some_and(|need| need <= left)
    }
    fn has_trailing(&mut self) -> bool {
        !self.input.at_end()
    }
}

struct AsciiBody<'i, R> {
    input: &'i mut Input<R>,
    /// The current entry's line.
    buf: Vec<u8>,
    /// Where the next value is looked for in `buf`.
    at: usize,
    /// Line of the current entry (of `end_header` before the first).
    line: usize,
}

impl<R: Read> Body for AsciiBody<'_, R> {
    fn begin(&mut self) -> bool {
        while self.input.line(&mut self.buf) {
            self.line += 1;
            if !self.buf.trim_ascii().is_empty() {
                self.at = 0;
                return true;
            }
        }
        false
    }
    fn value(&mut self, ty: Ty) -> Result<Num, ValueError> {
        let (start, end) = token_at(&self.buf, self.at).ok_or(ValueError::End)?;
        self.at = end;
        let t = &self.buf[start..end];
        let v = if ty.is_int() {
            parse_int(t).map(Num::I)
        } else {
            parse_f64(t).map(Num::F)
        };
        v.ok_or_else(|| ValueError::Bad(format!("bad number '{}'", show(t))))
    }
    fn end(&mut self) -> Result<(), String> {
        match token_at(&self.buf, self.at) {
            Some((start, end)) => Err(format!(
                "unexpected value '{}' after the end of the entry",
                show(&self.buf[start..end])
            )),
            None => Ok(()),
        }
    }
    fn location(&self) -> Location {
        Location::Line(self.line)
    }
    fn eof_location(&self) -> Location {
        Location::Line(self.line)
    }
    fn short_message(&self, element: &str, i: u64, count: u64) -> String {
        format!(
            "too few values on the line for {element} {} of {count}",
            i + 1
        )
    }
    fn precheck(&self, _: &Element, _: &str) -> Result<(), LoadError> {
        Ok(())
    }
    fn max_entries(&self, e: &Element) -> u64 {
        // Each value takes at least one character and one separator.
        self.input.left().map_or(UNKNOWN_LEFT_RESERVE, |left| {
            left / (2 * e.props.len() as u64).max(1)
        })
    }
    fn list_fits(&self, _: u64, _: Ty) -> bool {
        // The line runs out first; reading item by item stops there.
        true
    }
    fn has_trailing(&mut self) -> bool {
        while self.input.line(&mut self.buf) {
            if !self.buf.trim_ascii().is_empty() {
                return true;
            }
        }
        false
    }
}

#[derive(Default)]
struct Data {
    positions: Vec<DVec3>,
    corners: Vec<u32>,
    face_lens: Vec<u32>,
    warnings: Vec<String>,
}

fn read_body<B: Body>(h: &Header, body: &mut B, name: &str) -> Result<Data, LoadError> {
    let mut d = Data::default();
    let nverts = h
        .vertex
        .and_then(|v| h.elements.get(v.element))
        .map_or(0, |e| e.count);
    for (k, e) in h.elements.iter().enumerate() {
        if e.props.is_empty() || e.count == 0 {
            continue; // occupies no data, whatever its count
        }
        let ename = lossy(&e.name).into_owned();
        let vrole = h.vertex.filter(|v| v.element == k);
        let frole = h.face.filter(|f| f.element == k);
        if vrole.is_none() && frole.is_none() {
            d.warnings
                .push(format!("element '{ename}' ({} entries) skipped", e.count));
        }
        body.precheck(e, name)?;
        let cap = e.count.min(body.max_entries(e)) as usize;
        if vrole.is_some() {
            d.positions.reserve(cap);
        }
        if frole.is_some() {
            d.face_lens.reserve(cap);
            d.corners.reserve(cap.saturating_mul(3));
        }
        for i in 0..e.count {
            if !body.begin() {
                return Err(LoadError::new(
                    name,
                    body.eof_location(),
                    format!(
                        "unexpected end of data: element '{ename}' declares {} entries, only {i} present",
                        e.count
                    ),
                ));
            }
            let value_err = |body: &B, err: ValueError| match err {
                ValueError::End => LoadError::new(
                    name,
                    body.location(),
                    body.short_message(&ename, i, e.count),
                ),
                ValueError::Bad(m) => LoadError::new(
                    name,
                    body.location(),
                    format!("{m} in {ename} {} of {}", i + 1, e.count),
                ),
            };
            let mut xyz = [0.0f64; 3];
            let first_corner = d.corners.len();
            for (pi, p) in e.props.iter().enumerate() {
                match p.kind {
                    Kind::Scalar(ty) => {
                        let v = body.value(ty).map_err(|x| value_err(body, x))?;
                        if let Some(v_role) = vrole
                            && let Some(axis) = v_role.xyz.iter().position(|&a| a == pi)
                        {
                            xyz[axis] = v.f64();
                        }
                    }
                    Kind::List { count, item } => {
                        let n = match body.value(count).map_err(|x| value_err(body, x))? {
                            Num::I(n) if n >= 0 => n as u64,
                            v => {
                                return Err(LoadError::new(
                                    name,
                                    body.location(),
                                    format!(
                                        "bad list length {} in {ename} {} of {}",
                                        v.f64(),
                                        i + 1,
                                        e.count
                                    ),
                                ));
                            }
                        };
                        if !body.list_fits(n, item) {
                            return Err(LoadError::new(
                                name,
                                body.location(),
                                format!(
                                    "truncated: {ename} {} of {} has a list of {n} items that runs past the end of the file",
                                    i + 1,
                                    e.count
                                ),
                            ));
                        }
                        let keep = frole.is_some_and(|f| f.list == pi);
                        for _ in 0..n {
                            let v = body.value(item).map_err(|x| value_err(body, x))?;
                            if keep {
                                let Num::I(v) = v else { continue }; // item type is an integer
                                if v < 0 || v as u64 >= nverts {
                                    return Err(LoadError::new(
                                        name,
                                        body.location(),
                                        format!(
                                            "face {} of {}: vertex index {v} out of range (the file has {nverts} vertices)",
                                            i + 1,
                                            e.count
                                        ),
                                    ));
                                }
                                d.corners.push(v as u32);
                            }
                        }
                    }
                }
            }
            body.end().map_err(|m| {
                LoadError::new(
                    name,
                    body.location(),
                    format!("{m} ({ename} {} of {})", i + 1, e.count),
                )
            })?;
            if vrole.is_some() {
                if !xyz.iter().all(|c| c.is_finite()) {
                    return Err(LoadError::new(
                        name,
                        body.location(),
                        format!(
                            "vertex {} of {} has a coordinate that is not finite ({}, {}, {})",
                            i + 1,
                            e.count,
                            xyz[0],
                            xyz[1],
                            xyz[2]
                        ),
                    ));
                }
                d.positions.push(DVec3::from_array(xyz));
            }
            if frole.is_some() {
                let n = d.corners.len() - first_corner;
                if n < 3 {
                    return Err(LoadError::new(
                        name,
                        body.location(),
                        format!(
                            "face {} of {} has {n} vertex indices, needs at least 3",
                            i + 1,
                            e.count
                        ),
                    ));
                }
                if d.corners.len() > u32::MAX as usize {
                    // Corner offsets in a scene are u32.
                    return Err(LoadError::new(
                        name,
                        body.location(),
                        "too many face corners for one scene",
                    ));
                }
                d.face_lens.push(n as u32);
            }
        }
    }
    if body.has_trailing() {
        d.warnings
            .push(format!("{name}: data after the last element ignored"));
    }
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(bytes: &[u8], name: &str) -> Result<Scene, LoadError> {
        super::load(Input::new(bytes, Some(bytes.len() as u64)), name)
    }

    const HEAD: &str = "ply\nformat ascii 1.0\ncomment hi\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty list uchar float extra\nelement face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\nelement edge 1\nproperty int a\nproperty int b\nend_header\n";

    fn load_str(s: &str) -> Result<Scene, LoadError> {
        load(s.as_bytes(), "t.ply")
    }

    #[test]
    fn ascii_skips_other_properties_and_elements() {
        let s = load_str(&format!(
            "{HEAD}0 0 0 2 5 6\n1 0 0 0\n\n0 1 0 1 7\n9 3 0 1 2\n0 1\n"
        ))
        .unwrap();
        assert_eq!(s.positions.len(), 3);
        assert_eq!(s.faces.len(), 1);
        assert_eq!(s.face_corners(&s.faces[0]), &[0, 1, 2]);
        assert_eq!(s.positions[2], DVec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn ascii_errors_name_the_line() {
        for (body, line, needle) in [
            (
                "0 0 0 0\n1 0 0 0\n0 1 0 0\n9 3 0 1 3\n0 1\n",
                19,
                "out of range",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 0 0\n9 3 0 1\n0 1\n",
                19,
                "too few values",
            ),
            (
                "0 0 0 0\n1 0 0 0 4\n0 1 0 0\n9 3 0 1 2\n0 1\n",
                17,
                "unexpected value",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 nan 0\n9 3 0 1 2\n0 1\n",
                18,
                "not finite",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 x 0\n9 3 0 1 2\n0 1\n",
                18,
                "bad number",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 0 0\n9 2 0 1\n0 1\n",
                19,
                "needs at least 3",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 0 0\n9 -3 0 1 2\n0 1\n",
                19,
                "bad list length",
            ),
            (
                "0 0 0 0\n1 0 0 0\n0 1 0 0\n9 3 0 1 2\n",
                19,
                "unexpected end of data",
            ),
        ] {
            let e = load_str(&format!("{HEAD}{body}")).unwrap_err();
            assert_eq!(e.location, Location::Line(line), "{body:?}: {e}");
            assert!(e.message.contains(needle), "{body:?}: {e}");
        }
    }

    #[test]
    fn header_errors() {
        for (src, line, needle) in [
            ("plx\n", 1, "not a PLY file"),
            ("ply\nformat ascii 1.0\nelement vertex 1\n", 3, "end_header"),
            (
                "ply\nformat binary_middle_endian 1.0\n",
                2,
                "unsupported format",
            ),
            ("ply\nformat ascii 2.0\n", 2, "version"),
            (
                "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
                3,
                "bad element count",
            ),
            (
                "ply\nformat ascii 1.0\nproperty float x\n",
                3,
                "before any element",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n",
                4,
                "unknown property type",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n",
                4,
                "count type",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n",
                3,
                "no 'z'",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int idx\nend_header\n",
                7,
                "vertex_indices",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n",
                7,
                "integer",
            ),
            ("ply\nelement vertex 0\nend_header\n", 3, "no format"),
            ("ply\nformat ascii 1.0\nfoo\n", 3, "unknown header line"),
        ] {
            let e = load_str(src).unwrap_err();
            assert_eq!(e.location, Location::Line(line), "{src:?}: {e}");
            assert!(e.message.contains(needle), "{src:?}: {e}");
        }
    }

    fn binary(big_endian: bool, truncate: usize) -> Vec<u8> {
        let fmt = if big_endian { "big" } else { "little" };
        let mut b = format!(
            "ply\r\nformat binary_{fmt}_endian 1.0\r\nelement vertex 3\r\nproperty double x\r\nproperty short q\r\nproperty float y\r\nproperty float z\r\nelement face 1\r\nproperty list ushort uint vertex_index\r\nproperty list uchar char tex\r\nend_header\r\n"
        )
        .into_bytes();
        let mut put = |bytes: &[u8]| {
            let mut v = bytes.to_vec();
            if big_endian {
                v.reverse();
            }
            b.extend_from_slice(&v);
        };
        for p in [[0.0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
            put(&(p[0] as f64).to_le_bytes());
            put(&7i16.to_le_bytes());
            put(&p[1].to_le_bytes());
            put(&p[2].to_le_bytes());
        }
        put(&3u16.to_le_bytes());
        for i in [0u32, 1, 2] {
            put(&i.to_le_bytes());
        }
        put(&[2]);
        put(&[1]);
        put(&[2]);
        b.truncate(b.len() - truncate);
        b
    }

    #[test]
    fn binary_both_endians() {
        for be in [false, true] {
            let s = load(&binary(be, 0), "t.ply").unwrap();
            assert_eq!(s.positions[1], DVec3::new(1.0, 0.0, 0.0));
            assert_eq!(s.face_corners(&s.faces[0]), &[0, 1, 2]);
        }
    }

    #[test]
    fn binary_truncation_names_the_entry() {
        let full = binary(false, 0);
        let e = load(&binary(false, 1), "t.ply").unwrap_err();
        let face_start = full.len() - (2 + 12 + 3);
        assert_eq!(e.location, Location::Byte(face_start as u64), "{e}");
        assert!(e.message.contains("truncated"), "{e}");
        // Cut inside the vertices: the fixed-size check reports the first incomplete vertex.
        let e = load(&binary(false, 17 + 10), "t.ply").unwrap_err();
        assert_eq!(e.location, Location::Byte((face_start - 18) as u64), "{e}");
    }

    #[test]
    fn huge_counts_do_not_allocate() {
        let src = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n";
        let e = load(src.as_bytes(), "t.ply").unwrap_err();
        assert_eq!(e.location, Location::Byte(src.len() as u64));
        // Elements without properties take no bytes whatever their count.
        let src = "ply\nformat ascii 1.0\nelement nothing 18446744073709551615\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert!(load_str(src).is_ok());
    }

    #[test]
    fn no_faces_is_an_empty_scene() {
        let e = load_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n").unwrap_err();
        assert_eq!(e.location, Location::File);
        assert!(e.message.contains("point cloud"));
    }
}
