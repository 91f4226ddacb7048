//! Unit tests of `src/output.rs`, moved out of the library (one test binary).

use mdsolids::output::{
    Layout, TEMPORARIES, escape_for_terminal, host_name, read_at_most, read_regular, sweep_temporaries,
    write_atomically,
};
use std::sync::atomic::Ordering;
use std::time::Duration;

#[test]
fn planted_links_at_the_temporary_names_are_never_written_through() {
    let dir = crate::common::scratch();
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
    let dir = crate::common::scratch();
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

/// Guards issue 31, item 7: the store's reader opens only regular files and reads at most its
/// limit. A FIFO (opening it for reading blocked until a writer came) and a link to
/// `/dev/zero` (read until the memory ran out) are refused at once, each named; a file over
/// the limit is refused after one byte past it; a regular file, or a link to one, is read.
#[test]
fn only_regular_files_are_read_and_never_past_the_limit() {
    let dir = crate::common::scratch();
    let fifo = dir.path().join("record.json");
    let path = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(path.as_ptr(), 0o644) }, 0);
    let zero = dir.path().join("run.series");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    // On its own thread: the reader this replaced never returned from the FIFO.
    let (send, receive) = std::sync::mpsc::channel();
    let paths = (fifo.clone(), zero.clone());
    std::thread::spawn(move || {
        let read = |p: &std::path::Path| read_regular(p, 1 << 20, "a stored file").map_err(|e| e.to_string());
        let _ = send.send((read(&paths.0), read(&paths.1)));
    });
    let (from_fifo, from_zero) = receive.recv_timeout(Duration::from_secs(10)).expect("no answer within 10 s");
    assert_eq!(from_fifo, Err("a FIFO, not a regular file".into()));
    assert_eq!(from_zero, Err("a character device, not a regular file".into()));

    let file = dir.path().join("small.json");
    std::fs::write(&file, b"0123456789").unwrap();
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink(&file, &link).unwrap();
    assert_eq!(read_regular(&link, 10, "a stored file").unwrap(), b"0123456789");
    let error = read_regular(&file, 9, "a stored file").unwrap_err();
    assert_eq!(error.kind(), std::io::ErrorKind::FileTooLarge);
    assert_eq!(error.to_string(), "larger than 9 bytes, the most a stored file may hold");
    let error = read_at_most(std::io::repeat(0), 1 << 20, "a campaign file").unwrap_err();
    assert_eq!(error.to_string(), "larger than 1048576 bytes (1 MiB), the most a campaign file may hold");
}

/// Guards issue 31, item 8: text from the store printed to a terminal has its control
/// characters and bidirectional overrides escaped, and other text is left as it is.
#[test]
fn stored_text_is_escaped_for_the_terminal() {
    let hostile = "0.1.0+x\u{1b}]0;title\u{7}\u{1b}[2J\r\nnext\u{9b}31m\u{202e}txt";
    assert_eq!(escape_for_terminal(hostile), "0.1.0+x\\u{1b}]0;title\\u{7}\\u{1b}[2J\\r\\nnext\\u{9b}31m\\u{202e}txt");
    let plain = "pair-1a2b: γ = 0.5 N s/m, ü, 'quoted'";
    assert!(matches!(escape_for_terminal(plain), std::borrow::Cow::Borrowed(p) if p == plain));
}
