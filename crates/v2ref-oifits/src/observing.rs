//! Where and when an OIFITS file says the observation was made: the
//! target's name and coordinates, the date, the array's site. A
//! configuration models interferograms, not a night, so each is the user's
//! to give (CLI flags `--target-name`, `--ra-deg`, `--dec-deg`, `--date`,
//! `--site` and `--site-lon-deg`/`--site-lat-deg`/`--site-height-m`; the
//! Python keywords of the same names). Left out, a file says what it said
//! before they existed: target `V2REF_MODEL` at RA = Dec = 0, 2000-01-01,
//! IOTA.

use crate::error::in_range;
use crate::{Error, Result};

/// `TARGET` when no name is given.
pub const DEFAULT_TARGET: &str = "V2REF_MODEL";
/// `DATE-OBS` when no date is given: 2000-01-01T00:00 UTC (MJD 51544), a
/// fixed, recognisable epoch.
pub const DEFAULT_DATE: &str = "2000-01-01";
/// Longest target or site name: `TARGET` is a 16-character column.
pub const MAX_NAME_CHARS: usize = 16;
/// Accepted site heights above the ellipsoid, m: from the shore of the
/// Dead Sea to above any observatory.
pub const SITE_HEIGHT_RANGE_M: (f64, f64) = (-500.0, 6_000.0);
/// The earliest date accepted: MJD 0 (an earlier one has a negative MJD).
pub const EARLIEST_DATE: &str = "1858-11-17";

/// The named arrays `--site` knows (lower case), each a [`Site`].
pub const KNOWN_SITES: [&str; 3] = ["iota", "vlti", "chara"];

/// A known array by name (any case), or None.
pub fn known_site(name: &str) -> Option<Site> {
    let site = |name: &str, lon_deg, lat_deg, height_m| Site {
        name: name.into(),
        lon_deg,
        lat_deg,
        height_m,
    };
    match name.to_ascii_lowercase().as_str() {
        "iota" => Some(iota()),
        // Cerro Paranal: the position VLTI's raw data headers give.
        "vlti" => Some(site("VLTI", -70.404_986_88, -24.627_439_41, 2669.0)),
        // Mount Wilson: the position the CHARA Array publishes.
        "chara" => Some(site("CHARA", -118.061_684, 34.222_579_81, 1742.0)),
        _ => None,
    }
}

/// What the user said of the observation; None keeps the default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObservingSpec {
    /// `TARGET` and `OBJECT`.
    pub target_name: Option<String>,
    /// Right ascension (J2000), degrees; with `dec_deg`.
    pub ra_deg: Option<f64>,
    /// Declination (J2000), degrees; with `ra_deg`.
    pub dec_deg: Option<f64>,
    /// `DATE-OBS`: `YYYY-MM-DD` or `YYYY-MM-DDThh:mm:ss[.s]` (UTC), when
    /// the first row starts.
    pub date: Option<String>,
    /// A known array (`KNOWN_SITES`), or the name of the site whose
    /// coordinates follow.
    pub site: Option<String>,
    /// The site's east longitude, degrees (with `site_lat_deg`,
    /// `site_height_m` and `site`).
    pub site_lon_deg: Option<f64>,
    /// The site's geodetic latitude, degrees.
    pub site_lat_deg: Option<f64>,
    /// The site's height above the WGS84 ellipsoid, m.
    pub site_height_m: Option<f64>,
}

impl ObservingSpec {
    /// The parameter of the first value given, in declaration order.
    pub fn first_given(&self) -> Option<&'static str> {
        let given = [
            ("target_name", self.target_name.is_some()),
            ("ra_deg", self.ra_deg.is_some()),
            ("dec_deg", self.dec_deg.is_some()),
            ("date", self.date.is_some()),
            ("site", self.site.is_some()),
            ("site_lon_deg", self.site_lon_deg.is_some()),
            ("site_lat_deg", self.site_lat_deg.is_some()),
            ("site_height_m", self.site_height_m.is_some()),
        ];
        given.iter().find(|(_, g)| *g).map(|(p, _)| *p)
    }

    /// [`ObservingSpec::resolve`] for a command that writes an OIFITS
    /// file only when `writes`: without one, any value given is refused
    /// (`what_writes` says what would write one).
    pub fn resolve_for(&self, writes: bool, what_writes: &str) -> Result<ObservingContext> {
        match self.first_given() {
            Some(param) if !writes => Err(Error::Invalid {
                param,
                reason: format!("applies when an OIFITS file is written ({what_writes})"),
            }),
            _ => self.resolve(),
        }
    }

    /// The observation these values describe, each checked; an error
    /// names the parameter and what it accepts.
    pub fn resolve(&self) -> Result<ObservingContext> {
        let target_name = match &self.target_name {
            Some(n) => check_name("target_name", n)?,
            None => DEFAULT_TARGET.to_owned(),
        };
        let radec_deg = match (self.ra_deg, self.dec_deg) {
            (None, None) => (0.0, 0.0),
            (Some(ra), Some(dec)) => (check_ra(ra)?, in_range("dec_deg", dec, -90.0, 90.0)?),
            (Some(_), None) => return Err(together("dec_deg", "ra_deg")),
            (None, Some(_)) => return Err(together("ra_deg", "dec_deg")),
        };
        let date = match &self.date {
            Some(d) => check_date(d)?,
            None => DEFAULT_DATE.to_owned(),
        };
        Ok(ObservingContext {
            target_name,
            radec_deg,
            date,
            site: self.site()?,
        })
    }

    fn site(&self) -> Result<Site> {
        let coords = [
            ("site_lon_deg", self.site_lon_deg),
            ("site_lat_deg", self.site_lat_deg),
            ("site_height_m", self.site_height_m),
        ];
        let given = coords.iter().filter(|(_, v)| v.is_some()).count();
        let Some(name) = &self.site else {
            if let Some((p, _)) = coords.iter().find(|(_, v)| v.is_some()) {
                return Err(Error::Invalid {
                    param: p,
                    reason: "a site's coordinates need its name (site) too".into(),
                });
            }
            return Ok(iota());
        };
        if given == 0 {
            return known_site(name).ok_or_else(|| Error::Invalid {
                param: "site",
                reason: format!(
                    "'{name}' is not a known array ({}); or give the site's longitude, latitude and height too",
                    KNOWN_SITES.join(", ")
                ),
            });
        }
        if let Some((p, _)) = coords.iter().find(|(_, v)| v.is_none()) {
            return Err(Error::Invalid {
                param: p,
                reason:
                    "a site's coordinates are three: site-lon-deg, site-lat-deg and site-height-m"
                        .into(),
            });
        }
        let [lon, lat, h] = coords.map(|(_, v)| v.unwrap_or(0.0));
        let (h_lo, h_hi) = SITE_HEIGHT_RANGE_M;
        Ok(Site {
            name: check_name("site", name)?,
            lon_deg: in_range("site_lon_deg", lon, -180.0, 180.0)?,
            lat_deg: in_range("site_lat_deg", lat, -90.0, 90.0)?,
            height_m: in_range("site_height_m", h, h_lo, h_hi)?,
        })
    }
}

/// Where and when, checked: what an OIFITS file says of the observation.
#[derive(Debug, Clone, PartialEq)]
pub struct ObservingContext {
    /// `TARGET` and `OBJECT`.
    pub target_name: String,
    /// Right ascension and declination (J2000), degrees.
    pub radec_deg: (f64, f64),
    /// `DATE-OBS` (see [`ObservingSpec::date`]).
    pub date: String,
    /// The array's site.
    pub site: Site,
}

impl Default for ObservingContext {
    /// The file's defaults: `DEFAULT_TARGET` at RA = Dec = 0,
    /// `DEFAULT_DATE`, IOTA.
    fn default() -> Self {
        ObservingContext {
            target_name: DEFAULT_TARGET.into(),
            radec_deg: (0.0, 0.0),
            date: DEFAULT_DATE.into(),
            site: iota(),
        }
    }
}

/// Right ascension or declination given alone.
fn together(missing: &'static str, given: &str) -> Error {
    let name = |p: &str| {
        if p == "ra_deg" {
            "right ascension"
        } else {
            "declination"
        }
    };
    Error::Invalid {
        param: missing,
        reason: format!(
            "the {} is needed with the {} (the target's J2000 position)",
            name(missing),
            name(given)
        ),
    }
}

/// A name of 1 to [`MAX_NAME_CHARS`] printable ASCII characters, without
/// leading or trailing spaces (FITS strings are ASCII; `TARGET` is 16 wide).
fn check_name(param: &'static str, name: &str) -> Result<String> {
    let printable = name.chars().all(|c| (' '..='~').contains(&c));
    if printable && !name.is_empty() && name.len() <= MAX_NAME_CHARS && name.trim() == name {
        return Ok(name.to_owned());
    }
    Err(Error::Invalid {
        param,
        reason: format!(
            "{name:?}: 1 to {MAX_NAME_CHARS} printable ASCII characters, no leading or trailing space"
        ),
    })
}

fn check_ra(ra_deg: f64) -> Result<f64> {
    crate::error::finite("ra_deg", ra_deg)?;
    if (0.0..360.0).contains(&ra_deg) {
        return Ok(ra_deg);
    }
    Err(Error::OutOfRange {
        param: "ra_deg",
        value: ra_deg,
        accepted: "0 to 360 (360 excluded)".into(),
    })
}

/// A `DATE-OBS` value, checked: a real calendar date from
/// [`EARLIEST_DATE`], with a time of day or not.
fn check_date(date: &str) -> Result<String> {
    if mjd_of_date(date).is_some() {
        return Ok(date.to_owned());
    }
    Err(Error::Invalid {
        param: "date",
        reason: format!(
            "{date:?}: a UTC date YYYY-MM-DD or date and time YYYY-MM-DDThh:mm:ss[.s] \
             (at most {MAX_FRACTION_DIGITS} digits after the point; 23:59:60 on June 30 or December 31, \
             a leap second), from {EARLIEST_DATE} (MJD 0) to 9999-12-31"
        ),
    })
}

/// Most digits of a second's fraction (a nanosecond): a longer date would
/// be cut where its FITS card ends, not written as given.
const MAX_FRACTION_DIGITS: usize = 9;

/// The MJD of a `DATE-OBS` value: `YYYY-MM-DD` (its 00:00 UTC) or
/// `YYYY-MM-DDThh:mm:ss[.s]`. None unless it is a real calendar date and
/// time from [`EARLIEST_DATE`] on.
///
/// A leap second, `23:59:60[.s]`, is a UTC time on the days UTC inserts
/// them (June 30 and December 31; which years did is not checked: it is
/// announced months ahead). MJD counts 86 400 s a day (FITS 4.0 §9.2.2
/// leaves the MJD of a leap second to the writer), so every instant of
/// the leap second has the MJD of the next day's 00:00 UTC.
pub fn mjd_of_date(date: &str) -> Option<f64> {
    let (day, time) = match date.split_once('T') {
        Some((d, t)) => (d, Some(t)),
        None => (date, None),
    };
    let mjd = mjd_of_day(day)?;
    let day_fraction = match time {
        None => 0.0,
        Some(t) => {
            let leap_day = day.ends_with("-06-30") || day.ends_with("-12-31");
            (seconds_of_day(t, leap_day)? / 86_400.0).min(1.0)
        }
    };
    (mjd >= 0.0).then_some(mjd + day_fraction)
}

/// The MJD of 00:00 UTC of `YYYY-MM-DD`.
fn mjd_of_day(day: &str) -> Option<f64> {
    let b = day.as_bytes();
    if b.len() != 10 || b[4] != b'-' || b[7] != b'-' {
        return None;
    }
    let (y, m, d) = (digits(&day[..4])?, digits(&day[5..7])?, digits(&day[8..])?);
    let month = time::Month::try_from(u8::try_from(m).ok()?).ok()?;
    let date = time::Date::from_calendar_date(i32::try_from(y).ok()?, month, u8::try_from(d).ok()?)
        .ok()?;
    // The Julian day number counts from noon: MJD 0 is JDN 2 400 001.
    Some(f64::from(date.to_julian_day() - 2_400_001))
}

/// Seconds since 00:00 of `hh:mm:ss[.s]` (FITS's time of day); second
/// 60 of 23:59 only on a day that may end with a leap second.
fn seconds_of_day(time: &str, leap_day: bool) -> Option<f64> {
    let b = time.as_bytes();
    if b.len() < 8 || b[2] != b':' || b[5] != b':' {
        return None;
    }
    let (h, m) = (digits(&time[..2])?, digits(&time[3..5])?);
    let whole_s = digits(&time[6..8])?;
    let fraction = &time[8..];
    let fraction_s = match fraction.strip_prefix('.') {
        None if fraction.is_empty() => 0.0,
        Some(f)
            if (1..=MAX_FRACTION_DIGITS).contains(&f.len())
                && f.bytes().all(|c| c.is_ascii_digit()) =>
        {
            format!("0.{f}").parse::<f64>().ok()?
        }
        _ => return None,
    };
    let leap_second = leap_day && h == 23 && m == 59 && whole_s == 60;
    (h < 24 && m < 60 && (whole_s < 60 || leap_second))
        .then(|| (h * 3600 + m * 60 + whole_s) as f64 + fraction_s)
}

/// A field of ASCII digits only (no sign, no space).
fn digits(s: &str) -> Option<i64> {
    if s.is_empty() || !s.bytes().all(|c| c.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

/// Where the array stands: a named site, geodetic (WGS84).
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    /// `ARRNAME` and `TELESCOP`.
    pub name: String,
    /// East longitude, degrees.
    pub lon_deg: f64,
    /// Geodetic latitude, degrees.
    pub lat_deg: f64,
    /// Height above the ellipsoid, m.
    pub height_m: f64,
}

/// The site of the paper's instrument: IOTA (FLUOR's 0.45 m siderostats)
/// on Mount Hopkins, Arizona (Traub et al. 2003, SPIE 4838, 45).
pub fn iota() -> Site {
    Site {
        name: "IOTA".into(),
        lon_deg: -110.885,
        lat_deg: 31.6916,
        height_m: 2564.0,
    }
}

impl Site {
    /// The site's geocentric position (ITRS), m: WGS84 ellipsoid.
    pub fn geocentric_m(&self) -> [f64; 3] {
        const A: f64 = 6_378_137.0;
        const F: f64 = 1.0 / 298.257_223_563;
        let e2 = F * (2.0 - F);
        let (lat, lon) = (self.lat_deg.to_radians(), self.lon_deg.to_radians());
        let n = A / (1.0 - e2 * lat.sin().powi(2)).sqrt();
        let r = (n + self.height_m) * lat.cos();
        [
            r * lon.cos(),
            r * lon.sin(),
            (n * (1.0 - e2) + self.height_m) * lat.sin(),
        ]
    }

    /// The local east unit vector in the geocentric frame.
    pub fn east(&self) -> [f64; 3] {
        let lon = self.lon_deg.to_radians();
        [-lon.sin(), lon.cos(), 0.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_calendar_dates() {
        assert_eq!(mjd_of_date("2000-01-01"), Some(51_544.0));
        assert_eq!(mjd_of_date("1858-11-17"), Some(0.0));
        assert_eq!(mjd_of_date("2024-02-29"), Some(60_369.0));
        assert_eq!(mjd_of_date("2026-11-26T06:00:00"), Some(61_370.25));
        assert_eq!(
            mjd_of_date("2026-11-26T00:00:01.5"),
            Some(61_370.0 + 1.5 / 86_400.0)
        );
        // A leap second: the MJD of the next day's start.
        assert_eq!(mjd_of_date("2016-12-31T23:59:60.5"), Some(57_754.0));
        assert_eq!(
            mjd_of_date("2015-06-30T23:59:60"),
            mjd_of_date("2015-07-01")
        );
        assert!(mjd_of_date("2026-11-26T00:00:01.123456789").is_some());
        for bad in [
            "2023-02-29",
            "2026-04-31",
            "2026-13-01",
            "2026-00-10",
            "1858-11-16",
            "26-11-26",
            "2026-1-26",
            "2026-11-26T24:00:00",
            "2026-11-26T12:60:00",
            "2026-11-26T12:00",
            "2026-11-26T12:00:00Z",
            "2026-11-26T12:00:00.",
            "2026-11-26T23:59:60",
            "2016-12-31T23:58:60",
            "2026-11-26T12:00:00.1234567891",
            "+026-11-26",
            "2026-11-26 ",
            "",
        ] {
            assert_eq!(mjd_of_date(bad), None, "{bad}");
        }
    }

    /// Every day from MJD 0 to 9999-12-31 has the MJD one counts to it,
    /// day after day (the `time` crate's calendar against a count), and
    /// the day after each month's last is refused.
    #[test]
    #[cfg_attr(miri, ignore = "3 million days: too long for the interpreter")]
    fn every_day_counts_from_mjd_zero() {
        let (mut y, mut m, mut d, mut mjd) = (1858, 11, 17, 0.0);
        while y <= 9999 {
            assert_eq!(mjd_of_date(&format!("{y:04}-{m:02}-{d:02}")), Some(mjd));
            let leap = y % 4 == 0 && (y % 100 != 0 || y % 400 == 0);
            let last = match m {
                2 if leap => 29,
                2 => 28,
                4 | 6 | 9 | 11 => 30,
                _ => 31,
            };
            if d == last {
                assert_eq!(mjd_of_date(&format!("{y:04}-{m:02}-{:02}", d + 1)), None);
                (d, m) = (1, m % 12 + 1);
                y += i32::from(m == 1);
            } else {
                d += 1;
            }
            mjd += 1.0;
        }
    }
}
