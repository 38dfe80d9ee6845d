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
    let row = row_height(ui);
    fixed_height(ui, rows * row, add)
}

/// Draws `add` in at least `height` points ([`fixed_rows`] in points).
pub fn fixed_height<R>(ui: &mut egui::Ui, height: f32, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
    let top = ui.cursor().min.y;
    let r = add(ui);
    let used = ui.cursor().min.y - top;
    if used < height {
        ui.add_space(height - used);
    }
    r
}

/// The height `text` takes in `style`, wrapped to the ui's width, with the space after it: what
/// a label of it adds to a column.
pub fn text_height(ui: &egui::Ui, text: &str, style: egui::TextStyle) -> f32 {
    let galley = egui::WidgetText::from(text).into_galley(
        ui,
        Some(egui::TextWrapMode::Wrap),
        ui.available_width(),
        style,
    );
    galley.size().y + ui.spacing().item_spacing.y
}

/// The height of a row of body text or of buttons, whichever is taller, with the space
/// between rows.
pub fn row_height(ui: &egui::Ui) -> f32 {
    ui.text_style_height(&egui::TextStyle::Body)
        .max(ui.spacing().interact_size.y)
        + ui.spacing().item_spacing.y
}

/// Whether the keyboard belongs to the panels rather than the scene: from a press on a panel
/// (or a window over the scene: the Challenge box, the tour) or the frame a text field takes the
/// focus, until the user clicks in the scene or presses Esc. While it does, no key is a
/// shortcut. Keys typed into a box that had lost its focus (Enter pressed, a click on a button)
/// went to the shortcuts, so an answer with an r in it reset the run and erased its grades, and
/// a typed path toggled overlays that were then saved in the preferences; a click that missed a
/// box (it had moved down after *Check*) left the keys with the shortcuts, and the typed answer
/// played and reset the run; in the page at 3-6 fps a click into a box and the first key came in
/// one frame, before egui had given the box the focus, and the key chose the impulse tool.
#[derive(bevy::prelude::Resource, Debug, Clone, Default, PartialEq, Eq)]
pub struct Typing {
    /// The keyboard is the panels': a text field has or had it, or the last press was on a
    /// panel, and no click in the scene or Esc has come since.
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

    /// A press of a mouse button (`pressed`, this frame) at `cursor` (window logical pixels;
    /// None: off the window) with the scene's viewport `scene`, `over_egui` when egui drew a
    /// panel or a window under the pointer: a press anywhere but the bare scene gives the
    /// keyboard to the panels at once, in the frame of the press, before any key of that frame
    /// is read as a shortcut; a press in the bare scene gives it back to the shortcuts.
    pub fn press(
        &mut self,
        pressed: bool,
        cursor: Option<bevy::prelude::Vec2>,
        scene: bevy::prelude::Rect,
        over_egui: bool,
    ) {
        if !pressed {
            return;
        }
        self.active = !cursor.is_some_and(|c| scene.contains(c)) || over_egui;
    }

    /// Whether a key may be a shortcut now (`egui_wants`: egui asked for the keyboard).
    pub fn shortcuts_on(typing: Option<&Typing>, egui_wants: bool) -> bool {
        !egui_wants && !typing.is_some_and(|t| t.active)
    }
}
