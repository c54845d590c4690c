//! The deterministic numbers behind the random test cases: reports must not change from run
//! to run or from machine to machine, so nothing here is seeded from the clock.

/// xorshift64* (Vigna, "An experimental exploration of Marsaglia's xorshift generators,
/// scrambled", 2016): the emitter patterns of [`super::standard_cases`], the channel mixes
/// of `eigenrad verify` and the random bases of the tests.
///
/// The field is the state, and the seed is its first value; it must not be 0 (the state
/// would stay 0).
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in `[0, 1)`, 53 bits.
    pub fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// Level vector number `k` for `channels` channels, each level in `[0.1, 1]`: an additive
/// recurrence (the golden-ratio conjugate along `k`), so that `eigenrad-bench` can draw
/// vector `k` directly inside a timing loop without carrying a generator, and the levels
/// stay evenly spread however many it draws.
pub fn level_vector(k: usize, channels: usize) -> Vec<f64> {
    (0..channels)
        .map(|c| {
            let x = (k as f64 * 0.618_033_988_75 + c as f64 * 0.377_2).fract();
            0.1 + 0.9 * x
        })
        .collect()
}
