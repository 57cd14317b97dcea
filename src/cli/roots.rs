//! `detach roots`, `detach kappa0`, `detach critical-curve`.
