//! `sightline bench --suite`: the time-versus-error benchmark's command line, its outputs and
//! its errors.

use std::process::{Command, Output};

fn sightline(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(args)
        .output()
        .expect("run sightline")
}

/// The loadable fixtures, as the suite lists them.
fn fixture_count() -> usize {
    std::fs::read_dir("fixtures")
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.is_file()
                && p.extension()
                    .is_some_and(|e| ["obj", "stl", "ply", "x3d"].contains(&e.to_str().unwrap()))
        })
        .count()
}

#[test]
fn the_fixtures_suite_writes_every_row_with_the_exact_method_at_zero_and_the_painter_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let o = sightline(&[
        "bench",
        "--suite",
        "fixtures",
        "--methods",
        "zbuffer,coverage,painter",
        "--sizes",
        "32,64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("scene,method,engine,exact,size,time_s,peak_rss_kb,error,reused,pieces,chosen")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), fixture_count() * 3 * 2);
    assert!(rows.iter().all(|r| r.len() == 11));
    let error = |r: &[&str]| r[7].parse::<f64>().unwrap();
    for r in &rows {
        let t: f64 = r[5].parse().unwrap();
        assert!(t >= 0.0 && t.is_finite(), "{r:?}");
        match r[1] {
            "zbuffer" => assert!(error(r) > 0.0 && error(r) < 1.0, "{r:?}"),
            "coverage" => assert_eq!(error(r), 0.0, "{r:?}"),
            "painter" => assert!(error(r) > 0.0, "{r:?}"),
            m => panic!("unexpected method {m}"),
        }
        if cfg!(target_os = "linux") {
            assert!(r[6].parse::<u64>().unwrap() > 0, "{r:?}");
        }
    }
    let at = |method: &str, size: &str| {
        rows.iter()
            .find(|r| r[0] == "cyclic_bars.obj" && r[1] == method && r[4] == size)
            .map(|r| error(r))
            .unwrap()
    };
    // The painter sorts whole faces: on the cyclic bars it shows the wrong face over whole
    // areas, beyond the z-buffer's edge sampling.
    assert!(
        at("painter", "64") > at("zbuffer", "64"),
        "{} {}",
        at("painter", "64"),
        at("zbuffer", "64")
    );
    // Sampling error shrinks with the pixel size.
    assert!(at("zbuffer", "64") < at("zbuffer", "32"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), rows.len());
    assert_eq!(json["sizes"], serde_json::json!([32, 64]));
    assert!(out.join("plot-cyclic_bars_obj.svg").is_file());
}

#[test]
fn bad_sizes_unknown_methods_and_unwritable_folders_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let out = out.to_str().unwrap();
    for (args, says) in [
        (vec!["--sizes", "64,32"], "increase"),
        (vec!["--sizes", "0"], "not an image side"),
        (vec!["--sizes", "abc"], "'abc'"),
        (vec!["--methods", "zbuffer,nope"], "unknown method 'nope'"),
        (vec!["--time-limit", "0"], "seconds above 0"),
        (vec!["--time-limit", "-5"], "seconds above 0"),
        (vec!["--memory-limit", "0"], "'0'"),
    ] {
        let mut a = vec!["bench", "--suite", "fixtures", "--out", out];
        a.extend(args);
        let o = sightline(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(says), "{a:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    // A file where the folder should be.
    let file = dir.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let o = sightline(&[
        "bench",
        "--suite",
        "fixtures",
        "--methods",
        "zbuffer",
        "--sizes",
        "8",
        "--out",
        file.join("sub").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: ") && !err.contains("panicked"),
        "{err}"
    );
    // The meshes folder missing.
    let o = sightline(&[
        "bench",
        "--suite",
        "meshes",
        "--dir",
        dir.path().join("none").to_str().unwrap(),
        "--out",
        out,
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("meshes folder") && err.contains("missing"),
        "{err}"
    );
    // --suite needs --out; the single-scene form still works.
    assert!(
        !sightline(&["bench", "--suite", "fixtures"])
            .status
            .success()
    );
    let o = sightline(&[
        "bench",
        "fixtures/cube.obj",
        "--repeat",
        "1",
        "--size",
        "32x32",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_measurement_over_its_memory_limit_is_recorded_as_failed_and_the_others_kept() {
    // Every process peaks above 1 MB, so each child measurement is over the limit: judged from
    // the peak it reports even when it ends between two polls.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let o = sightline(&[
        "bench",
        "--suite",
        "generated",
        "--methods",
        "coverage",
        "--sizes",
        "16",
        "--memory-limit",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains("coverage on soup-100 at 16x16: stopped at the memory limit of 1 MB"),
        "{err}"
    );
    assert!(err.contains("measurement(s) failed"), "{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let failed = json["failed"].as_array().unwrap();
    assert_eq!(failed.len(), 5, "one method on five scenes");
    assert!(
        failed
            .iter()
            .all(|f| f["failure"]["kind"] == "memory_limit" && f["failure"]["kb"] == 1024),
        "{failed:?}"
    );
    assert_eq!(json["rows"].as_array().unwrap().len(), 0);
}
