//! The scene options every scene-taking subcommand shares: a preset, named overrides for the
//! common fields, and `--set PATH=VALUE` for any other field.

use crate::presets::load_shipped;
use anyhow::{Context, bail};
use atmoscope_model::Scene;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::ground::GroundType;
use atmoscope_model::profiles::{AirProfile, OzoneProfile};
use atmoscope_model::scene::limits::{self, Limit};
use atmoscope_model::scene::{OzoneColumn, SunSettings};
use clap::Args;
use std::path::PathBuf;

/// `--help` text of a ranged option, the range read from its one home (`scene::limits`).
fn ranged(text: &str, l: Limit) -> String {
    format!("{text} ({} to {}{})", l.min, l.max, l.unit)
}

#[derive(Args, Debug, Default, Clone)]
pub struct SceneArgs {
    /// Preset file (.ron), or the name of a shipped preset (see `atmoscope presets list`).
    /// Without it the built-in default scene is used.
    #[arg(long, value_name = "FILE")]
    pub preset: Option<PathBuf>,
    #[arg(long, value_name = "M", allow_hyphen_values = true, help = ranged("Camera height above the ground", limits::CAMERA_ALTITUDE_M))]
    pub altitude_m: Option<f64>,
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, help = ranged("A polarising filter on the camera, its transmission axis from up in the picture towards right", limits::CAMERA_POLARISER_DEG))]
    pub polariser: Option<f64>,
    /// Sun zenith angle, degrees (0 to 180).
    #[arg(
        long,
        value_name = "DEG",
        conflicts_with = "sun_elevation_deg",
        allow_hyphen_values = true
    )]
    pub sun_zenith_deg: Option<f64>,
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, help = ranged("Sun elevation above the horizon", limits::SUN_ELEVATION_DEG))]
    pub sun_elevation_deg: Option<f64>,
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, help = ranged("Sun azimuth clockwise from north", limits::SUN_AZIMUTH_DEG))]
    pub sun_azimuth_deg: Option<f64>,
    /// Aerosol type: none, background, desert-dust, maritime-clean, maritime-mineral,
    /// polar-antarctic, polar-arctic, remote-continental, rural, urban, custom. Sets the
    /// type's typical AOD unless --aod550 is given.
    #[arg(long, value_name = "TYPE")]
    pub aerosol: Option<String>,
    #[arg(long, value_name = "TAU", allow_hyphen_values = true, help = ranged("Aerosol optical depth at 550 nm", limits::AOD550))]
    pub aod550: Option<f64>,
    /// Month 1–12: sets the total ozone column to that month's mean at Arosa (47° N), or with
    /// --ozone-latitude the zonal mean at that latitude.
    #[arg(
        long,
        value_name = "1-12",
        allow_hyphen_values = true,
        conflicts_with = "ozone_du"
    )]
    pub month: Option<u32>,
    /// Latitude, degrees north (−90 to 90): sets the total ozone column to the zonal mean
    /// there (AFGL 1986 climatology) in --month (else the scene's month, else June); with the
    /// sun placed by date and place, its latitude and month win.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        conflicts_with = "ozone_du"
    )]
    pub ozone_latitude: Option<f64>,
    #[arg(long, value_name = "DU", allow_hyphen_values = true, help = ranged("Total ozone column", limits::OZONE_COLUMN_DU))]
    pub ozone_du: Option<f64>,
    #[arg(long, value_name = "A", allow_hyphen_values = true, conflicts_with = "ground", help = ranged("Albedo of a grey ground (sets the ground grey)", limits::GROUND_ALBEDO))]
    pub albedo: Option<f64>,
    /// Ground type, its measured spectral albedo used by every model and the path tracer:
    /// grey (the scene's albedo at every wavelength), fresh-snow, grass, desert-sand,
    /// dry-soil, ocean.
    #[arg(long, value_name = "TYPE")]
    pub ground: Option<String>,
    /// Air density profile: us-standard-1976, afgl-us-standard, afgl-tropical,
    /// afgl-midlatitude-summer, afgl-midlatitude-winter, afgl-subarctic-summer,
    /// afgl-subarctic-winter, exponential-fit, exponential-8km.
    #[arg(long, value_name = "NAME")]
    pub air_profile: Option<String>,
    /// Ozone profile: an AFGL name (keeps its own column unless --ozone-du or --month is
    /// given), guimera, fit, or tent.
    #[arg(long, value_name = "NAME")]
    pub ozone_profile: Option<String>,
    #[arg(long, value_name = "K", allow_hyphen_values = true, help = ranged("Temperature of the ozone cross-section", limits::OZONE_TEMPERATURE_K))]
    pub ozone_temperature_k: Option<f64>,
    #[arg(long, value_name = "KM", allow_hyphen_values = true, help = ranged("Planet radius", limits::PLANET_RADIUS_KM))]
    pub planet_radius_km: Option<f64>,
    #[arg(long, value_name = "KM", allow_hyphen_values = true, help = ranged("Height of the top of the atmosphere", limits::TOP_KM))]
    pub top_km: Option<f64>,
    #[arg(long, value_name = "X", allow_hyphen_values = true, help = ranged("Factor on the air's density at every height (Earth 1)", limits::AIR_DENSITY_SCALE))]
    pub air_density_scale: Option<f64>,
    /// Any other scene field by its dotted path, value as JSON or a bare word, e.g.
    /// `--set camera.fov_deg=50`, `--set atmosphere.aerosol.phase=CornetteShanks`. Repeatable.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
}

fn names<T: Copy>(all: &[T], name: fn(T) -> &'static str) -> String {
    all.iter().map(|&t| name(t)).collect::<Vec<_>>().join(", ")
}

impl SceneArgs {
    /// The scene: the preset (or default) with every override applied, validated.
    pub fn scene(&self) -> anyhow::Result<Scene> {
        let mut scene = match &self.preset {
            None => Scene::default(),
            Some(p) if p.exists() => Scene::load(p)?,
            Some(p) => {
                let name = p.to_string_lossy();
                let file = if name.ends_with(".ron") {
                    name.to_string()
                } else {
                    format!("{name}.ron")
                };
                match load_shipped(&file) {
                    Some(result) => result?,
                    None => bail!(
                        "{}: no such file, nor a shipped preset (see `atmoscope presets list`)",
                        p.display()
                    ),
                }
            }
        };
        self.apply(&mut scene)?;
        scene.tie_ozone_to_sun();
        scene.validate().map_err(|errors| {
            let list = errors
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ");
            anyhow::anyhow!("the scene after the command-line overrides is invalid: {list}")
        })?;
        Ok(scene)
    }

    fn apply(&self, scene: &mut Scene) -> anyhow::Result<()> {
        let atm = &mut scene.atmosphere;
        if let Some(v) = self.planet_radius_km {
            atm.planet_radius_km = v;
        }
        if let Some(v) = self.air_density_scale {
            atm.air_density_scale = v;
        }
        if let Some(v) = self.top_km {
            atm.top_km = v;
        }
        if let Some(name) = &self.air_profile {
            atm.air_profile = AirProfile::from_cli_name(name).with_context(|| {
                format!(
                    "--air-profile {name}: unknown; choose one of {}",
                    names(&AirProfile::all(), AirProfile::cli_name)
                )
            })?;
        }
        if let Some(name) = &self.aerosol {
            let kind = AerosolType::from_cli_name(name).with_context(|| {
                format!(
                    "--aerosol {name}: unknown; choose one of {}",
                    names(&AerosolType::ALL, AerosolType::cli_name)
                )
            })?;
            atm.aerosol.kind = kind;
            atm.aerosol.aod550 = kind.default_aod550();
        }
        if let Some(v) = self.aod550 {
            atm.aerosol.aod550 = v;
        }
        if let Some(name) = &self.ozone_profile {
            let profile = OzoneProfile::from_cli_name(name).with_context(|| {
                format!(
                    "--ozone-profile {name}: unknown; choose one of {}",
                    names(&OzoneProfile::all(), OzoneProfile::cli_name)
                )
            })?;
            atm.ozone.profile = profile;
            match profile {
                OzoneProfile::Afgl(_) => atm.ozone.column = OzoneColumn::Profile,
                _ if atm.ozone.column == OzoneColumn::Profile => {
                    atm.ozone.column = OzoneColumn::Month(6)
                }
                _ => {}
            }
        }
        match (self.ozone_latitude, self.month) {
            (Some(latitude_deg), month) => {
                let month = month.unwrap_or(match atm.ozone.column {
                    OzoneColumn::Month(m) | OzoneColumn::Zonal { month: m, .. } => m,
                    _ => 6,
                });
                atm.ozone.column = OzoneColumn::Zonal {
                    latitude_deg,
                    month,
                };
            }
            (None, Some(m)) => match &mut atm.ozone.column {
                OzoneColumn::Zonal { month, .. } => *month = m,
                column => *column = OzoneColumn::Month(m),
            },
            (None, None) => {}
        }
        if let Some(du) = self.ozone_du {
            atm.ozone.column = OzoneColumn::Du(du);
        }
        if let Some(t) = self.ozone_temperature_k {
            atm.ozone.temperature_k = t;
        }
        if let Some(a) = self.albedo {
            atm.ground_albedo = a;
            atm.ground = GroundType::Grey;
        }
        if let Some(name) = &self.ground {
            atm.ground = GroundType::from_cli_name(name).with_context(|| {
                format!(
                    "--ground {name}: unknown; choose one of {}",
                    names(&GroundType::ALL, GroundType::cli_name)
                )
            })?;
        }
        if let Some(angle) = self.polariser {
            scene.camera.polariser_deg = Some(angle);
        }
        if let Some(h) = self.altitude_m {
            scene.camera.altitude_m = h;
        }
        let elevation = self
            .sun_elevation_deg
            .or(self.sun_zenith_deg.map(|z| 90.0 - z));
        if elevation.is_some() || self.sun_azimuth_deg.is_some() {
            // Named angles switch a date-placed sun to angles, starting where it stood.
            let now = scene.sun.angles();
            scene.sun = SunSettings::Angles {
                elevation_deg: elevation.unwrap_or(now.elevation_deg),
                azimuth_deg: self.sun_azimuth_deg.unwrap_or(now.azimuth_deg),
            };
        }
        for assignment in &self.set {
            let Some((path, value)) = assignment.split_once('=') else {
                bail!("--set {assignment}: expected PATH=VALUE, e.g. camera.fov_deg=50");
            };
            scene.set_path(path.trim(), value.trim())?;
        }
        Ok(())
    }
}
