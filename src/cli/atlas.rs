//! `detach atlas`, `detach pave`, `detach scenes`.
