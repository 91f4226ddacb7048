//! What a campaign or scene name may be: names become directory and file names.

/// Longest campaign or scene name. Names become directory and file names (`reports/<name>/`,
/// `runs/<scene>-<hash>.json`, `plots/<scene>-side-by-side.gif`), which file systems cap at
/// 255 bytes.
pub const MAX_NAME_LEN: usize = 100;

/// A campaign or scene name that is safe as a file name: 1 to [`MAX_NAME_LEN`] ASCII letters,
/// digits, `-` and `_`, so never `..`, a path separator or an absolute path.
pub(super) fn is_safe_name(name: &str) -> bool {
    (1..=MAX_NAME_LEN).contains(&name.len()) && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}
