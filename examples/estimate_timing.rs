//! The floor of `estimate` and v2ref's library call, timed on the same
//! rows, for `benches/python_estimate.py` (which times the Python binding
//! and the CLI against them).
//!
//! ```sh
//! # rows in memory, read from raw float64 (what NumPy's `x.tofile` writes):
//! cargo run --release --example estimate_timing -- memory ROWS.f64 64 [threads] [repeats]
//! # the floor of the CLI: a .npy read, estimated and written as a .npy
//! cargo run --release --example estimate_timing -- file ROWS.npy OUT.npy [threads]
//! ```
//!
//! `memory` prints `rows samples floor_seconds v2ref_seconds checksum`
//! (best of `repeats`, floor and v2ref interleaved); `file` prints the
//! seconds from the read to the written file.

#[path = "../benches/floors/estimate_floor.rs"]
mod estimate_floor;

use estimate_floor::estimate_floor;
use std::time::Instant;
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::in_pool_capped as in_pool;
use v2ref_core::simulator::{Inputs, Model};

type Failure = Box<dyn std::error::Error>;

fn arg<T: std::str::FromStr>(args: &[String], i: usize, default: T) -> Result<T, Failure> {
    match args.get(i) {
        None => Ok(default),
        Some(s) => s.parse().map_err(|_| format!("argument {i}: {s}").into()),
    }
}

fn main() -> Result<(), Failure> {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("memory") if args.len() >= 4 => memory(&args),
        Some("file") if args.len() >= 4 => file(&args),
        _ => Err("usage: estimate_timing memory ROWS.f64 SAMPLES [threads] [repeats] | file ROWS.npy OUT.npy [threads]".into()),
    }
}

fn memory(args: &[String]) -> Result<(), Failure> {
    let samples: usize = arg(args, 3, 0)?;
    let threads: usize = arg(args, 4, 0)?;
    let repeats: usize = arg(args, 5, 3)?;
    let data: Vec<f64> = std::fs::read(&args[2])?
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    let model = Model::new(&Inputs {
        samples,
        ..Inputs::default()
    })?;
    let (mut floor, mut ours, mut checksum) = (f64::INFINITY, f64::INFINITY, 0.0);
    for _ in 0..repeats {
        let t = Instant::now();
        let raw = in_pool(threads, || estimate_floor(&data, samples));
        floor = floor.min(t.elapsed().as_secs_f64());
        std::hint::black_box(raw);
        let t = Instant::now();
        let est = RowEstimator::new(&model, BinWindow::Positive, BiasConvention::Model, true)?;
        let rows = est.estimate_rows(&data, threads)?;
        ours = ours.min(t.elapsed().as_secs_f64());
        checksum = rows.iter().map(|r| r.v1_sq + r.v2_sq).sum::<f64>();
    }
    println!(
        "{} {samples} {floor:.6} {ours:.6} {checksum:.17e}",
        data.len() / samples
    );
    Ok(())
}

/// The CLI's unavoidable work: the file read, the rows estimated (the
/// floor), six values per row written as a .npy.
fn file(args: &[String]) -> Result<(), Failure> {
    let threads: usize = arg(args, 4, 0)?;
    let t = Instant::now();
    let bytes = std::fs::read(&args[2])?;
    // A version 1 header: magic (6), version (2), header length (2, LE).
    let header = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let text = String::from_utf8_lossy(&bytes[10..header]);
    let shape = text
        .split("'shape': (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .ok_or("no shape in the .npy header")?;
    let dims: Vec<usize> = shape
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let (rows, n) = (dims[0], dims[1]);
    let data: Vec<f64> = bytes[header..]
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    let raw = in_pool(threads, || estimate_floor(&data, n));
    let mut out = Vec::with_capacity(128 + rows * 48);
    let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, 6), }}");
    let pad = 64 - (10 + dict.len() + 1) % 64;
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&((dict.len() + pad + 1) as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.extend(std::iter::repeat_n(b' ', pad));
    out.push(b'\n');
    for (v1, v2) in raw {
        for v in [v1, v2, 0.0, 0.0, v1, v2] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    std::fs::write(&args[3], out)?;
    println!("{:.6}", t.elapsed().as_secs_f64());
    Ok(())
}
