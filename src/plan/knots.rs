//! Rungs to knots: fan direction, width, nozzle height and painting speed per rung (001 eq. 2.4–2.6), and splitting wide strokes into passes.
