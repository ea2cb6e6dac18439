//! A Monte Carlo command split into ranges of its work units, for a run
//! spread over processes or machines (the Python package maps the ranges
//! on a Dask cluster; this crate knows nothing of Dask).
//!
//! A command's job ([`UnitJob`]) counts its units, runs a range of them
//! into a [`Partial`] (bytes that travel between processes or wait in a
//! checkpoint folder), and reduces the partials of every range, in unit
//! order, to the one-process command's answer, bit for bit. The units are
//! the library's own (fixed, keyed by what they compute, one generator
//! each), and a partial carries the result of each of its units, not a
//! merge of them: the one-process reduction merges unit by unit, and
//! floating-point merges regrouped by range would round differently.

pub mod piston;
pub mod simulate;
pub mod truth;
pub mod verify;

use crate::error::{Error, Result};
use std::ops::Range;

/// A Monte Carlo command as independent ranges of work units.
pub trait UnitJob {
    /// The one-process command's answer.
    type Answer;

    /// A hash of everything the answer depends on (the inputs, the seed,
    /// the size, this crate's version; not the thread count): partials
    /// of another request are refused.
    fn key(&self) -> u64;

    /// Number of work units.
    fn unit_count(&self) -> Result<u64>;

    /// Words of each unit's result (a partial of n units holds n times
    /// as many: what a reader of partials may expect, and no more).
    fn words_per_unit(&self) -> Result<usize>;

    /// [`UnitJob::unit_count`] and [`UnitJob::words_per_unit`] together
    /// (a job whose setup is costly overrides it to set up once).
    fn shape(&self) -> Result<(u64, usize)> {
        Ok((self.unit_count()?, self.words_per_unit()?))
    }

    /// Runs the units of `range` (within `0..unit_count()`); `progress`
    /// as the command's.
    fn run_range(&self, range: Range<u64>, progress: &(dyn Fn(u64) + Sync)) -> Result<Partial>;

    /// The answer from the partials of ranges that tile `0..unit_count()`
    /// in order.
    fn reduce(&self, partials: &[Partial]) -> Result<Self::Answer>;
}

/// The results of a range of units: per unit, a fixed number of 64-bit
/// words (floats by their bits).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Partial {
    /// The [`UnitJob::key`] of the request that computed it.
    pub key: u64,
    /// The units it holds.
    pub range: Range<u64>,
    /// Their results, unit after unit.
    pub words: Vec<u64>,
}

/// The first bytes of an encoded [`Partial`] (format version 2: version 1
/// had no checksum and is refused).
const MAGIC: &[u8; 8] = b"v2rpart2";

/// Header: magic, key, range start, range end, word count.
pub const HEADER_BYTES: usize = 8 + 4 * 8;

/// Bytes of an encoded partial beside its words: the header and the
/// trailing checksum.
pub const FRAME_BYTES: usize = HEADER_BYTES + 8;

impl Partial {
    /// The encoding: the 8 bytes `v2rpart2` (format version 2), then
    /// key, range start, range end, word count, the words and a checksum
    /// of every byte before it ([`checksum`]), little-endian.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(FRAME_BYTES + 8 * self.words.len());
        out.extend_from_slice(MAGIC);
        let header = [
            self.key,
            self.range.start,
            self.range.end,
            self.words.len() as u64,
        ];
        for w in header.iter().chain(&self.words) {
            out.extend_from_slice(&w.to_le_bytes());
        }
        let sum = checksum(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    /// Decodes [`Partial::to_bytes`]; refuses (parameter `partial`) other
    /// bytes, another format version, bytes whose checksum does not match
    /// (a bit flipped anywhere: in a result, the range or the key), or a
    /// partial of another request than `key`.
    pub fn from_bytes(bytes: &[u8], key: u64) -> Result<Partial> {
        let refuse = |reason: String| Error::Invalid {
            param: "partial",
            reason,
        };
        if bytes.len() < FRAME_BYTES || &bytes[..8] != MAGIC {
            return Err(refuse(
                "not a v2ref partial result of format version 2".into(),
            ));
        }
        if bytes.len() % 8 != 0 {
            return Err(refuse("a truncated or malformed partial result".into()));
        }
        let (body, sum) = bytes.split_at(bytes.len() - 8);
        let words: Vec<u64> = body[8..]
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        if u64::from_le_bytes(sum.try_into().unwrap_or([0; 8])) != checksum(body) {
            return Err(refuse(
                "its checksum does not match its content (a damaged partial result)".into(),
            ));
        }
        let (found, start, end, count) = (words[0], words[1], words[2], words[3]);
        if count != words.len() as u64 - 4 || start >= end {
            return Err(refuse("a truncated or malformed partial result".into()));
        }
        if found != key {
            return Err(refuse(format!(
                "computed for another request (key {found:016x}, this one {key:016x})"
            )));
        }
        Ok(Partial {
            key,
            range: start..end,
            words: words[4..].to_vec(),
        })
    }
}

/// Checks that `range` is a non-empty range of the `units` units.
pub fn check_range(range: &Range<u64>, units: u64) -> Result<()> {
    if range.start < range.end && range.end <= units {
        return Ok(());
    }
    Err(Error::Invalid {
        param: "units",
        reason: format!(
            "{}..{} is not a non-empty range of the {units} work units",
            range.start, range.end
        ),
    })
}

/// The words of every unit of `partials`, in unit order, `per_unit` words
/// each; refuses partials of another request, or that do not tile
/// `0..units` in order.
pub fn unit_words(
    partials: &[Partial],
    key: u64,
    units: u64,
    per_unit: usize,
) -> Result<Vec<&[u64]>> {
    let mut next = 0;
    let mut out = Vec::with_capacity(units as usize);
    for p in partials {
        let refuse = |reason: String| Error::Invalid {
            param: "partial",
            reason,
        };
        if p.key != key {
            return Err(refuse("computed for another request".into()));
        }
        if p.range.start != next || p.range.end <= next || p.range.end > units {
            return Err(refuse(format!(
                "units {}..{} where units {next}.. of {units} come next",
                p.range.start, p.range.end
            )));
        }
        if p.words.len() as u64 != (p.range.end - p.range.start) * per_unit as u64 {
            return Err(refuse("the wrong number of results for its units".into()));
        }
        out.extend(p.words.chunks_exact(per_unit));
        next = p.range.end;
    }
    if next != units {
        return Err(Error::Invalid {
            param: "partial",
            reason: format!("units {next}..{units} are missing"),
        });
    }
    Ok(out)
}

/// A 64-bit FNV-1a hash of `bytes` and this crate's version (a key of
/// [`UnitJob::key`]: partials of another version are refused too).
pub fn key_of(bytes: &[u8]) -> u64 {
    let version = env!("CARGO_PKG_VERSION").as_bytes();
    fnv1a(fnv1a(fnv1a(FNV_OFFSET, version), b"\0"), bytes)
}

/// The checksum of an encoded partial: FNV-1a (64 bits) of its bytes.
/// Chosen because it is already the keys' hash (no new dependency) and
/// every step is a bijection of the state for a given byte, so two
/// encodings of one length that differ in one byte (one bit flipped) never
/// share a checksum; other damage passes with a chance near 2⁻⁶⁴. It
/// detects damage and mix-ups, not forgery (docs/threat-model.md).
pub fn checksum(bytes: &[u8]) -> u64 {
    fnv1a(FNV_OFFSET, bytes)
}

/// FNV-1a's offset basis.
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a from the state `h` over `bytes`.
fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for b in bytes {
        h = (h ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The text that keys a spectrum CSV's table (its values, to the bit),
/// empty without one: a key hashes the table read, not the file's name,
/// so an edited file is another request.
pub fn spectrum_key_text(physical: &crate::parameters::Physical) -> String {
    physical
        .spectrum_csv
        .as_ref()
        .map_or_else(String::new, |f| format!("{:?}", f.spectrum()))
}

/// Words per [`RunningStats`](crate::montecarlo::RunningStats) in a
/// partial: its count, then its mean and central sums as f64 bits.
pub(crate) const STATS_WORDS: usize = 5;

/// Appends `stats`' words (exact: the bits, not a rounding).
pub(crate) fn put_stats(stats: &crate::montecarlo::RunningStats, out: &mut Vec<u64>) {
    out.push(stats.count);
    out.extend([stats.mean, stats.m2, stats.m3, stats.m4].map(f64::to_bits));
}

/// The statistics written by [`put_stats`], one per [`STATS_WORDS`] words.
pub(crate) fn take_stats(words: &[u64]) -> Vec<crate::montecarlo::RunningStats> {
    words
        .chunks_exact(STATS_WORDS)
        .map(|w| crate::montecarlo::RunningStats {
            count: w[0],
            mean: f64::from_bits(w[1]),
            m2: f64::from_bits(w[2]),
            m3: f64::from_bits(w[3]),
            m4: f64::from_bits(w[4]),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn partial() -> Partial {
        Partial {
            key: 7,
            range: 2..4,
            words: vec![1, 2, 3, 4],
        }
    }

    #[test]
    fn bytes_round_trip_and_refusals() {
        let bytes = partial().to_bytes();
        assert_eq!(Partial::from_bytes(&bytes, 7).unwrap(), partial());
        let param = |r: Result<Partial>| r.unwrap_err().param();
        assert_eq!(param(Partial::from_bytes(&bytes, 8)), Some("partial"));
        assert_eq!(
            param(Partial::from_bytes(&bytes[..bytes.len() - 8], 7)),
            Some("partial")
        );
        assert_eq!(
            param(Partial::from_bytes(&bytes[..bytes.len() - 1], 7)),
            Some("partial")
        );
        let mut other_version = bytes.clone();
        other_version[7] = b'1';
        assert_eq!(
            param(Partial::from_bytes(&other_version, 7)),
            Some("partial")
        );
        assert_eq!(param(Partial::from_bytes(b"v2r", 7)), Some("partial"));
    }

    #[test]
    fn every_bit_flipped_is_refused_by_the_checksum() {
        let bytes = partial().to_bytes();
        for bit in 0..8 * bytes.len() {
            let mut damaged = bytes.clone();
            damaged[bit / 8] ^= 1 << (bit % 8);
            let err = Partial::from_bytes(&damaged, 7).unwrap_err();
            assert_eq!(err.param(), Some("partial"), "bit {bit}");
        }
        // A flip in a word (a result, then the range) names the damage.
        for at in [FRAME_BYTES - 8, HEADER_BYTES + 8, 8 + 8] {
            let mut damaged = bytes.clone();
            damaged[at] ^= 1;
            let err = Partial::from_bytes(&damaged, 7).unwrap_err();
            assert!(err.to_string().contains("checksum"), "{at}: {err}");
        }
    }

    #[test]
    fn unit_words_need_an_ordered_tiling() {
        let a = Partial {
            range: 0..2,
            ..partial()
        };
        let b = partial();
        assert_eq!(
            unit_words(&[a.clone(), b.clone()], 7, 4, 2).unwrap().len(),
            4
        );
        assert!(unit_words(&[b.clone(), a.clone()], 7, 4, 2).is_err());
        assert!(unit_words(std::slice::from_ref(&a), 7, 4, 2).is_err());
        assert!(unit_words(&[a.clone(), b.clone()], 7, 4, 1).is_err());
        assert!(unit_words(&[a, b], 9, 4, 2).is_err());
        assert!(check_range(&(3..3), 4).is_err() && check_range(&(3..5), 4).is_err());
    }
}
