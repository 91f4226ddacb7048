//! Unit tests of `src/report/mod.rs`, moved out of the library (one test binary).

/// Math is written once: LaTeX in `report.md`, MathML in `index.html`.
#[test]
fn write_pages_keeps_math_as_latex_in_markdown_and_mathml_in_html() {
    let dir = crate::common::scratch();
    let template =
        "# {{ title }}\n\nInline $t_c = {{ tc | tex }}\\,\\mathrm{s}$ and\n\n$$r = e^{-\\gamma t_c / 2m}$$\n";
    let mut context = tera::Context::new();
    context.insert("title", "Math");
    context.insert("tc", &"1.25e-3");
    mdsolids::report::write_pages(dir.path(), ("t.md", template), context).unwrap();
    let markdown = std::fs::read_to_string(dir.path().join("report.md")).unwrap();
    assert!(markdown.contains("$t_c = 1.25 \\times 10^{-3}\\,\\mathrm{s}$"), "{markdown}");
    assert!(markdown.contains("$$r = e^{-\\gamma t_c / 2m}$$"), "{markdown}");
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("<math display=\"inline\"><msub><mi>t</mi><mi>c</mi></msub><mo>=</mo><mn>1.25</mn><mo>×</mo><msup><mn>10</mn>"), "{html}");
    assert!(html.contains("<math display=\"block\">"), "{html}");
    assert!(!html.contains('$'), "{html}");
}
