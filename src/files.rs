//! Files rigidlab writes, written so that nothing the user made is lost: a file is written whole
//! to a temporary file beside it and renamed over its name only once complete ([`Pending`],
//! [`write_replacing`]); a file the user did not ask to replace gets a name of its own, with a
//! counter ([`write_new`]); an output is never one of the run's inputs ([`same_file`]). Images
//! are encoded in memory first ([`png_bytes`]), so that a PNG is written whole as any file is.
//!
//! A file a command writes over from run to run (an image, a study's summary) carries rigidlab's
//! mark ([`Mark`]), and is replaced only where the mark shows rigidlab wrote it
//! ([`write_over_own`]): a user's photo or notes under the same name are refused and kept.
//!
//! Imports nothing of rigidlab: the command line, the report's CSV, the studies and the window
//! all write through it.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// How many names [`write_new`] tries (`name.ext`, `name-2.ext`, ... `name-9999.ext`).
const MAX_COUNTER: u32 = 9999;

/// A file being written: the bytes go to a temporary file in the destination's folder (so that
/// the rename is atomic) and [`Pending::commit`] renames it over the destination once they are
/// all written and flushed. Dropped without a commit (an error, a panic), the temporary file is
/// removed and the destination is left as it was.
///
/// A destination that exists and is not a regular file or a folder (`/dev/stdout`, a FIFO) is
/// written directly: there is nothing there to keep, and a rename would replace the device.
pub struct Pending {
    dest: PathBuf,
    tmp: Option<PathBuf>,
    file: Option<BufWriter<File>>,
}

impl Pending {
    /// Starts writing `dest`. The folder must exist.
    pub fn create(dest: &Path) -> io::Result<Pending> {
        if let Ok(meta) = fs::metadata(dest) {
            if !meta.is_file() && !meta.is_dir() {
                let file = OpenOptions::new().write(true).open(dest)?;
                return Ok(Pending {
                    dest: dest.to_path_buf(),
                    tmp: None,
                    file: Some(BufWriter::new(file)),
                });
            }
        }
        let (tmp, file) = temp_beside(dest)?;
        Ok(Pending {
            dest: dest.to_path_buf(),
            tmp: Some(tmp),
            file: Some(BufWriter::new(file)),
        })
    }

    /// Where the bytes go once committed.
    pub fn dest(&self) -> &Path {
        &self.dest
    }

    /// Flushes the bytes to disk and renames the temporary file over the destination.
    pub fn commit(mut self) -> io::Result<()> {
        let file = self
            .file
            .take()
            .expect("a pending file has its file until committed");
        let file = file.into_inner().map_err(|e| e.into_error())?;
        if self.tmp.is_some() {
            file.sync_all()?;
        }
        drop(file);
        if let Some(tmp) = self.tmp.take() {
            if let Err(e) = fs::rename(&tmp, &self.dest) {
                let _ = fs::remove_file(&tmp);
                return Err(e);
            }
        }
        Ok(())
    }

    /// Commits to a name of its own: `dest` if it is free, else `dest` with a counter
    /// (`name-2.ext`, `name-3.ext`, ...). Returns the name used. Never replaces a file.
    pub fn commit_new(mut self) -> io::Result<PathBuf> {
        let file = self
            .file
            .take()
            .expect("a pending file has its file until committed");
        let file = file.into_inner().map_err(|e| e.into_error())?;
        let Some(tmp) = self.tmp.take() else {
            // Written directly into a device or FIFO the user named.
            return Ok(self.dest.clone());
        };
        file.sync_all()?;
        drop(file);
        let result = claim(&tmp, &self.dest);
        let _ = fs::remove_file(&tmp);
        result
    }
}

impl Pending {
    /// Commits to `dest` only if no file has that name, else fails with `AlreadyExists` and
    /// leaves the file there as it was: for an output the user named that must never replace
    /// anything (`grade --out`), even a file made between a check and the write.
    pub fn commit_fresh(mut self) -> io::Result<()> {
        let file = self
            .file
            .take()
            .expect("a pending file has its file until committed");
        let file = file.into_inner().map_err(|e| e.into_error())?;
        let Some(tmp) = self.tmp.take() else {
            return Ok(());
        };
        file.sync_all()?;
        drop(file);
        let result = claim_upto(&tmp, &self.dest, 1);
        let _ = fs::remove_file(&tmp);
        result.map(|_| ())
    }
}

/// Renames `from` onto `name` if no file has that name: the name is reserved first
/// (`create_new`), so an earlier file is never renamed over. None when it is taken.
fn rename_onto_new(from: &Path, name: &Path) -> io::Result<Option<PathBuf>> {
    match OpenOptions::new().write(true).create_new(true).open(name) {
        Ok(_) => match fs::rename(from, name) {
            Ok(()) => Ok(Some(name.to_path_buf())),
            Err(e) => {
                let _ = fs::remove_file(name);
                Err(e)
            }
        },
        Err(e) if e.kind() == io::ErrorKind::AlreadyExists => Ok(None),
        Err(e) => Err(e),
    }
}

/// Links the finished temporary file under the first free name (a hard link fails where the name
/// is taken, so no file is replaced); where the file system has no hard links, the name is
/// reserved with an empty file made with `create_new` and the temporary file renamed over it.
fn claim(tmp: &Path, dest: &Path) -> io::Result<PathBuf> {
    claim_upto(tmp, dest, MAX_COUNTER)
}

/// [`claim`] over the first `max` names (1: `dest` only).
fn claim_upto(tmp: &Path, dest: &Path, max: u32) -> io::Result<PathBuf> {
    for n in 1..=max {
        let name = numbered(dest, n);
        match fs::hard_link(tmp, &name) {
            Ok(()) => return Ok(name),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(_) => {}
        }
        if let Some(name) = rename_onto_new(tmp, &name)? {
            return Ok(name);
        }
    }
    let what = if max <= 1 {
        format!("{} exists", dest.display())
    } else {
        format!(
            "{} and {max} numbered names after it are taken",
            dest.display()
        )
    };
    Err(io::Error::new(io::ErrorKind::AlreadyExists, what))
}

impl Write for Pending {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.file.as_mut().expect("not committed").write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file.as_mut().expect("not committed").flush()
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        self.file.take();
        if let Some(tmp) = self.tmp.take() {
            let _ = fs::remove_file(tmp);
        }
    }
}

/// A fresh temporary file in `dest`'s folder, named after it (`.NAME.PID-N.tmp`).
fn temp_beside(dest: &Path) -> io::Result<(PathBuf, File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = dest.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} names no file", dest.display()),
        )
    })?;
    let dir = match dest.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(
            ".{}.{}-{n}.tmp",
            name.to_string_lossy(),
            std::process::id()
        ));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// Writes `bytes` as `dest` whole: to a temporary file beside it, renamed over it once written.
/// An earlier `dest` stays as it was if anything fails.
pub fn write_replacing(dest: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut p = Pending::create(dest)?;
    p.write_all(bytes)?;
    p.commit()
}

/// Writes `bytes` under `dest`'s name if it is free, else under the first free numbered name
/// (`name-2.ext`, ...), whole as [`write_replacing`] does; never replaces a file. Returns the
/// name used.
pub fn write_new(dest: &Path, bytes: &[u8]) -> io::Result<PathBuf> {
    let mut p = Pending::create(dest)?;
    p.write_all(bytes)?;
    p.commit_new()
}

/// How a kind of file shows that rigidlab wrote it.
#[derive(Clone, Copy, Debug)]
pub enum Mark<'a> {
    /// A PNG with the text chunk `Software` = `rigidlab` ([`png_bytes`] writes it).
    Png,
    /// A text file whose first line is this one (a CSV's header, an HTML comment).
    FirstLine(&'a str),
}

/// The first line of the Markdown and SVG files rigidlab writes over from run to run.
pub const TEXT_MARK: &str = "<!-- written by rigidlab -->";

impl Mark<'_> {
    /// Whether `bytes` carry the mark.
    pub fn on(self, bytes: &[u8]) -> bool {
        match self {
            Mark::Png => {
                bytes.starts_with(b"\x89PNG") && contains(bytes, b"tEXtSoftware\0rigidlab")
            }
            Mark::FirstLine(line) => {
                let first = bytes.split(|&b| b == b'\n').next().unwrap_or_default();
                first.strip_suffix(b"\r").unwrap_or(first) == line.as_bytes()
            }
        }
    }
}

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// Err when `dest` holds a file rigidlab cannot show it wrote (no `mark`): checked before a
/// command does its work, so a refused output costs nothing. A missing `dest` is fine.
pub fn replaceable(dest: &Path, mark: Mark<'_>) -> io::Result<()> {
    match fs::metadata(dest) {
        Ok(meta) if meta.is_file() => {
            if mark.on(&fs::read(dest)?) {
                Ok(())
            } else {
                Err(io::Error::new(
                    io::ErrorKind::AlreadyExists,
                    format!(
                        "{} exists and rigidlab did not write it, so it is kept\n  help: give another name, or move that file away",
                        dest.display()
                    ),
                ))
            }
        }
        Ok(meta) if meta.is_dir() => Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            format!("{} is a folder\n  help: give a file name", dest.display()),
        )),
        _ => Ok(()),
    }
}

/// [`write_replacing`], but only over a file rigidlab wrote ([`replaceable`]); anything else at
/// `dest` is kept and the write refused.
pub fn write_over_own(dest: &Path, bytes: &[u8], mark: Mark<'_>) -> io::Result<()> {
    replaceable(dest, mark)?;
    write_replacing(dest, bytes)
}

/// `path` with the counter `n` before its extension: `a/b.ron` -> `a/b-2.ron` (n = 1: `path`).
pub fn numbered(path: &Path, n: u32) -> PathBuf {
    if n <= 1 {
        return path.to_path_buf();
    }
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().to_string());
    let name = match path.extension() {
        Some(ext) => format!("{stem}-{n}.{}", ext.to_string_lossy()),
        None => format!("{stem}-{n}"),
    };
    path.with_file_name(name)
}

/// Moves `path` aside to `path` + `suffix` (`prefs.ron` -> `prefs.ron.bad`), or to a numbered
/// name (`prefs.ron-2.bad`) where that is taken; never replaces a file. Returns the new name.
pub fn move_aside(path: &Path, suffix: &str) -> io::Result<PathBuf> {
    let mut aside = path.as_os_str().to_owned();
    aside.push(suffix);
    let aside = PathBuf::from(aside);
    for n in 1..=MAX_COUNTER {
        if let Some(name) = rename_onto_new(path, &numbered(&aside, n))? {
            return Ok(name);
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!("no free name beside {}", path.display()),
    ))
}

/// Whether `a` and `b` name the same file: the same canonical path (links and `..` resolved;
/// a path that does not exist yet by its folder's canonical path), or on Unix the same inode
/// (hard links).
pub fn same_file(a: &Path, b: &Path) -> bool {
    fn canonical(p: &Path) -> Option<PathBuf> {
        if let Ok(c) = p.canonicalize() {
            return Some(c);
        }
        let name = p.file_name()?;
        let dir = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(dir.canonicalize().ok()?.join(name))
    }
    if let (Some(x), Some(y)) = (canonical(a), canonical(b)) {
        if x == y {
            return true;
        }
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    false
}

/// An image as PNG bytes: 8-bit RGB (`alpha` false) or RGBA rows, top first.
pub fn png_bytes(width: u32, height: u32, alpha: bool, pixels: &[u8]) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(if alpha {
            png::ColorType::Rgba
        } else {
            png::ColorType::Rgb
        });
        enc.set_depth(png::BitDepth::Eight);
        // The mark that lets a later run replace this image and nothing else (Mark::Png).
        enc.add_text_chunk("Software".to_string(), "rigidlab".to_string())
            .map_err(|e| e.to_string())?;
        let mut w = enc.write_header().map_err(|e| e.to_string())?;
        w.write_image_data(pixels).map_err(|e| e.to_string())?;
        w.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rigidlab-files-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn only_a_file_rigidlab_marked_is_written_over() {
        let d = dir("own");
        let photo = d.join("photo.png");
        fs::write(&photo, b"\x89PNG a user's photo").unwrap();
        let ours = png_bytes(1, 1, false, &[0, 0, 0]).unwrap();
        assert!(Mark::Png.on(&ours), "png_bytes marks its images");
        let err = write_over_own(&photo, &ours, Mark::Png).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::AlreadyExists);
        assert_eq!(fs::read(&photo).unwrap(), b"\x89PNG a user's photo", "kept");
        let fresh = d.join("fresh.png");
        write_over_own(&fresh, &ours, Mark::Png).unwrap();
        write_over_own(&fresh, &ours, Mark::Png).expect("its own image is replaced");
        let notes = d.join("summary.md");
        fs::write(&notes, "my notes\n").unwrap();
        let md = format!("{TEXT_MARK}\n# summary\n");
        assert!(write_over_own(&notes, md.as_bytes(), Mark::FirstLine(TEXT_MARK)).is_err());
        assert_eq!(fs::read_to_string(&notes).unwrap(), "my notes\n");
        fs::remove_file(&notes).unwrap();
        write_over_own(&notes, md.as_bytes(), Mark::FirstLine(TEXT_MARK)).unwrap();
        write_over_own(&notes, md.as_bytes(), Mark::FirstLine(TEXT_MARK)).unwrap();
    }

    #[test]
    fn a_pending_file_dropped_leaves_the_old_one_and_no_temporary() {
        let d = dir("drop");
        let f = d.join("a.csv");
        fs::write(&f, "old").unwrap();
        {
            let mut p = Pending::create(&f).unwrap();
            p.write_all(b"new, half written").unwrap();
        }
        assert_eq!(fs::read_to_string(&f).unwrap(), "old");
        assert_eq!(fs::read_dir(&d).unwrap().count(), 1);
        write_replacing(&f, b"new").unwrap();
        assert_eq!(fs::read_to_string(&f).unwrap(), "new");
        assert_eq!(fs::read_dir(&d).unwrap().count(), 1);
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn write_new_and_move_aside_count_past_taken_names() {
        let d = dir("new");
        let f = d.join("s.ron");
        assert_eq!(write_new(&f, b"1").unwrap(), f);
        assert_eq!(write_new(&f, b"2").unwrap(), d.join("s-2.ron"));
        assert_eq!(write_new(&f, b"3").unwrap(), d.join("s-3.ron"));
        assert_eq!(fs::read_to_string(&f).unwrap(), "1");
        assert_eq!(fs::read_to_string(d.join("s-2.ron")).unwrap(), "2");
        assert_eq!(move_aside(&f, ".bad").unwrap(), d.join("s.ron.bad"));
        fs::write(&f, "4").unwrap();
        assert_eq!(move_aside(&f, ".bad").unwrap(), d.join("s.ron-2.bad"));
        assert_eq!(fs::read_to_string(d.join("s.ron.bad")).unwrap(), "1");
        assert_eq!(fs::read_dir(&d).unwrap().count(), 4);
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn same_file_sees_through_dots_and_links() {
        let d = dir("same");
        let f = d.join("l.ron");
        fs::write(&f, "x").unwrap();
        assert!(same_file(&f, &d.join(".").join("l.ron")));
        assert!(!same_file(&f, &d.join("m.ron")));
        fs::hard_link(&f, d.join("h.ron")).unwrap();
        assert!(same_file(&f, &d.join("h.ron")));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&f, d.join("s.ron")).unwrap();
            assert!(same_file(&d.join("s.ron"), &f));
        }
        let _ = fs::remove_dir_all(&d);
    }
}
