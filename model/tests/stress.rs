//! Property tests over the whole scene parameter space: every optical quantity stays finite and
//! physical for any valid scene, wavelength and ray (a small run in CI; docs/testing.md).

use atmoscope_model::Atmosphere;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::geometry::Ray;
use atmoscope_model::profiles::{AirProfile, OzoneProfile};
use atmoscope_model::scene::{AtmosphereSettings, OzoneColumn};
use glam::DVec3;
use proptest::prelude::*;

fn settings() -> impl Strategy<Value = AtmosphereSettings> {
    let air = prop::sample::select(AirProfile::all());
    let ozone = prop::sample::select(OzoneProfile::all());
    let aerosol = prop::sample::select(AerosolType::ALL.to_vec());
    (
        air,
        ozone,
        aerosol,
        0.0..5.0f64,
        0.0..1000.0f64,
        203.0..293.0f64,
        1000.0..100_000.0f64,
        10.0..1000.0f64,
    )
        .prop_map(|(air, ozone, kind, aod, du, t, radius, top)| {
            let mut s = AtmosphereSettings::default();
            s.air_profile = air;
            s.ozone.profile = ozone;
            s.ozone.column = OzoneColumn::Du(du);
            s.ozone.temperature_k = t;
            s.aerosol.kind = kind;
            s.aerosol.aod550 = aod;
            s.planet_radius_km = radius;
            s.top_km = top;
            s
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn optical_depth_and_transmittance_are_physical(
        s in settings(),
        wavelength in 360.0..830.0f64,
        altitude_fraction in 0.0..1.5f64,
        log_far in 0.0..8.0f64,
        dir in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
    ) {
        let atm = Atmosphere::new(&s);
        let optics = atm.optics(wavelength);
        // Altitudes from the ground to far into space.
        let h = if altitude_fraction > 1.0 { 10f64.powf(log_far) * atm.thickness_m() } else { altitude_fraction * atm.thickness_m() };
        let origin = DVec3::new(0.0, 0.0, atm.bottom_radius_m + h);
        let d = DVec3::new(dir.0, dir.1, dir.2);
        prop_assume!(d.length() > 1e-3);
        let tau = atm.optical_depth(&optics, &Ray::new(origin, d));
        for v in [tau.rayleigh, tau.ozone, tau.aerosol] {
            prop_assert!(v.is_finite() && v >= 0.0, "{tau:?}");
        }
        let t = atm.transmittance_to_sun(&optics, origin, d.normalize());
        prop_assert!((0.0..=1.0).contains(&t), "{t}");
        let up = atm.vertical_optical_depth(&optics, h.min(atm.thickness_m()));
        let ground = atm.vertical_optical_depth(&optics, 0.0);
        prop_assert!(up.total() <= ground.total() * (1.0 + 1e-9), "{up:?} > {ground:?}");
        prop_assert!(optics.aerosol_ssa > 0.0 && optics.aerosol_ssa <= 1.0);
    }
}

/// A preset the mutations start from: every kind of field, the sun by date.
fn preset_text() -> String {
    let mut s = atmoscope_model::Scene::default();
    s.sun = atmoscope_model::scene::SunSettings::Date {
        time: atmoscope_model::sun_position::DateTime {
            year: 2024,
            month: 6,
            day: 21,
            hour: 12.0,
            utc_offset_h: 2.0,
        },
        latitude_deg: 46.8,
        longitude_deg: 9.7,
    };
    s.to_ron()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// The preset loader never panics: any text is a scene that validates, or an error.
    #[test]
    fn any_text_is_a_valid_scene_or_an_error(text in "\\PC{0,300}") {
        let path = std::path::Path::new("fuzz.ron");
        if let Ok(scene) = atmoscope_model::Scene::from_ron(&text, path) {
            prop_assert!(scene.validate().is_ok());
        }
    }

    /// Valid presets with a few bytes replaced (a number cut short, a field renamed, binary
    /// noise) load as valid scenes or are refused with a message naming the file.
    #[test]
    fn mutated_presets_are_valid_scenes_or_named_errors(
        at in any::<prop::sample::Index>(),
        cut in 0usize..12,
        noise in prop::collection::vec(any::<u8>(), 0..12),
    ) {
        let text = preset_text();
        let start = at.index(text.len());
        let end = (start + cut).min(text.len());
        let mut bytes = text.as_bytes().to_vec();
        bytes.splice(start..end, noise);
        let mutated = String::from_utf8_lossy(&bytes);
        match atmoscope_model::Scene::from_ron(&mutated, std::path::Path::new("fuzz.ron")) {
            Ok(scene) => prop_assert!(scene.validate().is_ok()),
            Err(e) => prop_assert!(e.to_string().contains("fuzz.ron"), "{e}"),
        }
    }
}
