//! What checking a case concluded: the case passed (and what it ran), or why it failed. Both
//! kinds of case, scenes ([`crate::check`]) and pool shots ([`crate::pool`]), report this.

/// Why a case failed.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// A finder's run differs from the oracle's.
    Mismatch(String),
    /// The oracle's run file fails `verify` (or cannot be read back).
    Verify(String),
    /// Something panicked (the simulation, a finder, the recorder or `verify`).
    Panic(String),
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Mismatch(m) => write!(f, "finder mismatch: {m}"),
            Failure::Verify(m) => write!(f, "verify: {m}"),
            Failure::Panic(m) => write!(f, "panic: {m}"),
        }
    }
}

/// The result of a case that the scene validator accepted.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// Events of the oracle's run.
    pub events: u64,
    /// Finder runs compared with it.
    pub runs: usize,
}
