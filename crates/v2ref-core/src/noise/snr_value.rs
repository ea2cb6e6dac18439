//! How a signal-to-noise ratio is written when it has no finite value.
//!
//! SNR = signal / √var. Without noise (no photon noise and no detector
//! noise) the variance is 0: the SNR of a signal is **infinite**, and that
//! of a zero signal is **undefined** (0/0). JSON has no such numbers (a
//! serializer would write `null`, which also means "absent"), so these are
//! written as the words `"infinite"` and `"undefined"`; a finite SNR is a
//! number as usual.

/// The word for a non-finite SNR: `infinite` (signal without noise) or
/// `undefined` (no signal and no noise); `None` for a finite SNR.
pub fn snr_word(snr: f64) -> Option<&'static str> {
    if snr.is_nan() {
        Some("undefined")
    } else if snr.is_infinite() {
        Some("infinite")
    } else {
        None
    }
}

/// Serde `serialize_with` for an SNR field: a number, or the word of
/// [`snr_word`].
pub fn serialize_snr<S: serde::Serializer>(snr: &f64, s: S) -> Result<S::Ok, S::Error> {
    match snr_word(*snr) {
        Some(word) => s.serialize_str(word),
        None => s.serialize_f64(*snr),
    }
}

/// An SNR for a table: `precision` decimals, or the word of [`snr_word`]
/// with its reason.
pub fn snr_text(snr: f64, precision: usize) -> String {
    match snr_word(snr) {
        Some("infinite") => "infinite (no noise)".to_owned(),
        Some(_) => "undefined (no signal and no noise)".to_owned(),
        None => format!("{snr:.precision$}"),
    }
}
