//! The images a report page shows, read back from its folder when the page is written: each
//! one's size in pixels, which the page writes as the `<img>`'s `width` and `height` (the
//! browser keeps the image's place before it loads: nothing below it moves), and for each movie
//! (an animated GIF) its filmstrip for print (`draw::filmstrip`), written beside it as
//! `<name>.filmstrip.png`.

use std::collections::HashMap;
use std::path::Path;

use crate::draw::filmstrip::filmstrip;
use crate::output::{read_regular, write_atomically};

/// What a page knows of one image it shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shown {
    /// Width and height in pixels, when the file could be read.
    pub size: Option<(u32, u32)>,
    /// A movie's frames on paper.
    pub filmstrip: Option<Strip>,
}

/// A movie's filmstrip: its file (relative to the page), size in pixels and what it shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Strip {
    /// Its path, relative to the page.
    pub file: String,
    /// Width and height (pixels).
    pub size: (u32, u32),
    /// Which frames it shows, in words.
    pub caption: String,
}

/// Larger image files are not read (bytes): a report's largest movie is a few MB.
const MOST_BYTES: u64 = 64 << 20;

/// The images `sources` (as the page links them, relative to `dir`) read from `dir`: sizes,
/// and each GIF's filmstrip, written. An image that cannot be read (missing, not ours: an
/// absolute path, a URL, a `..`) is left out and shown without a size; a GIF that cannot be
/// decoded has no strip and prints its first frame.
pub fn shown<'a>(dir: &Path, sources: impl IntoIterator<Item = &'a str>) -> anyhow::Result<HashMap<String, Shown>> {
    let mut found = HashMap::new();
    for source in sources {
        if found.contains_key(source) || !inside(source) {
            continue;
        }
        let Ok(bytes) = read_regular(&dir.join(source), MOST_BYTES, source) else { continue };
        let mut image = Shown { size: size_of(&bytes), filmstrip: None };
        if source.ends_with(".gif")
            && let Ok(strip) = filmstrip(&bytes)
        {
            let file = strip_name(source);
            write_atomically(&dir.join(&file), &strip.png)?;
            let frames: Vec<String> = strip.shown.iter().map(usize::to_string).collect();
            let caption = format!("frames {} of {} of the movie", frames.join(", "), strip.frames);
            image.filmstrip = Some(Strip { file, size: strip.size, caption });
        }
        found.insert(source.to_string(), image);
    }
    Ok(found)
}

/// Whether `source` is a path below the page's folder.
fn inside(source: &str) -> bool {
    !source.is_empty()
        && !source.starts_with('/')
        && !source.contains(':')
        && source.split('/').all(|part| !part.is_empty() && part != "..")
}

/// `plots/x.gif` → `plots/x.filmstrip.png`.
pub fn strip_name(source: &str) -> String {
    format!("{}.filmstrip.png", source.strip_suffix(".gif").unwrap_or(source))
}

/// The width and height in pixels of a PNG, GIF or SVG (the root's `width` and `height`).
pub fn size_of(bytes: &[u8]) -> Option<(u32, u32)> {
    let be = |at: usize| Some(u32::from_be_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    let le = |at: usize| Some(u16::from_le_bytes(bytes.get(at..at + 2)?.try_into().ok()?) as u32);
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Some((be(16)?, be(20)?));
    }
    if bytes.starts_with(b"GIF8") {
        return Some((le(6)?, le(8)?));
    }
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
    let tag = &text[text.find("<svg")?..];
    let tag = &tag[..tag.find('>')?];
    let attribute = |name: &str| -> Option<u32> {
        let value = &tag[tag.find(&format!(" {name}=\""))? + name.len() + 3..];
        let value = value[..value.find('"')?].trim_end_matches("px");
        value.parse::<f64>().ok().filter(|v| *v > 0.0).map(|v| v.round() as u32)
    };
    Some((attribute("width")?, attribute("height")?))
}
