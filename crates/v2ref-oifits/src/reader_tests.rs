//! The safe reader on real files' bytes, with no cfitsio and no file
//! system: the tests Miri runs (`cargo +nightly miri test --lib
//! formats::oifits`, see tests/README.md), where any read outside a buffer
//! or use of uninitialised memory would stop the run. The files are
//! committed: an intact estimates file (12 rows, two `OI_VIS2` tables,
//! written by `v2ref estimate --out FILE.fits.gz`) and the damaged files
//! that crashed or fooled the reader before it was rewritten.

use super::integrity::ReadOptions;
use super::read::parse_oifits;
use std::io::Read;

const INTACT_GZ: &[u8] = include_bytes!("../../../tests/data/oifits_intact.fits.gz");
const DAMAGED_GZ: [(&str, &[u8]); 4] = [
    (
        "naxis1_inflated",
        include_bytes!("../../../tests/data/oifits_damaged/naxis1_inflated.fits.gz"),
    ),
    (
        "naxis2_inflated",
        include_bytes!("../../../tests/data/oifits_damaged/naxis2_inflated.fits.gz"),
    ),
    (
        "truncated_one_block",
        include_bytes!("../../../tests/data/oifits_damaged/truncated_one_block.fits.gz"),
    ),
    (
        "truncated_two_blocks",
        include_bytes!("../../../tests/data/oifits_damaged/truncated_two_blocks.fits.gz"),
    ),
];
const BLOCK: usize = 2880;
/// Damage is read past the checksums, so that the size checks face it.
const ANYWAY: ReadOptions = ReadOptions {
    accept_checksum_mismatch: true,
};

/// Under Miri (about 10^4 times slower) one case in `MIRI_EVERY` of the
/// cuts and flips runs: still every kind, at fewer places.
const MIRI_EVERY: usize = if cfg!(miri) { 8 } else { 1 };

fn gunzip(gz: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    flate2::read::GzDecoder::new(gz)
        .read_to_end(&mut out)
        .unwrap();
    out
}

/// The intact file's bytes, gunzipped once for every test.
fn intact() -> &'static [u8] {
    static BYTES: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    BYTES.get_or_init(|| gunzip(INTACT_GZ))
}

/// Replaces the value of the first card `key` in the header of HDU
/// `hdu` (0-based) with `value` (right-aligned in columns 11–30).
fn set_card(bytes: &mut [u8], hdu: usize, key: &str, value: i64) {
    let name = format!("{key:<8}= ");
    let mut seen = 0;
    let mut card = 0;
    while card * 80 < bytes.len() {
        let c = &bytes[card * 80..card * 80 + 80];
        if card % 36 == 0 && (c.starts_with(b"XTENSION") || c.starts_with(b"SIMPLE  ")) {
            seen += 1;
        }
        if seen == hdu + 1 && c.starts_with(name.as_bytes()) {
            let v = format!("{value:>20}");
            bytes[card * 80 + 10..card * 80 + 30].copy_from_slice(v.as_bytes());
            return;
        }
        card += 1;
    }
    panic!("no {key} in HDU {hdu}");
}

#[test]
fn the_intact_file_is_read_whole() {
    let file = parse_oifits(intact(), ReadOptions::default()).unwrap();
    assert_eq!(file.tables.len(), 2);
    for t in &file.tables {
        assert_eq!((t.rows, t.nwave, t.vis2data.len()), (12, 1, 12));
        assert!(t.vis2data.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn the_damaged_files_are_refused() {
    for (name, gz) in DAMAGED_GZ {
        let bytes = gunzip(gz);
        for options in [ReadOptions::default(), ANYWAY] {
            assert!(parse_oifits(&bytes, options).is_err(), "{name}");
        }
    }
}

#[test]
fn a_file_cut_anywhere_is_refused() {
    let bytes = intact();
    let cuts = (0..bytes.len() / BLOCK).flat_map(|b| [b * BLOCK, b * BLOCK + 1000]);
    for cut in cuts.step_by(MIRI_EVERY) {
        assert!(parse_oifits(&bytes[..cut], ANYWAY).is_err(), "cut at {cut}");
    }
}

#[test]
fn sizes_announced_beyond_the_bytes_are_refused() {
    let intact = intact();
    // HDU 6 (from 0) is the last OI_VIS2: 12 rows of 63 bytes in one
    // block of data.
    for (key, value) in [
        ("NAXIS2", 100),
        ("NAXIS2", 1 << 40),
        ("NAXIS1", 1000),
        ("NAXIS1", i64::MAX),
        ("PCOUNT", 1 << 20),
    ] {
        let mut bytes = intact.to_vec();
        set_card(&mut bytes, 6, key, value);
        assert!(parse_oifits(&bytes, ANYWAY).is_err(), "{key} = {value}");
    }
}

#[test]
fn flipped_bytes_are_read_or_refused_never_past_the_buffer() {
    let intact = intact();
    // A byte every 487 (a prime: offsets all over the cards and blocks of
    // the file), set to characters a header can hold.
    for (i, at) in (0..intact.len()).step_by(487 * MIRI_EVERY).enumerate() {
        let mut bytes = intact.to_vec();
        bytes[at] = b"9 -'=E/T"[i % 8];
        let _ = parse_oifits(&bytes, ANYWAY);
    }
}

/// The intact file's HDUs, each as its bytes.
fn hdu_bytes() -> Vec<Vec<u8>> {
    super::fits::parse(intact())
        .unwrap()
        .iter()
        .map(|h| [h.header_bytes, h.data].concat())
        .collect()
}

#[test]
fn an_hdu_removed_from_the_middle_is_read_with_a_note() {
    // OI_ARRAY (HDU 3) removed, as an editor does: the rest is whole.
    let mut hdus = hdu_bytes();
    hdus.remove(2);
    let file = parse_oifits(&hdus.concat(), ReadOptions::default()).unwrap();
    assert_eq!(file.tables.len(), 2);
    assert_eq!(file.notes.len(), 1, "{:?}", file.notes);
    assert!(file.notes[0].contains("written with 7 HDUs and holds 6: HDUs were removed"));
}

#[test]
fn a_cut_after_a_whole_hdu_is_refused_even_past_the_checksums() {
    let hdus = hdu_bytes();
    for held in 1..hdus.len() {
        let r = parse_oifits(&hdus[..held].concat(), ANYWAY).unwrap_err();
        assert!(r.reason.contains("truncated after a whole HDU"), "{r:?}");
    }
}

#[test]
fn an_unsigned_hdu_in_a_signed_file_is_read_and_named() {
    // An IMAGE extension of no data, with no CHECKSUM or DATASUM.
    let mut cards: Vec<u8> = [
        "XTENSION= 'IMAGE   '",
        "BITPIX  =                    8",
        "NAXIS   =                    0",
        "PCOUNT  =                    0",
        "GCOUNT  =                    1",
        "EXTNAME = 'LATER   '",
        "END",
    ]
    .iter()
    .flat_map(|c| format!("{c:<80}").into_bytes())
    .collect();
    cards.resize(BLOCK, b' ');
    let bytes = [intact(), &cards].concat();
    let file = parse_oifits(&bytes, ReadOptions::default()).unwrap();
    assert_eq!(file.tables.len(), 2);
    assert_eq!(file.notes.len(), 2, "{:?}", file.notes);
    assert!(file.notes[1].starts_with("HDU 8 (EXTNAME LATER) carries no CHECKSUM"));
}
