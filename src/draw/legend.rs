//! Where a chart's legend goes: in a corner of the plotting area where it covers no drawn point,
//! and where every corner would cover one, at the top, in room made for it above the data. The
//! geometry is in fractions of the plotting area (0 at its left and top, 1 at its right and
//! bottom), so it is decided before anything is drawn.

use plotters::prelude::*;

/// A legend's place: its corner, and the factor by which the y axis' span (in log10 units on a
/// logarithmic axis) grows upwards to make room for it (1: it fits as the axes are).
pub(super) struct Placement {
    pub corner: SeriesLabelPosition,
    pub taller: f64,
}

/// Past this share of the plotting area's height the legend is not given room of its own: the
/// data would be squeezed into less than half the figure; it takes the least crowded corner.
const MOST_ROOM: f64 = 0.5;

/// The legend box of `labels` in pixels, as plotters lays it out (`SeriesLabelStyle::draw`):
/// the widest label plus its 30 px mark area and two 10 px margins wide, the lines (1.25 font
/// heights each) plus the margins high, 5 px from the plot's edges; and a marker's 4 px radius
/// around it, so that no disc is half under it.
pub(super) fn legend_pixels(labels: &[&str], font_px: u32) -> anyhow::Result<(f64, f64)> {
    let mut text = MultiLineText::<(i32, i32), &str>::new((0, 0), ("sans-serif", font_px));
    for label in labels {
        text.push_line(*label);
    }
    let (width, height) = text.estimate_dimension().map_err(|e| anyhow::anyhow!("cannot measure a legend: {e:?}"))?;
    let (edge, marker) = (5.0, 4.0);
    Ok((f64::from(width) + 50.0 + edge + marker, f64::from(height) + 20.0 + edge + marker))
}

/// Where a legend of `size` (fractions of the plotting area's width and height) goes among
/// `points` (fractions from the left and the top): the first corner, upper right first, that
/// covers none of them; else above the highest point, the axis made taller by
/// g = (1 − a) / (1 − h), a the highest point's distance from the top and h the legend's height
/// (after it, that point is h from the new top); else, for a legend taller than [`MOST_ROOM`],
/// the corner that covers the fewest.
pub(super) fn place(points: &[(f64, f64)], size: (f64, f64)) -> Placement {
    let (width, height) = size;
    let corners = [
        (SeriesLabelPosition::UpperRight, true, false),
        (SeriesLabelPosition::UpperLeft, true, true),
        (SeriesLabelPosition::LowerRight, false, false),
        (SeriesLabelPosition::LowerLeft, false, true),
    ];
    let covered = |upper: bool, left: bool| {
        let under = |&&(x, y): &&(f64, f64)| {
            let in_x = if left { x <= width } else { x >= 1.0 - width };
            let in_y = if upper { y <= height } else { y >= 1.0 - height };
            in_x && in_y
        };
        points.iter().filter(under).count()
    };
    let (corner, fewest) = corners
        .into_iter()
        .map(|(corner, upper, left)| (corner, covered(upper, left)))
        .min_by_key(|&(_, count)| count)
        .unwrap_or((SeriesLabelPosition::UpperRight, 0));
    if fewest == 0 || height >= MOST_ROOM {
        return Placement { corner, taller: 1.0 };
    }
    let highest = points.iter().map(|p| p.1).fold(1.0, f64::min);
    Placement { corner: SeriesLabelPosition::UpperRight, taller: ((1.0 - highest) / (1.0 - height)).max(1.0) }
}

/// Where `value` lies along `range` as a fraction, 0 at its start and 1 at its end (in log10
/// units on a logarithmic axis).
pub(super) fn along(value: f64, range: &std::ops::Range<f64>, log: bool) -> f64 {
    if log {
        (value / range.start).log10() / (range.end / range.start).log10()
    } else {
        (value - range.start) / (range.end - range.start)
    }
}

/// `range` with its span grown `taller` times upwards, from its start (in log10 units on a
/// logarithmic axis).
pub(super) fn grown(range: std::ops::Range<f64>, taller: f64, log: bool) -> std::ops::Range<f64> {
    let end = if log {
        range.start * (range.end / range.start).powf(taller)
    } else {
        range.start + (range.end - range.start) * taller
    };
    range.start..end
}
