//! X3D loader (XML encoding): the static-geometry subset the course material uses.
//!
//! Read: an `<X3D>` root holding a `<Scene>` (or a bare `<Scene>` root); `Group`, `StaticGroup`,
//! `Collision` and `Anchor` (plain groups); `Transform` (translation, rotation, scale, center,
//! scaleOrientation, composed as P' = T·C·R·SR·S·-SR·-C·P, nested transforms multiplied outside
//! in); `Shape` with `Appearance`/`Material` (or `UnlitMaterial`); the geometry `TriangleSet`,
//! `IndexedFaceSet`, `IndexedTriangleSet` (each with a `Coordinate` or `CoordinateDouble` child,
//! and optionally `TextureCoordinate` and `Normal`), `ImageTexture` in an `Appearance`,
//! `Box`, `Sphere`, `Cone`, `Cylinder`; `Viewpoint`; `DEF`/`USE` for every node read, resolved
//! to the nearest earlier `DEF` of the same element name.
//!
//! Guarantees:
//! - every Shape that produces faces is one mesh (named by its `DEF`, else by its line) with a
//!   material of its own; geometry `solid="false"` makes it two-sided (X3D's default is solid);
//! - faces are counter-clockwise seen from the front: `ccw="false"` reverses the file's winding,
//!   and so does a mirroring transform (negative determinant), so outward faces stay outward;
//! - colour rule (the course renderer's): a Material that sets `emissiveColor` but not
//!   `diffuseColor` is drawn unlit in its emissive colour (diffuse 0); one that sets
//!   `diffuseColor` uses it, plus its emissive colour if set; one that sets neither, and a Shape
//!   without Appearance or Material, get X3D's default diffuse 0.8 grey. An `UnlitMaterial` is
//!   its emissiveColor (default white) with diffuse 0. Colours and transparency outside [0,1] are
//!   clamped with a warning;
//! - Box, Sphere, Cone and Cylinder are tessellated by [`super::primitives`] at its default
//!   resolution: 32 segments around the y axis, 16 rings pole to pole;
//! - the first Viewpoint is the scene's camera, with the Transforms around it applied to its
//!   position and orientation (the view direction and up vector are carried through the transform
//!   and re-orthonormalised, so a scale does not skew the camera); later ones are ignored with a
//!   warning;
//! - texture coordinates and normals follow X3D's indexing: IndexedFaceSet uses `texCoordIndex`
//!   (`normalIndex`) when it is not empty, with -1 at the same places as `coordIndex`, and
//!   `coordIndex` otherwise; with `normalPerVertex="false"` one normal per polygon (by
//!   `normalIndex`, else in order). IndexedTriangleSet indexes them by `index` (per face: in
//!   order), TriangleSet takes them in order. Every index is range-checked like `coordIndex`.
//!   Normals are carried to world space by the inverse transpose of the transform (not
//!   normalised) and stay with their corners when the winding is reversed;
//! - `ImageTexture`: the first `url` naming an existing file, resolved against the X3D file's
//!   directory (urls with a scheme such as `http:` are not read; with no directory, bytes loaded
//!   from memory, none is). When no url exists the first local one is kept and the renderer
//!   warns that it cannot read it; loading does not fail. A texture is applied only to geometry
//!   with a `TextureCoordinate` (default mappings are not generated; a warning says so), and then,
//!   X3D's rule, it replaces the diffuse colour: the material's diffuse becomes white when the
//!   image exists (the texture colour times the lighting);
//! - the first `Background` (anywhere in the Scene) gives the scene's background colour: its first
//!   `skyColor` colour, clamped to [0,1] with a warning; without a Background or a skyColor the
//!   background is X3D's default, black. Other Backgrounds and their other fields are ignored;
//! - every other element (NavigationInfo, Color, lights,
//!   ROUTEs, ...) is skipped with everything inside it, with one warning per element name giving
//!   the line of its first occurrence. `<head>` under `<X3D>` is skipped silently;
//! - a TriangleSet whose vertex count is not a multiple of 3, or an IndexedTriangleSet whose
//!   index count is not, keeps its whole triangles and drops the rest with a warning (as the X3D
//!   specification says); a `point` list whose number count is not a multiple of 3 is an error;
//! - errors name the file, the element and the line it starts on: XML syntax errors (at the
//!   innermost element open where the parser stopped, the parser's own line:column in the
//!   message), a bad or non-finite number (naming the attribute and, for long values, the line of
//!   the number), a wrong number of values, a coordIndex out of range or below -1, a negative
//!   size or radius, a fieldOfView outside (0, π), a non-finite transformed vertex, a
//!   TextureCoordinate or Normal value count that is not a multiple of 2 or 3, a texCoordIndex or
//!   normalIndex that is too short, out of range or has its -1 elsewhere than coordIndex, too few
//!   texture coordinates or normals for the vertices or faces, a malformed `url`, and an empty
//!   scene (at the `<Scene>` element);
//! - no input makes the loader panic, recurse without bound or allocate without bound: nesting
//!   is limited to [`MAX_DEPTH`] levels, and DEF/USE expansion by caps on visited nodes, vertices,
//!   faces and corners.

use super::input::Input;
use super::primitives::{self, Parts, Tessellation};
use super::{CornerAttrs, Material, Scene, SceneBuilder, Viewpoint};
use crate::error::LoadError;
use glam::{DMat3, DMat4, DQuat, DVec3};
use roxmltree::{Document, Node, NodeId, ParsingOptions};
use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Deepest element nesting followed (the traversal is recursive).
pub(crate) const MAX_DEPTH: usize = 128;
/// Node visits, counting each USE of a group again: bounds DEF/USE expansion of empty groups.
const MAX_VISITS: usize = 1 << 20;
const MAX_VERTICES: usize = 1 << 24;
const MAX_FACES: usize = 1 << 24;
const MAX_CORNERS: usize = 1 << 26;
/// XML nodes the parser may build (elements, attributes' owners, text).
const MAX_XML_NODES: u32 = 1 << 26;

type Res<T> = Result<T, LoadError>;

/// Reads the whole document (the XML parser needs it), then loads it.
pub(super) fn load<R: Read>(mut input: Input<R>, name: &str, dir: Option<&Path>) -> Res<Scene> {
    let mut bytes = Vec::new();
    input.read_rest(&mut bytes);
    let result = load_document(&bytes, name, dir);
    input.finish(result, name)
}

fn load_document(bytes: &[u8], name: &str, dir: Option<&Path>) -> Res<Scene> {
    let text = decode(bytes, name)?;
    let options = ParsingOptions {
        // X3D files usually carry a DOCTYPE; roxmltree still guards against entity bombs.
        allow_dtd: true,
        nodes_limit: MAX_XML_NODES,
        ..ParsingOptions::default()
    };
    let doc =
        Document::parse_with_options(&text, options).map_err(|e| syntax_error(name, &text, &e))?;
    let mut ld = Loader::new(&doc, name, dir);
    let root = doc.root_element();
    let scene = match root.tag_name().name() {
        "Scene" => root,
        "X3D" => {
            let mut scene = None;
            for c in root.children().filter(Node::is_element) {
                match c.tag_name().name() {
                    "Scene" if scene.is_none() => scene = Some(c),
                    "head" => {}
                    _ => ld.skip(c),
                }
            }
            scene.ok_or_else(|| ld.err(root, "no <Scene> element in <X3D>"))?
        }
        other => {
            return Err(ld.err(
                root,
                format!(
                    "not an X3D scene: the root element is <{other}>, expected <X3D> or <Scene>"
                ),
            ));
        }
    };
    ld.active.push(scene.id());
    ld.children(scene, &DMat4::IDENTITY, 0)?;
    let background = ld.background(scene)?;
    let line = ld.line(scene);
    let mut out = ld.b.finish().ok_or_else(|| {
        LoadError::element(name, "Scene", line, "empty scene: no Shape produced a face")
    })?;
    out.background = Some(background);
    Ok(out)
}

/// The text of the file: UTF-8 (a BOM is skipped), or UTF-16 with a BOM.
fn decode<'a>(bytes: &'a [u8], name: &str) -> Res<Cow<'a, str>> {
    let utf16 = |rest: &[u8], unit: fn([u8; 2]) -> u16| {
        let units = rest.chunks_exact(2).map(|c| unit([c[0], c[1]]));
        char::decode_utf16(units)
            .collect::<Result<String, _>>()
            .map(Cow::Owned)
            .map_err(|_| LoadError::element(name, "xml", 1, "invalid UTF-16 text"))
    };
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        return utf16(rest, u16::from_le_bytes);
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        return utf16(rest, u16::from_be_bytes);
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok(Cow::Borrowed(s)),
        Err(e) => {
            let good = e.valid_up_to();
            // Cannot fail: the prefix is exactly the valid part.
            let prefix = std::str::from_utf8(&bytes[..good]).unwrap_or_default();
            let line = 1 + prefix.bytes().filter(|&c| c == b'\n').count();
            let msg = format!("invalid UTF-8 at line {line} (byte {good}); X3D files are UTF-8");
            Err(match open_elements(prefix, good).last() {
                Some((el, at)) => LoadError::element(name, el, *at, msg),
                None => LoadError::element(name, "xml", line, msg),
            })
        }
    }
}

/// An XML syntax error, blamed on the innermost element open where the parser stopped (the
/// element a user has to fix, e.g. a `<Viewpoint ...>` that should have been `<Viewpoint .../>`),
/// at the line that element starts on; the parser's own position is in the message.
fn syntax_error(name: &str, text: &str, e: &roxmltree::Error) -> LoadError {
    use roxmltree::Error as E;
    let offset = match e {
        E::UnexpectedEndOfStream | E::UnclosedRootNode => text.len(),
        _ => byte_offset(text, e.pos().row as usize, e.pos().col as usize),
    };
    let open = open_elements(text, offset);
    let msg = match e {
        E::UnexpectedCloseTag(expected, actual, pos) => format!(
            "XML syntax error: <{expected}> is never closed, found </{actual}> at {pos} \
             (an element without children is written <{expected} ... />)"
        ),
        E::UnexpectedEndOfStream | E::UnclosedRootNode => match open.last() {
            Some((el, _)) => format!("XML syntax error: the file ends inside <{el}>"),
            None => format!("XML syntax error: {e}"),
        },
        _ => format!("XML syntax error: {e}"),
    };
    match open.last() {
        Some((el, line)) => LoadError::element(name, el, *line, msg),
        None => LoadError::element(name, "xml", e.pos().row as usize, msg),
    }
}

/// Byte offset of a 1-based row and character column, clamped to the text.
fn byte_offset(text: &str, row: usize, col: usize) -> usize {
    let mut start = 0;
    for _ in 1..row {
        match text[start..].find('\n') {
            Some(k) => start += k + 1,
            None => return text.len(),
        }
    }
    text[start..]
        .char_indices()
        .nth(col.saturating_sub(1))
        .map_or(text.len(), |(k, _)| start + k)
}

/// The elements open (or being opened) at byte `end`, outermost first, with the lines their start
/// tags begin on. A lenient scan for error messages only: it stops at the first close tag that
/// does not match, which is where a well-formedness error is.
fn open_elements(text: &str, end: usize) -> Vec<(String, usize)> {
    let bytes = text.as_bytes();
    let end = end.min(bytes.len());
    let mut open: Vec<(String, usize)> = Vec::new();
    let mut line = 1;
    let mut i = 0;
    // Index just past `pat` at or after `from`, or the end of the text.
    let past = |from: usize, pat: &str| {
        text.get(from..)
            .and_then(|t| t.find(pat))
            .map_or(bytes.len(), |k| from + k + pat.len())
    };
    let name_at = |from: usize| {
        let n = bytes[from..]
            .iter()
            .take_while(|&&c| !(c.is_ascii_whitespace() || c == b'/' || c == b'>' || c == b'<'))
            .count();
        String::from_utf8_lossy(&bytes[from..from + n]).into_owned()
    };
    while i < end {
        if bytes[i] == b'\n' {
            line += 1;
            i += 1;
            continue;
        }
        if bytes[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &bytes[i..];
        let close = if rest.starts_with(b"<!--") {
            past(i + 4, "-->")
        } else if rest.starts_with(b"<![CDATA[") {
            past(i + 9, "]]>")
        } else if rest.starts_with(b"<?") {
            past(i + 2, "?>")
        } else if rest.starts_with(b"<!") {
            // DOCTYPE, possibly with an internal subset in brackets.
            let gt = past(i + 2, ">");
            let bracket = past(i + 2, "[");
            if bracket < gt {
                past(past(bracket, "]"), ">")
            } else {
                gt
            }
        } else if rest.starts_with(b"</") {
            let tag = name_at(i + 2);
            let gt = past(i + 2, ">");
            if gt > end || open.last().is_none_or(|(top, _)| *top != tag) {
                break;
            }
            open.pop();
            gt
        } else {
            // A start tag: find its '>' outside quoted attribute values.
            let tag = name_at(i + 1);
            if tag.is_empty() {
                // A stray '<': not a tag.
                i += 1;
                continue;
            }
            let (mut j, mut quote) = (i + 1, None);
            while j < bytes.len() {
                match (bytes[j], quote) {
                    (b'"' | b'\'', None) => quote = Some(bytes[j]),
                    (c, Some(q)) if c == q => quote = None,
                    (b'>', None) => break,
                    _ => {}
                }
                j += 1;
            }
            let self_closing = j < bytes.len() && j > i && bytes[j - 1] == b'/';
            if j >= end || !self_closing {
                open.push((tag, line));
            }
            if j >= end {
                break;
            }
            j + 1
        };
        if close > end {
            break;
        }
        line += bytes[i..close].iter().filter(|&&c| c == b'\n').count();
        i = close;
    }
    open
}

/// What a geometry node holds: its Coordinate (points, node), TextureCoordinate and Normal.
#[derive(Default)]
struct Children<'a, 'i> {
    points: Vec<DVec3>,
    coord: Option<Node<'a, 'i>>,
    uvs: Option<(Vec<[f64; 2]>, Node<'a, 'i>)>,
    normals: Option<(Vec<DVec3>, Node<'a, 'i>)>,
}

/// The attributes of the face being emitted (each empty when the geometry has none).
#[derive(Default)]
struct FaceAttrs {
    uvs: Vec<[f64; 2]>,
    normals: Vec<DVec3>,
}

impl FaceAttrs {
    /// Takes the attributes of corners `range` (indices checked already).
    fn push(
        &mut self,
        uvs: &Option<(Vec<[f64; 2]>, Node)>,
        uv_index: Option<&[i64]>,
        normals: &[DVec3],
        normal_index: Option<&[i64]>,
        range: std::ops::Range<usize>,
    ) {
        if let (Some((uvs, _)), Some(ix)) = (uvs, uv_index) {
            self.uvs
                .extend(ix[range.clone()].iter().map(|&i| uvs[i as usize]));
        }
        if let Some(ix) = normal_index {
            self.normals
                .extend(ix[range].iter().map(|&i| normals[i as usize]));
        }
    }
}

/// Which corner order to emit: the file's, or reversed.
fn flipped(ccw: bool, m: &DMat4) -> bool {
    !ccw ^ (m.determinant() < 0.0)
}

struct Loader<'a, 'i> {
    file: &'a str,
    /// Where ImageTexture urls are looked for (`None`: bytes from memory, urls not followed).
    dir: Option<&'a Path>,
    doc: &'a Document<'i>,
    /// Byte offset of the start of every line, for line numbers in O(log n).
    line_starts: Vec<usize>,
    b: SceneBuilder,
    /// DEF name to the nodes defining it, in document order.
    defs: HashMap<&'a str, Vec<Node<'a, 'i>>>,
    /// Keys of warnings already given (element names, mostly).
    warned: HashSet<String>,
    /// The grouping nodes being visited, to refuse a USE of an enclosing node (a cycle).
    active: Vec<NodeId>,
    visits: usize,
    corners: usize,
    viewpoint_seen: bool,
}

impl<'a, 'i> Loader<'a, 'i> {
    fn new(doc: &'a Document<'i>, file: &'a str, dir: Option<&'a Path>) -> Self {
        let text = doc.input_text();
        let line_starts = std::iter::once(0)
            .chain(
                text.bytes()
                    .enumerate()
                    .filter(|&(_, c)| c == b'\n')
                    .map(|(k, _)| k + 1),
            )
            .collect();
        let mut defs: HashMap<&'a str, Vec<Node<'a, 'i>>> = HashMap::new();
        for n in doc.descendants().filter(Node::is_element) {
            if let Some(d) = n.attribute("DEF") {
                defs.entry(d).or_default().push(n);
            }
        }
        Loader {
            file,
            dir,
            doc,
            line_starts,
            b: SceneBuilder::new(file),
            defs,
            warned: HashSet::new(),
            active: Vec::new(),
            visits: 0,
            corners: 0,
            viewpoint_seen: false,
        }
    }

    fn line_at(&self, offset: usize) -> usize {
        self.line_starts.partition_point(|&s| s <= offset)
    }

    fn line(&self, node: Node) -> usize {
        self.line_at(node.range().start)
    }

    fn err(&self, node: Node, msg: impl Into<String>) -> LoadError {
        LoadError::element(self.file, node.tag_name().name(), self.line(node), msg)
    }

    fn warn_once(&mut self, key: String, msg: impl FnOnce() -> String) {
        if self.warned.insert(key) {
            let m = msg();
            self.b.warn(m);
        }
    }

    /// An element this loader does not read where it stands: skipped with its subtree.
    fn skip(&mut self, node: Node) {
        let name = node.tag_name().name();
        let line = self.line(node);
        self.warn_once(name.to_string(), || {
            format!(
                "line {line}: <{name}> is not supported here; skipped with everything inside it"
            )
        });
    }

    /// The node a `USE` stands for (the nearest earlier `DEF` of the same element name), or the
    /// node itself. `None` (with a warning) when the USE cannot be honoured.
    fn resolve(&mut self, node: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
        let Some(name) = node.attribute("USE") else {
            return Some(node);
        };
        let element = node.tag_name().name();
        let at = node.range().start;
        let line = self.line(node);
        let target = self
            .defs
            .get(name)
            .and_then(|v| v.iter().rev().find(|d| d.range().start < at))
            .copied();
        let problem = match target {
            None => "names no earlier DEF",
            Some(t) if t.tag_name().name() != element => "names a DEF of another element",
            Some(t) if t.attribute("USE").is_some() => "names a node that is itself a USE",
            Some(t) if self.active.contains(&t.id()) => "names an enclosing node (a cycle)",
            Some(t) => return Some(t),
        };
        self.warn_once(format!("USE {name} {element} {problem}"), || {
            format!("line {line}: <{element} USE='{name}'> {problem}; skipped")
        });
        None
    }

    /// Visits a child of a grouping node.
    fn visit(&mut self, node: Node<'a, 'i>, m: &DMat4, depth: usize) -> Res<()> {
        let name = node.tag_name().name();
        if name == "Background" {
            return Ok(()); // read by `background`
        }
        if !matches!(
            name,
            "Group" | "StaticGroup" | "Collision" | "Anchor" | "Transform" | "Shape" | "Viewpoint"
        ) {
            self.skip(node);
            return Ok(());
        }
        let Some(node) = self.resolve(node) else {
            return Ok(());
        };
        self.visits += 1;
        if self.visits > MAX_VISITS {
            return Err(self.err(
                node,
                format!("more than {MAX_VISITS} node instances (runaway DEF/USE nesting?)"),
            ));
        }
        if depth >= MAX_DEPTH {
            return Err(self.err(node, format!("nested more than {MAX_DEPTH} levels deep")));
        }
        self.active.push(node.id());
        match name {
            "Transform" => {
                let local = self.transform(node)?;
                let world = *m * local;
                if !world.is_finite() {
                    return Err(self.err(node, "the composed transform is not finite"));
                }
                self.children(node, &world, depth + 1)?;
            }
            "Shape" => self.shape(node, m)?,
            "Viewpoint" => self.viewpoint(node, m)?,
            _ => self.children(node, m, depth + 1)?,
        }
        self.active.pop();
        Ok(())
    }

    fn children(&mut self, node: Node<'a, 'i>, m: &DMat4, depth: usize) -> Res<()> {
        for c in node.children().filter(Node::is_element) {
            self.visit(c, m, depth)?;
        }
        Ok(())
    }

    // ---- attributes ----

    /// The numbers of an attribute (separated by whitespace or commas), `None` when absent.
    fn floats(&self, node: Node, attr: &str) -> Res<Option<Vec<f64>>> {
        let Some(value) = node.attribute(attr) else {
            return Ok(None);
        };
        let mut out = Vec::new();
        for (k, tok) in tokens(value).enumerate() {
            match tok.parse::<f64>() {
                Ok(x) if x.is_finite() => out.push(x),
                Ok(_) => {
                    return Err(self.value_err(
                        node,
                        attr,
                        value,
                        tok,
                        k,
                        "is not a finite number",
                    ));
                }
                Err(_) => return Err(self.value_err(node, attr, value, tok, k, "is not a number")),
            }
        }
        Ok(Some(out))
    }

    /// The integers of an attribute, `None` when absent.
    fn ints(&self, node: Node, attr: &str) -> Res<Option<Vec<i64>>> {
        let Some(value) = node.attribute(attr) else {
            return Ok(None);
        };
        let mut out = Vec::new();
        for (k, tok) in tokens(value).enumerate() {
            match parse_int(tok) {
                Some(x) => out.push(x),
                None => return Err(self.value_err(node, attr, value, tok, k, "is not an integer")),
            }
        }
        Ok(Some(out))
    }

    /// An error about one value of an attribute: names the attribute, the value and its place,
    /// and its line when that is not the element's.
    fn value_err(
        &self,
        node: Node,
        attr: &str,
        value: &str,
        tok: &str,
        index: usize,
        problem: &str,
    ) -> LoadError {
        let shown: String = if tok.chars().count() > 40 {
            tok.chars().take(40).chain("...".chars()).collect()
        } else {
            tok.to_string()
        };
        let mut msg = format!(
            "attribute '{attr}': '{shown}' (value {}) {problem}",
            index + 1
        );
        // The value maps byte for byte onto the file (whitespace normalised to spaces) unless
        // entities or CR LF line ends changed its length; only then can the number's own line
        // be told.
        let within = tok.as_ptr() as usize - value.as_ptr() as usize;
        if let Some(a) = node.attributes().find(|a| a.name() == attr) {
            let range = a.range_value();
            let same = |raw: &str| {
                raw.len() == value.len()
                    && raw
                        .bytes()
                        .zip(value.bytes())
                        .all(|(r, v)| r == v || (v == b' ' && r.is_ascii_whitespace()))
            };
            if self.doc.input_text().get(range.clone()).is_some_and(same) {
                let line = self.line_at(range.start + within);
                if line != self.line(node) {
                    msg.push_str(&format!(" at line {line}"));
                }
            }
        }
        self.err(node, msg)
    }

    fn count_err(&self, node: Node, attr: &str, want: &str, got: usize) -> LoadError {
        self.err(
            node,
            format!("attribute '{attr}' needs {want}, got {got} number(s)"),
        )
    }

    fn float(&self, node: Node, attr: &str, default: f64) -> Res<f64> {
        match self.floats(node, attr)? {
            None => Ok(default),
            Some(v) if v.len() == 1 => Ok(v[0]),
            Some(v) => Err(self.count_err(node, attr, "1 number", v.len())),
        }
    }

    fn non_negative(&self, node: Node, attr: &str, default: f64) -> Res<f64> {
        let x = self.float(node, attr, default)?;
        if x < 0.0 {
            return Err(self.err(node, format!("attribute '{attr}' is negative ({x})")));
        }
        Ok(x)
    }

    fn vec3(&self, node: Node, attr: &str, default: DVec3) -> Res<DVec3> {
        match self.floats(node, attr)? {
            None => Ok(default),
            Some(v) if v.len() == 3 => Ok(DVec3::new(v[0], v[1], v[2])),
            Some(v) => Err(self.count_err(node, attr, "3 numbers", v.len())),
        }
    }

    /// An SFRotation: `None` when absent or the identity; the axis normalised.
    fn axis_angle(&mut self, node: Node, attr: &str) -> Res<Option<(DVec3, f64)>> {
        let Some(v) = self.floats(node, attr)? else {
            return Ok(None);
        };
        if v.len() != 4 {
            return Err(self.count_err(node, attr, "4 numbers (axis x y z, angle)", v.len()));
        }
        let (axis, angle) = (DVec3::new(v[0], v[1], v[2]), v[3]);
        if angle == 0.0 {
            return Ok(None);
        }
        // Scale first so that huge components do not overflow the length.
        let big = axis.abs().max_element();
        let axis = if big > 0.0 {
            (axis / big).normalize()
        } else {
            DVec3::ZERO
        };
        if !axis.is_finite() || axis == DVec3::ZERO {
            let line = self.line(node);
            let element = node.tag_name().name().to_string();
            self.warn_once(format!("zero axis {element} {attr}"), || {
                format!("line {line}: <{element}> {attr} has a zero axis; taken as no rotation")
            });
            return Ok(None);
        }
        Ok(Some((axis, angle)))
    }

    fn rotation(&mut self, node: Node, attr: &str) -> Res<DQuat> {
        Ok(self
            .axis_angle(node, attr)?
            .map_or(DQuat::IDENTITY, |(a, t)| DQuat::from_axis_angle(a, t)))
    }

    fn boolean(&self, node: Node, attr: &str, default: bool) -> Res<bool> {
        match node.attribute(attr).map(str::trim) {
            None => Ok(default),
            Some(v) if v.eq_ignore_ascii_case("true") => Ok(true),
            Some(v) if v.eq_ignore_ascii_case("false") => Ok(false),
            Some(v) => {
                let shown: String = v.chars().take(40).collect();
                Err(self.err(
                    node,
                    format!("attribute '{attr}' must be true or false, not '{shown}'"),
                ))
            }
        }
    }

    /// A colour in [0,1]³ (clamped with a warning), `None` when absent.
    fn colour(&mut self, node: Node, attr: &str) -> Res<Option<[f64; 3]>> {
        if node.attribute(attr).is_none() {
            return Ok(None);
        }
        let c = self.vec3(node, attr, DVec3::ZERO)?;
        let clamped = c.clamp(DVec3::ZERO, DVec3::ONE);
        if clamped != c {
            self.clamp_warning(node, attr);
        }
        Ok(Some(clamped.to_array()))
    }

    fn clamp_warning(&mut self, node: Node, attr: &str) {
        let line = self.line(node);
        let element = node.tag_name().name().to_string();
        self.warn_once(format!("clamp {element} {attr}"), || {
            format!("line {line}: <{element}> {attr} outside [0,1]; clamped")
        });
    }

    // ---- nodes ----

    fn transform(&mut self, node: Node) -> Res<DMat4> {
        let t = self.vec3(node, "translation", DVec3::ZERO)?;
        let c = self.vec3(node, "center", DVec3::ZERO)?;
        let r = self.rotation(node, "rotation")?;
        let s = self.vec3(node, "scale", DVec3::ONE)?;
        let sr = self.rotation(node, "scaleOrientation")?;
        let m = DMat4::from_translation(t)
            * DMat4::from_translation(c)
            * DMat4::from_quat(r)
            * DMat4::from_quat(sr)
            * DMat4::from_scale(s)
            * DMat4::from_quat(sr.inverse())
            * DMat4::from_translation(-c);
        if !m.is_finite() {
            return Err(self.err(node, "the transform is not finite"));
        }
        Ok(m)
    }

    fn shape(&mut self, node: Node<'a, 'i>, m: &DMat4) -> Res<()> {
        let mut appearance = None;
        let mut geometry = None;
        for c in node.children().filter(Node::is_element) {
            let slot = match c.tag_name().name() {
                "Appearance" => &mut appearance,
                "TriangleSet" | "IndexedFaceSet" | "IndexedTriangleSet" | "Box" | "Sphere"
                | "Cone" | "Cylinder" => &mut geometry,
                _ => {
                    self.skip(c);
                    continue;
                }
            };
            if slot.is_some() {
                self.skip(c);
            } else if let Some(r) = self.resolve(c) {
                *slot = Some(r);
            }
        }
        let Some(geometry) = geometry else {
            let line = self.line(node);
            self.b.warn(format!(
                "line {line}: <Shape> without supported geometry; skipped"
            ));
            return Ok(());
        };
        let solid = self.boolean(geometry, "solid", true)?;
        let (mut material, texture) = match appearance {
            Some(a) => self.appearance(a)?,
            None => (Material::default(), None),
        };
        material.two_sided = !solid;
        // A texture needs texture coordinates; only the polygon sets read them from the file.
        let texture = texture.filter(|(path, tex_node)| {
            let has_coords = matches!(
                geometry.tag_name().name(),
                "TriangleSet" | "IndexedFaceSet" | "IndexedTriangleSet"
            ) && geometry
                .children()
                .any(|c| c.has_tag_name("TextureCoordinate"));
            if !has_coords {
                let (line, geom) = (self.line(*tex_node), geometry.tag_name().name().to_string());
                self.warn_once(format!("texture without coordinates {line}"), || {
                    format!(
                        "line {line}: <ImageTexture> not applied: <{geom}> has no <TextureCoordinate> \
                         (default texture mappings are not generated)"
                    )
                });
            } else if path.is_file() {
                // X3D: an RGB texture replaces the diffuse colour (lighting still applies).
                material.diffuse = [1.0; 3];
            }
            has_coords
        });
        let mesh = match node.attribute("DEF") {
            Some(d) => d.to_string(),
            None => format!("Shape (line {})", self.line(node)),
        };
        self.b.begin_mesh(mesh);
        let material = self.b.add_material(material);
        if let Some((path, _)) = texture {
            self.b.set_texture(material, path);
        }
        self.geometry(geometry, m, material)
    }

    /// The Material and the ImageTexture file of an Appearance.
    fn appearance(
        &mut self,
        node: Node<'a, 'i>,
    ) -> Res<(Material, Option<(PathBuf, Node<'a, 'i>)>)> {
        let (mut material, mut texture) = (None, None);
        for c in node.children().filter(Node::is_element) {
            match c.tag_name().name() {
                "Material" | "UnlitMaterial" if material.is_none() => {
                    if let Some(r) = self.resolve(c) {
                        material = Some(self.material(r)?);
                    }
                }
                "ImageTexture" if texture.is_none() => {
                    texture = Some(match self.resolve(c) {
                        Some(r) => self.image_texture(r)?.map(|p| (p, r)),
                        None => None,
                    });
                }
                _ => self.skip(c),
            }
        }
        Ok((material.unwrap_or_default(), texture.flatten()))
    }

    /// The file of an ImageTexture: the first `url` naming an existing file, resolved against
    /// the X3D file's directory; when none exists, the first local one (the renderer warns that
    /// it cannot read it). `None`, with a warning, when there is no local url or no directory.
    fn image_texture(&mut self, node: Node) -> Res<Option<PathBuf>> {
        let urls = self.strings(node, "url")?.unwrap_or_default();
        let line = self.line(node);
        // Only local files: a url with a scheme (http:, https:, data:, ...) is not read.
        let local: Vec<&String> = urls
            .iter()
            .filter(|u| !u.is_empty() && !has_scheme(u))
            .collect();
        let Some(dir) = self.dir else {
            self.warn_once("ImageTexture no dir".into(), || {
                format!("line {line}: <ImageTexture> not read (no directory to look in)")
            });
            return Ok(None);
        };
        if local.is_empty() {
            self.warn_once(format!("ImageTexture no url {line}"), || {
                format!("line {line}: <ImageTexture> has no local file in its url; not applied")
            });
            return Ok(None);
        }
        let paths: Vec<PathBuf> = local.iter().map(|u| dir.join(u.as_str())).collect();
        Ok(paths
            .iter()
            .find(|p| p.is_file())
            .or(paths.first())
            .cloned())
    }

    /// An MFString attribute: double-quoted strings (with `\"` and `\\` escapes) separated by
    /// whitespace or commas; a value without any quote is taken as one string (a common
    /// shorthand). `None` when absent.
    fn strings(&self, node: Node, attr: &str) -> Res<Option<Vec<String>>> {
        let Some(value) = node.attribute(attr) else {
            return Ok(None);
        };
        let v = value.trim();
        if !v.starts_with('"') {
            return Ok(Some(if v.is_empty() {
                vec![]
            } else {
                vec![v.to_string()]
            }));
        }
        let mut out = Vec::new();
        let mut chars = v.chars();
        loop {
            // Between strings: separators, then a quote or the end.
            match chars.by_ref().find(|c| !(c.is_whitespace() || *c == ',')) {
                None => return Ok(Some(out)),
                Some('"') => {}
                Some(c) => {
                    return Err(self.err(
                        node,
                        format!(
                            "attribute '{attr}': string {} should start with '\"', found '{c}'",
                            out.len() + 1
                        ),
                    ));
                }
            }
            let mut cur = String::new();
            loop {
                match chars.next() {
                    None => {
                        return Err(self.err(
                            node,
                            format!(
                                "attribute '{attr}': string {} has no closing '\"'",
                                out.len() + 1
                            ),
                        ));
                    }
                    Some('"') => break,
                    Some('\\') => match chars.next() {
                        Some(c) => cur.push(c),
                        None => continue,
                    },
                    Some(c) => cur.push(c),
                }
            }
            out.push(cur);
        }
    }

    fn material(&mut self, node: Node) -> Res<Material> {
        let diffuse = self.colour(node, "diffuseColor")?;
        let emissive = self.colour(node, "emissiveColor")?;
        let mut transparency = self.float(node, "transparency", 0.0)?;
        if !(0.0..=1.0).contains(&transparency) {
            self.clamp_warning(node, "transparency");
            transparency = transparency.clamp(0.0, 1.0);
        }
        let (diffuse, emissive) = if node.tag_name().name() == "UnlitMaterial" {
            ([0.0; 3], emissive.unwrap_or([1.0; 3]))
        } else {
            match (diffuse, emissive) {
                (Some(d), e) => (d, e.unwrap_or([0.0; 3])),
                // The course renderer draws an emissive-only Material unlit.
                (None, Some(e)) => ([0.0; 3], e),
                (None, None) => (Material::default().diffuse, [0.0; 3]),
            }
        };
        let name = match node.attribute("DEF") {
            Some(d) => d.to_string(),
            None => format!("{} (line {})", node.tag_name().name(), self.line(node)),
        };
        Ok(Material {
            name,
            diffuse,
            emissive,
            transparency,
            two_sided: false,
        })
    }

    /// The children of a geometry node: the local points of its Coordinate (empty when it has
    /// none), its TextureCoordinate points and its Normal vectors (each `None` when absent).
    fn geometry_children(&mut self, geometry: Node<'a, 'i>) -> Res<Children<'a, 'i>> {
        let (mut coord, mut tex, mut normal) = (None, None, None);
        for c in geometry.children().filter(Node::is_element) {
            let slot = match c.tag_name().name() {
                "Coordinate" | "CoordinateDouble" => &mut coord,
                "TextureCoordinate" => &mut tex,
                "Normal" => &mut normal,
                _ => {
                    self.skip(c);
                    continue;
                }
            };
            if slot.is_some() {
                self.skip(c);
            } else {
                *slot = Some(self.resolve(c));
            }
        }
        let mut out = Children::default();
        if let Some(Some(t)) = tex {
            let v = self.tuples(t, "point", 2, "s t per point")?;
            out.uvs = Some((v.chunks_exact(2).map(|c| [c[0], c[1]]).collect(), t));
        }
        if let Some(Some(n)) = normal {
            let v = self.tuples(n, "vector", 3, "x y z per vector")?;
            let normals = v.chunks_exact(3).map(DVec3::from_slice).collect();
            out.normals = Some((normals, n));
        }
        let Some(Some(coord)) = coord else {
            if coord.is_none() {
                let line = self.line(geometry);
                let element = geometry.tag_name().name().to_string();
                self.warn_once(format!("no Coordinate {element}"), || {
                    format!("line {line}: <{element}> has no <Coordinate>")
                });
            }
            return Ok(out);
        };
        let v = self.tuples(coord, "point", 3, "x y z per point")?;
        out.points = v.chunks_exact(3).map(DVec3::from_slice).collect();
        out.coord = Some(coord);
        Ok(out)
    }

    /// The numbers of a multi-value attribute whose count must be a multiple of `n` (empty when
    /// absent).
    fn tuples(&self, node: Node, attr: &str, n: usize, what: &str) -> Res<Vec<f64>> {
        let v = self.floats(node, attr)?.unwrap_or_default();
        if v.len() % n != 0 {
            return Err(self.err(
                node,
                format!(
                    "attribute '{attr}' has {} numbers, not a multiple of {n} ({what})",
                    v.len()
                ),
            ));
        }
        Ok(v)
    }

    /// Adds transformed points as vertices; returns the index of the first.
    fn add_points(&mut self, blame: Node, points: &[DVec3], m: &DMat4) -> Res<u32> {
        if self.b.vertex_count() + points.len() > MAX_VERTICES {
            return Err(self.err(
                blame,
                format!("more than {MAX_VERTICES} vertices in the scene"),
            ));
        }
        let base = self.b.vertex_count() as u32;
        for (k, &p) in points.iter().enumerate() {
            let w = m.transform_point3(p);
            if !w.is_finite() {
                return Err(self.err(
                    blame,
                    format!("point {} is not finite once transformed", k + 1),
                ));
            }
            self.b.add_vertex(w);
        }
        Ok(base)
    }

    /// Checks the caps before adding `faces` faces with `corners` corners in all.
    fn reserve(&mut self, blame: Node, faces: usize, corners: usize) -> Res<()> {
        self.corners += corners;
        if self.b.next_face_id() as usize + faces > MAX_FACES || self.corners > MAX_CORNERS {
            return Err(self.err(
                blame,
                format!("more than {MAX_FACES} faces or {MAX_CORNERS} corners in the scene"),
            ));
        }
        Ok(())
    }

    /// Adds one face; its attributes (when given) are parallel to `corners` and reversed with
    /// them.
    fn face(&mut self, corners: &mut [u32], flip: bool, material: u32, attrs: &mut FaceAttrs) {
        if flip {
            corners.reverse();
            attrs.uvs.reverse();
            attrs.normals.reverse();
        }
        let a = CornerAttrs {
            uvs: (!attrs.uvs.is_empty()).then_some(&attrs.uvs[..]),
            normals: (!attrs.normals.is_empty()).then_some(&attrs.normals[..]),
        };
        self.b.add_face_with(corners, material, a);
        attrs.uvs.clear();
        attrs.normals.clear();
    }

    fn geometry(&mut self, g: Node<'a, 'i>, m: &DMat4, material: u32) -> Res<()> {
        let name = g.tag_name().name();
        let tessellation = match name {
            "TriangleSet" => return self.triangle_set(g, m, material),
            "IndexedFaceSet" => return self.indexed_face_set(g, m, material),
            "IndexedTriangleSet" => return self.indexed_triangle_set(g, m, material),
            "Box" => {
                let size = self.vec3(g, "size", DVec3::splat(2.0))?;
                if size.min_element() < 0.0 {
                    return Err(self.err(g, format!("attribute 'size' is negative ({size})")));
                }
                primitives::box_mesh(size)
            }
            "Sphere" => {
                let r = self.non_negative(g, "radius", 1.0)?;
                primitives::sphere_mesh(r, primitives::DEFAULT_SEGMENTS, primitives::DEFAULT_RINGS)
            }
            "Cone" => {
                let r = self.non_negative(g, "bottomRadius", 1.0)?;
                let h = self.non_negative(g, "height", 2.0)?;
                let parts = Parts {
                    side: self.boolean(g, "side", true)?,
                    top: false,
                    bottom: self.boolean(g, "bottom", true)?,
                };
                primitives::cone_mesh(r, h, primitives::DEFAULT_SEGMENTS, parts)
            }
            _ => {
                let r = self.non_negative(g, "radius", 1.0)?;
                let h = self.non_negative(g, "height", 2.0)?;
                let parts = Parts {
                    side: self.boolean(g, "side", true)?,
                    top: self.boolean(g, "top", true)?,
                    bottom: self.boolean(g, "bottom", true)?,
                };
                primitives::cylinder_mesh(r, h, primitives::DEFAULT_SEGMENTS, parts)
            }
        };
        self.primitive(g, &tessellation, m, material)
    }

    fn primitive(&mut self, g: Node, t: &Tessellation, m: &DMat4, material: u32) -> Res<()> {
        if self.b.vertex_count() + t.positions.len() > MAX_VERTICES {
            return Err(self.err(g, format!("more than {MAX_VERTICES} vertices in the scene")));
        }
        self.reserve(g, t.face_count(), t.corners.len())?;
        t.emit(&mut self.b, m, material)
            .map_err(|_| self.err(g, "a vertex is not finite once transformed"))
    }

    fn triangle_set(&mut self, g: Node<'a, 'i>, m: &DMat4, material: u32) -> Res<()> {
        let flip = flipped(self.boolean(g, "ccw", true)?, m);
        let per_vertex = self.boolean(g, "normalPerVertex", true)?;
        let ch = self.geometry_children(g)?;
        let points = &ch.points;
        let whole = points.len() / 3 * 3;
        if whole != points.len() {
            let line = self.line(g);
            self.b.warn(format!(
                "line {line}: <TriangleSet> has {} points, not a multiple of 3; the last {} dropped",
                points.len(),
                points.len() - whole
            ));
        }
        // Attributes in order: one per vertex, or one normal per triangle.
        let order: Vec<i64> = (0..whole as i64).collect();
        let uv = self.attribute_indices(g, &ch.uvs, None, &order, true)?;
        let per_face = (!per_vertex).then(|| (0..whole as i64 / 3).collect::<Vec<_>>());
        let per_face = per_face.map(|f| f.iter().flat_map(|&k| [k; 3]).collect::<Vec<_>>());
        let normal_order = per_face.as_deref().unwrap_or(&order);
        let nor = self.attribute_indices(g, &ch.normals, None, normal_order, per_vertex)?;
        let normals = self.world_normals(&ch.normals, m)?;
        let base = self.add_points(ch.coord.unwrap_or(g), &points[..whole], m)?;
        self.reserve(g, whole / 3, whole)?;
        let mut attrs = FaceAttrs::default();
        for k in (0..whole).step_by(3) {
            attrs.push(&ch.uvs, uv.as_deref(), &normals, nor.as_deref(), k..k + 3);
            let b = base + k as u32;
            self.face(&mut [b, b + 1, b + 2], flip, material, &mut attrs);
        }
        Ok(())
    }

    fn indexed_face_set(&mut self, g: Node<'a, 'i>, m: &DMat4, material: u32) -> Res<()> {
        let flip = flipped(self.boolean(g, "ccw", true)?, m);
        let per_vertex = self.boolean(g, "normalPerVertex", true)?;
        let index = self.ints(g, "coordIndex")?.unwrap_or_default();
        let ch = self.geometry_children(g)?;
        self.check_indices(g, "coordIndex", &index, ch.points.len(), -1, "Coordinate")?;
        // Corner ranges of the polygons in `index` (empty ones skipped).
        let mut polygons = Vec::new();
        let mut start = 0;
        for k in 0..=index.len() {
            if k == index.len() || index[k] == -1 {
                if k > start {
                    polygons.push(start..k);
                }
                start = k + 1;
            }
        }
        let uv = self.attribute_indices(g, &ch.uvs, Some("texCoordIndex"), &index, true)?;
        let nor = if per_vertex {
            self.attribute_indices(g, &ch.normals, Some("normalIndex"), &index, true)?
        } else {
            // One normal per polygon (normalIndex, else in order), spread over its corners.
            let faces: Vec<i64> = (0..polygons.len() as i64).collect();
            let per_face =
                self.attribute_indices(g, &ch.normals, Some("normalIndex"), &faces, false)?;
            per_face.map(|f| {
                let mut spread = vec![-1; index.len()];
                for (p, &n) in polygons.iter().zip(&f) {
                    spread[p.clone()].fill(n);
                }
                spread
            })
        };
        let normals = self.world_normals(&ch.normals, m)?;
        self.reserve(g, polygons.len(), index.len())?;
        let base = self.add_points(ch.coord.unwrap_or(g), &ch.points, m)?;
        let mut face = Vec::new();
        let mut attrs = FaceAttrs::default();
        for p in polygons {
            face.clear();
            face.extend(index[p.clone()].iter().map(|&i| base + i as u32));
            attrs.push(&ch.uvs, uv.as_deref(), &normals, nor.as_deref(), p);
            self.face(&mut face, flip, material, &mut attrs);
        }
        Ok(())
    }

    fn indexed_triangle_set(&mut self, g: Node<'a, 'i>, m: &DMat4, material: u32) -> Res<()> {
        let flip = flipped(self.boolean(g, "ccw", true)?, m);
        let per_vertex = self.boolean(g, "normalPerVertex", true)?;
        let index = self.ints(g, "index")?.unwrap_or_default();
        let ch = self.geometry_children(g)?;
        self.check_indices(g, "index", &index, ch.points.len(), 0, "Coordinate")?;
        let whole = index.len() / 3 * 3;
        if whole != index.len() {
            let line = self.line(g);
            self.b.warn(format!(
                "line {line}: <IndexedTriangleSet> has {} indices, not a multiple of 3; the last {} dropped",
                index.len(),
                index.len() - whole
            ));
        }
        let index = &index[..whole];
        // The index serves the attributes too; normals per face go in triangle order.
        let uv = self.attribute_indices(g, &ch.uvs, None, index, true)?;
        let per_face: Vec<i64>;
        let normal_order = if per_vertex {
            index
        } else {
            per_face = (0..whole as i64).map(|k| k / 3).collect();
            &per_face
        };
        let nor = self.attribute_indices(g, &ch.normals, None, normal_order, per_vertex)?;
        let normals = self.world_normals(&ch.normals, m)?;
        self.reserve(g, whole / 3, whole)?;
        let base = self.add_points(ch.coord.unwrap_or(g), &ch.points, m)?;
        let mut attrs = FaceAttrs::default();
        for (k, t) in index.chunks_exact(3).enumerate() {
            let mut face = [0u32; 3];
            for (f, &i) in face.iter_mut().zip(t) {
                *f = base + i as u32;
            }
            attrs.push(
                &ch.uvs,
                uv.as_deref(),
                &normals,
                nor.as_deref(),
                3 * k..3 * k + 3,
            );
            self.face(&mut face, flip, material, &mut attrs);
        }
        Ok(())
    }

    /// The index of each corner's attribute (TextureCoordinate point or Normal vector), parallel
    /// to `order` (-1 where `order` separates polygons), or `None` when the geometry has no such
    /// child. `own` names the geometry's own index attribute (texCoordIndex, normalIndex): when
    /// it is present and not empty it must have a value for each of `order`, with -1 at the same
    /// places (X3D's rule; extra values are ignored); otherwise `order` itself is used (X3D's
    /// rule for an empty texCoordIndex or normalIndex: the coordIndex). `separated` says whether
    /// `order` holds -1 separators (false for one normal per face). Every index used is checked
    /// against the child's length.
    fn attribute_indices<T>(
        &self,
        g: Node,
        child: &Option<(Vec<T>, Node)>,
        own: Option<&str>,
        order: &[i64],
        separated: bool,
    ) -> Res<Option<Vec<i64>>> {
        let Some((values, node)) = child else {
            return Ok(None);
        };
        let target = node.tag_name().name();
        let given = match own {
            Some(attr) => self
                .ints(g, attr)?
                .filter(|v| !v.is_empty())
                .map(|v| (attr, v)),
            None => None,
        };
        let Some((attr, mut own)) = given else {
            let lowest = if separated { -1 } else { 0 };
            // `order` is the file's own index list (already checked against the Coordinate) or
            // generated in order; either way it must fit the child too.
            let attr = match g.tag_name().name() {
                "IndexedFaceSet" if separated => "coordIndex",
                "IndexedTriangleSet" if separated => "index",
                _ => "",
            };
            if attr.is_empty() {
                let need = order.iter().copied().max().map_or(0, |m| m + 1);
                if need as u64 > values.len() as u64 {
                    return Err(self.err(
                        g,
                        format!(
                            "the <{target}> has {} value(s), {need} are needed (one per {})",
                            values.len(),
                            if separated { "vertex" } else { "face" }
                        ),
                    ));
                }
            } else {
                self.check_indices(g, attr, order, values.len(), lowest, target)?;
            }
            return Ok(Some(order.to_vec()));
        };
        if own.len() < order.len() {
            return Err(self.err(
                g,
                format!(
                    "attribute '{attr}' has {} value(s), fewer than the {} it needs",
                    own.len(),
                    order.len()
                ),
            ));
        }
        own.truncate(order.len());
        if separated && let Some(k) = (0..order.len()).find(|&k| (order[k] == -1) != (own[k] == -1))
        {
            return Err(self.err(
                g,
                format!(
                    "attribute '{attr}': value {} is {} but coordIndex {} there (the -1 \
                     separators must be at the same places)",
                    k + 1,
                    own[k],
                    if order[k] == -1 {
                        "ends a polygon"
                    } else {
                        "does not"
                    },
                ),
            ));
        }
        self.check_indices(
            g,
            attr,
            &own,
            values.len(),
            if separated { -1 } else { 0 },
            target,
        )?;
        Ok(Some(own))
    }

    /// The Normal vectors in world space: transformed by the inverse transpose of the linear
    /// part of `m` (as its cofactor matrix, signed by the determinant, so that a singular scale
    /// still gives finite normals). Not normalised.
    fn world_normals(&self, normals: &Option<(Vec<DVec3>, Node)>, m: &DMat4) -> Res<Vec<DVec3>> {
        let Some((normals, node)) = normals else {
            return Ok(Vec::new());
        };
        let l = DMat3::from_mat4(*m);
        let (a, b, c) = (l.x_axis, l.y_axis, l.z_axis);
        let sign = if l.determinant() < 0.0 { -1.0 } else { 1.0 };
        let cof = DMat3::from_cols(b.cross(c), c.cross(a), a.cross(b)) * sign;
        normals
            .iter()
            .enumerate()
            .map(|(k, &n)| {
                let w = if l == DMat3::IDENTITY { n } else { cof * n };
                if w.is_finite() {
                    Ok(w)
                } else {
                    Err(self.err(
                        *node,
                        format!("vector {} is not finite once transformed", k + 1),
                    ))
                }
            })
            .collect()
    }

    /// Every index in `lowest..count` (`lowest` is -1 where -1 separates polygons); `target`
    /// names the node indexed.
    fn check_indices(
        &self,
        g: Node,
        attr: &str,
        index: &[i64],
        count: usize,
        lowest: i64,
        target: &str,
    ) -> Res<()> {
        let unit = if target == "Normal" {
            "vector"
        } else {
            "point"
        };
        for (k, &i) in index.iter().enumerate() {
            if i < lowest {
                let what = if lowest == -1 {
                    "is below -1 (only -1 separates polygons)"
                } else {
                    "is negative"
                };
                return Err(self.err(
                    g,
                    format!("attribute '{attr}': index {i} (value {}) {what}", k + 1),
                ));
            }
            if i >= 0 && i as u64 >= count as u64 {
                return Err(self.err(
                    g,
                    format!(
                        "attribute '{attr}': index {i} (value {}) is out of range: the {target} has {count} {unit}(s)",
                        k + 1
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The background colour: the first `Background`'s first `skyColor` colour (clamped to
    /// [0,1] with a warning), black (X3D's default) when there is no Background or no skyColor.
    fn background(&mut self, scene: Node<'a, 'i>) -> Res<[f64; 3]> {
        const BLACK: [f64; 3] = [0.0; 3];
        let Some(node) = scene.descendants().find(|n| n.has_tag_name("Background")) else {
            return Ok(BLACK);
        };
        let Some(node) = self.resolve(node) else {
            return Ok(BLACK);
        };
        let Some(v) = self.floats(node, "skyColor")? else {
            return Ok(BLACK);
        };
        if v.len() % 3 != 0 {
            return Err(self.count_err(node, "skyColor", "a multiple of 3 numbers", v.len()));
        }
        let Some(first) = v.get(..3) else {
            return Ok(BLACK);
        };
        let c = DVec3::from_slice(first);
        let clamped = c.clamp(DVec3::ZERO, DVec3::ONE);
        if clamped != c {
            self.clamp_warning(node, "skyColor");
        }
        Ok(clamped.to_array())
    }

    fn viewpoint(&mut self, node: Node, m: &DMat4) -> Res<()> {
        let position = self.vec3(node, "position", DVec3::new(0.0, 0.0, 10.0))?;
        let orientation = self.axis_angle(node, "orientation")?;
        let fov = self.float(node, "fieldOfView", PI / 4.0)?;
        if !(fov > 0.0 && fov < PI) {
            return Err(self.err(
                node,
                format!("attribute 'fieldOfView' must be between 0 and π radians, not {fov}"),
            ));
        }
        if self.viewpoint_seen {
            let line = self.line(node);
            self.warn_once("later Viewpoint".into(), || {
                format!("line {line}: only the first <Viewpoint> is used; later ones are ignored")
            });
            return Ok(());
        }
        self.viewpoint_seen = true;
        let position = m.transform_point3(position);
        if !position.is_finite() {
            return Err(self.err(node, "the position is not finite once transformed"));
        }
        let local = orientation.map_or(DQuat::IDENTITY, |(a, t)| DQuat::from_axis_angle(a, t));
        let linear = DMat3::from_mat4(*m);
        let (axis, angle) = if linear == DMat3::IDENTITY {
            // Keep the file's numbers exactly.
            orientation.unwrap_or((DVec3::Z, 0.0))
        } else {
            match view_rotation(linear * (local * DVec3::NEG_Z), linear * (local * DVec3::Y)) {
                Some(q) => {
                    let (axis, angle) = q.to_axis_angle();
                    if angle == 0.0 {
                        (DVec3::Z, 0.0)
                    } else {
                        (axis, angle)
                    }
                }
                None => {
                    let line = self.line(node);
                    self.b.warn(format!(
                        "line {line}: the transforms around <Viewpoint> flatten its view; orientation taken as given"
                    ));
                    orientation.unwrap_or((DVec3::Z, 0.0))
                }
            }
        };
        self.b.set_viewpoint(Viewpoint {
            position,
            orientation_axis: axis,
            orientation_angle: angle,
            field_of_view: fov,
        });
        Ok(())
    }
}

/// The rotation taking the default view (looking down -z, y up) to one looking along `dir` with
/// `up` as near up as it can be; `None` when they do not span a plane.
fn view_rotation(dir: DVec3, up: DVec3) -> Option<DQuat> {
    let z = -dir.normalize_or_zero();
    let x = up.cross(z).normalize_or_zero();
    if !(z.is_finite() && x.is_finite()) || z == DVec3::ZERO || x == DVec3::ZERO {
        return None;
    }
    let y = z.cross(x);
    let q = DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize();
    q.is_finite().then_some(q)
}

/// Whether a url names a scheme (`http:`, `data:`, ...) rather than a file. A one-letter
/// scheme is a Windows drive and counts as a file.
fn has_scheme(url: &str) -> bool {
    url.split_once(':').is_some_and(|(scheme, _)| {
        scheme.len() > 1
            && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
            && scheme
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
    })
}

/// The values of an X3D multi-value field: separated by whitespace or commas.
fn tokens(value: &str) -> impl Iterator<Item = &str> {
    value
        .split(|c: char| c.is_ascii_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
}

/// An SFInt32: decimal or 0x hexadecimal, optionally signed.
fn parse_int(tok: &str) -> Option<i64> {
    let (neg, digits) = match tok.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, tok.strip_prefix('+').unwrap_or(tok)),
    };
    let magnitude = match digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        Some(hex) if !hex.starts_with(['+', '-']) => i64::from_str_radix(hex, 16).ok()?,
        Some(_) => return None,
        None if digits.starts_with(['+', '-']) => return None,
        None => digits.parse::<i64>().ok()?,
    };
    Some(if neg { -magnitude } else { magnitude })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_elements_finds_the_unclosed_tag() {
        let text = "<Scene>\n <Viewpoint a='>'>\n <Group/>\n</Scene>";
        let at = text.find("</Scene>").unwrap();
        let open = open_elements(text, at + 3);
        assert_eq!(
            open,
            vec![("Scene".to_string(), 1), ("Viewpoint".to_string(), 2)]
        );
        assert!(open_elements("", 10).is_empty());
        assert_eq!(
            open_elements("<!-- <a> -->\n<b", 100),
            vec![("b".into(), 2)]
        );
    }

    #[test]
    fn ints_and_offsets() {
        assert_eq!(parse_int("-1"), Some(-1));
        assert_eq!(parse_int("0x1F"), Some(31));
        assert_eq!(parse_int("+7"), Some(7));
        assert_eq!(parse_int("--1"), None);
        assert_eq!(parse_int("1.0"), None);
        assert_eq!(byte_offset("ab\ncd", 2, 2), 4);
        assert_eq!(byte_offset("ab", 9, 9), 2);
    }
}
