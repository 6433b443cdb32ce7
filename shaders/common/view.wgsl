// What every sky pass shares: the camera's rays and the sun's disk. Twins of
// model::camera::Camera::ray and model::methods::shared::sun_disk.

// Pipeline constants: the engine compiles one variant per projection and per camera inside or
// above the atmosphere, so that no pixel pays for branches the frame cannot take (software
// drivers run both sides of a branch).
override PROJECTION: u32 = PROJECTION_PERSPECTIVE;
override ABOVE_ATMOSPHERE: bool = false;

// The ray through pixel (x, y) in world coordinates; w = 0 where the projection shows nothing.
// Twin of model::camera::Camera::ray.
fn camera_ray(x: f32, y: f32) -> vec4<f32> {
    let w = f32(globals.view.x);
    let h = f32(globals.view.y);
    let heading = globals.camera.x;
    let pitch = globals.camera.y;
    var local: vec3<f32>;
    switch PROJECTION {
        case PROJECTION_FISHEYE: {
            let size = min(w, h);
            let dx = (2.0 * x - w) / size;
            let dy = (h - 2.0 * y) / size;
            let rho = sqrt(dx * dx + dy * dy);
            if rho > 1.0 {
                return vec4<f32>(0.0);
            }
            local = direction_from_angles(0.5 * PI * (1.0 - rho), heading + atan2(dx, dy));
        }
        case PROJECTION_PANORAMA: {
            local = direction_from_angles(0.5 * PI - y / h * PI, heading + (x / w - 0.5) * 2.0 * PI);
        }
        default: {
            let tan_half = globals.camera.z;
            let sx = (2.0 * x / w - 1.0) * tan_half * w / h;
            let sy = (1.0 - 2.0 * y / h) * tan_half;
            let forward = direction_from_angles(pitch, heading);
            let right = direction_from_angles(0.0, heading + 0.5 * PI);
            let up = cross(right, forward);
            local = normalize(forward + right * sx + up * sy);
        }
    }
    let world = globals.camera_east.xyz * local.x + globals.camera_north.xyz * local.y
        + globals.camera_up.xyz * local.z;
    return vec4<f32>(world, 1.0);
}

// Limb-darkened sun disk per unit solar irradiance (sr⁻¹).
fn sun_disk(dir: vec3<f32>, sun: vec3<f32>) -> f32 {
    if dot(dir, sun) <= 0.0 {
        return 0.0;
    }
    let gamma = asin(min(length(cross(dir, sun)), 1.0));
    if gamma >= SUN_ANGULAR_RADIUS_RAD {
        return 0.0;
    }
    let x = gamma / SUN_ANGULAR_RADIUS_RAD;
    let mu_prime = sqrt(1.0 - x * x);
    let limb = (1.0 - SUN_LIMB_DARKENING_U * (1.0 - mu_prime)) / (1.0 - SUN_LIMB_DARKENING_U / 3.0);
    let half_angle = 0.5 * SUN_ANGULAR_RADIUS_RAD;
    return limb / (4.0 * PI * sin(half_angle) * sin(half_angle));
}


// (φ, θ): azimuth from the sun in [0, π] and zenith angle of `dir` at a point whose vertical is
// `up`; twin of model::methods::shared::sun_relative_angles.
fn sun_relative_angles(up: vec3<f32>, dir: vec3<f32>, sun: vec3<f32>) -> vec2<f32> {
    let mu = dot(dir, up);
    let dir_t = dir - up * mu;
    let sun_t = sun - up * dot(sun, up);
    let l = length(dir_t) * length(sun_t);
    var cos_phi = 1.0;
    if l > 1e-12 {
        cos_phi = dot(dir_t, sun_t) / l;
    }
    return vec2<f32>(acos(clamp(cos_phi, -1.0, 1.0)), acos(clamp(mu, -1.0, 1.0)));
}

// Where the ray (h, mu) from above the atmosphere enters it: (mu, mu_s) at the entry point and
// z = 1, or z = 0 when it misses; twin of model::methods::shared::entry_into_atmosphere.
fn entry_into_atmosphere(h: f32, mu: f32, mu_s: f32, nu: f32) -> vec3<f32> {
    let r = bottom_radius() + h;
    let top = top_radius();
    let rm = r * mu;
    let disc = rm * rm - (h - thickness()) * (r + top);
    if mu >= 0.0 || disc < 0.0 {
        return vec3<f32>(0.0);
    }
    let t_entry = -rm - sqrt(disc);
    return vec3<f32>(clamp((rm + t_entry) / top, -1.0, 1.0), clamp((r * mu_s + t_entry * nu) / top, -1.0, 1.0), 1.0);
}
