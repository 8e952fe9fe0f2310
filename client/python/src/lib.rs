//! `floe_client._codec`: Floe frames decoded in Python by floe-proto, the codec the
//! server encodes with, into numpy arrays that take over the decoder's buffers (no
//! element is copied on the way to Python). The Python package wraps this module
//! (`floe_client.frames`); the mapping of frame fields lives in [`frame`].

mod frame;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

create_exception!(
    _codec,
    DecodeError,
    PyValueError,
    "A frame that could not be decoded: malformed, incomplete, of another format version, over \
     the decoder's limits, or a delta frame whose base frame this decoder does not hold."
);

/// Decodes the frames of one stream in order, holding the last identity-ordered frame
/// that delta frames predict from.
#[pyclass(module = "floe_client._codec")]
struct Decoder {
    inner: floe_proto::Decoder,
}

#[pymethods]
impl Decoder {
    /// A decoder refusing frames of more than `max_particles` particles or
    /// `max_frame_bytes` bytes (defaults: 16 Mi particles, 1 GiB).
    #[new]
    #[pyo3(signature = (max_particles = None, max_frame_bytes = None))]
    fn new(max_particles: Option<u32>, max_frame_bytes: Option<u32>) -> Self {
        let default = floe_proto::Limits::default();
        let limits = floe_proto::Limits {
            max_particles: max_particles.unwrap_or(default.max_particles),
            max_frame_bytes: max_frame_bytes.unwrap_or(default.max_frame_bytes),
        };
        Self { inner: floe_proto::Decoder::new(limits) }
    }

    /// Decodes one frame (bytes after its length are ignored) into
    /// `(header dict, [(name, unit, values, max_error), ...])`. The interpreter lock is
    /// released while decoding. On error the decoder's state is unchanged.
    fn decode<'py>(&mut self, py: Python<'py>, data: &[u8]) -> PyResult<Bound<'py, PyTuple>> {
        let inner = &mut self.inner;
        let decoded = py.detach(|| inner.decode(data)).map_err(|e| DecodeError::new_err(e.to_string()))?;
        frame::to_python(py, decoded)
    }

    /// Forgets the held frame, so that only a keyframe decodes next.
    fn reset(&mut self) {
        self.inner.reset();
    }

    /// Sequence number of the last frame decoded, or None.
    #[getter]
    fn last_sequence(&self) -> Option<u64> {
        self.inner.last_sequence()
    }

    /// Sequence number of the identity-ordered frame delta frames can apply to, or None.
    #[getter]
    fn held_sequence(&self) -> Option<u64> {
        self.inner.held_sequence()
    }
}

/// The module.
#[pymodule]
#[pyo3(name = "_codec")]
fn codec(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Decoder>()?;
    m.add("DecodeError", m.py().get_type::<DecodeError>())?;
    m.add("FORMAT_VERSION", floe_proto::header::VERSION)?;
    Ok(())
}
