//! Running the `accelbench` binary from tests, and the shared meshes they read.

use super::temp::temp_path;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the binary with `args` from the crate's root, so `scenes/` and `../shared` resolve.
pub fn accelbench(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelbench"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the accelbench binary runs")
}

/// Runs `args`, asserts a zero exit (printing stderr otherwise) and returns stdout.
pub fn accelbench_ok(args: &[&str]) -> String {
    let out = accelbench(args);
    assert!(
        out.status.success(),
        "{args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Runs `args`, expects a non-zero exit without a panic, and every `expected` piece in stderr.
pub fn accelbench_fails(args: &[&str], expected: &[&str]) {
    let out = accelbench(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail; stderr: {err}");
    for e in expected {
        assert!(
            err.contains(e),
            "{args:?}: expected '{e}' in stderr:\n{err}"
        );
    }
    assert!(!err.contains("panicked"), "{args:?} panicked:\n{err}");
}

/// Runs `accelbench sweep INDEX --scene SCENE --size 24 --repeats 1` over the sweep options
/// `points` into a scratch folder, and asserts a zero exit, one CSV row per point (`rows` of
/// them), a row containing every string of `row_with`, and both charts of the primary rays.
pub fn small_sweep(index: &str, scene: &str, points: &[&str], rows: usize, row_with: &[&str]) {
    let (_dir, out) = temp_path("s");
    let head = [
        "sweep",
        index,
        "--scene",
        scene,
        "--size",
        "24",
        "--repeats",
        "1",
    ];
    accelbench_ok(&[&head[..], points, &["--out", out.to_str().unwrap()]].concat());
    for f in ["primary-rays_per_s.svg", "primary-build_ms.svg"] {
        assert!(out.join(f).exists(), "{f}");
    }
    let csv = std::fs::read_to_string(out.join("primary.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + rows, "{csv}");
    assert!(
        csv.lines().any(|l| row_with.iter().all(|w| l.contains(w))),
        "{csv}"
    );
}

/// `../shared/meshes/<name>` when present; otherwise `None`, with a line saying the test part
/// that needs it is skipped.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/meshes")
        .join(name);
    if !p.exists() {
        eprintln!("skipped: {} not found", p.display());
    }
    p.exists().then_some(p)
}

/// A small `run` or `verify` for tests, as its arguments: `--quick --quiet` on the given scenes,
/// indices and ray sets, and for `run` one thread, one repeat, no pictures and `--out`. Options
/// are set or replaced with [`Suite::with`] and dropped with [`Suite::without`], so each test
/// states only what it changes.
#[derive(Clone, Debug)]
pub struct Suite {
    command: &'static str,
    /// Flags in order, each with its value (`None` for a switch such as `--quiet`).
    flags: Vec<(String, Option<String>)>,
}

impl Suite {
    /// `verify --quick --quiet --scenes S --indices I --rays R`.
    pub fn verify(scenes: &str, indices: &str, rays: &str) -> Suite {
        Suite {
            command: "verify",
            flags: Vec::new(),
        }
        .switch("--quick")
        .switch("--quiet")
        .with("--scenes", scenes)
        .with("--indices", indices)
        .with("--rays", rays)
    }

    /// `run`, as [`Suite::verify`] plus `--threads 1 --repeats 1 --picture-size 0 --out OUT`.
    pub fn run(scenes: &str, indices: &str, rays: &str, out: &Path) -> Suite {
        Suite {
            command: "run",
            ..Suite::verify(scenes, indices, rays)
        }
        .with("--threads", "1")
        .with("--repeats", "1")
        .with("--picture-size", "0")
        .with("--out", out.to_str().unwrap())
    }

    /// Sets option `flag` to `value`, in place of the value it had.
    pub fn with(mut self, flag: &str, value: &str) -> Suite {
        let value = Some(value.to_owned());
        match self.flags.iter_mut().find(|(f, _)| f == flag) {
            Some(entry) => entry.1 = value,
            None => self.flags.push((flag.to_owned(), value)),
        }
        self
    }

    /// Adds the switch `flag` (an option without a value).
    pub fn switch(mut self, flag: &str) -> Suite {
        if !self.flags.iter().any(|(f, _)| f == flag) {
            self.flags.push((flag.to_owned(), None));
        }
        self
    }

    /// Drops `flag` and its value.
    pub fn without(mut self, flag: &str) -> Suite {
        self.flags.retain(|(f, _)| f != flag);
        self
    }

    /// The command line after the program's name.
    pub fn args(&self) -> Vec<&str> {
        let mut args = vec![self.command];
        for (flag, value) in &self.flags {
            args.push(flag);
            args.extend(value.as_deref());
        }
        args
    }

    /// Runs it (see [`accelbench`]).
    pub fn output(&self) -> Output {
        accelbench(&self.args())
    }

    /// Runs it and expects success (see [`accelbench_ok`]); returns stdout.
    pub fn ok(&self) -> String {
        accelbench_ok(&self.args())
    }

    /// Runs it and expects a clean failure naming every `expected` piece (see
    /// [`accelbench_fails`]).
    pub fn fails(&self, expected: &[&str]) {
        accelbench_fails(&self.args(), expected)
    }
}

/// Writes the ray set `set` of `scene` to `out` with `accelbench rays`, its size or count given
/// by `amount` (for example `["--size", "8"]`), and asserts that it worked.
pub fn write_rays(out: &Path, scene: &str, set: &str, amount: &[&str]) {
    let head = ["rays", "--scene", scene, "--set", set, "--out"];
    accelbench_ok(&[&head[..], &[out.to_str().unwrap()], amount].concat());
}

/// The one line of a command's output `text` that contains `needle`; fails (showing `text`)
/// unless exactly one does.
pub fn the_line_with<'a>(text: &'a str, needle: &str) -> &'a str {
    let lines: Vec<&str> = text.lines().filter(|l| l.contains(needle)).collect();
    assert_eq!(lines.len(), 1, "{text}");
    lines[0]
}

/// accelbench started with `args` in the crate's folder, its standard output dropped and its
/// standard error piped (for tests that interrupt it).
pub fn spawn_piped(args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_accelbench"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

/// Sends `child` (from [`spawn_piped`]) a SIGINT as soon as a line of its standard error
/// contains `cue`, failing with `early` and what it said if it ends first; returns its exit
/// code and its standard error before and after the signal.
#[cfg(unix)]
pub fn interrupt_at(
    mut child: std::process::Child,
    cue: &str,
    early: &str,
) -> (Option<i32>, String, String) {
    use std::io::BufRead;
    let mut stderr = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut seen = String::new();
    loop {
        let mut line = String::new();
        let n = stderr.read_line(&mut line).unwrap();
        assert!(n > 0, "{early}:\n{seen}");
        seen.push_str(&line);
        if line.contains(cue) {
            break;
        }
    }
    // SAFETY: signals a child process this test started and has not reaped.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    (child.wait().unwrap().code(), seen, rest)
}
