//! The generated wire types, client and server of `railcontact.v1`: the
//! `railcontact-proto` crate (`crates/proto`), which the CONTACT library's
//! forwarding client shares.

pub use railcontact_proto::*;
