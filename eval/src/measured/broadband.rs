//! Broadband clear-sky irradiance on a horizontal surface by the model of R. E. Bird and
//! R. L. Hulstrom (1981), "A Simplified Clear Sky Model for Direct and Diffuse Insolation on
//! Horizontal Surfaces", SERI/TR-642-761: closed-form broadband transmittances of Rayleigh
//! scattering, ozone, the uniformly mixed gases, water vapour and the aerosol.
//!
//! A pyranometer sees 300–2800 nm, where water vapour and the mixed gases absorb; Atmoscope's
//! physics stops at 830 nm. This model is what turns a pyranometer's reading into an aerosol
//! optical depth ([`super::retrieve`]) and what carries each model's sky from its band to the
//! pyranometer's ([`super::run::evaluate`]).

/// The broadband solar constant the model was fitted with, W·m⁻².
pub const SOLAR_CONSTANT_W_M2: f64 = 1367.0;
/// Share of the aerosol's scattering that goes forward (Bird & Hulstrom's Ba).
const FORWARD_SCATTERING: f64 = 0.84;
/// Aerosol absorption coefficient K1 of the model.
const AEROSOL_ABSORPTION: f64 = 0.1;

/// What the model needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs {
    /// Sun zenith angle, degrees (0–89).
    pub sun_zenith_deg: f64,
    /// Surface pressure over 1013.25 hPa (0.5–1.1).
    pub pressure_ratio: f64,
    /// Total ozone column, cm at STP (= DU/1000).
    pub ozone_cm: f64,
    /// Precipitable water, cm.
    pub water_cm: f64,
    /// Aerosol optical depth at 380 and 500 nm.
    pub aod380: f64,
    pub aod500: f64,
    /// Broadband ground albedo (0–1).
    pub albedo: f64,
    /// Sunlight at the date's Earth–Sun distance over that at 1 AU.
    pub sunlight_scale: f64,
}

/// Precipitable water assumed where no measurement gives it, cm: a mid-latitude spring day.
/// The global irradiance changes by about 1 % per cm.
pub const DEFAULT_WATER_CM: f64 = 1.5;
/// Broadband albedo of grass.
pub const GRASS_ALBEDO: f64 = 0.2;

/// Direct and diffuse horizontal irradiance, W·m⁻²; None with the sun lower than 89° zenith.
pub fn irradiance(i: &Inputs) -> Option<(f64, f64)> {
    if !(0.0..89.0).contains(&i.sun_zenith_deg) {
        return None;
    }
    let z = i.sun_zenith_deg;
    let cos_z = z.to_radians().cos();
    // Relative air mass (Kasten 1966), and at the site's pressure.
    let m = 1.0 / (cos_z + 0.15 * (93.885 - z).powf(-1.253));
    let mp = m * i.pressure_ratio;
    let t_rayleigh = (-0.0903 * mp.powf(0.84) * (1.0 + mp - mp.powf(1.01))).exp();
    let uo = i.ozone_cm * m;
    let t_ozone = 1.0
        - 0.1611 * uo * (1.0 + 139.48 * uo).powf(-0.3035)
        - 0.002715 * uo / (1.0 + 0.044 * uo + 0.0003 * uo * uo);
    let t_gases = (-0.0127 * mp.powf(0.26)).exp();
    let uw = i.water_cm * m;
    let t_water = 1.0 - 2.4959 * uw / ((1.0 + 79.034 * uw).powf(0.6828) + 6.385 * uw);
    let tau = 0.2758 * i.aod380 + 0.35 * i.aod500;
    let t_aerosol = (-tau.powf(0.873) * (1.0 + tau - tau.powf(0.7088)) * m.powf(0.9108)).exp();
    let t_absorbed = 1.0 - AEROSOL_ABSORPTION * (1.0 - m + m.powf(1.06)) * (1.0 - t_aerosol);
    let t_scattered = t_aerosol / t_absorbed;
    let e0 = SOLAR_CONSTANT_W_M2 * i.sunlight_scale;
    let direct = 0.9662 * e0 * cos_z * t_rayleigh * t_ozone * t_gases * t_water * t_aerosol;
    let sky = 0.79
        * e0
        * cos_z
        * t_ozone
        * t_gases
        * t_water
        * t_absorbed
        * (0.5 * (1.0 - t_rayleigh) + FORWARD_SCATTERING * (1.0 - t_scattered))
        / (1.0 - m + m.powf(1.02));
    let sky_albedo = 0.0685 + (1.0 - FORWARD_SCATTERING) * (1.0 - t_scattered);
    let global = (direct + sky) / (1.0 - i.albedo * sky_albedo);
    Some((direct, global - direct))
}

/// Global horizontal irradiance, W·m⁻².
pub fn global(i: &Inputs) -> Option<f64> {
    irradiance(i).map(|(d, s)| d + s)
}

/// The aerosol optical depth at 550 nm (0–3) whose global irradiance is `measured_w_m2`, with
/// the Ångström exponent `angstrom`; the bounds when the measurement lies beyond them. By
/// bisection: the global irradiance falls as the optical depth grows.
pub fn aod550_from_global(measured_w_m2: f64, inputs: &Inputs, angstrom: f64) -> Option<f64> {
    let at = |aod550: f64| {
        global(&Inputs {
            aod380: aod550 * (380.0_f64 / 550.0).powf(-angstrom),
            aod500: aod550 * (500.0_f64 / 550.0).powf(-angstrom),
            ..*inputs
        })
    };
    let (mut lo, mut hi) = (0.0, 3.0);
    if measured_w_m2 >= at(lo)? {
        return Some(lo);
    }
    if measured_w_m2 <= at(hi)? {
        return Some(hi);
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if at(mid)? > measured_w_m2 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noon() -> Inputs {
        Inputs {
            sun_zenith_deg: 30.0,
            pressure_ratio: 1.0,
            ozone_cm: 0.3,
            water_cm: 1.5,
            aod380: 0.15,
            aod500: 0.1,
            albedo: 0.2,
            sunlight_scale: 1.0,
        }
    }

    /// Clear-sky global irradiance at 30° zenith is 850–950 W/m² the world over, with a
    /// diffuse share of 8–15 %; and the model gives what pvlib's own implementation of Bird &
    /// Hulstrom (`pvlib.clearsky.bird` 0.16.1, through `tests/scripts/bird_hulstrom_pvlib.py`)
    /// gives at that noon and in a hazy afternoon, within 0.5 W/m².
    #[test]
    fn a_clear_noon_gives_the_irradiance_pyranometers_read() {
        let (direct, diffuse) = irradiance(&noon()).expect("sun up");
        let g = direct + diffuse;
        assert!((850.0..950.0).contains(&g), "{g}");
        assert!((0.08..0.15).contains(&(diffuse / g)), "{}", diffuse / g);
        let hazy = Inputs {
            sun_zenith_deg: 60.0,
            pressure_ratio: 0.9,
            ozone_cm: 0.35,
            water_cm: 3.0,
            aod380: 0.45,
            aod500: 0.30,
            albedo: 0.3,
            sunlight_scale: 0.97,
        };
        for (name, inputs, pvlib_global, pvlib_direct) in [
            ("noon", noon(), 917.21, 799.78),
            ("hazy", hazy, 446.44, 288.42),
        ] {
            let (direct, diffuse) = irradiance(&inputs).expect("sun up");
            assert!(
                (direct + diffuse - pvlib_global).abs() < 0.5
                    && (direct - pvlib_direct).abs() < 0.5,
                "{name}: global {:.2}, direct {direct:.2}; pvlib {pvlib_global}, {pvlib_direct}",
                direct + diffuse
            );
        }
    }

    #[test]
    fn the_optical_depth_of_an_irradiance_is_found_again() {
        for aod in [0.0, 0.05, 0.2, 0.6] {
            let alpha = 1.2;
            let inputs = Inputs {
                aod380: aod * (380.0_f64 / 550.0).powf(-alpha),
                aod500: aod * (500.0_f64 / 550.0).powf(-alpha),
                ..noon()
            };
            let g = global(&inputs).expect("sun up");
            let got = aod550_from_global(g, &noon(), alpha).expect("sun up");
            assert!((got - aod).abs() < 1e-9, "{aod}: {got}");
        }
    }

    #[test]
    fn more_aerosol_and_more_water_darken_the_ground() {
        let g = |i: Inputs| global(&i).expect("sun up");
        assert!(
            g(Inputs {
                aod500: 0.3,
                aod380: 0.4,
                ..noon()
            }) < g(noon())
        );
        assert!(
            g(Inputs {
                water_cm: 3.0,
                ..noon()
            }) < g(noon())
        );
        assert_eq!(
            irradiance(&Inputs {
                sun_zenith_deg: 95.0,
                ..noon()
            }),
            None
        );
    }
}
