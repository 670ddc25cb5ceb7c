//! Closed-loop simulation: arm and hydraulics plant, sensors, controllers, integrator, report.
