//! The path tracer's vector mode: order 1 against the exact vector single-scattering
//! integrator, the scalar mode where nothing polarises, symmetry about the sun's vertical, and
//! the depolarisation that multiple scattering brings.

use atmoscope_model::Atmosphere;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::geometry::{Ray, direction_from_angles};
use atmoscope_model::methods::path_tracer::{
    LANES, LaneOptics, Lanes, PathTracer, PathTracerSettings,
};
use atmoscope_model::methods::rng::Rng;
use atmoscope_model::methods::single_scattering;
use atmoscope_model::polarisation::{Stokes, meridian_frame, rayleigh_degree};
use atmoscope_model::scene::{AerosolPhase, AtmosphereSettings};
use glam::DVec3;

/// Mean and standard error of (I, Q, U, V) over `n` vector paths, per lane.
fn estimate(
    pt: &PathTracer,
    ray: &Ray,
    lanes: &LaneOptics,
    n: u64,
    seed: u64,
) -> [([f64; 4], [f64; 4]); LANES] {
    let (mut sum, mut sum2) = ([[0.0; 4]; LANES], [[0.0; 4]; LANES]);
    let up = meridian(ray);
    for k in 0..n {
        let mut rng = Rng::new(seed, 0, k);
        let s = pt.radiance_stokes(ray, up, lanes, &mut rng);
        for i in 0..LANES {
            for (c, v) in s[i].to_array().into_iter().enumerate() {
                sum[i][c] += v;
                sum2[i][c] += v * v;
            }
        }
    }
    let nf = n as f64;
    std::array::from_fn(|i| {
        let mean = sum[i].map(|s| s / nf);
        let se = std::array::from_fn(|c| {
            ((sum2[i][c] / nf - mean[c] * mean[c]).max(0.0) / (nf - 1.0)).sqrt()
        });
        (mean, se)
    })
}

/// The ray's meridian frame's e₁, the frame of `single_scattering::stokes`.
fn meridian(ray: &Ray) -> DVec3 {
    meridian_frame(ray.direction, ray.origin.normalize()).0
}

fn at_altitude(atm: &Atmosphere, h: f64, elevation: f64, azimuth: f64) -> Ray {
    Ray::new(
        DVec3::new(0.0, 0.0, atm.bottom_radius_m + h),
        direction_from_angles(elevation, azimuth),
    )
}

fn air_only(planet_radius_km: f64) -> AtmosphereSettings {
    let mut s = AtmosphereSettings::default();
    s.planet_radius_km = planet_radius_km;
    s.aerosol.kind = AerosolType::None;
    s.ground_albedo = 0.0;
    s
}

/// Order 1 of the vector tracer is the exact vector single-scattering integrator in I, Q and U
/// (V is then exactly zero): under desert dust's Mie matrix (which polarises along the
/// scattering plane at some angles), and in air over a planet of 100 000 km radius, the nearly
/// plane-parallel atmosphere of the published tables, where f64 must still hold.
#[test]
fn vector_order_one_agrees_with_the_vector_single_scattering_integrator() {
    let mut dust = AtmosphereSettings::default();
    dust.aerosol.kind = AerosolType::DesertDust;
    dust.aerosol.aod550 = 0.4;
    dust.aerosol.phase = AerosolPhase::Mie;
    dust.ground_albedo = 0.3;
    let settings = PathTracerSettings {
        max_order: Some(1),
        sun_angular_radius_rad: 1e-6,
        ..PathTracerSettings::default()
    };
    let sun = direction_from_angles(25.0, 180.0);
    for s in [dust, air_only(100_000.0)] {
        let atm = Atmosphere::new(&s);
        let pt = PathTracer::new(&atm, sun, settings);
        let lanes = LaneOptics::new(&atm, Lanes([440.0, 520.0, 610.0, 700.0]));
        let views = [
            at_altitude(&atm, 1.0, 30.0, 90.0),    // side sky
            at_altitude(&atm, 1.0, 20.0, 150.0),   // near the sun
            at_altitude(&atm, 1.0, 65.0, 0.0),     // 90° from the sun, away from it
            at_altitude(&atm, 5000.0, -20.0, 0.0), // ground seen from a plane
        ];
        for ray in views {
            let estimates = estimate(&pt, &ray, &lanes, 12_000, 5);
            for (i, (mean, se)) in estimates.into_iter().enumerate() {
                let w = lanes.wavelengths_nm[i];
                let exact = single_scattering::stokes(&atm, &ray, sun, w).to_array();
                for c in 0..3 {
                    assert!(
                        (mean[c] - exact[c]).abs() <= 4.0 * se[c] + 1e-9 * exact[0],
                        "planet {} km, {ray:?}, {w} nm, component {c}: {mean:?} ± {se:?} vs \
                         {exact:?}",
                        s.planet_radius_km
                    );
                }
                assert_eq!(mean[3], 0.0);
            }
        }
    }
}

/// Where nothing polarises (no air; an isotropic Henyey–Greenstein aerosol over a grey
/// ground) the vector mode's paths are the scalar mode's: the same I to rounding, Q = U = V =
/// 0, at every order.
#[test]
fn the_vector_mode_is_the_scalar_mode_where_nothing_polarises() {
    let mut s = AtmosphereSettings::default();
    s.air_density_scale = 0.0;
    s.aerosol.kind = AerosolType::Custom;
    s.aerosol.custom.asymmetry_g = 0.0;
    s.aerosol.custom.single_scattering_albedo = 0.95;
    s.aerosol.aod550 = 0.5;
    s.ground_albedo = 0.4;
    let atm = Atmosphere::new(&s);
    let pt = PathTracer::new(
        &atm,
        direction_from_angles(20.0, 0.0),
        PathTracerSettings::default(),
    );
    let lanes = LaneOptics::new(&atm, Lanes([450.0, 550.0, 650.0, 700.0]));
    for (elevation, azimuth) in [(10.0, 90.0), (60.0, 180.0), (-10.0, 0.0)] {
        let ray = at_altitude(&atm, 500.0, elevation, azimuth);
        for k in 0..300 {
            let scalar = pt.radiance(&ray, &lanes, &mut Rng::new(3, 1, k));
            let vector = pt.radiance_stokes(&ray, meridian(&ray), &lanes, &mut Rng::new(3, 1, k));
            for i in 0..LANES {
                let Stokes { i: v_i, q, u, v } = vector[i];
                assert!(
                    (v_i - scalar[i]).abs() <= 1e-12 * scalar[i],
                    "{v_i} vs {}",
                    scalar[i]
                );
                assert_eq!([q, u, v], [0.0; 3]);
            }
        }
    }
}

/// Views mirrored about the sun's vertical plane see the same I and Q and opposite U (the
/// frame's handedness mirrors too), at all orders through haze over a grey ground.
#[test]
fn mirrored_views_have_mirrored_stokes_vectors() {
    let mut s = AtmosphereSettings::default();
    s.aerosol.kind = AerosolType::Rural;
    s.aerosol.aod550 = 0.15;
    let atm = Atmosphere::new(&s);
    let sun = direction_from_angles(15.0, 90.0);
    let pt = PathTracer::new(&atm, sun, PathTracerSettings::default());
    let lanes = LaneOptics::new(&atm, Lanes([450.0, 500.0, 550.0, 600.0]));
    let mut us = Vec::new();
    for (elevation, offset) in [(30.0, 60.0), (55.0, 120.0)] {
        let a = estimate(
            &pt,
            &at_altitude(&atm, 1.0, elevation, 90.0 + offset),
            &lanes,
            6000,
            1,
        );
        let b = estimate(
            &pt,
            &at_altitude(&atm, 1.0, elevation, 90.0 - offset),
            &lanes,
            6000,
            2,
        );
        for i in 0..LANES {
            let ((ma, sa), (mb, sb)) = (a[i], b[i]);
            for (c, sign) in [(0, 1.0), (1, 1.0), (2, -1.0)] {
                let diff = ma[c] - sign * mb[c];
                assert!(
                    diff.abs() <= 4.0 * sa[c].hypot(sb[c]),
                    "{elevation}°, ±{offset}°, lane {i}, component {c}: {ma:?} vs {mb:?}"
                );
            }
            // Polarised light, so that the comparison says something.
            assert!(ma[1].hypot(ma[2]) > 0.1 * ma[0], "{ma:?} ± {sa:?}");
            us.push(ma[2] / ma[0]);
        }
    }
    // And U is not zero throughout: off the sun's vertical the angle turns.
    assert!(us.iter().any(|u| u.abs() > 0.05), "{us:?}");
}

/// In clear air over a black ground, 90° from the sun, multiple scattering lowers the degree of
/// polarisation below single scattering's (1−ρ)/(1+ρ), the more so at shorter wavelengths
/// (more scattering), and the polarisation stays across the scattering plane (horizontal for
/// the sun in the view's vertical plane: Q < 0, U ≈ 0).
#[test]
fn multiple_scattering_depolarises_the_band_of_strongest_polarisation() {
    let atm = Atmosphere::new(&air_only(6360.0));
    let sun = direction_from_angles(30.0, 0.0);
    let pt = PathTracer::new(&atm, sun, PathTracerSettings::default());
    let lanes = LaneOptics::new(&atm, Lanes([400.0, 450.0, 550.0, 700.0]));
    let ray = at_altitude(&atm, 1.0, 60.0, 180.0);
    let estimates = estimate(&pt, &ray, &lanes, 8000, 9);
    let mut degrees = [0.0; LANES];
    for (i, (mean, se)) in estimates.into_iter().enumerate() {
        let s = Stokes {
            i: mean[0],
            q: mean[1],
            u: mean[2],
            v: mean[3],
        };
        let rho = atm.optics(lanes.wavelengths_nm[i]).rayleigh_depolarisation;
        let single = rayleigh_degree(0.0, rho);
        degrees[i] = s.degree_of_polarization();
        assert!(
            degrees[i] < single - 0.03 && degrees[i] > 0.5,
            "{i}: {s:?} vs {single}"
        );
        assert!(
            mean[1] < 0.0 && mean[2].abs() < 4.0 * se[2] + 0.01 * mean[0],
            "{s:?}"
        );
    }
    assert!(degrees[0] < degrees[3], "{degrees:?}");
}
