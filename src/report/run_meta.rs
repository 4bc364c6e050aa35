//! `meta.json`: the facts about a run that are not in its rows (date, git revision, machine,
//! command, configuration).

use crate::harness::suite::{Shard, SuiteConfig};
use serde::{Deserialize, Serialize};

/// Facts about the run that are not in the rows. `accelbench merge` reads it back from the
/// shards' `meta.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunMeta {
    pub run_id: String,
    /// UTC, `YYYY-MM-DDTHH:MM:SSZ`.
    pub date: String,
    pub git_revision: String,
    pub cpu: String,
    pub cores: usize,
    pub os: String,
    pub command: String,
    /// Names of the run's scenes in run order (the order of rows and of shard work items).
    pub scenes: Vec<String>,
    /// Thread counts of the timed passes, ascending.
    pub threads: Vec<usize>,
    /// The triangle kernel's name.
    pub kernel: String,
    /// Timed repeats per measurement.
    pub repeats: usize,
    /// The share of the work this run did (`1/1` for a whole run).
    pub shard: Shard,
    /// Every parameter of the run: the suite configuration as JSON.
    pub config: serde_json::Value,
    /// Whether the report holds the whole run ([`RunStatus`]); reports written before the
    /// field read back as `complete`.
    #[serde(default)]
    pub status: RunStatus,
    /// The GPU adapter and its driver, when the run has GPU indices (feature `gpu`) and the
    /// machine an adapter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gpu_adapter: Option<String>,
}

/// How a run ended, `meta.json`'s `status`: `complete` (every measurement made and passed),
/// `interrupted` (a SIGINT stopped it: the report holds the ray sets finished before), or
/// `failed: REASON` (it ended with an error, e.g. a mismatch or a failed index of ours: the
/// report holds what was measured). `complete` exactly when `run` exits 0.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(into = "String", from = "String")]
pub enum RunStatus {
    #[default]
    Complete,
    Interrupted,
    Failed(String),
}

impl RunStatus {
    pub fn is_complete(&self) -> bool {
        *self == RunStatus::Complete
    }

    /// The status and what it means for the report, one sentence (`summary.md`, `index.html`).
    pub fn sentence(&self) -> String {
        match self {
            RunStatus::Complete => "complete: the report holds the whole run.".into(),
            RunStatus::Interrupted => "interrupted: a SIGINT stopped the run; the report holds \
                                       the ray sets finished before it."
                .into(),
            RunStatus::Failed(why) => {
                format!("failed: {why}; the report holds what was measured.")
            }
        }
    }
}

impl std::fmt::Display for RunStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            RunStatus::Complete => f.write_str("complete"),
            RunStatus::Interrupted => f.write_str("interrupted"),
            RunStatus::Failed(why) => write!(f, "failed: {why}"),
        }
    }
}

impl From<RunStatus> for String {
    fn from(s: RunStatus) -> String {
        s.to_string()
    }
}

/// The text `meta.json` holds; anything but `complete` and `interrupted` is a failure.
impl From<String> for RunStatus {
    fn from(s: String) -> RunStatus {
        match s.as_str() {
            "complete" => RunStatus::Complete,
            "interrupted" => RunStatus::Interrupted,
            _ => RunStatus::Failed(s.strip_prefix("failed: ").unwrap_or(&s).to_owned()),
        }
    }
}

impl RunMeta {
    /// Collects the machine facts and the date now.
    pub fn collect(
        run_id: String,
        command: String,
        config: &SuiteConfig,
        scenes: Vec<String>,
    ) -> RunMeta {
        RunMeta {
            run_id,
            date: utc_now(),
            git_revision: git_revision(),
            cpu: cpu_model(),
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: std::env::consts::OS.to_owned(),
            command,
            scenes,
            threads: config.threads.clone(),
            kernel: config.kernel.name().to_owned(),
            repeats: config.repeats,
            shard: config.shard,
            config: serde_json::to_value(config).expect("the configuration serializes"),
            status: RunStatus::Complete,
            gpu_adapter: gpu_adapter(config),
        }
    }
}

/// The adapter of the run's GPU indices, opened only when the run has any.
fn gpu_adapter(config: &SuiteConfig) -> Option<String> {
    #[cfg(feature = "gpu")]
    if config
        .indices
        .iter()
        .any(|s| crate::index::registry::kind_of(&s.name) == Some(crate::index::Kind::Gpu))
    {
        return crate::index::gpu::gpu().ok().map(|g| g.adapter.clone());
    }
    let _ = config;
    None
}

/// `YYYYMMDD-HHMMSS` of the current UTC time (a run id).
pub fn run_id_now() -> String {
    utc_now()
        .replace(['-', ':'], "")
        .replace('T', "-")
        .trim_end_matches('Z')
        .to_owned()
}

fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

fn git_revision() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_else(|| "unknown".into())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_status_reads_back_as_written() {
        for s in [
            RunStatus::Complete,
            RunStatus::Interrupted,
            RunStatus::Failed("verification: 3 mismatching results".into()),
        ] {
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(
                serde_json::from_str::<RunStatus>(&json).unwrap(),
                s,
                "{json}"
            );
        }
        assert_eq!(
            serde_json::to_string(&RunStatus::Failed("x".into())).unwrap(),
            "\"failed: x\""
        );
    }

    #[test]
    fn utc_date_format() {
        let d = utc_now();
        assert_eq!(d.len(), 20, "{d}");
        assert!(d.starts_with("20") && d.ends_with('Z'));
        let id = run_id_now();
        assert_eq!(id.len(), 15, "{id}");
    }
}
