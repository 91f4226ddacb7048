//! Where a campaign's files go, and how they are written: whole or not at all.

use anyhow::Context;
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The output tree of one campaign: `<reports>/<campaign>/`.
#[derive(Clone, Debug)]
pub struct Layout {
    /// `<reports>/<campaign>`.
    pub root: PathBuf,
}

/// The movie of run `run_id`, relative to its campaign's directory (as the report links it).
pub fn movie_name(run_id: &str) -> String {
    format!("plots/{run_id}.gif")
}

/// The probe table of run `run_id` (its probed lines, `runner::record`), relative to its
/// campaign's directory.
pub fn probe_table_name(run_id: &str) -> String {
    format!("probes/{run_id}.parquet")
}

/// The series table of run `run_id` (its sample times and energies, `runner::series`),
/// relative to its campaign's directory.
pub fn series_table_name(run_id: &str) -> String {
    format!("series/{run_id}.parquet")
}

/// The particle table of run `run_id` (its per-particle series, `runner::series`), relative to
/// its campaign's directory.
pub fn particle_table_name(run_id: &str) -> String {
    format!("series/{run_id}.particles.parquet")
}

/// The final state of packing run `run_id` (its discs' x, y and radius, `runner::series`),
/// relative to its campaign's directory.
pub fn packing_name(run_id: &str) -> String {
    format!("packings/{run_id}.parquet")
}

/// The side-by-side movie of `scene`, relative to its campaign's directory.
pub fn side_by_side_name(scene: &str) -> String {
    format!("plots/{scene}-side-by-side.gif")
}

impl Layout {
    /// Layout of campaign `name` under the reports directory `reports`.
    pub fn new(reports: &Path, name: &str) -> Layout {
        Layout { root: reports.join(name) }
    }
    /// Stored result of one run.
    pub fn run_file(&self, run_id: &str) -> PathBuf {
        self.root.join("runs").join(format!("{run_id}.json"))
    }
    /// The series table of run `run_id`, stored with its record.
    pub fn series_table_file(&self, run_id: &str) -> PathBuf {
        self.file(&series_table_name(run_id))
    }
    /// The particle table of run `run_id`, stored with its record when it keeps any.
    pub fn particle_table_file(&self, run_id: &str) -> PathBuf {
        self.file(&particle_table_name(run_id))
    }
    /// The probe table of run `run_id`, stored with its record.
    pub fn probe_table_file(&self, run_id: &str) -> PathBuf {
        self.file(&probe_table_name(run_id))
    }
    /// The final state of packing run `run_id`, written with its record.
    pub fn packing_file(&self, run_id: &str) -> PathBuf {
        self.file(&packing_name(run_id))
    }
    /// The lock file held while run `run_id` is simulated (hidden, beside the records).
    pub fn run_lock_file(&self, run_id: &str) -> PathBuf {
        self.root.join("runs").join(".locks").join(format!("{run_id}.lock"))
    }
    /// The movie of run `run_id`, beside the figures (the report shows it; `runs/` is the cache).
    pub fn movie_file(&self, run_id: &str) -> PathBuf {
        self.file(&movie_name(run_id))
    }
    /// The movie of all runs of `scene` side by side.
    pub fn side_by_side_movie(&self, scene: &str) -> PathBuf {
        self.file(&side_by_side_name(scene))
    }
    /// The run ids (one a line) the side-by-side movie of `scene` was drawn from.
    pub fn side_by_side_runs(&self, scene: &str) -> PathBuf {
        self.plot_file(&format!("{scene}-side-by-side.runs"))
    }
    /// The lock file held while tables and reports are written.
    pub fn publish_lock_file(&self) -> PathBuf {
        self.root.join(".publish.lock")
    }
    /// A figure.
    pub fn plot_file(&self, name: &str) -> PathBuf {
        self.root.join("plots").join(name)
    }
    /// A file at the top of the campaign's directory.
    pub fn file(&self, name: &str) -> PathBuf {
        self.root.join(name)
    }
}

/// Writes `bytes` to `path` atomically: into a temporary file beside it, then renamed over it,
/// so a reader sees the old file or the new one, never half of one. Every file the program
/// writes goes through here.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create directory '{}'", dir.display()))?;
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("output");
    // A fresh name (host, process, counter) opened with O_CREAT|O_EXCL|O_NOFOLLOW: whatever
    // is planted there (a symbolic link, a file) is never written through; the next name is
    // tried instead. Flushed to the disk before the rename, so that after a crash the name
    // holds the whole new file or the old one. A failed write removes its partial temporary.
    let mut temporary = dir.join(temporary_name(name));
    let mut opened = create_exclusive(&temporary);
    for _ in 0..16 {
        if !opened.as_ref().is_err_and(|e| e.kind() == std::io::ErrorKind::AlreadyExists) {
            break;
        }
        temporary = dir.join(temporary_name(name));
        opened = create_exclusive(&temporary);
    }
    let written = opened.and_then(|mut file| {
        std::io::Write::write_all(&mut file, bytes)?;
        file.sync_all()
    });
    if let Err(error) = written {
        let _ = std::fs::remove_file(&temporary);
        return Err(error).with_context(|| {
            format!("cannot write '{}' (its temporary '{}' is removed)", path.display(), temporary.display())
        });
    }
    if let Err(error) = std::fs::rename(&temporary, path) {
        let _ = std::fs::remove_file(&temporary);
        return Err(error).with_context(|| format!("cannot move '{}' into place", path.display()));
    }
    Ok(())
}

/// Reads `reader` to its end, refusing more than `most` bytes with an error saying that this is
/// the most `what` (e.g. "a campaign file") may hold. One byte past the limit is read and no
/// more, so `/dev/zero` or a runaway generator is refused at once instead of filling the memory.
pub fn read_at_most(reader: impl std::io::Read, most: u64, what: &str) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    reader.take(most + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > most {
        return Err(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!("larger than {}, the most {what} may hold", binary_size(most)),
        ));
    }
    Ok(bytes)
}

/// Reads the regular file at `path` (a link to one is followed) whole, at most `most` bytes
/// ([`read_at_most`]): every read of the store and the report folders goes through here, since
/// another user of a shared folder may plant anything there. A FIFO, a device, a socket or a
/// directory, or a link to one, is refused without being read: opening a FIFO for reading
/// blocks until a writer comes, and a device may never end. Its type is checked before it is
/// opened (so no device is opened at all), and again on the opened handle, which was opened
/// with `O_NONBLOCK` (POSIX: an open of a FIFO for reading then returns at once) in case the
/// name was swapped in between; on a regular file `O_NONBLOCK` changes nothing.
pub fn read_regular(path: &Path, most: u64, what: &str) -> std::io::Result<Vec<u8>> {
    refuse_unless_regular(&std::fs::metadata(path)?)?;
    let file = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path)?;
    refuse_unless_regular(&file.metadata()?)?;
    read_at_most(file, most, what)
}

/// An error naming what `metadata` describes unless it is a regular file.
fn refuse_unless_regular(metadata: &std::fs::Metadata) -> std::io::Result<()> {
    use std::os::unix::fs::FileTypeExt;
    let kind = metadata.file_type();
    let what = match () {
        _ if kind.is_file() => return Ok(()),
        _ if kind.is_fifo() => "a FIFO",
        _ if kind.is_char_device() => "a character device",
        _ if kind.is_block_device() => "a block device",
        _ if kind.is_socket() => "a socket",
        _ if kind.is_dir() => "a directory",
        _ => "not a file",
    };
    Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, format!("{what}, not a regular file")))
}

/// `bytes`, and in MiB or KiB when it is a whole number of them.
fn binary_size(bytes: u64) -> String {
    match bytes {
        b if b >= 1 << 20 && b % (1 << 20) == 0 => format!("{b} bytes ({} MiB)", b >> 20),
        b if b >= 1 << 10 && b % (1 << 10) == 0 => format!("{b} bytes ({} KiB)", b >> 10),
        b => format!("{b} bytes"),
    }
}

/// `text` as it may be printed to a terminal: control characters (escape, bell, line breaks,
/// the C1 set) and the bidirectional overrides shown escaped (`\u{1b}`, `\n`). Text read from
/// the store or a shared folder (a record's build, why a record is corrupt, a folder's owner)
/// could otherwise retitle the window, move the cursor, clear the screen or reorder what it
/// shows. Every such text printed to stdout or stderr goes through here.
pub fn escape_for_terminal(text: &str) -> std::borrow::Cow<'_, str> {
    let hostile = |c: char| c.is_control() || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}');
    if !text.chars().any(hostile) {
        return text.into();
    }
    let mut shown = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if hostile(c) {
            shown.extend(c.escape_default());
        } else {
            shown.push(c);
        }
    }
    shown.into()
}

/// Creates `path`, failing if anything (a symbolic link included) is there already.
fn create_exclusive(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::OpenOptions::new().write(true).create_new(true).custom_flags(libc::O_NOFOLLOW).open(path)
}

/// Numbers the temporaries of this process.
pub static TEMPORARIES: AtomicU64 = AtomicU64::new(0);

/// `.<name>.<host>.<pid>.<n>.tmp`: unique among the threads and processes of all hosts that
/// share the folder, hidden, and telling `sweep_temporaries` whose it is.
fn temporary_name(name: &str) -> String {
    let n = TEMPORARIES.fetch_add(1, Ordering::Relaxed);
    format!(".{name}.{}.{}.{n}.tmp", host_name(), std::process::id())
}

/// This machine's name with dots replaced (they separate the fields of a temporary's name).
pub fn host_name() -> String {
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let name: String =
        name.trim().chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect();
    if name.is_empty() { "host".into() } else { name }
}

/// Removes the temporaries that processes of this host left when they were killed mid-write
/// (`.<name>.<host>.<pid>.<n>.tmp` whose process no longer exists), in the campaign's folder
/// and its subfolders, and the fixed-name `<run_id>.gif.tmp` of earlier versions. A live
/// process's temporary is never touched: its pid is alive; another host's is left alone (its
/// pids cannot be checked here). Returns how many were removed.
pub fn sweep_temporaries(layout: &Layout) -> usize {
    let (host, processes) = (host_name(), Path::new("/proc"));
    if !processes.join("self").exists() {
        return 0; // no /proc: whether a process lives cannot be told
    }
    let mut dirs = vec![layout.root.clone()];
    if let Ok(entries) = std::fs::read_dir(&layout.root) {
        dirs.extend(entries.flatten().filter(|e| e.file_type().is_ok_and(|t| t.is_dir())).map(|e| e.path()));
    }
    let mut removed = 0;
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().to_string();
            let abandoned = match name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) {
                Some(stem) => {
                    let mut fields = stem.rsplitn(4, '.');
                    let (_, pid, owner) = (fields.next(), fields.next(), fields.next());
                    owner == Some(host.as_str())
                        && pid.is_some_and(|pid| pid.parse::<u32>().is_ok() && !processes.join(pid).exists())
                }
                None => name.ends_with(".gif.tmp"),
            };
            if abandoned && entry.file_type().is_ok_and(|t| !t.is_dir()) && std::fs::remove_file(entry.path()).is_ok() {
                removed += 1;
            }
        }
    }
    removed
}

/// Opens (creating it) the lock file at `path`. A symbolic link there is refused (O_NOFOLLOW):
/// locking must never create or open a file elsewhere.
pub fn open_lock_file(path: &Path) -> anyhow::Result<std::fs::File> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create directory '{}'", dir.display()))?;
    }
    std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .custom_flags(libc::O_NOFOLLOW)
        .open(path)
        .with_context(|| {
            let link = if path.is_symlink() { " (it is a symbolic link: remove it)" } else { "" };
            format!("cannot open the lock file '{}'{link}", path.display())
        })
}

/// Takes the OS lock on `file` if no other process holds it: `Ok(false)` when one does.
pub fn try_lock(file: &std::fs::File, path: &Path) -> anyhow::Result<bool> {
    match file.try_lock() {
        Ok(()) => Ok(true),
        Err(std::fs::TryLockError::WouldBlock) => Ok(false),
        Err(std::fs::TryLockError::Error(error)) => {
            Err(error).with_context(|| format!("cannot lock '{}'", path.display()))
        }
    }
}

/// Takes the OS lock on `file` (at `path`, guarding `what`), waiting while another process
/// holds it: says on stderr what it waits for, and gives up with an error after `patience`.
pub fn wait_for_lock(file: &std::fs::File, path: &Path, what: &str, patience: Duration) -> anyhow::Result<()> {
    if try_lock(file, path)? {
        return Ok(());
    }
    eprintln!(
        "waiting for {what}: another mdsolids process holds its lock file '{}' (giving up after {} s; --lock-wait)",
        path.display(),
        patience.as_secs_f64()
    );
    let started = Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(50));
        if try_lock(file, path)? {
            return Ok(());
        }
        anyhow::ensure!(
            started.elapsed() < patience,
            "gave up waiting for {what} after {} s: another mdsolids process (suspended, or still working) holds \
             its lock file '{}'; rerun when it has finished, or wait longer with --lock-wait SECONDS",
            patience.as_secs_f64(),
            path.display()
        );
    }
}
