//! Passes and WGSL files more than one model uses: the views' passes after every sky, the
//! transmittance, the moving sky of the marches per pixel, the table-free single-scattering
//! skies with and without Hillaire's higher orders, and Leenman's segment sky.

use super::{
    DISPLAY, Dispatch, GpuMethod, HISTOGRAM, ModelConstants, PassSpec, RADIANCE, Read, Repeat,
    Resource, Shader, Table, read, read_table, shader,
};
use atmoscope_model::methods::Inputs;
use atmoscope_model::methods::hillaire::multiple_scattering as hillaire_ms;
use atmoscope_model::methods::shared::Params;
use atmoscope_model::methods::shared::{moving_sky, single_scattering_sky, transmittance};
use atmoscope_model::scene::Method;

/// The WGSL files every pass includes, after the generated prelude; `bindings.wgsl` holds group
/// 0, whose layout mirrors `crate::uniforms`; group 1 is generated ([`super::bindings`]).
pub const COMMON: [Shader; 10] = [
    shader!("common/bindings.wgsl"),
    shader!("common/geometry.wgsl"),
    shader!("common/lut.wgsl"),
    shader!("common/sky_view.wgsl"),
    shader!("common/phase.wgsl"),
    shader!("common/medium.wgsl"),
    shader!("common/transmittance.wgsl"),
    shader!("common/ray.wgsl"),
    shader!("common/view.wgsl"),
    shader!("common/group.wgsl"),
];

/// What the display shows of a pixel's radiance, in every pass that writes [`DISPLAY`] (the
/// sky pass and the display pass) before the pass's own file.
pub const TONE: Shader = shader!("views/tone.wgsl");

/// The entry point every sky pass ends with; the pass's own file defines `radiance(layer, dir)`.
pub const SKY_ENTRY_POINT: Shader = shader!("views/sky.wgsl");

/// The polarisation of the real-time sky, which every sky pass's entry point draws on
/// (`GpuMethod::files` puts it before [`SKY_ENTRY_POINT`]).
pub const SKY_POLARISATION: Shader = shader!("views/polarisation.wgsl");

/// What the entry point draws along a direction (`view_radiance`): the model's `radiance`, or
/// for a sky pass that reads the moving sky in frames drawn in tiles that table.
pub const VIEW_RADIANCE: Shader = shader!("views/radiance.wgsl");
pub const MOVING_SKY_RADIANCE: Shader = shader!("views/moving_sky_radiance.wgsl");

/// What every sky pass reads besides its tables.
pub const SKY_INPUTS: Inputs = Inputs::VIEWPOINT
    .union(Inputs::SUN)
    .union(Inputs::CAMERA)
    .union(Inputs::VIEW_SIZE);

/// The display pass every model ends with: radiance → exposure, tone map, sRGB or false colour
/// (`shaders/views/tone.wgsl`, which the sky pass applies too). It runs in frames that change
/// the display but not the sky: a frame whose sky pass ran has its display image already.
pub const DISPLAY_PASS: PassSpec = PassSpec {
    name: "display",
    files: &[TONE, shader!("views/display.wgsl")],
    reads: &[read(RADIANCE)],
    writes: &[DISPLAY],
    inputs: Inputs::DISPLAY.union(Inputs::VIEW_SIZE),
    dispatch: Dispatch::View,
    // The projection places each pixel's direction for the glare around the sun.
    constants: &[
        super::Constant::DisplayMode,
        super::Constant::ToneMap,
        super::Constant::Glare,
        super::Constant::Projection,
    ],
    repeat: Repeat::Once,
};

/// The pass that counts the view's pixels per luminance bin, after every model's view; it
/// runs only while the engine meters (`Engine::set_metering`).
pub const METER_PASS: PassSpec = PassSpec {
    name: "meter",
    files: &[shader!("views/meter.wgsl")],
    reads: &[read(RADIANCE)],
    writes: &[HISTOGRAM],
    inputs: Inputs::VIEW_SIZE,
    dispatch: Dispatch::View,
    constants: &[],
    repeat: Repeat::Once,
};

/// The passes after every model's sky pass: they read the view, not the tables.
pub const VIEW_PASSES: [PassSpec; 2] = [DISPLAY_PASS, METER_PASS];

/// The transmittance table, which the table-based models share.
pub const TRANSMITTANCE: Resource = Resource::table(&transmittance::TABLE);

/// The transmittance pass the table-based models share.
pub const TRANSMITTANCE_PASS: PassSpec = PassSpec::table(
    "transmittance",
    &[shader!("shared/transmittance.wgsl")],
    &[],
    &[TRANSMITTANCE],
    Dispatch::Table(Table(&transmittance::TABLE)),
    Repeat::Once,
);

/// The sun's disk through the transmittance table, for the models that have one: the
/// `sun_through_atmosphere` every sky pass's entry point calls (a model without the table
/// defines its own).
pub const SUN_DISK_FROM_TABLE: Shader = shader!("shared/sun_disk.wgsl");

/// The table of the moving sky (`atmoscope_model::methods::shared::moving_sky`).
pub const MOVING_SKY: Resource = Resource::table(&moving_sky::TABLE);

/// The name of the moving sky's pass.
pub const MOVING_SKY_PASS: &str = "moving-sky";

/// The entry point of the moving sky's pass, after the model's sky file.
pub const MOVING_SKY_ENTRY_POINT: Shader = shader!("shared/moving_sky.wgsl");

/// The moving sky of a march per pixel, made of `files` (the model's sky file, whose
/// `radiance(layer, dir)` [`MOVING_SKY_ENTRY_POINT`] evaluates at the directions of the
/// sky-view grid, last) and reading what the sky pass reads. On a software GPU a march costs
/// 10–300 table look-ups a pixel; a view in motion is drawn from this table of 192 × 108
/// marches (the sky pass's [`Read::in_motion`] of [`MOVING_SKY`]), rebuilt only when the
/// viewpoint moves, and the still frame after it marches every pixel.
pub const fn moving_sky_pass(files: &'static [Shader], reads: &'static [Read]) -> PassSpec {
    PassSpec::table(
        MOVING_SKY_PASS,
        files,
        reads,
        &[MOVING_SKY],
        Dispatch::Table(Table(&moving_sky::TABLE)),
        Repeat::Once,
    )
}

/// The sky file of the table-free single-scattering models: the view march lit through the
/// optical depth towards the sun by the model's rule (its constants say which).
pub const SINGLE_SCATTERING_SKY: Shader = shader!("shared/single_scattering_sky.wgsl");

/// The table-free models' way to the sun and the sun's disk through it, with
/// `sun_transmittance_by_way` marched at every sample or, in the nested marches' moving sky,
/// looked up in [`SUN_ROUTE_TABLE`].
pub const SUN_ROUTE: Shader = shader!("shared/sun_route.wgsl");
pub const SUN_ROUTE_MARCHED: Shader = shader!("shared/sun_route_marched.wgsl");
pub const SUN_ROUTE_FROM_TABLE: Shader = shader!("shared/sun_route_from_table.wgsl");

/// The nested marches' way to the sun tabulated for their moving sky.
pub const SUN_ROUTE_TABLE: Resource = Resource::table(&single_scattering_sky::SUN_ROUTE_TABLE);

/// The name of [`sun_route_pass`]; only the moving sky reads its table, so a still frame
/// never runs it.
pub const SUN_ROUTE_PASS: &str = "sun-route";

/// The pass that tabulates a nested march's way to the sun, reading what the way reads
/// (Gałaj's spline its mesh); it depends on the atmosphere alone.
pub const fn sun_route_pass(reads: &'static [Read]) -> PassSpec {
    PassSpec::table(
        SUN_ROUTE_PASS,
        &[
            SUN_ROUTE,
            SUN_ROUTE_MARCHED,
            shader!("shared/sun_route_table.wgsl"),
        ],
        reads,
        &[SUN_ROUTE_TABLE],
        Dispatch::Table(Table(&single_scattering_sky::SUN_ROUTE_TABLE)),
        Repeat::Once,
    )
}

/// The files of a table-free single-scattering sky pass.
pub const SINGLE_SCATTERING_SKY_FILES: [Shader; 6] = [
    SUN_ROUTE,
    SUN_ROUTE_MARCHED,
    TONE,
    SINGLE_SCATTERING_SKY,
    MOVING_SKY_RADIANCE,
    SKY_ENTRY_POINT,
];

/// The files of its moving sky, the way to the sun marched or (a nested march) tabulated.
pub const SINGLE_SCATTERING_MOVING_SKY_FILES: [Shader; 4] = [
    SUN_ROUTE,
    SUN_ROUTE_MARCHED,
    SINGLE_SCATTERING_SKY,
    MOVING_SKY_ENTRY_POINT,
];
pub const NESTED_MARCH_MOVING_SKY_FILES: [Shader; 4] = [
    SUN_ROUTE,
    SUN_ROUTE_FROM_TABLE,
    SINGLE_SCATTERING_SKY,
    MOVING_SKY_ENTRY_POINT,
];

/// Hillaire's Ψ_ms table, the higher orders of the `-ms` rows.
pub const HILLAIRE_MS: Resource = Resource::table(&hillaire_ms::TABLE);

/// The passes of a table-free single-scattering model: its moving sky and its sky pass.
pub const SINGLE_SCATTERING_PASSES: [PassSpec; 2] = [
    moving_sky_pass(&SINGLE_SCATTERING_MOVING_SKY_FILES, &[]),
    PassSpec::sky(
        &SINGLE_SCATTERING_SKY_FILES,
        &[read(MOVING_SKY).in_motion()],
    ),
];

/// The passes of a nested march (the midpoint or the trapezoid rule towards the sun): its way
/// to the sun tabulated, the moving sky built from that table, and the sky pass marching every
/// sample's way to the sun.
pub const NESTED_MARCH_PASSES: [PassSpec; 3] = [
    sun_route_pass(&[]),
    moving_sky_pass(&NESTED_MARCH_MOVING_SKY_FILES, &[read(SUN_ROUTE_TABLE)]),
    PassSpec::sky(
        &SINGLE_SCATTERING_SKY_FILES,
        &[read(MOVING_SKY).in_motion()],
    ),
];

/// Single scattering alone: the table-free sky pass's `higher_orders` and `ground_skylight`
/// are zero.
pub const NO_HIGHER_ORDERS: Shader = shader!("shared/no_higher_orders.wgsl");

/// Hillaire's Ψ_ms table as a single-scattering model's higher orders (the `-ms` rows): the
/// table's look-up, and the sky pass's higher orders from it.
pub const HILLAIRE_HIGHER_ORDERS: [Shader; 3] = [
    MU_S_AXIS,
    shader!("hillaire/common.wgsl"),
    shader!("shared/isotropic_higher_orders.wgsl"),
];

/// The sun-zenith axis dense in twilight (Hillaire's tables, the intensity volumes).
pub const MU_S_AXIS: Shader = shader!("shared/mu_s_axis.wgsl");

/// The exponential medium and its closed forms of the optical depth along a ray (the analytic
/// ways to the sun, and Leenman's depths along the view too).
pub const EXPONENTIAL: Shader = shader!("shared/exponential.wgsl");

/// The closed forms' columns along a ray for the way to the sun (`galaj_spline` defines its
/// own from its mesh).
pub const CLOSED_FORM_COLUMNS: Shader = shader!("shared/closed_form_columns.wgsl");

/// What every pass of a table-free single-scattering model includes: no higher orders, or
/// Hillaire's Ψ_ms (the `-ms` rows); the exponential medium and its columns either way.
pub const SINGLE_SCATTERING_COMMON: [Shader; 3] =
    [NO_HIGHER_ORDERS, EXPONENTIAL, CLOSED_FORM_COLUMNS];
pub const SINGLE_SCATTERING_MS_COMMON: [Shader; 5] = [
    HILLAIRE_HIGHER_ORDERS[0],
    HILLAIRE_HIGHER_ORDERS[1],
    HILLAIRE_HIGHER_ORDERS[2],
    EXPONENTIAL,
    CLOSED_FORM_COLUMNS,
];

/// The Ψ_ms table's pass (Hillaire's), which the single-scattering `-ms` rows share.
pub const MULTIPLE_SCATTERING_PASS: PassSpec = PassSpec::table(
    "multiple-scattering",
    &[shader!("hillaire/multiple_scattering.wgsl")],
    &[read_table(&transmittance::TABLE)],
    &[HILLAIRE_MS],
    Dispatch::TexelRuns(Table(&hillaire_ms::TABLE)),
    Repeat::Once,
);

/// The passes of a table-free single-scattering model with Hillaire's higher orders: the
/// transmittance and Ψ_ms tables, then the moving sky and the sky pass reading Ψ_ms.
pub const SINGLE_SCATTERING_MS_PASSES: [PassSpec; 4] = [
    TRANSMITTANCE_PASS,
    MULTIPLE_SCATTERING_PASS,
    moving_sky_pass(&SINGLE_SCATTERING_MOVING_SKY_FILES, &[read(HILLAIRE_MS)]),
    PassSpec::sky(
        &SINGLE_SCATTERING_SKY_FILES,
        &[read(HILLAIRE_MS), read(MOVING_SKY).in_motion()],
    ),
];

/// [`SINGLE_SCATTERING_MS_PASSES`] of a nested march, its way to the sun tabulated for the
/// moving sky as in [`NESTED_MARCH_PASSES`].
pub const NESTED_MARCH_MS_PASSES: [PassSpec; 5] = [
    TRANSMITTANCE_PASS,
    MULTIPLE_SCATTERING_PASS,
    sun_route_pass(&[]),
    moving_sky_pass(
        &NESTED_MARCH_MOVING_SKY_FILES,
        &[read(HILLAIRE_MS), read(SUN_ROUTE_TABLE)],
    ),
    PassSpec::sky(
        &SINGLE_SCATTERING_SKY_FILES,
        &[read(HILLAIRE_MS), read(MOVING_SKY).in_motion()],
    ),
];

/// Leenman's segment-integral sky (`flat`, `raymarched`): what every pass includes, and its
/// one pass.
pub const SEGMENTS_COMMON: [Shader; 2] = [EXPONENTIAL, CLOSED_FORM_COLUMNS];
pub const SEGMENTS_SKY_PASS: PassSpec = PassSpec::sky(
    &[
        SUN_ROUTE,
        SUN_ROUTE_MARCHED,
        TONE,
        shader!("shared/segments_sky.wgsl"),
        VIEW_RADIANCE,
        SKY_ENTRY_POINT,
    ],
    &[],
);

/// A table-free single-scattering model's two rows: the model alone and with Hillaire's Ψ_ms
/// table as its higher orders (its `-ms` row), its way to the sun tabulated for the moving sky
/// where it is a nested march (`nested`), the model's constants the same in both.
pub const fn single_scattering_rows(
    method: Method,
    with_higher_orders: Method,
    nested: bool,
    constants: fn(&Params) -> ModelConstants,
) -> [GpuMethod; 2] {
    let (passes, ms_passes): (&'static [PassSpec], &'static [PassSpec]) = if nested {
        (&NESTED_MARCH_PASSES, &NESTED_MARCH_MS_PASSES)
    } else {
        (&SINGLE_SCATTERING_PASSES, &SINGLE_SCATTERING_MS_PASSES)
    };
    [
        GpuMethod {
            method,
            lowest_table_mu_s: None,
            common: &SINGLE_SCATTERING_COMMON,
            constants,
            batch_rows: None,
            passes,
        },
        GpuMethod {
            method: with_higher_orders,
            lowest_table_mu_s: None,
            common: &SINGLE_SCATTERING_MS_COMMON,
            constants,
            batch_rows: None,
            passes: ms_passes,
        },
    ]
}
