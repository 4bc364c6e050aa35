//! The exact kernel's static filter constant, shared by its scalar form and its lane forms.

/// `2^-49`: the static filter's constant (see the module docs of [`super`]).
pub(super) const FILTER: f64 = 1.0 / (1u64 << 49) as f64;
