//! Drawing, below both the runner and the report: the generic line chart and heat map every
//! figure is drawn with (`chart.rs`), the animated GIFs of runs (`movie.rs`), which the
//! runner writes beside each run's record, and a movie's frames on paper (`filmstrip.rs`).

pub mod chart;
pub mod filmstrip;
pub mod movie;

pub use self::movie::{Movie, PastDeadline, encode_movie_panels, speed_color, write_movie};
