//! Output files and folders that a kill, a second writer or a special path
//! cannot spoil. Every file detach writes goes through this module:
//!
//! - `-` (and `/dev/stdout`) is standard output; a named pipe, a device or
//!   any path under `/dev` or `/proc` is opened and written in place (never
//!   replaced, never truncated by a rename).
//! - A regular file (or a missing one) is replaced atomically: the content
//!   goes to a temporary file beside it, created exclusively under a name no
//!   other writer can pick (`.NAME.PID-RANDOM.tmp.EXT`), is flushed to disk
//!   and renamed over the target. A kill, a full disk or `ulimit -f` leaves
//!   the previous file or the complete new one; of two concurrent writers,
//!   the last rename wins whole. The replaced file's permission bits are kept.
//! - A symlink is followed: its final target is replaced atomically, and the
//!   link stays a link.
//! - A folder written as a whole ([`FolderDraft`]) is built as a hidden
//!   sibling folder and swapped in by one atomic exchange, so the folder is
//!   the old one or the new one, never a mix. Entries of the old folder the
//!   run did not write are carried over unchanged.
//!
//! Live temporaries are registered; [`remove_temporaries_on_signals`] makes
//! SIGINT, SIGTERM and SIGHUP remove them and exit with 128 + the signal
//! number. Only SIGKILL (or a power cut) leaves a hidden temporary behind,
//! beside the target; the target itself is never partial.

use std::fs::{File, OpenOptions, Permissions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

/// The temporaries alive now (files and draft folders), removed on a signal.
struct Live {
    /// Set once a signal arrived: no new temporary may be created.
    stopping: bool,
    paths: Vec<PathBuf>,
}

static LIVE: Mutex<Live> = Mutex::new(Live {
    stopping: false,
    paths: Vec::new(),
});

fn live() -> MutexGuard<'static, Live> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes a file or a folder, whichever `path` is.
fn remove_any(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = std::fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// Removes every live temporary and refuses new ones; returns how many were
/// removed. The lock is kept by the caller until it exits, so no writer can
/// rename or create a temporary in between.
fn remove_all_temporaries(live: &mut Live) -> usize {
    live.stopping = true;
    let n = live.paths.len();
    for p in live.paths.drain(..) {
        remove_any(&p);
    }
    n
}

/// Makes SIGINT, SIGTERM and SIGHUP remove the live temporaries and exit
/// with 128 + the signal number (130, 143, 129), and makes a file-size limit
/// (`ulimit -f`) an error (EFBIG) instead of a silent death by SIGXFSZ.
/// Call it first in `main`, before any thread starts: the signals are
/// blocked in every thread and received by one thread that waits for them.
#[cfg(unix)]
pub fn remove_temporaries_on_signals() {
    // SAFETY: plain libc calls on a local signal set, before other threads
    // exist; SIG_IGN for SIGXFSZ makes write(2) return EFBIG.
    let set = unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&mut set, s);
        }
        libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut());
        set
    };
    std::thread::spawn(move || loop {
        let mut sig: libc::c_int = 0;
        // SAFETY: waits on the signals blocked above.
        if unsafe { libc::sigwait(&set, &mut sig) } != 0 {
            continue;
        }
        let mut live = live();
        let n = remove_all_temporaries(&mut live);
        let name = match sig {
            libc::SIGINT => "SIGINT",
            libc::SIGTERM => "SIGTERM",
            _ => "SIGHUP",
        };
        eprintln!(
            "detach: stopped by {name}; outputs left as they were ({n} temporar{} removed)",
            if n == 1 { "y" } else { "ies" }
        );
        std::process::exit(128 + sig);
    });
}

#[cfg(not(unix))]
pub fn remove_temporaries_on_signals() {}

/// A name no other writer picks: the process id (not unique across
/// containers sharing a folder) with a random part from std's per-process
/// random hash keys, the time and a counter. Creation is exclusive anyway.
fn unique_tag() -> String {
    use std::hash::{BuildHasher, Hasher};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or_default(),
    );
    h.write_usize(&h as *const _ as usize);
    format!("{}-{:016x}", std::process::id(), h.finish())
}

/// The temporary's name for `path`: hidden, in the same folder (a rename
/// stays on one file system) and with the same extension (image encoders
/// choose the format by it).
fn temporary_name(path: &Path) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let tag = unique_tag();
    let name = match path.extension() {
        Some(ext) => format!(".{stem}.{tag}.tmp.{}", ext.to_string_lossy()),
        None => format!(".{stem}.{tag}.tmp"),
    };
    path.with_file_name(name)
}

/// Whether `name` is one of detach's temporaries (`.NAME.….tmp[.EXT]`).
pub fn is_temporary_name(name: &str) -> bool {
    name.starts_with('.') && (name.ends_with(".tmp") || name.contains(".tmp."))
}

/// A registered temporary file or folder; removed when dropped unless it
/// was renamed into place.
struct Temporary {
    path: PathBuf,
}

impl Temporary {
    /// Creates, exclusively, a fresh temporary file (or folder) for `target`.
    fn create(target: &Path, folder: bool) -> io::Result<(Temporary, Option<File>)> {
        let mut live = live();
        if live.stopping {
            return Err(io::Error::new(io::ErrorKind::Interrupted, "stopping"));
        }
        for _ in 0..64 {
            let path = temporary_name(target);
            let made = if folder {
                std::fs::create_dir(&path).map(|()| None)
            } else {
                OpenOptions::new()
                    .write(true)
                    .create_new(true)
                    .open(&path)
                    .map(Some)
            };
            match made {
                Ok(file) => {
                    live.paths.push(path.clone());
                    return Ok((Temporary { path }, file));
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
        Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            "no free temporary name",
        ))
    }

    /// Renames the temporary over `target` (with `mode` if given).
    fn rename_onto(self, target: &Path, mode: Option<Permissions>) -> io::Result<()> {
        if let Some(mode) = mode {
            std::fs::set_permissions(&self.path, mode)?;
        }
        let mut live = live();
        if live.stopping {
            return Err(io::Error::new(io::ErrorKind::Interrupted, "stopping"));
        }
        std::fs::rename(&self.path, target)?;
        live.paths.retain(|p| p != &self.path);
        std::mem::forget(self);
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        let mut live = live();
        remove_any(&self.path);
        live.paths.retain(|p| p != &self.path);
    }
}

/// Where the bytes for an output path go.
enum Destination {
    Stdout,
    /// A pipe, a device or a path under `/dev` or `/proc`: written in place.
    InPlace(PathBuf),
    /// A regular file (or none yet) at this path, links followed: replaced
    /// atomically, keeping the old file's permission bits.
    Replace(PathBuf, Option<Permissions>),
}

/// Whether `path` means standard output: `-` or `/dev/stdout`.
pub fn is_stdout(path: &Path) -> bool {
    let s = path.as_os_str();
    s == "-" || s == "/dev/stdout" || s == "/dev/fd/1" || s == "/proc/self/fd/1"
}

/// `path` for messages: `standard output` for `-`.
pub fn shown(path: &Path) -> String {
    if is_stdout(path) {
        "standard output".into()
    } else {
        path.display().to_string()
    }
}

/// `path` with its last component's symlinks followed (at most 40).
fn follow_links(path: &Path) -> io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

fn destination(path: &Path) -> io::Result<Destination> {
    if is_stdout(path) {
        return Ok(Destination::Stdout);
    }
    if path.starts_with("/dev") || path.starts_with("/proc") {
        return Ok(Destination::InPlace(path.to_path_buf()));
    }
    let target = follow_links(path)?;
    match std::fs::metadata(&target) {
        Ok(m) if m.is_dir() => Err(io::Error::other("is a folder")),
        Ok(m) if m.is_file() => Ok(Destination::Replace(target, Some(m.permissions()))),
        Ok(_) => Ok(Destination::InPlace(target)),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(Destination::Replace(target, None)),
        Err(e) => Err(e),
    }
}

/// Writes through `fill` to a writer that is not replaced (stdout, a pipe, a
/// device). A reader of standard output that stops early (`| head`) ends
/// the output quietly, as for the command's other output.
fn write_in_place(
    dest: &Destination,
    fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    match dest {
        Destination::Stdout => {
            let mut w = BufWriter::new(io::stdout().lock());
            match fill(&mut w).and_then(|()| w.flush()) {
                Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
                r => r,
            }
        }
        Destination::InPlace(p) => {
            let mut w = BufWriter::new(OpenOptions::new().write(true).open(p)?);
            fill(&mut w)?;
            w.flush()
        }
        Destination::Replace(..) => unreachable!("replaced, not written in place"),
    }
}

/// Writes `bytes` to `path` (see the module's rules).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Writes `path` through `fill`, which writes to a buffered writer.
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let (target, mode) = match destination(path)? {
        Destination::Replace(target, mode) => (target, mode),
        other => return write_in_place(&other, fill),
    };
    let (tmp, file) = Temporary::create(&target, false)?;
    let mut w = BufWriter::new(file.expect("a file"));
    fill(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()?;
    tmp.rename_onto(&target, mode)
}

/// Lets `render` write a file at a temporary path (a drawing backend that
/// takes a path), then puts it at `path` by the module's rules.
pub fn render_atomic<E: std::fmt::Display>(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), String> {
    let fail = |e: String| format!("{}: {e}", shown(path));
    let dest = destination(path).map_err(|e| fail(e.to_string()))?;
    // In place: drawn beside the system's temporary files, then copied.
    let beside = match &dest {
        Destination::Replace(target, _) => target.clone(),
        _ => std::env::temp_dir().join(path.file_name().unwrap_or("out".as_ref())),
    };
    let (tmp, _) = Temporary::create(&beside, false).map_err(|e| fail(e.to_string()))?;
    render(&tmp.path).map_err(|e| fail(e.to_string()))?;
    let put = match dest {
        Destination::Replace(target, mode) => File::open(&tmp.path)
            .and_then(|f| f.sync_all())
            .and_then(|()| tmp.rename_onto(&target, mode)),
        other => std::fs::read(&tmp.path).and_then(|b| write_in_place(&other, |w| w.write_all(&b))),
    };
    put.map_err(|e| fail(e.to_string()))
}

/// A folder written as a whole: files go to a hidden sibling folder, and
/// [`FolderDraft::commit`] swaps it with the folder in one atomic step.
/// Dropped without a commit, the draft is removed and the folder untouched.
pub struct FolderDraft {
    target: PathBuf,
    draft: Temporary,
}

impl FolderDraft {
    /// Starts a draft of folder `target` (links followed). Refuses a target
    /// that is not a folder, and the current folder or one containing it
    /// (swapping it would pull the folder from under the user's shell).
    pub fn begin(target: &Path) -> io::Result<FolderDraft> {
        let target = follow_links(target)?;
        match std::fs::metadata(&target) {
            Ok(m) if !m.is_dir() => return Err(io::Error::other("not a folder")),
            Ok(_) => {
                let here = std::env::current_dir()?.canonicalize()?;
                if here.starts_with(target.canonicalize()?) {
                    return Err(io::Error::other(
                        "is the current folder or contains it; give a folder of its own",
                    ));
                }
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(e),
        }
        if let Some(parent) = target.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)?;
        }
        let (draft, _) = Temporary::create(&target, true)?;
        Ok(FolderDraft { target, draft })
    }

    /// Where the run writes its files.
    pub fn path(&self) -> &Path {
        &self.draft.path
    }

    /// Carries over what the old folder holds and the run did not write
    /// (detach's own leftover temporaries excepted), then puts the draft in
    /// the folder's place: an atomic exchange where the file system offers
    /// one, else two renames (a kill between them leaves the old folder
    /// aside as a hidden sibling). The old folder is then removed.
    pub fn commit(self) -> io::Result<()> {
        let FolderDraft { target, draft } = self;
        let old = match std::fs::metadata(&target) {
            Ok(m) => {
                carry_over(&target, &draft.path)?;
                std::fs::set_permissions(&draft.path, m.permissions())?;
                true
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => false,
            Err(e) => return Err(e),
        };
        if !old {
            return draft.rename_onto(&target, None);
        }
        let live = live();
        if live.stopping {
            return Err(io::Error::new(io::ErrorKind::Interrupted, "stopping"));
        }
        if exchange(&draft.path, &target).is_err() {
            // No atomic exchange here: old aside, new in.
            let aside = temporary_name(&target);
            std::fs::rename(&target, &aside)?;
            if let Err(e) = std::fs::rename(&draft.path, &target) {
                let _ = std::fs::rename(&aside, &target);
                return Err(e);
            }
            std::fs::rename(&aside, &draft.path)?;
        }
        drop(live);
        // `draft` now names the old folder; dropping it removes it.
        drop(draft);
        Ok(())
    }
}

/// Exchanges two paths atomically (Linux `renameat2(RENAME_EXCHANGE)`).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| CString::new(p.as_os_str().as_bytes()).map_err(io::Error::other);
    let (a, b) = (c(a)?, c(b)?);
    // SAFETY: two valid NUL-terminated paths; the call only renames.
    let r = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if r == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> io::Result<()> {
    Err(io::Error::from(io::ErrorKind::Unsupported))
}

/// Copies into `to` every entry of `from` that `to` lacks, recursively;
/// files by hard link where possible (no bytes copied), links as links.
fn carry_over(from: &Path, to: &Path) -> io::Result<()> {
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let name = entry.file_name();
        if is_temporary_name(&name.to_string_lossy()) {
            continue;
        }
        let (src, dst) = (entry.path(), to.join(&name));
        let kind = entry.file_type()?;
        if kind.is_dir() {
            if !dst.exists() {
                std::fs::create_dir(&dst)?;
                std::fs::set_permissions(&dst, std::fs::metadata(&src)?.permissions())?;
            }
            carry_over(&src, &dst)?;
        } else if std::fs::symlink_metadata(&dst).is_ok() {
            // Written by this run: the run's version wins.
        } else if kind.is_symlink() {
            symlink(&std::fs::read_link(&src)?, &dst)?;
        } else if kind.is_file() {
            if std::fs::hard_link(&src, &dst).is_err() {
                std::fs::copy(&src, &dst)?;
            }
        } else {
            return Err(io::Error::other(format!(
                "cannot carry over {}: not a file, folder or link",
                src.display()
            )));
        }
    }
    Ok(())
}

#[cfg(unix)]
fn symlink(to: &Path, at: &Path) -> io::Result<()> {
    std::os::unix::fs::symlink(to, at)
}

#[cfg(not(unix))]
fn symlink(_: &Path, at: &Path) -> io::Result<()> {
    Err(io::Error::other(format!(
        "cannot carry over the link {}",
        at.display()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("detach-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let d = scratch("replace");
        let p = d.join("out.csv");
        write_atomic(&p, b"old\n").unwrap();
        write_atomic(&p, b"new\n").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new\n");
        assert_eq!(names(&d), ["out.csv"]);
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
        assert_eq!(names(&d), ["out.json"]);
        let failed = render_atomic(&p, |tmp| {
            std::fs::write(tmp, "partial").unwrap();
            Err("drawing failed")
        });
        assert!(failed.unwrap_err().contains("drawing failed"));
        assert_eq!(std::fs::read(&p).unwrap(), b"old");
        assert_eq!(names(&d), ["out.json"]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn temporaries_are_hidden_unique_and_keep_folder_and_extension() {
        let t = temporary_name(Path::new("a/b/atlas.png"));
        assert_eq!(t.parent(), Some(Path::new("a/b")));
        assert_eq!(t.extension().unwrap(), "png");
        let name = t.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name.starts_with(".atlas."), "{name}");
        assert!(is_temporary_name(&name), "{name}");
        let u = temporary_name(Path::new("a/b/atlas.png"));
        assert_ne!(t, u, "two temporaries of one process share a name");
        assert!(!is_temporary_name("atlas.png") && !is_temporary_name(".hidden.json"));
    }

    #[test]
    fn a_missing_folder_is_an_error() {
        let p = Path::new("/nonexistent-detach-dir/x.json");
        assert!(write_atomic(p, b"x").is_err());
        assert!(live()
            .paths
            .iter()
            .all(|q| !q.starts_with("/nonexistent-detach-dir")));
    }

    /// Writers in one process (one PID) racing for one file: the file is
    /// always one writer's whole content. With the PID-only names of before,
    /// writers shared one temporary and tore it.
    #[test]
    fn same_pid_writers_never_tear_a_file() {
        let d = scratch("race");
        let p = d.join("race.csv");
        for round in 0..20 {
            let contents: Vec<Vec<u8>> = (0..8u8)
                .map(|i| vec![b'a' + i; 20_000 + 997 * usize::from(i) + round])
                .collect();
            std::thread::scope(|s| {
                for c in &contents {
                    let p = &p;
                    s.spawn(move || {
                        write_atomic_with(p, |w| {
                            for chunk in c.chunks(1000) {
                                w.write_all(chunk)?;
                                w.flush()?;
                                std::thread::yield_now();
                            }
                            Ok(())
                        })
                        .unwrap()
                    });
                }
            });
            let got = std::fs::read(&p).unwrap();
            assert!(contents.contains(&got), "torn: {} bytes", got.len());
            assert_eq!(names(&d), ["race.csv"]);
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[cfg(unix)]
    #[test]
    fn permission_bits_of_a_replaced_file_are_kept() {
        use std::os::unix::fs::PermissionsExt;
        let d = scratch("mode");
        let p = d.join("leaves.csv");
        std::fs::write(&p, "old").unwrap();
        std::fs::set_permissions(&p, Permissions::from_mode(0o640)).unwrap();
        write_atomic(&p, b"new").unwrap();
        let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o7777;
        assert_eq!(mode, 0o640);
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_is_written_through_and_stays_a_link() {
        let d = scratch("link");
        std::fs::create_dir(d.join("real")).unwrap();
        let real = d.join("real/out.json");
        std::fs::write(&real, "old").unwrap();
        let link = d.join("link.json");
        std::os::unix::fs::symlink("real/out.json", &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert_eq!(names(&d), ["link.json", "real"]);
        assert_eq!(names(&d.join("real")), ["out.json"]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_folder_draft_swaps_whole_and_keeps_what_it_did_not_write() {
        let d = scratch("folder");
        let f = d.join("proofs");
        std::fs::create_dir_all(f.join("sub")).unwrap();
        std::fs::write(f.join("a.json"), "old a").unwrap();
        std::fs::write(f.join("README.md"), "mine").unwrap();
        std::fs::write(f.join("sub/x"), "mine too").unwrap();
        std::fs::write(f.join(".a.123.tmp.json"), "debris").unwrap();
        let draft = FolderDraft::begin(&f).unwrap();
        std::fs::write(draft.path().join("a.json"), "new a").unwrap();
        std::fs::write(draft.path().join("b.json"), "new b").unwrap();
        // Before the commit the folder is the old one, untouched.
        assert_eq!(std::fs::read(f.join("a.json")).unwrap(), b"old a");
        assert!(!f.join("b.json").exists());
        draft.commit().unwrap();
        assert_eq!(names(&f), ["README.md", "a.json", "b.json", "sub"]);
        assert_eq!(std::fs::read(f.join("a.json")).unwrap(), b"new a");
        assert_eq!(std::fs::read(f.join("README.md")).unwrap(), b"mine");
        assert_eq!(std::fs::read(f.join("sub/x")).unwrap(), b"mine too");
        assert_eq!(names(&d), ["proofs"], "the old folder or the draft is left");
        // A draft dropped without a commit leaves the folder as it was.
        let draft = FolderDraft::begin(&f).unwrap();
        std::fs::write(draft.path().join("a.json"), "newer").unwrap();
        drop(draft);
        assert_eq!(names(&d), ["proofs"]);
        assert_eq!(std::fs::read(f.join("a.json")).unwrap(), b"new a");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_folder_draft_refuses_a_file_and_the_current_folder() {
        let d = scratch("refuse");
        std::fs::write(d.join("file"), "x").unwrap();
        assert!(FolderDraft::begin(&d.join("file")).is_err());
        let err = FolderDraft::begin(Path::new(".")).err().unwrap();
        assert!(err.to_string().contains("current folder"), "{err}");
        assert_eq!(names(&d), ["file"]);
        let _ = std::fs::remove_dir_all(&d);
    }
}
