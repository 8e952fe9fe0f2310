//! Implicit viscosity on the GPU: the conjugate-gradient passes of floe-engine
//! `viscosity::implicit`, one kernel each; the sums between them stay on the
//! device (`visc_scalars`).

use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;

/// `d` and the starting residual.
pub static DIAGONAL: GpuPass = GpuPass {
    name: "viscosity.implicit_diagonal",
    source: walk_kernel!("varying_walls.wgsl", "implicit/pair.wgsl", "implicit/diagonal.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "viscosity"),
        (U, "dt"),
        (R, "x"),
        (R, "v"),
        (R, "rho"),
        (R, "mu"),
        (R, "starts"),
        (R, "walls"),
        (W, "visc_diag"),
        (W, "visc_r"),
    ],
    space: PARTICLES,
    when: always,
};

/// The first direction and the terms of `r.z`.
pub static PRECONDITION: GpuPass = GpuPass {
    name: "viscosity.implicit_precondition",
    source: particle_kernel!("implicit/precondition.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "visc_r"), (R, "visc_diag"), (W, "visc_p"), (W, "visc_dot"), (W, "visc_residual")],
    space: PARTICLES,
    when: always,
};

/// `Ap` and the terms of `p.Ap`.
pub static PRODUCT: GpuPass = GpuPass {
    name: "viscosity.implicit_product",
    source: walk_kernel!(fluid_only; "varying_walls.wgsl", "implicit/pair.wgsl", "implicit/product.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "viscosity"),
        (U, "dt"),
        (R, "x"),
        (R, "rho"),
        (R, "mu"),
        (R, "starts"),
        (R, "visc_p"),
        (R, "visc_diag"),
        (W, "visc_ap"),
        (W, "visc_dot"),
    ],
    space: PARTICLES,
    when: always,
};

/// The step along the direction.
pub static UPDATE: GpuPass = GpuPass {
    name: "viscosity.implicit_update",
    source: particle_kernel!("implicit/update.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (R, "visc_scalars"),
        (R, "visc_p"),
        (R, "visc_ap"),
        (R, "visc_diag"),
        (W, "v"),
        (W, "visc_r"),
        (W, "visc_dot"),
        (W, "visc_residual"),
    ],
    space: PARTICLES,
    when: always,
};

/// The next direction.
pub static DIRECTION: GpuPass = GpuPass {
    name: "viscosity.implicit_direction",
    source: particle_kernel!("implicit/direction.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "visc_scalars"), (R, "visc_r"), (R, "visc_diag"), (W, "visc_p")],
    space: PARTICLES,
    when: always,
};
