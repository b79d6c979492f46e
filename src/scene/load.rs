//! Choosing a loader: by file extension (`.gz` is looked through), or by an explicit [`Format`];
//! and feeding it the file as a stream (decompressed as it is read when it starts with the gzip
//! magic bytes), with progress counted in bytes of the file on disk.

use super::Scene;
use super::input::{Gunzip, Input, Progress};
use crate::error::LoadError;
use flate2::bufread::MultiGzDecoder;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// An input format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Wavefront OBJ (with its MTL materials).
    Obj,
    /// STL, ASCII or binary.
    Stl,
    /// PLY, ASCII or binary.
    Ply,
    /// X3D (XML encoding).
    X3d,
}

impl Format {
    /// The format named by a file's extension (after stripping `.gz`).
    pub fn from_path(path: &Path) -> Option<Format> {
        let name = path.file_name()?.to_string_lossy().to_ascii_lowercase();
        let name = name.strip_suffix(".gz").unwrap_or(&name);
        let ext = name.rsplit_once('.')?.1;
        match ext {
            "obj" => Some(Format::Obj),
            "stl" => Some(Format::Stl),
            "ply" => Some(Format::Ply),
            "x3d" => Some(Format::X3d),
            _ => None,
        }
    }
}

/// Loads a scene from a file. `format` overrides the extension.
pub fn load(path: &Path, format: Option<Format>) -> Result<Scene, LoadError> {
    load_with_progress(path, format, &mut |_, _| {})
}

/// Size of the read buffers: large enough that reading costs little next to parsing.
const BUFFER: usize = 1 << 20;

/// [`load`], calling `on_progress(bytes of the file read so far, file size)` as the file is read
/// (for a `.gz` file, compressed bytes: the total is known before decompressing).
///
/// The file is streamed: OBJ, STL and PLY are parsed as they are read (and decompressed), so
/// memory follows the scene, not the file. X3D is decompressed whole and then parsed (the XML
/// parser needs the whole document).
pub fn load_with_progress(
    path: &Path,
    format: Option<Format>,
    on_progress: &mut dyn FnMut(u64, u64),
) -> Result<Scene, LoadError> {
    let name = path.display().to_string();
    let format = match format.or_else(|| Format::from_path(path)) {
        Some(f) => f,
        None => {
            return Err(LoadError::file(
                &name,
                "unknown file format (expected .obj, .stl, .ply or .x3d, optionally .gz; or pass --format)",
            ));
        }
    };
    let cannot_read = |e: std::io::Error| LoadError::file(&name, format!("cannot read: {e}"));
    let file = std::fs::File::open(path).map_err(cannot_read)?;
    let size = file.metadata().map_err(cannot_read)?.len();
    let mut raw = BufReader::with_capacity(
        BUFFER,
        Progress {
            inner: file,
            read: 0,
            total: size,
            on_progress,
        },
    );
    let gzipped = raw
        .fill_buf()
        .map_err(|e| LoadError::file(&name, e.to_string()))?
        .starts_with(&[0x1f, 0x8b]);
    let dir = path.parent();
    // One loader instance for both kinds of file: a virtual call per buffer refill is noise.
    let input: Input<Box<dyn Read + '_>> = if gzipped {
        Input::new(Box::new(Gunzip(MultiGzDecoder::new(raw))), None)
    } else {
        Input::new(Box::new(raw), Some(size))
    };
    load_stream(input, format, &name, dir)
}

/// Loads a scene from bytes already in memory. `name` is used in messages; `dir` is where files
/// the scene refers to (an OBJ's .mtl and textures, an X3D ImageTexture) are looked for.
pub fn load_bytes(
    bytes: &[u8],
    format: Format,
    name: &str,
    dir: Option<&Path>,
) -> Result<Scene, LoadError> {
    load_stream(
        Input::new(bytes, Some(bytes.len() as u64)),
        format,
        name,
        dir,
    )
}

fn load_stream<R: Read>(
    input: Input<R>,
    format: Format,
    name: &str,
    dir: Option<&Path>,
) -> Result<Scene, LoadError> {
    match format {
        Format::Obj => super::obj::load(input, name, dir),
        Format::Stl => super::stl::load(input, name),
        Format::Ply => super::ply::load(input, name),
        Format::X3d => super::x3d::load(input, name, dir),
    }
}
