//! Reading what a stranger sends: only regular files, never more than a cap,
//! a FIFO never waited on; a folder's `.json` files and its manifest lines,
//! which must name files inside the folder. `detach verify` and `--scene-file`
//! read through here too.

use std::fs::{File, Metadata};
use std::io::Read;
use std::path::{Path, PathBuf};

/// Largest proof file read (bytes).
pub const MAX_PROOF_BYTES: u64 = 32 << 20;

/// Largest `MANIFEST.sha256` read (bytes): a line per proof is far less.
pub const MAX_MANIFEST_BYTES: u64 = 1 << 20;

/// The name of a folder's manifest.
pub const MANIFEST: &str = "MANIFEST.sha256";

/// What a path is, for a message: `a named pipe`, `a directory`, …
fn kind(m: &Metadata) -> &'static str {
    let t = m.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else {
        "a special file"
    }
}

/// Opens without waiting for a writer: a FIFO swapped in after the check
/// must not block (`O_NONBLOCK`; its value on Linux and on the BSDs/macOS).
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    let mut o = std::fs::OpenOptions::new();
    o.read(true);
    #[cfg(any(target_os = "linux", target_os = "android"))]
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut o, 0o4000);
    #[cfg(any(target_os = "macos", target_os = "freebsd", target_os = "openbsd"))]
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut o, 0x4);
    o.open(path)
}

/// The bytes of the regular file at `path` (links followed), at most `cap`
/// of them; anything else (a pipe, a device, a folder, a larger file) is
/// refused with a one-line reason (without the path), before anything is
/// read.
pub fn read_regular(path: &Path, cap: u64) -> Result<Vec<u8>, String> {
    let not_regular = |m: &Metadata| format!("{}, not a regular file", kind(m));
    let cannot = |e: std::io::Error| format!("cannot read: {e}");
    let m = std::fs::metadata(path).map_err(cannot)?;
    if !m.is_file() {
        return Err(not_regular(&m));
    }
    let f = open_nonblocking(path).map_err(cannot)?;
    // The file opened may not be the one looked at: look again.
    let m = f.metadata().map_err(cannot)?;
    if !m.is_file() {
        return Err(not_regular(&m));
    }
    let too_large =
        |n: u64| format!("larger than {cap} bytes ({n} bytes), the limit for this kind of file");
    if m.len() > cap {
        return Err(too_large(m.len()));
    }
    let mut bytes = Vec::with_capacity(m.len() as usize);
    // One byte past the cap tells a file that grew while read.
    f.take(cap + 1).read_to_end(&mut bytes).map_err(cannot)?;
    if bytes.len() as u64 > cap {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// The `.json` entries directly in `dir` that are not hidden (a leading
/// `.`: detach's temporaries among them), sorted by name (whatever their
/// type: a pipe or a folder named `x.json` is then refused by its check,
/// not skipped). An entry that cannot be listed fails the whole folder.
pub fn json_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for e in std::fs::read_dir(dir)? {
        let p = e?.path();
        let hidden = p
            .file_name()
            .is_some_and(|n| n.as_encoded_bytes().starts_with(b"."));
        if !hidden && p.extension().is_some_and(|x| x == "json") {
            files.push(p);
        }
    }
    files.sort();
    Ok(files)
}

/// One line of a manifest: the SHA-256 (64 lowercase hex digits) a file
/// must have, and the file, inside the manifest's folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ManifestEntry {
    pub sha256: String,
    pub path: PathBuf,
}

/// The entries of `dir/MANIFEST.sha256` (`sha256sum` text: `HASH␣␣NAME` a
/// line), or `None` when there is no manifest. A manifest that is not a
/// regular UTF-8 file, or a line that is not `HASH␣␣NAME` with NAME a plain
/// file name of the folder (no `/`, `\`, `..`, NUL, nor a leading `.`),
/// is an error: a manifest is never skipped.
pub fn manifest_entries(dir: &Path) -> Result<Option<Vec<ManifestEntry>>, String> {
    let path = dir.join(MANIFEST);
    if let Err(e) = std::fs::symlink_metadata(&path) {
        if e.kind() == std::io::ErrorKind::NotFound {
            return Ok(None);
        }
        return Err(format!("cannot read {}: {e}", path.display()));
    }
    let bytes =
        read_regular(&path, MAX_MANIFEST_BYTES).map_err(|e| format!("{}: {e}", path.display()))?;
    let text = String::from_utf8(bytes)
        .map_err(|e| format!("{} is not UTF-8 text: {e}", path.display()))?;
    let mut entries = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |why: &str| format!("{} line {}: {why}", path.display(), i + 1);
        // `sha256sum` writes `HASH  NAME` (text mode) or `HASH *NAME` (binary).
        let Some((hash, name)) = line
            .split_once("  ")
            .or_else(|| line.split_once(" *"))
            .filter(|(h, _)| !h.contains(' '))
        else {
            return Err(bad("not `SHA256  NAME` or `SHA256 *NAME`"));
        };
        if hash.len() != 64 || !hash.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(bad("the hash is not 64 hex digits"));
        }
        let plain = !name.is_empty()
            && !name.starts_with('.')
            && !name.contains(['/', '\\', '\0'])
            && Path::new(name).file_name() == Some(name.as_ref());
        if !plain {
            return Err(bad("the name must be a file of the folder (no path)"));
        }
        entries.push(ManifestEntry {
            sha256: hash.to_ascii_lowercase(),
            path: dir.join(name),
        });
    }
    Ok(Some(entries))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("detach-check-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_folder_and_a_device_are_refused_before_reading() {
        let d = tmp("kinds");
        let e = read_regular(&d, 10).unwrap_err();
        assert!(e.contains("a directory"), "{e}");
        #[cfg(unix)]
        {
            let e = read_regular(Path::new("/dev/zero"), 10).unwrap_err();
            assert!(e.contains("a device"), "{e}");
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_file_past_the_cap_is_refused() {
        let d = tmp("cap");
        let f = d.join("a.json");
        std::fs::write(&f, [b'x'; 11]).unwrap();
        assert!(read_regular(&f, 10)
            .unwrap_err()
            .contains("larger than 10 bytes"));
        assert_eq!(read_regular(&f, 11).unwrap().len(), 11);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_folder_lists_its_json_but_not_hidden_temporaries() {
        let d = tmp("listing");
        for name in ["b.json", "a.json", ".a.123-9f.tmp.json", ".x.json", "c.txt"] {
            std::fs::write(d.join(name), "{}").unwrap();
        }
        let names: Vec<_> = json_files(&d)
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["a.json", "b.json"]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn manifest_names_stay_inside_the_folder() {
        let d = tmp("names");
        let h = "0".repeat(64);
        for name in [
            "../x.json",
            "/etc/passwd",
            "a/b.json",
            "..",
            ".",
            "",
            "a\\b.json",
            ".hidden",
        ] {
            std::fs::write(d.join(MANIFEST), format!("{h}  {name}\n")).unwrap();
            assert!(manifest_entries(&d).is_err(), "{name:?} accepted");
        }
        // Both of sha256sum's forms name the same file.
        for line in [format!("{h}  a.json\n"), format!("{h} *a.json\n")] {
            std::fs::write(d.join(MANIFEST), line).unwrap();
            let e = manifest_entries(&d).unwrap().unwrap();
            assert_eq!(e[0].path, d.join("a.json"));
        }
        for line in [format!("{h} a.json\n"), format!("{h}\t*a.json\n")] {
            std::fs::write(d.join(MANIFEST), line).unwrap();
            assert!(manifest_entries(&d).is_err());
        }
        std::fs::write(d.join(MANIFEST), format!("{}  a.json\n", "g".repeat(64))).unwrap();
        assert!(manifest_entries(&d).unwrap_err().contains("hex"));
        std::fs::remove_file(d.join(MANIFEST)).unwrap();
        assert_eq!(manifest_entries(&d).unwrap(), None);
        let _ = std::fs::remove_dir_all(&d);
    }
}
