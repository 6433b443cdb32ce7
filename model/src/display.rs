//! Display transform: linear sRGB radiance → exposure → tone map → sRGB-encoded 8-bit, with
//! dithering so that smooth skies do not band.
//!
//! Exposure 0 EV maps a luminance of 20 W·m⁻²·sr⁻¹ in Y (≈ 14 000 cd/m², a bright daylight sky)
//! to 1 before tone mapping; +1 EV doubles it. The curves: the papers' exponential 1 − e^(−x)
//! (Bruneton 2008, Hillaire 2020), Narkowicz's (2015) fit of the ACES film curve, Sobotka's
//! AgX in its common sixth-order polynomial fit, Khronos PBR Neutral (2024), and a plain clip.
//! Optional veiling glare around the sun ([`glare`]): the Stiles–Holladay law of disability
//! glare as the CIE gives it (CIE 146:2002), the radiance a bright source adds by scattering in
//! the eye, 10·E/θ² (θ in degrees from the source, E its irradiance at the eye).
//! `shaders/views/tone.wgsl`, which the sky pass and the display pass apply, is the f32 twin of
//! this module.

use crate::colour::srgb_encode;
use crate::scene::ToneMap;

/// Scale from linear radiance (Y in W·m⁻²·sr⁻¹) to tone-mapper input at 0 EV.
pub const EXPOSURE_SCALE: f64 = 1.0 / 20.0;

/// The Stiles–Holladay constant of veiling glare, sr⁻¹·deg²: L = GLARE_K·E/θ².
pub const GLARE_K: f64 = 10.0;
/// Angle from the sun's centre below which the glare stays at its value there, degrees: the
/// law is stated from 1° outwards (inside, the sun's own disk outshines it 1 500-fold).
pub const GLARE_MIN_ANGLE_DEG: f64 = 1.0;

/// The veiling glare radiance a sun of irradiance `sun_irradiance` (linear sRGB, W·m⁻², as it
/// reaches the eye) adds to a pixel whose direction makes cosine `cos_theta` with the sun's.
pub fn glare(cos_theta: f64, sun_irradiance: [f64; 3]) -> [f64; 3] {
    let theta_deg = cos_theta
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
        .max(GLARE_MIN_ANGLE_DEG);
    sun_irradiance.map(|e| GLARE_K * e / (theta_deg * theta_deg))
}

/// The sun's irradiance reaching a viewer at altitude `h` (m) with the sun at zenith cosine
/// `mu_s`, in linear sRGB (W·m⁻²): the optics' solar irradiance through the medium towards the
/// sun (a 64-interval midpoint march, the sun's visible fraction above the horizon included),
/// the glare's source.
pub fn sun_irradiance_rgb(p: &crate::methods::shared::Params, h: f64, mu_s: f64) -> [f64; 3] {
    use crate::methods::shared::single_scattering_sky::{Rule, SunRoute, Way};
    let mut route = SunRoute::new(p, Way::March(Rule::Midpoint));
    route.intervals = 64;
    let colours: Vec<_> = p.batches.iter().map(|b| b.colour.clone()).collect();
    let through: Vec<_> = (0..p.batches.len())
        .map(|layer| {
            let t = route.seen_from(p, layer, h, mu_s);
            p.batches[layer].solar_irradiance * t
        })
        .collect();
    crate::wavelengths::to_linear_srgb(&colours, &through)
}

/// The default range of luminance maps, log10 cd/m²: 10⁻² (deep twilight) to 10⁵ (a bright
/// sky near the sun).
pub const LUMINANCE_LOG10_RANGE: [f64; 2] = [-2.0, 5.0];

/// AgX: linear sRGB into its working space (rows), and back out.
pub const AGX_INSET: [[f64; 3]; 3] = [
    [0.842479062253094, 0.0784335999999992, 0.0792237451477643],
    [0.0423282422610123, 0.878468636469772, 0.0791661274605434],
    [0.0423756549057051, 0.0784336, 0.879142973793104],
];
pub const AGX_OUTSET: [[f64; 3]; 3] = [
    [1.19687900512017, -0.0980208811401368, -0.0990297440797205],
    [-0.0528968517574562, 1.15190312990417, -0.0989611768448433],
    [-0.0529716355144438, -0.0980434501171241, 1.15107367264116],
];
/// AgX's log2 range (stops around 0.18) mapped onto the sigmoid's [0, 1].
pub const AGX_LOG2_RANGE: [f64; 2] = [-12.47393, 4.026069];
/// AgX's sigmoid, a polynomial in x from the sixth power down to the constant.
pub const AGX_SIGMOID: [f64; 7] = [15.5, -40.14, 31.96, -6.868, 0.4298, 0.1191, -0.00232];
/// Khronos PBR Neutral: where compression starts and how much highlights desaturate.
pub const NEUTRAL_START: f64 = 0.76;
pub const NEUTRAL_DESATURATION: f64 = 0.15;

fn times(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
}

/// AgX: linear in, linear out (the sigmoid's output is display-encoded with a 2.2 power).
pub fn agx(rgb: [f64; 3]) -> [f64; 3] {
    let [lo, hi] = AGX_LOG2_RANGE;
    let encoded = times(&AGX_INSET, rgb).map(|c| {
        let x = (c.max(1e-10).log2().clamp(lo, hi) - lo) / (hi - lo);
        AGX_SIGMOID.iter().fold(0.0, |acc, k| acc * x + k)
    });
    times(&AGX_OUTSET, encoded).map(|c| c.max(0.0).powf(2.2))
}

/// Khronos PBR Neutral: an offset that keeps blacks black, identity up to `NEUTRAL_START`,
/// then the peak channel compressed towards 1 and the colour mixed towards white.
pub fn pbr_neutral(rgb: [f64; 3]) -> [f64; 3] {
    let x = rgb[0].min(rgb[1]).min(rgb[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = rgb.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    if peak < NEUTRAL_START {
        return c;
    }
    let d = 1.0 - NEUTRAL_START;
    let new_peak = 1.0 - d * d / (peak + d - NEUTRAL_START);
    let g = 1.0 - 1.0 / (NEUTRAL_DESATURATION * (peak - new_peak) + 1.0);
    c.map(|v| {
        let scaled = v * new_peak / peak;
        scaled + (new_peak - scaled) * g
    })
}

/// The tone map of exposed linear sRGB (≥ 0), before the sRGB encoding.
pub fn tone_map(x: [f64; 3], t: ToneMap) -> [f64; 3] {
    match t {
        ToneMap::Exponential => x.map(|c| 1.0 - (-c).exp()),
        ToneMap::Filmic => x.map(|c| (c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14)),
        ToneMap::AgX => agx(x),
        ToneMap::PbrNeutral => pbr_neutral(x),
        ToneMap::Linear => x,
    }
}

/// One linear sRGB radiance → display sRGB in [0, 1].
pub fn display(rgb: [f64; 3], exposure_ev: f64, tone_map_kind: ToneMap) -> [f64; 3] {
    let k = EXPOSURE_SCALE * exposure_ev.exp2();
    tone_map(rgb.map(|c| (c * k).max(0.0)), tone_map_kind).map(srgb_encode)
}

/// `display` of linear sRGB balanced first by `balance` (`white_balance::matrix`).
pub fn display_balanced(
    rgb: [f64; 3],
    balance: &[[f64; 3]; 3],
    exposure_ev: f64,
    tone_map_kind: ToneMap,
) -> [f64; 3] {
    display(
        crate::white_balance::apply(balance, rgb),
        exposure_ev,
        tone_map_kind,
    )
}

/// 8-bit display value.
pub fn to_u8(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// A 32-bit integer hash (Wellons' "lowbias32"), the same in WGSL.
pub fn hash32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// The dither added to pixel (x, y) before quantising to 8 bits, in units of one step (1/255):
/// triangular noise in (−1, 1), the sum of two uniform values from a hash of the pixel, so its
/// error neither depends on the signal nor shows a pattern. Exact in f32 (24-bit values).
pub fn dither(x: u32, y: u32) -> f64 {
    let a = hash32(x ^ hash32(y));
    let b = hash32(a);
    let unit = |h: u32| f64::from(h >> 8) / f64::from(1u32 << 24);
    unit(a) + unit(b) - 1.0
}

/// 8-bit display value of pixel (x, y), dithered.
pub fn to_u8_dithered(v: f64, x: u32, y: u32) -> u8 {
    to_u8(v + dither(x, y) / 255.0)
}

/// Luminance histogram range, log10 cd/m² (a moonless night to the sun's disk), and bins.
pub const HISTOGRAM_LOG10_RANGE: [f64; 2] = [-4.0, 8.0];
pub const HISTOGRAM_BINS: usize = 96;

/// The mid-grey an automatic exposure puts the view's log-average luminance at.
pub const METER_MID_GREY: f64 = 0.18;

/// The bin of a luminance (cd/m²); below and above the range count in the end bins.
pub fn histogram_bin(luminance_cd_m2: f64) -> usize {
    let [lo, hi] = HISTOGRAM_LOG10_RANGE;
    let t = (luminance_cd_m2.max(1e-30).log10() - lo) / (hi - lo);
    ((t * HISTOGRAM_BINS as f64).floor().max(0.0) as usize).min(HISTOGRAM_BINS - 1)
}

/// How many pixels of a view fall in each luminance bin (`HISTOGRAM_LOG10_RANGE`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Histogram {
    pub counts: Vec<u32>,
}

impl Histogram {
    /// The histogram of luminances (cd/m²).
    pub fn of(luminances: impl IntoIterator<Item = f64>) -> Histogram {
        let mut counts = vec![0; HISTOGRAM_BINS];
        for l in luminances {
            counts[histogram_bin(l)] += 1;
        }
        Histogram { counts }
    }

    /// log10 cd/m² at the centre of bin `i`.
    pub fn bin_centre_log10(i: usize) -> f64 {
        let [lo, hi] = HISTOGRAM_LOG10_RANGE;
        lo + (i as f64 + 0.5) * (hi - lo) / HISTOGRAM_BINS as f64
    }

    /// The geometric mean of the luminances (cd/m²) from the bins' centres (within half a bin,
    /// 0.06 decades), leaving out the first bin (below 10⁻⁴ cd/m²: black space, not a sky to
    /// expose for); None when no pixel is lit.
    pub fn log_average_cd_m2(&self) -> Option<f64> {
        let lit = || self.counts.iter().enumerate().skip(1);
        let n: u64 = lit().map(|(_, &c)| u64::from(c)).sum();
        (n > 0).then(|| {
            let sum: f64 = lit()
                .map(|(i, &c)| f64::from(c) * Self::bin_centre_log10(i))
                .sum();
            10f64.powf(sum / n as f64)
        })
    }
}

/// The exposure value at ISO 100 a reflected-light meter gives for a scene of average
/// luminance `l_cd_m2` (K = 12.5 cd·s/m²).
pub fn ev100(l_cd_m2: f64) -> f64 {
    (l_cd_m2 * 100.0 / 12.5).log2()
}

/// The exposure (EV, in `display`'s sense) that shows a view of log-average luminance
/// `l_cd_m2` at mid-grey, plus `compensation_ev`, within the exposure range (−20 to 20).
pub fn metered_exposure_ev(l_cd_m2: f64, compensation_ev: f64) -> f64 {
    let y = l_cd_m2.max(1e-12) / crate::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
    ((METER_MID_GREY / (EXPOSURE_SCALE * y)).log2() + compensation_ev).clamp(-20.0, 20.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The glare falls as the square of the angle from the sun (a quarter at twice the angle),
    /// stays at 10·E inside a degree, and is ten times E per square degree at 1°.
    #[test]
    fn glare_follows_the_stiles_holladay_law() {
        let e = [2.0, 4.0, 8.0];
        let at = |deg: f64| glare(deg.to_radians().cos(), e);
        assert!((at(1.0)[1] - 40.0).abs() < 1e-9);
        for deg in [2.0, 5.0, 15.0] {
            for c in 0..3 {
                assert!((at(deg)[c] / at(2.0 * deg)[c] - 4.0).abs() < 1e-9);
            }
        }
        assert_eq!(at(0.2), at(1.0));
        assert_eq!(glare(1.0, [0.0; 3]), [0.0; 3]);
    }

    /// The glare's source: the sun overhead on the ground is the top-of-atmosphere sun dimmed
    /// by the vertical optical depth; below the horizon there is none.
    #[test]
    fn the_sun_reaching_the_eye_is_dimmed_by_the_air_and_gone_below_the_horizon() {
        let p = crate::methods::shared::optics::tests::params();
        let noon = sun_irradiance_rgb(&p, 0.0, 1.0);
        let space = sun_irradiance_rgb(&p, 200_000.0, 1.0);
        let low = sun_irradiance_rgb(&p, 0.0, 5f64.to_radians().sin());
        for c in 0..3 {
            assert!(
                space[c] > noon[c] && noon[c] > 0.5 * space[c],
                "{noon:?} {space:?}"
            );
            assert!(low[c] < noon[c], "{low:?}");
        }
        // Redder at a low sun: blue loses more than red.
        assert!(low[2] / noon[2] < low[0] / noon[0], "{low:?} {noon:?}");
        assert_eq!(sun_irradiance_rgb(&p, 0.0, -0.2), [0.0; 3]);
    }

    #[test]
    fn black_stays_black_and_bright_saturates() {
        for t in ToneMap::ALL {
            let black = display([0.0; 3], 0.0, t);
            assert!(black.iter().all(|&c| c < 0.01), "{t:?}: {black:?}");
            assert!(display([1e6; 3], 0.0, t)[0] > 0.99, "{t:?}");
        }
    }

    #[test]
    fn one_stop_brighter_is_brighter() {
        for t in ToneMap::ALL {
            let a = display([5.0, 5.0, 5.0], 0.0, t)[0];
            let b = display([5.0, 5.0, 5.0], 1.0, t)[0];
            assert!(b > a, "{t:?}");
        }
    }

    /// Each curve against values worked out by hand from its definition.
    #[test]
    fn each_tone_map_gives_its_reference_values() {
        let grey = |t, x: f64| tone_map([x; 3], t)[0];
        // 1 − e^(−1).
        assert!((grey(ToneMap::Exponential, 1.0) - 0.632_121).abs() < 1e-6);
        // (2.51 + 0.03) / (2.43 + 0.59 + 0.14).
        assert!((grey(ToneMap::Filmic, 1.0) - 2.54 / 3.16).abs() < 1e-12);
        // Mid grey: log2(0.18) sits at 0.60606 of AgX's range, the sigmoid gives 0.49681,
        // and 0.49681^2.2 = 0.21457 (the matrices' rows sum to 1 within 2e-4).
        assert!(
            (grey(ToneMap::AgX, 0.18) - 0.21457).abs() < 1e-3,
            "{}",
            grey(ToneMap::AgX, 0.18)
        );
        // Neutral: 0.5 − 0.04 below the knee; 1 → 0.96 compressed to 1 − 0.24²/0.44; a
        // dark 0.04 less its offset 0.04 − 6.25·0.04².
        assert!((grey(ToneMap::PbrNeutral, 0.5) - 0.46).abs() < 1e-12);
        assert!((grey(ToneMap::PbrNeutral, 1.0) - (1.0 - 0.0576 / 0.44)).abs() < 1e-12);
        assert!((grey(ToneMap::PbrNeutral, 0.04) - 0.01).abs() < 1e-12);
        assert_eq!(grey(ToneMap::Linear, 0.3), 0.3);
        // Neutral keeps a colour below the knee as it is, bar the offset; AgX bleaches a
        // bright saturated red towards white where the per-channel curves keep it pure.
        let red = [0.6, 0.2, 0.1];
        let n = tone_map(red, ToneMap::PbrNeutral);
        assert!((n[0] - 0.56).abs() < 1e-12 && (n[2] - 0.06).abs() < 1e-12);
        let bright = [40.0, 0.5, 0.2];
        let (a, e) = (
            tone_map(bright, ToneMap::AgX),
            tone_map(bright, ToneMap::Exponential),
        );
        assert!(a[2] / a[0] > 2.0 * e[2] / e[0], "{a:?} {e:?}");
    }

    /// A view of one luminance metered to mid-grey: exposed by the metered EV it comes out at
    /// 0.18 before the tone map (2^c · 0.18 with compensation c); the histogram's average is
    /// within half a bin; a sunlit scene averaging 4 000 cd/m² meters EV100 15 (the "sunny 16"
    /// rule: f/16 at 1/100 s and ISO 100).
    #[test]
    fn metering_puts_the_log_average_at_mid_grey() {
        for l in [0.01, 3.0, 4000.0, 2e5] {
            let h = Histogram::of(std::iter::repeat_n(l, 50).chain([l * 2.0, l / 2.0]));
            let avg = h.log_average_cd_m2().expect("pixels");
            assert!((avg.log10() - l.log10()).abs() < 0.07, "{l}: {avg}");
            for c in [0.0, -1.5] {
                let ev = metered_exposure_ev(l, c);
                let y = l / crate::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
                let exposed = EXPOSURE_SCALE * ev.exp2() * y;
                assert!(
                    (exposed - 0.18 * c.exp2()).abs() < 1e-9,
                    "{l} {c}: {exposed}"
                );
            }
        }
        assert!((ev100(4_000.0) - 15.0).abs() < 0.05);
        assert_eq!(Histogram::of([]).log_average_cd_m2(), None);
        let h = Histogram::of([1e-9, 1e12]);
        assert_eq!((h.counts[0], h.counts[HISTOGRAM_BINS - 1]), (1, 1));
        // Black space around a lit planet does not count.
        let planet = Histogram::of([0.0; 1000].into_iter().chain([50.0; 10]));
        let avg = planet.log_average_cd_m2().expect("lit");
        assert!((avg.log10() - 50f64.log10()).abs() < 0.07, "{avg}");
    }

    /// A smooth ramp quantised with dithering has row means within a tenth of a step of the
    /// exact ones; without, they are off by up to half a step in bands.
    #[test]
    fn dithering_removes_banding_from_a_smooth_ramp() {
        let (w, h) = (256u32, 64u32);
        let exact = |y: u32| 0.4 + 0.02 * f64::from(y) / f64::from(h);
        let worst = |quantise: &dyn Fn(f64, u32, u32) -> u8| {
            (0..h)
                .map(|y| {
                    let mean = (0..w)
                        .map(|x| f64::from(quantise(exact(y), x, y)))
                        .sum::<f64>()
                        / f64::from(w);
                    (mean - 255.0 * exact(y)).abs()
                })
                .fold(0.0, f64::max)
        };
        let with = worst(&to_u8_dithered);
        let without = worst(&|v, _, _| to_u8(v));
        assert!(with < 0.1 && without > 0.4, "{with} {without}");
        let noise: Vec<f64> = (0..10_000).map(|i| dither(i % 100, i / 100)).collect();
        let mean = noise.iter().sum::<f64>() / noise.len() as f64;
        assert!(
            mean.abs() < 0.02 && noise.iter().all(|n| n.abs() <= 1.0),
            "{mean}"
        );
    }
}
