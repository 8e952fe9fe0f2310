//! Where floe-proto's decoded [`Frame`] and [`Header`] meet Python: every field of
//! either that the module reads is read here. Channels are handed on in the frame's
//! order, positions first (none in a grid frame), each with its wire tag, its name
//! and unit from the channel table (`proto/channels.json`; a per-scene tag gets
//! `channel <tag>` and no unit, which the client replaces with the scene's own), and
//! its quantisation error.

use floe_proto::{ChannelKind, Frame, Header, Mode, Values};
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// The name of a frame mode, as `StreamFramesRequest` spells it in Python (`FrameMode`).
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Unordered => "unordered",
        Mode::IdentityOrdered => "identity",
        Mode::Grid => "grid",
    }
}

/// The header as a dict of its fields; `set` is the index of the particle set (the
/// client names it from the scene's list), `grid` the grid of a grid frame.
fn header_dict<'py>(py: Python<'py>, frame: &Frame) -> PyResult<Bound<'py, PyDict>> {
    let h: &Header = &frame.header;
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
    d.set_item("set", h.set)?;
    match &frame.grid {
        Some(g) => d.set_item("grid", (g.origin, g.size, g.dims))?,
        None => d.set_item("grid", py.None())?,
    }
    Ok(d)
}

/// A decoded frame for Python: `(header, [(tag, name, unit, values, max_error), ...])`,
/// the values numpy arrays that take over the decoder's buffers (`(N, c)` float32 for
/// `c` components, `(N,)` float32 for one, `(N,)` uint8 for exact channels) and
/// `max_error` the quantisation error of each component.
pub fn to_python<'py>(py: Python<'py>, frame: Frame) -> PyResult<Bound<'py, PyTuple>> {
    let header = header_dict(py, &frame)?;
    let n = frame.header.particle_count as usize;
    let errors = |tag: u8| -> Vec<f32> {
        let info = frame.header.channels.iter().find(|c| c.tag == tag);
        info.map(|c| c.ranges.iter().map(|r| r.max_error).collect()).unwrap_or_default()
    };
    let list = PyList::empty(py);
    let describe = |kind: ChannelKind| (kind.tag(), kind.name(), kind.def().map_or("", |d| d.unit), errors(kind.tag()));
    if frame.grid.is_none() {
        let (tag, name, unit, max_error) = describe(ChannelKind::POSITION);
        // [f32; 3] and f32 share their alignment: the cast reuses the allocation.
        let array = bytemuck::cast_vec::<[f32; 3], f32>(frame.positions).into_pyarray(py).reshape([n, 3])?;
        list.append((tag, name, unit, array.into_any(), PyTuple::new(py, max_error)?))?;
    }
    for (kind, values) in frame.channels {
        let (tag, name, unit, max_error) = describe(kind);
        let array = match values {
            Values::Float { components: 1, data } => data.into_pyarray(py).into_any(),
            Values::Float { components, data } => {
                data.into_pyarray(py).reshape([n, usize::from(components)])?.into_any()
            }
            Values::Exact(v) => v.into_pyarray(py).into_any(),
        };
        list.append((tag, name, unit, array, PyTuple::new(py, max_error)?))?;
    }
    // The particles' ids, where the frame names them (a set whose particles are born and die).
    if let Some(ids) = frame.ids {
        let (tag, name, unit, _) = describe(ChannelKind::IDS);
        list.append((tag, name, unit, ids.into_pyarray(py).into_any(), PyTuple::new(py, [0.0f32])?))?;
    }
    PyTuple::new(py, [header.into_any(), list.into_any()])
}
