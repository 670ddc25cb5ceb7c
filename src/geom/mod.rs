//! Curves and edges: lines, cardinal splines, conic arcs; evaluation, arc length, subdivision.
