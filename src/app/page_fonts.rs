//! The page's fonts: egui's four default fonts, subset to the characters the page can show
//! (`web/fonts/subset.py` says which), in egui's own order and sizes. egui's `default_fonts`
//! feature is on natively only (Cargo.toml), so the page carries these 0.58 MB instead of the
//! whole 1.41 MB (docs/web.md, "A lighter page").

use bevy::prelude::*;
use bevy_egui::egui::{FontData, FontDefinitions, FontFamily, FontTweak};
use bevy_egui::{EguiContext, EguiPreUpdateSet};
use std::sync::Arc;

/// Hack for monospace text, Ubuntu Light for the rest, Noto Emoji and the icon font for symbols:
/// egui 0.36's `FontDefinitions::default()` with the subsets' bytes.
pub fn definitions() -> FontDefinitions {
    let font = |bytes: &'static [u8], scale: f32| {
        Arc::new(FontData::from_static(bytes).tweak(FontTweak {
            scale,
            ..Default::default()
        }))
    };
    let mut defs = FontDefinitions::empty();
    let data = [
        (
            "Hack",
            font(include_bytes!("../../web/fonts/Hack-Regular.ttf"), 1.0),
        ),
        (
            "Ubuntu-Light",
            font(include_bytes!("../../web/fonts/Ubuntu-Light.ttf"), 1.0),
        ),
        // egui's scales: its emoji smaller than the text.
        (
            "NotoEmoji-Regular",
            font(
                include_bytes!("../../web/fonts/NotoEmoji-Regular.ttf"),
                0.81,
            ),
        ),
        (
            "emoji-icon-font",
            font(include_bytes!("../../web/fonts/emoji-icon-font.ttf"), 0.90),
        ),
    ];
    for (name, d) in data {
        defs.font_data.insert(name.to_owned(), d);
    }
    let names = |list: &[&str]| list.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
    defs.families.insert(
        FontFamily::Monospace,
        names(&[
            "Hack",
            "Ubuntu-Light",
            "NotoEmoji-Regular",
            "emoji-icon-font",
        ]),
    );
    defs.families.insert(
        FontFamily::Proportional,
        names(&["Ubuntu-Light", "NotoEmoji-Regular", "emoji-icon-font"]),
    );
    defs
}

/// Gives each new egui context the fonts before its first pass begins (egui takes new fonts at
/// the start of a pass: set in the pass itself, the first frame would lay out text with none).
pub struct PageFontsPlugin;

impl Plugin for PageFontsPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            PreUpdate,
            set_fonts
                .after(EguiPreUpdateSet::InitContexts)
                .before(EguiPreUpdateSet::BeginPass),
        );
    }
}

fn set_fonts(mut added: Query<&mut EguiContext, Added<EguiContext>>) {
    for mut ctx in &mut added {
        ctx.get_mut().set_fonts(definitions());
    }
}
