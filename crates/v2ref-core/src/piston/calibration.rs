//! §6: what every scan of the piston Monte Carlo shares — the tabulated
//! fringes of the source and of its unresolved calibrator, the bins of each
//! window, the FFT — and the piston-free calibration of each detector: V1
//! and V2 of the source without piston (the reference of the bias) and the
//! calibrator's raw estimates that normalize them.

use crate::error::Result;
use crate::formalism::estimator::{raw_sums, Pair, BIN_WINDOWS};
use crate::formalism::observation::Observation;
use crate::formalism::source::Source;
use crate::piston::fringe_table::FringeTable;
use crate::piston::scan::{fill_scan, Detector, ScanSetup};
use num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// What every scan needs: the fringe tables of the source and of the
/// unresolved calibrator, the bins of each window and the FFT plan.
pub(crate) struct ScanContext<'a> {
    pub(crate) setup: &'a ScanSetup,
    pub(crate) table: FringeTable,
    /// `None` when the source is its own calibrator.
    cal_table: Option<FringeTable>,
    bins: Vec<Vec<usize>>,
    fft: Arc<dyn Fft<f64>>,
}

impl<'a> ScanContext<'a> {
    pub(crate) fn new(obs: &Observation, setup: &'a ScanSetup, max_opd_um: f64) -> Result<Self> {
        let cal_table = if obs.source == Source::Point && obs.phase.is_zero() {
            None
        } else {
            Some(FringeTable::new(&obs.calibrator(), max_opd_um)?)
        };
        Ok(ScanContext {
            setup,
            table: FringeTable::new(obs, max_opd_um)?,
            cal_table,
            bins: BIN_WINDOWS
                .iter()
                .map(|w| w.bins(setup.samples, setup.dx_um, &obs.spectrum))
                .collect::<Result<_>>()?,
            fft: FftPlanner::new().plan_fft_forward(setup.samples),
        })
    }
}

/// Reusable buffers of one thread's scans.
pub(crate) struct Workspace {
    pub(crate) samples: Vec<f64>,
    buf: Vec<Complex64>,
    scratch: Vec<Complex64>,
}

impl Workspace {
    pub(crate) fn new(n: usize) -> Self {
        Workspace {
            samples: vec![0.0; n],
            buf: Vec::with_capacity(n),
            scratch: Vec::new(),
        }
    }

    /// The raw V1², V2² per window ([`BIN_WINDOWS`]) of the samples now in
    /// the workspace.
    pub(crate) fn raw_per_window(&mut self, ctx: &ScanContext) -> [Pair; BIN_WINDOWS.len()] {
        self.buf.clear();
        self.buf
            .extend(self.samples.iter().map(|&m| Complex64::new(m, 0.0)));
        let zero = Complex64::new(0.0, 0.0);
        self.scratch.resize(ctx.fft.get_inplace_scratch_len(), zero);
        ctx.fft
            .process_with_scratch(&mut self.buf, &mut self.scratch);
        std::array::from_fn(|w| raw_sums(&self.buf, &ctx.bins[w]))
    }
}

/// One detector's piston-free calibration: per window, the raw estimates of
/// the calibrator (the normalization) and V1, V2 of the source without
/// piston (what the piston's effect is measured from).
#[derive(Debug, Clone)]
pub struct Calibration {
    /// The detector.
    pub detector: Detector,
    /// Sub-sample offsets and weights of the detector.
    pub(crate) sub: (Vec<f64>, Vec<f64>),
    /// Raw V1², V2² of the calibrator, per window.
    calibrator: Vec<Pair>,
    /// V1, V2 (not squared) of the source without piston, per window.
    pub(crate) no_piston: Vec<Pair>,
}

impl Calibration {
    pub(crate) fn new(ctx: &ScanContext, detector: Detector, ws: &mut Workspace) -> Result<Self> {
        let sub = detector.sub_samples()?;
        let (u, w) = (&sub.0, &sub.1);
        fill_scan(&ctx.table, ctx.setup, u, w, &|_| 0.0, 0.0, &mut ws.samples);
        let source = ws.raw_per_window(ctx);
        let calibrator = match &ctx.cal_table {
            None => source.to_vec(),
            Some(t) => {
                fill_scan(t, ctx.setup, u, w, &|_| 0.0, 0.0, &mut ws.samples);
                ws.raw_per_window(ctx).to_vec()
            }
        };
        let no_piston = source
            .iter()
            .zip(&calibrator)
            .map(|(s, c)| Pair {
                v1_sq: (s.v1_sq / c.v1_sq).sqrt(),
                v2_sq: (s.v2_sq / c.v2_sq).sqrt(),
            })
            .collect();
        Ok(Calibration {
            detector,
            sub,
            calibrator,
            no_piston,
        })
    }

    /// V(piston) − V(no piston) of V1 and V2 per window, from the raw
    /// estimates of a scan with piston.
    pub(crate) fn differences(&self, raw: &[Pair; BIN_WINDOWS.len()]) -> [Pair; BIN_WINDOWS.len()] {
        std::array::from_fn(|w| {
            let (r, c, v0) = (raw[w], self.calibrator[w], self.no_piston[w]);
            Pair {
                v1_sq: (r.v1_sq / c.v1_sq).sqrt() - v0.v1_sq,
                v2_sq: (r.v2_sq / c.v2_sq).sqrt() - v0.v2_sq,
            }
        })
    }
}
