//! The `railcontact` command: see [`railcontact::cli`].

use clap::Parser;

fn main() {
    let cli = railcontact::cli::Cli::parse();
    std::process::exit(railcontact::cli::run(cli));
}
