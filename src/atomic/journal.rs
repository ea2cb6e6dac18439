//! The commit record of a set: what makes the placing of a set's files
//! (one rename per file) whole even when the process is killed between two
//! renames (SIGKILL, the OOM killer, a power cut), when no handler runs.
//!
//! Each member of a set has an entry beside it, `.v2ref-journal-HASH`
//! (HASH names the member's file, as its lock's does). Every entry holds
//! the same record: the writer's pid, whether it replaces (`--force`), and
//! for each member its target, its finished temporary and the old file
//! kept aside; the record ends with a checksum of its bytes, so a record
//! cut short (the writer killed while writing it) is told from a whole one.
//! One entry, the first member's, is the *commit record*; the others are
//! *intents*.
//!
//! The writer, once every temporary is complete and synced: writes and
//! syncs the intents, then the commit record (from its last byte on, the
//! set is committed), renames the temporaries one by one, removes the old
//! files, the commit record, then the intents; each step synced.
//!
//! Whoever next finds an entry of a member (a run that writes that member,
//! a run that reads it, a run that removes stale temporaries beside it)
//! first takes the locks of every member of the record: a live writer holds
//! them, and the finder is refused, naming the process. Then it finishes
//! the dead writer's work: with a whole commit record, the set is rolled
//! forward (the temporaries that remain take their places, they are
//! complete); without one (absent or cut short: the renames never
//! started), the temporaries and old copies are removed and the previous
//! set stays. Either way every file of the set is then the previous set's
//! or every one the new set's, never a mix.

use super::lock::{name_bytes, name_from_bytes, name_hash, OutputLock, LOCK_PREFIX};
use super::target::{check_replaceable, parent_of};
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// The prefix of an entry of a set's commit record.
pub(crate) const JOURNAL_PREFIX: &str = ".v2ref-journal-";

const HEADER: &str = "v2ref commit record 1";

/// One file of a set: absolute paths of where it goes, where it waits, and
/// where the file it replaces is kept (with `--force`) until the end.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Member {
    pub(crate) target: PathBuf,
    pub(crate) temp: PathBuf,
    pub(crate) old: Option<PathBuf>,
}

/// What every entry of one set holds.
#[derive(Debug, Clone, PartialEq)]
struct Record {
    pid: u32,
    force: bool,
    members: Vec<Member>,
}

/// The entry of `target` (an absolute path) in its folder.
pub(crate) fn entry_of(target: &Path) -> PathBuf {
    parent_of(target).join(format!("{JOURNAL_PREFIX}{}", name_hash(target)))
}

fn hex(path: &Path) -> String {
    name_bytes(path.as_os_str())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn unhex(text: &str) -> Option<PathBuf> {
    if text.len() % 2 != 0 || text.is_empty() {
        return None;
    }
    let bytes: Option<Vec<u8>> = (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(text.get(i..i + 2)?, 16).ok())
        .collect();
    Some(PathBuf::from(name_from_bytes(bytes?)))
}

/// FNV-1a of the record's bytes: a record cut short or altered fails it.
fn checksum(bytes: &[u8]) -> String {
    let h = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{h:016x}")
}

impl Record {
    fn to_bytes(&self) -> Vec<u8> {
        let mut text = format!(
            "{HEADER}\npid {}\nforce {}\n",
            self.pid,
            u8::from(self.force)
        );
        for m in &self.members {
            let old = m.old.as_deref().map_or_else(|| "-".to_owned(), hex);
            text += &format!("member {} {} {old}\n", hex(&m.target), hex(&m.temp));
        }
        let sum = checksum(text.as_bytes());
        format!("{text}sum {sum}\n").into_bytes()
    }

    /// The record in `bytes`; None when it is cut short or altered.
    fn parse(bytes: &[u8]) -> Option<Record> {
        let text = std::str::from_utf8(bytes).ok()?;
        let body_end = text.strip_suffix('\n')?.rfind('\n')? + 1;
        let (body, last) = text.split_at(body_end);
        if last != format!("sum {}\n", checksum(body.as_bytes())) {
            return None;
        }
        let mut lines = body.lines();
        if lines.next()? != HEADER {
            return None;
        }
        let pid = lines.next()?.strip_prefix("pid ")?.parse().ok()?;
        let force = match lines.next()? {
            "force 1" => true,
            "force 0" => false,
            _ => return None,
        };
        let members = lines.map(parse_member).collect::<Option<Vec<_>>>()?;
        (!members.is_empty()).then_some(Record {
            pid,
            force,
            members,
        })
    }

    /// The entries: the commit record's first, then the intents.
    fn entries(&self) -> Vec<PathBuf> {
        self.members.iter().map(|m| entry_of(&m.target)).collect()
    }
}

fn parse_member(line: &str) -> Option<Member> {
    let mut words = line.strip_prefix("member ")?.split(' ');
    let (target, temp, old) = (words.next()?, words.next()?, words.next()?);
    if words.next().is_some() {
        return None;
    }
    Some(Member {
        target: unhex(target)?,
        temp: unhex(temp)?,
        old: if old == "-" { None } else { Some(unhex(old)?) },
    })
}

/// Syncs the folder `dir`, so that a rename or a removal in it survives a
/// power cut. Ignored where folders cannot be synced.
pub(crate) fn sync_folder(dir: &Path) {
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

fn sync_folders_of(paths: impl IntoIterator<Item = PathBuf>) {
    let mut done: Vec<PathBuf> = Vec::new();
    for p in paths {
        let dir = parent_of(&p);
        if !done.contains(&dir) {
            sync_folder(&dir);
            done.push(dir);
        }
    }
}

fn write_synced(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write as _;
    let mut f = std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .open(path)?;
    f.write_all(bytes)?;
    f.sync_all()
}

fn output_error(path: &Path, e: std::io::Error) -> Error {
    Error::Output {
        path: path.display().to_string(),
        reason: format!("cannot write the set's commit record: {e}"),
    }
}

/// The record of a set being placed by this process.
pub(crate) struct Commit {
    record: Record,
}

impl Commit {
    /// Writes the intents, then the commit record: from its end on, the set
    /// is committed and a later run completes it if this one is killed.
    pub(crate) fn write(members: Vec<Member>, force: bool) -> Result<Commit> {
        let record = Record {
            pid: std::process::id(),
            force,
            members,
        };
        let bytes = record.to_bytes();
        let entries = record.entries();
        let commit = Commit { record };
        fault::point("before-journal");
        // A failed write (a full disk) leaves no entry behind.
        let failed = |e: &Path, err| {
            commit.remove_entries();
            output_error(e, err)
        };
        for e in &entries[1..] {
            write_synced(e, &bytes).map_err(|err| failed(e, err))?;
        }
        sync_folders_of(entries[1..].to_vec());
        let home = &entries[0];
        if fault::armed("in-journal") {
            let _ = write_synced(home, &bytes[..bytes.len() / 2]);
            fault::point("in-journal");
        }
        write_synced(home, &bytes).map_err(|err| failed(home, err))?;
        sync_folder(&parent_of(home));
        fault::point("after-journal");
        Ok(commit)
    }

    /// After the last rename: the folders synced, the old files, the
    /// commit record and the intents removed.
    pub(crate) fn finish(self) {
        let r = &self.record;
        sync_folders_of(r.members.iter().map(|m| m.target.clone()));
        for old in r.members.iter().filter_map(|m| m.old.as_ref()) {
            let _ = std::fs::remove_file(old);
        }
        fault::point("before-journal-removal");
        self.remove_entries();
    }

    /// The set is not placed (a rename failed; the placed files were put
    /// back): its entries removed.
    pub(crate) fn abandon(self) {
        self.remove_entries();
    }

    /// The commit record first, then the intents. Not synced: an entry
    /// that a power cut brings back finds its set placed, its temporaries
    /// and old files gone, and is removed with nothing to do.
    fn remove_entries(&self) {
        let entries = self.record.entries();
        let _ = std::fs::remove_file(&entries[0]);
        fault::point("after-journal-removal");
        for e in &entries[1..] {
            let _ = std::fs::remove_file(e);
        }
    }
}

/// The folder (resolved) and name of `path`: where its entry and lock are.
pub(crate) fn real_location(path: &Path) -> PathBuf {
    if let Ok(real) = std::fs::canonicalize(path) {
        return real;
    }
    let parent = parent_of(path);
    let parent = std::fs::canonicalize(&parent).unwrap_or(parent);
    parent.join(path.file_name().unwrap_or_default())
}

/// Before `path` (named by `param`) is read: when a set it belongs to was
/// left half placed by a process that died, the set is completed or
/// rolled back first (see the module doc); refused, naming the process,
/// while a live process places it.
pub fn settle_before_read(path: &Path, param: &'static str) -> Result<()> {
    let entry = entry_of(&real_location(path));
    if std::fs::symlink_metadata(&entry).is_err() {
        return Ok(());
    }
    settle(&entry, param, &[])
}

/// Completes (rolls forward) or rolls back the set of the entry `entry`,
/// holding the locks of all its members (those of `held`, absolute
/// targets, are already held by the caller). Refused, naming the process,
/// when a live process holds one; refused, naming the file, when a file
/// that appeared at a target would have to be replaced without `--force`
/// (the entry then stays, and every later reader is refused alike).
pub(crate) fn settle(entry: &Path, param: &'static str, held: &[PathBuf]) -> Result<()> {
    for _ in 0..8 {
        let Ok(bytes) = std::fs::read(entry) else {
            return Ok(());
        };
        let Some(record) = Record::parse(&bytes) else {
            return settle_cut_short(entry, &bytes, param);
        };
        let record = located(record, entry, param)?;
        let mut locks = Vec::new();
        for m in &record.members {
            if !held.contains(&m.target) {
                locks.push(OutputLock::acquire(&m.target, param)?);
            }
        }
        // Another run may have settled it between the read and the locks.
        if std::fs::read(entry).ok().as_deref() != Some(&bytes[..]) {
            continue;
        }
        let entries = record.entries();
        let committed = std::fs::read(&entries[0]).ok().as_deref() == Some(&bytes[..]);
        if committed {
            roll_forward(&record, param)?;
        } else {
            roll_back(&record);
        }
        let _ = std::fs::remove_file(&entries[0]);
        sync_folder(&parent_of(&entries[0]));
        for e in &entries[1..] {
            let _ = std::fs::remove_file(e);
        }
        sync_folders_of(entries[1..].to_vec());
        return Ok(());
    }
    Ok(())
}

/// The record as found at `entry`: as written, or, when its folder was
/// moved or copied since (the entry is not where the record puts it), its
/// members taken in the entry's folder. A set of several folders found
/// elsewhere cannot be placed: refused, naming the entry.
fn located(record: Record, entry: &Path, param: &'static str) -> Result<Record> {
    let here = real_location(&parent_of(entry));
    let entry = here.join(entry.file_name().unwrap_or_default());
    if record.entries().contains(&entry) {
        return Ok(record);
    }
    let folder = parent_of(&record.members[0].target);
    let one_folder = record.members.iter().all(|m| {
        [&m.target, &m.temp]
            .into_iter()
            .chain(&m.old)
            .all(|p| parent_of(p) == folder)
    });
    if !one_folder {
        return Err(Error::Invalid {
            param,
            reason: format!(
                "{}: the commit record of a set of several folders, moved here from {}; its files cannot be told whole: remove it and check the set",
                entry.display(),
                folder.display()
            ),
        });
    }
    let moved = |p: &Path| here.join(p.file_name().unwrap_or_default());
    let members = record.members.iter().map(|m| Member {
        target: moved(&m.target),
        temp: moved(&m.temp),
        old: m.old.as_deref().map(moved),
    });
    Ok(Record {
        members: members.collect(),
        ..record
    })
}

/// An entry cut short: its writer was killed while writing it, before any
/// rename (an intent is whole before the commit record is begun, and the
/// commit record before the first rename). Removed under its member's
/// lock; the temporaries stay for the stale cleanup (their process is
/// dead) unless an intent elsewhere names them.
fn settle_cut_short(entry: &Path, bytes: &[u8], param: &'static str) -> Result<()> {
    let name = entry.file_name().map(name_bytes).unwrap_or_default();
    let hash = name.strip_prefix(JOURNAL_PREFIX.as_bytes()).unwrap_or(&[]);
    let lock = parent_of(entry).join(format!("{LOCK_PREFIX}{}", String::from_utf8_lossy(hash)));
    let _lock = OutputLock::acquire_at(lock, entry, param)?;
    if std::fs::read(entry).ok().as_deref() == Some(bytes) {
        let _ = std::fs::remove_file(entry);
        sync_folder(&parent_of(entry));
    }
    Ok(())
}

#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::symlink_metadata(a), std::fs::symlink_metadata(b)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &Path, _: &Path) -> bool {
    false
}

/// The members whose temporary is still to take its place (a temporary
/// linked at its target already, its own name not yet removed, is placed).
fn to_place(record: &Record) -> impl Iterator<Item = &Member> {
    record
        .members
        .iter()
        .filter(|m| std::fs::symlink_metadata(&m.temp).is_ok() && !same_file(&m.temp, &m.target))
}

/// Places the temporaries that remain, then removes the rest. Checked
/// first, so that nothing moves when one cannot be placed.
fn roll_forward(record: &Record, param: &'static str) -> Result<()> {
    for m in to_place(record) {
        check_replaceable(&m.target, Some(param))?;
        if !record.force && std::fs::symlink_metadata(&m.target).is_ok() {
            return Err(Error::Invalid {
                param,
                reason: format!(
                    "{}: the set of process {} was stopped while its files took their places, and this file appeared since; remove it to let the set be completed",
                    m.target.display(),
                    record.pid
                ),
            });
        }
    }
    let pending: Vec<Member> = to_place(record).cloned().collect();
    for m in &pending {
        std::fs::rename(&m.temp, &m.target).map_err(|e| Error::file(Some(param), &m.target, e))?;
    }
    for m in &record.members {
        if std::fs::symlink_metadata(&m.temp).is_ok() && same_file(&m.temp, &m.target) {
            let _ = std::fs::remove_file(&m.temp);
        }
    }
    sync_folders_of(record.members.iter().map(|m| m.target.clone()));
    for old in record.members.iter().filter_map(|m| m.old.as_ref()) {
        let _ = std::fs::remove_file(old);
    }
    Ok(())
}

/// The renames never started: the temporaries and the old copies go, the
/// files at the targets (the previous set) stay.
fn roll_back(record: &Record) {
    for m in &record.members {
        if !same_file(&m.temp, &m.target) {
            let _ = std::fs::remove_file(&m.temp);
        }
        if let Some(old) = &m.old {
            let _ = std::fs::remove_file(old);
        }
    }
    sync_folders_of(record.members.iter().map(|m| m.target.clone()));
}

/// Settles every entry in `dir` that no live process holds; returns the
/// names in `dir` of the temporaries and old copies the entries that
/// remain still name (kept by the stale cleanup).
pub(crate) fn settle_folder(dir: &Path) -> Vec<std::ffi::OsString> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut kept = Vec::new();
    for entry in entries.flatten() {
        let name = name_bytes(&entry.file_name());
        if !name.starts_with(JOURNAL_PREFIX.as_bytes()) {
            continue;
        }
        let path = entry.path();
        if settle(&path, "out", &[]).is_ok() && std::fs::symlink_metadata(&path).is_err() {
            continue;
        }
        let record = std::fs::read(&path).ok().and_then(|b| Record::parse(&b));
        for m in record.iter().flat_map(|r| &r.members) {
            kept.extend(m.temp.file_name().map(ToOwned::to_owned));
            kept.extend(
                m.old
                    .iter()
                    .filter_map(|o| o.file_name().map(ToOwned::to_owned)),
            );
        }
    }
    kept
}

/// A test-only way to stop a run at a given step of placing a set, as a
/// SIGKILL there would: the process kills itself with SIGKILL when the
/// environment variable [`fault::VARIABLE`] is exactly a step's name
/// (`before-journal`, `in-journal` (the commit record half written),
/// `after-journal`, `after-rename-K` (K from 1), `before-journal-removal`,
/// `after-journal-removal`). Its long name is not one to set by accident.
pub(crate) mod fault {
    /// The variable's name.
    pub(crate) const VARIABLE: &str = "V2REF_TEST_ONLY_SIGKILL_SELF_AT_SET_COMMIT_STEP";

    /// Whether the process is asked to die at `step`.
    pub(crate) fn armed(step: &str) -> bool {
        std::env::var_os(VARIABLE).is_some_and(|v| v == step)
    }

    /// Dies here, as by a SIGKILL, when asked to at `step`.
    pub(crate) fn point(step: &str) {
        if armed(step) {
            kill_self();
        }
    }

    #[cfg(unix)]
    fn kill_self() {
        // SAFETY: `kill` only reads its arguments; the signal is sent to
        // this process, which it ends at once.
        unsafe {
            libc::kill(libc::getpid(), libc::SIGKILL);
        }
    }

    #[cfg(not(unix))]
    fn kill_self() {
        std::process::abort();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record() -> Record {
        Record {
            pid: 42,
            force: true,
            members: vec![
                Member {
                    target: PathBuf::from("/a/set.npy"),
                    temp: PathBuf::from("/a/.v2ref-tmp-42-0-set.npy"),
                    old: Some(PathBuf::from("/a/.v2ref-tmp-42-1000-set.npy")),
                },
                Member {
                    target: PathBuf::from("/b/set \u{e9}.json"),
                    temp: PathBuf::from("/b/.v2ref-tmp-42-0-set \u{e9}.json"),
                    old: None,
                },
            ],
        }
    }

    #[test]
    fn a_record_reads_back_and_a_cut_or_altered_one_is_refused() {
        let r = record();
        let bytes = r.to_bytes();
        assert_eq!(Record::parse(&bytes), Some(r));
        for cut in 0..bytes.len() {
            assert_eq!(Record::parse(&bytes[..cut]), None, "cut at {cut}");
        }
        let mut altered = bytes.clone();
        altered[30] ^= 1;
        assert_eq!(Record::parse(&altered), None);
    }
}
