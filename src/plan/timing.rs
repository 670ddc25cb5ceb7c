//! Time law: a time-optimal parameterisation of a joint path under velocity and acceleration limits, resampled at the control period.
