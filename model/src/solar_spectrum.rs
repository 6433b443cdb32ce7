//! Extraterrestrial solar spectral irradiance at 1 AU, W·m⁻²·nm⁻¹.
//!
//! ASTM G173-03 (Gueymard) is the default; Gueymard (2004), Bruneton's 10 nm bins of ASTM G173
//! and the Wehrli (1985) table of Skytracer are selectable to reproduce other renderers.

use crate::csv_table::tables;
use crate::spectrum::Spectrum;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum SolarSpectrum {
    #[default]
    AstmG173,
    Gueymard2004,
    Bruneton10nm,
    Wehrli1985,
}

impl SolarSpectrum {
    pub const ALL: [SolarSpectrum; 4] = [
        SolarSpectrum::AstmG173,
        SolarSpectrum::Gueymard2004,
        SolarSpectrum::Bruneton10nm,
        SolarSpectrum::Wehrli1985,
    ];

    pub fn label(self) -> &'static str {
        match self {
            SolarSpectrum::AstmG173 => "ASTM G173-03",
            SolarSpectrum::Gueymard2004 => "Gueymard 2004",
            SolarSpectrum::Bruneton10nm => "Bruneton 10 nm",
            SolarSpectrum::Wehrli1985 => "Wehrli 1985",
        }
    }

    /// The irradiance spectrum.
    pub fn spectrum(self) -> &'static Spectrum {
        static CACHE: [OnceLock<Spectrum>; 4] = [
            OnceLock::new(),
            OnceLock::new(),
            OnceLock::new(),
            OnceLock::new(),
        ];
        let i = SolarSpectrum::ALL
            .iter()
            .position(|&s| s == self)
            .unwrap_or(0);
        CACHE[i].get_or_init(|| {
            let col = "irradiance_W_m2_nm";
            match self {
                SolarSpectrum::AstmG173 => {
                    Spectrum::from_table(tables::solar_astm_g173(), "wavelength_nm", col)
                }
                SolarSpectrum::Gueymard2004 => {
                    Spectrum::from_table(tables::solar_gueymard2004(), "wavelength_nm", col)
                }
                SolarSpectrum::Wehrli1985 => {
                    Spectrum::from_table(tables::solar_wehrli1985(), "wavelength_nm", col)
                }
                SolarSpectrum::Bruneton10nm => {
                    // Means over [L, L+10) nm belong to the bin centres.
                    let t = tables::solar_bruneton_10nm();
                    let w = t.numbers("wavelength_nm").iter().map(|w| w + 5.0).collect();
                    Spectrum::new(w, t.numbers(col)).expect("valid embedded table")
                }
            }
        })
    }

    /// Irradiance averaged over a band of `width_nm` around `wavelength_nm`, W·m⁻²·nm⁻¹.
    pub fn irradiance(self, wavelength_nm: f64, width_nm: f64) -> f64 {
        self.spectrum().bin_average(wavelength_nm, width_nm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visible_irradiance_agrees_between_tables() {
        let reference = SolarSpectrum::AstmG173.spectrum().integrate(400.0, 700.0);
        // About 530 W/m² of the solar constant lies in 400–700 nm.
        assert!(reference > 500.0 && reference < 560.0, "{reference}");
        for s in SolarSpectrum::ALL {
            let v = s.spectrum().integrate(400.0, 700.0);
            assert!((v / reference - 1.0).abs() < 0.03, "{s:?}: {v}");
        }
    }

    #[test]
    fn band_averages_are_close_to_the_published_ones() {
        // Bruneton's bins are ASTM means: the 550–560 bin mean must match our band average.
        let ours = SolarSpectrum::AstmG173.irradiance(555.0, 10.0);
        let theirs = SolarSpectrum::Bruneton10nm.spectrum().sample(555.0);
        assert!((ours / theirs - 1.0).abs() < 0.01, "{ours} vs {theirs}");
    }
}
