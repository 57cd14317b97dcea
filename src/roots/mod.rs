//! Certified isolation of real roots of scalar equations.
