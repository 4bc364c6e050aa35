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
        }
    }
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
    fn utc_date_format() {
        let d = utc_now();
        assert_eq!(d.len(), 20, "{d}");
        assert!(d.starts_with("20") && d.ends_with('Z'));
        let id = run_id_now();
        assert_eq!(id.len(), 15, "{id}");
    }
}
