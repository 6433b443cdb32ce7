//! The explorer driven through its controls, as a user would, with egui_kittest.

use super::ExplorerApp;
use atmoscope_model::Scene;
use atmoscope_model::aerosol::AerosolType;
use eframe::egui;
use eframe::egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn harness() -> Harness<'static, ExplorerApp> {
    Harness::builder()
        .with_size(egui::vec2(1280.0, 1000.0))
        .build_eframe(|_cc| ExplorerApp::new(Scene::default()))
}

#[test]
fn sliders_change_albedo_sun_and_altitude() {
    let mut h = harness();
    h.get_by_role_and_label(Role::Slider, "ground albedo")
        .set_value_accesskit(0.8);
    h.run();
    assert_eq!(h.state().scene.atmosphere.ground_albedo, 0.8);

    h.get_by_role_and_label(Role::Slider, "elevation")
        .set_value_accesskit(-10.0);
    h.run();
    assert_eq!(h.state().scene.sun.angles().elevation_deg, -10.0);
    // The summary follows: no direct sunlight once the sun has set.
    let summary = h
        .state()
        .summary
        .shown()
        .map(|info| info.wavelengths[0].direct_transmittance);
    assert_eq!(summary, Some(0.0));

    h.get_by_role_and_label(Role::Slider, "altitude")
        .set_value_accesskit(10_000.0);
    h.run();
    assert_eq!(h.state().scene.camera.altitude_m, 10_000.0);
}

#[test]
fn choosing_an_aerosol_type_sets_its_typical_amount() {
    let mut h = harness();
    h.get_by_role_and_label(Role::ComboBox, "Type").click();
    h.run();
    h.get_by_label("Urban").click_accesskit();
    h.run();
    let a = &h.state().scene.atmosphere.aerosol;
    assert_eq!(a.kind, AerosolType::Urban);
    assert_eq!(a.aod550, AerosolType::Urban.default_aod550());
}

#[test]
fn month_slider_sets_the_ozone_column() {
    let mut h = harness();
    h.get_by_role_and_label(Role::Slider, "month")
        .set_value_accesskit(1.0);
    h.run();
    let info = h.state().summary.shown().map(|info| info.ozone_column_du);
    assert_eq!(info, Some(347.0), "January at Arosa");
}

#[test]
fn loading_a_preset_replaces_the_scene() {
    let mut h = harness();
    h.get_by_role_and_label(Role::ComboBox, "Preset").click();
    h.run();
    h.get_by_label("orbit-400km").click();
    h.run();
    assert_eq!(h.state().scene.camera.altitude_m, 400_000.0);
    assert_eq!(h.state().scene.name, "Orbit at 400 km");
    assert!(h.state().message.is_none());
}

#[test]
fn the_camera_can_be_moved_back_over_the_planet() {
    let mut h = harness();
    h.get_by_role_and_label(Role::Slider, "moved back")
        .set_value_accesskit(1000.0);
    h.run();
    assert_eq!(h.state().scene.camera.back_km, 1000.0);
}
