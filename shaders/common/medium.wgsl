// The medium of every table-based model: density profile and per-batch coefficients; twins of
// model::methods::shared::optics. And the local frame the view tables are built in.

struct Medium {
    rayleigh_scattering: vec4<f32>,
    aerosol_scattering: vec4<f32>,
    extinction: vec4<f32>,
}

// Profile values at altitude h, linear in x = sqrt(h / H); zero above the top.
fn densities(h: f32) -> vec3<f32> {
    if h > thickness() {
        return vec3<f32>(0.0);
    }
    let x = sqrt(max(h, 0.0) / thickness()) * f32(PROFILE_SAMPLES - 1u);
    let i = min(u32(floor(x)), PROFILE_SAMPLES - 2u);
    let f = x - f32(i);
    return mix(profile[i].xyz, profile[i + 1u].xyz, f);
}


// The batch is passed by value: load it once per invocation, not once per step.
fn medium(b: Batch, h: f32) -> Medium {
    let d = densities(h);
    var m: Medium;
    m.rayleigh_scattering = b.rayleigh_scattering * d.x;
    m.extinction = m.rayleigh_scattering + b.ozone_absorption * d.y;
    m.aerosol_scattering = vec4<f32>(0.0);
    if has_aerosol() {
        m.aerosol_scattering = b.aerosol_scattering * d.z;
        m.extinction += m.aerosol_scattering + b.aerosol_absorption * d.z;
    }
    return m;
}

// The sun in the local frame where azimuths are measured from it (twin of shared::local_sun).
fn local_sun(mu_s: f32) -> vec3<f32> {
    return vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);
}

fn direction_from_phi_theta(phi: f32, theta: f32) -> vec3<f32> {
    return vec3<f32>(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}
