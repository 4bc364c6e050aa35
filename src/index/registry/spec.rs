//! Index specs on the command line: `NAME` or `NAME:key=value,...` ([`IndexSpec`]), and the
//! parser of the parameter list.

use crate::index::BuildError;
use std::fmt;

/// An index name with optional parameters: `NAME` or `NAME:key=value,key=value`, values in TOML
/// syntax (`bvh:leaf_size=4,preset="sweep"`, `grid:res=[64,64,32]`).
#[derive(Debug, Clone, PartialEq)]
pub struct IndexSpec {
    pub name: String,
    pub params: toml::Table,
}

impl IndexSpec {
    /// The spec of `name` with default parameters.
    pub fn named(name: &str) -> IndexSpec {
        IndexSpec {
            name: name.to_owned(),
            params: toml::Table::new(),
        }
    }
}

impl fmt::Display for IndexSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)?;
        for (i, (k, v)) in self.params.iter().enumerate() {
            write!(f, "{}{k}={v}", if i == 0 { ':' } else { ',' })?;
        }
        Ok(())
    }
}

/// The parameters `rest` of a spec of index `name` (after the colon): split on commas outside
/// brackets and quotes, each `key=value` read as a TOML line.
pub(super) fn parse_params_list(name: &str, rest: &str) -> Result<toml::Table, BuildError> {
    let bad = |message: String| BuildError::Params {
        index: name.to_owned(),
        message,
    };
    // Split on commas outside brackets and quotes, then parse as TOML `key = value` lines.
    let mut doc = String::new();
    let (mut depth, mut quoted, mut start) = (0i32, false, 0usize);
    let bytes = rest.as_bytes();
    for i in 0..=bytes.len() {
        let c = bytes.get(i).copied();
        match c {
            Some(b'"') => quoted = !quoted,
            Some(b'[') if !quoted => depth += 1,
            Some(b']') if !quoted => depth -= 1,
            Some(b',') | None if depth == 0 && !quoted => {
                let item = rest[start..i].trim();
                start = i + 1;
                if item.is_empty() {
                    continue;
                }
                let (k, v) = item
                    .split_once('=')
                    .ok_or_else(|| bad(format!("'{item}' is not key=value")))?;
                doc.push_str(&format!("{} = {}\n", k.trim(), v.trim()));
            }
            _ => {}
        }
    }
    doc.parse().map_err(|e| bad(format!("{e}")))
}
