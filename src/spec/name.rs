//! What a campaign or scene name may be: names become directory and file names.

use serde::Deserialize;
use serde_json::Value;

use super::raw::RawCampaign;

/// Longest campaign or scene name. Names become directory and file names (`reports/<name>/`,
/// `runs/<scene>-<hash>.json`, `plots/<scene>-side-by-side.gif`), which file systems cap at
/// 255 bytes.
pub const MAX_NAME_LEN: usize = 100;

/// A campaign or scene name that is safe as a file name: 1 to [`MAX_NAME_LEN`] ASCII letters,
/// digits, `-` and `_`, so never `..`, a path separator or an absolute path.
pub(super) fn is_safe_name(name: &str) -> bool {
    (1..=MAX_NAME_LEN).contains(&name.len()) && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// The names of a campaign as a YAML value reads them: there an unquoted `y`, `no` or `on` is a
/// boolean, as it is to every YAML 1.1 reader.
#[derive(Deserialize)]
struct Names {
    name: Value,
    #[serde(default)]
    scenes: Vec<SceneName>,
}

#[derive(Deserialize)]
struct SceneName {
    #[serde(default)]
    name: Value,
}

/// Why the campaign's `name:` or a scene's is refused when it is a word YAML reads as a boolean
/// unless quoted (`y`, `n`, `yes`, `no`, `on`, `off`, `true`, `false`): serde-saphyr hands the
/// string field the word, but other readers of the same file see true or false.
pub(super) fn read_as_boolean(text: &str, raw: &RawCampaign) -> Option<String> {
    let names: Names = serde_saphyr::from_str(text).ok()?;
    let scenes = names.scenes.iter().zip(&raw.scenes).enumerate();
    let scenes = scenes.map(|(i, (read, raw))| (format!("scenes[{i}].name"), &read.name, raw.name.as_deref()));
    let (field, read, word) = std::iter::once(("name".to_string(), &names.name, Some(raw.name.as_str())))
        .chain(scenes)
        .find(|(_, read, _)| read.is_boolean())?;
    let word = word.unwrap_or_default();
    Some(format!(
        "{field} = {word}: YAML reads an unquoted {word} as the boolean {read}, not as a name (so do y, n, yes, no, \
         on and off); quote it: name: \"{word}\""
    ))
}
