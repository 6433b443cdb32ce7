//! The plan of a frame, pure and testable without a device: from the inputs that changed,
//! which passes run (`plan`), with which pipeline constants and grids (`FrameSetup`), and the
//! order loop that repeats a pass once per scattering order (`with_order_loop`).

use super::*;

/// What a frame draws, from the scene and the atmosphere on screen.
pub(super) struct FrameSetup {
    pub(super) snapshot: Snapshot,
    pub(super) globals: Globals,
    pub(super) sun: DVec3,
    pub(super) size: [u32; 2],
    pub(super) camera: Camera,
    pub(super) bottom_radius_m: f64,
    /// Whether the camera is above the top of the atmosphere.
    pub(super) above: bool,
    /// Whether a view ray may start with the sun below Bruneton's tables (from above the
    /// atmosphere, or with the sun that low at the camera).
    pub(super) sun_below_tables: bool,
    /// Pixels on a side of the sky pass's interpolated tiles this frame (1: every pixel).
    pub(super) sky_tile: u32,
    /// Whether the sky pass writes the radiance image: all but a frame in tiles that nothing
    /// meters.
    pub(super) write_radiance: bool,
    /// Whether the sky pass runs in bands of what the rows see, the sun's disk apart
    /// (`Engine::set_view_bands`), or as one dispatch.
    pub(super) bands: bool,
}

impl FrameSetup {
    pub(super) fn new(
        scene: &Scene,
        view: &View,
        state: &AtmosphereState,
        gpu: &GpuMethod,
    ) -> FrameSetup {
        let params = &state.params;
        let camera = Camera::new(&scene.camera, params.bottom_radius_m, view.projection);
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let viewpoint = viewpoint(scene, &camera);
        let size = [view.width.max(1), view.height.max(1)];
        let snapshot = Snapshot {
            atmosphere: state.key.without_albedo(),
            ground: (state.key.settings.ground, state.key.settings.ground_albedo),
            viewpoint: [viewpoint.h, viewpoint.mu_s],
            sun: sun.extend(scene.sun.sunlight_scale()).to_array(),
            // The Polarisation mode's radiance image holds Stokes vectors: entering or leaving
            // it redraws the view, as a new camera would.
            camera: (
                scene.camera.clone(),
                view.projection,
                view.mode == DisplayMode::Polarisation,
            ),
            size,
            display: (
                scene.display.exposure_ev,
                scene.display.tone_map,
                view.mode,
                scene.display.dither,
                scene.display.white_balance,
                scene.display.glare,
            ),
        };
        let globals = Globals::from(&FrameInputs {
            scene,
            params,
            camera: &camera,
            sun,
            viewpoint,
            size,
            mode: view.mode,
            model: state.model_constants,
            // Only a display that shows glare pays for its source.
            glare: (scene.display.glare && view.mode == DisplayMode::Colour).then(|| {
                atmoscope_model::display::sun_irradiance_rgb(params, viewpoint.h, viewpoint.mu_s)
            }),
            balance: white_balance::matrix_with(scene, || {
                *state.noon_white.get_or_init(|| {
                    white_balance::noon_sun_white(&Atmosphere::new(&state.key.settings))
                })
            }),
        });
        let above = viewpoint.h > params.thickness_m();
        FrameSetup {
            snapshot,
            globals,
            sun,
            size,
            camera,
            bottom_radius_m: params.bottom_radius_m,
            above,
            sun_below_tables: above
                || gpu
                    .lowest_table_mu_s
                    .is_some_and(|lowest| viewpoint.mu_s < lowest),
            sky_tile: 1,
            write_radiance: true,
            bands: true,
        }
    }

    /// What this frame is like for the passes' reads (`spec::Read`), with or without the
    /// ground in view and in motion (drawn in tiles) or not.
    pub(super) fn situation(&self, ground_in_view: bool, in_motion: bool) -> Situation {
        Situation {
            above_atmosphere: self.above,
            sun_below_tables: self.sun_below_tables,
            ground_in_view,
            in_motion,
        }
    }

    /// Whether some pixel of `view` sees the ground.
    pub(super) fn shows_ground(&self, view: &View) -> bool {
        self.camera
            .shows_ground(self.bottom_radius_m, view.width, view.height)
    }

    /// A pipeline constant's value in this frame; a dispatch over the whole view draws the
    /// sun's disk and decides sky or ground per pixel.
    pub(super) fn value(&self, c: Constant, scene: &Scene, view: &View) -> u32 {
        match c {
            Constant::Projection => uniforms::projection_code(view.projection),
            Constant::AboveAtmosphere => u32::from(self.above),
            Constant::DisplayMode => uniforms::display_code(view.mode),
            Constant::ToneMap => uniforms::tone_map_code(scene.display.tone_map),
            Constant::SunDisk => 1,
            Constant::ViewRegion => uniforms::region_code(Sees::Both),
            Constant::SkyTile => 1,
            Constant::SkyTileExact => 0,
            Constant::Glare => u32::from(scene.display.glare && view.mode == DisplayMode::Colour),
            Constant::WriteRadiance => u32::from(self.write_radiance),
            Constant::FirstOrder => 1,
            Constant::SunBelowTables => u32::from(self.sun_below_tables),
            Constant::Polarisation => {
                uniforms::polarisation_code(view.mode, scene.camera.polariser_deg)
            }
        }
    }

    /// Each pass's pipeline constants for a dispatch over all of it.
    pub(super) fn variants(
        &self,
        pipelines: &Pipelines,
        scene: &Scene,
        view: &View,
    ) -> Vec<Variant> {
        (0..pipelines.len())
            .map(|i| pipelines.variant(i, |c| self.value(c, scene, view)))
            .collect()
    }

    /// The dispatches of pass `i` this frame. A view pass that takes the region runs in bands
    /// of rows that see sky alone, ground alone or both (`Camera::rows_see`), and one that
    /// takes the sun's disk draws it in one more dispatch over the pixels the disk reaches
    /// (`SunInView::pixel_box`), so that no pixel runs the code of what it cannot see (a
    /// software GPU runs both sides of every branch). A frame with tiles (`sky_tile` > 1)
    /// runs the sky pass as one dispatch of tiles, which decides sky or ground per corner and
    /// lists the tiles it cannot interpolate, an indirect dispatch over those, then the sun's
    /// disk pixel by pixel. Without bands (`Engine::set_view_bands`) a frame at full
    /// resolution is one dispatch, as is any other pass.
    pub(super) fn work(
        &self,
        pipelines: &Pipelines,
        step: Step,
        layers: u32,
        scene: &Scene,
        view: &View,
    ) -> Vec<Work> {
        let i = step.pass;
        let grid = grid(pipelines, i, layers, self.size);
        let constants = pipelines.specs().nth(i).map_or(&[][..], |s| s.constants);
        let variant = |region: Sees, sun: bool, tile: u32, exact: bool| {
            pipelines.variant(i, |c| match c {
                Constant::SunDisk => u32::from(sun),
                Constant::ViewRegion => uniforms::region_code(region),
                Constant::SkyTile => tile,
                Constant::SkyTileExact => u32::from(exact),
                Constant::FirstOrder => step.first_order(),
                other => self.value(other, scene, view),
            })
        };
        let takes = |c: Constant| constants.contains(&c);
        let tile = self.sky_tile;
        let tiled = takes(Constant::SkyTile) && tile > 1;
        if (!takes(Constant::ViewRegion) && !takes(Constant::SunDisk)) || (!self.bands && !tiled) {
            return vec![Work::whole(i, variant(Sees::Both, true, 1, false), grid)];
        }
        let [w, h] = self.size;
        let mut work = Vec::new();
        if tiled {
            let span = WORKGROUP_SIZE * tile;
            work.push(Work {
                tiles: TilePhase::Fill,
                ..Work::whole(
                    i,
                    variant(Sees::Both, false, tile, false),
                    [w.div_ceil(span), h.div_ceil(span), 1],
                )
            });
            work.push(Work {
                tiles: TilePhase::Compute,
                ..Work::whole(i, variant(Sees::Both, false, tile, true), [0; 3])
            });
        } else if takes(Constant::ViewRegion) && !self.above {
            let rows = self.camera.rows_see(self.bottom_radius_m, w, h);
            let group_rows: Vec<Sees> = rows
                .chunks(WORKGROUP_SIZE as usize)
                .map(|c| {
                    if c.iter().all(|&s| s == c[0]) {
                        c[0]
                    } else {
                        Sees::Both
                    }
                })
                .collect();
            let mut start = 0;
            for (g, &seen) in group_rows.iter().enumerate() {
                if group_rows.get(g + 1) != Some(&seen) {
                    work.push(Work {
                        pass: i,
                        variant: variant(seen, false, 1, false),
                        origin: [0, start as u32 * WORKGROUP_SIZE, 0],
                        groups: [grid[0], (g + 1 - start) as u32, 1],
                        tiles: TilePhase::None,
                    });
                    start = g + 1;
                }
            }
        } else {
            work.push(Work::whole(i, variant(Sees::Both, false, 1, false), grid));
        }
        let sun_box = self
            .camera
            .sun_in_view(self.sun, w, h)
            .and_then(|s| s.pixel_box(w, h));
        if let (true, Some([x0, y0, x1, y1])) = (takes(Constant::SunDisk), sun_box) {
            work.push(Work {
                pass: i,
                variant: variant(Sees::Both, true, 1, false),
                origin: [x0, y0, 0],
                groups: [groups(x1 - x0), groups(y1 - y0), 1],
                tiles: TilePhase::None,
            });
        }
        work
    }
}

/// The passes to run (indices in order) when `changed` inputs changed: a pass is stale when an
/// input it reads changed, a table it reads was just rewritten or it was left stale before
/// (`deferred`); it runs when the view needs what it writes in a frame like `situation` (each
/// read says when it is needed, `spec::Read`), and otherwise stays marked in `deferred`.
pub(super) fn plan(
    method: &GpuMethod,
    changed: Inputs,
    situation: &Situation,
    unwanted: &[&str],
    deferred: &mut [bool],
) -> Vec<usize> {
    let specs: Vec<&PassSpec> = method.specs().collect();
    let mut needed = vec![false; specs.len()];
    let mut needed_resources: Vec<Resource> = Vec::new();
    for (i, spec) in specs.iter().enumerate().rev() {
        let wanted = !spec.is_table() && !unwanted.contains(&spec.name);
        if wanted || spec.writes.iter().any(|w| needed_resources.contains(w)) {
            needed[i] = true;
            needed_resources.extend(spec.reads_in(situation));
        }
    }
    let mut written: Vec<Resource> = Vec::new();
    let mut run = Vec::new();
    for (i, spec) in specs.iter().enumerate() {
        let stale = deferred[i]
            || spec.direct_inputs().intersects(changed)
            || spec.reads.iter().any(|r| written.contains(&r.resource));
        // A view pass whose every output an earlier pass of this frame wrote with the frame's
        // inputs (the sky pass draws the display image too) has nothing left to do.
        let covered = !spec.is_table() && spec.writes.iter().all(|w| written.contains(w));
        if covered {
            deferred[i] = false;
        } else if stale {
            deferred[i] = !needed[i];
            // A pass left stale rewrites nothing: its readers are not stale for it.
            if needed[i] {
                written.extend(spec.writes);
                run.push(i);
            }
        }
    }
    run
}

/// One pass to encode, and the scattering order it computes when it is in an order loop (0
/// when it is not).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Step {
    pub(super) pass: usize,
    pub(super) order: u32,
}

impl Step {
    /// The value of [`Constant::FirstOrder`]: whether the deltas this step reads are single
    /// scattering (outside an order loop, or at its order 2).
    pub(super) fn first_order(self) -> u32 {
        u32::from(self.order <= 2)
    }
}

/// The passes to encode: `run` (pass indices in order) with each stretch of consecutive
/// order-loop passes repeated once per scattering order from 2 to `orders`.
pub(super) fn with_order_loop(run: &[usize], pipelines: &Pipelines, orders: u32) -> Vec<Step> {
    let specs: Vec<&PassSpec> = pipelines.specs().collect();
    let mut out = Vec::with_capacity(run.len());
    let mut group: Vec<usize> = Vec::new();
    let flush = |group: &mut Vec<usize>, out: &mut Vec<Step>| {
        for order in 2..=orders {
            out.extend(group.iter().map(|&pass| Step { pass, order }));
        }
        group.clear();
    };
    for &i in run {
        if specs[i].repeat == Repeat::PerOrder {
            group.push(i);
        } else {
            flush(&mut group, &mut out);
            out.push(Step { pass: i, order: 0 });
        }
    }
    flush(&mut group, &mut out);
    out
}

/// The scheduler on the CPU, with no device: every real-time model of the registry, as the
/// engine plans its frames. A model added to the registry (and its passes as data) is covered
/// with no edit here.
#[cfg(test)]
mod tests {
    use super::plan;
    use crate::methods::{
        DISPLAY, GpuMethod, METER_PASS, PassSpec, RADIANCE, Resource, Situation, TRANSMITTANCE,
        gpu_method,
    };
    use atmoscope_model::methods::{self, Inputs};

    /// Every real-time model's passes as data, from the registry.
    fn models() -> Vec<&'static GpuMethod> {
        let models: Vec<_> = methods::realtime()
            .map(|m| {
                gpu_method(m.method)
                    .unwrap_or_else(|| panic!("{}: a real-time model with no GPU passes", m.id))
            })
            .collect();
        assert!(models.len() > 1, "the registry lists real-time models");
        models
    }

    /// A still frame from inside the atmosphere with the ground in view.
    const INSIDE: Situation = Situation {
        above_atmosphere: false,
        sun_below_tables: false,
        ground_in_view: true,
        in_motion: false,
    };

    /// The names of the passes a frame that changes `changed` runs, from inside the atmosphere,
    /// the ground in view, still and not metering.
    fn names(method: &GpuMethod, changed: Inputs, deferred: &mut [bool]) -> Vec<&'static str> {
        let specs: Vec<_> = method.specs().collect();
        plan(method, changed, &INSIDE, &[METER_PASS.name], deferred)
            .into_iter()
            .map(|i| specs[i].name)
            .collect()
    }

    /// The pass that draws the radiance of the view (the sky pass).
    fn sky(method: &GpuMethod) -> &'static str {
        let sky = method
            .specs()
            .find(|s| !s.is_table() && s.writes.contains(&RADIANCE));
        sky.unwrap_or_else(|| panic!("{}: no pass draws the view", method.info().id))
            .name
    }

    #[test]
    fn a_new_atmosphere_runs_every_table_then_the_sky_and_an_unchanged_frame_nothing() {
        for method in models() {
            let id = method.info().id;
            let mut deferred = vec![false; method.specs().count()];
            let first = names(method, Inputs::ALL, &mut deferred);
            assert_eq!(first.last(), Some(&sky(method)), "{id}: {first:?}");
            // The sky pass draws the display image too: no display pass after it.
            let display = method
                .specs()
                .find(|s| s.writes == [DISPLAY])
                .map(|s| s.name);
            assert!(
                !first.iter().any(|n| Some(*n) == display),
                "{id}: {first:?}"
            );
            // A new atmosphere runs exactly the tables the sky reads, directly or through
            // other tables (from inside, still, the ground in view), in the model's order,
            // then the sky; every other table stays marked stale for a frame that reads it.
            let specs: Vec<_> = method.specs().collect();
            let reads = |s: &PassSpec| s.reads_in(&INSIDE).collect::<Vec<_>>();
            let mut wanted: Vec<Resource> = specs
                .iter()
                .filter(|s| s.name == sky(method))
                .flat_map(|s| reads(s))
                .collect();
            let mut expected = Vec::new();
            for s in specs.iter().rev().filter(|s| s.is_table()) {
                if s.writes.iter().any(|w| wanted.contains(w)) {
                    wanted.extend(reads(s));
                    expected.push(s.name);
                }
            }
            expected.reverse();
            expected.push(sky(method));
            assert_eq!(first, expected, "{id}: a new atmosphere");
            for (i, t) in specs.iter().enumerate().filter(|(_, s)| s.is_table()) {
                assert_eq!(deferred[i], !first.contains(&t.name), "{id}: {}", t.name);
            }
            assert_eq!(
                names(method, Inputs::NONE, &mut deferred),
                Vec::<&str>::new(),
                "{id}: an unchanged frame runs nothing"
            );
        }
    }

    #[test]
    fn turning_the_camera_redraws_the_sky_and_the_exposure_only_the_display() {
        for method in models() {
            let id = method.info().id;
            let mut deferred = vec![false; method.specs().count()];
            names(method, Inputs::ALL, &mut deferred);
            assert_eq!(
                names(method, Inputs::CAMERA, &mut deferred),
                vec![sky(method)],
                "{id}: turning"
            );
            assert_eq!(
                names(method, Inputs::DISPLAY, &mut deferred),
                vec!["display"],
                "{id}: exposure"
            );
        }
    }

    #[test]
    fn a_sun_move_reruns_a_subset_and_never_a_table_of_the_atmosphere_alone() {
        for method in models() {
            let id = method.info().id;
            let mut deferred = vec![false; method.specs().count()];
            let all = names(method, Inputs::ALL, &mut deferred);
            let moved = names(method, Inputs::SUN.union(Inputs::VIEWPOINT), &mut deferred);
            assert!(
                moved.iter().all(|n| all.contains(n)),
                "{id}: {moved:?} ⊄ {all:?}"
            );
            assert!(moved.contains(&sky(method)), "{id}: the sky is redrawn");
            if let Some(t) = method.specs().find(|s| s.writes == [TRANSMITTANCE]) {
                assert!(!moved.contains(&t.name), "{id}: {moved:?}");
            }
        }
    }

    /// A pass left stale because the view does not need it (from above the atmosphere) runs in
    /// the first frame that does, so nothing is lost by deferring it.
    #[test]
    fn passes_left_stale_from_above_run_once_a_view_needs_them() {
        for method in models() {
            let id = method.info().id;
            let n = method.specs().count();
            let specs: Vec<_> = method.specs().collect();
            let mut deferred = vec![false; n];
            let from_space = Situation {
                above_atmosphere: true,
                ..INSIDE
            };
            let above = plan(method, Inputs::ALL, &from_space, &[], &mut deferred);
            let inside = plan(method, Inputs::NONE, &INSIDE, &[], &mut deferred);
            let mut fresh = vec![false; n];
            let whole = plan(method, Inputs::ALL, &INSIDE, &[], &mut fresh);
            for i in whole {
                assert!(
                    above.contains(&i) || inside.contains(&i),
                    "{id}: {} never ran after the camera came down",
                    specs[i].name
                );
            }
            for i in &inside {
                assert!(
                    !(above.contains(i) && specs[*i].is_table()),
                    "{id}: {} ran twice for one atmosphere",
                    specs[*i].name
                );
            }
        }
    }
}
