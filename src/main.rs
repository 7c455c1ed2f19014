//! `dlw`: from a sensing joint's design to drawings, laser programs and a working sensor.
//!
//! `main` parses the command line, runs the command and prints the error chain once.

use std::process::ExitCode;

use clap::Parser;

mod cli;

fn main() -> ExitCode {
    // A closed pipe (`dlw inspect --json … | head`) ends dlw quietly, as it ends any Unix tool,
    // instead of a panic in `println!` (Rust ignores SIGPIPE by default). A staging folder left
    // by such an end is removed by the next run (docs/outputs.md).
    // SAFETY: sets a signal's disposition to the default before any other thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            // A library's message may quote a whole input line (a TOML parser does): cut it.
            let message = dlw::limits::clip_message(&format!("{err:#}"));
            eprintln!("dlw: error: {message}");
            ExitCode::FAILURE
        }
    }
}
