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

/// The numbers of `attribute="…"` in each of `svg`'s `<element …>` tags that carry `marker`.
fn tag_numbers(svg: &str, element: &str, marker: &str, attributes: &[&str]) -> Vec<Vec<f64>> {
    let number = |tag: &str, name: &str| {
        let start = tag.find(&format!(" {name}=\"")).map(|i| i + name.len() + 3).expect(name);
        tag[start..].split('"').next().and_then(|v| v.parse().ok()).expect(name)
    };
    svg.split(&format!("<{element} "))
        .skip(1)
        .map(|rest| &rest[..rest.find('>').unwrap_or(rest.len())])
        .filter(|tag| tag.contains(marker))
        .map(|tag| attributes.iter().map(|name| number(&format!(" {tag}"), name)).collect())
        .collect()
}

/// The legend's box (x, y, width, height, px) and the centres of the discs drawn under it and
/// outside it, of a chart of three marker series drawn as an SVG.
fn legend_and_discs(series: &[Series]) -> ([f64; 4], usize, Vec<(f64, f64)>) {
    let chart = Chart { title: "t".into(), x_label: "x".into(), y_label: "y".into(), scale: Scale::Linear };
    let Image::Svg(svg) = line_chart(&chart, series).unwrap() else { panic!("a few points are an SVG") };
    let boxes = tag_numbers(&svg, "rect", "opacity=\"0.85\"", &["x", "y", "width", "height"]);
    assert_eq!(boxes.len(), 1, "one legend: {svg}");
    let b = [boxes[0][0], boxes[0][1], boxes[0][2], boxes[0][3]];
    let discs = tag_numbers(&svg, "circle", "r=\"4\"", &["cx", "cy"]);
    // A disc is under the box when any of it is: its centre within its 4 px radius of the box.
    let under =
        |d: &&Vec<f64>| d[0] > b[0] - 4.0 && d[0] < b[0] + b[2] + 4.0 && d[1] > b[1] - 4.0 && d[1] < b[1] + b[3] + 4.0;
    let inside = discs.iter().filter(under).count();
    let outside = discs.iter().filter(|d| !under(d)).map(|d| (d[0], d[1])).collect();
    (b, inside, outside)
}

/// The legend covers no data point. With every corner of the plot occupied (a point in each,
/// which the old corner-only choice had to cover), the y axis grows upwards to make room above
/// the data: the only discs under the box are the legend's own three, and every data disc lies
/// below it. With the upper-left corner empty the legend goes there, and the axes are not
/// stretched: the highest point stays within the top tenth of the plot (the 5 % margin).
#[test]
fn the_legend_covers_no_point_and_takes_room_above_the_data_only_when_no_corner_is_free() {
    let markers = |label: &str, points: Vec<(f64, f64)>| Series { label: label.into(), points, mark: Mark::Markers };
    let crowded = [
        markers("lower corners", vec![(0.0, 0.0), (10.0, 0.0)]),
        markers("upper corners, with a long label that makes the box wide", vec![(0.0, 10.0), (10.0, 10.0)]),
        markers("middle", vec![(5.0, 5.0)]),
    ];
    let (legend, inside, outside) = legend_and_discs(&crowded);
    assert_eq!(inside, 3, "only the legend's own discs under {legend:?}: {outside:?}");
    assert_eq!(outside.len(), 5, "{outside:?}");
    assert!(
        outside.iter().all(|d| d.1 > legend[1] + legend[3]),
        "every point below the legend {legend:?}: {outside:?}"
    );
    let free_upper_left = [
        markers("lower corners", vec![(0.0, 0.0), (10.0, 0.0)]),
        markers("upper right", vec![(10.0, 10.0)]),
        markers("middle", vec![(5.0, 5.0)]),
    ];
    let (legend, inside, outside) = legend_and_discs(&free_upper_left);
    assert_eq!(inside, 3, "only the legend's own discs under {legend:?}: {outside:?}");
    assert!(legend[0] < 410.0 - legend[2] / 2.0, "the legend in the left half: {legend:?}");
    let top = outside.iter().map(|d| d.1).fold(f64::INFINITY, f64::min);
    let bottom = outside.iter().map(|d| d.1).fold(0.0, f64::max);
    // Data span 0 … 10 with 5 % margins: the highest disc is 0.05/1.1 of the plot's height
    // below the top of the data area (~400 px), about 18 px below the legend's top edge.
    assert!(
        top - legend[1] < 0.1 * (bottom - top),
        "the axis is not stretched: top disc at {top}, legend at {legend:?}"
    );
}

/// A fitted series is one colour and one legend entry: its discs at the points, its line
/// through the fit's points (which the axes hold too: the fit's far end at y = 20 lies above
/// every point), and in the legend a disc on a stroke beside its one label.
#[test]
fn a_fitted_series_draws_discs_and_its_line_in_one_colour_under_one_label() {
    let chart = Chart { title: "t".into(), x_label: "x".into(), y_label: "y".into(), scale: Scale::Linear };
    let fitted = Series {
        label: "points, fit".into(),
        points: vec![(1.0, 1.0), (2.0, 2.5), (3.0, 2.0)],
        mark: Mark::Fitted(vec![(1.0, 0.5), (3.0, 20.0)]),
    };
    let Image::Svg(svg) = line_chart(&chart, &[fitted]).unwrap() else { panic!("a few points are an SVG") };
    // Three data discs and the legend's, all in the first colour.
    let discs = tag_numbers(&svg, "circle", "fill=\"#1F77B4\"", &["cx", "cy"]);
    assert_eq!(discs.len(), 4, "{svg}");
    // The fit's line and the legend's stroke, in the same colour (an entry's unused bar is an
    // empty path).
    let strokes =
        |points: &str| svg.matches(&format!("stroke=\"#1F77B4\" stroke-width=\"2\" points=\"{points}")).count();
    assert_eq!(strokes("") - strokes("\""), 2, "{svg}");
    assert_eq!(svg.matches("points, fit").count(), 1, "{svg}");
    // The y axis reaches the fit's end at 20, beyond the points' 2.5.
    assert!(svg.contains("\n20\n") || svg.contains("\n20.0\n"), "{svg}");
}
