//! Display transform: linear sRGB radiance → exposure → tone map → sRGB-encoded 8-bit.
//!
//! Exposure 0 EV maps a luminance of 20 W·m⁻²·sr⁻¹ in Y (≈ 14 000 cd/m², a bright daylight sky)
//! to 1 before tone mapping; +1 EV doubles it. The exponential curve 1 − e^(−x) is the papers'
//! (Bruneton 2008, Hillaire 2020); the filmic one is Narkowicz's ACES fit.

use crate::colour::srgb_encode;
use crate::scene::ToneMap;

/// Scale from linear radiance (Y in W·m⁻²·sr⁻¹) to tone-mapper input at 0 EV.
pub const EXPOSURE_SCALE: f64 = 1.0 / 20.0;

/// The default range of luminance maps, log10 cd/m²: 10⁻² (deep twilight) to 10⁵ (a bright
/// sky near the sun).
pub const LUMINANCE_LOG10_RANGE: [f64; 2] = [-2.0, 5.0];

/// One linear sRGB radiance → display sRGB in [0, 1].
pub fn display(rgb: [f64; 3], exposure_ev: f64, tone_map: ToneMap) -> [f64; 3] {
    let k = EXPOSURE_SCALE * exposure_ev.exp2();
    rgb.map(|c| {
        let x = (c * k).max(0.0);
        let mapped = match tone_map {
            ToneMap::Exponential => 1.0 - (-x).exp(),
            ToneMap::Filmic => (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14),
            ToneMap::Linear => x,
        };
        srgb_encode(mapped)
    })
}

/// 8-bit display value.
pub fn to_u8(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn black_stays_black_and_bright_saturates() {
        for t in [ToneMap::Exponential, ToneMap::Filmic, ToneMap::Linear] {
            assert_eq!(display([0.0; 3], 0.0, t), [0.0; 3]);
            assert!(display([1e6; 3], 0.0, t)[0] > 0.99);
        }
    }

    #[test]
    fn one_stop_brighter_is_brighter() {
        let a = display([5.0, 5.0, 5.0], 0.0, ToneMap::Exponential)[0];
        let b = display([5.0, 5.0, 5.0], 1.0, ToneMap::Exponential)[0];
        assert!(b > a);
    }
}
