//! Blender 5's Sky Texture node, type Multiple Scattering: García Liñán's (2023) model with
//! Blender's own Earth, which the user scales by three densities. At density 1 (Blender's
//! `intern/sky/source/sky_multiple_scattering.cpp`): a planet of 6371 km under 100 km of
//! air; air on García Liñán's fitted profile with 1.067·10⁻⁵ m⁻¹ of Rayleigh scattering at
//! 560 nm at sea level; an aerosol of 730 m scale height with the cross-sections below and
//! Henyey–Greenstein's g = 0.8; García Liñán's log-normal ozone, whose profile integrates to
//! 1.0595 times its nominal 334.5 DU, so 354.4 DU; a grey ground of albedo 0.3.

use anyhow::{Context, bail};
use atmoscope_model::Scene;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::atmosphere::Atmosphere;
use atmoscope_model::ground::GroundType;
use atmoscope_model::profiles::{AirProfile, OzoneProfile};
use atmoscope_model::scene::{AerosolPhase, OzoneColumn};

/// Blender's aerosol at density 1, sea level, at 630, 560, 490 and 430 nm, m⁻¹: its number
/// density 1.3681·10²⁰ times its scattering and absorption cross-sections.
const AEROSOL_SCATTERING_PER_M: [f64; 4] = [2.1763e-5, 2.4231e-5, 2.8651e-5, 3.2880e-5];
const AEROSOL_ABSORPTION_PER_M: [f64; 4] = [3.9294e-7, 6.3163e-7, 1.09046e-6, 1.85761e-6];
const AEROSOL_WAVELENGTHS_NM: [f64; 4] = [630.0, 560.0, 490.0, 430.0];
const AEROSOL_SCALE_HEIGHT_KM: f64 = 0.73;
const AEROSOL_G: f64 = 0.8;
/// Rayleigh scattering at 560 nm at sea level at density 1, m⁻¹.
const MOLECULAR_560_PER_M: f64 = 1.067e-5;
/// The ozone column at density 1, DU.
const OZONE_COLUMN_DU: f64 = 354.4;
const PLANET_RADIUS_KM: f64 = 6371.0;
const TOP_KM: f64 = 100.0;
const GROUND_ALBEDO: f64 = 0.3;
/// The camera altitudes Blender takes, m.
const ALTITUDE_M: (f64, f64) = (1.0, 99_999.0);

/// The node's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct BlenderSky {
    pub sun_elevation_deg: f64,
    /// The sun's azimuth, degrees clockwise from north: Blender 5's rotation, which turns
    /// clockwise from +Y seen from above.
    pub sun_rotation_deg: f64,
    pub altitude_m: f64,
    pub air_density: f64,
    pub aerosol_density: f64,
    pub ozone_density: f64,
}

impl BlenderSky {
    /// Blender's own Earth: every density 1 (the sun 30° high in the south, the camera 1 m up).
    pub const EARTH: BlenderSky = BlenderSky {
        sun_elevation_deg: 30.0,
        sun_rotation_deg: 180.0,
        altitude_m: 1.0,
        air_density: 1.0,
        aerosol_density: 1.0,
        ozone_density: 1.0,
    };

    /// The densities that give Blender's sky the scene's vertical optical depths of air (at
    /// 560 nm) and aerosol (at 550 nm) and its ozone column; the scene's sun and altitude.
    pub fn fit(scene: &Scene, atm: &Atmosphere) -> BlenderSky {
        let blender = Atmosphere::for_scene(&BlenderSky::EARTH.scene(scene));
        let depth = |a: &Atmosphere, w: f64| a.vertical_optical_depth(&a.optics(w), 0.0);
        let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
        let angles = scene.sun.angles();
        BlenderSky {
            sun_elevation_deg: angles.elevation_deg,
            sun_rotation_deg: angles.azimuth_deg,
            altitude_m: scene.camera.altitude_m.clamp(ALTITUDE_M.0, ALTITUDE_M.1),
            air_density: ratio(depth(atm, 560.0).rayleigh, depth(&blender, 560.0).rayleigh),
            aerosol_density: ratio(depth(atm, 550.0).aerosol, depth(&blender, 550.0).aerosol),
            ozone_density: scene
                .atmosphere
                .ozone
                .column_du(scene.atmosphere.top_km * 1000.0)
                / OZONE_COLUMN_DU,
        }
    }

    /// Blender's physics at these densities as a scene, with the base's sun, camera and
    /// display: what the node draws, for our models to draw.
    pub fn scene(&self, base: &Scene) -> Scene {
        let mut s = base.clone();
        let a = &mut s.atmosphere;
        a.planet_radius_km = PLANET_RADIUS_KM;
        a.top_km = TOP_KM;
        a.air_profile = AirProfile::ExponentialFit;
        // Our cross-sections on García Liñán's profile at density 1 against Blender's 560 nm
        // coefficient.
        a.air_density_scale = 1.0;
        let ours = {
            let atm = Atmosphere::new(a);
            atm.optics(560.0).rayleigh_cross_section_m2 * atm.air_density_m3(0.0)
        };
        a.air_density_scale = self.air_density * MOLECULAR_560_PER_M / ours;
        a.rayleigh_depolarisation = true;
        a.ozone.profile = OzoneProfile::Fit;
        a.ozone.column = OzoneColumn::Du(self.ozone_density * OZONE_COLUMN_DU);
        let extinction: Vec<f64> = (0..4)
            .map(|i| AEROSOL_SCATTERING_PER_M[i] + AEROSOL_ABSORPTION_PER_M[i])
            .collect();
        // Ångström's exponent through the ends of the four wavelengths.
        let angstrom = (extinction[3] / extinction[0]).ln()
            / (AEROSOL_WAVELENGTHS_NM[0] / AEROSOL_WAVELENGTHS_NM[3]).ln();
        let ssa_560 = AEROSOL_SCATTERING_PER_M[1] / extinction[1];
        a.aerosol.kind = AerosolType::Custom;
        a.aerosol.phase = AerosolPhase::HenyeyGreenstein;
        a.aerosol.custom.single_scattering_albedo = ssa_560;
        a.aerosol.custom.asymmetry_g = AEROSOL_G;
        a.aerosol.custom.angstrom_exponent = angstrom;
        a.aerosol.custom.scale_height_km = AEROSOL_SCALE_HEIGHT_KM;
        let depth_550 =
            extinction[1] * AEROSOL_SCALE_HEIGHT_KM * 1000.0 * (550.0f64 / 560.0).powf(-angstrom);
        a.aerosol.aod550 = self.aerosol_density * depth_550;
        a.ground = GroundType::Grey;
        a.ground_albedo = GROUND_ALBEDO;
        s
    }
}

/// The Python script a Blender user runs (Scripting workspace, or `blender --python`).
pub fn write(b: &BlenderSky, scene_name: &str) -> String {
    format!(
        "# Atmoscope: the atmosphere of \"{scene_name}\" as Blender 5's Sky Texture, Multiple\n\
         # Scattering. The densities scale Blender's own Earth so that its air (at 560 nm) and\n\
         # aerosol (at 550 nm) have the scene's vertical optical depths and its ozone the scene's\n\
         # column. The sun's rotation is its azimuth, clockwise from +Y seen from above (+Y is\n\
         # north). The sky is linked to the world's background. (Blender 4's Nishita type names\n\
         # the aerosol `dust_density`.)\n\
         import bpy, math\n\
         world = bpy.context.scene.world or bpy.data.worlds.new(\"World\")\n\
         bpy.context.scene.world = world\n\
         world.use_nodes = True\n\
         nodes, links = world.node_tree.nodes, world.node_tree.links\n\
         sky = nodes.get(\"Sky Texture\") or nodes.new(\"ShaderNodeTexSky\")\n\
         background = nodes.get(\"Background\") or nodes.new(\"ShaderNodeBackground\")\n\
         output = nodes.get(\"World Output\") or nodes.new(\"ShaderNodeOutputWorld\")\n\
         links.new(sky.outputs[\"Color\"], background.inputs[\"Color\"])\n\
         links.new(background.outputs[\"Background\"], output.inputs[\"Surface\"])\n\
         sky.sky_type = 'MULTIPLE_SCATTERING'\n\
         sky.sun_elevation = math.radians({:.4})\n\
         sky.sun_rotation = math.radians({:.4})\n\
         sky.altitude = {:.3}\n\
         sky.air_density = {:.5}\n\
         sky.aerosol_density = {:.5}\n\
         sky.ozone_density = {:.5}\n",
        b.sun_elevation_deg,
        b.sun_rotation_deg,
        b.altitude_m,
        b.air_density,
        b.aerosol_density,
        b.ozone_density,
    )
}

/// The node's settings from such a script: each `sky.NAME = VALUE` line, VALUE a number or
/// `math.radians(number)`.
pub fn read(text: &str) -> anyhow::Result<BlenderSky> {
    let value = |name: &str| -> anyhow::Result<f64> {
        let v = text
            .lines()
            .filter_map(|l| {
                l.trim()
                    .strip_prefix("sky.")?
                    .strip_prefix(name)?
                    .trim_start()
                    .strip_prefix('=')
            })
            .next_back()
            .with_context(|| format!("no sky.{name} = …"))?
            .trim();
        let (number, degrees) = match v
            .strip_prefix("math.radians(")
            .and_then(|r| r.strip_suffix(')'))
        {
            Some(n) => (n, true),
            None => (v, false),
        };
        let x: f64 = number
            .trim()
            .parse()
            .with_context(|| format!("sky.{name}: {v} is not a number"))?;
        if !x.is_finite() {
            bail!("sky.{name}: {v} is not finite");
        }
        Ok(if degrees {
            x
        } else if name.starts_with("sun_") {
            x.to_degrees()
        } else {
            x
        })
    };
    let b = BlenderSky {
        sun_elevation_deg: value("sun_elevation")?,
        sun_rotation_deg: value("sun_rotation")?,
        altitude_m: value("altitude")?,
        air_density: value("air_density")?,
        aerosol_density: value("aerosol_density")?,
        ozone_density: value("ozone_density")?,
    };
    // Blender's own ranges.
    for (name, v, max) in [
        ("air_density", b.air_density, 1000.0),
        ("aerosol_density", b.aerosol_density, 1000.0),
        ("ozone_density", b.ozone_density, 1000.0),
        ("altitude", b.altitude_m, 100_000.0),
    ] {
        if !(0.0..=max).contains(&v) {
            bail!("sky.{name} = {v}: Blender takes 0 to {max}");
        }
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blender's own Earth at density 1 fits back to density 1, and the script reads back.
    #[test]
    fn blenders_earth_fits_to_unit_densities_and_the_script_reads_back() {
        let base = Scene::default();
        let earth = BlenderSky::EARTH.scene(&base);
        assert!(earth.validate().is_ok(), "{:?}", earth.validate());
        let fit = BlenderSky::fit(&earth, &Atmosphere::for_scene(&earth));
        for (name, v) in [
            ("air", fit.air_density),
            ("aerosol", fit.aerosol_density),
            ("ozone", fit.ozone_density),
        ] {
            assert!((v - 1.0).abs() < 1e-6, "{name}: {v}");
        }
        // Blender's aerosol at density 1: optical depth about 0.018 at 550 nm.
        assert!((0.017..0.020).contains(&earth.atmosphere.aerosol.aod550));
        let back = read(&write(&fit, "test")).expect("reads");
        assert!((back.sun_elevation_deg - 30.0).abs() < 1e-4);
        assert!((back.air_density - 1.0).abs() < 1e-5);
        let script = write(&fit, "test");
        let dense = script.replace("sky.air_density = 1.00000", "sky.air_density = 2000");
        assert!(
            read(&dense).unwrap_err().to_string().contains("0 to 1000"),
            "{dense}"
        );
        let broken = script.replace("sky.ozone_density = 1.00000", "sky.ozone_density = x");
        assert!(read(&broken).is_err());
        // The default scene needs more aerosol than Blender's Earth has, and about its air.
        let default = BlenderSky::fit(&base, &Atmosphere::for_scene(&base));
        assert!(default.aerosol_density > 3.0, "{default:?}");
        assert!((0.9..1.15).contains(&default.air_density), "{default:?}");
    }
}
