//! The set-up of D. Leenman (2025), "A visual and performance comparison of atmospheric
//! scattering models" (master's thesis, Utrecht University), for `atmoscope bench leenman`:
//! his Earth, his twelve views with his exposures, his scale of radiance, and the values of his
//! appendices A–D (`data/leenman2025_appendix_tables.csv`).
//!
//! His Earth is the one of Hillaire's (2020) demo, which he takes for every model: linear-sRGB
//! coefficients (no spectral rendering), air exponential with an 8 km scale height, aerosol
//! exponential with 1.2 km, single-scattering albedo 0.9 and a Cornette–Shanks phase with
//! g = 0.8, ozone in a tent from 10 to 40 km, a black ground. Atmoscope renders it with the RGB3
//! set, whose 680/550/440 nm are the wavelengths those coefficients stand for, and the
//! `exponential-8km` air and `tent` ozone profiles (300 DU, Bruneton's column); the aerosol's
//! extinction 4.44·10⁻⁶ m⁻¹ at the ground over its 1.2 km scale height is an AOD of 0.0053,
//! grey (Ångström exponent 0).
//!
//! His sun has irradiance 6 in each channel and his images are radiance times a per-view
//! exposure (1, 16 at dawn, 2 for space, 32 for the planet's shadow), not tone mapped: a pixel
//! L of ours is exposure·6·L/E on his scale, E the sun's irradiance in the same channel.
//!
//! The views are the suite's (`presets/views/suite.ron`) with two corrections to his text: the
//! noon sun stands at the zenith (the suite's 60° keeps García Liñán's views apart), and in the
//! planet-shadow views the sun is 3° below the horizon to the viewer's right (the suite's has it
//! behind).

use crate::aerosol::AerosolType;
use crate::scene::{AerosolPhase, Method, OzoneColumn, Scene, SunSettings, WavelengthSet};
use crate::table::Table;
use crate::views::{self, View};
use std::sync::OnceLock;

/// His sun's irradiance, per channel (no unit).
pub const SUN_IRRADIANCE: f64 = 6.0;

/// Ground extinction of his aerosol, m⁻¹ (Hillaire's demo: 4.44·10⁻³ km⁻¹).
pub const AEROSOL_EXTINCTION_PER_M: f64 = 4.44e-6;
/// Scale height of his aerosol, km.
pub const AEROSOL_SCALE_HEIGHT_KM: f64 = 1.2;
/// Single-scattering albedo of his aerosol (3.996 / 4.44).
pub const AEROSOL_SINGLE_SCATTERING_ALBEDO: f64 = 0.9;
/// Asymmetry parameter of his aerosol's phase function.
pub const AEROSOL_G: f64 = 0.8;
/// Total ozone column of the tent, DU (Bruneton's 300 DU).
pub const OZONE_COLUMN_DU: f64 = 300.0;

/// One of his views: his name, the suite view it is built from, his exposure, and the sun's
/// position where it differs from the suite's (elevation, azimuth relative to the camera's
/// heading).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeenmanView {
    pub name: &'static str,
    pub suite: &'static str,
    pub exposure: f64,
    pub sun: Option<(f64, f64)>,
}

const NOON: Option<(f64, f64)> = Some((90.0, 0.0));
const SHADOW: Option<(f64, f64)> = Some((-3.0, 90.0));

/// His twelve views (appendices A and B), in his order.
pub const VIEWS: [LeenmanView; 12] = [
    view("ground-dawn", "ground-dawn", 16.0, None),
    view("ground-sunrise", "ground-sunrise", 1.0, None),
    view("ground-noon", "ground-noon", 1.0, NOON),
    view("plane-dawn", "plane-dawn", 16.0, None),
    view("plane-sunrise", "plane-sunrise", 1.0, None),
    view("plane-noon", "plane-noon", 1.0, NOON),
    view("orbit-dawn", "orbit-dawn", 16.0, None),
    view("orbit-sunrise", "orbit-sunrise", 1.0, None),
    view("orbit-noon", "orbit-noon", 1.0, NOON),
    view("space", "space", 2.0, None),
    view("planet-shadow-ground", "shadow-ground", 32.0, SHADOW),
    view("planet-shadow-orbit", "shadow-200km", 32.0, SHADOW),
];

/// His five transmittance views (appendices C and D): the cameras of the views named.
pub const TRANSMITTANCE_VIEWS: [(&str, &str); 5] = [
    ("ground", "ground-noon"),
    ("plane", "plane-noon"),
    ("orbit", "orbit-noon"),
    ("space", "space"),
    ("planet-shadow-orbit", "planet-shadow-orbit"),
];

const fn view(
    name: &'static str,
    suite: &'static str,
    exposure: f64,
    sun: Option<(f64, f64)>,
) -> LeenmanView {
    LeenmanView {
        name,
        suite,
        exposure,
        sun,
    }
}

impl LeenmanView {
    /// His view by his name.
    pub fn find(name: &str) -> Option<&'static LeenmanView> {
        VIEWS.iter().find(|v| v.name == name)
    }

    /// The suite's view with his sun.
    pub fn view(&self) -> View {
        let mut v = views::find(self.suite)
            .unwrap_or_else(|| panic!("the suite lacks {}", self.suite))
            .clone();
        if let Some((elevation_deg, to_the_right_deg)) = self.sun {
            v.sun = SunSettings::Angles {
                elevation_deg,
                azimuth_deg: (v.camera.heading_deg + to_the_right_deg).rem_euclid(360.0),
            };
        }
        v.name = self.name.into();
        v
    }

    /// His scene seen through this view.
    pub fn scene(&self) -> Scene {
        self.view().apply(&scene())
    }

    /// A pixel of ours, linear sRGB radiance `l`, on his scale: exposure·6·L/E per channel,
    /// with `sun` the sun's irradiance in the same channels and units.
    pub fn to_his_scale(&self, l: [f64; 3], sun: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|c| self.exposure * SUN_IRRADIANCE * l[c] / sun[c])
    }
}

/// His Earth (see the module's documentation).
pub fn scene() -> Scene {
    let mut s = Scene::default();
    s.name = "Leenman 2025 (Hillaire's Earth)".into();
    s.description = "Leenman (2025)'s comparison set-up: Hillaire's (2020) Earth in linear sRGB, exponential air and aerosol, tent ozone, black ground.".into();
    let a = &mut s.atmosphere;
    a.planet_radius_km = 6360.0;
    a.top_km = 100.0;
    a.air_profile = crate::profiles::AirProfile::Exponential8km;
    a.air_density_scale = 1.0;
    a.rayleigh_depolarisation = false;
    a.aerosol.kind = AerosolType::Custom;
    a.aerosol.aod550 = AEROSOL_EXTINCTION_PER_M * AEROSOL_SCALE_HEIGHT_KM * 1000.0;
    a.aerosol.phase = AerosolPhase::CornetteShanks;
    a.aerosol.custom.single_scattering_albedo = AEROSOL_SINGLE_SCATTERING_ALBEDO;
    a.aerosol.custom.asymmetry_g = AEROSOL_G;
    a.aerosol.custom.angstrom_exponent = 0.0;
    a.aerosol.custom.scale_height_km = AEROSOL_SCALE_HEIGHT_KM;
    a.ozone.profile = crate::profiles::OzoneProfile::Tent;
    a.ozone.column = OzoneColumn::Du(OZONE_COLUMN_DU);
    a.ground_albedo = 0.0;
    s.render.wavelengths = WavelengthSet::Rgb3;
    s
}

/// The models he compares (his neural network excepted), his name beside the registry's.
pub const MODELS: [(&str, Method); 8] = [
    ("Preetham, Shirley, and Smits", Method::Preetham),
    ("Empty", Method::Empty),
    ("Raymarched", Method::Raymarched),
    ("Schuler", Method::Schuler),
    ("Naive", Method::Nishita),
    ("Hillaire", Method::Hillaire),
    ("Flat", Method::Flat),
    ("Bruneton and Neyret", Method::Bruneton),
];

/// His name for one of our models, where he compares it.
pub fn his_name(method: Method) -> Option<&'static str> {
    MODELS.iter().find(|m| m.1 == method).map(|m| m.0)
}

/// His appendices' tables.
pub const TABLES: [&str; 4] = ["A_FLIP", "B_RMSE", "C_FLIP_T", "D_RMSE_T"];

/// One published value.
#[derive(Debug, Clone, PartialEq)]
pub struct Published {
    pub table: String,
    pub view: String,
    pub model: String,
    pub value: f64,
}

/// Every value of his appendices A–D, as printed.
pub fn published() -> &'static [Published] {
    static ROWS: OnceLock<Vec<Published>> = OnceLock::new();
    ROWS.get_or_init(|| {
        let t = Table::parse(
            "leenman2025_appendix_tables.csv",
            include_str!("../data/leenman2025_appendix_tables.csv"),
        );
        let values = t.numbers("value");
        t.text("table")
            .into_iter()
            .zip(t.text("view"))
            .zip(t.text("model"))
            .zip(values)
            .map(|(((table, view), model), value)| Published {
                table: table.into(),
                view: view.into(),
                model: model.into(),
                value,
            })
            .collect()
    })
}

/// His value for one cell, if he published one.
pub fn published_value(table: &str, view: &str, model: &str) -> Option<f64> {
    published()
        .iter()
        .find(|p| p.table == table && p.view == view && p.model == model)
        .map(|p| p.value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn his_tables_are_complete_and_name_his_views_and_models() {
        let rows = published();
        assert_eq!(rows.len(), 236);
        for (table, views, models) in [("A_FLIP", 12, 9), ("B_RMSE", 12, 9)] {
            let n = rows.iter().filter(|r| r.table == table).count();
            assert_eq!(n, views * models, "{table}");
            for v in &VIEWS {
                for (m, _) in MODELS {
                    assert!(
                        published_value(table, v.name, m).is_some(),
                        "{table} {v:?} {m}"
                    );
                }
            }
        }
        for table in ["C_FLIP_T", "D_RMSE_T"] {
            for (v, _) in TRANSMITTANCE_VIEWS {
                assert!(published_value(table, v, "Flat").is_some(), "{table} {v}");
            }
        }
        assert!(rows.iter().all(|r| r.value.is_finite() && r.value >= 0.0));
    }

    #[test]
    fn his_scene_is_valid_and_his_views_exist_with_his_sun() {
        let s = scene();
        assert!(s.validate().is_ok(), "{:?}", s.validate());
        for v in &VIEWS {
            let scene = v.scene();
            assert!(scene.validate().is_ok(), "{}", v.name);
        }
        let noon = LeenmanView::find("ground-noon").expect("view");
        assert_eq!(noon.scene().sun.angles().elevation_deg, 90.0);
        let shadow = LeenmanView::find("planet-shadow-ground").expect("view");
        let s = shadow.scene();
        let a = s.sun.angles();
        assert_eq!(a.elevation_deg, -3.0);
        assert_eq!(
            a.azimuth_deg,
            (s.camera.heading_deg + 90.0).rem_euclid(360.0)
        );
        // His scale: a pixel as bright as the sun's irradiance per steradian is 6 at exposure 1.
        assert_eq!(
            LeenmanView::find("ground-sunrise")
                .expect("view")
                .to_his_scale([2.0, 4.0, 8.0], [2.0, 4.0, 8.0]),
            [6.0; 3]
        );
    }
}
