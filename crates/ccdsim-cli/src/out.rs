//! Writing to standard output without panicking: `println!` panics when the reader has gone
//! (`ccdsim run --json | head -c 100`); these return the error, and `main` ends a command
//! whose reader stopped reading quietly, as Unix tools do.

/// `println!` that returns `std::io::Result<()>` instead of panicking.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)
    }};
}

/// `print!` that returns `std::io::Result<()>` instead of panicking.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout().lock(), $($arg)*)
    }};
}
