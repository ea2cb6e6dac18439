//! cfitsio files being written, in memory: built in a buffer cfitsio
//! grows with the C allocator, then copied out and written atomically.
//! No cfitsio file name is ever parsed, so a path holding `[`, `]` or `!`
//! is just a path. (Files are read without cfitsio: [`super::fits`].)

use super::status_text;
use fitsio::{FileOpenMode, FitsFile};
use std::os::raw::{c_int, c_void};
use std::ptr;

extern "C" {
    fn malloc(size: usize) -> *mut c_void;
    fn realloc(p: *mut c_void, size: usize) -> *mut c_void;
    fn free(p: *mut c_void);
}

use super::fits::BLOCK;

/// The buffer and its size, at a fixed address while cfitsio holds
/// pointers to both.
struct Buffer {
    ptr: *mut c_void,
    size: usize,
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: `ptr` was allocated by malloc (or realloc by cfitsio) and
        // is freed once, after the file holding it is closed.
        unsafe { free(self.ptr) };
    }
}

/// A FITS file being written in memory. Fields drop in order: the file
/// is closed before its buffer is freed.
pub(crate) struct MemFits {
    /// The file (primary HDU created), for `fitsio`'s calls.
    pub(crate) file: FitsFile,
    buf: Box<Buffer>,
}

/// A failed cfitsio call, in words.
fn check(status: c_int, what: &str) -> Result<(), String> {
    if status == 0 {
        Ok(())
    } else {
        Err(format!("{what}: {}", status_text(status)))
    }
}

impl MemFits {
    /// A new file in memory with an empty primary HDU.
    pub(crate) fn create() -> Result<MemFits, String> {
        // SAFETY: a fresh malloc'd block handed to cfitsio with the matching
        // realloc; `buf` is boxed so the pointers cfitsio keeps stay valid.
        unsafe {
            let p = malloc(BLOCK);
            if p.is_null() {
                return Err("out of memory".into());
            }
            let mut buf = Box::new(Buffer {
                ptr: p,
                size: BLOCK,
            });
            let mut fptr = ptr::null_mut();
            let mut status = 0;
            fitsio_sys::ffimem(
                &mut fptr,
                &mut buf.ptr,
                &mut buf.size,
                16 * BLOCK,
                Some(realloc),
                &mut status,
            );
            check(status, "creating the file in memory")?;
            fitsio_sys::ffcrim(fptr, 8, 0, ptr::null_mut(), &mut status);
            if status != 0 {
                let mut ignored = 0;
                fitsio_sys::ffclos(fptr, &mut ignored);
                return Err(format!("creating the primary HDU: {}", status_text(status)));
            }
            let file = FitsFile::from_raw(fptr, FileOpenMode::READWRITE)
                .map_err(|e| format!("opening the file in memory: {e}"))?;
            Ok(MemFits { file, buf })
        }
    }

    /// Writes every HDU's `CHECKSUM` and `DATASUM`, flushes and closes the
    /// file; its bytes (a whole number of blocks).
    pub(crate) fn into_bytes(mut self) -> Result<Vec<u8>, String> {
        let mut status = 0;
        let (mut nhdu, mut head, mut start, mut end) = (0, 0, 0, 0);
        // SAFETY: the file is open; the calls write the out-parameters and
        // the file's own buffer, which cfitsio grows itself (realloc).
        unsafe {
            let fptr = self.file.as_raw();
            fitsio_sys::ffthdu(fptr, &mut nhdu, &mut status);
            for hdu in 1..=nhdu {
                fitsio_sys::ffmahd(fptr, hdu, ptr::null_mut(), &mut status);
                fitsio_sys::ffpcks(fptr, &mut status);
            }
            fitsio_sys::ffflus(fptr, &mut status);
            fitsio_sys::ffmahd(fptr, nhdu, ptr::null_mut(), &mut status);
            fitsio_sys::ffghadll(fptr, &mut head, &mut start, &mut end, &mut status);
        }
        check(status, "finishing the file")?;
        let MemFits { file, buf } = self;
        drop(file);
        let len = usize::try_from(end).unwrap_or(usize::MAX);
        if len == 0 || len % BLOCK != 0 || len > buf.size {
            return Err(format!(
                "cfitsio ended the file at byte {end} of a {}-byte buffer",
                buf.size
            ));
        }
        // SAFETY: `buf.ptr` holds `buf.size >= len` initialized bytes
        // written by cfitsio, and the file is closed.
        Ok(unsafe { std::slice::from_raw_parts(buf.ptr as *const u8, len) }.to_vec())
    }
}
