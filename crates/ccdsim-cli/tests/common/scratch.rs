//! Scratch space for one test, removed when the test ends, pass or fail (a failing assertion
//! unwinds through the guard's `drop`), so test runs leave nothing in the temporary directory.
//! The viewer's tests include this file too (`#[path]`), to keep one copy.

use std::ffi::OsStr;
use std::ops::Deref;
use std::path::{Path, PathBuf};

/// A fresh, empty directory `ccdsim-<name>-<random>` in the temporary directory, removed with
/// its contents when dropped. It derefs to its path.
pub struct ScratchDir(tempfile::TempDir);

impl ScratchDir {
    /// Creates the directory; panics if the temporary directory cannot hold it.
    pub fn new(name: &str) -> Self {
        let dir = tempfile::Builder::new()
            .prefix(&format!("ccdsim-{name}-"))
            .tempdir()
            .expect("a scratch directory in the temporary directory");
        ScratchDir(dir)
    }
}

impl Deref for ScratchDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for ScratchDir {
    fn as_ref(&self) -> &Path {
        self
    }
}

impl AsRef<OsStr> for ScratchDir {
    fn as_ref(&self) -> &OsStr {
        self.0.path().as_os_str()
    }
}

/// The path of a file `name` (not created) in a scratch directory of its own, which is
/// removed with the file when this is dropped. It derefs to the file's path.
pub struct ScratchFile {
    path: PathBuf,
    _dir: ScratchDir,
}

impl ScratchFile {
    /// A path for `name` in a new scratch directory named after `group`.
    pub fn new(group: &str, name: &str) -> Self {
        let dir = ScratchDir::new(group);
        ScratchFile {
            path: dir.join(name),
            _dir: dir,
        }
    }
}

impl Deref for ScratchFile {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for ScratchFile {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<OsStr> for ScratchFile {
    fn as_ref(&self) -> &OsStr {
        self.path.as_os_str()
    }
}
