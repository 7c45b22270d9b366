//! What the two front ends (the command line, `cli`, and the service) share, and
//! nothing else: neither imports the other, both import this.
//!
//! | item | what |
//! |---|---|
//! | [`pb`] | the generated wire types, client and server of `railcontact.v1` |
//! | [`BUILTIN_PAIR`] | the profile pair every server registers at start |
//! | [`EXIT_BAD_INPUT`], [`EXIT_FAILURE`] | the process exit codes of every subcommand |
//! | [`error_chain`] | an error with its sources, for messages to a user |

pub mod pb;

/// Name of the built-in profile pair (S1002 wheel on UIC60 rail, the
/// Manchester benchmark's) that every server registers at start; clients
/// may name it in place of a pair id (`RegisterProfilePairRequest.builtin_pair`).
pub const BUILTIN_PAIR: &str = "mbench_s1002_uic60";

/// Exit code for bad input (case file, options, settings).
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for any other failure.
pub const EXIT_FAILURE: i32 = 1;

/// An error with its sources, one after the other (transport errors say
/// little at the top).
pub fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut source = e.source();
    while let Some(c) = source {
        let t = c.to_string();
        if !s.contains(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
        source = c.source();
    }
    s
}
