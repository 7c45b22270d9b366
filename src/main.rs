//! The `railcontact` command: the command line's subcommands
//! ([`railcontact::cli`]) and `serve` ([`railcontact::service::command`]).
//! This is the one place that names both front ends.

use clap::{Parser, Subcommand};

use railcontact::cli;
use railcontact::service::command::{self, ServeArgs};

/// Frictional wheel/rail contact: Kalker's exact theory, conformal contact
/// (CECT), Hertz and FASTSIM.
#[derive(Debug, Parser)]
#[command(name = "railcontact", version, about, long_about = None)]
struct Railcontact {
    /// What to do.
    #[command(subcommand)]
    command: Command,
}

/// Every subcommand.
#[derive(Debug, Subcommand)]
enum Command {
    #[command(flatten)]
    Cli(cli::Command),
    /// Serve the gRPC contact service (package railcontact.v1, see
    /// proto/railcontact/v1/railcontact.proto) until SIGTERM or Ctrl-C.
    ///
    /// Runs with no configuration on 127.0.0.1:50051. Settings come in
    /// layers: defaults, then --config FILE.toml, then the environment
    /// variables RAILCONTACT_KEY (the key in capitals), then these flags;
    /// every key is listed below. Logs go to stderr, filtered by RUST_LOG
    /// (default info), in colour only on a terminal and without NO_COLOR.
    #[command(after_help = command::settings_help())]
    Serve(ServeArgs),
}

fn main() {
    let code = match Railcontact::parse().command {
        Command::Cli(command) => cli::run(command),
        Command::Serve(args) => command::run(&args),
    };
    std::process::exit(code);
}
