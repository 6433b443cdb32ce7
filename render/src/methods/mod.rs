//! Each model's GPU passes as data: which shader, which tables it reads and writes, which scene
//! inputs it reads directly, how it is dispatched and which pipeline constants it takes. The
//! engine runs any model from this description alone (`crate::engine`): a pass reruns when a
//! scene input it reads changed or a table it reads was rewritten this frame.
//!
//! One module per model, named as in `model::methods`; the tables are declared once in the
//! model's registry row (`model::methods::MODELS`) and their bindings once in
//! `shaders/common/bindings.wgsl`.

pub mod bruneton;
pub mod elek;
pub mod empty;
pub mod flat;
pub mod galaj_spline;
pub mod galaj_taylor;
pub mod garcia_linan;
pub mod hillaire;
pub mod nishita;
pub mod preetham;
pub mod raymarched;
pub mod schuler;
pub mod trapezoid;

use atmoscope_model::methods::shared::moving_sky;
use atmoscope_model::methods::{self, Inputs, ModelInfo};
use atmoscope_model::scene::Method;

/// A WGSL file: its path under `shaders/` and its text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shader {
    pub path: &'static str,
    pub source: &'static str,
}

/// Includes `shaders/<path>` as a [`Shader`].
macro_rules! shader {
    ($path:literal) => {
        $crate::methods::Shader {
            path: $path,
            source: include_str!(concat!("../../../shaders/", $path)),
        }
    };
}
pub(crate) use shader;

/// A pipeline-overridable constant a pass is compiled with; the engine picks its value per
/// frame, compiling one variant per value so no pixel pays for a branch the frame cannot take.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Constant {
    /// The view's projection (`PROJECTION_*` codes of the prelude).
    Projection,
    /// Whether the camera is above the top of the atmosphere.
    AboveAtmosphere,
    /// Colour or luminance map (`DISPLAY_*`).
    DisplayMode,
    /// The tone map (`TONE_MAP_*`).
    ToneMap,
    /// Whether the dispatch draws the sun's disk (only the pixels it reaches do).
    SunDisk,
    /// What the dispatch's rows see (`REGION_*`): sky or ground alone, decided per row on
    /// the CPU, or both, decided per pixel.
    ViewRegion,
    /// Pixels on a side of the tiles interpolated from their corners (1: every pixel computed;
    /// `Engine::set_sky_tile`).
    SkyTile,
    /// Whether the dispatch computes, pixel by pixel, the tiles listed in [`EXACT_TILES`].
    SkyTileExact,
    /// Whether the display adds the veiling glare around the sun (`display.glare`, colour
    /// only).
    Glare,
    /// Whether the sky pass writes [`RADIANCE`]: always but in a frame drawn in tiles that
    /// nothing meters, which writes the display image alone.
    WriteRadiance,
    /// Whether an order loop's pass reads single scattering (order 2), whose deltas have a Mie
    /// part; at later orders that part is zero and goes unread.
    FirstOrder,
    /// Whether a view ray may start with the sun below Bruneton's tables (102° from the
    /// zenith): only then does its sky pass carry the code for such rays.
    SunBelowTables,
}

impl Constant {
    /// The `override` name in WGSL.
    pub fn name(self) -> &'static str {
        match self {
            Constant::Projection => "PROJECTION",
            Constant::AboveAtmosphere => "ABOVE_ATMOSPHERE",
            Constant::DisplayMode => "DISPLAY_MODE",
            Constant::ToneMap => "TONE_MAP",
            Constant::SunDisk => "SUN_DISK",
            Constant::ViewRegion => "VIEW_REGION",
            Constant::SkyTile => "SKY_TILE",
            Constant::SkyTileExact => "SKY_TILE_EXACT",
            Constant::Glare => "GLARE",
            Constant::WriteRadiance => "WRITE_RADIANCE",
            Constant::FirstOrder => "FIRST_ORDER",
            Constant::SunBelowTables => "SUN_BELOW_TABLES",
        }
    }
}

/// The pipeline constants of every sky pass ([`PassSpec::sky`]).
pub const SKY_CONSTANTS: [Constant; 10] = [
    Constant::Projection,
    Constant::AboveAtmosphere,
    Constant::SunDisk,
    Constant::ViewRegion,
    Constant::SkyTile,
    Constant::SkyTileExact,
    Constant::DisplayMode,
    Constant::ToneMap,
    Constant::Glare,
    Constant::WriteRadiance,
];

/// How many workgroups a pass runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dispatch {
    /// One invocation per texel (x, y) of the table with this id (× the march split,
    /// `prelude::march_split`, in the passes that split their marches), one z per batch; a
    /// pass over a 3D table marches its slices inside each invocation.
    Table(&'static str),
    /// One workgroup per texel (x, y) of the table with this id (per column of a 3D table), one
    /// z per batch: the workgroup's invocations share the texel's directions or the column's
    /// slices, for tables of few texels and much work each (a GPU needs thousands of
    /// invocations in flight).
    TexelGroups(&'static str),
    /// One workgroup per run of `prelude::texel_run` texels along a row (x) of the table with
    /// this id, one z per batch: as `TexelGroups`, for a table whose texels along x share
    /// their rays and differ only in the light along them (Hillaire's Ψ_ms over the sun's
    /// angle), so that a workgroup marches each ray once for the run.
    TexelRuns(&'static str),
    /// One invocation per texel (x, y, z) of the 3D table with this id, z running over the
    /// slices of every batch in turn.
    Volume(&'static str),
    /// One invocation per pixel of the view.
    View,
}

/// How often a pass runs in a frame that runs it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Repeat {
    Once,
    /// Once for each scattering order from 2 to the scene's count (none for one order), the
    /// consecutive passes marked so running in turn for each order: an order loop.
    PerOrder,
}

/// Most tables one pass may bind: the storage buffers per shader stage the engine asks for
/// (`gpu::STORAGE_BUFFERS_PER_STAGE`) less group 0's batches and profile and the sky pass's
/// [`EXACT_TILES`].
pub const MAX_TABLES_PER_PASS: usize = 6;

/// Resources that are not tables: the view's images, written and read by the view passes.
pub const RADIANCE: &str = "radiance";
pub const DISPLAY: &str = "display";
/// The tiles a sky pass drawn in tiles computes pixel by pixel (a storage buffer that is also
/// the arguments of an indirect dispatch).
pub const EXACT_TILES: &str = "exact-tiles";
/// The view's luminance histogram (a storage buffer of `HISTOGRAM_BINS` counts).
pub const HISTOGRAM: &str = "histogram";

/// One pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PassSpec {
    /// Stable name (kebab case), shown in the Performance panel and the benchmarks.
    pub name: &'static str,
    /// The entry file; `shaders/common/` and the model's common files come first.
    pub shader: Shader,
    /// Tables (registry ids) or images ([`RADIANCE`]) the pass reads.
    pub reads: &'static [&'static str],
    /// Tables or images the pass writes.
    pub writes: &'static [&'static str],
    /// Scene inputs the pass reads itself; those of the tables it writes are added from the
    /// registry, and everything is rebuilt when the atmosphere changes.
    pub inputs: Inputs,
    pub dispatch: Dispatch,
    pub constants: &'static [Constant],
    pub repeat: Repeat,
    /// What the pass reads when the camera is above the atmosphere, where it reads less (a sky
    /// pass that marches every pixel instead of looking up the view tables, or reads Bruneton's
    /// 4D or Elek's 3D tables instead of their slices at the camera); None: `reads`.
    /// The engine leaves the passes that only the other reads need stale until they are.
    pub reads_above_atmosphere: Option<&'static [&'static str]>,
    /// What the pass reads when a view ray may start with the sun below Bruneton's tables
    /// (`Constant::SunBelowTables`), where it reads the 4D tables instead of their slices at
    /// the camera; None: `reads`. Left stale the same way.
    pub reads_with_sun_below_tables: Option<&'static [&'static str]>,
    /// What the pass reads only for pixels that see the ground: a view without ground leaves
    /// the passes that only these need stale until a view shows the ground.
    pub reads_for_ground: &'static [&'static str],
    /// What the pass reads only in frames drawn in tiles (a view in motion on a software GPU)
    /// from inside the atmosphere: the moving sky of a march per pixel ([`moving_sky_pass`]).
    /// Other frames leave the passes that only these need stale until such a frame.
    pub reads_in_motion: &'static [&'static str],
}

impl PassSpec {
    /// A pass that builds tables from tables, reading no scene input itself (those of the
    /// tables it writes come from the registry).
    pub const fn table(
        name: &'static str,
        shader: Shader,
        reads: &'static [&'static str],
        writes: &'static [&'static str],
        dispatch: Dispatch,
        repeat: Repeat,
    ) -> PassSpec {
        PassSpec {
            name,
            shader,
            reads,
            writes,
            inputs: Inputs::NONE,
            dispatch,
            constants: &[],
            repeat,
            reads_above_atmosphere: None,
            reads_with_sun_below_tables: None,
            reads_for_ground: &[],
            reads_in_motion: &[],
        }
    }

    /// A model's sky pass: draws the view from the tables it reads, compiled per projection
    /// and per camera inside or above the atmosphere. It writes the radiance and the view as
    /// displayed, so the display pass runs only in frames that leave the sky as it was; the
    /// display settings are not among its inputs for the same reason.
    pub const fn sky(shader: Shader, reads: &'static [&'static str]) -> PassSpec {
        PassSpec {
            name: "sky",
            shader,
            reads,
            writes: &[RADIANCE, DISPLAY, EXACT_TILES],
            inputs: SKY_INPUTS,
            dispatch: Dispatch::View,
            constants: &SKY_CONSTANTS,
            repeat: Repeat::Once,
            reads_above_atmosphere: None,
            reads_with_sun_below_tables: None,
            reads_for_ground: &[],
            reads_in_motion: &[],
        }
    }

    /// A sky pass that marches every pixel from above the atmosphere, reading only
    /// `reads_above_atmosphere` there.
    pub const fn sky_marching_from_space(
        shader: Shader,
        reads: &'static [&'static str],
        reads_above_atmosphere: &'static [&'static str],
    ) -> PassSpec {
        PassSpec {
            reads_above_atmosphere: Some(reads_above_atmosphere),
            ..PassSpec::sky(shader, reads)
        }
    }

    /// The same pass reading `tables` only for pixels that see the ground.
    pub const fn with_reads_for_ground(self, tables: &'static [&'static str]) -> PassSpec {
        PassSpec {
            reads_for_ground: tables,
            ..self
        }
    }

    /// The same sky pass of a march per pixel drawing its frames in tiles from the moving sky
    /// ([`moving_sky_pass`]), which it must read: `views/moving_sky_radiance.wgsl`.
    pub const fn with_moving_sky(self) -> PassSpec {
        PassSpec {
            reads_in_motion: &[MOVING_SKY],
            ..self
        }
    }

    /// What the pass reads with the camera above the atmosphere or not, with the sun below
    /// Bruneton's tables for some view ray or not, in a view that shows the ground or not, in
    /// a frame drawn in tiles or not.
    pub fn reads_where(
        &self,
        above_atmosphere: bool,
        sun_below_tables: bool,
        ground_in_view: bool,
        in_motion: bool,
    ) -> Vec<&'static str> {
        let reads = match (
            self.reads_above_atmosphere,
            self.reads_with_sun_below_tables,
        ) {
            (Some(r), _) if above_atmosphere => r,
            (_, Some(r)) if sun_below_tables => r,
            _ => self.reads,
        };
        reads
            .iter()
            .copied()
            .filter(|r| ground_in_view || !self.reads_for_ground.contains(r))
            .filter(|r| (in_motion && !above_atmosphere) || !self.reads_in_motion.contains(r))
            .collect()
    }

    /// Whether the pass builds a table (as opposed to drawing the view).
    pub fn is_table(&self) -> bool {
        !matches!(self.dispatch, Dispatch::View)
    }

    /// Whether the pass binds `id` as a table it only reads: a storage buffer bound read-only,
    /// so that passes which read the same tables and write different ones follow each other
    /// with no barrier between them and a GPU may run them side by side. The view's images,
    /// the exact-tile list and the histogram keep their own access.
    pub fn reads_only(&self, id: &str) -> bool {
        ![RADIANCE, DISPLAY, EXACT_TILES, HISTOGRAM].contains(&id) && !self.writes.contains(&id)
    }

    /// Every resource the pass binds: what it reads, then what it writes, without repeats.
    pub fn resources(&self) -> Vec<&'static str> {
        let mut v: Vec<&'static str> = Vec::new();
        for &r in self.reads.iter().chain(self.writes) {
            if !v.contains(&r) {
                v.push(r);
            }
        }
        v
    }

    /// The scene inputs that make the pass stale directly: its own and those the registry
    /// declares for the tables it writes; a view pass's include the ground albedo, with which
    /// the sky pass draws the ground.
    pub fn direct_inputs(&self, model: &ModelInfo) -> Inputs {
        let own = self.inputs.union(Inputs::ATMOSPHERE);
        let own = if self.is_table() {
            own
        } else {
            own.union(Inputs::GROUND_ALBEDO)
        };
        self.writes
            .iter()
            .filter_map(|id| model.table(id))
            .fold(own, |a, t| a.union(t.invalidated_by))
    }
}

/// The passes of one model.
#[derive(Debug, Clone, Copy)]
pub struct GpuMethod {
    pub method: Method,
    /// The cosine of the largest sun zenith angle the model's tables cover, where a view ray
    /// may start with the sun below it and the passes read other tables
    /// (`Constant::SunBelowTables`, `PassSpec::reads_with_sun_below_tables`); None: tables
    /// that cover every sun. −1 to 1.
    pub lowest_table_mu_s: Option<f64>,
    /// WGSL files every pass of the model includes after `shaders/common/`.
    pub common: &'static [Shader],
    /// Table passes in dependency order, then the sky pass (which writes [`RADIANCE`]).
    pub passes: &'static [PassSpec],
    /// The model's constants the passes read from `globals.model`, for the optics and model
    /// settings of `Params`.
    pub constants: fn(&atmoscope_model::methods::shared::Params) -> ModelConstants,
}

/// The values of `globals.model`: three rows of four.
pub type ModelConstants = [f64; 12];

/// Constants that fill the first row of `globals.model` alone.
pub fn first_row(row: [f64; 4]) -> ModelConstants {
    let mut c = [0.0; 12];
    c[..4].copy_from_slice(&row);
    c
}

impl GpuMethod {
    /// The registry row of the model.
    pub fn info(&self) -> &'static ModelInfo {
        methods::info(self.method)
    }

    /// Every pass in the order a frame runs them: the model's, then the views' shared ones.
    pub fn specs(&self) -> impl Iterator<Item = &PassSpec> {
        self.passes.iter().chain(&VIEW_PASSES)
    }
}

/// The display pass every model ends with: radiance → exposure, tone map, sRGB or false colour
/// (`shaders/views/tone.wgsl`, which the sky pass applies too). It runs in frames that change
/// the display but not the sky: a frame whose sky pass ran has its display image already.
pub const DISPLAY_PASS: PassSpec = PassSpec {
    name: "display",
    shader: shader!("views/display.wgsl"),
    reads: &[RADIANCE],
    writes: &[DISPLAY],
    inputs: Inputs::DISPLAY.union(Inputs::VIEW_SIZE),
    dispatch: Dispatch::View,
    // The projection places each pixel's direction for the glare around the sun.
    constants: &[
        Constant::DisplayMode,
        Constant::ToneMap,
        Constant::Glare,
        Constant::Projection,
    ],
    repeat: Repeat::Once,
    reads_above_atmosphere: None,
    reads_with_sun_below_tables: None,
    reads_for_ground: &[],
    reads_in_motion: &[],
};

/// The pass that counts the view's pixels per luminance bin, after every model's view; it
/// runs only while the engine meters (`Engine::set_metering`).
pub const METER_PASS: PassSpec = PassSpec {
    name: "meter",
    shader: shader!("views/meter.wgsl"),
    reads: &[RADIANCE],
    writes: &[HISTOGRAM],
    inputs: Inputs::VIEW_SIZE,
    dispatch: Dispatch::View,
    constants: &[],
    repeat: Repeat::Once,
    reads_above_atmosphere: None,
    reads_with_sun_below_tables: None,
    reads_for_ground: &[],
    reads_in_motion: &[],
};

/// The passes after every model's sky pass: they read the view, not the tables.
pub const VIEW_PASSES: [PassSpec; 2] = [DISPLAY_PASS, METER_PASS];

/// The transmittance pass the table-based models share.
pub const TRANSMITTANCE_PASS: PassSpec = PassSpec {
    name: "transmittance",
    shader: shader!("shared/transmittance.wgsl"),
    reads: &[],
    writes: &["transmittance"],
    inputs: Inputs::NONE,
    dispatch: Dispatch::Table("transmittance"),
    constants: &[],
    repeat: Repeat::Once,
    reads_above_atmosphere: None,
    reads_with_sun_below_tables: None,
    reads_for_ground: &[],
    reads_in_motion: &[],
};

/// The table of the moving sky (`atmoscope_model::methods::shared::moving_sky`).
pub const MOVING_SKY: &str = moving_sky::TABLE.id;

/// The moving sky of a march per pixel: the model's sky file `sky`, whose `radiance(layer,
/// dir)` the entry point `shared/moving_sky.wgsl` evaluates at the directions of the sky-view
/// grid, reading what the sky pass reads. On a software GPU a march costs 10–300 table look-ups
/// a pixel; a view in motion is drawn from this table of 192 × 108 marches
/// ([`PassSpec::with_moving_sky`]), rebuilt only when the viewpoint moves, and the still frame
/// after it marches every pixel.
pub const fn moving_sky_pass(sky: Shader, reads: &'static [&'static str]) -> PassSpec {
    PassSpec::table(
        MOVING_SKY_PASS,
        sky,
        reads,
        &[MOVING_SKY],
        Dispatch::Table(MOVING_SKY),
        Repeat::Once,
    )
}

/// The name of [`moving_sky_pass`].
pub const MOVING_SKY_PASS: &str = "moving-sky";

/// The entry point of [`moving_sky_pass`], after the model's sky file.
pub const MOVING_SKY_ENTRY_POINT: Shader = shader!("shared/moving_sky.wgsl");

/// The sky file of the table-free single-scattering models: the view march lit through the
/// optical depth towards the sun by the model's rule (its constants say which).
pub const SINGLE_SCATTERING_SKY: Shader = shader!("shared/single_scattering_sky.wgsl");

/// The passes of a table-free single-scattering model: its moving sky and its sky pass.
pub const SINGLE_SCATTERING_PASSES: [PassSpec; 2] = [
    moving_sky_pass(SINGLE_SCATTERING_SKY, &[]),
    PassSpec::sky(SINGLE_SCATTERING_SKY, &[MOVING_SKY]).with_moving_sky(),
];

/// The passes of a nested march (the midpoint or the trapezoid rule towards the sun): its way
/// to the sun tabulated, the moving sky built from that table, and the sky pass marching every
/// sample's way to the sun.
pub const NESTED_MARCH_PASSES: [PassSpec; 3] = [
    sun_route_pass(&[]),
    moving_sky_pass(SINGLE_SCATTERING_SKY, &[SUN_ROUTE_TABLE]),
    PassSpec::sky(SINGLE_SCATTERING_SKY, &[MOVING_SKY]).with_moving_sky(),
];

/// Single scattering alone: the `psi` of the table-free sky pass is zero.
pub const NO_HIGHER_ORDERS: Shader = shader!("shared/no_higher_orders.wgsl");

/// The exponential medium and its closed forms of the optical depth along a ray (the analytic
/// ways to the sun, and Leenman's depths along the view too).
pub const EXPONENTIAL: Shader = shader!("shared/exponential.wgsl");

/// The closed forms' columns along a ray for the way to the sun (`galaj_spline` defines its
/// own from its mesh).
pub const CLOSED_FORM_COLUMNS: Shader = shader!("shared/closed_form_columns.wgsl");

/// The table-free models' way to the sun and the sun's disk through it.
pub const SUN_ROUTE: Shader = shader!("shared/sun_route.wgsl");

/// What `sun_transmittance_by_way` is in a pass of a model with [`SUN_ROUTE`]: the way marched
/// at every sample, or, in a pass that reads [`SUN_ROUTE_TABLE`] (the nested marches' moving
/// sky), looked up in it (`passes::shader_source` chooses).
pub const SUN_ROUTE_MARCHED: Shader = shader!("shared/sun_route_marched.wgsl");
pub const SUN_ROUTE_FROM_TABLE: Shader = shader!("shared/sun_route_from_table.wgsl");

/// The nested marches' way to the sun tabulated for their moving sky
/// (`single_scattering_sky::SUN_ROUTE_TABLE`).
pub const SUN_ROUTE_TABLE: &str =
    atmoscope_model::methods::shared::single_scattering_sky::SUN_ROUTE_TABLE.id;

/// The pass that tabulates a nested march's way to the sun, reading what the way reads
/// (Gałaj's spline its mesh); it depends on the atmosphere alone.
pub const fn sun_route_pass(reads: &'static [&'static str]) -> PassSpec {
    PassSpec::table(
        SUN_ROUTE_PASS,
        shader!("shared/sun_route_table.wgsl"),
        reads,
        &[SUN_ROUTE_TABLE],
        Dispatch::Table(SUN_ROUTE_TABLE),
        Repeat::Once,
    )
}

/// The name of [`sun_route_pass`]; only the moving sky reads its table, so a still frame
/// never runs it.
pub const SUN_ROUTE_PASS: &str = "sun-route";

/// Hillaire's Ψ_ms table as a single-scattering model's higher orders (the `-ms` rows).
pub const HILLAIRE_HIGHER_ORDERS: Shader = shader!("hillaire/common.wgsl");

/// What a table-free single-scattering model includes: no higher orders, or Hillaire's Ψ_ms
/// (the `-ms` rows); the exponential medium, its columns and the way to the sun either way.
pub const SINGLE_SCATTERING_COMMON: [Shader; 4] = [
    NO_HIGHER_ORDERS,
    EXPONENTIAL,
    CLOSED_FORM_COLUMNS,
    SUN_ROUTE,
];
pub const SINGLE_SCATTERING_MS_COMMON: [Shader; 4] = [
    HILLAIRE_HIGHER_ORDERS,
    EXPONENTIAL,
    CLOSED_FORM_COLUMNS,
    SUN_ROUTE,
];

/// Leenman's segment-integral sky (`flat`, `raymarched`) and what it reads.
pub const SEGMENTS_COMMON: [Shader; 3] = [EXPONENTIAL, CLOSED_FORM_COLUMNS, SUN_ROUTE];
pub const SEGMENTS_SKY_PASS: PassSpec = PassSpec::sky(shader!("shared/segments_sky.wgsl"), &[]);

/// The passes that build Hillaire's higher orders for a single-scattering model: the
/// transmittance and Ψ_ms tables.
pub const HIGHER_ORDERS_PASSES: [PassSpec; 2] =
    [TRANSMITTANCE_PASS, hillaire::MULTIPLE_SCATTERING_PASS];

/// The passes of a table-free single-scattering model with Hillaire's higher orders: the
/// transmittance and Ψ_ms tables (Hillaire's pass), then the moving sky and the sky pass
/// reading Ψ_ms.
pub const SINGLE_SCATTERING_MS_PASSES: [PassSpec; 4] = [
    HIGHER_ORDERS_PASSES[0],
    HIGHER_ORDERS_PASSES[1],
    moving_sky_pass(SINGLE_SCATTERING_SKY, &["multiple-scattering"]),
    PassSpec::sky(SINGLE_SCATTERING_SKY, &["multiple-scattering", MOVING_SKY]).with_moving_sky(),
];

/// [`SINGLE_SCATTERING_MS_PASSES`] of a nested march, its way to the sun tabulated for the
/// moving sky as in [`NESTED_MARCH_PASSES`].
pub const NESTED_MARCH_MS_PASSES: [PassSpec; 5] = [
    HIGHER_ORDERS_PASSES[0],
    HIGHER_ORDERS_PASSES[1],
    sun_route_pass(&[]),
    moving_sky_pass(
        SINGLE_SCATTERING_SKY,
        &["multiple-scattering", SUN_ROUTE_TABLE],
    ),
    PassSpec::sky(SINGLE_SCATTERING_SKY, &["multiple-scattering", MOVING_SKY]).with_moving_sky(),
];

/// The sun's disk through the transmittance table, for the models that have one: the
/// `sun_through_atmosphere` every sky pass's entry point calls (a model without the table
/// defines its own).
pub const SUN_DISK_FROM_TABLE: Shader = shader!("shared/sun_disk.wgsl");

/// The entry point every sky pass ends with; the pass's own file defines `radiance(layer, dir)`.
pub const SKY_ENTRY_POINT: Shader = shader!("views/sky.wgsl");

/// What the entry point draws along a direction (`view_radiance`): the model's `radiance`, or
/// for a sky pass [`PassSpec::with_moving_sky`] the moving sky in frames drawn in tiles.
pub const VIEW_RADIANCE: Shader = shader!("views/radiance.wgsl");
pub const MOVING_SKY_RADIANCE: Shader = shader!("views/moving_sky_radiance.wgsl");

/// What the display shows of a pixel's radiance, included by every pass that writes
/// [`DISPLAY`] (the sky pass and the display pass) before the pass's own file.
pub const TONE: Shader = shader!("views/tone.wgsl");

/// What every sky pass reads besides its tables.
pub const SKY_INPUTS: Inputs = Inputs::VIEWPOINT
    .union(Inputs::SUN)
    .union(Inputs::CAMERA)
    .union(Inputs::VIEW_SIZE);

/// The WGSL files every pass includes, after the generated prelude.
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

/// Every real-time model's passes, in registry order.
pub const GPU_METHODS: [GpuMethod; 18] = [
    hillaire::METHOD,
    bruneton::METHOD,
    garcia_linan::METHOD,
    elek::METHOD,
    nishita::METHOD,
    trapezoid::METHOD,
    nishita::METHOD_MS,
    trapezoid::METHOD_MS,
    schuler::METHOD,
    schuler::METHOD_MS,
    galaj_taylor::METHOD,
    galaj_taylor::METHOD_MS,
    galaj_spline::METHOD,
    galaj_spline::METHOD_MS,
    flat::METHOD,
    raymarched::METHOD,
    preetham::METHOD,
    empty::METHOD,
];

/// The passes of `method`, or None for a model with no real-time passes (the path tracer).
pub fn gpu_method(method: Method) -> Option<&'static GpuMethod> {
    GPU_METHODS.iter().find(|m| m.method == method)
}

/// The group-1 binding of a table or image, from `shaders/common/bindings.wgsl`: the table
/// with registry id `id` is declared there as `<id with _ for ->_lut`, the images by name.
pub fn binding(id: &str) -> Option<u32> {
    let name = match id {
        RADIANCE => "radiance_out".to_string(),
        DISPLAY => "display_out".to_string(),
        EXACT_TILES => "exact_tiles".to_string(),
        HISTOGRAM => "histogram".to_string(),
        table => format!("{}_lut", table.replace('-', "_")),
    };
    binding_of(&name)
}

/// The group-1 binding of the variable `name` in `shaders/common/bindings.wgsl`.
pub fn binding_of(name: &str) -> Option<u32> {
    COMMON[0].source.lines().find_map(|line| {
        let rest = line.trim().strip_prefix("@group(1) @binding(")?;
        let (n, decl) = rest.split_once(')')?;
        let var = decl.trim_start().strip_prefix("var")?;
        // `var<storage, read_write> name: …` or `var name: …`
        let var = match var.strip_prefix('<') {
            Some(rest) => rest.split_once('>')?.1,
            None => var,
        };
        let declared = var.split(':').next()?.trim();
        (declared == name).then(|| n.parse().ok())?
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No pass takes more pipeline constants than a variant holds (`passes::MAX_CONSTANTS`): one
    /// more would be dropped and compiled at its default.
    #[test]
    fn no_pass_takes_more_constants_than_a_variant_holds() {
        for method in GPU_METHODS {
            for pass in method.passes.iter().chain(&VIEW_PASSES) {
                assert!(
                    pass.constants.len() <= crate::passes::MAX_CONSTANTS,
                    "{:?} {}: {} constants",
                    method.method,
                    pass.name,
                    pass.constants.len()
                );
            }
        }
    }

    #[test]
    fn every_real_time_model_of_the_registry_has_passes_and_every_table_a_writer() {
        for row in methods::realtime() {
            let gpu =
                gpu_method(row.method).unwrap_or_else(|| panic!("{} has no GPU passes", row.id));
            for t in row.tables {
                // One writer outside the order loop at most; the loop's passes may rewrite it.
                let writers: Vec<_> = gpu
                    .passes
                    .iter()
                    .filter(|p| p.writes.contains(&t.id))
                    .collect();
                let once = writers.iter().filter(|p| p.repeat == Repeat::Once).count();
                assert!(
                    !writers.is_empty() && once <= 1,
                    "{}: table {} is written by {} passes, {once} outside the order loop",
                    row.id,
                    t.id,
                    writers.len()
                );
                assert!(binding(t.id).is_some(), "{} has no binding", t.id);
            }
            let looped: Vec<usize> = (0..gpu.passes.len())
                .filter(|&i| gpu.passes[i].repeat == Repeat::PerOrder)
                .collect();
            assert!(
                looped.windows(2).all(|w| w[1] == w[0] + 1),
                "{}: the order loop's passes are consecutive",
                row.id
            );
            let last = gpu.passes.last().expect("passes");
            assert!(
                last.writes.contains(&RADIANCE),
                "{}: the sky pass comes last",
                row.id
            );
            // The engine recreates the view's images when the size changes.
            assert!(
                last.inputs.intersects(Inputs::VIEW_SIZE),
                "{}: the sky pass reads the view size",
                row.id
            );
            for (i, p) in gpu.passes.iter().enumerate() {
                let tables = p
                    .resources()
                    .iter()
                    .filter(|r| ![RADIANCE, DISPLAY, EXACT_TILES].contains(r))
                    .count();
                assert!(
                    tables <= MAX_TABLES_PER_PASS,
                    "{}: {} binds {tables} tables",
                    row.id,
                    p.name
                );
                let fewer = [
                    p.reads_where(true, true, true, true),
                    p.reads_where(false, true, true, true),
                ];
                assert!(
                    fewer.iter().flatten().all(|r| p.reads.contains(r)),
                    "{}: {} reads from space what it does not declare",
                    row.id,
                    p.name
                );
                assert!(
                    p.reads_in_motion.iter().all(|r| p.reads.contains(r)),
                    "{}: {} reads in motion what it does not declare",
                    row.id,
                    p.name
                );
                if p.writes.contains(&MOVING_SKY) {
                    // The moving sky evaluates the sky pass's radiance: it reads what that reads,
                    // but for a nested march's way to the sun, which it reads from its table.
                    let tabulated = p.reads.contains(&SUN_ROUTE_TABLE);
                    let sky: Vec<_> = last
                        .reads
                        .iter()
                        .filter(|&&r| {
                            r != MOVING_SKY
                                && !(tabulated
                                    && r == atmoscope_model::methods::galaj_spline::MESH.id)
                        })
                        .collect();
                    assert_eq!(
                        p.reads
                            .iter()
                            .filter(|&&r| r != SUN_ROUTE_TABLE)
                            .collect::<Vec<_>>(),
                        sky,
                        "{}: the moving sky reads what the sky pass reads",
                        row.id
                    );
                    assert_eq!(last.shader, p.shader, "{}: the same sky file", row.id);
                    assert_eq!(last.reads_in_motion, [MOVING_SKY], "{}", row.id);
                }
                for r in p.reads {
                    let earlier = gpu.passes[..i].iter().any(|q| q.writes.contains(r));
                    assert!(
                        earlier,
                        "{}: {} reads {r} before it is written",
                        row.id, p.name
                    );
                }
                if let Dispatch::Table(id) | Dispatch::Volume(id) = p.dispatch {
                    assert!(
                        row.table(id).is_some(),
                        "{}: {} dispatches over {id}",
                        row.id,
                        p.name
                    );
                }
            }
        }
    }

    #[test]
    fn bindings_are_found_in_the_one_wgsl_file_and_are_distinct() {
        assert_eq!(binding("transmittance"), Some(0));
        assert_eq!(binding("sky-view"), Some(3));
        assert_eq!(binding(RADIANCE), Some(6));
        assert_eq!(binding_of("radiance_in"), Some(7));
        assert!(binding_of("radiance_in").is_some());
        assert!(binding("no-such-table").is_none());
        let mut all: Vec<u32> = GPU_METHODS
            .iter()
            .flat_map(|m| m.info().tables.iter().map(|t| t.id))
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .filter_map(binding)
            .chain(
                [RADIANCE, DISPLAY, EXACT_TILES]
                    .into_iter()
                    .filter_map(binding),
            )
            .chain(binding_of("radiance_in"))
            .collect();
        let n = all.len();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), n, "two resources share a binding");
    }
}
