//! The `sightline` binary run as users run it, from the repository root.

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Output, Stdio};

/// Runs `sightline ARGS` and returns what it did.
pub fn sightline(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// Runs `sightline ARGS` and fails the test, with its stderr, unless it succeeds.
pub fn run_ok(args: &[&str]) -> Output {
    let o = sightline(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// Runs `sightline render INPUT -o OUT FLAGS...` and fails the test unless it succeeds.
pub fn render_ok(input: &str, out: &Path, flags: &[&str]) -> Output {
    let out = out.to_str().unwrap();
    run_ok(&[&["render", input, "-o", out][..], flags].concat())
}

/// Runs `sightline ARGS` and returns (exit code, stderr).
pub fn run_err(args: &[&str]) -> (Option<i32>, String) {
    let o = sightline(args);
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).to_string(),
    )
}

/// Starts `sightline ARGS` with its stdout and stderr piped to the test.
pub fn spawn_piped(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs")
}

/// Waits for a child of [`spawn_piped`] and returns its exit status and stderr.
pub fn wait_with_stderr(mut child: Child) -> (ExitStatus, String) {
    let status = child.wait().unwrap();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    (status, err)
}

/// Decodes PNG bytes, failing the test on anything else.
pub fn decode_png(bytes: &[u8]) -> image::DynamicImage {
    image::load_from_memory_with_format(bytes, image::ImageFormat::Png).expect("valid PNG")
}

/// Runs a shell command under `script`, which gives it a pseudo-terminal (its output, terminal
/// and all, is the stdout); `None` when `script` is not installed.
pub fn on_a_terminal(cmd: &str) -> Option<Output> {
    Command::new("script")
        .args(["-qec", cmd, "/dev/null"])
        .output()
        .ok()
}
