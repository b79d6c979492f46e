//! Writing results without ever destroying what the output path is.
//!
//! Invariants, by what the path names:
//! - `-`: standard output. A reader that stops early (`| head`) ends the write quietly.
//! - A regular file, or nothing yet: replaced whole or not at all. Bytes go to a temporary file
//!   in the target's directory, renamed over the target once written and synced; a failed
//!   write removes the temporary file and leaves the old file as it was. A replaced file keeps
//!   its mode (and its owner and group where the process may set them); a new file gets
//!   `0666 & !umask`, as open(2) gives.
//! - A symlink: followed (chains too, a relative target resolved against the link's directory)
//!   and its final target replaced as above, so the link stays a link. A dangling link creates
//!   its target.
//! - Anything else (FIFO, character device, socket, `/dev/stdout`, links through `/proc`):
//!   opened and written in place, never renamed over.
//!
//! A temporary file lives as long as its output is being written (a drawing's PNG is
//! rasterized while it streams out): a program interrupted meanwhile calls
//! [`remove_unfinished_outputs`] before it exits, so that nothing is left beside the target.

pub mod canonical;
pub mod drawing;
pub mod dxf;
pub mod json;
pub mod line_json;
pub mod line_svg;
pub mod pdf;
pub mod png;
pub mod raster_drawing;
pub mod svg;
pub mod svg_stream;

use crate::error::Error;
use std::fs::{File, Metadata, OpenOptions, Permissions};
use std::io::{self, BufWriter, Write};
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporary files being written now.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes the temporary files of the outputs being written (for an interrupt handler: the
/// targets stay as they were).
pub fn remove_unfinished_outputs() {
    let paths = UNFINISHED.lock().map(|mut v| std::mem::take(&mut *v));
    for path in paths.unwrap_or_default() {
        let _ = std::fs::remove_file(path);
    }
}

/// Lists a temporary file in [`UNFINISHED`] while it lives.
struct Unfinished(PathBuf);

impl Unfinished {
    fn new(path: &Path) -> Unfinished {
        if let Ok(mut v) = UNFINISHED.lock() {
            v.push(path.to_path_buf());
        }
        Unfinished(path.to_path_buf())
    }
}

impl Drop for Unfinished {
    fn drop(&mut self) {
        if let Ok(mut v) = UNFINISHED.lock() {
            v.retain(|p| *p != self.0);
        }
    }
}

/// Writes `bytes` to `path` by the rules of this module (atomically for regular files), or to
/// stdout when `path` is `-`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_with(path, |w| w.write_all(bytes))
}

/// Writes to `path` by the rules of this module whatever `write` writes into the (buffered)
/// writer it is given, so outputs can be streamed. When `write` fails, a regular file is left
/// as it was.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), Error> {
    let io_err = |source| Error::Io {
        path: path.display().to_string(),
        source,
    };
    if path.as_os_str() == "-" {
        return write_stdout(write).map_err(io_err);
    }
    match target_of(path).map_err(io_err)? {
        Target::Replace { path: target, old } => {
            replace(&target, old.as_ref(), write).map_err(|source| Error::Io {
                path: target.display().to_string(),
                source,
            })
        }
        Target::InPlace => write_in_place(path, write).map_err(io_err),
    }
}

/// Where the bytes for an output path go.
enum Target {
    /// A regular file to replace (or create) at `path`, the end of any chain of links; `old` is
    /// the file being replaced.
    Replace {
        path: PathBuf,
        old: Option<Metadata>,
    },
    /// Not a regular file: open the given path and write into it.
    InPlace,
}

/// Symlink hops followed before giving up, as the kernel's ELOOP limit.
const MAX_LINKS: usize = 40;

fn target_of(path: &Path) -> io::Result<Target> {
    // The kernel follows every link (including /proc's magic ones) to say what is there.
    let old = match std::fs::metadata(path) {
        Ok(m) if !m.is_file() => return Ok(Target::InPlace),
        Ok(m) => Some(m),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(e),
    };
    // A regular file or nothing: find the path the links lead to, to replace it there.
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let dir = p.parent().unwrap_or(Path::new(""));
                // /proc/self/fd/1 and its kin name open files, not places: writing there means
                // writing to that open file (as `cp x /dev/stdout` does).
                if std::fs::canonicalize(if dir.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    dir
                })
                .is_ok_and(|d| d.starts_with("/proc"))
                {
                    return Ok(Target::InPlace);
                }
                // Joined, never normalized: `..` in a target is the kernel's to resolve.
                p = dir.join(std::fs::read_link(&p)?);
            }
            Ok(_) => return Ok(Target::Replace { path: p, old }),
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return Ok(Target::Replace { path: p, old });
            }
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// Replaces (or creates) the regular file `target` atomically.
fn replace(
    target: &Path,
    old: Option<&Metadata>,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // A new file: 0666 minus the umask (open(2) applies it). A replaced one: private until its
    // old mode is set, before any byte is written.
    let create_mode = if old.is_some() { 0o600 } else { 0o666 };
    let tmp = tempfile::Builder::new()
        .prefix(".sightline-")
        .permissions(Permissions::from_mode(create_mode))
        .tempfile_in(dir)?;
    let _listed = Unfinished::new(tmp.path());
    if let Some(old) = old {
        keep_owner_and_mode(tmp.as_file(), old)?;
    }
    let mut out = BufWriter::new(Writeback::new(tmp.as_file()));
    write(&mut out)?;
    out.flush()?;
    drop(out);
    tmp.as_file().sync_all()?;
    tmp.persist(target).map_err(|e| e.error)?;
    Ok(())
}

/// A file being written, its bytes handed to the disk every [`Writeback::EVERY`] bytes as they
/// come (Linux `sync_file_range`, which starts the writeback and does not wait), so that the
/// final sync waits for the last stretch only: writing the disk overlaps making the bytes (a
/// 71 MB drawing's sync took ~60 ms after the last byte). Elsewhere a plain file.
struct Writeback<'f> {
    file: &'f File,
    /// Bytes written, and those handed to the disk.
    written: u64,
    started: u64,
}

impl<'f> Writeback<'f> {
    const EVERY: u64 = 8 << 20;

    fn new(file: &'f File) -> Self {
        Writeback {
            file,
            written: 0,
            started: 0,
        }
    }
}

impl Write for Writeback<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = (&*self.file).write(buf)?;
        self.written += n as u64;
        if self.written - self.started >= Self::EVERY {
            // libc is a dependency where glibc is (`Cargo.toml`).
            #[cfg(all(target_os = "linux", target_env = "gnu"))]
            {
                use std::os::fd::AsRawFd;
                let (from, len) = (self.started as i64, (self.written - self.started) as i64);
                // SAFETY: the descriptor is open for the borrow's lifetime; the call only
                // starts writing back pages of that range. Its failure is harmless: the final
                // sync writes whatever it did not.
                unsafe {
                    libc::sync_file_range(
                        self.file.as_raw_fd(),
                        from,
                        len,
                        libc::SYNC_FILE_RANGE_WRITE,
                    );
                }
            }
            self.started = self.written;
        }
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        (&*self.file).flush()
    }
}

/// Gives the new file the old one's owner, group and mode. Only root may give a file away, so
/// an owner that cannot be kept is not an error (the file is then the writer's, as with any
/// editor); the mode is set after, since a change of owner clears set-id bits.
fn keep_owner_and_mode(file: &File, old: &Metadata) -> io::Result<()> {
    let new = file.metadata()?;
    if (new.uid(), new.gid()) != (old.uid(), old.gid()) {
        let _ = std::os::unix::fs::fchown(file, Some(old.uid()), Some(old.gid()));
    }
    file.set_permissions(Permissions::from_mode(old.mode() & 0o7777))
}

/// Opens what is at `path` (FIFO, device, ...) and writes into it, without creating anything.
fn write_in_place(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    // O_TRUNC is ignored by FIFOs and devices, and empties a regular file reached through /proc
    // (`-o /dev/stdout > file`), as `cp` does.
    let file = OpenOptions::new().write(true).truncate(true).open(path)?;
    let mut out = BufWriter::new(file);
    write(&mut out)?;
    out.flush()
}

fn write_stdout(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> io::Result<()> {
    let mut out = PipeEnd {
        inner: BufWriter::new(io::stdout().lock()),
        closed: false,
    };
    match write(&mut out).and_then(|()| out.flush()) {
        // The reader stopped early (`| head`): it wanted no more, as Unix tools treat it.
        // Encoders may rewrap the error, so the writer remembers what happened.
        Err(_) if out.closed => Ok(()),
        other => other,
    }
}

/// A writer that remembers whether its reader went away (EPIPE).
struct PipeEnd<W: Write> {
    inner: W,
    closed: bool,
}

impl<W: Write> PipeEnd<W> {
    fn note<T>(&mut self, r: io::Result<T>) -> io::Result<T> {
        if let Err(e) = &r {
            self.closed |= e.kind() == io::ErrorKind::BrokenPipe;
        }
        r
    }
}

impl<W: Write> Write for PipeEnd<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let r = self.inner.write(buf);
        self.note(r)
    }

    fn flush(&mut self) -> io::Result<()> {
        let r = self.inner.flush();
        self.note(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The writeback is started once a stretch of [`Writeback::EVERY`] bytes is written, for
    /// that whole stretch, and every byte reaches the file.
    #[test]
    fn writeback_starts_each_full_stretch_and_keeps_every_byte() {
        let file = tempfile::tempfile().unwrap();
        let mut w = Writeback::new(&file);
        let every = Writeback::EVERY as usize;
        let chunk = vec![7u8; every / 2 + 1];
        w.write_all(&chunk).unwrap();
        assert_eq!((w.written, w.started), (chunk.len() as u64, 0));
        w.write_all(&chunk).unwrap();
        let two = 2 * chunk.len() as u64;
        assert_eq!((w.written, w.started), (two, two));
        w.write_all(&[1, 2, 3]).unwrap();
        assert_eq!((w.written, w.started), (two + 3, two));
        w.flush().unwrap();
        assert_eq!(file.metadata().unwrap().len(), two + 3);
    }
}
