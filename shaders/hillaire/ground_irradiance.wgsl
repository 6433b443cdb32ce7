// Pass: sky irradiance on horizontal ground per unit solar irradiance, ∫ L·cos θ dΩ over the
// upper hemisphere on rings about the sun (GROUND_IRRADIANCE_DIRECTIONS: rings at γ = π·u²
// from the sun, dense near it, × azimuths about it; the half on one side of the sun's vertical
// plane, counted twice; directions below the horizon skipped). One workgroup per texel, its
// invocations sharing the directions; a workgroup of more invocations than directions (256 on
// a GPU, for 128) splits each direction's march into RUNS runs of steps, joined in order.
// Twin of model::methods::hillaire::ground_irradiance.

// The directions marched: one side of the sun's vertical plane.
const DIRECTIONS: u32 = GROUND_IRRADIANCE_DIRECTIONS.x * (GROUND_IRRADIANCE_DIRECTIONS.y / 2u);
const RUNS: u32 = select(1u, WIDE_GROUP_SIZE / DIRECTIONS, WIDE_GROUP_SIZE >= 2u * DIRECTIONS);

@compute @workgroup_size(WIDE_GROUP_SIZE, 1, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_texel(workgroup);
    let inside = id.x < GROUND_IRRADIANCE_SIZE && id.y < 1u && id.z < batch_count();
    let mu_s = ground_irradiance_mu_s_from_texel(f32(id.x));
    let sun = local_sun(mu_s);
    // A frame about the sun (local_sun lies in the x–z plane).
    let across = vec3<f32>(0.0, 1.0, 0.0);
    let up = cross(sun, across);
    let n_rings = GROUND_IRRADIANCE_DIRECTIONS.x;
    let n_azimuths = GROUND_IRRADIANCE_DIRECTIONS.y;
    let n = globals.steps_a.z;
    var sum = vec4<f32>(0.0);
    // The azimuths on one side of the sun's vertical plane, each standing for its mirror too.
    let half = n_azimuths / 2u;
    let part = index / DIRECTIONS;
    for (var k = index % DIRECTIONS; inside && part < RUNS && k < DIRECTIONS;
        k += WIDE_GROUP_SIZE) {
        let d = ground_irradiance_direction(k, sun, across, up);
        var l = nothing_marched();
        if d.x > 0.0 {
            let t_max = distance_to_top(0.0, d.x);
            let run = march_run(part, RUNS, n);
            l = integrate_inscattering_steps(id.z,
                vec4<f32>(0.0, d.x, mu_s, d.y), 0.0, t_max, run, n, SPACING_QUADRATIC);
        }
        if RUNS > 1u {
            // Each run's radiance from its start and its transmittance, joined below.
            group_a[index] = l.radiance;
            group_b[index] = l.transmittance;
        } else {
            sum += l.radiance * (d.x * d.z);
        }
    }
    if RUNS > 1u {
        workgroupBarrier();
        // The first run of each direction joins them all; the others add nothing.
        sum = vec4<f32>(0.0);
        if inside && part == 0u {
            var throughput = vec4<f32>(1.0);
            for (var j = 0u; j < RUNS; j++) {
                sum += throughput * group_a[index + j * DIRECTIONS];
                throughput *= group_b[index + j * DIRECTIONS];
            }
            let d = ground_irradiance_direction(index, sun, across, up);
            sum *= max(d.x, 0.0) * d.z;
        }
        // The sums below rewrite group_a and group_b.
        workgroupBarrier();
    }
    let sums = group_sums(WIDE_GROUP_SIZE, index, sum, vec4<f32>(0.0));
    if inside && index == 0u {
        ground_irradiance_lut[id.z * GROUND_IRRADIANCE_SIZE + id.x] = sums[0];
    }
}

// Direction k of the integral: its zenith cosine mu, its cosine nu to the sun, its solid-angle
// weight (mirror included).
fn ground_irradiance_direction(k: u32, sun: vec3<f32>, across: vec3<f32>, up: vec3<f32>) -> vec3<f32> {
    let n_rings = GROUND_IRRADIANCE_DIRECTIONS.x;
    let n_azimuths = GROUND_IRRADIANCE_DIRECTIONS.y;
    let half = n_azimuths / 2u;
    let i = k / half;
    let j = k % half;
    let u0 = f32(i) / f32(n_rings);
    let u1 = f32(i + 1u) / f32(n_rings);
    let um = 0.5 * (u0 + u1);
    let gamma = PI * um * um;
    let weight = 4.0 * PI * (cos(PI * u0 * u0) - cos(PI * u1 * u1)) / f32(n_azimuths);
    let a = 2.0 * PI * (f32(j) + 0.5) / f32(n_azimuths) - 0.5 * PI;
    let dir = sun * cos(gamma) + (across * cos(a) + up * sin(a)) * sin(gamma);
    return vec3<f32>(dir.z, cos(gamma), weight);
}
