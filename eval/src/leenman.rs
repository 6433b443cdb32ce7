//! The set-up of D. Leenman (2025), "A visual and performance comparison of atmospheric
//! scattering models" (master's thesis, Utrecht University), for `atmoscope bench leenman`:
//! his Earth, his twelve views with his exposures, his scale of radiance, and the values of his
//! appendices A–D (`data/leenman2025_appendix_tables.csv`).
//!
//! His Earth is the one of Hillaire's (2020) demo (`data/hillaire2020_earth_defaults.csv`),
//! which he takes for every model: linear-sRGB
//! coefficients (no spectral rendering), air exponential with an 8 km scale height, aerosol
//! exponential with 1.2 km, single-scattering albedo 0.9 and a Cornette–Shanks phase with
//! g = 0.8, ozone in a tent from 10 to 40 km, a black ground. Atmoscope renders it with the RGB3
//! set, whose 680/550/440 nm are the wavelengths those coefficients stand for, and the
//! `exponential-8km` air and `tent` ozone profiles (300 DU, Bruneton's column); his air, from
//! Bruneton's λ⁻⁴ fit, scatters 17 % more than real air at 550 nm, so its density is scaled to
//! match (`air_density_scale`: red then comes out 1.4 % short of his and blue 2.3 % over;
//! ozone's absorption at the peak +12 %, −4 % and −14 %); the aerosol's
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

use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::csv_table::Table;
use atmoscope_model::scene::{
    AerosolPhase, Method, OzoneColumn, Scene, SunSettings, WavelengthSet,
};
use atmoscope_model::views::{self, View};
use std::sync::OnceLock;

/// His sun's irradiance, per channel (no unit).
pub const SUN_IRRADIANCE: f64 = 6.0;

/// Total ozone column of the tent, DU: Bruneton's (2017) 300 DU, whose peak density Hillaire's
/// absorption coefficients stand for.
pub const OZONE_COLUMN_DU: f64 = 300.0;

/// One value of Hillaire's (2020) demo Earth (`data/hillaire2020_earth_defaults.csv`), in the
/// table's unit.
pub fn hillaire_earth(parameter: &str) -> f64 {
    let t = atmoscope_model::csv_table::tables::hillaire_earth().filter("parameter", parameter);
    *t.numbers("value")
        .first()
        .unwrap_or_else(|| panic!("hillaire2020_earth_defaults.csv lacks {parameter}"))
}

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
    let (bottom_km, top_km) = (
        hillaire_earth("bottom_radius"),
        hillaire_earth("top_radius"),
    );
    let aerosol_scale_height_km = hillaire_earth("mie_scale_height");
    let (mie_scattering, mie_extinction) = (
        hillaire_earth("mie_scattering"),
        hillaire_earth("mie_extinction"),
    );
    let a = &mut s.atmosphere;
    a.planet_radius_km = bottom_km;
    a.top_km = top_km - bottom_km;
    a.air_profile = atmoscope_model::profiles::AirProfile::Exponential8km;
    // His air scatters as Bruneton's λ⁻⁴ fit, 17 % more than air at sea level: the density
    // that gives his green channel's coefficient at 550 nm.
    let green = atmoscope_model::csv_table::tables::hillaire_earth()
        .filter("parameter", "rayleigh_scattering")
        .filter("channel", "G")
        .numbers("value")[0];
    let ground_m3 = atmoscope_model::profiles::AirProfile::Exponential8km.number_density_m3(0.0);
    a.air_density_scale = green
        / 1000.0
        / (ground_m3
            * atmoscope_model::rayleigh::cross_section_m2(
                atmoscope_model::wavelengths::RGB3_NM[1],
            ));
    a.rayleigh_depolarisation = false;
    a.aerosol.kind = AerosolType::Custom;
    // Extinction (km⁻¹) at the ground over the scale height (km): the vertical optical depth.
    a.aerosol.aod550 = mie_extinction * aerosol_scale_height_km;
    a.aerosol.phase = AerosolPhase::CornetteShanks;
    a.aerosol.custom.single_scattering_albedo = mie_scattering / mie_extinction;
    a.aerosol.custom.asymmetry_g = hillaire_earth("mie_phase_g");
    a.aerosol.custom.angstrom_exponent = 0.0;
    a.aerosol.custom.scale_height_km = aerosol_scale_height_km;
    a.ozone.profile = atmoscope_model::profiles::OzoneProfile::Tent;
    a.ozone.column = OzoneColumn::Du(OZONE_COLUMN_DU);
    a.ground_albedo = hillaire_earth("ground_albedo");
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

    /// His Earth rebuilt from Atmoscope's physics at the RGB3 wavelengths: the aerosol and the
    /// air's green channel exactly (set from his numbers), the other channels and ozone from
    /// their cross-sections close to his coefficients.
    #[test]
    fn his_earth_has_his_coefficients() {
        use atmoscope_model::methods::shared::Params;
        let p = Params::new(
            &atmoscope_model::Atmosphere::for_scene(&scene()),
            WavelengthSet::Rgb3,
            atmoscope_model::scene::Quality::Medium,
        );
        let per_km = |m: f64| m * 1000.0;
        let ground = p.medium(0, 0.0);
        let peak = p.medium(0, 25_000.0);
        for (lane, channel) in ["R", "G", "B"].into_iter().enumerate() {
            let his = |name: &str| {
                let t = atmoscope_model::csv_table::tables::hillaire_earth()
                    .filter("parameter", name)
                    .filter("channel", channel);
                t.numbers("value")[0]
            };
            let rayleigh = per_km(ground.rayleigh_scattering[lane]);
            assert!(
                (rayleigh / his("rayleigh_scattering") - 1.0).abs() < 0.03,
                "{channel}: Rayleigh {rayleigh} km⁻¹"
            );
            // No ozone at the ground in the tent.
            let aerosol_extinction =
                per_km(ground.extinction[lane] - ground.rayleigh_scattering[lane]);
            assert!(
                (aerosol_extinction / hillaire_earth("mie_extinction") - 1.0).abs() < 0.02,
                "{channel}: aerosol {aerosol_extinction} km⁻¹"
            );
            let ozone = per_km(peak.extinction[lane] - peak.rayleigh_scattering[lane]);
            assert!(
                (ozone / his("ozone_absorption") - 1.0).abs() < 0.15,
                "{channel}: ozone {ozone} km⁻¹"
            );
        }
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
