//! `railcontact health --target HOST:PORT [--service NAME]`: one
//! `grpc.health.v1.Health/Check` call. Prints the serving status and exits
//! 0 when it is SERVING, 1 otherwise (NOT_SERVING while the server shuts
//! down, unreachable, no answer in time). Made for container HEALTHCHECKs
//! and exec probes, where no grpc_health_probe is installed.

use std::time::Duration;

use clap::Args;

use super::loadtest::{connect, health, ConnectArgs};
use super::CliError;

/// Options of `railcontact health`.
#[derive(Debug, Clone, Args)]
pub struct HealthArgs {
    /// The server, HOST:PORT.
    #[arg(long, value_name = "HOST:PORT", default_value = "127.0.0.1:50051")]
    pub target: String,
    /// The service to ask about; empty: the whole server. The contact
    /// service is `railcontact.v1.ContactService`.
    #[arg(long, default_value = "")]
    pub service: String,
    /// Time limit to connect and to get the answer, in seconds.
    #[arg(long, default_value_t = 5.0)]
    pub timeout: f64,
    /// TLS and token (the health service itself needs no token).
    #[command(flatten)]
    pub security: ConnectArgs,
}

/// Checks the health; Ok only when SERVING.
pub fn run(args: &HealthArgs) -> Result<(), CliError> {
    if !(args.timeout.is_finite() && args.timeout > 0.0) {
        return Err(CliError::BadInput("--timeout must be > 0".into()));
    }
    let timeout = Duration::from_secs_f64(args.timeout);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|e| CliError::Failure(format!("cannot start the runtime: {e}")))?;
    let status = runtime.block_on(async {
        let channel = connect(&args.target, timeout, &args.security).await?;
        health(channel, &args.service, timeout).await.map_err(|s| {
            CliError::Failure(format!(
                "{}: health check failed: {:?}: {}{}",
                args.target,
                s.code(),
                s.message(),
                super::loadtest::tls_hint(s.message(), args.security.tls_ca.is_some())
            ))
        })
    })?;
    use tonic_health::pb::health_check_response::ServingStatus;
    super::write_stdout(&format!("{}\n", status.as_str_name()))?;
    match status {
        ServingStatus::Serving => Ok(()),
        s => Err(CliError::Failure(format!(
            "{} is {}",
            args.target,
            s.as_str_name()
        ))),
    }
}
