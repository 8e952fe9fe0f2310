//! Validation cases with their references (see `VALIDATION.md` in the shared
//! reference set): the measurements a test, a benchmark or `floe validate` needs.

pub mod dam_break;
pub mod hydrostatic;
