//! A movie on paper: a few of its frames (the first, the last and evenly between) side by side
//! in one PNG, which a printed page shows in place of the animated GIF (a GIF prints as its
//! first frame only). Made from the GIF's own bytes, so every movie the runner drew, one run's
//! or side by side, has its strip without drawing a frame again.

/// Frames a strip shows: the first, the last and two between, in a 2 × 2 grid.
pub const FRAMES: usize = 4;

/// Gap (pixels) between the frames of a strip, in the colour of the first frame's top-left pixel.
const GAP: usize = 6;

/// A strip of the animated GIF `gif`: its bytes (an indexed PNG on the GIF's own palette, so no
/// colour changes), its size in pixels, and which frames it shows (1-based) of how many.
pub struct Filmstrip {
    /// The PNG file's bytes.
    pub png: Vec<u8>,
    /// Width and height (pixels).
    pub size: (u32, u32),
    /// The frames shown, counted from 1.
    pub shown: Vec<usize>,
    /// The movie's frame count.
    pub frames: usize,
}

/// The strip of `gif`: every frame composed over the ones before it (this program's movies
/// keep each frame and draw only the box that changed, its unchanged pixels transparent), the
/// [`FRAMES`] chosen laid out two to a row.
pub fn filmstrip(gif: &[u8]) -> anyhow::Result<Filmstrip> {
    let decoding = |error: gif::DecodingError| anyhow::anyhow!("cannot read the movie: {error}");
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options.read_info(gif).map_err(decoding)?;
    let palette =
        decoder.global_palette().map(<[u8]>::to_vec).ok_or_else(|| anyhow::anyhow!("a movie without a palette"))?;
    let (width, height) = (decoder.width() as usize, decoder.height() as usize);
    let mut canvas = vec![0u8; width * height];
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().map_err(decoding)? {
        let (left, top, w) = (frame.left as usize, frame.top as usize, frame.width as usize);
        for (i, &index) in frame.buffer.iter().enumerate() {
            let (x, y) = (left + i % w, top + i / w);
            if Some(index) != frame.transparent && x < width && y < height {
                canvas[y * width + x] = index;
            }
        }
        frames.push(canvas.clone());
    }
    anyhow::ensure!(!frames.is_empty(), "a movie without frames");
    let shown = chosen(frames.len());
    let picked: Vec<&[u8]> = shown.iter().map(|&k| frames[k].as_slice()).collect();
    let (png, size) = grid(&picked, (width, height), &palette)?;
    Ok(Filmstrip { png, size, shown: shown.iter().map(|k| k + 1).collect(), frames: frames.len() })
}

/// Up to [`FRAMES`] frame indices of `count`, evenly spread from the first to the last.
fn chosen(count: usize) -> Vec<usize> {
    let mut shown: Vec<usize> = (0..FRAMES).map(|i| (i * (count - 1) + (FRAMES - 1) / 2) / (FRAMES - 1)).collect();
    shown.dedup();
    shown
}

/// `frames` (palette indices, each `size`) two to a row, [`GAP`] apart, as an indexed PNG.
fn grid(frames: &[&[u8]], size: (usize, usize), palette: &[u8]) -> anyhow::Result<(Vec<u8>, (u32, u32))> {
    let (width, height) = size;
    let columns = frames.len().min(2);
    let rows = frames.len().div_ceil(2);
    let (total_w, total_h) = (columns * width + (columns - 1) * GAP, rows * height + (rows - 1) * GAP);
    let mut pixels = vec![frames[0][0]; total_w * total_h];
    for (n, frame) in frames.iter().enumerate() {
        let (x0, y0) = ((n % 2) * (width + GAP), (n / 2) * (height + GAP));
        for y in 0..height {
            let at = (y0 + y) * total_w + x0;
            pixels[at..at + width].copy_from_slice(&frame[y * width..(y + 1) * width]);
        }
    }
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, total_w as u32, total_h as u32);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(palette.to_vec());
    encoder.set_compression(png::Compression::Best);
    let encoding = |error: png::EncodingError| anyhow::anyhow!("cannot encode a filmstrip as PNG: {error}");
    encoder.write_header().and_then(|mut writer| writer.write_image_data(&pixels)).map_err(encoding)?;
    Ok((bytes, (total_w as u32, total_h as u32)))
}
