//! The scene's atmosphere in the terms real-time engines take: Hillaire's (2020)
//! parameterisation, which bevy's `Atmosphere` and Unreal's SkyAtmosphere share. Three colour
//! channels at 680, 550 and 440 nm; air and aerosol each one exponential; ozone one tent; a
//! Henyey–Greenstein aerosol; a ground albedo per channel.
//!
//! [`EngineAtmosphere::fit`] keeps each constituent's vertical optical depth at every channel,
//! from the moments of the profile the real-time models read (`shared::exponential::moments`):
//! - air: its ground density, and the scale height that holds its column (column / ground
//!   density);
//! - aerosol: its mean height (the centroid of its profile, which is the scale height of an
//!   exponential) and the extinction at the ground that holds its optical depth there, as
//!   the analytic models' `ExponentialMedium` fits it;
//! - ozone: a symmetric tent at the profile's centroid with the profile's variance (a tent of
//!   half-width w has variance w²/6), its tip holding the column.
//!
//! [`EngineAtmosphere::params`] turns it back into the optics the real-time models draw, so that
//! what the parameterisation loses can be measured against the scene's full physics.

use crate::atmosphere::Atmosphere;
use crate::methods::shared::exponential::moments;
use crate::methods::shared::optics::Params;
use crate::scene::AerosolPhase;
use crate::scene::{Quality, WavelengthSet};
use crate::wavelengths::RGB3_NM;

/// The channels' wavelengths, nm: red, green, blue (Hillaire's).
pub const CHANNELS_NM: [f64; 3] = RGB3_NM;

/// Steps of the tent's integral over height.
const STEPS: usize = 4000;

/// An atmosphere of exponentials and a tent, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineAtmosphere {
    /// Planet radius, m.
    pub bottom_radius_m: f64,
    /// Radius of the top of the atmosphere, m.
    pub top_radius_m: f64,
    /// Rayleigh scattering at the ground per channel, m⁻¹.
    pub rayleigh_scattering_per_m: [f64; 3],
    /// Height over which the air's density falls by 1/e, m.
    pub rayleigh_scale_height_m: f64,
    /// Aerosol scattering at the ground per channel, m⁻¹.
    pub mie_scattering_per_m: [f64; 3],
    /// Aerosol absorption at the ground per channel, m⁻¹.
    pub mie_absorption_per_m: [f64; 3],
    /// Height over which the aerosol's density falls by 1/e, m.
    pub mie_scale_height_m: f64,
    /// Henyey–Greenstein asymmetry of the aerosol (−1–1).
    pub mie_asymmetry: f64,
    /// Ozone absorption at the tent's tip per channel, m⁻¹.
    pub ozone_absorption_per_m: [f64; 3],
    /// Height of the tent's tip, m.
    pub ozone_tip_altitude_m: f64,
    /// Half the tent's base: the density falls linearly from the tip to zero over this, m.
    pub ozone_half_width_m: f64,
    /// Lambertian ground albedo per channel (0–1).
    pub ground_albedo: [f64; 3],
}

impl EngineAtmosphere {
    /// Hillaire's (2020) Earth, which bevy's `Atmosphere::EARTH` and Unreal's defaults take.
    pub const HILLAIRE_EARTH: EngineAtmosphere = EngineAtmosphere {
        bottom_radius_m: 6_360_000.0,
        top_radius_m: 6_460_000.0,
        rayleigh_scattering_per_m: [5.802e-6, 13.558e-6, 33.1e-6],
        rayleigh_scale_height_m: 8000.0,
        mie_scattering_per_m: [3.996e-6; 3],
        mie_absorption_per_m: [0.444e-6; 3],
        mie_scale_height_m: 1200.0,
        mie_asymmetry: 0.8,
        ozone_absorption_per_m: [0.65e-6, 1.881e-6, 0.085e-6],
        ozone_tip_altitude_m: 25_000.0,
        ozone_half_width_m: 15_000.0,
        ground_albedo: [0.3; 3],
    };

    /// The exponentials and tent that keep `atm`'s vertical optical depths (module docs),
    /// from its optics at the RGB3 channels (whose lanes average the sunlight and the ground's
    /// albedo over their bands).
    pub fn fit(atm: &Atmosphere) -> EngineAtmosphere {
        let p = Params::new(atm, WavelengthSet::Rgb3, Quality::default());
        let b = &p.batches[0];
        // Column and centroid of air (relative density, 1 at its densest, the ground), ozone
        // (relative to its peak) and aerosol (m⁻¹ per unit of optical depth).
        let (air, _, _) = moments(&p, 0);
        let air_ground = p.profile[0][0];
        let rayleigh_scale_height_m = if air > 0.0 && air_ground > 0.0 {
            air / air_ground
        } else {
            8000.0
        };
        let (aerosol, aerosol_centroid, _) = moments(&p, 2);
        let mie_scale_height_m = if aerosol > 0.0 {
            aerosol_centroid.max(1.0)
        } else {
            1200.0
        };
        let (ozone, ozone_centroid, ozone_spread) = moments(&p, 1);
        let (ozone_tip_altitude_m, ozone_half_width_m) = if ozone > 0.0 {
            // A tent of half-width w has variance w²/6; it stays above the ground.
            let w = (6.0f64.sqrt() * ozone_spread).clamp(1.0, ozone_centroid.max(1.0));
            (ozone_centroid, w)
        } else {
            (25_000.0, 15_000.0)
        };
        // Lanes 0, 1, 2 are the channels (`wavelengths::batches(Rgb3)`).
        let per_channel = |f: &dyn Fn(usize) -> f64| [f(0), f(1), f(2)];
        let mie = aerosol / mie_scale_height_m;
        EngineAtmosphere {
            bottom_radius_m: p.bottom_radius_m,
            top_radius_m: p.top_radius_m,
            rayleigh_scattering_per_m: per_channel(&|c| b.rayleigh_scattering[c] * air_ground),
            rayleigh_scale_height_m,
            mie_scattering_per_m: per_channel(&|c| b.aerosol_scattering[c] * mie),
            mie_absorption_per_m: per_channel(&|c| b.aerosol_absorption[c] * mie),
            mie_scale_height_m,
            mie_asymmetry: b.aerosol_g[1],
            ozone_absorption_per_m: per_channel(&|c| {
                b.ozone_absorption[c] * ozone / ozone_half_width_m
            }),
            ozone_tip_altitude_m,
            ozone_half_width_m,
            ground_albedo: per_channel(&|c| b.ground_albedo[c]),
        }
    }

    /// Why this atmosphere cannot be drawn (a snippet read back may say anything): radii,
    /// heights and widths finite and positive, the top above the ground, coefficients and
    /// albedos finite and not negative, the asymmetry within −1–1.
    pub fn check(&self) -> Result<(), String> {
        let positive = [
            ("bottom radius", self.bottom_radius_m),
            ("Rayleigh scale height", self.rayleigh_scale_height_m),
            ("Mie scale height", self.mie_scale_height_m),
            ("ozone half-width", self.ozone_half_width_m),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} {v} m: must be positive"));
            }
        }
        if !(self.top_radius_m.is_finite() && self.top_radius_m > self.bottom_radius_m) {
            return Err(format!(
                "top radius {} m: must lie above the bottom radius {} m",
                self.top_radius_m, self.bottom_radius_m
            ));
        }
        let coefficients = [
            ("Rayleigh scattering", self.rayleigh_scattering_per_m),
            ("Mie scattering", self.mie_scattering_per_m),
            ("Mie absorption", self.mie_absorption_per_m),
            ("ozone absorption", self.ozone_absorption_per_m),
            ("ground albedo", self.ground_albedo),
        ];
        for (name, c) in coefficients {
            if c.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(format!("{name} {c:?}: must be finite and not negative"));
            }
        }
        if !(-1.0..=1.0).contains(&self.mie_asymmetry) || !self.ozone_tip_altitude_m.is_finite() {
            return Err(format!(
                "Mie asymmetry {} (−1–1) or ozone tip {} m out of range",
                self.mie_asymmetry, self.ozone_tip_altitude_m
            ));
        }
        Ok(())
    }

    /// The ozone tent's density relative to its tip at height `h_m` (0–1).
    pub fn ozone_tent(&self, h_m: f64) -> f64 {
        (1.0 - (h_m - self.ozone_tip_altitude_m).abs() / self.ozone_half_width_m).max(0.0)
    }

    /// Vertical optical depth of each constituent (Rayleigh, aerosol, ozone) per channel, from
    /// the ground to the top.
    pub fn vertical_optical_depths(&self) -> [[f64; 3]; 3] {
        let top = self.top_radius_m - self.bottom_radius_m;
        let column = |h: f64| h * (1.0 - (-top / h).exp());
        let (r, m) = (
            column(self.rayleigh_scale_height_m),
            column(self.mie_scale_height_m),
        );
        let dh = top / STEPS as f64;
        let tent: f64 = (0..STEPS)
            .map(|i| self.ozone_tent((i as f64 + 0.5) * dh) * dh)
            .sum();
        let each = |f: &dyn Fn(usize) -> f64| [f(0), f(1), f(2)];
        [
            each(&|i| self.rayleigh_scattering_per_m[i] * r),
            each(&|i| (self.mie_scattering_per_m[i] + self.mie_absorption_per_m[i]) * m),
            each(&|i| self.ozone_absorption_per_m[i] * tent),
        ]
    }

    /// The optics of this atmosphere for the real-time models: `base` (the scene's optics at
    /// the RGB3 channels, whose sunlight, colour matrix and sampling it keeps) with its
    /// geometry, density profile and coefficients replaced. Air is drawn without
    /// depolarisation and the aerosol with Henyey–Greenstein's phase, as the engines do.
    pub fn params(&self, base: &Params) -> Params {
        let mut p = base.clone();
        p.bottom_radius_m = self.bottom_radius_m;
        p.top_radius_m = self.top_radius_m;
        p.aerosol_phase = AerosolPhase::HenyeyGreenstein;
        p.mie_phase = None;
        let top = self.top_radius_m - self.bottom_radius_m;
        let n = p.profile.len();
        for (i, row) in p.profile.iter_mut().enumerate() {
            // The profile's spacing (`optics::PROFILE_SAMPLES`): h = H·x², dense near the ground.
            let h = top * (i as f64 / (n - 1) as f64).powi(2);
            *row = [
                (-h / self.rayleigh_scale_height_m).exp(),
                self.ozone_tent(h),
                (-h / self.mie_scale_height_m).exp(),
                0.0,
            ];
        }
        for b in &mut p.batches {
            for lane in 0..b.colour.wavelengths_nm.len() {
                // Each lane takes the channel nearest its wavelength (RGB3: 680, 550, 440, 550).
                let w = b.colour.wavelengths_nm[lane];
                let c = (0..3)
                    .min_by(|&x, &y| {
                        (CHANNELS_NM[x] - w)
                            .abs()
                            .total_cmp(&(CHANNELS_NM[y] - w).abs())
                    })
                    .unwrap_or(1);
                b.rayleigh_scattering[lane] = self.rayleigh_scattering_per_m[c];
                b.rayleigh_depolarisation[lane] = 0.0;
                b.ozone_absorption[lane] = self.ozone_absorption_per_m[c];
                b.aerosol_scattering[lane] = self.mie_scattering_per_m[c];
                b.aerosol_absorption[lane] = self.mie_absorption_per_m[c];
                b.aerosol_g[lane] = self.mie_asymmetry;
                b.ground_albedo[lane] = self.ground_albedo[c];
            }
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerosol::AerosolType;
    use crate::profiles::{AirProfile, OzoneProfile};
    use crate::scene::{OzoneColumn, Scene};

    fn within(a: f64, b: f64, tolerance: f64) -> bool {
        (a / b - 1.0).abs() < tolerance
    }

    /// An atmosphere built as Hillaire's Earth (exponential air and aerosol, the tent ozone,
    /// a grey Henyey–Greenstein aerosol) fits back to his published coefficients.
    #[test]
    fn hillaires_earth_fits_back_to_his_coefficients() {
        let mut s = Scene::default();
        let a = &mut s.atmosphere;
        a.air_profile = AirProfile::Exponential8km;
        a.rayleigh_depolarisation = false;
        a.ozone.profile = OzoneProfile::Tent;
        a.ozone.column = OzoneColumn::Du(300.0);
        a.aerosol.kind = AerosolType::Custom;
        a.aerosol.custom.single_scattering_albedo = 0.9;
        a.aerosol.custom.asymmetry_g = 0.8;
        a.aerosol.custom.angstrom_exponent = 0.0;
        a.aerosol.custom.scale_height_km = 1.2;
        // Hillaire's Mie extinction (3.996 + 0.444)·10⁻⁶ m⁻¹ over a 1.2 km scale height.
        a.aerosol.aod550 = 4.44e-6 * 1200.0;
        let fit = EngineAtmosphere::fit(&Atmosphere::for_scene(&s));
        let e = EngineAtmosphere::HILLAIRE_EARTH;
        // His Rayleigh coefficients (Bruneton & Neyret's) lie above the ones our
        // cross-sections give at the US Standard Atmosphere's ground density, which follow
        // Bucholtz (1995): ours held to 80–90 % of his, the spectral shape to 3 %.
        let r = |c: usize| fit.rayleigh_scattering_per_m[c] / e.rayleigh_scattering_per_m[c];
        for c in 0..3 {
            assert!((0.80..0.90).contains(&r(c)), "{c}: {fit:?}");
            assert!(within(r(c), r(1), 0.03), "{c}: {fit:?}");
        }
        for c in 0..3 {
            assert!(within(
                fit.mie_scattering_per_m[c],
                e.mie_scattering_per_m[c],
                0.01
            ));
            assert!(within(
                fit.mie_absorption_per_m[c],
                e.mie_absorption_per_m[c],
                0.01
            ));
        }
        assert!(within(fit.rayleigh_scale_height_m, 8000.0, 0.01), "{fit:?}");
        assert!(within(fit.mie_scale_height_m, 1200.0, 0.01), "{fit:?}");
        assert!(
            (fit.ozone_tip_altitude_m - 25_000.0).abs() < 300.0,
            "{fit:?}"
        );
        assert!((fit.ozone_half_width_m - 15_000.0).abs() < 300.0, "{fit:?}");
        assert!((fit.mie_asymmetry - 0.8).abs() < 1e-9);
        // Ozone: his 1.881·10⁻⁶ m⁻¹ at 550 nm is Bruneton's column with a 15 km tent; ours
        // has another cross-section table and 300 DU.
        assert!(within(
            fit.ozone_absorption_per_m[1],
            e.ozone_absorption_per_m[1],
            0.15
        ));
    }

    /// The default scene's tabulated profiles fit to exponentials and a tent that keep every
    /// constituent's vertical optical depth at every channel.
    #[test]
    fn the_fit_keeps_every_vertical_optical_depth() {
        let atm = Atmosphere::for_scene(&Scene::default());
        let fit = EngineAtmosphere::fit(&atm);
        let depths = fit.vertical_optical_depths();
        for (c, &w) in CHANNELS_NM.iter().enumerate() {
            let exact = atm.vertical_optical_depth(&atm.optics(w), 0.0);
            assert!(
                within(depths[0][c], exact.rayleigh, 0.01),
                "{w}: {depths:?} {exact:?}"
            );
            assert!(
                within(depths[1][c], exact.aerosol, 0.01),
                "{w}: {depths:?} {exact:?}"
            );
            assert!(
                within(depths[2][c], exact.ozone, 0.01),
                "{w}: {depths:?} {exact:?}"
            );
        }
        assert!(
            (7000.0..9000.0).contains(&fit.rayleigh_scale_height_m),
            "{fit:?}"
        );
        assert!(
            (15_000.0..35_000.0).contains(&fit.ozone_tip_altitude_m),
            "{fit:?}"
        );
    }

    /// The optics handed to the models are the fit's: exponentials and the tent at the
    /// profile's heights, each lane the coefficients of its channel.
    #[test]
    fn the_params_carry_the_fit() {
        let s = Scene::default();
        let atm = Atmosphere::for_scene(&s);
        let fit = EngineAtmosphere::fit(&atm);
        let base = Params::new(&atm, crate::scene::WavelengthSet::Rgb3, s.render.quality);
        let p = fit.params(&base);
        assert_eq!(p.profile[0], [1.0, fit.ozone_tent(0.0), 1.0, 0.0]);
        let b = &p.batches[0];
        assert_eq!(b.rayleigh_scattering[2], fit.rayleigh_scattering_per_m[2]);
        assert_eq!(b.rayleigh_scattering[3], fit.rayleigh_scattering_per_m[1]);
        assert_eq!(b.ground_albedo[0], fit.ground_albedo[0]);
        assert_eq!(p.aerosol_phase, AerosolPhase::HenyeyGreenstein);
        let n = p.profile.len();
        let top = fit.top_radius_m - fit.bottom_radius_m;
        let h = top * ((n / 2) as f64 / (n - 1) as f64).powi(2);
        assert!((p.profile[n / 2][0] - (-h / fit.rayleigh_scale_height_m).exp()).abs() < 1e-12);
    }
}
