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

/// The smallest text the window draws, in points (CSS pixels in the page): egui's small style
/// is 9 points, which the editor's notes, the preview's verdicts and the hints under the tools
/// were written in, too small to read on a laptop screen.
pub const SMALL_TEXT: f32 = 11.5;

/// The window's text sizes: egui's, with the small style raised to [`SMALL_TEXT`].
pub fn legible(style: &mut egui::Style) {
    if let Some(f) = style.text_styles.get_mut(&egui::TextStyle::Small) {
        f.size = f.size.max(SMALL_TEXT);
    }
}

/// Draws `add` in at least `rows` lines of body text: a row whose text comes and goes or changes
/// length (a tool's hint, a warning, the editor's note) then never moves the controls below it,
/// so a click aimed at a button lands on it (rows appearing above the Build tools moved them
/// under the pointer).
pub fn fixed_rows<R>(ui: &mut egui::Ui, rows: f32, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
    let top = ui.cursor().min.y;
    let r = add(ui);
    let row = row_height(ui);
    let used = ui.cursor().min.y - top;
    if used < rows * row {
        ui.add_space(rows * row - used);
    }
    r
}

/// The height of a row of body text or of buttons, whichever is taller, with the space
/// between rows.
pub fn row_height(ui: &egui::Ui) -> f32 {
    ui.text_style_height(&egui::TextStyle::Body)
        .max(ui.spacing().interact_size.y)
        + ui.spacing().item_spacing.y
}

/// Whether the keyboard belongs to a text field: from the frame one takes the focus until the
/// user clicks in the scene or presses Esc. While it does, no key is a shortcut: keys typed
/// into a box that had lost its focus (Enter pressed, a click on a button) went to the
/// shortcuts, so an answer with an r in it reset the run and erased its grades, and a typed
/// path toggled overlays that were then saved in the preferences.
#[derive(bevy::prelude::Resource, Debug, Clone, Default, PartialEq, Eq)]
pub struct Typing {
    /// A text field has or had the keyboard, and no click in the scene or Esc has come since.
    pub active: bool,
}

impl Typing {
    /// After a frame: `focused` a text field has the keyboard focus; `scene_click` the pointer
    /// was pressed outside the panels; `escape` Esc was pressed.
    pub fn follow(&mut self, focused: bool, scene_click: bool, escape: bool) {
        if focused {
            self.active = true;
        } else if scene_click || escape {
            self.active = false;
        }
    }

    /// Whether a key may be a shortcut now (`egui_wants`: egui asked for the keyboard).
    pub fn shortcuts_on(typing: Option<&Typing>, egui_wants: bool) -> bool {
        !egui_wants && !typing.is_some_and(|t| t.active)
    }
}
