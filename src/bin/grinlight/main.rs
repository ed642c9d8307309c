//! The grinlight command line: parses the arguments ([`args`]), calls one library function per
//! command ([`grinlight::commands`]) and shows its progress and report ([`console`]).

mod args;
mod console;

use args::{Cli, Command};
use clap::error::{ContextKind, ContextValue, ErrorKind};
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

/// The command line, or exits with clap's message; a flag `render` does not know is refused
/// in the scene file's words for a key it does not know, listing the settings.
fn parse() -> Cli {
    let e = match Cli::try_parse() {
        Ok(cli) => return cli,
        Err(e) => e,
    };
    let render = std::env::args().nth(1).as_deref() == Some("render");
    if let (true, ErrorKind::UnknownArgument, Some(ContextValue::String(given))) =
        (render, e.kind(), e.get(ContextKind::InvalidArg))
    {
        // A stray word is not a flag: clap says what it is.
        let Some(flag) = given.strip_prefix("--") else {
            e.exit()
        };
        let flag = flag.split('=').next().unwrap_or(flag);
        let name = flag.replace('-', "_");
        let flag = format!("--{flag}");
        eprintln!(
            "error: {flag}: {}; render's other options: grinlight render --help",
            grinlight::settings::unknown(&name, &["no_table"])
        );
        std::process::exit(2);
    }
    e.exit()
}

fn main() {
    let cli = parse();
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
