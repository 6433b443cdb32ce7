//! What the explorer does to its web page: downloads, the message that replaces the canvas,
//! and the marks a test or a benchmark reads (`web/tests`).

use wasm_bindgen::JsCast;

/// The page's element with `id`.
pub fn element(id: &str) -> Option<web_sys::Element> {
    web_sys::window()?.document()?.get_element_by_id(id)
}

/// Replaces the canvas with a message: a title and what to do (plain text).
pub fn show_problem(title: &str, detail: &str) {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(canvas) = element(super::CANVAS_ID) {
        let _ = canvas.set_attribute("hidden", "");
    }
    let Some(problem) = element("problem") else {
        return;
    };
    problem.set_text_content(None);
    for (tag, text) in [("h1", title), ("p", detail)] {
        if let Ok(e) = document.create_element(tag) {
            e.set_text_content(Some(text));
            let _ = problem.append_child(&e);
        }
    }
    let _ = problem.remove_attribute("hidden");
}

/// Has the browser download `bytes` as a file called `name`.
pub fn download(name: &str, bytes: &[u8]) -> anyhow::Result<()> {
    let fail = |what: &str, e: wasm_bindgen::JsValue| anyhow::anyhow!("cannot {what}: {e:?}");
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| anyhow::anyhow!("cannot download {name}: no document"))?;
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let blob = web_sys::Blob::new_with_u8_array_sequence(&parts)
        .map_err(|e| fail("make the download", e))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)
        .map_err(|e| fail("make the download", e))?;
    let link = document
        .create_element("a")
        .map_err(|e| fail("make the download", e))?
        .dyn_into::<web_sys::HtmlAnchorElement>()
        .map_err(|e| fail("make the download", e.into()))?;
    link.set_href(&url);
    link.set_download(name);
    link.click();
    // The browser reads the blob after this returns: it is released a minute later.
    let release = wasm_bindgen::closure::Closure::once_into_js(move || {
        let _ = web_sys::Url::revoke_object_url(&url);
    });
    if let Some(window) = web_sys::window() {
        let _ = window
            .set_timeout_with_callback_and_timeout_and_arguments_0(release.unchecked_ref(), 60_000);
    }
    Ok(())
}

/// Notes on the page, once, that the explorer has drawn its first complete sky: the
/// `data-first-frame-ms` attribute of the body (milliseconds since the page began to load)
/// and a console line.
pub fn mark_first_frame() {
    let Some(window) = web_sys::window() else {
        return;
    };
    let Some(body) = window.document().and_then(|d| d.body()) else {
        return;
    };
    if body.has_attribute("data-first-frame-ms") {
        return;
    }
    let ms = window.performance().map_or(f64::NAN, |p| p.now());
    let _ = body.set_attribute("data-first-frame-ms", &format!("{ms:.0}"));
    web_sys::console::log_1(&format!("atmoscope: first frame after {ms:.0} ms").into());
}

/// Puts a `bench gui` report on the page: the console, and the body's `data-bench-csv`
/// attribute that the browser benchmark reads (`web/tests/browser.mjs --bench`).
pub fn report_bench(markdown: &str, csv: &str) {
    web_sys::console::log_1(&markdown.into());
    if let Some(body) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.body())
    {
        let _ = body.set_attribute("data-bench-csv", csv);
    }
}

/// The page address's query parameter `name`, if given.
pub fn query(name: &str) -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    web_sys::UrlSearchParams::new_with_str(&search)
        .ok()?
        .get(name)
}
