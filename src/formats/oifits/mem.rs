//! cfitsio files in memory: built in a buffer cfitsio grows with the C
//! allocator (then copied out and written atomically), or opened read-only
//! on the bytes of a file already read. No cfitsio file name is ever
//! parsed, so a path holding `[`, `]` or `!` is just a path.

use super::status_text;
use fitsio::{FileOpenMode, FitsFile};
use std::os::raw::{c_int, c_void};
use std::ptr;

extern "C" {
    fn malloc(size: usize) -> *mut c_void;
    fn realloc(p: *mut c_void, size: usize) -> *mut c_void;
    fn free(p: *mut c_void);
}

/// One FITS block, bytes (every HDU is a whole number of them).
pub(crate) const BLOCK: usize = 2880;

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

    /// Flushes and closes the file; its bytes (a whole number of blocks).
    pub(crate) fn into_bytes(mut self) -> Result<Vec<u8>, String> {
        let mut status = 0;
        let (mut nhdu, mut head, mut start, mut end) = (0, 0, 0, 0);
        // SAFETY: the file is open; the calls only write the out-parameters.
        unsafe {
            let fptr = self.file.as_raw();
            fitsio_sys::ffflus(fptr, &mut status);
            fitsio_sys::ffthdu(fptr, &mut nhdu, &mut status);
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

/// A FITS file opened read-only on bytes in memory; closed on drop.
pub(crate) struct MemRead {
    pub(crate) fptr: *mut fitsio_sys::fitsfile,
    // cfitsio keeps pointers to these two until the file is closed.
    _ptr: Box<*mut c_void>,
    _size: Box<usize>,
    _bytes: Vec<u8>,
}

impl MemRead {
    /// Opens `bytes` (a whole file) read-only.
    pub(crate) fn open(mut bytes: Vec<u8>) -> Result<MemRead, String> {
        let mut ptr_box = Box::new(bytes.as_mut_ptr() as *mut c_void);
        let mut size_box = Box::new(bytes.len());
        let mut fptr = ptr::null_mut();
        let mut status = 0;
        let name = c"v2ref-input.fits";
        // SAFETY: the bytes and the two boxed words outlive the file (they
        // are owned by the returned value, which closes the file first);
        // READONLY with no realloc: cfitsio never writes or grows them.
        unsafe {
            fitsio_sys::ffomem(
                &mut fptr,
                name.as_ptr(),
                fitsio_sys::READONLY as c_int,
                &mut *ptr_box,
                &mut *size_box,
                0,
                None,
                &mut status,
            );
        }
        if status != 0 || fptr.is_null() {
            if !fptr.is_null() {
                let mut ignored = 0;
                // SAFETY: closing what ffomem opened.
                unsafe { fitsio_sys::ffclos(fptr, &mut ignored) };
            }
            return Err(format!("not a readable FITS file: {}", status_text(status)));
        }
        Ok(MemRead {
            fptr,
            _ptr: ptr_box,
            _size: size_box,
            _bytes: bytes,
        })
    }
}

impl Drop for MemRead {
    fn drop(&mut self) {
        let mut status = 0;
        // SAFETY: `fptr` was opened by ffomem and is closed once.
        unsafe { fitsio_sys::ffclos(self.fptr, &mut status) };
    }
}
