//! SVG figures drawn with plotters: one generic line chart, used for every figure.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::prelude::*;
use std::sync::OnceLock;

/// The font every figure uses, shipped in the repository (DejaVu Sans, licence beside it), so
/// nothing depends on the machine's fonts.
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const SIZE: (u32, u32) = (820, 500);

/// Registers the bundled font once; plotters' `ab_glyph` backend draws no text without it.
fn ensure_font() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED
        .get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, DEJAVU_SANS).is_ok());
    anyhow::ensure!(ok, "the bundled font assets/fonts/DejaVuSans.ttf could not be loaded");
    Ok(())
}

/// One line (or marker set) of a chart.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Draw markers instead of a line.
    pub markers: bool,
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
    /// Logarithmic axes (both), for errors against step size.
    pub log: bool,
}

/// Draws `series` as an SVG document.
pub fn line_chart(chart: &Chart, series: &[Series]) -> anyhow::Result<String> {
    ensure_font()?;
    let points = || series.iter().flat_map(|s| s.points.iter()).filter(|(x, y)| x.is_finite() && y.is_finite());
    let points_used: Vec<(f64, f64)> =
        points().filter(|(x, y)| !chart.log || (*x > 0.0 && *y > 0.0)).copied().collect();
    let (x_range, y_range) = bounds(&points_used, chart.log);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        if chart.log {
            let mut ctx = frame(&root, chart)?
                .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
                .map_err(draw_error)?;
            draw(&mut ctx, chart, series, true)?;
        } else {
            let mut ctx = frame(&root, chart)?.build_cartesian_2d(x_range, y_range).map_err(draw_error)?;
            draw(&mut ctx, chart, series, false)?;
        }
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

fn draw_error<E: std::fmt::Debug>(error: E) -> anyhow::Error {
    anyhow::anyhow!("cannot draw a figure: {error:?}")
}

fn frame<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    chart: &Chart,
) -> anyhow::Result<ChartBuilder<'a, 'b, SVGBackend<'b>>> {
    let mut builder = ChartBuilder::on(root);
    builder.caption(&chart.title, ("sans-serif", 20)).margin(12).x_label_area_size(45).y_label_area_size(80);
    Ok(builder)
}

/// Data bounds with a 5 % margin (a factor on log axes); a flat range is widened.
fn bounds(points: &[(f64, f64)], log: bool) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let range = |values: Vec<f64>| {
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        if !lo.is_finite() {
            return if log { 0.1..10.0 } else { 0.0..1.0 };
        }
        if log {
            (lo / 1.5)..(hi * 1.5)
        } else {
            let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 * lo.abs().max(1e-12) };
            (lo - pad)..(hi + pad)
        }
    };
    (range(points.iter().map(|p| p.0).collect()), range(points.iter().map(|p| p.1).collect()))
}

fn draw<'a, 'b: 'a, X, Y>(
    ctx: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>,
    chart: &Chart,
    series: &[Series],
    log: bool,
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    // Decade ticks read best as 1e-3; linear ticks keep plotters' own format.
    let scientific = |v: &f64| format!("{v:.0e}");
    let mut mesh = ctx.configure_mesh();
    mesh.x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15));
    if log {
        mesh.x_label_formatter(&scientific).y_label_formatter(&scientific);
    }
    mesh.draw().map_err(draw_error)?;
    for (index, s) in series.iter().enumerate() {
        let color = Palette99::pick(index).to_rgba();
        let points: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!log || (*x > 0.0 && *y > 0.0)))
            .collect();
        let legend = if s.markers {
            ctx.draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled()))).map_err(draw_error)?
        } else {
            ctx.draw_series(LineSeries::new(points, color.stroke_width(2))).map_err(draw_error)?
        };
        if !s.label.is_empty() {
            legend
                .label(s.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
    }
    ctx.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        // Errors fall towards small dt, leaving the upper left of a log–log chart empty.
        .position(if log { SeriesLabelPosition::UpperLeft } else { SeriesLabelPosition::UpperRight })
        .draw()
        .map_err(draw_error)
}
