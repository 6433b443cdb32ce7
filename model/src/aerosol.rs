//! Aerosol types: spectral extinction shape, single-scattering albedo, asymmetry and vertical
//! profile, computed with our own Mie code from the OPAC components (Hess et al. 1998).
//!
//! The nine types of Guimera et al. (2018) follow d'Almeida et al. (1991). The precomputed
//! Guimera cross-section table cannot be trusted (for sulfate and sea salt its absorption exceeds
//! its scattering by 10⁷), so each type is rebuilt here as a mixture of OPAC components, with the
//! number densities of the closest OPAC type (Hess et al. 1998, Table 4) and the optics of each
//! component from a Mie average over its log-normal size distribution at 50 % relative humidity
//! (the humidity of libRadtran's OPAC files). Only the spectral shape, the single-scattering
//! albedo and g come from the mixture: the amount is set by the user as optical depth at 550 nm.
//!
//! The vertical structure is OPAC's, as libRadtran's standard profiles lay it out: each type's
//! own aerosol lives in a mixing layer up to 2 km (Guimera's scale height H_p within it; the polar
//! types, whose H_p of 30 km would put two thirds of their AOD above 12 km, take OPAC's Antarctic
//! layer instead), above which every type shares OPAC's free-tropospheric aerosol (2–12 km) and
//! stratospheric sulfate layer (12–35 km), their extinction from our Mie code and the profiles'
//! mass concentrations. Nothing lies above 35 km. Guimera's Background type is those shared
//! layers alone.

use crate::constants::AOD_REFERENCE_NM;
use crate::csv_table::tables;
use crate::mie::{self, BulkOptics, LogNormal};
use crate::polarisation::mueller::ReducedMatrix;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The aerosol types a scene can choose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum AerosolType {
    /// No aerosol at all.
    None,
    Background,
    DesertDust,
    MaritimeClean,
    MaritimeMineral,
    PolarAntarctic,
    PolarArctic,
    RemoteContinental,
    #[default]
    Rural,
    Urban,
    /// The user's own single-scattering albedo, asymmetry, Ångström exponent and scale height.
    Custom,
}

/// Relative humidity at which hygroscopic components are taken, %.
pub const RELATIVE_HUMIDITY_PERCENT: u32 = 50;

/// One OPAC component in a mixture, with its number density (cm⁻³, Hess et al. 1998 Table 4).
type Mixture = &'static [(&'static str, f64)];

/// What the tests hold every type to: literature ranges at 550 nm (SSA, g) and 440–870 nm
/// (Ångström exponent), from OPAC (Hess et al. 1998, Table 4 and Fig. 5) and AERONET
/// climatologies (Dubovik et al. 2002, J. Atmos. Sci. 59, 590), widened for the humidity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlausibleRange {
    pub ssa: (f64, f64),
    pub g: (f64, f64),
    pub angstrom: (f64, f64),
}

/// Static description of a type.
#[derive(Debug, Clone, Copy)]
pub struct TypeInfo {
    pub label: &'static str,
    /// Key in the Guimera profile table.
    guimera_key: &'static str,
    mixture: Mixture,
    /// Typical aerosol optical depth at 550 nm for the type (rounded from OPAC Table 4 and
    /// AERONET site climatologies); the scene's default amount.
    pub default_aod550: f64,
    pub plausible: PlausibleRange,
    /// Why the type is this mixture.
    pub note: &'static str,
}

impl AerosolType {
    pub const ALL: [AerosolType; 11] = [
        AerosolType::None,
        AerosolType::Background,
        AerosolType::DesertDust,
        AerosolType::MaritimeClean,
        AerosolType::MaritimeMineral,
        AerosolType::PolarAntarctic,
        AerosolType::PolarArctic,
        AerosolType::RemoteContinental,
        AerosolType::Rural,
        AerosolType::Urban,
        AerosolType::Custom,
    ];

    /// The nine types built from OPAC components.
    pub const MIXTURES: [AerosolType; 9] = [
        AerosolType::Background,
        AerosolType::DesertDust,
        AerosolType::MaritimeClean,
        AerosolType::MaritimeMineral,
        AerosolType::PolarAntarctic,
        AerosolType::PolarArctic,
        AerosolType::RemoteContinental,
        AerosolType::Rural,
        AerosolType::Urban,
    ];

    /// Command-line and preset name, e.g. `desert-dust`.
    pub fn cli_name(self) -> &'static str {
        match self {
            AerosolType::None => "none",
            AerosolType::Background => "background",
            AerosolType::DesertDust => "desert-dust",
            AerosolType::MaritimeClean => "maritime-clean",
            AerosolType::MaritimeMineral => "maritime-mineral",
            AerosolType::PolarAntarctic => "polar-antarctic",
            AerosolType::PolarArctic => "polar-arctic",
            AerosolType::RemoteContinental => "remote-continental",
            AerosolType::Rural => "rural",
            AerosolType::Urban => "urban",
            AerosolType::Custom => "custom",
        }
    }

    pub fn from_cli_name(name: &str) -> Option<AerosolType> {
        AerosolType::ALL.into_iter().find(|t| t.cli_name() == name)
    }

    pub fn label(self) -> &'static str {
        match self.info() {
            Some(i) => i.label,
            None if self == AerosolType::None => "None",
            None => "Custom",
        }
    }

    /// Typical optical depth at 550 nm (0 for None, 0.1 for Custom).
    pub fn default_aod550(self) -> f64 {
        match self {
            AerosolType::None => 0.0,
            AerosolType::Custom => 0.1,
            t => t.info().map_or(0.0, |i| i.default_aod550),
        }
    }

    /// The mixture description of the nine OPAC-based types.
    pub fn info(self) -> Option<&'static TypeInfo> {
        const fn r(ssa: (f64, f64), g: (f64, f64), angstrom: (f64, f64)) -> PlausibleRange {
            PlausibleRange { ssa, g, angstrom }
        }
        static BACKGROUND: TypeInfo = TypeInfo {
            label: "Background",
            guimera_key: "background",
            mixture: &[("suso", 1.0)],
            default_aod550: 0.02,
            plausible: r((0.99, 1.0), (0.55, 0.80), (0.6, 2.5)),
            note: "free-tropospheric and stratospheric sulfate droplets (OPAC suso), non-absorbing; \
                   OPAC's droplets (effective radius ≈ 0.34 µm at 50 % RH) give Ångström ≈ 0.9, \
                   smaller stratospheric droplets up to ≈ 2",
        };
        static DESERT_DUST: TypeInfo = TypeInfo {
            label: "Desert Dust",
            guimera_key: "desert_dust",
            mixture: &[
                ("waso", 2000.0),
                ("minm", 269.5),
                ("miam", 30.5),
                ("micm", 0.142),
            ],
            default_aod550: 0.3,
            plausible: r((0.80, 0.97), (0.65, 0.85), (-0.2, 0.6)),
            note: "OPAC desert: mineral nucleation, accumulation and coarse modes with water-soluble",
        };
        static MARITIME_CLEAN: TypeInfo = TypeInfo {
            label: "Maritime Clean",
            guimera_key: "maritime_clean",
            mixture: &[("waso", 1500.0), ("ssam", 20.0), ("sscm", 3.2e-3)],
            default_aod550: 0.09,
            plausible: r((0.97, 1.0), (0.65, 0.85), (-0.2, 1.0)),
            note: "OPAC maritime clean: sea salt accumulation and coarse modes with water-soluble",
        };
        static MARITIME_MINERAL: TypeInfo = TypeInfo {
            label: "Maritime Mineral",
            guimera_key: "maritime_mineral",
            mixture: &[
                ("waso", 1500.0),
                ("ssam", 20.0),
                ("sscm", 3.2e-3),
                ("mitr", 5.0),
            ],
            default_aod550: 0.15,
            plausible: r((0.90, 1.0), (0.65, 0.85), (-0.2, 1.0)),
            note: "maritime clean plus transported mineral dust (OPAC mitr, 5 cm⁻³: a dust share \
                   of the extinction comparable to the sea salt's, as downwind of deserts)",
        };
        static POLAR_ANTARCTIC: TypeInfo = TypeInfo {
            label: "Polar Antarctic",
            guimera_key: "polar_antarctic",
            mixture: &[("suso", 42.9), ("ssam", 0.047), ("mitr", 0.0053)],
            default_aod550: 0.04,
            plausible: r((0.97, 1.0), (0.6, 0.8), (0.3, 2.0)),
            note: "OPAC antarctic: sulfate with traces of sea salt and mineral",
        };
        static POLAR_ARCTIC: TypeInfo = TypeInfo {
            label: "Polar Arctic",
            guimera_key: "polar_arctic",
            mixture: &[
                ("waso", 1300.0),
                ("inso", 0.01),
                ("ssam", 1.9),
                ("soot", 5300.0),
            ],
            default_aod550: 0.06,
            plausible: r((0.75, 0.95), (0.55, 0.8), (0.6, 1.8)),
            note: "OPAC arctic: Arctic haze of water-soluble and soot with some sea salt",
        };
        static REMOTE_CONTINENTAL: TypeInfo = TypeInfo {
            label: "Remote Continental",
            guimera_key: "remote_continental",
            mixture: &[("waso", 2600.0), ("inso", 0.15)],
            default_aod550: 0.06,
            plausible: r((0.93, 1.0), (0.6, 0.78), (0.8, 1.7)),
            note: "OPAC continental clean: water-soluble with a little insoluble dust",
        };
        static RURAL: TypeInfo = TypeInfo {
            label: "Rural",
            guimera_key: "rural",
            mixture: &[("waso", 7000.0), ("inso", 0.4), ("soot", 8300.0)],
            default_aod550: 0.15,
            plausible: r((0.83, 0.96), (0.6, 0.75), (0.9, 1.7)),
            note: "OPAC continental average: water-soluble, insoluble and soot",
        };
        static URBAN: TypeInfo = TypeInfo {
            label: "Urban",
            guimera_key: "urban",
            mixture: &[("waso", 28000.0), ("inso", 1.5), ("soot", 130000.0)],
            default_aod550: 0.5,
            plausible: r((0.6, 0.87), (0.55, 0.72), (0.9, 1.8)),
            note: "OPAC urban: water-soluble with much soot",
        };
        match self {
            AerosolType::Background => Some(&BACKGROUND),
            AerosolType::DesertDust => Some(&DESERT_DUST),
            AerosolType::MaritimeClean => Some(&MARITIME_CLEAN),
            AerosolType::MaritimeMineral => Some(&MARITIME_MINERAL),
            AerosolType::PolarAntarctic => Some(&POLAR_ANTARCTIC),
            AerosolType::PolarArctic => Some(&POLAR_ARCTIC),
            AerosolType::RemoteContinental => Some(&REMOTE_CONTINENTAL),
            AerosolType::Rural => Some(&RURAL),
            AerosolType::Urban => Some(&URBAN),
            AerosolType::None | AerosolType::Custom => None,
        }
    }

    /// Guimera's scale height H_p of the type, m (0: constant with height, Background).
    pub fn guimera_scale_height_m(self) -> Option<f64> {
        let info = self.info()?;
        let t = tables::guimera_aerosol_types().filter("type", info.guimera_key);
        Some(*t.numbers("H_p_km").first()? * 1000.0)
    }

    /// Scale height of the type's own aerosol in the mixing layer (0 to [`MIXING_LAYER_TOP_M`]),
    /// m: Guimera's H_p where it fits in the layer, OPAC's Antarctic mixing layer for the polar
    /// types; `None` for Background, which has no mixing layer of its own, and for the types
    /// that are not mixtures.
    pub fn mixing_layer_scale_height_m(self) -> Option<f64> {
        match self.guimera_scale_height_m()? {
            h if h <= 0.0 => None,
            h if h <= MIXING_LAYER_TOP_M => Some(h),
            _ => Some(shared_layers().antarctic_mixing_scale_height_m),
        }
    }
}

/// Top of the mixing layer that holds each type's own aerosol, m: OPAC's standard profiles give
/// the type's composition at 0 and 1 km and the free troposphere from 2 km.
pub const MIXING_LAYER_TOP_M: f64 = 2000.0;
/// Top of OPAC's free troposphere, where its stratospheric sulfate layer begins, m.
pub const FREE_TROPOSPHERE_TOP_M: f64 = 12_000.0;
/// Top of OPAC's stratospheric sulfate layer, m; its extinction falls linearly to nil there.
pub const STRATOSPHERE_TOP_M: f64 = 35_000.0;

/// The aerosol every type shares above its mixing layer (OPAC's free troposphere and
/// stratosphere), as extinction at 550 nm from our Mie code and the mass concentrations of
/// libRadtran's OPAC profiles.
#[derive(Debug, Clone, Copy)]
pub struct SharedLayers {
    /// Free-tropospheric extinction at [`MIXING_LAYER_TOP_M`], m⁻¹.
    pub free_troposphere_per_m: f64,
    /// Its scale height (fitted between 2 and 11 km), m.
    pub free_troposphere_scale_height_m: f64,
    /// Stratospheric extinction at [`FREE_TROPOSPHERE_TOP_M`], m⁻¹, falling linearly to nil at
    /// [`STRATOSPHERE_TOP_M`].
    pub stratosphere_per_m: f64,
    /// Scale height of the extinction of OPAC's Antarctic mixing layer (0 to 1 km), m.
    pub antarctic_mixing_scale_height_m: f64,
}

impl SharedLayers {
    /// Extinction at 550 nm at altitude `h_m`, m⁻¹.
    pub fn extinction_per_m(&self, h_m: f64) -> f64 {
        if h_m < MIXING_LAYER_TOP_M {
            0.0
        } else if h_m < FREE_TROPOSPHERE_TOP_M {
            self.free_troposphere_per_m
                * (-(h_m - MIXING_LAYER_TOP_M) / self.free_troposphere_scale_height_m).exp()
        } else if h_m < STRATOSPHERE_TOP_M {
            self.stratosphere_per_m * (STRATOSPHERE_TOP_M - h_m)
                / (STRATOSPHERE_TOP_M - FREE_TROPOSPHERE_TOP_M)
        } else {
            0.0
        }
    }

    /// Optical depth at 550 nm from the ground to `top_m`.
    pub fn optical_depth_to(&self, top_m: f64) -> f64 {
        let h = self.free_troposphere_scale_height_m;
        let ft_top = top_m.min(FREE_TROPOSPHERE_TOP_M);
        let ft = if ft_top > MIXING_LAYER_TOP_M {
            self.free_troposphere_per_m * h * (1.0 - (-(ft_top - MIXING_LAYER_TOP_M) / h).exp())
        } else {
            0.0
        };
        let depth = STRATOSPHERE_TOP_M - FREE_TROPOSPHERE_TOP_M;
        let st_top = (top_m.min(STRATOSPHERE_TOP_M) - FREE_TROPOSPHERE_TOP_M).max(0.0);
        let st = self.stratosphere_per_m * st_top * (1.0 - st_top / (2.0 * depth));
        ft + st
    }
}

/// The shared layers (computed once).
pub fn shared_layers() -> &'static SharedLayers {
    static LAYERS: OnceLock<SharedLayers> = OnceLock::new();
    LAYERS.get_or_init(|| {
        let profiles = tables::opac_type_profiles();
        let mut mass_extinction: HashMap<String, f64> = HashMap::new();
        // Extinction at 550 nm of one OPAC type's components at `z_km`, m⁻¹.
        let mut extinction = |kind: &str, z_km: &str| -> f64 {
            let rows = profiles.filter("type", kind).filter("z_km", z_km);
            rows.text("component")
                .iter()
                .zip(rows.numbers("mass_g_m3"))
                .map(|(&c, mass)| {
                    let k = *mass_extinction.entry(c.to_string()).or_insert_with(|| {
                        Component::load(c, RELATIVE_HUMIDITY_PERCENT)
                            .mass_extinction_m2_per_g(AOD_REFERENCE_NM)
                    });
                    mass * k
                })
                .sum()
        };
        // Above the mixing layer every OPAC type is the same; continental average is one.
        let ft_bottom = extinction("continental_average", "2");
        let ft_high = extinction("continental_average", "11");
        let stratosphere = extinction("continental_average", "12");
        let antarctic = (extinction("antarctic", "0"), extinction("antarctic", "1"));
        SharedLayers {
            free_troposphere_per_m: ft_bottom,
            free_troposphere_scale_height_m: 9000.0 / (ft_bottom / ft_high).ln(),
            stratosphere_per_m: stratosphere,
            antarctic_mixing_scale_height_m: 1000.0 / (antarctic.0 / antarctic.1).ln(),
        }
    })
}

/// Spectral optics of a type, tabulated on a wavelength grid and interpolated linearly.
#[derive(Debug, Clone)]
pub struct TypeOptics {
    pub wavelengths_nm: Vec<f64>,
    /// Extinction relative to its value at 550 nm.
    pub extinction_ratio: Vec<f64>,
    pub single_scattering_albedo: Vec<f64>,
    pub asymmetry_g: Vec<f64>,
}

impl TypeOptics {
    fn interpolate(&self, values: &[f64], wavelength_nm: f64) -> f64 {
        let w = &self.wavelengths_nm;
        let x = wavelength_nm.clamp(w[0], w[w.len() - 1]);
        let i = w.partition_point(|&v| v <= x).clamp(1, w.len() - 1);
        let t = (x - w[i - 1]) / (w[i] - w[i - 1]);
        values[i - 1] + t * (values[i] - values[i - 1])
    }

    /// Extinction at λ over extinction at 550 nm (clamped to the grid's ends outside it).
    pub fn extinction_ratio_at(&self, wavelength_nm: f64) -> f64 {
        self.interpolate(&self.extinction_ratio, wavelength_nm)
    }

    pub fn ssa_at(&self, wavelength_nm: f64) -> f64 {
        self.interpolate(&self.single_scattering_albedo, wavelength_nm)
    }

    pub fn g_at(&self, wavelength_nm: f64) -> f64 {
        self.interpolate(&self.asymmetry_g, wavelength_nm)
    }

    /// Ångström exponent between 440 and 870 nm (the AERONET convention).
    pub fn angstrom_exponent(&self) -> f64 {
        -(self.extinction_ratio_at(440.0) / self.extinction_ratio_at(870.0)).ln()
            / (440.0f64 / 870.0).ln()
    }
}

/// Wavelength grid of the type tables, nm: 350–900 nm at 10 nm (covers 440 and 870 nm).
pub fn optics_grid_nm() -> Vec<f64> {
    (35..=90).map(|i| i as f64 * 10.0).collect()
}

/// Radii per size distribution in the Mie average; 0.06 in ln r, about 12 per ln σ.
const MIE_POINTS: usize = 160;

/// What `compute` makes of a mixture type's components, computed once per process and shared
/// (None for `None` and `Custom`, which have no components).
fn per_type<T: Send + Sync + 'static>(
    cache: &'static OnceLock<Mutex<HashMap<AerosolType, &'static T>>>,
    t: AerosolType,
    compute: fn(Mixture) -> T,
) -> Option<&'static T> {
    let info = t.info()?;
    let cache = cache.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(v) = cache.lock().ok()?.get(&t) {
        return Some(v);
    }
    let value: &'static T = Box::leak(Box::new(compute(info.mixture)));
    cache.lock().ok()?.insert(t, value);
    Some(value)
}

/// The Mie optics of a mixture type, computed once per process and shared.
pub fn type_optics(t: AerosolType) -> Option<&'static TypeOptics> {
    static CACHE: OnceLock<Mutex<HashMap<AerosolType, &'static TypeOptics>>> = OnceLock::new();
    per_type(&CACHE, t, compute_mixture)
}

fn compute_mixture(mixture: Mixture) -> TypeOptics {
    let grid = optics_grid_nm();
    let components: Vec<(Component, f64)> = mixture
        .iter()
        .map(|&(name, n)| (Component::load(name, RELATIVE_HUMIDITY_PERCENT), n))
        .collect();
    let bulk: Vec<BulkOptics> = grid
        .iter()
        .map(|&w| {
            let (mut ext, mut sca, mut g_sca) = (0.0, 0.0, 0.0);
            for (c, n) in &components {
                let b = c.optics(w);
                ext += n * b.ext_um2;
                sca += n * b.sca_um2;
                g_sca += n * b.sca_um2 * b.g;
            }
            BulkOptics {
                ext_um2: ext,
                sca_um2: sca,
                g: g_sca / sca,
            }
        })
        .collect();
    let mut optics = TypeOptics {
        wavelengths_nm: grid,
        extinction_ratio: bulk.iter().map(|b| b.ext_um2).collect(),
        single_scattering_albedo: bulk
            .iter()
            .map(BulkOptics::single_scattering_albedo)
            .collect(),
        asymmetry_g: bulk.iter().map(|b| b.g).collect(),
    };
    let reference = optics.extinction_ratio_at(AOD_REFERENCE_NM);
    optics
        .extinction_ratio
        .iter_mut()
        .for_each(|e| *e /= reference);
    optics
}

/// Scattering angles of a tabulated Mie phase function: θ_i = π·(i/(N−1))², dense towards the
/// forward peak (the first step is 0.011°, the last 2.8°).
pub const MIE_PHASE_ANGLES: usize = 128;

/// Wavelengths at which a type's Mie phase function is computed, nm. Between two of them the
/// phase function is the linear mix of theirs, which keeps it normalised.
pub const MIE_PHASE_WAVELENGTHS_NM: [f64; 5] = [350.0, 450.0, 550.0, 700.0, 900.0];

/// A mixture type's phase function from the Mie code, tabulated: what Henyey–Greenstein with
/// the same g misses (the forward peak of large particles, the back-scatter of the spheres).
#[derive(Debug, Clone, PartialEq)]
pub struct MiePhase {
    /// ln p (p in sr⁻¹) at the angles of [`MIE_PHASE_ANGLES`], one row per wavelength of
    /// [`MIE_PHASE_WAVELENGTHS_NM`]; each row integrates to 1 over the sphere as
    /// [`crate::phase::tabulated`] interpolates it.
    pub ln_rows: Vec<f64>,
    /// The scattering matrix over the phase function at the same angles and wavelengths:
    /// (b₁, a₃, b₂) = (S₁₂, S₃₃, S₃₄)/S₁₁ of the mixture (spheres: a₂ = 1, a₄ = a₃).
    pub matrix_rows: Vec<[f64; 3]>,
}

impl MiePhase {
    /// Where `wavelength_nm` falls among the rows: a fractional row index (clamped to the ends).
    pub fn node_at(wavelength_nm: f64) -> f64 {
        let w = &MIE_PHASE_WAVELENGTHS_NM;
        let x = wavelength_nm.clamp(w[0], w[w.len() - 1]);
        let i = w.partition_point(|&v| v <= x).clamp(1, w.len() - 1);
        (i - 1) as f64 + (x - w[i - 1]) / (w[i] - w[i - 1])
    }

    /// The phase function (sr⁻¹) at `wavelength_nm` and scattering cosine `nu`.
    pub fn phase(&self, wavelength_nm: f64, nu: f64) -> f64 {
        crate::phase::tabulated(
            &self.ln_rows,
            MIE_PHASE_ANGLES,
            Self::node_at(wavelength_nm),
            nu,
        )
    }

    /// The scattering matrix over the phase function at `wavelength_nm` and scattering cosine
    /// `nu`: each element linear in u = √(θ/π) within a row, like ln p, and between two
    /// wavelengths' rows weighted by their phase functions, as the mixed phase mixes them.
    pub fn matrix(&self, wavelength_nm: f64, nu: f64) -> ReducedMatrix {
        let n = MIE_PHASE_ANGLES;
        let rows = self.ln_rows.len() / n;
        let u = (nu.clamp(-1.0, 1.0).acos() / std::f64::consts::PI).sqrt();
        let x = u * (n - 1) as f64;
        let i = (x as usize).min(n - 2);
        let t = x - i as f64;
        let at = |r: usize| {
            let (l, m) = (&self.ln_rows[r * n..], &self.matrix_rows[r * n..]);
            let p = (l[i] + t * (l[i + 1] - l[i])).exp();
            (
                p,
                std::array::from_fn::<f64, 3, _>(|k| m[i][k] + t * (m[i + 1][k] - m[i][k])),
            )
        };
        let node = Self::node_at(wavelength_nm);
        let r0 = (node as usize).min(rows - 1);
        let r1 = (r0 + 1).min(rows - 1);
        let s = node - r0 as f64;
        let ((p0, m0), (p1, m1)) = (at(r0), at(r1));
        let (w0, w1) = ((1.0 - s) * p0, s * p1);
        let [b1, a3, b2] = std::array::from_fn(|k| (w0 * m0[k] + w1 * m1[k]) / (w0 + w1));
        ReducedMatrix {
            b1,
            a2: 1.0,
            a3,
            a4: a3,
            b2,
        }
    }
}

/// The tabulated Mie phase function of a mixture type (None for `None` and `Custom`), computed
/// once per process and cached, as the coarse modes reach size parameters x ≈ 1 800.
pub fn type_phase(t: AerosolType) -> Option<&'static MiePhase> {
    static CACHE: OnceLock<Mutex<HashMap<AerosolType, &'static MiePhase>>> = OnceLock::new();
    per_type(&CACHE, t, compute_phase)
}

fn compute_phase(mixture: Mixture) -> MiePhase {
    use rayon::prelude::*;
    let n = MIE_PHASE_ANGLES;
    let nus: Vec<f64> = (0..n)
        .map(|i| {
            let u = i as f64 / (n - 1) as f64;
            (std::f64::consts::PI * u * u).cos()
        })
        .collect();
    let components: Vec<(Component, f64)> = mixture
        .iter()
        .map(|&(name, count)| (Component::load(name, RELATIVE_HUMIDITY_PERCENT), count))
        .collect();
    let jobs: Vec<(usize, usize)> = (0..MIE_PHASE_WAVELENGTHS_NM.len())
        .flat_map(|w| (0..components.len()).map(move |c| (w, c)))
        .collect();
    // (wavelength, component) → (C_sca, its scattering matrix) per particle.
    let parts: Vec<(usize, f64, Vec<mie::MatrixElements>)> = jobs
        .par_iter()
        .map(|&(w, c)| {
            let (component, count) = &components[c];
            let (bulk, differential) = component.scattering(MIE_PHASE_WAVELENGTHS_NM[w], &nus);
            (
                w,
                count * bulk.sca_um2,
                differential.iter().map(|d| d.map(|e| count * e)).collect(),
            )
        })
        .collect();
    let mut ln_rows = Vec::with_capacity(MIE_PHASE_WAVELENGTHS_NM.len() * n);
    let mut matrix_rows = Vec::with_capacity(MIE_PHASE_WAVELENGTHS_NM.len() * n);
    for w in 0..MIE_PHASE_WAVELENGTHS_NM.len() {
        let (mut sca, mut differential) = (0.0, vec![[0.0; 4]; n]);
        for (_, s, d) in parts.iter().filter(|(pw, _, _)| *pw == w) {
            sca += s;
            for (a, b) in differential.iter_mut().zip(d) {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
            }
        }
        let row: Vec<f64> = differential
            .iter()
            .map(|d| (d[0] / sca).max(f64::MIN_POSITIVE).ln())
            .collect();
        matrix_rows.extend(differential.iter().map(|d| {
            if d[0] > 0.0 {
                [d[1] / d[0], d[2] / d[0], d[3] / d[0]]
            } else {
                [0.0, 1.0, 0.0]
            }
        }));
        // Normalise the row as it will be read: the interpolation, not the nodes, integrates to 1.
        let norm = crate::phase::tabulated_integral(&row, n).ln();
        ln_rows.extend(row.iter().map(|l| l - norm));
    }
    MiePhase {
        ln_rows,
        matrix_rows,
    }
}

/// An OPAC component at one humidity: size distribution and refractive index table.
struct Component {
    size: LogNormal,
    /// Particle density, g cm⁻³.
    rho_g_cm3: f64,
    wavelengths_nm: Vec<f64>,
    n: Vec<f64>,
    k: Vec<f64>,
}

impl Component {
    fn load(name: &str, rh_percent: u32) -> Component {
        // Non-hygroscopic components exist only at 0 % humidity.
        let sizes = tables::opac_size_distributions().filter("component", name);
        let rh_rows = sizes.text("rh_percent");
        let rh = if rh_rows.contains(&rh_percent.to_string().as_str()) {
            rh_percent.to_string()
        } else {
            "0".into()
        };
        let s = sizes.filter("rh_percent", &rh);
        let first = |col: &str| {
            s.numbers(col)
                .first()
                .copied()
                .unwrap_or_else(|| panic!("OPAC component {name} has no {col}"))
        };
        let size = LogNormal {
            r_mod_um: first("r_mod_um"),
            sigma: first("sigma"),
            r_min_um: first("r_min_um"),
            r_max_um: first("r_max_um"),
        };
        let idx = tables::opac_refractive_indices()
            .filter("component", name)
            .filter("rh_percent", &rh);
        Component {
            size,
            rho_g_cm3: first("rho_g_cm3"),
            wavelengths_nm: idx.numbers("wavelength_nm"),
            n: idx.numbers("n"),
            k: idx.numbers("k"),
        }
    }

    fn refractive_index(&self, wavelength_nm: f64) -> Complex64 {
        let w = &self.wavelengths_nm;
        let i = w
            .partition_point(|&v| v <= wavelength_nm)
            .clamp(1, w.len() - 1);
        let t = ((wavelength_nm - w[i - 1]) / (w[i] - w[i - 1])).clamp(0.0, 1.0);
        Complex64::new(
            self.n[i - 1] + t * (self.n[i] - self.n[i - 1]),
            self.k[i - 1] + t * (self.k[i] - self.k[i - 1]),
        )
    }

    /// Extinction per gram of particles, m² g⁻¹ (µm² over g cm⁻³ · µm³).
    fn mass_extinction_m2_per_g(&self, wavelength_nm: f64) -> f64 {
        self.optics(wavelength_nm).ext_um2
            / (self.rho_g_cm3 * self.size.mean_volume_um3(MIE_POINTS))
    }

    /// [`Component::optics`] and the mean differential scattering cross-section per particle
    /// at each scattering cosine of `nus`, µm² sr⁻¹.
    fn scattering(
        &self,
        wavelength_nm: f64,
        nus: &[f64],
    ) -> (BulkOptics, Vec<mie::MatrixElements>) {
        mie::lognormal_scattering(
            &self.size,
            wavelength_nm / 1000.0,
            self.refractive_index(wavelength_nm),
            MIE_POINTS,
            nus,
        )
    }

    fn optics(&self, wavelength_nm: f64) -> BulkOptics {
        mie::lognormal(
            &self.size,
            wavelength_nm / 1000.0,
            self.refractive_index(wavelength_nm),
            MIE_POINTS,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The types' Mie matrices over their phase functions: forward, the light keeps its
    /// polarisation and none is made (b₁ = 0, a₃ = 1); elsewhere no element exceeds 1 in size
    /// and b₁² + a₃² + b₂² ≤ 1 (a mixture of spheres is no purer than one, Hovenier's
    /// inequality); at a wavelength of the table, the node's own values.
    #[test]
    fn mie_matrices_are_physical_and_start_forward_as_the_identity() {
        for t in [
            AerosolType::DesertDust,
            AerosolType::Urban,
            AerosolType::MaritimeClean,
        ] {
            let phase = type_phase(t).expect("a mixture type");
            let forward = phase.matrix(550.0, 1.0);
            assert!(
                forward.b1.abs() < 1e-6 && (forward.a3 - 1.0).abs() < 1e-6,
                "{t:?}"
            );
            for k in 0..=60 {
                let nu = (k as f64 * 3.0f64).to_radians().cos();
                for w in [400.0, 550.0, 800.0] {
                    let m = phase.matrix(w, nu);
                    assert!(
                        m.b1 * m.b1 + m.a3 * m.a3 + m.b2 * m.b2 <= 1.0 + 1e-9,
                        "{t:?} {w} {nu}: {m:?}"
                    );
                }
            }
            let n = MIE_PHASE_ANGLES;
            let (row, i) = (2, 90);
            let theta = std::f64::consts::PI * (i as f64 / (n - 1) as f64).powi(2);
            let m = phase.matrix(MIE_PHASE_WAVELENGTHS_NM[row], theta.cos());
            let node = phase.matrix_rows[row * n + i];
            assert!(
                (m.b1 - node[0]).abs() < 1e-9 && (m.a3 - node[1]).abs() < 1e-9,
                "{t:?}"
            );
        }
    }

    /// Dust's and sea salt's Mie phase functions integrate to 1 at every wavelength, have the
    /// mixture's g for mean cosine, and peak forward far above Henyey–Greenstein with that g
    /// (the coarse modes' diffraction peak), as the issue of their shape asked.
    #[test]
    fn mie_phase_functions_are_normalised_with_the_types_g_and_a_forward_peak() {
        use crate::phase::{henyey_greenstein, tabulated, tabulated_integral};
        use crate::quadrature::integrate_adaptive;
        let n = MIE_PHASE_ANGLES;
        for t in [AerosolType::DesertDust, AerosolType::MaritimeClean] {
            let phase = type_phase(t).expect("a mixture type");
            assert_eq!(phase.ln_rows.len(), n * MIE_PHASE_WAVELENGTHS_NM.len());
            for (r, &w) in MIE_PHASE_WAVELENGTHS_NM.iter().enumerate() {
                let row = &phase.ln_rows[r * n..(r + 1) * n];
                assert!(
                    (tabulated_integral(row, n) - 1.0).abs() < 1e-9,
                    "{t:?} {w} nm"
                );
                let mean_cos = 2.0
                    * std::f64::consts::PI
                    * integrate_adaptive(
                        |nu| nu * tabulated(row, n, 0.0, nu),
                        -1.0,
                        1.0,
                        1e-9,
                        0.0,
                    )
                    .value;
                let g = type_optics(t).expect("optics").g_at(w);
                assert!(
                    (mean_cos - g).abs() < 0.02,
                    "{t:?} {w} nm: ⟨cos⟩ {mean_cos}, g {g}"
                );
                let forward = phase.phase(w, 1.0);
                assert!(
                    forward > 2.5 * henyey_greenstein(1.0, g),
                    "{t:?} {w} nm: p(0°) {forward} against HG {}",
                    henyey_greenstein(1.0, g)
                );
            }
            // Between the rows the mix stays normalised.
            let mid = |nu| phase.phase(500.0, nu);
            let total =
                2.0 * std::f64::consts::PI * integrate_adaptive(mid, -1.0, 1.0, 1e-9, 0.0).value;
            assert!((total - 1.0).abs() < 1e-3, "{t:?} at 500 nm: {total}");
        }
        assert!(type_phase(AerosolType::Custom).is_none());
    }

    #[test]
    fn every_type_lies_in_its_documented_range() {
        for t in AerosolType::MIXTURES {
            let info = t.info().unwrap();
            let o = type_optics(t).unwrap();
            let (ssa, g, a) = (o.ssa_at(550.0), o.g_at(550.0), o.angstrom_exponent());
            let p = info.plausible;
            assert!(
                ssa >= p.ssa.0 && ssa <= p.ssa.1,
                "{t:?}: SSA {ssa:.4} outside {:?}",
                p.ssa
            );
            assert!(
                g >= p.g.0 && g <= p.g.1,
                "{t:?}: g {g:.4} outside {:?}",
                p.g
            );
            assert!(
                a >= p.angstrom.0 && a <= p.angstrom.1,
                "{t:?}: Ångström {a:.3} outside {:?}",
                p.angstrom
            );
            assert!((o.extinction_ratio_at(550.0) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn spectral_optics_are_physical_everywhere() {
        for t in AerosolType::MIXTURES {
            let o = type_optics(t).unwrap();
            for i in 0..o.wavelengths_nm.len() {
                assert!(o.extinction_ratio[i] > 0.0);
                assert!(
                    o.single_scattering_albedo[i] > 0.0 && o.single_scattering_albedo[i] <= 1.0
                );
                assert!(o.asymmetry_g[i] > 0.0 && o.asymmetry_g[i] < 1.0);
            }
        }
    }

    #[test]
    fn fine_particles_have_a_steeper_spectrum_than_dust() {
        let urban = type_optics(AerosolType::Urban).unwrap().angstrom_exponent();
        let dust = type_optics(AerosolType::DesertDust)
            .unwrap()
            .angstrom_exponent();
        assert!(urban > dust + 0.5, "urban {urban}, dust {dust}");
    }

    #[test]
    fn names_and_profiles_are_complete() {
        for t in AerosolType::ALL {
            assert_eq!(AerosolType::from_cli_name(t.cli_name()), Some(t));
        }
        for t in AerosolType::MIXTURES {
            let h = t.guimera_scale_height_m().unwrap();
            assert!(h >= 0.0, "{t:?}");
            let mixing = t.mixing_layer_scale_height_m();
            assert_eq!(mixing.is_none(), t == AerosolType::Background, "{t:?}");
            assert!(
                mixing.is_none_or(|h| h > 0.0 && h < 20_000.0),
                "{t:?}: {mixing:?}"
            );
        }
    }

    /// OPAC's shared layers: a free troposphere thinning upwards with a scale height of a few
    /// km, a stratospheric layer far thinner, and together an optical depth of a few hundredths
    /// (OPAC's free troposphere and stratosphere: 0.01 to 0.05 at 550 nm).
    #[test]
    fn the_shared_layers_are_thin_and_fall_with_height() {
        let s = shared_layers();
        assert!(
            (3000.0..15_000.0).contains(&s.free_troposphere_scale_height_m),
            "{s:?}"
        );
        assert!(
            s.stratosphere_per_m < 0.2 * s.free_troposphere_per_m,
            "{s:?}"
        );
        let tau = s.optical_depth_to(100_000.0);
        assert!((0.005..0.06).contains(&tau), "{tau}");
        assert_eq!(s.extinction_per_m(1000.0), 0.0);
        assert_eq!(s.extinction_per_m(40_000.0), 0.0);
        // The analytic column agrees with a quadrature of the profile.
        let n = 100_000;
        let dz = 40_000.0 / n as f64;
        let sum: f64 = (0..n)
            .map(|i| s.extinction_per_m((i as f64 + 0.5) * dz) * dz)
            .sum();
        assert!((sum - tau).abs() < 1e-4 * tau, "{sum} vs {tau}");
    }
}
