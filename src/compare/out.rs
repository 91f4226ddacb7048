//! Where a comparison writes: a folder of its own. `--out` is refused where the comparison
//! would overwrite or delete what it did not write: a folder that already holds other files,
//! and any folder inside a campaign's report folder. The comparison marks its folder with a
//! small file listing what it wrote, so that a later comparison into the same folder may
//! replace those files, and remove those it no longer writes, without touching anything else.

use anyhow::Context as _;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::output::{escape_for_terminal, read_regular, write_atomically};

/// The mark of a comparison's folder: the files (relative paths) the last comparison wrote.
pub const MARKER: &str = ".mdsolids-compare";

/// The marker's first line, so that a reader knows what the file is.
const HEADER: &str = "# written by `mdsolids compare`: the files of this folder it wrote, one a line";

/// The marker is a short list; a larger file is not ours.
const MARKER_MOST_BYTES: u64 = 1 << 20;

/// A folder claimed for a comparison, with the files the previous comparison wrote there.
pub(super) struct Out {
    pub(super) dir: PathBuf,
    previous: BTreeSet<String>,
}

/// Claims `dir` for a comparison: refuses a folder inside a campaign's report folder and a
/// folder that holds files no comparison wrote; marks the folder before anything is written,
/// so that a comparison that stops half way leaves a folder the next one may write into.
/// `given`: the user named the folder (otherwise it is --out's default), for the messages.
pub(super) fn claim(dir: &Path, given: bool) -> anyhow::Result<Out> {
    let flag = format!("{}--out '{}'", if given { "" } else { "the default " }, dir.display());
    refuse_inside_campaign(dir, &flag)?;
    let previous = previous_output(dir, &flag)?;
    write_marker(dir, &previous)?;
    Ok(Out { dir: dir.to_path_buf(), previous })
}

/// `dir` or a folder above it is a campaign's report folder: a comparison there would mix its
/// files with the campaign's, which `mdsolids report` rewrites and removes as its own.
fn refuse_inside_campaign(dir: &Path, flag: &str) -> anyhow::Result<()> {
    let resolved = resolved(dir)?;
    for folder in resolved.ancestors() {
        if let Some(owner) = crate::owner::campaign_of(folder) {
            let place = if folder == resolved { "is" } else { "is inside" };
            anyhow::bail!(
                "{flag} {place} the report folder of {owner} ('{}'): a comparison there would overwrite or mix \
                 with its report; --out must be a new folder, an empty one, or the folder of an earlier comparison, \
                 outside every campaign's report folder",
                folder.display()
            );
        }
    }
    Ok(())
}

/// `dir` made absolute with its links and `..` resolved as far as it exists (the rest may be
/// created), so that a folder inside a campaign is recognised by whatever path names it.
fn resolved(dir: &Path) -> anyhow::Result<PathBuf> {
    let absolute = std::path::absolute(dir).with_context(|| format!("cannot resolve --out '{}'", dir.display()))?;
    let mut existing = absolute.as_path();
    let mut rest = Vec::new();
    while let Err(error) = std::fs::canonicalize(existing) {
        match (error.kind(), existing.parent(), existing.file_name()) {
            (std::io::ErrorKind::NotFound, Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                existing = parent;
            }
            _ => return Err(error).with_context(|| format!("cannot resolve --out '{}'", dir.display())),
        }
    }
    let mut path = std::fs::canonicalize(existing)?;
    path.extend(rest.iter().rev());
    Ok(path)
}

/// The files an earlier comparison wrote into `dir` (none for a new or empty folder); refuses a
/// folder that holds anything else without the comparison's marker.
fn previous_output(dir: &Path, flag: &str) -> anyhow::Result<BTreeSet<String>> {
    let entries = match std::fs::read_dir(dir) {
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeSet::new()),
        other => other.with_context(|| format!("{flag} is not a folder that can be read"))?,
    };
    let mut names: Vec<String> =
        entries.map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned())).collect::<Result<_, _>>()?;
    if names.iter().any(|n| n == MARKER) {
        let marker = read_regular(&dir.join(MARKER), MARKER_MOST_BYTES, "a comparison's marker")
            .with_context(|| format!("cannot read '{}'", dir.join(MARKER).display()))?;
        let listed = String::from_utf8_lossy(&marker);
        return Ok(listed.lines().filter(|l| !l.starts_with('#') && !l.is_empty()).map(str::to_string).collect());
    }
    names.sort();
    anyhow::ensure!(
        names.is_empty(),
        "{flag} already holds files not listed as written by `mdsolids compare` ({}; a comparison of an earlier \
         version lists none: delete its folder): they would be overwritten or \
         removed. --out must be a new folder, an empty one, or the folder of an earlier comparison (marked by its \
         '{MARKER}')",
        escape_for_terminal(&listed(&names))
    );
    Ok(BTreeSet::new())
}

/// The first few of `names`, and how many more.
fn listed(names: &[String]) -> String {
    const SHOWN: usize = 5;
    let mut words: Vec<String> = names.iter().take(SHOWN).cloned().collect();
    if names.len() > SHOWN {
        words.push(format!("and {} more", names.len() - SHOWN));
    }
    words.join(", ")
}

fn write_marker(dir: &Path, files: &BTreeSet<String>) -> anyhow::Result<()> {
    let lines: Vec<&str> = std::iter::once(HEADER).chain(files.iter().map(String::as_str)).collect();
    write_atomically(&dir.join(MARKER), format!("{}\n", lines.join("\n")).as_bytes())
}

impl Out {
    /// Records `written` (paths relative to the folder) as the comparison's files and removes
    /// those the previous comparison wrote that this one did not (the figures of quantities that
    /// no longer differ): only files listed as the comparison's are ever removed.
    pub(super) fn finish(&self, written: &BTreeSet<String>) -> anyhow::Result<()> {
        write_marker(&self.dir, &self.previous.union(written).cloned().collect())?;
        for stale in self.previous.difference(written).filter(|f| is_own_name(f)) {
            let path = self.dir.join(stale);
            match std::fs::remove_file(&path) {
                Err(error) if error.kind() != std::io::ErrorKind::NotFound => {
                    return Err(error).with_context(|| format!("cannot remove the stale '{}'", path.display()));
                }
                _ => {}
            }
        }
        write_marker(&self.dir, written)
    }
}

/// A listed name the comparison could have written: a path below its folder (a marker edited
/// to name `../x` or `/x` removes nothing outside it).
fn is_own_name(name: &str) -> bool {
    !name.starts_with('/') && name.split('/').all(|part| !part.is_empty() && part != ".." && part != ".")
}
