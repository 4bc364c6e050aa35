//! A deterministic share of a suite run (`accelbench run --shard K/N`): the scene x index work
//! items are numbered scene-major in run order, and shard `K` of `N` takes the items whose
//! number is `K - 1` modulo `N`, so the `N` shards together run every item exactly once and
//! neighbouring items (the same scene's indices) spread over the shards.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Shard `k` (1-based) of `n`; `1/1` is the whole run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct Shard {
    k: usize,
    n: usize,
}

impl Shard {
    /// The whole run.
    pub const WHOLE: Shard = Shard { k: 1, n: 1 };

    /// Shard `k` of `n`; `None` unless `1 <= k <= n`.
    pub fn new(k: usize, n: usize) -> Option<Shard> {
        (1..=n).contains(&k).then_some(Shard { k, n })
    }

    /// This shard's number, 1-based.
    pub fn k(self) -> usize {
        self.k
    }

    /// How many shards the run is split into.
    pub fn n(self) -> usize {
        self.n
    }

    /// Whether the work item of scene `scene` (position in the run's scene list) and index
    /// `index` (position in the run's index list of `indices` entries) belongs to this shard.
    pub fn takes(self, scene: usize, index: usize, indices: usize) -> bool {
        (scene * indices + index) % self.n == self.k - 1
    }
}

impl Default for Shard {
    fn default() -> Shard {
        Shard::WHOLE
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("'{s}' is not a shard: write K/N with 1 <= K <= N, e.g. 2/4");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k = k.trim().parse().map_err(|_| bad())?;
        let n = n.trim().parse().map_err(|_| bad())?;
        Shard::new(k, n).ok_or_else(bad)
    }
}

impl TryFrom<String> for Shard {
    type Error = String;
    fn try_from(s: String) -> Result<Shard, String> {
        s.parse()
    }
}

impl From<Shard> for String {
    fn from(s: Shard) -> String {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_every_item_once() {
        for n in 1..5 {
            for (scenes, indices) in [(1, 1), (3, 4), (2, 7)] {
                for s in 0..scenes {
                    for i in 0..indices {
                        let owners = (1..=n)
                            .filter(|&k| Shard::new(k, n).unwrap().takes(s, i, indices))
                            .count();
                        assert_eq!(owners, 1, "n={n} s={s} i={i}");
                    }
                }
            }
        }
    }

    #[test]
    fn parses_and_rejects() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard::new(2, 4).unwrap()));
        assert_eq!(Shard::new(2, 4).unwrap().to_string(), "2/4");
        for bad in ["0/2", "3/2", "1", "a/b", "1/0"] {
            assert!(bad.parse::<Shard>().unwrap_err().contains("K/N"), "{bad}");
        }
    }
}
