//! One measurement of `bench --suite` in a child process (`sightline bench-one`), held to a
//! time and a memory limit, so that one method that runs away on one scene (Newell's list on a
//! large soup, a BSP's fragments) costs the suite a recorded failure, not the run.
//!
//! Invariant: a measurement is either [`Measured`], from a child that exited successfully
//! within both limits, or a [`Failure`] saying which limit or error stopped it. Both limits are
//! also judged after the child exits (its wall time, its own reported peak), so a child that
//! crosses a limit between two polls is never recorded as measured.

use serde::Serialize;
use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What a measurement may take.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Wall time of the whole child (load, projection, the timed runs).
    pub time: Duration,
    /// Resident set, kB.
    pub memory_kb: u64,
}

/// A successful measurement, as `bench-one` prints it.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// Median seconds of the method after load and projection.
    pub time_s: f64,
    /// The child's peak resident set, kB.
    pub peak_rss_kb: Option<u64>,
    /// Visible pieces (object-space methods).
    pub pieces: Option<u64>,
    /// What `auto` chose (its `chosen` statistic).
    pub chosen: Option<String>,
}

/// Why a measurement has no result.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Failure {
    /// Stopped at the time limit.
    TimeLimit {
        /// The limit, seconds.
        seconds: f64,
    },
    /// Stopped at the memory limit.
    MemoryLimit {
        /// The limit, kB.
        kb: u64,
    },
    /// The child could not run or failed.
    Failed {
        /// What went wrong.
        message: String,
    },
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::TimeLimit { seconds } => write!(f, "stopped at the time limit of {seconds} s"),
            Failure::MemoryLimit { kb } => {
                write!(f, "stopped at the memory limit of {} MB", kb / 1024)
            }
            Failure::Failed { message } => f.write_str(message),
        }
    }
}

/// How often the child's time and resident set are looked at.
const POLL: Duration = Duration::from_millis(10);

/// Runs `command` (a `bench-one` invocation) under `limits` and reads its one JSON line.
pub fn measure(mut command: Command, limits: Limits) -> Result<Measured, Failure> {
    let failed = |message: String| Failure::Failed { message };
    let start = Instant::now();
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| failed(format!("could not start the child process: {e}")))?;
    // Readers on their own threads, so a chatty child never blocks on a full pipe.
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut bytes);
            }
            bytes
        })
    };
    let stdout = drain(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let stderr = drain(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let over = loop {
        match child.try_wait() {
            Ok(Some(_)) => break None,
            Ok(None) => {}
            Err(e) => break Some(failed(format!("could not wait for the child: {e}"))),
        }
        if start.elapsed() > limits.time {
            break Some(Failure::TimeLimit {
                seconds: limits.time.as_secs_f64(),
            });
        }
        if resident_kb(child.id()).is_some_and(|kb| kb > limits.memory_kb) {
            break Some(Failure::MemoryLimit {
                kb: limits.memory_kb,
            });
        }
        std::thread::sleep(POLL.min(limits.time / 4));
    };
    if let Some(failure) = over {
        let _ = child.kill();
        let _ = child.wait();
        return Err(failure);
    }
    let status = child
        .wait()
        .map_err(|e| failed(format!("could not wait for the child: {e}")))?;
    let wall = start.elapsed();
    let out = stdout.join().unwrap_or_default();
    let err = stderr.join().unwrap_or_default();
    if !status.success() {
        return Err(failed(format!(
            "the child process failed ({status}): {}",
            String::from_utf8_lossy(&err).trim()
        )));
    }
    let v: serde_json::Value = serde_json::from_slice(&out)
        .map_err(|e| failed(format!("unreadable child output: {e}")))?;
    let measured = Measured {
        time_s: v["time_s"]
            .as_f64()
            .ok_or_else(|| failed("no time in the child output".into()))?,
        peak_rss_kb: v["peak_rss_kb"].as_u64(),
        pieces: v["pieces"].as_u64(),
        chosen: v["chosen"].as_str().map(str::to_string),
    };
    // The limits hold for the whole run, also between the last poll and the exit.
    if wall > limits.time {
        return Err(Failure::TimeLimit {
            seconds: limits.time.as_secs_f64(),
        });
    }
    if measured.peak_rss_kb.is_some_and(|kb| kb > limits.memory_kb) {
        return Err(Failure::MemoryLimit {
            kb: limits.memory_kb,
        });
    }
    Ok(measured)
}

/// The current resident set of process `pid` in kB (`VmRSS`), on Linux.
fn resident_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    super::status_kb(&status, "VmRSS:")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sh(script: &str) -> Command {
        let mut c = Command::new("sh");
        c.args(["-c", script]);
        c
    }

    const ROOMY: Limits = Limits {
        time: Duration::from_secs(30),
        memory_kb: 64 << 20,
    };

    #[test]
    fn a_child_line_is_read_with_its_pieces_and_choice() {
        let m = measure(
            sh(r#"echo '{"time_s":0.5,"peak_rss_kb":100,"pieces":7,"chosen":"coverage"}'"#),
            ROOMY,
        )
        .unwrap();
        assert_eq!(m.time_s, 0.5);
        assert_eq!(
            (m.peak_rss_kb, m.pieces, m.chosen.as_deref()),
            (Some(100), Some(7), Some("coverage"))
        );
    }

    #[test]
    fn a_child_over_time_is_stopped_and_reported() {
        let limits = Limits {
            time: Duration::from_millis(100),
            ..ROOMY
        };
        let t = Instant::now();
        let r = measure(sh("sleep 20"), limits);
        assert_eq!(r, Err(Failure::TimeLimit { seconds: 0.1 }));
        assert!(t.elapsed() < Duration::from_secs(10), "killed, not waited");
    }

    #[test]
    fn a_child_reporting_a_peak_over_the_memory_limit_is_not_measured() {
        let limits = Limits {
            memory_kb: 1000,
            ..ROOMY
        };
        let r = measure(sh(r#"echo '{"time_s":0.5,"peak_rss_kb":5000}'"#), limits);
        assert_eq!(r, Err(Failure::MemoryLimit { kb: 1000 }));
    }

    #[test]
    fn a_failing_child_gives_its_message() {
        match measure(sh("echo boom >&2; exit 3"), ROOMY) {
            Err(Failure::Failed { message }) => assert!(message.contains("boom"), "{message}"),
            other => panic!("{other:?}"),
        }
        match measure(sh("echo not json"), ROOMY) {
            Err(Failure::Failed { message }) => {
                assert!(message.contains("unreadable"), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }
}
