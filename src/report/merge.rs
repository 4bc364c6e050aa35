//! `accelbench merge DIR... --out DIR`: the shards of one run (`accelbench run --shard K/N`)
//! combined into one report whose rows are the rows an unsharded run writes, in its order
//! (timings aside: each shard timed its own work).
//!
//! Order: an unsharded run writes scene by scene (run order), ray set by ray set (the
//! configuration's order), index by index (the `--indices` order), thread count by thread count.
//! A shard ran index `j` of scene `s` when [`Shard::takes`]; within one scene and ray set its
//! rows come in its indices' order, so each group of rows is matched to the next index of the
//! shard's share with the same name.

use super::ReportError;
use super::run_meta::RunMeta;
use super::run_notes::RunNotes;
use crate::harness::suite::{ResultRow, Shard};
use std::path::{Path, PathBuf};

/// One shard's report folder, read back.
#[derive(Debug)]
pub struct ShardReport {
    pub dir: PathBuf,
    pub meta: RunMeta,
    pub rows: Vec<ResultRow>,
    pub notes: RunNotes,
}

fn read_err(path: &Path, message: String) -> ReportError {
    ReportError::Read {
        path: path.to_owned(),
        message,
    }
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, ReportError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        read_err(
            path,
            format!(
                "{e}; give a report folder written by `accelbench run` (to merge: one per shard of `run --shard K/N`)"
            ),
        )
    })?;
    serde_json::from_str(&text).map_err(|e| read_err(path, e.to_string()))
}

/// Reads `meta.json`, `notes.json` and `results.csv` of a shard's report folder.
pub fn load_shard(dir: &Path) -> Result<ShardReport, ReportError> {
    let csv_path = dir.join("results.csv");
    let mut r =
        csv::Reader::from_path(&csv_path).map_err(|e| read_err(&csv_path, e.to_string()))?;
    let rows = r
        .deserialize()
        .collect::<Result<Vec<ResultRow>, _>>()
        .map_err(|e| read_err(&csv_path, e.to_string()))?;
    Ok(ShardReport {
        dir: dir.to_owned(),
        meta: read_json(&dir.join("meta.json"))?,
        notes: read_json(&dir.join("notes.json"))?,
        rows,
    })
}

/// The configuration without its `shard` entry: equal for the shards of one run.
fn config_of_run(meta: &RunMeta) -> serde_json::Value {
    let mut c = meta.config.clone();
    if let Some(o) = c.as_object_mut() {
        o.remove("shard");
    }
    c
}

/// Checks that `shards` are every shard of one run, once each; sorts them by number.
fn check_complete(shards: &mut [ShardReport]) -> Result<(), ReportError> {
    let bad = |m: String| ReportError::Merge(m);
    let first = shards
        .first()
        .ok_or_else(|| bad("no shard folders given".into()))?;
    let n = first.meta.shard.n();
    let (config, scenes) = (config_of_run(&first.meta), first.meta.scenes.clone());
    for s in shards.iter() {
        if s.meta.shard.n() != n || config_of_run(&s.meta) != config || s.meta.scenes != scenes {
            return Err(bad(format!(
                "{} is not a shard of the same run as {} (another configuration, scene list or \
                 shard count): merge the shards of one `accelbench run --shard K/N` command",
                s.dir.display(),
                first.dir.display()
            )));
        }
    }
    shards.sort_by_key(|s| s.meta.shard.k());
    for k in 1..=n {
        let have: Vec<&ShardReport> = shards.iter().filter(|s| s.meta.shard.k() == k).collect();
        match have.len() {
            1 => {}
            0 => {
                return Err(bad(format!(
                    "shard {k}/{n} is missing: run it and give its folder"
                )));
            }
            _ => {
                let dirs: Vec<String> = have.iter().map(|s| s.dir.display().to_string()).collect();
                return Err(bad(format!(
                    "shard {k}/{n} is given twice: {}",
                    dirs.join(", ")
                )));
            }
        }
    }
    Ok(())
}

/// The index position (in the run's `--indices` list) of each row of one shard, matched as the
/// module doc says; `usize::MAX` for a row no index of the share matches.
fn index_positions(shard: &ShardReport, index_names: &[String]) -> Vec<usize> {
    let n = index_names.len();
    let mut pos = vec![usize::MAX; shard.rows.len()];
    let mut i = 0;
    while i < shard.rows.len() {
        let (scene, set) = (&shard.rows[i].scene, &shard.rows[i].ray_set);
        let s = shard
            .meta
            .scenes
            .iter()
            .position(|x| x == scene)
            .unwrap_or(0);
        let mut share = (0..n).filter(|&j| shard.meta.shard.takes(s, j, n));
        // The rows of this scene and ray set, grouped by index and parameters.
        while i < shard.rows.len() && shard.rows[i].scene == *scene && shard.rows[i].ray_set == *set
        {
            let r = &shard.rows[i];
            let j = share
                .find(|&j| index_names[j] == r.index)
                .unwrap_or(usize::MAX);
            while i < shard.rows.len()
                && shard.rows[i].scene == r.scene
                && shard.rows[i].ray_set == r.ray_set
                && shard.rows[i].index == r.index
                && shard.rows[i].params == r.params
            {
                pos[i] = j;
                i += 1;
            }
        }
    }
    pos
}

/// Merges the shards of one run: the metadata of a whole run (`command` is the merge's), the
/// rows in an unsharded run's order, and every shard's notes.
pub fn merge_shards(
    mut shards: Vec<ShardReport>,
    command: String,
) -> Result<(RunMeta, Vec<ResultRow>, RunNotes), ReportError> {
    check_complete(&mut shards)?;
    if let Some(s) = shards.iter().find(|s| !s.meta.status.is_complete()) {
        return Err(ReportError::Merge(format!(
            "{} holds an unfinished run (status: {}): rerun that shard, then merge",
            s.dir.display(),
            s.meta.status
        )));
    }
    let meta0 = &shards[0].meta;
    let strings = |key: &str| -> Vec<String> {
        (meta0.config[key].as_array().into_iter().flatten())
            .map(|v| v.as_str().unwrap_or_default().to_owned())
            .collect()
    };
    let index_names: Vec<String> = strings("indices")
        .iter()
        .map(|s| s.split(':').next().unwrap_or_default().trim().to_owned())
        .collect();
    let sets = strings("sets");
    let mut keyed = Vec::new();
    let mut notes = RunNotes::default();
    for shard in &shards {
        let pos = index_positions(shard, &index_names);
        for (r, j) in shard.rows.iter().zip(pos) {
            let scene = meta0.scenes.iter().position(|s| *s == r.scene);
            let set = sets.iter().position(|s| *s == r.ray_set);
            keyed.push(((scene, set, j, r.threads), r.clone()));
        }
        notes.absorb(shard.notes.clone());
    }
    keyed.sort_by_key(|(k, _)| *k);
    let mut meta = meta0.clone();
    meta.shard = Shard::WHOLE;
    meta.run_id = format!("{}-merged", meta0.run_id);
    meta.command = command;
    Ok((meta, keyed.into_iter().map(|(_, r)| r).collect(), notes))
}
