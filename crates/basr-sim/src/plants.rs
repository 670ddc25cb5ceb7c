//! `basr simulate --plants N --spread F --seed S` (SPEC §6): the verdict
//! when the model is wrong. N plants are drawn around the robot description
//! — every uncertain number scaled by 1 + F·w·u, u uniform in [−1, 1], w
//! how poorly that number is known against the others (`UNCERTAIN`) — and
//! the controller, built for the description, drives each. The draws are a
//! fixed algorithm (xorshift128 seeded from S and the plant's index), so the
//! same call gives the same bytes on every machine; the plants run in
//! parallel (rayon) and are gathered in index order.

use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use serde::Serialize;

use super::{simulate_plant, Checkpoints, Options, SimError, SimModel};
use basr_job::Job;

/// The uncertain numbers: name (as in the robot description), how far each
/// is known relative to the others, and how to scale it in the simulator's
/// model.
type Scale = fn(&mut SimModel, f64);

/// One uncertain number of the plant.
struct Uncertain {
    name: &'static str,
    /// Its spread in units of `--spread`: a plant draws the number within
    /// ±`spread × weight` of the description's (at most ±[`MAX_SHARE`]).
    /// 1 is a number known to about ±10 % at the default spread 0.1.
    weight: f64,
    scale: Scale,
}

/// Largest share any one number is drawn off the description (a mass or a
/// modulus at −100 % is no longer the arm described).
pub const MAX_SHARE: f64 = 0.5;

const UNCERTAIN: [Uncertain; 12] = [
    // Gun, valve and the paint in them; not weighed per job.
    Uncertain {
        name: "end_effector.mass_kg",
        weight: 1.0,
        scale: |m, f| m.arm.ee_mass_kg *= f,
    },
    // the links' masses follow the holding force B (model.rs)
    Uncertain {
        name: "hydraulics.gravity_b_n",
        weight: 1.0,
        scale: |m, f| m.arm.holding_b_n *= f,
    },
    // From drawings, not measured.
    Uncertain {
        name: "dynamics.base_inertia_kgm2",
        weight: 1.0,
        scale: |m, f| m.arm.base_inertia_kgm2 *= f,
    },
    // Seal friction changes with the oil's temperature and the seals' wear
    // (000 models it as Stribeck friction with fitted constants): twice the
    // others' spread.
    Uncertain {
        name: "dynamics.motor friction",
        weight: 2.0,
        scale: |m, f| {
            m.motor.friction.viscous *= f;
            m.motor.friction.coulomb *= f;
            m.motor.friction.stiction *= f;
        },
    },
    Uncertain {
        name: "dynamics.cylinder friction",
        weight: 2.0,
        scale: |m, f| {
            m.cylinder.friction.viscous *= f;
            m.cylinder.friction.coulomb *= f;
            m.cylinder.friction.stiction *= f;
        },
    },
    // The effective modulus of oil with entrained air and hoses is known
    // poorly (000 assumes it constant): twice the others' spread.
    Uncertain {
        name: "hydraulics.bulk_modulus_pa",
        weight: 2.0,
        scale: |m, f| m.hydraulics.bulk_modulus_pa *= f,
    },
    // Servovalve catalogues give rated flow to ±10 %.
    Uncertain {
        name: "hydraulics.valve_flow_gain",
        weight: 1.0,
        scale: |m, f| m.motor.valve_gain *= f,
    },
    Uncertain {
        name: "dynamics.cylinder_valve_flow_gain",
        weight: 1.0,
        scale: |m, f| m.cylinder.valve_gain *= f,
    },
    // A pressure-compensated pump holds its setting: the seeds take the
    // supply as constant (000 §2, p_0), and service manuals give the
    // compensator's setting to about ±2 % (for example 21 000 ± 350 kPa,
    // US Army TM 5-3805-291-23-1, 0003 00-109); half the others' spread
    // leaves room for the drop in the lines at full flow.
    Uncertain {
        name: "hydraulics.supply_pa",
        weight: 0.5,
        scale: |m, f| m.hydraulics.supply_pa *= f,
    },
    Uncertain {
        name: "dynamics.valve_time_constant_s",
        weight: 1.0,
        scale: |m, f| {
            m.motor.valve_tau_s *= f;
            m.cylinder.valve_tau_s *= f;
        },
    },
    Uncertain {
        name: "dynamics.counterbalance_bleed_m3_per_s_pa",
        weight: 1.0,
        scale: |m, f| m.circuit.cb_bleed *= f,
    },
    // The pressure transducers' calibration (span error): industrial
    // transmitters are specified to 0.1–0.5 % of span; a tenth of the
    // others' spread (±1 % at 0.1) leaves room for the amplifier and ADC.
    Uncertain {
        name: "dynamics.pressure_pa_per_volt",
        weight: 0.1,
        scale: |m, f| m.sensors.pressure_gain *= f,
    },
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
    /// The uncertain number drawn furthest from its value (in its own
    /// spread) in most failing
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
        .map(|k| {
            let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64; // [0, 1)
            1.0 + share(spread, k.weight) * (2.0 * u - 1.0)
        })
        .collect()
}

/// How far a number of `weight` is drawn at `spread`: ±this share.
fn share(spread: f64, weight: f64) -> f64 {
    (spread * weight).min(MAX_SHARE)
}

/// The uncertain numbers' names, in the order of [`draw`]'s factors.
pub fn names() -> Vec<&'static str> {
    UNCERTAIN.iter().map(|u| u.name).collect()
}

/// Each uncertain number's name and the share it is drawn within at
/// `spread` (±, of the description's value), in [`draw`]'s order.
pub fn shares(spread: f64) -> Vec<(&'static str, f64)> {
    UNCERTAIN
        .iter()
        .map(|u| (u.name, share(spread, u.weight)))
        .collect()
}

/// `nominal` with each uncertain number scaled by its factor of `f`.
pub fn scaled(nominal: &SimModel, f: &[f64]) -> SimModel {
    let mut m = nominal.clone();
    for (u, fi) in UNCERTAIN.iter().zip(f) {
        (u.scale)(&mut m, *fi);
    }
    m
}

/// Each plant of `factors` (one factor per uncertain number, in
/// [`names`]' order, as [`draw`] gives them) driven through `job` by the
/// controller built for `nominal`, in parallel; the reports and each run's
/// checkpoints in the order of `factors`. `resume`: the checkpoints of the
/// same plants' runs of the job as it was and the first row at which its
/// rows changed since (`Samples::first_difference`); each run resumes at
/// its last checkpoint before it, and reports as a whole run. Compile's
/// verification on the spread runs its fixed set so.
pub fn run_each(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    factors: &[Vec<f64>],
    resume: Option<(Vec<Checkpoints>, usize)>,
) -> Result<Vec<(super::Report, Checkpoints)>, SimError> {
    let resumes = resumes_of(factors, resume)?;
    let runs: Vec<Result<(super::Report, Checkpoints), SimError>> = factors
        .par_iter()
        .zip(resumes)
        .map(|(f, resume)| {
            let m = scaled(nominal, f);
            super::simulate_plant_resumable(job, nominal, &m, opts, resume)
                .map(|(o, c)| (o.report, c))
        })
        .collect();
    // the first error in the plants' order, whichever thread met it first
    runs.into_iter().collect()
}

/// Each plant's checkpoints to resume from (none unless there is one set
/// per plant), once every plant has a factor per uncertain number.
fn resumes_of(
    factors: &[Vec<f64>],
    resume: Option<(Vec<Checkpoints>, usize)>,
) -> Result<Vec<Option<(Checkpoints, usize)>>, SimError> {
    if let Some(f) = factors.iter().find(|f| f.len() != UNCERTAIN.len()) {
        return Err(SimError::Option(format!(
            "a plant needs {} factors, not {}",
            UNCERTAIN.len(),
            f.len()
        )));
    }
    Ok(match resume {
        Some((cps, row)) if cps.len() == factors.len() => {
            cps.into_iter().map(|c| Some((c, row))).collect()
        }
        _ => factors.iter().map(|_| None).collect(),
    })
}

/// [`run_each`], the plants advanced together (`lockstep`): at every
/// checkpoint each waits for the others, and once one has ended at its
/// first painting error over `opts.stop_over_m` the others end at the next
/// checkpoint instead of running on. Compile's verification asks of the
/// set only which plant failed first, where and why, and re-times there:
/// that plant's report (and that of every plant that failed before the
/// checkpoint where the others ended) is the one [`run_each`] gives; a
/// plant ended early reports the run up to there (its largest error so
/// far). A plant ended early with a limit broken is run on to its end, so
/// that its report is a whole run's as well; one that would break a limit
/// only after that checkpoint is not seen to fail in this round (run
/// alone, it would be, and ranked by the time of its largest error: the
/// set's failure is then found in the next round, if the re-timing did
/// not remove it).
/// One thread per plant (they wait for each other, which a pool of fewer
/// threads could not); the reports and checkpoints in `factors`' order.
pub fn run_each_in_step(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    factors: &[Vec<f64>],
    resume: Option<(Vec<Checkpoints>, usize)>,
) -> Result<Vec<(super::Report, Checkpoints)>, SimError> {
    let resumes = resumes_of(factors, resume)?;
    let models: Vec<SimModel> = factors.iter().map(|f| scaled(nominal, f)).collect();
    let runs = in_step(job, nominal, opts, None, &models, resumes);
    whole_where_broken(job, nominal, opts, &models, runs)
}

/// The robot description's own run of `job` (resumed from `described`,
/// as `simulate_resumable` resumes) beside [`run_each_in_step`]'s plants,
/// all in step: the description's run leads (`lockstep::Group::
/// leader_gate`): its failure ends the plants at the next checkpoint,
/// and a plant's failure ends it at a checkpoint once it knows of it.
/// Compile verifies a station on the description first and on the set
/// only once it passes; run together, the two cores the set shares are
/// never idle while the description runs alone, and a plant that fails
/// early ends the description's run soon after: the station is re-timed
/// at that failure, after which the rows differ and every run resumes
/// there anyway (a fitted STOP ran the description 115 s past a plant's
/// failure, twice). Returns the description's run and, when it did not
/// fail before every plant did, the plants' reports as
/// [`run_each_in_step`] gives them (`Beside::stopped`: a plant failed
/// first); when it did, `Err` of the plants' checkpoints as far as they
/// ran (their reports say nothing: the station is re-timed for the
/// description first), for the next round to resume from. Which of these
/// it is, and the plants' reports, do not depend on the threads' timing;
/// whether and where the description's run ended after a plant failed
/// first does (it runs on until it knows), and so its report, which says
/// only that it had not failed before (a run on from its last checkpoint
/// is the whole run, bit for bit).
pub fn run_beside_description_in_step(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    described: Option<(Checkpoints, usize)>,
    factors: &[Vec<f64>],
    resume: Option<(Vec<Checkpoints>, usize)>,
) -> Result<Beside, SimError> {
    let resumes = resumes_of(factors, resume)?;
    let models: Vec<SimModel> = factors.iter().map(|f| scaled(nominal, f)).collect();
    let mut runs = in_step(job, nominal, opts, Some(described), &models, resumes);
    let (description, stopped) = runs.remove(0);
    let description = description?;
    // A plant that failed before the description's own failure: the
    // description, not knowing of it yet, ran on to its own.
    let plant_first = |own: f64| {
        runs.iter().any(|(run, _)| {
            run.as_ref()
                .is_ok_and(|(o, _)| o.report.cut_short_at_s.is_some_and(|t| t < own))
        })
    };
    let own = description.0.report.cut_short_at_s;
    let stopped = stopped || own.is_some_and(plant_first);
    if own.is_some() && !stopped {
        let kept = runs
            .into_iter()
            .map(|(run, _)| run.map(|(_, k)| k))
            .collect::<Result<_, _>>()?;
        return Ok(Beside {
            description,
            stopped: false,
            plants: Err(kept),
        });
    }
    let plants = whole_where_broken(job, nominal, opts, &models, runs)?;
    Ok(Beside {
        description,
        stopped,
        plants: Ok(plants),
    })
}

/// The description's run beside the plants' ([`run_beside_description_in_step`]).
pub struct Beside {
    /// The description's run, and its checkpoints.
    pub description: (super::Outcome, Checkpoints),
    /// A plant failed first: the description's run ended at a checkpoint
    /// after that failure, or at its own failure later; its report is not
    /// a verdict (it had not failed before the plant did). Run on from its
    /// last checkpoint (`simulate_resumable` with no row changed), it is
    /// the whole run, for a station that is not re-timed there.
    pub stopped: bool,
    /// The plants' reports, or their checkpoints as far as they ran when
    /// the description failed.
    pub plants: Result<Vec<(super::Report, Checkpoints)>, Vec<Checkpoints>>,
}

/// How many checkpoints' time the description's run may lead the plants
/// in step beside it (`lockstep::Group::leading_by`). assumed: two keep a
/// fitted STOP's description from running far past the plants' first
/// failure (`benches/fit.rs`: the description had run to 88 s when a plant
/// failed at 24 s; the fit simulated 214 300 ticks, held 210 300 with 5 s
/// checkpoints, 204 998 with 1 s ones) and leave compile STOP's ticks as
/// they were (205 352 with 5 s checkpoints, 204 152 with 1 s).
const LEAD_CHECKPOINTS: f64 = 2.0;

/// A run of a group in step, and whether the group ended it.
type StepRun = (Result<(super::Outcome, Checkpoints), SimError>, bool);

/// Runs of `job` in step on their own threads: the description's (driven
/// by the controller built for `nominal`, resumed from `described`'s
/// checkpoints) first and leading (`lockstep::Group::leader_gate`) when
/// `described` is given, then one per plant of `models` (resumed from
/// `resumes`); each run and whether the group ended it. One thread per
/// run: they wait for each other, which a pool of fewer threads could
/// not.
fn in_step(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    described: Option<Option<(Checkpoints, usize)>>,
    models: &[SimModel],
    resumes: Vec<Option<(Checkpoints, usize)>>,
) -> Vec<StepRun> {
    let led = described.is_some();
    let mut runs: Vec<(&SimModel, Option<(Checkpoints, usize)>)> = Vec::new();
    if let Some(resume) = described {
        runs.push((nominal, resume));
    }
    runs.extend(models.iter().zip(resumes));
    // The description leads by two checkpoints at most: a plant's failure
    // then costs it at most that much more simulation than the plants, and
    // the threads of the others still have its windows to catch up in.
    let group = super::lockstep::Group::new(runs.len())
        .leading_by(LEAD_CHECKPOINTS * super::run::CHECKPOINT_S);
    // Every gate before any thread (`Group::gates`).
    let gates = group.gates(led.then_some(0));
    std::thread::scope(|sc| {
        let handles: Vec<_> = runs
            .into_iter()
            .zip(gates)
            .map(|((m, resume), mut gate)| {
                sc.spawn(move || {
                    let run = super::run::run_resumable(
                        job,
                        nominal,
                        m,
                        opts,
                        &[],
                        &mut |_, _| {},
                        resume,
                        true,
                        Some(&mut gate),
                    );
                    (run, gate.stopped)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect::<Vec<_>>()
    })
}

/// The plants' reports of runs in step: one the group ended with a limit
/// broken is run on from its last checkpoint to its end, so that its
/// report is a whole run's as well.
fn whole_where_broken(
    job: &Job,
    nominal: &SimModel,
    opts: &Options,
    models: &[SimModel],
    runs: Vec<StepRun>,
) -> Result<Vec<(super::Report, Checkpoints)>, SimError> {
    let end = job.samples.len();
    models
        .iter()
        .zip(runs)
        .map(|(m, (run, stopped))| {
            let (outcome, kept) = run?;
            let broke = outcome.report.limits.iter().any(|l| l.fails);
            if stopped && broke {
                // the rest of the run, from its last checkpoint
                let (o, k) =
                    super::simulate_plant_resumable(job, nominal, m, opts, Some((kept, end)))?;
                return Ok((o.report, k));
            }
            Ok((outcome.report, kept))
        })
        .collect()
}

/// The p-quantile (0..1) of sorted `v` (nearest rank).
pub fn quantile(v: &[f64], p: f64) -> f64 {
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
            .zip(UNCERTAIN.iter())
            .map(|(fi, u)| (fi - 1.0).abs() / share(plants.spread, u.weight).max(f64::MIN_POSITIVE))
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
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
        .map(|(k, _)| UNCERTAIN[k].name.to_string());
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
        // each number within its own share of the spread
        for (f, (_, sh)) in a.iter().zip(shares(0.1)) {
            assert!((1.0 - sh..=1.0 + sh).contains(f), "{f} outside ±{sh}");
        }
        // a number known twice as poorly is drawn twice as far, capped at ±50 %
        let sh = shares(0.1);
        let w = |n: &str| sh.iter().find(|s| s.0 == n).unwrap().1;
        assert!((w("dynamics.motor friction") - 0.2).abs() < 1e-12);
        assert!((w("hydraulics.supply_pa") - 0.05).abs() < 1e-12);
        assert!((w("dynamics.pressure_pa_per_volt") - 0.01).abs() < 1e-12);
        assert!(shares(0.5).iter().all(|s| s.1 <= MAX_SHARE));
        let wide: Vec<f64> = (0..200).flat_map(|i| draw(1, i, 0.5)).collect();
        assert!(wide
            .iter()
            .all(|f| (1.0 - MAX_SHARE..=1.0 + MAX_SHARE).contains(f)));
        // spread 0 is the description itself
        assert!(draw(7, 3, 0.0).iter().all(|&f| f == 1.0));
        // the stream is the algorithm's, not the platform's: compile's
        // verification set is plants 0–4 of seed 1 at 0.1, so pin plant 0
        let pinned = [
            0.9286749903400588,
            1.0732569829352498,
            1.0212544289939172,
            0.8531877224195291,
            0.824289794284307,
            0.9032154821973599,
            1.0056512947117855,
            1.0168043591375187,
            1.0477662836583184,
            1.0703240722586267,
            1.0352253142786145,
            1.0097633087039943,
        ];
        assert_eq!(draw(1, 0, 0.1), pinned);
    }

    /// The tests' set: the synthetic letter, the seed's plant, six plants
    /// drawn wide around it, and each plant's whole run.
    #[allow(clippy::type_complexity)]
    fn set_up() -> (
        Job,
        SimModel,
        Vec<Vec<f64>>,
        Vec<(crate::Report, Checkpoints)>,
    ) {
        let job = crate::synthetic::letter_job();
        let nominal = SimModel::basr();
        let factors: Vec<Vec<f64>> = (0..6).map(|i| draw(3, i, 0.3)).collect();
        let whole = run_each(&job, &nominal, &Options::default(), &factors, None).unwrap();
        (job, nominal, factors, whole)
    }

    /// The plants in step give the first failure (plant, place, report) a
    /// run of each alone gives, every time; the others report no more
    /// than their whole runs.
    #[test]
    fn plants_in_step_find_the_same_first_failure() {
        let (job, nominal, factors, whole) = set_up();
        let mut errors: Vec<f64> = whole.iter().map(|(r, _)| r.max_error_m).collect();
        errors.sort_by(f64::total_cmp);
        // a bound some plants pass and some fail, at different places
        let opts = Options {
            stop_over_m: Some(0.5 * (errors[2] + errors[3])),
            ..Options::default()
        };
        let alone = run_each(&job, &nominal, &opts, &factors, None).unwrap();
        let first = |runs: &[(crate::Report, Checkpoints)]| {
            runs.iter()
                .enumerate()
                .filter(|(_, (r, _))| r.cut_short_at_s.is_some())
                .min_by(|a, b| a.1 .0.worst.t_s.total_cmp(&b.1 .0.worst.t_s))
                .map(|(i, (r, _))| (i, r.clone()))
        };
        let want = first(&alone).expect("a plant fails");
        let failed = alone
            .iter()
            .filter(|(r, _)| r.cut_short_at_s.is_some())
            .count();
        assert!((2..6).contains(&failed), "{failed} of 6 fail");
        let mut last = None;
        for _ in 0..3 {
            let step = run_each_in_step(&job, &nominal, &opts, &factors, None).unwrap();
            assert_eq!(first(&step), Some(want.clone()));
            for ((s, _), (a, _)) in step.iter().zip(&alone) {
                if s.cut_short_at_s.is_some() {
                    assert_eq!(s, a, "a plant that failed in step failed so alone");
                } else {
                    assert!(s.max_error_m <= a.max_error_m);
                }
            }
            assert!(
                step.iter()
                    .zip(&alone)
                    .any(|((s, _), (a, _))| s.cut_short_at_s.is_none() && s != a),
                "a plant ended early, at a checkpoint after the first failure"
            );
            let reports: Vec<crate::Report> = step.into_iter().map(|(r, _)| r).collect();
            if let Some(prev) = &last {
                assert_eq!(prev, &reports, "the same every time");
            }
            last = Some(reports);
        }
    }

    /// The description's run beside the set is its run alone up to where
    /// the group ends it: run on from its last checkpoint, it is its run
    /// alone; when a plant fails first, the plants report as in step
    /// without it; when it fails first, the plants end soon after and
    /// their checkpoints are returned for the next round.
    #[test]
    fn the_description_beside_the_set_is_its_run_alone() {
        let (job, nominal, factors, whole) = set_up();
        let mut errors: Vec<f64> = whole.iter().map(|(r, _)| r.max_error_m).collect();
        errors.sort_by(f64::total_cmp);
        let lone = |opts: &Options| {
            crate::simulate_resumable(&job, &nominal, opts, None)
                .unwrap()
                .0
                .report
        };
        let described = lone(&Options::default()).max_error_m;
        // plants fail, the description passes
        let opts = Options {
            stop_over_m: Some(0.5 * (errors[2] + errors[3]).max(described * 1.01)),
            ..Options::default()
        };
        for _ in 0..3 {
            let b = run_beside_description_in_step(&job, &nominal, &opts, None, &factors, None)
                .unwrap();
            let (d, kept) = b.description;
            assert_eq!(d.report.cut_short_at_s, None, "it did not fail itself");
            // ended early once it knew of the plant's failure, or whole
            // when it did not know in time
            let rest =
                crate::simulate_resumable(&job, &nominal, &opts, Some((kept, job.samples.len())))
                    .unwrap()
                    .0
                    .report;
            assert_eq!(rest, lone(&opts), "run on, it is its run alone");
            assert!(d.report.max_error_m <= rest.max_error_m);
            if !b.stopped {
                assert_eq!(d.report, rest);
            }
            let step = run_each_in_step(&job, &nominal, &opts, &factors, None).unwrap();
            let Ok(set) = b.plants else {
                panic!("the description did not fail: the plants report");
            };
            let a: Vec<&crate::Report> = set.iter().map(|(r, _)| r).collect();
            let b: Vec<&crate::Report> = step.iter().map(|(r, _)| r).collect();
            assert_eq!(a, b);
        }
        // no run fails: the description runs whole
        let opts = Options {
            stop_over_m: Some(2.0 * errors[5].max(described)),
            ..Options::default()
        };
        let b =
            run_beside_description_in_step(&job, &nominal, &opts, None, &factors, None).unwrap();
        assert!(!b.stopped);
        assert_eq!(b.description.0.report, lone(&opts));
        // the description fails: when before every plant, the plants end
        // at most a checkpoint later and wait for the next round; when a
        // plant failed first, the plants report (the station is re-timed
        // there first)
        // (plants like the description fail with it, not before it)
        let same = vec![vec![1.0; factors[0].len()]; 2];
        let mut seen = [false; 2];
        for (factors, k) in [&factors, &same]
            .into_iter()
            .flat_map(|f| (3..10).map(move |k| (f, k)))
        {
            let opts = Options {
                stop_over_m: Some(0.1 * k as f64 * described),
                ..Options::default()
            };
            let want = lone(&opts);
            let Some(own) = want.cut_short_at_s else {
                continue;
            };
            let plant_first = run_each(&job, &nominal, &opts, factors, None)
                .unwrap()
                .iter()
                .filter_map(|(r, _)| r.cut_short_at_s)
                .any(|t| t < own);
            let b =
                run_beside_description_in_step(&job, &nominal, &opts, None, factors, None).unwrap();
            assert_eq!(b.stopped, plant_first, "bound {k}/10");
            match b.plants {
                Err(kept) => {
                    assert!(!plant_first);
                    assert_eq!(b.description.0.report, want);
                    assert_eq!(kept.len(), factors.len());
                }
                Ok(set) => {
                    assert!(plant_first);
                    let step = run_each_in_step(&job, &nominal, &opts, factors, None).unwrap();
                    let a: Vec<&crate::Report> = set.iter().map(|(r, _)| r).collect();
                    let b: Vec<&crate::Report> = step.iter().map(|(r, _)| r).collect();
                    assert_eq!(a, b);
                }
            }
            seen[plant_first as usize] = true;
        }
        assert_eq!(seen, [true, true], "both orders met");
    }

    /// Runs in step resumed from checkpoints past the group's first
    /// failure (the set kept from a round its description failed, where a
    /// plant had failed first) meet that failure at the checkpoint they
    /// resume at, and report as the set run afresh: a resumed run checks
    /// the group there as a whole run does.
    #[test]
    fn a_set_resumed_past_a_plant_failure_reports_as_a_fresh_set() {
        let (job, nominal, factors, whole) = set_up();
        let cp = crate::run::CHECKPOINT_S;
        // a bound some plants fail before the first checkpoint and others
        // pass it: those end there, with a checkpoint at it
        let found = whole
            .iter()
            .flat_map(|(r, _)| (3..10).map(move |s| 0.1 * s as f64 * r.max_error_m))
            .find_map(|b| {
                let opts = Options {
                    stop_over_m: Some(b),
                    ..Options::default()
                };
                let alone = run_each(&job, &nominal, &opts, &factors, None).unwrap();
                let t: Vec<Option<f64>> = alone.iter().map(|(r, _)| r.cut_short_at_s).collect();
                let early = t.iter().flatten().any(|&t| t < cp);
                let past = t.iter().any(|t| t.is_none_or(|t| t > 2.0 * cp));
                (early && past).then_some(opts)
            });
        let opts = found.expect("a bound some plants fail before 5 s and others pass 10 s at");
        let (fresh, kept): (Vec<crate::Report>, Vec<Checkpoints>) =
            run_each_in_step(&job, &nominal, &opts, &factors, None)
                .unwrap()
                .into_iter()
                .unzip();
        let rows = job.samples.len();
        let resumed: Vec<crate::Report> =
            run_each_in_step(&job, &nominal, &opts, &factors, Some((kept, rows)))
                .unwrap()
                .into_iter()
                .map(|(r, _)| r)
                .collect();
        assert_eq!(resumed, fresh);
    }

    #[test]
    fn quantiles_are_nearest_rank() {
        let v: Vec<f64> = (1..=40).map(f64::from).collect();
        assert_eq!(quantile(&v, 0.5), 20.0);
        assert_eq!(quantile(&v, 0.95), 38.0);
        assert_eq!(quantile(&[3.0], 0.95), 3.0);
    }
}
