//! The file readers fed random and truncated headers and bytes: every
//! `.npy`, CSV and estimates file either reads or is refused with a typed
//! error naming the file, never a panic, and no single allocation grows
//! beyond a small constant plus a few times the file's size (a header
//! claiming 2^64 values must not be believed).
//!
//! A counting global allocator records the largest allocation made while a
//! reader runs.

use proptest::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use v2ref_core::Error;
use v2ref_files::formats::{read_estimates, read_matrix, NpyRows};

/// The system allocator, recording the largest request since the last
/// [`reset_largest`].
struct Counting;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Tests of this binary run one at a time here (the allocator's record is
/// process-wide).
static SERIAL: Mutex<()> = Mutex::new(());

/// The reader's buffer (1 MiB) and a margin; beyond that, an allocation
/// must be paid for by the file's own bytes.
const FIXED_ALLOWANCE: usize = 2 << 20;

fn temp_file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Runs every reader on `path` and checks the outcome and the allocations.
fn read_all_ways(path: &Path, len: usize) -> Result<(), TestCaseError> {
    let _one = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    LARGEST.store(0, Ordering::Relaxed);
    let outcomes = std::panic::catch_unwind(|| {
        let m = match read_matrix(path, "input") {
            // A matrix read is whole: every row can be indexed.
            Ok(m) => {
                let whole = m.rows.checked_mul(m.cols) == Some(m.data.len());
                assert!(
                    whole,
                    "{} x {} with {} values",
                    m.rows,
                    m.cols,
                    m.data.len()
                );
                let _ = m.row(m.rows - 1);
                None
            }
            Err(e) => Some(e),
        };
        let e = read_estimates(path, None).err();
        let s = match NpyRows::open(path, "input") {
            Ok(Some(mut rows)) => {
                let mut block = Vec::new();
                let mut err = None;
                loop {
                    match rows.next_block(7, &mut block) {
                        Ok(0) => break,
                        Ok(_) => {}
                        Err(x) => {
                            err = Some(x);
                            break;
                        }
                    }
                }
                err
            }
            Ok(None) => None,
            Err(x) => Some(x),
        };
        [m, e, s]
    });
    let largest = LARGEST.load(Ordering::Relaxed);
    let Ok(errors) = outcomes else {
        return Err(TestCaseError::fail(format!(
            "a reader panicked on {}",
            path.display()
        )));
    };
    for e in errors.into_iter().flatten() {
        match &e {
            Error::Data { path: p, .. } | Error::Io { path: p, .. } => {
                prop_assert_eq!(p.as_path(), path, "{}", e);
            }
            Error::Invalid { .. } => {}
            other => return Err(TestCaseError::fail(format!("untyped refusal: {other:?}"))),
        }
    }
    prop_assert!(
        largest <= FIXED_ALLOWANCE + 8 * len,
        "an allocation of {} bytes for a file of {} bytes",
        largest,
        len
    );
    Ok(())
}

/// A `.npy` header text with the given shape and order, padded as numpy
/// pads it.
fn header_text(shape: &str, fortran: bool, descr: &str) -> String {
    let order = if fortran { "True" } else { "False" };
    let mut h = format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    h
}

/// Dimensions from ordinary to absurd.
fn dim() -> impl Strategy<Value = u64> {
    prop_oneof![
        0u64..6,
        Just(1u64 << 32),
        Just(1u64 << 61),
        Just(u64::MAX),
        Just(i64::MAX as u64),
        any::<u64>(),
    ]
}

fn shape() -> impl Strategy<Value = String> {
    prop::collection::vec(dim(), 0..4).prop_map(|d| match d.len() {
        1 => format!("({},)", d[0]),
        _ => format!(
            "({})",
            d.iter().map(u64::to_string).collect::<Vec<_>>().join(", ")
        ),
    })
}

/// A `.npy` file: a well-formed or damaged preamble, a header claiming any
/// shape, and any number of data bytes, possibly truncated anywhere.
fn npy_bytes() -> impl Strategy<Value = Vec<u8>> {
    (
        shape(),
        any::<bool>(),
        prop_oneof![
            Just("<f8"),
            Just(">f8"),
            Just("<i8"),
            Just("|u1"),
            Just("<f4")
        ],
        prop_oneof![Just(1u8), Just(2u8), Just(3u8), any::<u8>()],
        prop_oneof![Just(None), any::<u32>().prop_map(Some)],
        prop::collection::vec(any::<u8>(), 0..400),
        prop_oneof![Just(None), any::<usize>().prop_map(Some)],
    )
        .prop_map(|(shape, fortran, descr, version, claimed, data, cut)| {
            let h = header_text(&shape, fortran, descr);
            let mut out = b"\x93NUMPY".to_vec();
            out.push(version);
            out.push(0);
            let len = claimed.unwrap_or(h.len() as u32);
            if version == 1 {
                out.extend_from_slice(&(len as u16).to_le_bytes());
            } else {
                out.extend_from_slice(&len.to_le_bytes());
            }
            out.extend_from_slice(h.as_bytes());
            out.extend_from_slice(&data);
            if let Some(c) = cut {
                out.truncate(c % (out.len() + 1));
            }
            out
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn npy_headers_and_data_of_any_claim(bytes in npy_bytes()) {
        let dir = tempfile::tempdir().unwrap();
        let p = temp_file(dir.path(), "x.npy", &bytes);
        read_all_ways(&p, bytes.len())?;
    }

    #[test]
    fn npy_of_random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        let dir = tempfile::tempdir().unwrap();
        let mut with_magic = b"\x93NUMPY".to_vec();
        with_magic.extend_from_slice(&bytes);
        for (name, b) in [("a.npy", &bytes), ("b.npy", &with_magic)] {
            let p = temp_file(dir.path(), name, b);
            read_all_ways(&p, b.len())?;
        }
    }

    #[test]
    fn csv_of_random_text_and_bytes(
        text in "[0-9eE+.,#\n -]{0,300}|(v1_sq|v2_sq|row|x)(,(v1_sq|v2_sq|row|1e308|nan|inf|-0)){0,4}\n([0-9.,e-]{0,20}\n){0,8}",
        bytes in prop::collection::vec(any::<u8>(), 0..200),
    ) {
        let dir = tempfile::tempdir().unwrap();
        for (name, b) in [("a.csv", text.as_bytes()), ("b.csv", &bytes[..])] {
            let p = temp_file(dir.path(), name, b);
            read_all_ways(&p, b.len())?;
        }
    }
}

/// Claimed shapes that panicked or aborted a reader before issue 35.
const OVERFLOWING_SHAPES: [&str; 6] = [
    "(4294967296, 4294967296)",
    "(2305843009213693952, 8)",
    "(18446744073709551615, 3)",
    "(3, 6148914691236517206)",
    // Past u64: refused by v2ref's own reading of the shape.
    "(99999999999999999999999, 1)",
    // No values, but npyz's strides (products of the trailing
    // dimensions) overflow: a panic in the test profile.
    "(0, 4294967296, 4294967296)",
];

/// A `.npy` of `<f8` that is a header claiming `shape` and no data.
fn npy_header_only(shape: &str) -> Vec<u8> {
    let h = header_text(shape, false, "<f8");
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(h.len() as u16).to_le_bytes());
    bytes.extend_from_slice(h.as_bytes());
    bytes
}

/// The headers that panicked or aborted before this round, each refused by
/// name (a test that fails on the old reader).
#[test]
fn claimed_shapes_that_overflow_are_refused_with_the_header() {
    let dir = tempfile::tempdir().unwrap();
    for shape in OVERFLOWING_SHAPES {
        let bytes = npy_header_only(shape);
        let p = temp_file(dir.path(), "big.npy", &bytes);
        let e = read_matrix(&p, "input").unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("input") && text.contains("header") && text.contains("claims"),
            "{shape}: {text}"
        );
        read_all_ways(&p, bytes.len()).unwrap();
    }
    // A version-2 header claiming 4 GiB of header text, in a 16-byte file.
    let mut bytes = b"\x93NUMPY\x02\x00".to_vec();
    bytes.extend_from_slice(&u32::MAX.to_le_bytes());
    bytes.extend_from_slice(b"{'descr'");
    let p = temp_file(dir.path(), "hdr.npy", &bytes);
    let text = read_matrix(&p, "calibrator").unwrap_err().to_string();
    assert!(
        text.contains("calibrator") && text.contains("header claims"),
        "{text}"
    );
    read_all_ways(&p, bytes.len()).unwrap();
}

/// A column read twice is refused by its name and both places, whichever
/// holds the junk (before, the first was read without a word).
#[test]
fn an_estimates_column_named_twice_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    for (header, twice, places) in [
        ("v1_sq,v2_sq,v1_sq", "v1_sq", "columns 1 and 3"),
        ("row,v2_sq,v2_sq", "v2_sq", "columns 2 and 3"),
    ] {
        let text = format!("{header}\n1,0.5,0.25\n2,0.5,0.25\n");
        let p = temp_file(dir.path(), "twice.csv", text.as_bytes());
        let e = read_estimates(&p, None).unwrap_err().to_string();
        assert!(
            e.contains("estimates") && e.contains(twice) && e.contains(places),
            "{header}: {e}"
        );
    }
}

/// The binary refuses the same headers with status 2 and one line naming
/// `--input`, in every build profile: with overflow checks on (`cargo
/// test`'s profile, which CI runs this suite in too) the binary of
/// 02610a7 panicked inside npyz's header parsing (status 101) before its
/// own check ran.
#[test]
fn claimed_shapes_that_overflow_are_refused_by_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    for shape in OVERFLOWING_SHAPES {
        temp_file(dir.path(), "big.npy", &npy_header_only(shape));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .current_dir(dir.path())
            .args(["estimate", "--input", "big.npy"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{shape}: {err}");
        assert!(
            err.lines().count() == 1 && err.contains("--input") && err.contains("header"),
            "{shape}: {err}"
        );
    }
}

/// `score` refuses an estimates CSV with a column named twice, naming it
/// and both places, with status 2 (before, it scored the first column,
/// here junk, without a word).
#[test]
fn score_refuses_an_estimates_column_named_twice() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let v2ref = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .current_dir(d)
            .args(args)
            .output()
            .unwrap()
    };
    let synth = ["synth", "--rows", "4", "--samples", "16", "--quiet"];
    assert!(v2ref(&[&synth[..], &["--out", "set"]].concat())
        .status
        .success());
    let estimated = v2ref(&["estimate", "--sidecar", "set.json"]);
    assert!(estimated.status.success());
    // The estimates' columns, then a junk v1_sq before them.
    let text = String::from_utf8(estimated.stdout).unwrap();
    let mut lines = text.lines();
    let header = format!("v1_sq,{}", lines.next().unwrap());
    let rows: Vec<String> = lines.map(|l| format!("1e9,{l}")).collect();
    let csv = format!("{header}\n{}\n", rows.join("\n"));
    temp_file(d, "twice.csv", csv.as_bytes());
    let out = v2ref(&["score", "--sidecar", "set.json", "--estimates", "twice.csv"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--estimates") && err.contains("v1_sq") && err.contains("columns 1 and 6"),
        "{err}"
    );
}
