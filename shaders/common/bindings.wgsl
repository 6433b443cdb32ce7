// Group 0, read by every pass. The layouts mirror `render/src/uniforms.rs`; a test checks
// the sizes with naga. Physical numbers arrive here as data, never as literals.

struct Globals {
    // bottom radius (m), top radius (m), thickness (m), 0
    planet: vec4<f32>,
    // camera position from the planet's centre (m); w: camera altitude h (m)
    camera_position: vec4<f32>,
    // camera local frame (east, north, up) in world coordinates
    camera_east: vec4<f32>,
    camera_north: vec4<f32>,
    camera_up: vec4<f32>,
    // heading (rad), pitch (rad), tan(fov / 2), horizon angle β from the nadir at the camera (rad)
    camera: vec4<f32>,
    // the perspective view's forward, right and up directions in world coordinates
    view_forward: vec4<f32>,
    view_right: vec4<f32>,
    view_up: vec4<f32>,
    // world direction to the sun; w: mu_s at the camera (the viewpoint of the view tables)
    sun: vec4<f32>,
    // where the sun's centre falls in the view (pixels: x, y) and a pixel's angular width and
    // height there (rad); z = 0 when the view cannot show the sun
    sun_view: vec4<f32>,
    // width, height (pixels), 0, 0 (projection, display mode and tone map are pipeline constants)
    view: vec4<u32>,
    // aerosol phase function, batch count, 1 with aerosol in the atmosphere (else 0), 0
    options: vec4<u32>,
    // steps: transmittance, multiple scattering, ground irradiance, sky view
    steps_a: vec4<u32>,
    // steps: aerial perspective per slice, ray march from space, trapezoid intervals along a
    // texel's ray (Bruneton, Elek), sphere zenith samples (Bruneton, Elek)
    steps_b: vec4<u32>,
    // exposure scale, log10 luminance min and max (cd/m²), 1 to dither the 8-bit image (else 0)
    display: vec4<f32>,
    // the sun's irradiance at the camera (linear sRGB, W/m²) where the display adds its veiling
    // glare (the GLARE pipeline constant; model::display::glare), else 0; w unused
    glare: vec4<f32>,
    // x: the sunlight at the scene's Earth–Sun distance over that at 1 AU (1/d², d in AU), by
    // which the sky pass scales every radiance it writes (the tables hold sunlight at 1 AU);
    // yzw unused
    // y: the camera's polarising filter's transmission axis from up in the picture, rad
    // (views/polarisation.wgsl)
    sunlight: vec4<f32>,
    // white balance matrix rows on linear sRGB (model::white_balance), w unused
    white_balance: array<vec4<f32>, 3>,
    // constants of the model on screen, three rows (render::methods::GpuMethod::constants)
    model: array<vec4<f32>, 3>,
}

// The optics of one batch of four wavelengths (per unit of the density profile).
struct Batch {
    rayleigh_scattering: vec4<f32>,
    rayleigh_depolarisation: vec4<f32>,
    ozone_absorption: vec4<f32>,
    aerosol_scattering: vec4<f32>,
    aerosol_absorption: vec4<f32>,
    aerosol_g: vec4<f32>,
    solar_irradiance: vec4<f32>,
    ground_albedo: vec4<f32>,
    to_srgb_r: vec4<f32>,
    to_srgb_g: vec4<f32>,
    to_srgb_b: vec4<f32>,
    // the batch's four wavelengths, nm
    wavelengths_nm: vec4<f32>,
    // each lane's fractional row of the tabulated Mie phase function (model::aerosol::MiePhase)
    aerosol_phase_node: vec4<f32>,
    // rows a model computes for the batch on the CPU (render::methods::GpuMethod::batch_rows)
    model: array<vec4<f32>, BATCH_MODEL_ROWS>,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var<storage, read> batches: array<Batch>;
// relative air, relative ozone, aerosol (1/m) at h = H·(i/(n−1))², and 0
@group(0) @binding(2) var<storage, read> profile: array<vec4<f32>>;

// Where this dispatch starts in its pass's grid (x, y, z; w unused): a pass run in slices across
// frames is several dispatches, each over part of its rows or layers (render::engine).
@group(0) @binding(3) var<uniform> origin: vec4<u32>;

// The tabulated Mie phase function: ln p (sr⁻¹) at θ_i = π·(i/(MIE_PHASE_ANGLES − 1))², one row
// per wavelength of model::aerosol::MIE_PHASE_WAVELENGTHS_NM (zeros unless the scene asks for it),
// packed four to a vec4 as a uniform array must be.
@group(0) @binding(4) var<uniform> mie_phase_rows: array<vec4<f32>, MIE_PHASE_VEC4S>;

fn mie_phase_ln(k: u32) -> f32 { return mie_phase_rows[k / 4u][k % 4u]; }

// The invocation's place in the pass's whole grid.
fn dispatched(invocation: vec3<u32>) -> vec3<u32> { return invocation + origin.xyz; }

// The texel of a workgroup of a pass run one workgroup per texel (Dispatch::TexelGroups): a
// slice's origin counts WORKGROUP_SIZE invocations per row of workgroups, as for any pass.
fn dispatched_texel(workgroup: vec3<u32>) -> vec3<u32> {
    return vec3<u32>(workgroup.xy + origin.xy / WORKGROUP_SIZE, workgroup.z + origin.z);
}

fn bottom_radius() -> f32 { return globals.planet.x; }
fn top_radius() -> f32 { return globals.planet.y; }
fn thickness() -> f32 { return globals.planet.z; }
fn batch_count() -> u32 { return globals.options.y; }
// Whether the atmosphere holds aerosol: without, no pass spends work on its terms (the branch
// is uniform, so no invocation takes it).
fn has_aerosol() -> bool { return globals.options.z != 0u; }

// Group 1 (the tables and the view's images) is generated from the registry for each pass
// (render::spec::bindings); the exact-tile list it binds has this layout.
// The tiles of a moving frame's sky that their corners could not interpolate (views/sky.wgsl):
// the workgroups of the indirect dispatch that computes them pixel by pixel (x, y, z), their
// number, then each tile as x | y << 16.
struct ExactTiles {
    groups_x: atomic<u32>,
    groups_y: atomic<u32>,
    groups_z: atomic<u32>,
    count: atomic<u32>,
    tiles: array<u32>,
}
