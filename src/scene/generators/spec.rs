//! A generator request with its size and seed, as written on the command line
//! (`soup`, `stadium:n=1000000`, `soup:n=100_000,seed=3`) or in a scene file's `[[generator]]`.

use super::{DEFAULT_SEED, DEFAULT_SIZE, GENERATOR_NAMES, generate};
use crate::scene::{Scene, SceneError};
use std::fmt;

/// The largest `n` a generator accepts (about 6.4 GB of triangles at 48 bytes each); larger
/// requests are refused instead of exhausting memory.
pub const MAX_GENERATED: usize = 1 << 27;

/// A known generator name with a validated size `1..=MAX_GENERATED` and a seed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GeneratorSpec {
    pub name: String,
    pub n: usize,
    pub seed: u64,
}

impl GeneratorSpec {
    /// Checks the name and the size; `n` is signed so a negative value gets a clear message.
    pub fn new(name: &str, n: i64, seed: u64) -> Result<GeneratorSpec, SceneError> {
        if !GENERATOR_NAMES.contains(&name) {
            return Err(SceneError::UnknownScene(
                name.to_owned(),
                GENERATOR_NAMES.join(", "),
            ));
        }
        if n < 1 || n as u64 > MAX_GENERATED as u64 {
            return Err(SceneError::Invalid(
                name.to_owned(),
                format!(
                    "n = {n} is out of range: give a primitive count from 1 to {MAX_GENERATED}"
                ),
            ));
        }
        Ok(GeneratorSpec {
            name: name.to_owned(),
            n: n as usize,
            seed,
        })
    }

    /// Parses `NAME` or `NAME:key=value,...` with keys `n` and `seed` (digits, `_` allowed),
    /// each at most once.
    /// An unknown name is [`SceneError::UnknownScene`]; anything else wrong is
    /// [`SceneError::Invalid`] naming the bad part.
    pub fn parse(arg: &str) -> Result<GeneratorSpec, SceneError> {
        let (name, rest) = arg.split_once(':').unwrap_or((arg, ""));
        let name = name.trim();
        let bad = |message: String| SceneError::Invalid(arg.to_owned(), message);
        GeneratorSpec::new(name, 1, 0)?;
        let (mut n, mut seed) = (DEFAULT_SIZE as i64, DEFAULT_SEED);
        let mut seen: Vec<&str> = Vec::new();
        for item in rest.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, value) = item
                .split_once('=')
                .ok_or_else(|| bad(format!("'{item}' is not key=value (keys: n, seed)")))?;
            if seen.contains(&key.trim()) {
                return Err(bad(format!(
                    "'{}' is given twice: give each parameter once",
                    key.trim()
                )));
            }
            seen.push(key.trim());
            let value = value.trim().replace('_', "");
            let number = || {
                value
                    .parse::<i64>()
                    .map_err(|_| bad(format!("'{item}': the value must be a whole number")))
            };
            match key.trim() {
                "n" => n = number()?,
                "seed" => {
                    let digits = !value.is_empty() && value.bytes().all(|b| b.is_ascii_digit());
                    seed = value.parse::<u64>().map_err(|_| match digits {
                        true => bad(format!("'{item}': the seed must be at most {}", u64::MAX)),
                        false => bad(format!("'{item}': the seed must be a whole number >= 0")),
                    })?
                }
                other => {
                    return Err(bad(format!(
                        "unknown parameter '{other}': a built-in scene takes n and seed"
                    )));
                }
            }
        }
        GeneratorSpec::new(name, n, seed)
    }

    /// The generated, validated scene, named by this spec (see [`fmt::Display`]).
    pub fn generate(&self) -> Result<Scene, SceneError> {
        let mut scene =
            generate(&self.name, self.n, self.seed).expect("GeneratorSpec::new checked the name");
        scene.name = self.to_string();
        scene.validate()?;
        Ok(scene)
    }
}

/// `NAME` when size and seed are the defaults, else `NAME:n=N,seed=S`.
impl fmt::Display for GeneratorSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.n == DEFAULT_SIZE && self.seed == DEFAULT_SEED {
            f.write_str(&self.name)
        } else {
            write!(f, "{}:n={},seed={}", self.name, self.n, self.seed)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_name_size_and_seed() {
        let s = GeneratorSpec::parse("soup:n=100_000, seed=3").unwrap();
        assert_eq!((s.name.as_str(), s.n, s.seed), ("soup", 100_000, 3));
        assert_eq!(s.to_string(), "soup:n=100000,seed=3");
        let d = GeneratorSpec::parse("terrain").unwrap();
        assert_eq!((d.n, d.seed), (DEFAULT_SIZE, DEFAULT_SEED));
        assert_eq!(d.to_string(), "terrain");
        assert_eq!(GeneratorSpec::parse("room:n=1000").unwrap().n, 1000);
    }

    #[test]
    fn bad_specs_are_typed_errors() {
        assert!(matches!(
            GeneratorSpec::parse("nope:n=5"),
            Err(SceneError::UnknownScene(..))
        ));
        for bad in [
            "soup:n=0",
            "soup:n=-5",
            "soup:n=1e6",
            "soup:n=99999999999",
            "soup:seed=-1",
            "soup:size=10",
            "soup:n",
            "soup:n=10,n=20",
            "soup:seed=1,n=5,seed=1",
        ] {
            assert!(
                matches!(GeneratorSpec::parse(bad), Err(SceneError::Invalid(..))),
                "{bad}"
            );
        }
    }

    #[test]
    fn generated_scene_is_named_by_the_spec() {
        let s = GeneratorSpec::parse("soup:n=1000,seed=3")
            .unwrap()
            .generate()
            .unwrap();
        assert_eq!((s.name.as_str(), s.len()), ("soup:n=1000,seed=3", 1000));
    }
}
