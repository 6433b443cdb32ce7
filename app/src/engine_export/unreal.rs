//! Unreal Engine's SkyAtmosphere component: Hillaire's parameterisation in kilometres and
//! km⁻¹, each coefficient a scale times a colour, the ozone ("other absorption") a tent whose
//! `Width` is half its base, the ground albedo an 8-bit sRGB colour. Written as JSON of the
//! component's properties by their C++ names (the Python editor API spells them in
//! snake_case: `rayleigh_scattering_scale`, …).

use anyhow::Context;
use atmoscope_model::engine_atmosphere::EngineAtmosphere;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct File {
    #[serde(rename = "_about", default)]
    about: String,
    sky_atmosphere_component: Properties,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct Properties {
    bottom_radius: f64,
    ground_albedo: ColourBytes,
    atmosphere_height: f64,
    multi_scattering_factor: f64,
    rayleigh_scattering_scale: f64,
    rayleigh_scattering: LinearColour,
    rayleigh_exponential_distribution: f64,
    mie_scattering_scale: f64,
    mie_scattering: LinearColour,
    mie_absorption_scale: f64,
    mie_absorption: LinearColour,
    mie_anisotropy: f64,
    mie_exponential_distribution: f64,
    other_absorption_scale: f64,
    other_absorption: LinearColour,
    other_tent_distribution: Tent,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct ColourBytes {
    r: u8,
    g: u8,
    b: u8,
    a: u8,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct LinearColour {
    r: f64,
    g: f64,
    b: f64,
    a: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct Tent {
    tip_altitude: f64,
    tip_value: f64,
    width: f64,
}

/// Coefficients per metre as Unreal's scale (km⁻¹, the largest channel) and colour (0–1).
fn scaled(per_m: [f64; 3]) -> (f64, LinearColour) {
    let per_km = per_m.map(|v| v * 1000.0);
    let scale = per_km.iter().copied().fold(0.0, f64::max);
    let c = |v: f64| if scale > 0.0 { v / scale } else { 1.0 };
    (
        scale,
        LinearColour {
            r: c(per_km[0]),
            g: c(per_km[1]),
            b: c(per_km[2]),
            a: 1.0,
        },
    )
}

fn per_m(scale: f64, c: LinearColour) -> [f64; 3] {
    [c.r, c.g, c.b].map(|v| v * scale / 1000.0)
}

/// The sRGB transfer function and its inverse, for the ground albedo's 8-bit colour.
fn to_srgb_byte(linear: f64) -> u8 {
    let l = linear.clamp(0.0, 1.0);
    let v = if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (v * 255.0).round() as u8
}

fn from_srgb_byte(b: u8) -> f64 {
    let v = f64::from(b) / 255.0;
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The component's properties as JSON.
pub fn write(e: &EngineAtmosphere, scene_name: &str) -> String {
    let (rayleigh_scale, rayleigh) = scaled(e.rayleigh_scattering_per_m);
    let (mie_scale, mie) = scaled(e.mie_scattering_per_m);
    let (mie_absorption_scale, mie_absorption) = scaled(e.mie_absorption_per_m);
    let (ozone_scale, ozone) = scaled(e.ozone_absorption_per_m);
    let file = File {
        about: format!(
            "Atmoscope: the atmosphere of \"{scene_name}\" for Unreal Engine's SkyAtmosphere component (km, km^-1; coefficient = scale x colour at 680, 550 and 440 nm), fitted to the scene's physics: air and aerosol as exponentials, ozone as a tent, each keeping its vertical optical depth. Set each property in the Details panel, or from Python with set_editor_property and the snake_case names."
        ),
        sky_atmosphere_component: Properties {
            bottom_radius: e.bottom_radius_m / 1000.0,
            ground_albedo: ColourBytes {
                r: to_srgb_byte(e.ground_albedo[0]),
                g: to_srgb_byte(e.ground_albedo[1]),
                b: to_srgb_byte(e.ground_albedo[2]),
                a: 255,
            },
            atmosphere_height: (e.top_radius_m - e.bottom_radius_m) / 1000.0,
            multi_scattering_factor: 1.0,
            rayleigh_scattering_scale: rayleigh_scale,
            rayleigh_scattering: rayleigh,
            rayleigh_exponential_distribution: e.rayleigh_scale_height_m / 1000.0,
            mie_scattering_scale: mie_scale,
            mie_scattering: mie,
            mie_absorption_scale,
            mie_absorption,
            // Unreal takes 0–0.999.
            mie_anisotropy: e.mie_asymmetry.clamp(0.0, 0.999),
            mie_exponential_distribution: e.mie_scale_height_m / 1000.0,
            other_absorption_scale: ozone_scale,
            other_absorption: ozone,
            other_tent_distribution: Tent {
                tip_altitude: e.ozone_tip_altitude_m / 1000.0,
                tip_value: 1.0,
                width: e.ozone_half_width_m / 1000.0,
            },
        },
    };
    // Plain data: serialising cannot fail.
    serde_json::to_string_pretty(&file).unwrap_or_default() + "\n"
}

/// The atmosphere a JSON of the component's properties sets (every property present).
pub fn read(text: &str) -> anyhow::Result<EngineAtmosphere> {
    let f: File = serde_json::from_str(text).context("not the properties Atmoscope writes")?;
    let p = f.sky_atmosphere_component;
    let t = p.other_tent_distribution;
    let e = EngineAtmosphere {
        bottom_radius_m: p.bottom_radius * 1000.0,
        top_radius_m: (p.bottom_radius + p.atmosphere_height) * 1000.0,
        rayleigh_scattering_per_m: per_m(p.rayleigh_scattering_scale, p.rayleigh_scattering),
        rayleigh_scale_height_m: p.rayleigh_exponential_distribution * 1000.0,
        mie_scattering_per_m: per_m(p.mie_scattering_scale, p.mie_scattering),
        mie_absorption_per_m: per_m(p.mie_absorption_scale, p.mie_absorption),
        mie_scale_height_m: p.mie_exponential_distribution * 1000.0,
        mie_asymmetry: p.mie_anisotropy,
        // A tip value other than 1 scales the whole tent.
        ozone_absorption_per_m: per_m(p.other_absorption_scale * t.tip_value, p.other_absorption),
        ozone_tip_altitude_m: t.tip_altitude * 1000.0,
        ozone_half_width_m: t.width * 1000.0,
        ground_albedo: [p.ground_albedo.r, p.ground_albedo.g, p.ground_albedo.b]
            .map(from_srgb_byte),
    };
    e.check().map_err(|why| anyhow::anyhow!("{why}"))?;
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hillaires_earth_writes_unreals_defaults_and_reads_back() {
        let e = EngineAtmosphere::HILLAIRE_EARTH;
        let text = write(&e, "test");
        let f: File = serde_json::from_str(&text).expect("JSON");
        let p = &f.sky_atmosphere_component;
        // Unreal's own defaults are Hillaire's Earth: 0.0331 km⁻¹ × (0.175287, 0.409607, 1).
        assert!((p.rayleigh_scattering_scale - 0.0331).abs() < 1e-9);
        assert!((p.rayleigh_scattering.r - 0.175287).abs() < 1e-6);
        assert!((p.other_absorption.g - 1.0).abs() < 1e-12);
        assert!((p.other_absorption.r - 0.345561).abs() < 1e-6);
        assert_eq!(p.other_tent_distribution.width, 15.0);
        let back = read(&text).expect("reads");
        for c in 0..3 {
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-12);
            assert!(close(
                back.rayleigh_scattering_per_m[c],
                e.rayleigh_scattering_per_m[c]
            ));
            assert!(close(
                back.ozone_absorption_per_m[c],
                e.ozone_absorption_per_m[c]
            ));
            // 8-bit sRGB: within half a step.
            assert!((back.ground_albedo[c] - 0.3).abs() < 0.003);
        }
        assert!(read(&text.replace("\"BottomRadius\": 6360.0", "\"BottomRadius\": -1.0")).is_err());
        assert!(read("{}").is_err());
    }
}
