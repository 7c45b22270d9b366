//! Compiles the repository's `proto/railcontact/v1/railcontact.proto` without a system
//! `protoc`: protox (a pure-Rust protobuf compiler) parses it into a
//! FileDescriptorSet, tonic-prost-build generates the messages, client and
//! server from that, and the encoded set is kept in OUT_DIR for the
//! server's reflection service.

use std::path::PathBuf;

use prost::Message;

const PROTO: &str = "../../proto/railcontact/v1/railcontact.proto";
const INCLUDE: &str = "../../proto";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // tonic-prost-build 0.14 does not emit this when given a descriptor set.
    println!("cargo:rerun-if-changed={PROTO}");
    let fds = protox::compile([PROTO], [INCLUDE])?;
    let out_dir = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::write(
        out_dir.join("railcontact_descriptor.bin"),
        fds.encode_to_vec(),
    )?;
    tonic_prost_build::configure()
        .build_client(true)
        .build_server(true)
        .compile_fds(fds)?;
    Ok(())
}
