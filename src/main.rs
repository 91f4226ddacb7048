//! The `mdsolids` command: see `mdsolids --help`.

/// Large arrays start at staggered offsets in their pages (`mdsolids::alloc`): the force loop
/// runs 1.2–1.3× faster than with the arrays all page-aligned.
#[global_allocator]
static ALLOCATOR: mdsolids::alloc::Coloured = mdsolids::alloc::Coloured;

fn main() {
    // A reader that stops early (`mdsolids plan big.yaml | head`) closes the pipe: die of
    // SIGPIPE quietly, as `ls | head` does, instead of Rust's default (SIGPIPE ignored, the
    // next `println!` panics with a backtrace). What is stored is stored atomically.
    // SAFETY: resets one signal's disposition to the default before any thread starts.
    unsafe { libc::signal(libc::SIGPIPE, libc::SIG_DFL) };
    if let Err(error) = mdsolids::cli::run() {
        eprintln!("Error: {error:#}");
        std::process::exit(1);
    }
}
