//! The guide holds together: the README stays a front page, every relative link in it and in
//! `docs/` reaches a file (and a heading, where it names one), every docs page opens with what
//! it answers, and the field reference of `docs/campaigns.md` lists every field the campaign
//! parser accepts (read from its serde derives, `spec::scene_fields` and
//! `spec::campaign_fields`) and no field it does not.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::common::repo;

/// Most lines the README may have: a front page, the guide beside it.
const README_LINES: usize = 250;

/// README.md and every `docs/*.md`.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![repo().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(repo().join("docs"))
        .expect("docs/")
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The lines of a Markdown text outside fenced code blocks, with their numbers (from 1).
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fence: Option<&str> = None;
    let mut lines = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let marker = ["```", "~~~"].into_iter().find(|m| trimmed.starts_with(m));
        match (fence, marker) {
            (None, Some(m)) => fence = Some(m),
            (Some(open), Some(m)) if open == m => fence = None,
            (None, None) => lines.push((index + 1, line)),
            _ => {}
        }
    }
    lines
}

/// `line` with its inline code spans blanked (a link written inside backticks is no link).
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let fence = &rest[start..start + ticks];
        match rest[start + ticks..].find(fence) {
            Some(end) => rest = &rest[start + ticks + end + ticks..],
            None => {
                out.push_str(&rest[start..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// The targets of the inline links and images of `text` (`[text](target)`, `![alt](target)`),
/// with their line numbers.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (number, line) in prose_lines(text) {
        let line = without_code_spans(line);
        let mut rest = line.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            // `[text](target "title")`: the target is the first word.
            let target = after[..end].split_whitespace().next().unwrap_or("");
            found.push((number, target.trim_matches(['<', '>']).to_string()));
            rest = &after[end..];
        }
    }
    found
}

/// The anchors of every heading of a Markdown text; a repeated one gets `-1`, `-2`, ...
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut anchors = BTreeSet::new();
    for (_, line) in prose_lines(text) {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if !(1..=6).contains(&hashes) || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = mdsolids::report::page::slug(&line[hashes..]);
        let count = seen.entry(base.clone()).or_insert(0);
        anchors.insert(if *count == 0 { base.clone() } else { format!("{base}-{count}") });
        *count += 1;
    }
    anchors
}

/// Why a link target does not resolve, if it does not.
fn broken(page: &Path, target: &str) -> Option<String> {
    if target.is_empty() {
        return Some("an empty link".into());
    }
    if target.contains("://") || target.starts_with("mailto:") {
        return None;
    }
    let (path, fragment) = match target.split_once('#') {
        Some((path, fragment)) => (path, Some(fragment)),
        None => (target, None),
    };
    let file = if path.is_empty() { page.to_path_buf() } else { page.parent().unwrap().join(path) };
    if !file.exists() {
        return Some(format!("{} does not exist", file.display()));
    }
    let fragment = fragment?;
    if file.extension().is_none_or(|e| e != "md") {
        return Some(format!("#{fragment} points into {}, which has no headings", file.display()));
    }
    if anchors(&read(&file)).contains(fragment) {
        None
    } else {
        Some(format!("{} has no heading with the anchor #{fragment}", file.display()))
    }
}

#[test]
fn the_readme_is_a_front_page() {
    let text = read(&repo().join("README.md"));
    let lines = text.lines().count();
    assert!(lines <= README_LINES, "README.md has {lines} lines; at most {README_LINES} (move the rest into docs/)");
}

#[test]
fn every_relative_link_resolves() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for page in pages() {
        for (line, target) in links(&read(&page)) {
            checked += 1;
            if let Some(why) = broken(&page, &target) {
                failures.push(format!("{}:{line}: ({target}): {why}", page.display()));
            }
        }
    }
    assert!(checked > 20, "only {checked} links found: is the link reader broken?");
    assert!(failures.is_empty(), "broken links:\n{}", failures.join("\n"));
}

#[test]
fn every_docs_page_opens_with_what_it_answers() {
    for page in pages().into_iter().skip(1) {
        let text = read(&page);
        let mut lines = text.lines().filter(|line| !line.trim().is_empty());
        let title = lines.next().unwrap_or("");
        assert!(title.starts_with("# "), "{}: opens with {title:?}, not a title", page.display());
        let opening = lines.next().unwrap_or("");
        assert!(
            !opening.is_empty() && !["#", "|", "```", "-", "!", ">"].iter().any(|m| opening.starts_with(m)),
            "{}: the title is followed by {opening:?}, not by the sentence saying what the page answers",
            page.display()
        );
    }
}

/// The code spans of the first cells of the field tables (header `| field | ...`) of a page.
fn documented_fields(text: &str) -> BTreeSet<String> {
    let mut fields = BTreeSet::new();
    let mut in_field_table = false;
    for (_, line) in prose_lines(text) {
        let Some(row) = line.trim().strip_prefix('|') else {
            in_field_table = false;
            continue;
        };
        let first = row.split('|').next().unwrap_or("").trim();
        if first == "field" {
            in_field_table = true;
            continue;
        }
        if !in_field_table {
            continue;
        }
        fields.extend(first.split('`').skip(1).step_by(2).map(str::to_string));
    }
    fields
}

#[test]
fn the_field_reference_lists_every_field_the_parser_accepts() {
    let page = repo().join("docs/campaigns.md");
    let documented = documented_fields(&read(&page));
    let accepted: BTreeSet<String> =
        mdsolids::spec::scene_fields().into_iter().chain(mdsolids::spec::campaign_fields()).collect();
    // The walk itself: fields of nested sections, a renamed key, the campaign's own.
    for expected in ["material.mass", "lattice.type", "relax.tolerance", "budget.seconds_per_run", "version", "scenes"]
    {
        assert!(accepted.contains(expected), "{expected} missing from the parser's fields: {accepted:?}");
    }
    let missing: Vec<&String> = accepted.iter().filter(|field| !documented.contains(*field)).collect();
    assert!(
        missing.is_empty(),
        "fields the campaign parser accepts but the field tables of {} do not list (first column, in backticks): \
         {missing:?}",
        page.display()
    );
    // A documented path is a field or a section holding fields (`relax`, `movie`).
    let unknown: Vec<&String> = documented
        .iter()
        .filter(|doc| !accepted.iter().any(|field| field == *doc || field.starts_with(&format!("{doc}."))))
        .collect();
    assert!(unknown.is_empty(), "{} documents fields the parser does not accept: {unknown:?}", page.display());
}
