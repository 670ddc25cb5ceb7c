//! A deterministic ±1 noise source for measured points in tests and
//! benches (a 64-bit LCG; Knuth's MMIX constants).

/// The generator's state.
pub struct Noise(pub u64);

impl Noise {
    /// The next value, uniform in [−1, 1).
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}
