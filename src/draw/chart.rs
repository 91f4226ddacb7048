//! SVG figures drawn with plotters: one generic line chart and a space–time heat map, with
//! which every figure of the report and of the comparison is drawn.

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
fn thin_line(points: Vec<(f64, f64)>, most: usize) -> Vec<(f64, f64)> {
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

/// Draws `series` as an SVG document.
pub fn line_chart(chart: &Chart, series: &[Series]) -> anyhow::Result<String> {
    ensure_font()?;
    let scale = chart.scale;
    let shown: Vec<(f64, f64)> =
        series.iter().flat_map(|s| s.points.iter().copied()).filter(|&p| scale.shows(p)).collect();
    let x_range = bounds(shown.iter().map(|p| p.0), scale.log_x());
    let y_range = bounds(shown.iter().map(|p| p.1), scale.log_y());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let builder = || frame(&root, chart);
        match scale {
            Scale::Linear => {
                draw(&mut builder()?.build_cartesian_2d(x_range, y_range).map_err(draw_error)?, chart, series)?
            }
            Scale::LogLog => draw(
                &mut builder()?.build_cartesian_2d(x_range.log_scale(), y_range.log_scale()).map_err(draw_error)?,
                chart,
                series,
            )?,
            Scale::LogY => draw(
                &mut builder()?.build_cartesian_2d(x_range, y_range.log_scale()).map_err(draw_error)?,
                chart,
                series,
            )?,
            Scale::LogX => draw(
                &mut builder()?.build_cartesian_2d(x_range.log_scale(), y_range).map_err(draw_error)?,
                chart,
                series,
            )?,
        }
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

pub(crate) fn draw_error<E: std::fmt::Debug>(error: E) -> anyhow::Error {
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

/// Bounds of `values` with a 5 % margin (a factor 1.5 on a log axis); a flat range is widened.
fn bounds(values: impl Iterator<Item = f64>, log: bool) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
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

fn draw<'a, 'b: 'a, X, Y>(
    ctx: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>,
    chart: &Chart,
    series: &[Series],
) -> anyhow::Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    // Decade ticks read best as 1e-3; linear ticks keep plotters' own format where it fits.
    let scientific = |v: &f64| format!("{v:.0e}");
    let (x_linear, y_linear) = (linear_labels(ctx.x_range()), linear_labels(ctx.y_range()));
    let mut mesh = ctx.configure_mesh();
    mesh.x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15));
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
    mesh.draw().map_err(draw_error)?;
    for (index, s) in series.iter().enumerate() {
        let color = Palette99::pick(index).to_rgba();
        let points: Vec<(f64, f64)> = s.points.iter().copied().filter(|&p| chart.scale.shows(p)).collect();
        let points = if s.markers { points } else { thin_line(points, LINE_POINTS) };
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
        .position(if chart.scale.log_x() { SeriesLabelPosition::UpperLeft } else { SeriesLabelPosition::UpperRight })
        .draw()
        .map_err(draw_error)
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

/// At most this many cells along each axis of a heat map (an SVG of rectangles stays small).
const HEATMAP_CELLS: (usize, usize) = (150, 100);

/// A space–time heat map as an SVG document: `values[s][j]` at time `times[s]` and row `j`
/// (a particle), coloured by value / max |value| on a blue–white–red scale; long series are
/// thinned to at most [`HEATMAP_CELLS`] samples and rows.
pub fn heatmap(chart: &Chart, times: &[f64], values: &[Vec<f64>]) -> anyhow::Result<String> {
    ensure_font()?;
    let rows = values.first().map_or(0, Vec::len);
    anyhow::ensure!(times.len() >= 2 && rows > 0, "a heat map needs two samples and one row");
    let largest = values.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    let time_stride = times.len().div_ceil(HEATMAP_CELLS.0);
    let row_stride = rows.div_ceil(HEATMAP_CELLS.1);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let mut ctx = frame(&root, chart)?
            .build_cartesian_2d(times[0]..times[times.len() - 1], 0.0..rows as f64)
            .map_err(draw_error)?;
        ctx.configure_mesh()
            .disable_mesh()
            .x_desc(&chart.x_label)
            .y_desc(&chart.y_label)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 15))
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
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let svg = line_chart(&chart, &[Series { label: "e".into(), points, markers: false }]).unwrap();
        // ~30 bytes per drawn point.
        assert!(svg.len() < 300_000, "{} bytes", svg.len());
    }
}
