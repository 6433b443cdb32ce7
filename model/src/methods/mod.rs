//! Sky models and the registry that lists them, one row each. Everything that offers a choice of
//! model — the Scene panel, the command line, Compare, the LUT tab, the benchmarks and the tests
//! — iterates [`MODELS`]; nothing else lists models.
//!
//! A model is its registry row, its CPU twin here (`methods/<model>/`, one file per GPU pass,
//! implementing [`SkyModel`]), its shaders (`shaders/<model>/`) and its passes as data
//! (`render/src/methods/<model>.rs`). What table-based models share is in [`shared`]. The path
//! tracer is the ground truth every model is measured against; it has a row (the scene can name
//! it) but no real-time passes.

pub mod bruneton;
pub mod cie_standard_sky;
pub mod elek;
pub mod empty;
pub mod flat;
pub mod galaj_spline;
pub mod galaj_taylor;
pub mod garcia_linan;
pub mod haber;
pub mod hillaire;
pub mod hosek_wilkie;
pub mod nishita;
pub mod nishita_96;
pub mod oneil;
pub mod path_tracer;
pub mod preetham;
pub mod raymarched;
pub mod rng;
pub mod schuler;
pub mod shared;
pub mod single_scattering;
pub mod trapezoid;

use crate::atmosphere::Atmosphere;
use crate::camera::{Camera, Projection};
use crate::geometry::direction_from_angles;
use crate::scene::{Method, Scene};
use crate::wavelengths::{WavelengthBatch, to_linear_srgb};
use glam::DVec3;
use rayon::prelude::*;
use shared::single_scattering_sky;
use shared::{Lanes, Lut, Params, TableSpec, Viewpoint};

/// What a pass or a table can depend on in a scene; a set of these is a bit mask. The engine
/// compares them between frames and reruns exactly the passes that read something that changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Inputs(u8);

impl Inputs {
    pub const NONE: Inputs = Inputs(0);
    /// Atmosphere settings but the ground albedo, model, wavelength set and quality.
    pub const ATMOSPHERE: Inputs = Inputs(1);
    /// The camera's altitude and the sun's zenith angle there (what the view tables depend on).
    pub const VIEWPOINT: Inputs = Inputs(2);
    /// The sun's direction in the world, and the strength of its light at the scene's
    /// Earth–Sun distance (`SunSettings::sunlight_scale`).
    pub const SUN: Inputs = Inputs(4);
    /// The camera's position, orientation, field of view and projection.
    pub const CAMERA: Inputs = Inputs(8);
    pub const VIEW_SIZE: Inputs = Inputs(16);
    /// Exposure, tone map and display mode.
    pub const DISPLAY: Inputs = Inputs(32);
    /// The ground's albedo: the sky pass draws the ground with it, and the tables of the
    /// models whose multiple scattering bounces off the ground hold it.
    pub const GROUND_ALBEDO: Inputs = Inputs(64);
    pub const ALL: Inputs = Inputs(127);

    pub const fn union(self, other: Inputs) -> Inputs {
        Inputs(self.0 | other.0)
    }

    pub fn intersects(self, other: Inputs) -> bool {
        self.0 & other.0 != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Names of the inputs in the set, for documentation and the UI.
    pub fn names(self) -> Vec<&'static str> {
        [
            (Inputs::ATMOSPHERE, "atmosphere"),
            (Inputs::VIEWPOINT, "camera altitude and sun elevation"),
            (Inputs::SUN, "sun direction and distance"),
            (Inputs::CAMERA, "camera"),
            (Inputs::VIEW_SIZE, "view size"),
            (Inputs::DISPLAY, "display"),
            (Inputs::GROUND_ALBEDO, "ground albedo"),
        ]
        .into_iter()
        .filter(|(i, _)| self.intersects(*i))
        .map(|(_, n)| n)
        .collect()
    }
}

/// Where a model is meant to work. Views outside it still render (and are marked as such), so a
/// user can see how a model fails, unless the model refuses them ([`Domain::refuses`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// Highest camera altitude, m (`f64::INFINITY`: anywhere).
    pub max_altitude_m: f64,
    /// Lowest sun elevation, degrees (−90: twilight and night included).
    pub min_sun_elevation_deg: f64,
    /// One sentence on the domain and why.
    pub note: &'static str,
    /// Highest aerosol optical depth at 550 nm (`f64::INFINITY`: any): the largest AOD at
    /// which the model's sky radiance stays within [`AOD_RANGE_ERROR`] of the path tracer on
    /// average (`atmoscope bench aod` measures it; above it the error grows with the AOD);
    /// 0 when no AOD is inside (single scattering alone is too dark even in clean air).
    pub max_aod550: f64,
    /// Whether the model refuses to draw a view outside its altitude and sun range (a fit
    /// that means nothing there) instead of drawing it marked.
    pub refuses: bool,
}

/// What the project states of a real-time model against the path tracer, per registry row:
/// the research tier (`tests/cli.rs`, `render/tests/stress.rs`) holds every model to it, so a
/// model added to the registry states its bounds in its row and nowhere else. The measured
/// values behind each bound are logged in `docs/measurements/stated-bounds.md`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stated {
    /// Highest mean ΔE2000 at Spectral4 (at each view's exposure, against the shipped
    /// path-traced references, whose noise it includes) on any daylight view of the suite in
    /// the model's domain, `atmoscope bench accuracy`; None: a baseline, held to being far off
    /// instead. 0 to ∞.
    pub daylight_delta_e2000: Option<f64>,
    /// The same on the twilight views; None: the model's domain has no twilight.
    pub twilight_delta_e2000: Option<f64>,
    /// Highest |relative error| of the diffuse sky radiance against the path tracer in a hazy
    /// daylight sky (rural aerosol, AOD 0.15, sun 30° up, camera at the ground),
    /// `atmoscope probe`; None: the model draws no sky. 0 to ∞.
    pub probe_relative_error: Option<f64>,
    /// Scenes drawn per run of the stress test: fewer for twins that take seconds to build.
    pub stress_cases: u32,
}

impl Stated {
    /// For the path tracer, which is the ground truth the others are held to.
    pub const NONE: Stated = Stated {
        daylight_delta_e2000: None,
        twilight_delta_e2000: None,
        probe_relative_error: None,
        stress_cases: 0,
    };
}

/// The mean relative error of sky radiance against the path tracer that bounds a model's AOD
/// range (rural aerosol, sun at 30° and 5°, 48 directions and 3 wavelengths).
pub const AOD_RANGE_ERROR: f64 = 0.25;

/// Camera altitude below which a view is a ground view, m.
pub const GROUND_VIEW_MAX_ALTITUDE_M: f64 = 2_000.0;
/// Camera altitude below which a view is a plane view, m (above: space).
pub const PLANE_VIEW_MAX_ALTITUDE_M: f64 = 20_000.0;

impl Domain {
    /// Everywhere: the ground, planes, space and twilight.
    pub const EVERYWHERE: Domain = Domain {
        max_altitude_m: f64::INFINITY,
        min_sun_elevation_deg: -90.0,
        note: "ground, plane, space and twilight views",
        max_aod550: f64::INFINITY,
        refuses: false,
    };

    /// The kinds of view the domain covers: ground, plane, space, twilight.
    pub fn kinds(&self) -> Vec<&'static str> {
        let mut k = vec!["ground"];
        if self.max_altitude_m > GROUND_VIEW_MAX_ALTITUDE_M {
            k.push("plane");
        }
        if self.max_altitude_m > PLANE_VIEW_MAX_ALTITUDE_M {
            k.push("space");
        }
        if self.min_sun_elevation_deg < 0.0 {
            k.push("twilight");
        }
        k
    }

    /// Why a view from `altitude_m` with the sun at `sun_elevation_deg` lies outside the
    /// domain, or None when it is inside.
    pub fn excludes(&self, altitude_m: f64, sun_elevation_deg: f64) -> Option<String> {
        if altitude_m > self.max_altitude_m {
            Some(format!(
                "camera at {:.0} m is above this model's domain (up to {:.0} m): {}",
                altitude_m, self.max_altitude_m, self.note
            ))
        } else if sun_elevation_deg < self.min_sun_elevation_deg {
            Some(format!(
                "sun at {sun_elevation_deg:.1}° is below this model's domain (from {:.1}°): {}",
                self.min_sun_elevation_deg, self.note
            ))
        } else {
            None
        }
    }

    /// Why an aerosol optical depth `aod550` lies outside the model's AOD range, or None. A
    /// model whose range is empty (`max_aod550` 0) is outside it at any AOD.
    pub fn excludes_aod(&self, aod550: f64) -> Option<String> {
        if self.max_aod550 <= 0.0 {
            return Some(format!(
                "this model has no AOD range: its sky stays more than {:.0} % from the path tracer's even without aerosol ({})",
                AOD_RANGE_ERROR * 100.0,
                self.note
            ));
        }
        (aod550 > self.max_aod550).then(|| {
            format!(
                "AOD {aod550:.2} is above this model's range (up to {:.2}, where its sky stays within {:.0} % of the path tracer); more aerosol darkens it further",
                self.max_aod550,
                AOD_RANGE_ERROR * 100.0
            )
        })
    }

    /// Why `scene` lies outside the domain, by its view or its aerosol, or None.
    pub fn excludes_scene(&self, scene: &crate::Scene) -> Option<String> {
        let a = &scene.atmosphere.aerosol;
        let aod550 = if a.kind == crate::aerosol::AerosolType::None {
            0.0
        } else {
            a.aod550
        };
        self.excludes(scene.camera.altitude_m, sun_elevation_at_camera_deg(scene))
            .or_else(|| self.excludes_aod(aod550))
    }
}

/// A model's CPU twin for one scene's optics and viewpoint: its tables and the radiance of any
/// direction, in f64. `probe`, the Inspector and the tests use it.
pub trait SkyModel: Send + Sync {
    /// The optics the model was built for.
    fn params(&self) -> &Params;

    /// Radiance of batch `layer` (W·m⁻²·sr⁻¹·nm⁻¹ per lane) of the sky and the ground seen from
    /// `position` (m from the planet's centre, at altitude `h`, m) along the unit direction
    /// `dir`, with the sun in the unit direction `sun`; the sun's disk is [`SkyModel::sun`].
    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes;

    /// [`SkyModel::radiance`] as the moving sky tabulates it (`shared::moving_sky`): the
    /// same but for the nested marches, whose way to the sun is looked up in their
    /// `sun-route` table there (`single_scattering_sky::Way::tabulated_in_motion`).
    fn radiance_in_motion(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        self.radiance(layer, at, dir, sun)
    }

    /// One of the model's tables by its registry id.
    fn table(&self, id: &str) -> Option<&Lut>;

    /// Moves the twin to viewpoint `vp` by rebuilding only what depends on it, where that is
    /// cheap next to the rest (Bruneton's and Elek's camera slices); false where the model
    /// cannot, and the caller builds it again.
    fn move_to(&mut self, _vp: Viewpoint) -> bool {
        false
    }

    /// The turbidity a fit takes from the scene (`OpticalDepth::turbidity`), for the models
    /// that take one (Preetham, Hosek–Wilkie, the CIE sky's zenith luminance); `probe`
    /// reports it.
    fn turbidity(&self) -> Option<f64> {
        None
    }

    /// Radiance of the sun's disk for batch `layer` seen from altitude `h` (m) with the sun at
    /// zenith cosine `mu_s`, where the disk's radiance per unit irradiance is `disk` (sr⁻¹ per
    /// lane, limb darkening depending on the wavelength:
    /// `shared::sun_disk` in a single direction, `SunInView::disk_in_pixel` averaged over a
    /// pixel): the solar irradiance through the model's transmittance table along the sun's
    /// own ray, behind the planet's limb or not. The view adds it to every pixel the disk
    /// covers, whatever the pixel's centre sees.
    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        let p = self.params();
        let lit = disk.iter().any(|&d| d > 0.0);
        let Some(t) = self.table("transmittance").filter(|_| lit) else {
            return Lanes::ZERO;
        };
        let tr = shared::transmittance::sun_seen_from(p, t, layer, h, mu_s);
        p.batches[layer].solar_irradiance * tr * disk
    }
}

/// The kinds of method in the registry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Tables of scattered light precomputed per atmosphere and read per pixel.
    PrecomputedTables,
    /// Single scattering marched per pixel, the optical depths exact or in closed form.
    SingleScattering,
    /// The same plus Hillaire's isotropic higher orders Ψ_ms (the `-ms` rows).
    WithIsotropicOrders,
    /// The view ray as one or a few homogeneous slabs in closed form.
    ClosedFormSlab,
    /// Nishita et al.'s (1996) intensity volume, gathered order by order.
    IntensityVolume,
    /// Analytic distributions fitted to measured or simulated skies.
    AnalyticFit,
    /// No atmosphere: the benchmarks' floor.
    Baseline,
    /// The path tracer.
    GroundTruth,
}

impl Family {
    pub const ALL: [Family; 8] = [
        Family::PrecomputedTables,
        Family::SingleScattering,
        Family::WithIsotropicOrders,
        Family::ClosedFormSlab,
        Family::IntensityVolume,
        Family::AnalyticFit,
        Family::Baseline,
        Family::GroundTruth,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Family::PrecomputedTables => "precomputed tables",
            Family::SingleScattering => "single scattering",
            Family::WithIsotropicOrders => "single + isotropic orders",
            Family::ClosedFormSlab => "closed-form slabs",
            Family::IntensityVolume => "intensity volume",
            Family::AnalyticFit => "analytic fits",
            Family::Baseline => "baseline",
            Family::GroundTruth => "ground truth",
        }
    }

    /// This family's position in `ALL` and `model`'s among the registry's rows of the family:
    /// a chart's colour and marker for the model, distinct for every row. None for an id the
    /// registry does not have.
    pub fn style_of(model: &str) -> Option<(usize, usize)> {
        let info = by_id(model)?;
        let family = Family::ALL.iter().position(|&f| f == info.family)?;
        let within = MODELS
            .iter()
            .filter(|m| m.family == info.family)
            .position(|m| m.id == info.id)?;
        Some((family, within))
    }
}

/// One row of the registry.
#[derive(Debug, Clone, Copy)]
pub struct ModelInfo {
    pub method: Method,
    /// Stable id, as the command line spells it.
    pub id: &'static str,
    pub label: &'static str,
    /// The kind of method, for grouping in charts and lists.
    pub family: Family,
    pub citation: &'static str,
    /// One or two sentences: what the model does and what it costs.
    pub summary: &'static str,
    pub domain: Domain,
    /// Every table, in the order the passes compute them.
    pub tables: &'static [TableSpec],
    /// Whether the model gathers scattering orders one by one, as many as
    /// `render.scattering_orders` says.
    pub gathers_orders: bool,
    /// Whether the model has fitted constants, published and refitted, that
    /// `render.fitted_constants` chooses between.
    pub refittable: bool,
    /// A baseline to measure models against (no atmosphere), not a model of the sky: the
    /// benchmarks list it, the accuracy tests hold it to being far off.
    pub baseline: bool,
    /// What the project states of the model's error and how long its stress run is; the
    /// research tier holds the model to it.
    pub stated: Stated,
    /// The CPU twin's constructor; None for the path tracer, which is not a real-time model.
    pub build: Option<fn(&Params, Viewpoint) -> Box<dyn SkyModel>>,
}

impl ModelInfo {
    /// Whether the model renders in real time on the GPU.
    pub fn is_realtime(&self) -> bool {
        self.build.is_some()
    }

    /// Whether any table the model's still frames read depends on the viewpoint (camera
    /// altitude, sun elevation): if not, one CPU twin serves every viewpoint of an atmosphere.
    /// The moving sky is read by views in motion alone, which no CPU twin draws.
    pub fn reads_viewpoint(&self) -> bool {
        self.tables
            .iter()
            .any(|t| t.invalidated_by.intersects(Inputs::VIEWPOINT) && !t.motion_only())
    }

    /// Whether any table but the moving sky holds the ground albedo: if none does, a change
    /// of the albedo redraws the view alone.
    pub fn tables_hold_the_albedo(&self) -> bool {
        self.tables
            .iter()
            .any(|t| t.invalidated_by.intersects(Inputs::GROUND_ALBEDO) && !t.motion_only())
    }

    /// A table of the model by id.
    pub fn table(&self, id: &str) -> Option<&'static TableSpec> {
        self.tables.iter().find(|t| t.id == id)
    }

    /// Why the model will not draw `scene`: it is offline, or it refuses views outside its
    /// domain and this one is. None when it draws.
    pub fn cannot_draw(&self, scene: &Scene) -> Option<CannotDraw> {
        if !self.is_realtime() {
            return Some(CannotDraw::NotRealtime(self.id, realtime_ids()));
        }
        if !self.domain.refuses {
            return None;
        }
        self.domain
            .excludes(scene.camera.altitude_m, sun_elevation_at_camera_deg(scene))
            .map(|why| CannotDraw::Refused(self.label, why))
    }
}

/// The sun's elevation above the camera's own horizon, degrees: the scene's sun elevation
/// unless the camera is moved back over the planet (`camera.back_km`), which tilts its horizon.
pub fn sun_elevation_at_camera_deg(scene: &Scene) -> f64 {
    let camera = Camera::new(
        &scene.camera,
        scene.atmosphere.planet_radius_km * 1000.0,
        Projection::Perspective,
    );
    shared::viewpoint(scene, &camera)
        .mu_s
        .clamp(-1.0, 1.0)
        .asin()
        .to_degrees()
}

/// The registry: every model, one row each.
pub const MODELS: &[ModelInfo] = &[
    ModelInfo {
        method: Method::Hillaire,
        id: "hillaire",
        family: Family::PrecomputedTables,
        label: "Hillaire 2020",
        citation: "S. Hillaire (2020), A Scalable and Production Ready Sky and Atmosphere Rendering Technique, Computer Graphics Forum 39(4)",
        summary: "Transmittance and multiple-scattering tables, a sky-view table at the camera's altitude and an aerial-perspective volume; ray-marched from space.",
        domain: hillaire::DOMAIN,
        tables: &hillaire::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(4.5),
            twilight_delta_e2000: Some(5.5),
            probe_relative_error: Some(0.15),
            stress_cases: 24,
        },
        build: Some(hillaire::build),
    },
    ModelInfo {
        method: Method::Bruneton,
        id: "bruneton",
        family: Family::PrecomputedTables,
        label: "Bruneton & Neyret 2008",
        citation: "E. Bruneton, F. Neyret (2008), Precomputed Atmospheric Scattering, Computer Graphics Forum 27(4); parameterisation of E. Bruneton's 2017 reference implementation",
        summary: "4D scattering tables (altitude, view, sun, view–sun angle) with every order up to N gathered one by one at precompute time, and sky irradiance; only their 2D slices at the camera depend on the sun or the camera's altitude.",
        domain: bruneton::DOMAIN,
        tables: &bruneton::TABLES,
        gathers_orders: true,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(3.0),
            twilight_delta_e2000: Some(3.0),
            probe_relative_error: Some(0.1),
            stress_cases: 3,
        },
        build: Some(bruneton::build),
    },
    ModelInfo {
        method: Method::GarciaLinan,
        id: "garcia-linan",
        family: Family::PrecomputedTables,
        label: "García Liñán 2023",
        citation: "F. García Liñán (2023), A real-time spectral atmosphere model, master's thesis",
        summary: "Transmittance table and ray-marched single scattering in a sky texture, plus a closed-form ground-bounce term and a fitted logistic multiple-scattering term.",
        domain: garcia_linan::DOMAIN,
        tables: &garcia_linan::TABLES,
        gathers_orders: false,
        refittable: true,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(13.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.4),
            stress_cases: 24,
        },
        build: Some(garcia_linan::build),
    },
    ModelInfo {
        method: Method::Elek,
        id: "elek",
        family: Family::PrecomputedTables,
        label: "Elek 2009",
        citation: "O. Elek (2009), Rendering Parametrizable Planetary Atmospheres with Multiple Scattering in Real-Time, CESCG; as described in J. Boody's Atmosphere Plus notes after Bodare & Sandberg (2014)",
        summary: "3D tables (altitude, view, sun) without the view–sun azimuth, Rayleigh and Mie apart with their phase functions applied at look-up (a modified Rayleigh phase), every order up to N gathered one by one; only their rows at the camera (one blend per texel) depend on the sun or the camera's altitude.",
        domain: elek::DOMAIN,
        tables: &elek::TABLES,
        gathers_orders: true,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(12.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.45),
            stress_cases: 4,
        },
        build: Some(elek::build),
    },
    ModelInfo {
        method: Method::Nishita,
        id: "nishita",
        family: Family::SingleScattering,
        label: "Nishita 1993",
        citation: "T. Nishita, T. Sirai, K. Tadamura, E. Nakamae (1993), Display of the Earth Taking into Account Atmospheric Scattering, SIGGRAPH; per pixel on the GPU as in S. O'Neil (2005), Accurate Atmospheric Scattering, GPU Gems 2",
        summary: "Single scattering by nested quadrature, no tables of the atmosphere: every pixel marches its view ray and, at each sample, the ray to the sun. No higher orders; all the cost is in the frame (in motion on a software GPU, in the moving sky: the same marches at 192 × 108 directions).",
        domain: nishita::DOMAIN,
        tables: &nishita::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(14.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(nishita::build),
    },
    ModelInfo {
        method: Method::Trapezoid,
        id: "trapezoid",
        family: Family::SingleScattering,
        label: "Trapezoid rule",
        citation: "Single scattering with the trapezoid rule along the sun's ray, the baseline of T. Gałaj, F. Pietrusiak, M. Galewski, R. Ledzion, A. Wojciechowski (2021), Hybrid Integration Method for Sunlight Atmospheric Scattering, IEEE Access 9",
        summary: "Nishita's table-free single scattering with the optical depth towards the sun by the trapezoid rule (both ends sampled) instead of midpoints; the same sample counts.",
        domain: trapezoid::DOMAIN,
        tables: &trapezoid::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(17.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.7),
            stress_cases: 8,
        },
        build: Some(trapezoid::build),
    },
    ModelInfo {
        method: Method::NishitaMs,
        id: "nishita-ms",
        family: Family::WithIsotropicOrders,
        label: "Nishita 1993 + Hillaire's Ψ_ms",
        citation: "Nishita et al. (1993) as the nishita row, with the multiple-scattering table of S. Hillaire (2020) as its higher orders",
        summary: "The nishita row's table-free single scattering plus Hillaire's isotropic higher orders Ψ_ms, looked up at every sample: two small tables that depend on the atmosphere alone (and the moving sky for views in motion on a software GPU).",
        domain: nishita::DOMAIN_MS,
        tables: &single_scattering_sky::TABLES_WITH_HIGHER_ORDERS_NESTED,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(11.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.15),
            stress_cases: 8,
        },
        build: Some(nishita::build_ms),
    },
    ModelInfo {
        method: Method::TrapezoidMs,
        id: "trapezoid-ms",
        family: Family::WithIsotropicOrders,
        label: "Trapezoid rule + Hillaire's Ψ_ms",
        citation: "The trapezoid row, with the multiple-scattering table of S. Hillaire (2020) as its higher orders",
        summary: "The trapezoid row's single scattering plus Hillaire's isotropic higher orders Ψ_ms.",
        domain: trapezoid::DOMAIN_MS,
        tables: &single_scattering_sky::TABLES_WITH_HIGHER_ORDERS_NESTED,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(13.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.15),
            stress_cases: 8,
        },
        build: Some(trapezoid::build_ms),
    },
    ModelInfo {
        method: Method::Schuler,
        id: "schuler",
        family: Family::SingleScattering,
        label: "Schuler 2012",
        citation: "C. Schuler (2012), An Approximation to the Chapman Grazing-Incidence Function for Atmospheric Scattering, GPU Pro 3; as compared by D. Leenman (2025)",
        summary: "Nishita's per-pixel single scattering with the march towards the sun replaced by Schuler's closed-form Chapman function on exponential fits of air and aerosol (ozone as a thin shell); no tables of the atmosphere (views in motion on a software GPU are drawn from the moving sky), no higher orders.",
        domain: schuler::DOMAIN,
        tables: &schuler::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(14.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(schuler::build),
    },
    ModelInfo {
        method: Method::SchulerMs,
        id: "schuler-ms",
        family: Family::WithIsotropicOrders,
        label: "Schuler 2012 + Hillaire's Ψ_ms",
        citation: "The schuler row, with the multiple-scattering table of S. Hillaire (2020) as its higher orders",
        summary: "The schuler row's single scattering plus Hillaire's isotropic higher orders Ψ_ms.",
        domain: schuler::DOMAIN_MS,
        tables: &single_scattering_sky::TABLES_WITH_HIGHER_ORDERS,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(11.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.15),
            stress_cases: 8,
        },
        build: Some(schuler::build_ms),
    },
    ModelInfo {
        method: Method::GalajTaylor,
        id: "galaj-taylor",
        family: Family::SingleScattering,
        label: "Gałaj 2021 (Taylor)",
        citation: "T. Gałaj, F. Pietrusiak, M. Galewski, R. Ledzion, A. Wojciechowski (2021), Hybrid Integration Method for Sunlight Atmospheric Scattering, IEEE Access 9: the Taylor-series transmittance (a = b = 0.45)",
        summary: "Single scattering marched along the view ray, with the optical depth towards the sun from one closed form per constituent: the altitude along the sun's ray expanded to order 1 + a about a point b of the way to the top; exponential fits of air and aerosol, ozone as a thin shell; no tables of the atmosphere (views in motion on a software GPU are drawn from the moving sky), no higher orders.",
        domain: galaj_taylor::DOMAIN,
        tables: &galaj_taylor::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(26.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(galaj_taylor::build),
    },
    ModelInfo {
        method: Method::GalajTaylorMs,
        id: "galaj-taylor-ms",
        family: Family::WithIsotropicOrders,
        label: "Gałaj 2021 (Taylor) + Hillaire's Ψ_ms",
        citation: "The galaj-taylor row, with the multiple-scattering table of S. Hillaire (2020) as its higher orders",
        summary: "The galaj-taylor row's single scattering plus Hillaire's isotropic higher orders Ψ_ms.",
        domain: galaj_taylor::DOMAIN_MS,
        tables: &single_scattering_sky::TABLES_WITH_HIGHER_ORDERS,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(21.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.15),
            stress_cases: 8,
        },
        build: Some(galaj_taylor::build_ms),
    },
    ModelInfo {
        method: Method::GalajSpline,
        id: "galaj-spline",
        family: Family::SingleScattering,
        label: "Gałaj 2021 (spline)",
        citation: "T. Gałaj, F. Pietrusiak, M. Galewski, R. Ledzion, A. Wojciechowski (2021), Hybrid Integration Method for Sunlight Atmospheric Scattering, IEEE Access 9: the spline transmittance (Hermite, 50 × 20 mesh)",
        summary: "Single scattering marched along the view ray, with the optical depth towards the sun integrated exactly over a cubic Hermite spline of the integrand, read from a 50 × 20 mesh per constituent (lines above the ground in distance, lines meeting it in altitude); exponential fits of air and aerosol, ozone as a thin shell; no higher orders.",
        domain: galaj_spline::DOMAIN,
        tables: &galaj_spline::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(14.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(galaj_spline::build),
    },
    ModelInfo {
        method: Method::GalajSplineMs,
        id: "galaj-spline-ms",
        family: Family::WithIsotropicOrders,
        label: "Gałaj 2021 (spline) + Hillaire's Ψ_ms",
        citation: "The galaj-spline row, with the multiple-scattering table of S. Hillaire (2020) as its higher orders",
        summary: "The galaj-spline row's single scattering plus Hillaire's isotropic higher orders Ψ_ms.",
        domain: galaj_spline::DOMAIN_MS,
        tables: &galaj_spline::TABLES_MS,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(11.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.15),
            stress_cases: 8,
        },
        build: Some(galaj_spline::build_ms),
    },
    ModelInfo {
        method: Method::Flat,
        id: "flat",
        family: Family::ClosedFormSlab,
        label: "Leenman 2025 (flat)",
        citation: "D. Leenman (2025), A visual and performance comparison of atmospheric scattering models, master's thesis: the flat homogeneous atmosphere on the sphere, after Jodie (2019)",
        summary: "Single scattering of the whole view ray as one slab in closed form, every optical depth the chord through a homogeneous shell one scale height thick; no tables, no march, no higher orders, no Earth shadow in the sky.",
        domain: flat::DOMAIN,
        tables: &flat::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(17.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(flat::build),
    },
    ModelInfo {
        method: Method::Raymarched,
        id: "raymarched",
        family: Family::ClosedFormSlab,
        label: "Leenman 2025 (raymarched)",
        citation: "D. Leenman (2025), A visual and performance comparison of atmospheric scattering models, master's thesis: five slab segments along the view ray (his eq. 55) with homogeneous-shell optical depths",
        summary: "The flat model's slab integral over five segments of the view ray, each between its ends' view and sun optical depths; no tables, no higher orders, no Earth shadow in the sky.",
        domain: raymarched::DOMAIN,
        tables: &raymarched::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(17.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.65),
            stress_cases: 8,
        },
        build: Some(raymarched::build),
    },
    ModelInfo {
        method: Method::ONeil,
        id: "oneil",
        family: Family::SingleScattering,
        label: "O'Neil 2005",
        citation: "S. O'Neil (2005), Accurate Atmospheric Scattering, in GPU Gems 2, ch. 16, Addison-Wesley, 253–268",
        summary: "The games-era sky: Nishita's single scattering in five samples per view ray, every optical depth from one fitted function of the angle times the density (refitted to the scene's planet and air), air and aerosol sharing one scale height, no ozone; no tables, no higher orders, no Earth shadow.",
        domain: oneil::DOMAIN,
        tables: &oneil::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(21.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.75),
            stress_cases: 8,
        },
        build: Some(oneil::build),
    },
    ModelInfo {
        method: Method::Nishita96,
        id: "nishita-96",
        family: Family::IntensityVolume,
        label: "Nishita 1996",
        citation: "T. Nishita, Y. Dobashi, K. Kaneda, H. Yamashita (1996), Display Method of the Sky Color Taking into Account Multiple Scattering, Pacific Graphics",
        summary: "The nishita row's single scattering plus the second order, gathered at every view sample from an intensity volume: the once-scattered light stored per altitude and sun angle for 64 cells of directions centred on the sun, computed once per atmosphere.",
        domain: nishita_96::DOMAIN,
        tables: &nishita_96::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(6.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.35),
            stress_cases: 4,
        },
        build: Some(nishita_96::build),
    },
    ModelInfo {
        method: Method::Haber,
        id: "haber",
        family: Family::IntensityVolume,
        label: "Haber 2005",
        citation: "J. Haber, M. Magnor, H.-P. Seidel (2005), Physically based simulation of twilight phenomena, ACM Transactions on Graphics 24(4), 1353–1373",
        summary: "Multiple scattering for twilight: the intensity volume of nishita-96 iterated order by order to the scene's count (each order gathered from the one before, Earth's shadow included), the view marching single scattering and gathering one order more; no refraction.",
        domain: haber::DOMAIN,
        tables: &haber::TABLES,
        gathers_orders: true,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(2.6),
            twilight_delta_e2000: Some(1.8),
            probe_relative_error: Some(0.1),
            stress_cases: 4,
        },
        build: Some(haber::build),
    },
    ModelInfo {
        method: Method::Preetham,
        id: "preetham",
        family: Family::AnalyticFit,
        label: "Preetham 1999",
        citation: "A. J. Preetham, P. Shirley, B. Smits (1999), A Practical Analytic Model for Daylight, SIGGRAPH; on the sky-luminance distribution of R. Perez, R. Seals, J. Michalsky (1993)",
        summary: "The analytic daylight model: Perez's five-parameter distribution in xyY, linear in the turbidity, scaled by fitted zenith values; one closed form per pixel, no tables. Ground views in daylight only; the ground gets the direct sun alone.",
        domain: preetham::DOMAIN,
        tables: &preetham::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(31.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(1.7),
            stress_cases: 8,
        },
        build: Some(preetham::build),
    },
    ModelInfo {
        method: Method::HosekWilkie,
        id: "hosek-wilkie",
        family: Family::AnalyticFit,
        label: "Hosek–Wilkie 2012",
        citation: "L. Hosek, A. Wilkie (2012), An Analytic Model for Full Spectral Sky-Dome Radiance, ACM Transactions on Graphics 31(4); the sun from L. Hosek, A. Wilkie (2013), Adding a Solar Radiance Function to the Hosek Skylight Model, IEEE Computer Graphics and Applications 33(3)",
        summary: "The analytic sky of production renderers: a nine-parameter distribution per band (11 bands, 320–720 nm, or its own sRGB fit), each parameter a Bézier curve in the sun's elevation blended over turbidity and ground albedo; the sun from the 2013 solar radiance function. One closed form per pixel, coefficients computed on the CPU per sun. Ground views in daylight only.",
        domain: hosek_wilkie::DOMAIN,
        tables: &hosek_wilkie::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(22.0),
            twilight_delta_e2000: None,
            probe_relative_error: Some(0.4),
            stress_cases: 8,
        },
        build: Some(hosek_wilkie::build),
    },
    ModelInfo {
        method: Method::CieStandardSky,
        id: "cie-standard-sky",
        family: Family::AnalyticFit,
        label: "CIE standard general sky",
        citation: "CIE S 011/E:2003 (ISO 15469:2004), Spatial distribution of daylight — CIE standard general sky; zenith luminance of A. J. Preetham, P. Shirley, B. Smits (1999)",
        summary: "The daylighting standard's 15 relative luminance distributions (overcast to turbid clear, `render.cie_sky_type`), a gradation in the zenith angle times an indicatrix in the angle from the sun; the zenith luminance from Preetham's formula at the scene's turbidity. A luminance model: no spectrum, the colour of the sun. Ground views in daylight only.",
        domain: cie_standard_sky::DOMAIN,
        tables: &cie_standard_sky::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated {
            daylight_delta_e2000: Some(31.5),
            twilight_delta_e2000: None,
            probe_relative_error: Some(2.1),
            stress_cases: 8,
        },
        build: Some(cie_standard_sky::build),
    },
    ModelInfo {
        method: Method::Empty,
        id: "empty",
        family: Family::Baseline,
        label: "No atmosphere",
        citation: "The baseline of D. Leenman (2025), A visual and performance comparison of atmospheric scattering models, master's thesis (his empty shader): the planet without air",
        summary: "A black sky over ground lit by the sun as in space: the cheapest frame and the largest error, the benchmark's baseline.",
        domain: empty::DOMAIN,
        tables: &empty::TABLES,
        gathers_orders: false,
        refittable: false,
        baseline: true,
        stated: Stated {
            daylight_delta_e2000: None,
            twilight_delta_e2000: None,
            probe_relative_error: None,
            stress_cases: 8,
        },
        build: Some(empty::build),
    },
    ModelInfo {
        method: Method::PathTracer,
        id: "path-tracer",
        family: Family::GroundTruth,
        label: "Path tracer",
        citation: "Spectral Monte Carlo path tracer with ratio tracking and next-event estimation (this project)",
        summary: "The offline ground truth: all scattering orders, no tables. `atmoscope reference` and the Reference tab render with it.",
        domain: Domain::EVERYWHERE,
        tables: &[],
        gathers_orders: false,
        refittable: false,
        baseline: false,
        stated: Stated::NONE,
        build: None,
    },
];

/// The registry row of `method`.
pub fn info(method: Method) -> &'static ModelInfo {
    // Every `Method` has its row (`every_method_has_one_registry_row`).
    match MODELS.iter().find(|m| m.method == method) {
        Some(row) => row,
        None => panic!("{method:?} has no row in the registry"),
    }
}

/// The registry row with the command-line id `id`.
pub fn by_id(id: &str) -> Option<&'static ModelInfo> {
    MODELS.iter().find(|m| m.id == id)
}

/// The real-time models, in registry order.
pub fn realtime() -> impl Iterator<Item = &'static ModelInfo> {
    MODELS.iter().filter(|m| m.is_realtime())
}

/// Ids of the real-time models, comma separated (for messages and `--help`).
pub fn realtime_ids() -> String {
    realtime().map(|m| m.id).collect::<Vec<_>>().join(", ")
}

/// Why a model draws nothing for a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CannotDraw {
    /// The path tracer is offline: its id and the real-time models' ids.
    #[error("{0} is not a real-time model (real-time models: {1})")]
    NotRealtime(&'static str, String),
    /// The view lies outside the domain of a model that refuses such views: its label and why.
    #[error("{0} does not draw this view: {1}")]
    Refused(&'static str, String),
}

/// The CPU twin of the scene's model for `scene` seen through `camera`. Its optics and tables
/// hold sunlight at 1 AU, as the GPU's do: [`render_with`] scales its radiance to the scene's
/// Earth–Sun distance ([`crate::scene::SunSettings::sunlight_scale`]).
pub fn build(scene: &Scene, camera: &Camera) -> Result<Box<dyn SkyModel>, CannotDraw> {
    let row = info(scene.render.method);
    if let Some(why) = row.cannot_draw(scene) {
        return Err(why);
    }
    let build = row
        .build
        .ok_or_else(|| CannotDraw::NotRealtime(row.id, realtime_ids()))?;
    let atm = Atmosphere::new(&scene.atmosphere);
    let p = Params::new(&atm, scene.render.wavelengths, scene.render.quality)
        .with_render(&scene.render);
    Ok(build(&p, shared::viewpoint(scene, camera)))
}

/// CPU render of a whole view with the scene's model: linear sRGB per pixel (row-major, top row
/// first; zero where the projection shows nothing), sampled at pixel centres.
pub fn render(
    scene: &Scene,
    projection: Projection,
    width: u32,
    height: u32,
) -> Result<Vec<[f64; 3]>, CannotDraw> {
    let (model, camera) = built(scene, projection)?;
    Ok(render_with(model.as_ref(), scene, &camera, width, height))
}

/// The scene's model built for its camera through `projection`, and that camera.
fn built(scene: &Scene, projection: Projection) -> Result<(Box<dyn SkyModel>, Camera), CannotDraw> {
    let camera = Camera::new(
        &scene.camera,
        scene.atmosphere.planet_radius_km * 1000.0,
        projection,
    );
    Ok((build(scene, &camera)?, camera))
}

/// CPU render with a model already built ([`build`]: sunlight at 1 AU), its radiance scaled to
/// the scene's Earth–Sun distance, through the camera's polarising filter where it has one.
pub fn render_with(
    model: &dyn SkyModel,
    scene: &Scene,
    camera: &Camera,
    width: u32,
    height: u32,
) -> Vec<[f64; 3]> {
    shade(model, scene, camera, width, height, false)
}

/// [`render`]'s view as the Polarisation display mode sees it: per pixel the Stokes vector
/// (I_Y, Q_Y, U_Y) weighted by ȳ like the luminance, W·m⁻²·sr⁻¹, referred to up in the picture
/// (`Camera::image_up`); the filter, if any, left out. Twin of the GPU's.
pub fn render_stokes(
    scene: &Scene,
    projection: Projection,
    width: u32,
    height: u32,
) -> Result<Vec<[f64; 3]>, CannotDraw> {
    let (model, camera) = built(scene, projection)?;
    Ok(shade(model.as_ref(), scene, &camera, width, height, true))
}

/// The Stokes Q and U per lane of a model's light `sky` (the sun's disk apart) along `dir` from
/// `at`, referred to the frame whose e₁ is `e_up`: `shared::polarisation::sky_stokes` through
/// the model's own transmittance towards the sun.
#[allow(clippy::too_many_arguments)]
pub fn sky_stokes(
    model: &dyn SkyModel,
    layer: usize,
    at: (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
    e_up: DVec3,
    sky: Lanes,
) -> [Lanes; 2] {
    let p = model.params();
    let e = p.batches[layer].solar_irradiance;
    shared::polarisation::sky_stokes(p, layer, at, dir, sun, e_up, sky, |h, mu_s| {
        let t = model.sun(layer, h, mu_s, Lanes::ONE);
        Lanes::from_fn(|k| if e[k] > 0.0 { t[k] / e[k] } else { 0.0 })
    })
}

/// Every pixel of the view: linear sRGB through the polarising filter, or with `stokes` the
/// Stokes vector (I_Y, Q_Y, U_Y); the sun's disk included (unpolarised).
fn shade(
    model: &dyn SkyModel,
    scene: &Scene,
    camera: &Camera,
    width: u32,
    height: u32,
    stokes: bool,
) -> Vec<[f64; 3]> {
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let p = model.params();
    let colours: Vec<WavelengthBatch> = p.batches.iter().map(|b| b.colour.clone()).collect();
    let sun_in_view = camera.sun_in_view(sun, width, height);
    let sunlight = scene.sun.sunlight_scale();
    let polariser = if stokes {
        None
    } else {
        scene.camera.polariser_deg.map(f64::to_radians)
    };
    (0..width * height)
        .into_par_iter()
        .map(|i| {
            let (x, y) = (f64::from(i % width) + 0.5, f64::from(i / width) + 0.5);
            let Some(ray) = camera.ray(x, y, width, height) else {
                return [0.0; 3];
            };
            let at = (ray.origin, scene.camera.altitude_m);
            let mu_s = sun.dot(ray.origin.normalize());
            let up = (stokes || polariser.is_some())
                .then(|| camera.image_up(x, y, width, height, ray.direction));
            // The disk's geometry once per pixel, its limb darkening per batch.
            let disk_here = sun_in_view.and_then(|s| s.pixel(x, y));
            let mut parts = [Vec::new(), Vec::new(), Vec::new()];
            for layer in 0..p.batches.len() {
                let disk = disk_here.map_or(Lanes::ZERO, |d| {
                    d.radiance(&Lanes(colours[layer].wavelengths_nm))
                });
                let sky = model.radiance(layer, at, ray.direction, sun);
                let mut l = sky + model.sun(layer, at.1, mu_s, disk);
                let polarised =
                    up.map(|e_up| sky_stokes(model, layer, at, ray.direction, sun, e_up, sky));
                if let (Some(theta), Some([q, u])) = (polariser, polarised) {
                    l = Lanes::from_fn(|k| {
                        0.5 * (l[k] + q[k] * (2.0 * theta).cos() + u[k] * (2.0 * theta).sin())
                    });
                }
                let [q, u] = polarised.unwrap_or([Lanes::ZERO; 2]);
                parts[0].push(l);
                parts[1].push(q);
                parts[2].push(u);
            }
            if stokes {
                let y = |lanes: &[Lanes]| {
                    crate::colour::linear_srgb_to_xyz(to_linear_srgb(&colours, lanes)).y
                };
                [y(&parts[0]), y(&parts[1]), y(&parts[2])].map(|c| c * sunlight)
            } else {
                to_linear_srgb(&colours, &parts[0]).map(|c| c * sunlight)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sun's disk goes through the transmittance along the sun's own ray, whatever the
    /// pixel's centre sees: nothing once the sun is below the horizon (so a pixel straddling
    /// the horizon cannot let a set sun through the air above it), all of it from space.
    #[test]
    fn the_sun_is_seen_along_its_own_ray() {
        let mut scene = Scene::default();
        scene.render.method = Method::Hillaire;
        scene.render.wavelengths = crate::scene::WavelengthSet::Rgb3;
        let camera = Camera::new(&scene.camera, 6_360_000.0, Projection::Perspective);
        let model = build(&scene, &camera).expect("a real-time model");
        let e = model.params().batches[0].solar_irradiance;
        let sin = |deg: f64| deg.to_radians().sin();
        let high = model.sun(0, 2.0, sin(30.0), Lanes::ONE);
        assert!(
            (0..3).all(|i| high[i] > 0.3 * e[i] && high[i] < e[i]),
            "{high:?} of {e:?}"
        );
        assert_eq!(model.sun(0, 2.0, sin(-2.0), Lanes::ONE), Lanes::ZERO);
        assert_eq!(model.sun(0, 2.0, sin(30.0), Lanes::ZERO), Lanes::ZERO);
        // From 20 000 km: straight up through nothing, straight down behind the planet.
        let space = model.sun(0, 2e7, 1.0, Lanes::ONE);
        assert!(
            (0..3).all(|i| (space[i] - e[i]).abs() < 1e-9 * e[i]),
            "{space:?}"
        );
        assert_eq!(model.sun(0, 2e7, -1.0, Lanes::ONE), Lanes::ZERO);
    }

    #[test]
    fn the_registry_has_unique_ids_and_tables() {
        for (i, a) in MODELS.iter().enumerate() {
            assert_eq!(info(a.method).id, a.id);
            assert_eq!(by_id(a.id).map(|m| m.method), Some(a.method));
            for b in &MODELS[i + 1..] {
                assert_ne!(a.id, b.id);
                assert_ne!(a.method, b.method);
            }
            for (j, t) in a.tables.iter().enumerate() {
                assert!(a.tables[j + 1..].iter().all(|u| u.id != t.id), "{}", t.id);
                assert!(!t.invalidated_by.is_empty(), "{} {}", a.id, t.id);
                assert!(t.size.iter().all(|&n| n > 0));
            }
        }
        assert!(!info(Method::PathTracer).is_realtime());
    }

    /// Every real-time model states its bounds in its row (the research tier reads them from
    /// there); a baseline states none for ΔE, being held to being far off instead.
    #[test]
    fn every_real_time_model_states_its_bounds_in_its_row() {
        for m in realtime() {
            let s = m.stated;
            assert!(s.stress_cases > 0, "{}", m.id);
            assert_eq!(s.daylight_delta_e2000.is_none(), m.baseline, "{}", m.id);
            for bound in [
                s.daylight_delta_e2000,
                s.twilight_delta_e2000,
                s.probe_relative_error,
            ]
            .into_iter()
            .flatten()
            {
                assert!(bound.is_finite() && bound > 0.0, "{}: {bound}", m.id);
            }
            if !m.baseline {
                assert!(s.probe_relative_error.is_some(), "{}", m.id);
            }
        }
        assert_eq!(info(Method::PathTracer).stated, Stated::NONE);
    }

    #[test]
    fn every_model_of_the_registry_builds_its_declared_tables() {
        let mut scene = Scene::default();
        scene.render.quality = crate::scene::Quality::Low;
        scene.render.wavelengths = crate::scene::WavelengthSet::Rgb3;
        for row in realtime() {
            scene.render.method = row.method;
            let camera = Camera::new(&scene.camera, 6_360_000.0, Projection::Perspective);
            let model = build(&scene, &camera).expect("real-time model");
            // The moving sky's twin is `shared::moving_sky::compute_lut`, tested on its own.
            for spec in row.tables.iter().filter(|t| !t.motion_only()) {
                let lut = model
                    .table(spec.id)
                    .unwrap_or_else(|| panic!("{} has no table {}", row.id, spec.id));
                assert_eq!(
                    [lut.width, lut.height, lut.depth].map(|n| n as u32),
                    spec.size,
                    "{} {}",
                    row.id,
                    spec.id
                );
                assert!(
                    lut.data
                        .iter()
                        .flatten()
                        .all(|v| v.is_finite() && *v >= 0.0)
                );
            }
        }
        scene.render.method = Method::PathTracer;
        let camera = Camera::new(&scene.camera, 6_360_000.0, Projection::Perspective);
        assert!(build(&scene, &camera).is_err());
    }

    /// Every real-time model is linear in the sunlight, so its optics and tables hold it at
    /// 1 AU and the view is scaled to the date's distance: the twin drawn that way draws what a
    /// twin built with the optics at the date's distance draws (4 January, the Earth nearest
    /// the sun: 3.4 % more sunlight).
    #[test]
    fn every_real_time_model_draws_the_date_s_sunlight_by_scaling_its_view() {
        let mut scene = Scene::default();
        scene.render.quality = crate::scene::Quality::Low;
        scene.render.wavelengths = crate::scene::WavelengthSet::Rgb3;
        scene.camera.pitch_deg = -5.0;
        // Two orders are enough to show the higher ones linear too, at a fraction of the time.
        scene.render.scattering_orders = 2;
        scene.sun = crate::scene::SunSettings::Date {
            time: crate::sun_position::DateTime {
                year: 2026,
                month: 1,
                day: 4,
                hour: 11.0,
                utc_offset_h: 1.0,
            },
            latitude_deg: 47.4,
            longitude_deg: 8.5,
        };
        let a = scene.sun.angles();
        let mut at_1_au = scene.clone();
        at_1_au.sun = crate::scene::SunSettings::Angles {
            elevation_deg: a.elevation_deg,
            azimuth_deg: a.azimuth_deg,
        };
        let scale = scene.sun.sunlight_scale();
        assert!((scale - 1.034).abs() < 0.001, "{scale}");
        let camera = Camera::new(&scene.camera, 6_360_000.0, Projection::Perspective);
        let (w, h) = (6, 4);
        for row in realtime() {
            scene.render.method = row.method;
            at_1_au.render.method = row.method;
            if row.cannot_draw(&scene).is_some() {
                continue;
            }
            let twin_at_1_au = build(&scene, &camera).expect("real-time");
            let scaled = render_with(twin_at_1_au.as_ref(), &scene, &camera, w, h);
            let optics = Params::new(
                &Atmosphere::for_scene(&scene),
                scene.render.wavelengths,
                scene.render.quality,
            )
            .with_render(&scene.render);
            let build_with = row.build.expect("a real-time model builds a twin");
            let twin = build_with(&optics, shared::viewpoint(&scene, &camera));
            // Drawn with the sun at the same angles, so that the view is not scaled again.
            let at_distance = render_with(twin.as_ref(), &at_1_au, &camera, w, h);
            for (s, d) in scaled.iter().zip(&at_distance) {
                for c in 0..3 {
                    let tol = 1e-9 * d[c].abs() + 1e-12;
                    assert!(
                        (s[c] - d[c]).abs() <= tol,
                        "{}: {s:?} against {d:?}",
                        row.id
                    );
                }
            }
        }
    }

    /// Every model that refuses views outside its domain (the fits: Preetham, Hosek–Wilkie,
    /// the CIE sky) draws ground views in daylight, and refuses a plane, space and a sun below
    /// the horizon with a message that names the model and the limit, both when asked and when
    /// its twin is built.
    #[test]
    fn every_refusing_model_names_itself_and_the_limit() {
        let fits: Vec<&ModelInfo> = realtime().filter(|m| m.domain.refuses).collect();
        assert!(fits.len() >= 3, "{}", fits.len());
        for model in fits {
            for (altitude_m, elevation_deg, refused) in [
                (1.0, 30.0, None),
                (1500.0, 0.5, None),
                (10_000.0, 30.0, Some("above this model's domain")),
                (400_000.0, 30.0, Some("above this model's domain")),
                (1.0, -4.0, Some("below this model's domain")),
            ] {
                let mut s = Scene::default();
                s.render.method = model.method;
                s.camera.altitude_m = altitude_m;
                s.sun = crate::scene::SunSettings::Angles {
                    elevation_deg,
                    azimuth_deg: 180.0,
                };
                let camera = Camera::new(&s.camera, 6_360_000.0, Projection::Perspective);
                let asked = model.cannot_draw(&s).map(|e| e.to_string());
                let built = build(&s, &camera).err().map(|e| e.to_string());
                assert_eq!(asked, built, "{} at {altitude_m} m", model.id);
                match (refused, asked) {
                    (None, None) => {}
                    (Some(words), Some(text)) => assert!(
                        text.contains(model.label) && text.contains(words),
                        "{}: {text}",
                        model.id
                    ),
                    (want, got) => panic!(
                        "{} at {altitude_m} m, sun {elevation_deg}°: {want:?} vs {got:?}",
                        model.id
                    ),
                }
            }
        }
    }

    #[test]
    fn domains_explain_what_they_exclude() {
        let d = Domain {
            max_altitude_m: 1000.0,
            min_sun_elevation_deg: 0.0,
            note: "ground views in daylight",
            max_aod550: 0.3,
            refuses: false,
        };
        assert!(d.excludes(10.0, 30.0).is_none());
        assert!(d.excludes_aod(0.3).is_none());
        assert!(d.excludes_aod(0.5).unwrap().contains("AOD 0.50"));
        let mut hazy = crate::Scene::default();
        hazy.atmosphere.aerosol.aod550 = 1.0;
        assert!(d.excludes_scene(&hazy).unwrap().contains("range"));
        hazy.atmosphere.aerosol.kind = crate::aerosol::AerosolType::None;
        assert!(d.excludes_scene(&hazy).is_none(), "no aerosol, no AOD");
        assert!(d.excludes(5000.0, 30.0).unwrap().contains("above"));
        assert!(d.excludes(10.0, -6.0).unwrap().contains("below"));
        assert_eq!(d.kinds(), vec!["ground"]);
        assert_eq!(
            Domain::EVERYWHERE.kinds(),
            vec!["ground", "plane", "space", "twilight"]
        );
    }
}
