//! Small egui helpers every panel shares: a palette color in egui's terms, text in a color, a
//! number as the overlays write it. A leaf of the window: it imports nothing above `draw.rs`, so
//! panels and the files beside them take these from below instead of from `panels/mod.rs`.

use super::draw::si;
use bevy::prelude::Color;
use bevy_egui::egui;

/// A palette color as egui takes it.
pub fn color32(c: Color) -> egui::Color32 {
    let c = c.to_srgba();
    egui::Color32::from_rgba_unmultiplied(
        (c.red * 255.0).round() as u8,
        (c.green * 255.0).round() as u8,
        (c.blue * 255.0).round() as u8,
        (c.alpha * 255.0).round() as u8,
    )
}

/// Text in one of the palette's colors.
pub fn rich(text: impl Into<String>, c: Color) -> egui::RichText {
    egui::RichText::new(text.into()).color(color32(c))
}

/// A number with an SI prefix, as the overlays write magnitudes.
pub fn fmt(x: f64) -> String {
    si(x, "")
}
