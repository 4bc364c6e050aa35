//! `accelbench report DIR --markdown`: a report folder's dated results page names the machine,
//! the command and the commit of its run and holds its verdict and tables; a folder that is not
//! a report is refused with the missing file named.

use crate::common::cli::{Suite, accelbench, accelbench_fails, accelbench_ok};
use crate::common::temp::temp_path;

#[test]
fn a_report_folder_becomes_a_dated_results_page() {
    let (dir, out) = temp_path("run");
    Suite::run("icosphere:n=300", "bvh,grid", "primary", &out)
        .with("--picture-size", "16")
        .ok();
    let page_file = dir.path().join("page.md");
    let (o, p) = (out.to_str().unwrap(), page_file.to_str().unwrap());
    let title = "a small sphere";
    accelbench_ok(&["report", o, "--markdown", "--title", title, "--out", p]);
    let page = std::fs::read_to_string(&page_file).unwrap();
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    let day = &meta["date"].as_str().unwrap()[..10];
    assert!(
        page.starts_with(&format!("# {day}: a small sphere\n")),
        "{page}"
    );
    for fact in ["cpu", "command", "git_revision"] {
        let value = meta[fact].as_str().unwrap();
        assert!(
            page.contains(value),
            "the page lacks the run's {fact} '{value}':\n{page}"
        );
    }
    assert!(page.contains("## Verdict"), "{page}");
    assert!(page.contains("### icosphere"), "{page}");
    assert!(page.contains("| `bvh`") || page.contains("| bvh"), "{page}");

    let o = accelbench(&["report", out.to_str().unwrap()]);
    assert!(!o.status.success(), "a page without a format was written");
    let not_a_report = dir.path().to_str().unwrap();
    accelbench_fails(&["report", not_a_report, "--markdown"], &["results.csv"]);
}
