//! Text from campaign files, run records and results tables, made inert in the Markdown reports.
//!
//! The Markdown templates are rendered by a tera instance whose autoescape writes every
//! `{{ value }}` through [`escape_inline`]: the value shows as the text it is, in running text, a
//! heading or a table cell, and can open no HTML tag, link, emphasis, code span or new table
//! column (pulldown-cmark passes raw HTML in Markdown straight into `index.html`, so escaping
//! has to happen where the text enters the Markdown). Two filters cover the other places text
//! goes: `code` writes a whole code span, `paragraphs` free text of several paragraphs.

use std::io::Write;

/// Characters with a meaning in inline Markdown (CommonMark and GitHub tables), written with a
/// backslash: HTML and autolinks (`<`, `>`), entities (`&`), code spans, emphasis, links and
/// images, table cells (`|`), headings' closing `#`, strikethrough, math (`$`, which `index.html`
/// renders as LaTeX) and the backslash itself. `_` is escaped only where it could open or close
/// emphasis (see [`escape_inline`]).
const INLINE_SPECIAL: &[char] = &['\\', '`', '*', '[', ']', '<', '>', '|', '&', '#', '~', '$'];

/// tera's escape function for the Markdown templates: `text` as literal inline Markdown on one
/// line. Control characters (line breaks included) become spaces, so a value cannot end a table
/// row or start a block. An `_` between two letters or digits is left alone: CommonMark lets it
/// neither open nor close emphasis, and `k_d/k`, `no_equilibrium` stay readable in `report.md`.
pub fn escape_inline(text: &str, out: &mut dyn Write) -> std::io::Result<()> {
    let chars: Vec<char> = text.chars().collect();
    let mut buffer = String::with_capacity(text.len() + 8);
    for (i, &c) in chars.iter().enumerate() {
        let word = |j: Option<usize>| j.and_then(|j| chars.get(j)).is_some_and(|c| c.is_alphanumeric());
        if c.is_control() {
            buffer.push(' ');
        } else if INLINE_SPECIAL.contains(&c) || (c == '_' && !(word(i.checked_sub(1)) && word(Some(i + 1)))) {
            buffer.push('\\');
            buffer.push(c);
        } else {
            buffer.push(c);
        }
    }
    out.write_all(buffer.as_bytes())
}

/// `text` as inline Markdown ([`escape_inline`]) in a `String`.
pub fn inline(text: &str) -> String {
    let mut out = Vec::new();
    escape_inline(text, &mut out).expect("writing to a Vec cannot fail");
    String::from_utf8(out).expect("escaping keeps UTF-8")
}

/// `text` as one code span, shown verbatim: fenced by one backtick more than its longest run of
/// backticks (padded with a space where it starts or ends with one, which CommonMark strips) and
/// control characters as spaces. In a table cell (`in_cell`) a `|` is written `\|`: a GitHub
/// table splits cells before it finds code spans, and pulldown-cmark drops that backslash again;
/// outside a table the backslash would show, so there `|` stays as it is.
pub fn code(text: &str, in_cell: bool) -> String {
    let mut text: String = text.chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
    if in_cell {
        text = text.replace('|', "\\|");
    }
    let longest = text.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    let fence = "`".repeat(longest + 1);
    let pad = if text.starts_with('`') || text.ends_with('`') || text.is_empty() { " " } else { "" };
    format!("{fence}{pad}{text}{pad}{fence}")
}

/// Free text (a campaign's `description`) as Markdown paragraphs of literal text: split at blank
/// lines, each paragraph on one line ([`escape_inline`]), leading white space dropped (four
/// spaces would start a code block), and a leading list marker (`-`, `+`, `1.`, `1)`) or
/// setext underline (`=`) escaped, so the text stays paragraphs of its own words.
pub fn paragraphs(text: &str) -> String {
    let normalised = text.replace("\r\n", "\n").replace('\r', "\n");
    let mut out = Vec::new();
    let mut paragraph: Vec<&str> = Vec::new();
    for line in normalised.split('\n').chain([""]) {
        if line.trim().is_empty() {
            if !paragraph.is_empty() {
                out.push(block_safe(&inline(paragraph.join(" ").trim())));
                paragraph.clear();
            }
        } else {
            paragraph.push(line.trim());
        }
    }
    out.join("\n\n")
}

/// An escaped paragraph with a leading block marker escaped too.
fn block_safe(escaped: &str) -> String {
    let digits = escaped.chars().take_while(char::is_ascii_digit).count();
    match escaped[digits..].chars().next() {
        Some('-' | '+' | '=') if digits == 0 => format!("\\{escaped}"),
        Some('.' | ')') if digits > 0 => format!("{}\\{}", &escaped[..digits], &escaped[digits..]),
        _ => escaped.to_string(),
    }
}

/// `text` for inside math (`$…$`, `$$…$$`, LaTeX): a number in e-notation as LaTeX's
/// `m \times 10^{e}` (`1.25e-3` → `1.25 \times 10^{-3}`, not "1.25 e − 3"), any other text with
/// LaTeX's special characters escaped and `|` as `\vert` (a table cell ends at a bare `|`, math
/// or not). Markdown escaping ([`escape_inline`]) does not belong there: math is read verbatim.
pub fn tex(text: &str) -> String {
    if let Some((mantissa, exponent)) = text.trim().split_once(['e', 'E'])
        && mantissa.parse::<f64>().is_ok()
        && let Ok(exponent) = exponent.parse::<i32>()
    {
        return format!("{mantissa} \\times 10^{{{exponent}}}");
    }
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\\' => out.push_str("\\backslash "),
            '{' | '}' | '$' | '&' | '#' | '%' | '_' => {
                out.push('\\');
                out.push(c);
            }
            '^' => out.push_str("\\hat{}"),
            '~' => out.push_str("\\sim "),
            '|' => out.push_str("\\vert "),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A tera instance for a Markdown template: autoescape by [`escape_inline`] on templates named
/// `*.md`, and the filters `code` (a code span in running text), `code_cell` (one in a table
/// cell), `paragraphs` and `tex` (a value inside math, [`tex`]), whose output is marked safe: they
/// escape themselves.
pub fn tera() -> tera::Tera {
    let mut tera = tera::Tera::new();
    tera.autoescape_on([".md"]);
    tera.set_escape_fn(escape_inline);
    tera.register_filter("code", code_filter);
    tera.register_filter("code_cell", code_cell_filter);
    tera.register_filter("paragraphs", paragraphs_filter);
    tera.register_filter("tex", tex_filter);
    tera
}

fn tex_filter(text: &str, _: tera::Kwargs, _: &tera::State) -> tera::Value {
    tera::Value::safe_string(&tex(text))
}

fn code_filter(text: &str, _: tera::Kwargs, _: &tera::State) -> tera::Value {
    tera::Value::safe_string(&code(text, false))
}

fn code_cell_filter(text: &str, _: tera::Kwargs, _: &tera::State) -> tera::Value {
    tera::Value::safe_string(&code(text, true))
}

fn paragraphs_filter(text: &str, _: tera::Kwargs, _: &tera::State) -> tera::Value {
    tera::Value::safe_string(&paragraphs(text))
}
