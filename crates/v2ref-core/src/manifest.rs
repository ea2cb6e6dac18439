//! The member list of a set of output files: each file by name, size and
//! checksum, written last (in the sidecar) so that a reader can tell a set
//! whose files were all placed from one a stopped run left half placed.
//! Here, at the oracle's foundation, because both the writer (`atomic`, the
//! crate `v2ref-files`) and the sidecar (`conformance`) name it.

use serde::{Deserialize, Serialize};

/// One file of a set as its sidecar lists it: the file's name (in the
/// sidecar's folder, lossy when it is not UTF-8), its size and its
/// checksum (FNV-1a, 64 bits, of its bytes: it tells a file from another
/// file, it does not authenticate one).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Member {
    /// The file name, without a folder.
    pub name: String,
    /// Its size, bytes.
    pub bytes: u64,
    /// FNV-1a (64 bits) of its bytes, 16 hexadecimal digits.
    pub fnv1a64: String,
}

impl Member {
    /// The member `name` of `bytes` bytes whose FNV-1a 64 is `fnv1a64`.
    pub fn new(name: String, bytes: u64, fnv1a64: u64) -> Member {
        Member {
            name,
            bytes,
            fnv1a64: format!("{fnv1a64:016x}"),
        }
    }
}
