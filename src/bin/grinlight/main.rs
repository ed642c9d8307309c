//! The grinlight command line: parses the arguments ([`args`]), calls one library function per
//! command ([`grinlight::commands`]) and shows its progress and report ([`console`]).

mod args;
mod console;

use args::{Cli, Command};
use clap::Parser;
use grinlight::commands;
use grinlight::error::Error;

/// Runs the command; true when it finished, false when an interrupt cut it short.
fn run(cli: Cli, console: &console::Console) -> Result<bool, Error> {
    Ok(match cli.command {
        Command::Render(args) => !commands::render(&args.into(), console)?.interrupted,
        Command::Validate(args) => {
            commands::validate(&args.into(), console)?;
            true
        }
        Command::Trace(args) => {
            commands::trace(&args.into(), console)?;
            !grinlight::interrupt::requested()
        }
        Command::Convert(args) => {
            for told in commands::convert(&args.into())? {
                commands::Observer::warning(console, &told);
            }
            true
        }
        Command::Merge(args) => {
            commands::merge(&args.into(), console)?;
            true
        }
    })
}

fn main() {
    let cli = Cli::parse();
    let console = console::Console::new();
    console::install_interrupt_handler();
    let code = match run(cli, &console) {
        Ok(true) => 0,
        Ok(false) => console::INTERRUPTED,
        Err(e) => {
            console.clear();
            match &e {
                Error::Setting { key, message } => {
                    eprintln!("error: {} {message}", args::flag(key))
                }
                _ => eprintln!("error: {e}"),
            }
            match e {
                Error::Interrupted(_) => console::INTERRUPTED,
                _ => 1,
            }
        }
    };
    std::process::exit(code);
}
