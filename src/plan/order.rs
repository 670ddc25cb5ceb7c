//! Stroke order and direction that minimise air travel.
