//! Wavefront OBJ loader, with its own parser so that every error names the line.
//!
//! Guarantees of a scene returned from here (besides the [`Scene`] invariants kept by the
//! builder): every corner index is in range, every coordinate is finite, faces keep the file's
//! winding, and face ids follow the order of the `f` statements.
//!
//! Read: `v x y z [w]` (w and trailing vertex colours ignored), `vt u [v [w]]` (v defaults to 0,
//! w ignored), `vn x y z`, `f` with any number of corners in the forms `i`, `i/t`, `i//n`, `i/t/n`,
//! negative indices (relative to the vertices, texture coordinates or normals defined before that
//! line), `o`, `usemtl`, `mtllib`, `#` comments, `\r\n` endings, a leading UTF-8 byte-order
//! mark and trailing-backslash line continuations. A face gets texture coordinates (normals) only when every one of its corners
//! names one; texture and normal indices are range-checked like vertex indices, and an index out
//! of range is an error naming the face's line.
//!
//! `o NAME` starts a new mesh. `g NAME` does not: groups are labels only, because closedness and
//! orientation are decided per mesh and exporters freely split one closed solid into several
//! groups (by material, by smoothing, ...).
//!
//! Positive indices may refer to vertices defined later in the file (faces are handed to the
//! builder only after every vertex is read); such an index that is still out of range at the end
//! is reported at its own line, but only after the rest of the file parsed without error.
//!
//! `vp`, `s`, `g`, `l` and `p` are ignored; any other statement gets one warning per
//! keyword. A missing or unreadable `.mtl` is a warning, an error inside one is an error naming
//! that file. With no directory (bytes loaded from memory) `mtllib` is not followed.
//!
//! Invalid UTF-8 is an error only where it changes the geometry (a number); in names (`o`,
//! `usemtl`, `newmtl`) it is replaced, the same way on both sides of a material lookup, and
//! `mtllib` file names are used as raw bytes on Unix.
//!
//! The file is read a batch of blocks of whole lines at a time (see [`super::input`]), each
//! block's numbers parsed on all cores and its statements then taken in file order: memory holds
//! the scene being built and two batches (about 16 MiB) of text, not the file.

use super::input::Input;
use super::text::{Tokens, file_label, lossy, parse_coord, show};
use super::{CornerAttrs, Material, Scene, SceneBuilder, mtl};
use crate::error::LoadError;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};

mod block;
use block::{Block, RawCorner, Statement, continues};

pub(super) fn load<R: Read>(
    mut input: Input<R>,
    name: &str,
    dir: Option<&Path>,
) -> Result<Scene, LoadError> {
    let result = parse(&mut input, name, dir);
    input.finish(result, name)
}

/// Blocks (about 1 MiB of whole lines each) read before they are parsed together on all cores.
const BLOCKS_PER_BATCH: usize = 8;

/// Reads the file a batch of blocks at a time, parses the blocks' lines on all cores
/// ([`Block::parse`]: numbers and index syntax, which need nothing from the rest of the file),
/// then hands their statements to the parser in file order, which resolves indices against what
/// was defined before each line and stops at the first error. So the scene, the warnings and the
/// first error are those of reading the lines one by one. While a batch is parsed on the pool,
/// this thread hands the batch before it to the parser and reads the batch after it: memory
/// holds two batches of text (about 16 MiB), not the file.
fn parse<R: Read>(
    input: &mut Input<R>,
    name: &str,
    dir: Option<&Path>,
) -> Result<Scene, LoadError> {
    let mut parser = Parser::new(name, dir);
    let mut lines_before = 0usize;
    // Two slots: one batch parsed while the other's blocks are replayed and its text refilled.
    let mut texts: [Vec<Vec<u8>>; 2] = Default::default();
    let mut blocks: [Vec<Block>; 2] = Default::default();
    // Per slot: the block in which reading failed (its last line may be cut short), if any.
    let mut failed_in: [Option<usize>; 2] = [None, None];
    let mut to_parse = read_batch(input, &mut texts[0], &mut failed_in[0]);
    let mut to_replay = 0;
    let mut slot = 0;
    while to_parse > 0 || to_replay > 0 {
        let ([t0, t1], [b0, b1]) = (&mut texts, &mut blocks);
        let (text, next_text, parsed, parsed_before) = match slot {
            0 => (&*t0, t1, b0, &*b1),
            _ => (&*t1, t0, b1, &*b0),
        };
        let more = to_parse == BLOCKS_PER_BATCH;
        let failed_before = &mut failed_in[1 - slot];
        let next = rayon::in_place_scope(|scope| {
            scope.spawn(|_| {
                parsed.resize_with(to_parse, Block::default);
                (text[..to_parse].par_iter())
                    .zip(parsed.par_iter_mut())
                    .for_each(|(text, block)| block.parse(text));
            });
            for (k, block) in parsed_before[..to_replay].iter().enumerate() {
                if let Err(e) = parser.replay(block, lines_before) {
                    // Read line by line, the file would not have been read past this block:
                    // a read error met later (read ahead) is not its first problem.
                    if failed_before.is_none_or(|f| f > k) {
                        input.forget_error();
                    }
                    return Err(e);
                }
                lines_before += block.lines;
            }
            Ok(if more {
                read_batch(input, next_text, failed_before)
            } else {
                0
            })
        })?;
        (to_replay, to_parse, slot) = (to_parse, next, 1 - slot);
    }
    parser.finish()
}

/// Reads up to [`BLOCKS_PER_BATCH`] blocks into `texts`; returns how many. `failed_in`: the
/// block in which reading failed, if any.
fn read_batch<R: Read>(
    input: &mut Input<R>,
    texts: &mut Vec<Vec<u8>>,
    failed_in: &mut Option<usize>,
) -> usize {
    *failed_in = None;
    let mut read = 0;
    while read < BLOCKS_PER_BATCH {
        if texts.len() == read {
            texts.push(Vec::new());
        }
        if !input.lines_block(&mut texts[read], continues) {
            break;
        }
        if input.failed() {
            failed_in.get_or_insert(read);
        }
        read += 1;
    }
    read
}

/// A face as read in the first pass: its corners are the next `len` entries of `Parser::corners`.
struct FaceRec {
    len: u32,
    line: usize,
    /// Index into `Parser::mat_names`, or `NO_MATERIAL`.
    slot: u32,
}

const NO_MATERIAL: u32 = u32::MAX;
/// A corner without a texture coordinate or normal index.
const NONE: u32 = u32::MAX;

struct Parser<'a> {
    name: &'a str,
    dir: Option<&'a Path>,
    builder: SceneBuilder,
    /// Corner indices (0-based, already resolved) of all faces, face after face.
    corners: Vec<u32>,
    /// Per corner: 0-based `vt` and `vn` index (resolved, range-checked at the end), or `NONE`;
    /// corners past the end of a list have none (most files give no corner any).
    corner_tex: Vec<u32>,
    corner_nor: Vec<u32>,
    uvs: Vec<[f64; 2]>,
    normals: Vec<DVec3>,
    faces: Vec<FaceRec>,
    /// `o` statements: (number of faces before it, object name).
    objects: Vec<(usize, String)>,
    /// Material names used by `usemtl`, in order of first use.
    mat_names: Vec<String>,
    mat_slots: HashMap<String, u32>,
    slot: u32,
    /// Materials read from the `.mtl` files, first definition of a name wins.
    library: HashMap<String, (Material, Option<PathBuf>)>,
    /// Positive indices past the vertices defined so far: (line, 1-based index, vertices defined
    /// before that line). Only entries larger than every earlier one are kept, which is enough to
    /// find the first out-of-range one at the end.
    forward: Vec<(usize, u64, usize)>,
    unknown_seen: Vec<Vec<u8>>,
    warned_no_dir: bool,
}

impl<'a> Parser<'a> {
    fn new(name: &'a str, dir: Option<&'a Path>) -> Self {
        Parser {
            name,
            dir,
            builder: SceneBuilder::new(name),
            corners: Vec::new(),
            corner_tex: Vec::new(),
            corner_nor: Vec::new(),
            uvs: Vec::new(),
            normals: Vec::new(),
            faces: Vec::new(),
            objects: Vec::new(),
            mat_names: Vec::new(),
            mat_slots: HashMap::new(),
            slot: NO_MATERIAL,
            library: HashMap::new(),
            forward: Vec::new(),
            unknown_seen: Vec::new(),
            warned_no_dir: false,
        }
    }

    fn err(&self, line: usize, msg: impl Into<String>) -> LoadError {
        LoadError::line(self.name, line, msg)
    }

    /// Hands a parsed block's statements to the scene in order; `lines_before`: the file's
    /// lines before the block.
    fn replay(&mut self, block: &Block, lines_before: usize) -> Result<(), LoadError> {
        let (mut vertices, mut corners, mut raw) =
            (&block.vertices[..], &block.corners[..], &block.raw[..]);
        for statement in &block.statements {
            match *statement {
                Statement::Vertices { line, count } => {
                    let (these, rest) = vertices.split_at(count);
                    vertices = rest;
                    let room = (u32::MAX as usize).saturating_sub(self.builder.vertex_count());
                    if count > room {
                        let line = lines_before + line + room;
                        return Err(self.err(line, "too many vertices (more than 4294967295)"));
                    }
                    self.builder.add_vertices(these);
                }
                Statement::Face { line, len, max } => {
                    let (these, rest) = corners.split_at(len);
                    corners = rest;
                    self.plain_face(these, max, lines_before + line)?
                }
                Statement::RawFace { line, len, ref bad } => {
                    let (these, rest) = raw.split_at(len);
                    raw = rest;
                    self.face(these, bad.as_deref(), lines_before + line)?
                }
                Statement::Other { line, start, end } => {
                    self.statement(&block.text[start..end], lines_before + line)?
                }
                Statement::BadVertex { line, ref message } => {
                    return Err(self.err(lines_before + line, message.as_str()));
                }
            }
        }
        Ok(())
    }

    /// A face of positive vertex indices alone (0-based `corners`, the largest 1-based `max`):
    /// [`Parser::face`] without the checks that cannot fail.
    fn plain_face(&mut self, corners: &[u32], max: u32, line: usize) -> Result<(), LoadError> {
        let defined = self.builder.vertex_count();
        if max as usize > defined {
            // Forward references, kept as `vertex_index` keeps them.
            for &c in corners {
                self.note_forward(c as u64 + 1, line, defined);
            }
        }
        self.corners.extend_from_slice(corners);
        self.push_face(corners.len(), line)
    }

    /// Records a positive 1-based index past the `defined` vertices before its line, when it is
    /// larger than every one recorded so far (enough to find the first still out of range at
    /// the end).
    fn note_forward(&mut self, i: u64, line: usize, defined: usize) {
        if i > defined as u64 && self.forward.last().is_none_or(|&(_, m, _)| i > m) {
            self.forward.push((line, i, defined));
        }
    }

    /// Ends a face whose `n` corners were just added.
    fn push_face(&mut self, n: usize, line: usize) -> Result<(), LoadError> {
        // Face ids and corner offsets in a scene are u32.
        if self.faces.len() >= u32::MAX as usize || self.corners.len() > u32::MAX as usize {
            return Err(self.err(line, "too many faces or face corners for one scene"));
        }
        self.faces.push(FaceRec {
            len: n as u32,
            line,
            slot: self.slot,
        });
        Ok(())
    }

    /// A statement other than `v` and `f` (which come parsed: [`Block`]).
    fn statement(&mut self, text: &[u8], line: usize) -> Result<(), LoadError> {
        let mut toks = Tokens::new(text);
        let Some(kw) = toks.next() else {
            return Ok(());
        };
        match kw {
            b"o" => {
                let name = lossy(toks.rest());
                let name = if name.is_empty() {
                    format!("object at line {line}")
                } else {
                    name.into_owned()
                };
                self.objects.push((self.faces.len(), name));
                Ok(())
            }
            b"usemtl" => {
                let name = lossy(toks.rest());
                if name.is_empty() {
                    self.builder.warn(format!(
                        "{}:{line}: usemtl without a name: default material",
                        self.name
                    ));
                    self.slot = NO_MATERIAL;
                } else if let Some(&s) = self.mat_slots.get(name.as_ref()) {
                    self.slot = s;
                } else {
                    let s = self.mat_names.len() as u32;
                    self.mat_names.push(name.clone().into_owned());
                    self.mat_slots.insert(name.into_owned(), s);
                    self.slot = s;
                }
                Ok(())
            }
            b"mtllib" => self.mtllib(toks.rest(), line),
            b"vt" => {
                let mut uv = [0.0; 2];
                let mut n = 0;
                for t in toks.take(3) {
                    let x = parse_coord(t).map_err(|m| self.err(line, m))?;
                    if n < 2 {
                        uv[n] = x;
                    }
                    n += 1;
                }
                if n == 0 {
                    return Err(self.err(line, "vt has no coordinates, needs 1 to 3"));
                }
                self.uvs.push(uv);
                Ok(())
            }
            b"vn" => {
                let mut c = [0.0f64; 3];
                for (i, slot) in c.iter_mut().enumerate() {
                    let Some(t) = toks.next() else {
                        return Err(self.err(line, format!("vn has {i} coordinates, needs 3")));
                    };
                    *slot = parse_coord(t).map_err(|m| self.err(line, m))?;
                }
                self.normals.push(DVec3::from_array(c));
                Ok(())
            }
            b"vp" | b"s" | b"g" | b"l" | b"p" => Ok(()),
            _ => {
                if !self.unknown_seen.iter().any(|k| k == kw) {
                    self.unknown_seen.push(kw.to_vec());
                    self.builder.warn(format!(
                        "{}:{line}: unsupported statement '{}' ignored (reported once)",
                        self.name,
                        show(kw)
                    ));
                }
                Ok(())
            }
        }
    }

    /// A face: its corners resolved in order, then `bad` (the syntax error of the corner after
    /// them), if any.
    fn face(&mut self, raw: &[RawCorner], bad: Option<&str>, line: usize) -> Result<(), LoadError> {
        let defined = self.builder.vertex_count();
        let start = self.corners.len();
        let truncate = |p: &mut Self| {
            p.corners.truncate(start);
            p.corner_tex.truncate(start.min(p.corner_tex.len()));
            p.corner_nor.truncate(start.min(p.corner_nor.len()));
        };
        for c in raw {
            match self.corner(c, line, defined) {
                Ok((v, tex, nor)) => {
                    self.corners.push(v);
                    for (list, i) in [(&mut self.corner_tex, tex), (&mut self.corner_nor, nor)] {
                        if i != NONE {
                            list.resize(self.corners.len() - 1, NONE);
                            list.push(i);
                        }
                    }
                }
                Err(e) => {
                    truncate(self);
                    return Err(e);
                }
            }
        }
        if let Some(message) = bad {
            truncate(self);
            return Err(self.err(line, message));
        }
        let n = self.corners.len() - start;
        if n < 3 {
            truncate(self);
            return Err(self.err(line, format!("face has {n} corners, needs at least 3")));
        }
        self.push_face(n, line)
    }

    /// Resolves one face corner to 0-based vertex, texture-coordinate and normal indices (the
    /// last two `NONE` when absent). Negative indices are range-checked now; positive ones past
    /// what is defined so far at the end.
    fn corner(
        &mut self,
        c: &RawCorner,
        line: usize,
        defined: usize,
    ) -> Result<(u32, u32, u32), LoadError> {
        let v = self.vertex_index(c.v, line, defined)?;
        let tex = self.attr_index(c.tex, "texture coordinate", self.uvs.len(), line)?;
        let nor = self.attr_index(c.nor, "normal", self.normals.len(), line)?;
        Ok((v, tex, nor))
    }

    /// Index 0 is an error; a negative index counts back from the `defined` items before this
    /// line (resolved 0-based here, or an error if it reaches past the first); a positive one is
    /// the caller's (`None`).
    fn zero_or_relative(
        &self,
        i: i64,
        defined: usize,
        what: &str,
        plural: &str,
        line: usize,
    ) -> Result<Option<u32>, LoadError> {
        if i == 0 {
            return Err(self.err(line, format!("{what} index 0 (OBJ indices start at 1)")));
        }
        if i > 0 {
            return Ok(None);
        }
        let abs = i.unsigned_abs();
        if abs > defined as u64 {
            return Err(self.err(
                line,
                format!(
                    "{what} index {i} out of range: only {defined} {plural} are defined before this line"
                ),
            ));
        }
        Ok(Some((defined as u64 - abs) as u32))
    }

    /// A `vt` or `vn` index of a corner: 0-based, or `NONE` when not given.
    fn attr_index(
        &self,
        index: Option<i64>,
        what: &str,
        defined: usize,
        line: usize,
    ) -> Result<u32, LoadError> {
        let Some(i) = index else {
            return Ok(NONE);
        };
        if let Some(resolved) =
            self.zero_or_relative(i, defined, what, &format!("{what}s"), line)?
        {
            return Ok(resolved);
        }
        // Checked against the whole file at the end; NONE - 1 would be ambiguous, so refuse it.
        if i as u64 >= NONE as u64 {
            return Err(self.err(line, format!("{what} index {i} out of range")));
        }
        Ok((i - 1) as u32)
    }

    fn vertex_index(&mut self, i: i64, line: usize, defined: usize) -> Result<u32, LoadError> {
        if let Some(resolved) = self.zero_or_relative(i, defined, "vertex", "vertices", line)? {
            return Ok(resolved);
        }
        let i = i as u64;
        if i > u32::MAX as u64 {
            return Err(self.err(
                line,
                format!(
                    "vertex index {i} out of range: {defined} vertices are defined before this line"
                ),
            ));
        }
        self.note_forward(i, line, defined);
        Ok((i - 1) as u32)
    }

    fn mtllib(&mut self, rest: &[u8], line: usize) -> Result<(), LoadError> {
        let Some(dir) = self.dir else {
            if !self.warned_no_dir {
                self.warned_no_dir = true;
                self.builder.warn(format!(
                    "{}:{line}: mtllib not followed (no directory to look in)",
                    self.name
                ));
            }
            return Ok(());
        };
        if rest.is_empty() {
            self.builder
                .warn(format!("{}:{line}: mtllib without a file name", self.name));
            return Ok(());
        }
        // The statement lists files separated by spaces, but some exporters write one name
        // containing spaces: prefer the whole rest of the line when such a file exists.
        let whole = dir.join(path_from_bytes(rest));
        let paths: Vec<PathBuf> = if whole.is_file() {
            vec![whole]
        } else {
            Tokens::new(rest)
                .map(|t| dir.join(path_from_bytes(t)))
                .collect()
        };
        for path in paths {
            let shown = path.display().to_string();
            let bytes = match std::fs::read(&path) {
                Ok(b) => b,
                Err(e) => {
                    self.builder.warn(format!(
                        "{}:{line}: material library {shown} not read ({e}); its materials are replaced by the default",
                        self.name
                    ));
                    continue;
                }
            };
            let mut warnings = Vec::new();
            let (materials, textures) = mtl::parse_with_textures(&bytes, &shown, &mut warnings)?;
            for w in warnings {
                self.builder.warn(w);
            }
            // A texture is named relative to its material library.
            let mtl_dir = path.parent().unwrap_or(dir).to_path_buf();
            for (m, t) in materials.into_iter().zip(textures) {
                if self.library.contains_key(&m.name) {
                    self.builder.warn(format!(
                        "{shown}: material '{}' defined again; the first definition is used",
                        m.name
                    ));
                } else {
                    let t = t.map(|t| mtl_dir.join(path_from_bytes(&t)));
                    self.library.insert(m.name.clone(), (m, t));
                }
            }
        }
        Ok(())
    }

    /// The first (by line) positive index that is still out of range at the end of the file.
    fn range_error(&self) -> Option<LoadError> {
        let total = self.builder.vertex_count() as u64;
        let mut first: Option<(usize, String)> = self
            .forward
            .iter()
            .find(|f| f.1 > total)
            .map(|&(line, i, defined)| {
                (
                    line,
                    format!(
                        "vertex index {i} out of range: the file has {total} vertices ({defined} defined before this line)"
                    ),
                )
            });
        // Texture and normal indices: the first face (and its first bad corner) with either.
        let given = self.corner_tex.len().max(self.corner_nor.len());
        let mut start = 0usize;
        for f in &self.faces {
            if start >= given {
                break;
            }
            if first.as_ref().is_some_and(|(l, _)| *l <= f.line) {
                break;
            }
            let end = start + f.len as usize;
            for k in start..end {
                for (what, i, total) in [
                    (
                        "texture coordinate",
                        attr(&self.corner_tex, k),
                        self.uvs.len(),
                    ),
                    ("normal", attr(&self.corner_nor, k), self.normals.len()),
                ] {
                    if i != NONE
                        && i as usize >= total
                        && first.as_ref().is_none_or(|(l, _)| *l > f.line)
                    {
                        let msg = format!(
                            "{what} index {} out of range: the file has {total} {what}s",
                            i as u64 + 1
                        );
                        first = Some((f.line, msg));
                    }
                }
            }
            start = end;
        }
        first.map(|(line, msg)| self.err(line, msg))
    }

    fn finish(self) -> Result<Scene, LoadError> {
        if let Some(e) = self.range_error() {
            return Err(e);
        }

        let mut b = self.builder;
        // Resolve material names to scene materials, in order of first use.
        let mut slot_material = Vec::with_capacity(self.mat_names.len());
        for name in &self.mat_names {
            match self.library.get(name) {
                Some((m, t)) => {
                    let id = b.add_material(m.clone());
                    if let Some(t) = t {
                        b.set_texture(id, t.clone());
                    }
                    slot_material.push(id)
                }
                None => {
                    b.warn(format!(
                        "{}: material '{name}' is not defined in any material library; default material used",
                        self.name
                    ));
                    slot_material.push(b.default_material());
                }
            }
        }

        // Which faces the builder keeps whole with no other test, asked on all cores (it reads
        // the vertices only): most of adding a face is that test.
        let starts: Vec<u32> = (self.faces.iter())
            .scan(0u32, |at, f| {
                let start = *at;
                *at += f.len;
                Some(start)
            })
            .collect();
        let plain: Vec<bool> = (self.faces.par_iter().zip(&starts))
            .with_min_len(4096)
            .map(|(f, &start)| {
                let start = start as usize;
                b.is_plain_triangle(&self.corners[start..start + f.len as usize])
            })
            .collect();
        drop(starts);
        b.begin_mesh(file_label(self.name));
        let mut objects = self.objects.into_iter().peekable();
        let mut start = 0usize;
        let mut default = None;
        let given = |list: &[u32], start: usize, end: usize| {
            list.len() >= end && !list[start..end].contains(&NONE)
        };
        // A plain triangle without corner attributes: the faces added in runs.
        let bare = |k: usize, start: usize| {
            plain[k]
                && !given(&self.corner_tex, start, start + 3)
                && !given(&self.corner_nor, start, start + 3)
        };
        let mut k = 0;
        while k < self.faces.len() {
            let f = &self.faces[k];
            while let Some((_, name)) = objects.next_if(|(at, _)| *at <= k) {
                b.begin_mesh(name);
            }
            let end = start + f.len as usize;
            let material = match slot_material.get(f.slot as usize) {
                Some(&m) => m,
                None => *default.get_or_insert_with(|| b.default_material()),
            };
            if bare(k, start) {
                // The run of bare triangles of this material within this object.
                let mut run = 1;
                while k + run < self.faces.len()
                    && self.faces[k + run].slot == f.slot
                    && objects.peek().is_none_or(|(at, _)| *at > k + run)
                    && bare(k + run, start + 3 * run)
                {
                    run += 1;
                }
                b.add_plain_triangles(&self.corners[start..start + 3 * run], material);
                start += 3 * run;
                k += run;
                continue;
            }
            if let Some(c) = self.corners.get(start..end) {
                let uvs: Option<Vec<[f64; 2]>> = given(&self.corner_tex, start, end).then(|| {
                    let tex = &self.corner_tex[start..end];
                    tex.iter().map(|&i| self.uvs[i as usize]).collect()
                });
                let normals: Option<Vec<DVec3>> = given(&self.corner_nor, start, end).then(|| {
                    let nor = &self.corner_nor[start..end];
                    nor.iter().map(|&i| self.normals[i as usize]).collect()
                });
                let attrs = CornerAttrs {
                    normals: normals.as_deref(),
                    uvs: uvs.as_deref(),
                };
                if plain[k] {
                    b.add_plain_triangle(c, material, attrs);
                } else {
                    b.add_face_with(c, material, attrs);
                }
            }
            start = end;
            k += 1;
        }
        let faces = self.faces.len();
        let name = self.name;
        b.finish().ok_or_else(|| {
            if faces == 0 {
                LoadError::file(name, "empty scene: no faces")
            } else {
                LoadError::file(
                    name,
                    format!("empty scene: all {faces} faces are degenerate"),
                )
            }
        })
    }
}

/// Corner `k`'s entry in a `vt` or `vn` index list that may stop short of it.
fn attr(list: &[u32], k: usize) -> u32 {
    list.get(k).copied().unwrap_or(NONE)
}

#[cfg(unix)]
fn path_from_bytes(b: &[u8]) -> PathBuf {
    use std::os::unix::ffi::OsStrExt;
    PathBuf::from(std::ffi::OsStr::from_bytes(b))
}

#[cfg(not(unix))]
fn path_from_bytes(b: &[u8]) -> PathBuf {
    PathBuf::from(String::from_utf8_lossy(b).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::text::parse_int;

    fn load(bytes: &[u8], name: &str, dir: Option<&Path>) -> Result<Scene, LoadError> {
        super::load(Input::new(bytes, Some(bytes.len() as u64)), name, dir)
    }
    use crate::error::Location;

    fn load_str(s: &str) -> Result<Scene, LoadError> {
        load(s.as_bytes(), "t.obj", None)
    }

    fn line_of(e: &LoadError) -> usize {
        match e.location {
            Location::Line(l) => l,
            ref other => panic!("expected a line, got {other:?}"),
        }
    }

    #[test]
    fn parse_int_edges() {
        assert_eq!(parse_int(b"12"), Some(12));
        assert_eq!(parse_int(b"-3"), Some(-3));
        assert_eq!(parse_int(b"+7"), Some(7));
        assert_eq!(parse_int(b"-9223372036854775808"), Some(i64::MIN));
        assert_eq!(parse_int(b"9223372036854775808"), None);
        assert_eq!(parse_int(b"-"), None);
        assert_eq!(parse_int(b""), None);
        assert_eq!(parse_int(b"1.0"), None);
    }

    #[test]
    fn tokens_and_rest() {
        let mut t = Tokens::new(b"  usemtl  my  mat \t");
        assert_eq!(t.next(), Some(&b"usemtl"[..]));
        assert_eq!(t.rest(), b"my  mat");
        assert_eq!(t.next(), Some(&b"my"[..]));
        assert_eq!(t.next(), Some(&b"mat"[..]));
        assert_eq!(t.next(), None);
    }

    #[test]
    fn corner_forms_and_negative_indices() {
        let s = load_str(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1\nv 0 0 1\nf -4 -2 -3\n",
        )
        .unwrap();
        assert_eq!(s.faces.len(), 2);
        assert_eq!(s.face_corners(&s.faces[0]), &[0, 1, 2]);
        assert_eq!(s.face_corners(&s.faces[1]), &[0, 2, 1]);
    }

    #[test]
    fn forward_references_are_accepted() {
        let s = load_str("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(s.faces.len(), 1);
    }

    #[test]
    fn forward_reference_out_of_range_names_its_line() {
        let e = load_str("f 1 2 3\nf 1 2 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap_err();
        assert_eq!(line_of(&e), 2);
        assert!(e.message.contains("vertex index 9 out of range"), "{e}");
        assert!(e.message.contains("3 vertices"), "{e}");
    }

    #[test]
    fn crlf_comments_and_continuation() {
        let s = load_str(
            "# head\r\nv 0 0 0 # origin\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 \\\r\n 2 \\\n 3\r\nfoo bar\nfoo\n",
        )
        .unwrap();
        assert_eq!(s.faces.len(), 1);
        assert_eq!(s.stats.warnings.len(), 1, "{:?}", s.stats.warnings);
        assert!(
            s.stats.warnings[0].contains(":8:"),
            "{:?}",
            s.stats.warnings
        );
    }

    #[test]
    fn line_numbers_count_continued_lines() {
        let e = load_str("v 0 0 \\\n 0\nv 1 0 0\nv x 0 0\n").unwrap_err();
        assert_eq!(line_of(&e), 4);
    }

    #[test]
    fn vertex_colours_and_w_are_ignored() {
        let s = load_str("v 0 0 0 1\nv 1 0 0 1 0 0\nv 0 1 0 0.5 0.5 0.5\nf 1 2 3\n").unwrap();
        assert_eq!(s.positions.len(), 3);
    }

    #[test]
    fn errors_name_the_problem() {
        let cases: &[(&str, usize, &str)] = &[
            ("v 0 0\n", 1, "2 coordinates"),
            ("v 0 0 0\nv 1 0 nan\n", 2, "not finite"),
            ("v 0 0 0\nv 1 0 1e999\n", 2, "not finite"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "2 corners"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", 4, "index 0"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                4,
                "only 3 vertices",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x\n",
                4,
                "bad face corner",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/1/1/1\n",
                4,
                "bad face corner",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n",
                4,
                "bad vertex index",
            ),
        ];
        for (src, line, needle) in cases {
            let e = load_str(src).unwrap_err();
            assert_eq!(line_of(&e), *line, "{src:?}: {e}");
            assert!(e.message.contains(needle), "{src:?}: {e}");
        }
        let e = load(b"v 0 0 0\nv 1 0 \xff\n", "t.obj", None).unwrap_err();
        assert_eq!(line_of(&e), 2);
        assert!(e.message.contains("bad number"), "{e}");
    }

    #[test]
    fn objects_start_meshes_groups_do_not() {
        let s = load_str(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no a\ng x\nf 1 2 3\ng y\nf 1 3 4\no b\nf 1 2 4\n",
        )
        .unwrap();
        assert_eq!(s.meshes.len(), 2);
        assert_eq!(s.meshes[0].name, "a");
        assert_eq!(s.meshes[0].faces, 0..2);
        assert_eq!(s.meshes[1].name, "b");
    }

    /// Bare triangles are added in runs; a run ends at an object, a `usemtl` (of an undefined
    /// material here: the default one), a face with corner attributes, a quad and a degenerate
    /// face, each face keeping its id, mesh, corners and attributes in file order.
    #[test]
    fn runs_of_bare_triangles_end_where_the_faces_differ() {
        let s = load_str(concat!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\nvt 0 0\nvn 0 0 1\n",
            "o a\nf 1 2 3\nf 2 4 3\n",
            "usemtl m\nf 1 2 4\nf 1/1 2/1 3/1\nf 2 5 4\n",
            "o b\nf 1 2 3\nf 1 5 4\nf 1//1 2//1 4//1\nf 1 2 4 3\nf 3 4 3\nf 2 4 3\n",
        ))
        .unwrap();
        let corners: Vec<&[u32]> = s.faces.iter().map(|f| s.face_corners(f)).collect();
        let want: [&[u32]; 10] = [
            &[0, 1, 2],
            &[1, 3, 2],
            &[0, 1, 3],
            &[0, 1, 2],
            &[1, 4, 3],
            &[0, 1, 2],
            &[0, 4, 3],
            &[0, 1, 3],
            &[0, 1, 3, 2],
            &[1, 3, 2],
        ];
        assert_eq!(corners, want);
        // The degenerate face (index 9 in the file) is dropped: ids skip it.
        let ids: Vec<u32> = s.faces.iter().map(|f| f.id).collect();
        assert_eq!(ids, [0, 1, 2, 3, 4, 5, 6, 7, 8, 10]);
        let meshes: Vec<u32> = s.faces.iter().map(|f| f.mesh).collect();
        assert_eq!(meshes, [0, 0, 0, 0, 0, 1, 1, 1, 1, 1]);
        assert_eq!(s.corner_uvs.len(), s.corners.len());
        assert!(s.corner_uvs[9..12].iter().all(Option::is_some));
        assert!(
            s.corner_uvs[..9]
                .iter()
                .chain(&s.corner_uvs[12..])
                .all(Option::is_none)
        );
        assert_eq!(s.corner_normals.len(), s.corners.len());
        assert!(s.corner_normals[21..24].iter().all(Option::is_some));
    }

    #[test]
    fn unknown_material_warns_and_uses_default() {
        let s = load_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\n").unwrap();
        assert_eq!(
            s.materials[s.faces[0].material as usize],
            Material::default()
        );
        assert!(s.stats.warnings.iter().any(|w| w.contains("'nope'")));
    }

    #[test]
    fn empty_and_all_degenerate() {
        let e = load_str("# nothing\nv 0 0 0\n").unwrap_err();
        assert_eq!(e.location, Location::File);
        let e = load_str("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap_err();
        assert!(e.message.contains("degenerate"), "{e}");
    }

    /// The scene's geometry and structure as text, to compare two loads.
    fn shape(s: &Scene) -> String {
        format!(
            "{:?}\n{:?}\n{:?}\n{:?}\n{:?}\n{:?}",
            s.positions, s.faces, s.corners, s.meshes, s.corner_normals, s.stats.warnings
        )
    }

    /// A grid of `n` x `n` vertices and its triangles, more than one batch of blocks for
    /// n = 450 (11 MiB). `fancy`: the same statements written every other way the format
    /// allows (relative indices, CRLF, comments, blank lines, continued lines).
    fn grid_obj(n: usize, fancy: bool) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        for i in 0..n * n {
            let (x, y) = (i % n, i / n);
            let end = if fancy && i % 7 == 0 { "\r\n" } else { "\n" };
            write!(s, "v {x} {y} {}{end}", (x * y) % 5).unwrap();
            if fancy && i % 1000 == 0 {
                s.push_str("# a comment\n\n");
            }
        }
        let mut face = 0;
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                let a = y * n + x + 1;
                for t in [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]] {
                    if face % 50_000 == 0 {
                        writeln!(s, "o part{face}").unwrap();
                    }
                    let total = n * n;
                    let c = t.map(|c| {
                        if fancy && face % 3 == 0 {
                            format!("-{}", total + 1 - c)
                        } else {
                            c.to_string()
                        }
                    });
                    if fancy && face % 997 == 0 {
                        writeln!(s, "f {} \\\n {} {} # continued", c[0], c[1], c[2]).unwrap();
                    } else {
                        writeln!(s, "f {} {} {}", c[0], c[1], c[2]).unwrap();
                    }
                    face += 1;
                }
            }
        }
        s
    }

    #[test]
    fn a_file_of_many_blocks_loads_as_its_lines_read_one_by_one() {
        let plain = grid_obj(450, false);
        let fancy = grid_obj(450, true);
        assert!(
            fancy.len() > BLOCKS_PER_BATCH << 20,
            "{} bytes",
            fancy.len()
        );
        let a = load_str(&plain).unwrap();
        let b = load_str(&fancy).unwrap();
        assert_eq!(a.faces.len(), 2 * 449 * 449);
        assert_eq!(a.meshes.len(), a.faces.len().div_ceil(50_000));
        assert!(shape(&a) == shape(&b), "the two spellings differ");
        // Line numbers run on across blocks and batches.
        let lines = fancy.bytes().filter(|&b| b == b'\n').count();
        let e = load_str(&format!("{fancy}f 1 2 x\n")).unwrap_err();
        assert_eq!(line_of(&e), lines + 1, "{e}");
        let e = load_str(&format!("{fancy}f 1 2 {}\n", 450 * 450 + 1)).unwrap_err();
        assert_eq!(line_of(&e), lines + 1, "{e}");
    }

    #[test]
    fn a_bad_line_before_a_read_failure_further_on_is_the_error() {
        let long = "x".repeat(crate::scene::input::MAX_LINE + (1 << 20));
        let e = load_str(&format!("v 0 0 0\nv bad 0 0\n{long}")).unwrap_err();
        assert_eq!(line_of(&e), 2, "{e}");
        assert!(e.message.contains("bad number"), "{e}");
        let e = load_str(&format!("v 0 0 0\n{long}")).unwrap_err();
        assert!(e.message.contains("line 2 is longer than"), "{e}");
    }

    #[test]
    fn a_forward_reference_names_the_first_corner_out_of_range() {
        let vertices = "v 0 0 0\n".repeat(8);
        let e = load_str(&format!("f 9 12 1\n{vertices}")).unwrap_err();
        assert!(e.message.contains("vertex index 9 out of range"), "{e}");
    }
}
