//! Physical constants and Earth defaults: the one home of every number the model, the GPU
//! shaders (through the generated prelude) and the app share.

/// Boltzmann constant, J/K (CODATA 2018, exact).
pub const BOLTZMANN_J_PER_K: f64 = 1.380649e-23;
/// Planck constant, J·s (CODATA 2018, exact).
pub const PLANCK_J_S: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum, m/s (exact).
pub const SPEED_OF_LIGHT_M_PER_S: f64 = 299_792_458.0;
/// One Dobson unit as a column number density, molecules·m⁻² (2.6867e16 cm⁻²).
pub const DOBSON_UNIT_PER_M2: f64 = 2.6867e20;
/// Number density of standard air (288.15 K, 1013.25 hPa), m⁻³ (Bodhaine et al. 1999, eq. 2).
pub const STANDARD_AIR_NUMBER_DENSITY_M3: f64 = 2.546899e25;
/// Maximum luminous efficacy of photopic vision, lm/W (CIE).
pub const MAX_LUMINOUS_EFFICACY_LM_PER_W: f64 = 683.0;

/// Earth's mean radius used by the renderer, m (Bruneton 2017, Hillaire 2020; docs/architecture.md).
pub const EARTH_RADIUS_M: f64 = 6_360_000.0;
/// Height of the top of the atmosphere above the ground, m.
pub const EARTH_ATMOSPHERE_TOP_M: f64 = 100_000.0;
/// Angular radius of the sun seen from the Earth, radians (0.2666°).
pub const SUN_ANGULAR_RADIUS_RAD: f64 = 0.2666 * std::f64::consts::PI / 180.0;

/// Solar limb darkening by wavelength, Hestroffer & Magnan (1998, eq. 5), their one-parameter
/// law I(μ′)/I(1) = μ′^α fitted to Pierce & Slaughter (1977) and Neckel & Labs (1994):
/// α = a + b/λ (λ in µm) with (a, b) from [`SUN_LIMB_ALPHA_LONG`] where 1/λ is below
/// [`SUN_LIMB_ALPHA_BREAK_PER_UM`] (λ above 417 nm), else from [`SUN_LIMB_ALPHA_SHORT`].
pub const SUN_LIMB_ALPHA_LONG: [f64; 2] = [-0.023, 0.292];
/// (a, b) of the limb-darkening exponent below 417 nm.
pub const SUN_LIMB_ALPHA_SHORT: [f64; 2] = [-0.507, 0.441];
/// Wavenumber (µm⁻¹) between the limb-darkening fits' two ranges.
pub const SUN_LIMB_ALPHA_BREAK_PER_UM: f64 = 2.4;

/// Visible range over which spectral quantities are integrated, nm (the CIE table's range).
pub const VISIBLE_MIN_NM: f64 = 360.0;
/// Upper end of the visible range, nm.
pub const VISIBLE_MAX_NM: f64 = 830.0;
/// Reference wavelength of aerosol optical depth, nm.
pub const AOD_REFERENCE_NM: f64 = 550.0;

/// Fit of the air density of García Liñán (2023): n(h)/n(0) = exp(-a·h^b), h in km.
pub const AIR_DENSITY_FIT_A: f64 = 0.07771971;
/// Exponent b of the air density fit.
pub const AIR_DENSITY_FIT_B: f64 = 1.16364243;

/// Scale height of the exponential air of Bruneton & Neyret (2008) and Hillaire (2020), m: the
/// real-time literature's Earth (`AirProfile::Exponential8km`).
pub const EXPONENTIAL_AIR_SCALE_HEIGHT_M: f64 = 8_000.0;

/// The ozone "tent" of Bruneton (2017) and Hillaire (2020): density rising linearly from zero
/// at 10 km to its peak at 25 km and back to zero at 40 km (`OzoneProfile::Tent`). Peak, m.
pub const OZONE_TENT_PEAK_M: f64 = 25_000.0;
/// Half width of the ozone tent at its base, m.
pub const OZONE_TENT_HALF_WIDTH_M: f64 = 15_000.0;

/// Log-normal ozone profile fit of García Liñán (2023): n(h) ∝ exp(-k·(ln h − c)²)/h, h in km.
pub const OZONE_FIT_C: f64 = 3.22261;
/// Width parameter k of the ozone fit, 1/(2·0.3²).
pub const OZONE_FIT_K: f64 = 5.555_555_55;
