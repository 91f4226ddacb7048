//! Which campaign file a report folder belongs to. Two campaign files with the same `name:`
//! would write the same `reports/<name>/`, each overwriting the other's tables and reports. So
//! the first command that writes there records the campaign file in `campaign.json`, and every
//! later `run`, `report` or `slurm` of another file is refused (or, with `--force`, takes the
//! folder over). A campaign file is identified by its canonical path: editing the file keeps the
//! folder, moving it or copying it elsewhere is another campaign.

use anyhow::Context;
use serde::{Deserialize, Serialize};
use std::path::Path;

use crate::output::{Layout, escape_for_terminal, read_regular, write_atomically};

/// The marker in a campaign's folder naming the campaign file that owns it.
pub const MARKER: &str = "campaign.json";

/// The most bytes of [`MARKER`] read: a name and a path (at most 4096 bytes on Linux) in JSON.
const MARKER_MOST_BYTES: u64 = 64 << 10;

/// What [`MARKER`] holds.
#[derive(Debug, Serialize, Deserialize)]
struct Owner {
    /// The campaign's name (the folder's).
    name: String,
    /// Canonical path of the campaign file.
    campaign_file: String,
}

/// The identity of a campaign file: its canonical path, or its absolute path where it cannot be
/// resolved (a pipe such as `/dev/stdin`).
pub fn identity(file: &Path) -> anyhow::Result<String> {
    let path = std::fs::canonicalize(file)
        .or_else(|_| std::path::absolute(file))
        .with_context(|| format!("cannot resolve the campaign file '{}'", file.display()))?;
    Ok(path.to_string_lossy().into_owned())
}

/// Makes `layout`'s folder the campaign file `file`'s. Refuses a folder that another campaign
/// file owns (unless `force`, which records `file` instead) or that holds a comparison.
pub fn claim(layout: &Layout, file: &Path, force: bool) -> anyhow::Result<()> {
    let name = layout.root.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let me = Owner { name, campaign_file: identity(file)? };
    let marker = layout.file(MARKER);
    let json = serde_json::to_vec_pretty(&me).context("cannot serialise the folder's owner")?;
    if force {
        return write_atomically(&marker, &json);
    }
    // Twice at most: a first claim that loses the race to create the marker reads the winner's.
    for _ in 0..2 {
        match read_owner(&marker)? {
            Some(owner) if owner.campaign_file == me.campaign_file => return Ok(()),
            Some(owner) => anyhow::bail!(
                "'{}' belongs to campaign file '{}' (recorded in '{}'), not to '{}': both campaigns are named \
                 '{}' and would overwrite each other's tables, reports and figures. Give this campaign another \
                 `name:`, or pass --force to make the folder this file's (after moving the campaign file, say)",
                layout.root.display(),
                escape_for_terminal(&owner.campaign_file),
                marker.display(),
                me.campaign_file,
                me.name
            ),
            None => {
                anyhow::ensure!(
                    !layout.file("compare.parquet").exists(),
                    "'{}' holds the output of `mdsolids compare`, not a campaign's: give the campaign another \
                     `name:` or use another --reports directory",
                    layout.root.display()
                );
                if create_new(&marker, &json)? {
                    return Ok(());
                }
            }
        }
    }
    anyhow::bail!("'{}' keeps changing while it is claimed; try again", marker.display())
}

/// The owner recorded in `marker`, or `None` when there is no marker.
fn read_owner(marker: &Path) -> anyhow::Result<Option<Owner>> {
    let text = match read_regular(marker, MARKER_MOST_BYTES, "a folder's owner file") {
        Ok(text) => text,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(error) => return Err(error).with_context(|| format!("cannot read '{}'", marker.display())),
    };
    serde_json::from_slice(&text).map(Some).with_context(|| {
        format!(
            "'{}' does not name the campaign file that owns this folder: delete it or pass --force",
            marker.display()
        )
    })
}

/// Writes `bytes` to `path` whole, only if `path` does not exist: written atomically beside it,
/// then hard-linked into place (a link never replaces a file). False when `path` appeared first.
fn create_new(path: &Path, bytes: &[u8]) -> anyhow::Result<bool> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let staged = path.with_file_name(format!(".{name}.{}.new", std::process::id()));
    write_atomically(&staged, bytes)?;
    let linked = std::fs::hard_link(&staged, path);
    let _ = std::fs::remove_file(&staged);
    match linked {
        Ok(()) => Ok(true),
        Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
        Err(error) => Err(error).with_context(|| format!("cannot create '{}'", path.display())),
    }
}

/// The campaign file that owns the folder `dir`, if a campaign has written there: read from its
/// marker, or "a campaign" for a folder with a run store but no marker (written before markers).
pub fn campaign_of(dir: &Path) -> Option<String> {
    match read_owner(&dir.join(MARKER)) {
        Ok(Some(owner)) => Some(format!("campaign file '{}'", escape_for_terminal(&owner.campaign_file))),
        Ok(None) if !dir.join("runs").is_dir() => None,
        _ => Some("a campaign".into()),
    }
}
