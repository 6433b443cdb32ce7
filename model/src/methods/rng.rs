//! A small deterministic random number generator for Monte Carlo: SplitMix64 to seed,
//! xoshiro256++ to draw (Blackman & Vigna 2018). Streams are keyed by (seed, pixel, pass), so a
//! render is reproducible whatever the thread schedule.

/// xoshiro256++ state.
#[derive(Debug, Clone)]
pub struct Rng {
    s: [u64; 4],
}

fn splitmix64(x: &mut u64) -> u64 {
    *x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *x;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Rng {
    /// A stream for the given keys.
    pub fn new(seed: u64, stream: u64, pass: u64) -> Rng {
        let mut x = seed
            ^ stream.wrapping_mul(0xD1B5_4A32_D192_ED03)
            ^ pass.wrapping_mul(0xABC9_8388_FB8F_AC03);
        Rng {
            s: [
                splitmix64(&mut x),
                splitmix64(&mut x),
                splitmix64(&mut x),
                splitmix64(&mut x),
            ],
        }
    }

    pub fn next_u64(&mut self) -> u64 {
        let s = &mut self.s;
        let result = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_is_in_range_with_the_right_mean_and_streams_differ() {
        let mut r = Rng::new(1, 2, 3);
        let n = 100_000;
        let mean = (0..n)
            .map(|_| r.uniform())
            .inspect(|u| assert!((0.0..1.0).contains(u)))
            .sum::<f64>()
            / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
        assert_ne!(Rng::new(1, 2, 3).next_u64(), Rng::new(1, 2, 4).next_u64());
        assert_eq!(Rng::new(7, 8, 9).next_u64(), Rng::new(7, 8, 9).next_u64());
    }
}
