//! The help text of each physical input, kept by hand beside the struct
//! [`super::Physical`] (one entry per field, in its order; a test holds the names
//! to the struct's serde fields): unit, accepted range, what it is. The
//! CLI's flags state the same text in their doc comments (a test of the
//! binary holds each to its entry), Python's docstrings are written from it
//! at import, and the tests below hold the accepted ranges to what the
//! library's checks do.

use serde::Serialize;

/// One physical input, declared once. In the texts, `{name}` names another
/// input: each edge writes it its own way (`--name` for the CLI, ``` ``name`` ```
/// for Python).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Parameter {
    /// The field of [`super::Physical`] and the Python keyword argument;
    /// the CLI's flag is `--` and the name with `_` as `-`.
    pub name: &'static str,
    /// Its unit (empty for a count, a flag or a choice).
    pub unit: &'static str,
    /// The values accepted, in words (a flag's: `true or false`).
    pub accepted: &'static str,
    /// What it is: a noun phrase.
    pub what: &'static str,
    /// More on it, in sentences (or empty).
    pub note: &'static str,
    /// What leaving it unset means, for the inputs that may be unset (an
    /// `Option` of [`super::Physical`]); else empty.
    pub unset: &'static str,
    /// Why the accepted range is what it is (the docs' table), or empty.
    pub why: &'static str,
}

impl Parameter {
    /// The help text: `what, unit: accepted. note`, without the accepted
    /// range for a flag (`true or false`), each `{name}` written by `refer`.
    pub fn describe(&self, refer: &dyn Fn(&str) -> String) -> String {
        let mut s = self.what.to_owned();
        if !self.unit.is_empty() {
            s = format!("{s}, {}", self.unit);
        }
        if !self.is_flag() {
            s = format!("{s}: {}", self.accepted);
        }
        s.push('.');
        if !self.note.is_empty() {
            s = format!("{s} {}", self.note);
        }
        refer_to(&s, refer)
    }

    /// What leaving it unset means, each `{name}` written by `refer`.
    pub fn unset(&self, refer: &dyn Fn(&str) -> String) -> String {
        refer_to(self.unset, refer)
    }

    /// A flag: true or false.
    pub fn is_flag(&self) -> bool {
        self.accepted == FLAG
    }

    /// The entry of the field `name`, if it is one.
    pub fn named(name: &str) -> Option<&'static Parameter> {
        PARAMETERS.iter().find(|p| p.name == name)
    }
}

/// The accepted values of a flag.
const FLAG: &str = "true or false";

/// `text` with each `{name}` replaced by `refer(name)`.
pub fn refer_to(text: &str, refer: &dyn Fn(&str) -> String) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        let close = rest[open..].find('}').map_or(rest.len(), |c| open + c);
        out.push_str(&rest[..open]);
        out.push_str(&refer(&rest[open + 1..close]));
        rest = rest.get(close + 1..).unwrap_or("");
    }
    out.push_str(rest);
    out
}

/// Every field of [`super::Physical`], in declaration order, with its help text.
pub const PARAMETERS: [Parameter; 27] = [
    Parameter {
        name: "wavelength_um",
        unit: "µm",
        accepted: "0.001 to 100000",
        what: "Centre wavelength λ0",
        note: "With {spectrum_csv} it still sets λ0 of the fringe frequency f = v/λ0, \
                   of the samples per fringe and of the seeing: give the spectrum's centre.",
        unset: "",
        why: "1 nm (X-rays, no fringe-scanning interferometer) to 10 cm (radio)",
    },
    Parameter {
        name: "bandwidth_nm",
        unit: "nm",
        accepted: "1e-12 λ0 to under 2 λ0",
        what: "Full bandwidth Δλ",
        note: "The band [λ0 − Δλ/2, λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ \
                   (not per unit wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and \
                   1/(λ0 − Δλ/2)).",
        unset: "",
        why: "narrower is lost in the rounding of λ0 (use a line); wider reaches zero wavelength",
    },
    Parameter {
        name: "spectrum_csv",
        unit: "",
        accepted: "a CSV file of at most 100000 rows, 16 MiB",
        what: "A tabulated S(σ)F(σ) instead of the flat band",
        note: "Header `wavelength_um,weight` or `wavenumber_per_um,weight`, the weight \
                   per unit wavenumber (`weight_per_wavenumber` says so explicitly; \
                   `weight_per_um` is per unit wavelength and is converted by λ²); a leading \
                   byte-order mark is fine.",
        unset: "the flat band of {wavelength_um} and {bandwidth_nm}",
        why: "far more than the bias integrals need; a longer file (or `/dev/zero`) is \
                  refused at once",
    },
    Parameter {
        name: "channels",
        unit: "",
        accepted: "1 to 4096",
        what: "Spectral channels C of equal width in wavenumber over the band",
        note: "bias, snr and simulate answer per channel (docs/conventions.md §16); one of \
                   {channels}, {resolution} or {channels_csv}. 1: the wide band's numbers.",
        unset: "the wide band, no channels",
        why: "far more than any spectrograph of the field records; each channel needs a DFT \
                  bin of the scan",
    },
    Parameter {
        name: "resolution",
        unit: "",
        accepted: "> 0 (at most 4096 channels over the band)",
        what: "Channels of spectral resolution R = λ/Δλ across the band",
        note: "Geometric edges, the whole number of channels nearest R; each channel must \
                   hold a DFT bin of the scan.",
        unset: "the wide band, no channels",
        why: "R below the band's own gives the band as one channel",
    },
    Parameter {
        name: "channels_csv",
        unit: "",
        accepted: "a CSV file of at most 4096 rows, 1 MiB",
        what: "Channels' edges and responses from a table",
        note: "Header `wavelength_lo_um,wavelength_hi_um,response` or \
                   `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per channel by \
                   increasing axis value, the channels inside the band, neither overlapping \
                   nor out of order.",
        unset: "the wide band, no channels",
        why: "far more channels than the spectrographs of the field; a longer file is refused \
                  at once",
    },
    Parameter {
        name: "source",
        unit: "",
        accepted: "point or ud",
        what: "Source model",
        note: "ud: a uniform disk of diameter {diameter_mas}; point: unresolved (V = 1).",
        unset: "",
        why: "",
    },
    Parameter {
        name: "diameter_mas",
        unit: "mas",
        accepted: "> 0 to 3.6e6",
        what: "Uniform-disk diameter θ",
        note: "",
        unset: "",
        why: "up to 1°: the visibility is that of a small source",
    },
    Parameter {
        name: "spatial_freq_cpas",
        unit: "cycles/arcsec",
        accepted: "0 to 1e13 (and B = S/σ_eff at most 1e9 m)",
        what: "Spatial frequency S = B σ_eff",
        note: "",
        unset: "40, the paper's 18 m baseline in K (or from {baseline_m})",
        why: "the frequency of a 1e9 m baseline at 1 nm",
    },
    Parameter {
        name: "baseline_m",
        unit: "m",
        accepted: "0 to 1e9",
        what: "Projected baseline B",
        note: "Instead of {spatial_freq_cpas}.",
        unset: "from {spatial_freq_cpas}",
        why: "beyond any interferometer, space included",
    },
    Parameter {
        name: "dispersion_pp_rad",
        unit: "rad",
        accepted: "-1e4 to 1e4",
        what: "Quadratic dispersion phase, peak-to-peak over the band",
        note: "",
        unset: "",
        why: "the V2 quadrature follows the Fresnel 1/√P law up to here (20 % off at 3e4)",
    },
    Parameter {
        name: "stroke_um",
        unit: "µm",
        accepted: "N = Δx/δx, rounded, from 2 to 2^24",
        what: "OPD stroke Δx",
        note: "",
        unset: "{samples} × {dx_um}",
        why: "",
    },
    Parameter {
        name: "dx_um",
        unit: "µm",
        accepted: "> 0",
        what: "Sample spacing δx",
        note: "",
        unset: "",
        why: "",
    },
    Parameter {
        name: "samples",
        unit: "",
        accepted: "2 to 2^24",
        what: "Number of samples N",
        note: "Ignored when {stroke_um} is given. The finite scan costs about N² \
                   (N = 16384: about 10 s on two cores).",
        unset: "",
        why: "",
    },
    Parameter {
        name: "integrating",
        unit: "",
        accepted: FLAG,
        what: "Integrating detector (each sample averages the fringe over δx)",
        note: "",
        unset: "",
        why: "",
    },
    Parameter {
        name: "visibility",
        unit: "",
        accepted: "0 to 1",
        what: "Visibility V scaling the fringe",
        note: "m_0 = n V for a point source (a source of known V: {source} point).",
        unset: "",
        why: "",
    },
    Parameter {
        name: "photons",
        unit: "photons per sample",
        accepted: "> 0 to 1e12",
        what: "Continuum n (c = n)",
        note: "",
        unset: "",
        why: "beyond any full well; keeps the fourth moments of the variances far from overflow",
    },
    Parameter {
        name: "read_noise",
        unit: "photons per sample",
        accepted: "0 to 1e12",
        what: "Detector noise standard deviation σ_det",
        note: "",
        unset: "",
        why: "as the photons",
    },
    Parameter {
        name: "photon_noise",
        unit: "",
        accepted: FLAG,
        what: "Poisson photon noise (when off, detector noise only)",
        note: "",
        unset: "",
        why: "",
    },
    Parameter {
        name: "fringe_hz",
        unit: "Hz",
        accepted: "0.001 to 1e7",
        what: "Fringe frequency f = v/λ0",
        note: "Adds the differential piston of §6 (consecutive scans through one \
                   piston sequence).",
        unset: "no piston",
        why: "",
    },
    Parameter {
        name: "wind_mps",
        unit: "m/s",
        accepted: "0.001 to 343",
        what: "Wind speed",
        note: "Frozen flow along the baseline.",
        unset: "",
        why: "no atmospheric layer moves faster than sound; below a millimetre a second the \
                  piston's time scales leave the range where its spectrum is finite",
    },
    Parameter {
        name: "seeing_arcsec",
        unit: "arcsec",
        accepted: "0 to 100",
        what: "Seeing λ/r0",
        note: "Quoted at {seeing_wavelength_um}; 0: no turbulence.",
        unset: "",
        why: "r0 of 4.5 mm in K: no fringe can be tracked beyond",
    },
    Parameter {
        name: "seeing_wavelength_um",
        unit: "µm",
        accepted: "0.3 to 30",
        what: "Wavelength at which {seeing_arcsec} is quoted",
        note: "Site monitors quote 0.5. Converted to the observing wavelength by \
                   r0 ∝ λ^(6/5).",
        unset: "the observing wavelength {wavelength_um}",
        why: "where seeing is measured, and where the λ^(-1/5) law that converts it holds",
    },
    Parameter {
        name: "aperture_m",
        unit: "m",
        accepted: "0.001 to 1000",
        what: "Telescope aperture diameter",
        note: "",
        unset: "",
        why: "a millimetre to a kilometre; at 1e300 m or 1e-308 m the aperture filter under- \
                  or overflows and every piston statistic was undefined",
    },
    Parameter {
        name: "outer_scale_m",
        unit: "m",
        accepted: "> 0",
        what: "von Kármán outer scale",
        note: "",
        unset: "infinite",
        why: "",
    },
    Parameter {
        name: "sub_samples",
        unit: "",
        accepted: "1 to 64",
        what: "Sub-samples per sample of the integrating detector under piston",
        note: "",
        unset: "",
        why: "",
    },
    Parameter {
        name: "reference",
        unit: "",
        accepted: "centre, mean or absolute",
        what: "Where the fringe packet sits in each scan",
        note: "",
        unset: "",
        why: "",
    },
];

#[cfg(test)]
mod tests {
    use super::{refer_to, Parameter, PARAMETERS};
    use crate::parameters::{Physical, DEFAULT_SPATIAL_FREQ_CPAS};

    /// Every text names other inputs by declared names only, and an input
    /// may be unset exactly where its field is an `Option` (unset by
    /// default), the spatial frequency's default being the library's.
    #[test]
    fn texts_name_declared_inputs_and_unset_means_none() {
        let defaults = serde_json::to_value(Physical::DEFAULT).unwrap();
        let names: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
        let fields: Vec<&String> = defaults.as_object().unwrap().keys().collect();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, fields);
        for p in &PARAMETERS {
            for text in [p.accepted, p.what, p.note, p.unset, p.why] {
                refer_to(text, &|n| {
                    assert!(names.contains(&n), "{}: {{{n}}}", p.name);
                    String::new()
                });
            }
            assert_eq!(
                p.unset.is_empty(),
                !defaults[p.name].is_null(),
                "{}",
                p.name
            );
            assert_eq!(p.is_flag(), defaults[p.name].is_boolean(), "{}", p.name);
        }
        let s = Parameter::named("spatial_freq_cpas").unwrap().unset;
        assert!(
            s.starts_with(&format!("{DEFAULT_SPATIAL_FREQ_CPAS}, ")),
            "{s}"
        );
    }

    /// A choice's accepted values in words are its words
    /// ([`crate::words::Words`]), as the edges accept them.
    #[test]
    fn a_choice_accepts_its_words() {
        use crate::words::Words;
        fn listed<T: Words>() -> String {
            let words: Vec<&str> = T::WORDS.iter().map(|w| w.word).collect();
            let (last, rest) = words.split_last().unwrap();
            format!("{} or {last}", rest.join(", "))
        }
        assert_eq!(
            Parameter::named("source").unwrap().accepted,
            listed::<super::super::SourceKind>()
        );
        let reference = listed::<crate::piston::PistonReference>();
        assert_eq!(Parameter::named("reference").unwrap().accepted, reference);
    }

    /// The bounds of `accepted` in words: (low, low included, high, high
    /// included) for `[> ]A[ λ0] to [under ]B[ λ0][ (…)]`
    /// and `> 0`, with λ0 the default's, in nm (the bandwidth's); None for
    /// words of another form (a choice, a file, a rounded count).
    fn bounds(p: &Parameter) -> Option<(f64, bool, f64, bool)> {
        let d = Physical::DEFAULT;
        // A condition in brackets bounds the high end elsewhere: not tested.
        let (words, cond) = match p.accepted.split_once(" (") {
            Some((w, _)) => (w, true),
            None => (p.accepted, false),
        };
        let number = |w: &str| -> Option<f64> {
            let (w, f) = match w.strip_suffix(" λ0") {
                Some(w) => (w, d.wavelength_um * 1e3),
                None => (w, 1.0),
            };
            let x = match w.split_once('^') {
                Some((b, e)) => b.parse::<f64>().ok()?.powf(e.parse().ok()?),
                None => w.parse().ok()?,
            };
            Some(x * f)
        };
        let (lo, hi) = words.split_once(" to ").unwrap_or((words, "inf"));
        let (lo, lo_in) = lo.strip_prefix("> ").map_or((lo, true), |l| (l, false));
        let (hi, hi_in) = hi.strip_prefix("under ").map_or((hi, true), |h| (h, false));
        let hi = if cond { None } else { number(hi) };
        Some((number(lo)?, lo_in, hi.unwrap_or(f64::INFINITY), hi_in))
    }

    /// `value` of the input `name` is refused by the library and names it
    /// (Err), or accepted (Ok): the default configuration, with the piston
    /// on and an integrating detector so that every input is checked.
    fn probe(name: &str, value: f64) -> Result<(), String> {
        let mut p = Physical {
            fringe_hz: Some(300.0),
            integrating: true,
            ..Physical::DEFAULT
        };
        let given = match is_count(name) {
            true => serde_json::json!(value as usize),
            false => serde_json::json!(value),
        };
        p.overlay(serde_json::json!({ name: given })).unwrap();
        if name == "wavelength_um" {
            // The band follows λ0, as a user's would.
            p.bandwidth_nm = value * 100.0;
        }
        if name.ends_with("wavelength_um") || name == "bandwidth_nm" {
            // Four samples per shortest wavelength of the band.
            p.dx_um = (p.wavelength_um - p.bandwidth_nm / 2e3) / 4.0;
        }
        match p
            .check()
            .and_then(|()| p.inputs())
            .and_then(|_| p.channels())
        {
            Ok(_) => Ok(()),
            Err(e) if e.param().map(crate::parameters::keyword_of).as_deref() == Some(name) => {
                Err(e.to_string())
            }
            Err(e) => panic!("{name} = {value}: refused for another input: {e}"),
        }
    }

    /// A whole count (its edges are ±1, its value an integer).
    fn is_count(name: &str) -> bool {
        name.contains("samples") || name == "channels"
    }

    /// The values at the edges of `p`'s accepted range in words, each
    /// with whether it is accepted: each bound (nudged inward by its
    /// rounding) when included, and just beyond it; None as [`bounds`].
    fn edges(p: &Parameter) -> Option<Vec<(f64, bool)>> {
        let (lo, lo_in, hi, hi_in) = bounds(p)?;
        let count = is_count(p.name);
        let beyond = |x: f64, dir: f64| match count {
            true => x + dir,
            false => x + dir * (x.abs() * 1e-6).max(1e-9),
        };
        let at = |x: f64, inward: f64| x + if count { 0.0 } else { inward * x.abs() * 1e-12 };
        let (ok_lo, bad_lo) = match lo_in {
            true => (at(lo, 1.0), beyond(lo, -1.0)),
            false => (beyond(lo, 1.0), lo),
        };
        let (ok_hi, bad_hi) = match hi_in {
            true => (at(hi, -1.0), beyond(hi, 1.0)),
            false => (beyond(hi, -1.0), hi),
        };
        let all = [
            (ok_lo, true),
            (bad_lo, false),
            (ok_hi, true),
            (bad_hi, false),
        ];
        Some(all.into_iter().filter(|(x, _)| x.is_finite()).collect())
    }

    /// The accepted range in words is the library's: the values at its
    /// edges are accepted or refused naming the input as it says (a range
    /// stated wider or narrower than the checks fails).
    #[test]
    fn accepted_ranges_are_the_library_checks() {
        let mut tested = Vec::new();
        for p in &PARAMETERS {
            let Some(edges) = edges(p) else { continue };
            for (x, ok) in edges {
                let got = probe(p.name, x);
                assert_eq!(got.is_ok(), ok, "{} = {x}: {got:?}", p.name);
            }
            tested.push(p.name);
        }
        let untested: Vec<&str> = PARAMETERS
            .iter()
            .map(|p| p.name)
            .filter(|n| !tested.contains(n))
            .collect();
        let words = [
            "spectrum_csv",
            "channels_csv",
            "source",
            "stroke_um",
            "integrating",
        ];
        assert_eq!(
            untested,
            [&words[..], &["photon_noise", "reference"]].concat()
        );
    }

    /// The input table of `docs/conventions.md` §14, kept by hand, states
    /// each entry: its row starts with the name, what it is and the unit
    /// and ends with the accepted range and why (an entry changed on one
    /// side fails).
    #[test]
    fn the_docs_table_states_each_entry() {
        let docs = include_str!("../../../../docs/conventions.md");
        let code = |n: &str| format!("`{n}`");
        for p in &PARAMETERS {
            let head = format!(
                "| `{}` | {} | {} |",
                p.name,
                refer_to(p.what, &code),
                p.unit
            );
            let tail = format!(
                "| {} | {} |",
                refer_to(p.accepted, &code),
                refer_to(p.why, &code)
            );
            let tail = tail.replace("|  |", "| |").replace(" | |", " |  |");
            let row = docs.lines().find(|l| l.starts_with(&head));
            let row = row.unwrap_or_else(|| panic!("no row {head}"));
            assert!(
                row.ends_with(&tail) || row.ends_with(&tail.replace("|  |", "| |")),
                "{row}\n{tail}"
            );
        }
    }
}
