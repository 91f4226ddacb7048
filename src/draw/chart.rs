//! Figures drawn with plotters: one generic line chart and a space–time heat map, with which
//! every figure of the report and of the comparison is drawn, as SVG, or as PNG where the SVG
//! would be heavy ([`Image`]).

use super::legend;
use plotters::chart::SeriesAnno;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::prelude::*;
use std::sync::OnceLock;

/// The font every figure uses, shipped in the repository (DejaVu Sans, licence beside it), so
/// nothing depends on the machine's fonts.
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const SIZE: (u32, u32) = (820, 500);

/// Registers the bundled font once; plotters' `ab_glyph` backend draws no text without it.
pub(crate) fn ensure_font() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED
        .get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, DEJAVU_SANS).is_ok());
    anyhow::ensure!(ok, "the bundled font assets/fonts/DejaVuSans.ttf could not be loaded");
    Ok(())
}

/// One line, marker set or set of error bars of a chart.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// How the points are drawn.
    pub mark: Mark,
}

/// How a series' points are drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A line through them (thinned to [`LINE_POINTS`]); a point with a NaN coordinate breaks
    /// it, so one series (one colour, one legend entry) may be several lines, e.g. the two
    /// edges of one lattice.
    Line,
    /// A disc at each.
    Markers,
    /// A disc at each with a vertical error bar y ± `half_widths[i]` (a mean ± one standard
    /// deviation of an ensemble), capped at both ends; one half-width per point (in the units of
    /// y, ≥ 0). On a logarithmic y axis a bar reaching 0 or below is cut at the axis' bottom.
    ErrorBars(Vec<f64>),
    /// A disc at each, and a line through the points given here (a curve fitted to them), in
    /// one colour under one legend entry: a disc on a stroke.
    Fitted(Vec<(f64, f64)>),
}

/// Titles and axis kinds of a chart.
#[derive(Clone, Debug)]
pub struct Chart {
    /// Caption.
    pub title: String,
    /// x-axis description with unit.
    pub x_label: String,
    /// y-axis description with unit.
    pub y_label: String,
    /// Axis scales.
    pub scale: Scale,
}

/// Linear or logarithmic axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Both linear.
    Linear,
    /// Both logarithmic (errors against step size).
    LogLog,
    /// Linear x, logarithmic y (energy ratios against time).
    LogY,
    /// Logarithmic x, linear y (a quantity of order one against a parameter swept over decades).
    LogX,
}

impl Scale {
    fn log_x(self) -> bool {
        matches!(self, Scale::LogLog | Scale::LogX)
    }
    fn log_y(self) -> bool {
        matches!(self, Scale::LogLog | Scale::LogY)
    }
    /// True when the point can be drawn on these axes (positive where logarithmic).
    fn shows(self, (x, y): (f64, f64)) -> bool {
        x.is_finite() && y.is_finite() && (!self.log_x() || x > 0.0) && (!self.log_y() || y > 0.0)
    }
}

/// A line is drawn through at most this many points (an SVG of a few hundred kB per figure
/// however long the run), about two per pixel column of the figure.
pub const LINE_POINTS: usize = 2000;

/// `points` in order, thinned to at most `most` (even): split into `most`/2 runs of
/// consecutive points, each kept as its lowest and highest point in their order, so peaks,
/// troughs and the envelope of an oscillation stay where they are.
pub fn thin_line(points: Vec<(f64, f64)>, most: usize) -> Vec<(f64, f64)> {
    if points.len() <= most {
        return points;
    }
    let run = points.len().div_ceil(most / 2);
    let mut kept = Vec::with_capacity(most);
    for chunk in points.chunks(run) {
        let lowest = (0..chunk.len()).min_by(|&a, &b| chunk[a].1.total_cmp(&chunk[b].1)).unwrap_or(0);
        let highest = (0..chunk.len()).max_by(|&a, &b| chunk[a].1.total_cmp(&chunk[b].1)).unwrap_or(0);
        kept.push(chunk[lowest.min(highest)]);
        if lowest != highest {
            kept.push(chunk[lowest.max(highest)]);
        }
    }
    kept
}

/// A drawn figure: an SVG document, or a PNG image where the SVG would pass
/// [`SVG_MOST_BYTES`] (many lines, points or heat-map cells: one PNG of a few tens of kB
/// instead of up to a megabyte of vector shapes; the report stays light to load).
#[derive(Clone, Debug)]
pub enum Image {
    /// An SVG document.
    Svg(String),
    /// A PNG file's bytes.
    Png(Vec<u8>),
}

impl Image {
    /// The file's bytes.
    pub fn bytes(&self) -> &[u8] {
        match self {
            Image::Svg(svg) => svg.as_bytes(),
            Image::Png(png) => png,
        }
    }
    /// `file` (a name with an extension, `plots/x.svg`) with the extension of this image's format
    /// instead (`svg` or `png`).
    pub fn file_name(&self, file: &str) -> String {
        let extension = match self {
            Image::Svg(_) => "svg",
            Image::Png(_) => "png",
        };
        std::path::Path::new(file).with_extension(extension).to_string_lossy().into_owned()
    }
}

/// A figure whose SVG is larger than this (bytes) is drawn as a PNG instead: past it the
/// vector shapes (mostly one per line point or heat-map cell) cost more than the pixels.
pub const SVG_MOST_BYTES: usize = 30_000;

/// Draws a figure by `svg` (an SVG document), or when that passes [`SVG_MOST_BYTES`] again by
/// `png` on a bitmap of the same size, encoded as PNG: the two are one generic drawing
/// function instantiated for either backend.
fn svg_or_png(
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> anyhow::Result<()>,
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> anyhow::Result<()>,
) -> anyhow::Result<Image> {
    ensure_font()?;
    let mut text = String::new();
    svg(SVGBackend::with_string(&mut text, SIZE).into_drawing_area())?;
    if text.len() <= SVG_MOST_BYTES {
        return Ok(Image::Svg(text));
    }
    let mut pixels = vec![0u8; SIZE.0 as usize * SIZE.1 as usize * 3];
    png(BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area())?;
    Ok(Image::Png(indexed_png(&pixels, SIZE)?))
}

/// NeuQuant's sampling factor (1 learns from every pixel, 30, its fastest, from every 30th):
/// the coursework's 24 heavy charts have 296–798 colours, mostly flat fills and the
/// anti-aliased edges between them, and at 30 their PNGs took 0.5 % fewer bytes than at 10 (the
/// GIF encoders' default) and their report 0.7 s less CPU (3.03 → 2.32 s, 2026-12-06).
const QUANTISER_SAMPLING: i32 = 30;

/// RGB `pixels` of `size` as a PNG of at most 256 colours (NeuQuant, as GIF encoders choose
/// theirs): a chart has a few hundred (its anti-aliased text), and indexed it takes half the
/// bytes of RGB with no difference to see.
fn indexed_png(pixels: &[u8], size: (u32, u32)) -> anyhow::Result<Vec<u8>> {
    let rgba: Vec<u8> = pixels.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
    let quantiser = color_quant::NeuQuant::new(QUANTISER_SAMPLING, 256, &rgba);
    let mut nearest = std::collections::HashMap::new();
    let indices = super::by_runs(pixels, |[r, g, b]| {
        *nearest.entry([r, g, b]).or_insert_with(|| quantiser.index_of(&[r, g, b, 255]) as u8)
    });
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, size.0, size.1);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(quantiser.color_map_rgb());
    encoder.set_compression(png::Compression::Best);
    let encoding = |error: png::EncodingError| anyhow::anyhow!("cannot encode a figure as PNG: {error}");
    encoder.write_header().and_then(|mut writer| writer.write_image_data(&indices)).map_err(encoding)?;
    Ok(bytes)
}

/// Draws `series` as a line chart ([`Image`]: SVG, or PNG when heavy).
pub fn line_chart(chart: &Chart, series: &[Series]) -> anyhow::Result<Image> {
    svg_or_png(|root| line_chart_on(root, chart, series), |root| line_chart_on(root, chart, series))
}

/// Draws `series` on `root`, a drawing area of any plotters backend.
fn line_chart_on<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    chart: &Chart,
    series: &[Series],
) -> anyhow::Result<()> {
    let scale = chart.scale;
    // The axes hold the points, the ends of their error bars and their fitted curves.
    let shown: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied().chain(bar_ends(s)).chain(fit_points(s)))
        .filter(|&p| scale.shows(p))
        .collect();
    let x_range = bounds(shown.iter().map(|p| p.0), scale.log_x());
    let y_range = bounds(shown.iter().map(|p| p.1), scale.log_y());
    let placement = legend_placement(&root, chart, series, &shown, (&x_range, &y_range))?;
    let y_range = legend::grown(y_range, placement.taller, scale.log_y());
    {
        root.fill(&WHITE).map_err(draw_error)?;
        let builder = || frame(&root, chart);
        let corner = placement.corner;
        match scale {
            Scale::Linear => {
                draw(&mut builder()?.build_cartesian_2d(x_range, y_range).map_err(draw_error)?, chart, series, corner)?
            }
            Scale::LogLog => draw(
                &mut builder()?.build_cartesian_2d(log_axis(x_range), log_axis(y_range)).map_err(draw_error)?,
                chart,
                series,
                corner,
            )?,
            Scale::LogY => draw(
                &mut builder()?.build_cartesian_2d(x_range, log_axis(y_range)).map_err(draw_error)?,
                chart,
                series,
                corner,
            )?,
            Scale::LogX => draw(
                &mut builder()?.build_cartesian_2d(log_axis(x_range), y_range).map_err(draw_error)?,
                chart,
                series,
                corner,
            )?,
        }
        root.present().map_err(draw_error)?;
    }
    Ok(())
}

/// Where the legend of `series` goes among the `shown` points on axes over `ranges`
/// ([`legend::place`]). The plotting area's size in pixels is plotters' to lay out (the caption
/// and the label areas around it); it is read off the same frame built on a scratch bitmap of
/// `root`'s size, the axes' ranges changing nothing of it.
fn legend_placement<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart,
    series: &[Series],
    shown: &[(f64, f64)],
    (x_range, y_range): (&std::ops::Range<f64>, &std::ops::Range<f64>),
) -> anyhow::Result<legend::Placement> {
    let labels: Vec<&str> = series.iter().map(|s| s.label.as_str()).filter(|l| !l.is_empty()).collect();
    if labels.is_empty() {
        return Ok(legend::Placement { corner: SeriesLabelPosition::UpperRight, taller: 1.0 });
    }
    let (width, height) = root.dim_in_pixel();
    let mut scratch = vec![0u8; width as usize * height as usize * 3];
    let scratch_area = BitMapBackend::with_buffer(&mut scratch, (width, height)).into_drawing_area();
    let plot = frame(&scratch_area, chart)?.build_cartesian_2d(0.0..1.0, 0.0..1.0).map_err(draw_error)?;
    let (x_pixels, y_pixels) = plot.plotting_area().get_pixel_range();
    let (box_width, box_height) = legend::legend_pixels(&labels, LABEL_TEXT)?;
    let size =
        (box_width / f64::from(x_pixels.end - x_pixels.start), box_height / f64::from(y_pixels.end - y_pixels.start));
    let scale = chart.scale;
    let fractions: Vec<(f64, f64)> = shown
        .iter()
        .map(|&(x, y)| (legend::along(x, x_range, scale.log_x()), 1.0 - legend::along(y, y_range, scale.log_y())))
        .collect();
    Ok(legend::place(&fractions, size))
}

/// A logarithmic axis over `range` with ticks a reader can use: 1, 2, 3, 5 and 7 times each
/// power of ten where the range spans about a decade, 1, 2 and 5 over a few decades, every
/// decade over more, every other decade beyond eight (plotters' own marks only whole decades,
/// and none at all inside one).
fn log_axis(range: std::ops::Range<f64>) -> plotters::coord::combinators::WithKeyPoints<LogCoord<f64>> {
    let (lo, hi) = (range.start, range.end);
    let span = (hi / lo).log10();
    let (mantissas, every): (&[f64], i32) = match span {
        s if s <= 1.3 => (&[1.0, 2.0, 3.0, 5.0, 7.0], 1),
        s if s <= 3.0 => (&[1.0, 2.0, 5.0], 1),
        s if s <= 8.0 => (&[1.0], 1),
        _ => (&[1.0], 2),
    };
    let ticks: Vec<f64> = (lo.log10().floor() as i32..=hi.log10().ceil() as i32)
        .filter(|decade| decade.rem_euclid(every) == 0)
        .flat_map(|decade| mantissas.iter().map(move |m| m * 10f64.powi(decade)))
        .filter(|t| (lo..=hi).contains(t))
        .collect();
    range.log_scale().with_key_points(ticks)
}

/// Text sizes (px) of a figure [`SIZE`] wide: printed 14 cm wide, 1 px is 0.48 pt, so tick
/// labels of 17 px are 8.2 pt, the least a thesis figure should carry.
const TICK_TEXT: u32 = 17;
/// Axis titles and the legend (px).
const LABEL_TEXT: u32 = 18;

pub(crate) fn draw_error<E: std::fmt::Debug>(error: E) -> anyhow::Error {
    anyhow::anyhow!("cannot draw a figure: {error:?}")
}

fn frame<'a, 'b, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    chart: &Chart,
) -> anyhow::Result<ChartBuilder<'a, 'b, DB>> {
    let mut builder = ChartBuilder::on(root);
    builder.caption(&chart.title, ("sans-serif", 22)).margin(12).x_label_area_size(58).y_label_area_size(100);
    Ok(builder)
}

/// Bounds of `values` with a 5 % margin (a factor 1.5 on a log axis); a flat range is widened.
fn bounds(values: impl Iterator<Item = f64>, log: bool) -> std::ops::Range<f64> {
    let (lo, hi) = crate::measure::extremes(values);
    if !lo.is_finite() {
        return if log { 0.1..10.0 } else { 0.0..1.0 };
    }
    if log {
        (lo / 1.5)..(hi * 1.5)
    } else {
        let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 * lo.abs().max(1e-12) };
        (lo - pad)..(hi + pad)
    }
}

/// Draws the axes, `series` and their legend in `legend_corner`.
fn draw<'a, DB: DrawingBackend + 'a, X, Y>(
    ctx: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    chart: &Chart,
    series: &[Series],
    legend_corner: SeriesLabelPosition,
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    draw_axes(ctx, chart)?;
    let y_floor = ctx.y_range().start;
    for (index, s) in series.iter().enumerate() {
        let color = series_colour(index).to_rgba();
        let drawn = draw_marks(ctx, s, color, chart.scale, y_floor)?;
        if !s.label.is_empty() {
            legend_entry(drawn, s, color);
        }
    }
    ctx.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", LABEL_TEXT))
        .position(legend_corner)
        .draw()
        .map_err(draw_error)
}

/// The axes with their titles and tick labels, and the grid at the labelled ticks.
fn draw_axes<'a, DB: DrawingBackend + 'a, X, Y>(
    ctx: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    chart: &Chart,
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    // Log ticks read best as 1e-3 or 2e-3; linear ticks keep plotters' own format where it fits.
    let scientific = |v: &f64| format!("{v:.0e}");
    let (x_linear, y_linear) = (linear_labels(ctx.x_range()), linear_labels(ctx.y_range()));
    let mut mesh = ctx.configure_mesh();
    // No faint minor grid between the labelled lines: ten per interval were 40 % of a small
    // chart's SVG and are barely visible on screen or paper.
    mesh.max_light_lines(0);
    mesh.x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", TICK_TEXT))
        .axis_desc_style(("sans-serif", LABEL_TEXT));
    if chart.scale.log_x() {
        mesh.x_label_formatter(&scientific);
    } else if let Some(labels) = &x_linear {
        mesh.x_label_formatter(labels);
    }
    if chart.scale.log_y() {
        mesh.y_label_formatter(&scientific);
    } else if let Some(labels) = &y_linear {
        mesh.y_label_formatter(labels);
    }
    mesh.draw().map_err(draw_error)
}

/// Draws the points of `s` that the axes of `scale` show, by its mark, in `color` (an error bar
/// reaching 0 or below on a logarithmic y axis cut at `y_floor`, the axis' bottom); returns the
/// drawn series, for its legend entry.
fn draw_marks<'a, 'b, DB: DrawingBackend + 'a, X, Y>(
    ctx: &'b mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    s: &Series,
    color: RGBAColor,
    scale: Scale,
    y_floor: f64,
) -> anyhow::Result<&'b mut SeriesAnno<'a, DB>>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let shown = |p: &(f64, f64)| scale.shows(*p);
    match &s.mark {
        Mark::Line => {
            let mut pieces: Vec<Vec<(f64, f64)>> = s
                .points
                .split(|(x, y)| x.is_nan() || y.is_nan())
                .map(|piece| thin_line(piece.iter().copied().filter(shown).collect(), LINE_POINTS))
                .collect();
            // `split` yields at least one piece; the first carries the legend entry.
            let first = pieces.remove(0);
            for piece in pieces {
                ctx.draw_series(LineSeries::new(piece, color.stroke_width(2))).map_err(draw_error)?;
            }
            ctx.draw_series(LineSeries::new(first, color.stroke_width(2))).map_err(draw_error)
        }
        Mark::Markers => ctx
            .draw_series(s.points.iter().copied().filter(shown).map(|p| Circle::new(p, 4, color.filled())))
            .map_err(draw_error),
        Mark::Fitted(fit) => {
            let line = thin_line(fit.iter().copied().filter(shown).collect(), LINE_POINTS);
            ctx.draw_series(LineSeries::new(line, color.stroke_width(2))).map_err(draw_error)?;
            ctx.draw_series(s.points.iter().copied().filter(shown).map(|p| Circle::new(p, 4, color.filled())))
                .map_err(draw_error)
        }
        Mark::ErrorBars(half_widths) => {
            let bars = s.points.iter().zip(half_widths).filter(|(p, _)| shown(p)).map(|(&(x, y), &h)| {
                let low = if scale.log_y() && y - h <= 0.0 { y_floor } else { y - h };
                ErrorBar::new_vertical(x, low, y, y + h, color.filled().stroke_width(2), 10)
            });
            ctx.draw_series(bars).map_err(draw_error)?;
            ctx.draw_series(s.points.iter().copied().filter(shown).map(|p| Circle::new(p, 4, color.filled())))
                .map_err(draw_error)
        }
    }
}

/// The legend entry of the drawn series `s`: its label beside its mark, a stroke for a line, a
/// disc for markers, a disc on a bar for error bars.
fn legend_entry<'a, DB: DrawingBackend + 'a>(drawn: &mut SeriesAnno<'a, DB>, s: &Series, color: RGBAColor) {
    let (stroke, disc, bar) = match s.mark {
        Mark::Line => (true, false, false),
        Mark::Markers => (false, true, false),
        Mark::ErrorBars(_) => (false, true, true),
        Mark::Fitted(_) => (true, true, false),
    };
    drawn.label(s.label.clone()).legend(move |(x, y)| {
        let stroke = if stroke { vec![(-9, 0), (9, 0)] } else { Vec::new() };
        let bar = if bar { vec![(0, -8), (0, 8)] } else { Vec::new() };
        EmptyElement::at((x + 9, y))
            + PathElement::new(stroke, color.stroke_width(2))
            + PathElement::new(bar, color.stroke_width(2))
            + Circle::new((0, 0), if disc { 4 } else { 0 }, color.filled())
    });
}

/// The colours of a chart's series in order, repeating: Tableau's ten, which stay apart on
/// screen and in print (no yellow on white).
const SERIES_COLOURS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

fn series_colour(index: usize) -> RGBColor {
    SERIES_COLOURS[index % SERIES_COLOURS.len()]
}

/// The points of a series' fitted curve; none for other marks.
fn fit_points(s: &Series) -> impl Iterator<Item = (f64, f64)> + '_ {
    let fit = match &s.mark {
        Mark::Fitted(fit) => fit.as_slice(),
        _ => &[],
    };
    fit.iter().copied()
}

/// The ends (x, y ± half-width) of a series' error bars; none for other marks.
pub fn bar_ends(s: &Series) -> impl Iterator<Item = (f64, f64)> + '_ {
    let half_widths = match &s.mark {
        Mark::ErrorBars(h) => h.as_slice(),
        _ => &[],
    };
    s.points.iter().zip(half_widths).flat_map(|(&(x, y), &h)| [(x, y - h), (x, y + h)])
}

/// Labels of a linear axis over `range` where plotters' own do not fit: they never use an
/// exponent, so from 1e6 up (a modulus of 2e11) they overflow the label area and below 1e-4 (an
/// error of 1e-7) they round to 0. There the labels are scientific, with the digits that tell
/// neighbouring ticks (about ten over the range) apart; elsewhere plotters' stay.
fn linear_labels(range: std::ops::Range<f64>) -> Option<impl Fn(&f64) -> String> {
    let largest = range.start.abs().max(range.end.abs());
    if largest == 0.0 || (1e-4..1e6).contains(&largest) {
        return None;
    }
    let step = (range.end - range.start).abs() / 10.0;
    let digits = (largest.log10().floor() - step.log10().floor()).clamp(0.0, 6.0) as usize;
    Some(move |v: &f64| format!("{v:.digits$e}"))
}

/// Colour of a value in [−1, 1] on a diverging scale: blue (−1), white (0), red (+1).
pub(crate) fn diverging(value: f64) -> RGBColor {
    let v = value.clamp(-1.0, 1.0);
    let fade = |c: f64| (255.0 * (1.0 - v.abs()) + c * v.abs()) as u8;
    if v >= 0.0 { RGBColor(fade(200.0), fade(30.0), fade(30.0)) } else { RGBColor(fade(30.0), fade(60.0), fade(200.0)) }
}

/// At most this many cells along each axis of a heat map.
const HEATMAP_CELLS: (usize, usize) = (150, 100);

/// A space–time heat map ([`Image`]: SVG, or PNG when heavy, as most are): `values[s][j]` at
/// time `times[s]` and row `j` (a particle), coloured by value / max |value| on a
/// blue–white–red scale; long series are thinned to at most [`HEATMAP_CELLS`] samples and rows.
pub fn heatmap(chart: &Chart, times: &[f64], values: &[Vec<f64>]) -> anyhow::Result<Image> {
    let rows = values.first().map_or(0, Vec::len);
    anyhow::ensure!(times.len() >= 2 && rows > 0, "a heat map needs two samples and one row");
    svg_or_png(|root| heatmap_on(root, chart, times, values), |root| heatmap_on(root, chart, times, values))
}

/// Draws the heat map of [`heatmap`] on `root`, a drawing area of any plotters backend.
fn heatmap_on<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    chart: &Chart,
    times: &[f64],
    values: &[Vec<f64>],
) -> anyhow::Result<()> {
    let rows = values.first().map_or(0, Vec::len);
    let largest = values.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    let time_stride = times.len().div_ceil(HEATMAP_CELLS.0);
    let row_stride = rows.div_ceil(HEATMAP_CELLS.1);
    root.fill(&WHITE).map_err(draw_error)?;
    let (map, bar) = root.split_horizontally(SIZE.0 - COLOUR_BAR_WIDTH);
    let mut ctx = frame(&map, chart)?
        .build_cartesian_2d(times[0]..times[times.len() - 1], 0.0..rows as f64)
        .map_err(draw_error)?;
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", TICK_TEXT))
        .axis_desc_style(("sans-serif", LABEL_TEXT))
        .draw()
        .map_err(draw_error)?;
    let mut cells = Vec::new();
    for s in (0..times.len() - 1).step_by(time_stride) {
        let t1 = times[(s + time_stride).min(times.len() - 1)];
        for j in (0..rows).step_by(row_stride) {
            let color = diverging(values[s][j] / largest);
            cells.push(Rectangle::new([(times[s], j as f64), (t1, (j + row_stride) as f64)], color.filled()));
        }
    }
    ctx.draw_series(cells).map_err(draw_error)?;
    colour_bar(&bar, largest)?;
    root.present().map_err(draw_error)?;
    Ok(())
}

/// Width (px) of a heat map's colour bar with its labels.
const COLOUR_BAR_WIDTH: u32 = 125;

/// The diverging scale of a heat map, −`largest` (blue) to +`largest` (red), with its values.
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, largest: f64) -> anyhow::Result<()> {
    let mut ctx = ChartBuilder::on(area)
        .margin_top(44)
        .margin_bottom(70)
        .margin_right(8)
        .y_label_area_size(82)
        .build_cartesian_2d(0.0..1.0, -largest..largest)
        .map_err(draw_error)?;
    let labels = |v: &f64| format!("{v:.1e}");
    ctx.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(5)
        .y_label_formatter(&labels)
        .label_style(("sans-serif", TICK_TEXT))
        .draw()
        .map_err(draw_error)?;
    const STEPS: usize = 64;
    let step = 2.0 * largest / STEPS as f64;
    ctx.draw_series((0..STEPS).map(|i| {
        let low = -largest + i as f64 * step;
        Rectangle::new([(0.0, low), (1.0, low + step)], diverging((low + 0.5 * step) / largest).filled())
    }))
    .map_err(draw_error)?;
    Ok(())
}
