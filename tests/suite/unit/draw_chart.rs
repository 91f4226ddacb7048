//! Unit tests of `src/draw/chart.rs`, moved out of the library (one test binary).

use mdsolids::draw::chart::{
    Chart, Image, LINE_POINTS, Mark, SVG_MOST_BYTES, Scale, Series, bar_ends, heatmap, line_chart, thin_line,
};

/// A line of 10⁶ points (a long run's energy) makes a figure of bounded size (issue 14: 441 MB
/// of SVG for 10⁷ samples; here ~40 MB unthinned) that keeps its extremes: a single spike and
/// the envelope of the oscillation are drawn.
#[test]
fn long_lines_are_thinned_keeping_their_extremes() {
    let spike = 777_777;
    let points: Vec<(f64, f64)> =
        (0..1_000_000).map(|i| (i as f64 * 1e-3, if i == spike { 3.0 } else { (i as f64 * 1e-2).sin() })).collect();
    let thinned = thin_line(points.clone(), LINE_POINTS);
    assert!(thinned.len() <= LINE_POINTS, "{}", thinned.len());
    assert!(thinned.contains(&points[spike]), "the spike is kept");
    let lowest = thinned.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    assert!(lowest < -0.9999, "the troughs are kept: {lowest}");
    assert!(thinned.windows(2).all(|w| w[0].0 < w[1].0), "in order");
    let chart = Chart { title: "t".into(), x_label: "x".into(), y_label: "y".into(), scale: Scale::Linear };
    let image = line_chart(&chart, &[Series { label: "e".into(), points, mark: Mark::Line }]).unwrap();
    assert!(image.bytes().len() < SVG_MOST_BYTES, "{} bytes", image.bytes().len());
}

/// An ensemble's error bars: the axes hold the bar ends (a bar 10× taller than the points'
/// spread is not cut off), each point gets a bar with two caps beside its disc, and on a log
/// axis a bar reaching below zero is cut at the axis instead of vanishing.
#[test]
fn error_bars_are_drawn_whole_around_their_points() {
    let points = vec![(1.0, 1.0), (2.0, 1.0), (3.0, 1.0)];
    let bars =
        Series { label: "mean ± σ".into(), points: points.clone(), mark: Mark::ErrorBars(vec![1.0, 0.5, 2.0]) };
    assert_eq!(
        bar_ends(&bars).collect::<Vec<_>>(),
        [(1.0, 0.0), (1.0, 2.0), (2.0, 0.5), (2.0, 1.5), (3.0, -1.0), (3.0, 3.0)]
    );
    let svg = |scale: Scale, mark: Mark| {
        let chart = Chart { title: "t".into(), x_label: "x".into(), y_label: "y".into(), scale };
        match line_chart(&chart, &[Series { label: "s".into(), points: points.clone(), mark }]).unwrap() {
            Image::Svg(svg) => svg,
            Image::Png(_) => panic!("three points are an SVG"),
        }
    };
    // Lines in the series' colour (the first): none for markers, a stem and two caps per bar.
    let lines = |text: &str| text.matches("<line opacity=\"1\" stroke=\"#1F77B4\"").count();
    let plain = svg(Scale::Linear, Mark::Markers);
    let with_bars = svg(Scale::Linear, bars.mark.clone());
    assert_eq!(lines(&plain), 0, "{plain}");
    assert!(lines(&with_bars) >= 3 * 3, "{with_bars}");
    // The y axis reaches the lowest bar end, −1, so it is labelled below 0 (the points alone
    // span 1 … 1).
    let below_zero = |text: &str| text.contains("\n-0.5\n");
    assert!(below_zero(&with_bars) && !below_zero(&plain), "{with_bars}");
    let log = svg(Scale::LogY, bars.mark.clone());
    assert!(lines(&log) >= 3 * 3, "the bar reaching −1 is drawn, cut at the axis: {log}");
}

/// A chart of few points stays a vector drawing; one of many lines (or a heat map) passes
/// [`SVG_MOST_BYTES`] and is written as a PNG of a few tens of kB.
#[test]
fn heavy_figures_are_drawn_as_png() {
    let chart = Chart { title: "t".into(), x_label: "x".into(), y_label: "y".into(), scale: Scale::Linear };
    let line = |k: usize, n: usize| Series {
        label: String::new(),
        points: (0..n).map(|i| (i as f64, k as f64 + (i as f64 * 0.1).sin())).collect(),
        mark: Mark::Line,
    };
    let light = line_chart(&chart, &[line(0, 50)]).unwrap();
    assert!(matches!(light, Image::Svg(_)), "{} bytes", light.bytes().len());
    assert_eq!(light.file_name("plots/a-b.svg"), "plots/a-b.svg");
    let heavy = line_chart(&chart, &(0..30).map(|k| line(k, 2000)).collect::<Vec<_>>()).unwrap();
    assert!(matches!(heavy, Image::Png(_)));
    assert!(heavy.bytes().starts_with(b"\x89PNG") && heavy.bytes().len() < 100_000, "{}", heavy.bytes().len());
    assert_eq!(heavy.file_name("plots/a-time.dt.svg"), "plots/a-time.dt.png");
    let times: Vec<f64> = (0..400).map(f64::from).collect();
    let values: Vec<Vec<f64>> = (0..400).map(|s| (0..60).map(|j| ((s + j) as f64 * 0.05).sin()).collect()).collect();
    assert!(matches!(heatmap(&chart, &times, &values).unwrap(), Image::Png(_)), "15 000 cells");
}
