//! Paint: the spray deposition model, the film raster and its metrics.
