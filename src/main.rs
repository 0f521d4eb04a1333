//! The `asperity` command line: run, plan and validate studies, print the study schema.
//! The only place that prints to the terminal.

#![deny(unsafe_code)]

mod cli;
#[allow(unsafe_code)]
mod huge_pages;

use std::process::ExitCode;

use clap::Parser;

#[global_allocator]
static ALLOCATOR: huge_pages::HugePageAllocator = huge_pages::HugePageAllocator;

fn main() -> ExitCode {
    huge_pages::return_freed_blocks();
    // A closed pipe ends the process as it ends every Unix filter (`asperity inspect f | head`).
    #[cfg(unix)]
    sigpipe::reset();
    let args = cli::Cli::parse();
    cli::init_tracing(args.verbose);
    if let Err(e) = cli::interrupt::install() {
        eprintln!("warning: Ctrl-C cannot be handled cleanly ({e}); it ends the process at once");
    }
    match cli::run(args) {
        Ok(code) => code,
        Err(e) if e.downcast_ref::<cli::interrupt::Interrupted>().is_some() => {
            eprintln!("interrupted");
            ExitCode::from(cli::interrupt::EXIT_CODE)
        }
        Err(e) => {
            eprintln!("error: {}", cli::error_text(&e));
            ExitCode::from(1)
        }
    }
}
