//! Each hot path of v2ref against its floor: the minimal code doing the
//! same unavoidable work on the same data, timed in the same run,
//! interleaved (floor, v2ref, floor, v2ref, …), best of `--repeats`, and
//! printed as a ratio. docs/performance.md says what each floor holds and
//! why it is the floor.
//!
//! ```sh
//! cargo bench --bench floors                       # every path, 1 and 2 threads
//! cargo bench --bench floors -- estimate simulate  # some paths
//! cargo bench --bench floors -- estimate --threads 1 --repeats 9
//! # one side alone, once, for an instruction count:
//! valgrind --tool=callgrind target/release/deps/floors-* estimate --threads 1 --only floor --repeats 1
//! ```
//!
//! Paths: `estimate` (library, 200 000 rows of N = 64), `simulate` (noise
//! Monte Carlo, 2^17 trials of N = 128, Poisson and Gaussian), `synth`
//! (the rows of a set), `piston` (one piston sequence and its scans).

#[path = "floors/estimate_floor.rs"]
mod estimate_floor;
#[path = "floors/paths.rs"]
mod paths;

use std::time::Instant;

/// What one path times: `floor()` and `v2ref()` on `threads` threads,
/// each returning a checksum (kept, so that nothing is optimized away).
pub struct Case {
    /// The path and its size, as printed.
    pub name: String,
    /// The floor.
    pub floor: Box<dyn Fn(usize) -> f64>,
    /// v2ref's code for the same work.
    pub v2ref: Box<dyn Fn(usize) -> f64>,
}

struct Options {
    paths: Vec<String>,
    threads: Vec<usize>,
    repeats: usize,
    only: Option<String>,
}

fn options() -> Result<Options, String> {
    let mut o = Options {
        paths: Vec::new(),
        threads: vec![1, 2],
        repeats: 5,
        only: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |flag: &str| args.next().ok_or(format!("{flag} needs a value"));
        match a.as_str() {
            "--threads" => {
                let v = value("--threads")?;
                o.threads = v
                    .split(',')
                    .map(|t| t.parse().map_err(|_| format!("--threads: {t}")))
                    .collect::<Result<_, _>>()?;
            }
            "--repeats" => {
                let v = value("--repeats")?;
                o.repeats = v.parse().map_err(|_| format!("--repeats: {v}"))?;
            }
            "--only" => o.only = Some(value("--only")?),
            "--list" => {
                println!("{}", paths::NAMES.join(" "));
                std::process::exit(0);
            }
            "--bench" => {} // what `cargo bench` passes
            p if !p.starts_with('-') => o.paths.push(p.to_owned()),
            other => return Err(format!("unknown option {other}")),
        }
    }
    if o.paths.is_empty() {
        o.paths = paths::NAMES.iter().map(|s| s.to_string()).collect();
    }
    Ok(o)
}

/// Wall time of one call of `f(threads)`, seconds, and its checksum (not
/// inlined: `valgrind --tool=callgrind --toggle-collect=*floors::time*`
/// counts the timed work alone).
#[inline(never)]
fn time(f: &dyn Fn(usize) -> f64, threads: usize) -> (f64, f64) {
    let t = Instant::now();
    let sum = f(threads);
    (t.elapsed().as_secs_f64(), sum)
}

fn main() {
    let o = match options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("floors: {e}");
            std::process::exit(2);
        }
    };
    println!(
        "{:<44} {:>3} {:>10} {:>10} {:>6}",
        "path", "thr", "floor ms", "v2ref ms", "ratio"
    );
    for name in &o.paths {
        let Some(case) = paths::case(name) else {
            eprintln!(
                "floors: unknown path {name} (known: {})",
                paths::NAMES.join(", ")
            );
            std::process::exit(2);
        };
        for &threads in &o.threads {
            let (mut floor, mut ours) = (f64::INFINITY, f64::INFINITY);
            let (mut fsum, mut osum) = (0.0, 0.0);
            for _ in 0..o.repeats {
                if o.only.as_deref() != Some("v2ref") {
                    let (t, s) = time(&case.floor, threads);
                    (floor, fsum) = (floor.min(t), s);
                }
                if o.only.as_deref() != Some("floor") {
                    let (t, s) = time(&case.v2ref, threads);
                    (ours, osum) = (ours.min(t), s);
                }
            }
            println!(
                "{:<44} {threads:>3} {:>10.2} {:>10.2} {:>6.2}   (checksums {fsum:.6e} {osum:.6e})",
                case.name,
                floor * 1e3,
                ours * 1e3,
                ours / floor
            );
        }
    }
}
