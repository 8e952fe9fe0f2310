//! The generated types of `proto/floe/v1/scenes.proto` (package `floe.v1`):
//! messages, the `SceneService` server trait and client. Generated code stays at
//! the edge: the server converts it in one place (`floe-server`'s `convert.rs`).
#![allow(missing_docs, clippy::all, clippy::pedantic, missing_debug_implementations)]

tonic::include_proto!("floe.v1");

/// The encoded file descriptor set of the contract, for gRPC reflection.
pub const FILE_DESCRIPTOR_SET: &[u8] = tonic::include_file_descriptor_set!("floe_v1_descriptor");
