//! The vocabulary of a model's GPU passes as data: which shader files make a pass, which tables
//! and images it reads (and when) and writes, which scene inputs it reads directly, how it is
//! dispatched and which pipeline constants it takes. Every model's file in `crate::methods`
//! describes its passes with these types; the engine runs any model from that description
//! alone (`crate::engine`): a pass reruns when a scene input it reads changed or a table it
//! reads was rewritten this frame.
//!
//! Tables are named by their declaration in the model's registry row
//! (`model::methods::MODELS`, [`Table`]); their WGSL bindings are generated from the registry
//! ([`bindings`]), as the constants are ([`crate::prelude`]).

pub mod bindings;
pub mod shared;

pub use shared::*;

use atmoscope_model::methods::shared::sun_rows::RowsFn;
use atmoscope_model::methods::shared::{Params, TableSpec};
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
        $crate::spec::Shader {
            path: $path,
            source: include_str!(concat!("../../../shaders/", $path)),
        }
    };
}
pub(crate) use shader;

/// A table as its registry row declares it (`model::methods::shared::TableSpec`); two are the
/// same table when their ids are.
#[derive(Debug, Clone, Copy)]
pub struct Table(pub &'static TableSpec);

impl PartialEq for Table {
    fn eq(&self, other: &Table) -> bool {
        self.0.id == other.0.id
    }
}
impl Eq for Table {}

impl std::ops::Deref for Table {
    type Target = TableSpec;
    fn deref(&self) -> &TableSpec {
        self.0
    }
}

/// Something a pass binds: a table of the registry, or one of the view's images and buffers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resource {
    Table(Table),
    /// The view's radiance (rgba32float), written by the sky pass and read by the view passes.
    Radiance,
    /// The view as displayed (rgba8unorm).
    Display,
    /// The tiles a sky pass drawn in tiles computes pixel by pixel (a storage buffer that is
    /// also the arguments of an indirect dispatch).
    ExactTiles,
    /// The view's luminance histogram (a storage buffer of `HISTOGRAM_BINS` counts).
    Histogram,
}

impl Resource {
    /// The table `spec` declares.
    pub const fn table(spec: &'static TableSpec) -> Resource {
        Resource::Table(Table(spec))
    }

    /// Stable id: the table's registry id, or the image's name.
    pub const fn id(self) -> &'static str {
        match self {
            Resource::Table(t) => t.0.id,
            Resource::Radiance => "radiance",
            Resource::Display => "display",
            Resource::ExactTiles => "exact-tiles",
            Resource::Histogram => "histogram",
        }
    }

    /// The table's declaration, None for the view's images and buffers.
    pub const fn as_table(self) -> Option<&'static TableSpec> {
        match self {
            Resource::Table(t) => Some(t.0),
            _ => None,
        }
    }
}

pub const RADIANCE: Resource = Resource::Radiance;
pub const DISPLAY: Resource = Resource::Display;
pub const EXACT_TILES: Resource = Resource::ExactTiles;
pub const HISTOGRAM: Resource = Resource::Histogram;

/// What a frame is like, as far as what a pass reads goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Situation {
    /// The camera is above the top of the atmosphere.
    pub above_atmosphere: bool,
    /// A view ray may start with the sun below the model's tables
    /// (`GpuMethod::lowest_table_mu_s`, `Constant::SunBelowTables`).
    pub sun_below_tables: bool,
    /// Some pixel of the view sees the ground.
    pub ground_in_view: bool,
    /// The frame is drawn in tiles (a view in motion on a software GPU).
    pub in_motion: bool,
}

impl Situation {
    /// A frame that needs every read a pass declares: from inside the atmosphere, the sun in
    /// the tables, the ground in view, in motion.
    pub const EVERYTHING_INSIDE: Situation = Situation {
        above_atmosphere: false,
        sun_below_tables: false,
        ground_in_view: true,
        in_motion: true,
    };
}

/// When a pass needs something it reads: each condition set narrows it to the frames with it.
/// A pass's readers left stale by a frame that does not need them run in a later frame that
/// does (`crate::engine`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct When {
    /// Only from inside the atmosphere (a sky pass that marches every pixel from space reads
    /// fewer tables there, Bruneton's and Elek's not their slices at the camera).
    pub inside_atmosphere: bool,
    /// Only while no view ray may start with the sun below the model's tables (Bruneton's
    /// slices at the camera cover only the sun the tables do).
    pub sun_in_tables: bool,
    /// Only for pixels that see the ground.
    pub ground_in_view: bool,
    /// Only in frames drawn in tiles, from inside the atmosphere (the moving sky).
    pub in_motion: bool,
}

impl When {
    pub const ALWAYS: When = When {
        inside_atmosphere: false,
        sun_in_tables: false,
        ground_in_view: false,
        in_motion: false,
    };

    /// Whether a frame like `s` needs the read.
    pub const fn holds(self, s: &Situation) -> bool {
        (!self.inside_atmosphere || !s.above_atmosphere)
            && (!self.sun_in_tables || !s.sun_below_tables)
            && (!self.ground_in_view || s.ground_in_view)
            && (!self.in_motion || (s.in_motion && !s.above_atmosphere))
    }
}

/// One resource a pass reads, and when it needs it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Read {
    pub resource: Resource,
    pub when: When,
}

/// A read the pass always needs; the methods narrow it.
pub const fn read(resource: Resource) -> Read {
    Read {
        resource,
        when: When::ALWAYS,
    }
}

/// A read of the table `spec` declares, always needed; the methods narrow it.
pub const fn read_table(spec: &'static TableSpec) -> Read {
    read(Resource::table(spec))
}

impl Read {
    /// Needed only from inside the atmosphere.
    pub const fn inside_atmosphere(self) -> Read {
        Read {
            when: When {
                inside_atmosphere: true,
                ..self.when
            },
            ..self
        }
    }

    /// Needed only while every view ray starts with the sun in the model's tables.
    pub const fn with_sun_in_tables(self) -> Read {
        Read {
            when: When {
                sun_in_tables: true,
                ..self.when
            },
            ..self
        }
    }

    /// Needed only for pixels that see the ground.
    pub const fn for_ground(self) -> Read {
        Read {
            when: When {
                ground_in_view: true,
                ..self.when
            },
            ..self
        }
    }

    /// Needed only in frames drawn in tiles from inside the atmosphere.
    pub const fn in_motion(self) -> Read {
        Read {
            when: When {
                in_motion: true,
                ..self.when
            },
            ..self
        }
    }
}

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
    /// What the sky pass does with the light's polarisation (`POLARISATION_*`): nothing, the
    /// camera's polarising filter, or the Stokes vector of the Polarisation display mode.
    Polarisation,
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
            Constant::Polarisation => "POLARISATION",
        }
    }
}

/// The pipeline constants of every sky pass ([`PassSpec::sky`]).
pub const SKY_CONSTANTS: [Constant; 11] = [
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
    Constant::Polarisation,
];

/// How many workgroups a pass runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dispatch {
    /// One invocation per texel (x, y) of the table (× the march split,
    /// `prelude::march_split`, in the passes that split their marches), one z per batch; a
    /// pass over a 3D table marches its slices inside each invocation.
    Table(Table),
    /// One workgroup per texel (x, y) of the table (per column of a 3D table), one z per
    /// batch: the workgroup's invocations share the texel's directions or the column's
    /// slices, for tables of few texels and much work each (a GPU needs thousands of
    /// invocations in flight).
    TexelGroups(Table),
    /// One workgroup per run of `prelude::texel_run` texels along a row (x) of the table, one
    /// z per batch: as `TexelGroups`, for a table whose texels along x share their rays and
    /// differ only in the light along them (Hillaire's Ψ_ms over the sun's angle), so that a
    /// workgroup marches each ray once for the run.
    TexelRuns(Table),
    /// One invocation per texel (x, y, z) of the 3D table, z running over the slices of every
    /// batch in turn.
    Volume(Table),
    /// One invocation per pixel of the view.
    View,
}

impl Dispatch {
    /// The table the dispatch runs over, None for the view.
    pub fn table(self) -> Option<Table> {
        match self {
            Dispatch::Table(t)
            | Dispatch::TexelGroups(t)
            | Dispatch::TexelRuns(t)
            | Dispatch::Volume(t) => Some(t),
            Dispatch::View => None,
        }
    }
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

/// One pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PassSpec {
    /// Stable name (kebab case), shown in the Performance panel and the benchmarks.
    pub name: &'static str,
    /// The WGSL files of the pass, in order, after the generated prelude and bindings,
    /// [`COMMON`] and (for a model's pass) the model's `GpuMethod::common`: the pass's own file
    /// last but for the entry points that wrap it.
    pub files: &'static [Shader],
    /// What the pass reads, each with when it needs it.
    pub reads: &'static [Read],
    /// Tables or images the pass writes.
    pub writes: &'static [Resource],
    /// Scene inputs the pass reads itself; those of the tables it writes are added from the
    /// registry, and everything is rebuilt when the atmosphere changes.
    pub inputs: Inputs,
    pub dispatch: Dispatch,
    pub constants: &'static [Constant],
    pub repeat: Repeat,
}

impl PassSpec {
    /// A pass that builds tables from tables, reading no scene input itself (those of the
    /// tables it writes come from the registry).
    pub const fn table(
        name: &'static str,
        files: &'static [Shader],
        reads: &'static [Read],
        writes: &'static [Resource],
        dispatch: Dispatch,
        repeat: Repeat,
    ) -> PassSpec {
        PassSpec {
            name,
            files,
            reads,
            writes,
            inputs: Inputs::NONE,
            dispatch,
            constants: &[],
            repeat,
        }
    }

    /// A model's sky pass: draws the view from what it reads, compiled per projection and per
    /// camera inside or above the atmosphere. It writes the radiance and the view as
    /// displayed, so the display pass runs only in frames that leave the sky as it was; the
    /// display settings are not among its inputs for the same reason. Its files end with
    /// [`TONE`], the model's sky file, [`VIEW_RADIANCE`] (or [`MOVING_SKY_RADIANCE`]) and
    /// [`SKY_ENTRY_POINT`].
    pub const fn sky(files: &'static [Shader], reads: &'static [Read]) -> PassSpec {
        PassSpec {
            name: "sky",
            files,
            reads,
            writes: &[RADIANCE, DISPLAY, EXACT_TILES],
            inputs: SKY_INPUTS,
            dispatch: Dispatch::View,
            constants: &SKY_CONSTANTS,
            repeat: Repeat::Once,
        }
    }

    /// What the pass reads in a frame like `s`.
    pub fn reads_in(&self, s: &Situation) -> impl Iterator<Item = Resource> + '_ {
        let s = *s;
        self.reads
            .iter()
            .filter(move |r| r.when.holds(&s))
            .map(|r| r.resource)
    }

    /// Whether the pass reads `resource` in some frame.
    pub fn reads(&self, resource: Resource) -> bool {
        self.reads.iter().any(|r| r.resource == resource)
    }

    /// Whether the pass builds a table (as opposed to drawing the view).
    pub fn is_table(&self) -> bool {
        !matches!(self.dispatch, Dispatch::View)
    }

    /// Whether the pass binds `resource` as a table it only reads: a storage buffer bound
    /// read-only, so that passes which read the same tables and write different ones follow
    /// each other with no barrier between them and a GPU may run them side by side. The
    /// view's images, the exact-tile list and the histogram keep their own access.
    pub fn reads_only(&self, resource: Resource) -> bool {
        matches!(resource, Resource::Table(_)) && !self.writes.contains(&resource)
    }

    /// Every resource the pass binds: what it reads, then what it writes, without repeats.
    pub fn resources(&self) -> Vec<Resource> {
        let mut v: Vec<Resource> = Vec::new();
        for r in self
            .reads
            .iter()
            .map(|r| r.resource)
            .chain(self.writes.iter().copied())
        {
            if !v.contains(&r) {
                v.push(r);
            }
        }
        v
    }

    /// The scene inputs that make the pass stale directly: its own and those the registry
    /// declares for the tables it writes; a view pass's include the ground albedo, with which
    /// the sky pass draws the ground.
    pub fn direct_inputs(&self) -> Inputs {
        let own = self.inputs.union(Inputs::ATMOSPHERE);
        let own = if self.is_table() {
            own
        } else {
            own.union(Inputs::GROUND_ALBEDO)
        };
        self.writes
            .iter()
            .filter_map(|r| r.as_table())
            .fold(own, |a, t| a.union(t.invalidated_by))
    }

    /// The pass's own file: the last of its files that is not a shared entry point.
    pub fn own_file(&self) -> Option<Shader> {
        self.files
            .iter()
            .rev()
            .find(|f| {
                ![
                    SKY_ENTRY_POINT,
                    VIEW_RADIANCE,
                    MOVING_SKY_RADIANCE,
                    MOVING_SKY_ENTRY_POINT,
                ]
                .contains(f)
            })
            .copied()
    }
}

/// The passes of one model.
#[derive(Debug, Clone, Copy)]
pub struct GpuMethod {
    pub method: Method,
    /// The cosine of the largest sun zenith angle the model's tables cover, where a view ray
    /// may start with the sun below it and the passes read other tables
    /// (`Constant::SunBelowTables`, [`When::sun_in_tables`]); None: tables that cover every
    /// sun. −1 to 1.
    pub lowest_table_mu_s: Option<f64>,
    /// WGSL files every pass of the model includes after [`COMMON`], before its own.
    pub common: &'static [Shader],
    /// Table passes in dependency order, then the sky pass (which writes [`RADIANCE`]).
    pub passes: &'static [PassSpec],
    /// The model's constants the passes read from `globals.model`, for the optics and model
    /// settings of `Params`.
    pub constants: fn(&Params) -> ModelConstants,
    /// Rows the model computes on the CPU for each batch and the sun at the camera (zenith
    /// cosine), which its passes read as `batches[layer].model` (a fit's coefficients, too
    /// many for `globals.model`); None for a model without.
    pub batch_rows: Option<RowsFn>,
}

/// The values of `globals.model`: three rows of four.
pub type ModelConstants = [f64; 12];

/// No model constants.
pub fn no_constants(_: &Params) -> ModelConstants {
    [0.0; 12]
}

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

    /// The WGSL files of `pass` after the prelude and the bindings, in order: [`COMMON`], the
    /// model's common files (not for the views' shared passes, which read no table), then the
    /// pass's own.
    pub fn files(&self, pass: &PassSpec) -> Vec<Shader> {
        let model: &[Shader] = if VIEW_PASSES.contains(pass) {
            &[]
        } else {
            self.common
        };
        // A sky pass's entry point draws the light's polarisation too.
        let (own, entry): (&[Shader], &[Shader]) = match pass.files.split_last() {
            Some((last, rest)) if *last == SKY_ENTRY_POINT => {
                (rest, &[SKY_POLARISATION, SKY_ENTRY_POINT])
            }
            _ => (pass.files, &[]),
        };
        COMMON
            .iter()
            .chain(model)
            .chain(own)
            .chain(entry)
            .copied()
            .collect()
    }
}
