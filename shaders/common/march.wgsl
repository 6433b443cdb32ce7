// The in-scattering march every table-based model shares; twin of
// model::methods::shared::march::march_inscattering. Each model's common file defines
// psi(layer, h, mu_s): its isotropic higher-order term per unit solar irradiance (sr⁻¹), which
// the march multiplies by the local scattering coefficient. Included by the models' passes,
// after common/, through their GpuMethod::common list.

struct Inscattering {
    // per unit solar irradiance, sr⁻¹
    radiance: vec4<f32>,
    transmittance: vec4<f32>,
}

// A march of no steps: no radiance, full transmittance (where sums and joins start).
fn nothing_marched() -> Inscattering {
    return Inscattering(vec4<f32>(0.0), vec4<f32>(1.0));
}

// (h, mu, mu_s, nu) start the ray; the march covers [t0, t1].
fn integrate_inscattering(
    layer: u32,
    start: vec4<f32>,
    t0: f32,
    t1: f32,
    steps: u32,
    spacing: u32,
) -> Inscattering {
    return integrate_inscattering_steps(layer, start, t0, t1, vec2<u32>(0u, steps), steps, spacing);
}

// Steps [run.x, run.y) of that march: their radiance from their own start and their
// transmittance (a part of a split march, split_join below).
fn integrate_inscattering_steps(
    layer: u32,
    start: vec4<f32>,
    t0: f32,
    t1: f32,
    run: vec2<u32>,
    steps: u32,
    spacing: u32,
) -> Inscattering {
    let h = start.x;
    let mu = start.y;
    let mu_s = start.z;
    let nu = start.w;
    let r = bottom_radius() + h;
    let b = batches[layer];
    let phase_r = rayleigh_phase(nu, b.rayleigh_depolarisation);
    let phase_a = aerosol_phase(nu, layer);
    var result = nothing_marched();
    for (var s = run.x; s < run.y; s++) {
        let seg = march_segment(spacing, t0, t1, s, steps);
        let dt = seg.y - seg.x;
        let ts = 0.5 * (seg.x + seg.y);
        // A point past the ground (the aerial-perspective columns march on through it, so
        // that rows interpolate smoothly) takes the ground's medium and light.
        let at = max(altitude_along(h, mu, ts), vec2<f32>(0.0, bottom_radius()));
        let mu_s_t = clamp((r * mu_s + ts * nu) / at.y, -1.0, 1.0);
        let m = medium(b, at.x);
        let sun_t = sun_transmittance(layer, at.x, mu_s_t);
        let higher = psi(layer, at.x, mu_s_t);
        let weight = result.transmittance * segment_weight(m.extinction, dt);
        let source = m.rayleigh_scattering * (phase_r * sun_t + higher)
            + m.aerosol_scattering * (phase_a * sun_t + higher);
        result.radiance += weight * source;
        result.transmittance *= exp(-m.extinction * dt);
    }
    return result;
}

// A texel's parts of an in-scattering march joined in order: each part's radiance (from its own
// start) dimmed by the transmittance of the parts before it. From uniform control flow
// (common/group.wgsl has the split's layout).
fn split_join(index: u32, part: Inscattering) -> Inscattering {
    if MARCH_SPLIT == 1u {
        return part;
    }
    split_a[index] = part.radiance;
    split_b[index] = part.transmittance;
    workgroupBarrier();
    var joined = nothing_marched();
    for (var k = 0u; k < MARCH_SPLIT; k++) {
        let j = index % SPLIT_TEXELS + k * SPLIT_TEXELS;
        joined.radiance += joined.transmittance * split_a[j];
        joined.transmittance *= split_b[j];
    }
    return joined;
}
