//! Unit tests of `src/output.rs`, moved out of the library (one test binary).

use mdsolids::output::{Layout, TEMPORARIES, host_name, sweep_temporaries, write_atomically};
use std::sync::atomic::Ordering;

#[test]
fn planted_links_at_the_temporary_names_are_never_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim");
    std::fs::write(&victim, "precious").unwrap();
    // Links at the next names this process would use (other tests may take some first).
    let next = TEMPORARIES.load(Ordering::Relaxed);
    for n in next..next + 8 {
        let name = format!(".out.json.{}.{}.{n}.tmp", host_name(), std::process::id());
        std::os::unix::fs::symlink(&victim, dir.path().join(name)).unwrap();
    }
    write_atomically(&dir.path().join("out.json"), b"new").unwrap();
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert_eq!(std::fs::read_to_string(dir.path().join("out.json")).unwrap(), "new");
}

#[test]
fn sweeping_removes_only_the_temporaries_of_dead_processes_of_this_host() {
    let dir = tempfile::tempdir().unwrap();
    let layout = Layout::new(dir.path(), "c");
    let runs = layout.root.join("runs");
    std::fs::create_dir_all(&runs).unwrap();
    // A pid that has ended (reaped, so /proc has no entry for it).
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let (host, live) = (host_name(), std::process::id());
    let names = [
        (format!(".a.json.{host}.{dead}.0.tmp"), false),
        (format!(".a.json.{host}.{live}.0.tmp"), true), // this process: alive
        (format!(".a.json.other-host.{dead}.0.tmp"), true), // its pid cannot be checked here
        ("a-0123.gif.tmp".to_string(), false),          // the fixed name of earlier versions
        ("a-0123.json".to_string(), true),
    ];
    for (name, _) in &names {
        std::fs::write(runs.join(name), "x").unwrap();
    }
    assert_eq!(sweep_temporaries(&layout), 2);
    for (name, kept) in &names {
        assert_eq!(runs.join(name).exists(), *kept, "{name}");
    }
}
