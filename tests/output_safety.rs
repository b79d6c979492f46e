//! `-o PATH` never destroys what PATH is: a regular file is replaced atomically and keeps its
//! mode, a symlink is followed (the link stays), a FIFO is written in place; new files get
//! `0666 & !umask`. Everything happens in a temporary directory.

mod support;

use sightline::output::{write_atomic, write_with};
use std::fs;
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::mpsc;
use std::time::Duration;
use support::cli::{run_ok, sightline};

const BIN: &str = env!("CARGO_BIN_EXE_sightline");

/// The render the tests write: the cube as a 24x16 PNG, into `out`.
fn render_args(out: &Path) -> [&str; 6] {
    let out = out.to_str().unwrap();
    ["render", "fixtures/cube.obj", "--size", "24x16", "-o", out]
}

/// Renders into `out`, which must succeed, and checks that `file` then holds the PNG.
fn render_into(out: &Path, file: &Path) {
    run_ok(&render_args(out));
    assert!(
        is_png(&fs::read(file).unwrap()),
        "{} holds no PNG",
        file.display()
    );
}

fn is_png(bytes: &[u8]) -> bool {
    image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .is_ok_and(|img| (img.width(), img.height()) == (24, 16))
}

/// `dir/name` holding "old".
fn old_file(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    fs::write(&path, "old").unwrap();
    path
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    v.sort();
    v
}

/// `dir/link.png`, a relative link to `target` (which need not exist).
fn link_to(dir: &Path, target: &str) -> PathBuf {
    let link = dir.join("link.png");
    symlink(target, &link).unwrap();
    link
}

/// Is `path` a symbolic link (not followed)?
fn is_link(path: impl AsRef<Path>) -> bool {
    fs::symlink_metadata(path).unwrap().file_type().is_symlink()
}

fn mode(path: &Path) -> u32 {
    fs::metadata(path).unwrap().mode() & 0o7777
}

#[test]
fn a_symlink_stays_a_link_and_its_target_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let target = old_file(dir.path(), "target.png");
    let link = link_to(dir.path(), "target.png");
    render_into(&link, &target);
    assert!(is_link(&link));
    assert_eq!(fs::read_link(&link).unwrap(), Path::new("target.png"));
    assert_eq!(names(dir.path()), ["link.png", "target.png"]);
}

#[test]
fn a_chain_of_relative_links_is_resolved_from_each_links_directory() {
    // top.png -> sub/mid.png -> ../real/out.png: relative to sub/, that is real/out.png.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir_all(d.join("sub")).unwrap();
    fs::create_dir_all(d.join("real")).unwrap();
    fs::write(d.join("real/out.png"), "old").unwrap();
    symlink("sub/mid.png", d.join("top.png")).unwrap();
    symlink("../real/out.png", d.join("sub/mid.png")).unwrap();
    write_atomic(&d.join("top.png"), b"new bytes").unwrap();
    assert_eq!(fs::read(d.join("real/out.png")).unwrap(), b"new bytes");
    assert!(is_link(d.join("top.png")));
    assert!(is_link(d.join("sub/mid.png")));
    assert_eq!(names(&d.join("sub")), ["mid.png"]);
    assert_eq!(names(&d.join("real")), ["out.png"]);
}

#[test]
fn a_dangling_link_creates_its_target_and_stays_a_link() {
    let dir = tempfile::tempdir().unwrap();
    let link = link_to(dir.path(), "made.png");
    render_into(&link, &dir.path().join("made.png"));
    assert!(is_link(&link));
}

#[test]
fn a_fifo_is_written_in_place_for_its_reader() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.png");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let (tx, rx) = mpsc::channel();
    let reader_path = fifo.clone();
    // Blocks in open(2) until a writer opens the FIFO, then reads to its end.
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let r = fs::File::open(&reader_path).and_then(|mut f| f.read_to_end(&mut bytes));
        tx.send(r.map(|_| bytes)).unwrap();
    });
    run_ok(&render_args(&fifo));
    // Renamed over, the FIFO would never see a writer: its reader would wait forever.
    let got = rx
        .recv_timeout(Duration::from_secs(20))
        .expect("the FIFO's reader got its bytes")
        .unwrap();
    assert!(is_png(&got), "{} bytes, not the PNG", got.len());
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(names(dir.path()), ["pipe.png"]);
}

/// A file of many megabytes (its writeback started as it is written, every few megabytes)
/// replaces the old one with every byte in place, whatever sizes the writes come in.
#[test]
fn a_large_output_replaces_the_old_file_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let out = old_file(dir.path(), "big.svg");
    let bytes: Vec<u8> = (0..21_000_017u32).map(|i| (i % 251) as u8).collect();
    write_with(&out, |w| {
        let mut rest = &bytes[..];
        for size in [1, 7_000, 3 << 20, 5].into_iter().cycle() {
            if rest.is_empty() {
                break;
            }
            let (now, after) = rest.split_at(size.min(rest.len()));
            w.write_all(now)?;
            rest = after;
        }
        Ok(())
    })
    .unwrap();
    assert!(fs::read(&out).unwrap() == bytes, "the file differs");
    assert_eq!(names(dir.path()), ["big.svg"]);
}

#[test]
fn a_replaced_file_keeps_its_mode() {
    let dir = tempfile::tempdir().unwrap();
    for m in [0o664, 0o640, 0o600, 0o444] {
        let out = old_file(dir.path(), &format!("out{m:o}.png"));
        fs::set_permissions(&out, fs::Permissions::from_mode(m)).unwrap();
        render_into(&out, &out);
        assert_eq!(mode(&out), m, "mode {m:o} became {:o}", mode(&out));
    }
}

#[test]
fn a_replaced_file_keeps_its_owner_and_group_when_the_writer_may_set_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = old_file(dir.path(), "owned.png");
    let (uid, gid) = (4321, 4322);
    let Ok(()) = std::os::unix::fs::chown(&out, Some(uid), Some(gid)) else {
        // Not root: nobody else's file can be made here, and ours stays ours.
        eprintln!("not root: owner kept trivially; checking only the replacement");
        render_into(&out, &out);
        return;
    };
    render_into(&out, &out);
    let m = fs::metadata(&out).unwrap();
    assert_eq!((m.uid(), m.gid()), (uid, gid));
}

/// Renders into `out` under `umask` (set in a shell, so only the child has it).
fn render_under_umask(umask: &str, out: &Path) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!(
            "umask {umask} && exec \"$0\" render fixtures/cube.obj --size 24x16 -o \"$1\""
        ))
        .arg(BIN)
        .arg(out)
        .output()
        .expect("sh runs")
}

#[test]
fn a_new_file_gets_0666_minus_the_umask() {
    let dir = tempfile::tempdir().unwrap();
    for (umask, want) in [("022", 0o644), ("002", 0o664), ("077", 0o600)] {
        let out = dir.path().join(format!("new{umask}.png"));
        let o = render_under_umask(umask, &out);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(mode(&out), want, "umask {umask}: mode {:o}", mode(&out));
    }
}

#[test]
fn a_failed_write_leaves_the_old_file_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let out = old_file(dir.path(), "keep.png");
    let link = link_to(dir.path(), "keep.png");
    for path in [&out, &link] {
        let r = write_with(path, |w| {
            w.write_all(&[7; 100_000])?;
            Err(std::io::Error::other("encoder failed halfway"))
        });
        assert!(r.is_err());
        assert_eq!(fs::read(&out).unwrap(), b"old");
        assert_eq!(names(dir.path()), ["keep.png", "link.png"]);
    }
}

#[test]
fn a_directory_is_an_error_and_stays_a_directory() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("out.png");
    fs::create_dir(&sub).unwrap();
    let o = sightline(&render_args(&sub));
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("out.png"));
    assert!(fs::metadata(&sub).unwrap().is_dir());
}

/// An interrupted render (SIGTERM, as Ctrl-C's SIGINT) leaves neither its temporary file nor a
/// partial output: a drawing's PNG is rasterized while it streams into the temporary file, so
/// the render is stopped while that file exists. An old output stays as it was.
#[test]
fn an_interrupted_render_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = old_file(dir.path(), "big.png");
    let mut child = Command::new(BIN)
        .args([
            "render",
            "fixtures/cube.obj",
            "--method",
            "bsp",
            "--size",
            "16384x16384",
            "-o",
        ])
        .arg(&out)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("binary runs");
    // Wait for the temporary file (the render takes seconds after it appears).
    let temporary = || {
        names(dir.path())
            .iter()
            .any(|n| n.starts_with(".sightline-"))
    };
    let mut waited = Duration::ZERO;
    while !temporary() && waited < Duration::from_secs(30) {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the render ended early"
        );
        std::thread::sleep(Duration::from_millis(20));
        waited += Duration::from_millis(20);
    }
    assert!(temporary(), "the temporary file appeared");
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert!(!status.success());
    assert_eq!(names(dir.path()), vec!["big.png".to_string()]);
    assert_eq!(fs::read(&out).unwrap(), b"old");
}
