//! Where a campaign's files go, and how they are written: whole or not at all.

use anyhow::Context;
use std::path::{Path, PathBuf};

/// The output tree of one campaign: `<reports>/<campaign>/`.
#[derive(Clone, Debug)]
pub struct Layout {
    /// `<reports>/<campaign>`.
    pub root: PathBuf,
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
    /// The lock file held while run `run_id` is simulated (hidden, beside the records).
    pub fn run_lock_file(&self, run_id: &str) -> PathBuf {
        self.root.join("runs").join(".locks").join(format!("{run_id}.lock"))
    }
    /// The movie of run `run_id`, beside its record.
    pub fn movie_file(&self, run_id: &str) -> PathBuf {
        self.root.join("runs").join(format!("{run_id}.gif"))
    }
    /// The movie of all runs of `scene` side by side.
    pub fn side_by_side_movie(&self, scene: &str) -> PathBuf {
        self.plot_file(&format!("{scene}-side-by-side.gif"))
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
/// so a reader sees the old file or the new one, never half of one.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create directory '{}'", dir.display()))?;
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("output");
    let temporary = dir.join(format!(".{name}.{}.{:?}.tmp", std::process::id(), std::thread::current().id()));
    // Flushed to the disk before the rename, so that after a crash the name holds the whole
    // new file or the old one. A failed write removes its partial temporary file.
    let written = std::fs::File::create(&temporary).and_then(|mut file| {
        std::io::Write::write_all(&mut file, bytes)?;
        file.sync_all()
    });
    if let Err(error) = written {
        let _ = std::fs::remove_file(&temporary);
        return Err(error).with_context(|| format!("cannot write '{}'", temporary.display()));
    }
    if let Err(error) = std::fs::rename(&temporary, path) {
        let _ = std::fs::remove_file(&temporary);
        return Err(error).with_context(|| format!("cannot move '{}' into place", path.display()));
    }
    Ok(())
}
