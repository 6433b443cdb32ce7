//! The scene: everything a user sets, and the RON preset format.
//!
//! Every struct is `#[serde(default)]`, so a preset names only what it changes, and unknown
//! fields are rejected so a typo never passes silently. `version` guards against presets from
//! a newer Atmoscope. `validate` checks every number against its documented range and reports
//! the field's path; loading names the file, and parse errors carry the line, column and path.

use crate::aerosol::AerosolType;
use crate::constants::{EARTH_ATMOSPHERE_TOP_M, EARTH_RADIUS_M};
use crate::ground::GroundType;
use crate::ozone::{self, OzoneCrossSection};
use crate::profiles::{AirProfile, OzoneProfile};
use crate::solar_spectrum::SolarSpectrum;
use crate::sun_position::{self, DateTime, SunAngles};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};

/// Highest camera altitude, m (100 000 km: the Moon's distance is 3.8e8 m, geostationary orbit
/// 3.6e7 m).
pub const MAX_CAMERA_ALTITUDE_M: f64 = 1e8;

/// The preset format version this build reads and writes.
pub const SCENE_VERSION: u32 = 1;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Scene {
    /// Preset format version (this build: 1).
    pub version: u32,
    pub name: String,
    pub description: String,
    pub atmosphere: AtmosphereSettings,
    pub sun: SunSettings,
    pub camera: CameraSettings,
    pub render: RenderSettings,
    pub display: DisplaySettings,
}

impl Default for Scene {
    /// The built-in default scene: a clear rural afternoon seen from the ground.
    fn default() -> Scene {
        Scene {
            version: SCENE_VERSION,
            name: "Default".into(),
            description: "Rural aerosol, June ozone, sun 30° high, camera on the ground.".into(),
            atmosphere: AtmosphereSettings::default(),
            sun: SunSettings::default(),
            camera: CameraSettings::default(),
            render: RenderSettings::default(),
            display: DisplaySettings::default(),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AtmosphereSettings {
    /// Planet radius, km (1000–100 000; Earth 6360).
    pub planet_radius_km: f64,
    /// Height of the top of the atmosphere above the ground, km (10–1000; Earth 100).
    pub top_km: f64,
    pub air_profile: AirProfile,
    /// Factor on the air profile's density at every height (0.001–10; Earth 1): thinner or
    /// denser air of the same composition, for other worlds (Mars' surface air is about 1/60
    /// of Earth's).
    pub air_density_scale: f64,
    /// Use the wavelength-dependent depolarisation of air in the Rayleigh phase function.
    pub rayleigh_depolarisation: bool,
    pub aerosol: AerosolSettings,
    pub ozone: OzoneSettings,
    /// Lambertian ground albedo (0–1) of the grey ground.
    pub ground_albedo: f64,
    /// The ground's surface: grey (`ground_albedo` at every wavelength) or a measured
    /// spectral albedo (`ground::GroundType`).
    pub ground: GroundType,
    pub solar_spectrum: SolarSpectrum,
}

impl Default for AtmosphereSettings {
    fn default() -> Self {
        AtmosphereSettings {
            planet_radius_km: EARTH_RADIUS_M / 1000.0,
            top_km: EARTH_ATMOSPHERE_TOP_M / 1000.0,
            air_profile: AirProfile::default(),
            air_density_scale: 1.0,
            rayleigh_depolarisation: true,
            aerosol: AerosolSettings::default(),
            ozone: OzoneSettings::default(),
            ground_albedo: 0.3,
            ground: GroundType::Grey,
            solar_spectrum: SolarSpectrum::default(),
        }
    }
}

/// Aerosol phase function model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum AerosolPhase {
    #[default]
    HenyeyGreenstein,
    CornetteShanks,
    /// The type's own phase function from the Mie code, tabulated (`aerosol::type_phase`):
    /// the forward peak and back-scatter a one-parameter function misses. Not for Custom.
    Mie,
}

impl AerosolPhase {
    /// The phase function (sr⁻¹) at scattering cosine `nu` for asymmetry `g`, with the type's
    /// tabulated Mie phase `mie` at `wavelength_nm` where this is `Mie` (Henyey–Greenstein if
    /// the type has none).
    pub fn value(
        self,
        mie: Option<&crate::aerosol::MiePhase>,
        wavelength_nm: f64,
        g: f64,
        nu: f64,
    ) -> f64 {
        match (self, mie) {
            (AerosolPhase::CornetteShanks, _) => crate::phase::cornette_shanks(nu, g),
            (AerosolPhase::Mie, Some(m)) => m.phase(wavelength_nm, nu),
            _ => crate::phase::henyey_greenstein(nu, g),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AerosolSettings {
    pub kind: AerosolType,
    /// Aerosol optical depth at 550 nm, vertical, ground to top (0–5).
    pub aod550: f64,
    pub phase: AerosolPhase,
    /// Used when `kind` is Custom.
    pub custom: CustomAerosol,
}

impl Default for AerosolSettings {
    fn default() -> Self {
        AerosolSettings {
            kind: AerosolType::Rural,
            aod550: AerosolType::Rural.default_aod550(),
            phase: AerosolPhase::default(),
            custom: CustomAerosol::default(),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CustomAerosol {
    /// Single-scattering albedo (0–1).
    pub single_scattering_albedo: f64,
    /// Asymmetry parameter g (−0.95–0.95).
    pub asymmetry_g: f64,
    /// Ångström exponent α: extinction ∝ (λ/550 nm)^−α (−1–4).
    pub angstrom_exponent: f64,
    /// Scale height of the exponential profile, km (0.1–100).
    pub scale_height_km: f64,
}

impl Default for CustomAerosol {
    fn default() -> Self {
        CustomAerosol {
            single_scattering_albedo: 0.9,
            asymmetry_g: 0.7,
            angstrom_exponent: 1.3,
            scale_height_km: 1.2,
        }
    }
}

/// Where the total ozone column comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum OzoneColumn {
    /// Monthly mean at Arosa (Dütsch 1973), month 1–12.
    Month(u32),
    /// Set directly, Dobson units (0–1000).
    Du(f64),
    /// The column of the chosen AFGL profile itself.
    Profile,
    /// Zonal mean at a latitude (−90–90°, north positive) in a month (1–12), from the AFGL
    /// standard atmospheres (`ozone::zonal_column_du`). With the sun placed by date and place,
    /// both follow the sun's (`Scene::tie_ozone_to_sun`).
    Zonal { latitude_deg: f64, month: u32 },
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OzoneSettings {
    pub profile: OzoneProfile,
    pub column: OzoneColumn,
    pub cross_section: OzoneCrossSection,
    /// Temperature of the ozone cross-section, K (203–293; Bogumil only).
    pub temperature_k: f64,
}

impl Default for OzoneSettings {
    fn default() -> Self {
        OzoneSettings {
            profile: OzoneProfile::default(),
            column: OzoneColumn::Month(6),
            cross_section: OzoneCrossSection::default(),
            temperature_k: 233.0,
        }
    }
}

impl OzoneSettings {
    /// The total column this setting stands for, DU, given the atmosphere's top.
    pub fn column_du(&self, top_m: f64) -> f64 {
        match self.column {
            OzoneColumn::Month(m) => ozone::monthly_column_du(m).unwrap_or(300.0),
            OzoneColumn::Du(du) => du,
            OzoneColumn::Profile => self.profile.native_column_du(top_m).unwrap_or(300.0),
            OzoneColumn::Zonal {
                latitude_deg,
                month,
            } => ozone::zonal_column_du(latitude_deg, month).unwrap_or(300.0),
        }
    }
}

/// Where the sun is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SunSettings {
    /// Elevation above the horizon (−90–90°) and azimuth clockwise from north (0–360°).
    Angles {
        elevation_deg: f64,
        azimuth_deg: f64,
    },
    /// From date, time and place (NOAA solar position).
    Date {
        time: DateTime,
        /// Latitude, degrees north (−90–90).
        latitude_deg: f64,
        /// Longitude, degrees east (−180–180).
        longitude_deg: f64,
    },
}

impl Default for SunSettings {
    fn default() -> Self {
        SunSettings::Angles {
            elevation_deg: 30.0,
            azimuth_deg: 180.0,
        }
    }
}

impl SunSettings {
    /// The sun's elevation and azimuth.
    pub fn angles(&self) -> SunAngles {
        match *self {
            SunSettings::Angles {
                elevation_deg,
                azimuth_deg,
            } => SunAngles {
                elevation_deg,
                azimuth_deg,
            },
            SunSettings::Date {
                time,
                latitude_deg,
                longitude_deg,
            } => sun_position::position(&time, latitude_deg, longitude_deg),
        }
    }

    /// The Earth–Sun distance, AU: from the date when the sun is placed by date, else the
    /// mean distance (1 AU), at which the solar spectra are tabulated.
    pub fn distance_au(&self) -> f64 {
        match self {
            SunSettings::Angles { .. } => 1.0,
            SunSettings::Date { time, .. } => sun_position::distance_au(time.julian_day()),
        }
    }

    /// Sunlight at the scene's Earth–Sun distance over that at 1 AU: 1/d² (0.967–1.034).
    /// The real-time models hold sunlight at 1 AU in their optics and tables and draw their
    /// radiance times this (every one is linear in the sunlight), so a sun moving by date
    /// and time moves only what its direction moves.
    pub fn sunlight_scale(&self) -> f64 {
        self.distance_au().powi(-2)
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraSettings {
    /// Height above the ground, m (0–100 000 km = 1e8 m).
    pub altitude_m: f64,
    /// View direction clockwise from north, degrees (0–360).
    pub heading_deg: f64,
    /// View elevation above the horizon, degrees (−90–90).
    pub pitch_deg: f64,
    /// Vertical field of view, degrees (1–170).
    pub fov_deg: f64,
    /// Distance the camera is moved back over the planet's surface against its heading, km
    /// (0–20 000), keeping its altitude; the sun stays fixed in the scene's frame.
    pub back_km: f64,
    /// A linear polarising filter in front of the lens (a photographer's circular polariser
    /// acts on the scene as one): None for none, else the angle of its transmission axis,
    /// degrees (−90–90) from up in the picture towards right (left in the fisheye, which shows
    /// the dome as from above). It passes (I + Q·cos 2θ + U·sin 2θ)/2 of the real-time sky's
    /// light (`methods::shared::polarisation`): half of unpolarised light, like a real filter's
    /// factor of one stop, which metered exposure makes up.
    pub polariser_deg: Option<f64>,
}

impl Default for CameraSettings {
    fn default() -> Self {
        CameraSettings {
            altitude_m: 1.0,
            heading_deg: 180.0,
            pitch_deg: 10.0,
            fov_deg: 70.0,
            back_km: 0.0,
            polariser_deg: None,
        }
    }
}

/// Rendering method: a row of the model registry (`methods::MODELS`), which says what each is.
/// Written as the variant's name (`Bruneton`); read back also by its registry id, as the
/// command line spells it (`--set render.method=garcia-linan`; in a RON preset, where an
/// identifier cannot hold a hyphen, `method: garcia_linan`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Default)]
pub enum Method {
    #[default]
    Hillaire,
    Bruneton,
    GarciaLinan,
    Elek,
    Nishita,
    Trapezoid,
    NishitaMs,
    TrapezoidMs,
    Schuler,
    SchulerMs,
    GalajTaylor,
    GalajTaylorMs,
    GalajSpline,
    GalajSplineMs,
    Flat,
    Raymarched,
    ONeil,
    Nishita96,
    Haber,
    Preetham,
    HosekWilkie,
    CieStandardSky,
    Empty,
    PathTracer,
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Method, D::Error> {
        use serde::de::{self, EnumAccess, VariantAccess, Visitor};
        use std::fmt;

        /// A model's name where an enum's variant stands: an identifier in RON, a string in
        /// JSON (`--set render.method=bruneton`).
        struct Name(String);
        impl<'de> Deserialize<'de> for Name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Name, D::Error> {
                struct NameVisitor;
                impl Visitor<'_> for NameVisitor {
                    type Value = Name;
                    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                        f.write_str("a model's name")
                    }
                    fn visit_str<E: de::Error>(self, s: &str) -> Result<Name, E> {
                        Ok(Name(s.to_string()))
                    }
                }
                d.deserialize_identifier(NameVisitor)
            }
        }

        struct MethodVisitor;
        impl<'de> Visitor<'de> for MethodVisitor {
            type Value = Method;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a model: its registry id or name")
            }
            fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<Method, A::Error> {
                let (Name(name), variant) = data.variant()?;
                variant.unit_variant()?;
                Method::from_name(&name).ok_or_else(|| {
                    let ids: Vec<&str> = crate::methods::MODELS.iter().map(|m| m.id).collect();
                    de::Error::custom(format!(
                        "unknown model `{name}`, expected one of {}",
                        ids.join(", ")
                    ))
                })
            }
        }

        deserializer.deserialize_enum("Method", &[], MethodVisitor)
    }
}

impl Method {
    /// The method a user named: its registry id (`garcia-linan`, or `garcia_linan` where a
    /// hyphen cannot stand, as in a RON identifier) or its variant's name (`GarciaLinan`).
    pub fn from_name(name: &str) -> Option<Method> {
        crate::methods::MODELS
            .iter()
            .find(|m| {
                m.id == name || m.id.replace('-', "_") == name || format!("{:?}", m.method) == name
            })
            .map(|m| m.method)
    }
}

/// Wavelengths a render samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum WavelengthSet {
    /// 680/550/440 nm used directly as linear sRGB.
    Rgb3,
    /// Four wavelengths with a 3×4 matrix to sRGB (García Liñán 2023's method; the wavelengths
    /// and matrix fitted by `atmoscope fit-wavelengths`).
    Spectral4,
    /// N evenly spaced bands over 360–830 nm, N a multiple of 4 (4–128).
    SpectralN(u32),
}

impl WavelengthSet {
    /// Whether the set is one this build renders: SpectralN needs N a multiple of 4 in 4–128.
    pub fn is_valid(self) -> bool {
        match self {
            WavelengthSet::SpectralN(n) => n % 4 == 0 && (4..=128).contains(&n),
            _ => true,
        }
    }

    /// The set's name as shown: RGB3, Spectral4, Spectral32.
    pub fn label(self) -> String {
        match self {
            WavelengthSet::Rgb3 => "RGB3".into(),
            WavelengthSet::Spectral4 => "Spectral4".into(),
            WavelengthSet::SpectralN(n) => format!("Spectral{n}"),
        }
    }
}

impl Default for WavelengthSet {
    fn default() -> Self {
        WavelengthSet::Spectral4
    }
}

/// Quality presets: the real-time method's ray-marching sample counts (×1, ×2, ×4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum Quality {
    Low,
    #[default]
    Medium,
    High,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RenderSettings {
    pub method: Method,
    pub wavelengths: WavelengthSet,
    pub quality: Quality,
    /// Scattering orders of the models that gather them one by one (Bruneton, Elek), 1–10.
    pub scattering_orders: u32,
    /// Which fitted constants the models that have them use (García Liñán's L_ms).
    pub fitted_constants: FittedConstants,
    /// Which of the CIE standard general sky's 15 types (CIE S 011 / ISO 15469) the
    /// `cie-standard-sky` model draws, 1–15: 1 the overcast sky, 12 the standard clear sky.
    pub cie_sky_type: u8,
}

/// The CIE sky type by default: 12, the CIE standard clear sky.
pub const DEFAULT_CIE_SKY_TYPE: u8 = 12;

/// The source of a model's fitted constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum FittedConstants {
    /// As the model's author published them.
    #[default]
    Published,
    /// Refitted by this project against the path tracer over the view suite
    /// (`atmoscope fit-garcia-linan`), shipped in `model/data`.
    Refit,
}

/// Scattering orders by default: six, where Bruneton 2017 gathers four. In a hazy sky the
/// orders beyond the fourth still add a visible share of the blue near the horizon, so four
/// leave the sky too dark there against the path tracer; past six the gain is small for the
/// added precompute of every further order.
pub const DEFAULT_SCATTERING_ORDERS: u32 = 6;

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            method: Method::default(),
            wavelengths: WavelengthSet::default(),
            quality: Quality::default(),
            scattering_orders: DEFAULT_SCATTERING_ORDERS,
            fitted_constants: FittedConstants::default(),
            cie_sky_type: DEFAULT_CIE_SKY_TYPE,
        }
    }
}

/// Tone mapping from linear radiance to display.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum ToneMap {
    /// 1 − exp(−k·L), as in the papers.
    #[default]
    Exponential,
    /// The ACES filmic curve as fitted by Narkowicz (2015), per channel.
    Filmic,
    /// AgX (Sobotka), in its widely used polynomial fit: bright colours bleach towards white
    /// the way film does instead of skewing in hue.
    AgX,
    /// Khronos PBR Neutral (2024): colours pass unchanged up to 0.76, only highlights are
    /// compressed and desaturated.
    PbrNeutral,
    /// Exposure only, clipped.
    Linear,
}

impl ToneMap {
    pub const ALL: [ToneMap; 5] = [
        ToneMap::Exponential,
        ToneMap::Filmic,
        ToneMap::AgX,
        ToneMap::PbrNeutral,
        ToneMap::Linear,
    ];

    pub fn label(self) -> &'static str {
        match self {
            ToneMap::Exponential => "Exponential (papers)",
            ToneMap::Filmic => "ACES (fitted)",
            ToneMap::AgX => "AgX",
            ToneMap::PbrNeutral => "Khronos PBR Neutral",
            ToneMap::Linear => "Linear (clip)",
        }
    }

    /// What the curve does to colour, for a tooltip.
    pub fn describe(self) -> &'static str {
        match self {
            ToneMap::Exponential => {
                "1 − e^(−x) per channel, as Bruneton and Hillaire display their skies: soft highlights, \
                 bright colours drift towards the hue of their strongest channel."
            }
            ToneMap::Filmic => {
                "Narkowicz's fit of the ACES film curve per channel: more contrast and a toe in the \
                 shadows; saturated highlights shift in hue (a red sun turns orange-yellow)."
            }
            ToneMap::AgX => {
                "Sobotka's AgX: a log encoding and a sigmoid in a slightly desaturated space, so \
                 bright colours fade to white as on film while hues hold; lower contrast."
            }
            ToneMap::PbrNeutral => {
                "Khronos PBR Neutral: below 0.76 colours are shown as they are (only a small black \
                 offset); brighter ones are compressed and desaturated towards white."
            }
            ToneMap::Linear => {
                "No curve: exposure, then clipped at 1. What a measurement wants; highlights burn out."
            }
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DisplaySettings {
    /// Exposure in stops (−20–20). With `auto_exposure` the explorer sets it from the view.
    pub exposure_ev: f64,
    /// Meter the view: the exposure that puts its log-average luminance at mid-grey, plus
    /// `compensation_ev`, adapting over about half a second in the explorer.
    pub auto_exposure: bool,
    /// Added to the metered exposure, stops (−10–10).
    pub compensation_ev: f64,
    pub tone_map: ToneMap,
    /// Dither the 8-bit image (triangular noise of up to one step per pixel) so that smooth
    /// gradients do not band; off for byte-exact comparisons.
    pub dither: bool,
    /// Which light the display shows as white (`model::white_balance`).
    pub white_balance: WhiteBalance,
    /// Add the eye's veiling glare around the sun to what is shown (`model::display::glare`):
    /// a display effect for pictures; the radiance, and so every measurement, stays without.
    pub glare: bool,
}

/// The light a display shows as white.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub enum WhiteBalance {
    /// D65, the sRGB white: colours as measured.
    #[default]
    None,
    /// The sun's direct light at the ground when overhead, through the scene's atmosphere.
    SunAtNoon,
    /// A blackbody at this colour temperature, K (1000–40 000).
    Temperature { kelvin: f64 },
}

impl Default for DisplaySettings {
    fn default() -> Self {
        DisplaySettings {
            exposure_ev: 0.0,
            auto_exposure: false,
            compensation_ev: 0.0,
            tone_map: ToneMap::default(),
            dither: true,
            white_balance: WhiteBalance::default(),
            glare: false,
        }
    }
}

/// One field out of range.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Dotted path of the field, e.g. `atmosphere.aerosol.aod550`.
    pub path: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

/// Largest preset file read, bytes: a preset is a few kilobytes of RON; a longer file is not
/// one, and a pipe or a device is never read.
pub const MAX_PRESET_BYTES: u64 = 1 << 20;

/// Why a scene could not be loaded, parsed or accepted.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    // The cause is part of the message and not a `source`: error chains would print it twice.
    #[error("{file}: cannot read: {error}")]
    Io {
        file: PathBuf,
        error: std::io::Error,
    },
    #[error("{file}: cannot write: {error}")]
    Write {
        file: PathBuf,
        error: std::io::Error,
    },
    #[error("{file}:{line}:{column}: {path}{message}")]
    Parse {
        file: PathBuf,
        line: usize,
        column: usize,
        path: String,
        message: String,
    },
    #[error(
        "{file}: preset version {found} is newer than this Atmoscope reads (up to {supported}); update Atmoscope"
    )]
    NewerVersion {
        file: PathBuf,
        found: u32,
        supported: u32,
    },
    #[error("{file}: {}", join_errors(.errors))]
    Invalid {
        file: PathBuf,
        errors: Vec<FieldError>,
    },
    #[error("--set {assignment}: {message}")]
    Override { assignment: String, message: String },
}

fn join_errors(errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// The allowed range of every numeric scene field: its one home, read by `Scene::validate`,
/// the explorer's sliders and the command line's messages.
pub mod limits {
    use super::MAX_CAMERA_ALTITUDE_M;
    use crate::ozone;

    /// An inclusive range with the unit its values are given in.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Limit {
        pub min: f64,
        pub max: f64,
        /// Suffix of a value, with its leading space (" km"), or empty.
        pub unit: &'static str,
    }

    impl Limit {
        pub fn range(&self) -> std::ops::RangeInclusive<f64> {
            self.min..=self.max
        }

        pub fn contains(&self, v: f64) -> bool {
            v >= self.min && v <= self.max
        }
    }

    /// `atmosphere.planet_radius_km`.
    pub const PLANET_RADIUS_KM: Limit = Limit {
        min: 1000.0,
        max: 100_000.0,
        unit: " km",
    };
    /// `atmosphere.top_km`.
    pub const TOP_KM: Limit = Limit {
        min: 10.0,
        max: 1000.0,
        unit: " km",
    };
    /// `atmosphere.air_density_scale`.
    pub const AIR_DENSITY_SCALE: Limit = Limit {
        min: 0.001,
        max: 10.0,
        unit: "",
    };
    /// `atmosphere.ground_albedo`.
    pub const GROUND_ALBEDO: Limit = Limit {
        min: 0.0,
        max: 1.0,
        unit: "",
    };
    /// `atmosphere.aerosol.aod550`.
    pub const AOD550: Limit = Limit {
        min: 0.0,
        max: 5.0,
        unit: "",
    };
    /// `atmosphere.aerosol.custom.single_scattering_albedo`.
    pub const CUSTOM_AEROSOL_SSA: Limit = Limit {
        min: 0.0,
        max: 1.0,
        unit: "",
    };
    /// `atmosphere.aerosol.custom.asymmetry_g`.
    pub const CUSTOM_AEROSOL_G: Limit = Limit {
        min: -0.95,
        max: 0.95,
        unit: "",
    };
    /// `atmosphere.aerosol.custom.angstrom_exponent`.
    pub const CUSTOM_AEROSOL_ANGSTROM: Limit = Limit {
        min: -1.0,
        max: 4.0,
        unit: "",
    };
    /// `atmosphere.aerosol.custom.scale_height_km`.
    pub const CUSTOM_AEROSOL_SCALE_HEIGHT_KM: Limit = Limit {
        min: 0.1,
        max: 100.0,
        unit: " km",
    };
    /// `atmosphere.ozone.temperature_k`.
    pub const OZONE_TEMPERATURE_K: Limit = Limit {
        min: ozone::TEMPERATURE_RANGE_K.0,
        max: ozone::TEMPERATURE_RANGE_K.1,
        unit: " K",
    };
    /// `atmosphere.ozone.column.Du`.
    pub const OZONE_COLUMN_DU: Limit = Limit {
        min: 0.0,
        max: 1000.0,
        unit: " DU",
    };
    /// `sun.Angles.elevation_deg`.
    pub const SUN_ELEVATION_DEG: Limit = Limit {
        min: -90.0,
        max: 90.0,
        unit: "°",
    };
    /// `sun.Angles.azimuth_deg`.
    pub const SUN_AZIMUTH_DEG: Limit = Limit {
        min: 0.0,
        max: 360.0,
        unit: "°",
    };
    /// `sun.Date.time.year`.
    pub const DATE_YEAR: Limit = Limit {
        min: 1900.0,
        max: 2100.0,
        unit: "",
    };
    /// `sun.Date.time.month`.
    pub const DATE_MONTH: Limit = Limit {
        min: 1.0,
        max: 12.0,
        unit: "",
    };
    /// `sun.Date.time.day`.
    pub const DATE_DAY: Limit = Limit {
        min: 1.0,
        max: 31.0,
        unit: "",
    };
    /// `sun.Date.time.hour` (24 is the next day's 0: refused, so a date names one instant).
    pub const DATE_HOUR: Limit = Limit {
        min: 0.0,
        max: 23.99,
        unit: " h",
    };
    /// `sun.Date.time.utc_offset_h`.
    pub const DATE_UTC_OFFSET_H: Limit = Limit {
        min: -12.0,
        max: 14.0,
        unit: " h",
    };
    /// `sun.Date.latitude_deg`.
    pub const LATITUDE_DEG: Limit = Limit {
        min: -90.0,
        max: 90.0,
        unit: "°",
    };
    /// `sun.Date.longitude_deg`.
    pub const LONGITUDE_DEG: Limit = Limit {
        min: -180.0,
        max: 180.0,
        unit: "°",
    };
    /// `camera.altitude_m`.
    pub const CAMERA_ALTITUDE_M: Limit = Limit {
        min: 0.0,
        max: MAX_CAMERA_ALTITUDE_M,
        unit: " m",
    };
    /// `camera.heading_deg`.
    pub const CAMERA_HEADING_DEG: Limit = Limit {
        min: 0.0,
        max: 360.0,
        unit: "°",
    };
    /// `camera.pitch_deg`.
    pub const CAMERA_PITCH_DEG: Limit = Limit {
        min: -90.0,
        max: 90.0,
        unit: "°",
    };
    /// `camera.fov_deg`.
    pub const CAMERA_FOV_DEG: Limit = Limit {
        min: 1.0,
        max: 170.0,
        unit: "°",
    };
    /// `camera.polariser_deg`.
    pub const CAMERA_POLARISER_DEG: Limit = Limit {
        min: -90.0,
        max: 90.0,
        unit: "°",
    };
    /// `camera.back_km`.
    pub const CAMERA_BACK_KM: Limit = Limit {
        min: 0.0,
        max: 20_000.0,
        unit: " km",
    };
    /// `display.exposure_ev`.
    pub const EXPOSURE_EV: Limit = Limit {
        min: -20.0,
        max: 20.0,
        unit: " EV",
    };
    /// `display.white_balance`'s colour temperature.
    pub const WHITE_BALANCE_KELVIN: Limit = Limit {
        min: 1000.0,
        max: 40000.0,
        unit: " K",
    };
    /// `display.compensation_ev`.
    pub const COMPENSATION_EV: Limit = Limit {
        min: -10.0,
        max: 10.0,
        unit: " EV",
    };
    /// `render.scattering_orders`.
    pub const SCATTERING_ORDERS: Limit = Limit {
        min: 1.0,
        max: 10.0,
        unit: "",
    };
    /// `render.cie_sky_type`.
    pub const CIE_SKY_TYPE: Limit = Limit {
        min: 1.0,
        max: 15.0,
        unit: "",
    };
}

struct Checker {
    errors: Vec<FieldError>,
}

impl Checker {
    fn range(&mut self, path: &str, value: f64, min: f64, max: f64, unit: &str) {
        if !(value >= min && value <= max) {
            self.errors.push(FieldError {
                path: path.into(),
                message: format!("is {value}{unit}, allowed {min}{unit} to {max}{unit}"),
            });
        }
    }

    fn limit(&mut self, path: &str, value: f64, l: limits::Limit) {
        self.range(path, value, l.min, l.max, l.unit);
    }

    fn fail(&mut self, path: &str, message: String) {
        self.errors.push(FieldError {
            path: path.into(),
            message,
        });
    }
}

/// Days in `month` (1–12) of `year` in the Gregorian calendar.
fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        2 if (year % 4 == 0 && year % 100 != 0) || year % 400 == 0 => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

impl Scene {
    /// Checks every field against its range; returns all problems at once.
    pub fn validate(&self) -> Result<(), Vec<FieldError>> {
        let mut c = Checker { errors: vec![] };
        if self.version == 0 {
            c.fail("version", format!("is 0, allowed 1 to {SCENE_VERSION}"));
        }
        if self.version > SCENE_VERSION {
            c.fail(
                "version",
                format!(
                    "is {}, this build reads up to {SCENE_VERSION}",
                    self.version
                ),
            );
        }
        let a = &self.atmosphere;
        c.limit(
            "atmosphere.planet_radius_km",
            a.planet_radius_km,
            limits::PLANET_RADIUS_KM,
        );
        c.limit("atmosphere.top_km", a.top_km, limits::TOP_KM);
        c.limit(
            "atmosphere.air_density_scale",
            a.air_density_scale,
            limits::AIR_DENSITY_SCALE,
        );
        c.limit(
            "atmosphere.ground_albedo",
            a.ground_albedo,
            limits::GROUND_ALBEDO,
        );
        c.limit(
            "atmosphere.aerosol.aod550",
            a.aerosol.aod550,
            limits::AOD550,
        );
        if a.aerosol.phase == AerosolPhase::Mie && a.aerosol.kind == AerosolType::Custom {
            c.fail(
                "atmosphere.aerosol.phase",
                "Mie needs a type built from OPAC components; Custom has none: choose \
                 HenyeyGreenstein or CornetteShanks"
                    .to_string(),
            );
        }
        let ca = &a.aerosol.custom;
        c.limit(
            "atmosphere.aerosol.custom.single_scattering_albedo",
            ca.single_scattering_albedo,
            limits::CUSTOM_AEROSOL_SSA,
        );
        c.limit(
            "atmosphere.aerosol.custom.asymmetry_g",
            ca.asymmetry_g,
            limits::CUSTOM_AEROSOL_G,
        );
        c.limit(
            "atmosphere.aerosol.custom.angstrom_exponent",
            ca.angstrom_exponent,
            limits::CUSTOM_AEROSOL_ANGSTROM,
        );
        c.limit(
            "atmosphere.aerosol.custom.scale_height_km",
            ca.scale_height_km,
            limits::CUSTOM_AEROSOL_SCALE_HEIGHT_KM,
        );
        let o = &a.ozone;
        c.limit(
            "atmosphere.ozone.temperature_k",
            o.temperature_k,
            limits::OZONE_TEMPERATURE_K,
        );
        match o.column {
            OzoneColumn::Month(m) if !(1..=12).contains(&m) => {
                c.fail("atmosphere.ozone.column.Month", format!("is {m}, allowed 1 to 12"))
            }
            OzoneColumn::Du(du) => c.limit("atmosphere.ozone.column.Du", du, limits::OZONE_COLUMN_DU),
            OzoneColumn::Profile if !matches!(o.profile, OzoneProfile::Afgl(_)) => c.fail(
                "atmosphere.ozone.column",
                format!("Profile needs an AFGL ozone profile, the profile is {:?}; give Month(m) or Du(x)", o.profile),
            ),
            OzoneColumn::Zonal {
                latitude_deg,
                month,
            } => {
                c.limit("atmosphere.ozone.column.Zonal.latitude_deg", latitude_deg, limits::LATITUDE_DEG);
                if !(1..=12).contains(&month) {
                    c.fail("atmosphere.ozone.column.Zonal.month", format!("is {month}, allowed 1 to 12"));
                }
            }
            _ => {}
        }
        match self.sun {
            SunSettings::Angles {
                elevation_deg,
                azimuth_deg,
            } => {
                c.limit(
                    "sun.Angles.elevation_deg",
                    elevation_deg,
                    limits::SUN_ELEVATION_DEG,
                );
                c.limit(
                    "sun.Angles.azimuth_deg",
                    azimuth_deg,
                    limits::SUN_AZIMUTH_DEG,
                );
            }
            SunSettings::Date {
                time,
                latitude_deg,
                longitude_deg,
            } => {
                c.limit("sun.Date.time.year", time.year as f64, limits::DATE_YEAR);
                c.limit("sun.Date.time.month", time.month as f64, limits::DATE_MONTH);
                c.limit("sun.Date.time.day", time.day as f64, limits::DATE_DAY);
                let last = days_in_month(time.year, time.month);
                if (1..=12).contains(&time.month) && time.day > last && time.day <= 31 {
                    c.fail(
                        "sun.Date.time.day",
                        format!(
                            "is {}, but month {} of {} has {last} days",
                            time.day, time.month, time.year
                        ),
                    );
                }
                c.limit("sun.Date.time.hour", time.hour, limits::DATE_HOUR);
                c.limit(
                    "sun.Date.time.utc_offset_h",
                    time.utc_offset_h,
                    limits::DATE_UTC_OFFSET_H,
                );
                c.limit("sun.Date.latitude_deg", latitude_deg, limits::LATITUDE_DEG);
                c.limit(
                    "sun.Date.longitude_deg",
                    longitude_deg,
                    limits::LONGITUDE_DEG,
                );
            }
        }
        let cam = &self.camera;
        c.limit(
            "camera.altitude_m",
            cam.altitude_m,
            limits::CAMERA_ALTITUDE_M,
        );
        c.limit(
            "camera.heading_deg",
            cam.heading_deg,
            limits::CAMERA_HEADING_DEG,
        );
        c.limit("camera.pitch_deg", cam.pitch_deg, limits::CAMERA_PITCH_DEG);
        c.limit("camera.fov_deg", cam.fov_deg, limits::CAMERA_FOV_DEG);
        c.limit("camera.back_km", cam.back_km, limits::CAMERA_BACK_KM);
        if let Some(angle) = cam.polariser_deg {
            c.limit("camera.polariser_deg", angle, limits::CAMERA_POLARISER_DEG);
        }
        if let WavelengthSet::SpectralN(n) = self.render.wavelengths {
            if !self.render.wavelengths.is_valid() {
                c.fail(
                    "render.wavelengths.SpectralN",
                    format!("is {n}, allowed a multiple of 4 from 4 to 128"),
                );
            }
        }
        c.limit(
            "render.scattering_orders",
            f64::from(self.render.scattering_orders),
            limits::SCATTERING_ORDERS,
        );
        c.limit(
            "render.cie_sky_type",
            f64::from(self.render.cie_sky_type),
            limits::CIE_SKY_TYPE,
        );
        c.limit(
            "display.exposure_ev",
            self.display.exposure_ev,
            limits::EXPOSURE_EV,
        );
        if let WhiteBalance::Temperature { kelvin } = self.display.white_balance {
            c.limit(
                "display.white_balance.kelvin",
                kelvin,
                limits::WHITE_BALANCE_KELVIN,
            );
        }
        c.limit(
            "display.compensation_ev",
            self.display.compensation_ev,
            limits::COMPENSATION_EV,
        );
        if c.errors.is_empty() {
            Ok(())
        } else {
            Err(c.errors)
        }
    }

    /// With the sun placed by date and place and a zonal-mean ozone column, gives the column
    /// the sun's latitude and month, so that the ozone follows the date and place the sky is
    /// drawn for. Returns whether anything changed.
    pub fn tie_ozone_to_sun(&mut self) -> bool {
        let (
            SunSettings::Date {
                time, latitude_deg, ..
            },
            OzoneColumn::Zonal {
                latitude_deg: lat,
                month,
            },
        ) = (self.sun, &mut self.atmosphere.ozone.column)
        else {
            return false;
        };
        let changed = *lat != latitude_deg || *month != time.month;
        *lat = latitude_deg;
        *month = time.month;
        changed
    }

    /// Parses RON text; `file` names the source in messages. A UTF-8 byte-order mark (which
    /// some editors write) is skipped.
    pub fn from_ron(text: &str, file: &Path) -> Result<Scene, SceneError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        #[derive(Deserialize)]
        struct VersionOnly {
            #[serde(default)]
            version: u32,
        }
        let parse_error = |e: ron::error::SpannedError, path: String| SceneError::Parse {
            file: file.into(),
            line: e.span.start.line,
            column: e.span.start.col,
            path,
            message: e.code.to_string(),
        };
        // A newer preset may have fields this build does not know: say "newer", not "unknown".
        let options = ron::Options::default();
        if let Ok(v) = options.from_str::<VersionOnly>(text) {
            if v.version > SCENE_VERSION {
                return Err(SceneError::NewerVersion {
                    file: file.into(),
                    found: v.version,
                    supported: SCENE_VERSION,
                });
            }
        }
        let mut de =
            ron::Deserializer::from_str(text).map_err(|e| parse_error(e, String::new()))?;
        let mut scene: Scene = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." {
                String::new()
            } else {
                format!("{path}: ")
            };
            let inner = e.into_inner();
            let span = de.span_error(inner);
            parse_error(span, path)
        })?;
        de.end()
            .map_err(|e| parse_error(de.span_error(e), String::new()))?;
        scene.tie_ozone_to_sun();
        scene.validate().map_err(|errors| SceneError::Invalid {
            file: file.into(),
            errors,
        })?;
        Ok(scene)
    }

    /// Reads and validates a preset file: a regular file of at most [`MAX_PRESET_BYTES`].
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = crate::files::read_text_limited(path, MAX_PRESET_BYTES).map_err(|error| {
            SceneError::Io {
                file: path.into(),
                error,
            }
        })?;
        Scene::from_ron(&text, path)
    }

    /// The scene as pretty RON.
    pub fn to_ron(&self) -> String {
        let config = ron::ser::PrettyConfig::new()
            .struct_names(false)
            .depth_limit(4);
        ron::ser::to_string_pretty(self, config)
            .unwrap_or_else(|e| format!("// cannot serialise scene: {e}"))
    }

    /// Writes the scene as RON, atomically (the file is replaced whole or not at all).
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        let text = self.to_ron() + "\n";
        crate::files::write_atomic(path, text.as_bytes()).map_err(|error| SceneError::Write {
            file: path.into(),
            error,
        })
    }

    /// Sets the field at a dotted `path` (e.g. `atmosphere.aerosol.aod550`) to `value`, given as
    /// JSON (`0.3`, `true`, `{"Month":6}`) or as a bare word taken as a string (`DesertDust`).
    /// The result is validated; on any error the scene is left unchanged.
    pub fn set_path(&mut self, path: &str, value: &str) -> Result<(), SceneError> {
        let assignment = format!("{path}={value}");
        let fail = |message: String| SceneError::Override {
            assignment: assignment.clone(),
            message,
        };
        let mut tree = serde_json::to_value(&*self).map_err(|e| fail(e.to_string()))?;
        let parsed: serde_json::Value = serde_json::from_str(value)
            .unwrap_or_else(|_| serde_json::Value::String(value.to_string()));
        let mut node = &mut tree;
        let keys: Vec<&str> = path.split('.').collect();
        for (i, key) in keys.iter().enumerate() {
            let object = node.as_object_mut().ok_or_else(|| {
                fail(format!(
                    "`{}` is not a group of fields",
                    keys[..i].join(".")
                ))
            })?;
            if !object.contains_key(*key) {
                // Switching an enum's variant (e.g. sun.Date while sun is Angles) replaces it whole.
                let known: Vec<String> = object.keys().cloned().collect();
                if i + 1 == keys.len()
                    && known.len() == 1
                    && key.chars().next().is_some_and(char::is_uppercase)
                {
                    object.clear();
                } else {
                    return Err(fail(format!(
                        "no field `{key}` here; fields: {}",
                        known.join(", ")
                    )));
                }
                object.insert(key.to_string(), serde_json::Value::Null);
            }
            node = object
                .get_mut(*key)
                .ok_or_else(|| fail(format!("no field `{key}`")))?;
        }
        *node = parsed;
        let mut scene: Scene = serde_json::from_value(tree).map_err(|e| fail(e.to_string()))?;
        scene.tie_ozone_to_sun();
        scene
            .validate()
            .map_err(|errors| fail(join_errors(&errors)))?;
        *self = scene;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Scene, SceneError> {
        Scene::from_ron(text, Path::new("test.ron"))
    }

    #[test]
    fn default_scene_is_valid_and_round_trips() {
        let s = Scene::default();
        s.validate().unwrap();
        assert_eq!(parse(&s.to_ron()).unwrap(), s);
    }

    #[test]
    fn impossible_dates_version_zero_are_refused_and_a_byte_order_mark_is_read() {
        let date = |y: i32, m: u32, d: u32, h: f64| {
            format!(
                "(sun: Date(time: (year: {y}, month: {m}, day: {d}, hour: {h}, utc_offset_h: 0.0), latitude_deg: 46.8, longitude_deg: 9.7))"
            )
        };
        let e = parse(&date(2025, 2, 31, 12.0)).unwrap_err().to_string();
        assert!(
            e.contains("sun.Date.time.day") && e.contains("has 28 days"),
            "{e}"
        );
        assert!(parse(&date(2024, 2, 29, 12.0)).is_ok(), "a leap day");
        assert!(
            parse(&date(2100, 2, 29, 12.0)).is_err(),
            "2100 is no leap year"
        );
        assert!(parse(&date(2025, 4, 31, 12.0)).is_err());
        let e = parse(&date(2025, 6, 21, 24.0)).unwrap_err().to_string();
        assert!(e.contains("sun.Date.time.hour"), "{e}");
        assert!(parse(&date(2025, 12, 31, 23.5)).is_ok());
        let e = parse("(version: 0)").unwrap_err().to_string();
        assert!(e.contains("version") && e.contains("is 0"), "{e}");
        let good = Scene::default().to_ron();
        assert_eq!(parse(&format!("\u{feff}{good}")).unwrap(), Scene::default());
    }

    #[test]
    fn empty_preset_is_the_default_scene() {
        assert_eq!(parse("()").unwrap(), Scene::default());
    }

    #[test]
    fn out_of_range_names_file_field_and_range() {
        let e = parse("(atmosphere: (aerosol: (aod550: 7.5)))")
            .unwrap_err()
            .to_string();
        assert!(e.contains("test.ron"), "{e}");
        assert!(e.contains("atmosphere.aerosol.aod550"), "{e}");
        assert!(e.contains("7.5") && e.contains("0 to 5"), "{e}");
    }

    #[test]
    fn malformed_preset_names_line_and_field() {
        let e = parse("(\n  atmosphere: (\n    ground_albedo: \"white\",\n  ),\n)").unwrap_err();
        match &e {
            SceneError::Parse { line, path, .. } => {
                assert_eq!(*line, 3, "{e}");
                assert!(path.contains("atmosphere.ground_albedo"), "{e}");
            }
            other => panic!("expected a parse error, got {other}"),
        }
        let e = parse("(camera: (altitud_m: 3.0))").unwrap_err().to_string();
        assert!(e.contains("altitud_m"), "{e}");
    }

    #[test]
    fn newer_version_is_refused_clearly() {
        let e = parse("(version: 9, future_field: 1)").unwrap_err();
        assert!(
            matches!(e, SceneError::NewerVersion { found: 9, .. }),
            "{e}"
        );
    }

    #[test]
    fn set_path_changes_one_field_and_validates() {
        let mut s = Scene::default();
        s.set_path("atmosphere.aerosol.aod550", "0.4").unwrap();
        assert_eq!(s.atmosphere.aerosol.aod550, 0.4);
        s.set_path("atmosphere.aerosol.kind", "DesertDust").unwrap();
        assert_eq!(s.atmosphere.aerosol.kind, AerosolType::DesertDust);
        s.set_path("atmosphere.ozone.column", r#"{"Du":280}"#)
            .unwrap();
        assert_eq!(s.atmosphere.ozone.column, OzoneColumn::Du(280.0));
        let before = s.clone();
        assert!(s.set_path("atmosphere.ground_albedo", "1.5").is_err());
        assert!(s.set_path("atmosphere.nope", "1").is_err());
        assert!(
            s.set_path("render.wavelengths", r#"{"SpectralN":30}"#)
                .is_err()
        );
        assert_eq!(s, before, "a failed override changes nothing");
    }

    /// A model is read by its registry id as well as by its variant's name: in a preset, in
    /// `--set` and in old presets alike; an unknown name lists the ids.
    #[test]
    fn a_model_is_read_by_its_registry_id_or_its_name() {
        let mut s = Scene::default();
        for (written, method) in [
            ("bruneton", Method::Bruneton),
            ("garcia-linan", Method::GarciaLinan),
            ("GalajSplineMs", Method::GalajSplineMs),
            ("galaj-spline-ms", Method::GalajSplineMs),
        ] {
            s.set_path("render.method", written).unwrap();
            assert_eq!(s.render.method, method, "--set render.method={written}");
        }
        let err = s.set_path("render.method", "bruneton-2099").unwrap_err();
        assert!(err.to_string().contains("garcia-linan"), "{err}");
        for (written, method) in [
            ("Bruneton", Method::Bruneton),
            ("bruneton", Method::Bruneton),
            ("garcia_linan", Method::GarciaLinan),
        ] {
            let mut preset = Scene::default();
            preset.render.method = Method::Hillaire;
            let text = preset
                .to_ron()
                .replace("method: Hillaire", &format!("method: {written}"));
            assert_ne!(text, preset.to_ron(), "the preset names its method");
            let read = Scene::from_ron(&text, Path::new("test.ron")).unwrap();
            assert_eq!(read.render.method, method, "method: {written}");
        }
        let written = Scene::from_ron(&Scene::default().to_ron(), Path::new("a.ron")).unwrap();
        assert_eq!(written, Scene::default(), "a written preset reads back");
    }

    /// With the sun placed by date and place, a zonal-mean ozone column takes the sun's
    /// latitude and month, from a preset, an override or an edit; placed by angles, it keeps
    /// its own. Out-of-range latitudes and months are refused.
    #[test]
    fn zonal_ozone_follows_the_sun_placed_by_date() {
        let file = Path::new("zonal.ron");
        let text = "(atmosphere: (ozone: (column: Zonal(latitude_deg: 45.0, month: 1))), \
            sun: Date(time: (year: 2024, month: 1, day: 15, hour: 12.0, utc_offset_h: 0.0), \
            latitude_deg: -45.0, longitude_deg: 0.0))";
        let s = Scene::from_ron(text, file).unwrap();
        let column = s.atmosphere.ozone.column;
        assert_eq!(
            column,
            OzoneColumn::Zonal {
                latitude_deg: -45.0,
                month: 1
            }
        );
        // Southern summer: less ozone than the north's January.
        let top_m = s.atmosphere.top_km * 1000.0;
        let north = OzoneSettings {
            column: OzoneColumn::Zonal {
                latitude_deg: 45.0,
                month: 1,
            },
            ..s.atmosphere.ozone.clone()
        };
        assert!(s.atmosphere.ozone.column_du(top_m) < north.column_du(top_m) - 30.0);

        let mut t = s.clone();
        t.set_path("sun.Date.time.month", "7").unwrap();
        assert_eq!(
            t.atmosphere.ozone.column,
            OzoneColumn::Zonal {
                latitude_deg: -45.0,
                month: 7
            }
        );
        let mut angles = Scene::default();
        angles.atmosphere.ozone.column = OzoneColumn::Zonal {
            latitude_deg: 10.0,
            month: 3,
        };
        assert!(!angles.tie_ozone_to_sun());
        assert!(angles.validate().is_ok());
        angles.atmosphere.ozone.column = OzoneColumn::Zonal {
            latitude_deg: 95.0,
            month: 13,
        };
        assert_eq!(angles.validate().unwrap_err().len(), 2);
    }

    /// The Mie phase function comes from a type's OPAC components: Custom has none and is
    /// refused with it, naming the field; every mixture type takes it.
    #[test]
    fn the_mie_phase_needs_a_mixture_type() {
        let mut s = Scene::default();
        s.set_path("atmosphere.aerosol.phase", "Mie").unwrap();
        let e = s.set_path("atmosphere.aerosol.kind", "Custom").unwrap_err();
        assert!(e.to_string().contains("atmosphere.aerosol.phase"), "{e}");
        assert_eq!(s.atmosphere.aerosol.kind, AerosolType::Rural);
    }

    #[test]
    fn set_path_switches_sun_mode() {
        let mut s = Scene::default();
        s.set_path(
            "sun.Date",
            r#"{"time":{"year":2024,"month":6,"day":21,"hour":12,"utc_offset_h":2},"latitude_deg":46.8,"longitude_deg":9.7}"#,
        )
        .unwrap();
        let a = s.sun.angles();
        assert!(a.elevation_deg > 60.0 && a.elevation_deg < 70.0, "{a:?}");
    }
}
