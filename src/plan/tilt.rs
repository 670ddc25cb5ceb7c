//! Tilt of the fan nozzle: tile area ratios U (001 eq. 2.7–2.8), trapezoid and quadrilateral bisectors (eq. 2.10–2.20) and the corrected nozzle position (eq. 2.21–2.24).
