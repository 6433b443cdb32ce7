// What every sky pass shares: the camera's rays and the sun's disk. Twins of
// model::camera::Camera::ray and model::methods::shared::sun::SunInView::pixel.

// Pipeline constants: the engine compiles one variant per projection and per camera inside or
// above the atmosphere, so that no pixel pays for branches the frame cannot take (software
// drivers run both sides of a branch).
override PROJECTION: u32 = PROJECTION_PERSPECTIVE;
override ABOVE_ATMOSPHERE: bool = false;
// A dispatch over rows that see only sky or only ground says so, and the other side's work
// is compiled away; over the pixels the sun's disk reaches the disk is drawn, elsewhere not.
override VIEW_REGION: u32 = REGION_BOTH;
override SUN_DISK: bool = true;

// Whether the camera's ray (h, mu) ends on the ground (hits_ground where the rows see both).
fn sees_ground(h: f32, mu: f32) -> bool {
    switch VIEW_REGION {
        case REGION_SKY: {
            return false;
        }
        case REGION_GROUND: {
            return true;
        }
        default: {
            return hits_ground(h, mu);
        }
    }
}

// The ray through pixel (x, y) in world coordinates; w = 0 where the projection shows nothing.
// Twin of model::camera::Camera::ray.
fn camera_ray(x: f32, y: f32) -> vec4<f32> {
    let w = f32(globals.view.x);
    let h = f32(globals.view.y);
    let heading = globals.camera.x;
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
            let dir = globals.view_forward.xyz + globals.view_right.xyz * sx + globals.view_up.xyz * sy;
            return vec4<f32>(normalize(dir), 1.0);
        }
    }
    let world = globals.camera_east.xyz * local.x + globals.camera_north.xyz * local.y
        + globals.camera_up.xyz * local.z;
    return vec4<f32>(world, 1.0);
}

// Exponent α of the limb darkening μ′^α at each wavelength (nm); twin of
// model::methods::shared::sun::limb_exponent.
fn limb_exponent(wavelengths_nm: vec4<f32>) -> vec4<f32> {
    let per_um = 1000.0 / wavelengths_nm;
    let long = SUN_LIMB_ALPHA_LONG_A + SUN_LIMB_ALPHA_LONG_B * per_um;
    let short = SUN_LIMB_ALPHA_SHORT_A + SUN_LIMB_ALPHA_SHORT_B * per_um;
    return select(short, long, per_um < vec4<f32>(SUN_LIMB_ALPHA_BREAK_PER_UM));
}

// Limb darkening with exponents alpha at the fraction x of the disk's radius, normalised to the
// disk's mean; twin of model::methods::shared::sun::limb.
fn limb(x: f32, alpha: vec4<f32>) -> vec4<f32> {
    return pow(vec4<f32>(sqrt(max(1.0 - x * x, 0.0))), alpha) * (alpha + 2.0) * 0.5;
}

// Area shared by two disks of radii a and b whose centres are d apart; twin of
// model::methods::shared::sun::disk_overlap.
fn disk_overlap(a: f32, b: f32, d: f32) -> f32 {
    if d >= a + b {
        return 0.0;
    }
    if d <= abs(a - b) {
        let m = min(a, b);
        return PI * m * m;
    }
    let ca = clamp((d * d + a * a - b * b) / (2.0 * d * a), -1.0, 1.0);
    let cb = clamp((d * d + b * b - a * a) / (2.0 * d * b), -1.0, 1.0);
    let k = max((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b), 0.0);
    return a * a * acos(ca) + b * b * acos(cb) - 0.5 * sqrt(k);
}

// Share of the sun's disk whose offset from its centre along an axis is below s (rad).
fn chord_share(s: f32) -> f32 {
    let t = clamp(s / SUN_ANGULAR_RADIUS_RAD, -1.0, 1.0);
    return 1.0 - (acos(t) - t * sqrt(1.0 - t * t)) / PI;
}

// The sun's disk over one pixel apart from wavelength; twin of
// model::methods::shared::sun::DiskInPixel (reaches: whether the disk touches the pixel).
struct DiskInPixel {
    reaches: bool,
    overlap: f32,
    unresolved: f32,
    blend: f32,
    ring_x: array<f32, LIMB_RINGS>,
    ring_weight: array<f32, LIMB_RINGS>,
}

fn no_disk() -> DiskInPixel {
    var d: DiskInPixel;
    d.reaches = false;
    return d;
}

// How the sun's disk covers the pixel centred at (x, y), from where the sun falls in the view
// (globals.sun_view); twin of model::methods::shared::sun::SunInView::pixel.
fn sun_pixel(x: f32, y: f32) -> DiskInPixel {
    var d = no_disk();
    let a = SUN_ANGULAR_RADIUS_RAD;
    let wx = globals.sun_view.z;
    let wy = globals.sun_view.w;
    if wx <= 0.0 {
        return d;
    }
    var dx = x - globals.sun_view.x;
    if PROJECTION == PROJECTION_PANORAMA {
        let w = f32(globals.view.x);
        dx -= w * round(dx / w);
    }
    let ox = dx * wx;
    let oy = (y - globals.sun_view.y) * wy;
    let gamma = length(vec2<f32>(ox, oy));
    if gamma >= a + wx + wy {
        return d;
    }
    let sr = wx * wy;
    let p = sqrt(sr / PI);
    d.reaches = true;
    d.blend = smoothstep(1.0, 2.0, sqrt(sr) / a);
    if d.blend < 1.0 {
        d.overlap = disk_overlap(a, p, gamma) / (PI * a * a) / sr;
        // Twin of model::methods::shared::sun::limb_rings.
        let r0 = max(gamma - p, 0.0);
        let r1 = min(gamma + p, a);
        if r1 > r0 {
            var total = 0.0;
            for (var k = 0u; k < LIMB_RINGS; k++) {
                let rho = r0 + (f32(k) + 0.5) / f32(LIMB_RINGS) * (r1 - r0);
                var arc = PI;
                if rho > p - gamma {
                    arc = acos(clamp((rho * rho + gamma * gamma - p * p) / (2.0 * rho * gamma),
                        -1.0, 1.0));
                }
                d.ring_x[k] = rho / a;
                d.ring_weight[k] = arc * rho;
                total += arc * rho;
            }
            for (var k = 0u; k < LIMB_RINGS; k++) {
                d.ring_weight[k] /= max(total, 1e-30);
            }
        }
    }
    if d.blend > 0.0 {
        let share_x = chord_share(0.5 * wx + ox) - chord_share(-0.5 * wx + ox);
        let share_y = chord_share(0.5 * wy + oy) - chord_share(-0.5 * wy + oy);
        d.unresolved = share_x * share_y / sr;
    }
    return d;
}

// Radiance of the disk over its pixel at each of `wavelengths_nm`, per unit solar irradiance
// (sr⁻¹); twin of model::methods::shared::sun::DiskInPixel::radiance.
fn disk_radiance(d: DiskInPixel, wavelengths_nm: vec4<f32>) -> vec4<f32> {
    let alpha = limb_exponent(wavelengths_nm);
    var l = vec4<f32>(0.0);
    for (var k = 0u; k < LIMB_RINGS; k++) {
        l += d.ring_weight[k] * limb(d.ring_x[k], alpha);
    }
    return mix(l * d.overlap, vec4<f32>(d.unresolved), d.blend);
}

// (φ, θ): azimuth from the sun in [0, π] and zenith angle of `dir` at a point whose vertical is
// `up`; twin of model::methods::shared::sun_relative_angles.
fn sun_relative_angles(up: vec3<f32>, dir: vec3<f32>, sun: vec3<f32>) -> vec2<f32> {
    let mu = dot(dir, up);
    let dir_t = dir - up * mu;
    let sun_t = sun - up * dot(sun, up);
    let a = length(dir_t);
    let b = length(sun_t);
    var cos_phi = 1.0;
    if a > VERTICAL_RAD && b > VERTICAL_RAD {
        cos_phi = dot(dir_t, sun_t) / (a * b);
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
