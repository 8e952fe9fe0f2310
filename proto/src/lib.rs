//! # floe-proto
//!
//! The wire format of particle frames: snapshots of a scene's particles streamed to
//! browsers and scripted clients. One definition, used by the server to encode and by
//! Rust clients to decode; the browser viewer mirrors the layout documented in
//! [`header`], [`stream`] and [`quantize`], checked against the golden frames in
//! `proto/testdata/`.
//!
//! Two modes ([`Mode`]):
//!
//! - **Unordered**, for viewers: positions are quantised over the scene bounds (one step for
//!   all three axes), particles are sorted by the Morton key of their quantised position and
//!   the sorted keys are delta-coded; other channels follow the same order, each value
//!   predicted from the previous particle's. 3.4 bytes per particle at 16-bit positions on
//!   the dam break, 2.7 at 14 bits (`docs/benchmarks.md`).
//! - **Identity-ordered**, for clients that follow particles: particle `i` stays at index `i`;
//!   delta frames store each position code's difference from its prediction from the previous
//!   frame (or the previous two, extrapolated with a fitted velocity gain per axis, so frames
//!   unequally spaced in time predict as well as equally spaced ones), with a keyframe at a
//!   configurable interval or on request ([`Encoder::force_keyframe`]). A decoder that does not hold a delta
//!   frame's base returns [`DecodeError::NeedKeyframe`]. At 16 bits with a keyframe every 30
//!   frames: 0.7 to 1.5 bytes per particle for frames 1 to 32 solver steps apart, 2.8 for
//!   frames 1/60 s of simulated time apart.
//!
//! Stored values are Rice-coded in blocks of 128, each block with its own parameter
//! ([`stream`]). Decoding never panics: every length is checked against the frame, and the
//! particle count and frame size against the caller's [`Limits`].
//!
//! ```
//! use floe_proto::{Bounds, Decoder, Encoder, EncoderConfig, FrameInput, Limits, Mode};
//!
//! let bounds = Bounds { min: [0.0; 3], max: [2.0, 1.2, 0.25] }.with_margin(0.05);
//! let mut encoder = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 7, bounds))?;
//! let positions = vec![[0.5, 0.25, 0.1], [1.0, 0.5, 0.2]];
//! let bytes = encoder.encode(0, 0.0, &FrameInput::positions(&positions))?;
//!
//! let frame = Decoder::new(Limits::default()).decode(&bytes)?;
//! let error = frame.header.channels[0].ranges[0].max_error;
//! assert!((frame.positions[1][0] - 1.0).abs() <= error * 1.01);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bits;
pub mod channels;
mod codes;
mod decoder;
mod encoder;
mod error;
pub mod export;
mod frame;
pub mod header;
mod morton;
mod particles;
#[cfg(feature = "grpc")]
pub mod pb;
mod predict;
pub mod quantize;
mod reader;
pub mod stream;
mod unordered;
mod zigzag;

pub use channels::{CHANNELS, ChannelDef, ChannelKind};
pub use decoder::{Decoder, Limits, read_header};
pub use encoder::{Bounds, Encoder, EncoderConfig};
pub use error::{DecodeError, EncodeError};
pub use frame::{Frame, FrameInput, GridInfo, Values, ValuesRef};
pub use header::{ChannelInfo, ComponentRange, Header, Mode, Predictor};
pub use particles::Particles;
