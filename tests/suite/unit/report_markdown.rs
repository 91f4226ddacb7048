//! Unit tests of `src/report/markdown.rs`, moved out of the library (one test binary).

use mdsolids::report::markdown::{code, inline, paragraphs, tex};

use mdsolids::report::page::to_html;

const HOSTILE: &str =
    "<script>alert(1)</script> | a*b* _c_ [x](javascript:y) ![i](j) `k` &lt; #\n| row\r\n~~s~~ $x$ \\";

#[test]
fn inline_text_shows_as_itself_and_opens_nothing() {
    let body = html(&format!("# {}\n\nbefore {} after\n", inline(HOSTILE), inline(HOSTILE)));
    for live in ["<script", "<em>", "<a ", "<img", "<code>", "<del>", "<h2", "<tr", "<math"] {
        assert!(!body.contains(live), "{live} in {body}");
    }
    assert!(body.contains("&lt;script&gt;alert(1)&lt;/script&gt; | a*b* _c_ [x](javascript:y)"), "{body}");
    assert!(body.contains("`k` &amp;lt; #"), "{body}");
    assert_eq!(inline("k_d/k no_equilibrium dt·ω_max"), "k_d/k no_equilibrium dt·ω_max");
    assert_eq!(inline("-1.5e-3 (x) 2.5 %"), "-1.5e-3 (x) 2.5 %");
}

#[test]
fn a_table_keeps_its_columns() {
    let markdown = format!(
        "| a | b | c |\n|---|---|---|\n| {} | {} | {} |\n",
        inline(HOSTILE),
        code(HOSTILE, true),
        code("``a`|b", true)
    );
    let body = html(&markdown);
    assert_eq!(body.matches("<td>").count(), 3, "{body}");
    assert_eq!(body.matches("<tr>").count(), 2, "one header and one body row: {body}");
    assert!(!body.contains("<script"), "{body}");
    assert!(body.contains("<code>``a`|b</code>"), "{body}");
    assert!(body.contains("<code>&lt;script&gt;alert(1)&lt;/script&gt; | a*b*"), "{body}");
}

#[test]
fn code_spans_are_verbatim_outside_tables() {
    assert_eq!(code("run-1", true), "`run-1`");
    assert_eq!(code("`x`", false), "`` `x` ``");
    assert!(html(&format!("## Scene {}\n", code("a`b|<i>", false))).contains("<code>a`b|&lt;i&gt;</code>"));
}

#[test]
fn values_inside_math_read_as_latex() {
    assert_eq!(tex("1.25e-3"), "1.25 \\times 10^{-3}");
    assert_eq!(tex("-2E+11"), "-2 \\times 10^{11}");
    assert_eq!(tex("0.636"), "0.636");
    assert_eq!(tex("k_d|{x}$ 5% #1 ^~\\"), "k\\_d\\vert \\{x\\}\\$ 5\\% \\#1 \\hat{}\\sim \\backslash ");
    let body = html(&format!("| a |\n|---|\n| ${}$ |\n", tex("x|y_1")));
    assert_eq!(body.matches("<td>").count(), 1, "{body}");
    assert!(body.contains("<math") && !body.contains("math-error"), "{body}");
}

#[test]
fn paragraphs_stay_paragraphs() {
    let text =
        "- not a list\n1. not a list either\n\n    not code\n\n---\n\n# not a heading\n\n1986) a year\n\n<div>x</div>";
    let body = html(&paragraphs(text));
    assert_eq!(body.matches("<p>").count(), 6, "{body}");
    for block in ["<ul", "<ol", "<pre", "<hr", "<h1", "<div"] {
        assert!(!body.contains(block), "{block} in {body}");
    }
    assert!(body.contains("<p>- not a list 1. not a list either</p>"), "{body}");
    assert!(body.contains("<p>1986) a year</p>"), "{body}");
}

/// The page's HTML of `markdown`, with no images to size.
fn html(markdown: &str) -> String {
    to_html(markdown, &Default::default())
}
