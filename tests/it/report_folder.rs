//! A report folder holds exactly one run (issue 47, case 5): a run writes into a staging folder
//! and moves it into place whole, a lock refuses a second run on the same folder, and
//! `meta.json`, `summary.md` and `index.html` say whether the run is `complete` or was
//! `interrupted`.

use crate::common::cli::{Suite, accelbench_fails};
#[cfg(unix)]
use crate::common::cli::{interrupt_at, spawn_piped};
use crate::common::temp::temp_path;
use std::path::Path;

/// A quick one-index run into `out`.
fn quick_run(out: &Path) -> Suite {
    Suite::run("icosphere:n=100", "bvh", "primary", out)
}

fn status_of(out: &Path) -> String {
    let meta = std::fs::read_to_string(out.join("meta.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&meta).unwrap();
    v["status"].as_str().unwrap_or("(none)").to_owned()
}

/// The names in `dir`, sorted.
fn names_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn a_rerun_replaces_the_older_report_whole_and_says_complete() {
    let (tmp, out) = temp_path("r");
    quick_run(&out).ok();
    assert_eq!(status_of(&out), "complete");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("data-status=\"complete\""), "{html}");
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("**Status: complete"), "{md}");
    // An older run's chart and picture, which this run does not write.
    std::fs::write(out.join("mrays_shadow.svg"), "<svg/>").unwrap();
    std::fs::create_dir_all(out.join("pictures")).unwrap();
    std::fs::write(out.join("pictures/old.png"), "").unwrap();
    quick_run(&out).ok();
    assert!(
        !out.join("mrays_shadow.svg").exists(),
        "a stale chart stayed"
    );
    assert!(!out.join("pictures").exists(), "stale pictures stayed");
    assert_eq!(status_of(&out), "complete");
    // No lock, staging or old folder is left beside it.
    assert_eq!(names_in(tmp.path()), ["r"]);
}

#[test]
fn a_second_run_on_a_held_folder_is_refused() {
    let (tmp, out) = temp_path("r");
    let lock = tmp.path().join(".r.accelbench-lock");
    // Held by a live process: this test's.
    std::fs::write(&lock, format!("{}\n", std::process::id())).unwrap();
    quick_run(&out).fails(&["is writing this report folder", ".r.accelbench-lock"]);
    assert!(!out.exists(), "the refused run wrote a report");
    assert!(
        lock.exists(),
        "the refused run removed the other run's lock"
    );
    // Left by a process that is gone (a pid above any pid_max): taken over.
    std::fs::write(&lock, "2147483646\n").unwrap();
    quick_run(&out).ok();
    assert_eq!(status_of(&out), "complete");
    assert!(!lock.exists(), "the lock outlived its run");
}

#[test]
fn a_folder_of_other_files_is_never_replaced() {
    let (_tmp, out) = temp_path("mine");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("thesis.tex"), "precious").unwrap();
    quick_run(&out).fails(&["no accelbench report"]);
    assert_eq!(names_in(&out), ["thesis.tex"]);
}

/// SIGINT after the first of three scenes: the run stops before the third, writes what it
/// measured with the status `interrupted`, and exits 130.
#[cfg(unix)]
#[test]
fn an_interrupted_run_keeps_what_it_measured_and_says_so() {
    let (tmp, out) = temp_path("r");
    let run = Suite::run(
        "icosphere:n=100,soup:n=300000,terrain:n=200",
        "bvh",
        "primary,incoherent",
        &out,
    )
    .without("--quiet");
    let early = "the run ended before its first scene was done";
    let (code, seen, rest) = interrupt_at(spawn_piped(&run.args()), "scene 1/3 done", early);
    assert_eq!(code, Some(130), "{seen}{rest}");
    assert!(rest.contains("interrupted"), "{rest}");
    assert_eq!(status_of(&out), "interrupted");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(
        csv.contains("icosphere"),
        "the first scene's rows are lost:\n{csv}"
    );
    assert!(
        !csv.contains("terrain"),
        "the run went on after the SIGINT:\n{csv}"
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("data-status=\"interrupted\""));
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("**Status: interrupted"), "{md}");
    // A merge refuses an unfinished run.
    let merged = tmp.path().join("m");
    let (out, merged) = (out.to_str().unwrap(), merged.to_str().unwrap());
    accelbench_fails(&["merge", out, "--out", merged], &["unfinished run"]);
}

/// Runs `run`, sends it a SIGINT after `wait` and waits at most `within`
/// for it to end; returns its exit code and standard error.
#[cfg(unix)]
fn interrupted(
    run: Suite,
    wait: std::time::Duration,
    within: std::time::Duration,
) -> (Option<i32>, String) {
    let mut child = spawn_piped(&run.args());
    std::thread::sleep(wait);
    // SAFETY: signals a child process this test started and has not reaped.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let signalled = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if signalled.elapsed() > within {
            child.kill().unwrap();
            panic!("the run went on for {within:?} after the SIGINT");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let mut err = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err).unwrap();
    (status.code(), err)
}

/// SIGINT in the middle of a ray set's timed passes (a thousand repeats in two modes, most of
/// a minute): the run stops at the next pass instead of finishing the set, leaves the
/// unfinished set out and exits 130 with the status `interrupted`.
#[cfg(unix)]
#[test]
fn an_interrupt_inside_a_ray_set_stops_at_the_next_pass() {
    use std::time::Duration;
    let (_tmp, out) = temp_path("r");
    let args = Suite::run("soup:n=100000", "bvh", "primary", &out).with("--repeats", "1000");
    // The build, brute force's reference and the counting pass take well under 4 s; the
    // 2,000 timed passes, about 20 ms each, take most of a minute.
    let (code, err) = interrupted(args, Duration::from_secs(4), Duration::from_secs(20));
    assert_eq!(code, Some(130), "{err}");
    assert_eq!(status_of(&out), "interrupted");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(
        !csv.contains("soup"),
        "the unfinished set gave rows:\n{csv}"
    );
}

/// SIGINT inside one long counting pass: `grid` on 20,000 overlapping slivers traces about
/// 50,000 rays a second, so its counting pass of a million rays takes about 20 s on one
/// thread. The pass stops within a slice of 16,384 rays, and the run exits 130 with the set
/// left out, instead of finishing the pass first.
#[cfg(unix)]
#[test]
fn an_interrupt_inside_a_long_counting_pass_stops_it() {
    use std::time::Duration;
    let (_tmp, out) = temp_path("r");
    let args =
        Suite::run("slivers:n=20000", "grid", "incoherent", &out).with("--incoherent", "1000000");
    let (code, err) = interrupted(args, Duration::from_secs(6), Duration::from_secs(8));
    assert_eq!(code, Some(130), "{err}");
    assert_eq!(status_of(&out), "interrupted");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(!csv.contains("slivers"), "the cut set gave rows:\n{csv}");
}
