//! The hydraulic modifications of 000 section I and the arm's structure
//! beyond the rigid Lagrange model: supply accumulator and pump, supply check
//! valves, counterbalance valves on the motor's exhaust, the hose between
//! each servovalve port and its actuator, and one lumped lateral bending mode
//! per main link. Numbers in robots/basr.toml `[dynamics]` with sources.
//!
//! Section I: "a hydraulic fluid accumulator to improve power delivery …
//! smoothed out pressure variations in the line … supply check valves were
//! inserted to minimize fluid back-flow between the actuators … counter
//! balanced valves were therefore added on the exhaust side of the motors to
//! provide the needed damping". Section II's model assumes a constant supply
//! p0 and no lines; these add what it left out.

use serde::{Deserialize, Serialize};

/// Supply, check valves, counterbalance valves and lines (constant numbers).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Circuit {
    /// Gas volume of the accumulator at precharge (m³).
    pub acc_gas_m3: f64,
    /// Accumulator gas precharge (Pa).
    pub acc_precharge_pa: f64,
    /// Oil volume of the supply manifold and hose (m³): the supply's
    /// compliance when the accumulator is empty.
    pub supply_volume_m3: f64,
    /// Pressure-compensated pump: full flow (m³/s), falling to zero over the
    /// last `pump_band_pa` below the compensator setting (`supply_pa`).
    pub pump_flow_m3ps: f64,
    pub pump_band_pa: f64,
    /// Supply check valve cracking pressure (Pa): no flow back into supply.
    pub check_crack_pa: f64,
    /// Counterbalance valve: pilot ratio, cracking pressure, opening band (Pa),
    /// fully open orifice coefficient (m³/(s·√Pa)), laminar bleed (m³/(s·Pa)).
    pub cb_pilot_ratio: f64,
    pub cb_crack_pa: f64,
    pub cb_band_pa: f64,
    pub cb_gain: f64,
    pub cb_bleed: f64,
    /// Hose from valve port to actuator: volume (m³), effective bulk modulus
    /// (Pa, oil and hose wall), inertance (kg/m⁴), laminar resistance (Pa·s/m³).
    pub line_volume_m3: f64,
    pub line_bulk_pa: f64,
    pub line_inertance: f64,
    pub line_resistance: f64,
    /// Supply pressure can be cut (a fault): pump flow × this factor.
    pub pump_on: bool,
}

impl Circuit {
    /// dV_oil/dp of the supply node (m³/Pa): the accumulator's gas above
    /// precharge, the manifold oil always.
    #[inline]
    pub fn supply_capacitance(&self, p: f64, bulk: f64) -> f64 {
        let oil = self.supply_volume_m3 / bulk;
        if p > self.acc_precharge_pa {
            // isothermal nitrogen (assumed: the supply swings by a few per
            // cent; a polytropic exponent of 1.4 would stiffen it by 40 % and
            // cost a powf per step): V_gas = V0·p0/p, −dV_gas/dp = V0·p0/p²
            oil + self.acc_gas_m3 * self.acc_precharge_pa / (p * p)
        } else {
            oil
        }
    }

    /// Pump delivery at supply pressure `p` against compensator setting `set`.
    #[inline]
    pub fn pump_flow(&self, p: f64, set: f64) -> f64 {
        if !self.pump_on {
            return 0.0;
        }
        self.pump_flow_m3ps * ((set - p) / self.pump_band_pa).clamp(0.0, 1.0)
    }

    /// Opening (0..1) of the counterbalance valve on the exhaust side at
    /// `p_ex`, piloted by the inlet side `p_pilot`.
    #[inline]
    pub fn cb_opening(&self, p_ex: f64, p_pilot: f64) -> f64 {
        // closed below cracking: a load-holding poppet (its damping is the
        // bleed across the motor, `cb_bleed`); a 5 % floor let a motor whose
        // inlet had lost pressure coast on at 0.2 rad/s (issue 12, faults)
        ((p_ex + self.cb_pilot_ratio * p_pilot - self.cb_crack_pa) / self.cb_band_pa)
            .clamp(0.0, 1.0)
    }

    /// Natural frequency of one line (Hz): inertance on the hose's compliance.
    pub fn line_hz(&self) -> f64 {
        (self.line_bulk_pa / (self.line_volume_m3 * self.line_inertance)).sqrt()
            / std::f64::consts::TAU
    }
}

/// One lumped lateral bending mode per main link (rad/s, damping ratio) and
/// how far each moves the nozzle per metre of modal deflection.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Boom {
    pub omega: [f64; 2],
    pub damping_ratio: f64,
}

/// Series combination of two orifices (m³/(s·√Pa)): 1/a² = 1/a1² + 1/a2².
#[inline]
pub fn series(a1: f64, a2: f64) -> f64 {
    if a1 <= 0.0 || a2 <= 0.0 {
        0.0
    } else {
        a1 * a2 / (a1 * a1 + a2 * a2).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SimModel;

    #[test]
    fn accumulator_is_far_softer_than_the_manifold_above_precharge() {
        let c = SimModel::basr().circuit;
        let e = 1.6e9;
        let above = c.supply_capacitance(2.0e7, e);
        let below = c.supply_capacitance(0.9 * c.acc_precharge_pa, e);
        assert!(above > 20.0 * below, "{above} vs {below}");
        // the gas law: C·p integrates to the gas volume change
        let (p1, p2) = (1.6e7, 2.0e7);
        let n = 2000;
        let dv: f64 = (0..n)
            .map(|i| {
                let p = p1 + (p2 - p1) * (i as f64 + 0.5) / n as f64;
                (c.supply_capacitance(p, e) - c.supply_volume_m3 / e) * (p2 - p1) / n as f64
            })
            .sum();
        let gas = |p: f64| c.acc_gas_m3 * c.acc_precharge_pa / p;
        assert!((dv - (gas(p1) - gas(p2))).abs() < 1e-4 * dv);
    }

    #[test]
    fn counterbalance_closes_when_the_inlet_loses_pressure() {
        let c = SimModel::basr().circuit;
        let open = c.cb_opening(1.0e7, 1.0e7);
        let braking = c.cb_opening(1.4e7, 0.4e7);
        assert!(open > 0.5 && braking < open, "{open} {braking}");
        assert!((series(3.0, 4.0) - 2.4).abs() < 1e-12);
    }
}
