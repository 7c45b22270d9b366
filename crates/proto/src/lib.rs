//! The generated wire types, client and server of `railcontact.v1` (see
//! the repository's `proto/railcontact/v1/railcontact.proto`, compiled by
//! `build.rs`).

#![allow(missing_docs, clippy::all, clippy::pedantic)]

tonic::include_proto!("railcontact.v1");

/// The encoded FileDescriptorSet of the API, for server reflection.
pub const FILE_DESCRIPTOR_SET: &[u8] =
    include_bytes!(concat!(env!("OUT_DIR"), "/railcontact_descriptor.bin"));
