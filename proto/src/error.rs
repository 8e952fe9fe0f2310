//! Errors of encoding and decoding frames.

use crate::channels::ChannelKind;

/// Why a frame could not be decoded. The decoder returns one of these for any input it
/// cannot use; it never panics.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DecodeError {
    /// The bytes end before the frame does: wait for `needed` bytes in all.
    #[error("incomplete frame: {needed} bytes needed, {available} available")]
    Incomplete {
        /// Bytes the frame needs (at least the fixed header until its length field is read).
        needed: usize,
        /// Bytes given.
        available: usize,
    },
    /// The bytes are not a valid frame.
    #[error("malformed frame: {what}")]
    Malformed {
        /// What was wrong.
        what: String,
    },
    /// The frame uses a format version this decoder does not read.
    #[error("unsupported frame format version {found} (this decoder reads versions {oldest} to {newest})")]
    UnsupportedVersion {
        /// Version in the frame.
        found: u16,
        /// Oldest version this decoder reads.
        oldest: u16,
        /// Newest version this decoder reads.
        newest: u16,
    },
    /// A delta frame predicts from a frame this decoder does not hold; decode a keyframe first.
    #[error("frame {sequence} predicts from frame {base}, but the decoder holds {held:?}: a keyframe is needed")]
    NeedKeyframe {
        /// Sequence number of the delta frame.
        sequence: u64,
        /// The frame it predicts from.
        base: u64,
        /// The identity-ordered frame the decoder holds, if any.
        held: Option<u64>,
    },
    /// The frame declares more than the caller's limits allow.
    #[error("frame declares {declared} {what}, over the limit of {limit}")]
    TooLarge {
        /// What is too large (`particles`, `bytes`).
        what: &'static str,
        /// Declared amount.
        declared: u64,
        /// The caller's limit.
        limit: u64,
    },
}

impl DecodeError {
    pub(crate) fn malformed(what: impl Into<String>) -> Self {
        DecodeError::Malformed { what: what.into() }
    }
}

/// Why a frame could not be encoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EncodeError {
    /// A channel has a different number of particles than the positions.
    #[error("{channel} has {got} values but there are {expected} particles")]
    LengthMismatch {
        /// The channel.
        channel: ChannelKind,
        /// Particles (positions).
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// More particles than the format's u32 count holds.
    #[error("{count} particles exceed the format's limit of {}", u32::MAX)]
    TooManyParticles {
        /// Particles given.
        count: usize,
    },
    /// The encoded frame would exceed the u32 frame length.
    #[error("the frame would exceed the format's limit of {} bytes", u32::MAX)]
    FrameTooLarge,
    /// The simulated time is NaN or infinite.
    #[error("time is {0}, not a finite number of seconds")]
    NonFiniteTime(f64),
    /// A channel's per-frame range overflows f32 (values near ±3.4e38).
    #[error("{channel} values span more than f32 can hold")]
    RangeOverflow {
        /// The channel.
        channel: ChannelKind,
    },
    /// The encoder configuration is invalid.
    #[error("invalid encoder configuration: {0}")]
    InvalidConfig(String),
    /// The input does not fit the channel table or the encoder's mode.
    #[error("invalid frame input: {0}")]
    InvalidInput(String),
}
