//! Choosing a loader: by file extension (`.gz` is looked through), or by an explicit [`Format`].

use super::Scene;
use crate::error::LoadError;
use std::io::Read;
use std::path::Path;

/// An input format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    Obj,
    Stl,
    Ply,
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
    let raw =
        std::fs::read(path).map_err(|e| LoadError::file(&name, format!("cannot read: {e}")))?;
    let bytes = if raw.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        flate2::read::MultiGzDecoder::new(&raw[..])
            .read_to_end(&mut out)
            .map_err(|e| LoadError::file(&name, format!("bad gzip data: {e}")))?;
        out
    } else {
        raw
    };
    load_bytes(&bytes, format, &name, path.parent())
}

/// Loads a scene from bytes already in memory. `name` is used in messages; `dir` is where files
/// the scene refers to (an OBJ's .mtl and textures, an X3D ImageTexture) are looked for.
pub fn load_bytes(
    bytes: &[u8],
    format: Format,
    name: &str,
    dir: Option<&Path>,
) -> Result<Scene, LoadError> {
    match format {
        Format::Obj => super::obj::load(bytes, name, dir),
        Format::Stl => super::stl::load(bytes, name),
        Format::Ply => super::ply::load(bytes, name),
        Format::X3d => super::x3d::load(bytes, name, dir),
    }
}
