//! Movies: an animated GIF of a run, particles as discs coloured by speed (with a colour bar),
//! bonds as grey lines (or coloured by strain), walls and held nodes as black marks, the time
//! (or, for a run with no time, what the frame shows) and the displacement magnification on
//! every frame.

use anyhow::Context;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

use super::chart::{diverging, draw_error, ensure_font};
use crate::measure::{Discs, extremes};
use crate::sim::Frame;

/// What a movie shows: the frames, the bonds between the particles, the size.
#[derive(Clone, Debug, PartialEq)]
pub struct Movie {
    /// Frames in time order.
    pub frames: Vec<Frame>,
    /// What each frame shows, in place of its time, when the run has no time (a minimiser or
    /// the static solve: "start", then the state it ended in); empty for a run in time, whose
    /// frames show t in s and in t_c.
    pub captions: Vec<String>,
    /// Bonds drawn as lines (i, j, rest length in m); bonds across a periodic side are left out.
    pub bonds: Vec<(usize, usize, f64)>,
    /// Held particles and the axes they are held along: in a 1D scene (all particles on one
    /// line) a wall, drawn as a bar; in 2D a filled square when held along both axes, an open
    /// one when along one.
    pub supports: Vec<(usize, crate::model::Axes)>,
    /// A packing's discs, drawn to scale in their box in place of the frames' particles:
    /// coloured by their load Σ|f|, their contacts as black lines as wide as their force is
    /// large (the force chains).
    pub discs: Option<Discs>,
    /// Frame count and size.
    pub spec: crate::spec::MovieSpec,
    /// Title drawn on every frame.
    pub title: String,
    /// The run's two-body contact time t_c (s): each frame's time is also given in t_c.
    pub t_c: f64,
    /// The run's deadline: encoding the movie is part of the run (its time budget).
    pub deadline: Option<std::time::Instant>,
}

/// Delay between frames (ms): 12.5 frames per second.
const FRAME_DELAY_MS: u32 = 80;

/// Width (pixels) kept on the right for the colour bar.
const BAR_WIDTH: u32 = 90;

/// Height (pixels) of a panel's header: the title, the time, and the magnification (if any).
pub const HEADER: u32 = 60;

/// Colour of a speed fraction in [0, 1] on a viridis-like scale: dark violet at rest, through
/// blue and green, to yellow at the fastest.
pub fn speed_color(fraction: f64) -> RGBColor {
    const ANCHORS: [(f64, f64, f64); 5] =
        [(68.0, 1.0, 84.0), (59.0, 82.0, 139.0), (33.0, 145.0, 140.0), (94.0, 201.0, 98.0), (253.0, 231.0, 37.0)];
    let f = fraction.clamp(0.0, 1.0) * (ANCHORS.len() - 1) as f64;
    let i = (f.floor() as usize).min(ANCHORS.len() - 2);
    let t = f - i as f64;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    let mix = |p: f64, q: f64| (p + t * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Encoding a movie stopped at its run's deadline (the movie's `deadline`): nothing written.
#[derive(Debug)]
pub struct PastDeadline;

impl std::fmt::Display for PastDeadline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the movie was not finished by the run's deadline")
    }
}

impl std::error::Error for PastDeadline {}

/// Writes `movie` as an animated GIF at `path`, atomically (`output::write_atomically`): the
/// GIF of [`encode_movie_panels`]. The view is fixed over all frames with equal scales on both
/// axes; colours are scaled to the fastest speed after the first frame. Fails with
/// [`PastDeadline`] once the movie's deadline passes (looked at between frames), writing nothing.
pub fn write_movie(path: &Path, movie: &Movie) -> anyhow::Result<()> {
    let bytes = encode_movie_panels(&[movie], movie.deadline)
        .with_context(|| format!("cannot draw the movie '{}'", path.display()))?;
    crate::output::write_atomically(path, &bytes)
}

/// `panels` side by side as the bytes of one animated GIF (each `width` of the first panel's
/// size, one colour bar): the same view and the same colour scale for all, so the runs compare
/// frame by frame (e.g. a lattice with and without diagonals). As many frames as the shortest
/// panel has. Drawing and encoding only: an error here is the movie's own (no frames, positions
/// not finite, past `deadline`), which the runner records on the run; writing the bytes is
/// the caller's, and a file that cannot be written (a full disk) stops a campaign. One run's
/// movie is part of the run, so its `deadline` is the run's; side-by-side panels have none.
pub fn encode_movie_panels(panels: &[&Movie], deadline: Option<std::time::Instant>) -> anyhow::Result<Vec<u8>> {
    ensure_font()?;
    let frames = panels.iter().map(|m| m.frames.len()).min().unwrap_or(0);
    anyhow::ensure!(frames > 0, "a movie needs at least one frame");
    let view = View::of(panels)?;
    let scales = Scales::of(panels, frames);
    // Frames are drawn into one RGB buffer and encoded into memory (as plotters' GIF backend
    // does, but that one writes to a fixed path itself); the file is then written atomically.
    let encoding = |error: gif::EncodingError| anyhow::anyhow!("cannot encode the movie: {error}");
    let (width, height) = (view.width, view.height);
    let mut pixels = vec![0u8; width as usize * height as usize * 3];
    let mut palette = Palette::default();
    let mut previous: Option<Vec<u8>> = None;
    let mut encoder = gif::Encoder::new(Vec::new(), width as u16, height as u16, &palette.colours).map_err(encoding)?;
    encoder.set_repeat(gif::Repeat::Infinite).map_err(encoding)?;
    for k in 0..frames {
        if deadline.is_some_and(|deadline| std::time::Instant::now() > deadline) {
            return Err(PastDeadline.into());
        }
        draw_frame(&mut pixels, panels, &view, &scales, k)?;
        let now = palette.indices(&pixels);
        let mut frame = gif_frame(&now, previous.as_deref(), width as usize);
        frame.delay = ((FRAME_DELAY_MS + 5) / 10) as u16; // GIF delays are in 1/100 s
        encoder.write_frame(&frame).map_err(encoding)?;
        previous = Some(now);
    }
    encoder.into_inner().map_err(|error| encoding(error.into()))
}

/// Where the panels are drawn, fixed over all frames: the picture's size, the positions as
/// drawn (displacements magnified), the data ranges of a panel with equal scales on both axes,
/// the disc size.
struct View {
    /// The whole picture (pixels): the panels side by side and the colour bar.
    width: u32,
    height: u32,
    /// Each panel's positions (x, y) (m) as drawn, frame by frame.
    shown: Vec<Vec<(Vec<f64>, Vec<f64>)>>,
    x_range: std::ops::Range<f64>,
    y_range: std::ops::Range<f64>,
    /// Metres per pixel.
    scale: f64,
    /// Disc radius (pixels).
    radius: i32,
    /// The factor M displacements are drawn magnified by (1: as they are).
    magnification: f64,
    /// All particles on one line (a chain or a pair): its held particles are walls.
    one_dimensional: bool,
}

impl View {
    fn of(panels: &[&Movie]) -> anyhow::Result<View> {
        let spec = panels[0].spec;
        let panel_width = spec.width - BAR_WIDTH;
        let (width, height) = (panel_width * panels.len() as u32 + BAR_WIDTH, spec.height);
        let (plot_w, plot_h) = (f64::from(panel_width), f64::from(height - HEADER));
        let all = || panels.iter().flat_map(|m| m.frames.iter());
        let (x0, x1) = extremes(all().flat_map(|f| f.x.iter().copied()));
        let (y0, y1) = extremes(all().flat_map(|f| f.y.iter().copied()));
        anyhow::ensure!(x0.is_finite() && y0.is_finite(), "a movie's positions must be finite");
        // All particles on one line (a chain or a pair): its held particles are walls.
        let one_dimensional = y1 == y0;
        let spacing = shortest_bond(panels).unwrap_or((x1 - x0).max(y1 - y0).max(1.0) / 10.0);
        // Displacements u = r(t) − r(0) too small to see against the spacing a (a kick of 0.1
        // m/s moves the nodes of a steel-like lattice by microns) are drawn magnified, at
        // r(0) + M u: the same M for every panel and frame, stated on each frame.
        let largest_displacement = panels
            .iter()
            .flat_map(|m| m.frames.iter().map(move |f| (&m.frames[0], f)))
            .flat_map(|(first, f)| (0..f.x.len()).map(move |i| (f.x[i] - first.x[i]).hypot(f.y[i] - first.y[i])))
            .fold(0.0f64, f64::max);
        // A packing's discs move by their size and more: drawn as they are, in their box.
        let largest_disc =
            panels.iter().flat_map(|m| m.discs.iter().flat_map(|d| d.radius.iter().copied())).fold(0.0, f64::max);
        let magnification = if largest_disc > 0.0 { 1.0 } else { magnification(largest_displacement, spacing) };
        let shown = shown_positions(panels, magnification);
        let drawn = || shown.iter().flatten();
        let (x0, x1) = extremes(drawn().flat_map(|(x, _)| x.iter().copied()));
        let (y0, y1) = extremes(drawn().flat_map(|(_, y)| y.iter().copied()));
        let pad = if largest_disc > 0.0 { largest_disc } else { 0.6 * spacing };
        let scale = (((x1 - x0) / 2.0 + pad) / plot_w * 2.0).max(((y1 - y0) / 2.0 + pad) / plot_h * 2.0);
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        // Smaller discs when the bonds carry colour, so the bonds show between them.
        let disc = if panels.iter().any(|m| m.spec.bond_strain) { 0.2 } else { 0.35 };
        Ok(View {
            width,
            height,
            shown,
            x_range: (cx - scale * plot_w / 2.0)..(cx + scale * plot_w / 2.0),
            y_range: (cy - scale * plot_h / 2.0)..(cy + scale * plot_h / 2.0),
            scale,
            radius: (disc * spacing / scale).clamp(2.0, 14.0) as i32,
            magnification,
            one_dimensional,
        })
    }
}

/// The positions each panel's frames are drawn at: a packing's discs in their box, other
/// particles at r(0) + M (r − r(0)) with the magnification M of every panel.
fn shown_positions(panels: &[&Movie], magnification: f64) -> Vec<Vec<(Vec<f64>, Vec<f64>)>> {
    let magnified = |now: &[f64], start: &[f64]| -> Vec<f64> {
        now.iter().zip(start).map(|(r, r0)| r0 + magnification * (r - r0)).collect()
    };
    panels
        .iter()
        .map(|m| match &m.discs {
            Some(discs) => discs.frames.iter().map(|f| (f.x.clone(), f.y.clone())).collect(),
            None => {
                m.frames.iter().map(|f| (magnified(&f.x, &m.frames[0].x), magnified(&f.y, &m.frames[0].y))).collect()
            }
        })
        .collect()
}

/// The shortest bond (m) at the start of any panel, which sets the disc size and the margin;
/// `None` without bonds of non-zero length.
fn shortest_bond(panels: &[&Movie]) -> Option<f64> {
    let shortest = panels
        .iter()
        .flat_map(|m| m.bonds.iter().map(move |&(i, j, _)| (&m.frames[0], i, j)))
        .map(|(first, i, j)| (first.x[i] - first.x[j]).hypot(first.y[i] - first.y[j]))
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    shortest.is_finite().then_some(shortest)
}

/// The colour scales, shared by every panel and frame: the fastest speed (m/s) and, when bonds
/// are coloured, the strain of full colour (0: no bond strained).
struct Scales {
    fastest: f64,
    largest_strain: f64,
    /// A packing's largest disc load Σ|f| (N) over its frames (the smallest positive number
    /// when there is none, so the colours divide by it) and contact force |f| (N, 0: none).
    largest_load: f64,
    largest_force: f64,
}

impl Scales {
    fn of(panels: &[&Movie], frames: usize) -> Scales {
        // Colours span the speeds after the first frame: a kicked node's start speed would leave
        // a spreading 2D wave too dark to see; it is drawn at the top colour (clamped) instead.
        let skip = usize::from(frames > 1);
        let fastest = panels
            .iter()
            .flat_map(|m| m.frames[skip..].iter())
            .flat_map(|f| f.speed.iter().copied())
            .fold(0.0f64, f64::max);
        // Bond strain on a diverging scale that saturates at the 99th percentile of |ε| over the
        // run: a kick strains its first bonds far more than the wave it sends, which would
        // otherwise fade to white.
        let mut strains: Vec<f64> = panels
            .iter()
            .filter(|m| m.spec.bond_strain)
            .flat_map(|m| m.frames.iter().flat_map(move |f| m.bonds.iter().map(move |b| strain(f, b).abs())))
            .filter(|e| *e > 0.0)
            .collect();
        strains.sort_by(f64::total_cmp);
        // A packing's random start overlaps far more than its relaxed state: the loads and
        // forces after the first frame set the scales, so the force chains of the relaxed
        // packing span them (the start is drawn at the top colour and width, clamped).
        let disc_frames = || panels.iter().flat_map(|m| m.discs.iter().flat_map(|d| d.frames[skip..].iter()));
        Scales {
            fastest: if fastest > 0.0 { fastest } else { 1.0 },
            largest_strain: strains.get(strains.len() * 99 / 100).copied().unwrap_or(0.0),
            largest_load: disc_frames().flat_map(|f| f.load.iter().copied()).fold(f64::MIN_POSITIVE, f64::max),
            largest_force: disc_frames().flat_map(|f| f.contacts.iter().map(|c| c.2)).fold(0.0, f64::max),
        }
    }
}

/// A bond's strain ε = (|r_ij| − rest)/rest in `frame`.
fn strain(frame: &Frame, &(i, j, rest): &(usize, usize, f64)) -> f64 {
    (frame.x[i] - frame.x[j]).hypot(frame.y[i] - frame.y[j]) / rest - 1.0
}

/// Draws frame `k` of every panel and the colour bar into `pixels` (RGB rows of `view.width`).
fn draw_frame(pixels: &mut [u8], panels: &[&Movie], view: &View, scales: &Scales, k: usize) -> anyhow::Result<()> {
    let root = BitMapBackend::with_buffer(pixels, (view.width, view.height)).into_drawing_area();
    root.fill(&WHITE).map_err(draw_error)?;
    let (plots, bar) = root.split_horizontally(view.width - BAR_WIDTH);
    let areas = plots.split_evenly((1, panels.len()));
    for ((movie, area), positions) in panels.iter().zip(&areas).zip(&view.shown) {
        let (header, body) = area.split_vertically(HEADER);
        draw_header(&header, movie, k, view.magnification)?;
        match &movie.discs {
            Some(discs) => draw_discs(&body, discs, k, view, scales)?,
            None => draw_particles(&body, movie, &positions[k], &movie.frames[k], view, scales)?,
        }
    }
    let strained = scales.largest_strain > 0.0;
    let colours = if panels.iter().any(|m| m.discs.is_some()) {
        (scales.largest_load, "Σ|f| (N)")
    } else {
        (scales.fastest, "|v| (m/s)")
    };
    draw_colour_bar(&bar, colours, strained.then_some(scales.largest_strain), view.height)?;
    root.present().map_err(draw_error)
}

/// A panel's header at frame `k`: the title, the time (or the frame's caption) and the
/// magnification, if any.
fn draw_header(
    header: &DrawingArea<BitMapBackend<'_>, Shift>,
    movie: &Movie,
    k: usize,
    magnification: f64,
) -> anyhow::Result<()> {
    let font = ("sans-serif", 15).into_font().color(&BLACK);
    header.draw(&Text::new(movie.title.clone(), (8, 4), font.clone())).map_err(draw_error)?;
    let time = movie.frames[k].time;
    let when = movie
        .captions
        .get(k)
        .cloned()
        .unwrap_or_else(|| format!("t = {} s = {} t_c", readable(time), readable(time / movie.t_c)));
    header.draw(&Text::new(when, (8, 22), font.clone())).map_err(draw_error)?;
    // A line of its own: beside the time, which grows frame by frame, it ran off a narrow frame.
    if magnification > 1.0 {
        let enlarged = format!("displacements × {magnification}");
        header.draw(&Text::new(enlarged, (8, 40), font)).map_err(draw_error)?;
    }
    Ok(())
}

/// A panel's bonds, discs and supports at the positions `(x, y)` drawn for `frame`.
fn draw_particles(
    body: &DrawingArea<BitMapBackend<'_>, Shift>,
    movie: &Movie,
    (x, y): &(Vec<f64>, Vec<f64>),
    frame: &Frame,
    view: &View,
    scales: &Scales,
) -> anyhow::Result<()> {
    let mut ctx =
        ChartBuilder::on(body).build_cartesian_2d(view.x_range.clone(), view.y_range.clone()).map_err(draw_error)?;
    let coloured = movie.spec.bond_strain && scales.largest_strain > 0.0;
    ctx.draw_series(movie.bonds.iter().map(|bond @ &(i, j, _)| {
        let style = if coloured {
            diverging(strain(frame, bond) / scales.largest_strain).stroke_width(2)
        } else {
            RGBColor(170, 170, 170).stroke_width(1)
        };
        PathElement::new(vec![(x[i], y[i]), (x[j], y[j])], style)
    }))
    .map_err(draw_error)?;
    let radius = view.radius;
    ctx.draw_series(
        (0..frame.x.len())
            .map(|i| Circle::new((x[i], y[i]), radius, speed_color(frame.speed[i] / scales.fastest).filled())),
    )
    .map_err(draw_error)?;
    // Supports over their discs, sized in pixels (`scale` m per pixel).
    let half = f64::from(radius) * view.scale;
    ctx.draw_series(movie.supports.iter().map(|&(i, held)| {
        let (cx, cy) = (x[i], y[i]);
        let (w, h, style) = if view.one_dimensional {
            (0.4 * half, 3.0 * half, BLACK.filled())
        } else if held.x && held.y {
            (half, half, BLACK.filled())
        } else {
            (half, half, BLACK.stroke_width(2))
        };
        Rectangle::new([(cx - w, cy - h), (cx + w, cy + h)], style)
    }))
    .map_err(draw_error)?;
    Ok(())
}

/// Pixels of a contact line carrying the force `force` of the run's largest `largest` (N),
/// between discs whose smallest is `small` px across: 1 px for a vanishing force, growing
/// linearly to half that disc (at most 8 px) at the largest, so a chain stays inside its discs.
pub fn force_line_width(force: f64, largest: f64, small: f64) -> u32 {
    let widest = (0.5 * small).clamp(1.0, 8.0);
    if largest > 0.0 { 1 + ((widest - 1.0) * (force / largest).clamp(0.0, 1.0)).round() as u32 } else { 1 }
}

/// Frame `k` of a packing: its contacts as black lines ([`force_line_width`]; those under 1e-6 of
/// the largest force left out) under its discs,
/// each a circle of its own radius (to scale) coloured by its load Σ|f| on the speed scale and
/// outlined, so the lines show where the discs overlap and through the gaps.
fn draw_discs(
    body: &DrawingArea<BitMapBackend<'_>, Shift>,
    discs: &Discs,
    k: usize,
    view: &View,
    scales: &Scales,
) -> anyhow::Result<()> {
    let mut ctx =
        ChartBuilder::on(body).build_cartesian_2d(view.x_range.clone(), view.y_range.clone()).map_err(draw_error)?;
    let frame = &discs.frames[k];
    let pixels = |r: f64| ((r / view.scale).round() as i32).max(1);
    let load = |i: usize| speed_color(frame.load[i] / scales.largest_load);
    ctx.draw_series(
        (0..frame.x.len()).map(|i| Circle::new((frame.x[i], frame.y[i]), pixels(discs.radius[i]), load(i).filled())),
    )
    .map_err(draw_error)?;
    ctx.draw_series(
        (0..frame.x.len()).map(|i| {
            Circle::new((frame.x[i], frame.y[i]), pixels(discs.radius[i]), RGBColor(90, 90, 90).stroke_width(1))
        }),
    )
    .map_err(draw_error)?;
    let small = 2.0 * discs.radius.iter().copied().fold(f64::INFINITY, f64::min) / view.scale;
    // A contact under 1e-6 of the largest force is an overlap the minimiser left at its floor
    // (an unjammed packing's), not a force chain: not drawn.
    let carrying = frame.contacts.iter().filter(|c| c.2 > 1e-6 * scales.largest_force);
    ctx.draw_series(carrying.map(|&(from, to, force)| {
        PathElement::new(vec![from, to], BLACK.stroke_width(force_line_width(force, scales.largest_force, small)))
    }))
    .map_err(draw_error)?;
    let side = frame.side;
    ctx.draw_series(std::iter::once(PathElement::new(
        vec![(0.0, 0.0), (side, 0.0), (side, side), (0.0, side), (0.0, 0.0)],
        RGBColor(200, 0, 0).stroke_width(1),
    )))
    .map_err(draw_error)?;
    Ok(())
}

/// The magnification M of displacements whose largest is `largest` (m) in a network of
/// spacing `spacing` (m): the largest 1, 2 or 5 × 10^k that keeps M·largest within 0.3
/// spacing; 1 (drawn as they are) when the displacements are already visible.
pub fn magnification(largest: f64, spacing: f64) -> f64 {
    let target = 0.3 * spacing / largest;
    if !target.is_finite() || target < 2.0 {
        return 1.0;
    }
    let decade = 10f64.powi(target.log10().floor() as i32);
    [5.0, 2.0, 1.0].into_iter().map(|m| m * decade).find(|&m| m <= target).unwrap_or(decade)
}

/// `value` with four significant digits, plain from 0.001 to 99 999 (`22.57`, `0.004443`),
/// scientific beyond (`1.234e-7`): a time stamp read at a glance, not `2.2570e1`.
pub fn readable(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let exponent = value.abs().log10().floor() as i32;
    if (-3..5).contains(&exponent) {
        let decimals = (3 - exponent).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.3e}")
    }
}

/// The movies' one colour table (a GIF's global palette): what the frames are drawn with,
/// quantised to 32 colours (8 greys for text and grey bonds, 12 steps of the speed scale, 11 of
/// the strain scale), index 0 for "as in the frame before". Few colours (LZW codes start at 6
/// bits instead of 9) and unchanged pixels left transparent compress: measured on the
/// coursework's movies, a third to a half of the bytes of a palette fitted to each whole frame.
pub struct Palette {
    /// RGB triples, index 0 the transparent one.
    pub colours: Vec<u8>,
    /// The nearest index of every colour met so far.
    nearest: std::collections::HashMap<[u8; 3], u8>,
}

/// The transparent index: the pixel is as in the previous frame.
pub const UNCHANGED: u8 = 0;

impl Default for Palette {
    /// The 32 colours, none met yet.
    fn default() -> Palette {
        let greys = [0, 60, 100, 140, 170, 200, 230, 255].map(|g| RGBColor(g, g, g));
        let speeds = (0..12).map(|s| speed_color(f64::from(s) / 11.0));
        let strains = (0..11).map(|s| diverging(f64::from(s) / 5.0 - 1.0));
        let mut colours = vec![255, 0, 255];
        for RGBColor(r, g, b) in greys.into_iter().chain(speeds).chain(strains) {
            colours.extend([r, g, b]);
        }
        Palette { colours, nearest: std::collections::HashMap::new() }
    }
}

impl Palette {
    /// The index of the palette colour nearest to `rgb` (squared RGB distance), never 0.
    fn index(&mut self, rgb: [u8; 3]) -> u8 {
        let colours = &self.colours;
        *self.nearest.entry(rgb).or_insert_with(|| {
            let distance =
                |i: usize| -> i32 { (0..3).map(|c| (i32::from(colours[3 * i + c]) - i32::from(rgb[c])).pow(2)).sum() };
            (1..colours.len() / 3).min_by_key(|&i| distance(i)).expect("the palette has colours") as u8
        })
    }

    /// RGB `pixels` as palette indices.
    pub fn indices(&mut self, pixels: &[u8]) -> Vec<u8> {
        super::by_runs(pixels, |rgb| self.index(rgb))
    }
}

/// Palette indices `now` (rows of `width`) as a GIF frame: after the first, only the box of
/// pixels whose colour changed since `previous` (indices: a shade that rounds to the same
/// palette colour is no change), unchanged ones in it transparent over the frame kept below.
pub fn gif_frame(now: &[u8], previous: Option<&[u8]>, width: usize) -> gif::Frame<'static> {
    let height = now.len() / width;
    let changed = |i: usize| previous.is_none_or(|p| p[i] != now[i]);
    let (mut x0, mut y0, mut x1, mut y1) = (width, height, 0, 0);
    for i in (0..width * height).filter(|&i| changed(i)) {
        (x0, y0, x1, y1) = (x0.min(i % width), y0.min(i / width), x1.max(i % width + 1), y1.max(i / width + 1));
    }
    if x1 == 0 {
        (x0, y0, x1, y1) = (0, 0, 1, 1); // nothing changed: one transparent pixel
    }
    let mut buffer = Vec::with_capacity((x1 - x0) * (y1 - y0));
    for y in y0..y1 {
        buffer.extend(((y * width + x0)..(y * width + x1)).map(|i| if changed(i) { now[i] } else { UNCHANGED }));
    }
    gif::Frame {
        left: x0 as u16,
        top: y0 as u16,
        width: (x1 - x0) as u16,
        height: (y1 - y0) as u16,
        buffer: buffer.into(),
        transparent: previous.map(|_| UNCHANGED),
        dispose: gif::DisposalMethod::Keep,
        ..gif::Frame::default()
    }
}

/// The colour bar: 0 at the bottom, the fastest speed at the top; below it, when bonds are
/// coloured, the strain scale (red stretched, blue compressed, full colour from ±`largest_strain`).
fn draw_colour_bar(
    bar: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    (largest_value, label): (f64, &str),
    largest_strain: Option<f64>,
    height: u32,
) -> anyhow::Result<()> {
    let (top, bottom) = (HEADER as i32, height as i32 - 20);
    let steps = 40;
    for s in 0..steps {
        let fraction = s as f64 / (steps - 1) as f64;
        let y = bottom - ((bottom - top) as f64 * (s + 1) as f64 / steps as f64) as i32;
        let h = ((bottom - top) as f64 / steps as f64).ceil() as i32 + 1;
        bar.draw(&Rectangle::new([(10, y), (30, y + h)], speed_color(fraction).filled())).map_err(draw_error)?;
    }
    let style = ("sans-serif", 12).into_font().color(&BLACK);
    bar.draw(&Text::new(format!("{largest_value:.2e}"), (34, top), style.clone())).map_err(draw_error)?;
    bar.draw(&Text::new("0".to_string(), (34, bottom - 12), style.clone())).map_err(draw_error)?;
    bar.draw(&Text::new(label.to_string(), (4, 8), style.clone())).map_err(draw_error)?;
    if let Some(largest) = largest_strain {
        // Bonds: red stretched, blue compressed, full colour at ±largest.
        bar.draw(&Text::new("ε:".to_string(), (2, bottom + 4), style.clone())).map_err(draw_error)?;
        bar.draw(&Text::new(format!("±{largest:.1e}"), (16, bottom + 4), style.color(&diverging(1.0))))
            .map_err(draw_error)?;
    }
    Ok(())
}
