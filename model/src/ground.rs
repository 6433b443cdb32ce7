//! The ground: a Lambertian surface, grey (the scene's `ground_albedo`) or with the measured
//! spectral albedo of a natural surface. Every model's ground bounce and the path tracer read
//! the albedo at their own wavelengths through [`GroundType::albedo`].
//!
//! The spectra (`data/ground_albedo/`, each with its provenance): dry fresh snow from Bowker et
//! al. (1985, NASA RP-1139), 390–1020 nm; grass, dry sand and dry loam from Feister & Grewe
//! (1995), 290–800 nm; open-ocean sea water from the USGS spectral library splib06a (Clark et
//! al. 2007), 205–1049 nm. Past a table's ends its end value holds (the engine's wavelengths
//! lie in 360–830 nm, so this reaches only snow below 390 nm and the Feister & Grewe surfaces
//! above 800 nm).

use crate::csv_table::Table;
use crate::spectrum::Spectrum;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// The wavelengths over which the visible albedo is averaged, nm.
pub const VISIBLE_NM: (f64, f64) = (400.0, 700.0);

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum GroundType {
    /// The same albedo at every wavelength: the scene's `ground_albedo`.
    #[default]
    Grey,
    FreshSnow,
    Grass,
    DesertSand,
    DrySoil,
    Ocean,
}

impl GroundType {
    pub const ALL: [GroundType; 6] = [
        GroundType::Grey,
        GroundType::FreshSnow,
        GroundType::Grass,
        GroundType::DesertSand,
        GroundType::DrySoil,
        GroundType::Ocean,
    ];

    pub fn label(self) -> &'static str {
        match self {
            GroundType::Grey => "grey",
            GroundType::FreshSnow => "fresh snow",
            GroundType::Grass => "grass",
            GroundType::DesertSand => "desert sand",
            GroundType::DrySoil => "dry soil",
            GroundType::Ocean => "ocean",
        }
    }

    /// The command line's name, e.g. `fresh-snow`.
    pub fn cli_name(self) -> &'static str {
        match self {
            GroundType::Grey => "grey",
            GroundType::FreshSnow => "fresh-snow",
            GroundType::Grass => "grass",
            GroundType::DesertSand => "desert-sand",
            GroundType::DrySoil => "dry-soil",
            GroundType::Ocean => "ocean",
        }
    }

    pub fn from_cli_name(name: &str) -> Option<GroundType> {
        GroundType::ALL.into_iter().find(|g| g.cli_name() == name)
    }

    /// Where the spectrum was measured; empty for grey.
    pub fn source(self) -> &'static str {
        match self {
            GroundType::Grey => "",
            GroundType::FreshSnow => {
                "Dry fresh snow, Bowker et al. (1985), NASA Reference Publication 1139"
            }
            GroundType::Grass => {
                "A meadow, Feister & Grewe (1995), Photochemistry and Photobiology 62(4)"
            }
            GroundType::DesertSand => {
                "Dry sand, Feister & Grewe (1995), Photochemistry and Photobiology 62(4)"
            }
            GroundType::DrySoil => {
                "Dry loam, Feister & Grewe (1995), Photochemistry and Photobiology 62(4)"
            }
            GroundType::Ocean => {
                "Open-ocean sea water, USGS spectral library splib06a (Clark et al. 2007)"
            }
        }
    }

    /// The visible albedo the spectrum gives (its mean over 400–700 nm weighted by the ASTM
    /// G173 sun), as the docs and the Scene panel state it; None for grey, which is the scene's.
    /// For comparison, Oke's (1987) broadband albedos: fresh snow 0.80–0.95, desert 0.20–0.45,
    /// dry soils up to 0.35, water at a high sun 0.03–0.10; grass, 0.16–0.26 in Oke's broadband
    /// figure, is dark in the visible and bright in the near infrared.
    pub fn stated_visible_albedo(self) -> Option<f64> {
        match self {
            GroundType::Grey => None,
            GroundType::FreshSnow => Some(0.90),
            GroundType::Grass => Some(0.05),
            GroundType::DesertSand => Some(0.31),
            GroundType::DrySoil => Some(0.15),
            GroundType::Ocean => Some(0.03),
        }
    }

    /// The measured spectrum; None for grey.
    pub fn spectrum(self) -> Option<&'static Spectrum> {
        static CACHE: [OnceLock<Spectrum>; 6] = [const { OnceLock::new() }; 6];
        let (file, text, column, to_nm) = match self {
            GroundType::Grey => return None,
            GroundType::FreshSnow => (
                "bowker1985_dry_fresh_snow.csv",
                include_str!("../data/ground_albedo/bowker1985_dry_fresh_snow.csv"),
                "wavelength_nm",
                1.0,
            ),
            GroundType::Grass => (
                "feister_grewe1995_grass.csv",
                include_str!("../data/ground_albedo/feister_grewe1995_grass.csv"),
                "wavelength_nm",
                1.0,
            ),
            GroundType::DesertSand => (
                "feister_grewe1995_sand.csv",
                include_str!("../data/ground_albedo/feister_grewe1995_sand.csv"),
                "wavelength_nm",
                1.0,
            ),
            GroundType::DrySoil => (
                "feister_grewe1995_loam.csv",
                include_str!("../data/ground_albedo/feister_grewe1995_loam.csv"),
                "wavelength_nm",
                1.0,
            ),
            GroundType::Ocean => (
                "usgs_splib06a_seawater_open_ocean.csv",
                include_str!("../data/ground_albedo/usgs_splib06a_seawater_open_ocean.csv"),
                "wavelength_um",
                1000.0,
            ),
        };
        let i = GroundType::ALL.iter().position(|&g| g == self)?;
        Some(CACHE[i].get_or_init(|| {
            let table = Table::parse(file, text);
            let nm = table.numbers(column).iter().map(|w| w * to_nm).collect();
            Spectrum::new(nm, table.numbers("albedo")).expect("valid embedded table")
        }))
    }

    /// The albedo (0–1) at `wavelength_nm`, averaged over a band `band_nm` wide where given
    /// (the engine's broad RGB lanes); `grey` (0–1) is the albedo of [`GroundType::Grey`].
    pub fn albedo(self, grey: f64, wavelength_nm: f64, band_nm: Option<f64>) -> f64 {
        let Some(s) = self.spectrum() else {
            return grey;
        };
        let (lo, hi) = s.range_nm();
        let at = |w: f64| s.sample(w.clamp(lo, hi));
        match band_nm.filter(|&b| b > 1.0) {
            // The band's mean by the midpoint rule on 1 nm steps (the tables are 1–10 nm).
            Some(band) => {
                let n = band.ceil() as usize;
                let start = wavelength_nm - band / 2.0;
                (0..n)
                    .map(|k| at(start + (k as f64 + 0.5) * band / n as f64))
                    .sum::<f64>()
                    / n as f64
            }
            None => at(wavelength_nm),
        }
    }

    /// The visible albedo (400–700 nm, weighted by `sun`, W·m⁻²·nm⁻¹), by the midpoint rule
    /// on 1 nm steps.
    pub fn visible_albedo(self, grey: f64, sun: &Spectrum) -> f64 {
        let (a, b) = VISIBLE_NM;
        let (mut weighted, mut total) = (0.0, 0.0);
        for k in 0..(b - a) as usize {
            let w = a + k as f64 + 0.5;
            let e = sun.sample(w);
            weighted += e * self.albedo(grey, w, None);
            total += e;
        }
        weighted / total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solar_spectrum::SolarSpectrum;

    /// The visible albedos that `tests/scripts/ground_visible_albedo.py` computes from the same
    /// tables apart from this code: the exact integral of the tables' straight lines (Simpson's
    /// rule on their merged points) where the crate takes the midpoint rule on 1 nm steps.
    const INDEPENDENT: [(GroundType, f64); 5] = [
        (GroundType::FreshSnow, 0.8996),
        (GroundType::Grass, 0.0489),
        (GroundType::DesertSand, 0.3138),
        (GroundType::DrySoil, 0.1523),
        (GroundType::Ocean, 0.0308),
    ];

    /// Each spectrum's visible albedo is the independent integral's, and the stated value (the
    /// docs' and the Scene panel's) is that integral rounded. Where a published broadband range
    /// applies to the visible, the spectrum lies in it: Oke (1987), fresh snow 0.80–0.95, desert
    /// 0.20–0.45, dry soils up to 0.35, water at a high sun 0.03–0.10 (grass is darker in the
    /// visible than in Oke's broadband 0.16–0.26, and has no such check).
    #[test]
    fn the_spectra_integrate_to_their_stated_visible_albedos() {
        let sun = SolarSpectrum::AstmG173.spectrum();
        let grey = GroundType::Grey.visible_albedo(0.3, sun);
        assert!((grey - 0.3).abs() < 1e-12, "grey is the scene's: {grey}");
        assert_eq!(GroundType::Grey.stated_visible_albedo(), None);
        assert_eq!(
            INDEPENDENT.len(),
            GroundType::ALL.len() - 1,
            "every measured ground"
        );
        for (g, independent) in INDEPENDENT {
            let a = g.visible_albedo(0.3, sun);
            assert!(
                (a - independent).abs() < 0.002,
                "{g:?}: {a:.4}, the independent integral {independent}"
            );
            let stated = g.stated_visible_albedo().expect("a measured ground");
            assert!(
                (stated - independent).abs() < 0.005,
                "{g:?} states {stated}, the independent integral gives {independent}"
            );
            let published = match g {
                GroundType::FreshSnow => 0.80..0.95,
                GroundType::DesertSand => 0.20..0.45,
                GroundType::DrySoil => 0.0..0.35,
                GroundType::Ocean => 0.03..0.10,
                _ => continue,
            };
            assert!(
                published.contains(&a),
                "{g:?}: {a:.4} outside Oke's {published:?}"
            );
        }
    }

    #[test]
    fn the_spectra_have_their_surfaces_shapes() {
        let a = |g: GroundType, w: f64| g.albedo(0.3, w, None);
        // Chlorophyll: a green peak over blue and red, and the red edge past 700 nm.
        assert!(a(GroundType::Grass, 550.0) > 2.0 * a(GroundType::Grass, 450.0));
        assert!(a(GroundType::Grass, 550.0) > 2.0 * a(GroundType::Grass, 670.0));
        assert!(a(GroundType::Grass, 780.0) > 5.0 * a(GroundType::Grass, 670.0));
        // Sand and soil redden; water is bluest; snow is near white everywhere.
        for g in [GroundType::DesertSand, GroundType::DrySoil] {
            assert!(a(g, 650.0) > 1.2 * a(g, 450.0), "{g:?}");
        }
        assert!(a(GroundType::Ocean, 450.0) > 1.5 * a(GroundType::Ocean, 650.0));
        for w in [380.0, 450.0, 550.0, 650.0, 830.0] {
            assert!((0.85..0.92).contains(&a(GroundType::FreshSnow, w)), "{w}");
        }
        // Past a table's end its end value holds; the band mean of a straight piece is its
        // centre value.
        assert_eq!(a(GroundType::Grass, 830.0), a(GroundType::Grass, 800.0));
        let band = GroundType::DesertSand.albedo(0.3, 600.0, Some(20.0));
        assert!(
            (band - a(GroundType::DesertSand, 600.0)).abs() < 2e-3,
            "{band}"
        );
        assert_eq!(GroundType::Grey.albedo(0.42, 500.0, Some(100.0)), 0.42);
    }
}
