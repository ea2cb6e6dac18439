//! Grids of values given on the command line: `--fringe-hz` takes a value,
//! or a range `A:B:N` (N values from A to B inclusive, linearly spaced) or
//! `A:B:N:log` (log-spaced), and may be repeated; [`parse_fringe_hz`] is
//! the one parser every `--fringe-hz` flag uses.

/// Most values one range may give.
pub const MAX_RANGE_VALUES: usize = 10_000;

/// The accepted forms, for error messages.
pub const GRID_FORMS: &str =
    "expected a frequency in Hz, A:B:N (N values from A to B inclusive) or A:B:N:log (N log-spaced values, A and B > 0)";

/// The values of one `--fringe-hz` occurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid(pub Vec<f64>);

/// Every value of `grids`, in the order given.
pub fn flatten(grids: &[Grid]) -> Vec<f64> {
    grids.iter().flat_map(|g| g.0.iter().copied()).collect()
}

/// Parses one `--fringe-hz` value: a finite number, `A:B:N` or
/// `A:B:N:log` (2 ≤ N ≤ [`MAX_RANGE_VALUES`]; the ends are exact).
pub fn parse_fringe_hz(s: &str) -> Result<Grid, String> {
    let parts: Vec<&str> = s.trim().split(':').collect();
    let number = |p: &str| match p.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{p}' is not a finite number: {GRID_FORMS}")),
    };
    let (a, b, count, log) = match parts.as_slice() {
        [v] => return Ok(Grid(vec![number(v)?])),
        [a, b, n] => (number(a)?, number(b)?, *n, false),
        [a, b, n, "log"] => (number(a)?, number(b)?, *n, true),
        _ => return Err(GRID_FORMS.into()),
    };
    let n = match count.trim().parse::<usize>() {
        Ok(n) if (2..=MAX_RANGE_VALUES).contains(&n) => n,
        _ => {
            return Err(format!(
                "N = '{count}' is not a count from 2 to {MAX_RANGE_VALUES}: {GRID_FORMS}"
            ))
        }
    };
    if log && (a <= 0.0 || b <= 0.0) {
        return Err(format!("a log-spaced range needs A, B > 0: {GRID_FORMS}"));
    }
    Ok(Grid(spaced(a, b, n, log)))
}

/// `n` ≥ 2 values from `a` to `b`, linearly or log-spaced, ends exact.
fn spaced(a: f64, b: f64, n: usize, log: bool) -> Vec<f64> {
    let last = (n - 1) as f64;
    (0..n)
        .map(|i| {
            let t = i as f64 / last;
            match (i, log) {
                (0, _) => a,
                (i, _) if i == n - 1 => b,
                (_, false) => a + (b - a) * t,
                (_, true) => (a.ln() + (b.ln() - a.ln()) * t).exp(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_and_ranges() {
        assert_eq!(parse_fringe_hz("300").unwrap().0, vec![300.0]);
        assert_eq!(
            parse_fringe_hz("100:400:4").unwrap().0,
            vec![100.0, 200.0, 300.0, 400.0]
        );
        let log = parse_fringe_hz("10:1000:3:log").unwrap().0;
        assert_eq!((log[0], log[2]), (10.0, 1000.0));
        assert!((log[1] - 100.0).abs() < 1e-12);
    }

    #[test]
    fn malformed_ranges_name_the_forms() {
        for bad in [
            "",
            "a",
            "1:2",
            "1:2:1",
            "1:2:x",
            "1:2:3:lin",
            "0:10:3:log",
            "1:inf:3",
        ] {
            let e = parse_fringe_hz(bad).unwrap_err();
            assert!(e.contains("A:B:N"), "{bad}: {e}");
        }
    }
}
