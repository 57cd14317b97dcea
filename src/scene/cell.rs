//! The two regions of every scene, Ω and Ω₀, and the four cells of the
//! partition they make: the one vocabulary of pavings, quadrature, proofs,
//! pictures and the command line.

use std::fmt;
use std::str::FromStr;

/// Ω, Ω₀ and the four cells, in the order used everywhere (output files,
/// tables, [`Cell::ALL`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cell {
    /// Ω: no detachment.
    Omega = 0,
    /// Ω₀: the contact reaction keeps its sign.
    Omega0 = 1,
    /// Ω∩Ω₀.
    OmegaAndOmega0 = 2,
    /// Ω̄∩Ω̄₀.
    NeitherOmegaNorOmega0 = 3,
    /// Ω̄∩Ω₀.
    Omega0NotOmega = 4,
    /// Ω∩Ω̄₀.
    OmegaNotOmega0 = 5,
}

impl Cell {
    pub const ALL: [Cell; 6] = [
        Cell::Omega,
        Cell::Omega0,
        Cell::OmegaAndOmega0,
        Cell::NeitherOmegaNorOmega0,
        Cell::Omega0NotOmega,
        Cell::OmegaNotOmega0,
    ];

    /// Its place in [`Cell::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// `omega`, `omega0`, `omega_and_omega0`, … as in output and proof files
    /// and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Cell::Omega => "omega",
            Cell::Omega0 => "omega0",
            Cell::OmegaAndOmega0 => "omega_and_omega0",
            Cell::NeitherOmegaNorOmega0 => "not_omega_and_not_omega0",
            Cell::Omega0NotOmega => "not_omega_and_omega0",
            Cell::OmegaNotOmega0 => "omega_and_not_omega0",
        }
    }

    /// `Ω`, `Ω₀`, `Ω∩Ω₀`, …
    pub fn label(self) -> &'static str {
        match self {
            Cell::Omega => "Ω",
            Cell::Omega0 => "Ω₀",
            Cell::OmegaAndOmega0 => "Ω∩Ω₀",
            Cell::NeitherOmegaNorOmega0 => "Ω̄∩Ω̄₀",
            Cell::Omega0NotOmega => "Ω̄∩Ω₀",
            Cell::OmegaNotOmega0 => "Ω∩Ω̄₀",
        }
    }

    /// What it asks of (Ω, Ω₀): `Some(true)` inside, `Some(false)` outside,
    /// `None` either.
    pub fn literals(self) -> [Option<bool>; 2] {
        let (t, f) = (Some(true), Some(false));
        match self {
            Cell::Omega => [t, None],
            Cell::Omega0 => [None, t],
            Cell::OmegaAndOmega0 => [t, t],
            Cell::NeitherOmegaNorOmega0 => [f, f],
            Cell::Omega0NotOmega => [f, t],
            Cell::OmegaNotOmega0 => [t, f],
        }
    }
}

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is none of [`Cell::name`]'s.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown region `{0}` (known: omega, omega0, omega_and_omega0, not_omega_and_not_omega0, not_omega_and_omega0, omega_and_not_omega0)")]
pub struct UnknownCell(pub String);

impl FromStr for Cell {
    type Err = UnknownCell;

    fn from_str(s: &str) -> Result<Cell, UnknownCell> {
        Cell::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| UnknownCell(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names read back to their cell; the error lists every name, in order.
    #[test]
    fn names_parse_back_and_the_error_lists_them() {
        for c in Cell::ALL {
            assert_eq!(c.name().parse::<Cell>(), Ok(c));
            assert_eq!(c.to_string(), c.name());
            assert_eq!(Cell::ALL[c.index()], c);
        }
        let e = "omega1".parse::<Cell>().unwrap_err().to_string();
        let names: Vec<&str> = Cell::ALL.iter().map(|c| c.name()).collect();
        assert!(e.contains(&names.join(", ")), "{e}");
        assert!("Omega".parse::<Cell>().is_err() && "".parse::<Cell>().is_err());
    }

    /// The four cells partition the plane: each point (in or out of Ω, of
    /// Ω₀) is in exactly one; Ω and Ω₀ are the unions of their two cells.
    #[test]
    fn cells_partition_the_plane() {
        let holds = |c: Cell, p: [bool; 2]| {
            c.literals()
                .iter()
                .zip(p)
                .all(|(l, x)| l.is_none_or(|l| l == x))
        };
        for p in [[true, true], [true, false], [false, true], [false, false]] {
            let n = Cell::ALL[2..].iter().filter(|&&c| holds(c, p)).count();
            assert_eq!(n, 1, "{p:?}");
            assert_eq!(holds(Cell::Omega, p), p[0]);
            assert_eq!(holds(Cell::Omega0, p), p[1]);
        }
    }
}
