//! The page's own file input and output (wasm32): the file chooser a level is opened with and the
//! download a saved level, a table or a screenshot becomes. A leaf below the panels and
//! `user_files.rs`, which call it; `web.rs` (the page's app, above them) handles what was picked.

use wasm_bindgen::JsCast;

/// Opens the page's file chooser (`<input id="pick" type="file">`; its change handler in
/// `web/index.html` hands the text to `web::open_picked_file`). Called on a button click: the
/// browser allows it within the click's user activation.
pub fn pick_file() {
    if let Some(input) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("pick"))
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    {
        input.click();
    }
}

/// Offers `bytes` to the user as a download named `name` (a saved scene, an exported table).
pub fn download(name: &str, bytes: &[u8], mime: &str) -> Result<(), String> {
    let fail = |what: &str| format!("cannot download {name}: {what}");
    let array = js_sys::Uint8Array::from(bytes);
    let parts = js_sys::Array::of1(&array);
    let props = web_sys::BlobPropertyBag::new();
    props.set_type(mime);
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &props)
        .map_err(|_| fail("the browser refused to make a Blob"))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)
        .map_err(|_| fail("the browser refused an object URL"))?;
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| fail("no document"))?;
    let a: web_sys::HtmlAnchorElement = document
        .create_element("a")
        .map_err(|_| fail("cannot create a link"))?
        .dyn_into()
        .map_err(|_| fail("not a link"))?;
    a.set_href(&url);
    a.set_download(name);
    a.click();
    web_sys::Url::revoke_object_url(&url).ok();
    Ok(())
}
