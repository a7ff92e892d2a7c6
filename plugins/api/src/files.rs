//! Files a shape's parameters name (a font, a height field), read for the plugin by Prism.
//!
//! A plugin never opens a file itself: [`crate::ShapeParams::build_with_files`] asks a
//! [`FileReader`] for the file a parameter names, and Prism's reader resolves it relative to
//! the scene file that wrote it under the rules every scene file obeys (regular files only,
//! a size cap, the `--root` sandbox), notes it for `prism watch`, and remembers the resolved
//! path so that a saved scene and an exported POV-Ray file still find it.

use std::path::PathBuf;

use crate::ParamError;

/// A file read for a shape: where it is (absolute, symlinks resolved) and its bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamFile {
    /// The file's canonical path (what `to_pov` writes, through [`crate::pov::FilePaths`]).
    pub path: PathBuf,
    /// Its contents.
    pub bytes: Vec<u8>,
}

/// Reads the files named by shape parameters.
pub trait FileReader {
    /// The file written as `written` at parameter `key` (a top-level key of the shape's
    /// table, such as `font`). An error names `key`, so Prism reports the file, line and
    /// column of the value.
    fn read(&mut self, key: &str, written: &str) -> Result<ParamFile, ParamError>;
}

/// A reader that refuses every file, for shapes built outside a scene that name none.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoFiles;

impl FileReader for NoFiles {
    fn read(&mut self, key: &str, _written: &str) -> Result<ParamFile, ParamError> {
        Err(ParamError::new(key, "cannot be read here: no files are available to this shape"))
    }
}

/// A reader of the local file system relative to a directory, without Prism's sandbox or
/// size caps: for plugin tests, benchmarks and tools, never for scenes.
#[derive(Clone, Debug, Default)]
pub struct LocalFiles(pub PathBuf);

impl FileReader for LocalFiles {
    fn read(&mut self, key: &str, written: &str) -> Result<ParamFile, ParamError> {
        let path = self.0.join(written);
        let failed = |e: std::io::Error| ParamError::new(key, format!("cannot read `{written}`: {e}"));
        let path = std::fs::canonicalize(&path).map_err(failed)?;
        let bytes = std::fs::read(&path).map_err(failed)?;
        Ok(ParamFile { path, bytes })
    }
}
