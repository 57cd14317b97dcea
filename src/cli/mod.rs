//! Command-line front: argument types and one `run_*` per subcommand.

pub mod atlas;
pub mod paper;
pub mod roots;

use std::fmt;

/// A failure to report on stderr, with its exit code (2 = bad input).
#[derive(Debug)]
pub struct CliError {
    pub message: String,
    pub code: i32,
}

impl CliError {
    /// Bad input: exit code 2.
    pub fn usage(message: impl fmt::Display) -> Self {
        CliError {
            message: message.to_string(),
            code: 2,
        }
    }
    /// Failure while running (I/O, drawing): exit code 1.
    pub fn runtime(message: impl fmt::Display) -> Self {
        CliError {
            message: message.to_string(),
            code: 1,
        }
    }
}

pub type CliResult = Result<(), CliError>;
