//! Drawing, below both the runner and the report: the generic line chart and heat map every
//! figure is drawn with (`chart.rs`, its legend placed by `legend.rs`), the animated GIFs of
//! runs (`movie.rs`), which the runner writes beside each run's record, and a movie's frames on
//! paper (`filmstrip.rs`).

pub mod chart;
pub mod filmstrip;
mod legend;
pub mod movie;

pub use self::movie::{Movie, PastDeadline, encode_movie_panels, speed_color, write_movie};

/// `lookup` of every colour of `pixels` (RGB triples), called once per run of equal colours:
/// a picture is mostly runs of one colour (the background, a disc's fill, a line), and the
/// lookups behind it hash the colour (a twelfth of a coursework share's run when every pixel
/// was hashed).
pub(crate) fn by_runs<T: Copy>(pixels: &[u8], mut lookup: impl FnMut([u8; 3]) -> T) -> Vec<T> {
    let mut last: Option<([u8; 3], T)> = None;
    let mut value_of = |rgb: [u8; 3]| match last {
        Some((colour, value)) if colour == rgb => value,
        _ => {
            let value = lookup(rgb);
            last = Some((rgb, value));
            value
        }
    };
    pixels.chunks_exact(3).map(|p| value_of([p[0], p[1], p[2]])).collect()
}
