//! CSV tables: one `Serialize` struct per row, the header from its field names.

use super::ReportError;
use serde::Serialize;
use std::path::Path;

/// Writes `rows` to `path` (creating parent directories), with a header row even when `rows` is
/// empty only if the row type can name its fields (csv writes the header with the first row).
pub fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> Result<(), ReportError> {
    let err = |message: String| ReportError::Write {
        path: path.to_owned(),
        message,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| err(e.to_string()))?;
    }
    let mut w = csv::Writer::from_path(path).map_err(|e| err(e.to_string()))?;
    for r in rows {
        w.serialize(r).map_err(|e| err(e.to_string()))?;
    }
    w.flush().map_err(|e| err(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize, serde::Deserialize, Debug, PartialEq)]
    struct Row {
        name: String,
        value: f64,
    }

    #[test]
    fn rows_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("sub/t.csv");
        let rows = vec![
            Row {
                name: "a,b".into(),
                value: 1.5,
            },
            Row {
                name: "c".into(),
                value: -2.0,
            },
        ];
        write_csv(&p, &rows).unwrap();
        let back: Vec<Row> = csv::Reader::from_path(&p)
            .unwrap()
            .deserialize()
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(back, rows);
    }
}
