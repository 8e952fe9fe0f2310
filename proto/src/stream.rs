//! Streams: how a channel's payload stores its values.
//!
//! A channel's payload is one stream per component, or a single stream of Morton-key
//! differences for unordered positions ([`crate::header::Predictor::Morton`]). A stream
//! holds `n` unsigned values (`n` = the particle count) as byte planes:
//!
//! | offset | size | type | field |
//! |---:|---:|---|---|
//! | 0 | 1 | u8 | width `w`: bytes per value (1 to 2, or 1 to 6 for Morton differences) |
//! | 1 | 5 + len | | plane 0 (byte 0 of every value), then planes 1 to `w - 1` |
//!
//! and each plane is
//!
//! | offset | size | type | field |
//! |---:|---:|---|---|
//! | 0 | 1 | u8 | method: 0 stored, 1 LZ4 block (no size prefix, no frame) |
//! | 1 | 4 | u32 | stored length `len` in bytes |
//! | 5 | len | bytes | the plane; it must come out as exactly `n` bytes |
//!
//! A plane is stored as is when LZ4 would not make it smaller, which also skips the
//! decompression work for the noisy low bytes.

use crate::error::DecodeError;
use crate::reader::Reader;
use crate::shuffle;

const STORED: u8 = 0;
const LZ4: u8 = 1;

/// Appends a stream of `values`, all at most `max`, to `out`; `planes` is scratch.
pub(crate) fn write<T: Copy + Into<u64>>(out: &mut Vec<u8>, values: &[T], max: u64, planes: &mut Vec<u8>) {
    let n = values.len();
    let width = shuffle::width_of(max);
    shuffle::split_planes(values, width, planes);
    out.push(width as u8);
    for k in 0..width {
        let plane = &planes[k * n..(k + 1) * n];
        let at = out.len();
        out.resize(at + 5 + lz4_flex::block::get_maximum_output_size(n), 0);
        let packed = lz4_flex::block::compress_into(plane, &mut out[at + 5..]).ok().filter(|&len| len < n);
        let (method, len) = match packed {
            Some(len) => (LZ4, len),
            None => {
                out[at + 5..at + 5 + n].copy_from_slice(plane);
                (STORED, n)
            }
        };
        out[at] = method;
        // `len <= n`, and the encoder has checked that `n` fits in u32.
        out[at + 1..at + 5].copy_from_slice(&(len as u32).to_le_bytes());
        out.truncate(at + 5 + len);
    }
}

/// Reads a stream of `n` values of at most `max_width` bytes into `planes`
/// (`width * n` bytes, plane after plane) and returns the width.
///
/// Allocation is bounded twice: by `n` (which the caller has checked against its
/// limit) and by the bytes actually present, since an LZ4 block expands at most about
/// 255-fold (each extra match-length byte adds at most 255 bytes).
pub(crate) fn read(r: &mut Reader<'_>, n: usize, max_width: usize, planes: &mut Vec<u8>) -> Result<usize, DecodeError> {
    let width = usize::from(r.u8()?);
    if !(1..=max_width).contains(&width) {
        return Err(DecodeError::malformed(format!("stream width {width} (1 to {max_width} allowed)")));
    }
    planes.clear();
    for k in 0..width {
        let method = r.u8()?;
        let len = r.u32()? as usize;
        let data = r.take(len)?;
        let at = planes.len();
        match method {
            STORED if len == n => planes.extend_from_slice(data),
            STORED => return Err(DecodeError::malformed(format!("stored plane {k} has {len} bytes, not {n}"))),
            LZ4 => {
                if (n as u64) > 256 * len as u64 + 64 {
                    return Err(DecodeError::malformed(format!("{len} LZ4 bytes cannot hold a plane of {n} bytes")));
                }
                planes.resize(at + n, 0);
                match lz4_flex::block::decompress_into(data, &mut planes[at..]) {
                    Ok(got) if got == n => {}
                    Ok(got) => {
                        return Err(DecodeError::malformed(format!("plane {k} decompresses to {got} bytes, not {n}")));
                    }
                    Err(e) => return Err(DecodeError::malformed(format!("plane {k}: LZ4: {e}"))),
                }
            }
            other => return Err(DecodeError::malformed(format!("plane {k}: unknown method {other}"))),
        }
    }
    Ok(width)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_round_trip_and_compress_zero_planes() {
        let values: Vec<u64> = (0..10_000u64).map(|i| (i * 2_654_435_761) % 300).collect();
        let (mut out, mut planes) = (Vec::new(), Vec::new());
        write(&mut out, &values, 299, &mut planes);
        assert_eq!(out[0], 2, "values up to 299 need two bytes");
        assert!(out.len() < 10_000 + 200, "the high plane (0 or 1) compresses: {} bytes", out.len());
        let mut r = Reader::new(&out, "stream");
        let width = read(&mut r, values.len(), 8, &mut planes).unwrap();
        assert_eq!(r.remaining(), 0);
        let mut back = vec![0; values.len()];
        shuffle::join_planes_u64(&planes, width, &mut back);
        assert_eq!(back, values);
    }

    #[test]
    fn an_implausible_plane_length_is_refused_before_allocating() {
        let mut bytes = vec![1, LZ4];
        bytes.extend_from_slice(&4u32.to_le_bytes());
        bytes.extend_from_slice(&[0; 4]);
        let err = read(&mut Reader::new(&bytes, "stream"), 1 << 30, 2, &mut Vec::new()).unwrap_err();
        assert!(matches!(err, DecodeError::Malformed { .. }), "{err}");
    }
}
