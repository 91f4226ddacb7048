//! When and how loops over particles run on several threads. Work is split into fixed chunks
//! (independent of the thread count), so results are the same for any `-j`.

/// Systems smaller than this run every loop on one thread: below it a step takes well under a
/// millisecond and handing work to threads costs more than it saves.
pub const PARALLEL_MIN_PARTICLES: usize = 10_000;

/// Particles per chunk of an element-wise loop (four 32 KiB arrays fit in L2).
pub const CHUNK: usize = 4096;

/// True when a loop over `n` particles should be split over the rayon pool.
pub fn worth_splitting(n: usize) -> bool {
    n >= PARALLEL_MIN_PARTICLES && rayon::current_num_threads() > 1
}

/// Runs `kernel(offset, a, b, ..., c, ...)` on matching chunks of the mutable slices
/// `[a, b, ...]` and the shared slices `[c, ...]` (all the same length), where `offset` is the
/// index of the chunk's first element; on the rayon pool when the system is large enough, on
/// the calling thread otherwise. The slices must be local variables (identifiers).
macro_rules! for_chunks {
    ($kernel:expr, [$($m:ident),+], [$($r:ident),*]) => {{
        let kernel = $kernel;
        let n = [$($m.len()),+][0];
        if $crate::sim::parallel::worth_splitting(n) {
            use rayon::prelude::*;
            let chunk = $crate::sim::parallel::CHUNK;
            ($($m.par_chunks_mut(chunk),)+ $($r.par_chunks(chunk),)*)
                .into_par_iter()
                .enumerate()
                .for_each(|(index, ($($m,)+ $($r,)*))| kernel(index * chunk, $($m,)+ $($r,)*));
        } else {
            kernel(0, $($m,)+ $($r,)*);
        }
    }};
}
pub(crate) use for_chunks;

/// Inverse masses of the particles: one array, or one value when all masses are equal (so the
/// particle loops read one array less).
pub trait InverseMass: Copy + Send + Sync {
    /// The values of particles `offset..offset + len`.
    fn part(self, offset: usize, len: usize) -> Self;
    /// 1/m of particle `i` of this part.
    fn at(self, i: usize) -> f64;
}

impl InverseMass for &[f64] {
    #[inline(always)]
    fn part(self, offset: usize, len: usize) -> Self {
        &self[offset..offset + len]
    }
    #[inline(always)]
    fn at(self, i: usize) -> f64 {
        self[i]
    }
}

/// The same 1/m (1/kg) for every particle.
#[derive(Clone, Copy, Debug)]
pub struct Uniform(pub f64);

impl InverseMass for Uniform {
    #[inline(always)]
    fn part(self, _offset: usize, _len: usize) -> Self {
        self
    }
    #[inline(always)]
    fn at(self, _i: usize) -> f64 {
        self.0
    }
}
