//! bevy's `Atmosphere` component (bevy 0.16 and 0.17, `bevy::pbr::Atmosphere`): Hillaire's
//! parameterisation in metres and m⁻¹, the Rayleigh and Mie densities `exp(−h·scale)`, the
//! ozone a tent of full width `ozone_layer_width` about `ozone_layer_altitude`, and a grey
//! aerosol (one scattering and one absorption coefficient for every channel).

use super::number;
use anyhow::{Context, bail};
use atmoscope_model::engine_atmosphere::EngineAtmosphere;

/// The Rust function a bevy user pastes: it returns the scene's atmosphere.
pub fn write(e: &EngineAtmosphere, scene_name: &str) -> String {
    let v = |c: [f64; 3]| {
        format!(
            "Vec3::new({}, {}, {})",
            number(c[0]),
            number(c[1]),
            number(c[2])
        )
    };
    // The aerosol is grey in bevy: the scene's at 550 nm.
    format!(
        "// Atmoscope: the atmosphere of \"{scene_name}\" for bevy 0.16–0.17 (`bevy::pbr::Atmosphere`),\n\
         // fitted to the scene's physics: air and aerosol as exponentials, ozone as a tent, each\n\
         // keeping its vertical optical depth; coefficients at 680, 550 and 440 nm, in m^-1.\n\
         // bevy's aerosol is grey: its coefficients here are the scene's at 550 nm.\n\
         // Use it on the camera: commands.spawn((Camera3d::default(), atmosphere()));\n\
         use bevy::math::Vec3;\n\
         use bevy::pbr::Atmosphere;\n\
         \n\
         pub fn atmosphere() -> Atmosphere {{\n\
         \x20   Atmosphere {{\n\
         \x20       bottom_radius: {},\n\
         \x20       top_radius: {},\n\
         \x20       ground_albedo: {},\n\
         \x20       rayleigh_density_exp_scale: 1.0 / {},\n\
         \x20       rayleigh_scattering: {},\n\
         \x20       mie_density_exp_scale: 1.0 / {},\n\
         \x20       mie_scattering: {},\n\
         \x20       mie_absorption: {},\n\
         \x20       mie_asymmetry: {},\n\
         \x20       ozone_layer_altitude: {},\n\
         \x20       ozone_layer_width: {},\n\
         \x20       ozone_absorption: {},\n\
         \x20   }}\n\
         }}\n",
        number(e.bottom_radius_m),
        number(e.top_radius_m),
        v(e.ground_albedo),
        number(e.rayleigh_scale_height_m),
        v(e.rayleigh_scattering_per_m),
        number(e.mie_scale_height_m),
        number(e.mie_scattering_per_m[1]),
        number(e.mie_absorption_per_m[1]),
        number(e.mie_asymmetry),
        number(e.ozone_tip_altitude_m),
        number(2.0 * e.ozone_half_width_m),
        v(e.ozone_absorption_per_m),
    )
}

/// The atmosphere a bevy snippet sets: every field of the struct, each `name: value,` on a
/// line, a value a number, `1.0 / number` or `Vec3::new(x, y, z)` (or `Vec3::splat(x)`).
pub fn read(text: &str) -> anyhow::Result<EngineAtmosphere> {
    let field = |name: &str| -> anyhow::Result<&str> {
        text.lines()
            .filter_map(|l| l.trim().strip_prefix(name)?.trim_start().strip_prefix(':'))
            .map(|v| v.trim().trim_end_matches(','))
            .next()
            .with_context(|| format!("no field {name}"))
    };
    let scalar = |name: &str| -> anyhow::Result<f64> {
        let v = field(name)?;
        let value = match v.split_once('/') {
            Some((a, b)) => parse(a)? / parse(b)?,
            None => parse(v)?,
        };
        if !value.is_finite() {
            bail!("{name}: {v} is not a finite number");
        }
        Ok(value)
    };
    let vector = |name: &str| -> anyhow::Result<[f64; 3]> {
        let v = field(name)?;
        if let Some(x) = v
            .strip_prefix("Vec3::splat(")
            .and_then(|r| r.strip_suffix(')'))
        {
            return Ok([parse(x)?; 3]);
        }
        let inner = v
            .strip_prefix("Vec3::new(")
            .and_then(|r| r.strip_suffix(')'))
            .with_context(|| format!("{name}: {v} is not Vec3::new(x, y, z)"))?;
        let parts: Vec<f64> = inner.split(',').map(parse).collect::<Result<_, _>>()?;
        <[f64; 3]>::try_from(parts).map_err(|p| anyhow::anyhow!("{name}: {} components", p.len()))
    };
    let grey = |name: &str| -> anyhow::Result<[f64; 3]> { Ok([scalar(name)?; 3]) };
    let half_width = scalar("ozone_layer_width")? / 2.0;
    let e = EngineAtmosphere {
        bottom_radius_m: scalar("bottom_radius")?,
        top_radius_m: scalar("top_radius")?,
        rayleigh_scattering_per_m: vector("rayleigh_scattering")?,
        rayleigh_scale_height_m: 1.0 / scalar("rayleigh_density_exp_scale")?,
        mie_scattering_per_m: grey("mie_scattering")?,
        mie_absorption_per_m: grey("mie_absorption")?,
        mie_scale_height_m: 1.0 / scalar("mie_density_exp_scale")?,
        mie_asymmetry: scalar("mie_asymmetry")?,
        ozone_absorption_per_m: vector("ozone_absorption")?,
        ozone_tip_altitude_m: scalar("ozone_layer_altitude")?,
        ozone_half_width_m: half_width,
        ground_albedo: vector("ground_albedo")?,
    };
    e.check().map_err(|why| anyhow::anyhow!("{why}"))?;
    Ok(e)
}

/// A Rust float literal (`1.5`, `6.5e-7`, `6_360_000.0`).
fn parse(s: &str) -> anyhow::Result<f64> {
    let t = s.trim().replace('_', "");
    let t = t.trim_end_matches("f32").trim_end_matches("f64");
    t.parse()
        .with_context(|| format!("{} is not a number", s.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_snippet_reads_back_as_written_with_a_grey_aerosol() {
        let e = EngineAtmosphere {
            mie_scattering_per_m: [3.0e-6, 4.0e-6, 5.0e-6],
            ..EngineAtmosphere::HILLAIRE_EARTH
        };
        let text = write(&e, "test");
        let back = read(&text).expect("reads");
        let expected = EngineAtmosphere {
            mie_scattering_per_m: [4.0e-6; 3],
            ..e.clone()
        };
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs();
        assert!(close(
            back.rayleigh_scale_height_m,
            expected.rayleigh_scale_height_m
        ));
        assert!(close(back.ozone_half_width_m, expected.ozone_half_width_m));
        for c in 0..3 {
            assert!(close(
                back.rayleigh_scattering_per_m[c],
                expected.rayleigh_scattering_per_m[c]
            ));
            assert!(close(
                back.mie_scattering_per_m[c],
                expected.mie_scattering_per_m[c]
            ));
            assert!(close(
                back.ozone_absorption_per_m[c],
                expected.ozone_absorption_per_m[c]
            ));
        }
        assert!(text.contains("ozone_layer_width: 30000.0,"), "{text}");
        assert!(read("mie_asymmetry: 0.8,").is_err());
        let flat = text.replace(
            "rayleigh_density_exp_scale: 1.0 / 8000.0",
            "rayleigh_density_exp_scale: 0.0",
        );
        assert!(
            read(&flat)
                .unwrap_err()
                .to_string()
                .contains("scale height"),
            "{flat}"
        );
        let broken = text.replace("Vec3::new(0.3, 0.3, 0.3)", "Vec3::new(0.3, 0.3)");
        assert!(read(&broken).is_err(), "{broken}");
    }
}
