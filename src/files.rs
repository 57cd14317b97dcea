//! Output files written atomically: the content goes to a temporary file
//! beside the target, is flushed to disk, and is renamed over the target.
//! A run killed at any moment, or a write that fails (a full disk, a
//! read-only folder), leaves the previous file or the complete new one,
//! never a truncated one. A killed run may leave its temporary file
//! (`.NAME.PID.tmp.EXT`) behind.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// The temporary file for `path`: in the same folder (a rename stays on one
/// file system) and with the same extension (image encoders choose the
/// format by it).
pub fn temporary_beside(path: &Path) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let name = match path.extension() {
        Some(ext) => format!(
            ".{stem}.{}.tmp.{}",
            std::process::id(),
            ext.to_string_lossy()
        ),
        None => format!(".{stem}.{}.tmp", std::process::id()),
    };
    path.with_file_name(name)
}

/// Writes `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Writes `path` atomically through `fill`, which writes to a buffered file.
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let tmp = temporary_beside(path);
    let written = (|| {
        let mut w = BufWriter::new(File::create(&tmp)?);
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// Lets `render` write a file at a temporary path beside `path` (a drawing
/// backend that takes a path), then flushes it and renames it over `path`.
pub fn render_atomic<E: std::fmt::Display>(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), String> {
    let tmp = temporary_beside(path);
    let done = render(&tmp).map_err(|e| e.to_string()).and_then(|()| {
        File::open(&tmp)
            .and_then(|f| f.sync_all())
            .and_then(|()| std::fs::rename(&tmp, path))
            .map_err(|e| e.to_string())
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done.map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("detach-files-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let d = scratch("replace");
        let p = d.join("out.csv");
        write_atomic(&p, b"old\n").unwrap();
        write_atomic(&p, b"new\n").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_failed_fill_keeps_the_old_file() {
        let d = scratch("fail");
        let p = d.join("out.json");
        write_atomic(&p, b"old").unwrap();
        let r = write_atomic_with(&p, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("disk full"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&p).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        let failed = render_atomic(&p, |tmp| {
            std::fs::write(tmp, "partial").unwrap();
            Err("drawing failed")
        });
        assert!(failed.unwrap_err().contains("drawing failed"));
        assert_eq!(std::fs::read(&p).unwrap(), b"old");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn temporary_keeps_folder_and_extension() {
        let t = temporary_beside(Path::new("a/b/atlas.png"));
        assert_eq!(t.parent(), Some(Path::new("a/b")));
        assert_eq!(t.extension().unwrap(), "png");
        assert!(t
            .file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with(".atlas."));
    }

    #[test]
    fn a_missing_folder_is_an_error() {
        let p = Path::new("/nonexistent-detach-dir/x.json");
        assert!(write_atomic(p, b"x").is_err());
    }
}
