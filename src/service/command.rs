//! `railcontact serve`: its options, the list of settings in its help, and
//! the run that turns a bad setting into exit code 2. The binary
//! (`src/main.rs`) puts this subcommand beside the command line's
//! (the `cli` module); neither front end imports the other.

use std::path::PathBuf;

use clap::Args;

use crate::service::config::{ServeConfig, ServeFlags, ENV_PREFIX};
use crate::shared::{EXIT_BAD_INPUT, EXIT_FAILURE};

/// Options of `railcontact serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// Settings file (TOML, the keys listed below; a sample with every key
    /// at its default: deploy/serve.toml).
    #[arg(long, value_name = "FILE.toml")]
    pub config: Option<PathBuf>,
    /// The settings given as flags.
    #[command(flatten)]
    pub flags: ServeFlags,
}

/// The keys of the settings file of `serve`, in the order of
/// [`ServeConfig`]'s fields (read from its deserializer, so the list
/// follows the struct). Each has the environment variable `RAILCONTACT_` +
/// the key in upper case.
pub fn settings_keys() -> &'static [&'static str] {
    serde_aux::serde_introspection::serde_introspect::<ServeConfig>()
}

/// The environment variable of a settings key.
pub fn env_var(key: &str) -> String {
    format!("{ENV_PREFIX}{}", key.to_ascii_uppercase())
}

/// The list of settings at the end of `serve --help`.
pub fn settings_help() -> String {
    let width = settings_keys().iter().map(|k| k.len()).max().unwrap_or(0);
    let mut text = String::from(
        "Settings: every key of the settings file and its environment variable \
         (meanings and defaults: deploy/serve.toml):\n",
    );
    for key in settings_keys() {
        text.push_str(&format!("  {key:<width$}  {}\n", env_var(key)));
    }
    text
}

/// Loads the settings in their layers and serves until a shutdown signal;
/// returns the process exit code: 0 after a clean shutdown,
/// [`EXIT_BAD_INPUT`] for bad settings (also those the server refuses at
/// start: exposure without protection, unreadable TLS or tokens files),
/// [`EXIT_FAILURE`] otherwise. The error goes to stderr.
pub fn run(args: &ServeArgs) -> i32 {
    let env = |name: &str| std::env::var(name).ok();
    let names = std::env::vars_os().filter_map(|(k, _)| k.into_string().ok());
    for warning in crate::service::config::unknown_env_vars(names) {
        eprintln!("warning: {warning}");
    }
    let result = match ServeConfig::load(args.config.as_deref(), &env, &args.flags) {
        Err(e) => Err((EXIT_BAD_INPUT, format!("serve settings: {e}"))),
        Ok(config) => crate::service::server::serve(&config).map_err(|e| match e.kind() {
            std::io::ErrorKind::InvalidInput => (EXIT_BAD_INPUT, format!("serve: {e}")),
            _ => (EXIT_FAILURE, format!("serve: {e}")),
        }),
    };
    match result {
        Ok(()) => 0,
        Err((code, message)) => {
            eprintln!("error: {message}");
            code
        }
    }
}
