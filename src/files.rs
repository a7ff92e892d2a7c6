//! `files`: the one door through which Prism reads a file (scenes and their includes, OBJ
//! and MTL files, glTF files with their buffers and images, textures, environment maps, the
//! files shape plugins name: fonts).
//!
//! [`FileAccess::read`] opens only regular files: a FIFO, a device (`/dev/stdin`,
//! `/dev/zero`), a socket or a directory is refused after the open, which on Unix uses
//! `O_NONBLOCK` so that opening a FIFO cannot block. The size is checked against the
//! [`FileKind`]'s cap before anything is read, and the read stops one byte past the cap
//! (a file growing while it is read cannot exceed it either).
//!
//! A [`FileAccess::sandboxed`] access is the `--root DIR` sandbox: every path must resolve,
//! after symlinks, inside the root, and a path written in a scene or mesh file
//! ([`FileAccess::join`]) may not be absolute.
//!
//! A [`FileAccess::in_memory`] access reads from a map of paths to bytes instead of the
//! disk, under the same size caps: the fuzz targets (`fuzz/`) drive every loader through it.
//!
//! Messages name files, never their contents, and long names are shortened ([`shown`]).
//!
//! [`FileAccess::logged`] also notes every path asked for (read or not: a missing include
//! may appear later), which is how `prism watch` knows the files a scene depends on.

use std::collections::HashMap;
use std::io::Read;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Largest scene file (TOML, each include counted alone): 16 MiB (100,000 spheres take 9).
pub const MAX_SCENE_BYTES: u64 = 16 << 20;
/// Largest mesh file (OBJ, MTL, glTF, GLB) or glTF buffer: 1 GiB.
pub const MAX_MESH_BYTES: u64 = 1 << 30;
/// Largest encoded image file (textures, environment maps, glTF images): 256 MiB.
pub const MAX_IMAGE_BYTES: u64 = 256 << 20;

/// Largest file a shape plugin reads (a font): 256 MiB.
pub const MAX_SHAPE_DATA_BYTES: u64 = 256 << 20;

/// Longest file name or key echoed in a message, in characters; longer ones keep their end.
pub const MAX_SHOWN_CHARS: usize = 64;

/// What a file is read as; sets its size cap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// A scene file or include ([`MAX_SCENE_BYTES`]).
    Scene,
    /// A mesh file, material library or glTF buffer ([`MAX_MESH_BYTES`]).
    Mesh,
    /// An image ([`MAX_IMAGE_BYTES`]).
    Image,
    /// A file a shape plugin reads, such as a font ([`MAX_SHAPE_DATA_BYTES`]).
    ShapeData,
}

impl FileKind {
    /// The largest file of this kind that is read, in bytes.
    pub fn cap(self) -> u64 {
        match self {
            FileKind::Scene => MAX_SCENE_BYTES,
            FileKind::Mesh => MAX_MESH_BYTES,
            FileKind::Image => MAX_IMAGE_BYTES,
            FileKind::ShapeData => MAX_SHAPE_DATA_BYTES,
        }
    }

    fn noun(self) -> &'static str {
        match self {
            FileKind::Scene => "scene file",
            FileKind::Mesh => "mesh file",
            FileKind::Image => "image",
            FileKind::ShapeData => "shape's file",
        }
    }
}

/// Why a file is not read.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The operating system refused (missing file, permissions, not UTF-8 where text is needed).
    #[error("cannot read `{}`: {source}", shown_path(.path))]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The path names a directory, FIFO, device or socket.
    #[error("cannot read `{}`: it is {what}, not a regular file", shown_path(.path))]
    NotRegular {
        /// The file.
        path: PathBuf,
        /// `a directory`, `a FIFO`, `a device`, `a socket`.
        what: &'static str,
    },
    /// The file is larger than its kind's cap.
    #[error("cannot read `{}`: the {noun} is larger than the limit of {cap} bytes", shown_path(.path))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What it was read as.
        noun: &'static str,
        /// The cap in bytes.
        cap: u64,
    },
    /// Under `--root`, a path written in a file is absolute.
    #[error("`{}`: absolute paths are not allowed under --root", shown_path(.path))]
    Absolute {
        /// The path as written.
        path: PathBuf,
    },
    /// Under `--root`, the path resolves outside the root.
    #[error("`{}` is outside the --root directory", shown_path(.path))]
    OutsideRoot {
        /// The path as given.
        path: PathBuf,
    },
    /// A URI scheme other than a relative path or `data:` (glTF).
    #[error("`{}`: unsupported URI (only relative paths and data: URIs are read)", shown(.uri))]
    Uri {
        /// The URI.
        uri: String,
    },
}

impl FileError {
    /// The reason without the file's name (for messages that name the file themselves).
    pub fn cause(&self) -> String {
        match self {
            FileError::Io { source, .. } => source.to_string(),
            FileError::NotRegular { what, .. } => format!("it is {what}, not a regular file"),
            FileError::TooLarge { noun, cap, .. } => format!("the {noun} is larger than the limit of {cap} bytes"),
            FileError::Absolute { .. } => "absolute paths are not allowed under --root".into(),
            FileError::OutsideRoot { .. } => "it is outside the --root directory".into(),
            FileError::Uri { .. } => "unsupported URI".into(),
        }
    }

    /// True for the sandbox's refusals ([`FileError::Absolute`], [`FileError::OutsideRoot`],
    /// [`FileError::Uri`]): errors even where an unreadable file is only a warning.
    pub fn is_sandbox(&self) -> bool {
        matches!(self, FileError::Absolute { .. } | FileError::OutsideRoot { .. } | FileError::Uri { .. })
    }
}

/// `text` for a message: at most [`MAX_SHOWN_CHARS`] characters, keeping the end (where a
/// file's name is) behind a leading `...`.
pub fn shown(text: &str) -> String {
    let count = text.chars().count();
    if count <= MAX_SHOWN_CHARS {
        return text.to_string();
    }
    let tail: String = text.chars().skip(count - (MAX_SHOWN_CHARS - 3)).collect();
    format!("...{tail}")
}

/// [`shown`] for a path.
pub fn shown_path(path: &Path) -> String {
    shown(&path.display().to_string())
}

/// How files are read: anywhere, only inside a root directory, or from memory.
#[derive(Clone, Debug, Default)]
pub struct FileAccess {
    /// The canonical root, under `--root`.
    root: Option<PathBuf>,
    /// Files held in memory by [`normalize`]d path; when set, the disk is never touched.
    memory: Option<Arc<HashMap<PathBuf, Vec<u8>>>>,
    /// Where the paths asked for are noted, when they are.
    log: Option<ReadLog>,
}

/// The paths a [`FileAccess`] (and every clone of it) was asked to read, in order, each
/// once, made absolute against the working directory.
#[derive(Clone, Debug, Default)]
pub struct ReadLog(Arc<Mutex<Vec<PathBuf>>>);

impl ReadLog {
    /// The paths noted so far.
    pub fn paths(&self) -> Vec<PathBuf> {
        self.0.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone()
    }

    fn note(&self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        let mut paths = self.0.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if !paths.contains(&path) {
            paths.push(path);
        }
    }
}

impl FileAccess {
    /// Reads any regular file the process may read.
    pub fn unrestricted() -> Self {
        Self::default()
    }

    /// Reads only files that resolve inside `root` (which must be a directory).
    pub fn sandboxed(root: &Path) -> Result<Self, FileError> {
        let canonical = std::fs::canonicalize(root).map_err(|source| FileError::Io { path: root.into(), source })?;
        if !canonical.is_dir() {
            return Err(FileError::NotRegular { path: root.into(), what: "not a directory" });
        }
        Ok(Self { root: Some(canonical), memory: None, log: None })
    }

    /// Reads only the given files (path, bytes), never the disk; paths are compared after
    /// [`normalize`], and each file's kind cap still applies. For fuzzing and tests.
    pub fn in_memory(files: impl IntoIterator<Item = (PathBuf, Vec<u8>)>) -> Self {
        let files = files.into_iter().map(|(path, bytes)| (normalize(&path), bytes)).collect();
        Self { root: None, memory: Some(Arc::new(files)), log: None }
    }

    /// This access, noting in the returned log every path it (or a clone) is asked to read.
    pub fn logged(self) -> (Self, ReadLog) {
        let log = ReadLog::default();
        (Self { log: Some(log.clone()), ..self }, log)
    }

    /// The sandbox's root, if any.
    pub fn root(&self) -> Option<&Path> {
        self.root.as_deref()
    }

    /// `written` (a path inside a scene or mesh file) relative to `dir`. Under a sandbox an
    /// absolute path is an error; `..` is allowed as long as the result stays inside.
    pub fn join(&self, dir: &Path, written: &str) -> Result<PathBuf, FileError> {
        let path = Path::new(written);
        if self.root.is_some() && (path.is_absolute() || path.components().any(|c| matches!(c, Component::Prefix(_)))) {
            return Err(FileError::Absolute { path: path.into() });
        }
        Ok(dir.join(path))
    }

    /// The canonical form of `path` (symlinks resolved), checked to lie inside the root.
    pub fn resolve(&self, path: &Path) -> Result<PathBuf, FileError> {
        if let Some(files) = &self.memory {
            let key = normalize(path);
            return match files.contains_key(&key) {
                true => Ok(key),
                false => Err(FileError::Io { path: path.into(), source: std::io::ErrorKind::NotFound.into() }),
            };
        }
        let canonical = match std::fs::canonicalize(path) {
            Ok(canonical) => canonical,
            // A missing file outside the root is reported as outside, as an existing one is:
            // the error must not tell a scene which files exist beyond the sandbox.
            Err(_) if self.root.as_ref().is_some_and(|root| !would_lie_inside(path, root)) => {
                return Err(FileError::OutsideRoot { path: path.into() });
            }
            Err(source) => return Err(FileError::Io { path: path.into(), source }),
        };
        match &self.root {
            Some(root) if !canonical.starts_with(root) => Err(FileError::OutsideRoot { path: path.into() }),
            _ => Ok(canonical),
        }
    }

    /// The bytes of the regular file at `path`, at most `kind.cap()` of them.
    pub fn read(&self, path: &Path, kind: FileKind) -> Result<Vec<u8>, FileError> {
        if let Some(log) = &self.log {
            log.note(path);
        }
        let canonical = self.resolve(path)?;
        let cap = kind.cap();
        let too_large = || FileError::TooLarge { path: path.into(), noun: kind.noun(), cap };
        if let Some(files) = &self.memory {
            let bytes = &files[&canonical];
            return if bytes.len() as u64 > cap { Err(too_large()) } else { Ok(bytes.clone()) };
        }
        let io = |source| FileError::Io { path: path.into(), source };
        let file = open_nonblocking(&canonical).map_err(io)?;
        let metadata = file.metadata().map_err(io)?;
        if let Some(what) = not_regular(&metadata.file_type()) {
            return Err(FileError::NotRegular { path: path.into(), what });
        }
        if metadata.len() > cap {
            return Err(too_large());
        }
        let mut bytes = Vec::with_capacity(metadata.len() as usize);
        file.take(cap + 1).read_to_end(&mut bytes).map_err(io)?;
        if bytes.len() as u64 > cap {
            return Err(too_large());
        }
        Ok(bytes)
    }

    /// [`FileAccess::read`] as UTF-8 text.
    pub fn read_text(&self, path: &Path, kind: FileKind) -> Result<String, FileError> {
        let bytes = self.read(path, kind)?;
        String::from_utf8(bytes).map_err(|_| FileError::Io {
            path: path.into(),
            source: std::io::Error::new(std::io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"),
        })
    }
}

/// Whether `path`, which does not resolve, would lie inside `root` if it existed: its
/// deepest ancestor that exists, resolved (symlinks followed), with the rest appended and
/// normalized as written.
fn would_lie_inside(path: &Path, root: &Path) -> bool {
    let Ok(absolute) = std::path::absolute(path) else { return false };
    for ancestor in absolute.ancestors() {
        if let Ok(resolved) = std::fs::canonicalize(ancestor) {
            let rest = absolute.strip_prefix(ancestor).unwrap_or(Path::new(""));
            return normalize(&resolved.join(rest)).starts_with(root);
        }
    }
    false
}

/// `a/./b/../c` -> `a/c`, without touching the file system (a leading `..` is kept).
pub fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Opens for reading without blocking on a FIFO (the flag matters only for the open: the
/// file is refused right after unless it is regular).
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    options.open(path)
}

/// What a non-regular file is, or `None` for a regular file.
pub fn not_regular(file_type: &std::fs::FileType) -> Option<&'static str> {
    if file_type.is_file() {
        return None;
    }
    if file_type.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return Some("a FIFO");
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return Some("a device");
        }
        if file_type.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_logged_access_notes_every_path_asked_for_once_through_its_clones() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, "x = 1\n").unwrap();
        let missing = dir.path().join("later.toml");
        let (access, log) = FileAccess::unrestricted().logged();
        access.read(&file, FileKind::Scene).unwrap();
        access.clone().read(&missing, FileKind::Scene).unwrap_err();
        access.read(&file, FileKind::Scene).unwrap();
        assert_eq!(log.paths(), vec![file, missing]);
        // An access that is not logged notes nothing anywhere.
        FileAccess::unrestricted().read(dir.path(), FileKind::Scene).unwrap_err();
        assert_eq!(log.paths().len(), 2);
    }

    #[test]
    fn regular_files_are_read_and_others_refused() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, "x = 1\n").unwrap();
        let access = FileAccess::unrestricted();
        assert_eq!(access.read_text(&file, FileKind::Scene).unwrap(), "x = 1\n");
        let e = access.read(dir.path(), FileKind::Scene).unwrap_err();
        assert!(matches!(e, FileError::NotRegular { what: "a directory", .. }), "{e}");
        #[cfg(unix)]
        {
            for device in ["/dev/zero", "/dev/null"] {
                let e = access.read(Path::new(device), FileKind::Mesh).unwrap_err();
                assert!(matches!(e, FileError::NotRegular { what: "a device", .. }), "{e}");
            }
            let fifo = dir.path().join("fifo");
            let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
            // SAFETY: a valid NUL-terminated path.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
            // Would block forever without O_NONBLOCK (no writer ever opens it).
            let e = access.read(&fifo, FileKind::Scene).unwrap_err();
            assert!(matches!(e, FileError::NotRegular { what: "a FIFO", .. }), "{e}");
        }
    }

    #[test]
    fn files_over_the_cap_are_refused_before_reading() {
        let dir = tempfile::tempdir().unwrap();
        let big = dir.path().join("big.toml");
        let f = std::fs::File::create(&big).unwrap();
        // Sparse: costs no disk, and reading it whole would cost 16 MiB + 1.
        f.set_len(MAX_SCENE_BYTES + 1).unwrap();
        let e = FileAccess::unrestricted().read(&big, FileKind::Scene).unwrap_err();
        assert!(matches!(e, FileError::TooLarge { cap: MAX_SCENE_BYTES, .. }), "{e}");
    }

    #[test]
    fn the_sandbox_confines_reads() {
        let outer = tempfile::tempdir().unwrap();
        let root = outer.path().join("root");
        std::fs::create_dir(&root).unwrap();
        std::fs::write(root.join("in.toml"), "").unwrap();
        std::fs::write(outer.path().join("secret.toml"), "").unwrap();
        let access = FileAccess::sandboxed(&root).unwrap();
        assert!(access.read(&root.join("in.toml"), FileKind::Scene).is_ok());
        let escape = access.join(&root, "../secret.toml").unwrap();
        assert!(matches!(access.read(&escape, FileKind::Scene), Err(FileError::OutsideRoot { .. })));
        assert!(matches!(access.join(&root, "/etc/passwd"), Err(FileError::Absolute { .. })));
        // A missing file is outside as an existing one is (the error tells nothing of what
        // exists beyond the root), and missing inside when it would lie inside.
        for missing in ["../nosuch.toml", "../nodir/x.toml", "sub/../../nosuch.toml", "nodir/../../secret.toml"] {
            let path = access.join(&root, missing).unwrap();
            assert!(matches!(access.read(&path, FileKind::Scene), Err(FileError::OutsideRoot { .. })), "{missing}");
        }
        for missing in ["nosuch.toml", "nodir/x.toml", "nodir/../nosuch.toml"] {
            let path = access.join(&root, missing).unwrap();
            let e = access.read(&path, FileKind::Scene).unwrap_err();
            assert!(
                matches!(&e, FileError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound),
                "{missing}: {e}"
            );
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(outer.path().join("secret.toml"), root.join("link.toml")).unwrap();
            assert!(matches!(
                access.read(&root.join("link.toml"), FileKind::Scene),
                Err(FileError::OutsideRoot { .. })
            ));
        }
        assert!(FileAccess::unrestricted().join(&root, "/etc/passwd").is_ok());
    }

    #[test]
    fn in_memory_files_are_read_by_normalized_path_under_the_caps() {
        let access = FileAccess::in_memory([
            (PathBuf::from("scene/a.toml"), b"x = 1\n".to_vec()),
            (PathBuf::from("big.toml"), vec![b' '; MAX_SCENE_BYTES as usize + 1]),
        ]);
        let joined = access.join(Path::new("scene/sub"), "../a.toml").unwrap();
        assert_eq!(access.read_text(&joined, FileKind::Scene).unwrap(), "x = 1\n");
        assert_eq!(access.resolve(&joined).unwrap(), Path::new("scene/a.toml"));
        let e = access.read(Path::new("scene/missing.toml"), FileKind::Scene).unwrap_err();
        assert!(matches!(&e, FileError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound), "{e}");
        assert!(matches!(access.read(Path::new("big.toml"), FileKind::Scene), Err(FileError::TooLarge { .. })));
        assert!(access.read(Path::new("big.toml"), FileKind::Mesh).is_ok());
        // Never the disk, even for a file that exists there.
        assert!(access.read(Path::new("/proc/self/status"), FileKind::Scene).is_err());
    }

    #[test]
    fn long_names_are_shortened_keeping_their_end() {
        let long = format!("{}end.toml", "x".repeat(10_000));
        let s = shown(&long);
        assert_eq!(s.chars().count(), MAX_SHOWN_CHARS);
        assert!(s.starts_with("...") && s.ends_with("end.toml"));
        assert_eq!(shown("short"), "short");
    }
}
