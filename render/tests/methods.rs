//! Every real-time model of the registry on a real device (lavapipe in CI): shaders parse and
//! match the Rust layouts; every table matches its f64 CPU twin texel by texel; rendered views
//! match the CPU twin's render; every shipped preset renders finite, non-negative luminance;
//! the engine runs exactly the passes whose inputs changed.

mod common;

use atmoscope_eval::metrics::{DisplaySetup, compare};
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::colour::{linear_srgb_to_xyz, srgb_decode};
use atmoscope_model::methods::shared::{Lut, moving_sky, viewpoint};
use atmoscope_model::methods::{self, CannotDraw, Inputs, ModelInfo, SkyModel};
use atmoscope_model::scene::{
    FittedConstants, Method, Quality, Scene, SunSettings, ToneMap, WavelengthSet,
};
use atmoscope_render::methods::{
    DISPLAY_PASS, MOVING_SKY, MOVING_SKY_PASS, Repeat, SUN_ROUTE_PASS, SUN_ROUTE_TABLE, gpu_method,
    gpu_methods,
};
use atmoscope_render::passes::shader_source;
use atmoscope_render::uniforms::{Batch, Globals};
use atmoscope_render::{Engine, EngineError, FrameStats, GpuContext, MovingSkyStep, View};
use common::context;
use std::time::Duration;

/// The scene with `model`'s method.
fn with(model: &ModelInfo, scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.render.method = model.method;
    // Every branch of an order loop has run by the fourth order; more only cost time here.
    s.render.scattering_orders = s.render.scattering_orders.min(4);
    // The GPU and its twin take the same steps at every quality, and the fewest halve the
    // tests' time (the CPU twins' integrals, Bruneton's above all, took most of it).
    s.render.quality = Quality::Low;
    s
}

/// Whether the scene's model refuses the scene (`a_refused_view_is_an_error_with_its_reason`
/// checks the refusals themselves).
fn refused(scene: &Scene) -> bool {
    methods::info(scene.render.method)
        .cannot_draw(scene)
        .is_some()
}

#[test]
fn every_shader_parses_validates_and_matches_the_rust_layouts() {
    for (method, pass) in
        gpu_methods().flat_map(|m| m.passes.iter().chain([&DISPLAY_PASS]).map(move |p| (m, p)))
    {
        let file = format!("{:?} {}", method.method, pass.name);
        let src = shader_source(method, pass, 64);
        let module = naga::front::wgsl::parse_str(&src)
            .unwrap_or_else(|e| panic!("{file}: {}", e.emit_to_string(&src)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{file}: {}", e.emit_to_string(&src)));
        // A table the pass only reads is bound read-only, so that no barrier waits between
        // passes that read the same tables; what it writes stays writable.
        for (_, var) in module.global_variables.iter() {
            let (Some(name), naga::AddressSpace::Storage { access }) = (&var.name, var.space)
            else {
                continue;
            };
            let Some(table) = name.strip_suffix("_lut") else {
                continue;
            };
            let id = table.replace('_', "-");
            assert_eq!(
                access.contains(naga::StorageAccess::STORE),
                pass.writes.iter().any(|w| w.id() == id),
                "{file}: access of {name}"
            );
        }
        for (name, size) in [
            ("Globals", std::mem::size_of::<Globals>()),
            ("Batch", std::mem::size_of::<Batch>()),
        ] {
            let (_, ty) = module
                .types
                .iter()
                .find(|(_, t)| t.name.as_deref() == Some(name))
                .unwrap_or_else(|| panic!("{file}: no struct {name}"));
            let naga::TypeInner::Struct { span, .. } = ty.inner else {
                panic!("{name} is not a struct");
            };
            assert_eq!(span as usize, size, "{file}: size of {name}");
        }
    }
}

/// Every pass, at every texel-group size the engine allows (`Engine::set_texel_group_size`:
/// powers of two to 256, and the march split that follows), validates, uses at most the 16 KiB
/// of workgroup memory every Vulkan device offers (the engine asks for no more), and has at
/// most 256 invocations to a workgroup.
#[test]
fn every_pass_fits_the_workgroup_limits_at_every_group_size() {
    let limits = wgpu::Limits::default();
    for n in (0..=8).map(|k| 1u32 << k) {
        for (method, pass) in
            gpu_methods().flat_map(|m| m.passes.iter().chain([&DISPLAY_PASS]).map(move |p| (m, p)))
        {
            let file = format!("{:?} {}", method.method, pass.name);
            let src = shader_source(method, pass, n);
            let module = naga::front::wgsl::parse_str(&src)
                .unwrap_or_else(|e| panic!("{file}: {}", e.emit_to_string(&src)));
            let info = naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::default(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{file} at {n}: {}", e.emit_to_string(&src)));
            for (i, entry) in module.entry_points.iter().enumerate() {
                let used = info.get_entry_point(i);
                let bytes: u32 = module
                    .global_variables
                    .iter()
                    .filter(|(h, v)| {
                        v.space == naga::AddressSpace::WorkGroup && !used[*h].is_empty()
                    })
                    .map(|(_, v)| module.types[v.ty].inner.size(module.to_ctx()))
                    .sum();
                assert!(
                    bytes <= limits.max_compute_workgroup_storage_size,
                    "{file} at {n}: {bytes} bytes of workgroup memory"
                );
                let invocations: u32 = entry.workgroup_size.iter().product();
                assert!(
                    invocations <= limits.max_compute_invocations_per_workgroup,
                    "{file} at {n}: {invocations} invocations"
                );
            }
        }
    }
}

/// Worst |gpu − cpu| / (|cpu| + floor·max|cpu|) over every texel and lane.
fn worst_error(gpu: &[[f32; 4]], cpu: &Lut, floor: f64) -> (f64, usize) {
    assert_eq!(gpu.len(), cpu.data.len(), "table sizes differ");
    let max = cpu
        .data
        .iter()
        .flatten()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut worst = (0.0, 0);
    for (i, (g, c)) in gpu.iter().zip(&cpu.data).enumerate() {
        for lane in 0..4 {
            assert!(g[lane].is_finite(), "texel {i} lane {lane} is {}", g[lane]);
            let e = (f64::from(g[lane]) - c[lane]).abs() / (c[lane].abs() + floor * max);
            if e > worst.0 {
                worst = (e, i);
            }
        }
    }
    worst
}

/// Peak signal-to-noise ratio of the GPU table against the CPU one (the peak being the CPU
/// table's largest value), dB.
fn psnr_db(gpu: &[[f32; 4]], cpu: &Lut) -> f64 {
    let (mut peak, mut sum) = (0.0_f64, 0.0);
    for (g, c) in gpu.iter().zip(&cpu.data) {
        for lane in 0..4 {
            peak = peak.max(c[lane].abs());
            sum += (f64::from(g[lane]) - c[lane]).powi(2);
        }
    }
    let mse = sum / (4 * cpu.data.len()) as f64;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (peak * peak / mse).log10()
    }
}

fn twilight_spectral8() -> Scene {
    let mut s = Scene::default();
    s.sun = SunSettings::Angles {
        elevation_deg: -3.0,
        azimuth_deg: 250.0,
    };
    s.camera.altitude_m = 2000.0;
    s.render.wavelengths = WavelengthSet::SpectralN(8);
    s.render.quality = Quality::Low;
    s
}

#[test]
fn every_lookup_table_matches_its_cpu_twin() {
    let Some(gpu) = context() else { return };
    let mut failures = Vec::new();
    for model in methods::realtime() {
        for scene in [Scene::default(), twilight_spectral8()] {
            let scene = with(model, &scene);
            if refused(&scene) {
                continue;
            }
            let mut engine = Engine::new(&gpu.device, &gpu.queue);
            let view = View::new(Projection::Perspective, 16, 16);
            engine.try_render(&scene, &view).expect("a real-time model");
            let radius = scene.atmosphere.planet_radius_km * 1000.0;
            let camera = Camera::new(&scene.camera, radius, view.projection);
            let cpu = methods::build(&scene, &camera).expect("a real-time model");
            // A still frame leaves the moving sky unbuilt: the next test holds it to its twin.
            for table in model.tables.iter().filter(|t| !t.motion_only()) {
                let gpu_lut = engine.read_table(table.id).expect("read-back");
                let cpu_lut = cpu.table(table.id).expect("the twin's table");
                let (e, texel) = worst_error(&gpu_lut, cpu_lut, 1e-3);
                let psnr = psnr_db(&gpu_lut, cpu_lut);
                eprintln!(
                    "{} {}: worst relative error {e:.2e} at texel {texel} (GPU {:?}, CPU {:?}), PSNR {psnr:.1} dB",
                    model.id, table.id, gpu_lut[texel], cpu_lut.data[texel]
                );
                if e >= 1e-3 && psnr < 47.0 {
                    failures.push(format!(
                        "{} {} differs from its twin by {e:.2e} at texel {texel}, PSNR {psnr:.1} dB",
                        model.id, table.id
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A march per pixel draws its views in motion (frames in tiles) from the moving sky, its own
/// radiance at the sky-view grid's directions: built by the first such frame, it matches its
/// f64 twin texel by texel; it is not built again while only the camera turns, and it is again
/// when the sun moves; a still frame marches every pixel and builds nothing, nor does the frame
/// that swaps in a rebuild done in slices.
#[test]
fn the_moving_sky_matches_its_cpu_twin_and_is_built_only_in_motion() {
    let Some(gpu) = context() else { return };
    let mut failures = Vec::new();
    for method in [
        Method::Nishita,
        Method::TrapezoidMs,
        Method::SchulerMs,
        Method::GalajSpline,
    ] {
        for scene in [Scene::default(), twilight_spectral8()] {
            let mut scene = scene.clone();
            scene.render.method = method;
            if refused(&scene) {
                continue;
            }
            let name = format!("{method:?}, sun {:.0}°", scene.sun.angles().elevation_deg);
            let view = View::new(Projection::Perspective, 32, 18);
            let mut engine = Engine::new(&gpu.device, &gpu.queue);
            let still = engine.render(&scene, &view).clone();
            assert!(!still.ran(MOVING_SKY_PASS), "{name}: a still frame marches");
            engine.set_sky_tile(4);
            let mut turned = scene.clone();
            turned.camera.heading_deg += 10.0;
            let moving = engine.render(&turned, &view).clone();
            assert!(
                moving.ran(MOVING_SKY_PASS),
                "{name}: the first frame in motion builds it"
            );
            turned.camera.heading_deg += 10.0;
            let turning = engine.render(&turned, &view).clone();
            assert_eq!(
                turning.run,
                vec!["sky"],
                "{name}: turning, nothing but the sky"
            );

            let radius = scene.atmosphere.planet_radius_km * 1000.0;
            let camera = Camera::new(&turned.camera, radius, view.projection);
            let cpu = methods::build(&turned, &camera).expect("a real-time model");
            let vp = viewpoint(&turned, &camera);
            // A nested march builds its moving sky from its way to the sun tabulated.
            let nested = methods::info(method).table(SUN_ROUTE_TABLE.id()).map(|_| {
                cpu.table(SUN_ROUTE_TABLE.id())
                    .expect("the twin's way to the sun")
            });
            assert_eq!(
                nested.is_some(),
                method != Method::SchulerMs,
                "{name}: only the nested marches tabulate their way to the sun"
            );
            let cpu_lut = moving_sky::compute_lut(&*cpu, vp);
            for (id, cpu_lut) in [
                (MOVING_SKY.id(), Some(&cpu_lut)),
                (SUN_ROUTE_TABLE.id(), nested),
            ] {
                let Some(cpu_lut) = cpu_lut else { continue };
                let gpu_lut = engine.read_table(id).expect("read-back");
                let (e, texel) = worst_error(&gpu_lut, cpu_lut, 1e-3);
                let psnr = psnr_db(&gpu_lut, cpu_lut);
                eprintln!(
                    "{name}: {id}, worst relative error {e:.2e} at texel {texel}, PSNR {psnr:.1} dB"
                );
                if e >= 1e-3 && psnr < 47.0 {
                    failures.push(format!(
                        "{name}: {id} differs from its twin by {e:.2e} at texel {texel}, PSNR {psnr:.1} dB"
                    ));
                }
            }

            turned.sun = SunSettings::Angles {
                elevation_deg: scene.sun.angles().elevation_deg + 1.0,
                azimuth_deg: scene.sun.angles().azimuth_deg,
            };
            let sun_moved = engine.render(&turned, &view).clone();
            assert!(sun_moved.ran(MOVING_SKY_PASS), "{name}: the sun moved");

            // A rebuild in slices draws its view at full resolution; the frame that swaps it in
            // changes nothing, so it builds no moving sky, and the frame after it runs nothing.
            engine.set_rebuild_slices(Some(std::time::Duration::ZERO));
            turned.atmosphere.aerosol.aod550 = 0.3;
            let swapped = loop {
                let stats = engine.render(&turned, &view).clone();
                engine.wait();
                if !engine.rebuilding() {
                    break stats;
                }
            };
            assert!(swapped.rebuild_done, "{name}: the rebuild ends");
            assert!(
                !swapped.ran(MOVING_SKY_PASS),
                "{name}: the frame that swaps in a rebuild ran {:?}",
                swapped.run
            );
            let after = engine.render(&turned, &view).run.clone();
            assert!(after.is_empty(), "{name}: after the rebuild, ran {after:?}");
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Where the engine slices its work (the explorer), a sun move in motion builds the next moving
/// sky in slices while the sky pass reads the last complete one. Once every slice has finished
/// it is copied over that one, equal to the moving sky built whole for the sun of the frame that
/// started it; a sun move while it is being built starts another after it. A rebuild in slices
/// builds the moving sky with its tables, so the first frame in motion after it builds none;
/// with slicing turned off, a moving sky being built is dropped and built whole.
#[test]
fn a_moving_sky_built_in_slices_is_the_one_built_whole() {
    let Some(gpu) = context() else { return };
    let mut scene = Scene::default();
    scene.render.method = Method::Nishita;
    let view = View::new(Projection::Perspective, 32, 18);
    let elevation_deg = scene.sun.angles().elevation_deg;
    let sun_at = |scene: &mut Scene, elevation_deg: f64| {
        scene.sun = SunSettings::Angles {
            elevation_deg,
            azimuth_deg: scene.sun.angles().azimuth_deg,
        };
    };
    // The moving sky of `scene`, built whole by an engine that does not slice: its first frame,
    // which changes everything, is one in motion.
    let built_whole = |scene: &Scene| {
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.set_sky_tile(4);
        assert!(engine.render(scene, &view).ran(MOVING_SKY_PASS));
        engine.read_table(MOVING_SKY.id()).expect("read-back")
    };
    // The same dispatches over the same inputs: equal but for a table of another sun (a
    // degree moves texels by percents).
    let same = |a: &[[f32; 4]], b: &[[f32; 4]]| {
        let max = b.iter().flatten().fold(0.0_f32, |m, v| m.max(v.abs()));
        a.len() == b.len()
            && a.iter()
                .flatten()
                .zip(b.iter().flatten())
                .all(|(x, y)| (x - y).abs() <= 1e-6 * max)
    };

    // The first atmosphere built whole (a first build in slices would build its moving sky
    // too), then slicing on.
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    engine.set_sky_tile(4);
    let mut frame = scene.clone();
    let first = engine.render(&frame, &view).clone();
    engine.set_rebuild_slices(Some(Duration::ZERO));
    assert!(
        first.ran(MOVING_SKY_PASS),
        "none is complete yet: the first frame in motion builds it whole"
    );
    let mut on_screen = engine.read_table(MOVING_SKY.id()).expect("read-back");
    assert!(same(&on_screen, &built_whole(&frame)));

    // The sun moves in the first two frames, the camera turns in the first three, then the
    // view holds still: the moving sky of the second sun, left stale while the first was
    // being built, is built in still frames.
    let mut published = Vec::new();
    let mut slices = 0;
    for k in 0..500 {
        if k < 3 {
            frame.camera.heading_deg += 1.0;
        }
        if k < 2 {
            sun_at(&mut frame, elevation_deg + 1.0 + k as f64);
        }
        let stats = engine.render(&frame, &view).clone();
        engine.wait();
        assert!(
            !stats.ran(MOVING_SKY_PASS),
            "frame {k}: a complete moving sky is on screen, the next is built in slices"
        );
        assert_eq!(stats.sky_tile, if k < 3 { 4 } else { 1 }, "frame {k}");
        let table = engine.read_table(MOVING_SKY.id()).expect("read-back");
        match stats.moving_sky {
            MovingSkyStep::Published => {
                published.push(k);
                let sun = elevation_deg + published.len() as f64;
                assert!(
                    same(
                        &table,
                        &built_whole(&{
                            let mut s = frame.clone();
                            sun_at(&mut s, sun);
                            s
                        })
                    ),
                    "frame {k}: the moving sky published is the one of the sun at {sun}°"
                );
                on_screen = table;
                if published.len() == 2 {
                    break;
                }
            }
            step => {
                assert!(
                    same(&table, &on_screen),
                    "frame {k} ({step:?}): the sky pass reads the last complete moving sky"
                );
                slices += usize::from(step == MovingSkyStep::Slice);
            }
        }
    }
    assert_eq!(published.len(), 2, "two moving skies built in slices");
    // A zero target cuts slices in half rows of workgroups: two a row of each layer.
    let [w, h, _] = moving_sky::TABLE.size;
    let layers = on_screen.len() / (w * h) as usize;
    let rows = h.div_ceil(atmoscope_render::prelude::WORKGROUP_SIZE) as usize;
    assert_eq!(slices, 2 * 2 * rows * layers, "slices of the two");
    assert!(!engine.building_moving_sky());
    let stats = engine.render(&frame, &view).clone();
    assert!(
        !stats.ran(MOVING_SKY_PASS) && stats.moving_sky == MovingSkyStep::None,
        "still, the moving sky up to date: {:?}, {:?}",
        stats.run,
        stats.moving_sky
    );

    // A rebuild in slices builds the moving sky with its tables.
    frame.atmosphere.aerosol.aod550 = 0.3;
    while engine.render(&frame, &view).rebuild.is_some() {
        engine.wait();
    }
    engine.wait();
    frame.camera.heading_deg += 1.0;
    let after = engine.render(&frame, &view).clone();
    assert!(
        !after.ran(MOVING_SKY_PASS) && after.moving_sky == MovingSkyStep::None,
        "the rebuild built it: {:?}, {:?}",
        after.run,
        after.moving_sky
    );
    let table = engine.read_table(MOVING_SKY.id()).expect("read-back");
    assert!(
        same(&table, &built_whole(&frame)),
        "the rebuild's moving sky"
    );

    // Slicing turned off while one is built: the next frame in motion builds it whole.
    sun_at(&mut frame, elevation_deg - 1.0);
    frame.camera.heading_deg += 1.0;
    assert_eq!(
        engine.render(&frame, &view).moving_sky,
        MovingSkyStep::Slice
    );
    engine.set_rebuild_slices(None);
    assert!(!engine.building_moving_sky());
    frame.camera.heading_deg += 1.0;
    assert!(engine.render(&frame, &view).ran(MOVING_SKY_PASS));
    let table = engine.read_table(MOVING_SKY.id()).expect("read-back");
    assert!(same(&table, &built_whole(&frame)));
}

/// The engine's last rendered view as linear sRGB.
/// How many of the display's bytes may be a step off the f64 twin: one in 20. Lavapipe's f32
/// puts under 2 % a step off, an H100's faster exp and pow 3.3 % (127 of 3 888); never 2 steps.
const DIFFER_AT_MOST_ONE_IN: usize = 20;

fn radiance_image(engine: &Engine) -> Vec<[f64; 3]> {
    engine
        .read_radiance()
        .expect("read-back")
        .iter()
        .map(|p| [p[0], p[1], p[2]].map(f64::from))
        .collect()
}

/// The passes a still frame that draws everything runs: all but the display pass, whose image
/// the sky pass draws too, and the moving sky with the sun-route table it reads, which frames in
/// motion alone read.
fn every_still_pass(stats: &FrameStats) -> Vec<&'static str> {
    stats
        .passes
        .iter()
        .copied()
        .filter(|&p| ![DISPLAY_PASS.name, MOVING_SKY_PASS, SUN_ROUTE_PASS].contains(&p))
        .collect()
}

/// The displayed image as linear colour (its sRGB bytes decoded).
fn displayed_image(engine: &Engine) -> Vec<[f64; 3]> {
    engine
        .read_display()
        .expect("read-back")
        .chunks_exact(4)
        .map(|p| std::array::from_fn(|c| srgb_decode(f64::from(p[c]) / 255.0)))
        .collect()
}

fn luminance(rgb: [f64; 3]) -> f64 {
    linear_srgb_to_xyz(rgb).y
}

#[test]
fn rendered_views_match_the_cpu_twin() {
    let Some(gpu) = context() else { return };
    let mut ground = Scene::default();
    ground.camera.pitch_deg = -4.0;
    ground.camera.heading_deg = 150.0;
    let mut space = Scene::default();
    space.camera.altitude_m = 400_000.0;
    space.camera.pitch_deg = -70.0;
    space.camera.fov_deg = 120.0;
    let mut plane = Scene::default();
    plane.camera.altitude_m = 10_000.0;
    plane.camera.pitch_deg = -20.0;
    let cases = [
        (
            "ground, perspective",
            ground,
            Projection::Perspective,
            48,
            32,
        ),
        ("fisheye", Scene::default(), Projection::Fisheye, 40, 40),
        ("panorama", Scene::default(), Projection::Panorama, 64, 32),
        (
            "twilight fisheye, Spectral8",
            twilight_spectral8(),
            Projection::Fisheye,
            40,
            40,
        ),
        (
            "10 km, looking down",
            plane,
            Projection::Perspective,
            48,
            32,
        ),
        ("from 400 km", space, Projection::Perspective, 48, 32),
    ];
    // One engine per model draws its cases in turn, rebuilding what each change needs; and a
    // twin whose tables hold no viewpoint (Haber's among them) is built once per atmosphere, as
    // the engine's tables are.
    for model in methods::realtime() {
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        let mut twin: Option<(Scene, Box<dyn SkyModel>)> = None;
        for (name, scene, projection, w, h) in &cases {
            let scene = with(model, scene);
            if refused(&scene) {
                continue;
            }
            let name = format!("{} {name}", model.id);
            let camera = Camera::new(
                &scene.camera,
                scene.atmosphere.planet_radius_km * 1000.0,
                *projection,
            );
            let atmosphere = Scene {
                camera: Default::default(),
                ..scene.clone()
            };
            let reusable =
                !model.reads_viewpoint() && twin.as_ref().is_some_and(|(a, _)| *a == atmosphere);
            if !reusable {
                let built = methods::build(&scene, &camera).expect("a real-time model");
                twin = Some((atmosphere, built));
            }
            let (_, built) = twin.as_ref().expect("built above");
            engine.render(&scene, &View::new(*projection, *w, *h));
            let gpu_image = radiance_image(&engine);
            let cpu_image = methods::render_with(built.as_ref(), &scene, &camera, *w, *h);
            assert_images_match(&name, &gpu_image, &cpu_image, *w, *h);
        }
    }
}

/// The polarisation the views show against the CPU twin's, for a model with tables of multiple
/// scattering on the dome and an analytic fit in perspective (the shader is the same for
/// every model; Bruneton's and Nishita's agreed as well when written): the Polarisation mode's
/// Stokes vectors (degree of polarisation within 0.01, angle within 1° where the light is over
/// 5 % polarised, for 99 % of the pixels), and the view through the polarising filter at 30°
/// (the colour twin test's bounds). The filter passes what Malus's law gives of the view's own
/// Stokes vector, ½(I + Q·cos 2ψ + U·sin 2ψ) in luminance, within 0.02 of the light.
#[test]
fn polarisation_views_match_the_cpu_twin() {
    let Some(gpu) = context() else { return };
    // Looking east, 90° in azimuth from the sun in the south.
    let mut noon = Scene::default();
    noon.camera.pitch_deg = 30.0;
    noon.camera.heading_deg = 90.0;
    for (model, projection, w, h) in [
        (Method::Hillaire, Projection::Fisheye, 24, 24),
        (Method::Preetham, Projection::Perspective, 40, 24),
    ] {
        let scene = with(methods::info(model), &noon);
        let name = format!("{model:?} {projection:?}");
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        let view = View {
            mode: atmoscope_render::DisplayMode::Polarisation,
            ..View::new(projection, w, h)
        };
        engine.render(&scene, &view);
        let gpu_stokes = radiance_image(&engine);
        let cpu_stokes = methods::render_stokes(&scene, projection, w, h).expect("a twin");
        let degree = |s: [f64; 3]| {
            if s[0] > 0.0 {
                s[1].hypot(s[2]) / s[0]
            } else {
                0.0
            }
        };
        let angle = |s: [f64; 3]| 0.5 * s[2].atan2(s[1]).to_degrees();
        let mut off = 0;
        let mut polarised = 0;
        for (g, c) in gpu_stokes.iter().zip(&cpu_stokes) {
            let turn = (angle(*g) - angle(*c)).rem_euclid(180.0);
            let far = (degree(*g) - degree(*c)).abs() > 0.01
                || (degree(*c) > 0.05 && turn.min(180.0 - turn) > 1.0);
            off += usize::from(far);
            polarised += usize::from(degree(*c) > 0.2);
        }
        eprintln!("{name}: {off} of {} pixels off", gpu_stokes.len());
        assert!(off * 100 <= gpu_stokes.len(), "{name}: {off} pixels off");
        assert!(
            polarised * 4 > gpu_stokes.len(),
            "{name}: {polarised} pixels over 20 %"
        );
        // The filter: the colour twin test's bounds, and what it lets through.
        let mut filtered = scene.clone();
        filtered.camera.polariser_deg = Some(30.0);
        let through =
            assert_engine_matches_the_twin(&mut engine, &name, &filtered, projection, w, h);
        engine.render(&scene, &View::new(projection, w, h));
        let open = radiance_image(&engine);
        let psi = 2.0 * 30f64.to_radians();
        for ((t, o), s) in through.iter().zip(&open).zip(&gpu_stokes) {
            let (lt, lo) = (luminance(*t), luminance(*o));
            if lo > 0.0 && s[0] > 0.0 {
                let ratio = lt / lo;
                let malus = 0.5 * (1.0 + (s[1] * psi.cos() + s[2] * psi.sin()) / s[0]);
                assert!(
                    (ratio - malus).abs() < 0.02,
                    "{name}: {ratio} through the filter, Malus's law {malus} (degree {})",
                    degree(*s)
                );
            }
        }
    }
}

/// The GPU's render of `scene` against the CPU twin's: ΔE2000 mean under 0.3 and at most 1 %
/// of the pixels off by more than 1 % in luminance. Returns the GPU's radiance image.
fn assert_render_matches_the_twin(
    gpu: &GpuContext,
    name: &str,
    scene: &Scene,
    projection: Projection,
    w: u32,
    h: u32,
) -> Vec<[f64; 3]> {
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    assert_engine_matches_the_twin(&mut engine, name, scene, projection, w, h)
}

/// [`assert_render_matches_the_twin`] with an engine that may have drawn other scenes before.
fn assert_engine_matches_the_twin(
    engine: &mut Engine,
    name: &str,
    scene: &Scene,
    projection: Projection,
    w: u32,
    h: u32,
) -> Vec<[f64; 3]> {
    engine.render(scene, &View::new(projection, w, h));
    let gpu_image = radiance_image(engine);
    let cpu_image = methods::render(scene, projection, w, h).expect("a real-time model");
    assert_images_match(name, &gpu_image, &cpu_image, w, h);
    gpu_image
}

/// The GPU's image within the twin's: a mean ΔE2000 under 0.3 and at most 1 % of the pixels
/// off by more than 1 % in luminance.
fn assert_images_match(name: &str, gpu_image: &[[f64; 3]], cpu_image: &[[f64; 3]], w: u32, h: u32) {
    let (c, _) = compare(gpu_image, cpu_image, w, h, DisplaySetup::default());
    let off = gpu_image
        .iter()
        .zip(cpu_image)
        .filter(|(g, c)| {
            let (lg, lc) = (luminance(**g), luminance(**c));
            (lg - lc).abs() > 0.01 * lc.abs() + 1e-6
        })
        .count();
    eprintln!(
        "{name}: ΔE2000 mean {:.3}, p95 {:.3}; {off} of {} pixels off by > 1 % in luminance",
        c.delta_e2000_mean,
        c.delta_e2000_p95,
        gpu_image.len()
    );
    assert!(
        c.delta_e2000_mean < 0.3,
        "{name}: ΔE2000 mean {}",
        c.delta_e2000_mean
    );
    assert!(
        off * 100 <= gpu_image.len(),
        "{name}: {off} pixels differ by more than 1 % in luminance"
    );
}

/// Bruneton from space with the sun past its tables' 102° where the rays enter the air
/// (Leenman's orbit at dawn: the night side, the terminator and the limb beyond it): the
/// look-up from where each ray comes back to 102°, and the dark beyond, as the twin has them.
#[test]
fn bruneton_past_its_tables_edge_matches_the_cpu_twin() {
    let Some(gpu) = context() else { return };
    let view = atmoscope_model::views::find("orbit-dawn").expect("a suite view");
    let bruneton = methods::info(Method::Bruneton);
    let scene = with(bruneton, &view.apply(&Scene::default()));
    assert!(!refused(&scene));
    let image = assert_render_matches_the_twin(
        &gpu,
        "bruneton orbit-dawn",
        &scene,
        view.projection,
        48,
        27,
    );
    let dark = image.iter().filter(|&&p| luminance(p) == 0.0).count();
    let lit = image.iter().filter(|&&p| luminance(p) > 0.0).count();
    assert!(
        dark > 0 && lit > 0,
        "the night side dark ({dark} pixels), the limb lit ({lit})"
    );
}

/// Hosek–Wilkie's coefficients are blended on the CPU for the sun at the camera: one engine
/// follows the sun as it moves (the rows are uploaded again), and both the sRGB fit (RGB3) and
/// the spectral bands (SpectralN, some lanes past 720 nm) match the twin.
#[test]
fn hosek_wilkie_follows_the_sun_in_every_wavelength_set() {
    let Some(gpu) = context() else { return };
    let model = methods::info(Method::HosekWilkie);
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    for (set, elevation_deg) in [
        (WavelengthSet::Rgb3, 30.0),
        (WavelengthSet::Rgb3, 70.0),
        (WavelengthSet::SpectralN(16), 8.0),
    ] {
        let mut scene = with(model, &Scene::default());
        scene.render.wavelengths = set;
        scene.camera.pitch_deg = 0.0;
        scene.sun = SunSettings::Angles {
            elevation_deg,
            azimuth_deg: 180.0,
        };
        let name = format!("hosek-wilkie {set:?}, sun {elevation_deg}°");
        let image =
            assert_engine_matches_the_twin(&mut engine, &name, &scene, Projection::Fisheye, 32, 32);
        assert!(image.iter().any(|p| luminance(*p) > 0.0), "{name}: a sky");
    }
}

#[test]
fn every_shipped_preset_renders_finite_non_negative_luminance() {
    let Some(gpu) = context() else { return };
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../presets");
    let mut presets: Vec<_> = std::fs::read_dir(&dir)
        .expect("presets directory")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    presets.sort();
    assert!(
        presets.len() >= 10,
        "only {} presets found in {}",
        presets.len(),
        dir.display()
    );
    let scenes: Vec<Scene> = presets
        .iter()
        .map(|p| Scene::load(p).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    // Each preset with its own model, and each model with one preset in turn (the first from
    // its turn on that it draws): rebuilding every model for every preset took a quarter of CI.
    let mut jobs: Vec<(usize, &ModelInfo)> = scenes
        .iter()
        .enumerate()
        .map(|(i, s)| (i, methods::info(s.render.method)))
        .filter(|(i, m)| m.is_realtime() && !refused(&with(m, &scenes[*i])))
        .collect();
    for (j, model) in methods::realtime().enumerate() {
        let n = scenes.len();
        let turn = (0..n)
            .map(|k| (j + k) % n)
            .find(|&i| !refused(&with(model, &scenes[i])))
            .unwrap_or_else(|| panic!("{} draws no preset", model.id));
        if !jobs
            .iter()
            .any(|(i, m)| *i == turn && m.method == model.method)
        {
            jobs.push((turn, model));
        }
    }
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    for (i, model) in jobs {
        let path = &presets[i];
        for projection in [Projection::Perspective, Projection::Fisheye] {
            let scene = with(model, &scenes[i]);
            engine.render(&scene, &View::new(projection, 24, 16));
            let image = engine.read_radiance().expect("read-back");
            for (i, p) in image.iter().enumerate() {
                let rgb = [p[0], p[1], p[2]].map(f64::from);
                assert!(
                    rgb.iter().all(|c| c.is_finite()) && luminance(rgb) >= 0.0,
                    "{} {}: pixel {i} is {p:?}",
                    model.id,
                    path.display()
                );
            }
            // From space the fisheye (the sky dome above the camera) is black by design, and
            // so is the baseline's sky before sunrise.
            if projection == Projection::Perspective && !model.baseline {
                assert!(
                    image.iter().any(|p| p[1] > 0.0),
                    "{} {}: a black image",
                    model.id,
                    path.display()
                );
            }
        }
    }
}

/// A model that refuses a view (Preetham from a plane, from space, or under a set sun) makes the
/// frame an error that names the model and the reason, on the GPU as in the CPU twin; the
/// engine then draws the next view it accepts as usual.
#[test]
fn a_refused_view_is_an_error_with_its_reason() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let refusing: Vec<_> = methods::realtime().filter(|m| m.domain.refuses).collect();
    assert!(
        !refusing.is_empty(),
        "preetham refuses views off the ground"
    );
    for model in refusing {
        let mut scene = with(model, &Scene::default());
        scene.camera.altitude_m = 400_000.0;
        match engine.try_render(&scene, &view) {
            Err(EngineError::CannotDraw(CannotDraw::Refused(label, why))) => {
                assert_eq!(label, model.label);
                assert!(why.contains("above this model's domain"), "{why}");
            }
            other => panic!(
                "{}: expected a refusal, got {:?}",
                model.id,
                other.map(|_| ())
            ),
        }
        assert!(methods::render(&scene, Projection::Perspective, 8, 8).is_err());
        scene.camera.altitude_m = 1.0;
        engine
            .try_render(&scene, &view)
            .expect("a ground view draws");
        let image = engine.read_radiance().expect("read-back");
        assert!(
            image.iter().any(|p| p[1] > 0.0),
            "{}: a black sky",
            model.id
        );
    }
}

/// Hillaire's passes, named: what each change reruns.
#[test]
fn each_frame_runs_only_the_passes_whose_inputs_changed() {
    let Some(gpu) = context() else { return };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let mut scene = Scene::default();
    let mut view = View::new(Projection::Perspective, 32, 18);
    let run =
        |engine: &mut Engine, scene: &Scene, view: &View| engine.render(scene, view).run.clone();
    let all = vec![
        "transmittance",
        "multiple-scattering",
        "ground-irradiance",
        "sky-view",
        "aerial-perspective",
        "sky",
    ];
    // The sky pass draws the display image too: the display pass waits for a frame that
    // changes the display alone.
    assert_eq!(run(&mut engine, &scene, &view), all.clone(), "first frame");
    let stats = engine.render(&scene, &view).clone();
    assert!(
        stats.run.is_empty(),
        "an unchanged frame ran {:?}",
        stats.run
    );
    assert_eq!(stats.skipped.len(), all.len() + 1);

    scene.camera.heading_deg += 40.0;
    scene.camera.pitch_deg += 10.0;
    scene.camera.fov_deg = 90.0;
    assert_eq!(run(&mut engine, &scene, &view), vec!["sky"], "turning");
    view.projection = Projection::Fisheye;
    assert_eq!(run(&mut engine, &scene, &view), vec!["sky"], "projection");

    scene.display.exposure_ev += 1.0;
    assert_eq!(run(&mut engine, &scene, &view), vec!["display"], "exposure");
    view = view.luminance();
    assert_eq!(
        run(&mut engine, &scene, &view),
        vec!["display"],
        "luminance map"
    );

    let SunSettings::Angles {
        elevation_deg,
        azimuth_deg,
    } = scene.sun
    else {
        panic!("the default scene gives the sun by angles");
    };
    scene.sun = SunSettings::Angles {
        elevation_deg,
        azimuth_deg: azimuth_deg + 20.0,
    };
    assert_eq!(run(&mut engine, &scene, &view), vec!["sky"], "sun azimuth");
    scene.sun = SunSettings::Angles {
        elevation_deg: elevation_deg - 10.0,
        azimuth_deg,
    };
    // The fisheye shows the sky above the horizon: the tables only the ground's pixels read
    // (ground irradiance, aerial perspective) wait until a view shows the ground.
    let moved = run(&mut engine, &scene, &view);
    assert_eq!(
        moved,
        vec!["sky-view", "sky"],
        "sun elevation, no ground in view"
    );
    scene.camera.altitude_m = 5000.0;
    assert_eq!(run(&mut engine, &scene, &view), moved, "altitude");

    view.width = 40;
    assert_eq!(run(&mut engine, &scene, &view), vec!["sky"], "size");

    let without_ground: Vec<_> = all
        .iter()
        .copied()
        .filter(|p| !["ground-irradiance", "aerial-perspective"].contains(p))
        .collect();
    scene.atmosphere.ground_albedo = 0.8;
    assert_eq!(run(&mut engine, &scene, &view), without_ground, "albedo");
    view.projection = Projection::Perspective;
    scene.camera.pitch_deg = -10.0;
    assert_eq!(
        run(&mut engine, &scene, &view),
        vec!["ground-irradiance", "aerial-perspective", "sky"],
        "the ground comes into view"
    );
    scene.render.wavelengths = WavelengthSet::Rgb3;
    assert_eq!(
        run(&mut engine, &scene, &view),
        all.clone(),
        "wavelength set"
    );
    assert!(engine.render(&scene, &view).run.is_empty());
}

/// A sun placed by date moves through the day, and its light through the year, without a
/// table rebuilt: the tables hold sunlight at 1 AU and the sky pass scales the view to the
/// date's Earth–Sun distance. The view drawn so is the one drawn afresh and the twin's, and the
/// same sun given by angles (at 1 AU) is 1/d² as bright.
#[test]
fn a_sun_placed_by_date_moves_without_rebuilding_the_tables() {
    let Some(gpu) = context() else { return };
    let mut scene = Scene::default();
    let view = View::new(Projection::Fisheye, 24, 24);
    let at = |hour: f64| SunSettings::Date {
        time: atmoscope_model::sun_position::DateTime {
            year: 2026,
            month: 1,
            day: 4,
            hour,
            utc_offset_h: 1.0,
        },
        latitude_deg: 47.4,
        longitude_deg: 8.5,
    };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    scene.sun = at(10.0);
    engine.render(&scene, &view);
    scene.sun = at(11.0);
    // The fisheye shows no ground: of the tables, only the sky view follows the sun.
    assert_eq!(
        engine.render(&scene, &view).run,
        vec!["sky-view", "sky"],
        "an hour later"
    );
    let moved = radiance_image(&engine);
    let afresh = assert_render_matches_the_twin(&gpu, "by date", &scene, view.projection, 24, 24);
    let a = scene.sun.angles();
    scene.sun = SunSettings::Angles {
        elevation_deg: a.elevation_deg,
        azimuth_deg: a.azimuth_deg,
    };
    assert_eq!(engine.render(&scene, &view).run, vec!["sky"], "at 1 AU");
    let at_1_au = radiance_image(&engine);
    let scale = at(11.0).sunlight_scale();
    assert!(scale > 1.03, "{scale}");
    for ((m, f), u) in moved.iter().zip(&afresh).zip(&at_1_au) {
        for c in 0..3 {
            assert!((m[c] - f[c]).abs() <= 1e-6 * f[c].abs(), "{m:?} {f:?}");
            assert!(
                (m[c] - scale * u[c]).abs() <= 1e-5 * m[c].abs(),
                "{m:?} {u:?}"
            );
        }
    }
}

/// Where no table holds the ground albedo (Elek's, and the models without tables), a change of
/// it alone redraws the view with the tables on screen, in one frame and where the engine
/// builds in slices alike, and the view is the one drawn afresh.
#[test]
fn a_change_of_the_ground_albedo_alone_keeps_the_tables_that_do_not_hold_it() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    let mut with_tables = Vec::new();
    for model in methods::realtime().filter(|m| !m.tables_hold_the_albedo()) {
        let mut scene = with(model, &Scene::default());
        scene.camera.pitch_deg = -5.0;
        if refused(&scene) {
            continue;
        }
        let mut fresh = Engine::new(&gpu.device, &gpu.queue);
        let mut brighter = scene.clone();
        brighter.atmosphere.ground_albedo = 0.7;
        fresh.render(&brighter, &view);
        let afresh = radiance_image(&fresh);
        for slices in [None, Some(Duration::from_millis(20))] {
            // The first atmosphere on screen, built whole; then the albedo changes.
            let mut engine = Engine::new(&gpu.device, &gpu.queue);
            if !engine.render(&scene, &view).tables_run.is_empty() {
                with_tables.push(model.id);
            }
            engine.set_rebuild_slices(slices);
            let stats = engine.render(&brighter, &view).clone();
            let name = format!("{}, slices {slices:?}", model.id);
            assert!(
                stats.tables_run.is_empty(),
                "{name}: {:?}",
                stats.tables_run
            );
            assert!(
                stats.rebuild.is_none() && !stats.rebuild_done && stats.run.contains(&"sky"),
                "{name}"
            );
            for (m, f) in radiance_image(&engine).iter().zip(&afresh) {
                for c in 0..3 {
                    assert!(
                        (m[c] - f[c]).abs() <= 1e-6 * f[c].abs(),
                        "{name}: {m:?} {f:?}"
                    );
                }
            }
        }
    }
    assert!(with_tables.contains(&"elek"), "{with_tables:?}");
}

/// Where the engine slices its work (`Engine::set_rebuild_slices`), the still frame after frames
/// in tiles is drawn half a row of workgroups per frame (a zero target), the image in tiles on screen
/// meanwhile, and comes out as the still frame drawn whole.
#[test]
fn the_still_frame_after_tiles_in_slices_is_the_one_drawn_whole() {
    let Some(gpu) = context() else { return };
    let (w, h) = (96, 64);
    let view = View::new(Projection::Perspective, w, h);
    for method in [Method::Hillaire, Method::Nishita] {
        let mut scene = Scene::default();
        scene.render.method = method;
        scene.camera.pitch_deg = 5.0;
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.render(&scene, &view);
        let (exact, exact_shown) = (radiance_image(&engine), displayed_image(&engine));
        engine.set_sky_tile(4);
        engine.set_rebuild_slices(Some(std::time::Duration::ZERO));
        let mut turned = scene.clone();
        turned.camera.heading_deg += 1.0;
        engine.render(&turned, &view);
        assert_eq!(
            engine.render(&scene, &view).sky_tile,
            4,
            "{method:?}: in motion"
        );
        let (mut frames, mut slices) = (0, 0);
        while engine.settling() {
            assert!(
                matches!(engine.read_radiance(), Err(EngineError::InMotion)),
                "{method:?}: the radiance waits for the last slice"
            );
            let stats = engine.render(&scene, &view).clone();
            frames += 1;
            assert!(
                stats.run.iter().all(|p| *p == "sky"),
                "{method:?}: {:?}",
                stats.run
            );
            if stats.ran("sky") {
                slices += 1;
                assert_eq!(stats.sky_tile, 1, "{method:?}: every pixel");
            }
            assert!(frames < 10_000, "{method:?}: the still frame never ends");
        }
        // A zero target takes half a row of workgroups a slice: a row of a march per pixel
        // can take longer than a frame may.
        let rows = h.div_ceil(atmoscope_render::prelude::WORKGROUP_SIZE);
        assert!(
            slices >= 2 * rows,
            "{method:?}: {slices} slices over {frames} frames for {rows} rows of workgroups"
        );
        assert_eq!(radiance_image(&engine), exact, "{method:?}: radiance");
        assert_eq!(
            displayed_image(&engine),
            exact_shown,
            "{method:?}: as shown"
        );
        assert!(
            engine.render(&scene, &view).run.is_empty(),
            "{method:?}: then nothing"
        );
    }
}

/// A moving frame drawn in tiles (`Engine::set_sky_tile`) stays close to the frame drawn pixel
/// by pixel, sharp at the horizon, the sun and the fisheye's edge (their tiles are computed
/// exactly), and the first still frame after it redraws the view at full resolution.
#[test]
fn a_moving_frame_in_tiles_is_close_and_the_still_frame_after_it_exact() {
    let Some(gpu) = context() else { return };
    let mut horizon = Scene::default();
    horizon.camera.pitch_deg = 2.0;
    horizon.sun = SunSettings::Angles {
        elevation_deg: 4.0,
        azimuth_deg: 180.0,
    };
    horizon.camera.heading_deg = 170.0;
    // The glare's 1/θ² around the sun, in view, must not be smeared by the tiles either.
    horizon.display.glare = true;
    let mut space = Scene::default();
    space.camera.altitude_m = 400_000.0;
    space.camera.pitch_deg = -70.0;
    space.camera.fov_deg = 120.0;
    let cases = [
        (
            "horizon and low sun",
            horizon,
            Projection::Perspective,
            160,
            90,
        ),
        ("fisheye", Scene::default(), Projection::Fisheye, 96, 96),
        ("from 400 km", space, Projection::Perspective, 96, 64),
    ];
    for (name, scene, projection, w, h) in cases {
        for method in [
            Method::Hillaire,
            Method::Preetham,
            Method::Nishita,
            Method::Schuler,
        ] {
            let mut scene = scene.clone();
            scene.render.method = method;
            if refused(&scene) {
                continue;
            }
            let name = format!("{method:?}, {name}");
            let view = View::new(projection, w, h);
            let mut engine = Engine::new(&gpu.device, &gpu.queue);
            engine.render(&scene, &view);
            let exact = radiance_image(&engine);
            let exact_shown = displayed_image(&engine);
            let close = |what: &str, image: &[[f64; 3]], exact: &[[f64; 3]], setup| {
                let de = atmoscope_eval::metrics::delta_e2000_map(image, exact, setup);
                let mean = de.iter().sum::<f64>() / de.len() as f64;
                let max = de.iter().copied().fold(0.0, f64::max);
                eprintln!("{name}: {what} in tiles: ΔE2000 mean {mean:.3}, max {max:.3}");
                assert!(mean < 0.3, "{name}: {what}: ΔE2000 mean {mean}");
                assert!(
                    max < 2.0,
                    "{name}: {what}: ΔE2000 max {max} (a tile interpolated across an edge)"
                );
            };
            let as_shown = DisplaySetup {
                tone_map: ToneMap::Linear,
                ..DisplaySetup::default()
            };

            engine.set_sky_tile(4);
            // The same scene as a frame in motion: a frame whose inputs did not change is still.
            engine.invalidate_inputs(Inputs::CAMERA);
            let moving = engine.render(&scene, &view).clone();
            assert!(moving.ran("sky"), "{name}: the moving frame draws");
            assert_eq!(moving.sky_tile, 4, "{name}: the moving frame's tiles");
            assert!(
                engine.settling(),
                "{name}: a frame in tiles awaits its full resolution"
            );
            assert!(
                matches!(engine.read_radiance(), Err(EngineError::InMotion)),
                "{name}: no radiance in motion unless metered"
            );
            close(
                "displayed",
                &displayed_image(&engine),
                &exact_shown,
                as_shown,
            );

            let still = engine.render(&scene, &view).clone();
            eprintln!("{name}: moving {:?} still {:?}", moving.run, still.run);
            assert_eq!(still.run, vec!["sky"], "{name}: the still frame");
            assert_eq!(
                still.sky_tile, 1,
                "{name}: the still frame draws every pixel"
            );
            assert_eq!(
                radiance_image(&engine),
                exact,
                "{name}: full resolution again"
            );
            assert_eq!(displayed_image(&engine), exact_shown, "{name}: as shown");
            assert!(!engine.settling(), "{name}");
            let after = engine.render(&scene, &view).run.clone();
            assert!(after.is_empty(), "{name}: then nothing, ran {after:?}");

            // A change of the display alone after tiles draws the view at full resolution: the
            // display pass would read a radiance image the tiles did not write.
            let mut turned = scene.clone();
            turned.camera.heading_deg += 1.0;
            engine.render(&turned, &view);
            turned.display.exposure_ev += 1.0;
            assert_eq!(
                engine.render(&turned, &view).run,
                vec!["sky"],
                "{name}: exposure after tiles"
            );
            assert!(
                engine.read_radiance().is_ok() && !engine.settling(),
                "{name}"
            );
            engine.render(&scene, &view);
            engine.render(&scene, &view);

            // The meter reads the radiance of every frame: in motion too.
            engine.set_metering(true);
            engine.render(&turned, &view);
            engine.render(&scene, &view);
            assert!(engine.settling(), "{name}: metered, in tiles");
            close(
                "metered radiance",
                &radiance_image(&engine),
                &exact,
                DisplaySetup::default(),
            );
            // Metered tiles wrote their radiance: a change of the display alone reads it, and
            // the still frame after it draws the view at full resolution.
            let mut brighter = scene.clone();
            brighter.display.exposure_ev += 1.0;
            assert_eq!(
                engine.render(&brighter, &view).run,
                vec!["display"],
                "{name}: display after metered tiles"
            );
            assert_eq!(
                engine.render(&brighter, &view).run,
                vec!["sky", "meter"],
                "{name}: still after metered tiles"
            );
            assert_eq!(radiance_image(&engine), exact, "{name}: exact after tiles");
        }
    }
}

/// A GPU draws the sky in one dispatch that decides sky, ground and the sun's disk per pixel
/// (`Engine::set_view_bands(false)`), a software GPU in bands of rows with the disk apart: the
/// same image, at the horizon, the sun and from space.
#[test]
fn the_sky_in_one_dispatch_is_the_sky_in_bands() {
    let Some(gpu) = context() else { return };
    let mut horizon = Scene::default();
    let sun = horizon.sun.angles();
    horizon.camera.heading_deg = sun.azimuth_deg + 10.0;
    horizon.camera.pitch_deg = sun.elevation_deg - 10.0;
    horizon.camera.fov_deg = 80.0;
    let mut space = horizon.clone();
    space.camera.altitude_m = 400_000.0;
    space.camera.pitch_deg = -30.0;
    let view = View::new(Projection::Perspective, 64, 36);
    for (name, scene) in [("horizon", horizon), ("space", space)] {
        for method in [Method::Hillaire, Method::Nishita] {
            let mut scene = scene.clone();
            scene.render.method = method;
            let name = format!("{method:?}, {name}");
            let mut images = Vec::new();
            for bands in [true, false] {
                let mut engine = Engine::new(&gpu.device, &gpu.queue);
                engine.set_view_bands(bands);
                let stats = engine.render(&scene, &view).clone();
                assert!(stats.ran("sky"), "{name}");
                images.push((
                    radiance_image(&engine),
                    engine.read_display().expect("display"),
                ));
            }
            let (banded, whole) = (&images[0], &images[1]);
            // Relative to each value, down to the median's size (the sun's disk is 10⁴–10⁵
            // times the sky: a fraction of the peak would let the sky be anything).
            let mut sizes: Vec<f64> = banded.0.iter().flatten().map(|v| v.abs()).collect();
            sizes.sort_by(f64::total_cmp);
            let median = sizes[sizes.len() / 2];
            let worst = banded
                .0
                .iter()
                .flatten()
                .zip(whole.0.iter().flatten())
                .map(|(a, b)| (a - b).abs() / b.abs().max(median))
                .fold(0.0, f64::max);
            assert!(median > 0.0 && worst < 1e-4, "{name}: {worst} apart");
            let steps = banded
                .1
                .iter()
                .zip(&whole.1)
                .map(|(a, b)| a.abs_diff(*b))
                .max();
            assert!(steps <= Some(1), "{name}: displayed {steps:?} steps apart");
        }
    }
}

#[test]
fn timing_reports_every_pass_that_ran() {
    let Some(gpu) = context() else { return };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    engine.set_timing(true);
    let stats = engine
        .render(
            &Scene::default(),
            &View::new(Projection::Perspective, 32, 18),
        )
        .clone();
    assert_eq!(stats.timing_source, Some(engine.timing_source()));
    assert_eq!(stats.timings_ms.len(), stats.run.len());
    assert_eq!(stats.run, every_still_pass(&stats));
    assert!(
        stats
            .timings_ms
            .iter()
            .all(|(_, ms)| ms.is_finite() && *ms >= 0.0)
    );
}

/// Timed in spans, a frame reports its tables and itself from end to end, with either timer
/// (GPU timestamps written only at the ends, or fenced CPU time summed), and no pass alone.
#[test]
fn span_timing_reports_the_tables_and_the_frame_end_to_end() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 32, 18);
    for cpu in [false, true] {
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        if cpu {
            engine.force_cpu_timing();
        }
        engine.set_timing(true);
        engine.set_span_timing(true);
        let mut scene = Scene::default();
        let source = engine.timing_source();
        let rebuild = engine.render(&scene, &view).clone();
        assert!(rebuild.timings_ms.is_empty(), "{source:?}");
        let spans = rebuild.spans_ms.expect("spans");
        let tables = spans.tables_ms.expect("the first frame builds the tables");
        assert!(
            tables.is_finite() && tables >= 0.0 && spans.frame_ms >= tables,
            "{source:?}: {spans:?}"
        );
        scene.display.exposure_ev += 0.5;
        let display = engine.render(&scene, &view).clone();
        assert!(
            !display.ran_any_lut(),
            "an exposure change redraws the display alone"
        );
        let spans = display.spans_ms.expect("spans");
        assert!(
            spans.tables_ms.is_none() && spans.frame_ms.is_finite(),
            "{spans:?}"
        );
    }
}

/// The tables of the models that gather scattering orders (Bruneton, Elek) depend on the
/// atmosphere alone, but for the views of them at the camera (their camera slices): a sun
/// or camera move runs those and the sky, and from above the atmosphere, where the sky reads
/// the tables themselves, the sky alone. Their order loop runs once per order from the second.
#[test]
fn order_gathering_models_rebuild_only_their_view_tables_when_the_sun_or_the_camera_moves() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    let models: Vec<_> = methods::realtime().filter(|m| m.gathers_orders).collect();
    assert!(models.len() >= 2, "Bruneton and Elek gather orders");
    for model in models {
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        let mut scene = with(model, &Scene::default());
        scene.render.wavelengths = WavelengthSet::Rgb3;
        let passes = gpu_method(model.method).expect("passes").passes;
        let looped = passes
            .iter()
            .filter(|p| p.repeat == Repeat::PerOrder)
            .count();
        let id = model.id;
        let first = engine.render(&scene, &view).clone();
        assert_eq!(first.run, every_still_pass(&first), "{id}");
        let once = every_still_pass(&first).len() - looped;
        let orders = scene.render.scattering_orders as usize;
        assert_eq!(
            first.dispatched,
            once + looped * (orders - 1),
            "{id}: orders 2 to {orders}"
        );
        // The passes that write only tables of the viewpoint, then the sky; none for a model
        // whose tables hold the atmosphere alone (Haber's), and the moving sky only in motion.
        let mut view_only: Vec<_> = passes
            .iter()
            .filter(|p| {
                !p.writes.is_empty()
                    && p.writes.iter().all(|w| {
                        w.as_table().is_some_and(|t| {
                            !t.motion_only()
                                && t.invalidated_by.intersects(methods::Inputs::VIEWPOINT)
                        })
                    })
            })
            .map(|p| p.name)
            .collect();
        assert!(
            !view_only.is_empty() || !matches!(id, "bruneton" | "elek"),
            "{id}: tables at the camera"
        );
        view_only.push("sky");
        scene.sun = SunSettings::Angles {
            elevation_deg: 5.0,
            azimuth_deg: 200.0,
        };
        assert_eq!(engine.render(&scene, &view).run, view_only, "{id}: sun");
        // The same when only told that the viewpoint changed (`bench methods` times the view
        // tables so).
        engine.invalidate_inputs(methods::Inputs::VIEWPOINT);
        assert_eq!(engine.render(&scene, &view).run, view_only, "{id}: told");
        for altitude_m in [10_000.0, 400_000.0, 2.0] {
            scene.camera.altitude_m = altitude_m;
            let expected = if altitude_m > 100_000.0 {
                vec!["sky"]
            } else {
                view_only.clone()
            };
            assert_eq!(
                engine.render(&scene, &view).run,
                expected,
                "{id}: {altitude_m} m"
            );
        }
        // With the sun below Bruneton's tables at the camera (nautical twilight at −15°) his
        // sky reads the 4D tables, so the slices wait; they are made when the sun comes back.
        // Elek's tables hold every sun.
        let below = if model.method == Method::Bruneton {
            vec!["sky"]
        } else {
            view_only.clone()
        };
        for (elevation_deg, expected) in [(-15.0, below), (5.0, view_only.clone())] {
            scene.sun = SunSettings::Angles {
                elevation_deg,
                azimuth_deg: 200.0,
            };
            assert_eq!(
                engine.render(&scene, &view).run,
                expected,
                "{id}: sun at {elevation_deg}°"
            );
        }
        scene.render.scattering_orders = 1;
        let single = engine.render(&scene, &view).clone();
        assert_eq!(single.dispatched, once, "{id}: one order, no loop");
        // The order loop's passes, the display pass, whose image the sky pass drew, and those
        // of frames in motion (Haber's way to the sun and moving sky).
        let in_motion = passes
            .iter()
            .filter(|p| {
                p.writes
                    .iter()
                    .any(|w| w.as_table().is_some_and(|t| t.motion_only()))
            })
            .count();
        assert_eq!(single.skipped.len(), looped + 1 + in_motion, "{id}");
        scene.render.scattering_orders = 10;
        assert_eq!(
            engine.render(&scene, &view).dispatched,
            once + looped * 9,
            "{id}"
        );
    }
}

/// Elek's tables at the camera are the GPU's own 3D tables blended at the viewpoint, between
/// texels in both the altitude and the sun, to f32 rounding: the check of the slice alone,
/// apart from how closely the 3D tables follow their twin.
#[test]
fn elek_s_tables_at_the_camera_blend_his_three_dimensional_tables_there() {
    use atmoscope_model::methods::elek::{self, camera_slice};
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    let mut scene = Scene::default();
    scene.render.method = Method::Elek;
    scene.render.quality = Quality::Low;
    scene.render.wavelengths = WavelengthSet::Rgb3;
    scene.render.scattering_orders = 2;
    // 1234 m and the sun 20° up fall between texels on both axes (3.4 and 26.3).
    scene.camera.altitude_m = 1234.0;
    scene.sun = SunSettings::Angles {
        elevation_deg: 20.0,
        azimuth_deg: 120.0,
    };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    engine.try_render(&scene, &view).expect("Elek draws");
    let radius = scene.atmosphere.planet_radius_km * 1000.0;
    let camera = Camera::new(&scene.camera, radius, view.projection);
    let cpu = methods::build(&scene, &camera).expect("a real-time model");
    let p = cpu.params();
    let vp = viewpoint(&scene, &camera);
    let [w, h, d] = elek::SIZE.map(|n| n as usize);
    for (table, slice) in [
        (elek::RAYLEIGH, camera_slice::CAMERA_RAYLEIGH),
        (elek::MIE, camera_slice::CAMERA_MIE),
    ] {
        let texels = engine.read_table(table.id).expect("read-back");
        let lut = Lut {
            width: w,
            height: h,
            depth: d,
            layers: p.batches.len(),
            data: texels.iter().map(|t| t.map(f64::from).into()).collect(),
        };
        let expected = camera_slice::compute_camera_slice(p, &slice, &lut, vp);
        let got = engine.read_table(slice.id).expect("read-back");
        let largest = expected
            .data
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(largest > 0.0, "{}", slice.id);
        for (i, (g, e)) in got.iter().zip(&expected.data).enumerate() {
            for l in 0..4 {
                let tolerance = 1e-5 * (e[l].abs() + 1e-3 * largest);
                assert!(
                    (f64::from(g[l]) - e[l]).abs() <= tolerance,
                    "{} texel {i}: GPU {g:?}, blend of the GPU's table {e:?}",
                    slice.id
                );
            }
        }
    }
}

/// `render.fitted_constants` reaches García Liñán's passes: switching it rebuilds the sky
/// texture, and the GPU matches the CPU twin with either set of constants.
#[test]
fn fitted_constants_reach_the_gpu_and_rebuild_the_tables() {
    let Some(gpu) = context() else { return };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let model = methods::realtime()
        .find(|m| m.refittable)
        .expect("a model with fitted constants");
    let mut scene = with(model, &Scene::default());
    let (w, h) = (24, 24);
    let view = View::new(Projection::Fisheye, w, h);
    let mut images = Vec::new();
    for choice in [FittedConstants::Published, FittedConstants::Refit] {
        scene.render.fitted_constants = choice;
        let stats = engine.render(&scene, &view).clone();
        assert_eq!(
            stats.run,
            every_still_pass(&stats),
            "{choice:?}: every table rebuilt"
        );
        let gpu_image = radiance_image(&engine);
        let cpu_image = methods::render(&scene, view.projection, w, h).expect("real-time");
        let (c, _) = compare(&gpu_image, &cpu_image, w, h, DisplaySetup::default());
        assert!(
            c.delta_e2000_mean < 0.3,
            "{choice:?}: {}",
            c.delta_e2000_mean
        );
        images.push(gpu_image);
    }
    let (c, _) = compare(&images[0], &images[1], w, h, DisplaySetup::default());
    assert!(
        c.delta_e2000_mean > 0.5,
        "the refit changes the sky: {}",
        c.delta_e2000_mean
    );
}

/// From above the atmosphere the models that march every pixel (or, as Bruneton's and Elek's,
/// read their 4D or 3D tables instead of their slices at the camera) leave the view tables they do not read
/// stale, and build them when the camera comes back down: the image is then the same as a
/// fresh engine's.
#[test]
fn from_above_the_atmosphere_the_view_tables_wait_until_a_view_needs_them() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    // A model that refuses views from space has nothing to wait for.
    for model in methods::realtime().filter(|m| !m.domain.refuses) {
        let from_space: &[&str] = match model.id {
            "hillaire" => &[
                "transmittance",
                "multiple-scattering",
                "ground-irradiance",
                "sky",
            ],
            "garcia-linan" => &["transmittance", "sky"],
            "bruneton" => &[
                "transmittance",
                "direct-irradiance",
                "single-scattering",
                "scattering-density",
                "indirect-irradiance",
                "multiple-scattering",
                "sky",
            ],
            "elek" => &[
                "transmittance",
                "single-scattering",
                "gather",
                "multiple-scattering",
                "accumulate",
                "sky",
            ],
            // No view tables to leave stale: the same passes everywhere.
            "nishita" | "trapezoid" | "schuler" | "galaj-taylor" | "galaj-spline" | "flat"
            | "raymarched" | "oneil" | "empty" => {
                continue;
            }
            // The same passes from space: the sky pass marches every pixel anyway.
            "nishita-ms" | "trapezoid-ms" | "schuler-ms" | "galaj-taylor-ms" => {
                &["transmittance", "multiple-scattering", "sky"]
            }
            // The intensity volume depends on the atmosphere alone: built from space too.
            "nishita-96" => &["transmittance", "intensity-volume", "sky"],
            "haber" => &[
                "transmittance",
                "first-order",
                "previous-order",
                "next-order",
                "sky",
            ],
            "galaj-spline-ms" => &[
                "galaj-spline-mesh",
                "transmittance",
                "multiple-scattering",
                "sky",
            ],
            other => panic!("state what {other} runs from space"),
        };
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        let mut scene = with(model, &Scene::default());
        scene.camera.altitude_m = 400_000.0;
        scene.camera.pitch_deg = -60.0;
        let first = engine.render(&scene, &view).clone();
        assert_eq!(first.run, from_space, "{}: from space", model.id);
        scene.sun = SunSettings::Angles {
            elevation_deg: 12.0,
            azimuth_deg: 100.0,
        };
        assert_eq!(
            engine.render(&scene, &view).run,
            vec!["sky"],
            "{}: the sun moves in space",
            model.id
        );
        scene.camera.altitude_m = 1000.0;
        let down = engine.render(&scene, &view).clone();
        assert!(
            every_still_pass(&down)
                .iter()
                .filter(|p| !from_space.contains(p))
                .all(|p| down.run.contains(p)),
            "{}: coming down runs what waited: {:?}",
            model.id,
            down.run
        );
        let image = radiance_image(&engine);
        let mut fresh = Engine::new(&gpu.device, &gpu.queue);
        fresh.render(&scene, &view);
        assert_eq!(image, radiance_image(&fresh), "{}", model.id);
    }
}

#[test]
#[ignore = "research tier: the scheduler end to end on the GPU; the fast tier tests its plan on the CPU (engine::schedule)"]
fn every_model_skips_its_tables_when_only_the_view_or_the_display_changes() {
    let Some(gpu) = context() else { return };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let view = View::new(Projection::Perspective, 24, 16);
    for model in methods::realtime() {
        let mut scene = with(model, &Scene::default());
        let first = engine.render(&scene, &view).clone();
        assert_eq!(
            first.run,
            every_still_pass(&first),
            "{}: a new model runs every pass",
            model.id
        );
        assert!(
            engine.render(&scene, &view).run.is_empty(),
            "{}: idle",
            model.id
        );
        scene.camera.heading_deg += 30.0;
        assert_eq!(
            engine.render(&scene, &view).run,
            vec!["sky"],
            "{}",
            model.id
        );
        scene.display.exposure_ev += 1.0;
        assert_eq!(
            engine.render(&scene, &view).run,
            vec!["display"],
            "{}",
            model.id
        );
        scene.atmosphere.aerosol.aod550 = 0.3;
        let stats = engine.render(&scene, &view).clone();
        assert_eq!(stats.run, every_still_pass(&stats), "{}: aerosol", model.id);
    }
    let mut offline = Scene::default();
    offline.render.method = Method::PathTracer;
    assert!(engine.try_render(&offline, &view).is_err());
}

/// A sun exactly at the centre of an even-sized view falls between pixel centres: each pixel
/// averages the disk over its footprint, so the view keeps the sun's energy (it vanished when
/// the disk was point-sampled).
#[test]
fn the_sun_centred_in_an_even_sized_view_keeps_its_energy() {
    let Some(gpu) = context() else { return };
    let mut scene = Scene::default();
    scene.sun = SunSettings::Angles {
        elevation_deg: 30.0,
        azimuth_deg: 180.0,
    };
    scene.camera.heading_deg = 180.0;
    scene.camera.pitch_deg = 30.0;
    scene.camera.fov_deg = 2.0;
    let radius = scene.atmosphere.planet_radius_km * 1000.0;
    // Σ Y·Ω over the view: the sun's illuminance through the atmosphere, plus a little sky.
    let energy = |image: &[[f64; 3]], camera: &Camera, size: u32| -> f64 {
        image
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (x, y) = (
                    (i as u32 % size) as f64 + 0.5,
                    (i as u32 / size) as f64 + 0.5,
                );
                luminance(*p)
                    * camera
                        .pixel_axes(x, y, size, size)
                        .map_or(0.0, |a| a.solid_angle())
            })
            .sum()
    };
    for model in methods::realtime() {
        let scene = with(model, &scene);
        let camera = Camera::new(&scene.camera, radius, Projection::Perspective);
        let twin = methods::build(&scene, &camera).expect("a real-time model");
        // A 64² view holds the energy of a 256² one to 0.07 % for every model (measured), at
        // a sixteenth of the CPU time.
        let fine = energy(
            &methods::render_with(twin.as_ref(), &scene, &camera, 64, 64),
            &camera,
            64,
        );
        let coarse = energy(
            &methods::render_with(twin.as_ref(), &scene, &camera, 4, 4),
            &camera,
            4,
        );
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.render(&scene, &View::new(Projection::Perspective, 4, 4));
        let on_gpu = energy(&radiance_image(&engine), &camera, 4);
        eprintln!(
            "{}: Σ Y·Ω fine {fine:.4e}, 4×4 {coarse:.4e}, GPU 4×4 {on_gpu:.4e}",
            model.id
        );
        assert!(
            (coarse / fine - 1.0).abs() < 0.03,
            "{}: the 4×4 view holds {coarse:e}, the 64×64 one {fine:e}",
            model.id
        );
        assert!(
            (on_gpu / coarse - 1.0).abs() < 0.02,
            "{}: GPU {on_gpu:e}, CPU twin {coarse:e}",
            model.id
        );
    }
}

/// A constituent of zero amount costs no integration work: without aerosol every pass skips
/// the aerosol terms (`has_aerosol()` in the shaders), and the view still matches the CPU twin.
#[test]
fn no_aerosol_skips_the_aerosol_terms_and_matches_the_twin() {
    let Some(gpu) = context() else { return };
    let mut clear = Scene::default();
    clear.atmosphere.aerosol.aod550 = 0.0;
    let (w, h) = (32, 16);
    for model in methods::realtime() {
        let scene = with(model, &clear);
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.render(&scene, &View::new(Projection::Panorama, w, h));
        assert!(!engine.params().expect("rendered").has_aerosol());
        let cpu = methods::render(&scene, Projection::Panorama, w, h).expect("a real-time model");
        let (c, _) = compare(
            &radiance_image(&engine),
            &cpu,
            w,
            h,
            DisplaySetup::default(),
        );
        assert!(
            c.delta_e2000_mean < 0.3,
            "{}: ΔE2000 {}",
            model.id,
            c.delta_e2000_mean
        );
    }
}

/// With the tabulated Mie phase (desert dust, whose coarse particles peak forward far more
/// than Henyey–Greenstein with their g), the views match their CPU twins for a model of each
/// shader that reads the phase (the others share those shaders), and the phase reaches the GPU:
/// the circumsolar sky differs from Henyey–Greenstein's.
#[test]
fn the_mie_phase_matches_the_cpu_twin_in_every_shader_that_reads_it() {
    use atmoscope_model::aerosol::AerosolType;
    use atmoscope_model::scene::AerosolPhase;
    let Some(gpu) = context() else { return };
    let mut dust = Scene::default();
    dust.atmosphere.aerosol.kind = AerosolType::DesertDust;
    dust.atmosphere.aerosol.aod550 = 0.5;
    dust.atmosphere.aerosol.phase = AerosolPhase::Mie;
    dust.render.quality = Quality::Low;
    dust.sun = SunSettings::Angles {
        elevation_deg: 20.0,
        azimuth_deg: 180.0,
    };
    let (w, h) = (32, 32);
    let readers = [
        Method::Hillaire,    // the shared march
        Method::Bruneton,    // single Mie, scattering density, orders
        Method::Elek,        // gather
        Method::GarciaLinan, // its sky texture
        Method::Flat,        // the segments sky
        Method::GalajTaylor, // the single-scattering sky
    ];
    for model in methods::realtime().filter(|m| readers.contains(&m.method)) {
        let scene = with(model, &dust);
        if refused(&scene) {
            continue;
        }
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.render(&scene, &View::new(Projection::Fisheye, w, h));
        let mie = radiance_image(&engine);
        let cpu = methods::render(&scene, Projection::Fisheye, w, h).expect("a real-time model");
        let (c, _) = compare(&mie, &cpu, w, h, DisplaySetup::default());
        assert!(
            c.delta_e2000_mean < 0.3,
            "{}: ΔE2000 {} against the twin",
            model.id,
            c.delta_e2000_mean
        );
        if model.method == Method::Hillaire {
            let mut hg = scene.clone();
            hg.atmosphere.aerosol.phase = AerosolPhase::HenyeyGreenstein;
            engine.render(&hg, &View::new(Projection::Fisheye, w, h));
            let (d, _) = compare(
                &mie,
                &radiance_image(&engine),
                w,
                h,
                DisplaySetup::default(),
            );
            assert!(
                d.delta_e2000_mean > 0.5,
                "Mie against Henyey–Greenstein: ΔE2000 {}",
                d.delta_e2000_mean
            );
        }
    }
}

/// A rebuild run in slices across frames (half a row of workgroups at a time, a frame each, so
/// that slices start inside rows as well as at their ends) keeps the previous image on screen until it is done,
/// and then gives every table and the image exactly as a rebuild in one frame does.
#[test]
fn a_rebuild_in_slices_gives_the_same_tables_as_a_whole_one() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    for model in methods::realtime() {
        let mut before = with(model, &Scene::default());
        before.render.wavelengths = WavelengthSet::SpectralN(8);
        let mut after = before.clone();
        after.atmosphere.ground_albedo = 0.6;
        after.atmosphere.aerosol.aod550 = 0.3;
        let mut sliced = Engine::new(&gpu.device, &gpu.queue);
        sliced.render(&before, &view);
        let old_image = radiance_image(&sliced);
        sliced.set_rebuild_slices(Some(std::time::Duration::ZERO));
        let mut frames = 0;
        loop {
            let stats = sliced.render(&after, &view).clone();
            sliced.wait();
            if !sliced.rebuilding() {
                break;
            }
            let progress = stats.rebuild.expect("progress while rebuilding");
            assert!(progress.done <= progress.total, "{}", model.id);
            // Nothing but the swap at the end writes the image, so one overwritten mid-build
            // would stay overwritten: reading it back in the first 16 slices, every 16th after
            // and the last finds it (a read-back waits for the GPU, and Bruneton's rebuild
            // takes thousands of slices).
            if frames < 16 || frames % 16 == 0 || progress.done + 1 >= progress.total {
                assert_eq!(
                    radiance_image(&sliced),
                    old_image,
                    "{}: the old image stays",
                    model.id
                );
            }
            frames += 1;
        }
        let passes = gpu_method(model.method).expect("real-time").passes.len();
        assert!(frames > passes, "{}: {frames} slices", model.id);
        let mut whole = Engine::new(&gpu.device, &gpu.queue);
        whole.render(&after, &view);
        assert_built_alike(model, &sliced, &whole);
        assert_ne!(radiance_image(&sliced), old_image, "{}", model.id);
        // The displayed image comes from the sky pass's slices: the same within a step.
        let (a, b) = (
            sliced.read_display().expect("display"),
            whole.read_display().expect("display"),
        );
        let steps = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).max();
        assert!(
            steps <= Some(1),
            "{}: displayed {steps:?} steps apart",
            model.id
        );
    }
}

/// An engine that slices its work from the start builds its first atmosphere in slices too,
/// drawing nothing meanwhile, and ends with the tables and view of a whole build; a held
/// rebuild (`Engine::hold_rebuild`: another engine of the window has the frame's slice) makes
/// no progress and draws nothing either.
#[test]
fn the_first_build_in_slices_gives_the_tables_of_a_whole_one() {
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 24, 16);
    for model in methods::realtime() {
        let mut scene = with(model, &Scene::default());
        scene.render.wavelengths = WavelengthSet::Rgb3;
        let mut sliced = Engine::new(&gpu.device, &gpu.queue);
        sliced.set_rebuild_slices(Some(std::time::Duration::ZERO));
        sliced.hold_rebuild(true);
        let held = sliced.render(&scene, &view).clone();
        let start = held.rebuild.expect("a first build under way");
        assert_eq!((start.done, held.run.len()), (0, 0), "{}: held", model.id);
        sliced.hold_rebuild(false);
        let mut frames = 0;
        loop {
            let stats = sliced.render(&scene, &view).clone();
            sliced.wait();
            if stats.rebuild_done {
                break;
            }
            let progress = stats.rebuild.expect("progress while building");
            assert!(progress.done <= progress.total, "{}", model.id);
            assert!(
                stats.run.is_empty() && sliced.read_radiance().is_err(),
                "{}: nothing is drawn before the first build is done",
                model.id
            );
            frames += 1;
            assert!(frames < 1_000_000, "{}: the build ends", model.id);
        }
        assert!(frames > 1, "{}: {frames} slices", model.id);
        let mut whole = Engine::new(&gpu.device, &gpu.queue);
        whole.render(&scene, &view);
        assert_built_alike(model, &sliced, &whole);
    }
}

/// An engine that built in slices holds the tables of one that built whole, texel for texel,
/// and draws the same radiance: bit for bit on lavapipe; an NVIDIA driver was seen to round
/// 12 of 384 pixels an f32 ulp apart (3e-7) between two engines.
fn assert_built_alike(model: &ModelInfo, sliced: &Engine, whole: &Engine) {
    for table in model.tables {
        let a = sliced.read_table(table.id).expect("sliced");
        let b = whole.read_table(table.id).expect("whole");
        let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
        assert_eq!(
            (a.len(), differ),
            (b.len(), 0),
            "{}: {}",
            model.id,
            table.id
        );
    }
    let worst = radiance_image(sliced)
        .iter()
        .flatten()
        .zip(radiance_image(whole).iter().flatten())
        .map(|(a, b)| (a - b).abs() / b.abs().max(1e-30))
        .fold(0.0, f64::max);
    assert!(worst <= 1e-6, "{}: {worst}", model.id);
}

/// Tables whose texels are shared by a workgroup (`Dispatch::TexelGroups`) or whose marches are
/// split across invocations (`prelude::march_split`) come out the same, up to f32 rounding of
/// the sums' order, whatever the workgroup's size: 16 as on lavapipe (no split), 64 as on a GPU
/// (more invocations than the aerial perspective's 32 slices; marches in parts), every other
/// size the engine allows up to 256, and 1 (one invocation per texel, the old layout).
#[test]
fn texel_groups_of_any_size_give_the_same_tables() {
    const TABLES: [(Method, &str); 7] = [
        (Method::Hillaire, "transmittance"),
        (Method::Hillaire, "sky-view"),
        (Method::Hillaire, "multiple-scattering"),
        (Method::Hillaire, "ground-irradiance"),
        (Method::Hillaire, "aerial-perspective-inscattering"),
        (Method::Hillaire, "aerial-perspective-transmittance"),
        (Method::GarciaLinan, "sky-texture"),
    ];
    let Some(gpu) = context() else { return };
    let view = View::new(Projection::Perspective, 8, 8);
    let read = |n: u32| {
        let mut engine = Engine::new(&gpu.device, &gpu.queue);
        engine.set_texel_group_size(n);
        TABLES.map(|(method, id)| {
            let mut scene = Scene::default();
            scene.render.method = method;
            engine.render(&scene, &view);
            engine.read_table(id).expect(id)
        })
    };
    let reference = read(1);
    for n in [16, 32, 64, 128, 256] {
        for ((_, table), (a, b)) in TABLES.iter().zip(read(n).iter().zip(&reference)) {
            assert_eq!(a.len(), b.len());
            let worst = a
                .iter()
                .flatten()
                .zip(b.iter().flatten())
                .map(|(x, y)| (x - y).abs() / y.abs().max(1e-30))
                .fold(0.0f32, f32::max);
            assert!(worst < 1e-4, "{table} with groups of {n}: {worst}");
            assert!(b.iter().flatten().any(|&v| v > 0.0), "{table} is empty");
        }
    }
}

/// With glare on, the display pass adds the veiling glare of `model::display::glare` around
/// the sun, from the sun's irradiance of `sun_irradiance_rgb`, to each pixel before the white
/// balance and the tone map: the bytes the CPU gives from the same radiance within a step; the
/// radiance itself (what every measurement reads) is the same with glare as without.
#[test]
fn the_display_adds_the_glare_of_its_cpu_twin_around_the_sun() {
    use atmoscope_model::display::{display_balanced, glare, sun_irradiance_rgb, to_u8};
    use atmoscope_model::geometry::direction_from_angles;
    use atmoscope_model::methods::shared::Params;
    let Some(gpu) = context() else { return };
    let (w, h) = (48u32, 27u32);
    let view = View::new(Projection::Perspective, w, h);
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let mut scene = Scene::default();
    let sun = scene.sun.angles();
    scene.camera.heading_deg = sun.azimuth_deg + 10.0;
    scene.camera.pitch_deg = sun.elevation_deg - 5.0;
    scene.display.tone_map = ToneMap::Filmic;
    scene.display.exposure_ev = -1.0;
    scene.display.dither = false;
    engine.render(&scene, &view);
    let (plain_radiance, plain) = (
        engine.read_radiance().expect("radiance"),
        engine.read_display().expect("display"),
    );
    scene.display.glare = true;
    engine.render(&scene, &view);
    let shown = engine.read_display().expect("display");
    // A fresh engine draws the view with its sky pass, which draws the glare too.
    let mut fresh = Engine::new(&gpu.device, &gpu.queue);
    fresh.render(&scene, &view);
    let radiance = fresh.read_radiance().expect("radiance");
    assert_eq!(radiance, plain_radiance, "glare never reaches the radiance");
    let steps = fresh
        .read_display()
        .expect("display")
        .iter()
        .zip(&shown)
        .map(|(a, b)| a.abs_diff(*b))
        .max();
    assert!(
        steps <= Some(1),
        "the sky pass's glare: {steps:?} steps from the display pass's"
    );
    assert_ne!(shown, plain, "glare shows");
    let p = Params::new(
        &atmoscope_model::Atmosphere::for_scene(&scene),
        scene.render.wavelengths,
        scene.render.quality,
    );
    let e = sun_irradiance_rgb(
        &p,
        scene.camera.altitude_m,
        sun.elevation_deg.to_radians().sin(),
    );
    let camera = Camera::new(&scene.camera, p.bottom_radius_m, Projection::Perspective);
    let sun_dir = direction_from_angles(sun.elevation_deg, sun.azimuth_deg);
    let balance = atmoscope_model::white_balance::matrix(&scene);
    let (mut worst, mut differ) = (0, 0);
    for (i, l) in radiance.iter().enumerate() {
        let (x, y) = (i as u32 % w, i as u32 / w);
        let ray = camera
            .ray(f64::from(x) + 0.5, f64::from(y) + 0.5, w, h)
            .expect("a perspective pixel");
        let g = glare(ray.direction.dot(sun_dir), e);
        let l = [l[0], l[1], l[2]].map(f64::from);
        let cpu = display_balanced(
            std::array::from_fn(|c| l[c] + g[c]),
            &balance,
            scene.display.exposure_ev,
            scene.display.tone_map,
        );
        for c in 0..3 {
            let d = to_u8(cpu[c]).abs_diff(shown[4 * i + c]);
            worst = worst.max(d);
            differ += usize::from(d > 0);
        }
    }
    let n = radiance.len() * 3;
    assert!(
        worst <= 1 && differ * DIFFER_AT_MOST_ONE_IN <= n,
        "{worst} steps, {differ} of {n} bytes"
    );
}

/// The display pass is the twin of `model::display`: every tone map, with and without
/// dithering, under each white balance, gives the bytes the CPU gives from the same radiance, within one step (f32
/// against f64 at rounding edges, in a fiftieth of the bytes at most); dithering changes bytes and keeps their mean.
#[test]
fn the_display_pass_matches_its_cpu_twin_for_every_tone_map() {
    use atmoscope_model::display::{display_balanced, to_u8, to_u8_dithered};
    use atmoscope_model::scene::WhiteBalance;
    let Some(gpu) = context() else { return };
    let (w, h) = (48u32, 27u32);
    let view = View::new(Projection::Perspective, w, h);
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let mut scene = Scene::default();
    scene.display.exposure_ev = 1.5;
    let balances = [
        WhiteBalance::None,
        WhiteBalance::SunAtNoon,
        WhiteBalance::Temperature { kelvin: 3200.0 },
    ];
    for (k, tone_map) in ToneMap::ALL.into_iter().enumerate() {
        let mut bytes = Vec::new();
        scene.display.white_balance = balances[k % balances.len()];
        let balance = atmoscope_model::white_balance::matrix(&scene);
        for dither in [false, true] {
            scene.display.tone_map = tone_map;
            scene.display.dither = dither;
            engine.render(&scene, &view);
            let radiance = engine.read_radiance().expect("radiance");
            let gpu_bytes = engine.read_display().expect("display");
            let (mut worst, mut differ) = (0, 0);
            for (i, p) in radiance.iter().enumerate() {
                let (x, y) = (i as u32 % w, i as u32 / w);
                let shown = display_balanced(
                    [p[0], p[1], p[2]].map(f64::from),
                    &balance,
                    scene.display.exposure_ev,
                    tone_map,
                );
                for c in 0..3 {
                    let cpu = if dither {
                        to_u8_dithered(shown[c], x, y)
                    } else {
                        to_u8(shown[c])
                    };
                    let d = cpu.abs_diff(gpu_bytes[4 * i + c]);
                    worst = worst.max(d);
                    differ += usize::from(d > 0);
                }
            }
            // Off by a step only where f32 and f64 round a value on either side of an edge.
            let n = radiance.len() * 3;
            assert!(
                worst <= 1 && differ * DIFFER_AT_MOST_ONE_IN <= n,
                "{tone_map:?} dither {dither}: {worst} steps, {differ} of {n} bytes"
            );
            bytes.push(gpu_bytes);
        }
        let mean = |b: &[u8]| b.iter().map(|&v| f64::from(v)).sum::<f64>() / b.len() as f64;
        assert_ne!(bytes[0], bytes[1], "{tone_map:?}: dithering changes bytes");
        assert!(
            (mean(&bytes[0]) - mean(&bytes[1])).abs() < 0.3,
            "{tone_map:?}"
        );
    }
}

/// The sky pass draws the display image as the display pass does from its radiance: every tone
/// map, with glare and without, and the luminance map, within a step (the same f32 code in two
/// shaders), in a twentieth of the bytes at most.
#[test]
fn the_sky_pass_displays_what_the_display_pass_shows() {
    let Some(gpu) = context() else { return };
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let mut scene = Scene::default();
    let sun = scene.sun.angles();
    scene.camera.heading_deg = sun.azimuth_deg + 10.0;
    scene.camera.pitch_deg = sun.elevation_deg - 5.0;
    scene.display.exposure_ev = 1.0;
    let colour = View::new(Projection::Perspective, 48, 27);
    engine.render(&scene, &colour);
    for (view, tone_map, glare) in ToneMap::ALL
        .into_iter()
        .flat_map(|t| [(colour, t, false), (colour, t, true)])
        .chain([(colour.luminance(), ToneMap::Exponential, false)])
    {
        let name = format!("{:?} {tone_map:?}, glare {glare}", view.mode);
        scene.display.tone_map = tone_map;
        scene.display.glare = glare;
        scene.camera.heading_deg += 0.5;
        assert_eq!(engine.render(&scene, &view).run, vec!["sky"], "{name}");
        let by_sky = engine.read_display().expect("display");
        scene.display.exposure_ev += 1.0;
        engine.render(&scene, &view);
        scene.display.exposure_ev -= 1.0;
        assert_eq!(engine.render(&scene, &view).run, vec!["display"], "{name}");
        let by_pass = engine.read_display().expect("display");
        let steps: Vec<u8> = by_sky
            .iter()
            .zip(&by_pass)
            .map(|(a, b)| a.abs_diff(*b))
            .collect();
        let worst = steps.iter().copied().max().unwrap_or(0);
        let differ = steps.iter().filter(|&&d| d > 0).count();
        assert!(
            worst <= 1 && differ * DIFFER_AT_MOST_ONE_IN <= steps.len(),
            "{name}: {worst} steps, {differ} of {} bytes",
            steps.len()
        );
        assert!(by_sky.iter().any(|&b| b > 0), "{name}: an image");
    }
}

/// The meter pass counts the view's pixels per luminance bin as the CPU does from the same
/// radiance (a pixel may land in the neighbouring bin where f32 and f64 logarithms straddle
/// an edge); it runs only while the engine meters, and turning metering on runs it alone.
#[test]
fn the_meter_pass_counts_the_luminance_histogram_like_its_cpu_twin() {
    use atmoscope_model::colour::linear_srgb_to_xyz;
    use atmoscope_model::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
    use atmoscope_model::display::Histogram;
    let Some(gpu) = context() else { return };
    let (w, h) = (40u32, 30u32);
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let scene = Scene::default();
    for projection in [Projection::Perspective, Projection::Fisheye] {
        let view = View::new(projection, w, h);
        engine.set_metering(false);
        let first = engine.render(&scene, &view).clone();
        assert!(!first.passes.contains(&"meter") && !first.run.contains(&"meter"));
        engine.set_metering(true);
        assert_eq!(
            engine.render(&scene, &view).run,
            vec!["meter"],
            "{projection:?}"
        );
        let counts = engine.histogram().expect("histogram").counts;
        let radiance = engine.read_radiance().expect("radiance");
        let cpu = Histogram::of(radiance.iter().filter(|p| p[3] > 0.0).map(|p| {
            let rgb = [p[0], p[1], p[2]].map(f64::from);
            linear_srgb_to_xyz(rgb).y * MAX_LUMINOUS_EFFICACY_LM_PER_W
        }));
        let total: u32 = counts.iter().sum();
        assert_eq!(
            total,
            cpu.counts.iter().sum::<u32>(),
            "{projection:?}: every pixel shown"
        );
        let moved: u32 = counts
            .iter()
            .zip(&cpu.counts)
            .map(|(a, b)| a.abs_diff(*b))
            .sum();
        assert!(
            moved * 100 <= total,
            "{projection:?}: {moved} of {total} in other bins"
        );
        assert!(counts.iter().filter(|&&c| c > 0).count() > 3, "{counts:?}");
    }
}
