//! Where floe-proto's decoded [`Frame`] and [`Header`] meet Python: every field of
//! either that the module reads is read here, so a change of the frame's layout is
//! absorbed in this file alone. Channels are handed on by [`ChannelKind::name`],
//! positions first, each with its unit from [`UNITS`] and its quantisation error.

use floe_proto::{ChannelKind, Frame, Header, Mode};
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// The unit of each channel, by channel name: one table for every frame handed to Python.
/// A channel missing here (a kind newer than this table) has the empty unit.
pub const UNITS: [(&str, &str); 6] = [
    ("position", "m"),
    ("velocity", "m/s"),
    ("density", "kg/m^3"),
    ("pressure", "Pa"),
    ("temperature", "K"),
    ("phase", ""),
];

fn unit(name: &str) -> &'static str {
    UNITS.iter().find(|(n, _)| *n == name).map_or("", |(_, u)| u)
}

/// One channel's values as decoded.
enum Values {
    /// Three components per particle.
    Vectors(Vec<[f32; 3]>),
    /// One value per particle.
    Scalars(Vec<f32>),
    /// An exact byte per particle (phase or material indices).
    Bytes(Vec<u8>),
}

/// The frame's channels in the order of its channel table (positions first).
fn channels(frame: Frame) -> Vec<(ChannelKind, Values)> {
    let mut out = vec![(ChannelKind::Position, Values::Vectors(frame.positions))];
    out.extend(frame.velocities.map(|v| (ChannelKind::Velocity, Values::Vectors(v))));
    out.extend(frame.densities.map(|v| (ChannelKind::Density, Values::Scalars(v))));
    out.extend(frame.pressures.map(|v| (ChannelKind::Pressure, Values::Scalars(v))));
    out.extend(frame.temperatures.map(|v| (ChannelKind::Temperature, Values::Scalars(v))));
    out.extend(frame.phases.map(|v| (ChannelKind::Phase, Values::Bytes(v))));
    out
}

/// The name of a frame mode, as `StreamFramesRequest` spells it in Python (`FrameMode`).
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Unordered => "unordered",
        Mode::IdentityOrdered => "identity",
    }
}

/// The header as a dict of its fields. `particle_set` is None: format version 3 frames
/// do not name the particle set they carry.
fn header_dict<'py>(py: Python<'py>, h: &Header) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("version", h.version)?;
    d.set_item("mode", mode_name(h.mode))?;
    d.set_item("keyframe", h.keyframe)?;
    d.set_item("frame_len", h.frame_len)?;
    d.set_item("particle_count", h.particle_count)?;
    d.set_item("scene_id", h.scene_id)?;
    d.set_item("sequence", h.sequence)?;
    d.set_item("base_sequence", h.base_sequence)?;
    d.set_item("step", h.step)?;
    d.set_item("time", h.time)?;
    d.set_item("particle_set", py.None())?;
    Ok(d)
}

/// A decoded frame for Python: `(header, [(name, unit, values, max_error), ...])`, the
/// values numpy arrays that take over the decoder's buffers (`(N, 3)` float32, `(N,)`
/// float32 or `(N,)` uint8) and `max_error` the quantisation error of each component.
pub fn to_python<'py>(py: Python<'py>, frame: Frame) -> PyResult<Bound<'py, PyTuple>> {
    let header = header_dict(py, &frame.header)?;
    let n = frame.header.particle_count as usize;
    let infos = frame.header.channels.clone();
    let list = PyList::empty(py);
    for (kind, values) in channels(frame) {
        let array = match values {
            // [f32; 3] and f32 share their alignment: the cast reuses the allocation.
            Values::Vectors(v) => bytemuck::cast_vec::<[f32; 3], f32>(v).into_pyarray(py).reshape([n, 3])?.into_any(),
            Values::Scalars(v) => v.into_pyarray(py).into_any(),
            Values::Bytes(v) => v.into_pyarray(py).into_any(),
        };
        let errors: Vec<f32> = infos
            .iter()
            .find(|c| c.kind() == Some(kind))
            .map(|c| c.ranges.iter().map(|r| r.max_error).collect())
            .unwrap_or_default();
        let name = kind.name();
        list.append((name, unit(name), array, PyTuple::new(py, errors)?))?;
    }
    PyTuple::new(py, [header.into_any(), list.into_any()])
}
