// A ray of a table texel through the atmosphere, as the models that tabulate in-scattering per
// (h, mu, mu_s, nu) integrate it: its length, its samples, the local angles at a sample and
// single scattering along it without phase functions. Twin of model::methods::shared::ray.

struct Coords {
    h: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    ground: bool,
}

fn ray_length(c: Coords) -> f32 {
    if c.ground {
        return distance_to_ground(c.h, c.mu);
    }
    return distance_to_top(c.h, c.mu);
}

// Sample k of the 2(n + 1) along the ray of c: (distance, weight), crowding towards the ray's
// lowest point.
fn ray_sample(c: Coords, k: u32, n: u32) -> vec2<f32> {
    let length = ray_length(c);
    var lowest = min(-(bottom_radius() + c.h) * c.mu, length);
    if c.ground {
        lowest = length;
    } else if c.mu >= 0.0 {
        lowest = 0.0;
    }
    let i = k % (n + 1u);
    let s = f32(i) / f32(n);
    let trapezoid = select(1.0, 0.5, i == 0u || i == n) / f32(n);
    if k <= n {
        return vec2<f32>(lowest * (1.0 - (1.0 - s) * (1.0 - s)), trapezoid * 2.0 * lowest * (1.0 - s));
    }
    let b = length - lowest;
    return vec2<f32>(lowest + b * s * s, trapezoid * 2.0 * b * s);
}

// (altitude, view zenith cosine, sun zenith cosine) at distance d along the ray of c.
fn along(c: Coords, d: f32) -> vec3<f32> {
    let r = bottom_radius() + c.h;
    let at = altitude_along(c.h, c.mu, d);
    return vec3<f32>(max(at.x, 0.0), clamp((r * c.mu + d) / at.y, -1.0, 1.0),
        clamp((r * c.mu_s + d * c.nu) / at.y, -1.0, 1.0));
}

struct RayleighMie {
    rayleigh: vec4<f32>,
    mie: vec4<f32>,
}

// Rayleigh and Mie single scattering along the ray of c without phase functions.
fn single_scattering(layer: u32, c: Coords) -> RayleighMie {
    let b = batches[layer];
    let n = globals.steps_b.z;
    var s: RayleighMie;
    s.rayleigh = vec4<f32>(0.0);
    s.mie = vec4<f32>(0.0);
    for (var k = 0u; k < 2u * (n + 1u); k++) {
        let sample = ray_sample(c, k, n);
        let d = sample.x;
        let at = along(c, d);
        let tr = sample.y * transmittance_between(layer, c.h, c.mu, d)
            * sun_transmittance(layer, at.x, at.z);
        let m = medium(b, at.x);
        s.rayleigh += tr * m.rayleigh_scattering;
        s.mie += tr * m.aerosol_scattering;
    }
    s.rayleigh *= b.solar_irradiance;
    s.mie *= b.solar_irradiance;
    return s;
}

// The camera's ray along `dir` as the models that look a whole ray up in their tables see it:
// at the camera, or where the ray enters the atmosphere when the camera is above it; `hit` is
// false when it misses. Twin of model::methods::shared::ray::camera_coords.
// Where a looked-up ray `c` that ends on the ground meets it: the transmittance to it and the
// sun's zenith cosine there; twin of shared::ray::behind, which the caller finishes with its
// ground's radiance.
struct GroundHit {
    transmittance: vec4<f32>,
    mu_s: f32,
}

fn ground_hit(layer: u32, c: Coords) -> GroundHit {
    let d = distance_to_ground(c.h, c.mu);
    var g: GroundHit;
    g.mu_s = clamp(((bottom_radius() + c.h) * c.mu_s + d * c.nu) / bottom_radius(), -1.0, 1.0);
    g.transmittance = transmittance_between(layer, c.h, c.mu, d);
    return g;
}

struct CameraCoords {
    c: Coords,
    hit: bool,
}

fn camera_coords(dir: vec3<f32>) -> CameraCoords {
    let up = normalize(globals.camera_position.xyz);
    let sun = globals.sun.xyz;
    var r: CameraCoords;
    r.c.h = globals.camera_position.w;
    r.c.mu = dot(dir, up);
    r.c.mu_s = dot(sun, up);
    r.c.nu = clamp(dot(dir, sun), -1.0, 1.0);
    r.hit = true;
    if ABOVE_ATMOSPHERE {
        let entry = entry_into_atmosphere(r.c.h, r.c.mu, r.c.mu_s, r.c.nu);
        r.hit = entry.z != 0.0;
        r.c.h = thickness();
        r.c.mu = entry.x;
        r.c.mu_s = entry.y;
    }
    r.c.ground = sees_ground(r.c.h, r.c.mu);
    return r;
}
