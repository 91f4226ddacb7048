//! Markdown → HTML of the report pages (`index.html` of a campaign and of `mdsolids compare`):
//! LaTeX math as MathML (no JavaScript, no network), an `id` on every heading and a contents
//! list, numbered figures with their captions, tables that scroll inside their own box, images
//! loaded lazily. `report.md` keeps the Markdown as the template wrote it (math stays `$…$`),
//! with the same figure numbers in its captions and the contents list as links where the
//! template asks for it.
//!
//! What a template writes:
//! - math in LaTeX, `$…$` inline and `$$…$$` displayed; LaTeX the renderer cannot read shows as
//!   its code text, and the page is written all the same;
//! - a line [`CONTENTS_MARKER`] where the contents list goes (h2 sections with their h3 nested,
//!   leaving out the headings that a link above the list already leads to, such as the
//!   sections a summary table links); without one, `index.html` gets the list before the first
//!   h2 and `report.md` none;
//! - a figure as a paragraph holding only an image (or a link around one) followed by an italic
//!   paragraph, its caption: both pages number it, the caption starting "Figure N: " (in
//!   `index.html` inside a `<figure id="figure-N">`), nothing to count.
//! - a line [`APPENDIX_MARKER`] where the appendix starts: `index.html` ends there with a link to
//!   `appendix.html`, which holds the rest ([`split_appendix`]); `report.md` stays one document.
//!
//! Every `<img>` gets its `width` and `height` from [`images::shown`](super::images::shown), a
//! movie its filmstrip (an `<img class="filmstrip">` the page's print style shows in its place),
//! and a table without rows is not written.

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use pulldown_cmark::{CowStr, Event, HeadingLevel, Options, Parser, Tag, TagEnd};
use pulldown_cmark_escape::{escape_href, escape_html};

use super::images::Shown;

/// The line (alone on it) where a template wants the contents list: an HTML comment, so
/// Markdown viewers show nothing of it when no list follows.
pub const CONTENTS_MARKER: &str = "<!-- contents -->";

/// The line (alone on it) where the appendix starts: an HTML comment, invisible in `report.md`.
pub const APPENDIX_MARKER: &str = "<!-- appendix -->";

/// The page a report opens on.
pub const MAIN_PAGE: &str = "index.html";
/// The page a report's appendix is written to.
pub const APPENDIX_PAGE: &str = "appendix.html";

/// GitHub's tables, and `$…$` / `$$…$$` read as math, not text.
const OPTIONS: Options = Options::ENABLE_TABLES.union(Options::ENABLE_MATH);

/// A heading: level, its Markdown source as written (the contents list's link text) and the id
/// it gets on the page.
struct Heading {
    level: HeadingLevel,
    source: String,
    id: String,
}

/// The id of a heading whose text is `text`, as GitHub makes it: lower case, letters, digits,
/// `-` and `_` kept, spaces as `-`, everything else dropped (for ASCII headings the same
/// anchors as GitHub's view of `report.md`).
pub fn slug(text: &str) -> String {
    let slug: String = text
        .trim()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            '-' | '_' => Some(c),
            c if c.is_alphanumeric() => Some(c),
            _ => None,
        })
        .flat_map(char::to_lowercase)
        .collect();
    if slug.is_empty() { "section".into() } else { slug }
}

/// `base`, or `base-1`, `base-2`, … (GitHub's suffixes), the first not in `used`, now used.
fn unique(base: String, used: &mut HashSet<String>) -> String {
    let id = (0..).map(|n| if n == 0 { base.clone() } else { format!("{base}-{n}") }).find(|id| !used.contains(id));
    let id = id.expect("some suffix is free");
    used.insert(id.clone());
    id
}

/// The headings of `markdown` in order, each with a unique id.
fn headings(markdown: &str) -> Vec<Heading> {
    let mut found = Vec::new();
    let mut used = HashSet::new();
    // (level, text for the slug, source range of the inline content)
    let mut open: Option<(HeadingLevel, String, Option<Range<usize>>)> = None;
    for (event, range) in Parser::new_ext(markdown, OPTIONS).into_offset_iter() {
        match event {
            Event::Start(Tag::Heading { level, .. }) => open = Some((level, String::new(), None)),
            Event::End(TagEnd::Heading(_)) => {
                if let Some((level, text, source)) = open.take() {
                    let source = source.map_or(String::new(), |r| markdown[r].trim().to_string());
                    found.push(Heading { level, source, id: unique(slug(&text), &mut used) });
                }
            }
            event => {
                if let Some((_, text, source)) = open.as_mut() {
                    if let Event::Text(t) | Event::Code(t) | Event::InlineMath(t) = &event {
                        text.push_str(t);
                    }
                    *source = Some(source.as_ref().map_or(range.clone(), |s| s.start..range.end));
                }
            }
        }
    }
    found
}

/// The contents list of `headings` in Markdown: the h2 sections linked by id, their h3 nested,
/// except the headings whose ids are in `listed` (linked already above the list).
fn contents_list(headings: &[Heading], listed: &HashSet<String>) -> String {
    let mut list = String::from("**Contents**\n\n");
    for heading in headings.iter().filter(|h| !listed.contains(&h.id)) {
        let indent = match heading.level {
            HeadingLevel::H2 => "",
            HeadingLevel::H3 => "  ",
            _ => continue,
        };
        list.push_str(&format!("{indent}- [{}](#{})\n", heading.source, heading.id));
    }
    list
}

/// The ids that links in `markdown[..end]` lead to (`#id`, as the page's ids: percent escapes
/// of non-ASCII letters decoded).
fn linked_ids(markdown: &str, end: usize) -> HashSet<String> {
    Parser::new_ext(markdown, OPTIONS)
        .into_offset_iter()
        .take_while(|(_, range)| range.start < end)
        .filter_map(|(event, _)| match event {
            Event::Start(Tag::Link { dest_url, .. }) => dest_url.strip_prefix('#').map(percent_decoded),
            _ => None,
        })
        .collect()
}

/// `text` with its `%XX` escapes decoded, as a browser reads a link's fragment.
pub fn percent_decoded(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let escape = (bytes[i] == b'%').then(|| text.get(i + 1..i + 3)).flatten();
        match escape.and_then(|hex| u8::from_str_radix(hex, 16).ok()) {
            Some(byte) => {
                out.push(byte);
                i += 3;
            }
            None => {
                out.push(bytes[i]);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// `markdown` with the contents list after the [`CONTENTS_MARKER`] line; without that line,
/// unchanged, or (`before_first_section`) with the marker and list put before the first h2.
fn place_contents(markdown: &str, before_first_section: bool) -> String {
    let headings = headings(markdown);
    let marker_line = markdown.split_inclusive('\n').scan(0, |at, line| {
        let start = *at;
        *at += line.len();
        Some((start, line))
    });
    if let Some((start, line)) = marker_line.into_iter().find(|(_, line)| line.trim() == CONTENTS_MARKER) {
        let list = contents_list(&headings, &linked_ids(markdown, start));
        let rest = &markdown[start + line.len()..];
        let gap = if rest.starts_with('\n') { "" } else { "\n" };
        return format!("{}{CONTENTS_MARKER}\n\n{list}{gap}{rest}", &markdown[..start]);
    }
    let first_section = Parser::new_ext(markdown, OPTIONS).into_offset_iter().find_map(|(event, range)| {
        matches!(event, Event::Start(Tag::Heading { level: HeadingLevel::H2, .. })).then_some(range.start)
    });
    match first_section {
        Some(at) if before_first_section => {
            let list = contents_list(&headings, &linked_ids(markdown, at));
            format!("{}{CONTENTS_MARKER}\n\n{list}\n{}", &markdown[..at], &markdown[at..])
        }
        _ => markdown.to_string(),
    }
}

/// `markdown` as written to `report.md`: its figures' captions numbered ("Figure N: "), the
/// contents list (Markdown links to the headings' anchors) after the [`CONTENTS_MARKER`] line,
/// if the template wrote one.
pub fn with_contents(markdown: &str) -> String {
    place_contents(&number_captions(markdown), false)
}

/// `markdown` as the HTML body of `index.html` (see the module's documentation): numbered as in
/// [`with_contents`], its images sized by `images` (keyed by their source as written).
pub fn to_html(markdown: &str, images: &HashMap<String, Shown>) -> String {
    let markdown = place_contents(&number_captions(markdown), true);
    let events = figure_elements(without_empty_tables(Parser::new_ext(&markdown, OPTIONS).collect()));
    let mut ids = headings(&markdown).into_iter().map(|h| h.id);
    let mut out = Vec::with_capacity(events.len());
    let mut nav: Option<usize> = None; // open lists inside the contents' <nav>
    let mut image: Option<(CowStr, CowStr, String)> = None; // src, title, alt text so far
    for event in events {
        if let Some((_, _, alt)) = image.as_mut() {
            match event {
                Event::End(TagEnd::Image) => {
                    let (src, title, alt) = image.take().expect("an image is open");
                    out.push(Event::InlineHtml(img(&src, &title, &alt, images.get(src.as_ref())).into()));
                }
                Event::Text(t) | Event::Code(t) | Event::InlineMath(t) | Event::DisplayMath(t) => alt.push_str(&t),
                _ => {}
            }
            continue;
        }
        match event {
            Event::Start(Tag::Image { dest_url, title, .. }) => image = Some((dest_url, title, String::new())),
            Event::Start(Tag::Heading { level, classes, attrs, .. }) => {
                out.push(Event::Start(Tag::Heading { level, id: ids.next().map(CowStr::from), classes, attrs }))
            }
            Event::Html(text) if text.trim() == CONTENTS_MARKER => {
                nav = Some(0);
                out.push(Event::Html("<nav class=\"contents\" aria-label=\"Contents\">\n".into()));
            }
            Event::Start(Tag::List(start)) => {
                nav = nav.map(|open| open + 1);
                out.push(Event::Start(Tag::List(start)));
            }
            Event::End(TagEnd::List(ordered)) => {
                out.push(Event::End(TagEnd::List(ordered)));
                nav = nav.map(|open| open - 1);
                if nav == Some(0) {
                    out.push(Event::Html("</nav>\n".into()));
                    nav = None;
                }
            }
            Event::Start(Tag::Table(alignments)) => {
                out.push(Event::Html("<div class=\"table-wrap\">\n".into()));
                out.push(Event::Start(Tag::Table(alignments)));
            }
            Event::End(TagEnd::Table) => {
                out.push(Event::End(TagEnd::Table));
                out.push(Event::Html("</div>\n".into()));
            }
            Event::InlineMath(latex) => out.push(Event::InlineHtml(math(&latex, false).into())),
            Event::DisplayMath(latex) => out.push(Event::InlineHtml(math(&latex, true).into())),
            event => out.push(event),
        }
    }
    let mut body = String::new();
    pulldown_cmark::html::push_html(&mut body, out.into_iter());
    body
}

/// An `<img>` loaded when it comes near the window (the page shows dozens of figures), with its
/// size where `shown` knows it; a movie with a filmstrip is followed by the strip, which only
/// print shows (`.filmstrip` in the page's style) and the screen leaves out (`.movie` there).
fn img(src: &str, title: &str, alt: &str, shown: Option<&Shown>) -> String {
    let strip = shown.and_then(|s| s.filmstrip.as_ref());
    let mut html = tag(src, alt, shown.and_then(|s| s.size), strip.map(|_| "movie"));
    if !title.is_empty() {
        html.insert_str(html.len() - 1, &attribute("title", title));
    }
    if let Some(strip) = strip {
        html.push_str(&tag(&strip.file, &format!("{alt} ({})", strip.caption), Some(strip.size), Some("filmstrip")));
    }
    html
}

/// `<img src alt [width height] [class] loading="lazy">`, every value escaped.
fn tag(src: &str, alt: &str, size: Option<(u32, u32)>, class: Option<&str>) -> String {
    let mut html = String::from("<img src=\"");
    escape_href(&mut html, src).expect("writing to a String cannot fail");
    html.push('"');
    html.push_str(&attribute("alt", alt));
    if let Some((width, height)) = size {
        html.push_str(&format!(" width=\"{width}\" height=\"{height}\""));
    }
    if let Some(class) = class {
        html.push_str(&attribute("class", class));
    }
    html.push_str(" loading=\"lazy\">");
    html
}

/// ` name="value"`, the value escaped for HTML.
fn attribute(name: &str, value: &str) -> String {
    let mut html = format!(" {name}=\"");
    escape_html(&mut html, value).expect("writing to a String cannot fail");
    html.push('"');
    html
}

/// `events` without the tables that have no rows below their header (a table the data left
/// empty says nothing, and a reader would look for what is missing).
fn without_empty_tables(events: Vec<Event>) -> Vec<Event> {
    let mut out = Vec::with_capacity(events.len());
    let mut table: Option<(usize, bool)> = None; // where the open table starts in `out`, has it a row
    for event in events {
        match &event {
            Event::Start(Tag::Table(_)) => table = Some((out.len(), false)),
            Event::Start(Tag::TableRow) => table = table.map(|(start, _)| (start, true)),
            Event::End(TagEnd::Table) => {
                if let Some((start, false)) = table.take() {
                    out.truncate(start);
                    continue;
                }
            }
            _ => {}
        }
        out.push(event);
    }
    out
}

/// The sources of the images `markdown` shows, as written, in order.
pub fn image_sources(markdown: &str) -> Vec<String> {
    Parser::new_ext(markdown, OPTIONS)
        .filter_map(|event| match event {
            Event::Start(Tag::Image { dest_url, .. }) => Some(dest_url.into_string()),
            _ => None,
        })
        .collect()
}

/// `body` (of [`to_html`]) split at the [`APPENDIX_MARKER`]: the main page, ending with a link
/// to `appendix.html`, and the appendix, starting with a link back; each link to a heading or
/// figure on the other page leads there. Without the marker, `body` and no appendix.
pub fn split_appendix(body: &str) -> (String, Option<String>) {
    let Some(at) = body.find(APPENDIX_MARKER) else { return (body.to_string(), None) };
    let (main, appendix) = (&body[..at], &body[at + APPENDIX_MARKER.len()..]);
    let main = linked_across(main, appendix, APPENDIX_PAGE);
    let appendix = linked_across(appendix, main.as_str(), MAIN_PAGE);
    let main = format!(
        "{main}<p class=\"appendix-link\"><strong>Appendix</strong> (the methods, every scene's figures, movies \
         and tables, every run's numbers): <a href=\"{APPENDIX_PAGE}\">{APPENDIX_PAGE}</a>.</p>\n"
    );
    let appendix = format!("<p class=\"back\"><a href=\"{MAIN_PAGE}\">← the report</a></p>\n{appendix}");
    (main, Some(appendix))
}

/// `part` with each `href="#id"` whose id is not in `part` but in `other` pointing to
/// `other_page#id`.
fn linked_across(part: &str, other: &str, other_page: &str) -> String {
    let ids = |html: &str| -> HashSet<String> {
        html.split(" id=\"").skip(1).filter_map(|rest| rest.split('"').next()).map(str::to_string).collect()
    };
    let (mine, theirs) = (ids(part), ids(other));
    let mut out = String::with_capacity(part.len());
    let mut pieces = part.split("href=\"#");
    out.push_str(pieces.next().unwrap_or_default());
    for piece in pieces {
        let id = piece.split('"').next().unwrap_or_default();
        let decoded = percent_decoded(id);
        let elsewhere = !mine.contains(&decoded) && theirs.contains(&decoded);
        out.push_str(if elsewhere { "href=\"" } else { "href=\"#" });
        if elsewhere {
            out.push_str(other_page);
            out.push('#');
        }
        out.push_str(piece);
    }
    out
}

/// LaTeX `latex` as MathML (a block when `display`); LaTeX the renderer cannot read as its code
/// text, marked, so one bad formula costs its own rendering and nothing else.
fn math(latex: &str, display: bool) -> String {
    let storage = pulldown_latex::Storage::new();
    let events: Vec<_> = pulldown_latex::Parser::new(latex, &storage).collect();
    let display_mode =
        if display { pulldown_latex::config::DisplayMode::Block } else { pulldown_latex::config::DisplayMode::Inline };
    let config = pulldown_latex::RenderConfig { display_mode, ..Default::default() };
    let mut mathml = String::new();
    if events.iter().all(Result::is_ok) && pulldown_latex::push_mathml(&mut mathml, events.into_iter(), config).is_ok()
    {
        return mathml;
    }
    let mut code = String::from("<code class=\"math-error\" title=\"LaTeX that could not be rendered\">");
    escape_html(&mut code, latex).expect("writing to a String cannot fail");
    code.push_str("</code>");
    code
}

/// The index of the `End(Paragraph)` closing the paragraph opened at `start`, if one opens there.
fn paragraph_end(events: &[Event], start: usize) -> Option<usize> {
    if !matches!(events.get(start), Some(Event::Start(Tag::Paragraph))) {
        return None;
    }
    (start..events.len()).find(|&i| matches!(events[i], Event::End(TagEnd::Paragraph)))
}

/// Whether `inner` (a paragraph's content) is one image, or one link around one image.
fn only_an_image(inner: &[Event]) -> bool {
    let inner = match inner {
        [Event::Start(Tag::Link { .. }), inside @ .., Event::End(TagEnd::Link)] => inside,
        inner => inner,
    };
    matches!(inner, [Event::Start(Tag::Image { .. }), .., Event::End(TagEnd::Image)])
        && inner.iter().filter(|e| matches!(e, Event::Start(Tag::Image { .. }))).count() == 1
}

/// Whether `inner` (a paragraph's content) is one emphasis from its start to its end.
fn all_emphasis(inner: &[Event]) -> bool {
    let mut depth = 0usize;
    for (i, event) in inner.iter().enumerate() {
        match event {
            Event::Start(Tag::Emphasis) => depth += 1,
            Event::End(TagEnd::Emphasis) => depth -= 1,
            _ if depth == 0 => return false,
            _ => {}
        }
        if depth == 0 && i + 1 < inner.len() {
            return false;
        }
    }
    !inner.is_empty()
}

/// The figures among `events`: for each image paragraph that an italic caption paragraph
/// follows, the index of the image paragraph's start, its end and the caption's end.
fn figures(events: &[Event]) -> Vec<(usize, usize, usize)> {
    let mut found = Vec::new();
    let mut i = 0;
    while i < events.len() {
        let image = paragraph_end(events, i).filter(|&end| only_an_image(&events[i + 1..end]));
        let caption = image.and_then(|end| paragraph_end(events, end + 1).map(|close| (end, close)));
        match caption.filter(|&(end, close)| all_emphasis(&events[end + 2..close])) {
            Some((end, close)) => {
                found.push((i, end, close));
                i = close + 1;
            }
            None => i += 1,
        }
    }
    found
}

/// "Figure N: ", the start of the N-th figure's caption (N from 1).
fn figure_label(n: usize) -> String {
    format!("Figure {n}: ")
}

/// `markdown` with the caption of each figure (`figures`) starting `figure_label`, inside
/// its emphasis: `*Figure 3: The speed …*`.
pub fn number_captions(markdown: &str) -> String {
    let (events, ranges): (Vec<Event>, Vec<Range<usize>>) =
        Parser::new_ext(markdown, OPTIONS).into_offset_iter().unzip();
    let mut out = String::with_capacity(markdown.len());
    let mut copied = 0;
    for (n, (_, end, _)) in figures(&events).into_iter().enumerate() {
        // The caption paragraph starts with its emphasis' delimiter, `*` or `_`.
        let at = ranges[end + 1].start + 1;
        out.push_str(&markdown[copied..at]);
        out.push_str(&figure_label(n + 1));
        copied = at;
    }
    out.push_str(&markdown[copied..]);
    out
}

/// `events` (of captions numbered by [`number_captions`]) with each figure written as a
/// `<figure id="figure-N">` holding its image and a `<figcaption>`, its number set apart.
fn figure_elements(events: Vec<Event>) -> Vec<Event> {
    let mut out = Vec::with_capacity(events.len());
    let mut copied = 0;
    for (n, (start, end, close)) in figures(&events).into_iter().enumerate() {
        let number = n + 1;
        out.extend(events[copied..start].iter().cloned());
        out.push(Event::Html(format!("<figure id=\"figure-{number}\">\n").into()));
        out.extend(events[start + 1..end].iter().cloned());
        out.push(Event::Html("\n<figcaption>".into()));
        // The caption inside its emphasis; its number as a span of its own.
        let mut caption = events[end + 3..close - 1].iter().cloned();
        let label = figure_label(number);
        match caption.next() {
            Some(Event::Text(text)) if text.starts_with(&label) => {
                out.push(Event::Html(format!("<span class=\"figure-number\">{}</span> ", label.trim_end()).into()));
                out.push(Event::Text(text[label.len()..].to_string().into()));
            }
            Some(other) => out.push(other),
            None => {}
        }
        out.extend(caption);
        out.push(Event::Html("</figcaption>\n</figure>\n".into()));
        copied = close + 1;
    }
    out.extend(events[copied..].iter().cloned());
    out
}
