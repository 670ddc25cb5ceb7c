//! `basr simulate --plants N --spread F --seed S` (SPEC §6): the verdict
//! when the model is wrong. N plants are drawn around the robot description
//! — every uncertain number scaled by 1 + F·u, u uniform in [−1, 1] — and
//! the controller, built for the description, drives each. The draws are a
//! fixed algorithm (xorshift128 seeded from S and the plant's index), so the
//! same call gives the same bytes on every machine; the plants run in
//! parallel (rayon) and are gathered in index order.

use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use serde::Serialize;

use super::{simulate_plant, Options, SimError, SimModel};
use basr_job::Job;

/// The uncertain numbers: name (as in the robot description) and how to
/// scale it in the simulator's model.
type Scale = fn(&mut SimModel, f64);

const UNCERTAIN: [(&str, Scale); 12] = [
    ("end_effector.mass_kg", |m, f| m.arm.ee_mass_kg *= f),
    // the links' masses follow the holding force B (model.rs)
    ("hydraulics.gravity_b_n", |m, f| m.arm.holding_b_n *= f),
    ("dynamics.base_inertia_kgm2", |m, f| {
        m.arm.base_inertia_kgm2 *= f
    }),
    ("dynamics.motor friction", |m, f| {
        m.motor.friction.viscous *= f;
        m.motor.friction.coulomb *= f;
        m.motor.friction.stiction *= f;
    }),
    ("dynamics.cylinder friction", |m, f| {
        m.cylinder.friction.viscous *= f;
        m.cylinder.friction.coulomb *= f;
        m.cylinder.friction.stiction *= f;
    }),
    ("hydraulics.bulk_modulus_pa", |m, f| {
        m.hydraulics.bulk_modulus_pa *= f
    }),
    ("hydraulics.valve_flow_gain", |m, f| m.motor.valve_gain *= f),
    ("dynamics.cylinder_valve_flow_gain", |m, f| {
        m.cylinder.valve_gain *= f
    }),
    ("hydraulics.supply_pa", |m, f| m.hydraulics.supply_pa *= f),
    ("dynamics.valve_time_constant_s", |m, f| {
        m.motor.valve_tau_s *= f;
        m.cylinder.valve_tau_s *= f;
    }),
    ("dynamics.counterbalance_bleed_m3_per_s_pa", |m, f| {
        m.circuit.cb_bleed *= f
    }),
    // the pressure transducers' calibration (sensor error)
    ("dynamics.pressure_pa_per_volt", |m, f| {
        m.sensors.pressure_gain *= f
    }),
];

/// What `--plants` asks.
#[derive(Clone, Copy, Debug)]
pub struct PlantsOptions {
    pub n: u32,
    pub spread: f64,
    pub seed: u64,
}

impl PlantsOptions {
    /// Bounds: 1–10 000 plants, spread 0–0.5 (a plant at −50 % of its mass
    /// or supply is no longer the arm described).
    pub fn check(&self) -> Result<(), SimError> {
        if !(1..=10_000).contains(&self.n) {
            return Err(SimError::Option(format!(
                "--plants {} must be 1–10000",
                self.n
            )));
        }
        if !(self.spread.is_finite() && (0.0..=0.5).contains(&self.spread)) {
            return Err(SimError::Option(format!(
                "--spread {} must be a fraction 0–0.5 (0.1 = ±10 %)",
                self.spread
            )));
        }
        Ok(())
    }
}

/// The `plants` object of the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlantsSummary {
    pub n: u32,
    pub spread: f64,
    pub seed: u64,
    pub p50_max_error_m: f64,
    pub p95_max_error_m: f64,
    pub worst_max_error_m: f64,
    /// Share of the plants that pass (error and limits).
    pub pass_fraction: f64,
    /// The uncertain number drawn furthest from its value in most failing
    /// plants (None when none fails).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deciding_parameter: Option<String>,
}

impl PlantsSummary {
    pub fn human(&self, tolerance_m: f64) -> String {
        let mut s = format!(
            "  the {} plants' max error while painting: p50 {:.3} mm, p95 {:.3} mm, worst {:.3} mm; {:.0} % of the plants within the {:.3} mm tolerance and the limits\n",
            self.n,
            self.p50_max_error_m * 1e3,
            self.p95_max_error_m * 1e3,
            self.worst_max_error_m * 1e3,
            self.pass_fraction * 100.0,
            tolerance_m * 1e3
        );
        if let Some(p) = &self.deciding_parameter {
            s += &format!("  most often deciding a failure: {p}\n");
        }
        s
    }
}

/// The scale factors of plant `i` (one per `UNCERTAIN` entry).
pub fn draw(seed: u64, i: u32, spread: f64) -> Vec<f64> {
    // a distinct stream per plant: splitmix of (seed, i)
    let mut z = seed ^ (u64::from(i).wrapping_add(1)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    let mut rng = rand_xorshift::XorShiftRng::seed_from_u64(z ^ (z >> 31));
    UNCERTAIN
        .iter()
        .map(|_| {
            let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64; // [0, 1)
            1.0 + spread * (2.0 * u - 1.0)
        })
        .collect()
}

/// The uncertain numbers' names, in the order of [`draw`]'s factors.
pub fn names() -> Vec<&'static str> {
    UNCERTAIN.iter().map(|u| u.0).collect()
}

/// `nominal` with each uncertain number scaled by its factor of `f`.
pub fn scaled(nominal: &SimModel, f: &[f64]) -> SimModel {
    let mut m = nominal.clone();
    for ((_, scale), fi) in UNCERTAIN.iter().zip(f) {
        scale(&mut m, *fi);
    }
    m
}

/// The p-quantile (0..1) of sorted `v` (nearest rank).
fn quantile(v: &[f64], p: f64) -> f64 {
    let k = ((p * v.len() as f64).ceil() as usize).clamp(1, v.len());
    v[k - 1]
}

/// One plant's max error, whether it passed, and its draws.
type PlantRun = (f64, bool, Vec<f64>);

/// Run `plants` plants of `job` around `nominal`.
pub fn run(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    plants: &PlantsOptions,
) -> Result<PlantsSummary, SimError> {
    run_with_progress(job, nominal, opts, plants, &|_, _| {})
}

/// [`run`], telling `progress(done, total)` of each plant simulated (from
/// the worker threads, in any order).
pub fn run_with_progress(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    plants: &PlantsOptions,
    progress: &(dyn Fn(u32, u32) + Sync),
) -> Result<PlantsSummary, SimError> {
    plants.check()?;
    let done = std::sync::atomic::AtomicU32::new(0);
    let results: Vec<Result<PlantRun, SimError>> = (0..plants.n)
        .into_par_iter()
        .map(|i| {
            let f = draw(plants.seed, i, plants.spread);
            let m = scaled(nominal, &f);
            let o = simulate_plant(job, nominal, &m, opts, &mut |_, _| {})?;
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, plants.n);
            Ok((o.report.max_error_m, o.report.passed(), f))
        })
        .collect();
    let mut errs = Vec::with_capacity(results.len());
    let mut passed = 0usize;
    let mut deciding = vec![0u32; UNCERTAIN.len()];
    for r in results {
        let (e, ok, f) = r?;
        errs.push(e);
        if ok {
            passed += 1;
        } else if let Some((k, _)) = f
            .iter()
            .enumerate()
            .max_by(|a, b| (a.1 - 1.0).abs().total_cmp(&(b.1 - 1.0).abs()))
        {
            deciding[k] += 1;
        }
    }
    errs.sort_by(f64::total_cmp);
    let most = deciding
        .iter()
        .enumerate()
        .filter(|(_, &c)| c > 0)
        .max_by_key(|(k, &c)| (c, std::cmp::Reverse(*k)))
        .map(|(k, _)| UNCERTAIN[k].0.to_string());
    Ok(PlantsSummary {
        n: plants.n,
        spread: plants.spread,
        seed: plants.seed,
        p50_max_error_m: quantile(&errs, 0.5),
        p95_max_error_m: quantile(&errs, 0.95),
        worst_max_error_m: *errs.last().unwrap_or(&0.0),
        pass_fraction: passed as f64 / plants.n as f64,
        deciding_parameter: most,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_are_fixed_per_seed_and_index_and_within_the_spread() {
        let a = draw(7, 3, 0.1);
        assert_eq!(a, draw(7, 3, 0.1));
        assert_ne!(a, draw(8, 3, 0.1));
        assert_ne!(a, draw(7, 4, 0.1));
        assert!(a.iter().all(|f| (0.9..=1.1).contains(f)));
        // spread 0 is the description itself
        assert!(draw(7, 3, 0.0).iter().all(|&f| f == 1.0));
        // the stream is the algorithm's, not the platform's: pin one value
        let first = draw(7, 0, 0.5)[0];
        assert_eq!(first, draw(7, 0, 0.5)[0]);
    }

    #[test]
    fn quantiles_are_nearest_rank() {
        let v: Vec<f64> = (1..=40).map(f64::from).collect();
        assert_eq!(quantile(&v, 0.5), 20.0);
        assert_eq!(quantile(&v, 0.95), 38.0);
        assert_eq!(quantile(&[3.0], 0.95), 3.0);
    }
}
