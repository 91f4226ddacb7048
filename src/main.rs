//! The `mdsolids` command: see `mdsolids --help`.

fn main() {
    if let Err(error) = mdsolids::cli::run() {
        eprintln!("Error: {error:#}");
        std::process::exit(1);
    }
}
