//! The explorer in a browser, on WebGPU (`web/README.md` builds and serves it). The page
//! (`web/index.html`) holds a canvas and a place for a message; this module checks that the
//! browser can run the engine, starts eframe's web runner on the canvas, and gives the explorer
//! what a page has instead of files: downloads for what it writes, the browser's file picker
//! for presets to open. The layout and the last scene are kept in the browser's local storage
//! by eframe, and validated when read back as on the desktop (`gui::restore`).

mod page;

use crate::gui::{self, ExplorerApp};
use eframe::egui_wgpu::{WgpuSetup, wgpu};
use std::cell::RefCell;
use wasm_bindgen::JsCast;

pub use page::{download, mark_first_frame, query, report_bench, show_problem};

/// The canvas the explorer draws on (`web/index.html`).
const CANVAS_ID: &str = "atmoscope";

/// Starts the explorer on the page; a problem (no WebGPU, an adapter short of what the engine
/// needs, a crash) replaces the canvas with a message saying what to use instead.
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let text = info.to_string();
        web_sys::console::error_1(&text.clone().into());
        show_problem("The explorer stopped with an error", &text);
    }));
    wasm_bindgen_futures::spawn_local(async {
        if let Err(problem) = run().await {
            web_sys::console::error_1(&problem.detail.clone().into());
            show_problem(problem.title, &problem.detail);
        }
    });
}

/// Why the explorer cannot run here.
struct Problem {
    title: &'static str,
    detail: String,
}

async fn run() -> Result<(), Problem> {
    check_webgpu().await?;
    let canvas = page::element(CANVAS_ID)
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        .ok_or_else(|| Problem {
            title: "The page is incomplete",
            detail: format!("it has no canvas with the id `{CANVAS_ID}`"),
        })?;
    let bench = bench_args()?;
    let mut options = eframe::WebOptions::default();
    options.wgpu_options.wgpu_setup = webgpu_setup();
    gui::ask_for_what_the_engine_uses(&mut options.wgpu_options.wgpu_setup);
    eframe::WebRunner::new()
        .start(
            canvas,
            options,
            Box::new(|cc| {
                if let Some(rs) = cc.wgpu_render_state.as_ref() {
                    // A GPU fault is a console error (the browser test fails on one), not a
                    // panic of wgpu's default handler.
                    rs.device.on_uncaptured_error(std::sync::Arc::new(|e| {
                        web_sys::console::error_1(&format!("WebGPU error: {e}").into());
                    }));
                }
                let ctx = cc.egui_ctx.clone();
                atmoscope_render::readback::set_waker(move || ctx.request_repaint());
                let Some(bench) = bench else {
                    let (scene, layout) = gui::restore(cc.storage, None);
                    return Ok(Box::new(ExplorerApp::new(
                        scene,
                        layout,
                        cc.wgpu_render_state.as_ref(),
                    )));
                };
                // A scripted session, as `atmoscope bench gui` plays it in a window: it starts
                // from the defaults and saves nothing.
                let mut app = ExplorerApp::new(
                    atmoscope_model::Scene::default(),
                    gui::Layout::default(),
                    cc.wgpu_render_state.as_ref(),
                );
                app.session = Some(gui::scripted::Session::new(&bench, Default::default()));
                Ok(Box::new(app))
            }),
        )
        .await
        .map_err(|e| Problem {
            title: "The explorer could not start",
            detail: format!("{e:?}"),
        })
}

/// The page's `?bench=SCRIPT&model=ID` query as `bench gui`'s arguments (`?bench=sky-frames`
/// is the browser's half of the Sky view's frame-time benchmark); None without `bench`.
fn bench_args() -> Result<Option<crate::gui_bench::GuiBenchArgs>, Problem> {
    use clap::Parser;
    #[derive(clap::Parser)]
    struct Query {
        #[command(flatten)]
        bench: crate::gui_bench::GuiBenchArgs,
    }
    let Some(script) = query("bench") else {
        return Ok(None);
    };
    let mut argv = vec!["atmoscope".to_string(), "--script".into(), script];
    if let Some(model) = query("model") {
        argv.extend(["--model".into(), model]);
    }
    Query::try_parse_from(argv)
        .map(|q| Some(q.bench))
        .map_err(|e| Problem {
            title: "The benchmark's address is wrong",
            detail: e.to_string(),
        })
}

/// WebGPU only: the engine computes its tables in compute shaders, which WebGL lacks.
fn webgpu_setup() -> WgpuSetup {
    let mut setup = WgpuSetup::without_display_handle();
    if let WgpuSetup::CreateNew(create) = &mut setup {
        create.instance_descriptor.backends = wgpu::Backends::BROWSER_WEBGPU;
    }
    setup
}

/// Refuses a browser without WebGPU, or whose adapter lacks what the engine needs, with a
/// message saying what to use instead.
async fn check_webgpu() -> Result<(), Problem> {
    const INSTEAD: &str = "Use a browser with WebGPU (Chrome or Edge 113 or later, Safari 26, \
        Firefox 141 on Windows), or the desktop explorer (see the project's README).";
    if !wgpu::util::is_browser_webgpu_supported().await {
        return Err(Problem {
            title: "This browser has no WebGPU",
            detail: format!(
                "Atmoscope computes the sky with WebGPU compute shaders, which this browser \
                 does not offer (or has turned off). {INSTEAD}"
            ),
        });
    }
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
    descriptor.backends = wgpu::Backends::BROWSER_WEBGPU;
    let instance = wgpu::Instance::new(descriptor);
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        })
        .await
        .map_err(|e| Problem {
            title: "WebGPU gave no adapter",
            detail: format!(
                "The browser has WebGPU but no adapter to use ({e}): the GPU may be on its \
                 block list. {INSTEAD}"
            ),
        })?;
    atmoscope_render::gpu::check_adapter(&adapter).map_err(|e| Problem {
        title: "This GPU cannot run the engine in a browser",
        detail: format!("{e}. {INSTEAD}"),
    })
}

thread_local! {
    /// A preset the user picked in the browser's file dialog, until the explorer takes it.
    static PICKED: RefCell<Option<(String, Vec<u8>)>> = const { RefCell::new(None) };
}

/// Opens the browser's file picker for a preset; what is picked comes later from
/// [`take_picked`] (the window is asked to draw a frame when it has).
pub fn pick_preset(ctx: &eframe::egui::Context) {
    let ctx = ctx.clone();
    wasm_bindgen_futures::spawn_local(async move {
        let file = rfd::AsyncFileDialog::new()
            .set_title("Open a preset")
            .add_filter("Atmoscope preset", &["ron"])
            .pick_file()
            .await;
        if let Some(file) = file {
            let bytes = file.read().await;
            PICKED.with_borrow_mut(|p| *p = Some((file.file_name(), bytes)));
            ctx.request_repaint();
        }
    });
}

/// Reads a preset dropped on the page; it comes later from [`take_picked`].
pub fn read_dropped(ctx: &eframe::egui::Context, file: eframe::egui::DroppedFileHandle) {
    let ctx = ctx.clone();
    wasm_bindgen_futures::spawn_local(async move {
        let name = file.path().file_name().map_or_else(
            || "dropped file".into(),
            |n| n.to_string_lossy().into_owned(),
        );
        match file.bytes_async().await {
            Ok(bytes) => PICKED.with_borrow_mut(|p| *p = Some((name, bytes))),
            Err(e) => web_sys::console::warn_1(&format!("cannot read {name}: {e}").into()),
        }
        ctx.request_repaint();
    });
}

/// The preset picked last (its file name and bytes), once.
pub fn take_picked() -> Option<(String, Vec<u8>)> {
    PICKED.with_borrow_mut(Option::take)
}
