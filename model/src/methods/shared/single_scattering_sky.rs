//! The sky pass of the table-free single-scattering models (`nishita`, `trapezoid`, `schuler`,
//! `galaj-taylor`, `galaj-spline`, their `-ms` rows, `nishita-96`, `haber`): per pixel, single
//! scattering marched along the view ray with the model's own transmittance towards the sun at
//! every sample, plus the model's higher orders ([`HigherOrders`]), and the ground behind it lit
//! by the sun and the higher orders' skylight; from above the atmosphere the march starts where
//! the ray enters it. The models differ in their way to the sun ([`Way`]: a quadrature rule
//! along the sun's ray, or a closed form on the exponential medium, [`super::exponential`]) and
//! in their higher orders. Twin of `shaders/shared/single_scattering_sky.wgsl`,
//! which reads the counts, the way and the fitted medium from the model's constants.

use super::exponential::{self, ExponentialMedium};
use super::ray::camera_coords;
use super::sun_disk::visible_fraction;
use super::transmittance::{transmittance_h_mu_from_texel, transmittance_texel_from_h_mu};
use super::{
    Lanes, Lut, Params, TableSpec, aerosol_phase, entry_into_atmosphere, rayleigh_phase,
    segment_weight,
};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top};
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Samples of the view march and of each march towards the sun: (view, sun). Twice and once
/// the sky-view march's count (64 and 32 at Medium), O'Neil's budget scaled with the quality;
/// every table-free single-scattering model takes the same, so that they differ only in their
/// way to the sun.
pub fn steps(p: &Params) -> (u32, u32) {
    (2 * p.steps.sky_view, p.steps.sky_view)
}

/// The values the GPU reads from `globals.model`: (view samples, sun intervals, the way to the
/// sun's code, 0), then the fitted exponential medium ([`ExponentialMedium::constants`]).
pub fn constants(p: &Params, way: Way) -> [f64; 12] {
    let (view, sun) = steps(p);
    let mut c = [0.0; 12];
    c[..4].copy_from_slice(&[f64::from(view), f64::from(sun), way.code(), 0.0]);
    c[4..].copy_from_slice(&ExponentialMedium::fit(p).constants());
    c
}

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun` (the sun's disk not
/// included: `SkyModel::sun`): `view_steps` midpoint samples, each lit through
/// `sun_transmittance(h, mu_s)` (per lane, the disk's visible fraction included), plus the
/// model's `higher` orders ([`HigherOrders`]; none for single scattering alone); the ground
/// behind is lit by the sun and by the higher orders' skylight.
#[allow(clippy::too_many_arguments)]
pub fn radiance(
    p: &Params,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
    view_steps: u32,
    sun_transmittance: impl Fn(f64, f64) -> Lanes,
    higher: &dyn HigherOrders,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let Some(c) = camera_coords(p, (position, h), dir, sun) else {
        return Lanes::ZERO;
    };
    let (h0, mu0, mu_s0, nu) = (c.h, c.mu, c.mu_s, c.nu);
    let b = &p.batches[layer];
    let (phase_r, phase_a) = (rayleigh_phase(p, layer, nu), aerosol_phase(p, layer, nu));
    let r0 = big_r + h0;
    let t_max = if c.ground {
        distance_to_ground(h0, mu0, big_r)
    } else {
        distance_to_top(h0, mu0, big_r, p.top_radius_m)
    };
    let dt = t_max / f64::from(view_steps);
    let mut inscattered = Lanes::ZERO;
    let mut throughput = Lanes::ONE;
    for s in 0..view_steps {
        let t = (f64::from(s) + 0.5) * dt;
        let (h_t, r_t) = altitude_along(h0, mu0, t, big_r);
        let mu_t = ((r0 * mu0 + t) / r_t).clamp(-1.0, 1.0);
        let mu_s_t = ((r0 * mu_s0 + t * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let sun_t = sun_transmittance(h_t, mu_s_t);
        let (air, aerosol) = higher.source(p, layer, (h_t, mu_s_t), mu_t, nu);
        let weight = segment_weight(m.extinction, dt);
        for i in 0..4 {
            let source = m.rayleigh_scattering[i] * (phase_r[i] * sun_t[i] + air[i])
                + m.aerosol_scattering[i] * (phase_a[i] * sun_t[i] + aerosol[i]);
            inscattered[i] += throughput[i] * weight[i] * source;
            throughput[i] *= (-m.extinction[i] * dt).exp();
        }
    }
    let mut l: Lanes = inscattered * b.solar_irradiance;
    if c.ground {
        let mu_s_g = ((r0 * mu_s0 + t_max * nu) / big_r).clamp(-1.0, 1.0);
        let sun_g = sun_transmittance(0.0, mu_s_g);
        let sky_g = higher.ground_irradiance(p, layer, mu_s_g);
        for i in 0..4 {
            let ground = b.ground_albedo[i] / PI
                * b.solar_irradiance[i]
                * (sun_g[i] * mu_s_g.max(0.0) + sky_g[i]);
            l[i] += throughput[i] * ground;
        }
    }
    l
}

/// A quadrature rule over equal intervals of a ray.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// One sample at the middle of each interval.
    Midpoint,
    /// Samples at the ends of each interval, half weight at the ray's two ends.
    Trapezoid,
}

/// Optical depth per lane from altitude `h` (m) along zenith cosine `mu` to the top of the
/// atmosphere, by `rule` over `intervals` equal intervals.
pub fn optical_depth(
    p: &Params,
    layer: usize,
    h: f64,
    mu: f64,
    intervals: u32,
    rule: Rule,
) -> Lanes {
    let d = distance_to_top(h, mu, p.bottom_radius_m, p.top_radius_m);
    let dt = d / f64::from(intervals);
    let (samples, offset) = match rule {
        Rule::Midpoint => (intervals, 0.5),
        Rule::Trapezoid => (intervals + 1, 0.0),
    };
    let mut depth = [0.0; 4];
    for s in 0..samples {
        let (h_t, _) = altitude_along(h, mu, (f64::from(s) + offset) * dt, p.bottom_radius_m);
        let w = if rule == Rule::Trapezoid && (s == 0 || s == intervals) {
            0.5
        } else {
            1.0
        };
        let m = p.medium(layer, h_t);
        for (d, e) in depth.iter_mut().zip(m.extinction) {
            *d += w * e * dt;
        }
    }
    Lanes(depth)
}

/// Transmittance per lane from altitude `h` (m) towards the sun at zenith cosine `mu_s`
/// through [`optical_depth`], times the visible fraction of the sun's disk above the horizon
/// (0, and no integral, where the planet hides it).
pub fn sun_transmittance(
    p: &Params,
    layer: usize,
    h: f64,
    mu_s: f64,
    intervals: u32,
    rule: Rule,
) -> Lanes {
    towards_sun(p, h, mu_s, || {
        optical_depth(p, layer, h, mu_s, intervals, rule)
    })
}

/// exp(−`depth`) times the visible fraction of the sun's disk from altitude `h` at zenith
/// cosine `mu_s`; `depth` is not evaluated where the planet hides the sun.
fn towards_sun(p: &Params, h: f64, mu_s: f64, depth: impl FnOnce() -> Lanes) -> Lanes {
    let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
    if visible <= 0.0 {
        return Lanes::ZERO;
    }
    depth().map(|d| (-d).exp() * visible)
}

/// A table-free model's way to the optical depth towards the sun.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Way {
    /// Integrated along the sun's ray by a quadrature rule (`nishita`, `trapezoid`).
    March(Rule),
    /// Schuler's (2012) Chapman function on the exponential medium (`schuler`).
    SchulerChapman,
    /// Gałaj et al.'s (2021) Taylor-series integral on the exponential medium (`galaj-taylor`).
    GalajTaylor,
    /// Leenman's (2025) homogeneous shell one scale height thick on the exponential medium
    /// (`flat`, `raymarched`).
    HomogeneousShell,
    /// Gałaj et al.'s (2021) Hermite spline over a mesh of the exponential medium's integrand
    /// (`galaj-spline`).
    GalajSpline,
}

impl Way {
    /// The code the GPU branches on (uniform across a dispatch).
    pub fn code(self) -> f64 {
        match self {
            Way::March(Rule::Midpoint) => 0.0,
            Way::March(Rule::Trapezoid) => 1.0,
            Way::SchulerChapman => 2.0,
            Way::GalajTaylor => 3.0,
            Way::HomogeneousShell => 4.0,
            Way::GalajSpline => 5.0,
        }
    }

    /// Whether the moving sky reads this way from [`SUN_ROUTE_TABLE`]: a nested integral per
    /// view sample (either rule's march, the spline over its mesh) costs tens of medium
    /// evaluations where the closed forms cost a few; tabulated, a sun move of these models
    /// rebuilds the moving sky at about the closed forms' cost. The table holds optical depth:
    /// the trapezoid rule's grows fast along grazing rays (its first sample, at the point
    /// itself, weighs half an interval of the whole ray), so blending the depths and then
    /// taking the exponential follows the march with a low sun where blending the
    /// exponentials does not.
    pub fn tabulated_in_motion(self) -> bool {
        matches!(self, Way::March(_) | Way::GalajSpline)
    }
}

/// The model's own optical depth towards the top of the atmosphere by its way to the sun (per
/// lane), on the transmittance table's grid and mapping: the nested integral of the marches,
/// computed once per atmosphere, from which their moving sky (`super::moving_sky`) is built.
/// The still frame marches every sample's way to the sun.
pub const SUN_ROUTE_TABLE: TableSpec = TableSpec {
    id: "sun-route",
    label: "optical depth by the model's way to the sun (for the moving sky)",
    invalidated_by: crate::methods::Inputs::ATMOSPHERE,
    transmittance: false,
    ..super::transmittance::TABLE
};

/// The way to the sun of a table-free model, with what it needs: the march's interval count,
/// the fitted exponential medium of the closed forms, the spline's mesh.
pub struct SunRoute {
    pub way: Way,
    pub intervals: u32,
    pub medium: ExponentialMedium,
    /// The integrand's mesh of [`Way::GalajSpline`] (`galaj_spline::MESH`); None otherwise.
    pub mesh: Option<Lut>,
    /// [`SUN_ROUTE_TABLE`] of a way tabulated in motion, built when first asked for.
    table: OnceLock<Lut>,
}

impl SunRoute {
    pub fn new(p: &Params, way: Way) -> SunRoute {
        SunRoute {
            way,
            intervals: steps(p).1,
            medium: ExponentialMedium::fit(p),
            mesh: (way == Way::GalajSpline)
                .then(|| crate::methods::galaj_spline::compute_mesh_lut(p)),
            table: OnceLock::new(),
        }
    }

    /// [`SUN_ROUTE_TABLE`] of this way: the optical depth at each texel's (h, mu). The depth,
    /// not its exponential, is what the look-up blends: along grazing rays the depth varies
    /// about linearly between texels where exp(−depth) falls by orders of magnitude, so the
    /// blend of exponentials overshoots where the blend of depths does not.
    pub fn table(&self, p: &Params) -> &Lut {
        self.table.get_or_init(|| {
            Lut::from_spec(&SUN_ROUTE_TABLE, p.batches.len(), |layer, _, y, x| {
                let (h, mu) = transmittance_h_mu_from_texel(p, x as f64, y as f64);
                self.optical_depth(p, layer, h, mu)
            })
        })
    }

    /// [`SunRoute::transmittance`] as the moving sky takes it: looked up in
    /// [`SunRoute::table`] for a way tabulated in motion ([`Way::tabulated_in_motion`]).
    pub fn transmittance_in_motion(&self, p: &Params, layer: usize, h: f64, mu_s: f64) -> Lanes {
        if !self.way.tabulated_in_motion() {
            return self.transmittance(p, layer, h, mu_s);
        }
        let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
        if visible <= 0.0 {
            return Lanes::ZERO;
        }
        let (fx, fy) = transmittance_texel_from_h_mu(p, h, mu_s);
        let depth = self.table(p).bilinear(layer, fx, fy, 0);
        depth.map(|d| (-d).exp() * visible)
    }

    /// Optical depth per lane from altitude `h` (m) along zenith cosine `mu` to the top.
    pub fn optical_depth(&self, p: &Params, layer: usize, h: f64, mu: f64) -> Lanes {
        let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
        match self.way {
            Way::March(rule) => optical_depth(p, layer, h, mu, self.intervals, rule),
            Way::SchulerChapman => self.medium.optical_depth(p, layer, h, mu, |h, mu, hh| {
                exponential::schuler_chapman(h, mu, hh, big_r)
            }),
            Way::GalajTaylor => self.medium.optical_depth(p, layer, h, mu, |h, mu, hh| {
                exponential::galaj_taylor(
                    h,
                    mu,
                    hh,
                    big_r,
                    top,
                    (exponential::GALAJ_TAYLOR_A, exponential::GALAJ_TAYLOR_B),
                )
            }),
            Way::HomogeneousShell => self.medium.optical_depth(p, layer, h, mu, |h, mu, hh| {
                exponential::homogeneous_shell(h, mu, hh, big_r)
            }),
            Way::GalajSpline => {
                let mesh = self
                    .mesh
                    .as_ref()
                    .expect("SunRoute::new builds the spline's mesh");
                let columns = crate::methods::galaj_spline::columns(p, mesh, h, mu);
                self.medium
                    .optical_depth_from_columns(p, layer, h, mu, columns)
            }
        }
    }

    /// Transmittance per lane from altitude `h` (m) towards the sun at zenith cosine `mu_s`,
    /// times the visible fraction of the sun's disk above the horizon (0, and no integral,
    /// where the planet hides it).
    pub fn transmittance(&self, p: &Params, layer: usize, h: f64, mu_s: f64) -> Lanes {
        towards_sun(p, h, mu_s, || self.optical_depth(p, layer, h, mu_s))
    }

    /// [`SunRoute::transmittance`] seen from any altitude: from where the sun's ray enters the
    /// atmosphere when the point is above it (1 where the ray misses it).
    pub fn seen_from(&self, p: &Params, layer: usize, h: f64, mu_s: f64) -> Lanes {
        if h <= p.thickness_m() {
            return self.transmittance(p, layer, h, mu_s);
        }
        match entry_into_atmosphere(p, h, mu_s, mu_s, 1.0) {
            Some((mu_entry, _)) => self.transmittance(p, layer, p.thickness_m(), mu_entry),
            None => Lanes::ONE,
        }
    }

    /// The sun's disk for batch `layer` seen from altitude `h` at zenith cosine `mu_s`, where
    /// the disk's radiance per unit irradiance is `disk` (sr⁻¹, per lane): `SkyModel::sun` of
    /// the table-free models.
    pub fn sun_disk(&self, p: &Params, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        if disk.iter().all(|&d| d <= 0.0) {
            return Lanes::ZERO;
        }
        let tr = self.seen_from(p, layer, h, mu_s);
        p.batches[layer].solar_irradiance * tr * disk
    }
}

/// What a single-scattering model adds to the sunlight at every sample of its view march: the
/// light of the higher orders, and the skylight on the ground behind.
pub trait HigherOrders: Send + Sync {
    /// The higher orders' scattering source at (h, mu_s) towards the view (zenith cosine `mu`,
    /// view–sun cosine `nu`), per unit scattering coefficient of (air, aerosol), sr⁻¹ per unit
    /// solar irradiance.
    fn source(&self, p: &Params, layer: usize, at: (f64, f64), mu: f64, nu: f64) -> (Lanes, Lanes);
    /// The skylight on the ground where the sun's zenith cosine is `mu_s_g`, per unit solar
    /// irradiance (zero where the model lights the ground by the sun alone).
    fn ground_irradiance(&self, _p: &Params, _layer: usize, _mu_s_g: f64) -> Lanes {
        Lanes::ZERO
    }
    /// The model's table `id` that holds them, if any.
    fn table(&self, id: &str) -> Option<&Lut>;
}

/// Single scattering alone.
pub struct NoHigherOrders;

impl HigherOrders for NoHigherOrders {
    fn source(&self, _: &Params, _: usize, _: (f64, f64), _: f64, _: f64) -> (Lanes, Lanes) {
        (Lanes::ZERO, Lanes::ZERO)
    }
    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }
}

/// Hillaire's (2020) transmittance and multiple-scattering tables, added to a single-scattering
/// model as its isotropic higher orders Ψ_ms (the same for both constituents and every view).
pub struct HillaireHigherOrders {
    pub transmittance: Lut,
    pub multiple_scattering: Lut,
}

impl HillaireHigherOrders {
    pub fn compute(p: &Params) -> HillaireHigherOrders {
        let transmittance = super::transmittance::compute_transmittance_lut(p);
        let multiple_scattering =
            crate::methods::hillaire::multiple_scattering::compute_multiple_scattering_lut(
                p,
                &transmittance,
            );
        HillaireHigherOrders {
            transmittance,
            multiple_scattering,
        }
    }
}

impl HigherOrders for HillaireHigherOrders {
    fn source(
        &self,
        p: &Params,
        layer: usize,
        (h, mu_s): (f64, f64),
        _: f64,
        _: f64,
    ) -> (Lanes, Lanes) {
        let psi = crate::methods::hillaire::multiple_scattering::multiple_scattering(
            p,
            &self.multiple_scattering,
            layer,
            h,
            mu_s,
        );
        (psi, psi)
    }
    fn table(&self, id: &str) -> Option<&Lut> {
        match id {
            "transmittance" => Some(&self.transmittance),
            "multiple-scattering" => Some(&self.multiple_scattering),
            _ => None,
        }
    }
}

/// The tables of a single-scattering model with Hillaire's higher orders, in pass order: the
/// transmittance and Ψ_ms tables, then the moving sky (`super::moving_sky`).
pub const TABLES_WITH_HIGHER_ORDERS: [TableSpec; 3] = [
    super::transmittance::TABLE,
    crate::methods::hillaire::multiple_scattering::TABLE,
    super::moving_sky::TABLE,
];

/// The tables of a model whose way to the sun is tabulated in motion
/// ([`Way::tabulated_in_motion`]): its way to the sun, then the moving sky built from it.
pub const TABLES_NESTED: [TableSpec; 2] = [SUN_ROUTE_TABLE, super::moving_sky::TABLE];

/// [`TABLES_WITH_HIGHER_ORDERS`] of such a model, its way to the sun before the moving sky.
pub const TABLES_WITH_HIGHER_ORDERS_NESTED: [TableSpec; 4] = [
    super::transmittance::TABLE,
    crate::methods::hillaire::multiple_scattering::TABLE,
    SUN_ROUTE_TABLE,
    super::moving_sky::TABLE,
];

/// A single-scattering model: the optics, the view march's sample count, the model's way to
/// the sun, and the higher orders it adds ([`NoHigherOrders`] for single scattering alone).
pub struct SingleScattering {
    pub params: Params,
    pub view_steps: u32,
    pub sun_path: SunRoute,
    pub higher_orders: Box<dyn HigherOrders>,
}

impl crate::methods::SkyModel for SingleScattering {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        let p = &self.params;
        self.radiance_through(layer, at, dir, sun, |h, mu_s| {
            self.sun_path.transmittance(p, layer, h, mu_s)
        })
    }

    fn radiance_in_motion(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        let p = &self.params;
        self.radiance_through(layer, at, dir, sun, |h, mu_s| {
            self.sun_path.transmittance_in_motion(p, layer, h, mu_s)
        })
    }

    fn table(&self, id: &str) -> Option<&Lut> {
        if id == crate::methods::galaj_spline::MESH.id {
            return self.sun_path.mesh.as_ref();
        }
        if id == SUN_ROUTE_TABLE.id && self.sun_path.way.tabulated_in_motion() {
            return Some(self.sun_path.table(&self.params));
        }
        self.higher_orders.table(id)
    }

    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        self.sun_path.sun_disk(&self.params, layer, h, mu_s, disk)
    }
}

impl SingleScattering {
    /// The view march lit through `sun_t(h, mu_s)`, the transmittance to the sun.
    fn radiance_through(
        &self,
        layer: usize,
        at: (DVec3, f64),
        dir: DVec3,
        sun: DVec3,
        sun_t: impl Fn(f64, f64) -> Lanes,
    ) -> Lanes {
        let p = &self.params;
        radiance(
            p,
            layer,
            at,
            dir,
            sun,
            self.view_steps,
            sun_t,
            self.higher_orders.as_ref(),
        )
    }
}

/// A single-scattering model with `way` to the sun and the shared sample counts, with or
/// without Hillaire's higher orders (what the registry constructors of the table-free models
/// and their `-ms` rows build).
pub fn build(p: &Params, way: Way, with_higher_orders: bool) -> Box<dyn crate::methods::SkyModel> {
    Box::new(SingleScattering {
        params: p.clone(),
        view_steps: steps(p).0,
        sun_path: SunRoute::new(p, way),
        higher_orders: if with_higher_orders {
            Box::new(HillaireHigherOrders::compute(p))
        } else {
            Box::new(NoHigherOrders)
        },
    })
}
