//! Colour maps: perceptually even viridis for quantities, and a few fixed
//! colours for overlays.

/// Viridis anchor colours at t = 0, 1/8, …, 1 (matplotlib's viridis, the
/// standard perceptually uniform map; sampled from its published table).
const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 144, 141],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

/// Viridis at `t` ∈ [0, 1] (clamped; NaN gives the low end).
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let pos = t * (VIRIDIS.len() - 1) as f64;
    let k = (pos.floor() as usize).min(VIRIDIS.len() - 2);
    let f = pos - k as f64;
    let mut out = [0u8; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (a, b) = (VIRIDIS[k][c] as f64, VIRIDIS[k + 1][c] as f64);
        *o = (a + f * (b - a)).round() as u8;
    }
    out
}

/// Film within this factor of the target is drawn as on target (the ±10 %
/// band of the film scale). // assumed: 10 % off is not visible on a road.
pub const FILM_BAND: f64 = 0.10;

/// The film colour scale, diverging about the target: `ratio` = film /
/// target. Thin film in blues (darker thinner), the ±10 % band around the
/// target one flat green, heavy film in oranges to dark red at 1.5×.
pub fn film(ratio: f64) -> [u8; 3] {
    let mix = |a: [u8; 3], b: [u8; 3], t: f64| -> [u8; 3] {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        std::array::from_fn(|c| (a[c] as f64 + t * (b[c] as f64 - a[c] as f64)).round() as u8)
    };
    // ColorBrewer RdBu ends and YlOrRd middle, a green band between.
    let (lo, hi) = (1.0 - FILM_BAND, 1.0 + FILM_BAND);
    if ratio < lo {
        mix([8, 48, 107], [158, 202, 225], ratio / lo)
    } else if ratio <= hi {
        [35, 139, 69]
    } else {
        mix([254, 178, 76], [128, 0, 38], (ratio - hi) / (1.5 - hi))
    }
}

/// `#rrggbb` for a colour.
pub fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Overlay colours shared by the plots.
pub mod palette {
    /// Letter outlines.
    pub const OUTLINE: &str = "#d7191c";
    /// Nozzle path with the gun on.
    pub const PATH_ON: &str = "#ffffff";
    /// Nozzle path with the gun off (air moves).
    pub const PATH_OFF: &str = "#7f7f7f";
    /// Truck stations.
    pub const STATION: &str = "#2c7bb6";
    /// Bare road.
    pub const ROAD: &str = "#e6e6e6";
    /// Text.
    pub const INK: &str = "#1a1a1a";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_clamps() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(2.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        assert_eq!(hex([0, 16, 255]), "#0010ff");
    }
}
