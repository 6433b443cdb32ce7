// The polarisation of the real-time sky, for every model's sky pass (twin of
// model::methods::shared::polarisation): sunlight scattered once along the view ray, lit through the
// model's own transmittance towards the sun (`sun_through_atmosphere`) and polarised by air's
// matrix, plus the correction for the light of the higher orders (the model's radiance less
// single scattering's), partly polarised like single scattering and partly vertically.
//
// POLARISATION (a pipeline constant): off; the camera's polarising filter, whose transmission
// axis is globals.sunlight.y radians from up in the picture; or the view's Stokes vector, for
// the Polarisation display mode, in which the sky pass writes (I_Y, Q_Y, U_Y) to the radiance
// image, referred to up in the picture.

override POLARISATION: u32 = POLARISATION_OFF;

struct LaneStokes {
    q: vec4<f32>,
    u: vec4<f32>,
}

fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    return select(vec3<f32>(0.0), v / l, l > 1e-12);
}

// (cos 2χ, sin 2χ) of the unit vector e (perpendicular to dir) in the frame whose e₁ is e_up and
// e₂ = dir × e₁.
fn double_angle(e: vec3<f32>, e_up: vec3<f32>, dir: vec3<f32>) -> vec2<f32> {
    let c = dot(e, e_up);
    let s = dot(e, cross(dir, e_up));
    return vec2<f32>(c * c - s * s, 2.0 * c * s);
}

// Air's b₁ over its a₁ at scattering cosine nu (Hansen & Travis 1974, eq. 2.15); twin of
// model::polarisation::mueller::ReducedMatrix::rayleigh.
fn rayleigh_b1(nu: f32, rho: vec4<f32>) -> vec4<f32> {
    let delta = (1.0 - rho) / (1.0 + 0.5 * rho);
    let nu2 = min(nu * nu, 1.0);
    let a1 = 0.75 * delta * (1.0 + nu2) + 1.0 - delta;
    return -0.75 * delta * (1.0 - nu2) / a1;
}

// The middle and length (m) of sample s of a view ray t_max long from altitude h0: spaced as u²
// from a camera in the lower atmosphere, evenly from higher up; twin of
// model::methods::shared::polarisation::view_step.
fn view_step(s: u32, t_max: f32, h0: f32) -> vec2<f32> {
    let n = f32(POLARISATION_VIEW_STEPS);
    var a = f32(s) / n;
    var b = f32(s + 1u) / n;
    if h0 < POLARISATION_DENSE_BELOW_M {
        a *= a;
        b *= b;
    }
    return vec2<f32>(0.5 * (a + b) * t_max, (b - a) * t_max);
}

// The unit vector across `dir` nearest `v`, or zero.
fn across(v: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return normalize_or_zero(v - dir * dot(dir, v));
}

// Up in the picture at the view's point (x, y), perpendicular to the ray dir: the camera's up in
// a perspective view, else from the rays half a pixel above and below; where that fails, the
// meridian plane's up, or north, or east (twin of model::camera::Camera::image_up).
fn image_up(x: f32, y: f32, dir: vec3<f32>) -> vec3<f32> {
    var d = globals.view_up.xyz;
    if PROJECTION != PROJECTION_PERSPECTIVE {
        let above = camera_ray(x, y - 0.5);
        let below = camera_ray(x, y + 0.5);
        d = above.xyz - below.xyz;
        if above.w == 0.0 {
            d = dir - below.xyz;
        } else if below.w == 0.0 {
            d = above.xyz - dir;
        }
    }
    var up = across(d, dir);
    if length(up) == 0.0 {
        up = across(normalize(globals.camera_position.xyz), dir);
    }
    if length(up) == 0.0 {
        up = across(vec3<f32>(0.0, 1.0, 0.0), dir);
    }
    if length(up) == 0.0 {
        up = across(vec3<f32>(1.0, 0.0, 0.0), dir);
    }
    return up;
}

// Q and U per lane of batch `layer`'s light i_model (the model's radiance, the sun's disk
// apart) along dir, referred to the frame whose e₁ is e_up; twin of
// model::methods::shared::polarisation::sky_stokes.
fn sky_stokes(layer: u32, dir: vec3<f32>, e_up: vec3<f32>, i_model: vec4<f32>) -> LaneStokes {
    var out: LaneStokes;
    out.q = vec4<f32>(0.0);
    out.u = vec4<f32>(0.0);
    let cc = camera_coords(dir);
    if !cc.hit {
        return out;
    }
    let big_r = bottom_radius();
    let h0 = cc.c.h;
    let mu0 = cc.c.mu;
    let mu_s0 = cc.c.mu_s;
    let nu = cc.c.nu;
    let b = batches[layer];
    let phase_r = rayleigh_phase(nu, b.rayleigh_depolarisation);
    let phase_a = aerosol_phase(nu, layer);
    let b1 = rayleigh_b1(nu, b.rayleigh_depolarisation);
    let r0 = big_r + h0;
    var t_max = distance_to_top(h0, mu0);
    if cc.c.ground {
        t_max = distance_to_ground(h0, mu0);
    }
    var i1 = vec4<f32>(0.0);
    var q1 = vec4<f32>(0.0);
    var throughput = vec4<f32>(1.0);
    for (var s = 0u; s < POLARISATION_VIEW_STEPS; s++) {
        let step = view_step(s, t_max, h0);
        let t = step.x;
        let dt = step.y;
        let at = altitude_along(h0, mu0, t);
        let mu_s_t = clamp((r0 * mu_s0 + t * nu) / at.y, -1.0, 1.0);
        let m = medium(b, at.x);
        let w = throughput * segment_weight(m.extinction, dt)
            * sun_through_atmosphere(layer, at.x, mu_s_t);
        let air = m.rayleigh_scattering * phase_r;
        i1 += w * (air + m.aerosol_scattering * phase_a);
        q1 += w * air * b1;
        throughput *= exp(-m.extinction * dt);
    }
    i1 *= b.solar_irradiance;
    q1 *= b.solar_irradiance;
    let across = double_angle(normalize_or_zero(cross(dir, globals.sun.xyz)), e_up, dir);
    let zenith = normalize(globals.camera_position.xyz);
    let vertical = double_angle(normalize_or_zero(zenith - dir * dot(dir, zenith)), e_up, dir);
    let sin2_view = 1.0 - dot(dir, zenith) * dot(dir, zenith);
    var polarised = -q1;
    var vertical_part = vec4<f32>(0.0);
    if !cc.c.ground {
        let multiple = max(i_model - i1, vec4<f32>(0.0));
        let lit = i1 > vec4<f32>(0.0);
        polarised *= select(vec4<f32>(1.0), 1.0 + MS_LIKE_SINGLE * multiple / max(i1, vec4<f32>(1e-30)), lit);
        vertical_part = select(vec4<f32>(0.0), MS_VERTICAL * sin2_view * multiple, lit);
    }
    out.q = polarised * across.x + vertical_part * vertical.x;
    out.u = polarised * across.y + vertical_part * vertical.y;
    // No more polarised light than light.
    let length_qu = sqrt(out.q * out.q + out.u * out.u);
    let room = max(i_model, vec4<f32>(0.0));
    let scale = select(vec4<f32>(1.0), room / max(length_qu, vec4<f32>(1e-30)), length_qu > room);
    out.q *= scale;
    out.u *= scale;
    return out;
}

// What passes the camera's polarising filter of batch `layer`'s light l along dir, with e_up
// up in the picture there (the sun's disk, unpolarised, within l; sky its sky part alone).
fn through_polariser(layer: u32, dir: vec3<f32>, e_up: vec3<f32>, l: vec4<f32>, sky: vec4<f32>) -> vec4<f32> {
    let s = sky_stokes(layer, dir, e_up, sky);
    let angle = 2.0 * globals.sunlight.y;
    return 0.5 * (l + s.q * cos(angle) + s.u * sin(angle));
}
