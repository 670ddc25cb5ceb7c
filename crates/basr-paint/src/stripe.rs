//! A test stripe: the film an untilted fan lays across a straight stripe
//! painted at one height and speed, and the fit of a tip's flow and flux
//! profile to a measured one (`basr calibrate`).
//!
//! Painted along a straight line at speed `v`, a fan standing square to the
//! travel lays at offset `x` from the line the film
//! `Q·η/v · ρ(x)`, where `ρ(x)` is the share of the fan's paint landing per
//! metre of offset there: `d/dx cdf(atan(x/h))` for the nozzle `h` over the
//! road. The fan's depth along the travel integrates out, so the stripe
//! measures the profile alone.

use super::spray::{Depth, Lobe, Profile, SprayModel};
use super::PaintError;

/// Half-width of the difference that turns the profile's CDF into a density
/// per metre of offset. assumed: 0.1 mm, far below any gauge's spacing
/// (millimetres) and far above f64 noise at 0.1–0.3 m stand-off.
const DENSITY_STEP_M: f64 = 1e-4;

/// Widths (as fractions of the half fan angle) a one-lobe `gauss` profile
/// may take in the fit: past 5 the lobe is flat across the fan
/// (`uniform-angle`), under 0.05 it is a pencil stream, no fan.
const GAUSS_SIGMA_RANGE: (f64, f64) = (0.05, 5.0);

/// A `gauss` fit is preferred to the parameterless profiles only when its
/// residual is below this share of theirs: with one parameter more it always
/// fits a noisy stripe a little closer. assumed: 0.9, so a wide lobe that
/// only follows the noise of a `uniform-angle` stripe is not chosen.
const GAUSS_PREFERENCE: f64 = 0.9;

/// A measured stripe: film across it, and how it was painted.
#[derive(Clone, Debug, PartialEq)]
pub struct Stripe {
    /// Offsets across the stripe (m), any origin: the fit centres them.
    pub offsets_m: Vec<f64>,
    /// Wet film at each offset (m).
    pub film_m: Vec<f64>,
    /// Nozzle tip height over the road (m).
    pub height_m: f64,
    /// Nozzle speed along the stripe (m/s).
    pub speed_mps: f64,
}

/// One profile fitted to a stripe.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    pub profile: Profile,
    /// The profile as `preview --profile` and `paint.profile` take it.
    pub profile_text: String,
    pub flow_m3ps: f64,
    /// RMS of measured − fitted film over the stripe's peak film.
    pub residual: f64,
}

/// The film (m) a fan of `model` at `height_m`, painting `flow_m3ps` with
/// `efficiency` at `speed_mps`, lays at `offset_m` from the stripe's line.
pub fn film_across(
    model: &SprayModel,
    height_m: f64,
    speed_mps: f64,
    flow_m3ps: f64,
    efficiency: f64,
    offset_m: f64,
) -> f64 {
    let theta = |x: f64| (x / height_m).atan();
    let d = DENSITY_STEP_M;
    let per_m = (model.cdf(theta(offset_m + d)) - model.cdf(theta(offset_m - d))) / (2.0 * d);
    flow_m3ps * efficiency / speed_mps * per_m
}

fn check(stripe: &Stripe) -> Result<(), PaintError> {
    let bad = |why: String| Err(PaintError::Model(format!("test stripe: {why}")));
    if stripe.offsets_m.len() != stripe.film_m.len() {
        return bad("offsets and films differ in number".into());
    }
    if stripe.offsets_m.len() < 5 {
        return bad(format!(
            "{} readings; give at least 5 across the stripe (a reading every 5–10 mm)",
            stripe.offsets_m.len()
        ));
    }
    if !(stripe.height_m.is_finite() && stripe.height_m > 0.0) {
        return bad(format!(
            "nozzle height {} m: give the tip's height over the road, above zero",
            stripe.height_m
        ));
    }
    if !(stripe.speed_mps.is_finite() && stripe.speed_mps > 0.0) {
        return bad(format!(
            "speed {} m/s: give the nozzle's speed along the stripe, above zero",
            stripe.speed_mps
        ));
    }
    if stripe
        .offsets_m
        .iter()
        .chain(&stripe.film_m)
        .any(|v| !v.is_finite())
    {
        return bad("an offset or film is not a number".into());
    }
    if stripe.film_m.iter().any(|&f| f < 0.0) {
        return bad("a film reading is negative".into());
    }
    if !stripe.film_m.iter().any(|&f| f > 0.0) {
        return bad("no reading holds any film".into());
    }
    Ok(())
}

/// The flow and residual of `profile` on `stripe` (offsets centred).
fn fit_one(
    stripe: &Stripe,
    centred: &[f64],
    fan_angle_rad: f64,
    efficiency: f64,
    profile: Profile,
    profile_text: String,
) -> Result<Fit, PaintError> {
    let model = SprayModel::new(fan_angle_rad, profile, Depth::default())?;
    // Film per unit flow: linear least squares gives the flow.
    let shape: Vec<f64> = centred
        .iter()
        .map(|&x| {
            film_across(
                &model,
                stripe.height_m,
                stripe.speed_mps,
                1.0,
                efficiency,
                x,
            )
        })
        .collect();
    let ss: f64 = shape.iter().map(|s| s * s).sum();
    let sf: f64 = shape.iter().zip(&stripe.film_m).map(|(s, f)| s * f).sum();
    let flow = if ss > 0.0 { sf / ss } else { 0.0 };
    let peak = stripe.film_m.iter().cloned().fold(0.0, f64::max);
    let n = stripe.film_m.len() as f64;
    let rms = (shape
        .iter()
        .zip(&stripe.film_m)
        .map(|(s, f)| (f - flow * s).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    Ok(Fit {
        profile: model.profile,
        profile_text,
        flow_m3ps: flow,
        residual: rms / peak,
    })
}

fn gauss(sigma: f64) -> (Profile, String) {
    (
        Profile::GaussianSum(vec![Lobe {
            weight: 1.0,
            mean: 0.0,
            sigma,
        }]),
        format!("gauss:1,0,{sigma:.4}"),
    )
}

/// Every profile fitted to `stripe` (uniform, uniform-angle, the best
/// one-lobe gauss), the chosen one first: the lowest residual, a gauss only
/// when clearly below the others (`GAUSS_PREFERENCE`).
pub fn fit(stripe: &Stripe, fan_angle_rad: f64, efficiency: f64) -> Result<Vec<Fit>, PaintError> {
    check(stripe)?;
    // Centre the offsets on the film's centroid: every profile fitted is
    // symmetric about the nozzle axis.
    let total: f64 = stripe.film_m.iter().sum();
    let centre = stripe
        .offsets_m
        .iter()
        .zip(&stripe.film_m)
        .map(|(x, f)| x * f)
        .sum::<f64>()
        / total;
    let centred: Vec<f64> = stripe.offsets_m.iter().map(|x| x - centre).collect();
    let one = |p: Profile, t: String| fit_one(stripe, &centred, fan_angle_rad, efficiency, p, t);
    let mut simple = vec![
        one(Profile::Uniform, "uniform".into())?,
        one(Profile::UniformAngle, "uniform-angle".into())?,
    ];
    simple.sort_by(|a, b| a.residual.total_cmp(&b.residual));
    // The lobe's width: a log grid, then golden-section search around the
    // grid's best (the residual is smooth in σ).
    let (lo, hi) = (GAUSS_SIGMA_RANGE.0.ln(), GAUSS_SIGMA_RANGE.1.ln());
    let at = |ls: f64| {
        let (p, t) = gauss(ls.exp());
        one(p, t)
    };
    const GRID: usize = 40;
    let step = (hi - lo) / GRID as f64;
    let mut best = (lo, f64::INFINITY);
    for k in 0..=GRID {
        let ls = lo + k as f64 * step;
        let r = at(ls)?.residual;
        if r < best.1 {
            best = (ls, r);
        }
    }
    let (mut a, mut b) = ((best.0 - step).max(lo), (best.0 + step).min(hi));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..40 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if at(c)?.residual < at(d)?.residual {
            b = d;
        } else {
            a = c;
        }
    }
    let best_gauss = at((a + b) / 2.0)?;
    let mut all = simple;
    if best_gauss.residual < GAUSS_PREFERENCE * all[0].residual {
        all.insert(0, best_gauss);
    } else {
        all.push(best_gauss);
    }
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALPHA: f64 = 63.5 * std::f64::consts::PI / 180.0; // SPEC §4

    fn stripe_of(profile: Profile, flow: f64) -> Stripe {
        let m = SprayModel::new(ALPHA, profile, Depth::default()).unwrap();
        let offsets_m: Vec<f64> = (-60..=60).map(|k| 0.003 * k as f64 + 0.01).collect();
        let film_m = offsets_m
            .iter()
            .map(|&x| film_across(&m, 0.2, 0.15, flow, 0.9, x - 0.01))
            .collect();
        Stripe {
            offsets_m,
            film_m,
            height_m: 0.2,
            speed_mps: 0.15,
        }
    }

    #[test]
    fn uniform_stripe_lays_the_film_law() {
        // k = Q·η/film and v·w = k: an untilted uniform fan at v lays Q·η/(v·w).
        let m = SprayModel::seed(ALPHA).unwrap();
        let w = 2.0 * 0.2 * (ALPHA / 2.0).tan();
        let f = film_across(&m, 0.2, 0.15, 6.667e-6, 0.9, 0.0);
        assert!(
            (f - 6.667e-6 * 0.9 / (0.15 * w)).abs() < 1e-9 * f.max(1.0),
            "{f}"
        );
    }

    #[test]
    fn each_profile_is_recovered_from_its_own_stripe() {
        for (p, name) in [
            (Profile::Uniform, "uniform"),
            (Profile::UniformAngle, "uniform-angle"),
            (gauss(0.4).0, "gauss"),
        ] {
            let fits = fit(&stripe_of(p, 5e-6), ALPHA, 0.9).unwrap();
            assert!(fits[0].profile_text.starts_with(name), "{name}: {fits:?}");
            assert!((fits[0].flow_m3ps / 5e-6 - 1.0).abs() < 1e-3, "{fits:?}");
            assert!(fits[0].residual < 1e-3, "{fits:?}");
        }
    }

    #[test]
    fn bad_stripes_are_refused() {
        let mut s = stripe_of(Profile::Uniform, 5e-6);
        s.speed_mps = 0.0;
        assert!(fit(&s, ALPHA, 0.9).is_err());
        let mut s = stripe_of(Profile::Uniform, 5e-6);
        s.film_m.iter_mut().for_each(|f| *f = 0.0);
        assert!(fit(&s, ALPHA, 0.9).is_err());
    }
}
