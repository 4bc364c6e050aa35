//! The layer table of `ARCHITECTURE.md` ("Layers, bottom up"): which top-level folders each
//! top-level folder may import, read from the table's "may import" column so that the check
//! and the document cannot disagree.

use std::collections::{BTreeMap, BTreeSet};

/// Each layer (a top-level folder or file of `src/`) and the layers it may import.
pub type Layers = BTreeMap<String, BTreeSet<String>>;

/// The layers of the table under the heading `## Layers, bottom up` of `architecture`.
///
/// A row's first cell names its layers (backticked), which may import each other; its last
/// cell says what they may import besides: "nothing of ours", backticked names, "everything
/// above" (the rows before it), "`X` and everything below it" (`X` and the rows before `X`'s),
/// "everything except `X`", or "everything".
pub fn layers(architecture: &str) -> Layers {
    let table: Vec<(Vec<String>, String)> = architecture
        .split("## Layers, bottom up")
        .nth(1)
        .expect("ARCHITECTURE.md has a section 'Layers, bottom up'")
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split('|').collect();
            (
                backticked(cells[0]),
                cells[cells.len() - 1].trim().to_owned(),
            )
        })
        .collect();
    let all: BTreeSet<String> = table.iter().flat_map(|(n, _)| n.clone()).collect();
    let before = |row: usize| -> BTreeSet<String> {
        table[..row].iter().flat_map(|(n, _)| n.clone()).collect()
    };
    let row_of = |name: &str| table.iter().position(|(n, _)| n.iter().any(|x| x == name));
    let mut out = Layers::new();
    for (row, (names, rule)) in table.iter().enumerate() {
        let named: BTreeSet<String> = backticked(rule).into_iter().collect();
        let allowed = if rule.contains("nothing of ours") {
            BTreeSet::new()
        } else if rule.contains("everything above") {
            before(row)
        } else if rule.contains("everything below") {
            let mut below = named.clone();
            for n in &named {
                below.extend(before(row_of(n).expect("a layer of the table")));
            }
            below
        } else if rule.contains("everything except") {
            all.difference(&named).cloned().collect()
        } else if rule.contains("everything") {
            all.clone()
        } else {
            named
        };
        for n in names {
            let mut allowed = allowed.clone();
            allowed.extend(names.iter().filter(|m| *m != n).cloned());
            out.insert(n.clone(), allowed);
        }
    }
    out
}

/// The backticked words of a table cell.
fn backticked(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_of_the_table_is_read() {
        let doc = "## Layers, bottom up\n\n| folder | what | may import |\n|---|---|---|\n\
            | `a` | x | nothing of ours |\n| `b`, `c` | x | `a` |\n| `d` | x | everything above |\n\
            | `e` | x | `c` and everything below it |\n| `f` | x | everything except `g` |\n\
            | `g` | x | everything |\n\n## Next\n";
        let l = layers(doc);
        let set = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<BTreeSet<_>>();
        assert_eq!(l["a"], set(&[]));
        assert_eq!(
            l["c"],
            set(&["a", "b"]),
            "a row's layers may import each other"
        );
        assert_eq!(l["d"], set(&["a", "b", "c"]));
        assert_eq!(l["e"], set(&["a", "c"]));
        assert_eq!(l["f"], set(&["a", "b", "c", "d", "e", "f"]));
        assert_eq!(l["g"].len(), 7);
    }
}
