//! Unit tests of `src/owner.rs`, moved out of the library (one test binary).

use mdsolids::output::Layout;
use mdsolids::owner::{MARKER, campaign_of, claim, identity};

#[test]
fn the_first_file_owns_the_folder_and_another_is_refused_unless_forced() {
    let work = crate::common::scratch();
    let (a, b) = (work.path().join("a.yaml"), work.path().join("b.yaml"));
    std::fs::write(&a, "a").unwrap();
    std::fs::write(&b, "b").unwrap();
    let layout = Layout::new(&work.path().join("reports"), "same");
    claim(&layout, &a, false).unwrap();
    claim(&layout, &a, false).unwrap();
    // The same file by another path is the same campaign.
    claim(&layout, &work.path().join(".").join("a.yaml"), false).unwrap();
    let error = claim(&layout, &b, false).unwrap_err().to_string();
    for part in [&identity(&a).unwrap(), &identity(&b).unwrap(), "--force", "name:"] {
        assert!(error.contains(part), "{part} missing from: {error}");
    }
    claim(&layout, &b, true).unwrap();
    assert!(claim(&layout, &a, false).is_err(), "forced: the folder is b's now");
    claim(&layout, &b, false).unwrap();
    assert_eq!(campaign_of(&layout.root), Some(format!("campaign file '{}'", identity(&b).unwrap())));
    let left: Vec<_> = std::fs::read_dir(&layout.root).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, vec![std::ffi::OsString::from(MARKER)], "no staged files left behind");
}

#[test]
fn a_garbled_marker_and_a_comparison_folder_are_refused() {
    let work = crate::common::scratch();
    let file = work.path().join("a.yaml");
    std::fs::write(&file, "a").unwrap();
    let layout = Layout::new(work.path(), "x");
    std::fs::create_dir_all(&layout.root).unwrap();
    std::fs::write(layout.file("compare.parquet"), "").unwrap();
    assert!(claim(&layout, &file, false).unwrap_err().to_string().contains("mdsolids compare"));
    std::fs::write(layout.file(MARKER), "{").unwrap();
    assert!(claim(&layout, &file, false).unwrap_err().to_string().contains("--force"));
    assert_eq!(campaign_of(&layout.root).as_deref(), Some("a campaign"));
}
