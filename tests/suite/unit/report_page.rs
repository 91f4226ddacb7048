//! Unit tests of `src/report/page.rs`, moved out of the library (one test binary).

use mdsolids::report::images::{Shown, Strip, size_of};
use mdsolids::report::page::{
    APPENDIX_MARKER, CONTENTS_MARKER, number_captions, percent_decoded, split_appendix, to_html, with_contents,
};
use std::collections::{HashMap, HashSet};

const PAGE: &str = "# Title\n\nLead paragraph.\n\n## Results\n\n### Speed `v`\n\n\
    ![A chart](plots/a.svg)\n\n*The speed against time.*\n\n\
    [![A movie](plots/m.gif)](plots/m.gif)\n\n*A movie of it.*\n\n![Alone](plots/b.svg)\n\n\
    ## Results\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n## Ünïcode & more!\n";

/// The values of `attribute="…"` in `html`.
fn values<'a>(html: &'a str, attribute: &str) -> Vec<&'a str> {
    let key = format!("{attribute}=\"");
    html.split(&key).skip(1).map(|rest| &rest[..rest.find('"').unwrap()]).collect()
}

#[test]
fn every_heading_has_a_unique_id_and_every_contents_link_resolves() {
    let html = to_html(PAGE, &Default::default());
    let ids = values(&html, "id");
    assert_eq!(["<h1", "<h2", "<h3"].iter().map(|h| html.matches(h).count()).sum::<usize>(), 5, "{html}");
    for id in ["title", "results", "speed-v", "results-1", "ünïcode--more"] {
        assert!(ids.contains(&id), "{id} in {ids:?}");
    }
    let unique: HashSet<&&str> = ids.iter().collect();
    assert_eq!(unique.len(), ids.len(), "{ids:?}");
    let links: Vec<&str> = values(&html, "href").into_iter().filter_map(|h| h.strip_prefix('#')).collect();
    assert_eq!(links.len(), 4, "h2 and h3 listed, h1 not: {links:?}");
    for link in &links {
        assert!(ids.contains(&percent_decoded(link).as_str()), "#{link} resolves: {ids:?}");
    }
    // Before the first section, after the lead; h3 nested in its h2's item.
    let nav = html.find("<nav class=\"contents\"").unwrap();
    assert!(html.find("Lead paragraph").unwrap() < nav && nav < html.find("<h2").unwrap(), "{html}");
    assert!(
        html.contains("<a href=\"#results\">Results</a>\n<ul>\n<li><a href=\"#speed-v\">Speed <code>v</code>"),
        "{html}"
    );
}

#[test]
fn the_contents_go_where_the_marker_is_in_both_pages() {
    let page = format!("# T\n\n{CONTENTS_MARKER}\n\nIntro.\n\n## A b\n\n## C\n");
    let markdown = with_contents(&page);
    assert!(markdown.contains("- [A b](#a-b)\n- [C](#c)\n\nIntro."), "{markdown}");
    assert_eq!(with_contents(PAGE), number_captions(PAGE), "no marker: no list in report.md");
    let html = to_html(&page, &Default::default());
    assert_eq!(html.matches("<nav").count(), 1, "{html}");
    assert!(html.find("</nav>").unwrap() < html.find("Intro.").unwrap(), "{html}");
}

#[test]
fn captioned_images_are_numbered_figures_and_all_images_load_lazily() {
    let html = to_html(PAGE, &Default::default());
    assert_eq!(html.matches("<figure").count(), 2, "{html}");
    assert!(
        html.contains(
            "<figcaption><span class=\"figure-number\">Figure 1:</span> The speed against time.</figcaption>"
        ),
        "{html}"
    );
    assert!(
        html.contains("<a href=\"plots/m.gif\"><img src=\"plots/m.gif\" alt=\"A movie\" loading=\"lazy\"></a>"),
        "{html}"
    );
    assert!(html.contains("Figure 2:</span> A movie of it."), "{html}");
    assert_eq!(html.matches("Figure 1").count(), 1, "numbered once: {html}");
    assert!(
        html.contains("<p><img src=\"plots/b.svg\" alt=\"Alone\" loading=\"lazy\"></p>"),
        "no caption, no number: {html}"
    );
    assert_eq!(html.matches("<img").count(), html.matches("loading=\"lazy\"").count());
    let text_after = to_html("![a](x.svg) and text\n\n*not a caption*\n", &Default::default());
    assert!(!text_after.contains("<figure"), "{text_after}");
}

/// report.md numbers its figures as index.html does, in the caption's emphasis; an image
/// without a caption is no figure in either.
#[test]
fn report_md_numbers_the_figures_as_the_page_does() {
    let markdown = with_contents(PAGE);
    assert!(markdown.contains("![A chart](plots/a.svg)\n\n*Figure 1: The speed against time.*"), "{markdown}");
    assert!(markdown.contains("*Figure 2: A movie of it.*\n\n![Alone](plots/b.svg)\n"), "{markdown}");
    assert_eq!(markdown.matches("Figure ").count(), 2, "{markdown}");
    let underscores = with_contents("![a](x.svg)\n\n_Its caption._\n");
    assert_eq!(underscores, "![a](x.svg)\n\n_Figure 1: Its caption._\n");
}

/// Sections a table above the contents already links (a summary of numbered items) are not
/// listed again; their parent section is, and every listed link still resolves.
#[test]
fn the_contents_leave_out_what_a_summary_above_links() {
    let page = format!(
        "# T\n\n## Summary\n\n| item |\n|---|\n| [1. A](#1-a) |\n| [2. Ü](#2-%C3%BC) |\n\n{CONTENTS_MARKER}\n\n\
         ## Answers\n\n### 1. A\n\n### 2. Ü\n\n## Appendix\n\n### Methods\n"
    );
    let markdown = with_contents(&page);
    let list = &markdown[markdown.find("**Contents**").unwrap()..markdown.find("## Answers").unwrap()];
    assert_eq!(
        list,
        "**Contents**\n\n- [Summary](#summary)\n- [Answers](#answers)\n- [Appendix](#appendix)\n  - [Methods](#methods)\n\n"
    );
    let html = to_html(&page, &Default::default());
    let ids = values(&html, "id");
    for id in ["1-a", "2-ü", "answers", "methods"] {
        assert!(ids.contains(&id), "{id} in {ids:?}");
    }
    let nav = &html[html.find("<nav").unwrap()..html.find("</nav>").unwrap()];
    assert_eq!(nav.matches("<a href").count(), 4, "{nav}");
}

#[test]
fn tables_scroll_inside_their_own_box() {
    let html = to_html(PAGE, &Default::default());
    assert!(html.contains("<div class=\"table-wrap\">\n<table>"), "{html}");
    assert!(html.contains("</table>\n</div>"), "{html}");
}

#[test]
fn math_becomes_mathml_and_bad_latex_falls_back_to_its_code() {
    let html = to_html(
        "Inline $t_c = \\pi \\sqrt{m/k}$ and\n\n$$E = \\frac{1}{2} m v^2$$\n\nBad $\\frac{1}$, $\\nosuchcommand x$ here.\n",
        &Default::default(),
    );
    assert!(html.contains("<math"), "{html}");
    assert!(html.contains("display=\"block\""), "{html}");
    assert!(html.contains("<mfrac>"), "{html}");
    assert!(html.contains("<code class=\"math-error\" title=\"LaTeX that could not be rendered\">\\frac{1}</code>, <code class=\"math-error\" title=\"LaTeX that could not be rendered\">\\nosuchcommand x</code> here."), "{html}");
    assert!(!html.contains('$'), "{html}");
}

#[test]
fn images_carry_their_size_and_a_movie_its_filmstrip() {
    let strip = Strip { file: "plots/m.filmstrip.png".into(), size: (806, 326), caption: "frames 1, 4 of 4".into() };
    let images = HashMap::from([
        ("plots/a.svg".to_string(), Shown { size: Some((820, 500)), filmstrip: None }),
        ("plots/m.gif".to_string(), Shown { size: Some((400, 160)), filmstrip: Some(strip) }),
    ]);
    let html = to_html(PAGE, &images);
    assert!(
        html.contains(r#"<img src="plots/a.svg" alt="A chart" width="820" height="500" loading="lazy">"#),
        "{html}"
    );
    assert!(html.contains(r#"<img src="plots/m.gif" alt="A movie" width="400" height="160" class="movie" loading="lazy"><img src="plots/m.filmstrip.png" alt="A movie (frames 1, 4 of 4)" width="806" height="326" class="filmstrip" loading="lazy">"#), "{html}");
    // An image the page could not read is shown without a size, not left out.
    assert!(html.contains(r#"<img src="plots/b.svg" alt="Alone" loading="lazy">"#), "{html}");
}

#[test]
fn image_sizes_are_read_from_png_gif_and_svg_headers() {
    // Files written by the crates that write the report's images, of sizes chosen here.
    let mut png = Vec::new();
    let mut encoder = png::Encoder::new(&mut png, 37, 11);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.write_header().unwrap().write_image_data(&[0u8; 37 * 11]).unwrap();
    assert_eq!(size_of(&png), Some((37, 11)));
    let mut gif = Vec::new();
    {
        let mut encoder = gif::Encoder::new(&mut gif, 23, 5, &[0, 0, 0, 255, 255, 255]).unwrap();
        encoder
            .write_frame(&gif::Frame { width: 23, height: 5, buffer: vec![0u8; 23 * 5].into(), ..Default::default() })
            .unwrap();
    }
    assert_eq!(size_of(&gif), Some((23, 5)));
    let svg = br#"<?xml version="1.0"?>
<svg width="820" height="500" viewBox="0 0 820 500" xmlns="http://www.w3.org/2000/svg"><rect/></svg>"#;
    assert_eq!(size_of(svg), Some((820, 500)));
    assert_eq!(size_of(b"<svg viewBox=\"0 0 1 1\"></svg>"), None, "no size given: none guessed");
    assert_eq!(size_of(b"plain text"), None);
}

#[test]
fn a_table_without_rows_is_not_written() {
    let html = to_html("Before.\n\n| a | b |\n|---|---|\n\nAfter.\n\n| c |\n|---|\n| 1 |\n", &Default::default());
    assert_eq!(html.matches("<table>").count(), 1, "{html}");
    assert_eq!(html.matches("table-wrap").count(), 1, "{html}");
    assert!(html.contains("<td>1</td>") && !html.contains("<th>a</th>"), "{html}");
}

#[test]
fn the_appendix_is_a_page_of_its_own_and_links_cross_between_the_pages() {
    let page = format!(
        "# T\n\n{CONTENTS_MARKER}\n\n## Answers\n\nSee [the method](#method) and [above](#answers).\n\n\
         {APPENDIX_MARKER}\n\n## Appendix\n\n### Method\n\nBack to [the answers](#answers), [here](#method).\n"
    );
    let (main, appendix) = split_appendix(&to_html(&page, &Default::default()));
    let appendix = appendix.expect("the marker starts an appendix");
    assert!(main.contains(r##"<a href="appendix.html#method">the method</a>"##), "{main}");
    assert!(main.contains(r##"<a href="#answers">above</a>"##), "{main}");
    assert!(main.contains(r#"<a href="appendix.html">appendix.html</a>"#), "the main page links its appendix: {main}");
    assert!(!main.contains("<h3"), "the appendix's headings are not on the main page: {main}");
    // The contents list on the main page leads to the appendix's sections there.
    assert!(main.contains(r##"href="appendix.html#appendix""##), "{main}");
    assert!(appendix.contains(r##"<a href="index.html#answers">the answers</a>"##), "{appendix}");
    assert!(appendix.contains(r##"<a href="#method">here</a>"##), "{appendix}");
    assert!(appendix.contains(r#"<a href="index.html">"#), "the appendix links back: {appendix}");
    // Without the marker: one page, as before.
    let (whole, none) = split_appendix(&to_html(PAGE, &Default::default()));
    assert!(none.is_none() && whole == to_html(PAGE, &Default::default()));
}
